"""Cost of the IMM against the single filters, measured in one run (ratios only; absolute times are noisy).

    .venv/bin/python benchmarks/bench_imm.py [--quick]

For each IMM (M modes) the time of ``imm_batch`` over a batch, against ``filter_batch`` of its modes' models on
the same data; prints IMM / (M × one filter), "one filter" being the mean time of the modes' filters run alone,
IMM / Σ (the modes run alone), the flop bound of IMM / (M × one filter) (``flops.imm_bound``: the IMM's arithmetic
in filter steps, counted from the generated source) and the measured ratio over that bound (issue #26's goal:
≤ 1.3). Both run on one thread (NUMBA_NUM_THREADS=1 is
set before numba loads: the filters' prange and the IMM's threads, ``lgekf.estimators.threads``, obey it; other jobs on
the machine then matter less); best of 5.
Where an IMM step's time goes (mixing, likelihood, combined output): benchmarks/profile_imm.py.
"""

from __future__ import annotations

import argparse
import os
import time

os.environ.setdefault("NUMBA_NUM_THREADS", "1")

import numpy as np  # noqa: E402

from lgekf import filter_batch  # noqa: E402
from lgekf.core.common import covariance_from_common, state_from_common  # noqa: E402
from lgekf.estimators.imm.estimator import imm_batch, parse_modes  # noqa: E402

from flops import imm_bound  # noqa: E402

CASES = ["se2r3:calm,se2r3:manoeuvre", "cv,se2r3", "cv,ctrv,se2r3", "se2se2:calm,se2se2:manoeuvre"]


def best_of(fn, repeat=5):
    best = float("inf")
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t)
    return best


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="a small batch (a smoke test)")
    a = ap.parse_args(argv)
    B, K = (20, 50) if a.quick else (400, 200)
    rng = np.random.default_rng(0)
    t = 0.1 * np.arange(1, K + 1)
    z = np.stack([3 * t, 0.2 * t**2], axis=-1)[None] + 0.5 * rng.standard_normal((B, K, 2))
    c0 = np.tile([0.0, 0.0, 0.0, 3.0, 0.0, 0.1], (B, 1))
    P0c = np.diag([0.25, 0.25, 0.01, 0.25, 0.25, 0.01])
    print(f"batch {B} × {K} steps, position measurements, {os.environ['NUMBA_NUM_THREADS']} numba thread(s); best of 5")
    print(f"{'IMM modes':32s} {'M':>2s} {'ns/step IMM':>12s} {'ns/step filters (mean)':>23s} {'IMM/(M·filter)':>15s} {'IMM/Σ filters':>14s} {'bound':>6s} {'/bound':>7s}")
    for case in CASES:
        modes = parse_modes(case)
        M = len(modes)
        imm_batch(z[:2, :3], modes, dt=0.1, meas_std=0.5, x0=c0[:2], P0=P0c)  # compile / load
        t_imm = best_of(lambda: imm_batch(z, modes, dt=0.1, meas_std=0.5, x0=c0, P0=P0c))
        t_f = []
        for m in modes:
            x0 = state_from_common(m.model, c0)
            P0 = covariance_from_common(m.model, c0[0], P0c) + 1e-12 * np.eye(x0.shape[1])
            filter_batch(m.model, z[:2, :3], dt=0.1, accel_std=m.accel_std, meas_std=0.5, x0=x0[:2], P0=P0)
            t_f.append(best_of(lambda: filter_batch(m.model, z, dt=0.1, accel_std=m.accel_std, meas_std=0.5, x0=x0, P0=P0)))
        ns = 1e9 / (B * K)
        ratio, bound = t_imm / (M * np.mean(t_f)), imm_bound([m.model for m in modes])
        print(f"{case:32s} {M:2d} {t_imm * ns:12.0f} {np.mean(t_f) * ns:23.0f} {ratio:15.2f} "
              f"{t_imm / sum(t_f):14.2f} {bound:6.2f} {ratio / bound:7.2f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
