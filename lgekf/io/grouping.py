"""Rows grouped by object for a caller that no longer needs the file-order rows (``lgekf track``): the
result of ``Measurements.grouped`` made with less peak memory.

``Measurements.grouped`` keeps its input intact, so the file-order columns and their sorted copies exist
side by side (5 arrays of 10⁶ rows: 80 MB at once). ``grouped_consuming`` takes the input over instead:
the checks run first (on failure ``Measurements.grouped`` raises its own error), then each column is sorted
in turn and its file-order version released from the input; a file already grouped by object is not
copied at all. The object index of each row is not kept (``obj`` is None: after grouping, object b's rows are
``starts[b]:starts[b + 1]``); the line number of each row is (``line``, int64, sorted with the rows), so that
warnings about a row or an object can name its line in the input file.
"""

from __future__ import annotations

import numpy as np

from .fastcsv import group_order, times_increase
from .readers import Measurements

__all__ = ["grouped_consuming", "row_objects", "objects_subset"]


def grouped_consuming(meas: Measurements, min_length: int = 2):
    """``meas.grouped(min_length)``'s rows, times, positions, headings and labels, taking ``meas`` over.

    Parameters
    ----------
    meas : Measurements
        Rows in file order; its columns are released (set to None) as their sorted copies are made, so
        the caller must not use it afterwards.
    min_length : int
        Fewest measurements per object (fewer: the ``DataError`` of ``Measurements.grouped``).

    Returns
    -------
    grouped : Measurements
        Rows sorted by object (objects in order of first appearance, rows in file order), ``t``, ``z``,
        ``heading``, ``line``, ``extra`` as ``Measurements.grouped`` gives them; ``obj`` is None
        (``row_objects`` gives the object of rows from ``starts``).
    starts : ndarray of int64, shape (objects + 1,)
        Object b's rows are ``starts[b]:starts[b + 1]``.

    Raises
    ------
    DataError
        As ``Measurements.grouped`` (an object with too few measurements, times not increasing).
    """
    obj = np.ascontiguousarray(meas.obj, dtype=np.int64)
    t = meas.t
    counts = np.bincount(obj, minlength=meas.n_objects).astype(np.int64, copy=False)
    # the checks on the rows in file order, before anything is sorted: an error names lines (meas.line)
    if np.any(counts < min_length) or not times_increase(np.ascontiguousarray(t, dtype=float), obj, meas.n_objects):
        meas.grouped(min_length)  # raises its error naming the object and lines
        raise AssertionError("grouped_consuming: a check failed that Measurements.grouped passed")  # not reached
    in_order = obj.size < 2 or bool(np.all(obj[1:] >= obj[:-1]))  # the counting sort's order is then the identity
    order = None if in_order else group_order(obj, meas.n_objects)[0]
    starts = np.zeros(meas.n_objects + 1, dtype=np.int64)
    np.cumsum(counts, out=starts[1:])
    meas.obj = None
    del obj
    meas.t = None
    t = _own(t) if in_order else t[order]
    labels = list(meas.labels)
    cols = {}
    for name in ("z", "heading", "line"):
        v = getattr(meas, name)
        setattr(meas, name, None)
        cols[name] = v if v is None else _own(v) if in_order else v[order]
        del v
    extra = {}
    for k in list(meas.extra):
        v = meas.extra.pop(k)
        extra[k] = _own(v) if in_order else v[order]
        del v
    out = Measurements(t, cols["z"], cols["heading"], None, labels, cols["line"], meas.source, extra, meas.origin,
                       unused=meas.unused, time_iso=meas.time_iso, line_word=meas.line_word,
                       quaternion=meas.quaternion)
    return out, starts


def _own(a: np.ndarray) -> np.ndarray:
    """``a`` itself, or a copy when it is a view holding a larger buffer alive (a column of a parsed table; the
    fast path's positions own a buffer of their own size, unless ``_positions_in_place`` could not shrink it)."""
    return a.copy() if a.base is not None and a.base.nbytes > a.nbytes else a


def row_objects(starts: np.ndarray, first: int, last: int) -> np.ndarray:
    """The object index of every row of objects ``first .. last - 1`` (rows ``starts[first]:starts[last]``).

    Parameters
    ----------
    starts : ndarray of int64, shape (objects + 1,)
        Row offsets of the objects (grouped rows).
    first, last : int
        The objects.

    Returns
    -------
    ndarray of int64, shape (starts[last] - starts[first],)
        What ``Measurements.grouped``'s ``obj`` holds on those rows.
    """
    return np.repeat(np.arange(first, last, dtype=np.int64), np.diff(starts[first:last + 1]))


def objects_subset(starts, objs) -> tuple:
    """(rows, starts of the subset): the rows of objects ``objs`` (sorted) of a table with ``starts``, in order."""
    starts = np.asarray(starts, dtype=np.int64)
    objs = np.asarray(objs, dtype=np.int64)
    lens = starts[objs + 1] - starts[objs]
    sub = np.zeros(objs.size + 1, dtype=np.int64)
    np.cumsum(lens, out=sub[1:])
    rows = np.concatenate([np.arange(starts[b], starts[b + 1]) for b in objs]) if objs.size else np.zeros(0, np.int64)
    return rows, sub
