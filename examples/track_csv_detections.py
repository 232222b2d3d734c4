"""Track the objects of a CSV file of detections (columns t, x, y, id) with the SE(2)×SE(2) LG-EKF, from Python.

Without an argument the script writes a small demo file into a temporary folder (a turning car and a
walking pedestrian, irregular timestamps, 0.3 m detection noise) and tracks it; give your own file as
``python examples/track_csv_detections.py detections.csv`` (t in s, x and y in m; rows of different
objects may be interleaved). ``lgekf.track`` runs the engine of the ``lgekf track`` command (the same checks,
noise estimated from the data, divergence monitor) and returns its output as a pandas DataFrame: one row per
detection with the state, its stds, the NIS and the flag column (docs/track.md).

Run: ``python examples/track_csv_detections.py [detections.csv]``
"""

import csv
import math
import sys
import tempfile
from pathlib import Path

import numpy as np

import lgekf

MEAS_STD = 0.3  # detection noise per axis of the demo (m); lgekf.track estimates it from the data


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
        truth[f"{name}:z"] = z
        rows += [(tt, zx, zy, name) for tt, (zx, zy) in zip(t, z)]
    rows.sort()  # interleaved in time, as a detector would write them
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["t", "x", "y", "id"])
        w.writerows(rows)
    return truth


def main(path, truth=None):
    tracks = lgekf.track(path, model="se2se2")
    for name, obj in tracks.groupby("id", sort=False):
        t = obj["t"].to_numpy()
        last = obj.iloc[-1]
        line = (f"{name}: {len(obj)} detections over {t[-1] - t[0]:.1f} s; last estimate x = {last['x']:.2f} m, "
                f"y = {last['y']:.2f} m, speed {math.hypot(last['vx'], last['vy']):.2f} m/s, "
                f"turn rate {last['omega']:+.2f} ± {last['std_omega']:.2f} rad/s")
        if truth is not None:  # rows 0 and 1 of an object are its two-point start: scored from row 2 on, as before
            est = obj[["x", "y"]].to_numpy()[2:]
            rmse = np.sqrt(np.mean(np.sum((est - truth[name][2:]) ** 2, axis=1)))
            raw = np.sqrt(np.mean(np.sum((truth[f"{name}:z"][2:] - truth[name][2:]) ** 2, axis=1)))
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
            print(f"demo detections written to a temporary file: {sum(len(truth[n]) for n in ('car', 'walker'))} rows, 2 objects")
            main(demo, truth)
