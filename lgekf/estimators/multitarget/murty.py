"""The k best assignments of a rectangular cost matrix: Murty's algorithm.

K. G. Murty, "An algorithm for ranking all the assignments in order of increasing cost", Operations Research
16(3), 1968; in the form of Cox & Miller, "On finding ranked assignments with application to multitarget
tracking and motion correspondence", IEEE TAES 31(1), 1995: the best assignment partitions the remaining solution
space into subproblems, the i-th forcing the first i − 1 pairs of the solution and forbidding its i-th pair; the
best subproblem solution is the next-best assignment and is partitioned in turn.

Each subproblem's best assignment is the shortest augmenting path algorithm of Crouse, "On implementing 2D
rectangular assignment algorithms", IEEE TAES 52(4), 2016 (``best_assignment``, numba): the algorithm of scipy's
``linear_sum_assignment``, transcribed step by step (its ties broken the same way: the same assignments).

Every row must be assigned to a distinct column; forbidden pairs have cost +inf. The PMBM update
(``lgekf.estimators.multitarget.pmbm``, ``global_hypotheses``) calls ``k_best_into`` with detections as rows and
one column per (Bernoulli, new target) choice.
"""

from __future__ import annotations

import heapq

import numba as nb
import numpy as np

__all__ = ["k_best_assignments", "k_best_into", "best_assignment"]


@nb.njit(cache=True)
def best_assignment(cost, col4row):
    """The least-cost assignment of every row of ``cost`` (R, C), R ≤ C (+inf = forbidden), written to col4row (R,);
    returns its cost, +inf when infeasible (Crouse 2016, Algorithm 1: one shortest augmenting path per row with the
    dual variables u, v; scipy's ``rectangular_lsap.cpp``)."""
    R, C = cost.shape
    inf = np.inf
    u = np.zeros(R)
    v = np.zeros(C)
    shortest = np.empty(C)
    path = np.full(C, -1, dtype=np.int64)
    row4col = np.full(C, -1, dtype=np.int64)
    col4row[:] = -1
    SR = np.zeros(R, dtype=np.bool_)
    SC = np.zeros(C, dtype=np.bool_)
    remaining = np.empty(C, dtype=np.int64)
    for cur in range(R):
        # the shortest augmenting path from row cur (Dijkstra on the reduced costs)
        min_val = 0.0
        n_rem = C
        for it in range(C):
            remaining[it] = C - it - 1
        SR[:] = False
        SC[:] = False
        shortest[:] = inf
        sink = -1
        i = cur
        while sink == -1:
            index = -1
            lowest = inf
            SR[i] = True
            for it in range(n_rem):
                j = remaining[it]
                r = min_val + cost[i, j] - u[i] - v[j]
                if r < shortest[j]:
                    path[j] = i
                    shortest[j] = r
                # among equal minima prefer a free column (a new sink)
                if shortest[j] < lowest or (shortest[j] == lowest and row4col[j] == -1):
                    lowest = shortest[j]
                    index = it
            min_val = lowest
            if min_val == inf:
                return inf
            j = remaining[index]
            if row4col[j] == -1:
                sink = j
            else:
                i = row4col[j]
            SC[j] = True
            n_rem -= 1
            remaining[index] = remaining[n_rem]
        # dual update
        u[cur] += min_val
        for i in range(R):
            if SR[i] and i != cur:
                u[i] += min_val - shortest[col4row[i]]
        for j in range(C):
            if SC[j]:
                v[j] -= min_val - shortest[j]
        # augment along the path
        j = sink
        while True:
            i = path[j]
            row4col[j] = i
            j, col4row[i] = col4row[i], j
            if i == cur:
                break
    total = 0.0
    for i in range(R):
        total += cost[i, col4row[i]]
    return total


@nb.njit(cache=True)
def k_best_into(cost, k, sols, costs):
    """Murty's k best assignments of ``cost`` (R, C), R ≤ C, written to sols (≥ k, R) and costs (≥ k) in increasing
    cost (ties in the order found); returns how many (fewer than k when fewer feasible assignments exist)."""
    R = cost.shape[0]
    col = np.empty(R, dtype=np.int64)
    first = best_assignment(cost, col)
    if not np.isfinite(first) or k < 1:
        return 0
    heap = [(first, 0)]
    subs = [cost.copy()]
    found = [col.copy()]
    n = 0
    while len(heap) > 0 and n < k:
        c, idx = heapq.heappop(heap)
        sol = found[idx]
        sols[n, :] = sol
        costs[n] = c
        n += 1
        if n == k:
            break
        # partition: subproblem i keeps pairs 0..i-1 of sol forced, forbids pair i
        forced = subs[idx].copy()
        for i in range(R):
            child = forced.copy()
            child[i, sol[i]] = np.inf
            got = best_assignment(child, col)
            if np.isfinite(got):
                heapq.heappush(heap, (got, len(subs)))
                subs.append(child)
                found.append(col.copy())
            # force pair i in the next subproblems: row i only to sol[i], column sol[i] only to row i
            keep = forced[i, sol[i]]
            forced[i, :] = np.inf
            forced[:, sol[i]] = np.inf
            forced[i, sol[i]] = keep
    return n


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
    k = int(k)
    if k < 1:
        return []
    sols = np.empty((k, cost.shape[0]), dtype=np.int64)
    costs = np.empty(k)
    n = k_best_into(np.ascontiguousarray(cost), k, sols, costs)
    return [(sols[i].copy(), float(costs[i])) for i in range(n)]
