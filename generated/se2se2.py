"""LG-EKF on SE(2)xSE(2) (pose + body-frame velocity as a second SE(2) element): model quantities, fused predict/update steps and loops.

GENERATED FILE: DO NOT EDIT.
Source: derive/models/se2se2.py (definition) through derive/codegen/emitter.py and derive/algebra.py
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

__all__ = ['state_from_physical', 'state_to_physical', 'physical_into', 'group_mean', 'motion_omega', 'motion', 'calC', 'transition', 'process_noise', 'limit_angle_variance', 'predict', 'calH_pose', 'update_pose', 'step_try_pose', 'step_pose', 'measure_pose', 'run_one_pose', 'run_segments_pose', 'run_one_from_pose', 'run_segments_from_pose', 'run_batch_pose', 'measure_batch_pose', 'innovation_into_pose', 'innovation_bank_pose', 'calH_bank_pose', 'run_segments_noise_from_pose', 'rerun_pose', 'recover_pose', 'lane_pose', 'run_batch_soa_pose', 'calH_position', 'update_position', 'step_try_position', 'step_position', 'measure_position', 'run_one_position', 'run_segments_position', 'run_one_from_position', 'run_segments_from_position', 'run_batch_position', 'measure_batch_position', 'innovation_into_position', 'innovation_bank_position', 'calH_bank_position', 'run_segments_noise_from_position', 'rerun_position', 'recover_position', 'lane_position', 'run_batch_soa_position', 'covariance_is_pd', 'covariance_is_pd_fused', 'repair_pd', 'covariance_is_pd_lane', 'physical_lane', 'propagate', 'position_into', 'simulate_batch', 'states_from_physical', 'propagate_rows', 'propagate_positions', 'world_velocity', 'world_velocity_into', 'world_velocities', 'row_speeds', 'common_to_state', 'common_jacobian', 'common_to_states', 'common_jacobians', 'reinit_into', 'speed_std_at', 'speed_stds', 'first_alarm', 'tangent_error', 'retract', 'between', 'right_jacobian', 'right_jacobian_inv', 'predict_bank', 'retract_bank', 'right_jacobian_bank', 'innovation_logdet_pose', 'step_store_pose', 'lane_store_pose', 'run_batch_store_soa_pose', 'run_one_store_pose', 'run_batch_store_pose', 'loglik_batch_pose', 'innovation_logdet_position', 'step_store_position', 'lane_store_position', 'run_batch_store_soa_position', 'run_one_store_position', 'run_batch_store_position', 'loglik_batch_position', 'smooth_step_at', 'lane_smooth', 'physical_smooth_lane', 'smooth_batch_soa', 'smooth_one', 'smooth_batch', 'physical_to_common', 'physical_to_common_jacobian', 'common_missing', 'state_from_physical_into', 'transition_into', 'calH_pose_into', 'calH_position_into', 'common_to_state_into', 'common_jacobian_into', 'between_into', 'right_jacobian_into', 'right_jacobian_inv_into', 'physical_to_common_into', 'physical_to_common_jacobian_into', 'between_add', 'mix_transport', 'common_of_state', 'state_of_common', 'between_add_at', 'mix_transport_at', 'retract_at', 'common_of_state_at', 'state_of_common_at', 'step_ll_pose', 'step_ll_position', 'mix_on_group_at']


@nb.njit(cache=True)
def state_from_physical(xp):
    """Internal state [x, y, c_theta, s_theta, v_x, v_y, omega, c_omega, s_omega] from the physical [x, y, theta, vx, vy, omega].
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
    """Physical [x, y, theta, vx, vy, omega] (angles in (-π, π]) from the internal state.
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
    """Physical [x, y, theta, vx, vy, omega] from the internal state, written into ``out`` (no allocation).
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
    """The mean μ as a group matrix (block-diagonal for a product group).
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
    """Ω(μ), the tangent increment of one step (eq:motionG).
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
def motion(s, dt):
    """The internal state after one noise-free step, μ exp(Ω(μ)) (eq:pred_mu); x' = f(x) for a Euclidean model.
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
    out = np.zeros(9)
    _a0 = dt*omega
    _sin__a0 = math.sin(_a0)
    _cos__a0 = math.cos(_a0)
    _sinc__a0, _cosc__a0, _sinc2__a0, _cosc2__a0 = sinc_family(_a0, _sin__a0, _cos__a0)
    _t0 = dt*v_y
    _t1 = -(_cosc__a0*_t0) + _sinc__a0*dt*v_x
    _t2 = _cosc__a0*dt*v_x + _sinc__a0*_t0
    out[0] = _t1*c_theta - _t2*s_theta + x
    out[1] = _t1*s_theta + _t2*c_theta + y
    out[2] = _cos__a0*c_theta - _sin__a0*s_theta
    out[3] = _cos__a0*s_theta + _sin__a0*c_theta
    out[4] = v_x
    out[5] = v_y
    out[6] = omega
    out[7] = c_omega
    out[8] = s_omega
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
    _sinc__a0, _cosc__a0, _sinc2__a0, _cosc2__a0 = sinc_family(_a0, _sin__a0, _cos__a0)
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
def process_noise(s, dt, sigma_x, sigma_y, sigma_omega):
    """Q = G diag(σ²) G^T: the noise n (sigma_x, sigma_y, sigma_omega) of eq:motionG in the tangent.
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
    """Cap the std of the angle coordinates [2, 5] of P at π by congruence scaling (see derive/codegen/emitter.py)."""
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
    s: internal state [x, y, c_theta, s_theta, v_x, v_y, omega, c_omega, s_omega], p: packed covariance (21), dt > 0.
    Then the std of the tangent angles is capped at π (limit_angle_variance; inactive while ≤ π).
    legend: cc = 𝒞 (eq:C), f = F = Ad(exp(−Ω)) + Φ(Ω)𝒞 (eq:pred_cov), g = Φ(Ω)G, hh = ℋ (eq:calH), hp = ℋP, inn = [log_G'(h(μ)⁻¹Z)]^∨, S = ℋPℋᵀ + R, Si = S⁻¹, k = K (eq:K), nk = Kν, alpha = gain damping, nu = ν, phi = Φ(ν) (eq:up_P), a = I − αKℋ, b = aP, beta = α(2 − α), kb = βK, pj = Joseph-form P (= P − βKℋP), cp = Φ(ν)·pj, mu/e = new mean
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
    _t0 = c_omega*dt
    _t1 = dt*s_omega
    cc03 = _t0
    cc04 = -_t1
    cc13 = _t1
    cc14 = _t0
    _a0 = dt*omega
    _sin__a0 = math.sin(_a0)
    _cos__a0 = math.cos(_a0)
    _sinc__a0, _cosc__a0, _sinc2__a0, _cosc2__a0 = sinc_family(_a0, _sin__a0, _cos__a0)
    _t2 = dt*v_x
    _t3 = _cosc__a0*_t2
    _t4 = dt*v_y
    _t5 = _sinc__a0*_t4
    _t6 = -(_cosc2__a0*_t4) + _sinc2__a0*dt*v_x
    _t7 = _cosc__a0*_t4
    _t8 = _cosc2__a0*_t2 + _sinc2__a0*_t4
    _t9 = (dt*dt)/2.0
    _t10 = _sinc__a0*_t9
    _t11 = _cosc__a0*_t9
    _t12 = _sinc__a0*dt*v_x - _t7
    _t13 = _t3 + _t5
    f00 = _cos__a0
    f01 = _sin__a0
    f02 = _t3 - _t5
    f03 = _cosc__a0*cc13 + _sinc__a0*cc03
    f04 = _cosc__a0*cc14 + _sinc__a0*cc04
    f05 = _t6*dt
    f10 = -_sin__a0
    f11 = _cos__a0
    f12 = _sinc__a0*_t2 + _t7
    f13 = -(_cosc__a0*cc03) + _sinc__a0*cc13
    f14 = -(_cosc__a0*cc04) + _sinc__a0*cc14
    f15 = _t8*dt
    g00 = _t10
    g01 = _t11
    g02 = _t6*_t9
    g10 = -_t11
    g11 = _t10
    g12 = _t8*_t9
    g22 = _t9
    e00 = _t12*c_theta - _t13*s_theta + x
    e01 = _t12*s_theta + _t13*c_theta + y
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
    _t14 = sigma_x*sigma_x
    _t15 = sigma_y*sigma_y
    _t16 = sigma_omega*sigma_omega
    _t17 = _t14*g00
    _t18 = _t15*g01
    _t19 = _t16*g02
    _t20 = _t16*g12
    _t21 = dt*dt
    p[0] = _t14*(g00*g00) + _t15*(g01*g01) + _t16*(g02*g02) + f00*m00 + f01*m01 + f02*m02 + f03*m03 + f04*m04 + f05*m05
    p[1] = _t17*g10 + _t18*g11 + _t19*g12 + f10*m00 + f11*m01 + f12*m02 + f13*m03 + f14*m04 + f15*m05
    p[2] = _t19*g22 + dt*m05 + m02
    p[3] = _t17*dt + m03
    p[4] = _t18*dt + m04
    p[5] = _t19*dt + m05
    p[6] = _t14*(g10*g10) + _t15*(g11*g11) + _t16*(g12*g12) + f10*m10 + f11*m11 + f12*m12 + f13*m13 + f14*m14 + f15*m15
    p[7] = _t20*g22 + dt*m15 + m12
    p[8] = _t14*dt*g10 + m13
    p[9] = _t15*dt*g11 + m14
    p[10] = _t20*dt + m15
    p[11] = _t16*(g22*g22) + dt*m25 + m22
    p[12] = m23
    p[13] = m24
    p[14] = _t16*dt*g22 + m25
    p[15] = _t14*_t21 + p33
    p[16] = p34
    p[17] = p35
    p[18] = _t15*_t21 + p44
    p[19] = p45
    p[20] = _t16*_t21 + p55
    s[0] = e00
    s[1] = e01
    s[2] = e02
    s[3] = e03
    limit_angle_variance(p)


@nb.njit(cache=True)
def calH_pose(s):
    """ℋ = ∂[log_G'(h(μ)^-1 h(μ exp ε))]^∨/∂ε at ε = 0 (eq:calH, eq:calH_model) for pose measurements.
    """
    out = np.zeros((3, 6))
    out[0, 0] = 1.0
    out[1, 1] = 1.0
    out[2, 2] = 1.0
    return out


@nb.njit(cache=True, fastmath=FASTMATH)
def update_pose(s, p, z_x, z_y, z_theta, r_x, r_y, r_theta):
    """Fused update with a pose measurement (2-D pose z = (x, y, θ) in SE(2) with noise stds (r_x, r_y, r_θ) in its tangent (body frame)), in place.
    z = (z_x, z_y, z_theta), noise stds (r_x, r_y, r_theta); Z = h(μ)·exp(m), m ~ N(0, R) in the tangent of G'.
    K = P ℋ^T (ℋ P ℋ^T + R)^-1, ν = K [log_G'(h(μ)^-1 Z)]^∨ (eq:K), μ ← μ exp(ν) (eq:up_mu),
    P ← Φ(ν) [(I - Kℋ) P (I - Kℋ)^T + K R K^T] Φ(ν)^T: eq:up_P in Joseph form. Returns the NIS e^T S^-1 e.
    Safeguard: if a rotation angle of ν exceeds π the gain is damped, K → αK, α = π/|angle|
    (derive.lie.special.gain_damping; α = 1 in every regular step).
    If rounding leaves P not positive definite (condition numbers ≳ 1e15) a rounding-level jitter restores it (repair_pd).
    legend: cc = 𝒞 (eq:C), f = F = Ad(exp(−Ω)) + Φ(Ω)𝒞 (eq:pred_cov), g = Φ(Ω)G, hh = ℋ (eq:calH), hp = ℋP, inn = [log_G'(h(μ)⁻¹Z)]^∨, S = ℋPℋᵀ + R, Si = S⁻¹, k = K (eq:K), nk = Kν, alpha = gain damping, nu = ν, phi = Φ(ν) (eq:up_P), a = I − αKℋ, b = aP, beta = α(2 − α), kb = βK, pj = Joseph-form P (= P − βKℋP), cp = Φ(ν)·pj, mu/e = new mean
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
    _sin_z_theta = math.sin(z_theta)
    _cos_z_theta = math.cos(z_theta)
    _a0 = math.atan2(c_theta*math.sin(z_theta) - s_theta*math.cos(z_theta), c_theta*math.cos(z_theta) + s_theta*math.sin(z_theta))
    _sin__a0 = math.sin(_a0)
    _cos__a0 = math.cos(_a0)
    _halfcot__a0 = halfcot(_a0, _sin__a0, _cos__a0)
    _t0 = -(c_theta*x) + c_theta*z_x - s_theta*y + s_theta*z_y
    _t1 = -(c_theta*y) + c_theta*z_y + s_theta*x - s_theta*z_x
    _t2 = math.atan2(-(_cos_z_theta*s_theta) + _sin_z_theta*c_theta, _cos_z_theta*c_theta + _sin_z_theta*s_theta)
    _t3 = _t2/2.0
    inn00 = _halfcot__a0*_t0 + _t1*_t3
    inn10 = _halfcot__a0*_t1 - _t0*_t3
    inn20 = _t2
    S00 = p00 + r_x*r_x
    S11 = p11 + r_y*r_y
    S22 = p22 + r_theta*r_theta
    rdet = 1.0/(S00*S11*S22 - S00*(p12*p12) - S11*(p02*p02) - S22*(p01*p01) + 2.0*p01*p02*p12)
    Si00 = rdet*(S11*S22 - p12*p12)
    Si01 = rdet*(-(S22*p01) + p02*p12)
    Si02 = rdet*(-(S11*p02) + p01*p12)
    Si11 = rdet*(S00*S22 - p02*p02)
    Si12 = rdet*(-(S00*p12) + p01*p02)
    Si22 = rdet*(S00*S11 - p01*p01)
    _t4 = Si01*p01
    _t5 = Si02*p02
    _t6 = Si12*p12
    _t7 = 2.0*inn00
    k00 = Si00*p00 + _t4 + _t5
    k01 = Si01*p00 + Si11*p01 + Si12*p02
    k02 = Si02*p00 + Si12*p01 + Si22*p02
    k10 = Si00*p01 + Si01*p11 + Si02*p12
    k11 = Si11*p11 + _t4 + _t6
    k12 = Si02*p01 + Si12*p11 + Si22*p12
    k20 = Si00*p02 + Si01*p12 + Si02*p22
    k21 = Si01*p02 + Si11*p12 + Si12*p22
    k22 = Si22*p22 + _t5 + _t6
    k30 = Si00*p03 + Si01*p13 + Si02*p23
    k31 = Si01*p03 + Si11*p13 + Si12*p23
    k32 = Si02*p03 + Si12*p13 + Si22*p23
    k40 = Si00*p04 + Si01*p14 + Si02*p24
    k41 = Si01*p04 + Si11*p14 + Si12*p24
    k42 = Si02*p04 + Si12*p14 + Si22*p24
    k50 = Si00*p05 + Si01*p15 + Si02*p25
    k51 = Si01*p05 + Si11*p15 + Si12*p25
    k52 = Si02*p05 + Si12*p15 + Si22*p25
    nis = Si00*(inn00*inn00) + Si01*_t7*inn10 + Si02*_t7*inn20 + Si11*(inn10*inn10) + 2.0*Si12*inn10*inn20 + Si22*(inn20*inn20)
    nk0 = inn00*k00 + inn10*k01 + inn20*k02
    nk1 = inn00*k10 + inn10*k11 + inn20*k12
    nk2 = inn00*k20 + inn10*k21 + inn20*k22
    nk3 = inn00*k30 + inn10*k31 + inn20*k32
    nk4 = inn00*k40 + inn10*k41 + inn20*k42
    nk5 = inn00*k50 + inn10*k51 + inn20*k52
    alpha = gain_damping(nk2, nk5)
    nu0 = alpha*nk0
    nu1 = alpha*nk1
    nu2 = alpha*nk2
    nu3 = alpha*nk3
    nu4 = alpha*nk4
    nu5 = alpha*nk5
    _sin_nu2 = math.sin(nu2)
    _cos_nu2 = math.cos(nu2)
    _sinc_nu2, _cosc_nu2, _sinc2_nu2, _cosc2_nu2 = sinc_family(nu2, _sin_nu2, _cos_nu2)
    _sin_nu5 = math.sin(nu5)
    _cos_nu5 = math.cos(nu5)
    _sinc_nu5, _cosc_nu5, _sinc2_nu5, _cosc2_nu5 = sinc_family(nu5, _sin_nu5, _cos_nu5)
    _t8 = -(_cosc_nu2*nu1) + _sinc_nu2*nu0
    _t9 = _cosc_nu2*nu0 + _sinc_nu2*nu1
    _t10 = -(_cosc_nu5*nu4) + _sinc_nu5*nu3
    _t11 = _cosc_nu5*nu3 + _sinc_nu5*nu4
    _t12 = _cos_nu5*s_omega + _sin_nu5*c_omega
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
    mu00 = _t8*c_theta - _t9*s_theta + x
    mu01 = _t8*s_theta + _t9*c_theta + y
    mu02 = _cos_nu2*c_theta - _sin_nu2*s_theta
    mu03 = _cos_nu2*s_theta + _sin_nu2*c_theta
    mu04 = _t10*c_omega - _t11*s_omega + v_x
    mu05 = _t10*s_omega + _t11*c_omega + v_y
    mu06 = wrap_angle_sum(nu5 + omega, _t12)
    mu07 = _cos_nu5*c_omega - _sin_nu5*s_omega
    mu08 = _t12
    a00 = -(alpha*k00) + 1.0
    a01 = -(alpha*k01)
    a02 = -(alpha*k02)
    a10 = -(alpha*k10)
    a11 = -(alpha*k11) + 1.0
    a12 = -(alpha*k12)
    a20 = -(alpha*k20)
    a21 = -(alpha*k21)
    a22 = -(alpha*k22) + 1.0
    a30 = -(alpha*k30)
    a31 = -(alpha*k31)
    a32 = -(alpha*k32)
    a40 = -(alpha*k40)
    a41 = -(alpha*k41)
    a42 = -(alpha*k42)
    a50 = -(alpha*k50)
    a51 = -(alpha*k51)
    a52 = -(alpha*k52)
    b00 = a00*p00 + a01*p01 + a02*p02
    b01 = a00*p01 + a01*p11 + a02*p12
    b02 = a00*p02 + a01*p12 + a02*p22
    b03 = a00*p03 + a01*p13 + a02*p23
    b04 = a00*p04 + a01*p14 + a02*p24
    b05 = a00*p05 + a01*p15 + a02*p25
    b10 = a10*p00 + a11*p01 + a12*p02
    b11 = a10*p01 + a11*p11 + a12*p12
    b12 = a10*p02 + a11*p12 + a12*p22
    b13 = a10*p03 + a11*p13 + a12*p23
    b14 = a10*p04 + a11*p14 + a12*p24
    b15 = a10*p05 + a11*p15 + a12*p25
    b20 = a20*p00 + a21*p01 + a22*p02
    b21 = a20*p01 + a21*p11 + a22*p12
    b22 = a20*p02 + a21*p12 + a22*p22
    b23 = a20*p03 + a21*p13 + a22*p23
    b24 = a20*p04 + a21*p14 + a22*p24
    b25 = a20*p05 + a21*p15 + a22*p25
    b30 = a30*p00 + a31*p01 + a32*p02 + p03
    b31 = a30*p01 + a31*p11 + a32*p12 + p13
    b32 = a30*p02 + a31*p12 + a32*p22 + p23
    b33 = a30*p03 + a31*p13 + a32*p23 + p33
    b34 = a30*p04 + a31*p14 + a32*p24 + p34
    b35 = a30*p05 + a31*p15 + a32*p25 + p35
    b40 = a40*p00 + a41*p01 + a42*p02 + p04
    b41 = a40*p01 + a41*p11 + a42*p12 + p14
    b42 = a40*p02 + a41*p12 + a42*p22 + p24
    b44 = a40*p04 + a41*p14 + a42*p24 + p44
    b45 = a40*p05 + a41*p15 + a42*p25 + p45
    b50 = a50*p00 + a51*p01 + a52*p02 + p05
    b51 = a50*p01 + a51*p11 + a52*p12 + p15
    b52 = a50*p02 + a51*p12 + a52*p22 + p25
    b55 = a50*p05 + a51*p15 + a52*p25 + p55
    _t13 = alpha*alpha
    _t14 = _t13*(r_x*r_x)
    _t15 = _t13*(r_y*r_y)
    _t16 = _t13*(r_theta*r_theta)
    _t17 = _t14*k00
    _t18 = _t15*k01
    _t19 = _t16*k02
    _t20 = _t14*k10
    _t21 = _t15*k11
    _t22 = _t16*k12
    _t23 = _t14*k20
    _t24 = _t15*k21
    _t25 = _t16*k22
    _t26 = _t14*k30
    _t27 = _t15*k31
    _t28 = _t16*k32
    pj00 = _t14*(k00*k00) + _t15*(k01*k01) + _t16*(k02*k02) + a00*b00 + a01*b01 + a02*b02
    pj01 = _t17*k10 + _t18*k11 + _t19*k12 + a10*b00 + a11*b01 + a12*b02
    pj02 = _t17*k20 + _t18*k21 + _t19*k22 + a20*b00 + a21*b01 + a22*b02
    pj03 = _t17*k30 + _t18*k31 + _t19*k32 + a30*b00 + a31*b01 + a32*b02 + b03
    pj04 = _t17*k40 + _t18*k41 + _t19*k42 + a40*b00 + a41*b01 + a42*b02 + b04
    pj05 = _t17*k50 + _t18*k51 + _t19*k52 + a50*b00 + a51*b01 + a52*b02 + b05
    pj11 = _t14*(k10*k10) + _t15*(k11*k11) + _t16*(k12*k12) + a10*b10 + a11*b11 + a12*b12
    pj12 = _t20*k20 + _t21*k21 + _t22*k22 + a20*b10 + a21*b11 + a22*b12
    pj13 = _t20*k30 + _t21*k31 + _t22*k32 + a30*b10 + a31*b11 + a32*b12 + b13
    pj14 = _t20*k40 + _t21*k41 + _t22*k42 + a40*b10 + a41*b11 + a42*b12 + b14
    pj15 = _t20*k50 + _t21*k51 + _t22*k52 + a50*b10 + a51*b11 + a52*b12 + b15
    pj22 = _t14*(k20*k20) + _t15*(k21*k21) + _t16*(k22*k22) + a20*b20 + a21*b21 + a22*b22
    pj23 = _t23*k30 + _t24*k31 + _t25*k32 + a30*b20 + a31*b21 + a32*b22 + b23
    pj24 = _t23*k40 + _t24*k41 + _t25*k42 + a40*b20 + a41*b21 + a42*b22 + b24
    pj25 = _t23*k50 + _t24*k51 + _t25*k52 + a50*b20 + a51*b21 + a52*b22 + b25
    pj33 = _t14*(k30*k30) + _t15*(k31*k31) + _t16*(k32*k32) + a30*b30 + a31*b31 + a32*b32 + b33
    pj34 = _t26*k40 + _t27*k41 + _t28*k42 + a40*b30 + a41*b31 + a42*b32 + b34
    pj35 = _t26*k50 + _t27*k51 + _t28*k52 + a50*b30 + a51*b31 + a52*b32 + b35
    pj44 = _t14*(k40*k40) + _t15*(k41*k41) + _t16*(k42*k42) + a40*b40 + a41*b41 + a42*b42 + b44
    pj45 = _t14*k40*k50 + _t15*k41*k51 + _t16*k42*k52 + a50*b40 + a51*b41 + a52*b42 + b45
    pj55 = _t14*(k50*k50) + _t15*(k51*k51) + _t16*(k52*k52) + a50*b50 + a51*b51 + a52*b52 + b55
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
    s[6] = mu06
    s[7] = mu07
    s[8] = mu08
    if not covariance_is_pd(p):
        repair_pd(p)
    return nis


@nb.njit(cache=True, fastmath=FASTMATH, error_model="numpy")
def step_try_pose(s, p, dt, sigma_x, sigma_y, sigma_omega, z_x, z_y, z_theta, r_x, r_y, r_theta):
    """One fused LG-EKF step with a pose measurement, in place: ``predict`` then ``update_pose``
    (eq:pred_mu, eq:pred_cov, angle-variance cap, eq:K, eq:up_mu, eq:up_P) in one kernel; returns the NIS.
    Covariance as P − βKℋP; a step whose result fails the LDLᵀ test (covariance_is_pd_fused) leaves the
    prediction in s, p and returns -1.0: the caller then runs update_pose (Joseph form;
    derive/codegen/fused.py).
    legend: cc = 𝒞 (eq:C), f = F = Ad(exp(−Ω)) + Φ(Ω)𝒞 (eq:pred_cov), g = Φ(Ω)G, hh = ℋ (eq:calH), hp = ℋP, inn = [log_G'(h(μ)⁻¹Z)]^∨, S = ℋPℋᵀ + R, Si = S⁻¹, k = K (eq:K), nk = Kν, alpha = gain damping, nu = ν, phi = Φ(ν) (eq:up_P), a = I − αKℋ, b = aP, beta = α(2 − α), kb = βK, pj = Joseph-form P (= P − βKℋP), cp = Φ(ν)·pj, mu/e = new mean
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
    _t0 = c_omega*dt
    _t1 = dt*s_omega
    cc03 = _t0
    cc04 = -_t1
    cc13 = _t1
    cc14 = _t0
    _a0 = dt*omega
    _sin__a0 = math.sin(_a0)
    _cos__a0 = math.cos(_a0)
    _sinc__a0, _cosc__a0, _sinc2__a0, _cosc2__a0 = sinc_family(_a0, _sin__a0, _cos__a0)
    _t2 = dt*v_x
    _t3 = _cosc__a0*_t2
    _t4 = dt*v_y
    _t5 = _sinc__a0*_t4
    _t6 = -(_cosc2__a0*_t4) + _sinc2__a0*dt*v_x
    _t7 = _cosc__a0*_t4
    _t8 = _cosc2__a0*_t2 + _sinc2__a0*_t4
    _t9 = (dt*dt)/2.0
    _t10 = _sinc__a0*_t9
    _t11 = _cosc__a0*_t9
    _t12 = _sinc__a0*dt*v_x - _t7
    _t13 = _t3 + _t5
    f00 = _cos__a0
    f01 = _sin__a0
    f02 = _t3 - _t5
    f03 = _cosc__a0*cc13 + _sinc__a0*cc03
    f04 = _cosc__a0*cc14 + _sinc__a0*cc04
    f05 = _t6*dt
    f10 = -_sin__a0
    f11 = _cos__a0
    f12 = _sinc__a0*_t2 + _t7
    f13 = -(_cosc__a0*cc03) + _sinc__a0*cc13
    f14 = -(_cosc__a0*cc04) + _sinc__a0*cc14
    f15 = _t8*dt
    g00 = _t10
    g01 = _t11
    g02 = _t6*_t9
    g10 = -_t11
    g11 = _t10
    g12 = _t8*_t9
    g22 = _t9
    e00 = _t12*c_theta - _t13*s_theta + x
    e01 = _t12*s_theta + _t13*c_theta + y
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
    _t14 = sigma_x*sigma_x
    _t15 = sigma_y*sigma_y
    _t16 = sigma_omega*sigma_omega
    _t17 = _t14*g00
    _t18 = _t15*g01
    _t19 = _t16*g02
    _t20 = _t16*g12
    _t21 = dt*dt
    pp00 = _t14*(g00*g00) + _t15*(g01*g01) + _t16*(g02*g02) + f00*m00 + f01*m01 + f02*m02 + f03*m03 + f04*m04 + f05*m05
    pp01 = _t17*g10 + _t18*g11 + _t19*g12 + f10*m00 + f11*m01 + f12*m02 + f13*m03 + f14*m04 + f15*m05
    pp02 = _t19*g22 + dt*m05 + m02
    pp03 = _t17*dt + m03
    pp04 = _t18*dt + m04
    pp05 = _t19*dt + m05
    pp11 = _t14*(g10*g10) + _t15*(g11*g11) + _t16*(g12*g12) + f10*m10 + f11*m11 + f12*m12 + f13*m13 + f14*m14 + f15*m15
    pp12 = _t20*g22 + dt*m15 + m12
    pp13 = _t14*dt*g10 + m13
    pp14 = _t15*dt*g11 + m14
    pp15 = _t20*dt + m15
    pp22 = _t16*(g22*g22) + dt*m25 + m22
    pp23 = m23
    pp24 = m24
    pp25 = _t16*dt*g22 + m25
    pp33 = _t14*_t21 + p33
    pp34 = p34
    pp35 = p35
    pp44 = _t15*_t21 + p44
    pp45 = p45
    pp55 = _t16*_t21 + p55
    x_p = e00
    y_p = e01
    c_theta_p = e02
    s_theta_p = e03
    if pp22 > math.pi * math.pi:
        _cap = math.pi / math.sqrt(pp22)
        pp02 = pp02 * _cap
        pp12 = pp12 * _cap
        pp23 = pp23 * _cap
        pp24 = pp24 * _cap
        pp25 = pp25 * _cap
        pp22 = math.pi * math.pi
    if pp55 > math.pi * math.pi:
        _cap = math.pi / math.sqrt(pp55)
        pp05 = pp05 * _cap
        pp15 = pp15 * _cap
        pp25 = pp25 * _cap
        pp35 = pp35 * _cap
        pp45 = pp45 * _cap
        pp55 = math.pi * math.pi
    _sin_z_theta = math.sin(z_theta)
    _cos_z_theta = math.cos(z_theta)
    _a1 = math.atan2(c_theta_p*math.sin(z_theta) - s_theta_p*math.cos(z_theta), c_theta_p*math.cos(z_theta) + s_theta_p*math.sin(z_theta))
    _sin__a1 = math.sin(_a1)
    _cos__a1 = math.cos(_a1)
    _halfcot__a1 = halfcot(_a1, _sin__a1, _cos__a1)
    _t22 = -(c_theta_p*x_p) + c_theta_p*z_x - s_theta_p*y_p + s_theta_p*z_y
    _t23 = -(c_theta_p*y_p) + c_theta_p*z_y + s_theta_p*x_p - s_theta_p*z_x
    _t24 = math.atan2(-(_cos_z_theta*s_theta_p) + _sin_z_theta*c_theta_p, _cos_z_theta*c_theta_p + _sin_z_theta*s_theta_p)
    _t25 = _t24/2.0
    inn00 = _halfcot__a1*_t22 + _t23*_t25
    inn10 = _halfcot__a1*_t23 - _t22*_t25
    inn20 = _t24
    S00 = pp00 + r_x*r_x
    S11 = pp11 + r_y*r_y
    S22 = pp22 + r_theta*r_theta
    rdet = 1.0/(S00*S11*S22 - S00*(pp12*pp12) - S11*(pp02*pp02) - S22*(pp01*pp01) + 2.0*pp01*pp02*pp12)
    Si00 = rdet*(S11*S22 - pp12*pp12)
    Si01 = rdet*(-(S22*pp01) + pp02*pp12)
    Si02 = rdet*(-(S11*pp02) + pp01*pp12)
    Si11 = rdet*(S00*S22 - pp02*pp02)
    Si12 = rdet*(-(S00*pp12) + pp01*pp02)
    Si22 = rdet*(S00*S11 - pp01*pp01)
    _t26 = Si01*pp01
    _t27 = Si02*pp02
    _t28 = Si12*pp12
    _t29 = 2.0*inn00
    k00 = Si00*pp00 + _t26 + _t27
    k01 = Si01*pp00 + Si11*pp01 + Si12*pp02
    k02 = Si02*pp00 + Si12*pp01 + Si22*pp02
    k10 = Si00*pp01 + Si01*pp11 + Si02*pp12
    k11 = Si11*pp11 + _t26 + _t28
    k12 = Si02*pp01 + Si12*pp11 + Si22*pp12
    k20 = Si00*pp02 + Si01*pp12 + Si02*pp22
    k21 = Si01*pp02 + Si11*pp12 + Si12*pp22
    k22 = Si22*pp22 + _t27 + _t28
    k30 = Si00*pp03 + Si01*pp13 + Si02*pp23
    k31 = Si01*pp03 + Si11*pp13 + Si12*pp23
    k32 = Si02*pp03 + Si12*pp13 + Si22*pp23
    k40 = Si00*pp04 + Si01*pp14 + Si02*pp24
    k41 = Si01*pp04 + Si11*pp14 + Si12*pp24
    k42 = Si02*pp04 + Si12*pp14 + Si22*pp24
    k50 = Si00*pp05 + Si01*pp15 + Si02*pp25
    k51 = Si01*pp05 + Si11*pp15 + Si12*pp25
    k52 = Si02*pp05 + Si12*pp15 + Si22*pp25
    nis = Si00*(inn00*inn00) + Si01*_t29*inn10 + Si02*_t29*inn20 + Si11*(inn10*inn10) + 2.0*Si12*inn10*inn20 + Si22*(inn20*inn20)
    nk0 = inn00*k00 + inn10*k01 + inn20*k02
    nk1 = inn00*k10 + inn10*k11 + inn20*k12
    nk2 = inn00*k20 + inn10*k21 + inn20*k22
    nk3 = inn00*k30 + inn10*k31 + inn20*k32
    nk4 = inn00*k40 + inn10*k41 + inn20*k42
    nk5 = inn00*k50 + inn10*k51 + inn20*k52
    alpha = gain_damping(nk2, nk5)
    nu0 = alpha*nk0
    nu1 = alpha*nk1
    nu2 = alpha*nk2
    nu3 = alpha*nk3
    nu4 = alpha*nk4
    nu5 = alpha*nk5
    _sin_nu2 = math.sin(nu2)
    _cos_nu2 = math.cos(nu2)
    _sinc_nu2, _cosc_nu2, _sinc2_nu2, _cosc2_nu2 = sinc_family(nu2, _sin_nu2, _cos_nu2)
    _sin_nu5 = math.sin(nu5)
    _cos_nu5 = math.cos(nu5)
    _sinc_nu5, _cosc_nu5, _sinc2_nu5, _cosc2_nu5 = sinc_family(nu5, _sin_nu5, _cos_nu5)
    _t30 = -(_cosc_nu2*nu1) + _sinc_nu2*nu0
    _t31 = _cosc_nu2*nu0 + _sinc_nu2*nu1
    _t32 = -(_cosc_nu5*nu4) + _sinc_nu5*nu3
    _t33 = _cosc_nu5*nu3 + _sinc_nu5*nu4
    _t34 = _cos_nu5*s_omega + _sin_nu5*c_omega
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
    mu00 = _t30*c_theta_p - _t31*s_theta_p + x_p
    mu01 = _t30*s_theta_p + _t31*c_theta_p + y_p
    mu02 = _cos_nu2*c_theta_p - _sin_nu2*s_theta_p
    mu03 = _cos_nu2*s_theta_p + _sin_nu2*c_theta_p
    mu04 = _t32*c_omega - _t33*s_omega + v_x
    mu05 = _t32*s_omega + _t33*c_omega + v_y
    mu06 = wrap_angle_sum(nu5 + omega, _t34)
    mu07 = _cos_nu5*c_omega - _sin_nu5*s_omega
    mu08 = _t34
    beta = alpha*(2.0 - alpha)
    kb00 = beta*k00
    kb01 = beta*k01
    kb02 = beta*k02
    kb10 = beta*k10
    kb11 = beta*k11
    kb12 = beta*k12
    kb20 = beta*k20
    kb21 = beta*k21
    kb22 = beta*k22
    kb30 = beta*k30
    kb31 = beta*k31
    kb32 = beta*k32
    kb40 = beta*k40
    kb41 = beta*k41
    kb42 = beta*k42
    kb50 = beta*k50
    kb51 = beta*k51
    kb52 = beta*k52
    pj00 = -(kb00*pp00) - kb01*pp01 - kb02*pp02 + pp00
    pj01 = -(kb00*pp01) - kb01*pp11 - kb02*pp12 + pp01
    pj02 = -(kb00*pp02) - kb01*pp12 - kb02*pp22 + pp02
    pj03 = -(kb00*pp03) - kb01*pp13 - kb02*pp23 + pp03
    pj04 = -(kb00*pp04) - kb01*pp14 - kb02*pp24 + pp04
    pj05 = -(kb00*pp05) - kb01*pp15 - kb02*pp25 + pp05
    pj11 = -(kb10*pp01) - kb11*pp11 - kb12*pp12 + pp11
    pj12 = -(kb10*pp02) - kb11*pp12 - kb12*pp22 + pp12
    pj13 = -(kb10*pp03) - kb11*pp13 - kb12*pp23 + pp13
    pj14 = -(kb10*pp04) - kb11*pp14 - kb12*pp24 + pp14
    pj15 = -(kb10*pp05) - kb11*pp15 - kb12*pp25 + pp15
    pj22 = -(kb20*pp02) - kb21*pp12 - kb22*pp22 + pp22
    pj23 = -(kb20*pp03) - kb21*pp13 - kb22*pp23 + pp23
    pj24 = -(kb20*pp04) - kb21*pp14 - kb22*pp24 + pp24
    pj25 = -(kb20*pp05) - kb21*pp15 - kb22*pp25 + pp25
    pj33 = -(kb30*pp03) - kb31*pp13 - kb32*pp23 + pp33
    pj34 = -(kb30*pp04) - kb31*pp14 - kb32*pp24 + pp34
    pj35 = -(kb30*pp05) - kb31*pp15 - kb32*pp25 + pp35
    pj44 = -(kb40*pp04) - kb41*pp14 - kb42*pp24 + pp44
    pj45 = -(kb40*pp05) - kb41*pp15 - kb42*pp25 + pp45
    pj55 = -(kb50*pp05) - kb51*pp15 - kb52*pp25 + pp55
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
    out_p0 = cp00*phi00 + cp01*phi01 + cp02*phi02
    out_p1 = cp00*phi10 + cp01*phi11 + cp02*phi12
    out_p2 = cp02
    out_p3 = cp03*phi33 + cp04*phi34 + cp05*phi35
    out_p4 = cp03*phi43 + cp04*phi44 + cp05*phi45
    out_p5 = cp05
    out_p6 = cp10*phi10 + cp11*phi11 + cp12*phi12
    out_p7 = cp12
    out_p8 = cp13*phi33 + cp14*phi34 + cp15*phi35
    out_p9 = cp13*phi43 + cp14*phi44 + cp15*phi45
    out_p10 = cp15
    out_p11 = pj22
    out_p12 = phi33*pj23 + phi34*pj24 + phi35*pj25
    out_p13 = phi43*pj23 + phi44*pj24 + phi45*pj25
    out_p14 = pj25
    out_p15 = cp33*phi33 + cp34*phi34 + cp35*phi35
    out_p16 = cp33*phi43 + cp34*phi44 + cp35*phi45
    out_p17 = cp35
    out_p18 = cp43*phi43 + cp44*phi44 + cp45*phi45
    out_p19 = cp45
    out_p20 = pj55
    out_s0 = mu00
    out_s1 = mu01
    out_s2 = mu02
    out_s3 = mu03
    out_s4 = mu04
    out_s5 = mu05
    out_s6 = mu06
    out_s7 = mu07
    out_s8 = mu08
    if not covariance_is_pd_fused(out_p0, out_p1, out_p2, out_p3, out_p4, out_p5, out_p6, out_p7, out_p8, out_p9, out_p10, out_p11, out_p12, out_p13, out_p14, out_p15, out_p16, out_p17, out_p18, out_p19, out_p20):
        out_p0 = pp00
        out_p1 = pp01
        out_p2 = pp02
        out_p3 = pp03
        out_p4 = pp04
        out_p5 = pp05
        out_p6 = pp11
        out_p7 = pp12
        out_p8 = pp13
        out_p9 = pp14
        out_p10 = pp15
        out_p11 = pp22
        out_p12 = pp23
        out_p13 = pp24
        out_p14 = pp25
        out_p15 = pp33
        out_p16 = pp34
        out_p17 = pp35
        out_p18 = pp44
        out_p19 = pp45
        out_p20 = pp55
        out_s0 = x_p
        out_s1 = y_p
        out_s2 = c_theta_p
        out_s3 = s_theta_p
        out_s4 = v_x
        out_s5 = v_y
        out_s6 = omega
        out_s7 = c_omega
        out_s8 = s_omega
        nis = -1.0
    p[0] = out_p0
    p[1] = out_p1
    p[2] = out_p2
    p[3] = out_p3
    p[4] = out_p4
    p[5] = out_p5
    p[6] = out_p6
    p[7] = out_p7
    p[8] = out_p8
    p[9] = out_p9
    p[10] = out_p10
    p[11] = out_p11
    p[12] = out_p12
    p[13] = out_p13
    p[14] = out_p14
    p[15] = out_p15
    p[16] = out_p16
    p[17] = out_p17
    p[18] = out_p18
    p[19] = out_p19
    p[20] = out_p20
    s[0] = out_s0
    s[1] = out_s1
    s[2] = out_s2
    s[3] = out_s3
    s[4] = out_s4
    s[5] = out_s5
    s[6] = out_s6
    s[7] = out_s7
    s[8] = out_s8
    return nis


@nb.njit(cache=True)
def step_pose(s, p, dt, sigma_x, sigma_y, sigma_omega, z_x, z_y, z_theta, r_x, r_y, r_theta):
    """One LG-EKF step with a pose measurement, in place; returns the NIS: ``step_try_pose``, and on the rare
    step whose cheap covariance fails the LDLᵀ test, ``update_pose`` (Joseph form) from the prediction
    (derive/codegen/fused.py)."""
    nis = step_try_pose(s, p, dt, sigma_x, sigma_y, sigma_omega, z_x, z_y, z_theta, r_x, r_y, r_theta)
    if nis < 0.0:
        nis = update_pose(s, p, z_x, z_y, z_theta, r_x, r_y, r_theta)
    return nis


@nb.njit(cache=True)
def measure_pose(s, m0, m1, m2):
    """Simulated pose measurement vector(h(X)·exp(m)) of the state s for a noise sample m.
    """
    x = s[0]
    y = s[1]
    c_theta = s[2]
    s_theta = s[3]
    out = np.zeros(3)
    _sin_m2 = math.sin(m2)
    _cos_m2 = math.cos(m2)
    _sinc_m2, _cosc_m2, _sinc2_m2, _cosc2_m2 = sinc_family(m2, _sin_m2, _cos_m2)
    _t0 = -(_cosc_m2*m1) + _sinc_m2*m0
    _t1 = _cosc_m2*m0 + _sinc_m2*m1
    out[0] = _t0*c_theta - _t1*s_theta + x
    out[1] = _t0*s_theta + _t1*c_theta + y
    out[2] = math.atan2(_cos_m2*s_theta + _sin_m2*c_theta, _cos_m2*c_theta - _sin_m2*s_theta)
    return out


@nb.njit(cache=True, nogil=True)  # nogil: the process-noise search (lgekf.apps.search) runs filters in threads
def run_one_pose(z, dts, x0, p0, q, r, out_x, out_p, out_nis):
    """Filter one trajectory with pose measurements: z (K, 3), dts (K,), x0 (6,), p0 (21,).

    A row of z containing NaN is a missed detection: the step predicts only (its NIS is NaN).
    """
    s = state_from_physical(x0)
    p = p0.copy()
    K = z.shape[0]
    keep_p = out_p.shape[0] == K
    for k in range(K):
        if np.isnan(z[k, 0]) or np.isnan(z[k, 1]) or np.isnan(z[k, 2]):
            predict(s, p, dts[k], q[0], q[1], q[2])
            out_nis[k] = np.nan
        else:
            nis = step_try_pose(s, p, dts[k], q[0], q[1], q[2], z[k, 0], z[k, 1], z[k, 2], r[0], r[1], r[2])
            if nis < 0.0:  # rare: the cheap covariance failed the LDLᵀ test; Joseph form from the prediction
                nis = update_pose(s, p, z[k, 0], z[k, 1], z[k, 2], r[0], r[1], r[2])
            out_nis[k] = nis
        physical_into(s, out_x[k])
        if keep_p:
            for i in range(21):
                out_p[k, i] = p[i]


@nb.njit(cache=True, nogil=True)
def run_segments_pose(z, t, first, lengths, x0, p0, q, r, out_x, out_p, out_nis):
    """``run_one_pose`` on segments of rows, one after the other (no Python per segment).

    Segment i is rows first[i] .. first[i] + lengths[i] - 1 (first[i] >= 1) of z (N, 3) and t (N,), filtered
    from x0[i] (6,), p0[i] (21,) at time t[first[i] - 1]; its outputs go to the same rows of out_x (N, 6),
    out_p (N, 21) and out_nis (N,). The numbers of ``run_one_pose`` called per segment with
    dts = t[a:b] - t[a - 1:b - 1].
    """
    longest = 0
    for i in range(first.shape[0]):
        longest = max(longest, lengths[i])
    dts = np.empty(longest)
    for i in range(first.shape[0]):
        a = first[i]
        b = a + lengths[i]
        for k in range(a, b):
            dts[k - a] = t[k] - t[k - 1]
        run_one_pose(z[a:b], dts[:b - a], x0[i], p0[i], q, r, out_x[a:b], out_p[a:b], out_nis[a:b])


@nb.njit(cache=True, nogil=True)
def run_one_from_pose(z, dts, s0, p0, q, r, out_x, out_p, out_nis):
    """``run_one_pose`` from the internal state s0 (9,) (the layout of ``state_from_physical``) and p0 (21,),
    which on return hold the posterior of the last row: a later call from them continues exactly (the numbers
    of one call over both rows). ``lgekf track`` filters a long object in windows of rows with it.
    """
    s = s0.copy()
    p = p0.copy()
    K = z.shape[0]
    keep_p = out_p.shape[0] == K
    for k in range(K):
        if np.isnan(z[k, 0]) or np.isnan(z[k, 1]) or np.isnan(z[k, 2]):
            predict(s, p, dts[k], q[0], q[1], q[2])
            out_nis[k] = np.nan
        else:
            nis = step_try_pose(s, p, dts[k], q[0], q[1], q[2], z[k, 0], z[k, 1], z[k, 2], r[0], r[1], r[2])
            if nis < 0.0:  # rare: the cheap covariance failed the LDLᵀ test; Joseph form from the prediction
                nis = update_pose(s, p, z[k, 0], z[k, 1], z[k, 2], r[0], r[1], r[2])
            out_nis[k] = nis
        physical_into(s, out_x[k])
        if keep_p:
            for i in range(21):
                out_p[k, i] = p[i]
    s0[:] = s
    p0[:] = p


@nb.njit(cache=True, nogil=True)
def run_segments_from_pose(z, t, first, lengths, s0, p0, q, r, out_x, out_p, out_nis):
    """``run_segments_pose`` from internal states s0 (S, 9) and p0 (S, 21) (``run_one_from_pose``): on
    return s0[i], p0[i] hold the posterior of segment i's last row (unchanged for an empty segment).
    """
    longest = 0
    for i in range(first.shape[0]):
        longest = max(longest, lengths[i])
    dts = np.empty(longest)
    for i in range(first.shape[0]):
        a = first[i]
        b = a + lengths[i]
        for k in range(a, b):
            dts[k - a] = t[k] - t[k - 1]
        run_one_from_pose(z[a:b], dts[:b - a], s0[i], p0[i], q, r, out_x[a:b], out_p[a:b], out_nis[a:b])


@nb.njit(cache=True, parallel=True)
def run_batch_pose(z, dts, x0, p0, q, r, out_x, out_p, out_nis):
    """Filter B trajectories in parallel (numba prange), predict then update at every step.

    z (B, K, 3) pose measurements (a NaN row = missed detection); dts (B, K) step lengths; x0 (B, 6)
    physical initial states; p0 (B, 21) packed initial covariances; q (3,) process-noise stds;
    r (3,) measurement-noise stds. Writes the posterior physical states into out_x (B, K, 6), the
    packed covariances into out_p (B, K, 21) when out_p.shape[1] == K (pass (B, 0, 21) to skip),
    and the NIS into out_nis (B, K).
    """
    for b in nb.prange(z.shape[0]):
        run_one_pose(z[b], dts[b], x0[b], p0[b], q, r, out_x[b], out_p[b], out_nis[b])


@nb.njit(cache=True)
def measure_batch_pose(X, noise, out):
    """Simulated pose measurements z = vector(h(X)·exp(m)) of every physical state X (N, 6),
    noise samples m (N, 3) (already scaled), into out (N, 3)."""
    for i in range(X.shape[0]):
        s = state_from_physical(X[i])
        z = measure_pose(s, noise[i, 0], noise[i, 1], noise[i, 2])
        for j in range(3):
            out[i, j] = z[j]


@nb.njit(cache=True)
def innovation_into_pose(s, z_x, z_y, z_theta, out):
    """The pose innovation e = [log_G'(h(μ)⁻¹ Z)]^∨ (eq:K) of the state s for the measured z, written into out (3,).
    """
    x = s[0]
    y = s[1]
    c_theta = s[2]
    s_theta = s[3]
    _sin_z_theta = math.sin(z_theta)
    _cos_z_theta = math.cos(z_theta)
    _a0 = math.atan2(c_theta*math.sin(z_theta) - s_theta*math.cos(z_theta), c_theta*math.cos(z_theta) + s_theta*math.sin(z_theta))
    _sin__a0 = math.sin(_a0)
    _cos__a0 = math.cos(_a0)
    _halfcot__a0 = halfcot(_a0, _sin__a0, _cos__a0)
    _t0 = -(c_theta*x) + c_theta*z_x - s_theta*y + s_theta*z_y
    _t1 = -(c_theta*y) + c_theta*z_y + s_theta*x - s_theta*z_x
    _t2 = math.atan2(-(_cos_z_theta*s_theta) + _sin_z_theta*c_theta, _cos_z_theta*c_theta + _sin_z_theta*s_theta)
    _t3 = _t2/2.0
    out[0] = _halfcot__a0*_t0 + _t1*_t3
    out[1] = _halfcot__a0*_t1 - _t0*_t3
    out[2] = _t2


@nb.njit(cache=True)
def innovation_bank_pose(s, live, z, out):
    """Innovation [log_G'(h(μ_i)⁻¹ Z_j)]^∨ of every live track i (rows of s, live[i] true) and every
    pose detection j (rows of z, (M, 3)) into out (N, M, 3); rows of dead tracks are not written."""
    for i in range(s.shape[0]):
        if live[i]:
            si = s[i]
            for j in range(z.shape[0]):
                innovation_into_pose(si, z[j, 0], z[j, 1], z[j, 2], out[i, j])


@nb.njit(cache=True)
def calH_bank_pose(s, live, out):
    """ℋ (eq:calH) of every live track for pose measurements into out (N, 3, 6)."""
    for i in range(s.shape[0]):
        if live[i]:
            h = calH_pose(s[i])
            for a in range(3):
                for b in range(6):
                    out[i, a, b] = h[a, b]


@nb.njit(cache=True, nogil=True)
def run_segments_noise_from_pose(z, t, first, lengths, s0, p0, q, r, out_x, out_p, out_nis):
    """``run_segments_from_pose`` with noise stds of each segment's own: q (S, 3), r (S, 3) (the divergence
    recovery's reruns, each object's noise inflated by its own factor). On return s0[i], p0[i] hold the posterior
    of segment i's last row, from which a later call continues exactly. The numbers of ``run_one_from_pose``
    called per segment i with q[i], r[i]."""
    longest = 0
    for i in range(first.shape[0]):
        longest = max(longest, lengths[i])
    dts = np.empty(longest)
    for i in range(first.shape[0]):
        a = first[i]
        b = a + lengths[i]
        for k in range(a, b):
            dts[k - a] = t[k] - t[k - 1]
        run_one_from_pose(z[a:b], dts[:b - a], s0[i], p0[i], q[i], r[i], out_x[a:b], out_p[a:b], out_nis[a:b])


@nb.njit(cache=True, nogil=True, error_model="numpy")
def rerun_pose(zm, t, a, b, s1, p1, q, r, scale, q1, r1, x, p, nis):
    """Filter rows a .. b - 1 from the internal state s1 (1, ni) and packed covariance p1 (1, n(n+1)/2) of row a - 1, every
    noise std times ``scale`` (q1, r1 (1, nq), (1, nr) scratch), into x, p, nis; s1, p1 are left at row b - 1."""
    for j in range(q.shape[0]):
        q1[0, j] = q[j] * scale
    for j in range(r.shape[0]):
        r1[0, j] = r[j] * scale
    run_segments_noise_from_pose(zm, t, np.full(1, a, np.int64), np.full(1, b - a, np.int64), s1, p1, q1, r1, x, p, nis)


@nb.njit(cache=True, nogil=True, error_model="numpy")
def recover_pose(
        x, p, nis, flag, seg_obj, seg_first, seg_end, run_first, run_s, run_p, run_scale0, limits, m, window, short, clip, thr,
        thr_short, n_sigma, max_reinit, repeat, max_inflation, rerun_rows, count, scale, last, zm, t, q, r, t_all, z_all,
        heading_all, offset, obj_first, meas_std, omega_std, heading_std, heading_cap, sideslip, baseline, angles, carry_s,
        carry_p, carry_scale, carry_reached):
    """The divergence monitor and recovery of ``lgekf.apps.divergence.recover``, segment after segment, compiled.

    Segment i is rows seg_first[i] .. seg_end[i] - 1 of object seg_obj[i]. Where run_first[i] >= 0 its rows run_first[i]
    .. seg_end[i] - 1 are filtered first, from the internal state run_s[i] and covariance run_p[i] of the row before, the
    noise stds times run_scale0[i] (the first pass of ``lgekf.apps.track.track_monitored``: one library with the
    filter's step per model instead of two); else they are in x, p, nis already. Each
    round scans rows for the first alarm (``first_alarm``); at an alarm the row is re-initialised (``reinit_into``, the
    measurements of global row + ``offset`` of t_all, z_all, heading_all; obj_first (B,) global) and the filter is
    run again over a window of ``rerun_rows`` rows that doubles until the next alarm or the segment's end, each window
    going on from the previous one's last state and scanned from max(window, short) rows before it. count, scale,
    last (B,): the objects' memory, updated in place; flag (N,) int8 set on the alarms' rows. carry_s, carry_p,
    carry_scale, carry_reached (B,): the filter's state, covariance and noise inflation after the segment's last row
    where a re-initialisation or a rerun reached it (carry_reached True). Returns the alarms (A, 8): obj, row, kind,
    value, limit, updates, reinitialised (1.0 / 0.0), scale, object after object, each object's in order."""
    N = x.shape[0]
    n = x.shape[1]
    over = np.zeros(N, np.bool_)
    absurd = np.zeros(N, np.bool_)
    bad = np.zeros(N, np.bool_)
    sp = np.empty(N)
    rows = np.empty(N, np.int64)
    xh = np.empty((1, n))
    grad = np.empty(n)
    reach = max(window, short)
    found = np.empty((16, 8))  # the alarms: obj, row, kind, value, limit, updates, reinitialised, scale (rows grow)
    na = 0
    s1 = np.empty((1, carry_s.shape[1]))
    p1 = np.empty((1, p.shape[1]))
    q1 = np.empty((1, q.shape[0]))
    r1 = np.empty((1, r.shape[0]))
    x0 = np.empty((1, n))
    p0 = np.empty(p.shape[1])
    nc = z_all.shape[1] * (z_all.shape[1] + 1)  # the space's common coordinates: 2d + d(d - 1) (6 in the plane, 12 in 3-D)
    c1 = np.empty((1, nc))
    var1 = np.empty(nc)
    cj1 = np.empty((1, nc))
    J1 = np.empty((1, n, nc))
    P1 = np.empty((n, n))
    for si in range(seg_obj.shape[0]):
        o = seg_obj[si]
        first = seg_first[si]
        end = seg_end[si]
        scan_from = first
        scan_end = end
        run_scale = scale[o]  # the noise inflation of the run being scanned
        reached = False  # a run or a re-initialisation reached the segment's last row
        if run_first[si] >= 0:  # the first pass
            copy_row(run_s, si, s1, 0)
            copy_row(run_p, si, p1, 0)
            run_scale = run_scale0[si]
            rerun_pose(zm, t, run_first[si], end, s1, p1, q, r, run_scale, q1, r1, x, p, nis)
            reached = True
        while True:
            g, kind, val, start, lim = first_alarm(x, p, nis, scan_from, scan_end, limits[o], window, short, clip, thr, thr_short,
                                                   n_sigma, over, absurd, bad, sp, rows, xh, grad)
            if g < 0:
                if scan_end >= end:
                    break
                # no alarm in this window: the next, twice as wide, goes on from where the run stopped
                new_end = min(end, first + 2 * (scan_end - first))
                rerun_pose(zm, t, scan_end, new_end, s1, p1, q, r, run_scale, q1, r1, x, p, nis)
                scan_from = max(first, scan_end - reach)
                scan_end = new_end
                reached = scan_end == end
                continue
            count[o] += 1
            if kind == 1 and g - last[o] <= repeat * window:  # soon after the last re-initialisation: the noise is too small
                scale[o] *= minimum(math.sqrt(maximum(val / m, 1.0)), max_inflation)
            ok = count[o] <= max_reinit
            if na == found.shape[0]:
                more = np.empty((2 * na, 8))
                for i in range(na):
                    for j in range(8):
                        more[i, j] = found[i, j]
                found = more
            found[na, 0] = o
            found[na, 1] = g
            found[na, 2] = kind
            found[na, 3] = val
            found[na, 4] = lim
            found[na, 5] = g - start + 1 if kind == 1 else 0
            found[na, 6] = 1.0 if ok else 0.0
            found[na, 7] = scale[o]
            na += 1
            # the NIS of an update tests the estimate before it: flag from the row before the alarm's first update (not
            # before the segment's first row) through the alarm row
            for k in range(max(max(start, first) - 1, 0), g + 1):
                flag[k] = 1
            if not ok:  # max_reinit used up: no more monitoring; the run goes on to the segment's end
                if scan_end < end:
                    rerun_pose(zm, t, scan_end, end, s1, p1, q, r, run_scale, q1, r1, x, p, nis)
                    reached = True
                break
            last[o] = g
            reinit_into(t_all, z_all, heading_all, g + offset, obj_first[o], scale[o], meas_std, omega_std, heading_std, heading_cap,
                        sideslip, baseline, angles, c1, var1, cj1, J1, P1, x0, p0)
            copy_row(x0, 0, x, g)
            for j in range(p0.shape[0]):
                p[g, j] = p0[j]
            nis[g] = np.nan
            states_from_physical(x0, s1)
            for j in range(p0.shape[0]):
                p1[0, j] = p0[j]
            run_scale = scale[o]
            if g + 1 >= end:  # the re-initialised row is the segment's last
                reached = True
                break
            first = g + 1
            scan_from = first
            scan_end = min(end, first + rerun_rows)
            rerun_pose(zm, t, first, scan_end, s1, p1, q, r, run_scale, q1, r1, x, p, nis)
            reached = scan_end == end
        if reached:
            copy_row(s1, 0, carry_s, o)
            copy_row(p1, 0, carry_p, o)
            carry_scale[o] = run_scale
            carry_reached[o] = True
    return found[:na]


@nb.njit(inline="always", fastmath={"contract"}, error_model="numpy")
def lane_pose(W, j, sigma_x, sigma_y, sigma_omega, r_x, r_y, r_theta):
    """step_pose on lane j of the work array W (rows: derive/codegen/soa.py Layout), without branches (SIMD).
    """
    x = W[0 + j]
    y = W[64 + j]
    c_theta = W[128 + j]
    s_theta = W[192 + j]
    v_x = W[256 + j]
    v_y = W[320 + j]
    omega = W[384 + j]
    c_omega = W[448 + j]
    s_omega = W[512 + j]
    p00 = W[576 + j]
    p01 = W[640 + j]
    p02 = W[704 + j]
    p03 = W[768 + j]
    p04 = W[832 + j]
    p05 = W[896 + j]
    p11 = W[960 + j]
    p12 = W[1024 + j]
    p13 = W[1088 + j]
    p14 = W[1152 + j]
    p15 = W[1216 + j]
    p22 = W[1280 + j]
    p23 = W[1344 + j]
    p24 = W[1408 + j]
    p25 = W[1472 + j]
    p33 = W[1536 + j]
    p34 = W[1600 + j]
    p35 = W[1664 + j]
    p44 = W[1728 + j]
    p45 = W[1792 + j]
    p55 = W[1856 + j]
    dt = W[3840 + j]
    z_x = W[4032 + j]
    z_y = W[4096 + j]
    z_theta = W[4160 + j]
    _t0 = c_omega*dt
    _t1 = dt*s_omega
    cc03 = _t0
    cc04 = -_t1
    cc13 = _t1
    cc14 = _t0
    _a0 = dt*omega
    _sin__a0 = sin_v(_a0)
    _cos__a0 = cos_v(_a0)
    _sinc__a0, _cosc__a0, _sinc2__a0, _cosc2__a0 = sinc_family(_a0, _sin__a0, _cos__a0)
    _t2 = dt*v_x
    _t3 = _cosc__a0*_t2
    _t4 = dt*v_y
    _t5 = _sinc__a0*_t4
    _t6 = -(_cosc2__a0*_t4) + _sinc2__a0*dt*v_x
    _t7 = _cosc__a0*_t4
    _t8 = _cosc2__a0*_t2 + _sinc2__a0*_t4
    _t9 = (dt*dt)/2.0
    _t10 = _sinc__a0*_t9
    _t11 = _cosc__a0*_t9
    _t12 = _sinc__a0*dt*v_x - _t7
    _t13 = _t3 + _t5
    f00 = _cos__a0
    f01 = _sin__a0
    f02 = _t3 - _t5
    f03 = _cosc__a0*cc13 + _sinc__a0*cc03
    f04 = _cosc__a0*cc14 + _sinc__a0*cc04
    f05 = _t6*dt
    f10 = -_sin__a0
    f11 = _cos__a0
    f12 = _sinc__a0*_t2 + _t7
    f13 = -(_cosc__a0*cc03) + _sinc__a0*cc13
    f14 = -(_cosc__a0*cc04) + _sinc__a0*cc14
    f15 = _t8*dt
    g00 = _t10
    g01 = _t11
    g02 = _t6*_t9
    g10 = -_t11
    g11 = _t10
    g12 = _t8*_t9
    g22 = _t9
    e00 = _t12*c_theta - _t13*s_theta + x
    e01 = _t12*s_theta + _t13*c_theta + y
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
    _t14 = sigma_x*sigma_x
    _t15 = sigma_y*sigma_y
    _t16 = sigma_omega*sigma_omega
    _t17 = _t14*g00
    _t18 = _t15*g01
    _t19 = _t16*g02
    _t20 = _t16*g12
    _t21 = dt*dt
    pp00 = _t14*(g00*g00) + _t15*(g01*g01) + _t16*(g02*g02) + f00*m00 + f01*m01 + f02*m02 + f03*m03 + f04*m04 + f05*m05
    pp01 = _t17*g10 + _t18*g11 + _t19*g12 + f10*m00 + f11*m01 + f12*m02 + f13*m03 + f14*m04 + f15*m05
    pp02 = _t19*g22 + dt*m05 + m02
    pp03 = _t17*dt + m03
    pp04 = _t18*dt + m04
    pp05 = _t19*dt + m05
    pp11 = _t14*(g10*g10) + _t15*(g11*g11) + _t16*(g12*g12) + f10*m10 + f11*m11 + f12*m12 + f13*m13 + f14*m14 + f15*m15
    pp12 = _t20*g22 + dt*m15 + m12
    pp13 = _t14*dt*g10 + m13
    pp14 = _t15*dt*g11 + m14
    pp15 = _t20*dt + m15
    pp22 = _t16*(g22*g22) + dt*m25 + m22
    pp23 = m23
    pp24 = m24
    pp25 = _t16*dt*g22 + m25
    pp33 = _t14*_t21 + p33
    pp34 = p34
    pp35 = p35
    pp44 = _t15*_t21 + p44
    pp45 = p45
    pp55 = _t16*_t21 + p55
    x_p = e00
    y_p = e01
    c_theta_p = e02
    s_theta_p = e03
    if pp22 > math.pi * math.pi:
        _cap = math.pi / math.sqrt(pp22)
        pp02 = pp02 * _cap
        pp12 = pp12 * _cap
        pp23 = pp23 * _cap
        pp24 = pp24 * _cap
        pp25 = pp25 * _cap
        pp22 = math.pi * math.pi
    if pp55 > math.pi * math.pi:
        _cap = math.pi / math.sqrt(pp55)
        pp05 = pp05 * _cap
        pp15 = pp15 * _cap
        pp25 = pp25 * _cap
        pp35 = pp35 * _cap
        pp45 = pp45 * _cap
        pp55 = math.pi * math.pi
    _sin_z_theta = sin_v(z_theta)
    _cos_z_theta = cos_v(z_theta)
    _a1 = atan2_v(c_theta_p*sin_v(z_theta) - s_theta_p*cos_v(z_theta), c_theta_p*cos_v(z_theta) + s_theta_p*sin_v(z_theta))
    _sin__a1 = sin_v(_a1)
    _cos__a1 = cos_v(_a1)
    _halfcot__a1 = halfcot_v(_a1, _sin__a1, _cos__a1)
    _t22 = -(c_theta_p*x_p) + c_theta_p*z_x - s_theta_p*y_p + s_theta_p*z_y
    _t23 = -(c_theta_p*y_p) + c_theta_p*z_y + s_theta_p*x_p - s_theta_p*z_x
    _t24 = atan2_v(-(_cos_z_theta*s_theta_p) + _sin_z_theta*c_theta_p, _cos_z_theta*c_theta_p + _sin_z_theta*s_theta_p)
    _t25 = _t24/2.0
    inn00 = _halfcot__a1*_t22 + _t23*_t25
    inn10 = _halfcot__a1*_t23 - _t22*_t25
    inn20 = _t24
    S00 = pp00 + r_x*r_x
    S11 = pp11 + r_y*r_y
    S22 = pp22 + r_theta*r_theta
    rdet = 1.0/(S00*S11*S22 - S00*(pp12*pp12) - S11*(pp02*pp02) - S22*(pp01*pp01) + 2.0*pp01*pp02*pp12)
    Si00 = rdet*(S11*S22 - pp12*pp12)
    Si01 = rdet*(-(S22*pp01) + pp02*pp12)
    Si02 = rdet*(-(S11*pp02) + pp01*pp12)
    Si11 = rdet*(S00*S22 - pp02*pp02)
    Si12 = rdet*(-(S00*pp12) + pp01*pp02)
    Si22 = rdet*(S00*S11 - pp01*pp01)
    _t26 = Si01*pp01
    _t27 = Si02*pp02
    _t28 = Si12*pp12
    _t29 = 2.0*inn00
    k00 = Si00*pp00 + _t26 + _t27
    k01 = Si01*pp00 + Si11*pp01 + Si12*pp02
    k02 = Si02*pp00 + Si12*pp01 + Si22*pp02
    k10 = Si00*pp01 + Si01*pp11 + Si02*pp12
    k11 = Si11*pp11 + _t26 + _t28
    k12 = Si02*pp01 + Si12*pp11 + Si22*pp12
    k20 = Si00*pp02 + Si01*pp12 + Si02*pp22
    k21 = Si01*pp02 + Si11*pp12 + Si12*pp22
    k22 = Si22*pp22 + _t27 + _t28
    k30 = Si00*pp03 + Si01*pp13 + Si02*pp23
    k31 = Si01*pp03 + Si11*pp13 + Si12*pp23
    k32 = Si02*pp03 + Si12*pp13 + Si22*pp23
    k40 = Si00*pp04 + Si01*pp14 + Si02*pp24
    k41 = Si01*pp04 + Si11*pp14 + Si12*pp24
    k42 = Si02*pp04 + Si12*pp14 + Si22*pp24
    k50 = Si00*pp05 + Si01*pp15 + Si02*pp25
    k51 = Si01*pp05 + Si11*pp15 + Si12*pp25
    k52 = Si02*pp05 + Si12*pp15 + Si22*pp25
    nis = Si00*(inn00*inn00) + Si01*_t29*inn10 + Si02*_t29*inn20 + Si11*(inn10*inn10) + 2.0*Si12*inn10*inn20 + Si22*(inn20*inn20)
    nk0 = inn00*k00 + inn10*k01 + inn20*k02
    nk1 = inn00*k10 + inn10*k11 + inn20*k12
    nk2 = inn00*k20 + inn10*k21 + inn20*k22
    nk3 = inn00*k30 + inn10*k31 + inn20*k32
    nk4 = inn00*k40 + inn10*k41 + inn20*k42
    nk5 = inn00*k50 + inn10*k51 + inn20*k52
    alpha = gain_damping_v(nk2, nk5)
    nu0 = alpha*nk0
    nu1 = alpha*nk1
    nu2 = alpha*nk2
    nu3 = alpha*nk3
    nu4 = alpha*nk4
    nu5 = alpha*nk5
    _sin_nu2 = sin_v(nu2)
    _cos_nu2 = cos_v(nu2)
    _sinc_nu2, _cosc_nu2, _sinc2_nu2, _cosc2_nu2 = sinc_family(nu2, _sin_nu2, _cos_nu2)
    _sin_nu5 = sin_v(nu5)
    _cos_nu5 = cos_v(nu5)
    _sinc_nu5, _cosc_nu5, _sinc2_nu5, _cosc2_nu5 = sinc_family(nu5, _sin_nu5, _cos_nu5)
    _t30 = -(_cosc_nu2*nu1) + _sinc_nu2*nu0
    _t31 = _cosc_nu2*nu0 + _sinc_nu2*nu1
    _t32 = -(_cosc_nu5*nu4) + _sinc_nu5*nu3
    _t33 = _cosc_nu5*nu3 + _sinc_nu5*nu4
    _t34 = _cos_nu5*s_omega + _sin_nu5*c_omega
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
    mu00 = _t30*c_theta_p - _t31*s_theta_p + x_p
    mu01 = _t30*s_theta_p + _t31*c_theta_p + y_p
    mu02 = _cos_nu2*c_theta_p - _sin_nu2*s_theta_p
    mu03 = _cos_nu2*s_theta_p + _sin_nu2*c_theta_p
    mu04 = _t32*c_omega - _t33*s_omega + v_x
    mu05 = _t32*s_omega + _t33*c_omega + v_y
    mu06 = wrap_sum_v(nu5 + omega, _t34)
    mu07 = _cos_nu5*c_omega - _sin_nu5*s_omega
    mu08 = _t34
    beta = alpha*(2.0 - alpha)
    kb00 = beta*k00
    kb01 = beta*k01
    kb02 = beta*k02
    kb10 = beta*k10
    kb11 = beta*k11
    kb12 = beta*k12
    kb20 = beta*k20
    kb21 = beta*k21
    kb22 = beta*k22
    kb30 = beta*k30
    kb31 = beta*k31
    kb32 = beta*k32
    kb40 = beta*k40
    kb41 = beta*k41
    kb42 = beta*k42
    kb50 = beta*k50
    kb51 = beta*k51
    kb52 = beta*k52
    pj00 = -(kb00*pp00) - kb01*pp01 - kb02*pp02 + pp00
    pj01 = -(kb00*pp01) - kb01*pp11 - kb02*pp12 + pp01
    pj02 = -(kb00*pp02) - kb01*pp12 - kb02*pp22 + pp02
    pj03 = -(kb00*pp03) - kb01*pp13 - kb02*pp23 + pp03
    pj04 = -(kb00*pp04) - kb01*pp14 - kb02*pp24 + pp04
    pj05 = -(kb00*pp05) - kb01*pp15 - kb02*pp25 + pp05
    pj11 = -(kb10*pp01) - kb11*pp11 - kb12*pp12 + pp11
    pj12 = -(kb10*pp02) - kb11*pp12 - kb12*pp22 + pp12
    pj13 = -(kb10*pp03) - kb11*pp13 - kb12*pp23 + pp13
    pj14 = -(kb10*pp04) - kb11*pp14 - kb12*pp24 + pp14
    pj15 = -(kb10*pp05) - kb11*pp15 - kb12*pp25 + pp15
    pj22 = -(kb20*pp02) - kb21*pp12 - kb22*pp22 + pp22
    pj23 = -(kb20*pp03) - kb21*pp13 - kb22*pp23 + pp23
    pj24 = -(kb20*pp04) - kb21*pp14 - kb22*pp24 + pp24
    pj25 = -(kb20*pp05) - kb21*pp15 - kb22*pp25 + pp25
    pj33 = -(kb30*pp03) - kb31*pp13 - kb32*pp23 + pp33
    pj34 = -(kb30*pp04) - kb31*pp14 - kb32*pp24 + pp34
    pj35 = -(kb30*pp05) - kb31*pp15 - kb32*pp25 + pp35
    pj44 = -(kb40*pp04) - kb41*pp14 - kb42*pp24 + pp44
    pj45 = -(kb40*pp05) - kb41*pp15 - kb42*pp25 + pp45
    pj55 = -(kb50*pp05) - kb51*pp15 - kb52*pp25 + pp55
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
    W[2496 + j] = cp00*phi00 + cp01*phi01 + cp02*phi02
    W[2560 + j] = cp00*phi10 + cp01*phi11 + cp02*phi12
    W[2624 + j] = cp02
    W[2688 + j] = cp03*phi33 + cp04*phi34 + cp05*phi35
    W[2752 + j] = cp03*phi43 + cp04*phi44 + cp05*phi45
    W[2816 + j] = cp05
    W[2880 + j] = cp10*phi10 + cp11*phi11 + cp12*phi12
    W[2944 + j] = cp12
    W[3008 + j] = cp13*phi33 + cp14*phi34 + cp15*phi35
    W[3072 + j] = cp13*phi43 + cp14*phi44 + cp15*phi45
    W[3136 + j] = cp15
    W[3200 + j] = pj22
    W[3264 + j] = phi33*pj23 + phi34*pj24 + phi35*pj25
    W[3328 + j] = phi43*pj23 + phi44*pj24 + phi45*pj25
    W[3392 + j] = pj25
    W[3456 + j] = cp33*phi33 + cp34*phi34 + cp35*phi35
    W[3520 + j] = cp33*phi43 + cp34*phi44 + cp35*phi45
    W[3584 + j] = cp35
    W[3648 + j] = cp43*phi43 + cp44*phi44 + cp45*phi45
    W[3712 + j] = cp45
    W[3776 + j] = pj55
    W[1920 + j] = mu00
    W[1984 + j] = mu01
    W[2048 + j] = mu02
    W[2112 + j] = mu03
    W[2176 + j] = mu04
    W[2240 + j] = mu05
    W[2304 + j] = mu06
    W[2368 + j] = mu07
    W[2432 + j] = mu08
    return nis


@nb.njit(cache=True, parallel=True, fastmath=FASTMATH, error_model="numpy")
def run_batch_soa_pose(z, dts, x0, p0, q, r, out_x, out_p, out_nis):
    """run_batch_pose with trajectories in the SIMD lanes (derive/codegen/soa.py): same arguments and results.

    Blocks of 64 trajectories (prange over blocks); in a block every per-trajectory quantity is a row of one
    work array (rows × 64) and lane_pose runs vectorised over the lanes; a lane failing the LDLᵀ test or with
    a NaN row (NaN NIS) is redone by the scalar predict / update_pose.
    """
    B = z.shape[0]
    K = z.shape[1]
    keep_p = out_p.shape[1] == K
    nblk = (B + 64 - 1) // 64
    for blk in nb.prange(nblk):
        lo = blk * 64
        L = min(64, B - lo)
        W = np.zeros(66 * 64)
        s = np.empty(9)
        p = np.empty(21)
        for j in range(L):
            s0 = state_from_physical(x0[lo + j])
            for i in range(9):
                W[(0 + i) * 64 + j] = s0[i]
            for i in range(21):
                W[(9 + i) * 64 + j] = p0[lo + j, i]
        for k in range(K):
            for j in range(L):
                W[60 * 64 + j] = dts[lo + j, k]
                W[63 * 64 + j] = z[lo + j, k, 0]
                W[64 * 64 + j] = z[lo + j, k, 1]
                W[65 * 64 + j] = z[lo + j, k, 2]
            for j in range(L):
                W[61 * 64 + j] = lane_pose(W, j, q[0], q[1], q[2], r[0], r[1], r[2])
                good = covariance_is_pd_lane(W, j) & (W[61 * 64 + j] == W[61 * 64 + j])
                W[62 * 64 + j] = 1.0 if good else 0.0
            for j in range(L):
                if W[62 * 64 + j] == 0.0:
                    b = lo + j
                    for i in range(9):
                        s[i] = W[(0 + i) * 64 + j]
                    for i in range(21):
                        p[i] = W[(9 + i) * 64 + j]
                    predict(s, p, dts[b, k], q[0], q[1], q[2])
                    if np.isnan(z[b, k, 0]) or np.isnan(z[b, k, 1]) or np.isnan(z[b, k, 2]):
                        W[61 * 64 + j] = np.nan
                    else:
                        W[61 * 64 + j] = update_pose(s, p, z[b, k, 0], z[b, k, 1], z[b, k, 2], r[0], r[1], r[2])
                    for i in range(9):
                        W[(30 + i) * 64 + j] = s[i]
                    for i in range(21):
                        W[(39 + i) * 64 + j] = p[i]
            for j in range(L):
                out_nis[lo + j, k] = W[61 * 64 + j]
                physical_lane(W, j, out_x, lo + j, k)
            if keep_p:
                for j in range(L):
                    for i in range(21):
                        out_p[lo + j, k, i] = W[(39 + i) * 64 + j]
            for i in range(9 + 21):
                for j in range(L):
                    W[(0 + i) * 64 + j] = W[(30 + i) * 64 + j]


@nb.njit(cache=True)
def calH_position(s):
    """ℋ = ∂[log_G'(h(μ)^-1 h(μ exp ε))]^∨/∂ε at ε = 0 (eq:calH, eq:calH_model) for position measurements.
    """
    c_theta = s[2]
    s_theta = s[3]
    out = np.zeros((2, 6))
    out[0, 0] = c_theta
    out[0, 1] = -s_theta
    out[1, 0] = s_theta
    out[1, 1] = c_theta
    return out


@nb.njit(cache=True, fastmath=FASTMATH)
def update_position(s, p, z_x, z_y, r):
    """Fused update with a position measurement (2-D position z = (x, y) with isotropic noise std r (the paper's measurement)), in place.
    z = (z_x, z_y), noise stds (r); Z = h(μ)·exp(m), m ~ N(0, R) in the tangent of G'.
    K = P ℋ^T (ℋ P ℋ^T + R)^-1, ν = K [log_G'(h(μ)^-1 Z)]^∨ (eq:K), μ ← μ exp(ν) (eq:up_mu),
    P ← Φ(ν) [(I - Kℋ) P (I - Kℋ)^T + K R K^T] Φ(ν)^T: eq:up_P in Joseph form. Returns the NIS e^T S^-1 e.
    Safeguard: if a rotation angle of ν exceeds π the gain is damped, K → αK, α = π/|angle|
    (derive.lie.special.gain_damping; α = 1 in every regular step).
    If rounding leaves P not positive definite (condition numbers ≳ 1e15) a rounding-level jitter restores it (repair_pd).
    legend: cc = 𝒞 (eq:C), f = F = Ad(exp(−Ω)) + Φ(Ω)𝒞 (eq:pred_cov), g = Φ(Ω)G, hh = ℋ (eq:calH), hp = ℋP, inn = [log_G'(h(μ)⁻¹Z)]^∨, S = ℋPℋᵀ + R, Si = S⁻¹, k = K (eq:K), nk = Kν, alpha = gain damping, nu = ν, phi = Φ(ν) (eq:up_P), a = I − αKℋ, b = aP, beta = α(2 − α), kb = βK, pj = Joseph-form P (= P − βKℋP), cp = Φ(ν)·pj, mu/e = new mean
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
    hh01 = -s_theta
    _t0 = c_theta*p01
    hp00 = c_theta*p00 + hh01*p01
    hp01 = _t0 + hh01*p11
    hp02 = c_theta*p02 + hh01*p12
    hp03 = c_theta*p03 + hh01*p13
    hp04 = c_theta*p04 + hh01*p14
    hp05 = c_theta*p05 + hh01*p15
    hp10 = _t0 + p00*s_theta
    hp11 = c_theta*p11 + p01*s_theta
    hp12 = c_theta*p12 + p02*s_theta
    hp13 = c_theta*p13 + p03*s_theta
    hp14 = c_theta*p14 + p04*s_theta
    hp15 = c_theta*p15 + p05*s_theta
    inn00 = -x + z_x
    inn10 = -y + z_y
    _t1 = r*r
    S00 = _t1 + c_theta*hp00 + hh01*hp01
    S01 = c_theta*hp01 + hp00*s_theta
    S11 = _t1 + c_theta*hp11 + hp10*s_theta
    rdet = 1.0/(S00*S11 - S01*S01)
    Si00 = S11*rdet
    Si01 = -(S01*rdet)
    Si11 = S00*rdet
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
    nis = Si00*(inn00*inn00) + 2.0*Si01*inn00*inn10 + Si11*(inn10*inn10)
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
    _sinc_nu2, _cosc_nu2, _sinc2_nu2, _cosc2_nu2 = sinc_family(nu2, _sin_nu2, _cos_nu2)
    _sin_nu5 = math.sin(nu5)
    _cos_nu5 = math.cos(nu5)
    _sinc_nu5, _cosc_nu5, _sinc2_nu5, _cosc2_nu5 = sinc_family(nu5, _sin_nu5, _cos_nu5)
    _t2 = -(_cosc_nu2*nu1) + _sinc_nu2*nu0
    _t3 = _cosc_nu2*nu0 + _sinc_nu2*nu1
    _t4 = -(_cosc_nu5*nu4) + _sinc_nu5*nu3
    _t5 = _cosc_nu5*nu3 + _sinc_nu5*nu4
    _t6 = _cos_nu5*s_omega + _sin_nu5*c_omega
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
    mu00 = _t2*c_theta - _t3*s_theta + x
    mu01 = _t2*s_theta + _t3*c_theta + y
    mu02 = _cos_nu2*c_theta - _sin_nu2*s_theta
    mu03 = _cos_nu2*s_theta + _sin_nu2*c_theta
    mu04 = _t4*c_omega - _t5*s_omega + v_x
    mu05 = _t4*s_omega + _t5*c_omega + v_y
    mu06 = wrap_angle_sum(nu5 + omega, _t6)
    mu07 = _cos_nu5*c_omega - _sin_nu5*s_omega
    mu08 = _t6
    _t7 = alpha*c_theta
    _t8 = alpha*s_theta
    _t9 = alpha*hh01
    a00 = -(_t7*k00) - _t8*k01 + 1.0
    a01 = -(_t7*k01) - _t9*k00
    a10 = -(_t7*k10) - _t8*k11
    a11 = -(_t7*k11) - _t9*k10 + 1.0
    a20 = -(_t7*k20) - _t8*k21
    a21 = -(_t7*k21) - _t9*k20
    a30 = -(_t7*k30) - _t8*k31
    a31 = -(_t7*k31) - _t9*k30
    a40 = -(_t7*k40) - _t8*k41
    a41 = -(_t7*k41) - _t9*k40
    a50 = -(_t7*k50) - _t8*k51
    a51 = -(_t7*k51) - _t9*k50
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
    _t10 = (alpha*alpha)*(r*r)
    _t11 = _t10*k00
    _t12 = _t10*k01
    _t13 = _t10*k10
    _t14 = _t10*k11
    _t15 = _t10*k20
    _t16 = _t10*k21
    _t17 = _t10*k30
    _t18 = _t10*k31
    pj00 = _t10*(k00*k00) + _t10*(k01*k01) + a00*b00 + a01*b01
    pj01 = _t11*k10 + _t12*k11 + a10*b00 + a11*b01
    pj02 = _t11*k20 + _t12*k21 + a20*b00 + a21*b01 + b02
    pj03 = _t11*k30 + _t12*k31 + a30*b00 + a31*b01 + b03
    pj04 = _t11*k40 + _t12*k41 + a40*b00 + a41*b01 + b04
    pj05 = _t11*k50 + _t12*k51 + a50*b00 + a51*b01 + b05
    pj11 = _t10*(k10*k10) + _t10*(k11*k11) + a10*b10 + a11*b11
    pj12 = _t13*k20 + _t14*k21 + a20*b10 + a21*b11 + b12
    pj13 = _t13*k30 + _t14*k31 + a30*b10 + a31*b11 + b13
    pj14 = _t13*k40 + _t14*k41 + a40*b10 + a41*b11 + b14
    pj15 = _t13*k50 + _t14*k51 + a50*b10 + a51*b11 + b15
    pj22 = _t10*(k20*k20) + _t10*(k21*k21) + a20*b20 + a21*b21 + b22
    pj23 = _t15*k30 + _t16*k31 + a30*b20 + a31*b21 + b23
    pj24 = _t15*k40 + _t16*k41 + a40*b20 + a41*b21 + b24
    pj25 = _t15*k50 + _t16*k51 + a50*b20 + a51*b21 + b25
    pj33 = _t10*(k30*k30) + _t10*(k31*k31) + a30*b30 + a31*b31 + b33
    pj34 = _t17*k40 + _t18*k41 + a40*b30 + a41*b31 + b34
    pj35 = _t17*k50 + _t18*k51 + a50*b30 + a51*b31 + b35
    pj44 = _t10*(k40*k40) + _t10*(k41*k41) + a40*b40 + a41*b41 + b44
    pj45 = _t10*k40*k50 + _t10*k41*k51 + a50*b40 + a51*b41 + b45
    pj55 = _t10*(k50*k50) + _t10*(k51*k51) + a50*b50 + a51*b51 + b55
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
    s[6] = mu06
    s[7] = mu07
    s[8] = mu08
    if not covariance_is_pd(p):
        repair_pd(p)
    return nis


@nb.njit(cache=True, fastmath=FASTMATH, error_model="numpy")
def step_try_position(s, p, dt, sigma_x, sigma_y, sigma_omega, z_x, z_y, r):
    """One fused LG-EKF step with a position measurement, in place: ``predict`` then ``update_position``
    (eq:pred_mu, eq:pred_cov, angle-variance cap, eq:K, eq:up_mu, eq:up_P) in one kernel; returns the NIS.
    Covariance as P − βKℋP; a step whose result fails the LDLᵀ test (covariance_is_pd_fused) leaves the
    prediction in s, p and returns -1.0: the caller then runs update_position (Joseph form;
    derive/codegen/fused.py).
    legend: cc = 𝒞 (eq:C), f = F = Ad(exp(−Ω)) + Φ(Ω)𝒞 (eq:pred_cov), g = Φ(Ω)G, hh = ℋ (eq:calH), hp = ℋP, inn = [log_G'(h(μ)⁻¹Z)]^∨, S = ℋPℋᵀ + R, Si = S⁻¹, k = K (eq:K), nk = Kν, alpha = gain damping, nu = ν, phi = Φ(ν) (eq:up_P), a = I − αKℋ, b = aP, beta = α(2 − α), kb = βK, pj = Joseph-form P (= P − βKℋP), cp = Φ(ν)·pj, mu/e = new mean
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
    _t0 = c_omega*dt
    _t1 = dt*s_omega
    cc03 = _t0
    cc04 = -_t1
    cc13 = _t1
    cc14 = _t0
    _a0 = dt*omega
    _sin__a0 = math.sin(_a0)
    _cos__a0 = math.cos(_a0)
    _sinc__a0, _cosc__a0, _sinc2__a0, _cosc2__a0 = sinc_family(_a0, _sin__a0, _cos__a0)
    _t2 = dt*v_x
    _t3 = _cosc__a0*_t2
    _t4 = dt*v_y
    _t5 = _sinc__a0*_t4
    _t6 = -(_cosc2__a0*_t4) + _sinc2__a0*dt*v_x
    _t7 = _cosc__a0*_t4
    _t8 = _cosc2__a0*_t2 + _sinc2__a0*_t4
    _t9 = (dt*dt)/2.0
    _t10 = _sinc__a0*_t9
    _t11 = _cosc__a0*_t9
    _t12 = _sinc__a0*dt*v_x - _t7
    _t13 = _t3 + _t5
    f00 = _cos__a0
    f01 = _sin__a0
    f02 = _t3 - _t5
    f03 = _cosc__a0*cc13 + _sinc__a0*cc03
    f04 = _cosc__a0*cc14 + _sinc__a0*cc04
    f05 = _t6*dt
    f10 = -_sin__a0
    f11 = _cos__a0
    f12 = _sinc__a0*_t2 + _t7
    f13 = -(_cosc__a0*cc03) + _sinc__a0*cc13
    f14 = -(_cosc__a0*cc04) + _sinc__a0*cc14
    f15 = _t8*dt
    g00 = _t10
    g01 = _t11
    g02 = _t6*_t9
    g10 = -_t11
    g11 = _t10
    g12 = _t8*_t9
    g22 = _t9
    e00 = _t12*c_theta - _t13*s_theta + x
    e01 = _t12*s_theta + _t13*c_theta + y
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
    _t14 = sigma_x*sigma_x
    _t15 = sigma_y*sigma_y
    _t16 = sigma_omega*sigma_omega
    _t17 = _t14*g00
    _t18 = _t15*g01
    _t19 = _t16*g02
    _t20 = _t16*g12
    _t21 = dt*dt
    pp00 = _t14*(g00*g00) + _t15*(g01*g01) + _t16*(g02*g02) + f00*m00 + f01*m01 + f02*m02 + f03*m03 + f04*m04 + f05*m05
    pp01 = _t17*g10 + _t18*g11 + _t19*g12 + f10*m00 + f11*m01 + f12*m02 + f13*m03 + f14*m04 + f15*m05
    pp02 = _t19*g22 + dt*m05 + m02
    pp03 = _t17*dt + m03
    pp04 = _t18*dt + m04
    pp05 = _t19*dt + m05
    pp11 = _t14*(g10*g10) + _t15*(g11*g11) + _t16*(g12*g12) + f10*m10 + f11*m11 + f12*m12 + f13*m13 + f14*m14 + f15*m15
    pp12 = _t20*g22 + dt*m15 + m12
    pp13 = _t14*dt*g10 + m13
    pp14 = _t15*dt*g11 + m14
    pp15 = _t20*dt + m15
    pp22 = _t16*(g22*g22) + dt*m25 + m22
    pp23 = m23
    pp24 = m24
    pp25 = _t16*dt*g22 + m25
    pp33 = _t14*_t21 + p33
    pp34 = p34
    pp35 = p35
    pp44 = _t15*_t21 + p44
    pp45 = p45
    pp55 = _t16*_t21 + p55
    x_p = e00
    y_p = e01
    c_theta_p = e02
    s_theta_p = e03
    if pp22 > math.pi * math.pi:
        _cap = math.pi / math.sqrt(pp22)
        pp02 = pp02 * _cap
        pp12 = pp12 * _cap
        pp23 = pp23 * _cap
        pp24 = pp24 * _cap
        pp25 = pp25 * _cap
        pp22 = math.pi * math.pi
    if pp55 > math.pi * math.pi:
        _cap = math.pi / math.sqrt(pp55)
        pp05 = pp05 * _cap
        pp15 = pp15 * _cap
        pp25 = pp25 * _cap
        pp35 = pp35 * _cap
        pp45 = pp45 * _cap
        pp55 = math.pi * math.pi
    hh01 = -s_theta_p
    _t22 = c_theta_p*pp01
    hp00 = c_theta_p*pp00 + hh01*pp01
    hp01 = _t22 + hh01*pp11
    hp02 = c_theta_p*pp02 + hh01*pp12
    hp03 = c_theta_p*pp03 + hh01*pp13
    hp04 = c_theta_p*pp04 + hh01*pp14
    hp05 = c_theta_p*pp05 + hh01*pp15
    hp10 = _t22 + pp00*s_theta_p
    hp11 = c_theta_p*pp11 + pp01*s_theta_p
    hp12 = c_theta_p*pp12 + pp02*s_theta_p
    hp13 = c_theta_p*pp13 + pp03*s_theta_p
    hp14 = c_theta_p*pp14 + pp04*s_theta_p
    hp15 = c_theta_p*pp15 + pp05*s_theta_p
    inn00 = -x_p + z_x
    inn10 = -y_p + z_y
    _t23 = r*r
    S00 = _t23 + c_theta_p*hp00 + hh01*hp01
    S01 = c_theta_p*hp01 + hp00*s_theta_p
    S11 = _t23 + c_theta_p*hp11 + hp10*s_theta_p
    rdet = 1.0/(S00*S11 - S01*S01)
    Si00 = S11*rdet
    Si01 = -(S01*rdet)
    Si11 = S00*rdet
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
    nis = Si00*(inn00*inn00) + 2.0*Si01*inn00*inn10 + Si11*(inn10*inn10)
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
    _sinc_nu2, _cosc_nu2, _sinc2_nu2, _cosc2_nu2 = sinc_family(nu2, _sin_nu2, _cos_nu2)
    _sin_nu5 = math.sin(nu5)
    _cos_nu5 = math.cos(nu5)
    _sinc_nu5, _cosc_nu5, _sinc2_nu5, _cosc2_nu5 = sinc_family(nu5, _sin_nu5, _cos_nu5)
    _t24 = -(_cosc_nu2*nu1) + _sinc_nu2*nu0
    _t25 = _cosc_nu2*nu0 + _sinc_nu2*nu1
    _t26 = -(_cosc_nu5*nu4) + _sinc_nu5*nu3
    _t27 = _cosc_nu5*nu3 + _sinc_nu5*nu4
    _t28 = _cos_nu5*s_omega + _sin_nu5*c_omega
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
    mu00 = _t24*c_theta_p - _t25*s_theta_p + x_p
    mu01 = _t24*s_theta_p + _t25*c_theta_p + y_p
    mu02 = _cos_nu2*c_theta_p - _sin_nu2*s_theta_p
    mu03 = _cos_nu2*s_theta_p + _sin_nu2*c_theta_p
    mu04 = _t26*c_omega - _t27*s_omega + v_x
    mu05 = _t26*s_omega + _t27*c_omega + v_y
    mu06 = wrap_angle_sum(nu5 + omega, _t28)
    mu07 = _cos_nu5*c_omega - _sin_nu5*s_omega
    mu08 = _t28
    beta = alpha*(2.0 - alpha)
    kb00 = beta*k00
    kb01 = beta*k01
    kb10 = beta*k10
    kb11 = beta*k11
    kb20 = beta*k20
    kb21 = beta*k21
    kb30 = beta*k30
    kb31 = beta*k31
    kb40 = beta*k40
    kb41 = beta*k41
    kb50 = beta*k50
    kb51 = beta*k51
    pj00 = -(hp00*kb00) - hp10*kb01 + pp00
    pj01 = -(hp01*kb00) - hp11*kb01 + pp01
    pj02 = -(hp02*kb00) - hp12*kb01 + pp02
    pj03 = -(hp03*kb00) - hp13*kb01 + pp03
    pj04 = -(hp04*kb00) - hp14*kb01 + pp04
    pj05 = -(hp05*kb00) - hp15*kb01 + pp05
    pj11 = -(hp01*kb10) - hp11*kb11 + pp11
    pj12 = -(hp02*kb10) - hp12*kb11 + pp12
    pj13 = -(hp03*kb10) - hp13*kb11 + pp13
    pj14 = -(hp04*kb10) - hp14*kb11 + pp14
    pj15 = -(hp05*kb10) - hp15*kb11 + pp15
    pj22 = -(hp02*kb20) - hp12*kb21 + pp22
    pj23 = -(hp03*kb20) - hp13*kb21 + pp23
    pj24 = -(hp04*kb20) - hp14*kb21 + pp24
    pj25 = -(hp05*kb20) - hp15*kb21 + pp25
    pj33 = -(hp03*kb30) - hp13*kb31 + pp33
    pj34 = -(hp04*kb30) - hp14*kb31 + pp34
    pj35 = -(hp05*kb30) - hp15*kb31 + pp35
    pj44 = -(hp04*kb40) - hp14*kb41 + pp44
    pj45 = -(hp05*kb40) - hp15*kb41 + pp45
    pj55 = -(hp05*kb50) - hp15*kb51 + pp55
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
    out_p0 = cp00*phi00 + cp01*phi01 + cp02*phi02
    out_p1 = cp00*phi10 + cp01*phi11 + cp02*phi12
    out_p2 = cp02
    out_p3 = cp03*phi33 + cp04*phi34 + cp05*phi35
    out_p4 = cp03*phi43 + cp04*phi44 + cp05*phi45
    out_p5 = cp05
    out_p6 = cp10*phi10 + cp11*phi11 + cp12*phi12
    out_p7 = cp12
    out_p8 = cp13*phi33 + cp14*phi34 + cp15*phi35
    out_p9 = cp13*phi43 + cp14*phi44 + cp15*phi45
    out_p10 = cp15
    out_p11 = pj22
    out_p12 = phi33*pj23 + phi34*pj24 + phi35*pj25
    out_p13 = phi43*pj23 + phi44*pj24 + phi45*pj25
    out_p14 = pj25
    out_p15 = cp33*phi33 + cp34*phi34 + cp35*phi35
    out_p16 = cp33*phi43 + cp34*phi44 + cp35*phi45
    out_p17 = cp35
    out_p18 = cp43*phi43 + cp44*phi44 + cp45*phi45
    out_p19 = cp45
    out_p20 = pj55
    out_s0 = mu00
    out_s1 = mu01
    out_s2 = mu02
    out_s3 = mu03
    out_s4 = mu04
    out_s5 = mu05
    out_s6 = mu06
    out_s7 = mu07
    out_s8 = mu08
    if not covariance_is_pd_fused(out_p0, out_p1, out_p2, out_p3, out_p4, out_p5, out_p6, out_p7, out_p8, out_p9, out_p10, out_p11, out_p12, out_p13, out_p14, out_p15, out_p16, out_p17, out_p18, out_p19, out_p20):
        out_p0 = pp00
        out_p1 = pp01
        out_p2 = pp02
        out_p3 = pp03
        out_p4 = pp04
        out_p5 = pp05
        out_p6 = pp11
        out_p7 = pp12
        out_p8 = pp13
        out_p9 = pp14
        out_p10 = pp15
        out_p11 = pp22
        out_p12 = pp23
        out_p13 = pp24
        out_p14 = pp25
        out_p15 = pp33
        out_p16 = pp34
        out_p17 = pp35
        out_p18 = pp44
        out_p19 = pp45
        out_p20 = pp55
        out_s0 = x_p
        out_s1 = y_p
        out_s2 = c_theta_p
        out_s3 = s_theta_p
        out_s4 = v_x
        out_s5 = v_y
        out_s6 = omega
        out_s7 = c_omega
        out_s8 = s_omega
        nis = -1.0
    p[0] = out_p0
    p[1] = out_p1
    p[2] = out_p2
    p[3] = out_p3
    p[4] = out_p4
    p[5] = out_p5
    p[6] = out_p6
    p[7] = out_p7
    p[8] = out_p8
    p[9] = out_p9
    p[10] = out_p10
    p[11] = out_p11
    p[12] = out_p12
    p[13] = out_p13
    p[14] = out_p14
    p[15] = out_p15
    p[16] = out_p16
    p[17] = out_p17
    p[18] = out_p18
    p[19] = out_p19
    p[20] = out_p20
    s[0] = out_s0
    s[1] = out_s1
    s[2] = out_s2
    s[3] = out_s3
    s[4] = out_s4
    s[5] = out_s5
    s[6] = out_s6
    s[7] = out_s7
    s[8] = out_s8
    return nis


@nb.njit(cache=True)
def step_position(s, p, dt, sigma_x, sigma_y, sigma_omega, z_x, z_y, r):
    """One LG-EKF step with a position measurement, in place; returns the NIS: ``step_try_position``, and on the rare
    step whose cheap covariance fails the LDLᵀ test, ``update_position`` (Joseph form) from the prediction
    (derive/codegen/fused.py)."""
    nis = step_try_position(s, p, dt, sigma_x, sigma_y, sigma_omega, z_x, z_y, r)
    if nis < 0.0:
        nis = update_position(s, p, z_x, z_y, r)
    return nis


@nb.njit(cache=True)
def measure_position(s, m0, m1):
    """Simulated position measurement vector(h(X)·exp(m)) of the state s for a noise sample m.
    """
    x = s[0]
    y = s[1]
    out = np.zeros(2)
    out[0] = m0 + x
    out[1] = m1 + y
    return out


@nb.njit(cache=True, nogil=True)  # nogil: the process-noise search (lgekf.apps.search) runs filters in threads
def run_one_position(z, dts, x0, p0, q, r, out_x, out_p, out_nis):
    """Filter one trajectory with position measurements: z (K, 2), dts (K,), x0 (6,), p0 (21,).

    A row of z containing NaN is a missed detection: the step predicts only (its NIS is NaN).
    """
    s = state_from_physical(x0)
    p = p0.copy()
    K = z.shape[0]
    keep_p = out_p.shape[0] == K
    for k in range(K):
        if np.isnan(z[k, 0]) or np.isnan(z[k, 1]):
            predict(s, p, dts[k], q[0], q[1], q[2])
            out_nis[k] = np.nan
        else:
            nis = step_try_position(s, p, dts[k], q[0], q[1], q[2], z[k, 0], z[k, 1], r[0])
            if nis < 0.0:  # rare: the cheap covariance failed the LDLᵀ test; Joseph form from the prediction
                nis = update_position(s, p, z[k, 0], z[k, 1], r[0])
            out_nis[k] = nis
        physical_into(s, out_x[k])
        if keep_p:
            for i in range(21):
                out_p[k, i] = p[i]


@nb.njit(cache=True, nogil=True)
def run_segments_position(z, t, first, lengths, x0, p0, q, r, out_x, out_p, out_nis):
    """``run_one_position`` on segments of rows, one after the other (no Python per segment).

    Segment i is rows first[i] .. first[i] + lengths[i] - 1 (first[i] >= 1) of z (N, 2) and t (N,), filtered
    from x0[i] (6,), p0[i] (21,) at time t[first[i] - 1]; its outputs go to the same rows of out_x (N, 6),
    out_p (N, 21) and out_nis (N,). The numbers of ``run_one_position`` called per segment with
    dts = t[a:b] - t[a - 1:b - 1].
    """
    longest = 0
    for i in range(first.shape[0]):
        longest = max(longest, lengths[i])
    dts = np.empty(longest)
    for i in range(first.shape[0]):
        a = first[i]
        b = a + lengths[i]
        for k in range(a, b):
            dts[k - a] = t[k] - t[k - 1]
        run_one_position(z[a:b], dts[:b - a], x0[i], p0[i], q, r, out_x[a:b], out_p[a:b], out_nis[a:b])


@nb.njit(cache=True, nogil=True)
def run_one_from_position(z, dts, s0, p0, q, r, out_x, out_p, out_nis):
    """``run_one_position`` from the internal state s0 (9,) (the layout of ``state_from_physical``) and p0 (21,),
    which on return hold the posterior of the last row: a later call from them continues exactly (the numbers
    of one call over both rows). ``lgekf track`` filters a long object in windows of rows with it.
    """
    s = s0.copy()
    p = p0.copy()
    K = z.shape[0]
    keep_p = out_p.shape[0] == K
    for k in range(K):
        if np.isnan(z[k, 0]) or np.isnan(z[k, 1]):
            predict(s, p, dts[k], q[0], q[1], q[2])
            out_nis[k] = np.nan
        else:
            nis = step_try_position(s, p, dts[k], q[0], q[1], q[2], z[k, 0], z[k, 1], r[0])
            if nis < 0.0:  # rare: the cheap covariance failed the LDLᵀ test; Joseph form from the prediction
                nis = update_position(s, p, z[k, 0], z[k, 1], r[0])
            out_nis[k] = nis
        physical_into(s, out_x[k])
        if keep_p:
            for i in range(21):
                out_p[k, i] = p[i]
    s0[:] = s
    p0[:] = p


@nb.njit(cache=True, nogil=True)
def run_segments_from_position(z, t, first, lengths, s0, p0, q, r, out_x, out_p, out_nis):
    """``run_segments_position`` from internal states s0 (S, 9) and p0 (S, 21) (``run_one_from_position``): on
    return s0[i], p0[i] hold the posterior of segment i's last row (unchanged for an empty segment).
    """
    longest = 0
    for i in range(first.shape[0]):
        longest = max(longest, lengths[i])
    dts = np.empty(longest)
    for i in range(first.shape[0]):
        a = first[i]
        b = a + lengths[i]
        for k in range(a, b):
            dts[k - a] = t[k] - t[k - 1]
        run_one_from_position(z[a:b], dts[:b - a], s0[i], p0[i], q, r, out_x[a:b], out_p[a:b], out_nis[a:b])


@nb.njit(cache=True, parallel=True)
def run_batch_position(z, dts, x0, p0, q, r, out_x, out_p, out_nis):
    """Filter B trajectories in parallel (numba prange), predict then update at every step.

    z (B, K, 2) position measurements (a NaN row = missed detection); dts (B, K) step lengths; x0 (B, 6)
    physical initial states; p0 (B, 21) packed initial covariances; q (3,) process-noise stds;
    r (1,) measurement-noise stds. Writes the posterior physical states into out_x (B, K, 6), the
    packed covariances into out_p (B, K, 21) when out_p.shape[1] == K (pass (B, 0, 21) to skip),
    and the NIS into out_nis (B, K).
    """
    for b in nb.prange(z.shape[0]):
        run_one_position(z[b], dts[b], x0[b], p0[b], q, r, out_x[b], out_p[b], out_nis[b])


@nb.njit(cache=True)
def measure_batch_position(X, noise, out):
    """Simulated position measurements z = vector(h(X)·exp(m)) of every physical state X (N, 6),
    noise samples m (N, 2) (already scaled), into out (N, 2)."""
    for i in range(X.shape[0]):
        s = state_from_physical(X[i])
        z = measure_position(s, noise[i, 0], noise[i, 1])
        for j in range(2):
            out[i, j] = z[j]


@nb.njit(cache=True)
def innovation_into_position(s, z_x, z_y, out):
    """The position innovation e = [log_G'(h(μ)⁻¹ Z)]^∨ (eq:K) of the state s for the measured z, written into out (2,).
    """
    x = s[0]
    y = s[1]
    out[0] = -x + z_x
    out[1] = -y + z_y


@nb.njit(cache=True)
def innovation_bank_position(s, live, z, out):
    """Innovation [log_G'(h(μ_i)⁻¹ Z_j)]^∨ of every live track i (rows of s, live[i] true) and every
    position detection j (rows of z, (M, 2)) into out (N, M, 2); rows of dead tracks are not written."""
    for i in range(s.shape[0]):
        if live[i]:
            si = s[i]
            for j in range(z.shape[0]):
                innovation_into_position(si, z[j, 0], z[j, 1], out[i, j])


@nb.njit(cache=True)
def calH_bank_position(s, live, out):
    """ℋ (eq:calH) of every live track for position measurements into out (N, 2, 6)."""
    for i in range(s.shape[0]):
        if live[i]:
            h = calH_position(s[i])
            for a in range(2):
                for b in range(6):
                    out[i, a, b] = h[a, b]


@nb.njit(cache=True, nogil=True)
def run_segments_noise_from_position(z, t, first, lengths, s0, p0, q, r, out_x, out_p, out_nis):
    """``run_segments_from_position`` with noise stds of each segment's own: q (S, 3), r (S, 1) (the divergence
    recovery's reruns, each object's noise inflated by its own factor). On return s0[i], p0[i] hold the posterior
    of segment i's last row, from which a later call continues exactly. The numbers of ``run_one_from_position``
    called per segment i with q[i], r[i]."""
    longest = 0
    for i in range(first.shape[0]):
        longest = max(longest, lengths[i])
    dts = np.empty(longest)
    for i in range(first.shape[0]):
        a = first[i]
        b = a + lengths[i]
        for k in range(a, b):
            dts[k - a] = t[k] - t[k - 1]
        run_one_from_position(z[a:b], dts[:b - a], s0[i], p0[i], q[i], r[i], out_x[a:b], out_p[a:b], out_nis[a:b])


@nb.njit(cache=True, nogil=True, error_model="numpy")
def rerun_position(zm, t, a, b, s1, p1, q, r, scale, q1, r1, x, p, nis):
    """Filter rows a .. b - 1 from the internal state s1 (1, ni) and packed covariance p1 (1, n(n+1)/2) of row a - 1, every
    noise std times ``scale`` (q1, r1 (1, nq), (1, nr) scratch), into x, p, nis; s1, p1 are left at row b - 1."""
    for j in range(q.shape[0]):
        q1[0, j] = q[j] * scale
    for j in range(r.shape[0]):
        r1[0, j] = r[j] * scale
    run_segments_noise_from_position(zm, t, np.full(1, a, np.int64), np.full(1, b - a, np.int64), s1, p1, q1, r1, x, p, nis)


@nb.njit(cache=True, nogil=True, error_model="numpy")
def recover_position(
        x, p, nis, flag, seg_obj, seg_first, seg_end, run_first, run_s, run_p, run_scale0, limits, m, window, short, clip, thr,
        thr_short, n_sigma, max_reinit, repeat, max_inflation, rerun_rows, count, scale, last, zm, t, q, r, t_all, z_all,
        heading_all, offset, obj_first, meas_std, omega_std, heading_std, heading_cap, sideslip, baseline, angles, carry_s,
        carry_p, carry_scale, carry_reached):
    """The divergence monitor and recovery of ``lgekf.apps.divergence.recover``, segment after segment, compiled.

    Segment i is rows seg_first[i] .. seg_end[i] - 1 of object seg_obj[i]. Where run_first[i] >= 0 its rows run_first[i]
    .. seg_end[i] - 1 are filtered first, from the internal state run_s[i] and covariance run_p[i] of the row before, the
    noise stds times run_scale0[i] (the first pass of ``lgekf.apps.track.track_monitored``: one library with the
    filter's step per model instead of two); else they are in x, p, nis already. Each
    round scans rows for the first alarm (``first_alarm``); at an alarm the row is re-initialised (``reinit_into``, the
    measurements of global row + ``offset`` of t_all, z_all, heading_all; obj_first (B,) global) and the filter is
    run again over a window of ``rerun_rows`` rows that doubles until the next alarm or the segment's end, each window
    going on from the previous one's last state and scanned from max(window, short) rows before it. count, scale,
    last (B,): the objects' memory, updated in place; flag (N,) int8 set on the alarms' rows. carry_s, carry_p,
    carry_scale, carry_reached (B,): the filter's state, covariance and noise inflation after the segment's last row
    where a re-initialisation or a rerun reached it (carry_reached True). Returns the alarms (A, 8): obj, row, kind,
    value, limit, updates, reinitialised (1.0 / 0.0), scale, object after object, each object's in order."""
    N = x.shape[0]
    n = x.shape[1]
    over = np.zeros(N, np.bool_)
    absurd = np.zeros(N, np.bool_)
    bad = np.zeros(N, np.bool_)
    sp = np.empty(N)
    rows = np.empty(N, np.int64)
    xh = np.empty((1, n))
    grad = np.empty(n)
    reach = max(window, short)
    found = np.empty((16, 8))  # the alarms: obj, row, kind, value, limit, updates, reinitialised, scale (rows grow)
    na = 0
    s1 = np.empty((1, carry_s.shape[1]))
    p1 = np.empty((1, p.shape[1]))
    q1 = np.empty((1, q.shape[0]))
    r1 = np.empty((1, r.shape[0]))
    x0 = np.empty((1, n))
    p0 = np.empty(p.shape[1])
    nc = z_all.shape[1] * (z_all.shape[1] + 1)  # the space's common coordinates: 2d + d(d - 1) (6 in the plane, 12 in 3-D)
    c1 = np.empty((1, nc))
    var1 = np.empty(nc)
    cj1 = np.empty((1, nc))
    J1 = np.empty((1, n, nc))
    P1 = np.empty((n, n))
    for si in range(seg_obj.shape[0]):
        o = seg_obj[si]
        first = seg_first[si]
        end = seg_end[si]
        scan_from = first
        scan_end = end
        run_scale = scale[o]  # the noise inflation of the run being scanned
        reached = False  # a run or a re-initialisation reached the segment's last row
        if run_first[si] >= 0:  # the first pass
            copy_row(run_s, si, s1, 0)
            copy_row(run_p, si, p1, 0)
            run_scale = run_scale0[si]
            rerun_position(zm, t, run_first[si], end, s1, p1, q, r, run_scale, q1, r1, x, p, nis)
            reached = True
        while True:
            g, kind, val, start, lim = first_alarm(x, p, nis, scan_from, scan_end, limits[o], window, short, clip, thr, thr_short,
                                                   n_sigma, over, absurd, bad, sp, rows, xh, grad)
            if g < 0:
                if scan_end >= end:
                    break
                # no alarm in this window: the next, twice as wide, goes on from where the run stopped
                new_end = min(end, first + 2 * (scan_end - first))
                rerun_position(zm, t, scan_end, new_end, s1, p1, q, r, run_scale, q1, r1, x, p, nis)
                scan_from = max(first, scan_end - reach)
                scan_end = new_end
                reached = scan_end == end
                continue
            count[o] += 1
            if kind == 1 and g - last[o] <= repeat * window:  # soon after the last re-initialisation: the noise is too small
                scale[o] *= minimum(math.sqrt(maximum(val / m, 1.0)), max_inflation)
            ok = count[o] <= max_reinit
            if na == found.shape[0]:
                more = np.empty((2 * na, 8))
                for i in range(na):
                    for j in range(8):
                        more[i, j] = found[i, j]
                found = more
            found[na, 0] = o
            found[na, 1] = g
            found[na, 2] = kind
            found[na, 3] = val
            found[na, 4] = lim
            found[na, 5] = g - start + 1 if kind == 1 else 0
            found[na, 6] = 1.0 if ok else 0.0
            found[na, 7] = scale[o]
            na += 1
            # the NIS of an update tests the estimate before it: flag from the row before the alarm's first update (not
            # before the segment's first row) through the alarm row
            for k in range(max(max(start, first) - 1, 0), g + 1):
                flag[k] = 1
            if not ok:  # max_reinit used up: no more monitoring; the run goes on to the segment's end
                if scan_end < end:
                    rerun_position(zm, t, scan_end, end, s1, p1, q, r, run_scale, q1, r1, x, p, nis)
                    reached = True
                break
            last[o] = g
            reinit_into(t_all, z_all, heading_all, g + offset, obj_first[o], scale[o], meas_std, omega_std, heading_std, heading_cap,
                        sideslip, baseline, angles, c1, var1, cj1, J1, P1, x0, p0)
            copy_row(x0, 0, x, g)
            for j in range(p0.shape[0]):
                p[g, j] = p0[j]
            nis[g] = np.nan
            states_from_physical(x0, s1)
            for j in range(p0.shape[0]):
                p1[0, j] = p0[j]
            run_scale = scale[o]
            if g + 1 >= end:  # the re-initialised row is the segment's last
                reached = True
                break
            first = g + 1
            scan_from = first
            scan_end = min(end, first + rerun_rows)
            rerun_position(zm, t, first, scan_end, s1, p1, q, r, run_scale, q1, r1, x, p, nis)
            reached = scan_end == end
        if reached:
            copy_row(s1, 0, carry_s, o)
            copy_row(p1, 0, carry_p, o)
            carry_scale[o] = run_scale
            carry_reached[o] = True
    return found[:na]


@nb.njit(inline="always", fastmath={"contract"}, error_model="numpy")
def lane_position(W, j, sigma_x, sigma_y, sigma_omega, r):
    """step_position on lane j of the work array W (rows: derive/codegen/soa.py Layout), without branches (SIMD).
    """
    x = W[0 + j]
    y = W[64 + j]
    c_theta = W[128 + j]
    s_theta = W[192 + j]
    v_x = W[256 + j]
    v_y = W[320 + j]
    omega = W[384 + j]
    c_omega = W[448 + j]
    s_omega = W[512 + j]
    p00 = W[576 + j]
    p01 = W[640 + j]
    p02 = W[704 + j]
    p03 = W[768 + j]
    p04 = W[832 + j]
    p05 = W[896 + j]
    p11 = W[960 + j]
    p12 = W[1024 + j]
    p13 = W[1088 + j]
    p14 = W[1152 + j]
    p15 = W[1216 + j]
    p22 = W[1280 + j]
    p23 = W[1344 + j]
    p24 = W[1408 + j]
    p25 = W[1472 + j]
    p33 = W[1536 + j]
    p34 = W[1600 + j]
    p35 = W[1664 + j]
    p44 = W[1728 + j]
    p45 = W[1792 + j]
    p55 = W[1856 + j]
    dt = W[3840 + j]
    z_x = W[4032 + j]
    z_y = W[4096 + j]
    _t0 = c_omega*dt
    _t1 = dt*s_omega
    cc03 = _t0
    cc04 = -_t1
    cc13 = _t1
    cc14 = _t0
    _a0 = dt*omega
    _sin__a0 = sin_v(_a0)
    _cos__a0 = cos_v(_a0)
    _sinc__a0, _cosc__a0, _sinc2__a0, _cosc2__a0 = sinc_family(_a0, _sin__a0, _cos__a0)
    _t2 = dt*v_x
    _t3 = _cosc__a0*_t2
    _t4 = dt*v_y
    _t5 = _sinc__a0*_t4
    _t6 = -(_cosc2__a0*_t4) + _sinc2__a0*dt*v_x
    _t7 = _cosc__a0*_t4
    _t8 = _cosc2__a0*_t2 + _sinc2__a0*_t4
    _t9 = (dt*dt)/2.0
    _t10 = _sinc__a0*_t9
    _t11 = _cosc__a0*_t9
    _t12 = _sinc__a0*dt*v_x - _t7
    _t13 = _t3 + _t5
    f00 = _cos__a0
    f01 = _sin__a0
    f02 = _t3 - _t5
    f03 = _cosc__a0*cc13 + _sinc__a0*cc03
    f04 = _cosc__a0*cc14 + _sinc__a0*cc04
    f05 = _t6*dt
    f10 = -_sin__a0
    f11 = _cos__a0
    f12 = _sinc__a0*_t2 + _t7
    f13 = -(_cosc__a0*cc03) + _sinc__a0*cc13
    f14 = -(_cosc__a0*cc04) + _sinc__a0*cc14
    f15 = _t8*dt
    g00 = _t10
    g01 = _t11
    g02 = _t6*_t9
    g10 = -_t11
    g11 = _t10
    g12 = _t8*_t9
    g22 = _t9
    e00 = _t12*c_theta - _t13*s_theta + x
    e01 = _t12*s_theta + _t13*c_theta + y
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
    _t14 = sigma_x*sigma_x
    _t15 = sigma_y*sigma_y
    _t16 = sigma_omega*sigma_omega
    _t17 = _t14*g00
    _t18 = _t15*g01
    _t19 = _t16*g02
    _t20 = _t16*g12
    _t21 = dt*dt
    pp00 = _t14*(g00*g00) + _t15*(g01*g01) + _t16*(g02*g02) + f00*m00 + f01*m01 + f02*m02 + f03*m03 + f04*m04 + f05*m05
    pp01 = _t17*g10 + _t18*g11 + _t19*g12 + f10*m00 + f11*m01 + f12*m02 + f13*m03 + f14*m04 + f15*m05
    pp02 = _t19*g22 + dt*m05 + m02
    pp03 = _t17*dt + m03
    pp04 = _t18*dt + m04
    pp05 = _t19*dt + m05
    pp11 = _t14*(g10*g10) + _t15*(g11*g11) + _t16*(g12*g12) + f10*m10 + f11*m11 + f12*m12 + f13*m13 + f14*m14 + f15*m15
    pp12 = _t20*g22 + dt*m15 + m12
    pp13 = _t14*dt*g10 + m13
    pp14 = _t15*dt*g11 + m14
    pp15 = _t20*dt + m15
    pp22 = _t16*(g22*g22) + dt*m25 + m22
    pp23 = m23
    pp24 = m24
    pp25 = _t16*dt*g22 + m25
    pp33 = _t14*_t21 + p33
    pp34 = p34
    pp35 = p35
    pp44 = _t15*_t21 + p44
    pp45 = p45
    pp55 = _t16*_t21 + p55
    x_p = e00
    y_p = e01
    c_theta_p = e02
    s_theta_p = e03
    if pp22 > math.pi * math.pi:
        _cap = math.pi / math.sqrt(pp22)
        pp02 = pp02 * _cap
        pp12 = pp12 * _cap
        pp23 = pp23 * _cap
        pp24 = pp24 * _cap
        pp25 = pp25 * _cap
        pp22 = math.pi * math.pi
    if pp55 > math.pi * math.pi:
        _cap = math.pi / math.sqrt(pp55)
        pp05 = pp05 * _cap
        pp15 = pp15 * _cap
        pp25 = pp25 * _cap
        pp35 = pp35 * _cap
        pp45 = pp45 * _cap
        pp55 = math.pi * math.pi
    hh01 = -s_theta_p
    _t22 = c_theta_p*pp01
    hp00 = c_theta_p*pp00 + hh01*pp01
    hp01 = _t22 + hh01*pp11
    hp02 = c_theta_p*pp02 + hh01*pp12
    hp03 = c_theta_p*pp03 + hh01*pp13
    hp04 = c_theta_p*pp04 + hh01*pp14
    hp05 = c_theta_p*pp05 + hh01*pp15
    hp10 = _t22 + pp00*s_theta_p
    hp11 = c_theta_p*pp11 + pp01*s_theta_p
    hp12 = c_theta_p*pp12 + pp02*s_theta_p
    hp13 = c_theta_p*pp13 + pp03*s_theta_p
    hp14 = c_theta_p*pp14 + pp04*s_theta_p
    hp15 = c_theta_p*pp15 + pp05*s_theta_p
    inn00 = -x_p + z_x
    inn10 = -y_p + z_y
    _t23 = r*r
    S00 = _t23 + c_theta_p*hp00 + hh01*hp01
    S01 = c_theta_p*hp01 + hp00*s_theta_p
    S11 = _t23 + c_theta_p*hp11 + hp10*s_theta_p
    rdet = 1.0/(S00*S11 - S01*S01)
    Si00 = S11*rdet
    Si01 = -(S01*rdet)
    Si11 = S00*rdet
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
    nis = Si00*(inn00*inn00) + 2.0*Si01*inn00*inn10 + Si11*(inn10*inn10)
    nk0 = inn00*k00 + inn10*k01
    nk1 = inn00*k10 + inn10*k11
    nk2 = inn00*k20 + inn10*k21
    nk3 = inn00*k30 + inn10*k31
    nk4 = inn00*k40 + inn10*k41
    nk5 = inn00*k50 + inn10*k51
    alpha = gain_damping_v(nk2, nk5)
    nu0 = alpha*nk0
    nu1 = alpha*nk1
    nu2 = alpha*nk2
    nu3 = alpha*nk3
    nu4 = alpha*nk4
    nu5 = alpha*nk5
    _sin_nu2 = sin_v(nu2)
    _cos_nu2 = cos_v(nu2)
    _sinc_nu2, _cosc_nu2, _sinc2_nu2, _cosc2_nu2 = sinc_family(nu2, _sin_nu2, _cos_nu2)
    _sin_nu5 = sin_v(nu5)
    _cos_nu5 = cos_v(nu5)
    _sinc_nu5, _cosc_nu5, _sinc2_nu5, _cosc2_nu5 = sinc_family(nu5, _sin_nu5, _cos_nu5)
    _t24 = -(_cosc_nu2*nu1) + _sinc_nu2*nu0
    _t25 = _cosc_nu2*nu0 + _sinc_nu2*nu1
    _t26 = -(_cosc_nu5*nu4) + _sinc_nu5*nu3
    _t27 = _cosc_nu5*nu3 + _sinc_nu5*nu4
    _t28 = _cos_nu5*s_omega + _sin_nu5*c_omega
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
    mu00 = _t24*c_theta_p - _t25*s_theta_p + x_p
    mu01 = _t24*s_theta_p + _t25*c_theta_p + y_p
    mu02 = _cos_nu2*c_theta_p - _sin_nu2*s_theta_p
    mu03 = _cos_nu2*s_theta_p + _sin_nu2*c_theta_p
    mu04 = _t26*c_omega - _t27*s_omega + v_x
    mu05 = _t26*s_omega + _t27*c_omega + v_y
    mu06 = wrap_sum_v(nu5 + omega, _t28)
    mu07 = _cos_nu5*c_omega - _sin_nu5*s_omega
    mu08 = _t28
    beta = alpha*(2.0 - alpha)
    kb00 = beta*k00
    kb01 = beta*k01
    kb10 = beta*k10
    kb11 = beta*k11
    kb20 = beta*k20
    kb21 = beta*k21
    kb30 = beta*k30
    kb31 = beta*k31
    kb40 = beta*k40
    kb41 = beta*k41
    kb50 = beta*k50
    kb51 = beta*k51
    pj00 = -(hp00*kb00) - hp10*kb01 + pp00
    pj01 = -(hp01*kb00) - hp11*kb01 + pp01
    pj02 = -(hp02*kb00) - hp12*kb01 + pp02
    pj03 = -(hp03*kb00) - hp13*kb01 + pp03
    pj04 = -(hp04*kb00) - hp14*kb01 + pp04
    pj05 = -(hp05*kb00) - hp15*kb01 + pp05
    pj11 = -(hp01*kb10) - hp11*kb11 + pp11
    pj12 = -(hp02*kb10) - hp12*kb11 + pp12
    pj13 = -(hp03*kb10) - hp13*kb11 + pp13
    pj14 = -(hp04*kb10) - hp14*kb11 + pp14
    pj15 = -(hp05*kb10) - hp15*kb11 + pp15
    pj22 = -(hp02*kb20) - hp12*kb21 + pp22
    pj23 = -(hp03*kb20) - hp13*kb21 + pp23
    pj24 = -(hp04*kb20) - hp14*kb21 + pp24
    pj25 = -(hp05*kb20) - hp15*kb21 + pp25
    pj33 = -(hp03*kb30) - hp13*kb31 + pp33
    pj34 = -(hp04*kb30) - hp14*kb31 + pp34
    pj35 = -(hp05*kb30) - hp15*kb31 + pp35
    pj44 = -(hp04*kb40) - hp14*kb41 + pp44
    pj45 = -(hp05*kb40) - hp15*kb41 + pp45
    pj55 = -(hp05*kb50) - hp15*kb51 + pp55
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
    W[2496 + j] = cp00*phi00 + cp01*phi01 + cp02*phi02
    W[2560 + j] = cp00*phi10 + cp01*phi11 + cp02*phi12
    W[2624 + j] = cp02
    W[2688 + j] = cp03*phi33 + cp04*phi34 + cp05*phi35
    W[2752 + j] = cp03*phi43 + cp04*phi44 + cp05*phi45
    W[2816 + j] = cp05
    W[2880 + j] = cp10*phi10 + cp11*phi11 + cp12*phi12
    W[2944 + j] = cp12
    W[3008 + j] = cp13*phi33 + cp14*phi34 + cp15*phi35
    W[3072 + j] = cp13*phi43 + cp14*phi44 + cp15*phi45
    W[3136 + j] = cp15
    W[3200 + j] = pj22
    W[3264 + j] = phi33*pj23 + phi34*pj24 + phi35*pj25
    W[3328 + j] = phi43*pj23 + phi44*pj24 + phi45*pj25
    W[3392 + j] = pj25
    W[3456 + j] = cp33*phi33 + cp34*phi34 + cp35*phi35
    W[3520 + j] = cp33*phi43 + cp34*phi44 + cp35*phi45
    W[3584 + j] = cp35
    W[3648 + j] = cp43*phi43 + cp44*phi44 + cp45*phi45
    W[3712 + j] = cp45
    W[3776 + j] = pj55
    W[1920 + j] = mu00
    W[1984 + j] = mu01
    W[2048 + j] = mu02
    W[2112 + j] = mu03
    W[2176 + j] = mu04
    W[2240 + j] = mu05
    W[2304 + j] = mu06
    W[2368 + j] = mu07
    W[2432 + j] = mu08
    return nis


@nb.njit(cache=True, parallel=True, fastmath=FASTMATH, error_model="numpy")
def run_batch_soa_position(z, dts, x0, p0, q, r, out_x, out_p, out_nis):
    """run_batch_position with trajectories in the SIMD lanes (derive/codegen/soa.py): same arguments and results.

    Blocks of 64 trajectories (prange over blocks); in a block every per-trajectory quantity is a row of one
    work array (rows × 64) and lane_position runs vectorised over the lanes; a lane failing the LDLᵀ test or with
    a NaN row (NaN NIS) is redone by the scalar predict / update_position.
    """
    B = z.shape[0]
    K = z.shape[1]
    keep_p = out_p.shape[1] == K
    nblk = (B + 64 - 1) // 64
    for blk in nb.prange(nblk):
        lo = blk * 64
        L = min(64, B - lo)
        W = np.zeros(65 * 64)
        s = np.empty(9)
        p = np.empty(21)
        for j in range(L):
            s0 = state_from_physical(x0[lo + j])
            for i in range(9):
                W[(0 + i) * 64 + j] = s0[i]
            for i in range(21):
                W[(9 + i) * 64 + j] = p0[lo + j, i]
        for k in range(K):
            for j in range(L):
                W[60 * 64 + j] = dts[lo + j, k]
                W[63 * 64 + j] = z[lo + j, k, 0]
                W[64 * 64 + j] = z[lo + j, k, 1]
            for j in range(L):
                W[61 * 64 + j] = lane_position(W, j, q[0], q[1], q[2], r[0])
                good = covariance_is_pd_lane(W, j) & (W[61 * 64 + j] == W[61 * 64 + j])
                W[62 * 64 + j] = 1.0 if good else 0.0
            for j in range(L):
                if W[62 * 64 + j] == 0.0:
                    b = lo + j
                    for i in range(9):
                        s[i] = W[(0 + i) * 64 + j]
                    for i in range(21):
                        p[i] = W[(9 + i) * 64 + j]
                    predict(s, p, dts[b, k], q[0], q[1], q[2])
                    if np.isnan(z[b, k, 0]) or np.isnan(z[b, k, 1]):
                        W[61 * 64 + j] = np.nan
                    else:
                        W[61 * 64 + j] = update_position(s, p, z[b, k, 0], z[b, k, 1], r[0])
                    for i in range(9):
                        W[(30 + i) * 64 + j] = s[i]
                    for i in range(21):
                        W[(39 + i) * 64 + j] = p[i]
            for j in range(L):
                out_nis[lo + j, k] = W[61 * 64 + j]
                physical_lane(W, j, out_x, lo + j, k)
            if keep_p:
                for j in range(L):
                    for i in range(21):
                        out_p[lo + j, k, i] = W[(39 + i) * 64 + j]
            for i in range(9 + 21):
                for j in range(L):
                    W[(0 + i) * 64 + j] = W[(30 + i) * 64 + j]


@nb.njit(cache=True)
def covariance_is_pd(p):
    """LDLᵀ test of the packed covariance: every pivot d_j > 1e-13 · max_i P_ii (NaN fails)."""
    p0_0 = p[0]
    p0_1 = p[1]
    p0_2 = p[2]
    p0_3 = p[3]
    p0_4 = p[4]
    p0_5 = p[5]
    p1_1 = p[6]
    p1_2 = p[7]
    p1_3 = p[8]
    p1_4 = p[9]
    p1_5 = p[10]
    p2_2 = p[11]
    p2_3 = p[12]
    p2_4 = p[13]
    p2_5 = p[14]
    p3_3 = p[15]
    p3_4 = p[16]
    p3_5 = p[17]
    p4_4 = p[18]
    p4_5 = p[19]
    p5_5 = p[20]
    tol = 1e-13 * max(p0_0, p1_1, p2_2, p3_3, p4_4, p5_5)
    d0 = p0_0
    if not d0 > tol:
        return False
    r0 = 1.0 / d0
    l1_0 = (p0_1) * r0
    l2_0 = (p0_2) * r0
    l3_0 = (p0_3) * r0
    l4_0 = (p0_4) * r0
    l5_0 = (p0_5) * r0
    d1 = p1_1 - l1_0 * l1_0 * d0
    if not d1 > tol:
        return False
    r1 = 1.0 / d1
    l2_1 = (p1_2 - l2_0 * l1_0 * d0) * r1
    l3_1 = (p1_3 - l3_0 * l1_0 * d0) * r1
    l4_1 = (p1_4 - l4_0 * l1_0 * d0) * r1
    l5_1 = (p1_5 - l5_0 * l1_0 * d0) * r1
    d2 = p2_2 - l2_0 * l2_0 * d0 - l2_1 * l2_1 * d1
    if not d2 > tol:
        return False
    r2 = 1.0 / d2
    l3_2 = (p2_3 - l3_0 * l2_0 * d0 - l3_1 * l2_1 * d1) * r2
    l4_2 = (p2_4 - l4_0 * l2_0 * d0 - l4_1 * l2_1 * d1) * r2
    l5_2 = (p2_5 - l5_0 * l2_0 * d0 - l5_1 * l2_1 * d1) * r2
    d3 = p3_3 - l3_0 * l3_0 * d0 - l3_1 * l3_1 * d1 - l3_2 * l3_2 * d2
    if not d3 > tol:
        return False
    r3 = 1.0 / d3
    l4_3 = (p3_4 - l4_0 * l3_0 * d0 - l4_1 * l3_1 * d1 - l4_2 * l3_2 * d2) * r3
    l5_3 = (p3_5 - l5_0 * l3_0 * d0 - l5_1 * l3_1 * d1 - l5_2 * l3_2 * d2) * r3
    d4 = p4_4 - l4_0 * l4_0 * d0 - l4_1 * l4_1 * d1 - l4_2 * l4_2 * d2 - l4_3 * l4_3 * d3
    if not d4 > tol:
        return False
    r4 = 1.0 / d4
    l5_4 = (p4_5 - l5_0 * l4_0 * d0 - l5_1 * l4_1 * d1 - l5_2 * l4_2 * d2 - l5_3 * l4_3 * d3) * r4
    d5 = p5_5 - l5_0 * l5_0 * d0 - l5_1 * l5_1 * d1 - l5_2 * l5_2 * d2 - l5_3 * l5_3 * d3 - l5_4 * l5_4 * d4
    if not d5 > tol:
        return False
    return True


@nb.njit(cache=True, inline="always", error_model="numpy")
def covariance_is_pd_fused(p0_0, p0_1, p0_2, p0_3, p0_4, p0_5, p1_1, p1_2, p1_3, p1_4, p1_5, p2_2, p2_3, p2_4, p2_5, p3_3, p3_4, p3_5, p4_4, p4_5, p5_5):
    """covariance_is_pd of the entries p<i>_<j> (upper triangle, row-major) as numbers, inlined into the fused
    steps (derive/codegen/fused.py), with pivots > 1e-11 · max_i P_ii."""
    tol = 1e-11 * max(p0_0, p1_1, p2_2, p3_3, p4_4, p5_5)
    d0 = p0_0
    if not d0 > tol:
        return False
    r0 = 1.0 / d0
    l1_0 = (p0_1) * r0
    l2_0 = (p0_2) * r0
    l3_0 = (p0_3) * r0
    l4_0 = (p0_4) * r0
    l5_0 = (p0_5) * r0
    d1 = p1_1 - l1_0 * l1_0 * d0
    if not d1 > tol:
        return False
    r1 = 1.0 / d1
    l2_1 = (p1_2 - l2_0 * l1_0 * d0) * r1
    l3_1 = (p1_3 - l3_0 * l1_0 * d0) * r1
    l4_1 = (p1_4 - l4_0 * l1_0 * d0) * r1
    l5_1 = (p1_5 - l5_0 * l1_0 * d0) * r1
    d2 = p2_2 - l2_0 * l2_0 * d0 - l2_1 * l2_1 * d1
    if not d2 > tol:
        return False
    r2 = 1.0 / d2
    l3_2 = (p2_3 - l3_0 * l2_0 * d0 - l3_1 * l2_1 * d1) * r2
    l4_2 = (p2_4 - l4_0 * l2_0 * d0 - l4_1 * l2_1 * d1) * r2
    l5_2 = (p2_5 - l5_0 * l2_0 * d0 - l5_1 * l2_1 * d1) * r2
    d3 = p3_3 - l3_0 * l3_0 * d0 - l3_1 * l3_1 * d1 - l3_2 * l3_2 * d2
    if not d3 > tol:
        return False
    r3 = 1.0 / d3
    l4_3 = (p3_4 - l4_0 * l3_0 * d0 - l4_1 * l3_1 * d1 - l4_2 * l3_2 * d2) * r3
    l5_3 = (p3_5 - l5_0 * l3_0 * d0 - l5_1 * l3_1 * d1 - l5_2 * l3_2 * d2) * r3
    d4 = p4_4 - l4_0 * l4_0 * d0 - l4_1 * l4_1 * d1 - l4_2 * l4_2 * d2 - l4_3 * l4_3 * d3
    if not d4 > tol:
        return False
    r4 = 1.0 / d4
    l5_4 = (p4_5 - l5_0 * l4_0 * d0 - l5_1 * l4_1 * d1 - l5_2 * l4_2 * d2 - l5_3 * l4_3 * d3) * r4
    d5 = p5_5 - l5_0 * l5_0 * d0 - l5_1 * l5_1 * d1 - l5_2 * l5_2 * d2 - l5_3 * l5_3 * d3 - l5_4 * l5_4 * d4
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


@nb.njit(inline="always", fastmath={"contract"}, error_model="numpy")
def covariance_is_pd_lane(W, j):
    """covariance_is_pd of lane j of the new covariance rows of W, without branches (all pivots)."""
    p0_0 = W[2496 + j]
    p0_1 = W[2560 + j]
    p0_2 = W[2624 + j]
    p0_3 = W[2688 + j]
    p0_4 = W[2752 + j]
    p0_5 = W[2816 + j]
    p1_1 = W[2880 + j]
    p1_2 = W[2944 + j]
    p1_3 = W[3008 + j]
    p1_4 = W[3072 + j]
    p1_5 = W[3136 + j]
    p2_2 = W[3200 + j]
    p2_3 = W[3264 + j]
    p2_4 = W[3328 + j]
    p2_5 = W[3392 + j]
    p3_3 = W[3456 + j]
    p3_4 = W[3520 + j]
    p3_5 = W[3584 + j]
    p4_4 = W[3648 + j]
    p4_5 = W[3712 + j]
    p5_5 = W[3776 + j]
    tol = 1e-13 * max(p0_0, p1_1, p2_2, p3_3, p4_4, p5_5)
    d0 = p0_0
    r0 = 1.0 / d0
    l1_0 = (p0_1) * r0
    l2_0 = (p0_2) * r0
    l3_0 = (p0_3) * r0
    l4_0 = (p0_4) * r0
    l5_0 = (p0_5) * r0
    d1 = p1_1 - l1_0 * l1_0 * d0
    r1 = 1.0 / d1
    l2_1 = (p1_2 - l2_0 * l1_0 * d0) * r1
    l3_1 = (p1_3 - l3_0 * l1_0 * d0) * r1
    l4_1 = (p1_4 - l4_0 * l1_0 * d0) * r1
    l5_1 = (p1_5 - l5_0 * l1_0 * d0) * r1
    d2 = p2_2 - l2_0 * l2_0 * d0 - l2_1 * l2_1 * d1
    r2 = 1.0 / d2
    l3_2 = (p2_3 - l3_0 * l2_0 * d0 - l3_1 * l2_1 * d1) * r2
    l4_2 = (p2_4 - l4_0 * l2_0 * d0 - l4_1 * l2_1 * d1) * r2
    l5_2 = (p2_5 - l5_0 * l2_0 * d0 - l5_1 * l2_1 * d1) * r2
    d3 = p3_3 - l3_0 * l3_0 * d0 - l3_1 * l3_1 * d1 - l3_2 * l3_2 * d2
    r3 = 1.0 / d3
    l4_3 = (p3_4 - l4_0 * l3_0 * d0 - l4_1 * l3_1 * d1 - l4_2 * l3_2 * d2) * r3
    l5_3 = (p3_5 - l5_0 * l3_0 * d0 - l5_1 * l3_1 * d1 - l5_2 * l3_2 * d2) * r3
    d4 = p4_4 - l4_0 * l4_0 * d0 - l4_1 * l4_1 * d1 - l4_2 * l4_2 * d2 - l4_3 * l4_3 * d3
    r4 = 1.0 / d4
    l5_4 = (p4_5 - l5_0 * l4_0 * d0 - l5_1 * l4_1 * d1 - l5_2 * l4_2 * d2 - l5_3 * l4_3 * d3) * r4
    d5 = p5_5 - l5_0 * l5_0 * d0 - l5_1 * l5_1 * d1 - l5_2 * l5_2 * d2 - l5_3 * l5_3 * d3 - l5_4 * l5_4 * d4
    return (d0 > tol) & (d1 > tol) & (d2 > tol) & (d3 > tol) & (d4 > tol) & (d5 > tol)


@nb.njit(inline="always", fastmath={"contract"}, error_model="numpy")
def physical_lane(W, j, out, b, k):
    """Physical [x, y, theta, vx, vy, omega] from the internal state, written into ``out`` (no allocation).
    """
    x = W[1920 + j]
    y = W[1984 + j]
    c_theta = W[2048 + j]
    s_theta = W[2112 + j]
    v_x = W[2176 + j]
    v_y = W[2240 + j]
    omega = W[2304 + j]
    out[b, k, 0] = x
    out[b, k, 1] = y
    out[b, k, 2] = wrap_v(atan2_v(s_theta, c_theta))
    out[b, k, 3] = v_x
    out[b, k, 4] = v_y
    out[b, k, 5] = omega


@nb.njit(cache=True)
def propagate(s, dt, n0, n1, n2):
    """Exact motion X ← X exp([Ω(X) + G n]^∧) (eq:model) for one noise sample n, in place.
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
    _a0 = dt*n2
    _sin__a0 = math.sin(_a0)
    _cos__a0 = math.cos(_a0)
    _sinc__a0, _cosc__a0, _sinc2__a0, _cosc2__a0 = sinc_family(_a0, _sin__a0, _cos__a0)
    _a1 = (dt*dt)*n2/2.0 + dt*omega
    _sin__a1 = math.sin(_a1)
    _cos__a1 = math.cos(_a1)
    _sinc__a1, _cosc__a1, _sinc2__a1, _cosc2__a1 = sinc_family(_a1, _sin__a1, _cos__a1)
    _t0 = (dt*dt)/2.0
    _t1 = _t0*n1 + dt*v_y
    _t2 = _t0*n0 + dt*v_x
    _t3 = -(_cosc__a1*_t1) + _sinc__a1*_t2
    _t4 = _cosc__a1*_t2 + _sinc__a1*_t1
    _t5 = dt*n1
    _t6 = -(_cosc__a0*_t5) + _sinc__a0*dt*n0
    _t7 = _cosc__a0*dt*n0 + _sinc__a0*_t5
    _t8 = _cos__a0*s_omega + _sin__a0*c_omega
    _t9 = _cos__a0*c_omega - _sin__a0*s_omega
    xn00 = _t3*c_theta - _t4*s_theta + x
    xn01 = _t3*s_theta + _t4*c_theta + y
    xn02 = _cos__a1*c_theta - _sin__a1*s_theta
    xn03 = _cos__a1*s_theta + _sin__a1*c_theta
    xn04 = _t6*c_omega - _t7*s_omega + v_x
    xn05 = _t6*s_omega + _t7*c_omega + v_y
    xn06 = math.atan2(_t8, _t9)
    xn07 = _t9
    xn08 = _t8
    s[0] = xn00
    s[1] = xn01
    s[2] = xn02
    s[3] = xn03
    s[4] = xn04
    s[5] = xn05
    s[6] = xn06
    s[7] = xn07
    s[8] = xn08


@nb.njit(cache=True)
def position_into(s, out):
    """The position (the first two physical coordinates) of the internal state into ``out`` (2,).
    """
    x = s[0]
    y = s[1]
    out[0] = x
    out[1] = y


@nb.njit(cache=True, parallel=True)
def simulate_batch(x0, dts, noise, out_x):
    """Simulate the motion model X_{k+1} = X_k exp([Ω(X_k) + G n_k]^) for B trajectories (prange).

    x0 (B, 6) physical initial states; dts (B, K) step lengths; noise (B, K, 3) samples of n (already
    scaled by their stds); out_x (B, K + 1, 6) receives the physical states, out_x[:, 0] = x0.
    """
    B = x0.shape[0]
    K = dts.shape[1]
    for b in nb.prange(B):
        s = state_from_physical(x0[b])
        physical_into(s, out_x[b, 0])
        for k in range(K):
            propagate(s, dts[b, k], noise[b, k, 0], noise[b, k, 1], noise[b, k, 2])
            physical_into(s, out_x[b, k + 1])


@nb.njit(cache=True, nogil=True)
def states_from_physical(x, out):
    """state_from_physical of every row: physical states x (N, 6) into internal states out (N, 9)."""
    for i in range(x.shape[0]):
        state_from_physical_into(x[i], out[i])


@nb.njit(cache=True, nogil=True)  # serial and nogil: threads may run it at once (lgekf.apps.search)
def propagate_rows(x, dts, out_x):
    """The noise-free exact motion of each row: out_x[i] = X_i exp([Ω(X_i)]^) over dts[i] (simulate_batch with
    zero noise, one step per row); x (N, 6) and out_x (N, 6) physical states, dts (N,)."""
    s = np.empty(9)
    for i in range(x.shape[0]):
        state_from_physical_into(x[i], s)
        propagate(s, dts[i], 0.0, 0.0, 0.0)
        physical_into(s, out_x[i])


@nb.njit(cache=True, nogil=True)  # serial and nogil: threads may run it at once (lgekf.apps.search)
def propagate_positions(x, dts, out_xy):
    """The position (the first d physical coordinates, d the space's dimension) of ``propagate_rows``'s rows, bit for bit, into
    out_xy (N, d): the other coordinates are not converted (the noise search's one-step errors)."""
    s = np.empty(9)
    for i in range(x.shape[0]):
        state_from_physical_into(x[i], s)
        propagate(s, dts[i], 0.0, 0.0, 0.0)
        position_into(s, out_xy[i])


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
def world_velocity_into(x, out):
    """world_velocity of a physical state x written into out (2,) (no allocation).
    """
    theta = x[2]
    v_x = x[3]
    v_y = x[4]
    _sin_theta = math.sin(theta)
    _cos_theta = math.cos(theta)
    out[0] = _cos_theta*v_x - _sin_theta*v_y
    out[1] = _cos_theta*v_y + _sin_theta*v_x


@nb.njit(cache=True, nogil=True)
def world_velocities(X, out):
    """world_velocity of every row of X (N, n) into out (N, 2) (the space's dimension)."""
    for i in range(X.shape[0]):
        world_velocity_into(X[i], out[i])


@nb.njit(cache=True, nogil=True)
def row_speeds(X, rows, out):
    """Speed |world_velocity| of the rows X[rows[i]] of physical states X (N, n) into out (R,): no per-row
    allocation nor gathered copy of X (the divergence monitor's speeds)."""
    v = np.empty(2)
    for i in range(rows.shape[0]):
        world_velocity_into(X[rows[i]], v)
        out[i] = math.hypot(v[0], v[1])


@nb.njit(cache=True)
def common_to_state(c):
    """The model's physical state from the common c = (x, y, θ, v_x, v_y, ω), velocities in the body frame.
    """
    c0 = c[0]
    c1 = c[1]
    c2 = c[2]
    c3 = c[3]
    c4 = c[4]
    c5 = c[5]
    out = np.zeros(6)
    out[0] = c0
    out[1] = c1
    out[2] = c2
    out[3] = c3
    out[4] = c4
    out[5] = c5
    return out


@nb.njit(cache=True)
def common_jacobian(c):
    """J = ∂(filter coordinates ε)/∂c at c: maps a covariance of c to the filter's P (P = J P_c J^T).
    """
    c2 = c[2]
    c5 = c[5]
    out = np.zeros((6, 6))
    _sin_c2 = math.sin(c2)
    _cos_c2 = math.cos(c2)
    _sin_c5 = math.sin(c5)
    _cos_c5 = math.cos(c5)
    out[0, 0] = _cos_c2
    out[0, 1] = _sin_c2
    out[1, 0] = -_sin_c2
    out[1, 1] = _cos_c2
    out[2, 2] = 1.0
    out[3, 3] = _cos_c5
    out[3, 4] = _sin_c5
    out[4, 3] = -_sin_c5
    out[4, 4] = _cos_c5
    out[5, 5] = 1.0
    return out


@nb.njit(cache=True, nogil=True)
def common_to_states(c, out):
    """common_to_state of every row of c (B, 6) into out (B, n) (the two-point initialisation of many objects)."""
    for b in range(c.shape[0]):
        x = common_to_state(c[b])
        for i in range(out.shape[1]):
            out[b, i] = x[i]


@nb.njit(cache=True, nogil=True)
def common_jacobians(c, out):
    """common_jacobian of every row of c (B, 6) into out (B, n, 6)."""
    for b in range(c.shape[0]):
        J = common_jacobian(c[b])
        for i in range(out.shape[1]):
            for j in range(out.shape[2]):
                out[b, i, j] = J[i, j]


@nb.njit(cache=True, nogil=True, error_model="numpy")
def reinit_into(
        t_all, z_all, heading_all, g, a, scale, meas_std, omega_std, heading_std, heading_cap, sideslip, baseline, angles, c, var,
        cj, J, P, x_out, p_out):
    """The re-initialisation at (global) row g of an object starting at row a: the two-point estimate from g and the
    latest row at least ``baseline`` s earlier, the measurement std times ``scale``: physical x_out (1, n) and packed
    p_out (n(n+1)/2,); c, cj (1, n_c), var (n_c,), J (1, n, n_c), P (n, n) scratch (n_c the space's common coordinates)."""
    two_point_into(t_all, z_all, heading_all, reinit_earlier_row(t_all, g, a, baseline), g, meas_std * scale, omega_std, heading_std,
                   heading_cap, sideslip, c[0], var)
    jacobian_point(c[0], var, cj[0])
    common_to_states(c, x_out)
    common_jacobians(cj, J)
    initial_covariance_into(J[0], var, angles, P)
    pack_into(P, p_out)


@nb.njit(cache=True, nogil=True, error_model="numpy")
def speed_std_at(x, p, k, xh, grad):
    """The std of the speed |world_velocity| of row k of physical states x (N, n) with packed covariances p: its
    gradient by central differences (steps 1e-6 max(1, |x_i|)) through ``speed_std_from``; xh (1, n), grad (n,) scratch."""
    n = x.shape[1]
    one = np.zeros(1, np.int64)
    spd = np.empty(1)
    for i in range(n):
        h = 1e-6 * max(1.0, abs(x[k, i]))
        for j in range(n):
            xh[0, j] = x[k, j]
        xh[0, i] = x[k, i] + h
        row_speeds(xh, one, spd)
        up = spd[0]
        xh[0, i] = x[k, i] - h
        row_speeds(xh, one, spd)
        grad[i] = (up - spd[0]) / (2 * h)
    return speed_std_from(grad, p[k], n)


@nb.njit(cache=True, nogil=True, error_model="numpy")
def speed_stds(x, p, out):
    """``speed_std_at`` of every row of x (N, n), p (N, n(n+1)/2) into out (N,)."""
    xh = np.empty((1, x.shape[1]))
    grad = np.empty(x.shape[1])
    for k in range(x.shape[0]):
        out[k] = speed_std_at(x, p, k, xh, grad)


@nb.njit(cache=True, nogil=True, error_model="numpy")
def first_alarm(
        x, p, nis, a, e, limit, window, short, clip, thr, thr_short, n_sigma, over, absurd, bad, sp, rows, xh, grad):
    """The first alarm of rows [a, e) of one object: (row or -1, kind (1 NIS, 2 speed, 3 non-finite), value (the
    window's mean NIS, the speed), first flagged row, limit (of the mean NIS, of the speed)); ``limit`` the object's
    speed limit. over, absurd, bad (N,) bool, sp (N,), rows (N,) int64, xh (1, n), grad (n,): scratch."""
    if e <= a:  # no row
        return -1, 0, 0.0, 0, limit
    R = e - a
    for k in range(R):
        rows[k] = a + k
    row_speeds(x, rows[:R], sp[:R])
    for k in range(a, e):
        fin = finite_row(x, p, k)
        bad[k] = not fin
        ov = fin and sp[k - a] > limit
        over[k] = ov
        absurd[k] = ov and sp[k - a] - n_sigma * speed_std_at(x, p, k, xh, grad) > limit
    g, kind, val, start = scan_segment(nis, absurd, over, bad, a, e, window, short, clip, thr, thr_short)
    if kind == 2:
        val = sp[g - a]
    if kind == 1:
        lim = thr_short / short if g - start + 1 == short else thr / window
    else:
        lim = limit
    return g, kind, val, start, lim


@nb.njit(cache=True)
def tangent_error(s, c):
    """ε = [log_G(μ^-1 X)]^∨: the error of the estimate μ (internal state s) w.r.t. a true common state c,
    in the coordinates of P (for NEES = εᵀ P^-1 ε); angle coordinates wrapped to (-π, π].
    """
    x = s[0]
    y = s[1]
    c_theta = s[2]
    s_theta = s[3]
    v_x = s[4]
    v_y = s[5]
    c_omega = s[7]
    s_omega = s[8]
    c0 = c[0]
    c1 = c[1]
    c2 = c[2]
    c3 = c[3]
    c4 = c[4]
    c5 = c[5]
    out = np.zeros(6)
    _sin_c2 = math.sin(c2)
    _cos_c2 = math.cos(c2)
    _sin_c5 = math.sin(c5)
    _cos_c5 = math.cos(c5)
    _a0 = math.atan2(c_omega*math.sin(c5) - s_omega*math.cos(c5), c_omega*math.cos(c5) + s_omega*math.sin(c5))
    _sin__a0 = math.sin(_a0)
    _cos__a0 = math.cos(_a0)
    _halfcot__a0 = halfcot(_a0, _sin__a0, _cos__a0)
    _a1 = math.atan2(c_theta*math.sin(c2) - s_theta*math.cos(c2), c_theta*math.cos(c2) + s_theta*math.sin(c2))
    _sin__a1 = math.sin(_a1)
    _cos__a1 = math.cos(_a1)
    _halfcot__a1 = halfcot(_a1, _sin__a1, _cos__a1)
    _t0 = c0*c_theta + c1*s_theta - c_theta*x - s_theta*y
    _t1 = -(c0*s_theta) + c1*c_theta - c_theta*y + s_theta*x
    _t2 = math.atan2(-(_cos_c2*s_theta) + _sin_c2*c_theta, _cos_c2*c_theta + _sin_c2*s_theta)
    _t3 = _t2/2.0
    _t4 = c3*c_omega + c4*s_omega - c_omega*v_x - s_omega*v_y
    _t5 = -(c3*s_omega) + c4*c_omega - c_omega*v_y + s_omega*v_x
    _t6 = math.atan2(-(_cos_c5*s_omega) + _sin_c5*c_omega, _cos_c5*c_omega + _sin_c5*s_omega)
    _t7 = _t6/2.0
    out[0] = _halfcot__a1*_t0 + _t1*_t3
    out[1] = _halfcot__a1*_t1 - _t0*_t3
    out[2] = wrap_angle(_t2)
    out[3] = _halfcot__a0*_t4 + _t5*_t7
    out[4] = _halfcot__a0*_t5 - _t4*_t7
    out[5] = _t6
    return out


@nb.njit(cache=True)
def retract(s, eps):
    """μ ← μ·exp([ε]^∧) in place (right perturbation; the update's eq:up_mu for a given ε).
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
    eps0 = eps[0]
    eps1 = eps[1]
    eps2 = eps[2]
    eps3 = eps[3]
    eps4 = eps[4]
    eps5 = eps[5]
    _sin_eps2 = math.sin(eps2)
    _cos_eps2 = math.cos(eps2)
    _sinc_eps2, _cosc_eps2, _sinc2_eps2, _cosc2_eps2 = sinc_family(eps2, _sin_eps2, _cos_eps2)
    _sin_eps5 = math.sin(eps5)
    _cos_eps5 = math.cos(eps5)
    _sinc_eps5, _cosc_eps5, _sinc2_eps5, _cosc2_eps5 = sinc_family(eps5, _sin_eps5, _cos_eps5)
    _t0 = -(_cosc_eps2*eps1) + _sinc_eps2*eps0
    _t1 = _cosc_eps2*eps0 + _sinc_eps2*eps1
    _t2 = -(_cosc_eps5*eps4) + _sinc_eps5*eps3
    _t3 = _cosc_eps5*eps3 + _sinc_eps5*eps4
    _t4 = _cos_eps5*s_omega + _sin_eps5*c_omega
    s[0] = _t0*c_theta - _t1*s_theta + x
    s[1] = _t0*s_theta + _t1*c_theta + y
    s[2] = _cos_eps2*c_theta - _sin_eps2*s_theta
    s[3] = _cos_eps2*s_theta + _sin_eps2*c_theta
    s[4] = _t2*c_omega - _t3*s_omega + v_x
    s[5] = _t2*s_omega + _t3*c_omega + v_y
    s[6] = wrap_angle_sum(eps5 + omega, _t4)
    s[7] = _cos_eps5*c_omega - _sin_eps5*s_omega
    s[8] = _t4


@nb.njit(cache=True)
def between(s, t):
    """[log_G(μ_s^-1 μ_t)]^∨: the tangent ε with μ_t = μ_s·exp(ε) (s ⊖: μ_s, t: μ_t, internal states);
    angle coordinates of a Euclidean model wrapped to (-π, π].
    """
    x = s[0]
    y = s[1]
    c_theta = s[2]
    s_theta = s[3]
    v_x = s[4]
    v_y = s[5]
    c_omega = s[7]
    s_omega = s[8]
    t_x = t[0]
    t_y = t[1]
    t_c_theta = t[2]
    t_s_theta = t[3]
    t_v_x = t[4]
    t_v_y = t[5]
    t_c_omega = t[7]
    t_s_omega = t[8]
    out = np.zeros(6)
    _a0 = math.atan2(c_omega*t_s_omega - s_omega*t_c_omega, c_omega*t_c_omega + s_omega*t_s_omega)
    _sin__a0 = math.sin(_a0)
    _cos__a0 = math.cos(_a0)
    _halfcot__a0 = halfcot(_a0, _sin__a0, _cos__a0)
    _a1 = math.atan2(c_theta*t_s_theta - s_theta*t_c_theta, c_theta*t_c_theta + s_theta*t_s_theta)
    _sin__a1 = math.sin(_a1)
    _cos__a1 = math.cos(_a1)
    _halfcot__a1 = halfcot(_a1, _sin__a1, _cos__a1)
    _t0 = c_theta*t_x - c_theta*x + s_theta*t_y - s_theta*y
    _t1 = c_theta*t_y - c_theta*y - s_theta*t_x + s_theta*x
    _t2 = _a1/2.0
    _t3 = c_omega*t_v_x - c_omega*v_x + s_omega*t_v_y - s_omega*v_y
    _t4 = c_omega*t_v_y - c_omega*v_y - s_omega*t_v_x + s_omega*v_x
    _t5 = _a0/2.0
    out[0] = _halfcot__a1*_t0 + _t1*_t2
    out[1] = _halfcot__a1*_t1 - _t0*_t2
    out[2] = _a1
    out[3] = _halfcot__a0*_t3 + _t4*_t5
    out[4] = _halfcot__a0*_t4 - _t3*_t5
    out[5] = _a0
    return out


@nb.njit(cache=True)
def right_jacobian(eps):
    """Φ_G(ε) of the whole group (block-diagonal over its factors, I for Rⁿ);
    log(exp(-ε) exp(ε + δ)) ≈ Φ_G(ε) δ.
    """
    eps0 = eps[0]
    eps1 = eps[1]
    eps2 = eps[2]
    eps3 = eps[3]
    eps4 = eps[4]
    eps5 = eps[5]
    out = np.zeros((6, 6))
    _sin_eps2 = math.sin(eps2)
    _cos_eps2 = math.cos(eps2)
    _sinc_eps2, _cosc_eps2, _sinc2_eps2, _cosc2_eps2 = sinc_family(eps2, _sin_eps2, _cos_eps2)
    _sin_eps5 = math.sin(eps5)
    _cos_eps5 = math.cos(eps5)
    _sinc_eps5, _cosc_eps5, _sinc2_eps5, _cosc2_eps5 = sinc_family(eps5, _sin_eps5, _cos_eps5)
    out[0, 0] = _sinc_eps2
    out[0, 1] = _cosc_eps2
    out[0, 2] = -(_cosc2_eps2*eps1) + _sinc2_eps2*eps0
    out[1, 0] = -_cosc_eps2
    out[1, 1] = _sinc_eps2
    out[1, 2] = _cosc2_eps2*eps0 + _sinc2_eps2*eps1
    out[2, 2] = 1.0
    out[3, 3] = _sinc_eps5
    out[3, 4] = _cosc_eps5
    out[3, 5] = -(_cosc2_eps5*eps4) + _sinc2_eps5*eps3
    out[4, 3] = -_cosc_eps5
    out[4, 4] = _sinc_eps5
    out[4, 5] = _cosc2_eps5*eps3 + _sinc2_eps5*eps4
    out[5, 5] = 1.0
    return out


@nb.njit(cache=True)
def right_jacobian_inv(eps):
    """Φ_G(ε)^-1 of the whole group.
    """
    eps0 = eps[0]
    eps1 = eps[1]
    eps2 = eps[2]
    eps3 = eps[3]
    eps4 = eps[4]
    eps5 = eps[5]
    out = np.zeros((6, 6))
    _sin_eps2 = math.sin(eps2)
    _cos_eps2 = math.cos(eps2)
    _halfcot_eps2 = halfcot(eps2, _sin_eps2, _cos_eps2)
    _halfcot1_eps2 = halfcot1(eps2, _sin_eps2, _cos_eps2)
    _sin_eps5 = math.sin(eps5)
    _cos_eps5 = math.cos(eps5)
    _halfcot_eps5 = halfcot(eps5, _sin_eps5, _cos_eps5)
    _halfcot1_eps5 = halfcot1(eps5, _sin_eps5, _cos_eps5)
    _t0 = eps2/2.0
    _t1 = eps5/2.0
    out[0, 0] = _halfcot_eps2
    out[0, 1] = -_t0
    out[0, 2] = _halfcot1_eps2*eps0 + eps1/2.0
    out[1, 0] = _t0
    out[1, 1] = _halfcot_eps2
    out[1, 2] = _halfcot1_eps2*eps1 - eps0/2.0
    out[2, 2] = 1.0
    out[3, 3] = _halfcot_eps5
    out[3, 4] = -_t1
    out[3, 5] = _halfcot1_eps5*eps3 + eps4/2.0
    out[4, 3] = _t1
    out[4, 4] = _halfcot_eps5
    out[4, 5] = _halfcot1_eps5*eps4 - eps3/2.0
    out[5, 5] = 1.0
    return out


@nb.njit(cache=True)
def predict_bank(s, p, live, dt, q):
    """The fused prediction (eq:pred_mu, eq:pred_cov) of every live track (rows of s and p) by dt, in place;
    q (3,) process-noise stds."""
    for i in range(s.shape[0]):
        if live[i]:
            predict(s[i], p[i], dt, q[0], q[1], q[2])


@nb.njit(cache=True)
def retract_bank(s, live, eps):
    """μ_i ← μ_i·exp([ε_i]^∧) for every live track (eq:up_mu with the given corrections eps (N, 6))."""
    for i in range(s.shape[0]):
        if live[i]:
            retract(s[i], eps[i])


@nb.njit(cache=True)
def right_jacobian_bank(live, eps, out):
    """Φ_G(ε_i) (eq:up_P) of every live track's correction eps (N, 6) into out (N, 6, 6)."""
    for i in range(eps.shape[0]):
        if live[i]:
            f = right_jacobian(eps[i])
            for a in range(6):
                for b in range(6):
                    out[i, a, b] = f[a, b]


@nb.njit(cache=True)
def innovation_logdet_pose(s, p, r_x, r_y, r_theta):
    """log det S, S = ℋ P ℋᵀ + R (eq:K) for a pose measurement at the predicted state (s, p),
    noise stds (r_x, r_y, r_theta): the log-determinant term of the innovation log-likelihood.
    """
    p00 = p[0]
    p01 = p[1]
    p02 = p[2]
    p11 = p[6]
    p12 = p[7]
    p22 = p[11]
    S00 = p00 + r_x*r_x
    S11 = p11 + r_y*r_y
    S22 = p22 + r_theta*r_theta
    detS = S00*S11*S22 - S00*(p12*p12) - S11*(p02*p02) - S22*(p01*p01) + 2.0*p01*p02*p12
    return math.log(detS)


@nb.njit(cache=True, fastmath=FASTMATH, error_model="numpy")
def step_store_pose(s, p, dt, sigma_x, sigma_y, sigma_omega, z_x, z_y, z_theta, r_x, r_y, r_theta, sq, pq):
    """step_try_pose that also writes the predicted internal state into sq and the predicted packed covariance
    (after the angle-variance cap) into pq, and returns (NIS, log det S) (derive/codegen/smooth_step.py); a NIS
    of -1 means the caller must run update_pose (derive/codegen/fused.py).
    (eq:pred_mu, eq:pred_cov, angle-variance cap, eq:K, eq:up_mu, eq:up_P) in one kernel; returns the NIS.
    Covariance as P − βKℋP; a step whose result fails the LDLᵀ test (covariance_is_pd_fused) leaves the
    prediction in s, p and returns -1.0: the caller then runs update_pose (Joseph form;
    derive/codegen/fused.py).
    legend: cc = 𝒞 (eq:C), f = F = Ad(exp(−Ω)) + Φ(Ω)𝒞 (eq:pred_cov), g = Φ(Ω)G, hh = ℋ (eq:calH), hp = ℋP, inn = [log_G'(h(μ)⁻¹Z)]^∨, S = ℋPℋᵀ + R, Si = S⁻¹, k = K (eq:K), nk = Kν, alpha = gain damping, nu = ν, phi = Φ(ν) (eq:up_P), a = I − αKℋ, b = aP, beta = α(2 − α), kb = βK, pj = Joseph-form P (= P − βKℋP), cp = Φ(ν)·pj, mu/e = new mean
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
    _t0 = c_omega*dt
    _t1 = dt*s_omega
    cc03 = _t0
    cc04 = -_t1
    cc13 = _t1
    cc14 = _t0
    _a0 = dt*omega
    _sin__a0 = math.sin(_a0)
    _cos__a0 = math.cos(_a0)
    _sinc__a0, _cosc__a0, _sinc2__a0, _cosc2__a0 = sinc_family(_a0, _sin__a0, _cos__a0)
    _t2 = dt*v_x
    _t3 = _cosc__a0*_t2
    _t4 = dt*v_y
    _t5 = _sinc__a0*_t4
    _t6 = -(_cosc2__a0*_t4) + _sinc2__a0*dt*v_x
    _t7 = _cosc__a0*_t4
    _t8 = _cosc2__a0*_t2 + _sinc2__a0*_t4
    _t9 = (dt*dt)/2.0
    _t10 = _sinc__a0*_t9
    _t11 = _cosc__a0*_t9
    _t12 = _sinc__a0*dt*v_x - _t7
    _t13 = _t3 + _t5
    f00 = _cos__a0
    f01 = _sin__a0
    f02 = _t3 - _t5
    f03 = _cosc__a0*cc13 + _sinc__a0*cc03
    f04 = _cosc__a0*cc14 + _sinc__a0*cc04
    f05 = _t6*dt
    f10 = -_sin__a0
    f11 = _cos__a0
    f12 = _sinc__a0*_t2 + _t7
    f13 = -(_cosc__a0*cc03) + _sinc__a0*cc13
    f14 = -(_cosc__a0*cc04) + _sinc__a0*cc14
    f15 = _t8*dt
    g00 = _t10
    g01 = _t11
    g02 = _t6*_t9
    g10 = -_t11
    g11 = _t10
    g12 = _t8*_t9
    g22 = _t9
    e00 = _t12*c_theta - _t13*s_theta + x
    e01 = _t12*s_theta + _t13*c_theta + y
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
    _t14 = sigma_x*sigma_x
    _t15 = sigma_y*sigma_y
    _t16 = sigma_omega*sigma_omega
    _t17 = _t14*g00
    _t18 = _t15*g01
    _t19 = _t16*g02
    _t20 = _t16*g12
    _t21 = dt*dt
    pp00 = _t14*(g00*g00) + _t15*(g01*g01) + _t16*(g02*g02) + f00*m00 + f01*m01 + f02*m02 + f03*m03 + f04*m04 + f05*m05
    pp01 = _t17*g10 + _t18*g11 + _t19*g12 + f10*m00 + f11*m01 + f12*m02 + f13*m03 + f14*m04 + f15*m05
    pp02 = _t19*g22 + dt*m05 + m02
    pp03 = _t17*dt + m03
    pp04 = _t18*dt + m04
    pp05 = _t19*dt + m05
    pp11 = _t14*(g10*g10) + _t15*(g11*g11) + _t16*(g12*g12) + f10*m10 + f11*m11 + f12*m12 + f13*m13 + f14*m14 + f15*m15
    pp12 = _t20*g22 + dt*m15 + m12
    pp13 = _t14*dt*g10 + m13
    pp14 = _t15*dt*g11 + m14
    pp15 = _t20*dt + m15
    pp22 = _t16*(g22*g22) + dt*m25 + m22
    pp23 = m23
    pp24 = m24
    pp25 = _t16*dt*g22 + m25
    pp33 = _t14*_t21 + p33
    pp34 = p34
    pp35 = p35
    pp44 = _t15*_t21 + p44
    pp45 = p45
    pp55 = _t16*_t21 + p55
    x_p = e00
    y_p = e01
    c_theta_p = e02
    s_theta_p = e03
    if pp22 > math.pi * math.pi:
        _cap = math.pi / math.sqrt(pp22)
        pp02 = pp02 * _cap
        pp12 = pp12 * _cap
        pp23 = pp23 * _cap
        pp24 = pp24 * _cap
        pp25 = pp25 * _cap
        pp22 = math.pi * math.pi
    if pp55 > math.pi * math.pi:
        _cap = math.pi / math.sqrt(pp55)
        pp05 = pp05 * _cap
        pp15 = pp15 * _cap
        pp25 = pp25 * _cap
        pp35 = pp35 * _cap
        pp45 = pp45 * _cap
        pp55 = math.pi * math.pi
    _sin_z_theta = math.sin(z_theta)
    _cos_z_theta = math.cos(z_theta)
    _a1 = math.atan2(c_theta_p*math.sin(z_theta) - s_theta_p*math.cos(z_theta), c_theta_p*math.cos(z_theta) + s_theta_p*math.sin(z_theta))
    _sin__a1 = math.sin(_a1)
    _cos__a1 = math.cos(_a1)
    _halfcot__a1 = halfcot(_a1, _sin__a1, _cos__a1)
    _t22 = -(c_theta_p*x_p) + c_theta_p*z_x - s_theta_p*y_p + s_theta_p*z_y
    _t23 = -(c_theta_p*y_p) + c_theta_p*z_y + s_theta_p*x_p - s_theta_p*z_x
    _t24 = math.atan2(-(_cos_z_theta*s_theta_p) + _sin_z_theta*c_theta_p, _cos_z_theta*c_theta_p + _sin_z_theta*s_theta_p)
    _t25 = _t24/2.0
    inn00 = _halfcot__a1*_t22 + _t23*_t25
    inn10 = _halfcot__a1*_t23 - _t22*_t25
    inn20 = _t24
    S00 = pp00 + r_x*r_x
    S11 = pp11 + r_y*r_y
    S22 = pp22 + r_theta*r_theta
    rdet = 1.0/(S00*S11*S22 - S00*(pp12*pp12) - S11*(pp02*pp02) - S22*(pp01*pp01) + 2.0*pp01*pp02*pp12)
    Si00 = rdet*(S11*S22 - pp12*pp12)
    Si01 = rdet*(-(S22*pp01) + pp02*pp12)
    Si02 = rdet*(-(S11*pp02) + pp01*pp12)
    Si11 = rdet*(S00*S22 - pp02*pp02)
    Si12 = rdet*(-(S00*pp12) + pp01*pp02)
    Si22 = rdet*(S00*S11 - pp01*pp01)
    _t26 = Si01*pp01
    _t27 = Si02*pp02
    _t28 = Si12*pp12
    _t29 = 2.0*inn00
    k00 = Si00*pp00 + _t26 + _t27
    k01 = Si01*pp00 + Si11*pp01 + Si12*pp02
    k02 = Si02*pp00 + Si12*pp01 + Si22*pp02
    k10 = Si00*pp01 + Si01*pp11 + Si02*pp12
    k11 = Si11*pp11 + _t26 + _t28
    k12 = Si02*pp01 + Si12*pp11 + Si22*pp12
    k20 = Si00*pp02 + Si01*pp12 + Si02*pp22
    k21 = Si01*pp02 + Si11*pp12 + Si12*pp22
    k22 = Si22*pp22 + _t27 + _t28
    k30 = Si00*pp03 + Si01*pp13 + Si02*pp23
    k31 = Si01*pp03 + Si11*pp13 + Si12*pp23
    k32 = Si02*pp03 + Si12*pp13 + Si22*pp23
    k40 = Si00*pp04 + Si01*pp14 + Si02*pp24
    k41 = Si01*pp04 + Si11*pp14 + Si12*pp24
    k42 = Si02*pp04 + Si12*pp14 + Si22*pp24
    k50 = Si00*pp05 + Si01*pp15 + Si02*pp25
    k51 = Si01*pp05 + Si11*pp15 + Si12*pp25
    k52 = Si02*pp05 + Si12*pp15 + Si22*pp25
    nis = Si00*(inn00*inn00) + Si01*_t29*inn10 + Si02*_t29*inn20 + Si11*(inn10*inn10) + 2.0*Si12*inn10*inn20 + Si22*(inn20*inn20)
    nk0 = inn00*k00 + inn10*k01 + inn20*k02
    nk1 = inn00*k10 + inn10*k11 + inn20*k12
    nk2 = inn00*k20 + inn10*k21 + inn20*k22
    nk3 = inn00*k30 + inn10*k31 + inn20*k32
    nk4 = inn00*k40 + inn10*k41 + inn20*k42
    nk5 = inn00*k50 + inn10*k51 + inn20*k52
    alpha = gain_damping(nk2, nk5)
    nu0 = alpha*nk0
    nu1 = alpha*nk1
    nu2 = alpha*nk2
    nu3 = alpha*nk3
    nu4 = alpha*nk4
    nu5 = alpha*nk5
    _sin_nu2 = math.sin(nu2)
    _cos_nu2 = math.cos(nu2)
    _sinc_nu2, _cosc_nu2, _sinc2_nu2, _cosc2_nu2 = sinc_family(nu2, _sin_nu2, _cos_nu2)
    _sin_nu5 = math.sin(nu5)
    _cos_nu5 = math.cos(nu5)
    _sinc_nu5, _cosc_nu5, _sinc2_nu5, _cosc2_nu5 = sinc_family(nu5, _sin_nu5, _cos_nu5)
    _t30 = -(_cosc_nu2*nu1) + _sinc_nu2*nu0
    _t31 = _cosc_nu2*nu0 + _sinc_nu2*nu1
    _t32 = -(_cosc_nu5*nu4) + _sinc_nu5*nu3
    _t33 = _cosc_nu5*nu3 + _sinc_nu5*nu4
    _t34 = _cos_nu5*s_omega + _sin_nu5*c_omega
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
    mu00 = _t30*c_theta_p - _t31*s_theta_p + x_p
    mu01 = _t30*s_theta_p + _t31*c_theta_p + y_p
    mu02 = _cos_nu2*c_theta_p - _sin_nu2*s_theta_p
    mu03 = _cos_nu2*s_theta_p + _sin_nu2*c_theta_p
    mu04 = _t32*c_omega - _t33*s_omega + v_x
    mu05 = _t32*s_omega + _t33*c_omega + v_y
    mu06 = wrap_angle_sum(nu5 + omega, _t34)
    mu07 = _cos_nu5*c_omega - _sin_nu5*s_omega
    mu08 = _t34
    beta = alpha*(2.0 - alpha)
    kb00 = beta*k00
    kb01 = beta*k01
    kb02 = beta*k02
    kb10 = beta*k10
    kb11 = beta*k11
    kb12 = beta*k12
    kb20 = beta*k20
    kb21 = beta*k21
    kb22 = beta*k22
    kb30 = beta*k30
    kb31 = beta*k31
    kb32 = beta*k32
    kb40 = beta*k40
    kb41 = beta*k41
    kb42 = beta*k42
    kb50 = beta*k50
    kb51 = beta*k51
    kb52 = beta*k52
    pj00 = -(kb00*pp00) - kb01*pp01 - kb02*pp02 + pp00
    pj01 = -(kb00*pp01) - kb01*pp11 - kb02*pp12 + pp01
    pj02 = -(kb00*pp02) - kb01*pp12 - kb02*pp22 + pp02
    pj03 = -(kb00*pp03) - kb01*pp13 - kb02*pp23 + pp03
    pj04 = -(kb00*pp04) - kb01*pp14 - kb02*pp24 + pp04
    pj05 = -(kb00*pp05) - kb01*pp15 - kb02*pp25 + pp05
    pj11 = -(kb10*pp01) - kb11*pp11 - kb12*pp12 + pp11
    pj12 = -(kb10*pp02) - kb11*pp12 - kb12*pp22 + pp12
    pj13 = -(kb10*pp03) - kb11*pp13 - kb12*pp23 + pp13
    pj14 = -(kb10*pp04) - kb11*pp14 - kb12*pp24 + pp14
    pj15 = -(kb10*pp05) - kb11*pp15 - kb12*pp25 + pp15
    pj22 = -(kb20*pp02) - kb21*pp12 - kb22*pp22 + pp22
    pj23 = -(kb20*pp03) - kb21*pp13 - kb22*pp23 + pp23
    pj24 = -(kb20*pp04) - kb21*pp14 - kb22*pp24 + pp24
    pj25 = -(kb20*pp05) - kb21*pp15 - kb22*pp25 + pp25
    pj33 = -(kb30*pp03) - kb31*pp13 - kb32*pp23 + pp33
    pj34 = -(kb30*pp04) - kb31*pp14 - kb32*pp24 + pp34
    pj35 = -(kb30*pp05) - kb31*pp15 - kb32*pp25 + pp35
    pj44 = -(kb40*pp04) - kb41*pp14 - kb42*pp24 + pp44
    pj45 = -(kb40*pp05) - kb41*pp15 - kb42*pp25 + pp45
    pj55 = -(kb50*pp05) - kb51*pp15 - kb52*pp25 + pp55
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
    sq[0] = x_p
    sq[1] = y_p
    sq[2] = c_theta_p
    sq[3] = s_theta_p
    sq[4] = v_x
    sq[5] = v_y
    sq[6] = omega
    sq[7] = c_omega
    sq[8] = s_omega
    pq[0] = pp00
    pq[1] = pp01
    pq[2] = pp02
    pq[3] = pp03
    pq[4] = pp04
    pq[5] = pp05
    pq[6] = pp11
    pq[7] = pp12
    pq[8] = pp13
    pq[9] = pp14
    pq[10] = pp15
    pq[11] = pp22
    pq[12] = pp23
    pq[13] = pp24
    pq[14] = pp25
    pq[15] = pp33
    pq[16] = pp34
    pq[17] = pp35
    pq[18] = pp44
    pq[19] = pp45
    pq[20] = pp55
    out_p0 = cp00*phi00 + cp01*phi01 + cp02*phi02
    out_p1 = cp00*phi10 + cp01*phi11 + cp02*phi12
    out_p2 = cp02
    out_p3 = cp03*phi33 + cp04*phi34 + cp05*phi35
    out_p4 = cp03*phi43 + cp04*phi44 + cp05*phi45
    out_p5 = cp05
    out_p6 = cp10*phi10 + cp11*phi11 + cp12*phi12
    out_p7 = cp12
    out_p8 = cp13*phi33 + cp14*phi34 + cp15*phi35
    out_p9 = cp13*phi43 + cp14*phi44 + cp15*phi45
    out_p10 = cp15
    out_p11 = pj22
    out_p12 = phi33*pj23 + phi34*pj24 + phi35*pj25
    out_p13 = phi43*pj23 + phi44*pj24 + phi45*pj25
    out_p14 = pj25
    out_p15 = cp33*phi33 + cp34*phi34 + cp35*phi35
    out_p16 = cp33*phi43 + cp34*phi44 + cp35*phi45
    out_p17 = cp35
    out_p18 = cp43*phi43 + cp44*phi44 + cp45*phi45
    out_p19 = cp45
    out_p20 = pj55
    out_s0 = mu00
    out_s1 = mu01
    out_s2 = mu02
    out_s3 = mu03
    out_s4 = mu04
    out_s5 = mu05
    out_s6 = mu06
    out_s7 = mu07
    out_s8 = mu08
    if not covariance_is_pd_fused(out_p0, out_p1, out_p2, out_p3, out_p4, out_p5, out_p6, out_p7, out_p8, out_p9, out_p10, out_p11, out_p12, out_p13, out_p14, out_p15, out_p16, out_p17, out_p18, out_p19, out_p20):
        out_p0 = pp00
        out_p1 = pp01
        out_p2 = pp02
        out_p3 = pp03
        out_p4 = pp04
        out_p5 = pp05
        out_p6 = pp11
        out_p7 = pp12
        out_p8 = pp13
        out_p9 = pp14
        out_p10 = pp15
        out_p11 = pp22
        out_p12 = pp23
        out_p13 = pp24
        out_p14 = pp25
        out_p15 = pp33
        out_p16 = pp34
        out_p17 = pp35
        out_p18 = pp44
        out_p19 = pp45
        out_p20 = pp55
        out_s0 = x_p
        out_s1 = y_p
        out_s2 = c_theta_p
        out_s3 = s_theta_p
        out_s4 = v_x
        out_s5 = v_y
        out_s6 = omega
        out_s7 = c_omega
        out_s8 = s_omega
        nis = -1.0
    p[0] = out_p0
    p[1] = out_p1
    p[2] = out_p2
    p[3] = out_p3
    p[4] = out_p4
    p[5] = out_p5
    p[6] = out_p6
    p[7] = out_p7
    p[8] = out_p8
    p[9] = out_p9
    p[10] = out_p10
    p[11] = out_p11
    p[12] = out_p12
    p[13] = out_p13
    p[14] = out_p14
    p[15] = out_p15
    p[16] = out_p16
    p[17] = out_p17
    p[18] = out_p18
    p[19] = out_p19
    p[20] = out_p20
    s[0] = out_s0
    s[1] = out_s1
    s[2] = out_s2
    s[3] = out_s3
    s[4] = out_s4
    s[5] = out_s5
    s[6] = out_s6
    s[7] = out_s7
    s[8] = out_s8
    return nis, -math.log(rdet)


@nb.njit(inline="always", fastmath={"contract"}, error_model="numpy")
def lane_store_pose(W, j, sigma_x, sigma_y, sigma_omega, r_x, r_y, r_theta):
    """step_store_pose on lane j of the work array W (rows: derive/codegen/smooth_step.py), without branches (SIMD); 1/det S in a row of W.
    """
    x = W[0 + j]
    y = W[64 + j]
    c_theta = W[128 + j]
    s_theta = W[192 + j]
    v_x = W[256 + j]
    v_y = W[320 + j]
    omega = W[384 + j]
    c_omega = W[448 + j]
    s_omega = W[512 + j]
    p00 = W[576 + j]
    p01 = W[640 + j]
    p02 = W[704 + j]
    p03 = W[768 + j]
    p04 = W[832 + j]
    p05 = W[896 + j]
    p11 = W[960 + j]
    p12 = W[1024 + j]
    p13 = W[1088 + j]
    p14 = W[1152 + j]
    p15 = W[1216 + j]
    p22 = W[1280 + j]
    p23 = W[1344 + j]
    p24 = W[1408 + j]
    p25 = W[1472 + j]
    p33 = W[1536 + j]
    p34 = W[1600 + j]
    p35 = W[1664 + j]
    p44 = W[1728 + j]
    p45 = W[1792 + j]
    p55 = W[1856 + j]
    dt = W[3840 + j]
    z_x = W[4032 + j]
    z_y = W[4096 + j]
    z_theta = W[4160 + j]
    _t0 = c_omega*dt
    _t1 = dt*s_omega
    cc03 = _t0
    cc04 = -_t1
    cc13 = _t1
    cc14 = _t0
    _a0 = dt*omega
    _sin__a0 = sin_v(_a0)
    _cos__a0 = cos_v(_a0)
    _sinc__a0, _cosc__a0, _sinc2__a0, _cosc2__a0 = sinc_family(_a0, _sin__a0, _cos__a0)
    _t2 = dt*v_x
    _t3 = _cosc__a0*_t2
    _t4 = dt*v_y
    _t5 = _sinc__a0*_t4
    _t6 = -(_cosc2__a0*_t4) + _sinc2__a0*dt*v_x
    _t7 = _cosc__a0*_t4
    _t8 = _cosc2__a0*_t2 + _sinc2__a0*_t4
    _t9 = (dt*dt)/2.0
    _t10 = _sinc__a0*_t9
    _t11 = _cosc__a0*_t9
    _t12 = _sinc__a0*dt*v_x - _t7
    _t13 = _t3 + _t5
    f00 = _cos__a0
    f01 = _sin__a0
    f02 = _t3 - _t5
    f03 = _cosc__a0*cc13 + _sinc__a0*cc03
    f04 = _cosc__a0*cc14 + _sinc__a0*cc04
    f05 = _t6*dt
    f10 = -_sin__a0
    f11 = _cos__a0
    f12 = _sinc__a0*_t2 + _t7
    f13 = -(_cosc__a0*cc03) + _sinc__a0*cc13
    f14 = -(_cosc__a0*cc04) + _sinc__a0*cc14
    f15 = _t8*dt
    g00 = _t10
    g01 = _t11
    g02 = _t6*_t9
    g10 = -_t11
    g11 = _t10
    g12 = _t8*_t9
    g22 = _t9
    e00 = _t12*c_theta - _t13*s_theta + x
    e01 = _t12*s_theta + _t13*c_theta + y
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
    _t14 = sigma_x*sigma_x
    _t15 = sigma_y*sigma_y
    _t16 = sigma_omega*sigma_omega
    _t17 = _t14*g00
    _t18 = _t15*g01
    _t19 = _t16*g02
    _t20 = _t16*g12
    _t21 = dt*dt
    pp00 = _t14*(g00*g00) + _t15*(g01*g01) + _t16*(g02*g02) + f00*m00 + f01*m01 + f02*m02 + f03*m03 + f04*m04 + f05*m05
    pp01 = _t17*g10 + _t18*g11 + _t19*g12 + f10*m00 + f11*m01 + f12*m02 + f13*m03 + f14*m04 + f15*m05
    pp02 = _t19*g22 + dt*m05 + m02
    pp03 = _t17*dt + m03
    pp04 = _t18*dt + m04
    pp05 = _t19*dt + m05
    pp11 = _t14*(g10*g10) + _t15*(g11*g11) + _t16*(g12*g12) + f10*m10 + f11*m11 + f12*m12 + f13*m13 + f14*m14 + f15*m15
    pp12 = _t20*g22 + dt*m15 + m12
    pp13 = _t14*dt*g10 + m13
    pp14 = _t15*dt*g11 + m14
    pp15 = _t20*dt + m15
    pp22 = _t16*(g22*g22) + dt*m25 + m22
    pp23 = m23
    pp24 = m24
    pp25 = _t16*dt*g22 + m25
    pp33 = _t14*_t21 + p33
    pp34 = p34
    pp35 = p35
    pp44 = _t15*_t21 + p44
    pp45 = p45
    pp55 = _t16*_t21 + p55
    x_p = e00
    y_p = e01
    c_theta_p = e02
    s_theta_p = e03
    if pp22 > math.pi * math.pi:
        _cap = math.pi / math.sqrt(pp22)
        pp02 = pp02 * _cap
        pp12 = pp12 * _cap
        pp23 = pp23 * _cap
        pp24 = pp24 * _cap
        pp25 = pp25 * _cap
        pp22 = math.pi * math.pi
    if pp55 > math.pi * math.pi:
        _cap = math.pi / math.sqrt(pp55)
        pp05 = pp05 * _cap
        pp15 = pp15 * _cap
        pp25 = pp25 * _cap
        pp35 = pp35 * _cap
        pp45 = pp45 * _cap
        pp55 = math.pi * math.pi
    _sin_z_theta = sin_v(z_theta)
    _cos_z_theta = cos_v(z_theta)
    _a1 = atan2_v(c_theta_p*sin_v(z_theta) - s_theta_p*cos_v(z_theta), c_theta_p*cos_v(z_theta) + s_theta_p*sin_v(z_theta))
    _sin__a1 = sin_v(_a1)
    _cos__a1 = cos_v(_a1)
    _halfcot__a1 = halfcot_v(_a1, _sin__a1, _cos__a1)
    _t22 = -(c_theta_p*x_p) + c_theta_p*z_x - s_theta_p*y_p + s_theta_p*z_y
    _t23 = -(c_theta_p*y_p) + c_theta_p*z_y + s_theta_p*x_p - s_theta_p*z_x
    _t24 = atan2_v(-(_cos_z_theta*s_theta_p) + _sin_z_theta*c_theta_p, _cos_z_theta*c_theta_p + _sin_z_theta*s_theta_p)
    _t25 = _t24/2.0
    inn00 = _halfcot__a1*_t22 + _t23*_t25
    inn10 = _halfcot__a1*_t23 - _t22*_t25
    inn20 = _t24
    S00 = pp00 + r_x*r_x
    S11 = pp11 + r_y*r_y
    S22 = pp22 + r_theta*r_theta
    rdet = 1.0/(S00*S11*S22 - S00*(pp12*pp12) - S11*(pp02*pp02) - S22*(pp01*pp01) + 2.0*pp01*pp02*pp12)
    Si00 = rdet*(S11*S22 - pp12*pp12)
    Si01 = rdet*(-(S22*pp01) + pp02*pp12)
    Si02 = rdet*(-(S11*pp02) + pp01*pp12)
    Si11 = rdet*(S00*S22 - pp02*pp02)
    Si12 = rdet*(-(S00*pp12) + pp01*pp02)
    Si22 = rdet*(S00*S11 - pp01*pp01)
    _t26 = Si01*pp01
    _t27 = Si02*pp02
    _t28 = Si12*pp12
    _t29 = 2.0*inn00
    k00 = Si00*pp00 + _t26 + _t27
    k01 = Si01*pp00 + Si11*pp01 + Si12*pp02
    k02 = Si02*pp00 + Si12*pp01 + Si22*pp02
    k10 = Si00*pp01 + Si01*pp11 + Si02*pp12
    k11 = Si11*pp11 + _t26 + _t28
    k12 = Si02*pp01 + Si12*pp11 + Si22*pp12
    k20 = Si00*pp02 + Si01*pp12 + Si02*pp22
    k21 = Si01*pp02 + Si11*pp12 + Si12*pp22
    k22 = Si22*pp22 + _t27 + _t28
    k30 = Si00*pp03 + Si01*pp13 + Si02*pp23
    k31 = Si01*pp03 + Si11*pp13 + Si12*pp23
    k32 = Si02*pp03 + Si12*pp13 + Si22*pp23
    k40 = Si00*pp04 + Si01*pp14 + Si02*pp24
    k41 = Si01*pp04 + Si11*pp14 + Si12*pp24
    k42 = Si02*pp04 + Si12*pp14 + Si22*pp24
    k50 = Si00*pp05 + Si01*pp15 + Si02*pp25
    k51 = Si01*pp05 + Si11*pp15 + Si12*pp25
    k52 = Si02*pp05 + Si12*pp15 + Si22*pp25
    nis = Si00*(inn00*inn00) + Si01*_t29*inn10 + Si02*_t29*inn20 + Si11*(inn10*inn10) + 2.0*Si12*inn10*inn20 + Si22*(inn20*inn20)
    nk0 = inn00*k00 + inn10*k01 + inn20*k02
    nk1 = inn00*k10 + inn10*k11 + inn20*k12
    nk2 = inn00*k20 + inn10*k21 + inn20*k22
    nk3 = inn00*k30 + inn10*k31 + inn20*k32
    nk4 = inn00*k40 + inn10*k41 + inn20*k42
    nk5 = inn00*k50 + inn10*k51 + inn20*k52
    alpha = gain_damping_v(nk2, nk5)
    nu0 = alpha*nk0
    nu1 = alpha*nk1
    nu2 = alpha*nk2
    nu3 = alpha*nk3
    nu4 = alpha*nk4
    nu5 = alpha*nk5
    _sin_nu2 = sin_v(nu2)
    _cos_nu2 = cos_v(nu2)
    _sinc_nu2, _cosc_nu2, _sinc2_nu2, _cosc2_nu2 = sinc_family(nu2, _sin_nu2, _cos_nu2)
    _sin_nu5 = sin_v(nu5)
    _cos_nu5 = cos_v(nu5)
    _sinc_nu5, _cosc_nu5, _sinc2_nu5, _cosc2_nu5 = sinc_family(nu5, _sin_nu5, _cos_nu5)
    _t30 = -(_cosc_nu2*nu1) + _sinc_nu2*nu0
    _t31 = _cosc_nu2*nu0 + _sinc_nu2*nu1
    _t32 = -(_cosc_nu5*nu4) + _sinc_nu5*nu3
    _t33 = _cosc_nu5*nu3 + _sinc_nu5*nu4
    _t34 = _cos_nu5*s_omega + _sin_nu5*c_omega
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
    mu00 = _t30*c_theta_p - _t31*s_theta_p + x_p
    mu01 = _t30*s_theta_p + _t31*c_theta_p + y_p
    mu02 = _cos_nu2*c_theta_p - _sin_nu2*s_theta_p
    mu03 = _cos_nu2*s_theta_p + _sin_nu2*c_theta_p
    mu04 = _t32*c_omega - _t33*s_omega + v_x
    mu05 = _t32*s_omega + _t33*c_omega + v_y
    mu06 = wrap_sum_v(nu5 + omega, _t34)
    mu07 = _cos_nu5*c_omega - _sin_nu5*s_omega
    mu08 = _t34
    beta = alpha*(2.0 - alpha)
    kb00 = beta*k00
    kb01 = beta*k01
    kb02 = beta*k02
    kb10 = beta*k10
    kb11 = beta*k11
    kb12 = beta*k12
    kb20 = beta*k20
    kb21 = beta*k21
    kb22 = beta*k22
    kb30 = beta*k30
    kb31 = beta*k31
    kb32 = beta*k32
    kb40 = beta*k40
    kb41 = beta*k41
    kb42 = beta*k42
    kb50 = beta*k50
    kb51 = beta*k51
    kb52 = beta*k52
    pj00 = -(kb00*pp00) - kb01*pp01 - kb02*pp02 + pp00
    pj01 = -(kb00*pp01) - kb01*pp11 - kb02*pp12 + pp01
    pj02 = -(kb00*pp02) - kb01*pp12 - kb02*pp22 + pp02
    pj03 = -(kb00*pp03) - kb01*pp13 - kb02*pp23 + pp03
    pj04 = -(kb00*pp04) - kb01*pp14 - kb02*pp24 + pp04
    pj05 = -(kb00*pp05) - kb01*pp15 - kb02*pp25 + pp05
    pj11 = -(kb10*pp01) - kb11*pp11 - kb12*pp12 + pp11
    pj12 = -(kb10*pp02) - kb11*pp12 - kb12*pp22 + pp12
    pj13 = -(kb10*pp03) - kb11*pp13 - kb12*pp23 + pp13
    pj14 = -(kb10*pp04) - kb11*pp14 - kb12*pp24 + pp14
    pj15 = -(kb10*pp05) - kb11*pp15 - kb12*pp25 + pp15
    pj22 = -(kb20*pp02) - kb21*pp12 - kb22*pp22 + pp22
    pj23 = -(kb20*pp03) - kb21*pp13 - kb22*pp23 + pp23
    pj24 = -(kb20*pp04) - kb21*pp14 - kb22*pp24 + pp24
    pj25 = -(kb20*pp05) - kb21*pp15 - kb22*pp25 + pp25
    pj33 = -(kb30*pp03) - kb31*pp13 - kb32*pp23 + pp33
    pj34 = -(kb30*pp04) - kb31*pp14 - kb32*pp24 + pp34
    pj35 = -(kb30*pp05) - kb31*pp15 - kb32*pp25 + pp35
    pj44 = -(kb40*pp04) - kb41*pp14 - kb42*pp24 + pp44
    pj45 = -(kb40*pp05) - kb41*pp15 - kb42*pp25 + pp45
    pj55 = -(kb50*pp05) - kb51*pp15 - kb52*pp25 + pp55
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
    W[4224 + j] = x_p
    W[4288 + j] = y_p
    W[4352 + j] = c_theta_p
    W[4416 + j] = s_theta_p
    W[4480 + j] = v_x
    W[4544 + j] = v_y
    W[4608 + j] = omega
    W[4672 + j] = c_omega
    W[4736 + j] = s_omega
    W[4800 + j] = pp00
    W[4864 + j] = pp01
    W[4928 + j] = pp02
    W[4992 + j] = pp03
    W[5056 + j] = pp04
    W[5120 + j] = pp05
    W[5184 + j] = pp11
    W[5248 + j] = pp12
    W[5312 + j] = pp13
    W[5376 + j] = pp14
    W[5440 + j] = pp15
    W[5504 + j] = pp22
    W[5568 + j] = pp23
    W[5632 + j] = pp24
    W[5696 + j] = pp25
    W[5760 + j] = pp33
    W[5824 + j] = pp34
    W[5888 + j] = pp35
    W[5952 + j] = pp44
    W[6016 + j] = pp45
    W[6080 + j] = pp55
    W[2496 + j] = cp00*phi00 + cp01*phi01 + cp02*phi02
    W[2560 + j] = cp00*phi10 + cp01*phi11 + cp02*phi12
    W[2624 + j] = cp02
    W[2688 + j] = cp03*phi33 + cp04*phi34 + cp05*phi35
    W[2752 + j] = cp03*phi43 + cp04*phi44 + cp05*phi45
    W[2816 + j] = cp05
    W[2880 + j] = cp10*phi10 + cp11*phi11 + cp12*phi12
    W[2944 + j] = cp12
    W[3008 + j] = cp13*phi33 + cp14*phi34 + cp15*phi35
    W[3072 + j] = cp13*phi43 + cp14*phi44 + cp15*phi45
    W[3136 + j] = cp15
    W[3200 + j] = pj22
    W[3264 + j] = phi33*pj23 + phi34*pj24 + phi35*pj25
    W[3328 + j] = phi43*pj23 + phi44*pj24 + phi45*pj25
    W[3392 + j] = pj25
    W[3456 + j] = cp33*phi33 + cp34*phi34 + cp35*phi35
    W[3520 + j] = cp33*phi43 + cp34*phi44 + cp35*phi45
    W[3584 + j] = cp35
    W[3648 + j] = cp43*phi43 + cp44*phi44 + cp45*phi45
    W[3712 + j] = cp45
    W[3776 + j] = pj55
    W[1920 + j] = mu00
    W[1984 + j] = mu01
    W[2048 + j] = mu02
    W[2112 + j] = mu03
    W[2176 + j] = mu04
    W[2240 + j] = mu05
    W[2304 + j] = mu06
    W[2368 + j] = mu07
    W[2432 + j] = mu08
    W[6144 + j] = rdet
    return nis


@nb.njit(cache=True, parallel=True, fastmath=FASTMATH, error_model="numpy")
def run_batch_store_soa_pose(z, dts, x0, p0, q, r, Qb, Fb, out_nis, out_logdet, out_x):
    """run_batch_store_pose with trajectories in the SIMD lanes (derive/codegen/smooth_step.py), the same results
    with the states stored in blocks: Qb, Fb (nblk, K, 30, 64), nblk = ⌈B / 64⌉, get the predicted /
    posterior internal state and packed covariance of step k of trajectory blk·64 + j in Qb[blk, k, :, j]
    (lanes past B: zeros). As run_batch_soa_pose (prange over blocks, lane_store_pose vectorised over the lanes,
    a lane failing the LDLᵀ test or with a NaN row redone by the scalar predict / update_pose)."""
    B = z.shape[0]
    K = z.shape[1]
    nblk = (B + 64 - 1) // 64
    for blk in nb.prange(nblk):
        lo = blk * 64
        L = min(64, B - lo)
        W = np.zeros(97 * 64)
        s = np.empty(9)
        p = np.empty(21)
        for j in range(L):
            s0 = state_from_physical(x0[lo + j])
            for i in range(9):
                W[(0 + i) * 64 + j] = s0[i]
            for i in range(21):
                W[(9 + i) * 64 + j] = p0[lo + j, i]
        for k in range(K):
            for j in range(L):
                W[60 * 64 + j] = dts[lo + j, k]
                W[63 * 64 + j] = z[lo + j, k, 0]
                W[64 * 64 + j] = z[lo + j, k, 1]
                W[65 * 64 + j] = z[lo + j, k, 2]
            for j in range(L):
                W[61 * 64 + j] = lane_store_pose(W, j, q[0], q[1], q[2], r[0], r[1], r[2])
                good = covariance_is_pd_lane(W, j) & (W[61 * 64 + j] == W[61 * 64 + j])
                W[62 * 64 + j] = 1.0 if good else 0.0
            for j in range(L):
                b = lo + j
                if W[62 * 64 + j] == 0.0:
                    for i in range(9):
                        s[i] = W[(0 + i) * 64 + j]
                    for i in range(21):
                        p[i] = W[(9 + i) * 64 + j]
                    predict(s, p, dts[b, k], q[0], q[1], q[2])
                    for i in range(9):
                        W[(66 + i) * 64 + j] = s[i]
                    for i in range(21):
                        W[(75 + i) * 64 + j] = p[i]
                    if np.isnan(z[b, k, 0]) or np.isnan(z[b, k, 1]) or np.isnan(z[b, k, 2]):
                        W[61 * 64 + j] = np.nan
                        out_logdet[b, k] = np.nan
                    else:
                        out_logdet[b, k] = innovation_logdet_pose(s, p, r[0], r[1], r[2])
                        W[61 * 64 + j] = update_pose(s, p, z[b, k, 0], z[b, k, 1], z[b, k, 2], r[0], r[1], r[2])
                    for i in range(9):
                        W[(30 + i) * 64 + j] = s[i]
                    for i in range(21):
                        W[(39 + i) * 64 + j] = p[i]
                else:
                    out_logdet[b, k] = -math.log(W[96 * 64 + j])
            for j in range(L):
                out_nis[lo + j, k] = W[61 * 64 + j]
                physical_lane(W, j, out_x, lo + j, k)
            for i in range(9 + 21):
                for j in range(64):
                    Qb[blk, k, i, j] = W[(66 + i) * 64 + j]
                    Fb[blk, k, i, j] = W[(30 + i) * 64 + j]
            for i in range(9 + 21):
                for j in range(L):
                    W[(0 + i) * 64 + j] = W[(30 + i) * 64 + j]


@nb.njit(cache=True)
def run_one_store_pose(z, dts, x0, p0, q, r, s_pred, p_pred, s_filt, p_filt, out_nis, out_logdet, out_x):
    """Filter one trajectory like run_one_pose and keep every step's predicted internal state and packed
    covariance (s_pred (K, 9), p_pred (K, 21), before the update) and posterior ones (s_filt, p_filt),
    the NIS and log det S of each update (both NaN for a missed detection: a NaN row of z predicts only) and
    the posterior physical states out_x (K, 6). A step with a measurement is the fused step_store_pose (the
    filter's step_try_pose writing its prediction; derive/codegen/smooth_step.py), with the same Joseph-form
    fallback as run_one_pose."""
    s = state_from_physical(x0)
    p = p0.copy()
    K = z.shape[0]
    for k in range(K):
        if np.isnan(z[k, 0]) or np.isnan(z[k, 1]) or np.isnan(z[k, 2]):
            predict(s, p, dts[k], q[0], q[1], q[2])
            for i in range(9):
                s_pred[k, i] = s[i]
            for i in range(21):
                p_pred[k, i] = p[i]
            out_nis[k] = np.nan
            out_logdet[k] = np.nan
        else:
            nis, out_logdet[k] = step_store_pose(s, p, dts[k], q[0], q[1], q[2], z[k, 0], z[k, 1], z[k, 2], r[0], r[1], r[2], s_pred[k], p_pred[k])
            if nis < 0.0:  # rare: the cheap covariance failed the LDLᵀ test; Joseph form from the prediction
                nis = update_pose(s, p, z[k, 0], z[k, 1], z[k, 2], r[0], r[1], r[2])
            out_nis[k] = nis
        for i in range(9):
            s_filt[k, i] = s[i]
        for i in range(21):
            p_filt[k, i] = p[i]
        physical_into(s, out_x[k])


@nb.njit(cache=True, parallel=True)
def run_batch_store_pose(z, dts, x0, p0, q, r, s_pred, p_pred, s_filt, p_filt, out_nis, out_logdet, out_x):
    """run_one_store_pose over B trajectories in parallel (prange); arrays as run_batch_pose with a
    leading batch axis (s_pred, s_filt (B, K, 9); p_pred, p_filt (B, K, 21); out_nis, out_logdet (B, K);
    out_x (B, K, 6))."""
    for b in nb.prange(z.shape[0]):
        run_one_store_pose(z[b], dts[b], x0[b], p0[b], q, r, s_pred[b], p_pred[b], s_filt[b], p_filt[b], out_nis[b],
                             out_logdet[b], out_x[b])


@nb.njit(cache=True, parallel=True)
def loglik_batch_pose(z, dts, x0, p0, q, r, lengths, out_ll, out_count):
    """Innovation log-likelihood of each of B trajectories (prange): out_ll[b] = Σ_k −½(log det S_k + NIS_k +
    3·log 2π) over its first lengths[b] steps (the rest is padding), out_count[b] = its number of updates
    (NaN rows of z are missed detections: predicted, not counted). A diverged filter gives NaN."""
    for b in nb.prange(z.shape[0]):
        s = state_from_physical(x0[b])
        p = p0[b].copy()
        ll = 0.0
        cnt = 0
        for k in range(lengths[b]):
            predict(s, p, dts[b, k], q[0], q[1], q[2])
            if not (np.isnan(z[b, k, 0]) or np.isnan(z[b, k, 1]) or np.isnan(z[b, k, 2])):
                ld = innovation_logdet_pose(s, p, r[0], r[1], r[2])
                nis = update_pose(s, p, z[b, k, 0], z[b, k, 1], z[b, k, 2], r[0], r[1], r[2])
                ll += -0.5 * (ld + nis + 3.0 * 1.8378770664093453)
                cnt += 1
        out_ll[b] = ll
        out_count[b] = cnt


@nb.njit(cache=True)
def innovation_logdet_position(s, p, r):
    """log det S, S = ℋ P ℋᵀ + R (eq:K) for a position measurement at the predicted state (s, p),
    noise stds (r): the log-determinant term of the innovation log-likelihood.
    """
    c_theta = s[2]
    s_theta = s[3]
    p00 = p[0]
    p01 = p[1]
    p11 = p[6]
    hh01 = -s_theta
    _t0 = c_theta*p01
    hp00 = c_theta*p00 + hh01*p01
    hp01 = _t0 + hh01*p11
    hp10 = _t0 + p00*s_theta
    hp11 = c_theta*p11 + p01*s_theta
    _t1 = r*r
    S00 = _t1 + c_theta*hp00 + hh01*hp01
    S01 = c_theta*hp01 + hp00*s_theta
    S11 = _t1 + c_theta*hp11 + hp10*s_theta
    detS = S00*S11 - S01*S01
    return math.log(detS)


@nb.njit(cache=True, fastmath=FASTMATH, error_model="numpy")
def step_store_position(s, p, dt, sigma_x, sigma_y, sigma_omega, z_x, z_y, r, sq, pq):
    """step_try_position that also writes the predicted internal state into sq and the predicted packed covariance
    (after the angle-variance cap) into pq, and returns (NIS, log det S) (derive/codegen/smooth_step.py); a NIS
    of -1 means the caller must run update_position (derive/codegen/fused.py).
    (eq:pred_mu, eq:pred_cov, angle-variance cap, eq:K, eq:up_mu, eq:up_P) in one kernel; returns the NIS.
    Covariance as P − βKℋP; a step whose result fails the LDLᵀ test (covariance_is_pd_fused) leaves the
    prediction in s, p and returns -1.0: the caller then runs update_position (Joseph form;
    derive/codegen/fused.py).
    legend: cc = 𝒞 (eq:C), f = F = Ad(exp(−Ω)) + Φ(Ω)𝒞 (eq:pred_cov), g = Φ(Ω)G, hh = ℋ (eq:calH), hp = ℋP, inn = [log_G'(h(μ)⁻¹Z)]^∨, S = ℋPℋᵀ + R, Si = S⁻¹, k = K (eq:K), nk = Kν, alpha = gain damping, nu = ν, phi = Φ(ν) (eq:up_P), a = I − αKℋ, b = aP, beta = α(2 − α), kb = βK, pj = Joseph-form P (= P − βKℋP), cp = Φ(ν)·pj, mu/e = new mean
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
    _t0 = c_omega*dt
    _t1 = dt*s_omega
    cc03 = _t0
    cc04 = -_t1
    cc13 = _t1
    cc14 = _t0
    _a0 = dt*omega
    _sin__a0 = math.sin(_a0)
    _cos__a0 = math.cos(_a0)
    _sinc__a0, _cosc__a0, _sinc2__a0, _cosc2__a0 = sinc_family(_a0, _sin__a0, _cos__a0)
    _t2 = dt*v_x
    _t3 = _cosc__a0*_t2
    _t4 = dt*v_y
    _t5 = _sinc__a0*_t4
    _t6 = -(_cosc2__a0*_t4) + _sinc2__a0*dt*v_x
    _t7 = _cosc__a0*_t4
    _t8 = _cosc2__a0*_t2 + _sinc2__a0*_t4
    _t9 = (dt*dt)/2.0
    _t10 = _sinc__a0*_t9
    _t11 = _cosc__a0*_t9
    _t12 = _sinc__a0*dt*v_x - _t7
    _t13 = _t3 + _t5
    f00 = _cos__a0
    f01 = _sin__a0
    f02 = _t3 - _t5
    f03 = _cosc__a0*cc13 + _sinc__a0*cc03
    f04 = _cosc__a0*cc14 + _sinc__a0*cc04
    f05 = _t6*dt
    f10 = -_sin__a0
    f11 = _cos__a0
    f12 = _sinc__a0*_t2 + _t7
    f13 = -(_cosc__a0*cc03) + _sinc__a0*cc13
    f14 = -(_cosc__a0*cc04) + _sinc__a0*cc14
    f15 = _t8*dt
    g00 = _t10
    g01 = _t11
    g02 = _t6*_t9
    g10 = -_t11
    g11 = _t10
    g12 = _t8*_t9
    g22 = _t9
    e00 = _t12*c_theta - _t13*s_theta + x
    e01 = _t12*s_theta + _t13*c_theta + y
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
    _t14 = sigma_x*sigma_x
    _t15 = sigma_y*sigma_y
    _t16 = sigma_omega*sigma_omega
    _t17 = _t14*g00
    _t18 = _t15*g01
    _t19 = _t16*g02
    _t20 = _t16*g12
    _t21 = dt*dt
    pp00 = _t14*(g00*g00) + _t15*(g01*g01) + _t16*(g02*g02) + f00*m00 + f01*m01 + f02*m02 + f03*m03 + f04*m04 + f05*m05
    pp01 = _t17*g10 + _t18*g11 + _t19*g12 + f10*m00 + f11*m01 + f12*m02 + f13*m03 + f14*m04 + f15*m05
    pp02 = _t19*g22 + dt*m05 + m02
    pp03 = _t17*dt + m03
    pp04 = _t18*dt + m04
    pp05 = _t19*dt + m05
    pp11 = _t14*(g10*g10) + _t15*(g11*g11) + _t16*(g12*g12) + f10*m10 + f11*m11 + f12*m12 + f13*m13 + f14*m14 + f15*m15
    pp12 = _t20*g22 + dt*m15 + m12
    pp13 = _t14*dt*g10 + m13
    pp14 = _t15*dt*g11 + m14
    pp15 = _t20*dt + m15
    pp22 = _t16*(g22*g22) + dt*m25 + m22
    pp23 = m23
    pp24 = m24
    pp25 = _t16*dt*g22 + m25
    pp33 = _t14*_t21 + p33
    pp34 = p34
    pp35 = p35
    pp44 = _t15*_t21 + p44
    pp45 = p45
    pp55 = _t16*_t21 + p55
    x_p = e00
    y_p = e01
    c_theta_p = e02
    s_theta_p = e03
    if pp22 > math.pi * math.pi:
        _cap = math.pi / math.sqrt(pp22)
        pp02 = pp02 * _cap
        pp12 = pp12 * _cap
        pp23 = pp23 * _cap
        pp24 = pp24 * _cap
        pp25 = pp25 * _cap
        pp22 = math.pi * math.pi
    if pp55 > math.pi * math.pi:
        _cap = math.pi / math.sqrt(pp55)
        pp05 = pp05 * _cap
        pp15 = pp15 * _cap
        pp25 = pp25 * _cap
        pp35 = pp35 * _cap
        pp45 = pp45 * _cap
        pp55 = math.pi * math.pi
    hh01 = -s_theta_p
    _t22 = c_theta_p*pp01
    hp00 = c_theta_p*pp00 + hh01*pp01
    hp01 = _t22 + hh01*pp11
    hp02 = c_theta_p*pp02 + hh01*pp12
    hp03 = c_theta_p*pp03 + hh01*pp13
    hp04 = c_theta_p*pp04 + hh01*pp14
    hp05 = c_theta_p*pp05 + hh01*pp15
    hp10 = _t22 + pp00*s_theta_p
    hp11 = c_theta_p*pp11 + pp01*s_theta_p
    hp12 = c_theta_p*pp12 + pp02*s_theta_p
    hp13 = c_theta_p*pp13 + pp03*s_theta_p
    hp14 = c_theta_p*pp14 + pp04*s_theta_p
    hp15 = c_theta_p*pp15 + pp05*s_theta_p
    inn00 = -x_p + z_x
    inn10 = -y_p + z_y
    _t23 = r*r
    S00 = _t23 + c_theta_p*hp00 + hh01*hp01
    S01 = c_theta_p*hp01 + hp00*s_theta_p
    S11 = _t23 + c_theta_p*hp11 + hp10*s_theta_p
    rdet = 1.0/(S00*S11 - S01*S01)
    Si00 = S11*rdet
    Si01 = -(S01*rdet)
    Si11 = S00*rdet
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
    nis = Si00*(inn00*inn00) + 2.0*Si01*inn00*inn10 + Si11*(inn10*inn10)
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
    _sinc_nu2, _cosc_nu2, _sinc2_nu2, _cosc2_nu2 = sinc_family(nu2, _sin_nu2, _cos_nu2)
    _sin_nu5 = math.sin(nu5)
    _cos_nu5 = math.cos(nu5)
    _sinc_nu5, _cosc_nu5, _sinc2_nu5, _cosc2_nu5 = sinc_family(nu5, _sin_nu5, _cos_nu5)
    _t24 = -(_cosc_nu2*nu1) + _sinc_nu2*nu0
    _t25 = _cosc_nu2*nu0 + _sinc_nu2*nu1
    _t26 = -(_cosc_nu5*nu4) + _sinc_nu5*nu3
    _t27 = _cosc_nu5*nu3 + _sinc_nu5*nu4
    _t28 = _cos_nu5*s_omega + _sin_nu5*c_omega
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
    mu00 = _t24*c_theta_p - _t25*s_theta_p + x_p
    mu01 = _t24*s_theta_p + _t25*c_theta_p + y_p
    mu02 = _cos_nu2*c_theta_p - _sin_nu2*s_theta_p
    mu03 = _cos_nu2*s_theta_p + _sin_nu2*c_theta_p
    mu04 = _t26*c_omega - _t27*s_omega + v_x
    mu05 = _t26*s_omega + _t27*c_omega + v_y
    mu06 = wrap_angle_sum(nu5 + omega, _t28)
    mu07 = _cos_nu5*c_omega - _sin_nu5*s_omega
    mu08 = _t28
    beta = alpha*(2.0 - alpha)
    kb00 = beta*k00
    kb01 = beta*k01
    kb10 = beta*k10
    kb11 = beta*k11
    kb20 = beta*k20
    kb21 = beta*k21
    kb30 = beta*k30
    kb31 = beta*k31
    kb40 = beta*k40
    kb41 = beta*k41
    kb50 = beta*k50
    kb51 = beta*k51
    pj00 = -(hp00*kb00) - hp10*kb01 + pp00
    pj01 = -(hp01*kb00) - hp11*kb01 + pp01
    pj02 = -(hp02*kb00) - hp12*kb01 + pp02
    pj03 = -(hp03*kb00) - hp13*kb01 + pp03
    pj04 = -(hp04*kb00) - hp14*kb01 + pp04
    pj05 = -(hp05*kb00) - hp15*kb01 + pp05
    pj11 = -(hp01*kb10) - hp11*kb11 + pp11
    pj12 = -(hp02*kb10) - hp12*kb11 + pp12
    pj13 = -(hp03*kb10) - hp13*kb11 + pp13
    pj14 = -(hp04*kb10) - hp14*kb11 + pp14
    pj15 = -(hp05*kb10) - hp15*kb11 + pp15
    pj22 = -(hp02*kb20) - hp12*kb21 + pp22
    pj23 = -(hp03*kb20) - hp13*kb21 + pp23
    pj24 = -(hp04*kb20) - hp14*kb21 + pp24
    pj25 = -(hp05*kb20) - hp15*kb21 + pp25
    pj33 = -(hp03*kb30) - hp13*kb31 + pp33
    pj34 = -(hp04*kb30) - hp14*kb31 + pp34
    pj35 = -(hp05*kb30) - hp15*kb31 + pp35
    pj44 = -(hp04*kb40) - hp14*kb41 + pp44
    pj45 = -(hp05*kb40) - hp15*kb41 + pp45
    pj55 = -(hp05*kb50) - hp15*kb51 + pp55
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
    sq[0] = x_p
    sq[1] = y_p
    sq[2] = c_theta_p
    sq[3] = s_theta_p
    sq[4] = v_x
    sq[5] = v_y
    sq[6] = omega
    sq[7] = c_omega
    sq[8] = s_omega
    pq[0] = pp00
    pq[1] = pp01
    pq[2] = pp02
    pq[3] = pp03
    pq[4] = pp04
    pq[5] = pp05
    pq[6] = pp11
    pq[7] = pp12
    pq[8] = pp13
    pq[9] = pp14
    pq[10] = pp15
    pq[11] = pp22
    pq[12] = pp23
    pq[13] = pp24
    pq[14] = pp25
    pq[15] = pp33
    pq[16] = pp34
    pq[17] = pp35
    pq[18] = pp44
    pq[19] = pp45
    pq[20] = pp55
    out_p0 = cp00*phi00 + cp01*phi01 + cp02*phi02
    out_p1 = cp00*phi10 + cp01*phi11 + cp02*phi12
    out_p2 = cp02
    out_p3 = cp03*phi33 + cp04*phi34 + cp05*phi35
    out_p4 = cp03*phi43 + cp04*phi44 + cp05*phi45
    out_p5 = cp05
    out_p6 = cp10*phi10 + cp11*phi11 + cp12*phi12
    out_p7 = cp12
    out_p8 = cp13*phi33 + cp14*phi34 + cp15*phi35
    out_p9 = cp13*phi43 + cp14*phi44 + cp15*phi45
    out_p10 = cp15
    out_p11 = pj22
    out_p12 = phi33*pj23 + phi34*pj24 + phi35*pj25
    out_p13 = phi43*pj23 + phi44*pj24 + phi45*pj25
    out_p14 = pj25
    out_p15 = cp33*phi33 + cp34*phi34 + cp35*phi35
    out_p16 = cp33*phi43 + cp34*phi44 + cp35*phi45
    out_p17 = cp35
    out_p18 = cp43*phi43 + cp44*phi44 + cp45*phi45
    out_p19 = cp45
    out_p20 = pj55
    out_s0 = mu00
    out_s1 = mu01
    out_s2 = mu02
    out_s3 = mu03
    out_s4 = mu04
    out_s5 = mu05
    out_s6 = mu06
    out_s7 = mu07
    out_s8 = mu08
    if not covariance_is_pd_fused(out_p0, out_p1, out_p2, out_p3, out_p4, out_p5, out_p6, out_p7, out_p8, out_p9, out_p10, out_p11, out_p12, out_p13, out_p14, out_p15, out_p16, out_p17, out_p18, out_p19, out_p20):
        out_p0 = pp00
        out_p1 = pp01
        out_p2 = pp02
        out_p3 = pp03
        out_p4 = pp04
        out_p5 = pp05
        out_p6 = pp11
        out_p7 = pp12
        out_p8 = pp13
        out_p9 = pp14
        out_p10 = pp15
        out_p11 = pp22
        out_p12 = pp23
        out_p13 = pp24
        out_p14 = pp25
        out_p15 = pp33
        out_p16 = pp34
        out_p17 = pp35
        out_p18 = pp44
        out_p19 = pp45
        out_p20 = pp55
        out_s0 = x_p
        out_s1 = y_p
        out_s2 = c_theta_p
        out_s3 = s_theta_p
        out_s4 = v_x
        out_s5 = v_y
        out_s6 = omega
        out_s7 = c_omega
        out_s8 = s_omega
        nis = -1.0
    p[0] = out_p0
    p[1] = out_p1
    p[2] = out_p2
    p[3] = out_p3
    p[4] = out_p4
    p[5] = out_p5
    p[6] = out_p6
    p[7] = out_p7
    p[8] = out_p8
    p[9] = out_p9
    p[10] = out_p10
    p[11] = out_p11
    p[12] = out_p12
    p[13] = out_p13
    p[14] = out_p14
    p[15] = out_p15
    p[16] = out_p16
    p[17] = out_p17
    p[18] = out_p18
    p[19] = out_p19
    p[20] = out_p20
    s[0] = out_s0
    s[1] = out_s1
    s[2] = out_s2
    s[3] = out_s3
    s[4] = out_s4
    s[5] = out_s5
    s[6] = out_s6
    s[7] = out_s7
    s[8] = out_s8
    return nis, -math.log(rdet)


@nb.njit(inline="always", fastmath={"contract"}, error_model="numpy")
def lane_store_position(W, j, sigma_x, sigma_y, sigma_omega, r):
    """step_store_position on lane j of the work array W (rows: derive/codegen/smooth_step.py), without branches (SIMD); 1/det S in a row of W.
    """
    x = W[0 + j]
    y = W[64 + j]
    c_theta = W[128 + j]
    s_theta = W[192 + j]
    v_x = W[256 + j]
    v_y = W[320 + j]
    omega = W[384 + j]
    c_omega = W[448 + j]
    s_omega = W[512 + j]
    p00 = W[576 + j]
    p01 = W[640 + j]
    p02 = W[704 + j]
    p03 = W[768 + j]
    p04 = W[832 + j]
    p05 = W[896 + j]
    p11 = W[960 + j]
    p12 = W[1024 + j]
    p13 = W[1088 + j]
    p14 = W[1152 + j]
    p15 = W[1216 + j]
    p22 = W[1280 + j]
    p23 = W[1344 + j]
    p24 = W[1408 + j]
    p25 = W[1472 + j]
    p33 = W[1536 + j]
    p34 = W[1600 + j]
    p35 = W[1664 + j]
    p44 = W[1728 + j]
    p45 = W[1792 + j]
    p55 = W[1856 + j]
    dt = W[3840 + j]
    z_x = W[4032 + j]
    z_y = W[4096 + j]
    _t0 = c_omega*dt
    _t1 = dt*s_omega
    cc03 = _t0
    cc04 = -_t1
    cc13 = _t1
    cc14 = _t0
    _a0 = dt*omega
    _sin__a0 = sin_v(_a0)
    _cos__a0 = cos_v(_a0)
    _sinc__a0, _cosc__a0, _sinc2__a0, _cosc2__a0 = sinc_family(_a0, _sin__a0, _cos__a0)
    _t2 = dt*v_x
    _t3 = _cosc__a0*_t2
    _t4 = dt*v_y
    _t5 = _sinc__a0*_t4
    _t6 = -(_cosc2__a0*_t4) + _sinc2__a0*dt*v_x
    _t7 = _cosc__a0*_t4
    _t8 = _cosc2__a0*_t2 + _sinc2__a0*_t4
    _t9 = (dt*dt)/2.0
    _t10 = _sinc__a0*_t9
    _t11 = _cosc__a0*_t9
    _t12 = _sinc__a0*dt*v_x - _t7
    _t13 = _t3 + _t5
    f00 = _cos__a0
    f01 = _sin__a0
    f02 = _t3 - _t5
    f03 = _cosc__a0*cc13 + _sinc__a0*cc03
    f04 = _cosc__a0*cc14 + _sinc__a0*cc04
    f05 = _t6*dt
    f10 = -_sin__a0
    f11 = _cos__a0
    f12 = _sinc__a0*_t2 + _t7
    f13 = -(_cosc__a0*cc03) + _sinc__a0*cc13
    f14 = -(_cosc__a0*cc04) + _sinc__a0*cc14
    f15 = _t8*dt
    g00 = _t10
    g01 = _t11
    g02 = _t6*_t9
    g10 = -_t11
    g11 = _t10
    g12 = _t8*_t9
    g22 = _t9
    e00 = _t12*c_theta - _t13*s_theta + x
    e01 = _t12*s_theta + _t13*c_theta + y
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
    _t14 = sigma_x*sigma_x
    _t15 = sigma_y*sigma_y
    _t16 = sigma_omega*sigma_omega
    _t17 = _t14*g00
    _t18 = _t15*g01
    _t19 = _t16*g02
    _t20 = _t16*g12
    _t21 = dt*dt
    pp00 = _t14*(g00*g00) + _t15*(g01*g01) + _t16*(g02*g02) + f00*m00 + f01*m01 + f02*m02 + f03*m03 + f04*m04 + f05*m05
    pp01 = _t17*g10 + _t18*g11 + _t19*g12 + f10*m00 + f11*m01 + f12*m02 + f13*m03 + f14*m04 + f15*m05
    pp02 = _t19*g22 + dt*m05 + m02
    pp03 = _t17*dt + m03
    pp04 = _t18*dt + m04
    pp05 = _t19*dt + m05
    pp11 = _t14*(g10*g10) + _t15*(g11*g11) + _t16*(g12*g12) + f10*m10 + f11*m11 + f12*m12 + f13*m13 + f14*m14 + f15*m15
    pp12 = _t20*g22 + dt*m15 + m12
    pp13 = _t14*dt*g10 + m13
    pp14 = _t15*dt*g11 + m14
    pp15 = _t20*dt + m15
    pp22 = _t16*(g22*g22) + dt*m25 + m22
    pp23 = m23
    pp24 = m24
    pp25 = _t16*dt*g22 + m25
    pp33 = _t14*_t21 + p33
    pp34 = p34
    pp35 = p35
    pp44 = _t15*_t21 + p44
    pp45 = p45
    pp55 = _t16*_t21 + p55
    x_p = e00
    y_p = e01
    c_theta_p = e02
    s_theta_p = e03
    if pp22 > math.pi * math.pi:
        _cap = math.pi / math.sqrt(pp22)
        pp02 = pp02 * _cap
        pp12 = pp12 * _cap
        pp23 = pp23 * _cap
        pp24 = pp24 * _cap
        pp25 = pp25 * _cap
        pp22 = math.pi * math.pi
    if pp55 > math.pi * math.pi:
        _cap = math.pi / math.sqrt(pp55)
        pp05 = pp05 * _cap
        pp15 = pp15 * _cap
        pp25 = pp25 * _cap
        pp35 = pp35 * _cap
        pp45 = pp45 * _cap
        pp55 = math.pi * math.pi
    hh01 = -s_theta_p
    _t22 = c_theta_p*pp01
    hp00 = c_theta_p*pp00 + hh01*pp01
    hp01 = _t22 + hh01*pp11
    hp02 = c_theta_p*pp02 + hh01*pp12
    hp03 = c_theta_p*pp03 + hh01*pp13
    hp04 = c_theta_p*pp04 + hh01*pp14
    hp05 = c_theta_p*pp05 + hh01*pp15
    hp10 = _t22 + pp00*s_theta_p
    hp11 = c_theta_p*pp11 + pp01*s_theta_p
    hp12 = c_theta_p*pp12 + pp02*s_theta_p
    hp13 = c_theta_p*pp13 + pp03*s_theta_p
    hp14 = c_theta_p*pp14 + pp04*s_theta_p
    hp15 = c_theta_p*pp15 + pp05*s_theta_p
    inn00 = -x_p + z_x
    inn10 = -y_p + z_y
    _t23 = r*r
    S00 = _t23 + c_theta_p*hp00 + hh01*hp01
    S01 = c_theta_p*hp01 + hp00*s_theta_p
    S11 = _t23 + c_theta_p*hp11 + hp10*s_theta_p
    rdet = 1.0/(S00*S11 - S01*S01)
    Si00 = S11*rdet
    Si01 = -(S01*rdet)
    Si11 = S00*rdet
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
    nis = Si00*(inn00*inn00) + 2.0*Si01*inn00*inn10 + Si11*(inn10*inn10)
    nk0 = inn00*k00 + inn10*k01
    nk1 = inn00*k10 + inn10*k11
    nk2 = inn00*k20 + inn10*k21
    nk3 = inn00*k30 + inn10*k31
    nk4 = inn00*k40 + inn10*k41
    nk5 = inn00*k50 + inn10*k51
    alpha = gain_damping_v(nk2, nk5)
    nu0 = alpha*nk0
    nu1 = alpha*nk1
    nu2 = alpha*nk2
    nu3 = alpha*nk3
    nu4 = alpha*nk4
    nu5 = alpha*nk5
    _sin_nu2 = sin_v(nu2)
    _cos_nu2 = cos_v(nu2)
    _sinc_nu2, _cosc_nu2, _sinc2_nu2, _cosc2_nu2 = sinc_family(nu2, _sin_nu2, _cos_nu2)
    _sin_nu5 = sin_v(nu5)
    _cos_nu5 = cos_v(nu5)
    _sinc_nu5, _cosc_nu5, _sinc2_nu5, _cosc2_nu5 = sinc_family(nu5, _sin_nu5, _cos_nu5)
    _t24 = -(_cosc_nu2*nu1) + _sinc_nu2*nu0
    _t25 = _cosc_nu2*nu0 + _sinc_nu2*nu1
    _t26 = -(_cosc_nu5*nu4) + _sinc_nu5*nu3
    _t27 = _cosc_nu5*nu3 + _sinc_nu5*nu4
    _t28 = _cos_nu5*s_omega + _sin_nu5*c_omega
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
    mu00 = _t24*c_theta_p - _t25*s_theta_p + x_p
    mu01 = _t24*s_theta_p + _t25*c_theta_p + y_p
    mu02 = _cos_nu2*c_theta_p - _sin_nu2*s_theta_p
    mu03 = _cos_nu2*s_theta_p + _sin_nu2*c_theta_p
    mu04 = _t26*c_omega - _t27*s_omega + v_x
    mu05 = _t26*s_omega + _t27*c_omega + v_y
    mu06 = wrap_sum_v(nu5 + omega, _t28)
    mu07 = _cos_nu5*c_omega - _sin_nu5*s_omega
    mu08 = _t28
    beta = alpha*(2.0 - alpha)
    kb00 = beta*k00
    kb01 = beta*k01
    kb10 = beta*k10
    kb11 = beta*k11
    kb20 = beta*k20
    kb21 = beta*k21
    kb30 = beta*k30
    kb31 = beta*k31
    kb40 = beta*k40
    kb41 = beta*k41
    kb50 = beta*k50
    kb51 = beta*k51
    pj00 = -(hp00*kb00) - hp10*kb01 + pp00
    pj01 = -(hp01*kb00) - hp11*kb01 + pp01
    pj02 = -(hp02*kb00) - hp12*kb01 + pp02
    pj03 = -(hp03*kb00) - hp13*kb01 + pp03
    pj04 = -(hp04*kb00) - hp14*kb01 + pp04
    pj05 = -(hp05*kb00) - hp15*kb01 + pp05
    pj11 = -(hp01*kb10) - hp11*kb11 + pp11
    pj12 = -(hp02*kb10) - hp12*kb11 + pp12
    pj13 = -(hp03*kb10) - hp13*kb11 + pp13
    pj14 = -(hp04*kb10) - hp14*kb11 + pp14
    pj15 = -(hp05*kb10) - hp15*kb11 + pp15
    pj22 = -(hp02*kb20) - hp12*kb21 + pp22
    pj23 = -(hp03*kb20) - hp13*kb21 + pp23
    pj24 = -(hp04*kb20) - hp14*kb21 + pp24
    pj25 = -(hp05*kb20) - hp15*kb21 + pp25
    pj33 = -(hp03*kb30) - hp13*kb31 + pp33
    pj34 = -(hp04*kb30) - hp14*kb31 + pp34
    pj35 = -(hp05*kb30) - hp15*kb31 + pp35
    pj44 = -(hp04*kb40) - hp14*kb41 + pp44
    pj45 = -(hp05*kb40) - hp15*kb41 + pp45
    pj55 = -(hp05*kb50) - hp15*kb51 + pp55
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
    W[4160 + j] = x_p
    W[4224 + j] = y_p
    W[4288 + j] = c_theta_p
    W[4352 + j] = s_theta_p
    W[4416 + j] = v_x
    W[4480 + j] = v_y
    W[4544 + j] = omega
    W[4608 + j] = c_omega
    W[4672 + j] = s_omega
    W[4736 + j] = pp00
    W[4800 + j] = pp01
    W[4864 + j] = pp02
    W[4928 + j] = pp03
    W[4992 + j] = pp04
    W[5056 + j] = pp05
    W[5120 + j] = pp11
    W[5184 + j] = pp12
    W[5248 + j] = pp13
    W[5312 + j] = pp14
    W[5376 + j] = pp15
    W[5440 + j] = pp22
    W[5504 + j] = pp23
    W[5568 + j] = pp24
    W[5632 + j] = pp25
    W[5696 + j] = pp33
    W[5760 + j] = pp34
    W[5824 + j] = pp35
    W[5888 + j] = pp44
    W[5952 + j] = pp45
    W[6016 + j] = pp55
    W[2496 + j] = cp00*phi00 + cp01*phi01 + cp02*phi02
    W[2560 + j] = cp00*phi10 + cp01*phi11 + cp02*phi12
    W[2624 + j] = cp02
    W[2688 + j] = cp03*phi33 + cp04*phi34 + cp05*phi35
    W[2752 + j] = cp03*phi43 + cp04*phi44 + cp05*phi45
    W[2816 + j] = cp05
    W[2880 + j] = cp10*phi10 + cp11*phi11 + cp12*phi12
    W[2944 + j] = cp12
    W[3008 + j] = cp13*phi33 + cp14*phi34 + cp15*phi35
    W[3072 + j] = cp13*phi43 + cp14*phi44 + cp15*phi45
    W[3136 + j] = cp15
    W[3200 + j] = pj22
    W[3264 + j] = phi33*pj23 + phi34*pj24 + phi35*pj25
    W[3328 + j] = phi43*pj23 + phi44*pj24 + phi45*pj25
    W[3392 + j] = pj25
    W[3456 + j] = cp33*phi33 + cp34*phi34 + cp35*phi35
    W[3520 + j] = cp33*phi43 + cp34*phi44 + cp35*phi45
    W[3584 + j] = cp35
    W[3648 + j] = cp43*phi43 + cp44*phi44 + cp45*phi45
    W[3712 + j] = cp45
    W[3776 + j] = pj55
    W[1920 + j] = mu00
    W[1984 + j] = mu01
    W[2048 + j] = mu02
    W[2112 + j] = mu03
    W[2176 + j] = mu04
    W[2240 + j] = mu05
    W[2304 + j] = mu06
    W[2368 + j] = mu07
    W[2432 + j] = mu08
    W[6080 + j] = rdet
    return nis


@nb.njit(cache=True, parallel=True, fastmath=FASTMATH, error_model="numpy")
def run_batch_store_soa_position(z, dts, x0, p0, q, r, Qb, Fb, out_nis, out_logdet, out_x):
    """run_batch_store_position with trajectories in the SIMD lanes (derive/codegen/smooth_step.py), the same results
    with the states stored in blocks: Qb, Fb (nblk, K, 30, 64), nblk = ⌈B / 64⌉, get the predicted /
    posterior internal state and packed covariance of step k of trajectory blk·64 + j in Qb[blk, k, :, j]
    (lanes past B: zeros). As run_batch_soa_position (prange over blocks, lane_store_position vectorised over the lanes,
    a lane failing the LDLᵀ test or with a NaN row redone by the scalar predict / update_position)."""
    B = z.shape[0]
    K = z.shape[1]
    nblk = (B + 64 - 1) // 64
    for blk in nb.prange(nblk):
        lo = blk * 64
        L = min(64, B - lo)
        W = np.zeros(96 * 64)
        s = np.empty(9)
        p = np.empty(21)
        for j in range(L):
            s0 = state_from_physical(x0[lo + j])
            for i in range(9):
                W[(0 + i) * 64 + j] = s0[i]
            for i in range(21):
                W[(9 + i) * 64 + j] = p0[lo + j, i]
        for k in range(K):
            for j in range(L):
                W[60 * 64 + j] = dts[lo + j, k]
                W[63 * 64 + j] = z[lo + j, k, 0]
                W[64 * 64 + j] = z[lo + j, k, 1]
            for j in range(L):
                W[61 * 64 + j] = lane_store_position(W, j, q[0], q[1], q[2], r[0])
                good = covariance_is_pd_lane(W, j) & (W[61 * 64 + j] == W[61 * 64 + j])
                W[62 * 64 + j] = 1.0 if good else 0.0
            for j in range(L):
                b = lo + j
                if W[62 * 64 + j] == 0.0:
                    for i in range(9):
                        s[i] = W[(0 + i) * 64 + j]
                    for i in range(21):
                        p[i] = W[(9 + i) * 64 + j]
                    predict(s, p, dts[b, k], q[0], q[1], q[2])
                    for i in range(9):
                        W[(65 + i) * 64 + j] = s[i]
                    for i in range(21):
                        W[(74 + i) * 64 + j] = p[i]
                    if np.isnan(z[b, k, 0]) or np.isnan(z[b, k, 1]):
                        W[61 * 64 + j] = np.nan
                        out_logdet[b, k] = np.nan
                    else:
                        out_logdet[b, k] = innovation_logdet_position(s, p, r[0])
                        W[61 * 64 + j] = update_position(s, p, z[b, k, 0], z[b, k, 1], r[0])
                    for i in range(9):
                        W[(30 + i) * 64 + j] = s[i]
                    for i in range(21):
                        W[(39 + i) * 64 + j] = p[i]
                else:
                    out_logdet[b, k] = -math.log(W[95 * 64 + j])
            for j in range(L):
                out_nis[lo + j, k] = W[61 * 64 + j]
                physical_lane(W, j, out_x, lo + j, k)
            for i in range(9 + 21):
                for j in range(64):
                    Qb[blk, k, i, j] = W[(65 + i) * 64 + j]
                    Fb[blk, k, i, j] = W[(30 + i) * 64 + j]
            for i in range(9 + 21):
                for j in range(L):
                    W[(0 + i) * 64 + j] = W[(30 + i) * 64 + j]


@nb.njit(cache=True)
def run_one_store_position(z, dts, x0, p0, q, r, s_pred, p_pred, s_filt, p_filt, out_nis, out_logdet, out_x):
    """Filter one trajectory like run_one_position and keep every step's predicted internal state and packed
    covariance (s_pred (K, 9), p_pred (K, 21), before the update) and posterior ones (s_filt, p_filt),
    the NIS and log det S of each update (both NaN for a missed detection: a NaN row of z predicts only) and
    the posterior physical states out_x (K, 6). A step with a measurement is the fused step_store_position (the
    filter's step_try_position writing its prediction; derive/codegen/smooth_step.py), with the same Joseph-form
    fallback as run_one_position."""
    s = state_from_physical(x0)
    p = p0.copy()
    K = z.shape[0]
    for k in range(K):
        if np.isnan(z[k, 0]) or np.isnan(z[k, 1]):
            predict(s, p, dts[k], q[0], q[1], q[2])
            for i in range(9):
                s_pred[k, i] = s[i]
            for i in range(21):
                p_pred[k, i] = p[i]
            out_nis[k] = np.nan
            out_logdet[k] = np.nan
        else:
            nis, out_logdet[k] = step_store_position(s, p, dts[k], q[0], q[1], q[2], z[k, 0], z[k, 1], r[0], s_pred[k], p_pred[k])
            if nis < 0.0:  # rare: the cheap covariance failed the LDLᵀ test; Joseph form from the prediction
                nis = update_position(s, p, z[k, 0], z[k, 1], r[0])
            out_nis[k] = nis
        for i in range(9):
            s_filt[k, i] = s[i]
        for i in range(21):
            p_filt[k, i] = p[i]
        physical_into(s, out_x[k])


@nb.njit(cache=True, parallel=True)
def run_batch_store_position(z, dts, x0, p0, q, r, s_pred, p_pred, s_filt, p_filt, out_nis, out_logdet, out_x):
    """run_one_store_position over B trajectories in parallel (prange); arrays as run_batch_position with a
    leading batch axis (s_pred, s_filt (B, K, 9); p_pred, p_filt (B, K, 21); out_nis, out_logdet (B, K);
    out_x (B, K, 6))."""
    for b in nb.prange(z.shape[0]):
        run_one_store_position(z[b], dts[b], x0[b], p0[b], q, r, s_pred[b], p_pred[b], s_filt[b], p_filt[b], out_nis[b],
                             out_logdet[b], out_x[b])


@nb.njit(cache=True, parallel=True)
def loglik_batch_position(z, dts, x0, p0, q, r, lengths, out_ll, out_count):
    """Innovation log-likelihood of each of B trajectories (prange): out_ll[b] = Σ_k −½(log det S_k + NIS_k +
    2·log 2π) over its first lengths[b] steps (the rest is padding), out_count[b] = its number of updates
    (NaN rows of z are missed detections: predicted, not counted). A diverged filter gives NaN."""
    for b in nb.prange(z.shape[0]):
        s = state_from_physical(x0[b])
        p = p0[b].copy()
        ll = 0.0
        cnt = 0
        for k in range(lengths[b]):
            predict(s, p, dts[b, k], q[0], q[1], q[2])
            if not (np.isnan(z[b, k, 0]) or np.isnan(z[b, k, 1])):
                ld = innovation_logdet_position(s, p, r[0])
                nis = update_position(s, p, z[b, k, 0], z[b, k, 1], r[0])
                ll += -0.5 * (ld + nis + 2.0 * 1.8378770664093453)
                cnt += 1
        out_ll[b] = ll
        out_count[b] = cnt


@nb.njit(cache=True, fastmath=FASTMATH, error_model="numpy")
def smooth_step_at(s_filt, p_filt, s_pred, p_pred, s_sm, p_sm, k, dt):
    """One Rauch–Tung–Striebel backward step on the group (lgekf.estimators.smoother), straight-line:
    from the posterior (sf, pf) at k, the prediction (sq, pq) at k+1 and the smoothed (ss, ps) at k+1, with
    F = transition(μ_k, dt): d = log(μ_{k+1|k}⁻¹ μˢ_{k+1}), G = P_k Fᵀ P_{k+1|k}⁻¹ (LDLᵀ), δ = G d,
    P̃ = P_k + G (Φ(d)⁻¹ Pˢ_{k+1} Φ(d)⁻ᵀ − P_{k+1|k}) Gᵀ; writes μˢ_k = μ_k·exp(δ) into so and
    Pˢ_k = Φ(δ) P̃ Φ(δ)ᵀ (packed) into po (derive/codegen/smooth_step.py).
    legend: cc = 𝒞, ff = F, cf = P_k Fᵀ, dd = d, ji = Φ(d)⁻¹, jp = Φ(d)⁻¹Pˢ, dm = P̄ − P_{k+1|k},
    ld/ll/lr = LDLᵀ pivots, factor and reciprocal pivots, ly/gg = the solves for G, de = δ, gd = G·dm,
    pt = P̃, ph = Φ(δ), tp = Φ(δ)P̃.
    On the rows of the stored passes at step k: sf = s_filt[k], pf = p_filt[k], sq = s_pred[k + 1],
    pq = p_pred[k + 1], ss = s_sm[k + 1], ps = p_sm[k + 1], so = s_sm[k], po = p_sm[k] (derive/codegen/families/smoother.py).
    """
    x = s_filt[k, 0]
    y = s_filt[k, 1]
    c_theta = s_filt[k, 2]
    s_theta = s_filt[k, 3]
    v_x = s_filt[k, 4]
    v_y = s_filt[k, 5]
    omega = s_filt[k, 6]
    c_omega = s_filt[k, 7]
    s_omega = s_filt[k, 8]
    pf00 = p_filt[k, 0]
    pf01 = p_filt[k, 1]
    pf02 = p_filt[k, 2]
    pf03 = p_filt[k, 3]
    pf04 = p_filt[k, 4]
    pf05 = p_filt[k, 5]
    pf11 = p_filt[k, 6]
    pf12 = p_filt[k, 7]
    pf13 = p_filt[k, 8]
    pf14 = p_filt[k, 9]
    pf15 = p_filt[k, 10]
    pf22 = p_filt[k, 11]
    pf23 = p_filt[k, 12]
    pf24 = p_filt[k, 13]
    pf25 = p_filt[k, 14]
    pf33 = p_filt[k, 15]
    pf34 = p_filt[k, 16]
    pf35 = p_filt[k, 17]
    pf44 = p_filt[k, 18]
    pf45 = p_filt[k, 19]
    pf55 = p_filt[k, 20]
    q_x = s_pred[k + 1, 0]
    q_y = s_pred[k + 1, 1]
    q_c_theta = s_pred[k + 1, 2]
    q_s_theta = s_pred[k + 1, 3]
    q_v_x = s_pred[k + 1, 4]
    q_v_y = s_pred[k + 1, 5]
    q_c_omega = s_pred[k + 1, 7]
    q_s_omega = s_pred[k + 1, 8]
    pq00 = p_pred[k + 1, 0]
    pq01 = p_pred[k + 1, 1]
    pq02 = p_pred[k + 1, 2]
    pq03 = p_pred[k + 1, 3]
    pq04 = p_pred[k + 1, 4]
    pq05 = p_pred[k + 1, 5]
    pq11 = p_pred[k + 1, 6]
    pq12 = p_pred[k + 1, 7]
    pq13 = p_pred[k + 1, 8]
    pq14 = p_pred[k + 1, 9]
    pq15 = p_pred[k + 1, 10]
    pq22 = p_pred[k + 1, 11]
    pq23 = p_pred[k + 1, 12]
    pq24 = p_pred[k + 1, 13]
    pq25 = p_pred[k + 1, 14]
    pq33 = p_pred[k + 1, 15]
    pq34 = p_pred[k + 1, 16]
    pq35 = p_pred[k + 1, 17]
    pq44 = p_pred[k + 1, 18]
    pq45 = p_pred[k + 1, 19]
    pq55 = p_pred[k + 1, 20]
    t_x = s_sm[k + 1, 0]
    t_y = s_sm[k + 1, 1]
    t_c_theta = s_sm[k + 1, 2]
    t_s_theta = s_sm[k + 1, 3]
    t_v_x = s_sm[k + 1, 4]
    t_v_y = s_sm[k + 1, 5]
    t_c_omega = s_sm[k + 1, 7]
    t_s_omega = s_sm[k + 1, 8]
    ps00 = p_sm[k + 1, 0]
    ps01 = p_sm[k + 1, 1]
    ps02 = p_sm[k + 1, 2]
    ps03 = p_sm[k + 1, 3]
    ps04 = p_sm[k + 1, 4]
    ps05 = p_sm[k + 1, 5]
    ps11 = p_sm[k + 1, 6]
    ps12 = p_sm[k + 1, 7]
    ps13 = p_sm[k + 1, 8]
    ps14 = p_sm[k + 1, 9]
    ps15 = p_sm[k + 1, 10]
    ps22 = p_sm[k + 1, 11]
    ps23 = p_sm[k + 1, 12]
    ps24 = p_sm[k + 1, 13]
    ps25 = p_sm[k + 1, 14]
    ps33 = p_sm[k + 1, 15]
    ps34 = p_sm[k + 1, 16]
    ps35 = p_sm[k + 1, 17]
    ps44 = p_sm[k + 1, 18]
    ps45 = p_sm[k + 1, 19]
    ps55 = p_sm[k + 1, 20]
    _a0 = dt*omega
    _sin__a0 = math.sin(_a0)
    _cos__a0 = math.cos(_a0)
    _sinc__a0, _cosc__a0, _sinc2__a0, _cosc2__a0 = sinc_family(_a0, _sin__a0, _cos__a0)
    _a1 = math.atan2(q_c_omega*t_s_omega - q_s_omega*t_c_omega, q_c_omega*t_c_omega + q_s_omega*t_s_omega)
    _sin__a1 = math.sin(_a1)
    _cos__a1 = math.cos(_a1)
    _halfcot__a1 = halfcot(_a1, _sin__a1, _cos__a1)
    _a2 = math.atan2(q_c_theta*t_s_theta - q_s_theta*t_c_theta, q_c_theta*t_c_theta + q_s_theta*t_s_theta)
    _sin__a2 = math.sin(_a2)
    _cos__a2 = math.cos(_a2)
    _halfcot__a2 = halfcot(_a2, _sin__a2, _cos__a2)
    _t0 = c_omega*dt
    _t1 = dt*s_omega
    _t2 = dt*v_x
    _t3 = dt*v_y
    _t4 = -(q_c_theta*q_x) + q_c_theta*t_x - q_s_theta*q_y + q_s_theta*t_y
    _t5 = -(q_c_theta*q_y) + q_c_theta*t_y + q_s_theta*q_x - q_s_theta*t_x
    _t6 = _a2/2.0
    _t7 = -(q_c_omega*q_v_x) + q_c_omega*t_v_x - q_s_omega*q_v_y + q_s_omega*t_v_y
    _t8 = -(q_c_omega*q_v_y) + q_c_omega*t_v_y + q_s_omega*q_v_x - q_s_omega*t_v_x
    _t9 = _a1/2.0
    cc0_3 = _t0
    cc0_4 = -_t1
    cc1_3 = _t1
    cc1_4 = _t0
    ff0_0 = _cos__a0
    ff0_1 = _sin__a0
    ff0_2 = _cosc__a0*_t2 - _sinc__a0*_t3
    ff0_5 = dt*(-(_cosc2__a0*_t3) + _sinc2__a0*dt*v_x)
    ff1_0 = -_sin__a0
    ff1_1 = _cos__a0
    ff1_2 = _cosc__a0*_t3 + _sinc__a0*_t2
    ff1_5 = dt*(_cosc2__a0*_t2 + _sinc2__a0*_t3)
    cf0_2 = dt*pf05 + pf02
    cf1_2 = dt*pf15 + pf12
    cf2_2 = dt*pf25 + pf22
    cf3_2 = dt*pf35 + pf23
    cf4_2 = dt*pf45 + pf24
    cf5_2 = dt*pf55 + pf25
    dd0_0 = _halfcot__a2*_t4 + _t5*_t6
    dd0_1 = _halfcot__a2*_t5 - _t4*_t6
    dd0_2 = _a2
    dd0_3 = _halfcot__a1*_t7 + _t8*_t9
    dd0_4 = _halfcot__a1*_t8 - _t7*_t9
    dd0_5 = _a1
    dm2_2 = -pq22 + ps22
    dm2_5 = -pq25 + ps25
    dm5_5 = -pq55 + ps55
    lr0 = 1.0/max(1e-300, pq00)
    _sin_dd0_2 = math.sin(dd0_2)
    _cos_dd0_2 = math.cos(dd0_2)
    _halfcot_dd0_2 = halfcot(dd0_2, _sin_dd0_2, _cos_dd0_2)
    _halfcot1_dd0_2 = halfcot1(dd0_2, _sin_dd0_2, _cos_dd0_2)
    _sin_dd0_5 = math.sin(dd0_5)
    _cos_dd0_5 = math.cos(dd0_5)
    _halfcot_dd0_5 = halfcot(dd0_5, _sin_dd0_5, _cos_dd0_5)
    _halfcot1_dd0_5 = halfcot1(dd0_5, _sin_dd0_5, _cos_dd0_5)
    _t10 = dd0_2/2.0
    _t11 = dd0_5/2.0
    ff0_3 = _cosc__a0*cc1_3 + _sinc__a0*cc0_3
    ff0_4 = _cosc__a0*cc1_4 + _sinc__a0*cc0_4
    ff1_3 = -(_cosc__a0*cc0_3) + _sinc__a0*cc1_3
    ff1_4 = -(_cosc__a0*cc0_4) + _sinc__a0*cc1_4
    ji0_0 = _halfcot_dd0_2
    ji0_1 = -_t10
    ji0_2 = _halfcot1_dd0_2*dd0_0 + dd0_1/2.0
    ji1_0 = _t10
    ji1_1 = _halfcot_dd0_2
    ji1_2 = _halfcot1_dd0_2*dd0_1 - dd0_0/2.0
    ji3_3 = _halfcot_dd0_5
    ji3_4 = -_t11
    ji3_5 = _halfcot1_dd0_5*dd0_3 + dd0_4/2.0
    ji4_3 = _t11
    ji4_4 = _halfcot_dd0_5
    ji4_5 = _halfcot1_dd0_5*dd0_4 - dd0_3/2.0
    ll1_0 = lr0*pq01
    ll2_0 = lr0*pq02
    ll3_0 = lr0*pq03
    ll4_0 = lr0*pq04
    ll5_0 = lr0*pq05
    cf0_0 = ff0_0*pf00 + ff0_1*pf01 + ff0_2*pf02 + ff0_3*pf03 + ff0_4*pf04 + ff0_5*pf05
    cf0_1 = ff1_0*pf00 + ff1_1*pf01 + ff1_2*pf02 + ff1_3*pf03 + ff1_4*pf04 + ff1_5*pf05
    cf1_0 = ff0_0*pf01 + ff0_1*pf11 + ff0_2*pf12 + ff0_3*pf13 + ff0_4*pf14 + ff0_5*pf15
    cf1_1 = ff1_0*pf01 + ff1_1*pf11 + ff1_2*pf12 + ff1_3*pf13 + ff1_4*pf14 + ff1_5*pf15
    cf2_0 = ff0_0*pf02 + ff0_1*pf12 + ff0_2*pf22 + ff0_3*pf23 + ff0_4*pf24 + ff0_5*pf25
    cf2_1 = ff1_0*pf02 + ff1_1*pf12 + ff1_2*pf22 + ff1_3*pf23 + ff1_4*pf24 + ff1_5*pf25
    cf3_0 = ff0_0*pf03 + ff0_1*pf13 + ff0_2*pf23 + ff0_3*pf33 + ff0_4*pf34 + ff0_5*pf35
    cf3_1 = ff1_0*pf03 + ff1_1*pf13 + ff1_2*pf23 + ff1_3*pf33 + ff1_4*pf34 + ff1_5*pf35
    cf4_0 = ff0_0*pf04 + ff0_1*pf14 + ff0_2*pf24 + ff0_3*pf34 + ff0_4*pf44 + ff0_5*pf45
    cf4_1 = ff1_0*pf04 + ff1_1*pf14 + ff1_2*pf24 + ff1_3*pf34 + ff1_4*pf44 + ff1_5*pf45
    cf5_0 = ff0_0*pf05 + ff0_1*pf15 + ff0_2*pf25 + ff0_3*pf35 + ff0_4*pf45 + ff0_5*pf55
    cf5_1 = ff1_0*pf05 + ff1_1*pf15 + ff1_2*pf25 + ff1_3*pf35 + ff1_4*pf45 + ff1_5*pf55
    jp0_0 = ji0_0*ps00 + ji0_1*ps01 + ji0_2*ps02
    jp0_1 = ji0_0*ps01 + ji0_1*ps11 + ji0_2*ps12
    jp0_2 = ji0_0*ps02 + ji0_1*ps12 + ji0_2*ps22
    jp0_3 = ji0_0*ps03 + ji0_1*ps13 + ji0_2*ps23
    jp0_4 = ji0_0*ps04 + ji0_1*ps14 + ji0_2*ps24
    jp0_5 = ji0_0*ps05 + ji0_1*ps15 + ji0_2*ps25
    jp1_0 = ji1_0*ps00 + ji1_1*ps01 + ji1_2*ps02
    jp1_1 = ji1_0*ps01 + ji1_1*ps11 + ji1_2*ps12
    jp1_2 = ji1_0*ps02 + ji1_1*ps12 + ji1_2*ps22
    jp1_3 = ji1_0*ps03 + ji1_1*ps13 + ji1_2*ps23
    jp1_4 = ji1_0*ps04 + ji1_1*ps14 + ji1_2*ps24
    jp1_5 = ji1_0*ps05 + ji1_1*ps15 + ji1_2*ps25
    jp3_3 = ji3_3*ps33 + ji3_4*ps34 + ji3_5*ps35
    jp3_4 = ji3_3*ps34 + ji3_4*ps44 + ji3_5*ps45
    jp3_5 = ji3_3*ps35 + ji3_4*ps45 + ji3_5*ps55
    jp4_3 = ji4_3*ps33 + ji4_4*ps34 + ji4_5*ps35
    jp4_4 = ji4_3*ps34 + ji4_4*ps44 + ji4_5*ps45
    jp4_5 = ji4_3*ps35 + ji4_4*ps45 + ji4_5*ps55
    dm2_3 = ji3_3*ps23 + ji3_4*ps24 + ji3_5*ps25 - pq23
    dm2_4 = ji4_3*ps23 + ji4_4*ps24 + ji4_5*ps25 - pq24
    lw1_0 = ll1_0*pq00
    lw2_0 = ll2_0*pq00
    lw3_0 = ll3_0*pq00
    lw4_0 = ll4_0*pq00
    lw5_0 = ll5_0*pq00
    _t12 = -pq11
    dm0_0 = ji0_0*jp0_0 + ji0_1*jp0_1 + ji0_2*jp0_2 - pq00
    dm0_1 = ji1_0*jp0_0 + ji1_1*jp0_1 + ji1_2*jp0_2 - pq01
    dm0_2 = jp0_2 - pq02
    dm0_3 = ji3_3*jp0_3 + ji3_4*jp0_4 + ji3_5*jp0_5 - pq03
    dm0_4 = ji4_3*jp0_3 + ji4_4*jp0_4 + ji4_5*jp0_5 - pq04
    dm0_5 = jp0_5 - pq05
    dm1_1 = _t12 + ji1_0*jp1_0 + ji1_1*jp1_1 + ji1_2*jp1_2
    dm1_2 = jp1_2 - pq12
    dm1_3 = ji3_3*jp1_3 + ji3_4*jp1_4 + ji3_5*jp1_5 - pq13
    dm1_4 = ji4_3*jp1_3 + ji4_4*jp1_4 + ji4_5*jp1_5 - pq14
    dm1_5 = jp1_5 - pq15
    dm3_3 = ji3_3*jp3_3 + ji3_4*jp3_4 + ji3_5*jp3_5 - pq33
    dm3_4 = ji4_3*jp3_3 + ji4_4*jp3_4 + ji4_5*jp3_5 - pq34
    dm3_5 = jp3_5 - pq35
    dm4_4 = ji4_3*jp4_3 + ji4_4*jp4_4 + ji4_5*jp4_5 - pq44
    dm4_5 = jp4_5 - pq45
    ld1 = -_t12 - ll1_0*lw1_0
    ly0_1 = -(cf0_0*ll1_0) + cf0_1
    ly1_1 = -(cf1_0*ll1_0) + cf1_1
    ly2_1 = -(cf2_0*ll1_0) + cf2_1
    ly3_1 = -(cf3_0*ll1_0) + cf3_1
    ly4_1 = -(cf4_0*ll1_0) + cf4_1
    ly5_1 = -(cf5_0*ll1_0) + cf5_1
    lr1 = 1.0/max(1e-300, ld1)
    ll2_1 = lr1*(-(ll2_0*lw1_0) + pq12)
    ll3_1 = lr1*(-(ll3_0*lw1_0) + pq13)
    ll4_1 = lr1*(-(ll4_0*lw1_0) + pq14)
    ll5_1 = lr1*(-(ll5_0*lw1_0) + pq15)
    lw2_1 = ld1*ll2_1
    lw3_1 = ld1*ll3_1
    lw4_1 = ld1*ll4_1
    lw5_1 = ld1*ll5_1
    ly0_2 = -(cf0_0*ll2_0) + cf0_2 - ll2_1*ly0_1
    ly1_2 = -(cf1_0*ll2_0) + cf1_2 - ll2_1*ly1_1
    ly2_2 = -(cf2_0*ll2_0) + cf2_2 - ll2_1*ly2_1
    ly3_2 = -(cf3_0*ll2_0) + cf3_2 - ll2_1*ly3_1
    ly4_2 = -(cf4_0*ll2_0) + cf4_2 - ll2_1*ly4_1
    ly5_2 = -(cf5_0*ll2_0) + cf5_2 - ll2_1*ly5_1
    ld2 = -(ll2_0*lw2_0) - ll2_1*lw2_1 + pq22
    lr2 = 1.0/max(1e-300, ld2)
    ll3_2 = lr2*(-(ll3_0*lw2_0) - ll3_1*lw2_1 + pq23)
    ll4_2 = lr2*(-(ll4_0*lw2_0) - ll4_1*lw2_1 + pq24)
    ll5_2 = lr2*(-(ll5_0*lw2_0) - ll5_1*lw2_1 + pq25)
    lw3_2 = ld2*ll3_2
    lw4_2 = ld2*ll4_2
    lw5_2 = ld2*ll5_2
    ly0_3 = -(cf0_0*ll3_0) - ll3_1*ly0_1 - ll3_2*ly0_2 + pf03
    ly1_3 = -(cf1_0*ll3_0) - ll3_1*ly1_1 - ll3_2*ly1_2 + pf13
    ly2_3 = -(cf2_0*ll3_0) - ll3_1*ly2_1 - ll3_2*ly2_2 + pf23
    ly3_3 = -(cf3_0*ll3_0) - ll3_1*ly3_1 - ll3_2*ly3_2 + pf33
    ly4_3 = -(cf4_0*ll3_0) - ll3_1*ly4_1 - ll3_2*ly4_2 + pf34
    ly5_3 = -(cf5_0*ll3_0) - ll3_1*ly5_1 - ll3_2*ly5_2 + pf35
    ld3 = -(ll3_0*lw3_0) - ll3_1*lw3_1 - ll3_2*lw3_2 + pq33
    lr3 = 1.0/max(1e-300, ld3)
    ll4_3 = lr3*(-(ll4_0*lw3_0) - ll4_1*lw3_1 - ll4_2*lw3_2 + pq34)
    ll5_3 = lr3*(-(ll5_0*lw3_0) - ll5_1*lw3_1 - ll5_2*lw3_2 + pq35)
    lw4_3 = ld3*ll4_3
    lw5_3 = ld3*ll5_3
    ly0_4 = -(cf0_0*ll4_0) - ll4_1*ly0_1 - ll4_2*ly0_2 - ll4_3*ly0_3 + pf04
    ly1_4 = -(cf1_0*ll4_0) - ll4_1*ly1_1 - ll4_2*ly1_2 - ll4_3*ly1_3 + pf14
    ly2_4 = -(cf2_0*ll4_0) - ll4_1*ly2_1 - ll4_2*ly2_2 - ll4_3*ly2_3 + pf24
    ly3_4 = -(cf3_0*ll4_0) - ll4_1*ly3_1 - ll4_2*ly3_2 - ll4_3*ly3_3 + pf34
    ly4_4 = -(cf4_0*ll4_0) - ll4_1*ly4_1 - ll4_2*ly4_2 - ll4_3*ly4_3 + pf44
    ly5_4 = -(cf5_0*ll4_0) - ll4_1*ly5_1 - ll4_2*ly5_2 - ll4_3*ly5_3 + pf45
    ld4 = -(ll4_0*lw4_0) - ll4_1*lw4_1 - ll4_2*lw4_2 - ll4_3*lw4_3 + pq44
    lr4 = 1.0/max(1e-300, ld4)
    ll5_4 = lr4*(-(ll5_0*lw4_0) - ll5_1*lw4_1 - ll5_2*lw4_2 - ll5_3*lw4_3 + pq45)
    lw5_4 = ld4*ll5_4
    ly0_5 = -(cf0_0*ll5_0) - ll5_1*ly0_1 - ll5_2*ly0_2 - ll5_3*ly0_3 - ll5_4*ly0_4 + pf05
    ly1_5 = -(cf1_0*ll5_0) - ll5_1*ly1_1 - ll5_2*ly1_2 - ll5_3*ly1_3 - ll5_4*ly1_4 + pf15
    ly2_5 = -(cf2_0*ll5_0) - ll5_1*ly2_1 - ll5_2*ly2_2 - ll5_3*ly2_3 - ll5_4*ly2_4 + pf25
    ly3_5 = -(cf3_0*ll5_0) - ll5_1*ly3_1 - ll5_2*ly3_2 - ll5_3*ly3_3 - ll5_4*ly3_4 + pf35
    ly4_5 = -(cf4_0*ll5_0) - ll5_1*ly4_1 - ll5_2*ly4_2 - ll5_3*ly4_3 - ll5_4*ly4_4 + pf45
    ly5_5 = -(cf5_0*ll5_0) - ll5_1*ly5_1 - ll5_2*ly5_2 - ll5_3*ly5_3 - ll5_4*ly5_4 + pf55
    ld5 = -(ll5_0*lw5_0) - ll5_1*lw5_1 - ll5_2*lw5_2 - ll5_3*lw5_3 - ll5_4*lw5_4 + pq55
    lr5 = 1.0/max(1e-300, ld5)
    gg0_5 = lr5*ly0_5
    gg1_5 = lr5*ly1_5
    gg2_5 = lr5*ly2_5
    gg3_5 = lr5*ly3_5
    gg4_5 = lr5*ly4_5
    gg5_5 = lr5*ly5_5
    gg0_4 = -(gg0_5*ll5_4) + lr4*ly0_4
    gg1_4 = -(gg1_5*ll5_4) + lr4*ly1_4
    gg2_4 = -(gg2_5*ll5_4) + lr4*ly2_4
    gg3_4 = -(gg3_5*ll5_4) + lr4*ly3_4
    gg4_4 = -(gg4_5*ll5_4) + lr4*ly4_4
    gg5_4 = -(gg5_5*ll5_4) + lr4*ly5_4
    gg0_3 = -(gg0_4*ll4_3) - gg0_5*ll5_3 + lr3*ly0_3
    gg1_3 = -(gg1_4*ll4_3) - gg1_5*ll5_3 + lr3*ly1_3
    gg2_3 = -(gg2_4*ll4_3) - gg2_5*ll5_3 + lr3*ly2_3
    gg3_3 = -(gg3_4*ll4_3) - gg3_5*ll5_3 + lr3*ly3_3
    gg4_3 = -(gg4_4*ll4_3) - gg4_5*ll5_3 + lr3*ly4_3
    gg5_3 = -(gg5_4*ll4_3) - gg5_5*ll5_3 + lr3*ly5_3
    gg0_2 = -(gg0_3*ll3_2) - gg0_4*ll4_2 - gg0_5*ll5_2 + lr2*ly0_2
    gg1_2 = -(gg1_3*ll3_2) - gg1_4*ll4_2 - gg1_5*ll5_2 + lr2*ly1_2
    gg2_2 = -(gg2_3*ll3_2) - gg2_4*ll4_2 - gg2_5*ll5_2 + lr2*ly2_2
    gg3_2 = -(gg3_3*ll3_2) - gg3_4*ll4_2 - gg3_5*ll5_2 + lr2*ly3_2
    gg4_2 = -(gg4_3*ll3_2) - gg4_4*ll4_2 - gg4_5*ll5_2 + lr2*ly4_2
    gg5_2 = -(gg5_3*ll3_2) - gg5_4*ll4_2 - gg5_5*ll5_2 + lr2*ly5_2
    gg0_1 = -(gg0_2*ll2_1) - gg0_3*ll3_1 - gg0_4*ll4_1 - gg0_5*ll5_1 + lr1*ly0_1
    gg1_1 = -(gg1_2*ll2_1) - gg1_3*ll3_1 - gg1_4*ll4_1 - gg1_5*ll5_1 + lr1*ly1_1
    gg2_1 = -(gg2_2*ll2_1) - gg2_3*ll3_1 - gg2_4*ll4_1 - gg2_5*ll5_1 + lr1*ly2_1
    gg3_1 = -(gg3_2*ll2_1) - gg3_3*ll3_1 - gg3_4*ll4_1 - gg3_5*ll5_1 + lr1*ly3_1
    gg4_1 = -(gg4_2*ll2_1) - gg4_3*ll3_1 - gg4_4*ll4_1 - gg4_5*ll5_1 + lr1*ly4_1
    gg5_1 = -(gg5_2*ll2_1) - gg5_3*ll3_1 - gg5_4*ll4_1 - gg5_5*ll5_1 + lr1*ly5_1
    gg0_0 = cf0_0*lr0 - gg0_1*ll1_0 - gg0_2*ll2_0 - gg0_3*ll3_0 - gg0_4*ll4_0 - gg0_5*ll5_0
    gg1_0 = cf1_0*lr0 - gg1_1*ll1_0 - gg1_2*ll2_0 - gg1_3*ll3_0 - gg1_4*ll4_0 - gg1_5*ll5_0
    gg2_0 = cf2_0*lr0 - gg2_1*ll1_0 - gg2_2*ll2_0 - gg2_3*ll3_0 - gg2_4*ll4_0 - gg2_5*ll5_0
    gg3_0 = cf3_0*lr0 - gg3_1*ll1_0 - gg3_2*ll2_0 - gg3_3*ll3_0 - gg3_4*ll4_0 - gg3_5*ll5_0
    gg4_0 = cf4_0*lr0 - gg4_1*ll1_0 - gg4_2*ll2_0 - gg4_3*ll3_0 - gg4_4*ll4_0 - gg4_5*ll5_0
    gg5_0 = cf5_0*lr0 - gg5_1*ll1_0 - gg5_2*ll2_0 - gg5_3*ll3_0 - gg5_4*ll4_0 - gg5_5*ll5_0
    de0_0 = dd0_0*gg0_0 + dd0_1*gg0_1 + dd0_2*gg0_2 + dd0_3*gg0_3 + dd0_4*gg0_4 + dd0_5*gg0_5
    de1_0 = dd0_0*gg1_0 + dd0_1*gg1_1 + dd0_2*gg1_2 + dd0_3*gg1_3 + dd0_4*gg1_4 + dd0_5*gg1_5
    de2_0 = dd0_0*gg2_0 + dd0_1*gg2_1 + dd0_2*gg2_2 + dd0_3*gg2_3 + dd0_4*gg2_4 + dd0_5*gg2_5
    de3_0 = dd0_0*gg3_0 + dd0_1*gg3_1 + dd0_2*gg3_2 + dd0_3*gg3_3 + dd0_4*gg3_4 + dd0_5*gg3_5
    de4_0 = dd0_0*gg4_0 + dd0_1*gg4_1 + dd0_2*gg4_2 + dd0_3*gg4_3 + dd0_4*gg4_4 + dd0_5*gg4_5
    de5_0 = dd0_0*gg5_0 + dd0_1*gg5_1 + dd0_2*gg5_2 + dd0_3*gg5_3 + dd0_4*gg5_4 + dd0_5*gg5_5
    gd0_0 = dm0_0*gg0_0 + dm0_1*gg0_1 + dm0_2*gg0_2 + dm0_3*gg0_3 + dm0_4*gg0_4 + dm0_5*gg0_5
    gd0_1 = dm0_1*gg0_0 + dm1_1*gg0_1 + dm1_2*gg0_2 + dm1_3*gg0_3 + dm1_4*gg0_4 + dm1_5*gg0_5
    gd0_2 = dm0_2*gg0_0 + dm1_2*gg0_1 + dm2_2*gg0_2 + dm2_3*gg0_3 + dm2_4*gg0_4 + dm2_5*gg0_5
    gd0_3 = dm0_3*gg0_0 + dm1_3*gg0_1 + dm2_3*gg0_2 + dm3_3*gg0_3 + dm3_4*gg0_4 + dm3_5*gg0_5
    gd0_4 = dm0_4*gg0_0 + dm1_4*gg0_1 + dm2_4*gg0_2 + dm3_4*gg0_3 + dm4_4*gg0_4 + dm4_5*gg0_5
    gd0_5 = dm0_5*gg0_0 + dm1_5*gg0_1 + dm2_5*gg0_2 + dm3_5*gg0_3 + dm4_5*gg0_4 + dm5_5*gg0_5
    gd1_0 = dm0_0*gg1_0 + dm0_1*gg1_1 + dm0_2*gg1_2 + dm0_3*gg1_3 + dm0_4*gg1_4 + dm0_5*gg1_5
    gd1_1 = dm0_1*gg1_0 + dm1_1*gg1_1 + dm1_2*gg1_2 + dm1_3*gg1_3 + dm1_4*gg1_4 + dm1_5*gg1_5
    gd1_2 = dm0_2*gg1_0 + dm1_2*gg1_1 + dm2_2*gg1_2 + dm2_3*gg1_3 + dm2_4*gg1_4 + dm2_5*gg1_5
    gd1_3 = dm0_3*gg1_0 + dm1_3*gg1_1 + dm2_3*gg1_2 + dm3_3*gg1_3 + dm3_4*gg1_4 + dm3_5*gg1_5
    gd1_4 = dm0_4*gg1_0 + dm1_4*gg1_1 + dm2_4*gg1_2 + dm3_4*gg1_3 + dm4_4*gg1_4 + dm4_5*gg1_5
    gd1_5 = dm0_5*gg1_0 + dm1_5*gg1_1 + dm2_5*gg1_2 + dm3_5*gg1_3 + dm4_5*gg1_4 + dm5_5*gg1_5
    gd2_0 = dm0_0*gg2_0 + dm0_1*gg2_1 + dm0_2*gg2_2 + dm0_3*gg2_3 + dm0_4*gg2_4 + dm0_5*gg2_5
    gd2_1 = dm0_1*gg2_0 + dm1_1*gg2_1 + dm1_2*gg2_2 + dm1_3*gg2_3 + dm1_4*gg2_4 + dm1_5*gg2_5
    gd2_2 = dm0_2*gg2_0 + dm1_2*gg2_1 + dm2_2*gg2_2 + dm2_3*gg2_3 + dm2_4*gg2_4 + dm2_5*gg2_5
    gd2_3 = dm0_3*gg2_0 + dm1_3*gg2_1 + dm2_3*gg2_2 + dm3_3*gg2_3 + dm3_4*gg2_4 + dm3_5*gg2_5
    gd2_4 = dm0_4*gg2_0 + dm1_4*gg2_1 + dm2_4*gg2_2 + dm3_4*gg2_3 + dm4_4*gg2_4 + dm4_5*gg2_5
    gd2_5 = dm0_5*gg2_0 + dm1_5*gg2_1 + dm2_5*gg2_2 + dm3_5*gg2_3 + dm4_5*gg2_4 + dm5_5*gg2_5
    gd3_0 = dm0_0*gg3_0 + dm0_1*gg3_1 + dm0_2*gg3_2 + dm0_3*gg3_3 + dm0_4*gg3_4 + dm0_5*gg3_5
    gd3_1 = dm0_1*gg3_0 + dm1_1*gg3_1 + dm1_2*gg3_2 + dm1_3*gg3_3 + dm1_4*gg3_4 + dm1_5*gg3_5
    gd3_2 = dm0_2*gg3_0 + dm1_2*gg3_1 + dm2_2*gg3_2 + dm2_3*gg3_3 + dm2_4*gg3_4 + dm2_5*gg3_5
    gd3_3 = dm0_3*gg3_0 + dm1_3*gg3_1 + dm2_3*gg3_2 + dm3_3*gg3_3 + dm3_4*gg3_4 + dm3_5*gg3_5
    gd3_4 = dm0_4*gg3_0 + dm1_4*gg3_1 + dm2_4*gg3_2 + dm3_4*gg3_3 + dm4_4*gg3_4 + dm4_5*gg3_5
    gd3_5 = dm0_5*gg3_0 + dm1_5*gg3_1 + dm2_5*gg3_2 + dm3_5*gg3_3 + dm4_5*gg3_4 + dm5_5*gg3_5
    gd4_0 = dm0_0*gg4_0 + dm0_1*gg4_1 + dm0_2*gg4_2 + dm0_3*gg4_3 + dm0_4*gg4_4 + dm0_5*gg4_5
    gd4_1 = dm0_1*gg4_0 + dm1_1*gg4_1 + dm1_2*gg4_2 + dm1_3*gg4_3 + dm1_4*gg4_4 + dm1_5*gg4_5
    gd4_2 = dm0_2*gg4_0 + dm1_2*gg4_1 + dm2_2*gg4_2 + dm2_3*gg4_3 + dm2_4*gg4_4 + dm2_5*gg4_5
    gd4_3 = dm0_3*gg4_0 + dm1_3*gg4_1 + dm2_3*gg4_2 + dm3_3*gg4_3 + dm3_4*gg4_4 + dm3_5*gg4_5
    gd4_4 = dm0_4*gg4_0 + dm1_4*gg4_1 + dm2_4*gg4_2 + dm3_4*gg4_3 + dm4_4*gg4_4 + dm4_5*gg4_5
    gd4_5 = dm0_5*gg4_0 + dm1_5*gg4_1 + dm2_5*gg4_2 + dm3_5*gg4_3 + dm4_5*gg4_4 + dm5_5*gg4_5
    gd5_0 = dm0_0*gg5_0 + dm0_1*gg5_1 + dm0_2*gg5_2 + dm0_3*gg5_3 + dm0_4*gg5_4 + dm0_5*gg5_5
    gd5_1 = dm0_1*gg5_0 + dm1_1*gg5_1 + dm1_2*gg5_2 + dm1_3*gg5_3 + dm1_4*gg5_4 + dm1_5*gg5_5
    gd5_2 = dm0_2*gg5_0 + dm1_2*gg5_1 + dm2_2*gg5_2 + dm2_3*gg5_3 + dm2_4*gg5_4 + dm2_5*gg5_5
    gd5_3 = dm0_3*gg5_0 + dm1_3*gg5_1 + dm2_3*gg5_2 + dm3_3*gg5_3 + dm3_4*gg5_4 + dm3_5*gg5_5
    gd5_4 = dm0_4*gg5_0 + dm1_4*gg5_1 + dm2_4*gg5_2 + dm3_4*gg5_3 + dm4_4*gg5_4 + dm4_5*gg5_5
    gd5_5 = dm0_5*gg5_0 + dm1_5*gg5_1 + dm2_5*gg5_2 + dm3_5*gg5_3 + dm4_5*gg5_4 + dm5_5*gg5_5
    _sin_de2_0 = math.sin(de2_0)
    _cos_de2_0 = math.cos(de2_0)
    _sinc_de2_0, _cosc_de2_0, _sinc2_de2_0, _cosc2_de2_0 = sinc_family(de2_0, _sin_de2_0, _cos_de2_0)
    _sin_de5_0 = math.sin(de5_0)
    _cos_de5_0 = math.cos(de5_0)
    _sinc_de5_0, _cosc_de5_0, _sinc2_de5_0, _cosc2_de5_0 = sinc_family(de5_0, _sin_de5_0, _cos_de5_0)
    pt0_0 = gd0_0*gg0_0 + gd0_1*gg0_1 + gd0_2*gg0_2 + gd0_3*gg0_3 + gd0_4*gg0_4 + gd0_5*gg0_5 + pf00
    pt0_1 = gd0_0*gg1_0 + gd0_1*gg1_1 + gd0_2*gg1_2 + gd0_3*gg1_3 + gd0_4*gg1_4 + gd0_5*gg1_5 + pf01
    pt0_2 = gd0_0*gg2_0 + gd0_1*gg2_1 + gd0_2*gg2_2 + gd0_3*gg2_3 + gd0_4*gg2_4 + gd0_5*gg2_5 + pf02
    pt0_3 = gd0_0*gg3_0 + gd0_1*gg3_1 + gd0_2*gg3_2 + gd0_3*gg3_3 + gd0_4*gg3_4 + gd0_5*gg3_5 + pf03
    pt0_4 = gd0_0*gg4_0 + gd0_1*gg4_1 + gd0_2*gg4_2 + gd0_3*gg4_3 + gd0_4*gg4_4 + gd0_5*gg4_5 + pf04
    pt0_5 = gd0_0*gg5_0 + gd0_1*gg5_1 + gd0_2*gg5_2 + gd0_3*gg5_3 + gd0_4*gg5_4 + gd0_5*gg5_5 + pf05
    pt1_1 = gd1_0*gg1_0 + gd1_1*gg1_1 + gd1_2*gg1_2 + gd1_3*gg1_3 + gd1_4*gg1_4 + gd1_5*gg1_5 + pf11
    pt1_2 = gd1_0*gg2_0 + gd1_1*gg2_1 + gd1_2*gg2_2 + gd1_3*gg2_3 + gd1_4*gg2_4 + gd1_5*gg2_5 + pf12
    pt1_3 = gd1_0*gg3_0 + gd1_1*gg3_1 + gd1_2*gg3_2 + gd1_3*gg3_3 + gd1_4*gg3_4 + gd1_5*gg3_5 + pf13
    pt1_4 = gd1_0*gg4_0 + gd1_1*gg4_1 + gd1_2*gg4_2 + gd1_3*gg4_3 + gd1_4*gg4_4 + gd1_5*gg4_5 + pf14
    pt1_5 = gd1_0*gg5_0 + gd1_1*gg5_1 + gd1_2*gg5_2 + gd1_3*gg5_3 + gd1_4*gg5_4 + gd1_5*gg5_5 + pf15
    pt2_2 = gd2_0*gg2_0 + gd2_1*gg2_1 + gd2_2*gg2_2 + gd2_3*gg2_3 + gd2_4*gg2_4 + gd2_5*gg2_5 + pf22
    pt2_3 = gd2_0*gg3_0 + gd2_1*gg3_1 + gd2_2*gg3_2 + gd2_3*gg3_3 + gd2_4*gg3_4 + gd2_5*gg3_5 + pf23
    pt2_4 = gd2_0*gg4_0 + gd2_1*gg4_1 + gd2_2*gg4_2 + gd2_3*gg4_3 + gd2_4*gg4_4 + gd2_5*gg4_5 + pf24
    pt2_5 = gd2_0*gg5_0 + gd2_1*gg5_1 + gd2_2*gg5_2 + gd2_3*gg5_3 + gd2_4*gg5_4 + gd2_5*gg5_5 + pf25
    pt3_3 = gd3_0*gg3_0 + gd3_1*gg3_1 + gd3_2*gg3_2 + gd3_3*gg3_3 + gd3_4*gg3_4 + gd3_5*gg3_5 + pf33
    pt3_4 = gd3_0*gg4_0 + gd3_1*gg4_1 + gd3_2*gg4_2 + gd3_3*gg4_3 + gd3_4*gg4_4 + gd3_5*gg4_5 + pf34
    pt3_5 = gd3_0*gg5_0 + gd3_1*gg5_1 + gd3_2*gg5_2 + gd3_3*gg5_3 + gd3_4*gg5_4 + gd3_5*gg5_5 + pf35
    pt4_4 = gd4_0*gg4_0 + gd4_1*gg4_1 + gd4_2*gg4_2 + gd4_3*gg4_3 + gd4_4*gg4_4 + gd4_5*gg4_5 + pf44
    pt4_5 = gd4_0*gg5_0 + gd4_1*gg5_1 + gd4_2*gg5_2 + gd4_3*gg5_3 + gd4_4*gg5_4 + gd4_5*gg5_5 + pf45
    pt5_5 = gd5_0*gg5_0 + gd5_1*gg5_1 + gd5_2*gg5_2 + gd5_3*gg5_3 + gd5_4*gg5_4 + gd5_5*gg5_5 + pf55
    ph0_0 = _sinc_de2_0
    ph0_1 = _cosc_de2_0
    ph0_2 = -(_cosc2_de2_0*de1_0) + _sinc2_de2_0*de0_0
    ph1_0 = -_cosc_de2_0
    ph1_1 = _sinc_de2_0
    ph1_2 = _cosc2_de2_0*de0_0 + _sinc2_de2_0*de1_0
    ph3_3 = _sinc_de5_0
    ph3_4 = _cosc_de5_0
    ph3_5 = -(_cosc2_de5_0*de4_0) + _sinc2_de5_0*de3_0
    ph4_3 = -_cosc_de5_0
    ph4_4 = _sinc_de5_0
    ph4_5 = _cosc2_de5_0*de3_0 + _sinc2_de5_0*de4_0
    tp0_0 = ph0_0*pt0_0 + ph0_1*pt0_1 + ph0_2*pt0_2
    tp0_1 = ph0_0*pt0_1 + ph0_1*pt1_1 + ph0_2*pt1_2
    tp0_2 = ph0_0*pt0_2 + ph0_1*pt1_2 + ph0_2*pt2_2
    tp0_3 = ph0_0*pt0_3 + ph0_1*pt1_3 + ph0_2*pt2_3
    tp0_4 = ph0_0*pt0_4 + ph0_1*pt1_4 + ph0_2*pt2_4
    tp0_5 = ph0_0*pt0_5 + ph0_1*pt1_5 + ph0_2*pt2_5
    tp1_0 = ph1_0*pt0_0 + ph1_1*pt0_1 + ph1_2*pt0_2
    tp1_1 = ph1_0*pt0_1 + ph1_1*pt1_1 + ph1_2*pt1_2
    tp1_2 = ph1_0*pt0_2 + ph1_1*pt1_2 + ph1_2*pt2_2
    tp1_3 = ph1_0*pt0_3 + ph1_1*pt1_3 + ph1_2*pt2_3
    tp1_4 = ph1_0*pt0_4 + ph1_1*pt1_4 + ph1_2*pt2_4
    tp1_5 = ph1_0*pt0_5 + ph1_1*pt1_5 + ph1_2*pt2_5
    tp3_3 = ph3_3*pt3_3 + ph3_4*pt3_4 + ph3_5*pt3_5
    tp3_4 = ph3_3*pt3_4 + ph3_4*pt4_4 + ph3_5*pt4_5
    tp3_5 = ph3_3*pt3_5 + ph3_4*pt4_5 + ph3_5*pt5_5
    tp4_3 = ph4_3*pt3_3 + ph4_4*pt3_4 + ph4_5*pt3_5
    tp4_4 = ph4_3*pt3_4 + ph4_4*pt4_4 + ph4_5*pt4_5
    tp4_5 = ph4_3*pt3_5 + ph4_4*pt4_5 + ph4_5*pt5_5
    _t13 = -(_cosc_de2_0*de1_0) + _sinc_de2_0*de0_0
    _t14 = _cosc_de2_0*de0_0 + _sinc_de2_0*de1_0
    _t15 = -(_cosc_de5_0*de4_0) + _sinc_de5_0*de3_0
    _t16 = _cosc_de5_0*de3_0 + _sinc_de5_0*de4_0
    _t17 = _cos_de5_0*s_omega + _sin_de5_0*c_omega
    p_sm[k, 0] = ph0_0*tp0_0 + ph0_1*tp0_1 + ph0_2*tp0_2
    p_sm[k, 1] = ph1_0*tp0_0 + ph1_1*tp0_1 + ph1_2*tp0_2
    p_sm[k, 2] = tp0_2
    p_sm[k, 3] = ph3_3*tp0_3 + ph3_4*tp0_4 + ph3_5*tp0_5
    p_sm[k, 4] = ph4_3*tp0_3 + ph4_4*tp0_4 + ph4_5*tp0_5
    p_sm[k, 5] = tp0_5
    p_sm[k, 6] = ph1_0*tp1_0 + ph1_1*tp1_1 + ph1_2*tp1_2
    p_sm[k, 7] = tp1_2
    p_sm[k, 8] = ph3_3*tp1_3 + ph3_4*tp1_4 + ph3_5*tp1_5
    p_sm[k, 9] = ph4_3*tp1_3 + ph4_4*tp1_4 + ph4_5*tp1_5
    p_sm[k, 10] = tp1_5
    p_sm[k, 11] = pt2_2
    p_sm[k, 12] = ph3_3*pt2_3 + ph3_4*pt2_4 + ph3_5*pt2_5
    p_sm[k, 13] = ph4_3*pt2_3 + ph4_4*pt2_4 + ph4_5*pt2_5
    p_sm[k, 14] = pt2_5
    p_sm[k, 15] = ph3_3*tp3_3 + ph3_4*tp3_4 + ph3_5*tp3_5
    p_sm[k, 16] = ph4_3*tp3_3 + ph4_4*tp3_4 + ph4_5*tp3_5
    p_sm[k, 17] = tp3_5
    p_sm[k, 18] = ph4_3*tp4_3 + ph4_4*tp4_4 + ph4_5*tp4_5
    p_sm[k, 19] = tp4_5
    p_sm[k, 20] = pt5_5
    s_sm[k, 0] = _t13*c_theta - _t14*s_theta + x
    s_sm[k, 1] = _t13*s_theta + _t14*c_theta + y
    s_sm[k, 2] = _cos_de2_0*c_theta - _sin_de2_0*s_theta
    s_sm[k, 3] = _cos_de2_0*s_theta + _sin_de2_0*c_theta
    s_sm[k, 4] = _t15*c_omega - _t16*s_omega + v_x
    s_sm[k, 5] = _t15*s_omega + _t16*c_omega + v_y
    s_sm[k, 6] = wrap_angle_sum(de5_0 + omega, _t17)
    s_sm[k, 7] = _cos_de5_0*c_omega - _sin_de5_0*s_omega
    s_sm[k, 8] = _t17


@nb.njit(inline="always", fastmath={"contract"}, error_model="numpy")
def lane_smooth(W, j):
    """smooth_step on lane j of the work array W (rows: derive/codegen/smooth_step.py), without branches (SIMD).
    """
    x = W[0 + j]
    y = W[64 + j]
    c_theta = W[128 + j]
    s_theta = W[192 + j]
    v_x = W[256 + j]
    v_y = W[320 + j]
    omega = W[384 + j]
    c_omega = W[448 + j]
    s_omega = W[512 + j]
    pf00 = W[576 + j]
    pf01 = W[640 + j]
    pf02 = W[704 + j]
    pf03 = W[768 + j]
    pf04 = W[832 + j]
    pf05 = W[896 + j]
    pf11 = W[960 + j]
    pf12 = W[1024 + j]
    pf13 = W[1088 + j]
    pf14 = W[1152 + j]
    pf15 = W[1216 + j]
    pf22 = W[1280 + j]
    pf23 = W[1344 + j]
    pf24 = W[1408 + j]
    pf25 = W[1472 + j]
    pf33 = W[1536 + j]
    pf34 = W[1600 + j]
    pf35 = W[1664 + j]
    pf44 = W[1728 + j]
    pf45 = W[1792 + j]
    pf55 = W[1856 + j]
    q_x = W[1920 + j]
    q_y = W[1984 + j]
    q_c_theta = W[2048 + j]
    q_s_theta = W[2112 + j]
    q_v_x = W[2176 + j]
    q_v_y = W[2240 + j]
    q_c_omega = W[2368 + j]
    q_s_omega = W[2432 + j]
    pq00 = W[2496 + j]
    pq01 = W[2560 + j]
    pq02 = W[2624 + j]
    pq03 = W[2688 + j]
    pq04 = W[2752 + j]
    pq05 = W[2816 + j]
    pq11 = W[2880 + j]
    pq12 = W[2944 + j]
    pq13 = W[3008 + j]
    pq14 = W[3072 + j]
    pq15 = W[3136 + j]
    pq22 = W[3200 + j]
    pq23 = W[3264 + j]
    pq24 = W[3328 + j]
    pq25 = W[3392 + j]
    pq33 = W[3456 + j]
    pq34 = W[3520 + j]
    pq35 = W[3584 + j]
    pq44 = W[3648 + j]
    pq45 = W[3712 + j]
    pq55 = W[3776 + j]
    t_x = W[3840 + j]
    t_y = W[3904 + j]
    t_c_theta = W[3968 + j]
    t_s_theta = W[4032 + j]
    t_v_x = W[4096 + j]
    t_v_y = W[4160 + j]
    t_c_omega = W[4288 + j]
    t_s_omega = W[4352 + j]
    ps00 = W[4416 + j]
    ps01 = W[4480 + j]
    ps02 = W[4544 + j]
    ps03 = W[4608 + j]
    ps04 = W[4672 + j]
    ps05 = W[4736 + j]
    ps11 = W[4800 + j]
    ps12 = W[4864 + j]
    ps13 = W[4928 + j]
    ps14 = W[4992 + j]
    ps15 = W[5056 + j]
    ps22 = W[5120 + j]
    ps23 = W[5184 + j]
    ps24 = W[5248 + j]
    ps25 = W[5312 + j]
    ps33 = W[5376 + j]
    ps34 = W[5440 + j]
    ps35 = W[5504 + j]
    ps44 = W[5568 + j]
    ps45 = W[5632 + j]
    ps55 = W[5696 + j]
    dt = W[7680 + j]
    _a0 = dt*omega
    _sin__a0 = sin_v(_a0)
    _cos__a0 = cos_v(_a0)
    _sinc__a0, _cosc__a0, _sinc2__a0, _cosc2__a0 = sinc_family(_a0, _sin__a0, _cos__a0)
    _a1 = atan2_v(q_c_omega*t_s_omega - q_s_omega*t_c_omega, q_c_omega*t_c_omega + q_s_omega*t_s_omega)
    _sin__a1 = sin_v(_a1)
    _cos__a1 = cos_v(_a1)
    _halfcot__a1 = halfcot_v(_a1, _sin__a1, _cos__a1)
    _a2 = atan2_v(q_c_theta*t_s_theta - q_s_theta*t_c_theta, q_c_theta*t_c_theta + q_s_theta*t_s_theta)
    _sin__a2 = sin_v(_a2)
    _cos__a2 = cos_v(_a2)
    _halfcot__a2 = halfcot_v(_a2, _sin__a2, _cos__a2)
    _t0 = c_omega*dt
    _t1 = dt*s_omega
    _t2 = dt*v_x
    _t3 = dt*v_y
    _t4 = -(q_c_theta*q_x) + q_c_theta*t_x - q_s_theta*q_y + q_s_theta*t_y
    _t5 = -(q_c_theta*q_y) + q_c_theta*t_y + q_s_theta*q_x - q_s_theta*t_x
    _t6 = _a2/2.0
    _t7 = -(q_c_omega*q_v_x) + q_c_omega*t_v_x - q_s_omega*q_v_y + q_s_omega*t_v_y
    _t8 = -(q_c_omega*q_v_y) + q_c_omega*t_v_y + q_s_omega*q_v_x - q_s_omega*t_v_x
    _t9 = _a1/2.0
    cc0_3 = _t0
    cc0_4 = -_t1
    cc1_3 = _t1
    cc1_4 = _t0
    ff0_0 = _cos__a0
    ff0_1 = _sin__a0
    ff0_2 = _cosc__a0*_t2 - _sinc__a0*_t3
    ff0_5 = dt*(-(_cosc2__a0*_t3) + _sinc2__a0*dt*v_x)
    ff1_0 = -_sin__a0
    ff1_1 = _cos__a0
    ff1_2 = _cosc__a0*_t3 + _sinc__a0*_t2
    ff1_5 = dt*(_cosc2__a0*_t2 + _sinc2__a0*_t3)
    cf0_2 = dt*pf05 + pf02
    cf1_2 = dt*pf15 + pf12
    cf2_2 = dt*pf25 + pf22
    cf3_2 = dt*pf35 + pf23
    cf4_2 = dt*pf45 + pf24
    cf5_2 = dt*pf55 + pf25
    dd0_0 = _halfcot__a2*_t4 + _t5*_t6
    dd0_1 = _halfcot__a2*_t5 - _t4*_t6
    dd0_2 = _a2
    dd0_3 = _halfcot__a1*_t7 + _t8*_t9
    dd0_4 = _halfcot__a1*_t8 - _t7*_t9
    dd0_5 = _a1
    dm2_2 = -pq22 + ps22
    dm2_5 = -pq25 + ps25
    dm5_5 = -pq55 + ps55
    lr0 = 1.0/max(1e-300, pq00)
    _sin_dd0_2 = sin_v(dd0_2)
    _cos_dd0_2 = cos_v(dd0_2)
    _halfcot_dd0_2 = halfcot_v(dd0_2, _sin_dd0_2, _cos_dd0_2)
    _halfcot1_dd0_2 = halfcot1_v(dd0_2, _sin_dd0_2, _cos_dd0_2)
    _sin_dd0_5 = sin_v(dd0_5)
    _cos_dd0_5 = cos_v(dd0_5)
    _halfcot_dd0_5 = halfcot_v(dd0_5, _sin_dd0_5, _cos_dd0_5)
    _halfcot1_dd0_5 = halfcot1_v(dd0_5, _sin_dd0_5, _cos_dd0_5)
    _t10 = dd0_2/2.0
    _t11 = dd0_5/2.0
    ff0_3 = _cosc__a0*cc1_3 + _sinc__a0*cc0_3
    ff0_4 = _cosc__a0*cc1_4 + _sinc__a0*cc0_4
    ff1_3 = -(_cosc__a0*cc0_3) + _sinc__a0*cc1_3
    ff1_4 = -(_cosc__a0*cc0_4) + _sinc__a0*cc1_4
    ji0_0 = _halfcot_dd0_2
    ji0_1 = -_t10
    ji0_2 = _halfcot1_dd0_2*dd0_0 + dd0_1/2.0
    ji1_0 = _t10
    ji1_1 = _halfcot_dd0_2
    ji1_2 = _halfcot1_dd0_2*dd0_1 - dd0_0/2.0
    ji3_3 = _halfcot_dd0_5
    ji3_4 = -_t11
    ji3_5 = _halfcot1_dd0_5*dd0_3 + dd0_4/2.0
    ji4_3 = _t11
    ji4_4 = _halfcot_dd0_5
    ji4_5 = _halfcot1_dd0_5*dd0_4 - dd0_3/2.0
    ll1_0 = lr0*pq01
    ll2_0 = lr0*pq02
    ll3_0 = lr0*pq03
    ll4_0 = lr0*pq04
    ll5_0 = lr0*pq05
    cf0_0 = ff0_0*pf00 + ff0_1*pf01 + ff0_2*pf02 + ff0_3*pf03 + ff0_4*pf04 + ff0_5*pf05
    cf0_1 = ff1_0*pf00 + ff1_1*pf01 + ff1_2*pf02 + ff1_3*pf03 + ff1_4*pf04 + ff1_5*pf05
    cf1_0 = ff0_0*pf01 + ff0_1*pf11 + ff0_2*pf12 + ff0_3*pf13 + ff0_4*pf14 + ff0_5*pf15
    cf1_1 = ff1_0*pf01 + ff1_1*pf11 + ff1_2*pf12 + ff1_3*pf13 + ff1_4*pf14 + ff1_5*pf15
    cf2_0 = ff0_0*pf02 + ff0_1*pf12 + ff0_2*pf22 + ff0_3*pf23 + ff0_4*pf24 + ff0_5*pf25
    cf2_1 = ff1_0*pf02 + ff1_1*pf12 + ff1_2*pf22 + ff1_3*pf23 + ff1_4*pf24 + ff1_5*pf25
    cf3_0 = ff0_0*pf03 + ff0_1*pf13 + ff0_2*pf23 + ff0_3*pf33 + ff0_4*pf34 + ff0_5*pf35
    cf3_1 = ff1_0*pf03 + ff1_1*pf13 + ff1_2*pf23 + ff1_3*pf33 + ff1_4*pf34 + ff1_5*pf35
    cf4_0 = ff0_0*pf04 + ff0_1*pf14 + ff0_2*pf24 + ff0_3*pf34 + ff0_4*pf44 + ff0_5*pf45
    cf4_1 = ff1_0*pf04 + ff1_1*pf14 + ff1_2*pf24 + ff1_3*pf34 + ff1_4*pf44 + ff1_5*pf45
    cf5_0 = ff0_0*pf05 + ff0_1*pf15 + ff0_2*pf25 + ff0_3*pf35 + ff0_4*pf45 + ff0_5*pf55
    cf5_1 = ff1_0*pf05 + ff1_1*pf15 + ff1_2*pf25 + ff1_3*pf35 + ff1_4*pf45 + ff1_5*pf55
    jp0_0 = ji0_0*ps00 + ji0_1*ps01 + ji0_2*ps02
    jp0_1 = ji0_0*ps01 + ji0_1*ps11 + ji0_2*ps12
    jp0_2 = ji0_0*ps02 + ji0_1*ps12 + ji0_2*ps22
    jp0_3 = ji0_0*ps03 + ji0_1*ps13 + ji0_2*ps23
    jp0_4 = ji0_0*ps04 + ji0_1*ps14 + ji0_2*ps24
    jp0_5 = ji0_0*ps05 + ji0_1*ps15 + ji0_2*ps25
    jp1_0 = ji1_0*ps00 + ji1_1*ps01 + ji1_2*ps02
    jp1_1 = ji1_0*ps01 + ji1_1*ps11 + ji1_2*ps12
    jp1_2 = ji1_0*ps02 + ji1_1*ps12 + ji1_2*ps22
    jp1_3 = ji1_0*ps03 + ji1_1*ps13 + ji1_2*ps23
    jp1_4 = ji1_0*ps04 + ji1_1*ps14 + ji1_2*ps24
    jp1_5 = ji1_0*ps05 + ji1_1*ps15 + ji1_2*ps25
    jp3_3 = ji3_3*ps33 + ji3_4*ps34 + ji3_5*ps35
    jp3_4 = ji3_3*ps34 + ji3_4*ps44 + ji3_5*ps45
    jp3_5 = ji3_3*ps35 + ji3_4*ps45 + ji3_5*ps55
    jp4_3 = ji4_3*ps33 + ji4_4*ps34 + ji4_5*ps35
    jp4_4 = ji4_3*ps34 + ji4_4*ps44 + ji4_5*ps45
    jp4_5 = ji4_3*ps35 + ji4_4*ps45 + ji4_5*ps55
    dm2_3 = ji3_3*ps23 + ji3_4*ps24 + ji3_5*ps25 - pq23
    dm2_4 = ji4_3*ps23 + ji4_4*ps24 + ji4_5*ps25 - pq24
    lw1_0 = ll1_0*pq00
    lw2_0 = ll2_0*pq00
    lw3_0 = ll3_0*pq00
    lw4_0 = ll4_0*pq00
    lw5_0 = ll5_0*pq00
    _t12 = -pq11
    dm0_0 = ji0_0*jp0_0 + ji0_1*jp0_1 + ji0_2*jp0_2 - pq00
    dm0_1 = ji1_0*jp0_0 + ji1_1*jp0_1 + ji1_2*jp0_2 - pq01
    dm0_2 = jp0_2 - pq02
    dm0_3 = ji3_3*jp0_3 + ji3_4*jp0_4 + ji3_5*jp0_5 - pq03
    dm0_4 = ji4_3*jp0_3 + ji4_4*jp0_4 + ji4_5*jp0_5 - pq04
    dm0_5 = jp0_5 - pq05
    dm1_1 = _t12 + ji1_0*jp1_0 + ji1_1*jp1_1 + ji1_2*jp1_2
    dm1_2 = jp1_2 - pq12
    dm1_3 = ji3_3*jp1_3 + ji3_4*jp1_4 + ji3_5*jp1_5 - pq13
    dm1_4 = ji4_3*jp1_3 + ji4_4*jp1_4 + ji4_5*jp1_5 - pq14
    dm1_5 = jp1_5 - pq15
    dm3_3 = ji3_3*jp3_3 + ji3_4*jp3_4 + ji3_5*jp3_5 - pq33
    dm3_4 = ji4_3*jp3_3 + ji4_4*jp3_4 + ji4_5*jp3_5 - pq34
    dm3_5 = jp3_5 - pq35
    dm4_4 = ji4_3*jp4_3 + ji4_4*jp4_4 + ji4_5*jp4_5 - pq44
    dm4_5 = jp4_5 - pq45
    ld1 = -_t12 - ll1_0*lw1_0
    ly0_1 = -(cf0_0*ll1_0) + cf0_1
    ly1_1 = -(cf1_0*ll1_0) + cf1_1
    ly2_1 = -(cf2_0*ll1_0) + cf2_1
    ly3_1 = -(cf3_0*ll1_0) + cf3_1
    ly4_1 = -(cf4_0*ll1_0) + cf4_1
    ly5_1 = -(cf5_0*ll1_0) + cf5_1
    lr1 = 1.0/max(1e-300, ld1)
    ll2_1 = lr1*(-(ll2_0*lw1_0) + pq12)
    ll3_1 = lr1*(-(ll3_0*lw1_0) + pq13)
    ll4_1 = lr1*(-(ll4_0*lw1_0) + pq14)
    ll5_1 = lr1*(-(ll5_0*lw1_0) + pq15)
    lw2_1 = ld1*ll2_1
    lw3_1 = ld1*ll3_1
    lw4_1 = ld1*ll4_1
    lw5_1 = ld1*ll5_1
    ly0_2 = -(cf0_0*ll2_0) + cf0_2 - ll2_1*ly0_1
    ly1_2 = -(cf1_0*ll2_0) + cf1_2 - ll2_1*ly1_1
    ly2_2 = -(cf2_0*ll2_0) + cf2_2 - ll2_1*ly2_1
    ly3_2 = -(cf3_0*ll2_0) + cf3_2 - ll2_1*ly3_1
    ly4_2 = -(cf4_0*ll2_0) + cf4_2 - ll2_1*ly4_1
    ly5_2 = -(cf5_0*ll2_0) + cf5_2 - ll2_1*ly5_1
    ld2 = -(ll2_0*lw2_0) - ll2_1*lw2_1 + pq22
    lr2 = 1.0/max(1e-300, ld2)
    ll3_2 = lr2*(-(ll3_0*lw2_0) - ll3_1*lw2_1 + pq23)
    ll4_2 = lr2*(-(ll4_0*lw2_0) - ll4_1*lw2_1 + pq24)
    ll5_2 = lr2*(-(ll5_0*lw2_0) - ll5_1*lw2_1 + pq25)
    lw3_2 = ld2*ll3_2
    lw4_2 = ld2*ll4_2
    lw5_2 = ld2*ll5_2
    ly0_3 = -(cf0_0*ll3_0) - ll3_1*ly0_1 - ll3_2*ly0_2 + pf03
    ly1_3 = -(cf1_0*ll3_0) - ll3_1*ly1_1 - ll3_2*ly1_2 + pf13
    ly2_3 = -(cf2_0*ll3_0) - ll3_1*ly2_1 - ll3_2*ly2_2 + pf23
    ly3_3 = -(cf3_0*ll3_0) - ll3_1*ly3_1 - ll3_2*ly3_2 + pf33
    ly4_3 = -(cf4_0*ll3_0) - ll3_1*ly4_1 - ll3_2*ly4_2 + pf34
    ly5_3 = -(cf5_0*ll3_0) - ll3_1*ly5_1 - ll3_2*ly5_2 + pf35
    ld3 = -(ll3_0*lw3_0) - ll3_1*lw3_1 - ll3_2*lw3_2 + pq33
    lr3 = 1.0/max(1e-300, ld3)
    ll4_3 = lr3*(-(ll4_0*lw3_0) - ll4_1*lw3_1 - ll4_2*lw3_2 + pq34)
    ll5_3 = lr3*(-(ll5_0*lw3_0) - ll5_1*lw3_1 - ll5_2*lw3_2 + pq35)
    lw4_3 = ld3*ll4_3
    lw5_3 = ld3*ll5_3
    ly0_4 = -(cf0_0*ll4_0) - ll4_1*ly0_1 - ll4_2*ly0_2 - ll4_3*ly0_3 + pf04
    ly1_4 = -(cf1_0*ll4_0) - ll4_1*ly1_1 - ll4_2*ly1_2 - ll4_3*ly1_3 + pf14
    ly2_4 = -(cf2_0*ll4_0) - ll4_1*ly2_1 - ll4_2*ly2_2 - ll4_3*ly2_3 + pf24
    ly3_4 = -(cf3_0*ll4_0) - ll4_1*ly3_1 - ll4_2*ly3_2 - ll4_3*ly3_3 + pf34
    ly4_4 = -(cf4_0*ll4_0) - ll4_1*ly4_1 - ll4_2*ly4_2 - ll4_3*ly4_3 + pf44
    ly5_4 = -(cf5_0*ll4_0) - ll4_1*ly5_1 - ll4_2*ly5_2 - ll4_3*ly5_3 + pf45
    ld4 = -(ll4_0*lw4_0) - ll4_1*lw4_1 - ll4_2*lw4_2 - ll4_3*lw4_3 + pq44
    lr4 = 1.0/max(1e-300, ld4)
    ll5_4 = lr4*(-(ll5_0*lw4_0) - ll5_1*lw4_1 - ll5_2*lw4_2 - ll5_3*lw4_3 + pq45)
    lw5_4 = ld4*ll5_4
    ly0_5 = -(cf0_0*ll5_0) - ll5_1*ly0_1 - ll5_2*ly0_2 - ll5_3*ly0_3 - ll5_4*ly0_4 + pf05
    ly1_5 = -(cf1_0*ll5_0) - ll5_1*ly1_1 - ll5_2*ly1_2 - ll5_3*ly1_3 - ll5_4*ly1_4 + pf15
    ly2_5 = -(cf2_0*ll5_0) - ll5_1*ly2_1 - ll5_2*ly2_2 - ll5_3*ly2_3 - ll5_4*ly2_4 + pf25
    ly3_5 = -(cf3_0*ll5_0) - ll5_1*ly3_1 - ll5_2*ly3_2 - ll5_3*ly3_3 - ll5_4*ly3_4 + pf35
    ly4_5 = -(cf4_0*ll5_0) - ll5_1*ly4_1 - ll5_2*ly4_2 - ll5_3*ly4_3 - ll5_4*ly4_4 + pf45
    ly5_5 = -(cf5_0*ll5_0) - ll5_1*ly5_1 - ll5_2*ly5_2 - ll5_3*ly5_3 - ll5_4*ly5_4 + pf55
    ld5 = -(ll5_0*lw5_0) - ll5_1*lw5_1 - ll5_2*lw5_2 - ll5_3*lw5_3 - ll5_4*lw5_4 + pq55
    lr5 = 1.0/max(1e-300, ld5)
    gg0_5 = lr5*ly0_5
    gg1_5 = lr5*ly1_5
    gg2_5 = lr5*ly2_5
    gg3_5 = lr5*ly3_5
    gg4_5 = lr5*ly4_5
    gg5_5 = lr5*ly5_5
    gg0_4 = -(gg0_5*ll5_4) + lr4*ly0_4
    gg1_4 = -(gg1_5*ll5_4) + lr4*ly1_4
    gg2_4 = -(gg2_5*ll5_4) + lr4*ly2_4
    gg3_4 = -(gg3_5*ll5_4) + lr4*ly3_4
    gg4_4 = -(gg4_5*ll5_4) + lr4*ly4_4
    gg5_4 = -(gg5_5*ll5_4) + lr4*ly5_4
    gg0_3 = -(gg0_4*ll4_3) - gg0_5*ll5_3 + lr3*ly0_3
    gg1_3 = -(gg1_4*ll4_3) - gg1_5*ll5_3 + lr3*ly1_3
    gg2_3 = -(gg2_4*ll4_3) - gg2_5*ll5_3 + lr3*ly2_3
    gg3_3 = -(gg3_4*ll4_3) - gg3_5*ll5_3 + lr3*ly3_3
    gg4_3 = -(gg4_4*ll4_3) - gg4_5*ll5_3 + lr3*ly4_3
    gg5_3 = -(gg5_4*ll4_3) - gg5_5*ll5_3 + lr3*ly5_3
    gg0_2 = -(gg0_3*ll3_2) - gg0_4*ll4_2 - gg0_5*ll5_2 + lr2*ly0_2
    gg1_2 = -(gg1_3*ll3_2) - gg1_4*ll4_2 - gg1_5*ll5_2 + lr2*ly1_2
    gg2_2 = -(gg2_3*ll3_2) - gg2_4*ll4_2 - gg2_5*ll5_2 + lr2*ly2_2
    gg3_2 = -(gg3_3*ll3_2) - gg3_4*ll4_2 - gg3_5*ll5_2 + lr2*ly3_2
    gg4_2 = -(gg4_3*ll3_2) - gg4_4*ll4_2 - gg4_5*ll5_2 + lr2*ly4_2
    gg5_2 = -(gg5_3*ll3_2) - gg5_4*ll4_2 - gg5_5*ll5_2 + lr2*ly5_2
    gg0_1 = -(gg0_2*ll2_1) - gg0_3*ll3_1 - gg0_4*ll4_1 - gg0_5*ll5_1 + lr1*ly0_1
    gg1_1 = -(gg1_2*ll2_1) - gg1_3*ll3_1 - gg1_4*ll4_1 - gg1_5*ll5_1 + lr1*ly1_1
    gg2_1 = -(gg2_2*ll2_1) - gg2_3*ll3_1 - gg2_4*ll4_1 - gg2_5*ll5_1 + lr1*ly2_1
    gg3_1 = -(gg3_2*ll2_1) - gg3_3*ll3_1 - gg3_4*ll4_1 - gg3_5*ll5_1 + lr1*ly3_1
    gg4_1 = -(gg4_2*ll2_1) - gg4_3*ll3_1 - gg4_4*ll4_1 - gg4_5*ll5_1 + lr1*ly4_1
    gg5_1 = -(gg5_2*ll2_1) - gg5_3*ll3_1 - gg5_4*ll4_1 - gg5_5*ll5_1 + lr1*ly5_1
    gg0_0 = cf0_0*lr0 - gg0_1*ll1_0 - gg0_2*ll2_0 - gg0_3*ll3_0 - gg0_4*ll4_0 - gg0_5*ll5_0
    gg1_0 = cf1_0*lr0 - gg1_1*ll1_0 - gg1_2*ll2_0 - gg1_3*ll3_0 - gg1_4*ll4_0 - gg1_5*ll5_0
    gg2_0 = cf2_0*lr0 - gg2_1*ll1_0 - gg2_2*ll2_0 - gg2_3*ll3_0 - gg2_4*ll4_0 - gg2_5*ll5_0
    gg3_0 = cf3_0*lr0 - gg3_1*ll1_0 - gg3_2*ll2_0 - gg3_3*ll3_0 - gg3_4*ll4_0 - gg3_5*ll5_0
    gg4_0 = cf4_0*lr0 - gg4_1*ll1_0 - gg4_2*ll2_0 - gg4_3*ll3_0 - gg4_4*ll4_0 - gg4_5*ll5_0
    gg5_0 = cf5_0*lr0 - gg5_1*ll1_0 - gg5_2*ll2_0 - gg5_3*ll3_0 - gg5_4*ll4_0 - gg5_5*ll5_0
    de0_0 = dd0_0*gg0_0 + dd0_1*gg0_1 + dd0_2*gg0_2 + dd0_3*gg0_3 + dd0_4*gg0_4 + dd0_5*gg0_5
    de1_0 = dd0_0*gg1_0 + dd0_1*gg1_1 + dd0_2*gg1_2 + dd0_3*gg1_3 + dd0_4*gg1_4 + dd0_5*gg1_5
    de2_0 = dd0_0*gg2_0 + dd0_1*gg2_1 + dd0_2*gg2_2 + dd0_3*gg2_3 + dd0_4*gg2_4 + dd0_5*gg2_5
    de3_0 = dd0_0*gg3_0 + dd0_1*gg3_1 + dd0_2*gg3_2 + dd0_3*gg3_3 + dd0_4*gg3_4 + dd0_5*gg3_5
    de4_0 = dd0_0*gg4_0 + dd0_1*gg4_1 + dd0_2*gg4_2 + dd0_3*gg4_3 + dd0_4*gg4_4 + dd0_5*gg4_5
    de5_0 = dd0_0*gg5_0 + dd0_1*gg5_1 + dd0_2*gg5_2 + dd0_3*gg5_3 + dd0_4*gg5_4 + dd0_5*gg5_5
    gd0_0 = dm0_0*gg0_0 + dm0_1*gg0_1 + dm0_2*gg0_2 + dm0_3*gg0_3 + dm0_4*gg0_4 + dm0_5*gg0_5
    gd0_1 = dm0_1*gg0_0 + dm1_1*gg0_1 + dm1_2*gg0_2 + dm1_3*gg0_3 + dm1_4*gg0_4 + dm1_5*gg0_5
    gd0_2 = dm0_2*gg0_0 + dm1_2*gg0_1 + dm2_2*gg0_2 + dm2_3*gg0_3 + dm2_4*gg0_4 + dm2_5*gg0_5
    gd0_3 = dm0_3*gg0_0 + dm1_3*gg0_1 + dm2_3*gg0_2 + dm3_3*gg0_3 + dm3_4*gg0_4 + dm3_5*gg0_5
    gd0_4 = dm0_4*gg0_0 + dm1_4*gg0_1 + dm2_4*gg0_2 + dm3_4*gg0_3 + dm4_4*gg0_4 + dm4_5*gg0_5
    gd0_5 = dm0_5*gg0_0 + dm1_5*gg0_1 + dm2_5*gg0_2 + dm3_5*gg0_3 + dm4_5*gg0_4 + dm5_5*gg0_5
    gd1_0 = dm0_0*gg1_0 + dm0_1*gg1_1 + dm0_2*gg1_2 + dm0_3*gg1_3 + dm0_4*gg1_4 + dm0_5*gg1_5
    gd1_1 = dm0_1*gg1_0 + dm1_1*gg1_1 + dm1_2*gg1_2 + dm1_3*gg1_3 + dm1_4*gg1_4 + dm1_5*gg1_5
    gd1_2 = dm0_2*gg1_0 + dm1_2*gg1_1 + dm2_2*gg1_2 + dm2_3*gg1_3 + dm2_4*gg1_4 + dm2_5*gg1_5
    gd1_3 = dm0_3*gg1_0 + dm1_3*gg1_1 + dm2_3*gg1_2 + dm3_3*gg1_3 + dm3_4*gg1_4 + dm3_5*gg1_5
    gd1_4 = dm0_4*gg1_0 + dm1_4*gg1_1 + dm2_4*gg1_2 + dm3_4*gg1_3 + dm4_4*gg1_4 + dm4_5*gg1_5
    gd1_5 = dm0_5*gg1_0 + dm1_5*gg1_1 + dm2_5*gg1_2 + dm3_5*gg1_3 + dm4_5*gg1_4 + dm5_5*gg1_5
    gd2_0 = dm0_0*gg2_0 + dm0_1*gg2_1 + dm0_2*gg2_2 + dm0_3*gg2_3 + dm0_4*gg2_4 + dm0_5*gg2_5
    gd2_1 = dm0_1*gg2_0 + dm1_1*gg2_1 + dm1_2*gg2_2 + dm1_3*gg2_3 + dm1_4*gg2_4 + dm1_5*gg2_5
    gd2_2 = dm0_2*gg2_0 + dm1_2*gg2_1 + dm2_2*gg2_2 + dm2_3*gg2_3 + dm2_4*gg2_4 + dm2_5*gg2_5
    gd2_3 = dm0_3*gg2_0 + dm1_3*gg2_1 + dm2_3*gg2_2 + dm3_3*gg2_3 + dm3_4*gg2_4 + dm3_5*gg2_5
    gd2_4 = dm0_4*gg2_0 + dm1_4*gg2_1 + dm2_4*gg2_2 + dm3_4*gg2_3 + dm4_4*gg2_4 + dm4_5*gg2_5
    gd2_5 = dm0_5*gg2_0 + dm1_5*gg2_1 + dm2_5*gg2_2 + dm3_5*gg2_3 + dm4_5*gg2_4 + dm5_5*gg2_5
    gd3_0 = dm0_0*gg3_0 + dm0_1*gg3_1 + dm0_2*gg3_2 + dm0_3*gg3_3 + dm0_4*gg3_4 + dm0_5*gg3_5
    gd3_1 = dm0_1*gg3_0 + dm1_1*gg3_1 + dm1_2*gg3_2 + dm1_3*gg3_3 + dm1_4*gg3_4 + dm1_5*gg3_5
    gd3_2 = dm0_2*gg3_0 + dm1_2*gg3_1 + dm2_2*gg3_2 + dm2_3*gg3_3 + dm2_4*gg3_4 + dm2_5*gg3_5
    gd3_3 = dm0_3*gg3_0 + dm1_3*gg3_1 + dm2_3*gg3_2 + dm3_3*gg3_3 + dm3_4*gg3_4 + dm3_5*gg3_5
    gd3_4 = dm0_4*gg3_0 + dm1_4*gg3_1 + dm2_4*gg3_2 + dm3_4*gg3_3 + dm4_4*gg3_4 + dm4_5*gg3_5
    gd3_5 = dm0_5*gg3_0 + dm1_5*gg3_1 + dm2_5*gg3_2 + dm3_5*gg3_3 + dm4_5*gg3_4 + dm5_5*gg3_5
    gd4_0 = dm0_0*gg4_0 + dm0_1*gg4_1 + dm0_2*gg4_2 + dm0_3*gg4_3 + dm0_4*gg4_4 + dm0_5*gg4_5
    gd4_1 = dm0_1*gg4_0 + dm1_1*gg4_1 + dm1_2*gg4_2 + dm1_3*gg4_3 + dm1_4*gg4_4 + dm1_5*gg4_5
    gd4_2 = dm0_2*gg4_0 + dm1_2*gg4_1 + dm2_2*gg4_2 + dm2_3*gg4_3 + dm2_4*gg4_4 + dm2_5*gg4_5
    gd4_3 = dm0_3*gg4_0 + dm1_3*gg4_1 + dm2_3*gg4_2 + dm3_3*gg4_3 + dm3_4*gg4_4 + dm3_5*gg4_5
    gd4_4 = dm0_4*gg4_0 + dm1_4*gg4_1 + dm2_4*gg4_2 + dm3_4*gg4_3 + dm4_4*gg4_4 + dm4_5*gg4_5
    gd4_5 = dm0_5*gg4_0 + dm1_5*gg4_1 + dm2_5*gg4_2 + dm3_5*gg4_3 + dm4_5*gg4_4 + dm5_5*gg4_5
    gd5_0 = dm0_0*gg5_0 + dm0_1*gg5_1 + dm0_2*gg5_2 + dm0_3*gg5_3 + dm0_4*gg5_4 + dm0_5*gg5_5
    gd5_1 = dm0_1*gg5_0 + dm1_1*gg5_1 + dm1_2*gg5_2 + dm1_3*gg5_3 + dm1_4*gg5_4 + dm1_5*gg5_5
    gd5_2 = dm0_2*gg5_0 + dm1_2*gg5_1 + dm2_2*gg5_2 + dm2_3*gg5_3 + dm2_4*gg5_4 + dm2_5*gg5_5
    gd5_3 = dm0_3*gg5_0 + dm1_3*gg5_1 + dm2_3*gg5_2 + dm3_3*gg5_3 + dm3_4*gg5_4 + dm3_5*gg5_5
    gd5_4 = dm0_4*gg5_0 + dm1_4*gg5_1 + dm2_4*gg5_2 + dm3_4*gg5_3 + dm4_4*gg5_4 + dm4_5*gg5_5
    gd5_5 = dm0_5*gg5_0 + dm1_5*gg5_1 + dm2_5*gg5_2 + dm3_5*gg5_3 + dm4_5*gg5_4 + dm5_5*gg5_5
    _sin_de2_0 = sin_v(de2_0)
    _cos_de2_0 = cos_v(de2_0)
    _sinc_de2_0, _cosc_de2_0, _sinc2_de2_0, _cosc2_de2_0 = sinc_family(de2_0, _sin_de2_0, _cos_de2_0)
    _sin_de5_0 = sin_v(de5_0)
    _cos_de5_0 = cos_v(de5_0)
    _sinc_de5_0, _cosc_de5_0, _sinc2_de5_0, _cosc2_de5_0 = sinc_family(de5_0, _sin_de5_0, _cos_de5_0)
    pt0_0 = gd0_0*gg0_0 + gd0_1*gg0_1 + gd0_2*gg0_2 + gd0_3*gg0_3 + gd0_4*gg0_4 + gd0_5*gg0_5 + pf00
    pt0_1 = gd0_0*gg1_0 + gd0_1*gg1_1 + gd0_2*gg1_2 + gd0_3*gg1_3 + gd0_4*gg1_4 + gd0_5*gg1_5 + pf01
    pt0_2 = gd0_0*gg2_0 + gd0_1*gg2_1 + gd0_2*gg2_2 + gd0_3*gg2_3 + gd0_4*gg2_4 + gd0_5*gg2_5 + pf02
    pt0_3 = gd0_0*gg3_0 + gd0_1*gg3_1 + gd0_2*gg3_2 + gd0_3*gg3_3 + gd0_4*gg3_4 + gd0_5*gg3_5 + pf03
    pt0_4 = gd0_0*gg4_0 + gd0_1*gg4_1 + gd0_2*gg4_2 + gd0_3*gg4_3 + gd0_4*gg4_4 + gd0_5*gg4_5 + pf04
    pt0_5 = gd0_0*gg5_0 + gd0_1*gg5_1 + gd0_2*gg5_2 + gd0_3*gg5_3 + gd0_4*gg5_4 + gd0_5*gg5_5 + pf05
    pt1_1 = gd1_0*gg1_0 + gd1_1*gg1_1 + gd1_2*gg1_2 + gd1_3*gg1_3 + gd1_4*gg1_4 + gd1_5*gg1_5 + pf11
    pt1_2 = gd1_0*gg2_0 + gd1_1*gg2_1 + gd1_2*gg2_2 + gd1_3*gg2_3 + gd1_4*gg2_4 + gd1_5*gg2_5 + pf12
    pt1_3 = gd1_0*gg3_0 + gd1_1*gg3_1 + gd1_2*gg3_2 + gd1_3*gg3_3 + gd1_4*gg3_4 + gd1_5*gg3_5 + pf13
    pt1_4 = gd1_0*gg4_0 + gd1_1*gg4_1 + gd1_2*gg4_2 + gd1_3*gg4_3 + gd1_4*gg4_4 + gd1_5*gg4_5 + pf14
    pt1_5 = gd1_0*gg5_0 + gd1_1*gg5_1 + gd1_2*gg5_2 + gd1_3*gg5_3 + gd1_4*gg5_4 + gd1_5*gg5_5 + pf15
    pt2_2 = gd2_0*gg2_0 + gd2_1*gg2_1 + gd2_2*gg2_2 + gd2_3*gg2_3 + gd2_4*gg2_4 + gd2_5*gg2_5 + pf22
    pt2_3 = gd2_0*gg3_0 + gd2_1*gg3_1 + gd2_2*gg3_2 + gd2_3*gg3_3 + gd2_4*gg3_4 + gd2_5*gg3_5 + pf23
    pt2_4 = gd2_0*gg4_0 + gd2_1*gg4_1 + gd2_2*gg4_2 + gd2_3*gg4_3 + gd2_4*gg4_4 + gd2_5*gg4_5 + pf24
    pt2_5 = gd2_0*gg5_0 + gd2_1*gg5_1 + gd2_2*gg5_2 + gd2_3*gg5_3 + gd2_4*gg5_4 + gd2_5*gg5_5 + pf25
    pt3_3 = gd3_0*gg3_0 + gd3_1*gg3_1 + gd3_2*gg3_2 + gd3_3*gg3_3 + gd3_4*gg3_4 + gd3_5*gg3_5 + pf33
    pt3_4 = gd3_0*gg4_0 + gd3_1*gg4_1 + gd3_2*gg4_2 + gd3_3*gg4_3 + gd3_4*gg4_4 + gd3_5*gg4_5 + pf34
    pt3_5 = gd3_0*gg5_0 + gd3_1*gg5_1 + gd3_2*gg5_2 + gd3_3*gg5_3 + gd3_4*gg5_4 + gd3_5*gg5_5 + pf35
    pt4_4 = gd4_0*gg4_0 + gd4_1*gg4_1 + gd4_2*gg4_2 + gd4_3*gg4_3 + gd4_4*gg4_4 + gd4_5*gg4_5 + pf44
    pt4_5 = gd4_0*gg5_0 + gd4_1*gg5_1 + gd4_2*gg5_2 + gd4_3*gg5_3 + gd4_4*gg5_4 + gd4_5*gg5_5 + pf45
    pt5_5 = gd5_0*gg5_0 + gd5_1*gg5_1 + gd5_2*gg5_2 + gd5_3*gg5_3 + gd5_4*gg5_4 + gd5_5*gg5_5 + pf55
    ph0_0 = _sinc_de2_0
    ph0_1 = _cosc_de2_0
    ph0_2 = -(_cosc2_de2_0*de1_0) + _sinc2_de2_0*de0_0
    ph1_0 = -_cosc_de2_0
    ph1_1 = _sinc_de2_0
    ph1_2 = _cosc2_de2_0*de0_0 + _sinc2_de2_0*de1_0
    ph3_3 = _sinc_de5_0
    ph3_4 = _cosc_de5_0
    ph3_5 = -(_cosc2_de5_0*de4_0) + _sinc2_de5_0*de3_0
    ph4_3 = -_cosc_de5_0
    ph4_4 = _sinc_de5_0
    ph4_5 = _cosc2_de5_0*de3_0 + _sinc2_de5_0*de4_0
    tp0_0 = ph0_0*pt0_0 + ph0_1*pt0_1 + ph0_2*pt0_2
    tp0_1 = ph0_0*pt0_1 + ph0_1*pt1_1 + ph0_2*pt1_2
    tp0_2 = ph0_0*pt0_2 + ph0_1*pt1_2 + ph0_2*pt2_2
    tp0_3 = ph0_0*pt0_3 + ph0_1*pt1_3 + ph0_2*pt2_3
    tp0_4 = ph0_0*pt0_4 + ph0_1*pt1_4 + ph0_2*pt2_4
    tp0_5 = ph0_0*pt0_5 + ph0_1*pt1_5 + ph0_2*pt2_5
    tp1_0 = ph1_0*pt0_0 + ph1_1*pt0_1 + ph1_2*pt0_2
    tp1_1 = ph1_0*pt0_1 + ph1_1*pt1_1 + ph1_2*pt1_2
    tp1_2 = ph1_0*pt0_2 + ph1_1*pt1_2 + ph1_2*pt2_2
    tp1_3 = ph1_0*pt0_3 + ph1_1*pt1_3 + ph1_2*pt2_3
    tp1_4 = ph1_0*pt0_4 + ph1_1*pt1_4 + ph1_2*pt2_4
    tp1_5 = ph1_0*pt0_5 + ph1_1*pt1_5 + ph1_2*pt2_5
    tp3_3 = ph3_3*pt3_3 + ph3_4*pt3_4 + ph3_5*pt3_5
    tp3_4 = ph3_3*pt3_4 + ph3_4*pt4_4 + ph3_5*pt4_5
    tp3_5 = ph3_3*pt3_5 + ph3_4*pt4_5 + ph3_5*pt5_5
    tp4_3 = ph4_3*pt3_3 + ph4_4*pt3_4 + ph4_5*pt3_5
    tp4_4 = ph4_3*pt3_4 + ph4_4*pt4_4 + ph4_5*pt4_5
    tp4_5 = ph4_3*pt3_5 + ph4_4*pt4_5 + ph4_5*pt5_5
    _t13 = -(_cosc_de2_0*de1_0) + _sinc_de2_0*de0_0
    _t14 = _cosc_de2_0*de0_0 + _sinc_de2_0*de1_0
    _t15 = -(_cosc_de5_0*de4_0) + _sinc_de5_0*de3_0
    _t16 = _cosc_de5_0*de3_0 + _sinc_de5_0*de4_0
    _t17 = _cos_de5_0*s_omega + _sin_de5_0*c_omega
    W[6336 + j] = ph0_0*tp0_0 + ph0_1*tp0_1 + ph0_2*tp0_2
    W[6400 + j] = ph1_0*tp0_0 + ph1_1*tp0_1 + ph1_2*tp0_2
    W[6464 + j] = tp0_2
    W[6528 + j] = ph3_3*tp0_3 + ph3_4*tp0_4 + ph3_5*tp0_5
    W[6592 + j] = ph4_3*tp0_3 + ph4_4*tp0_4 + ph4_5*tp0_5
    W[6656 + j] = tp0_5
    W[6720 + j] = ph1_0*tp1_0 + ph1_1*tp1_1 + ph1_2*tp1_2
    W[6784 + j] = tp1_2
    W[6848 + j] = ph3_3*tp1_3 + ph3_4*tp1_4 + ph3_5*tp1_5
    W[6912 + j] = ph4_3*tp1_3 + ph4_4*tp1_4 + ph4_5*tp1_5
    W[6976 + j] = tp1_5
    W[7040 + j] = pt2_2
    W[7104 + j] = ph3_3*pt2_3 + ph3_4*pt2_4 + ph3_5*pt2_5
    W[7168 + j] = ph4_3*pt2_3 + ph4_4*pt2_4 + ph4_5*pt2_5
    W[7232 + j] = pt2_5
    W[7296 + j] = ph3_3*tp3_3 + ph3_4*tp3_4 + ph3_5*tp3_5
    W[7360 + j] = ph4_3*tp3_3 + ph4_4*tp3_4 + ph4_5*tp3_5
    W[7424 + j] = tp3_5
    W[7488 + j] = ph4_3*tp4_3 + ph4_4*tp4_4 + ph4_5*tp4_5
    W[7552 + j] = tp4_5
    W[7616 + j] = pt5_5
    W[5760 + j] = _t13*c_theta - _t14*s_theta + x
    W[5824 + j] = _t13*s_theta + _t14*c_theta + y
    W[5888 + j] = _cos_de2_0*c_theta - _sin_de2_0*s_theta
    W[5952 + j] = _cos_de2_0*s_theta + _sin_de2_0*c_theta
    W[6016 + j] = _t15*c_omega - _t16*s_omega + v_x
    W[6080 + j] = _t15*s_omega + _t16*c_omega + v_y
    W[6144 + j] = wrap_sum_v(de5_0 + omega, _t17)
    W[6208 + j] = _cos_de5_0*c_omega - _sin_de5_0*s_omega
    W[6272 + j] = _t17


@nb.njit(inline="always", fastmath={"contract"}, error_model="numpy")
def physical_smooth_lane(W, j, out, b, k):
    """The physical state of lane j of the smoothed rows of the work array W into out[b, k] (SIMD).
    """
    x = W[3840 + j]
    y = W[3904 + j]
    c_theta = W[3968 + j]
    s_theta = W[4032 + j]
    v_x = W[4096 + j]
    v_y = W[4160 + j]
    omega = W[4224 + j]
    out[b, k, 0] = x
    out[b, k, 1] = y
    out[b, k, 2] = wrap_v(atan2_v(s_theta, c_theta))
    out[b, k, 3] = v_x
    out[b, k, 4] = v_y
    out[b, k, 5] = omega


@nb.njit(cache=True, parallel=True, fastmath=FASTMATH, error_model="numpy")
def smooth_batch_soa(dts, Qb, Fb, lengths, Sb, out_x):
    """smooth_batch with trajectories in the SIMD lanes (derive/codegen/smooth_step.py), over a forward pass stored
    in blocks by run_batch_store_soa_<meas>: Qb, Fb (nblk, K, 30, 64) hold the predicted / posterior internal
    state and packed covariance of step k of trajectory blk·64 + j in Qb[blk, k, :, j]; writes the smoothed ones
    into Sb (same layout; pass Sb with no steps, (nblk, 0, 30, 64), to skip them) and the smoothed physical
    states into out_x (B, K, 6). Trajectory b starts at its last
    step lengths[b] − 1 (smoothed = filtered there); entries past its length are left unset. Per block (prange) and
    step, the rows are copied into one work array (rows × 64) and lane_smooth runs vectorised over the lanes.
    """
    B = dts.shape[0]
    nblk = Qb.shape[0]
    keep = Sb.shape[1] > 0
    for blk in nb.prange(nblk):
        lo = blk * 64
        L = min(64, B - lo)
        W = np.zeros(123 * 64)
        Kmax = 0
        for j in range(L):
            Kmax = max(Kmax, lengths[lo + j])
        for k in range(Kmax - 1, -1, -1):
            for i in range(30):
                for j in range(64):
                    W[(0 + i) * 64 + j] = Fb[blk, k, i, j]
            for j in range(L):
                Kb = lengths[lo + j]
                W[121 * 64 + j] = 1.0 if k < Kb - 1 else 0.0
                W[122 * 64 + j] = 1.0 if k == Kb - 1 else 0.0
            if k < Kmax - 1:
                for i in range(30):
                    for j in range(64):
                        W[(30 + i) * 64 + j] = Qb[blk, k + 1, i, j]
                for j in range(L):
                    W[120 * 64 + j] = dts[lo + j, k + 1]
                for j in range(L):
                    lane_smooth(W, j)
                for i in range(30):
                    for j in range(64):
                        act = W[121 * 64 + j] > 0.5
                        W[(60 + i) * 64 + j] = W[(90 + i) * 64 + j] if act else W[(60 + i) * 64 + j]
            for i in range(30):
                for j in range(64):
                    start = W[122 * 64 + j] > 0.5
                    W[(60 + i) * 64 + j] = W[(0 + i) * 64 + j] if start else W[(60 + i) * 64 + j]
            if keep:
                for i in range(30):
                    for j in range(64):
                        Sb[blk, k, i, j] = W[(60 + i) * 64 + j]
            for j in range(L):
                if k < lengths[lo + j]:
                    physical_smooth_lane(W, j, out_x, lo + j, k)


@nb.njit(cache=True)
def smooth_one(dts, s_pred, p_pred, s_filt, p_filt, K, s_sm, p_sm):
    """Rauch–Tung–Striebel backward pass on the group over the first K steps (derivation:
    lgekf.estimators.smoother). dts (K,) step lengths (dts[k] led to step k); s_pred, p_pred / s_filt, p_filt:
    predicted / posterior internal states and packed covariances (run_one_store_*); writes the smoothed ones
    into s_sm (K, 9), p_sm (K, 21). For k = K-2 ... 0, with F = transition(μ_k, dts[k+1]):
    d = log(μ_{k+1|k}⁻¹ μˢ_{k+1}), P̄ = Φ(d)⁻¹ Pˢ_{k+1} Φ(d)⁻ᵀ, G = P_k Fᵀ P_{k+1|k}⁻¹, δ = G d,
    μˢ_k = μ_k·exp(δ), Pˢ_k = Φ(δ) [P_k + G (P̄ − P_{k+1|k}) Gᵀ] Φ(δ)ᵀ."""
    for i in range(9):
        s_sm[K - 1, i] = s_filt[K - 1, i]
    for i in range(21):
        p_sm[K - 1, i] = p_filt[K - 1, i]
    for k in range(K - 2, -1, -1):
        smooth_step_at(s_filt, p_filt, s_pred, p_pred, s_sm, p_sm, k, dts[k + 1])  # smooth_step on the rows k, k + 1


@nb.njit(cache=True, parallel=True)
def smooth_batch(dts, s_pred, p_pred, s_filt, p_filt, lengths, s_sm, p_sm, out_x):
    """smooth_one for B trajectories (prange), trajectory b over its first lengths[b] steps; also writes the
    smoothed physical states into out_x (B, K, 6)."""
    for b in nb.prange(dts.shape[0]):
        Kb = lengths[b]
        if Kb > 0:
            smooth_one(dts[b], s_pred[b], p_pred[b], s_filt[b], p_filt[b], Kb, s_sm[b], p_sm[b])
            for k in range(Kb):
                physical_into(s_sm[b, k], out_x[b, k])


@nb.njit(cache=True)
def physical_to_common(xp):
    """c = (x, y, θ, v_x, v_y, ω) of a physical state x (θ from the velocity for a model
    without a heading; 0 for the coordinates of common_missing).
    """
    x = xp[0]
    y = xp[1]
    theta = xp[2]
    v_x = xp[3]
    v_y = xp[4]
    omega = xp[5]
    out = np.zeros(6)
    out[0] = x
    out[1] = y
    out[2] = theta
    out[3] = v_x
    out[4] = v_y
    out[5] = omega
    return out


@nb.njit(cache=True)
def physical_to_common_jacobian(xp):
    """A = ∂c/∂ε (6 × n) at the physical state x (X = μ·exp ε): P_c = A P Aᵀ.
    """
    theta = xp[2]
    omega = xp[5]
    out = np.zeros((6, 6))
    _sin_omega = math.sin(omega)
    _cos_omega = math.cos(omega)
    _sin_theta = math.sin(theta)
    _cos_theta = math.cos(theta)
    out[0, 0] = _cos_theta
    out[0, 1] = -_sin_theta
    out[1, 0] = _sin_theta
    out[1, 1] = _cos_theta
    out[2, 2] = 1.0
    out[3, 3] = _cos_omega
    out[3, 4] = -_sin_omega
    out[4, 3] = _sin_omega
    out[4, 4] = _cos_omega
    out[5, 5] = 1.0
    return out


@nb.njit(cache=True)
def common_missing():
    """1.0 for each common coordinate (x, y, θ, v_x, v_y, ω) the model carries no information on."""
    return np.array([0.0, 0.0, 0.0, 0.0, 0.0, 0.0])


@nb.njit(cache=True)
def state_from_physical_into(xp, out):
    """Internal state [x, y, c_theta, s_theta, v_x, v_y, omega, c_omega, s_omega] from the physical [x, y, theta, vx, vy, omega].
    Written into ``out`` (no allocation).
    """
    x = xp[0]
    y = xp[1]
    theta = xp[2]
    v_x = xp[3]
    v_y = xp[4]
    omega = xp[5]
    out[:] = 0.0
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


@nb.njit(cache=True)
def transition_into(s, dt, out):
    """F = Ad_G(exp(-Ω)) + Φ_G(Ω) 𝒞 (paper, below eq:pred_cov).
    Written into ``out`` (no allocation).
    """
    v_x = s[4]
    v_y = s[5]
    omega = s[6]
    c_omega = s[7]
    s_omega = s[8]
    out[:, :] = 0.0
    _a0 = dt*omega
    _sin__a0 = math.sin(_a0)
    _cos__a0 = math.cos(_a0)
    _sinc__a0, _cosc__a0, _sinc2__a0, _cosc2__a0 = sinc_family(_a0, _sin__a0, _cos__a0)
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


@nb.njit(cache=True)
def calH_pose_into(s, out):
    """ℋ = ∂[log_G'(h(μ)^-1 h(μ exp ε))]^∨/∂ε at ε = 0 (eq:calH, eq:calH_model) for pose measurements.
    Written into ``out`` (no allocation).
    """
    out[:, :] = 0.0
    out[0, 0] = 1.0
    out[1, 1] = 1.0
    out[2, 2] = 1.0


@nb.njit(cache=True)
def calH_position_into(s, out):
    """ℋ = ∂[log_G'(h(μ)^-1 h(μ exp ε))]^∨/∂ε at ε = 0 (eq:calH, eq:calH_model) for position measurements.
    Written into ``out`` (no allocation).
    """
    c_theta = s[2]
    s_theta = s[3]
    out[:, :] = 0.0
    out[0, 0] = c_theta
    out[0, 1] = -s_theta
    out[1, 0] = s_theta
    out[1, 1] = c_theta


@nb.njit(cache=True)
def common_to_state_into(c, out):
    """The model's physical state from the common c = (x, y, θ, v_x, v_y, ω), velocities in the body frame.
    Written into ``out`` (no allocation).
    """
    c0 = c[0]
    c1 = c[1]
    c2 = c[2]
    c3 = c[3]
    c4 = c[4]
    c5 = c[5]
    out[:] = 0.0
    out[0] = c0
    out[1] = c1
    out[2] = c2
    out[3] = c3
    out[4] = c4
    out[5] = c5


@nb.njit(cache=True)
def common_jacobian_into(c, out):
    """J = ∂(filter coordinates ε)/∂c at c: maps a covariance of c to the filter's P (P = J P_c J^T).
    Written into ``out`` (no allocation).
    """
    c2 = c[2]
    c5 = c[5]
    out[:, :] = 0.0
    _sin_c2 = math.sin(c2)
    _cos_c2 = math.cos(c2)
    _sin_c5 = math.sin(c5)
    _cos_c5 = math.cos(c5)
    out[0, 0] = _cos_c2
    out[0, 1] = _sin_c2
    out[1, 0] = -_sin_c2
    out[1, 1] = _cos_c2
    out[2, 2] = 1.0
    out[3, 3] = _cos_c5
    out[3, 4] = _sin_c5
    out[4, 3] = -_sin_c5
    out[4, 4] = _cos_c5
    out[5, 5] = 1.0


@nb.njit(cache=True)
def between_into(s, t, out):
    """[log_G(μ_s^-1 μ_t)]^∨: the tangent ε with μ_t = μ_s·exp(ε) (s ⊖: μ_s, t: μ_t, internal states);
    angle coordinates of a Euclidean model wrapped to (-π, π].
    Written into ``out`` (no allocation).
    """
    x = s[0]
    y = s[1]
    c_theta = s[2]
    s_theta = s[3]
    v_x = s[4]
    v_y = s[5]
    c_omega = s[7]
    s_omega = s[8]
    t_x = t[0]
    t_y = t[1]
    t_c_theta = t[2]
    t_s_theta = t[3]
    t_v_x = t[4]
    t_v_y = t[5]
    t_c_omega = t[7]
    t_s_omega = t[8]
    out[:] = 0.0
    _a0 = math.atan2(c_omega*t_s_omega - s_omega*t_c_omega, c_omega*t_c_omega + s_omega*t_s_omega)
    _sin__a0 = math.sin(_a0)
    _cos__a0 = math.cos(_a0)
    _halfcot__a0 = halfcot(_a0, _sin__a0, _cos__a0)
    _a1 = math.atan2(c_theta*t_s_theta - s_theta*t_c_theta, c_theta*t_c_theta + s_theta*t_s_theta)
    _sin__a1 = math.sin(_a1)
    _cos__a1 = math.cos(_a1)
    _halfcot__a1 = halfcot(_a1, _sin__a1, _cos__a1)
    _t0 = c_theta*t_x - c_theta*x + s_theta*t_y - s_theta*y
    _t1 = c_theta*t_y - c_theta*y - s_theta*t_x + s_theta*x
    _t2 = _a1/2.0
    _t3 = c_omega*t_v_x - c_omega*v_x + s_omega*t_v_y - s_omega*v_y
    _t4 = c_omega*t_v_y - c_omega*v_y - s_omega*t_v_x + s_omega*v_x
    _t5 = _a0/2.0
    out[0] = _halfcot__a1*_t0 + _t1*_t2
    out[1] = _halfcot__a1*_t1 - _t0*_t2
    out[2] = _a1
    out[3] = _halfcot__a0*_t3 + _t4*_t5
    out[4] = _halfcot__a0*_t4 - _t3*_t5
    out[5] = _a0


@nb.njit(cache=True)
def right_jacobian_into(eps, out):
    """Φ_G(ε) of the whole group (block-diagonal over its factors, I for Rⁿ);
    log(exp(-ε) exp(ε + δ)) ≈ Φ_G(ε) δ.
    Written into ``out`` (no allocation).
    """
    eps0 = eps[0]
    eps1 = eps[1]
    eps2 = eps[2]
    eps3 = eps[3]
    eps4 = eps[4]
    eps5 = eps[5]
    out[:, :] = 0.0
    _sin_eps2 = math.sin(eps2)
    _cos_eps2 = math.cos(eps2)
    _sinc_eps2, _cosc_eps2, _sinc2_eps2, _cosc2_eps2 = sinc_family(eps2, _sin_eps2, _cos_eps2)
    _sin_eps5 = math.sin(eps5)
    _cos_eps5 = math.cos(eps5)
    _sinc_eps5, _cosc_eps5, _sinc2_eps5, _cosc2_eps5 = sinc_family(eps5, _sin_eps5, _cos_eps5)
    out[0, 0] = _sinc_eps2
    out[0, 1] = _cosc_eps2
    out[0, 2] = -(_cosc2_eps2*eps1) + _sinc2_eps2*eps0
    out[1, 0] = -_cosc_eps2
    out[1, 1] = _sinc_eps2
    out[1, 2] = _cosc2_eps2*eps0 + _sinc2_eps2*eps1
    out[2, 2] = 1.0
    out[3, 3] = _sinc_eps5
    out[3, 4] = _cosc_eps5
    out[3, 5] = -(_cosc2_eps5*eps4) + _sinc2_eps5*eps3
    out[4, 3] = -_cosc_eps5
    out[4, 4] = _sinc_eps5
    out[4, 5] = _cosc2_eps5*eps3 + _sinc2_eps5*eps4
    out[5, 5] = 1.0


@nb.njit(cache=True)
def right_jacobian_inv_into(eps, out):
    """Φ_G(ε)^-1 of the whole group.
    Written into ``out`` (no allocation).
    """
    eps0 = eps[0]
    eps1 = eps[1]
    eps2 = eps[2]
    eps3 = eps[3]
    eps4 = eps[4]
    eps5 = eps[5]
    out[:, :] = 0.0
    _sin_eps2 = math.sin(eps2)
    _cos_eps2 = math.cos(eps2)
    _halfcot_eps2 = halfcot(eps2, _sin_eps2, _cos_eps2)
    _halfcot1_eps2 = halfcot1(eps2, _sin_eps2, _cos_eps2)
    _sin_eps5 = math.sin(eps5)
    _cos_eps5 = math.cos(eps5)
    _halfcot_eps5 = halfcot(eps5, _sin_eps5, _cos_eps5)
    _halfcot1_eps5 = halfcot1(eps5, _sin_eps5, _cos_eps5)
    _t0 = eps2/2.0
    _t1 = eps5/2.0
    out[0, 0] = _halfcot_eps2
    out[0, 1] = -_t0
    out[0, 2] = _halfcot1_eps2*eps0 + eps1/2.0
    out[1, 0] = _t0
    out[1, 1] = _halfcot_eps2
    out[1, 2] = _halfcot1_eps2*eps1 - eps0/2.0
    out[2, 2] = 1.0
    out[3, 3] = _halfcot_eps5
    out[3, 4] = -_t1
    out[3, 5] = _halfcot1_eps5*eps3 + eps4/2.0
    out[4, 3] = _t1
    out[4, 4] = _halfcot_eps5
    out[4, 5] = _halfcot1_eps5*eps4 - eps3/2.0
    out[5, 5] = 1.0


@nb.njit(cache=True)
def physical_to_common_into(xp, out):
    """c = (x, y, θ, v_x, v_y, ω) of a physical state x (θ from the velocity for a model
    without a heading; 0 for the coordinates of common_missing).
    Written into ``out`` (no allocation).
    """
    x = xp[0]
    y = xp[1]
    theta = xp[2]
    v_x = xp[3]
    v_y = xp[4]
    omega = xp[5]
    out[:] = 0.0
    out[0] = x
    out[1] = y
    out[2] = theta
    out[3] = v_x
    out[4] = v_y
    out[5] = omega


@nb.njit(cache=True)
def physical_to_common_jacobian_into(xp, out):
    """A = ∂c/∂ε (6 × n) at the physical state x (X = μ·exp ε): P_c = A P Aᵀ.
    Written into ``out`` (no allocation).
    """
    theta = xp[2]
    omega = xp[5]
    out[:, :] = 0.0
    _sin_omega = math.sin(omega)
    _cos_omega = math.cos(omega)
    _sin_theta = math.sin(theta)
    _cos_theta = math.cos(theta)
    out[0, 0] = _cos_theta
    out[0, 1] = -_sin_theta
    out[1, 0] = _sin_theta
    out[1, 1] = _cos_theta
    out[2, 2] = 1.0
    out[3, 3] = _cos_omega
    out[3, 4] = -_sin_omega
    out[4, 3] = _sin_omega
    out[4, 4] = _cos_omega
    out[5, 5] = 1.0


@nb.njit(cache=True)
def between_add(s, t, w, acc):
    """acc += w·[log_G(μ_s^-1 μ_t)]^∨ (a term of the iterated mean μ ← μ·exp(Σ w_i d_i); d as ``between``).
    """
    x = s[0]
    y = s[1]
    c_theta = s[2]
    s_theta = s[3]
    v_x = s[4]
    v_y = s[5]
    c_omega = s[7]
    s_omega = s[8]
    t_x = t[0]
    t_y = t[1]
    t_c_theta = t[2]
    t_s_theta = t[3]
    t_v_x = t[4]
    t_v_y = t[5]
    t_c_omega = t[7]
    t_s_omega = t[8]
    acc0 = acc[0]
    acc1 = acc[1]
    acc2 = acc[2]
    acc3 = acc[3]
    acc4 = acc[4]
    acc5 = acc[5]
    _y__a0 = c_omega*t_s_omega - s_omega*t_c_omega
    _x__a0 = c_omega*t_c_omega + s_omega*t_s_omega
    _a0 = math.atan2(_y__a0, _x__a0)
    _r__a0 = math.sqrt(_x__a0*_x__a0 + _y__a0*_y__a0)
    _sin__a0 = _y__a0/_r__a0
    _cos__a0 = _x__a0/_r__a0
    _halfcot__a0 = halfcot(_a0, _sin__a0, _cos__a0)
    _y__a1 = c_theta*t_s_theta - s_theta*t_c_theta
    _x__a1 = c_theta*t_c_theta + s_theta*t_s_theta
    _a1 = math.atan2(_y__a1, _x__a1)
    _r__a1 = math.sqrt(_x__a1*_x__a1 + _y__a1*_y__a1)
    _sin__a1 = _y__a1/_r__a1
    _cos__a1 = _x__a1/_r__a1
    _halfcot__a1 = halfcot(_a1, _sin__a1, _cos__a1)
    _t0 = c_theta*t_x - c_theta*x + s_theta*t_y - s_theta*y
    _t1 = c_theta*t_y - c_theta*y - s_theta*t_x + s_theta*x
    _t2 = _a1/2.0
    _t3 = c_omega*t_v_x - c_omega*v_x + s_omega*t_v_y - s_omega*v_y
    _t4 = c_omega*t_v_y - c_omega*v_y - s_omega*t_v_x + s_omega*v_x
    _t5 = _a0/2.0
    d0 = _halfcot__a1*_t0 + _t1*_t2
    d1 = _halfcot__a1*_t1 - _t0*_t2
    d2 = _a1
    d3 = _halfcot__a0*_t3 + _t4*_t5
    d4 = _halfcot__a0*_t4 - _t3*_t5
    d5 = _a0
    acc[0] = acc0 + d0*w
    acc[1] = acc1 + d1*w
    acc[2] = acc2 + d2*w
    acc[3] = acc3 + d3*w
    acc[4] = acc4 + d4*w
    acc[5] = acc5 + d5*w


@nb.njit(cache=True)
def mix_transport(s, t, pt, w, acc):
    """acc (packed upper triangle) += w·[Φ(d)^-1 P_t Φ(d)^-T + d dᵀ], d = [log_G(μ_s^-1 μ_t)]^∨, P_t = unpack(pt):
    one source's term of a mixture's covariance about the mean μ_s (X = μ_t·exp ε_t = μ_s·exp(d + Φ(d)^-1 ε_t)
    to first order; lgekf.estimators.imm.kernels). Straight line over the non-zero entries of Φ^-1.
    """
    x = s[0]
    y = s[1]
    c_theta = s[2]
    s_theta = s[3]
    v_x = s[4]
    v_y = s[5]
    c_omega = s[7]
    s_omega = s[8]
    t_x = t[0]
    t_y = t[1]
    t_c_theta = t[2]
    t_s_theta = t[3]
    t_v_x = t[4]
    t_v_y = t[5]
    t_c_omega = t[7]
    t_s_omega = t[8]
    pt0_0 = pt[0]
    pt0_1 = pt[1]
    pt0_2 = pt[2]
    pt0_3 = pt[3]
    pt0_4 = pt[4]
    pt0_5 = pt[5]
    pt1_1 = pt[6]
    pt1_2 = pt[7]
    pt1_3 = pt[8]
    pt1_4 = pt[9]
    pt1_5 = pt[10]
    pt2_2 = pt[11]
    pt2_3 = pt[12]
    pt2_4 = pt[13]
    pt2_5 = pt[14]
    pt3_3 = pt[15]
    pt3_4 = pt[16]
    pt3_5 = pt[17]
    pt4_4 = pt[18]
    pt4_5 = pt[19]
    pt5_5 = pt[20]
    acc0 = acc[0]
    acc1 = acc[1]
    acc2 = acc[2]
    acc3 = acc[3]
    acc4 = acc[4]
    acc5 = acc[5]
    acc6 = acc[6]
    acc7 = acc[7]
    acc8 = acc[8]
    acc9 = acc[9]
    acc10 = acc[10]
    acc11 = acc[11]
    acc12 = acc[12]
    acc13 = acc[13]
    acc14 = acc[14]
    acc15 = acc[15]
    acc16 = acc[16]
    acc17 = acc[17]
    acc18 = acc[18]
    acc19 = acc[19]
    acc20 = acc[20]
    _y__a0 = c_omega*t_s_omega - s_omega*t_c_omega
    _x__a0 = c_omega*t_c_omega + s_omega*t_s_omega
    _a0 = math.atan2(_y__a0, _x__a0)
    _r__a0 = math.sqrt(_x__a0*_x__a0 + _y__a0*_y__a0)
    _sin__a0 = _y__a0/_r__a0
    _cos__a0 = _x__a0/_r__a0
    _halfcot__a0 = halfcot(_a0, _sin__a0, _cos__a0)
    _y__a1 = c_theta*t_s_theta - s_theta*t_c_theta
    _x__a1 = c_theta*t_c_theta + s_theta*t_s_theta
    _a1 = math.atan2(_y__a1, _x__a1)
    _r__a1 = math.sqrt(_x__a1*_x__a1 + _y__a1*_y__a1)
    _sin__a1 = _y__a1/_r__a1
    _cos__a1 = _x__a1/_r__a1
    _halfcot__a1 = halfcot(_a1, _sin__a1, _cos__a1)
    _t0 = c_theta*t_x - c_theta*x + s_theta*t_y - s_theta*y
    _t1 = c_theta*t_y - c_theta*y - s_theta*t_x + s_theta*x
    _t2 = _a1/2.0
    _t3 = c_omega*t_v_x - c_omega*v_x + s_omega*t_v_y - s_omega*v_y
    _t4 = c_omega*t_v_y - c_omega*v_y - s_omega*t_v_x + s_omega*v_x
    _t5 = _a0/2.0
    d0 = _halfcot__a1*_t0 + _t1*_t2
    d1 = _halfcot__a1*_t1 - _t0*_t2
    d2 = _a1
    d3 = _halfcot__a0*_t3 + _t4*_t5
    d4 = _halfcot__a0*_t4 - _t3*_t5
    d5 = _a0
    _halfcot1__a0 = halfcot1(_a0, _sin__a0, _cos__a0)
    _halfcot1__a1 = halfcot1(_a1, _sin__a1, _cos__a1)
    _t6 = d2/2.0
    _t7 = d5/2.0
    T0_0 = _halfcot__a1
    T0_1 = -_t6
    T0_2 = _halfcot1__a1*d0 + d1/2.0
    T1_0 = _t6
    T1_1 = _halfcot__a1
    T1_2 = _halfcot1__a1*d1 - d0/2.0
    T3_3 = _halfcot__a0
    T3_4 = -_t7
    T3_5 = _halfcot1__a0*d3 + d4/2.0
    T4_3 = _t7
    T4_4 = _halfcot__a0
    T4_5 = _halfcot1__a0*d4 - d3/2.0
    U0_0 = T0_0*pt0_0 + T0_1*pt0_1 + T0_2*pt0_2
    U0_1 = T0_0*pt0_1 + T0_1*pt1_1 + T0_2*pt1_2
    U0_2 = T0_0*pt0_2 + T0_1*pt1_2 + T0_2*pt2_2
    U0_3 = T0_0*pt0_3 + T0_1*pt1_3 + T0_2*pt2_3
    U0_4 = T0_0*pt0_4 + T0_1*pt1_4 + T0_2*pt2_4
    U0_5 = T0_0*pt0_5 + T0_1*pt1_5 + T0_2*pt2_5
    U1_0 = T1_0*pt0_0 + T1_1*pt0_1 + T1_2*pt0_2
    U1_1 = T1_0*pt0_1 + T1_1*pt1_1 + T1_2*pt1_2
    U1_2 = T1_0*pt0_2 + T1_1*pt1_2 + T1_2*pt2_2
    U1_3 = T1_0*pt0_3 + T1_1*pt1_3 + T1_2*pt2_3
    U1_4 = T1_0*pt0_4 + T1_1*pt1_4 + T1_2*pt2_4
    U1_5 = T1_0*pt0_5 + T1_1*pt1_5 + T1_2*pt2_5
    U3_3 = T3_3*pt3_3 + T3_4*pt3_4 + T3_5*pt3_5
    U3_4 = T3_3*pt3_4 + T3_4*pt4_4 + T3_5*pt4_5
    U3_5 = T3_3*pt3_5 + T3_4*pt4_5 + T3_5*pt5_5
    U4_3 = T4_3*pt3_3 + T4_4*pt3_4 + T4_5*pt3_5
    U4_4 = T4_3*pt3_4 + T4_4*pt4_4 + T4_5*pt4_5
    U4_5 = T4_3*pt3_5 + T4_4*pt4_5 + T4_5*pt5_5
    acc[0] = acc0 + w*(T0_0*U0_0 + T0_1*U0_1 + T0_2*U0_2 + d0*d0)
    acc[1] = acc1 + w*(T1_0*U0_0 + T1_1*U0_1 + T1_2*U0_2 + d0*d1)
    acc[2] = acc2 + w*(U0_2 + d0*d2)
    acc[3] = acc3 + w*(T3_3*U0_3 + T3_4*U0_4 + T3_5*U0_5 + d0*d3)
    acc[4] = acc4 + w*(T4_3*U0_3 + T4_4*U0_4 + T4_5*U0_5 + d0*d4)
    acc[5] = acc5 + w*(U0_5 + d0*d5)
    acc[6] = acc6 + w*(T1_0*U1_0 + T1_1*U1_1 + T1_2*U1_2 + d1*d1)
    acc[7] = acc7 + w*(U1_2 + d1*d2)
    acc[8] = acc8 + w*(T3_3*U1_3 + T3_4*U1_4 + T3_5*U1_5 + d1*d3)
    acc[9] = acc9 + w*(T4_3*U1_3 + T4_4*U1_4 + T4_5*U1_5 + d1*d4)
    acc[10] = acc10 + w*(U1_5 + d1*d5)
    acc[11] = acc11 + w*(d2*d2 + pt2_2)
    acc[12] = acc12 + w*(T3_3*pt2_3 + T3_4*pt2_4 + T3_5*pt2_5 + d2*d3)
    acc[13] = acc13 + w*(T4_3*pt2_3 + T4_4*pt2_4 + T4_5*pt2_5 + d2*d4)
    acc[14] = acc14 + w*(d2*d5 + pt2_5)
    acc[15] = acc15 + w*(T3_3*U3_3 + T3_4*U3_4 + T3_5*U3_5 + d3*d3)
    acc[16] = acc16 + w*(T4_3*U3_3 + T4_4*U3_4 + T4_5*U3_5 + d3*d4)
    acc[17] = acc17 + w*(U3_5 + d3*d5)
    acc[18] = acc18 + w*(T4_3*U4_3 + T4_4*U4_4 + T4_5*U4_5 + d4*d4)
    acc[19] = acc19 + w*(U4_5 + d4*d5)
    acc[20] = acc20 + w*(d5*d5 + pt5_5)


@nb.njit(cache=True, error_model="numpy")
def common_of_state(s, p, c, Pc):
    """A mode's Gaussian in the common coordinates: c = (x, y, θ, v_x, v_y, ω) of the internal state s (as
    physical_to_common(physical(s))) and Pc = A P Aᵀ (6 × 6), A = ∂c/∂ε (physical_to_common_jacobian) at s.
    """
    x = s[0]
    y = s[1]
    c_theta = s[2]
    s_theta = s[3]
    v_x = s[4]
    v_y = s[5]
    omega = s[6]
    p0_0 = p[0]
    p0_1 = p[1]
    p0_2 = p[2]
    p0_3 = p[3]
    p0_4 = p[4]
    p0_5 = p[5]
    p1_1 = p[6]
    p1_2 = p[7]
    p1_3 = p[8]
    p1_4 = p[9]
    p1_5 = p[10]
    p2_2 = p[11]
    p2_3 = p[12]
    p2_4 = p[13]
    p2_5 = p[14]
    p3_3 = p[15]
    p3_4 = p[16]
    p3_5 = p[17]
    p4_4 = p[18]
    p4_5 = p[19]
    p5_5 = p[20]
    xp_x = x
    xp_y = y
    xp_theta = wrap_angle(math.atan2(s_theta, c_theta))
    xp_v_x = v_x
    xp_v_y = v_y
    xp_omega = omega
    _sin_xp_omega = math.sin(xp_omega)
    _cos_xp_omega = math.cos(xp_omega)
    _sin_xp_theta = math.sin(xp_theta)
    _cos_xp_theta = math.cos(xp_theta)
    A0_0 = _cos_xp_theta
    A0_1 = -_sin_xp_theta
    A1_0 = _sin_xp_theta
    A1_1 = _cos_xp_theta
    A3_3 = _cos_xp_omega
    A3_4 = -_sin_xp_omega
    A4_3 = _sin_xp_omega
    A4_4 = _cos_xp_omega
    U0_0 = A0_0*p0_0 + A0_1*p0_1
    U0_1 = A0_0*p0_1 + A0_1*p1_1
    U0_2 = A0_0*p0_2 + A0_1*p1_2
    U0_3 = A0_0*p0_3 + A0_1*p1_3
    U0_4 = A0_0*p0_4 + A0_1*p1_4
    U0_5 = A0_0*p0_5 + A0_1*p1_5
    U1_0 = A1_0*p0_0 + A1_1*p0_1
    U1_1 = A1_0*p0_1 + A1_1*p1_1
    U1_2 = A1_0*p0_2 + A1_1*p1_2
    U1_3 = A1_0*p0_3 + A1_1*p1_3
    U1_4 = A1_0*p0_4 + A1_1*p1_4
    U1_5 = A1_0*p0_5 + A1_1*p1_5
    U3_3 = A3_3*p3_3 + A3_4*p3_4
    U3_4 = A3_3*p3_4 + A3_4*p4_4
    U3_5 = A3_3*p3_5 + A3_4*p4_5
    U4_3 = A4_3*p3_3 + A4_4*p3_4
    U4_4 = A4_3*p3_4 + A4_4*p4_4
    U4_5 = A4_3*p3_5 + A4_4*p4_5
    _t0 = A1_0*U0_0 + A1_1*U0_1
    _t1 = A3_3*U0_3 + A3_4*U0_4
    _t2 = A4_3*U0_3 + A4_4*U0_4
    _t3 = A3_3*U1_3 + A3_4*U1_4
    _t4 = A4_3*U1_3 + A4_4*U1_4
    _t5 = A3_3*p2_3 + A3_4*p2_4
    _t6 = A4_3*p2_3 + A4_4*p2_4
    _t7 = A4_3*U3_3 + A4_4*U3_4
    c[0] = xp_x
    c[1] = xp_y
    c[2] = xp_theta
    c[3] = xp_v_x
    c[4] = xp_v_y
    c[5] = xp_omega
    Pc[0, 0] = A0_0*U0_0 + A0_1*U0_1
    Pc[0, 1] = _t0
    Pc[1, 0] = _t0
    Pc[0, 2] = U0_2
    Pc[2, 0] = U0_2
    Pc[0, 3] = _t1
    Pc[3, 0] = _t1
    Pc[0, 4] = _t2
    Pc[4, 0] = _t2
    Pc[0, 5] = U0_5
    Pc[5, 0] = U0_5
    Pc[1, 1] = A1_0*U1_0 + A1_1*U1_1
    Pc[1, 2] = U1_2
    Pc[2, 1] = U1_2
    Pc[1, 3] = _t3
    Pc[3, 1] = _t3
    Pc[1, 4] = _t4
    Pc[4, 1] = _t4
    Pc[1, 5] = U1_5
    Pc[5, 1] = U1_5
    Pc[2, 2] = p2_2
    Pc[2, 3] = _t5
    Pc[3, 2] = _t5
    Pc[2, 4] = _t6
    Pc[4, 2] = _t6
    Pc[2, 5] = p2_5
    Pc[5, 2] = p2_5
    Pc[3, 3] = A3_3*U3_3 + A3_4*U3_4
    Pc[3, 4] = _t7
    Pc[4, 3] = _t7
    Pc[3, 5] = U3_5
    Pc[5, 3] = U3_5
    Pc[4, 4] = A4_3*U4_3 + A4_4*U4_4
    Pc[4, 5] = U4_5
    Pc[5, 4] = U4_5
    Pc[5, 5] = p5_5


@nb.njit(cache=True)
def state_of_common(c, Pc, s, p):
    """A Gaussian in the common coordinates (c, Pc (6 × 6, upper triangle read)) as the model's: the internal state
    s = state_from_physical(common_to_state(c)) and p = J Pc Jᵀ packed, J = ∂ε/∂c (common_jacobian) at c.
    """
    c0 = c[0]
    c1 = c[1]
    c2 = c[2]
    c3 = c[3]
    c4 = c[4]
    c5 = c[5]
    pc0_0 = Pc[0, 0]
    pc0_1 = Pc[0, 1]
    pc0_2 = Pc[0, 2]
    pc0_3 = Pc[0, 3]
    pc0_4 = Pc[0, 4]
    pc0_5 = Pc[0, 5]
    pc1_1 = Pc[1, 1]
    pc1_2 = Pc[1, 2]
    pc1_3 = Pc[1, 3]
    pc1_4 = Pc[1, 4]
    pc1_5 = Pc[1, 5]
    pc2_2 = Pc[2, 2]
    pc2_3 = Pc[2, 3]
    pc2_4 = Pc[2, 4]
    pc2_5 = Pc[2, 5]
    pc3_3 = Pc[3, 3]
    pc3_4 = Pc[3, 4]
    pc3_5 = Pc[3, 5]
    pc4_4 = Pc[4, 4]
    pc4_5 = Pc[4, 5]
    pc5_5 = Pc[5, 5]
    xp_x = c0
    xp_y = c1
    xp_theta = c2
    xp_v_x = c3
    xp_v_y = c4
    xp_omega = c5
    _sin_c2 = math.sin(c2)
    _cos_c2 = math.cos(c2)
    _sin_c5 = math.sin(c5)
    _cos_c5 = math.cos(c5)
    J0_0 = _cos_c2
    J0_1 = _sin_c2
    J1_0 = -_sin_c2
    J1_1 = _cos_c2
    J3_3 = _cos_c5
    J3_4 = _sin_c5
    J4_3 = -_sin_c5
    J4_4 = _cos_c5
    V0_0 = J0_0*pc0_0 + J0_1*pc0_1
    V0_1 = J0_0*pc0_1 + J0_1*pc1_1
    V0_2 = J0_0*pc0_2 + J0_1*pc1_2
    V0_3 = J0_0*pc0_3 + J0_1*pc1_3
    V0_4 = J0_0*pc0_4 + J0_1*pc1_4
    V0_5 = J0_0*pc0_5 + J0_1*pc1_5
    V1_0 = J1_0*pc0_0 + J1_1*pc0_1
    V1_1 = J1_0*pc0_1 + J1_1*pc1_1
    V1_2 = J1_0*pc0_2 + J1_1*pc1_2
    V1_3 = J1_0*pc0_3 + J1_1*pc1_3
    V1_4 = J1_0*pc0_4 + J1_1*pc1_4
    V1_5 = J1_0*pc0_5 + J1_1*pc1_5
    V3_3 = J3_3*pc3_3 + J3_4*pc3_4
    V3_4 = J3_3*pc3_4 + J3_4*pc4_4
    V3_5 = J3_3*pc3_5 + J3_4*pc4_5
    V4_3 = J4_3*pc3_3 + J4_4*pc3_4
    V4_4 = J4_3*pc3_4 + J4_4*pc4_4
    V4_5 = J4_3*pc3_5 + J4_4*pc4_5
    _sin_xp_omega = math.sin(xp_omega)
    _cos_xp_omega = math.cos(xp_omega)
    _sin_xp_theta = math.sin(xp_theta)
    _cos_xp_theta = math.cos(xp_theta)
    s[0] = xp_x
    s[1] = xp_y
    s[2] = _cos_xp_theta
    s[3] = _sin_xp_theta
    s[4] = xp_v_x
    s[5] = xp_v_y
    s[6] = math.atan2(_sin_xp_omega, _cos_xp_omega)
    s[7] = _cos_xp_omega
    s[8] = _sin_xp_omega
    p[0] = J0_0*V0_0 + J0_1*V0_1
    p[1] = J1_0*V0_0 + J1_1*V0_1
    p[2] = V0_2
    p[3] = J3_3*V0_3 + J3_4*V0_4
    p[4] = J4_3*V0_3 + J4_4*V0_4
    p[5] = V0_5
    p[6] = J1_0*V1_0 + J1_1*V1_1
    p[7] = V1_2
    p[8] = J3_3*V1_3 + J3_4*V1_4
    p[9] = J4_3*V1_3 + J4_4*V1_4
    p[10] = V1_5
    p[11] = pc2_2
    p[12] = J3_3*pc2_3 + J3_4*pc2_4
    p[13] = J4_3*pc2_3 + J4_4*pc2_4
    p[14] = pc2_5
    p[15] = J3_3*V3_3 + J3_4*V3_4
    p[16] = J4_3*V3_3 + J4_4*V3_4
    p[17] = V3_5
    p[18] = J4_3*V4_3 + J4_4*V4_4
    p[19] = V4_5
    p[20] = pc5_5


@nb.njit(cache=True, error_model="numpy")
def between_add_at(ws, js, jt, w, jacc):
    """acc += w·[log_G(μ_s^-1 μ_t)]^∨ (a term of the iterated mean μ ← μ·exp(Σ w_i d_i); d as ``between``).
    On rows of ws: s = ws[js], t = ws[jt], acc = ws[jacc] (derive/codegen/imm_rows.py).
    """
    x = ws[js, 0]
    y = ws[js, 1]
    c_theta = ws[js, 2]
    s_theta = ws[js, 3]
    v_x = ws[js, 4]
    v_y = ws[js, 5]
    c_omega = ws[js, 7]
    s_omega = ws[js, 8]
    t_x = ws[jt, 0]
    t_y = ws[jt, 1]
    t_c_theta = ws[jt, 2]
    t_s_theta = ws[jt, 3]
    t_v_x = ws[jt, 4]
    t_v_y = ws[jt, 5]
    t_c_omega = ws[jt, 7]
    t_s_omega = ws[jt, 8]
    acc0 = ws[jacc, 0]
    acc1 = ws[jacc, 1]
    acc2 = ws[jacc, 2]
    acc3 = ws[jacc, 3]
    acc4 = ws[jacc, 4]
    acc5 = ws[jacc, 5]
    _y__a0 = c_omega*t_s_omega - s_omega*t_c_omega
    _x__a0 = c_omega*t_c_omega + s_omega*t_s_omega
    _a0 = math.atan2(_y__a0, _x__a0)
    _r__a0 = math.sqrt(_x__a0*_x__a0 + _y__a0*_y__a0)
    _sin__a0 = _y__a0/_r__a0
    _cos__a0 = _x__a0/_r__a0
    _halfcot__a0 = halfcot(_a0, _sin__a0, _cos__a0)
    _y__a1 = c_theta*t_s_theta - s_theta*t_c_theta
    _x__a1 = c_theta*t_c_theta + s_theta*t_s_theta
    _a1 = math.atan2(_y__a1, _x__a1)
    _r__a1 = math.sqrt(_x__a1*_x__a1 + _y__a1*_y__a1)
    _sin__a1 = _y__a1/_r__a1
    _cos__a1 = _x__a1/_r__a1
    _halfcot__a1 = halfcot(_a1, _sin__a1, _cos__a1)
    _t0 = c_theta*t_x - c_theta*x + s_theta*t_y - s_theta*y
    _t1 = c_theta*t_y - c_theta*y - s_theta*t_x + s_theta*x
    _t2 = _a1/2.0
    _t3 = c_omega*t_v_x - c_omega*v_x + s_omega*t_v_y - s_omega*v_y
    _t4 = c_omega*t_v_y - c_omega*v_y - s_omega*t_v_x + s_omega*v_x
    _t5 = _a0/2.0
    d0 = _halfcot__a1*_t0 + _t1*_t2
    d1 = _halfcot__a1*_t1 - _t0*_t2
    d2 = _a1
    d3 = _halfcot__a0*_t3 + _t4*_t5
    d4 = _halfcot__a0*_t4 - _t3*_t5
    d5 = _a0
    ws[jacc, 0] = acc0 + d0*w
    ws[jacc, 1] = acc1 + d1*w
    ws[jacc, 2] = acc2 + d2*w
    ws[jacc, 3] = acc3 + d3*w
    ws[jacc, 4] = acc4 + d4*w
    ws[jacc, 5] = acc5 + d5*w


@nb.njit(cache=True, error_model="numpy")
def mix_transport_at(ws, js, jt, jpt, w, jacc):
    """acc (packed upper triangle) += w·[Φ(d)^-1 P_t Φ(d)^-T + d dᵀ], d = [log_G(μ_s^-1 μ_t)]^∨, P_t = unpack(pt):
    one source's term of a mixture's covariance about the mean μ_s (X = μ_t·exp ε_t = μ_s·exp(d + Φ(d)^-1 ε_t)
    to first order; lgekf.estimators.imm.kernels). Straight line over the non-zero entries of Φ^-1.
    On rows of ws: s = ws[js], t = ws[jt], pt = ws[jpt], acc = ws[jacc] (derive/codegen/imm_rows.py).
    """
    x = ws[js, 0]
    y = ws[js, 1]
    c_theta = ws[js, 2]
    s_theta = ws[js, 3]
    v_x = ws[js, 4]
    v_y = ws[js, 5]
    c_omega = ws[js, 7]
    s_omega = ws[js, 8]
    t_x = ws[jt, 0]
    t_y = ws[jt, 1]
    t_c_theta = ws[jt, 2]
    t_s_theta = ws[jt, 3]
    t_v_x = ws[jt, 4]
    t_v_y = ws[jt, 5]
    t_c_omega = ws[jt, 7]
    t_s_omega = ws[jt, 8]
    pt0_0 = ws[jpt, 0]
    pt0_1 = ws[jpt, 1]
    pt0_2 = ws[jpt, 2]
    pt0_3 = ws[jpt, 3]
    pt0_4 = ws[jpt, 4]
    pt0_5 = ws[jpt, 5]
    pt1_1 = ws[jpt, 6]
    pt1_2 = ws[jpt, 7]
    pt1_3 = ws[jpt, 8]
    pt1_4 = ws[jpt, 9]
    pt1_5 = ws[jpt, 10]
    pt2_2 = ws[jpt, 11]
    pt2_3 = ws[jpt, 12]
    pt2_4 = ws[jpt, 13]
    pt2_5 = ws[jpt, 14]
    pt3_3 = ws[jpt, 15]
    pt3_4 = ws[jpt, 16]
    pt3_5 = ws[jpt, 17]
    pt4_4 = ws[jpt, 18]
    pt4_5 = ws[jpt, 19]
    pt5_5 = ws[jpt, 20]
    acc0 = ws[jacc, 0]
    acc1 = ws[jacc, 1]
    acc2 = ws[jacc, 2]
    acc3 = ws[jacc, 3]
    acc4 = ws[jacc, 4]
    acc5 = ws[jacc, 5]
    acc6 = ws[jacc, 6]
    acc7 = ws[jacc, 7]
    acc8 = ws[jacc, 8]
    acc9 = ws[jacc, 9]
    acc10 = ws[jacc, 10]
    acc11 = ws[jacc, 11]
    acc12 = ws[jacc, 12]
    acc13 = ws[jacc, 13]
    acc14 = ws[jacc, 14]
    acc15 = ws[jacc, 15]
    acc16 = ws[jacc, 16]
    acc17 = ws[jacc, 17]
    acc18 = ws[jacc, 18]
    acc19 = ws[jacc, 19]
    acc20 = ws[jacc, 20]
    _y__a0 = c_omega*t_s_omega - s_omega*t_c_omega
    _x__a0 = c_omega*t_c_omega + s_omega*t_s_omega
    _a0 = math.atan2(_y__a0, _x__a0)
    _r__a0 = math.sqrt(_x__a0*_x__a0 + _y__a0*_y__a0)
    _sin__a0 = _y__a0/_r__a0
    _cos__a0 = _x__a0/_r__a0
    _halfcot__a0 = halfcot(_a0, _sin__a0, _cos__a0)
    _y__a1 = c_theta*t_s_theta - s_theta*t_c_theta
    _x__a1 = c_theta*t_c_theta + s_theta*t_s_theta
    _a1 = math.atan2(_y__a1, _x__a1)
    _r__a1 = math.sqrt(_x__a1*_x__a1 + _y__a1*_y__a1)
    _sin__a1 = _y__a1/_r__a1
    _cos__a1 = _x__a1/_r__a1
    _halfcot__a1 = halfcot(_a1, _sin__a1, _cos__a1)
    _t0 = c_theta*t_x - c_theta*x + s_theta*t_y - s_theta*y
    _t1 = c_theta*t_y - c_theta*y - s_theta*t_x + s_theta*x
    _t2 = _a1/2.0
    _t3 = c_omega*t_v_x - c_omega*v_x + s_omega*t_v_y - s_omega*v_y
    _t4 = c_omega*t_v_y - c_omega*v_y - s_omega*t_v_x + s_omega*v_x
    _t5 = _a0/2.0
    d0 = _halfcot__a1*_t0 + _t1*_t2
    d1 = _halfcot__a1*_t1 - _t0*_t2
    d2 = _a1
    d3 = _halfcot__a0*_t3 + _t4*_t5
    d4 = _halfcot__a0*_t4 - _t3*_t5
    d5 = _a0
    _halfcot1__a0 = halfcot1(_a0, _sin__a0, _cos__a0)
    _halfcot1__a1 = halfcot1(_a1, _sin__a1, _cos__a1)
    _t6 = d2/2.0
    _t7 = d5/2.0
    T0_0 = _halfcot__a1
    T0_1 = -_t6
    T0_2 = _halfcot1__a1*d0 + d1/2.0
    T1_0 = _t6
    T1_1 = _halfcot__a1
    T1_2 = _halfcot1__a1*d1 - d0/2.0
    T3_3 = _halfcot__a0
    T3_4 = -_t7
    T3_5 = _halfcot1__a0*d3 + d4/2.0
    T4_3 = _t7
    T4_4 = _halfcot__a0
    T4_5 = _halfcot1__a0*d4 - d3/2.0
    U0_0 = T0_0*pt0_0 + T0_1*pt0_1 + T0_2*pt0_2
    U0_1 = T0_0*pt0_1 + T0_1*pt1_1 + T0_2*pt1_2
    U0_2 = T0_0*pt0_2 + T0_1*pt1_2 + T0_2*pt2_2
    U0_3 = T0_0*pt0_3 + T0_1*pt1_3 + T0_2*pt2_3
    U0_4 = T0_0*pt0_4 + T0_1*pt1_4 + T0_2*pt2_4
    U0_5 = T0_0*pt0_5 + T0_1*pt1_5 + T0_2*pt2_5
    U1_0 = T1_0*pt0_0 + T1_1*pt0_1 + T1_2*pt0_2
    U1_1 = T1_0*pt0_1 + T1_1*pt1_1 + T1_2*pt1_2
    U1_2 = T1_0*pt0_2 + T1_1*pt1_2 + T1_2*pt2_2
    U1_3 = T1_0*pt0_3 + T1_1*pt1_3 + T1_2*pt2_3
    U1_4 = T1_0*pt0_4 + T1_1*pt1_4 + T1_2*pt2_4
    U1_5 = T1_0*pt0_5 + T1_1*pt1_5 + T1_2*pt2_5
    U3_3 = T3_3*pt3_3 + T3_4*pt3_4 + T3_5*pt3_5
    U3_4 = T3_3*pt3_4 + T3_4*pt4_4 + T3_5*pt4_5
    U3_5 = T3_3*pt3_5 + T3_4*pt4_5 + T3_5*pt5_5
    U4_3 = T4_3*pt3_3 + T4_4*pt3_4 + T4_5*pt3_5
    U4_4 = T4_3*pt3_4 + T4_4*pt4_4 + T4_5*pt4_5
    U4_5 = T4_3*pt3_5 + T4_4*pt4_5 + T4_5*pt5_5
    ws[jacc, 0] = acc0 + w*(T0_0*U0_0 + T0_1*U0_1 + T0_2*U0_2 + d0*d0)
    ws[jacc, 1] = acc1 + w*(T1_0*U0_0 + T1_1*U0_1 + T1_2*U0_2 + d0*d1)
    ws[jacc, 2] = acc2 + w*(U0_2 + d0*d2)
    ws[jacc, 3] = acc3 + w*(T3_3*U0_3 + T3_4*U0_4 + T3_5*U0_5 + d0*d3)
    ws[jacc, 4] = acc4 + w*(T4_3*U0_3 + T4_4*U0_4 + T4_5*U0_5 + d0*d4)
    ws[jacc, 5] = acc5 + w*(U0_5 + d0*d5)
    ws[jacc, 6] = acc6 + w*(T1_0*U1_0 + T1_1*U1_1 + T1_2*U1_2 + d1*d1)
    ws[jacc, 7] = acc7 + w*(U1_2 + d1*d2)
    ws[jacc, 8] = acc8 + w*(T3_3*U1_3 + T3_4*U1_4 + T3_5*U1_5 + d1*d3)
    ws[jacc, 9] = acc9 + w*(T4_3*U1_3 + T4_4*U1_4 + T4_5*U1_5 + d1*d4)
    ws[jacc, 10] = acc10 + w*(U1_5 + d1*d5)
    ws[jacc, 11] = acc11 + w*(d2*d2 + pt2_2)
    ws[jacc, 12] = acc12 + w*(T3_3*pt2_3 + T3_4*pt2_4 + T3_5*pt2_5 + d2*d3)
    ws[jacc, 13] = acc13 + w*(T4_3*pt2_3 + T4_4*pt2_4 + T4_5*pt2_5 + d2*d4)
    ws[jacc, 14] = acc14 + w*(d2*d5 + pt2_5)
    ws[jacc, 15] = acc15 + w*(T3_3*U3_3 + T3_4*U3_4 + T3_5*U3_5 + d3*d3)
    ws[jacc, 16] = acc16 + w*(T4_3*U3_3 + T4_4*U3_4 + T4_5*U3_5 + d3*d4)
    ws[jacc, 17] = acc17 + w*(U3_5 + d3*d5)
    ws[jacc, 18] = acc18 + w*(T4_3*U4_3 + T4_4*U4_4 + T4_5*U4_5 + d4*d4)
    ws[jacc, 19] = acc19 + w*(U4_5 + d4*d5)
    ws[jacc, 20] = acc20 + w*(d5*d5 + pt5_5)


@nb.njit(cache=True, error_model="numpy")
def retract_at(ws, js, jeps):
    """μ ← μ·exp([ε]^∧) in place (right perturbation; the update's eq:up_mu for a given ε).
    On rows of ws: s = ws[js], eps = ws[jeps] (derive/codegen/imm_rows.py).
    """
    x = ws[js, 0]
    y = ws[js, 1]
    c_theta = ws[js, 2]
    s_theta = ws[js, 3]
    v_x = ws[js, 4]
    v_y = ws[js, 5]
    omega = ws[js, 6]
    c_omega = ws[js, 7]
    s_omega = ws[js, 8]
    eps0 = ws[jeps, 0]
    eps1 = ws[jeps, 1]
    eps2 = ws[jeps, 2]
    eps3 = ws[jeps, 3]
    eps4 = ws[jeps, 4]
    eps5 = ws[jeps, 5]
    _sin_eps2 = math.sin(eps2)
    _cos_eps2 = math.cos(eps2)
    _sinc_eps2, _cosc_eps2, _sinc2_eps2, _cosc2_eps2 = sinc_family(eps2, _sin_eps2, _cos_eps2)
    _sin_eps5 = math.sin(eps5)
    _cos_eps5 = math.cos(eps5)
    _sinc_eps5, _cosc_eps5, _sinc2_eps5, _cosc2_eps5 = sinc_family(eps5, _sin_eps5, _cos_eps5)
    _t0 = -(_cosc_eps2*eps1) + _sinc_eps2*eps0
    _t1 = _cosc_eps2*eps0 + _sinc_eps2*eps1
    _t2 = -(_cosc_eps5*eps4) + _sinc_eps5*eps3
    _t3 = _cosc_eps5*eps3 + _sinc_eps5*eps4
    _t4 = _cos_eps5*s_omega + _sin_eps5*c_omega
    ws[js, 0] = _t0*c_theta - _t1*s_theta + x
    ws[js, 1] = _t0*s_theta + _t1*c_theta + y
    ws[js, 2] = _cos_eps2*c_theta - _sin_eps2*s_theta
    ws[js, 3] = _cos_eps2*s_theta + _sin_eps2*c_theta
    ws[js, 4] = _t2*c_omega - _t3*s_omega + v_x
    ws[js, 5] = _t2*s_omega + _t3*c_omega + v_y
    ws[js, 6] = wrap_angle_sum(eps5 + omega, _t4)
    ws[js, 7] = _cos_eps5*c_omega - _sin_eps5*s_omega
    ws[js, 8] = _t4


@nb.njit(cache=True, error_model="numpy")
def common_of_state_at(ws, js, jp, jc, jPc):
    """A mode's Gaussian in the common coordinates: c = (x, y, θ, v_x, v_y, ω) of the internal state s (as
    physical_to_common(physical(s))) and Pc = A P Aᵀ (6 × 6), A = ∂c/∂ε (physical_to_common_jacobian) at s.
    On rows of ws: s = ws[js], p = ws[jp], c = ws[jc], Pc = ws[jPc] (derive/codegen/imm_rows.py).
    """
    x = ws[js, 0]
    y = ws[js, 1]
    c_theta = ws[js, 2]
    s_theta = ws[js, 3]
    v_x = ws[js, 4]
    v_y = ws[js, 5]
    omega = ws[js, 6]
    p0_0 = ws[jp, 0]
    p0_1 = ws[jp, 1]
    p0_2 = ws[jp, 2]
    p0_3 = ws[jp, 3]
    p0_4 = ws[jp, 4]
    p0_5 = ws[jp, 5]
    p1_1 = ws[jp, 6]
    p1_2 = ws[jp, 7]
    p1_3 = ws[jp, 8]
    p1_4 = ws[jp, 9]
    p1_5 = ws[jp, 10]
    p2_2 = ws[jp, 11]
    p2_3 = ws[jp, 12]
    p2_4 = ws[jp, 13]
    p2_5 = ws[jp, 14]
    p3_3 = ws[jp, 15]
    p3_4 = ws[jp, 16]
    p3_5 = ws[jp, 17]
    p4_4 = ws[jp, 18]
    p4_5 = ws[jp, 19]
    p5_5 = ws[jp, 20]
    xp_x = x
    xp_y = y
    xp_theta = wrap_angle(math.atan2(s_theta, c_theta))
    xp_v_x = v_x
    xp_v_y = v_y
    xp_omega = omega
    _sin_xp_omega = math.sin(xp_omega)
    _cos_xp_omega = math.cos(xp_omega)
    _sin_xp_theta = math.sin(xp_theta)
    _cos_xp_theta = math.cos(xp_theta)
    A0_0 = _cos_xp_theta
    A0_1 = -_sin_xp_theta
    A1_0 = _sin_xp_theta
    A1_1 = _cos_xp_theta
    A3_3 = _cos_xp_omega
    A3_4 = -_sin_xp_omega
    A4_3 = _sin_xp_omega
    A4_4 = _cos_xp_omega
    U0_0 = A0_0*p0_0 + A0_1*p0_1
    U0_1 = A0_0*p0_1 + A0_1*p1_1
    U0_2 = A0_0*p0_2 + A0_1*p1_2
    U0_3 = A0_0*p0_3 + A0_1*p1_3
    U0_4 = A0_0*p0_4 + A0_1*p1_4
    U0_5 = A0_0*p0_5 + A0_1*p1_5
    U1_0 = A1_0*p0_0 + A1_1*p0_1
    U1_1 = A1_0*p0_1 + A1_1*p1_1
    U1_2 = A1_0*p0_2 + A1_1*p1_2
    U1_3 = A1_0*p0_3 + A1_1*p1_3
    U1_4 = A1_0*p0_4 + A1_1*p1_4
    U1_5 = A1_0*p0_5 + A1_1*p1_5
    U3_3 = A3_3*p3_3 + A3_4*p3_4
    U3_4 = A3_3*p3_4 + A3_4*p4_4
    U3_5 = A3_3*p3_5 + A3_4*p4_5
    U4_3 = A4_3*p3_3 + A4_4*p3_4
    U4_4 = A4_3*p3_4 + A4_4*p4_4
    U4_5 = A4_3*p3_5 + A4_4*p4_5
    _t0 = A1_0*U0_0 + A1_1*U0_1
    _t1 = A3_3*U0_3 + A3_4*U0_4
    _t2 = A4_3*U0_3 + A4_4*U0_4
    _t3 = A3_3*U1_3 + A3_4*U1_4
    _t4 = A4_3*U1_3 + A4_4*U1_4
    _t5 = A3_3*p2_3 + A3_4*p2_4
    _t6 = A4_3*p2_3 + A4_4*p2_4
    _t7 = A4_3*U3_3 + A4_4*U3_4
    ws[jc, 0] = xp_x
    ws[jc, 1] = xp_y
    ws[jc, 2] = xp_theta
    ws[jc, 3] = xp_v_x
    ws[jc, 4] = xp_v_y
    ws[jc, 5] = xp_omega
    ws[jPc, 0] = A0_0*U0_0 + A0_1*U0_1
    ws[jPc, 1] = _t0
    ws[jPc, 6] = _t0
    ws[jPc, 2] = U0_2
    ws[jPc, 12] = U0_2
    ws[jPc, 3] = _t1
    ws[jPc, 18] = _t1
    ws[jPc, 4] = _t2
    ws[jPc, 24] = _t2
    ws[jPc, 5] = U0_5
    ws[jPc, 30] = U0_5
    ws[jPc, 7] = A1_0*U1_0 + A1_1*U1_1
    ws[jPc, 8] = U1_2
    ws[jPc, 13] = U1_2
    ws[jPc, 9] = _t3
    ws[jPc, 19] = _t3
    ws[jPc, 10] = _t4
    ws[jPc, 25] = _t4
    ws[jPc, 11] = U1_5
    ws[jPc, 31] = U1_5
    ws[jPc, 14] = p2_2
    ws[jPc, 15] = _t5
    ws[jPc, 20] = _t5
    ws[jPc, 16] = _t6
    ws[jPc, 26] = _t6
    ws[jPc, 17] = p2_5
    ws[jPc, 32] = p2_5
    ws[jPc, 21] = A3_3*U3_3 + A3_4*U3_4
    ws[jPc, 22] = _t7
    ws[jPc, 27] = _t7
    ws[jPc, 23] = U3_5
    ws[jPc, 33] = U3_5
    ws[jPc, 28] = A4_3*U4_3 + A4_4*U4_4
    ws[jPc, 29] = U4_5
    ws[jPc, 34] = U4_5
    ws[jPc, 35] = p5_5


@nb.njit(cache=True, error_model="numpy")
def state_of_common_at(ws, jc, jPc, js, jp):
    """A Gaussian in the common coordinates (c, Pc (6 × 6, upper triangle read)) as the model's: the internal state
    s = state_from_physical(common_to_state(c)) and p = J Pc Jᵀ packed, J = ∂ε/∂c (common_jacobian) at c.
    On rows of ws: c = ws[jc], Pc = ws[jPc], s = ws[js], p = ws[jp] (derive/codegen/imm_rows.py).
    """
    c0 = ws[jc, 0]
    c1 = ws[jc, 1]
    c2 = ws[jc, 2]
    c3 = ws[jc, 3]
    c4 = ws[jc, 4]
    c5 = ws[jc, 5]
    pc0_0 = ws[jPc, 0]
    pc0_1 = ws[jPc, 1]
    pc0_2 = ws[jPc, 2]
    pc0_3 = ws[jPc, 3]
    pc0_4 = ws[jPc, 4]
    pc0_5 = ws[jPc, 5]
    pc1_1 = ws[jPc, 7]
    pc1_2 = ws[jPc, 8]
    pc1_3 = ws[jPc, 9]
    pc1_4 = ws[jPc, 10]
    pc1_5 = ws[jPc, 11]
    pc2_2 = ws[jPc, 14]
    pc2_3 = ws[jPc, 15]
    pc2_4 = ws[jPc, 16]
    pc2_5 = ws[jPc, 17]
    pc3_3 = ws[jPc, 21]
    pc3_4 = ws[jPc, 22]
    pc3_5 = ws[jPc, 23]
    pc4_4 = ws[jPc, 28]
    pc4_5 = ws[jPc, 29]
    pc5_5 = ws[jPc, 35]
    xp_x = c0
    xp_y = c1
    xp_theta = c2
    xp_v_x = c3
    xp_v_y = c4
    xp_omega = c5
    _sin_c2 = math.sin(c2)
    _cos_c2 = math.cos(c2)
    _sin_c5 = math.sin(c5)
    _cos_c5 = math.cos(c5)
    J0_0 = _cos_c2
    J0_1 = _sin_c2
    J1_0 = -_sin_c2
    J1_1 = _cos_c2
    J3_3 = _cos_c5
    J3_4 = _sin_c5
    J4_3 = -_sin_c5
    J4_4 = _cos_c5
    V0_0 = J0_0*pc0_0 + J0_1*pc0_1
    V0_1 = J0_0*pc0_1 + J0_1*pc1_1
    V0_2 = J0_0*pc0_2 + J0_1*pc1_2
    V0_3 = J0_0*pc0_3 + J0_1*pc1_3
    V0_4 = J0_0*pc0_4 + J0_1*pc1_4
    V0_5 = J0_0*pc0_5 + J0_1*pc1_5
    V1_0 = J1_0*pc0_0 + J1_1*pc0_1
    V1_1 = J1_0*pc0_1 + J1_1*pc1_1
    V1_2 = J1_0*pc0_2 + J1_1*pc1_2
    V1_3 = J1_0*pc0_3 + J1_1*pc1_3
    V1_4 = J1_0*pc0_4 + J1_1*pc1_4
    V1_5 = J1_0*pc0_5 + J1_1*pc1_5
    V3_3 = J3_3*pc3_3 + J3_4*pc3_4
    V3_4 = J3_3*pc3_4 + J3_4*pc4_4
    V3_5 = J3_3*pc3_5 + J3_4*pc4_5
    V4_3 = J4_3*pc3_3 + J4_4*pc3_4
    V4_4 = J4_3*pc3_4 + J4_4*pc4_4
    V4_5 = J4_3*pc3_5 + J4_4*pc4_5
    _sin_xp_omega = math.sin(xp_omega)
    _cos_xp_omega = math.cos(xp_omega)
    _sin_xp_theta = math.sin(xp_theta)
    _cos_xp_theta = math.cos(xp_theta)
    ws[js, 0] = xp_x
    ws[js, 1] = xp_y
    ws[js, 2] = _cos_xp_theta
    ws[js, 3] = _sin_xp_theta
    ws[js, 4] = xp_v_x
    ws[js, 5] = xp_v_y
    ws[js, 6] = math.atan2(_sin_xp_omega, _cos_xp_omega)
    ws[js, 7] = _cos_xp_omega
    ws[js, 8] = _sin_xp_omega
    ws[jp, 0] = J0_0*V0_0 + J0_1*V0_1
    ws[jp, 1] = J1_0*V0_0 + J1_1*V0_1
    ws[jp, 2] = V0_2
    ws[jp, 3] = J3_3*V0_3 + J3_4*V0_4
    ws[jp, 4] = J4_3*V0_3 + J4_4*V0_4
    ws[jp, 5] = V0_5
    ws[jp, 6] = J1_0*V1_0 + J1_1*V1_1
    ws[jp, 7] = V1_2
    ws[jp, 8] = J3_3*V1_3 + J3_4*V1_4
    ws[jp, 9] = J4_3*V1_3 + J4_4*V1_4
    ws[jp, 10] = V1_5
    ws[jp, 11] = pc2_2
    ws[jp, 12] = J3_3*pc2_3 + J3_4*pc2_4
    ws[jp, 13] = J4_3*pc2_3 + J4_4*pc2_4
    ws[jp, 14] = pc2_5
    ws[jp, 15] = J3_3*V3_3 + J3_4*V3_4
    ws[jp, 16] = J4_3*V3_3 + J4_4*V3_4
    ws[jp, 17] = V3_5
    ws[jp, 18] = J4_3*V4_3 + J4_4*V4_4
    ws[jp, 19] = V4_5
    ws[jp, 20] = pc5_5


@nb.njit(cache=True, fastmath=FASTMATH, error_model="numpy")
def step_ll_pose(ws, js, jp, dt, sigma_x, sigma_y, sigma_omega, z_x, z_y, z_theta, r_x, r_y, r_theta):
    """``step_try_pose`` on rows s = ws[js], p = ws[jp] (derive/codegen/imm_rows.py); returns (nis, rdet),
    rdet = 1/det S, S = ℋPℋᵀ + R at the predicted state (eq:K), also when nis is FALLBACK.
    """
    x = ws[js, 0]
    y = ws[js, 1]
    c_theta = ws[js, 2]
    s_theta = ws[js, 3]
    v_x = ws[js, 4]
    v_y = ws[js, 5]
    omega = ws[js, 6]
    c_omega = ws[js, 7]
    s_omega = ws[js, 8]
    p00 = ws[jp, 0]
    p01 = ws[jp, 1]
    p02 = ws[jp, 2]
    p03 = ws[jp, 3]
    p04 = ws[jp, 4]
    p05 = ws[jp, 5]
    p11 = ws[jp, 6]
    p12 = ws[jp, 7]
    p13 = ws[jp, 8]
    p14 = ws[jp, 9]
    p15 = ws[jp, 10]
    p22 = ws[jp, 11]
    p23 = ws[jp, 12]
    p24 = ws[jp, 13]
    p25 = ws[jp, 14]
    p33 = ws[jp, 15]
    p34 = ws[jp, 16]
    p35 = ws[jp, 17]
    p44 = ws[jp, 18]
    p45 = ws[jp, 19]
    p55 = ws[jp, 20]
    _t0 = c_omega*dt
    _t1 = dt*s_omega
    cc03 = _t0
    cc04 = -_t1
    cc13 = _t1
    cc14 = _t0
    _a0 = dt*omega
    _sin__a0 = math.sin(_a0)
    _cos__a0 = math.cos(_a0)
    _sinc__a0, _cosc__a0, _sinc2__a0, _cosc2__a0 = sinc_family(_a0, _sin__a0, _cos__a0)
    _t2 = dt*v_x
    _t3 = _cosc__a0*_t2
    _t4 = dt*v_y
    _t5 = _sinc__a0*_t4
    _t6 = -(_cosc2__a0*_t4) + _sinc2__a0*dt*v_x
    _t7 = _cosc__a0*_t4
    _t8 = _cosc2__a0*_t2 + _sinc2__a0*_t4
    _t9 = (dt*dt)/2.0
    _t10 = _sinc__a0*_t9
    _t11 = _cosc__a0*_t9
    _t12 = _sinc__a0*dt*v_x - _t7
    _t13 = _t3 + _t5
    f00 = _cos__a0
    f01 = _sin__a0
    f02 = _t3 - _t5
    f03 = _cosc__a0*cc13 + _sinc__a0*cc03
    f04 = _cosc__a0*cc14 + _sinc__a0*cc04
    f05 = _t6*dt
    f10 = -_sin__a0
    f11 = _cos__a0
    f12 = _sinc__a0*_t2 + _t7
    f13 = -(_cosc__a0*cc03) + _sinc__a0*cc13
    f14 = -(_cosc__a0*cc04) + _sinc__a0*cc14
    f15 = _t8*dt
    g00 = _t10
    g01 = _t11
    g02 = _t6*_t9
    g10 = -_t11
    g11 = _t10
    g12 = _t8*_t9
    g22 = _t9
    e00 = _t12*c_theta - _t13*s_theta + x
    e01 = _t12*s_theta + _t13*c_theta + y
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
    _t14 = sigma_x*sigma_x
    _t15 = sigma_y*sigma_y
    _t16 = sigma_omega*sigma_omega
    _t17 = _t14*g00
    _t18 = _t15*g01
    _t19 = _t16*g02
    _t20 = _t16*g12
    _t21 = dt*dt
    pp00 = _t14*(g00*g00) + _t15*(g01*g01) + _t16*(g02*g02) + f00*m00 + f01*m01 + f02*m02 + f03*m03 + f04*m04 + f05*m05
    pp01 = _t17*g10 + _t18*g11 + _t19*g12 + f10*m00 + f11*m01 + f12*m02 + f13*m03 + f14*m04 + f15*m05
    pp02 = _t19*g22 + dt*m05 + m02
    pp03 = _t17*dt + m03
    pp04 = _t18*dt + m04
    pp05 = _t19*dt + m05
    pp11 = _t14*(g10*g10) + _t15*(g11*g11) + _t16*(g12*g12) + f10*m10 + f11*m11 + f12*m12 + f13*m13 + f14*m14 + f15*m15
    pp12 = _t20*g22 + dt*m15 + m12
    pp13 = _t14*dt*g10 + m13
    pp14 = _t15*dt*g11 + m14
    pp15 = _t20*dt + m15
    pp22 = _t16*(g22*g22) + dt*m25 + m22
    pp23 = m23
    pp24 = m24
    pp25 = _t16*dt*g22 + m25
    pp33 = _t14*_t21 + p33
    pp34 = p34
    pp35 = p35
    pp44 = _t15*_t21 + p44
    pp45 = p45
    pp55 = _t16*_t21 + p55
    x_p = e00
    y_p = e01
    c_theta_p = e02
    s_theta_p = e03
    if pp22 > math.pi * math.pi:
        _cap = math.pi / math.sqrt(pp22)
        pp02 = pp02 * _cap
        pp12 = pp12 * _cap
        pp23 = pp23 * _cap
        pp24 = pp24 * _cap
        pp25 = pp25 * _cap
        pp22 = math.pi * math.pi
    if pp55 > math.pi * math.pi:
        _cap = math.pi / math.sqrt(pp55)
        pp05 = pp05 * _cap
        pp15 = pp15 * _cap
        pp25 = pp25 * _cap
        pp35 = pp35 * _cap
        pp45 = pp45 * _cap
        pp55 = math.pi * math.pi
    _sin_z_theta = math.sin(z_theta)
    _cos_z_theta = math.cos(z_theta)
    _a1 = math.atan2(c_theta_p*math.sin(z_theta) - s_theta_p*math.cos(z_theta), c_theta_p*math.cos(z_theta) + s_theta_p*math.sin(z_theta))
    _sin__a1 = math.sin(_a1)
    _cos__a1 = math.cos(_a1)
    _halfcot__a1 = halfcot(_a1, _sin__a1, _cos__a1)
    _t22 = -(c_theta_p*x_p) + c_theta_p*z_x - s_theta_p*y_p + s_theta_p*z_y
    _t23 = -(c_theta_p*y_p) + c_theta_p*z_y + s_theta_p*x_p - s_theta_p*z_x
    _t24 = math.atan2(-(_cos_z_theta*s_theta_p) + _sin_z_theta*c_theta_p, _cos_z_theta*c_theta_p + _sin_z_theta*s_theta_p)
    _t25 = _t24/2.0
    inn00 = _halfcot__a1*_t22 + _t23*_t25
    inn10 = _halfcot__a1*_t23 - _t22*_t25
    inn20 = _t24
    S00 = pp00 + r_x*r_x
    S11 = pp11 + r_y*r_y
    S22 = pp22 + r_theta*r_theta
    rdet = 1.0/(S00*S11*S22 - S00*(pp12*pp12) - S11*(pp02*pp02) - S22*(pp01*pp01) + 2.0*pp01*pp02*pp12)
    Si00 = rdet*(S11*S22 - pp12*pp12)
    Si01 = rdet*(-(S22*pp01) + pp02*pp12)
    Si02 = rdet*(-(S11*pp02) + pp01*pp12)
    Si11 = rdet*(S00*S22 - pp02*pp02)
    Si12 = rdet*(-(S00*pp12) + pp01*pp02)
    Si22 = rdet*(S00*S11 - pp01*pp01)
    _t26 = Si01*pp01
    _t27 = Si02*pp02
    _t28 = Si12*pp12
    _t29 = 2.0*inn00
    k00 = Si00*pp00 + _t26 + _t27
    k01 = Si01*pp00 + Si11*pp01 + Si12*pp02
    k02 = Si02*pp00 + Si12*pp01 + Si22*pp02
    k10 = Si00*pp01 + Si01*pp11 + Si02*pp12
    k11 = Si11*pp11 + _t26 + _t28
    k12 = Si02*pp01 + Si12*pp11 + Si22*pp12
    k20 = Si00*pp02 + Si01*pp12 + Si02*pp22
    k21 = Si01*pp02 + Si11*pp12 + Si12*pp22
    k22 = Si22*pp22 + _t27 + _t28
    k30 = Si00*pp03 + Si01*pp13 + Si02*pp23
    k31 = Si01*pp03 + Si11*pp13 + Si12*pp23
    k32 = Si02*pp03 + Si12*pp13 + Si22*pp23
    k40 = Si00*pp04 + Si01*pp14 + Si02*pp24
    k41 = Si01*pp04 + Si11*pp14 + Si12*pp24
    k42 = Si02*pp04 + Si12*pp14 + Si22*pp24
    k50 = Si00*pp05 + Si01*pp15 + Si02*pp25
    k51 = Si01*pp05 + Si11*pp15 + Si12*pp25
    k52 = Si02*pp05 + Si12*pp15 + Si22*pp25
    nis = Si00*(inn00*inn00) + Si01*_t29*inn10 + Si02*_t29*inn20 + Si11*(inn10*inn10) + 2.0*Si12*inn10*inn20 + Si22*(inn20*inn20)
    nk0 = inn00*k00 + inn10*k01 + inn20*k02
    nk1 = inn00*k10 + inn10*k11 + inn20*k12
    nk2 = inn00*k20 + inn10*k21 + inn20*k22
    nk3 = inn00*k30 + inn10*k31 + inn20*k32
    nk4 = inn00*k40 + inn10*k41 + inn20*k42
    nk5 = inn00*k50 + inn10*k51 + inn20*k52
    alpha = gain_damping(nk2, nk5)
    nu0 = alpha*nk0
    nu1 = alpha*nk1
    nu2 = alpha*nk2
    nu3 = alpha*nk3
    nu4 = alpha*nk4
    nu5 = alpha*nk5
    _sin_nu2 = math.sin(nu2)
    _cos_nu2 = math.cos(nu2)
    _sinc_nu2, _cosc_nu2, _sinc2_nu2, _cosc2_nu2 = sinc_family(nu2, _sin_nu2, _cos_nu2)
    _sin_nu5 = math.sin(nu5)
    _cos_nu5 = math.cos(nu5)
    _sinc_nu5, _cosc_nu5, _sinc2_nu5, _cosc2_nu5 = sinc_family(nu5, _sin_nu5, _cos_nu5)
    _t30 = -(_cosc_nu2*nu1) + _sinc_nu2*nu0
    _t31 = _cosc_nu2*nu0 + _sinc_nu2*nu1
    _t32 = -(_cosc_nu5*nu4) + _sinc_nu5*nu3
    _t33 = _cosc_nu5*nu3 + _sinc_nu5*nu4
    _t34 = _cos_nu5*s_omega + _sin_nu5*c_omega
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
    mu00 = _t30*c_theta_p - _t31*s_theta_p + x_p
    mu01 = _t30*s_theta_p + _t31*c_theta_p + y_p
    mu02 = _cos_nu2*c_theta_p - _sin_nu2*s_theta_p
    mu03 = _cos_nu2*s_theta_p + _sin_nu2*c_theta_p
    mu04 = _t32*c_omega - _t33*s_omega + v_x
    mu05 = _t32*s_omega + _t33*c_omega + v_y
    mu06 = wrap_angle_sum(nu5 + omega, _t34)
    mu07 = _cos_nu5*c_omega - _sin_nu5*s_omega
    mu08 = _t34
    beta = alpha*(2.0 - alpha)
    kb00 = beta*k00
    kb01 = beta*k01
    kb02 = beta*k02
    kb10 = beta*k10
    kb11 = beta*k11
    kb12 = beta*k12
    kb20 = beta*k20
    kb21 = beta*k21
    kb22 = beta*k22
    kb30 = beta*k30
    kb31 = beta*k31
    kb32 = beta*k32
    kb40 = beta*k40
    kb41 = beta*k41
    kb42 = beta*k42
    kb50 = beta*k50
    kb51 = beta*k51
    kb52 = beta*k52
    pj00 = -(kb00*pp00) - kb01*pp01 - kb02*pp02 + pp00
    pj01 = -(kb00*pp01) - kb01*pp11 - kb02*pp12 + pp01
    pj02 = -(kb00*pp02) - kb01*pp12 - kb02*pp22 + pp02
    pj03 = -(kb00*pp03) - kb01*pp13 - kb02*pp23 + pp03
    pj04 = -(kb00*pp04) - kb01*pp14 - kb02*pp24 + pp04
    pj05 = -(kb00*pp05) - kb01*pp15 - kb02*pp25 + pp05
    pj11 = -(kb10*pp01) - kb11*pp11 - kb12*pp12 + pp11
    pj12 = -(kb10*pp02) - kb11*pp12 - kb12*pp22 + pp12
    pj13 = -(kb10*pp03) - kb11*pp13 - kb12*pp23 + pp13
    pj14 = -(kb10*pp04) - kb11*pp14 - kb12*pp24 + pp14
    pj15 = -(kb10*pp05) - kb11*pp15 - kb12*pp25 + pp15
    pj22 = -(kb20*pp02) - kb21*pp12 - kb22*pp22 + pp22
    pj23 = -(kb20*pp03) - kb21*pp13 - kb22*pp23 + pp23
    pj24 = -(kb20*pp04) - kb21*pp14 - kb22*pp24 + pp24
    pj25 = -(kb20*pp05) - kb21*pp15 - kb22*pp25 + pp25
    pj33 = -(kb30*pp03) - kb31*pp13 - kb32*pp23 + pp33
    pj34 = -(kb30*pp04) - kb31*pp14 - kb32*pp24 + pp34
    pj35 = -(kb30*pp05) - kb31*pp15 - kb32*pp25 + pp35
    pj44 = -(kb40*pp04) - kb41*pp14 - kb42*pp24 + pp44
    pj45 = -(kb40*pp05) - kb41*pp15 - kb42*pp25 + pp45
    pj55 = -(kb50*pp05) - kb51*pp15 - kb52*pp25 + pp55
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
    out_p0 = cp00*phi00 + cp01*phi01 + cp02*phi02
    out_p1 = cp00*phi10 + cp01*phi11 + cp02*phi12
    out_p2 = cp02
    out_p3 = cp03*phi33 + cp04*phi34 + cp05*phi35
    out_p4 = cp03*phi43 + cp04*phi44 + cp05*phi45
    out_p5 = cp05
    out_p6 = cp10*phi10 + cp11*phi11 + cp12*phi12
    out_p7 = cp12
    out_p8 = cp13*phi33 + cp14*phi34 + cp15*phi35
    out_p9 = cp13*phi43 + cp14*phi44 + cp15*phi45
    out_p10 = cp15
    out_p11 = pj22
    out_p12 = phi33*pj23 + phi34*pj24 + phi35*pj25
    out_p13 = phi43*pj23 + phi44*pj24 + phi45*pj25
    out_p14 = pj25
    out_p15 = cp33*phi33 + cp34*phi34 + cp35*phi35
    out_p16 = cp33*phi43 + cp34*phi44 + cp35*phi45
    out_p17 = cp35
    out_p18 = cp43*phi43 + cp44*phi44 + cp45*phi45
    out_p19 = cp45
    out_p20 = pj55
    out_s0 = mu00
    out_s1 = mu01
    out_s2 = mu02
    out_s3 = mu03
    out_s4 = mu04
    out_s5 = mu05
    out_s6 = mu06
    out_s7 = mu07
    out_s8 = mu08
    if not covariance_is_pd_fused(out_p0, out_p1, out_p2, out_p3, out_p4, out_p5, out_p6, out_p7, out_p8, out_p9, out_p10, out_p11, out_p12, out_p13, out_p14, out_p15, out_p16, out_p17, out_p18, out_p19, out_p20):
        out_p0 = pp00
        out_p1 = pp01
        out_p2 = pp02
        out_p3 = pp03
        out_p4 = pp04
        out_p5 = pp05
        out_p6 = pp11
        out_p7 = pp12
        out_p8 = pp13
        out_p9 = pp14
        out_p10 = pp15
        out_p11 = pp22
        out_p12 = pp23
        out_p13 = pp24
        out_p14 = pp25
        out_p15 = pp33
        out_p16 = pp34
        out_p17 = pp35
        out_p18 = pp44
        out_p19 = pp45
        out_p20 = pp55
        out_s0 = x_p
        out_s1 = y_p
        out_s2 = c_theta_p
        out_s3 = s_theta_p
        out_s4 = v_x
        out_s5 = v_y
        out_s6 = omega
        out_s7 = c_omega
        out_s8 = s_omega
        nis = -1.0
    ws[jp, 0] = out_p0
    ws[jp, 1] = out_p1
    ws[jp, 2] = out_p2
    ws[jp, 3] = out_p3
    ws[jp, 4] = out_p4
    ws[jp, 5] = out_p5
    ws[jp, 6] = out_p6
    ws[jp, 7] = out_p7
    ws[jp, 8] = out_p8
    ws[jp, 9] = out_p9
    ws[jp, 10] = out_p10
    ws[jp, 11] = out_p11
    ws[jp, 12] = out_p12
    ws[jp, 13] = out_p13
    ws[jp, 14] = out_p14
    ws[jp, 15] = out_p15
    ws[jp, 16] = out_p16
    ws[jp, 17] = out_p17
    ws[jp, 18] = out_p18
    ws[jp, 19] = out_p19
    ws[jp, 20] = out_p20
    ws[js, 0] = out_s0
    ws[js, 1] = out_s1
    ws[js, 2] = out_s2
    ws[js, 3] = out_s3
    ws[js, 4] = out_s4
    ws[js, 5] = out_s5
    ws[js, 6] = out_s6
    ws[js, 7] = out_s7
    ws[js, 8] = out_s8
    return nis, rdet


@nb.njit(cache=True, fastmath=FASTMATH, error_model="numpy")
def step_ll_position(ws, js, jp, dt, sigma_x, sigma_y, sigma_omega, z_x, z_y, r):
    """``step_try_position`` on rows s = ws[js], p = ws[jp] (derive/codegen/imm_rows.py); returns (nis, rdet),
    rdet = 1/det S, S = ℋPℋᵀ + R at the predicted state (eq:K), also when nis is FALLBACK.
    """
    x = ws[js, 0]
    y = ws[js, 1]
    c_theta = ws[js, 2]
    s_theta = ws[js, 3]
    v_x = ws[js, 4]
    v_y = ws[js, 5]
    omega = ws[js, 6]
    c_omega = ws[js, 7]
    s_omega = ws[js, 8]
    p00 = ws[jp, 0]
    p01 = ws[jp, 1]
    p02 = ws[jp, 2]
    p03 = ws[jp, 3]
    p04 = ws[jp, 4]
    p05 = ws[jp, 5]
    p11 = ws[jp, 6]
    p12 = ws[jp, 7]
    p13 = ws[jp, 8]
    p14 = ws[jp, 9]
    p15 = ws[jp, 10]
    p22 = ws[jp, 11]
    p23 = ws[jp, 12]
    p24 = ws[jp, 13]
    p25 = ws[jp, 14]
    p33 = ws[jp, 15]
    p34 = ws[jp, 16]
    p35 = ws[jp, 17]
    p44 = ws[jp, 18]
    p45 = ws[jp, 19]
    p55 = ws[jp, 20]
    _t0 = c_omega*dt
    _t1 = dt*s_omega
    cc03 = _t0
    cc04 = -_t1
    cc13 = _t1
    cc14 = _t0
    _a0 = dt*omega
    _sin__a0 = math.sin(_a0)
    _cos__a0 = math.cos(_a0)
    _sinc__a0, _cosc__a0, _sinc2__a0, _cosc2__a0 = sinc_family(_a0, _sin__a0, _cos__a0)
    _t2 = dt*v_x
    _t3 = _cosc__a0*_t2
    _t4 = dt*v_y
    _t5 = _sinc__a0*_t4
    _t6 = -(_cosc2__a0*_t4) + _sinc2__a0*dt*v_x
    _t7 = _cosc__a0*_t4
    _t8 = _cosc2__a0*_t2 + _sinc2__a0*_t4
    _t9 = (dt*dt)/2.0
    _t10 = _sinc__a0*_t9
    _t11 = _cosc__a0*_t9
    _t12 = _sinc__a0*dt*v_x - _t7
    _t13 = _t3 + _t5
    f00 = _cos__a0
    f01 = _sin__a0
    f02 = _t3 - _t5
    f03 = _cosc__a0*cc13 + _sinc__a0*cc03
    f04 = _cosc__a0*cc14 + _sinc__a0*cc04
    f05 = _t6*dt
    f10 = -_sin__a0
    f11 = _cos__a0
    f12 = _sinc__a0*_t2 + _t7
    f13 = -(_cosc__a0*cc03) + _sinc__a0*cc13
    f14 = -(_cosc__a0*cc04) + _sinc__a0*cc14
    f15 = _t8*dt
    g00 = _t10
    g01 = _t11
    g02 = _t6*_t9
    g10 = -_t11
    g11 = _t10
    g12 = _t8*_t9
    g22 = _t9
    e00 = _t12*c_theta - _t13*s_theta + x
    e01 = _t12*s_theta + _t13*c_theta + y
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
    _t14 = sigma_x*sigma_x
    _t15 = sigma_y*sigma_y
    _t16 = sigma_omega*sigma_omega
    _t17 = _t14*g00
    _t18 = _t15*g01
    _t19 = _t16*g02
    _t20 = _t16*g12
    _t21 = dt*dt
    pp00 = _t14*(g00*g00) + _t15*(g01*g01) + _t16*(g02*g02) + f00*m00 + f01*m01 + f02*m02 + f03*m03 + f04*m04 + f05*m05
    pp01 = _t17*g10 + _t18*g11 + _t19*g12 + f10*m00 + f11*m01 + f12*m02 + f13*m03 + f14*m04 + f15*m05
    pp02 = _t19*g22 + dt*m05 + m02
    pp03 = _t17*dt + m03
    pp04 = _t18*dt + m04
    pp05 = _t19*dt + m05
    pp11 = _t14*(g10*g10) + _t15*(g11*g11) + _t16*(g12*g12) + f10*m10 + f11*m11 + f12*m12 + f13*m13 + f14*m14 + f15*m15
    pp12 = _t20*g22 + dt*m15 + m12
    pp13 = _t14*dt*g10 + m13
    pp14 = _t15*dt*g11 + m14
    pp15 = _t20*dt + m15
    pp22 = _t16*(g22*g22) + dt*m25 + m22
    pp23 = m23
    pp24 = m24
    pp25 = _t16*dt*g22 + m25
    pp33 = _t14*_t21 + p33
    pp34 = p34
    pp35 = p35
    pp44 = _t15*_t21 + p44
    pp45 = p45
    pp55 = _t16*_t21 + p55
    x_p = e00
    y_p = e01
    c_theta_p = e02
    s_theta_p = e03
    if pp22 > math.pi * math.pi:
        _cap = math.pi / math.sqrt(pp22)
        pp02 = pp02 * _cap
        pp12 = pp12 * _cap
        pp23 = pp23 * _cap
        pp24 = pp24 * _cap
        pp25 = pp25 * _cap
        pp22 = math.pi * math.pi
    if pp55 > math.pi * math.pi:
        _cap = math.pi / math.sqrt(pp55)
        pp05 = pp05 * _cap
        pp15 = pp15 * _cap
        pp25 = pp25 * _cap
        pp35 = pp35 * _cap
        pp45 = pp45 * _cap
        pp55 = math.pi * math.pi
    hh01 = -s_theta_p
    _t22 = c_theta_p*pp01
    hp00 = c_theta_p*pp00 + hh01*pp01
    hp01 = _t22 + hh01*pp11
    hp02 = c_theta_p*pp02 + hh01*pp12
    hp03 = c_theta_p*pp03 + hh01*pp13
    hp04 = c_theta_p*pp04 + hh01*pp14
    hp05 = c_theta_p*pp05 + hh01*pp15
    hp10 = _t22 + pp00*s_theta_p
    hp11 = c_theta_p*pp11 + pp01*s_theta_p
    hp12 = c_theta_p*pp12 + pp02*s_theta_p
    hp13 = c_theta_p*pp13 + pp03*s_theta_p
    hp14 = c_theta_p*pp14 + pp04*s_theta_p
    hp15 = c_theta_p*pp15 + pp05*s_theta_p
    inn00 = -x_p + z_x
    inn10 = -y_p + z_y
    _t23 = r*r
    S00 = _t23 + c_theta_p*hp00 + hh01*hp01
    S01 = c_theta_p*hp01 + hp00*s_theta_p
    S11 = _t23 + c_theta_p*hp11 + hp10*s_theta_p
    rdet = 1.0/(S00*S11 - S01*S01)
    Si00 = S11*rdet
    Si01 = -(S01*rdet)
    Si11 = S00*rdet
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
    nis = Si00*(inn00*inn00) + 2.0*Si01*inn00*inn10 + Si11*(inn10*inn10)
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
    _sinc_nu2, _cosc_nu2, _sinc2_nu2, _cosc2_nu2 = sinc_family(nu2, _sin_nu2, _cos_nu2)
    _sin_nu5 = math.sin(nu5)
    _cos_nu5 = math.cos(nu5)
    _sinc_nu5, _cosc_nu5, _sinc2_nu5, _cosc2_nu5 = sinc_family(nu5, _sin_nu5, _cos_nu5)
    _t24 = -(_cosc_nu2*nu1) + _sinc_nu2*nu0
    _t25 = _cosc_nu2*nu0 + _sinc_nu2*nu1
    _t26 = -(_cosc_nu5*nu4) + _sinc_nu5*nu3
    _t27 = _cosc_nu5*nu3 + _sinc_nu5*nu4
    _t28 = _cos_nu5*s_omega + _sin_nu5*c_omega
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
    mu00 = _t24*c_theta_p - _t25*s_theta_p + x_p
    mu01 = _t24*s_theta_p + _t25*c_theta_p + y_p
    mu02 = _cos_nu2*c_theta_p - _sin_nu2*s_theta_p
    mu03 = _cos_nu2*s_theta_p + _sin_nu2*c_theta_p
    mu04 = _t26*c_omega - _t27*s_omega + v_x
    mu05 = _t26*s_omega + _t27*c_omega + v_y
    mu06 = wrap_angle_sum(nu5 + omega, _t28)
    mu07 = _cos_nu5*c_omega - _sin_nu5*s_omega
    mu08 = _t28
    beta = alpha*(2.0 - alpha)
    kb00 = beta*k00
    kb01 = beta*k01
    kb10 = beta*k10
    kb11 = beta*k11
    kb20 = beta*k20
    kb21 = beta*k21
    kb30 = beta*k30
    kb31 = beta*k31
    kb40 = beta*k40
    kb41 = beta*k41
    kb50 = beta*k50
    kb51 = beta*k51
    pj00 = -(hp00*kb00) - hp10*kb01 + pp00
    pj01 = -(hp01*kb00) - hp11*kb01 + pp01
    pj02 = -(hp02*kb00) - hp12*kb01 + pp02
    pj03 = -(hp03*kb00) - hp13*kb01 + pp03
    pj04 = -(hp04*kb00) - hp14*kb01 + pp04
    pj05 = -(hp05*kb00) - hp15*kb01 + pp05
    pj11 = -(hp01*kb10) - hp11*kb11 + pp11
    pj12 = -(hp02*kb10) - hp12*kb11 + pp12
    pj13 = -(hp03*kb10) - hp13*kb11 + pp13
    pj14 = -(hp04*kb10) - hp14*kb11 + pp14
    pj15 = -(hp05*kb10) - hp15*kb11 + pp15
    pj22 = -(hp02*kb20) - hp12*kb21 + pp22
    pj23 = -(hp03*kb20) - hp13*kb21 + pp23
    pj24 = -(hp04*kb20) - hp14*kb21 + pp24
    pj25 = -(hp05*kb20) - hp15*kb21 + pp25
    pj33 = -(hp03*kb30) - hp13*kb31 + pp33
    pj34 = -(hp04*kb30) - hp14*kb31 + pp34
    pj35 = -(hp05*kb30) - hp15*kb31 + pp35
    pj44 = -(hp04*kb40) - hp14*kb41 + pp44
    pj45 = -(hp05*kb40) - hp15*kb41 + pp45
    pj55 = -(hp05*kb50) - hp15*kb51 + pp55
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
    out_p0 = cp00*phi00 + cp01*phi01 + cp02*phi02
    out_p1 = cp00*phi10 + cp01*phi11 + cp02*phi12
    out_p2 = cp02
    out_p3 = cp03*phi33 + cp04*phi34 + cp05*phi35
    out_p4 = cp03*phi43 + cp04*phi44 + cp05*phi45
    out_p5 = cp05
    out_p6 = cp10*phi10 + cp11*phi11 + cp12*phi12
    out_p7 = cp12
    out_p8 = cp13*phi33 + cp14*phi34 + cp15*phi35
    out_p9 = cp13*phi43 + cp14*phi44 + cp15*phi45
    out_p10 = cp15
    out_p11 = pj22
    out_p12 = phi33*pj23 + phi34*pj24 + phi35*pj25
    out_p13 = phi43*pj23 + phi44*pj24 + phi45*pj25
    out_p14 = pj25
    out_p15 = cp33*phi33 + cp34*phi34 + cp35*phi35
    out_p16 = cp33*phi43 + cp34*phi44 + cp35*phi45
    out_p17 = cp35
    out_p18 = cp43*phi43 + cp44*phi44 + cp45*phi45
    out_p19 = cp45
    out_p20 = pj55
    out_s0 = mu00
    out_s1 = mu01
    out_s2 = mu02
    out_s3 = mu03
    out_s4 = mu04
    out_s5 = mu05
    out_s6 = mu06
    out_s7 = mu07
    out_s8 = mu08
    if not covariance_is_pd_fused(out_p0, out_p1, out_p2, out_p3, out_p4, out_p5, out_p6, out_p7, out_p8, out_p9, out_p10, out_p11, out_p12, out_p13, out_p14, out_p15, out_p16, out_p17, out_p18, out_p19, out_p20):
        out_p0 = pp00
        out_p1 = pp01
        out_p2 = pp02
        out_p3 = pp03
        out_p4 = pp04
        out_p5 = pp05
        out_p6 = pp11
        out_p7 = pp12
        out_p8 = pp13
        out_p9 = pp14
        out_p10 = pp15
        out_p11 = pp22
        out_p12 = pp23
        out_p13 = pp24
        out_p14 = pp25
        out_p15 = pp33
        out_p16 = pp34
        out_p17 = pp35
        out_p18 = pp44
        out_p19 = pp45
        out_p20 = pp55
        out_s0 = x_p
        out_s1 = y_p
        out_s2 = c_theta_p
        out_s3 = s_theta_p
        out_s4 = v_x
        out_s5 = v_y
        out_s6 = omega
        out_s7 = c_omega
        out_s8 = s_omega
        nis = -1.0
    ws[jp, 0] = out_p0
    ws[jp, 1] = out_p1
    ws[jp, 2] = out_p2
    ws[jp, 3] = out_p3
    ws[jp, 4] = out_p4
    ws[jp, 5] = out_p5
    ws[jp, 6] = out_p6
    ws[jp, 7] = out_p7
    ws[jp, 8] = out_p8
    ws[jp, 9] = out_p9
    ws[jp, 10] = out_p10
    ws[jp, 11] = out_p11
    ws[jp, 12] = out_p12
    ws[jp, 13] = out_p13
    ws[jp, 14] = out_p14
    ws[jp, 15] = out_p15
    ws[jp, 16] = out_p16
    ws[jp, 17] = out_p17
    ws[jp, 18] = out_p18
    ws[jp, 19] = out_p19
    ws[jp, 20] = out_p20
    ws[js, 0] = out_s0
    ws[js, 1] = out_s1
    ws[js, 2] = out_s2
    ws[js, 3] = out_s3
    ws[js, 4] = out_s4
    ws[js, 5] = out_s5
    ws[js, 6] = out_s6
    ws[js, 7] = out_s7
    ws[js, 8] = out_s8
    return nis, rdet


@nb.njit(cache=True, error_model="numpy")
def mix_on_group_at(ws, M, rw, rs, rp, rS, rPp, rd):
    """Σ_i w_i N_G(μ_i, P_i) → N_G(μ, P) (lgekf.estimators.imm.kernels): the sources' states ws[rS + i], packed
    covariances ws[rPp + i], weights ws[rw, i] (i < M); μ into ws[rs], packed P into ws[rp]; ws[rd] scratch (the
    mean iteration's Σ w_i d_i). The mean: μ ← μ·exp(Σ w_i d_i) from the most probable source until
    |Σ w_i d_i| < 1e-12 (at most 50 iterations); P = Σ w_i [Φ(d_i)⁻¹ P_i Φ(d_i)⁻ᵀ + d_i d_iᵀ]. Returns the
    iterations used (derive/codegen/imm_rows.py)."""
    best = 0
    for i in range(M):
        if ws[rw, i] > ws[rw, best]:
            best = i
    for k in range(9):
        ws[rs, k] = ws[rS + best, k]
    it = 0
    if M > 1:
        for it in range(1, 51):
            for k in range(6):
                ws[rd, k] = 0.0
            for i in range(M):
                w = ws[rw, i]
                if w > 0.0 and not (i == best and it == 1):  # d_best = 0 in the first iteration
                    between_add_at(ws, rs, rS + i, w, rd)
            retract_at(ws, rs, rd)
            nrm = 0.0
            for k in range(6):
                nrm += ws[rd, k] * ws[rd, k]
            if nrm < 1e-24:
                break
    if M == 1:
        for k in range(21):
            ws[rp, k] = ws[rPp, k]
        return it
    for k in range(21):
        ws[rp, k] = 0.0
    for i in range(M):
        w = ws[rw, i]
        if w > 0.0:
            mix_transport_at(ws, rs, rS + i, rPp + i, w, rp)
    return it
