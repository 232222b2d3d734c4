"""The IMM's loop: mixing, mode-matched steps, mode probabilities and the combined estimate.

GENERATED FILE: DO NOT EDIT.
Source: derive/codegen/templates/imm_*.py.tmpl through derive/codegen/families/imm.py
Regenerate with: lgekf derive      (check freshness with: lgekf derive --check)
"""
import math

import numba as nb
import numpy as np

from . import dispatch_3d as D

__all__ = ['MEASUREMENT_NAMES', 'unpack_into', 'pack_from', 'workspace', 'mix_on_group', 'mix_common', 'combined_common', 'imm_predict', 'imm_step', 'imm_loglik_one', 'imm_run_one', 'imm_update_pose3', 'imm_run_batch_pose3', 'imm_loglik_batch_pose3', 'imm_forward_store_pose3', 'imm_update_position3', 'imm_run_batch_position3', 'imm_loglik_batch_position3', 'imm_forward_store_position3', 'imm_update']

#: the measurements, by index (the IMM's ``meas`` argument)
MEASUREMENT_NAMES = ('pose3', 'position3')


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


LOG_2PI = math.log(2.0 * math.pi)
NMAX = int(np.max(D.N_TANGENT))  # the largest tangent dimension of the registry
LMAX = int(np.max(D.N_INTERNAL))
NPMAX = NMAX * (NMAX + 1) // 2
NC = 12  # the common coordinates of the space (derive/space.py)
NC2 = NC * NC
NW = max(NMAX, NC)  # square scratch matrices hold n × n and n × NC blocks
#: 1.0 at the common coordinates that are angles (``Space.common_angles``): wrapped when mixed, std capped at π
IS_ANGLE = np.array([0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0])
#: the body-frame velocity in c, the forward speed first (``Space.common_velocity``)
VELOCITY = np.array([6, 7, 8])
SPEED_FLOOR = 1e-9  # m/s: conversions' Jacobians are evaluated at least this far from speed 0

# rows of the workspace (module docstring): fixed ones, then blocks of M rows (_r_* give their first row)
_R_DELTA = 0  # the mean iteration's Σ w_i d_i (n)
_R_CBAR = 1  # predicted mode probabilities Σ_i PI_ij μ_i (M)
_R_LOGLIK = 2  # each mode's log N_j (M)
_R_PRIOR = 3  # the probabilities before the update (M)
_R_FILLC = 4  # common coordinates a source lacks: mean (NC)
_R_FILLP = 5  # ... and variance (NC × NC row-major, diagonal used)
_R_CM = 6  # a mixed common mean (NC)
_R_PCM = 7  # its covariance (NC × NC row-major)
_R_D = 8  # a deviation (NC)
_R_SMIX = 9  # the combined estimate on the group: state (L)
_R_PMIX = 10  # ... packed covariance (n(n+1)/2)
_R_MU = 11  # the weights of the combined estimate (M)
_R_Z = 12  # the measurement (m)
_R_MODEL = 13  # the modes' model indices (M, as floats)
_R_MUV = 14  # the mode probabilities μ (M)
_R_R = 15  # the measurement noise stds
_R_NIS = 16  # each mode's NIS of the last update (M)
_R_BLOCKS = 17
_N_BLOCKS = 12


@nb.njit(cache=True, inline="always")
def _r_w(M):
    """First of M rows: W[j, i] = w_{i|j}, the mixing weights into mode j."""
    return _R_BLOCKS


@nb.njit(cache=True, inline="always")
def _r_snew(M):
    """First of M rows: the mixed states."""
    return _R_BLOCKS + M


@nb.njit(cache=True, inline="always")
def _r_pnew(M):
    """First of M rows: the mixed packed covariances."""
    return _R_BLOCKS + 2 * M


@nb.njit(cache=True, inline="always")
def _r_c(M):
    """First of M rows: each mode's common mean (NC)."""
    return _R_BLOCKS + 3 * M


@nb.njit(cache=True, inline="always")
def _r_pc(M):
    """First of M rows: each mode's common covariance (NC × NC row-major)."""
    return _R_BLOCKS + 4 * M


@nb.njit(cache=True, inline="always")
def _r_miss(M):
    """First of M rows: each mode's COMMON_MISSING flags (NC)."""
    return _R_BLOCKS + 5 * M


@nb.njit(cache=True, inline="always")
def _r_ci(M):
    """First of M rows: scratch of mix_common (sources with filled coordinates, NC)."""
    return _R_BLOCKS + 6 * M


@nb.njit(cache=True, inline="always")
def _r_pi(M):
    """First of M rows: scratch of mix_common (their covariances, NC²)."""
    return _R_BLOCKS + 7 * M


@nb.njit(cache=True, inline="always")
def _r_s(M):
    """First of M rows: the modes' internal states (L)."""
    return _R_BLOCKS + 8 * M


@nb.njit(cache=True, inline="always")
def _r_pp(M):
    """First of M rows: the modes' packed covariances."""
    return _R_BLOCKS + 9 * M


@nb.njit(cache=True, inline="always")
def _r_trans(M):
    """First of M rows: the transition matrix, row i = PI[i, :]."""
    return _R_BLOCKS + 10 * M


@nb.njit(cache=True, inline="always")
def _r_q(M):
    """First of M rows: the modes' process-noise stds."""
    return _R_BLOCKS + 11 * M


@nb.njit(cache=True, inline="always")
def _model(ws, j):
    return int(ws[_R_MODEL, j])


@nb.njit(cache=True)
def workspace(M):
    """The workspace of one IMM of M modes: one 2-D float array, a quantity per row (module docstring; no
    allocation and no views inside the step loop)."""
    return np.zeros((_R_BLOCKS + _N_BLOCKS * M, max(NC2, LMAX, NPMAX, M, 8)))


@nb.njit(cache=True)
def _load_modes(ws, models, S, Pp):
    """Model indices, states and packed covariances into the workspace."""
    M = models.shape[0]
    for j in range(M):
        ws[_R_MODEL, j] = models[j]
        for k in range(S.shape[1]):
            ws[_r_s(M) + j, k] = S[j, k]
        for k in range(Pp.shape[1]):
            ws[_r_pp(M) + j, k] = Pp[j, k]


@nb.njit(cache=True)
def _load(ws, models, S, Pp, mu, PI, Q, r):
    """Everything the step reads into the workspace."""
    M = models.shape[0]
    _load_modes(ws, models, S, Pp)
    for j in range(M):
        ws[_R_MUV, j] = mu[j]
        for i in range(M):
            ws[_r_trans(M) + j, i] = PI[j, i]
        for i in range(Q.shape[1]):
            ws[_r_q(M) + j, i] = Q[j, i]
    for i in range(r.shape[0]):
        ws[_R_R, i] = r[i]


@nb.njit(cache=True)
def _store(ws, S, Pp, mu):
    """The states, covariances and probabilities back from the workspace."""
    M = S.shape[0]
    for j in range(M):
        mu[j] = ws[_R_MUV, j]
        for k in range(S.shape[1]):
            S[j, k] = ws[_r_s(M) + j, k]
        for k in range(Pp.shape[1]):
            Pp[j, k] = ws[_r_pp(M) + j, k]


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
    M = S.shape[0]
    for i in range(M):
        ws[_R_MU, i] = w[i]
        ws[_R_MODEL, i] = model
    _load_modes(ws, np.full(M, model), S, Pp)
    it = _mix_on_group(ws, M, model, _R_MU, _R_SMIX, _R_PMIX)
    for k in range(D.N_INTERNAL[model]):
        s_out[k] = ws[_R_SMIX, k]
    unpack_into(ws[_R_PMIX], D.N_TANGENT[model], P_out)
    return it


@nb.njit(cache=True, inline="always")
def _mix_on_group(ws, M, model, rw, rs, rp):
    """mix_on_group of the modes in the workspace with the weights ws[rw, :M], into the state ws[rs] and the
    packed covariance ws[rp] (the generated loop ``mix_on_group_at``: the mean iterated with ``between_add`` and
    ``retract``, then each source's term w_i [Φ(d_i)⁻¹ P_i Φ(d_i)⁻ᵀ + d_i d_iᵀ] from ``mix_transport``, straight
    line, packed in and out; their row variants). Returns the iterations used."""
    return D.mix_on_group_at(model, ws, M, rw, rs, rp, _r_s(M), _r_pp(M), _R_DELTA)


@nb.njit(cache=True, error_model="numpy")
def _to_common(ws, model, js, jp, rc, rP):
    """State ws[js], packed covariance ws[jp] of a model -> common c (ws[rc], NC) and its covariance (ws[rP],
    NC × NC row-major) (A P Aᵀ, generated ``common_of_state``).

    At a speed below SPEED_FLOOR the Jacobian is taken at the state with forward speed SPEED_FLOOR (a heading or
    attitude read off the velocity, CV's, is singular at 0; its variance is then capped by _cap_angles)."""
    D.common_of_state_at(model, ws, js, jp, rc, rP)  # generated, straight line: c and A P Aᵀ at s
    if _speed(ws, rc) < SPEED_FLOOR:
        _to_common_slow(ws, model, js, jp, rc, rP)
    _cap_angles(ws, rc, rP)


@nb.njit(cache=True, inline="always")
def _speed(ws, rc):
    """|v| of the body-frame velocity (the entries VELOCITY) of the common coordinates ws[rc]."""
    acc = 0.0
    for a in VELOCITY:
        acc += ws[rc, a] * ws[rc, a]
    return math.sqrt(acc)


@nb.njit(cache=True)
def _to_common_slow(ws, model, js, jp, rc, rP):
    """_to_common's path below SPEED_FLOOR (rare: allocates its scratch)."""
    n = D.N_TANGENT[model]
    s, p = ws[js].copy(), ws[jp].copy()
    x, A, row = np.empty(NMAX), np.empty((NC, NMAX)), np.empty(NW)
    Pd, ctmp, Pc = np.empty((NW, NW)), np.empty(NC), np.empty((NC, NC))
    D.physical_into(model, s, x)
    D.physical_to_common_into(model, x, ctmp)
    for k in range(NC):
        ws[rc, k] = ctmp[k]
    if _speed(ws, rc) < SPEED_FLOOR:
        for a in VELOCITY:
            ctmp[a] = 0.0
        ctmp[VELOCITY[0]] = SPEED_FLOOR
        D.common_to_state_into(model, ctmp, x)
    D.physical_to_common_jacobian_into(model, x, A)
    unpack_into(p, n, Pd)
    _congruence_dense(A, NC, Pd, n, row, Pc)
    for a in range(NC):
        for b in range(NC):
            ws[rP, NC * a + b] = Pc[a, b]


@nb.njit(cache=True, inline="always")
def _cap_angles(ws, rc, rP):
    """Cap the std of every common angle a (IS_ANGLE; ws[rc, a], covariance ws[rP] NC × NC row-major) at π by
    congruence scaling of its row and column (as the filters' limit_angle_variance): a heading or attitude read off a
    velocity near zero (CV) is unknown, not infinitely uncertain; a non-finite one becomes a = 0, variance π²."""
    for a in range(NC):
        if IS_ANGLE[a] < 0.5:
            continue
        v = ws[rP, (NC + 1) * a]
        if not (np.isfinite(v) and np.isfinite(ws[rc, a])):
            ws[rc, a] = 0.0
            for k in range(NC):
                ws[rP, NC * a + k] = 0.0
                ws[rP, NC * k + a] = 0.0
            ws[rP, (NC + 1) * a] = math.pi * math.pi
        elif v > math.pi * math.pi:
            f = math.pi / math.sqrt(v)
            for k in range(NC):
                ws[rP, NC * a + k] *= f
                ws[rP, NC * k + a] *= f


@nb.njit(cache=True, inline="always")
def _wrap(a):
    return a - 2.0 * math.pi * math.floor((a + math.pi) / (2.0 * math.pi))


@nb.njit(cache=True)
def mix_common(C, PC, miss, w, fill_c, fill_P, c_out, P_out, Ci, Pi, d):
    """Moment-match Σ w_i N(c_i, P_c,i) in the common coordinates (angles wrapped); coordinates k a source does not
    carry (miss[i, k] = 1) take fill_c[k] and the variance fill_P[k, k] (no correlation) for that source.
    Ci (M, NC), Pi (M, NC, NC), d (NC,): scratch. (The IMM's loop runs the same on its workspace rows.)"""
    M = C.shape[0]
    ws = workspace(M)
    for i in range(M):
        ws[_R_MU, i] = w[i]
        for a in range(NC):
            ws[_r_c(M) + i, a] = C[i, a]
            ws[_r_miss(M) + i, a] = miss[i, a]
            for b in range(NC):
                ws[_r_pc(M) + i, NC * a + b] = PC[i, a, b]
    for a in range(NC):
        ws[_R_FILLC, a] = fill_c[a]
        for b in range(NC):
            ws[_R_FILLP, NC * a + b] = fill_P[a, b]
    _mix_common(ws, M, _R_MU, _R_FILLC, _R_FILLP, _R_CM, _R_PCM)
    for a in range(NC):
        c_out[a] = ws[_R_CM, a]
        for b in range(NC):
            P_out[a, b] = ws[_R_PCM, NC * a + b]


@nb.njit(cache=True, error_model="numpy")
def _mix_common(ws, M, rw, rfc, rfp, rc, rP):
    """mix_common on workspace rows: sources c_i, P_c,i, miss_i in the blocks _r_c, _r_pc, _r_miss; weights ws[rw];
    fill mean ws[rfc], fill covariance ws[rfp] (NC × NC row-major, diagonal used); result into ws[rc], ws[rP];
    the angles (IS_ANGLE) averaged as differences wrapped to (−π, π] about the most probable source."""
    rC, rPC, rMS, rCI, rPI = _r_c(M), _r_pc(M), _r_miss(M), _r_ci(M), _r_pi(M)
    best = 0
    for i in range(M):
        if ws[rw, i] > ws[rw, best]:
            best = i
    for i in range(M):
        for a in range(NC):
            ws[rCI + i, a] = ws[rC + i, a]
        for e in range(NC2):
            ws[rPI + i, e] = ws[rPC + i, e]
        for a in range(NC):
            if ws[rMS + i, a] > 0.5:
                ws[rCI + i, a] = ws[rfc, a]
                for b in range(NC):
                    ws[rPI + i, NC * a + b] = 0.0
                    ws[rPI + i, NC * b + a] = 0.0
                ws[rPI + i, (NC + 1) * a] = ws[rfp, (NC + 1) * a]
    for a in range(NC):
        ws[rc, a] = 0.0
    for i in range(M):
        w = ws[rw, i]
        if w == 0.0:
            continue
        for a in range(NC):
            v = ws[rCI + i, a]
            if IS_ANGLE[a] > 0.5:
                ref = ws[rCI + best, a]
                v = ref + _wrap(v - ref)
            ws[rc, a] += w * v
    for e in range(NC2):
        ws[rP, e] = 0.0
    for i in range(M):
        w = ws[rw, i]
        if w == 0.0:
            continue
        for a in range(NC):
            ws[_R_D, a] = ws[rCI + i, a] - ws[rc, a]
            if IS_ANGLE[a] > 0.5:
                ws[_R_D, a] = _wrap(ws[_R_D, a])
        for a in range(NC):
            for b in range(NC):
                ws[rP, NC * a + b] += w * (ws[rPI + i, NC * a + b] + ws[_R_D, a] * ws[_R_D, b])
    for a in range(NC):
        if IS_ANGLE[a] > 0.5:
            ws[rc, a] = _wrap(ws[rc, a])


@nb.njit(cache=True, error_model="numpy")
def _all_common(ws, M):
    """Every mode in the common coordinates: the workspace blocks _r_c (M, NC), _r_pc (M, NC²), _r_miss (M, NC)."""
    for i in range(M):
        model = _model(ws, i)
        _to_common(ws, model, _r_s(M) + i, _r_pp(M) + i, _r_c(M) + i, _r_pc(M) + i)
        for a in range(NC):
            ws[_r_miss(M) + i, a] = D.COMMON_MISSING[model, a]


@nb.njit(cache=True, error_model="numpy")
def _combined(ws, M, same_group):
    """The combined estimate (weights ws[_R_MU]) in the common coordinates into ws[_R_CM], ws[_R_PCM]."""
    if M == 1:
        _to_common(ws, _model(ws, 0), _r_s(M), _r_pp(M), _R_CM, _R_PCM)
        return
    if same_group:
        model = _model(ws, 0)
        _mix_on_group(ws, M, model, _R_MU, _R_SMIX, _R_PMIX)
        _to_common(ws, model, _R_SMIX, _R_PMIX, _R_CM, _R_PCM)
        return
    _all_common(ws, M)
    rC, rPC, rMS = _r_c(M), _r_pc(M), _r_miss(M)
    # a coordinate some modes lack: filled with the probability-weighted mean/variance of the modes that carry it
    for e in range(NC2):
        ws[_R_FILLP, e] = 0.0
    for a in range(NC):
        ws[_R_FILLC, a] = 0.0
        tot = 0.0
        for i in range(M):
            if ws[rMS + i, a] < 0.5:
                tot += ws[_R_MU, i]
        if tot > 0.0:
            for i in range(M):
                if ws[rMS + i, a] < 0.5:
                    ws[_R_FILLC, a] += ws[_R_MU, i] / tot * ws[rC + i, a]
            for i in range(M):
                if ws[rMS + i, a] < 0.5:
                    e = ws[rC + i, a] - ws[_R_FILLC, a]
                    ws[_R_FILLP, (NC + 1) * a] += ws[_R_MU, i] / tot * (ws[rPC + i, (NC + 1) * a] + e * e)
    _mix_common(ws, M, _R_MU, _R_FILLC, _R_FILLP, _R_CM, _R_PCM)


@nb.njit(cache=True)
def combined_common(models, S, Pp, mu, same_group, c_out, P_out, ws):
    """The IMM's combined estimate in the common coordinates: c (NC,), P_c (NC, NC)."""
    _load_modes(ws, models, S, Pp)
    for i in range(models.shape[0]):
        ws[_R_MU, i] = mu[i]
    _combined(ws, models.shape[0], same_group)
    for a in range(NC):
        c_out[a] = ws[_R_CM, a]
        for b in range(NC):
            P_out[a, b] = ws[_R_PCM, NC * a + b]


@nb.njit(cache=True)
def _state_of_common_slow(ws, model, rc, rP, rs, rp):
    """The mixed common Gaussian ws[rc], ws[rP] below SPEED_FLOOR to a mode's state ws[rs] and packed covariance
    ws[rp] (rare: allocates its scratch)."""
    n = D.N_TANGENT[model]
    c, Pc, x = np.empty(NC), np.empty((NC, NC)), np.empty(NMAX)
    J, P, row = np.empty((NW, NW)), np.empty((NW, NW)), np.empty(NW)
    s, p = np.empty(LMAX), np.empty(NPMAX)
    for a in range(NC):
        c[a] = ws[rc, a]
        for b in range(NC):
            Pc[a, b] = ws[rP, NC * a + b]
    D.common_to_state_into(model, c, x)
    D.state_from_physical_into(model, x, s)
    c[VELOCITY[0]] = SPEED_FLOOR  # the Jacobian of a heading of motion is singular at speed 0
    D.common_jacobian_into(model, c, J)
    _congruence_dense(J, n, Pc, NC, row, P)
    pack_from(P, n, p)
    for k in range(D.N_INTERNAL[model]):
        ws[rs, k] = s[k]
    for k in range(n * (n + 1) // 2):
        ws[rp, k] = p[k]


@nb.njit(cache=True, error_model="numpy")
def _mix_rows(ws, M, same_group):
    """The IMM's interaction step on the workspace: every mode restarts from its mixed estimate; the predicted
    probabilities cbar_j = Σ_i PI_ij μ_i into ws[_R_CBAR]."""
    rT = _r_trans(M)
    for j in range(M):
        cb = 0.0
        for i in range(M):
            cb += ws[rT + i, j] * ws[_R_MUV, i]
        ws[_R_CBAR, j] = cb
    if M == 1:
        return
    rW, rSn, rPn = _r_w(M), _r_snew(M), _r_pnew(M)
    for j in range(M):
        cb = ws[_R_CBAR, j]
        for i in range(M):
            ws[rW + j, i] = ws[rT + i, j] * ws[_R_MUV, i] / cb if cb > 0.0 else (1.0 if i == j else 0.0)
    if same_group:
        model = _model(ws, 0)
        for j in range(M):
            _mix_on_group(ws, M, model, rW + j, rSn + j, rPn + j)
    else:
        _all_common(ws, M)
        for j in range(M):
            _mix_common(ws, M, rW + j, _r_c(M) + j, _r_pc(M) + j, _R_CM, _R_PCM)
            model = _model(ws, j)
            if _speed(ws, _R_CM) >= SPEED_FLOOR:  # generated, straight line: state, J Pc Jᵀ
                D.state_of_common_at(model, ws, _R_CM, _R_PCM, rSn + j, rPn + j)
            else:
                _state_of_common_slow(ws, model, _R_CM, _R_PCM, rSn + j, rPn + j)
    rS, rPp = _r_s(M), _r_pp(M)
    for j in range(M):
        model = _model(ws, j)
        for k in range(D.N_INTERNAL[model]):
            ws[rS + j, k] = ws[rSn + j, k]
        n = D.N_TANGENT[model]
        for k in range(n * (n + 1) // 2):
            ws[rPp + j, k] = ws[rPn + j, k]


@nb.njit(cache=True)
def _mix(models, S, Pp, mu, PI, same_group, cbar, ws):
    """The IMM's interaction step, in place: every mode restarts from its mixed estimate; cbar_j = Σ_i PI_ij μ_i."""
    M = models.shape[0]
    _load(ws, models, S, Pp, mu, PI, np.zeros((M, 1)), np.zeros(1))
    _mix_rows(ws, M, same_group)
    _store(ws, S, Pp, mu)
    for j in range(M):
        cbar[j] = ws[_R_CBAR, j]


@nb.njit(cache=True)
def _predict_modes(ws, M, dt):
    """Every mode's prediction by dt, in place in the workspace (views: used for missed detections only)."""
    for j in range(M):
        D.predict(_model(ws, j), ws[_r_s(M) + j], ws[_r_pp(M) + j], dt, ws[_r_q(M) + j])


@nb.njit(cache=True)
def imm_predict(models, S, Pp, mu, PI, Q, dt, same_group, ws):
    """Mixing, then every mode's prediction by dt, in place; mu becomes the predicted probabilities Σ_i PI_ij μ_i.

    Q (M, q): the modes' process-noise stds; ws: ``workspace(M)``.
    """
    M = models.shape[0]
    _load(ws, models, S, Pp, mu, PI, Q, np.zeros(1))
    _mix_rows(ws, M, same_group)
    _predict_modes(ws, M, dt)
    for j in range(M):
        ws[_R_MUV, j] = ws[_R_CBAR, j]
    _store(ws, S, Pp, mu)


@nb.njit(cache=True, error_model="numpy")
def _posterior(ws, M):
    """μ_j ∝ μ_j exp(loglik_j) (ws[_R_MUV], ws[_R_LOGLIK]); returns log Σ_j μ_j N_j, or −inf (and μ back to
    ws[_R_PRIOR]) when no mode explains the measurement."""
    top = -np.inf
    for j in range(M):
        if ws[_R_MUV, j] > 0.0 and ws[_R_LOGLIK, j] > top:
            top = ws[_R_LOGLIK, j]
    tot = 0.0
    for j in range(M):
        ll = ws[_R_LOGLIK, j]
        v = ws[_R_MUV, j] * math.exp(ll - top) if np.isfinite(ll) else 0.0
        ws[_R_MUV, j] = v
        tot += v
    if not (tot > 0.0) or not np.isfinite(tot):
        for j in range(M):
            ws[_R_MUV, j] = ws[_R_PRIOR, j]
        return -np.inf
    for j in range(M):
        ws[_R_MUV, j] /= tot
    return top + math.log(tot)


@nb.njit(cache=True, error_model="numpy")
def _mix_or_predict(ws, M, m, dt, same_group):
    """The step's start: mixing, μ ← the predicted probabilities; for a missed detection (NaN in ws[_R_Z, :m]) also
    each mode's prediction and NaN NIS. Returns whether it was missed."""
    missed = False
    for k in range(m):
        if np.isnan(ws[_R_Z, k]):
            missed = True
    _mix_rows(ws, M, same_group)
    for j in range(M):
        ws[_R_MUV, j] = ws[_R_CBAR, j]
    if missed:
        _predict_modes(ws, M, dt)
        for j in range(M):
            ws[_R_NIS, j] = np.nan
    return missed


@nb.njit(cache=True, error_model="numpy")
def _step_rows(ws, M, m, dt, same_group, meas):
    """imm_step on the workspace, measurement ws[_R_Z, :m]: mixing, each mode's fused step, the mode
    probabilities; returns the step log-likelihood (NaN when missed, −inf when no mode explains z)."""
    if _mix_or_predict(ws, M, m, dt, same_group):
        return np.nan
    _modes(ws, M, m, dt, meas)
    return _posterior(ws, M)


@nb.njit(cache=True)
def imm_step(models, S, Pp, mu, PI, Q, r, z, dt, same_group, meas, nis_out, ws):
    """One IMM cycle in place: imm_predict by dt, then imm_update with z (NaN: missed detection); returns the step's
    log-likelihood log Σ_j μ_j N_j (NaN for a missed detection, −inf when no mode explains z).

    Each mode's prediction and update run as the filter's fused step (module docstring); equal to imm_predict
    followed by imm_update to rounding."""
    M = models.shape[0]
    _load(ws, models, S, Pp, mu, PI, Q, r)
    m = z.shape[0]
    for k in range(m):
        ws[_R_Z, k] = z[k]
    ll = _step_rows(ws, M, m, dt, same_group, meas)
    _store(ws, S, Pp, mu)
    for j in range(M):
        nis_out[j] = ws[_R_NIS, j]
    return ll


@nb.njit(cache=True)
def imm_loglik_one(models, S, Pp, mu, PI, Q, r, z, dts, start, stop, same_group, meas):
    """Σ of imm_step's log-likelihood over the steps k in [start, stop) of one track z (K, m), dts (K,), run from
    step 0 from the state (S, Pp, mu) (modified); missed detections (NaN) are not counted. The same steps as
    calling imm_step for k < stop, on a workspace loaded once. Returns (the sum, the steps counted); the sum is
    −inf once no mode explains a measurement."""
    M = models.shape[0]
    m = z.shape[1]
    ws = workspace(M)
    _load(ws, models, S, Pp, mu, PI, Q, r)
    tot = 0.0
    n = 0
    for k in range(stop):
        for i in range(m):
            ws[_R_Z, i] = z[k, i]
        v = _step_rows(ws, M, m, dts[k], same_group, meas)
        if k >= start and not np.isnan(v):
            tot += v
            n += 1
    _store(ws, S, Pp, mu)
    return tot, n


@nb.njit(cache=True, error_model="numpy")
def _outputs(ws, M, k, same_group, out_c, out_P, out_mu):
    """After step k: the mode probabilities and the combined estimate (its covariance when out_P has K rows)."""
    for j in range(M):
        ws[_R_MU, j] = ws[_R_MUV, j]
        out_mu[k, j] = ws[_R_MUV, j]
    _combined(ws, M, same_group)
    for a in range(NC):
        out_c[k, a] = ws[_R_CM, a]
    if out_P.shape[0] > k:
        for a in range(NC):
            for b in range(NC):
                out_P[k, a, b] = ws[_R_PCM, NC * a + b]


@nb.njit(cache=True)
def imm_run_one(models, S, Pp, mu, PI, Q, r, z, dts, same_group, meas, out_c, out_P, out_mu):
    """Run the IMM over one trajectory z (K, m) with steps dts (K,), from the state (S, Pp, mu) (modified).

    Writes the combined common estimate out_c (K, NC), its covariance out_P (K, NC, NC) when out_P.shape[0] == K,
    and the mode probabilities out_mu (K, M).
    """
    M = models.shape[0]
    ws = workspace(M)
    _load(ws, models, S, Pp, mu, PI, Q, r)
    _run(ws, M, z, dts, same_group, meas, out_c, out_P, out_mu)
    _store(ws, S, Pp, mu)


@nb.njit(cache=True)
def imm_update_pose3(models, S, Pp, mu, r, z, nis_out, ws):
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
    m = z.shape[0]
    for j in range(M):
        sj, pj = S[j], Pp[j]  # one view each (a view costs a reference count)
        # log det S at the predicted state (generated innovation_logdet_pose3), then the update
        logdet = D.innovation_logdet_pose3(models[j], sj, pj, r)
        nis = D.update_pose3(models[j], sj, pj, z, r)
        nis_out[j] = nis
        ws[_R_LOGLIK, j] = -0.5 * (nis + logdet + m * LOG_2PI)
        ws[_R_PRIOR, j] = mu[j]
        ws[_R_MUV, j] = mu[j]
    ll = _posterior(ws, M)
    for j in range(M):
        mu[j] = ws[_R_MUV, j]
    return ll


@nb.njit(cache=True)
def _fallback_pose3(ws, model, j, M, m):
    """``update_pose3`` of mode j from its prediction (the fused step's rare FALLBACK: Joseph form, jitter
    repair); views of the workspace."""
    return D.update_pose3(model, ws[_r_s(M) + j], ws[_r_pp(M) + j], ws[_R_Z, :m], ws[_R_R])


@nb.njit(cache=True, error_model="numpy")
def _modes_pose3(ws, M, m, dt):
    """Each mode's fused step ``step_ll_pose3`` (prediction, 1/det S, update; ``update_pose3`` when its LDLᵀ
    test fails) with the measurement ws[_R_Z, :m]; the modes' log-likelihoods into ws[_R_LOGLIK]."""
    rS, rPp, rQ = _r_s(M), _r_pp(M), _r_q(M)
    for j in range(M):
        model = _model(ws, j)
        nis, rdet = D.step_ll_pose3(model, ws, rS + j, rPp + j, dt, rQ + j, _R_Z, _R_R)
        if nis < 0.0:  # FALLBACK: the prediction is in the workspace
            nis = _fallback_pose3(ws, model, j, M, m)
        ws[_R_NIS, j] = nis
        ws[_R_LOGLIK, j] = -0.5 * (nis - math.log(rdet) + m * LOG_2PI)
        ws[_R_PRIOR, j] = ws[_R_MUV, j]


@nb.njit(cache=True, error_model="numpy")
def _run_pose3(ws, M, z, dts, same_group, out_c, out_P, out_mu):
    """The loop of imm_run_one with pose3 measurements, on a loaded workspace (only the pose3 kernels are
    compiled for it, no other measurement's)."""
    m = z.shape[1]
    for k in range(z.shape[0]):
        for i in range(m):
            ws[_R_Z, i] = z[k, i]
        if not _mix_or_predict(ws, M, m, dts[k], same_group):
            _modes_pose3(ws, M, m, dts[k])
            _posterior(ws, M)
        _outputs(ws, M, k, same_group, out_c, out_P, out_mu)


@nb.njit(cache=True, nogil=True)
def imm_run_batch_pose3(models, S0, P0, mu0, PI, Q, r, z, dts, same_group, out_c, out_P, out_mu):
    """imm_run_one over B trajectories, pose3 measurements (compiles only its kernels): S0 (B, M, L), P0 (B, M, N),
    z (B, K, m), dts (B, K). Serial and without the GIL: ``lgekf.estimators.imm.kernels.run_batch`` runs parts of
    the batch on threads (numba's parallel loop would cost about 9 s more to compile)."""
    M = models.shape[0]
    for b in range(z.shape[0]):
        ws = workspace(M)
        _load(ws, models, S0[b], P0[b], mu0, PI, Q, r)
        _run_pose3(ws, M, z[b], dts[b], same_group, out_c[b], out_P[b], out_mu[b])


@nb.njit(cache=True, nogil=True, error_model="numpy")
def imm_loglik_batch_pose3(models, S0, P0, mu0, PI, Q, r, z, dts, lengths, skip, same_group, ll, cnt):
    """imm_loglik_one of each track b with pose3 measurements (only its kernels compile), over its steps k in
    [skip[b], lengths[b]) from the initial mode states S0[b] (M, L), packed covariances P0[b] (M, N) and
    probabilities mu0; z (B, K, m), dts (B, K) padded beyond lengths[b]. Writes ll (B,) (−inf once no mode explains
    a measurement) and cnt (B,), the steps counted. Serial and without the GIL: a caller runs parts of the batch on
    threads (numba's parallel loop would cost about 9 s more to compile)."""
    M = models.shape[0]
    m = z.shape[2]
    for b in range(z.shape[0]):
        ws = workspace(M)  # a fresh one per track, as imm_loglik_one
        _load(ws, models, S0[b], P0[b], mu0, PI, Q, r)
        tot = 0.0
        n = 0
        for k in range(lengths[b]):
            for i in range(m):
                ws[_R_Z, i] = z[b, k, i]
            if _mix_or_predict(ws, M, m, dts[b, k], same_group):
                continue
            _modes_pose3(ws, M, m, dts[b, k])
            v = _posterior(ws, M)
            if k >= skip[b] and not np.isnan(v):
                tot += v
                n += 1
        ll[b] = tot
        cnt[b] = n


@nb.njit(cache=True)
def imm_forward_store_pose3(models, S, Pp, mu, PI, Q, r, z, dts, same_group, S_mix, P_mix, S_pred, P_pred, S_filt,
                      P_filt, mu_pred, mu_filt):
    """The IMM over one trajectory z (K, m) of pose3 measurements, from (S, Pp, mu) (modified), keeping every step
    (the smoother's forward pass, lgekf.estimators.imm.smoother): S_mix/P_mix (K, M, ·) the mixed estimates the
    prediction to step k started from (at step k-1), S_pred/P_pred the predictions, S_filt/P_filt the posteriors,
    mu_pred/mu_filt (K, M) the predicted and posterior mode probabilities."""
    K = z.shape[0]
    M = models.shape[0]
    ws = workspace(M)
    nis = np.empty(M)
    cbar = np.empty(M)
    for k in range(K):
        _mix(models, S, Pp, mu, PI, same_group, cbar, ws)
        S_mix[k] = S
        P_mix[k] = Pp
        for j in range(M):
            D.predict(models[j], S[j], Pp[j], dts[k], Q[j])
            mu[j] = cbar[j]
        S_pred[k] = S
        P_pred[k] = Pp
        mu_pred[k] = mu
        imm_update_pose3(models, S, Pp, mu, r, z[k], nis, ws)
        S_filt[k] = S
        P_filt[k] = Pp
        mu_filt[k] = mu


@nb.njit(cache=True)
def imm_update_position3(models, S, Pp, mu, r, z, nis_out, ws):
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
    m = z.shape[0]
    for j in range(M):
        sj, pj = S[j], Pp[j]  # one view each (a view costs a reference count)
        # log det S at the predicted state (generated innovation_logdet_position3), then the update
        logdet = D.innovation_logdet_position3(models[j], sj, pj, r)
        nis = D.update_position3(models[j], sj, pj, z, r)
        nis_out[j] = nis
        ws[_R_LOGLIK, j] = -0.5 * (nis + logdet + m * LOG_2PI)
        ws[_R_PRIOR, j] = mu[j]
        ws[_R_MUV, j] = mu[j]
    ll = _posterior(ws, M)
    for j in range(M):
        mu[j] = ws[_R_MUV, j]
    return ll


@nb.njit(cache=True)
def _fallback_position3(ws, model, j, M, m):
    """``update_position3`` of mode j from its prediction (the fused step's rare FALLBACK: Joseph form, jitter
    repair); views of the workspace."""
    return D.update_position3(model, ws[_r_s(M) + j], ws[_r_pp(M) + j], ws[_R_Z, :m], ws[_R_R])


@nb.njit(cache=True, error_model="numpy")
def _modes_position3(ws, M, m, dt):
    """Each mode's fused step ``step_ll_position3`` (prediction, 1/det S, update; ``update_position3`` when its LDLᵀ
    test fails) with the measurement ws[_R_Z, :m]; the modes' log-likelihoods into ws[_R_LOGLIK]."""
    rS, rPp, rQ = _r_s(M), _r_pp(M), _r_q(M)
    for j in range(M):
        model = _model(ws, j)
        nis, rdet = D.step_ll_position3(model, ws, rS + j, rPp + j, dt, rQ + j, _R_Z, _R_R)
        if nis < 0.0:  # FALLBACK: the prediction is in the workspace
            nis = _fallback_position3(ws, model, j, M, m)
        ws[_R_NIS, j] = nis
        ws[_R_LOGLIK, j] = -0.5 * (nis - math.log(rdet) + m * LOG_2PI)
        ws[_R_PRIOR, j] = ws[_R_MUV, j]


@nb.njit(cache=True, error_model="numpy")
def _run_position3(ws, M, z, dts, same_group, out_c, out_P, out_mu):
    """The loop of imm_run_one with position3 measurements, on a loaded workspace (only the position3 kernels are
    compiled for it, no other measurement's)."""
    m = z.shape[1]
    for k in range(z.shape[0]):
        for i in range(m):
            ws[_R_Z, i] = z[k, i]
        if not _mix_or_predict(ws, M, m, dts[k], same_group):
            _modes_position3(ws, M, m, dts[k])
            _posterior(ws, M)
        _outputs(ws, M, k, same_group, out_c, out_P, out_mu)


@nb.njit(cache=True, nogil=True)
def imm_run_batch_position3(models, S0, P0, mu0, PI, Q, r, z, dts, same_group, out_c, out_P, out_mu):
    """imm_run_one over B trajectories, position3 measurements (compiles only its kernels): S0 (B, M, L), P0 (B, M, N),
    z (B, K, m), dts (B, K). Serial and without the GIL: ``lgekf.estimators.imm.kernels.run_batch`` runs parts of
    the batch on threads (numba's parallel loop would cost about 9 s more to compile)."""
    M = models.shape[0]
    for b in range(z.shape[0]):
        ws = workspace(M)
        _load(ws, models, S0[b], P0[b], mu0, PI, Q, r)
        _run_position3(ws, M, z[b], dts[b], same_group, out_c[b], out_P[b], out_mu[b])


@nb.njit(cache=True, nogil=True, error_model="numpy")
def imm_loglik_batch_position3(models, S0, P0, mu0, PI, Q, r, z, dts, lengths, skip, same_group, ll, cnt):
    """imm_loglik_one of each track b with position3 measurements (only its kernels compile), over its steps k in
    [skip[b], lengths[b]) from the initial mode states S0[b] (M, L), packed covariances P0[b] (M, N) and
    probabilities mu0; z (B, K, m), dts (B, K) padded beyond lengths[b]. Writes ll (B,) (−inf once no mode explains
    a measurement) and cnt (B,), the steps counted. Serial and without the GIL: a caller runs parts of the batch on
    threads (numba's parallel loop would cost about 9 s more to compile)."""
    M = models.shape[0]
    m = z.shape[2]
    for b in range(z.shape[0]):
        ws = workspace(M)  # a fresh one per track, as imm_loglik_one
        _load(ws, models, S0[b], P0[b], mu0, PI, Q, r)
        tot = 0.0
        n = 0
        for k in range(lengths[b]):
            for i in range(m):
                ws[_R_Z, i] = z[b, k, i]
            if _mix_or_predict(ws, M, m, dts[b, k], same_group):
                continue
            _modes_position3(ws, M, m, dts[b, k])
            v = _posterior(ws, M)
            if k >= skip[b] and not np.isnan(v):
                tot += v
                n += 1
        ll[b] = tot
        cnt[b] = n


@nb.njit(cache=True)
def imm_forward_store_position3(models, S, Pp, mu, PI, Q, r, z, dts, same_group, S_mix, P_mix, S_pred, P_pred, S_filt,
                      P_filt, mu_pred, mu_filt):
    """The IMM over one trajectory z (K, m) of position3 measurements, from (S, Pp, mu) (modified), keeping every step
    (the smoother's forward pass, lgekf.estimators.imm.smoother): S_mix/P_mix (K, M, ·) the mixed estimates the
    prediction to step k started from (at step k-1), S_pred/P_pred the predictions, S_filt/P_filt the posteriors,
    mu_pred/mu_filt (K, M) the predicted and posterior mode probabilities."""
    K = z.shape[0]
    M = models.shape[0]
    ws = workspace(M)
    nis = np.empty(M)
    cbar = np.empty(M)
    for k in range(K):
        _mix(models, S, Pp, mu, PI, same_group, cbar, ws)
        S_mix[k] = S
        P_mix[k] = Pp
        for j in range(M):
            D.predict(models[j], S[j], Pp[j], dts[k], Q[j])
            mu[j] = cbar[j]
        S_pred[k] = S
        P_pred[k] = Pp
        mu_pred[k] = mu
        imm_update_position3(models, S, Pp, mu, r, z[k], nis, ws)
        S_filt[k] = S
        P_filt[k] = Pp
        mu_filt[k] = mu


@nb.njit(cache=True, inline="always")
def imm_update(models, S, Pp, mu, r, z, meas, nis_out, ws):
    """``imm_update_{meas}`` of the measurement MEASUREMENT_NAMES[meas] (derive/codegen/families/imm.py)."""
    if meas == 0:
        return imm_update_pose3(models, S, Pp, mu, r, z, nis_out, ws)
    else:
        return imm_update_position3(models, S, Pp, mu, r, z, nis_out, ws)


@nb.njit(cache=True, inline="always")
def _modes(ws, M, m, dt, meas):
    """``_modes_{meas}`` of the measurement MEASUREMENT_NAMES[meas] (derive/codegen/families/imm.py)."""
    if meas == 0:
        _modes_pose3(ws, M, m, dt)
    else:
        _modes_position3(ws, M, m, dt)


@nb.njit(cache=True, inline="always")
def _run(ws, M, z, dts, same_group, meas, out_c, out_P, out_mu):
    """``_run_{meas}`` of the measurement MEASUREMENT_NAMES[meas] (derive/codegen/families/imm.py)."""
    if meas == 0:
        _run_pose3(ws, M, z, dts, same_group, out_c, out_P, out_mu)
    else:
        _run_position3(ws, M, z, dts, same_group, out_c, out_P, out_mu)
