"""Two-point initialisation of a track from two measurements (the rule of ``lgekf track``, documented in
``lgekf.apps.track``'s module docstring): common coordinates c = (x, y, θ, v_x, v_y, ω) and their variances
from two positions, then any model's x0 and P0 through the generated ``common_to_state`` /
``common_jacobian``. Shared by ``lgekf track`` and the multi-target tracker (``lgekf.estimators.tracker``).
"""

from __future__ import annotations

import math

import numpy as np

from .registry import get_model

__all__ = ["two_point", "initial_estimates", "DEFAULT_OMEGA_STD", "DEFAULT_HEADING_STD", "SIDESLIP_FRACTION"]

DEFAULT_OMEGA_STD = 0.5
DEFAULT_HEADING_STD = 0.1
SIDESLIP_FRACTION = 0.1


def two_point(t, z, rows, meas_std, omega_std=DEFAULT_OMEGA_STD, heading=None, heading_std=DEFAULT_HEADING_STD,
              heading_cap=math.pi, first=None):
    """The two-point estimate at each of ``rows`` (R,) from the measurements ``first`` (default rows - 1)
    and rows (the rules of the module docstring): common coordinates c (R, 6) and diagonal variances (R, 6).
    ``meas_std`` is a number or one per row.

    ``heading_cap``: the largest heading std of the prior; the lateral velocity variance the heading does
    not take goes to v_y (π: the rule of the module docstring; ``lgekf track`` uses ``TRACK_HEADING_CAP``).
    """
    i1 = np.asarray(rows, dtype=np.int64)
    i0 = i1 - 1 if first is None else np.asarray(first, dtype=np.int64)
    dt = t[i1] - t[i0]
    v = (z[i1] - z[i0]) / dt[:, None]
    speed = np.hypot(v[:, 0], v[:, 1])
    r2 = meas_std**2
    var_v = 2.0 * r2 / dt**2
    floor_vy = (SIDESLIP_FRACTION**2) * var_v
    B = len(i0)
    c = np.zeros((B, 6))
    c[:, :2] = z[i1]
    var = np.empty((B, 6))
    var[:, 0] = var[:, 1] = r2
    var[:, 3] = var_v
    var[:, 5] = omega_std**2
    if heading is None:
        c[:, 2] = np.where(speed > 0, np.arctan2(v[:, 1], v[:, 0]), 0.0)
        c[:, 3] = speed
        with np.errstate(divide="ignore"):
            var_th = np.minimum(np.where(speed > 0, var_v / np.where(speed > 0, speed, 1.0) ** 2, np.inf), heading_cap**2)
        var[:, 2] = var_th
        var[:, 4] = np.maximum(var_v - speed**2 * var_th, floor_vy)
    else:
        h = heading[i1]
        c[:, 2] = np.arctan2(np.sin(h), np.cos(h))
        c[:, 3] = v[:, 0] * np.cos(h) + v[:, 1] * np.sin(h)
        var[:, 2] = heading_std**2
        var[:, 4] = floor_vy
    return c, var


def initial_estimates(model, c, var):
    """Each object's x0 (B, n) in the model's physical coordinates and P0 (B, n, n) in its filter coordinates."""
    spec = get_model(model)
    k = spec.kernels
    B = c.shape[0]
    x0 = np.empty((B, spec.n))
    J = np.empty((B, spec.n, 6))
    cj = c.copy()
    # the Jacobian of a heading-of-motion coordinate (CTRV's ψ = θ + atan2(v_y, v_x)) is singular at v = 0;
    # evaluate it just off zero
    tiny = 1e-9 * np.sqrt(var[:, 3])
    cj[:, 3] = np.where(np.abs(cj[:, 3]) < tiny, np.where(cj[:, 3] < 0, -tiny, tiny), cj[:, 3])
    k.common_to_states(np.ascontiguousarray(c, dtype=float), x0)  # common_to_state / common_jacobian of every row
    k.common_jacobians(np.ascontiguousarray(cj, dtype=float), J)
    P0 = np.einsum("bij,bj,bkj->bik", J, var, J)
    P0 = 0.5 * (P0 + np.swapaxes(P0, 1, 2))
    for a in spec.angles:
        big = P0[:, a, a] > math.pi**2
        if big.any():
            s = np.ones((int(big.sum()), spec.n))
            s[:, a] = math.pi / np.sqrt(P0[big, a, a])
            P0[big] *= s[:, :, None] * s[:, None, :]
    return x0, P0
