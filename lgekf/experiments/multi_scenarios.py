"""Multi-target scenarios with births, deaths, crossings, close parallel targets, clutter and missed
detections (the test bed of ``lgekf study --multi``), and detection streams from any truth.

Truth: constant-turn motion x' = v cos θ, y' = v sin θ, θ' = ω, integrated exactly per step, with a small
random walk on the speed (``speed_noise`` m/s/√s) and the turn rate (``turn_noise`` rad/s/√s). The base
scenario (20 s, 8 targets, region 200 m × 200 m around the origin):

* two targets crossing at the centre at the same time (at 90°), a third crossing their paths later;
* two close parallel targets, 2.5 m apart at the same speed;
* two turning targets (ω = ±0.3 rad/s, ±0.2 rad/s);
* births at 5 s and 8 s, deaths at 12 s and 16 s.

Detections per scan: each living target is detected with probability P_D, z = its position + N(0, r² I)
(pose: heading + N(0, r_θ²)); false alarms: Poisson with mean λ·area, uniform in the region (pose: heading
uniform in (−π, π]); the rows of a scan are shuffled.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..core.registry import get_measurement

__all__ = ["MultiScenario", "BASE_TARGETS", "base_scenario", "truth_trajectories", "detection_stream", "dataset_scenario"]

# id: (birth s, death s, x0, y0, heading deg, speed m/s, turn rate rad/s)
BASE_TARGETS = (
    (0.0, 20.0, -40.0, -40.0, 45.0, 5.0, 0.0),     # crossing pair, meets the next one at (0, 0) at ~11.3 s
    (0.0, 20.0, 40.0, -40.0, 135.0, 5.0, 0.0),
    (0.0, 20.0, -60.0, 20.0, 0.0, 6.0, 0.0),      # close parallel pair, 2.5 m apart
    (0.0, 20.0, -60.0, 22.5, 0.0, 6.0, 0.0),
    (0.0, 20.0, 30.0, 30.0, 180.0, 4.0, 0.3),     # turning
    (5.0, 16.0, 0.0, -70.0, 90.0, 7.0, 0.0),      # born at 5 s, crosses the first pair's paths, dies at 16 s
    (0.0, 12.0, 70.0, 0.0, 200.0, 5.0, 0.0),      # dies at 12 s
    (8.0, 20.0, -20.0, 60.0, -60.0, 3.0, -0.2),   # born at 8 s, turning
)
REGION = (-100.0, 100.0, -100.0, 100.0)


@dataclass
class MultiScenario:
    """A multi-target scenario: scans and truth.

    Attributes
    ----------
    times : ndarray, (K,)
        Scan times.
    truth : list of (ids (n_k,), states (n_k, 3))
        Per scan, the living targets' ids and (x, y, heading).
    detections : list of ndarray, (M_k, m)
        Per scan, the detections (x, y) or (x, y, θ), unlabelled, shuffled.
    sources : list of ndarray, (M_k,)
        Per scan, the target id of each detection (-1: false alarm) -- for tests, never for tracking.
    region : tuple
        (x_min, x_max, y_min, y_max) of the clutter.
    """

    times: np.ndarray
    truth: list
    detections: list
    sources: list
    region: tuple

    def head(self, scans: int | None) -> "MultiScenario":
        """The first ``scans`` scans (all when None); the clutter region unchanged."""
        if scans is None:
            return self
        return MultiScenario(self.times[:scans], self.truth[:scans], self.detections[:scans], self.sources[:scans],
                             self.region)


def truth_trajectories(targets, times, rng, speed_noise: float = 0.2, turn_noise: float = 0.02):
    """Per scan (ids, (x, y, heading)) of the targets (rows like ``BASE_TARGETS``) at ``times``."""
    states = {}
    out = []
    prev = None
    for t in times:
        dt = 0.0 if prev is None else t - prev
        ids, xs = [], []
        for k, (b, d, x0, y0, hd, v, w) in enumerate(targets):
            if t + 1e-9 < b or t > d + 1e-9:
                states.pop(k, None)
                continue
            if k not in states:
                states[k] = [x0, y0, math.radians(hd), v, w]
            else:
                x, y, th, v_, w_ = states[k]
                if abs(w_) > 1e-9:
                    x += v_ / w_ * (math.sin(th + w_ * dt) - math.sin(th))
                    y += v_ / w_ * (math.cos(th) - math.cos(th + w_ * dt))
                else:
                    x += v_ * dt * math.cos(th)
                    y += v_ * dt * math.sin(th)
                th = math.atan2(math.sin(th + w_ * dt), math.cos(th + w_ * dt))
                v_ = max(v_ + speed_noise * math.sqrt(dt) * rng.standard_normal(), 0.0)
                w_ = w_ + turn_noise * math.sqrt(dt) * rng.standard_normal()
                states[k] = [x, y, th, v_, w_]
            ids.append(k)
            xs.append(states[k][:3])
        out.append((np.asarray(ids, dtype=np.int64), np.asarray(xs, dtype=float).reshape(-1, 3)))
        prev = t
    return out


def detection_stream(truth, rng, detection_prob: float, clutter_density: float, meas_std, region,
                     measurement: str = "position"):
    """Detections and their sources per scan from a truth (list of (ids, (x, y, heading)) per scan).

    Parameters
    ----------
    truth : list of (ndarray, ndarray)
        Per scan, target ids (n_k,) and states (n_k, 3) (x, y, heading).
    rng : numpy.random.Generator
        Random numbers.
    detection_prob : float
        P_D.
    clutter_density : float
        λ, false alarms per m² per scan.
    meas_std : float or tuple
        Position std r, or (r, r_θ) / (r_x, r_y, r_θ) for pose.
    region : tuple
        (x_min, x_max, y_min, y_max) of the clutter.
    measurement : {"position", "pose"}
        What is measured.

    Returns
    -------
    detections : list of ndarray, (M_k, 2 or 3)
    sources : list of ndarray, (M_k,)
        Target id per detection, -1 for a false alarm.
    """
    r = np.atleast_1d(np.asarray(meas_std, dtype=float))
    rxy, rth = float(r[0]), float(r[-1]) if r.size > 1 else 0.0
    m = get_measurement(measurement).dim
    x0, x1, y0, y1 = region
    area = (x1 - x0) * (y1 - y0)
    dets, srcs = [], []
    for ids, X in truth:
        hit = rng.random(ids.size) < detection_prob
        Z = np.empty((int(hit.sum()), m))
        Z[:, :2] = X[hit, :2] + rxy * rng.standard_normal((Z.shape[0], 2))
        if m == 3:
            h = X[hit, 2] + rth * rng.standard_normal(Z.shape[0])
            Z[:, 2] = np.arctan2(np.sin(h), np.cos(h))
        nc = rng.poisson(clutter_density * area)
        C = np.empty((nc, m))
        C[:, 0] = rng.uniform(x0, x1, nc)
        C[:, 1] = rng.uniform(y0, y1, nc)
        if m == 3:
            C[:, 2] = rng.uniform(-math.pi, math.pi, nc)
        allz = np.vstack([Z, C])
        src = np.concatenate([ids[hit], np.full(nc, -1)])
        order = rng.permutation(allz.shape[0])
        dets.append(allz[order])
        srcs.append(src[order])
    return dets, srcs


def base_scenario(seed: int = 0, dt: float = 0.1, duration: float = 20.0, detection_prob: float = 0.9,
                  clutter_density: float = 1e-4, meas_std=0.3, measurement: str = "position",
                  targets=BASE_TARGETS, region=REGION) -> MultiScenario:
    """The base scenario of the module docstring with clutter and misses.

    Parameters
    ----------
    seed : int
        Seed of the truth's random walk, the misses, the noise and the clutter.
    dt : float
        Scan interval (s).
    duration : float
        Length (s); scans at 0, dt, ..., duration.
    detection_prob : float
        P_D.
    clutter_density : float
        λ, false alarms per m² per scan (1e-4: 4 per scan in the 200 m × 200 m region).
    meas_std : float or tuple
        Measurement noise (see ``detection_stream``).
    measurement : {"position", "pose"}
        What is measured.
    targets : sequence
        Rows (birth, death, x0, y0, heading deg, speed, turn rate).
    region : tuple
        The clutter region.

    Returns
    -------
    MultiScenario
    """
    rng = np.random.default_rng(seed)
    times = np.round(np.arange(0.0, duration + dt / 2, dt), 10)
    truth = truth_trajectories(targets, times, rng)
    dets, srcs = detection_stream(truth, rng, detection_prob, clutter_density, meas_std, region, measurement)
    return MultiScenario(times, truth, dets, srcs, tuple(region))


def dataset_scenario(ds, seed: int = 0, detection_prob: float = 0.9, clutter_density: float = 0.01, meas_std=0.1,
                     margin: float = 2.0) -> MultiScenario:
    """A detection stream from real trajectories (``lgekf.io.datasets.Dataset``, e.g. the pedestrians of
    ``lgekf evaluate``): one scan per distinct time, truth = the objects present then, detections = truth +
    N(0, r² I) noise, each kept with probability P_D, plus Poisson clutter of density λ uniform in the
    data's bounding box grown by ``margin`` metres.

    Parameters
    ----------
    ds : Dataset
        Tracks sorted by object (t, p, starts).
    seed : int
        Seed of the noise, misses and clutter.
    detection_prob, clutter_density : float
        P_D and λ (false alarms per m² per scan).
    meas_std : float
        Position noise std r (m).
    margin : float
        Border added around the bounding box of the data for the clutter (m).

    Returns
    -------
    MultiScenario
        The truth's heading column is the direction of motion between consecutive samples (0 when unknown).
    """
    rng = np.random.default_rng(seed)
    obj = np.repeat(np.arange(ds.n_tracks), np.diff(ds.starts))
    heading = np.zeros(ds.t.size)
    d = np.diff(ds.p, axis=0)
    same = obj[1:] == obj[:-1]
    heading[1:][same] = np.arctan2(d[same, 1], d[same, 0])
    times, inv = np.unique(ds.t, return_inverse=True)
    order = np.argsort(inv, kind="stable")
    cuts = np.searchsorted(inv[order], np.arange(times.size + 1))
    truth = []
    for k in range(times.size):
        rows = order[cuts[k]:cuts[k + 1]]
        truth.append((obj[rows].astype(np.int64), np.column_stack([ds.p[rows], heading[rows]])))
    lo, hi = ds.p.min(axis=0) - margin, ds.p.max(axis=0) + margin
    region = (float(lo[0]), float(hi[0]), float(lo[1]), float(hi[1]))
    dets, srcs = detection_stream(truth, rng, detection_prob, clutter_density, meas_std, region)
    return MultiScenario(times, truth, dets, srcs, region)
