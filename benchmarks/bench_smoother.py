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
* ``fwd_simd``: the same in the SIMD lanes, ``run_batch_store_soa_<meas>`` (the states kept in blocks of lanes);
* ``bwd``: the backward pass ``smooth_batch`` (``smooth_step_at`` per step, prange over trajectories);
* ``bwd_simd``: the backward pass ``smooth_batch_soa`` (``smooth_step`` in the SIMD lanes) over the blocks that
  fwd_simd stored, what ``filter_batch(smooth=True)`` runs from SOA_SMOOTH_MIN_BATCH trajectories on.

Both backward passes are timed as filter_batch runs them without ``return_cov`` (smoothed states only, no
covariances unpacked from the blocks).

Printed: ns per trajectory-step of each, and three ratios of smoothing (forward pass + backward pass) to filtering:

* ``same/scalar`` = (fwd + bwd) / scalar: **the issue's ratio** ("smoothing costs at most 2× filtering", issue #11),
  filtering and smoothing on the same scalar prange path (what filter_batch does below 1000 trajectories);
* ``simd/scalar`` = (fwd_simd + bwd_simd) / scalar;
* ``simd/simd`` = (fwd_simd + bwd_simd) / simd: filter_batch(smooth=True) against filter_batch from 1000
  trajectories on, both on their SIMD paths.

``bound`` = ``flops.smoother_bound``: (filter step + ``smooth_step_at``) / filter step in flops counted from the
generated source, what same/scalar would be at the filter's speed per flop; ``/bound`` = same/scalar over it (issue
#26's goal: ≤ 1.2).

The machine may be shared: absolute times are noisy, the ratios of one interleaved run much less so.
"""

import sys
import time

import numpy as np

from lgekf.core.covariance import pack
from lgekf.core.registry import MODELS, get_model
from lgekf.core.rts import forward_store, smooth_stored

from flops import smoother_bound


def _inputs(spec, B, K, rng):
    t = 0.1 * np.arange(1, K + 1)
    z = np.stack([3 * t, 0.2 * t**2], axis=-1)[None] + 0.3 * rng.standard_normal((B, K, 2))
    x0 = np.tile(spec.kernels.common_to_state(np.array([0, 0, 0, 3.0, 0, 0])), (B, 1))
    p0 = pack(np.broadcast_to(np.eye(spec.n) * 0.25, (B, spec.n, spec.n)))
    return np.ascontiguousarray(z), np.full((B, K), 0.1), x0, p0


def main(B=2000, K=200, repeats=5):
    rng = np.random.default_rng(0)
    print(f"{B} trajectories x {K} steps, position measurements; best of {repeats} interleaved rounds (ns per trajectory-step)")
    print(f"{'model':<8} {'scalar':>7} {'simd':>7} {'fwd':>7} {'fwd_simd':>8} {'bwd':>7} {'bwd_simd':>8}  {'same/scalar':>11}"
          f" {'simd/scalar':>11}"
          f" {'simd/simd':>9} {'bound':>6} {'/bound':>7}")
    worst = [0.0, 0.0, 0.0]
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
        for simd_pass in (False, True):
            smooth_stored(spec, forward_store(spec, "position", z[:4], dts[:4], x0[:4], p0[:4], q, r, simd=simd_pass),
                          covariances=False)
        ts = {k: [] for k in ("scalar", "simd", "fwd", "fwd_simd", "bwd", "bwd_simd")}
        for _ in range(repeats):
            t0 = time.perf_counter()
            scalar(z, dts, x0, p0, q, r, out_x, out_p, out_nis)
            t1 = time.perf_counter()
            simd(z, dts, x0, p0, q, r, out_x, out_p, out_nis)
            t2 = time.perf_counter()
            fp = forward_store(spec, "position", z, dts, x0, p0, q, r, simd=False)
            t3 = time.perf_counter()
            fps = forward_store(spec, "position", z, dts, x0, p0, q, r, simd=True)
            t3s = time.perf_counter()
            smooth_stored(spec, fp, covariances=False)
            t4 = time.perf_counter()
            smooth_stored(spec, fps, covariances=False)
            t5 = time.perf_counter()
            for k, v in zip(ts, (t1 - t0, t2 - t1, t3 - t2, t3s - t3, t4 - t3s, t5 - t4)):
                ts[k].append(v)
        best = {k: min(v) for k, v in ts.items()}
        simd_sum = best["fwd_simd"] + best["bwd_simd"]
        ratios = [(best["fwd"] + best["bwd"]) / best["scalar"], simd_sum / best["scalar"], simd_sum / best["simd"]]
        worst = [max(w, v) for w, v in zip(worst, ratios)]
        bound = smoother_bound(name)
        ns = 1e9 / (B * K)
        print(f"{name:<8} " + " ".join(f"{best[k] * ns:{w}.0f}" for k, w in (("scalar", 7), ("simd", 7), ("fwd", 7), ("fwd_simd", 8),
                                                                             ("bwd", 7), ("bwd_simd", 8)))
              + f"  {ratios[0]:11.2f} {ratios[1]:11.2f} {ratios[2]:9.2f} {bound:6.2f} {ratios[0] / bound:7.2f}", flush=True)
    print(f"largest same/scalar (the issue's ratio) {worst[0]:.2f}, simd/scalar {worst[1]:.2f}, simd/simd {worst[2]:.2f}")


if __name__ == "__main__":
    main(*[int(v) for v in sys.argv[1:4]])
