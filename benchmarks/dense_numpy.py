"""A plain dense-numpy SE(2)×SE(2) LG-EKF, written the way most research code is written.

Used by the benchmarks as the speed baseline and by ``errata_effect.py`` to build the filter with the
paper's printed ad_SE(2) (corner entry 1).  Independent of lgekf's generated kernels on purpose.
"""

from __future__ import annotations

import numpy as np


def hat(xi):
    x, y, th = xi
    return np.array([[0.0, -th, x], [th, 0.0, y], [0.0, 0.0, 0.0]])


def se2_exp(xi):
    x, y, th = xi
    c, s = np.cos(th), np.sin(th)
    if abs(th) < 1e-9:
        V = np.eye(2)
    else:
        V = np.array([[s, -(1 - c)], [1 - c, s]]) / th
    T = np.eye(3)
    T[:2, :2] = [[c, -s], [s, c]]
    T[:2, 2] = V @ np.array([x, y])
    return T


def Ad(T):
    A = np.eye(3)
    A[:2, :2] = T[:2, :2]
    A[0, 2] = T[1, 2]
    A[1, 2] = -T[0, 2]
    return A


def ad(xi, printed=False):
    x, y, th = xi
    a = np.array([[0.0, -th, y], [th, 0.0, -x], [0.0, 0.0, 0.0]])
    if printed:
        a[2, 2] = 1.0  # the paper prints 1 in the corner (erratum ad_se2)
    return a


def Phi(xi, printed=False, terms=30):
    """Φ = Σ (-1)^m/(m+1)! ad^m, summed (the paper's definition)."""
    A = ad(xi, printed)
    out = np.zeros((3, 3))
    P = np.eye(3)
    fact = 1.0
    for m in range(terms):
        fact *= m + 1
        out += ((-1) ** m / fact) * P
        P = P @ A
    return out


def blockdiag(a, b):
    out = np.zeros((6, 6))
    out[:3, :3] = a
    out[3:, 3:] = b
    return out


class DenseSE2SE2:
    """X = (T_s, T_d) as two 3×3 matrices; P 6×6; every step in dense matrix algebra."""

    def __init__(self, dt, accel_std, meas_std, x0, P0, printed_ad=False):
        self.dt = dt
        self.q = np.asarray(accel_std, float)
        self.r = float(meas_std)
        x, y, th, vx, vy, w = x0
        self.Ts = np.array([[np.cos(th), -np.sin(th), x], [np.sin(th), np.cos(th), y], [0, 0, 1.0]])
        self.Td = np.array([[np.cos(w), -np.sin(w), vx], [np.sin(w), np.cos(w), vy], [0, 0, 1.0]])
        self.P = np.array(P0, float)
        self.printed = printed_ad

    def predict(self):
        T = self.dt
        w = np.arctan2(self.Td[1, 0], self.Td[0, 0])
        vx, vy = self.Td[0, 2], self.Td[1, 2]
        Om = np.array([T * vx, T * vy, T * w])
        C = np.zeros((6, 6))
        c, s = np.cos(w), np.sin(w)
        C[:3, 3:] = np.array([[T * c, -T * s, 0], [T * s, T * c, 0], [0, 0, T]])
        PhiO = blockdiag(Phi(Om, self.printed), np.eye(3))
        F = blockdiag(Ad(se2_exp(-Om)), np.eye(3)) + PhiO @ C
        G = np.vstack([T**2 / 2 * np.eye(3), T * np.eye(3)])
        Q = G @ np.diag(self.q**2) @ G.T
        self.Ts = self.Ts @ se2_exp(Om)
        self.P = F @ self.P @ F.T + PhiO @ Q @ PhiO.T

    def update(self, z):
        th = np.arctan2(self.Ts[1, 0], self.Ts[0, 0])
        H = np.zeros((2, 6))
        H[:, :2] = [[np.cos(th), -np.sin(th)], [np.sin(th), np.cos(th)]]
        S = H @ self.P @ H.T + self.r**2 * np.eye(2)
        K = self.P @ H.T @ np.linalg.inv(S)
        nu = K @ (np.asarray(z) - self.Ts[:2, 2])
        self.Ts = self.Ts @ se2_exp(nu[:3])
        self.Td = self.Td @ se2_exp(nu[3:])
        Ph = blockdiag(Phi(nu[:3], self.printed), Phi(nu[3:], self.printed))
        self.P = Ph @ (np.eye(6) - K @ H) @ self.P @ Ph.T

    @property
    def position(self):
        return self.Ts[:2, 2].copy()


def run_dense(z, dt, accel_std, meas_std, x0, P0, printed_ad=False):
    """Positions (B, K, 2) of the dense filter over a batch, one Python step at a time."""
    B, K = z.shape[:2]
    out = np.empty((B, K, 2))
    for b in range(B):
        f = DenseSE2SE2(dt, accel_std, meas_std, x0[b], P0[b] if np.ndim(P0) == 3 else P0, printed_ad)
        for k in range(K):
            f.predict()
            f.update(z[b, k])
            out[b, k] = f.position
    return out
