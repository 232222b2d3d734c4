"""``lgekf.io.fastcsv.parse`` on a file mapped in memory, in segments whose pages are released once parsed.

``read_csv``'s fast path parsed the bytes of the whole file, read into memory, so that the file's size and the
parsed columns were held at once (38.6 MB + 40 MB for 10⁶ rows of ``id,t,x,y``). Here the file is mapped
(``mmap``) and its body cut at line ends into segments of about ``SEGMENT_BYTES``; each segment is parsed by
``fastcsv.parse_rows`` (two segments at a time in two threads) and its pages then dropped from the process
(``madvise(MADV_DONTNEED)``: a later read of an id's bytes maps them in again from the page cache). At most
a few segments of the file are resident besides the parsed columns.

The result is ``fastcsv.parse``'s, bit for bit: the same parser on the same lines, rows in file order, line
numbers counted from the segments' line ends, objects numbered in order of first appearance (each segment's
ids merged into those of the segments before it, as ``parse`` merges its two halves).
"""

from __future__ import annotations

import mmap
import os
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from . import fastcsv
from .fastcsv import OK, _merge_ids, _rehash, parse_rows

__all__ = ["MappedFile", "parse_mapped", "SEGMENT_BYTES", "MAP_MIN_BYTES"]

SEGMENT_BYTES = 1 << 23  # bytes of the body parsed at a time (8 MiB); whole lines
MAP_MIN_BYTES = 1 << 24  # ``read_csv`` maps files of at least this size (smaller: read whole, as before)
_PAGE = mmap.PAGESIZE


class MappedFile:
    """A file's bytes mapped read-only; ``release(a, b)`` drops the whole pages of bytes a..b from memory.

    Parameters
    ----------
    path : str or Path
        A regular, non-empty file.

    Attributes
    ----------
    data : mmap.mmap
        The bytes (``data[a:b]`` gives bytes; ``numpy.frombuffer(data, numpy.uint8)`` a read-only view).
    """

    def __init__(self, path):
        with open(path, "rb") as f:
            self.data = mmap.mmap(f.fileno(), 0, access=mmap.ACCESS_READ)

    def __len__(self) -> int:
        return len(self.data)

    def release(self, a: int, b: int) -> None:
        """Drop the pages lying wholly inside bytes a..b (they are read again from the page cache if used)."""
        lo = -(-a // _PAGE) * _PAGE
        hi = (b // _PAGE) * _PAGE
        if hi > lo and hasattr(mmap, "MADV_DONTNEED"):
            self.data.madvise(mmap.MADV_DONTNEED, lo, hi - lo)

    def close(self) -> None:
        """Unmap (a no-op while numpy views of the bytes are alive; the mapping then goes with them)."""
        try:
            self.data.close()
        except BufferError:
            pass


def _segments(buf, start: int, size: int) -> list:
    """Byte ranges (a, b) covering buf[start:], each ending after a line feed (the last at the end); at least one."""
    n = buf.shape[0]
    out = []
    a = start
    while a < n:
        b = min(a + size, n)
        if b < n:
            nl = np.flatnonzero(buf[b:min(b + (1 << 20), n)] == 10)
            while nl.size == 0 and b < n:  # a line longer than 1 MiB: look further
                b = min(b + (1 << 20), n)
                nl = np.flatnonzero(buf[b:min(b + (1 << 20), n)] == 10)
            b = n if nl.size == 0 else b + int(nl[0]) + 1
        out.append((a, b))
        a = b
    return out or [(start, n)]  # no body: one empty segment (no rows)


def parse_mapped(mf: MappedFile, start: int, delim: int, cols, idcol: int, first_line: int, segment_bytes: int | None = None):
    """``fastcsv.parse(data, start, delim, cols, idcol, first_line)`` of a mapped file, segment by segment.

    Parameters
    ----------
    mf : MappedFile
        The file.
    start, delim, cols, idcol, first_line
        As for ``fastcsv.parse``.
    segment_bytes : int, optional
        About this many bytes are parsed at a time (default ``SEGMENT_BYTES``).

    Returns
    -------
    tuple
        ``fastcsv.parse``'s (status, vals, line, obj, lab, hard, nonascii).
    """
    buf = np.frombuffer(mf.data, dtype=np.uint8)
    cols = np.asarray(cols, dtype=np.int64)
    segs = _segments(buf, start, max(int(SEGMENT_BYTES if segment_bytes is None else segment_bytes), 1))
    caps = []
    for a, b in segs:  # lines per segment (room for every row), the pages released again
        caps.append(int(np.count_nonzero(buf[a:b] == 10)) + (1 if b == len(mf) and buf[b - 1] != 10 else 0))
        mf.release(a, b)
    offs = np.concatenate([[0], np.cumsum(caps)]).astype(np.int64)  # also the line feeds before each segment
    cap = int(offs[-1])
    vals, line, obj = np.empty((cap, cols.size)), np.empty(cap, np.int64), np.empty(cap, np.int64)

    def one(k):
        a, b = segs[k]
        lo, hi = int(offs[k]), int(offs[k + 1])
        res = parse_rows(buf[:b], a, delim, cols, idcol, first_line + lo, vals[lo:hi], line[lo:hi], obj[lo:hi])
        mf.release(a, b)
        return res

    threads = min(2, fastcsv._cpus()) if len(segs) > 1 else 1
    if threads > 1:
        with ThreadPoolExecutor(threads) as pool:
            parts = list(pool.map(one, range(len(segs))))
    else:
        parts = [one(k) for k in range(len(segs))]
    nonascii = any(p[5] for p in parts)
    for p in parts:
        if p[0] != OK:
            return p[0], vals[:0], line[:0], obj[:0], parts[0][2], parts[0][4], nonascii
    # close the gaps of blank lines, number the objects in order of first appearance, shift the hard rows
    r = 0
    lab = None
    table = None
    hards = []
    for k, (_, rows, lab_k, table_k, hard_k, _) in enumerate(parts):
        lo = int(offs[k])
        if r != lo and rows:
            vals[r:r + rows] = vals[lo:lo + rows].copy()
            line[r:r + rows] = line[lo:lo + rows].copy()
            obj[r:r + rows] = obj[lo:lo + rows].copy()
        if idcol >= 0:
            if lab is None:
                lab, table = lab_k, table_k
            elif lab_k.shape[0]:
                index, new = _merge_ids(buf, table, lab, lab_k)
                obj[r:r + rows] = index[obj[r:r + rows]]
                if new.shape[0]:
                    lab = np.concatenate([lab, new])
                    size = table.shape[0]
                    while size < 2 * lab.shape[0]:  # the table's load stays under 1/2, as in parse_rows
                        size *= 2
                    table = _rehash(buf, lab, lab.shape[0], size)
                mf.release(start, segs[k][1])  # the earlier ids' pages the merge read again
        elif rows and lab is None:
            lab = lab_k
        hard_k = hard_k.copy()
        hard_k[:, 1] += r
        hards.append(hard_k)
        r += rows
    if lab is None:
        lab = parts[0][2]
    hard = np.concatenate(hards) if hards else np.empty((0, 4), np.int64)
    return OK, vals[:r], line[:r], obj[:r], lab, hard, nonascii
