"""Divergence monitoring and recovery of the filters in ``lgekf track``.

Monitor (per object, over the rows the filter produced since its last (re-)initialisation)
-----------------------------------------------------------------------------------------
* **NIS window**: the normalised innovations squared of the last W = ``window`` updates, each clipped at
  its 99.99 % chi-square quantile (m degrees of freedom, m = measurement dimension; so that one outlying
  measurement cannot trigger), are summed and compared with the (1 − α) quantile of the chi-square
  distribution with W·m degrees of freedom, α = ``alpha`` (default 1e-6 per test). For a consistent
  filter (NIS ~ χ²_m, independent) the clipped sum exceeds it with probability at most α; a filter that
  has become over-confident (covariance too small for its errors) exceeds it persistently.
* **Absurd speed**: the filter claims, at ``n_sigma`` (3) standard deviations, a speed above the object's
  limit ``speed_factor`` (2) × its largest chord speed over ≥ 1 s (``noise.chord_speeds``) + 5·√2·r/1 s
  (the chord's noise, r the measurement std in use) + ``speed_margin`` (1 m/s): a speed far above anything
  the data's finite differences show. The speed std is √λ_max of P on the state coordinates the speed
  depends on, times the gradient norm (exact for the models on Rⁿ and the R² / R³ velocity parts, an
  upper bound for the others' anisotropic blocks); the speed and its gradient come from the generated
  ``row_speeds`` (|``world_velocity``| of the monitored rows, read in place, no copy; the gradient by central
  differences of it, only on the rows over the limit).
* **Non-finite**: a NaN or infinite state or covariance entry.

Recovery: at the alarm row g the object is re-initialised by the two-point rule of its start
(``track.two_point``, from its measurement g and the latest one at least 0.5 s earlier), the estimate of
row g is that initial estimate (NIS nan), and the filter continues from row g + 1; the monitor restarts
(the NIS windows need new updates). An alarm is a lost filter, not always wrong noise (a maneuver the
model cannot follow, a bent LG-EKF update), so the first re-initialisation keeps the noise; an NIS alarm
within ``repeat`` × W = 30 rows of the object's previous re-initialisation says the noise itself is too
small for this object, and its noise stds (process and measurement) are inflated by √(mean NIS / m) of
that window (at most ×4 per alarm; covariance inflation through the noise, kept for the rest of the
object). At most ``max_reinit`` = 100 re-initialisations per object; later alarms are reported and the
object is left running.

Flags (the output's ``flag`` column): 1 on the rows of the alarm — the rows of the NIS window (or the
rows since the speed first exceeded the limit, at most W, or the non-finite row) and the row before them
(the NIS of an update tests the previous estimate carried forward) — through the re-initialisation row
g; 0 elsewhere.

Implementation: ``recover`` is one call of the generated ``recover_<meas>`` of the model (templates in
``derive/codegen/monitor.py``), which goes through the objects one after the other — scan, re-initialisation,
reruns — with no Python per alarm; ``first_alarms`` and ``speed_std`` run its scan and its speed std from Python.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numba as nb
import numpy as np

from ..core.initiation import SIDESLIP_FRACTION, attitude_rows
from ..core.registry import get_model
from .noise import CHORD_S, chi2_quantile, chord_speeds

__all__ = ["MonitorConfig", "MonitorMemory", "Alarm", "Restart", "Carry", "FirstPass", "recover", "speed_limits", "speeds", "speed_std", "first_alarms",
           "KIND_NAMES"]


KIND_NAMES = {1: "NIS", 2: "speed", 3: "non-finite"}
# the first window of rows filtered again after a re-initialisation (then doubled until the next alarm): the rows of a
# window past the next alarm are filtered in vain, and a window costs a kernel call and a scan. The noise search's
# low-noise candidates on one long object raise an alarm every few hundred rows: the five searches, serial, on one object
# of 10⁶ rows, CPU-s (2026-11-24, compiled monitor): 2⁴ 0.874, 2⁵ 0.868, 2⁶ 0.856, 2⁷ 0.886, 2⁸ 0.921, 2¹⁰ 1.135; on 10⁴
# objects of 100 rows within 0.03 s whatever the size; the same plans
RERUN_ROWS = 1 << 6


@dataclass(frozen=True)
class MonitorConfig:
    """Parameters of the divergence monitor (see the module docstring)."""

    window: int = 10
    short: int = 3
    # α and the clip hold about one false alarm per 10⁶ rows of a benign track at 10 Hz (0 to 2 alarms on 2 x 10⁶ rows of
    # a smooth car, every model; α 1e-4 and clip 1e-3 gave 29 to 54, 2026-11-29); α 3e-7 missed a divergence of the
    # robustness set (irregular steps, se2r2). The clip stays low enough that three clipped NIS can still exceed the
    # short window's threshold (3 x 18.4 > 38.3).
    alpha: float = 1e-6
    clip: float = 1e-4  # each NIS is clipped at its (1 - clip) chi-square quantile
    speed_factor: float = 2.0
    speed_margin: float = 1.0
    n_sigma: float = 3.0
    max_reinit: int = 100
    repeat: int = 3  # an NIS alarm within repeat x window rows of the object's last re-initialisation inflates its noise
    max_inflation: float = 4.0  # at most this factor on the noise stds per inflation

    def nis_thresholds(self, m: int) -> tuple:
        """(clip value of one NIS, threshold of the clipped sum over ``window`` updates, and over ``short``
        updates) for m-dimensional measurements."""
        return (chi2_quantile(1.0 - self.clip, m), chi2_quantile(1.0 - self.alpha, self.window * m),
                chi2_quantile(1.0 - self.alpha, self.short * m))


@dataclass
class Alarm:
    """One detected divergence: object index, row (global), its kind (1 NIS, 2 speed, 3 non-finite),
    the monitored value and its threshold."""

    obj: int
    row: int
    kind: int
    value: float
    limit: float
    updates: int = 0  # length of the NIS window that triggered (kind 1)
    reinitialised: bool = True  # False once the object's max_reinit re-initialisations are used up
    scale: float = 1.0  # the object's noise inflation (factor on every noise std) from this alarm on

    @property
    def kind_name(self) -> str:
        return KIND_NAMES[self.kind]


@nb.njit(cache=True, nogil=True)
def _segment_finite_max(c, starts, out):
    """out[b] = the largest finite value of c[starts[b]:starts[b + 1]] (0 if none or below 0)."""
    for b in range(starts.shape[0] - 1):
        top = 0.0
        for i in range(starts[b], starts[b + 1]):
            v = c[i]
            if np.isfinite(v) and v > top:
                top = v
        out[b] = top


def speed_limits(t, z, starts, meas_std: float, cfg: MonitorConfig) -> np.ndarray:
    """Per object (B,): the speed above which an estimate is absurd for it (m/s)."""
    c = chord_speeds(t, z, starts)
    top = np.empty(len(starts) - 1)
    _segment_finite_max(c, np.asarray(starts, dtype=np.int64), top)
    return cfg.speed_factor * top + 5.0 * math.sqrt(2.0) * meas_std / CHORD_S + cfg.speed_margin


def speeds(model: str, x: np.ndarray, rows: np.ndarray | None = None) -> np.ndarray:
    """|world velocity| (N,) of physical states x (N, n), or (R,) of its rows ``rows`` (R,) only.

    The generated ``row_speeds`` (``hypot`` of the definition's ``world_velocity``): no per-row allocation and
    no gathered copy of x[rows].
    """
    x = np.ascontiguousarray(x, dtype=float)
    rows = np.arange(x.shape[0], dtype=np.int64) if rows is None else np.ascontiguousarray(rows, dtype=np.int64)
    out = np.empty(rows.shape[0])
    get_model(model).kernels.row_speeds(x, rows, out)
    return out


def speed_std(model: str, x: np.ndarray, p: np.ndarray) -> np.ndarray:
    """Std (N,) of the speed of states x (N, n) with packed covariances p (N, n(n+1)/2): |∇speed| ·
    √λ_max(P restricted to the coordinates the speed depends on), the gradient by central differences (the
    generated ``speed_stds``, whose ``speed_std_at`` the compiled monitor calls)."""
    x = np.ascontiguousarray(x, dtype=float)
    out = np.empty(x.shape[0])
    get_model(model).kernels.speed_stds(x, np.ascontiguousarray(p, dtype=float), out)
    return out


def first_alarms(model: str, x, p, nis, seg_first, seg_end, limit_seg, m: int, cfg: MonitorConfig):
    """Scan the segments [seg_first[i], seg_end[i]) of the output arrays for their first alarm: the generated
    ``first_alarm`` (the scan ``recover``'s compiled loop makes) called per segment from Python, to inspect a run.

    Returns (row (S,), kind (S,), value (S,), first flagged row (S,), limit (S,)); row -1 = no alarm.
    ``limit_seg`` (S,) is each segment's speed limit. The speed is computed only on the segments' rows, its std
    only where the speed exceeds the limit.
    """
    kernel = get_model(model).kernels.first_alarm
    x = np.ascontiguousarray(x, dtype=float)
    p = np.ascontiguousarray(p, dtype=float)
    nis = np.ascontiguousarray(nis, dtype=float)
    N, n = x.shape
    S = len(seg_first)
    over, absurd, bad = (np.zeros(N, np.bool_) for _ in range(3))
    sp, rows, xh, grad = np.empty(N), np.empty(N, np.int64), np.empty((1, n)), np.empty(n)
    clip, thr, thr_short = cfg.nis_thresholds(m)
    out = (np.empty(S, np.int64), np.zeros(S, np.int64), np.zeros(S), np.zeros(S, np.int64), np.zeros(S))
    for i in range(S):
        found = kernel(x, p, nis, int(seg_first[i]), int(seg_end[i]), float(limit_seg[i]), int(cfg.window), int(cfg.short), float(clip),
                       float(thr), float(thr_short), float(cfg.n_sigma), over, absurd, bad, sp, rows, xh, grad)
        for column, value in zip(out, found):
            column[i] = value
    return out


@dataclass
class MonitorMemory:
    """What the monitor remembers of each object between calls of ``recover`` over consecutive windows of its rows
    (``lgekf.apps.windows``): its re-initialisations so far, its noise inflation, the row of its last
    re-initialisation (in the row numbers of the arrays ``recover`` is given: shift ``last`` when they move)."""

    count: np.ndarray
    scale: np.ndarray
    last: np.ndarray

    @classmethod
    def fresh(cls, objects: int) -> "MonitorMemory":
        """No alarm yet for any of ``objects`` objects."""
        return cls(np.zeros(objects, np.int64), np.ones(objects), np.full(objects, NEVER, dtype=np.int64))


NEVER = -(10**18)  # the row of the last re-initialisation of an object that has had none


@dataclass(frozen=True)
class Restart:
    """What ``recover`` needs to re-initialise an object and filter it again: the inputs of the generated
    ``recover_<meas>`` besides the outputs and the monitor's settings.

    ``t`` (T,), ``z`` (T, 2) positions, ``heading`` (T,) or None, ``zm`` (T, m): the times and measurements (those of
    the two-point re-initialisation, ``lgekf.core.initiation.two_point``, and the filter's), an output row k being
    their row k + ``offset``; ``q``, ``r``: the filter's noise stds; ``obj_first`` (B,): each object's first row of
    t (the earliest a re-initialisation may use); ``meas_std``, ``omega_std``, ``heading_std``, ``heading_cap``: the
    two-point start's parameters; ``baseline``: the least time between its two measurements (s,
    the generated ``reinit_earlier_row``).
    """

    measurement: str
    t: np.ndarray
    z: np.ndarray
    heading: np.ndarray | None
    zm: np.ndarray
    q: np.ndarray
    r: np.ndarray
    obj_first: np.ndarray
    meas_std: float
    omega_std: float
    heading_std: float
    heading_cap: float
    baseline: float
    offset: int = 0


@dataclass
class Carry:
    """Where ``recover`` left each object's filter when a run or a re-initialisation reached its last row
    (``reached`` True): the internal state (the layout of the generated ``state_from_physical``), the packed covariance
    and the noise inflation of that run (``lgekf.apps.windows`` goes on from there)."""

    s: np.ndarray
    p: np.ndarray
    scale: np.ndarray
    reached: np.ndarray

    @classmethod
    def empty(cls, model: str, objects: int) -> "Carry":
        spec = get_model(model)
        return cls(np.zeros((objects, len(spec.internal_names))), np.zeros((objects, spec.n_packed)), np.ones(objects),
                   np.zeros(objects, np.bool_))


@dataclass
class FirstPass:
    """The filter's first pass over each object, made by ``recover`` before it monitors (one compiled library with the
    filter's step per model, not two): rows ``start`` (B,) on, from the internal state ``s`` (B, ni) and packed
    covariance ``p`` (B, n(n+1)/2) of the row before, every noise std times ``scale`` (B,)."""

    start: np.ndarray
    s: np.ndarray
    p: np.ndarray
    scale: np.ndarray


def recover(model: str, x, p, nis, starts, limits, m: int, cfg: MonitorConfig, restart: Restart, first=None,
            memory: MonitorMemory | None = None, carry: Carry | None = None, first_pass: FirstPass | None = None):
    """Monitor every object's rows 2, 3, ... and re-initialise it at each alarm (in place): one call of the
    generated ``recover_<meas>`` (``derive/codegen/monitor.py``), object after object, no Python per alarm.

    Each object is scanned for its first alarm (``first_alarm``); at an alarm row g it is re-initialised there
    (``restart``), and the filter runs again from g + 1 over a window of ``RERUN_ROWS`` rows that doubles until
    the next alarm or the object's end; each window goes on from the filter's internal state at the end of the
    previous one and is scanned from max(window, short) rows before it (a test at a row looks back fewer rows than
    that; the rows before were tested already), so that the numbers and alarms are those of one rerun to the end
    scanned at once.

    Parameters
    ----------
    model : str
    x, p, nis : ndarray
        The tracker's outputs (N, n), (N, n(n+1)/2), (N,), overwritten after each re-initialisation.
    starts : ndarray, (B + 1,)
        Object offsets.
    limits : ndarray, (B,)
        Speed limits (``speed_limits``).
    m : int
        Measurement dimension.
    cfg : MonitorConfig
    restart : Restart
        The re-initialisation's measurements and the filter's inputs.
    first : ndarray, (B,), optional
        The first monitored row of each object (default ``starts[:-1] + 2``: rows 0 and 1 of an object are its
        two-point start). An object with no row from there on is not monitored.
    memory : MonitorMemory, optional
        The objects' re-initialisations so far, read and updated in place (default: none yet). With ``first``,
        monitoring continues over a later window of the same objects' rows as over one array.
    carry : Carry, optional
        Filled where a run or a re-initialisation reached an object's last row.
    first_pass : FirstPass, optional
        Filter the objects' rows from ``first_pass.start`` on before monitoring them (default: x, p, nis hold them).

    Returns
    -------
    flag : ndarray, (N,) int8
        1 on the rows of each alarm through its re-initialisation row.
    alarms : list of Alarm
        Object after object, each object's in order of detection; at most ``max_reinit`` + 1 per object.
    """
    spec = get_model(model)
    B = len(starts) - 1
    starts = np.asarray(starts, dtype=np.int64)
    flag = np.zeros(x.shape[0], np.int8)
    first = starts[:-1] + 2 if first is None else np.asarray(first, dtype=np.int64)
    todo = first < starts[1:]
    if first_pass is not None:
        todo |= np.asarray(first_pass.start) < starts[1:]
    seg_obj = np.flatnonzero(todo)
    memory = MonitorMemory.fresh(B) if memory is None else memory
    carry = Carry.empty(model, B) if carry is None else carry
    clip, thr, thr_short = cfg.nis_thresholds(m)
    rs = restart
    heading = attitude_rows(rs.heading)
    t_all = np.ascontiguousarray(rs.t, dtype=float)
    rows = slice(int(rs.offset), int(rs.offset) + x.shape[0])  # the outputs' rows of t, zm
    kernel = spec.kernel("recover", rs.measurement)
    if first_pass is None:
        run_first, run_s, run_p, run_scale = np.full(seg_obj.size, -1, np.int64), carry.s[:0], carry.p[:0], carry.scale[:0]
    else:
        fp = first_pass
        run_first = np.asarray(fp.start, dtype=np.int64)[seg_obj]
        run_s, run_p = np.ascontiguousarray(fp.s[seg_obj], dtype=float), np.ascontiguousarray(fp.p[seg_obj], dtype=float)
        run_scale = np.ascontiguousarray(np.asarray(fp.scale, dtype=float)[seg_obj])
    found = kernel(x, p, nis, flag, seg_obj, first[seg_obj], starts[seg_obj + 1], run_first, run_s, run_p, run_scale,
                   np.ascontiguousarray(limits, dtype=float), int(m),
                   int(cfg.window), int(cfg.short), float(clip), float(thr), float(thr_short), float(cfg.n_sigma), int(cfg.max_reinit),
                   int(cfg.repeat), float(cfg.max_inflation), int(RERUN_ROWS), memory.count, memory.scale, memory.last,
                   np.ascontiguousarray(rs.zm[rows], dtype=float), t_all[rows], np.ascontiguousarray(rs.q, dtype=float),
                   np.ascontiguousarray(rs.r, dtype=float), t_all, np.ascontiguousarray(rs.z, dtype=float),
                   heading, int(rs.offset), np.ascontiguousarray(rs.obj_first, dtype=np.int64), float(rs.meas_std), float(rs.omega_std),
                   float(rs.heading_std), float(rs.heading_cap), SIDESLIP_FRACTION, float(rs.baseline),
                   np.array(spec.angles, dtype=np.int64), carry.s, carry.p, carry.scale, carry.reached)
    ints = found[:, [0, 1, 2, 5]].astype(np.int64).T.tolist()
    alarms = list(map(Alarm, ints[0], ints[1], ints[2], found[:, 3].tolist(), found[:, 4].tolist(), ints[3], (found[:, 6] != 0).tolist(),
                      found[:, 7].tolist()))
    return flag, alarms
