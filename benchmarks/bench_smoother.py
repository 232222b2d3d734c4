"""Cost of RTS smoothing on the group relative to filtering, per model (ratios measured in one interleaved run).

    python benchmarks/bench_smoother.py [B] [K] [repeats]

For every registry model, position measurements, B trajectories × K steps (default 2000 × 200), the kernels
``filter_batch`` runs, called directly (numba compiled first, best of ``repeats`` interleaved rounds):

* ``scalar``: the scalar batch filter ``run_batch_<meas>`` (prange over trajectories), the path the smoother's
  forward pass shares (filter_batch below SOA_MIN_BATCH trajectories);
* ``simd``: the SIMD filter ``run_batch_soa_<meas>`` (trajectories in the vector lanes), the fastest path
  (filter_batch from SOA_MIN_BATCH trajectories on);
* ``fwd``: the smoother's storing forward pass ``run_batch_store_<meas>`` (the fused filter step, also writing
  the predicted state and covariance; ``lgekf.core.rts.forward_store``);
* ``bwd``: the backward pass ``smooth_batch`` (``smooth_step`` per step; ``lgekf.core.rts.smooth_stored``).

Printed: ns per trajectory-step of each, and the ratios (fwd + bwd) / scalar and (fwd + bwd) / simd.
**The issue's ratio** ("smoothing costs at most 2× filtering", issue #11) is (fwd + bwd) / scalar: filtering and
smoothing on the same (scalar, prange) path; (fwd + bwd) / simd compares with the fastest filter there is, which
the smoother has no SIMD counterpart of.  The machine may be shared: absolute times are noisy, the ratios of one
interleaved run much less so.
"""

import sys
import time

import numpy as np

from lgekf.core.covariance import pack
from lgekf.core.registry import MODELS, get_model
from lgekf.core.rts import forward_store, smooth_stored


def _inputs(spec, B, K, rng):
    t = 0.1 * np.arange(1, K + 1)
    z = np.stack([3 * t, 0.2 * t**2], axis=-1)[None] + 0.3 * rng.standard_normal((B, K, 2))
    x0 = np.tile(spec.kernels.common_to_state(np.array([0, 0, 0, 3.0, 0, 0])), (B, 1))
    p0 = pack(np.broadcast_to(np.eye(spec.n) * 0.25, (B, spec.n, spec.n)))
    return np.ascontiguousarray(z), np.full((B, K), 0.1), x0, p0


def main(B=2000, K=200, repeats=5):
    rng = np.random.default_rng(0)
    print(f"{B} trajectories x {K} steps, position measurements; best of {repeats} interleaved rounds (ns per trajectory-step)")
    print(f"{'model':<8} {'scalar':>7} {'simd':>7} {'fwd':>7} {'bwd':>7}  {'(fwd+bwd)/scalar':>16} {'(fwd+bwd)/simd':>14}")
    worst = [0.0, 0.0]
    for name in MODELS:
        spec = get_model(name)
        z, dts, x0, p0 = _inputs(spec, B, K, rng)
        q = np.asarray(spec.default_accel_std, dtype=float)
        r = np.array([0.3])
        out_x = np.empty((B, K, spec.n))
        out_p = np.empty((B, 0, spec.n_packed))
        out_nis = np.empty((B, K))
        scalar = spec.kernels.run_batch_position
        simd = spec.kernels.run_batch_soa_position
        for f in (scalar, simd):  # compile
            f(z[:4], dts[:4], x0[:4], p0[:4], q, r, out_x[:4], out_p[:4], out_nis[:4])
        smooth_stored(spec, forward_store(spec, "position", z[:4], dts[:4], x0[:4], p0[:4], q, r))
        ts = {k: [] for k in ("scalar", "simd", "fwd", "bwd")}
        for _ in range(repeats):
            t0 = time.perf_counter()
            scalar(z, dts, x0, p0, q, r, out_x, out_p, out_nis)
            t1 = time.perf_counter()
            simd(z, dts, x0, p0, q, r, out_x, out_p, out_nis)
            t2 = time.perf_counter()
            fp = forward_store(spec, "position", z, dts, x0, p0, q, r)
            t3 = time.perf_counter()
            smooth_stored(spec, fp)
            t4 = time.perf_counter()
            for k, v in zip(ts, (t1 - t0, t2 - t1, t3 - t2, t4 - t3)):
                ts[k].append(v)
        best = {k: min(v) for k, v in ts.items()}
        sm = best["fwd"] + best["bwd"]
        ra, rb = sm / best["scalar"], sm / best["simd"]
        worst = [max(worst[0], ra), max(worst[1], rb)]
        ns = 1e9 / (B * K)
        print(f"{name:<8} {best['scalar'] * ns:7.0f} {best['simd'] * ns:7.0f} {best['fwd'] * ns:7.0f} {best['bwd'] * ns:7.0f}"
              f"  {ra:16.2f} {rb:14.2f}", flush=True)
    print(f"largest (fwd+bwd)/scalar (the issue's ratio): {worst[0]:.2f}; largest (fwd+bwd)/simd: {worst[1]:.2f}")


if __name__ == "__main__":
    main(*[int(v) for v in sys.argv[1:4]])
