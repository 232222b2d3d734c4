"""The model family: a motion model's own quantities and steps, from its definition (``derive.models``) and the
measurements that fit it (``derive.measurements``); nothing here knows a model by name or by dimension.

* conversions: ``state_from_physical``, ``state_to_physical``, ``physical_into``, ``group_mean``, ``common_to_state``,
  ``common_jacobian``, ``world_velocity``, ``world_velocity_into``, ``tangent_error``;
* the paper's quantities: ``motion_omega`` (Ω), ``motion``, ``calC`` (𝒞), ``transition`` (F), ``process_noise`` (Q),
  ``calH_<meas>`` (ℋ);
* the steps: ``predict`` and ``update_<meas>`` (CSE over each whole step), safeguards ``limit_angle_variance``,
  ``covariance_is_pd``, ``covariance_is_pd_fused``, ``repair_pd``;
* simulation: ``propagate`` (the exact motion), ``position_into``, ``measure_<meas>`` (Z = h(X)·exp(m)).

The loops over rows that call them are the filter family (``families/filter.py``); the fused step the fused family.
"""

from __future__ import annotations

import sympy as sp

from ...algebra import LEGEND, lg_predict, lg_update, packed_index, symbolize
from ..blocks import cov_outputs, matrix_kernel, vec_inputs, vector_kernel
from ..printer import Kernel
from ..template import load

_WORDS = {2: "two", 3: "three"}

__all__ = ["PD_TOL", "PD_TOL_FUSED", "pd_check_kernels", "angle_limit_kernel", "kernels"]


# --------------------------------------------------------------------------- safeguards
PD_TOL = 1e-13  # LDLᵀ pivot / largest variance below which a covariance counts as lost to rounding
# the same test inlined into the fused steps runs under their FMA contraction, whose rounding differs from the IEEE
# test's; it asks for 100× larger pivots, so that it accepts no covariance that covariance_is_pd rejects (measured on
# tests/core/test_covariance_health.py; derive/codegen/fused.py)
PD_TOL_FUSED = 1e-11


#: CPython compiles a call with more positional arguments than this as f(*args) (its STACK_USE_GUIDELINE), which numba
#: cannot inline: a covariance with more packed entries is tested as an array (``fused_test_takes_numbers``)
CALL_ARGS_LIMIT = 30


def fused_test_takes_numbers(n: int) -> bool:
    """Whether ``covariance_is_pd_fused`` takes the n(n+1)/2 entries as numbers (else the packed array)."""
    return n * (n + 1) // 2 <= CALL_ARGS_LIMIT


def pd_check_kernels(n: int):
    """``covariance_is_pd(p)`` and ``repair_pd(p)`` for a packed n×n covariance (scalar-unrolled LDLᵀ).

    At condition numbers beyond ~1e13 rounding alone can make the smallest eigenvalue of
    Φ(ν) P_J Φ(ν)ᵀ negative.  ``covariance_is_pd`` runs LDLᵀ and requires every pivot
    d_j > PD_TOL · max_i P_ii; ``repair_pd`` adds the smallest diagonal jitter (PD_TOL · max_i P_ii,
    growing ×4) that passes.  Regular steps never trigger it.
    """
    idx = packed_index(n)
    lines = ["@nb.njit(cache=True)", "def covariance_is_pd(p):",
             f'    """LDLᵀ test of the packed covariance: every pivot d_j > {PD_TOL!r} · max_i P_ii (NaN fails)."""']
    for i in range(n):
        for j in range(i, n):
            lines.append(f"    p{i}_{j} = p[{idx[(i, j)]}]")
    lines.append(f"    tol = {PD_TOL!r} * max({', '.join(f'p{j}_{j}' for j in range(n))})")
    for j in range(n):
        terms = "".join(f" - l{j}_{k} * l{j}_{k} * d{k}" for k in range(j))
        lines.append(f"    d{j} = p{j}_{j}{terms}")
        lines.append(f"    if not d{j} > tol:")
        lines.append("        return False")
        if j < n - 1:
            lines.append(f"    r{j} = 1.0 / d{j}")
        for i in range(j + 1, n):
            terms = "".join(f" - l{i}_{k} * l{j}_{k} * d{k}" for k in range(j))
            lines.append(f"    l{i}_{j} = (p{j}_{i}{terms}) * r{j}")
    lines.append("    return True")
    diag = [idx[(j, j)] for j in range(n)]
    repair = load("repair_pd.py.tmpl").format(tol=repr(PD_TOL), diag=repr(tuple(diag)))
    names = [f"p{i}_{j}" for i in range(n) for j in range(i, n)]
    tight = [ln.replace(f"{PD_TOL!r} * max(", f"{PD_TOL_FUSED!r} * max(") for ln in lines[3:]]
    if fused_test_takes_numbers(n):
        fused = ['@nb.njit(cache=True, inline="always", error_model="numpy")',
                 f"def covariance_is_pd_fused({', '.join(names)}):",
                 f'    """covariance_is_pd of the entries p<i>_<j> (upper triangle, row-major) as numbers, inlined into the fused\n'
                 f'    steps (derive/codegen/fused.py), with pivots > {PD_TOL_FUSED!r} · max_i P_ii."""'] + tight[len(names):]
    else:
        fused = ['@nb.njit(cache=True, inline="always", error_model="numpy")',
                 "def covariance_is_pd_fused(p):",
                 f'    """covariance_is_pd of the packed covariance p, inlined into the fused steps (derive/codegen/fused.py), with\n'
                 f'    pivots > {PD_TOL_FUSED!r} · max_i P_ii (its {len(names)} entries are too many for a call with one argument each)."""'] + tight
    return [("covariance_is_pd", "\n".join(lines)), ("covariance_is_pd_fused", "\n".join(fused)), ("repair_pd", repair)]


def angle_limit_kernel(n: int, angles: tuple):
    """``limit_angle_variance(p)``: cap the std of the periodic tangent coordinates at π (congruence scaling).

    A concentrated Gaussian is only meaningful where exp is bijective, |ε_θ| < π (paper, Sec. II-B); an
    angle std beyond π says "heading unknown", which the CGD cannot express.  With position-only
    measurements the heading and the direction of the body-frame velocity are observable only as a sum,
    so that variance can otherwise grow without bound.  P ← D P D, D = diag(1, ..., π/σ_θ, ...), keeps P
    symmetric positive definite.  Inactive while σ_θ ≤ π, i.e. in every regular step.
    """
    idx = packed_index(n)
    lines = ["@nb.njit(cache=True)", "def limit_angle_variance(p):",
             '    """Cap the std of the angle coordinates ' + str(list(angles)) + ' of P at π by congruence scaling (see derive/codegen/emitter.py)."""']
    for a in angles:
        d = idx[(a, a)]
        lines.append(f"    if p[{d}] > math.pi * math.pi:")
        lines.append(f"        f = math.pi / math.sqrt(p[{d}])")
        for j in range(n):
            if j != a:
                lines.append(f"        p[{idx[(a, j)]}] *= f")
        lines.append(f"        p[{d}] = math.pi * math.pi")
    if not angles:
        lines.append("    return")
    return ("limit_angle_variance", "\n".join(lines))


# --------------------------------------------------------------------------- one model
def _measurement_kernels(model, meas, P, pin, sin_):
    """``calH_<meas>`` and ``update_<meas>`` (slot ``update``), ``measure_<meas>`` (slot ``measure``)."""
    m = meas.m
    z = meas.z_symbols
    noise = meas.noise_symbols
    stages, outs, Pu, nis, transported = lg_update(model, meas, P, z, noise)
    z_params = [f"z_{nm}" for nm in meas.z_names]
    r_params = list(meas.noise_names)
    doc = (
        f"Fused update with a {meas.name} measurement ({meas.description}), in place.\n"
        f"z = ({', '.join(z_params)}), noise stds ({', '.join(r_params)}); Z = h(μ)·exp(m), m ~ N(0, R) in the tangent of G'.\n"
        "K = P ℋ^T (ℋ P ℋ^T + R)^-1, ν = K [log_G'(h(μ)^-1 Z)]^∨ (eq:K), μ ← μ exp(ν) (eq:up_mu),\n"
        "P ← Φ(ν) [(I - Kℋ) P (I - Kℋ)^T + K R K^T] Φ(ν)^T: eq:up_P in Joseph form. Returns the NIS e^T S^-1 e.\n"
    )
    if model.periodic_tangent():
        doc += ("Safeguard: if a rotation angle of ν exceeds π the gain is damped, K → αK, α = π/|angle|\n"
                "(derive.lie.special.gain_damping; α = 1 in every regular step).\n")
    if transported:
        doc += "If rounding leaves P not positive definite (condition numbers ≳ 1e15) a rounding-level jitter restores it (repair_pd).\n"
    doc += LEGEND
    outputs = cov_outputs(Pu) + [(f"s[{i}]", e) for i, e in outs.items()]
    upd = Kernel(
        name=f"update_{meas.name}", doc=doc, params=["s", "p", *z_params, *r_params],
        inputs=sin_ + pin + list(zip(z, z_params)) + list(zip(noise, r_params)),
        stages=stages, outputs=outputs, ret="nis",
        epilogue=["if not covariance_is_pd(p):", "    repair_pd(p)"] if transported else [],
        fastmath=True,
    )
    sub = model.to_internal
    calH = matrix_kernel(
        f"calH_{meas.name}", f"ℋ = ∂[log_G'(h(μ)^-1 h(μ exp ε))]^∨/∂ε at ε = 0 (eq:calH, eq:calH_model) for {meas.name} measurements.",
        ["s"], sin_, model.calH_for(meas).applyfunc(sub),
    )
    ms = sp.symbols(f"m0:{m}", real=True)
    Z = meas.h(model, model.mean()) * meas.group.exp(list(ms))
    measure = vector_kernel(
        f"measure_{meas.name}", f"Simulated {meas.name} measurement vector(h(X)·exp(m)) of the state s for a noise sample m.",
        ["s", *[f"m{i}" for i in range(m)]], sin_ + [(mi, f"m{i}") for i, mi in enumerate(ms)],
        [sub(e) for e in meas.vector(Z)],
    )
    return [(("update", meas.name), calH), (("update", meas.name), upd), (("measure", meas.name), measure)]


def kernels(model, measurements: dict, built) -> list:
    """The family's entry (``derive.codegen.emitter``): (slot, kernel) pairs of one model module. Leaves the prediction's
    stages on ``built.predict_parts`` for the fused step (``families/fused.py``)."""
    n = model.n
    sub = model.to_internal
    dt = sp.Symbol("dt", positive=True)
    sig = model.noise_symbols
    sin_ = built.sin_
    phys_in = vec_inputs("xp", model.physical)
    P, pin = built.P, built.pin
    layout = "[" + ", ".join(str(v) for v in model.internal) + "]"
    phys = "[" + ", ".join(model.physical_names) + "]"
    ks = [
        vector_kernel("state_from_physical", f"Internal state {layout} from the physical {phys}.", ["xp"], phys_in,
                      model.internal_from_physical()),
        vector_kernel("state_to_physical", f"Physical {phys} (angles in (-π, π]) from the internal state.", ["s"], sin_,
                      model.physical_from_internal()),
        Kernel(name="physical_into", doc=f"Physical {phys} from the internal state, written into ``out`` (no allocation).",
               params=["s", "out"], inputs=sin_, outputs=[(f"out[{i}]", e) for i, e in enumerate(model.physical_from_internal())]),
        matrix_kernel("group_mean", "The mean μ as a group matrix (block-diagonal for a product group).", ["s"], sin_,
                      model.mean().applyfunc(sub)),
        vector_kernel("motion_omega", "Ω(μ), the tangent increment of one step (eq:motionG).", ["s", "dt"], sin_ + [(dt, "dt")],
                      model.Omega.applyfunc(sub)),
        vector_kernel("motion", "The internal state after one noise-free step, μ exp(Ω(μ)) (eq:pred_mu); x' = f(x) for a Euclidean model.",
                      ["s", "dt"], sin_ + [(dt, "dt")],
                      [sub(e) for e in model.internal_of(model.mean().applyfunc(sub) * model.group.exp(model.Omega.applyfunc(sub)))]),
        matrix_kernel("calC", "𝒞 = ∂Ω(μ exp ε)/∂ε at ε = 0 (eq:C, eq:calCFinal).", ["s", "dt"], sin_ + [(dt, "dt")],
                      model.calC.applyfunc(sub)),
        matrix_kernel("transition", "F = Ad_G(exp(-Ω)) + Φ_G(Ω) 𝒞 (paper, below eq:pred_cov).", ["s", "dt"], sin_ + [(dt, "dt")],
                      model.F.applyfunc(sub)),
        matrix_kernel("process_noise", f"Q = G diag(σ²) G^T: the noise n ({', '.join(model.noise_names)}) of eq:motionG in the tangent.",
                      ["s", "dt", *model.noise_names], sin_ + [(dt, "dt")] + list(zip(sig, model.noise_names)),
                      model.Q.applyfunc(sub)),
    ]
    # ---- fused prediction
    stages, outs, Pn = lg_predict(model, P)
    built.predict_parts = (stages, outs, Pn)
    periodic = model.periodic_tangent()
    ks.append(angle_limit_kernel(n, periodic))
    ks.append(Kernel(
        name="predict",
        doc=("Fused LG-EKF prediction, in place: μ ← μ exp(Ω(μ)) (eq:pred_mu),\n"
             "P ← F P F^T + Φ(Ω) Q Φ(Ω)^T (eq:pred_cov), Q = G diag(σ²) G^T.\n"
             f"s: internal state {layout}, p: packed covariance ({n * (n + 1) // 2}), dt > 0.\n"
             + ("Then the std of the tangent angles is capped at π (limit_angle_variance; inactive while ≤ π).\n" if periodic else "")
             + LEGEND),
        params=["s", "p", "dt", *model.noise_names],
        inputs=sin_ + pin + [(dt, "dt")] + list(zip(sig, model.noise_names)),
        stages=stages, outputs=cov_outputs(Pn) + [(f"s[{i}]", e) for i, e in outs.items()],
        epilogue=["limit_angle_variance(p)"] if periodic else [], fastmath=True,
    ))
    out = [("quantities", k) for k in ks]
    for meas in measurements.values():
        out.extend(_measurement_kernels(model, meas, P, pin, sin_))
    out += [("safeguards", k) for k in pd_check_kernels(n)]
    # ---- exact motion for simulation
    nn = sp.symbols(f"n0:{len(model.noise_stds())}", real=True)
    new = {i: e for i, e in enumerate(model.internal_of(model.propagated(nn).applyfunc(sub)))}
    new = {i: model.to_internal(e) for i, e in new.items() if model.to_internal(e) != model.internal[i]}
    pdefs, Ps = symbolize(sp.Matrix([list(new.values())]), "xn")
    nparams = [f"n{i}" for i in range(len(nn))]
    out.append(("simulation", Kernel(
        name="propagate",
        doc="Exact motion X ← X exp([Ω(X) + G n]^∧) (eq:model) for one noise sample n, in place.",
        params=["s", "dt", *nparams], inputs=sin_ + [(dt, "dt")] + list(zip(nn, nparams)),
        stages=[pdefs], outputs=[(f"s[{i}]", Ps[0, k]) for k, i in enumerate(new)],
    )))
    out.append(("simulation", Kernel(
        name="position_into", doc=f"The position (the first {_WORDS[model.space.dim]} physical coordinates) of the internal state into ``out`` ({model.space.dim},).",
        params=["s", "out"], inputs=sin_, outputs=[(f"out[{i}]", e) for i, e in enumerate(model.physical_from_internal()[:model.space.dim])])))
    # ---- common coordinates
    cs = sp.symbols(f"c0:{model.n_common}", real=True)
    csub = dict(zip(model.space.common, cs))
    cin = vec_inputs("c", cs)
    nd = model.space.dim
    out.append(("velocity", vector_kernel("world_velocity", f"World-frame velocity ({nd},) of a physical state x of this model.", ["x"],
                                          vec_inputs("x", model.physical), model.world_velocity())))
    out.append(("velocity", Kernel(name="world_velocity_into", doc=f"world_velocity of a physical state x written into out ({nd},) (no allocation).",
                                   params=["x", "out"], inputs=vec_inputs("x", model.physical),
                                   outputs=[(f"out[{i}]", e) for i, e in enumerate(model.world_velocity())])))
    out.append(("common", vector_kernel(
        "common_to_state", f"The model's physical state from the common c = {model.space.common_doc}, velocities in the body frame.",
        ["c"], cin, [sp.sympify(e).subs(csub, simultaneous=True) for e in model.from_common()])))
    out.append(("common", matrix_kernel(
        "common_jacobian", "J = ∂(filter coordinates ε)/∂c at c: maps a covariance of c to the filter's P (P = J P_c J^T).",
        ["c"], cin, model.common_jacobian.subs(csub, simultaneous=True))))
    # ---- estimation error in the filter's tangent coordinates (NEES)
    G = model.group
    true_mean = model.mean_of_common.subs(csub, simultaneous=True)
    err = G.log(G.inverse(model.mean()).applyfunc(sub) * true_mean)
    from ...lie.special import wrap

    err = sp.Matrix([wrap(e) if i in model.angles else e for i, e in enumerate(err)])
    out.append(("error", vector_kernel(
        "tangent_error",
        "ε = [log_G(μ^-1 X)]^∨: the error of the estimate μ (internal state s) w.r.t. a true common state c,\n"
        "in the coordinates of P (for NEES = εᵀ P^-1 ε); angle coordinates wrapped to (-π, π].",
        ["s", "c"], sin_ + cin, err.applyfunc(sub),
    )))
    return out
