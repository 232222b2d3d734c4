"""Does an EM in the tangent space around the smoothed trajectory increase the likelihood of the LG models?

The experiment behind the refusal of ``lgekf.estimators.noise.em.learn_noise_em`` for the non-linear models. For every
registry model (generically: only its generated kernels), on simulated SE(2)×SE(2) motion with position
measurements, it runs the *approximate* EM that one would write: E-step = the RTS smoother on the group
(``forward_store``, ``smooth_stored``); the process residual of step k is ē_k = between(motion(μˢ_{k-1}), μˢ_k) in the
tangent at the predicted mean, its covariance Pˢ_k + F Pˢ_{k-1} Fᵀ − Pˢ_k Jᵀ Fᵀ − F J Pˢ_k with F and the noise
shapes Q_i = process_noise(μˢ_{k-1}, dt, e_i) at the smoothed state, J the filter's smoother gain (the frames of
the filtered and smoothed means are not distinguished: the approximation); the measurement residual is the
innovation at μˢ_k with ℋ Pˢ_k ℋᵀ; M-step the closed forms of ``lgekf.estimators.noise.em`` (the transition from the
start and the start's dependence on r are left out). After every iteration it evaluates the exact objective of
``learn_noise`` (the innovation log-likelihood, ``log_likelihood``) and prints how often it went down, where it
ended, and the L-BFGS maximum for comparison.

Usage: .venv/bin/python benchmarks/em_lie_groups.py [iterations [model ...]]   (default 40, all models; about a
minute per model and 40 iterations)
"""

from __future__ import annotations

import sys

import numpy as np

from lgekf.core.covariance import pack, unpack
from lgekf.core.registry import MODELS
from lgekf.core.rts import forward_store, smooth_stored
from lgekf.estimators.noise.tracks import batch_tracks, two_point_prior
from lgekf.estimators.noise.tuning import learn_noise, log_likelihood
from lgekf.experiments.simulate import simulate


def approximate_em_step(spec, batch, x0, prior, q, r):
    """One tangent-space EM iteration (module docstring): the new (q, r)."""
    K = spec.kernels
    n = spec.n
    nq = len(spec.noise_names)
    P0 = prior(r[0])
    fp = forward_store(spec, "position", batch.z, batch.dts, x0, pack(P0), q, r, simd=False)
    fp.lengths = np.ascontiguousarray(batch.lengths, dtype=np.int64)
    _, s_sm, p_sm = smooth_stored(spec, fp)
    s_pred, p_pred, s_filt, p_filt = fp.states()
    ranks = np.array([list(spec.noise_inputs).count(i) for i in range(nq)])
    Enn = np.zeros(nq)
    cnt = 0
    Vsum = 0.0
    nv = 0
    out = np.empty(2)
    for b in range(batch.z.shape[0]):
        L = int(batch.lengths[b])
        for k in range(L):
            Ps = unpack(p_sm[b, k], n)
            z = batch.z[b, k]
            if not np.any(np.isnan(z)):
                K.innovation_into_position(s_sm[b, k], z[0], z[1], out)
                H = K.calH_position(s_sm[b, k])
                Vsum += float(out @ out + np.trace(H @ Ps @ H.T))
                nv += 2
            if k == 0:
                continue
            sp_ = s_sm[b, k - 1]
            dt = batch.dts[b, k]
            F = K.transition(sp_, dt)
            e = K.between(K.motion(sp_, dt), s_sm[b, k])
            Pf = unpack(p_filt[b, k - 1], n)
            Pp = unpack(p_pred[b, k], n)
            J = np.linalg.solve(Pp, F @ Pf).T
            Psp = unpack(p_sm[b, k - 1], n)
            C = Ps @ J.T
            M = np.outer(e, e) + Ps + F @ Psp @ F.T - F @ C.T - C @ F.T
            cols = []
            for i in range(nq):
                qi = np.zeros(nq)
                qi[i] = 1.0
                w, V = np.linalg.eigh(K.process_noise(sp_, dt, *qi))
                cols.append(V[:, -ranks[i]:] * np.sqrt(np.maximum(w[-ranks[i]:], 1e-300)))
            Gp = np.linalg.pinv(np.concatenate(cols, axis=1))
            d = np.diag(Gp @ M @ Gp.T)
            j = 0
            for i in range(nq):
                Enn[i] += d[j:j + ranks[i]].sum()
                j += ranks[i]
            cnt += 1
    return Enn / (ranks * cnt), np.array([np.sqrt(Vsum / nv)])


def main() -> None:
    iters = int(sys.argv[1]) if len(sys.argv) > 1 else 40
    only = sys.argv[2:] or list(MODELS)
    rng = np.random.default_rng(7)
    B = 12
    sim = simulate(np.tile([0, 0, 0, 3.0, 0, 0], (B, 1)), dt=0.1, steps=100, sigma_v=0.5, sigma_w=0.2, meas_std=0.2, rng=rng)
    t = sim.dt * np.arange(sim.z.shape[1])
    tracks = [(t, zb) for zb in sim.z]
    batch = batch_tracks(tracks, 2, None, 1.0)
    print(f"truth SE(2)xSE(2): sigma_v 0.5, sigma_w 0.2, r 0.2; {B} tracks x 100 steps of 0.1 s; {iters} iterations")
    for name, spec in MODELS.items():
        if "position" not in spec.measurements or name not in only:
            continue
        x0, prior = two_point_prior(spec, batch, None)
        q = np.asarray(spec.default_accel_std, dtype=float) * 2.0
        r = np.array([0.5])
        lls = [log_likelihood(name, batch, q, r)]
        broke = ""
        for it in range(iters):
            var, r = approximate_em_step(spec, batch, x0, prior, q, r)
            if np.any(var <= 0):  # the approximate E[n²] is not a second moment any more
                broke = f"; stopped at iteration {it + 1}: approximate E[n²] of {np.array(spec.noise_names)[var <= 0].tolist()} ≤ 0"
                break
            q = np.sqrt(var)
            lls.append(log_likelihood(name, batch, q, r))
        lls = np.array(lls)
        drops = np.diff(lls) < -1e-6 * (1 + np.abs(lls[1:]))
        ref = learn_noise(name, batch, n_starts=1, hessian=False)
        print(f"{name}: log L {lls[0]:.2f} -> {lls[-1]:.2f} (max along the way {np.nanmax(lls):.2f}, "
              f"{int(drops.sum())} decreases in {len(lls) - 1} iterations{broke}); L-BFGS maximum {ref.loglik:.2f}; "
              f"approx. EM stds {np.round(np.concatenate([q, r]), 4).tolist()} vs L-BFGS {np.round(ref.values, 4).tolist()}")


if __name__ == "__main__":
    main()
