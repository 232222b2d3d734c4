"""The multi-target study: scenario contents, detection streams from real trajectories (skipped without the
data), the study's cells and table, and `lgekf study --multi` errors."""

from __future__ import annotations

import numpy as np
import pytest

from lgekf.experiments.multi_scenarios import BASE_TARGETS, base_scenario, dataset_scenario
from lgekf.estimators.multitarget.tracker import DEFAULT_INITIATION
from lgekf.experiments.multi_study import MultiStudyConfig, format_multi_table, run_multi_study
from lgekf.io.datasets import Dataset, data_root, load_dataset


def test_base_scenario_has_births_deaths_clutter_and_misses():
    sc = base_scenario(seed=3, clutter_density=1e-4, detection_prob=0.9)
    alive = np.array([len(ids) for ids, _ in sc.truth])
    assert alive.min() == 6 and alive.max() == len(BASE_TARGETS)  # all 8 between 8 s (birth) and 12 s (death)
    assert alive[0] == 6 and alive[-1] == 6 and alive[int(np.searchsorted(sc.times, 6.0))] == 7
    src = np.concatenate(sc.sources)
    n_truth = alive.sum()
    assert 0.86 < np.sum(src >= 0) / n_truth < 0.94  # P_D = 0.9
    assert 3.0 < np.sum(src < 0) / len(sc.times) < 5.0  # λ · area = 4 per scan
    # the crossing pair meets: at some scan the two are within 1 m
    d = [np.hypot(*(X[list(ids).index(0), :2] - X[list(ids).index(1), :2])) for ids, X in sc.truth]
    assert min(d) < 1.0
    # the parallel pair stays 2.5 m apart (up to the speed random walk)
    d = [np.hypot(*(X[list(ids).index(2), :2] - X[list(ids).index(3), :2])) for ids, X in sc.truth[:50]]
    assert 2.0 < min(d) and max(d) < 3.5


def test_dataset_scenario_from_synthetic_tracks():
    t = np.array([0.0, 0.4, 0.8, 0.4, 0.8, 1.2])
    p = np.array([[0, 0], [0.5, 0], [1.0, 0], [5, 5], [5, 5.5], [5, 6.0]], dtype=float)
    ds = Dataset("toy", t, p, None, np.array([0, 3, 6]), ["a", "b"])
    sc = dataset_scenario(ds, seed=0, detection_prob=1.0, clutter_density=1e-9, meas_std=1e-6)
    assert sc.times.tolist() == [0.0, 0.4, 0.8, 1.2]
    assert [ids.tolist() for ids, _ in sc.truth] == [[0], [0, 1], [0, 1], [1]]
    np.testing.assert_allclose(sc.truth[1][1][:, :2], [[0.5, 0], [5, 5]])
    np.testing.assert_allclose(sc.truth[2][1][:, 2], [0.0, np.pi / 2])  # heading of motion
    got = sorted(map(tuple, np.round(sc.detections[1], 4)))
    assert got == [(0.5, 0.0), (5.0, 5.0)]


def test_study_cells_and_table():
    cfg = MultiStudyConfig(models=("cv",), associations=("jpda", "gnn"), runs=1, duration=3.0)
    cells = run_multi_study(cfg)
    assert [(c.model, c.association, c.initiation) for c in cells] == [("cv", "jpda", DEFAULT_INITIATION["jpda"]),
                                                                       ("cv", "gnn", DEFAULT_INITIATION["gnn"])]
    for c in cells:
        assert c.gospa > 0 and c.localisation >= 0 and c.missed >= 0 and c.false >= 0
    text = format_multi_table(cells, cfg)
    assert "GOSPA (c = 5 m, p = 2" in text and text.count("\ncv ") == 2


def test_study_intervals_over_runs(tmp_path):
    """Two runs: each cell keeps both runs' values (the second is what a one-run study from the next seed gives), the
    means and the summed switches come from them, and multi_gospa.csv holds the half-widths of the 95 % t-intervals,
    t_{0.975, 1}·|a − b|/2 with t_{0.975, 1} = 12.706205 (tables), and the switches per run."""
    import csv

    from lgekf.cli import main

    cfg = MultiStudyConfig(models=("cv",), associations=("gnn",), runs=2, duration=2.0, seed=7)
    (cell,) = run_multi_study(cfg)
    (second,) = run_multi_study(MultiStudyConfig(models=("cv",), associations=("gnn",), runs=1, duration=2.0, seed=8))
    a, b = cell.per_run
    assert cell.per_run.shape == (2, 5)
    assert tuple(b) == (second.gospa, second.localisation, second.missed, second.false, second.switches)
    assert cell.gospa == pytest.approx((a[0] + b[0]) / 2) and cell.switches == a[4] + b[4]
    assert main(["study", "--multi", "--out", str(tmp_path), "--models", "cv", "--association", "gnn", "--runs", "2",
                 "--duration", "2", "--seed", "7", "--quiet"]) == 0
    (row,) = list(csv.DictReader(open(tmp_path / "multi_gospa.csv")))
    assert row["runs"] == "2"
    for k, part in enumerate(("gospa", "localisation", "missed", "false")):
        assert float(row[part]) == pytest.approx((a[k] + b[k]) / 2, rel=1e-5)
        assert float(row[f"{part}_ci95"]) == pytest.approx(12.706205 * abs(a[k] - b[k]) / 2, rel=1e-5, abs=1e-9)
    assert float(row["switches_per_run"]) == pytest.approx((a[4] + b[4]) / 2)
    assert "±" in format_multi_table([cell], cfg)


def test_dataset_scenario_head():
    t = np.array([0.0, 0.4, 0.8, 0.4, 0.8, 1.2])
    p = np.array([[0, 0], [0.5, 0], [1.0, 0], [5, 5], [5, 5.5], [5, 6.0]], dtype=float)
    sc = dataset_scenario(Dataset("toy", t, p, None, np.array([0, 3, 6]), ["a", "b"]), seed=0, clutter_density=1e-9)
    head = sc.head(2)
    assert head.times.tolist() == [0.0, 0.4] and len(head.truth) == len(head.detections) == len(head.sources) == 2
    assert head.region == sc.region and sc.head(None) is sc


def test_study_compares_initiations_on_the_same_detections():
    """--initiation one-point,two-point: one cell each, in that order, on the same detections (a cell of its own run
    gives the same numbers)."""
    cfg = MultiStudyConfig(models=("cv",), associations=("jpda",), initiations=("one-point", "two-point"), runs=1,
                           duration=2.0)
    cells = run_multi_study(cfg)
    assert [c.initiation for c in cells] == ["one-point", "two-point"]
    alone = run_multi_study(MultiStudyConfig(models=("cv",), associations=("jpda",), initiations=("two-point",), runs=1,
                                             duration=2.0))
    assert (cells[1].gospa, cells[1].missed, cells[1].switches) == (alone[0].gospa, alone[0].missed, alone[0].switches)


def test_noise_from_the_data_is_what_track_multi_estimates_on_each_run(tmp_path):
    """--noise data: each run's process noise is ``study_process_noise`` of that run's detections (the passes of
    ``lgekf track --multi``, tested in tests/cli/test_track_multi_defaults.py), recorded per run in the accel_std
    column; the cell's tracker then uses it (its GOSPA is that of a default-noise cell given those stds)."""
    import csv

    from lgekf.apps.track_multi import study_process_noise
    from lgekf.cli import main
    from lgekf.experiments.multi_study import scenarios

    cfg = MultiStudyConfig(models=("cv",), associations=("gnn",), runs=1, duration=3.0, noise="data")
    with pytest.raises(ValueError, match="noise='data' needs noise_fit"):
        run_multi_study(cfg)
    cell = run_multi_study(cfg, noise_fit=study_process_noise)[0]
    sc = scenarios(cfg)[0]
    args = dict(model="cv", association="gnn", detection_prob=0.9, clutter_density=cfg.clutter_density, max_speed=30.0,
                measurement="position", initiation=None)
    noise, text = study_process_noise(sc.times, [Z[:, :2] for Z in sc.detections], args, cfg.meas_std, cfg.heading_std)
    assert cell.accel_std == text and float(text) > 0
    assert noise["accel_std"] != (0.5,)  # not the default here: the estimate acts
    from lgekf.experiments.multi_study import run_tracker_on
    from lgekf.estimators.multitarget.tracker import MultiTargetTracker

    trk = MultiTargetTracker(meas_std=cfg.meas_std, **args, **noise)
    g = run_tracker_on(sc, lambda t, Z: (lambda r: (r.ids, r.states[:, :2]))(trk.step(t, Z[:, :2])), cfg.c, cfg.p)[0]
    assert cell.gospa == g
    assert main(["study", "--multi", "--noise", "data", "--runs", "1", "--duration", "2", "--models", "cv", "--association",
                 "gnn", "--out", str(tmp_path), "--quiet"]) == 0
    rows = list(csv.DictReader(open(tmp_path / "multi_gospa.csv")))
    assert len(rows) == 1 and float(rows[0]["accel_std"]) > 0


def test_study_runs_the_pmbm_one_point_only():
    """pmbm in the study: its cell with one-point initiation, none with two-point (the PMBM refuses it), next to
    JPDA's two."""
    cfg = MultiStudyConfig(models=("cv",), associations=("jpda", "pmbm"), initiations=("one-point", "two-point"),
                           runs=1, duration=2.0)
    cells = run_multi_study(cfg)
    assert [(c.association, c.initiation) for c in cells] == [("jpda", "one-point"), ("jpda", "two-point"),
                                                              ("pmbm", "one-point")]
    assert np.isfinite(cells[2].gospa) and cells[2].gospa < 5.0


def test_real_trajectories_as_detection_streams():
    root = data_root()
    try:
        ds = load_dataset("eth", root=root)
    except Exception as e:  # noqa: BLE001 - absent data is a skip, any reason
        pytest.skip(f"ETH data not available under {root}: {e}")
    sc = dataset_scenario(ds, seed=0, detection_prob=0.9, clutter_density=0.01, meas_std=0.1)
    assert len(sc.times) == np.unique(ds.t).size
    assert sum(len(ids) for ids, _ in sc.truth) == ds.t.size


@pytest.mark.parametrize("args,msg", [
    (["--models", "ukf"], "--models: unknown name 'ukf'"),
    (["--runs", "0"], "--runs: must be at least 1"),
    (["--detection-prob", "0"], "--detection-prob: must be a probability"),
    (["--gospa-p", "0.5"], "--gospa-p: must be at least 1"),
    (["--initiation", "three-point"], "--initiation: unknown name 'three-point'"),
    (["--noise", "learned"], "--noise: invalid choice: 'learned'"),
    (["--scans", "50"], "--scans: a positive number of scans, with --dataset only"),
])
def test_study_multi_errors_are_one_line(args, msg, capsys, tmp_path):
    from lgekf.cli import main

    code = main(["study", "--multi", "--out", str(tmp_path), *args])
    err = capsys.readouterr().err
    assert code == 2 and len(err.strip().splitlines()) == 1 and msg in err, err
    assert not (tmp_path / "multi_gospa.csv").exists()
