"""The PMBM's update of global hypotheses, one scan's groups of clusters in one compiled call.

García-Fernández, Williams, Granström & Svensson, "Poisson multi-Bernoulli mixture filter: direct derivation and
implementation", IEEE TAES 54(4), 2018, Section IV (the update) and Section V-C (Murty's k best assignments per
global hypothesis, k_h = ⌈N_h w_h⌉). ``lgekf.estimators.multitarget.pmbm`` forms the groups (clusters whose gates
take a common detection, their hypotheses' product) and applies the result to the bank; this module is the
arithmetic in between:

for global hypothesis h of weight w_h with local hypotheses (bank rows) ρ_hb of its B Bernoullis (−1: does not
exist) and the group's d detections j_1..j_d, the cost matrix d × (B + d)

    C[a, b]     = −log(r P_D N(z_ja; ẑ, S) / ((1 − r P_D P_G) κ_ja))   (row ρ_hb, z_ja in its gate; +inf otherwise)
    C[a, B + a] = −log((e + λ_ja)/λ_ja)                                  (new target or clutter; +inf off the diagonal)

(−(ll + A_ρ + b_j), A, b the per-row and per-detection terms of ``pmbm.LogWeights``), its k_h best assignments
(``murty.k_best_into``), each a new global hypothesis of log-weight log w_h + Σ_b log(1 − r_b P_D P_G) − cost.
One Bernoulli with one local hypothesis is enumerated instead (the miss and each gated detection: Murty's d + 1
assignments, the others new targets or clutter). Then per group: normalise, drop those below the pruning
threshold, keep at most N_h (at least the best).

A new global hypothesis is a table of *children*, one entry per Bernoulli and per detection of the group:
(parent row, detection) — the miss (ρ, −1), detection j to row ρ (ρ, j), a new Bernoulli born from j (−1, j) — or
(−2, −2) where the Bernoulli does not exist / the detection is another's.
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

from .jpda import _find as _root  # the union-find's root, with path halving
from .murty import k_best_into

__all__ = ["update_global_hypotheses", "cluster_components", "NOBODY"]

NOBODY = -2  # a table entry without a child


@nb.njit(cache=True)
def cluster_components(row_cluster, gated, C):
    """The groups of a scan: connected components of the graph of C clusters and M detections (nodes 0..C−1 and
    C..C+M−1) with an edge where a row of cluster ``row_cluster[i]`` (−1: none) gates detection j. Labels (C + M,)
    numbered in order of each component's smallest node (as scipy's ``connected_components``)."""
    N, M = gated.shape
    parent = np.arange(C + M)
    for i in range(N):
        c = row_cluster[i]
        if c < 0:
            continue
        for j in range(M):
            if gated[i, j]:
                a = _root(parent, c)
                b = _root(parent, C + j)
                if a != b:
                    parent[max(a, b)] = min(a, b)
    label = np.full(C + M, -1, dtype=np.int64)
    comp = np.empty(C + M, dtype=np.int64)
    n = 0
    for v in range(C + M):
        r = _root(parent, v)
        if label[r] < 0:
            label[r] = n
            n += 1
        comp[v] = label[r]
    return comp


@nb.njit(cache=True)
def _log_sum_exp(a):
    m = np.max(a)
    s = 0.0
    for x in a:
        s += math.exp(x - m)
    return m + math.log(s)


@nb.njit(cache=True)
def _enumerate_single(row, dets, ll, gated, A, Bv, log_new, max_h, log_prune, parent, det, lw):
    """One Bernoulli with one local hypothesis (row): the miss and each gated detection (the other detections new
    targets or clutter), normalised, pruned, capped; tables (n, 1 + d) into parent, det; returns n."""
    d = dets.size
    hit = np.empty(d, dtype=np.int64)
    nh = 0
    for a in range(d):
        if gated[row, dets[a]]:
            hit[nh] = a
            nh += 1
    w = np.empty(1 + nh)
    w[0] = 0.0  # the miss, then each gated detection (relative to all detections new targets or clutter)
    for i in range(nh):
        j = dets[hit[i]]
        w[1 + i] = ll[row, j] + A[row] + Bv[j] - log_new[j]
    w -= np.max(w)
    w -= math.log(np.sum(np.exp(w)))
    order = np.argsort(-w, kind="mergesort")
    n = 0
    for x in w:
        if x >= log_prune:
            n += 1
    n = max(1, min(n, max_h))
    for a in range(n):
        o = order[a]
        own = -1 if o == 0 else hit[o - 1]
        parent[a, 0] = row
        det[a, 0] = -1 if own < 0 else dets[own]
        for k in range(d):
            if k != own:
                parent[a, 1 + k] = -1
                det[a, 1 + k] = dets[k]
            else:
                parent[a, 1 + k] = NOBODY
                det[a, 1 + k] = NOBODY
    if n > 1:
        sel = w[order[:n]]
        lw[:n] = sel - _log_sum_exp(sel)
    else:
        lw[0] = 0.0
    return n


@nb.njit(cache=True)
def update_global_hypotheses(h_off, rows, r_off, lw_in, fl_in, n_bern, d_off, dets, ll, gated, A, Bv, logw0, log_new,
                             max_h, log_prune):
    """The new global hypotheses of G groups (module docstring).

    Group g has the hypotheses h_off[g]..h_off[g+1] (log-weights lw_in, not necessarily normalised; fl_in: descends
    from the reported one), B = n_bern[g] Bernoullis with rows ``rows[r_off[g]:]`` ((H, B) row-major) and the
    detections dets[d_off[g]:d_off[g+1]]. ll, gated (N, M): the bank's log-likelihoods and gates; A (N,), Bv (M,):
    the per-row and per-detection log-weight terms; logw0 (N,): log(1 − r P_D P_G); log_new (M,).

    Returns (o_off (G + 1,), lw (n,), fl (n,), t_off (G + 1,), parent, det): group g's new hypotheses are
    o_off[g]..o_off[g+1], normalised; their tables (B + d entries each, row-major) start at t_off[g].
    """
    G = n_bern.size
    # capacity: at most min(N_h, Σ_h k_h) per group, at least 1
    o_off = np.zeros(G + 1, dtype=np.int64)
    t_off = np.zeros(G + 1, dtype=np.int64)
    for g in range(G):
        H = h_off[g + 1] - h_off[g]
        d = d_off[g + 1] - d_off[g]
        lw = lw_in[h_off[g]:h_off[g + 1]]
        lw = lw - _log_sum_exp(lw)
        if d == 0:
            tot = H
        else:
            tot = 0
            for h in range(H):
                tot += max(1, math.ceil(max_h * math.exp(lw[h])))
            if n_bern[g] == 1 and H == 1:
                tot = d + 1
        cap = max(1, min(max_h, tot))
        o_off[g + 1] = o_off[g] + cap
        t_off[g + 1] = t_off[g] + cap * (n_bern[g] + d)
    out_lw = np.empty(o_off[G])
    out_fl = np.zeros(o_off[G], dtype=np.bool_)
    out_parent = np.empty(t_off[G], dtype=np.int64)
    out_det = np.empty(t_off[G], dtype=np.int64)
    used = np.zeros(G + 1, dtype=np.int64)  # hypotheses written per group
    for g in range(G):
        H = h_off[g + 1] - h_off[g]
        B = n_bern[g]
        gd = dets[d_off[g]:d_off[g + 1]]
        d = gd.size
        W = B + d
        R = rows[r_off[g]:r_off[g] + H * B].reshape((H, B))
        lw = lw_in[h_off[g]:h_off[g + 1]]
        lw = lw - _log_sum_exp(lw)
        cap = o_off[g + 1] - o_off[g]
        tp = out_parent[t_off[g]:t_off[g + 1]].reshape((cap, W))
        td = out_det[t_off[g]:t_off[g + 1]].reshape((cap, W))
        if B == 1 and H == 1 and R[0, 0] >= 0:
            n = _enumerate_single(R[0, 0], gd, ll, gated, A, Bv, log_new, max_h, log_prune, tp, td,
                                  out_lw[o_off[g]:o_off[g + 1]])
            out_fl[o_off[g]:o_off[g] + n] = True
            used[g] = n
            continue
        # every hypothesis's k best assignments, then normalise, prune, cap
        tot = 0
        for h in range(H):
            tot += 1 if d == 0 else max(1, math.ceil(max_h * math.exp(lw[h])))
        all_p = np.empty((tot, W), dtype=np.int64)
        all_d = np.empty((tot, W), dtype=np.int64)
        all_w = np.empty(tot)
        all_f = np.empty(tot, dtype=np.bool_)
        n_all = 0
        cost = np.empty((d, W))
        for h in range(H):
            rh = R[h]
            s0 = 0.0
            for b in range(B):
                if rh[b] >= 0:
                    s0 += logw0[rh[b]]
            base = lw[h] + s0
            if d == 0:
                k = 1
                sols = np.zeros((1, 0), dtype=np.int64)
                costs = np.zeros(1)
                n = 1
            else:
                cost[:, :] = np.inf
                for a in range(d):
                    j = gd[a]
                    for b in range(B):
                        i = rh[b]
                        if i >= 0 and gated[i, j]:
                            cost[a, b] = -(ll[i, j] + A[i] + Bv[j])
                    cost[a, B + a] = -log_new[j]
                k = max(1, math.ceil(max_h * math.exp(lw[h])))
                sols = np.empty((k, d), dtype=np.int64)
                costs = np.empty(k)
                n = k_best_into(cost, k, sols, costs)
            for s in range(n):
                row_p = all_p[n_all]
                row_d = all_d[n_all]
                for b in range(B):
                    if rh[b] >= 0:
                        row_p[b] = rh[b]
                        row_d[b] = -1
                    else:
                        row_p[b] = NOBODY
                        row_d[b] = NOBODY
                for a in range(d):
                    col = sols[s, a]
                    if col < B:
                        row_d[col] = gd[a]
                        row_p[B + a] = NOBODY
                        row_d[B + a] = NOBODY
                    else:
                        row_p[B + a] = -1
                        row_d[B + a] = gd[a]
                all_w[n_all] = base - costs[s]
                all_f[n_all] = fl_in[h_off[g] + h]
                n_all += 1
        w = all_w[:n_all] - _log_sum_exp(all_w[:n_all])
        order = np.argsort(-w, kind="mergesort")
        n = 0
        for o in order:
            if w[o] >= log_prune and n < max_h:
                n += 1
            else:
                break
        n = max(1, n)
        sel = w[order[:n]]
        out_lw[o_off[g]:o_off[g] + n] = sel - _log_sum_exp(sel)
        for a in range(n):
            tp[a] = all_p[order[a]]
            td[a] = all_d[order[a]]
            out_fl[o_off[g] + a] = all_f[order[a]]
        used[g] = n
    # compact: drop the unused capacity
    n_out = np.zeros(G + 1, dtype=np.int64)
    m_out = np.zeros(G + 1, dtype=np.int64)
    for g in range(G):
        W = n_bern[g] + d_off[g + 1] - d_off[g]
        n_out[g + 1] = n_out[g] + used[g]
        m_out[g + 1] = m_out[g] + used[g] * W
    lw = np.empty(n_out[G])
    fl = np.empty(n_out[G], dtype=np.bool_)
    parent = np.empty(m_out[G], dtype=np.int64)
    det = np.empty(m_out[G], dtype=np.int64)
    for g in range(G):
        u = used[g]
        W = n_bern[g] + d_off[g + 1] - d_off[g]
        lw[n_out[g]:n_out[g] + u] = out_lw[o_off[g]:o_off[g] + u]
        fl[n_out[g]:n_out[g] + u] = out_fl[o_off[g]:o_off[g] + u]
        parent[m_out[g]:m_out[g] + u * W] = out_parent[t_off[g]:t_off[g] + u * W]
        det[m_out[g]:m_out[g] + u * W] = out_det[t_off[g]:t_off[g] + u * W]
    return n_out, lw, fl, m_out, parent, det


@nb.njit(cache=True)
def _rows_less(R, a, b):
    """Row a of R before row b in lexicographic order (np.unique's order of rows)."""
    for c in range(R.shape[1]):
        if R[a, c] != R[b, c]:
            return R[a, c] < R[b, c]
    return False


@nb.njit(cache=True)
def _merge_equal_hypotheses(R, lw, fl):
    """Global hypotheses with equal rows as one (weights added, flags or-ed), in np.unique's order of rows; unchanged
    when all differ (``pmbm._merge_duplicates``)."""
    H = R.shape[0]
    order = np.arange(H)
    for a in range(1, H):  # stable insertion sort by rows
        k = order[a]
        b = a - 1
        while b >= 0 and _rows_less(R, k, order[b]):
            order[b + 1] = order[b]
            b -= 1
        order[b + 1] = k
    first = np.zeros(H, dtype=np.bool_)
    n = 0
    for a in range(H):
        if a == 0 or _rows_less(R, order[a - 1], order[a]):
            first[a] = True
            n += 1
    if n == H:
        return R, lw, fl
    R2 = np.empty((n, R.shape[1]), dtype=np.int64)
    lw2 = np.empty(n)
    fl2 = np.zeros(n, dtype=np.bool_)
    u = -1
    start = 0
    for a in range(H + 1):
        if a == H or first[a]:
            if u >= 0:  # members order[start:a], summed in their original order
                members = np.sort(order[start:a])
                lw2[u] = _log_sum_exp(lw[members])
                for k in members:
                    fl2[u] = fl2[u] or fl[k]
            if a == H:
                break
            u += 1
            start = a
            R2[u] = R[order[a]]
    return R2, lw2, fl2


@nb.njit(cache=True)
def split_clusters(R_all, faint, t_off, o_off, n_bern, ids, ids_off, lw, fl, next_id, row_ids, log_bonus):
    """The new clusters of G groups from their tables in bank rows (``update_global_hypotheses``' tables, children
    replaced by their rows, −1 where the Bernoulli does not exist; ``faint``: set to −1 by the deletion threshold):
    columns that exist nowhere dropped, the new Bernoullis' ids (from next_id, in column order) written to
    ``row_ids``, equal hypotheses merged (only after a deletion), and every column with the same local hypothesis in
    all hypotheses split off as a one-Bernoulli cluster (exact: the weights do not depend on it). The reported
    hypothesis: argmax of lw + log_bonus·(descends from the last reported one) (``pmbm._choose``).

    Returns (single rows, single ids, multi ids, multi id offsets, multi rows (H, B) row-major, multi row offsets,
    multi lw, multi lw offsets, multi chosen, next_id)."""
    G = n_bern.size
    cap = R_all.size
    s_rows = np.empty(cap, dtype=np.int64)
    s_ids = np.empty(cap, dtype=np.int64)
    m_ids = np.empty(cap, dtype=np.int64)
    m_rows = np.empty(cap, dtype=np.int64)
    m_lw = np.empty(lw.size)
    m_ids_off = np.zeros(G + 1, dtype=np.int64)
    m_rows_off = np.zeros(G + 1, dtype=np.int64)
    m_lw_off = np.zeros(G + 1, dtype=np.int64)
    m_chosen = np.empty(G, dtype=np.int64)
    ns = 0
    nm = 0
    for g in range(G):
        H = o_off[g + 1] - o_off[g]
        W = (t_off[g + 1] - t_off[g]) // H
        B = n_bern[g]
        R = R_all[t_off[g]:t_off[g + 1]].reshape((H, W))
        deleted = False
        for x in faint[t_off[g]:t_off[g + 1]]:
            deleted = deleted or x
        keep = np.zeros(W, dtype=np.int64)
        cid = np.empty(W, dtype=np.int64)
        nk = 0
        for c in range(W):
            ex = False
            for h in range(H):
                ex = ex or R[h, c] >= 0
            if not ex:
                continue
            if c < B:
                cid[nk] = ids[ids_off[g] + c]
            else:
                cid[nk] = next_id
                next_id += 1
            keep[nk] = c
            nk += 1
        if nk == 0:
            continue
        Rk = np.empty((H, nk), dtype=np.int64)
        for h in range(H):
            for a in range(nk):
                Rk[h, a] = R[h, keep[a]]
                if Rk[h, a] >= 0:
                    row_ids[Rk[h, a]] = cid[a]
        if H == 1:
            for a in range(nk):
                s_rows[ns] = Rk[0, a]
                s_ids[ns] = cid[a]
                ns += 1
            continue
        w = lw[o_off[g]:o_off[g + 1]].copy()
        f = fl[o_off[g]:o_off[g + 1]].copy()
        if deleted:  # (distinct assignments give distinct children: equal hypotheses only after a deletion)
            Rk, w, f = _merge_equal_hypotheses(Rk, w, f)
            H = Rk.shape[0]
        w = w - _log_sum_exp(w)
        multi = np.empty(nk, dtype=np.int64)
        nmc = 0
        for a in range(nk):
            const = Rk[0, a] >= 0
            for h in range(1, H):
                const = const and Rk[h, a] == Rk[0, a]
            if const:
                s_rows[ns] = Rk[0, a]
                s_ids[ns] = cid[a]
                ns += 1
            else:
                multi[nmc] = a
                nmc += 1
        if nmc == 0:
            continue
        m_ids_off[nm + 1] = m_ids_off[nm] + nmc
        m_rows_off[nm + 1] = m_rows_off[nm] + H * nmc
        m_lw_off[nm + 1] = m_lw_off[nm] + H
        for a in range(nmc):
            m_ids[m_ids_off[nm] + a] = cid[multi[a]]
        for h in range(H):
            for a in range(nmc):
                m_rows[m_rows_off[nm] + h * nmc + a] = Rk[h, multi[a]]
        best = 0
        for h in range(H):
            m_lw[m_lw_off[nm] + h] = w[h]
            if w[h] + log_bonus * f[h] > w[best] + log_bonus * f[best]:
                best = h
        m_chosen[nm] = best
        nm += 1
    return (s_rows[:ns], s_ids[:ns], m_ids, m_ids_off[:nm + 1], m_rows, m_rows_off[:nm + 1], m_lw, m_lw_off[:nm + 1],
            m_chosen[:nm], next_id)
