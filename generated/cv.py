"""CV Kalman filter: transition, noise and fused predict/update steps.

GENERATED FILE: DO NOT EDIT.
Source: derive/steps.py (cv), from derive/models.py and derive/groups.py
Regenerate with: lgekf derive      (check freshness with: lgekf derive --check)
"""
import math

import numba as nb
import numpy as np
from .special import sinc, cosc, sinc2, cosc2, dsinc, halfcot, halfcot1, gain_damping, wrap_angle  # noqa: F401

# fused steps use FMA contraction only ("contract"); every other IEEE rule holds
FASTMATH = {"contract"}

__all__ = ['transition', 'process_noise', 'predict', 'update', 'state_from_physical', 'state_to_physical', 'physical_into', 'run_one', 'run_batch', 'world_velocity', 'world_velocities', 'common_to_state', 'common_jacobian']


@nb.njit(cache=True)
def transition(dt):
    """CV transition F = [[I, T I], [0, I]].
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
def process_noise(dt, sigma_a):
    """Q = σ_a² G G^T, G = [T²/2 I; T I] (DWNA).
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


@nb.njit(cache=True, fastmath=FASTMATH)
def predict(s, p, dt, sigma_a):
    """CV Kalman prediction in place: x ← F x, P ← F P F^T + Q.
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
    _t0 = dt*p23
    m00 = dt*p02 + p00
    m01 = dt*p12 + p01
    m02 = dt*p22 + p02
    m03 = _t0 + p03
    m11 = dt*p13 + p11
    m12 = _t0 + p12
    m13 = dt*p33 + p13
    _t1 = sigma_a*sigma_a
    _t2 = _t1*(dt*dt*dt*dt)/4.0
    _t3 = _t1*(dt*dt*dt)/2.0
    _t4 = _t1*(dt*dt)
    p[0] = _t2 + dt*m02 + m00
    p[1] = dt*m03 + m01
    p[2] = _t3 + m02
    p[3] = m03
    p[4] = _t2 + dt*m13 + m11
    p[5] = m12
    p[6] = _t3 + m13
    p[7] = _t4 + p22
    p[8] = p23
    p[9] = _t4 + p33
    s[0] = dt*w_x + x
    s[1] = dt*w_y + y


@nb.njit(cache=True, fastmath=FASTMATH)
def update(s, p, z_x, z_y, r):
    """CV Kalman update with a position measurement z = (z_x, z_y), noise std r, in place.
    K = P H^T S^-1, S = H P H^T + r² I, x ← x + K e, P ← (I-KH)P(I-KH)^T + r² K K^T (Joseph form).
    Returns the NIS e^T S^-1 e.
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
    nis = inn00*(Si00*inn00 + Si01*inn10) + inn10*(Si01*inn00 + Si11*inn10)
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
    _t3 = r*r
    _t4 = _t3*k00
    _t5 = _t3*k01
    _t6 = _t3*k10
    _t7 = _t3*k11
    p[0] = _t3*(k00*k00) + _t3*(k01*k01) + a00*b00 + a01*b01
    p[1] = _t4*k10 + _t5*k11 + a10*b00 + a11*b01
    p[2] = _t4*k20 + _t5*k21 + a20*b00 + a21*b01 + b02
    p[3] = _t4*k30 + _t5*k31 + a30*b00 + a31*b01 + b03
    p[4] = _t3*(k10*k10) + _t3*(k11*k11) + a10*b10 + a11*b11
    p[5] = _t6*k20 + _t7*k21 + a20*b10 + a21*b11 + b12
    p[6] = _t6*k30 + _t7*k31 + a30*b10 + a31*b11 + b13
    p[7] = _t3*(k20*k20) + _t3*(k21*k21) + a20*b20 + a21*b21 + b22
    p[8] = _t3*k20*k30 + _t3*k21*k31 + a30*b20 + a31*b21 + b23
    p[9] = _t3*(k30*k30) + _t3*(k31*k31) + a30*b30 + a31*b31 + b33
    s[0] = inn00*k00 + inn10*k01 + x
    s[1] = inn00*k10 + inn10*k11 + y
    s[2] = inn00*k20 + inn10*k21 + w_x
    s[3] = inn00*k30 + inn10*k31 + w_y
    return nis


@nb.njit(cache=True)
def state_from_physical(xp):
    """Internal state = physical [x, y, v_x, v_y].
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
    """Physical state [x, y, v_x, v_y].
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
    """Physical [x, y, v_x, v_y]. Written into ``out`` (no allocation).
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
def run_one(z, dts, x0, p0, q, r, out_x, out_p, out_nis):
    """Filter one trajectory: z (K, 2), dts (K,), x0 (4,), p0 (10,); see run_batch."""
    s = state_from_physical(x0)
    p = p0.copy()
    K = z.shape[0]
    keep_p = out_p.shape[0] == K
    for k in range(K):
        predict(s, p, dts[k], q[0])
        out_nis[k] = update(s, p, z[k, 0], z[k, 1], r)
        physical_into(s, out_x[k])
        if keep_p:
            for i in range(10):
                out_p[k, i] = p[i]


@nb.njit(cache=True, parallel=True)
def run_batch(z, dts, x0, p0, q, r, out_x, out_p, out_nis):
    """Filter B trajectories in parallel (numba prange), predict then update at every step.

    z (B, K, 2) positions; dts (B, K) step lengths; x0 (B, 4) physical initial states; p0 (B, 10)
    packed initial covariances; q (1,) noise stds; r the measurement std. Writes the posterior
    physical states into out_x (B, K, 4), the packed covariances into out_p (B, K, 10) when
    out_p.shape[1] == K (pass shape (B, 0, 10) to skip), and the NIS into out_nis (B, K).
    """
    for b in nb.prange(z.shape[0]):
        run_one(z[b], dts[b], x0[b], p0[b], q, r, out_x[b], out_p[b], out_nis[b])


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
    out = np.zeros(4)
    _sin_theta = math.sin(theta)
    _cos_theta = math.cos(theta)
    out[0] = x
    out[1] = y
    out[2] = _cos_theta*v_x - _sin_theta*v_y
    out[3] = _cos_theta*v_y + _sin_theta*v_x
    return out


@nb.njit(cache=True)
def common_jacobian(c):
    """J = ∂(filter coordinates)/∂c at c: maps a covariance of c to the filter's P (P = J P_c J^T).
    """
    theta = c[2]
    v_x = c[3]
    v_y = c[4]
    out = np.zeros((4, 6))
    _sin_theta = math.sin(theta)
    _cos_theta = math.cos(theta)
    out[0, 0] = 1.0
    out[1, 1] = 1.0
    out[2, 2] = -(_cos_theta*v_y) - _sin_theta*v_x
    out[2, 3] = _cos_theta
    out[2, 4] = -_sin_theta
    out[3, 2] = _cos_theta*v_x - _sin_theta*v_y
    out[3, 3] = _sin_theta
    out[3, 4] = _cos_theta
    return out
