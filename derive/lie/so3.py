"""SO(3), the rotations of space, as a matrix Lie group, symbolically (SymPy).

Conventions (the same as SE(2)'s in ``derive.lie.groups`` and SE(3)'s in ``derive.lie.se3``):

* the tangent vector is the rotation vector φ = (φx, φy, φz), with angle t = |φ| and hat
  φ^ = [[0, -φz, φy], [φz, 0, -φx], [-φy, φx, 0]] (φ^ v = φ × v);
* perturbations act on the right, R = μ · exp(ε^);
* ``right_jacobian`` is J_r(φ) = Σ_m (-1)^m/(m+1)! ad(φ)^m = ∫_0^1 exp(-s φ^) ds, i.e. the Jacobian with
  log(exp(-φ) exp(φ + δ)) = J_r(φ) δ + O(|δ|²); it equals Barfoot's left Jacobian of -φ.

Closed forms (Barfoot, *State Estimation for Robotics*, §7.1; Solà et al., *A micro Lie theory*, App. B), with
the angle functions of ``derive.lie.special`` evaluated at t = |φ| (Taylor branches near 0):

* exp(φ) = I + sinc(t) φ^ + cosc2(t) φ^²                 (Rodrigues),
* J_r(φ) = I - cosc2(t) φ^ + sinc3(t) φ^²,   J_r(φ)^-1 = I + φ^/2 + halfcot2(t) φ^²,
* J_l(φ) = J_r(-φ) = I + cosc2(t) φ^ + sinc3(t) φ^²  (the V of exp_SE(3)),  J_l(φ)^-1 = I - φ^/2 + halfcot2(t) φ^².

log: the angle t = atan2(|a|, (tr R - 1)/2) from the antisymmetric part a = [(R - R^T)/2]^∨ = sin t · u (accurate
for every t, unlike acos of the trace), then

* cos t >= 0: φ = a / sinc(t) (the antisymmetric part holds the axis with full relative accuracy);
* cos t < 0: the symmetric part S = (R + R^T)/2 - cos t · I = (1 - cos t) u u^T gives the axis: its column k of
  largest diagonal entry, u = sign(a_k) S[:, k] / √(S_kk (1 - cos t)), φ = t u.  Near t = π the antisymmetric
  part is ~ sin t and has lost the axis to rounding; the symmetric part has not.  At t = π exactly (a = 0) the
  sign is +, one of the two logs ±π u.

The ``derived_*`` functions (``derive.lie.first_principles``) obtain the same quantities from first principles (the
matrix exponential series, Ad by conjugation, ad by the bracket, Φ by its series); the exp/Φ series take numeric
tangents (exact rationals or high-precision Floats). ``tests/derive/test_lie3.py`` compares them with the closed forms.
"""

from __future__ import annotations

import sympy as sp

from .first_principles import SeriesDerivations
from .special import cosc2, halfcot2, sinc, sinc3

__all__ = ["SO3", "skew", "angle_of_norm", "quadratic_in_hat", "sin_axis_and_cos", "so3_angle", "so3_log_with_angle",
           "rotation_vector", "rotation_vector_entry", "orthonormal_reduce",
           "rotation_matrix", "rotation_matrix_entry"]


def skew(v) -> sp.Matrix:
    """v^ = [[0, -v3, v2], [v3, 0, -v1], [-v2, v1, 0]] (v^ w = v × w)."""
    x, y, z = v
    return sp.Matrix([[0, -z, y], [z, 0, -x], [-y, x, 0]])


def angle_of_norm(v):
    """t = |v| = √(v·v), the rotation angle of the rotation vector v."""
    return sp.sqrt(sum(e**2 for e in v))


def quadratic_in_hat(phi, first, second) -> sp.Matrix:
    """I + first · φ^ + second · φ^²: the shape of exp, J_l, J_r and their inverses (coefficients in t = |φ|)."""
    K = skew(phi)
    return sp.eye(3) + first * K + second * K * K


def sin_axis_and_cos(R: sp.Matrix):
    """(a, cos t): a = [(R - R^T)/2]^∨ = sin t · u (u the axis) and cos t = (tr R - 1)/2."""
    return SO3.vee((R - R.T) / 2), (R[0, 0] + R[1, 1] + R[2, 2] - 1) / 2


def so3_angle(R: sp.Matrix):
    """t = atan2(|a|, (tr R - 1)/2) ∈ [0, π], a = [(R - R^T)/2]^∨: the rotation angle, accurate for every t."""
    a, c = sin_axis_and_cos(R)
    return sp.atan2(angle_of_norm(a), c)


def so3_log_with_angle(R: sp.Matrix, t) -> sp.Matrix:
    """[log_SO(3)(R)]^∨ given its angle t = so3_angle(R) (a symbol in generated kernels): a Piecewise of the
    antisymmetric-part method (cos t >= 0) and the symmetric-part method (cos t < 0, near π); see the module."""
    a, c = sin_axis_and_cos(R)
    S = (R + R.T) / 2 - c * sp.eye(3)
    near_zero = a / sinc(t)

    def axis(k):
        sign = sp.Piecewise((1, a[k] >= 0), (-1, True))
        return t * sign * S[:, k] / sp.sqrt(S[k, k] * (1 - c))

    ax = [axis(k) for k in range(3)]
    first = sp.And(S[0, 0] >= S[1, 1], S[0, 0] >= S[2, 2])
    return sp.Matrix([
        sp.Piecewise((near_zero[i], c >= 0), (ax[0][i], first), (ax[1][i], S[1, 1] >= S[2, 2]), (ax[2][i], True))
        for i in range(3)
    ])


class SO3(SeriesDerivations):
    """The rotation group SO(3) = {R : R^T R = I, det R = 1}, tangent the rotation vector φ = (φx, φy, φz)."""

    dim = 3
    #: the exponential's directional limits through |φ| take minutes in SymPy: first derivatives at ε = 0 use
    #: exp(ε) = I + ε^∧ + O(|ε|²) (``MotionModel.perturbed_mean``)
    exact_limits = False
    matrix_size = 3

    @staticmethod
    def periodic_coordinates():
        """The rotation-vector coordinates (0, 1, 2): exp is periodic along φ (period 2π in |φ|), not per coordinate."""
        return (0, 1, 2)

    # --- definitions ------------------------------------------------------------------------------
    @staticmethod
    def hat(phi) -> sp.Matrix:
        """[φx φy φz]^ = [[0, -φz, φy], [φz, 0, -φx], [-φy, φx, 0]]."""
        return skew(phi)

    @staticmethod
    def vee(M: sp.Matrix) -> sp.Matrix:
        """[M]^∨ = (M[2, 1], M[0, 2], M[1, 0])."""
        return sp.Matrix([M[2, 1], M[0, 2], M[1, 0]])

    @staticmethod
    def inverse(R: sp.Matrix) -> sp.Matrix:
        """R^-1 = R^T."""
        return R.T

    # --- closed forms (emitted by the code generator) ---------------------------------------------
    @staticmethod
    def exp(phi) -> sp.Matrix:
        """exp(φ^) = I + sinc(t) φ^ + cosc2(t) φ^², t = |φ| (Rodrigues)."""
        t = angle_of_norm(phi)
        return quadratic_in_hat(phi, sinc(t), cosc2(t))

    @staticmethod
    def log(R: sp.Matrix, t=None) -> sp.Matrix:
        """[log_SO(3)(R)]^∨ ∈ {|φ| <= π}: angle from atan2, axis from the antisymmetric or (near π) symmetric part."""
        return so3_log_with_angle(R, so3_angle(R) if t is None else t)

    @staticmethod
    def Ad(R: sp.Matrix) -> sp.Matrix:
        """Ad_SO(3)(R) = R."""
        return sp.Matrix(R)

    @staticmethod
    def ad(phi) -> sp.Matrix:
        """ad_SO(3)(φ) = φ^."""
        return skew(phi)

    @staticmethod
    def left_jacobian(phi) -> sp.Matrix:
        """J_l(φ) = I + cosc2(t) φ^ + sinc3(t) φ^² = J_r(-φ): the V of exp_SE(3), translation V(φ) ρ."""
        t = angle_of_norm(phi)
        return quadratic_in_hat(phi, cosc2(t), sinc3(t))

    @staticmethod
    def left_jacobian_inv(phi, t=None) -> sp.Matrix:
        """J_l(φ)^-1 = I - φ^/2 + halfcot2(t) φ^² (t = |φ|, or the angle of log given as a symbol)."""
        t = angle_of_norm(phi) if t is None else t
        return quadratic_in_hat(phi, -sp.Rational(1, 2), halfcot2(t))

    @classmethod
    def right_jacobian(cls, phi) -> sp.Matrix:
        """J_r(φ) = J_l(-φ) = I - cosc2(t) φ^ + sinc3(t) φ^², log(exp(-φ) exp(φ + δ)) ≈ J_r(φ) δ."""
        return cls.left_jacobian([-e for e in phi])

    @classmethod
    def right_jacobian_inv(cls, phi) -> sp.Matrix:
        """J_r(φ)^-1 = J_l(-φ)^-1 = I + φ^/2 + halfcot2(t) φ^² (singular at |φ| = 2π)."""
        return cls.left_jacobian_inv([-e for e in phi])


class _ClosedFormFunction(sp.Function):
    """A real function kept unevaluated in derivations (its derivative given by ``fdiff``), evaluated numerically and
    printed through its ``closed_form``."""

    def closed_form(self):  # pragma: no cover - abstract
        raise NotImplementedError

    def _eval_evalf(self, prec):
        if all(a.is_number for a in self.args):
            return self.closed_form().evalf(prec)
        return None

    def _eval_is_real(self):
        return True


class rotation_vector_entry(_ClosedFormFunction):
    """φ_k = [log_SO(3)(R)]^∨_k (k = 0, 1, 2) of the rotation R given by its nine entries, row-major: (k, r11, ..., r33).

    Unevaluated, so that a derivation can differentiate a model through the log of a rotation it carries (SE(3)×SE(3)'s
    turn rate is the rotation vector of the velocity's rotation). Its derivative is the inverse right Jacobian: a right
    perturbation R·exp(δ^) moves the log by J_r(φ)^-1 δ (Barfoot, *State Estimation for Robotics*, §7.1.5; Solà et al.,
    *A micro Lie theory*, eq. 145). ``fdiff`` writes that for a direction dR of the nine entries as

        dφ = J_r(φ)^-1 · [(Rᵀ dR − dRᵀ R)/2]^∨        (the skew part of Rᵀ dR; exactly δ for dR = R δ^, RᵀR = I),

    with J_r(φ)^-1 = I + φ^/2 + halfcot2(|φ|) φ^² (Taylor branch near 0). It is the derivative along directions that
    keep R a rotation (dR = R δ^, what every derivation here differentiates along), not the derivative of the closed
    form along an arbitrary entry (which leaves the rotations: the log is not defined there). ``closed_form`` is
    ``SO3.log`` (the angle from atan2, the axis from the antisymmetric part or, near π, the symmetric part): what
    kernels compute. ``tests/derive/test_carried_rotations.py`` checks the derivative against finite differences of
    SciPy's rotation vector.
    """

    nargs = 10

    def _matrix(self) -> sp.Matrix:
        return sp.Matrix(3, 3, list(self.args[1:]))

    def fdiff(self, argindex=1):
        if argindex == 1:
            return sp.S.Zero
        R = self._matrix()
        i, j = divmod(argindex - 2, 3)
        E = sp.zeros(3, 3)
        E[i, j] = 1
        M = R.T * E
        d = SO3.right_jacobian_inv(rotation_vector(R)) * SO3.vee((M - M.T) / 2)
        return d[int(self.args[0])]

    def closed_form(self):
        """[SO3.log(R)]_k, printable (Piecewise of the two axis methods)."""
        return SO3.log(self._matrix())[int(self.args[0])]



def rotation_vector(R: sp.Matrix) -> sp.Matrix:
    """[log_SO(3)(R)]^∨ as three ``rotation_vector_entry`` (unevaluated, differentiable: the inverse right Jacobian)."""
    r = [R[i, j] for i in range(3) for j in range(3)]
    return sp.Matrix([rotation_vector_entry(k, *r) for k in range(3)])


def orthonormal_reduce(expr, entries):
    """``expr`` with RᵀR = I applied, R the rotation of the nine ``entries`` (row-major symbols).

    Differentiating the log of a right-perturbed rotation R·(I + δ^) through ``rotation_vector_entry`` gives
    J_r(φ)^-1 [(RᵀR δ^ − δ^ᵀRᵀR)/2]^∨, which is J_r(φ)^-1 δ only once RᵀR = I is used. Written as a polynomial in the
    entries, each coefficient (a function of the other symbols) must multiply whole Gram entries
    g_ij = Σ_k r_ki r_kj, the inner products of R's columns; then the polynomial is Σ c_ij g_ij = Σ_i c_ii. An
    expression that is not of that form is returned unchanged.
    """
    r = list(entries)
    R = sp.Matrix(3, 3, r)
    original = sp.sympify(expr)
    if not original.free_symbols & set(r):
        return original
    expr = sp.expand(original)
    try:
        poly = sp.Poly(expr, *r)
    except sp.PolynomialError:  # the entries inside a function: not a polynomial in them
        return original
    if poly.total_degree() != 2 or any(sum(m) not in (0, 2) for m in poly.monoms()):
        return original
    constant = poly.coeff_monomial(1)
    reduced, rebuilt = constant, constant
    for i in range(3):
        for j in range(i, 3):
            c = poly.coeff_monomial(R[0, i] * R[0, j])
            g = sum(R[k, i] * R[k, j] for k in range(3))
            rebuilt += c * g
            reduced += c if i == j else 0
    return reduced if sp.expand(rebuilt - expr) == 0 else original


class rotation_matrix_entry(_ClosedFormFunction):
    """[exp_SO(3)(φ^)]_ij (i, j, φx, φy, φz), unevaluated, so that a derivation can differentiate a rotation built from
    a rotation vector without dividing by |φ|.

    Its derivative is the right Jacobian: exp((φ + dφ)^) = exp(φ^)·exp((J_r(φ) dφ)^) to first order (Barfoot,
    *State Estimation for Robotics*, §7.1.5), so ∂R/∂φ_k = R·(J_r(φ) e_k)^ with J_r(φ) = I − cosc2(|φ|) φ^ +
    sinc3(|φ|) φ^² (Taylor branches near 0), where differentiating the closed form of exp through |φ| would print
    sinc'(|φ|)·φ_k/|φ|, 0/0 at φ = 0. ``closed_form`` is ``SO3.exp``.
    """

    nargs = 5

    def fdiff(self, argindex=1):
        if argindex <= 2:
            return sp.S.Zero
        i, j = int(self.args[0]), int(self.args[1])
        phi = list(self.args[2:])
        R = rotation_matrix(phi)
        return (R * skew(SO3.right_jacobian(phi)[:, argindex - 3]))[i, j]

    def closed_form(self):
        """[SO3.exp(φ)]_ij."""
        return SO3.exp(list(self.args[2:]))[int(self.args[0]), int(self.args[1])]



def rotation_matrix(phi) -> sp.Matrix:
    """exp_SO(3)(φ^) as nine ``rotation_matrix_entry`` (unevaluated, differentiable: the right Jacobian)."""
    return sp.Matrix(3, 3, lambda i, j: rotation_matrix_entry(i, j, *phi))
