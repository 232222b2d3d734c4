"""Packed covariances in numba: the upper triangle of a symmetric n × n matrix, row-major (the layout of the
generated kernels' ``p``), to and from a dense array. Shared by the IMM, gating and PDA kernels.
"""

from __future__ import annotations

import numba as nb

__all__ = ["unpack_into", "pack_from"]


@nb.njit(cache=True)
def unpack_into(p, n, out):
    """Packed upper triangle (row-major) -> dense symmetric out[:n, :n]."""
    k = 0
    for i in range(n):
        for j in range(i, n):
            out[i, j] = p[k]
            out[j, i] = p[k]
            k += 1


@nb.njit(cache=True)
def pack_from(P, n, p):
    """Dense P[:n, :n] -> packed upper triangle p (symmetrised)."""
    k = 0
    for i in range(n):
        for j in range(i, n):
            p[k] = 0.5 * (P[i, j] + P[j, i])
            k += 1
