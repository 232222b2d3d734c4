"""One long object tracked in windows of rows, with the memory of a window instead of the object's.

``track_monitored`` holds every row's state and covariance of what it tracks (the divergence monitor re-runs the
filter from a re-initialisation anywhere in the object): for one object of 10⁶ rows, SE(2)×SE(2) (21 packed
covariance entries a row), that is 230 MB, ten times its CSV. ``filter_windows`` gives the same rows, bit for bit,
a window at a time:

* the filter continues from the internal state and covariance of the previous window's last row (the first pass of
  the compiled monitor ``recover_<meas>``, or the generated ``run_segments_from_<meas>`` when nothing is monitored),
  so a window's numbers are those of one run over the object;
* the monitor (``divergence.recover``) scans a window's rows from W = max(``window``, ``short``) rows before it (the
  furthest its NIS tests reach back), or from the object's last re-initialisation if later: every test it makes from the window's first row on sums the same
  NIS values, over the same updates since the (re-)initialisation, as one scan over the object; the rows
  before the window were tested there already (without an alarm, else the previous window would have
  recovered). Its memory of the object (re-initialisations so far, noise inflation, last re-initialisation)
  goes from window to window (``divergence.MonitorMemory``); once ``max_reinit`` is used up the object is
  no longer monitored, as in one scan;
* an alarm flags rows from at most the row before its scan's first row, W + 1 rows before the window, so the
  last W + 1 rows of a window are held back and given out with the next one.

Conventions as ``track_monitored``: rows 0 and 1 carry the two-point start, the filter runs from row 2;
states physical, covariances packed in the filter's tangent coordinates (X = μ·exp(ε)).
"""

from __future__ import annotations

from dataclasses import replace
from typing import Iterator

import numpy as np

from ..core.registry import get_model
from .divergence import NEVER, Carry, FirstPass, MonitorConfig, MonitorMemory, Restart, recover

__all__ = ["filter_windows", "WINDOW_ROWS"]

WINDOW_ROWS = 1 << 15  # rows filtered and monitored at a time


def filter_windows(model: str, x0, p0, restart: Restart, monitor: MonitorConfig | None, limit: float,
                   rows: int = WINDOW_ROWS) -> Iterator[tuple]:
    """Filter and monitor ONE object (every row of ``t``, ``zm``) as ``track_monitored`` does, a window of rows at a
    time (``lgekf.apps.track.track_windows`` prepares the inputs from a ``TrackConfig``).

    Parameters
    ----------
    model : str
        Registry model.
    x0 : ndarray, shape (n,)
        The two-point start (physical) at row 1; row 0 carries it with the first measured position.
    p0 : ndarray, shape (n(n+1)/2,)
        Its packed covariance.
    restart : divergence.Restart
        The object: its times ``t`` (N,) (increasing, N >= 2) and measurements ``zm`` (N, m), the measurement, the
        noise stds q, r and the re-initialisation's inputs (``obj_first`` [0]); each window is its ``offset``.
    monitor : MonitorConfig or None
        None: no monitoring (all flags 0).
    limit : float
        The object's speed limit (``divergence.speed_limits``).
    rows : int
        Rows filtered per window (at least 1).

    Yields
    ------
    (a, x, p, nis, flag, alarms)
        Consecutive row ranges [a, a + len(x)) covering 0 .. N - 1 in order, each with what ``track_monitored``
        gives on those rows and the alarms detected since the previous piece (``obj`` 0, ``row`` counted from the
        object's first row, not from a; an alarm's row may be among the rows held back for the next piece).
    """
    if rows < 1:
        raise ValueError(f"rows: must be at least 1, got {rows}")
    spec = get_model(model)
    kern = spec.kernels
    run = spec.kernel("run_segments_from", restart.measurement)
    t, zm, q, r = restart.t, restart.zm, restart.q, restart.r
    N = t.size
    limits = np.array([limit], dtype=float)
    x0 = np.asarray(x0, dtype=float)
    p0 = np.asarray(p0, dtype=float)
    carry_s = np.empty((1, len(spec.internal_names)))  # the filter's internal state and covariance after the last row filtered
    kern.state_from_physical_into(x0, carry_s[0])
    carry_p = p0[None, :].copy()
    memory = MonitorMemory.fresh(1)  # `last` in the object's rows
    # the NIS tests reach back `reach` rows; the next window's scan starts at most that far back, and its alarms flag
    # rows from at most the row before its scan's first row: those rows are held back (without a monitor, one row:
    # the time of the row before the next window)
    reach = 0 if monitor is None else max(int(monitor.window), int(monitor.short))
    hold = reach + 1
    run_scale = 1.0  # the noise inflation of the run that filtered the last row (after max_reinit, not the object's latest)
    tail = None  # the held-back rows: (x, p, nis, flag) of rows [L, A)
    L, A = 0, 2  # the window's arrays start at row L; the filter goes on from row A
    while True:
        B = min(N, A + rows)
        x = np.empty((B - L, spec.n))
        p = np.empty((B - L, spec.n_packed))
        nis = np.full(B - L, np.nan)
        flag = np.zeros(B - L, np.int8)
        if tail is None:  # rows 0 and 1: the two-point start (as track_arrays)
            x[0] = x0
            x[0, :2] = zm[0, :2]
            x[1] = x0
            p[0] = p[1] = p0
        else:
            x[:A - L], p[:A - L], nis[:A - L], flag[:A - L] = tail
        alarms = []
        if monitor is not None and memory.count[0] <= monitor.max_reinit:
            last_global = int(memory.last[0])
            scan_from = max(A - reach, 2, last_global + 1 if last_global != NEVER else 2)
            if last_global != NEVER:
                memory.last[0] = last_global - L
            # the window's rows filtered from where the previous window's run ended, then monitored, in one compiled call;
            # carry: where the run that filtered the window's last row left the filter
            carry = Carry(carry_s, carry_p, np.array([run_scale]), np.zeros(1, np.bool_))
            f, alarms = recover(model, x, p, nis, np.array([0, B - L], np.int64), limits, zm.shape[1], monitor,
                                replace(restart, offset=L), first=np.array([scan_from - L], np.int64), memory=memory,
                                carry=carry, first_pass=FirstPass(np.array([A - L]), carry_s.copy(), carry_p.copy(), np.array([run_scale])))
            run_scale = float(carry.scale[0])
            if memory.last[0] != NEVER:
                memory.last[0] += L
            flag |= f
            for al in alarms:
                al.row += L
        else:  # no monitor (or none left after max_reinit): the filter alone
            run(zm[L:B], t[L:B], np.array([A - L], np.int64), np.array([B - A], np.int64), carry_s, carry_p, q * run_scale, r * run_scale,
                x, p, nis)
        done = B == N
        keep = 0 if done else min(hold, B - L)
        cut = B - L - keep
        yield L, x[:cut], p[:cut], nis[:cut], flag[:cut], alarms
        if done:
            return
        tail = (x[cut:].copy(), p[cut:].copy(), nis[cut:].copy(), flag[cut:].copy())
        L, A = B - keep, B
