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

__all__ = ["ForwardPass", "forward_store", "smooth_stored", "unblock", "SOA_SMOOTH_MIN_BATCH"]

#: from this many trajectories on, the forward and the backward pass run ``run_batch_store_soa_<meas>`` and
#: ``smooth_batch_soa`` (trajectories in the SIMD lanes; the same numbers to ~1e-14, faster than the scalar prange
#: kernels: benchmarks/bench_smoother.py); together they cost 10-90 s of compilation per model on their first use
#: (cached after), which only a large batch repays
SOA_SMOOTH_MIN_BATCH = 1000
#: trajectories per block of the SIMD kernels (derive/codegen/soa.py LANES)
LANES = 64


@dataclass
class ForwardPass:
    """What the forward pass keeps, per trajectory b and step k: predicted internal states ``s_pred``
    (B, K, n_int) and packed covariances ``p_pred`` (B, K, n(n+1)/2), the posterior ones ``s_filt``,
    ``p_filt``, the NIS and log det S of each update (NaN at a missed detection), the step lengths and
    the number of valid steps of each trajectory, and the posterior physical states ``x_filt`` (B, K, n).

    A pass run in the SIMD lanes keeps the four state arrays in blocks instead (``blocks`` = (Qb, Fb), each
    (⌈B / LANES⌉, K, n_int + n(n+1)/2, LANES), the layout ``smooth_batch_soa`` reads) and has them None;
    :meth:`states` gives them in either case."""

    s_pred: np.ndarray | None
    p_pred: np.ndarray | None
    s_filt: np.ndarray | None
    p_filt: np.ndarray | None
    nis: np.ndarray
    logdet: np.ndarray
    dts: np.ndarray
    lengths: np.ndarray
    x_filt: np.ndarray
    blocks: tuple | None = None

    def states(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """(s_pred, p_pred, s_filt, p_filt), unpacked from ``blocks`` when the pass ran in SIMD lanes."""
        if self.blocks is None:
            return self.s_pred, self.p_pred, self.s_filt, self.p_filt
        B = self.x_filt.shape[0]
        ni = self.blocks[0].shape[2] - _n_packed_of(self.x_filt.shape[2])
        q, f = (unblock(a, B) for a in self.blocks)
        return q[..., :ni], q[..., ni:], f[..., :ni], f[..., ni:]


def _n_packed_of(n: int) -> int:
    return n * (n + 1) // 2


def unblock(a: np.ndarray, B: int) -> np.ndarray:
    """A SIMD block array (nblk, K, R, LANES) as (B, K, R): trajectory blk·LANES + j is a[blk, :, :, j]."""
    nblk, K, R, lanes = a.shape
    return np.ascontiguousarray(a.transpose(0, 3, 1, 2).reshape(nblk * lanes, K, R)[:B])


def forward_store(spec: ModelSpec, measurement: str, z, dts, x0, p0, q, r, simd: bool | None = None) -> ForwardPass:
    """Run the filter over z (B, K, m) with dts (B, K), physical x0 (B, n), packed p0 (B, n(n+1)/2), keeping
    every step (``run_batch_store_<measurement>``). ``simd``: run ``run_batch_store_soa_<measurement>``
    (trajectories in the SIMD lanes, the same results to ~1e-14, the states kept in blocks: ForwardPass);
    None: from ``SOA_SMOOTH_MIN_BATCH`` trajectories on."""
    B, K = z.shape[:2]
    ni = len(spec.internal_names)
    q = np.asarray(q, dtype=float)
    r = np.asarray(r, dtype=float)
    if simd is None:
        simd = B >= SOA_SMOOTH_MIN_BATCH
    if simd:
        shape = ((B + LANES - 1) // LANES, K, ni + spec.n_packed, LANES)  # every lane written (past B: zeros)
        fp = ForwardPass(None, None, None, None, np.empty((B, K)), np.empty((B, K)), dts, np.full(B, K, dtype=np.int64),
                         np.empty((B, K, spec.n)), (np.empty(shape), np.empty(shape)))
        spec.kernel("run_batch_store_soa", measurement)(z, dts, x0, p0, q, r, *fp.blocks, fp.nis, fp.logdet,
                                                                    fp.x_filt)
        return fp
    fp = ForwardPass(np.empty((B, K, ni)), np.empty((B, K, spec.n_packed)), np.empty((B, K, ni)),
                     np.empty((B, K, spec.n_packed)), np.empty((B, K)), np.empty((B, K)), dts,
                     np.full(B, K, dtype=np.int64), np.empty((B, K, spec.n)))
    spec.kernel("run_batch_store", measurement)(
        z, dts, x0, p0, q, r, fp.s_pred, fp.p_pred, fp.s_filt, fp.p_filt, fp.nis, fp.logdet, fp.x_filt)
    return fp


def smooth_stored(spec: ModelSpec, fp: ForwardPass, covariances: bool = True
                  ) -> tuple[np.ndarray, np.ndarray | None, np.ndarray | None]:
    """The RTS backward pass over a stored forward pass: smoothed physical states (B, K, n), internal states
    (B, K, n_int) and packed covariances (B, K, n(n+1)/2) (entries past a trajectory's length are left unset).
    ``smooth_batch`` for a scalar pass, ``smooth_batch_soa`` (SIMD lanes, the same results to ~1e-14) for a pass
    kept in blocks; then the internal states and covariances are unpacked only with ``covariances`` (else None)."""
    B, K = fp.x_filt.shape[:2]
    x_sm = np.full((B, K, spec.n), np.nan)
    lengths = np.ascontiguousarray(fp.lengths, dtype=np.int64)
    if fp.blocks is not None:
        nblk, _, R, lanes = fp.blocks[0].shape
        Sb = np.empty((nblk, K if covariances else 0, R, lanes))
        spec.kernels.smooth_batch_soa(fp.dts, *fp.blocks, lengths, Sb, x_sm)
        if not covariances:
            return x_sm, None, None
        s = unblock(Sb, B)
        ni = len(spec.internal_names)
        return x_sm, s[..., :ni], s[..., ni:]
    s_sm = np.empty_like(fp.s_filt)
    p_sm = np.empty_like(fp.p_filt)
    spec.kernels.smooth_batch(fp.dts, fp.s_pred, fp.p_pred, fp.s_filt, fp.p_filt, lengths, s_sm, p_sm, x_sm)
    return x_sm, s_sm, p_sm
