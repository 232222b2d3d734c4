"""Murty's k best assignments against brute-force enumeration of every assignment."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from lgekf.estimators.multitarget.murty import k_best_assignments


def brute_force(cost):
    """Every feasible assignment (row -> distinct column, no inf) and its cost, sorted by cost."""
    R, C = cost.shape
    out = []
    for cols in itertools.permutations(range(C), R):
        c = sum(cost[i, cols[i]] for i in range(R))
        if np.isfinite(c):
            out.append((cols, c))
    return sorted(out, key=lambda x: x[1])


@pytest.mark.parametrize("seed", range(12))
def test_k_best_equals_the_sorted_enumeration(seed):
    rng = np.random.default_rng(seed)
    R = int(rng.integers(1, 4))
    C = int(rng.integers(R, 6))
    cost = rng.normal(size=(R, C)).round(1) if seed % 3 == 0 else rng.normal(size=(R, C))  # rounded: ties
    cost[rng.random((R, C)) < 0.3] = np.inf
    ref = brute_force(cost)
    k = len(ref) + 2
    got = k_best_assignments(cost, k)
    assert len(got) == len(ref)
    np.testing.assert_allclose([c for _, c in got], [c for _, c in ref], atol=1e-12)
    # every assignment found once, each with the cost it claims
    assert len({tuple(a) for a, _ in got}) == len(got)
    for a, c in got:
        assert len(set(a.tolist())) == R
        assert c == pytest.approx(sum(cost[i, a[i]] for i in range(R)))
    # the first k of them for a smaller k
    few = k_best_assignments(cost, 3)
    np.testing.assert_allclose([c for _, c in few], [c for _, c in ref[:3]], atol=1e-12)


def test_infeasible_and_empty():
    cost = np.array([[np.inf, 1.0], [np.inf, 2.0]])  # both rows need column 1
    assert k_best_assignments(cost, 5) == []
    got = k_best_assignments(np.zeros((0, 3)), 4)
    assert len(got) == 1 and got[0][1] == 0.0
    with pytest.raises(ValueError, match="R ≤ C"):
        k_best_assignments(np.zeros((3, 2)), 1)


def test_best_assignment_is_scipys():
    """The compiled shortest augmenting path (a transcription of scipy's) gives scipy's assignment, ties and forbidden
    pairs included, and +inf where scipy finds none."""
    from scipy.optimize import linear_sum_assignment

    from lgekf.estimators.multitarget.murty import best_assignment

    rng = np.random.default_rng(7)
    for t in range(400):
        R = int(rng.integers(1, 6))
        C = int(rng.integers(R, 9))
        cost = rng.normal(size=(R, C))
        if t % 3 == 0:
            cost = cost.round(0)  # many ties
        cost[rng.random((R, C)) < 0.3 * (t % 2)] = np.inf
        col = np.empty(R, dtype=np.int64)
        got = best_assignment(cost, col)
        try:
            rows, ref = linear_sum_assignment(cost)
        except ValueError:  # infeasible
            assert got == np.inf
            continue
        if not np.isfinite(cost[rows, ref].sum()):
            assert got == np.inf
            continue
        np.testing.assert_array_equal(col, ref)
        assert got == pytest.approx(cost[rows, ref].sum(), abs=1e-12)
