"""Tracks as padded batches for the generated loops, and the two-point prior of each track.

A *track* is one object's measurements: times t (K,) and measurements z (K, m). The estimators start each
track from its first two measurements (the rule of ``lgekf.apps.track.two_point``, repeated here in the
layer below the apps) and filter the rest.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..core.registry import ModelSpec

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
        if np.any(np.diff(t) <= 0):
            raise ValueError(f"tracks[{i}]: times must increase")
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


def two_point_prior(spec: ModelSpec, batch: TrackBatch, angle_index: int | None = None, omega_std: float = 0.5,
                    heading_cap: float = math.pi):
    """The two-point start of every track as a function of the measurement std.

    Returns ``(x0 (B, n), prior)`` where ``prior(r, r_angle=None)`` gives P0 (B, n, n) for a position std r (and the
    std of the measured heading when the measurement has one, entry ``angle_index`` of z): the estimate at the
    second measurement, position z1 (variance r²), world velocity (z1 − z0)/Δ (variance σ_v² = 2r²/Δ² per
    axis), heading atan2(v) with variance min(σ_v²/|v|², cap²) (or the measured heading), body velocity (|v|, 0)
    with var v_x = σ_v², var v_y = max(σ_v² − |v|² var θ, (0.1 σ_v)²), ω = 0 with std ``omega_std``; converted
    to the model by the generated ``common_to_state`` / ``common_jacobian`` (P0 = J P_c Jᵀ, angle variances
    capped at π²) as ``lgekf.apps.track.two_point`` does.
    """
    k = spec.kernels
    z0, z1 = batch.z01[:, 0], batch.z01[:, 1]
    dt = batch.t01[:, 1] - batch.t01[:, 0]
    v = (z1[:, :2] - z0[:, :2]) / dt[:, None]
    speed = np.hypot(v[:, 0], v[:, 1])
    B = len(dt)
    c = np.zeros((B, 6))
    c[:, :2] = z1[:, :2]
    if angle_index is None:
        c[:, 2] = np.where(speed > 0, np.arctan2(v[:, 1], v[:, 0]), 0.0)
        c[:, 3] = speed
    else:
        h = z1[:, angle_index]
        c[:, 2] = np.arctan2(np.sin(h), np.cos(h))
        c[:, 3] = v[:, 0] * np.cos(h) + v[:, 1] * np.sin(h)
    cj = c.copy()
    cj[:, 3] = np.where(np.abs(cj[:, 3]) < 1e-9, 1e-9, cj[:, 3])
    x0 = np.array([k.common_to_state(ci) for ci in c]).reshape(B, spec.n)
    J = np.array([k.common_jacobian(ci) for ci in cj]).reshape(B, spec.n, 6)

    def prior(r: float, r_angle: float | None = None) -> np.ndarray:
        var_v = 2.0 * r**2 / dt**2
        var = np.empty((B, 6))
        var[:, 0] = var[:, 1] = r**2
        var[:, 3] = var_v
        var[:, 5] = omega_std**2
        if angle_index is None:
            with np.errstate(divide="ignore"):
                var_th = np.minimum(np.where(speed > 0, var_v / np.where(speed > 0, speed, 1.0) ** 2, np.inf), heading_cap**2)
            var[:, 2] = var_th
            var[:, 4] = np.maximum(var_v - speed**2 * var_th, 0.01 * var_v)
        else:
            var[:, 2] = (r_angle if r_angle is not None else 0.1) ** 2
            var[:, 4] = 0.01 * var_v
        P0 = np.einsum("bij,bj,bkj->bik", J, var, J)
        P0 = 0.5 * (P0 + np.swapaxes(P0, 1, 2))
        for a in spec.angles:
            big = P0[:, a, a] > math.pi**2
            if big.any():
                s = np.ones((int(big.sum()), spec.n))
                s[:, a] = math.pi / np.sqrt(P0[big, a, a])
                P0[big] *= s[:, :, None] * s[:, None, :]
        return P0

    return x0, prior
