"""What the paper's errata do to a filter's output (the only one that can: ad_SE(2)'s corner entry).

    .venv/bin/python benchmarks/errata_effect.py

Builds the dense SE(2)×SE(2) LG-EKF twice, with Φ summed from the correct ad_SE(2) and from the ad
as printed (corner entry 1 instead of 0), runs both on the same simulated trajectories of the
study's protocol, and reports the position RMSE of each.  The intermediate typos in eq:derC and
eq:derH do not reach the final 𝒞 and ℋ, so they cannot change any output.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

from dense_numpy import run_dense  # noqa: E402

from lgekf.experiments.simulate import simulate  # noqa: E402


def main(n=30):
    rng = np.random.default_rng(5)
    P0 = np.diag([0.25, 0.25, 0.01, 0.25, 0.25, 0.01])
    print(f"{'σ_ω':>5} {'RMSE correct ad':>16} {'RMSE printed ad':>16} {'change':>8}")
    for sw in (0.1, 1.0, 2.0, 3.0):
        x0 = np.tile([0, 0, 0, 3.0, 0, 0], (n, 1))
        sim = simulate(x0, dt=0.1, steps=100, sigma_v=0.1, sigma_w=sw, meas_std=0.5, rng=rng)
        pos = sim.truth[:, 1:, :2]
        r = []
        for printed in (False, True):
            est = run_dense(sim.z, 0.1, (0.1, 0.1, sw), 0.5, x0, P0, printed_ad=printed)
            r.append(np.sqrt(np.mean(np.sum((est - pos) ** 2, axis=2), axis=1)).mean())
        print(f"{sw:5.1f} {r[0]:16.4f} {r[1]:16.4f} {(r[1] / r[0] - 1):+8.1%}")


if __name__ == "__main__":
    main()
