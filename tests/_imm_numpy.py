"""An IMM of CV modes written out in numpy (Blom and Bar-Shalom), independent of lgekf's IMM kernels, in the plane or
3-D space (the dimension of z): the reference of the IMM likelihood tests (tests/estimators/test_imm_tuning.py,
tests/estimators/test_imm_chain.py) and of the 3-D IMM (tests/estimators/test_imm_3d.py)."""

import math

import numpy as np


def numpy_cv_imm(x0, P0, z, dts, stds, PI, r, mu0, counted=None):
    """The IMM of CV modes over one track, positions z (K, d) (d = 2: state (x, y, v_x, v_y); d = 3: (x, y, z, v_x,
    v_y, v_z)): mixing with the weights PI_ij μ_i / c̄_j (c̄ = PIᵀ μ), the mode-matched Kalman filters with white
    acceleration of std ``stds[j]`` on each axis (G = [T²/2 I; T I]), μ_j ∝ c̄_j N(ν_j; 0, S_j).

    x0 (2d,), P0 (2d, 2d): every mode's initial state; dts (K,) the step before each z; mu0 (M,) initial mode
    probabilities; counted (K,) bool: which steps enter the log-likelihood (default all).
    Returns (Σ_k log Σ_j c̄_j N_j, the combined means Σ_j μ_j x_j (K, 2d), the mode probabilities (K, M)).
    """
    M = len(stds)
    d = np.shape(z)[1]
    xs, Ps, mu = [np.array(x0, float) for _ in range(M)], [np.array(P0, float) for _ in range(M)], np.array(mu0, float)
    H = np.eye(d, 2 * d)
    total = 0.0
    means, mus = [], []
    for k in range(len(z)):
        T = dts[k]
        F = np.eye(2 * d)
        F[:d, d:] = T * np.eye(d)
        G = np.vstack([T**2 / 2 * np.eye(d), T * np.eye(d)])
        cbar = PI.T @ mu
        lik = np.empty(M)
        new = []
        for j in range(M):
            w = PI[:, j] * mu / cbar[j]
            xm = sum(w[i] * xs[i] for i in range(M))
            Pm = sum(w[i] * (Ps[i] + np.outer(xs[i] - xm, xs[i] - xm)) for i in range(M))
            x = F @ xm
            P = F @ Pm @ F.T + stds[j] ** 2 * G @ G.T
            S = H @ P @ H.T + r**2 * np.eye(d)
            nu = z[k] - H @ x
            lik[j] = math.exp(-0.5 * (np.linalg.slogdet(S)[1] + nu @ np.linalg.solve(S, nu)) - 0.5 * d * math.log(2 * math.pi))
            K = P @ H.T @ np.linalg.inv(S)
            new.append((x + K @ nu, (np.eye(2 * d) - K @ H) @ P))
        xs, Ps = [a for a, _ in new], [b for _, b in new]
        if counted is None or counted[k]:
            total += math.log(cbar @ lik)
        mu = cbar * lik / (cbar @ lik)
        means.append(sum(mu[j] * xs[j] for j in range(M)))
        mus.append(mu.copy())
    return total, np.array(means), np.array(mus)


def numpy_cv_imm_loglik(x0, P0, z, dts, stds, PI, r, mu0, counted=None):
    """Σ_k log Σ_j c̄_j N(ν_j; 0, S_j) of one track (``numpy_cv_imm``), positions z (K, 2) (or (K, 3))."""
    return numpy_cv_imm(x0, P0, z, dts, stds, PI, r, mu0, counted)[0]
