"""Derivatives at ε = 0 through removable singularities (the paper's "multivariate limits").

Entries of 𝒞 (eq:C) and ℋ (eq:calH) are partial derivatives of expressions such as
``[ε_vx sin ε_ω + ε_vy (cos ε_ω - 1)] / ε_ω`` whose value at ε = 0 is 0/0.  We do not substitute a
special-function form and hope: each entry is evaluated as the limit t → 0 along ε = t·u for several
directions u (every axis and several generic directions), and the limits must agree.  Agreement
along many directions is what the paper calls the multivariate limit; a disagreement raises.

Along an axis the printed expression is often undefined on the whole line (ε_ω = 0 makes it 0/0
for every t), so every path is bent slightly off the singular set: ε(t) = t·u + t²·w with a fixed
generic w whose components are all non-zero.  Its tangent at 0 is still u.
"""

from __future__ import annotations

import itertools

import sympy as sp

__all__ = ["DEFAULT_DIRECTIONS", "directions_for", "limit_at_zero", "jacobian_at_zero", "LimitMismatch"]


class LimitMismatch(ValueError):
    """The directional limits of an expression at ε = 0 differ (no multivariate limit)."""


_GENERIC = ((1, 1, 1, 1, 1, 1), (1, -2, 3, -1, 2, -3), (3, 1, -2, 2, -1, 1), (-2, 3, 1, -3, 1, 2))


def directions_for(n: int):
    """Each coordinate axis plus four generic (non-axis) directions in R^n (beyond 6 coordinates the generic
    directions repeat their pattern, scaled by 2, 3, ... so that no two coordinates move alike)."""
    axes = [tuple(1 if i == j else 0 for i in range(n)) for j in range(n)]
    generic = [tuple(g[k % 6] * (1 + k // 6) for k in range(n)) for g in _GENERIC]
    return axes + generic


DEFAULT_DIRECTIONS = directions_for


def _is_singular_at_zero(expr, eps) -> bool:
    zero = {e: 0 for e in eps}
    try:
        val = expr.subs(zero)
    except ZeroDivisionError:  # pragma: no cover - sympy returns zoo instead
        return True
    return val.has(sp.zoo, sp.nan, sp.oo, -sp.oo)


def limit_at_zero(expr, eps, directions=None, *, report=None):
    """lim_{ε→0} expr, required to be the same along every direction in ``directions``.

    ``report`` (a list) receives a tuple ``(expr, {direction: limit})`` for every singular entry.
    """
    expr = sp.sympify(expr)
    eps = list(eps)
    if not any(expr.has(e) for e in eps):
        return expr
    if not _is_singular_at_zero(expr, eps):
        return sp.simplify(expr.subs({e: 0 for e in eps}))
    t = sp.Symbol("_t", positive=True)
    dirs = directions if directions is not None else directions_for(len(eps))
    bend = [sp.Rational(k + 2, 7) * (-1) ** k for k in range(len(eps))]
    values = {}
    for u in dirs:
        along = expr.subs({e: t * ui + t**2 * wi for e, ui, wi in zip(eps, u, bend)}, simultaneous=True)
        values[tuple(u)] = sp.simplify(sp.limit(along, t, 0))
    ref = next(iter(values.values()))
    for u, v in values.items():
        if sp.simplify(v - ref) != 0:
            raise LimitMismatch(f"limit of {expr} at 0 depends on the direction: {values}")
    if report is not None:
        report.append((expr, values))
    return ref


def jacobian_at_zero(f: sp.Matrix, eps, directions=None, *, report=None) -> sp.Matrix:
    """∂f/∂ε at ε = 0, each entry through :func:`limit_at_zero`."""
    J = sp.Matrix(f).jacobian(sp.Matrix(eps))
    out = sp.zeros(*J.shape)
    for i, j in itertools.product(range(J.shape[0]), range(J.shape[1])):
        out[i, j] = limit_at_zero(J[i, j], eps, directions, report=report)
    return out
