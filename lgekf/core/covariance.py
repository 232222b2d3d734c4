"""Packed storage of symmetric covariances: the upper triangle, row-major (n(n+1)/2 numbers)."""

from __future__ import annotations

import numpy as np

__all__ = ["pack", "unpack", "packed_indices", "packed_diagonal"]


def packed_indices(n: int):
    """Row and column indices of the packed upper triangle, in storage order."""
    return np.triu_indices(n)


def packed_diagonal(n: int) -> np.ndarray:
    """Positions of the diagonal entries in the packed storage."""
    i, j = packed_indices(n)
    return np.flatnonzero(i == j)


def pack(P: np.ndarray) -> np.ndarray:
    """(..., n, n) symmetric -> (..., n(n+1)/2); the upper triangle is kept."""
    P = np.asarray(P, dtype=float)
    i, j = packed_indices(P.shape[-1])
    return np.ascontiguousarray(P[..., i, j])


def unpack(p: np.ndarray, n: int) -> np.ndarray:
    """(..., n(n+1)/2) -> (..., n, n), symmetric by construction."""
    p = np.asarray(p, dtype=float)
    i, j = packed_indices(n)
    out = np.empty(p.shape[:-1] + (n, n))
    out[..., i, j] = p
    out[..., j, i] = p
    return out
