"""Small builders of ``Kernel`` objects (inputs read from arrays, matrix / vector / packed-covariance outputs) shared
by the emitter and the kernel families (dispatch, smoothing steps): a module of their own, so that the families do not
import the emitter that imports them."""

from __future__ import annotations

import sympy as sp

from ..algebra import packed_index
from .printer import Kernel

__all__ = ["vec_inputs", "mat_inputs", "matrix_kernel", "vector_kernel", "cov_outputs", "arg_list"]


def vec_inputs(name, syms):
    return [(s, f"{name}[{i}]") for i, s in enumerate(syms)]


def mat_inputs(name, rows, cols, prefix):
    syms = sp.Matrix(rows, cols, lambda i, j: sp.Symbol(f"{prefix}{i}{j}", real=True))
    return syms, [(syms[i, j], f"{name}[{i}, {j}]") for i in range(rows) for j in range(cols)]


def matrix_kernel(name, doc, params, inputs, Mx, subs=None):
    return Kernel(
        name=name, doc=doc, params=params, inputs=inputs,
        outputs=[(f"out[{i}, {j}]", Mx[i, j]) for i in range(Mx.shape[0]) for j in range(Mx.shape[1])],
        prologue=[f"out = np.zeros(({Mx.shape[0]}, {Mx.shape[1]}))"], ret="out",
        substitutions=subs or {}, skip_zero_outputs=True,
    )


def vector_kernel(name, doc, params, inputs, v, subs=None):
    v = list(v)
    return Kernel(
        name=name, doc=doc, params=params, inputs=inputs,
        outputs=[(f"out[{i}]", e) for i, e in enumerate(v)],
        prologue=[f"out = np.zeros({len(v)})"], ret="out",
        substitutions=subs or {}, skip_zero_outputs=True,
    )


def cov_outputs(Pn: sp.Matrix):
    n = Pn.shape[0]
    idx = packed_index(n)
    return [(f"p[{idx[(i, j)]}]", Pn[i, j]) for i in range(n) for j in range(i, n)]


def arg_list(prefix, k):
    """``prefix[0], prefix[1], ...`` (k entries): the arguments of a generated call."""
    return ", ".join(f"{prefix}[{i}]" for i in range(k))
