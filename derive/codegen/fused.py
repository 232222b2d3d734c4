"""The fused step ``step_<meas>``: one prediction and one update in a single straight-line kernel.

The loops (``run_one_<meas>``) call it for every step with a measurement, so the state and the covariance stay in
registers between the prediction and the update (no store and reload through ``s``/``p``) and the compiler schedules
both together.  It is the same algebra as ``predict`` followed by ``update_<meas>`` (``derive.algebra``): the
predicted covariance and the predicted state entries become named intermediates (``pp..``, ``<name>_p``), the
angle-variance cap runs on them (``limit_angle_variance``'s rule, as literal code: it branches), and the update's
inputs are substituted by them.

Checked fallback.  The step writes the Joseph-form covariance as P − βKℋP (``derive.algebra``, form="symmetric":
about a third of the flops of the Joseph products), then runs the LDLᵀ test ``covariance_is_pd`` on the result.
When it fails, the predicted state and covariance are restored from registers and ``update_<meas>`` redoes the
update exactly as the filter classes do: Joseph products, and the LDLᵀ test with its jitter repair where Φ(ν)
transports P.  Regular steps never fail the test, so they cost the cheaper form plus the test; the rare steps that
do are the old, proven update.

Why not a cheaper screen: measured on tests/test_covariance_health.py (10⁵ steps, extreme settings), the symmetric
form alone leaves 85 % of the CTRV covariances and 0.2 % of the SE(2)×R³ ones indefinite (the Joseph form keeps them
positive definite: that is the accuracy it buys, in diverging filters with R ≪ ℋPℋᵀ), and a screen on the diagonal
(a variance shrunk by the update below 1e-6 of its prediction, or below PD_TOL × the largest) still missed 179
SE(2)×R³ steps: there the prediction itself was conditioned beyond 1e21, which no diagonal test sees.
"""

from __future__ import annotations

import sympy as sp

from ..algebra import LEGEND, lg_update, packed_index, sym_cov
from .printer import Kernel, RawStage

__all__ = ["fused_step_kernel", "angle_cap_lines", "fallback_lines"]

def angle_cap_lines(Pp: sp.Matrix, angles: tuple) -> list[str]:
    """``limit_angle_variance`` on named covariance entries: cap the std of each angle coordinate at π."""
    n = Pp.shape[0]
    lines = []
    for a in angles:
        d = Pp[a, a].name
        lines.append(f"if {d} > math.pi * math.pi:")
        lines.append(f"    _cap = math.pi / math.sqrt({d})")
        for j in range(n):
            if j != a:
                e = Pp[min(a, j), max(a, j)].name
                lines.append(f"    {e} = {e} * _cap")
        lines.append(f"    {d} = math.pi * math.pi")
    return lines


def fallback_lines(Pp: sp.Matrix, restore: list[tuple[str, str]], call: str) -> list[str]:
    """If the posterior fails the LDLᵀ test: restore the prediction and ``nis = call`` (see the module docstring)."""
    n = Pp.shape[0]
    idx = packed_index(n)
    lines = ["if not covariance_is_pd(p):"]
    lines += [f"    p[{idx[(i, j)]}] = {Pp[i, j].name}" for i in range(n) for j in range(i, n)]
    lines += [f"    {t} = {v}" for t, v in restore]
    return lines + [f"    nis = {call}"]


def fused_step_kernel(model, meas, P, pin, sin_, predict_parts, dt) -> Kernel:
    """``step_<meas>(s, p, dt, *q, *z, *r) -> nis``: predict then update, in place (see the module docstring)."""
    n = model.n
    pstages, pouts, Pn = predict_parts
    Pp, _ = sym_cov(n, "pp")
    pred_state = {i: sp.Symbol(f"{model.internal[i].name}_p", real=True) for i in pouts}
    pred_defs = [(Pp[i, j], Pn[i, j]) for i in range(n) for j in range(i, n)] + [(pred_state[i], e) for i, e in pouts.items()]
    stages = list(pstages) + [pred_defs]
    periodic = model.periodic_tangent()
    if periodic:
        uses = tuple({Pp[min(a, j), max(a, j)] for a in periodic for j in range(n)})
        stages.append(RawStage(angle_cap_lines(Pp, periodic), tuple(sorted(uses, key=lambda s: s.name))))
    z, noise = meas.z_symbols, meas.noise_symbols
    ustages, uouts, Pu, _, _ = lg_update(model, meas, P, z, noise, form="symmetric")
    rep = {P[i, j]: Pp[i, j] for i in range(n) for j in range(n)}
    rep.update({model.internal[i]: s for i, s in pred_state.items()})
    stages += [[(s, sp.sympify(e).xreplace(rep)) for s, e in st] for st in ustages]
    idx = packed_index(n)
    outputs = [(f"p[{idx[(i, j)]}]", sp.sympify(Pu[i, j]).xreplace(rep)) for i in range(n) for j in range(i, n)]
    for i in sorted(set(pouts) | set(uouts)):
        outputs.append((f"s[{i}]", sp.sympify(uouts[i]).xreplace(rep) if i in uouts else pred_state[i]))
    sig = model.noise_symbols
    z_params = [f"z_{nm}" for nm in meas.z_names]
    r_params = list(meas.noise_names)
    # the fallback: restore the predicted state (registers) and redo the update with update_<meas>
    written = sorted(set(pouts) | set(uouts))
    restore = [(f"s[{i}]", pred_state[i].name if i in pouts else model.internal[i].name) for i in written]
    stages.insert(0, RawStage([], tuple(model.internal[i] for i in written if i not in pouts)))
    epilogue = fallback_lines(Pp, restore, f"update_{meas.name}(s, p, {', '.join(z_params + r_params)})")
    return Kernel(
        name=f"step_{meas.name}",
        doc=(f"One fused LG-EKF step with a {meas.name} measurement, in place: ``predict`` then ``update_{meas.name}``\n"
             "(eq:pred_mu, eq:pred_cov, angle-variance cap, eq:K, eq:up_mu, eq:up_P) in one kernel; returns the NIS.\n"
             + "Covariance as P − βKℋP; a step whose result fails the LDLᵀ test is redone by update_" + meas.name
             + " (Joseph form; derive/codegen/fused.py).\n"
             + LEGEND),
        params=["s", "p", "dt", *model.noise_names, *z_params, *r_params],
        inputs=sin_ + pin + [(dt, "dt")] + list(zip(sig, model.noise_names)) + list(zip(z, z_params)) + list(zip(noise, r_params)),
        stages=stages, outputs=outputs, ret="nis", epilogue=epilogue, fastmath=True,
    )
