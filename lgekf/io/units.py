"""Units of a measurement file: the time unit (``--time-unit``) and a plausibility check.

The filters work in seconds and metres. A file in other units is accepted silently by the parser, so
``unit_warnings`` looks at the median time step and the median speed between consecutive measurements
of the same object and returns one line per implausible value, saying what to do:

* median step ≥ ``MAX_PLAUSIBLE_DT`` (10 s): probably milli-, micro- or nanoseconds (the unit that
  brings the step between 1 ms and 10 s is suggested) — or genuinely slow sampling, then ignore it;
* median speed > ``MAX_PLAUSIBLE_SPEED`` (300 m/s, faster than an airliner): x, y not in metres or t not
  in seconds;
* median speed below 1 mm/s with every x, y within ±180: x, y are probably degrees (a lat, lon pair
  moves about 1e-5 "units" per second at walking speed); such files need ``lat, lon`` columns.

Those medians are over all objects, so one object in other units among many is not seen there (and its noise, its
speed, would spoil the noise estimated for all). ``object_warnings`` checks each object against the others and names
it (its id as written) with the time of its first offending row:

* scale: its median speed and its jitter (median |z_{k+1} − 2 z_k + z_{k−1}|, mostly measurement noise) both at
  least ``SCALE_RATIO`` (50) times those of the median object, by factors within ``SCALE_AGREE`` (3) of each other:
  one object in mm or cm among objects in metres (a units mistake scales both alike; a faster object has a larger
  speed, a noisier sensor a larger jitter, not both). The other direction (one object in km) is not checked: it looks
  like a standing object whose positions are interpolated (speed and jitter near 0, common in annotated pedestrian
  sets); its class's measurement std then hits its floor, which ``lgekf track`` says (``lgekf.apps.defaults``);
* speed: its median speed above ``MAX_PLAUSIBLE_SPEED`` while the file's is plausible;
* step: a step of at least ``MAX_PLAUSIBLE_DT`` and ``GAP_RATIO`` times its own median step (a gap: the filter
  predicts across it, see ``lgekf.apps.defaults.after_gaps``), when the file's median step is plausible.

At most ``MAX_OBJECT_LINES`` lines per check, then one line counting the rest.
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

__all__ = ["TIME_UNITS", "MAX_PLAUSIBLE_DT", "MAX_PLAUSIBLE_SPEED", "MIN_DEGREE_LIKE_SPEED", "to_seconds", "unit_warnings",
           "heading_in_radians", "heading_agreement", "DEGREES_MARGIN", "object_warnings", "gap_rows", "SCALE_RATIO", "GAP_RATIO",
           "MAX_OBJECT_LINES"]

TIME_UNITS = {"s": 1.0, "ms": 1e-3, "us": 1e-6, "ns": 1e-9}
UNIT_NAMES = {"s": "seconds", "ms": "milliseconds", "us": "microseconds", "ns": "nanoseconds"}
MAX_PLAUSIBLE_DT = 10.0
MAX_PLAUSIBLE_SPEED = 300.0
MIN_DEGREE_LIKE_SPEED = 1e-3
SCALE_RATIO = 50.0
SCALE_AGREE = 3.0
GAP_RATIO = 10.0
MAX_OBJECT_LINES = 5


def to_seconds(t: np.ndarray, unit: str) -> np.ndarray:
    """Times converted to seconds.

    Parameters
    ----------
    t : ndarray
        Times in ``unit``.
    unit : str
        A key of ``TIME_UNITS`` (s, ms, us, ns).

    Returns
    -------
    ndarray
        ``t`` itself for seconds, else a new array.
    """
    if unit not in TIME_UNITS:
        raise ValueError(f"--time-unit: unknown unit {unit!r}; choose one of {', '.join(TIME_UNITS)}")
    return t if unit == "s" else t * TIME_UNITS[unit]


STEP_BLOCK = 1 << 16  # pairs computed at a time by ``_step_values``


def _step_values(t, z, starts, what: str, out: np.ndarray) -> int:
    """The time step (``what="dt"``) or the speed (``"speed"``: distance / dt) of every consecutive pair of rows of
    the same object (rows sorted by object), in row order, written to ``out[:n]``; returns n.

    Computed ``STEP_BLOCK`` pairs at a time, so that ``out`` is the only array of the rows' size (a whole-array
    ``np.diff`` of z and its hypot held five: 40 MB at 10⁶ rows). The values are those of the whole-array
    expressions ``np.diff(t)`` and ``np.hypot(*np.diff(z, axis=0).T) / np.diff(t)``, element by element.
    """
    n_rows = t.shape[0]
    cut = np.asarray(starts[1:-1], dtype=np.int64) - 1  # pairs across two objects (sorted)
    n = 0
    for a in range(0, n_rows - 1, STEP_BLOCK):
        b = min(a + STEP_BLOCK, n_rows - 1)
        v = t[a + 1:b + 1] - t[a:b]
        if what == "speed":
            dz = z[a + 1:b + 1] - z[a:b]
            with np.errstate(divide="ignore", invalid="ignore"):  # a pair across two objects may share a time: dropped below
                v = np.hypot(dz[:, 0], dz[:, 1]) / v
        lo, hi = np.searchsorted(cut, [a, b])
        if hi > lo:
            keep = np.ones(b - a, dtype=bool)
            keep[cut[lo:hi] - a] = False
            v = v[keep]
        out[n:n + v.size] = v
        n += v.size
    return n


def unit_warnings(t, z, starts, time_unit: str = "s", projected: bool = False, fmt: str = "csv") -> list[str]:
    """Lines (without a prefix) describing implausible units, empty when all looks like s and m.

    Parameters
    ----------
    t : ndarray (N,)
        Times in seconds, sorted by object, increasing within each.
    z : ndarray (N, 2)
        Positions.
    starts : ndarray (B + 1,)
        Row offsets of the objects.
    time_unit : str
        The ``--time-unit`` given (named in the advice).
    projected : bool
        True when z was projected from lat, lon (then the degree hint is not given).
    fmt : str
        ``"csv"`` or ``"pedestrian"`` (whose time comes from ``--frame-dt`` and which has no column names:
        the advice is adapted).

    Returns
    -------
    list of str
        At most one line about the time step and one about the speed.
    """
    t, z = np.asarray(t, float), np.asarray(z, float)
    buf = np.empty(max(t.shape[0] - 1, 0))  # the one array of the rows' size: the steps, then the speeds
    n = _step_values(t, z, starts, "dt", buf)
    if n == 0:
        return []
    out = []
    med_dt = float(np.median(buf[:n], overwrite_input=True))  # the median of a multiset: the order does not matter
    dt_flagged = med_dt >= MAX_PLAUSIBLE_DT
    if dt_flagged:
        scale = TIME_UNITS[time_unit]
        fits = [u for u, f in TIME_UNITS.items() if f < scale and 1e-3 <= med_dt * f / scale <= MAX_PLAUSIBLE_DT]
        if fmt == "pedestrian":
            advice = "check --frame-dt (seconds per frame unit: 0.04 for ETH/UCY's 10 frames = 0.4 s)"
        else:
            advice = (f"if t is in {UNIT_NAMES[fits[0]]}, add --time-unit {fits[0]}" if fits
                      else "check the unit of t (--time-unit s|ms|us|ns)")
        out.append(f"the median time step is {med_dt:.4g} s: {advice} (ignore this if the sampling really is that slow)")
    _step_values(t, z, starts, "speed", buf)
    med_v = float(np.median(buf[:n], overwrite_input=True))
    if med_v > MAX_PLAUSIBLE_SPEED:
        hint = "see --frame-dt" if fmt == "pedestrian" else "degrees go in lat, lon columns; see --time-unit for t"
        out.append(f"the median speed is {med_v:.3g} m/s: x, y should be metres and t seconds ({hint})")
    elif (0.0 < med_v < MIN_DEGREE_LIKE_SPEED and fmt == "csv" and not projected and not dt_flagged
          and max(-float(z.min()), float(z.max())) <= 180.0):  # max |z| without an |z| copy
        out.append(f"the median speed is {med_v:.3g} m/s: if x, y are degrees of longitude and latitude, "
                   "name the columns lon, lat instead (they are then projected to metres)")
    return out


@nb.njit(cache=True, nogil=True, error_model="numpy")
def _object_medians(t, z, starts, speed, step, jitter, longest_step):
    """Per object b: the median speed and time step over its consecutive pairs and its median jitter
    |z_{k+1} − 2 z_k + z_{k−1}| (nan without any), the non-finite values left out, and its longest step (0 without
    any); one scratch buffer of the longest object's size."""
    longest = 0
    for b in range(starts.shape[0] - 1):
        longest = max(longest, starts[b + 1] - starts[b])
    buf = np.empty(max(longest, 1))
    for b in range(starts.shape[0] - 1):
        a, e = starts[b], starts[b + 1]
        longest_step[b] = 0.0
        for k in range(a, e - 1):
            longest_step[b] = max(longest_step[b], t[k + 1] - t[k])
        for what in range(3):
            n = 0
            for k in range(a, e - 1 - (what == 2)):
                if what == 0:
                    v = math.hypot(z[k + 1, 0] - z[k, 0], z[k + 1, 1] - z[k, 1]) / (t[k + 1] - t[k])
                elif what == 1:
                    v = t[k + 1] - t[k]
                else:
                    v = math.hypot(z[k + 2, 0] - 2 * z[k + 1, 0] + z[k, 0], z[k + 2, 1] - 2 * z[k + 1, 1] + z[k, 1])
                if np.isfinite(v):
                    buf[n] = v
                    n += 1
            m = np.median(buf[:n]) if n > 0 else np.nan
            if what == 0:
                speed[b] = m
            elif what == 1:
                step[b] = m
            else:
                jitter[b] = m


def _when(t, time_unit):
    return f"t = {t / TIME_UNITS[time_unit]:.15g}{'' if time_unit == 's' else ' ' + time_unit}"


@nb.njit(cache=True, nogil=True)
def _gap_rows(t, starts, min_gap, ratio, out):
    for b in range(starts.shape[0] - 1):
        a, e = starts[b], starts[b + 1]
        if e - a < 2:
            continue
        d = t[a + 1:e] - t[a:e - 1]
        med = np.median(d[np.isfinite(d)]) if np.isfinite(d).any() else np.nan
        for k in range(d.shape[0]):
            out[a + 1 + k] = d[k] >= min_gap and d[k] > ratio * med


def gap_rows(t, starts) -> np.ndarray:
    """(N,) bool: the rows that end a gap, a step of at least ``MAX_PLAUSIBLE_DT`` and ``GAP_RATIO`` times its object's
    median step (rows sorted by object with ``starts``). The one definition of a gap: warned about per object
    (``object_warnings``) and left out of the process-noise search's score (``lgekf.apps.defaults.after_gaps``)."""
    out = np.zeros(len(t), dtype=np.bool_)
    _gap_rows(np.ascontiguousarray(t, dtype=float), np.asarray(starts, dtype=np.int64), MAX_PLAUSIBLE_DT, GAP_RATIO, out)
    return out


def object_warnings(t, z, starts, labels, time_unit: str = "s", where=None) -> list[str]:
    """Lines (without a prefix) naming the objects whose scale, speed or steps are implausible beside the others
    (module docstring); empty when every object looks like the rest. ``labels`` (B,): the objects' ids as written;
    ``where`` (optional, ``Measurements.where``): row index -> "line N", named beside the time of a row.
    Arrays of the rows' size: one (the file's medians, as ``unit_warnings``)."""
    t = np.ascontiguousarray(t, dtype=float)
    z = np.ascontiguousarray(np.asarray(z, float)[:, :2])
    starts = np.asarray(starts, dtype=np.int64)
    B = len(starts) - 1
    if B == 0 or t.size < 2:
        return []
    speed_b, dt_b, jit_b, long_b = np.empty(B), np.empty(B), np.empty(B), np.empty(B)
    _object_medians(t, z, starts, speed_b, dt_b, jit_b, long_b)
    buf = np.empty(t.size - 1)
    n = _step_values(t, z, starts, "dt", buf)
    if n == 0:
        return []
    file_dt = float(np.median(buf[:n], overwrite_input=True))
    _step_values(t, z, starts, "speed", buf)
    file_speed = float(np.median(buf[:n], overwrite_input=True))
    del buf

    def first_row(b, bad):
        """The time of object b's first row at which ``bad`` (a bool over its pairs: from the previous row) holds."""
        k = np.flatnonzero(bad)
        row = starts[b] + 1 + int(k[0]) if k.size else starts[b]
        at = where(row) if where is not None else ""
        return f"{at} ({_when(t[row], time_unit)})" if at else _when(t[row], time_unit)

    def capped(lines, what):
        if len(lines) > MAX_OBJECT_LINES:
            return lines[:MAX_OBJECT_LINES] + [f"... and {len(lines) - MAX_OBJECT_LINES} more objects with {what}"]
        return lines

    out = []
    named = set()
    ok_v, ok_j = np.isfinite(speed_b), np.isfinite(jit_b)
    med_v = float(np.median(speed_b[ok_v])) if ok_v.any() else math.nan
    med_j = float(np.median(jit_b[ok_j])) if ok_j.any() else math.nan
    if B >= 3 and med_v > 0 and med_j > 0:
        scale = []
        with np.errstate(invalid="ignore", divide="ignore"):
            rv, rj = speed_b / med_v, jit_b / med_j
            odd = (rv >= SCALE_RATIO) & (rj >= SCALE_RATIO) & (np.abs(np.log(rv / rj)) <= math.log(SCALE_AGREE))
        for b in np.flatnonzero(odd):
            f = float(np.sqrt(rv[b] * rj[b]))
            named.add(int(b))
            scale.append(f"object {labels[b]}: its median speed {speed_b[b]:.3g} m/s and its jitter {jit_b[b]:.3g} m are "
                         f"about {f:.3g} times those of the other objects ({med_v:.3g} m/s, {med_j:.3g} m), from "
                         f"{_when(t[starts[b]], time_unit)}: x, y in {'mm' if f > 300 else 'cm'}? lgekf expects metres")
        out += capped(scale, "another scale")
    if file_speed <= MAX_PLAUSIBLE_SPEED:
        fast = []
        for b in np.flatnonzero(speed_b > MAX_PLAUSIBLE_SPEED):
            if int(b) in named:
                continue
            a, e = starts[b], starts[b + 1]
            with np.errstate(divide="ignore", invalid="ignore"):
                v = np.hypot(*np.diff(z[a:e], axis=0).T) / np.diff(t[a:e])
            fast.append(f"object {labels[b]}: median speed {speed_b[b]:.3g} m/s (the file's {file_speed:.3g} m/s), first "
                        f"above {MAX_PLAUSIBLE_SPEED:g} m/s at {first_row(b, v > MAX_PLAUSIBLE_SPEED)}: x, y should be metres")
        out += capped(fast, "implausible speeds")
    if file_dt < MAX_PLAUSIBLE_DT:
        gaps = []
        ends = gap_rows(t, starts)
        for b in np.unique(np.searchsorted(starts, np.flatnonzero(ends), side="right") - 1):
            a, e = starts[b], starts[b + 1]
            d = np.diff(t[a:e])
            bad = ends[a + 1:e]  # the pairs (k, k + 1) of the object whose step is a gap
            if bad.any():
                gaps.append(f"object {labels[b]}: a gap of {float(d[bad].max()):.4g} s (its median step {dt_b[b]:.3g} s), "
                            f"the first ending at {first_row(b, bad)}: the filter predicts across it (split the object "
                            "if it is two)")
        out += capped(gaps, "gaps")
    return out


DEGREES_MARGIN = 0.3  # the heading follows the direction of motion this much better (mean cosine) read as degrees


def heading_agreement(h, z, starts) -> tuple[float, float]:
    """How well the heading column follows the direction of motion, read as radians and as degrees: the mean of
    cos(h − course) over the moving steps (a step longer than the median step of the file; course = atan2 of the step
    from row k to k + 1 of an object, h at row k). NaN, NaN without such steps."""
    starts = np.asarray(starts, dtype=np.int64)
    inside = np.ones(max(len(h) - 1, 0), bool)
    inside[starts[1:-1] - 1] = False  # steps across two objects
    d = np.diff(np.asarray(z, float)[:, :2], axis=0)[inside]
    hk = np.asarray(h, float)[:-1][inside]
    step = np.hypot(d[:, 0], d[:, 1])
    ok = np.isfinite(step) & np.isfinite(hk) & (step > 0)
    if not ok.any():
        return math.nan, math.nan
    moving = ok & (step >= np.median(step[ok]))
    course = np.arctan2(d[moving, 1], d[moving, 0])
    return float(np.mean(np.cos(hk[moving] - course))), float(np.mean(np.cos(np.radians(hk[moving]) - course)))


def heading_in_radians(h, unit, z, starts):
    """The heading column in radians. ``unit`` "deg": converted; "rad": as it is; None (not given): radians, but when a
    value lies beyond ±2π (degrees, or an unwrapped heading in radians) and the column follows the direction of motion
    clearly better read as degrees (``heading_agreement``, by ``DEGREES_MARGIN``), one ValueError saying to give
    ``--heading-unit deg`` (a heading in degrees read as radians tracked worse than the raw positions)."""
    if unit == "deg":
        return np.radians(h)
    if unit == "rad" or not np.any(np.abs(h) > 2 * math.pi + 1e-9):
        return h
    as_rad, as_deg = heading_agreement(h, z, starts)
    if as_deg > as_rad + DEGREES_MARGIN:
        big = np.abs(h) > 2 * math.pi + 1e-9
        raise ValueError(f"heading column: {int(big.sum())} value{'s' if big.sum() > 1 else ''} beyond ±2π (largest "
                         f"{float(np.nanmax(np.abs(h))):g}), and it follows the direction of motion as degrees (mean cos "
                         f"{as_deg:.2f}), not as radians ({as_rad:.2f}): give --heading-unit deg (or rad to keep radians)")
    return h
