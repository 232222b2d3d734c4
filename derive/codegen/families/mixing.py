"""Fused kernels for mixing Gaussians on a model's group (the IMM's interaction and combination steps).

Mixing Σ w_i N_G(μ_i, P_i) into one N_G(μ, P) (derivation in ``lgekf.estimators.imm.kernels``) needs, per
source i, d_i = [log(μ⁻¹μ_i)]^∨ (``between``) while the mean is iterated, and at the mean the transported
term w_i [Φ(d_i)⁻¹ P_i Φ(d_i)⁻ᵀ + d_i d_iᵀ].  Done with the general kernels (``between_into``,
``right_jacobian_inv_into``, a dense n × n congruence) that costs: the angle of d_i is evaluated by atan2 and
then sin/cos of it twice (once in ``between``, once in Φ⁻¹), the n × n products run over the structural zeros
of Φ⁻¹ (the identity on every Rⁿ factor), and the packed covariances go through dense copies.  Emitted here,
per model, from the same definitions (``derive.lie`` groups, the model's internal layout):

* ``between_add(s, t, w, acc)``: acc += w·[log(μ_s⁻¹μ_t)]^∨ (one mean iteration's term);
* ``mix_transport(s, t, pt, w, acc)``: acc (packed, upper triangle row-major, n(n+1)/2) +=
  w·[Φ(d)⁻¹ P_t Φ(d)⁻ᵀ + d dᵀ], d = [log(μ_s⁻¹μ_t)]^∨, P_t the packed ``pt``; straight-line, with CSE over
  between and Φ⁻¹ (one atan2 per SE(2) factor) and only the non-zero products.

Both evaluate sin/cos of a relative angle a = atan2(y, x) as y/r, x/r (r = √(x² + y²), ``Kernel.sincos_of_atan2``):
equal to sin(a), cos(a) to rounding, without the two libm calls.
"""

from __future__ import annotations

import sympy as sp

from ...algebra import packed_index
from ...dag import dag_xreplace
from ...lie.special import ANGLE_FUNCTIONS, wrap
from ..printer import Kernel

__all__ = ["mixing_kernels", "common_kernels", "kernels"]


def _between(model):
    """(inputs of s and t, d = [log(μ_s⁻¹μ_t)]^∨ as expressions in the internal entries of s and t)."""
    G = model.group
    sub = model.to_internal
    mu = model.mean().applyfunc(sub)
    tsyms = [sp.Symbol(f"t_{v}", real=True) for v in model.internal]
    mu_t = mu.subs(dict(zip(model.internal, tsyms)), simultaneous=True)
    d = G.log(G.inverse(mu) * mu_t)
    d = [wrap(e) if i in model.angles and i not in model.periodic_tangent() else e for i, e in enumerate(d)]
    sin_ = [(v, f"s[{i}]") for i, v in enumerate(model.internal)]
    tin = [(v, f"t[{i}]") for i, v in enumerate(tsyms)]
    return sin_ + tin, [sub(sp.sympify(e)) for e in d]


def _angle_args_to(expr, rep: dict):
    """expr with ``rep`` applied inside the arguments of sin, cos and the angle functions only (so that the printer
    reuses the sin/cos of an angle already evaluated for d, e.g. atan2(...), instead of calling sin(d_k) again)."""
    kinds = (sp.sin, sp.cos, *ANGLE_FUNCTIONS)
    return sp.sympify(expr).replace(lambda e: isinstance(e, kinds), lambda e: e.func(*(a.xreplace(rep) for a in e.args)))


def mixing_kernels(model) -> list:
    """``between_add`` and ``mix_transport`` of one model (module docstring)."""
    n = model.n
    idx = packed_index(n)
    st_in, d_expr = _between(model)
    dsyms = sp.symbols(f"d0:{n}", real=True)
    acc = [sp.Symbol(f"acc{k}", real=True) for k in range(n * (n + 1) // 2)]
    acc_in = [(a, f"acc[{k}]") for k, a in enumerate(acc)]
    w = sp.Symbol("w", real=True)
    add = Kernel(
        name="between_add",
        doc="acc += w·[log_G(μ_s^-1 μ_t)]^∨ (a term of the iterated mean μ ← μ·exp(Σ w_i d_i); d as ``between``).",
        params=["s", "t", "w", "acc"], inputs=st_in + [(w, "w")] + acc_in[:n],
        stages=[list(zip(dsyms, d_expr))],
        outputs=[(f"acc[{k}]", acc[k] + w * dsyms[k]) for k in range(n)], sincos_of_atan2=True,
    )
    # Φ(d)⁻¹ with the d_k inside angle functions replaced by their expressions (shared sin/cos, see _angle_args_to)
    eps = sp.symbols(f"eps0:{n}", real=True)
    Tinv = model.group.right_jacobian_inv(list(eps))
    memo: dict = {}  # a renaming of symbols: xreplace, each shared subexpression once (derive.dag)
    Tinv = Tinv.applyfunc(lambda e: dag_xreplace(e, dict(zip(eps, dsyms)), memo))
    Tinv = Tinv.applyfunc(lambda e: _angle_args_to(e, dict(zip(dsyms, d_expr))))
    tdefs, T = _symbolic(Tinv, "T")
    psyms = {(i, j): sp.Symbol(f"pt{i}_{j}", real=True) for i in range(n) for j in range(i, n)}
    Pt = sp.Matrix(n, n, lambda i, j: psyms[(min(i, j), max(i, j))])
    p_in = [(psyms[(i, j)], f"pt[{idx[(i, j)]}]") for i in range(n) for j in range(i, n)]
    U = T * Pt
    udefs, Us = [], sp.zeros(n, n)
    for i in range(n):
        for j in range(n):
            e = sp.expand(U[i, j])
            if e.is_Symbol or e.is_number:
                Us[i, j] = e
            else:
                Us[i, j] = sp.Symbol(f"U{i}_{j}", real=True)
                udefs.append((Us[i, j], e))
    C = Us * T.T
    outputs = []
    for i in range(n):
        for j in range(i, n):
            k = idx[(i, j)]
            outputs.append((f"acc[{k}]", acc[k] + w * (C[i, j] + dsyms[i] * dsyms[j])))
    transport = Kernel(
        name="mix_transport",
        doc=("acc (packed upper triangle) += w·[Φ(d)^-1 P_t Φ(d)^-T + d dᵀ], d = [log_G(μ_s^-1 μ_t)]^∨, P_t = unpack(pt):\n"
             "one source's term of a mixture's covariance about the mean μ_s (X = μ_t·exp ε_t = μ_s·exp(d + Φ(d)^-1 ε_t)\n"
             "to first order; lgekf.estimators.imm.kernels). Straight line over the non-zero entries of Φ^-1."),
        params=["s", "t", "pt", "w", "acc"], inputs=st_in + p_in + [(w, "w")] + acc_in,
        stages=[list(zip(dsyms, d_expr)), tdefs, udefs], outputs=outputs, sincos_of_atan2=True,
    )
    return [add, transport]


def _congruence(T: sp.Matrix, P: sp.Matrix, prefix: str):
    """(definitions of U = T P over its non-trivial entries, U Tᵀ): T P Tᵀ without the structural zeros."""
    U = T * P
    defs, Us = [], sp.zeros(*U.shape)
    for i in range(U.shape[0]):
        for j in range(U.shape[1]):
            e = sp.expand(U[i, j])
            if e.is_Symbol or e.is_number:
                Us[i, j] = e
            else:
                Us[i, j] = sp.Symbol(f"{prefix}{i}_{j}", real=True)
                defs.append((Us[i, j], e))
    return defs, Us * T.T


def _symbolic(Mx: sp.Matrix, prefix: str):
    """Mx with each non-constant entry replaced by a symbol; returns (definitions, matrix)."""
    defs, out = [], sp.zeros(*Mx.shape)
    for i in range(Mx.shape[0]):
        for j in range(Mx.shape[1]):
            e = sp.sympify(Mx[i, j])
            if e.is_number:
                out[i, j] = e
            else:
                out[i, j] = sp.Symbol(f"{prefix}{i}_{j}", real=True)
                defs.append((out[i, j], e))
    return defs, out


def common_kernels(model) -> list:
    """``common_of_state`` and ``state_of_common``: a mode's Gaussian to and from the common coordinates in one kernel.

    ``common_of_state(s, p, c, Pc)``: c = ``physical_to_common``(physical(s)) (6,), Pc = A P Aᵀ (6 × 6, dense) with
    A = ∂c/∂ε (``physical_to_common_jacobian``) at that state; ``state_of_common(c, Pc, s, p)``: s =
    state_from_physical(``common_to_state``(c)), p = J P_c Jᵀ packed, J = ``common_jacobian``(c).  Both evaluate
    the Jacobian where they are called: the caller handles speed 0 (``lgekf.estimators.imm.kernels.SPEED_FLOOR``);
    ``common_of_state`` runs with error_model="numpy" (a heading read off a zero velocity gives NaN/inf, not an
    exception, and the caller redoes that rare case).
    """
    common, nc, cdoc = model.space.common, model.n_common, model.space.common_doc
    n = model.n
    idx = packed_index(n)
    sin_ = [(v, f"s[{i}]") for i, v in enumerate(model.internal)]
    xs = [sp.Symbol(f"xp_{v.name}", real=True) for v in model.physical]
    xsub = dict(zip(model.physical, xs))
    phys = [(xi, sp.sympify(e)) for xi, e in zip(xs, model.physical_from_internal())]
    cvals = [sp.sympify(e).xreplace(xsub) for e in model.common_of_physical]
    adefs, A = _symbolic(model.common_of_physical_jacobian.xreplace(xsub), "A")
    psyms = {(i, j): sp.Symbol(f"p{i}_{j}", real=True) for i in range(n) for j in range(i, n)}
    P = sp.Matrix(n, n, lambda i, j: psyms[(min(i, j), max(i, j))])
    p_in = [(psyms[(i, j)], f"p[{idx[(i, j)]}]") for i in range(n) for j in range(i, n)]
    udefs, C = _congruence(A, P, "U")
    outs = [(f"c[{k}]", cvals[k]) for k in range(nc)]
    for i in range(nc):
        for j in range(i, nc):
            outs.append((f"Pc[{i}, {j}]", C[i, j]))
            if j != i:
                outs.append((f"Pc[{j}, {i}]", C[i, j]))
    to_common = Kernel(
        name="common_of_state",
        doc=(f"A mode's Gaussian in the common coordinates: c = {cdoc} of the internal state s (as\n"
             f"physical_to_common(physical(s))) and Pc = A P Aᵀ ({nc} × {nc}), A = ∂c/∂ε (physical_to_common_jacobian) at s."),
        params=["s", "p", "c", "Pc"], inputs=sin_ + p_in, stages=[phys, adefs, udefs], outputs=outs,
        error_model="numpy",
    )
    cs = sp.symbols(f"c0:{nc}", real=True)
    csub = dict(zip(common, cs))
    cin = [(ci, f"c[{k}]") for k, ci in enumerate(cs)]
    pcs = {(i, j): sp.Symbol(f"pc{i}_{j}", real=True) for i in range(nc) for j in range(i, nc)}
    Pc = sp.Matrix(nc, nc, lambda i, j: pcs[(min(i, j), max(i, j))])
    pc_in = [(pcs[(i, j)], f"Pc[{i}, {j}]") for i in range(nc) for j in range(i, nc)]
    phys_c = [(xi, sp.sympify(e).subs(csub, simultaneous=True)) for xi, e in zip(xs, model.from_common())]
    internal = [sp.sympify(e).xreplace(xsub) for e in model.internal_from_physical()]
    jdefs, J = _symbolic(model.common_jacobian.subs(csub, simultaneous=True), "J")
    vdefs, C = _congruence(J, Pc, "V")
    outs = [(f"s[{k}]", e) for k, e in enumerate(internal)]
    outs += [(f"p[{idx[(i, j)]}]", C[i, j]) for i in range(n) for j in range(i, n)]
    from_common = Kernel(
        name="state_of_common",
        doc=(f"A Gaussian in the common coordinates (c, Pc ({nc} × {nc}, upper triangle read)) as the model's: the internal state\n"
             "s = state_from_physical(common_to_state(c)) and p = J Pc Jᵀ packed, J = ∂ε/∂c (common_jacobian) at c."),
        params=["c", "Pc", "s", "p"], inputs=cin + pc_in, stages=[phys_c, jdefs, vdefs], outputs=outs,
    )
    return [to_common, from_common]


def kernels(model, measurements: dict, built) -> list:
    """The family's entry (``derive.codegen.emitter``): the fused terms of mixing on the group and a mode's Gaussian to
    and from the common coordinates (slot ``mixing``)."""
    return [("mixing", k) for k in mixing_kernels(model) + common_kernels(model)]
