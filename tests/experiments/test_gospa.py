"""GOSPA (α = 2) against hand-computed cases, and track switches."""

from __future__ import annotations

import doctest
import math

import numpy as np
import pytest

from lgekf.experiments import gospa as gospa_module
from lgekf.experiments.gospa import gospa, track_switches


def test_empty_sets():
    g = gospa(np.zeros((0, 2)), np.zeros((0, 2)))
    assert g.distance == 0.0 and g.n_missed == 0 and g.n_false == 0


def test_only_missed_and_only_false():
    # two truths, nothing estimated: 2 · c^p / 2 = c^p -> GOSPA = c
    g = gospa(np.array([[0.0, 0.0], [5.0, 5.0]]), np.zeros((0, 2)), c=4.0, p=2)
    assert (g.n_missed, g.n_false) == (2, 0)
    assert g.missed == pytest.approx(16.0) and g.distance == pytest.approx(4.0)
    g = gospa(np.zeros((0, 2)), np.array([[1.0, 1.0]]), c=4.0, p=1)
    assert g.false == pytest.approx(2.0) and g.distance == pytest.approx(2.0)


def test_one_pair_inside_and_beyond_the_cut_off():
    g = gospa(np.array([[0.0, 0.0]]), np.array([[3.0, 4.0]]), c=10.0, p=2)
    assert g.distance == pytest.approx(5.0) and g.localisation == pytest.approx(25.0) and g.assignment == [(0, 0)]
    g = gospa(np.array([[0.0, 0.0]]), np.array([[6.0, 8.0]]), c=5.0, p=2)  # d = 10 ≥ c: missed + false
    assert (g.n_missed, g.n_false, g.assignment) == (1, 1, [])
    assert g.distance == pytest.approx(math.sqrt(25 / 2 + 25 / 2))


def test_optimal_assignment_beats_greedy():
    """Greedy nearest pairing takes (x1, y0) at distance 1 and leaves x0–y1 at distance 9; the optimum pairs
    x0–y0 (2) and x1–y1 (2): 4 + 4 = 8 < 1 + 81."""
    X = np.array([[0.0, 0.0], [3.0, 0.0]])
    Y = np.array([[2.0, 0.0], [5.0, 0.0]])
    g = gospa(X, Y, c=20.0, p=2)
    assert sorted(g.assignment) == [(0, 0), (1, 1)]
    assert g.distance == pytest.approx(math.sqrt(8.0))


def test_mixed_case_by_hand():
    """3 truths, 2 estimates (one near a truth, one far from all), c = 3, p = 1:
    localisation 1 (pair), missed 2 · 1.5, false 1 · 1.5 -> 1 + 3 + 1.5 = 5.5."""
    X = np.array([[0.0, 0.0], [10.0, 0.0], [20.0, 0.0]])
    Y = np.array([[0.0, 1.0], [50.0, 50.0]])
    g = gospa(X, Y, c=3.0, p=1)
    assert (g.n_missed, g.n_false) == (2, 1)
    assert (g.localisation, g.missed, g.false) == pytest.approx((1.0, 3.0, 1.5))
    assert g.distance == pytest.approx(5.5)


def test_bad_parameters():
    with pytest.raises(ValueError, match="c > 0"):
        gospa(np.zeros((1, 2)), np.zeros((1, 2)), c=0.0)
    with pytest.raises(ValueError, match="p >= 1"):
        gospa(np.zeros((1, 2)), np.zeros((1, 2)), p=0.5)


def test_track_switches():
    assert track_switches([]) == 0
    assert track_switches([{0: 1, 1: 2}, {0: 2, 1: 1}]) == 2  # a swap is two switches
    assert track_switches([{0: 1}, {}, {0: 1}, {0: 3}, {0: 1}]) == 2


def test_docstring_examples_run():
    res = doctest.testmod(gospa_module, extraglobs={"np": np})
    assert res.attempted > 0 and res.failed == 0
