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
  maximum-likelihood noise learning (``lgekf.estimators.noise.tuning``);
* ``smooth_one`` / ``smooth_batch``: the Rauch–Tung–Striebel backward pass on the group (derivation in
  ``lgekf.estimators.smoother``), one call of the straight-line ``smooth_step`` per step (F, Φ(d)⁻¹, Φ(δ)
  symbolic, unrolled LDLᵀ; ``derive/codegen/smooth_step.py``);
* the SIMD versions (trajectories in the vector lanes, as ``derive/codegen/soa.py`` for the filter):
  ``lane_store_<meas>`` / ``run_batch_store_soa_<meas>`` and ``lane_smooth`` / ``smooth_batch_soa``.
"""

from __future__ import annotations

import sympy as sp

from ...algebra import symbolize
from ..blocks import arg_list, rows_variant
from ..printer import Kernel
from ..template import load
from .smooth_step import smooth_soa_kernels, smooth_step_kernel, store_soa_kernels, store_step_kernel

__all__ = ["estimator_kernels", "kernels"]

STORE_TEMPLATE = load("store.py.tmpl")
SMOOTH_TEMPLATE = load("smooth.py.tmpl")


#: measurement dimensions up to which det S is SymPy's expanded determinant (m = 2, 3: a few products); beyond, the
#: expansion takes SymPy minutes (m = 6: 160 s, a 3-D pose) and the kernel multiplies the pivots of an unrolled LDLᵀ
LDL_FROM = 3


def _ldl_determinant(S: sp.Matrix, det: sp.Symbol) -> list:
    """Stages computing det = Π d_j, the pivots of S = L D Lᵀ (S symmetric; one definition per stage, each reading the
    earlier ones)."""
    m = S.shape[0]
    d, L, stages = [], {}, []
    for j in range(m):
        dj = sp.Symbol(f"ld{j}", real=True)
        stages.append([(dj, S[j, j] - sum((L[j, k] ** 2 * d[k] for k in range(j)), sp.Integer(0)))])
        d.append(dj)
        for i in range(j + 1, m):
            lij = sp.Symbol(f"ll{i}_{j}", real=True)
            stages.append([(lij, (S[i, j] - sum((L[i, k] * L[j, k] * d[k] for k in range(j)), sp.Integer(0))) / dj)])
            L[i, j] = lij
    return stages + [[(det, sp.Mul(*d))]]


def _logdet_kernel(model, meas, P, pin, sin_):
    """log det(ℋ P ℋᵀ + R) at the predicted state: ℋ of eq:calH, R of the measurement definition."""
    H = model.calH_for(meas).applyfunc(model.to_internal)
    hdefs, Hs = symbolize(H, "hh")
    pdefs, HPs = symbolize(Hs * P, "hp")
    sdefs, Ss = symbolize(HPs * Hs.T + meas.R(), "S", only_upper=True)
    det = sp.Symbol("detS", real=True)
    if meas.m <= LDL_FROM:
        det_stages = [[(det, sp.expand(Ss.det()) if meas.m > 1 else Ss[0, 0])]]
    else:
        det_stages = _ldl_determinant(Ss, det)
    r_params = list(meas.noise_names)
    return Kernel(
        name=f"innovation_logdet_{meas.name}",
        doc=(f"log det S, S = ℋ P ℋᵀ + R (eq:K) for a {meas.name} measurement at the predicted state (s, p),\n"
             "noise stds (" + ", ".join(r_params) + "): the log-determinant term of the innovation log-likelihood."),
        params=["s", "p", *r_params], inputs=sin_ + pin + list(zip(meas.noise_symbols, r_params)),
        stages=[hdefs, pdefs, sdefs, *det_stages],
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
    step = smooth_step_kernel(model)  # emitted on rows (smooth_step_at) and in SIMD lanes (lane_smooth), not as itself
    ks.append(smooth_step_at_kernel(step))
    physical = next(k for k in kernels if getattr(k, "name", None) == "physical_into")
    ks.extend(smooth_soa_kernels(model, step, physical))  # smooth_batch_soa: the backward pass in SIMD lanes
    ks.append(("smooth_one", SMOOTH_TEMPLATE.format(n=n, ni=ni, npk=npk)))
    return ks


def smooth_step_at_kernel(step) -> "Kernel":
    """``smooth_step`` on the rows of the stored passes at step k (``smooth_one``'s loop): sf, pf = s_filt[k],
    p_filt[k]; sq, pq = s_pred[k+1], p_pred[k+1]; ss, ps = s_sm[k+1], p_sm[k+1]; writes so, po = s_sm[k], p_sm[k].
    The same straight-line code; no row views and fewer array arguments per step (numba counts a reference for
    each: about 11-25 % of the backward pass, measured on 2026-11-29)."""
    rows = {"sf": ("s_filt", "k", None), "pf": ("p_filt", "k", None), "sq": ("s_pred", "k + 1", None),
            "pq": ("p_pred", "k + 1", None), "ss": ("s_sm", "k + 1", None), "ps": ("p_sm", "k + 1", None),
            "so": ("s_sm", "k", None), "po": ("p_sm", "k", None)}
    return rows_variant(step, "smooth_step_at", ["s_filt", "p_filt", "s_pred", "p_pred", "s_sm", "p_sm", "k", "dt"], rows,
                        step.doc.rstrip() + "\nOn the rows of the stored passes at step k: sf = s_filt[k], pf = p_filt[k], "
                        "sq = s_pred[k + 1],\npq = p_pred[k + 1], ss = s_sm[k + 1], ps = p_sm[k + 1], so = s_sm[k], "
                        "po = p_sm[k] (derive/codegen/families/smoother.py).")


def kernels(model, measurements: dict, built) -> list:
    """The family's entry (``derive.codegen.emitter``): per measurement the likelihood and the storing forward pass
    (slot ``likelihood``), then the RTS smoother (slot ``smoother``)."""
    out = []
    smooth = {"smooth_step_at", "lane_smooth", "physical_smooth_lane", "smooth_batch_soa", "smooth_one"}
    for k in estimator_kernels(model, measurements, built.P, built.pin, built.sin_, built.ordered()):
        name = k.name if hasattr(k, "name") else k[0]
        if name in smooth:
            out.append(("smoother", k))
        else:
            meas = next(m for m in measurements.values() if name.endswith("_" + m.name))
            out.append((("likelihood", meas.name), k))
    return out
