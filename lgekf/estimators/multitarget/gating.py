"""Gating with each model's innovation covariance: S = ℋPℋᵀ + R (eq:calH, eq:K) for every track, the
Mahalanobis distance d² = eᵀS⁻¹e of every track × detection innovation e = [log_G'(h(μ)⁻¹Z)]^∨, the gate
d² ≤ γ and the Gaussian log-likelihood log N(e; 0, S).

Generic over the registry: ℋ and e come from the generated ``calH_bank_<meas>`` and
``innovation_bank_<meas>`` kernels of the model, P is the packed covariance (upper triangle, row-major) in
the tangent coordinates of X = μ·exp(ε); nothing here knows a model. Inputs are arrays over a bank of
tracks (rows); ``live`` marks the rows in use.
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np
from scipy.special import gammaincinv

from ..packed import unpack_into

__all__ = ["gate_threshold", "innovation_covariances", "gate_scores"]


def gate_threshold(gate_prob: float, m: int) -> float:
    """γ with P(d² ≤ γ) = ``gate_prob`` for d² ~ χ²(m) (the gate of an m-dimensional measurement).

    Parameters
    ----------
    gate_prob : float
        P_G in (0, 1): the probability that a target's own detection falls inside its gate.
    m : int
        Dimension of the measurement's tangent.

    Returns
    -------
    float
        The χ²_m quantile γ.

    Examples
    --------
    >>> round(gate_threshold(0.99, 2), 4)   # -2 ln(0.01)
    9.2103
    """
    if not 0.0 < gate_prob < 1.0:
        raise ValueError(f"gate probability: must be in (0, 1), got {gate_prob}")
    return float(2.0 * gammaincinv(0.5 * m, gate_prob))  # the χ²_m quantile


@nb.njit(cache=True)
def innovation_covariances(H, p, live, R, S, Sinv, logdet):
    """S_i = ℋ_i P_i ℋ_iᵀ + R for every live track (eq:K), with S_i⁻¹ and log det S_i.

    H (N, m, n) from ``calH_bank_<meas>``, p (N, n(n+1)/2) packed covariances, R (m, m); outputs
    S, Sinv (N, m, m), logdet (N,).
    """
    N, m, n = H.shape
    P = np.empty((n, n))
    HP = np.empty((m, n))
    for i in range(N):
        if not live[i]:
            continue
        unpack_into(p[i], n, P)
        for a in range(m):
            for b in range(n):
                acc = 0.0
                for c in range(n):
                    acc += H[i, a, c] * P[c, b]
                HP[a, b] = acc
        for a in range(m):
            for b in range(a, m):
                acc = R[a, b]
                for c in range(n):
                    acc += HP[a, c] * H[i, b, c]
                S[i, a, b] = acc
                S[i, b, a] = acc
        Sinv[i] = np.linalg.inv(S[i])
        logdet[i] = math.log(np.linalg.det(S[i]))


@nb.njit(cache=True)
def gate_scores(E, Sinv, logdet, live, gamma, d2, loglik, gated):
    """d²_ij = e_ijᵀ S_i⁻¹ e_ij, gated_ij = d²_ij ≤ γ and log N(e_ij; 0, S_i) for live tracks i and
    detections j; E (N, M, m) innovations. Not gated pairs get loglik = -inf."""
    N, M, m = E.shape
    c0 = 0.5 * m * math.log(2.0 * math.pi)
    for i in range(N):
        if not live[i]:
            for j in range(M):
                gated[i, j] = False
                loglik[i, j] = -np.inf
                d2[i, j] = np.inf
            continue
        for j in range(M):
            acc = 0.0
            for a in range(m):
                ea = E[i, j, a]
                acc += ea * Sinv[i, a, a] * ea
                for b in range(a + 1, m):
                    acc += 2.0 * ea * Sinv[i, a, b] * E[i, j, b]
            d2[i, j] = acc
            if acc <= gamma:
                gated[i, j] = True
                loglik[i, j] = -0.5 * acc - 0.5 * logdet[i] - c0
            else:
                gated[i, j] = False
                loglik[i, j] = -np.inf
