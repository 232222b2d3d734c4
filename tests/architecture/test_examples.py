"""Every script in examples/ runs (exit status 0, a few seconds), writes nothing into its working folder
and prints what it promises."""

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def run(script, *args, cwd):
    return subprocess.run([sys.executable, str(EXAMPLES / script), *map(str, args)], capture_output=True,
                          text=True, cwd=cwd, timeout=300, env={**os.environ, "MPLBACKEND": "Agg"})


def _number(pattern, text):
    m = re.search(pattern, text, re.M)
    assert m, f"{pattern!r} not in:\n{text}"
    return float(m.group(1))


def check_track_turning_object(out):
    meas = _number(r"^measurements\s+([\d.]+)", out)
    for name in ("SE(2)xSE(2) LG-EKF", "SE(2)xR3 LG-EKF", "CTRV EKF"):
        rmse = _number(rf"^{re.escape(name)}\s+([\d.]+)", out)
        assert 0 < rmse < meas  # the turning models beat the raw measurements
        assert 1.0 < _number(rf"^{re.escape(name)}\s+[\d.]+\s+([\d.]+)", out) < 3.0  # mean NIS near 2
    assert _number(r"^CV KF\s+([\d.]+)", out) > 0


def check_batch_monte_carlo_nees(out):
    lg_nees = _number(r"^se2se2\s+[\d.]+\s+([\d.]+) \(6\)", out)
    cv_nees = _number(r"^cv\s+[\d.]+\s+([\d.]+) \(4\)", out)
    assert 4.0 < lg_nees < 12.0 and cv_nees > 3 * lg_nees
    assert 1.5 < _number(r"^se2se2 .* ([\d.]+)$", out) < 2.5  # its mean NIS


def check_track_csv_detections(out):
    for name in ("car", "walker"):
        rmse = _number(rf"^{name}: .*position RMSE ([\d.]+) m", out)
        raw = _number(rf"^{name}: .*raw detections ([\d.]+) m", out)
        assert 0 < rmse < raw
    assert abs(_number(r"^car: .*speed ([\d.]+) m/s", out) - 8.0) < 0.5  # the demo car drives at 8 m/s


CHECKS = {
    "track_turning_object.py": check_track_turning_object,
    "batch_monte_carlo_nees.py": check_batch_monte_carlo_nees,
    "track_csv_detections.py": check_track_csv_detections,
}


def test_every_example_has_a_check():
    assert sorted(p.name for p in EXAMPLES.glob("*.py")) == sorted(CHECKS)


@pytest.mark.parametrize("script", sorted(CHECKS))
def test_example_runs(script, tmp_path):
    r = run(script, cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert r.stderr == ""
    CHECKS[script](r.stdout)
    assert list(tmp_path.iterdir()) == []  # nothing written outside a temporary folder


def test_csv_example_reads_a_given_file(tmp_path):
    data = tmp_path / "mine.csv"
    data.write_text("t,x,y,id\n" + "".join(f"{0.1 * k},{1.5 * 0.1 * k},0.0,bike\n" for k in range(20)))
    r = run("track_csv_detections.py", data, cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert _number(r"^bike: 20 detections .* speed ([\d.]+) m/s", r.stdout) == pytest.approx(1.5, abs=0.05)
    r = run("track_csv_detections.py", tmp_path / "missing.csv", cwd=tmp_path)
    assert r.returncode == 2 and r.stderr.count("\n") == 1 and "no such file" in r.stderr
