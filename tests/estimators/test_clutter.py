"""The clutter density from the data (``lgekf.estimators.multitarget.clutter``, issue #29 item 4): the per-scan
moment estimate against known Poisson clutter, the map against a dense patch, targets not counted as clutter, the
tracker's use of λ(z), the CLI (`lgekf track --multi --clutter`) and `lgekf study --multi --scenario`, bad input."""

from __future__ import annotations

import math
import subprocess

import numpy as np
import pytest
from _cli import cli_command

from lgekf.estimators.multitarget import clutter as cl
from lgekf.estimators.multitarget.clutter import (
    ClutterEstimator, ClutterMap, ConstantClutter, ScanClutter, bounding_box_density, clutter_estimator, clutter_from_data,
    map_cell_from_counts,
)
from lgekf.estimators.multitarget.tracker import MultiTargetTracker, one_point_existence
from lgekf.experiments.clutter_scenarios import PATCH, clutter_scenario, study_clutter
from lgekf.experiments.multi_scenarios import detection_stream, truth_trajectories

REGION = (-100.0, 100.0, -100.0, 100.0)
AREA = 200.0 * 200.0


def poisson_scans(rng, scans, per_scan, box=REGION):
    """``scans`` scans of Poisson(per_scan) points uniform in ``box``."""
    x0, x1, y0, y1 = box
    out = []
    for _ in range(scans):
        n = rng.poisson(per_scan)
        out.append(np.column_stack([rng.uniform(x0, x1, n), rng.uniform(y0, y1, n)]))
    return out


# ---------------------------------------------------------------- the per-scan estimate
def test_scan_estimate_converges_to_the_poisson_rate():
    """No targets (expected = 0), μ = 10 false alarms per scan over a known area: the forgetting average of the counts
    has steady-state std √(μ (1 − a)/(1 + a)) (0.73 at a = 0.9); every scan after the first 50 within 5 of those
    stds of μ (350 correlated scans: the largest of them is about 3σ), and their mean, whose std is about √(μ/350)
    = 0.17, within 4 of its stds."""
    mu, a = 10.0, 0.9
    est = ScanClutter(forgetting=a, area=AREA)
    counts = []
    for Z in poisson_scans(np.random.default_rng(5), 400, mu):
        lam = est.density(0.0, Z, 0.0)
        assert lam == est.level
        counts.append(lam * AREA)
    c = np.array(counts[50:])
    sd = math.sqrt(mu * (1 - a) / (1 + a))
    assert np.all(np.abs(c - mu) < 5 * sd), (c.min(), c.max())
    assert abs(c.mean() - mu) < 4 * math.sqrt(mu / c.size)


def test_scan_estimate_inside_the_tracker_with_targets_and_clutter():
    """Three targets (P_D 0.9, as the tracker assumes) and 10 false alarms per scan over 200 m x 200 m, 300 scans: the
    tracker's per-scan level, averaged over scans 30-299, is within 4 stds of the Poisson mean (std √(10/270)/10 =
    1.9 %) plus the bias of the tracks' existence below 1 (3 × 0.9 × (1 − 0.98) = 0.05 false alarms per scan)."""
    rng = np.random.default_rng(11)
    targets = ((0.0, 99.0, -50.0, -50.0, 30.0, 5.0, 0.0), (0.0, 99.0, 50.0, 0.0, 180.0, 3.0, 0.05),
               (0.0, 99.0, 0.0, 60.0, -90.0, 4.0, 0.0))
    times = np.round(0.1 * np.arange(300), 10)
    truth = truth_trajectories(targets, times, rng)
    dets, _ = detection_stream(truth, rng, 0.9, 10.0 / AREA, 0.3, REGION)
    trk = MultiTargetTracker(model="cv", clutter_density=ScanClutter(area=AREA), meas_std=0.3, accel_std=(1.0,))
    level = []
    for t, Z in zip(times, dets):
        rep = trk.step(t, Z)
        level.append(trk.clutter_density * AREA)
    assert rep.ids.size == 3
    m = np.mean(level[30:])
    assert abs(m - 10.0) < 4 * math.sqrt(10.0 / 270) + 0.05, m


def test_targets_are_not_counted_as_clutter():
    """30 targets and no false alarm at all: the per-file estimate (all detections per scan over the bounding box)
    counts every target's detection, about 27 per scan; the per-scan estimate removes those its tracks explain and
    is below a tenth of it once the tracks exist (its floor is 1 − a = 0.1 false alarms per scan)."""
    rng = np.random.default_rng(3)
    targets = tuple((0.0, 99.0, x, y, h, 2.0, 0.0) for x, y, h in
                    zip(rng.uniform(-80, 80, 30), rng.uniform(-80, 80, 30), rng.uniform(0, 360, 30)))
    times = np.round(0.1 * np.arange(100), 10)
    truth = truth_trajectories(targets, times, rng)
    dets, src = detection_stream(truth, rng, 0.9, 0.0, 0.3, REGION)
    assert not np.any(np.concatenate(src) < 0)
    per_file = bounding_box_density(np.vstack(dets), len(times))
    trk = MultiTargetTracker(model="cv", clutter_density="scan", meas_std=0.3)
    level = []
    for t, Z in zip(times, dets):
        trk.step(t, Z)
        level.append(trk.clutter_density)
    assert np.median(level[20:]) < 0.1 * per_file, (np.median(level[20:]), per_file)


# ---------------------------------------------------------------- the map
def test_map_finds_a_dense_patch():
    """4 false alarms per scan uniform over 200 m x 200 m and 20 more in a 40 m x 40 m patch (a density 126x the
    background there), 200 scans, every detection clutter: the map's shape ρ in the patch's cells is more than 10x
    that of the cells outside, and the densest cell is in the patch."""
    rng = np.random.default_rng(8)
    back = poisson_scans(rng, 200, 4.0)
    patch = poisson_scans(rng, 200, 20.0, PATCH)
    m = ClutterMap(cell=10.0, area=AREA)
    for Zb, Zp in zip(back, patch):
        Z = np.vstack([Zb, Zp])
        lam = m.density(0.0, Z, 0.0)
        m.update(Z, np.ones(Z.shape[0]))
    assert lam.shape == (Z.shape[0],)
    x = (m.origin[0] + np.arange(m.counts.shape[0]) + 0.5) * m.cell
    y = (m.origin[1] + np.arange(m.counts.shape[1]) + 0.5) * m.cell
    X, Y = np.meshgrid(x, y, indexing="ij")
    inside = (X > PATCH[0]) & (X < PATCH[1]) & (Y > PATCH[2]) & (Y < PATCH[3])
    cells = np.argwhere(np.ones(m.counts.shape, dtype=bool))
    rho = m.shape(cells).reshape(m.counts.shape)
    assert np.median(rho[inside]) > 10 * np.median(rho[~inside]), (np.median(rho[inside]), np.median(rho[~inside]))
    assert inside[np.unravel_index(np.argmax(rho), rho.shape)]
    assert m.peak() == pytest.approx(rho.max())


def test_map_in_the_tracker_on_the_patch_scenario():
    """The tracker's map on the patch scenario (targets and clutter, weights from the association; the tracker's own
    cell side, 8 gate diameters: 20.6 m, about half the patch): its densest cell is at the patch, and the density it
    gives the last scan's detections in the patch is more than 5x the density it gives those more than a cell away
    from it."""
    sc = clutter_scenario("patch", seed=1)
    trk = MultiTargetTracker(model="se2r3", clutter_density="map", meas_std=0.3)
    for t, Z in zip(sc.times, sc.detections):
        trk.step(t, Z)
    m = trk.clutter
    assert isinstance(m, ClutterMap) and m.cell == pytest.approx(8 * 2 * math.sqrt(2 * trk.gamma) * 0.3)
    i, j = np.unravel_index(np.argmax(m.counts), m.counts.shape)
    centre = (np.array([i, j]) + m.origin + 0.5) * m.cell
    assert PATCH[0] - m.cell < centre[0] < PATCH[1] + m.cell and PATCH[2] - m.cell < centre[1] < PATCH[3] + m.cell
    Z = sc.detections[-1]
    lam = m.density(sc.times[-1] + 0.1, Z, 0.0)
    inside = (Z[:, 0] > PATCH[0]) & (Z[:, 0] < PATCH[1]) & (Z[:, 1] > PATCH[2]) & (Z[:, 1] < PATCH[3])
    far = (Z[:, 0] < PATCH[0] - m.cell) | (Z[:, 0] > PATCH[1] + m.cell) | (Z[:, 1] < PATCH[2] - m.cell) | (
        Z[:, 1] > PATCH[3] + m.cell)
    assert inside.sum() > 5 and far.sum() > 1
    assert np.median(lam[inside]) > 5 * np.median(lam[far]), (np.median(lam[inside]), np.median(lam[far]))


def test_map_grid_grows_and_coarsens_keeping_its_counts(monkeypatch):
    """Detections far apart grow the grid; beyond MAX_CELLS its cells double (2 x 2 summed), the counts' total kept."""
    monkeypatch.setattr(cl, "MAX_CELLS", 400)
    m = ClutterMap(cell=1.0, forgetting=0.5, area=1e4)
    Z = np.array([[0.5, 0.5], [3.2, -4.1], [9.9, 9.9]])
    m.density(0.0, Z, 0.0)
    m.update(Z, np.ones(3))
    assert m.cell == 1.0 and m.counts.sum() == pytest.approx(3.0)
    Z2 = np.array([[-15.0, 0.0], [18.0, 25.0]])  # 34 x 30 cells of 1 m: coarsened to 2 m (17 x 15)
    m.density(1.0, Z2, 0.0)
    m.update(Z2, np.array([1.0, 0.25]))
    assert m.coarsened == 1 and m.cell == 2.0 and m.counts.size <= 400
    assert m.counts.sum() == pytest.approx(0.5 * 3.0 + 1.25)  # the old counts decayed by a = 0.5, then the new ones
    cells = np.floor(np.vstack([Z, Z2]) / m.cell).astype(np.int64) - m.origin
    assert np.all(cells >= 0) and np.all(cells < np.array(m.counts.shape))
    assert m.counts[tuple(cells[0])] == pytest.approx(0.5)


# ---------------------------------------------------------------- the tracker's use of λ
class Fixed(ClutterEstimator):
    """λ given per detection by a function of the positions (for the tests)."""

    name = "fixed"

    def __init__(self, fn):
        self.fn = fn

    def fresh(self):
        return Fixed(self.fn)

    def density(self, t, Z, expected):
        lam = self.fn(Z)
        self.level = float(np.mean(lam)) if np.size(lam) else 1e-4
        return lam


def _run(clutter, scans=40, **kw):
    sc = clutter_scenario("base", seed=4, duration=0.1 * (scans - 1))
    trk = MultiTargetTracker(model="cv", clutter_density=clutter, meas_std=0.3, **kw)
    out = []
    for t, Z in zip(sc.times, sc.detections):
        rep = trk.step(t, Z)
        out.append((rep.ids.copy(), rep.states.copy(), rep.existence.copy()))
    return trk, out


def test_lambda_per_detection_equal_to_a_constant_gives_the_constant_tracks():
    """λ(z) = λ at every detection (the array path: the weights rescaled per detection) gives the tracks of the
    constant λ (the scalar path), to rounding."""
    _, a = _run(1e-4)
    _, b = _run(Fixed(lambda Z: np.full(Z.shape[0], 1e-4)))
    for (ia, xa, ra), (ib, xb, rb) in zip(a, b):
        assert ia.tolist() == ib.tolist()
        np.testing.assert_allclose(xb, xa, rtol=1e-9, atol=1e-9)
        np.testing.assert_allclose(rb, ra, rtol=1e-9, atol=1e-12)


def test_one_point_existence_uses_the_density_at_each_detection():
    """With birth_density β and λ(z), a new track's existence is β/(β + λ(z)) at its detection."""
    beta = 1e-5
    lam = lambda Z: np.where(Z[:, 0] > 0, 1e-3, 1e-5)  # noqa: E731
    trk = MultiTargetTracker(model="cv", clutter_density=Fixed(lam), birth_density=beta, meas_std=0.3)
    Z = np.array([[50.0, 0.0], [-50.0, 0.0]])
    trk.step(0.0, Z)
    live = np.flatnonzero(trk.bank.live)
    r = dict(zip(trk.ids[live].tolist(), trk.r[live].tolist()))
    assert r[0] == pytest.approx(one_point_existence(beta, 1e-3))
    assert r[1] == pytest.approx(one_point_existence(beta, 1e-5))


def test_a_given_estimator_is_never_changed_and_constant_is_the_default():
    """The tracker works on a fresh copy: the same instance in two trackers gives the same tracks, and is unused."""
    est = ScanClutter(area=AREA)
    _, a = _run(est, scans=20)
    _, b = _run(est, scans=20)
    assert [x[0].tolist() for x in a] == [x[0].tolist() for x in b]
    assert math.isnan(est.level)
    trk = MultiTargetTracker(model="cv")
    assert isinstance(trk.clutter, ConstantClutter) and trk.clutter_density == 1e-4


@pytest.mark.parametrize("value,msg", [
    ("often", "clutter-density: a number or one of scan, map"),
    (-1e-4, "clutter-density: must be a positive number"),
    (float("nan"), "clutter-density: contains NaN"),
    (0.0, "clutter-density: must be a positive number"),
])
def test_bad_clutter_density_is_one_error(value, msg):
    with pytest.raises(ValueError, match=msg):
        MultiTargetTracker(model="cv", clutter_density=value)


@pytest.mark.parametrize("make,msg", [
    (lambda: ScanClutter(forgetting=1.0), "forgetting factor must be in"),
    (lambda: ClutterMap(forgetting=-0.1), "forgetting factor must be in"),
    (lambda: ClutterMap(cell=0.0), "clutter-map cell: must be a positive number"),
    (lambda: ClutterMap(prior=float("nan")), "clutter-map prior: contains NaN"),
    (lambda: clutter_from_data("guess", np.zeros((2, 2)), 1), "clutter: one of file, scan, map"),
])
def test_bad_estimator_settings(make, msg):
    with pytest.raises(ValueError, match=msg):
        make()


@pytest.mark.parametrize("bad", [np.nan, -1.0, 0.0])
def test_a_bad_estimate_stops_the_tracker_with_one_error(bad):
    trk = MultiTargetTracker(model="cv", clutter_density=Fixed(lambda Z: np.full(Z.shape[0], bad)))
    with pytest.raises(ValueError, match=r"clutter density at t = 0.0: the fixed estimate is not a positive number"):
        trk.step(0.0, np.array([[0.0, 0.0]]))


def test_clutter_estimator_and_clutter_from_data():
    assert isinstance(clutter_estimator(2e-4), ConstantClutter) and clutter_estimator(2e-4).level == 2e-4
    assert isinstance(clutter_estimator("scan"), ScanClutter) and isinstance(clutter_estimator("map"), ClutterMap)
    z = np.array([[0.0, 0.0], [10.0, 0.0], [10.0, 20.0], [0.0, 5.0]])
    assert clutter_from_data("file", z, 2) == pytest.approx(2.0 / 200.0)
    est = clutter_from_data("map", z, 2)
    assert isinstance(est, ClutterMap) and est.surveillance_area == pytest.approx(200.0)
    # 2 detections per scan, 200 per memory of 100 scans, 30 per cell: 6.67 cells of 200/6.67 = 30 m² each
    assert est.cell == pytest.approx(map_cell_from_counts(z, 2)) == pytest.approx(math.sqrt(30.0))
    sc = clutter_scenario("patch", seed=0)
    assert 18 < study_clutter("map", sc, 1e-4).cell < 22  # about 31 detections per scan over 200 m x 200 m
    assert clutter_from_data("scan", z[:1], 1).surveillance_area == cl.MIN_AREA  # a point: at least 1 m²


# ---------------------------------------------------------------- the CLI and the study
def _write(path, sc):
    rows = ["t,x,y"] + [f"{t:.6f},{z[0]:.4f},{z[1]:.4f}" for t, Z in zip(sc.times, sc.detections) for z in Z]
    path.write_text("\n".join(rows) + "\n")


def _track(*args):
    return subprocess.run([*cli_command(), "track", *map(str, args)], capture_output=True, text=True)


@pytest.mark.slow
@pytest.mark.parametrize("clutter,words", [
    (None, "clutter density from the data: a map of"),
    ("map", "clutter density from the data: a map of"),
    ("scan", "clutter density from the data: per scan (the moment estimate"),
    ("file", "estimated: detections per scan / bounding-box area"),
])
def test_cli_estimates_the_clutter_and_says_so(tmp_path, clutter, words):
    """`lgekf track --multi` without --clutter-density on the patch scenario: one line with the estimate; the map's
    line names the densest cell, the others no map."""
    sc = clutter_scenario("patch", seed=2, duration=6.0)
    _write(tmp_path / "d.csv", sc)
    extra = [] if clutter is None else ["--clutter", clutter]
    p = _track(tmp_path / "d.csv", "--multi", "--model", "cv", "--meas-std", "0.3", "-o", tmp_path / "o.csv", *extra)
    assert p.returncode == 0, p.stderr
    assert words in p.stderr and p.stderr.count("clutter density") == 1, p.stderr
    assert ("the densest cell" in p.stderr) == (clutter in (None, "map"))
    assert "confirmed track" in p.stdout


@pytest.mark.parametrize("args,msg", [
    (["--clutter", "map", "--clutter-density", "1e-4"], "--clutter: not with --clutter-density"),
    (["--clutter-density", "-1e-4"], "clutter-density: must be a positive number"),
    (["--clutter-density", "nan"], "clutter-density: contains NaN"),
])
def test_cli_bad_clutter_is_one_line_and_no_output(tmp_path, capsys, args, msg):
    from lgekf.cli import main

    (tmp_path / "d.csv").write_text("t,x,y\n0,0,0\n0.1,0.1,0\n")
    code = main(["track", str(tmp_path / "d.csv"), "--multi", "-o", str(tmp_path / "o.csv"), *args])
    err = capsys.readouterr().err
    assert code == 2 and len(err.strip().splitlines()) == 1 and msg in err, err
    assert not (tmp_path / "o.csv").exists()


def test_cli_clutter_needs_multi(tmp_path, capsys):
    from lgekf.cli import main

    (tmp_path / "d.csv").write_text("id,t,x,y\na,0,0,0\na,0.1,0.1,0\na,0.2,0.2,0\n")
    code = main(["track", str(tmp_path / "d.csv"), "-o", str(tmp_path / "o.csv"), "--clutter", "scan"])
    err = capsys.readouterr().err
    assert code == 2 and "--clutter" in err and "--multi" in err, err


def test_study_compares_clutters_on_the_same_detections():
    from lgekf.experiments.multi_study import MultiStudyConfig, format_multi_table, run_multi_study

    cfg = MultiStudyConfig(models=("cv",), associations=("jpda",), runs=1, duration=2.0, scenario="patch",
                           clutters=("true", "map", "oracle"))
    cells = run_multi_study(cfg)
    assert [c.clutter for c in cells] == ["true", "map", "oracle"]
    assert all(c.gospa > 0 for c in cells)
    text = format_multi_table(cells, cfg)
    assert "of the patch scenario" in text and "background λ = 0.0001" in text and "\ncv       jpda  one-point map" in text


@pytest.mark.parametrize("args,msg", [
    (["--scenario", "storm"], "--scenario: invalid choice"),
    (["--clutter", "true,guess"], "--clutter: unknown name 'guess'"),
    (["--scenario", "patch", "--dataset", "eth"], "--scenario: not with --dataset"),
])
def test_study_clutter_errors_are_one_line(args, msg, capsys, tmp_path):
    from lgekf.cli import main

    code = main(["study", "--multi", "--out", str(tmp_path), *args])
    err = capsys.readouterr().err
    assert code == 2 and msg in err, err
    assert not (tmp_path / "multi_gospa.csv").exists()


def test_scenarios_have_their_clutter():
    """The burst scenario has 16x the false alarms per scan during the burst, the patch scenario 5x the background's
    per scan and most of them in the patch; the base scenario's detections are those of ``base_scenario``."""
    from lgekf.experiments.clutter_scenarios import BURST
    from lgekf.experiments.multi_scenarios import base_scenario

    b = clutter_scenario("burst", seed=0)
    n = np.array([np.sum(s < 0) for s in b.sources])
    on = (b.times >= BURST[0]) & (b.times <= BURST[1])
    assert 50 < n[on].mean() < 80 and 2 < n[~on].mean() < 6
    assert b.mean_density == pytest.approx(1e-4 + 1.5e-3 * on.mean())
    p = clutter_scenario("patch", seed=0)
    false = np.vstack([Z[s < 0] for Z, s in zip(p.detections, p.sources)])
    inside = (false[:, 0] >= PATCH[0]) & (false[:, 0] <= PATCH[1]) & (false[:, 1] >= PATCH[2]) & (false[:, 1] <= PATCH[3])
    assert 0.75 < inside.mean() < 0.9
    np.testing.assert_allclose(p.true_density(0.0, np.array([[0.0, 0.0], [90.0, 90.0]])), [1e-4 + 1.25e-2, 1e-4])
    base, ref = clutter_scenario("base", seed=3), base_scenario(seed=3)
    assert all(np.array_equal(x, y) for x, y in zip(base.detections, ref.detections))


def test_the_imm_bank_takes_the_estimated_clutter():
    """An IMM per track (``model="imm"``) with the map: the same component, λ(z) in its association."""
    sc = clutter_scenario("patch", seed=0, duration=3.0)
    trk = MultiTargetTracker(model="imm", clutter_density=study_clutter("map", sc, 1e-4), meas_std=0.3)
    for t, Z in zip(sc.times, sc.detections):
        rep = trk.step(t, Z)
    assert isinstance(trk.clutter, ClutterMap) and trk.clutter.peak() > 3
    assert 4 <= rep.ids.size <= 10 and np.isfinite(trk.clutter_density)
