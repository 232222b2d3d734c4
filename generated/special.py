"""Angle functions with removable singularities, Taylor-safe near 0.

GENERATED FILE: DO NOT EDIT.
Source: derive/lie/special.py
Regenerate with: lgekf derive      (check freshness with: lgekf derive --check)
"""
import math

import numba as nb

__all__ = ['sinc', 'cosc', 'sinc2', 'cosc2', 'dsinc', 'halfcot', 'halfcot1', 'wrap_angle', 'gain_damping']


@nb.njit(cache=True)
def sinc(x, s, c):
    """sinc(x) = sin(x)/x; s = sin x, c = cos x.

    |x| < 0.0001: Taylor polynomial of degree 6 (coefficients from SymPy);
    otherwise the cancellation-free closed form `s / x`.
    """
    if abs(x) < 0.0001:
        x2 = x * x
        return 1.0 + x2 * (-0.16666666666666666 + x2 * (0.008333333333333333 + x2 * (-0.0001984126984126984)))
    return s / x


@nb.njit(cache=True)
def cosc(x, s, c):
    """cosc(x) = (1 - cos(x))/x; s = sin x, c = cos x.

    |x| < 0.0001: Taylor polynomial of degree 7 (coefficients from SymPy);
    otherwise the cancellation-free closed form `(s * s / (1.0 + c)) / x if c > 0.0 else (1.0 - c) / x`.
    """
    if abs(x) < 0.0001:
        x2 = x * x
        return x * (0.5 + x2 * (-0.041666666666666664 + x2 * (0.001388888888888889 + x2 * (-2.48015873015873e-05))))
    return (s * s / (1.0 + c)) / x if c > 0.0 else (1.0 - c) / x


@nb.njit(cache=True)
def sinc2(x, s, c):
    """sinc2(x) = (x - sin(x))/x**2; s = sin x, c = cos x.

    |x| < 0.75: Taylor polynomial of degree 15 (coefficients from SymPy);
    otherwise the cancellation-free closed form `(x - s) / (x * x)`.
    """
    if abs(x) < 0.75:
        x2 = x * x
        return x * (0.16666666666666666 + x2 * (-0.008333333333333333 + x2 * (0.0001984126984126984 + x2 * (-2.7557319223985893e-06 + x2 * (2.505210838544172e-08 + x2 * (-1.6059043836821613e-10 + x2 * (7.647163731819816e-13 + x2 * (-2.8114572543455206e-15))))))))
    return (x - s) / (x * x)


@nb.njit(cache=True)
def cosc2(x, s, c):
    """cosc2(x) = (1 - cos(x))/x**2; s = sin x, c = cos x.

    |x| < 0.0001: Taylor polynomial of degree 6 (coefficients from SymPy);
    otherwise the cancellation-free closed form `(s / x) * (s / x) / (1.0 + c) if c > 0.0 else (1.0 - c) / (x * x)`.
    """
    if abs(x) < 0.0001:
        x2 = x * x
        return 0.5 + x2 * (-0.041666666666666664 + x2 * (0.001388888888888889 + x2 * (-2.48015873015873e-05)))
    return (s / x) * (s / x) / (1.0 + c) if c > 0.0 else (1.0 - c) / (x * x)


@nb.njit(cache=True)
def dsinc(x, s, c):
    """dsinc(x) = (-x*cos(x) + sin(x))/x**2; s = sin x, c = cos x.

    |x| < 0.75: Taylor polynomial of degree 15 (coefficients from SymPy);
    otherwise the cancellation-free closed form `(s - x * c) / (x * x)`.
    """
    if abs(x) < 0.75:
        x2 = x * x
        return x * (0.3333333333333333 + x2 * (-0.03333333333333333 + x2 * (0.0011904761904761906 + x2 * (-2.2045855379188714e-05 + x2 * (2.505210838544172e-07 + x2 * (-1.9270852604185937e-09 + x2 * (1.0706029224547743e-11 + x2 * (-4.498331606952833e-14))))))))
    return (s - x * c) / (x * x)


@nb.njit(cache=True)
def halfcot(x, s, c):
    """halfcot(x) = x*sin(x)/(2 - 2*cos(x)); s = sin x, c = cos x.

    |x| < 0.0001: Taylor polynomial of degree 6 (coefficients from SymPy);
    otherwise the cancellation-free closed form `0.5 * x * (1.0 + c) / s if c > 0.0 else 0.5 * x * s / (1.0 - c)`.
    """
    if abs(x) < 0.0001:
        x2 = x * x
        return 1.0 + x2 * (-0.08333333333333333 + x2 * (-0.001388888888888889 + x2 * (-3.306878306878307e-05)))
    return 0.5 * x * (1.0 + c) / s if c > 0.0 else 0.5 * x * s / (1.0 - c)


@nb.njit(cache=True)
def halfcot1(x, s, c):
    """halfcot1(x) = (-x*sin(x)/(2 - 2*cos(x)) + 1)/x; s = sin x, c = cos x.

    |x| < 1.5: Taylor polynomial of degree 29 (coefficients from SymPy);
    otherwise the cancellation-free closed form `(1.0 - (0.5 * x * (1.0 + c) / s if c > 0.0 else 0.5 * x * s / (1.0 - c))) / x`.
    """
    if abs(x) < 1.5:
        x2 = x * x
        return x * (0.08333333333333333 + x2 * (0.001388888888888889 + x2 * (3.306878306878307e-05 + x2 * (8.267195767195768e-07 + x2 * (2.08767569878681e-08 + x2 * (5.284190138687493e-10 + x2 * (1.3382536530684679e-11 + x2 * (3.3896802963225827e-13 + x2 * (8.586062056277845e-15 + x2 * (2.174868698558062e-16 + x2 * (5.5090028283602295e-18 + x2 * (1.3954464685812522e-19 + x2 * (3.534707039629467e-21 + x2 * (8.953517427037546e-23 + x2 * (2.267952452337683e-24)))))))))))))))
    return (1.0 - (0.5 * x * (1.0 + c) / s if c > 0.0 else 0.5 * x * s / (1.0 - c))) / x


@nb.njit(cache=True)
def wrap_angle(a):
    """a wrapped to (-π, π]."""
    if -math.pi < a <= math.pi:
        return a
    r = a - 2.0 * math.pi * math.floor((a + math.pi) / (2.0 * math.pi))
    if r <= -math.pi:
        r += 2.0 * math.pi
    return r


@nb.njit(cache=True)
def gain_damping(a, b):
    """min(1, π / max(|a|, |b|)): keeps the angles of a Kalman correction within [-π, π]
    (see derive.special.gain_damping)."""
    m = max(abs(a), abs(b))
    if m <= math.pi:
        return 1.0
    return math.pi / m
