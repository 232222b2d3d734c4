"""EKF with the 3-D coordinated-turn model (horizontal CTRV, constant vertical speed): model quantities, fused predict/update steps and loops.

GENERATED FILE: DO NOT EDIT.
Source: derive/models/ct3.py (definition) through derive/codegen/emitter.py and derive/algebra.py
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

__all__ = ['state_from_physical', 'state_to_physical', 'physical_into', 'group_mean', 'motion_omega', 'motion', 'calC', 'transition', 'process_noise', 'limit_angle_variance', 'predict', 'calH_position3', 'update_position3', 'step_try_position3', 'step_position3', 'measure_position3', 'run_one_position3', 'run_segments_position3', 'run_one_from_position3', 'run_segments_from_position3', 'run_batch_position3', 'measure_batch_position3', 'innovation_into_position3', 'innovation_bank_position3', 'calH_bank_position3', 'run_segments_noise_from_position3', 'rerun_position3', 'recover_position3', 'lane_position3', 'run_batch_soa_position3', 'covariance_is_pd', 'covariance_is_pd_fused', 'repair_pd', 'covariance_is_pd_lane', 'physical_lane', 'propagate', 'position_into', 'simulate_batch', 'states_from_physical', 'propagate_rows', 'propagate_positions', 'world_velocity', 'world_velocity_into', 'world_velocities', 'row_speeds', 'common_to_state', 'common_jacobian', 'common_to_states', 'common_jacobians', 'reinit_into', 'speed_std_at', 'speed_stds', 'first_alarm', 'tangent_error', 'retract', 'between', 'right_jacobian', 'right_jacobian_inv', 'predict_bank', 'retract_bank', 'right_jacobian_bank', 'innovation_logdet_position3', 'step_store_position3', 'lane_store_position3', 'run_batch_store_soa_position3', 'run_one_store_position3', 'run_batch_store_position3', 'loglik_batch_position3', 'smooth_step_at', 'lane_smooth', 'physical_smooth_lane', 'smooth_batch_soa', 'smooth_one', 'smooth_batch', 'physical_to_common', 'physical_to_common_jacobian', 'common_missing', 'state_from_physical_into', 'transition_into', 'calH_position3_into', 'common_to_state_into', 'common_jacobian_into', 'between_into', 'right_jacobian_into', 'right_jacobian_inv_into', 'physical_to_common_into', 'physical_to_common_jacobian_into', 'between_add', 'mix_transport', 'common_of_state', 'state_of_common', 'between_add_at', 'mix_transport_at', 'retract_at', 'common_of_state_at', 'state_of_common_at', 'step_ll_position3', 'mix_on_group_at']


@nb.njit(cache=True)
def state_from_physical(xp):
    """Internal state [x, y, z, psi, v, omega, v_up] from the physical [x, y, z, psi, v, omega, vz].
    """
    x = xp[0]
    y = xp[1]
    z = xp[2]
    psi = xp[3]
    v = xp[4]
    omega = xp[5]
    v_up = xp[6]
    out = np.zeros(7)
    out[0] = x
    out[1] = y
    out[2] = z
    out[3] = psi
    out[4] = v
    out[5] = omega
    out[6] = v_up
    return out


@nb.njit(cache=True)
def state_to_physical(s):
    """Physical [x, y, z, psi, v, omega, vz] (angles in (-π, π]) from the internal state.
    """
    x = s[0]
    y = s[1]
    z = s[2]
    psi = s[3]
    v = s[4]
    omega = s[5]
    v_up = s[6]
    out = np.zeros(7)
    out[0] = x
    out[1] = y
    out[2] = z
    out[3] = wrap_angle(psi)
    out[4] = v
    out[5] = omega
    out[6] = v_up
    return out


@nb.njit(cache=True)
def physical_into(s, out):
    """Physical [x, y, z, psi, v, omega, vz] from the internal state, written into ``out`` (no allocation).
    """
    x = s[0]
    y = s[1]
    z = s[2]
    psi = s[3]
    v = s[4]
    omega = s[5]
    v_up = s[6]
    out[0] = x
    out[1] = y
    out[2] = z
    out[3] = wrap_angle(psi)
    out[4] = v
    out[5] = omega
    out[6] = v_up


@nb.njit(cache=True)
def group_mean(s):
    """The mean μ as a group matrix (block-diagonal for a product group).
    """
    x = s[0]
    y = s[1]
    z = s[2]
    psi = s[3]
    v = s[4]
    omega = s[5]
    v_up = s[6]
    out = np.zeros((8, 8))
    out[0, 0] = 1.0
    out[0, 7] = x
    out[1, 1] = 1.0
    out[1, 7] = y
    out[2, 2] = 1.0
    out[2, 7] = z
    out[3, 3] = 1.0
    out[3, 7] = psi
    out[4, 4] = 1.0
    out[4, 7] = v
    out[5, 5] = 1.0
    out[5, 7] = omega
    out[6, 6] = 1.0
    out[6, 7] = v_up
    out[7, 7] = 1.0
    return out


@nb.njit(cache=True)
def motion_omega(s, dt):
    """Ω(μ), the tangent increment of one step (eq:motionG).
    """
    psi = s[3]
    v = s[4]
    omega = s[5]
    v_up = s[6]
    out = np.zeros(7)
    _a0 = dt*omega/2.0
    _sin__a0 = math.sin(_a0)
    _cos__a0 = math.cos(_a0)
    _sinc__a0 = sinc(_a0, _sin__a0, _cos__a0)
    _a1 = dt*omega/2.0 + psi
    _sin__a1 = math.sin(_a1)
    _cos__a1 = math.cos(_a1)
    _t0 = _sinc__a0*dt*v
    out[0] = _cos__a1*_t0
    out[1] = _sin__a1*_t0
    out[2] = dt*v_up
    out[3] = dt*omega
    return out


@nb.njit(cache=True)
def motion(s, dt):
    """The internal state after one noise-free step, μ exp(Ω(μ)) (eq:pred_mu); x' = f(x) for a Euclidean model.
    """
    x = s[0]
    y = s[1]
    z = s[2]
    psi = s[3]
    v = s[4]
    omega = s[5]
    v_up = s[6]
    out = np.zeros(7)
    _a0 = dt*omega/2.0
    _sin__a0 = math.sin(_a0)
    _cos__a0 = math.cos(_a0)
    _sinc__a0 = sinc(_a0, _sin__a0, _cos__a0)
    _a1 = dt*omega/2.0 + psi
    _sin__a1 = math.sin(_a1)
    _cos__a1 = math.cos(_a1)
    _t0 = _sinc__a0*dt*v
    out[0] = _cos__a1*_t0 + x
    out[1] = _sin__a1*_t0 + y
    out[2] = dt*v_up + z
    out[3] = dt*omega + psi
    out[4] = v
    out[5] = omega
    out[6] = v_up
    return out


@nb.njit(cache=True)
def calC(s, dt):
    """𝒞 = ∂Ω(μ exp ε)/∂ε at ε = 0 (eq:C, eq:calCFinal).
    """
    psi = s[3]
    v = s[4]
    omega = s[5]
    out = np.zeros((7, 7))
    _a0 = dt*omega/2.0
    _sin__a0 = math.sin(_a0)
    _cos__a0 = math.cos(_a0)
    _dsinc__a0 = dsinc(_a0, _sin__a0, _cos__a0)
    _sinc__a0 = sinc(_a0, _sin__a0, _cos__a0)
    _a1 = dt*omega/2.0 + psi
    _sin__a1 = math.sin(_a1)
    _cos__a1 = math.cos(_a1)
    _t0 = _sin__a1*_sinc__a0
    _t1 = _t0*dt
    _t2 = _cos__a1*_sinc__a0
    _t3 = _t2*dt
    _t4 = (dt*dt)*v/2.0
    out[0, 3] = -(_t1*v)
    out[0, 4] = _t3
    out[0, 5] = -(_t4*(_cos__a1*_dsinc__a0 + _t0))
    out[1, 3] = _t3*v
    out[1, 4] = _t1
    out[1, 5] = _t4*(-(_dsinc__a0*_sin__a1) + _t2)
    out[2, 6] = dt
    out[3, 5] = dt
    return out


@nb.njit(cache=True)
def transition(s, dt):
    """F = Ad_G(exp(-Ω)) + Φ_G(Ω) 𝒞 (paper, below eq:pred_cov).
    """
    psi = s[3]
    v = s[4]
    omega = s[5]
    out = np.zeros((7, 7))
    _a0 = dt*omega/2.0
    _sin__a0 = math.sin(_a0)
    _cos__a0 = math.cos(_a0)
    _dsinc__a0 = dsinc(_a0, _sin__a0, _cos__a0)
    _sinc__a0 = sinc(_a0, _sin__a0, _cos__a0)
    _a1 = dt*omega/2.0 + psi
    _sin__a1 = math.sin(_a1)
    _cos__a1 = math.cos(_a1)
    _t0 = _sin__a1*_sinc__a0
    _t1 = _t0*dt
    _t2 = _cos__a1*_sinc__a0
    _t3 = _t2*dt
    _t4 = (dt*dt)*v/2.0
    out[0, 0] = 1.0
    out[0, 3] = -(_t1*v)
    out[0, 4] = _t3
    out[0, 5] = -(_t4*(_cos__a1*_dsinc__a0 + _t0))
    out[1, 1] = 1.0
    out[1, 3] = _t3*v
    out[1, 4] = _t1
    out[1, 5] = _t4*(-(_dsinc__a0*_sin__a1) + _t2)
    out[2, 2] = 1.0
    out[2, 6] = dt
    out[3, 3] = 1.0
    out[3, 5] = dt
    out[4, 4] = 1.0
    out[5, 5] = 1.0
    out[6, 6] = 1.0
    return out


@nb.njit(cache=True)
def process_noise(s, dt, sigma_a, sigma_alpha, sigma_z):
    """Q = G diag(σ²) G^T: the noise n (sigma_a, sigma_alpha, sigma_z) of eq:motionG in the tangent.
    """
    psi = s[3]
    out = np.zeros((7, 7))
    _sin_psi = math.sin(psi)
    _cos_psi = math.cos(psi)
    _t0 = sigma_a*sigma_a
    _t1 = (dt*dt*dt*dt)/4.0
    _t2 = _t0*_t1
    _t3 = _cos_psi*_sin_psi*_t2
    _t4 = (dt*dt*dt)/2.0
    _t5 = _t0*_t4
    _t6 = _cos_psi*_t5
    _t7 = _sin_psi*_t5
    _t8 = sigma_z*sigma_z
    _t9 = _t4*_t8
    _t10 = sigma_alpha*sigma_alpha
    _t11 = _t10*_t4
    _t12 = dt*dt
    out[0, 0] = (_cos_psi*_cos_psi)*_t2
    out[0, 1] = _t3
    out[0, 4] = _t6
    out[1, 0] = _t3
    out[1, 1] = (_sin_psi*_sin_psi)*_t2
    out[1, 4] = _t7
    out[2, 2] = _t1*_t8
    out[2, 6] = _t9
    out[3, 3] = _t1*_t10
    out[3, 5] = _t11
    out[4, 0] = _t6
    out[4, 1] = _t7
    out[4, 4] = _t0*_t12
    out[5, 3] = _t11
    out[5, 5] = _t10*_t12
    out[6, 2] = _t9
    out[6, 6] = _t12*_t8
    return out


@nb.njit(cache=True)
def limit_angle_variance(p):
    """Cap the std of the angle coordinates [] of P at π by congruence scaling (see derive/codegen/emitter.py)."""
    return


@nb.njit(cache=True, fastmath=FASTMATH)
def predict(s, p, dt, sigma_a, sigma_alpha, sigma_z):
    """Fused LG-EKF prediction, in place: μ ← μ exp(Ω(μ)) (eq:pred_mu),
    P ← F P F^T + Φ(Ω) Q Φ(Ω)^T (eq:pred_cov), Q = G diag(σ²) G^T.
    s: internal state [x, y, z, psi, v, omega, v_up], p: packed covariance (28), dt > 0.
    legend: cc = 𝒞 (eq:C), f = F = Ad(exp(−Ω)) + Φ(Ω)𝒞 (eq:pred_cov), g = Φ(Ω)G, hh = ℋ (eq:calH), hp = ℋP, inn = [log_G'(h(μ)⁻¹Z)]^∨, S = ℋPℋᵀ + R, Si = S⁻¹, k = K (eq:K), nk = Kν, alpha = gain damping, nu = ν, phi = Φ(ν) (eq:up_P), a = I − αKℋ, b = aP, beta = α(2 − α), kb = βK, pj = Joseph-form P (= P − βKℋP), cp = Φ(ν)·pj, mu/e = new mean
    """
    x = s[0]
    y = s[1]
    z = s[2]
    psi = s[3]
    v = s[4]
    omega = s[5]
    v_up = s[6]
    p00 = p[0]
    p01 = p[1]
    p02 = p[2]
    p03 = p[3]
    p04 = p[4]
    p05 = p[5]
    p06 = p[6]
    p11 = p[7]
    p12 = p[8]
    p13 = p[9]
    p14 = p[10]
    p15 = p[11]
    p16 = p[12]
    p22 = p[13]
    p23 = p[14]
    p24 = p[15]
    p25 = p[16]
    p26 = p[17]
    p33 = p[18]
    p34 = p[19]
    p35 = p[20]
    p36 = p[21]
    p44 = p[22]
    p45 = p[23]
    p46 = p[24]
    p55 = p[25]
    p56 = p[26]
    p66 = p[27]
    _a0 = dt*omega/2.0
    _sin__a0 = math.sin(_a0)
    _cos__a0 = math.cos(_a0)
    _dsinc__a0 = dsinc(_a0, _sin__a0, _cos__a0)
    _sinc__a0 = sinc(_a0, _sin__a0, _cos__a0)
    _a1 = dt*omega/2.0 + psi
    _sin__a1 = math.sin(_a1)
    _cos__a1 = math.cos(_a1)
    _t0 = _sin__a1*_sinc__a0
    _t1 = _t0*dt
    _t2 = _cos__a1*_sinc__a0
    _t3 = _t2*dt
    _t4 = (dt*dt)*v/2.0
    cc03 = -(_t1*v)
    cc04 = _t3
    cc05 = -(_t4*(_cos__a1*_dsinc__a0 + _t0))
    cc13 = _t3*v
    cc14 = _t1
    cc15 = _t4*(-(_dsinc__a0*_sin__a1) + _t2)
    _sin_psi = math.sin(psi)
    _cos_psi = math.cos(psi)
    _t5 = (dt*dt)/2.0
    _t6 = _sinc__a0*dt*v
    g00 = _cos_psi*_t5
    g10 = _sin_psi*_t5
    g22 = _t5
    g31 = _t5
    e00 = _cos__a1*_t6 + x
    e01 = _sin__a1*_t6 + y
    e02 = dt*v_up + z
    e03 = dt*omega + psi
    _t7 = dt*p56
    m00 = cc03*p03 + cc04*p04 + cc05*p05 + p00
    m01 = cc03*p13 + cc04*p14 + cc05*p15 + p01
    m02 = cc03*p23 + cc04*p24 + cc05*p25 + p02
    m03 = cc03*p33 + cc04*p34 + cc05*p35 + p03
    m04 = cc03*p34 + cc04*p44 + cc05*p45 + p04
    m05 = cc03*p35 + cc04*p45 + cc05*p55 + p05
    m06 = cc03*p36 + cc04*p46 + cc05*p56 + p06
    m11 = cc13*p13 + cc14*p14 + cc15*p15 + p11
    m12 = cc13*p23 + cc14*p24 + cc15*p25 + p12
    m13 = cc13*p33 + cc14*p34 + cc15*p35 + p13
    m14 = cc13*p34 + cc14*p44 + cc15*p45 + p14
    m15 = cc13*p35 + cc14*p45 + cc15*p55 + p15
    m16 = cc13*p36 + cc14*p46 + cc15*p56 + p16
    m22 = dt*p26 + p22
    m23 = dt*p36 + p23
    m24 = dt*p46 + p24
    m25 = _t7 + p25
    m26 = dt*p66 + p26
    m33 = dt*p35 + p33
    m34 = dt*p45 + p34
    m35 = dt*p55 + p35
    m36 = _t7 + p36
    _t8 = sigma_a*sigma_a
    _t9 = _t8*g00
    _t10 = sigma_z*sigma_z
    _t11 = sigma_alpha*sigma_alpha
    _t12 = dt*dt
    p[0] = _t8*(g00*g00) + cc03*m03 + cc04*m04 + cc05*m05 + m00
    p[1] = _t9*g10 + cc13*m03 + cc14*m04 + cc15*m05 + m01
    p[2] = dt*m06 + m02
    p[3] = dt*m05 + m03
    p[4] = _t9*dt + m04
    p[5] = m05
    p[6] = m06
    p[7] = _t8*(g10*g10) + cc13*m13 + cc14*m14 + cc15*m15 + m11
    p[8] = dt*m16 + m12
    p[9] = dt*m15 + m13
    p[10] = _t8*dt*g10 + m14
    p[11] = m15
    p[12] = m16
    p[13] = _t10*(g22*g22) + dt*m26 + m22
    p[14] = dt*m25 + m23
    p[15] = m24
    p[16] = m25
    p[17] = _t10*dt*g22 + m26
    p[18] = _t11*(g31*g31) + dt*m35 + m33
    p[19] = m34
    p[20] = _t11*dt*g31 + m35
    p[21] = m36
    p[22] = _t12*_t8 + p44
    p[23] = p45
    p[24] = p46
    p[25] = _t11*_t12 + p55
    p[26] = p56
    p[27] = _t10*_t12 + p66
    s[0] = e00
    s[1] = e01
    s[2] = e02
    s[3] = e03


@nb.njit(cache=True)
def calH_position3(s):
    """ℋ = ∂[log_G'(h(μ)^-1 h(μ exp ε))]^∨/∂ε at ε = 0 (eq:calH, eq:calH_model) for position3 measurements.
    """
    out = np.zeros((3, 7))
    out[0, 0] = 1.0
    out[1, 1] = 1.0
    out[2, 2] = 1.0
    return out


@nb.njit(cache=True, fastmath=FASTMATH)
def update_position3(s, p, z_x, z_y, z_z, r):
    """Fused update with a position3 measurement (3-D position z = (x, y, z) with isotropic noise std r), in place.
    z = (z_x, z_y, z_z), noise stds (r); Z = h(μ)·exp(m), m ~ N(0, R) in the tangent of G'.
    K = P ℋ^T (ℋ P ℋ^T + R)^-1, ν = K [log_G'(h(μ)^-1 Z)]^∨ (eq:K), μ ← μ exp(ν) (eq:up_mu),
    P ← Φ(ν) [(I - Kℋ) P (I - Kℋ)^T + K R K^T] Φ(ν)^T: eq:up_P in Joseph form. Returns the NIS e^T S^-1 e.
    legend: cc = 𝒞 (eq:C), f = F = Ad(exp(−Ω)) + Φ(Ω)𝒞 (eq:pred_cov), g = Φ(Ω)G, hh = ℋ (eq:calH), hp = ℋP, inn = [log_G'(h(μ)⁻¹Z)]^∨, S = ℋPℋᵀ + R, Si = S⁻¹, k = K (eq:K), nk = Kν, alpha = gain damping, nu = ν, phi = Φ(ν) (eq:up_P), a = I − αKℋ, b = aP, beta = α(2 − α), kb = βK, pj = Joseph-form P (= P − βKℋP), cp = Φ(ν)·pj, mu/e = new mean
    """
    x = s[0]
    y = s[1]
    z = s[2]
    psi = s[3]
    v = s[4]
    omega = s[5]
    v_up = s[6]
    p00 = p[0]
    p01 = p[1]
    p02 = p[2]
    p03 = p[3]
    p04 = p[4]
    p05 = p[5]
    p06 = p[6]
    p11 = p[7]
    p12 = p[8]
    p13 = p[9]
    p14 = p[10]
    p15 = p[11]
    p16 = p[12]
    p22 = p[13]
    p23 = p[14]
    p24 = p[15]
    p25 = p[16]
    p26 = p[17]
    p33 = p[18]
    p34 = p[19]
    p35 = p[20]
    p36 = p[21]
    p44 = p[22]
    p45 = p[23]
    p46 = p[24]
    p55 = p[25]
    p56 = p[26]
    p66 = p[27]
    inn00 = -x + z_x
    inn10 = -y + z_y
    inn20 = -z + z_z
    _t0 = r*r
    S00 = _t0 + p00
    S11 = _t0 + p11
    S22 = _t0 + p22
    rdet = 1.0/(S00*S11*S22 - S00*(p12*p12) - S11*(p02*p02) - S22*(p01*p01) + 2.0*p01*p02*p12)
    Si00 = rdet*(S11*S22 - p12*p12)
    Si01 = rdet*(-(S22*p01) + p02*p12)
    Si02 = rdet*(-(S11*p02) + p01*p12)
    Si11 = rdet*(S00*S22 - p02*p02)
    Si12 = rdet*(-(S00*p12) + p01*p02)
    Si22 = rdet*(S00*S11 - p01*p01)
    _t1 = Si01*p01
    _t2 = Si02*p02
    _t3 = Si12*p12
    _t4 = 2.0*inn00
    k00 = Si00*p00 + _t1 + _t2
    k01 = Si01*p00 + Si11*p01 + Si12*p02
    k02 = Si02*p00 + Si12*p01 + Si22*p02
    k10 = Si00*p01 + Si01*p11 + Si02*p12
    k11 = Si11*p11 + _t1 + _t3
    k12 = Si02*p01 + Si12*p11 + Si22*p12
    k20 = Si00*p02 + Si01*p12 + Si02*p22
    k21 = Si01*p02 + Si11*p12 + Si12*p22
    k22 = Si22*p22 + _t2 + _t3
    k30 = Si00*p03 + Si01*p13 + Si02*p23
    k31 = Si01*p03 + Si11*p13 + Si12*p23
    k32 = Si02*p03 + Si12*p13 + Si22*p23
    k40 = Si00*p04 + Si01*p14 + Si02*p24
    k41 = Si01*p04 + Si11*p14 + Si12*p24
    k42 = Si02*p04 + Si12*p14 + Si22*p24
    k50 = Si00*p05 + Si01*p15 + Si02*p25
    k51 = Si01*p05 + Si11*p15 + Si12*p25
    k52 = Si02*p05 + Si12*p15 + Si22*p25
    k60 = Si00*p06 + Si01*p16 + Si02*p26
    k61 = Si01*p06 + Si11*p16 + Si12*p26
    k62 = Si02*p06 + Si12*p16 + Si22*p26
    nis = Si00*(inn00*inn00) + Si01*_t4*inn10 + Si02*_t4*inn20 + Si11*(inn10*inn10) + 2.0*Si12*inn10*inn20 + Si22*(inn20*inn20)
    nk0 = inn00*k00 + inn10*k01 + inn20*k02
    nk1 = inn00*k10 + inn10*k11 + inn20*k12
    nk2 = inn00*k20 + inn10*k21 + inn20*k22
    nk3 = inn00*k30 + inn10*k31 + inn20*k32
    nk4 = inn00*k40 + inn10*k41 + inn20*k42
    nk5 = inn00*k50 + inn10*k51 + inn20*k52
    nk6 = inn00*k60 + inn10*k61 + inn20*k62
    mu00 = nk0 + x
    mu01 = nk1 + y
    mu02 = nk2 + z
    mu03 = nk3 + psi
    mu04 = nk4 + v
    mu05 = nk5 + omega
    mu06 = nk6 + v_up
    a00 = 1.0 - k00
    a01 = -k01
    a02 = -k02
    a10 = -k10
    a11 = 1.0 - k11
    a12 = -k12
    a20 = -k20
    a21 = -k21
    a22 = 1.0 - k22
    a30 = -k30
    a31 = -k31
    a32 = -k32
    a40 = -k40
    a41 = -k41
    a42 = -k42
    a50 = -k50
    a51 = -k51
    a52 = -k52
    a60 = -k60
    a61 = -k61
    a62 = -k62
    b00 = a00*p00 + a01*p01 + a02*p02
    b01 = a00*p01 + a01*p11 + a02*p12
    b02 = a00*p02 + a01*p12 + a02*p22
    b03 = a00*p03 + a01*p13 + a02*p23
    b04 = a00*p04 + a01*p14 + a02*p24
    b05 = a00*p05 + a01*p15 + a02*p25
    b06 = a00*p06 + a01*p16 + a02*p26
    b10 = a10*p00 + a11*p01 + a12*p02
    b11 = a10*p01 + a11*p11 + a12*p12
    b12 = a10*p02 + a11*p12 + a12*p22
    b13 = a10*p03 + a11*p13 + a12*p23
    b14 = a10*p04 + a11*p14 + a12*p24
    b15 = a10*p05 + a11*p15 + a12*p25
    b16 = a10*p06 + a11*p16 + a12*p26
    b20 = a20*p00 + a21*p01 + a22*p02
    b21 = a20*p01 + a21*p11 + a22*p12
    b22 = a20*p02 + a21*p12 + a22*p22
    b23 = a20*p03 + a21*p13 + a22*p23
    b24 = a20*p04 + a21*p14 + a22*p24
    b25 = a20*p05 + a21*p15 + a22*p25
    b26 = a20*p06 + a21*p16 + a22*p26
    b30 = a30*p00 + a31*p01 + a32*p02 + p03
    b31 = a30*p01 + a31*p11 + a32*p12 + p13
    b32 = a30*p02 + a31*p12 + a32*p22 + p23
    b33 = a30*p03 + a31*p13 + a32*p23 + p33
    b34 = a30*p04 + a31*p14 + a32*p24 + p34
    b35 = a30*p05 + a31*p15 + a32*p25 + p35
    b36 = a30*p06 + a31*p16 + a32*p26 + p36
    b40 = a40*p00 + a41*p01 + a42*p02 + p04
    b41 = a40*p01 + a41*p11 + a42*p12 + p14
    b42 = a40*p02 + a41*p12 + a42*p22 + p24
    b44 = a40*p04 + a41*p14 + a42*p24 + p44
    b45 = a40*p05 + a41*p15 + a42*p25 + p45
    b46 = a40*p06 + a41*p16 + a42*p26 + p46
    b50 = a50*p00 + a51*p01 + a52*p02 + p05
    b51 = a50*p01 + a51*p11 + a52*p12 + p15
    b52 = a50*p02 + a51*p12 + a52*p22 + p25
    b55 = a50*p05 + a51*p15 + a52*p25 + p55
    b56 = a50*p06 + a51*p16 + a52*p26 + p56
    b60 = a60*p00 + a61*p01 + a62*p02 + p06
    b61 = a60*p01 + a61*p11 + a62*p12 + p16
    b62 = a60*p02 + a61*p12 + a62*p22 + p26
    b66 = a60*p06 + a61*p16 + a62*p26 + p66
    _t5 = r*r
    _t6 = _t5*k00
    _t7 = _t5*k01
    _t8 = _t5*k02
    _t9 = _t5*k10
    _t10 = _t5*k11
    _t11 = _t5*k12
    _t12 = _t5*k20
    _t13 = _t5*k21
    _t14 = _t5*k22
    _t15 = _t5*k30
    _t16 = _t5*k31
    _t17 = _t5*k32
    _t18 = _t5*k40
    _t19 = _t5*k41
    _t20 = _t5*k42
    pj00 = _t5*(k00*k00) + _t5*(k01*k01) + _t5*(k02*k02) + a00*b00 + a01*b01 + a02*b02
    pj01 = _t6*k10 + _t7*k11 + _t8*k12 + a10*b00 + a11*b01 + a12*b02
    pj02 = _t6*k20 + _t7*k21 + _t8*k22 + a20*b00 + a21*b01 + a22*b02
    pj03 = _t6*k30 + _t7*k31 + _t8*k32 + a30*b00 + a31*b01 + a32*b02 + b03
    pj04 = _t6*k40 + _t7*k41 + _t8*k42 + a40*b00 + a41*b01 + a42*b02 + b04
    pj05 = _t6*k50 + _t7*k51 + _t8*k52 + a50*b00 + a51*b01 + a52*b02 + b05
    pj06 = _t6*k60 + _t7*k61 + _t8*k62 + a60*b00 + a61*b01 + a62*b02 + b06
    pj11 = _t5*(k10*k10) + _t5*(k11*k11) + _t5*(k12*k12) + a10*b10 + a11*b11 + a12*b12
    pj12 = _t10*k21 + _t11*k22 + _t9*k20 + a20*b10 + a21*b11 + a22*b12
    pj13 = _t10*k31 + _t11*k32 + _t9*k30 + a30*b10 + a31*b11 + a32*b12 + b13
    pj14 = _t10*k41 + _t11*k42 + _t9*k40 + a40*b10 + a41*b11 + a42*b12 + b14
    pj15 = _t10*k51 + _t11*k52 + _t9*k50 + a50*b10 + a51*b11 + a52*b12 + b15
    pj16 = _t10*k61 + _t11*k62 + _t9*k60 + a60*b10 + a61*b11 + a62*b12 + b16
    pj22 = _t5*(k20*k20) + _t5*(k21*k21) + _t5*(k22*k22) + a20*b20 + a21*b21 + a22*b22
    pj23 = _t12*k30 + _t13*k31 + _t14*k32 + a30*b20 + a31*b21 + a32*b22 + b23
    pj24 = _t12*k40 + _t13*k41 + _t14*k42 + a40*b20 + a41*b21 + a42*b22 + b24
    pj25 = _t12*k50 + _t13*k51 + _t14*k52 + a50*b20 + a51*b21 + a52*b22 + b25
    pj26 = _t12*k60 + _t13*k61 + _t14*k62 + a60*b20 + a61*b21 + a62*b22 + b26
    pj33 = _t5*(k30*k30) + _t5*(k31*k31) + _t5*(k32*k32) + a30*b30 + a31*b31 + a32*b32 + b33
    pj34 = _t15*k40 + _t16*k41 + _t17*k42 + a40*b30 + a41*b31 + a42*b32 + b34
    pj35 = _t15*k50 + _t16*k51 + _t17*k52 + a50*b30 + a51*b31 + a52*b32 + b35
    pj36 = _t15*k60 + _t16*k61 + _t17*k62 + a60*b30 + a61*b31 + a62*b32 + b36
    pj44 = _t5*(k40*k40) + _t5*(k41*k41) + _t5*(k42*k42) + a40*b40 + a41*b41 + a42*b42 + b44
    pj45 = _t18*k50 + _t19*k51 + _t20*k52 + a50*b40 + a51*b41 + a52*b42 + b45
    pj46 = _t18*k60 + _t19*k61 + _t20*k62 + a60*b40 + a61*b41 + a62*b42 + b46
    pj55 = _t5*(k50*k50) + _t5*(k51*k51) + _t5*(k52*k52) + a50*b50 + a51*b51 + a52*b52 + b55
    pj56 = _t5*k50*k60 + _t5*k51*k61 + _t5*k52*k62 + a60*b50 + a61*b51 + a62*b52 + b56
    pj66 = _t5*(k60*k60) + _t5*(k61*k61) + _t5*(k62*k62) + a60*b60 + a61*b61 + a62*b62 + b66
    p[0] = pj00
    p[1] = pj01
    p[2] = pj02
    p[3] = pj03
    p[4] = pj04
    p[5] = pj05
    p[6] = pj06
    p[7] = pj11
    p[8] = pj12
    p[9] = pj13
    p[10] = pj14
    p[11] = pj15
    p[12] = pj16
    p[13] = pj22
    p[14] = pj23
    p[15] = pj24
    p[16] = pj25
    p[17] = pj26
    p[18] = pj33
    p[19] = pj34
    p[20] = pj35
    p[21] = pj36
    p[22] = pj44
    p[23] = pj45
    p[24] = pj46
    p[25] = pj55
    p[26] = pj56
    p[27] = pj66
    s[0] = mu00
    s[1] = mu01
    s[2] = mu02
    s[3] = mu03
    s[4] = mu04
    s[5] = mu05
    s[6] = mu06
    return nis


@nb.njit(cache=True, fastmath=FASTMATH, error_model="numpy")
def step_try_position3(s, p, dt, sigma_a, sigma_alpha, sigma_z, z_x, z_y, z_z, r):
    """One fused LG-EKF step with a position3 measurement, in place: ``predict`` then ``update_position3``
    (eq:pred_mu, eq:pred_cov, angle-variance cap, eq:K, eq:up_mu, eq:up_P) in one kernel; returns the NIS.
    Covariance as P − βKℋP; a step whose result fails the LDLᵀ test (covariance_is_pd_fused) leaves the
    prediction in s, p and returns -1.0: the caller then runs update_position3 (Joseph form;
    derive/codegen/fused.py).
    legend: cc = 𝒞 (eq:C), f = F = Ad(exp(−Ω)) + Φ(Ω)𝒞 (eq:pred_cov), g = Φ(Ω)G, hh = ℋ (eq:calH), hp = ℋP, inn = [log_G'(h(μ)⁻¹Z)]^∨, S = ℋPℋᵀ + R, Si = S⁻¹, k = K (eq:K), nk = Kν, alpha = gain damping, nu = ν, phi = Φ(ν) (eq:up_P), a = I − αKℋ, b = aP, beta = α(2 − α), kb = βK, pj = Joseph-form P (= P − βKℋP), cp = Φ(ν)·pj, mu/e = new mean
    """
    x = s[0]
    y = s[1]
    z = s[2]
    psi = s[3]
    v = s[4]
    omega = s[5]
    v_up = s[6]
    p00 = p[0]
    p01 = p[1]
    p02 = p[2]
    p03 = p[3]
    p04 = p[4]
    p05 = p[5]
    p06 = p[6]
    p11 = p[7]
    p12 = p[8]
    p13 = p[9]
    p14 = p[10]
    p15 = p[11]
    p16 = p[12]
    p22 = p[13]
    p23 = p[14]
    p24 = p[15]
    p25 = p[16]
    p26 = p[17]
    p33 = p[18]
    p34 = p[19]
    p35 = p[20]
    p36 = p[21]
    p44 = p[22]
    p45 = p[23]
    p46 = p[24]
    p55 = p[25]
    p56 = p[26]
    p66 = p[27]
    _a0 = dt*omega/2.0
    _sin__a0 = math.sin(_a0)
    _cos__a0 = math.cos(_a0)
    _dsinc__a0 = dsinc(_a0, _sin__a0, _cos__a0)
    _sinc__a0 = sinc(_a0, _sin__a0, _cos__a0)
    _a1 = dt*omega/2.0 + psi
    _sin__a1 = math.sin(_a1)
    _cos__a1 = math.cos(_a1)
    _t0 = _sin__a1*_sinc__a0
    _t1 = _t0*dt
    _t2 = _cos__a1*_sinc__a0
    _t3 = _t2*dt
    _t4 = (dt*dt)*v/2.0
    cc03 = -(_t1*v)
    cc04 = _t3
    cc05 = -(_t4*(_cos__a1*_dsinc__a0 + _t0))
    cc13 = _t3*v
    cc14 = _t1
    cc15 = _t4*(-(_dsinc__a0*_sin__a1) + _t2)
    _sin_psi = math.sin(psi)
    _cos_psi = math.cos(psi)
    _t5 = (dt*dt)/2.0
    _t6 = _sinc__a0*dt*v
    g00 = _cos_psi*_t5
    g10 = _sin_psi*_t5
    g22 = _t5
    g31 = _t5
    e00 = _cos__a1*_t6 + x
    e01 = _sin__a1*_t6 + y
    e02 = dt*v_up + z
    e03 = dt*omega + psi
    _t7 = dt*p56
    m00 = cc03*p03 + cc04*p04 + cc05*p05 + p00
    m01 = cc03*p13 + cc04*p14 + cc05*p15 + p01
    m02 = cc03*p23 + cc04*p24 + cc05*p25 + p02
    m03 = cc03*p33 + cc04*p34 + cc05*p35 + p03
    m04 = cc03*p34 + cc04*p44 + cc05*p45 + p04
    m05 = cc03*p35 + cc04*p45 + cc05*p55 + p05
    m06 = cc03*p36 + cc04*p46 + cc05*p56 + p06
    m11 = cc13*p13 + cc14*p14 + cc15*p15 + p11
    m12 = cc13*p23 + cc14*p24 + cc15*p25 + p12
    m13 = cc13*p33 + cc14*p34 + cc15*p35 + p13
    m14 = cc13*p34 + cc14*p44 + cc15*p45 + p14
    m15 = cc13*p35 + cc14*p45 + cc15*p55 + p15
    m16 = cc13*p36 + cc14*p46 + cc15*p56 + p16
    m22 = dt*p26 + p22
    m23 = dt*p36 + p23
    m24 = dt*p46 + p24
    m25 = _t7 + p25
    m26 = dt*p66 + p26
    m33 = dt*p35 + p33
    m34 = dt*p45 + p34
    m35 = dt*p55 + p35
    m36 = _t7 + p36
    _t8 = sigma_a*sigma_a
    _t9 = _t8*g00
    _t10 = sigma_z*sigma_z
    _t11 = sigma_alpha*sigma_alpha
    _t12 = dt*dt
    pp00 = _t8*(g00*g00) + cc03*m03 + cc04*m04 + cc05*m05 + m00
    pp01 = _t9*g10 + cc13*m03 + cc14*m04 + cc15*m05 + m01
    pp02 = dt*m06 + m02
    pp03 = dt*m05 + m03
    pp04 = _t9*dt + m04
    pp05 = m05
    pp06 = m06
    pp11 = _t8*(g10*g10) + cc13*m13 + cc14*m14 + cc15*m15 + m11
    pp12 = dt*m16 + m12
    pp13 = dt*m15 + m13
    pp14 = _t8*dt*g10 + m14
    pp15 = m15
    pp16 = m16
    pp22 = _t10*(g22*g22) + dt*m26 + m22
    pp23 = dt*m25 + m23
    pp24 = m24
    pp25 = m25
    pp26 = _t10*dt*g22 + m26
    pp33 = _t11*(g31*g31) + dt*m35 + m33
    pp34 = m34
    pp35 = _t11*dt*g31 + m35
    pp36 = m36
    pp44 = _t12*_t8 + p44
    pp45 = p45
    pp46 = p46
    pp55 = _t11*_t12 + p55
    pp56 = p56
    pp66 = _t10*_t12 + p66
    x_p = e00
    y_p = e01
    z_p = e02
    psi_p = e03
    inn00 = -x_p + z_x
    inn10 = -y_p + z_y
    inn20 = -z_p + z_z
    _t13 = r*r
    S00 = _t13 + pp00
    S11 = _t13 + pp11
    S22 = _t13 + pp22
    rdet = 1.0/(S00*S11*S22 - S00*(pp12*pp12) - S11*(pp02*pp02) - S22*(pp01*pp01) + 2.0*pp01*pp02*pp12)
    Si00 = rdet*(S11*S22 - pp12*pp12)
    Si01 = rdet*(-(S22*pp01) + pp02*pp12)
    Si02 = rdet*(-(S11*pp02) + pp01*pp12)
    Si11 = rdet*(S00*S22 - pp02*pp02)
    Si12 = rdet*(-(S00*pp12) + pp01*pp02)
    Si22 = rdet*(S00*S11 - pp01*pp01)
    _t14 = Si01*pp01
    _t15 = Si02*pp02
    _t16 = Si12*pp12
    _t17 = 2.0*inn00
    k00 = Si00*pp00 + _t14 + _t15
    k01 = Si01*pp00 + Si11*pp01 + Si12*pp02
    k02 = Si02*pp00 + Si12*pp01 + Si22*pp02
    k10 = Si00*pp01 + Si01*pp11 + Si02*pp12
    k11 = Si11*pp11 + _t14 + _t16
    k12 = Si02*pp01 + Si12*pp11 + Si22*pp12
    k20 = Si00*pp02 + Si01*pp12 + Si02*pp22
    k21 = Si01*pp02 + Si11*pp12 + Si12*pp22
    k22 = Si22*pp22 + _t15 + _t16
    k30 = Si00*pp03 + Si01*pp13 + Si02*pp23
    k31 = Si01*pp03 + Si11*pp13 + Si12*pp23
    k32 = Si02*pp03 + Si12*pp13 + Si22*pp23
    k40 = Si00*pp04 + Si01*pp14 + Si02*pp24
    k41 = Si01*pp04 + Si11*pp14 + Si12*pp24
    k42 = Si02*pp04 + Si12*pp14 + Si22*pp24
    k50 = Si00*pp05 + Si01*pp15 + Si02*pp25
    k51 = Si01*pp05 + Si11*pp15 + Si12*pp25
    k52 = Si02*pp05 + Si12*pp15 + Si22*pp25
    k60 = Si00*pp06 + Si01*pp16 + Si02*pp26
    k61 = Si01*pp06 + Si11*pp16 + Si12*pp26
    k62 = Si02*pp06 + Si12*pp16 + Si22*pp26
    nis = Si00*(inn00*inn00) + Si01*_t17*inn10 + Si02*_t17*inn20 + Si11*(inn10*inn10) + 2.0*Si12*inn10*inn20 + Si22*(inn20*inn20)
    nk0 = inn00*k00 + inn10*k01 + inn20*k02
    nk1 = inn00*k10 + inn10*k11 + inn20*k12
    nk2 = inn00*k20 + inn10*k21 + inn20*k22
    nk3 = inn00*k30 + inn10*k31 + inn20*k32
    nk4 = inn00*k40 + inn10*k41 + inn20*k42
    nk5 = inn00*k50 + inn10*k51 + inn20*k52
    nk6 = inn00*k60 + inn10*k61 + inn20*k62
    mu00 = nk0 + x_p
    mu01 = nk1 + y_p
    mu02 = nk2 + z_p
    mu03 = nk3 + psi_p
    mu04 = nk4 + v
    mu05 = nk5 + omega
    mu06 = nk6 + v_up
    pj00 = -(k00*pp00) - k01*pp01 - k02*pp02 + pp00
    pj01 = -(k00*pp01) - k01*pp11 - k02*pp12 + pp01
    pj02 = -(k00*pp02) - k01*pp12 - k02*pp22 + pp02
    pj03 = -(k00*pp03) - k01*pp13 - k02*pp23 + pp03
    pj04 = -(k00*pp04) - k01*pp14 - k02*pp24 + pp04
    pj05 = -(k00*pp05) - k01*pp15 - k02*pp25 + pp05
    pj06 = -(k00*pp06) - k01*pp16 - k02*pp26 + pp06
    pj11 = -(k10*pp01) - k11*pp11 - k12*pp12 + pp11
    pj12 = -(k10*pp02) - k11*pp12 - k12*pp22 + pp12
    pj13 = -(k10*pp03) - k11*pp13 - k12*pp23 + pp13
    pj14 = -(k10*pp04) - k11*pp14 - k12*pp24 + pp14
    pj15 = -(k10*pp05) - k11*pp15 - k12*pp25 + pp15
    pj16 = -(k10*pp06) - k11*pp16 - k12*pp26 + pp16
    pj22 = -(k20*pp02) - k21*pp12 - k22*pp22 + pp22
    pj23 = -(k20*pp03) - k21*pp13 - k22*pp23 + pp23
    pj24 = -(k20*pp04) - k21*pp14 - k22*pp24 + pp24
    pj25 = -(k20*pp05) - k21*pp15 - k22*pp25 + pp25
    pj26 = -(k20*pp06) - k21*pp16 - k22*pp26 + pp26
    pj33 = -(k30*pp03) - k31*pp13 - k32*pp23 + pp33
    pj34 = -(k30*pp04) - k31*pp14 - k32*pp24 + pp34
    pj35 = -(k30*pp05) - k31*pp15 - k32*pp25 + pp35
    pj36 = -(k30*pp06) - k31*pp16 - k32*pp26 + pp36
    pj44 = -(k40*pp04) - k41*pp14 - k42*pp24 + pp44
    pj45 = -(k40*pp05) - k41*pp15 - k42*pp25 + pp45
    pj46 = -(k40*pp06) - k41*pp16 - k42*pp26 + pp46
    pj55 = -(k50*pp05) - k51*pp15 - k52*pp25 + pp55
    pj56 = -(k50*pp06) - k51*pp16 - k52*pp26 + pp56
    pj66 = -(k60*pp06) - k61*pp16 - k62*pp26 + pp66
    out_p0 = pj00
    out_p1 = pj01
    out_p2 = pj02
    out_p3 = pj03
    out_p4 = pj04
    out_p5 = pj05
    out_p6 = pj06
    out_p7 = pj11
    out_p8 = pj12
    out_p9 = pj13
    out_p10 = pj14
    out_p11 = pj15
    out_p12 = pj16
    out_p13 = pj22
    out_p14 = pj23
    out_p15 = pj24
    out_p16 = pj25
    out_p17 = pj26
    out_p18 = pj33
    out_p19 = pj34
    out_p20 = pj35
    out_p21 = pj36
    out_p22 = pj44
    out_p23 = pj45
    out_p24 = pj46
    out_p25 = pj55
    out_p26 = pj56
    out_p27 = pj66
    out_s0 = mu00
    out_s1 = mu01
    out_s2 = mu02
    out_s3 = mu03
    out_s4 = mu04
    out_s5 = mu05
    out_s6 = mu06
    if not covariance_is_pd_fused(out_p0, out_p1, out_p2, out_p3, out_p4, out_p5, out_p6, out_p7, out_p8, out_p9, out_p10, out_p11, out_p12, out_p13, out_p14, out_p15, out_p16, out_p17, out_p18, out_p19, out_p20, out_p21, out_p22, out_p23, out_p24, out_p25, out_p26, out_p27):
        out_p0 = pp00
        out_p1 = pp01
        out_p2 = pp02
        out_p3 = pp03
        out_p4 = pp04
        out_p5 = pp05
        out_p6 = pp06
        out_p7 = pp11
        out_p8 = pp12
        out_p9 = pp13
        out_p10 = pp14
        out_p11 = pp15
        out_p12 = pp16
        out_p13 = pp22
        out_p14 = pp23
        out_p15 = pp24
        out_p16 = pp25
        out_p17 = pp26
        out_p18 = pp33
        out_p19 = pp34
        out_p20 = pp35
        out_p21 = pp36
        out_p22 = pp44
        out_p23 = pp45
        out_p24 = pp46
        out_p25 = pp55
        out_p26 = pp56
        out_p27 = pp66
        out_s0 = x_p
        out_s1 = y_p
        out_s2 = z_p
        out_s3 = psi_p
        out_s4 = v
        out_s5 = omega
        out_s6 = v_up
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
    p[21] = out_p21
    p[22] = out_p22
    p[23] = out_p23
    p[24] = out_p24
    p[25] = out_p25
    p[26] = out_p26
    p[27] = out_p27
    s[0] = out_s0
    s[1] = out_s1
    s[2] = out_s2
    s[3] = out_s3
    s[4] = out_s4
    s[5] = out_s5
    s[6] = out_s6
    return nis


@nb.njit(cache=True)
def step_position3(s, p, dt, sigma_a, sigma_alpha, sigma_z, z_x, z_y, z_z, r):
    """One LG-EKF step with a position3 measurement, in place; returns the NIS: ``step_try_position3``, and on the rare
    step whose cheap covariance fails the LDLᵀ test, ``update_position3`` (Joseph form) from the prediction
    (derive/codegen/fused.py)."""
    nis = step_try_position3(s, p, dt, sigma_a, sigma_alpha, sigma_z, z_x, z_y, z_z, r)
    if nis < 0.0:
        nis = update_position3(s, p, z_x, z_y, z_z, r)
    return nis


@nb.njit(cache=True)
def measure_position3(s, m0, m1, m2):
    """Simulated position3 measurement vector(h(X)·exp(m)) of the state s for a noise sample m.
    """
    x = s[0]
    y = s[1]
    z = s[2]
    out = np.zeros(3)
    out[0] = m0 + x
    out[1] = m1 + y
    out[2] = m2 + z
    return out


@nb.njit(cache=True, nogil=True)  # nogil: the process-noise search (lgekf.apps.search) runs filters in threads
def run_one_position3(z, dts, x0, p0, q, r, out_x, out_p, out_nis):
    """Filter one trajectory with position3 measurements: z (K, 3), dts (K,), x0 (7,), p0 (28,).

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
            nis = step_try_position3(s, p, dts[k], q[0], q[1], q[2], z[k, 0], z[k, 1], z[k, 2], r[0])
            if nis < 0.0:  # rare: the cheap covariance failed the LDLᵀ test; Joseph form from the prediction
                nis = update_position3(s, p, z[k, 0], z[k, 1], z[k, 2], r[0])
            out_nis[k] = nis
        physical_into(s, out_x[k])
        if keep_p:
            for i in range(28):
                out_p[k, i] = p[i]


@nb.njit(cache=True, nogil=True)
def run_segments_position3(z, t, first, lengths, x0, p0, q, r, out_x, out_p, out_nis):
    """``run_one_position3`` on segments of rows, one after the other (no Python per segment).

    Segment i is rows first[i] .. first[i] + lengths[i] - 1 (first[i] >= 1) of z (N, 3) and t (N,), filtered
    from x0[i] (7,), p0[i] (28,) at time t[first[i] - 1]; its outputs go to the same rows of out_x (N, 7),
    out_p (N, 28) and out_nis (N,). The numbers of ``run_one_position3`` called per segment with
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
        run_one_position3(z[a:b], dts[:b - a], x0[i], p0[i], q, r, out_x[a:b], out_p[a:b], out_nis[a:b])


@nb.njit(cache=True, nogil=True)
def run_one_from_position3(z, dts, s0, p0, q, r, out_x, out_p, out_nis):
    """``run_one_position3`` from the internal state s0 (7,) (the layout of ``state_from_physical``) and p0 (28,),
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
            nis = step_try_position3(s, p, dts[k], q[0], q[1], q[2], z[k, 0], z[k, 1], z[k, 2], r[0])
            if nis < 0.0:  # rare: the cheap covariance failed the LDLᵀ test; Joseph form from the prediction
                nis = update_position3(s, p, z[k, 0], z[k, 1], z[k, 2], r[0])
            out_nis[k] = nis
        physical_into(s, out_x[k])
        if keep_p:
            for i in range(28):
                out_p[k, i] = p[i]
    s0[:] = s
    p0[:] = p


@nb.njit(cache=True, nogil=True)
def run_segments_from_position3(z, t, first, lengths, s0, p0, q, r, out_x, out_p, out_nis):
    """``run_segments_position3`` from internal states s0 (S, 7) and p0 (S, 28) (``run_one_from_position3``): on
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
        run_one_from_position3(z[a:b], dts[:b - a], s0[i], p0[i], q, r, out_x[a:b], out_p[a:b], out_nis[a:b])


@nb.njit(cache=True, parallel=True)
def run_batch_position3(z, dts, x0, p0, q, r, out_x, out_p, out_nis):
    """Filter B trajectories in parallel (numba prange), predict then update at every step.

    z (B, K, 3) position3 measurements (a NaN row = missed detection); dts (B, K) step lengths; x0 (B, 7)
    physical initial states; p0 (B, 28) packed initial covariances; q (3,) process-noise stds;
    r (1,) measurement-noise stds. Writes the posterior physical states into out_x (B, K, 7), the
    packed covariances into out_p (B, K, 28) when out_p.shape[1] == K (pass (B, 0, 28) to skip),
    and the NIS into out_nis (B, K).
    """
    for b in nb.prange(z.shape[0]):
        run_one_position3(z[b], dts[b], x0[b], p0[b], q, r, out_x[b], out_p[b], out_nis[b])


@nb.njit(cache=True)
def measure_batch_position3(X, noise, out):
    """Simulated position3 measurements z = vector(h(X)·exp(m)) of every physical state X (N, 7),
    noise samples m (N, 3) (already scaled), into out (N, 3)."""
    for i in range(X.shape[0]):
        s = state_from_physical(X[i])
        z = measure_position3(s, noise[i, 0], noise[i, 1], noise[i, 2])
        for j in range(3):
            out[i, j] = z[j]


@nb.njit(cache=True)
def innovation_into_position3(s, z_x, z_y, z_z, out):
    """The position3 innovation e = [log_G'(h(μ)⁻¹ Z)]^∨ (eq:K) of the state s for the measured z, written into out (3,).
    """
    x = s[0]
    y = s[1]
    z = s[2]
    out[0] = -x + z_x
    out[1] = -y + z_y
    out[2] = -z + z_z


@nb.njit(cache=True)
def innovation_bank_position3(s, live, z, out):
    """Innovation [log_G'(h(μ_i)⁻¹ Z_j)]^∨ of every live track i (rows of s, live[i] true) and every
    position3 detection j (rows of z, (M, 3)) into out (N, M, 3); rows of dead tracks are not written."""
    for i in range(s.shape[0]):
        if live[i]:
            si = s[i]
            for j in range(z.shape[0]):
                innovation_into_position3(si, z[j, 0], z[j, 1], z[j, 2], out[i, j])


@nb.njit(cache=True)
def calH_bank_position3(s, live, out):
    """ℋ (eq:calH) of every live track for position3 measurements into out (N, 3, 7)."""
    for i in range(s.shape[0]):
        if live[i]:
            h = calH_position3(s[i])
            for a in range(3):
                for b in range(7):
                    out[i, a, b] = h[a, b]


@nb.njit(cache=True, nogil=True)
def run_segments_noise_from_position3(z, t, first, lengths, s0, p0, q, r, out_x, out_p, out_nis):
    """``run_segments_from_position3`` with noise stds of each segment's own: q (S, 3), r (S, 1) (the divergence
    recovery's reruns, each object's noise inflated by its own factor). On return s0[i], p0[i] hold the posterior
    of segment i's last row, from which a later call continues exactly. The numbers of ``run_one_from_position3``
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
        run_one_from_position3(z[a:b], dts[:b - a], s0[i], p0[i], q[i], r[i], out_x[a:b], out_p[a:b], out_nis[a:b])


@nb.njit(cache=True, nogil=True, error_model="numpy")
def rerun_position3(zm, t, a, b, s1, p1, q, r, scale, q1, r1, x, p, nis):
    """Filter rows a .. b - 1 from the internal state s1 (1, ni) and packed covariance p1 (1, n(n+1)/2) of row a - 1, every
    noise std times ``scale`` (q1, r1 (1, nq), (1, nr) scratch), into x, p, nis; s1, p1 are left at row b - 1."""
    for j in range(q.shape[0]):
        q1[0, j] = q[j] * scale
    for j in range(r.shape[0]):
        r1[0, j] = r[j] * scale
    run_segments_noise_from_position3(zm, t, np.full(1, a, np.int64), np.full(1, b - a, np.int64), s1, p1, q1, r1, x, p, nis)


@nb.njit(cache=True, nogil=True, error_model="numpy")
def recover_position3(
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
            rerun_position3(zm, t, run_first[si], end, s1, p1, q, r, run_scale, q1, r1, x, p, nis)
            reached = True
        while True:
            g, kind, val, start, lim = first_alarm(x, p, nis, scan_from, scan_end, limits[o], window, short, clip, thr, thr_short,
                                                   n_sigma, over, absurd, bad, sp, rows, xh, grad)
            if g < 0:
                if scan_end >= end:
                    break
                # no alarm in this window: the next, twice as wide, goes on from where the run stopped
                new_end = min(end, first + 2 * (scan_end - first))
                rerun_position3(zm, t, scan_end, new_end, s1, p1, q, r, run_scale, q1, r1, x, p, nis)
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
                    rerun_position3(zm, t, scan_end, end, s1, p1, q, r, run_scale, q1, r1, x, p, nis)
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
            rerun_position3(zm, t, first, scan_end, s1, p1, q, r, run_scale, q1, r1, x, p, nis)
            reached = scan_end == end
        if reached:
            copy_row(s1, 0, carry_s, o)
            copy_row(p1, 0, carry_p, o)
            carry_scale[o] = run_scale
            carry_reached[o] = True
    return found[:na]


@nb.njit(inline="always", fastmath={"contract"}, error_model="numpy")
def lane_position3(W, j, sigma_a, sigma_alpha, sigma_z, r):
    """step_position3 on lane j of the work array W (rows: derive/codegen/soa.py Layout), without branches (SIMD).
    """
    x = W[0 + j]
    y = W[64 + j]
    z = W[128 + j]
    psi = W[192 + j]
    v = W[256 + j]
    omega = W[320 + j]
    v_up = W[384 + j]
    p00 = W[448 + j]
    p01 = W[512 + j]
    p02 = W[576 + j]
    p03 = W[640 + j]
    p04 = W[704 + j]
    p05 = W[768 + j]
    p06 = W[832 + j]
    p11 = W[896 + j]
    p12 = W[960 + j]
    p13 = W[1024 + j]
    p14 = W[1088 + j]
    p15 = W[1152 + j]
    p16 = W[1216 + j]
    p22 = W[1280 + j]
    p23 = W[1344 + j]
    p24 = W[1408 + j]
    p25 = W[1472 + j]
    p26 = W[1536 + j]
    p33 = W[1600 + j]
    p34 = W[1664 + j]
    p35 = W[1728 + j]
    p36 = W[1792 + j]
    p44 = W[1856 + j]
    p45 = W[1920 + j]
    p46 = W[1984 + j]
    p55 = W[2048 + j]
    p56 = W[2112 + j]
    p66 = W[2176 + j]
    dt = W[4480 + j]
    z_x = W[4672 + j]
    z_y = W[4736 + j]
    z_z = W[4800 + j]
    _a0 = dt*omega/2.0
    _sin__a0 = sin_v(_a0)
    _cos__a0 = cos_v(_a0)
    _dsinc__a0 = dsinc_v(_a0, _sin__a0, _cos__a0)
    _sinc__a0 = sinc_v(_a0, _sin__a0, _cos__a0)
    _a1 = dt*omega/2.0 + psi
    _sin__a1 = sin_v(_a1)
    _cos__a1 = cos_v(_a1)
    _t0 = _sin__a1*_sinc__a0
    _t1 = _t0*dt
    _t2 = _cos__a1*_sinc__a0
    _t3 = _t2*dt
    _t4 = (dt*dt)*v/2.0
    cc03 = -(_t1*v)
    cc04 = _t3
    cc05 = -(_t4*(_cos__a1*_dsinc__a0 + _t0))
    cc13 = _t3*v
    cc14 = _t1
    cc15 = _t4*(-(_dsinc__a0*_sin__a1) + _t2)
    _sin_psi = sin_v(psi)
    _cos_psi = cos_v(psi)
    _t5 = (dt*dt)/2.0
    _t6 = _sinc__a0*dt*v
    g00 = _cos_psi*_t5
    g10 = _sin_psi*_t5
    g22 = _t5
    g31 = _t5
    e00 = _cos__a1*_t6 + x
    e01 = _sin__a1*_t6 + y
    e02 = dt*v_up + z
    e03 = dt*omega + psi
    _t7 = dt*p56
    m00 = cc03*p03 + cc04*p04 + cc05*p05 + p00
    m01 = cc03*p13 + cc04*p14 + cc05*p15 + p01
    m02 = cc03*p23 + cc04*p24 + cc05*p25 + p02
    m03 = cc03*p33 + cc04*p34 + cc05*p35 + p03
    m04 = cc03*p34 + cc04*p44 + cc05*p45 + p04
    m05 = cc03*p35 + cc04*p45 + cc05*p55 + p05
    m06 = cc03*p36 + cc04*p46 + cc05*p56 + p06
    m11 = cc13*p13 + cc14*p14 + cc15*p15 + p11
    m12 = cc13*p23 + cc14*p24 + cc15*p25 + p12
    m13 = cc13*p33 + cc14*p34 + cc15*p35 + p13
    m14 = cc13*p34 + cc14*p44 + cc15*p45 + p14
    m15 = cc13*p35 + cc14*p45 + cc15*p55 + p15
    m16 = cc13*p36 + cc14*p46 + cc15*p56 + p16
    m22 = dt*p26 + p22
    m23 = dt*p36 + p23
    m24 = dt*p46 + p24
    m25 = _t7 + p25
    m26 = dt*p66 + p26
    m33 = dt*p35 + p33
    m34 = dt*p45 + p34
    m35 = dt*p55 + p35
    m36 = _t7 + p36
    _t8 = sigma_a*sigma_a
    _t9 = _t8*g00
    _t10 = sigma_z*sigma_z
    _t11 = sigma_alpha*sigma_alpha
    _t12 = dt*dt
    pp00 = _t8*(g00*g00) + cc03*m03 + cc04*m04 + cc05*m05 + m00
    pp01 = _t9*g10 + cc13*m03 + cc14*m04 + cc15*m05 + m01
    pp02 = dt*m06 + m02
    pp03 = dt*m05 + m03
    pp04 = _t9*dt + m04
    pp05 = m05
    pp06 = m06
    pp11 = _t8*(g10*g10) + cc13*m13 + cc14*m14 + cc15*m15 + m11
    pp12 = dt*m16 + m12
    pp13 = dt*m15 + m13
    pp14 = _t8*dt*g10 + m14
    pp15 = m15
    pp16 = m16
    pp22 = _t10*(g22*g22) + dt*m26 + m22
    pp23 = dt*m25 + m23
    pp24 = m24
    pp25 = m25
    pp26 = _t10*dt*g22 + m26
    pp33 = _t11*(g31*g31) + dt*m35 + m33
    pp34 = m34
    pp35 = _t11*dt*g31 + m35
    pp36 = m36
    pp44 = _t12*_t8 + p44
    pp45 = p45
    pp46 = p46
    pp55 = _t11*_t12 + p55
    pp56 = p56
    pp66 = _t10*_t12 + p66
    x_p = e00
    y_p = e01
    z_p = e02
    psi_p = e03
    inn00 = -x_p + z_x
    inn10 = -y_p + z_y
    inn20 = -z_p + z_z
    _t13 = r*r
    S00 = _t13 + pp00
    S11 = _t13 + pp11
    S22 = _t13 + pp22
    rdet = 1.0/(S00*S11*S22 - S00*(pp12*pp12) - S11*(pp02*pp02) - S22*(pp01*pp01) + 2.0*pp01*pp02*pp12)
    Si00 = rdet*(S11*S22 - pp12*pp12)
    Si01 = rdet*(-(S22*pp01) + pp02*pp12)
    Si02 = rdet*(-(S11*pp02) + pp01*pp12)
    Si11 = rdet*(S00*S22 - pp02*pp02)
    Si12 = rdet*(-(S00*pp12) + pp01*pp02)
    Si22 = rdet*(S00*S11 - pp01*pp01)
    _t14 = Si01*pp01
    _t15 = Si02*pp02
    _t16 = Si12*pp12
    _t17 = 2.0*inn00
    k00 = Si00*pp00 + _t14 + _t15
    k01 = Si01*pp00 + Si11*pp01 + Si12*pp02
    k02 = Si02*pp00 + Si12*pp01 + Si22*pp02
    k10 = Si00*pp01 + Si01*pp11 + Si02*pp12
    k11 = Si11*pp11 + _t14 + _t16
    k12 = Si02*pp01 + Si12*pp11 + Si22*pp12
    k20 = Si00*pp02 + Si01*pp12 + Si02*pp22
    k21 = Si01*pp02 + Si11*pp12 + Si12*pp22
    k22 = Si22*pp22 + _t15 + _t16
    k30 = Si00*pp03 + Si01*pp13 + Si02*pp23
    k31 = Si01*pp03 + Si11*pp13 + Si12*pp23
    k32 = Si02*pp03 + Si12*pp13 + Si22*pp23
    k40 = Si00*pp04 + Si01*pp14 + Si02*pp24
    k41 = Si01*pp04 + Si11*pp14 + Si12*pp24
    k42 = Si02*pp04 + Si12*pp14 + Si22*pp24
    k50 = Si00*pp05 + Si01*pp15 + Si02*pp25
    k51 = Si01*pp05 + Si11*pp15 + Si12*pp25
    k52 = Si02*pp05 + Si12*pp15 + Si22*pp25
    k60 = Si00*pp06 + Si01*pp16 + Si02*pp26
    k61 = Si01*pp06 + Si11*pp16 + Si12*pp26
    k62 = Si02*pp06 + Si12*pp16 + Si22*pp26
    nis = Si00*(inn00*inn00) + Si01*_t17*inn10 + Si02*_t17*inn20 + Si11*(inn10*inn10) + 2.0*Si12*inn10*inn20 + Si22*(inn20*inn20)
    nk0 = inn00*k00 + inn10*k01 + inn20*k02
    nk1 = inn00*k10 + inn10*k11 + inn20*k12
    nk2 = inn00*k20 + inn10*k21 + inn20*k22
    nk3 = inn00*k30 + inn10*k31 + inn20*k32
    nk4 = inn00*k40 + inn10*k41 + inn20*k42
    nk5 = inn00*k50 + inn10*k51 + inn20*k52
    nk6 = inn00*k60 + inn10*k61 + inn20*k62
    mu00 = nk0 + x_p
    mu01 = nk1 + y_p
    mu02 = nk2 + z_p
    mu03 = nk3 + psi_p
    mu04 = nk4 + v
    mu05 = nk5 + omega
    mu06 = nk6 + v_up
    pj00 = -(k00*pp00) - k01*pp01 - k02*pp02 + pp00
    pj01 = -(k00*pp01) - k01*pp11 - k02*pp12 + pp01
    pj02 = -(k00*pp02) - k01*pp12 - k02*pp22 + pp02
    pj03 = -(k00*pp03) - k01*pp13 - k02*pp23 + pp03
    pj04 = -(k00*pp04) - k01*pp14 - k02*pp24 + pp04
    pj05 = -(k00*pp05) - k01*pp15 - k02*pp25 + pp05
    pj06 = -(k00*pp06) - k01*pp16 - k02*pp26 + pp06
    pj11 = -(k10*pp01) - k11*pp11 - k12*pp12 + pp11
    pj12 = -(k10*pp02) - k11*pp12 - k12*pp22 + pp12
    pj13 = -(k10*pp03) - k11*pp13 - k12*pp23 + pp13
    pj14 = -(k10*pp04) - k11*pp14 - k12*pp24 + pp14
    pj15 = -(k10*pp05) - k11*pp15 - k12*pp25 + pp15
    pj16 = -(k10*pp06) - k11*pp16 - k12*pp26 + pp16
    pj22 = -(k20*pp02) - k21*pp12 - k22*pp22 + pp22
    pj23 = -(k20*pp03) - k21*pp13 - k22*pp23 + pp23
    pj24 = -(k20*pp04) - k21*pp14 - k22*pp24 + pp24
    pj25 = -(k20*pp05) - k21*pp15 - k22*pp25 + pp25
    pj26 = -(k20*pp06) - k21*pp16 - k22*pp26 + pp26
    pj33 = -(k30*pp03) - k31*pp13 - k32*pp23 + pp33
    pj34 = -(k30*pp04) - k31*pp14 - k32*pp24 + pp34
    pj35 = -(k30*pp05) - k31*pp15 - k32*pp25 + pp35
    pj36 = -(k30*pp06) - k31*pp16 - k32*pp26 + pp36
    pj44 = -(k40*pp04) - k41*pp14 - k42*pp24 + pp44
    pj45 = -(k40*pp05) - k41*pp15 - k42*pp25 + pp45
    pj46 = -(k40*pp06) - k41*pp16 - k42*pp26 + pp46
    pj55 = -(k50*pp05) - k51*pp15 - k52*pp25 + pp55
    pj56 = -(k50*pp06) - k51*pp16 - k52*pp26 + pp56
    pj66 = -(k60*pp06) - k61*pp16 - k62*pp26 + pp66
    W[2688 + j] = pj00
    W[2752 + j] = pj01
    W[2816 + j] = pj02
    W[2880 + j] = pj03
    W[2944 + j] = pj04
    W[3008 + j] = pj05
    W[3072 + j] = pj06
    W[3136 + j] = pj11
    W[3200 + j] = pj12
    W[3264 + j] = pj13
    W[3328 + j] = pj14
    W[3392 + j] = pj15
    W[3456 + j] = pj16
    W[3520 + j] = pj22
    W[3584 + j] = pj23
    W[3648 + j] = pj24
    W[3712 + j] = pj25
    W[3776 + j] = pj26
    W[3840 + j] = pj33
    W[3904 + j] = pj34
    W[3968 + j] = pj35
    W[4032 + j] = pj36
    W[4096 + j] = pj44
    W[4160 + j] = pj45
    W[4224 + j] = pj46
    W[4288 + j] = pj55
    W[4352 + j] = pj56
    W[4416 + j] = pj66
    W[2240 + j] = mu00
    W[2304 + j] = mu01
    W[2368 + j] = mu02
    W[2432 + j] = mu03
    W[2496 + j] = mu04
    W[2560 + j] = mu05
    W[2624 + j] = mu06
    return nis


@nb.njit(cache=True, parallel=True, fastmath=FASTMATH, error_model="numpy")
def run_batch_soa_position3(z, dts, x0, p0, q, r, out_x, out_p, out_nis):
    """run_batch_position3 with trajectories in the SIMD lanes (derive/codegen/soa.py): same arguments and results.

    Blocks of 64 trajectories (prange over blocks); in a block every per-trajectory quantity is a row of one
    work array (rows × 64) and lane_position3 runs vectorised over the lanes; a lane failing the LDLᵀ test or with
    a NaN row (NaN NIS) is redone by the scalar predict / update_position3.
    """
    B = z.shape[0]
    K = z.shape[1]
    keep_p = out_p.shape[1] == K
    nblk = (B + 64 - 1) // 64
    for blk in nb.prange(nblk):
        lo = blk * 64
        L = min(64, B - lo)
        W = np.zeros(76 * 64)
        s = np.empty(7)
        p = np.empty(28)
        for j in range(L):
            s0 = state_from_physical(x0[lo + j])
            for i in range(7):
                W[(0 + i) * 64 + j] = s0[i]
            for i in range(28):
                W[(7 + i) * 64 + j] = p0[lo + j, i]
        for k in range(K):
            for j in range(L):
                W[70 * 64 + j] = dts[lo + j, k]
                W[73 * 64 + j] = z[lo + j, k, 0]
                W[74 * 64 + j] = z[lo + j, k, 1]
                W[75 * 64 + j] = z[lo + j, k, 2]
            for j in range(L):
                W[71 * 64 + j] = lane_position3(W, j, q[0], q[1], q[2], r[0])
                good = covariance_is_pd_lane(W, j) & (W[71 * 64 + j] == W[71 * 64 + j])
                W[72 * 64 + j] = 1.0 if good else 0.0
            for j in range(L):
                if W[72 * 64 + j] == 0.0:
                    b = lo + j
                    for i in range(7):
                        s[i] = W[(0 + i) * 64 + j]
                    for i in range(28):
                        p[i] = W[(7 + i) * 64 + j]
                    predict(s, p, dts[b, k], q[0], q[1], q[2])
                    if np.isnan(z[b, k, 0]) or np.isnan(z[b, k, 1]) or np.isnan(z[b, k, 2]):
                        W[71 * 64 + j] = np.nan
                    else:
                        W[71 * 64 + j] = update_position3(s, p, z[b, k, 0], z[b, k, 1], z[b, k, 2], r[0])
                    for i in range(7):
                        W[(35 + i) * 64 + j] = s[i]
                    for i in range(28):
                        W[(42 + i) * 64 + j] = p[i]
            for j in range(L):
                out_nis[lo + j, k] = W[71 * 64 + j]
                physical_lane(W, j, out_x, lo + j, k)
            if keep_p:
                for j in range(L):
                    for i in range(28):
                        out_p[lo + j, k, i] = W[(42 + i) * 64 + j]
            for i in range(7 + 28):
                for j in range(L):
                    W[(0 + i) * 64 + j] = W[(35 + i) * 64 + j]


@nb.njit(cache=True)
def covariance_is_pd(p):
    """LDLᵀ test of the packed covariance: every pivot d_j > 1e-13 · max_i P_ii (NaN fails)."""
    p0_0 = p[0]
    p0_1 = p[1]
    p0_2 = p[2]
    p0_3 = p[3]
    p0_4 = p[4]
    p0_5 = p[5]
    p0_6 = p[6]
    p1_1 = p[7]
    p1_2 = p[8]
    p1_3 = p[9]
    p1_4 = p[10]
    p1_5 = p[11]
    p1_6 = p[12]
    p2_2 = p[13]
    p2_3 = p[14]
    p2_4 = p[15]
    p2_5 = p[16]
    p2_6 = p[17]
    p3_3 = p[18]
    p3_4 = p[19]
    p3_5 = p[20]
    p3_6 = p[21]
    p4_4 = p[22]
    p4_5 = p[23]
    p4_6 = p[24]
    p5_5 = p[25]
    p5_6 = p[26]
    p6_6 = p[27]
    tol = 1e-13 * max(p0_0, p1_1, p2_2, p3_3, p4_4, p5_5, p6_6)
    d0 = p0_0
    if not d0 > tol:
        return False
    r0 = 1.0 / d0
    l1_0 = (p0_1) * r0
    l2_0 = (p0_2) * r0
    l3_0 = (p0_3) * r0
    l4_0 = (p0_4) * r0
    l5_0 = (p0_5) * r0
    l6_0 = (p0_6) * r0
    d1 = p1_1 - l1_0 * l1_0 * d0
    if not d1 > tol:
        return False
    r1 = 1.0 / d1
    l2_1 = (p1_2 - l2_0 * l1_0 * d0) * r1
    l3_1 = (p1_3 - l3_0 * l1_0 * d0) * r1
    l4_1 = (p1_4 - l4_0 * l1_0 * d0) * r1
    l5_1 = (p1_5 - l5_0 * l1_0 * d0) * r1
    l6_1 = (p1_6 - l6_0 * l1_0 * d0) * r1
    d2 = p2_2 - l2_0 * l2_0 * d0 - l2_1 * l2_1 * d1
    if not d2 > tol:
        return False
    r2 = 1.0 / d2
    l3_2 = (p2_3 - l3_0 * l2_0 * d0 - l3_1 * l2_1 * d1) * r2
    l4_2 = (p2_4 - l4_0 * l2_0 * d0 - l4_1 * l2_1 * d1) * r2
    l5_2 = (p2_5 - l5_0 * l2_0 * d0 - l5_1 * l2_1 * d1) * r2
    l6_2 = (p2_6 - l6_0 * l2_0 * d0 - l6_1 * l2_1 * d1) * r2
    d3 = p3_3 - l3_0 * l3_0 * d0 - l3_1 * l3_1 * d1 - l3_2 * l3_2 * d2
    if not d3 > tol:
        return False
    r3 = 1.0 / d3
    l4_3 = (p3_4 - l4_0 * l3_0 * d0 - l4_1 * l3_1 * d1 - l4_2 * l3_2 * d2) * r3
    l5_3 = (p3_5 - l5_0 * l3_0 * d0 - l5_1 * l3_1 * d1 - l5_2 * l3_2 * d2) * r3
    l6_3 = (p3_6 - l6_0 * l3_0 * d0 - l6_1 * l3_1 * d1 - l6_2 * l3_2 * d2) * r3
    d4 = p4_4 - l4_0 * l4_0 * d0 - l4_1 * l4_1 * d1 - l4_2 * l4_2 * d2 - l4_3 * l4_3 * d3
    if not d4 > tol:
        return False
    r4 = 1.0 / d4
    l5_4 = (p4_5 - l5_0 * l4_0 * d0 - l5_1 * l4_1 * d1 - l5_2 * l4_2 * d2 - l5_3 * l4_3 * d3) * r4
    l6_4 = (p4_6 - l6_0 * l4_0 * d0 - l6_1 * l4_1 * d1 - l6_2 * l4_2 * d2 - l6_3 * l4_3 * d3) * r4
    d5 = p5_5 - l5_0 * l5_0 * d0 - l5_1 * l5_1 * d1 - l5_2 * l5_2 * d2 - l5_3 * l5_3 * d3 - l5_4 * l5_4 * d4
    if not d5 > tol:
        return False
    r5 = 1.0 / d5
    l6_5 = (p5_6 - l6_0 * l5_0 * d0 - l6_1 * l5_1 * d1 - l6_2 * l5_2 * d2 - l6_3 * l5_3 * d3 - l6_4 * l5_4 * d4) * r5
    d6 = p6_6 - l6_0 * l6_0 * d0 - l6_1 * l6_1 * d1 - l6_2 * l6_2 * d2 - l6_3 * l6_3 * d3 - l6_4 * l6_4 * d4 - l6_5 * l6_5 * d5
    if not d6 > tol:
        return False
    return True


@nb.njit(cache=True, inline="always", error_model="numpy")
def covariance_is_pd_fused(p0_0, p0_1, p0_2, p0_3, p0_4, p0_5, p0_6, p1_1, p1_2, p1_3, p1_4, p1_5, p1_6, p2_2, p2_3, p2_4, p2_5, p2_6, p3_3, p3_4, p3_5, p3_6, p4_4, p4_5, p4_6, p5_5, p5_6, p6_6):
    """covariance_is_pd of the entries p<i>_<j> (upper triangle, row-major) as numbers, inlined into the fused
    steps (derive/codegen/fused.py), with pivots > 1e-11 · max_i P_ii."""
    tol = 1e-11 * max(p0_0, p1_1, p2_2, p3_3, p4_4, p5_5, p6_6)
    d0 = p0_0
    if not d0 > tol:
        return False
    r0 = 1.0 / d0
    l1_0 = (p0_1) * r0
    l2_0 = (p0_2) * r0
    l3_0 = (p0_3) * r0
    l4_0 = (p0_4) * r0
    l5_0 = (p0_5) * r0
    l6_0 = (p0_6) * r0
    d1 = p1_1 - l1_0 * l1_0 * d0
    if not d1 > tol:
        return False
    r1 = 1.0 / d1
    l2_1 = (p1_2 - l2_0 * l1_0 * d0) * r1
    l3_1 = (p1_3 - l3_0 * l1_0 * d0) * r1
    l4_1 = (p1_4 - l4_0 * l1_0 * d0) * r1
    l5_1 = (p1_5 - l5_0 * l1_0 * d0) * r1
    l6_1 = (p1_6 - l6_0 * l1_0 * d0) * r1
    d2 = p2_2 - l2_0 * l2_0 * d0 - l2_1 * l2_1 * d1
    if not d2 > tol:
        return False
    r2 = 1.0 / d2
    l3_2 = (p2_3 - l3_0 * l2_0 * d0 - l3_1 * l2_1 * d1) * r2
    l4_2 = (p2_4 - l4_0 * l2_0 * d0 - l4_1 * l2_1 * d1) * r2
    l5_2 = (p2_5 - l5_0 * l2_0 * d0 - l5_1 * l2_1 * d1) * r2
    l6_2 = (p2_6 - l6_0 * l2_0 * d0 - l6_1 * l2_1 * d1) * r2
    d3 = p3_3 - l3_0 * l3_0 * d0 - l3_1 * l3_1 * d1 - l3_2 * l3_2 * d2
    if not d3 > tol:
        return False
    r3 = 1.0 / d3
    l4_3 = (p3_4 - l4_0 * l3_0 * d0 - l4_1 * l3_1 * d1 - l4_2 * l3_2 * d2) * r3
    l5_3 = (p3_5 - l5_0 * l3_0 * d0 - l5_1 * l3_1 * d1 - l5_2 * l3_2 * d2) * r3
    l6_3 = (p3_6 - l6_0 * l3_0 * d0 - l6_1 * l3_1 * d1 - l6_2 * l3_2 * d2) * r3
    d4 = p4_4 - l4_0 * l4_0 * d0 - l4_1 * l4_1 * d1 - l4_2 * l4_2 * d2 - l4_3 * l4_3 * d3
    if not d4 > tol:
        return False
    r4 = 1.0 / d4
    l5_4 = (p4_5 - l5_0 * l4_0 * d0 - l5_1 * l4_1 * d1 - l5_2 * l4_2 * d2 - l5_3 * l4_3 * d3) * r4
    l6_4 = (p4_6 - l6_0 * l4_0 * d0 - l6_1 * l4_1 * d1 - l6_2 * l4_2 * d2 - l6_3 * l4_3 * d3) * r4
    d5 = p5_5 - l5_0 * l5_0 * d0 - l5_1 * l5_1 * d1 - l5_2 * l5_2 * d2 - l5_3 * l5_3 * d3 - l5_4 * l5_4 * d4
    if not d5 > tol:
        return False
    r5 = 1.0 / d5
    l6_5 = (p5_6 - l6_0 * l5_0 * d0 - l6_1 * l5_1 * d1 - l6_2 * l5_2 * d2 - l6_3 * l5_3 * d3 - l6_4 * l5_4 * d4) * r5
    d6 = p6_6 - l6_0 * l6_0 * d0 - l6_1 * l6_1 * d1 - l6_2 * l6_2 * d2 - l6_3 * l6_3 * d3 - l6_4 * l6_4 * d4 - l6_5 * l6_5 * d5
    if not d6 > tol:
        return False
    return True


@nb.njit(cache=True)
def repair_pd(p):
    """Add the smallest diagonal jitter (1e-13 · max_i P_ii, growing ×4) that makes covariance_is_pd pass."""
    scale = 0.0
    for i in (0, 7, 13, 18, 22, 25, 27):
        scale = max(scale, abs(p[i]))
    delta = 1e-13 * scale
    for _ in range(60):
        if covariance_is_pd(p):
            return
        for i in (0, 7, 13, 18, 22, 25, 27):
            p[i] += delta
        delta *= 4.0


@nb.njit(inline="always", fastmath={"contract"}, error_model="numpy")
def covariance_is_pd_lane(W, j):
    """covariance_is_pd of lane j of the new covariance rows of W, without branches (all pivots)."""
    p0_0 = W[2688 + j]
    p0_1 = W[2752 + j]
    p0_2 = W[2816 + j]
    p0_3 = W[2880 + j]
    p0_4 = W[2944 + j]
    p0_5 = W[3008 + j]
    p0_6 = W[3072 + j]
    p1_1 = W[3136 + j]
    p1_2 = W[3200 + j]
    p1_3 = W[3264 + j]
    p1_4 = W[3328 + j]
    p1_5 = W[3392 + j]
    p1_6 = W[3456 + j]
    p2_2 = W[3520 + j]
    p2_3 = W[3584 + j]
    p2_4 = W[3648 + j]
    p2_5 = W[3712 + j]
    p2_6 = W[3776 + j]
    p3_3 = W[3840 + j]
    p3_4 = W[3904 + j]
    p3_5 = W[3968 + j]
    p3_6 = W[4032 + j]
    p4_4 = W[4096 + j]
    p4_5 = W[4160 + j]
    p4_6 = W[4224 + j]
    p5_5 = W[4288 + j]
    p5_6 = W[4352 + j]
    p6_6 = W[4416 + j]
    tol = 1e-13 * max(p0_0, p1_1, p2_2, p3_3, p4_4, p5_5, p6_6)
    d0 = p0_0
    r0 = 1.0 / d0
    l1_0 = (p0_1) * r0
    l2_0 = (p0_2) * r0
    l3_0 = (p0_3) * r0
    l4_0 = (p0_4) * r0
    l5_0 = (p0_5) * r0
    l6_0 = (p0_6) * r0
    d1 = p1_1 - l1_0 * l1_0 * d0
    r1 = 1.0 / d1
    l2_1 = (p1_2 - l2_0 * l1_0 * d0) * r1
    l3_1 = (p1_3 - l3_0 * l1_0 * d0) * r1
    l4_1 = (p1_4 - l4_0 * l1_0 * d0) * r1
    l5_1 = (p1_5 - l5_0 * l1_0 * d0) * r1
    l6_1 = (p1_6 - l6_0 * l1_0 * d0) * r1
    d2 = p2_2 - l2_0 * l2_0 * d0 - l2_1 * l2_1 * d1
    r2 = 1.0 / d2
    l3_2 = (p2_3 - l3_0 * l2_0 * d0 - l3_1 * l2_1 * d1) * r2
    l4_2 = (p2_4 - l4_0 * l2_0 * d0 - l4_1 * l2_1 * d1) * r2
    l5_2 = (p2_5 - l5_0 * l2_0 * d0 - l5_1 * l2_1 * d1) * r2
    l6_2 = (p2_6 - l6_0 * l2_0 * d0 - l6_1 * l2_1 * d1) * r2
    d3 = p3_3 - l3_0 * l3_0 * d0 - l3_1 * l3_1 * d1 - l3_2 * l3_2 * d2
    r3 = 1.0 / d3
    l4_3 = (p3_4 - l4_0 * l3_0 * d0 - l4_1 * l3_1 * d1 - l4_2 * l3_2 * d2) * r3
    l5_3 = (p3_5 - l5_0 * l3_0 * d0 - l5_1 * l3_1 * d1 - l5_2 * l3_2 * d2) * r3
    l6_3 = (p3_6 - l6_0 * l3_0 * d0 - l6_1 * l3_1 * d1 - l6_2 * l3_2 * d2) * r3
    d4 = p4_4 - l4_0 * l4_0 * d0 - l4_1 * l4_1 * d1 - l4_2 * l4_2 * d2 - l4_3 * l4_3 * d3
    r4 = 1.0 / d4
    l5_4 = (p4_5 - l5_0 * l4_0 * d0 - l5_1 * l4_1 * d1 - l5_2 * l4_2 * d2 - l5_3 * l4_3 * d3) * r4
    l6_4 = (p4_6 - l6_0 * l4_0 * d0 - l6_1 * l4_1 * d1 - l6_2 * l4_2 * d2 - l6_3 * l4_3 * d3) * r4
    d5 = p5_5 - l5_0 * l5_0 * d0 - l5_1 * l5_1 * d1 - l5_2 * l5_2 * d2 - l5_3 * l5_3 * d3 - l5_4 * l5_4 * d4
    r5 = 1.0 / d5
    l6_5 = (p5_6 - l6_0 * l5_0 * d0 - l6_1 * l5_1 * d1 - l6_2 * l5_2 * d2 - l6_3 * l5_3 * d3 - l6_4 * l5_4 * d4) * r5
    d6 = p6_6 - l6_0 * l6_0 * d0 - l6_1 * l6_1 * d1 - l6_2 * l6_2 * d2 - l6_3 * l6_3 * d3 - l6_4 * l6_4 * d4 - l6_5 * l6_5 * d5
    return (d0 > tol) & (d1 > tol) & (d2 > tol) & (d3 > tol) & (d4 > tol) & (d5 > tol) & (d6 > tol)


@nb.njit(inline="always", fastmath={"contract"}, error_model="numpy")
def physical_lane(W, j, out, b, k):
    """Physical [x, y, z, psi, v, omega, vz] from the internal state, written into ``out`` (no allocation).
    """
    x = W[2240 + j]
    y = W[2304 + j]
    z = W[2368 + j]
    psi = W[2432 + j]
    v = W[2496 + j]
    omega = W[2560 + j]
    v_up = W[2624 + j]
    out[b, k, 0] = x
    out[b, k, 1] = y
    out[b, k, 2] = z
    out[b, k, 3] = wrap_v(psi)
    out[b, k, 4] = v
    out[b, k, 5] = omega
    out[b, k, 6] = v_up


@nb.njit(cache=True)
def propagate(s, dt, n0, n1, n2):
    """Exact motion X ← X exp([Ω(X) + G n]^∧) (eq:model) for one noise sample n, in place.
    """
    x = s[0]
    y = s[1]
    z = s[2]
    psi = s[3]
    v = s[4]
    omega = s[5]
    v_up = s[6]
    _sin_psi = math.sin(psi)
    _cos_psi = math.cos(psi)
    _a0 = dt*omega/2.0
    _sin__a0 = math.sin(_a0)
    _cos__a0 = math.cos(_a0)
    _sinc__a0 = sinc(_a0, _sin__a0, _cos__a0)
    _a1 = dt*omega/2.0 + psi
    _sin__a1 = math.sin(_a1)
    _cos__a1 = math.cos(_a1)
    _t0 = _sinc__a0*dt*v
    _t1 = (dt*dt)/2.0
    _t2 = _t1*n0
    xn00 = _cos__a1*_t0 + _cos_psi*_t2 + x
    xn01 = _sin__a1*_t0 + _sin_psi*_t2 + y
    xn02 = _t1*n2 + dt*v_up + z
    xn03 = _t1*n1 + dt*omega + psi
    xn04 = dt*n0 + v
    xn05 = dt*n1 + omega
    xn06 = dt*n2 + v_up
    s[0] = xn00
    s[1] = xn01
    s[2] = xn02
    s[3] = xn03
    s[4] = xn04
    s[5] = xn05
    s[6] = xn06


@nb.njit(cache=True)
def position_into(s, out):
    """The position (the first three physical coordinates) of the internal state into ``out`` (3,).
    """
    x = s[0]
    y = s[1]
    z = s[2]
    out[0] = x
    out[1] = y
    out[2] = z


@nb.njit(cache=True, parallel=True)
def simulate_batch(x0, dts, noise, out_x):
    """Simulate the motion model X_{k+1} = X_k exp([Ω(X_k) + G n_k]^) for B trajectories (prange).

    x0 (B, 7) physical initial states; dts (B, K) step lengths; noise (B, K, 3) samples of n (already
    scaled by their stds); out_x (B, K + 1, 7) receives the physical states, out_x[:, 0] = x0.
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
    """state_from_physical of every row: physical states x (N, 7) into internal states out (N, 7)."""
    for i in range(x.shape[0]):
        state_from_physical_into(x[i], out[i])


@nb.njit(cache=True, nogil=True)  # serial and nogil: threads may run it at once (lgekf.apps.search)
def propagate_rows(x, dts, out_x):
    """The noise-free exact motion of each row: out_x[i] = X_i exp([Ω(X_i)]^) over dts[i] (simulate_batch with
    zero noise, one step per row); x (N, 7) and out_x (N, 7) physical states, dts (N,)."""
    s = np.empty(7)
    for i in range(x.shape[0]):
        state_from_physical_into(x[i], s)
        propagate(s, dts[i], 0.0, 0.0, 0.0)
        physical_into(s, out_x[i])


@nb.njit(cache=True, nogil=True)  # serial and nogil: threads may run it at once (lgekf.apps.search)
def propagate_positions(x, dts, out_xy):
    """The position (the first d physical coordinates, d the space's dimension) of ``propagate_rows``'s rows, bit for bit, into
    out_xy (N, d): the other coordinates are not converted (the noise search's one-step errors)."""
    s = np.empty(7)
    for i in range(x.shape[0]):
        state_from_physical_into(x[i], s)
        propagate(s, dts[i], 0.0, 0.0, 0.0)
        position_into(s, out_xy[i])


@nb.njit(cache=True)
def world_velocity(x):
    """World-frame velocity (3,) of a physical state x of this model.
    """
    psi = x[3]
    v = x[4]
    v_up = x[6]
    out = np.zeros(3)
    _sin_psi = math.sin(psi)
    _cos_psi = math.cos(psi)
    out[0] = _cos_psi*v
    out[1] = _sin_psi*v
    out[2] = v_up
    return out


@nb.njit(cache=True)
def world_velocity_into(x, out):
    """world_velocity of a physical state x written into out (3,) (no allocation).
    """
    psi = x[3]
    v = x[4]
    v_up = x[6]
    _sin_psi = math.sin(psi)
    _cos_psi = math.cos(psi)
    out[0] = _cos_psi*v
    out[1] = _sin_psi*v
    out[2] = v_up


@nb.njit(cache=True, nogil=True)
def world_velocities(X, out):
    """world_velocity of every row of X (N, n) into out (N, 3) (the space's dimension)."""
    for i in range(X.shape[0]):
        world_velocity_into(X[i], out[i])


@nb.njit(cache=True, nogil=True)
def row_speeds(X, rows, out):
    """Speed |world_velocity| of the rows X[rows[i]] of physical states X (N, n) into out (R,): no per-row
    allocation nor gathered copy of X (the divergence monitor's speeds)."""
    v = np.empty(3)
    for i in range(rows.shape[0]):
        world_velocity_into(X[rows[i]], v)
        out[i] = math.sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2])


@nb.njit(cache=True)
def common_to_state(c):
    """The model's physical state from the common c = (x, y, z, roll, pitch, yaw, v_x, v_y, v_z, ω_x, ω_y, ω_z), velocities in the body frame.
    """
    c0 = c[0]
    c1 = c[1]
    c2 = c[2]
    c3 = c[3]
    c4 = c[4]
    c5 = c[5]
    c6 = c[6]
    c7 = c[7]
    c8 = c[8]
    c9 = c[9]
    c10 = c[10]
    c11 = c[11]
    out = np.zeros(7)
    _sin_c3 = math.sin(c3)
    _cos_c3 = math.cos(c3)
    _sin_c4 = math.sin(c4)
    _cos_c4 = math.cos(c4)
    _sin_c5 = math.sin(c5)
    _cos_c5 = math.cos(c5)
    _t0 = _cos_c4*c6
    _t1 = _cos_c3*_cos_c5
    _t2 = _sin_c3*_sin_c5
    _t3 = _cos_c3*_sin_c5
    _t4 = _sin_c5*_t0 + c7*(_sin_c4*_t2 + _t1) + c8*(-(_cos_c5*_sin_c3) + _sin_c4*_t3)
    _t5 = _cos_c5*_t0 + c7*(_cos_c5*_sin_c3*_sin_c4 - _t3) + c8*(_sin_c4*_t1 + _t2)
    _t6 = _cos_c3*_cos_c4
    _t7 = _cos_c4*_sin_c3
    out[0] = c0
    out[1] = c1
    out[2] = c2
    out[3] = math.atan2(_t4, _t5)
    out[4] = math.sqrt(_t4*_t4 + _t5*_t5)
    out[5] = -(_sin_c4*c9) + _t6*c11 + _t7*c10
    out[6] = -(_sin_c4*c6) + _t6*c8 + _t7*c7
    return out


@nb.njit(cache=True)
def common_jacobian(c):
    """J = ∂(filter coordinates ε)/∂c at c: maps a covariance of c to the filter's P (P = J P_c J^T).
    """
    c3 = c[3]
    c4 = c[4]
    c5 = c[5]
    c6 = c[6]
    c7 = c[7]
    c8 = c[8]
    c9 = c[9]
    c10 = c[10]
    c11 = c[11]
    out = np.zeros((7, 12))
    _sin_c3 = math.sin(c3)
    _cos_c3 = math.cos(c3)
    _sin_c4 = math.sin(c4)
    _cos_c4 = math.cos(c4)
    _sin_c5 = math.sin(c5)
    _cos_c5 = math.cos(c5)
    _t0 = _cos_c5*_sin_c3
    _t1 = _cos_c3*_sin_c5
    _t2 = _sin_c4*_t1
    _t3 = -_t0 + _t2
    _t4 = _t3*c7
    _t5 = _cos_c3*_cos_c5
    _t6 = _sin_c3*_sin_c5
    _t7 = _sin_c4*_t6
    _t8 = _t5 + _t7
    _t9 = -_t8
    _t10 = _t9*c8
    _t11 = _cos_c4*c6
    _t12 = _cos_c5*_t11
    _t13 = _sin_c4*_t5
    _t14 = _t13 + _t6
    _t15 = _t14*c8
    _t16 = -(_cos_c5*_sin_c3*_sin_c4) + _t1
    _t17 = -_t16
    _t18 = _t17*c7
    _t19 = _t12 + _t15 + _t18
    _t20 = _t19*_t19
    _t21 = _sin_c5*_t11
    _t22 = _t21 + _t3*c8 + _t8*c7
    _t23 = _t20 + _t22*_t22
    _t24 = 1.0/_t23
    _t25 = _t19*_t24
    _t26 = _t14*c7
    _t27 = _t16*c8
    _t28 = -(_t22*_t24)
    _t29 = _sin_c4*c6
    _t30 = _sin_c5*_t29
    _t31 = _cos_c4*c8
    _t32 = _cos_c4*c7
    _t33 = _cos_c5*_t29
    _t34 = -(_t3*c8)
    _t35 = _t9*c7
    _t36 = _cos_c4*_sin_c5
    _t37 = _cos_c4*_cos_c5
    _t38 = 1.0/math.sqrt(_t23)
    _t39 = _t19/2.0
    _t40 = _t22/2.0
    _t41 = 2.0*_t5
    _t42 = 2.0*_t0
    _t43 = 2.0*_t1
    _t44 = 2.0*_t6
    _t45 = _cos_c3*_sin_c4
    _t46 = _sin_c3*_sin_c4
    _t47 = -_sin_c4
    _t48 = _cos_c4*_sin_c3
    _t49 = _cos_c3*_cos_c4
    out[0, 0] = 1.0
    out[1, 1] = 1.0
    out[2, 2] = 1.0
    out[3, 3] = _t25*(_t10 + _t4) + _t28*(_t26 + _t27)
    out[3, 4] = _t25*(_t1*_t31 - _t30 + _t32*_t6) + _t28*(_t0*_t32 + _t31*_t5 - _t33)
    out[3, 5] = _t20*_t24 + _t28*(-_t21 + _t34 + _t35)
    out[3, 6] = _t25*_t36 + _t28*_t37
    out[3, 7] = _t17*_t28 + _t25*_t8
    out[3, 8] = _t14*_t28 + _t25*_t3
    out[4, 3] = _t38*(_t39*(2.0*_t26 + 2.0*_t27) + _t40*(2.0*_t10 + 2.0*_t4))
    out[4, 4] = _t38*(_t39*(_t31*_t41 + _t32*_t42 - 2.0*_t33) + _t40*(-(2.0*_t30) + _t31*_t43 + _t32*_t44))
    out[4, 5] = _t38*(_t39*(-(2.0*_t21) + 2.0*_t34 + 2.0*_t35) + _t40*(2.0*_t12 + 2.0*_t15 + 2.0*_t18))
    out[4, 6] = _t38*(_t19*_t37 + _t22*_t36)
    out[4, 7] = _t38*(_t39*(2.0*_cos_c5*_sin_c3*_sin_c4 - _t43) + _t40*(_t41 + 2.0*_t7))
    out[4, 8] = _t38*(_t39*(2.0*_t13 + _t44) + _t40*(2.0*_t2 - _t42))
    out[5, 3] = _cos_c4*(_cos_c3*c10 - _sin_c3*c11)
    out[5, 4] = -(_cos_c4*c9) - _t45*c11 - _t46*c10
    out[5, 9] = _t47
    out[5, 10] = _t48
    out[5, 11] = _t49
    out[6, 3] = _cos_c4*(_cos_c3*c7 - _sin_c3*c8)
    out[6, 4] = -_t11 - _t45*c8 - _t46*c7
    out[6, 6] = _t47
    out[6, 7] = _t48
    out[6, 8] = _t49
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
    z = s[2]
    psi = s[3]
    v = s[4]
    omega = s[5]
    v_up = s[6]
    c0 = c[0]
    c1 = c[1]
    c2 = c[2]
    c3 = c[3]
    c4 = c[4]
    c5 = c[5]
    c6 = c[6]
    c7 = c[7]
    c8 = c[8]
    c9 = c[9]
    c10 = c[10]
    c11 = c[11]
    out = np.zeros(7)
    _sin_c3 = math.sin(c3)
    _cos_c3 = math.cos(c3)
    _sin_c4 = math.sin(c4)
    _cos_c4 = math.cos(c4)
    _sin_c5 = math.sin(c5)
    _cos_c5 = math.cos(c5)
    _t0 = _cos_c4*c6
    _t1 = _cos_c3*_cos_c5
    _t2 = _sin_c3*_sin_c5
    _t3 = _cos_c3*_sin_c5
    _t4 = _sin_c5*_t0 + c7*(_sin_c4*_t2 + _t1) + c8*(-(_cos_c5*_sin_c3) + _sin_c4*_t3)
    _t5 = _cos_c5*_t0 + c7*(_cos_c5*_sin_c3*_sin_c4 - _t3) + c8*(_sin_c4*_t1 + _t2)
    _t6 = _cos_c3*_cos_c4
    _t7 = _cos_c4*_sin_c3
    out[0] = c0 - x
    out[1] = c1 - y
    out[2] = c2 - z
    out[3] = wrap_angle(-psi + math.atan2(_t4, _t5))
    out[4] = -v + math.sqrt(_t4*_t4 + _t5*_t5)
    out[5] = -(_sin_c4*c9) + _t6*c11 + _t7*c10 - omega
    out[6] = -(_sin_c4*c6) + _t6*c8 + _t7*c7 - v_up
    return out


@nb.njit(cache=True)
def retract(s, eps):
    """μ ← μ·exp([ε]^∧) in place (right perturbation; the update's eq:up_mu for a given ε).
    """
    x = s[0]
    y = s[1]
    z = s[2]
    psi = s[3]
    v = s[4]
    omega = s[5]
    v_up = s[6]
    eps0 = eps[0]
    eps1 = eps[1]
    eps2 = eps[2]
    eps3 = eps[3]
    eps4 = eps[4]
    eps5 = eps[5]
    eps6 = eps[6]
    s[0] = eps0 + x
    s[1] = eps1 + y
    s[2] = eps2 + z
    s[3] = eps3 + psi
    s[4] = eps4 + v
    s[5] = eps5 + omega
    s[6] = eps6 + v_up


@nb.njit(cache=True)
def between(s, t):
    """[log_G(μ_s^-1 μ_t)]^∨: the tangent ε with μ_t = μ_s·exp(ε) (s ⊖: μ_s, t: μ_t, internal states);
    angle coordinates of a Euclidean model wrapped to (-π, π].
    """
    x = s[0]
    y = s[1]
    z = s[2]
    psi = s[3]
    v = s[4]
    omega = s[5]
    v_up = s[6]
    t_x = t[0]
    t_y = t[1]
    t_z = t[2]
    t_psi = t[3]
    t_v = t[4]
    t_omega = t[5]
    t_v_up = t[6]
    out = np.zeros(7)
    out[0] = t_x - x
    out[1] = t_y - y
    out[2] = t_z - z
    out[3] = wrap_angle(-psi + t_psi)
    out[4] = t_v - v
    out[5] = -omega + t_omega
    out[6] = t_v_up - v_up
    return out


@nb.njit(cache=True)
def right_jacobian(eps):
    """Φ_G(ε) of the whole group (block-diagonal over its factors, I for Rⁿ);
    log(exp(-ε) exp(ε + δ)) ≈ Φ_G(ε) δ.
    """
    out = np.zeros((7, 7))
    out[0, 0] = 1.0
    out[1, 1] = 1.0
    out[2, 2] = 1.0
    out[3, 3] = 1.0
    out[4, 4] = 1.0
    out[5, 5] = 1.0
    out[6, 6] = 1.0
    return out


@nb.njit(cache=True)
def right_jacobian_inv(eps):
    """Φ_G(ε)^-1 of the whole group.
    """
    out = np.zeros((7, 7))
    out[0, 0] = 1.0
    out[1, 1] = 1.0
    out[2, 2] = 1.0
    out[3, 3] = 1.0
    out[4, 4] = 1.0
    out[5, 5] = 1.0
    out[6, 6] = 1.0
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
    """μ_i ← μ_i·exp([ε_i]^∧) for every live track (eq:up_mu with the given corrections eps (N, 7))."""
    for i in range(s.shape[0]):
        if live[i]:
            retract(s[i], eps[i])


@nb.njit(cache=True)
def right_jacobian_bank(live, eps, out):
    """Φ_G(ε_i) (eq:up_P) of every live track's correction eps (N, 7) into out (N, 7, 7)."""
    for i in range(eps.shape[0]):
        if live[i]:
            f = right_jacobian(eps[i])
            for a in range(7):
                for b in range(7):
                    out[i, a, b] = f[a, b]


@nb.njit(cache=True)
def innovation_logdet_position3(s, p, r):
    """log det S, S = ℋ P ℋᵀ + R (eq:K) for a position3 measurement at the predicted state (s, p),
    noise stds (r): the log-determinant term of the innovation log-likelihood.
    """
    p00 = p[0]
    p01 = p[1]
    p02 = p[2]
    p11 = p[7]
    p12 = p[8]
    p22 = p[13]
    _t0 = r*r
    S00 = _t0 + p00
    S11 = _t0 + p11
    S22 = _t0 + p22
    detS = S00*S11*S22 - S00*(p12*p12) - S11*(p02*p02) - S22*(p01*p01) + 2.0*p01*p02*p12
    return math.log(detS)


@nb.njit(cache=True, fastmath=FASTMATH, error_model="numpy")
def step_store_position3(s, p, dt, sigma_a, sigma_alpha, sigma_z, z_x, z_y, z_z, r, sq, pq):
    """step_try_position3 that also writes the predicted internal state into sq and the predicted packed covariance
    (after the angle-variance cap) into pq, and returns (NIS, log det S) (derive/codegen/smooth_step.py); a NIS
    of -1 means the caller must run update_position3 (derive/codegen/fused.py).
    (eq:pred_mu, eq:pred_cov, angle-variance cap, eq:K, eq:up_mu, eq:up_P) in one kernel; returns the NIS.
    Covariance as P − βKℋP; a step whose result fails the LDLᵀ test (covariance_is_pd_fused) leaves the
    prediction in s, p and returns -1.0: the caller then runs update_position3 (Joseph form;
    derive/codegen/fused.py).
    legend: cc = 𝒞 (eq:C), f = F = Ad(exp(−Ω)) + Φ(Ω)𝒞 (eq:pred_cov), g = Φ(Ω)G, hh = ℋ (eq:calH), hp = ℋP, inn = [log_G'(h(μ)⁻¹Z)]^∨, S = ℋPℋᵀ + R, Si = S⁻¹, k = K (eq:K), nk = Kν, alpha = gain damping, nu = ν, phi = Φ(ν) (eq:up_P), a = I − αKℋ, b = aP, beta = α(2 − α), kb = βK, pj = Joseph-form P (= P − βKℋP), cp = Φ(ν)·pj, mu/e = new mean
    """
    x = s[0]
    y = s[1]
    z = s[2]
    psi = s[3]
    v = s[4]
    omega = s[5]
    v_up = s[6]
    p00 = p[0]
    p01 = p[1]
    p02 = p[2]
    p03 = p[3]
    p04 = p[4]
    p05 = p[5]
    p06 = p[6]
    p11 = p[7]
    p12 = p[8]
    p13 = p[9]
    p14 = p[10]
    p15 = p[11]
    p16 = p[12]
    p22 = p[13]
    p23 = p[14]
    p24 = p[15]
    p25 = p[16]
    p26 = p[17]
    p33 = p[18]
    p34 = p[19]
    p35 = p[20]
    p36 = p[21]
    p44 = p[22]
    p45 = p[23]
    p46 = p[24]
    p55 = p[25]
    p56 = p[26]
    p66 = p[27]
    _a0 = dt*omega/2.0
    _sin__a0 = math.sin(_a0)
    _cos__a0 = math.cos(_a0)
    _dsinc__a0 = dsinc(_a0, _sin__a0, _cos__a0)
    _sinc__a0 = sinc(_a0, _sin__a0, _cos__a0)
    _a1 = dt*omega/2.0 + psi
    _sin__a1 = math.sin(_a1)
    _cos__a1 = math.cos(_a1)
    _t0 = _sin__a1*_sinc__a0
    _t1 = _t0*dt
    _t2 = _cos__a1*_sinc__a0
    _t3 = _t2*dt
    _t4 = (dt*dt)*v/2.0
    cc03 = -(_t1*v)
    cc04 = _t3
    cc05 = -(_t4*(_cos__a1*_dsinc__a0 + _t0))
    cc13 = _t3*v
    cc14 = _t1
    cc15 = _t4*(-(_dsinc__a0*_sin__a1) + _t2)
    _sin_psi = math.sin(psi)
    _cos_psi = math.cos(psi)
    _t5 = (dt*dt)/2.0
    _t6 = _sinc__a0*dt*v
    g00 = _cos_psi*_t5
    g10 = _sin_psi*_t5
    g22 = _t5
    g31 = _t5
    e00 = _cos__a1*_t6 + x
    e01 = _sin__a1*_t6 + y
    e02 = dt*v_up + z
    e03 = dt*omega + psi
    _t7 = dt*p56
    m00 = cc03*p03 + cc04*p04 + cc05*p05 + p00
    m01 = cc03*p13 + cc04*p14 + cc05*p15 + p01
    m02 = cc03*p23 + cc04*p24 + cc05*p25 + p02
    m03 = cc03*p33 + cc04*p34 + cc05*p35 + p03
    m04 = cc03*p34 + cc04*p44 + cc05*p45 + p04
    m05 = cc03*p35 + cc04*p45 + cc05*p55 + p05
    m06 = cc03*p36 + cc04*p46 + cc05*p56 + p06
    m11 = cc13*p13 + cc14*p14 + cc15*p15 + p11
    m12 = cc13*p23 + cc14*p24 + cc15*p25 + p12
    m13 = cc13*p33 + cc14*p34 + cc15*p35 + p13
    m14 = cc13*p34 + cc14*p44 + cc15*p45 + p14
    m15 = cc13*p35 + cc14*p45 + cc15*p55 + p15
    m16 = cc13*p36 + cc14*p46 + cc15*p56 + p16
    m22 = dt*p26 + p22
    m23 = dt*p36 + p23
    m24 = dt*p46 + p24
    m25 = _t7 + p25
    m26 = dt*p66 + p26
    m33 = dt*p35 + p33
    m34 = dt*p45 + p34
    m35 = dt*p55 + p35
    m36 = _t7 + p36
    _t8 = sigma_a*sigma_a
    _t9 = _t8*g00
    _t10 = sigma_z*sigma_z
    _t11 = sigma_alpha*sigma_alpha
    _t12 = dt*dt
    pp00 = _t8*(g00*g00) + cc03*m03 + cc04*m04 + cc05*m05 + m00
    pp01 = _t9*g10 + cc13*m03 + cc14*m04 + cc15*m05 + m01
    pp02 = dt*m06 + m02
    pp03 = dt*m05 + m03
    pp04 = _t9*dt + m04
    pp05 = m05
    pp06 = m06
    pp11 = _t8*(g10*g10) + cc13*m13 + cc14*m14 + cc15*m15 + m11
    pp12 = dt*m16 + m12
    pp13 = dt*m15 + m13
    pp14 = _t8*dt*g10 + m14
    pp15 = m15
    pp16 = m16
    pp22 = _t10*(g22*g22) + dt*m26 + m22
    pp23 = dt*m25 + m23
    pp24 = m24
    pp25 = m25
    pp26 = _t10*dt*g22 + m26
    pp33 = _t11*(g31*g31) + dt*m35 + m33
    pp34 = m34
    pp35 = _t11*dt*g31 + m35
    pp36 = m36
    pp44 = _t12*_t8 + p44
    pp45 = p45
    pp46 = p46
    pp55 = _t11*_t12 + p55
    pp56 = p56
    pp66 = _t10*_t12 + p66
    x_p = e00
    y_p = e01
    z_p = e02
    psi_p = e03
    inn00 = -x_p + z_x
    inn10 = -y_p + z_y
    inn20 = -z_p + z_z
    _t13 = r*r
    S00 = _t13 + pp00
    S11 = _t13 + pp11
    S22 = _t13 + pp22
    rdet = 1.0/(S00*S11*S22 - S00*(pp12*pp12) - S11*(pp02*pp02) - S22*(pp01*pp01) + 2.0*pp01*pp02*pp12)
    Si00 = rdet*(S11*S22 - pp12*pp12)
    Si01 = rdet*(-(S22*pp01) + pp02*pp12)
    Si02 = rdet*(-(S11*pp02) + pp01*pp12)
    Si11 = rdet*(S00*S22 - pp02*pp02)
    Si12 = rdet*(-(S00*pp12) + pp01*pp02)
    Si22 = rdet*(S00*S11 - pp01*pp01)
    _t14 = Si01*pp01
    _t15 = Si02*pp02
    _t16 = Si12*pp12
    _t17 = 2.0*inn00
    k00 = Si00*pp00 + _t14 + _t15
    k01 = Si01*pp00 + Si11*pp01 + Si12*pp02
    k02 = Si02*pp00 + Si12*pp01 + Si22*pp02
    k10 = Si00*pp01 + Si01*pp11 + Si02*pp12
    k11 = Si11*pp11 + _t14 + _t16
    k12 = Si02*pp01 + Si12*pp11 + Si22*pp12
    k20 = Si00*pp02 + Si01*pp12 + Si02*pp22
    k21 = Si01*pp02 + Si11*pp12 + Si12*pp22
    k22 = Si22*pp22 + _t15 + _t16
    k30 = Si00*pp03 + Si01*pp13 + Si02*pp23
    k31 = Si01*pp03 + Si11*pp13 + Si12*pp23
    k32 = Si02*pp03 + Si12*pp13 + Si22*pp23
    k40 = Si00*pp04 + Si01*pp14 + Si02*pp24
    k41 = Si01*pp04 + Si11*pp14 + Si12*pp24
    k42 = Si02*pp04 + Si12*pp14 + Si22*pp24
    k50 = Si00*pp05 + Si01*pp15 + Si02*pp25
    k51 = Si01*pp05 + Si11*pp15 + Si12*pp25
    k52 = Si02*pp05 + Si12*pp15 + Si22*pp25
    k60 = Si00*pp06 + Si01*pp16 + Si02*pp26
    k61 = Si01*pp06 + Si11*pp16 + Si12*pp26
    k62 = Si02*pp06 + Si12*pp16 + Si22*pp26
    nis = Si00*(inn00*inn00) + Si01*_t17*inn10 + Si02*_t17*inn20 + Si11*(inn10*inn10) + 2.0*Si12*inn10*inn20 + Si22*(inn20*inn20)
    nk0 = inn00*k00 + inn10*k01 + inn20*k02
    nk1 = inn00*k10 + inn10*k11 + inn20*k12
    nk2 = inn00*k20 + inn10*k21 + inn20*k22
    nk3 = inn00*k30 + inn10*k31 + inn20*k32
    nk4 = inn00*k40 + inn10*k41 + inn20*k42
    nk5 = inn00*k50 + inn10*k51 + inn20*k52
    nk6 = inn00*k60 + inn10*k61 + inn20*k62
    mu00 = nk0 + x_p
    mu01 = nk1 + y_p
    mu02 = nk2 + z_p
    mu03 = nk3 + psi_p
    mu04 = nk4 + v
    mu05 = nk5 + omega
    mu06 = nk6 + v_up
    pj00 = -(k00*pp00) - k01*pp01 - k02*pp02 + pp00
    pj01 = -(k00*pp01) - k01*pp11 - k02*pp12 + pp01
    pj02 = -(k00*pp02) - k01*pp12 - k02*pp22 + pp02
    pj03 = -(k00*pp03) - k01*pp13 - k02*pp23 + pp03
    pj04 = -(k00*pp04) - k01*pp14 - k02*pp24 + pp04
    pj05 = -(k00*pp05) - k01*pp15 - k02*pp25 + pp05
    pj06 = -(k00*pp06) - k01*pp16 - k02*pp26 + pp06
    pj11 = -(k10*pp01) - k11*pp11 - k12*pp12 + pp11
    pj12 = -(k10*pp02) - k11*pp12 - k12*pp22 + pp12
    pj13 = -(k10*pp03) - k11*pp13 - k12*pp23 + pp13
    pj14 = -(k10*pp04) - k11*pp14 - k12*pp24 + pp14
    pj15 = -(k10*pp05) - k11*pp15 - k12*pp25 + pp15
    pj16 = -(k10*pp06) - k11*pp16 - k12*pp26 + pp16
    pj22 = -(k20*pp02) - k21*pp12 - k22*pp22 + pp22
    pj23 = -(k20*pp03) - k21*pp13 - k22*pp23 + pp23
    pj24 = -(k20*pp04) - k21*pp14 - k22*pp24 + pp24
    pj25 = -(k20*pp05) - k21*pp15 - k22*pp25 + pp25
    pj26 = -(k20*pp06) - k21*pp16 - k22*pp26 + pp26
    pj33 = -(k30*pp03) - k31*pp13 - k32*pp23 + pp33
    pj34 = -(k30*pp04) - k31*pp14 - k32*pp24 + pp34
    pj35 = -(k30*pp05) - k31*pp15 - k32*pp25 + pp35
    pj36 = -(k30*pp06) - k31*pp16 - k32*pp26 + pp36
    pj44 = -(k40*pp04) - k41*pp14 - k42*pp24 + pp44
    pj45 = -(k40*pp05) - k41*pp15 - k42*pp25 + pp45
    pj46 = -(k40*pp06) - k41*pp16 - k42*pp26 + pp46
    pj55 = -(k50*pp05) - k51*pp15 - k52*pp25 + pp55
    pj56 = -(k50*pp06) - k51*pp16 - k52*pp26 + pp56
    pj66 = -(k60*pp06) - k61*pp16 - k62*pp26 + pp66
    sq[0] = x_p
    sq[1] = y_p
    sq[2] = z_p
    sq[3] = psi_p
    sq[4] = v
    sq[5] = omega
    sq[6] = v_up
    pq[0] = pp00
    pq[1] = pp01
    pq[2] = pp02
    pq[3] = pp03
    pq[4] = pp04
    pq[5] = pp05
    pq[6] = pp06
    pq[7] = pp11
    pq[8] = pp12
    pq[9] = pp13
    pq[10] = pp14
    pq[11] = pp15
    pq[12] = pp16
    pq[13] = pp22
    pq[14] = pp23
    pq[15] = pp24
    pq[16] = pp25
    pq[17] = pp26
    pq[18] = pp33
    pq[19] = pp34
    pq[20] = pp35
    pq[21] = pp36
    pq[22] = pp44
    pq[23] = pp45
    pq[24] = pp46
    pq[25] = pp55
    pq[26] = pp56
    pq[27] = pp66
    out_p0 = pj00
    out_p1 = pj01
    out_p2 = pj02
    out_p3 = pj03
    out_p4 = pj04
    out_p5 = pj05
    out_p6 = pj06
    out_p7 = pj11
    out_p8 = pj12
    out_p9 = pj13
    out_p10 = pj14
    out_p11 = pj15
    out_p12 = pj16
    out_p13 = pj22
    out_p14 = pj23
    out_p15 = pj24
    out_p16 = pj25
    out_p17 = pj26
    out_p18 = pj33
    out_p19 = pj34
    out_p20 = pj35
    out_p21 = pj36
    out_p22 = pj44
    out_p23 = pj45
    out_p24 = pj46
    out_p25 = pj55
    out_p26 = pj56
    out_p27 = pj66
    out_s0 = mu00
    out_s1 = mu01
    out_s2 = mu02
    out_s3 = mu03
    out_s4 = mu04
    out_s5 = mu05
    out_s6 = mu06
    if not covariance_is_pd_fused(out_p0, out_p1, out_p2, out_p3, out_p4, out_p5, out_p6, out_p7, out_p8, out_p9, out_p10, out_p11, out_p12, out_p13, out_p14, out_p15, out_p16, out_p17, out_p18, out_p19, out_p20, out_p21, out_p22, out_p23, out_p24, out_p25, out_p26, out_p27):
        out_p0 = pp00
        out_p1 = pp01
        out_p2 = pp02
        out_p3 = pp03
        out_p4 = pp04
        out_p5 = pp05
        out_p6 = pp06
        out_p7 = pp11
        out_p8 = pp12
        out_p9 = pp13
        out_p10 = pp14
        out_p11 = pp15
        out_p12 = pp16
        out_p13 = pp22
        out_p14 = pp23
        out_p15 = pp24
        out_p16 = pp25
        out_p17 = pp26
        out_p18 = pp33
        out_p19 = pp34
        out_p20 = pp35
        out_p21 = pp36
        out_p22 = pp44
        out_p23 = pp45
        out_p24 = pp46
        out_p25 = pp55
        out_p26 = pp56
        out_p27 = pp66
        out_s0 = x_p
        out_s1 = y_p
        out_s2 = z_p
        out_s3 = psi_p
        out_s4 = v
        out_s5 = omega
        out_s6 = v_up
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
    p[21] = out_p21
    p[22] = out_p22
    p[23] = out_p23
    p[24] = out_p24
    p[25] = out_p25
    p[26] = out_p26
    p[27] = out_p27
    s[0] = out_s0
    s[1] = out_s1
    s[2] = out_s2
    s[3] = out_s3
    s[4] = out_s4
    s[5] = out_s5
    s[6] = out_s6
    return nis, -math.log(rdet)


@nb.njit(inline="always", fastmath={"contract"}, error_model="numpy")
def lane_store_position3(W, j, sigma_a, sigma_alpha, sigma_z, r):
    """step_store_position3 on lane j of the work array W (rows: derive/codegen/smooth_step.py), without branches (SIMD); 1/det S in a row of W.
    """
    x = W[0 + j]
    y = W[64 + j]
    z = W[128 + j]
    psi = W[192 + j]
    v = W[256 + j]
    omega = W[320 + j]
    v_up = W[384 + j]
    p00 = W[448 + j]
    p01 = W[512 + j]
    p02 = W[576 + j]
    p03 = W[640 + j]
    p04 = W[704 + j]
    p05 = W[768 + j]
    p06 = W[832 + j]
    p11 = W[896 + j]
    p12 = W[960 + j]
    p13 = W[1024 + j]
    p14 = W[1088 + j]
    p15 = W[1152 + j]
    p16 = W[1216 + j]
    p22 = W[1280 + j]
    p23 = W[1344 + j]
    p24 = W[1408 + j]
    p25 = W[1472 + j]
    p26 = W[1536 + j]
    p33 = W[1600 + j]
    p34 = W[1664 + j]
    p35 = W[1728 + j]
    p36 = W[1792 + j]
    p44 = W[1856 + j]
    p45 = W[1920 + j]
    p46 = W[1984 + j]
    p55 = W[2048 + j]
    p56 = W[2112 + j]
    p66 = W[2176 + j]
    dt = W[4480 + j]
    z_x = W[4672 + j]
    z_y = W[4736 + j]
    z_z = W[4800 + j]
    _a0 = dt*omega/2.0
    _sin__a0 = sin_v(_a0)
    _cos__a0 = cos_v(_a0)
    _dsinc__a0 = dsinc_v(_a0, _sin__a0, _cos__a0)
    _sinc__a0 = sinc_v(_a0, _sin__a0, _cos__a0)
    _a1 = dt*omega/2.0 + psi
    _sin__a1 = sin_v(_a1)
    _cos__a1 = cos_v(_a1)
    _t0 = _sin__a1*_sinc__a0
    _t1 = _t0*dt
    _t2 = _cos__a1*_sinc__a0
    _t3 = _t2*dt
    _t4 = (dt*dt)*v/2.0
    cc03 = -(_t1*v)
    cc04 = _t3
    cc05 = -(_t4*(_cos__a1*_dsinc__a0 + _t0))
    cc13 = _t3*v
    cc14 = _t1
    cc15 = _t4*(-(_dsinc__a0*_sin__a1) + _t2)
    _sin_psi = sin_v(psi)
    _cos_psi = cos_v(psi)
    _t5 = (dt*dt)/2.0
    _t6 = _sinc__a0*dt*v
    g00 = _cos_psi*_t5
    g10 = _sin_psi*_t5
    g22 = _t5
    g31 = _t5
    e00 = _cos__a1*_t6 + x
    e01 = _sin__a1*_t6 + y
    e02 = dt*v_up + z
    e03 = dt*omega + psi
    _t7 = dt*p56
    m00 = cc03*p03 + cc04*p04 + cc05*p05 + p00
    m01 = cc03*p13 + cc04*p14 + cc05*p15 + p01
    m02 = cc03*p23 + cc04*p24 + cc05*p25 + p02
    m03 = cc03*p33 + cc04*p34 + cc05*p35 + p03
    m04 = cc03*p34 + cc04*p44 + cc05*p45 + p04
    m05 = cc03*p35 + cc04*p45 + cc05*p55 + p05
    m06 = cc03*p36 + cc04*p46 + cc05*p56 + p06
    m11 = cc13*p13 + cc14*p14 + cc15*p15 + p11
    m12 = cc13*p23 + cc14*p24 + cc15*p25 + p12
    m13 = cc13*p33 + cc14*p34 + cc15*p35 + p13
    m14 = cc13*p34 + cc14*p44 + cc15*p45 + p14
    m15 = cc13*p35 + cc14*p45 + cc15*p55 + p15
    m16 = cc13*p36 + cc14*p46 + cc15*p56 + p16
    m22 = dt*p26 + p22
    m23 = dt*p36 + p23
    m24 = dt*p46 + p24
    m25 = _t7 + p25
    m26 = dt*p66 + p26
    m33 = dt*p35 + p33
    m34 = dt*p45 + p34
    m35 = dt*p55 + p35
    m36 = _t7 + p36
    _t8 = sigma_a*sigma_a
    _t9 = _t8*g00
    _t10 = sigma_z*sigma_z
    _t11 = sigma_alpha*sigma_alpha
    _t12 = dt*dt
    pp00 = _t8*(g00*g00) + cc03*m03 + cc04*m04 + cc05*m05 + m00
    pp01 = _t9*g10 + cc13*m03 + cc14*m04 + cc15*m05 + m01
    pp02 = dt*m06 + m02
    pp03 = dt*m05 + m03
    pp04 = _t9*dt + m04
    pp05 = m05
    pp06 = m06
    pp11 = _t8*(g10*g10) + cc13*m13 + cc14*m14 + cc15*m15 + m11
    pp12 = dt*m16 + m12
    pp13 = dt*m15 + m13
    pp14 = _t8*dt*g10 + m14
    pp15 = m15
    pp16 = m16
    pp22 = _t10*(g22*g22) + dt*m26 + m22
    pp23 = dt*m25 + m23
    pp24 = m24
    pp25 = m25
    pp26 = _t10*dt*g22 + m26
    pp33 = _t11*(g31*g31) + dt*m35 + m33
    pp34 = m34
    pp35 = _t11*dt*g31 + m35
    pp36 = m36
    pp44 = _t12*_t8 + p44
    pp45 = p45
    pp46 = p46
    pp55 = _t11*_t12 + p55
    pp56 = p56
    pp66 = _t10*_t12 + p66
    x_p = e00
    y_p = e01
    z_p = e02
    psi_p = e03
    inn00 = -x_p + z_x
    inn10 = -y_p + z_y
    inn20 = -z_p + z_z
    _t13 = r*r
    S00 = _t13 + pp00
    S11 = _t13 + pp11
    S22 = _t13 + pp22
    rdet = 1.0/(S00*S11*S22 - S00*(pp12*pp12) - S11*(pp02*pp02) - S22*(pp01*pp01) + 2.0*pp01*pp02*pp12)
    Si00 = rdet*(S11*S22 - pp12*pp12)
    Si01 = rdet*(-(S22*pp01) + pp02*pp12)
    Si02 = rdet*(-(S11*pp02) + pp01*pp12)
    Si11 = rdet*(S00*S22 - pp02*pp02)
    Si12 = rdet*(-(S00*pp12) + pp01*pp02)
    Si22 = rdet*(S00*S11 - pp01*pp01)
    _t14 = Si01*pp01
    _t15 = Si02*pp02
    _t16 = Si12*pp12
    _t17 = 2.0*inn00
    k00 = Si00*pp00 + _t14 + _t15
    k01 = Si01*pp00 + Si11*pp01 + Si12*pp02
    k02 = Si02*pp00 + Si12*pp01 + Si22*pp02
    k10 = Si00*pp01 + Si01*pp11 + Si02*pp12
    k11 = Si11*pp11 + _t14 + _t16
    k12 = Si02*pp01 + Si12*pp11 + Si22*pp12
    k20 = Si00*pp02 + Si01*pp12 + Si02*pp22
    k21 = Si01*pp02 + Si11*pp12 + Si12*pp22
    k22 = Si22*pp22 + _t15 + _t16
    k30 = Si00*pp03 + Si01*pp13 + Si02*pp23
    k31 = Si01*pp03 + Si11*pp13 + Si12*pp23
    k32 = Si02*pp03 + Si12*pp13 + Si22*pp23
    k40 = Si00*pp04 + Si01*pp14 + Si02*pp24
    k41 = Si01*pp04 + Si11*pp14 + Si12*pp24
    k42 = Si02*pp04 + Si12*pp14 + Si22*pp24
    k50 = Si00*pp05 + Si01*pp15 + Si02*pp25
    k51 = Si01*pp05 + Si11*pp15 + Si12*pp25
    k52 = Si02*pp05 + Si12*pp15 + Si22*pp25
    k60 = Si00*pp06 + Si01*pp16 + Si02*pp26
    k61 = Si01*pp06 + Si11*pp16 + Si12*pp26
    k62 = Si02*pp06 + Si12*pp16 + Si22*pp26
    nis = Si00*(inn00*inn00) + Si01*_t17*inn10 + Si02*_t17*inn20 + Si11*(inn10*inn10) + 2.0*Si12*inn10*inn20 + Si22*(inn20*inn20)
    nk0 = inn00*k00 + inn10*k01 + inn20*k02
    nk1 = inn00*k10 + inn10*k11 + inn20*k12
    nk2 = inn00*k20 + inn10*k21 + inn20*k22
    nk3 = inn00*k30 + inn10*k31 + inn20*k32
    nk4 = inn00*k40 + inn10*k41 + inn20*k42
    nk5 = inn00*k50 + inn10*k51 + inn20*k52
    nk6 = inn00*k60 + inn10*k61 + inn20*k62
    mu00 = nk0 + x_p
    mu01 = nk1 + y_p
    mu02 = nk2 + z_p
    mu03 = nk3 + psi_p
    mu04 = nk4 + v
    mu05 = nk5 + omega
    mu06 = nk6 + v_up
    pj00 = -(k00*pp00) - k01*pp01 - k02*pp02 + pp00
    pj01 = -(k00*pp01) - k01*pp11 - k02*pp12 + pp01
    pj02 = -(k00*pp02) - k01*pp12 - k02*pp22 + pp02
    pj03 = -(k00*pp03) - k01*pp13 - k02*pp23 + pp03
    pj04 = -(k00*pp04) - k01*pp14 - k02*pp24 + pp04
    pj05 = -(k00*pp05) - k01*pp15 - k02*pp25 + pp05
    pj06 = -(k00*pp06) - k01*pp16 - k02*pp26 + pp06
    pj11 = -(k10*pp01) - k11*pp11 - k12*pp12 + pp11
    pj12 = -(k10*pp02) - k11*pp12 - k12*pp22 + pp12
    pj13 = -(k10*pp03) - k11*pp13 - k12*pp23 + pp13
    pj14 = -(k10*pp04) - k11*pp14 - k12*pp24 + pp14
    pj15 = -(k10*pp05) - k11*pp15 - k12*pp25 + pp15
    pj16 = -(k10*pp06) - k11*pp16 - k12*pp26 + pp16
    pj22 = -(k20*pp02) - k21*pp12 - k22*pp22 + pp22
    pj23 = -(k20*pp03) - k21*pp13 - k22*pp23 + pp23
    pj24 = -(k20*pp04) - k21*pp14 - k22*pp24 + pp24
    pj25 = -(k20*pp05) - k21*pp15 - k22*pp25 + pp25
    pj26 = -(k20*pp06) - k21*pp16 - k22*pp26 + pp26
    pj33 = -(k30*pp03) - k31*pp13 - k32*pp23 + pp33
    pj34 = -(k30*pp04) - k31*pp14 - k32*pp24 + pp34
    pj35 = -(k30*pp05) - k31*pp15 - k32*pp25 + pp35
    pj36 = -(k30*pp06) - k31*pp16 - k32*pp26 + pp36
    pj44 = -(k40*pp04) - k41*pp14 - k42*pp24 + pp44
    pj45 = -(k40*pp05) - k41*pp15 - k42*pp25 + pp45
    pj46 = -(k40*pp06) - k41*pp16 - k42*pp26 + pp46
    pj55 = -(k50*pp05) - k51*pp15 - k52*pp25 + pp55
    pj56 = -(k50*pp06) - k51*pp16 - k52*pp26 + pp56
    pj66 = -(k60*pp06) - k61*pp16 - k62*pp26 + pp66
    W[4864 + j] = x_p
    W[4928 + j] = y_p
    W[4992 + j] = z_p
    W[5056 + j] = psi_p
    W[5120 + j] = v
    W[5184 + j] = omega
    W[5248 + j] = v_up
    W[5312 + j] = pp00
    W[5376 + j] = pp01
    W[5440 + j] = pp02
    W[5504 + j] = pp03
    W[5568 + j] = pp04
    W[5632 + j] = pp05
    W[5696 + j] = pp06
    W[5760 + j] = pp11
    W[5824 + j] = pp12
    W[5888 + j] = pp13
    W[5952 + j] = pp14
    W[6016 + j] = pp15
    W[6080 + j] = pp16
    W[6144 + j] = pp22
    W[6208 + j] = pp23
    W[6272 + j] = pp24
    W[6336 + j] = pp25
    W[6400 + j] = pp26
    W[6464 + j] = pp33
    W[6528 + j] = pp34
    W[6592 + j] = pp35
    W[6656 + j] = pp36
    W[6720 + j] = pp44
    W[6784 + j] = pp45
    W[6848 + j] = pp46
    W[6912 + j] = pp55
    W[6976 + j] = pp56
    W[7040 + j] = pp66
    W[2688 + j] = pj00
    W[2752 + j] = pj01
    W[2816 + j] = pj02
    W[2880 + j] = pj03
    W[2944 + j] = pj04
    W[3008 + j] = pj05
    W[3072 + j] = pj06
    W[3136 + j] = pj11
    W[3200 + j] = pj12
    W[3264 + j] = pj13
    W[3328 + j] = pj14
    W[3392 + j] = pj15
    W[3456 + j] = pj16
    W[3520 + j] = pj22
    W[3584 + j] = pj23
    W[3648 + j] = pj24
    W[3712 + j] = pj25
    W[3776 + j] = pj26
    W[3840 + j] = pj33
    W[3904 + j] = pj34
    W[3968 + j] = pj35
    W[4032 + j] = pj36
    W[4096 + j] = pj44
    W[4160 + j] = pj45
    W[4224 + j] = pj46
    W[4288 + j] = pj55
    W[4352 + j] = pj56
    W[4416 + j] = pj66
    W[2240 + j] = mu00
    W[2304 + j] = mu01
    W[2368 + j] = mu02
    W[2432 + j] = mu03
    W[2496 + j] = mu04
    W[2560 + j] = mu05
    W[2624 + j] = mu06
    W[7104 + j] = rdet
    return nis


@nb.njit(cache=True, parallel=True, fastmath=FASTMATH, error_model="numpy")
def run_batch_store_soa_position3(z, dts, x0, p0, q, r, Qb, Fb, out_nis, out_logdet, out_x):
    """run_batch_store_position3 with trajectories in the SIMD lanes (derive/codegen/smooth_step.py), the same results
    with the states stored in blocks: Qb, Fb (nblk, K, 35, 64), nblk = ⌈B / 64⌉, get the predicted /
    posterior internal state and packed covariance of step k of trajectory blk·64 + j in Qb[blk, k, :, j]
    (lanes past B: zeros). As run_batch_soa_position3 (prange over blocks, lane_store_position3 vectorised over the lanes,
    a lane failing the LDLᵀ test or with a NaN row redone by the scalar predict / update_position3)."""
    B = z.shape[0]
    K = z.shape[1]
    nblk = (B + 64 - 1) // 64
    for blk in nb.prange(nblk):
        lo = blk * 64
        L = min(64, B - lo)
        W = np.zeros(112 * 64)
        s = np.empty(7)
        p = np.empty(28)
        for j in range(L):
            s0 = state_from_physical(x0[lo + j])
            for i in range(7):
                W[(0 + i) * 64 + j] = s0[i]
            for i in range(28):
                W[(7 + i) * 64 + j] = p0[lo + j, i]
        for k in range(K):
            for j in range(L):
                W[70 * 64 + j] = dts[lo + j, k]
                W[73 * 64 + j] = z[lo + j, k, 0]
                W[74 * 64 + j] = z[lo + j, k, 1]
                W[75 * 64 + j] = z[lo + j, k, 2]
            for j in range(L):
                W[71 * 64 + j] = lane_store_position3(W, j, q[0], q[1], q[2], r[0])
                good = covariance_is_pd_lane(W, j) & (W[71 * 64 + j] == W[71 * 64 + j])
                W[72 * 64 + j] = 1.0 if good else 0.0
            for j in range(L):
                b = lo + j
                if W[72 * 64 + j] == 0.0:
                    for i in range(7):
                        s[i] = W[(0 + i) * 64 + j]
                    for i in range(28):
                        p[i] = W[(7 + i) * 64 + j]
                    predict(s, p, dts[b, k], q[0], q[1], q[2])
                    for i in range(7):
                        W[(76 + i) * 64 + j] = s[i]
                    for i in range(28):
                        W[(83 + i) * 64 + j] = p[i]
                    if np.isnan(z[b, k, 0]) or np.isnan(z[b, k, 1]) or np.isnan(z[b, k, 2]):
                        W[71 * 64 + j] = np.nan
                        out_logdet[b, k] = np.nan
                    else:
                        out_logdet[b, k] = innovation_logdet_position3(s, p, r[0])
                        W[71 * 64 + j] = update_position3(s, p, z[b, k, 0], z[b, k, 1], z[b, k, 2], r[0])
                    for i in range(7):
                        W[(35 + i) * 64 + j] = s[i]
                    for i in range(28):
                        W[(42 + i) * 64 + j] = p[i]
                else:
                    out_logdet[b, k] = -math.log(W[111 * 64 + j])
            for j in range(L):
                out_nis[lo + j, k] = W[71 * 64 + j]
                physical_lane(W, j, out_x, lo + j, k)
            for i in range(7 + 28):
                for j in range(64):
                    Qb[blk, k, i, j] = W[(76 + i) * 64 + j]
                    Fb[blk, k, i, j] = W[(35 + i) * 64 + j]
            for i in range(7 + 28):
                for j in range(L):
                    W[(0 + i) * 64 + j] = W[(35 + i) * 64 + j]


@nb.njit(cache=True)
def run_one_store_position3(z, dts, x0, p0, q, r, s_pred, p_pred, s_filt, p_filt, out_nis, out_logdet, out_x):
    """Filter one trajectory like run_one_position3 and keep every step's predicted internal state and packed
    covariance (s_pred (K, 7), p_pred (K, 28), before the update) and posterior ones (s_filt, p_filt),
    the NIS and log det S of each update (both NaN for a missed detection: a NaN row of z predicts only) and
    the posterior physical states out_x (K, 7). A step with a measurement is the fused step_store_position3 (the
    filter's step_try_position3 writing its prediction; derive/codegen/smooth_step.py), with the same Joseph-form
    fallback as run_one_position3."""
    s = state_from_physical(x0)
    p = p0.copy()
    K = z.shape[0]
    for k in range(K):
        if np.isnan(z[k, 0]) or np.isnan(z[k, 1]) or np.isnan(z[k, 2]):
            predict(s, p, dts[k], q[0], q[1], q[2])
            for i in range(7):
                s_pred[k, i] = s[i]
            for i in range(28):
                p_pred[k, i] = p[i]
            out_nis[k] = np.nan
            out_logdet[k] = np.nan
        else:
            nis, out_logdet[k] = step_store_position3(s, p, dts[k], q[0], q[1], q[2], z[k, 0], z[k, 1], z[k, 2], r[0], s_pred[k], p_pred[k])
            if nis < 0.0:  # rare: the cheap covariance failed the LDLᵀ test; Joseph form from the prediction
                nis = update_position3(s, p, z[k, 0], z[k, 1], z[k, 2], r[0])
            out_nis[k] = nis
        for i in range(7):
            s_filt[k, i] = s[i]
        for i in range(28):
            p_filt[k, i] = p[i]
        physical_into(s, out_x[k])


@nb.njit(cache=True, parallel=True)
def run_batch_store_position3(z, dts, x0, p0, q, r, s_pred, p_pred, s_filt, p_filt, out_nis, out_logdet, out_x):
    """run_one_store_position3 over B trajectories in parallel (prange); arrays as run_batch_position3 with a
    leading batch axis (s_pred, s_filt (B, K, 7); p_pred, p_filt (B, K, 28); out_nis, out_logdet (B, K);
    out_x (B, K, 7))."""
    for b in nb.prange(z.shape[0]):
        run_one_store_position3(z[b], dts[b], x0[b], p0[b], q, r, s_pred[b], p_pred[b], s_filt[b], p_filt[b], out_nis[b],
                             out_logdet[b], out_x[b])


@nb.njit(cache=True, parallel=True)
def loglik_batch_position3(z, dts, x0, p0, q, r, lengths, out_ll, out_count):
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
                ld = innovation_logdet_position3(s, p, r[0])
                nis = update_position3(s, p, z[b, k, 0], z[b, k, 1], z[b, k, 2], r[0])
                ll += -0.5 * (ld + nis + 3.0 * 1.8378770664093453)
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
    z = s_filt[k, 2]
    psi = s_filt[k, 3]
    v = s_filt[k, 4]
    omega = s_filt[k, 5]
    v_up = s_filt[k, 6]
    pf00 = p_filt[k, 0]
    pf01 = p_filt[k, 1]
    pf02 = p_filt[k, 2]
    pf03 = p_filt[k, 3]
    pf04 = p_filt[k, 4]
    pf05 = p_filt[k, 5]
    pf06 = p_filt[k, 6]
    pf11 = p_filt[k, 7]
    pf12 = p_filt[k, 8]
    pf13 = p_filt[k, 9]
    pf14 = p_filt[k, 10]
    pf15 = p_filt[k, 11]
    pf16 = p_filt[k, 12]
    pf22 = p_filt[k, 13]
    pf23 = p_filt[k, 14]
    pf24 = p_filt[k, 15]
    pf25 = p_filt[k, 16]
    pf26 = p_filt[k, 17]
    pf33 = p_filt[k, 18]
    pf34 = p_filt[k, 19]
    pf35 = p_filt[k, 20]
    pf36 = p_filt[k, 21]
    pf44 = p_filt[k, 22]
    pf45 = p_filt[k, 23]
    pf46 = p_filt[k, 24]
    pf55 = p_filt[k, 25]
    pf56 = p_filt[k, 26]
    pf66 = p_filt[k, 27]
    q_x = s_pred[k + 1, 0]
    q_y = s_pred[k + 1, 1]
    q_z = s_pred[k + 1, 2]
    q_psi = s_pred[k + 1, 3]
    q_v = s_pred[k + 1, 4]
    q_omega = s_pred[k + 1, 5]
    q_v_up = s_pred[k + 1, 6]
    pq00 = p_pred[k + 1, 0]
    pq01 = p_pred[k + 1, 1]
    pq02 = p_pred[k + 1, 2]
    pq03 = p_pred[k + 1, 3]
    pq04 = p_pred[k + 1, 4]
    pq05 = p_pred[k + 1, 5]
    pq06 = p_pred[k + 1, 6]
    pq11 = p_pred[k + 1, 7]
    pq12 = p_pred[k + 1, 8]
    pq13 = p_pred[k + 1, 9]
    pq14 = p_pred[k + 1, 10]
    pq15 = p_pred[k + 1, 11]
    pq16 = p_pred[k + 1, 12]
    pq22 = p_pred[k + 1, 13]
    pq23 = p_pred[k + 1, 14]
    pq24 = p_pred[k + 1, 15]
    pq25 = p_pred[k + 1, 16]
    pq26 = p_pred[k + 1, 17]
    pq33 = p_pred[k + 1, 18]
    pq34 = p_pred[k + 1, 19]
    pq35 = p_pred[k + 1, 20]
    pq36 = p_pred[k + 1, 21]
    pq44 = p_pred[k + 1, 22]
    pq45 = p_pred[k + 1, 23]
    pq46 = p_pred[k + 1, 24]
    pq55 = p_pred[k + 1, 25]
    pq56 = p_pred[k + 1, 26]
    pq66 = p_pred[k + 1, 27]
    t_x = s_sm[k + 1, 0]
    t_y = s_sm[k + 1, 1]
    t_z = s_sm[k + 1, 2]
    t_psi = s_sm[k + 1, 3]
    t_v = s_sm[k + 1, 4]
    t_omega = s_sm[k + 1, 5]
    t_v_up = s_sm[k + 1, 6]
    ps00 = p_sm[k + 1, 0]
    ps01 = p_sm[k + 1, 1]
    ps02 = p_sm[k + 1, 2]
    ps03 = p_sm[k + 1, 3]
    ps04 = p_sm[k + 1, 4]
    ps05 = p_sm[k + 1, 5]
    ps06 = p_sm[k + 1, 6]
    ps11 = p_sm[k + 1, 7]
    ps12 = p_sm[k + 1, 8]
    ps13 = p_sm[k + 1, 9]
    ps14 = p_sm[k + 1, 10]
    ps15 = p_sm[k + 1, 11]
    ps16 = p_sm[k + 1, 12]
    ps22 = p_sm[k + 1, 13]
    ps23 = p_sm[k + 1, 14]
    ps24 = p_sm[k + 1, 15]
    ps25 = p_sm[k + 1, 16]
    ps26 = p_sm[k + 1, 17]
    ps33 = p_sm[k + 1, 18]
    ps34 = p_sm[k + 1, 19]
    ps35 = p_sm[k + 1, 20]
    ps36 = p_sm[k + 1, 21]
    ps44 = p_sm[k + 1, 22]
    ps45 = p_sm[k + 1, 23]
    ps46 = p_sm[k + 1, 24]
    ps55 = p_sm[k + 1, 25]
    ps56 = p_sm[k + 1, 26]
    ps66 = p_sm[k + 1, 27]
    _a0 = dt*omega/2.0
    _sin__a0 = math.sin(_a0)
    _cos__a0 = math.cos(_a0)
    _dsinc__a0 = dsinc(_a0, _sin__a0, _cos__a0)
    _sinc__a0 = sinc(_a0, _sin__a0, _cos__a0)
    _a1 = dt*omega/2.0 + psi
    _sin__a1 = math.sin(_a1)
    _cos__a1 = math.cos(_a1)
    _t0 = _sin__a1*_sinc__a0
    _t1 = _t0*dt
    _t2 = _cos__a1*_sinc__a0
    _t3 = _t2*dt
    _t4 = (dt*dt)*v/2.0
    _t5 = dt*pf56
    cc0_3 = -(_t1*v)
    cc0_4 = _t3
    cc0_5 = -(_t4*(_cos__a1*_dsinc__a0 + _t0))
    cc1_3 = _t3*v
    cc1_4 = _t1
    cc1_5 = _t4*(-(_dsinc__a0*_sin__a1) + _t2)
    cf0_2 = dt*pf06 + pf02
    cf0_3 = dt*pf05 + pf03
    cf1_2 = dt*pf16 + pf12
    cf1_3 = dt*pf15 + pf13
    cf2_2 = dt*pf26 + pf22
    cf2_3 = dt*pf25 + pf23
    cf3_2 = dt*pf36 + pf23
    cf3_3 = dt*pf35 + pf33
    cf4_2 = dt*pf46 + pf24
    cf4_3 = dt*pf45 + pf34
    cf5_2 = _t5 + pf25
    cf5_3 = dt*pf55 + pf35
    cf6_2 = dt*pf66 + pf26
    cf6_3 = _t5 + pf36
    dd0_0 = -q_x + t_x
    dd0_1 = -q_y + t_y
    dd0_2 = -q_z + t_z
    dd0_3 = wrap_angle(-q_psi + t_psi)
    dd0_4 = -q_v + t_v
    dd0_5 = -q_omega + t_omega
    dd0_6 = -q_v_up + t_v_up
    dm0_0 = -pq00 + ps00
    dm0_1 = -pq01 + ps01
    dm0_2 = -pq02 + ps02
    dm0_3 = -pq03 + ps03
    dm0_4 = -pq04 + ps04
    dm0_5 = -pq05 + ps05
    dm0_6 = -pq06 + ps06
    dm1_1 = -pq11 + ps11
    dm1_2 = -pq12 + ps12
    dm1_3 = -pq13 + ps13
    dm1_4 = -pq14 + ps14
    dm1_5 = -pq15 + ps15
    dm1_6 = -pq16 + ps16
    dm2_2 = -pq22 + ps22
    dm2_3 = -pq23 + ps23
    dm2_4 = -pq24 + ps24
    dm2_5 = -pq25 + ps25
    dm2_6 = -pq26 + ps26
    dm3_3 = -pq33 + ps33
    dm3_4 = -pq34 + ps34
    dm3_5 = -pq35 + ps35
    dm3_6 = -pq36 + ps36
    dm4_4 = -pq44 + ps44
    dm4_5 = -pq45 + ps45
    dm4_6 = -pq46 + ps46
    dm5_5 = -pq55 + ps55
    dm5_6 = -pq56 + ps56
    dm6_6 = -pq66 + ps66
    lr0 = 1.0/max(1e-300, pq00)
    cf0_0 = cc0_3*pf03 + cc0_4*pf04 + cc0_5*pf05 + pf00
    cf0_1 = cc1_3*pf03 + cc1_4*pf04 + cc1_5*pf05 + pf01
    cf1_0 = cc0_3*pf13 + cc0_4*pf14 + cc0_5*pf15 + pf01
    cf1_1 = cc1_3*pf13 + cc1_4*pf14 + cc1_5*pf15 + pf11
    cf2_0 = cc0_3*pf23 + cc0_4*pf24 + cc0_5*pf25 + pf02
    cf2_1 = cc1_3*pf23 + cc1_4*pf24 + cc1_5*pf25 + pf12
    cf3_0 = cc0_3*pf33 + cc0_4*pf34 + cc0_5*pf35 + pf03
    cf3_1 = cc1_3*pf33 + cc1_4*pf34 + cc1_5*pf35 + pf13
    cf4_0 = cc0_3*pf34 + cc0_4*pf44 + cc0_5*pf45 + pf04
    cf4_1 = cc1_3*pf34 + cc1_4*pf44 + cc1_5*pf45 + pf14
    cf5_0 = cc0_3*pf35 + cc0_4*pf45 + cc0_5*pf55 + pf05
    cf5_1 = cc1_3*pf35 + cc1_4*pf45 + cc1_5*pf55 + pf15
    cf6_0 = cc0_3*pf36 + cc0_4*pf46 + cc0_5*pf56 + pf06
    cf6_1 = cc1_3*pf36 + cc1_4*pf46 + cc1_5*pf56 + pf16
    ll1_0 = lr0*pq01
    ll2_0 = lr0*pq02
    ll3_0 = lr0*pq03
    ll4_0 = lr0*pq04
    ll5_0 = lr0*pq05
    ll6_0 = lr0*pq06
    lw1_0 = ll1_0*pq00
    lw2_0 = ll2_0*pq00
    lw3_0 = ll3_0*pq00
    lw4_0 = ll4_0*pq00
    lw5_0 = ll5_0*pq00
    lw6_0 = ll6_0*pq00
    ly0_1 = -(cf0_0*ll1_0) + cf0_1
    ly1_1 = -(cf1_0*ll1_0) + cf1_1
    ly2_1 = -(cf2_0*ll1_0) + cf2_1
    ly3_1 = -(cf3_0*ll1_0) + cf3_1
    ly4_1 = -(cf4_0*ll1_0) + cf4_1
    ly5_1 = -(cf5_0*ll1_0) + cf5_1
    ly6_1 = -(cf6_0*ll1_0) + cf6_1
    ld1 = -(ll1_0*lw1_0) + pq11
    lr1 = 1.0/max(1e-300, ld1)
    ll2_1 = lr1*(-(ll2_0*lw1_0) + pq12)
    ll3_1 = lr1*(-(ll3_0*lw1_0) + pq13)
    ll4_1 = lr1*(-(ll4_0*lw1_0) + pq14)
    ll5_1 = lr1*(-(ll5_0*lw1_0) + pq15)
    ll6_1 = lr1*(-(ll6_0*lw1_0) + pq16)
    lw2_1 = ld1*ll2_1
    lw3_1 = ld1*ll3_1
    lw4_1 = ld1*ll4_1
    lw5_1 = ld1*ll5_1
    lw6_1 = ld1*ll6_1
    ly0_2 = -(cf0_0*ll2_0) + cf0_2 - ll2_1*ly0_1
    ly1_2 = -(cf1_0*ll2_0) + cf1_2 - ll2_1*ly1_1
    ly2_2 = -(cf2_0*ll2_0) + cf2_2 - ll2_1*ly2_1
    ly3_2 = -(cf3_0*ll2_0) + cf3_2 - ll2_1*ly3_1
    ly4_2 = -(cf4_0*ll2_0) + cf4_2 - ll2_1*ly4_1
    ly5_2 = -(cf5_0*ll2_0) + cf5_2 - ll2_1*ly5_1
    ly6_2 = -(cf6_0*ll2_0) + cf6_2 - ll2_1*ly6_1
    ld2 = -(ll2_0*lw2_0) - ll2_1*lw2_1 + pq22
    lr2 = 1.0/max(1e-300, ld2)
    ll3_2 = lr2*(-(ll3_0*lw2_0) - ll3_1*lw2_1 + pq23)
    ll4_2 = lr2*(-(ll4_0*lw2_0) - ll4_1*lw2_1 + pq24)
    ll5_2 = lr2*(-(ll5_0*lw2_0) - ll5_1*lw2_1 + pq25)
    ll6_2 = lr2*(-(ll6_0*lw2_0) - ll6_1*lw2_1 + pq26)
    lw3_2 = ld2*ll3_2
    lw4_2 = ld2*ll4_2
    lw5_2 = ld2*ll5_2
    lw6_2 = ld2*ll6_2
    ly0_3 = -(cf0_0*ll3_0) + cf0_3 - ll3_1*ly0_1 - ll3_2*ly0_2
    ly1_3 = -(cf1_0*ll3_0) + cf1_3 - ll3_1*ly1_1 - ll3_2*ly1_2
    ly2_3 = -(cf2_0*ll3_0) + cf2_3 - ll3_1*ly2_1 - ll3_2*ly2_2
    ly3_3 = -(cf3_0*ll3_0) + cf3_3 - ll3_1*ly3_1 - ll3_2*ly3_2
    ly4_3 = -(cf4_0*ll3_0) + cf4_3 - ll3_1*ly4_1 - ll3_2*ly4_2
    ly5_3 = -(cf5_0*ll3_0) + cf5_3 - ll3_1*ly5_1 - ll3_2*ly5_2
    ly6_3 = -(cf6_0*ll3_0) + cf6_3 - ll3_1*ly6_1 - ll3_2*ly6_2
    ld3 = -(ll3_0*lw3_0) - ll3_1*lw3_1 - ll3_2*lw3_2 + pq33
    lr3 = 1.0/max(1e-300, ld3)
    ll4_3 = lr3*(-(ll4_0*lw3_0) - ll4_1*lw3_1 - ll4_2*lw3_2 + pq34)
    ll5_3 = lr3*(-(ll5_0*lw3_0) - ll5_1*lw3_1 - ll5_2*lw3_2 + pq35)
    ll6_3 = lr3*(-(ll6_0*lw3_0) - ll6_1*lw3_1 - ll6_2*lw3_2 + pq36)
    lw4_3 = ld3*ll4_3
    lw5_3 = ld3*ll5_3
    lw6_3 = ld3*ll6_3
    ly0_4 = -(cf0_0*ll4_0) - ll4_1*ly0_1 - ll4_2*ly0_2 - ll4_3*ly0_3 + pf04
    ly1_4 = -(cf1_0*ll4_0) - ll4_1*ly1_1 - ll4_2*ly1_2 - ll4_3*ly1_3 + pf14
    ly2_4 = -(cf2_0*ll4_0) - ll4_1*ly2_1 - ll4_2*ly2_2 - ll4_3*ly2_3 + pf24
    ly3_4 = -(cf3_0*ll4_0) - ll4_1*ly3_1 - ll4_2*ly3_2 - ll4_3*ly3_3 + pf34
    ly4_4 = -(cf4_0*ll4_0) - ll4_1*ly4_1 - ll4_2*ly4_2 - ll4_3*ly4_3 + pf44
    ly5_4 = -(cf5_0*ll4_0) - ll4_1*ly5_1 - ll4_2*ly5_2 - ll4_3*ly5_3 + pf45
    ly6_4 = -(cf6_0*ll4_0) - ll4_1*ly6_1 - ll4_2*ly6_2 - ll4_3*ly6_3 + pf46
    ld4 = -(ll4_0*lw4_0) - ll4_1*lw4_1 - ll4_2*lw4_2 - ll4_3*lw4_3 + pq44
    lr4 = 1.0/max(1e-300, ld4)
    ll5_4 = lr4*(-(ll5_0*lw4_0) - ll5_1*lw4_1 - ll5_2*lw4_2 - ll5_3*lw4_3 + pq45)
    ll6_4 = lr4*(-(ll6_0*lw4_0) - ll6_1*lw4_1 - ll6_2*lw4_2 - ll6_3*lw4_3 + pq46)
    lw5_4 = ld4*ll5_4
    lw6_4 = ld4*ll6_4
    ly0_5 = -(cf0_0*ll5_0) - ll5_1*ly0_1 - ll5_2*ly0_2 - ll5_3*ly0_3 - ll5_4*ly0_4 + pf05
    ly1_5 = -(cf1_0*ll5_0) - ll5_1*ly1_1 - ll5_2*ly1_2 - ll5_3*ly1_3 - ll5_4*ly1_4 + pf15
    ly2_5 = -(cf2_0*ll5_0) - ll5_1*ly2_1 - ll5_2*ly2_2 - ll5_3*ly2_3 - ll5_4*ly2_4 + pf25
    ly3_5 = -(cf3_0*ll5_0) - ll5_1*ly3_1 - ll5_2*ly3_2 - ll5_3*ly3_3 - ll5_4*ly3_4 + pf35
    ly4_5 = -(cf4_0*ll5_0) - ll5_1*ly4_1 - ll5_2*ly4_2 - ll5_3*ly4_3 - ll5_4*ly4_4 + pf45
    ly5_5 = -(cf5_0*ll5_0) - ll5_1*ly5_1 - ll5_2*ly5_2 - ll5_3*ly5_3 - ll5_4*ly5_4 + pf55
    ly6_5 = -(cf6_0*ll5_0) - ll5_1*ly6_1 - ll5_2*ly6_2 - ll5_3*ly6_3 - ll5_4*ly6_4 + pf56
    ld5 = -(ll5_0*lw5_0) - ll5_1*lw5_1 - ll5_2*lw5_2 - ll5_3*lw5_3 - ll5_4*lw5_4 + pq55
    lr5 = 1.0/max(1e-300, ld5)
    ll6_5 = lr5*(-(ll6_0*lw5_0) - ll6_1*lw5_1 - ll6_2*lw5_2 - ll6_3*lw5_3 - ll6_4*lw5_4 + pq56)
    lw6_5 = ld5*ll6_5
    ly0_6 = -(cf0_0*ll6_0) - ll6_1*ly0_1 - ll6_2*ly0_2 - ll6_3*ly0_3 - ll6_4*ly0_4 - ll6_5*ly0_5 + pf06
    ly1_6 = -(cf1_0*ll6_0) - ll6_1*ly1_1 - ll6_2*ly1_2 - ll6_3*ly1_3 - ll6_4*ly1_4 - ll6_5*ly1_5 + pf16
    ly2_6 = -(cf2_0*ll6_0) - ll6_1*ly2_1 - ll6_2*ly2_2 - ll6_3*ly2_3 - ll6_4*ly2_4 - ll6_5*ly2_5 + pf26
    ly3_6 = -(cf3_0*ll6_0) - ll6_1*ly3_1 - ll6_2*ly3_2 - ll6_3*ly3_3 - ll6_4*ly3_4 - ll6_5*ly3_5 + pf36
    ly4_6 = -(cf4_0*ll6_0) - ll6_1*ly4_1 - ll6_2*ly4_2 - ll6_3*ly4_3 - ll6_4*ly4_4 - ll6_5*ly4_5 + pf46
    ly5_6 = -(cf5_0*ll6_0) - ll6_1*ly5_1 - ll6_2*ly5_2 - ll6_3*ly5_3 - ll6_4*ly5_4 - ll6_5*ly5_5 + pf56
    ly6_6 = -(cf6_0*ll6_0) - ll6_1*ly6_1 - ll6_2*ly6_2 - ll6_3*ly6_3 - ll6_4*ly6_4 - ll6_5*ly6_5 + pf66
    ld6 = -(ll6_0*lw6_0) - ll6_1*lw6_1 - ll6_2*lw6_2 - ll6_3*lw6_3 - ll6_4*lw6_4 - ll6_5*lw6_5 + pq66
    lr6 = 1.0/max(1e-300, ld6)
    gg0_6 = lr6*ly0_6
    gg1_6 = lr6*ly1_6
    gg2_6 = lr6*ly2_6
    gg3_6 = lr6*ly3_6
    gg4_6 = lr6*ly4_6
    gg5_6 = lr6*ly5_6
    gg6_6 = lr6*ly6_6
    gg0_5 = -(gg0_6*ll6_5) + lr5*ly0_5
    gg1_5 = -(gg1_6*ll6_5) + lr5*ly1_5
    gg2_5 = -(gg2_6*ll6_5) + lr5*ly2_5
    gg3_5 = -(gg3_6*ll6_5) + lr5*ly3_5
    gg4_5 = -(gg4_6*ll6_5) + lr5*ly4_5
    gg5_5 = -(gg5_6*ll6_5) + lr5*ly5_5
    gg6_5 = -(gg6_6*ll6_5) + lr5*ly6_5
    gg0_4 = -(gg0_5*ll5_4) - gg0_6*ll6_4 + lr4*ly0_4
    gg1_4 = -(gg1_5*ll5_4) - gg1_6*ll6_4 + lr4*ly1_4
    gg2_4 = -(gg2_5*ll5_4) - gg2_6*ll6_4 + lr4*ly2_4
    gg3_4 = -(gg3_5*ll5_4) - gg3_6*ll6_4 + lr4*ly3_4
    gg4_4 = -(gg4_5*ll5_4) - gg4_6*ll6_4 + lr4*ly4_4
    gg5_4 = -(gg5_5*ll5_4) - gg5_6*ll6_4 + lr4*ly5_4
    gg6_4 = -(gg6_5*ll5_4) - gg6_6*ll6_4 + lr4*ly6_4
    gg0_3 = -(gg0_4*ll4_3) - gg0_5*ll5_3 - gg0_6*ll6_3 + lr3*ly0_3
    gg1_3 = -(gg1_4*ll4_3) - gg1_5*ll5_3 - gg1_6*ll6_3 + lr3*ly1_3
    gg2_3 = -(gg2_4*ll4_3) - gg2_5*ll5_3 - gg2_6*ll6_3 + lr3*ly2_3
    gg3_3 = -(gg3_4*ll4_3) - gg3_5*ll5_3 - gg3_6*ll6_3 + lr3*ly3_3
    gg4_3 = -(gg4_4*ll4_3) - gg4_5*ll5_3 - gg4_6*ll6_3 + lr3*ly4_3
    gg5_3 = -(gg5_4*ll4_3) - gg5_5*ll5_3 - gg5_6*ll6_3 + lr3*ly5_3
    gg6_3 = -(gg6_4*ll4_3) - gg6_5*ll5_3 - gg6_6*ll6_3 + lr3*ly6_3
    gg0_2 = -(gg0_3*ll3_2) - gg0_4*ll4_2 - gg0_5*ll5_2 - gg0_6*ll6_2 + lr2*ly0_2
    gg1_2 = -(gg1_3*ll3_2) - gg1_4*ll4_2 - gg1_5*ll5_2 - gg1_6*ll6_2 + lr2*ly1_2
    gg2_2 = -(gg2_3*ll3_2) - gg2_4*ll4_2 - gg2_5*ll5_2 - gg2_6*ll6_2 + lr2*ly2_2
    gg3_2 = -(gg3_3*ll3_2) - gg3_4*ll4_2 - gg3_5*ll5_2 - gg3_6*ll6_2 + lr2*ly3_2
    gg4_2 = -(gg4_3*ll3_2) - gg4_4*ll4_2 - gg4_5*ll5_2 - gg4_6*ll6_2 + lr2*ly4_2
    gg5_2 = -(gg5_3*ll3_2) - gg5_4*ll4_2 - gg5_5*ll5_2 - gg5_6*ll6_2 + lr2*ly5_2
    gg6_2 = -(gg6_3*ll3_2) - gg6_4*ll4_2 - gg6_5*ll5_2 - gg6_6*ll6_2 + lr2*ly6_2
    gg0_1 = -(gg0_2*ll2_1) - gg0_3*ll3_1 - gg0_4*ll4_1 - gg0_5*ll5_1 - gg0_6*ll6_1 + lr1*ly0_1
    gg1_1 = -(gg1_2*ll2_1) - gg1_3*ll3_1 - gg1_4*ll4_1 - gg1_5*ll5_1 - gg1_6*ll6_1 + lr1*ly1_1
    gg2_1 = -(gg2_2*ll2_1) - gg2_3*ll3_1 - gg2_4*ll4_1 - gg2_5*ll5_1 - gg2_6*ll6_1 + lr1*ly2_1
    gg3_1 = -(gg3_2*ll2_1) - gg3_3*ll3_1 - gg3_4*ll4_1 - gg3_5*ll5_1 - gg3_6*ll6_1 + lr1*ly3_1
    gg4_1 = -(gg4_2*ll2_1) - gg4_3*ll3_1 - gg4_4*ll4_1 - gg4_5*ll5_1 - gg4_6*ll6_1 + lr1*ly4_1
    gg5_1 = -(gg5_2*ll2_1) - gg5_3*ll3_1 - gg5_4*ll4_1 - gg5_5*ll5_1 - gg5_6*ll6_1 + lr1*ly5_1
    gg6_1 = -(gg6_2*ll2_1) - gg6_3*ll3_1 - gg6_4*ll4_1 - gg6_5*ll5_1 - gg6_6*ll6_1 + lr1*ly6_1
    gg0_0 = cf0_0*lr0 - gg0_1*ll1_0 - gg0_2*ll2_0 - gg0_3*ll3_0 - gg0_4*ll4_0 - gg0_5*ll5_0 - gg0_6*ll6_0
    gg1_0 = cf1_0*lr0 - gg1_1*ll1_0 - gg1_2*ll2_0 - gg1_3*ll3_0 - gg1_4*ll4_0 - gg1_5*ll5_0 - gg1_6*ll6_0
    gg2_0 = cf2_0*lr0 - gg2_1*ll1_0 - gg2_2*ll2_0 - gg2_3*ll3_0 - gg2_4*ll4_0 - gg2_5*ll5_0 - gg2_6*ll6_0
    gg3_0 = cf3_0*lr0 - gg3_1*ll1_0 - gg3_2*ll2_0 - gg3_3*ll3_0 - gg3_4*ll4_0 - gg3_5*ll5_0 - gg3_6*ll6_0
    gg4_0 = cf4_0*lr0 - gg4_1*ll1_0 - gg4_2*ll2_0 - gg4_3*ll3_0 - gg4_4*ll4_0 - gg4_5*ll5_0 - gg4_6*ll6_0
    gg5_0 = cf5_0*lr0 - gg5_1*ll1_0 - gg5_2*ll2_0 - gg5_3*ll3_0 - gg5_4*ll4_0 - gg5_5*ll5_0 - gg5_6*ll6_0
    gg6_0 = cf6_0*lr0 - gg6_1*ll1_0 - gg6_2*ll2_0 - gg6_3*ll3_0 - gg6_4*ll4_0 - gg6_5*ll5_0 - gg6_6*ll6_0
    de0_0 = dd0_0*gg0_0 + dd0_1*gg0_1 + dd0_2*gg0_2 + dd0_3*gg0_3 + dd0_4*gg0_4 + dd0_5*gg0_5 + dd0_6*gg0_6
    de1_0 = dd0_0*gg1_0 + dd0_1*gg1_1 + dd0_2*gg1_2 + dd0_3*gg1_3 + dd0_4*gg1_4 + dd0_5*gg1_5 + dd0_6*gg1_6
    de2_0 = dd0_0*gg2_0 + dd0_1*gg2_1 + dd0_2*gg2_2 + dd0_3*gg2_3 + dd0_4*gg2_4 + dd0_5*gg2_5 + dd0_6*gg2_6
    de3_0 = dd0_0*gg3_0 + dd0_1*gg3_1 + dd0_2*gg3_2 + dd0_3*gg3_3 + dd0_4*gg3_4 + dd0_5*gg3_5 + dd0_6*gg3_6
    de4_0 = dd0_0*gg4_0 + dd0_1*gg4_1 + dd0_2*gg4_2 + dd0_3*gg4_3 + dd0_4*gg4_4 + dd0_5*gg4_5 + dd0_6*gg4_6
    de5_0 = dd0_0*gg5_0 + dd0_1*gg5_1 + dd0_2*gg5_2 + dd0_3*gg5_3 + dd0_4*gg5_4 + dd0_5*gg5_5 + dd0_6*gg5_6
    de6_0 = dd0_0*gg6_0 + dd0_1*gg6_1 + dd0_2*gg6_2 + dd0_3*gg6_3 + dd0_4*gg6_4 + dd0_5*gg6_5 + dd0_6*gg6_6
    gd0_0 = dm0_0*gg0_0 + dm0_1*gg0_1 + dm0_2*gg0_2 + dm0_3*gg0_3 + dm0_4*gg0_4 + dm0_5*gg0_5 + dm0_6*gg0_6
    gd0_1 = dm0_1*gg0_0 + dm1_1*gg0_1 + dm1_2*gg0_2 + dm1_3*gg0_3 + dm1_4*gg0_4 + dm1_5*gg0_5 + dm1_6*gg0_6
    gd0_2 = dm0_2*gg0_0 + dm1_2*gg0_1 + dm2_2*gg0_2 + dm2_3*gg0_3 + dm2_4*gg0_4 + dm2_5*gg0_5 + dm2_6*gg0_6
    gd0_3 = dm0_3*gg0_0 + dm1_3*gg0_1 + dm2_3*gg0_2 + dm3_3*gg0_3 + dm3_4*gg0_4 + dm3_5*gg0_5 + dm3_6*gg0_6
    gd0_4 = dm0_4*gg0_0 + dm1_4*gg0_1 + dm2_4*gg0_2 + dm3_4*gg0_3 + dm4_4*gg0_4 + dm4_5*gg0_5 + dm4_6*gg0_6
    gd0_5 = dm0_5*gg0_0 + dm1_5*gg0_1 + dm2_5*gg0_2 + dm3_5*gg0_3 + dm4_5*gg0_4 + dm5_5*gg0_5 + dm5_6*gg0_6
    gd0_6 = dm0_6*gg0_0 + dm1_6*gg0_1 + dm2_6*gg0_2 + dm3_6*gg0_3 + dm4_6*gg0_4 + dm5_6*gg0_5 + dm6_6*gg0_6
    gd1_0 = dm0_0*gg1_0 + dm0_1*gg1_1 + dm0_2*gg1_2 + dm0_3*gg1_3 + dm0_4*gg1_4 + dm0_5*gg1_5 + dm0_6*gg1_6
    gd1_1 = dm0_1*gg1_0 + dm1_1*gg1_1 + dm1_2*gg1_2 + dm1_3*gg1_3 + dm1_4*gg1_4 + dm1_5*gg1_5 + dm1_6*gg1_6
    gd1_2 = dm0_2*gg1_0 + dm1_2*gg1_1 + dm2_2*gg1_2 + dm2_3*gg1_3 + dm2_4*gg1_4 + dm2_5*gg1_5 + dm2_6*gg1_6
    gd1_3 = dm0_3*gg1_0 + dm1_3*gg1_1 + dm2_3*gg1_2 + dm3_3*gg1_3 + dm3_4*gg1_4 + dm3_5*gg1_5 + dm3_6*gg1_6
    gd1_4 = dm0_4*gg1_0 + dm1_4*gg1_1 + dm2_4*gg1_2 + dm3_4*gg1_3 + dm4_4*gg1_4 + dm4_5*gg1_5 + dm4_6*gg1_6
    gd1_5 = dm0_5*gg1_0 + dm1_5*gg1_1 + dm2_5*gg1_2 + dm3_5*gg1_3 + dm4_5*gg1_4 + dm5_5*gg1_5 + dm5_6*gg1_6
    gd1_6 = dm0_6*gg1_0 + dm1_6*gg1_1 + dm2_6*gg1_2 + dm3_6*gg1_3 + dm4_6*gg1_4 + dm5_6*gg1_5 + dm6_6*gg1_6
    gd2_0 = dm0_0*gg2_0 + dm0_1*gg2_1 + dm0_2*gg2_2 + dm0_3*gg2_3 + dm0_4*gg2_4 + dm0_5*gg2_5 + dm0_6*gg2_6
    gd2_1 = dm0_1*gg2_0 + dm1_1*gg2_1 + dm1_2*gg2_2 + dm1_3*gg2_3 + dm1_4*gg2_4 + dm1_5*gg2_5 + dm1_6*gg2_6
    gd2_2 = dm0_2*gg2_0 + dm1_2*gg2_1 + dm2_2*gg2_2 + dm2_3*gg2_3 + dm2_4*gg2_4 + dm2_5*gg2_5 + dm2_6*gg2_6
    gd2_3 = dm0_3*gg2_0 + dm1_3*gg2_1 + dm2_3*gg2_2 + dm3_3*gg2_3 + dm3_4*gg2_4 + dm3_5*gg2_5 + dm3_6*gg2_6
    gd2_4 = dm0_4*gg2_0 + dm1_4*gg2_1 + dm2_4*gg2_2 + dm3_4*gg2_3 + dm4_4*gg2_4 + dm4_5*gg2_5 + dm4_6*gg2_6
    gd2_5 = dm0_5*gg2_0 + dm1_5*gg2_1 + dm2_5*gg2_2 + dm3_5*gg2_3 + dm4_5*gg2_4 + dm5_5*gg2_5 + dm5_6*gg2_6
    gd2_6 = dm0_6*gg2_0 + dm1_6*gg2_1 + dm2_6*gg2_2 + dm3_6*gg2_3 + dm4_6*gg2_4 + dm5_6*gg2_5 + dm6_6*gg2_6
    gd3_0 = dm0_0*gg3_0 + dm0_1*gg3_1 + dm0_2*gg3_2 + dm0_3*gg3_3 + dm0_4*gg3_4 + dm0_5*gg3_5 + dm0_6*gg3_6
    gd3_1 = dm0_1*gg3_0 + dm1_1*gg3_1 + dm1_2*gg3_2 + dm1_3*gg3_3 + dm1_4*gg3_4 + dm1_5*gg3_5 + dm1_6*gg3_6
    gd3_2 = dm0_2*gg3_0 + dm1_2*gg3_1 + dm2_2*gg3_2 + dm2_3*gg3_3 + dm2_4*gg3_4 + dm2_5*gg3_5 + dm2_6*gg3_6
    gd3_3 = dm0_3*gg3_0 + dm1_3*gg3_1 + dm2_3*gg3_2 + dm3_3*gg3_3 + dm3_4*gg3_4 + dm3_5*gg3_5 + dm3_6*gg3_6
    gd3_4 = dm0_4*gg3_0 + dm1_4*gg3_1 + dm2_4*gg3_2 + dm3_4*gg3_3 + dm4_4*gg3_4 + dm4_5*gg3_5 + dm4_6*gg3_6
    gd3_5 = dm0_5*gg3_0 + dm1_5*gg3_1 + dm2_5*gg3_2 + dm3_5*gg3_3 + dm4_5*gg3_4 + dm5_5*gg3_5 + dm5_6*gg3_6
    gd3_6 = dm0_6*gg3_0 + dm1_6*gg3_1 + dm2_6*gg3_2 + dm3_6*gg3_3 + dm4_6*gg3_4 + dm5_6*gg3_5 + dm6_6*gg3_6
    gd4_0 = dm0_0*gg4_0 + dm0_1*gg4_1 + dm0_2*gg4_2 + dm0_3*gg4_3 + dm0_4*gg4_4 + dm0_5*gg4_5 + dm0_6*gg4_6
    gd4_1 = dm0_1*gg4_0 + dm1_1*gg4_1 + dm1_2*gg4_2 + dm1_3*gg4_3 + dm1_4*gg4_4 + dm1_5*gg4_5 + dm1_6*gg4_6
    gd4_2 = dm0_2*gg4_0 + dm1_2*gg4_1 + dm2_2*gg4_2 + dm2_3*gg4_3 + dm2_4*gg4_4 + dm2_5*gg4_5 + dm2_6*gg4_6
    gd4_3 = dm0_3*gg4_0 + dm1_3*gg4_1 + dm2_3*gg4_2 + dm3_3*gg4_3 + dm3_4*gg4_4 + dm3_5*gg4_5 + dm3_6*gg4_6
    gd4_4 = dm0_4*gg4_0 + dm1_4*gg4_1 + dm2_4*gg4_2 + dm3_4*gg4_3 + dm4_4*gg4_4 + dm4_5*gg4_5 + dm4_6*gg4_6
    gd4_5 = dm0_5*gg4_0 + dm1_5*gg4_1 + dm2_5*gg4_2 + dm3_5*gg4_3 + dm4_5*gg4_4 + dm5_5*gg4_5 + dm5_6*gg4_6
    gd4_6 = dm0_6*gg4_0 + dm1_6*gg4_1 + dm2_6*gg4_2 + dm3_6*gg4_3 + dm4_6*gg4_4 + dm5_6*gg4_5 + dm6_6*gg4_6
    gd5_0 = dm0_0*gg5_0 + dm0_1*gg5_1 + dm0_2*gg5_2 + dm0_3*gg5_3 + dm0_4*gg5_4 + dm0_5*gg5_5 + dm0_6*gg5_6
    gd5_1 = dm0_1*gg5_0 + dm1_1*gg5_1 + dm1_2*gg5_2 + dm1_3*gg5_3 + dm1_4*gg5_4 + dm1_5*gg5_5 + dm1_6*gg5_6
    gd5_2 = dm0_2*gg5_0 + dm1_2*gg5_1 + dm2_2*gg5_2 + dm2_3*gg5_3 + dm2_4*gg5_4 + dm2_5*gg5_5 + dm2_6*gg5_6
    gd5_3 = dm0_3*gg5_0 + dm1_3*gg5_1 + dm2_3*gg5_2 + dm3_3*gg5_3 + dm3_4*gg5_4 + dm3_5*gg5_5 + dm3_6*gg5_6
    gd5_4 = dm0_4*gg5_0 + dm1_4*gg5_1 + dm2_4*gg5_2 + dm3_4*gg5_3 + dm4_4*gg5_4 + dm4_5*gg5_5 + dm4_6*gg5_6
    gd5_5 = dm0_5*gg5_0 + dm1_5*gg5_1 + dm2_5*gg5_2 + dm3_5*gg5_3 + dm4_5*gg5_4 + dm5_5*gg5_5 + dm5_6*gg5_6
    gd5_6 = dm0_6*gg5_0 + dm1_6*gg5_1 + dm2_6*gg5_2 + dm3_6*gg5_3 + dm4_6*gg5_4 + dm5_6*gg5_5 + dm6_6*gg5_6
    gd6_0 = dm0_0*gg6_0 + dm0_1*gg6_1 + dm0_2*gg6_2 + dm0_3*gg6_3 + dm0_4*gg6_4 + dm0_5*gg6_5 + dm0_6*gg6_6
    gd6_1 = dm0_1*gg6_0 + dm1_1*gg6_1 + dm1_2*gg6_2 + dm1_3*gg6_3 + dm1_4*gg6_4 + dm1_5*gg6_5 + dm1_6*gg6_6
    gd6_2 = dm0_2*gg6_0 + dm1_2*gg6_1 + dm2_2*gg6_2 + dm2_3*gg6_3 + dm2_4*gg6_4 + dm2_5*gg6_5 + dm2_6*gg6_6
    gd6_3 = dm0_3*gg6_0 + dm1_3*gg6_1 + dm2_3*gg6_2 + dm3_3*gg6_3 + dm3_4*gg6_4 + dm3_5*gg6_5 + dm3_6*gg6_6
    gd6_4 = dm0_4*gg6_0 + dm1_4*gg6_1 + dm2_4*gg6_2 + dm3_4*gg6_3 + dm4_4*gg6_4 + dm4_5*gg6_5 + dm4_6*gg6_6
    gd6_5 = dm0_5*gg6_0 + dm1_5*gg6_1 + dm2_5*gg6_2 + dm3_5*gg6_3 + dm4_5*gg6_4 + dm5_5*gg6_5 + dm5_6*gg6_6
    gd6_6 = dm0_6*gg6_0 + dm1_6*gg6_1 + dm2_6*gg6_2 + dm3_6*gg6_3 + dm4_6*gg6_4 + dm5_6*gg6_5 + dm6_6*gg6_6
    pt0_0 = gd0_0*gg0_0 + gd0_1*gg0_1 + gd0_2*gg0_2 + gd0_3*gg0_3 + gd0_4*gg0_4 + gd0_5*gg0_5 + gd0_6*gg0_6 + pf00
    pt0_1 = gd0_0*gg1_0 + gd0_1*gg1_1 + gd0_2*gg1_2 + gd0_3*gg1_3 + gd0_4*gg1_4 + gd0_5*gg1_5 + gd0_6*gg1_6 + pf01
    pt0_2 = gd0_0*gg2_0 + gd0_1*gg2_1 + gd0_2*gg2_2 + gd0_3*gg2_3 + gd0_4*gg2_4 + gd0_5*gg2_5 + gd0_6*gg2_6 + pf02
    pt0_3 = gd0_0*gg3_0 + gd0_1*gg3_1 + gd0_2*gg3_2 + gd0_3*gg3_3 + gd0_4*gg3_4 + gd0_5*gg3_5 + gd0_6*gg3_6 + pf03
    pt0_4 = gd0_0*gg4_0 + gd0_1*gg4_1 + gd0_2*gg4_2 + gd0_3*gg4_3 + gd0_4*gg4_4 + gd0_5*gg4_5 + gd0_6*gg4_6 + pf04
    pt0_5 = gd0_0*gg5_0 + gd0_1*gg5_1 + gd0_2*gg5_2 + gd0_3*gg5_3 + gd0_4*gg5_4 + gd0_5*gg5_5 + gd0_6*gg5_6 + pf05
    pt0_6 = gd0_0*gg6_0 + gd0_1*gg6_1 + gd0_2*gg6_2 + gd0_3*gg6_3 + gd0_4*gg6_4 + gd0_5*gg6_5 + gd0_6*gg6_6 + pf06
    pt1_1 = gd1_0*gg1_0 + gd1_1*gg1_1 + gd1_2*gg1_2 + gd1_3*gg1_3 + gd1_4*gg1_4 + gd1_5*gg1_5 + gd1_6*gg1_6 + pf11
    pt1_2 = gd1_0*gg2_0 + gd1_1*gg2_1 + gd1_2*gg2_2 + gd1_3*gg2_3 + gd1_4*gg2_4 + gd1_5*gg2_5 + gd1_6*gg2_6 + pf12
    pt1_3 = gd1_0*gg3_0 + gd1_1*gg3_1 + gd1_2*gg3_2 + gd1_3*gg3_3 + gd1_4*gg3_4 + gd1_5*gg3_5 + gd1_6*gg3_6 + pf13
    pt1_4 = gd1_0*gg4_0 + gd1_1*gg4_1 + gd1_2*gg4_2 + gd1_3*gg4_3 + gd1_4*gg4_4 + gd1_5*gg4_5 + gd1_6*gg4_6 + pf14
    pt1_5 = gd1_0*gg5_0 + gd1_1*gg5_1 + gd1_2*gg5_2 + gd1_3*gg5_3 + gd1_4*gg5_4 + gd1_5*gg5_5 + gd1_6*gg5_6 + pf15
    pt1_6 = gd1_0*gg6_0 + gd1_1*gg6_1 + gd1_2*gg6_2 + gd1_3*gg6_3 + gd1_4*gg6_4 + gd1_5*gg6_5 + gd1_6*gg6_6 + pf16
    pt2_2 = gd2_0*gg2_0 + gd2_1*gg2_1 + gd2_2*gg2_2 + gd2_3*gg2_3 + gd2_4*gg2_4 + gd2_5*gg2_5 + gd2_6*gg2_6 + pf22
    pt2_3 = gd2_0*gg3_0 + gd2_1*gg3_1 + gd2_2*gg3_2 + gd2_3*gg3_3 + gd2_4*gg3_4 + gd2_5*gg3_5 + gd2_6*gg3_6 + pf23
    pt2_4 = gd2_0*gg4_0 + gd2_1*gg4_1 + gd2_2*gg4_2 + gd2_3*gg4_3 + gd2_4*gg4_4 + gd2_5*gg4_5 + gd2_6*gg4_6 + pf24
    pt2_5 = gd2_0*gg5_0 + gd2_1*gg5_1 + gd2_2*gg5_2 + gd2_3*gg5_3 + gd2_4*gg5_4 + gd2_5*gg5_5 + gd2_6*gg5_6 + pf25
    pt2_6 = gd2_0*gg6_0 + gd2_1*gg6_1 + gd2_2*gg6_2 + gd2_3*gg6_3 + gd2_4*gg6_4 + gd2_5*gg6_5 + gd2_6*gg6_6 + pf26
    pt3_3 = gd3_0*gg3_0 + gd3_1*gg3_1 + gd3_2*gg3_2 + gd3_3*gg3_3 + gd3_4*gg3_4 + gd3_5*gg3_5 + gd3_6*gg3_6 + pf33
    pt3_4 = gd3_0*gg4_0 + gd3_1*gg4_1 + gd3_2*gg4_2 + gd3_3*gg4_3 + gd3_4*gg4_4 + gd3_5*gg4_5 + gd3_6*gg4_6 + pf34
    pt3_5 = gd3_0*gg5_0 + gd3_1*gg5_1 + gd3_2*gg5_2 + gd3_3*gg5_3 + gd3_4*gg5_4 + gd3_5*gg5_5 + gd3_6*gg5_6 + pf35
    pt3_6 = gd3_0*gg6_0 + gd3_1*gg6_1 + gd3_2*gg6_2 + gd3_3*gg6_3 + gd3_4*gg6_4 + gd3_5*gg6_5 + gd3_6*gg6_6 + pf36
    pt4_4 = gd4_0*gg4_0 + gd4_1*gg4_1 + gd4_2*gg4_2 + gd4_3*gg4_3 + gd4_4*gg4_4 + gd4_5*gg4_5 + gd4_6*gg4_6 + pf44
    pt4_5 = gd4_0*gg5_0 + gd4_1*gg5_1 + gd4_2*gg5_2 + gd4_3*gg5_3 + gd4_4*gg5_4 + gd4_5*gg5_5 + gd4_6*gg5_6 + pf45
    pt4_6 = gd4_0*gg6_0 + gd4_1*gg6_1 + gd4_2*gg6_2 + gd4_3*gg6_3 + gd4_4*gg6_4 + gd4_5*gg6_5 + gd4_6*gg6_6 + pf46
    pt5_5 = gd5_0*gg5_0 + gd5_1*gg5_1 + gd5_2*gg5_2 + gd5_3*gg5_3 + gd5_4*gg5_4 + gd5_5*gg5_5 + gd5_6*gg5_6 + pf55
    pt5_6 = gd5_0*gg6_0 + gd5_1*gg6_1 + gd5_2*gg6_2 + gd5_3*gg6_3 + gd5_4*gg6_4 + gd5_5*gg6_5 + gd5_6*gg6_6 + pf56
    pt6_6 = gd6_0*gg6_0 + gd6_1*gg6_1 + gd6_2*gg6_2 + gd6_3*gg6_3 + gd6_4*gg6_4 + gd6_5*gg6_5 + gd6_6*gg6_6 + pf66
    p_sm[k, 0] = pt0_0
    p_sm[k, 1] = pt0_1
    p_sm[k, 2] = pt0_2
    p_sm[k, 3] = pt0_3
    p_sm[k, 4] = pt0_4
    p_sm[k, 5] = pt0_5
    p_sm[k, 6] = pt0_6
    p_sm[k, 7] = pt1_1
    p_sm[k, 8] = pt1_2
    p_sm[k, 9] = pt1_3
    p_sm[k, 10] = pt1_4
    p_sm[k, 11] = pt1_5
    p_sm[k, 12] = pt1_6
    p_sm[k, 13] = pt2_2
    p_sm[k, 14] = pt2_3
    p_sm[k, 15] = pt2_4
    p_sm[k, 16] = pt2_5
    p_sm[k, 17] = pt2_6
    p_sm[k, 18] = pt3_3
    p_sm[k, 19] = pt3_4
    p_sm[k, 20] = pt3_5
    p_sm[k, 21] = pt3_6
    p_sm[k, 22] = pt4_4
    p_sm[k, 23] = pt4_5
    p_sm[k, 24] = pt4_6
    p_sm[k, 25] = pt5_5
    p_sm[k, 26] = pt5_6
    p_sm[k, 27] = pt6_6
    s_sm[k, 0] = de0_0 + x
    s_sm[k, 1] = de1_0 + y
    s_sm[k, 2] = de2_0 + z
    s_sm[k, 3] = de3_0 + psi
    s_sm[k, 4] = de4_0 + v
    s_sm[k, 5] = de5_0 + omega
    s_sm[k, 6] = de6_0 + v_up


@nb.njit(inline="always", fastmath={"contract"}, error_model="numpy")
def lane_smooth(W, j):
    """smooth_step on lane j of the work array W (rows: derive/codegen/smooth_step.py), without branches (SIMD).
    """
    x = W[0 + j]
    y = W[64 + j]
    z = W[128 + j]
    psi = W[192 + j]
    v = W[256 + j]
    omega = W[320 + j]
    v_up = W[384 + j]
    pf00 = W[448 + j]
    pf01 = W[512 + j]
    pf02 = W[576 + j]
    pf03 = W[640 + j]
    pf04 = W[704 + j]
    pf05 = W[768 + j]
    pf06 = W[832 + j]
    pf11 = W[896 + j]
    pf12 = W[960 + j]
    pf13 = W[1024 + j]
    pf14 = W[1088 + j]
    pf15 = W[1152 + j]
    pf16 = W[1216 + j]
    pf22 = W[1280 + j]
    pf23 = W[1344 + j]
    pf24 = W[1408 + j]
    pf25 = W[1472 + j]
    pf26 = W[1536 + j]
    pf33 = W[1600 + j]
    pf34 = W[1664 + j]
    pf35 = W[1728 + j]
    pf36 = W[1792 + j]
    pf44 = W[1856 + j]
    pf45 = W[1920 + j]
    pf46 = W[1984 + j]
    pf55 = W[2048 + j]
    pf56 = W[2112 + j]
    pf66 = W[2176 + j]
    q_x = W[2240 + j]
    q_y = W[2304 + j]
    q_z = W[2368 + j]
    q_psi = W[2432 + j]
    q_v = W[2496 + j]
    q_omega = W[2560 + j]
    q_v_up = W[2624 + j]
    pq00 = W[2688 + j]
    pq01 = W[2752 + j]
    pq02 = W[2816 + j]
    pq03 = W[2880 + j]
    pq04 = W[2944 + j]
    pq05 = W[3008 + j]
    pq06 = W[3072 + j]
    pq11 = W[3136 + j]
    pq12 = W[3200 + j]
    pq13 = W[3264 + j]
    pq14 = W[3328 + j]
    pq15 = W[3392 + j]
    pq16 = W[3456 + j]
    pq22 = W[3520 + j]
    pq23 = W[3584 + j]
    pq24 = W[3648 + j]
    pq25 = W[3712 + j]
    pq26 = W[3776 + j]
    pq33 = W[3840 + j]
    pq34 = W[3904 + j]
    pq35 = W[3968 + j]
    pq36 = W[4032 + j]
    pq44 = W[4096 + j]
    pq45 = W[4160 + j]
    pq46 = W[4224 + j]
    pq55 = W[4288 + j]
    pq56 = W[4352 + j]
    pq66 = W[4416 + j]
    t_x = W[4480 + j]
    t_y = W[4544 + j]
    t_z = W[4608 + j]
    t_psi = W[4672 + j]
    t_v = W[4736 + j]
    t_omega = W[4800 + j]
    t_v_up = W[4864 + j]
    ps00 = W[4928 + j]
    ps01 = W[4992 + j]
    ps02 = W[5056 + j]
    ps03 = W[5120 + j]
    ps04 = W[5184 + j]
    ps05 = W[5248 + j]
    ps06 = W[5312 + j]
    ps11 = W[5376 + j]
    ps12 = W[5440 + j]
    ps13 = W[5504 + j]
    ps14 = W[5568 + j]
    ps15 = W[5632 + j]
    ps16 = W[5696 + j]
    ps22 = W[5760 + j]
    ps23 = W[5824 + j]
    ps24 = W[5888 + j]
    ps25 = W[5952 + j]
    ps26 = W[6016 + j]
    ps33 = W[6080 + j]
    ps34 = W[6144 + j]
    ps35 = W[6208 + j]
    ps36 = W[6272 + j]
    ps44 = W[6336 + j]
    ps45 = W[6400 + j]
    ps46 = W[6464 + j]
    ps55 = W[6528 + j]
    ps56 = W[6592 + j]
    ps66 = W[6656 + j]
    dt = W[8960 + j]
    _a0 = dt*omega/2.0
    _sin__a0 = sin_v(_a0)
    _cos__a0 = cos_v(_a0)
    _dsinc__a0 = dsinc_v(_a0, _sin__a0, _cos__a0)
    _sinc__a0 = sinc_v(_a0, _sin__a0, _cos__a0)
    _a1 = dt*omega/2.0 + psi
    _sin__a1 = sin_v(_a1)
    _cos__a1 = cos_v(_a1)
    _t0 = _sin__a1*_sinc__a0
    _t1 = _t0*dt
    _t2 = _cos__a1*_sinc__a0
    _t3 = _t2*dt
    _t4 = (dt*dt)*v/2.0
    _t5 = dt*pf56
    cc0_3 = -(_t1*v)
    cc0_4 = _t3
    cc0_5 = -(_t4*(_cos__a1*_dsinc__a0 + _t0))
    cc1_3 = _t3*v
    cc1_4 = _t1
    cc1_5 = _t4*(-(_dsinc__a0*_sin__a1) + _t2)
    cf0_2 = dt*pf06 + pf02
    cf0_3 = dt*pf05 + pf03
    cf1_2 = dt*pf16 + pf12
    cf1_3 = dt*pf15 + pf13
    cf2_2 = dt*pf26 + pf22
    cf2_3 = dt*pf25 + pf23
    cf3_2 = dt*pf36 + pf23
    cf3_3 = dt*pf35 + pf33
    cf4_2 = dt*pf46 + pf24
    cf4_3 = dt*pf45 + pf34
    cf5_2 = _t5 + pf25
    cf5_3 = dt*pf55 + pf35
    cf6_2 = dt*pf66 + pf26
    cf6_3 = _t5 + pf36
    dd0_0 = -q_x + t_x
    dd0_1 = -q_y + t_y
    dd0_2 = -q_z + t_z
    dd0_3 = wrap_v(-q_psi + t_psi)
    dd0_4 = -q_v + t_v
    dd0_5 = -q_omega + t_omega
    dd0_6 = -q_v_up + t_v_up
    dm0_0 = -pq00 + ps00
    dm0_1 = -pq01 + ps01
    dm0_2 = -pq02 + ps02
    dm0_3 = -pq03 + ps03
    dm0_4 = -pq04 + ps04
    dm0_5 = -pq05 + ps05
    dm0_6 = -pq06 + ps06
    dm1_1 = -pq11 + ps11
    dm1_2 = -pq12 + ps12
    dm1_3 = -pq13 + ps13
    dm1_4 = -pq14 + ps14
    dm1_5 = -pq15 + ps15
    dm1_6 = -pq16 + ps16
    dm2_2 = -pq22 + ps22
    dm2_3 = -pq23 + ps23
    dm2_4 = -pq24 + ps24
    dm2_5 = -pq25 + ps25
    dm2_6 = -pq26 + ps26
    dm3_3 = -pq33 + ps33
    dm3_4 = -pq34 + ps34
    dm3_5 = -pq35 + ps35
    dm3_6 = -pq36 + ps36
    dm4_4 = -pq44 + ps44
    dm4_5 = -pq45 + ps45
    dm4_6 = -pq46 + ps46
    dm5_5 = -pq55 + ps55
    dm5_6 = -pq56 + ps56
    dm6_6 = -pq66 + ps66
    lr0 = 1.0/max(1e-300, pq00)
    cf0_0 = cc0_3*pf03 + cc0_4*pf04 + cc0_5*pf05 + pf00
    cf0_1 = cc1_3*pf03 + cc1_4*pf04 + cc1_5*pf05 + pf01
    cf1_0 = cc0_3*pf13 + cc0_4*pf14 + cc0_5*pf15 + pf01
    cf1_1 = cc1_3*pf13 + cc1_4*pf14 + cc1_5*pf15 + pf11
    cf2_0 = cc0_3*pf23 + cc0_4*pf24 + cc0_5*pf25 + pf02
    cf2_1 = cc1_3*pf23 + cc1_4*pf24 + cc1_5*pf25 + pf12
    cf3_0 = cc0_3*pf33 + cc0_4*pf34 + cc0_5*pf35 + pf03
    cf3_1 = cc1_3*pf33 + cc1_4*pf34 + cc1_5*pf35 + pf13
    cf4_0 = cc0_3*pf34 + cc0_4*pf44 + cc0_5*pf45 + pf04
    cf4_1 = cc1_3*pf34 + cc1_4*pf44 + cc1_5*pf45 + pf14
    cf5_0 = cc0_3*pf35 + cc0_4*pf45 + cc0_5*pf55 + pf05
    cf5_1 = cc1_3*pf35 + cc1_4*pf45 + cc1_5*pf55 + pf15
    cf6_0 = cc0_3*pf36 + cc0_4*pf46 + cc0_5*pf56 + pf06
    cf6_1 = cc1_3*pf36 + cc1_4*pf46 + cc1_5*pf56 + pf16
    ll1_0 = lr0*pq01
    ll2_0 = lr0*pq02
    ll3_0 = lr0*pq03
    ll4_0 = lr0*pq04
    ll5_0 = lr0*pq05
    ll6_0 = lr0*pq06
    lw1_0 = ll1_0*pq00
    lw2_0 = ll2_0*pq00
    lw3_0 = ll3_0*pq00
    lw4_0 = ll4_0*pq00
    lw5_0 = ll5_0*pq00
    lw6_0 = ll6_0*pq00
    ly0_1 = -(cf0_0*ll1_0) + cf0_1
    ly1_1 = -(cf1_0*ll1_0) + cf1_1
    ly2_1 = -(cf2_0*ll1_0) + cf2_1
    ly3_1 = -(cf3_0*ll1_0) + cf3_1
    ly4_1 = -(cf4_0*ll1_0) + cf4_1
    ly5_1 = -(cf5_0*ll1_0) + cf5_1
    ly6_1 = -(cf6_0*ll1_0) + cf6_1
    ld1 = -(ll1_0*lw1_0) + pq11
    lr1 = 1.0/max(1e-300, ld1)
    ll2_1 = lr1*(-(ll2_0*lw1_0) + pq12)
    ll3_1 = lr1*(-(ll3_0*lw1_0) + pq13)
    ll4_1 = lr1*(-(ll4_0*lw1_0) + pq14)
    ll5_1 = lr1*(-(ll5_0*lw1_0) + pq15)
    ll6_1 = lr1*(-(ll6_0*lw1_0) + pq16)
    lw2_1 = ld1*ll2_1
    lw3_1 = ld1*ll3_1
    lw4_1 = ld1*ll4_1
    lw5_1 = ld1*ll5_1
    lw6_1 = ld1*ll6_1
    ly0_2 = -(cf0_0*ll2_0) + cf0_2 - ll2_1*ly0_1
    ly1_2 = -(cf1_0*ll2_0) + cf1_2 - ll2_1*ly1_1
    ly2_2 = -(cf2_0*ll2_0) + cf2_2 - ll2_1*ly2_1
    ly3_2 = -(cf3_0*ll2_0) + cf3_2 - ll2_1*ly3_1
    ly4_2 = -(cf4_0*ll2_0) + cf4_2 - ll2_1*ly4_1
    ly5_2 = -(cf5_0*ll2_0) + cf5_2 - ll2_1*ly5_1
    ly6_2 = -(cf6_0*ll2_0) + cf6_2 - ll2_1*ly6_1
    ld2 = -(ll2_0*lw2_0) - ll2_1*lw2_1 + pq22
    lr2 = 1.0/max(1e-300, ld2)
    ll3_2 = lr2*(-(ll3_0*lw2_0) - ll3_1*lw2_1 + pq23)
    ll4_2 = lr2*(-(ll4_0*lw2_0) - ll4_1*lw2_1 + pq24)
    ll5_2 = lr2*(-(ll5_0*lw2_0) - ll5_1*lw2_1 + pq25)
    ll6_2 = lr2*(-(ll6_0*lw2_0) - ll6_1*lw2_1 + pq26)
    lw3_2 = ld2*ll3_2
    lw4_2 = ld2*ll4_2
    lw5_2 = ld2*ll5_2
    lw6_2 = ld2*ll6_2
    ly0_3 = -(cf0_0*ll3_0) + cf0_3 - ll3_1*ly0_1 - ll3_2*ly0_2
    ly1_3 = -(cf1_0*ll3_0) + cf1_3 - ll3_1*ly1_1 - ll3_2*ly1_2
    ly2_3 = -(cf2_0*ll3_0) + cf2_3 - ll3_1*ly2_1 - ll3_2*ly2_2
    ly3_3 = -(cf3_0*ll3_0) + cf3_3 - ll3_1*ly3_1 - ll3_2*ly3_2
    ly4_3 = -(cf4_0*ll3_0) + cf4_3 - ll3_1*ly4_1 - ll3_2*ly4_2
    ly5_3 = -(cf5_0*ll3_0) + cf5_3 - ll3_1*ly5_1 - ll3_2*ly5_2
    ly6_3 = -(cf6_0*ll3_0) + cf6_3 - ll3_1*ly6_1 - ll3_2*ly6_2
    ld3 = -(ll3_0*lw3_0) - ll3_1*lw3_1 - ll3_2*lw3_2 + pq33
    lr3 = 1.0/max(1e-300, ld3)
    ll4_3 = lr3*(-(ll4_0*lw3_0) - ll4_1*lw3_1 - ll4_2*lw3_2 + pq34)
    ll5_3 = lr3*(-(ll5_0*lw3_0) - ll5_1*lw3_1 - ll5_2*lw3_2 + pq35)
    ll6_3 = lr3*(-(ll6_0*lw3_0) - ll6_1*lw3_1 - ll6_2*lw3_2 + pq36)
    lw4_3 = ld3*ll4_3
    lw5_3 = ld3*ll5_3
    lw6_3 = ld3*ll6_3
    ly0_4 = -(cf0_0*ll4_0) - ll4_1*ly0_1 - ll4_2*ly0_2 - ll4_3*ly0_3 + pf04
    ly1_4 = -(cf1_0*ll4_0) - ll4_1*ly1_1 - ll4_2*ly1_2 - ll4_3*ly1_3 + pf14
    ly2_4 = -(cf2_0*ll4_0) - ll4_1*ly2_1 - ll4_2*ly2_2 - ll4_3*ly2_3 + pf24
    ly3_4 = -(cf3_0*ll4_0) - ll4_1*ly3_1 - ll4_2*ly3_2 - ll4_3*ly3_3 + pf34
    ly4_4 = -(cf4_0*ll4_0) - ll4_1*ly4_1 - ll4_2*ly4_2 - ll4_3*ly4_3 + pf44
    ly5_4 = -(cf5_0*ll4_0) - ll4_1*ly5_1 - ll4_2*ly5_2 - ll4_3*ly5_3 + pf45
    ly6_4 = -(cf6_0*ll4_0) - ll4_1*ly6_1 - ll4_2*ly6_2 - ll4_3*ly6_3 + pf46
    ld4 = -(ll4_0*lw4_0) - ll4_1*lw4_1 - ll4_2*lw4_2 - ll4_3*lw4_3 + pq44
    lr4 = 1.0/max(1e-300, ld4)
    ll5_4 = lr4*(-(ll5_0*lw4_0) - ll5_1*lw4_1 - ll5_2*lw4_2 - ll5_3*lw4_3 + pq45)
    ll6_4 = lr4*(-(ll6_0*lw4_0) - ll6_1*lw4_1 - ll6_2*lw4_2 - ll6_3*lw4_3 + pq46)
    lw5_4 = ld4*ll5_4
    lw6_4 = ld4*ll6_4
    ly0_5 = -(cf0_0*ll5_0) - ll5_1*ly0_1 - ll5_2*ly0_2 - ll5_3*ly0_3 - ll5_4*ly0_4 + pf05
    ly1_5 = -(cf1_0*ll5_0) - ll5_1*ly1_1 - ll5_2*ly1_2 - ll5_3*ly1_3 - ll5_4*ly1_4 + pf15
    ly2_5 = -(cf2_0*ll5_0) - ll5_1*ly2_1 - ll5_2*ly2_2 - ll5_3*ly2_3 - ll5_4*ly2_4 + pf25
    ly3_5 = -(cf3_0*ll5_0) - ll5_1*ly3_1 - ll5_2*ly3_2 - ll5_3*ly3_3 - ll5_4*ly3_4 + pf35
    ly4_5 = -(cf4_0*ll5_0) - ll5_1*ly4_1 - ll5_2*ly4_2 - ll5_3*ly4_3 - ll5_4*ly4_4 + pf45
    ly5_5 = -(cf5_0*ll5_0) - ll5_1*ly5_1 - ll5_2*ly5_2 - ll5_3*ly5_3 - ll5_4*ly5_4 + pf55
    ly6_5 = -(cf6_0*ll5_0) - ll5_1*ly6_1 - ll5_2*ly6_2 - ll5_3*ly6_3 - ll5_4*ly6_4 + pf56
    ld5 = -(ll5_0*lw5_0) - ll5_1*lw5_1 - ll5_2*lw5_2 - ll5_3*lw5_3 - ll5_4*lw5_4 + pq55
    lr5 = 1.0/max(1e-300, ld5)
    ll6_5 = lr5*(-(ll6_0*lw5_0) - ll6_1*lw5_1 - ll6_2*lw5_2 - ll6_3*lw5_3 - ll6_4*lw5_4 + pq56)
    lw6_5 = ld5*ll6_5
    ly0_6 = -(cf0_0*ll6_0) - ll6_1*ly0_1 - ll6_2*ly0_2 - ll6_3*ly0_3 - ll6_4*ly0_4 - ll6_5*ly0_5 + pf06
    ly1_6 = -(cf1_0*ll6_0) - ll6_1*ly1_1 - ll6_2*ly1_2 - ll6_3*ly1_3 - ll6_4*ly1_4 - ll6_5*ly1_5 + pf16
    ly2_6 = -(cf2_0*ll6_0) - ll6_1*ly2_1 - ll6_2*ly2_2 - ll6_3*ly2_3 - ll6_4*ly2_4 - ll6_5*ly2_5 + pf26
    ly3_6 = -(cf3_0*ll6_0) - ll6_1*ly3_1 - ll6_2*ly3_2 - ll6_3*ly3_3 - ll6_4*ly3_4 - ll6_5*ly3_5 + pf36
    ly4_6 = -(cf4_0*ll6_0) - ll6_1*ly4_1 - ll6_2*ly4_2 - ll6_3*ly4_3 - ll6_4*ly4_4 - ll6_5*ly4_5 + pf46
    ly5_6 = -(cf5_0*ll6_0) - ll6_1*ly5_1 - ll6_2*ly5_2 - ll6_3*ly5_3 - ll6_4*ly5_4 - ll6_5*ly5_5 + pf56
    ly6_6 = -(cf6_0*ll6_0) - ll6_1*ly6_1 - ll6_2*ly6_2 - ll6_3*ly6_3 - ll6_4*ly6_4 - ll6_5*ly6_5 + pf66
    ld6 = -(ll6_0*lw6_0) - ll6_1*lw6_1 - ll6_2*lw6_2 - ll6_3*lw6_3 - ll6_4*lw6_4 - ll6_5*lw6_5 + pq66
    lr6 = 1.0/max(1e-300, ld6)
    gg0_6 = lr6*ly0_6
    gg1_6 = lr6*ly1_6
    gg2_6 = lr6*ly2_6
    gg3_6 = lr6*ly3_6
    gg4_6 = lr6*ly4_6
    gg5_6 = lr6*ly5_6
    gg6_6 = lr6*ly6_6
    gg0_5 = -(gg0_6*ll6_5) + lr5*ly0_5
    gg1_5 = -(gg1_6*ll6_5) + lr5*ly1_5
    gg2_5 = -(gg2_6*ll6_5) + lr5*ly2_5
    gg3_5 = -(gg3_6*ll6_5) + lr5*ly3_5
    gg4_5 = -(gg4_6*ll6_5) + lr5*ly4_5
    gg5_5 = -(gg5_6*ll6_5) + lr5*ly5_5
    gg6_5 = -(gg6_6*ll6_5) + lr5*ly6_5
    gg0_4 = -(gg0_5*ll5_4) - gg0_6*ll6_4 + lr4*ly0_4
    gg1_4 = -(gg1_5*ll5_4) - gg1_6*ll6_4 + lr4*ly1_4
    gg2_4 = -(gg2_5*ll5_4) - gg2_6*ll6_4 + lr4*ly2_4
    gg3_4 = -(gg3_5*ll5_4) - gg3_6*ll6_4 + lr4*ly3_4
    gg4_4 = -(gg4_5*ll5_4) - gg4_6*ll6_4 + lr4*ly4_4
    gg5_4 = -(gg5_5*ll5_4) - gg5_6*ll6_4 + lr4*ly5_4
    gg6_4 = -(gg6_5*ll5_4) - gg6_6*ll6_4 + lr4*ly6_4
    gg0_3 = -(gg0_4*ll4_3) - gg0_5*ll5_3 - gg0_6*ll6_3 + lr3*ly0_3
    gg1_3 = -(gg1_4*ll4_3) - gg1_5*ll5_3 - gg1_6*ll6_3 + lr3*ly1_3
    gg2_3 = -(gg2_4*ll4_3) - gg2_5*ll5_3 - gg2_6*ll6_3 + lr3*ly2_3
    gg3_3 = -(gg3_4*ll4_3) - gg3_5*ll5_3 - gg3_6*ll6_3 + lr3*ly3_3
    gg4_3 = -(gg4_4*ll4_3) - gg4_5*ll5_3 - gg4_6*ll6_3 + lr3*ly4_3
    gg5_3 = -(gg5_4*ll4_3) - gg5_5*ll5_3 - gg5_6*ll6_3 + lr3*ly5_3
    gg6_3 = -(gg6_4*ll4_3) - gg6_5*ll5_3 - gg6_6*ll6_3 + lr3*ly6_3
    gg0_2 = -(gg0_3*ll3_2) - gg0_4*ll4_2 - gg0_5*ll5_2 - gg0_6*ll6_2 + lr2*ly0_2
    gg1_2 = -(gg1_3*ll3_2) - gg1_4*ll4_2 - gg1_5*ll5_2 - gg1_6*ll6_2 + lr2*ly1_2
    gg2_2 = -(gg2_3*ll3_2) - gg2_4*ll4_2 - gg2_5*ll5_2 - gg2_6*ll6_2 + lr2*ly2_2
    gg3_2 = -(gg3_3*ll3_2) - gg3_4*ll4_2 - gg3_5*ll5_2 - gg3_6*ll6_2 + lr2*ly3_2
    gg4_2 = -(gg4_3*ll3_2) - gg4_4*ll4_2 - gg4_5*ll5_2 - gg4_6*ll6_2 + lr2*ly4_2
    gg5_2 = -(gg5_3*ll3_2) - gg5_4*ll4_2 - gg5_5*ll5_2 - gg5_6*ll6_2 + lr2*ly5_2
    gg6_2 = -(gg6_3*ll3_2) - gg6_4*ll4_2 - gg6_5*ll5_2 - gg6_6*ll6_2 + lr2*ly6_2
    gg0_1 = -(gg0_2*ll2_1) - gg0_3*ll3_1 - gg0_4*ll4_1 - gg0_5*ll5_1 - gg0_6*ll6_1 + lr1*ly0_1
    gg1_1 = -(gg1_2*ll2_1) - gg1_3*ll3_1 - gg1_4*ll4_1 - gg1_5*ll5_1 - gg1_6*ll6_1 + lr1*ly1_1
    gg2_1 = -(gg2_2*ll2_1) - gg2_3*ll3_1 - gg2_4*ll4_1 - gg2_5*ll5_1 - gg2_6*ll6_1 + lr1*ly2_1
    gg3_1 = -(gg3_2*ll2_1) - gg3_3*ll3_1 - gg3_4*ll4_1 - gg3_5*ll5_1 - gg3_6*ll6_1 + lr1*ly3_1
    gg4_1 = -(gg4_2*ll2_1) - gg4_3*ll3_1 - gg4_4*ll4_1 - gg4_5*ll5_1 - gg4_6*ll6_1 + lr1*ly4_1
    gg5_1 = -(gg5_2*ll2_1) - gg5_3*ll3_1 - gg5_4*ll4_1 - gg5_5*ll5_1 - gg5_6*ll6_1 + lr1*ly5_1
    gg6_1 = -(gg6_2*ll2_1) - gg6_3*ll3_1 - gg6_4*ll4_1 - gg6_5*ll5_1 - gg6_6*ll6_1 + lr1*ly6_1
    gg0_0 = cf0_0*lr0 - gg0_1*ll1_0 - gg0_2*ll2_0 - gg0_3*ll3_0 - gg0_4*ll4_0 - gg0_5*ll5_0 - gg0_6*ll6_0
    gg1_0 = cf1_0*lr0 - gg1_1*ll1_0 - gg1_2*ll2_0 - gg1_3*ll3_0 - gg1_4*ll4_0 - gg1_5*ll5_0 - gg1_6*ll6_0
    gg2_0 = cf2_0*lr0 - gg2_1*ll1_0 - gg2_2*ll2_0 - gg2_3*ll3_0 - gg2_4*ll4_0 - gg2_5*ll5_0 - gg2_6*ll6_0
    gg3_0 = cf3_0*lr0 - gg3_1*ll1_0 - gg3_2*ll2_0 - gg3_3*ll3_0 - gg3_4*ll4_0 - gg3_5*ll5_0 - gg3_6*ll6_0
    gg4_0 = cf4_0*lr0 - gg4_1*ll1_0 - gg4_2*ll2_0 - gg4_3*ll3_0 - gg4_4*ll4_0 - gg4_5*ll5_0 - gg4_6*ll6_0
    gg5_0 = cf5_0*lr0 - gg5_1*ll1_0 - gg5_2*ll2_0 - gg5_3*ll3_0 - gg5_4*ll4_0 - gg5_5*ll5_0 - gg5_6*ll6_0
    gg6_0 = cf6_0*lr0 - gg6_1*ll1_0 - gg6_2*ll2_0 - gg6_3*ll3_0 - gg6_4*ll4_0 - gg6_5*ll5_0 - gg6_6*ll6_0
    de0_0 = dd0_0*gg0_0 + dd0_1*gg0_1 + dd0_2*gg0_2 + dd0_3*gg0_3 + dd0_4*gg0_4 + dd0_5*gg0_5 + dd0_6*gg0_6
    de1_0 = dd0_0*gg1_0 + dd0_1*gg1_1 + dd0_2*gg1_2 + dd0_3*gg1_3 + dd0_4*gg1_4 + dd0_5*gg1_5 + dd0_6*gg1_6
    de2_0 = dd0_0*gg2_0 + dd0_1*gg2_1 + dd0_2*gg2_2 + dd0_3*gg2_3 + dd0_4*gg2_4 + dd0_5*gg2_5 + dd0_6*gg2_6
    de3_0 = dd0_0*gg3_0 + dd0_1*gg3_1 + dd0_2*gg3_2 + dd0_3*gg3_3 + dd0_4*gg3_4 + dd0_5*gg3_5 + dd0_6*gg3_6
    de4_0 = dd0_0*gg4_0 + dd0_1*gg4_1 + dd0_2*gg4_2 + dd0_3*gg4_3 + dd0_4*gg4_4 + dd0_5*gg4_5 + dd0_6*gg4_6
    de5_0 = dd0_0*gg5_0 + dd0_1*gg5_1 + dd0_2*gg5_2 + dd0_3*gg5_3 + dd0_4*gg5_4 + dd0_5*gg5_5 + dd0_6*gg5_6
    de6_0 = dd0_0*gg6_0 + dd0_1*gg6_1 + dd0_2*gg6_2 + dd0_3*gg6_3 + dd0_4*gg6_4 + dd0_5*gg6_5 + dd0_6*gg6_6
    gd0_0 = dm0_0*gg0_0 + dm0_1*gg0_1 + dm0_2*gg0_2 + dm0_3*gg0_3 + dm0_4*gg0_4 + dm0_5*gg0_5 + dm0_6*gg0_6
    gd0_1 = dm0_1*gg0_0 + dm1_1*gg0_1 + dm1_2*gg0_2 + dm1_3*gg0_3 + dm1_4*gg0_4 + dm1_5*gg0_5 + dm1_6*gg0_6
    gd0_2 = dm0_2*gg0_0 + dm1_2*gg0_1 + dm2_2*gg0_2 + dm2_3*gg0_3 + dm2_4*gg0_4 + dm2_5*gg0_5 + dm2_6*gg0_6
    gd0_3 = dm0_3*gg0_0 + dm1_3*gg0_1 + dm2_3*gg0_2 + dm3_3*gg0_3 + dm3_4*gg0_4 + dm3_5*gg0_5 + dm3_6*gg0_6
    gd0_4 = dm0_4*gg0_0 + dm1_4*gg0_1 + dm2_4*gg0_2 + dm3_4*gg0_3 + dm4_4*gg0_4 + dm4_5*gg0_5 + dm4_6*gg0_6
    gd0_5 = dm0_5*gg0_0 + dm1_5*gg0_1 + dm2_5*gg0_2 + dm3_5*gg0_3 + dm4_5*gg0_4 + dm5_5*gg0_5 + dm5_6*gg0_6
    gd0_6 = dm0_6*gg0_0 + dm1_6*gg0_1 + dm2_6*gg0_2 + dm3_6*gg0_3 + dm4_6*gg0_4 + dm5_6*gg0_5 + dm6_6*gg0_6
    gd1_0 = dm0_0*gg1_0 + dm0_1*gg1_1 + dm0_2*gg1_2 + dm0_3*gg1_3 + dm0_4*gg1_4 + dm0_5*gg1_5 + dm0_6*gg1_6
    gd1_1 = dm0_1*gg1_0 + dm1_1*gg1_1 + dm1_2*gg1_2 + dm1_3*gg1_3 + dm1_4*gg1_4 + dm1_5*gg1_5 + dm1_6*gg1_6
    gd1_2 = dm0_2*gg1_0 + dm1_2*gg1_1 + dm2_2*gg1_2 + dm2_3*gg1_3 + dm2_4*gg1_4 + dm2_5*gg1_5 + dm2_6*gg1_6
    gd1_3 = dm0_3*gg1_0 + dm1_3*gg1_1 + dm2_3*gg1_2 + dm3_3*gg1_3 + dm3_4*gg1_4 + dm3_5*gg1_5 + dm3_6*gg1_6
    gd1_4 = dm0_4*gg1_0 + dm1_4*gg1_1 + dm2_4*gg1_2 + dm3_4*gg1_3 + dm4_4*gg1_4 + dm4_5*gg1_5 + dm4_6*gg1_6
    gd1_5 = dm0_5*gg1_0 + dm1_5*gg1_1 + dm2_5*gg1_2 + dm3_5*gg1_3 + dm4_5*gg1_4 + dm5_5*gg1_5 + dm5_6*gg1_6
    gd1_6 = dm0_6*gg1_0 + dm1_6*gg1_1 + dm2_6*gg1_2 + dm3_6*gg1_3 + dm4_6*gg1_4 + dm5_6*gg1_5 + dm6_6*gg1_6
    gd2_0 = dm0_0*gg2_0 + dm0_1*gg2_1 + dm0_2*gg2_2 + dm0_3*gg2_3 + dm0_4*gg2_4 + dm0_5*gg2_5 + dm0_6*gg2_6
    gd2_1 = dm0_1*gg2_0 + dm1_1*gg2_1 + dm1_2*gg2_2 + dm1_3*gg2_3 + dm1_4*gg2_4 + dm1_5*gg2_5 + dm1_6*gg2_6
    gd2_2 = dm0_2*gg2_0 + dm1_2*gg2_1 + dm2_2*gg2_2 + dm2_3*gg2_3 + dm2_4*gg2_4 + dm2_5*gg2_5 + dm2_6*gg2_6
    gd2_3 = dm0_3*gg2_0 + dm1_3*gg2_1 + dm2_3*gg2_2 + dm3_3*gg2_3 + dm3_4*gg2_4 + dm3_5*gg2_5 + dm3_6*gg2_6
    gd2_4 = dm0_4*gg2_0 + dm1_4*gg2_1 + dm2_4*gg2_2 + dm3_4*gg2_3 + dm4_4*gg2_4 + dm4_5*gg2_5 + dm4_6*gg2_6
    gd2_5 = dm0_5*gg2_0 + dm1_5*gg2_1 + dm2_5*gg2_2 + dm3_5*gg2_3 + dm4_5*gg2_4 + dm5_5*gg2_5 + dm5_6*gg2_6
    gd2_6 = dm0_6*gg2_0 + dm1_6*gg2_1 + dm2_6*gg2_2 + dm3_6*gg2_3 + dm4_6*gg2_4 + dm5_6*gg2_5 + dm6_6*gg2_6
    gd3_0 = dm0_0*gg3_0 + dm0_1*gg3_1 + dm0_2*gg3_2 + dm0_3*gg3_3 + dm0_4*gg3_4 + dm0_5*gg3_5 + dm0_6*gg3_6
    gd3_1 = dm0_1*gg3_0 + dm1_1*gg3_1 + dm1_2*gg3_2 + dm1_3*gg3_3 + dm1_4*gg3_4 + dm1_5*gg3_5 + dm1_6*gg3_6
    gd3_2 = dm0_2*gg3_0 + dm1_2*gg3_1 + dm2_2*gg3_2 + dm2_3*gg3_3 + dm2_4*gg3_4 + dm2_5*gg3_5 + dm2_6*gg3_6
    gd3_3 = dm0_3*gg3_0 + dm1_3*gg3_1 + dm2_3*gg3_2 + dm3_3*gg3_3 + dm3_4*gg3_4 + dm3_5*gg3_5 + dm3_6*gg3_6
    gd3_4 = dm0_4*gg3_0 + dm1_4*gg3_1 + dm2_4*gg3_2 + dm3_4*gg3_3 + dm4_4*gg3_4 + dm4_5*gg3_5 + dm4_6*gg3_6
    gd3_5 = dm0_5*gg3_0 + dm1_5*gg3_1 + dm2_5*gg3_2 + dm3_5*gg3_3 + dm4_5*gg3_4 + dm5_5*gg3_5 + dm5_6*gg3_6
    gd3_6 = dm0_6*gg3_0 + dm1_6*gg3_1 + dm2_6*gg3_2 + dm3_6*gg3_3 + dm4_6*gg3_4 + dm5_6*gg3_5 + dm6_6*gg3_6
    gd4_0 = dm0_0*gg4_0 + dm0_1*gg4_1 + dm0_2*gg4_2 + dm0_3*gg4_3 + dm0_4*gg4_4 + dm0_5*gg4_5 + dm0_6*gg4_6
    gd4_1 = dm0_1*gg4_0 + dm1_1*gg4_1 + dm1_2*gg4_2 + dm1_3*gg4_3 + dm1_4*gg4_4 + dm1_5*gg4_5 + dm1_6*gg4_6
    gd4_2 = dm0_2*gg4_0 + dm1_2*gg4_1 + dm2_2*gg4_2 + dm2_3*gg4_3 + dm2_4*gg4_4 + dm2_5*gg4_5 + dm2_6*gg4_6
    gd4_3 = dm0_3*gg4_0 + dm1_3*gg4_1 + dm2_3*gg4_2 + dm3_3*gg4_3 + dm3_4*gg4_4 + dm3_5*gg4_5 + dm3_6*gg4_6
    gd4_4 = dm0_4*gg4_0 + dm1_4*gg4_1 + dm2_4*gg4_2 + dm3_4*gg4_3 + dm4_4*gg4_4 + dm4_5*gg4_5 + dm4_6*gg4_6
    gd4_5 = dm0_5*gg4_0 + dm1_5*gg4_1 + dm2_5*gg4_2 + dm3_5*gg4_3 + dm4_5*gg4_4 + dm5_5*gg4_5 + dm5_6*gg4_6
    gd4_6 = dm0_6*gg4_0 + dm1_6*gg4_1 + dm2_6*gg4_2 + dm3_6*gg4_3 + dm4_6*gg4_4 + dm5_6*gg4_5 + dm6_6*gg4_6
    gd5_0 = dm0_0*gg5_0 + dm0_1*gg5_1 + dm0_2*gg5_2 + dm0_3*gg5_3 + dm0_4*gg5_4 + dm0_5*gg5_5 + dm0_6*gg5_6
    gd5_1 = dm0_1*gg5_0 + dm1_1*gg5_1 + dm1_2*gg5_2 + dm1_3*gg5_3 + dm1_4*gg5_4 + dm1_5*gg5_5 + dm1_6*gg5_6
    gd5_2 = dm0_2*gg5_0 + dm1_2*gg5_1 + dm2_2*gg5_2 + dm2_3*gg5_3 + dm2_4*gg5_4 + dm2_5*gg5_5 + dm2_6*gg5_6
    gd5_3 = dm0_3*gg5_0 + dm1_3*gg5_1 + dm2_3*gg5_2 + dm3_3*gg5_3 + dm3_4*gg5_4 + dm3_5*gg5_5 + dm3_6*gg5_6
    gd5_4 = dm0_4*gg5_0 + dm1_4*gg5_1 + dm2_4*gg5_2 + dm3_4*gg5_3 + dm4_4*gg5_4 + dm4_5*gg5_5 + dm4_6*gg5_6
    gd5_5 = dm0_5*gg5_0 + dm1_5*gg5_1 + dm2_5*gg5_2 + dm3_5*gg5_3 + dm4_5*gg5_4 + dm5_5*gg5_5 + dm5_6*gg5_6
    gd5_6 = dm0_6*gg5_0 + dm1_6*gg5_1 + dm2_6*gg5_2 + dm3_6*gg5_3 + dm4_6*gg5_4 + dm5_6*gg5_5 + dm6_6*gg5_6
    gd6_0 = dm0_0*gg6_0 + dm0_1*gg6_1 + dm0_2*gg6_2 + dm0_3*gg6_3 + dm0_4*gg6_4 + dm0_5*gg6_5 + dm0_6*gg6_6
    gd6_1 = dm0_1*gg6_0 + dm1_1*gg6_1 + dm1_2*gg6_2 + dm1_3*gg6_3 + dm1_4*gg6_4 + dm1_5*gg6_5 + dm1_6*gg6_6
    gd6_2 = dm0_2*gg6_0 + dm1_2*gg6_1 + dm2_2*gg6_2 + dm2_3*gg6_3 + dm2_4*gg6_4 + dm2_5*gg6_5 + dm2_6*gg6_6
    gd6_3 = dm0_3*gg6_0 + dm1_3*gg6_1 + dm2_3*gg6_2 + dm3_3*gg6_3 + dm3_4*gg6_4 + dm3_5*gg6_5 + dm3_6*gg6_6
    gd6_4 = dm0_4*gg6_0 + dm1_4*gg6_1 + dm2_4*gg6_2 + dm3_4*gg6_3 + dm4_4*gg6_4 + dm4_5*gg6_5 + dm4_6*gg6_6
    gd6_5 = dm0_5*gg6_0 + dm1_5*gg6_1 + dm2_5*gg6_2 + dm3_5*gg6_3 + dm4_5*gg6_4 + dm5_5*gg6_5 + dm5_6*gg6_6
    gd6_6 = dm0_6*gg6_0 + dm1_6*gg6_1 + dm2_6*gg6_2 + dm3_6*gg6_3 + dm4_6*gg6_4 + dm5_6*gg6_5 + dm6_6*gg6_6
    pt0_0 = gd0_0*gg0_0 + gd0_1*gg0_1 + gd0_2*gg0_2 + gd0_3*gg0_3 + gd0_4*gg0_4 + gd0_5*gg0_5 + gd0_6*gg0_6 + pf00
    pt0_1 = gd0_0*gg1_0 + gd0_1*gg1_1 + gd0_2*gg1_2 + gd0_3*gg1_3 + gd0_4*gg1_4 + gd0_5*gg1_5 + gd0_6*gg1_6 + pf01
    pt0_2 = gd0_0*gg2_0 + gd0_1*gg2_1 + gd0_2*gg2_2 + gd0_3*gg2_3 + gd0_4*gg2_4 + gd0_5*gg2_5 + gd0_6*gg2_6 + pf02
    pt0_3 = gd0_0*gg3_0 + gd0_1*gg3_1 + gd0_2*gg3_2 + gd0_3*gg3_3 + gd0_4*gg3_4 + gd0_5*gg3_5 + gd0_6*gg3_6 + pf03
    pt0_4 = gd0_0*gg4_0 + gd0_1*gg4_1 + gd0_2*gg4_2 + gd0_3*gg4_3 + gd0_4*gg4_4 + gd0_5*gg4_5 + gd0_6*gg4_6 + pf04
    pt0_5 = gd0_0*gg5_0 + gd0_1*gg5_1 + gd0_2*gg5_2 + gd0_3*gg5_3 + gd0_4*gg5_4 + gd0_5*gg5_5 + gd0_6*gg5_6 + pf05
    pt0_6 = gd0_0*gg6_0 + gd0_1*gg6_1 + gd0_2*gg6_2 + gd0_3*gg6_3 + gd0_4*gg6_4 + gd0_5*gg6_5 + gd0_6*gg6_6 + pf06
    pt1_1 = gd1_0*gg1_0 + gd1_1*gg1_1 + gd1_2*gg1_2 + gd1_3*gg1_3 + gd1_4*gg1_4 + gd1_5*gg1_5 + gd1_6*gg1_6 + pf11
    pt1_2 = gd1_0*gg2_0 + gd1_1*gg2_1 + gd1_2*gg2_2 + gd1_3*gg2_3 + gd1_4*gg2_4 + gd1_5*gg2_5 + gd1_6*gg2_6 + pf12
    pt1_3 = gd1_0*gg3_0 + gd1_1*gg3_1 + gd1_2*gg3_2 + gd1_3*gg3_3 + gd1_4*gg3_4 + gd1_5*gg3_5 + gd1_6*gg3_6 + pf13
    pt1_4 = gd1_0*gg4_0 + gd1_1*gg4_1 + gd1_2*gg4_2 + gd1_3*gg4_3 + gd1_4*gg4_4 + gd1_5*gg4_5 + gd1_6*gg4_6 + pf14
    pt1_5 = gd1_0*gg5_0 + gd1_1*gg5_1 + gd1_2*gg5_2 + gd1_3*gg5_3 + gd1_4*gg5_4 + gd1_5*gg5_5 + gd1_6*gg5_6 + pf15
    pt1_6 = gd1_0*gg6_0 + gd1_1*gg6_1 + gd1_2*gg6_2 + gd1_3*gg6_3 + gd1_4*gg6_4 + gd1_5*gg6_5 + gd1_6*gg6_6 + pf16
    pt2_2 = gd2_0*gg2_0 + gd2_1*gg2_1 + gd2_2*gg2_2 + gd2_3*gg2_3 + gd2_4*gg2_4 + gd2_5*gg2_5 + gd2_6*gg2_6 + pf22
    pt2_3 = gd2_0*gg3_0 + gd2_1*gg3_1 + gd2_2*gg3_2 + gd2_3*gg3_3 + gd2_4*gg3_4 + gd2_5*gg3_5 + gd2_6*gg3_6 + pf23
    pt2_4 = gd2_0*gg4_0 + gd2_1*gg4_1 + gd2_2*gg4_2 + gd2_3*gg4_3 + gd2_4*gg4_4 + gd2_5*gg4_5 + gd2_6*gg4_6 + pf24
    pt2_5 = gd2_0*gg5_0 + gd2_1*gg5_1 + gd2_2*gg5_2 + gd2_3*gg5_3 + gd2_4*gg5_4 + gd2_5*gg5_5 + gd2_6*gg5_6 + pf25
    pt2_6 = gd2_0*gg6_0 + gd2_1*gg6_1 + gd2_2*gg6_2 + gd2_3*gg6_3 + gd2_4*gg6_4 + gd2_5*gg6_5 + gd2_6*gg6_6 + pf26
    pt3_3 = gd3_0*gg3_0 + gd3_1*gg3_1 + gd3_2*gg3_2 + gd3_3*gg3_3 + gd3_4*gg3_4 + gd3_5*gg3_5 + gd3_6*gg3_6 + pf33
    pt3_4 = gd3_0*gg4_0 + gd3_1*gg4_1 + gd3_2*gg4_2 + gd3_3*gg4_3 + gd3_4*gg4_4 + gd3_5*gg4_5 + gd3_6*gg4_6 + pf34
    pt3_5 = gd3_0*gg5_0 + gd3_1*gg5_1 + gd3_2*gg5_2 + gd3_3*gg5_3 + gd3_4*gg5_4 + gd3_5*gg5_5 + gd3_6*gg5_6 + pf35
    pt3_6 = gd3_0*gg6_0 + gd3_1*gg6_1 + gd3_2*gg6_2 + gd3_3*gg6_3 + gd3_4*gg6_4 + gd3_5*gg6_5 + gd3_6*gg6_6 + pf36
    pt4_4 = gd4_0*gg4_0 + gd4_1*gg4_1 + gd4_2*gg4_2 + gd4_3*gg4_3 + gd4_4*gg4_4 + gd4_5*gg4_5 + gd4_6*gg4_6 + pf44
    pt4_5 = gd4_0*gg5_0 + gd4_1*gg5_1 + gd4_2*gg5_2 + gd4_3*gg5_3 + gd4_4*gg5_4 + gd4_5*gg5_5 + gd4_6*gg5_6 + pf45
    pt4_6 = gd4_0*gg6_0 + gd4_1*gg6_1 + gd4_2*gg6_2 + gd4_3*gg6_3 + gd4_4*gg6_4 + gd4_5*gg6_5 + gd4_6*gg6_6 + pf46
    pt5_5 = gd5_0*gg5_0 + gd5_1*gg5_1 + gd5_2*gg5_2 + gd5_3*gg5_3 + gd5_4*gg5_4 + gd5_5*gg5_5 + gd5_6*gg5_6 + pf55
    pt5_6 = gd5_0*gg6_0 + gd5_1*gg6_1 + gd5_2*gg6_2 + gd5_3*gg6_3 + gd5_4*gg6_4 + gd5_5*gg6_5 + gd5_6*gg6_6 + pf56
    pt6_6 = gd6_0*gg6_0 + gd6_1*gg6_1 + gd6_2*gg6_2 + gd6_3*gg6_3 + gd6_4*gg6_4 + gd6_5*gg6_5 + gd6_6*gg6_6 + pf66
    W[7168 + j] = pt0_0
    W[7232 + j] = pt0_1
    W[7296 + j] = pt0_2
    W[7360 + j] = pt0_3
    W[7424 + j] = pt0_4
    W[7488 + j] = pt0_5
    W[7552 + j] = pt0_6
    W[7616 + j] = pt1_1
    W[7680 + j] = pt1_2
    W[7744 + j] = pt1_3
    W[7808 + j] = pt1_4
    W[7872 + j] = pt1_5
    W[7936 + j] = pt1_6
    W[8000 + j] = pt2_2
    W[8064 + j] = pt2_3
    W[8128 + j] = pt2_4
    W[8192 + j] = pt2_5
    W[8256 + j] = pt2_6
    W[8320 + j] = pt3_3
    W[8384 + j] = pt3_4
    W[8448 + j] = pt3_5
    W[8512 + j] = pt3_6
    W[8576 + j] = pt4_4
    W[8640 + j] = pt4_5
    W[8704 + j] = pt4_6
    W[8768 + j] = pt5_5
    W[8832 + j] = pt5_6
    W[8896 + j] = pt6_6
    W[6720 + j] = de0_0 + x
    W[6784 + j] = de1_0 + y
    W[6848 + j] = de2_0 + z
    W[6912 + j] = de3_0 + psi
    W[6976 + j] = de4_0 + v
    W[7040 + j] = de5_0 + omega
    W[7104 + j] = de6_0 + v_up


@nb.njit(inline="always", fastmath={"contract"}, error_model="numpy")
def physical_smooth_lane(W, j, out, b, k):
    """The physical state of lane j of the smoothed rows of the work array W into out[b, k] (SIMD).
    """
    x = W[4480 + j]
    y = W[4544 + j]
    z = W[4608 + j]
    psi = W[4672 + j]
    v = W[4736 + j]
    omega = W[4800 + j]
    v_up = W[4864 + j]
    out[b, k, 0] = x
    out[b, k, 1] = y
    out[b, k, 2] = z
    out[b, k, 3] = wrap_v(psi)
    out[b, k, 4] = v
    out[b, k, 5] = omega
    out[b, k, 6] = v_up


@nb.njit(cache=True, parallel=True, fastmath=FASTMATH, error_model="numpy")
def smooth_batch_soa(dts, Qb, Fb, lengths, Sb, out_x):
    """smooth_batch with trajectories in the SIMD lanes (derive/codegen/smooth_step.py), over a forward pass stored
    in blocks by run_batch_store_soa_<meas>: Qb, Fb (nblk, K, 35, 64) hold the predicted / posterior internal
    state and packed covariance of step k of trajectory blk·64 + j in Qb[blk, k, :, j]; writes the smoothed ones
    into Sb (same layout; pass Sb with no steps, (nblk, 0, 35, 64), to skip them) and the smoothed physical
    states into out_x (B, K, 7). Trajectory b starts at its last
    step lengths[b] − 1 (smoothed = filtered there); entries past its length are left unset. Per block (prange) and
    step, the rows are copied into one work array (rows × 64) and lane_smooth runs vectorised over the lanes.
    """
    B = dts.shape[0]
    nblk = Qb.shape[0]
    keep = Sb.shape[1] > 0
    for blk in nb.prange(nblk):
        lo = blk * 64
        L = min(64, B - lo)
        W = np.zeros(143 * 64)
        Kmax = 0
        for j in range(L):
            Kmax = max(Kmax, lengths[lo + j])
        for k in range(Kmax - 1, -1, -1):
            for i in range(35):
                for j in range(64):
                    W[(0 + i) * 64 + j] = Fb[blk, k, i, j]
            for j in range(L):
                Kb = lengths[lo + j]
                W[141 * 64 + j] = 1.0 if k < Kb - 1 else 0.0
                W[142 * 64 + j] = 1.0 if k == Kb - 1 else 0.0
            if k < Kmax - 1:
                for i in range(35):
                    for j in range(64):
                        W[(35 + i) * 64 + j] = Qb[blk, k + 1, i, j]
                for j in range(L):
                    W[140 * 64 + j] = dts[lo + j, k + 1]
                for j in range(L):
                    lane_smooth(W, j)
                for i in range(35):
                    for j in range(64):
                        act = W[141 * 64 + j] > 0.5
                        W[(70 + i) * 64 + j] = W[(105 + i) * 64 + j] if act else W[(70 + i) * 64 + j]
            for i in range(35):
                for j in range(64):
                    start = W[142 * 64 + j] > 0.5
                    W[(70 + i) * 64 + j] = W[(0 + i) * 64 + j] if start else W[(70 + i) * 64 + j]
            if keep:
                for i in range(35):
                    for j in range(64):
                        Sb[blk, k, i, j] = W[(70 + i) * 64 + j]
            for j in range(L):
                if k < lengths[lo + j]:
                    physical_smooth_lane(W, j, out_x, lo + j, k)


@nb.njit(cache=True)
def smooth_one(dts, s_pred, p_pred, s_filt, p_filt, K, s_sm, p_sm):
    """Rauch–Tung–Striebel backward pass on the group over the first K steps (derivation:
    lgekf.estimators.smoother). dts (K,) step lengths (dts[k] led to step k); s_pred, p_pred / s_filt, p_filt:
    predicted / posterior internal states and packed covariances (run_one_store_*); writes the smoothed ones
    into s_sm (K, 7), p_sm (K, 28). For k = K-2 ... 0, with F = transition(μ_k, dts[k+1]):
    d = log(μ_{k+1|k}⁻¹ μˢ_{k+1}), P̄ = Φ(d)⁻¹ Pˢ_{k+1} Φ(d)⁻ᵀ, G = P_k Fᵀ P_{k+1|k}⁻¹, δ = G d,
    μˢ_k = μ_k·exp(δ), Pˢ_k = Φ(δ) [P_k + G (P̄ − P_{k+1|k}) Gᵀ] Φ(δ)ᵀ."""
    for i in range(7):
        s_sm[K - 1, i] = s_filt[K - 1, i]
    for i in range(28):
        p_sm[K - 1, i] = p_filt[K - 1, i]
    for k in range(K - 2, -1, -1):
        smooth_step_at(s_filt, p_filt, s_pred, p_pred, s_sm, p_sm, k, dts[k + 1])  # smooth_step on the rows k, k + 1


@nb.njit(cache=True, parallel=True)
def smooth_batch(dts, s_pred, p_pred, s_filt, p_filt, lengths, s_sm, p_sm, out_x):
    """smooth_one for B trajectories (prange), trajectory b over its first lengths[b] steps; also writes the
    smoothed physical states into out_x (B, K, 7)."""
    for b in nb.prange(dts.shape[0]):
        Kb = lengths[b]
        if Kb > 0:
            smooth_one(dts[b], s_pred[b], p_pred[b], s_filt[b], p_filt[b], Kb, s_sm[b], p_sm[b])
            for k in range(Kb):
                physical_into(s_sm[b, k], out_x[b, k])


@nb.njit(cache=True)
def physical_to_common(xp):
    """c = (x, y, z, roll, pitch, yaw, v_x, v_y, v_z, ω_x, ω_y, ω_z) of a physical state x (the attitude from the velocity for a model
    without an attitude; 0 for the coordinates of common_missing).
    """
    x = xp[0]
    y = xp[1]
    z = xp[2]
    psi = xp[3]
    v = xp[4]
    omega = xp[5]
    v_up = xp[6]
    out = np.zeros(12)
    _sin_psi = math.sin(psi)
    _cos_psi = math.cos(psi)
    _t0 = v*v
    _t1 = (_cos_psi*_cos_psi)*_t0 + (_sin_psi*_sin_psi)*_t0
    _t2 = v_up*v_up
    _t3 = omega*(1.0/math.sqrt(_t0 + _t2))
    out[0] = x
    out[1] = y
    out[2] = z
    out[4] = math.atan2(-v_up, math.sqrt(_t1))
    out[5] = math.atan2(_sin_psi*v, _cos_psi*v)
    out[6] = math.sqrt(_t1 + _t2)
    out[9] = _t3*v_up
    out[11] = _t3*v
    return out


@nb.njit(cache=True)
def physical_to_common_jacobian(xp):
    """A = ∂c/∂ε (12 × n) at the physical state x (X = μ·exp ε): P_c = A P Aᵀ.
    """
    v = xp[4]
    omega = xp[5]
    v_up = xp[6]
    out = np.zeros((12, 7))
    _t0 = v*v
    _t1 = v_up*v_up
    _t2 = _t0 + _t1
    _t3 = 1.0/_t2
    _t4 = abs(v)
    _t5 = v*v_up
    _t6 = 1.0/math.sqrt(_t2)
    _t7 = _t6*v
    _t8 = _t6*v_up
    _t9 = (1.0/(_t2*math.sqrt(_t2)))*omega
    _t10 = -(_t5*_t9)
    out[0, 0] = 1.0
    out[1, 1] = 1.0
    out[2, 2] = 1.0
    out[4, 4] = _t3*_t5/_t4
    out[4, 6] = -(_t3*_t4)
    out[5, 3] = 1.0
    out[6, 4] = _t7
    out[6, 6] = _t8
    out[9, 4] = _t10
    out[9, 5] = _t8
    out[9, 6] = _t0*_t9
    out[11, 4] = _t1*_t9
    out[11, 5] = _t7
    out[11, 6] = _t10
    return out


@nb.njit(cache=True)
def common_missing():
    """1.0 for each common coordinate (x, y, z, roll, pitch, yaw, v_x, v_y, v_z, ω_x, ω_y, ω_z) the model carries no information on."""
    return np.array([0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0])


@nb.njit(cache=True)
def state_from_physical_into(xp, out):
    """Internal state [x, y, z, psi, v, omega, v_up] from the physical [x, y, z, psi, v, omega, vz].
    Written into ``out`` (no allocation).
    """
    x = xp[0]
    y = xp[1]
    z = xp[2]
    psi = xp[3]
    v = xp[4]
    omega = xp[5]
    v_up = xp[6]
    out[:] = 0.0
    out[0] = x
    out[1] = y
    out[2] = z
    out[3] = psi
    out[4] = v
    out[5] = omega
    out[6] = v_up


@nb.njit(cache=True)
def transition_into(s, dt, out):
    """F = Ad_G(exp(-Ω)) + Φ_G(Ω) 𝒞 (paper, below eq:pred_cov).
    Written into ``out`` (no allocation).
    """
    psi = s[3]
    v = s[4]
    omega = s[5]
    out[:, :] = 0.0
    _a0 = dt*omega/2.0
    _sin__a0 = math.sin(_a0)
    _cos__a0 = math.cos(_a0)
    _dsinc__a0 = dsinc(_a0, _sin__a0, _cos__a0)
    _sinc__a0 = sinc(_a0, _sin__a0, _cos__a0)
    _a1 = dt*omega/2.0 + psi
    _sin__a1 = math.sin(_a1)
    _cos__a1 = math.cos(_a1)
    _t0 = _sin__a1*_sinc__a0
    _t1 = _t0*dt
    _t2 = _cos__a1*_sinc__a0
    _t3 = _t2*dt
    _t4 = (dt*dt)*v/2.0
    out[0, 0] = 1.0
    out[0, 3] = -(_t1*v)
    out[0, 4] = _t3
    out[0, 5] = -(_t4*(_cos__a1*_dsinc__a0 + _t0))
    out[1, 1] = 1.0
    out[1, 3] = _t3*v
    out[1, 4] = _t1
    out[1, 5] = _t4*(-(_dsinc__a0*_sin__a1) + _t2)
    out[2, 2] = 1.0
    out[2, 6] = dt
    out[3, 3] = 1.0
    out[3, 5] = dt
    out[4, 4] = 1.0
    out[5, 5] = 1.0
    out[6, 6] = 1.0


@nb.njit(cache=True)
def calH_position3_into(s, out):
    """ℋ = ∂[log_G'(h(μ)^-1 h(μ exp ε))]^∨/∂ε at ε = 0 (eq:calH, eq:calH_model) for position3 measurements.
    Written into ``out`` (no allocation).
    """
    out[:, :] = 0.0
    out[0, 0] = 1.0
    out[1, 1] = 1.0
    out[2, 2] = 1.0


@nb.njit(cache=True)
def common_to_state_into(c, out):
    """The model's physical state from the common c = (x, y, z, roll, pitch, yaw, v_x, v_y, v_z, ω_x, ω_y, ω_z), velocities in the body frame.
    Written into ``out`` (no allocation).
    """
    c0 = c[0]
    c1 = c[1]
    c2 = c[2]
    c3 = c[3]
    c4 = c[4]
    c5 = c[5]
    c6 = c[6]
    c7 = c[7]
    c8 = c[8]
    c9 = c[9]
    c10 = c[10]
    c11 = c[11]
    out[:] = 0.0
    _sin_c3 = math.sin(c3)
    _cos_c3 = math.cos(c3)
    _sin_c4 = math.sin(c4)
    _cos_c4 = math.cos(c4)
    _sin_c5 = math.sin(c5)
    _cos_c5 = math.cos(c5)
    _t0 = _cos_c4*c6
    _t1 = _cos_c3*_cos_c5
    _t2 = _sin_c3*_sin_c5
    _t3 = _cos_c3*_sin_c5
    _t4 = _sin_c5*_t0 + c7*(_sin_c4*_t2 + _t1) + c8*(-(_cos_c5*_sin_c3) + _sin_c4*_t3)
    _t5 = _cos_c5*_t0 + c7*(_cos_c5*_sin_c3*_sin_c4 - _t3) + c8*(_sin_c4*_t1 + _t2)
    _t6 = _cos_c3*_cos_c4
    _t7 = _cos_c4*_sin_c3
    out[0] = c0
    out[1] = c1
    out[2] = c2
    out[3] = math.atan2(_t4, _t5)
    out[4] = math.sqrt(_t4*_t4 + _t5*_t5)
    out[5] = -(_sin_c4*c9) + _t6*c11 + _t7*c10
    out[6] = -(_sin_c4*c6) + _t6*c8 + _t7*c7


@nb.njit(cache=True)
def common_jacobian_into(c, out):
    """J = ∂(filter coordinates ε)/∂c at c: maps a covariance of c to the filter's P (P = J P_c J^T).
    Written into ``out`` (no allocation).
    """
    c3 = c[3]
    c4 = c[4]
    c5 = c[5]
    c6 = c[6]
    c7 = c[7]
    c8 = c[8]
    c9 = c[9]
    c10 = c[10]
    c11 = c[11]
    out[:, :] = 0.0
    _sin_c3 = math.sin(c3)
    _cos_c3 = math.cos(c3)
    _sin_c4 = math.sin(c4)
    _cos_c4 = math.cos(c4)
    _sin_c5 = math.sin(c5)
    _cos_c5 = math.cos(c5)
    _t0 = _cos_c5*_sin_c3
    _t1 = _cos_c3*_sin_c5
    _t2 = _sin_c4*_t1
    _t3 = -_t0 + _t2
    _t4 = _t3*c7
    _t5 = _cos_c3*_cos_c5
    _t6 = _sin_c3*_sin_c5
    _t7 = _sin_c4*_t6
    _t8 = _t5 + _t7
    _t9 = -_t8
    _t10 = _t9*c8
    _t11 = _cos_c4*c6
    _t12 = _cos_c5*_t11
    _t13 = _sin_c4*_t5
    _t14 = _t13 + _t6
    _t15 = _t14*c8
    _t16 = -(_cos_c5*_sin_c3*_sin_c4) + _t1
    _t17 = -_t16
    _t18 = _t17*c7
    _t19 = _t12 + _t15 + _t18
    _t20 = _t19*_t19
    _t21 = _sin_c5*_t11
    _t22 = _t21 + _t3*c8 + _t8*c7
    _t23 = _t20 + _t22*_t22
    _t24 = 1.0/_t23
    _t25 = _t19*_t24
    _t26 = _t14*c7
    _t27 = _t16*c8
    _t28 = -(_t22*_t24)
    _t29 = _sin_c4*c6
    _t30 = _sin_c5*_t29
    _t31 = _cos_c4*c8
    _t32 = _cos_c4*c7
    _t33 = _cos_c5*_t29
    _t34 = -(_t3*c8)
    _t35 = _t9*c7
    _t36 = _cos_c4*_sin_c5
    _t37 = _cos_c4*_cos_c5
    _t38 = 1.0/math.sqrt(_t23)
    _t39 = _t19/2.0
    _t40 = _t22/2.0
    _t41 = 2.0*_t5
    _t42 = 2.0*_t0
    _t43 = 2.0*_t1
    _t44 = 2.0*_t6
    _t45 = _cos_c3*_sin_c4
    _t46 = _sin_c3*_sin_c4
    _t47 = -_sin_c4
    _t48 = _cos_c4*_sin_c3
    _t49 = _cos_c3*_cos_c4
    out[0, 0] = 1.0
    out[1, 1] = 1.0
    out[2, 2] = 1.0
    out[3, 3] = _t25*(_t10 + _t4) + _t28*(_t26 + _t27)
    out[3, 4] = _t25*(_t1*_t31 - _t30 + _t32*_t6) + _t28*(_t0*_t32 + _t31*_t5 - _t33)
    out[3, 5] = _t20*_t24 + _t28*(-_t21 + _t34 + _t35)
    out[3, 6] = _t25*_t36 + _t28*_t37
    out[3, 7] = _t17*_t28 + _t25*_t8
    out[3, 8] = _t14*_t28 + _t25*_t3
    out[4, 3] = _t38*(_t39*(2.0*_t26 + 2.0*_t27) + _t40*(2.0*_t10 + 2.0*_t4))
    out[4, 4] = _t38*(_t39*(_t31*_t41 + _t32*_t42 - 2.0*_t33) + _t40*(-(2.0*_t30) + _t31*_t43 + _t32*_t44))
    out[4, 5] = _t38*(_t39*(-(2.0*_t21) + 2.0*_t34 + 2.0*_t35) + _t40*(2.0*_t12 + 2.0*_t15 + 2.0*_t18))
    out[4, 6] = _t38*(_t19*_t37 + _t22*_t36)
    out[4, 7] = _t38*(_t39*(2.0*_cos_c5*_sin_c3*_sin_c4 - _t43) + _t40*(_t41 + 2.0*_t7))
    out[4, 8] = _t38*(_t39*(2.0*_t13 + _t44) + _t40*(2.0*_t2 - _t42))
    out[5, 3] = _cos_c4*(_cos_c3*c10 - _sin_c3*c11)
    out[5, 4] = -(_cos_c4*c9) - _t45*c11 - _t46*c10
    out[5, 9] = _t47
    out[5, 10] = _t48
    out[5, 11] = _t49
    out[6, 3] = _cos_c4*(_cos_c3*c7 - _sin_c3*c8)
    out[6, 4] = -_t11 - _t45*c8 - _t46*c7
    out[6, 6] = _t47
    out[6, 7] = _t48
    out[6, 8] = _t49


@nb.njit(cache=True)
def between_into(s, t, out):
    """[log_G(μ_s^-1 μ_t)]^∨: the tangent ε with μ_t = μ_s·exp(ε) (s ⊖: μ_s, t: μ_t, internal states);
    angle coordinates of a Euclidean model wrapped to (-π, π].
    Written into ``out`` (no allocation).
    """
    x = s[0]
    y = s[1]
    z = s[2]
    psi = s[3]
    v = s[4]
    omega = s[5]
    v_up = s[6]
    t_x = t[0]
    t_y = t[1]
    t_z = t[2]
    t_psi = t[3]
    t_v = t[4]
    t_omega = t[5]
    t_v_up = t[6]
    out[:] = 0.0
    out[0] = t_x - x
    out[1] = t_y - y
    out[2] = t_z - z
    out[3] = wrap_angle(-psi + t_psi)
    out[4] = t_v - v
    out[5] = -omega + t_omega
    out[6] = t_v_up - v_up


@nb.njit(cache=True)
def right_jacobian_into(eps, out):
    """Φ_G(ε) of the whole group (block-diagonal over its factors, I for Rⁿ);
    log(exp(-ε) exp(ε + δ)) ≈ Φ_G(ε) δ.
    Written into ``out`` (no allocation).
    """
    out[:, :] = 0.0
    out[0, 0] = 1.0
    out[1, 1] = 1.0
    out[2, 2] = 1.0
    out[3, 3] = 1.0
    out[4, 4] = 1.0
    out[5, 5] = 1.0
    out[6, 6] = 1.0


@nb.njit(cache=True)
def right_jacobian_inv_into(eps, out):
    """Φ_G(ε)^-1 of the whole group.
    Written into ``out`` (no allocation).
    """
    out[:, :] = 0.0
    out[0, 0] = 1.0
    out[1, 1] = 1.0
    out[2, 2] = 1.0
    out[3, 3] = 1.0
    out[4, 4] = 1.0
    out[5, 5] = 1.0
    out[6, 6] = 1.0


@nb.njit(cache=True)
def physical_to_common_into(xp, out):
    """c = (x, y, z, roll, pitch, yaw, v_x, v_y, v_z, ω_x, ω_y, ω_z) of a physical state x (the attitude from the velocity for a model
    without an attitude; 0 for the coordinates of common_missing).
    Written into ``out`` (no allocation).
    """
    x = xp[0]
    y = xp[1]
    z = xp[2]
    psi = xp[3]
    v = xp[4]
    omega = xp[5]
    v_up = xp[6]
    out[:] = 0.0
    _sin_psi = math.sin(psi)
    _cos_psi = math.cos(psi)
    _t0 = v*v
    _t1 = (_cos_psi*_cos_psi)*_t0 + (_sin_psi*_sin_psi)*_t0
    _t2 = v_up*v_up
    _t3 = omega*(1.0/math.sqrt(_t0 + _t2))
    out[0] = x
    out[1] = y
    out[2] = z
    out[4] = math.atan2(-v_up, math.sqrt(_t1))
    out[5] = math.atan2(_sin_psi*v, _cos_psi*v)
    out[6] = math.sqrt(_t1 + _t2)
    out[9] = _t3*v_up
    out[11] = _t3*v


@nb.njit(cache=True)
def physical_to_common_jacobian_into(xp, out):
    """A = ∂c/∂ε (12 × n) at the physical state x (X = μ·exp ε): P_c = A P Aᵀ.
    Written into ``out`` (no allocation).
    """
    v = xp[4]
    omega = xp[5]
    v_up = xp[6]
    out[:, :] = 0.0
    _t0 = v*v
    _t1 = v_up*v_up
    _t2 = _t0 + _t1
    _t3 = 1.0/_t2
    _t4 = abs(v)
    _t5 = v*v_up
    _t6 = 1.0/math.sqrt(_t2)
    _t7 = _t6*v
    _t8 = _t6*v_up
    _t9 = (1.0/(_t2*math.sqrt(_t2)))*omega
    _t10 = -(_t5*_t9)
    out[0, 0] = 1.0
    out[1, 1] = 1.0
    out[2, 2] = 1.0
    out[4, 4] = _t3*_t5/_t4
    out[4, 6] = -(_t3*_t4)
    out[5, 3] = 1.0
    out[6, 4] = _t7
    out[6, 6] = _t8
    out[9, 4] = _t10
    out[9, 5] = _t8
    out[9, 6] = _t0*_t9
    out[11, 4] = _t1*_t9
    out[11, 5] = _t7
    out[11, 6] = _t10


@nb.njit(cache=True)
def between_add(s, t, w, acc):
    """acc += w·[log_G(μ_s^-1 μ_t)]^∨ (a term of the iterated mean μ ← μ·exp(Σ w_i d_i); d as ``between``).
    """
    x = s[0]
    y = s[1]
    z = s[2]
    psi = s[3]
    v = s[4]
    omega = s[5]
    v_up = s[6]
    t_x = t[0]
    t_y = t[1]
    t_z = t[2]
    t_psi = t[3]
    t_v = t[4]
    t_omega = t[5]
    t_v_up = t[6]
    acc0 = acc[0]
    acc1 = acc[1]
    acc2 = acc[2]
    acc3 = acc[3]
    acc4 = acc[4]
    acc5 = acc[5]
    acc6 = acc[6]
    d0 = t_x - x
    d1 = t_y - y
    d2 = t_z - z
    d3 = wrap_angle(-psi + t_psi)
    d4 = t_v - v
    d5 = -omega + t_omega
    d6 = t_v_up - v_up
    acc[0] = acc0 + d0*w
    acc[1] = acc1 + d1*w
    acc[2] = acc2 + d2*w
    acc[3] = acc3 + d3*w
    acc[4] = acc4 + d4*w
    acc[5] = acc5 + d5*w
    acc[6] = acc6 + d6*w


@nb.njit(cache=True)
def mix_transport(s, t, pt, w, acc):
    """acc (packed upper triangle) += w·[Φ(d)^-1 P_t Φ(d)^-T + d dᵀ], d = [log_G(μ_s^-1 μ_t)]^∨, P_t = unpack(pt):
    one source's term of a mixture's covariance about the mean μ_s (X = μ_t·exp ε_t = μ_s·exp(d + Φ(d)^-1 ε_t)
    to first order; lgekf.estimators.imm.kernels). Straight line over the non-zero entries of Φ^-1.
    """
    x = s[0]
    y = s[1]
    z = s[2]
    psi = s[3]
    v = s[4]
    omega = s[5]
    v_up = s[6]
    t_x = t[0]
    t_y = t[1]
    t_z = t[2]
    t_psi = t[3]
    t_v = t[4]
    t_omega = t[5]
    t_v_up = t[6]
    pt0_0 = pt[0]
    pt0_1 = pt[1]
    pt0_2 = pt[2]
    pt0_3 = pt[3]
    pt0_4 = pt[4]
    pt0_5 = pt[5]
    pt0_6 = pt[6]
    pt1_1 = pt[7]
    pt1_2 = pt[8]
    pt1_3 = pt[9]
    pt1_4 = pt[10]
    pt1_5 = pt[11]
    pt1_6 = pt[12]
    pt2_2 = pt[13]
    pt2_3 = pt[14]
    pt2_4 = pt[15]
    pt2_5 = pt[16]
    pt2_6 = pt[17]
    pt3_3 = pt[18]
    pt3_4 = pt[19]
    pt3_5 = pt[20]
    pt3_6 = pt[21]
    pt4_4 = pt[22]
    pt4_5 = pt[23]
    pt4_6 = pt[24]
    pt5_5 = pt[25]
    pt5_6 = pt[26]
    pt6_6 = pt[27]
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
    acc21 = acc[21]
    acc22 = acc[22]
    acc23 = acc[23]
    acc24 = acc[24]
    acc25 = acc[25]
    acc26 = acc[26]
    acc27 = acc[27]
    d0 = t_x - x
    d1 = t_y - y
    d2 = t_z - z
    d3 = wrap_angle(-psi + t_psi)
    d4 = t_v - v
    d5 = -omega + t_omega
    d6 = t_v_up - v_up
    acc[0] = acc0 + w*(d0*d0 + pt0_0)
    acc[1] = acc1 + w*(d0*d1 + pt0_1)
    acc[2] = acc2 + w*(d0*d2 + pt0_2)
    acc[3] = acc3 + w*(d0*d3 + pt0_3)
    acc[4] = acc4 + w*(d0*d4 + pt0_4)
    acc[5] = acc5 + w*(d0*d5 + pt0_5)
    acc[6] = acc6 + w*(d0*d6 + pt0_6)
    acc[7] = acc7 + w*(d1*d1 + pt1_1)
    acc[8] = acc8 + w*(d1*d2 + pt1_2)
    acc[9] = acc9 + w*(d1*d3 + pt1_3)
    acc[10] = acc10 + w*(d1*d4 + pt1_4)
    acc[11] = acc11 + w*(d1*d5 + pt1_5)
    acc[12] = acc12 + w*(d1*d6 + pt1_6)
    acc[13] = acc13 + w*(d2*d2 + pt2_2)
    acc[14] = acc14 + w*(d2*d3 + pt2_3)
    acc[15] = acc15 + w*(d2*d4 + pt2_4)
    acc[16] = acc16 + w*(d2*d5 + pt2_5)
    acc[17] = acc17 + w*(d2*d6 + pt2_6)
    acc[18] = acc18 + w*(d3*d3 + pt3_3)
    acc[19] = acc19 + w*(d3*d4 + pt3_4)
    acc[20] = acc20 + w*(d3*d5 + pt3_5)
    acc[21] = acc21 + w*(d3*d6 + pt3_6)
    acc[22] = acc22 + w*(d4*d4 + pt4_4)
    acc[23] = acc23 + w*(d4*d5 + pt4_5)
    acc[24] = acc24 + w*(d4*d6 + pt4_6)
    acc[25] = acc25 + w*(d5*d5 + pt5_5)
    acc[26] = acc26 + w*(d5*d6 + pt5_6)
    acc[27] = acc27 + w*(d6*d6 + pt6_6)


@nb.njit(cache=True, error_model="numpy")
def common_of_state(s, p, c, Pc):
    """A mode's Gaussian in the common coordinates: c = (x, y, z, roll, pitch, yaw, v_x, v_y, v_z, ω_x, ω_y, ω_z) of the internal state s (as
    physical_to_common(physical(s))) and Pc = A P Aᵀ (12 × 12), A = ∂c/∂ε (physical_to_common_jacobian) at s.
    """
    x = s[0]
    y = s[1]
    z = s[2]
    psi = s[3]
    v = s[4]
    omega = s[5]
    v_up = s[6]
    p0_0 = p[0]
    p0_1 = p[1]
    p0_2 = p[2]
    p0_3 = p[3]
    p0_4 = p[4]
    p0_5 = p[5]
    p0_6 = p[6]
    p1_1 = p[7]
    p1_2 = p[8]
    p1_3 = p[9]
    p1_4 = p[10]
    p1_5 = p[11]
    p1_6 = p[12]
    p2_2 = p[13]
    p2_3 = p[14]
    p2_4 = p[15]
    p2_5 = p[16]
    p2_6 = p[17]
    p3_3 = p[18]
    p3_4 = p[19]
    p3_5 = p[20]
    p3_6 = p[21]
    p4_4 = p[22]
    p4_5 = p[23]
    p4_6 = p[24]
    p5_5 = p[25]
    p5_6 = p[26]
    p6_6 = p[27]
    xp_x = x
    xp_y = y
    xp_z = z
    xp_psi = wrap_angle(psi)
    xp_v = v
    xp_omega = omega
    xp_v_up = v_up
    _t0 = xp_v*xp_v
    _t1 = xp_v_up*xp_v_up
    _t2 = _t0 + _t1
    _t3 = 1.0/_t2
    _t4 = abs(xp_v)
    _t5 = xp_v*xp_v_up
    _t6 = 1.0/math.sqrt(_t2)
    _t7 = _t6*xp_v
    _t8 = _t6*xp_v_up
    _t9 = (1.0/(_t2*math.sqrt(_t2)))*xp_omega
    _t10 = -(_t5*_t9)
    A4_4 = _t3*_t5/_t4
    A4_6 = -(_t3*_t4)
    A6_4 = _t7
    A6_6 = _t8
    A9_4 = _t10
    A9_5 = _t8
    A9_6 = _t0*_t9
    A11_4 = _t1*_t9
    A11_5 = _t7
    A11_6 = _t10
    U4_3 = A4_4*p3_4 + A4_6*p3_6
    U4_4 = A4_4*p4_4 + A4_6*p4_6
    U4_5 = A4_4*p4_5 + A4_6*p5_6
    U4_6 = A4_4*p4_6 + A4_6*p6_6
    U6_4 = A6_4*p4_4 + A6_6*p4_6
    U6_5 = A6_4*p4_5 + A6_6*p5_6
    U6_6 = A6_4*p4_6 + A6_6*p6_6
    U9_4 = A9_4*p4_4 + A9_5*p4_5 + A9_6*p4_6
    U9_5 = A9_4*p4_5 + A9_5*p5_5 + A9_6*p5_6
    U9_6 = A9_4*p4_6 + A9_5*p5_6 + A9_6*p6_6
    U11_4 = A11_4*p4_4 + A11_5*p4_5 + A11_6*p4_6
    U11_5 = A11_4*p4_5 + A11_5*p5_5 + A11_6*p5_6
    U11_6 = A11_4*p4_6 + A11_5*p5_6 + A11_6*p6_6
    _sin_xp_psi = math.sin(xp_psi)
    _cos_xp_psi = math.cos(xp_psi)
    _t11 = xp_v*xp_v
    _t12 = (_cos_xp_psi*_cos_xp_psi)*_t11 + (_sin_xp_psi*_sin_xp_psi)*_t11
    _t13 = xp_v_up*xp_v_up
    _t14 = xp_omega*(1.0/math.sqrt(_t11 + _t13))
    _t15 = A4_4*p0_4 + A4_6*p0_6
    _t16 = A6_4*p0_4 + A6_6*p0_6
    _t17 = A9_4*p0_4 + A9_5*p0_5 + A9_6*p0_6
    _t18 = A11_4*p0_4 + A11_5*p0_5 + A11_6*p0_6
    _t19 = A4_4*p1_4 + A4_6*p1_6
    _t20 = A6_4*p1_4 + A6_6*p1_6
    _t21 = A9_4*p1_4 + A9_5*p1_5 + A9_6*p1_6
    _t22 = A11_4*p1_4 + A11_5*p1_5 + A11_6*p1_6
    _t23 = A4_4*p2_4 + A4_6*p2_6
    _t24 = A6_4*p2_4 + A6_6*p2_6
    _t25 = A9_4*p2_4 + A9_5*p2_5 + A9_6*p2_6
    _t26 = A11_4*p2_4 + A11_5*p2_5 + A11_6*p2_6
    _t27 = A6_4*U4_4 + A6_6*U4_6
    _t28 = A9_4*U4_4 + A9_5*U4_5 + A9_6*U4_6
    _t29 = A11_4*U4_4 + A11_5*U4_5 + A11_6*U4_6
    _t30 = A6_4*p3_4 + A6_6*p3_6
    _t31 = A9_4*p3_4 + A9_5*p3_5 + A9_6*p3_6
    _t32 = A11_4*p3_4 + A11_5*p3_5 + A11_6*p3_6
    _t33 = A9_4*U6_4 + A9_5*U6_5 + A9_6*U6_6
    _t34 = A11_4*U6_4 + A11_5*U6_5 + A11_6*U6_6
    _t35 = A11_4*U9_4 + A11_5*U9_5 + A11_6*U9_6
    c[0] = xp_x
    c[1] = xp_y
    c[2] = xp_z
    c[3] = 0.0
    c[4] = math.atan2(-xp_v_up, math.sqrt(_t12))
    c[5] = math.atan2(_sin_xp_psi*xp_v, _cos_xp_psi*xp_v)
    c[6] = math.sqrt(_t12 + _t13)
    c[7] = 0.0
    c[8] = 0.0
    c[9] = _t14*xp_v_up
    c[10] = 0.0
    c[11] = _t14*xp_v
    Pc[0, 0] = p0_0
    Pc[0, 1] = p0_1
    Pc[1, 0] = p0_1
    Pc[0, 2] = p0_2
    Pc[2, 0] = p0_2
    Pc[0, 3] = 0.0
    Pc[3, 0] = 0.0
    Pc[0, 4] = _t15
    Pc[4, 0] = _t15
    Pc[0, 5] = p0_3
    Pc[5, 0] = p0_3
    Pc[0, 6] = _t16
    Pc[6, 0] = _t16
    Pc[0, 7] = 0.0
    Pc[7, 0] = 0.0
    Pc[0, 8] = 0.0
    Pc[8, 0] = 0.0
    Pc[0, 9] = _t17
    Pc[9, 0] = _t17
    Pc[0, 10] = 0.0
    Pc[10, 0] = 0.0
    Pc[0, 11] = _t18
    Pc[11, 0] = _t18
    Pc[1, 1] = p1_1
    Pc[1, 2] = p1_2
    Pc[2, 1] = p1_2
    Pc[1, 3] = 0.0
    Pc[3, 1] = 0.0
    Pc[1, 4] = _t19
    Pc[4, 1] = _t19
    Pc[1, 5] = p1_3
    Pc[5, 1] = p1_3
    Pc[1, 6] = _t20
    Pc[6, 1] = _t20
    Pc[1, 7] = 0.0
    Pc[7, 1] = 0.0
    Pc[1, 8] = 0.0
    Pc[8, 1] = 0.0
    Pc[1, 9] = _t21
    Pc[9, 1] = _t21
    Pc[1, 10] = 0.0
    Pc[10, 1] = 0.0
    Pc[1, 11] = _t22
    Pc[11, 1] = _t22
    Pc[2, 2] = p2_2
    Pc[2, 3] = 0.0
    Pc[3, 2] = 0.0
    Pc[2, 4] = _t23
    Pc[4, 2] = _t23
    Pc[2, 5] = p2_3
    Pc[5, 2] = p2_3
    Pc[2, 6] = _t24
    Pc[6, 2] = _t24
    Pc[2, 7] = 0.0
    Pc[7, 2] = 0.0
    Pc[2, 8] = 0.0
    Pc[8, 2] = 0.0
    Pc[2, 9] = _t25
    Pc[9, 2] = _t25
    Pc[2, 10] = 0.0
    Pc[10, 2] = 0.0
    Pc[2, 11] = _t26
    Pc[11, 2] = _t26
    Pc[3, 3] = 0.0
    Pc[3, 4] = 0.0
    Pc[4, 3] = 0.0
    Pc[3, 5] = 0.0
    Pc[5, 3] = 0.0
    Pc[3, 6] = 0.0
    Pc[6, 3] = 0.0
    Pc[3, 7] = 0.0
    Pc[7, 3] = 0.0
    Pc[3, 8] = 0.0
    Pc[8, 3] = 0.0
    Pc[3, 9] = 0.0
    Pc[9, 3] = 0.0
    Pc[3, 10] = 0.0
    Pc[10, 3] = 0.0
    Pc[3, 11] = 0.0
    Pc[11, 3] = 0.0
    Pc[4, 4] = A4_4*U4_4 + A4_6*U4_6
    Pc[4, 5] = U4_3
    Pc[5, 4] = U4_3
    Pc[4, 6] = _t27
    Pc[6, 4] = _t27
    Pc[4, 7] = 0.0
    Pc[7, 4] = 0.0
    Pc[4, 8] = 0.0
    Pc[8, 4] = 0.0
    Pc[4, 9] = _t28
    Pc[9, 4] = _t28
    Pc[4, 10] = 0.0
    Pc[10, 4] = 0.0
    Pc[4, 11] = _t29
    Pc[11, 4] = _t29
    Pc[5, 5] = p3_3
    Pc[5, 6] = _t30
    Pc[6, 5] = _t30
    Pc[5, 7] = 0.0
    Pc[7, 5] = 0.0
    Pc[5, 8] = 0.0
    Pc[8, 5] = 0.0
    Pc[5, 9] = _t31
    Pc[9, 5] = _t31
    Pc[5, 10] = 0.0
    Pc[10, 5] = 0.0
    Pc[5, 11] = _t32
    Pc[11, 5] = _t32
    Pc[6, 6] = A6_4*U6_4 + A6_6*U6_6
    Pc[6, 7] = 0.0
    Pc[7, 6] = 0.0
    Pc[6, 8] = 0.0
    Pc[8, 6] = 0.0
    Pc[6, 9] = _t33
    Pc[9, 6] = _t33
    Pc[6, 10] = 0.0
    Pc[10, 6] = 0.0
    Pc[6, 11] = _t34
    Pc[11, 6] = _t34
    Pc[7, 7] = 0.0
    Pc[7, 8] = 0.0
    Pc[8, 7] = 0.0
    Pc[7, 9] = 0.0
    Pc[9, 7] = 0.0
    Pc[7, 10] = 0.0
    Pc[10, 7] = 0.0
    Pc[7, 11] = 0.0
    Pc[11, 7] = 0.0
    Pc[8, 8] = 0.0
    Pc[8, 9] = 0.0
    Pc[9, 8] = 0.0
    Pc[8, 10] = 0.0
    Pc[10, 8] = 0.0
    Pc[8, 11] = 0.0
    Pc[11, 8] = 0.0
    Pc[9, 9] = A9_4*U9_4 + A9_5*U9_5 + A9_6*U9_6
    Pc[9, 10] = 0.0
    Pc[10, 9] = 0.0
    Pc[9, 11] = _t35
    Pc[11, 9] = _t35
    Pc[10, 10] = 0.0
    Pc[10, 11] = 0.0
    Pc[11, 10] = 0.0
    Pc[11, 11] = A11_4*U11_4 + A11_5*U11_5 + A11_6*U11_6


@nb.njit(cache=True)
def state_of_common(c, Pc, s, p):
    """A Gaussian in the common coordinates (c, Pc (12 × 12, upper triangle read)) as the model's: the internal state
    s = state_from_physical(common_to_state(c)) and p = J Pc Jᵀ packed, J = ∂ε/∂c (common_jacobian) at c.
    """
    c0 = c[0]
    c1 = c[1]
    c2 = c[2]
    c3 = c[3]
    c4 = c[4]
    c5 = c[5]
    c6 = c[6]
    c7 = c[7]
    c8 = c[8]
    c9 = c[9]
    c10 = c[10]
    c11 = c[11]
    pc0_0 = Pc[0, 0]
    pc0_1 = Pc[0, 1]
    pc0_2 = Pc[0, 2]
    pc0_3 = Pc[0, 3]
    pc0_4 = Pc[0, 4]
    pc0_5 = Pc[0, 5]
    pc0_6 = Pc[0, 6]
    pc0_7 = Pc[0, 7]
    pc0_8 = Pc[0, 8]
    pc0_9 = Pc[0, 9]
    pc0_10 = Pc[0, 10]
    pc0_11 = Pc[0, 11]
    pc1_1 = Pc[1, 1]
    pc1_2 = Pc[1, 2]
    pc1_3 = Pc[1, 3]
    pc1_4 = Pc[1, 4]
    pc1_5 = Pc[1, 5]
    pc1_6 = Pc[1, 6]
    pc1_7 = Pc[1, 7]
    pc1_8 = Pc[1, 8]
    pc1_9 = Pc[1, 9]
    pc1_10 = Pc[1, 10]
    pc1_11 = Pc[1, 11]
    pc2_2 = Pc[2, 2]
    pc2_3 = Pc[2, 3]
    pc2_4 = Pc[2, 4]
    pc2_5 = Pc[2, 5]
    pc2_6 = Pc[2, 6]
    pc2_7 = Pc[2, 7]
    pc2_8 = Pc[2, 8]
    pc2_9 = Pc[2, 9]
    pc2_10 = Pc[2, 10]
    pc2_11 = Pc[2, 11]
    pc3_3 = Pc[3, 3]
    pc3_4 = Pc[3, 4]
    pc3_5 = Pc[3, 5]
    pc3_6 = Pc[3, 6]
    pc3_7 = Pc[3, 7]
    pc3_8 = Pc[3, 8]
    pc3_9 = Pc[3, 9]
    pc3_10 = Pc[3, 10]
    pc3_11 = Pc[3, 11]
    pc4_4 = Pc[4, 4]
    pc4_5 = Pc[4, 5]
    pc4_6 = Pc[4, 6]
    pc4_7 = Pc[4, 7]
    pc4_8 = Pc[4, 8]
    pc4_9 = Pc[4, 9]
    pc4_10 = Pc[4, 10]
    pc4_11 = Pc[4, 11]
    pc5_5 = Pc[5, 5]
    pc5_6 = Pc[5, 6]
    pc5_7 = Pc[5, 7]
    pc5_8 = Pc[5, 8]
    pc5_9 = Pc[5, 9]
    pc5_10 = Pc[5, 10]
    pc5_11 = Pc[5, 11]
    pc6_6 = Pc[6, 6]
    pc6_7 = Pc[6, 7]
    pc6_8 = Pc[6, 8]
    pc6_9 = Pc[6, 9]
    pc6_10 = Pc[6, 10]
    pc6_11 = Pc[6, 11]
    pc7_7 = Pc[7, 7]
    pc7_8 = Pc[7, 8]
    pc7_9 = Pc[7, 9]
    pc7_10 = Pc[7, 10]
    pc7_11 = Pc[7, 11]
    pc8_8 = Pc[8, 8]
    pc8_9 = Pc[8, 9]
    pc8_10 = Pc[8, 10]
    pc8_11 = Pc[8, 11]
    pc9_9 = Pc[9, 9]
    pc9_10 = Pc[9, 10]
    pc9_11 = Pc[9, 11]
    pc10_10 = Pc[10, 10]
    pc10_11 = Pc[10, 11]
    pc11_11 = Pc[11, 11]
    _sin_c3 = math.sin(c3)
    _cos_c3 = math.cos(c3)
    _sin_c4 = math.sin(c4)
    _cos_c4 = math.cos(c4)
    _sin_c5 = math.sin(c5)
    _cos_c5 = math.cos(c5)
    _t0 = _cos_c4*c6
    _t1 = _cos_c3*_cos_c5
    _t2 = _sin_c3*_sin_c5
    _t3 = _cos_c3*_sin_c5
    _t4 = _sin_c5*_t0 + c7*(_sin_c4*_t2 + _t1) + c8*(-(_cos_c5*_sin_c3) + _sin_c4*_t3)
    _t5 = _cos_c5*_t0 + c7*(_cos_c5*_sin_c3*_sin_c4 - _t3) + c8*(_sin_c4*_t1 + _t2)
    _t6 = _cos_c3*_cos_c4
    _t7 = _cos_c4*_sin_c3
    xp_x = c0
    xp_y = c1
    xp_z = c2
    xp_psi = math.atan2(_t4, _t5)
    xp_v = math.sqrt(_t4*_t4 + _t5*_t5)
    xp_omega = -(_sin_c4*c9) + _t6*c11 + _t7*c10
    xp_v_up = -(_sin_c4*c6) + _t6*c8 + _t7*c7
    _t8 = _cos_c5*_sin_c3
    _t9 = _cos_c3*_sin_c5
    _t10 = _sin_c4*_t9
    _t11 = _t10 - _t8
    _t12 = _t11*c7
    _t13 = _cos_c3*_cos_c5
    _t14 = _sin_c3*_sin_c5
    _t15 = _sin_c4*_t14
    _t16 = _t13 + _t15
    _t17 = -_t16
    _t18 = _t17*c8
    _t19 = _cos_c4*c6
    _t20 = _cos_c5*_t19
    _t21 = _sin_c4*_t13
    _t22 = _t14 + _t21
    _t23 = _t22*c8
    _t24 = -(_cos_c5*_sin_c3*_sin_c4) + _t9
    _t25 = -_t24
    _t26 = _t25*c7
    _t27 = _t20 + _t23 + _t26
    _t28 = _t27*_t27
    _t29 = _sin_c5*_t19
    _t30 = _t11*c8 + _t16*c7 + _t29
    _t31 = _t28 + _t30*_t30
    _t32 = 1.0/_t31
    _t33 = _t27*_t32
    _t34 = _t22*c7
    _t35 = _t24*c8
    _t36 = -(_t30*_t32)
    _t37 = _sin_c4*c6
    _t38 = _sin_c5*_t37
    _t39 = _cos_c4*c8
    _t40 = _cos_c4*c7
    _t41 = _cos_c5*_t37
    _t42 = -(_t11*c8)
    _t43 = _t17*c7
    _t44 = _cos_c4*_sin_c5
    _t45 = _cos_c4*_cos_c5
    _t46 = 1.0/math.sqrt(_t31)
    _t47 = _t27/2.0
    _t48 = _t30/2.0
    _t49 = 2.0*_t13
    _t50 = 2.0*_t8
    _t51 = 2.0*_t9
    _t52 = 2.0*_t14
    _t53 = _cos_c3*_sin_c4
    _t54 = _sin_c3*_sin_c4
    _t55 = -_sin_c4
    _t56 = _cos_c4*_sin_c3
    _t57 = _cos_c3*_cos_c4
    J3_3 = _t33*(_t12 + _t18) + _t36*(_t34 + _t35)
    J3_4 = _t33*(_t14*_t40 - _t38 + _t39*_t9) + _t36*(_t13*_t39 + _t40*_t8 - _t41)
    J3_5 = _t28*_t32 + _t36*(-_t29 + _t42 + _t43)
    J3_6 = _t33*_t44 + _t36*_t45
    J3_7 = _t16*_t33 + _t25*_t36
    J3_8 = _t11*_t33 + _t22*_t36
    J4_3 = _t46*(_t47*(2.0*_t34 + 2.0*_t35) + _t48*(2.0*_t12 + 2.0*_t18))
    J4_4 = _t46*(_t47*(_t39*_t49 + _t40*_t50 - 2.0*_t41) + _t48*(-(2.0*_t38) + _t39*_t51 + _t40*_t52))
    J4_5 = _t46*(_t47*(-(2.0*_t29) + 2.0*_t42 + 2.0*_t43) + _t48*(2.0*_t20 + 2.0*_t23 + 2.0*_t26))
    J4_6 = _t46*(_t27*_t45 + _t30*_t44)
    J4_7 = _t46*(_t47*(2.0*_cos_c5*_sin_c3*_sin_c4 - _t51) + _t48*(2.0*_t15 + _t49))
    J4_8 = _t46*(_t47*(2.0*_t21 + _t52) + _t48*(2.0*_t10 - _t50))
    J5_3 = _cos_c4*(_cos_c3*c10 - _sin_c3*c11)
    J5_4 = -(_cos_c4*c9) - _t53*c11 - _t54*c10
    J5_9 = _t55
    J5_10 = _t56
    J5_11 = _t57
    J6_3 = _cos_c4*(_cos_c3*c7 - _sin_c3*c8)
    J6_4 = -_t19 - _t53*c8 - _t54*c7
    J6_6 = _t55
    J6_7 = _t56
    J6_8 = _t57
    V3_3 = J3_3*pc3_3 + J3_4*pc3_4 + J3_5*pc3_5 + J3_6*pc3_6 + J3_7*pc3_7 + J3_8*pc3_8
    V3_4 = J3_3*pc3_4 + J3_4*pc4_4 + J3_5*pc4_5 + J3_6*pc4_6 + J3_7*pc4_7 + J3_8*pc4_8
    V3_5 = J3_3*pc3_5 + J3_4*pc4_5 + J3_5*pc5_5 + J3_6*pc5_6 + J3_7*pc5_7 + J3_8*pc5_8
    V3_6 = J3_3*pc3_6 + J3_4*pc4_6 + J3_5*pc5_6 + J3_6*pc6_6 + J3_7*pc6_7 + J3_8*pc6_8
    V3_7 = J3_3*pc3_7 + J3_4*pc4_7 + J3_5*pc5_7 + J3_6*pc6_7 + J3_7*pc7_7 + J3_8*pc7_8
    V3_8 = J3_3*pc3_8 + J3_4*pc4_8 + J3_5*pc5_8 + J3_6*pc6_8 + J3_7*pc7_8 + J3_8*pc8_8
    V3_9 = J3_3*pc3_9 + J3_4*pc4_9 + J3_5*pc5_9 + J3_6*pc6_9 + J3_7*pc7_9 + J3_8*pc8_9
    V3_10 = J3_3*pc3_10 + J3_4*pc4_10 + J3_5*pc5_10 + J3_6*pc6_10 + J3_7*pc7_10 + J3_8*pc8_10
    V3_11 = J3_3*pc3_11 + J3_4*pc4_11 + J3_5*pc5_11 + J3_6*pc6_11 + J3_7*pc7_11 + J3_8*pc8_11
    V4_3 = J4_3*pc3_3 + J4_4*pc3_4 + J4_5*pc3_5 + J4_6*pc3_6 + J4_7*pc3_7 + J4_8*pc3_8
    V4_4 = J4_3*pc3_4 + J4_4*pc4_4 + J4_5*pc4_5 + J4_6*pc4_6 + J4_7*pc4_7 + J4_8*pc4_8
    V4_5 = J4_3*pc3_5 + J4_4*pc4_5 + J4_5*pc5_5 + J4_6*pc5_6 + J4_7*pc5_7 + J4_8*pc5_8
    V4_6 = J4_3*pc3_6 + J4_4*pc4_6 + J4_5*pc5_6 + J4_6*pc6_6 + J4_7*pc6_7 + J4_8*pc6_8
    V4_7 = J4_3*pc3_7 + J4_4*pc4_7 + J4_5*pc5_7 + J4_6*pc6_7 + J4_7*pc7_7 + J4_8*pc7_8
    V4_8 = J4_3*pc3_8 + J4_4*pc4_8 + J4_5*pc5_8 + J4_6*pc6_8 + J4_7*pc7_8 + J4_8*pc8_8
    V4_9 = J4_3*pc3_9 + J4_4*pc4_9 + J4_5*pc5_9 + J4_6*pc6_9 + J4_7*pc7_9 + J4_8*pc8_9
    V4_10 = J4_3*pc3_10 + J4_4*pc4_10 + J4_5*pc5_10 + J4_6*pc6_10 + J4_7*pc7_10 + J4_8*pc8_10
    V4_11 = J4_3*pc3_11 + J4_4*pc4_11 + J4_5*pc5_11 + J4_6*pc6_11 + J4_7*pc7_11 + J4_8*pc8_11
    V5_3 = J5_10*pc3_10 + J5_11*pc3_11 + J5_3*pc3_3 + J5_4*pc3_4 + J5_9*pc3_9
    V5_4 = J5_10*pc4_10 + J5_11*pc4_11 + J5_3*pc3_4 + J5_4*pc4_4 + J5_9*pc4_9
    V5_6 = J5_10*pc6_10 + J5_11*pc6_11 + J5_3*pc3_6 + J5_4*pc4_6 + J5_9*pc6_9
    V5_7 = J5_10*pc7_10 + J5_11*pc7_11 + J5_3*pc3_7 + J5_4*pc4_7 + J5_9*pc7_9
    V5_8 = J5_10*pc8_10 + J5_11*pc8_11 + J5_3*pc3_8 + J5_4*pc4_8 + J5_9*pc8_9
    V5_9 = J5_10*pc9_10 + J5_11*pc9_11 + J5_3*pc3_9 + J5_4*pc4_9 + J5_9*pc9_9
    V5_10 = J5_10*pc10_10 + J5_11*pc10_11 + J5_3*pc3_10 + J5_4*pc4_10 + J5_9*pc9_10
    V5_11 = J5_10*pc10_11 + J5_11*pc11_11 + J5_3*pc3_11 + J5_4*pc4_11 + J5_9*pc9_11
    V6_3 = J6_3*pc3_3 + J6_4*pc3_4 + J6_6*pc3_6 + J6_7*pc3_7 + J6_8*pc3_8
    V6_4 = J6_3*pc3_4 + J6_4*pc4_4 + J6_6*pc4_6 + J6_7*pc4_7 + J6_8*pc4_8
    V6_6 = J6_3*pc3_6 + J6_4*pc4_6 + J6_6*pc6_6 + J6_7*pc6_7 + J6_8*pc6_8
    V6_7 = J6_3*pc3_7 + J6_4*pc4_7 + J6_6*pc6_7 + J6_7*pc7_7 + J6_8*pc7_8
    V6_8 = J6_3*pc3_8 + J6_4*pc4_8 + J6_6*pc6_8 + J6_7*pc7_8 + J6_8*pc8_8
    s[0] = xp_x
    s[1] = xp_y
    s[2] = xp_z
    s[3] = xp_psi
    s[4] = xp_v
    s[5] = xp_omega
    s[6] = xp_v_up
    p[0] = pc0_0
    p[1] = pc0_1
    p[2] = pc0_2
    p[3] = J3_3*pc0_3 + J3_4*pc0_4 + J3_5*pc0_5 + J3_6*pc0_6 + J3_7*pc0_7 + J3_8*pc0_8
    p[4] = J4_3*pc0_3 + J4_4*pc0_4 + J4_5*pc0_5 + J4_6*pc0_6 + J4_7*pc0_7 + J4_8*pc0_8
    p[5] = J5_10*pc0_10 + J5_11*pc0_11 + J5_3*pc0_3 + J5_4*pc0_4 + J5_9*pc0_9
    p[6] = J6_3*pc0_3 + J6_4*pc0_4 + J6_6*pc0_6 + J6_7*pc0_7 + J6_8*pc0_8
    p[7] = pc1_1
    p[8] = pc1_2
    p[9] = J3_3*pc1_3 + J3_4*pc1_4 + J3_5*pc1_5 + J3_6*pc1_6 + J3_7*pc1_7 + J3_8*pc1_8
    p[10] = J4_3*pc1_3 + J4_4*pc1_4 + J4_5*pc1_5 + J4_6*pc1_6 + J4_7*pc1_7 + J4_8*pc1_8
    p[11] = J5_10*pc1_10 + J5_11*pc1_11 + J5_3*pc1_3 + J5_4*pc1_4 + J5_9*pc1_9
    p[12] = J6_3*pc1_3 + J6_4*pc1_4 + J6_6*pc1_6 + J6_7*pc1_7 + J6_8*pc1_8
    p[13] = pc2_2
    p[14] = J3_3*pc2_3 + J3_4*pc2_4 + J3_5*pc2_5 + J3_6*pc2_6 + J3_7*pc2_7 + J3_8*pc2_8
    p[15] = J4_3*pc2_3 + J4_4*pc2_4 + J4_5*pc2_5 + J4_6*pc2_6 + J4_7*pc2_7 + J4_8*pc2_8
    p[16] = J5_10*pc2_10 + J5_11*pc2_11 + J5_3*pc2_3 + J5_4*pc2_4 + J5_9*pc2_9
    p[17] = J6_3*pc2_3 + J6_4*pc2_4 + J6_6*pc2_6 + J6_7*pc2_7 + J6_8*pc2_8
    p[18] = J3_3*V3_3 + J3_4*V3_4 + J3_5*V3_5 + J3_6*V3_6 + J3_7*V3_7 + J3_8*V3_8
    p[19] = J4_3*V3_3 + J4_4*V3_4 + J4_5*V3_5 + J4_6*V3_6 + J4_7*V3_7 + J4_8*V3_8
    p[20] = J5_10*V3_10 + J5_11*V3_11 + J5_3*V3_3 + J5_4*V3_4 + J5_9*V3_9
    p[21] = J6_3*V3_3 + J6_4*V3_4 + J6_6*V3_6 + J6_7*V3_7 + J6_8*V3_8
    p[22] = J4_3*V4_3 + J4_4*V4_4 + J4_5*V4_5 + J4_6*V4_6 + J4_7*V4_7 + J4_8*V4_8
    p[23] = J5_10*V4_10 + J5_11*V4_11 + J5_3*V4_3 + J5_4*V4_4 + J5_9*V4_9
    p[24] = J6_3*V4_3 + J6_4*V4_4 + J6_6*V4_6 + J6_7*V4_7 + J6_8*V4_8
    p[25] = J5_10*V5_10 + J5_11*V5_11 + J5_3*V5_3 + J5_4*V5_4 + J5_9*V5_9
    p[26] = J6_3*V5_3 + J6_4*V5_4 + J6_6*V5_6 + J6_7*V5_7 + J6_8*V5_8
    p[27] = J6_3*V6_3 + J6_4*V6_4 + J6_6*V6_6 + J6_7*V6_7 + J6_8*V6_8


@nb.njit(cache=True, error_model="numpy")
def between_add_at(ws, js, jt, w, jacc):
    """acc += w·[log_G(μ_s^-1 μ_t)]^∨ (a term of the iterated mean μ ← μ·exp(Σ w_i d_i); d as ``between``).
    On rows of ws: s = ws[js], t = ws[jt], acc = ws[jacc] (derive/codegen/imm_rows.py).
    """
    x = ws[js, 0]
    y = ws[js, 1]
    z = ws[js, 2]
    psi = ws[js, 3]
    v = ws[js, 4]
    omega = ws[js, 5]
    v_up = ws[js, 6]
    t_x = ws[jt, 0]
    t_y = ws[jt, 1]
    t_z = ws[jt, 2]
    t_psi = ws[jt, 3]
    t_v = ws[jt, 4]
    t_omega = ws[jt, 5]
    t_v_up = ws[jt, 6]
    acc0 = ws[jacc, 0]
    acc1 = ws[jacc, 1]
    acc2 = ws[jacc, 2]
    acc3 = ws[jacc, 3]
    acc4 = ws[jacc, 4]
    acc5 = ws[jacc, 5]
    acc6 = ws[jacc, 6]
    d0 = t_x - x
    d1 = t_y - y
    d2 = t_z - z
    d3 = wrap_angle(-psi + t_psi)
    d4 = t_v - v
    d5 = -omega + t_omega
    d6 = t_v_up - v_up
    ws[jacc, 0] = acc0 + d0*w
    ws[jacc, 1] = acc1 + d1*w
    ws[jacc, 2] = acc2 + d2*w
    ws[jacc, 3] = acc3 + d3*w
    ws[jacc, 4] = acc4 + d4*w
    ws[jacc, 5] = acc5 + d5*w
    ws[jacc, 6] = acc6 + d6*w


@nb.njit(cache=True, error_model="numpy")
def mix_transport_at(ws, js, jt, jpt, w, jacc):
    """acc (packed upper triangle) += w·[Φ(d)^-1 P_t Φ(d)^-T + d dᵀ], d = [log_G(μ_s^-1 μ_t)]^∨, P_t = unpack(pt):
    one source's term of a mixture's covariance about the mean μ_s (X = μ_t·exp ε_t = μ_s·exp(d + Φ(d)^-1 ε_t)
    to first order; lgekf.estimators.imm.kernels). Straight line over the non-zero entries of Φ^-1.
    On rows of ws: s = ws[js], t = ws[jt], pt = ws[jpt], acc = ws[jacc] (derive/codegen/imm_rows.py).
    """
    x = ws[js, 0]
    y = ws[js, 1]
    z = ws[js, 2]
    psi = ws[js, 3]
    v = ws[js, 4]
    omega = ws[js, 5]
    v_up = ws[js, 6]
    t_x = ws[jt, 0]
    t_y = ws[jt, 1]
    t_z = ws[jt, 2]
    t_psi = ws[jt, 3]
    t_v = ws[jt, 4]
    t_omega = ws[jt, 5]
    t_v_up = ws[jt, 6]
    pt0_0 = ws[jpt, 0]
    pt0_1 = ws[jpt, 1]
    pt0_2 = ws[jpt, 2]
    pt0_3 = ws[jpt, 3]
    pt0_4 = ws[jpt, 4]
    pt0_5 = ws[jpt, 5]
    pt0_6 = ws[jpt, 6]
    pt1_1 = ws[jpt, 7]
    pt1_2 = ws[jpt, 8]
    pt1_3 = ws[jpt, 9]
    pt1_4 = ws[jpt, 10]
    pt1_5 = ws[jpt, 11]
    pt1_6 = ws[jpt, 12]
    pt2_2 = ws[jpt, 13]
    pt2_3 = ws[jpt, 14]
    pt2_4 = ws[jpt, 15]
    pt2_5 = ws[jpt, 16]
    pt2_6 = ws[jpt, 17]
    pt3_3 = ws[jpt, 18]
    pt3_4 = ws[jpt, 19]
    pt3_5 = ws[jpt, 20]
    pt3_6 = ws[jpt, 21]
    pt4_4 = ws[jpt, 22]
    pt4_5 = ws[jpt, 23]
    pt4_6 = ws[jpt, 24]
    pt5_5 = ws[jpt, 25]
    pt5_6 = ws[jpt, 26]
    pt6_6 = ws[jpt, 27]
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
    acc21 = ws[jacc, 21]
    acc22 = ws[jacc, 22]
    acc23 = ws[jacc, 23]
    acc24 = ws[jacc, 24]
    acc25 = ws[jacc, 25]
    acc26 = ws[jacc, 26]
    acc27 = ws[jacc, 27]
    d0 = t_x - x
    d1 = t_y - y
    d2 = t_z - z
    d3 = wrap_angle(-psi + t_psi)
    d4 = t_v - v
    d5 = -omega + t_omega
    d6 = t_v_up - v_up
    ws[jacc, 0] = acc0 + w*(d0*d0 + pt0_0)
    ws[jacc, 1] = acc1 + w*(d0*d1 + pt0_1)
    ws[jacc, 2] = acc2 + w*(d0*d2 + pt0_2)
    ws[jacc, 3] = acc3 + w*(d0*d3 + pt0_3)
    ws[jacc, 4] = acc4 + w*(d0*d4 + pt0_4)
    ws[jacc, 5] = acc5 + w*(d0*d5 + pt0_5)
    ws[jacc, 6] = acc6 + w*(d0*d6 + pt0_6)
    ws[jacc, 7] = acc7 + w*(d1*d1 + pt1_1)
    ws[jacc, 8] = acc8 + w*(d1*d2 + pt1_2)
    ws[jacc, 9] = acc9 + w*(d1*d3 + pt1_3)
    ws[jacc, 10] = acc10 + w*(d1*d4 + pt1_4)
    ws[jacc, 11] = acc11 + w*(d1*d5 + pt1_5)
    ws[jacc, 12] = acc12 + w*(d1*d6 + pt1_6)
    ws[jacc, 13] = acc13 + w*(d2*d2 + pt2_2)
    ws[jacc, 14] = acc14 + w*(d2*d3 + pt2_3)
    ws[jacc, 15] = acc15 + w*(d2*d4 + pt2_4)
    ws[jacc, 16] = acc16 + w*(d2*d5 + pt2_5)
    ws[jacc, 17] = acc17 + w*(d2*d6 + pt2_6)
    ws[jacc, 18] = acc18 + w*(d3*d3 + pt3_3)
    ws[jacc, 19] = acc19 + w*(d3*d4 + pt3_4)
    ws[jacc, 20] = acc20 + w*(d3*d5 + pt3_5)
    ws[jacc, 21] = acc21 + w*(d3*d6 + pt3_6)
    ws[jacc, 22] = acc22 + w*(d4*d4 + pt4_4)
    ws[jacc, 23] = acc23 + w*(d4*d5 + pt4_5)
    ws[jacc, 24] = acc24 + w*(d4*d6 + pt4_6)
    ws[jacc, 25] = acc25 + w*(d5*d5 + pt5_5)
    ws[jacc, 26] = acc26 + w*(d5*d6 + pt5_6)
    ws[jacc, 27] = acc27 + w*(d6*d6 + pt6_6)


@nb.njit(cache=True, error_model="numpy")
def retract_at(ws, js, jeps):
    """μ ← μ·exp([ε]^∧) in place (right perturbation; the update's eq:up_mu for a given ε).
    On rows of ws: s = ws[js], eps = ws[jeps] (derive/codegen/imm_rows.py).
    """
    x = ws[js, 0]
    y = ws[js, 1]
    z = ws[js, 2]
    psi = ws[js, 3]
    v = ws[js, 4]
    omega = ws[js, 5]
    v_up = ws[js, 6]
    eps0 = ws[jeps, 0]
    eps1 = ws[jeps, 1]
    eps2 = ws[jeps, 2]
    eps3 = ws[jeps, 3]
    eps4 = ws[jeps, 4]
    eps5 = ws[jeps, 5]
    eps6 = ws[jeps, 6]
    ws[js, 0] = eps0 + x
    ws[js, 1] = eps1 + y
    ws[js, 2] = eps2 + z
    ws[js, 3] = eps3 + psi
    ws[js, 4] = eps4 + v
    ws[js, 5] = eps5 + omega
    ws[js, 6] = eps6 + v_up


@nb.njit(cache=True, error_model="numpy")
def common_of_state_at(ws, js, jp, jc, jPc):
    """A mode's Gaussian in the common coordinates: c = (x, y, z, roll, pitch, yaw, v_x, v_y, v_z, ω_x, ω_y, ω_z) of the internal state s (as
    physical_to_common(physical(s))) and Pc = A P Aᵀ (12 × 12), A = ∂c/∂ε (physical_to_common_jacobian) at s.
    On rows of ws: s = ws[js], p = ws[jp], c = ws[jc], Pc = ws[jPc] (derive/codegen/imm_rows.py).
    """
    x = ws[js, 0]
    y = ws[js, 1]
    z = ws[js, 2]
    psi = ws[js, 3]
    v = ws[js, 4]
    omega = ws[js, 5]
    v_up = ws[js, 6]
    p0_0 = ws[jp, 0]
    p0_1 = ws[jp, 1]
    p0_2 = ws[jp, 2]
    p0_3 = ws[jp, 3]
    p0_4 = ws[jp, 4]
    p0_5 = ws[jp, 5]
    p0_6 = ws[jp, 6]
    p1_1 = ws[jp, 7]
    p1_2 = ws[jp, 8]
    p1_3 = ws[jp, 9]
    p1_4 = ws[jp, 10]
    p1_5 = ws[jp, 11]
    p1_6 = ws[jp, 12]
    p2_2 = ws[jp, 13]
    p2_3 = ws[jp, 14]
    p2_4 = ws[jp, 15]
    p2_5 = ws[jp, 16]
    p2_6 = ws[jp, 17]
    p3_3 = ws[jp, 18]
    p3_4 = ws[jp, 19]
    p3_5 = ws[jp, 20]
    p3_6 = ws[jp, 21]
    p4_4 = ws[jp, 22]
    p4_5 = ws[jp, 23]
    p4_6 = ws[jp, 24]
    p5_5 = ws[jp, 25]
    p5_6 = ws[jp, 26]
    p6_6 = ws[jp, 27]
    xp_x = x
    xp_y = y
    xp_z = z
    xp_psi = wrap_angle(psi)
    xp_v = v
    xp_omega = omega
    xp_v_up = v_up
    _t0 = xp_v*xp_v
    _t1 = xp_v_up*xp_v_up
    _t2 = _t0 + _t1
    _t3 = 1.0/_t2
    _t4 = abs(xp_v)
    _t5 = xp_v*xp_v_up
    _t6 = 1.0/math.sqrt(_t2)
    _t7 = _t6*xp_v
    _t8 = _t6*xp_v_up
    _t9 = (1.0/(_t2*math.sqrt(_t2)))*xp_omega
    _t10 = -(_t5*_t9)
    A4_4 = _t3*_t5/_t4
    A4_6 = -(_t3*_t4)
    A6_4 = _t7
    A6_6 = _t8
    A9_4 = _t10
    A9_5 = _t8
    A9_6 = _t0*_t9
    A11_4 = _t1*_t9
    A11_5 = _t7
    A11_6 = _t10
    U4_3 = A4_4*p3_4 + A4_6*p3_6
    U4_4 = A4_4*p4_4 + A4_6*p4_6
    U4_5 = A4_4*p4_5 + A4_6*p5_6
    U4_6 = A4_4*p4_6 + A4_6*p6_6
    U6_4 = A6_4*p4_4 + A6_6*p4_6
    U6_5 = A6_4*p4_5 + A6_6*p5_6
    U6_6 = A6_4*p4_6 + A6_6*p6_6
    U9_4 = A9_4*p4_4 + A9_5*p4_5 + A9_6*p4_6
    U9_5 = A9_4*p4_5 + A9_5*p5_5 + A9_6*p5_6
    U9_6 = A9_4*p4_6 + A9_5*p5_6 + A9_6*p6_6
    U11_4 = A11_4*p4_4 + A11_5*p4_5 + A11_6*p4_6
    U11_5 = A11_4*p4_5 + A11_5*p5_5 + A11_6*p5_6
    U11_6 = A11_4*p4_6 + A11_5*p5_6 + A11_6*p6_6
    _sin_xp_psi = math.sin(xp_psi)
    _cos_xp_psi = math.cos(xp_psi)
    _t11 = xp_v*xp_v
    _t12 = (_cos_xp_psi*_cos_xp_psi)*_t11 + (_sin_xp_psi*_sin_xp_psi)*_t11
    _t13 = xp_v_up*xp_v_up
    _t14 = xp_omega*(1.0/math.sqrt(_t11 + _t13))
    _t15 = A4_4*p0_4 + A4_6*p0_6
    _t16 = A6_4*p0_4 + A6_6*p0_6
    _t17 = A9_4*p0_4 + A9_5*p0_5 + A9_6*p0_6
    _t18 = A11_4*p0_4 + A11_5*p0_5 + A11_6*p0_6
    _t19 = A4_4*p1_4 + A4_6*p1_6
    _t20 = A6_4*p1_4 + A6_6*p1_6
    _t21 = A9_4*p1_4 + A9_5*p1_5 + A9_6*p1_6
    _t22 = A11_4*p1_4 + A11_5*p1_5 + A11_6*p1_6
    _t23 = A4_4*p2_4 + A4_6*p2_6
    _t24 = A6_4*p2_4 + A6_6*p2_6
    _t25 = A9_4*p2_4 + A9_5*p2_5 + A9_6*p2_6
    _t26 = A11_4*p2_4 + A11_5*p2_5 + A11_6*p2_6
    _t27 = A6_4*U4_4 + A6_6*U4_6
    _t28 = A9_4*U4_4 + A9_5*U4_5 + A9_6*U4_6
    _t29 = A11_4*U4_4 + A11_5*U4_5 + A11_6*U4_6
    _t30 = A6_4*p3_4 + A6_6*p3_6
    _t31 = A9_4*p3_4 + A9_5*p3_5 + A9_6*p3_6
    _t32 = A11_4*p3_4 + A11_5*p3_5 + A11_6*p3_6
    _t33 = A9_4*U6_4 + A9_5*U6_5 + A9_6*U6_6
    _t34 = A11_4*U6_4 + A11_5*U6_5 + A11_6*U6_6
    _t35 = A11_4*U9_4 + A11_5*U9_5 + A11_6*U9_6
    ws[jc, 0] = xp_x
    ws[jc, 1] = xp_y
    ws[jc, 2] = xp_z
    ws[jc, 3] = 0.0
    ws[jc, 4] = math.atan2(-xp_v_up, math.sqrt(_t12))
    ws[jc, 5] = math.atan2(_sin_xp_psi*xp_v, _cos_xp_psi*xp_v)
    ws[jc, 6] = math.sqrt(_t12 + _t13)
    ws[jc, 7] = 0.0
    ws[jc, 8] = 0.0
    ws[jc, 9] = _t14*xp_v_up
    ws[jc, 10] = 0.0
    ws[jc, 11] = _t14*xp_v
    ws[jPc, 0] = p0_0
    ws[jPc, 1] = p0_1
    ws[jPc, 12] = p0_1
    ws[jPc, 2] = p0_2
    ws[jPc, 24] = p0_2
    ws[jPc, 3] = 0.0
    ws[jPc, 36] = 0.0
    ws[jPc, 4] = _t15
    ws[jPc, 48] = _t15
    ws[jPc, 5] = p0_3
    ws[jPc, 60] = p0_3
    ws[jPc, 6] = _t16
    ws[jPc, 72] = _t16
    ws[jPc, 7] = 0.0
    ws[jPc, 84] = 0.0
    ws[jPc, 8] = 0.0
    ws[jPc, 96] = 0.0
    ws[jPc, 9] = _t17
    ws[jPc, 108] = _t17
    ws[jPc, 10] = 0.0
    ws[jPc, 120] = 0.0
    ws[jPc, 11] = _t18
    ws[jPc, 132] = _t18
    ws[jPc, 13] = p1_1
    ws[jPc, 14] = p1_2
    ws[jPc, 25] = p1_2
    ws[jPc, 15] = 0.0
    ws[jPc, 37] = 0.0
    ws[jPc, 16] = _t19
    ws[jPc, 49] = _t19
    ws[jPc, 17] = p1_3
    ws[jPc, 61] = p1_3
    ws[jPc, 18] = _t20
    ws[jPc, 73] = _t20
    ws[jPc, 19] = 0.0
    ws[jPc, 85] = 0.0
    ws[jPc, 20] = 0.0
    ws[jPc, 97] = 0.0
    ws[jPc, 21] = _t21
    ws[jPc, 109] = _t21
    ws[jPc, 22] = 0.0
    ws[jPc, 121] = 0.0
    ws[jPc, 23] = _t22
    ws[jPc, 133] = _t22
    ws[jPc, 26] = p2_2
    ws[jPc, 27] = 0.0
    ws[jPc, 38] = 0.0
    ws[jPc, 28] = _t23
    ws[jPc, 50] = _t23
    ws[jPc, 29] = p2_3
    ws[jPc, 62] = p2_3
    ws[jPc, 30] = _t24
    ws[jPc, 74] = _t24
    ws[jPc, 31] = 0.0
    ws[jPc, 86] = 0.0
    ws[jPc, 32] = 0.0
    ws[jPc, 98] = 0.0
    ws[jPc, 33] = _t25
    ws[jPc, 110] = _t25
    ws[jPc, 34] = 0.0
    ws[jPc, 122] = 0.0
    ws[jPc, 35] = _t26
    ws[jPc, 134] = _t26
    ws[jPc, 39] = 0.0
    ws[jPc, 40] = 0.0
    ws[jPc, 51] = 0.0
    ws[jPc, 41] = 0.0
    ws[jPc, 63] = 0.0
    ws[jPc, 42] = 0.0
    ws[jPc, 75] = 0.0
    ws[jPc, 43] = 0.0
    ws[jPc, 87] = 0.0
    ws[jPc, 44] = 0.0
    ws[jPc, 99] = 0.0
    ws[jPc, 45] = 0.0
    ws[jPc, 111] = 0.0
    ws[jPc, 46] = 0.0
    ws[jPc, 123] = 0.0
    ws[jPc, 47] = 0.0
    ws[jPc, 135] = 0.0
    ws[jPc, 52] = A4_4*U4_4 + A4_6*U4_6
    ws[jPc, 53] = U4_3
    ws[jPc, 64] = U4_3
    ws[jPc, 54] = _t27
    ws[jPc, 76] = _t27
    ws[jPc, 55] = 0.0
    ws[jPc, 88] = 0.0
    ws[jPc, 56] = 0.0
    ws[jPc, 100] = 0.0
    ws[jPc, 57] = _t28
    ws[jPc, 112] = _t28
    ws[jPc, 58] = 0.0
    ws[jPc, 124] = 0.0
    ws[jPc, 59] = _t29
    ws[jPc, 136] = _t29
    ws[jPc, 65] = p3_3
    ws[jPc, 66] = _t30
    ws[jPc, 77] = _t30
    ws[jPc, 67] = 0.0
    ws[jPc, 89] = 0.0
    ws[jPc, 68] = 0.0
    ws[jPc, 101] = 0.0
    ws[jPc, 69] = _t31
    ws[jPc, 113] = _t31
    ws[jPc, 70] = 0.0
    ws[jPc, 125] = 0.0
    ws[jPc, 71] = _t32
    ws[jPc, 137] = _t32
    ws[jPc, 78] = A6_4*U6_4 + A6_6*U6_6
    ws[jPc, 79] = 0.0
    ws[jPc, 90] = 0.0
    ws[jPc, 80] = 0.0
    ws[jPc, 102] = 0.0
    ws[jPc, 81] = _t33
    ws[jPc, 114] = _t33
    ws[jPc, 82] = 0.0
    ws[jPc, 126] = 0.0
    ws[jPc, 83] = _t34
    ws[jPc, 138] = _t34
    ws[jPc, 91] = 0.0
    ws[jPc, 92] = 0.0
    ws[jPc, 103] = 0.0
    ws[jPc, 93] = 0.0
    ws[jPc, 115] = 0.0
    ws[jPc, 94] = 0.0
    ws[jPc, 127] = 0.0
    ws[jPc, 95] = 0.0
    ws[jPc, 139] = 0.0
    ws[jPc, 104] = 0.0
    ws[jPc, 105] = 0.0
    ws[jPc, 116] = 0.0
    ws[jPc, 106] = 0.0
    ws[jPc, 128] = 0.0
    ws[jPc, 107] = 0.0
    ws[jPc, 140] = 0.0
    ws[jPc, 117] = A9_4*U9_4 + A9_5*U9_5 + A9_6*U9_6
    ws[jPc, 118] = 0.0
    ws[jPc, 129] = 0.0
    ws[jPc, 119] = _t35
    ws[jPc, 141] = _t35
    ws[jPc, 130] = 0.0
    ws[jPc, 131] = 0.0
    ws[jPc, 142] = 0.0
    ws[jPc, 143] = A11_4*U11_4 + A11_5*U11_5 + A11_6*U11_6


@nb.njit(cache=True, error_model="numpy")
def state_of_common_at(ws, jc, jPc, js, jp):
    """A Gaussian in the common coordinates (c, Pc (12 × 12, upper triangle read)) as the model's: the internal state
    s = state_from_physical(common_to_state(c)) and p = J Pc Jᵀ packed, J = ∂ε/∂c (common_jacobian) at c.
    On rows of ws: c = ws[jc], Pc = ws[jPc], s = ws[js], p = ws[jp] (derive/codegen/imm_rows.py).
    """
    c0 = ws[jc, 0]
    c1 = ws[jc, 1]
    c2 = ws[jc, 2]
    c3 = ws[jc, 3]
    c4 = ws[jc, 4]
    c5 = ws[jc, 5]
    c6 = ws[jc, 6]
    c7 = ws[jc, 7]
    c8 = ws[jc, 8]
    c9 = ws[jc, 9]
    c10 = ws[jc, 10]
    c11 = ws[jc, 11]
    pc0_0 = ws[jPc, 0]
    pc0_1 = ws[jPc, 1]
    pc0_2 = ws[jPc, 2]
    pc0_3 = ws[jPc, 3]
    pc0_4 = ws[jPc, 4]
    pc0_5 = ws[jPc, 5]
    pc0_6 = ws[jPc, 6]
    pc0_7 = ws[jPc, 7]
    pc0_8 = ws[jPc, 8]
    pc0_9 = ws[jPc, 9]
    pc0_10 = ws[jPc, 10]
    pc0_11 = ws[jPc, 11]
    pc1_1 = ws[jPc, 13]
    pc1_2 = ws[jPc, 14]
    pc1_3 = ws[jPc, 15]
    pc1_4 = ws[jPc, 16]
    pc1_5 = ws[jPc, 17]
    pc1_6 = ws[jPc, 18]
    pc1_7 = ws[jPc, 19]
    pc1_8 = ws[jPc, 20]
    pc1_9 = ws[jPc, 21]
    pc1_10 = ws[jPc, 22]
    pc1_11 = ws[jPc, 23]
    pc2_2 = ws[jPc, 26]
    pc2_3 = ws[jPc, 27]
    pc2_4 = ws[jPc, 28]
    pc2_5 = ws[jPc, 29]
    pc2_6 = ws[jPc, 30]
    pc2_7 = ws[jPc, 31]
    pc2_8 = ws[jPc, 32]
    pc2_9 = ws[jPc, 33]
    pc2_10 = ws[jPc, 34]
    pc2_11 = ws[jPc, 35]
    pc3_3 = ws[jPc, 39]
    pc3_4 = ws[jPc, 40]
    pc3_5 = ws[jPc, 41]
    pc3_6 = ws[jPc, 42]
    pc3_7 = ws[jPc, 43]
    pc3_8 = ws[jPc, 44]
    pc3_9 = ws[jPc, 45]
    pc3_10 = ws[jPc, 46]
    pc3_11 = ws[jPc, 47]
    pc4_4 = ws[jPc, 52]
    pc4_5 = ws[jPc, 53]
    pc4_6 = ws[jPc, 54]
    pc4_7 = ws[jPc, 55]
    pc4_8 = ws[jPc, 56]
    pc4_9 = ws[jPc, 57]
    pc4_10 = ws[jPc, 58]
    pc4_11 = ws[jPc, 59]
    pc5_5 = ws[jPc, 65]
    pc5_6 = ws[jPc, 66]
    pc5_7 = ws[jPc, 67]
    pc5_8 = ws[jPc, 68]
    pc5_9 = ws[jPc, 69]
    pc5_10 = ws[jPc, 70]
    pc5_11 = ws[jPc, 71]
    pc6_6 = ws[jPc, 78]
    pc6_7 = ws[jPc, 79]
    pc6_8 = ws[jPc, 80]
    pc6_9 = ws[jPc, 81]
    pc6_10 = ws[jPc, 82]
    pc6_11 = ws[jPc, 83]
    pc7_7 = ws[jPc, 91]
    pc7_8 = ws[jPc, 92]
    pc7_9 = ws[jPc, 93]
    pc7_10 = ws[jPc, 94]
    pc7_11 = ws[jPc, 95]
    pc8_8 = ws[jPc, 104]
    pc8_9 = ws[jPc, 105]
    pc8_10 = ws[jPc, 106]
    pc8_11 = ws[jPc, 107]
    pc9_9 = ws[jPc, 117]
    pc9_10 = ws[jPc, 118]
    pc9_11 = ws[jPc, 119]
    pc10_10 = ws[jPc, 130]
    pc10_11 = ws[jPc, 131]
    pc11_11 = ws[jPc, 143]
    _sin_c3 = math.sin(c3)
    _cos_c3 = math.cos(c3)
    _sin_c4 = math.sin(c4)
    _cos_c4 = math.cos(c4)
    _sin_c5 = math.sin(c5)
    _cos_c5 = math.cos(c5)
    _t0 = _cos_c4*c6
    _t1 = _cos_c3*_cos_c5
    _t2 = _sin_c3*_sin_c5
    _t3 = _cos_c3*_sin_c5
    _t4 = _sin_c5*_t0 + c7*(_sin_c4*_t2 + _t1) + c8*(-(_cos_c5*_sin_c3) + _sin_c4*_t3)
    _t5 = _cos_c5*_t0 + c7*(_cos_c5*_sin_c3*_sin_c4 - _t3) + c8*(_sin_c4*_t1 + _t2)
    _t6 = _cos_c3*_cos_c4
    _t7 = _cos_c4*_sin_c3
    xp_x = c0
    xp_y = c1
    xp_z = c2
    xp_psi = math.atan2(_t4, _t5)
    xp_v = math.sqrt(_t4*_t4 + _t5*_t5)
    xp_omega = -(_sin_c4*c9) + _t6*c11 + _t7*c10
    xp_v_up = -(_sin_c4*c6) + _t6*c8 + _t7*c7
    _t8 = _cos_c5*_sin_c3
    _t9 = _cos_c3*_sin_c5
    _t10 = _sin_c4*_t9
    _t11 = _t10 - _t8
    _t12 = _t11*c7
    _t13 = _cos_c3*_cos_c5
    _t14 = _sin_c3*_sin_c5
    _t15 = _sin_c4*_t14
    _t16 = _t13 + _t15
    _t17 = -_t16
    _t18 = _t17*c8
    _t19 = _cos_c4*c6
    _t20 = _cos_c5*_t19
    _t21 = _sin_c4*_t13
    _t22 = _t14 + _t21
    _t23 = _t22*c8
    _t24 = -(_cos_c5*_sin_c3*_sin_c4) + _t9
    _t25 = -_t24
    _t26 = _t25*c7
    _t27 = _t20 + _t23 + _t26
    _t28 = _t27*_t27
    _t29 = _sin_c5*_t19
    _t30 = _t11*c8 + _t16*c7 + _t29
    _t31 = _t28 + _t30*_t30
    _t32 = 1.0/_t31
    _t33 = _t27*_t32
    _t34 = _t22*c7
    _t35 = _t24*c8
    _t36 = -(_t30*_t32)
    _t37 = _sin_c4*c6
    _t38 = _sin_c5*_t37
    _t39 = _cos_c4*c8
    _t40 = _cos_c4*c7
    _t41 = _cos_c5*_t37
    _t42 = -(_t11*c8)
    _t43 = _t17*c7
    _t44 = _cos_c4*_sin_c5
    _t45 = _cos_c4*_cos_c5
    _t46 = 1.0/math.sqrt(_t31)
    _t47 = _t27/2.0
    _t48 = _t30/2.0
    _t49 = 2.0*_t13
    _t50 = 2.0*_t8
    _t51 = 2.0*_t9
    _t52 = 2.0*_t14
    _t53 = _cos_c3*_sin_c4
    _t54 = _sin_c3*_sin_c4
    _t55 = -_sin_c4
    _t56 = _cos_c4*_sin_c3
    _t57 = _cos_c3*_cos_c4
    J3_3 = _t33*(_t12 + _t18) + _t36*(_t34 + _t35)
    J3_4 = _t33*(_t14*_t40 - _t38 + _t39*_t9) + _t36*(_t13*_t39 + _t40*_t8 - _t41)
    J3_5 = _t28*_t32 + _t36*(-_t29 + _t42 + _t43)
    J3_6 = _t33*_t44 + _t36*_t45
    J3_7 = _t16*_t33 + _t25*_t36
    J3_8 = _t11*_t33 + _t22*_t36
    J4_3 = _t46*(_t47*(2.0*_t34 + 2.0*_t35) + _t48*(2.0*_t12 + 2.0*_t18))
    J4_4 = _t46*(_t47*(_t39*_t49 + _t40*_t50 - 2.0*_t41) + _t48*(-(2.0*_t38) + _t39*_t51 + _t40*_t52))
    J4_5 = _t46*(_t47*(-(2.0*_t29) + 2.0*_t42 + 2.0*_t43) + _t48*(2.0*_t20 + 2.0*_t23 + 2.0*_t26))
    J4_6 = _t46*(_t27*_t45 + _t30*_t44)
    J4_7 = _t46*(_t47*(2.0*_cos_c5*_sin_c3*_sin_c4 - _t51) + _t48*(2.0*_t15 + _t49))
    J4_8 = _t46*(_t47*(2.0*_t21 + _t52) + _t48*(2.0*_t10 - _t50))
    J5_3 = _cos_c4*(_cos_c3*c10 - _sin_c3*c11)
    J5_4 = -(_cos_c4*c9) - _t53*c11 - _t54*c10
    J5_9 = _t55
    J5_10 = _t56
    J5_11 = _t57
    J6_3 = _cos_c4*(_cos_c3*c7 - _sin_c3*c8)
    J6_4 = -_t19 - _t53*c8 - _t54*c7
    J6_6 = _t55
    J6_7 = _t56
    J6_8 = _t57
    V3_3 = J3_3*pc3_3 + J3_4*pc3_4 + J3_5*pc3_5 + J3_6*pc3_6 + J3_7*pc3_7 + J3_8*pc3_8
    V3_4 = J3_3*pc3_4 + J3_4*pc4_4 + J3_5*pc4_5 + J3_6*pc4_6 + J3_7*pc4_7 + J3_8*pc4_8
    V3_5 = J3_3*pc3_5 + J3_4*pc4_5 + J3_5*pc5_5 + J3_6*pc5_6 + J3_7*pc5_7 + J3_8*pc5_8
    V3_6 = J3_3*pc3_6 + J3_4*pc4_6 + J3_5*pc5_6 + J3_6*pc6_6 + J3_7*pc6_7 + J3_8*pc6_8
    V3_7 = J3_3*pc3_7 + J3_4*pc4_7 + J3_5*pc5_7 + J3_6*pc6_7 + J3_7*pc7_7 + J3_8*pc7_8
    V3_8 = J3_3*pc3_8 + J3_4*pc4_8 + J3_5*pc5_8 + J3_6*pc6_8 + J3_7*pc7_8 + J3_8*pc8_8
    V3_9 = J3_3*pc3_9 + J3_4*pc4_9 + J3_5*pc5_9 + J3_6*pc6_9 + J3_7*pc7_9 + J3_8*pc8_9
    V3_10 = J3_3*pc3_10 + J3_4*pc4_10 + J3_5*pc5_10 + J3_6*pc6_10 + J3_7*pc7_10 + J3_8*pc8_10
    V3_11 = J3_3*pc3_11 + J3_4*pc4_11 + J3_5*pc5_11 + J3_6*pc6_11 + J3_7*pc7_11 + J3_8*pc8_11
    V4_3 = J4_3*pc3_3 + J4_4*pc3_4 + J4_5*pc3_5 + J4_6*pc3_6 + J4_7*pc3_7 + J4_8*pc3_8
    V4_4 = J4_3*pc3_4 + J4_4*pc4_4 + J4_5*pc4_5 + J4_6*pc4_6 + J4_7*pc4_7 + J4_8*pc4_8
    V4_5 = J4_3*pc3_5 + J4_4*pc4_5 + J4_5*pc5_5 + J4_6*pc5_6 + J4_7*pc5_7 + J4_8*pc5_8
    V4_6 = J4_3*pc3_6 + J4_4*pc4_6 + J4_5*pc5_6 + J4_6*pc6_6 + J4_7*pc6_7 + J4_8*pc6_8
    V4_7 = J4_3*pc3_7 + J4_4*pc4_7 + J4_5*pc5_7 + J4_6*pc6_7 + J4_7*pc7_7 + J4_8*pc7_8
    V4_8 = J4_3*pc3_8 + J4_4*pc4_8 + J4_5*pc5_8 + J4_6*pc6_8 + J4_7*pc7_8 + J4_8*pc8_8
    V4_9 = J4_3*pc3_9 + J4_4*pc4_9 + J4_5*pc5_9 + J4_6*pc6_9 + J4_7*pc7_9 + J4_8*pc8_9
    V4_10 = J4_3*pc3_10 + J4_4*pc4_10 + J4_5*pc5_10 + J4_6*pc6_10 + J4_7*pc7_10 + J4_8*pc8_10
    V4_11 = J4_3*pc3_11 + J4_4*pc4_11 + J4_5*pc5_11 + J4_6*pc6_11 + J4_7*pc7_11 + J4_8*pc8_11
    V5_3 = J5_10*pc3_10 + J5_11*pc3_11 + J5_3*pc3_3 + J5_4*pc3_4 + J5_9*pc3_9
    V5_4 = J5_10*pc4_10 + J5_11*pc4_11 + J5_3*pc3_4 + J5_4*pc4_4 + J5_9*pc4_9
    V5_6 = J5_10*pc6_10 + J5_11*pc6_11 + J5_3*pc3_6 + J5_4*pc4_6 + J5_9*pc6_9
    V5_7 = J5_10*pc7_10 + J5_11*pc7_11 + J5_3*pc3_7 + J5_4*pc4_7 + J5_9*pc7_9
    V5_8 = J5_10*pc8_10 + J5_11*pc8_11 + J5_3*pc3_8 + J5_4*pc4_8 + J5_9*pc8_9
    V5_9 = J5_10*pc9_10 + J5_11*pc9_11 + J5_3*pc3_9 + J5_4*pc4_9 + J5_9*pc9_9
    V5_10 = J5_10*pc10_10 + J5_11*pc10_11 + J5_3*pc3_10 + J5_4*pc4_10 + J5_9*pc9_10
    V5_11 = J5_10*pc10_11 + J5_11*pc11_11 + J5_3*pc3_11 + J5_4*pc4_11 + J5_9*pc9_11
    V6_3 = J6_3*pc3_3 + J6_4*pc3_4 + J6_6*pc3_6 + J6_7*pc3_7 + J6_8*pc3_8
    V6_4 = J6_3*pc3_4 + J6_4*pc4_4 + J6_6*pc4_6 + J6_7*pc4_7 + J6_8*pc4_8
    V6_6 = J6_3*pc3_6 + J6_4*pc4_6 + J6_6*pc6_6 + J6_7*pc6_7 + J6_8*pc6_8
    V6_7 = J6_3*pc3_7 + J6_4*pc4_7 + J6_6*pc6_7 + J6_7*pc7_7 + J6_8*pc7_8
    V6_8 = J6_3*pc3_8 + J6_4*pc4_8 + J6_6*pc6_8 + J6_7*pc7_8 + J6_8*pc8_8
    ws[js, 0] = xp_x
    ws[js, 1] = xp_y
    ws[js, 2] = xp_z
    ws[js, 3] = xp_psi
    ws[js, 4] = xp_v
    ws[js, 5] = xp_omega
    ws[js, 6] = xp_v_up
    ws[jp, 0] = pc0_0
    ws[jp, 1] = pc0_1
    ws[jp, 2] = pc0_2
    ws[jp, 3] = J3_3*pc0_3 + J3_4*pc0_4 + J3_5*pc0_5 + J3_6*pc0_6 + J3_7*pc0_7 + J3_8*pc0_8
    ws[jp, 4] = J4_3*pc0_3 + J4_4*pc0_4 + J4_5*pc0_5 + J4_6*pc0_6 + J4_7*pc0_7 + J4_8*pc0_8
    ws[jp, 5] = J5_10*pc0_10 + J5_11*pc0_11 + J5_3*pc0_3 + J5_4*pc0_4 + J5_9*pc0_9
    ws[jp, 6] = J6_3*pc0_3 + J6_4*pc0_4 + J6_6*pc0_6 + J6_7*pc0_7 + J6_8*pc0_8
    ws[jp, 7] = pc1_1
    ws[jp, 8] = pc1_2
    ws[jp, 9] = J3_3*pc1_3 + J3_4*pc1_4 + J3_5*pc1_5 + J3_6*pc1_6 + J3_7*pc1_7 + J3_8*pc1_8
    ws[jp, 10] = J4_3*pc1_3 + J4_4*pc1_4 + J4_5*pc1_5 + J4_6*pc1_6 + J4_7*pc1_7 + J4_8*pc1_8
    ws[jp, 11] = J5_10*pc1_10 + J5_11*pc1_11 + J5_3*pc1_3 + J5_4*pc1_4 + J5_9*pc1_9
    ws[jp, 12] = J6_3*pc1_3 + J6_4*pc1_4 + J6_6*pc1_6 + J6_7*pc1_7 + J6_8*pc1_8
    ws[jp, 13] = pc2_2
    ws[jp, 14] = J3_3*pc2_3 + J3_4*pc2_4 + J3_5*pc2_5 + J3_6*pc2_6 + J3_7*pc2_7 + J3_8*pc2_8
    ws[jp, 15] = J4_3*pc2_3 + J4_4*pc2_4 + J4_5*pc2_5 + J4_6*pc2_6 + J4_7*pc2_7 + J4_8*pc2_8
    ws[jp, 16] = J5_10*pc2_10 + J5_11*pc2_11 + J5_3*pc2_3 + J5_4*pc2_4 + J5_9*pc2_9
    ws[jp, 17] = J6_3*pc2_3 + J6_4*pc2_4 + J6_6*pc2_6 + J6_7*pc2_7 + J6_8*pc2_8
    ws[jp, 18] = J3_3*V3_3 + J3_4*V3_4 + J3_5*V3_5 + J3_6*V3_6 + J3_7*V3_7 + J3_8*V3_8
    ws[jp, 19] = J4_3*V3_3 + J4_4*V3_4 + J4_5*V3_5 + J4_6*V3_6 + J4_7*V3_7 + J4_8*V3_8
    ws[jp, 20] = J5_10*V3_10 + J5_11*V3_11 + J5_3*V3_3 + J5_4*V3_4 + J5_9*V3_9
    ws[jp, 21] = J6_3*V3_3 + J6_4*V3_4 + J6_6*V3_6 + J6_7*V3_7 + J6_8*V3_8
    ws[jp, 22] = J4_3*V4_3 + J4_4*V4_4 + J4_5*V4_5 + J4_6*V4_6 + J4_7*V4_7 + J4_8*V4_8
    ws[jp, 23] = J5_10*V4_10 + J5_11*V4_11 + J5_3*V4_3 + J5_4*V4_4 + J5_9*V4_9
    ws[jp, 24] = J6_3*V4_3 + J6_4*V4_4 + J6_6*V4_6 + J6_7*V4_7 + J6_8*V4_8
    ws[jp, 25] = J5_10*V5_10 + J5_11*V5_11 + J5_3*V5_3 + J5_4*V5_4 + J5_9*V5_9
    ws[jp, 26] = J6_3*V5_3 + J6_4*V5_4 + J6_6*V5_6 + J6_7*V5_7 + J6_8*V5_8
    ws[jp, 27] = J6_3*V6_3 + J6_4*V6_4 + J6_6*V6_6 + J6_7*V6_7 + J6_8*V6_8


@nb.njit(cache=True, fastmath=FASTMATH, error_model="numpy")
def step_ll_position3(ws, js, jp, dt, sigma_a, sigma_alpha, sigma_z, z_x, z_y, z_z, r):
    """``step_try_position3`` on rows s = ws[js], p = ws[jp] (derive/codegen/imm_rows.py); returns (nis, rdet),
    rdet = 1/det S, S = ℋPℋᵀ + R at the predicted state (eq:K), also when nis is FALLBACK.
    """
    x = ws[js, 0]
    y = ws[js, 1]
    z = ws[js, 2]
    psi = ws[js, 3]
    v = ws[js, 4]
    omega = ws[js, 5]
    v_up = ws[js, 6]
    p00 = ws[jp, 0]
    p01 = ws[jp, 1]
    p02 = ws[jp, 2]
    p03 = ws[jp, 3]
    p04 = ws[jp, 4]
    p05 = ws[jp, 5]
    p06 = ws[jp, 6]
    p11 = ws[jp, 7]
    p12 = ws[jp, 8]
    p13 = ws[jp, 9]
    p14 = ws[jp, 10]
    p15 = ws[jp, 11]
    p16 = ws[jp, 12]
    p22 = ws[jp, 13]
    p23 = ws[jp, 14]
    p24 = ws[jp, 15]
    p25 = ws[jp, 16]
    p26 = ws[jp, 17]
    p33 = ws[jp, 18]
    p34 = ws[jp, 19]
    p35 = ws[jp, 20]
    p36 = ws[jp, 21]
    p44 = ws[jp, 22]
    p45 = ws[jp, 23]
    p46 = ws[jp, 24]
    p55 = ws[jp, 25]
    p56 = ws[jp, 26]
    p66 = ws[jp, 27]
    _a0 = dt*omega/2.0
    _sin__a0 = math.sin(_a0)
    _cos__a0 = math.cos(_a0)
    _dsinc__a0 = dsinc(_a0, _sin__a0, _cos__a0)
    _sinc__a0 = sinc(_a0, _sin__a0, _cos__a0)
    _a1 = dt*omega/2.0 + psi
    _sin__a1 = math.sin(_a1)
    _cos__a1 = math.cos(_a1)
    _t0 = _sin__a1*_sinc__a0
    _t1 = _t0*dt
    _t2 = _cos__a1*_sinc__a0
    _t3 = _t2*dt
    _t4 = (dt*dt)*v/2.0
    cc03 = -(_t1*v)
    cc04 = _t3
    cc05 = -(_t4*(_cos__a1*_dsinc__a0 + _t0))
    cc13 = _t3*v
    cc14 = _t1
    cc15 = _t4*(-(_dsinc__a0*_sin__a1) + _t2)
    _sin_psi = math.sin(psi)
    _cos_psi = math.cos(psi)
    _t5 = (dt*dt)/2.0
    _t6 = _sinc__a0*dt*v
    g00 = _cos_psi*_t5
    g10 = _sin_psi*_t5
    g22 = _t5
    g31 = _t5
    e00 = _cos__a1*_t6 + x
    e01 = _sin__a1*_t6 + y
    e02 = dt*v_up + z
    e03 = dt*omega + psi
    _t7 = dt*p56
    m00 = cc03*p03 + cc04*p04 + cc05*p05 + p00
    m01 = cc03*p13 + cc04*p14 + cc05*p15 + p01
    m02 = cc03*p23 + cc04*p24 + cc05*p25 + p02
    m03 = cc03*p33 + cc04*p34 + cc05*p35 + p03
    m04 = cc03*p34 + cc04*p44 + cc05*p45 + p04
    m05 = cc03*p35 + cc04*p45 + cc05*p55 + p05
    m06 = cc03*p36 + cc04*p46 + cc05*p56 + p06
    m11 = cc13*p13 + cc14*p14 + cc15*p15 + p11
    m12 = cc13*p23 + cc14*p24 + cc15*p25 + p12
    m13 = cc13*p33 + cc14*p34 + cc15*p35 + p13
    m14 = cc13*p34 + cc14*p44 + cc15*p45 + p14
    m15 = cc13*p35 + cc14*p45 + cc15*p55 + p15
    m16 = cc13*p36 + cc14*p46 + cc15*p56 + p16
    m22 = dt*p26 + p22
    m23 = dt*p36 + p23
    m24 = dt*p46 + p24
    m25 = _t7 + p25
    m26 = dt*p66 + p26
    m33 = dt*p35 + p33
    m34 = dt*p45 + p34
    m35 = dt*p55 + p35
    m36 = _t7 + p36
    _t8 = sigma_a*sigma_a
    _t9 = _t8*g00
    _t10 = sigma_z*sigma_z
    _t11 = sigma_alpha*sigma_alpha
    _t12 = dt*dt
    pp00 = _t8*(g00*g00) + cc03*m03 + cc04*m04 + cc05*m05 + m00
    pp01 = _t9*g10 + cc13*m03 + cc14*m04 + cc15*m05 + m01
    pp02 = dt*m06 + m02
    pp03 = dt*m05 + m03
    pp04 = _t9*dt + m04
    pp05 = m05
    pp06 = m06
    pp11 = _t8*(g10*g10) + cc13*m13 + cc14*m14 + cc15*m15 + m11
    pp12 = dt*m16 + m12
    pp13 = dt*m15 + m13
    pp14 = _t8*dt*g10 + m14
    pp15 = m15
    pp16 = m16
    pp22 = _t10*(g22*g22) + dt*m26 + m22
    pp23 = dt*m25 + m23
    pp24 = m24
    pp25 = m25
    pp26 = _t10*dt*g22 + m26
    pp33 = _t11*(g31*g31) + dt*m35 + m33
    pp34 = m34
    pp35 = _t11*dt*g31 + m35
    pp36 = m36
    pp44 = _t12*_t8 + p44
    pp45 = p45
    pp46 = p46
    pp55 = _t11*_t12 + p55
    pp56 = p56
    pp66 = _t10*_t12 + p66
    x_p = e00
    y_p = e01
    z_p = e02
    psi_p = e03
    inn00 = -x_p + z_x
    inn10 = -y_p + z_y
    inn20 = -z_p + z_z
    _t13 = r*r
    S00 = _t13 + pp00
    S11 = _t13 + pp11
    S22 = _t13 + pp22
    rdet = 1.0/(S00*S11*S22 - S00*(pp12*pp12) - S11*(pp02*pp02) - S22*(pp01*pp01) + 2.0*pp01*pp02*pp12)
    Si00 = rdet*(S11*S22 - pp12*pp12)
    Si01 = rdet*(-(S22*pp01) + pp02*pp12)
    Si02 = rdet*(-(S11*pp02) + pp01*pp12)
    Si11 = rdet*(S00*S22 - pp02*pp02)
    Si12 = rdet*(-(S00*pp12) + pp01*pp02)
    Si22 = rdet*(S00*S11 - pp01*pp01)
    _t14 = Si01*pp01
    _t15 = Si02*pp02
    _t16 = Si12*pp12
    _t17 = 2.0*inn00
    k00 = Si00*pp00 + _t14 + _t15
    k01 = Si01*pp00 + Si11*pp01 + Si12*pp02
    k02 = Si02*pp00 + Si12*pp01 + Si22*pp02
    k10 = Si00*pp01 + Si01*pp11 + Si02*pp12
    k11 = Si11*pp11 + _t14 + _t16
    k12 = Si02*pp01 + Si12*pp11 + Si22*pp12
    k20 = Si00*pp02 + Si01*pp12 + Si02*pp22
    k21 = Si01*pp02 + Si11*pp12 + Si12*pp22
    k22 = Si22*pp22 + _t15 + _t16
    k30 = Si00*pp03 + Si01*pp13 + Si02*pp23
    k31 = Si01*pp03 + Si11*pp13 + Si12*pp23
    k32 = Si02*pp03 + Si12*pp13 + Si22*pp23
    k40 = Si00*pp04 + Si01*pp14 + Si02*pp24
    k41 = Si01*pp04 + Si11*pp14 + Si12*pp24
    k42 = Si02*pp04 + Si12*pp14 + Si22*pp24
    k50 = Si00*pp05 + Si01*pp15 + Si02*pp25
    k51 = Si01*pp05 + Si11*pp15 + Si12*pp25
    k52 = Si02*pp05 + Si12*pp15 + Si22*pp25
    k60 = Si00*pp06 + Si01*pp16 + Si02*pp26
    k61 = Si01*pp06 + Si11*pp16 + Si12*pp26
    k62 = Si02*pp06 + Si12*pp16 + Si22*pp26
    nis = Si00*(inn00*inn00) + Si01*_t17*inn10 + Si02*_t17*inn20 + Si11*(inn10*inn10) + 2.0*Si12*inn10*inn20 + Si22*(inn20*inn20)
    nk0 = inn00*k00 + inn10*k01 + inn20*k02
    nk1 = inn00*k10 + inn10*k11 + inn20*k12
    nk2 = inn00*k20 + inn10*k21 + inn20*k22
    nk3 = inn00*k30 + inn10*k31 + inn20*k32
    nk4 = inn00*k40 + inn10*k41 + inn20*k42
    nk5 = inn00*k50 + inn10*k51 + inn20*k52
    nk6 = inn00*k60 + inn10*k61 + inn20*k62
    mu00 = nk0 + x_p
    mu01 = nk1 + y_p
    mu02 = nk2 + z_p
    mu03 = nk3 + psi_p
    mu04 = nk4 + v
    mu05 = nk5 + omega
    mu06 = nk6 + v_up
    pj00 = -(k00*pp00) - k01*pp01 - k02*pp02 + pp00
    pj01 = -(k00*pp01) - k01*pp11 - k02*pp12 + pp01
    pj02 = -(k00*pp02) - k01*pp12 - k02*pp22 + pp02
    pj03 = -(k00*pp03) - k01*pp13 - k02*pp23 + pp03
    pj04 = -(k00*pp04) - k01*pp14 - k02*pp24 + pp04
    pj05 = -(k00*pp05) - k01*pp15 - k02*pp25 + pp05
    pj06 = -(k00*pp06) - k01*pp16 - k02*pp26 + pp06
    pj11 = -(k10*pp01) - k11*pp11 - k12*pp12 + pp11
    pj12 = -(k10*pp02) - k11*pp12 - k12*pp22 + pp12
    pj13 = -(k10*pp03) - k11*pp13 - k12*pp23 + pp13
    pj14 = -(k10*pp04) - k11*pp14 - k12*pp24 + pp14
    pj15 = -(k10*pp05) - k11*pp15 - k12*pp25 + pp15
    pj16 = -(k10*pp06) - k11*pp16 - k12*pp26 + pp16
    pj22 = -(k20*pp02) - k21*pp12 - k22*pp22 + pp22
    pj23 = -(k20*pp03) - k21*pp13 - k22*pp23 + pp23
    pj24 = -(k20*pp04) - k21*pp14 - k22*pp24 + pp24
    pj25 = -(k20*pp05) - k21*pp15 - k22*pp25 + pp25
    pj26 = -(k20*pp06) - k21*pp16 - k22*pp26 + pp26
    pj33 = -(k30*pp03) - k31*pp13 - k32*pp23 + pp33
    pj34 = -(k30*pp04) - k31*pp14 - k32*pp24 + pp34
    pj35 = -(k30*pp05) - k31*pp15 - k32*pp25 + pp35
    pj36 = -(k30*pp06) - k31*pp16 - k32*pp26 + pp36
    pj44 = -(k40*pp04) - k41*pp14 - k42*pp24 + pp44
    pj45 = -(k40*pp05) - k41*pp15 - k42*pp25 + pp45
    pj46 = -(k40*pp06) - k41*pp16 - k42*pp26 + pp46
    pj55 = -(k50*pp05) - k51*pp15 - k52*pp25 + pp55
    pj56 = -(k50*pp06) - k51*pp16 - k52*pp26 + pp56
    pj66 = -(k60*pp06) - k61*pp16 - k62*pp26 + pp66
    out_p0 = pj00
    out_p1 = pj01
    out_p2 = pj02
    out_p3 = pj03
    out_p4 = pj04
    out_p5 = pj05
    out_p6 = pj06
    out_p7 = pj11
    out_p8 = pj12
    out_p9 = pj13
    out_p10 = pj14
    out_p11 = pj15
    out_p12 = pj16
    out_p13 = pj22
    out_p14 = pj23
    out_p15 = pj24
    out_p16 = pj25
    out_p17 = pj26
    out_p18 = pj33
    out_p19 = pj34
    out_p20 = pj35
    out_p21 = pj36
    out_p22 = pj44
    out_p23 = pj45
    out_p24 = pj46
    out_p25 = pj55
    out_p26 = pj56
    out_p27 = pj66
    out_s0 = mu00
    out_s1 = mu01
    out_s2 = mu02
    out_s3 = mu03
    out_s4 = mu04
    out_s5 = mu05
    out_s6 = mu06
    if not covariance_is_pd_fused(out_p0, out_p1, out_p2, out_p3, out_p4, out_p5, out_p6, out_p7, out_p8, out_p9, out_p10, out_p11, out_p12, out_p13, out_p14, out_p15, out_p16, out_p17, out_p18, out_p19, out_p20, out_p21, out_p22, out_p23, out_p24, out_p25, out_p26, out_p27):
        out_p0 = pp00
        out_p1 = pp01
        out_p2 = pp02
        out_p3 = pp03
        out_p4 = pp04
        out_p5 = pp05
        out_p6 = pp06
        out_p7 = pp11
        out_p8 = pp12
        out_p9 = pp13
        out_p10 = pp14
        out_p11 = pp15
        out_p12 = pp16
        out_p13 = pp22
        out_p14 = pp23
        out_p15 = pp24
        out_p16 = pp25
        out_p17 = pp26
        out_p18 = pp33
        out_p19 = pp34
        out_p20 = pp35
        out_p21 = pp36
        out_p22 = pp44
        out_p23 = pp45
        out_p24 = pp46
        out_p25 = pp55
        out_p26 = pp56
        out_p27 = pp66
        out_s0 = x_p
        out_s1 = y_p
        out_s2 = z_p
        out_s3 = psi_p
        out_s4 = v
        out_s5 = omega
        out_s6 = v_up
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
    ws[jp, 21] = out_p21
    ws[jp, 22] = out_p22
    ws[jp, 23] = out_p23
    ws[jp, 24] = out_p24
    ws[jp, 25] = out_p25
    ws[jp, 26] = out_p26
    ws[jp, 27] = out_p27
    ws[js, 0] = out_s0
    ws[js, 1] = out_s1
    ws[js, 2] = out_s2
    ws[js, 3] = out_s3
    ws[js, 4] = out_s4
    ws[js, 5] = out_s5
    ws[js, 6] = out_s6
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
    for k in range(7):
        ws[rs, k] = ws[rS + best, k]
    it = 0
    if M > 1:
        for it in range(1, 51):
            for k in range(7):
                ws[rd, k] = 0.0
            for i in range(M):
                w = ws[rw, i]
                if w > 0.0 and not (i == best and it == 1):  # d_best = 0 in the first iteration
                    between_add_at(ws, rs, rS + i, w, rd)
            retract_at(ws, rs, rd)
            nrm = 0.0
            for k in range(7):
                nrm += ws[rd, k] * ws[rd, k]
            if nrm < 1e-24:
                break
    if M == 1:
        for k in range(28):
            ws[rp, k] = ws[rPp, k]
        return it
    for k in range(28):
        ws[rp, k] = 0.0
    for i in range(M):
        w = ws[rw, i]
        if w > 0.0:
            mix_transport_at(ws, rs, rS + i, rPp + i, w, rp)
    return it
