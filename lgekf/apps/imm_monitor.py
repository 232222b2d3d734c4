"""The divergence monitor and recovery of ``lgekf track --model imm``: the single-model monitor's rules
(``lgekf.apps.divergence``) applied to the IMM's combined estimate.

The IMM runs object by object (``lgekf.estimators.imm.imm_batch``) from the two-point start; its combined
posterior c_k (common coordinates of the space, body-frame velocity: (x, y, θ, v_x, v_y, ω) in the plane,
(x, y, z, roll, pitch, yaw, v_x, v_y, v_z, ω_x, ω_y, ω_z) in 3-D) with covariance P_k is then scanned row by row
since the last (re-)initialisation (d = 2 or 3 the dimension of the positions z):

* **Residual window**: the posterior residual e_k = z_k − (position of c_k) of a consistent filter has covariance
  R − H P_k Hᵀ ⪯ R = r² I (r the measurement std in use), so d_k = |e_k|² / r², each clipped at its
  99.99 % χ²_d quantile (``clip``), summed over the last W = ``window`` (and over the last ``short``) updates exceeds the
  (1 − α) χ² quantile with dW (d·short) degrees of freedom with probability at most α (the test is
  conservative). An IMM that has lost the object, over-confident while its estimate drifts off the
  measurements, exceeds it persistently. (The IMM's combined prediction, which a NIS would need, is not an
  output of its kernel; the posterior residual needs nothing more than the output.)
* **Absurd speed**: |v| − ``n_sigma`` · √λ_max(P_k[v, v]) (v the body velocity of c, ``SPACES[space]["common_velocity"]``) above the object's speed limit
  (``divergence.speed_limits``: twice the data's largest chord speed plus the chord's noise and a margin).
  The speed is |v| in the body frame, equal to the world speed; its gradient has unit norm, so the std
  bound is exact for the velocity block.
* **Non-finite**: a NaN or infinite entry of c_k or P_k.

Recovery, as for the single models: at the alarm row g the object is re-initialised by the two-point rule
(``core.initiation.two_point``, from its measurement g and the latest one at least ``REINIT_BASELINE`` s
earlier, else its first), mode probabilities uniform, and the IMM continues from row g + 1. A residual
alarm within ``repeat`` × W rows of the previous re-initialisation inflates the object's noise stds (every
mode's process noise and the measurement std) by √(mean d / 2) of that window, at most ``max_inflation``
per alarm. At most ``max_reinit`` re-initialisations per object. Rows of the alarm's window (and the row
before it) through g are flagged 1.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..core.initiation import two_point
from ..core.registry import SPACES, space_of_positions
from ..estimators.imm.estimator import Mode, imm_batch
from .divergence import Alarm, MonitorConfig

__all__ = ["Segment", "ImmRun", "imm_monitored", "first_imm_alarm", "scaled_modes"]



@dataclass
class Segment:
    """Rows ``first`` .. ``end`` - 1 of the IMM's run from (c0, P0) at row ``first`` - 1 with the noise × ``scale``."""

    first: int
    end: int
    c0: np.ndarray
    P0: np.ndarray
    scale: float


@dataclass
class ImmRun:
    """One object's monitored IMM: combined estimates c (K, n_c), covariances P (K, n_c, n_c), mode probabilities
    mu (K, M), flags (K,), alarms (rows relative to the object's first row) and the segments run."""

    c: np.ndarray
    P: np.ndarray
    mu: np.ndarray
    flag: np.ndarray
    alarms: list
    segments: list


def scaled_modes(modes, scale: float) -> list:
    """The modes with every process-noise std × ``scale``."""
    if scale == 1.0:
        return list(modes)
    return [Mode(m.model, tuple(scale * v for v in m.accel_std), m.label) for m in modes]


def _window_sums(d: np.ndarray, w: int) -> np.ndarray:
    """s[k] = d[k - w + 1] + ... + d[k] for k >= w - 1 (NaN before)."""
    s = np.full(d.size, np.nan)
    if d.size >= w:
        c = np.concatenate([[0.0], np.cumsum(d)])
        s[w - 1:] = c[w:] - c[:-w]
    return s


def first_imm_alarm(z, c, P, meas_std: float, limit: float, cfg: MonitorConfig):
    """The first alarm of a segment's rows (z (K, d), c (K, n_c), P (K, n_c, n_c)), as (k, kind, value, threshold,
    updates, first flagged k) with k counted from the segment's first row, or None (module docstring). The flagged
    rows are the alarm's window and the row before it (-1: the segment's start row), as for the single models."""
    K = c.shape[0]
    if K == 0:
        return None
    finite = np.isfinite(c).all(axis=1) & np.isfinite(P.reshape(K, -1)).all(axis=1)
    dim = z.shape[1]
    clip, thr_w, thr_s = cfg.nis_thresholds(dim)  # the single models' thresholds, for m = d
    e = z[:, :dim] - c[:, :dim]
    d = np.minimum(np.where(finite, np.sum(e ** 2, axis=1) / meas_std ** 2, 0.0), clip)
    sw, ss = _window_sums(d, cfg.window), _window_sums(d, cfg.short)
    vel = list(SPACES[space_of_positions(dim)]["common_velocity"])
    if len(vel) == 2:
        a, b, cc = P[:, vel[0], vel[0]], P[:, vel[1], vel[1]], P[:, vel[0], vel[1]]
        lam = 0.5 * (a + b) + np.sqrt(0.25 * (a - b) ** 2 + cc ** 2)  # λ_max of the 2x2 velocity block
    else:
        block = np.where(finite[:, None, None], P[:, vel][:, :, vel], 0.0)
        lam = np.linalg.eigvalsh(block)[:, -1]  # λ_max of the velocity block
    speed_k = np.linalg.norm(c[:, vel], axis=1)
    speed = speed_k - cfg.n_sigma * np.sqrt(np.maximum(lam, 0.0))
    with np.errstate(invalid="ignore"):
        hits = {
            3: np.flatnonzero(~finite),
            1: np.flatnonzero((sw > thr_w) | (ss > thr_s)),
            2: np.flatnonzero(speed > limit),
        }
    found = [(int(v[0]), kind) for kind, v in hits.items() if v.size]
    if not found:
        return None
    k, kind = min(found)
    if kind == 3:
        return k, 3, math.nan, math.nan, 0, k
    if kind == 2:
        return k, 2, float(speed_k[k]), float(limit), 0, k - 1
    if sw[k] > thr_w:
        return k, 1, float(sw[k] / cfg.window), thr_w / cfg.window, cfg.window, k - cfg.window
    return k, 1, float(ss[k] / cfg.short), thr_s / cfg.short, cfg.short, k - cfg.short


def imm_monitored(t, z, modes, switch: float, meas_std: float, omega_std: float, c0, var0, limit: float,
                  cfg: MonitorConfig | None, baseline: float, heading_cap: float) -> ImmRun:
    """One object's IMM (rows 2, 3, ... of t (K,), z (K, d); rows 0 and 1 are the caller's two-point start
    c0 (n_c,), var0 (n_c,)) with the monitor and recovery of the module docstring; ``cfg`` None: unmonitored."""
    K = t.size
    M = len(modes)
    nc = np.size(c0)
    c = np.full((K, nc), np.nan)
    P = np.full((K, nc, nc), np.nan)
    mu = np.full((K, M), 1.0 / M)
    flag = np.zeros(K, np.int8)
    alarms, segments = [], []
    first, x0, P0, scale, last_reinit, n_reinit = 2, np.asarray(c0, float), np.diag(var0), 1.0, 1, 0
    while first < K:
        run_modes = scaled_modes(modes, scale)
        est, m, Pk = imm_batch(z[None, first:], run_modes, switch, dt=np.diff(t[first - 1:])[None], meas_std=meas_std * scale,
                               x0=x0, P0=P0, return_cov=True)
        c[first:], mu[first:], P[first:] = est[0], m[0], Pk[0]
        segments.append(Segment(first, K, x0, P0, scale))
        if cfg is None:
            break
        hit = first_imm_alarm(z[first:], c[first:], P[first:], meas_std * scale, limit, cfg)
        if hit is None:
            break
        k, kind, value, thr, updates, k_flag = hit
        g = first + k
        flag[first + k_flag:g + 1] = 1  # k_flag >= -1: at most the row of the segment's start
        if n_reinit >= cfg.max_reinit:
            alarms.append(Alarm(0, g, kind, value, thr, updates, reinitialised=False, scale=scale))
            break
        if kind == 1 and g - last_reinit <= cfg.repeat * cfg.window:
            scale *= min(max(math.sqrt(value / z.shape[1]), 1.0), cfg.max_inflation)
        alarms.append(Alarm(0, g, kind, value, thr, updates, scale=scale))
        j = int(np.searchsorted(t[:g], t[g] - baseline, side="right")) - 1
        cg, vg = two_point(t, z, np.array([g]), meas_std * scale, omega_std, heading_cap=heading_cap, first=np.array([max(j, 0)]))
        c[g], P[g], mu[g] = cg[0], np.diag(vg[0]), 1.0 / M
        segments[-1].end = g
        x0, P0, first, last_reinit, n_reinit = cg[0], np.diag(vg[0]), g + 1, g, n_reinit + 1
    return ImmRun(c, P, mu, flag, alarms, segments)
