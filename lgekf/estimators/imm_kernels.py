"""The IMM's per-step loop in numba: mixing (on the group or in the common coordinates), mode-matched
predict/update, mode probabilities from the innovation likelihoods, and the combined estimate.

Every model is reached through ``lgekf.generated.dispatch`` (its kernels by model index), so one compiled
loop runs any set of registry models. Storage of one IMM (M modes): ``models`` (M,) model indices; ``S``
(M, L) internal states (row j holds mode j's state in its first ``N_INTERNAL[models[j]]`` entries); ``Pp``
(M, N) packed covariances (upper triangle, row-major, of each mode's own n); ``mu`` (M,) mode probabilities;
``PI`` (M, M) the transition matrix, PI[i, j] = P(mode j at k | mode i at k-1).

Mixing on one group (every mode the same model, ``same_group``). Each mode i is a concentrated Gaussian
X = μ_i·exp(ε_i), ε_i ~ N(0, P_i). The mixture Σ w_i N_G(μ_i, P_i) is reduced to one N_G(μ, P):

* mean: iterate μ ← μ·exp(Σ w_i d_i), d_i = [log(μ⁻¹μ_i)]^∨ (generated ``between``, ``retract``), from
  the most probable μ_i, until |Σ w_i d_i| < 1e-12 (at most 50 iterations); then Σ w_i d_i = 0;
* covariance: X = μ_i·exp(ε_i) = μ·exp(d_i)·exp(ε_i). With the right Jacobian Φ = Φ_G of the generated
  ``right_jacobian`` (log(exp(−d) exp(d + δ)) ≈ Φ(d) δ, i.e. exp(d + δ) ≈ exp(d)·exp(Φ(d) δ)), putting
  δ = Φ(d_i)⁻¹ ε_i gives exp(d_i)·exp(ε_i) ≈ exp(d_i + Φ(d_i)⁻¹ ε_i), so to first order in ε_i the error
  about μ is ε = d_i + Φ(d_i)⁻¹ ε_i and
  P = Σ w_i [Φ(d_i)⁻¹ P_i Φ(d_i)⁻ᵀ + d_i d_iᵀ]  (``right_jacobian_inv``; tests/test_imm.py checks it
  against samples pushed through dense expm/logm).

Mixing across models (``same_group`` false): in the common coordinates c = (x, y, θ, v_x, v_y, ω) (body
velocity). Mode i's Gaussian is mapped to c_i = ``physical_to_common``(x_i), P_c,i = A_i P_i A_iᵀ with
A_i = ∂c/∂ε_i (``physical_to_common_jacobian``). A model carries no information on some coordinates
(``common_missing``: CV has no ω; its θ is the direction of its velocity and v_y = 0, no side slip, as for
CTRV and SE(2)×R²): for mixing into mode j those coordinates of mode i are replaced by mode j's own
(mean, variance; no correlation), i.e. only the shared components are mixed and each mode keeps its own
others. The mixture is moment-matched in c (θ differences wrapped to (−π, π] about the most probable
source) and converted to mode j: s_j = ``common_to_state``(c̄), P_j = J P̄_c Jᵀ, J = ``common_jacobian``(c̄).

Likelihood of mode j: N(ν; 0, S) with S = ℋ P ℋᵀ + R (generated ``calH_<meas>``, ``meas_cov_<meas>``) from
the predicted P, and νᵀS⁻¹ν the NIS returned by the fused update; a missed detection (NaN in z) leaves the
predicted probabilities. The combined output is in the common coordinates (the same reduction with the
mode probabilities, on the group when ``same_group``, then converted to c).
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

from ..generated import dispatch as D

__all__ = ["imm_predict", "imm_update", "imm_step", "imm_run_one", "imm_run_batch", "mix_on_group", "combined_common"]

LOG_2PI = math.log(2.0 * math.pi)


@nb.njit(cache=True)
def unpack_into(p, n, out):
    """Packed upper triangle (row-major) -> dense symmetric out[:n, :n]."""
    k = 0
    for i in range(n):
        for j in range(i, n):
            out[i, j] = p[k]
            out[j, i] = p[k]
            k += 1


@nb.njit(cache=True)
def pack_from(P, n, p):
    """Dense P[:n, :n] -> packed upper triangle p (symmetrised)."""
    k = 0
    for i in range(n):
        for j in range(i, n):
            p[k] = 0.5 * (P[i, j] + P[j, i])
            k += 1


@nb.njit(cache=True)
def _congruence_add(T, P, w, out):
    """out += w · T P Tᵀ (T (a, b), P (b, b), out (a, a))."""
    a, b = T.shape
    TP = np.empty((a, b))
    for i in range(a):
        for k in range(b):
            acc = 0.0
            for m in range(b):
                acc += T[i, m] * P[m, k]
            TP[i, k] = acc
    for i in range(a):
        for j in range(i, a):
            acc = 0.0
            for k in range(b):
                acc += TP[i, k] * T[j, k]
            out[i, j] += w * acc
            if j != i:
                out[j, i] += w * acc


@nb.njit(cache=True)
def _packed_at(p, n, i, j):
    """P[i, j] of a packed upper triangle (row-major)."""
    if i > j:
        i, j = j, i
    return p[i * n - i * (i - 1) // 2 + (j - i)]


@nb.njit(cache=True)
def _congruence_packed(T, p, n, out):
    """out = T P Tᵀ (T (a, n), P packed (n(n+1)/2)), no temporary arrays beyond one row."""
    a = T.shape[0]
    row = np.empty(n)
    for i in range(a):
        for k in range(n):
            acc = 0.0
            for m in range(n):
                t = T[i, m]
                if t != 0.0:
                    acc += t * _packed_at(p, n, m, k)
            row[k] = acc
        for j in range(i, a):
            acc = 0.0
            for k in range(n):
                acc += row[k] * T[j, k]
            out[i, j] = acc
            out[j, i] = acc


@nb.njit(cache=True)
def mix_on_group(model, S, Pp, w, s_out, P_out):
    """Reduce Σ w_i N_G(μ_i, P_i) (rows of S, Pp; all the same model) to one N_G(μ, P) (module docstring).

    s_out: (L,) receives μ (internal state); P_out (n, n) the dense covariance. Returns the iterations used.
    """
    M = S.shape[0]
    n = D.N_TANGENT[model]
    ni = D.N_INTERNAL[model]
    best = 0
    for i in range(M):
        if w[i] > w[best]:
            best = i
    for k in range(ni):
        s_out[k] = S[best, k]
    it = 0
    if M > 1:
        delta = np.empty(n)
        for it in range(1, 51):
            delta[:] = 0.0
            for i in range(M):
                if w[i] > 0.0:
                    d = D.between(model, s_out, S[i])
                    for k in range(n):
                        delta[k] += w[i] * d[k]
            D.retract(model, s_out, delta)
            nrm = 0.0
            for k in range(n):
                nrm += delta[k] * delta[k]
            if nrm < 1e-24:
                break
    Pi = np.empty((n, n))
    for a in range(n):
        for b in range(n):
            P_out[a, b] = 0.0
    for i in range(M):
        if w[i] <= 0.0:
            continue
        unpack_into(Pp[i], n, Pi)
        if M == 1:
            for a in range(n):
                for b in range(n):
                    P_out[a, b] += w[i] * Pi[a, b]
            continue
        d = D.between(model, s_out, S[i])
        Ti = D.right_jacobian_inv(model, d)
        _congruence_add(Ti, Pi, w[i], P_out)
        for a in range(n):
            for b in range(n):
                P_out[a, b] += w[i] * d[a] * d[b]
    return it


@nb.njit(cache=True)
def _to_common(model, s, p, c_out, P_out):
    """Mode state s, packed p -> common c (6,) and its covariance (6, 6) (A P Aᵀ)."""
    n = D.N_TANGENT[model]
    x = D.state_to_physical(model, s)
    c = D.physical_to_common(model, x)
    A = D.physical_to_common_jacobian(model, x)
    for a in range(6):
        c_out[a] = c[a]
    _congruence_packed(A, p, n, P_out)


@nb.njit(cache=True)
def _wrap(a):
    return a - 2.0 * math.pi * math.floor((a + math.pi) / (2.0 * math.pi))


@nb.njit(cache=True)
def mix_common(C, PC, miss, w, fill_c, fill_P, c_out, P_out):
    """Moment-match Σ w_i N(c_i, P_c,i) in the common coordinates (θ wrapped); coordinates k a source does not
    carry (miss[i, k] = 1) take fill_c[k] and the variance fill_P[k, k] (no correlation) for that source."""
    M = C.shape[0]
    best = 0
    for i in range(M):
        if w[i] > w[best]:
            best = i
    Ci = np.empty((M, 6))
    Pi = np.empty((M, 6, 6))
    for i in range(M):
        for a in range(6):
            Ci[i, a] = C[i, a]
            for b in range(6):
                Pi[i, a, b] = PC[i, a, b]
        for a in range(6):
            if miss[i, a] > 0.5:
                Ci[i, a] = fill_c[a]
                for b in range(6):
                    Pi[i, a, b] = 0.0
                    Pi[i, b, a] = 0.0
                Pi[i, a, a] = fill_P[a, a]
    ref = Ci[best, 2]
    for a in range(6):
        c_out[a] = 0.0
    for i in range(M):
        for a in range(6):
            v = Ci[i, a]
            if a == 2:
                v = ref + _wrap(v - ref)
            c_out[a] += w[i] * v
    for a in range(6):
        for b in range(6):
            P_out[a, b] = 0.0
    d = np.empty(6)
    for i in range(M):
        for a in range(6):
            d[a] = Ci[i, a] - c_out[a]
        d[2] = _wrap(d[2])
        for a in range(6):
            for b in range(6):
                P_out[a, b] += w[i] * (Pi[i, a, b] + d[a] * d[b])
    c_out[2] = _wrap(c_out[2])


@nb.njit(cache=True)
def combined_common(models, S, Pp, mu, same_group, c_out, P_out):
    """The IMM's combined estimate in the common coordinates: c (6,), P_c (6, 6)."""
    M = models.shape[0]
    if M == 1:
        _to_common(models[0], S[0], Pp[0], c_out, P_out)
        return
    if same_group:
        model = models[0]
        n = D.N_TANGENT[model]
        s = np.empty(S.shape[1])
        P = np.empty((n, n))
        mix_on_group(model, S, Pp, mu, s, P)
        p = np.empty(n * (n + 1) // 2)
        pack_from(P, n, p)
        _to_common(model, s, p, c_out, P_out)
        return
    C = np.empty((M, 6))
    PC = np.empty((M, 6, 6))
    miss = np.empty((M, 6))
    for i in range(M):
        _to_common(models[i], S[i], Pp[i], C[i], PC[i])
        miss[i] = D.common_missing(models[i])
    # a coordinate some modes lack: filled with the probability-weighted mean/variance of the modes that carry it
    fill_c = np.zeros(6)
    fill_P = np.zeros((6, 6))
    for a in range(6):
        tot = 0.0
        for i in range(M):
            if miss[i, a] < 0.5:
                tot += mu[i]
        if tot > 0.0:
            for i in range(M):
                if miss[i, a] < 0.5:
                    fill_c[a] += mu[i] / tot * C[i, a]
            for i in range(M):
                if miss[i, a] < 0.5:
                    e = C[i, a] - fill_c[a]
                    fill_P[a, a] += mu[i] / tot * (PC[i, a, a] + e * e)
    mix_common(C, PC, miss, mu, fill_c, fill_P, c_out, P_out)


@nb.njit(cache=True)
def _mix(models, S, Pp, mu, PI, same_group):
    """The IMM's interaction step, in place: every mode restarts from its mixed estimate; returns c̄_j = Σ_i PI_ij μ_i."""
    M = models.shape[0]
    cbar = np.zeros(M)
    for j in range(M):
        for i in range(M):
            cbar[j] += PI[i, j] * mu[i]
    if M == 1:
        return cbar
    W = np.zeros((M, M))  # W[j, i] = w_{i|j}
    for j in range(M):
        if cbar[j] > 0.0:
            for i in range(M):
                W[j, i] = PI[i, j] * mu[i] / cbar[j]
        else:
            W[j, j] = 1.0
    S_new = S.copy()
    P_new = Pp.copy()
    if same_group:
        model = models[0]
        n = D.N_TANGENT[model]
        P = np.empty((n, n))
        for j in range(M):
            mix_on_group(model, S, Pp, W[j], S_new[j], P)
            pack_from(P, n, P_new[j])
    else:
        C = np.empty((M, 6))
        PC = np.empty((M, 6, 6))
        miss = np.empty((M, 6))
        for i in range(M):
            _to_common(models[i], S[i], Pp[i], C[i], PC[i])
            miss[i] = D.common_missing(models[i])
        c = np.empty(6)
        Pc = np.empty((6, 6))
        for j in range(M):
            mix_common(C, PC, miss, W[j], C[j], PC[j], c, Pc)
            model = models[j]
            n = D.N_TANGENT[model]
            x = D.common_to_state(model, c)
            s = D.state_from_physical(model, x)
            for k in range(s.shape[0]):
                S_new[j, k] = s[k]
            J = D.common_jacobian(model, c)
            P = np.zeros((n, n))
            _congruence_add(J, Pc, 1.0, P)
            pack_from(P, n, P_new[j])
    S[:, :] = S_new
    Pp[:, :] = P_new
    return cbar


@nb.njit(cache=True)
def _log_likelihood(model, s, p, r, meas_pose):
    """log det S and m of the innovation covariance S = ℋ P ℋᵀ + R of mode (model, s, p)."""
    n = D.N_TANGENT[model]
    if meas_pose:
        H = D.calH_pose(model, s)
        R = D.meas_cov_pose(r)
    else:
        H = D.calH_position(model, s)
        R = D.meas_cov_position(r)
    m = H.shape[0]
    Sm = np.empty((m, m))
    _congruence_packed(H, p, n, Sm)
    for a in range(m):
        for b in range(m):
            Sm[a, b] += R[a, b]
    return _logdet_spd(Sm), m


@nb.njit(cache=True)
def _logdet_spd(A):
    """log det of a small symmetric positive definite matrix (Cholesky; -inf if not PD)."""
    m = A.shape[0]
    L = np.zeros((m, m))
    out = 0.0
    for j in range(m):
        d = A[j, j]
        for k in range(j):
            d -= L[j, k] * L[j, k]
        if not d > 0.0:
            return -np.inf
        L[j, j] = math.sqrt(d)
        out += math.log(d)
        for i in range(j + 1, m):
            v = A[i, j]
            for k in range(j):
                v -= L[i, k] * L[j, k]
            L[i, j] = v / L[j, j]
    return out


@nb.njit(cache=True)
def imm_predict(models, S, Pp, mu, PI, Q, dt, same_group):
    """Mixing, then every mode's prediction by dt, in place; mu becomes the predicted probabilities Σ_i PI_ij μ_i.

    Q (M, q): the modes' process-noise stds.
    """
    cbar = _mix(models, S, Pp, mu, PI, same_group)
    for j in range(models.shape[0]):
        D.predict(models[j], S[j], Pp[j], dt, Q[j])
        mu[j] = cbar[j]


@nb.njit(cache=True)
def imm_update(models, S, Pp, mu, r, z, meas_pose, nis_out):
    """Every mode's update with z, in place, and μ_j ∝ μ_j N(ν_j; 0, S_j); a NaN in z: nothing changes.

    nis_out (M,) receives each mode's NIS (NaN when missed). Returns the log-likelihood log Σ_j μ_j N_j.
    """
    M = models.shape[0]
    for k in range(z.shape[0]):
        if np.isnan(z[k]):
            for j in range(M):
                nis_out[j] = np.nan
            return np.nan
    loglik = np.zeros(M)
    for j in range(M):
        logdet, m = _log_likelihood(models[j], S[j], Pp[j], r, meas_pose)
        if meas_pose:
            nis = D.update_pose(models[j], S[j], Pp[j], z, r)
        else:
            nis = D.update_position(models[j], S[j], Pp[j], z, r)
        nis_out[j] = nis
        loglik[j] = -0.5 * (nis + logdet + m * LOG_2PI)
    prior = mu.copy()
    top = -np.inf
    for j in range(M):
        if mu[j] > 0.0 and loglik[j] > top:
            top = loglik[j]
    tot = 0.0
    for j in range(M):
        v = mu[j] * math.exp(loglik[j] - top) if np.isfinite(loglik[j]) else 0.0
        mu[j] = v
        tot += v
    if not (tot > 0.0) or not np.isfinite(tot):
        mu[:] = prior
        return -np.inf
    for j in range(M):
        mu[j] /= tot
    return top + math.log(tot)


@nb.njit(cache=True)
def imm_step(models, S, Pp, mu, PI, Q, r, z, dt, same_group, meas_pose, nis_out):
    """One IMM cycle in place: imm_predict by dt, then imm_update with z (NaN: missed detection)."""
    imm_predict(models, S, Pp, mu, PI, Q, dt, same_group)
    return imm_update(models, S, Pp, mu, r, z, meas_pose, nis_out)


@nb.njit(cache=True)
def imm_run_one(models, S, Pp, mu, PI, Q, r, z, dts, same_group, meas_pose, out_c, out_P, out_mu):
    """Run the IMM over one trajectory z (K, m) with steps dts (K,), from the state (S, Pp, mu) (modified).

    Writes the combined common estimate out_c (K, 6), its covariance out_P (K, 6, 6) when out_P.shape[0] == K,
    and the mode probabilities out_mu (K, M).
    """
    K = z.shape[0]
    keep_P = out_P.shape[0] == K
    Pc = np.empty((6, 6))
    nis = np.empty(models.shape[0])
    for k in range(K):
        imm_step(models, S, Pp, mu, PI, Q, r, z[k], dts[k], same_group, meas_pose, nis)
        combined_common(models, S, Pp, mu, same_group, out_c[k], Pc)
        if keep_P:
            out_P[k, :, :] = Pc
        for j in range(models.shape[0]):
            out_mu[k, j] = mu[j]


@nb.njit(cache=True, parallel=True)
def imm_run_batch(models, S0, P0, mu0, PI, Q, r, z, dts, same_group, meas_pose, out_c, out_P, out_mu):
    """imm_run_one over B trajectories in parallel: S0 (B, M, L), P0 (B, M, N), z (B, K, m), dts (B, K)."""
    for b in nb.prange(z.shape[0]):
        S = S0[b].copy()
        Pp = P0[b].copy()
        mu = mu0.copy()
        imm_run_one(models, S, Pp, mu, PI, Q, r, z[b], dts[b], same_group, meas_pose, out_c[b], out_P[b], out_mu[b])
