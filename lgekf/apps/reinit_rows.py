"""The earlier measurement of each re-initialisation of ``lgekf track``'s divergence recovery
(``lgekf.apps.divergence``): at an alarm row g of an object starting at row a, the two-point estimate uses
the measurement of g and the latest earlier one j ∈ [a, g) with t_j ≤ t_g − baseline (``REINIT_BASELINE``
= 0.5 s in ``lgekf.apps.track``), the object's first row a if there is none, and at most g − 1.

One compiled loop over the alarm rows (a binary search each, t increasing within an object) instead of a
Python ``searchsorted`` per row.
"""

from __future__ import annotations

import numba as nb
import numpy as np

__all__ = ["reinit_first_rows"]


@nb.njit(cache=True, nogil=True)
def _first_rows(t, rows, obj_first, baseline, out):
    """out[i] = min(max(a, (number of j in [a, g) with t[j] <= t[g] - baseline) + a - 1), g - 1),
    g = rows[i], a = obj_first[i]: ``np.searchsorted(t[a:g], t[g] - baseline, side="right")`` by bisection."""
    for i in range(rows.shape[0]):
        g = rows[i]
        a = obj_first[i]
        target = t[g] - baseline
        lo, hi = a, g  # the first j in [a, g) with t[j] > target
        while lo < hi:
            mid = (lo + hi) // 2
            if t[mid] <= target:
                lo = mid + 1
            else:
                hi = mid
        out[i] = min(max(a, lo - 1), g - 1)


def reinit_first_rows(t: np.ndarray, rows: np.ndarray, obj_first: np.ndarray, baseline: float) -> np.ndarray:
    """The earlier measurement of the two-point re-initialisation at each of ``rows``.

    Parameters
    ----------
    t : ndarray, (N,)
        Times (s), increasing within each object.
    rows : ndarray, (R,)
        Re-initialisation rows, each after its object's first row.
    obj_first : ndarray, (R,)
        The first row of the object of each of ``rows``.
    baseline : float
        The least time between the two measurements (s), if the object allows.

    Returns
    -------
    ndarray, (R,) int64
        The latest row of the same object at least ``baseline`` s before each row (the object's first row
        if none), at most the row before it.
    """
    rows = np.ascontiguousarray(rows, dtype=np.int64)
    out = np.empty(rows.shape[0], np.int64)
    _first_rows(np.ascontiguousarray(t, dtype=float), rows, np.ascontiguousarray(obj_first, dtype=np.int64), float(baseline), out)
    return out
