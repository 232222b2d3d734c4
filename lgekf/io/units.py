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
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["TIME_UNITS", "MAX_PLAUSIBLE_DT", "MAX_PLAUSIBLE_SPEED", "MIN_DEGREE_LIKE_SPEED", "to_seconds", "unit_warnings",
           "heading_in_radians", "heading_agreement", "DEGREES_MARGIN"]

TIME_UNITS = {"s": 1.0, "ms": 1e-3, "us": 1e-6, "ns": 1e-9}
UNIT_NAMES = {"s": "seconds", "ms": "milliseconds", "us": "microseconds", "ns": "nanoseconds"}
MAX_PLAUSIBLE_DT = 10.0
MAX_PLAUSIBLE_SPEED = 300.0
MIN_DEGREE_LIKE_SPEED = 1e-3


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
