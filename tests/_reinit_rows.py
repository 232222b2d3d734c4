"""(Test helper.) The earlier measurement of each re-initialisation of ``lgekf track``'s divergence recovery
(``lgekf.apps.divergence``): at an alarm row g of an object starting at row a, the two-point estimate uses
the measurement of g and the latest earlier one j ∈ [a, g) with t_j ≤ t_g − baseline (``REINIT_BASELINE``
= 0.5 s in ``lgekf.apps.track``), the object's first row a if there is none, and at most g − 1.

One compiled loop over the alarm rows (a binary search each, t increasing within an object): the generated
``reinit_earlier_rows``, whose ``reinit_earlier_row`` the compiled monitor (``recover_<meas>``) calls at each
re-initialisation.
"""

from __future__ import annotations

import numpy as np

from lgekf.generated.monitor import reinit_earlier_rows

__all__ = ["reinit_first_rows"]


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
    reinit_earlier_rows(np.ascontiguousarray(t, dtype=float), rows, np.ascontiguousarray(obj_first, dtype=np.int64), float(baseline), out)
    return out
