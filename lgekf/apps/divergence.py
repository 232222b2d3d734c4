"""Divergence monitoring and recovery of the filters in ``lgekf track``.

Monitor (per object, over the rows the filter produced since its last (re-)initialisation)
-----------------------------------------------------------------------------------------
* **NIS window**: the normalised innovations squared of the last W = ``window`` updates, each clipped at
  its 99.9 % chi-square quantile (m degrees of freedom, m = measurement dimension; so that one outlying
  measurement cannot trigger), are summed and compared with the (1 − α) quantile of the chi-square
  distribution with W·m degrees of freedom, α = ``alpha`` (default 1e-4 per test). For a consistent
  filter (NIS ~ χ²_m, independent) the clipped sum exceeds it with probability at most α; a filter that
  has become over-confident (covariance too small for its errors) exceeds it persistently.
* **Absurd speed**: the filter claims, at ``n_sigma`` (3) standard deviations, a speed above the object's
  limit ``speed_factor`` (2) × its largest chord speed over ≥ 1 s (``noise.chord_speeds``) + 5·√2·r/1 s
  (the chord's noise, r the measurement std in use) + ``speed_margin`` (1 m/s): a speed far above anything
  the data's finite differences show. The speed std is √λ_max of P on the state coordinates the speed
  depends on, times the gradient norm (exact for the models on Rⁿ and the R² / R³ velocity parts, an
  upper bound for the others' anisotropic blocks); the speed and its gradient come from the generated
  ``row_speeds`` (|``world_velocity``| of the monitored rows, read in place: no copy, no per-row allocation).
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
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numba as nb
import numpy as np

from ..core.covariance import unpack
from ..core.registry import get_model
from .noise import CHORD_S, chi2_quantile, chord_speeds

__all__ = ["MonitorConfig", "MonitorMemory", "Alarm", "speed_limits", "speeds", "speed_std", "first_alarms", "KIND_NAMES"]


KIND_NAMES = {1: "NIS", 2: "speed", 3: "non-finite"}
# the first window of rows filtered again after a re-initialisation (then doubled until the next alarm). The rows of
# a window past the next alarm are filtered in vain, a window costs a round of Python (~0.15 ms, the filtering of
# ~2000 rows); the noise search's low-noise candidates on one long object raise an alarm every few hundred rows:
# there 2⁸ rows cost least (the five searches, serial, on one object of 10⁶ rows: 2⁸ 1.36 CPU-s, 2¹⁰ 1.53, 2¹²
# 2.57, 2¹⁴ 6.6; 2⁶ and 2⁷ with windows growing 4x 1.50 and 1.38; the same plans); no change on 10⁴ objects
RERUN_ROWS = 1 << 8


@dataclass(frozen=True)
class MonitorConfig:
    """Parameters of the divergence monitor (see the module docstring)."""

    window: int = 10
    short: int = 3
    alpha: float = 1e-4
    clip: float = 1e-3  # each NIS is clipped at its (1 - clip) chi-square quantile
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
    √λ_max(P restricted to the coordinates the speed depends on)."""
    spec = get_model(model)
    n = spec.n
    N = x.shape[0]
    if N == 0:
        return np.empty(0)
    grad = np.empty((N, n))
    for i in range(n):
        h = 1e-6 * np.maximum(1.0, np.abs(x[:, i]))
        xp = x.copy()
        xm = x.copy()
        xp[:, i] += h
        xm[:, i] -= h
        grad[:, i] = (speeds(model, xp) - speeds(model, xm)) / (2 * h)
    P = unpack(p, n)
    out = np.empty(N)
    for r in range(N):
        s = np.flatnonzero(np.abs(grad[r]) > 1e-9 * max(1.0, np.abs(grad[r]).max()))
        if s.size == 0:
            out[r] = 0.0
            continue
        lam = np.linalg.eigvalsh(P[r][np.ix_(s, s)])[-1]
        out[r] = math.sqrt(max(lam, 0.0)) * float(np.linalg.norm(grad[r, s]))
    return out


@nb.njit(cache=True, nogil=True)
def _finite_rows(x, p, rows, out):
    """out[i] = every entry of x[rows[i]] and p[rows[i]] is finite."""
    for i in range(rows.shape[0]):
        r = rows[i]
        ok = True
        for j in range(x.shape[1]):
            if not np.isfinite(x[r, j]):
                ok = False
        for j in range(p.shape[1]):
            if not np.isfinite(p[r, j]):
                ok = False
        out[i] = ok


@nb.njit(cache=True, nogil=True)
def _scan(nis, absurd, over, bad, seg_first, seg_end, window, short, clip, thr, thr_short, out_row, out_kind, out_val,
          out_from):
    """First alarm per segment (row or -1), its kind, value (window mean NIS) and the first flagged row.
    Every row of a segment carries a NIS (no missed detections in ``lgekf track``). Each window's sum is added
    up afresh from its own rows (not a running sum), so that it does not depend on where the scan began: a
    scan from any row of the segment gives the same sums from there on (``lgekf.apps.windows``). A NaN NIS
    (possible through the library, not ``lgekf track``) silences only the windows that hold it; a running sum
    stayed NaN for the rest of the segment."""
    for s in range(seg_first.shape[0]):
        a, e = seg_first[s], seg_end[s]
        out_row[s] = -1
        count = 0
        run = 0
        for k in range(a, e):
            if bad[k]:
                out_row[s], out_kind[s], out_val[s], out_from[s] = k, 3, np.nan, k
                break
            run = run + 1 if over[k] else 0
            if absurd[k]:
                out_row[s], out_kind[s], out_val[s], out_from[s] = k, 2, 0.0, k - min(run, window) + 1
                break
            count += 1
            total_s = 0.0
            if count >= short:
                for j in range(k - short + 1, k + 1):
                    total_s += min(nis[j], clip)
            total = 0.0
            if count >= window:
                for j in range(k - window + 1, k + 1):
                    total += min(nis[j], clip)
            if count >= short and total_s > thr_short:
                out_row[s], out_kind[s], out_val[s], out_from[s] = k, 1, total_s / short, k - short + 1
                break
            if count >= window and total > thr:
                out_row[s], out_kind[s], out_val[s], out_from[s] = k, 1, total / window, k - window + 1
                break


def first_alarms(model: str, x, p, nis, seg_first, seg_end, limit_seg, m: int, cfg: MonitorConfig):
    """Scan the segments [seg_first[i], seg_end[i]) of the output arrays for their first alarm.

    Returns (row (S,), kind (S,), value (S,), first flagged row (S,), limit (S,)); row -1 = no alarm.
    ``limit_seg`` (S,) is each segment's speed limit. The speed and its std are computed only on the
    segments' rows (the std only where the speed exceeds the limit).
    """
    S = len(seg_first)
    N = x.shape[0]
    seg_first = np.asarray(seg_first, np.int64)
    seg_end = np.asarray(seg_end, np.int64)
    lens = seg_end - seg_first
    rows = np.repeat(seg_end - np.cumsum(lens), lens) + np.arange(int(lens.sum()))  # the segments' rows, in order
    lim_row = np.repeat(np.asarray(limit_seg, float), lens)
    over = np.zeros(N, np.bool_)
    absurd = np.zeros(N, np.bool_)
    bad = np.zeros(N, np.bool_)
    if rows.size:
        finite = np.empty(rows.size, np.bool_)
        _finite_rows(x, p, rows, finite)
        bad[rows] = ~finite
        sp = speeds(model, x, rows)  # a non-finite row's speed (nan) is not used: that row is an alarm of its own
        o = finite & (sp > lim_row)
        over[rows] = o
        if o.any():
            idx = np.flatnonzero(o)
            std = speed_std(model, x[rows[idx]], p[rows[idx]])
            absurd[rows[idx]] = sp[idx] - cfg.n_sigma * std > lim_row[idx]
    clip, thr, thr_short = cfg.nis_thresholds(m)
    out_row = np.empty(S, np.int64)
    out_kind = np.zeros(S, np.int64)
    out_val = np.zeros(S)
    out_from = np.zeros(S, np.int64)
    _scan(np.ascontiguousarray(nis, dtype=float), absurd, over, bad, seg_first, seg_end, int(cfg.window), int(cfg.short), float(clip), float(thr), float(thr_short),
          out_row, out_kind, out_val, out_from)
    hit = out_row >= 0
    sp_hit = out_kind == 2
    if np.any(hit & sp_hit):
        j = np.flatnonzero(hit & sp_hit)
        out_val[j] = speeds(model, x, out_row[j])
    short = (out_kind == 1) & (out_row - out_from + 1 == cfg.short)
    limit = np.where(out_kind == 1, np.where(short, thr_short / cfg.short, thr / cfg.window), np.asarray(limit_seg, float))
    return out_row, out_kind, out_val, out_from, limit


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


def recover(model: str, x, p, nis, starts, limits, m: int, cfg: MonitorConfig, reinit, rerun, first=None,
            memory: MonitorMemory | None = None):
    """Monitor every object's rows 2, 3, ... and re-initialise it at each alarm (in place).

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
    reinit : callable
        ``reinit(rows (R,), scale (R,)) -> (x0 (R, n), P0 packed (R, n(n+1)/2))``: the two-point estimate
        at each row, with the measurement std multiplied by ``scale``.
    rerun : callable
        ``rerun(first (R,), lengths (R,), s0 (R, ni), p0 (R, n(n+1)/2), scale (R,))``: filter rows first ..
        first + length - 1 of each segment from the filter's internal state s0 (the layout of the generated
        ``state_from_physical``) and packed covariance p0 at row first - 1, every noise std multiplied by
        ``scale``, writing into x, p, nis; s0 and p0 are left (in place) at the posterior of each segment's last
        row, from which a later call continues exactly.
    first : ndarray, (B,), optional
        The first monitored row of each object (default ``starts[:-1] + 2``: rows 0 and 1 of an object are its
        two-point start). An object with no row from there on is not monitored.
    memory : MonitorMemory, optional
        The objects' re-initialisations so far, read and updated in place (default: none yet). With ``first``,
        monitoring continues over a later window of the same objects' rows as over one array.

    Returns
    -------
    flag : ndarray, (N,) int8
        1 on the rows of each alarm through its re-initialisation row.
    alarms : list of Alarm
        In order of detection (rounds), at most ``max_reinit`` + 1 per object.
    """
    B = len(starts) - 1
    flag = np.zeros(x.shape[0], np.int8)
    alarms: list = []
    first = starts[:-1] + 2 if first is None else np.asarray(first, dtype=np.int64)
    seg_obj = np.flatnonzero(first < starts[1:])
    seg_first = first[seg_obj]
    seg_end = starts[seg_obj + 1]
    # after a re-initialisation the filter is rerun over a window of rows that doubles until the next alarm (or the
    # object's end); each window goes on from the filter's internal state at the end of the previous one (no window
    # refilters its predecessor's rows; the rows of a window past the next alarm are still filtered in vain) and is
    # scanned from `reach` rows before it, so that the numbers and alarms are those of one rerun to the end scanned
    # at once (a scan's tests at a row look back fewer than `reach` rows — NIS windows, the run of rows over the
    # speed limit: from `reach` rows on they are the tests of a scan from the segment's first row, and the rows
    # before were tested already)
    reach = max(int(cfg.window), int(cfg.short))
    spec = get_model(model)
    kernels, ni = spec.kernels, len(spec.internal_names)  # ni: the length of the filter's internal state
    scan_end = seg_end.copy()
    scan_from = seg_first.copy()
    seg_s = seg_p = None  # each rerun segment's internal state and covariance at its row scan_end - 1
    memory = MonitorMemory.fresh(B) if memory is None else memory
    count, scale, last = memory.count, memory.scale, memory.last  # updated in place: the caller's memory
    seg_scale = scale[seg_obj].copy()  # the noise inflation of each segment's run
    while seg_obj.size:
        row, kind, val, start, lim = first_alarms(model, x, p, nis, scan_from, scan_end, limits[seg_obj], m, cfg)
        hit = np.flatnonzero(row >= 0)
        grow = np.flatnonzero((row < 0) & (scan_end < seg_end))
        if hit.size == 0 and grow.size == 0:
            break
        # every alarm of the round at once: the segments of a round are of distinct objects (one each)
        o, g, k, v = seg_obj[hit], row[hit], kind[hit], val[hit]
        count[o] += 1
        again = (k == 1) & (g - last[o] <= cfg.repeat * cfg.window)
        if again.any():  # the same object again soon after its re-initialisation: its noise is too small
            scale[o[again]] *= np.minimum(np.sqrt(np.maximum(v[again] / m, 1.0)), cfg.max_inflation)
        ok = count[o] <= cfg.max_reinit
        alarms.extend(map(Alarm, o.tolist(), g.tolist(), k.tolist(), v.tolist(), lim[hit].tolist(),
                          np.where(k == 1, g - start[hit] + 1, 0).tolist(), ok.tolist(), scale[o].tolist()))
        # the NIS of update k tests the estimate of row k - 1 carried forward: flag from the row before the
        # alarm's first update (at most back to the segment's initialisation row) through the alarm row
        lo = np.maximum(np.maximum(start[hit], seg_first[hit]) - 1, 0)
        n = np.maximum(g + 1 - lo, 0)
        flag[np.repeat(lo - np.cumsum(n) + n, n) + np.arange(int(n.sum()))] = 1
        keep = hit[ok]
        last[o[ok]] = g[ok]
        finish = hit[~ok & (scan_end[hit] < seg_end[hit])]  # monitoring stops at this alarm: the run must still reach the end
        if finish.size:
            rerun(scan_end[finish], seg_end[finish] - scan_end[finish], seg_s[finish], seg_p[finish], seg_scale[finish])
        g = row[keep]
        obj = seg_obj[keep]
        if keep.size:
            x0, p0 = reinit(g, scale[obj])
            x[g] = x0
            p[g] = p0
            nis[g] = np.nan
        else:
            x0, p0 = x[:0], p[:0]
        end = seg_end[keep]
        more = g + 1 < end
        new_first = g[more] + 1
        s0 = np.empty((int(more.sum()), ni))
        kernels.states_from_physical(np.ascontiguousarray(x0[more], dtype=float), s0)
        # (object, first row, end, scan from, scan end, run from, state, covariance, noise inflation) of the next round
        nxt = [(obj[more], new_first, end[more], new_first, np.minimum(end[more], new_first + RERUN_ROWS), new_first, s0,
                np.array(p0[more], dtype=float), scale[obj[more]])]
        if grow.size:
            width = scan_end[grow] - seg_first[grow]
            nxt.append((seg_obj[grow], seg_first[grow], seg_end[grow], np.maximum(seg_first[grow], scan_end[grow] - reach),
                        np.minimum(seg_end[grow], seg_first[grow] + 2 * width), scan_end[grow], seg_s[grow], seg_p[grow],
                        seg_scale[grow]))
        seg_obj, seg_first, seg_end, scan_from, scan_end, run_from, seg_s, seg_p, seg_scale = (np.concatenate(parts)
                                                                                               for parts in zip(*nxt))
        if seg_obj.size:
            rerun(run_from, scan_end - run_from, seg_s, seg_p, seg_scale)  # leaves seg_s, seg_p at row scan_end - 1
    return flag, alarms
