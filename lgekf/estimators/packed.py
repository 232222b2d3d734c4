"""Packed covariances in numba: the upper triangle of a symmetric n × n matrix, row-major (the layout of the
generated kernels' ``p``), to and from a dense array. Shared by the IMM, gating and PDA kernels.

The two functions are emitted once, with the IMM's loops that need them inside ``generated/`` (``generated/imm.py``,
from ``derive/codegen/templates/imm_helpers.py.tmpl``: generated code does not import the runtime); the gating and
PDA kernels of ``lgekf.estimators.multitarget`` take them from here.
"""

from __future__ import annotations

from ..generated.imm import pack_from, unpack_into

__all__ = ["unpack_into", "pack_from"]
