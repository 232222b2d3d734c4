"""Measure where each angle function's closed form is accurate: `python -m lgekf.derive.lie.thresholds`.

For every function of derive.special, on a log-spaced grid of angles in [1e-6, π) (both signs), the
float64 closed form (its ``stable`` source, with math.sin/cos) is compared with the definition evaluated
in 50-digit mpmath.  Reported per function:

* ``tau``: the smallest grid angle above which the closed form stays within ``ulps`` ulp;
* ``order``: the smallest Taylor degree whose truncation error at that tau is below 1e-17 relative
  (measured, by evaluating the polynomial in mpmath against the definition);
* on a uniform 300-point grid of [0.5, π] (``fine_scan``): the last angle where the closed form is above 4 ulp,
  and the closed form's worst error (ulp) at or above the recorded tau.

The values recorded in derive/lie/special.py were chosen from this output (rounded up to simple numbers);
tests/derive/test_special_accuracy.py checks both sides of every threshold.
"""

from __future__ import annotations

import math

import mpmath as mp
import sympy as sp

from .special import ANGLE_FUNCTIONS, taylor_coefficients

mp.mp.dps = 50


def closed_form_error(func, x: float) -> float:
    s, c = math.sin(x), math.cos(x)
    val = eval(func.stable, {"x": x, "s": s, "c": c})  # noqa: S307 - our own source strings
    t = sp.Symbol("t")
    true = mp.mpf(str(sp.N(func.definition(t).subs(t, sp.Float(x, 60)), 50)))
    return float(abs((mp.mpf(val) - true) / true))


def taylor_error(func, x: float, order: int) -> float:
    coeffs = taylor_coefficients(func, order)
    xv = mp.mpf(x)
    poly = sum(mp.mpf(sp.Rational(cf).p) / mp.mpf(sp.Rational(cf).q) * xv**k for k, cf in enumerate(coeffs))
    t = sp.Symbol("t")
    true = mp.mpf(str(sp.N(func.definition(t).subs(t, sp.Float(x, 60)), 50)))
    return float(abs((poly - true) / true))


def measure(func, ulps: float = 4.0, grid: int = 240):
    xs = [10 ** (-6 + 6.5 * i / (grid - 1)) for i in range(grid)]
    xs = [x for x in xs if x < math.pi]
    errs = [max(closed_form_error(func, x), closed_form_error(func, -x)) for x in xs]
    limit = ulps * 2.220446049250313e-16
    tau = xs[-1]
    for i in range(len(xs) - 1, -1, -1):
        if errs[i] > limit:
            break
        tau = xs[i]
    order = 1
    while taylor_error(func, tau, order) > 1e-17 and order < 60:
        order += 1
    return tau, order, max(errs[xs.index(tau):])


def fine_scan(func, ulps: float = 4.0, lo: float = 0.5, hi: float = math.pi, points: int = 300):
    """On a uniform grid of [lo, hi]: (the last angle where the closed form is above ``ulps`` ulp, the worst ulp of the
    closed form at or above the recorded ``func.tau``).

    The log grid of :func:`measure` has ~6 % steps near 1, where the closed forms of SO(3)/SE(3) switch.
    """
    xs = [lo + (hi - lo) * k / points for k in range(points + 1)]
    errs = [max(closed_form_error(func, x), closed_form_error(func, -x)) / 2.220446049250313e-16 for x in xs]
    over = [x for x, e in zip(xs, errs) if e > ulps]
    above = [e for x, e in zip(xs, errs) if x >= func.tau]
    return (over[-1] if over else lo), (max(above) if above else 0.0)


def main():
    print(f"{'function':10} {'tau (<= 4 ulp above)':>22} {'Taylor order at tau':>20} {'max err above tau':>18}"
          f" {'fine: last > 4 ulp':>19} {'ulp above tau':>16}   recorded tau / order")
    for f in ANGLE_FUNCTIONS:
        tau, order, err = measure(f)
        last, worst = fine_scan(f)
        print(f"{f.__name__:10} {tau:22.3g} {order:20d} {err:18.2e} {last:19.3g} {worst:16.1f}   {f.tau} / {f.order}")


if __name__ == "__main__":
    main()
