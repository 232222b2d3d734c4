"""Two-point initialisation of a track from two measurements (the rule of ``lgekf track``, documented in
``lgekf.apps.track``'s module docstring): common coordinates c = (x, y, θ, v_x, v_y, ω) and their variances
from two positions, then any model's x0 and P0 through the generated ``common_to_state`` /
``common_jacobian``. Shared by ``lgekf track`` and the multi-target tracker (``lgekf.estimators.multitarget.tracker``).

Heading of a forward-speed model (``ModelSpec.forward_speed``: CTRV's ψ, v and SE(2)×R²'s θ, v). Two points give
the heading of their step and v = |step|/Δt ≥ 0. When noise makes that first step point backwards (a slow
pedestrian, a step shorter than the noise), the filter keeps that heading and drives v through zero: v < 0 and the
heading off by π for the rest of the track, although the positions are right. ``moving_backwards`` asks the data:
the chord from an object's first row to its first row at least ``LOOKAHEAD_S`` later (its last row if none) against
the first step (negative dot product) and longer than ``LOOKAHEAD_NOISE`` √2 σ (not noise). For such an object
``initial_estimates`` starts from the equivalent state (heading + π, −v): the same position and world velocity (the
same first prediction), but the heading of the motion, so that the updates bring v up through zero instead of
turning the heading round. Its covariance is the same matrix: the flip changes the sign of the speed coordinate (and
for SE(2)×R² of the body-frame position, a rotation by π), and the two-point P0 has no covariance between those and
the other coordinates (``tests/core/test_forward_speed.py``). The re-initialisations of the divergence monitor start
from a chord at least ``REINIT_BASELINE`` long (``lgekf.apps.track``), whose direction is that of the motion.
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

from ..generated.monitor import initial_covariances, jacobian_points, two_points
from .registry import SPACES, get_model, space_of_positions

__all__ = ["two_point", "initial_estimates", "moving_backwards", "common_size", "attitude_rows", "DEFAULT_OMEGA_STD",
           "DEFAULT_HEADING_STD", "SIDESLIP_FRACTION",
           "LOOKAHEAD_S", "LOOKAHEAD_NOISE"]

DEFAULT_OMEGA_STD = 0.5
DEFAULT_HEADING_STD = 0.1
SIDESLIP_FRACTION = 0.1
LOOKAHEAD_S = 1.0  # the chord that checks the direction of the first step spans at least this long (s)
LOOKAHEAD_NOISE = 3.0  # ... and is longer than this many √2 σ


def two_point(t, z, rows, meas_std, omega_std=DEFAULT_OMEGA_STD, heading=None, heading_std=DEFAULT_HEADING_STD,
              heading_cap=math.pi, first=None):
    """The two-point estimate at each of ``rows`` (R,) from the measurements ``first`` (default rows - 1)
    and rows (the rules of the module docstring): common coordinates c (R, n_c) and diagonal variances (R, n_c) of
    the space of z (N, d): n_c = 6 in the plane, 12 in 3-D (``common_size``; the 3-D rule: the generated
    ``two_point3_into``: yaw = atan2(v_y, v_x), pitch = −atan2(v_z, |v_h|), roll 0). ``meas_std`` is a number or
    one per row; ``heading`` (N,) in the plane, (N, 3) roll, pitch, yaw in 3-D, or None.

    ``heading_cap``: the largest heading std of the prior; the lateral velocity variance the heading does
    not take goes to v_y (π: the rule of the module docstring; ``lgekf track`` uses ``TRACK_HEADING_CAP``).

    One compiled loop (the generated ``two_points``, which the divergence monitor's re-initialisations also call).
    """
    i1 = np.ascontiguousarray(rows, dtype=np.int64)
    i0 = i1 - 1 if first is None else np.ascontiguousarray(first, dtype=np.int64)
    R = i1.shape[0]
    stds = np.ascontiguousarray(np.broadcast_to(np.asarray(meas_std, dtype=float), (R,)))
    nc = common_size(z)
    c = np.empty((R, nc))
    var = np.empty((R, nc))
    h = attitude_rows(heading)
    two_points(np.ascontiguousarray(t, dtype=float), np.ascontiguousarray(z, dtype=float), h, i0, i1, stds, float(omega_std),
               float(heading_std), float(heading_cap), SIDESLIP_FRACTION, c, var)
    return c, var


def common_size(z) -> int:
    """The number of common coordinates of the space of positions z (N, d) (``derive/space.py``: position, attitude,
    velocity, rate): 6 in the plane, 12 in 3-D."""
    return len(SPACES[space_of_positions(np.shape(z)[1])]["common_names"])


def attitude_rows(heading) -> np.ndarray:
    """The measured attitude as the generated ``two_points`` reads it: the heading (N,) in the plane, the (roll, pitch,
    yaw) rows (N, 3) of 3-D space flattened to (3N,); empty for none."""
    return np.empty(0) if heading is None else np.ascontiguousarray(np.asarray(heading, dtype=float).reshape(-1))


@nb.njit(cache=True, nogil=True)
def _backwards(t, z, starts, lookahead, min_chord, out):
    for b in range(starts.shape[0] - 1):
        a, e = starts[b], starts[b + 1]
        out[b] = False
        if e - a < 3:
            continue
        j = a + 2
        while j < e - 1 and t[j] - t[a] < lookahead:
            j += 1
        cx, cy = z[j, 0] - z[a, 0], z[j, 1] - z[a, 1]
        sx, sy = z[a + 1, 0] - z[a, 0], z[a + 1, 1] - z[a, 1]
        out[b] = cx * sx + cy * sy < 0.0 and math.hypot(cx, cy) > min_chord


def moving_backwards(t, z, starts, meas_std) -> np.ndarray:
    """(B,) bool: the objects whose first step (rows 0 → 1) points against their motion, as the chord from row 0 to
    the first row at least ``LOOKAHEAD_S`` later (the last row if none; row 2 at least) says: a negative dot product
    and a chord longer than ``LOOKAHEAD_NOISE`` √2 ``meas_std`` (module docstring). False for objects of 2 rows."""
    starts = np.asarray(starts, dtype=np.int64)
    out = np.zeros(len(starts) - 1, dtype=np.bool_)
    _backwards(np.ascontiguousarray(t, dtype=float), np.ascontiguousarray(np.asarray(z, float)[:, :2]), starts,
               LOOKAHEAD_S, LOOKAHEAD_NOISE * math.sqrt(2.0) * float(meas_std), out)
    return out


def initial_estimates(model, c, var, backwards=None):
    """Each object's x0 (B, n) in the model's physical coordinates and P0 (B, n, n) in its filter coordinates:
    P0 = J diag(var) Jᵀ (J the generated ``common_jacobian``, taken with the speed just off zero, where CTRV's
    heading of motion ψ = θ + atan2(v_y, v_x) is singular), symmetrised, each angle's variance capped at π²
    (the generated ``initial_covariances``).

    ``backwards`` (B,) bool (``moving_backwards``): for a model with a forward speed (``ModelSpec.forward_speed``)
    those objects start from the equivalent state (heading + π, −v) (module docstring); ignored by other models."""
    spec = get_model(model)
    k = spec.kernels
    c = np.ascontiguousarray(c, dtype=float)
    var = np.ascontiguousarray(var, dtype=float)
    B = c.shape[0]
    x0 = np.empty((B, spec.n))
    J = np.empty((B, spec.n, c.shape[1]))
    cj = np.empty_like(c)
    jacobian_points(c, var, cj)
    k.common_to_states(c, x0)  # common_to_state / common_jacobian of every row
    k.common_jacobians(cj, J)
    P0 = np.empty((B, spec.n, spec.n))
    initial_covariances(J, var, np.array(spec.angles, dtype=np.int64), P0)
    if backwards is not None and spec.forward_speed:
        h, v = spec.forward_speed
        bw = np.asarray(backwards, dtype=bool)
        x0[bw, h] = np.arctan2(-np.sin(x0[bw, h]), -np.cos(x0[bw, h]))  # + π, wrapped to (-π, π]
        x0[bw, v] = -x0[bw, v]
    return x0, P0
