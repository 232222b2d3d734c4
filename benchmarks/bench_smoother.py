"""Cost of RTS smoothing on the group relative to filtering, per model (ratios measured in one run).

    python benchmarks/bench_smoother.py [B] [K]

For every registry model: ``filter_batch`` (position measurements, B trajectories × K steps) without and
with ``smooth=True`` (the storing forward pass + the backward pass), best of 5 interleaved runs each after
a warm-up (numba compiled). Prints the time per trajectory-step and the ratio smooth / filter; the issue's
target is a ratio of at most 2.
"""

import sys
import time

import numpy as np

from lgekf import filter_batch
from lgekf.core.registry import MODELS, get_model


def main(B=1000, K=200, repeats=5):
    rng = np.random.default_rng(0)
    t = 0.1 * np.arange(1, K + 1)
    z = np.stack([3 * t, 0.2 * t**2], axis=-1)[None] + 0.3 * rng.standard_normal((B, K, 2))
    print(f"{B} trajectories x {K} steps, position measurements; best of {repeats} (ns per trajectory-step)")
    print(f"{'model':<8} {'filter':>8} {'filter+smooth':>14} {'ratio':>6}")
    worst = 0.0
    for name in MODELS:
        spec = get_model(name)
        x0 = np.tile(spec.kernels.common_to_state(np.array([0, 0, 0, 3.0, 0, 0])), (B, 1))
        P0 = np.eye(spec.n) * 0.25
        kw = dict(dt=0.1, accel_std=spec.default_accel_std, meas_std=0.3, x0=x0, P0=P0)
        filter_batch(name, z[:4], **{**kw, "x0": x0[:4]}, smooth=True)  # compile
        filter_batch(name, z[:4], **{**kw, "x0": x0[:4]})
        tf, ts = [], []
        for _ in range(repeats):
            a = time.perf_counter()
            filter_batch(name, z, **kw)
            b = time.perf_counter()
            filter_batch(name, z, **kw, smooth=True)
            c = time.perf_counter()
            tf.append(b - a)
            ts.append(c - b)
        f, s = min(tf), min(ts)
        worst = max(worst, s / f)
        print(f"{name:<8} {1e9 * f / (B * K):8.0f} {1e9 * s / (B * K):14.0f} {s / f:6.2f}")
    print(f"largest ratio smoothing / filtering: {worst:.2f}")


if __name__ == "__main__":
    main(*[int(v) for v in sys.argv[1:3]])
