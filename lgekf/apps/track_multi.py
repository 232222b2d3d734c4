"""`lgekf track --multi`: many objects from unlabelled detections with clutter and misses.

Input: the rows of a detection file (``t, x, y`` [, ``heading``]; an ``id`` column is ignored); one scan
is all rows with the same t (rows are ordered by t, stably). Every scan goes through
``lgekf.estimators.tracker.MultiTargetTracker``. Output: one row per confirmed track per scan,
``track, t, <state>, std_<state>, existence`` (the model's physical state, the stds of its tangent
coordinates, the existence probability).

With no clutter density given it is estimated from the data as the mean number of detections per scan
over the area of the detections' bounding box (an over-estimate: the targets' own detections count too,
which errs on the safe side of a wide clutter model).
"""

from __future__ import annotations

import numpy as np

from ..core.registry import get_model
from ..estimators.tracker import MultiTargetTracker
from ..io.formatting import format_rows, label_bytes

__all__ = ["scans", "estimated_clutter_density", "multi_output_columns", "track_scans", "write_multi"]


def scans(t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Row order sorted by time (stable) and the scan boundaries: scan k is order[starts[k]:starts[k+1]]."""
    order = np.argsort(t, kind="stable")
    ts = t[order]
    cut = np.flatnonzero(np.diff(ts) != 0) + 1
    starts = np.concatenate([[0], cut, [ts.size]]).astype(np.int64)
    return order, starts


def estimated_clutter_density(t: np.ndarray, z: np.ndarray) -> float:
    """Mean detections per scan / area of the detections' bounding box (per m² per scan, module docstring)."""
    _, starts = scans(t)
    span = np.ptp(z[:, :2], axis=0) if z.shape[0] else np.zeros(2)
    area = max(float(span[0]) * float(span[1]), 1.0)
    return max((z.shape[0] / (starts.size - 1)) / area, 1e-12)


def multi_output_columns(model: str) -> list:
    """The header: track, t, the model's state, std_<state>, existence."""
    names = list(get_model(model).state_names)
    return ["track", "t", *names, *(f"std_{s}" for s in names), "existence"]


def track_scans(t: np.ndarray, Z: np.ndarray, **tracker_args):
    """Run a ``MultiTargetTracker(**tracker_args)`` over every scan of the detections (t (N,), Z (N, m)).

    Returns
    -------
    ids : ndarray of int, (R,)
    times : ndarray, (R,)
    values : ndarray, (R, 2n + 1)
        State, stds and existence of every reported track and scan (rows in scan order, ids ascending).
    tracker : MultiTargetTracker
        The tracker after the last scan.
    """
    trk = MultiTargetTracker(**tracker_args)
    order, starts = scans(t)
    ids, times, vals = [], [], []
    for k in range(starts.size - 1):
        rows = order[starts[k]:starts[k + 1]]
        rep = trk.step(float(t[rows[0]]), Z[rows])
        if rep.ids.size:
            ids.append(rep.ids)
            times.append(np.full(rep.ids.size, rep.t))
            vals.append(np.hstack([rep.states, rep.stds, rep.existence[:, None]]))
    n = trk.spec.n
    if not ids:
        return np.zeros(0, dtype=np.int64), np.zeros(0), np.zeros((0, 2 * n + 1)), trk
    return np.concatenate(ids), np.concatenate(times), np.vstack(vals), trk


def write_multi(fh, model: str, ids, times, values, digits: int) -> None:
    """Write the header and the rows of ``track_scans`` as CSV bytes to ``fh``."""
    fh.write((",".join(multi_output_columns(model)) + "\n").encode())
    if ids.size == 0:
        return
    labels, row = np.unique(ids, return_inverse=True)
    fh.write(format_rows(label_bytes([str(i) for i in labels]), row, times, values, digits))
