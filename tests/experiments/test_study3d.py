"""`lgekf study --space 3d`: the paper's protocol lifted to SE(3) (truth se3r6, filters se3r6, se3se3, ct3, cv3, 3-D
position measurements), its claims through the lifted models, and its bad input."""

from __future__ import annotations

import csv
import json
import subprocess

import numpy as np
import pytest

from _cli import cli_command
from lgekf.experiments.study import StudyConfig, claims_check, run_study


@pytest.fixture(scope="module")
def reduced3d():
    return run_study(StudyConfig.for_space("3d", trajectories=30, sigmas=[0.0, 1.5, 3.0], seed=7))


def test_the_3d_protocol(reduced3d):
    cfg = reduced3d.config
    assert cfg.space == "3d" and cfg.truth == "se3r6" and cfg.measurement == "position3"
    assert set(cfg.filters) == {"se3r6", "se3se3", "ct3", "cv3"}
    # 3-D position noise N(0, 0.5² I): per-trajectory RMSE √3·0.5 up to O(1/K)
    m = reduced3d.mean("measurements")
    assert np.all(np.abs(m - 0.5 * np.sqrt(3)) < 0.03), m


def test_the_lg_filter_on_se3_beats_the_measurements_and_the_baselines_when_the_body_turns(reduced3d):
    """The paper's central claim carried over: with rotational noise the LG-EKF on SE(3)×R⁶ beats the raw
    measurements and both 3-D baselines (with the paper's matched noise)."""
    lg = reduced3d.mean("se3r6")
    assert np.all(lg < 0.75 * reduced3d.mean("measurements")), lg
    for base in ("ct3", "cv3"):
        assert np.all(lg[1:] < reduced3d.mean(base)[1:]), (base, lg, reduced3d.mean(base))


def test_claims_speak_of_the_lifted_models(reduced3d):
    claims = claims_check(reduced3d)
    assert claims and any("se3r6" in c.text for c in claims)
    assert not any("SE(2)xSE(2)" in c.text for c in claims)  # the lifted names, not the planar ones
    assert any("se3se3 and se3r6" in c.text for c in claims)  # SE(3)xSE(3) stands for SE(2)xSE(2)


def test_study_3d_cli(tmp_path):
    out = tmp_path / "s3d"
    r = subprocess.run([*cli_command(), "study", "--space", "3d", "--trajectories", "8", "--sigmas", "0,2", "--out", str(out),
                        "--no-figure"], capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    assert "se3r6 stands for se2r3" in r.stdout
    rows = list(csv.DictReader((out / "summary.csv").open()))
    assert {row["filter"] for row in rows} == {"se3r6", "se3se3", "ct3", "cv3", "measurements"}
    meta = json.loads((out / "meta.json").read_text())
    assert meta["protocol"]["space"] == "3d" and meta["protocol"]["v0"] == [3.0, 0.0, 0.0]


@pytest.mark.parametrize("args,message", [
    (["--space", "4d"], "--space: unknown space"),
    (["--space", "3d", "--v0", "3,0"], "--v0: expected 3"),
    (["--space", "3d", "--w0", "0.1"], "--w0: expected 3"),
    (["--space", "3d", "--filters", "se3r6,se2r3"], "--filters: unknown filter 'se2r3'"),
    (["--space", "3d", "--filters", "se3r6,imm", "--imm-modes", "cv,se2r3"], "imm-modes: cv,se2r3 are models of space '2d'"),
    (["--space", "3d", "--truth", "se2se2"], "truth"),
    (["--space", "3d", "--noise-scale", "cv=3"], "--noise-scale: unknown filter 'cv'"),
])
def test_bad_3d_options_are_one_clear_line(tmp_path, args, message):
    out = tmp_path / "never"
    r = subprocess.run([*cli_command(), "study", *args, "--trajectories", "4", "--sigmas", "0", "--out", str(out)],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 2, (r.returncode, r.stderr)
    assert message in r.stderr and "Traceback" not in r.stderr and len(r.stderr.strip().splitlines()) == 1, r.stderr
    assert not out.exists()
