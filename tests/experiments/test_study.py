"""The Monte Carlo study: a reduced run checks the robust facts of the paper's Fig. 4, and the CLI."""

from __future__ import annotations

import csv
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from lgekf.experiments.study import FILTERS, StudyConfig, claims_check, run_study

LGEKF = str(Path(sys.executable).with_name("lgekf"))


@pytest.fixture(scope="module")
def reduced():
    cfg = StudyConfig(trajectories=30, sigmas=[0.0, 1.5, 3.0], seed=7)
    return run_study(cfg)


def test_measurement_rmse_is_half_sqrt2(reduced):
    # per-trajectory RMSE of N(0, 0.5²) noise on two axes over 100 steps: sqrt(2)·0.5 up to O(1/K)
    m = reduced.mean("measurements")
    assert np.all(np.abs(m - 0.5 * np.sqrt(2)) < 0.02), m


def test_lg_filters_beat_measurements(reduced):
    for name in ("se2se2", "se2r3"):
        assert np.all(reduced.mean(name) < 0.75 * reduced.mean("measurements")), (name, reduced.mean(name))


def test_lg_filters_close(reduced):
    a, b = reduced.mean("se2se2"), reduced.mean("se2r3")
    assert np.all(np.abs(a - b) / np.minimum(a, b) < 0.05), (a, b)


def test_cv_degrades_with_sigma(reduced):
    cv = reduced.mean("cv")
    assert cv[0] < cv[1] and cv[0] < cv[2] and cv[2] > 2 * cv[0], cv


def test_same_seed_same_numbers(reduced):
    again = run_study(StudyConfig(trajectories=30, sigmas=[0.0, 1.5, 3.0], seed=7))
    for name in (*FILTERS, "measurements"):
        np.testing.assert_array_equal(again.rmse[name], reduced.rmse[name])
    other = run_study(StudyConfig(trajectories=30, sigmas=[0.0, 1.5, 3.0], seed=8))
    assert not np.array_equal(other.rmse["se2se2"], reduced.rmse["se2se2"])


def test_claims_have_numbers(reduced):
    claims = claims_check(reduced)
    assert len(claims) == 7
    for c in claims:
        assert isinstance(c.holds, bool) and any(ch.isdigit() for ch in c.evidence), c


def test_wraps_only_with_rotational_noise(reduced):
    assert reduced.wrapped[0] == 0  # σ_ω = 0: ω stays 0
    assert reduced.wrapped[2] > 0  # σ_ω = 3: a random walk of std 3 rad/s crosses ±π often


@pytest.mark.parametrize("bad", [["--sigmas=-1,2"], ["--sigmas"], ["--noise-scale", "kf=2"], ["--trajectories", "1"], ["--dt", "0"], ["--v0", "3"]])
def test_study_cli_bad_input(tmp_path, bad):
    out = tmp_path / "res"
    r = subprocess.run([LGEKF, "study", "--out", str(out), "--quiet", *bad], capture_output=True, text=True)
    assert r.returncode == 2, r.stderr
    assert "Traceback" not in r.stderr and len(r.stderr.strip().splitlines()) == 1, r.stderr
    assert not out.exists()


def test_study_cli_writes_results(tmp_path):
    out = tmp_path / "res"
    r = subprocess.run(
        [LGEKF, "study", "--trajectories", "8", "--sigmas", "0,3", "--out", str(out), "--seed", "3"],
        capture_output=True, text=True,
    )
    assert r.returncode == 0, r.stderr
    assert "claims of the paper" in r.stdout and ("holds" in r.stdout)
    with open(out / "summary.csv") as f:
        rows = list(csv.DictReader(f))
    assert list(rows[0]) == ["sigma_w", "filter", "mean_rmse", "std_rmse", "n"]
    assert {r["filter"] for r in rows} == {*FILTERS, "measurements"}
    assert len(rows) == 2 * (len(FILTERS) + 1) and all(int(r["n"]) == 8 for r in rows)
    with open(out / "rmse.csv") as f:
        assert sum(1 for _ in f) == 1 + 2 * 8 * (len(FILTERS) + 1)
    meta = json.loads((out / "meta.json").read_text())
    assert meta["protocol"]["seed"] == 3 and meta["protocol"]["sigmas"] == [0.0, 3.0]
    assert {"versions", "wall_seconds", "claims", "wrapped_trajectories_per_sigma"} <= set(meta)
    png = (out / "study.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and len(png) > 10_000


@pytest.mark.slow
def test_figures_cli(tmp_path):
    r = subprocess.run([LGEKF, "figures", "--out", str(tmp_path)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    for name in ("fig2_banana.png", "fig3_trajectories.png"):
        data = (tmp_path / name).read_bytes()
        assert data[:4] == b"\x89PNG" and len(data) > 10_000


@pytest.mark.parametrize("args", [["--noise-scale", "cv=30", "ctrv=3"], ["--noise-scale", "cv=30", "--noise-scale", "ctrv=3"]])
def test_noise_scale_several_values_after_one_flag_or_repeated(tmp_path, args):
    # the README's `--noise-scale cv=30 ctrv=3` failed with "unrecognized arguments: ctrv=3"
    out = tmp_path / "res"
    r = subprocess.run([LGEKF, "study", *args, "--trajectories", "3", "--sigmas", "0,1", "--steps", "10", "--no-figure",
                        "--quiet", "--out", str(out)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    meta = json.loads((out / "meta.json").read_text())
    assert meta["protocol"]["noise_scale"] == {**{f: 1.0 for f in FILTERS}, "ctrv": 3.0, "cv": 30.0}


def test_se2r3_truth_runs_beyond_pi_and_reports_se2se2_aliasing():
    """Issue #9: `--truth se2r3 --w0 3` runs; the SE(2)xSE(2) filter cannot represent |ω| > π and aliases:
    the study counts those trajectories (truth ω leaves [-π, π]) instead of refusing the protocol."""
    cfg = StudyConfig(trajectories=12, sigmas=[0.0, 1.5], steps=30, truth="se2r3", w0=3.0, seed=4)
    res = run_study(cfg)
    assert set(res.aliased) == {"se2se2"}  # the only model with a bounded coordinate
    # at σ_ω = 0 ω stays at 3 (+ init error) < π for most, at 1.5 the random walk leaves [-π, π] often
    assert res.aliased["se2se2"][1] > res.aliased["se2se2"][0] >= 0 and res.aliased["se2se2"][1] >= 3
    assert all(np.isfinite(res.rmse[f]).all() for f in cfg.filters)
    # the SE(2)xR3 filter (ω a plain number) tracks this truth; the aliased SE(2)xSE(2) filter does worse
    assert res.mean("se2r3")[1] < res.mean("se2se2")[1]
