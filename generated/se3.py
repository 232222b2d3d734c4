"""SO(3) and SE(3) building blocks: hat, vee, exp, log (also near |φ| = π), inverse, Ad, ad, right Jacobian Φ and Φ^-1;
tangent order (x, y, z, φx, φy, φz), T = μ·exp(ε), log(exp(-ξ) exp(ξ + δ)) ≈ Φ(ξ) δ.

GENERATED FILE: DO NOT EDIT.
Source: derive/lie/so3.py, derive/lie/se3.py through derive/codegen/families/group.py
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

__all__ = ['so3_hat', 'so3_vee', 'so3_exp', 'so3_log', 'se3_hat', 'se3_vee', 'se3_exp', 'se3_log', 'se3_inverse', 'se3_adjoint', 'se3_ad', 'right_jacobian', 'right_jacobian_inv']


@nb.njit(cache=True)
def so3_hat(phi):
    """[φx, φy, φz]^ = [[0, -φz, φy], [φz, 0, -φx], [-φy, φx, 0]].
    """
    phix = phi[0]
    phiy = phi[1]
    phiz = phi[2]
    out = np.zeros((3, 3))
    out[0, 1] = -phiz
    out[0, 2] = phiy
    out[1, 0] = phiz
    out[1, 2] = -phix
    out[2, 0] = -phiy
    out[2, 1] = phix
    return out


@nb.njit(cache=True)
def so3_vee(R):
    """[M]^∨ = (M[2, 1], M[0, 2], M[1, 0]).
    """
    R02 = R[0, 2]
    R10 = R[1, 0]
    R21 = R[2, 1]
    out = np.zeros(3)
    out[0] = R21
    out[1] = R02
    out[2] = R10
    return out


@nb.njit(cache=True)
def so3_exp(phi):
    """exp_SO(3)(φ^) = I + sinc(t) φ^ + cosc2(t) φ^², t = |φ| (Rodrigues), Taylor-safe at t = 0.
    """
    phix = phi[0]
    phiy = phi[1]
    phiz = phi[2]
    out = np.zeros((3, 3))
    _a0 = math.sqrt(phix*phix + phiy*phiy + phiz*phiz)
    _sin__a0 = math.sin(_a0)
    _cos__a0 = math.cos(_a0)
    _sinc__a0, _cosc__a0, _sinc2__a0, _cosc2__a0 = sinc_family(_a0, _sin__a0, _cos__a0)
    _t0 = _cosc2__a0*(phiy*phiy)
    _t1 = _cosc2__a0*(phiz*phiz) - 1.0
    _t2 = _sinc__a0*phiz
    _t3 = _cosc2__a0*phix
    _t4 = _t3*phiy
    _t5 = _sinc__a0*phiy
    _t6 = _t3*phiz
    _t7 = _cosc2__a0*(phix*phix)
    _t8 = _sinc__a0*phix
    _t9 = _cosc2__a0*phiy*phiz
    out[0, 0] = -_t0 - _t1
    out[0, 1] = -_t2 + _t4
    out[0, 2] = _t5 + _t6
    out[1, 0] = _t2 + _t4
    out[1, 1] = -_t1 - _t7
    out[1, 2] = -_t8 + _t9
    out[2, 0] = -_t5 + _t6
    out[2, 1] = _t8 + _t9
    out[2, 2] = -_t0 - _t7 + 1.0
    return out


@nb.njit(cache=True, error_model="numpy")
def so3_log(R):
    """[log_SO(3)(R)]^∨ = φ, |φ| <= π: θ = atan2(|a|, (tr R - 1)/2), a = [(R - R^T)/2]^∨; φ = a/sinc(θ) if cos θ >= 0, else from the symmetric
    part (R + R^T)/2 - cos θ I = (1 - cos θ) u u^T (its largest column, signed by a): accurate up to |φ| = π.
    """
    R00 = R[0, 0]
    R01 = R[0, 1]
    R02 = R[0, 2]
    R10 = R[1, 0]
    R11 = R[1, 1]
    R12 = R[1, 2]
    R20 = R[2, 0]
    R21 = R[2, 1]
    R22 = R[2, 2]
    theta = math.atan2(math.sqrt((-(R01/2.0) + R10/2.0)*(-(R01/2.0) + R10/2.0) + (R02/2.0 - R20/2.0)*(R02/2.0 - R20/2.0) + (-(R12/2.0) + R21/2.0)*(-(R12/2.0) + R21/2.0)), R00/2.0 + R11/2.0 + R22/2.0 - 0.5)
    out = np.empty(3)
    _sin_theta = math.sin(theta)
    _cos_theta = math.cos(theta)
    _sinc_theta = sinc(theta, _sin_theta, _cos_theta)
    _t0 = 1.0/_sinc_theta
    _t1 = R12/2.0
    _t2 = -(R21/2.0) + _t1
    _t3 = R00/2.0
    _t4 = R11/2.0
    _t5 = R22/2.0
    _t6 = _t4 + _t5
    _t7 = _t3 + _t6
    _t8 = _t7 >= 0.5
    _t9 = -_t5
    _t10 = _t3 - _t4
    _t11 = _t10 + _t9 + 0.5
    _t12 = 1.5 - _t7
    _t13 = theta*(1.0/math.sqrt(_t11*_t12))*(1.0 if _t2 <= 0.0 else -1.0)
    _t14 = -_t3 + _t6
    _t15 = _t10 + _t5
    _t16 = _t3 + _t4 + _t9
    _t17 = (_t14 <= _t15) and (_t14 <= _t16)
    _t18 = R01/2.0
    _t19 = R10/2.0
    _t20 = _t18 + _t19
    _t21 = 0.5 - _t15
    _t22 = R02/2.0
    _t23 = R20/2.0
    _t24 = _t22 - _t23
    _t25 = theta*(1.0/math.sqrt(_t12*_t21))*(1.0 if _t24 >= 0.0 else -1.0)
    _t26 = _t15 <= _t16
    _t27 = _t22 + _t23
    _t28 = 0.5 - _t16
    _t29 = _t18 - _t19
    _t30 = theta*(1.0/math.sqrt(_t12*_t28))*(1.0 if _t29 <= 0.0 else -1.0)
    _t31 = R21/2.0 + _t1
    out[0] = (-(_t0*_t2) if _t8 else (_t11*_t13 if _t17 else (_t20*_t25 if _t26 else _t27*_t30)))
    out[1] = (_t0*_t24 if _t8 else (_t13*_t20 if _t17 else (_t21*_t25 if _t26 else _t30*_t31)))
    out[2] = (-(_t0*_t29) if _t8 else (_t13*_t27 if _t17 else (_t25*_t31 if _t26 else _t28*_t30)))
    return out


@nb.njit(cache=True)
def se3_hat(xi):
    """[x, y, z, φx, φy, φz]^ = [[φ^, ρ], [0, 0]] (4×4), ρ = (x, y, z).
    """
    x = xi[0]
    y = xi[1]
    z = xi[2]
    phix = xi[3]
    phiy = xi[4]
    phiz = xi[5]
    out = np.zeros((4, 4))
    out[0, 1] = -phiz
    out[0, 2] = phiy
    out[0, 3] = x
    out[1, 0] = phiz
    out[1, 2] = -phix
    out[1, 3] = y
    out[2, 0] = -phiy
    out[2, 1] = phix
    out[2, 3] = z
    return out


@nb.njit(cache=True)
def se3_vee(T):
    """[M]^∨ = (M[0, 3], M[1, 3], M[2, 3], M[2, 1], M[0, 2], M[1, 0]).
    """
    T02 = T[0, 2]
    T03 = T[0, 3]
    T10 = T[1, 0]
    T13 = T[1, 3]
    T21 = T[2, 1]
    T23 = T[2, 3]
    out = np.zeros(6)
    out[0] = T03
    out[1] = T13
    out[2] = T23
    out[3] = T21
    out[4] = T02
    out[5] = T10
    return out


@nb.njit(cache=True)
def se3_exp(xi):
    """exp_SE(3)([ρ, φ]^) = [[exp_SO(3)(φ), V(φ) ρ], [0, 1]], V = I + cosc2(t) φ^ + sinc3(t) φ^²,
    t = |φ|, Taylor-safe at t = 0.
    """
    x = xi[0]
    y = xi[1]
    z = xi[2]
    phix = xi[3]
    phiy = xi[4]
    phiz = xi[5]
    out = np.zeros((4, 4))
    _a0 = math.sqrt(phix*phix + phiy*phiy + phiz*phiz)
    _sin__a0 = math.sin(_a0)
    _cos__a0 = math.cos(_a0)
    _sinc__a0, _cosc__a0, _sinc2__a0, _cosc2__a0 = sinc_family(_a0, _sin__a0, _cos__a0)
    _sinc3__a0 = sinc3(_a0, _sin__a0, _cos__a0)
    _t0 = phiy*phiy
    _t1 = _cosc2__a0*_t0
    _t2 = phiz*phiz
    _t3 = _cosc2__a0*_t2 - 1.0
    _t4 = _sinc__a0*phiz
    _t5 = _cosc2__a0*phiy
    _t6 = _t5*phix
    _t7 = _sinc__a0*phiy
    _t8 = _cosc2__a0*phiz
    _t9 = _t8*phix
    _t10 = _sinc3__a0*phix
    _t11 = _sinc3__a0*_t0
    _t12 = _sinc3__a0*_t2 - 1.0
    _t13 = phix*phix
    _t14 = _cosc2__a0*_t13
    _t15 = _sinc__a0*phix
    _t16 = _t8*phiy
    _t17 = _cosc2__a0*phix
    _t18 = _sinc3__a0*_t13
    out[0, 0] = -_t1 - _t3
    out[0, 1] = -_t4 + _t6
    out[0, 2] = _t7 + _t9
    out[0, 3] = x*(-_t11 - _t12) + y*(_sinc3__a0*phix*phiy - _t8) + z*(_t10*phiz + _t5)
    out[1, 0] = _t4 + _t6
    out[1, 1] = -_t14 - _t3
    out[1, 2] = -_t15 + _t16
    out[1, 3] = x*(_t10*phiy + _t8) + y*(-_t12 - _t18) + z*(_sinc3__a0*phiy*phiz - _t17)
    out[2, 0] = -_t7 + _t9
    out[2, 1] = _t15 + _t16
    out[2, 2] = -_t1 - _t14 + 1.0
    out[2, 3] = x*(_sinc3__a0*phix*phiz - _t5) + y*(_sinc3__a0*phiy*phiz + _t17) + z*(-_t11 - _t18 + 1.0)
    out[3, 3] = 1.0
    return out


@nb.njit(cache=True, error_model="numpy")
def se3_log(T):
    """[log_SE(3)(T)]^∨ = (V(φ)^-1 t, φ), V^-1 = I - φ^/2 + halfcot2(θ) φ^², φ = log_SO(3)(R):
    θ = atan2(|a|, (tr R - 1)/2), a = [(R - R^T)/2]^∨; φ = a/sinc(θ) if cos θ >= 0, else from the symmetric
    part (R + R^T)/2 - cos θ I = (1 - cos θ) u u^T (its largest column, signed by a): accurate up to |φ| = π.
    """
    T00 = T[0, 0]
    T01 = T[0, 1]
    T02 = T[0, 2]
    T03 = T[0, 3]
    T10 = T[1, 0]
    T11 = T[1, 1]
    T12 = T[1, 2]
    T13 = T[1, 3]
    T20 = T[2, 0]
    T21 = T[2, 1]
    T22 = T[2, 2]
    T23 = T[2, 3]
    theta = math.atan2(math.sqrt((-(T01/2.0) + T10/2.0)*(-(T01/2.0) + T10/2.0) + (T02/2.0 - T20/2.0)*(T02/2.0 - T20/2.0) + (-(T12/2.0) + T21/2.0)*(-(T12/2.0) + T21/2.0)), T00/2.0 + T11/2.0 + T22/2.0 - 0.5)
    _sin_theta = math.sin(theta)
    _cos_theta = math.cos(theta)
    _sinc_theta = sinc(theta, _sin_theta, _cos_theta)
    _t0 = 1.0/_sinc_theta
    _t1 = T12/2.0
    _t2 = -(T21/2.0) + _t1
    _t3 = T00/2.0
    _t4 = T11/2.0
    _t5 = T22/2.0
    _t6 = _t4 + _t5
    _t7 = _t3 + _t6
    _t8 = _t7 >= 0.5
    _t9 = -_t5
    _t10 = _t3 - _t4
    _t11 = _t10 + _t9 + 0.5
    _t12 = 1.5 - _t7
    _t13 = theta*(1.0/math.sqrt(_t11*_t12))*(1.0 if _t2 <= 0.0 else -1.0)
    _t14 = -_t3 + _t6
    _t15 = _t10 + _t5
    _t16 = _t3 + _t4 + _t9
    _t17 = (_t14 <= _t15) and (_t14 <= _t16)
    _t18 = T01/2.0
    _t19 = T10/2.0
    _t20 = _t18 + _t19
    _t21 = 0.5 - _t15
    _t22 = T02/2.0
    _t23 = T20/2.0
    _t24 = _t22 - _t23
    _t25 = theta*(1.0/math.sqrt(_t12*_t21))*(1.0 if _t24 >= 0.0 else -1.0)
    _t26 = _t15 <= _t16
    _t27 = _t22 + _t23
    _t28 = 0.5 - _t16
    _t29 = _t18 - _t19
    _t30 = theta*(1.0/math.sqrt(_t12*_t28))*(1.0 if _t29 <= 0.0 else -1.0)
    _t31 = T21/2.0 + _t1
    phi0 = (-(_t0*_t2) if _t8 else (_t11*_t13 if _t17 else (_t20*_t25 if _t26 else _t27*_t30)))
    phi1 = (_t0*_t24 if _t8 else (_t13*_t20 if _t17 else (_t21*_t25 if _t26 else _t30*_t31)))
    phi2 = (-(_t0*_t29) if _t8 else (_t13*_t27 if _t17 else (_t25*_t31 if _t26 else _t28*_t30)))
    out = np.empty(6)
    _halfcot2_theta = halfcot2(theta, _sin_theta, _cos_theta)
    _t32 = phi2/2.0
    _t33 = _halfcot2_theta*phi0
    _t34 = _t33*phi1
    _t35 = phi1/2.0
    _t36 = _t33*phi2
    _t37 = _halfcot2_theta*(phi1*phi1)
    _t38 = _halfcot2_theta*(phi2*phi2) - 1.0
    _t39 = phi0/2.0
    _t40 = _halfcot2_theta*phi1*phi2
    _t41 = _halfcot2_theta*(phi0*phi0)
    out[0] = T03*(-_t37 - _t38) + T13*(_t32 + _t34) + T23*(-_t35 + _t36)
    out[1] = T03*(-_t32 + _t34) + T13*(-_t38 - _t41) + T23*(_t39 + _t40)
    out[2] = T03*(_t35 + _t36) + T13*(-_t39 + _t40) + T23*(-_t37 - _t41 + 1.0)
    out[3] = phi0
    out[4] = phi1
    out[5] = phi2
    return out


@nb.njit(cache=True)
def se3_inverse(T):
    """T^-1 = [[R^T, -R^T t], [0, 1]].
    """
    T00 = T[0, 0]
    T01 = T[0, 1]
    T02 = T[0, 2]
    T03 = T[0, 3]
    T10 = T[1, 0]
    T11 = T[1, 1]
    T12 = T[1, 2]
    T13 = T[1, 3]
    T20 = T[2, 0]
    T21 = T[2, 1]
    T22 = T[2, 2]
    T23 = T[2, 3]
    out = np.zeros((4, 4))
    out[0, 0] = T00
    out[0, 1] = T10
    out[0, 2] = T20
    out[0, 3] = -(T00*T03) - T10*T13 - T20*T23
    out[1, 0] = T01
    out[1, 1] = T11
    out[1, 2] = T21
    out[1, 3] = -(T01*T03) - T11*T13 - T21*T23
    out[2, 0] = T02
    out[2, 1] = T12
    out[2, 2] = T22
    out[2, 3] = -(T02*T03) - T12*T13 - T22*T23
    out[3, 3] = 1.0
    return out


@nb.njit(cache=True)
def se3_adjoint(T):
    """Ad_SE(3)(T) = [[R, t^ R], [0, R]] (tangent order ρ, φ).
    """
    T00 = T[0, 0]
    T01 = T[0, 1]
    T02 = T[0, 2]
    T03 = T[0, 3]
    T10 = T[1, 0]
    T11 = T[1, 1]
    T12 = T[1, 2]
    T13 = T[1, 3]
    T20 = T[2, 0]
    T21 = T[2, 1]
    T22 = T[2, 2]
    T23 = T[2, 3]
    out = np.zeros((6, 6))
    out[0, 0] = T00
    out[0, 1] = T01
    out[0, 2] = T02
    out[0, 3] = -(T10*T23) + T13*T20
    out[0, 4] = -(T11*T23) + T13*T21
    out[0, 5] = -(T12*T23) + T13*T22
    out[1, 0] = T10
    out[1, 1] = T11
    out[1, 2] = T12
    out[1, 3] = T00*T23 - T03*T20
    out[1, 4] = T01*T23 - T03*T21
    out[1, 5] = T02*T23 - T03*T22
    out[2, 0] = T20
    out[2, 1] = T21
    out[2, 2] = T22
    out[2, 3] = -(T00*T13) + T03*T10
    out[2, 4] = -(T01*T13) + T03*T11
    out[2, 5] = -(T02*T13) + T03*T12
    out[3, 3] = T00
    out[3, 4] = T01
    out[3, 5] = T02
    out[4, 3] = T10
    out[4, 4] = T11
    out[4, 5] = T12
    out[5, 3] = T20
    out[5, 4] = T21
    out[5, 5] = T22
    return out


@nb.njit(cache=True)
def se3_ad(xi):
    """ad_SE(3)(ρ, φ) = [[φ^, ρ^], [0, φ^]].
    """
    x = xi[0]
    y = xi[1]
    z = xi[2]
    phix = xi[3]
    phiy = xi[4]
    phiz = xi[5]
    out = np.zeros((6, 6))
    _t0 = -phiz
    _t1 = -phix
    _t2 = -phiy
    out[0, 1] = _t0
    out[0, 2] = phiy
    out[0, 4] = -z
    out[0, 5] = y
    out[1, 0] = phiz
    out[1, 2] = _t1
    out[1, 3] = z
    out[1, 5] = -x
    out[2, 0] = _t2
    out[2, 1] = phix
    out[2, 3] = -y
    out[2, 4] = x
    out[3, 4] = _t0
    out[3, 5] = phiy
    out[4, 3] = phiz
    out[4, 5] = _t1
    out[5, 3] = _t2
    out[5, 4] = phix
    return out


@nb.njit(cache=True)
def right_jacobian(xi):
    """Φ_SE(3)(ξ) = [[J_r(φ), Q_r(ρ, φ)], [0, J_r(φ)]] = Σ (-1)^m/(m+1)! ad(ξ)^m (Barfoot's J_l(-ξ));
    log(exp(-ξ) exp(ξ + δ)) ≈ Φ δ. J_r = I - cosc2 φ^ + sinc3 φ^², Q_r(ρ, φ) = Q_l(-ρ, -φ) (derive/lie/se3.py).
    """
    x = xi[0]
    y = xi[1]
    z = xi[2]
    phix = xi[3]
    phiy = xi[4]
    phiz = xi[5]
    out = np.zeros((6, 6))
    _a0 = math.sqrt(phix*phix + phiy*phiy + phiz*phiz)
    _sin__a0 = math.sin(_a0)
    _cos__a0 = math.cos(_a0)
    _cosc2__a0 = cosc2(_a0, _sin__a0, _cos__a0)
    _cosc4__a0 = cosc4(_a0, _sin__a0, _cos__a0)
    _sinc3__a0 = sinc3(_a0, _sin__a0, _cos__a0)
    _sincos5__a0 = sincos5(_a0, _sin__a0, _cos__a0)
    _t0 = phiy*phiy
    _t1 = _sinc3__a0*_t0
    _t2 = phiz*phiz
    _t3 = _sinc3__a0*_t2 - 1.0
    _t4 = -_t1 - _t3
    _t5 = _cosc2__a0*phiz
    _t6 = _sinc3__a0*phix
    _t7 = _t5 + _t6*phiy
    _t8 = _cosc2__a0*phiy
    _t9 = _sinc3__a0*phix*phiz - _t8
    _t10 = phiy*y
    _t11 = 2.0*_t10
    _t12 = phiz*z
    _t13 = 2.0*_t12
    _t14 = phix*x
    _t15 = _t14*phiy
    _t16 = -_t10 - _t12
    _t17 = _t16*phiy
    _t18 = -_t17
    _t19 = _t15 + _t18
    _t20 = _t10*phiz
    _t21 = -_t12 - _t14
    _t22 = _t21*phiz
    _t23 = -_t22
    _t24 = _t20 + _t23
    _t25 = _t12*phiy
    _t26 = -_t10 - _t14
    _t27 = _t26*phiy
    _t28 = -_t27
    _t29 = -_t25 - _t28
    _t30 = _t29*phiy
    _t31 = _t14*phiz
    _t32 = _t16*phiz
    _t33 = -_t32
    _t34 = -_t31 - _t33
    _t35 = _t34*phiz
    _t36 = z/2.0
    _t37 = phix*y + phiy*x
    _t38 = phix*phix
    _t39 = _t0*z + _t38*z
    _t40 = _t12*phix
    _t41 = _t26*phix
    _t42 = -_t41
    _t43 = _t40 + _t42
    _t44 = y/2.0
    _t45 = phix*z + phiz*x
    _t46 = _t10*phix
    _t47 = _t21*phix
    _t48 = -_t47
    _t49 = -_t46 - _t48
    _t50 = _t2*y + _t38*y
    _t51 = _sinc3__a0*phix*phiy - _t5
    _t52 = _sinc3__a0*_t38
    _t53 = -_t3 - _t52
    _t54 = _cosc2__a0*phix
    _t55 = _sinc3__a0*phiy*phiz + _t54
    _t56 = 2.0*_t14
    _t57 = -(_t43*phix) + _t49*phix
    _t58 = x/2.0
    _t59 = phiy*z + phiz*y
    _t60 = _t0*x + _t2*x
    _t61 = _t6*phiz + _t8
    _t62 = _sinc3__a0*phiy*phiz - _t54
    _t63 = -_t1 - _t52 + 1.0
    out[0, 0] = _t4
    out[0, 1] = _t7
    out[0, 2] = _t9
    out[0, 3] = _sinc3__a0*(-_t11 - _t13) + _sincos5__a0*(_t19*phiy + _t24*phiz - _t30 - _t35)
    out[0, 4] = _cosc4__a0*(-_t23 - 2.0*_t32 - _t39 + 3.0*phix*phiz*x) + _sinc3__a0*(-_t31 + _t32 + _t37) + _sincos5__a0*(-(_t19*phix) - _t43*phiy) + _t36
    out[0, 5] = _cosc4__a0*(-(3.0*_t15) + 2.0*_t17 + _t28 + _t50) + _sinc3__a0*(_t19 + _t45) + _sincos5__a0*(_t34*phix + _t49*phiz) - _t44
    out[1, 0] = _t51
    out[1, 1] = _t53
    out[1, 2] = _t55
    out[1, 3] = _cosc4__a0*(-(3.0*_t20) + 2.0*_t22 + _t33 + _t39) + _sinc3__a0*(_t24 + _t37) + _sincos5__a0*(_t29*phix + _t49*phiy) - _t36
    out[1, 4] = _sinc3__a0*(-_t13 - _t56) + _sincos5__a0*(_t24*phiz - _t35 - _t57)
    out[1, 5] = _cosc4__a0*(-_t42 - 2.0*_t47 - _t60 + 3.0*phix*phiy*y) + _sinc3__a0*(-_t46 + _t47 + _t59) + _sincos5__a0*(-(_t19*phiz) - _t24*phiy) + _t58
    out[2, 0] = _t61
    out[2, 1] = _t62
    out[2, 2] = _t63
    out[2, 3] = _cosc4__a0*(-_t18 - 2.0*_t27 - _t50 + 3.0*phiy*phiz*z) + _sinc3__a0*(-_t25 + _t27 + _t45) + _sincos5__a0*(-(_t24*phix) - _t43*phiz) + _t44
    out[2, 4] = _cosc4__a0*(-(3.0*_t40) + 2.0*_t41 + _t48 + _t60) + _sinc3__a0*(_t43 + _t59) + _sincos5__a0*(_t29*phiz + _t34*phiy) - _t58
    out[2, 5] = _sinc3__a0*(-_t11 - _t56) + _sincos5__a0*(_t19*phiy - _t30 - _t57)
    out[3, 3] = _t4
    out[3, 4] = _t7
    out[3, 5] = _t9
    out[4, 3] = _t51
    out[4, 4] = _t53
    out[4, 5] = _t55
    out[5, 3] = _t61
    out[5, 4] = _t62
    out[5, 5] = _t63
    return out


@nb.njit(cache=True)
def right_jacobian_inv(xi):
    """Φ_SE(3)(ξ)^-1 = [[J_r^-1, -J_r^-1 Q_r J_r^-1], [0, J_r^-1]], J_r^-1 = I + φ^/2 + halfcot2 φ^².
    """
    x = xi[0]
    y = xi[1]
    z = xi[2]
    phix = xi[3]
    phiy = xi[4]
    phiz = xi[5]
    out = np.zeros((6, 6))
    _a0 = math.sqrt(phix*phix + phiy*phiy + phiz*phiz)
    _sin__a0 = math.sin(_a0)
    _cos__a0 = math.cos(_a0)
    _cosc4__a0 = cosc4(_a0, _sin__a0, _cos__a0)
    _halfcot2__a0 = halfcot2(_a0, _sin__a0, _cos__a0)
    _sinc3__a0 = sinc3(_a0, _sin__a0, _cos__a0)
    _sincos5__a0 = sincos5(_a0, _sin__a0, _cos__a0)
    _t0 = phiy*phiy
    _t1 = _halfcot2__a0*_t0
    _t2 = phiz*phiz
    _t3 = _halfcot2__a0*_t2 - 1.0
    _t4 = _t1 + _t3
    _t5 = -_t4
    _t6 = phiz/2.0
    _t7 = _halfcot2__a0*phix
    _t8 = _t7*phiy
    _t9 = -_t6 + _t8
    _t10 = phiy/2.0
    _t11 = _t7*phiz
    _t12 = _t10 + _t11
    _t13 = _t6 + _t8
    _t14 = -_t9
    _t15 = phix*x
    _t16 = 2.0*_t15
    _t17 = phiz*z
    _t18 = 2.0*_t17
    _t19 = _t15*phiz
    _t20 = phiy*y
    _t21 = -_t17 - _t20
    _t22 = _t21*phiz
    _t23 = -_t22
    _t24 = -_t19 - _t23
    _t25 = _t24*phiz
    _t26 = _t20*phiz
    _t27 = -_t15 - _t17
    _t28 = _t27*phiz
    _t29 = -_t28
    _t30 = _t26 + _t29
    _t31 = _t20*phix
    _t32 = _t27*phix
    _t33 = -_t32
    _t34 = -_t31 - _t33
    _t35 = _t17*phix
    _t36 = -_t15 - _t20
    _t37 = _t36*phix
    _t38 = -_t37
    _t39 = _t35 + _t38
    _t40 = _t34*phix - _t39*phix
    _t41 = _sinc3__a0*(-_t16 - _t18) + _sincos5__a0*(-_t25 + _t30*phiz - _t40)
    _t42 = -_t12
    _t43 = x/2.0
    _t44 = phiy*z + phiz*y
    _t45 = _t17*phiy
    _t46 = _t36*phiy
    _t47 = -_t46
    _t48 = -_t45 - _t47
    _t49 = _t0*x + _t2*x
    _t50 = _cosc4__a0*(_t33 - 3.0*_t35 + 2.0*_t37 + _t49) + _sinc3__a0*(_t39 + _t44) + _sincos5__a0*(_t24*phiy + _t48*phiz) - _t43
    _t51 = z/2.0
    _t52 = phix*y + phiy*x
    _t53 = phix*phix
    _t54 = _t0*z + _t53*z
    _t55 = _t15*phiy
    _t56 = _t21*phiy
    _t57 = -_t56
    _t58 = _t55 + _t57
    _t59 = _cosc4__a0*(-(2.0*_t22) - _t29 - _t54 + 3.0*phix*phiz*x) + _sinc3__a0*(-_t19 + _t22 + _t52) + _sincos5__a0*(-(_t39*phiy) - _t58*phix) + _t51
    _t60 = _t14*_t41 + _t4*_t59 + _t42*_t50
    _t61 = -_t10 + _t11
    _t62 = 2.0*_t20
    _t63 = _t48*phiy
    _t64 = _sinc3__a0*(-_t16 - _t62) + _sincos5__a0*(-_t40 + _t58*phiy - _t63)
    _t65 = _cosc4__a0*(-(2.0*_t32) - _t38 - _t49 + 3.0*phix*phiy*y) + _sinc3__a0*(-_t31 + _t32 + _t44) + _sincos5__a0*(-(_t30*phiy) - _t58*phiz) + _t43
    _t66 = y/2.0
    _t67 = phix*z + phiz*x
    _t68 = _t2*y + _t53*y
    _t69 = _cosc4__a0*(_t47 - 3.0*_t55 + 2.0*_t56 + _t68) + _sinc3__a0*(_t58 + _t67) + _sincos5__a0*(_t24*phix + _t34*phiz) - _t66
    _t70 = _t14*_t65 + _t4*_t69 + _t42*_t64
    _t71 = _sinc3__a0*(-_t18 - _t62) + _sincos5__a0*(-_t25 + _t30*phiz + _t58*phiy - _t63)
    _t72 = _cosc4__a0*(_t23 - 3.0*_t26 + 2.0*_t28 + _t54) + _sinc3__a0*(_t30 + _t52) + _sincos5__a0*(_t34*phiy + _t48*phix) - _t51
    _t73 = _cosc4__a0*(-(2.0*_t46) - _t57 - _t68 + 3.0*phiy*phiz*z) + _sinc3__a0*(-_t45 + _t46 + _t67) + _sincos5__a0*(-(_t30*phix) - _t39*phiz) + _t66
    _t74 = _t14*_t72 + _t4*_t71 + _t42*_t73
    _t75 = phix/2.0
    _t76 = _halfcot2__a0*phiy*phiz
    _t77 = _t75 + _t76
    _t78 = _halfcot2__a0*_t53
    _t79 = _t3 + _t78
    _t80 = -_t79
    _t81 = -_t75 + _t76
    _t82 = _t1 + _t78 - 1.0
    _t83 = -_t82
    _t84 = -_t81
    _t85 = -_t13
    _t86 = _t41*_t79 + _t50*_t84 + _t59*_t85
    _t87 = _t64*_t84 + _t65*_t79 + _t69*_t85
    _t88 = _t71*_t85 + _t72*_t79 + _t73*_t84
    _t89 = -_t77
    _t90 = -_t61
    _t91 = _t41*_t89 + _t50*_t82 + _t59*_t90
    _t92 = _t64*_t82 + _t65*_t89 + _t69*_t90
    _t93 = _t71*_t90 + _t72*_t89 + _t73*_t82
    out[0, 0] = _t5
    out[0, 1] = _t9
    out[0, 2] = _t12
    out[0, 3] = _t13*_t60 + _t5*_t74 + _t61*_t70
    out[0, 4] = _t60*_t80 + _t70*_t77 + _t74*_t9
    out[0, 5] = _t12*_t74 + _t60*_t81 + _t70*_t83
    out[1, 0] = _t13
    out[1, 1] = _t80
    out[1, 2] = _t81
    out[1, 3] = _t13*_t86 + _t5*_t88 + _t61*_t87
    out[1, 4] = _t77*_t87 + _t80*_t86 + _t88*_t9
    out[1, 5] = _t12*_t88 + _t81*_t86 + _t83*_t87
    out[2, 0] = _t61
    out[2, 1] = _t77
    out[2, 2] = _t83
    out[2, 3] = _t13*_t91 + _t5*_t93 + _t61*_t92
    out[2, 4] = _t77*_t92 + _t80*_t91 + _t9*_t93
    out[2, 5] = _t12*_t93 + _t81*_t91 + _t83*_t92
    out[3, 3] = _t5
    out[3, 4] = _t9
    out[3, 5] = _t12
    out[4, 3] = _t13
    out[4, 4] = _t80
    out[4, 5] = _t81
    out[5, 3] = _t61
    out[5, 4] = _t77
    out[5, 5] = _t83
    return out
