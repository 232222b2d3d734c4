"""The IMM's per-step loop in numba: mixing (on the group or in the common coordinates), mode-matched
predict/update, mode probabilities from the innovation likelihoods, and the combined estimate.

Every model is reached through ``lgekf.generated.dispatch`` (its kernels by model index, the chains inlined), so
one compiled loop runs any set of registry models. Storage of one IMM (M modes): ``models`` (M,) model indices; ``S``
(M, L) internal states (row j holds mode j's state in its first ``N_INTERNAL[models[j]]`` entries); ``Pp``
(M, N) packed covariances (upper triangle, row-major, of each mode's own n); ``mu`` (M,) mode probabilities;
``PI`` (M, M) the transition matrix, PI[i, j] = P(mode j at k | mode i at k-1).

Mixing on one group (every mode the same model, ``same_group``). Each mode i is a concentrated Gaussian
X = μ_i·exp(ε_i), ε_i ~ N(0, P_i). The mixture Σ w_i N_G(μ_i, P_i) is reduced to one N_G(μ, P):

* mean: iterate μ ← μ·exp(Σ w_i d_i), d_i = [log(μ⁻¹μ_i)]^∨ (generated ``between_add``, ``retract``), from
  the most probable μ_i, until |Σ w_i d_i| < 1e-12 (at most 50 iterations); then Σ w_i d_i = 0;
* covariance: X = μ_i·exp(ε_i) = μ·exp(d_i)·exp(ε_i). With the right Jacobian Φ = Φ_G of the generated
  ``right_jacobian`` (log(exp(−d) exp(d + δ)) ≈ Φ(d) δ, i.e. exp(d + δ) ≈ exp(d)·exp(Φ(d) δ)), putting
  δ = Φ(d_i)⁻¹ ε_i gives exp(d_i)·exp(ε_i) ≈ exp(d_i + Φ(d_i)⁻¹ ε_i), so to first order in ε_i the error
  about μ is ε = d_i + Φ(d_i)⁻¹ ε_i and
  P = Σ w_i [Φ(d_i)⁻¹ P_i Φ(d_i)⁻ᵀ + d_i d_iᵀ]  (``right_jacobian_inv``; tests/test_imm.py checks it
  against samples pushed through dense expm/logm). Each term comes from the generated ``mix_transport``
  (between, Φ⁻¹ and the congruence in one straight-line kernel over the packed covariances; derive/codegen/mixing.py).

Mixing across models (``same_group`` false): in the common coordinates c = (x, y, θ, v_x, v_y, ω) (body
velocity). Mode i's Gaussian is mapped to c_i = ``physical_to_common``(x_i), P_c,i = A_i P_i A_iᵀ with
A_i = ∂c/∂ε_i (``physical_to_common_jacobian``). A model carries no information on some coordinates
(``common_missing``: CV has no ω; its θ is the direction of its velocity and v_y = 0, no side slip, as for
CTRV and SE(2)×R²): for mixing into mode j those coordinates of mode i are replaced by mode j's own
(mean, variance; no correlation), i.e. only the shared components are mixed and each mode keeps its own
others. The mixture is moment-matched in c (θ differences wrapped to (−π, π] about the most probable
source) and converted to mode j: s_j = ``common_to_state``(c̄), P_j = J P̄_c Jᵀ, J = ``common_jacobian``(c̄) (both
directions through the generated straight-line ``common_of_state`` / ``state_of_common``).
A heading read off a velocity (CV) is singular at speed 0: the Jacobians are taken at speed ≥ 1e-9 m/s
(``SPEED_FLOOR``) and the std of the common θ is capped at π (congruence scaling, as the filters'
``limit_angle_variance``), so a stopped CV mode hands on "heading unknown", not an infinite variance.

Likelihood of mode j: N(ν; 0, S) with log det S, S = ℋ P ℋᵀ + R, from the generated ``innovation_logdet_<meas>`` at
the predicted state, and νᵀS⁻¹ν the NIS returned by the fused update; a missed detection (NaN in z) leaves the
predicted probabilities. The combined output is in the common coordinates (the same reduction with the
mode probabilities, on the group when ``same_group``, then converted to c).
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

from ..generated import dispatch as D
from .packed import pack_from, unpack_into

__all__ = ["imm_predict", "imm_update", "imm_step", "imm_run_one", "imm_run_batch", "mix_on_group", "combined_common",
           "workspace"]

LOG_2PI = math.log(2.0 * math.pi)
NMAX = int(np.max(D.N_TANGENT))  # the largest tangent dimension of the registry
LMAX = int(np.max(D.N_INTERNAL))
NW = max(NMAX, 6)  # square scratch matrices hold n × n and n × 6 blocks
SPEED_FLOOR = 1e-9  # m/s: conversions' Jacobians are evaluated at least this far from speed 0


@nb.njit(cache=True)
def workspace(M):
    """The scratch arrays of one IMM of M modes (no allocation inside the step loop)."""
    return (np.empty(NMAX), np.empty(NMAX), np.empty((NW, NW)), np.empty((NW, NW)), np.empty(NW),
            np.empty(NMAX), np.empty(6),
            np.empty((6, NMAX)), np.empty((M, 6)), np.empty((M, 6, 6)), np.empty((M, 6)), np.empty((M, M)),
            np.empty((M, LMAX)), np.empty((M, NMAX * (NMAX + 1) // 2)), np.empty(LMAX), np.empty(NMAX * (NMAX + 1) // 2),
            np.empty(M), np.empty(M), np.empty(6), np.empty((6, 6)), np.empty((M, 6)), np.empty((M, 6, 6)),
            np.empty((NW, NW)))


@nb.njit(cache=True)
def _congruence_dense(T, a, P, n, row, out):
    """out[:a, :a] = T P Tᵀ for T[:a, :n] and dense P[:n, :n]."""
    for i in range(a):
        for k in range(n):
            acc = 0.0
            for m in range(n):
                t = T[i, m]
                if t != 0.0:
                    acc += t * P[m, k]
            row[k] = acc
        for j in range(i, a):
            acc = 0.0
            for k in range(n):
                acc += row[k] * T[j, k]
            out[i, j] = acc
            out[j, i] = acc


@nb.njit(cache=True)
def mix_on_group(model, S, Pp, w, s_out, P_out, ws):
    """Reduce Σ w_i N_G(μ_i, P_i) (rows of S, Pp; all the same model) to one N_G(μ, P) (module docstring).

    s_out: (L,) receives μ (internal state); P_out (≥ n, ≥ n) the dense covariance; ws: ``workspace(M)``.
    Returns the iterations used.
    """
    p = ws[15]
    it = _mix_on_group(model, S, Pp, w, s_out, p, ws[0])
    unpack_into(p, D.N_TANGENT[model], P_out)
    return it


@nb.njit(cache=True)
def _mix_on_group(model, S, Pp, w, s_out, p_out, delta):
    """mix_on_group into the packed covariance p_out; delta (n,) scratch.

    The mean's terms come from the generated ``between_add``, each source's covariance term w_i [Φ(d_i)⁻¹ P_i
    Φ(d_i)⁻ᵀ + d_i d_iᵀ] from the generated ``mix_transport`` (straight line, packed in and out)."""
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
        for it in range(1, 51):
            for k in range(n):
                delta[k] = 0.0
            for i in range(M):
                if w[i] > 0.0 and not (i == best and it == 1):  # d_best = 0 in the first iteration
                    D.between_add(model, s_out, S[i], w[i], delta)
            D.retract(model, s_out, delta)
            nrm = 0.0
            for k in range(n):
                nrm += delta[k] * delta[k]
            if nrm < 1e-24:
                break
    npk = n * (n + 1) // 2
    if M == 1:
        for k in range(npk):
            p_out[k] = Pp[0, k]
        return it
    for k in range(npk):
        p_out[k] = 0.0
    for i in range(M):
        if w[i] > 0.0:
            D.mix_transport(model, s_out, S[i], Pp[i], w[i], p_out)
    return it


@nb.njit(cache=True)
def _to_common(model, s, p, c_out, P_out, x, A, row, Pd, ctmp):
    """Mode state s, packed p -> common c (6,) and its covariance (6, 6) (A P Aᵀ); x, A, row, Pd, ctmp scratch.

    At a speed below SPEED_FLOOR the Jacobian is taken at the state with speed SPEED_FLOOR along θ (a heading
    read off the velocity, CV's, is singular at 0; its variance is then capped by _cap_heading)."""
    n = D.N_TANGENT[model]
    D.common_of_state(model, s, p, c_out, P_out)  # generated, straight line: c and A P Aᵀ at s
    if math.hypot(c_out[3], c_out[4]) >= SPEED_FLOOR:
        _cap_heading(c_out, P_out)
        return
    D.physical_into(model, s, x)
    D.physical_to_common_into(model, x, c_out)
    if math.hypot(c_out[3], c_out[4]) < SPEED_FLOOR:
        for k in range(6):
            ctmp[k] = c_out[k]
        ctmp[3] = SPEED_FLOOR
        ctmp[4] = 0.0
        D.common_to_state_into(model, ctmp, x)
    D.physical_to_common_jacobian_into(model, x, A)
    unpack_into(p, n, Pd)
    _congruence_dense(A, 6, Pd, n, row, P_out)
    _cap_heading(c_out, P_out)


@nb.njit(cache=True)
def _cap_heading(c, P):
    """Cap the std of the common θ at π by congruence scaling (as the filters' limit_angle_variance): a heading
    read off a velocity near zero (CV) is unknown, not infinitely uncertain; at exactly zero θ = 0, variance π²."""
    v = P[2, 2]
    if not (np.isfinite(v) and np.isfinite(c[2])):
        c[2] = 0.0
        for k in range(6):
            P[2, k] = 0.0
            P[k, 2] = 0.0
        P[2, 2] = math.pi * math.pi
    elif v > math.pi * math.pi:
        f = math.pi / math.sqrt(v)
        for k in range(6):
            P[2, k] *= f
            P[k, 2] *= f


@nb.njit(cache=True)
def _wrap(a):
    return a - 2.0 * math.pi * math.floor((a + math.pi) / (2.0 * math.pi))


@nb.njit(cache=True)
def mix_common(C, PC, miss, w, fill_c, fill_P, c_out, P_out, Ci, Pi, d):
    """Moment-match Σ w_i N(c_i, P_c,i) in the common coordinates (θ wrapped); coordinates k a source does not
    carry (miss[i, k] = 1) take fill_c[k] and the variance fill_P[k, k] (no correlation) for that source.
    Ci (M, 6), Pi (M, 6, 6), d (6,): scratch."""
    M = C.shape[0]
    best = 0
    for i in range(M):
        if w[i] > w[best]:
            best = i
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
        if w[i] == 0.0:
            continue
        for a in range(6):
            v = Ci[i, a]
            if a == 2:
                v = ref + _wrap(v - ref)
            c_out[a] += w[i] * v
    for a in range(6):
        for b in range(6):
            P_out[a, b] = 0.0
    for i in range(M):
        if w[i] == 0.0:
            continue
        for a in range(6):
            d[a] = Ci[i, a] - c_out[a]
        d[2] = _wrap(d[2])
        for a in range(6):
            for b in range(6):
                P_out[a, b] += w[i] * (Pi[i, a, b] + d[a] * d[b])
    c_out[2] = _wrap(c_out[2])


@nb.njit(cache=True)
def _all_common(models, S, Pp, ws):
    """Every mode in the common coordinates: ws C (M, 6), PC (M, 6, 6), miss (M, 6)."""
    C, PC, miss = ws[8], ws[9], ws[10]
    for i in range(models.shape[0]):
        _to_common(models[i], S[i], Pp[i], C[i], PC[i], ws[5], ws[7], ws[4], ws[22], ws[6])
        for a in range(6):
            miss[i, a] = D.COMMON_MISSING[models[i], a]


@nb.njit(cache=True)
def combined_common(models, S, Pp, mu, same_group, c_out, P_out, ws):
    """The IMM's combined estimate in the common coordinates: c (6,), P_c (6, 6)."""
    M = models.shape[0]
    if M == 1:
        _to_common(models[0], S[0], Pp[0], c_out, P_out, ws[5], ws[7], ws[4], ws[22], ws[6])
        return
    if same_group:
        model = models[0]
        s, p = ws[14], ws[15]
        _mix_on_group(model, S, Pp, mu, s, p, ws[0])
        _to_common(model, s, p, c_out, P_out, ws[5], ws[7], ws[4], ws[22], ws[6])
        return
    _all_common(models, S, Pp, ws)
    C, PC, miss = ws[8], ws[9], ws[10]
    # a coordinate some modes lack: filled with the probability-weighted mean/variance of the modes that carry it
    fill_c, fill_P = ws[18], ws[19]
    for a in range(6):
        fill_c[a] = 0.0
        for b in range(6):
            fill_P[a, b] = 0.0
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
    mix_common(C, PC, miss, mu, fill_c, fill_P, c_out, P_out, ws[20], ws[21], ws[6])


@nb.njit(cache=True)
def _mix(models, S, Pp, mu, PI, same_group, cbar, ws):
    """The IMM's interaction step, in place: every mode restarts from its mixed estimate; cbar_j = Σ_i PI_ij μ_i."""
    M = models.shape[0]
    for j in range(M):
        cbar[j] = 0.0
        for i in range(M):
            cbar[j] += PI[i, j] * mu[i]
    if M == 1:
        return
    W = ws[11]  # W[j, i] = w_{i|j}
    for j in range(M):
        for i in range(M):
            W[j, i] = PI[i, j] * mu[i] / cbar[j] if cbar[j] > 0.0 else (1.0 if i == j else 0.0)
    S_new, P_new, P = ws[12], ws[13], ws[3]
    if same_group:
        model = models[0]
        n = D.N_TANGENT[model]
        for j in range(M):
            _mix_on_group(model, S, Pp, W[j], S_new[j], P_new[j], ws[0])
    else:
        _all_common(models, S, Pp, ws)
        C, PC, miss = ws[8], ws[9], ws[10]
        c, Pc, x, J, row = ws[18], ws[19], ws[5], ws[7], ws[4]
        # (ws[7] is 6 × NMAX; J of common_jacobian is n × 6: use ws[2] (NMAX × NMAX) instead)
        J = ws[2]
        for j in range(M):
            mix_common(C, PC, miss, W[j], C[j], PC[j], c, Pc, ws[20], ws[21], ws[6])
            model = models[j]
            n = D.N_TANGENT[model]
            if math.hypot(c[3], c[4]) >= SPEED_FLOOR:  # generated, straight line: the state and J Pc Jᵀ packed
                D.state_of_common(model, c, Pc, S_new[j], P_new[j])
                continue
            D.common_to_state_into(model, c, x)
            D.state_from_physical_into(model, x, S_new[j])
            c[3] = SPEED_FLOOR  # the Jacobian of a heading of motion is singular at speed 0
            D.common_jacobian_into(model, c, J)
            _congruence_dense(J, n, Pc, 6, row, P)
            pack_from(P, n, P_new[j])
    for j in range(M):
        model = models[j]
        for k in range(D.N_INTERNAL[model]):
            S[j, k] = S_new[j, k]
        n = D.N_TANGENT[model]
        for k in range(n * (n + 1) // 2):
            Pp[j, k] = P_new[j, k]


@nb.njit(cache=True)
def imm_predict(models, S, Pp, mu, PI, Q, dt, same_group, ws):
    """Mixing, then every mode's prediction by dt, in place; mu becomes the predicted probabilities Σ_i PI_ij μ_i.

    Q (M, q): the modes' process-noise stds; ws: ``workspace(M)``.
    """
    cbar = ws[16]
    _mix(models, S, Pp, mu, PI, same_group, cbar, ws)
    for j in range(models.shape[0]):
        D.predict(models[j], S[j], Pp[j], dt, Q[j])
        mu[j] = cbar[j]


@nb.njit(cache=True)
def imm_update(models, S, Pp, mu, r, z, meas_pose, nis_out, ws):
    """Every mode's update with z, in place, and μ_j ∝ μ_j N(ν_j; 0, S_j); a NaN in z: nothing changes.

    r: the measurement noise stds; nis_out (M,) receives each mode's NIS (NaN when missed). Returns the
    log-likelihood log Σ_j μ_j N_j.
    """
    M = models.shape[0]
    for k in range(z.shape[0]):
        if np.isnan(z[k]):
            for j in range(M):
                nis_out[j] = np.nan
            return np.nan
    loglik, prior = ws[17], ws[16]
    m = z.shape[0]
    for j in range(M):
        sj, pj = S[j], Pp[j]  # one view each (a view costs a reference count)
        if meas_pose:  # log det S at the predicted state (generated innovation_logdet_<meas>), then the update
            logdet = D.innovation_logdet_pose(models[j], sj, pj, r)
            nis = D.update_pose(models[j], sj, pj, z, r)
        else:
            logdet = D.innovation_logdet_position(models[j], sj, pj, r)
            nis = D.update_position(models[j], sj, pj, z, r)
        nis_out[j] = nis
        loglik[j] = -0.5 * (nis + logdet + m * LOG_2PI)
        prior[j] = mu[j]
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
        for j in range(M):
            mu[j] = prior[j]
        return -np.inf
    for j in range(M):
        mu[j] /= tot
    return top + math.log(tot)


@nb.njit(cache=True)
def imm_step(models, S, Pp, mu, PI, Q, r, z, dt, same_group, meas_pose, nis_out, ws):
    """One IMM cycle in place: imm_predict by dt, then imm_update with z (NaN: missed detection)."""
    imm_predict(models, S, Pp, mu, PI, Q, dt, same_group, ws)
    return imm_update(models, S, Pp, mu, r, z, meas_pose, nis_out, ws)


@nb.njit(cache=True)
def imm_run_one(models, S, Pp, mu, PI, Q, r, z, dts, same_group, meas_pose, out_c, out_P, out_mu):
    """Run the IMM over one trajectory z (K, m) with steps dts (K,), from the state (S, Pp, mu) (modified).

    Writes the combined common estimate out_c (K, 6), its covariance out_P (K, 6, 6) when out_P.shape[0] == K,
    and the mode probabilities out_mu (K, M).
    """
    K = z.shape[0]
    M = models.shape[0]
    keep_P = out_P.shape[0] == K
    ws = workspace(M)
    Pc = np.empty((6, 6))
    nis = np.empty(M)
    for k in range(K):
        imm_step(models, S, Pp, mu, PI, Q, r, z[k], dts[k], same_group, meas_pose, nis, ws)
        combined_common(models, S, Pp, mu, same_group, out_c[k], Pc, ws)
        if keep_P:
            out_P[k, :, :] = Pc
        for j in range(M):
            out_mu[k, j] = mu[j]


@nb.njit(cache=True, parallel=True)
def imm_run_batch(models, S0, P0, mu0, PI, Q, r, z, dts, same_group, meas_pose, out_c, out_P, out_mu):
    """imm_run_one over B trajectories in parallel: S0 (B, M, L), P0 (B, M, N), z (B, K, m), dts (B, K)."""
    for b in nb.prange(z.shape[0]):
        S = S0[b].copy()
        Pp = P0[b].copy()
        mu = mu0.copy()
        imm_run_one(models, S, Pp, mu, PI, Q, r, z[b], dts[b], same_group, meas_pose, out_c[b], out_P[b], out_mu[b])
