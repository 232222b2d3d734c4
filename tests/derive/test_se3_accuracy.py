"""Accuracy of the generated SO(3)/SE(3) kernels (generated/se3.py) against 50-digit mpmath references.

The references are first principles computed in mpmath at 50 digits from the exact float inputs, independent of
the closed forms: exp = mp.expm of the hat; log of a float matrix X = the ξ minimising |expm(ξ^) - X| (Gauss-Newton
from the tangent X was made from, with d expm(ξ^) = expm(ξ^) (Φ(ξ) δ)^; mp.logm returns complex nonsense near
|φ| = π); Ad by conjugation T ξ^ T^-1; ad by the bracket; Φ = Σ (-1)^m/(m+1)! ad^m summed to 1e-55; Φ^-1 = mp.inverse of
it.

Rotation angles |φ|: 0, ±1e-15, ±3e-15, ..., ±1e-3 (negative: the opposite axis), generic angles up to 3, π - 1e-3,
π - 1e-9, both sides of π/2 (log's switch to the symmetric part) and both sides (τ(1 ± 1e-9)) of every threshold of the angle functions the kernels use (sinc, cosc2:
1e-4; sinc3 0.75; halfcot2 1.5; cosc4 1.6; sincos5 2.1).  Axis u = (2, -3, 6)/7, translation ρ = (0.7, -1.3, 0.4).

Requirement: |computed - true| <= 1e-13 · max(|true|, 1e-300) for every entry (relative error 1e-13, exact zeros
stay zero).  The worst error per kernel is printed in the terminal summary (``accuracy_table``).
"""

from __future__ import annotations

import math

import mpmath as mp
import numpy as np
import pytest

from lgekf.derive.lie import special as S
from lgekf.generated import se3 as g

REL_TOL = 1e-13
ZERO_FLOOR = mp.mpf("1e-300")
DIGITS = 50

AXIS = np.array([2.0, -3.0, 6.0]) / 7.0
RHO = np.array([0.7, -1.3, 0.4])

_DECADES = [m * 10.0**k for k in range(-15, -2) for m in (1.0, 3.0)] + [1e-3]
# π/2 (1 ± 1e-9): where log switches from the antisymmetric to the symmetric part (cos θ = 0)
_GENERIC = [0.2, 0.6, 1.0, 1.4, 1.8, 2.2, 2.6, 3.0, math.pi - 1e-3, math.pi - 1e-9] + [math.pi / 2 * (1 - 1e-9), math.pi / 2 * (1 + 1e-9)]
_TAUS = sorted({f.tau for f in (S.sinc, S.cosc2, S.sinc3, S.halfcot2, S.cosc4, S.sincos5)})
_NEAR_TAU = [t * k for t in _TAUS for k in (1 - 1e-9, 1 + 1e-9)]
_POS = sorted(set(_DECADES + _GENERIC + _NEAR_TAU))
ANGLES = [0.0] + _POS + [-a for a in _POS]


def _phi(a):
    return a * AXIS


def _xi(a):
    return np.concatenate([RHO, _phi(a)])


# ------------------------------------------------------------------ mpmath references (first principles)
def M(a) -> mp.matrix:
    """An exact mpmath copy of a float array (vectors as columns)."""
    a = np.asarray(a, dtype=float)
    if a.ndim == 1:
        return mp.matrix([mp.mpf(float(x)) for x in a])
    return mp.matrix([[mp.mpf(float(x)) for x in row] for row in a])


def hat3(v):
    return mp.matrix([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]])


def hat6(v):
    H = mp.zeros(4, 4)
    K = hat3([v[3], v[4], v[5]])
    for i in range(3):
        for j in range(3):
            H[i, j] = K[i, j]
        H[i, 3] = v[i]
    return H


def vee6(H):
    """(H[0,3], H[1,3], H[2,3]) and the antisymmetric part's (H21, H02, H10) (logm of a rounded T is ~skew)."""
    return [H[0, 3], H[1, 3], H[2, 3], (H[2, 1] - H[1, 2]) / 2, (H[0, 2] - H[2, 0]) / 2, (H[1, 0] - H[0, 1]) / 2]


def ad6(v):
    """ad(v) w = [v^ w^ - w^ v^]^∨, column by column."""
    A = mp.zeros(6, 6)
    Hv = hat6(v)
    for k in range(6):
        e = [0] * 6
        e[k] = 1
        He = hat6(e)
        col = vee6(Hv * He - He * Hv)
        for i in range(6):
            A[i, k] = col[i]
    return A


def jr_series(v):
    return series_jr(ad6(v))


def ad3(v):
    return hat3(v)


def series_jr(A):
    """Σ (-1)^m/(m+1)! A^m, summed until a term is below 1e-55."""
    n = A.rows
    out, P, m = mp.zeros(n, n), mp.eye(n), 0
    while True:
        term = P * (mp.mpf(-1) ** m / mp.factorial(m + 1))
        out += term
        if m > 5 and mp.mnorm(term, 1) < mp.mpf(10) ** (-DIGITS - 5):
            return out
        P, m = P * A, m + 1


def log_by_newton(X, start, hat, ad):
    """argmin_ξ |expm(ξ^) - X|_F by Gauss-Newton from ``start``: d expm(ξ^)[δ] = expm(ξ^) (Φ(ξ) δ)^."""
    xi = M(start)
    n = len(xi)
    for _ in range(8):
        E = mp.expm(hat(xi))
        r = flat(E - X)
        J = series_jr(ad(xi))
        cols = []
        for k in range(n):
            d = [J[i, k] for i in range(n)]
            cols.append(flat(E * hat(d)))
        A = mp.matrix([[cols[k][i] for k in range(n)] for i in range(len(r))])
        step = mp.lu_solve(A.T * A, -(A.T * mp.matrix(r)))
        xi = xi + step
        if mp.norm(step) < mp.mpf(10) ** (-DIGITS + 5):
            break
    return [xi[i] for i in range(n)]


def Ad_conjugation(T):
    Ti = mp.inverse(T)
    A = mp.zeros(6, 6)
    for k in range(6):
        e = [0] * 6
        e[k] = 1
        col = vee6(T * hat6(e) * Ti)
        for i in range(6):
            A[i, k] = col[i]
    return A


def flat(X):
    if isinstance(X, list):
        return X
    return [X[i, j] for i in range(X.rows) for j in range(X.cols)]


KERNELS = {
    "se3.so3_exp": lambda a: (g.so3_exp(_phi(a)), mp.expm(hat3(M(_phi(a))))),
    "se3.so3_log(so3_exp)": lambda a: (lambda R: (g.so3_log(R), log_by_newton(M(R), _phi(a), hat3, ad3)))(g.so3_exp(_phi(a))),
    "se3.se3_exp": lambda a: (g.se3_exp(_xi(a)), mp.expm(hat6(M(_xi(a))))),
    "se3.se3_log(se3_exp)": lambda a: (lambda T: (g.se3_log(T), log_by_newton(M(T), _xi(a), hat6, ad6)))(g.se3_exp(_xi(a))),
    "se3.se3_inverse(se3_exp)": lambda a: (lambda T: (g.se3_inverse(T), mp.inverse(M(T))))(g.se3_exp(_xi(a))),
    "se3.se3_adjoint(se3_exp)": lambda a: (lambda T: (g.se3_adjoint(T), Ad_conjugation(M(T))))(g.se3_exp(_xi(a))),
    "se3.se3_ad": lambda a: (g.se3_ad(_xi(a)), ad6(M(_xi(a)))),
    "se3.right_jacobian": lambda a: (g.right_jacobian(_xi(a)), jr_series(M(_xi(a)))),
    "se3.right_jacobian_inv": lambda a: (g.right_jacobian_inv(_xi(a)), mp.inverse(jr_series(M(_xi(a))))),
}


@pytest.mark.parametrize("name", list(KERNELS))
def test_se3_kernel_accuracy(name, accuracy_table):
    case = KERNELS[name]
    worst = (0.0, None, None)
    failures = []
    with mp.workdps(DIGITS):
        for a in ANGLES:
            got, true = case(a)
            got = np.asarray(got, dtype=float).ravel()
            true = flat(true)
            assert got.size == len(true), (name, got.size, len(true))
            for k, (x, t) in enumerate(zip(got, true)):
                rel = float(abs(mp.mpf(x) - t) / max(abs(t), ZERO_FLOOR)) if math.isfinite(x) else math.inf
                if rel > worst[0]:
                    worst = (rel, f"[{k}]", a)
                if not rel <= REL_TOL:
                    failures.append(f"{name} entry [{k}] at |φ| = {a!r}: computed {x!r}, true {mp.nstr(t, 20)}, rel. {rel:.2e}")
    accuracy_table[name] = worst
    print(f"\n{name}: max relative error {worst[0]:.3e} (entry {worst[1]}, angle {worst[2]!r})")
    assert not failures, f"{len(failures)} entries above {REL_TOL:g} relative:\n" + "\n".join(failures[:25])


def test_hat_vee_are_exact():
    xi = _xi(0.7)
    H = g.se3_hat(xi)
    assert np.array_equal(g.se3_vee(H), xi)
    assert np.array_equal(H[:3, 3], RHO) and np.array_equal(H[:3, :3], -H[:3, :3].T)
    assert np.array_equal(g.so3_vee(g.so3_hat(_phi(0.7))), _phi(0.7))
    assert np.array_equal(g.so3_hat(np.array([1.0, 2.0, 3.0])) @ np.array([4.0, 5.0, 6.0]),
                          np.cross([1.0, 2.0, 3.0], [4.0, 5.0, 6.0]))


@pytest.mark.parametrize("axis", [np.array([1.0, 0.0, 0.0]), np.array([0.0, -1.0, 0.0]), np.array([0.0, 0.0, 1.0]), AXIS])
@pytest.mark.parametrize("gap", [1e-3, 1e-6, 1e-9, 1e-12, 0.0])
def test_log_near_pi_round_trip(axis, gap):
    """|φ| = π - gap (the symmetric-part branch; gap = 0: the float π, whose log may be ±φ): exp(log R) = R and,
    for gap > 0, log(exp φ) = φ to 1e-13 relative (|φ| ≈ π, the branch makes the axis exact)."""
    phi = (math.pi - gap) * axis
    R = g.so3_exp(phi)
    back = g.so3_log(R)
    assert np.abs(g.so3_exp(back) - R).max() <= 1e-15
    if gap > 0:
        assert np.abs(back - phi).max() <= 1e-13 * math.pi
    T = g.se3_exp(np.concatenate([RHO, phi]))
    assert np.abs(g.se3_exp(g.se3_log(T)) - T).max() <= 1e-14
