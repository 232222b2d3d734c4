"""An IMM of CV modes written out in numpy (Blom and Bar-Shalom), independent of lgekf's IMM kernels: the
reference of the IMM likelihood tests (tests/estimators/test_imm_tuning.py, tests/estimators/test_imm_chain.py)."""

import math

import numpy as np


def numpy_cv_imm_loglik(x0, P0, z, dts, stds, PI, r, mu0, counted=None):
    """Σ_k log Σ_j c̄_j N(ν_j; 0, S_j) of one track: mixing with the weights PI_ij μ_i / c̄_j (c̄ = PIᵀ μ), the
    mode-matched Kalman filters of CV state (x, y, v_x, v_y) with white acceleration of std ``stds[j]``.

    x0 (4,), P0 (4, 4): every mode's initial state; z (K, 2) positions; dts (K,) the step before each z;
    mu0 (M,) initial mode probabilities; counted (K,) bool: which steps enter the sum (default all).
    """
    M = len(stds)
    xs, Ps, mu = [np.array(x0, float) for _ in range(M)], [np.array(P0, float) for _ in range(M)], np.array(mu0, float)
    H = np.eye(2, 4)
    total = 0.0
    for k in range(len(z)):
        T = dts[k]
        F = np.eye(4)
        F[0, 2] = F[1, 3] = T
        G = np.array([[T**2 / 2, 0], [0, T**2 / 2], [T, 0], [0, T]])
        cbar = PI.T @ mu
        lik = np.empty(M)
        new = []
        for j in range(M):
            w = PI[:, j] * mu / cbar[j]
            xm = sum(w[i] * xs[i] for i in range(M))
            Pm = sum(w[i] * (Ps[i] + np.outer(xs[i] - xm, xs[i] - xm)) for i in range(M))
            x = F @ xm
            P = F @ Pm @ F.T + stds[j] ** 2 * G @ G.T
            S = H @ P @ H.T + r**2 * np.eye(2)
            nu = z[k] - H @ x
            lik[j] = math.exp(-0.5 * (np.linalg.slogdet(S)[1] + nu @ np.linalg.solve(S, nu)) - math.log(2 * math.pi))
            K = P @ H.T @ np.linalg.inv(S)
            new.append((x + K @ nu, (np.eye(4) - K @ H) @ P))
        xs, Ps = [a for a, _ in new], [b for _, b in new]
        if counted is None or counted[k]:
            total += math.log(cbar @ lik)
        mu = cbar * lik / (cbar @ lik)
    return total
