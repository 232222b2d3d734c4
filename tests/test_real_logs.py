"""Real logs that are almost right (issue 27): each case a file made for it, run as a user runs ``lgekf track``."""

from __future__ import annotations

import csv

import numpy as np

from lgekf.cli import main


def _turning_car(path, heading_unit="rad", n=120, seed=0):
    """A car at 10 m/s turning at 0.2 rad/s, 10 Hz, 0.5 m position noise, a heading column (0.05 rad noise) in
    ``heading_unit``. Returns the true positions."""
    rng = np.random.default_rng(seed)
    t = 0.1 * np.arange(n)
    psi = 0.4 + 0.2 * t
    p = np.column_stack([50 * (np.sin(psi) - np.sin(0.4)), -50 * (np.cos(psi) - np.cos(0.4))])
    z = p + 0.5 * rng.standard_normal(p.shape)
    h = np.angle(np.exp(1j * (psi + 0.05 * rng.standard_normal(n))))
    h = np.degrees(h) if heading_unit == "deg" else h
    rows = ["id,t,x,y,heading"] + [f"car,{t[k]:.2f},{z[k, 0]:.4f},{z[k, 1]:.4f},{h[k]:.5f}" for k in range(n)]
    path.write_text("\n".join(rows) + "\n")
    return p


def _pos_rmse(out, p):
    rows = list(csv.DictReader(open(out)))
    x = np.array([[float(r["x"]), float(r["y"])] for r in rows])
    return float(np.sqrt(np.mean(np.sum((x[2:] - p[2:]) ** 2, axis=1))))


def test_heading_in_degrees_is_refused_with_a_hint_and_converted_on_request(tmp_path, capsys):
    src = tmp_path / "deg.csv"
    p = _turning_car(src, "deg")
    out = tmp_path / "out.csv"
    assert main(["track", str(src), "--measure", "pose", "-o", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--heading-unit deg" in err[0] and not out.exists()
    assert main(["track", str(src), "--measure", "pose", "--heading-unit", "deg", "-o", str(out), "--quiet"]) == 0
    in_deg = _pos_rmse(out, p)
    rad = tmp_path / "rad.csv"
    _turning_car(rad, "rad")
    assert main(["track", str(rad), "--measure", "pose", "-o", str(out), "--quiet"]) == 0
    assert abs(in_deg - _pos_rmse(out, p)) < 1e-6  # the numbers of the file in radians (up to the 5 written digits)
    assert in_deg < 0.5  # and better than the raw 0.5 m per axis (0.71 m)
