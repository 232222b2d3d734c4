"""First-principles versions of a matrix Lie group's quantities (``derived_*``), shared by SE(2), SO(3) and SE(3).

The closed forms that the generator emits are checked against these (tests/derive/test_groups.py, test_lie3.py):
Ad(X) from its definition Ad(X) v = [X v^ X^-1]^∨, ad(a) from the Lie bracket ad(a) b = [a^ b^ - b^ a^]^∨, and,
for numeric tangents, the matrix exponential and the right Jacobian Φ(ξ) = Σ_m (-1)^m/(m+1)! ad(ξ)^m by their series.
A group class mixes these in and provides ``dim``, ``hat``, ``vee`` and ``inverse``.
"""

from __future__ import annotations

import sympy as sp

__all__ = ["matrix_series", "FirstPrinciples", "SeriesDerivations"]


def matrix_series(M: sp.Matrix, coefficient, tol_digits: int = 60, max_terms: int = 400) -> sp.Matrix:
    """Σ_m coefficient(m) M^m for a numeric M, summed until a term is below 10^-tol_digits."""
    out = sp.zeros(*M.shape)
    P = sp.eye(M.shape[0])
    tol = sp.Float(10) ** (-tol_digits)
    exact = all(e.is_Rational for e in M)
    for m in range(max_terms):
        term = coefficient(m) * P
        out += term
        if m > 4 and max(abs(e) for e in term) < tol:
            return out
        P = P * M if exact else (P * M).evalf(tol_digits + 20)
    raise ValueError("matrix series did not converge")


class FirstPrinciples:
    """derived_Ad (conjugation) and derived_ad (bracket), for any group class with dim, hat, vee, inverse."""

    @classmethod
    def derived_Ad(cls, X: sp.Matrix) -> sp.Matrix:
        """Ad(X) from its definition Ad(X) v = [X v^ X^-1]^∨."""
        v = sp.Matrix(sp.symbols(f"_v0:{cls.dim}", real=True))
        w = cls.vee(X * cls.hat(v) * cls.inverse(X))
        return w.jacobian(v).applyfunc(sp.expand)

    @classmethod
    def derived_ad(cls, xi) -> sp.Matrix:
        """ad(a) b = [a^ b^ - b^ a^]^∨ (the Lie bracket)."""
        b = sp.Matrix(sp.symbols(f"_b0:{cls.dim}", real=True))
        A, B = cls.hat(xi), cls.hat(b)
        return cls.vee(A * B - B * A).jacobian(b).applyfunc(sp.expand)


class SeriesDerivations(FirstPrinciples):
    """derived_exp and derived_right_jacobian by their series, for numeric tangents (rationals or Floats)."""

    @classmethod
    def derived_exp(cls, xi, digits: int = 60) -> sp.Matrix:
        """Σ_m (ξ^)^m / m! (the matrix exponential by its series)."""
        return matrix_series(cls.hat(xi), lambda m: sp.Rational(1, sp.factorial(m)), digits)

    @classmethod
    def derived_right_jacobian(cls, xi, digits: int = 60) -> sp.Matrix:
        """Σ_m (-1)^m/(m+1)! ad(ξ)^m (the series of ∫_0^1 exp(-s ad) ds)."""
        return matrix_series(cls.derived_ad(xi), lambda m: sp.Rational((-1) ** m, sp.factorial(m + 1)), digits)
