"""SE(2), R^n and their direct products as matrix Lie groups, symbolically (SymPy); SO(3) and SE(3) live in
``derive.lie.so3`` and ``derive.lie.se3`` and are re-exported here.

Conventions (used everywhere in lgekf):

* SE(2) tangent vectors are ordered ``(x, y, θ)``: translational part first, angle last; SE(3)'s
  ``(x, y, z, φx, φy, φz)``: translation ρ first, then the rotation vector φ.
* ``hat``/``vee`` are the paper's ``[·]^∧_G`` and ``[·]^∨_G``.
* Perturbations act on the right: ``X = μ · exp(ε^∧)`` (the paper's concentrated Gaussian).
* ``right_jacobian`` is the paper's Φ_G(v) = Σ_m (-1)^m/(m+1)! ad_G(v)^m, i.e. the Jacobian with
  ``log(exp(-v) exp(v + δ)) = Φ_G(v) δ + O(|δ|^2)``.

Each group offers two kinds of functions: the *closed forms* written with the angle functions of
``derive.special`` (the forms the code generator emits), and ``derived_*`` functions that obtain
the same quantity from first principles (matrix exponential, definition of Ad by conjugation,
the Lie bracket, the series of Φ summed as ∫_0^1 exp(-s ad) ds).  ``derive.verify`` compares the paper's printed
equations with them, and ``tests/derive/test_groups.py`` checks symbolically that closed and derived forms agree
(exp, Ad, ad, Φ, Φ·Φ^-1 = I, exp∘log).
"""

from __future__ import annotations

import sympy as sp

from .first_principles import FirstPrinciples
from .se3 import SE3
from .so3 import SO3
from .special import cosc, cosc2, halfcot, halfcot1, sinc, sinc2

__all__ = ["SE2", "SO3", "SE3", "Rn", "Product", "so2_log"]


def so2_log(R: sp.Matrix):
    """θ = log_SO(2)(R) = atan2(R_21, R_11) ∈ (-π, π] (paper, log_SE(2))."""
    return sp.atan2(R[1, 0], R[0, 0])


def _rot(c, s) -> sp.Matrix:
    return sp.Matrix([[c, -s], [s, c]])


class SE2(FirstPrinciples):
    """The rigid-body motion group SE(2) = {[[R, t], [0, 1]]}, tangent order (x, y, θ)."""

    dim = 3
    matrix_size = 3
    #: the exponential's directional limits at ε = 0 are quick in SymPy (``MotionModel.perturbed_mean``)
    exact_limits = True

    @staticmethod
    def periodic_coordinates():
        """Tangent coordinates in which exp is periodic (the rotation angle θ)."""
        return (2,)

    # --- definitions (paper, Section "The SE(2) group") -----------------------------------
    @staticmethod
    def hat(xi) -> sp.Matrix:
        """[x y θ]^∧ = [[0, -θ, x], [θ, 0, y], [0, 0, 0]]."""
        x, y, th = xi
        return sp.Matrix([[0, -th, x], [th, 0, y], [0, 0, 0]])

    @staticmethod
    def vee(M: sp.Matrix) -> sp.Matrix:
        return sp.Matrix([M[0, 2], M[1, 2], M[1, 0]])

    @staticmethod
    def element(c, s, tx, ty) -> sp.Matrix:
        """The group element with rotation (cos, sin) = (c, s) and translation (tx, ty)."""
        return sp.Matrix([[c, -s, tx], [s, c, ty], [0, 0, 1]])

    @staticmethod
    def inverse(T: sp.Matrix) -> sp.Matrix:
        """[[R, t], [0, 1]]^-1 = [[R^T, -R^T t], [0, 1]]."""
        R = T[:2, :2]
        t = T[:2, 2]
        Ri = R.T
        ti = -Ri * t
        return sp.Matrix([[Ri[0, 0], Ri[0, 1], ti[0]], [Ri[1, 0], Ri[1, 1], ti[1]], [0, 0, 1]])

    # --- closed forms (emitted by the code generator) -------------------------------------
    @staticmethod
    def V(th) -> sp.Matrix:
        """V(θ) with exp([ρ, θ]^∧) = [[R(θ), V(θ) ρ], [0, 1]]."""
        return sp.Matrix([[sinc(th), -cosc(th)], [cosc(th), sinc(th)]])

    @staticmethod
    def V_inv(th) -> sp.Matrix:
        """V(θ)^-1 = θ/(2(1 - cos θ)) [[sin θ, 1 - cos θ], [cos θ - 1, sin θ]] (paper, log_SE(2))."""
        return sp.Matrix([[halfcot(th), th / 2], [-th / 2, halfcot(th)]])

    @classmethod
    def exp(cls, xi) -> sp.Matrix:
        """exp_SE(2)([x y θ]^∧) (paper, exp_SE(2)); t = V(θ) [x, y]."""
        x, y, th = xi
        t = cls.V(th) * sp.Matrix([x, y])
        return cls.element(sp.cos(th), sp.sin(th), t[0], t[1])

    @classmethod
    def log(cls, T: sp.Matrix) -> sp.Matrix:
        """[log_SE(2)(T)]^∨ = [V(θ)^-1 t, θ] with θ = atan2(R_21, R_11)."""
        th = so2_log(T[:2, :2])
        rho = cls.V_inv(th) * T[:2, 2]
        return sp.Matrix([rho[0], rho[1], th])

    @staticmethod
    def Ad(T: sp.Matrix) -> sp.Matrix:
        """Ad_SE(2)(T) = [[R, J t], [0, 1]], J = [[0, 1], [-1, 0]] (paper, Ad_SE(2))."""
        return sp.Matrix([[T[0, 0], T[0, 1], T[1, 2]], [T[1, 0], T[1, 1], -T[0, 2]], [0, 0, 1]])

    @staticmethod
    def ad(xi) -> sp.Matrix:
        """ad_SE(2)([x y θ]) = [[-θ J, J v], [0, 0]] (paper prints a 1 in the corner: erratum)."""
        x, y, th = xi
        return sp.Matrix([[0, -th, y], [th, 0, -x], [0, 0, 0]])

    @staticmethod
    def right_jacobian(xi) -> sp.Matrix:
        """Φ_SE(2)(ξ) = Σ_m (-1)^m/(m+1)! ad(ξ)^m in closed form (paper, eq. for Φ_G)."""
        x, y, th = xi
        return sp.Matrix(
            [
                [sinc(th), cosc(th), x * sinc2(th) - y * cosc2(th)],
                [-cosc(th), sinc(th), x * cosc2(th) + y * sinc2(th)],
                [0, 0, 1],
            ]
        )

    @staticmethod
    def right_jacobian_inv(xi) -> sp.Matrix:
        """Φ_SE(2)(ξ)^-1 in closed form."""
        x, y, th = xi
        h, h1 = halfcot(th), halfcot1(th)
        return sp.Matrix([[h, -th / 2, x * h1 + y / 2], [th / 2, h, -x / 2 + y * h1], [0, 0, 1]])

    # --- first-principles derivations (checked against the closed forms) -----------------
    @classmethod
    def derived_exp(cls, xi) -> sp.Matrix:
        """The matrix exponential of ξ^∧, computed by SymPy (Jordan form), simplified."""
        M = cls.hat(xi).exp()
        return M.applyfunc(lambda e: sp.simplify(sp.expand_complex(e)))

    @classmethod
    def derived_right_jacobian(cls, xi) -> sp.Matrix:
        """Σ_m (-1)^m/(m+1)! ad^m = ∫_0^1 exp(-s ad) ds, integrated by SymPy."""
        s = sp.Symbol("_s", real=True)
        E = (-s * cls.derived_ad(xi)).exp().applyfunc(lambda e: sp.simplify(sp.expand_complex(e)))
        out = E.applyfunc(lambda e: sp.integrate(e, (s, 0, 1)))
        # SymPy returns Piecewise((f, θ != 0), (f0, True)); keep the generic branch
        return out.applyfunc(lambda e: e.args[0][0] if isinstance(e, sp.Piecewise) else e)

    @classmethod
    def right_jacobian_series(cls, xi, order: int) -> sp.Matrix:
        """The paper's series Σ_{m=0}^{order} (-1)^m/(m+1)! ad^m, truncated."""
        ad = cls.derived_ad(xi)
        out = sp.zeros(3, 3)
        P = sp.eye(3)
        for m in range(order + 1):
            out += sp.Rational((-1) ** m, sp.factorial(m + 1)) * P
            P = P * ad
        return out


class Rn:
    """R^n as a matrix Lie group: v ↦ [[I, v], [0, 1]] (the paper's G' for measurements, and R^3)."""

    def __init__(self, n: int):
        self.dim = n
        self.exact_limits = True  # exp is I + ε^∧ exactly
        self.matrix_size = n + 1

    def periodic_coordinates(self):
        """None: exp is injective on Rⁿ."""
        return ()

    def hat(self, v) -> sp.Matrix:
        n = self.dim
        M = sp.zeros(n + 1, n + 1)
        for i in range(n):
            M[i, n] = v[i]
        return M

    def vee(self, M: sp.Matrix) -> sp.Matrix:
        return sp.Matrix([M[i, self.dim] for i in range(self.dim)])

    def exp(self, v) -> sp.Matrix:
        return sp.eye(self.dim + 1) + self.hat(v)

    def log(self, M: sp.Matrix) -> sp.Matrix:
        return self.vee(M)

    def inverse(self, M: sp.Matrix) -> sp.Matrix:
        return sp.eye(self.dim + 1) - self.hat(self.vee(M))

    def Ad(self, M: sp.Matrix) -> sp.Matrix:
        return sp.eye(self.dim)

    def ad(self, v) -> sp.Matrix:
        return sp.zeros(self.dim, self.dim)

    def right_jacobian(self, v) -> sp.Matrix:
        return sp.eye(self.dim)

    def right_jacobian_inv(self, v) -> sp.Matrix:
        return sp.eye(self.dim)


class _GroupInstance:
    """A group given as a class of static/class methods (SE2, SO3, SE3) with the instance interface of Rn, so that
    Product can hold either."""

    def __init__(self, cls):
        self._cls = cls
        self.dim = cls.dim
        self.matrix_size = cls.matrix_size

    def __getattr__(self, name):
        return getattr(self._cls, name)


class Product:
    """Direct product G_1 × G_2 × ...: block-diagonal hat, exp, log, Ad, ad, Φ (paper, SE(2)^2 section).

    Factors: SE2, SO3, SE3 (the classes), Rn(k) instances, or other Products (nested products are flattened).
    The tangent is the concatenation of the factors' tangents, in order.
    """

    def __init__(self, *factors):
        flat = []
        for f in factors:
            flat.extend(f.factors if isinstance(f, Product) else [f])
        self.factors = [(_GroupInstance(f) if isinstance(f, type) else f) for f in flat]
        self.dim = sum(f.dim for f in self.factors)
        self.exact_limits = all(f.exact_limits for f in self.factors)

    @property
    def matrix_size(self):
        return sum(f.matrix_size for f in self.factors)

    def periodic_coordinates(self):
        """The periodic tangent coordinates of every factor, offset to their place in the product."""
        out, i = [], 0
        for f in self.factors:
            out.extend(i + k for k in f.periodic_coordinates())
            i += f.dim
        return tuple(out)

    def _split(self, xi):
        out, i = [], 0
        for f in self.factors:
            out.append(list(xi[i : i + f.dim]))
            i += f.dim
        return out

    def _split_matrix(self, X):
        out, i = [], 0
        for f in self.factors:
            m = f.matrix_size
            out.append(X[i : i + m, i : i + m])
            i += m
        return out

    def hat(self, xi):
        return sp.diag(*[f.hat(p) for f, p in zip(self.factors, self._split(xi))])

    def vee(self, M):
        return sp.Matrix.vstack(*[f.vee(B) for f, B in zip(self.factors, self._split_matrix(M))])

    def exp(self, xi):
        return sp.diag(*[f.exp(p) for f, p in zip(self.factors, self._split(xi))])

    def log(self, X):
        return sp.Matrix.vstack(*[f.log(B) for f, B in zip(self.factors, self._split_matrix(X))])

    def inverse(self, X):
        return sp.diag(*[f.inverse(B) for f, B in zip(self.factors, self._split_matrix(X))])

    def Ad(self, X):
        return sp.diag(*[f.Ad(B) for f, B in zip(self.factors, self._split_matrix(X))])

    def ad(self, xi):
        return sp.diag(*[f.ad(p) for f, p in zip(self.factors, self._split(xi))])

    def right_jacobian(self, xi):
        return sp.diag(*[f.right_jacobian(p) for f, p in zip(self.factors, self._split(xi))])

    def right_jacobian_inv(self, xi):
        return sp.diag(*[f.right_jacobian_inv(p) for f, p in zip(self.factors, self._split(xi))])
