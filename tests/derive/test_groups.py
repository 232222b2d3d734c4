"""SE(2): property tests of the generated numba kernels and symbolic checks of derive/lie/groups.py.

Conventions: tangent order (x, y, θ); X = μ·exp(ε); Φ = right_jacobian with
log(exp(-v) exp(v + δ)) = Φ(v) δ + O(δ²).
"""

from __future__ import annotations

import math
import os

import numpy as np
import pytest
import scipy.linalg as sla
import sympy as sp
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

from lgekf.derive.lie.groups import SE2
from lgekf.derive.lie.special import to_exact
from lgekf.generated import se2 as g

PI = math.pi
SETTINGS = dict(max_examples=int(os.environ.get("LGEKF_HYPOTHESIS_EXAMPLES", "300")), deadline=None, suppress_health_check=[HealthCheck.too_slow])

# ------------------------------------------------------------------ strategies
_tiny = st.floats(-12.0, -3.0).map(lambda e: 10.0**e)
_signed_tiny = st.tuples(_tiny, st.sampled_from([-1.0, 1.0])).map(lambda t: t[0] * t[1])
_near_pi_gap = st.floats(-12.0, -1.0).map(lambda e: 10.0**e)  # π - gap with gap in [1e-12, 0.1]
_near_pi = st.tuples(_near_pi_gap, st.sampled_from([-1.0, 1.0])).map(lambda t: t[1] * (PI - t[0]))


def angles(max_abs: float = PI, open_pi: bool = True):
    """θ: exactly 0, tiny (±1e-12..1e-3), near ±π, and uniform; |θ| < π (open) or <= max_abs."""
    parts = [st.just(0.0), st.just(-0.0), _signed_tiny]
    if max_abs >= PI:
        parts.append(_near_pi)
        uniform = st.floats(-PI, PI, exclude_min=open_pi, exclude_max=open_pi)
    else:
        uniform = st.floats(-max_abs, max_abs)
    parts.append(uniform)
    return st.one_of(*parts)


coords = st.floats(-10.0, 10.0, allow_subnormal=False)
small_coords = st.floats(-3.0, 3.0, allow_subnormal=False)


def tangent(theta=None, c=coords):
    theta = angles() if theta is None else theta
    return st.builds(lambda x, y, t: np.array([x, y, t]), c, c, theta)


def element(theta_c_s, tx, ty):
    c, s = theta_c_s
    return np.array([[c, -s, tx], [s, c, ty], [0.0, 0.0, 1.0]])


group_elements = st.builds(
    lambda t, x, y: element((math.cos(t), math.sin(t)), x, y), angles(), coords, coords
)


def hat(v):
    return np.array([[0.0, -v[2], v[0]], [v[2], 0.0, v[1]], [0.0, 0.0, 0.0]])


def scale(*vs):
    return 1.0 + max(float(np.max(np.abs(v))) for v in vs)


# ------------------------------------------------------------------ exp / log
@settings(**SETTINGS)
@given(group_elements)
@example(element((1.0, 0.0), 0.3, -0.2))
@example(element((math.cos(PI - 1e-12), math.sin(PI - 1e-12)), 2.0, 5.0))
def test_exp_of_log_is_identity(T):
    xi = g.se2_log(T)
    assert abs(xi[2]) <= PI
    np.testing.assert_allclose(g.se2_exp(xi), T, rtol=0, atol=1e-13 * scale(T))


@settings(**SETTINGS)
@given(tangent())
@example(np.array([1.0, 2.0, 0.0]))
@example(np.array([1.0, 2.0, 1e-300]))
@example(np.array([-4.0, 2.5, PI - 1e-12]))
def test_log_of_exp_is_identity(xi):
    assert abs(xi[2]) < PI
    # near |θ| = π the translation of log is amplified by |V(θ)^-1| <= π/2 * ... (well conditioned)
    np.testing.assert_allclose(g.se2_log(g.se2_exp(xi)), xi, rtol=0, atol=1e-13 * scale(xi))


@settings(**SETTINGS)
@given(tangent())
def test_exp_matches_scipy_expm(xi):
    np.testing.assert_allclose(g.se2_exp(xi), sla.expm(hat(xi)), rtol=0, atol=1e-13 * scale(xi))


@settings(**SETTINGS)
@given(tangent(theta=angles(max_abs=3.0)))
def test_log_matches_scipy_logm(xi):
    """logm is the principal logarithm: defined (and real) for |θ| < π; compared for |θ| <= 3."""
    T = g.se2_exp(xi)
    L = sla.logm(T)
    L = np.real_if_close(L, tol=1e6)
    assert np.all(np.isreal(L))
    ref = np.array([L[0, 2], L[1, 2], L[1, 0]])
    np.testing.assert_allclose(g.se2_log(T), ref, rtol=0, atol=1e-10 * scale(xi))
    # logm's result is a Lie algebra element
    np.testing.assert_allclose(L, hat(ref), rtol=0, atol=1e-10 * scale(xi))


@settings(**SETTINGS)
@given(tangent())
def test_hat_vee_inverse(xi):
    np.testing.assert_array_equal(g.se2_vee(g.se2_hat(xi)), xi)
    np.testing.assert_array_equal(g.se2_hat(xi), hat(xi))


@settings(**SETTINGS)
@given(group_elements)
def test_inverse(T):
    np.testing.assert_allclose(g.se2_inverse(T) @ T, np.eye(3), rtol=0, atol=1e-13 * scale(T))
    np.testing.assert_allclose(g.se2_inverse(T), np.linalg.inv(T), rtol=0, atol=1e-13 * scale(T))


# ------------------------------------------------------------------ Ad, ad
@settings(**SETTINGS)
@given(tangent(), tangent())
def test_Ad_is_conjugation(xi, v):
    X = g.se2_exp(xi)
    lhs = g.se2_adjoint(X) @ v
    rhs = g.se2_vee(X @ g.se2_hat(v) @ g.se2_inverse(X))
    np.testing.assert_allclose(lhs, rhs, rtol=0, atol=1e-12 * scale(xi) * scale(v))


@settings(**SETTINGS)
@given(tangent(), tangent())
def test_Ad_exp_is_exp_ad(xi, v):
    """exp(Ad(X) v) = X exp(v) X^-1."""
    X = g.se2_exp(xi)
    lhs = g.se2_exp(g.se2_adjoint(X) @ v)
    rhs = X @ g.se2_exp(v) @ g.se2_inverse(X)
    np.testing.assert_allclose(lhs, rhs, rtol=0, atol=1e-11 * scale(xi) ** 2 * scale(v))


@settings(**SETTINGS)
@given(tangent(), tangent())
def test_ad_is_bracket(a, b):
    A, B = g.se2_hat(a), g.se2_hat(b)
    np.testing.assert_allclose(g.se2_ad(a) @ b, g.se2_vee(A @ B - B @ A), rtol=0, atol=1e-13 * scale(a) * scale(b))


@settings(**SETTINGS)
@given(tangent())
def test_Ad_of_exp_is_expm_of_ad(xi):
    """Ad(exp(ξ)) = expm(ad(ξ))."""
    np.testing.assert_allclose(
        g.se2_adjoint(g.se2_exp(xi)), sla.expm(g.se2_ad(xi)), rtol=0, atol=1e-12 * scale(xi)
    )


# ------------------------------------------------------------------ right Jacobian Φ
def phi_series(xi, order=30):
    ad = g.se2_ad(xi)
    out = np.zeros((3, 3))
    P = np.eye(3)
    for m in range(order + 1):
        out += (-1) ** m / math.factorial(m + 1) * P
        P = P @ ad
    return out


@settings(**SETTINGS)
@given(tangent(theta=angles(max_abs=3.0), c=small_coords))
@example(np.array([1.0, -2.0, 0.0]))
@example(np.array([1.0, -2.0, 3.0]))
@example(np.array([1.0, -2.0, -3.0]))
def test_right_jacobian_equals_series(xi):
    np.testing.assert_allclose(g.right_jacobian(xi), phi_series(xi), rtol=0, atol=1e-13 * scale(xi))


@settings(**SETTINGS)
@given(tangent())
@example(np.array([1.0, -2.0, 0.0]))
@example(np.array([1.0, -2.0, PI - 1e-12]))
def test_right_jacobian_times_inverse_is_identity(xi):
    Phi, Phi_inv = g.right_jacobian(xi), g.right_jacobian_inv(xi)
    np.testing.assert_allclose(Phi @ Phi_inv, np.eye(3), rtol=0, atol=1e-13 * scale(xi))
    np.testing.assert_allclose(Phi_inv @ Phi, np.eye(3), rtol=0, atol=1e-13 * scale(xi))


def _central_jacobian(fun, n, h):
    cols = []
    for j in range(n):
        e = np.zeros(n)
        e[j] = h
        cols.append((fun(e) - fun(-e)) / (2 * h))
    return np.array(cols).T


@settings(**SETTINGS)
@given(tangent(c=small_coords))
@example(np.array([1.0, -2.0, 0.0]))
@example(np.array([1.0, -2.0, 1e-9]))
@example(np.array([1.0, -2.0, PI - 1e-9]))
def test_right_jacobian_defining_property(v):
    """log(exp(-v) exp(v + δ)) = Φ(v) δ + O(δ²), by central differences (error O(h²) + O(eps/h))."""
    E_minus = g.se2_exp(-v)

    def fun(d):
        return g.se2_log(E_minus @ g.se2_exp(v + d))

    J = _central_jacobian(fun, 3, 1e-6)
    np.testing.assert_allclose(g.right_jacobian(v), J, rtol=0, atol=1e-7 * scale(v) ** 2)


@settings(**SETTINGS)
@given(tangent(c=small_coords))
def test_right_jacobian_is_the_derivative_of_exp(v):
    """Equivalently exp(v + δ) = exp(v) exp(Φ(v) δ) + O(δ²)."""
    Ev = g.se2_exp(v)
    J = _central_jacobian(lambda d: g.se2_log(g.se2_inverse(Ev) @ g.se2_exp(v + d)), 3, 1e-6)
    np.testing.assert_allclose(g.right_jacobian(v), J, rtol=0, atol=1e-7 * scale(v) ** 2)


# ------------------------------------------------------------------ symbolic (derive/lie/groups.py)
x, y, th = sp.symbols("x y theta", real=True)
XI = [x, y, th]


def _is_zero_matrix(M) -> bool:
    return all(sp.simplify(e) == 0 for e in M)


def test_symbolic_derived_exp_equals_closed_form():
    assert _is_zero_matrix(to_exact(SE2.exp(XI)) - SE2.derived_exp(XI))


def test_symbolic_derived_Ad_equals_closed_form():
    tx, ty = sp.symbols("t_x t_y", real=True)
    T = SE2.element(sp.cos(th), sp.sin(th), tx, ty)
    assert _is_zero_matrix(SE2.derived_Ad(T) - SE2.Ad(T))
    # and on a group element given as exp(ξ)
    E = to_exact(SE2.exp(XI))
    assert _is_zero_matrix(SE2.derived_Ad(E) - SE2.Ad(E))


def test_symbolic_derived_ad_equals_closed_form():
    assert _is_zero_matrix(SE2.derived_ad(XI) - SE2.ad(XI))


def test_symbolic_derived_right_jacobian_equals_closed_form():
    assert _is_zero_matrix(SE2.derived_right_jacobian(XI) - to_exact(SE2.right_jacobian(XI)))


def test_symbolic_right_jacobian_series_order_8():
    """Taylor series in t of the closed form Φ(t ξ) = Σ_{m<=8} (-1)^m/(m+1)! ad(t ξ)^m + O(t^9)."""
    t = sp.Symbol("t", real=True)
    txi = [t * e for e in XI]
    closed = to_exact(SE2.right_jacobian(txi))
    truncated = SE2.right_jacobian_series(txi, 8)
    for c, s in zip(closed, truncated):
        ser = sp.series(c, t, 0, 9).removeO()
        assert sp.expand(ser - sp.expand(s)) == 0, (c, s)


def test_symbolic_right_jacobian_times_inverse_is_identity():
    P = to_exact(SE2.right_jacobian(XI) * SE2.right_jacobian_inv(XI))
    assert _is_zero_matrix(P - sp.eye(3))
    P = to_exact(SE2.right_jacobian_inv(XI) * SE2.right_jacobian(XI))
    assert _is_zero_matrix(P - sp.eye(3))


def test_symbolic_log_inverts_exp():
    """log(exp(ξ)) = ξ for θ in (-π, π) (θ = atan2(sin θ, cos θ) is then θ)."""
    t = sp.Symbol("t", real=True)
    L = to_exact(SE2.log(to_exact(SE2.exp([x, y, t]))))
    # atan2(sin t, cos t) = t on (-π, π); substitute it by hand, the rest must simplify exactly
    L = L.subs(sp.atan2(sp.sin(t), sp.cos(t)), t)
    assert _is_zero_matrix(L - sp.Matrix([x, y, t]))


@pytest.mark.parametrize("val", [sp.Rational(1, 3), sp.Rational(-5, 2), sp.Rational(1, 1000)])
def test_symbolic_log_inverts_exp_at_values(val):
    xi = [sp.Rational(7, 10), sp.Rational(-13, 10), val]
    L = SE2.log(SE2.exp(xi))
    assert all(abs(sp.N(a - b, 40)) < 1e-35 for a, b in zip(L, xi))
