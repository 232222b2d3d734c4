"""The fused step ``step_try_<meas>``: one prediction and one update in a single straight-line kernel.

The loops (``run_one_<meas>``) call it for every step with a measurement, so the state and the covariance stay in
registers between the prediction and the update (no store and reload through ``s``/``p``) and the compiler schedules
both together.  It is the same algebra as ``predict`` followed by ``update_<meas>`` (``derive.algebra``): the
predicted covariance and the predicted state entries become named intermediates (``pp..``, ``<name>_p``), the
angle-variance cap runs on them (``limit_angle_variance``'s rule, as literal code: it branches), and the update's
inputs are substituted by them.

Checked fallback.  The step writes the Joseph-form covariance as P − βKℋP (``derive.algebra``, form="symmetric":
about a third of the flops of the Joseph products), then runs the LDLᵀ test on the result. When it fails, the
step leaves the predicted state and covariance (from registers) in s and p and returns ``FALLBACK``; the loop then
runs ``update_<meas>`` exactly as the filter classes do: Joseph products, and the LDLᵀ test with its jitter repair
where Φ(ν) transports P.  Regular steps never fail the test, so they cost the cheaper form plus the test; the rare
steps that do are the old, proven update. ``step_<meas>`` is the two together.

Why the step returns instead of calling ``update_<meas>``: numba wraps a function that passes an array to a call,
or that can raise, in atomic reference-count increments and decrements of its array arguments (NRT_incref /
NRT_decref, ``lock`` instructions) at entry and exit; its pruning pass removes them only when nothing between them
calls out or raises. Measured with perf on the SE(2)×SE(2) loop (2026-11-24), those four locked instructions took
12 % of the run. So ``step_try_<meas>`` computes its results into numbers (``out_p<k>``, ``out_s<i>``), tests them
with ``covariance_is_pd_fused`` (inlined, the entries as arguments), stores them in one block and calls nothing that
is not inlined; it and the special functions it inlines (``sinc_family``, ``gain_damping``, ...) use
``error_model="numpy"``: a division by zero gives inf or NaN instead of raising, and a NaN covariance fails the test,
so such a step still ends in ``update_<meas>``, which raises as before. In the loop the counting is hoisted out.
The inlined test runs under the step's FMA contraction, whose rounding differs from the IEEE ``covariance_is_pd``:
on covariances conditioned beyond 1e16 the two can disagree (tests/core/test_covariance_health.py caught a CTRV step with
eigenvalue −1e-16 that passed the contracted test at the same tolerance), so the fused test asks for pivots 100×
larger (``PD_TOL_FUSED``, derive/codegen/emitter.py) and sends such borderline steps to the Joseph form. Measured
(``/tmp`` harness, CPU time, one trajectory of 2·10⁵ steps): the copy-and-retest alternative in the loop cost more
than the reference counting it saved.

Why not a cheaper screen: measured on tests/core/test_covariance_health.py (10⁵ steps, extreme settings), the symmetric
form alone leaves 85 % of the CTRV covariances and 0.2 % of the SE(2)×R³ ones indefinite (the Joseph form keeps them
positive definite: that is the accuracy it buys, in diverging filters with R ≪ ℋPℋᵀ), and a screen on the diagonal
(a variance shrunk by the update below 1e-6 of its prediction, or below PD_TOL × the largest) still missed 179
SE(2)×R³ steps: there the prediction itself was conditioned beyond 1e21, which no diagonal test sees.
"""

from __future__ import annotations

import sympy as sp

from ...algebra import LEGEND, lg_update, packed_index, sym_cov
from ..printer import Kernel, RawStage
from .model import fused_test_takes_numbers
from ..template import load

__all__ = ["fused_step_kernel", "step_wrapper", "angle_cap_lines", "fallback_lines", "FALLBACK", "kernels"]


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


STEP_TEMPLATE = load("step.py.tmpl")

#: what ``step_try_<meas>`` returns instead of the NIS (never negative) when the caller must redo the update
FALLBACK = -1.0


def fallback_lines(Pp: sp.Matrix, restore: list[tuple[int, str]]) -> list[str]:
    """The step's end: the LDLᵀ test of the new covariance ``out_p<k>``; if it fails, the prediction (``pp..``, and
    ``restore``: (state index, predicted value)) replaces the new values and the NIS becomes ``FALLBACK``; then one
    block stores them into p and s (module docstring)."""
    n = Pp.shape[0]
    npk = n * (n + 1) // 2
    idx = packed_index(n)
    if not fused_test_takes_numbers(n):  # too many entries for one call (model.CALL_ARGS_LIMIT): store, then test p
        lines = [f"p[{k}] = out_p{k}" for k in range(npk)]
        lines += ["if not covariance_is_pd_fused(p):"]
        lines += [f"    p[{idx[(i, j)]}] = {Pp[i, j].name}" for i in range(n) for j in range(i, n)]
        lines += [f"    out_s{i} = {v}" for i, v in restore]
        lines += [f"    nis = {FALLBACK!r}"]
        return lines + [f"s[{i}] = out_s{i}" for i, _ in restore]
    lines = [f"if not covariance_is_pd_fused({', '.join(f'out_p{k}' for k in range(npk))}):"]
    lines += [f"    out_p{idx[(i, j)]} = {Pp[i, j].name}" for i in range(n) for j in range(i, n)]
    lines += [f"    out_s{i} = {v}" for i, v in restore]
    lines += [f"    nis = {FALLBACK!r}"]
    lines += [f"p[{k}] = out_p{k}" for k in range(npk)]
    return lines + [f"s[{i}] = out_s{i}" for i, _ in restore]


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
    outputs = [(f"out_p{idx[(i, j)]}", sp.sympify(Pu[i, j]).xreplace(rep)) for i in range(n) for j in range(i, n)]
    for i in sorted(set(pouts) | set(uouts)):
        outputs.append((f"out_s{i}", sp.sympify(uouts[i]).xreplace(rep) if i in uouts else pred_state[i]))
    sig = model.noise_symbols
    z_params = [f"z_{nm}" for nm in meas.z_names]
    r_params = list(meas.noise_names)
    # the fallback: the predicted state (registers) replaces the new one; the loop then runs update_<meas>
    written = sorted(set(pouts) | set(uouts))
    restore = [(i, pred_state[i].name if i in pouts else model.internal[i].name) for i in written]
    stages.insert(0, RawStage([], tuple(model.internal[i] for i in written if i not in pouts)))
    return Kernel(
        name=f"step_try_{meas.name}",
        doc=(f"One fused LG-EKF step with a {meas.name} measurement, in place: ``predict`` then ``update_{meas.name}``\n"
             "(eq:pred_mu, eq:pred_cov, angle-variance cap, eq:K, eq:up_mu, eq:up_P) in one kernel; returns the NIS.\n"
             + "Covariance as P − βKℋP; a step whose result fails the LDLᵀ test (covariance_is_pd_fused) leaves the\n"
             + f"prediction in s, p and returns {FALLBACK!r}: the caller then runs update_{meas.name} (Joseph form;\n"
             + "derive/codegen/fused.py).\n"
             + LEGEND),
        params=["s", "p", "dt", *model.noise_names, *z_params, *r_params],
        inputs=sin_ + pin + [(dt, "dt")] + list(zip(sig, model.noise_names)) + list(zip(z, z_params)) + list(zip(noise, r_params)),
        stages=stages, outputs=outputs, ret="nis", epilogue=fallback_lines(Pp, restore), fastmath=True, error_model="numpy",
    )


def step_wrapper(model, meas) -> tuple[str, str]:
    """``step_<meas>(s, p, dt, *q, *z, *r) -> nis``: ``step_try_<meas>`` with its fallback (module docstring)."""
    z_params = [f"z_{nm}" for nm in meas.z_names]
    params = ["s", "p", "dt", *model.noise_names, *z_params, *meas.noise_names]
    return (f"step_{meas.name}", STEP_TEMPLATE.format(meas=meas.name, params=", ".join(params),
                                                      qargs=", ".join(model.noise_names),
                                                      update_args=", ".join(["s", "p", *z_params, *meas.noise_names])))


def kernels(model, measurements: dict, built) -> list:
    """The family's entry (``derive.codegen.emitter``): ``step_try_<meas>`` and ``step_<meas>`` of each measurement."""
    out = []
    for meas in measurements.values():
        step = fused_step_kernel(model, meas, built.P, built.pin, built.sin_, built.predict_parts, sp.Symbol("dt", positive=True))
        out += [(("step", meas.name), step), (("step", meas.name), step_wrapper(model, meas))]
    return out
