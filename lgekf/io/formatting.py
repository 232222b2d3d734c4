"""Fast CSV output: numbers formatted like Python's ``%.{digits}g`` inside numba (exact for float64),
labels and rows assembled into one byte buffer.

A number's digits: its decimal exponent from the binary one (``_decimal_exponent``), then round(|v|·10^k) from
ONE double product or quotient, exact but where the scaled value's fraction is exactly 1/2 (then the
double-double ``_round_scaled``; ``_round_scaled_fast`` has the proof). The text is written 8 digits a store
(``_put_digits``) straight into the output (no scratch copy), trailing zeros dropped from the integer first.
``tests/io/test_formatting_exact.py`` checks every byte against the formatter this replaced (about 2.7x slower) and
against Python's ``%g``; ``benchmarks/bench_format.py`` times both.
"""

from __future__ import annotations

import math
import re
from collections import deque
from concurrent.futures import ThreadPoolExecutor

import numba as nb
import numpy as np

from .cpus import usable_cpus as _cpus  # a module name of its own: tests set it

__all__ = ["format_rows", "write_rows", "write_rows_made", "format_g", "label_bytes", "data_digits", "output_digits",
           "DEFAULT_DIGITS", "POSITION_RESOLUTION", "TIME_RESOLUTION", "POSITION_COLUMNS"]

DEFAULT_DIGITS = 10  # significant digits of the output's numbers when --precision is not given
POSITION_RESOLUTION = 1e-4  # m: without --precision, positions are written to at least 0.1 mm
TIME_RESOLUTION = 1e-6  # s: t is written to at least 1 µs (epoch seconds: 16 digits)
T_DIGITS = 15  # t's digits at least (as always)
POSITION_COLUMNS = ("x", "y", "z", "smooth_x", "smooth_y", "smooth_z")

PARALLEL_ROWS = 1 << 13  # format_rows uses one thread per this many rows (at most one per CPU)
PARTS_PER_THREAD = 4  # the rows are cut into this many parts per thread (load balance; see _formatted_parts)
PART_ROWS = 1 << 12  # write_rows_made makes, formats and writes this many rows at a time per thread


@nb.njit(cache=True)
def _two_prod(a, b):
    """a*b = p + e exactly (Dekker's split; no FMA needed)."""
    p = a * b
    c = 134217729.0 * a
    ah = c - (c - a)
    al = a - ah
    c = 134217729.0 * b
    bh = c - (c - b)
    bl = b - bh
    e = ((ah * bh - p) + ah * bl + al * bh) + al * bl
    return p, e


# 10^0 .. 10^22: every one exactly representable (a table lookup instead of pow: the same doubles)
_P10F = np.array([10.0**i for i in range(23)])
# _decimal_exponent's test v >= 10^k as v·_EXP_SCALE[k+22] >= _EXP_BOUND[k+22], k = -22..22: (1, 10^k) for
# k >= 0 (exact), (10^-k, 1) for k < 0 (v·10^-k rounded, as it always was)
_EXP_SCALE = np.concatenate([_P10F[:0:-1], np.ones(23)])
_EXP_BOUND = np.concatenate([np.ones(22), _P10F])


@nb.njit(cache=True, error_model="numpy")
def _round_scaled(a, k):
    """round(a * 10^k) as an int64 (a > 0), ties to even.

    For |k| <= 22 (10^|k| exact) the product or quotient is carried in double-double, so the result is
    the correctly rounded one except in rare near-ties; beyond, a few ulp of error remain.
    """
    while k > 22:
        a *= 1e22
        k -= 22
    while k < -22:
        a /= 1e22
        k += 22
    if k >= 0:
        hi, lo = _two_prod(a, _P10F[k])
    else:
        d = _P10F[-k]
        hi = a / d
        p, e = _two_prod(hi, d)
        lo = ((a - p) - e) / d
    f = math.floor(hi)
    frac = (hi - f) + lo
    g = math.floor(frac)
    frac -= g
    q = np.int64(f) + np.int64(g)
    return q + np.int64((frac > 0.5) | ((frac == 0.5) & (q % 2 == 1)))  # up, or a tie to even: no branch


_POW10 = np.array([10**i for i in range(19)], dtype=np.int64)
_POW10U = _POW10.astype(np.uint64)
_PAIRS = np.frombuffer(b"".join(b"%02d" % i for i in range(100)), dtype=np.uint8).copy()
_PAIRS16 = _PAIRS[0::2].astype(np.uint16) | (_PAIRS[1::2].astype(np.uint16) << 8)  # "ab" as one little-endian uint16
_TWO52 = 4503599627370496.0  # 2^52: below it a double's ulp is at most 1/2


@nb.njit(cache=True, inline="always")
def _decimal_exponent(v):
    """floor(log10(v)) for v > 0, from the binary exponent and one comparison with a power of ten (no log10).

    Exact but for v within an ulp or so of a power of ten, where it may be one off: ``_decimal_digits``
    corrects either way by the size of its rounded digits (as it always did for log10's own rounding), to the
    same digits where they are exact (|p - 1 - e| <= 22); elsewhere ``_decimal_digits`` starts from log10.
    """
    biased = np.int64((np.float64(v).view(np.uint64) >> np.uint64(52)) & np.uint64(0x7FF))
    if biased > 0:
        e2 = biased - 1022  # frexp's exponent of a normal number: v in [2^(e2-1), 2^e2)
    else:
        e2 = math.frexp(v)[1]  # subnormal
    e = ((e2 - 1) * 78913) >> 18  # floor((e2 - 1)·log10 2) (exact for |e2| < 1650): floor(log10 v) or one less
    k = e + 1
    if -22 <= k <= 22:  # e = k if v >= 10^k, tested as v·10^-k >= 1 for k < 0; no branch on the outcome
        e += np.int64(v * _EXP_SCALE[k + 22] >= _EXP_BOUND[k + 22])
    else:
        e = int(math.floor(math.log10(v)))
    return e


@nb.njit(cache=True, error_model="numpy", inline="always")
def _round_scaled_fast(a, k):
    """round(a * 10^k) as an int64 (a > 0), ties to even: the same integer as ``_round_scaled``.

    Fast path for |k| <= 22, where 10^|k| is an exact double: h = fl(a·10^k) or fl(a / 10^|k|), ONE
    correctly rounded operation, so |h - x| <= ulp(h)/2 for the exact x = a·10^k. If 1 <= h < 2^52 then
    ulp(h) <= 1/2, so h - floor(h) and 1/2 are both multiples of ulp(h): unless h's fractional part is
    exactly 1/2, the nearest half-integer is at least ulp(h) from h, more than x's distance from h; x lies
    strictly on h's side of every half-integer, so round(x) = round(h) and x is no tie. This is the correctly
    rounded integer, and also ``_round_scaled``'s (its double-double error, at most about 2^-54 + ulp(h)·2^-52
    in the fractional part, is below x's distance ulp(h)/2 >= 2^-53 from the half-integer). Otherwise
    (|k| > 22, h < 1, h >= 2^52 or a fractional part of exactly 1/2): ``_round_scaled``.
    """
    if 0 <= k <= 22:
        h = a * _P10F[k]
    elif -22 <= k < 0:
        h = a / _P10F[-k]
    else:
        return _round_scaled(a, k)
    if 1.0 <= h < _TWO52:
        q = np.int64(h)  # floor (h > 0)
        frac = h - np.float64(q)  # exact
        if frac != 0.5:
            return q + np.int64(frac > 0.5)  # no branch on the (random) outcome
    return _round_scaled(a, k)


@nb.njit(cache=True, error_model="numpy", inline="always")
def _ascii4(u):
    """The 4 ASCII digits of u < 10^4 (zero-padded) in one integer, the first digit in the lowest byte."""
    hundred = np.uint64(100)
    a = u // hundred
    return np.uint64(_PAIRS16[a]) | (np.uint64(_PAIRS16[u - a * hundred]) << np.uint64(16))


@nb.njit(cache=True, error_model="numpy", inline="always")
def _put_digits8(buf, at, u):
    """Write the 8 digits of u < 10^8 (zero-padded) into buf[at:at + 8].

    Two independent 4-digit halves (two digits per table entry) in one integer, stored byte by byte at unsigned
    indices (no test for a negative one), stores that LLVM merges into wider ones.
    """
    ten4 = np.uint64(10000)
    a = u // ten4
    w = _ascii4(a) | (_ascii4(u - a * ten4) << np.uint64(32))
    i = np.uint64(at)
    m = np.uint64(255)
    buf[i] = w & m
    buf[i + np.uint64(1)] = (w >> np.uint64(8)) & m
    buf[i + np.uint64(2)] = (w >> np.uint64(16)) & m
    buf[i + np.uint64(3)] = (w >> np.uint64(24)) & m
    buf[i + np.uint64(4)] = (w >> np.uint64(32)) & m
    buf[i + np.uint64(5)] = (w >> np.uint64(40)) & m
    buf[i + np.uint64(6)] = (w >> np.uint64(48)) & m
    buf[i + np.uint64(7)] = w >> np.uint64(56)


@nb.njit(cache=True, error_model="numpy", inline="always")
def _put_digits(buf, start, q, n):
    """Write the n digits of q (10^(n-1) <= q < 10^n, n <= 17) into buf[start:start + n].

    q is first scaled to 8 or 16 digits (trailing zeros) and written 8 digits at a time (``_put_digits8``): so
    up to start + 17 is overwritten (scratch beyond start + n).
    """
    u = np.uint64(q)
    ten8 = np.uint64(100000000)
    if n <= 8:
        _put_digits8(buf, start, u * _POW10U[8 - n])
    else:
        if n == 17:
            d = u // np.uint64(10000000000000000)
            buf[start] = np.uint8(48 + d)
            u -= d * np.uint64(10000000000000000)
            start += 1
        else:
            u *= _POW10U[16 - n]
        h = u // ten8
        _put_digits8(buf, start, h)
        _put_digits8(buf, start + 8, u - h * ten8)


@nb.njit(cache=True, error_model="numpy", inline="always")
def _decimal_digits(v, p):
    """(q, n, e): v > 0 (finite) ≈ q·10^(e+1-n), rounded to p significant digits like ``'%.{p}g'``.

    q has n digits: n = p, except for an integer v of at most p digits (then q = v, n = e + 1, exact).
    Digits are round(v·10^(p-1-e)) (``_round_scaled_fast``, the double-double ``_round_scaled`` where one
    product is not enough): when |p-1-e| <= 21 and 1e-22 <= v < 1e22 (p = 17: v in [1e-5, 1e22); p = 10:
    [1e-12, 1e22)) this is the correctly rounded decimal except in rare near-ties (the scaled value's fraction
    within about 2^-54 of 1/2: ``_round_scaled``'s double-double rounds it as 1/2); outside, the last of 16-17
    digits can be off by one unit, and next to a power of ten (log10's start) the result can be the
    neighbouring p-digit decimal (e.g. 9.999999999999994e22 at p = 15: 1e+23). Exactly the digits of the
    formatter before the fast path, everywhere (tests/io/test_formatting_exact.py).
    """
    e = _decimal_exponent(v)
    if 0 <= e < p and e <= 22 and v == math.floor(v):  # an integer of e + 1 <= p digits: as is
        return np.int64(v), e + 1, e
    if not -21 <= p - 1 - e <= 21:  # digits not exact (see above): log10's start, whose one-off cases give these digits
        e = int(math.floor(math.log10(v)))
    top = _POW10[p]
    q = _round_scaled_fast(v, p - 1 - e)
    if q >= top:
        e += 1
        q = _round_scaled_fast(v, p - 1 - e)
    elif q < top // 10:
        e -= 1
        q = _round_scaled_fast(v, p - 1 - e)
    if q >= top:  # rounding carried into a new digit (e.g. 9.9999 -> 10.000)
        q = top // 10
        e += 1
    return q, p, e


@nb.njit(cache=True, error_model="numpy", inline="always")
def _put_decimal(buf, pos, q, n, e, p):
    """Write q·10^(e+1-n) (q of n digits) as ``%g`` with precision p into buf at pos: fixed notation for
    -4 <= e < p, else d.ddde±XX; trailing zeros (and a bare point) dropped. Return the new position.

    The trailing zeros are dropped from q before writing (the end is known without reading the text back).
    Writes up to 23 bytes past pos (digits in groups of 8, then the integer part moved) even when the text
    is shorter.
    """
    u = np.uint64(q)
    ten = np.uint64(10)
    while n > 1 and u % ten == 0:
        u = u // ten
        n -= 1
    if 0 <= e < p and n > e + 1:  # d.ddd: the digits at pos+1.., the integer part moved one left, the point
        _put_digits(buf, pos + 1, u, n)
        b = np.uint64(pos)  # unsigned indices here: no test for a negative one
        for i in range(np.uint64(e + 1)):
            buf[b + i] = buf[b + i + np.uint64(1)]
        buf[b + np.uint64(e + 1)] = 46
        end = pos + 1 + n
    elif -4 <= e < 0:  # 0.000ddd
        b = np.uint64(pos)
        buf[b] = 48
        buf[b + np.uint64(1)] = 46
        buf[b + np.uint64(2)] = 48
        buf[b + np.uint64(3)] = 48
        buf[b + np.uint64(4)] = 48
        _put_digits(buf, pos + 1 - e, u, n)
        end = pos + 1 - e + n
    else:  # the rarer layouts share one (inlined) digit writer: an integer (e + 1 digits), d.ddde±XX
        integer = 0 <= e < p
        if integer:
            u *= _POW10U[e + 1 - n]
            n = e + 1
        _put_digits(buf, pos + 1 - np.int64(integer), u, n)
        if integer:
            end = pos + n
        else:
            buf[pos] = buf[pos + 1]
            buf[pos + 1] = 46  # overwritten by the 'e' if there is one digit only
            end = pos + n + np.int64(n > 1)
            buf[end] = 101  # 'e'
            x = e
            if x < 0:
                buf[end + 1] = 45
                x = -x
            else:
                buf[end + 1] = 43
            end += 2
            if x >= 100:
                buf[end] = 48 + x // 100
                end += 1
            buf[end] = 48 + (x // 10) % 10
            buf[end + 1] = 48 + x % 10
            end += 2
    return end


@nb.njit(cache=True, error_model="numpy", inline="always")
def _put_special(buf, pos, v):
    """Write nan, 0 (also for -0.0), inf or -inf into buf at pos; return the new position."""
    if v != v:
        buf[pos] = 110  # nan
        buf[pos + 1] = 97
        buf[pos + 2] = 110
        pos += 3
    elif v == 0.0:
        buf[pos] = 48
        pos += 1
    else:
        if v < 0.0:
            buf[pos] = 45
            pos += 1
        buf[pos] = 105  # inf
        buf[pos + 1] = 110
        buf[pos + 2] = 102
        pos += 3
    return pos


@nb.njit(cache=True, nogil=True, error_model="numpy")  # nogil: format_rows runs it on parts of the rows in several threads
def _format_rows(lab_bytes, lab_off, row_lab, t, t_digits, vals, digits):
    """The bytes of the CSV lines ``label,t,v_0,...`` (see ``format_rows``); each number as ``'%.{p}g'``.

    Every helper that takes ``buf`` is inlined (numba ``inline="always"``) and calls no other compiled
    function (``_decimal_digits``, on scalars, is called from this loop): otherwise numba increments and
    decrements ``buf``'s reference count, atomically, for every number (a quarter of the old formatter's time).
    """
    n, m = vals.shape
    maxlab = 0
    for i in range(len(lab_off) - 1):
        maxlab = max(maxlab, lab_off[i + 1] - lab_off[i])
    buf = np.empty(n * (maxlab + 2 + 25 * (m + 1)), dtype=np.uint8)  # a number: ',' + at most 24 bytes written
    pos = 0
    for i in range(n):
        o = row_lab[i]
        for j in range(lab_off[o], lab_off[o + 1]):
            buf[pos] = lab_bytes[j]
            pos += 1
        for j in range(-1, m):
            if j < 0:
                v = t[i]
                p = t_digits
            else:
                v = vals[i, j]
                p = digits[j]
            buf[np.uint64(pos)] = 44
            pos += 1
            a = abs(v)
            if a == 0.0 or not a < np.inf:  # 0, nan, inf
                pos = _put_special(buf, pos, v)
            else:
                q, nd, e = _decimal_digits(a, p)
                buf[np.uint64(pos)] = 45  # '-', kept if v < 0 (no branch on the sign)
                pos += np.int64(v < 0.0)
                pos = _put_decimal(buf, pos, q, nd, e, p)
        buf[pos] = 10
        pos += 1
    return buf[:pos]


_NEEDS_QUOTES = re.compile('[,"\n\r]')  # a label with one of these is written quoted


def label_bytes(labels):
    """Concatenated UTF-8 bytes of CSV-quoted labels and their offsets (for ``format_rows``)."""
    enc = []
    for lab in labels:
        s = str(lab)
        if _NEEDS_QUOTES.search(s) or s != s.strip():
            s = '"' + s.replace('"', '""') + '"'
        enc.append(s.encode("utf-8"))
    off = np.zeros(len(enc) + 1, dtype=np.int64)
    np.cumsum([len(b) for b in enc], out=off[1:])
    return np.frombuffer(b"".join(enc), dtype=np.uint8).copy(), off


def format_rows(lab, row_label, t, values, digits, t_digits: int = 15) -> bytes:
    """CSV lines ``label,t,v_0,...,v_{m-1}`` for every row.

    lab: the result of ``label_bytes(labels)``; row_label (N,) index into the labels; t (N,);
    values (N, m); digits: significant digits per value column (an int or (m,)), 1..17.
    """
    return b"".join(p.tobytes() for p in _formatted_parts(lab, row_label, t, values, digits, t_digits))


def write_rows(fh, lab, row_label, t, values, digits, t_digits: int = 15) -> None:
    """Write ``format_rows``'s bytes to ``fh`` part by part (``write_rows_made`` on slices of ``values``: no
    joined copy of the text, at most a few parts' text held).

    Parameters
    ----------
    fh : file-like
        Has ``write`` taking a bytes-like object.
    lab, row_label, t, values, digits, t_digits
        As for ``format_rows``.
    """
    values = np.asarray(values)
    if values.ndim != 2:
        raise ValueError("values: expected a 2-D array")
    write_rows_made(fh, lab, row_label, t, lambda lo, hi: values[lo:hi], values.shape[0], digits, t_digits)


def _checked_digits(digits, m: int, t_digits: int) -> np.ndarray:
    """``digits`` as an int64 array of one entry per value column, each checked to be in 1..17."""
    d = np.broadcast_to(np.asarray(digits, dtype=np.int64), (m,)).copy()
    if np.any(d < 1) or np.any(d > 17) or not 1 <= t_digits <= 17:
        raise ValueError("digits: must be between 1 and 17")
    return d


def _formatted_parts(lab, row_label, t, values, digits, t_digits) -> list:
    """The CSV text of the rows as uint8 arrays, one per thread's contiguous part of the rows, in order."""
    values = np.ascontiguousarray(values, dtype=float)
    if values.ndim != 2:
        raise ValueError("values: expected a 2-D array")
    d = _checked_digits(digits, values.shape[1], t_digits)
    row_label = np.ascontiguousarray(row_label, dtype=np.int64)
    t = np.ascontiguousarray(t, dtype=float)
    n = values.shape[0]
    threads = min(_cpus(), n // PARALLEL_ROWS)
    if threads < 2:
        return [_format_rows(lab[0], lab[1], row_label, t, int(t_digits), values, d)]
    # contiguous parts of the rows in parallel threads (the kernel releases the GIL), in order: the same
    # bytes as one call. PARTS_PER_THREAD parts a thread, taken as threads free up: a thread that shares its
    # core with other work (`lgekf track` tracks the next chunk meanwhile) does not hold the others up
    parts = threads * PARTS_PER_THREAD
    cut = np.linspace(0, n, parts + 1).astype(np.int64)
    with ThreadPoolExecutor(threads) as pool:
        return list(pool.map(lambda i: _format_rows(lab[0], lab[1], row_label[cut[i]:cut[i + 1]], t[cut[i]:cut[i + 1]],
                                                    int(t_digits), values[cut[i]:cut[i + 1]], d), range(parts)))


def write_rows_made(fh, lab, row_label, t, values_of, n: int, digits, t_digits: int = 15) -> None:
    """Write the CSV lines of rows 0..n-1 (``format_rows``'s bytes) whose values are made part by part.

    ``values_of(lo, hi)`` returns the (hi - lo, m) values of rows lo..hi-1. Parts of ``PART_ROWS`` rows are
    made here, formatted in threads (one per CPU; the formatter releases the GIL, making the values does not,
    so it stays in this thread) and written in order as each is ready: making the next part's values,
    formatting and the file writes overlap, and at most 2 · threads + 1 parts are held.

    Parameters
    ----------
    fh : file-like
        Has ``write`` taking a bytes-like object.
    lab, row_label, t
        As for ``format_rows``, for the n rows.
    values_of : callable
        ``values_of(lo, hi)`` -> array_like of shape (hi - lo, m), m the same for every part.
    n : int
        The number of rows.
    digits, t_digits
        As for ``format_rows``.

    Raises
    ------
    ValueError
        Digits outside 1..17, row_label or t not of n rows, a part of the wrong shape or with another m than the
        first; an error of ``values_of``, of the formatter or of ``fh.write`` is raised as it is. Parts written
        before the error stay written (whole lines); the parts after it are not made.
    """
    row_label = np.ascontiguousarray(row_label, dtype=np.int64)
    t = np.ascontiguousarray(t, dtype=float)
    if row_label.shape != (n,) or t.shape != (n,):
        raise ValueError(f"row_label, t: expected {n} rows, got {row_label.shape} and {t.shape}")
    _checked_digits(digits, np.size(digits), t_digits)  # the range now, also when there are no rows
    checked = []  # (m, digits per column) of the first part

    def values(lo, hi):
        v = np.ascontiguousarray(values_of(lo, hi), dtype=float)
        if v.ndim != 2 or v.shape[0] != hi - lo:
            raise ValueError(f"values_of({lo}, {hi}): expected {hi - lo} rows of values, got shape {v.shape}")
        if not checked:
            checked.append((v.shape[1], _checked_digits(digits, v.shape[1], t_digits)))
        m, d = checked[0]
        if v.shape[1] != m:
            raise ValueError(f"values_of({lo}, {hi}): {v.shape[1]} columns, the first part had {m}")
        return v, d

    def text(lo, hi, v, d):
        return _format_rows(lab[0], lab[1], row_label[lo:hi], t[lo:hi], int(t_digits), v, d)

    threads = min(_cpus(), -(-n // PART_ROWS))
    if threads < 2:
        for lo in range(0, n, PART_ROWS):
            hi = min(lo + PART_ROWS, n)
            fh.write(text(lo, hi, *values(lo, hi)))
        return
    ahead = deque()
    with ThreadPoolExecutor(threads) as pool:
        try:
            for lo in range(0, n, PART_ROWS):
                hi = min(lo + PART_ROWS, n)
                ahead.append(pool.submit(text, lo, hi, *values(lo, hi)))  # the values here, the text in a thread
                while len(ahead) > 2 * threads or (ahead and ahead[0].done()):
                    fh.write(ahead.popleft().result())
            while ahead:
                fh.write(ahead.popleft().result())
        finally:
            for f in ahead:  # after an error: the parts not started are dropped
                f.cancel()


def data_digits(max_abs: float, resolution: float, at_least: int) -> int:
    """Significant digits that write every value of magnitude at most ``max_abs`` to ``resolution`` (a unit of the
    last digit at most ``resolution``, rounding error at most half of it), at least ``at_least``, at most 17.

    E.g. max |x| = 1e9 m, resolution 1e-4 m: 14 digits (1000000000.0001); 5e6 m: 11; epoch seconds 1.7e9 at 1 µs: 16.
    """
    if not (math.isfinite(max_abs) and max_abs > 0):
        return int(min(max(at_least, 1), 17))
    need = math.floor(math.log10(max_abs)) + 1 - math.floor(math.log10(resolution))
    return int(min(max(at_least, need), 17))


def output_digits(columns, digits, z, t):
    """Digits of a track file's value columns and of t.

    Parameters
    ----------
    columns : sequence of str
        The value columns' names (the header after ``id, t``).
    digits : int or None
        ``--precision``: every value column gets it; None (not given): ``DEFAULT_DIGITS``, but the position columns
        (``POSITION_COLUMNS``) as many as keep ``POSITION_RESOLUTION`` at the data's largest |x|, |y| (``z``).
    z : ndarray (N, 2)
        The measured positions (m).
    t : ndarray (N,)
        The times (s): t gets at least ``T_DIGITS`` digits, more when needed to keep ``TIME_RESOLUTION``.

    Returns
    -------
    (ndarray of int64, int)
        The digits per value column, and t's.
    """
    z = np.asarray(z)
    t = np.asarray(t)
    col = np.full(len(columns), DEFAULT_DIGITS if digits is None else int(digits), dtype=np.int64)
    if digits is None and z.size:
        big = float(np.nanmax(np.abs(z[np.isfinite(z)]))) if np.isfinite(z).any() else 0.0
        d = data_digits(big, POSITION_RESOLUTION, DEFAULT_DIGITS)
        for i, c in enumerate(columns):
            if c in POSITION_COLUMNS:
                col[i] = d
    t_big = float(np.nanmax(np.abs(t[np.isfinite(t)]))) if t.size and np.isfinite(t).any() else 0.0
    return col, data_digits(t_big, TIME_RESOLUTION, T_DIGITS)


def format_g(values, digits: int) -> list:
    """The strings ``format_rows`` writes for each value, through ``format_rows`` itself (for tests and
    small tables).

    Parameters
    ----------
    values : array_like
        Numbers (flattened).
    digits : int
        Significant digits, 1..17.

    Returns
    -------
    list of str
        ``'%.{digits}g' % v`` for each value, as ``format_rows`` writes it.
    """
    v = np.asarray(values, dtype=float).ravel()
    text = format_rows(label_bytes([""]), np.zeros(len(v), dtype=np.int64), v, np.empty((len(v), 0)), 1, t_digits=int(digits))
    return [line[1:] for line in text.decode().split("\n")[:-1]]
