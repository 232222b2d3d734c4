"""lgekf: moving-object tracking with the extended Kalman filter on matrix Lie groups.

Every model shares one interface (``predict()``, ``update(z)``, ``x``, ``P``): ``SE2SE2Filter`` and
``SE2R3Filter`` (the paper's LG-EKF, Ćesić, Marković, Petrović), ``SE2R2Filter`` (a unicycle on SE(2)×R²),
``CTRVFilter`` and ``CVFilter`` (baselines), one class per model definition in ``derive/models``.
``filter_batch`` runs any of them over many trajectories in numba; ``state_from_common`` and
``covariance_from_common`` build a model's initial state and P0 from common coordinates.
``gospa`` scores a multi-target tracker's output against the truth (GOSPA per scan, its parts, track switches).
``track`` is the main job from Python: ``lgekf track`` on a file, a DataFrame or a dict of columns, its output as a
DataFrame. The runtime never imports SymPy; the symbolic source of truth is ``lgekf.derive``.

The public names are imported on first use, so ``import lgekf`` is fast and ``lgekf derive`` works
even when the generated kernels are stale.
"""

from __future__ import annotations

import importlib

__version__ = "0.1.0"

_PUBLIC = {
    "filter_batch": "lgekf.core.batch",
    "Filter": "lgekf.core.filters",
    "make_filter": "lgekf.core.filters",
    "state_from_common": "lgekf.core.common",
    "covariance_from_common": "lgekf.core.common",
    "MODELS": "lgekf.core.registry",
    "get_model": "lgekf.core.registry",
    "track": "lgekf.cli.api",
    "plot_tracks": "lgekf.apps.plot_tracks",
    "gospa": "lgekf.experiments.gospa:gospa_tracks",  # the public name: "module:attribute" when they differ
}


def _filter_classes() -> list:
    from .generated.registry import MODELS  # every definition's table entry, of every space

    return [f"{name.upper()}Filter" for name in MODELS]


def __getattr__(name):
    if name in _PUBLIC:
        module, _, attr = _PUBLIC[name].partition(":")
        return getattr(importlib.import_module(module), attr or name)
    if name.endswith("Filter") and name in _filter_classes():
        return getattr(importlib.import_module("lgekf.core.filters"), name)
    raise AttributeError(f"module 'lgekf' has no attribute {name!r}")


def __dir__():
    return sorted([*_PUBLIC, *_filter_classes(), "__version__"])


__all__ = [*_PUBLIC, *_filter_classes(), "__version__"]
