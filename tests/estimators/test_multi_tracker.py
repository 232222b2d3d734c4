"""The multi-target tracker end to end on a simulated scenario (crossing and close parallel targets, clutter,
misses), its API checks, and `lgekf track --multi` as a user runs it (bad files -> one-line errors, no
partial output)."""

from __future__ import annotations

import doctest
import subprocess

import numpy as np
import pytest
from _cli import cli_command

from lgekf.estimators.multitarget import gating, tracker as tracker_module
from lgekf.estimators.multitarget.tracker import MultiTargetTracker
from lgekf.experiments.gospa import gospa, track_switches
from lgekf.experiments.multi_scenarios import BASE_TARGETS, base_scenario

CROSSING = BASE_TARGETS[:4]  # two targets crossing at 90°, two parallel 2.5 m apart


def run_scenario(model, association, seed, targets=CROSSING, duration=16.0):
    sc = base_scenario(seed=seed, targets=targets, duration=duration)
    trk = MultiTargetTracker(model=model, association=association, clutter_density=1e-4, meas_std=0.3, detection_prob=0.9)
    dist, assigned, covered = [], [], {}
    for t, Z, (ids, X) in zip(sc.times, sc.detections, sc.truth):
        rep = trk.step(t, Z)
        g = gospa(X[:, :2], rep.states[:, :2], c=5.0, p=2)
        dist.append(g.distance)
        assigned.append({int(ids[i]): int(rep.ids[j]) for i, j in g.assignment})
        if t >= 1.0:
            for i, _ in g.assignment:
                covered[int(ids[i])] = covered.get(int(ids[i]), 0) + 1
    n_after = int(np.sum(sc.times >= 1.0))
    return np.mean(dist), track_switches(assigned), {k: covered.get(k, 0) / n_after for k in range(len(targets))}, trk


@pytest.mark.parametrize("model", ["se2se2", "cv"])
def test_jpda_tracks_crossing_and_parallel_targets_in_clutter(model):
    """4 targets, 160 scans, 4 false alarms per scan, P_D = 0.9: every target held by a confirmed track in
    ≥ 95 % of the scans after the first second, mean GOSPA (c = 5 m, p = 2) < 1 m, at most 4 switches
    (measured: GOSPA 0.61-0.72 m (se2se2), 0.60-0.84 m (cv); switches 0-3 / 0-4, all while the close
    pair's tracks start, t < 1.5 s)."""
    for seed in (0, 1):
        mean_gospa, switches, cover, _ = run_scenario(model, "jpda", seed)
        assert min(cover.values()) >= 0.95, cover
        assert mean_gospa < 1.0
        assert switches <= 4


def test_births_and_deaths_are_followed():
    """The full base scenario (8 targets, 2 births, 2 deaths): each born target gets a track, a dead one's
    track is no longer reported 1.5 s after its death."""
    sc = base_scenario(seed=4)
    trk = MultiTargetTracker(model="se2se2", association="jpda", clutter_density=1e-4, meas_std=0.3, detection_prob=0.9)
    reports = [trk.step(t, Z) for t, Z in zip(sc.times, sc.detections)]
    for k, (birth, death, *_rest) in enumerate(BASE_TARGETS):
        alive = [i for i, t in enumerate(sc.times) if birth <= t <= death]
        late = alive[len(alive) // 2]  # the middle of its life: a confirmed track within 2 m
        pos = sc.truth[late][1][list(sc.truth[late][0]).index(k), :2]
        st = reports[late].states
        assert st.size and np.min(np.hypot(*(st[:, :2] - pos).T)) < 2.0, k
        if death < sc.times[-1]:
            after = int(np.searchsorted(sc.times, death + 1.5))
            last = sc.truth[alive[-1]][1][list(sc.truth[alive[-1]][0]).index(k), :2]
            st = reports[after].states
            assert not st.size or np.min(np.hypot(*(st[:, :2] - last).T)) > 5.0, k


def test_tracker_arguments_are_checked():
    with pytest.raises(ValueError, match="association"):
        MultiTargetTracker(model="cv", association="mht")
    with pytest.raises(ValueError, match="detection-prob"):
        MultiTargetTracker(model="cv", detection_prob=1.5)
    with pytest.raises(ValueError, match="clutter-density"):
        MultiTargetTracker(model="cv", clutter_density=0.0)
    with pytest.raises(ValueError, match="accel-std: ctrv takes 2"):
        MultiTargetTracker(model="ctrv", accel_std=(1, 2, 3))
    with pytest.raises(ValueError, match="no heading"):
        MultiTargetTracker(model="cv", measurement="pose")
    trk = MultiTargetTracker(model="cv")
    trk.step(1.0, np.zeros((0, 2)))
    with pytest.raises(ValueError, match="must increase"):
        trk.step(1.0, np.zeros((1, 2)))
    with pytest.raises(ValueError, match="NaN"):
        trk.step(2.0, np.array([[np.nan, 0.0]]))
    with pytest.raises(ValueError, match=r"expected shape \(M, 2\)"):
        trk.step(3.0, np.zeros((4, 3)))


@pytest.mark.parametrize("module", [tracker_module, gating])
def test_docstring_examples_run(module):
    res = doctest.testmod(module, extraglobs={"np": np}, optionflags=doctest.NORMALIZE_WHITESPACE)
    assert res.attempted > 0 and res.failed == 0


# ------------------------------------------------------------------------------------------ CLI
def run(*args, cwd=None):
    return subprocess.run([*cli_command(), "track", *map(str, args)], capture_output=True, text=True, cwd=cwd)


def detections_csv(path, seed=0, duration=6.0):
    sc = base_scenario(seed=seed, targets=CROSSING, duration=duration)
    lines = ["t,x,y,id"]  # an id column is ignored in --multi mode
    for t, Z in zip(sc.times, sc.detections):
        lines += [f"{t:.10g},{z[0]:.6f},{z[1]:.6f},x" for z in Z]
    path.write_text("\n".join(lines) + "\n")
    return sc


def test_cli_multi_writes_confirmed_tracks(tmp_path):
    sc = detections_csv(tmp_path / "d.csv")
    out = tmp_path / "tracks.csv"
    r = run(tmp_path / "d.csv", "--multi", "--model", "cv", "-o", out, "--clutter-density", "1e-4", "--association", "gnn")
    assert r.returncode == 0, r.stderr
    assert "confirmed track" in r.stdout
    header = out.read_text().splitlines()[0].split(",")
    assert header == ["track", "t", "x", "y", "vx", "vy", "std_x", "std_y", "std_vx", "std_vy", "speed", "course",
                      "existence", "flag"]
    data = np.loadtxt(out, delimiter=",", skiprows=1)
    assert set(np.unique(data[:, 0]).astype(int)) and np.all(data[:, -2] >= 0.5) and np.all(data[:, -2] <= 1.0)
    assert np.all(data[:, -1] == 0)  # a benign crossing: no alarm
    np.testing.assert_allclose(data[:, 10], np.hypot(data[:, 4], data[:, 5]), rtol=1e-8)  # CV: speed = |(vx, vy)|
    np.testing.assert_allclose(data[:, 11], np.arctan2(data[:, 5], data[:, 4]), atol=1e-8)
    last = data[data[:, 1] == data[:, 1].max()]
    truth = sc.truth[-1][1][:, :2]
    d = np.hypot(last[:, None, 2] - truth[None, :, 0], last[:, None, 3] - truth[None, :, 1]).min(axis=0)
    assert np.all(d < 1.5), d  # every target has a confirmed track at the end


BAD = {
    "missing_column": ("t,x\n0,1\n1,2\n", [], "missing column 'y'"),
    "non_numeric": ("t,x,y\n0,0,0\n0.1,abc,0\n", [], "line 3: column 'x': 'abc' is not a number"),
    "nan": ("t,x,y\n0,0,0\n0.1,nan,0\n", [], "NaN"),
    "empty_file": ("", [], "empty file"),
    "header_only": ("t,x,y\n", [], "no measurements"),
    "bad_association": ("t,x,y\n0,0,0\n", ["--association", "mht"], "invalid choice: 'mht'"),
    "bad_initiation": ("t,x,y\n0,0,0\n", ["--initiation", "three-point"], "invalid choice: 'three-point'"),
    "birth_density_two_point": ("t,x,y\n0,0,0\n", ["--initiation", "two-point", "--birth-density", "1e-6"],
                                "birth-density: only with one-point initiation"),
    "birth_density_and_existence": ("t,x,y\n0,0,0\n", ["--birth-density", "1e-6", "--birth-existence", "0.1"],
                                    "birth-density: not with birth-existence"),
    "bad_birth_density": ("t,x,y\n0,0,0\n", ["--birth-density", "0"], "birth-density: must be a positive number"),
    "bad_pd": ("t,x,y\n0,0,0\n", ["--detection-prob", "1.2"], "detection-prob: must be a probability"),
    "bad_clutter": ("t,x,y\n0,0,0\n", ["--clutter-density", "-1"], "clutter-density: must be a positive number"),
    "pose_without_heading": ("t,x,y\n0,0,0\n", ["--measure", "pose"], "heading"),
    "accel_arity": ("t,x,y\n0,0,0\n", ["--model", "cv", "--accel-std", "1,2"], "accel-std: cv takes 1"),
    "accel_other_model": ("t,x,y\n0,0,0\n", ["--model", "cv", "--accel-std", "se2se2=1,2,3"], "not the tracked model"),
    "cv_pose": ("t,x,y,heading\n0,0,0,0\n", ["--model", "cv", "--measure", "pose"], "no heading to measure"),
    "tune_smooth": ("t,x,y\n0,0,0\n", ["--tune", "--smooth"], "--tune, --smooth: not available with --multi"),
    "model_all": ("t,x,y\n0,0,0\n", ["--model", "all"], "--model all: not available with --multi"),
    "id_column": ("t,x,y,car\n0,0,0,1\n", ["--id-column", "car"], "--id-column: not available with --multi"),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_cli_multi_bad_input_is_one_line_and_no_output(tmp_path, case, capsys):
    """In process (``lgekf.cli.main``, what the ``lgekf`` script calls); one case below as a subprocess."""
    from lgekf.cli import main

    text, extra, msg = BAD[case]
    src = tmp_path / "in.csv"
    src.write_text(text)
    out = tmp_path / "out.csv"
    code = main(["track", str(src), "--multi", "-o", str(out), *extra])
    err = capsys.readouterr().err
    assert code == 2, err
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert len(lines) == 1 and msg in lines[0], err
    assert not out.exists() and not list(tmp_path.glob(".out.csv.tmp*"))


def test_cli_multi_bad_file_as_a_subprocess(tmp_path):
    src = tmp_path / "in.csv"
    src.write_text("t,x,y\n0,0,0\n0.1,abc,0\n")
    r = run(src, "--multi", "-o", tmp_path / "out.csv")
    assert r.returncode == 2 and r.stderr.count("\n") == 1 and "'abc' is not a number" in r.stderr, r.stderr
    assert not (tmp_path / "out.csv").exists()


def test_pose_detections_with_uniform_clutter_heading():
    """SE(2)×R² from pose detections (clutter headings uniform, κ = λ/2π): the close parallel pair is resolved
    (measured mean GOSPA 0.77 m, no switch)."""
    sc = base_scenario(seed=1, targets=CROSSING, duration=10.0, measurement="pose", meas_std=(0.3, 0.05))
    trk = MultiTargetTracker(model="se2r2", measurement="pose", meas_std=(0.3, 0.3, 0.05), clutter_density=1e-4)
    dist, assigned = [], []
    for t, Z, (ids, X) in zip(sc.times, sc.detections, sc.truth):
        rep = trk.step(t, Z)
        g = gospa(X[:, :2], rep.states[:, :2], c=5.0, p=2)
        dist.append(g.distance)
        assigned.append({int(ids[i]): int(rep.ids[j]) for i, j in g.assignment})
    assert np.mean(dist) < 1.0 and track_switches(assigned) <= 1
    assert trk.kappa == pytest.approx(1e-4 / (2 * np.pi))


class CountingBank:
    """A bank that delegates to a ModelBank and counts the calls: the tracker uses only the interface."""

    def __init__(self, inner):
        self.inner, self.calls = inner, {}

    def __getattr__(self, name):
        attr = getattr(self.inner, name)
        if callable(attr):
            def wrapped(*a, **k):
                self.calls[name] = self.calls.get(name, 0) + 1
                return attr(*a, **k)
            return wrapped
        return attr

    @property
    def live(self):
        return self.inner.live


@pytest.mark.parametrize("initiation, first", [("one-point", 1), ("two-point", 2)])
def test_tracker_runs_on_any_bank_with_the_interface(initiation, first):
    """The same tracks through a bank that only has the interface (also the one-point restart, by remove/add);
    gating and updates from the first scan with a track: scan 1 with one-point initiation (tracks from the first
    detections), scan 2 with two-point (from two scans' detections)."""
    from lgekf.estimators.multitarget.bank import ModelBank

    sc = base_scenario(seed=0, targets=CROSSING, duration=3.0)
    ref = MultiTargetTracker(model="cv", clutter_density=1e-4, initiation=initiation)
    bank = CountingBank(ModelBank("cv", "position", (0.5,), (0.3,)))
    trk = MultiTargetTracker(model="cv", clutter_density=1e-4, bank=bank, initiation=initiation)
    for t, Z in zip(sc.times, sc.detections):
        a, b = ref.step(t, Z), trk.step(t, Z)
        np.testing.assert_array_equal(a.ids, b.ids)
        np.testing.assert_allclose(a.states, b.states, rtol=1e-12)
    assert set(bank.calls) <= {"add", "remove", "predict", "gate", "update", "physical", "stds"}
    assert bank.calls["gate"] == bank.calls["update"] == len(sc.times) - first


def test_docs_python_example_runs(capsys):
    import re
    from pathlib import Path

    chapter = (Path(__file__).resolve().parents[2] / "docs" / "multi_target.md").read_text(encoding="utf-8")
    block = re.search(r"# Many objects in clutter.*?\n.*?```python\n(.*?)```", chapter, re.S).group(1)
    ns: dict = {}
    exec(compile(block, "docs/multi_target.md", "exec"), ns)  # noqa: S102 - our own documentation
    rep = ns["rep"]
    assert rep.ids.size == 2 and np.all(rep.existence > 0.9)
    np.testing.assert_allclose(np.sort(rep.states[:, 0]), [5.8, 50.0], atol=0.5)
    tracks = ns["trk"].tracks()  # the histories end on the last report
    assert sorted(t.id for t in tracks) == sorted(rep.ids.tolist()) and all(t.t[-1] == 0.1 * 29 for t in tracks)


def test_seed_scans_tolerates_a_missed_detection_at_the_start():
    """One object at 1 m/s detected at scans 0, 2, 3, 4: consecutive-only pairing starts its track at scan 3
    (from scans 2 and 3), a two-scan window already at scan 2 (from scans 0 and 2)."""
    scans = {0: [[0.0, 0.0]], 1: [], 2: [[0.2, 0.0]], 3: [[0.3, 0.0]], 4: [[0.4, 0.0]]}
    born = {}
    for window in (1, 2):
        trk = MultiTargetTracker(model="cv", clutter_density=1e-4, meas_std=0.05, seed_scans=window,
                                 initiation="two-point")
        for k, z in scans.items():
            trk.step(0.1 * k, np.array(z).reshape(-1, 2))
            if trk.n_tracks and window not in born:
                born[window] = k
    assert born == {1: 3, 2: 2}
    with pytest.raises(ValueError, match="seed-scans: must be at least 1"):
        MultiTargetTracker(model="cv", seed_scans=0, initiation="two-point")
    with pytest.raises(ValueError, match="seed-scans: only with two-point initiation"):
        MultiTargetTracker(model="cv", seed_scans=2, initiation="one-point")


@pytest.mark.parametrize("model", ["se2r3", "cv"])
def test_track_histories_follow_the_reports(model):
    """history=True: every reported track's history holds, scan by scan, what the reports said (times, states,
    existence), with its tangent covariance, whose diagonal gives the reported stds; a track id reported in no scan
    has no history; and each history follows a true target (the crossing scene, after its first second)."""
    sc = base_scenario(seed=2, targets=CROSSING, duration=6.0)
    trk = MultiTargetTracker(model=model, association="jpda", clutter_density=1e-4, meas_std=0.3, detection_prob=0.9,
                             history=True)
    seen = {}
    for t, Z in zip(sc.times, sc.detections):
        rep = trk.step(t, Z)
        for k, i in enumerate(rep.ids.tolist()):
            seen.setdefault(i, []).append((t, rep.states[k], rep.stds[k], rep.existence[k]))
    tracks = trk.tracks()
    assert [tr.id for tr in tracks] == sorted(seen) and len(tracks) >= 4
    n = trk.spec.n
    for tr in tracks:
        rows = seen[tr.id]
        assert tr.t.tolist() == [r[0] for r in rows]
        assert np.array_equal(tr.states, np.array([r[1] for r in rows]))
        assert np.array_equal(tr.existence, np.array([r[3] for r in rows]))
        assert tr.covariances.shape == (len(rows), n, n)
        assert np.allclose(np.sqrt(np.diagonal(tr.covariances, axis1=1, axis2=2)), np.array([r[2] for r in rows]))
        assert np.array_equal(tr.covariances, np.swapaxes(tr.covariances, 1, 2))
        assert np.all(np.linalg.eigvalsh(tr.covariances) > 0)
    # the four long tracks lie on the four targets
    long = [tr for tr in tracks if tr.t.size > 40]
    assert len(long) == 4
    for tr in long:
        k = int(np.searchsorted(sc.times, tr.t[-1]))
        ids, X = sc.truth[k]
        assert np.min(np.hypot(*(X[:, :2] - tr.states[-1, :2]).T)) < 1.5


def test_tracks_need_the_history_option():
    trk = MultiTargetTracker(model="cv", clutter_density=1e-4, meas_std=0.3)
    trk.step(0.0, np.array([[0.0, 0.0]]))
    with pytest.raises(ValueError, match="history=True"):
        trk.tracks()
