"""Rows grouped by object for a caller that no longer needs the file-order rows (``lgekf track``): the
result of ``Measurements.grouped`` made with less peak memory.

``Measurements.grouped`` keeps its input intact, so the file-order columns and their sorted copies exist
side by side (5 arrays of 10⁶ rows: 80 MB at once). ``grouped_consuming`` takes the input over instead:
the checks run first (on failure ``Measurements.grouped`` raises its own error), then each column is sorted
in turn and its file-order version released from the input; a file already grouped by object is not
copied at all. The object index and line number of each row are not kept (``obj`` and ``line`` are None):
after grouping, object b's rows are ``starts[b]:starts[b + 1]`` and no message names a line any more.
"""

from __future__ import annotations

import numpy as np

from .fastcsv import group_order
from .readers import Measurements

__all__ = ["grouped_consuming", "row_objects"]


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
        ``heading``, ``extra`` as ``Measurements.grouped`` gives them; ``obj`` and ``line`` are None
        (``row_objects`` gives the object of rows from ``starts``).
    starts : ndarray of int64, shape (objects + 1,)
        Object b's rows are ``starts[b]:starts[b + 1]``.

    Raises
    ------
    DataError
        As ``Measurements.grouped`` (an object with too few measurements, times not increasing).
    """
    obj = np.ascontiguousarray(meas.obj, dtype=np.int64)
    in_order = obj.size < 2 or bool(np.all(obj[1:] >= obj[:-1]))  # the counting sort's order is then the identity
    if in_order:
        order, counts = None, np.bincount(obj, minlength=meas.n_objects).astype(np.int64, copy=False)
    else:
        order, counts = group_order(obj, meas.n_objects)
    if np.any(counts < min_length):
        meas.grouped(min_length)  # raises its error naming the object and line
    starts = np.zeros(meas.n_objects + 1, dtype=np.int64)
    np.cumsum(counts, out=starts[1:])
    meas.obj = None  # not needed any more but for an error below, which rebuilds it from order and starts
    del obj
    t = _own(meas.t) if in_order else meas.t[order]
    if t.size > 1:
        bad = t[1:] <= t[:-1]  # np.diff(t) <= 0 for finite times, without a float copy
        bad[starts[1:-1] - 1] = False  # steps between objects do not count
        if bad.any():
            meas.obj = row_objects(starts, 0, len(starts) - 1)
            if order is not None:
                meas.obj[order] = meas.obj.copy()
            meas.grouped(min_length)  # raises its error naming the lines
        del bad
    labels = list(meas.labels)
    meas.obj = meas.line = meas.t = None
    cols = {}
    for name in ("z", "heading"):
        v = getattr(meas, name)
        setattr(meas, name, None)
        cols[name] = v if v is None else _own(v) if in_order else v[order]
        del v
    extra = {}
    for k in list(meas.extra):
        v = meas.extra.pop(k)
        extra[k] = _own(v) if in_order else v[order]
        del v
    out = Measurements(t, cols["z"], cols["heading"], None, labels, None, meas.source, extra, meas.origin)
    return out, starts


def _own(a: np.ndarray) -> np.ndarray:
    """``a`` itself, or a copy when it is a view holding a larger buffer alive (``read_csv``'s positions live in
    the first two thirds of its parsed numbers' buffer)."""
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
