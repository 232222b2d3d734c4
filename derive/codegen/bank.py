"""Kernels over a *bank* of filters (one row per track), for multi-target tracking (lgekf.estimators).

Each model module gets, per measurement that fits it, the measurement's innovation written into a
caller's array and the loops a tracker runs once per scan over all its tracks (no Python per track):

* ``innovation_into_<meas>(s, z.., out)``: e = [log_G'(h(μ)⁻¹ Z)]^∨ (eq:K's innovation) into ``out``;
* ``innovation_bank_<meas>(s, live, z, out)``: e for every live track i and detection j, out (N, M, m);
* ``calH_bank_<meas>(s, live, out)``: ℋ (eq:calH) of every live track, out (N, m, n);

and per model: ``predict_bank(s, p, live, dt, q)`` (the fused predict of every live track),
``retract_bank(s, live, eps)`` (μ ← μ·exp(ε), eq:up_mu with a given ε) and
``right_jacobian_bank(live, eps, out)`` (Φ(ε), eq:up_P), which the runtime's association updates
(PDA/JPDA: a combined correction ε per track) use. Only the model's own kernels are called: nothing
here knows a model.
"""

from __future__ import annotations

import sympy as sp

from .blocks import arg_list
from .printer import Kernel

__all__ = ["bank_measurement_kernels", "bank_model_kernels"]

MEAS_BANK_TEMPLATE = '''
@nb.njit(cache=True)
def innovation_bank_{meas}(s, live, z, out):
    """Innovation [log_G'(h(μ_i)⁻¹ Z_j)]^∨ of every live track i (rows of s, live[i] true) and every
    {meas} detection j (rows of z, (M, {m})) into out (N, M, {m}); rows of dead tracks are not written."""
    for i in range(s.shape[0]):
        if live[i]:
            si = s[i]
            for j in range(z.shape[0]):
                innovation_into_{meas}(si, {zargs}, out[i, j])


@nb.njit(cache=True)
def calH_bank_{meas}(s, live, out):
    """ℋ (eq:calH) of every live track for {meas} measurements into out (N, {m}, {n})."""
    for i in range(s.shape[0]):
        if live[i]:
            h = calH_{meas}(s[i])
            for a in range({m}):
                for b in range({n}):
                    out[i, a, b] = h[a, b]
'''

MODEL_BANK_TEMPLATE = '''
@nb.njit(cache=True)
def predict_bank(s, p, live, dt, q):
    """The fused prediction (eq:pred_mu, eq:pred_cov) of every live track (rows of s and p) by dt, in place;
    q ({nq},) process-noise stds."""
    for i in range(s.shape[0]):
        if live[i]:
            predict(s[i], p[i], dt, {qargs})


@nb.njit(cache=True)
def retract_bank(s, live, eps):
    """μ_i ← μ_i·exp([ε_i]^∧) for every live track (eq:up_mu with the given corrections eps (N, {n}))."""
    for i in range(s.shape[0]):
        if live[i]:
            retract(s[i], eps[i])


@nb.njit(cache=True)
def right_jacobian_bank(live, eps, out):
    """Φ_G(ε_i) (eq:up_P) of every live track's correction eps (N, {n}) into out (N, {n}, {n})."""
    for i in range(eps.shape[0]):
        if live[i]:
            f = right_jacobian(eps[i])
            for a in range({n}):
                for b in range({n}):
                    out[i, a, b] = f[a, b]
'''


def bank_measurement_kernels(model, meas, sin_) -> list:
    """``innovation_into_<meas>`` and the bank loops of one model × measurement."""
    sub = model.to_internal
    mu = model.mean().applyfunc(sub)
    z = meas.z_symbols
    z_params = [f"z_{nm}" for nm in meas.z_names]
    Gp = meas.group
    innov = Gp.log(Gp.inverse(meas.h(model, mu)) * meas.element(z)).applyfunc(sub)
    inn = Kernel(
        name=f"innovation_into_{meas.name}",
        doc=f"The {meas.name} innovation e = [log_G'(h(μ)⁻¹ Z)]^∨ (eq:K) of the state s for the measured z, written into out ({meas.m},).",
        params=["s", *z_params, "out"], inputs=sin_ + list(zip(z, z_params)),
        outputs=[(f"out[{i}]", sp.sympify(e)) for i, e in enumerate(innov)],
    )
    loops = (f"innovation_bank_{meas.name}", MEAS_BANK_TEMPLATE.format(
        meas=meas.name, m=meas.m, n=model.n, zargs=arg_list("z[j]", meas.m).replace("z[j][", "z[j, ")))
    return [inn, loops]


def bank_model_kernels(model) -> list:
    """``predict_bank``, ``retract_bank``, ``right_jacobian_bank`` of one model."""
    nq = len(model.noise_names)
    return [("predict_bank", MODEL_BANK_TEMPLATE.format(n=model.n, nq=nq, qargs=arg_list("q", nq)))]
