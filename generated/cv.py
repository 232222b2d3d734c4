"""Kalman filter with the constant (world-frame) velocity model: model quantities, fused predict/update steps and loops.

GENERATED FILE: DO NOT EDIT.
Source: derive/models/cv.py (definition) through derive/codegen/emitter.py and derive/algebra.py
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

__all__ = ['state_from_physical', 'state_to_physical', 'physical_into', 'group_mean', 'motion_omega', 'motion', 'calC', 'transition', 'process_noise', 'limit_angle_variance', 'predict', 'calH_position', 'update_position', 'step_try_position', 'step_position', 'measure_position', 'run_one_position', 'run_segments_position', 'run_one_from_position', 'run_segments_from_position', 'run_batch_position', 'measure_batch_position', 'innovation_into_position', 'innovation_bank_position', 'calH_bank_position', 'run_segments_noise_from_position', 'rerun_position', 'recover_position', 'lane_position', 'run_batch_soa_position', 'covariance_is_pd', 'covariance_is_pd_fused', 'repair_pd', 'covariance_is_pd_lane', 'physical_lane', 'propagate', 'position_into', 'simulate_batch', 'states_from_physical', 'propagate_rows', 'propagate_positions', 'world_velocity', 'world_velocity_into', 'world_velocities', 'row_speeds', 'common_to_state', 'common_jacobian', 'common_to_states', 'common_jacobians', 'reinit_into', 'speed_std_at', 'speed_stds', 'first_alarm', 'tangent_error', 'retract', 'between', 'right_jacobian', 'right_jacobian_inv', 'predict_bank', 'retract_bank', 'right_jacobian_bank', 'innovation_logdet_position', 'step_store_position', 'lane_store_position', 'run_batch_store_soa_position', 'run_one_store_position', 'run_batch_store_position', 'loglik_batch_position', 'smooth_step_at', 'lane_smooth', 'physical_smooth_lane', 'smooth_batch_soa', 'smooth_one', 'smooth_batch', 'physical_to_common', 'physical_to_common_jacobian', 'common_missing', 'state_from_physical_into', 'transition_into', 'calH_position_into', 'common_to_state_into', 'common_jacobian_into', 'between_into', 'right_jacobian_into', 'right_jacobian_inv_into', 'physical_to_common_into', 'physical_to_common_jacobian_into', 'between_add', 'mix_transport', 'common_of_state', 'state_of_common', 'between_add_at', 'mix_transport_at', 'retract_at', 'common_of_state_at', 'state_of_common_at', 'step_ll_position', 'mix_on_group_at']


@nb.njit(cache=True)
def state_from_physical(xp):
    """Internal state [x, y, w_x, w_y] from the physical [x, y, vx, vy].
    """
    x = xp[0]
    y = xp[1]
    w_x = xp[2]
    w_y = xp[3]
    out = np.zeros(4)
    out[0] = x
    out[1] = y
    out[2] = w_x
    out[3] = w_y
    return out


@nb.njit(cache=True)
def state_to_physical(s):
    """Physical [x, y, vx, vy] (angles in (-π, π]) from the internal state.
    """
    x = s[0]
    y = s[1]
    w_x = s[2]
    w_y = s[3]
    out = np.zeros(4)
    out[0] = x
    out[1] = y
    out[2] = w_x
    out[3] = w_y
    return out


@nb.njit(cache=True)
def physical_into(s, out):
    """Physical [x, y, vx, vy] from the internal state, written into ``out`` (no allocation).
    """
    x = s[0]
    y = s[1]
    w_x = s[2]
    w_y = s[3]
    out[0] = x
    out[1] = y
    out[2] = w_x
    out[3] = w_y


@nb.njit(cache=True)
def group_mean(s):
    """The mean μ as a group matrix (block-diagonal for a product group).
    """
    x = s[0]
    y = s[1]
    w_x = s[2]
    w_y = s[3]
    out = np.zeros((5, 5))
    out[0, 0] = 1.0
    out[0, 4] = x
    out[1, 1] = 1.0
    out[1, 4] = y
    out[2, 2] = 1.0
    out[2, 4] = w_x
    out[3, 3] = 1.0
    out[3, 4] = w_y
    out[4, 4] = 1.0
    return out


@nb.njit(cache=True)
def motion_omega(s, dt):
    """Ω(μ), the tangent increment of one step (eq:motionG).
    """
    w_x = s[2]
    w_y = s[3]
    out = np.zeros(4)
    out[0] = dt*w_x
    out[1] = dt*w_y
    return out


@nb.njit(cache=True)
def motion(s, dt):
    """The internal state after one noise-free step, μ exp(Ω(μ)) (eq:pred_mu); x' = f(x) for a Euclidean model.
    """
    x = s[0]
    y = s[1]
    w_x = s[2]
    w_y = s[3]
    out = np.zeros(4)
    out[0] = dt*w_x + x
    out[1] = dt*w_y + y
    out[2] = w_x
    out[3] = w_y
    return out


@nb.njit(cache=True)
def calC(s, dt):
    """𝒞 = ∂Ω(μ exp ε)/∂ε at ε = 0 (eq:C, eq:calCFinal).
    """
    out = np.zeros((4, 4))
    out[0, 2] = dt
    out[1, 3] = dt
    return out


@nb.njit(cache=True)
def transition(s, dt):
    """F = Ad_G(exp(-Ω)) + Φ_G(Ω) 𝒞 (paper, below eq:pred_cov).
    """
    out = np.zeros((4, 4))
    out[0, 0] = 1.0
    out[0, 2] = dt
    out[1, 1] = 1.0
    out[1, 3] = dt
    out[2, 2] = 1.0
    out[3, 3] = 1.0
    return out


@nb.njit(cache=True)
def process_noise(s, dt, sigma_a):
    """Q = G diag(σ²) G^T: the noise n (sigma_a) of eq:motionG in the tangent.
    """
    out = np.zeros((4, 4))
    _t0 = sigma_a*sigma_a
    _t1 = _t0*(dt*dt*dt*dt)/4.0
    _t2 = _t0*(dt*dt*dt)/2.0
    _t3 = _t0*(dt*dt)
    out[0, 0] = _t1
    out[0, 2] = _t2
    out[1, 1] = _t1
    out[1, 3] = _t2
    out[2, 0] = _t2
    out[2, 2] = _t3
    out[3, 1] = _t2
    out[3, 3] = _t3
    return out


@nb.njit(cache=True)
def limit_angle_variance(p):
    """Cap the std of the angle coordinates [] of P at π by congruence scaling (see derive/codegen/emitter.py)."""
    return


@nb.njit(cache=True, fastmath=FASTMATH)
def predict(s, p, dt, sigma_a):
    """Fused LG-EKF prediction, in place: μ ← μ exp(Ω(μ)) (eq:pred_mu),
    P ← F P F^T + Φ(Ω) Q Φ(Ω)^T (eq:pred_cov), Q = G diag(σ²) G^T.
    s: internal state [x, y, w_x, w_y], p: packed covariance (10), dt > 0.
    legend: cc = 𝒞 (eq:C), f = F = Ad(exp(−Ω)) + Φ(Ω)𝒞 (eq:pred_cov), g = Φ(Ω)G, hh = ℋ (eq:calH), hp = ℋP, inn = [log_G'(h(μ)⁻¹Z)]^∨, S = ℋPℋᵀ + R, Si = S⁻¹, k = K (eq:K), nk = Kν, alpha = gain damping, nu = ν, phi = Φ(ν) (eq:up_P), a = I − αKℋ, b = aP, beta = α(2 − α), kb = βK, pj = Joseph-form P (= P − βKℋP), cp = Φ(ν)·pj, mu/e = new mean
    """
    x = s[0]
    y = s[1]
    w_x = s[2]
    w_y = s[3]
    p00 = p[0]
    p01 = p[1]
    p02 = p[2]
    p03 = p[3]
    p11 = p[4]
    p12 = p[5]
    p13 = p[6]
    p22 = p[7]
    p23 = p[8]
    p33 = p[9]
    _t0 = (dt*dt)/2.0
    g00 = _t0
    g11 = _t0
    e00 = dt*w_x + x
    e01 = dt*w_y + y
    _t1 = dt*p23
    m00 = dt*p02 + p00
    m01 = dt*p12 + p01
    m02 = dt*p22 + p02
    m03 = _t1 + p03
    m11 = dt*p13 + p11
    m12 = _t1 + p12
    m13 = dt*p33 + p13
    _t2 = sigma_a*sigma_a
    _t3 = _t2*dt
    _t4 = _t2*(dt*dt)
    p[0] = _t2*(g00*g00) + dt*m02 + m00
    p[1] = dt*m03 + m01
    p[2] = _t3*g00 + m02
    p[3] = m03
    p[4] = _t2*(g11*g11) + dt*m13 + m11
    p[5] = m12
    p[6] = _t3*g11 + m13
    p[7] = _t4 + p22
    p[8] = p23
    p[9] = _t4 + p33
    s[0] = e00
    s[1] = e01


@nb.njit(cache=True)
def calH_position(s):
    """ℋ = ∂[log_G'(h(μ)^-1 h(μ exp ε))]^∨/∂ε at ε = 0 (eq:calH, eq:calH_model) for position measurements.
    """
    out = np.zeros((2, 4))
    out[0, 0] = 1.0
    out[1, 1] = 1.0
    return out


@nb.njit(cache=True, fastmath=FASTMATH)
def update_position(s, p, z_x, z_y, r):
    """Fused update with a position measurement (2-D position z = (x, y) with isotropic noise std r (the paper's measurement)), in place.
    z = (z_x, z_y), noise stds (r); Z = h(μ)·exp(m), m ~ N(0, R) in the tangent of G'.
    K = P ℋ^T (ℋ P ℋ^T + R)^-1, ν = K [log_G'(h(μ)^-1 Z)]^∨ (eq:K), μ ← μ exp(ν) (eq:up_mu),
    P ← Φ(ν) [(I - Kℋ) P (I - Kℋ)^T + K R K^T] Φ(ν)^T: eq:up_P in Joseph form. Returns the NIS e^T S^-1 e.
    legend: cc = 𝒞 (eq:C), f = F = Ad(exp(−Ω)) + Φ(Ω)𝒞 (eq:pred_cov), g = Φ(Ω)G, hh = ℋ (eq:calH), hp = ℋP, inn = [log_G'(h(μ)⁻¹Z)]^∨, S = ℋPℋᵀ + R, Si = S⁻¹, k = K (eq:K), nk = Kν, alpha = gain damping, nu = ν, phi = Φ(ν) (eq:up_P), a = I − αKℋ, b = aP, beta = α(2 − α), kb = βK, pj = Joseph-form P (= P − βKℋP), cp = Φ(ν)·pj, mu/e = new mean
    """
    x = s[0]
    y = s[1]
    w_x = s[2]
    w_y = s[3]
    p00 = p[0]
    p01 = p[1]
    p02 = p[2]
    p03 = p[3]
    p11 = p[4]
    p12 = p[5]
    p13 = p[6]
    p22 = p[7]
    p23 = p[8]
    p33 = p[9]
    inn00 = -x + z_x
    inn10 = -y + z_y
    _t0 = r*r
    S00 = _t0 + p00
    S11 = _t0 + p11
    rdet = 1.0/(S00*S11 - p01*p01)
    Si00 = S11*rdet
    Si01 = -(p01*rdet)
    Si11 = S00*rdet
    _t1 = Si01*p01
    k00 = Si00*p00 + _t1
    k01 = Si01*p00 + Si11*p01
    k10 = Si00*p01 + Si01*p11
    k11 = Si11*p11 + _t1
    k20 = Si00*p02 + Si01*p12
    k21 = Si01*p02 + Si11*p12
    k30 = Si00*p03 + Si01*p13
    k31 = Si01*p03 + Si11*p13
    nis = Si00*(inn00*inn00) + 2.0*Si01*inn00*inn10 + Si11*(inn10*inn10)
    nk0 = inn00*k00 + inn10*k01
    nk1 = inn00*k10 + inn10*k11
    nk2 = inn00*k20 + inn10*k21
    nk3 = inn00*k30 + inn10*k31
    mu00 = nk0 + x
    mu01 = nk1 + y
    mu02 = nk2 + w_x
    mu03 = nk3 + w_y
    a00 = 1.0 - k00
    a01 = -k01
    a10 = -k10
    a11 = 1.0 - k11
    a20 = -k20
    a21 = -k21
    a30 = -k30
    a31 = -k31
    b00 = a00*p00 + a01*p01
    b01 = a00*p01 + a01*p11
    b02 = a00*p02 + a01*p12
    b03 = a00*p03 + a01*p13
    b10 = a10*p00 + a11*p01
    b11 = a10*p01 + a11*p11
    b12 = a10*p02 + a11*p12
    b13 = a10*p03 + a11*p13
    b20 = a20*p00 + a21*p01 + p02
    b21 = a20*p01 + a21*p11 + p12
    b22 = a20*p02 + a21*p12 + p22
    b23 = a20*p03 + a21*p13 + p23
    b30 = a30*p00 + a31*p01 + p03
    b31 = a30*p01 + a31*p11 + p13
    b33 = a30*p03 + a31*p13 + p33
    _t2 = r*r
    _t3 = _t2*k00
    _t4 = _t2*k01
    _t5 = _t2*k10
    _t6 = _t2*k11
    pj00 = _t2*(k00*k00) + _t2*(k01*k01) + a00*b00 + a01*b01
    pj01 = _t3*k10 + _t4*k11 + a10*b00 + a11*b01
    pj02 = _t3*k20 + _t4*k21 + a20*b00 + a21*b01 + b02
    pj03 = _t3*k30 + _t4*k31 + a30*b00 + a31*b01 + b03
    pj11 = _t2*(k10*k10) + _t2*(k11*k11) + a10*b10 + a11*b11
    pj12 = _t5*k20 + _t6*k21 + a20*b10 + a21*b11 + b12
    pj13 = _t5*k30 + _t6*k31 + a30*b10 + a31*b11 + b13
    pj22 = _t2*(k20*k20) + _t2*(k21*k21) + a20*b20 + a21*b21 + b22
    pj23 = _t2*k20*k30 + _t2*k21*k31 + a30*b20 + a31*b21 + b23
    pj33 = _t2*(k30*k30) + _t2*(k31*k31) + a30*b30 + a31*b31 + b33
    p[0] = pj00
    p[1] = pj01
    p[2] = pj02
    p[3] = pj03
    p[4] = pj11
    p[5] = pj12
    p[6] = pj13
    p[7] = pj22
    p[8] = pj23
    p[9] = pj33
    s[0] = mu00
    s[1] = mu01
    s[2] = mu02
    s[3] = mu03
    return nis


@nb.njit(cache=True, fastmath=FASTMATH, error_model="numpy")
def step_try_position(s, p, dt, sigma_a, z_x, z_y, r):
    """One fused LG-EKF step with a position measurement, in place: ``predict`` then ``update_position``
    (eq:pred_mu, eq:pred_cov, angle-variance cap, eq:K, eq:up_mu, eq:up_P) in one kernel; returns the NIS.
    Covariance as P − βKℋP; a step whose result fails the LDLᵀ test (covariance_is_pd_fused) leaves the
    prediction in s, p and returns -1.0: the caller then runs update_position (Joseph form;
    derive/codegen/fused.py).
    legend: cc = 𝒞 (eq:C), f = F = Ad(exp(−Ω)) + Φ(Ω)𝒞 (eq:pred_cov), g = Φ(Ω)G, hh = ℋ (eq:calH), hp = ℋP, inn = [log_G'(h(μ)⁻¹Z)]^∨, S = ℋPℋᵀ + R, Si = S⁻¹, k = K (eq:K), nk = Kν, alpha = gain damping, nu = ν, phi = Φ(ν) (eq:up_P), a = I − αKℋ, b = aP, beta = α(2 − α), kb = βK, pj = Joseph-form P (= P − βKℋP), cp = Φ(ν)·pj, mu/e = new mean
    """
    x = s[0]
    y = s[1]
    w_x = s[2]
    w_y = s[3]
    p00 = p[0]
    p01 = p[1]
    p02 = p[2]
    p03 = p[3]
    p11 = p[4]
    p12 = p[5]
    p13 = p[6]
    p22 = p[7]
    p23 = p[8]
    p33 = p[9]
    _t0 = (dt*dt)/2.0
    g00 = _t0
    g11 = _t0
    e00 = dt*w_x + x
    e01 = dt*w_y + y
    _t1 = dt*p23
    m00 = dt*p02 + p00
    m01 = dt*p12 + p01
    m02 = dt*p22 + p02
    m03 = _t1 + p03
    m11 = dt*p13 + p11
    m12 = _t1 + p12
    m13 = dt*p33 + p13
    _t2 = sigma_a*sigma_a
    _t3 = _t2*dt
    _t4 = _t2*(dt*dt)
    pp00 = _t2*(g00*g00) + dt*m02 + m00
    pp01 = dt*m03 + m01
    pp02 = _t3*g00 + m02
    pp03 = m03
    pp11 = _t2*(g11*g11) + dt*m13 + m11
    pp12 = m12
    pp13 = _t3*g11 + m13
    pp22 = _t4 + p22
    pp23 = p23
    pp33 = _t4 + p33
    x_p = e00
    y_p = e01
    inn00 = -x_p + z_x
    inn10 = -y_p + z_y
    _t5 = r*r
    S00 = _t5 + pp00
    S11 = _t5 + pp11
    rdet = 1.0/(S00*S11 - pp01*pp01)
    Si00 = S11*rdet
    Si01 = -(pp01*rdet)
    Si11 = S00*rdet
    _t6 = Si01*pp01
    k00 = Si00*pp00 + _t6
    k01 = Si01*pp00 + Si11*pp01
    k10 = Si00*pp01 + Si01*pp11
    k11 = Si11*pp11 + _t6
    k20 = Si00*pp02 + Si01*pp12
    k21 = Si01*pp02 + Si11*pp12
    k30 = Si00*pp03 + Si01*pp13
    k31 = Si01*pp03 + Si11*pp13
    nis = Si00*(inn00*inn00) + 2.0*Si01*inn00*inn10 + Si11*(inn10*inn10)
    nk0 = inn00*k00 + inn10*k01
    nk1 = inn00*k10 + inn10*k11
    nk2 = inn00*k20 + inn10*k21
    nk3 = inn00*k30 + inn10*k31
    mu00 = nk0 + x_p
    mu01 = nk1 + y_p
    mu02 = nk2 + w_x
    mu03 = nk3 + w_y
    pj00 = -(k00*pp00) - k01*pp01 + pp00
    pj01 = -(k00*pp01) - k01*pp11 + pp01
    pj02 = -(k00*pp02) - k01*pp12 + pp02
    pj03 = -(k00*pp03) - k01*pp13 + pp03
    pj11 = -(k10*pp01) - k11*pp11 + pp11
    pj12 = -(k10*pp02) - k11*pp12 + pp12
    pj13 = -(k10*pp03) - k11*pp13 + pp13
    pj22 = -(k20*pp02) - k21*pp12 + pp22
    pj23 = -(k20*pp03) - k21*pp13 + pp23
    pj33 = -(k30*pp03) - k31*pp13 + pp33
    out_p0 = pj00
    out_p1 = pj01
    out_p2 = pj02
    out_p3 = pj03
    out_p4 = pj11
    out_p5 = pj12
    out_p6 = pj13
    out_p7 = pj22
    out_p8 = pj23
    out_p9 = pj33
    out_s0 = mu00
    out_s1 = mu01
    out_s2 = mu02
    out_s3 = mu03
    if not covariance_is_pd_fused(out_p0, out_p1, out_p2, out_p3, out_p4, out_p5, out_p6, out_p7, out_p8, out_p9):
        out_p0 = pp00
        out_p1 = pp01
        out_p2 = pp02
        out_p3 = pp03
        out_p4 = pp11
        out_p5 = pp12
        out_p6 = pp13
        out_p7 = pp22
        out_p8 = pp23
        out_p9 = pp33
        out_s0 = x_p
        out_s1 = y_p
        out_s2 = w_x
        out_s3 = w_y
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
    s[0] = out_s0
    s[1] = out_s1
    s[2] = out_s2
    s[3] = out_s3
    return nis


@nb.njit(cache=True)
def step_position(s, p, dt, sigma_a, z_x, z_y, r):
    """One LG-EKF step with a position measurement, in place; returns the NIS: ``step_try_position``, and on the rare
    step whose cheap covariance fails the LDLᵀ test, ``update_position`` (Joseph form) from the prediction
    (derive/codegen/fused.py)."""
    nis = step_try_position(s, p, dt, sigma_a, z_x, z_y, r)
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
    """Filter one trajectory with position measurements: z (K, 2), dts (K,), x0 (4,), p0 (10,).

    A row of z containing NaN is a missed detection: the step predicts only (its NIS is NaN).
    """
    s = state_from_physical(x0)
    p = p0.copy()
    K = z.shape[0]
    keep_p = out_p.shape[0] == K
    for k in range(K):
        if np.isnan(z[k, 0]) or np.isnan(z[k, 1]):
            predict(s, p, dts[k], q[0])
            out_nis[k] = np.nan
        else:
            nis = step_try_position(s, p, dts[k], q[0], z[k, 0], z[k, 1], r[0])
            if nis < 0.0:  # rare: the cheap covariance failed the LDLᵀ test; Joseph form from the prediction
                nis = update_position(s, p, z[k, 0], z[k, 1], r[0])
            out_nis[k] = nis
        physical_into(s, out_x[k])
        if keep_p:
            for i in range(10):
                out_p[k, i] = p[i]


@nb.njit(cache=True, nogil=True)
def run_segments_position(z, t, first, lengths, x0, p0, q, r, out_x, out_p, out_nis):
    """``run_one_position`` on segments of rows, one after the other (no Python per segment).

    Segment i is rows first[i] .. first[i] + lengths[i] - 1 (first[i] >= 1) of z (N, 2) and t (N,), filtered
    from x0[i] (4,), p0[i] (10,) at time t[first[i] - 1]; its outputs go to the same rows of out_x (N, 4),
    out_p (N, 10) and out_nis (N,). The numbers of ``run_one_position`` called per segment with
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
    """``run_one_position`` from the internal state s0 (4,) (the layout of ``state_from_physical``) and p0 (10,),
    which on return hold the posterior of the last row: a later call from them continues exactly (the numbers
    of one call over both rows). ``lgekf track`` filters a long object in windows of rows with it.
    """
    s = s0.copy()
    p = p0.copy()
    K = z.shape[0]
    keep_p = out_p.shape[0] == K
    for k in range(K):
        if np.isnan(z[k, 0]) or np.isnan(z[k, 1]):
            predict(s, p, dts[k], q[0])
            out_nis[k] = np.nan
        else:
            nis = step_try_position(s, p, dts[k], q[0], z[k, 0], z[k, 1], r[0])
            if nis < 0.0:  # rare: the cheap covariance failed the LDLᵀ test; Joseph form from the prediction
                nis = update_position(s, p, z[k, 0], z[k, 1], r[0])
            out_nis[k] = nis
        physical_into(s, out_x[k])
        if keep_p:
            for i in range(10):
                out_p[k, i] = p[i]
    s0[:] = s
    p0[:] = p


@nb.njit(cache=True, nogil=True)
def run_segments_from_position(z, t, first, lengths, s0, p0, q, r, out_x, out_p, out_nis):
    """``run_segments_position`` from internal states s0 (S, 4) and p0 (S, 10) (``run_one_from_position``): on
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

    z (B, K, 2) position measurements (a NaN row = missed detection); dts (B, K) step lengths; x0 (B, 4)
    physical initial states; p0 (B, 10) packed initial covariances; q (1,) process-noise stds;
    r (1,) measurement-noise stds. Writes the posterior physical states into out_x (B, K, 4), the
    packed covariances into out_p (B, K, 10) when out_p.shape[1] == K (pass (B, 0, 10) to skip),
    and the NIS into out_nis (B, K).
    """
    for b in nb.prange(z.shape[0]):
        run_one_position(z[b], dts[b], x0[b], p0[b], q, r, out_x[b], out_p[b], out_nis[b])


@nb.njit(cache=True)
def measure_batch_position(X, noise, out):
    """Simulated position measurements z = vector(h(X)·exp(m)) of every physical state X (N, 4),
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
    """ℋ (eq:calH) of every live track for position measurements into out (N, 2, 4)."""
    for i in range(s.shape[0]):
        if live[i]:
            h = calH_position(s[i])
            for a in range(2):
                for b in range(4):
                    out[i, a, b] = h[a, b]


@nb.njit(cache=True, nogil=True)
def run_segments_noise_from_position(z, t, first, lengths, s0, p0, q, r, out_x, out_p, out_nis):
    """``run_segments_from_position`` with noise stds of each segment's own: q (S, 1), r (S, 1) (the divergence
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
def lane_position(W, j, sigma_a, r):
    """step_position on lane j of the work array W (rows: derive/codegen/soa.py Layout), without branches (SIMD).
    """
    x = W[0 + j]
    y = W[64 + j]
    w_x = W[128 + j]
    w_y = W[192 + j]
    p00 = W[256 + j]
    p01 = W[320 + j]
    p02 = W[384 + j]
    p03 = W[448 + j]
    p11 = W[512 + j]
    p12 = W[576 + j]
    p13 = W[640 + j]
    p22 = W[704 + j]
    p23 = W[768 + j]
    p33 = W[832 + j]
    dt = W[1792 + j]
    z_x = W[1984 + j]
    z_y = W[2048 + j]
    _t0 = (dt*dt)/2.0
    g00 = _t0
    g11 = _t0
    e00 = dt*w_x + x
    e01 = dt*w_y + y
    _t1 = dt*p23
    m00 = dt*p02 + p00
    m01 = dt*p12 + p01
    m02 = dt*p22 + p02
    m03 = _t1 + p03
    m11 = dt*p13 + p11
    m12 = _t1 + p12
    m13 = dt*p33 + p13
    _t2 = sigma_a*sigma_a
    _t3 = _t2*dt
    _t4 = _t2*(dt*dt)
    pp00 = _t2*(g00*g00) + dt*m02 + m00
    pp01 = dt*m03 + m01
    pp02 = _t3*g00 + m02
    pp03 = m03
    pp11 = _t2*(g11*g11) + dt*m13 + m11
    pp12 = m12
    pp13 = _t3*g11 + m13
    pp22 = _t4 + p22
    pp23 = p23
    pp33 = _t4 + p33
    x_p = e00
    y_p = e01
    inn00 = -x_p + z_x
    inn10 = -y_p + z_y
    _t5 = r*r
    S00 = _t5 + pp00
    S11 = _t5 + pp11
    rdet = 1.0/(S00*S11 - pp01*pp01)
    Si00 = S11*rdet
    Si01 = -(pp01*rdet)
    Si11 = S00*rdet
    _t6 = Si01*pp01
    k00 = Si00*pp00 + _t6
    k01 = Si01*pp00 + Si11*pp01
    k10 = Si00*pp01 + Si01*pp11
    k11 = Si11*pp11 + _t6
    k20 = Si00*pp02 + Si01*pp12
    k21 = Si01*pp02 + Si11*pp12
    k30 = Si00*pp03 + Si01*pp13
    k31 = Si01*pp03 + Si11*pp13
    nis = Si00*(inn00*inn00) + 2.0*Si01*inn00*inn10 + Si11*(inn10*inn10)
    nk0 = inn00*k00 + inn10*k01
    nk1 = inn00*k10 + inn10*k11
    nk2 = inn00*k20 + inn10*k21
    nk3 = inn00*k30 + inn10*k31
    mu00 = nk0 + x_p
    mu01 = nk1 + y_p
    mu02 = nk2 + w_x
    mu03 = nk3 + w_y
    pj00 = -(k00*pp00) - k01*pp01 + pp00
    pj01 = -(k00*pp01) - k01*pp11 + pp01
    pj02 = -(k00*pp02) - k01*pp12 + pp02
    pj03 = -(k00*pp03) - k01*pp13 + pp03
    pj11 = -(k10*pp01) - k11*pp11 + pp11
    pj12 = -(k10*pp02) - k11*pp12 + pp12
    pj13 = -(k10*pp03) - k11*pp13 + pp13
    pj22 = -(k20*pp02) - k21*pp12 + pp22
    pj23 = -(k20*pp03) - k21*pp13 + pp23
    pj33 = -(k30*pp03) - k31*pp13 + pp33
    W[1152 + j] = pj00
    W[1216 + j] = pj01
    W[1280 + j] = pj02
    W[1344 + j] = pj03
    W[1408 + j] = pj11
    W[1472 + j] = pj12
    W[1536 + j] = pj13
    W[1600 + j] = pj22
    W[1664 + j] = pj23
    W[1728 + j] = pj33
    W[896 + j] = mu00
    W[960 + j] = mu01
    W[1024 + j] = mu02
    W[1088 + j] = mu03
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
        W = np.zeros(33 * 64)
        s = np.empty(4)
        p = np.empty(10)
        for j in range(L):
            s0 = state_from_physical(x0[lo + j])
            for i in range(4):
                W[(0 + i) * 64 + j] = s0[i]
            for i in range(10):
                W[(4 + i) * 64 + j] = p0[lo + j, i]
        for k in range(K):
            for j in range(L):
                W[28 * 64 + j] = dts[lo + j, k]
                W[31 * 64 + j] = z[lo + j, k, 0]
                W[32 * 64 + j] = z[lo + j, k, 1]
            for j in range(L):
                W[29 * 64 + j] = lane_position(W, j, q[0], r[0])
                good = covariance_is_pd_lane(W, j) & (W[29 * 64 + j] == W[29 * 64 + j])
                W[30 * 64 + j] = 1.0 if good else 0.0
            for j in range(L):
                if W[30 * 64 + j] == 0.0:
                    b = lo + j
                    for i in range(4):
                        s[i] = W[(0 + i) * 64 + j]
                    for i in range(10):
                        p[i] = W[(4 + i) * 64 + j]
                    predict(s, p, dts[b, k], q[0])
                    if np.isnan(z[b, k, 0]) or np.isnan(z[b, k, 1]):
                        W[29 * 64 + j] = np.nan
                    else:
                        W[29 * 64 + j] = update_position(s, p, z[b, k, 0], z[b, k, 1], r[0])
                    for i in range(4):
                        W[(14 + i) * 64 + j] = s[i]
                    for i in range(10):
                        W[(18 + i) * 64 + j] = p[i]
            for j in range(L):
                out_nis[lo + j, k] = W[29 * 64 + j]
                physical_lane(W, j, out_x, lo + j, k)
            if keep_p:
                for j in range(L):
                    for i in range(10):
                        out_p[lo + j, k, i] = W[(18 + i) * 64 + j]
            for i in range(4 + 10):
                for j in range(L):
                    W[(0 + i) * 64 + j] = W[(14 + i) * 64 + j]


@nb.njit(cache=True)
def covariance_is_pd(p):
    """LDLᵀ test of the packed covariance: every pivot d_j > 1e-13 · max_i P_ii (NaN fails)."""
    p0_0 = p[0]
    p0_1 = p[1]
    p0_2 = p[2]
    p0_3 = p[3]
    p1_1 = p[4]
    p1_2 = p[5]
    p1_3 = p[6]
    p2_2 = p[7]
    p2_3 = p[8]
    p3_3 = p[9]
    tol = 1e-13 * max(p0_0, p1_1, p2_2, p3_3)
    d0 = p0_0
    if not d0 > tol:
        return False
    r0 = 1.0 / d0
    l1_0 = (p0_1) * r0
    l2_0 = (p0_2) * r0
    l3_0 = (p0_3) * r0
    d1 = p1_1 - l1_0 * l1_0 * d0
    if not d1 > tol:
        return False
    r1 = 1.0 / d1
    l2_1 = (p1_2 - l2_0 * l1_0 * d0) * r1
    l3_1 = (p1_3 - l3_0 * l1_0 * d0) * r1
    d2 = p2_2 - l2_0 * l2_0 * d0 - l2_1 * l2_1 * d1
    if not d2 > tol:
        return False
    r2 = 1.0 / d2
    l3_2 = (p2_3 - l3_0 * l2_0 * d0 - l3_1 * l2_1 * d1) * r2
    d3 = p3_3 - l3_0 * l3_0 * d0 - l3_1 * l3_1 * d1 - l3_2 * l3_2 * d2
    if not d3 > tol:
        return False
    return True


@nb.njit(cache=True, inline="always", error_model="numpy")
def covariance_is_pd_fused(p0_0, p0_1, p0_2, p0_3, p1_1, p1_2, p1_3, p2_2, p2_3, p3_3):
    """covariance_is_pd of the entries p<i>_<j> (upper triangle, row-major) as numbers, inlined into the fused
    steps (derive/codegen/fused.py), with pivots > 1e-11 · max_i P_ii."""
    tol = 1e-11 * max(p0_0, p1_1, p2_2, p3_3)
    d0 = p0_0
    if not d0 > tol:
        return False
    r0 = 1.0 / d0
    l1_0 = (p0_1) * r0
    l2_0 = (p0_2) * r0
    l3_0 = (p0_3) * r0
    d1 = p1_1 - l1_0 * l1_0 * d0
    if not d1 > tol:
        return False
    r1 = 1.0 / d1
    l2_1 = (p1_2 - l2_0 * l1_0 * d0) * r1
    l3_1 = (p1_3 - l3_0 * l1_0 * d0) * r1
    d2 = p2_2 - l2_0 * l2_0 * d0 - l2_1 * l2_1 * d1
    if not d2 > tol:
        return False
    r2 = 1.0 / d2
    l3_2 = (p2_3 - l3_0 * l2_0 * d0 - l3_1 * l2_1 * d1) * r2
    d3 = p3_3 - l3_0 * l3_0 * d0 - l3_1 * l3_1 * d1 - l3_2 * l3_2 * d2
    if not d3 > tol:
        return False
    return True


@nb.njit(cache=True)
def repair_pd(p):
    """Add the smallest diagonal jitter (1e-13 · max_i P_ii, growing ×4) that makes covariance_is_pd pass."""
    scale = 0.0
    for i in (0, 4, 7, 9):
        scale = max(scale, abs(p[i]))
    delta = 1e-13 * scale
    for _ in range(60):
        if covariance_is_pd(p):
            return
        for i in (0, 4, 7, 9):
            p[i] += delta
        delta *= 4.0


@nb.njit(inline="always", fastmath={"contract"}, error_model="numpy")
def covariance_is_pd_lane(W, j):
    """covariance_is_pd of lane j of the new covariance rows of W, without branches (all pivots)."""
    p0_0 = W[1152 + j]
    p0_1 = W[1216 + j]
    p0_2 = W[1280 + j]
    p0_3 = W[1344 + j]
    p1_1 = W[1408 + j]
    p1_2 = W[1472 + j]
    p1_3 = W[1536 + j]
    p2_2 = W[1600 + j]
    p2_3 = W[1664 + j]
    p3_3 = W[1728 + j]
    tol = 1e-13 * max(p0_0, p1_1, p2_2, p3_3)
    d0 = p0_0
    r0 = 1.0 / d0
    l1_0 = (p0_1) * r0
    l2_0 = (p0_2) * r0
    l3_0 = (p0_3) * r0
    d1 = p1_1 - l1_0 * l1_0 * d0
    r1 = 1.0 / d1
    l2_1 = (p1_2 - l2_0 * l1_0 * d0) * r1
    l3_1 = (p1_3 - l3_0 * l1_0 * d0) * r1
    d2 = p2_2 - l2_0 * l2_0 * d0 - l2_1 * l2_1 * d1
    r2 = 1.0 / d2
    l3_2 = (p2_3 - l3_0 * l2_0 * d0 - l3_1 * l2_1 * d1) * r2
    d3 = p3_3 - l3_0 * l3_0 * d0 - l3_1 * l3_1 * d1 - l3_2 * l3_2 * d2
    return (d0 > tol) & (d1 > tol) & (d2 > tol) & (d3 > tol)


@nb.njit(inline="always", fastmath={"contract"}, error_model="numpy")
def physical_lane(W, j, out, b, k):
    """Physical [x, y, vx, vy] from the internal state, written into ``out`` (no allocation).
    """
    x = W[896 + j]
    y = W[960 + j]
    w_x = W[1024 + j]
    w_y = W[1088 + j]
    out[b, k, 0] = x
    out[b, k, 1] = y
    out[b, k, 2] = w_x
    out[b, k, 3] = w_y


@nb.njit(cache=True)
def propagate(s, dt, n0, n1):
    """Exact motion X ← X exp([Ω(X) + G n]^∧) (eq:model) for one noise sample n, in place.
    """
    x = s[0]
    y = s[1]
    w_x = s[2]
    w_y = s[3]
    _t0 = (dt*dt)/2.0
    xn00 = _t0*n0 + dt*w_x + x
    xn01 = _t0*n1 + dt*w_y + y
    xn02 = dt*n0 + w_x
    xn03 = dt*n1 + w_y
    s[0] = xn00
    s[1] = xn01
    s[2] = xn02
    s[3] = xn03


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

    x0 (B, 4) physical initial states; dts (B, K) step lengths; noise (B, K, 2) samples of n (already
    scaled by their stds); out_x (B, K + 1, 4) receives the physical states, out_x[:, 0] = x0.
    """
    B = x0.shape[0]
    K = dts.shape[1]
    for b in nb.prange(B):
        s = state_from_physical(x0[b])
        physical_into(s, out_x[b, 0])
        for k in range(K):
            propagate(s, dts[b, k], noise[b, k, 0], noise[b, k, 1])
            physical_into(s, out_x[b, k + 1])


@nb.njit(cache=True, nogil=True)
def states_from_physical(x, out):
    """state_from_physical of every row: physical states x (N, 4) into internal states out (N, 4)."""
    for i in range(x.shape[0]):
        state_from_physical_into(x[i], out[i])


@nb.njit(cache=True, nogil=True)  # serial and nogil: threads may run it at once (lgekf.apps.search)
def propagate_rows(x, dts, out_x):
    """The noise-free exact motion of each row: out_x[i] = X_i exp([Ω(X_i)]^) over dts[i] (simulate_batch with
    zero noise, one step per row); x (N, 4) and out_x (N, 4) physical states, dts (N,)."""
    s = np.empty(4)
    for i in range(x.shape[0]):
        state_from_physical_into(x[i], s)
        propagate(s, dts[i], 0.0, 0.0)
        physical_into(s, out_x[i])


@nb.njit(cache=True, nogil=True)  # serial and nogil: threads may run it at once (lgekf.apps.search)
def propagate_positions(x, dts, out_xy):
    """The position (the first d physical coordinates, d the space's dimension) of ``propagate_rows``'s rows, bit for bit, into
    out_xy (N, d): the other coordinates are not converted (the noise search's one-step errors)."""
    s = np.empty(4)
    for i in range(x.shape[0]):
        state_from_physical_into(x[i], s)
        propagate(s, dts[i], 0.0, 0.0)
        position_into(s, out_xy[i])


@nb.njit(cache=True)
def world_velocity(x):
    """World-frame velocity (2,) of a physical state x of this model.
    """
    w_x = x[2]
    w_y = x[3]
    out = np.zeros(2)
    out[0] = w_x
    out[1] = w_y
    return out


@nb.njit(cache=True)
def world_velocity_into(x, out):
    """world_velocity of a physical state x written into out (2,) (no allocation).
    """
    w_x = x[2]
    w_y = x[3]
    out[0] = w_x
    out[1] = w_y


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
    out = np.zeros(4)
    _sin_c2 = math.sin(c2)
    _cos_c2 = math.cos(c2)
    out[0] = c0
    out[1] = c1
    out[2] = _cos_c2*c3 - _sin_c2*c4
    out[3] = _cos_c2*c4 + _sin_c2*c3
    return out


@nb.njit(cache=True)
def common_jacobian(c):
    """J = ∂(filter coordinates ε)/∂c at c: maps a covariance of c to the filter's P (P = J P_c J^T).
    """
    c2 = c[2]
    c3 = c[3]
    c4 = c[4]
    out = np.zeros((4, 6))
    _sin_c2 = math.sin(c2)
    _cos_c2 = math.cos(c2)
    out[0, 0] = 1.0
    out[1, 1] = 1.0
    out[2, 2] = -(_cos_c2*c4) - _sin_c2*c3
    out[2, 3] = _cos_c2
    out[2, 4] = -_sin_c2
    out[3, 2] = _cos_c2*c3 - _sin_c2*c4
    out[3, 3] = _sin_c2
    out[3, 4] = _cos_c2
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
    w_x = s[2]
    w_y = s[3]
    c0 = c[0]
    c1 = c[1]
    c2 = c[2]
    c3 = c[3]
    c4 = c[4]
    out = np.zeros(4)
    _sin_c2 = math.sin(c2)
    _cos_c2 = math.cos(c2)
    out[0] = c0 - x
    out[1] = c1 - y
    out[2] = _cos_c2*c3 - _sin_c2*c4 - w_x
    out[3] = _cos_c2*c4 + _sin_c2*c3 - w_y
    return out


@nb.njit(cache=True)
def retract(s, eps):
    """μ ← μ·exp([ε]^∧) in place (right perturbation; the update's eq:up_mu for a given ε).
    """
    x = s[0]
    y = s[1]
    w_x = s[2]
    w_y = s[3]
    eps0 = eps[0]
    eps1 = eps[1]
    eps2 = eps[2]
    eps3 = eps[3]
    s[0] = eps0 + x
    s[1] = eps1 + y
    s[2] = eps2 + w_x
    s[3] = eps3 + w_y


@nb.njit(cache=True)
def between(s, t):
    """[log_G(μ_s^-1 μ_t)]^∨: the tangent ε with μ_t = μ_s·exp(ε) (s ⊖: μ_s, t: μ_t, internal states);
    angle coordinates of a Euclidean model wrapped to (-π, π].
    """
    x = s[0]
    y = s[1]
    w_x = s[2]
    w_y = s[3]
    t_x = t[0]
    t_y = t[1]
    t_w_x = t[2]
    t_w_y = t[3]
    out = np.zeros(4)
    out[0] = t_x - x
    out[1] = t_y - y
    out[2] = t_w_x - w_x
    out[3] = t_w_y - w_y
    return out


@nb.njit(cache=True)
def right_jacobian(eps):
    """Φ_G(ε) of the whole group (block-diagonal over its factors, I for Rⁿ);
    log(exp(-ε) exp(ε + δ)) ≈ Φ_G(ε) δ.
    """
    out = np.zeros((4, 4))
    out[0, 0] = 1.0
    out[1, 1] = 1.0
    out[2, 2] = 1.0
    out[3, 3] = 1.0
    return out


@nb.njit(cache=True)
def right_jacobian_inv(eps):
    """Φ_G(ε)^-1 of the whole group.
    """
    out = np.zeros((4, 4))
    out[0, 0] = 1.0
    out[1, 1] = 1.0
    out[2, 2] = 1.0
    out[3, 3] = 1.0
    return out


@nb.njit(cache=True)
def predict_bank(s, p, live, dt, q):
    """The fused prediction (eq:pred_mu, eq:pred_cov) of every live track (rows of s and p) by dt, in place;
    q (1,) process-noise stds."""
    for i in range(s.shape[0]):
        if live[i]:
            predict(s[i], p[i], dt, q[0])


@nb.njit(cache=True)
def retract_bank(s, live, eps):
    """μ_i ← μ_i·exp([ε_i]^∧) for every live track (eq:up_mu with the given corrections eps (N, 4))."""
    for i in range(s.shape[0]):
        if live[i]:
            retract(s[i], eps[i])


@nb.njit(cache=True)
def right_jacobian_bank(live, eps, out):
    """Φ_G(ε_i) (eq:up_P) of every live track's correction eps (N, 4) into out (N, 4, 4)."""
    for i in range(eps.shape[0]):
        if live[i]:
            f = right_jacobian(eps[i])
            for a in range(4):
                for b in range(4):
                    out[i, a, b] = f[a, b]


@nb.njit(cache=True)
def innovation_logdet_position(s, p, r):
    """log det S, S = ℋ P ℋᵀ + R (eq:K) for a position measurement at the predicted state (s, p),
    noise stds (r): the log-determinant term of the innovation log-likelihood.
    """
    p00 = p[0]
    p01 = p[1]
    p11 = p[4]
    _t0 = r*r
    S00 = _t0 + p00
    S11 = _t0 + p11
    detS = S00*S11 - p01*p01
    return math.log(detS)


@nb.njit(cache=True, fastmath=FASTMATH, error_model="numpy")
def step_store_position(s, p, dt, sigma_a, z_x, z_y, r, sq, pq):
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
    w_x = s[2]
    w_y = s[3]
    p00 = p[0]
    p01 = p[1]
    p02 = p[2]
    p03 = p[3]
    p11 = p[4]
    p12 = p[5]
    p13 = p[6]
    p22 = p[7]
    p23 = p[8]
    p33 = p[9]
    _t0 = (dt*dt)/2.0
    g00 = _t0
    g11 = _t0
    e00 = dt*w_x + x
    e01 = dt*w_y + y
    _t1 = dt*p23
    m00 = dt*p02 + p00
    m01 = dt*p12 + p01
    m02 = dt*p22 + p02
    m03 = _t1 + p03
    m11 = dt*p13 + p11
    m12 = _t1 + p12
    m13 = dt*p33 + p13
    _t2 = sigma_a*sigma_a
    _t3 = _t2*dt
    _t4 = _t2*(dt*dt)
    pp00 = _t2*(g00*g00) + dt*m02 + m00
    pp01 = dt*m03 + m01
    pp02 = _t3*g00 + m02
    pp03 = m03
    pp11 = _t2*(g11*g11) + dt*m13 + m11
    pp12 = m12
    pp13 = _t3*g11 + m13
    pp22 = _t4 + p22
    pp23 = p23
    pp33 = _t4 + p33
    x_p = e00
    y_p = e01
    inn00 = -x_p + z_x
    inn10 = -y_p + z_y
    _t5 = r*r
    S00 = _t5 + pp00
    S11 = _t5 + pp11
    rdet = 1.0/(S00*S11 - pp01*pp01)
    Si00 = S11*rdet
    Si01 = -(pp01*rdet)
    Si11 = S00*rdet
    _t6 = Si01*pp01
    k00 = Si00*pp00 + _t6
    k01 = Si01*pp00 + Si11*pp01
    k10 = Si00*pp01 + Si01*pp11
    k11 = Si11*pp11 + _t6
    k20 = Si00*pp02 + Si01*pp12
    k21 = Si01*pp02 + Si11*pp12
    k30 = Si00*pp03 + Si01*pp13
    k31 = Si01*pp03 + Si11*pp13
    nis = Si00*(inn00*inn00) + 2.0*Si01*inn00*inn10 + Si11*(inn10*inn10)
    nk0 = inn00*k00 + inn10*k01
    nk1 = inn00*k10 + inn10*k11
    nk2 = inn00*k20 + inn10*k21
    nk3 = inn00*k30 + inn10*k31
    mu00 = nk0 + x_p
    mu01 = nk1 + y_p
    mu02 = nk2 + w_x
    mu03 = nk3 + w_y
    pj00 = -(k00*pp00) - k01*pp01 + pp00
    pj01 = -(k00*pp01) - k01*pp11 + pp01
    pj02 = -(k00*pp02) - k01*pp12 + pp02
    pj03 = -(k00*pp03) - k01*pp13 + pp03
    pj11 = -(k10*pp01) - k11*pp11 + pp11
    pj12 = -(k10*pp02) - k11*pp12 + pp12
    pj13 = -(k10*pp03) - k11*pp13 + pp13
    pj22 = -(k20*pp02) - k21*pp12 + pp22
    pj23 = -(k20*pp03) - k21*pp13 + pp23
    pj33 = -(k30*pp03) - k31*pp13 + pp33
    sq[0] = x_p
    sq[1] = y_p
    sq[2] = w_x
    sq[3] = w_y
    pq[0] = pp00
    pq[1] = pp01
    pq[2] = pp02
    pq[3] = pp03
    pq[4] = pp11
    pq[5] = pp12
    pq[6] = pp13
    pq[7] = pp22
    pq[8] = pp23
    pq[9] = pp33
    out_p0 = pj00
    out_p1 = pj01
    out_p2 = pj02
    out_p3 = pj03
    out_p4 = pj11
    out_p5 = pj12
    out_p6 = pj13
    out_p7 = pj22
    out_p8 = pj23
    out_p9 = pj33
    out_s0 = mu00
    out_s1 = mu01
    out_s2 = mu02
    out_s3 = mu03
    if not covariance_is_pd_fused(out_p0, out_p1, out_p2, out_p3, out_p4, out_p5, out_p6, out_p7, out_p8, out_p9):
        out_p0 = pp00
        out_p1 = pp01
        out_p2 = pp02
        out_p3 = pp03
        out_p4 = pp11
        out_p5 = pp12
        out_p6 = pp13
        out_p7 = pp22
        out_p8 = pp23
        out_p9 = pp33
        out_s0 = x_p
        out_s1 = y_p
        out_s2 = w_x
        out_s3 = w_y
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
    s[0] = out_s0
    s[1] = out_s1
    s[2] = out_s2
    s[3] = out_s3
    return nis, -math.log(rdet)


@nb.njit(inline="always", fastmath={"contract"}, error_model="numpy")
def lane_store_position(W, j, sigma_a, r):
    """step_store_position on lane j of the work array W (rows: derive/codegen/smooth_step.py), without branches (SIMD); 1/det S in a row of W.
    """
    x = W[0 + j]
    y = W[64 + j]
    w_x = W[128 + j]
    w_y = W[192 + j]
    p00 = W[256 + j]
    p01 = W[320 + j]
    p02 = W[384 + j]
    p03 = W[448 + j]
    p11 = W[512 + j]
    p12 = W[576 + j]
    p13 = W[640 + j]
    p22 = W[704 + j]
    p23 = W[768 + j]
    p33 = W[832 + j]
    dt = W[1792 + j]
    z_x = W[1984 + j]
    z_y = W[2048 + j]
    _t0 = (dt*dt)/2.0
    g00 = _t0
    g11 = _t0
    e00 = dt*w_x + x
    e01 = dt*w_y + y
    _t1 = dt*p23
    m00 = dt*p02 + p00
    m01 = dt*p12 + p01
    m02 = dt*p22 + p02
    m03 = _t1 + p03
    m11 = dt*p13 + p11
    m12 = _t1 + p12
    m13 = dt*p33 + p13
    _t2 = sigma_a*sigma_a
    _t3 = _t2*dt
    _t4 = _t2*(dt*dt)
    pp00 = _t2*(g00*g00) + dt*m02 + m00
    pp01 = dt*m03 + m01
    pp02 = _t3*g00 + m02
    pp03 = m03
    pp11 = _t2*(g11*g11) + dt*m13 + m11
    pp12 = m12
    pp13 = _t3*g11 + m13
    pp22 = _t4 + p22
    pp23 = p23
    pp33 = _t4 + p33
    x_p = e00
    y_p = e01
    inn00 = -x_p + z_x
    inn10 = -y_p + z_y
    _t5 = r*r
    S00 = _t5 + pp00
    S11 = _t5 + pp11
    rdet = 1.0/(S00*S11 - pp01*pp01)
    Si00 = S11*rdet
    Si01 = -(pp01*rdet)
    Si11 = S00*rdet
    _t6 = Si01*pp01
    k00 = Si00*pp00 + _t6
    k01 = Si01*pp00 + Si11*pp01
    k10 = Si00*pp01 + Si01*pp11
    k11 = Si11*pp11 + _t6
    k20 = Si00*pp02 + Si01*pp12
    k21 = Si01*pp02 + Si11*pp12
    k30 = Si00*pp03 + Si01*pp13
    k31 = Si01*pp03 + Si11*pp13
    nis = Si00*(inn00*inn00) + 2.0*Si01*inn00*inn10 + Si11*(inn10*inn10)
    nk0 = inn00*k00 + inn10*k01
    nk1 = inn00*k10 + inn10*k11
    nk2 = inn00*k20 + inn10*k21
    nk3 = inn00*k30 + inn10*k31
    mu00 = nk0 + x_p
    mu01 = nk1 + y_p
    mu02 = nk2 + w_x
    mu03 = nk3 + w_y
    pj00 = -(k00*pp00) - k01*pp01 + pp00
    pj01 = -(k00*pp01) - k01*pp11 + pp01
    pj02 = -(k00*pp02) - k01*pp12 + pp02
    pj03 = -(k00*pp03) - k01*pp13 + pp03
    pj11 = -(k10*pp01) - k11*pp11 + pp11
    pj12 = -(k10*pp02) - k11*pp12 + pp12
    pj13 = -(k10*pp03) - k11*pp13 + pp13
    pj22 = -(k20*pp02) - k21*pp12 + pp22
    pj23 = -(k20*pp03) - k21*pp13 + pp23
    pj33 = -(k30*pp03) - k31*pp13 + pp33
    W[2112 + j] = x_p
    W[2176 + j] = y_p
    W[2240 + j] = w_x
    W[2304 + j] = w_y
    W[2368 + j] = pp00
    W[2432 + j] = pp01
    W[2496 + j] = pp02
    W[2560 + j] = pp03
    W[2624 + j] = pp11
    W[2688 + j] = pp12
    W[2752 + j] = pp13
    W[2816 + j] = pp22
    W[2880 + j] = pp23
    W[2944 + j] = pp33
    W[1152 + j] = pj00
    W[1216 + j] = pj01
    W[1280 + j] = pj02
    W[1344 + j] = pj03
    W[1408 + j] = pj11
    W[1472 + j] = pj12
    W[1536 + j] = pj13
    W[1600 + j] = pj22
    W[1664 + j] = pj23
    W[1728 + j] = pj33
    W[896 + j] = mu00
    W[960 + j] = mu01
    W[1024 + j] = mu02
    W[1088 + j] = mu03
    W[3008 + j] = rdet
    return nis


@nb.njit(cache=True, parallel=True, fastmath=FASTMATH, error_model="numpy")
def run_batch_store_soa_position(z, dts, x0, p0, q, r, Qb, Fb, out_nis, out_logdet, out_x):
    """run_batch_store_position with trajectories in the SIMD lanes (derive/codegen/smooth_step.py), the same results
    with the states stored in blocks: Qb, Fb (nblk, K, 14, 64), nblk = ⌈B / 64⌉, get the predicted /
    posterior internal state and packed covariance of step k of trajectory blk·64 + j in Qb[blk, k, :, j]
    (lanes past B: zeros). As run_batch_soa_position (prange over blocks, lane_store_position vectorised over the lanes,
    a lane failing the LDLᵀ test or with a NaN row redone by the scalar predict / update_position)."""
    B = z.shape[0]
    K = z.shape[1]
    nblk = (B + 64 - 1) // 64
    for blk in nb.prange(nblk):
        lo = blk * 64
        L = min(64, B - lo)
        W = np.zeros(48 * 64)
        s = np.empty(4)
        p = np.empty(10)
        for j in range(L):
            s0 = state_from_physical(x0[lo + j])
            for i in range(4):
                W[(0 + i) * 64 + j] = s0[i]
            for i in range(10):
                W[(4 + i) * 64 + j] = p0[lo + j, i]
        for k in range(K):
            for j in range(L):
                W[28 * 64 + j] = dts[lo + j, k]
                W[31 * 64 + j] = z[lo + j, k, 0]
                W[32 * 64 + j] = z[lo + j, k, 1]
            for j in range(L):
                W[29 * 64 + j] = lane_store_position(W, j, q[0], r[0])
                good = covariance_is_pd_lane(W, j) & (W[29 * 64 + j] == W[29 * 64 + j])
                W[30 * 64 + j] = 1.0 if good else 0.0
            for j in range(L):
                b = lo + j
                if W[30 * 64 + j] == 0.0:
                    for i in range(4):
                        s[i] = W[(0 + i) * 64 + j]
                    for i in range(10):
                        p[i] = W[(4 + i) * 64 + j]
                    predict(s, p, dts[b, k], q[0])
                    for i in range(4):
                        W[(33 + i) * 64 + j] = s[i]
                    for i in range(10):
                        W[(37 + i) * 64 + j] = p[i]
                    if np.isnan(z[b, k, 0]) or np.isnan(z[b, k, 1]):
                        W[29 * 64 + j] = np.nan
                        out_logdet[b, k] = np.nan
                    else:
                        out_logdet[b, k] = innovation_logdet_position(s, p, r[0])
                        W[29 * 64 + j] = update_position(s, p, z[b, k, 0], z[b, k, 1], r[0])
                    for i in range(4):
                        W[(14 + i) * 64 + j] = s[i]
                    for i in range(10):
                        W[(18 + i) * 64 + j] = p[i]
                else:
                    out_logdet[b, k] = -math.log(W[47 * 64 + j])
            for j in range(L):
                out_nis[lo + j, k] = W[29 * 64 + j]
                physical_lane(W, j, out_x, lo + j, k)
            for i in range(4 + 10):
                for j in range(64):
                    Qb[blk, k, i, j] = W[(33 + i) * 64 + j]
                    Fb[blk, k, i, j] = W[(14 + i) * 64 + j]
            for i in range(4 + 10):
                for j in range(L):
                    W[(0 + i) * 64 + j] = W[(14 + i) * 64 + j]


@nb.njit(cache=True)
def run_one_store_position(z, dts, x0, p0, q, r, s_pred, p_pred, s_filt, p_filt, out_nis, out_logdet, out_x):
    """Filter one trajectory like run_one_position and keep every step's predicted internal state and packed
    covariance (s_pred (K, 4), p_pred (K, 10), before the update) and posterior ones (s_filt, p_filt),
    the NIS and log det S of each update (both NaN for a missed detection: a NaN row of z predicts only) and
    the posterior physical states out_x (K, 4). A step with a measurement is the fused step_store_position (the
    filter's step_try_position writing its prediction; derive/codegen/smooth_step.py), with the same Joseph-form
    fallback as run_one_position."""
    s = state_from_physical(x0)
    p = p0.copy()
    K = z.shape[0]
    for k in range(K):
        if np.isnan(z[k, 0]) or np.isnan(z[k, 1]):
            predict(s, p, dts[k], q[0])
            for i in range(4):
                s_pred[k, i] = s[i]
            for i in range(10):
                p_pred[k, i] = p[i]
            out_nis[k] = np.nan
            out_logdet[k] = np.nan
        else:
            nis, out_logdet[k] = step_store_position(s, p, dts[k], q[0], z[k, 0], z[k, 1], r[0], s_pred[k], p_pred[k])
            if nis < 0.0:  # rare: the cheap covariance failed the LDLᵀ test; Joseph form from the prediction
                nis = update_position(s, p, z[k, 0], z[k, 1], r[0])
            out_nis[k] = nis
        for i in range(4):
            s_filt[k, i] = s[i]
        for i in range(10):
            p_filt[k, i] = p[i]
        physical_into(s, out_x[k])


@nb.njit(cache=True, parallel=True)
def run_batch_store_position(z, dts, x0, p0, q, r, s_pred, p_pred, s_filt, p_filt, out_nis, out_logdet, out_x):
    """run_one_store_position over B trajectories in parallel (prange); arrays as run_batch_position with a
    leading batch axis (s_pred, s_filt (B, K, 4); p_pred, p_filt (B, K, 10); out_nis, out_logdet (B, K);
    out_x (B, K, 4))."""
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
            predict(s, p, dts[b, k], q[0])
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
    w_x = s_filt[k, 2]
    w_y = s_filt[k, 3]
    pf00 = p_filt[k, 0]
    pf01 = p_filt[k, 1]
    pf02 = p_filt[k, 2]
    pf03 = p_filt[k, 3]
    pf11 = p_filt[k, 4]
    pf12 = p_filt[k, 5]
    pf13 = p_filt[k, 6]
    pf22 = p_filt[k, 7]
    pf23 = p_filt[k, 8]
    pf33 = p_filt[k, 9]
    q_x = s_pred[k + 1, 0]
    q_y = s_pred[k + 1, 1]
    q_w_x = s_pred[k + 1, 2]
    q_w_y = s_pred[k + 1, 3]
    pq00 = p_pred[k + 1, 0]
    pq01 = p_pred[k + 1, 1]
    pq02 = p_pred[k + 1, 2]
    pq03 = p_pred[k + 1, 3]
    pq11 = p_pred[k + 1, 4]
    pq12 = p_pred[k + 1, 5]
    pq13 = p_pred[k + 1, 6]
    pq22 = p_pred[k + 1, 7]
    pq23 = p_pred[k + 1, 8]
    pq33 = p_pred[k + 1, 9]
    t_x = s_sm[k + 1, 0]
    t_y = s_sm[k + 1, 1]
    t_w_x = s_sm[k + 1, 2]
    t_w_y = s_sm[k + 1, 3]
    ps00 = p_sm[k + 1, 0]
    ps01 = p_sm[k + 1, 1]
    ps02 = p_sm[k + 1, 2]
    ps03 = p_sm[k + 1, 3]
    ps11 = p_sm[k + 1, 4]
    ps12 = p_sm[k + 1, 5]
    ps13 = p_sm[k + 1, 6]
    ps22 = p_sm[k + 1, 7]
    ps23 = p_sm[k + 1, 8]
    ps33 = p_sm[k + 1, 9]
    _t0 = dt*pf23
    cf0_0 = dt*pf02 + pf00
    cf0_1 = dt*pf03 + pf01
    cf1_0 = dt*pf12 + pf01
    cf1_1 = dt*pf13 + pf11
    cf2_0 = dt*pf22 + pf02
    cf2_1 = _t0 + pf12
    cf3_0 = _t0 + pf03
    cf3_1 = dt*pf33 + pf13
    dd0_0 = -q_x + t_x
    dd0_1 = -q_y + t_y
    dd0_2 = -q_w_x + t_w_x
    dd0_3 = -q_w_y + t_w_y
    dm0_0 = -pq00 + ps00
    dm0_1 = -pq01 + ps01
    dm0_2 = -pq02 + ps02
    dm0_3 = -pq03 + ps03
    dm1_1 = -pq11 + ps11
    dm1_2 = -pq12 + ps12
    dm1_3 = -pq13 + ps13
    dm2_2 = -pq22 + ps22
    dm2_3 = -pq23 + ps23
    dm3_3 = -pq33 + ps33
    lr0 = 1.0/max(1e-300, pq00)
    ll1_0 = lr0*pq01
    ll2_0 = lr0*pq02
    ll3_0 = lr0*pq03
    lw1_0 = ll1_0*pq00
    lw2_0 = ll2_0*pq00
    lw3_0 = ll3_0*pq00
    ly0_1 = -(cf0_0*ll1_0) + cf0_1
    ly1_1 = -(cf1_0*ll1_0) + cf1_1
    ly2_1 = -(cf2_0*ll1_0) + cf2_1
    ly3_1 = -(cf3_0*ll1_0) + cf3_1
    ld1 = -(ll1_0*lw1_0) + pq11
    lr1 = 1.0/max(1e-300, ld1)
    ll2_1 = lr1*(-(ll2_0*lw1_0) + pq12)
    ll3_1 = lr1*(-(ll3_0*lw1_0) + pq13)
    lw2_1 = ld1*ll2_1
    lw3_1 = ld1*ll3_1
    ly0_2 = -(cf0_0*ll2_0) - ll2_1*ly0_1 + pf02
    ly1_2 = -(cf1_0*ll2_0) - ll2_1*ly1_1 + pf12
    ly2_2 = -(cf2_0*ll2_0) - ll2_1*ly2_1 + pf22
    ly3_2 = -(cf3_0*ll2_0) - ll2_1*ly3_1 + pf23
    ld2 = -(ll2_0*lw2_0) - ll2_1*lw2_1 + pq22
    lr2 = 1.0/max(1e-300, ld2)
    ll3_2 = lr2*(-(ll3_0*lw2_0) - ll3_1*lw2_1 + pq23)
    lw3_2 = ld2*ll3_2
    ly0_3 = -(cf0_0*ll3_0) - ll3_1*ly0_1 - ll3_2*ly0_2 + pf03
    ly1_3 = -(cf1_0*ll3_0) - ll3_1*ly1_1 - ll3_2*ly1_2 + pf13
    ly2_3 = -(cf2_0*ll3_0) - ll3_1*ly2_1 - ll3_2*ly2_2 + pf23
    ly3_3 = -(cf3_0*ll3_0) - ll3_1*ly3_1 - ll3_2*ly3_2 + pf33
    ld3 = -(ll3_0*lw3_0) - ll3_1*lw3_1 - ll3_2*lw3_2 + pq33
    lr3 = 1.0/max(1e-300, ld3)
    gg0_3 = lr3*ly0_3
    gg1_3 = lr3*ly1_3
    gg2_3 = lr3*ly2_3
    gg3_3 = lr3*ly3_3
    gg0_2 = -(gg0_3*ll3_2) + lr2*ly0_2
    gg1_2 = -(gg1_3*ll3_2) + lr2*ly1_2
    gg2_2 = -(gg2_3*ll3_2) + lr2*ly2_2
    gg3_2 = -(gg3_3*ll3_2) + lr2*ly3_2
    gg0_1 = -(gg0_2*ll2_1) - gg0_3*ll3_1 + lr1*ly0_1
    gg1_1 = -(gg1_2*ll2_1) - gg1_3*ll3_1 + lr1*ly1_1
    gg2_1 = -(gg2_2*ll2_1) - gg2_3*ll3_1 + lr1*ly2_1
    gg3_1 = -(gg3_2*ll2_1) - gg3_3*ll3_1 + lr1*ly3_1
    gg0_0 = cf0_0*lr0 - gg0_1*ll1_0 - gg0_2*ll2_0 - gg0_3*ll3_0
    gg1_0 = cf1_0*lr0 - gg1_1*ll1_0 - gg1_2*ll2_0 - gg1_3*ll3_0
    gg2_0 = cf2_0*lr0 - gg2_1*ll1_0 - gg2_2*ll2_0 - gg2_3*ll3_0
    gg3_0 = cf3_0*lr0 - gg3_1*ll1_0 - gg3_2*ll2_0 - gg3_3*ll3_0
    de0_0 = dd0_0*gg0_0 + dd0_1*gg0_1 + dd0_2*gg0_2 + dd0_3*gg0_3
    de1_0 = dd0_0*gg1_0 + dd0_1*gg1_1 + dd0_2*gg1_2 + dd0_3*gg1_3
    de2_0 = dd0_0*gg2_0 + dd0_1*gg2_1 + dd0_2*gg2_2 + dd0_3*gg2_3
    de3_0 = dd0_0*gg3_0 + dd0_1*gg3_1 + dd0_2*gg3_2 + dd0_3*gg3_3
    gd0_0 = dm0_0*gg0_0 + dm0_1*gg0_1 + dm0_2*gg0_2 + dm0_3*gg0_3
    gd0_1 = dm0_1*gg0_0 + dm1_1*gg0_1 + dm1_2*gg0_2 + dm1_3*gg0_3
    gd0_2 = dm0_2*gg0_0 + dm1_2*gg0_1 + dm2_2*gg0_2 + dm2_3*gg0_3
    gd0_3 = dm0_3*gg0_0 + dm1_3*gg0_1 + dm2_3*gg0_2 + dm3_3*gg0_3
    gd1_0 = dm0_0*gg1_0 + dm0_1*gg1_1 + dm0_2*gg1_2 + dm0_3*gg1_3
    gd1_1 = dm0_1*gg1_0 + dm1_1*gg1_1 + dm1_2*gg1_2 + dm1_3*gg1_3
    gd1_2 = dm0_2*gg1_0 + dm1_2*gg1_1 + dm2_2*gg1_2 + dm2_3*gg1_3
    gd1_3 = dm0_3*gg1_0 + dm1_3*gg1_1 + dm2_3*gg1_2 + dm3_3*gg1_3
    gd2_0 = dm0_0*gg2_0 + dm0_1*gg2_1 + dm0_2*gg2_2 + dm0_3*gg2_3
    gd2_1 = dm0_1*gg2_0 + dm1_1*gg2_1 + dm1_2*gg2_2 + dm1_3*gg2_3
    gd2_2 = dm0_2*gg2_0 + dm1_2*gg2_1 + dm2_2*gg2_2 + dm2_3*gg2_3
    gd2_3 = dm0_3*gg2_0 + dm1_3*gg2_1 + dm2_3*gg2_2 + dm3_3*gg2_3
    gd3_0 = dm0_0*gg3_0 + dm0_1*gg3_1 + dm0_2*gg3_2 + dm0_3*gg3_3
    gd3_1 = dm0_1*gg3_0 + dm1_1*gg3_1 + dm1_2*gg3_2 + dm1_3*gg3_3
    gd3_2 = dm0_2*gg3_0 + dm1_2*gg3_1 + dm2_2*gg3_2 + dm2_3*gg3_3
    gd3_3 = dm0_3*gg3_0 + dm1_3*gg3_1 + dm2_3*gg3_2 + dm3_3*gg3_3
    pt0_0 = gd0_0*gg0_0 + gd0_1*gg0_1 + gd0_2*gg0_2 + gd0_3*gg0_3 + pf00
    pt0_1 = gd0_0*gg1_0 + gd0_1*gg1_1 + gd0_2*gg1_2 + gd0_3*gg1_3 + pf01
    pt0_2 = gd0_0*gg2_0 + gd0_1*gg2_1 + gd0_2*gg2_2 + gd0_3*gg2_3 + pf02
    pt0_3 = gd0_0*gg3_0 + gd0_1*gg3_1 + gd0_2*gg3_2 + gd0_3*gg3_3 + pf03
    pt1_1 = gd1_0*gg1_0 + gd1_1*gg1_1 + gd1_2*gg1_2 + gd1_3*gg1_3 + pf11
    pt1_2 = gd1_0*gg2_0 + gd1_1*gg2_1 + gd1_2*gg2_2 + gd1_3*gg2_3 + pf12
    pt1_3 = gd1_0*gg3_0 + gd1_1*gg3_1 + gd1_2*gg3_2 + gd1_3*gg3_3 + pf13
    pt2_2 = gd2_0*gg2_0 + gd2_1*gg2_1 + gd2_2*gg2_2 + gd2_3*gg2_3 + pf22
    pt2_3 = gd2_0*gg3_0 + gd2_1*gg3_1 + gd2_2*gg3_2 + gd2_3*gg3_3 + pf23
    pt3_3 = gd3_0*gg3_0 + gd3_1*gg3_1 + gd3_2*gg3_2 + gd3_3*gg3_3 + pf33
    p_sm[k, 0] = pt0_0
    p_sm[k, 1] = pt0_1
    p_sm[k, 2] = pt0_2
    p_sm[k, 3] = pt0_3
    p_sm[k, 4] = pt1_1
    p_sm[k, 5] = pt1_2
    p_sm[k, 6] = pt1_3
    p_sm[k, 7] = pt2_2
    p_sm[k, 8] = pt2_3
    p_sm[k, 9] = pt3_3
    s_sm[k, 0] = de0_0 + x
    s_sm[k, 1] = de1_0 + y
    s_sm[k, 2] = de2_0 + w_x
    s_sm[k, 3] = de3_0 + w_y


@nb.njit(inline="always", fastmath={"contract"}, error_model="numpy")
def lane_smooth(W, j):
    """smooth_step on lane j of the work array W (rows: derive/codegen/smooth_step.py), without branches (SIMD).
    """
    x = W[0 + j]
    y = W[64 + j]
    w_x = W[128 + j]
    w_y = W[192 + j]
    pf00 = W[256 + j]
    pf01 = W[320 + j]
    pf02 = W[384 + j]
    pf03 = W[448 + j]
    pf11 = W[512 + j]
    pf12 = W[576 + j]
    pf13 = W[640 + j]
    pf22 = W[704 + j]
    pf23 = W[768 + j]
    pf33 = W[832 + j]
    q_x = W[896 + j]
    q_y = W[960 + j]
    q_w_x = W[1024 + j]
    q_w_y = W[1088 + j]
    pq00 = W[1152 + j]
    pq01 = W[1216 + j]
    pq02 = W[1280 + j]
    pq03 = W[1344 + j]
    pq11 = W[1408 + j]
    pq12 = W[1472 + j]
    pq13 = W[1536 + j]
    pq22 = W[1600 + j]
    pq23 = W[1664 + j]
    pq33 = W[1728 + j]
    t_x = W[1792 + j]
    t_y = W[1856 + j]
    t_w_x = W[1920 + j]
    t_w_y = W[1984 + j]
    ps00 = W[2048 + j]
    ps01 = W[2112 + j]
    ps02 = W[2176 + j]
    ps03 = W[2240 + j]
    ps11 = W[2304 + j]
    ps12 = W[2368 + j]
    ps13 = W[2432 + j]
    ps22 = W[2496 + j]
    ps23 = W[2560 + j]
    ps33 = W[2624 + j]
    dt = W[3584 + j]
    _t0 = dt*pf23
    cf0_0 = dt*pf02 + pf00
    cf0_1 = dt*pf03 + pf01
    cf1_0 = dt*pf12 + pf01
    cf1_1 = dt*pf13 + pf11
    cf2_0 = dt*pf22 + pf02
    cf2_1 = _t0 + pf12
    cf3_0 = _t0 + pf03
    cf3_1 = dt*pf33 + pf13
    dd0_0 = -q_x + t_x
    dd0_1 = -q_y + t_y
    dd0_2 = -q_w_x + t_w_x
    dd0_3 = -q_w_y + t_w_y
    dm0_0 = -pq00 + ps00
    dm0_1 = -pq01 + ps01
    dm0_2 = -pq02 + ps02
    dm0_3 = -pq03 + ps03
    dm1_1 = -pq11 + ps11
    dm1_2 = -pq12 + ps12
    dm1_3 = -pq13 + ps13
    dm2_2 = -pq22 + ps22
    dm2_3 = -pq23 + ps23
    dm3_3 = -pq33 + ps33
    lr0 = 1.0/max(1e-300, pq00)
    ll1_0 = lr0*pq01
    ll2_0 = lr0*pq02
    ll3_0 = lr0*pq03
    lw1_0 = ll1_0*pq00
    lw2_0 = ll2_0*pq00
    lw3_0 = ll3_0*pq00
    ly0_1 = -(cf0_0*ll1_0) + cf0_1
    ly1_1 = -(cf1_0*ll1_0) + cf1_1
    ly2_1 = -(cf2_0*ll1_0) + cf2_1
    ly3_1 = -(cf3_0*ll1_0) + cf3_1
    ld1 = -(ll1_0*lw1_0) + pq11
    lr1 = 1.0/max(1e-300, ld1)
    ll2_1 = lr1*(-(ll2_0*lw1_0) + pq12)
    ll3_1 = lr1*(-(ll3_0*lw1_0) + pq13)
    lw2_1 = ld1*ll2_1
    lw3_1 = ld1*ll3_1
    ly0_2 = -(cf0_0*ll2_0) - ll2_1*ly0_1 + pf02
    ly1_2 = -(cf1_0*ll2_0) - ll2_1*ly1_1 + pf12
    ly2_2 = -(cf2_0*ll2_0) - ll2_1*ly2_1 + pf22
    ly3_2 = -(cf3_0*ll2_0) - ll2_1*ly3_1 + pf23
    ld2 = -(ll2_0*lw2_0) - ll2_1*lw2_1 + pq22
    lr2 = 1.0/max(1e-300, ld2)
    ll3_2 = lr2*(-(ll3_0*lw2_0) - ll3_1*lw2_1 + pq23)
    lw3_2 = ld2*ll3_2
    ly0_3 = -(cf0_0*ll3_0) - ll3_1*ly0_1 - ll3_2*ly0_2 + pf03
    ly1_3 = -(cf1_0*ll3_0) - ll3_1*ly1_1 - ll3_2*ly1_2 + pf13
    ly2_3 = -(cf2_0*ll3_0) - ll3_1*ly2_1 - ll3_2*ly2_2 + pf23
    ly3_3 = -(cf3_0*ll3_0) - ll3_1*ly3_1 - ll3_2*ly3_2 + pf33
    ld3 = -(ll3_0*lw3_0) - ll3_1*lw3_1 - ll3_2*lw3_2 + pq33
    lr3 = 1.0/max(1e-300, ld3)
    gg0_3 = lr3*ly0_3
    gg1_3 = lr3*ly1_3
    gg2_3 = lr3*ly2_3
    gg3_3 = lr3*ly3_3
    gg0_2 = -(gg0_3*ll3_2) + lr2*ly0_2
    gg1_2 = -(gg1_3*ll3_2) + lr2*ly1_2
    gg2_2 = -(gg2_3*ll3_2) + lr2*ly2_2
    gg3_2 = -(gg3_3*ll3_2) + lr2*ly3_2
    gg0_1 = -(gg0_2*ll2_1) - gg0_3*ll3_1 + lr1*ly0_1
    gg1_1 = -(gg1_2*ll2_1) - gg1_3*ll3_1 + lr1*ly1_1
    gg2_1 = -(gg2_2*ll2_1) - gg2_3*ll3_1 + lr1*ly2_1
    gg3_1 = -(gg3_2*ll2_1) - gg3_3*ll3_1 + lr1*ly3_1
    gg0_0 = cf0_0*lr0 - gg0_1*ll1_0 - gg0_2*ll2_0 - gg0_3*ll3_0
    gg1_0 = cf1_0*lr0 - gg1_1*ll1_0 - gg1_2*ll2_0 - gg1_3*ll3_0
    gg2_0 = cf2_0*lr0 - gg2_1*ll1_0 - gg2_2*ll2_0 - gg2_3*ll3_0
    gg3_0 = cf3_0*lr0 - gg3_1*ll1_0 - gg3_2*ll2_0 - gg3_3*ll3_0
    de0_0 = dd0_0*gg0_0 + dd0_1*gg0_1 + dd0_2*gg0_2 + dd0_3*gg0_3
    de1_0 = dd0_0*gg1_0 + dd0_1*gg1_1 + dd0_2*gg1_2 + dd0_3*gg1_3
    de2_0 = dd0_0*gg2_0 + dd0_1*gg2_1 + dd0_2*gg2_2 + dd0_3*gg2_3
    de3_0 = dd0_0*gg3_0 + dd0_1*gg3_1 + dd0_2*gg3_2 + dd0_3*gg3_3
    gd0_0 = dm0_0*gg0_0 + dm0_1*gg0_1 + dm0_2*gg0_2 + dm0_3*gg0_3
    gd0_1 = dm0_1*gg0_0 + dm1_1*gg0_1 + dm1_2*gg0_2 + dm1_3*gg0_3
    gd0_2 = dm0_2*gg0_0 + dm1_2*gg0_1 + dm2_2*gg0_2 + dm2_3*gg0_3
    gd0_3 = dm0_3*gg0_0 + dm1_3*gg0_1 + dm2_3*gg0_2 + dm3_3*gg0_3
    gd1_0 = dm0_0*gg1_0 + dm0_1*gg1_1 + dm0_2*gg1_2 + dm0_3*gg1_3
    gd1_1 = dm0_1*gg1_0 + dm1_1*gg1_1 + dm1_2*gg1_2 + dm1_3*gg1_3
    gd1_2 = dm0_2*gg1_0 + dm1_2*gg1_1 + dm2_2*gg1_2 + dm2_3*gg1_3
    gd1_3 = dm0_3*gg1_0 + dm1_3*gg1_1 + dm2_3*gg1_2 + dm3_3*gg1_3
    gd2_0 = dm0_0*gg2_0 + dm0_1*gg2_1 + dm0_2*gg2_2 + dm0_3*gg2_3
    gd2_1 = dm0_1*gg2_0 + dm1_1*gg2_1 + dm1_2*gg2_2 + dm1_3*gg2_3
    gd2_2 = dm0_2*gg2_0 + dm1_2*gg2_1 + dm2_2*gg2_2 + dm2_3*gg2_3
    gd2_3 = dm0_3*gg2_0 + dm1_3*gg2_1 + dm2_3*gg2_2 + dm3_3*gg2_3
    gd3_0 = dm0_0*gg3_0 + dm0_1*gg3_1 + dm0_2*gg3_2 + dm0_3*gg3_3
    gd3_1 = dm0_1*gg3_0 + dm1_1*gg3_1 + dm1_2*gg3_2 + dm1_3*gg3_3
    gd3_2 = dm0_2*gg3_0 + dm1_2*gg3_1 + dm2_2*gg3_2 + dm2_3*gg3_3
    gd3_3 = dm0_3*gg3_0 + dm1_3*gg3_1 + dm2_3*gg3_2 + dm3_3*gg3_3
    pt0_0 = gd0_0*gg0_0 + gd0_1*gg0_1 + gd0_2*gg0_2 + gd0_3*gg0_3 + pf00
    pt0_1 = gd0_0*gg1_0 + gd0_1*gg1_1 + gd0_2*gg1_2 + gd0_3*gg1_3 + pf01
    pt0_2 = gd0_0*gg2_0 + gd0_1*gg2_1 + gd0_2*gg2_2 + gd0_3*gg2_3 + pf02
    pt0_3 = gd0_0*gg3_0 + gd0_1*gg3_1 + gd0_2*gg3_2 + gd0_3*gg3_3 + pf03
    pt1_1 = gd1_0*gg1_0 + gd1_1*gg1_1 + gd1_2*gg1_2 + gd1_3*gg1_3 + pf11
    pt1_2 = gd1_0*gg2_0 + gd1_1*gg2_1 + gd1_2*gg2_2 + gd1_3*gg2_3 + pf12
    pt1_3 = gd1_0*gg3_0 + gd1_1*gg3_1 + gd1_2*gg3_2 + gd1_3*gg3_3 + pf13
    pt2_2 = gd2_0*gg2_0 + gd2_1*gg2_1 + gd2_2*gg2_2 + gd2_3*gg2_3 + pf22
    pt2_3 = gd2_0*gg3_0 + gd2_1*gg3_1 + gd2_2*gg3_2 + gd2_3*gg3_3 + pf23
    pt3_3 = gd3_0*gg3_0 + gd3_1*gg3_1 + gd3_2*gg3_2 + gd3_3*gg3_3 + pf33
    W[2944 + j] = pt0_0
    W[3008 + j] = pt0_1
    W[3072 + j] = pt0_2
    W[3136 + j] = pt0_3
    W[3200 + j] = pt1_1
    W[3264 + j] = pt1_2
    W[3328 + j] = pt1_3
    W[3392 + j] = pt2_2
    W[3456 + j] = pt2_3
    W[3520 + j] = pt3_3
    W[2688 + j] = de0_0 + x
    W[2752 + j] = de1_0 + y
    W[2816 + j] = de2_0 + w_x
    W[2880 + j] = de3_0 + w_y


@nb.njit(inline="always", fastmath={"contract"}, error_model="numpy")
def physical_smooth_lane(W, j, out, b, k):
    """The physical state of lane j of the smoothed rows of the work array W into out[b, k] (SIMD).
    """
    x = W[1792 + j]
    y = W[1856 + j]
    w_x = W[1920 + j]
    w_y = W[1984 + j]
    out[b, k, 0] = x
    out[b, k, 1] = y
    out[b, k, 2] = w_x
    out[b, k, 3] = w_y


@nb.njit(cache=True, parallel=True, fastmath=FASTMATH, error_model="numpy")
def smooth_batch_soa(dts, Qb, Fb, lengths, Sb, out_x):
    """smooth_batch with trajectories in the SIMD lanes (derive/codegen/smooth_step.py), over a forward pass stored
    in blocks by run_batch_store_soa_<meas>: Qb, Fb (nblk, K, 14, 64) hold the predicted / posterior internal
    state and packed covariance of step k of trajectory blk·64 + j in Qb[blk, k, :, j]; writes the smoothed ones
    into Sb (same layout; pass Sb with no steps, (nblk, 0, 14, 64), to skip them) and the smoothed physical
    states into out_x (B, K, 4). Trajectory b starts at its last
    step lengths[b] − 1 (smoothed = filtered there); entries past its length are left unset. Per block (prange) and
    step, the rows are copied into one work array (rows × 64) and lane_smooth runs vectorised over the lanes.
    """
    B = dts.shape[0]
    nblk = Qb.shape[0]
    keep = Sb.shape[1] > 0
    for blk in nb.prange(nblk):
        lo = blk * 64
        L = min(64, B - lo)
        W = np.zeros(59 * 64)
        Kmax = 0
        for j in range(L):
            Kmax = max(Kmax, lengths[lo + j])
        for k in range(Kmax - 1, -1, -1):
            for i in range(14):
                for j in range(64):
                    W[(0 + i) * 64 + j] = Fb[blk, k, i, j]
            for j in range(L):
                Kb = lengths[lo + j]
                W[57 * 64 + j] = 1.0 if k < Kb - 1 else 0.0
                W[58 * 64 + j] = 1.0 if k == Kb - 1 else 0.0
            if k < Kmax - 1:
                for i in range(14):
                    for j in range(64):
                        W[(14 + i) * 64 + j] = Qb[blk, k + 1, i, j]
                for j in range(L):
                    W[56 * 64 + j] = dts[lo + j, k + 1]
                for j in range(L):
                    lane_smooth(W, j)
                for i in range(14):
                    for j in range(64):
                        act = W[57 * 64 + j] > 0.5
                        W[(28 + i) * 64 + j] = W[(42 + i) * 64 + j] if act else W[(28 + i) * 64 + j]
            for i in range(14):
                for j in range(64):
                    start = W[58 * 64 + j] > 0.5
                    W[(28 + i) * 64 + j] = W[(0 + i) * 64 + j] if start else W[(28 + i) * 64 + j]
            if keep:
                for i in range(14):
                    for j in range(64):
                        Sb[blk, k, i, j] = W[(28 + i) * 64 + j]
            for j in range(L):
                if k < lengths[lo + j]:
                    physical_smooth_lane(W, j, out_x, lo + j, k)


@nb.njit(cache=True)
def smooth_one(dts, s_pred, p_pred, s_filt, p_filt, K, s_sm, p_sm):
    """Rauch–Tung–Striebel backward pass on the group over the first K steps (derivation:
    lgekf.estimators.smoother). dts (K,) step lengths (dts[k] led to step k); s_pred, p_pred / s_filt, p_filt:
    predicted / posterior internal states and packed covariances (run_one_store_*); writes the smoothed ones
    into s_sm (K, 4), p_sm (K, 10). For k = K-2 ... 0, with F = transition(μ_k, dts[k+1]):
    d = log(μ_{k+1|k}⁻¹ μˢ_{k+1}), P̄ = Φ(d)⁻¹ Pˢ_{k+1} Φ(d)⁻ᵀ, G = P_k Fᵀ P_{k+1|k}⁻¹, δ = G d,
    μˢ_k = μ_k·exp(δ), Pˢ_k = Φ(δ) [P_k + G (P̄ − P_{k+1|k}) Gᵀ] Φ(δ)ᵀ."""
    for i in range(4):
        s_sm[K - 1, i] = s_filt[K - 1, i]
    for i in range(10):
        p_sm[K - 1, i] = p_filt[K - 1, i]
    for k in range(K - 2, -1, -1):
        smooth_step_at(s_filt, p_filt, s_pred, p_pred, s_sm, p_sm, k, dts[k + 1])  # smooth_step on the rows k, k + 1


@nb.njit(cache=True, parallel=True)
def smooth_batch(dts, s_pred, p_pred, s_filt, p_filt, lengths, s_sm, p_sm, out_x):
    """smooth_one for B trajectories (prange), trajectory b over its first lengths[b] steps; also writes the
    smoothed physical states into out_x (B, K, 4)."""
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
    w_x = xp[2]
    w_y = xp[3]
    out = np.zeros(6)
    out[0] = x
    out[1] = y
    out[2] = math.atan2(w_y, w_x)
    out[3] = math.sqrt(w_x*w_x + w_y*w_y)
    return out


@nb.njit(cache=True)
def physical_to_common_jacobian(xp):
    """A = ∂c/∂ε (6 × n) at the physical state x (X = μ·exp ε): P_c = A P Aᵀ.
    """
    w_x = xp[2]
    w_y = xp[3]
    out = np.zeros((6, 4))
    _t0 = w_x*w_x + w_y*w_y
    _t1 = 1.0/_t0
    _t2 = 1.0/math.sqrt(_t0)
    out[0, 0] = 1.0
    out[1, 1] = 1.0
    out[2, 2] = -(_t1*w_y)
    out[2, 3] = _t1*w_x
    out[3, 2] = _t2*w_x
    out[3, 3] = _t2*w_y
    return out


@nb.njit(cache=True)
def common_missing():
    """1.0 for each common coordinate (x, y, θ, v_x, v_y, ω) the model carries no information on."""
    return np.array([0.0, 0.0, 0.0, 0.0, 0.0, 1.0])


@nb.njit(cache=True)
def state_from_physical_into(xp, out):
    """Internal state [x, y, w_x, w_y] from the physical [x, y, vx, vy].
    Written into ``out`` (no allocation).
    """
    x = xp[0]
    y = xp[1]
    w_x = xp[2]
    w_y = xp[3]
    out[:] = 0.0
    out[0] = x
    out[1] = y
    out[2] = w_x
    out[3] = w_y


@nb.njit(cache=True)
def transition_into(s, dt, out):
    """F = Ad_G(exp(-Ω)) + Φ_G(Ω) 𝒞 (paper, below eq:pred_cov).
    Written into ``out`` (no allocation).
    """
    out[:, :] = 0.0
    out[0, 0] = 1.0
    out[0, 2] = dt
    out[1, 1] = 1.0
    out[1, 3] = dt
    out[2, 2] = 1.0
    out[3, 3] = 1.0


@nb.njit(cache=True)
def calH_position_into(s, out):
    """ℋ = ∂[log_G'(h(μ)^-1 h(μ exp ε))]^∨/∂ε at ε = 0 (eq:calH, eq:calH_model) for position measurements.
    Written into ``out`` (no allocation).
    """
    out[:, :] = 0.0
    out[0, 0] = 1.0
    out[1, 1] = 1.0


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
    out[:] = 0.0
    _sin_c2 = math.sin(c2)
    _cos_c2 = math.cos(c2)
    out[0] = c0
    out[1] = c1
    out[2] = _cos_c2*c3 - _sin_c2*c4
    out[3] = _cos_c2*c4 + _sin_c2*c3


@nb.njit(cache=True)
def common_jacobian_into(c, out):
    """J = ∂(filter coordinates ε)/∂c at c: maps a covariance of c to the filter's P (P = J P_c J^T).
    Written into ``out`` (no allocation).
    """
    c2 = c[2]
    c3 = c[3]
    c4 = c[4]
    out[:, :] = 0.0
    _sin_c2 = math.sin(c2)
    _cos_c2 = math.cos(c2)
    out[0, 0] = 1.0
    out[1, 1] = 1.0
    out[2, 2] = -(_cos_c2*c4) - _sin_c2*c3
    out[2, 3] = _cos_c2
    out[2, 4] = -_sin_c2
    out[3, 2] = _cos_c2*c3 - _sin_c2*c4
    out[3, 3] = _sin_c2
    out[3, 4] = _cos_c2


@nb.njit(cache=True)
def between_into(s, t, out):
    """[log_G(μ_s^-1 μ_t)]^∨: the tangent ε with μ_t = μ_s·exp(ε) (s ⊖: μ_s, t: μ_t, internal states);
    angle coordinates of a Euclidean model wrapped to (-π, π].
    Written into ``out`` (no allocation).
    """
    x = s[0]
    y = s[1]
    w_x = s[2]
    w_y = s[3]
    t_x = t[0]
    t_y = t[1]
    t_w_x = t[2]
    t_w_y = t[3]
    out[:] = 0.0
    out[0] = t_x - x
    out[1] = t_y - y
    out[2] = t_w_x - w_x
    out[3] = t_w_y - w_y


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


@nb.njit(cache=True)
def physical_to_common_into(xp, out):
    """c = (x, y, θ, v_x, v_y, ω) of a physical state x (θ from the velocity for a model
    without a heading; 0 for the coordinates of common_missing).
    Written into ``out`` (no allocation).
    """
    x = xp[0]
    y = xp[1]
    w_x = xp[2]
    w_y = xp[3]
    out[:] = 0.0
    out[0] = x
    out[1] = y
    out[2] = math.atan2(w_y, w_x)
    out[3] = math.sqrt(w_x*w_x + w_y*w_y)


@nb.njit(cache=True)
def physical_to_common_jacobian_into(xp, out):
    """A = ∂c/∂ε (6 × n) at the physical state x (X = μ·exp ε): P_c = A P Aᵀ.
    Written into ``out`` (no allocation).
    """
    w_x = xp[2]
    w_y = xp[3]
    out[:, :] = 0.0
    _t0 = w_x*w_x + w_y*w_y
    _t1 = 1.0/_t0
    _t2 = 1.0/math.sqrt(_t0)
    out[0, 0] = 1.0
    out[1, 1] = 1.0
    out[2, 2] = -(_t1*w_y)
    out[2, 3] = _t1*w_x
    out[3, 2] = _t2*w_x
    out[3, 3] = _t2*w_y


@nb.njit(cache=True)
def between_add(s, t, w, acc):
    """acc += w·[log_G(μ_s^-1 μ_t)]^∨ (a term of the iterated mean μ ← μ·exp(Σ w_i d_i); d as ``between``).
    """
    x = s[0]
    y = s[1]
    w_x = s[2]
    w_y = s[3]
    t_x = t[0]
    t_y = t[1]
    t_w_x = t[2]
    t_w_y = t[3]
    acc0 = acc[0]
    acc1 = acc[1]
    acc2 = acc[2]
    acc3 = acc[3]
    d0 = t_x - x
    d1 = t_y - y
    d2 = t_w_x - w_x
    d3 = t_w_y - w_y
    acc[0] = acc0 + d0*w
    acc[1] = acc1 + d1*w
    acc[2] = acc2 + d2*w
    acc[3] = acc3 + d3*w


@nb.njit(cache=True)
def mix_transport(s, t, pt, w, acc):
    """acc (packed upper triangle) += w·[Φ(d)^-1 P_t Φ(d)^-T + d dᵀ], d = [log_G(μ_s^-1 μ_t)]^∨, P_t = unpack(pt):
    one source's term of a mixture's covariance about the mean μ_s (X = μ_t·exp ε_t = μ_s·exp(d + Φ(d)^-1 ε_t)
    to first order; lgekf.estimators.imm.kernels). Straight line over the non-zero entries of Φ^-1.
    """
    x = s[0]
    y = s[1]
    w_x = s[2]
    w_y = s[3]
    t_x = t[0]
    t_y = t[1]
    t_w_x = t[2]
    t_w_y = t[3]
    pt0_0 = pt[0]
    pt0_1 = pt[1]
    pt0_2 = pt[2]
    pt0_3 = pt[3]
    pt1_1 = pt[4]
    pt1_2 = pt[5]
    pt1_3 = pt[6]
    pt2_2 = pt[7]
    pt2_3 = pt[8]
    pt3_3 = pt[9]
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
    d0 = t_x - x
    d1 = t_y - y
    d2 = t_w_x - w_x
    d3 = t_w_y - w_y
    acc[0] = acc0 + w*(d0*d0 + pt0_0)
    acc[1] = acc1 + w*(d0*d1 + pt0_1)
    acc[2] = acc2 + w*(d0*d2 + pt0_2)
    acc[3] = acc3 + w*(d0*d3 + pt0_3)
    acc[4] = acc4 + w*(d1*d1 + pt1_1)
    acc[5] = acc5 + w*(d1*d2 + pt1_2)
    acc[6] = acc6 + w*(d1*d3 + pt1_3)
    acc[7] = acc7 + w*(d2*d2 + pt2_2)
    acc[8] = acc8 + w*(d2*d3 + pt2_3)
    acc[9] = acc9 + w*(d3*d3 + pt3_3)


@nb.njit(cache=True, error_model="numpy")
def common_of_state(s, p, c, Pc):
    """A mode's Gaussian in the common coordinates: c = (x, y, θ, v_x, v_y, ω) of the internal state s (as
    physical_to_common(physical(s))) and Pc = A P Aᵀ (6 × 6), A = ∂c/∂ε (physical_to_common_jacobian) at s.
    """
    x = s[0]
    y = s[1]
    w_x = s[2]
    w_y = s[3]
    p0_0 = p[0]
    p0_1 = p[1]
    p0_2 = p[2]
    p0_3 = p[3]
    p1_1 = p[4]
    p1_2 = p[5]
    p1_3 = p[6]
    p2_2 = p[7]
    p2_3 = p[8]
    p3_3 = p[9]
    xp_x = x
    xp_y = y
    xp_w_x = w_x
    xp_w_y = w_y
    _t0 = xp_w_x*xp_w_x + xp_w_y*xp_w_y
    _t1 = 1.0/_t0
    _t2 = 1.0/math.sqrt(_t0)
    A2_2 = -(_t1*xp_w_y)
    A2_3 = _t1*xp_w_x
    A3_2 = _t2*xp_w_x
    A3_3 = _t2*xp_w_y
    U2_2 = A2_2*p2_2 + A2_3*p2_3
    U2_3 = A2_2*p2_3 + A2_3*p3_3
    U3_2 = A3_2*p2_2 + A3_3*p2_3
    U3_3 = A3_2*p2_3 + A3_3*p3_3
    _t3 = A2_2*p0_2 + A2_3*p0_3
    _t4 = A3_2*p0_2 + A3_3*p0_3
    _t5 = A2_2*p1_2 + A2_3*p1_3
    _t6 = A3_2*p1_2 + A3_3*p1_3
    _t7 = A3_2*U2_2 + A3_3*U2_3
    c[0] = xp_x
    c[1] = xp_y
    c[2] = math.atan2(xp_w_y, xp_w_x)
    c[3] = math.sqrt(xp_w_x*xp_w_x + xp_w_y*xp_w_y)
    c[4] = 0.0
    c[5] = 0.0
    Pc[0, 0] = p0_0
    Pc[0, 1] = p0_1
    Pc[1, 0] = p0_1
    Pc[0, 2] = _t3
    Pc[2, 0] = _t3
    Pc[0, 3] = _t4
    Pc[3, 0] = _t4
    Pc[0, 4] = 0.0
    Pc[4, 0] = 0.0
    Pc[0, 5] = 0.0
    Pc[5, 0] = 0.0
    Pc[1, 1] = p1_1
    Pc[1, 2] = _t5
    Pc[2, 1] = _t5
    Pc[1, 3] = _t6
    Pc[3, 1] = _t6
    Pc[1, 4] = 0.0
    Pc[4, 1] = 0.0
    Pc[1, 5] = 0.0
    Pc[5, 1] = 0.0
    Pc[2, 2] = A2_2*U2_2 + A2_3*U2_3
    Pc[2, 3] = _t7
    Pc[3, 2] = _t7
    Pc[2, 4] = 0.0
    Pc[4, 2] = 0.0
    Pc[2, 5] = 0.0
    Pc[5, 2] = 0.0
    Pc[3, 3] = A3_2*U3_2 + A3_3*U3_3
    Pc[3, 4] = 0.0
    Pc[4, 3] = 0.0
    Pc[3, 5] = 0.0
    Pc[5, 3] = 0.0
    Pc[4, 4] = 0.0
    Pc[4, 5] = 0.0
    Pc[5, 4] = 0.0
    Pc[5, 5] = 0.0


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
    pc0_0 = Pc[0, 0]
    pc0_1 = Pc[0, 1]
    pc0_2 = Pc[0, 2]
    pc0_3 = Pc[0, 3]
    pc0_4 = Pc[0, 4]
    pc1_1 = Pc[1, 1]
    pc1_2 = Pc[1, 2]
    pc1_3 = Pc[1, 3]
    pc1_4 = Pc[1, 4]
    pc2_2 = Pc[2, 2]
    pc2_3 = Pc[2, 3]
    pc2_4 = Pc[2, 4]
    pc3_3 = Pc[3, 3]
    pc3_4 = Pc[3, 4]
    pc4_4 = Pc[4, 4]
    _sin_c2 = math.sin(c2)
    _cos_c2 = math.cos(c2)
    xp_x = c0
    xp_y = c1
    xp_w_x = _cos_c2*c3 - _sin_c2*c4
    xp_w_y = _cos_c2*c4 + _sin_c2*c3
    J2_2 = -(_cos_c2*c4) - _sin_c2*c3
    J2_3 = _cos_c2
    J2_4 = -_sin_c2
    J3_2 = _cos_c2*c3 - _sin_c2*c4
    J3_3 = _sin_c2
    J3_4 = _cos_c2
    V2_2 = J2_2*pc2_2 + J2_3*pc2_3 + J2_4*pc2_4
    V2_3 = J2_2*pc2_3 + J2_3*pc3_3 + J2_4*pc3_4
    V2_4 = J2_2*pc2_4 + J2_3*pc3_4 + J2_4*pc4_4
    V3_2 = J3_2*pc2_2 + J3_3*pc2_3 + J3_4*pc2_4
    V3_3 = J3_2*pc2_3 + J3_3*pc3_3 + J3_4*pc3_4
    V3_4 = J3_2*pc2_4 + J3_3*pc3_4 + J3_4*pc4_4
    s[0] = xp_x
    s[1] = xp_y
    s[2] = xp_w_x
    s[3] = xp_w_y
    p[0] = pc0_0
    p[1] = pc0_1
    p[2] = J2_2*pc0_2 + J2_3*pc0_3 + J2_4*pc0_4
    p[3] = J3_2*pc0_2 + J3_3*pc0_3 + J3_4*pc0_4
    p[4] = pc1_1
    p[5] = J2_2*pc1_2 + J2_3*pc1_3 + J2_4*pc1_4
    p[6] = J3_2*pc1_2 + J3_3*pc1_3 + J3_4*pc1_4
    p[7] = J2_2*V2_2 + J2_3*V2_3 + J2_4*V2_4
    p[8] = J3_2*V2_2 + J3_3*V2_3 + J3_4*V2_4
    p[9] = J3_2*V3_2 + J3_3*V3_3 + J3_4*V3_4


@nb.njit(cache=True, error_model="numpy")
def between_add_at(ws, js, jt, w, jacc):
    """acc += w·[log_G(μ_s^-1 μ_t)]^∨ (a term of the iterated mean μ ← μ·exp(Σ w_i d_i); d as ``between``).
    On rows of ws: s = ws[js], t = ws[jt], acc = ws[jacc] (derive/codegen/imm_rows.py).
    """
    x = ws[js, 0]
    y = ws[js, 1]
    w_x = ws[js, 2]
    w_y = ws[js, 3]
    t_x = ws[jt, 0]
    t_y = ws[jt, 1]
    t_w_x = ws[jt, 2]
    t_w_y = ws[jt, 3]
    acc0 = ws[jacc, 0]
    acc1 = ws[jacc, 1]
    acc2 = ws[jacc, 2]
    acc3 = ws[jacc, 3]
    d0 = t_x - x
    d1 = t_y - y
    d2 = t_w_x - w_x
    d3 = t_w_y - w_y
    ws[jacc, 0] = acc0 + d0*w
    ws[jacc, 1] = acc1 + d1*w
    ws[jacc, 2] = acc2 + d2*w
    ws[jacc, 3] = acc3 + d3*w


@nb.njit(cache=True, error_model="numpy")
def mix_transport_at(ws, js, jt, jpt, w, jacc):
    """acc (packed upper triangle) += w·[Φ(d)^-1 P_t Φ(d)^-T + d dᵀ], d = [log_G(μ_s^-1 μ_t)]^∨, P_t = unpack(pt):
    one source's term of a mixture's covariance about the mean μ_s (X = μ_t·exp ε_t = μ_s·exp(d + Φ(d)^-1 ε_t)
    to first order; lgekf.estimators.imm.kernels). Straight line over the non-zero entries of Φ^-1.
    On rows of ws: s = ws[js], t = ws[jt], pt = ws[jpt], acc = ws[jacc] (derive/codegen/imm_rows.py).
    """
    x = ws[js, 0]
    y = ws[js, 1]
    w_x = ws[js, 2]
    w_y = ws[js, 3]
    t_x = ws[jt, 0]
    t_y = ws[jt, 1]
    t_w_x = ws[jt, 2]
    t_w_y = ws[jt, 3]
    pt0_0 = ws[jpt, 0]
    pt0_1 = ws[jpt, 1]
    pt0_2 = ws[jpt, 2]
    pt0_3 = ws[jpt, 3]
    pt1_1 = ws[jpt, 4]
    pt1_2 = ws[jpt, 5]
    pt1_3 = ws[jpt, 6]
    pt2_2 = ws[jpt, 7]
    pt2_3 = ws[jpt, 8]
    pt3_3 = ws[jpt, 9]
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
    d0 = t_x - x
    d1 = t_y - y
    d2 = t_w_x - w_x
    d3 = t_w_y - w_y
    ws[jacc, 0] = acc0 + w*(d0*d0 + pt0_0)
    ws[jacc, 1] = acc1 + w*(d0*d1 + pt0_1)
    ws[jacc, 2] = acc2 + w*(d0*d2 + pt0_2)
    ws[jacc, 3] = acc3 + w*(d0*d3 + pt0_3)
    ws[jacc, 4] = acc4 + w*(d1*d1 + pt1_1)
    ws[jacc, 5] = acc5 + w*(d1*d2 + pt1_2)
    ws[jacc, 6] = acc6 + w*(d1*d3 + pt1_3)
    ws[jacc, 7] = acc7 + w*(d2*d2 + pt2_2)
    ws[jacc, 8] = acc8 + w*(d2*d3 + pt2_3)
    ws[jacc, 9] = acc9 + w*(d3*d3 + pt3_3)


@nb.njit(cache=True, error_model="numpy")
def retract_at(ws, js, jeps):
    """μ ← μ·exp([ε]^∧) in place (right perturbation; the update's eq:up_mu for a given ε).
    On rows of ws: s = ws[js], eps = ws[jeps] (derive/codegen/imm_rows.py).
    """
    x = ws[js, 0]
    y = ws[js, 1]
    w_x = ws[js, 2]
    w_y = ws[js, 3]
    eps0 = ws[jeps, 0]
    eps1 = ws[jeps, 1]
    eps2 = ws[jeps, 2]
    eps3 = ws[jeps, 3]
    ws[js, 0] = eps0 + x
    ws[js, 1] = eps1 + y
    ws[js, 2] = eps2 + w_x
    ws[js, 3] = eps3 + w_y


@nb.njit(cache=True, error_model="numpy")
def common_of_state_at(ws, js, jp, jc, jPc):
    """A mode's Gaussian in the common coordinates: c = (x, y, θ, v_x, v_y, ω) of the internal state s (as
    physical_to_common(physical(s))) and Pc = A P Aᵀ (6 × 6), A = ∂c/∂ε (physical_to_common_jacobian) at s.
    On rows of ws: s = ws[js], p = ws[jp], c = ws[jc], Pc = ws[jPc] (derive/codegen/imm_rows.py).
    """
    x = ws[js, 0]
    y = ws[js, 1]
    w_x = ws[js, 2]
    w_y = ws[js, 3]
    p0_0 = ws[jp, 0]
    p0_1 = ws[jp, 1]
    p0_2 = ws[jp, 2]
    p0_3 = ws[jp, 3]
    p1_1 = ws[jp, 4]
    p1_2 = ws[jp, 5]
    p1_3 = ws[jp, 6]
    p2_2 = ws[jp, 7]
    p2_3 = ws[jp, 8]
    p3_3 = ws[jp, 9]
    xp_x = x
    xp_y = y
    xp_w_x = w_x
    xp_w_y = w_y
    _t0 = xp_w_x*xp_w_x + xp_w_y*xp_w_y
    _t1 = 1.0/_t0
    _t2 = 1.0/math.sqrt(_t0)
    A2_2 = -(_t1*xp_w_y)
    A2_3 = _t1*xp_w_x
    A3_2 = _t2*xp_w_x
    A3_3 = _t2*xp_w_y
    U2_2 = A2_2*p2_2 + A2_3*p2_3
    U2_3 = A2_2*p2_3 + A2_3*p3_3
    U3_2 = A3_2*p2_2 + A3_3*p2_3
    U3_3 = A3_2*p2_3 + A3_3*p3_3
    _t3 = A2_2*p0_2 + A2_3*p0_3
    _t4 = A3_2*p0_2 + A3_3*p0_3
    _t5 = A2_2*p1_2 + A2_3*p1_3
    _t6 = A3_2*p1_2 + A3_3*p1_3
    _t7 = A3_2*U2_2 + A3_3*U2_3
    ws[jc, 0] = xp_x
    ws[jc, 1] = xp_y
    ws[jc, 2] = math.atan2(xp_w_y, xp_w_x)
    ws[jc, 3] = math.sqrt(xp_w_x*xp_w_x + xp_w_y*xp_w_y)
    ws[jc, 4] = 0.0
    ws[jc, 5] = 0.0
    ws[jPc, 0] = p0_0
    ws[jPc, 1] = p0_1
    ws[jPc, 6] = p0_1
    ws[jPc, 2] = _t3
    ws[jPc, 12] = _t3
    ws[jPc, 3] = _t4
    ws[jPc, 18] = _t4
    ws[jPc, 4] = 0.0
    ws[jPc, 24] = 0.0
    ws[jPc, 5] = 0.0
    ws[jPc, 30] = 0.0
    ws[jPc, 7] = p1_1
    ws[jPc, 8] = _t5
    ws[jPc, 13] = _t5
    ws[jPc, 9] = _t6
    ws[jPc, 19] = _t6
    ws[jPc, 10] = 0.0
    ws[jPc, 25] = 0.0
    ws[jPc, 11] = 0.0
    ws[jPc, 31] = 0.0
    ws[jPc, 14] = A2_2*U2_2 + A2_3*U2_3
    ws[jPc, 15] = _t7
    ws[jPc, 20] = _t7
    ws[jPc, 16] = 0.0
    ws[jPc, 26] = 0.0
    ws[jPc, 17] = 0.0
    ws[jPc, 32] = 0.0
    ws[jPc, 21] = A3_2*U3_2 + A3_3*U3_3
    ws[jPc, 22] = 0.0
    ws[jPc, 27] = 0.0
    ws[jPc, 23] = 0.0
    ws[jPc, 33] = 0.0
    ws[jPc, 28] = 0.0
    ws[jPc, 29] = 0.0
    ws[jPc, 34] = 0.0
    ws[jPc, 35] = 0.0


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
    pc0_0 = ws[jPc, 0]
    pc0_1 = ws[jPc, 1]
    pc0_2 = ws[jPc, 2]
    pc0_3 = ws[jPc, 3]
    pc0_4 = ws[jPc, 4]
    pc1_1 = ws[jPc, 7]
    pc1_2 = ws[jPc, 8]
    pc1_3 = ws[jPc, 9]
    pc1_4 = ws[jPc, 10]
    pc2_2 = ws[jPc, 14]
    pc2_3 = ws[jPc, 15]
    pc2_4 = ws[jPc, 16]
    pc3_3 = ws[jPc, 21]
    pc3_4 = ws[jPc, 22]
    pc4_4 = ws[jPc, 28]
    _sin_c2 = math.sin(c2)
    _cos_c2 = math.cos(c2)
    xp_x = c0
    xp_y = c1
    xp_w_x = _cos_c2*c3 - _sin_c2*c4
    xp_w_y = _cos_c2*c4 + _sin_c2*c3
    J2_2 = -(_cos_c2*c4) - _sin_c2*c3
    J2_3 = _cos_c2
    J2_4 = -_sin_c2
    J3_2 = _cos_c2*c3 - _sin_c2*c4
    J3_3 = _sin_c2
    J3_4 = _cos_c2
    V2_2 = J2_2*pc2_2 + J2_3*pc2_3 + J2_4*pc2_4
    V2_3 = J2_2*pc2_3 + J2_3*pc3_3 + J2_4*pc3_4
    V2_4 = J2_2*pc2_4 + J2_3*pc3_4 + J2_4*pc4_4
    V3_2 = J3_2*pc2_2 + J3_3*pc2_3 + J3_4*pc2_4
    V3_3 = J3_2*pc2_3 + J3_3*pc3_3 + J3_4*pc3_4
    V3_4 = J3_2*pc2_4 + J3_3*pc3_4 + J3_4*pc4_4
    ws[js, 0] = xp_x
    ws[js, 1] = xp_y
    ws[js, 2] = xp_w_x
    ws[js, 3] = xp_w_y
    ws[jp, 0] = pc0_0
    ws[jp, 1] = pc0_1
    ws[jp, 2] = J2_2*pc0_2 + J2_3*pc0_3 + J2_4*pc0_4
    ws[jp, 3] = J3_2*pc0_2 + J3_3*pc0_3 + J3_4*pc0_4
    ws[jp, 4] = pc1_1
    ws[jp, 5] = J2_2*pc1_2 + J2_3*pc1_3 + J2_4*pc1_4
    ws[jp, 6] = J3_2*pc1_2 + J3_3*pc1_3 + J3_4*pc1_4
    ws[jp, 7] = J2_2*V2_2 + J2_3*V2_3 + J2_4*V2_4
    ws[jp, 8] = J3_2*V2_2 + J3_3*V2_3 + J3_4*V2_4
    ws[jp, 9] = J3_2*V3_2 + J3_3*V3_3 + J3_4*V3_4


@nb.njit(cache=True, fastmath=FASTMATH, error_model="numpy")
def step_ll_position(ws, js, jp, dt, sigma_a, z_x, z_y, r):
    """``step_try_position`` on rows s = ws[js], p = ws[jp] (derive/codegen/imm_rows.py); returns (nis, rdet),
    rdet = 1/det S, S = ℋPℋᵀ + R at the predicted state (eq:K), also when nis is FALLBACK.
    """
    x = ws[js, 0]
    y = ws[js, 1]
    w_x = ws[js, 2]
    w_y = ws[js, 3]
    p00 = ws[jp, 0]
    p01 = ws[jp, 1]
    p02 = ws[jp, 2]
    p03 = ws[jp, 3]
    p11 = ws[jp, 4]
    p12 = ws[jp, 5]
    p13 = ws[jp, 6]
    p22 = ws[jp, 7]
    p23 = ws[jp, 8]
    p33 = ws[jp, 9]
    _t0 = (dt*dt)/2.0
    g00 = _t0
    g11 = _t0
    e00 = dt*w_x + x
    e01 = dt*w_y + y
    _t1 = dt*p23
    m00 = dt*p02 + p00
    m01 = dt*p12 + p01
    m02 = dt*p22 + p02
    m03 = _t1 + p03
    m11 = dt*p13 + p11
    m12 = _t1 + p12
    m13 = dt*p33 + p13
    _t2 = sigma_a*sigma_a
    _t3 = _t2*dt
    _t4 = _t2*(dt*dt)
    pp00 = _t2*(g00*g00) + dt*m02 + m00
    pp01 = dt*m03 + m01
    pp02 = _t3*g00 + m02
    pp03 = m03
    pp11 = _t2*(g11*g11) + dt*m13 + m11
    pp12 = m12
    pp13 = _t3*g11 + m13
    pp22 = _t4 + p22
    pp23 = p23
    pp33 = _t4 + p33
    x_p = e00
    y_p = e01
    inn00 = -x_p + z_x
    inn10 = -y_p + z_y
    _t5 = r*r
    S00 = _t5 + pp00
    S11 = _t5 + pp11
    rdet = 1.0/(S00*S11 - pp01*pp01)
    Si00 = S11*rdet
    Si01 = -(pp01*rdet)
    Si11 = S00*rdet
    _t6 = Si01*pp01
    k00 = Si00*pp00 + _t6
    k01 = Si01*pp00 + Si11*pp01
    k10 = Si00*pp01 + Si01*pp11
    k11 = Si11*pp11 + _t6
    k20 = Si00*pp02 + Si01*pp12
    k21 = Si01*pp02 + Si11*pp12
    k30 = Si00*pp03 + Si01*pp13
    k31 = Si01*pp03 + Si11*pp13
    nis = Si00*(inn00*inn00) + 2.0*Si01*inn00*inn10 + Si11*(inn10*inn10)
    nk0 = inn00*k00 + inn10*k01
    nk1 = inn00*k10 + inn10*k11
    nk2 = inn00*k20 + inn10*k21
    nk3 = inn00*k30 + inn10*k31
    mu00 = nk0 + x_p
    mu01 = nk1 + y_p
    mu02 = nk2 + w_x
    mu03 = nk3 + w_y
    pj00 = -(k00*pp00) - k01*pp01 + pp00
    pj01 = -(k00*pp01) - k01*pp11 + pp01
    pj02 = -(k00*pp02) - k01*pp12 + pp02
    pj03 = -(k00*pp03) - k01*pp13 + pp03
    pj11 = -(k10*pp01) - k11*pp11 + pp11
    pj12 = -(k10*pp02) - k11*pp12 + pp12
    pj13 = -(k10*pp03) - k11*pp13 + pp13
    pj22 = -(k20*pp02) - k21*pp12 + pp22
    pj23 = -(k20*pp03) - k21*pp13 + pp23
    pj33 = -(k30*pp03) - k31*pp13 + pp33
    out_p0 = pj00
    out_p1 = pj01
    out_p2 = pj02
    out_p3 = pj03
    out_p4 = pj11
    out_p5 = pj12
    out_p6 = pj13
    out_p7 = pj22
    out_p8 = pj23
    out_p9 = pj33
    out_s0 = mu00
    out_s1 = mu01
    out_s2 = mu02
    out_s3 = mu03
    if not covariance_is_pd_fused(out_p0, out_p1, out_p2, out_p3, out_p4, out_p5, out_p6, out_p7, out_p8, out_p9):
        out_p0 = pp00
        out_p1 = pp01
        out_p2 = pp02
        out_p3 = pp03
        out_p4 = pp11
        out_p5 = pp12
        out_p6 = pp13
        out_p7 = pp22
        out_p8 = pp23
        out_p9 = pp33
        out_s0 = x_p
        out_s1 = y_p
        out_s2 = w_x
        out_s3 = w_y
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
    ws[js, 0] = out_s0
    ws[js, 1] = out_s1
    ws[js, 2] = out_s2
    ws[js, 3] = out_s3
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
    for k in range(4):
        ws[rs, k] = ws[rS + best, k]
    it = 0
    if M > 1:
        for it in range(1, 51):
            for k in range(4):
                ws[rd, k] = 0.0
            for i in range(M):
                w = ws[rw, i]
                if w > 0.0 and not (i == best and it == 1):  # d_best = 0 in the first iteration
                    between_add_at(ws, rs, rS + i, w, rd)
            retract_at(ws, rs, rd)
            nrm = 0.0
            for k in range(4):
                nrm += ws[rd, k] * ws[rd, k]
            if nrm < 1e-24:
                break
    if M == 1:
        for k in range(10):
            ws[rp, k] = ws[rPp, k]
        return it
    for k in range(10):
        ws[rp, k] = 0.0
    for i in range(M):
        w = ws[rw, i]
        if w > 0.0:
            mix_transport_at(ws, rs, rS + i, rPp + i, w, rp)
    return it
