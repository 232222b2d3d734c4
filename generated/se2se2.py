"""LG-EKF on SE(2)×SE(2): model quantities and fused predict/update steps.

GENERATED FILE: DO NOT EDIT.
Source: derive/steps.py (se2se2), from derive/models.py and derive/groups.py
Regenerate with: lgekf derive      (check freshness with: lgekf derive --check)
"""
import math

import numba as nb
import numpy as np
from .special import sinc, cosc, sinc2, cosc2, dsinc, halfcot, halfcot1, gain_damping, wrap_angle  # noqa: F401

# fused steps use FMA contraction only ("contract"); every other IEEE rule holds
FASTMATH = {"contract"}

__all__ = ['state_from_physical', 'state_to_physical', 'physical_into', 'group_mean', 'motion_omega', 'calC', 'calH', 'transition', 'process_noise', 'limit_angle_variance', 'predict', 'update', 'covariance_is_pd', 'repair_pd', 'run_one', 'run_batch', 'propagate', 'simulate_batch', 'world_velocity', 'world_velocities', 'common_to_state', 'common_jacobian', 'tangent_error']


@nb.njit(cache=True)
def state_from_physical(xp):
    """Internal state ['x', 'y', 'c_theta', 's_theta', 'v_x', 'v_y', 'omega', 'c_omega', 's_omega'] from the physical [x, y, θ, v_x, v_y, ω].
    """
    x = xp[0]
    y = xp[1]
    theta = xp[2]
    v_x = xp[3]
    v_y = xp[4]
    omega = xp[5]
    out = np.zeros(9)
    _sin_omega = math.sin(omega)
    _cos_omega = math.cos(omega)
    _sin_theta = math.sin(theta)
    _cos_theta = math.cos(theta)
    out[0] = x
    out[1] = y
    out[2] = _cos_theta
    out[3] = _sin_theta
    out[4] = v_x
    out[5] = v_y
    out[6] = math.atan2(_sin_omega, _cos_omega)
    out[7] = _cos_omega
    out[8] = _sin_omega
    return out


@nb.njit(cache=True)
def state_to_physical(s):
    """Physical [x, y, θ, v_x, v_y, ω] (θ in (-π, π]) from the internal state.
    """
    x = s[0]
    y = s[1]
    c_theta = s[2]
    s_theta = s[3]
    v_x = s[4]
    v_y = s[5]
    omega = s[6]
    out = np.zeros(6)
    out[0] = x
    out[1] = y
    out[2] = wrap_angle(math.atan2(s_theta, c_theta))
    out[3] = v_x
    out[4] = v_y
    out[5] = omega
    return out


@nb.njit(cache=True)
def physical_into(s, out):
    """Physical [x, y, θ, v_x, v_y, ω] from the internal state. Written into ``out`` (no allocation).
    """
    x = s[0]
    y = s[1]
    c_theta = s[2]
    s_theta = s[3]
    v_x = s[4]
    v_y = s[5]
    omega = s[6]
    out[0] = x
    out[1] = y
    out[2] = wrap_angle(math.atan2(s_theta, c_theta))
    out[3] = v_x
    out[4] = v_y
    out[5] = omega


@nb.njit(cache=True)
def group_mean(s):
    """The mean μ as a block-diagonal matrix: diag(T_s, T_d) (SE(2)×SE(2), 6×6) or diag(T_s, [[I, v], [0, 1]]) (SE(2)×R^3, 7×7).
    """
    x = s[0]
    y = s[1]
    c_theta = s[2]
    s_theta = s[3]
    v_x = s[4]
    v_y = s[5]
    c_omega = s[7]
    s_omega = s[8]
    out = np.zeros((6, 6))
    out[0, 0] = c_theta
    out[0, 1] = -s_theta
    out[0, 2] = x
    out[1, 0] = s_theta
    out[1, 1] = c_theta
    out[1, 2] = y
    out[2, 2] = 1.0
    out[3, 3] = c_omega
    out[3, 4] = -s_omega
    out[3, 5] = v_x
    out[4, 3] = s_omega
    out[4, 4] = c_omega
    out[4, 5] = v_y
    out[5, 5] = 1.0
    return out


@nb.njit(cache=True)
def motion_omega(s, dt):
    """Ω(μ) = [T v_x, T v_y, T ω, 0, 0, 0] (eq:motionG).
    """
    v_x = s[4]
    v_y = s[5]
    omega = s[6]
    out = np.zeros(6)
    out[0] = dt*v_x
    out[1] = dt*v_y
    out[2] = dt*omega
    return out


@nb.njit(cache=True)
def calC(s, dt):
    """𝒞 = ∂Ω(μ exp ε)/∂ε at ε = 0 (eq:C, eq:calCFinal).
    """
    c_omega = s[7]
    s_omega = s[8]
    out = np.zeros((6, 6))
    _t0 = c_omega*dt
    _t1 = dt*s_omega
    out[0, 3] = _t0
    out[0, 4] = -_t1
    out[1, 3] = _t1
    out[1, 4] = _t0
    out[2, 5] = dt
    return out


@nb.njit(cache=True)
def calH(s):
    """ℋ = ∂[log_G'(h(μ)^-1 h(μ exp ε))]^∨/∂ε at ε = 0 (eq:calH, eq:calH_model).
    """
    c_theta = s[2]
    s_theta = s[3]
    out = np.zeros((2, 6))
    out[0, 0] = c_theta
    out[0, 1] = -s_theta
    out[1, 0] = s_theta
    out[1, 1] = c_theta
    return out


@nb.njit(cache=True)
def transition(s, dt):
    """F = Ad_G(exp(-Ω)) + Φ_G(Ω) 𝒞 (paper, below eq:pred_cov).
    """
    v_x = s[4]
    v_y = s[5]
    omega = s[6]
    c_omega = s[7]
    s_omega = s[8]
    out = np.zeros((6, 6))
    _a0 = dt*omega
    _sin__a0 = math.sin(_a0)
    _cos__a0 = math.cos(_a0)
    _cosc__a0 = cosc(_a0, _sin__a0, _cos__a0)
    _cosc2__a0 = cosc2(_a0, _sin__a0, _cos__a0)
    _sinc__a0 = sinc(_a0, _sin__a0, _cos__a0)
    _sinc2__a0 = sinc2(_a0, _sin__a0, _cos__a0)
    _t0 = _cosc__a0*dt
    _t1 = _sinc__a0*dt
    _t2 = _t0*s_omega + _t1*c_omega
    _t3 = _t0*c_omega - _t1*s_omega
    _t4 = dt*v_y
    out[0, 0] = _cos__a0
    out[0, 1] = _sin__a0
    out[0, 2] = _t0*v_x - _t1*v_y
    out[0, 3] = _t2
    out[0, 4] = _t3
    out[0, 5] = dt*(-(_cosc2__a0*_t4) + _sinc2__a0*dt*v_x)
    out[1, 0] = -_sin__a0
    out[1, 1] = _cos__a0
    out[1, 2] = _t0*v_y + _t1*v_x
    out[1, 3] = -_t3
    out[1, 4] = _t2
    out[1, 5] = dt*(_cosc2__a0*dt*v_x + _sinc2__a0*_t4)
    out[2, 2] = 1.0
    out[2, 5] = dt
    out[3, 3] = 1.0
    out[4, 4] = 1.0
    out[5, 5] = 1.0
    return out


@nb.njit(cache=True)
def process_noise(dt, sigma_x, sigma_y, sigma_omega):
    """Q = G diag(σ_x², σ_y², σ_ω²) G^T, G = [T²/2 I; T I] (noise n_k of eq:motionG).
    """
    out = np.zeros((6, 6))
    _t0 = sigma_x*sigma_x
    _t1 = (dt*dt*dt*dt)/4.0
    _t2 = (dt*dt*dt)/2.0
    _t3 = _t0*_t2
    _t4 = sigma_y*sigma_y
    _t5 = _t2*_t4
    _t6 = sigma_omega*sigma_omega
    _t7 = _t2*_t6
    _t8 = dt*dt
    out[0, 0] = _t0*_t1
    out[0, 3] = _t3
    out[1, 1] = _t1*_t4
    out[1, 4] = _t5
    out[2, 2] = _t1*_t6
    out[2, 5] = _t7
    out[3, 0] = _t3
    out[3, 3] = _t0*_t8
    out[4, 1] = _t5
    out[4, 4] = _t4*_t8
    out[5, 2] = _t7
    out[5, 5] = _t6*_t8
    return out


@nb.njit(cache=True)
def limit_angle_variance(p):
    """Cap the std of the angle coordinates [2, 5] of P at π by congruence scaling (see derive/steps.py)."""
    if p[11] > math.pi * math.pi:
        f = math.pi / math.sqrt(p[11])
        p[2] *= f
        p[7] *= f
        p[12] *= f
        p[13] *= f
        p[14] *= f
        p[11] = math.pi * math.pi
    if p[20] > math.pi * math.pi:
        f = math.pi / math.sqrt(p[20])
        p[5] *= f
        p[10] *= f
        p[14] *= f
        p[17] *= f
        p[19] *= f
        p[20] = math.pi * math.pi


@nb.njit(cache=True, fastmath=FASTMATH)
def predict(s, p, dt, sigma_x, sigma_y, sigma_omega):
    """Fused LG-EKF prediction, in place: μ ← μ exp(Ω(μ)) (eq:pred_mu),
    P ← F P F^T + Φ(Ω) Q Φ(Ω)^T (eq:pred_cov), Q = G diag(σ²) G^T.
    s: internal state (see module doc), p: packed covariance (21), dt > 0.
    Then the std of the tangent angles is capped at π (limit_angle_variance; inactive while ≤ π).
    """
    x = s[0]
    y = s[1]
    c_theta = s[2]
    s_theta = s[3]
    v_x = s[4]
    v_y = s[5]
    omega = s[6]
    c_omega = s[7]
    s_omega = s[8]
    p00 = p[0]
    p01 = p[1]
    p02 = p[2]
    p03 = p[3]
    p04 = p[4]
    p05 = p[5]
    p11 = p[6]
    p12 = p[7]
    p13 = p[8]
    p14 = p[9]
    p15 = p[10]
    p22 = p[11]
    p23 = p[12]
    p24 = p[13]
    p25 = p[14]
    p33 = p[15]
    p34 = p[16]
    p35 = p[17]
    p44 = p[18]
    p45 = p[19]
    p55 = p[20]
    _a0 = dt*omega
    _sin__a0 = math.sin(_a0)
    _cos__a0 = math.cos(_a0)
    _cosc__a0 = cosc(_a0, _sin__a0, _cos__a0)
    _cosc2__a0 = cosc2(_a0, _sin__a0, _cos__a0)
    _sinc__a0 = sinc(_a0, _sin__a0, _cos__a0)
    _sinc2__a0 = sinc2(_a0, _sin__a0, _cos__a0)
    _t0 = _cosc__a0*dt
    _t1 = _t0*v_x
    _t2 = _sinc__a0*dt
    _t3 = _t2*v_y
    _t4 = _t0*s_omega + _t2*c_omega
    _t5 = _t0*c_omega - _t2*s_omega
    _t6 = dt*v_y
    _t7 = -(_cosc2__a0*_t6) + _sinc2__a0*dt*v_x
    _t8 = _t0*v_y
    _t9 = _cosc2__a0*dt*v_x + _sinc2__a0*_t6
    _t10 = (dt*dt)/2.0
    _t11 = _sinc__a0*_t10
    _t12 = _cosc__a0*_t10
    _t13 = _sinc__a0*dt*v_x - _t8
    _t14 = _t1 + _t3
    f00 = _cos__a0
    f01 = _sin__a0
    f02 = _t1 - _t3
    f03 = _t4
    f04 = _t5
    f05 = _t7*dt
    f10 = -_sin__a0
    f11 = _cos__a0
    f12 = _t2*v_x + _t8
    f13 = -_t5
    f14 = _t4
    f15 = _t9*dt
    g00 = _t11
    g01 = _t12
    g02 = _t10*_t7
    g10 = -_t12
    g11 = _t11
    g12 = _t10*_t9
    g22 = _t10
    e00 = _t13*c_theta - _t14*s_theta + x
    e01 = _t13*s_theta + _t14*c_theta + y
    e02 = _cos__a0*c_theta - _sin__a0*s_theta
    e03 = _cos__a0*s_theta + _sin__a0*c_theta
    m00 = f00*p00 + f01*p01 + f02*p02 + f03*p03 + f04*p04 + f05*p05
    m01 = f00*p01 + f01*p11 + f02*p12 + f03*p13 + f04*p14 + f05*p15
    m02 = f00*p02 + f01*p12 + f02*p22 + f03*p23 + f04*p24 + f05*p25
    m03 = f00*p03 + f01*p13 + f02*p23 + f03*p33 + f04*p34 + f05*p35
    m04 = f00*p04 + f01*p14 + f02*p24 + f03*p34 + f04*p44 + f05*p45
    m05 = f00*p05 + f01*p15 + f02*p25 + f03*p35 + f04*p45 + f05*p55
    m10 = f10*p00 + f11*p01 + f12*p02 + f13*p03 + f14*p04 + f15*p05
    m11 = f10*p01 + f11*p11 + f12*p12 + f13*p13 + f14*p14 + f15*p15
    m12 = f10*p02 + f11*p12 + f12*p22 + f13*p23 + f14*p24 + f15*p25
    m13 = f10*p03 + f11*p13 + f12*p23 + f13*p33 + f14*p34 + f15*p35
    m14 = f10*p04 + f11*p14 + f12*p24 + f13*p34 + f14*p44 + f15*p45
    m15 = f10*p05 + f11*p15 + f12*p25 + f13*p35 + f14*p45 + f15*p55
    m22 = dt*p25 + p22
    m23 = dt*p35 + p23
    m24 = dt*p45 + p24
    m25 = dt*p55 + p25
    _t15 = sigma_x*sigma_x
    _t16 = sigma_y*sigma_y
    _t17 = sigma_omega*sigma_omega
    _t18 = _t15*g00
    _t19 = _t16*g01
    _t20 = _t17*g02
    _t21 = _t17*g12
    _t22 = dt*dt
    p[0] = _t15*(g00*g00) + _t16*(g01*g01) + _t17*(g02*g02) + f00*m00 + f01*m01 + f02*m02 + f03*m03 + f04*m04 + f05*m05
    p[1] = _t18*g10 + _t19*g11 + _t20*g12 + f10*m00 + f11*m01 + f12*m02 + f13*m03 + f14*m04 + f15*m05
    p[2] = _t20*g22 + dt*m05 + m02
    p[3] = _t18*dt + m03
    p[4] = _t19*dt + m04
    p[5] = _t20*dt + m05
    p[6] = _t15*(g10*g10) + _t16*(g11*g11) + _t17*(g12*g12) + f10*m10 + f11*m11 + f12*m12 + f13*m13 + f14*m14 + f15*m15
    p[7] = _t21*g22 + dt*m15 + m12
    p[8] = _t15*dt*g10 + m13
    p[9] = _t16*dt*g11 + m14
    p[10] = _t21*dt + m15
    p[11] = _t17*(g22*g22) + dt*m25 + m22
    p[12] = m23
    p[13] = m24
    p[14] = _t17*dt*g22 + m25
    p[15] = _t15*_t22 + p33
    p[16] = p34
    p[17] = p35
    p[18] = _t16*_t22 + p44
    p[19] = p45
    p[20] = _t17*_t22 + p55
    s[0] = e00
    s[1] = e01
    s[2] = e02
    s[3] = e03
    limit_angle_variance(p)


@nb.njit(cache=True, fastmath=FASTMATH)
def update(s, p, z_x, z_y, r):
    """Fused LG-EKF update with a position measurement z = (z_x, z_y), noise std r, in place.
    K = P ℋ^T (ℋ P ℋ^T + r² I)^-1, ν = K [log_G'(h(μ)^-1 Z)]^∨ (eq:K), μ ← μ exp(ν) (eq:up_mu),
    P ← Φ(ν) [(I - Kℋ) P (I - Kℋ)^T + r² K K^T] Φ(ν)^T: eq:up_P in Joseph form (equal for the
    optimal gain, positive semidefinite by construction). Returns the NIS e^T S^-1 e.
    Safeguards (inactive in regular steps): if a rotation angle of ν exceeds π the gain is damped,
    K → αK with α = π/|angle| (derive.special.gain_damping); if rounding leaves P not positive
    definite (condition numbers ≳ 1e15) a rounding-level diagonal jitter restores it (repair_pd).
    """
    x = s[0]
    y = s[1]
    c_theta = s[2]
    s_theta = s[3]
    v_x = s[4]
    v_y = s[5]
    c_omega = s[7]
    s_omega = s[8]
    p00 = p[0]
    p01 = p[1]
    p02 = p[2]
    p03 = p[3]
    p04 = p[4]
    p05 = p[5]
    p11 = p[6]
    p12 = p[7]
    p13 = p[8]
    p14 = p[9]
    p15 = p[10]
    p22 = p[11]
    p23 = p[12]
    p24 = p[13]
    p25 = p[14]
    p33 = p[15]
    p34 = p[16]
    p35 = p[17]
    p44 = p[18]
    p45 = p[19]
    p55 = p[20]
    _t0 = p01*s_theta
    _t1 = c_theta*p01
    hp00 = -_t0 + c_theta*p00
    hp01 = _t1 - p11*s_theta
    hp02 = c_theta*p02 - p12*s_theta
    hp03 = c_theta*p03 - p13*s_theta
    hp04 = c_theta*p04 - p14*s_theta
    hp05 = c_theta*p05 - p15*s_theta
    hp10 = _t1 + p00*s_theta
    hp11 = _t0 + c_theta*p11
    hp12 = c_theta*p12 + p02*s_theta
    hp13 = c_theta*p13 + p03*s_theta
    hp14 = c_theta*p14 + p04*s_theta
    hp15 = c_theta*p15 + p05*s_theta
    inn00 = -x + z_x
    inn10 = -y + z_y
    _t2 = r*r
    S00 = _t2 + c_theta*hp00 - hp01*s_theta
    S01 = c_theta*hp01 + hp00*s_theta
    S11 = _t2 + c_theta*hp11 + hp10*s_theta
    det = S00*S11 - S01*S01
    _t3 = 1.0/det
    Si00 = S11*_t3
    Si01 = -(S01*_t3)
    Si11 = S00*_t3
    k00 = Si00*hp00 + Si01*hp10
    k01 = Si01*hp00 + Si11*hp10
    k10 = Si00*hp01 + Si01*hp11
    k11 = Si01*hp01 + Si11*hp11
    k20 = Si00*hp02 + Si01*hp12
    k21 = Si01*hp02 + Si11*hp12
    k30 = Si00*hp03 + Si01*hp13
    k31 = Si01*hp03 + Si11*hp13
    k40 = Si00*hp04 + Si01*hp14
    k41 = Si01*hp04 + Si11*hp14
    k50 = Si00*hp05 + Si01*hp15
    k51 = Si01*hp05 + Si11*hp15
    nis = inn00*(Si00*inn00 + Si01*inn10) + inn10*(Si01*inn00 + Si11*inn10)
    nk0 = inn00*k00 + inn10*k01
    nk1 = inn00*k10 + inn10*k11
    nk2 = inn00*k20 + inn10*k21
    nk3 = inn00*k30 + inn10*k31
    nk4 = inn00*k40 + inn10*k41
    nk5 = inn00*k50 + inn10*k51
    alpha = gain_damping(nk2, nk5)
    nu0 = alpha*nk0
    nu1 = alpha*nk1
    nu2 = alpha*nk2
    nu3 = alpha*nk3
    nu4 = alpha*nk4
    nu5 = alpha*nk5
    _sin_nu2 = math.sin(nu2)
    _cos_nu2 = math.cos(nu2)
    _cosc_nu2 = cosc(nu2, _sin_nu2, _cos_nu2)
    _cosc2_nu2 = cosc2(nu2, _sin_nu2, _cos_nu2)
    _sinc_nu2 = sinc(nu2, _sin_nu2, _cos_nu2)
    _sinc2_nu2 = sinc2(nu2, _sin_nu2, _cos_nu2)
    _sin_nu5 = math.sin(nu5)
    _cos_nu5 = math.cos(nu5)
    _cosc_nu5 = cosc(nu5, _sin_nu5, _cos_nu5)
    _cosc2_nu5 = cosc2(nu5, _sin_nu5, _cos_nu5)
    _sinc_nu5 = sinc(nu5, _sin_nu5, _cos_nu5)
    _sinc2_nu5 = sinc2(nu5, _sin_nu5, _cos_nu5)
    _t4 = -(_cosc_nu2*nu1) + _sinc_nu2*nu0
    _t5 = _cosc_nu2*nu0 + _sinc_nu2*nu1
    _t6 = -(_cosc_nu5*nu4) + _sinc_nu5*nu3
    _t7 = _cosc_nu5*nu3 + _sinc_nu5*nu4
    phi00 = _sinc_nu2
    phi01 = _cosc_nu2
    phi02 = -(_cosc2_nu2*nu1) + _sinc2_nu2*nu0
    phi10 = -_cosc_nu2
    phi11 = _sinc_nu2
    phi12 = _cosc2_nu2*nu0 + _sinc2_nu2*nu1
    phi33 = _sinc_nu5
    phi34 = _cosc_nu5
    phi35 = -(_cosc2_nu5*nu4) + _sinc2_nu5*nu3
    phi43 = -_cosc_nu5
    phi44 = _sinc_nu5
    phi45 = _cosc2_nu5*nu3 + _sinc2_nu5*nu4
    mu00 = _t4*c_theta - _t5*s_theta + x
    mu01 = _t4*s_theta + _t5*c_theta + y
    mu02 = _cos_nu2*c_theta - _sin_nu2*s_theta
    mu03 = _cos_nu2*s_theta + _sin_nu2*c_theta
    mu04 = _t6*c_omega - _t7*s_omega + v_x
    mu05 = _t6*s_omega + _t7*c_omega + v_y
    mu06 = _cos_nu5*c_omega - _sin_nu5*s_omega
    mu07 = _cos_nu5*s_omega + _sin_nu5*c_omega
    _t8 = alpha*k01
    _t9 = alpha*k10
    _t10 = alpha*k11
    _t11 = alpha*k21
    _t12 = alpha*k31
    _t13 = alpha*k41
    _t14 = alpha*k51
    a00 = -(_t8*s_theta) - alpha*c_theta*k00 + 1.0
    a01 = -(_t8*c_theta) + alpha*k00*s_theta
    a10 = -(_t10*s_theta) - _t9*c_theta
    a11 = -(_t10*c_theta) + _t9*s_theta + 1.0
    a20 = -(_t11*s_theta) - alpha*c_theta*k20
    a21 = -(_t11*c_theta) + alpha*k20*s_theta
    a30 = -(_t12*s_theta) - alpha*c_theta*k30
    a31 = -(_t12*c_theta) + alpha*k30*s_theta
    a40 = -(_t13*s_theta) - alpha*c_theta*k40
    a41 = -(_t13*c_theta) + alpha*k40*s_theta
    a50 = -(_t14*s_theta) - alpha*c_theta*k50
    a51 = -(_t14*c_theta) + alpha*k50*s_theta
    b00 = a00*p00 + a01*p01
    b01 = a00*p01 + a01*p11
    b02 = a00*p02 + a01*p12
    b03 = a00*p03 + a01*p13
    b04 = a00*p04 + a01*p14
    b05 = a00*p05 + a01*p15
    b10 = a10*p00 + a11*p01
    b11 = a10*p01 + a11*p11
    b12 = a10*p02 + a11*p12
    b13 = a10*p03 + a11*p13
    b14 = a10*p04 + a11*p14
    b15 = a10*p05 + a11*p15
    b20 = a20*p00 + a21*p01 + p02
    b21 = a20*p01 + a21*p11 + p12
    b22 = a20*p02 + a21*p12 + p22
    b23 = a20*p03 + a21*p13 + p23
    b24 = a20*p04 + a21*p14 + p24
    b25 = a20*p05 + a21*p15 + p25
    b30 = a30*p00 + a31*p01 + p03
    b31 = a30*p01 + a31*p11 + p13
    b33 = a30*p03 + a31*p13 + p33
    b34 = a30*p04 + a31*p14 + p34
    b35 = a30*p05 + a31*p15 + p35
    b40 = a40*p00 + a41*p01 + p04
    b41 = a40*p01 + a41*p11 + p14
    b44 = a40*p04 + a41*p14 + p44
    b45 = a40*p05 + a41*p15 + p45
    b50 = a50*p00 + a51*p01 + p05
    b51 = a50*p01 + a51*p11 + p15
    b55 = a50*p05 + a51*p15 + p55
    _t15 = (alpha*alpha)*(r*r)
    _t16 = _t15*k00
    _t17 = _t15*k01
    _t18 = _t15*k10
    _t19 = _t15*k11
    _t20 = _t15*k20
    _t21 = _t15*k21
    _t22 = _t15*k30
    _t23 = _t15*k31
    pj00 = _t15*(k00*k00) + _t15*(k01*k01) + a00*b00 + a01*b01
    pj01 = _t16*k10 + _t17*k11 + a10*b00 + a11*b01
    pj02 = _t16*k20 + _t17*k21 + a20*b00 + a21*b01 + b02
    pj03 = _t16*k30 + _t17*k31 + a30*b00 + a31*b01 + b03
    pj04 = _t16*k40 + _t17*k41 + a40*b00 + a41*b01 + b04
    pj05 = _t16*k50 + _t17*k51 + a50*b00 + a51*b01 + b05
    pj11 = _t15*(k10*k10) + _t15*(k11*k11) + a10*b10 + a11*b11
    pj12 = _t18*k20 + _t19*k21 + a20*b10 + a21*b11 + b12
    pj13 = _t18*k30 + _t19*k31 + a30*b10 + a31*b11 + b13
    pj14 = _t18*k40 + _t19*k41 + a40*b10 + a41*b11 + b14
    pj15 = _t18*k50 + _t19*k51 + a50*b10 + a51*b11 + b15
    pj22 = _t15*(k20*k20) + _t15*(k21*k21) + a20*b20 + a21*b21 + b22
    pj23 = _t20*k30 + _t21*k31 + a30*b20 + a31*b21 + b23
    pj24 = _t20*k40 + _t21*k41 + a40*b20 + a41*b21 + b24
    pj25 = _t20*k50 + _t21*k51 + a50*b20 + a51*b21 + b25
    pj33 = _t15*(k30*k30) + _t15*(k31*k31) + a30*b30 + a31*b31 + b33
    pj34 = _t22*k40 + _t23*k41 + a40*b30 + a41*b31 + b34
    pj35 = _t22*k50 + _t23*k51 + a50*b30 + a51*b31 + b35
    pj44 = _t15*(k40*k40) + _t15*(k41*k41) + a40*b40 + a41*b41 + b44
    pj45 = _t15*k40*k50 + _t15*k41*k51 + a50*b40 + a51*b41 + b45
    pj55 = _t15*(k50*k50) + _t15*(k51*k51) + a50*b50 + a51*b51 + b55
    cp00 = phi00*pj00 + phi01*pj01 + phi02*pj02
    cp01 = phi00*pj01 + phi01*pj11 + phi02*pj12
    cp02 = phi00*pj02 + phi01*pj12 + phi02*pj22
    cp03 = phi00*pj03 + phi01*pj13 + phi02*pj23
    cp04 = phi00*pj04 + phi01*pj14 + phi02*pj24
    cp05 = phi00*pj05 + phi01*pj15 + phi02*pj25
    cp10 = phi10*pj00 + phi11*pj01 + phi12*pj02
    cp11 = phi10*pj01 + phi11*pj11 + phi12*pj12
    cp12 = phi10*pj02 + phi11*pj12 + phi12*pj22
    cp13 = phi10*pj03 + phi11*pj13 + phi12*pj23
    cp14 = phi10*pj04 + phi11*pj14 + phi12*pj24
    cp15 = phi10*pj05 + phi11*pj15 + phi12*pj25
    cp33 = phi33*pj33 + phi34*pj34 + phi35*pj35
    cp34 = phi33*pj34 + phi34*pj44 + phi35*pj45
    cp35 = phi33*pj35 + phi34*pj45 + phi35*pj55
    cp43 = phi43*pj33 + phi44*pj34 + phi45*pj35
    cp44 = phi43*pj34 + phi44*pj44 + phi45*pj45
    cp45 = phi43*pj35 + phi44*pj45 + phi45*pj55
    p[0] = cp00*phi00 + cp01*phi01 + cp02*phi02
    p[1] = cp00*phi10 + cp01*phi11 + cp02*phi12
    p[2] = cp02
    p[3] = cp03*phi33 + cp04*phi34 + cp05*phi35
    p[4] = cp03*phi43 + cp04*phi44 + cp05*phi45
    p[5] = cp05
    p[6] = cp10*phi10 + cp11*phi11 + cp12*phi12
    p[7] = cp12
    p[8] = cp13*phi33 + cp14*phi34 + cp15*phi35
    p[9] = cp13*phi43 + cp14*phi44 + cp15*phi45
    p[10] = cp15
    p[11] = pj22
    p[12] = phi33*pj23 + phi34*pj24 + phi35*pj25
    p[13] = phi43*pj23 + phi44*pj24 + phi45*pj25
    p[14] = pj25
    p[15] = cp33*phi33 + cp34*phi34 + cp35*phi35
    p[16] = cp33*phi43 + cp34*phi44 + cp35*phi45
    p[17] = cp35
    p[18] = cp43*phi43 + cp44*phi44 + cp45*phi45
    p[19] = cp45
    p[20] = pj55
    s[0] = mu00
    s[1] = mu01
    s[2] = mu02
    s[3] = mu03
    s[4] = mu04
    s[5] = mu05
    s[7] = mu06
    s[8] = mu07
    s[6] = math.atan2(mu07, mu06)
    if not covariance_is_pd(p):
        repair_pd(p)
    return nis


@nb.njit(cache=True)
def covariance_is_pd(p):
    """LDLᵀ test of the packed covariance: every pivot d_j > 1e-13 · max_i P_ii (NaN fails)."""
    p00 = p[0]
    p01 = p[1]
    p02 = p[2]
    p03 = p[3]
    p04 = p[4]
    p05 = p[5]
    p11 = p[6]
    p12 = p[7]
    p13 = p[8]
    p14 = p[9]
    p15 = p[10]
    p22 = p[11]
    p23 = p[12]
    p24 = p[13]
    p25 = p[14]
    p33 = p[15]
    p34 = p[16]
    p35 = p[17]
    p44 = p[18]
    p45 = p[19]
    p55 = p[20]
    tol = 1e-13 * max(p00, p11, p22, p33, p44, p55)
    d0 = p00
    if not d0 > tol:
        return False
    r0 = 1.0 / d0
    l10 = (p01) * r0
    l20 = (p02) * r0
    l30 = (p03) * r0
    l40 = (p04) * r0
    l50 = (p05) * r0
    d1 = p11 - l10 * l10 * d0
    if not d1 > tol:
        return False
    r1 = 1.0 / d1
    l21 = (p12 - l20 * l10 * d0) * r1
    l31 = (p13 - l30 * l10 * d0) * r1
    l41 = (p14 - l40 * l10 * d0) * r1
    l51 = (p15 - l50 * l10 * d0) * r1
    d2 = p22 - l20 * l20 * d0 - l21 * l21 * d1
    if not d2 > tol:
        return False
    r2 = 1.0 / d2
    l32 = (p23 - l30 * l20 * d0 - l31 * l21 * d1) * r2
    l42 = (p24 - l40 * l20 * d0 - l41 * l21 * d1) * r2
    l52 = (p25 - l50 * l20 * d0 - l51 * l21 * d1) * r2
    d3 = p33 - l30 * l30 * d0 - l31 * l31 * d1 - l32 * l32 * d2
    if not d3 > tol:
        return False
    r3 = 1.0 / d3
    l43 = (p34 - l40 * l30 * d0 - l41 * l31 * d1 - l42 * l32 * d2) * r3
    l53 = (p35 - l50 * l30 * d0 - l51 * l31 * d1 - l52 * l32 * d2) * r3
    d4 = p44 - l40 * l40 * d0 - l41 * l41 * d1 - l42 * l42 * d2 - l43 * l43 * d3
    if not d4 > tol:
        return False
    r4 = 1.0 / d4
    l54 = (p45 - l50 * l40 * d0 - l51 * l41 * d1 - l52 * l42 * d2 - l53 * l43 * d3) * r4
    d5 = p55 - l50 * l50 * d0 - l51 * l51 * d1 - l52 * l52 * d2 - l53 * l53 * d3 - l54 * l54 * d4
    if not d5 > tol:
        return False
    return True


@nb.njit(cache=True)
def repair_pd(p):
    """Add the smallest diagonal jitter (1e-13 · max_i P_ii, growing ×4) that makes covariance_is_pd pass."""
    scale = 0.0
    for i in (0, 6, 11, 15, 18, 20):
        scale = max(scale, abs(p[i]))
    delta = 1e-13 * scale
    for _ in range(60):
        if covariance_is_pd(p):
            return
        for i in (0, 6, 11, 15, 18, 20):
            p[i] += delta
        delta *= 4.0


@nb.njit(cache=True)
def run_one(z, dts, x0, p0, q, r, out_x, out_p, out_nis):
    """Filter one trajectory: z (K, 2), dts (K,), x0 (6,), p0 (21,); see run_batch."""
    s = state_from_physical(x0)
    p = p0.copy()
    K = z.shape[0]
    keep_p = out_p.shape[0] == K
    for k in range(K):
        predict(s, p, dts[k], q[0], q[1], q[2])
        out_nis[k] = update(s, p, z[k, 0], z[k, 1], r)
        physical_into(s, out_x[k])
        if keep_p:
            for i in range(21):
                out_p[k, i] = p[i]


@nb.njit(cache=True, parallel=True)
def run_batch(z, dts, x0, p0, q, r, out_x, out_p, out_nis):
    """Filter B trajectories in parallel (numba prange), predict then update at every step.

    z (B, K, 2) positions; dts (B, K) step lengths; x0 (B, 6) physical initial states; p0 (B, 21)
    packed initial covariances; q (3,) noise stds; r the measurement std. Writes the posterior
    physical states into out_x (B, K, 6), the packed covariances into out_p (B, K, 21) when
    out_p.shape[1] == K (pass shape (B, 0, 21) to skip), and the NIS into out_nis (B, K).
    """
    for b in nb.prange(z.shape[0]):
        run_one(z[b], dts[b], x0[b], p0[b], q, r, out_x[b], out_p[b], out_nis[b])


@nb.njit(cache=True)
def propagate(s, dt, n_x, n_y, n_omega):
    """Exact motion X ← X exp([Ω(X) + G n]^∧) (eq:model) for one noise sample n = (n_x, n_y, n_ω), in place.
    """
    x = s[0]
    y = s[1]
    c_theta = s[2]
    s_theta = s[3]
    v_x = s[4]
    v_y = s[5]
    omega = s[6]
    c_omega = s[7]
    s_omega = s[8]
    _a0 = dt*n_omega
    _sin__a0 = math.sin(_a0)
    _cos__a0 = math.cos(_a0)
    _cosc__a0 = cosc(_a0, _sin__a0, _cos__a0)
    _sinc__a0 = sinc(_a0, _sin__a0, _cos__a0)
    _a1 = (dt*dt)*n_omega/2.0 + dt*omega
    _sin__a1 = math.sin(_a1)
    _cos__a1 = math.cos(_a1)
    _cosc__a1 = cosc(_a1, _sin__a1, _cos__a1)
    _sinc__a1 = sinc(_a1, _sin__a1, _cos__a1)
    _t0 = (dt*dt)/2.0
    _t1 = _t0*n_y + dt*v_y
    _t2 = _t0*n_x + dt*v_x
    _t3 = -(_cosc__a1*_t1) + _sinc__a1*_t2
    _t4 = _cosc__a1*_t2 + _sinc__a1*_t1
    _t5 = dt*n_y
    _t6 = -(_cosc__a0*_t5) + _sinc__a0*dt*n_x
    _t7 = _cosc__a0*dt*n_x + _sinc__a0*_t5
    xn00 = _t3*c_theta - _t4*s_theta + x
    xn01 = _t3*s_theta + _t4*c_theta + y
    xn02 = _cos__a1*c_theta - _sin__a1*s_theta
    xn03 = _cos__a1*s_theta + _sin__a1*c_theta
    xn04 = _t6*c_omega - _t7*s_omega + v_x
    xn05 = _t6*s_omega + _t7*c_omega + v_y
    xn06 = _cos__a0*c_omega - _sin__a0*s_omega
    xn07 = _cos__a0*s_omega + _sin__a0*c_omega
    s[0] = xn00
    s[1] = xn01
    s[2] = xn02
    s[3] = xn03
    s[4] = xn04
    s[5] = xn05
    s[7] = xn06
    s[8] = xn07
    s[6] = math.atan2(xn07, xn06)


@nb.njit(cache=True, parallel=True)
def simulate_batch(x0, dts, noise, out_x):
    """Simulate the motion model X_{k+1} = X_k exp([Ω(X_k) + G n_k]^) for B trajectories (prange).

    x0 (B, 6) physical initial states; dts (B, K) step lengths; noise (B, K, 3) samples of
    n = (n_x, n_y, n_ω) (already scaled by their stds); out_x (B, K + 1, 6) receives the physical
    states, out_x[:, 0] = x0 (for SE(2)×SE(2) ω is the log of T_d's rotation, in [-π, π]).
    """
    B = x0.shape[0]
    K = dts.shape[1]
    for b in nb.prange(B):
        s = state_from_physical(x0[b])
        physical_into(s, out_x[b, 0])
        for k in range(K):
            propagate(s, dts[b, k], noise[b, k, 0], noise[b, k, 1], noise[b, k, 2])
            physical_into(s, out_x[b, k + 1])


@nb.njit(cache=True)
def world_velocity(x):
    """World-frame velocity (2,) of a physical state x of this model.
    """
    theta = x[2]
    v_x = x[3]
    v_y = x[4]
    out = np.zeros(2)
    _sin_theta = math.sin(theta)
    _cos_theta = math.cos(theta)
    out[0] = _cos_theta*v_x - _sin_theta*v_y
    out[1] = _cos_theta*v_y + _sin_theta*v_x
    return out


@nb.njit(cache=True)
def world_velocities(X, out):
    """world_velocity of every row of X (N, n) into out (N, 2)."""
    for i in range(X.shape[0]):
        v = world_velocity(X[i])
        out[i, 0] = v[0]
        out[i, 1] = v[1]


@nb.njit(cache=True)
def common_to_state(c):
    """The model's physical state from the common c = (x, y, θ, v_x, v_y, ω), (v_x, v_y) in the body frame.
    """
    x = c[0]
    y = c[1]
    theta = c[2]
    v_x = c[3]
    v_y = c[4]
    omega = c[5]
    out = np.zeros(6)
    out[0] = x
    out[1] = y
    out[2] = theta
    out[3] = v_x
    out[4] = v_y
    out[5] = omega
    return out


@nb.njit(cache=True)
def common_jacobian(c):
    """J = ∂(filter coordinates)/∂c at c: maps a covariance of c to the filter's P (P = J P_c J^T).
    """
    theta = c[2]
    omega = c[5]
    out = np.zeros((6, 6))
    _sin_omega = math.sin(omega)
    _cos_omega = math.cos(omega)
    _sin_theta = math.sin(theta)
    _cos_theta = math.cos(theta)
    out[0, 0] = _cos_theta
    out[0, 1] = _sin_theta
    out[1, 0] = -_sin_theta
    out[1, 1] = _cos_theta
    out[2, 2] = 1.0
    out[3, 3] = _cos_omega
    out[3, 4] = _sin_omega
    out[4, 3] = -_sin_omega
    out[4, 4] = _cos_omega
    out[5, 5] = 1.0
    return out


@nb.njit(cache=True)
def tangent_error(s, c):
    """ε = [log_G(μ^-1 X)]^∨: the error of the estimate μ (internal state s) w.r.t. a true physical state c,
    in the coordinates of P (for NEES = εᵀ P^-1 ε).
    """
    x = s[0]
    y = s[1]
    c_theta = s[2]
    s_theta = s[3]
    v_x = s[4]
    v_y = s[5]
    c_omega = s[7]
    s_omega = s[8]
    xt = c[0]
    yt = c[1]
    thetat = c[2]
    vxt = c[3]
    vyt = c[4]
    omegat = c[5]
    out = np.zeros(6)
    _sin_omegat = math.sin(omegat)
    _cos_omegat = math.cos(omegat)
    _sin_thetat = math.sin(thetat)
    _cos_thetat = math.cos(thetat)
    _a0 = math.atan2(c_omega*math.sin(omegat) - s_omega*math.cos(omegat), c_omega*math.cos(omegat) + s_omega*math.sin(omegat))
    _sin__a0 = math.sin(_a0)
    _cos__a0 = math.cos(_a0)
    _halfcot__a0 = halfcot(_a0, _sin__a0, _cos__a0)
    _a1 = math.atan2(c_theta*math.sin(thetat) - s_theta*math.cos(thetat), c_theta*math.cos(thetat) + s_theta*math.sin(thetat))
    _sin__a1 = math.sin(_a1)
    _cos__a1 = math.cos(_a1)
    _halfcot__a1 = halfcot(_a1, _sin__a1, _cos__a1)
    _t0 = -(c_theta*x) + c_theta*xt - s_theta*y + s_theta*yt
    _t1 = -(c_theta*y) + c_theta*yt + s_theta*x - s_theta*xt
    _t2 = math.atan2(-(_cos_thetat*s_theta) + _sin_thetat*c_theta, _cos_thetat*c_theta + _sin_thetat*s_theta)
    _t3 = _t2/2.0
    _t4 = -(c_omega*v_x) + c_omega*vxt - s_omega*v_y + s_omega*vyt
    _t5 = -(c_omega*v_y) + c_omega*vyt + s_omega*v_x - s_omega*vxt
    _t6 = math.atan2(-(_cos_omegat*s_omega) + _sin_omegat*c_omega, _cos_omegat*c_omega + _sin_omegat*s_omega)
    _t7 = _t6/2.0
    out[0] = _halfcot__a1*_t0 + _t1*_t3
    out[1] = _halfcot__a1*_t1 - _t0*_t3
    out[2] = _t2
    out[3] = _halfcot__a0*_t4 + _t5*_t7
    out[4] = _halfcot__a0*_t5 - _t4*_t7
    out[5] = _t6
    return out
