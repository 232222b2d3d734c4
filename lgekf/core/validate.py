"""Argument checks shared by the filters, the batch runner and the CLI: one clear ValueError each."""

from __future__ import annotations

import numpy as np

__all__ = ["as_float_array", "positive_scalar", "positive_vector", "spd_matrix"]


def as_float_array(name: str, value, shape: tuple | None = None) -> np.ndarray:
    """A finite float array of the given shape (None entries match any length)."""
    try:
        a = np.array(value, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name}: expected numbers, got {type(value).__name__}") from None
    if shape is not None:
        ok = a.ndim == len(shape) and all(s is None or s == d for s, d in zip(shape, a.shape))
        if not ok:
            want = "(" + ", ".join("any" if s is None else str(s) for s in shape) + ")"
            raise ValueError(f"{name}: expected shape {want}, got {a.shape}")
    if not np.all(np.isfinite(a)):
        raise ValueError(f"{name}: contains NaN or infinite values")
    return a


def positive_scalar(name: str, value, allow_zero: bool = False) -> float:
    """A finite positive (or, with ``allow_zero``, non-negative) number; one ValueError naming ``name``.

    The one check of every noise std, step length and scale in the filters, the study, ``track`` and
    ``evaluate``."""
    a = as_float_array(name, value)
    if a.ndim != 0:
        raise ValueError(f"{name}: expected a single number, got shape {a.shape}")
    v = float(a)
    if v < 0 or (v == 0 and not allow_zero):
        raise ValueError(f"{name}: must be a {'non-negative' if allow_zero else 'positive'} number, got {v}")
    return v


def positive_vector(name: str, value, n: int, allow_zero: bool = True) -> np.ndarray:
    """A length-n vector of non-negative (or positive) stds; a scalar is accepted when n == 1."""
    a = as_float_array(name, value)
    if a.ndim == 0 and n == 1:
        a = a.reshape(1)
    if a.shape != (n,):
        raise ValueError(f"{name}: expected {n} value(s), got shape {a.shape}")
    if np.any(a < 0) or (not allow_zero and np.any(a == 0)):
        raise ValueError(f"{name}: must be {'non-negative' if allow_zero else 'positive'}, got {a.tolist()}")
    return a


def spd_matrix(name: str, value, n: int, batch: bool = False) -> np.ndarray:
    """A symmetric positive definite (n, n) matrix, or (B, n, n) when ``batch``."""
    a = as_float_array(name, value)
    if a.shape[-2:] != (n, n) or a.ndim not in ((2, 3) if batch else (2,)):
        raise ValueError(f"{name}: expected shape ({n}, {n}){' or (B, ' + str(n) + ', ' + str(n) + ')' if batch else ''}, got {a.shape}")
    scale = np.max(np.abs(a), axis=(-2, -1), keepdims=True)
    if np.any(np.abs(a - np.swapaxes(a, -1, -2)) > 1e-9 * np.maximum(scale, 1e-300)):
        raise ValueError(f"{name}: must be symmetric")
    try:
        np.linalg.cholesky(a)
    except np.linalg.LinAlgError:
        raise ValueError(f"{name}: must be positive definite") from None
    return 0.5 * (a + np.swapaxes(a, -1, -2))
