"""The fast path of ``read_csv``: the numeric body of a measurement CSV parsed in numba from its raw bytes.

The header line is read in Python (``lgekf.io.readers``: separator, column keys); the body is parsed by one
numba pass over the bytes (``parse``: ``parse_rows`` on the two halves of a large file in two threads), which also numbers the objects of the ``id`` column in order of
first appearance (a hash table of the ids' bytes), and ``group_order`` sorts the rows by object in O(N).

Numbers are correctly rounded float64, bit for bit what ``numpy.loadtxt`` and Python's ``float`` give: a
decimal with at most 15 significant digits (trailing zeros do not count) and a power of ten 10^e with
|e| <= 22 is m·10^e or m/10^-e of two exact doubles, one IEEE operation (Clinger's fast path); 16 to 19
digits with |e| <= 22 are computed in double-double and kept unless within 2^-30 ulp of a rounding
midpoint (``_long_mantissa``); any other
number (more digits, larger exponents) is parsed afterwards by ``numpy.loadtxt`` in one call (``hard_values``).

The fast path accepts only what it can read exactly as the general reader does: one-character separators
``, ; tab | :`` or runs of spaces/tabs; numbers ``[+-]digits[.digits][(e|E)[+-]digits]`` with spaces or
tabs around; lines ending in LF or CRLF; blank lines skipped. Anything else (quotes, NaN/inf text, empty
or malformed fields, too few columns, lone CR, control characters, an empty id) makes ``parse``
return a non-zero status, and ``read_csv`` re-reads the file with its general reader, whose one-line
error messages name the line and column (or which reads the file if it is valid after all).
"""

from __future__ import annotations

import atexit
import io
import math
import os
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

import numba as nb
import numpy as np

from .cpus import usable_cpus as _cpus  # a module name of its own: tests set it

from .formatting import _two_prod  # a*b = p + e exactly (Dekker), shared with the formatter

__all__ = ["parse", "parse_rows", "hard_values", "group_order", "times_increase", "compiled", "compile_in_background", "warm", "FAST_DELIMITERS", "OK", "PARALLEL_BYTES",
           "COMPILE_MIN_BYTES"]

# separators of the fast path (None: runs of spaces/tabs); others go to the general reader
FAST_DELIMITERS = (",", ";", "\t", "|", ":", None)
OK = 0
_BAD = 1  # anything the fast path does not read: the general reader decides (and names the line)

# 10^0 .. 10^22: each exactly representable
_P10 = np.array([10.0**i for i in range(23)])


@nb.njit(cache=True)
def _parse_number(buf, a, b):
    """The double of buf[a:b] (spaces/tabs around allowed): (value, status) with status 0 = exact,
    1 = valid but needs the general parser (hard_values) (too many digits or too large an exponent), 2 = not a number."""
    while a < b and (buf[a] == 32 or buf[a] == 9):
        a += 1
    while b > a and (buf[b - 1] == 32 or buf[b - 1] == 9):
        b -= 1
    if a == b:
        return 0.0, 2
    neg = False
    c = buf[a]
    if c == 45 or c == 43:  # - +
        neg = c == 45
        a += 1
    m = np.uint64(0)
    nd = 0  # significant digits taken into m
    zeros = 0  # zeros seen after the last nonzero significant digit (not yet in m)
    frac = 0  # digits after the decimal point
    digits = 0
    hard = False
    i = a
    while i < b and 48 <= buf[i] <= 57:  # integer part
        d = buf[i] - 48
        digits += 1
        if d == 0:
            if nd > 0:
                zeros += 1
        else:
            if nd + zeros + 1 > 19:
                hard = True
            else:
                for _ in range(zeros):
                    m = m * np.uint64(10)
                m = m * np.uint64(10) + np.uint64(d)
                nd += zeros + 1
            zeros = 0
        i += 1
    if i < b and buf[i] == 46:  # '.'
        i += 1
        while i < b and 48 <= buf[i] <= 57:
            d = buf[i] - 48
            digits += 1
            frac += 1
            if d == 0:
                if nd > 0:
                    zeros += 1
            else:
                if nd + zeros + 1 > 19:
                    hard = True
                else:
                    for _ in range(zeros):
                        m = m * np.uint64(10)
                    m = m * np.uint64(10) + np.uint64(d)
                    nd += zeros + 1
                zeros = 0
            i += 1
    if digits == 0:
        return 0.0, 2
    e = 0
    if i < b and (buf[i] == 101 or buf[i] == 69):  # e E
        i += 1
        eneg = False
        if i < b and (buf[i] == 45 or buf[i] == 43):
            eneg = buf[i] == 45
            i += 1
        ed = 0
        while i < b and 48 <= buf[i] <= 57:
            if e < 100000:
                e = e * 10 + (buf[i] - 48)
            ed += 1
            i += 1
        if ed == 0:
            return 0.0, 2
        if eneg:
            e = -e
    if i != b:
        return 0.0, 2
    if nd == 0:
        return (-0.0 if neg else 0.0), 0
    if hard:
        return 0.0, 1
    p = e + zeros - frac  # the number is m·10^p
    if p > 22 or p < -22:
        return 0.0, 1
    if nd <= 15:  # m and 10^|p| exact doubles: one correctly rounded operation
        v = float(m)
        if p >= 0:
            v = v * _P10[p]
        else:
            v = v / _P10[-p]
        return (-v if neg else v), 0
    v = _long_mantissa(m, p)  # 16-19 digits: double-double, unless too close to a rounding midpoint
    if v != v:
        return 0.0, 1
    return (-v if neg else v), 0


@nb.njit(cache=True)
def _long_mantissa(m, p):
    """The double nearest m·10^p for m < 10^19 (uint64) and |p| <= 22, or nan when it cannot be decided here.

    m = a + b exactly (a its top 53 bits, b < 2^11); m·10^p is carried as a double-double (hi, lo) with an error
    far below 2^-90 of the value, so hi is the correctly rounded result unless |lo| is within 2^-30 ulp(hi)
    of half an ulp (or hi is a power of two, where the ulp below is smaller): those return nan, and the
    general parser decides.
    """
    a = float(m & np.uint64(0xFFFFFFFFFFFFF800))
    b = float(m & np.uint64(0x7FF))
    if p >= 0:
        P = _P10[p]
        a1, e1 = _two_prod(a, P)
        a2, e2 = _two_prod(b, P)
        s = a1 + a2
        bb = s - a1
        t = (a1 - (s - bb)) + (a2 - bb)  # two_sum(a1, a2) = s + t
        t += e1 + e2
    else:
        P = _P10[-p]
        q1 = a / P
        p1, pe = _two_prod(q1, P)
        r = ((a - p1) - pe) + b  # m - q1·P: a - p1 exact (Sterbenz)
        s = q1
        t = r / P
    hi = s + t
    lo = t - (hi - s)
    mant, ex = math.frexp(hi)
    if mant == 0.5 or mant == -0.5:
        return np.nan
    ulp = math.ldexp(1.0, ex - 53)
    if abs(abs(lo) - 0.5 * ulp) < ulp * 9.313225746154785e-10:  # 2^-30
        return np.nan
    if abs(lo) > 0.5 * ulp:  # hi + lo rounds past hi (cannot happen after the fast two-sum; kept as a guard)
        return np.nan
    return hi


@nb.njit(cache=True)
def _hash(buf, a, b):
    h = np.uint64(14695981039346656037)
    for i in range(a, b):
        h = (h ^ np.uint64(buf[i])) * np.uint64(1099511628211)
    return h


@nb.njit(cache=True)
def _same(buf, a, b, c, d):
    if b - a != d - c:
        return False
    for i in range(b - a):
        if buf[a + i] != buf[c + i]:
            return False
    return True


_FULL_LABELS = 2  # the inner loop's "grow the id table" status
_FULL_HARD = 3  # the inner loop's "grow the hard-number list" status


@nb.njit(cache=True)
def _rows(buf, pos, r, ln, delim, slot, need, vals, line, obj, table, lab, nobj, hard, nhard, flags):
    """Parse lines from ``pos`` until the end or until ``lab`` or ``hard`` is full (no allocation here:
    the caller grows them and calls again). Returns (status, pos, r, ln, nobj, nhard)."""
    n = buf.shape[0]
    mask = table.shape[0] - 1
    while pos < n:
        if nobj + 1 >= lab.shape[0] or 2 * (nobj + 1) > table.shape[0]:
            return _FULL_LABELS, pos, r, ln, nobj, nhard
        if nhard + need >= hard.shape[0]:
            return _FULL_HARD, pos, r, ln, nobj, nhard
        # the line: buf[pos:end] without its CR LF
        end = pos
        blank = True
        while end < n and buf[end] != 10:
            c = buf[end]
            if c < 32:
                if c == 13:
                    if end + 1 < n and buf[end + 1] == 10:
                        break
                    return _BAD, pos, r, ln, nobj, nhard  # a lone CR is a line break to Python
                if c != 9:
                    return _BAD, pos, r, ln, nobj, nhard
            elif c == 34:  # a quote: the general reader's CSV quoting
                return _BAD, pos, r, ln, nobj, nhard
            elif c >= 128:
                flags[0] = 1
            if c != 32 and c != 9:
                blank = False
            end += 1
        nxt = end + 1
        if end < n and buf[end] == 13:
            nxt = end + 2
        ln += 1
        if blank:
            pos = nxt
            continue
        f = 0
        i = pos
        if delim < 0:
            while i < end and (buf[i] == 32 or buf[i] == 9):
                i += 1
        while f < need:
            if i > end or (delim < 0 and i == end):
                return _BAD, pos, r, ln, nobj, nhard  # too few columns
            j = i
            if delim >= 0:
                while j < end and buf[j] != delim:
                    j += 1
            else:
                while j < end and buf[j] != 32 and buf[j] != 9:
                    j += 1
            s = slot[f]
            if s >= 0:
                v, st = _parse_number(buf, i, j)
                if st == 2:
                    return _BAD, pos, r, ln, nobj, nhard
                if st == 1:
                    hard[nhard, 0] = s
                    hard[nhard, 1] = r
                    hard[nhard, 2] = i
                    hard[nhard, 3] = j
                    nhard += 1
                vals[r, s] = v
            elif s == -2:
                a = i
                b = j
                while a < b and (buf[a] == 32 or buf[a] == 9):
                    a += 1
                while b > a and (buf[b - 1] == 32 or buf[b - 1] == 9):
                    b -= 1
                if a == b:
                    return _BAD, pos, r, ln, nobj, nhard  # an empty id
                q = np.int64(_hash(buf, a, b) & np.uint64(mask))
                while True:
                    o = table[q]
                    if o < 0:
                        lab[nobj, 0] = a
                        lab[nobj, 1] = b
                        table[q] = nobj
                        o = nobj
                        nobj += 1
                        break
                    if _same(buf, lab[o, 0], lab[o, 1], a, b):
                        break
                    q = (q + 1) & mask
                obj[r] = o
            f += 1
            if delim >= 0:
                i = j + 1
            else:
                i = j
                while i < end and (buf[i] == 32 or buf[i] == 9):
                    i += 1
        line[r] = ln
        r += 1
        pos = nxt
    return OK, pos, r, ln, nobj, nhard


@nb.njit(cache=True)
def _rehash(buf, lab, nobj, size):
    table = np.full(size, -1, np.int64)
    mask = size - 1
    for u in range(nobj):
        q = np.int64(_hash(buf, lab[u, 0], lab[u, 1]) & np.uint64(mask))
        while table[q] >= 0:
            q = (q + 1) & mask
        table[q] = u
    return table


@nb.njit(cache=True, nogil=True)  # nogil: ``parse`` runs it on the two halves of a file in two threads
def parse_rows(buf, start, delim, cols, idcol, first_line, vals, line, obj):
    """Parse the lines of ``buf[start:]`` into ``vals``, ``line``, ``obj`` (rows from 0; room for every line).

    Parameters
    ----------
    buf : ndarray of uint8
        The bytes (a file's, or the first part of them: the lines end where ``buf`` ends).
    start : int
        Offset of the first line to parse.
    delim : int
        The separator's byte, or -1 for runs of spaces/tabs.
    cols : ndarray of int64
        The field indices (0-based) of the numeric columns to read.
    idcol : int
        The field index of the ``id`` column, or -1.
    first_line : int
        The 1-based line number of the first line.
    vals : ndarray, shape (L, len(cols))
        Out: the numbers (the ``hard`` ones left 0).
    line : ndarray of int64, shape (L,)
        Out: the 1-based line number of each row.
    obj : ndarray of int64, shape (L,)
        Out: the object index of each row (order of first appearance here; 0 without an id column).

    Returns
    -------
    status : int
        ``OK`` (0), or non-zero when the general reader must read the file.
    rows : int
        Rows written.
    lab : ndarray of int64, shape (objects, 2)
        Byte range of each object's id (spaces/tabs around removed).
    table : ndarray of int64
        The hash table of the ids (open addressing, size a power of two): object index or -1.
    hard : ndarray of int64, shape (h, 4)
        (column, row, byte from, byte to) of the numbers left to hard_values.
    nonascii : bool
        Some byte is >= 0x80 (the caller checks that the file is UTF-8).
    """
    k = cols.shape[0]
    need = idcol
    for j in range(k):
        need = max(need, cols[j])
    need += 1
    # which numeric slot (or -2 for the id) each field index fills
    slot = np.full(need, -1, np.int64)
    for j in range(k):
        slot[cols[j]] = j
    if idcol >= 0:
        slot[idcol] = -2
    else:
        obj[:] = 0
    lab = np.empty((1024, 2), np.int64)
    table = np.full(4096, -1, np.int64)
    hard = np.empty((64, 4), np.int64)
    flags = np.zeros(1, np.int64)
    zero = np.int64(0)  # one type for the loop-carried counts: _rows compiles once
    pos, r, ln, nobj, nhard = np.int64(start), zero, np.int64(first_line - 1), zero, zero
    while True:
        status, pos, r, ln, nobj, nhard = _rows(buf, pos, r, ln, delim, slot, need, vals, line, obj, table, lab, nobj, hard,
                                                nhard, flags)
        if status == _FULL_LABELS:  # room for more ids: the table's load stays under 1/2
            bigger = np.empty((2 * lab.shape[0], 2), np.int64)
            bigger[:nobj] = lab[:nobj]
            lab = bigger
            table = _rehash(buf, lab, nobj, 2 * lab.shape[0])
        elif status == _FULL_HARD:
            more = np.empty((2 * hard.shape[0], 4), np.int64)
            more[:nhard] = hard[:nhard]
            hard = more
        else:
            break
    if idcol < 0 and r > 0:
        lab[0, 0] = 0
        lab[0, 1] = 0
        nobj = 1
    return status, r, lab[:nobj], table, hard[:nhard], flags[0] != 0


@nb.njit(cache=True)
def _merge_ids(buf, table, lab, lab2):
    """The objects of a second part numbered after the first's: (index of each of lab2's ids among all,
    the byte ranges of the ids new in the second part, in their order)."""
    mask = table.shape[0] - 1
    n1 = lab.shape[0]
    index = np.empty(lab2.shape[0], np.int64)
    new = np.empty((lab2.shape[0], 2), np.int64)
    nn = 0
    for u in range(lab2.shape[0]):
        a, b = lab2[u, 0], lab2[u, 1]
        q = np.int64(_hash(buf, a, b) & np.uint64(mask))
        found = -1
        while table[q] >= 0:
            o = table[q]
            if _same(buf, lab[o, 0], lab[o, 1], a, b):
                found = o
                break
            q = (q + 1) & mask
        if found < 0:
            index[u] = n1 + nn
            new[nn, 0] = a
            new[nn, 1] = b
            nn += 1
        else:
            index[u] = found
    return index, new[:nn]


PARALLEL_BYTES = 1 << 22  # bodies of at least this many bytes are parsed in two halves at once
#: a cold cache compiles the parser (about 6 s of CPU, in a second process the command waits for) only for a file of
#: at least this size: below it the general reader loses less than the compilation costs (38.6 MB: 0.73 → 0.37 s)
COMPILE_MIN_BYTES = 1 << 24


def parse(data: bytes, start: int, delim: int, cols, idcol: int, first_line: int):
    """Parse the body of a CSV, in two threads (halves split at a line end) when it is large.

    Parameters
    ----------
    data : bytes
        The file's bytes.
    start, delim, cols, idcol, first_line
        As for ``parse_rows``.

    Returns
    -------
    status : int
        ``OK`` (0), or non-zero when the general reader must read the file.
    vals : ndarray, shape (rows, len(cols))
    line, obj : ndarray of int64, shape (rows,)
    lab : ndarray of int64, shape (objects, 2)
        Objects numbered in order of first appearance in the file.
    hard : ndarray of int64, shape (h, 4)
    nonascii : bool
        As for ``parse_rows``.
    """
    buf = np.frombuffer(data, dtype=np.uint8)
    cols = np.asarray(cols, dtype=np.int64)
    n = len(data)
    cut = data.find(b"\n", start + (n - start) // 2) + 1 if n - start >= PARALLEL_BYTES and _cpus() > 1 else 0
    if cut <= start or cut >= n:
        cap = data.count(b"\n", start) + 1
        vals, line, obj = np.empty((cap, cols.size)), np.empty(cap, np.int64), np.empty(cap, np.int64)
        status, r, lab, _, hard, nonascii = parse_rows(buf, start, delim, cols, idcol, first_line, vals, line, obj)
        return status, vals[:r], line[:r], obj[:r], lab, hard, nonascii
    cap1 = data.count(b"\n", start, cut)  # the first half's lines, each ending in LF
    cap = cap1 + data.count(b"\n", cut) + 1
    vals, line, obj = np.empty((cap, cols.size)), np.empty(cap, np.int64), np.empty(cap, np.int64)
    with ThreadPoolExecutor(2) as pool:
        one = pool.submit(parse_rows, buf[:cut], start, delim, cols, idcol, first_line, vals[:cap1], line[:cap1], obj[:cap1])
        two = pool.submit(parse_rows, buf, cut, delim, cols, idcol, first_line + cap1, vals[cap1:], line[cap1:], obj[cap1:])
        st1, r1, lab1, table1, hard1, na1 = one.result()
        st2, r2, lab2, _, hard2, na2 = two.result()
    if st1 != OK or st2 != OK:
        return (st1 if st1 != OK else st2), vals[:0], line[:0], obj[:0], lab1, hard1, na1 or na2
    if r1 < cap1:  # blank lines in the first half: close the gap
        vals[r1:r1 + r2] = vals[cap1:cap1 + r2].copy()
        line[r1:r1 + r2] = line[cap1:cap1 + r2].copy()
        obj[r1:r1 + r2] = obj[cap1:cap1 + r2].copy()
    if idcol >= 0:
        index, new = _merge_ids(buf, table1, lab1, lab2)
        obj[r1:r1 + r2] = index[obj[r1:r1 + r2]]
        lab = np.concatenate([lab1, new])
    else:
        lab = lab1 if r1 else lab2
    hard2 = hard2.copy()
    hard2[:, 1] += r1
    return OK, vals[:r1 + r2], line[:r1 + r2], obj[:r1 + r2], lab, np.concatenate([hard1, hard2]), na1 or na2


@nb.njit(cache=True)
def _hard_text(buf, hard):
    """The bytes of the fields ``hard[:, 2:4]``, one per line."""
    total = 0
    for i in range(hard.shape[0]):
        total += hard[i, 3] - hard[i, 2] + 1
    out = np.empty(total, np.uint8)
    pos = 0
    for i in range(hard.shape[0]):
        for j in range(hard[i, 2], hard[i, 3]):
            out[pos] = buf[j]
            pos += 1
        out[pos] = 10
        pos += 1
    return out


def hard_values(data: bytes, hard) -> np.ndarray:
    """The numbers the fast path left (``hard`` rows of ``parse``), correctly rounded by ``numpy.loadtxt`` (the
    general reader's own parser) in one call: no Python ``float`` per value when a file has many long numbers.

    Parameters
    ----------
    data : bytes
        The file's bytes.
    hard : ndarray of int64, shape (h, 4)
        (column, row, byte from, byte to) of each number.

    Returns
    -------
    ndarray, shape (h,)
    """
    if len(hard) == 0:
        return np.empty(0)
    text = _hard_text(np.frombuffer(data, dtype=np.uint8), np.ascontiguousarray(hard)).tobytes().decode("ascii")
    return np.loadtxt(io.StringIO(text), dtype=float, comments=None, ndmin=1)


def compiled() -> bool:
    """True when the parser's kernels are compiled in this process or in numba's cache (``cache=True``).

    On a cold cache ``read_csv`` reads with its general reader instead and calls ``compile_in_background``:
    compiling the parser takes several seconds of CPU, which would double a first run on small files.
    """
    if parse_rows.signatures:
        return True
    try:
        return os.path.exists(parse_rows._cache._cache_file._index_path)
    except AttributeError:  # another numba's internals: just compile when used
        return True


_COMPILER = []


def compile_in_background() -> None:
    """Compile the parser into numba's cache in a second process (once per process; the command waits for
    it when it exits, so that no process outlives it). The next run finds the kernels in the cache."""
    if _COMPILER:
        return
    proc = subprocess.Popen([sys.executable, "-c", "from lgekf.io.fastcsv import warm; warm()"],
                            stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    _COMPILER.append(proc)
    atexit.register(proc.wait)


def warm() -> None:
    """Compile (or load) every kernel of the fast path with the argument types ``read_csv`` passes: one part
    and two halves, ids, a number for ``hard_values``."""
    text = b"id,t,x,y\n" + b"".join(b"a%d, %d.5,1.25,-2e-3\n" % (i % 3, i) for i in range(40)) + b"b,1.5,0.1234567890123456789,2\n"
    for parts in (1 << 62, 8):
        global PARALLEL_BYTES
        saved, PARALLEL_BYTES = PARALLEL_BYTES, parts
        try:
            out = parse(text, 9, 44, [1, 2, 3], 0, 2)
        finally:
            PARALLEL_BYTES = saved
    hard_values(text, out[5])
    group_order(out[3], len(out[4]))
    times_increase(out[1][:, 0].copy(), out[3], len(out[4]))


@nb.njit(cache=True)
def group_order(obj, n_obj):
    """The stable sort of the rows by object (``numpy.argsort(obj, kind="stable")``) by counting, and the
    objects' row counts.

    Parameters
    ----------
    obj : ndarray of int64
        Object index per row, in [0, n_obj).
    n_obj : int
        Number of objects.

    Returns
    -------
    order : ndarray of int64
        Row indices sorted by object, file order within an object.
    counts : ndarray of int64
        Rows per object.
    """
    counts = np.zeros(n_obj, np.int64)
    for i in range(obj.shape[0]):
        counts[obj[i]] += 1
    nxt = np.empty(n_obj, np.int64)
    s = 0
    for o in range(n_obj):
        nxt[o] = s
        s += counts[o]
    order = np.empty(obj.shape[0], np.int64)
    for i in range(obj.shape[0]):
        o = obj[i]
        order[nxt[o]] = i
        nxt[o] += 1
    return order, counts


@nb.njit(cache=True)
def times_increase(t, obj, n_obj):
    """Whether every object's times increase strictly in file order (no row's t at or below its object's previous t).

    Parameters
    ----------
    t : ndarray of float64
        Time per row, in file order.
    obj : ndarray of int64
        Object index per row, in [0, n_obj).
    n_obj : int
        Number of objects.

    Returns
    -------
    bool
        What ``np.diff(t[order]) <= 0`` outside the steps between objects says for the rows grouped by object,
        found without grouping them.
    """
    last = np.full(n_obj, np.nan)  # t - nan is nan, not <= 0: an object's first row passes
    for i in range(t.shape[0]):
        o = obj[i]
        if t[i] - last[o] <= 0:  # np.diff's rule exactly, also for inf and nan (inf - inf is nan: passes)
            return False
        last[o] = t[i]
    return True
