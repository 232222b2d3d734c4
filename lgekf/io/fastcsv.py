"""The fast path of ``read_csv``: the numeric body of a measurement CSV parsed in numba from its raw bytes.

The header line is read in Python (``lgekf.io.readers``: separator, column keys); the body is parsed by one
numba pass over the bytes (``parse_body``), which also numbers the objects of the ``id`` column in order of
first appearance (a hash table of the ids' bytes), and ``group_order`` sorts the rows by object in O(N).

Numbers are correctly rounded float64, bit for bit what ``numpy.loadtxt`` and Python's ``float`` give: a
decimal with at most 15 significant digits (trailing zeros do not count) and a power of ten 10^e with
|e| <= 22 is m·10^e or m/10^-e of two exact doubles, one IEEE operation (Clinger's fast path); any other
number (more digits, larger exponents) is left to Python's ``float`` afterwards (``hard`` positions).

The fast path accepts only what it can read exactly as the general reader does: one-character separators
``, ; tab | :`` or runs of spaces/tabs; numbers ``[+-]digits[.digits][(e|E)[+-]digits]`` with spaces or
tabs around; lines ending in LF or CRLF; blank lines skipped. Anything else (quotes, NaN/inf text, empty
or malformed fields, too few columns, lone CR, control characters, an empty id) makes ``parse_body``
return a non-zero status, and ``read_csv`` re-reads the file with its general reader, whose one-line
error messages name the line and column (or which reads the file if it is valid after all).
"""

from __future__ import annotations

import numba as nb
import numpy as np

__all__ = ["parse_body", "group_order", "FAST_DELIMITERS", "OK"]

# separators of the fast path (None: runs of spaces/tabs); others go to the general reader
FAST_DELIMITERS = (",", ";", "\t", "|", ":", None)
OK = 0
_BAD = 1  # anything the fast path does not read: the general reader decides (and names the line)

# 10^0 .. 10^22: each exactly representable
_P10 = np.array([10.0**i for i in range(23)])


@nb.njit(cache=True)
def _count_lines(buf, start):
    n = 1
    for i in range(start, buf.shape[0]):
        if buf[i] == 10:
            n += 1
    return n


@nb.njit(cache=True)
def _parse_number(buf, a, b):
    """The double of buf[a:b] (spaces/tabs around allowed): (value, status) with status 0 = exact,
    1 = valid but needs Python's float (too many digits or too large an exponent), 2 = not a number."""
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
            if nd + zeros + 1 > 15:
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
                if nd + zeros + 1 > 15:
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
    v = float(m)
    if p >= 0:
        v = v * _P10[p]
    else:
        v = v / _P10[-p]
    return (-v if neg else v), 0


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
                vals[s, r] = v
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


@nb.njit(cache=True)
def parse_body(buf, start, delim, cols, idcol, first_line):
    """Parse the rows of ``buf[start:]`` (the bytes after the header line).

    Parameters
    ----------
    buf : ndarray of uint8
        The file's bytes.
    start : int
        Offset of the first body line.
    delim : int
        The separator's byte, or -1 for runs of spaces/tabs.
    cols : ndarray of int64
        The column indices of the numeric columns to read (0-based fields).
    idcol : int
        The field index of the ``id`` column, or -1.
    first_line : int
        The 1-based line number of the first body line.

    Returns
    -------
    status : int
        ``OK`` (0), or non-zero when the general reader must read the file.
    vals : ndarray, shape (len(cols), rows)
        The numbers (the ``hard`` ones still 0).
    line : ndarray of int64, shape (rows,)
        1-based line numbers.
    obj : ndarray of int64, shape (rows,)
        Object index per row (order of first appearance; all 0 without an id column).
    lab : ndarray of int64, shape (objects, 2)
        Byte range of each object's id (spaces/tabs removed).
    hard : ndarray of int64, shape (h, 4)
        (column, row, byte from, byte to) of the numbers left to Python's float.
    nonascii : bool
        Some byte of the body is >= 0x80 (the caller checks that the file is UTF-8).
    """
    cap = _count_lines(buf, start)
    k = cols.shape[0]
    vals = np.empty((k, cap))
    line = np.empty(cap, np.int64)
    obj = np.zeros(cap, np.int64)
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
    lab = np.empty((1024, 2), np.int64)
    table = np.full(4096, -1, np.int64)
    hard = np.empty((64, 4), np.int64)
    flags = np.zeros(1, np.int64)
    pos, r, ln, nobj, nhard = start, 0, first_line - 1, 0, 0
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
    return status, vals[:, :r], line[:r], obj[:r], lab[:nobj], hard[:nhard], flags[0] != 0


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
