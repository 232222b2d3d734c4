"""What storing the prediction costs the smoother's forward pass (the measurement quoted in derive/codegen/smooth_step.py).

    python benchmarks/bench_store_prediction.py [model ...]

Two scalar prange loops over the same trajectories (2000 × 200, position measurements), timed interleaved against
the filter's own ``run_batch_position`` (best of 7): one runs ``step_store_position`` and writes the prediction, the
posterior and the physical state (what ``run_batch_store_position`` writes), the other runs ``step_position`` and
writes only the posterior and the physical state (what a forward pass would write if the backward step recomputed
the prediction). Prints both as multiples of the filter.
"""

import sys
import time

import numba as nb
import numpy as np

from lgekf.core.covariance import pack
from lgekf.core.registry import MODELS, get_model


def loops(spec):
    k = spec.kernels
    step_store, step, phys, sfp = k.step_store_position, k.step_position, k.physical_into, k.state_from_physical
    ni, npk, nq = len(spec.internal_names), spec.n_packed, len(spec.noise_names)

    @nb.njit(parallel=True)
    def run(z, dts, x0, p0, q, r, s_pred, p_pred, s_filt, p_filt, out_x, keep):
        for b in nb.prange(z.shape[0]):
            s = sfp(x0[b])
            p = p0[b].copy()
            for kk in range(z.shape[1]):
                if keep:
                    if nq == 3:
                        step_store(s, p, dts[b, kk], q[0], q[1], q[2], z[b, kk, 0], z[b, kk, 1], r[0], s_pred[b, kk], p_pred[b, kk])
                    elif nq == 2:
                        step_store(s, p, dts[b, kk], q[0], q[1], z[b, kk, 0], z[b, kk, 1], r[0], s_pred[b, kk], p_pred[b, kk])
                    else:
                        step_store(s, p, dts[b, kk], q[0], z[b, kk, 0], z[b, kk, 1], r[0], s_pred[b, kk], p_pred[b, kk])
                else:
                    if nq == 3:
                        step(s, p, dts[b, kk], q[0], q[1], q[2], z[b, kk, 0], z[b, kk, 1], r[0])
                    elif nq == 2:
                        step(s, p, dts[b, kk], q[0], q[1], z[b, kk, 0], z[b, kk, 1], r[0])
                    else:
                        step(s, p, dts[b, kk], q[0], z[b, kk, 0], z[b, kk, 1], r[0])
                for i in range(ni):
                    s_filt[b, kk, i] = s[i]
                for i in range(npk):
                    p_filt[b, kk, i] = p[i]
                phys(s, out_x[b, kk])

    return run


def main(names, B=2000, K=200, repeats=7):
    for name in names:
        spec = get_model(name)
        k = spec.kernels
        rng = np.random.default_rng(0)
        t = 0.1 * np.arange(1, K + 1)
        z = np.ascontiguousarray(np.stack([3 * t, 0.2 * t**2], axis=-1)[None] + 0.3 * rng.standard_normal((B, K, 2)))
        x0 = np.tile(k.common_to_state(np.array([0, 0, 0, 3.0, 0, 0])), (B, 1))
        p0 = pack(np.broadcast_to(np.eye(spec.n) * 0.25, (B, spec.n, spec.n)))
        dts, q, r = np.full((B, K), 0.1), np.asarray(spec.default_accel_std, float), np.array([0.3])
        ni, npk = len(spec.internal_names), spec.n_packed
        arrs = [np.empty((B, K, ni)), np.empty((B, K, npk)), np.empty((B, K, ni)), np.empty((B, K, npk)), np.empty((B, K, spec.n))]
        run = loops(spec)
        for keep in (True, False):
            run(z[:2], dts[:2], x0[:2], p0[:2], q, r, *[a[:2] for a in arrs], keep)
        out, o0, nis = np.empty((B, K, spec.n)), np.empty((B, 0, npk)), np.empty((B, K))
        k.run_batch_position(z[:2], dts[:2], x0[:2], p0[:2], q, r, out[:2], o0[:2], nis[:2])
        tt = [[], [], []]
        for _ in range(repeats):
            a = time.perf_counter()
            k.run_batch_position(z, dts, x0, p0, q, r, out, o0, nis)
            b = time.perf_counter()
            run(z, dts, x0, p0, q, r, *arrs, True)
            c = time.perf_counter()
            run(z, dts, x0, p0, q, r, *arrs, False)
            d = time.perf_counter()
            for lst, v in zip(tt, (b - a, c - b, d - c)):
                lst.append(v)
        f, w, wo = (min(v) for v in tt)
        print(f"{name:<8} with the prediction stored: {w / f:.2f} filter steps; without: {wo / f:.2f}", flush=True)


if __name__ == "__main__":
    main(sys.argv[1:] or list(MODELS))
