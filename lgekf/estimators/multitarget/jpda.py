"""Joint probabilistic data association: the marginal probabilities that track i produced detection j
when tracks share detections (every detection from at most one track, every track at most one
detection).

Input are the weights of a joint event's factors (``lgekf.estimators.multitarget.association.association_weights``):
w0_i (track i undetected, or not existing) and W_ij (track i detected as j, gated pairs only); a joint
event θ has weight Π_i w_{i,θ(i)} and

    p_ij = Σ_{θ: θ(i) = j} Π_k w_{k,θ(k)} / Σ_θ Π_k w_{k,θ(k)},   p_i0 likewise with θ(i) = 0.

Tracks are split into clusters (connected components of "gate the same detection"); events of
different clusters are independent, so the marginals are computed per cluster:

* **exact** enumeration of every feasible joint event (depth-first, each track's options "missed" or an
  unused gated detection) when the cluster has at most ``max_events`` events by the bound Π_i (1 + n_i),
  n_i the detections in track i's gate;
  with ``star`` (JPDA*, Blom & Bloem 2000) only the most probable of the events that detect the same tracks with the
  same detections enters the sums (``exact_cluster_marginals``: against track coalescence);
* otherwise the **loopy belief propagation** approximation of Williams & Lau ("Approximate evaluation
  of marginal association probabilities with belief propagation", IEEE TAES 50(4), 2014): with
  ψ_ij = W_ij / w0_i, messages μ_{i→j} = ψ_ij / (1 + Σ_{j'≠j} ψ_ij' ν_{j'→i}) and
  ν_{j→i} = 1 / (1 + Σ_{i'≠i} μ_{i'→j}) are iterated to convergence; p_ij ∝ ψ_ij ν_{j→i}, p_i0 ∝ 1.
  It is exact on trees (clusters without cycles); on 20 random dense 5 × 5 clusters of the tests its
  marginals are off by at most 0.059 (median 0.035); its cost is linear in the gated pairs per iteration.
"""

from __future__ import annotations

import numba as nb
import numpy as np

__all__ = ["jpda_marginals", "cluster_labels", "exact_cluster_marginals", "lbp_cluster_marginals", "MAX_EVENTS"]

MAX_EVENTS = 5000  # clusters with more joint events (by the bound Π(1 + n_i)) use loopy belief propagation


@nb.njit(cache=True)
def _find(parent, i):
    while parent[i] != i:
        parent[i] = parent[parent[i]]
        i = parent[i]
    return i


@nb.njit(cache=True)
def cluster_labels(gated, live):
    """Cluster label (its smallest track index) of every live track, -1 for dead rows: tracks are in one
    cluster when a chain of shared gated detections links them."""
    N, M = gated.shape
    parent = np.arange(N)
    for j in range(M):
        first = -1
        for i in range(N):
            if live[i] and gated[i, j]:
                if first < 0:
                    first = i
                else:
                    a = _find(parent, first)
                    b = _find(parent, i)
                    if a != b:
                        if a < b:
                            parent[b] = a
                        else:
                            parent[a] = b
    out = np.full(N, -1)
    for i in range(N):
        if live[i]:
            out[i] = _find(parent, i)
    return out


@nb.njit(cache=True)
def _event_key(choice, opt, nt):
    """(detected tracks, used detections) of a joint event as two bit masks (nt, detections < 63)."""
    tmask = 0
    dmask = 0
    for k in range(nt):
        if choice[k] >= 1:
            tmask |= 1 << k
            dmask |= 1 << opt[k, choice[k] - 1]
    return tmask, dmask


@nb.njit(cache=True)
def _enumerate_events(sw0, sW, opt, nopt, mode, best, acc0, acc):
    """Depth-first over every feasible joint event of a cluster (each track "missed" or an unused gated detection),
    with the event weight v = Π_k w_{k,θ(k)}; returns Σ v over the events counted.

    ``best`` None: every event counts (JPDA; numba prunes the JPDA* branch from that specialisation, so plain JPDA
    allocates no dict). With a dict, mode 1: record in ``best`` the largest weight of each (detected tracks, used
    detections) key, count nothing; mode 2: count only the event of largest weight of its key (JPDA*; the first of
    equal ones), using the ``best`` of mode 1."""
    nt, nm = sW.shape
    choice = np.full(nt, -1)  # -1: not started; 0: missed; k >= 1: option k - 1
    used = np.zeros(nm, dtype=np.bool_)
    pw = np.ones(nt + 1)
    total = 0.0
    depth = 0
    while depth >= 0:
        i = depth
        if choice[i] >= 1:
            used[opt[i, choice[i] - 1]] = False
        choice[i] += 1
        while choice[i] >= 1 and choice[i] <= nopt[i] and used[opt[i, choice[i] - 1]]:
            choice[i] += 1
        if choice[i] > nopt[i]:
            choice[i] = -1
            depth -= 1
            continue
        if choice[i] == 0:
            w = sw0[i]
        else:
            j = opt[i, choice[i] - 1]
            w = sW[i, j]
            used[j] = True
        pw[i + 1] = pw[i] * w
        if i == nt - 1:
            v = pw[nt]
            if best is not None:
                key = _event_key(choice, opt, nt)
                if mode == 1:
                    if key not in best or v > best[key]:
                        best[key] = v
                    continue
                if v != best[key]:
                    continue
                best[key] = np.inf  # taken: an equal event of the same key does not count again
            total += v
            for k in range(nt):
                if choice[k] == 0:
                    acc0[k] += v
                else:
                    acc[k, opt[k, choice[k] - 1]] += v
        else:
            depth += 1
            choice[depth] = -1
    return total


@nb.njit(cache=True)
def exact_cluster_marginals(w0, W, gated, p0, P, star=False):
    """Exact marginals of one cluster by enumerating every feasible joint event.

    w0 (nt,), W (nt, nm), gated (nt, nm) bool; writes p0 (nt,) and P (nt, nm). Each track's weights are
    scaled by their maximum first (the marginals do not change: every event has one factor per track).

    ``star``: JPDA* (Blom & Bloem, "Probabilistic data association avoiding track coalescence", IEEE TAC 45(2),
    2000): of the joint events that detect the same tracks with the same detections (permutations of one
    another), only the most probable one enters the sums. When two tracks follow close targets, JPDA weighs
    "track 1 took z_a, track 2 took z_b" and the swapped event alike and pulls both tracks to the middle
    (coalescence); JPDA* keeps the better of the two. Needs fewer than 63 tracks and detections in the cluster
    (bit masks); beyond, plain JPDA. Returns whether the JPDA* rule was applied."""
    nt, nm = W.shape
    opt = np.full((nt, nm), -1)
    nopt = np.zeros(nt, dtype=np.int64)
    sw0 = np.empty(nt)
    sW = np.zeros((nt, nm))
    for i in range(nt):
        big = w0[i]
        for j in range(nm):
            if gated[i, j] and W[i, j] > big:
                big = W[i, j]
        if big <= 0.0:
            big = 1.0
        sw0[i] = w0[i] / big
        for j in range(nm):
            if gated[i, j]:
                sW[i, j] = W[i, j] / big
                opt[i, nopt[i]] = j
                nopt[i] += 1
    acc0 = np.zeros(nt)
    acc = np.zeros((nt, nm))
    applied = star and nt < 63 and nm < 63
    if applied:
        best = {(0, 0): 0.0}
        _enumerate_events(sw0, sW, opt, nopt, 1, best, acc0, acc)
        total = _enumerate_events(sw0, sW, opt, nopt, 2, best, acc0, acc)
    else:
        total = _enumerate_events(sw0, sW, opt, nopt, 0, None, acc0, acc)
    for i in range(nt):
        p0[i] = acc0[i] / total
        for j in range(nm):
            P[i, j] = acc[i, j] / total
    return applied


@nb.njit(cache=True)
def lbp_cluster_marginals(w0, W, gated, p0, P, max_iter=200, tol=1e-9):
    """Approximate marginals of one cluster by loopy belief propagation (Williams & Lau 2014, see the module
    docstring); same arguments as ``exact_cluster_marginals``. Returns the iterations used."""
    nt, nm = W.shape
    psi = np.zeros((nt, nm))
    for i in range(nt):
        for j in range(nm):
            if gated[i, j]:
                psi[i, j] = W[i, j] / w0[i]
    nu = np.ones((nt, nm))  # ν_{j→i}
    mu = np.zeros((nt, nm))  # μ_{i→j}
    it = 0
    for it in range(max_iter):
        for i in range(nt):
            s = 1.0
            for j in range(nm):
                s += psi[i, j] * nu[i, j]
            for j in range(nm):
                if psi[i, j] > 0.0:
                    mu[i, j] = psi[i, j] / (s - psi[i, j] * nu[i, j])
        change = 0.0
        for j in range(nm):
            s = 1.0
            for i in range(nt):
                s += mu[i, j]
            for i in range(nt):
                if psi[i, j] > 0.0:
                    new = 1.0 / (s - mu[i, j])
                    d = abs(new - nu[i, j])
                    if d > change:
                        change = d
                    nu[i, j] = new
        if change < tol:
            break
    for i in range(nt):
        s = 1.0
        for j in range(nm):
            s += psi[i, j] * nu[i, j]
        p0[i] = 1.0 / s
        for j in range(nm):
            P[i, j] = psi[i, j] * nu[i, j] / s
    return it + 1


@nb.njit(cache=True)
def jpda_marginals(w0, W, gated, live, max_events, p0, P, exact, star=False):
    """JPDA marginals of every live track: p0 (N,) missed, P (N, M) detection j; exact[i] tells whether
    track i's cluster was enumerated exactly (else loopy belief propagation, which has no JPDA* form: ``star``
    applies to the enumerated clusters). ``star``: JPDA* (``exact_cluster_marginals``). Returns the cluster
    labels."""
    N, M = W.shape
    labels = cluster_labels(gated, live)
    for i in range(N):
        for j in range(M):
            P[i, j] = 0.0
        p0[i] = 1.0
        exact[i] = True
    done = np.zeros(N, dtype=np.bool_)
    for root in range(N):
        if labels[root] != root or done[root]:
            continue
        members = np.flatnonzero(labels == root)
        nt = members.shape[0]
        done[root] = True
        colmask = np.zeros(M, dtype=np.bool_)
        bound = 1.0
        for a in range(nt):
            ni = 0
            for j in range(M):
                if gated[members[a], j]:
                    colmask[j] = True
                    ni += 1
            bound *= 1.0 + ni
        cols = np.flatnonzero(colmask)
        nm = cols.shape[0]
        if nm == 0:
            continue
        lw0 = np.empty(nt)
        lW = np.zeros((nt, nm))
        lg = np.zeros((nt, nm), dtype=np.bool_)
        for a in range(nt):
            lw0[a] = w0[members[a]]
            for b in range(nm):
                lg[a, b] = gated[members[a], cols[b]]
                if lg[a, b]:
                    lW[a, b] = W[members[a], cols[b]]
        lp0 = np.empty(nt)
        lP = np.zeros((nt, nm))
        ok = bound <= max_events
        if ok:
            exact_cluster_marginals(lw0, lW, lg, lp0, lP, star)
        else:
            lbp_cluster_marginals(lw0, lW, lg, lp0, lP)
        for a in range(nt):
            i = members[a]
            p0[i] = lp0[a]
            exact[i] = ok
            for b in range(nm):
                P[i, cols[b]] = lP[a, b]
    return labels
