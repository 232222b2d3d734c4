"""GOSPA, the generalised optimal sub-pattern assignment metric (Rahmathullah, García-Fernández & Svensson,
"Generalized optimal sub-pattern assignment metric", FUSION 2017), with α = 2, and track switches.

For truth positions X (n_x) and estimates Y (n_y), cut-off c > 0 and order p ≥ 1:

    GOSPA^p = min over assignments γ ⊆ {1..n_x}×{1..n_y} with d(x, y) < c of
              Σ_(i,j)∈γ d(x_i, y_j)^p  +  c^p/2 · (n_x − |γ|)  +  c^p/2 · (n_y − |γ|)

(the localisation, missed and false parts; α = 2 makes a pair at distance ≥ c cost the same as one
missed and one false object, so the optimum is a linear assignment of min(d, c)^p, solved with
``scipy.optimize.linear_sum_assignment``).

Over a sequence of scans (``gospa_series``, and ``gospa_tracks``, public as ``lgekf.gospa``, on the tables
``lgekf track --multi`` writes): the per-scan parts, their means, and the track switches of the per-scan
assignments (``track_switches``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.optimize import linear_sum_assignment

__all__ = ["GospaParts", "gospa", "track_switches", "GospaSeries", "gospa_series", "gospa_tracks"]


@dataclass
class GospaParts:
    """One GOSPA evaluation.

    Attributes
    ----------
    distance : float
        GOSPA (the p-th root of the sum of the parts).
    localisation : float
        Σ d^p over the assigned pairs.
    missed : float
        c^p/2 times the number of missed truths.
    false : float
        c^p/2 times the number of false estimates.
    n_missed, n_false : int
        The counts.
    assignment : list of (int, int)
        The assigned (truth index, estimate index) pairs (d < c).
    """

    distance: float
    localisation: float
    missed: float
    false: float
    n_missed: int
    n_false: int
    assignment: list


def gospa(truth: np.ndarray, estimates: np.ndarray, c: float = 10.0, p: float = 2.0) -> GospaParts:
    """GOSPA (α = 2) between truth positions (n_x, d) and estimated positions (n_y, d).

    Parameters
    ----------
    truth : ndarray, (n_x, d)
        True object positions.
    estimates : ndarray, (n_y, d)
        Estimated positions.
    c : float
        Cut-off distance (m) > 0.
    p : float
        Order ≥ 1.

    Returns
    -------
    GospaParts
        The distance, its three parts and the assignment.

    Examples
    --------
    >>> g = gospa(np.array([[0.0, 0.0], [10.0, 0.0]]), np.array([[3.0, 4.0]]), c=10, p=2)
    >>> g.localisation, g.missed, g.false, g.distance   # 5² + 10²/2 (one missed)
    (25.0, 50.0, 0.0, 8.660254037844387)
    """
    if not c > 0 or not p >= 1:
        raise ValueError(f"gospa: need c > 0 and p >= 1, got c = {c}, p = {p}")
    X = np.asarray(truth, dtype=float).reshape(len(truth), -1) if len(truth) else np.zeros((0, 2))
    Y = np.asarray(estimates, dtype=float).reshape(len(estimates), -1) if len(estimates) else np.zeros((0, 2))
    half = c**p / 2.0
    pairs = []
    loc = 0.0
    if X.shape[0] and Y.shape[0]:
        d = np.sqrt(((X[:, None, :] - Y[None, :, :]) ** 2).sum(-1))
        cost = np.minimum(d, c) ** p
        ri, ci = linear_sum_assignment(cost)
        for i, j in zip(ri, ci):
            if d[i, j] < c:
                pairs.append((int(i), int(j)))
                loc += d[i, j] ** p
    nm = X.shape[0] - len(pairs)
    nf = Y.shape[0] - len(pairs)
    total = loc + half * (nm + nf)
    return GospaParts(float(total ** (1.0 / p)), float(loc), float(half * nm), float(half * nf), nm, nf, pairs)


def track_switches(assigned_ids: list) -> int:
    """Track switches: the number of times a truth's assigned track id changes to a different id.

    Parameters
    ----------
    assigned_ids : list of dict
        Per scan, {truth id: track id} of the truths that have an assigned track (e.g. the GOSPA
        assignment). A scan without an assignment for a truth does not reset it: losing a track and
        being found again by the same id is no switch; by another id it is one.

    Returns
    -------
    int

    Examples
    --------
    >>> track_switches([{0: 5}, {0: 5}, {}, {0: 7}, {0: 7, 1: 2}])
    1
    """
    last: dict = {}
    n = 0
    for scan in assigned_ids:
        for truth, trk in scan.items():
            if truth in last and last[truth] != trk:
                n += 1
            last[truth] = trk
    return n


@dataclass
class GospaSeries:
    """GOSPA over a sequence of scans: the parts per scan (p-th powers, as ``GospaParts``) and the switches.

    Attributes
    ----------
    t : ndarray (S,)
        The scans' times.
    distance, localisation, missed, false : ndarray (S,)
        Per scan: GOSPA and its three parts.
    n_missed, n_false : ndarray of int (S,)
        Per scan: missed truths and false estimates.
    switches : int
        Track switches over the sequence (``track_switches`` of the per-scan assignments).
    c, p : float
        The cut-off and the order.
    """

    t: np.ndarray
    distance: np.ndarray
    localisation: np.ndarray
    missed: np.ndarray
    false: np.ndarray
    n_missed: np.ndarray
    n_false: np.ndarray
    switches: int
    c: float
    p: float

    @property
    def mean(self) -> float:
        """The mean per-scan GOSPA (the number the multi-target study reports)."""
        return float(np.mean(self.distance)) if self.distance.size else 0.0

    def summary(self) -> dict:
        """The means over the scans of GOSPA and its parts, the totals of missed and false, the switches."""
        m = (lambda v: float(np.mean(v)) if v.size else 0.0)
        return {"gospa": self.mean, "localisation": m(self.localisation), "missed": m(self.missed),
                "false": m(self.false), "n_missed": int(self.n_missed.sum()), "n_false": int(self.n_false.sum()),
                "switches": int(self.switches), "scans": int(self.t.size), "c": self.c, "p": self.p}

    def frame(self):
        """The per-scan table (pandas DataFrame: t, gospa, localisation, missed, false, n_missed, n_false)."""
        import pandas as pd

        return pd.DataFrame({"t": self.t, "gospa": self.distance, "localisation": self.localisation,
                             "missed": self.missed, "false": self.false, "n_missed": self.n_missed,
                             "n_false": self.n_false})

    def __str__(self) -> str:
        s = self.summary()
        return (f"GOSPA {s['gospa']:.4g} (mean of {s['scans']} scans; c = {self.c:g}, p = {self.p:g}): localisation "
                f"{s['localisation']:.4g}, missed {s['missed']:.4g} ({s['n_missed']} truths), false {s['false']:.4g} "
                f"({s['n_false']} estimates); {s['switches']} track switches")


def gospa_series(truth_scans, track_scans, c: float = 10.0, p: float = 2.0, times=None) -> GospaSeries:
    """GOSPA of every scan and the track switches over the sequence.

    Parameters
    ----------
    truth_scans, track_scans : sequences of (ids, positions)
        Per scan, the truths' ids (n_x,) and positions (n_x, d), and the estimates' track ids (n_y,) and positions
        (n_y, d); the two sequences are aligned scan by scan.
    c, p : float
        Cut-off (> 0) and order (≥ 1), as ``gospa``.
    times : array_like, optional
        The scans' times (default 0, 1, 2, ...).

    Returns
    -------
    GospaSeries
    """
    truth_scans, track_scans = list(truth_scans), list(track_scans)
    if len(truth_scans) != len(track_scans):
        raise ValueError(f"gospa_series: {len(truth_scans)} truth scans but {len(track_scans)} track scans")
    rows, assigned = [], []
    for (tid, X), (eid, Y) in zip(truth_scans, track_scans):
        g = gospa(X, Y, c=c, p=p)
        rows.append((g.distance, g.localisation, g.missed, g.false, g.n_missed, g.n_false))
        assigned.append({tid[i].item() if hasattr(tid[i], "item") else tid[i]:
                         eid[j].item() if hasattr(eid[j], "item") else eid[j] for i, j in g.assignment})
    cols = np.array(rows, dtype=float).reshape(len(rows), 6).T
    t = np.arange(len(rows), dtype=float) if times is None else np.asarray(times, dtype=float)
    return GospaSeries(t, cols[0], cols[1], cols[2], cols[3], cols[4].astype(np.int64), cols[5].astype(np.int64),
                       track_switches(assigned), float(c), float(p))


def _frame(data, what: str):
    """A path (CSV), a DataFrame or a mapping of columns as a DataFrame."""
    import os

    import pandas as pd

    if isinstance(data, (str, os.PathLike)):
        try:
            data = pd.read_csv(data)
        except (OSError, ValueError) as e:
            raise ValueError(f"{what}: cannot read {os.fspath(data)!r}: {e}") from None
    return data if hasattr(data, "columns") else pd.DataFrame(dict(data))


def _table(frame, what: str, columns):
    """{"id", "t", "pos" (N, d)} of a DataFrame for the columns (id, t, x, y[, z])."""
    if columns[0] == "id" and "id" not in frame.columns and "track" in frame.columns:
        columns = ("track", *columns[1:])  # `lgekf track --multi` names its track ids `track`
    missing = [c for c in columns if c not in frame.columns]
    if missing:
        raise ValueError(f"{what}: no column {', '.join(map(repr, missing))} (has {', '.join(map(str, frame.columns))}); "
                         f"expected {', '.join(columns)}")
    out = {"id": frame[columns[0]].to_numpy()}
    for name, col in zip(("t", *range(len(columns) - 2)), columns[1:]):
        try:
            v = frame[col].to_numpy(dtype=float)
        except (TypeError, ValueError):
            raise ValueError(f"{what}: column {col!r} is not numeric") from None
        bad = np.flatnonzero(~np.isfinite(v))
        if bad.size:
            raise ValueError(f"{what}: column {col!r} is not finite in row {bad[0] + 1} (of {v.size})")
        out[name] = v
    out["pos"] = np.stack([out.pop(i) for i in range(len(columns) - 2)], axis=1)
    return out


def gospa_tracks(tracks, truth, c: float = 2.0, p: float = 2.0, tolerance: float | None = None,
                 columns=None, truth_columns=None) -> GospaSeries:
    """GOSPA of a multi-target tracker's output against the truth, scan by scan, and its track switches
    (public as ``lgekf.gospa``).

    Parameters
    ----------
    tracks : path, pandas DataFrame or mapping of columns
        The estimates, one row per track and time (e.g. ``lgekf track --multi``'s output, or ``lgekf.track(...,
        multi=True)``), with an id, a time and a position column (``columns``).
    truth : path, DataFrame or mapping of columns
        The true objects, one row per object and time. Its distinct times are the scans.
    c : float
        Cut-off distance (m) > 0 (default 2 m: about a pedestrian's step; take more for vehicles).
    p : float
        Order ≥ 1 (default 2).
    tolerance : float, optional
        A track row belongs to the scan nearest in time when within this many seconds (default: half the smallest
        interval between the truth's times, so each row belongs to one scan at most; rows farther from every scan
        are left out). A scan where no track has a row counts every truth as missed.
    columns : (id, t, x, y) or (id, t, x, y, z), optional
        The column names of ``tracks`` (with ``id``, a table without ``id`` but with ``track``, as ``lgekf track
        --multi`` writes, is read by ``track``); the position columns after t, 2 in the plane, 3 in 3-D space. Default
        ``("id", "t", "x", "y")``, and ``"z"`` after them when both tables have a z column (3-D positions).
    truth_columns : (id, t, x, y[, z]), optional
        Those of ``truth`` (default ``columns``).

    Returns
    -------
    GospaSeries
        Per scan the parts, their means (``summary()``), the switches; ``str()`` gives one line.

    Examples
    --------
    >>> truth = {"id": [1, 1], "t": [0.0, 1.0], "x": [0.0, 1.0], "y": [0.0, 0.0]}
    >>> tracks = {"id": [7, 7], "t": [0.0, 1.0], "x": [0.75, 1.75], "y": [1.0, 1.0]}
    >>> g = gospa_tracks(tracks, truth, c=2, p=2)
    >>> g.distance.tolist(), g.switches   # d = √(0.75² + 1²) = 1.25 in both scans
    ([1.25, 1.25], 0)
    """
    if not (np.isfinite(c) and c > 0) or not (np.isfinite(p) and p >= 1):
        raise ValueError(f"gospa: need c > 0 and p >= 1, got c = {c}, p = {p}")
    tracks, truth = _frame(tracks, "gospa: tracks"), _frame(truth, "gospa: truth")
    if columns is None:
        columns = ("id", "t", "x", "y") + (("z",) if "z" in tracks.columns and "z" in truth.columns else ())
    est = _table(tracks, "gospa: tracks", tuple(columns))
    tru = _table(truth, "gospa: truth", tuple(truth_columns or columns))
    if est["pos"].shape[1] != tru["pos"].shape[1]:
        raise ValueError(f"gospa: the tracks have {est['pos'].shape[1]} position columns and the truth "
                         f"{tru['pos'].shape[1]}; give columns and truth_columns of the same space")
    scans = np.unique(tru["t"])
    if scans.size == 0:
        raise ValueError("gospa: the truth has no rows")
    if tolerance is None:
        tolerance = 0.5 * float(np.min(np.diff(scans))) if scans.size > 1 else 0.0
    elif not (np.isfinite(tolerance) and tolerance >= 0):
        raise ValueError(f"gospa: tolerance must be a non-negative number of seconds, got {tolerance}")
    k = np.clip(np.searchsorted(scans, est["t"]), 1, max(scans.size - 1, 1)) if scans.size > 1 else np.zeros(est["t"].size, int)
    if scans.size > 1:  # the nearer of the two neighbouring scans
        k = np.where(np.abs(est["t"] - scans[k - 1]) <= np.abs(est["t"] - scans[k]), k - 1, k)
    keep = np.abs(est["t"] - scans[k]) <= tolerance
    ti = np.searchsorted(scans, tru["t"])
    truth_scans, track_scans = [], []
    for s in range(scans.size):
        a, b = np.flatnonzero(ti == s), np.flatnonzero(keep & (k == s))
        ids = est["id"][b]
        if len(set(ids.tolist())) < ids.size:
            seen = set()
            dup = next(i for i in ids.tolist() if i in seen or seen.add(i))
            raise ValueError(f"gospa: track {dup!r} has more than one row at the scan t = {scans[s].item()!r} "
                             f"(tolerance {tolerance:g} s); give a smaller tolerance")
        truth_scans.append((tru["id"][a], tru["pos"][a]))
        track_scans.append((ids, est["pos"][b]))
    return gospa_series(truth_scans, track_scans, c=c, p=p, times=scans)
