"""Forward pass with storage and the RTS backward pass on the group, through the generated kernels.

The derivation of the backward step is in ``lgekf.estimators.smoother``; the kernels (``run_batch_store_<meas>``,
``smooth_batch``, ``smooth_batch_soa``) are emitted by ``derive/codegen/estimators.py`` and
``derive/codegen/smooth_step.py``. This module only allocates and calls them (it sits in ``core`` so that
``filter_batch(..., smooth=True)`` and the filter classes' ``smooth()`` can use it).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .registry import ModelSpec

__all__ = ["ForwardPass", "forward_store", "smooth_stored", "SOA_SMOOTH_MIN_BATCH"]

#: from this many trajectories on, the forward and the backward pass run ``run_batch_store_soa_<meas>`` and
#: ``smooth_batch_soa`` (trajectories in the SIMD lanes; the same numbers to ~1e-14, faster than the scalar prange
#: kernels: benchmarks/bench_smoother.py); together they cost 10-90 s of compilation per model on their first use
#: (cached after), which only a large batch repays
SOA_SMOOTH_MIN_BATCH = 1000


@dataclass
class ForwardPass:
    """What the forward pass keeps, per trajectory b and step k: predicted internal states ``s_pred``
    (B, K, n_int) and packed covariances ``p_pred`` (B, K, n(n+1)/2), the posterior ones ``s_filt``,
    ``p_filt``, the NIS and log det S of each update (NaN at a missed detection), the step lengths and
    the number of valid steps of each trajectory, and the posterior physical states ``x_filt`` (B, K, n)."""

    s_pred: np.ndarray
    p_pred: np.ndarray
    s_filt: np.ndarray
    p_filt: np.ndarray
    nis: np.ndarray
    logdet: np.ndarray
    dts: np.ndarray
    lengths: np.ndarray
    x_filt: np.ndarray


def forward_store(spec: ModelSpec, measurement: str, z, dts, x0, p0, q, r, simd: bool | None = None) -> ForwardPass:
    """Run the filter over z (B, K, m) with dts (B, K), physical x0 (B, n), packed p0 (B, n(n+1)/2), keeping
    every step (``run_batch_store_<measurement>``). ``simd``: run ``run_batch_store_soa_<measurement>``
    (trajectories in the SIMD lanes, the same results to ~1e-14); None: from ``SOA_SMOOTH_MIN_BATCH`` trajectories on."""
    B, K = z.shape[:2]
    ni = len(spec.internal_names)
    fp = ForwardPass(np.empty((B, K, ni)), np.empty((B, K, spec.n_packed)), np.empty((B, K, ni)),
                     np.empty((B, K, spec.n_packed)), np.empty((B, K)), np.empty((B, K)), dts,
                     np.full(B, K, dtype=np.int64), np.empty((B, K, spec.n)))
    if simd is None:
        simd = B >= SOA_SMOOTH_MIN_BATCH
    getattr(spec.kernels, f"run_batch_store{'_soa' if simd else ''}_{measurement}")(
        z, dts, x0, p0, np.asarray(q, dtype=float), np.asarray(r, dtype=float), fp.s_pred, fp.p_pred, fp.s_filt,
        fp.p_filt, fp.nis, fp.logdet, fp.x_filt)
    return fp


def smooth_stored(spec: ModelSpec, fp: ForwardPass, simd: bool | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The RTS backward pass (``smooth_batch``) over a stored forward pass: smoothed physical states
    (B, K, n), internal states (B, K, n_int) and packed covariances (B, K, n(n+1)/2) (entries past a
    trajectory's length are left unset). ``simd``: run ``smooth_batch_soa`` (trajectories in the SIMD lanes,
    the same results to ~1e-14); None: from ``SOA_SMOOTH_MIN_BATCH`` trajectories on."""
    B, K = fp.s_filt.shape[:2]
    s_sm = np.empty_like(fp.s_filt)
    p_sm = np.empty_like(fp.p_filt)
    x_sm = np.full((B, K, spec.n), np.nan)
    if simd is None:
        simd = B >= SOA_SMOOTH_MIN_BATCH
    kernel = spec.kernels.smooth_batch_soa if simd else spec.kernels.smooth_batch
    kernel(fp.dts, fp.s_pred, fp.p_pred, fp.s_filt, fp.p_filt, np.ascontiguousarray(fp.lengths, dtype=np.int64),
                              s_sm, p_sm, x_sm)
    return x_sm, s_sm, p_sm
