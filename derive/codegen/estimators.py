"""Kernels for the estimators (``lgekf.estimators``): the innovation likelihood and the RTS smoother on the group.

Added to every model module by ``emitter.model_kernels`` (one call), generic in n, m and the noise inputs
like the rest of the emitter:

* ``innovation_logdet_<meas>(s, p, *r)``: log det S, S = ℋ P ℋᵀ + R (eq:K) at the predicted state, the
  term of the Gaussian innovation log-likelihood that the fused update's NIS does not give;
* ``run_one_store_<meas>`` / ``run_batch_store_<meas>``: the filter loop of ``run_one_<meas>``, keeping the
  predicted and the posterior internal states and packed covariances of every step, the NIS and log det S
  (what the backward pass and the likelihood need), through ``step_store_<meas>`` (the fused filter step
  writing its prediction, ``derive/codegen/smooth_step.py``);
* ``loglik_batch_<meas>``: Σ_k −½(log det S_k + e_kᵀ S_k⁻¹ e_k + m log 2π) per trajectory (prange), for
  maximum-likelihood noise learning (``lgekf.estimators.tuning``);
* ``smooth_one`` / ``smooth_batch``: the Rauch–Tung–Striebel backward pass on the group (derivation in
  ``lgekf.estimators.smoother``), one call of the straight-line ``smooth_step`` per step (F, Φ(d)⁻¹, Φ(δ)
  symbolic, unrolled LDLᵀ; ``derive/codegen/smooth_step.py``);
* the SIMD versions (trajectories in the vector lanes, as ``derive/codegen/soa.py`` for the filter):
  ``lane_store_<meas>`` / ``run_batch_store_soa_<meas>`` and ``lane_smooth`` / ``smooth_batch_soa``.
"""

from __future__ import annotations

import sympy as sp

from ..algebra import symbolize
from .blocks import arg_list
from .printer import Kernel
from .smooth_step import smooth_soa_kernels, smooth_step_kernel, store_soa_kernels, store_step_kernel

__all__ = ["estimator_kernels"]

STORE_TEMPLATE = '''
@nb.njit(cache=True)
def run_one_store_{meas}(z, dts, x0, p0, q, r, s_pred, p_pred, s_filt, p_filt, out_nis, out_logdet, out_x):
    """Filter one trajectory like run_one_{meas} and keep every step's predicted internal state and packed
    covariance (s_pred (K, {ni}), p_pred (K, {npk}), before the update) and posterior ones (s_filt, p_filt),
    the NIS and log det S of each update (both NaN for a missed detection: a NaN row of z predicts only) and
    the posterior physical states out_x (K, {n}). A step with a measurement is the fused step_store_{meas} (the
    filter's step_try_{meas} writing its prediction; derive/codegen/smooth_step.py), with the same Joseph-form
    fallback as run_one_{meas}."""
    s = state_from_physical(x0)
    p = p0.copy()
    K = z.shape[0]
    for k in range(K):
        if {nan_test}:
            predict(s, p, dts[k], {qargs})
            for i in range({ni}):
                s_pred[k, i] = s[i]
            for i in range({npk}):
                p_pred[k, i] = p[i]
            out_nis[k] = np.nan
            out_logdet[k] = np.nan
        else:
            nis, out_logdet[k] = step_store_{meas}(s, p, dts[k], {qargs}, {zargs}, {rargs}, s_pred[k], p_pred[k])
            if nis < 0.0:  # rare: the cheap covariance failed the LDLᵀ test; Joseph form from the prediction
                nis = update_{meas}(s, p, {zargs}, {rargs})
            out_nis[k] = nis
        for i in range({ni}):
            s_filt[k, i] = s[i]
        for i in range({npk}):
            p_filt[k, i] = p[i]
        physical_into(s, out_x[k])


@nb.njit(cache=True, parallel=True)
def run_batch_store_{meas}(z, dts, x0, p0, q, r, s_pred, p_pred, s_filt, p_filt, out_nis, out_logdet, out_x):
    """run_one_store_{meas} over B trajectories in parallel (prange); arrays as run_batch_{meas} with a
    leading batch axis (s_pred, s_filt (B, K, {ni}); p_pred, p_filt (B, K, {npk}); out_nis, out_logdet (B, K);
    out_x (B, K, {n}))."""
    for b in nb.prange(z.shape[0]):
        run_one_store_{meas}(z[b], dts[b], x0[b], p0[b], q, r, s_pred[b], p_pred[b], s_filt[b], p_filt[b], out_nis[b],
                             out_logdet[b], out_x[b])


@nb.njit(cache=True, parallel=True)
def loglik_batch_{meas}(z, dts, x0, p0, q, r, lengths, out_ll, out_count):
    """Innovation log-likelihood of each of B trajectories (prange): out_ll[b] = Σ_k −½(log det S_k + NIS_k +
    {m}·log 2π) over its first lengths[b] steps (the rest is padding), out_count[b] = its number of updates
    (NaN rows of z are missed detections: predicted, not counted). A diverged filter gives NaN."""
    for b in nb.prange(z.shape[0]):
        s = state_from_physical(x0[b])
        p = p0[b].copy()
        ll = 0.0
        cnt = 0
        for k in range(lengths[b]):
            predict(s, p, dts[b, k], {qargs})
            if not ({nan_test_b}):
                ld = innovation_logdet_{meas}(s, p, {rargs})
                nis = update_{meas}(s, p, {zargs_b}, {rargs})
                ll += -0.5 * (ld + nis + {m}.0 * 1.8378770664093453)
                cnt += 1
        out_ll[b] = ll
        out_count[b] = cnt
'''

SMOOTH_TEMPLATE = '''
@nb.njit(cache=True)
def smooth_one(dts, s_pred, p_pred, s_filt, p_filt, K, s_sm, p_sm):
    """Rauch–Tung–Striebel backward pass on the group over the first K steps (derivation:
    lgekf.estimators.smoother). dts (K,) step lengths (dts[k] led to step k); s_pred, p_pred / s_filt, p_filt:
    predicted / posterior internal states and packed covariances (run_one_store_*); writes the smoothed ones
    into s_sm (K, {ni}), p_sm (K, {npk}). For k = K-2 ... 0, with F = transition(μ_k, dts[k+1]):
    d = log(μ_{{k+1|k}}⁻¹ μˢ_{{k+1}}), P̄ = Φ(d)⁻¹ Pˢ_{{k+1}} Φ(d)⁻ᵀ, G = P_k Fᵀ P_{{k+1|k}}⁻¹, δ = G d,
    μˢ_k = μ_k·exp(δ), Pˢ_k = Φ(δ) [P_k + G (P̄ − P_{{k+1|k}}) Gᵀ] Φ(δ)ᵀ."""
    for i in range({ni}):
        s_sm[K - 1, i] = s_filt[K - 1, i]
    for i in range({npk}):
        p_sm[K - 1, i] = p_filt[K - 1, i]
    for k in range(K - 2, -1, -1):
        smooth_step(s_filt[k], p_filt[k], s_pred[k + 1], p_pred[k + 1], s_sm[k + 1], p_sm[k + 1], dts[k + 1], s_sm[k],
                    p_sm[k])


@nb.njit(cache=True, parallel=True)
def smooth_batch(dts, s_pred, p_pred, s_filt, p_filt, lengths, s_sm, p_sm, out_x):
    """smooth_one for B trajectories (prange), trajectory b over its first lengths[b] steps; also writes the
    smoothed physical states into out_x (B, K, {n})."""
    for b in nb.prange(dts.shape[0]):
        Kb = lengths[b]
        if Kb > 0:
            smooth_one(dts[b], s_pred[b], p_pred[b], s_filt[b], p_filt[b], Kb, s_sm[b], p_sm[b])
            for k in range(Kb):
                physical_into(s_sm[b, k], out_x[b, k])
'''


def _logdet_kernel(model, meas, P, pin, sin_):
    """log det(ℋ P ℋᵀ + R) at the predicted state: ℋ of eq:calH, R of the measurement definition."""
    H = model.calH_for(meas).applyfunc(model.to_internal)
    hdefs, Hs = symbolize(H, "hh")
    pdefs, HPs = symbolize(Hs * P, "hp")
    sdefs, Ss = symbolize(HPs * Hs.T + meas.R(), "S", only_upper=True)
    det = sp.Symbol("detS", real=True)
    r_params = list(meas.noise_names)
    return Kernel(
        name=f"innovation_logdet_{meas.name}",
        doc=(f"log det S, S = ℋ P ℋᵀ + R (eq:K) for a {meas.name} measurement at the predicted state (s, p),\n"
             "noise stds (" + ", ".join(r_params) + "): the log-determinant term of the innovation log-likelihood."),
        params=["s", "p", *r_params], inputs=sin_ + pin + list(zip(meas.noise_symbols, r_params)),
        stages=[hdefs, pdefs, sdefs, [(det, sp.expand(Ss.det()) if meas.m > 1 else Ss[0, 0])]],
        outputs=[], ret="math.log(detS)",
    )


def estimator_kernels(model, measurements: dict, P, pin, sin_, kernels=()) -> list:
    """The estimator kernels of one model (module docstring), for the measurements that fit it; ``kernels``: the
    model's kernels so far (the fused ``step_<meas>`` of each measurement, which the storing loop extends)."""
    n = model.n
    ni = len(model.internal)
    npk = n * (n + 1) // 2
    nq = len(model.noise_names)
    ks = []
    for meas in measurements.values():
        m = meas.m
        nr = len(meas.noise_names)
        ks.append(_logdet_kernel(model, meas, P, pin, sin_))
        store = store_step_kernel(model, next(k for k in kernels if getattr(k, "name", None) == f"step_try_{meas.name}"))
        ks.append(store)
        ks.extend(store_soa_kernels(model, meas, store))  # run_batch_store_soa_<meas>: the forward pass in SIMD lanes
        ks.append((f"run_one_store_{meas.name}", STORE_TEMPLATE.format(
            meas=meas.name, m=m, n=n, ni=ni, npk=npk, qargs=arg_list("q", nq), rargs=arg_list("r", nr),
            zargs=arg_list("z[k]", m).replace("z[k][", "z[k, "),
            zargs_b=arg_list("z[b, k]", m).replace("z[b, k][", "z[b, k, "),
            nan_test=" or ".join(f"np.isnan(z[k, {i}])" for i in range(m)),
            nan_test_b=" or ".join(f"np.isnan(z[b, k, {i}])" for i in range(m)),
        )))
    step = smooth_step_kernel(model)
    ks.append(step)
    physical = next(k for k in kernels if getattr(k, "name", None) == "physical_into")
    ks.extend(smooth_soa_kernels(model, step, physical))  # smooth_batch_soa: the backward pass in SIMD lanes
    ks.append(("smooth_one", SMOOTH_TEMPLATE.format(n=n, ni=ni, npk=npk)))
    return ks
