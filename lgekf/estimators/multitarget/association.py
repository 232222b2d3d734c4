"""Data association of unlabelled detections to tracks, with clutter and missed detections: PDA, JPDA
(JIPDA with track existence) and GNN, all from the same factor weights.

Model (every scan): each existing target is detected with probability P_D, its detection falls in its
gate d² ≤ γ with probability P_G (``lgekf.estimators.multitarget.gating``); false alarms are a Poisson process of
density κ in the measurement space (``clutter_density``: λ per m² for position measurements; λ/(2π) per
m²·rad for pose, the clutter heading uniform); a track exists with probability r (integrated track
existence, IPDA/JIPDA: Musicki, Evans & Stankovic 1994; Musicki & Evans 2004). The factors of a joint
event θ (each detection from at most one track) are

    w0_i = 1 − r_i P_D P_G                      track i undetected (or not existing),
    W_ij = r_i P_D N(e_ij; 0, S_i) / κ           track i produced detection j (gated pairs only),

and the association marginals p_i0, p_ij (``association_marginals``) are

* ``"pda"``: every track on its own (no sharing constraint): p_ij = W_ij / (w0_i + Σ_j W_ij); with r = 1
  these are the β's of the parametric PDA (Bar-Shalom & Tse 1975);
* ``"jpda"``: joint events over clusters of tracks sharing detections (``lgekf.estimators.multitarget.jpda``: exact
  enumeration up to ``max_events`` events per cluster, loopy belief propagation beyond);
* ``"jpdastar"``: JPDA* (Blom & Bloem, "Probabilistic data association avoiding track coalescence", IEEE TAC 45(2),
  2000): the same joint events, but of the events that detect the same tracks with the same detections (permutations
  of one another) only the most probable enters the sums; JPDA weighs "track 1 took z_a, track 2 z_b" and the
  swapped event alike when two targets are close, pulls both tracks towards the middle and lets them swap
  identities; JPDA* does not (clusters beyond ``max_events`` events: the loopy-belief-propagation JPDA);
* ``"gnn"``: one global nearest-neighbour assignment maximising Π w (scipy's
  ``linear_sum_assignment`` on −log ψ_ij, ψ_ij = W_ij/w0_i, with a "missed" column per track); the
  assigned detection j* then gets p_ij* = W_ij*/(w0_i + W_ij*) (a PDA with the one detection). Given the
  existences r_i (``existence``), a second pass assigns the tracks the first left out to the detections it
  left free, on the weights given that the tracks exist (W_ij/r_i against 1 − P_D P_G = 1 − (1 − w0_i)/r_i),
  and they too get p_ij* = W_ij*/(w0_i + W_ij*). The first pass is the most probable joint event, and in it a
  new track of small existence (r₀ = 0.02 of a one-point start) is "not there" unless r₀ P_D N(e; 0, S)/κ >
  1 − r₀ P_D P_G: with its wide first gate and dense clutter never (on the ETH pedestrians with
  0.01 false alarms per m² one-point GNN confirmed no track at all); the second pass gives such a track the
  detection it would have if it existed and lets the existence recursion weigh it, as JPDA does. A
  confirmed track (r ≈ 1) gets the same weights in both passes: the second assigns it nothing new.

From the marginals (``existence_and_weights``): the existence after the scan
r_i⁺ = Σ_j p_ij + p_i0 · r_i (1 − P_D P_G) / w0_i, and the weights of the state update given that the
target exists, β_ij = p_ij / r_i⁺, β_i0 = 1 − Σ_j β_ij (``lgekf.estimators.multitarget.pda`` applies them).
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np
from scipy.optimize import linear_sum_assignment

from .jpda import MAX_EVENTS, jpda_marginals
from .settings import MARGINAL_ASSOCIATIONS as ASSOCIATIONS

__all__ = ["ASSOCIATIONS", "association_weights", "association_marginals", "existence_and_weights", "gnn_assignment"]

GNN_FORBIDDEN = 1e18


@nb.njit(cache=True)
def association_weights(loglik, gated, live, r, detection_prob, gate_prob, kappa, w0, W):
    """The factor weights w0 (N,) and W (N, M) of the module docstring from the gated log-likelihoods
    log N(e_ij; 0, S_i) (N, M), existence probabilities r (N,), P_D, P_G and the clutter density κ."""
    N, M = loglik.shape
    lk = math.log(kappa)
    for i in range(N):
        if not live[i]:
            w0[i] = 1.0
            for j in range(M):
                W[i, j] = 0.0
            continue
        w0[i] = 1.0 - r[i] * detection_prob * gate_prob
        c = math.log(r[i] * detection_prob) - lk
        for j in range(M):
            W[i, j] = math.exp(loglik[i, j] + c) if gated[i, j] else 0.0


@nb.njit(cache=True)
def _pda_marginals(w0, W, gated, live, p0, P):
    N, M = W.shape
    for i in range(N):
        s = w0[i]
        for j in range(M):
            if gated[i, j]:
                s += W[i, j]
        p0[i] = w0[i] / s if live[i] else 1.0
        for j in range(M):
            P[i, j] = W[i, j] / s if (live[i] and gated[i, j]) else 0.0


def gnn_assignment(w0: np.ndarray, W: np.ndarray, gated: np.ndarray, live: np.ndarray) -> np.ndarray:
    """The global nearest-neighbour assignment: detection index per track (-1: none).

    Maximises Π_i w_{i,θ(i)} over assignments θ with every detection used at most once, i.e. minimises
    Σ −log ψ_{iθ(i)} (ψ_ij = W_ij/w0_i, a missed track costs 0) with ``scipy.optimize.linear_sum_assignment``
    on the tracks and detections that are in some gate.

    Parameters
    ----------
    w0 : ndarray, (N,)
        Weight of "track i not detected".
    W : ndarray, (N, M)
        Weight of "track i produced detection j" (gated pairs).
    gated : ndarray of bool, (N, M)
        Gate membership.
    live : ndarray of bool, (N,)
        Rows in use.

    Returns
    -------
    ndarray of int, (N,)
        The detection of each track, -1 when the track is left unassigned.
    """
    N, M = W.shape
    out = np.full(N, -1, dtype=np.int64)
    g = gated & live[:, None]
    rows = np.flatnonzero(g.any(axis=1))
    cols = np.flatnonzero(g.any(axis=0))
    if rows.size == 0:
        return out
    gs = g[np.ix_(rows, cols)]
    with np.errstate(divide="ignore"):
        cost_det = np.where(gs, -np.log(W[np.ix_(rows, cols)] / w0[rows, None]), GNN_FORBIDDEN)
    nr = rows.size
    miss = np.full((nr, nr), GNN_FORBIDDEN)
    np.fill_diagonal(miss, 0.0)
    ri, ci = linear_sum_assignment(np.hstack([cost_det, miss]))
    for a, b in zip(ri, ci):
        if b < cols.size and gs[a, b]:
            out[rows[a]] = cols[b]
    return out


def association_marginals(method: str, w0: np.ndarray, W: np.ndarray, gated: np.ndarray, live: np.ndarray,
                          max_events: int = MAX_EVENTS, existence: np.ndarray | None = None,
                          ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The association marginals p_i0 and p_ij of every track (see the module docstring).

    Parameters
    ----------
    method : {"jpda", "jpdastar", "pda", "gnn"}
        Joint (tracks share detections), JPDA* (joint, the best permutation only), single-target, or global nearest
        neighbour.
    w0, W, gated, live : ndarray
        The factor weights (N,), (N, M), the gates (N, M) and the rows in use (N,)
        (``association_weights``).
    max_events : int
        JPDA: clusters with more joint events than this (bound Π(1 + n_i)) use loopy belief propagation.
    existence : ndarray, (N,), optional
        GNN: the tracks' existence probabilities r_i (the ones in w0, W): the second pass of the module
        docstring; None: the first pass only.

    Returns
    -------
    p0 : ndarray, (N,)
        Probability that track i produced no detection (or does not exist).
    P : ndarray, (N, M)
        Probability that track i produced detection j.
    exact : ndarray of bool, (N,)
        False where the JPDA marginals are the loopy-belief-propagation approximation.
    """
    N, M = W.shape
    p0 = np.ones(N)
    P = np.zeros((N, M))
    exact = np.ones(N, dtype=bool)
    if method == "pda":
        _pda_marginals(w0, W, gated, live, p0, P)
    elif method in ("jpda", "jpdastar"):
        jpda_marginals(w0, W, gated, live, int(max_events), p0, P, exact, method == "jpdastar")
    elif method == "gnn":
        j = gnn_assignment(w0, W, gated, live)
        left = live & (j < 0)
        if existence is not None and left.any():
            free = np.ones(W.shape[1], dtype=bool)
            free[j[j >= 0]] = False
            r = np.where(left, existence, 1.0)
            second = gnn_assignment(1.0 - (1.0 - w0) / r, W / r[:, None], gated & free[None, :], left)
            j = np.where(left, second, j)
        i = np.flatnonzero(j >= 0)
        w = W[i, j[i]]
        P[i, j[i]] = w / (w0[i] + w)
        p0[i] = w0[i] / (w0[i] + w)
    else:
        raise ValueError(f"association: unknown method {method!r}; choose one of {', '.join(ASSOCIATIONS)}")
    return p0, P, exact


@nb.njit(cache=True)
def existence_and_weights(p0, P, w0, r, live, detection_prob, gate_prob, r_out, beta0, beta):
    """r⁺ = Σ_j p_ij + p_i0 r_i (1 − P_D P_G)/w0_i and the update weights β_ij = p_ij / r⁺,
    β_i0 = 1 − Σ_j β_ij (module docstring), for every live track."""
    N, M = P.shape
    q = 1.0 - detection_prob * gate_prob
    for i in range(N):
        if not live[i]:
            continue
        sp = 0.0
        for j in range(M):
            sp += P[i, j]
        rn = sp + p0[i] * r[i] * q / w0[i]
        rn = min(max(rn, 0.0), 1.0)
        r_out[i] = rn
        sb = 0.0
        for j in range(M):
            beta[i, j] = P[i, j] / rn if rn > 0.0 else 0.0
            sb += beta[i, j]
        beta0[i] = max(1.0 - sb, 0.0)
