"""SE(3), the rigid-body motions of space, as a matrix Lie group, symbolically (SymPy).

Conventions (as for SE(2) in ``derive.lie.groups``):

* tangent order ξ = (ρ, φ): ρ = (x, y, z) the translational part first, then the rotation vector φ = (φx, φy, φz);
  ξ^ = [[φ^, ρ], [0, 0]] (4×4), group elements are homogeneous 4×4 matrices T = [[R, t], [0, 1]];
* perturbations act on the right, T = μ · exp(ε^);
* ``right_jacobian`` is Φ(ξ) = Σ_m (-1)^m/(m+1)! ad(ξ)^m, the Jacobian with log(exp(-ξ) exp(ξ + δ)) = Φ(ξ) δ + O(|δ|²).
  In Barfoot's notation (*State Estimation for Robotics*, §7.1.5, whose ξ is also (ρ, φ)) this is his left
  Jacobian of -ξ: Φ(ξ) = J_l(-ξ) = [[J_r(φ), Q_r(ρ, φ)], [0, J_r(φ)]] with Q_r(ρ, φ) = Q_l(-ρ, -φ),

      Q_l(ρ, φ) = ρ^/2 + A (φ^ρ^ + ρ^φ^ + φ^ρ^φ^) + B (φ^φ^ρ^ + ρ^φ^φ^ - 3 φ^ρ^φ^) + C (φ^ρ^φ^φ^ + φ^φ^ρ^φ^),

  A = sinc3(t) = (t - sin t)/t³, B = cosc4(t) = (t²/2 + cos t - 1)/t⁴, C = sincos5(t) = (2t - 3 sin t + t cos t)/(2t⁵),
  t = |φ| (Barfoot eq. 7.86). Φ^-1 = [[J_r^-1, -J_r^-1 Q_r J_r^-1], [0, J_r^-1]].
  (Solà's and manif's ρ/φ order and right Jacobian are the same, Sophus's order too; GTSAM's Pose3 puts φ first.)

Closed forms: exp(ξ) = [[exp_SO(3)(φ), V(φ) ρ], [0, 1]], V = J_l(φ) = I + cosc2(t) φ^ + sinc3(t) φ^²;
log(T) = (V(φ)^-1 t, φ) with φ = log_SO(3)(R) (accurate up to |φ| = π, see ``derive.lie.so3``) and
V^-1 = I - φ^/2 + halfcot2(t) φ^²; Ad(T) = [[R, t^ R], [0, R]]; ad(ξ) = [[φ^, ρ^], [0, φ^]].
"""

from __future__ import annotations

import sympy as sp

from .first_principles import SeriesDerivations
from .so3 import SO3, angle_of_norm, skew, so3_angle
from .special import cosc4, sinc3, sincos5

__all__ = ["SE3", "q_left"]


def q_left(rho, phi) -> sp.Matrix:
    """Barfoot's Q_l(ρ, φ) (eq. 7.86), the upper-right block of the left Jacobian J_l(ξ) of SE(3), t = |φ|."""
    t = angle_of_norm(phi)
    P, Rh = skew(phi), skew(rho)
    PR, RP, PRP = P * Rh, Rh * P, P * Rh * P
    return (Rh / 2 + sinc3(t) * (PR + RP + PRP) + cosc4(t) * (P * PR + RP * P - 3 * PRP)
            + sincos5(t) * (PRP * P + P * PRP))


def _blocks(A, B, C) -> sp.Matrix:
    """[[A, B], [0, C]] (3×3 blocks)."""
    return sp.Matrix(sp.BlockMatrix([[A, B], [sp.zeros(3), C]]))


class SE3(SeriesDerivations):
    """The rigid-body motion group SE(3) = {[[R, t], [0, 1]]}, tangent order (x, y, z, φx, φy, φz)."""

    dim = 6
    matrix_size = 4
    #: the exponential's directional limits through |φ| take minutes in SymPy: first derivatives at ε = 0 use
    #: exp(ε) = I + ε^∧ + O(|ε|²) (``MotionModel.perturbed_mean``)
    exact_limits = False

    @staticmethod
    def periodic_coordinates():
        """The rotation-vector coordinates (3, 4, 5): exp is periodic along φ (period 2π in |φ|)."""
        return (3, 4, 5)

    @staticmethod
    def split(xi):
        """(ρ, φ) of ξ = (x, y, z, φx, φy, φz)."""
        xi = list(xi)
        return xi[:3], xi[3:]

    # --- definitions --------------------------------------------------------------------------------
    @classmethod
    def hat(cls, xi) -> sp.Matrix:
        """[ρ, φ]^ = [[φ^, ρ], [0, 0]] (4×4)."""
        rho, phi = cls.split(xi)
        M = sp.zeros(4, 4)
        M[:3, :3] = skew(phi)
        M[:3, 3] = sp.Matrix(rho)
        return M

    @staticmethod
    def vee(M: sp.Matrix) -> sp.Matrix:
        """[M]^∨ = (M[0, 3], M[1, 3], M[2, 3], M[2, 1], M[0, 2], M[1, 0])."""
        return sp.Matrix([M[0, 3], M[1, 3], M[2, 3], M[2, 1], M[0, 2], M[1, 0]])

    @staticmethod
    def element(R: sp.Matrix, t) -> sp.Matrix:
        """The homogeneous matrix [[R, t], [0, 1]]."""
        T = sp.eye(4)
        T[:3, :3] = R
        T[:3, 3] = sp.Matrix(t)
        return T

    @classmethod
    def inverse(cls, T: sp.Matrix) -> sp.Matrix:
        """[[R, t], [0, 1]]^-1 = [[R^T, -R^T t], [0, 1]]."""
        R = T[:3, :3]
        return cls.element(R.T, -R.T * T[:3, 3])

    # --- closed forms (emitted by the code generator) ---------------------------------------------
    V = staticmethod(SO3.left_jacobian)
    V_inv = staticmethod(SO3.left_jacobian_inv)

    @classmethod
    def exp(cls, xi) -> sp.Matrix:
        """exp_SE(3)([ρ, φ]^) = [[exp_SO(3)(φ), V(φ) ρ], [0, 1]], V = I + cosc2(t) φ^ + sinc3(t) φ^²."""
        rho, phi = cls.split(xi)
        return cls.element(SO3.exp(phi), cls.V(phi) * sp.Matrix(rho))

    @classmethod
    def log(cls, T: sp.Matrix, t=None, phi=None) -> sp.Matrix:
        """[log_SE(3)(T)]^∨ = (V(φ)^-1 t, φ), φ = log_SO(3)(R) (``derive.lie.so3``), V^-1 = I - φ^/2 + halfcot2 φ^².

        ``t``, ``phi``: the rotation angle and vector when already computed (symbols in the generated kernel).
        """
        R = T[:3, :3]
        t = so3_angle(R) if t is None else t
        phi = list(SO3.log(R, t)) if phi is None else list(phi)
        rho = cls.V_inv(phi, t) * T[:3, 3]
        return sp.Matrix(list(rho) + phi)

    @staticmethod
    def Ad(T: sp.Matrix) -> sp.Matrix:
        """Ad_SE(3)(T) = [[R, t^ R], [0, R]]."""
        R = T[:3, :3]
        return _blocks(R, skew(T[:3, 3]) * R, R)

    @classmethod
    def ad(cls, xi) -> sp.Matrix:
        """ad_SE(3)(ρ, φ) = [[φ^, ρ^], [0, φ^]]."""
        rho, phi = cls.split(xi)
        return _blocks(skew(phi), skew(rho), skew(phi))

    @classmethod
    def q_right(cls, xi) -> sp.Matrix:
        """Q_r(ρ, φ) = Q_l(-ρ, -φ): the upper-right block of Φ(ξ)."""
        rho, phi = cls.split(xi)
        return q_left([-e for e in rho], [-e for e in phi])

    @classmethod
    def right_jacobian(cls, xi) -> sp.Matrix:
        """Φ_SE(3)(ξ) = [[J_r(φ), Q_r(ρ, φ)], [0, J_r(φ)]]; log(exp(-ξ) exp(ξ + δ)) ≈ Φ(ξ) δ."""
        _, phi = cls.split(xi)
        J = SO3.right_jacobian(phi)
        return _blocks(J, cls.q_right(xi), J)

    @classmethod
    def right_jacobian_inv(cls, xi) -> sp.Matrix:
        """Φ_SE(3)(ξ)^-1 = [[J_r^-1, -J_r^-1 Q_r J_r^-1], [0, J_r^-1]]."""
        _, phi = cls.split(xi)
        Ji = SO3.right_jacobian_inv(phi)
        return _blocks(Ji, -Ji * cls.q_right(xi) * Ji, Ji)
