"""Driving scenarios for the robustness set: a car-like object (unicycle, no side slip) driven by
piecewise-constant acceleration and path curvature, sampled at regular or irregular times, with i.i.d.
Gaussian position noise.

Motion (integrated on a fine grid of ``FINE_DT`` = 5 ms): speed v' = a, turn rate ω = κ·v (so ω → 0 when
the car stops and changes sign when it reverses), heading θ' = ω, and each fine step moves the position
along the exact arc (chord v·h·sinc(ωh/2) at angle θ + ωh/2). The control signals a(t), κ(t) are
piecewise constant, then smoothed by a moving average of ``SMOOTH_S`` = 0.6 s (finite jerk, continuous
turn rate). Forward driving clamps v at 0 (a stop is v = 0 exactly, held); reversing is a segment with
``reverse=True`` in which v may go negative.

Measurement times lie on the fine grid; the truth at a measurement is the fine-grid state there.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

__all__ = ["Segment", "Drive", "drive", "urban_drive", "parking", "sample", "sample_times", "Scenario", "FINE_DT"]

FINE_DT = 0.005
SMOOTH_S = 0.6


@dataclass(frozen=True)
class Segment:
    """``duration`` s of constant acceleration ``accel`` (m/s²) and curvature ``curvature`` (1/m).

    ``reverse``: v may go below 0 (backing up); otherwise v is clamped at 0 (braking ends in a stop).
    """

    duration: float
    accel: float = 0.0
    curvature: float = 0.0
    reverse: bool = False


@dataclass
class Drive:
    """A fine-grid truth: t (M,), position p (M, 2), heading th (M,), speed v (M,) (signed), turn rate w (M,)."""

    t: np.ndarray
    p: np.ndarray
    th: np.ndarray
    v: np.ndarray
    w: np.ndarray

    @property
    def velocity(self) -> np.ndarray:
        """World-frame velocity (M, 2)."""
        return self.v[:, None] * np.column_stack([np.cos(self.th), np.sin(self.th)])


def _smooth(u: np.ndarray, width: int) -> np.ndarray:
    if width <= 1:
        return u
    pad = np.concatenate([np.full(width // 2, u[0]), u, np.full(width - width // 2 - 1, u[-1])])
    c = np.cumsum(np.concatenate([[0.0], pad]))
    return (c[width:] - c[:-width]) / width


def drive(segments, v0: float = 0.0, heading0: float = 0.0, origin=(0.0, 0.0)) -> Drive:
    """Integrate the segments (see the module docstring) from speed ``v0`` and heading ``heading0``."""
    h = FINE_DT
    counts = [max(1, int(round(s.duration / h))) for s in segments]
    a = np.concatenate([np.full(c, s.accel) for c, s in zip(counts, segments)])
    k = np.concatenate([np.full(c, s.curvature) for c, s in zip(counts, segments)])
    rev = np.concatenate([np.full(c, s.reverse) for c, s in zip(counts, segments)])
    width = int(round(SMOOTH_S / h))
    a = _smooth(a, width)
    k = _smooth(k, width)
    M = a.size + 1
    v = np.empty(M)
    v[0] = v0
    for i in range(M - 1):
        nv = v[i] + a[i] * h
        if not rev[i] and nv < 0.0:  # forward driving: braking ends in a stop (and ends a reversal)
            nv = 0.0
        v[i + 1] = nv
    vm = 0.5 * (v[:-1] + v[1:])
    w_step = np.append(k, k[-1]) * v  # turn rate at the grid points
    wm = k * vm
    th = np.empty(M)
    th[0] = heading0
    th[1:] = heading0 + np.cumsum(wm * h)
    half = 0.5 * wm * h
    chord = vm * h * np.sinc(half / math.pi)  # np.sinc(x) = sin(πx)/(πx)
    ang = th[:-1] + half
    p = np.empty((M, 2))
    p[0] = origin
    p[1:, 0] = origin[0] + np.cumsum(chord * np.cos(ang))
    p[1:, 1] = origin[1] + np.cumsum(chord * np.sin(ang))
    return Drive(h * np.arange(M), p, th, v, w_step)


def urban_drive(duration: float, rng: np.random.Generator, *, cruise=(8.0, 14.0), turn_speed=(4.0, 6.0),
                radius=(10.0, 20.0), accel=(1.0, 2.5), brake=(1.5, 3.0), wait=(3.0, 15.0), cruise_time=(5.0, 20.0),
                events=("turn", "stop", "lane")) -> list:
    """Segments of at least ``duration`` s of random driving: accelerate to a cruise speed, cruise, then
    one of ``events``: a 90° turn (slowing to ``turn_speed``, radius ``radius``), a stop (braking to
    v = 0, waiting ``wait`` s) or a lane change (±0.35 m/s² lateral for 2 s each). Ranges are uniform."""
    segs: list = []
    total = 0.0
    v = 0.0

    def add(seg):
        nonlocal total
        if seg.duration > 0:
            segs.append(seg)
            total += seg.duration

    while total < duration:
        target = rng.uniform(*cruise)
        if target > v:
            acc = rng.uniform(*accel)
            add(Segment((target - v) / acc, acc))
        v = max(v, target)
        add(Segment(rng.uniform(*cruise_time)))
        choice = events[int(rng.integers(len(events)))]
        if choice == "turn":
            vt = min(v, rng.uniform(*turn_speed))
            dec = rng.uniform(*brake)
            add(Segment((v - vt) / dec, -dec))
            v = vt
            r = rng.uniform(*radius)
            sign = rng.choice([-1.0, 1.0])
            add(Segment((math.pi / 2) * r / vt, 0.0, sign / r))
        elif choice == "stop":
            dec = rng.uniform(*brake)
            add(Segment(v / dec + 0.5, -dec))
            v = 0.0
            add(Segment(rng.uniform(*wait)))
        else:
            sign = rng.choice([-1.0, 1.0])
            kappa = sign * 0.35 / (v * v)  # 0.35 m/s² lateral acceleration
            add(Segment(2.0, 0.0, kappa))
            add(Segment(2.0, 0.0, -kappa))
    return segs


def parking(rng: np.random.Generator, manoeuvres: int = 5) -> list:
    """Forward and reverse manoeuvres: each drives forward 3–8 s at 2–4 m/s, stops, backs up 2–5 s at
    1–2 m/s on a curve of radius 5–10 m, stops and waits 1–3 s (reversals through v = 0)."""
    segs = []
    for _ in range(manoeuvres):
        vf = rng.uniform(2.0, 4.0)
        segs += [Segment(vf / 1.5, 1.5), Segment(rng.uniform(3.0, 8.0)), Segment(vf / 2.0 + 0.5, -2.0),
                 Segment(rng.uniform(0.5, 1.5))]
        vr = rng.uniform(1.0, 2.0)
        k = rng.choice([-1.0, 1.0]) / rng.uniform(5.0, 10.0)
        segs += [Segment(vr / 1.0, -1.0, k, reverse=True), Segment(rng.uniform(2.0, 5.0), 0.0, k, reverse=True),
                 Segment(vr / 1.0, 1.0, k, reverse=True), Segment(rng.uniform(1.0, 3.0))]
    return segs


def sample_times(duration: float, rng: np.random.Generator, steps=(0.2,), probs=None) -> np.ndarray:
    """Measurement times from 0 to ``duration`` with steps drawn from ``steps`` (probabilities ``probs``),
    rounded to the fine grid."""
    n = int(duration / min(steps)) + 2
    dts = rng.choice(np.asarray(steps, dtype=float), size=n, p=probs)
    t = np.concatenate([[0.0], np.cumsum(dts)])
    t = t[t <= duration]
    return np.round(t / FINE_DT) * FINE_DT


@dataclass
class Scenario:
    """Tracks sorted by object: truth (t, p, velocity, turn rate), measurements z with noise std ``meas_std``."""

    name: str
    t: np.ndarray
    p: np.ndarray
    v: np.ndarray
    w: np.ndarray | None
    z: np.ndarray
    starts: np.ndarray
    meas_std: float
    description: str = ""
    labels: list = field(default_factory=list)


def sample(d: Drive, times: np.ndarray, meas_std: float, rng: np.random.Generator):
    """Truth (t, p, velocity, w) of drive ``d`` at ``times`` (on its grid) and noisy positions z."""
    idx = np.clip(np.round(times / FINE_DT).astype(np.int64), 0, d.t.size - 1)
    idx = np.unique(idx)
    p = d.p[idx]
    z = p + meas_std * rng.standard_normal(p.shape)
    return d.t[idx], p, d.velocity[idx], d.w[idx], z
