"""Track the objects of a CSV file of detections (columns t, x, y, id) with the SE(2)×SE(2) LG-EKF.

Without an argument the script writes a small demo file into a temporary folder (a turning car and a
walking pedestrian, irregular timestamps, 0.3 m detection noise) and tracks it; give your own file as
``python examples/track_csv_detections.py detections.csv`` (t in s, x and y in m; rows of different
objects may be interleaved). Each object is initialised from its first two detections, then filtered
with ``filter_batch`` using every step's own dt. The ``lgekf track`` command does the same for whole
files, with more options (see docs/track_evaluate.md); this script shows the Python API underneath.

Run: ``python examples/track_csv_detections.py [detections.csv]``
"""

import csv
import math
import sys
import tempfile
from pathlib import Path

import numpy as np

from lgekf import filter_batch

MEAS_STD = 0.3  # detection noise per axis (m)
ACCEL_STD = (0.5, 0.5, 1.0)  # body-frame accelerations (m/s²) and angular acceleration (rad/s²)


def write_demo(path):
    """Two objects with known truth: a car turning at 0.3 rad/s and a pedestrian; returns the truth."""
    rng = np.random.default_rng(9)
    truth, rows = {}, []
    for name, speed, turn, n in (("car", 8.0, 0.3, 80), ("walker", 1.4, 0.0, 60)):
        t = np.cumsum(rng.uniform(0.08, 0.15, n))
        heading = 0.4 + turn * t
        if turn:
            x = speed / turn * (np.sin(heading) - np.sin(0.4))
            y = -speed / turn * (np.cos(heading) - np.cos(0.4))
        else:
            x, y = speed * math.cos(0.4) * t, speed * math.sin(0.4) * t
        truth[name] = np.column_stack([x, y])
        z = truth[name] + MEAS_STD * rng.standard_normal((n, 2))
        rows += [(tt, zx, zy, name) for tt, (zx, zy) in zip(t, z)]
    rows.sort()  # interleaved in time, as a detector would write them
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["t", "x", "y", "id"])
        w.writerows(rows)
    return truth


def read_detections(path):
    """{id: (t (N,), z (N, 2))} sorted by time."""
    objects = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            objects.setdefault(row.get("id", "0"), []).append((float(row["t"]), float(row["x"]), float(row["y"])))
    out = {}
    for name, rows in objects.items():
        a = np.array(sorted(rows))
        out[name] = (a[:, 0], a[:, 1:])
    return out


def two_point_start(t, z):
    """State (x, y, θ, v_x, v_y, ω) and a diagonal P0 from the first two detections."""
    d = t[1] - t[0]
    v = (z[1] - z[0]) / d
    speed = float(np.hypot(*v))
    var_v = 2 * MEAS_STD**2 / d**2
    var_th = min(var_v / max(speed**2, 1e-12), math.pi**2)
    x0 = np.array([z[1, 0], z[1, 1], math.atan2(v[1], v[0]), speed, 0.0, 0.0])
    P0 = np.diag([MEAS_STD**2, MEAS_STD**2, var_th, var_v, max(var_v - speed**2 * var_th, 0.01 * var_v), 0.25])
    return x0, P0


def main(path, truth=None):
    for name, (t, z) in read_detections(path).items():
        if len(t) < 3:
            print(f"{name}: only {len(t)} detections, skipped")
            continue
        x0, P0 = two_point_start(t, z)
        x, P = filter_batch("se2se2", z[None, 2:], dt=np.diff(t)[1:], accel_std=ACCEL_STD, meas_std=MEAS_STD,
                            x0=x0[None], P0=P0, return_cov=True)
        last, std = x[0, -1], np.sqrt(np.diag(P[0, -1]))
        line = (f"{name}: {len(t)} detections over {t[-1] - t[0]:.1f} s; last estimate x = {last[0]:.2f} m, "
                f"y = {last[1]:.2f} m, speed {math.hypot(last[3], last[4]):.2f} m/s, "
                f"turn rate {last[5]:+.2f} ± {std[5]:.2f} rad/s")
        if truth is not None:
            rmse = np.sqrt(np.mean(np.sum((x[0, :, :2] - truth[name][2:]) ** 2, axis=1)))
            raw = np.sqrt(np.mean(np.sum((z[2:] - truth[name][2:]) ** 2, axis=1)))
            line += f"; position RMSE {rmse:.3f} m (raw detections {raw:.3f} m)"
        print(line)


if __name__ == "__main__":
    if len(sys.argv) > 1:
        if not Path(sys.argv[1]).is_file():
            print(f"track_csv_detections.py: error: {sys.argv[1]}: no such file", file=sys.stderr)
            sys.exit(2)
        main(Path(sys.argv[1]))
    else:
        with tempfile.TemporaryDirectory() as tmp:
            demo = Path(tmp) / "detections.csv"
            truth = write_demo(demo)
            print(f"demo detections written to a temporary file: {sum(len(v) for v in truth.values())} rows, 2 objects")
            main(demo, truth)
