"""Angle functions with removable singularities, Taylor-safe near 0.

GENERATED FILE: DO NOT EDIT.
Source: derive/lie/special.py
Regenerate with: lgekf derive      (check freshness with: lgekf derive --check)
"""
import math

import numba as nb

SCALAR_ERRORS = "numpy"

__all__ = ['sinc', 'cosc', 'sinc2', 'cosc2', 'dsinc', 'halfcot', 'halfcot1', 'sinc3', 'cosc4', 'sincos5', 'halfcot2', 'sinc_family', 'wrap_angle', 'wrap_angle_sum', 'gain_damping', 'sin_v', 'cos_v', 'atan2_v', 'wrap_v', 'wrap_sum_v', 'gain_damping_v', 'sinc_v', 'cosc_v', 'sinc2_v', 'cosc2_v', 'dsinc_v', 'halfcot_v', 'halfcot1_v', 'sinc3_v', 'cosc4_v', 'sincos5_v', 'halfcot2_v']


@nb.njit(cache=True, error_model=SCALAR_ERRORS)
def sinc(x, s, c):
    """sinc(x) = sin(x)/x; s = sin x, c = cos x.

    |x| < 0.0001: Taylor polynomial of degree 6 (coefficients from SymPy);
    otherwise the cancellation-free closed form `s / x`.
    """
    if abs(x) < 0.0001:
        x2 = x * x
        return 1.0 + x2 * (-0.16666666666666666 + x2 * (0.008333333333333333 + x2 * (-0.0001984126984126984)))
    return s / x


@nb.njit(cache=True, error_model=SCALAR_ERRORS)
def cosc(x, s, c):
    """cosc(x) = (1 - cos(x))/x; s = sin x, c = cos x.

    |x| < 0.0001: Taylor polynomial of degree 7 (coefficients from SymPy);
    otherwise the cancellation-free closed form `(s * s / (1.0 + c)) / x if c > 0.0 else (1.0 - c) / x`.
    """
    if abs(x) < 0.0001:
        x2 = x * x
        return x * (0.5 + x2 * (-0.041666666666666664 + x2 * (0.001388888888888889 + x2 * (-2.48015873015873e-05))))
    return (s * s / (1.0 + c)) / x if c > 0.0 else (1.0 - c) / x


@nb.njit(cache=True, error_model=SCALAR_ERRORS)
def sinc2(x, s, c):
    """sinc2(x) = (x - sin(x))/x**2; s = sin x, c = cos x.

    |x| < 0.75: Taylor polynomial of degree 15 (coefficients from SymPy);
    otherwise the cancellation-free closed form `(x - s) / (x * x)`.
    """
    if abs(x) < 0.75:
        x2 = x * x
        return x * (0.16666666666666666 + x2 * (-0.008333333333333333 + x2 * (0.0001984126984126984 + x2 * (-2.7557319223985893e-06 + x2 * (2.505210838544172e-08 + x2 * (-1.6059043836821613e-10 + x2 * (7.647163731819816e-13 + x2 * (-2.8114572543455206e-15))))))))
    return (x - s) / (x * x)


@nb.njit(cache=True, error_model=SCALAR_ERRORS)
def cosc2(x, s, c):
    """cosc2(x) = (1 - cos(x))/x**2; s = sin x, c = cos x.

    |x| < 0.0001: Taylor polynomial of degree 6 (coefficients from SymPy);
    otherwise the cancellation-free closed form `(s / x) * (s / x) / (1.0 + c) if c > 0.0 else (1.0 - c) / (x * x)`.
    """
    if abs(x) < 0.0001:
        x2 = x * x
        return 0.5 + x2 * (-0.041666666666666664 + x2 * (0.001388888888888889 + x2 * (-2.48015873015873e-05)))
    return (s / x) * (s / x) / (1.0 + c) if c > 0.0 else (1.0 - c) / (x * x)


@nb.njit(cache=True, error_model=SCALAR_ERRORS)
def dsinc(x, s, c):
    """dsinc(x) = (-x*cos(x) + sin(x))/x**2; s = sin x, c = cos x.

    |x| < 0.75: Taylor polynomial of degree 15 (coefficients from SymPy);
    otherwise the cancellation-free closed form `(s - x * c) / (x * x)`.
    """
    if abs(x) < 0.75:
        x2 = x * x
        return x * (0.3333333333333333 + x2 * (-0.03333333333333333 + x2 * (0.0011904761904761906 + x2 * (-2.2045855379188714e-05 + x2 * (2.505210838544172e-07 + x2 * (-1.9270852604185937e-09 + x2 * (1.0706029224547743e-11 + x2 * (-4.498331606952833e-14))))))))
    return (s - x * c) / (x * x)


@nb.njit(cache=True, error_model=SCALAR_ERRORS)
def halfcot(x, s, c):
    """halfcot(x) = x*sin(x)/(2 - 2*cos(x)); s = sin x, c = cos x.

    |x| < 0.0001: Taylor polynomial of degree 6 (coefficients from SymPy);
    otherwise the cancellation-free closed form `0.5 * x * (1.0 + c) / s if c > 0.0 else 0.5 * x * s / (1.0 - c)`.
    """
    if abs(x) < 0.0001:
        x2 = x * x
        return 1.0 + x2 * (-0.08333333333333333 + x2 * (-0.001388888888888889 + x2 * (-3.306878306878307e-05)))
    return 0.5 * x * (1.0 + c) / s if c > 0.0 else 0.5 * x * s / (1.0 - c)


@nb.njit(cache=True, error_model=SCALAR_ERRORS)
def halfcot1(x, s, c):
    """halfcot1(x) = (-x*sin(x)/(2 - 2*cos(x)) + 1)/x; s = sin x, c = cos x.

    |x| < 1.5: Taylor polynomial of degree 29 (coefficients from SymPy);
    otherwise the cancellation-free closed form `(1.0 - (0.5 * x * (1.0 + c) / s if c > 0.0 else 0.5 * x * s / (1.0 - c))) / x`.
    """
    if abs(x) < 1.5:
        x2 = x * x
        return x * (0.08333333333333333 + x2 * (0.001388888888888889 + x2 * (3.306878306878307e-05 + x2 * (8.267195767195768e-07 + x2 * (2.08767569878681e-08 + x2 * (5.284190138687493e-10 + x2 * (1.3382536530684679e-11 + x2 * (3.3896802963225827e-13 + x2 * (8.586062056277845e-15 + x2 * (2.174868698558062e-16 + x2 * (5.5090028283602295e-18 + x2 * (1.3954464685812522e-19 + x2 * (3.534707039629467e-21 + x2 * (8.953517427037546e-23 + x2 * (2.267952452337683e-24)))))))))))))))
    return (1.0 - (0.5 * x * (1.0 + c) / s if c > 0.0 else 0.5 * x * s / (1.0 - c))) / x


@nb.njit(cache=True, error_model=SCALAR_ERRORS)
def sinc3(x, s, c):
    """sinc3(x) = (x - sin(x))/x**3; s = sin x, c = cos x.

    |x| < 0.75: Taylor polynomial of degree 14 (coefficients from SymPy);
    otherwise the cancellation-free closed form `(x - s) / (x * x * x)`.
    """
    if abs(x) < 0.75:
        x2 = x * x
        return 0.16666666666666666 + x2 * (-0.008333333333333333 + x2 * (0.0001984126984126984 + x2 * (-2.7557319223985893e-06 + x2 * (2.505210838544172e-08 + x2 * (-1.6059043836821613e-10 + x2 * (7.647163731819816e-13 + x2 * (-2.8114572543455206e-15)))))))
    return (x - s) / (x * x * x)


@nb.njit(cache=True, error_model=SCALAR_ERRORS)
def cosc4(x, s, c):
    """cosc4(x) = (x**2/2 + cos(x) - 1)/x**4; s = sin x, c = cos x.

    |x| < 1.6: Taylor polynomial of degree 18 (coefficients from SymPy);
    otherwise the cancellation-free closed form `(0.5 * x * x - (s * s / (1.0 + c) if c > 0.0 else 1.0 - c)) / (x * x * x * x)`.
    """
    if abs(x) < 1.6:
        x2 = x * x
        return 0.041666666666666664 + x2 * (-0.001388888888888889 + x2 * (2.48015873015873e-05 + x2 * (-2.755731922398589e-07 + x2 * (2.08767569878681e-09 + x2 * (-1.1470745597729725e-11 + x2 * (4.779477332387385e-14 + x2 * (-1.5619206968586225e-16 + x2 * (4.110317623312165e-19 + x2 * (-8.896791392450574e-22)))))))))
    return (0.5 * x * x - (s * s / (1.0 + c) if c > 0.0 else 1.0 - c)) / (x * x * x * x)


@nb.njit(cache=True, error_model=SCALAR_ERRORS)
def sincos5(x, s, c):
    """sincos5(x) = (x*cos(x) + 2*x - 3*sin(x))/(2*x**5); s = sin x, c = cos x.

    |x| < 2.1: Taylor polynomial of degree 20 (coefficients from SymPy);
    otherwise the cancellation-free closed form `(2.0 * x - 3.0 * s + x * c) / (2.0 * x * x * x * x * x)`.
    """
    if abs(x) < 2.1:
        x2 = x * x
        return 0.008333333333333333 + x2 * (-0.0003968253968253968 + x2 * (8.267195767195768e-06 + x2 * (-1.0020843354176688e-07 + x2 * (8.029521918410807e-10 + x2 * (-4.58829823909189e-12 + x2 * (1.9680200780418645e-14 + x2 * (-6.576508197299464e-17 + x2 * (1.7615646957052136e-19 + x2 * (-3.868170170630684e-22 + x2 * (7.091645312822921e-25))))))))))
    return (2.0 * x - 3.0 * s + x * c) / (2.0 * x * x * x * x * x)


@nb.njit(cache=True, error_model=SCALAR_ERRORS)
def halfcot2(x, s, c):
    """halfcot2(x) = (-x*sin(x)/(2 - 2*cos(x)) + 1)/x**2; s = sin x, c = cos x.

    |x| < 1.5: Taylor polynomial of degree 26 (coefficients from SymPy);
    otherwise the cancellation-free closed form `(1.0 - (0.5 * x * (1.0 + c) / s if c > 0.0 else 0.5 * x * s / (1.0 - c))) / (x * x)`.
    """
    if abs(x) < 1.5:
        x2 = x * x
        return 0.08333333333333333 + x2 * (0.001388888888888889 + x2 * (3.306878306878307e-05 + x2 * (8.267195767195768e-07 + x2 * (2.08767569878681e-08 + x2 * (5.284190138687493e-10 + x2 * (1.3382536530684679e-11 + x2 * (3.3896802963225827e-13 + x2 * (8.586062056277845e-15 + x2 * (2.174868698558062e-16 + x2 * (5.5090028283602295e-18 + x2 * (1.3954464685812522e-19 + x2 * (3.534707039629467e-21 + x2 * (8.953517427037546e-23)))))))))))))
    return (1.0 - (0.5 * x * (1.0 + c) / s if c > 0.0 else 0.5 * x * s / (1.0 - c))) / (x * x)


@nb.njit(cache=True, inline="always", error_model=SCALAR_ERRORS)
def sinc_family(x, s, c):
    """(sinc, cosc, sinc2, cosc2)(x) with s = sin x, c = cos x, sharing 1/x and 1/(1 + c)
    (derive/codegen/build.py family_source; the same polynomials and thresholds as the four functions)."""
    x2 = x * x
    if abs(x) < 0.0001:
        a = 1.0 + x2 * (-0.16666666666666666 + x2 * (0.008333333333333333 + x2 * (-0.0001984126984126984)))
        b = x * (0.5 + x2 * (-0.041666666666666664 + x2 * (0.001388888888888889 + x2 * (-2.48015873015873e-05))))
        d = 0.5 + x2 * (-0.041666666666666664 + x2 * (0.001388888888888889 + x2 * (-2.48015873015873e-05)))
        e = x * (0.16666666666666666 + x2 * (-0.008333333333333333 + x2 * (0.0001984126984126984 + x2 * (-2.7557319223985893e-06 + x2 * (2.505210838544172e-08 + x2 * (-1.6059043836821613e-10 + x2 * (7.647163731819816e-13 + x2 * (-2.8114572543455206e-15))))))))
        return a, b, e, d
    rx = 1.0 / x
    h = s * s / (1.0 + c) if c > 0.0 else 1.0 - c
    a = s * rx
    b = h * rx
    d = b * rx
    if abs(x) < 0.75:
        e = x * (0.16666666666666666 + x2 * (-0.008333333333333333 + x2 * (0.0001984126984126984 + x2 * (-2.7557319223985893e-06 + x2 * (2.505210838544172e-08 + x2 * (-1.6059043836821613e-10 + x2 * (7.647163731819816e-13 + x2 * (-2.8114572543455206e-15))))))))
    else:
        e = (x - s) * (rx * rx)
    return a, b, e, d


@nb.njit(cache=True, error_model=SCALAR_ERRORS)
def wrap_angle(a):
    """a wrapped to (-π, π]."""
    if -math.pi < a <= math.pi:
        return a
    r = a - 2.0 * math.pi * math.floor((a + math.pi) / (2.0 * math.pi))
    if r <= -math.pi:
        r += 2.0 * math.pi
    return r


@nb.njit(cache=True, error_model=SCALAR_ERRORS)
def wrap_angle_sum(a, y):
    """wrap(a) with the sign of y beyond ±π/2: the angle of a composed rotation whose sine is y, as atan2 of
    its entries would give it, also at the branch cut (see derive.lie.special.angle_sum)."""
    w = wrap_angle(a)
    if abs(w) > 0.5 * math.pi:
        return math.copysign(abs(w), y)
    return w


@nb.njit(cache=True, error_model=SCALAR_ERRORS)
def gain_damping(a, b):
    """min(1, π / max(|a|, |b|)): keeps the angles of a Kalman correction within [-π, π]
    (see derive.special.gain_damping)."""
    m = max(abs(a), abs(b))
    if m <= math.pi:
        return 1.0
    return math.pi / m


# ---------------------------------------------------------------- branch-free helpers of the SIMD kernels
# (derive/codegen/soa.py): both sides of every branch are evaluated and selected, so LLVM can vectorise a loop
# whose body calls them (they are inlined by numba).

@nb.njit(inline="always", fastmath={"contract"}, error_model="numpy")
def _sin_cos_r(x):
    """(r, q): x = q·π/2 + r, |r| ≤ π/4 (Cody–Waite, π/2 in three parts), q mod 4 as a float."""
    kf = math.floor(x * 0.6366197723675814 + 0.5)
    r = ((x - kf * 1.5707963267341256) - kf * 6.077100506506192e-11) - kf * 2.0222662487959506e-21
    return r, kf - 4.0 * math.floor(kf * 0.25)


@nb.njit(inline="always", fastmath={"contract"}, error_model="numpy")
def sin_v(x):
    """sin x without branches: degree-17/18 Taylor polynomials on the reduced argument (error bound: soa.py)."""
    r, q = _sin_cos_r(x)
    r2 = r * r
    sp = r + r * r2 * (-0.16666666666666666 + r2 * (0.008333333333333333 + r2 * (-0.0001984126984126984 + r2 * (2.7557319223985893e-06 + r2 * (-2.505210838544172e-08 + r2 * (1.6059043836821613e-10 + r2 * (-7.647163731819816e-13 + r2 * (2.8114572543455206e-15))))))))
    cp = 1.0 + r2 * (-0.5 + r2 * (0.041666666666666664 + r2 * (-0.001388888888888889 + r2 * (2.48015873015873e-05 + r2 * (-2.755731922398589e-07 + r2 * (2.08767569878681e-09 + r2 * (-1.1470745597729725e-11 + r2 * (4.779477332387385e-14 + r2 * (-1.5619206968586225e-16)))))))))
    v = cp if (q == 1.0) | (q == 3.0) else sp
    return -v if q >= 2.0 else v


@nb.njit(inline="always", fastmath={"contract"}, error_model="numpy")
def cos_v(x):
    """cos x without branches (as sin_v)."""
    r, q = _sin_cos_r(x)
    r2 = r * r
    sp = r + r * r2 * (-0.16666666666666666 + r2 * (0.008333333333333333 + r2 * (-0.0001984126984126984 + r2 * (2.7557319223985893e-06 + r2 * (-2.505210838544172e-08 + r2 * (1.6059043836821613e-10 + r2 * (-7.647163731819816e-13 + r2 * (2.8114572543455206e-15))))))))
    cp = 1.0 + r2 * (-0.5 + r2 * (0.041666666666666664 + r2 * (-0.001388888888888889 + r2 * (2.48015873015873e-05 + r2 * (-2.755731922398589e-07 + r2 * (2.08767569878681e-09 + r2 * (-1.1470745597729725e-11 + r2 * (4.779477332387385e-14 + r2 * (-1.5619206968586225e-16)))))))))
    v = sp if (q == 1.0) | (q == 3.0) else cp
    return -v if (q == 1.0) | (q == 2.0) else v


@nb.njit(inline="always", fastmath={"contract"}, error_model="numpy")
def atan2_v(y, x):
    """atan2(y, x) ∈ [-π, π] without branches: t = min/max(|x|, |y|) ∈ [0, 1] reduced by the nearest tan(kπ/16),
    k = 0..4, to |t'| ≤ tan(π/32), Taylor polynomial of degree 17 (truncation < 1e-18)."""
    ax = abs(x)
    ay = abs(y)
    mx = max(ax, ay)
    t = min(ax, ay) / mx if mx > 0.0 else 0.0
    k = (1.0 if t > 0.09849140335716425 else 0.0) + (1.0 if t > 0.3033466836073424 else 0.0) + (1.0 if t > 0.5345111359507916 else 0.0) + (1.0 if t > 0.8206787908286602 else 0.0)
    c = 0.198912367379658 if k == 1.0 else (0.41421356237309503 if k == 2.0 else (0.6681786379192989 if k == 3.0 else (1.0 if k == 4.0 else 0.0)))
    u = (t - c) / (1.0 + t * c)
    u2 = u * u
    a = k * 0.19634954084936207 + u * (1.0 + u2 * (-0.3333333333333333 + u2 * (0.2 + u2 * (-0.14285714285714285 + u2 * (0.1111111111111111 + u2 * (-0.09090909090909091 + u2 * (0.07692307692307693 + u2 * (-0.06666666666666667 + u2 * (0.058823529411764705)))))))))
    a = 1.5707963267948966 - a if ay > ax else a
    a = 3.141592653589793 - a if x < 0.0 else a
    return -a if (y < 0.0) | ((y == 0.0) & (math.copysign(1.0, y) < 0.0)) else a


@nb.njit(inline="always", fastmath={"contract"}, error_model="numpy")
def wrap_v(a):
    """a wrapped to (-π, π] without branches (wrap_angle's formula, selected)."""
    r = a - 6.283185307179586 * math.floor((a + 3.141592653589793) / 6.283185307179586)
    r = r + 6.283185307179586 if r <= -3.141592653589793 else r
    return a if (a > -3.141592653589793) & (a <= 3.141592653589793) else r


@nb.njit(inline="always", fastmath={"contract"}, error_model="numpy")
def wrap_sum_v(a, y):
    """wrap_angle_sum without branches: wrap(a), with the sign of y beyond ±π/2."""
    w = wrap_v(a)
    return math.copysign(abs(w), y) if abs(w) > 1.5707963267948966 else w


@nb.njit(inline="always", fastmath={"contract"}, error_model="numpy")
def gain_damping_v(a, b):
    """min(1, π / max(|a|, |b|)) without branches (gain_damping)."""
    m = max(abs(a), abs(b))
    return 1.0 if m <= 3.141592653589793 else 3.141592653589793 / m


@nb.njit(inline="always", fastmath={"contract"}, error_model="numpy")
def sinc_v(x, s, c):
    """sinc without branches: Taylor polynomial and closed form both evaluated, selected at |x| < 0.0001."""
    x2 = x * x
    return (1.0 + x2 * (-0.16666666666666666 + x2 * (0.008333333333333333 + x2 * (-0.0001984126984126984)))) if abs(x) < 0.0001 else (s / x)


@nb.njit(inline="always", fastmath={"contract"}, error_model="numpy")
def cosc_v(x, s, c):
    """cosc without branches: Taylor polynomial and closed form both evaluated, selected at |x| < 0.0001."""
    x2 = x * x
    return (x * (0.5 + x2 * (-0.041666666666666664 + x2 * (0.001388888888888889 + x2 * (-2.48015873015873e-05))))) if abs(x) < 0.0001 else ((s * s / (1.0 + c)) / x if c > 0.0 else (1.0 - c) / x)


@nb.njit(inline="always", fastmath={"contract"}, error_model="numpy")
def sinc2_v(x, s, c):
    """sinc2 without branches: Taylor polynomial and closed form both evaluated, selected at |x| < 0.75."""
    x2 = x * x
    return (x * (0.16666666666666666 + x2 * (-0.008333333333333333 + x2 * (0.0001984126984126984 + x2 * (-2.7557319223985893e-06 + x2 * (2.505210838544172e-08 + x2 * (-1.6059043836821613e-10 + x2 * (7.647163731819816e-13 + x2 * (-2.8114572543455206e-15))))))))) if abs(x) < 0.75 else ((x - s) / (x * x))


@nb.njit(inline="always", fastmath={"contract"}, error_model="numpy")
def cosc2_v(x, s, c):
    """cosc2 without branches: Taylor polynomial and closed form both evaluated, selected at |x| < 0.0001."""
    x2 = x * x
    return (0.5 + x2 * (-0.041666666666666664 + x2 * (0.001388888888888889 + x2 * (-2.48015873015873e-05)))) if abs(x) < 0.0001 else ((s / x) * (s / x) / (1.0 + c) if c > 0.0 else (1.0 - c) / (x * x))


@nb.njit(inline="always", fastmath={"contract"}, error_model="numpy")
def dsinc_v(x, s, c):
    """dsinc without branches: Taylor polynomial and closed form both evaluated, selected at |x| < 0.75."""
    x2 = x * x
    return (x * (0.3333333333333333 + x2 * (-0.03333333333333333 + x2 * (0.0011904761904761906 + x2 * (-2.2045855379188714e-05 + x2 * (2.505210838544172e-07 + x2 * (-1.9270852604185937e-09 + x2 * (1.0706029224547743e-11 + x2 * (-4.498331606952833e-14))))))))) if abs(x) < 0.75 else ((s - x * c) / (x * x))


@nb.njit(inline="always", fastmath={"contract"}, error_model="numpy")
def halfcot_v(x, s, c):
    """halfcot without branches: Taylor polynomial and closed form both evaluated, selected at |x| < 0.0001."""
    x2 = x * x
    return (1.0 + x2 * (-0.08333333333333333 + x2 * (-0.001388888888888889 + x2 * (-3.306878306878307e-05)))) if abs(x) < 0.0001 else (0.5 * x * (1.0 + c) / s if c > 0.0 else 0.5 * x * s / (1.0 - c))


@nb.njit(inline="always", fastmath={"contract"}, error_model="numpy")
def halfcot1_v(x, s, c):
    """halfcot1 without branches: Taylor polynomial and closed form both evaluated, selected at |x| < 1.5."""
    x2 = x * x
    return (x * (0.08333333333333333 + x2 * (0.001388888888888889 + x2 * (3.306878306878307e-05 + x2 * (8.267195767195768e-07 + x2 * (2.08767569878681e-08 + x2 * (5.284190138687493e-10 + x2 * (1.3382536530684679e-11 + x2 * (3.3896802963225827e-13 + x2 * (8.586062056277845e-15 + x2 * (2.174868698558062e-16 + x2 * (5.5090028283602295e-18 + x2 * (1.3954464685812522e-19 + x2 * (3.534707039629467e-21 + x2 * (8.953517427037546e-23 + x2 * (2.267952452337683e-24)))))))))))))))) if abs(x) < 1.5 else ((1.0 - (0.5 * x * (1.0 + c) / s if c > 0.0 else 0.5 * x * s / (1.0 - c))) / x)


@nb.njit(inline="always", fastmath={"contract"}, error_model="numpy")
def sinc3_v(x, s, c):
    """sinc3 without branches: Taylor polynomial and closed form both evaluated, selected at |x| < 0.75."""
    x2 = x * x
    return (0.16666666666666666 + x2 * (-0.008333333333333333 + x2 * (0.0001984126984126984 + x2 * (-2.7557319223985893e-06 + x2 * (2.505210838544172e-08 + x2 * (-1.6059043836821613e-10 + x2 * (7.647163731819816e-13 + x2 * (-2.8114572543455206e-15)))))))) if abs(x) < 0.75 else ((x - s) / (x * x * x))


@nb.njit(inline="always", fastmath={"contract"}, error_model="numpy")
def cosc4_v(x, s, c):
    """cosc4 without branches: Taylor polynomial and closed form both evaluated, selected at |x| < 1.6."""
    x2 = x * x
    return (0.041666666666666664 + x2 * (-0.001388888888888889 + x2 * (2.48015873015873e-05 + x2 * (-2.755731922398589e-07 + x2 * (2.08767569878681e-09 + x2 * (-1.1470745597729725e-11 + x2 * (4.779477332387385e-14 + x2 * (-1.5619206968586225e-16 + x2 * (4.110317623312165e-19 + x2 * (-8.896791392450574e-22)))))))))) if abs(x) < 1.6 else ((0.5 * x * x - (s * s / (1.0 + c) if c > 0.0 else 1.0 - c)) / (x * x * x * x))


@nb.njit(inline="always", fastmath={"contract"}, error_model="numpy")
def sincos5_v(x, s, c):
    """sincos5 without branches: Taylor polynomial and closed form both evaluated, selected at |x| < 2.1."""
    x2 = x * x
    return (0.008333333333333333 + x2 * (-0.0003968253968253968 + x2 * (8.267195767195768e-06 + x2 * (-1.0020843354176688e-07 + x2 * (8.029521918410807e-10 + x2 * (-4.58829823909189e-12 + x2 * (1.9680200780418645e-14 + x2 * (-6.576508197299464e-17 + x2 * (1.7615646957052136e-19 + x2 * (-3.868170170630684e-22 + x2 * (7.091645312822921e-25))))))))))) if abs(x) < 2.1 else ((2.0 * x - 3.0 * s + x * c) / (2.0 * x * x * x * x * x))


@nb.njit(inline="always", fastmath={"contract"}, error_model="numpy")
def halfcot2_v(x, s, c):
    """halfcot2 without branches: Taylor polynomial and closed form both evaluated, selected at |x| < 1.5."""
    x2 = x * x
    return (0.08333333333333333 + x2 * (0.001388888888888889 + x2 * (3.306878306878307e-05 + x2 * (8.267195767195768e-07 + x2 * (2.08767569878681e-08 + x2 * (5.284190138687493e-10 + x2 * (1.3382536530684679e-11 + x2 * (3.3896802963225827e-13 + x2 * (8.586062056277845e-15 + x2 * (2.174868698558062e-16 + x2 * (5.5090028283602295e-18 + x2 * (1.3954464685812522e-19 + x2 * (3.534707039629467e-21 + x2 * (8.953517427037546e-23)))))))))))))) if abs(x) < 1.5 else ((1.0 - (0.5 * x * (1.0 + c) / s if c > 0.0 else 0.5 * x * s / (1.0 - c))) / (x * x))
