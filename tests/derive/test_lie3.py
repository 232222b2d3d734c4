"""SO(3) and SE(3) in derive/lie/so3.py, se3.py: the closed forms (what the generator emits) against first principles.

Conventions: SE(3) tangent order (x, y, z, φx, φy, φz) = (ρ, φ); T = μ·exp(ε); Φ = right_jacobian with
log(exp(-ξ) exp(ξ + δ)) = Φ(ξ) δ + O(δ²).  Full symbolic simplification of the 6×6 closed forms is slow, so the
closed forms are compared with the ``derived_*`` quantities (matrix-exponential series, Ad by conjugation, ad by
the bracket, Φ by its series Σ (-1)^m/(m+1)! ad^m) at exact rational samples, evaluated to 50 digits; the
identities that SymPy proves quickly (ad, Ad of SO(3), the Taylor series of the angle functions) are symbolic.
"""

from __future__ import annotations

import sympy as sp
import pytest

from lgekf.derive.lie import special as S
from lgekf.derive.lie.first_principles import matrix_series
from lgekf.derive.lie.groups import SE2, SE3, SO3, Product, Rn
from lgekf.derive.lie.se3 import q_left

DIGITS = 50
TOL = sp.Float("1e-40")

# exact samples: generic, a small and a large angle (|φ| up to 3, below π), and |φ| near π for log
_SAMPLES_6 = [
    [sp.Rational(7, 10), sp.Rational(-13, 10), sp.Rational(2, 5), sp.Rational(3, 10), sp.Rational(-1, 5), sp.Rational(1, 2)],
    [sp.Rational(-2), sp.Rational(1, 3), sp.Rational(5, 4), sp.Rational(1, 1000), sp.Rational(-3, 1000), sp.Rational(2, 1000)],
    [sp.Rational(1, 7), sp.Rational(3), sp.Rational(-1, 2), sp.Rational(-9, 5), sp.Rational(6, 5), sp.Rational(17, 10)],
]


def _num(M):
    return sp.Matrix(M).applyfunc(lambda e: sp.N(S.to_exact(e) if e.has(S.AngleFunction) else e, DIGITS))


def _small(M) -> bool:
    return max(abs(e) for e in sp.Matrix(M).evalf(DIGITS)) < TOL


def _close(A, B):
    return _small(_num(A) - _num(B))


@pytest.mark.parametrize("xi", _SAMPLES_6, ids=["generic", "small angle", "large angle"])
def test_se3_exp_equals_matrix_exponential_series(xi):
    assert _close(SE3.exp(xi), SE3.derived_exp(xi))


@pytest.mark.parametrize("xi", _SAMPLES_6, ids=["generic", "small angle", "large angle"])
def test_so3_exp_equals_matrix_exponential_series(xi):
    assert _close(SO3.exp(xi[3:]), SO3.derived_exp(xi[3:]))


@pytest.mark.parametrize("xi", _SAMPLES_6, ids=["generic", "small angle", "large angle"])
def test_se3_right_jacobian_equals_series(xi):
    """Φ(ξ) = [[J_r, Q_r], [0, J_r]] (Barfoot's Q with A = sinc3, B = cosc4, C = sincos5) = Σ (-1)^m/(m+1)! ad^m."""
    assert _close(SE3.right_jacobian(xi), SE3.derived_right_jacobian(xi))
    assert _close(SO3.right_jacobian(xi[3:]), SO3.derived_right_jacobian(xi[3:]))


@pytest.mark.parametrize("xi", _SAMPLES_6, ids=["generic", "small angle", "large angle"])
def test_right_jacobian_times_inverse_is_identity(xi):
    assert _close(_num(SE3.right_jacobian(xi)) * _num(SE3.right_jacobian_inv(xi)), sp.eye(6))
    assert _close(_num(SO3.right_jacobian(xi[3:])) * _num(SO3.right_jacobian_inv(xi[3:])), sp.eye(3))
    assert _close(_num(SO3.left_jacobian(xi[3:])) * _num(SO3.left_jacobian_inv(xi[3:])), sp.eye(3))


@pytest.mark.parametrize("xi", _SAMPLES_6, ids=["generic", "small angle", "large angle"])
def test_right_jacobian_is_left_jacobian_of_minus_xi(xi):
    """Φ(ξ) = J_l(-ξ) (Barfoot): the Q_r block is Barfoot's Q_l(-ρ, -φ), and the SO(3) J_r(φ) = J_l(-φ) = V(-φ)."""
    rho, phi = xi[:3], xi[3:]
    assert _close(SE3.q_right(xi), q_left([-e for e in rho], [-e for e in phi]))
    assert _close(SO3.right_jacobian(phi), SO3.left_jacobian([-e for e in phi]))


@pytest.mark.parametrize("xi", _SAMPLES_6, ids=["generic", "small angle", "large angle"])
def test_log_inverts_exp(xi):
    assert _close(SE3.log(SE3.exp(xi)), sp.Matrix(xi))
    assert _close(SO3.log(SO3.exp(xi[3:])), sp.Matrix(xi[3:]))


@pytest.mark.parametrize("gap", ["1e-3", "1e-9", "1e-20"])
def test_log_near_pi_uses_the_symmetric_part(gap):
    """|φ| = π - gap: the symmetric-part branch returns φ to 50 digits (also with the axis along each coordinate)."""
    u = sp.Matrix([sp.Rational(2, 7), sp.Rational(-3, 7), sp.Rational(6, 7)])  # |u| = 1
    th = sp.pi - sp.Float(gap, 60)
    for axis in (u, sp.Matrix([1, 0, 0]), sp.Matrix([0, -1, 0]), sp.Matrix([0, 0, 1])):
        phi = list(axis * th)
        xi = [sp.Rational(1, 3), -2, sp.Rational(5, 2)] + phi
        T = _num(SE3.exp(xi))
        assert _small(_num(SE3.log(T)) - _num(sp.Matrix(xi)))


def test_exp_of_log_at_exactly_pi():
    """At |φ| = π the log is ±π u; either way exp(log(R)) = R."""
    R = _num(SO3.exp([sp.pi * sp.Rational(2, 7), -sp.pi * sp.Rational(3, 7), sp.pi * sp.Rational(6, 7)]))
    assert _small(_num(SO3.exp(list(SO3.log(R)))) - R)


def test_symbolic_ad_is_the_bracket():
    xi = sp.symbols("a0:6", real=True)
    assert sp.simplify(SE3.ad(xi) - SE3.derived_ad(xi)) == sp.zeros(6, 6)
    assert sp.simplify(SO3.ad(xi[3:]) - SO3.derived_ad(xi[3:])) == sp.zeros(3, 3)


def test_so3_Ad_is_conjugation():
    """Ad(R) v = [R v^ R^T]^∨ = R v, at an exact rotation (the 50-digit series of a rational φ)."""
    Rs = SO3.derived_exp([sp.Rational(1, 3), sp.Rational(-1, 2), sp.Rational(1, 5)], DIGITS)
    assert _close(SO3.Ad(Rs), SO3.derived_Ad(Rs))


@pytest.mark.parametrize("xi", _SAMPLES_6, ids=["generic", "small angle", "large angle"])
def test_se3_Ad_is_conjugation(xi):
    T = _num(SE3.exp(xi))
    assert _close(SE3.Ad(T), SE3.derived_Ad(T))


@pytest.mark.parametrize("xi", _SAMPLES_6, ids=["generic", "small angle", "large angle"])
def test_Ad_of_exp_is_exp_of_ad(xi):
    """Ad(exp ξ) = exp(ad ξ), the right side by its series."""
    T = _num(SE3.exp(xi))
    expad = matrix_series(SE3.ad(xi), lambda m: sp.Rational(1, sp.factorial(m)), DIGITS)
    assert _close(SE3.Ad(T), expad)


def test_hat_vee_and_inverse():
    xi = sp.symbols("a0:6", real=True)
    assert SE3.vee(SE3.hat(xi)) == sp.Matrix(xi)
    assert SO3.vee(SO3.hat(xi[3:])) == sp.Matrix(xi[3:])
    T = _num(SE3.exp(_SAMPLES_6[0]))
    assert _small(_num(SE3.inverse(T) * T) - sp.eye(4))


@pytest.mark.parametrize("f", [S.sinc3, S.cosc4, S.sincos5, S.halfcot2], ids=lambda f: f.__name__)
def test_angle_function_series_starts_as_expected(f):
    """The Taylor coefficients SymPy computes match the known leading terms (1/6, 1/24, 1/120, 1/12)."""
    lead = {"sinc3": sp.Rational(1, 6), "cosc4": sp.Rational(1, 24), "sincos5": sp.Rational(1, 120),
            "halfcot2": sp.Rational(1, 12)}[f.__name__]
    assert S.taylor_coefficients(f)[0] == lead


# ------------------------------------------------------------------ products
@pytest.mark.parametrize("factors", [(SE3, Rn(6)), (SE3, SE3), (SO3, Rn(3)), (SE2, SE3)],
                         ids=["SE3xR6", "SE3xSE3", "SO3xR3", "SE2xSE3"])
def test_products_are_block_diagonal(factors):
    """Product composes any of the groups: dims add, exp/Ad/Φ are block-diagonal, log inverts exp."""
    G = Product(*factors)
    assert G.dim == sum(f.dim for f in factors)
    assert G.matrix_size == sum(f.matrix_size for f in factors)
    base = [sp.Rational(k + 1, 7) * (-1) ** k for k in range(G.dim)]
    X = _num(G.exp(base))
    J = _num(G.right_jacobian(base))
    assert _small(_num(G.log(X)) - _num(sp.Matrix(base)))
    assert _close(_num(G.right_jacobian(base)) * _num(G.right_jacobian_inv(base)), sp.eye(G.dim))
    i = j = 0
    for f in factors:
        part = base[i:i + f.dim]
        assert _close(X[j:j + f.matrix_size, j:j + f.matrix_size], f.exp(part))
        assert _close(J[i:i + f.dim, i:i + f.dim], f.right_jacobian(part))
        i, j = i + f.dim, j + f.matrix_size
    assert _close(G.Ad(X), sp.diag(*[f.Ad(B) for f, B in zip(G.factors, G._split_matrix(X))]))


def test_nested_products_flatten():
    G = Product(Product(SE3, Rn(3)), SE3)
    assert [f.dim for f in G.factors] == [6, 3, 6]
    assert G.periodic_coordinates() == (3, 4, 5, 12, 13, 14)
