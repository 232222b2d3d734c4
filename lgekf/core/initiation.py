"""Two-point initialisation of a track from two measurements (the rule of ``lgekf track``, documented in
``lgekf.apps.track``'s module docstring): common coordinates c = (x, y, θ, v_x, v_y, ω) and their variances
from two positions, then any model's x0 and P0 through the generated ``common_to_state`` /
``common_jacobian``. Shared by ``lgekf track`` and the multi-target tracker (``lgekf.estimators.multitarget.tracker``).
"""

from __future__ import annotations

import math

import numpy as np

from ..generated.monitor import initial_covariances, jacobian_points, two_points
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

    One compiled loop (the generated ``two_points``, which the divergence monitor's re-initialisations also call).
    """
    i1 = np.ascontiguousarray(rows, dtype=np.int64)
    i0 = i1 - 1 if first is None else np.ascontiguousarray(first, dtype=np.int64)
    R = i1.shape[0]
    stds = np.ascontiguousarray(np.broadcast_to(np.asarray(meas_std, dtype=float), (R,)))
    c = np.empty((R, 6))
    var = np.empty((R, 6))
    h = np.empty(0) if heading is None else np.ascontiguousarray(heading, dtype=float)
    two_points(np.ascontiguousarray(t, dtype=float), np.ascontiguousarray(z, dtype=float), h, i0, i1, stds, float(omega_std),
               float(heading_std), float(heading_cap), SIDESLIP_FRACTION, c, var)
    return c, var


def initial_estimates(model, c, var):
    """Each object's x0 (B, n) in the model's physical coordinates and P0 (B, n, n) in its filter coordinates:
    P0 = J diag(var) Jᵀ (J the generated ``common_jacobian``, taken with the speed just off zero, where CTRV's
    heading of motion ψ = θ + atan2(v_y, v_x) is singular), symmetrised, each angle's variance capped at π²
    (the generated ``initial_covariances``)."""
    spec = get_model(model)
    k = spec.kernels
    c = np.ascontiguousarray(c, dtype=float)
    var = np.ascontiguousarray(var, dtype=float)
    B = c.shape[0]
    x0 = np.empty((B, spec.n))
    J = np.empty((B, spec.n, 6))
    cj = np.empty_like(c)
    jacobian_points(c, var, cj)
    k.common_to_states(c, x0)  # common_to_state / common_jacobian of every row
    k.common_jacobians(cj, J)
    P0 = np.empty((B, spec.n, spec.n))
    initial_covariances(J, var, np.array(spec.angles, dtype=np.int64), P0)
    return x0, P0
