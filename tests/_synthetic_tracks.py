"""(Test helper.) Synthetic ground-truth tracks for ``lgekf evaluate`` and the ``--tune``/``--smooth`` CLI tests."""

from __future__ import annotations

import csv

import numpy as np


def synthetic_tracks(n=12, K=40, dt=0.1, seed=0):
    """Circles (turning) and straight lines with exact velocities."""
    rng = np.random.default_rng(seed)
    rows = []
    for i in range(n):
        t = np.arange(K) * dt + rng.uniform(0, 1)
        w = 0.0 if i % 3 == 0 else rng.uniform(-0.8, 0.8)
        sp, th0 = rng.uniform(1, 4), rng.uniform(-np.pi, np.pi)
        th = th0 + w * (t - t[0])
        if w == 0:
            x = sp * np.cos(th0) * (t - t[0])
            y = sp * np.sin(th0) * (t - t[0])
        else:
            x = sp / w * (np.sin(th) - np.sin(th0))
            y = -sp / w * (np.cos(th) - np.cos(th0))
        rows += [(i, tt, xx, yy, sp * np.cos(a), sp * np.sin(a)) for tt, xx, yy, a in zip(t, x, y, th)]
    return rows


def write_synthetic(path, rows, short=0):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["id", "t", "x", "y", "vx", "vy"])
        w.writerows([[r[0], *map(repr, map(float, r[1:]))] for r in rows])
        for k in range(short):  # a track too short to evaluate
            w.writerow([999, float(k), 0.0, 0.0, 0.0, 0.0])
    return path
