"""The k best assignments of a rectangular cost matrix: Murty's algorithm.

K. G. Murty, "An algorithm for ranking all the assignments in order of increasing cost", Operations Research
16(3), 1968; in the form of Cox & Miller, "On finding ranked assignments with application to multitarget
tracking and motion correspondence", IEEE TAES 31(1), 1995: the best assignment (``linear_sum_assignment``)
partitions the remaining solution space into subproblems, the i-th forcing the first i − 1 pairs of the solution
and forbidding its i-th pair; the best subproblem solution is the next-best assignment and is partitioned in turn.

Every row must be assigned to a distinct column; forbidden pairs have cost +inf. The PMBM update
(``lgekf.estimators.multitarget.pmbm``) calls it with detections as rows and one column per (Bernoulli, new
target) choice.
"""

from __future__ import annotations

import heapq

import numpy as np
from scipy.optimize import linear_sum_assignment

__all__ = ["k_best_assignments"]


def _best(cost: np.ndarray):
    """The least-cost assignment of every row of ``cost`` (inf = forbidden) and its cost; None when infeasible."""
    if cost.shape[0] == 0:
        return np.zeros(0, dtype=np.int64), 0.0
    try:
        rows, cols = linear_sum_assignment(cost)
    except ValueError:  # scipy: "cost matrix is infeasible"
        return None
    total = float(cost[rows, cols].sum())
    if not np.isfinite(total):
        return None
    out = np.empty(cost.shape[0], dtype=np.int64)
    out[rows] = cols
    return out, total


def k_best_assignments(cost, k: int) -> list[tuple[np.ndarray, float]]:
    """The k least-cost assignments of the rows of ``cost`` (R, C), R ≤ C, each row to a distinct column.

    Parameters
    ----------
    cost : array_like, (R, C)
        Costs; +inf marks a forbidden pair.
    k : int
        How many assignments (at most).

    Returns
    -------
    list of (ndarray of int (R,), float)
        The column of each row and the total cost, in increasing cost (ties in the order found); fewer than k when
        fewer feasible assignments exist, none when there is none.
    """
    cost = np.array(cost, dtype=float)
    if cost.ndim != 2 or cost.shape[0] > cost.shape[1]:
        raise ValueError(f"k_best_assignments: expected a cost matrix (R, C) with R ≤ C, got shape {cost.shape}")
    R = cost.shape[0]
    first = _best(cost)
    if first is None or k < 1:
        return []
    out = []
    heap = [(first[1], 0, first[0], cost)]
    counter = 1
    while heap and len(out) < k:
        c, _, sol, sub = heapq.heappop(heap)
        out.append((sol, c))
        if len(out) == k:
            break
        # partition: subproblem i keeps pairs 0..i-1 of sol forced, forbids pair i
        forced = sub.copy()
        for i in range(R):
            child = forced.copy()
            child[i, sol[i]] = np.inf
            got = _best(child)
            if got is not None:
                heapq.heappush(heap, (got[1], counter, got[0], child))
                counter += 1
            # force pair i in the next subproblems: row i only to sol[i], column sol[i] only to row i
            keep = forced[i, sol[i]]
            forced[i, :] = np.inf
            forced[:, sol[i]] = np.inf
            forced[i, sol[i]] = keep
    return out
