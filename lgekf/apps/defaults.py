"""The noise ``lgekf track`` runs with: each value given as an option, else estimated from the data
(``lgekf.apps.noise``): the measurement std from local quadratic residuals, then per model the process
noise that minimises the filter's mean squared one-step prediction error on a subsample of the objects
(the filter run as ``lgekf track`` runs it: the measurement std just found, the divergence monitor on;
the first ``BURN_IN`` updates of every object, which the two-point initialisation dominates, left out). The
search's runs go to a pool of threads, one per usable CPU (``lgekf.apps.search``; the same plan as serially).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..core.registry import get_model
from .divergence import MonitorConfig, speed_limits
from .noise import (
    SEARCH_ROWS, NoiseEstimate, measurement_std, one_step_errors, subsample_objects, typical_speed,
)
from .search import PARALLEL_MIN_ROWS, in_thread, process_noise_searches, usable_cpus
from .track import DEFAULT_MEAS_STD, TrackConfig, initial_common, initial_estimates, track_monitored

__all__ = ["NoisePlan", "plan_noise", "BURN_IN"]

BURN_IN = 3  # updates after each object's initialisation left out of the search's scores


@dataclass
class NoisePlan:
    """What was used and where it came from."""

    meas_std: float
    meas_source: str  # "given", "data" or "default"
    meas_estimate: NoiseEstimate | None
    accel_std: dict = field(default_factory=dict)  # model -> tuple
    accel_source: dict = field(default_factory=dict)  # model -> "given" | "data" | "default"
    accel_k: dict = field(default_factory=dict)  # model -> k (data only)
    median_nis: dict = field(default_factory=dict)
    search: dict = field(default_factory=dict)  # model -> noise.SearchResult
    v_typ: float = 0.0

    @property
    def estimated(self) -> bool:
        return self.meas_source != "given" or any(s != "given" for s in self.accel_source.values())

    def describe(self, heading_std: float | None = None, heading_given: bool = True) -> str:
        """One line for stderr: every noise value used and where it came from."""
        if self.meas_source == "data":
            meas = f"meas-std {self.meas_std:.3g} m ({self.meas_estimate.describe()})"
        elif self.meas_source == "default":
            meas = f"meas-std {self.meas_std:.3g} m (default: {self.meas_estimate.describe()})"
        else:
            meas = f"meas-std {self.meas_std:.3g} m (given)"
        parts = []
        for m, q in self.accel_std.items():
            vals = ",".join(f"{v:.3g}" for v in q)
            if self.accel_source[m] == "data":
                parts.append(f"{m} {vals} (k = {self.accel_k[m]:.3g}, median NIS {self.median_nis[m]:.2f})")
            elif self.accel_source[m] == "default":
                parts.append(f"{m} {vals} (default: no object has {BURN_IN + 3} measurements to learn from)")
            else:
                parts.append(f"{m} {vals} (given)")
        text = f"noise from the data: {meas}; accel-std {'; '.join(parts)}"
        if any(s == "data" for s in self.accel_source.values()):
            text += f"; typical speed {self.v_typ:.3g} m/s"
        if heading_std is not None:
            text += f"; heading-std {heading_std:.3g} rad ({'given' if heading_given else 'default'})"
        return text


def plan_noise(t, z, starts, models, *, meas_std=None, accel_std=None, omega_std, heading_std, heading_cap=math.pi, heading=None,
               measurement=None, monitor: MonitorConfig | None = MonitorConfig(), workers: int | None = None) -> NoisePlan:
    """Noise of every model: the given values, the rest from the data.

    Parameters
    ----------
    t, z, starts : ndarray
        Measurements sorted by object (as for ``track_arrays``).
    models : list of str
    meas_std : float, optional
        Given measurement std (m); estimated when None.
    accel_std : dict, optional
        Given process-noise stds per model; the models not in it are estimated.
    omega_std, heading_std : float
        Initial turn-rate std and heading std (used in the search runs).
    heading : ndarray, optional
        The heading column (pose measurements).
    measurement : dict, optional
        Model -> measurement ("position" / "pose"); default position.
    monitor : MonitorConfig or None
        The divergence monitor of the search runs.
    workers : int, optional
        Threads of the process-noise search (``lgekf.apps.search``; the same plan whatever the number);
        default: every usable CPU, 1 for a subsample of fewer than ``PARALLEL_MIN_ROWS`` rows.
    """
    accel_std = dict(accel_std or {})
    measurement = measurement or {}
    est = None
    speed = None  # the typical speed, computed meanwhile in a thread of its own (nogil kernels) when there are CPUs to spare
    if meas_std is None and any(m not in accel_std for m in models) and len(t) >= PARALLEL_MIN_ROWS and (workers or usable_cpus()) > 1:
        speed = in_thread(typical_speed, t, z, starts)
    if meas_std is None:
        est = measurement_std(t, z, starts)
        if est.usable:
            plan = NoisePlan(est.meas_std, "data", est)
        else:
            plan = NoisePlan(DEFAULT_MEAS_STD, "default", est)
    else:
        plan = NoisePlan(float(meas_std), "given", None)
    todo = [m for m in models if m not in accel_std]
    for m in models:
        if m in accel_std:
            plan.accel_std[m] = tuple(float(v) for v in accel_std[m])
            plan.accel_source[m] = "given"
    if not todo:
        return plan
    plan.v_typ = typical_speed(t, z, starts) if speed is None else speed.result()
    objs = subsample_objects(starts)
    lens = np.minimum(np.diff(starts)[objs], SEARCH_ROWS)  # an object longer than that: its first SEARCH_ROWS rows
    rows = np.concatenate([np.arange(starts[o], starts[o] + n) for o, n in zip(objs, lens)])
    sub_starts = np.zeros(len(objs) + 1, dtype=np.int64)
    np.cumsum(lens, out=sub_starts[1:])
    ts, zs = t[rows], z[rows]
    hs = None if heading is None else heading[rows]
    skip = np.zeros(rows.size, bool)
    for j in range(BURN_IN):
        idx = sub_starts[:-1] + 2 + j
        skip[idx[idx < sub_starts[1:]]] = True
    runs = {}
    # what every run of the search shares (it does not depend on the process noise): made once, read by all
    common = initial_common(ts, zs, sub_starts, plan.meas_std, omega_std, hs, heading_std, heading_cap)
    limits = None if monitor is None else speed_limits(ts, zs, sub_starts, plan.meas_std, monitor)
    for m in todo:
        meas = measurement.get(m, "position")
        get_model(m).measurement(meas)
        start = initial_estimates(m, *common)  # the model's two-point start (x0, P0) of every object

        def run(q, m=m, meas=meas, start=start):  # no shared mutable state: process_noise_searches calls it from several threads
            cfg = TrackConfig({m: q}, plan.meas_std, omega_std, heading_std, heading_cap)
            r = track_monitored(m, ts, zs, sub_starts, cfg, heading=hs, measurement=meas, monitor=monitor, start=start, limits=limits)
            err2 = one_step_errors(m, ts, zs, r.x, sub_starts)
            return np.where(skip, np.nan, r.nis), np.where(skip, np.nan, err2)

        runs[m] = run
    if workers is None:
        workers = usable_cpus() if rows.size >= PARALLEL_MIN_ROWS else 1
    for m, res in process_noise_searches(runs, plan.v_typ, workers=workers).items():
        plan.accel_std[m] = res.q
        plan.accel_source[m] = "data" if np.isfinite(res.mse) else "default"
        plan.accel_k[m] = res.k
        plan.median_nis[m] = res.median_nis
        plan.search[m] = res
    return plan
