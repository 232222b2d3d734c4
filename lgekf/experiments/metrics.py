"""Accuracy and consistency: position RMSE, NEES (estimation error vs P) and NIS (from the updates).

NEES uses each filter's own coordinates: the error ε = [log(μ⁻¹ X_true)]^∨ (generated ``tangent_error``;
for the Euclidean models the difference of the state vectors, angles wrapped). For a consistent filter
the mean NEES is n (the state dimension) and the mean NIS is m (the measurement dimension).
"""

from __future__ import annotations

import numpy as np

from ..core.registry import get_model

__all__ = ["position_rmse", "nees"]


def position_rmse(est, truth_xy, dim: int = 2) -> np.ndarray:
    """Per-trajectory RMSE of the position (the first ``dim`` coordinates: 2 in the plane, 3 in space):
    est (B, K, >=dim), truth_xy (B, K, >=dim) -> (B,)."""
    est = np.asarray(est, float)
    truth_xy = np.asarray(truth_xy, float)
    return np.sqrt(np.mean(np.sum((est[..., :dim] - truth_xy[..., :dim]) ** 2, axis=-1), axis=-1))


def nees(model: str, est, cov, truth) -> np.ndarray:
    """NEES of every estimate: est (..., n) physical states of ``model``, cov (..., n, n) its P,
    truth (..., 6) common physical states (x, y, θ, v_x, v_y, ω) -> (...)."""
    spec = get_model(model)
    k = spec.kernels
    est = np.asarray(est, float)
    cov = np.asarray(cov, float)
    truth = np.asarray(truth, float)
    flat_e = est.reshape(-1, spec.n)
    flat_t = truth.reshape(-1, 6)
    err = np.empty_like(flat_e)
    for i, (e, t) in enumerate(zip(flat_e, flat_t)):
        err[i] = k.tangent_error(k.state_from_physical(e), t)
    err = err.reshape(est.shape)
    sol = np.linalg.solve(cov, err[..., None])[..., 0]
    return np.einsum("...i,...i->...", err, sol)
