"""Tracks as padded batches for the generated loops, and the two-point prior of each track.

A *track* is one object's measurements: times t (K,) and measurements z (K, m). The estimators start each
track from its first two measurements (``lgekf.core.initiation``, the rule of ``lgekf track``) and filter the
rest.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...core.initiation import DEFAULT_HEADING_STD, DEFAULT_OMEGA_STD, initial_estimates, two_point
from ...core.registry import SPACES, ModelSpec

__all__ = ["TrackBatch", "batch_tracks", "two_point_prior"]


@dataclass
class TrackBatch:
    """Tracks padded to one array: ``z`` (B, K, m) of the filtered steps (each track's rows 2, 3, ...;
    padding NaN = predict only), ``dts`` (B, K) (padding 1 s), ``lengths`` (B,), and each track's first two
    measurements ``z01`` (B, 2, m) at times ``t01`` (B, 2) for its prior."""

    z: np.ndarray
    dts: np.ndarray
    lengths: np.ndarray
    z01: np.ndarray
    t01: np.ndarray

    @property
    def n_updates(self) -> int:
        """Number of measurements that update a filter (not NaN)."""
        ok = ~np.any(np.isnan(self.z), axis=2)
        return int(ok.sum())


def batch_tracks(tracks, m: int, dt: float | None = None, baseline: float = 0.0) -> TrackBatch:
    """A TrackBatch from a sequence of tracks: each a pair (t (K,), z (K, m)) or, with ``dt``, an array
    z (K, m) sampled every ``dt`` seconds.

    Each track starts from its first measurement and the first one at least ``baseline`` seconds later (at
    least the next one): the two-point prior; the filter runs over the measurements after the second.
    A longer baseline gives a far better initial velocity and heading (the velocity error of two points
    Δ apart is √2·r/Δ) at the price of the skipped measurements. Tracks with nothing left to filter are
    left out."""
    items = []
    for i, tr in enumerate(tracks):
        if dt is not None and not isinstance(tr, tuple):
            z = np.asarray(tr, dtype=float)
            t = dt * np.arange(len(z), dtype=float)
        else:
            t, z = (np.asarray(a, dtype=float) for a in tr)
        if z.ndim != 2 or z.shape[1] != m or t.shape != (z.shape[0],):
            raise ValueError(f"tracks[{i}]: expected t (K,) and z (K, {m}), got {t.shape} and {z.shape}")
        if not np.all(np.isfinite(t)) or np.any(np.diff(t) <= 0):
            raise ValueError(f"tracks[{i}]: times must be finite and increase")
        if np.any(np.isnan(z[0])):
            raise ValueError(f"tracks[{i}]: the first measurement starts the filter and must not be NaN")
        j = 1
        while j < len(t) and (t[j] - t[0] < baseline or np.any(np.isnan(z[j]))):
            j += 1
        if j + 1 < len(t):
            items.append((np.concatenate([t[:1], t[j:]]), np.concatenate([z[:1], z[j:]])))
    B = len(items)
    K = max((len(t) - 2 for t, _ in items), default=0)
    zb = np.full((B, K, m), np.nan)
    dts = np.ones((B, K))
    lengths = np.zeros(B, dtype=np.int64)
    z01 = np.empty((B, 2, m))
    t01 = np.empty((B, 2))
    for b, (t, z) in enumerate(items):
        L = len(t) - 2
        zb[b, :L] = z[2:]
        dts[b, :L] = np.diff(t)[1:]
        lengths[b] = L
        z01[b] = z[:2]
        t01[b] = t[:2]
    return TrackBatch(zb, dts, lengths, z01, t01)


def two_point_prior(spec: ModelSpec, batch: TrackBatch, angle_index: int | None = None, omega_std: float = DEFAULT_OMEGA_STD,
                    heading_cap: float = math.pi):
    """The two-point start of every track as a function of the measurement std.

    Returns ``(x0 (B, n), prior)`` where ``prior(r, r_angle=None)`` gives P0 (B, n, n) for a position std r (and the
    std of the measured heading when the measurement has one, entry ``angle_index`` of z): the estimate at each
    track's second measurement by the rule of ``lgekf track`` (``lgekf.core.initiation.two_point`` and
    ``initial_estimates``: position z1, world velocity (z1 − z0)/Δ, heading atan2(v) or the measured one, ω = 0
    with std ``omega_std``; P0 = J P_c Jᵀ through the generated ``common_jacobian``, angle variances capped at π²).
    """
    B, _, m = batch.z01.shape
    t = batch.t01.reshape(2 * B)
    z = batch.z01.reshape(2 * B, m)
    rows = np.arange(1, 2 * B, 2)
    heading = None if angle_index is None else z[:, angle_index]
    d = SPACES[spec.space]["dim"]  # the position's coordinates: z's first d entries

    def estimates(r: float, r_angle: float | None = None):
        c, var = two_point(t, z[:, :d], rows, r, omega_std, heading, DEFAULT_HEADING_STD if r_angle is None else r_angle,
                           heading_cap)
        return initial_estimates(spec.name, c, var)

    x0, _ = estimates(1.0)  # the mean does not depend on the stds

    def prior(r: float, r_angle: float | None = None) -> np.ndarray:
        return estimates(r, r_angle)[1]

    return x0, prior
