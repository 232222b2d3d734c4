"""Small builders of ``Kernel`` objects (inputs read from arrays, matrix / vector / packed-covariance outputs) shared
by the emitter and the kernel families (dispatch, smoothing steps): a module of their own, so that the families do not
import the emitter that imports them."""

from __future__ import annotations

import re
from dataclasses import replace

import sympy as sp

from ..algebra import packed_index
from .printer import Kernel, RawStage

__all__ = ["vec_inputs", "mat_inputs", "matrix_kernel", "vector_kernel", "cov_outputs", "arg_list", "on_rows", "rows_variant"]


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



def on_rows(code: str, rows: dict) -> str:
    """``code`` with each array parameter x of ``rows`` read and written as a row of a 2-D array: x → (array, row,
    ncols): x[i] → array[row, i], and for a 2-D x of ncols columns x[a, b] → array[row, a·ncols + b] (stored flat);
    x passed whole to a call → array[row] (a view of the row)."""
    for x, (array, row, ncols) in rows.items():
        if ncols is not None:
            code = re.sub(rf"\b{x}\[(\d+), (\d+)\]",
                          lambda m, a=array, r=row, nc=ncols: f"{a}[{r}, {int(m[1]) * nc + int(m[2])}]", code)
        code = re.sub(rf"\b{x}\[", f"{array}[{row}, ", code)
        # x passed whole (the PD test of a large packed covariance, ``covariance_is_pd_fused(p)``): the row itself
        code = re.sub(rf"\b{x}\b(?!\[)", f"{array}[{row}]", code)
    return code


def rows_variant(k: Kernel, name: str, params: list, rows: dict, doc: str, ret: str | None = None) -> Kernel:
    """``k`` reading and writing rows of 2-D arrays instead of taking each row as an array argument (a view and an
    argument each cost numba's reference counting): ``rows`` maps each array parameter x of ``k`` to (array, row
    expression, ncols or None) (``on_rows``; a row expression is evaluated where the row is read); ``params`` are the
    new parameters; error_model="numpy" (no exception paths)."""
    for x, (_, _, ncols) in rows.items():
        if ncols is None and any(re.search(rf"\b{x}\[\d+, ", src) for _, src in k.inputs):
            raise ValueError(f"{k.name}: {x} is 2-D")
    return replace(
        k, name=name, params=list(params), doc=doc,
        inputs=[(sym, on_rows(src, rows)) for sym, src in k.inputs],
        outputs=[(on_rows(t, rows), e) for t, e in k.outputs],
        prologue=[on_rows(line, rows) for line in k.prologue],
        epilogue=[on_rows(line, rows) for line in k.epilogue],
        stages=[RawStage([on_rows(line, rows) for line in st.lines], st.uses) if isinstance(st, RawStage) else st
                for st in k.stages],
        ret=ret if ret is not None else k.ret, error_model="numpy",
    )
