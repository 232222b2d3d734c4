"""SE(2) building blocks: hat, vee, exp, log, inverse, Ad, ad, right Jacobian Φ and Φ^-1.

GENERATED FILE: DO NOT EDIT.
Source: derive/lie/groups.py through derive/codegen/emitter.py
Regenerate with: lgekf derive      (check freshness with: lgekf derive --check)
"""
import math

import numba as nb
import numpy as np
from .special import sinc, cosc, sinc2, cosc2, dsinc, halfcot, halfcot1, sinc3, cosc4, sincos5, halfcot2, sinc_family, gain_damping, wrap_angle, wrap_angle_sum  # noqa: F401
from .special import sin_v, cos_v, atan2_v, wrap_v, wrap_sum_v, gain_damping_v, sinc_v, cosc_v, sinc2_v, cosc2_v, dsinc_v, halfcot_v, halfcot1_v, sinc3_v, cosc4_v, sincos5_v, halfcot2_v  # noqa: F401
from .monitor import maximum, minimum, two_point_into, jacobian_point, initial_covariance_into, copy_row, pack_into, reinit_earlier_row, finite_row, speed_std_from, scan_segment  # noqa: F401

# fused steps use FMA contraction only ("contract"); every other IEEE rule holds
FASTMATH = {"contract"}

__all__ = ['se2_hat', 'se2_vee', 'se2_exp', 'se2_log', 'se2_inverse', 'se2_adjoint', 'se2_ad', 'right_jacobian', 'right_jacobian_inv']


@nb.njit(cache=True)
def se2_hat(xi):
    """[x, y, θ]^∧ (paper, hat_SE(2)).
    """
    x = xi[0]
    y = xi[1]
    theta = xi[2]
    out = np.zeros((3, 3))
    out[0, 1] = -theta
    out[0, 2] = x
    out[1, 0] = theta
    out[1, 2] = y
    return out


@nb.njit(cache=True)
def se2_vee(T):
    """[M]^∨ = (M[0, 2], M[1, 2], M[1, 0]).
    """
    T02 = T[0, 2]
    T10 = T[1, 0]
    T12 = T[1, 2]
    out = np.zeros(3)
    out[0] = T02
    out[1] = T12
    out[2] = T10
    return out


@nb.njit(cache=True)
def se2_exp(xi):
    """exp_SE(2)([x, y, θ]^∧) (paper, exp_SE(2)); translation V(θ)[x, y], Taylor-safe at θ = 0.
    """
    x = xi[0]
    y = xi[1]
    theta = xi[2]
    out = np.zeros((3, 3))
    _sin_theta = math.sin(theta)
    _cos_theta = math.cos(theta)
    _sinc_theta, _cosc_theta, _sinc2_theta, _cosc2_theta = sinc_family(theta, _sin_theta, _cos_theta)
    out[0, 0] = _cos_theta
    out[0, 1] = -_sin_theta
    out[0, 2] = -(_cosc_theta*y) + _sinc_theta*x
    out[1, 0] = _sin_theta
    out[1, 1] = _cos_theta
    out[1, 2] = _cosc_theta*x + _sinc_theta*y
    out[2, 2] = 1.0
    return out


@nb.njit(cache=True)
def se2_log(T):
    """[log_SE(2)(T)]^∨ = [V(θ)^-1 t, θ], θ = atan2(T[1, 0], T[0, 0]) ∈ (-π, π] (paper, log_SE(2)).
    """
    T00 = T[0, 0]
    T02 = T[0, 2]
    T10 = T[1, 0]
    T12 = T[1, 2]
    theta = math.atan2(T10, T00)
    out = np.empty(3)
    _sin_theta = math.sin(theta)
    _cos_theta = math.cos(theta)
    _halfcot_theta = halfcot(theta, _sin_theta, _cos_theta)
    _t0 = theta/2.0
    out[0] = T02*_halfcot_theta + T12*_t0
    out[1] = -(T02*_t0) + T12*_halfcot_theta
    out[2] = theta
    return out


@nb.njit(cache=True)
def se2_inverse(T):
    """T^-1 = [[R^T, -R^T t], [0, 1]].
    """
    T00 = T[0, 0]
    T01 = T[0, 1]
    T02 = T[0, 2]
    T10 = T[1, 0]
    T11 = T[1, 1]
    T12 = T[1, 2]
    out = np.zeros((3, 3))
    out[0, 0] = T00
    out[0, 1] = T10
    out[0, 2] = -(T00*T02) - T10*T12
    out[1, 0] = T01
    out[1, 1] = T11
    out[1, 2] = -(T01*T02) - T11*T12
    out[2, 2] = 1.0
    return out


@nb.njit(cache=True)
def se2_adjoint(T):
    """Ad_SE(2)(T) = [[R, J t], [0, 1]], J = [[0, 1], [-1, 0]] (paper, Ad_SE(2)).
    """
    T00 = T[0, 0]
    T01 = T[0, 1]
    T02 = T[0, 2]
    T10 = T[1, 0]
    T11 = T[1, 1]
    T12 = T[1, 2]
    out = np.zeros((3, 3))
    out[0, 0] = T00
    out[0, 1] = T01
    out[0, 2] = T12
    out[1, 0] = T10
    out[1, 1] = T11
    out[1, 2] = -T02
    out[2, 2] = 1.0
    return out


@nb.njit(cache=True)
def se2_ad(xi):
    """ad_SE(2)([x, y, θ]) = [[-θ J, J v], [0, 0]] (paper's ad_SE(2), corner corrected to 0).
    """
    x = xi[0]
    y = xi[1]
    theta = xi[2]
    out = np.zeros((3, 3))
    out[0, 1] = -theta
    out[0, 2] = y
    out[1, 0] = theta
    out[1, 2] = -x
    return out


@nb.njit(cache=True)
def right_jacobian(xi):
    """Φ_SE(2)(ξ) = Σ (-1)^m/(m+1)! ad(ξ)^m, closed form (paper, Φ_G); log(exp(-ξ) exp(ξ + δ)) ≈ Φ δ.
    """
    x = xi[0]
    y = xi[1]
    theta = xi[2]
    out = np.zeros((3, 3))
    _sin_theta = math.sin(theta)
    _cos_theta = math.cos(theta)
    _sinc_theta, _cosc_theta, _sinc2_theta, _cosc2_theta = sinc_family(theta, _sin_theta, _cos_theta)
    out[0, 0] = _sinc_theta
    out[0, 1] = _cosc_theta
    out[0, 2] = -(_cosc2_theta*y) + _sinc2_theta*x
    out[1, 0] = -_cosc_theta
    out[1, 1] = _sinc_theta
    out[1, 2] = _cosc2_theta*x + _sinc2_theta*y
    out[2, 2] = 1.0
    return out


@nb.njit(cache=True)
def right_jacobian_inv(xi):
    """Φ_SE(2)(ξ)^-1, closed form.
    """
    x = xi[0]
    y = xi[1]
    theta = xi[2]
    out = np.zeros((3, 3))
    _sin_theta = math.sin(theta)
    _cos_theta = math.cos(theta)
    _halfcot_theta = halfcot(theta, _sin_theta, _cos_theta)
    _halfcot1_theta = halfcot1(theta, _sin_theta, _cos_theta)
    _t0 = theta/2.0
    out[0, 0] = _halfcot_theta
    out[0, 1] = -_t0
    out[0, 2] = _halfcot1_theta*x + y/2.0
    out[1, 0] = _t0
    out[1, 1] = _halfcot_theta
    out[1, 2] = _halfcot1_theta*y - x/2.0
    out[2, 2] = 1.0
    return out
