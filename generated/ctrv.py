"""CTRV EKF: exact motion, Jacobian, noise and fused predict/update steps.

GENERATED FILE: DO NOT EDIT.
Source: derive/steps.py (ctrv), from derive/models.py and derive/groups.py
Regenerate with: lgekf derive      (check freshness with: lgekf derive --check)
"""
import math

import numba as nb
import numpy as np
from .special import sinc, cosc, sinc2, cosc2, dsinc, halfcot, halfcot1, gain_damping, wrap_angle  # noqa: F401

# fused steps use FMA contraction only ("contract"); every other IEEE rule holds
FASTMATH = {"contract"}

__all__ = ['state_from_physical', 'state_to_physical', 'motion', 'transition', 'process_noise', 'predict', 'update', 'physical_into', 'run_one', 'run_batch', 'world_velocity', 'world_velocities', 'common_to_state', 'common_jacobian']


@nb.njit(cache=True)
def state_from_physical(xp):
    """Internal state = physical [x, y, ψ, v, ω].
    """
    x = xp[0]
    y = xp[1]
    psi = xp[2]
    v = xp[3]
    omega = xp[4]
    out = np.zeros(5)
    out[0] = x
    out[1] = y
    out[2] = psi
    out[3] = v
    out[4] = omega
    return out


@nb.njit(cache=True)
def state_to_physical(s):
    """Physical [x, y, ψ, v, ω] with ψ wrapped to (-π, π].
    """
    x = s[0]
    y = s[1]
    psi = s[2]
    v = s[3]
    omega = s[4]
    out = np.zeros(5)
    out[0] = x
    out[1] = y
    out[2] = wrap_angle(psi)
    out[3] = v
    out[4] = omega
    return out


@nb.njit(cache=True)
def motion(s, dt):
    """CTRV exact discretisation f(s): x' = x + vT cos(ψ + ωT/2) sinc(ωT/2), ...
    """
    x = s[0]
    y = s[1]
    psi = s[2]
    v = s[3]
    omega = s[4]
    out = np.zeros(5)
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
    out[2] = dt*omega + psi
    out[3] = v
    out[4] = omega
    return out


@nb.njit(cache=True)
def transition(s, dt):
    """CTRV EKF Jacobian F = ∂f/∂s, finite at ω = 0.
    """
    psi = s[2]
    v = s[3]
    omega = s[4]
    out = np.zeros((5, 5))
    _a0 = dt*omega/2.0
    _sin__a0 = math.sin(_a0)
    _cos__a0 = math.cos(_a0)
    _dsinc__a0 = dsinc(_a0, _sin__a0, _cos__a0)
    _sinc__a0 = sinc(_a0, _sin__a0, _cos__a0)
    _a1 = dt*omega/2.0 + psi
    _sin__a1 = math.sin(_a1)
    _cos__a1 = math.cos(_a1)
    _t0 = _sinc__a0*dt
    _t1 = _sin__a1*_t0
    _t2 = _cos__a1*_t0
    _t3 = (dt*dt)*v/2.0
    _t4 = _cos__a1*_t3
    _t5 = _sin__a1*_t3
    out[0, 0] = 1.0
    out[0, 2] = -(_t1*v)
    out[0, 3] = _t2
    out[0, 4] = -(_dsinc__a0*_t4) - _sinc__a0*_t5
    out[1, 1] = 1.0
    out[1, 2] = _t2*v
    out[1, 3] = _t1
    out[1, 4] = -(_dsinc__a0*_t5) + _sinc__a0*_t4
    out[2, 2] = 1.0
    out[2, 4] = dt
    out[3, 3] = 1.0
    out[4, 4] = 1.0
    return out


@nb.njit(cache=True)
def process_noise(s, dt, sigma_a, sigma_alpha):
    """Q = G diag(σ_a², σ_α²) G^T, G's columns (T²/2 cos ψ, T²/2 sin ψ, 0, T, 0), (0, 0, T²/2, 0, T).
    """
    psi = s[2]
    out = np.zeros((5, 5))
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
    _t8 = sigma_alpha*sigma_alpha
    _t9 = _t4*_t8
    _t10 = dt*dt
    out[0, 0] = (_cos_psi*_cos_psi)*_t2
    out[0, 1] = _t3
    out[0, 3] = _t6
    out[1, 0] = _t3
    out[1, 1] = (_sin_psi*_sin_psi)*_t2
    out[1, 3] = _t7
    out[2, 2] = _t1*_t8
    out[2, 4] = _t9
    out[3, 0] = _t6
    out[3, 1] = _t7
    out[3, 3] = _t0*_t10
    out[4, 2] = _t9
    out[4, 4] = _t10*_t8
    return out


@nb.njit(cache=True, fastmath=FASTMATH)
def predict(s, p, dt, sigma_a, sigma_alpha):
    """Fused CTRV EKF prediction in place: s ← f(s), P ← F P F^T + Q (Q at the state before the step).
    """
    x = s[0]
    y = s[1]
    psi = s[2]
    v = s[3]
    omega = s[4]
    p00 = p[0]
    p01 = p[1]
    p02 = p[2]
    p03 = p[3]
    p04 = p[4]
    p11 = p[5]
    p12 = p[6]
    p13 = p[7]
    p14 = p[8]
    p22 = p[9]
    p23 = p[10]
    p24 = p[11]
    p33 = p[12]
    p34 = p[13]
    p44 = p[14]
    _sin_psi = math.sin(psi)
    _cos_psi = math.cos(psi)
    _a0 = dt*omega/2.0
    _sin__a0 = math.sin(_a0)
    _cos__a0 = math.cos(_a0)
    _dsinc__a0 = dsinc(_a0, _sin__a0, _cos__a0)
    _sinc__a0 = sinc(_a0, _sin__a0, _cos__a0)
    _a1 = dt*omega/2.0 + psi
    _sin__a1 = math.sin(_a1)
    _cos__a1 = math.cos(_a1)
    _t0 = _sinc__a0*dt
    _t1 = _sin__a1*_t0
    _t2 = _t1*v
    _t3 = _cos__a1*_t0
    _t4 = (dt*dt)/2.0
    _t5 = _t4*v
    _t6 = _cos__a1*_t5
    _t7 = _sin__a1*_t5
    _t8 = _t3*v
    f02 = -_t2
    f03 = _t3
    f04 = -(_dsinc__a0*_t6) - _sinc__a0*_t7
    f12 = _t8
    f13 = _t1
    f14 = -(_dsinc__a0*_t7) + _sinc__a0*_t6
    g00 = _cos_psi*_t4
    g10 = _sin_psi*_t4
    g21 = _t4
    xn00 = _t8 + x
    xn10 = _t2 + y
    xn20 = dt*omega + psi
    m00 = f02*p02 + f03*p03 + f04*p04 + p00
    m01 = f02*p12 + f03*p13 + f04*p14 + p01
    m02 = f02*p22 + f03*p23 + f04*p24 + p02
    m03 = f02*p23 + f03*p33 + f04*p34 + p03
    m04 = f02*p24 + f03*p34 + f04*p44 + p04
    m11 = f12*p12 + f13*p13 + f14*p14 + p11
    m12 = f12*p22 + f13*p23 + f14*p24 + p12
    m13 = f12*p23 + f13*p33 + f14*p34 + p13
    m14 = f12*p24 + f13*p34 + f14*p44 + p14
    m22 = dt*p24 + p22
    m23 = dt*p34 + p23
    m24 = dt*p44 + p24
    _t9 = sigma_a*sigma_a
    _t10 = _t9*g00
    _t11 = sigma_alpha*sigma_alpha
    _t12 = dt*dt
    p[0] = _t9*(g00*g00) + f02*m02 + f03*m03 + f04*m04 + m00
    p[1] = _t10*g10 + f12*m02 + f13*m03 + f14*m04 + m01
    p[2] = dt*m04 + m02
    p[3] = _t10*dt + m03
    p[4] = m04
    p[5] = _t9*(g10*g10) + f12*m12 + f13*m13 + f14*m14 + m11
    p[6] = dt*m14 + m12
    p[7] = _t9*dt*g10 + m13
    p[8] = m14
    p[9] = _t11*(g21*g21) + dt*m24 + m22
    p[10] = m23
    p[11] = _t11*dt*g21 + m24
    p[12] = _t12*_t9 + p33
    p[13] = p34
    p[14] = _t11*_t12 + p44
    s[0] = xn00
    s[1] = xn10
    s[2] = xn20


@nb.njit(cache=True, fastmath=FASTMATH)
def update(s, p, z_x, z_y, r):
    """CTRV EKF Kalman update with a position measurement z = (z_x, z_y), noise std r, in place.
    K = P H^T S^-1, S = H P H^T + r² I, x ← x + K e, P ← (I-KH)P(I-KH)^T + r² K K^T (Joseph form).
    Returns the NIS e^T S^-1 e.
    """
    x = s[0]
    y = s[1]
    psi = s[2]
    v = s[3]
    omega = s[4]
    p00 = p[0]
    p01 = p[1]
    p02 = p[2]
    p03 = p[3]
    p04 = p[4]
    p11 = p[5]
    p12 = p[6]
    p13 = p[7]
    p14 = p[8]
    p22 = p[9]
    p23 = p[10]
    p24 = p[11]
    p33 = p[12]
    p34 = p[13]
    p44 = p[14]
    inn00 = -x + z_x
    inn10 = -y + z_y
    _t0 = r*r
    S00 = _t0 + p00
    S11 = _t0 + p11
    det = S00*S11 - p01*p01
    _t1 = 1.0/det
    Si00 = S11*_t1
    Si01 = -(_t1*p01)
    Si11 = S00*_t1
    _t2 = Si01*p01
    k00 = Si00*p00 + _t2
    k01 = Si01*p00 + Si11*p01
    k10 = Si00*p01 + Si01*p11
    k11 = Si11*p11 + _t2
    k20 = Si00*p02 + Si01*p12
    k21 = Si01*p02 + Si11*p12
    k30 = Si00*p03 + Si01*p13
    k31 = Si01*p03 + Si11*p13
    k40 = Si00*p04 + Si01*p14
    k41 = Si01*p04 + Si11*p14
    nis = inn00*(Si00*inn00 + Si01*inn10) + inn10*(Si01*inn00 + Si11*inn10)
    a00 = 1.0 - k00
    a01 = -k01
    a10 = -k10
    a11 = 1.0 - k11
    a20 = -k20
    a21 = -k21
    a30 = -k30
    a31 = -k31
    a40 = -k40
    a41 = -k41
    b00 = a00*p00 + a01*p01
    b01 = a00*p01 + a01*p11
    b02 = a00*p02 + a01*p12
    b03 = a00*p03 + a01*p13
    b04 = a00*p04 + a01*p14
    b10 = a10*p00 + a11*p01
    b11 = a10*p01 + a11*p11
    b12 = a10*p02 + a11*p12
    b13 = a10*p03 + a11*p13
    b14 = a10*p04 + a11*p14
    b20 = a20*p00 + a21*p01 + p02
    b21 = a20*p01 + a21*p11 + p12
    b22 = a20*p02 + a21*p12 + p22
    b23 = a20*p03 + a21*p13 + p23
    b24 = a20*p04 + a21*p14 + p24
    b30 = a30*p00 + a31*p01 + p03
    b31 = a30*p01 + a31*p11 + p13
    b33 = a30*p03 + a31*p13 + p33
    b34 = a30*p04 + a31*p14 + p34
    b40 = a40*p00 + a41*p01 + p04
    b41 = a40*p01 + a41*p11 + p14
    b44 = a40*p04 + a41*p14 + p44
    _t3 = r*r
    _t4 = _t3*k00
    _t5 = _t3*k01
    _t6 = _t3*k10
    _t7 = _t3*k11
    _t8 = _t3*k20
    _t9 = _t3*k21
    p[0] = _t3*(k00*k00) + _t3*(k01*k01) + a00*b00 + a01*b01
    p[1] = _t4*k10 + _t5*k11 + a10*b00 + a11*b01
    p[2] = _t4*k20 + _t5*k21 + a20*b00 + a21*b01 + b02
    p[3] = _t4*k30 + _t5*k31 + a30*b00 + a31*b01 + b03
    p[4] = _t4*k40 + _t5*k41 + a40*b00 + a41*b01 + b04
    p[5] = _t3*(k10*k10) + _t3*(k11*k11) + a10*b10 + a11*b11
    p[6] = _t6*k20 + _t7*k21 + a20*b10 + a21*b11 + b12
    p[7] = _t6*k30 + _t7*k31 + a30*b10 + a31*b11 + b13
    p[8] = _t6*k40 + _t7*k41 + a40*b10 + a41*b11 + b14
    p[9] = _t3*(k20*k20) + _t3*(k21*k21) + a20*b20 + a21*b21 + b22
    p[10] = _t8*k30 + _t9*k31 + a30*b20 + a31*b21 + b23
    p[11] = _t8*k40 + _t9*k41 + a40*b20 + a41*b21 + b24
    p[12] = _t3*(k30*k30) + _t3*(k31*k31) + a30*b30 + a31*b31 + b33
    p[13] = _t3*k30*k40 + _t3*k31*k41 + a40*b30 + a41*b31 + b34
    p[14] = _t3*(k40*k40) + _t3*(k41*k41) + a40*b40 + a41*b41 + b44
    s[0] = inn00*k00 + inn10*k01 + x
    s[1] = inn00*k10 + inn10*k11 + y
    s[2] = inn00*k20 + inn10*k21 + psi
    s[3] = inn00*k30 + inn10*k31 + v
    s[4] = inn00*k40 + inn10*k41 + omega
    return nis


@nb.njit(cache=True)
def physical_into(s, out):
    """Physical [x, y, ψ, v, ω], ψ in (-π, π]. Written into ``out`` (no allocation).
    """
    x = s[0]
    y = s[1]
    psi = s[2]
    v = s[3]
    omega = s[4]
    out[0] = x
    out[1] = y
    out[2] = wrap_angle(psi)
    out[3] = v
    out[4] = omega


@nb.njit(cache=True)
def run_one(z, dts, x0, p0, q, r, out_x, out_p, out_nis):
    """Filter one trajectory: z (K, 2), dts (K,), x0 (5,), p0 (15,); see run_batch."""
    s = state_from_physical(x0)
    p = p0.copy()
    K = z.shape[0]
    keep_p = out_p.shape[0] == K
    for k in range(K):
        predict(s, p, dts[k], q[0], q[1])
        out_nis[k] = update(s, p, z[k, 0], z[k, 1], r)
        physical_into(s, out_x[k])
        if keep_p:
            for i in range(15):
                out_p[k, i] = p[i]


@nb.njit(cache=True, parallel=True)
def run_batch(z, dts, x0, p0, q, r, out_x, out_p, out_nis):
    """Filter B trajectories in parallel (numba prange), predict then update at every step.

    z (B, K, 2) positions; dts (B, K) step lengths; x0 (B, 5) physical initial states; p0 (B, 15)
    packed initial covariances; q (2,) noise stds; r the measurement std. Writes the posterior
    physical states into out_x (B, K, 5), the packed covariances into out_p (B, K, 15) when
    out_p.shape[1] == K (pass shape (B, 0, 15) to skip), and the NIS into out_nis (B, K).
    """
    for b in nb.prange(z.shape[0]):
        run_one(z[b], dts[b], x0[b], p0[b], q, r, out_x[b], out_p[b], out_nis[b])


@nb.njit(cache=True)
def world_velocity(x):
    """World-frame velocity (2,) of a physical state x of this model.
    """
    psi = x[2]
    v = x[3]
    out = np.zeros(2)
    _sin_psi = math.sin(psi)
    _cos_psi = math.cos(psi)
    out[0] = _cos_psi*v
    out[1] = _sin_psi*v
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
    out = np.zeros(5)
    out[0] = x
    out[1] = y
    out[2] = theta + math.atan2(v_y, v_x)
    out[3] = math.sqrt(v_x*v_x + v_y*v_y)
    out[4] = omega
    return out


@nb.njit(cache=True)
def common_jacobian(c):
    """J = ∂(filter coordinates)/∂c at c: maps a covariance of c to the filter's P (P = J P_c J^T).
    """
    v_x = c[3]
    v_y = c[4]
    out = np.zeros((5, 6))
    _t0 = v_x*v_x + v_y*v_y
    _t1 = 1.0/_t0
    _t2 = 1.0/math.sqrt(_t0)
    out[0, 0] = 1.0
    out[1, 1] = 1.0
    out[2, 2] = 1.0
    out[2, 3] = -(_t1*v_y)
    out[2, 4] = _t1*v_x
    out[3, 3] = _t2*v_x
    out[3, 4] = _t2*v_y
    out[4, 5] = 1.0
    return out
