"""``filter_batch``: one model over many trajectories, entirely inside numba (prange over the batch)."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from .covariance import pack, unpack
from .filters import measurement_std
from .registry import base_measurement, get_model
from .rts import forward_store, smooth_stored
from .validate import as_float_array, positive_vector, spd_matrix

__all__ = ["filter_batch", "step_lengths", "batch_kernel", "SOA_MIN_BATCH", "SERIAL_STEPS"]

# batches of at most this many trajectory-steps run through the serial ``run_one`` kernel trajectory by
# trajectory (the same numbers): below it numba's threads cost more than they save, and a command that
# only filters small batches (the study: 100 x 100 per call) never compiles the parallel kernel (~1 s a model)
SERIAL_STEPS = 1 << 15


#: from this many trajectories on, filter_batch runs the SIMD kernel run_batch_soa_<meas> (trajectories in the vector
#: lanes, blocks of 64; derive/codegen/soa.py; ~3.5× faster per trajectory-step than the scalar batch here); below,
#: the scalar run_batch_<meas> (prange over trajectories).  The SIMD kernel costs ~15 s of compilation per model and
#: measurement on its first use (cached after), which only a large batch repays: the Monte Carlo study's 100
#: trajectories per point stay on the scalar kernel, so a first ``lgekf study`` does not compile it
SOA_MIN_BATCH = 1000


def batch_kernel(spec, measurement: str, B: int):
    """The loop filter_batch runs for ``B`` trajectories: ``run_batch_soa_<meas>`` where generated and
    B ≥ SOA_MIN_BATCH, else ``run_batch_<meas>``; both take the same arguments and agree to 1e-12."""
    soa = spec.kernel("run_batch_soa", measurement, default=False) or None
    if soa is not None and B >= SOA_MIN_BATCH:
        return soa
    return spec.kernel("run_batch", measurement)


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


def measurements_array(z, m: int) -> np.ndarray:
    """z as a contiguous (B, K, m) float array; NaN marks a missed detection, ±inf is rejected."""
    try:
        a = np.array(z, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"z: expected numbers, got {type(z).__name__}") from None
    if a.ndim != 3 or a.shape[2] != m:
        raise ValueError(f"z: expected shape (B, K, {m}), got {a.shape}")
    if np.any(np.isinf(a)):
        raise ValueError("z: contains infinite values (use NaN for a missed detection)")
    return np.ascontiguousarray(a)


def filter_batch(model: str, z: ArrayLike, *, dt: float | ArrayLike, accel_std: ArrayLike, meas_std: float | ArrayLike,
                 x0: ArrayLike, P0: ArrayLike, measurement: str | None = None, return_cov: bool = False,
                 return_nis: bool = False, smooth: bool = False) -> np.ndarray | tuple[np.ndarray, ...]:
    """Run ``model`` over a batch of measurement sequences.

    Parameters
    ----------
    model : str
        A registry model name ("se2se2", "se2r3", "se2r2", "ctrv", "cv"; in 3-D "se3r6", "ct3", "cv3", ...).
    z : array_like, (B, K, m)
        Measurements: (x, y) for ``measurement="position"``, (x, y, θ) for ``"pose"``. Step k is predicted
        by dt then updated with z[:, k]; a row containing NaN is a missed detection (predict only, NIS NaN).
    dt : float or array_like
        Step length: a number, (K,) or (B, K).
    accel_std, meas_std : array_like
        As for the filter classes (``meas_std`` one number for position, three for pose).
    x0 : array_like, (B, n)
        Initial states in physical coordinates (the estimate at time 0, before z[:, 0]).
    P0 : array_like, (n, n) or (B, n, n)
        Initial covariances in the filter's coordinates.
    measurement : str, optional
        ``"position"``, ``"pose"``, ``"position3"`` (a 3-D model's (x, y, z)); default: the position measurement of the
        model's space.
    return_cov, return_nis : bool
        Also return the covariances (B, K, n, n) and the NIS of every update (B, K).
    smooth : bool
        Also run the Rauch–Tung–Striebel backward pass on the group (``lgekf.estimators.smoother``) and
        return the smoothed states (B, K, n) (and, with ``return_cov``, their covariances (B, K, n, n)),
        after the filter's outputs. Missed detections (NaN rows) are smoothed like any other step.

    Notes
    -----
    From ``SOA_MIN_BATCH`` (1000) trajectories on the SIMD kernel runs (trajectories in the vector lanes), below it the
    scalar prange kernel (``batch_kernel``); the two agree to 1e-12.

    Returns
    -------
    states : ndarray, (B, K, n)
        Posterior physical states; followed by the covariances and/or NIS when asked for, then with
        ``smooth`` the smoothed states and (with ``return_cov``) the smoothed covariances.
    """
    spec = get_model(model)
    if measurement is None:
        measurement = base_measurement(spec.space)
    n = spec.n
    r = measurement_std(spec, measurement, meas_std)
    m = spec.measurement(measurement).dim
    z = measurements_array(z, m)
    B, K = z.shape[:2]
    dts = step_lengths(dt, B, K)
    q = positive_vector("accel_std", accel_std, len(spec.noise_names))
    x0 = np.ascontiguousarray(as_float_array("x0", x0, (B, n)))
    spec.check_state("x0", x0)
    P0 = spd_matrix("P0", P0, n, batch=True)
    if P0.ndim == 3 and P0.shape[0] != B:
        raise ValueError(f"P0: expected ({n}, {n}) or ({B}, {n}, {n}) for {B} trajectories, got {P0.shape}")
    p0 = pack(np.broadcast_to(P0, (B, n, n)))
    if smooth:
        return _filter_and_smooth(spec, measurement, z, dts, q, r, x0, p0, return_cov, return_nis)
    out_x = np.empty((B, K, n))
    out_p = np.empty((B, K if return_cov else 0, spec.n_packed))
    out_nis = np.empty((B, K))
    if B * K <= SERIAL_STEPS:  # small work: the serial kernel, no thread start-up, no parallel kernel to compile
        one = spec.kernel("run_one", measurement)
        for b in range(B):
            one(z[b], dts[b], x0[b], p0[b], q, r, out_x[b], out_p[b], out_nis[b])
    else:
        batch_kernel(spec, measurement, B)(z, dts, x0, p0, q, r, out_x, out_p, out_nis)
    result = [out_x]
    if return_cov:
        result.append(unpack(out_p, n))
    if return_nis:
        result.append(out_nis)
    return result[0] if len(result) == 1 else tuple(result)


def _filter_and_smooth(spec, measurement, z, dts, q, r, x0, p0, return_cov, return_nis):
    """filter_batch(..., smooth=True): the storing forward pass, then the backward pass."""
    fp = forward_store(spec, measurement, z, dts, x0, p0, q, r)
    x_f = fp.x_filt
    x_s, _, p_s = smooth_stored(spec, fp, covariances=return_cov)
    result = [x_f]
    if return_cov:
        result.append(unpack(fp.states()[3], spec.n))
    if return_nis:
        result.append(fp.nis)
    result.append(x_s)
    if return_cov:
        result.append(unpack(p_s, spec.n))
    return tuple(result)
