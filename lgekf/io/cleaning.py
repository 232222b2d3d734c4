"""Real logs that are almost right (``lgekf track --sort``, ``--skip-invalid``): rows sorted by time within each
object, and the rows no filter can take dropped with a count per reason, instead of refusing the whole file.

Both work on the rows of a file in file order (``Measurements``), before the grouping by object
(``lgekf.io.grouping``), which still checks what is left.
"""

from __future__ import annotations

import numba as nb
import numpy as np

from .readers import DataError, Measurements

__all__ = ["sort_within_objects", "drop_invalid", "take_rows", "skipped_summary", "sort_by_time", "check_time_order"]


def take_rows(meas: Measurements, keep: np.ndarray) -> Measurements:
    """The rows ``keep`` (mask or indices, in the order given) of ``meas``; objects left without a row removed (the
    others renumbered in order of first appearance)."""
    idx = np.flatnonzero(keep) if np.asarray(keep).dtype == bool else np.asarray(keep, dtype=np.int64)
    obj = meas.obj[idx]
    present = np.zeros(meas.n_objects, bool)
    present[obj] = True
    _, first = np.unique(obj, return_index=True)
    order = np.unique(obj)[np.argsort(first)]  # objects by first appearance among the kept rows
    new = np.full(meas.n_objects, -1, dtype=np.int64)
    new[order] = np.arange(order.size)
    return Measurements(meas.t[idx], meas.z[idx], None if meas.heading is None else meas.heading[idx], new[obj],
                        [meas.labels[i] for i in order], meas.line[idx], meas.source, {k: v[idx] for k, v in meas.extra.items()},
                        meas.origin, dict(meas.skipped), unused=meas.unused, time_iso=meas.time_iso, line_word=meas.line_word,
                       quaternion=meas.quaternion)


def sort_within_objects(meas: Measurements) -> tuple[Measurements, int]:
    """Each object's rows in increasing time (stable: rows of equal time keep their file order), the objects' rows
    where they were. Returns (measurements, how many rows moved)."""
    obj = np.asarray(meas.obj, dtype=np.int64)
    order = np.lexsort((np.arange(obj.size), meas.t, obj))  # by object, then time, then file order
    # the object's rows in time order, put back on the positions that object's rows had in the file
    by_obj = np.argsort(obj, kind="stable")
    out = np.empty_like(order)
    out[by_obj] = order
    moved = int(np.count_nonzero(out != np.arange(obj.size)))
    return (take_rows(meas, out) if moved else meas), moved


@nb.njit(cache=True)
def _after_previous(t, obj):
    """Rows (sorted by object, file order within) whose time is after every earlier row of their object (the first row
    of an object always): the rows a strictly increasing time keeps (a dropped row never raises the running maximum)."""
    keep = np.ones(t.size, np.bool_)
    top = -np.inf
    for k in range(t.size):
        if k == 0 or obj[k] != obj[k - 1]:
            top = t[k]
        elif t[k] > top:
            top = t[k]
        else:
            keep[k] = False
    return keep


def drop_invalid(meas: Measurements, min_length: int = 2) -> Measurements:
    """``meas`` without the rows no filter can take, each reason recorded in ``skipped`` (line numbers): a time not
    after the object's previous row's (a duplicate or an unsorted row: the first one kept), then objects left with fewer
    than ``min_length`` rows. (Rows with a NaN or infinite number are dropped while reading:
    ``readers.skipping_nonfinite_rows``.)"""
    obj = np.asarray(meas.obj, dtype=np.int64)
    by_obj = np.argsort(obj, kind="stable")
    keep = np.empty(obj.size, bool)
    keep[by_obj] = _after_previous(np.ascontiguousarray(meas.t[by_obj], dtype=float), obj[by_obj])
    skipped = dict(meas.skipped)
    if not keep.all():
        skipped["time not after the previous row's"] = meas.line[~keep].tolist()
    counts = np.bincount(obj[keep], minlength=meas.n_objects)
    short = keep & (counts[obj] < min_length)
    if short.any():
        skipped[f"objects with fewer than {min_length} rows"] = meas.line[short].tolist()
        keep &= ~short
    if keep.all() and counts.all():  # (an object whose every row had a NaN has no row left: renumbered below)
        return meas
    out = take_rows(meas, keep)
    out.skipped = skipped
    return out


def check_time_order(meas: Measurements) -> None:
    """Detections (``lgekf track --multi``): the rows must be in non-decreasing time (rows of equal t are one scan);
    else one DataError naming the first row that goes back in time and ``--sort``."""
    t = np.asarray(meas.t, dtype=float)
    back = np.flatnonzero(t[1:] < t[:-1])
    if back.size:
        k = int(back[0])
        w = meas.line_word
        raise DataError(
            f"{meas.source} {meas.where(k + 1)}: time goes back (t = {float(t[k + 1])!r} after t = {float(t[k])!r} on {w} "
            f"{int(meas.line[k])}); detections must be in non-decreasing time, rows of equal t being one scan "
            f"({back.size} row{'s' if back.size != 1 else ''} going back in time; --sort sorts them)"
        )


def sort_by_time(meas: Measurements) -> tuple[Measurements, int]:
    """The rows in non-decreasing time (stable: rows of equal time keep their file order; ``lgekf track --multi
    --sort``). Returns (measurements, how many rows moved)."""
    order = np.argsort(np.asarray(meas.t, dtype=float), kind="stable")
    moved = int(np.count_nonzero(order != np.arange(order.size)))
    return (take_rows(meas, order) if moved else meas), moved


def skipped_summary(meas: Measurements, first: int = 3) -> list:
    """One line per reason of ``meas.skipped``: how many rows, and the first few line numbers."""
    lines = []
    for why, where in meas.skipped.items():
        shown = ", ".join(str(v) for v in where[:first]) + (", ..." if len(where) > first else "")
        lines.append(f"skipped {len(where)} row{'s' if len(where) != 1 else ''} ({why}; line{'s' if len(where) != 1 else ''} {shown})")
    return lines
