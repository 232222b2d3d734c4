"""The output number formatter as it was before the fast path (lgekf/io/formatting.py at commit 025d2e0),
vendored as the reference for tests/io/test_formatting_exact.py and benchmarks/bench_format.py: the new formatter
must write exactly these bytes. Not part of the library; do not change it."""

from __future__ import annotations

import math

import numba as nb
import numpy as np

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


@nb.njit(cache=True)
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
    if frac > 0.5 or (frac == 0.5 and q % 2 == 1):
        q += 1
    return q


_POW10 = np.array([10**i for i in range(19)], dtype=np.int64)
_PAIRS = np.frombuffer(b"".join(b"%02d" % i for i in range(100)), dtype=np.uint8).copy()


@nb.njit(cache=True)
def _put_str(buf, pos, s):
    for i in range(len(s)):
        buf[pos + i] = ord(s[i])
    return pos + len(s)


@nb.njit(cache=True)
def _decimal_exponent(v):
    """floor(log10(v)) for v > 0, from the binary exponent and one comparison with a power of ten (no log10).

    Exact but for v within an ulp or so of a power of ten, where it may be one off: ``_put_g`` corrects
    either way by the size of its rounded digits (as it always did for log10's own rounding), to the same
    digits where they are exact (|p - 1 - e| <= 22); elsewhere ``_put_g`` starts from log10 as before.
    """
    e2 = math.frexp(v)[1]  # v in [2^(e2-1), 2^e2)
    e = int(math.floor((e2 - 1) * 0.30102999566398120))  # floor(log10 v) or one less
    k = e + 1
    if 0 <= k <= 22:
        if v >= _P10F[k]:
            e = k
    elif -22 <= k < 0:
        if v * _P10F[-k] >= 1.0:
            e = k
    else:
        e = int(math.floor(math.log10(v)))
    return e


@nb.njit(cache=True)
def _put_g(buf, pos, v, p, digits):
    """Write ``'%.{p}g' % v`` (1 <= p <= 17) into buf at pos; return the new position.

    Digits are round(|v|·10^(p-1-e)) computed in double-double: when |p-1-e| <= 22 (p = 17: |v| in
    [1e-6, 1e38]; p = 10: [1e-13, 1e31]) this is Python's correctly rounded output except in rare
    near-ties; outside, the last of 16-17 digits can be off by one unit. -0.0 is written as 0.
    """
    if v != v:
        return _put_str(buf, pos, "nan")
    if v == 0.0:
        buf[pos] = 48
        return pos + 1
    if v < 0.0:
        buf[pos] = 45  # '-'
        pos += 1
        v = -v
    if v == np.inf:
        return _put_str(buf, pos, "inf")
    e = _decimal_exponent(v)
    if not -21 <= p - 1 - e <= 21:  # digits not exact (see below): log10's start, whose one-off cases give these digits
        e = int(math.floor(math.log10(v)))
    top = _POW10[p]
    q = _round_scaled(v, p - 1 - e)
    if q >= top:
        e += 1
        q = _round_scaled(v, p - 1 - e)
    elif q < top // 10:
        e -= 1
        q = _round_scaled(v, p - 1 - e)
    if q >= top:  # rounding carried into a new digit (e.g. 9.9999 -> 10.000)
        q = top // 10
        e += 1
    u = np.uint64(q)
    hundred = np.uint64(100)
    i = p
    while i >= 2:  # two digits per division
        r = u % hundred
        u = u // hundred
        digits[i - 1] = _PAIRS[2 * r + 1]
        digits[i - 2] = _PAIRS[2 * r]
        i -= 2
    if i == 1:
        digits[0] = 48 + u
    nz = p
    while nz > 1 and digits[nz - 1] == 48:
        nz -= 1
    if -4 <= e < p:
        if e >= 0:
            for i in range(e + 1):
                buf[pos] = digits[i] if i < nz else 48
                pos += 1
            if nz > e + 1:
                buf[pos] = 46
                pos += 1
                for i in range(e + 1, nz):
                    buf[pos] = digits[i]
                    pos += 1
        else:
            buf[pos] = 48
            buf[pos + 1] = 46
            pos += 2
            for i in range(-e - 1):
                buf[pos] = 48
                pos += 1
            for i in range(nz):
                buf[pos] = digits[i]
                pos += 1
    else:
        buf[pos] = digits[0]
        pos += 1
        if nz > 1:
            buf[pos] = 46
            pos += 1
            for i in range(1, nz):
                buf[pos] = digits[i]
                pos += 1
        buf[pos] = 101  # 'e'
        pos += 1
        if e < 0:
            buf[pos] = 45
            e = -e
        else:
            buf[pos] = 43
        pos += 1
        if e >= 100:
            buf[pos] = 48 + e // 100
            pos += 1
        buf[pos] = 48 + (e // 10) % 10
        buf[pos + 1] = 48 + e % 10
        pos += 2
    return pos


@nb.njit(cache=True, nogil=True)  # nogil: format_rows runs it on parts of the rows in several threads
def _format_rows(lab_bytes, lab_off, row_lab, t, t_digits, vals, digits):
    n, m = vals.shape
    maxlab = 0
    for i in range(len(lab_off) - 1):
        maxlab = max(maxlab, lab_off[i + 1] - lab_off[i])
    buf = np.empty(n * (maxlab + 2 + 25 * (m + 1)), dtype=np.uint8)
    scratch = np.empty(20, dtype=np.uint8)
    pos = 0
    for i in range(n):
        o = row_lab[i]
        for j in range(lab_off[o], lab_off[o + 1]):
            buf[pos] = lab_bytes[j]
            pos += 1
        buf[pos] = 44
        pos = _put_g(buf, pos + 1, t[i], t_digits, scratch)
        for j in range(m):
            buf[pos] = 44
            pos = _put_g(buf, pos + 1, vals[i, j], digits[j], scratch)
        buf[pos] = 10
        pos += 1
    return buf[:pos]


def format_g(values, digits: int) -> list:  # noqa: D103
    """The strings ``format_rows`` writes for each value (for tests and small tables)."""
    out = []
    buf = np.empty(32, dtype=np.uint8)
    scratch = np.empty(20, dtype=np.uint8)
    for v in np.asarray(values, dtype=float).ravel():
        n = _put_g(buf, 0, float(v), int(digits), scratch)
        out.append(buf[:n].tobytes().decode())
    return out
