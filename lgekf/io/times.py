"""ISO-8601 date-times in a t column, read as seconds since the Unix epoch (1970-01-01T00:00:00Z).

Accepted: ``YYYY-MM-DD``, then optionally ``T`` or one space and ``hh[:mm[:ss[.fff...]]]``, then optionally a zone:
``Z``, ``±hh:mm`` or ``±hhmm``. A stamp without a zone is UTC (naive = UTC). Fractions are kept to the nanosecond
while parsing; the result is float64 seconds since the epoch, whose spacing near 2024 (1.7e9 s) is 2.4e-7 s: times
stay exact to well under 1 µs. The output writes t with enough digits to keep 1 µs (``lgekf.io.formatting.data_digits``).

Conventions: a whole column is either numbers (seconds, or ``--time-unit``) or date-times, decided by its first row.
"""

from __future__ import annotations

import warnings

import numpy as np

__all__ = ["looks_iso", "iso_seconds", "IsoError", "ISO_HINT"]

ISO_HINT = ("t must be numbers (seconds, or give --time-unit ms|us|ns) or ISO-8601 date-times such as "
            "2024-05-01T12:00:00.125Z (no zone = UTC)")

_EPOCH = np.datetime64("1970-01-01T00:00:00", "ns")


class IsoError(ValueError):
    """``iso_seconds`` found a value that is not an ISO-8601 date-time: ``index`` is its row."""

    def __init__(self, index: int, value: str):
        super().__init__(value)
        self.index, self.value = index, value


def looks_iso(text: str) -> bool:
    """Whether a single value starts like an ISO-8601 date (``YYYY-MM-DD``)."""
    s = text.strip()
    return len(s) >= 10 and s[:4].isdigit() and s[4] == "-" and s[5:7].isdigit() and s[7] == "-" and s[8:10].isdigit()


def _codes(a: np.ndarray) -> np.ndarray:
    w = max(a.dtype.itemsize // 4, 1)
    return np.ascontiguousarray(a.astype(f"U{w}")).view(np.uint32).reshape(a.size, w)


def iso_seconds(texts) -> np.ndarray:
    """Seconds since the epoch (float64) of ISO-8601 date-times (see the module's doc).

    Parameters
    ----------
    texts : array_like of str
        One date-time per row (surrounding spaces ignored).

    Returns
    -------
    ndarray of float64

    Raises
    ------
    IsoError
        With the index and text of the first value that is not an accepted date-time.
    """
    a = np.char.strip(np.asarray(texts, dtype=str))
    n = a.size
    if n == 0:
        return np.empty(0)
    c = _codes(a).copy()
    w = c.shape[1]
    ln = np.char.str_len(a).astype(np.int64)
    rows = np.arange(n)
    dash, colon, plus, minus, zed = ord("-"), ord(":"), ord("+"), ord("-"), ord("Z")

    def at(k):  # the character at position k from the end (k < 0) of every row, 0 where the row is shorter
        idx = ln + k
        ok = idx >= 0
        out = np.zeros(n, np.uint32)
        out[ok] = c[rows[ok], idx[ok]]
        return out

    def digit(v):
        return (v >= ord("0")) & (v <= ord("9"))

    shape_ok = (ln >= 10) & (c[:, 4] == dash) & (c[:, 7] == dash) if w >= 10 else np.zeros(n, bool)
    offset = np.zeros(n, np.int64)  # seconds east of UTC
    z = (at(-1) == zed) | (at(-1) == ord("z"))
    cut = np.where(z, 1, 0)
    # ±hh:mm (after the time: the sign at position 19 or later, beyond the date's dashes)
    s6, s3 = at(-6), at(-3)
    hm = ~z & (ln >= 16) & ((s6 == plus) | (s6 == minus)) & (s3 == colon) & digit(at(-5)) & digit(at(-4)) & digit(at(-2)) & digit(at(-1))
    hm &= (ln - 6) > 10
    s5 = at(-5)
    hhmm = ~z & ~hm & (ln >= 15) & ((s5 == plus) | (s5 == minus)) & digit(at(-4)) & digit(at(-3)) & digit(at(-2)) & digit(at(-1))
    hhmm &= (ln - 5) > 10
    for mask, k, sign_pos, h1, m1 in ((hm, 6, -6, -5, -2), (hhmm, 5, -5, -4, -2)):
        if mask.any():
            hh = (at(h1).astype(np.int64) - 48) * 10 + (at(h1 + 1).astype(np.int64) - 48)
            mm = (at(m1).astype(np.int64) - 48) * 10 + (at(m1 + 1).astype(np.int64) - 48)
            sign = np.where(at(sign_pos) == minus, -1, 1)
            offset = np.where(mask, sign * (hh * 3600 + mm * 60), offset)
            cut = np.where(mask, k, cut)
    if cut.any():  # the zone removed: its characters set to NUL (numpy's str ends at the first trailing NUL)
        pos = np.arange(w)[None, :]
        c[pos >= (ln - cut)[:, None]] = 0
    sep = c[:, 10] == ord(" ") if w > 10 else np.zeros(n, bool)
    if sep.any():
        c[sep, 10] = ord("T")
    b = c.view(f"U{w}").ravel()
    bad = ~shape_ok
    if bad.any():
        k = int(np.flatnonzero(bad)[0])
        raise IsoError(k, str(a[k]))
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # numpy's note on a zone it converts itself (±hh)
            dt = b.astype("datetime64[ns]")
    except ValueError:
        for k, v in enumerate(b.tolist()):
            try:
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    np.datetime64(v, "ns")
            except ValueError:
                raise IsoError(k, str(a[k])) from None
        raise
    if np.isnat(dt).any():
        k = int(np.flatnonzero(np.isnat(dt))[0])
        raise IsoError(k, str(a[k]))
    ns = (dt - _EPOCH).astype(np.int64) - offset * 1_000_000_000
    whole = np.floor_divide(ns, 1_000_000_000)
    return whole.astype(np.float64) + (ns - whole * 1_000_000_000).astype(np.float64) * 1e-9
