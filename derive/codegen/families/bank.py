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

from ..blocks import arg_list
from ..printer import Kernel
from ..template import load

__all__ = ["bank_measurement_kernels", "bank_model_kernels", "kernels"]

MEAS_BANK_TEMPLATE = load("bank_measurement.py.tmpl")
MODEL_BANK_TEMPLATE = load("bank_model.py.tmpl")


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


def kernels(model, measurements: dict, built) -> list:
    """The family's entry (``derive.codegen.emitter``): (slot, kernel) pairs of one model module."""
    out = []
    for meas in measurements.values():
        out += [(("bank", meas.name), k) for k in bank_measurement_kernels(model, meas, built.sin_)]
    return out + [("bank_model", k) for k in bank_model_kernels(model)]
