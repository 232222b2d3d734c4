"""`lgekf track --multi` with its defaults (issue #26): the noise from the data, scans with a time tolerance, a
line saying why when no track is confirmed. The CLI is run as a user runs it, on detection files made here from
known truths (``lgekf.experiments.multi_scenarios``: constant-turn targets, Gaussian detection noise, misses,
uniform false alarms)."""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

import numpy as np
import pytest
from _cli import cli_command

from lgekf.apps import track_multi as tm
from lgekf.estimators.multitarget.tracker import BIRTH_EXISTENCE
from lgekf.experiments.multi_scenarios import BASE_TARGETS, base_scenario, detection_stream, truth_trajectories

# id: (birth s, death s, x0, y0, heading deg, speed m/s, turn rate rad/s): two cars, two pedestrians
TARGETS = (
    (0.0, 99.0, -100.0, -60.0, 20.0, 12.0, 0.0),
    (0.0, 99.0, 120.0, 80.0, 200.0, 10.0, 0.02),
    (0.0, 99.0, -20.0, 30.0, 90.0, 1.5, 0.0),
    (0.0, 99.0, 40.0, -40.0, 135.0, 1.3, 0.05),
)
REGION = (-200.0, 200.0, -150.0, 150.0)  # false alarms: 2e-5 per m² per scan, 2.4 per scan


def run(*args):
    return subprocess.run([*cli_command(), "track", *map(str, args)], capture_output=True, text=True)


def scene(path, seed=1, jitter=0.0, targets=TARGETS, dt=0.2, scans=100, meas_std=1.0, clutter=2e-5, region=REGION,
          turn_noise=0.02):
    """Write a detection file t,x,y in time order (one t per scan, or with ``jitter``: each detection at scan time +
    U(0, jitter));
    returns the scan times and the truth per scan (ids, (x, y, heading))."""
    rng = np.random.default_rng(seed)
    times = np.round(dt * np.arange(scans), 10)
    truth = truth_trajectories(targets, times, rng, turn_noise=turn_noise)
    dets, _ = detection_stream(truth, rng, 0.9, clutter, meas_std, region)
    rows = []
    for t, Z in zip(times, dets):
        for z in Z:
            tt = t + rng.uniform(0.0, jitter) if jitter else t
            rows.append((round(tt, 6), f"{tt:.6f},{z[0]:.4f},{z[1]:.4f}"))
    rows.sort(key=lambda r: r[0])  # a sensor's log: rows in time order (stable; --multi refuses rows going back in time)
    path.write_text("\n".join(["t,x,y", *(r[1] for r in rows)]) + "\n")
    return times, truth


def read_tracks(path):
    data = np.genfromtxt(path, delimiter=",", skip_header=1, ndmin=2)
    return data.reshape(-1, 18)  # se2se2: track, t, 6 states, 6 stds, speed, course, existence, flag


def meas_std_printed(stderr):
    m = re.search(r"noise from the data: meas-std ([0-9.e+-]+) m \(quadratic residuals", stderr)
    assert m, stderr
    return float(m.group(1))


def held_targets(data, times, truth, reach=3.0, after=2.0):
    """For every target, the fraction of scans after ``after`` s in which some confirmed track is within ``reach`` m."""
    hits = {}
    n = 0
    for t, (ids, X) in zip(times, truth):
        if t < after:
            continue
        n += 1
        est = data[np.abs(data[:, 1] - t) < 0.01, 2:4]
        for i, x in zip(ids, X):
            near = est.size and np.min(np.hypot(*(est - x[:2]).T)) < reach
            hits[int(i)] = hits.get(int(i), 0) + bool(near)
    return {i: h / n for i, h in hits.items()}


# ------------------------------------------------------------------------------------------ noise from the data
def test_defaults_find_every_target_and_the_noise(tmp_path):
    """4 targets (cars 10-12 m/s, pedestrians 1.3-1.5 m/s), 1 m detection noise, P_D 0.9, 2.4 false alarms per
    scan, 100 scans at 5 Hz; no noise option. Exactly 4 confirmed tracks (main gave 31 with its fixed 0.3 m), each
    target within 3 m of a confirmed track in >= 90 % of the scans after 2 s, the printed meas-std within 1.3x of
    the true 1 m. (Seeds 1-5 of this scene give 4 tracks; seed 0 gives a fifth, confirmed from false alarms in the
    last two scans, also with --meas-std 1 given: the tracker's false-track rate, not the noise defaults.)"""
    times, truth = scene(tmp_path / "d.csv", seed=1)
    out = tmp_path / "tracks.csv"
    r = run(tmp_path / "d.csv", "--multi", "-o", out)
    assert r.returncode == 0, r.stderr
    assert "warning" not in r.stderr, r.stderr
    data = read_tracks(out)
    assert np.unique(data[:, 0]).size == 4, r.stdout
    cover = held_targets(data, times, truth)
    assert min(cover.values()) >= 0.9, cover
    assert 1 / 1.3 <= meas_std_printed(r.stderr) <= 1.3
    assert re.search(r"accel-std se2se2 [0-9.,]+ \(k = ", r.stderr), r.stderr  # the process noise from the data too


def test_per_detection_timestamps_give_the_same_tracks(tmp_path):
    """The scene of the test above with each detection at its own time (scan time + up to 2 ms): the scans are
    found from the gaps between the times (one line says so), the same 4 tracks, output times within the 2 ms
    after the true scan times. Main confirmed 0 tracks here, silently."""
    times, truth = scene(tmp_path / "d.csv", seed=1, jitter=0.002)
    out = tmp_path / "tracks.csv"
    r = run(tmp_path / "d.csv", "--multi", "-o", out)
    assert r.returncode == 0, r.stderr
    assert re.search(r"scans: the detections within [0-9.e-]+ s of a scan's first grouped into one .* 100 scans, "
                     r"period 0\.2 s", r.stderr), r.stderr
    data = read_tracks(out)
    assert np.unique(data[:, 0]).size == 4
    t_out = np.unique(data[:, 1])
    lag = t_out - times[np.searchsorted(times, t_out) - 1]  # the midpoint of a scan's first and last detection
    assert np.all((lag >= 0) & (lag <= 0.002)), lag
    assert min(held_targets(data, times, truth).values()) >= 0.9
    assert 1 / 1.3 <= meas_std_printed(r.stderr) <= 1.3


def test_given_meas_std_far_from_the_data_is_warned(tmp_path):
    """--meas-std 0.3 on 1 m detections: one warning line (the track's 2x rule); --meas-std 1: none; --quiet
    keeps the warning and drops the noise line."""
    scene(tmp_path / "d.csv", seed=1)
    out = tmp_path / "tracks.csv"
    r = run(tmp_path / "d.csv", "--multi", "-o", out, "--meas-std", "0.3", "--quiet")
    assert r.returncode == 0, r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("lgekf track: warning: --meas-std 0.3 m is "), r.stderr
    assert "leave --meas-std out" in lines[0]
    r = run(tmp_path / "d.csv", "--multi", "-o", out, "--meas-std", "1")
    assert r.returncode == 0 and "warning" not in r.stderr, r.stderr
    assert "meas-std 1 m (given)" in r.stderr  # the process noise is estimated, and said with the given std


def test_both_noises_given_print_no_noise_line(tmp_path):
    scene(tmp_path / "d.csv", seed=1)
    r = run(tmp_path / "d.csv", "--multi", "-o", tmp_path / "o.csv", "--meas-std", "1", "--accel-std", "0.5,0.5,0.1")
    assert r.returncode == 0, r.stderr
    assert "noise from the data" not in r.stderr and "warning" not in r.stderr, r.stderr


@pytest.mark.parametrize("factor", [30.0, 1 / 15])
def test_the_passes_recover_from_a_provisional_std_far_off(monkeypatch, factor):
    """The search of ``fit_noise`` from a first std 30x the truth and 1/15 of it (fragments) ends within 25 % of the
    true 0.3 m, with a track on each of the 4 targets for nearly all of the 61 scans. (With two-point initiation
    and main's GNN there were exactly 4 confirmed tracks; one-point, and the second GNN pass, confirm the odd false
    track for a few scans: 2 and 8 rows at 30x, 2 rows at 1/15.)"""
    sc0 = base_scenario(seed=0, targets=BASE_TARGETS[:4], duration=6.0)
    t = np.concatenate([np.full(len(Z), tt) for tt, Z in zip(sc0.times, sc0.detections)])
    Z = np.vstack(sc0.detections)
    monkeypatch.setattr(tm, "provisional_meas_std", lambda sc, z, dim=2: 0.3 * factor)
    sc = tm.scans(t, 0.0)
    run_, fit = tm.fit_noise(t, Z, sc, dict(model="cv", association="gnn", clutter_density=1e-4), heading_std=0.1,
                             omega_std=0.5)
    assert fit.meas_source == "data" and fit.converged
    assert 0.3 / 1.25 <= fit.meas_std <= 0.3 * 1.25, fit.passes
    ids, rows = np.unique(run_.ids, return_counts=True)
    assert np.sum(rows >= 50) == 4 and np.all(rows[rows < 50] <= 10), dict(zip(ids.tolist(), rows.tolist()))
    assert len(fit.passes) <= tm.MAX_PASSES


# ------------------------------------------------------------------------------------------ scans
def test_scans_of_one_time_each_are_the_distinct_times():
    t = np.array([0.2, 0.0, 0.1, 0.0, 0.2, 0.1, 0.0, 0.4])  # unsorted, scan 0.3 missing
    z = np.array([[1.0, 0], [0, 0], [0.5, 0], [50, 0], [51, 0], [50.5, 0], [0, 50], [2, 0]])
    assert tm.scan_window_from_data(t, z) == 0.0
    sc = tm.scans(t, 0.0)
    assert sc.times.tolist() == [0.0, 0.1, 0.2, 0.4]
    assert np.diff(sc.starts).tolist() == [3, 2, 2, 1]
    assert sorted(t[sc.order[sc.starts[1]:sc.starts[2]]].tolist()) == [0.1, 0.1]


def test_scan_window_from_jittered_times():
    """Three scans 0.1 s apart of objects 50 m apart moving 0.5 m per scan, detections up to 2 ms late: the window
    lies between the widest scan's spread (2 ms) and the smallest gap between scans (98 ms), the scan time is the
    midpoint of first and last."""
    t = np.array([0.0, 0.001, 0.002, 0.1005, 0.1, 0.2, 0.2015])
    z = np.array([[0.0, 0], [50, 0], [0, 50], [0.5, 0], [50.5, 0], [1, 0], [0, 51]])
    w = tm.scan_window_from_data(t, z)
    assert 0.002 < w < 0.098
    sc = tm.scans(t, w)
    assert sc.count == 3
    np.testing.assert_allclose(sc.times, [0.001, 0.10025, 0.20075], rtol=0, atol=1e-15)


def test_scan_window_ignores_pauses_and_irregular_scans():
    """One object at 1 m/s, one t per scan at 10 Hz: with a 100 s pause (a break of 1000x in the gaps, whose groups
    hold the same object again and again), or with irregular scans (gaps 0.05-0.3 s): window 0."""
    t = np.concatenate([0.1 * np.arange(50), 105.0 + 0.1 * np.arange(50)])
    z = np.column_stack([t, np.zeros_like(t)])
    assert tm.scan_window_from_data(t, z) == 0.0
    rng = np.random.default_rng(0)
    t = np.cumsum(rng.uniform(0.05, 0.3, 200))
    assert tm.scan_window_from_data(t, np.column_stack([t, np.zeros_like(t)])) == 0.0


@pytest.mark.parametrize("initiation", ["one-point", "two-point"])
def test_per_detection_times_with_scan_window_0_say_why_nothing_is_confirmed(tmp_path, initiation):
    """Main's behaviour forced (--scan-window 0: each detection its own scan): one warning line that says why and
    names --scan-window; exit 0. Two-point: no track, the output is the header only. One-point: tracks confirmed
    from two detections (the clutter density estimated from one detection per scan is tiny) that hold fewer than
    4 detections each: the line says so."""
    scene(tmp_path / "d.csv", seed=1, jitter=0.002)
    out = tmp_path / "o.csv"
    r = run(tmp_path / "d.csv", "--multi", "-o", out, "--scan-window", "0", "--meas-std", "1", "--quiet",
            "--initiation", initiation)
    assert r.returncode == 0, r.stderr
    lines = [ln for ln in r.stderr.splitlines() if "no track confirmed" in ln]
    assert len(lines) == 1, r.stderr
    assert "1 detection per scan" in lines[0] and "--scan-window SECONDS" in lines[0], lines[0]
    if initiation == "two-point":
        assert out.read_text().count("\n") == 1
    else:
        assert "no track confirmed that held 4 detections (" in lines[0], lines[0]
        held = np.unique(read_tracks(out)[:, 0], return_counts=True)[1]
        assert held.size and held.max() <= 10  # fragments: each reported in a few of the 614 scans


# ------------------------------------------------------------------------------------------ nothing confirmed
FAST = ((0.0, 99.0, -3000.0, 0.0, 0.0, 80.0, 0.0), (0.0, 99.0, 0.0, -3000.0, 90.0, 80.0, 0.0),
        (0.0, 99.0, 3000.0, 500.0, 180.0, 90.0, 0.0))


def test_objects_faster_than_max_speed_get_a_why_line_that_names_it(tmp_path):
    """Three aircraft-like objects at 80-90 m/s, 1 Hz, 1 m noise: with the default --max-speed 30 m/s no track can
    start at the estimated noise; one warning line says so and proposes a --max-speed above their speed, which
    then tracks all three."""
    scene(tmp_path / "d.csv", seed=1, targets=FAST, dt=1.0, scans=60, clutter=1e-7,
          region=(-4000.0, 4000.0, -4000.0, 4000.0), turn_noise=0.002)
    out = tmp_path / "o.csv"
    r = run(tmp_path / "d.csv", "--multi", "-o", out, "--quiet")
    assert r.returncode == 0, r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("lgekf track: warning: no track confirmed: 60 scans (period 1 s"), r.stderr
    m = re.search(r"objects faster than --max-speed 30 m/s start no track; try --max-speed ([0-9.]+)$", lines[0])
    assert m, lines[0]
    assert float(m.group(1)) > 90.0
    r = run(tmp_path / "d.csv", "--multi", "-o", out, "--max-speed", m.group(1))
    assert r.returncode == 0 and "warning" not in r.stderr, r.stderr
    assert np.unique(read_tracks(out)[:, 0]).size == 3


@pytest.mark.parametrize("initiation, why", [
    ("two-point", "no track started"),
    ("one-point", f"1 track started, the largest existence reached {BIRTH_EXISTENCE['one-point']:.2f} (confirmed at 0.9)"),
])
def test_a_single_detection_says_why(tmp_path, initiation, why):
    """Two-point: no pair, no track; one-point: the detection starts a tentative track at its birth existence."""
    (tmp_path / "d.csv").write_text("t,x,y\n0,0,0\n")
    r = run(tmp_path / "d.csv", "--multi", "-o", tmp_path / "o.csv", "--initiation", initiation)
    assert r.returncode == 0
    assert f"warning: no track confirmed: 1 scan (1 detection per scan); {why}" in r.stderr, r.stderr


# ------------------------------------------------------------------------------------------ bad options
@pytest.mark.parametrize("opt, value, msg", [
    ("--scan-window", "-0.1", "scan-window: must be a non-negative number"),
    ("--scan-window", "nan", "scan-window: contains NaN"),
    ("--max-speed", "0", "max-speed: must be a positive number"),
    ("--meas-std", "-1", "meas-std: must be a positive number"),
])
def test_bad_option_is_one_line_and_no_output(tmp_path, capsys, opt, value, msg):
    from lgekf.cli import main

    src = tmp_path / "in.csv"
    src.write_text("t,x,y\n0,0,0\n0.1,1,0\n")
    out = tmp_path / "out.csv"
    code = main(["track", str(src), "--multi", "-o", str(out), opt, value])
    err = capsys.readouterr().err
    assert code == 2, err
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert len(lines) == 1 and msg in lines[0], err
    assert "Traceback" not in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["in.csv"]


def test_shipped_example_with_multi_finds_its_three_objects(tmp_path):
    """examples/data/detections.csv (car, cyclist, pedestrian at 10 Hz, 0.3 m noise; the cyclist stamped 10 ms after
    the others) tracked as unlabelled detections: the 10 ms offsets make one scan, three tracks, the noise found."""
    src = Path(__file__).resolve().parents[2] / "examples" / "data" / "detections.csv"
    dets = np.genfromtxt(src, delimiter=",", names=True, dtype=None, encoding="utf-8")
    out = tmp_path / "tracks.csv"
    r = run(src, "--multi", "-o", out)  # the file is written object by object: not in time order
    assert r.returncode == 2 and "--sort sorts them" in r.stderr and not out.exists(), r.stderr
    r = run(src, "--multi", "--sort", "-o", out)
    assert r.returncode == 0, r.stderr
    assert "3 confirmed tracks" in r.stdout, r.stdout
    assert 0.24 <= meas_std_printed(r.stderr) <= 0.36  # the file's noise is 0.3 m
    data = read_tracks(out)
    assert np.all(data[:, -1] == 0)  # no alarm
    for obj in np.unique(dets["id"]):  # every object is followed by one track within 1 m of its last detection (0.3 m noise)
        last = dets[dets["id"] == obj][-1]
        near = data[np.abs(data[:, 1] - last["t"]) < 0.051]
        assert np.hypot(near[:, 2] - last["x"], near[:, 3] - last["y"]).min() < 1.0, obj
