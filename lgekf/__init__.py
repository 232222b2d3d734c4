"""lgekf: moving-object tracking with the extended Kalman filter on matrix Lie groups.

Four trackers share one interface (``predict()``, ``update(z)``, ``x``, ``P``):
``SE2SE2Filter`` and ``SE2R3Filter`` (LG-EKF, Ćesić, Marković, Petrović), ``CTRVFilter`` and
``CVFilter`` (baselines). ``filter_batch`` runs any of them over many trajectories in numba.
The runtime never imports SymPy; the symbolic source of truth is ``lgekf.derive``.
"""

from .batch import filter_batch
from .filters import CTRVFilter, CVFilter, SE2R3Filter, SE2SE2Filter, make_filter

__version__ = "0.1.0"

__all__ = ["SE2SE2Filter", "SE2R3Filter", "CTRVFilter", "CVFilter", "filter_batch", "make_filter", "__version__"]
