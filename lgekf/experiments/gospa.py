"""GOSPA, the generalised optimal sub-pattern assignment metric (Rahmathullah, García-Fernández & Svensson,
"Generalized optimal sub-pattern assignment metric", FUSION 2017), with α = 2, and track switches.

For truth positions X (n_x) and estimates Y (n_y), cut-off c > 0 and order p ≥ 1:

    GOSPA^p = min over assignments γ ⊆ {1..n_x}×{1..n_y} with d(x, y) < c of
              Σ_(i,j)∈γ d(x_i, y_j)^p  +  c^p/2 · (n_x − |γ|)  +  c^p/2 · (n_y − |γ|)

(the localisation, missed and false parts; α = 2 makes a pair at distance ≥ c cost the same as one
missed and one false object, so the optimum is a linear assignment of min(d, c)^p, solved with
``scipy.optimize.linear_sum_assignment``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import linear_sum_assignment

__all__ = ["GospaParts", "gospa", "track_switches"]


@dataclass
class GospaParts:
    """One GOSPA evaluation.

    Attributes
    ----------
    distance : float
        GOSPA (the p-th root of the sum of the parts).
    localisation : float
        Σ d^p over the assigned pairs.
    missed : float
        c^p/2 times the number of missed truths.
    false : float
        c^p/2 times the number of false estimates.
    n_missed, n_false : int
        The counts.
    assignment : list of (int, int)
        The assigned (truth index, estimate index) pairs (d < c).
    """

    distance: float
    localisation: float
    missed: float
    false: float
    n_missed: int
    n_false: int
    assignment: list


def gospa(truth: np.ndarray, estimates: np.ndarray, c: float = 10.0, p: float = 2.0) -> GospaParts:
    """GOSPA (α = 2) between truth positions (n_x, d) and estimated positions (n_y, d).

    Parameters
    ----------
    truth : ndarray, (n_x, d)
        True object positions.
    estimates : ndarray, (n_y, d)
        Estimated positions.
    c : float
        Cut-off distance (m) > 0.
    p : float
        Order ≥ 1.

    Returns
    -------
    GospaParts
        The distance, its three parts and the assignment.

    Examples
    --------
    >>> g = gospa(np.array([[0.0, 0.0], [10.0, 0.0]]), np.array([[3.0, 4.0]]), c=10, p=2)
    >>> g.localisation, g.missed, g.false, g.distance   # 5² + 10²/2 (one missed)
    (25.0, 50.0, 0.0, 8.660254037844387)
    """
    if not c > 0 or not p >= 1:
        raise ValueError(f"gospa: need c > 0 and p >= 1, got c = {c}, p = {p}")
    X = np.asarray(truth, dtype=float).reshape(len(truth), -1) if len(truth) else np.zeros((0, 2))
    Y = np.asarray(estimates, dtype=float).reshape(len(estimates), -1) if len(estimates) else np.zeros((0, 2))
    half = c**p / 2.0
    pairs = []
    loc = 0.0
    if X.shape[0] and Y.shape[0]:
        d = np.sqrt(((X[:, None, :] - Y[None, :, :]) ** 2).sum(-1))
        cost = np.minimum(d, c) ** p
        ri, ci = linear_sum_assignment(cost)
        for i, j in zip(ri, ci):
            if d[i, j] < c:
                pairs.append((int(i), int(j)))
                loc += d[i, j] ** p
    nm = X.shape[0] - len(pairs)
    nf = Y.shape[0] - len(pairs)
    total = loc + half * (nm + nf)
    return GospaParts(float(total ** (1.0 / p)), float(loc), float(half * nm), float(half * nf), nm, nf, pairs)


def track_switches(assigned_ids: list) -> int:
    """Track switches: the number of times a truth's assigned track id changes to a different id.

    Parameters
    ----------
    assigned_ids : list of dict
        Per scan, {truth id: track id} of the truths that have an assigned track (e.g. the GOSPA
        assignment). A scan without an assignment for a truth does not reset it: losing a track and
        being found again by the same id is no switch; by another id it is one.

    Returns
    -------
    int

    Examples
    --------
    >>> track_switches([{0: 5}, {0: 5}, {}, {0: 7}, {0: 7, 1: 2}])
    1
    """
    last: dict = {}
    n = 0
    for scan in assigned_ids:
        for truth, trk in scan.items():
            if truth in last and last[truth] != trk:
                n += 1
            last[truth] = trk
    return n
