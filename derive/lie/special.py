"""Angle functions with a removable singularity at 0: the building blocks of every SE(2), SO(3) and SE(3) formula.

Every closed form in this project (exp, log, the right Jacobian Φ and its inverse, the CTRV motion)
is written with a handful of functions of one angle ``x`` that are analytic at ``x = 0`` but are
*printed* with a division by ``x`` (``sin x / x``, ``(1 - cos x) / x`` ...).  Evaluating those
printed forms near ``x = 0`` loses accuracy (cancellation) or divides by zero, so each one is a
SymPy ``Function`` here with

* ``definition(x)``: the exact expression (what the paper or the derivation prints),
* a Taylor series at 0 (computed by SymPy from the definition, never typed by hand),
* a cancellation-free closed form used away from 0 (checked equal to the definition), and
* a threshold ``tau``: below ``|x| < tau`` the generated kernel evaluates the Taylor polynomial.

The thresholds were chosen by measurement (``python -m lgekf.derive.lie.thresholds``): ``tau`` is
(rounded up from) the smallest angle above which the float64 closed form stays within 4 ulp of a
50-digit mpmath reference (measured: sinc2 0.70, dsinc 0.66, halfcot1 0.96 but up to 7 ulp until 1.4,
so 1.5 is used; the others are exact
down to 1e-6 and only x = 0 needs the series), and the Taylor order is one whose truncation error at
``tau`` is below 1e-17 relative.  The functions of the SO(3)/SE(3) angle t = |φ| cancel more (their numerators
vanish to order 3 to 5), also measured on a uniform 300-point grid of [0.5, π] (``fine_scan``; the last angle above
4 ulp): sinc3 0.69 (6.9 ulp below it), so 0.75; halfcot2 1.33 (7.1 ulp at 1.01), so 1.5; cosc4 1.42, and on an
800-point grid 5.1 ulp at 1.51 and 4.5 at 1.56, so 1.6; sincos5 2.01 (its closed form loses ~360 ulp / t⁴; 5.6 ulp
at 2.015), so 2.1.  Above these the closed forms stay within ~4 ulp up to π.  ``tests/derive/test_special_accuracy.py`` checks both sides of every threshold.

Generated kernels call these functions as ``f(x, s, c)`` with ``s = sin x`` and ``c = cos x``
computed once per angle, so a step needs one sincos per distinct angle.
"""

from __future__ import annotations

from functools import lru_cache

import sympy as sp

__all__ = [
    "AngleFunction",
    "sinc",
    "cosc",
    "sinc2",
    "cosc2",
    "dsinc",
    "halfcot",
    "halfcot1",
    "sinc3",
    "cosc4",
    "sincos5",
    "halfcot2",
    "ANGLE_FUNCTIONS",
    "to_exact",
    "taylor_coefficients",
]


class AngleFunction(sp.Function):
    """f(x), analytic at x = 0, printed with a removable singularity there.

    Subclasses set ``parity`` (+1 even, -1 odd), ``tau`` and ``order`` (highest power of the Taylor
    polynomial used for ``|x| < tau``), ``stable`` (numba source of the closed form, in ``x, s, c``)
    and implement ``definition``.
    """

    nargs = 1
    parity = 1
    tau = 0.0
    order = 0
    stable = ""
    doc = ""

    @classmethod
    def definition(cls, x):  # pragma: no cover - abstract
        raise NotImplementedError

    @classmethod
    def value_at_zero(cls):
        x = sp.Symbol("x")
        return sp.limit(cls.definition(x), x, 0)

    @classmethod
    def eval(cls, x):
        if x.is_zero:
            return cls.value_at_zero()
        if x.could_extract_minus_sign():
            return cls.parity * cls(-x)
        return None

    def exact(self):
        return self.definition(self.args[0])

    def _eval_rewrite_as_cos(self, x, **kwargs):
        return self.definition(x)

    _eval_rewrite_as_sin = _eval_rewrite_as_cos

    def fdiff(self, argindex=1):
        x = self.args[0]
        d = sp.Symbol("_d")
        return sp.diff(self.definition(d), d).subs(d, x)

    def _eval_evalf(self, prec):
        x = self.args[0]
        if not x.is_number:
            return None
        xv = x.evalf(prec)
        if xv == 0:
            return sp.Float(self.value_at_zero(), prec)
        # near 0 the printed definition cancels even in multiprecision: use the series there
        if abs(xv) < sp.Float("1e-4", prec):
            t = sp.Symbol("t")
            series = taylor_polynomial(type(self), t, 40)
            return series.subs(t, xv).evalf(prec)
        return self.definition(xv).evalf(prec)

    def _eval_is_real(self):
        return self.args[0].is_real


class sinc(AngleFunction):
    """sinc(x) = sin(x)/x (even); the diagonal of V(x) in exp_SE(2)."""

    parity = 1
    tau = 1e-4
    order = 6
    stable = "s / x"

    @classmethod
    def definition(cls, x):
        return sp.sin(x) / x

    def fdiff(self, argindex=1):
        return -dsinc(self.args[0])


class cosc(AngleFunction):
    """cosc(x) = (1 - cos x)/x (odd); the off-diagonal of V(x) in exp_SE(2)."""

    parity = -1
    tau = 1e-4
    order = 7
    # 1 - cos x = sin^2 x / (1 + cos x) avoids the cancellation for cos x > 0
    stable = "(s * s / (1.0 + c)) / x if c > 0.0 else (1.0 - c) / x"

    @classmethod
    def definition(cls, x):
        return (1 - sp.cos(x)) / x

    def fdiff(self, argindex=1):
        x = self.args[0]
        return sinc(x) - cosc2(x)


class sinc2(AngleFunction):
    """sinc2(x) = (x - sin x)/x**2 (odd); appears in the third column of Φ_SE(2)."""

    parity = -1
    tau = 0.75
    order = 15
    stable = "(x - s) / (x * x)"

    @classmethod
    def definition(cls, x):
        return (x - sp.sin(x)) / x**2


class cosc2(AngleFunction):
    """cosc2(x) = (1 - cos x)/x**2 (even); appears in the third column of Φ_SE(2)."""

    parity = 1
    tau = 1e-4
    order = 6
    stable = "(s / x) * (s / x) / (1.0 + c) if c > 0.0 else (1.0 - c) / (x * x)"

    @classmethod
    def definition(cls, x):
        return (1 - sp.cos(x)) / x**2


class dsinc(AngleFunction):
    """dsinc(x) = (sin x - x cos x)/x**2 = -d sinc/dx (odd); CTRV Jacobian w.r.t. the turn rate."""

    parity = -1
    tau = 0.75
    order = 15
    stable = "(s - x * c) / (x * x)"

    @classmethod
    def definition(cls, x):
        return (sp.sin(x) - x * sp.cos(x)) / x**2


class halfcot(AngleFunction):
    """halfcot(x) = x sin x / (2 (1 - cos x)) = (x/2) cot(x/2) (even); diagonal of V(x)^-1 in log_SE(2).

    Defined for |x| < 2π; log_SE(2) only uses (-π, π].
    """

    parity = 1
    tau = 1e-4
    order = 6
    stable = "0.5 * x * (1.0 + c) / s if c > 0.0 else 0.5 * x * s / (1.0 - c)"

    @classmethod
    def definition(cls, x):
        return x * sp.sin(x) / (2 * (1 - sp.cos(x)))


class halfcot1(AngleFunction):
    """halfcot1(x) = (1 - halfcot(x))/x (odd); third column of Φ_SE(2)^-1."""

    parity = -1
    tau = 1.5
    order = 29
    stable = "(1.0 - (0.5 * x * (1.0 + c) / s if c > 0.0 else 0.5 * x * s / (1.0 - c))) / x"

    @classmethod
    def definition(cls, x):
        return (1 - x * sp.sin(x) / (2 * (1 - sp.cos(x)))) / x


# --- functions of the rotation angle t = |φ| of SO(3) / SE(3) (derive/lie/so3.py, se3.py) -------------
# All even; evaluated at t >= 0 (|φ|, or the angle of a rotation matrix).  Their closed forms cancel
# more than the SE(2) ones (the numerators vanish to 3rd-5th order), so the Taylor branches reach far.


class sinc3(AngleFunction):
    """sinc3(t) = (t - sin t)/t**3 (even): the φ^² coefficient of V(φ) = J_l(φ) in exp_SE(3) and of the SO(3)
    right Jacobian J_r(φ) = I - cosc2 φ^ + sinc3 φ^²; Barfoot's A in the Q block of the SE(3) Jacobian."""

    parity = 1
    tau = 0.75
    order = 14
    stable = "(x - s) / (x * x * x)"

    @classmethod
    def definition(cls, x):
        return (x - sp.sin(x)) / x**3


class cosc4(AngleFunction):
    """cosc4(t) = (t**2/2 + cos t - 1)/t**4 (even): Barfoot's B in the Q block of the SE(3) Jacobian.

    Closed form: 1 - cos t computed as sin²t/(1 + cos t) when cos t > 0 (as cosc2), then t²/2 - (1 - cos t).
    """

    parity = 1
    tau = 1.6
    order = 18
    stable = "(0.5 * x * x - (s * s / (1.0 + c) if c > 0.0 else 1.0 - c)) / (x * x * x * x)"

    @classmethod
    def definition(cls, x):
        return (x**2 / 2 + sp.cos(x) - 1) / x**4


class sincos5(AngleFunction):
    """sincos5(t) = (2t - 3 sin t + t cos t)/(2 t**5) (even): Barfoot's C, the coefficient of
    φ^ρ^φ^φ^ + φ^φ^ρ^φ^ in the Q block of the SE(3) Jacobian (its numerator vanishes to 5th order)."""

    parity = 1
    tau = 2.1
    order = 20
    stable = "(2.0 * x - 3.0 * s + x * c) / (2.0 * x * x * x * x * x)"

    @classmethod
    def definition(cls, x):
        return (2 * x - 3 * sp.sin(x) + x * sp.cos(x)) / (2 * x**5)


class halfcot2(AngleFunction):
    """halfcot2(t) = (1 - (t/2) cot(t/2))/t**2 = (1 - halfcot(t))/t**2 (even): the φ^² coefficient of
    J_r(φ)^-1 = I + φ^/2 + halfcot2 φ^² (SO(3)) and of V(φ)^-1 = I - φ^/2 + halfcot2 φ^² in log_SE(3).

    Defined for |t| < 2π; log uses t ∈ [0, π].
    """

    parity = 1
    tau = 1.5
    order = 26
    stable = "(1.0 - (0.5 * x * (1.0 + c) / s if c > 0.0 else 0.5 * x * s / (1.0 - c))) / (x * x)"

    @classmethod
    def definition(cls, x):
        return (1 - x * sp.sin(x) / (2 * (1 - sp.cos(x)))) / x**2


ANGLE_FUNCTIONS: tuple[type[AngleFunction], ...] = (
    sinc, cosc, sinc2, cosc2, dsinc, halfcot, halfcot1, sinc3, cosc4, sincos5, halfcot2
)


class wrap(sp.Function):
    """wrap(a): the angle a wrapped to (-π, π] (printed as the generated helper ``wrap_angle``)."""

    nargs = 1
    numba_name = "wrap_angle"


class angle_sum(sp.Function):
    """angle_sum(a, y) = wrap(a), the stored angle of a composed rotation whose sine is y (printed as the
    generated helper ``wrap_angle_sum``).

    The fused steps store the angle of R_a R_b as wrap(a + b) instead of atan2(sin, cos) of the composed
    entries (``derive.algebra.angle_sums``); the two agree to rounding except at the branch cut, where
    wrap gives +π and atan2 gives -π for a sine of -0.0 or -1e-16.  Beyond |wrap(a)| > π/2 the sign of the
    angle is that of its sine, so copysign(|wrap(a)|, y) is exactly what atan2 returns there: the stored
    angle stays the log of the stored rotation (an ω of -π stays -π through an update with ν = 0).
    """

    nargs = 2
    numba_name = "wrap_angle_sum"


class gain_damping(sp.Function):
    """gain_damping(a, b) = min(1, π / max(|a|, |b|)): the factor that keeps the rotation angles a, b of
    a Kalman correction ν within [-π, π] (printed as the generated helper ``gain_damping``).

    The concentrated Gaussian is only defined where exp is bijective (|angle| < π, paper Sec. II-B);
    a correction that turns the estimate by more than half a turn is a linearisation failure, and at
    angles 2πk (k ≠ 0) Φ(ν) is singular.  Damping the gain K → αK keeps Φ(ν) well conditioned; the
    Joseph-form covariance is exact for the damped gain.  α = 1 whenever |angle| ≤ π (every regular
    step), so the paper's filter is unchanged there.
    """

    nargs = 2
    numba_name = "gain_damping"


RUNTIME_FUNCTIONS = (wrap, angle_sum, gain_damping)


def to_exact(expr):
    """Replace every angle function by its printed definition (for symbolic comparison)."""
    return expr.replace(lambda e: isinstance(e, AngleFunction), lambda e: e.exact())


def taylor_coefficients(func: type[AngleFunction], order: int | None = None) -> list[sp.Rational]:
    """Coefficients a_0..a_order of the Taylor series of ``func`` at 0, computed by SymPy (memoised)."""
    return list(_taylor_coefficients(func, func.order if order is None else order))


@lru_cache(maxsize=None)
def _taylor_coefficients(func, order):
    x = sp.Symbol("x")
    ser = sp.series(func.definition(x), x, 0, order + 1).removeO()
    poly = sp.Poly(ser, x)
    return tuple(sp.Rational(poly.coeff_monomial(x**k)) for k in range(order + 1))


def taylor_polynomial(func: type[AngleFunction], x, order: int | None = None):
    coeffs = taylor_coefficients(func, order)
    return sum((c * x**k for k, c in enumerate(coeffs)), sp.Integer(0))
