"""``filter_batch``: one model over many trajectories, entirely inside numba (prange over the batch)."""

from __future__ import annotations

import numpy as np

from .covariance import pack, unpack
from .registry import get_model
from .validate import as_float_array, positive_scalar, positive_vector, spd_matrix

__all__ = ["filter_batch", "step_lengths"]


def step_lengths(dt, B: int, K: int) -> np.ndarray:
    """dt as a (B, K) array: a scalar, one value per step (K,), or per trajectory and step (B, K)."""
    a = as_float_array("dt", dt)
    if a.ndim == 0:
        a = np.full((B, K), float(a))
    elif a.shape == (K,):
        a = np.ascontiguousarray(np.broadcast_to(a, (B, K)))
    elif a.shape != (B, K):
        raise ValueError(f"dt: expected a number, shape ({K},) or ({B}, {K}), got {a.shape}")
    if np.any(a <= 0):
        raise ValueError("dt: every step length must be positive")
    return a


def filter_batch(model, z, *, dt, accel_std, meas_std, x0, P0, return_cov=False, return_nis=False):
    """Run ``model`` over a batch of measurement sequences.

    Parameters
    ----------
    model : "se2se2", "se2r3", "ctrv" or "cv"
    z : (B, K, 2) position measurements; step k is predicted by dt then updated with z[:, k]
    dt : step length: a number, (K,) or (B, K)
    accel_std, meas_std : as for the filter classes
    x0 : (B, n) initial states in physical coordinates (the estimate at time 0, before z[:, 0])
    P0 : (n, n) or (B, n, n) initial covariances in the filter's coordinates

    Returns
    -------
    states (B, K, n) posterior physical states; with ``return_cov`` also covariances (B, K, n, n);
    with ``return_nis`` also the NIS of every update (B, K).
    """
    spec = get_model(model)
    n = spec.n
    z = np.ascontiguousarray(as_float_array("z", z, (None, None, 2)))
    B, K = z.shape[:2]
    dts = step_lengths(dt, B, K)
    q = positive_vector("accel_std", accel_std, len(spec.noise_names))
    r = positive_scalar("meas_std", meas_std)
    x0 = np.ascontiguousarray(as_float_array("x0", x0, (B, n)))
    spec.check_state("x0", x0)
    P0 = spd_matrix("P0", P0, n, batch=True)
    if P0.ndim == 3 and P0.shape[0] != B:
        raise ValueError(f"P0: expected ({n}, {n}) or ({B}, {n}, {n}) for {B} trajectories, got {P0.shape}")
    p0 = pack(np.broadcast_to(P0, (B, n, n)))
    out_x = np.empty((B, K, n))
    out_p = np.empty((B, K if return_cov else 0, spec.n_packed))
    out_nis = np.empty((B, K))
    spec.kernels.run_batch(z, dts, x0, p0, q, r, out_x, out_p, out_nis)
    result = [out_x]
    if return_cov:
        result.append(unpack(out_p, n))
    if return_nis:
        result.append(out_nis)
    return result[0] if len(result) == 1 else tuple(result)
