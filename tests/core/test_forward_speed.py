"""The forward-speed models (CTRV, SE(2)×R²): the declaration carried into the registry, the data's say on the
direction of motion at a start (``moving_backwards``), and the equivalent start (heading + π, −v)."""

from __future__ import annotations

import numpy as np
import pytest

from lgekf.core.initiation import initial_estimates, moving_backwards, two_point
from lgekf.core.registry import MODELS


def test_the_models_with_a_signed_forward_speed_declare_it():
    declared = {m: s.forward_speed for m, s in MODELS.items() if s.forward_speed}
    assert declared == {"ctrv": (2, 3), "se2r2": (2, 3)}
    for m, (h, v) in declared.items():
        assert h in MODELS[m].angles and MODELS[m].state_names[v] == "v"


def _objects():
    """Four objects, 0.1 m noise free: walking -x with a first step +x (backwards), walking +x, 2 rows only, standing
    (steps of 1 cm, within the noise)."""
    t, z, starts = [], [], [0]
    tt = 0.4 * np.arange(10)
    walk = np.column_stack([10 - 1.3 * tt, np.zeros(10)])
    walk[1, 0] = walk[0, 0] + 0.3
    fwd = np.column_stack([1.3 * tt, np.zeros(10)])
    stand = np.column_stack([0.01 * (-1) ** np.arange(10), np.zeros(10)])
    for p, tk in ((walk, tt), (fwd, tt), (walk[:2], tt[:2]), (stand, tt)):
        t.append(tk)
        z.append(p)
        starts.append(starts[-1] + len(tk))
    return np.concatenate(t), np.concatenate(z), np.array(starts)


def test_moving_backwards_asks_the_chord_of_a_second():
    t, z, starts = _objects()
    assert moving_backwards(t, z, starts, 0.1).tolist() == [True, False, False, False]


@pytest.mark.parametrize("model", ["ctrv", "se2r2"])
def test_the_backward_start_is_the_same_motion_with_the_heading_of_the_data(model):
    t, z, starts = _objects()
    c, var = two_point(t, z, starts[:-1] + 1, 0.1)
    c[:, 5] = 0.3  # a turn rate, so that the motion is not symmetric in the flip by accident
    back = moving_backwards(t, z, starts, 0.1)
    x0, P0 = initial_estimates(model, c, var)
    x1, P1 = initial_estimates(model, c, var, back)
    h, v = MODELS[model].forward_speed
    assert x1[0, v] == pytest.approx(-x0[0, v]) and x1[0, v] < 0
    assert np.cos(x1[0, h] - x0[0, h]) == pytest.approx(-1.0)
    assert np.cos(x1[0, h] - np.pi) > 0.99  # the walker's motion: -x
    np.testing.assert_array_equal(x1[1:], x0[1:])
    k = MODELS[model].kernels
    for dt in (0.4, 2.0):  # the same predicted positions
        p0, p1 = np.empty((len(x0), 2)), np.empty((len(x0), 2))
        k.propagate_positions(np.ascontiguousarray(x0), np.full(len(x0), dt), p0)
        k.propagate_positions(np.ascontiguousarray(x1), np.full(len(x0), dt), p1)
        np.testing.assert_allclose(p1, p0, atol=1e-12)
    # the covariance is kept: the flip changes the sign of v (and for SE(2)×R² of the body-frame position), which
    # have no covariance with the heading and the turn rate nor with each other at a two-point start
    flipped = [v] + ([0, 1] if model == "se2r2" else [])
    other = [i for i in range(MODELS[model].n) if i not in flipped]
    assert np.all(P0[0][np.ix_(flipped, other)] == 0)
    assert P0[0][0, v] == 0 and P0[0][1, v] == 0
    np.testing.assert_array_equal(P1, P0)
