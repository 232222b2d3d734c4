"""The probabilistic-data-association update on the group: one correction per track from all its gated
detections, applied as in the LG-EKF update (eq:K, eq:up_mu, eq:up_P).

For track i with weights β_i0 (no detection is the target's) and β_ij (detection j is), innovations
e_ij = [log_G'(h(μ)⁻¹Z_j)]^∨, ℋ, S = ℋPℋᵀ + R and K = Pℋᵀ S⁻¹ (eq:K):

    ν = K Σ_j β_ij e_ij                                  (the combined innovation through the gain),
    P_c = P − (1 − β_i0) K S Kᵀ + K [Σ_j β_ij e_ij e_ijᵀ − ē ēᵀ] Kᵀ,   ē = Σ_j β_ij e_ij
                                                         (the PDA covariance with the spread of innovations),
    μ ← μ·exp(ν) (eq:up_mu, generated ``retract``),  P ← Φ(ν) P_c Φ(ν)ᵀ (eq:up_P, generated ``right_jacobian``),

in the tangent coordinates of X = μ·exp(ε) (right perturbation). With a single detection of weight 1 it
is the LG-EKF update (the standard-form covariance (I − Kℋ)P instead of the generated update's Joseph
form). As in the generated update, a rotation angle of ν beyond π damps the whole correction,
ν → αν, α = π/|angle|.
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

from ..packed import unpack_into

__all__ = ["pda_corrections", "transport_covariances"]


@nb.njit(cache=True)
def pda_corrections(p, live, H, S, Sinv, E, beta0, beta, periodic, eps, Pc, updated):
    """The tangent corrections ν (eps, (N, n)) and the covariances before transport P_c (Pc, (N, n, n)) of
    every live track from its weights β (module docstring); updated[i] is False where β_i0 = 1 (nothing
    to do). periodic: indices of the tangent's rotation angles (the model's ``periodic_tangent``)."""
    N, m, n = H.shape
    M = E.shape[1]
    P = np.empty((n, n))
    PHt = np.empty((n, m))
    K = np.empty((n, m))
    ebar = np.empty(m)
    C = np.empty((m, m))
    KC = np.empty((n, m))
    for i in range(N):
        updated[i] = False
        if not live[i] or beta0[i] >= 1.0:
            continue
        updated[i] = True
        unpack_into(p[i], n, P)
        for a in range(n):
            for b in range(m):
                acc = 0.0
                for c in range(n):
                    acc += P[a, c] * H[i, b, c]
                PHt[a, b] = acc
        for a in range(n):
            for b in range(m):
                acc = 0.0
                for c in range(m):
                    acc += PHt[a, c] * Sinv[i, c, b]
                K[a, b] = acc
        for a in range(m):
            ebar[a] = 0.0
            for b in range(m):
                C[a, b] = (1.0 - beta0[i]) * S[i, a, b]
        for j in range(M):
            bj = beta[i, j]
            if bj > 0.0:
                for a in range(m):
                    ebar[a] += bj * E[i, j, a]
                    for b in range(m):
                        C[a, b] -= bj * E[i, j, a] * E[i, j, b]
        for a in range(m):
            for b in range(m):
                C[a, b] += ebar[a] * ebar[b]
        # ν = K ē, damped if a rotation angle exceeds π
        alpha = 1.0
        for a in range(n):
            acc = 0.0
            for b in range(m):
                acc += K[a, b] * ebar[b]
            eps[i, a] = acc
        for k in range(periodic.shape[0]):
            v = abs(eps[i, periodic[k]])
            if v > math.pi:
                alpha = min(alpha, math.pi / v)
        if alpha < 1.0:
            for a in range(n):
                eps[i, a] *= alpha
        # P_c = P − K C Kᵀ, C = (1 − β0) S − spread
        for a in range(n):
            for b in range(m):
                acc = 0.0
                for c in range(m):
                    acc += K[a, c] * C[c, b]
                KC[a, b] = acc
        for a in range(n):
            for b in range(a, n):
                acc = P[a, b]
                for c in range(m):
                    acc -= KC[a, c] * K[b, c]
                Pc[i, a, b] = acc
                Pc[i, b, a] = acc


@nb.njit(cache=True)
def transport_covariances(Phi, Pc, updated, p):
    """p_i ← pack(Φ_i P_c,i Φ_iᵀ) (eq:up_P) for the updated tracks; Phi, Pc (N, n, n), p (N, n(n+1)/2)."""
    N, n, _ = Pc.shape
    T = np.empty((n, n))
    for i in range(N):
        if not updated[i]:
            continue
        for a in range(n):
            for b in range(n):
                acc = 0.0
                for c in range(n):
                    acc += Phi[i, a, c] * Pc[i, c, b]
                T[a, b] = acc
        k = 0
        for a in range(n):
            for b in range(a, n):
                acc = 0.0
                for c in range(n):
                    acc += T[a, c] * Phi[i, b, c]
                p[i, k] = acc
                k += 1
