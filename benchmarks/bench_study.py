"""Time of the Monte Carlo study, measured in one run.

    .venv/bin/python benchmarks/bench_study.py

* compute: `run_study` with the default protocol (30 σ_ω × 100 trajectories × 4 filters + simulation)
  once everything is compiled (best of 3);
* the whole `lgekf study` command in a fresh process with an empty numba cache (first run after an
  install) and again with that cache warm;
* the dense-numpy SE(2)×SE(2) LG-EKF (benchmarks/dense_numpy.py) on a subset of the same trajectories,
  extrapolated linearly to the study's 3000 trajectories: that is ONE filter, the study runs four.
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from dense_numpy import run_dense  # noqa: E402

from lgekf.experiments.simulate import simulate  # noqa: E402
from lgekf.experiments.study import StudyConfig, run_study  # noqa: E402


def main():
    cfg = StudyConfig()
    run_study(cfg)
    compute = min(run_study(cfg).compute_seconds for _ in range(3))
    lgekf = str(Path(sys.executable).with_name("lgekf"))
    walls = []
    with tempfile.TemporaryDirectory() as cache, tempfile.TemporaryDirectory() as out:
        env = dict(os.environ, NUMBA_CACHE_DIR=cache)
        for _ in range(2):
            t = time.perf_counter()
            subprocess.run([lgekf, "study", "--quiet", "--out", out], env=env, check=True, capture_output=True)
            walls.append(time.perf_counter() - t)
    # dense numpy on a subset: 3 σ_ω values x 10 trajectories of the same protocol
    rng = np.random.default_rng(0)
    n_sub = 0
    t = time.perf_counter()
    for sw in (0.0, 1.5, 3.0):
        x0 = np.tile([0, 0, 0, 3.0, 0, 0], (10, 1))
        sim = simulate(x0, dt=0.1, steps=100, sigma_v=0.1, sigma_w=sw, meas_std=0.5, rng=rng)
        run_dense(sim.z, 0.1, (0.1, 0.1, max(sw, 1e-9)), 0.5, x0, np.diag([0.25, 0.25, 0.01, 0.25, 0.25, 0.01]))
        n_sub += 10
    dense_full = (time.perf_counter() - t) / n_sub * 3000
    print(f"study compute (30 σ_ω x 100 trajectories x 4 filters + simulation, compiled): {compute:.2f} s")
    print(f"`lgekf study` wall time: empty numba cache {walls[0]:.1f} s, warm cache {walls[1]:.1f} s")
    print(f"dense-numpy SE(2)xSE(2) filter alone on 3000 trajectories (extrapolated from {n_sub}): {dense_full:.0f} s"
          f" = {dense_full / compute:.0f}x the whole study's compute")


if __name__ == "__main__":
    main()
