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

from ..core.initiation import moving_backwards
from ..core.registry import BASE_MEASUREMENT, get_model, measurement_in
from .divergence import MonitorConfig, speed_limits
from ..io.units import gap_rows
from ..io.grouping import objects_subset
from .noise import (
    K_GRID, MIN_MEAS_STD, SEARCH_ROWS, NoiseEstimate, measurement_std, object_measurement_stds, one_step_errors, subsample_objects, typical_speed,
)
from .search import PARALLEL_MIN_ROWS, in_thread, process_noise_searches, usable_cpus
from .track import (
    DEFAULT_HEADING_STD, DEFAULT_MEAS_STD, DEFAULT_OMEGA_STD, TRACK_HEADING_CAP, TrackConfig, initial_common, initial_estimates,
    track_monitored,
)

__all__ = ["NoisePlan", "plan_noise", "BURN_IN", "after_gaps", "gap_alarms", "NoiseClasses", "noise_classes", "plan_noise_by_class",
           "data_starts"]

BURN_IN = 3  # updates after each object's initialisation left out of the search's scores
NOISE_FREE = 1e-6  # a measurement std from the data below this (m) reads noise-free positions (round-off), not km
# Classes of objects by measurement std: an object's own estimate from n ≈ 300 windows is within about ±20 % (2.5 σ),
# so a class of one sensor spans a factor of about 1.5
CLASS_GAP = 1.5  # objects whose (shrunk) measurement stds are separated by a gap of more than this factor: classes of their own
CLASS_SPAN = 2.0  # a class whose stds span more than this factor is cut into bins CLASS_GAP wide
MAX_CLASSES = 6  # more would be cut into this many bins of equal width (log scale) over the whole range
LOG_STD_SPREAD = 1.2  # the standard error of an object's log std from n windows is about LOG_STD_SPREAD / √n


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

    def tune_starts(self, measurement: dict | None = None, heading_std: float = DEFAULT_HEADING_STD) -> dict:
        """{model: (accel_std, meas_std)}: this plan's noise as the starts of ``--tune``'s fits
        (``lgekf.apps.smooth_track.tune_models``): the plan's measurement std, for a model with pose measurements
        (``measurement[model]``, default position) ``heading_std`` for the heading entry."""
        out = {}
        for m, q in self.accel_std.items():
            meas = get_model(m).measurement((measurement or {}).get(m, "position"))
            r = np.full(len(meas.noise_names), float(self.meas_std))
            r[list(meas.angles)] = heading_std
            out[m] = (tuple(q), tuple(r))
        return out

    def bound_warnings(self) -> list:
        """One line per estimate that hit a floor or a bound of its search (empty when none did): the measurement std
        at ``MIN_MEAS_STD`` (coordinates in km: the noise of metres-scale data reads 1000 times smaller; or positions
        smoothed, as in annotated pedestrian sets; not below ``NOISE_FREE``: noise-free positions, exactly polynomial
        over 4 rows, such as simulated or linearly interpolated ones, are what the floor is for), else a model's process noise at the largest factor
        ``K_GRID`` tries (coordinates in mm or cm, or t not in seconds). With the measurement std at its floor the
        process noise searched against it is a consequence, not said again. (The smallest factor alone is common on
        smooth tracks, e.g. simulated ones: the noise line says "the smallest tried", no warning.)"""
        est = self.meas_estimate
        if self.meas_source == "data" and est is not None and est.floored and est.raw >= NOISE_FREE:
            return [f"the measurement std from the data ({est.raw:.2g} m) is below its floor {MIN_MEAS_STD:g} m, which "
                    f"was used: coordinates in km? lgekf expects metres (if the positions are smoothed or interpolated, "
                    f"give --meas-std)"]
        return [f"{m}: the process noise from the data is the largest the search tries (k = {k:g} × the model's "
                f"defaults): coordinates in mm or cm, or t not in seconds? lgekf expects metres and seconds (or give "
                f"--accel-std)" for m, k in self.accel_k.items() if self.accel_source.get(m) == "data" and k >= K_GRID[-1]]

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
                edge = (", the largest tried" if self.accel_k[m] >= K_GRID[-1] else
                        ", the smallest tried" if self.accel_k[m] <= K_GRID[0] else "")
                parts.append(f"{m} {vals} (k = {self.accel_k[m]:.3g}{edge}, median NIS {self.median_nis[m]:.2f})")
            elif self.accel_source[m] == "default":
                parts.append(f"{m} {vals} (default: no object has {BURN_IN + 3} measurements to learn from)")
            else:
                parts.append(f"{m} {vals} (given)")
        text = f"noise from the data: {meas}" + (f"; accel-std {'; '.join(parts)}" if parts else "")
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
    gaps = after_gaps(ts, sub_starts)
    skip |= gaps
    runs = {}
    # what every run of the search shares (it does not depend on the process noise): made once, read by all
    common = initial_common(ts, zs, sub_starts, plan.meas_std, omega_std, hs, heading_std, heading_cap)
    backwards = moving_backwards(ts, zs, sub_starts, plan.meas_std)
    limits = None if monitor is None else speed_limits(ts, zs, sub_starts, plan.meas_std, monitor)
    for m in todo:
        meas = measurement.get(m, "position")
        get_model(m).measurement(meas)
        start = initial_estimates(m, *common, backwards)  # the model's two-point start (x0, P0) of every object

        def run(q, m=m, meas=meas, start=start):  # no shared mutable state: process_noise_searches calls it from several threads
            cfg = TrackConfig({m: q}, plan.meas_std, omega_std, heading_std, heading_cap)
            r = track_monitored(m, ts, zs, sub_starts, cfg, heading=hs, measurement=meas, monitor=monitor, start=start, limits=limits)
            err2 = one_step_errors(m, ts, zs, r.x, sub_starts)
            left_out = skip | gap_alarms(r.flag, gaps, sub_starts) if gaps.any() else skip
            return np.where(left_out, np.nan, r.nis), np.where(left_out, np.nan, err2)

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


def after_gaps(t, starts, burn_in: int = BURN_IN) -> np.ndarray:
    """(N,) bool: the rows that end a gap (``lgekf.io.units.gap_rows``: a step of at least 10 s and 10 times its
    object's median step, the gap the per-object warnings name) and the ``burn_in`` rows after each, which the
    process-noise search leaves out of its score.

    The score is a mean of squared prediction errors: over a gap of an hour one object's error is kilometres, its
    mean dominated by a single row, and the search raised every object's process noise to predict across it (×8 with
    one such object among six). What the filter does across a gap says nothing about the motion between measurements
    that the process noise describes; the rows are left out as the rows after an object's start are (``BURN_IN``).
    Shorter gaps stay in the score: the filter predicts across them in every run, and its noise must allow for that
    (the robustness set's irregular car, 0.1 s steps with 2 s gaps: left out, they let the search choose a noise with
    which SE(2)×R² diverged after a gap)."""
    starts = np.asarray(starts, dtype=np.int64)
    ends = gap_rows(t, starts)
    out = ends.copy()
    row = np.flatnonzero(ends)
    end = starts[np.searchsorted(starts, row, side="right")]  # the end of each gap row's object
    for j in range(1, burn_in + 1):
        r = row + j
        out[r[r < end]] = True
    return out


def gap_alarms(flag, gaps, starts, burn_in: int = BURN_IN) -> np.ndarray:
    """(N,) bool: the flagged rows of every divergence alarm that a gap raised (a run of flagged rows that meets a row
    of ``gaps``, ``after_gaps``) and the ``burn_in`` rows after its re-initialisation: the gap's doing, not the motion's
    (the alarms elsewhere keep counting: a filter unstable with some process noise must score badly)."""
    f = np.asarray(flag).astype(bool)
    out = np.zeros(f.size, bool)
    if not f.any():
        return out
    s = np.flatnonzero(f & ~np.r_[False, f[:-1]])
    e = np.flatnonzero(f & ~np.r_[f[1:], False])  # inclusive
    cs = np.r_[0, np.cumsum(gaps)]
    ends = np.asarray(starts, dtype=np.int64)[1:]
    for a, b in zip(s, e):
        if cs[b + 1] > cs[a]:
            end = ends[np.searchsorted(ends, b, side="right")]  # the end of b's object
            out[a:min(b + 1 + burn_in, end)] = True
    return out


def noise_classes(t, z, starts, pooled: float) -> tuple:
    """Classes of objects by their own measurement std: (class of each object (B,), its shrunk std (B,)).

    Each object's log std (``noise.object_measurement_stds``, n windows; standard error s_b = ``LOG_STD_SPREAD``/√n)
    is shrunk toward the ``pooled`` one with weight τ² / (τ² + s_b²), τ² = max(0, the spread of the objects' log stds −
    the mean s_b²): the share of the spread the objects' own noise explains (James–Stein). One sensor: τ² ≈ 0 and
    every object sits at the pooled std; several sensors: τ² large and each object keeps its own. Sorted, a gap of
    more than ``CLASS_GAP`` starts a new class, and a class spanning more than ``CLASS_SPAN`` is cut into bins
    ``CLASS_GAP`` wide; more than ``MAX_CLASSES`` classes become ``MAX_CLASSES`` bins of equal width. Classes are
    numbered by increasing std; one class when the objects agree. An object of 3 rows or less (no window, no estimate
    of its own) joins the class of most windows (alone it would make a class whose plan is the library default).
    """
    r, n = object_measurement_stds(t, z, starts)
    own = np.isfinite(r) & (n > 0)
    lp = math.log(pooled)
    lr = np.full(r.size, lp)
    if own.sum() >= 2:
        lo = np.log(r[own])
        se2 = LOG_STD_SPREAD ** 2 / n[own]
        tau2 = max(float(np.var(lo)) - float(np.mean(se2)), 0.0)
        w = tau2 / (tau2 + se2)
        lr[own] = w * lo + (1 - w) * lp
    order = np.argsort(lr, kind="stable")
    cut = np.flatnonzero(np.diff(lr[order]) > math.log(CLASS_GAP)) + 1
    label = np.empty(lr.size, dtype=np.int64)
    k = 0
    for grp in np.split(order, cut):
        lo = lr[grp].min()
        if lr[grp].max() - lo > math.log(CLASS_SPAN):
            bins = np.floor((lr[grp] - lo) / math.log(CLASS_GAP)).astype(np.int64)
            _, sub = np.unique(bins, return_inverse=True)
            label[grp] = k + sub
            k += int(sub.max()) + 1
        else:
            label[grp] = k
            k += 1
    if k > MAX_CLASSES:  # a continuum of stds rather than a few sensors: MAX_CLASSES bins of equal width
        width = (lr.max() - lr.min()) / MAX_CLASSES
        _, label = np.unique(np.minimum(np.floor((lr - lr.min()) / width), MAX_CLASSES - 1), return_inverse=True)
    label = label.astype(np.int64)
    if own.any() and not own.all():  # objects without an estimate of their own (< 4 rows) make no class of their own:
        rows = np.bincount(label[own], weights=n[own], minlength=label.max() + 1)  # they join the class of most windows
        label[~own] = int(np.argmax(rows))
        _, label = np.unique(label, return_inverse=True)  # classes numbered by increasing std, none left empty
        label = label.astype(np.int64)
    return label, np.exp(lr)


@dataclass
class NoiseClasses:
    """The noise of every class of objects: ``plans[of_object[b]]`` is object b's ``NoisePlan``."""

    of_object: np.ndarray
    plans: list
    object_std: np.ndarray  # each object's shrunk measurement std (m)

    def describe(self, labels) -> str:
        """One line: that the objects differ, and the classes (objects, a few ids, the std range)."""
        parts = []
        for c, plan in enumerate(self.plans):
            objs = np.flatnonzero(self.of_object == c)
            ids = ", ".join(str(labels[b]) for b in objs[:3]) + (", ..." if objs.size > 3 else "")
            parts.append(f"{objs.size} object{'s' if objs.size > 1 else ''} ({ids}) at {plan.meas_std:.3g} m")
        lo, hi = self.object_std.min(), self.object_std.max()
        return (f"objects differ (their measurement stds {lo:.3g} to {hi:.3g} m): noise estimated per class of objects, "
                f"{len(self.plans)} classes: " + "; ".join(parts))


def plan_noise_by_class(t, z, starts, models, *, meas_std=None, accel_std=None, heading=None, **kw) -> NoiseClasses:
    """``plan_noise`` for each class of objects (``noise_classes``; its own measurement std and process noise, the
    given values kept); one class, the plan of ``plan_noise`` itself, when the objects agree or ``meas_std`` is given."""
    B = len(starts) - 1
    pooled = None if meas_std is not None else measurement_std(t, z, starts)
    if pooled is None or not pooled.usable:
        plan = plan_noise(t, z, starts, models, meas_std=meas_std, accel_std=accel_std, heading=heading, **kw)
        return NoiseClasses(np.zeros(B, dtype=np.int64), [plan], np.full(B, plan.meas_std))
    label, std = noise_classes(t, z, starts, pooled.meas_std)
    if label.max() == 0:
        plan = plan_noise(t, z, starts, models, meas_std=meas_std, accel_std=accel_std, heading=heading, **kw)
        return NoiseClasses(label, [plan], std)
    plans = []
    for c in range(int(label.max()) + 1):
        rows, sub = objects_subset(starts, np.flatnonzero(label == c))
        plans.append(plan_noise(t[rows], z[rows], sub, models, accel_std=accel_std,
                                heading=None if heading is None else heading[rows], **kw))
    return NoiseClasses(label, plans, std)


def data_starts(t, z, starts, models, meas_std=None, omega_std: float = DEFAULT_OMEGA_STD) -> dict:
    """``NoisePlan.tune_starts`` of the noise ``lgekf track`` estimates from all objects (``plan_noise``: position
    measurements, the divergence monitor on, the heading prior of ``lgekf track``), for a caller without a plan (the
    IMM's ``--tune``)."""
    position = {m: measurement_in(get_model(m).space, BASE_MEASUREMENT) for m in models}  # position3 for a 3-D model
    plan = plan_noise(t, z, starts, list(models), meas_std=meas_std, omega_std=omega_std, heading_std=DEFAULT_HEADING_STD,
                      heading_cap=TRACK_HEADING_CAP, monitor=MonitorConfig(), measurement=position)
    return plan.tune_starts(position)
