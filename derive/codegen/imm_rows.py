"""Row variants of the IMM's kernels: the same straight-line code reading and writing rows of 2-D arrays.

The IMM's loop (``lgekf.estimators.imm_kernels``) keeps every mode's state and covariance as rows of 2-D arrays
(``S`` (M, L), ``Pp`` (M, N)) and its scratch as rows of one 2-D workspace. Passing a row as a view (``S[j]``) or a
tuple of scratch arrays to a kernel costs numba's reference counting (atomic ``NRT_incref``/``NRT_decref``): measured
with ``perf``, about half of the IMM's time before this change. A row variant takes the array and the row index
instead, so the caller passes arrays it already holds (no view, nothing to count inside its loop), and uses
``error_model="numpy"`` (no exception paths), so the kernel itself needs no counting either.

``row_variant(k, arrays)`` rewrites a :class:`~derive.codegen.printer.Kernel` mechanically: every array parameter
``x`` becomes ``x, jx`` and ``x[i]`` becomes ``x[jx, i]``; a 2-D parameter ``x[a, b]`` of ``ncols`` columns is
stored flat in the row, ``x[jx, a·ncols + b]``. Emitted per model (``imm_row_kernels``):

* ``between_add_at``, ``mix_transport_at``, ``retract_at``: the mean iteration and the transported covariance
  terms of mixing on the group (``derive.codegen.mixing``);
* ``common_of_state_at`` / ``state_of_common_at``: a Gaussian to and from the common coordinates, the 6 × 6
  common covariance stored row-major in one row;
* ``step_ll_<meas>``: the fused step ``step_try_<meas>`` (``derive.codegen.fused``) on rows, returning
  ``(nis, rdet)``, rdet = 1/det S of the innovation covariance S = ℋPℋᵀ + R at the predicted state (eq:K), which
  the step computes anyway: the IMM's likelihood needs log det S = −log rdet, and no separate
  ``innovation_logdet_<meas>`` pass over the predicted covariance. S does not depend on the update, so rdet holds
  also when the step returns ``FALLBACK`` (the caller then runs ``update_<meas>``).

``dispatch_chains`` adds their model-index chains to ``generated/dispatch.py``.
"""

from __future__ import annotations

import re
from dataclasses import replace

from .printer import Kernel, RawStage

__all__ = ["row_variant", "imm_row_kernels", "dispatch_chains", "ROW_KERNELS"]

#: (kernel, name of the row variant, {array parameter: columns of its 2-D form, or None for a vector})
ROW_KERNELS = (
    ("between_add", "between_add_at", {"s": None, "t": None, "acc": None}),
    ("mix_transport", "mix_transport_at", {"s": None, "t": None, "pt": None, "acc": None}),
    ("retract", "retract_at", {"s": None, "eps": None}),
    ("common_of_state", "common_of_state_at", {"s": None, "p": None, "c": None, "Pc": 6}),
    ("state_of_common", "state_of_common_at", {"c": None, "Pc": 6, "s": None, "p": None}),
)


def _rewrite(code: str, arrays: dict) -> str:
    for x, ncols in arrays.items():
        if ncols is not None:
            code = re.sub(rf"\b{x}\[(\d+), (\d+)\]", lambda m, x=x, nc=ncols: f"{x}[j{x}, {int(m[1]) * nc + int(m[2])}]", code)
        code = re.sub(rf"\b{x}\[(?!j{x}, )", f"{x}[j{x}, ", code)
    return code


def row_variant(k: Kernel, name: str, arrays: dict, ret: str | None = None, doc: str | None = None) -> Kernel:
    """``k`` on rows: each parameter x of ``arrays`` becomes (x, jx), x[i] → x[jx, i] (x[a, b] → x[jx, a·ncols + b]
    for a 2-D parameter of ncols columns); error_model="numpy" (module docstring)."""
    for x, ncols in arrays.items():
        if ncols is None and any(re.search(rf"\b{x}\[\d+, ", s) for _, s in k.inputs):
            raise ValueError(f"{k.name}: {x} is 2-D")
    params = []
    for p in k.params:
        params += [p, f"j{p}"] if p in arrays else [p]
    return replace(
        k, name=name, params=params,
        doc=doc or f"{k.doc.rstrip()}\nOn rows: {', '.join(f'{x}[j{x}]' for x in arrays)} (derive/codegen/imm_rows.py).",
        inputs=[(s, _rewrite(src, arrays)) for s, src in k.inputs],
        outputs=[(_rewrite(t, arrays), e) for t, e in k.outputs],
        prologue=[_rewrite(line, arrays) for line in k.prologue],
        epilogue=[_rewrite(line, arrays) for line in k.epilogue],
        stages=[RawStage([_rewrite(line, arrays) for line in st.lines], st.uses) if isinstance(st, RawStage) else st
                for st in k.stages],
        ret=ret if ret is not None else k.ret, error_model="numpy",
    )


def imm_row_kernels(model, kernels) -> list:
    """The row variants of one model (module docstring); ``kernels``: the model's kernels so far."""
    by_name = {k.name: k for k in kernels if isinstance(k, Kernel)}
    out = [row_variant(by_name[src], name, arrays) for src, name, arrays in ROW_KERNELS]
    for kname, k in sorted(by_name.items()):
        if kname.startswith("step_try_"):
            meas = kname[len("step_try_"):]
            out.append(row_variant(
                k, f"step_ll_{meas}", {"s": None, "p": None}, ret="nis, rdet",
                doc=(f"``step_try_{meas}`` on rows s[js], p[jp] (derive/codegen/imm_rows.py); returns (nis, rdet),\n"
                     "rdet = 1/det S, S = ℋPℋᵀ + R at the predicted state (eq:K), also when nis is FALLBACK.")))
    return out


def dispatch_chains(chain, names: list, models: dict, fits: dict, measurements: dict) -> list[str]:
    """The model-index chains of the row variants (``chain``: derive.codegen.dispatch's chain renderer)."""
    funcs = [
        chain("between_add_at", "s, js, t, jt, w, acc, jacc", names,
              lambda n: f"{n}.between_add_at(s, js, t, jt, w, acc, jacc)", False),
        chain("mix_transport_at", "s, js, t, jt, pt, jpt, w, acc, jacc", names,
              lambda n: f"{n}.mix_transport_at(s, js, t, jt, pt, jpt, w, acc, jacc)", False),
        chain("retract_at", "s, js, eps, jeps", names, lambda n: f"{n}.retract_at(s, js, eps, jeps)", False),
        chain("common_of_state_at", "s, js, p, jp, c, jc, Pc, jPc", names,
              lambda n: f"{n}.common_of_state_at(s, js, p, jp, c, jc, Pc, jPc)", False),
        chain("state_of_common_at", "c, jc, Pc, jPc, s, js, p, jp", names,
              lambda n: f"{n}.state_of_common_at(c, jc, Pc, jPc, s, js, p, jp)", False),
    ]
    for mname, meas in sorted(measurements.items()):
        def call(n, mname=mname, meas=meas):
            if mname not in fits[n]:
                return None
            q = ", ".join(f"q[jq, {i}]" for i in range(len(models[n].noise_names)))
            z = ", ".join(f"z[jz, {i}]" for i in range(meas.m))
            r = ", ".join(f"r[jr, {i}]" for i in range(len(meas.noise_names)))
            return f"{n}.step_ll_{mname}(s, js, p, jp, dt, {q}, {z}, {r})"
        funcs.append(chain(f"step_ll_{mname}", "s, js, p, jp, dt, q, jq, z, jz, r, jr", names, call, True))
    return funcs
