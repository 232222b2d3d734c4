"""The Poisson multi-Bernoulli mixture (PMBM) filter, track-oriented, as the association ``"pmbm"`` of
``MultiTargetTracker``.

García-Fernández, Williams, Granström & Svensson, "Poisson multi-Bernoulli mixture filter: direct derivation and
implementation", IEEE TAES 54(4), 2018 (the update of their Section IV; notation as Granström, Svensson, Xia,
Williams & García-Fernández, "Poisson multi-Bernoulli mixtures for sets of trajectories", 2019). The multi-target
density is a Poisson part (targets never detected) times a mixture of multi-Bernoullis:

* **Poisson part**, for position detections a uniform density D_u of undetected targets per m² with the one-point
  velocity prior of the tracker (``one_point_prior``): predicted D_u ← p_S D_u + β (β the birth density per m² per
  scan) and updated by the miss, D_u ← (1 − P_D) D_u. A detection z not associated with an existing Bernoulli is
  a new target's first detection or clutter: it starts a **new Bernoulli** of existence e/(e + λ(z)), e = P_D D_u
  (weight e + λ(z)), its state the one-point prior at z;
* **Bernoullis**, each with **local hypotheses**: an existence r, a filter state (a row of the tracker's bank,
  ``TrackFilterBank``) and the detection it holds. A local hypothesis with prediction ẑ, S has the children
  - the miss: r' = r(1 − P_D P_G)/(1 − r P_D P_G), the state predicted only, weight 1 − r P_D P_G;
  - detection j in its gate: r' = 1, the state updated with z_j alone (a copy of the row, ``copy``, updated by
    ``update`` with β_ij = 1), weight r P_D N(z_j; ẑ, S);
  (P_G the gate probability; the tracker's JPDA weighs its joint events with the same factors);
* **global hypotheses**: one local hypothesis per Bernoulli (or "does not exist", e.g. a new Bernoulli whose
  detection went to another target), each with a weight. The update of a global hypothesis h of weight w_h: the
  k_h = ⌈N_h w_h⌉ best assignments of the scan's detections (N_h = ``max_hypotheses``; Murty's algorithm, ``murty``,
  compiled with the rest of this arithmetic in ``global_hypotheses``) on the cost matrix detections × (Bernoullis, one
  new-target-or-clutter column per detection), costs −log(r P_D N / ((1 − r P_D P_G) λ)) and −log((e + λ)/λ),
  forbidden outside the gates); the new weight is
  w_h Π_b (1 − r_b P_D P_G) × exp(−cost) (up to the factor Π_j λ_j common to all). Then normalise, prune the
  global hypotheses of weight below ``hypothesis_prune``, keep at most ``max_hypotheses``, drop the local
  hypotheses no global hypothesis uses, and the Bernoullis whose existence is below ``delete_existence`` in every
  global hypothesis.

**Clusters.** Global hypotheses are kept per cluster of Bernoullis that have shared detections: the mixture is the
product of the clusters' mixtures (exact while they do not interact). Per scan the clusters whose gates take a
common detection are merged (the product of their hypotheses, capped), and a Bernoulli whose local hypothesis is
the same in every global hypothesis of its cluster is split off into a cluster of its own (exact: the weights do
not depend on it). A detection in no gate starts a Bernoulli in a cluster of its own, without any assignment.

**Estimates.** The most likely global hypothesis is the product of each cluster's best one (García-Fernández et al.
2018, Section VI, estimator 1), with a hysteresis: in each cluster the reported global hypothesis is the most likely
one unless a continuation (a child) of the one reported at the last scan has at least 1/``BEST_HYSTERESIS`` (1/3)
of its weight; then the most likely such continuation. (Two global hypotheses that explain a target by two different
Bernoullis, e.g. a young track missed once and a new Bernoulli started by that detection, keep a nearly constant
weight ratio while their states differ a little, and the plain argmax flipped between them, an identity switch each
time; docs/multi_target.md.) A Bernoulli is *confirmed* the first time (a) its existence marginalised over the
global hypotheses, r̄_b = Σ_h w_h r_hb (r_hb = 0 where it does not exist), is ≥ ``confirm_existence``, or (b) the
detection its local hypothesis in the reported global hypothesis holds is a target's with probability
≥ ``confirm_existence``: Σ_h w_h (1 if a Bernoulli takes it in h, e/(e + λ) if it starts one there). A confirmed
Bernoulli is reported while its local hypothesis in the reported global hypothesis has r ≥ the report threshold,
with that local hypothesis's state and r̄_b as its existence; its id is the track id. Why not the local r for
confirmation: it is 1 after any detection, so a new Bernoulli of a false alarm that gets a second false alarm in its
gate would be confirmed at once whenever that hypothesis is the most likely (in dense clutter: 8× the false-track
part); the marginals weigh it against "both were clutter", as JIPDA's existence does. Why (b): a target's first
detections are often explained by two Bernoullis in different global hypotheses (one started at its first
detection, one at its second, the first missed), which split r̄ between them; the detection itself is a target's
in both.

**Local hypotheses below ``delete_existence``** are "does not exist" in their global hypothesis (a missed new
Bernoulli, r₀ = 0.02 → 0.002, as JPDA deletes its track); kept, their covariances grew scan by scan while other
global hypotheses held the Bernoulli, and their gates of hundreds of metres merged whole crowds into one capped
cluster.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from .global_hypotheses import NOBODY, cluster_components, split_clusters, update_global_hypotheses
from .settings import PMBM_DEFAULTS

__all__ = ["PMBM", "Cluster", "PMBM_DEFAULTS", "BEST_HYSTERESIS"]

BEST_HYSTERESIS = 3.0  # the reported global hypothesis's continuation is kept unless another is 3x as likely


def _logsumexp(a):
    m = np.max(a)
    return m + math.log(np.exp(a - m).sum())


@dataclass
class Cluster:
    """Global hypotheses over some Bernoullis: ``rows`` (H, B) the bank row of each Bernoulli's local hypothesis in
    each global hypothesis (−1: the Bernoulli does not exist there), ``lw`` (H,) normalised log-weights,
    ``ids`` (B,) the Bernoullis' ids (track ids)."""

    ids: np.ndarray
    rows: np.ndarray
    lw: np.ndarray
    chosen: int = 0

    @property
    def best(self) -> np.ndarray:
        """The rows of the reported global hypothesis (−1 where a Bernoulli does not exist in it): ``chosen``."""
        return self.rows[self.chosen]

    def chosen_flags(self) -> np.ndarray:
        """(H,) True at the reported global hypothesis."""
        f = np.zeros(self.lw.size, dtype=bool)
        f[self.chosen] = True
        return f


class LogWeights:
    """log(r P_D N(e_ij; 0, S_i) / ((1 − r P_D P_G) κ_j)) of rows i and detections j (the cost of detection j to the
    local hypothesis of row i against its miss, with the 1/κ_j common to all assignments), formed on demand from the
    bank's log-likelihoods ll (N, M), per-row and per-detection terms: ll_ij + a_i + b_j (−inf outside the gates)."""

    def __init__(self, ll, a, b):
        self.ll, self.a, self.b = ll, a, b

    def pairs(self, i, j):
        return self.ll[i, j] + self.a[i] + self.b[j]

    def block(self, rows, cols):
        return self.ll[np.ix_(rows, cols)] + self.a[rows, None] + self.b[None, cols]


def _choose(lw, from_chosen):
    """The global hypothesis to report: the most likely one, unless a continuation of the last reported one is within
    ``BEST_HYSTERESIS`` of it (module docstring): argmax of w_h·(BEST_HYSTERESIS if it descends from it, else 1)."""
    return int(np.argmax(lw + math.log(BEST_HYSTERESIS) * from_chosen))


def _merge_duplicates(rows, lw, flags):
    """Global hypotheses with equal local hypotheses as one (weights added; descending from the reported one if any
    did)."""
    if rows.shape[0] < 2:
        return rows, lw, flags
    uniq, inv = np.unique(rows, axis=0, return_inverse=True)
    if uniq.shape[0] == rows.shape[0]:
        return rows, lw, flags
    inv = inv.reshape(-1)
    out = np.full(uniq.shape[0], -np.inf)
    fl = np.zeros(uniq.shape[0], dtype=bool)
    for k in range(uniq.shape[0]):
        out[k] = _logsumexp(lw[inv == k])
        fl[k] = flags[inv == k].any()
    return uniq, out, fl


class PMBM:
    """The PMBM part of a ``MultiTargetTracker(association="pmbm")`` (module docstring). It keeps the clusters and the
    Poisson density; the tracker keeps, per bank row (local hypothesis), its existence ``r``, Bernoulli id ``ids``
    and one-point bookkeeping, and calls ``scan`` once per scan after the prediction.

    Parameters
    ----------
    trk : MultiTargetTracker
    max_hypotheses : int
        At most this many global hypotheses per cluster; also N_h of the k-best rule k_h = ⌈N_h w_h⌉.
    hypothesis_prune : float
        Global hypotheses of normalised weight below this are dropped (per cluster).
    birth : float
        β, the Poisson birth density per m² per scan.
    """

    confirm_by_detection = True  # also confirm by the held detection's probability of being a target's (docstring)

    def __init__(self, trk, max_hypotheses: int, hypothesis_prune: float, birth: float):
        self.trk = trk
        self.max_hypotheses = int(max_hypotheses)
        self.hypothesis_prune = float(hypothesis_prune)
        self.birth = float(birth)
        self.undetected = 0.0  # D_u per m² (after the last update)
        self.multi: list[Cluster] = []  # clusters of several Bernoullis or global hypotheses
        self.s_rows = np.zeros(0, dtype=np.int64)  # the clusters of one Bernoulli with one local hypothesis (most):
        self.s_ids = np.zeros(0, dtype=np.int64)  # its row and id, as arrays
        self.confirmed_ids: set = set()
        self.last_hypotheses = 0
        self._best = None  # best_rows() until the clusters change

    @property
    def clusters(self) -> list:
        """Every cluster as a ``Cluster`` (the one-Bernoulli one-hypothesis ones made from their arrays)."""
        return [Cluster(self.s_ids[k:k + 1], self.s_rows[k:k + 1, None], np.zeros(1)) for k in range(self.s_rows.size)] \
            + list(self.multi)

    @clusters.setter
    def clusters(self, clusters):
        single = [c for c in clusters if c.rows.shape == (1, 1) and c.rows[0, 0] >= 0]
        self.s_rows = np.array([c.rows[0, 0] for c in single], dtype=np.int64)
        self.s_ids = np.array([c.ids[0] for c in single], dtype=np.int64)
        self.multi = [c for c in clusters if not (c.rows.shape == (1, 1) and c.rows[0, 0] >= 0)]
        self._best = None

    def n_bernoullis(self) -> int:
        """The number of Bernoullis (tracks, tentative included)."""
        return self.s_rows.size + sum(c.ids.size for c in self.multi)

    # ------------------------------------------------------------------ Poisson part
    def predict_poisson(self):
        """D_u ← p_S D_u + β."""
        self.undetected = self.trk.ps * self.undetected + self.birth

    def best_rows(self) -> np.ndarray:
        """The rows of the most likely global hypothesis (every cluster's best)."""
        return self._best_and_existence()[0]

    def best_existence(self) -> np.ndarray:
        """The existence of each Bernoulli of ``best_rows`` marginalised over its cluster's global hypotheses,
        r̄_b = Σ_h w_h r_hb (r_hb = 0 where it does not exist): the probability that the target exists."""
        return self._best_and_existence()[1]

    def _best_and_existence(self):
        if self._best is None:
            r = self.trk.r
            rows, marg = [self.s_rows], [r[self.s_rows]]
            for c in self.multi:
                if c.lw.size == 1:
                    rows.append(c.rows[0])
                    marg.append(r[c.rows[0]])
                    continue
                rows.append(c.best)
                rr = np.where(c.rows >= 0, r[np.maximum(c.rows, 0)], 0.0)
                marg.append(np.exp(c.lw) @ rr)
            b = np.concatenate(rows) if rows else np.zeros(0, dtype=np.int64)
            m = np.concatenate(marg) if marg else np.zeros(0)
            self._best = (b[b >= 0], m[b >= 0])
        return self._best

    def n_hypotheses(self) -> int:
        """The number of global hypotheses summed over the clusters (their product is the mixture's size)."""
        return self.s_rows.size + sum(c.lw.size for c in self.multi)

    # ------------------------------------------------------------------ one scan
    def scan(self, t, Z, lam, ll, gated, d2):
        """The PMBM update with detections Z (M, m) at time t, clutter density λ (a float or (M,), per m²), the bank's
        log-likelihoods ll and gates (N, M) of every row and d² (N, M). Returns the held (ids, detections, d²) of the
        best global hypothesis."""
        trk = self.trk
        M = Z.shape[0]
        pdg = trk.pd * trk.pg
        lamv = np.broadcast_to(np.asarray(lam, dtype=float), (M,)).copy()
        e = trk.pd * self.undetected  # P_D D_u per m²
        self.e_last = e
        log_new = np.log1p(e / lamv)  # log((e + λ)/λ): the new-target-or-clutter column
        r = trk.r
        with np.errstate(divide="ignore"):
            logw0 = np.log1p(-r * pdg)  # per row
        # log(r P_D N / ((1 − r P_D P_G) κ)) on the gated pairs (κ = λ per m² per angle volume)
        # (ll is −inf outside the gates: so is logW; formed where needed, ``LogWeights``)
        with np.errstate(divide="ignore"):
            logW = LogWeights(ll, np.log(r * trk.pd) - logw0, -np.log(lamv / trk.angle_volume))
        # clusters touching common detections -> groups (connected components of clusters and detections)
        # (cluster k < S: the one-Bernoulli cluster s_rows[k]; k ≥ S: multi[k − S])
        S = self.s_rows.size
        C = S + len(self.multi)
        row_cluster = np.full(r.size, -1, dtype=np.int64)
        row_cluster[self.s_rows] = np.arange(S)
        shape11 = np.zeros(C, dtype=bool)
        shape11[:S] = True
        for k, c in enumerate(self.multi):
            row_cluster[c.rows[c.rows >= 0]] = S + k
        comp = cluster_components(row_cluster, gated, C)
        det_comp = comp[C:]
        cl_comp = comp[:C]
        n_cl = np.bincount(cl_comp, minlength=C + M)
        n_det = np.bincount(det_comp, minlength=C + M)
        # detections in no gate: a Bernoulli each, in a cluster of its own (``_apply``)
        self._lone = np.flatnonzero(n_cl[det_comp] == 0)
        # one Bernoulli, one hypothesis, no detection: missed, the cluster as it was
        quiet_mask = shape11 & (n_cl[cl_comp] == 1) & (n_det[cl_comp] == 0)
        quiet = np.flatnonzero(quiet_mask)  # (< S)
        # one Bernoulli, one hypothesis, one detection that no other gate takes, the miss's weight below the pruning
        # threshold: the hard update with it is the only global hypothesis kept (what the enumeration of its hypotheses gives), in bulk
        pair = np.flatnonzero(shape11 & (n_cl[cl_comp] == 1) & (n_det[cl_comp] == 1))
        det_of_comp = np.full(C + M, -1, dtype=np.int64)
        det_of_comp[det_comp] = np.arange(M)
        prow = self.s_rows[pair]
        pj = det_of_comp[cl_comp[pair]]
        sure = -np.logaddexp(0.0, logW.pairs(prow, pj) - log_new[pj]) < math.log(self.hypothesis_prune)  # log w_miss
        self._sure = (pair[sure], prow[sure], pj[sure])  # their children are registered after the others (``_apply``)
        busy_mask = ~quiet_mask
        busy_mask[pair[sure]] = False
        busy = np.flatnonzero(busy_mask)
        # the groups: busy clusters sorted by component (the detections of a component follow in index order)
        order = np.argsort(cl_comp[busy], kind="stable")
        ks_sorted = busy[order]
        comps = cl_comp[ks_sorted]
        starts = np.concatenate([[0], np.flatnonzero(np.diff(comps)) + 1]) if busy.size else np.zeros(0, dtype=np.int64)
        dorder = np.argsort(det_comp, kind="stable")
        dcomp = det_comp[dorder]
        g_comp = comps[starts]
        n_det = np.searchsorted(dcomp, g_comp, side="right") - np.searchsorted(dcomp, g_comp)
        dets = dorder[np.isin(dcomp, g_comp)]
        groups = self._groups(ks_sorted, starts)
        return self._apply(t, Z, lamv, e, self._update_groups(groups, dets, n_det, M, logW, gated, logw0, log_new),
                           quiet, d2)

    def _groups(self, ks_sorted, starts):
        """Per group of merged clusters (cluster numbers ``ks_sorted[starts[g]:starts[g + 1]]``, ``scan``'s
        numbering): (ids, rows (H, B), log-weights (H,), flags (H,)), the product of the clusters' hypotheses."""
        S = self.s_rows.size
        ends = np.append(starts[1:], ks_sorted.size)
        one, flag = np.zeros(1), np.ones(1, dtype=bool)
        out = []
        for a, b in zip(starts.tolist(), ends.tolist()):
            if b - a == 1:
                k = int(ks_sorted[a])
                if k < S:  # a one-Bernoulli one-hypothesis cluster, from its arrays
                    out.append((self.s_ids[k:k + 1], self.s_rows[k:k + 1], one, flag))
                else:
                    c = self.multi[k - S]
                    out.append((c.ids, c.rows, c.lw, c.chosen_flags()))
            else:
                out.append(self._product([self._cluster(k) for k in ks_sorted[a:b]]))
        return out

    def _cluster(self, k):
        """Cluster k of ``scan``'s numbering as a ``Cluster``."""
        S = self.s_rows.size
        if k >= S:
            return self.multi[k - S]
        return Cluster(self.s_ids[k:k + 1], self.s_rows[k:k + 1, None], np.zeros(1))

    def _product(self, clusters):
        """The merged clusters' global hypotheses: the product of their hypotheses, capped at ``max_hypotheses``
        (the most likely kept): (ids, rows (H, B), log-weights (H,) not normalised, flags (H,): descends from the
        reported one)."""
        c0 = clusters[0]
        if len(clusters) == 1:
            return c0.ids, c0.rows, c0.lw, c0.chosen_flags()
        ids = np.concatenate([c.ids for c in clusters])
        rows, lw, fl = c0.rows, c0.lw, c0.chosen_flags()
        for c in clusters[1:]:
            H1, H2 = lw.size, c.lw.size
            rows = np.hstack([np.repeat(rows, H2, axis=0), np.tile(c.rows, (H1, 1))])
            lw = (lw[:, None] + c.lw[None, :]).reshape(-1)
            fl = (fl[:, None] & c.chosen_flags()[None, :]).reshape(-1)
            if lw.size > self.max_hypotheses:
                keep = np.argsort(-lw, kind="stable")[:self.max_hypotheses]
                rows, lw, fl = rows[keep], lw[keep], fl[keep]
        return ids, rows, lw, fl

    def _update_groups(self, groups, dets, n_det, M, logW, gated, logw0, log_new):
        """The new global hypotheses of every group (``_groups``; their detections ``dets``, n_det of each, in group
        order) (``global_hypotheses.update_global_hypotheses``, one call) and
        their children: (parent row, detection) pairs numbered in order of first use (parent −1: born from the
        detection; detection −1: the miss). Sets ``_child_parent``, ``_child_det`` and ``_table`` (every group's
        tables of child indices, (H', B + d) row-major, −1: none); returns per group (the B old Bernoullis' ids, its
        tables' (start, end) in ``_table``, normalised log-weights (H',), flags (H',))."""
        G = len(groups)
        if G == 0:
            self._child_parent = self._child_det = self._table = np.zeros(0, dtype=np.int64)
            self._entry_w = np.zeros(0)
            return None
        n_bern = np.array([g[0].size for g in groups], dtype=np.int64)
        n_hyp = np.array([g[2].size for g in groups], dtype=np.int64)
        h_off = np.concatenate([[0], np.cumsum(n_hyp)])
        r_off = np.concatenate([[0], np.cumsum(n_hyp * n_bern)])
        d_off = np.concatenate([[0], np.cumsum(n_det)])
        rows = np.concatenate([g[1].reshape(-1) for g in groups]).astype(np.int64)
        lw = np.concatenate([g[2] for g in groups]).astype(float)
        fl = np.concatenate([g[3] for g in groups])
        dets = dets.astype(np.int64)
        n_det = n_det.astype(np.int64)
        o_off, w, fl, t_off, parent, det = update_global_hypotheses(
            h_off, rows, r_off, lw, fl, n_bern, d_off, dets, logW.ll, gated, logW.a, logW.b, logw0, log_new,
            self.max_hypotheses, math.log(self.hypothesis_prune))
        valid = parent != NOBODY
        vp, vd = parent[valid], det[valid]
        _, first, inv = np.unique((vp + 1) * (M + 1) + (vd + 1), return_index=True, return_inverse=True)
        order = np.argsort(first, kind="stable")  # children in order of first use
        rank = np.empty(order.size, dtype=np.int64)
        rank[order] = np.arange(order.size)
        table = np.full(parent.size, -1, dtype=np.int64)
        table[valid] = rank[inv.reshape(-1)]
        self._child_parent, self._child_det = vp[first[order]], vd[first[order]]
        self._entry_w = np.repeat(w, np.repeat(n_bern + n_det, np.diff(o_off)))  # each table entry's hypothesis weight
        self._table = table
        ids = np.concatenate([g[0] for g in groups]).astype(np.int64)
        return ids, np.concatenate([[0], np.cumsum(n_bern)]), t_off, o_off, w, fl, n_bern

    def _apply(self, t, Z, lamv, e, new_clusters, quiet, d2):
        """The bank operations of all children at once, then the clusters in bank rows, deletion and splitting."""
        trk = self.trk
        bank = trk.bank
        pdg = trk.pd * trk.pg
        sure_k, sure_row, sure_det = self._sure  # the sure hard updates: children n0, n0 + 1, ... (unique keys)
        n0 = len(self._child_parent)
        parent = np.concatenate([self._child_parent, sure_row])
        det = np.concatenate([self._child_det, sure_det])
        sure_child = n0 + np.arange(sure_k.size)
        n = parent.size
        child_row = np.full(n, -1, dtype=np.int64)
        miss = (parent >= 0) & (det < 0)
        child_row[miss] = parent[miss]  # the miss keeps the predicted state in place
        quiet_rows = self.s_rows[quiet]
        missed = np.concatenate([parent[miss], quiet_rows])
        hit = np.flatnonzero((parent >= 0) & (det >= 0))
        lone = self._lone
        born_det = np.concatenate([det[parent < 0], lone])  # new Bernoullis' detections: in hypotheses, then alone
        born = np.flatnonzero(parent < 0)
        restart = hit[trk.on_prior[parent[hit]]]
        plain = hit[~trk.on_prior[parent[hit]]]
        self.held_d2 = np.full(n, np.nan)
        self.held_d2[hit] = d2[parent[hit], det[hit]]
        # detection children: copies of the parent rows, hard-updated with their detection (β_ij = 1)
        if plain.size:
            new = bank.copy(parent[plain])
            trk._sync()
            N = bank.live.size
            beta0 = np.ones(N)
            beta = np.zeros((N, Z.shape[0]))
            beta0[new] = 0.0
            beta[new, det[plain]] = 1.0
            bank.update(beta0, beta)
            child_row[plain] = new
            for a in (trk.ids, trk.first_t, trk.first_z):
                a[new] = a[parent[plain]]
            trk.on_prior[new] = False
        # one-point children at their second detection: started again by the two-point rule (the tracker's)
        if restart.size:
            p = parent[restart]
            x0, P0 = trk._pair_estimates(trk.first_t[p], trk.first_z[p], np.full(p.size, t), Z[det[restart]])
            new = bank.add(x0, P0)
            trk._sync()
            child_row[restart] = new
            trk.ids[new] = trk.ids[p]
            trk.on_prior[new] = False
        r_parent = trk.r.copy()
        # parents no miss child keeps: gone
        is_child = np.zeros(bank.live.size, dtype=bool)
        is_child[child_row[child_row >= 0]] = True
        is_child[quiet_rows] = True
        old = np.flatnonzero(bank.live & ~is_child)
        if old.size:
            bank.remove(old)
            trk.r[old], trk.ids[old], trk.on_prior[old] = 0.0, -1, False
        trk.r[missed] = r_parent[missed] * (1.0 - pdg) / (1.0 - r_parent[missed] * pdg)
        trk.r[child_row[hit]] = 1.0
        # quiet Bernoullis missed below the deletion threshold (e.g. last scan's new Bernoullis of false alarms): gone
        # before the new Bernoullis take rows (the bank's peak size, hence its gates' cost, stays near the live rows)
        keep = (trk.r[quiet_rows] >= trk.r_delete) & np.isfinite(trk.r[quiet_rows])
        faint_quiet = quiet_rows[~keep]
        if faint_quiet.size:
            bank.remove(faint_quiet)
            trk.r[faint_quiet], trk.ids[faint_quiet], trk.on_prior[faint_quiet] = 0.0, -1, False
        lone_rows = np.zeros(0, dtype=np.int64)
        if born_det.size:  # new Bernoullis: the one-point prior at their detection, existence e/(e + λ)
            zj = Z[born_det]
            new = bank.add(*trk._one_point_estimates(zj))
            trk._sync()
            child_row[born] = new[:born.size]
            lone_rows = new[born.size:]
            trk.r[new] = e / (e + lamv[born_det])
            trk.on_prior[new] = True
            trk.first_t[new] = t
            trk.first_z[new] = zj
            trk.ids[new] = -1  # an id when a kept global hypothesis has it (below)
        self.undetected *= 1.0 - trk.pd
        # the clusters in rows; new Bernoullis get their ids; deletion; splitting
        s_rows = [quiet_rows[keep], child_row[sure_child]]
        s_ids = [self.s_ids[quiet[keep]], self.s_ids[sure_k]]
        lone_rows = lone_rows[trk.r[lone_rows] >= trk.r_delete]  # (else removed below: no hypothesis uses them)
        lone_ids = np.arange(trk.next_id, trk.next_id + lone_rows.size)
        trk.next_id += lone_rows.size
        trk.ids[lone_rows] = lone_ids
        s_rows.append(lone_rows)
        s_ids.append(lone_ids)
        clusters = []
        # each detection's probability of being a target's: Σ_h w_h (1 if a track takes it in h, e/(e + λ) if it
        # starts a Bernoulli there)
        r_new = e / (e + lamv)
        target = np.zeros(Z.shape[0])
        target[lone] = r_new[lone]
        target[sure_det] = 1.0
        if new_clusters is not None:
            ent = self._table >= 0
            ch = self._table[ent]
            jj = det[ch]
            on = jj >= 0
            np.add.at(target, jj[on], np.exp(self._entry_w[ent][on]) * np.where(parent[ch[on]] < 0, r_new[jj[on]], 1.0))
        self.detection_target = target
        # the tables in bank rows (−1: does not exist); a local hypothesis below the deletion threshold: the Bernoulli
        # does not exist there
        R_all = np.where(self._table >= 0, child_row[np.maximum(self._table, 0)], -1)
        faint_all = (R_all >= 0) & ~(trk.r[np.maximum(R_all, 0)] >= trk.r_delete)  # (NaN included)
        R_all[faint_all] = -1
        if new_clusters is not None:
            ids, ids_off, t_off, o_off, w, fl, n_bern = new_clusters
            (g_rows, g_ids, m_ids, m_ids_off, m_rows, m_rows_off, m_lw, m_lw_off, m_chosen,
             trk.next_id) = split_clusters(R_all, faint_all, t_off, o_off, n_bern, ids, ids_off, w, fl, trk.next_id,
                                           trk.ids, math.log(BEST_HYSTERESIS))
            s_rows.append(g_rows)
            s_ids.append(g_ids)
            for k in range(m_chosen.size):
                H = m_lw_off[k + 1] - m_lw_off[k]
                clusters.append(Cluster(m_ids[m_ids_off[k]:m_ids_off[k + 1]],
                                        m_rows[m_rows_off[k]:m_rows_off[k + 1]].reshape(H, -1),
                                        m_lw[m_lw_off[k]:m_lw_off[k + 1]], int(m_chosen[k])))
        self.multi = clusters
        self.s_rows = np.concatenate(s_rows).astype(np.int64)
        self.s_ids = np.concatenate(s_ids).astype(np.int64)
        self._best = None
        # local hypotheses no global hypothesis uses
        used = np.zeros(bank.live.size, dtype=bool)
        used[self.s_rows] = True
        for c in clusters:
            used[c.rows[c.rows >= 0]] = True
        gone = np.flatnonzero(bank.live & ~used)
        if gone.size:
            bank.remove(gone)
            trk.r[gone], trk.ids[gone], trk.on_prior[gone] = 0.0, -1, False
        self.last_hypotheses = self.n_hypotheses()
        # the best global hypothesis: confirmations (by the marginal existence) and the detections it holds
        best = self.best_rows()
        ok = self.best_existence() >= trk.r_confirm
        self.confirmed_ids.update(int(i) for i in trk.ids[best[ok]])
        row_child = np.full(bank.live.size, -1, dtype=np.int64)
        row_child[child_row[hit]] = hit
        hb = best[row_child[best] >= 0]
        ch = row_child[hb]
        if self.confirm_by_detection:
            self.confirmed_ids.update(int(i) for i in trk.ids[hb[target[det[ch]] >= trk.r_confirm]])
        return trk.ids[hb].copy(), det[ch].copy(), self.held_d2[ch].copy()

    def drop(self, ids):
        """Delete the Bernoullis with these ids (a divergence monitor's verdict) from every global hypothesis."""
        ids = np.asarray(ids, dtype=np.int64)
        out = []
        for c in self.clusters:
            gone = np.isin(c.ids, ids)
            if not gone.any():
                out.append(c)
                continue
            if gone.all():
                continue
            R, w, fl = _merge_duplicates(c.rows[:, ~gone], c.lw, c.chosen_flags())
            out.append(Cluster(c.ids[~gone], R, w - _logsumexp(w), _choose(w, fl)))
        self.clusters = out
