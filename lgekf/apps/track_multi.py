"""`lgekf track --multi`: many objects from unlabelled detections with clutter and misses.

Input: the rows of a detection file (``t, x, y`` [, ``heading``]; in 3-D ``t, x, y, z`` (or ``lat, lon, alt``) [, the
attitude]; an ``id`` column is ignored), ordered by
t (stably). Every scan goes through ``lgekf.estimators.multitarget.tracker.MultiTargetTracker``. Output: one row per
confirmed track per scan, ``track, t, <state>, std_<state>, existence`` (t the scan's time, the model's
physical state, the stds of its tangent coordinates, the existence probability).

Scans (``scans``, ``scan_window_from_data``)
--------------------------------------------
A scan starts at the earliest detection not yet in one and holds every detection at most ``window`` seconds
after it (t − t_first ≤ window); its time is the midpoint (t_first + t_last)/2 of its earliest and latest
detection (exactly t when all share one t; off the time of any of its detections by at most window/2).
``window`` 0 makes one scan of the rows with the same t. Without ``--scan-window`` the window comes from the
gaps g between the sorted distinct times: the jitter of per-detection timestamps makes gaps much smaller
than the scan period. For each break in the sorted gaps where one gap is at least ``SCAN_GAP_RATIO`` (5)
times the next smaller one (largest break value first), the times are linked wherever g ≤ the smaller gap
τ; the break is taken when the gaps between the linked groups are at least ``SCAN_GAP_RATIO`` times the
widest group's spread s, and then the window is √(s·d) (d the smallest gap between groups), which makes
exactly those groups (every group spans at most s < window, every gap between groups is at least d >
window) -- provided the groups look like scans: the median distance from a detection to the nearest
detection of *another time in its group* is at least twice the median distance to the nearest detection
of the *previous group* (over up to 200 groups spread over the data, up to 256 rows of each). A scan holds different objects and the next
scan the same ones again; a stretch of scans cut off by pauses (0.1-s scans, a 100-s pause: a break of 1000x)
holds the same objects again and again, and is rejected. No accepted break (one t per scan, also with
missed or irregular scans: their gaps differ by less than 5x, or the linked stretches are wider than a fifth of
the gaps between them; pauses): window 0, the scans of identical t. Objects stamped a little apart within a
period (a fifth of it or less) are grouped into one scan by this rule (the shipped example file: one object 10 ms
after the others at 10 Hz, gaps 0.01 and 0.09 s, a break of 9x; with a ratio of 10 it made 160 scans of one
or two objects and one track at a meas-std of 19 m); two sensors meant to be kept apart: ``--scan-window 0``.

Noise (``fit_noise``)
---------------------
The measurement std from the detections themselves, by tracking: the tracker is run with a std s, and the
detections that its *confirmed* tracks hold (β_ij ≥ 0.5: detection j is track i's with probability at least
one half given that the track exists; ``MultiTargetTracker.held``) form one sequence per track (each
detection at its own time), on which ``lgekf.apps.noise.measurement_std`` gives e: the MAD of the
local-quadratic residuals of 4-point windows, robust to the odd false alarm a track holds and to manoeuvres.
Measured on simulated scenes (0.3 and 1 m noise, 4-8 targets, 2-4 false alarms per scan): started *above*
the truth (2-30x), e is within 20 % of the truth after one pass (a wide gate holds every own detection);
started *below*, e is biased towards s (the narrow gate cuts the residuals: s = 0.3 m gives e ≈ 0.48 m for
1 m noise) and the tracks fragment; far above (7 m for 0.3 m noise at 10 Hz: the two-point start's
velocity std √2·s/Δt is then 100 m/s) the two-point start confirms no track at all (the one-point start, whose
velocity std is max_speed/3 whatever s, confirms the objects' tracks among many false ones, and e from their held
detections is near the truth). Hence:

1. s starts at an over-estimate from the data (``provisional_meas_std``): the lower quartile of the
   distance from a detection to the nearest one of the previous scan, over 1.07 (the lower quartile of that
   distance for a still object without clutter, 2σ·√(ln 4/3); 1.56σ in 3-D: ``nearest_distance_quartile``); motion and misses make it larger, and false
   alarms, which are mostly farther from their nearest neighbour, too (the quartile, not the median, so that
   scenes with more false alarms than target detections stay within a few times the truth);
2. each pass tracks at (s, q) and estimates e from the held detections, and the process noise q from the
   same sequences at the std e (``lgekf.apps.defaults.plan_noise``, what single-object ``lgekf track`` does:
   the prediction-error search);
3. e > 1.25·s (s below the truth): s ← 4·e (from above again); e < s/1.25: s ← e; no confirmed track: s ← s/4
   (too wide); confirmed tracks but none holding 4 detections: s ← 4·s (fragments of too narrow a noise);
   a step never goes back past a std already found too narrow or too wide (the geometric mean instead);
   once e agrees with s (within 1.25x) and (s, q) came from an estimate, that pass is the output (at most
   ``MAX_PASSES`` = 5 passes; typically 2; the output is the last pass, or the last that had an estimate).

A given ``--meas-std`` is kept fixed (the passes then estimate q only; e checks the given value); a given
``--accel-std`` too. With no confirmed track holding 4 detections in any pass nothing can be estimated: the
last pass is the output and the noise is the provisional one (said so).

The clutter density, when not given, is estimated by the tracker (``lgekf.estimators.multitarget.clutter``):
``--clutter map`` (the default) a spatial clutter map times the per-scan level, ``--clutter scan`` the per-scan
moment estimate (detections minus those the tracks are expected to explain), both over the area of the
detections' bounding box; ``--clutter file`` the mean number of detections per scan over that area (an
over-estimate: the targets' own detections count too). ``clutter_line`` says what was used.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numba as nb
import numpy as np

from ..core.initiation import DEFAULT_OMEGA_STD
from ..core.registry import BASE_MEASUREMENT, SPACES, get_measurement, get_model
from ..estimators.multitarget.clutter import ClutterMap, bounding_box_density
from ..estimators.multitarget.tracker import HEADING_CAP, IMM_MODEL, MultiTargetTracker
from ..io.formatting import format_rows, label_bytes, output_digits
from .defaults import NoisePlan, plan_noise
from .divergence import KIND_NAMES
from .multi_monitor import MultiMonitor, track_speed_course
from .noise import MIN_MEAS_STD, chord_speeds, measurement_std
from .track import MOTION_COLUMNS, motion_columns

__all__ = [
    "Scans", "scans", "scan_window_from_data", "estimated_clutter_density", "provisional_meas_std", "MultiRun",
    "track_scans", "NoiseFit", "fit_noise", "no_track_reason", "fastest_track_speed", "multi_alarm_line", "clutter_line",
    "multi_output_columns", "volume_unit", "nearest_distance_quartile",
    "write_multi", "SCAN_GAP_RATIO", "MAX_PASSES", "AGREE", "RESTART", "MIN_HELD",
]

SCAN_GAP_RATIO = 5.0  # scans: gaps between scans at least this many times the spread of a scan's times
MAX_BREAKS = 20  # scan_window_from_data: breaks tried at most
SCAN_CHECK_GROUPS = 200  # scan_window_from_data: groups whose nearest-neighbour distances are compared, at most
SCAN_CHECK_ROWS = 256  # ... and rows of each group
SCAN_SPACING_RATIO = 2.0  # ... a group's detections this much farther apart than from the previous group's: scans
PROVISIONAL_PAIRS = 2000  # provisional_meas_std: consecutive scan pairs looked at, at most (evenly spread)
MAX_PASSES = 5  # fit_noise: tracking passes at most
AGREE = 1.25  # fit_noise: e within s/AGREE .. s·AGREE: s agrees with the data
RESTART = 4.0  # fit_noise: s below the truth: start again from RESTART·e
MIN_HELD = 4  # a confirmed track's held detections enter the noise estimate from this many on (one 4-point window)


def nearest_distance_quartile(dim: int) -> float:
    """The lower quartile of |z1 − z0|/σ for z0, z1 ~ N(·, σ² I_d): |z1 − z0|/(√2 σ) is χ-distributed with d degrees
    of freedom, so √2·√(χ²_d quantile of 1/4) = √(4 P⁻¹(d/2, 1/4)) (P the regularised lower incomplete gamma
    function): 2√(ln 4/3) = 1.0727 in the plane (the Rayleigh quartile), 1.5572 in 3-D."""
    from scipy.special import gammaincinv

    return math.sqrt(4.0 * float(gammaincinv(0.5 * dim, 0.25)))


def volume_unit(dim: int) -> str:
    """The unit of a clutter density's volume: m² in the plane, m³ in 3-D space."""
    return {2: "m²", 3: "m³"}[dim]


@dataclass
class Scans:
    """The detections grouped into scans: scan k is rows ``order[starts[k]:starts[k + 1]]`` at time ``times[k]``.

    Attributes
    ----------
    order : ndarray of int, (N,)
        Row order sorted by time (stable).
    starts : ndarray of int, (K + 1,)
        Scan boundaries in ``order``.
    times : ndarray, (K,)
        Scan times: the midpoint of the scan's earliest and latest detection time.
    window : float
        The window used (s): a scan holds the detections at most this long after its earliest.
    """

    order: np.ndarray
    starts: np.ndarray
    times: np.ndarray
    window: float

    @property
    def count(self) -> int:
        """Number of scans."""
        return int(self.starts.size - 1)

    @property
    def period(self) -> float:
        """Median time between consecutive scans (s); nan with fewer than two scans."""
        return float(np.median(np.diff(self.times))) if self.times.size > 1 else float("nan")


@nb.njit(cache=True)
def _anchored_starts(ts, window):
    """Scan boundaries of sorted times ts: a scan holds the rows with ts − ts[first] ≤ window."""
    out = np.empty(ts.size + 1, dtype=np.int64)
    k = 0
    first = 0
    out[0] = 0
    for i in range(1, ts.size):
        if ts[i] - ts[first] > window:
            k += 1
            out[k] = i
            first = i
    out[k + 1] = ts.size
    return out[:k + 2]


def scans(t: np.ndarray, window: float = 0.0) -> Scans:
    """The scans of detection times t (N,) with time tolerance ``window`` ≥ 0 (s) (module docstring)."""
    order = np.argsort(t, kind="stable")
    ts = np.ascontiguousarray(t[order], dtype=float)
    if ts.size == 0:
        return Scans(order, np.zeros(1, dtype=np.int64), np.zeros(0), float(window))
    starts = _anchored_starts(ts, float(window))
    times = 0.5 * (ts[starts[:-1]] + ts[starts[1:] - 1])  # exact when the scan has one time
    return Scans(order, starts, times, float(window))


def _nearest_medians(ts, zs, first_row, sample):
    """Median distance from a detection to the nearest detection of *another time in its own group* and median
    distance from a detection to the nearest detection of the *previous group*, over the groups ``sample``
    (rows sorted by time ts, positions zs (N, d), group g = rows first_row[g]:first_row[g + 1]; of a group
    longer than ``SCAN_CHECK_ROWS`` rows its first ones, of the previous group its last ones)."""
    within, between = [], []
    for g in sample:
        a, b = first_row[g], min(first_row[g + 1], first_row[g] + SCAN_CHECK_ROWS)
        z, tt = zs[a:b], ts[a:b]
        d = np.linalg.norm(z[:, None, :] - z[None, :, :], axis=2)
        d[tt[:, None] == tt[None, :]] = np.inf  # the same time: not another detection of the scan
        near = d.min(axis=1)
        within.append(near[np.isfinite(near)])
        if g > 0:
            p = zs[max(first_row[g - 1], a - SCAN_CHECK_ROWS):a]
            between.append(np.linalg.norm(z[:, None, :] - p[None, :, :], axis=2).min(axis=1))
    w = np.concatenate(within) if within else np.zeros(0)
    v = np.concatenate(between) if between else np.zeros(0)
    return (float(np.median(w)) if w.size else math.nan), (float(np.median(v)) if v.size else math.nan)


def scan_window_from_data(t: np.ndarray, z: np.ndarray) -> float:
    """The default scan window (s) from the detection times t (N,) and positions z (N, d) (module docstring; d = 2 in
    the plane, 3 in 3-D space): 0 when the data show no scan structure coarser than their distinct times."""
    t = np.asarray(t, dtype=float)
    u = np.unique(t)
    g = np.diff(u)
    if g.size < 2:
        return 0.0
    gs = np.sort(g)
    ratio = gs[1:] / gs[:-1]
    order = np.argsort(t, kind="stable")
    ts, zs = t[order], np.asarray(z, dtype=float)[order]
    row_of_time = np.searchsorted(ts, u)  # first row of each distinct time
    for k in np.flatnonzero(ratio >= SCAN_GAP_RATIO)[::-1][:MAX_BREAKS]:  # largest break value first
        tau, d = gs[k], gs[k + 1]
        cut = np.flatnonzero(g > tau)  # a new group after these gaps
        first = np.concatenate([[0], cut + 1])
        last = np.concatenate([cut, [u.size - 1]])
        spread = float(np.max(u[last] - u[first]))
        if d < SCAN_GAP_RATIO * spread:
            continue
        first_row = np.append(row_of_time[first], ts.size)
        sample = np.unique(np.linspace(0, first.size - 1, min(first.size, SCAN_CHECK_GROUPS)).astype(np.int64))
        within, between = _nearest_medians(ts, zs, first_row, sample)
        if within > SCAN_SPACING_RATIO * between:  # a group holds different objects, the next the same ones again
            return math.sqrt(spread * d)
    return 0.0


def estimated_clutter_density(sc: Scans, z: np.ndarray) -> float:
    """Mean detections per scan / area of the detections' bounding box (per m² per scan, per m³ for positions z
    (N, 3); module docstring; ``lgekf.estimators.multitarget.clutter.bounding_box_density``)."""
    return bounding_box_density(z, sc.count, z.shape[1])


def provisional_meas_std(sc: Scans, z: np.ndarray, dim: int = 2) -> float | None:
    """The first pass's measurement std (m): the lower quartile of the distance from a detection to the nearest
    detection of the previous scan (positions: the first ``dim`` columns of z), over its value for a still object
    without clutter (``nearest_distance_quartile``: 1.07 in the plane; module docstring), from at most
    ``PROVISIONAL_PAIRS`` consecutive scan pairs spread evenly over the data; None when no two consecutive scans
    both hold detections."""
    from scipy.spatial import cKDTree

    K = sc.count
    if K < 2:
        return None
    pick = np.unique(np.linspace(0, K - 2, min(K - 1, PROVISIONAL_PAIRS)).astype(np.int64))
    dist = []
    for k in pick:
        a = z[sc.order[sc.starts[k]:sc.starts[k + 1]], :dim]
        b = z[sc.order[sc.starts[k + 1]:sc.starts[k + 2]], :dim]
        if a.shape[0] and b.shape[0]:
            dist.append(cKDTree(a).query(b)[0])
    if not dist:
        return None
    return max(float(np.quantile(np.concatenate(dist), 0.25)) / nearest_distance_quartile(dim), MIN_MEAS_STD)


@dataclass
class MultiRun:
    """One tracking pass over every scan.

    Attributes
    ----------
    ids : ndarray of int, (R,)
    times : ndarray, (R,)
    values : ndarray, (R, 2n + 1)
        The output rows: track id, scan time, state, stds and existence of every confirmed track and scan
        (rows in scan order, ids ascending).
    tracker : MultiTargetTracker
        The tracker after the last scan.
    held_t, held_z : ndarray, (H,), (H, m)
        The detections the confirmed tracks held (``MultiTargetTracker.held``), each at its own time,
        grouped by track (``held_starts``) and in time order within a track; only tracks holding at least
        ``MIN_HELD`` detections.
    held_starts : ndarray of int, (T + 1,)
    flags : ndarray of uint8, (R,)
        1 on the rows of a divergence alarm (``lgekf.apps.multi_monitor``), else 0.
    alarms : list of MultiAlarm
        The monitor's alarms (each one deleted its track).
    mu : ndarray, (R, M) or None
        With the IMM (``model="imm"``): the mode probabilities of each output row.
    clutter : ndarray, (K,)
        The mean clutter density of every scan (``MultiTargetTracker.clutter_density``; per m² (m³ in 3-D) per scan).
    """

    ids: np.ndarray
    times: np.ndarray
    values: np.ndarray
    tracker: MultiTargetTracker
    held_t: np.ndarray
    held_z: np.ndarray
    held_starts: np.ndarray
    flags: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=np.uint8))
    alarms: list = field(default_factory=list)
    mu: np.ndarray | None = None
    clutter: np.ndarray = field(default_factory=lambda: np.zeros(0))

    @property
    def n_confirmed(self) -> int:
        """Number of confirmed tracks (tracks in the output)."""
        return int(np.unique(self.ids).size)

    @property
    def fragments_only(self) -> bool:
        """Confirmed tracks, but none that held ``MIN_HELD`` detections (e.g. one-point tracks confirmed from two
        detections of a file whose scans each hold one detection)."""
        return self.n_confirmed > 0 and self.held_starts.size < 2


def track_scans(t: np.ndarray, Z: np.ndarray, sc: Scans, monitor: bool = True, **tracker_args) -> MultiRun:
    """Run a ``MultiTargetTracker(**tracker_args)`` over the scans ``sc`` of the detections (t (N,), Z (N, m)),
    with the divergence monitor (``lgekf.apps.multi_monitor``) unless ``monitor`` is False; the output rows and
    the confirmed tracks' held detections as a ``MultiRun``."""
    trk = MultiTargetTracker(**tracker_args)
    mon = MultiMonitor(trk.model, trk.meas.dim, trk.max_speed) if monitor else None
    order, starts = sc.order, sc.starts
    ids, times, vals, held_id, held_row, flagged, mus = [], [], [], [], [], [], []
    clutter = np.empty(sc.count)
    written = 0
    for k in range(sc.count):
        rows = order[starts[k]:starts[k + 1]]
        rep = trk.step(float(sc.times[k]), Z[rows])
        clutter[k] = trk.clutter_density
        hid, hj = trk.held
        if hid.size:
            held_id.append(hid)
            held_row.append(rows[hj])
        keep = slice(None)
        if mon is not None:
            flag_rows, keep = mon.scan(trk, rep, written)
            flagged += flag_rows
        if rep.ids[keep].size:
            ids.append(rep.ids[keep])
            times.append(np.full(rep.ids[keep].size, rep.t))
            vals.append(np.hstack([rep.states, rep.stds, rep.existence[:, None]])[keep])
            if rep.mu is not None:
                mus.append(rep.mu[keep])
            written += ids[-1].size
    n = len(trk.bank.state_names)
    modes = getattr(trk.bank, "modes", None)
    mu = None if modes is None else (np.vstack(mus) if mus else np.zeros((0, len(modes))))
    if not ids:
        ids, times, vals = np.zeros(0, dtype=np.int64), np.zeros(0), np.zeros((0, 2 * n + 1))
    else:
        ids, times, vals = np.concatenate(ids), np.concatenate(times), np.vstack(vals)
    flags = np.zeros(ids.size, dtype=np.uint8)
    flags[np.asarray(flagged, dtype=np.int64)] = 1
    hid = np.concatenate(held_id) if held_id else np.zeros(0, dtype=np.int64)
    hrow = np.concatenate(held_row) if held_row else np.zeros(0, dtype=np.int64)
    keep = np.isin(hid, ids)  # confirmed tracks only
    hid, hrow = hid[keep], hrow[keep]
    by = np.argsort(hid, kind="stable")  # by track, scan order within each
    hid, hrow = hid[by], hrow[by]
    count = np.unique(hid, return_counts=True)[1]
    hrow = hrow[np.repeat(count >= MIN_HELD, count)]
    counts = count[count >= MIN_HELD]
    hstarts = np.zeros(counts.size + 1, dtype=np.int64)
    np.cumsum(counts, out=hstarts[1:])
    return MultiRun(ids, times, vals, trk, t[hrow], Z[hrow], hstarts, flags, [] if mon is None else mon.alarms, mu,
                    clutter)


@dataclass
class NoiseFit:
    """The noise a run used and where it came from (``fit_noise``).

    Attributes
    ----------
    meas_std : float
        The position std used (m).
    meas_source : str
        "given", "data" (estimated from the held detections) or "provisional" (nothing to estimate from: the
        provisional std or where the passes left it).
    accel_std : tuple or None
        The process-noise stds used (None: the model's default); with the IMM its modes (``Mode`` list, the noise
        in them).
    plan : NoisePlan or None
        The estimate the values used came from (None: the first pass's values were kept).
    provisional : float or None
        The first pass's std when it was not given.
    passes : list of (float, float or None, int)
        Per pass: the std used, the std estimated from its held detections (None: none), confirmed tracks.
    converged : bool
        False when ``MAX_PASSES`` passes ended without the estimate agreeing with the std used.
    wider : (float, int, float) or None
        When the pass at the estimated noise confirmed no track that held ``MIN_HELD`` detections but an earlier
        pass at a wider std did: that std, its number of confirmed tracks and their fastest speed (m/s,
        ``fastest_track_speed``); typically objects faster than ``max_speed``, which only a wide noise let start.
    """

    meas_std: float
    meas_source: str
    accel_std: tuple | None
    plan: NoisePlan | None = None
    provisional: float | None = None
    passes: list = field(default_factory=list)
    converged: bool = True
    wider: tuple | None = None

    @property
    def check(self) -> float | None:
        """The std estimated from the output pass's held detections (None: no confirmed track held enough)."""
        return self.passes[-1][1] if self.passes else None

    def describe(self, model: str, accel_given: bool, heading_std: float | None = None, heading_given: bool = True) -> str:
        """One line for stderr: the noise used and where it came from (``lgekf track``'s wording; ``heading_std``:
        pose measurements, the heading std and whether it was given)."""
        if self.plan is not None:
            return self.plan.describe(heading_std, heading_given) + (f"; from the detections held by the confirmed tracks, {len(self.passes)} "
                                           f"tracking passes" + (f", the first at the provisional meas-std {self.provisional:.3g} m"
                                                                 if self.provisional is not None else "")
                                           + ("" if self.converged else f" (the estimate had not settled after {MAX_PASSES})"))
        n = len(self.passes)
        if self.meas_source == "given":
            meas = f"meas-std {self.meas_std:.3g} m (given)"
        else:
            dim = 2 if model == IMM_MODEL else SPACES[get_model(model).space]["dim"]
            first = ("no two consecutive scans hold detections" if self.provisional is None else
                     f"the first at the provisional {self.provisional:.3g} m: lower quartile of the distance to the previous "
                     f"scan's nearest detection / {nearest_distance_quartile(dim):.3g}")
            meas = f"meas-std {self.meas_std:.3g} m (not estimated; {n} tracking pass{'es' if n != 1 else ''}, {first})"
        if model == IMM_MODEL:  # the modes' noise: given as numbers or the models' defaults × their levels
            accel = "of the IMM's modes " + ", ".join(f"{m.name} {','.join(f'{v:.3g}' for v in m.accel_std)}"
                                                      for m in self.accel_std) + " (not estimated)"
        elif accel_given:
            accel = f"{model} {','.join(f'{v:.3g}' for v in self.accel_std)} (given)"
        else:
            accel = f"{model} {','.join(f'{v:.3g}' for v in get_model(model).default_accel_std)} (default)"
        head = "" if heading_std is None else f"; heading-std {heading_std:.3g} rad ({'given' if heading_given else 'default'})"
        return (f"noise from the data: {meas}; accel-std {accel}{head}; no confirmed track held {MIN_HELD} detections to "
                "estimate the noise from")


@dataclass
class _Pass:
    meas_std: float
    n_confirmed: int
    speed: float


def _held_plan(run: MultiRun, models: list, measurement: str, meas_std, accel_std, omega_std: float,
               heading_std: float) -> NoisePlan | None:
    """The noise of ``models`` from a run's held detections (``plan_noise`` on them; the measurement std estimated
    unless given, then estimated all the same as ``meas_estimate``; ``accel_std`` the given process noise, {model:
    stds}); None when no confirmed track holds ``MIN_HELD`` detections."""
    if run.held_starts.size < 2:
        return None
    d = run.tracker.dim  # the detections' position coordinates; a pose's angles after them
    est = measurement_std(run.held_t, run.held_z[:, :d], run.held_starts)
    if not est.usable:
        return None
    heading = None
    if get_measurement(measurement).has_angle:  # the plane's heading (H,), 3-D roll, pitch, yaw (H, 3)
        heading = run.held_z[:, d] if run.held_z.shape[1] == d + 1 else run.held_z[:, d:]
    plan = plan_noise(run.held_t, run.held_z[:, :d], run.held_starts, models, meas_std=est.meas_std if meas_std is None else meas_std,
                      accel_std=accel_std, omega_std=omega_std, heading_std=heading_std,
                      heading_cap=HEADING_CAP, heading=heading, measurement={m: measurement for m in models}, workers=1)
    plan.meas_source, plan.meas_estimate = ("data" if meas_std is None else "given"), est
    return plan


def _meas_tuple(s: float, measurement: str, heading_std: float):
    return get_measurement(measurement).stds(s, heading_std)


class _ProcessNoise:
    """The process noise of the tracker of ``tracker_args`` as ``fit_noise`` handles it: the models whose noise the
    data give (``models``), the given noise ({model: stds}) and the tracker's arguments for a plan's noise q ({model:
    stds} or None). A registry model: itself, ``accel_std``. The IMM (``IMM_MODEL``): the models of its modes whose
    noise is a named level or the default (``ImmTrackOptions.tunable_models``), each such mode getting the data's noise
    of its model × its level (as ``lgekf track --model imm``), as ``imm_modes``; modes given as numbers keep them."""

    def __init__(self, tracker_args: dict, accel_std):
        self.model = tracker_args["model"]
        self.imm = None
        if self.model == IMM_MODEL:
            from .track_imm import ImmTrackOptions

            self.imm = ImmTrackOptions(tracker_args.get("imm_modes"), tracker_args.get("imm_switch"))
            self.models = self.imm.tunable_models()
            self.given = {}
        else:
            self.models = [self.model]
            self.given = {} if accel_std is None else {self.model: accel_std}
        self.fixed = all(m in self.given for m in self.models)  # nothing for the data to set

    def learned(self, plan: NoisePlan):
        """The noise q of a plan: {model: stds} of the models estimated from the data (None: none)."""
        q = {m: plan.accel_std[m] for m in self.models if plan.accel_source[m] == "data"}
        return q or None

    def tracker_noise(self, q) -> dict:
        """The tracker's noise arguments for q (None: the given noise, else the defaults)."""
        if self.imm is None:
            return {"accel_std": self.given.get(self.model) if q is None else q[self.model]}
        from .track_imm import ImmTrackOptions

        opts = ImmTrackOptions(self.imm.modes_text if self.imm.modes_given else None, self.imm.switch)
        opts.with_learned_noise(q or {})
        return {"imm_modes": opts.modes}


def fit_noise(t, Z, sc: Scans, tracker_args: dict, *, meas_std: float | None = None, accel_std=None,
              heading_std: float, omega_std: float, monitor: bool = True) -> tuple[MultiRun, NoiseFit]:
    """Track the scans ``sc`` with the noise from the data (the passes of the module docstring).

    Parameters
    ----------
    t, Z : ndarray
        Detection times (N,) and detections (N, m).
    sc : Scans
        The scans.
    tracker_args : dict
        ``MultiTargetTracker`` arguments but ``meas_std`` and ``accel_std`` (``model`` and ``measurement`` among them).
    meas_std : float, optional
        A given position std (kept fixed); estimated when None.
    accel_std : tuple, optional
        Given process-noise stds (kept fixed); estimated when None.
    heading_std : float
        Pose measurements: the heading std (rad), given or default, never estimated.
    omega_std : float
        Initial turn-rate std (the search runs of ``plan_noise``).

    Returns
    -------
    run : MultiRun
        The output pass: the last one; the one before when the last, at the same std but with the process
        noise estimated, left no track to estimate from.
    fit : NoiseFit
        The noise it used.
    """
    measurement = tracker_args.get("measurement", BASE_MEASUREMENT)
    noise = _ProcessNoise(tracker_args, accel_std)
    args = {k: v for k, v in tracker_args.items() if k != "imm_modes"}
    provisional = None
    if meas_std is None:
        provisional = provisional_meas_std(sc, Z, SPACES[get_measurement(measurement).space]["dim"])
        s = 1.0 if provisional is None else provisional  # fewer than two scans hold detections: nothing to track anyway
    else:
        s = float(meas_std)
    q, used, passes, last = None, None, [], None  # used: the plan (s, q) came from; last: the previous pass with an estimate
    low, high = 0.0, math.inf  # stds known to be below the truth / to confirm no track
    while True:
        run = track_scans(t, Z, sc, monitor, meas_std=_meas_tuple(s, measurement, heading_std), **noise.tracker_noise(q), **args)
        plan = _held_plan(run, noise.models, measurement, meas_std, noise.given, omega_std, heading_std)
        e = None if plan is None else plan.meas_estimate.meas_std
        passes.append((s, e, run.n_confirmed))
        source = "given" if meas_std is not None else ("provisional" if used is None else "data")
        fit = NoiseFit(s, source, next(iter(noise.tracker_noise(q).values())), used, provisional, passes)
        agrees = plan is not None and (meas_std is not None or 1 / AGREE <= e / s <= AGREE)
        if agrees and (used is not None or (meas_std is not None and noise.fixed)):
            return run, fit
        if plan is None and last is not None:
            prev, prev_run, prev_fit = last
            if prev.meas_std > s:  # no estimate at the estimated noise, one at a wider noise: this pass, and say so
                fit.wider = (prev.meas_std, prev.n_confirmed, prev.speed)
                return run, fit
            prev_fit.converged = False  # the same std, the new process noise lost the tracks: the previous pass
            return prev_run, prev_fit
        if len(passes) == MAX_PASSES or (plan is None and (meas_std is not None or provisional is None)):
            fit.converged = False
            return run, fit
        if plan is None:
            if run.n_confirmed:  # tracks confirmed, none holding 4 detections: fragments of too narrow a noise
                low = max(low, s)
                s = RESTART * s if RESTART * s < high else math.sqrt(s * high)
            else:  # no track: too wide a noise (or data no noise helps: the passes run out)
                high = min(high, s)
                s = s / RESTART if s / RESTART > low else math.sqrt(s * low)
            continue
        last = (_Pass(s, run.n_confirmed, fastest_track_speed(run)), run, fit)
        if meas_std is None:
            if e > AGREE * s:  # s below the truth: e is biased towards s; from above again
                low = max(low, s)
                s = RESTART * e if RESTART * e < high else math.sqrt(e * high)
            else:
                s = e if e > low else math.sqrt(s * low)
        if not noise.fixed:
            q = noise.learned(plan)
        used = plan


def study_process_noise(times, detections, tracker_args: dict, meas_std: float, heading_std: float) -> tuple[dict, str]:
    """The process noise ``lgekf track --multi`` would estimate from a detection stream, for ``lgekf study --multi
    --noise data`` (``lgekf.experiments.multi_study.run_multi_study``'s ``noise_fit``): the tracking passes of
    ``fit_noise`` with the measurement std given (the study's), the process noise from the data, no monitor.

    Parameters
    ----------
    times : sequence of float
        The scans' times.
    detections : sequence of ndarray (M_k, m)
        The scans' detections.
    tracker_args : dict
        ``MultiTargetTracker`` arguments but ``meas_std`` and ``accel_std``.
    meas_std, heading_std : float
        The position std (m) and, for pose detections, the heading std (rad).

    Returns
    -------
    noise : dict
        The tracker's noise arguments: ``{"accel_std": stds}``, or ``{"imm_modes": modes}`` for the IMM.
    text : str
        The values, e.g. ``0.177,0.177,0.125``.
    """
    t = np.concatenate([np.full(len(Z), float(tk)) for tk, Z in zip(times, detections)])
    Z = np.vstack([np.asarray(Z, dtype=float) for Z in detections])
    sc = scans(t, 0.0)
    _, fit = fit_noise(t, Z, sc, tracker_args, meas_std=meas_std, accel_std=None, heading_std=heading_std,
                       omega_std=tracker_args.get("omega_std", DEFAULT_OMEGA_STD), monitor=False)
    if tracker_args["model"] == IMM_MODEL:
        return {"imm_modes": fit.accel_std}, " ".join(f"{m.name}:{','.join(f'{v:.3g}' for v in m.accel_std)}"
                                                      for m in fit.accel_std)
    q = fit.accel_std if fit.accel_std is not None else get_model(tracker_args["model"]).default_accel_std
    return {"accel_std": tuple(q)}, ",".join(f"{v:.3g}" for v in q)


def _round_up(v: float) -> str:
    """v rounded up to two significant digits, as text."""
    e = 10.0 ** (math.floor(math.log10(v)) - 1) if v > 0 else 1.0
    return f"{math.ceil(v / e) * e:g}"


def no_track_reason(run: MultiRun, sc: Scans, n_rows: int, max_speed: float, meas_std: float, confirm: float,
                    wider: tuple | None = None) -> str:
    """Why no track was confirmed (or, ``MultiRun.fragments_only``, none that held ``MIN_HELD`` detections), and what
    to try (one line): the scans (count, period, detections per scan, window), then the first that applies of:
    tracks confirmed only at a wider noise (``wider``: ``NoiseFit.wider``; with their speed against ``max_speed``),
    no track started (two-point: no pair of detections of consecutive scans within reach), tracks started but the
    largest existence reached below ``confirm`` (or only fragments confirmed)."""
    trk = run.tracker
    per_scan = n_rows / max(sc.count, 1)
    period = sc.period
    n = run.n_confirmed
    head = ("no track confirmed" if n == 0 else
            f"no track confirmed that held {MIN_HELD} detections ({n} confirmed, each holding fewer)")
    text = (f"{head}: {sc.count} scan{'s' if sc.count != 1 else ''} ("
            + ("" if not math.isfinite(period) else f"period {period:.3g} s, ")
            + f"{per_scan:.3g} detection{'s' if f'{per_scan:.3g}' != '1' else ''} per scan"
            + ("" if sc.window == 0 else f", scan window {sc.window:.3g} s") + "); ")
    hint = "; try --meas-std, --max-speed, --scan-window, --detection-prob or --clutter-density"
    if wider is not None:
        s, n, v = wider
        text += (f"none at the meas-std estimated from the data ({meas_std:.3g} m), {n} at the wider {s:.3g} m, the "
                 f"fastest moving at {v:.3g} m/s")
        if v >= 0.5 * max_speed:
            text += f": objects faster than --max-speed {max_speed:g} m/s start no track"
            hint = f"; try --max-speed {_round_up(1.25 * v)}"
    elif trk.next_id == 0:
        text += (f"no track started: no two detections of consecutive scans within --max-speed x dt + 3*sqrt(2) x "
                 f"meas-std ({max_speed:g} m/s, {meas_std:.3g} m)")
    elif n:
        text += f"{trk.next_id} track{'s' if trk.next_id != 1 else ''} started"
    else:
        text += (f"{trk.next_id} track{'s' if trk.next_id != 1 else ''} started, the largest existence reached "
                 f"{trk.max_existence:.2f} (confirmed at {confirm:g})")
    if per_scan < 1.5 and sc.count > 1:
        hint = ("; most scans hold a single detection: if each detection has its own time, group them into scans "
                "with --scan-window SECONDS" + hint.replace("; try", ", and try").replace(", --scan-window", ""))
    return text + hint


def fastest_track_speed(run: MultiRun) -> float:
    """The largest per-track median chord speed (m/s; ``lgekf.apps.noise.chord_speeds``) of the confirmed tracks'
    held detections; 0 when there are none."""
    if run.held_starts.size < 2:
        return 0.0
    c = chord_speeds(run.held_t, run.held_z[:, :run.tracker.dim], run.held_starts)
    best = 0.0
    for a, b in zip(run.held_starts[:-1], run.held_starts[1:]):
        v = c[a:b]
        v = v[np.isfinite(v)]
        if v.size:
            best = max(best, float(np.median(v)))
    return best


def multi_alarm_line(run: MultiRun, shown: int = 5) -> str:
    """One warning line about the monitor's alarms of a run: how many tracks, of which kinds, the first few ids and
    times."""
    kinds = sorted({a.kind for a in run.alarms})
    first = ", ".join(f"track {a.track} at t = {a.t:.6g} s ({KIND_NAMES[a.kind]})" for a in run.alarms[:shown])
    more = f" and {len(run.alarms) - shown} more" if len(run.alarms) > shown else ""
    return (f"possible divergence: {len(run.alarms)} track{'s' if len(run.alarms) != 1 else ''} deleted by the monitor "
            f"({', '.join(KIND_NAMES[k] for k in kinds)}): {first}{more}; their last rows have flag 1 and new tracks start "
            f"from the next detections (--no-monitor turns it off)")


def clutter_line(run: MultiRun) -> str:
    """One line about the clutter density a run estimated (``MultiRun.clutter``, the tracker's ``ScanClutter`` or
    ``ClutterMap``): what it is, the median and range of the per-scan level, a map's densest cell, how to fix it."""
    est, lam = run.tracker.clutter, run.clutter
    unit = volume_unit(run.tracker.dim)
    level = (f"median {np.median(lam):.3g} per {unit} per scan (range {lam.min():.3g} to {lam.max():.3g} over {lam.size} "
             f"scan{'s' if lam.size != 1 else ''})") if lam.size else "no scan"
    peak = f", the densest cell {est.peak():.3g}x the mean" if isinstance(est, ClutterMap) and lam.size else ""
    return (f"clutter density from the data: {est.describe()} over the detections' bounding box "
            f"({est.surveillance_area:.3g} {unit}), {level}{peak}; --clutter-density fixes it")


def multi_output_columns(model: str, modes=None) -> list:
    """The header: track, t, the model's state, std_<state>, speed, course (``multi_monitor.track_speed_course``: the
    world velocity's size and direction, whatever the model's state; a model of 3-D space also climb and turn_rate:
    ``lgekf.apps.track.motion_columns``), existence, flag (1 on a divergence alarm's rows,
    ``lgekf.apps.multi_monitor``). The IMM (``IMM_MODEL``): the combined estimate in the common coordinates x, y, theta,
    vx, vy, omega (the state names of se2r3, as ``lgekf track --model imm``), and the mode probabilities mu_<mode> of
    its ``modes`` after course."""
    if model == IMM_MODEL:
        from ..core.common import COMMON_NAMES
        from .track_imm import mode_columns

        names, mu, motion = list(COMMON_NAMES), mode_columns(modes), MOTION_COLUMNS  # the IMM: in the plane
    else:
        names, mu, motion = list(get_model(model).state_names), [], motion_columns(model)
    return ["track", "t", *names, *(f"std_{s}" for s in names), *motion, *mu, "existence", "flag"]


def write_multi(fh, model: str, run: MultiRun, digits: int | None, z=None) -> None:
    """Write the header and the rows of a ``MultiRun`` as CSV bytes to ``fh``. ``digits`` None (no ``--precision``):
    10 significant digits, the positions as many as keep 0.1 mm at the largest |x|, |y| of ``z`` (the detections;
    default the tracks' own), t 1 µs (``lgekf.io.formatting.output_digits``)."""
    cols = multi_output_columns(model, getattr(run.tracker.bank, "modes", None))
    fh.write((",".join(cols) + "\n").encode())
    if run.ids.size == 0:
        return
    n = len(run.tracker.bank.state_names)
    mu = [] if run.mu is None else [run.mu]
    values = np.hstack([run.values[:, :2 * n], track_speed_course(model, run.values[:, :n]), *mu, run.values[:, 2 * n:],
                        run.flags[:, None].astype(float)])
    labels, row = np.unique(run.ids, return_inverse=True)
    col_digits, t_digits = output_digits(cols[2:], digits, values[:, :2] if z is None else z, run.times)
    fh.write(format_rows(label_bytes([str(i) for i in labels]), row, run.times, values, col_digits, t_digits))
