"""GOSPA (α = 2) against hand-computed cases, and track switches."""

from __future__ import annotations

import doctest
import math

import numpy as np
import pytest

from lgekf.experiments import gospa as gospa_module
from lgekf.experiments.gospa import gospa, gospa_tracks, track_switches


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


# ---------------------------------------------------------------------------------------------------------------------
# over a sequence of scans, from tables (lgekf.gospa)

def _hand_case():
    """Two truths over three scans; track 5 follows truth 1 at 0.5 m; truth 2 is held by track 6, lost at t = 1 (when
    a false track 9 appears), then held by track 7 (one switch). Track rows carry up to 10 ms of time jitter; a row at
    t = 5 is outside every scan."""
    truth = {"id": [1, 1, 1, 2, 2, 2], "t": [0.0, 1.0, 2.0, 0.0, 1.0, 2.0],
             "x": [0.0, 1.0, 2.0, 10.0, 11.0, 12.0], "y": [0.0] * 6}
    tracks = {"id": [5, 5, 5, 6, 9, 7, 7], "t": [0.01, 0.99, 2.0, 0.0, 1.0, 2.01, 5.0],
              "x": [0.0, 1.0, 2.0, 10.0, 50.0, 12.0, 13.0], "y": [0.5, 0.5, 0.5, 1.0, 50.0, 0.75, 0.0]}
    return tracks, truth


def test_gospa_tracks_against_a_hand_computed_sequence():
    import lgekf

    g = lgekf.gospa(*_hand_case(), c=2.0, p=2.0)
    # scan 0: 0.5² + 1²; scan 1: 0.5² + one missed (2²/2) + one false (2²/2); scan 2: 0.5² + 0.75²
    want = [1.25, 0.25 + 2.0 + 2.0, 0.25 + 0.5625]
    assert g.t.tolist() == [0.0, 1.0, 2.0]
    assert g.distance == pytest.approx(np.sqrt(want))
    assert g.localisation == pytest.approx([1.25, 0.25, 0.8125])
    assert g.missed.tolist() == [0.0, 2.0, 0.0] and g.false.tolist() == [0.0, 2.0, 0.0]
    assert g.n_missed.tolist() == [0, 1, 0] and g.n_false.tolist() == [0, 1, 0]
    assert g.switches == 1  # truth 2: track 6, then track 7
    s = g.summary()
    assert s["gospa"] == pytest.approx(np.mean(np.sqrt(want))) and s["n_missed"] == 1 and s["scans"] == 3
    assert "1 track switches" in str(g) and list(g.frame().columns)[:2] == ["t", "gospa"]


def test_gospa_tracks_reads_files_and_frames_alike(tmp_path):
    import pandas as pd

    tracks, truth = _hand_case()
    pd.DataFrame(tracks).to_csv(tmp_path / "tracks.csv", index=False)
    renamed = pd.DataFrame(truth).rename(columns={"id": "object", "t": "time"})
    a = gospa_tracks(tmp_path / "tracks.csv", renamed, c=2.0, truth_columns=("object", "time", "x", "y"))
    b = gospa_tracks(pd.DataFrame(tracks), truth, c=2.0)
    assert a.distance.tolist() == b.distance.tolist() and a.switches == b.switches == 1


def test_gospa_tracks_tolerance_and_bad_input():
    tracks, truth = _hand_case()
    tight = gospa_tracks(tracks, truth, c=2.0, tolerance=0.0)  # the jittered rows (track 5 at 0.01, 0.99; 7 at 2.01) are left out
    assert tight.n_missed.tolist() == [1, 2, 1]
    with pytest.raises(ValueError, match="no column 'id'"):
        gospa_tracks({k: v for k, v in tracks.items() if k != "id"}, truth)
    with pytest.raises(ValueError, match="column 'x' is not finite in row 2"):
        gospa_tracks(dict(tracks, x=[0.0, np.nan, 2.0, 10.0, 50.0, 12.0, 13.0]), truth)
    with pytest.raises(ValueError, match="track 5 has more than one row at the scan t = 0.0"):
        gospa_tracks(dict(tracks, t=[0.0, 0.01, 2.0, 0.0, 1.0, 2.01, 5.0]), truth)
    with pytest.raises(ValueError, match="c > 0"):
        gospa_tracks(tracks, truth, c=0.0)
    with pytest.raises(ValueError, match="cannot read"):
        gospa_tracks("/nonexistent/tracks.csv", truth)


def test_gospa_tracks_reads_the_track_column_of_multi_output():
    """`lgekf track --multi` names its ids `track`: the default columns read it when there is no `id`."""
    truth = {"id": [1, 1], "t": [0.0, 1.0], "x": [0.0, 1.0], "y": [0.0, 0.0]}
    multi = {"track": [7, 7], "t": [0.0, 1.0], "x": [0.75, 1.75], "y": [1.0, 1.0]}
    assert gospa_tracks(multi, truth, c=2, p=2).distance.tolist() == [1.25, 1.25]
    with pytest.raises(ValueError, match="no column 'id'"):
        gospa_tracks({"obj": [7], "t": [0.0], "x": [0.0], "y": [0.0]}, truth)
