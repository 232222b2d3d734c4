"""Row variants of the IMM's kernels: the same straight-line code reading and writing rows of one 2-D array.

The IMM's loop (``lgekf.estimators.imm.kernels``) keeps every mode's state and covariance as rows of 2-D arrays
(and everything else its step touches) as rows of one 2-D workspace ``ws``. Passing a row as a view (``S[j]``), a
tuple of scratch arrays, or one array as several arguments of an inlined call costs numba's reference counting
(atomic ``NRT_incref``/``NRT_decref``; each array argument of the inlined dispatch chain is an alias, counted once
per call): measured with ``perf``, about half of the IMM's time before this change. A row variant takes the one
array and row indices instead, and uses ``error_model="numpy"`` (no exception paths), so the kernel itself needs
no counting either.

``row_variant(k, arrays)`` rewrites a :class:`~derive.codegen.printer.Kernel` mechanically: the first parameter is
``ws``, every array parameter ``x`` becomes a row index ``jx`` and ``x[i]`` becomes ``ws[jx, i]``; a 2-D parameter
``x[a, b]`` of ``ncols`` columns is stored flat in its row, ``ws[jx, a·ncols + b]``. Emitted per model (``imm_row_kernels``):

* ``between_add_at``, ``mix_transport_at``, ``retract_at``: the mean iteration and the transported covariance
  terms of mixing on the group (``derive.codegen.mixing``);
* ``common_of_state_at`` / ``state_of_common_at``: a Gaussian to and from the common coordinates, the common
  covariance (6 × 6 in the plane) stored row-major in one row;
* ``step_ll_<meas>``: the fused step ``step_try_<meas>`` (``derive.codegen.fused``) on rows, returning
  ``(nis, rdet)``, rdet = 1/det S of the innovation covariance S = ℋPℋᵀ + R at the predicted state (eq:K), which
  the step computes anyway: the IMM's likelihood needs log det S = −log rdet, and no separate
  ``innovation_logdet_<meas>`` pass over the predicted covariance. S does not depend on the update, so rdet holds
  also when the step returns ``FALLBACK`` (the caller then runs ``update_<meas>``).

``mix_on_group_at`` (a template per model, ``MIX_TEMPLATE``): the whole reduction Σ w_i N_G(μ_i, P_i) → N_G(μ, P) of
mixing on the group (the iterated mean, then the transported covariance terms; maths in
``lgekf.estimators.imm.kernels``) as one loop calling the row variants above directly: a call through the inlined
dispatch chain counts ``ws`` once, a direct call does not, so the loop's 2–4 kernel calls per source and iteration
count nothing.

``dispatch_chains`` adds their model-index chains to ``generated/dispatch.py``.
"""

from __future__ import annotations

from ..blocks import rows_variant
from ..printer import Kernel
from ..template import load

__all__ = ["row_variant", "imm_row_kernels", "dispatch_chains", "ROW_KERNELS", "MIX_TEMPLATE", "kernels"]

#: (kernel, name of the row variant, {array parameter: columns of its 2-D form ("common": the number of common
#: coordinates of the model's space), or None for a vector})
ROW_KERNELS = (
    ("between_add", "between_add_at", {"s": None, "t": None, "acc": None}),
    ("mix_transport", "mix_transport_at", {"s": None, "t": None, "pt": None, "acc": None}),
    ("retract", "retract_at", {"s": None, "eps": None}),
    ("common_of_state", "common_of_state_at", {"s": None, "p": None, "c": None, "Pc": "common"}),
    ("state_of_common", "state_of_common_at", {"c": None, "Pc": "common", "s": None, "p": None}),
)


def row_variant(k: Kernel, name: str, arrays: dict, ret: str | None = None, doc: str | None = None) -> Kernel:
    """``k`` on rows of one 2-D array ``ws``: each parameter x of ``arrays`` becomes a row index jx, x[i] → ws[jx, i]
    (x[a, b] → ws[jx, a·ncols + b] for a 2-D parameter of ncols columns); error_model="numpy" (module docstring)."""
    if "ws" in k.params:
        raise ValueError(f"{k.name}: a parameter is already called ws")
    return rows_variant(
        k, name, ["ws"] + [f"j{p}" if p in arrays else p for p in k.params],
        {x: ("ws", f"j{x}", ncols) for x, ncols in arrays.items()},
        doc or f"{k.doc.rstrip()}\nOn rows of ws: {', '.join(f'{x} = ws[j{x}]' for x in arrays)} (derive/codegen/imm_rows.py).",
        ret=ret)


MIX_TEMPLATE = load("mix_on_group.py.tmpl")


def imm_row_kernels(model, kernels) -> list:
    """The row variants of one model (module docstring); ``kernels``: the model's kernels so far."""
    by_name = {k.name: k for k in kernels if isinstance(k, Kernel)}
    out = [row_variant(by_name[src], name, {x: model.n_common if c == "common" else c for x, c in arrays.items()})
           for src, name, arrays in ROW_KERNELS]
    for kname, k in sorted(by_name.items()):
        if kname.startswith("step_try_"):
            meas = kname[len("step_try_"):]
            out.append(row_variant(
                k, f"step_ll_{meas}", {"s": None, "p": None}, ret="nis, rdet",
                doc=(f"``step_try_{meas}`` on rows s = ws[js], p = ws[jp] (derive/codegen/imm_rows.py); returns (nis, rdet),\n"
                     "rdet = 1/det S, S = ℋPℋᵀ + R at the predicted state (eq:K), also when nis is FALLBACK.")))
    n = model.n
    out.append(("mix_on_group_at", MIX_TEMPLATE.format(n=n, ni=len(model.internal), npk=n * (n + 1) // 2)))
    return out


def dispatch_chains(chain, names: list, models: dict, fits: dict, measurements: dict) -> list[str]:
    """The model-index chains of the row variants (``chain``: derive.codegen.dispatch's chain renderer); one array
    ``ws`` and row indices: the inlined chain aliases each array argument once (one reference count per call)."""
    funcs = [
        chain("between_add_at", "ws, js, jt, w, jacc", names, lambda n: f"{n}.between_add_at(ws, js, jt, w, jacc)", False),
        chain("mix_transport_at", "ws, js, jt, jpt, w, jacc", names,
              lambda n: f"{n}.mix_transport_at(ws, js, jt, jpt, w, jacc)", False),
        chain("retract_at", "ws, js, jeps", names, lambda n: f"{n}.retract_at(ws, js, jeps)", False),
        chain("mix_on_group_at", "ws, M, rw, rs, rp, rS, rPp, rd", names,
              lambda n: f"{n}.mix_on_group_at(ws, M, rw, rs, rp, rS, rPp, rd)", True),
        chain("common_of_state_at", "ws, js, jp, jc, jPc", names, lambda n: f"{n}.common_of_state_at(ws, js, jp, jc, jPc)", False),
        chain("state_of_common_at", "ws, jc, jPc, js, jp", names, lambda n: f"{n}.state_of_common_at(ws, jc, jPc, js, jp)", False),
    ]
    for mname, meas in sorted(measurements.items()):
        def call(n, mname=mname, meas=meas):
            if mname not in fits[n]:
                return None
            q = ", ".join(f"ws[jq, {i}]" for i in range(len(models[n].noise_names)))
            z = ", ".join(f"ws[jz, {i}]" for i in range(meas.m))
            r = ", ".join(f"ws[jr, {i}]" for i in range(len(meas.noise_names)))
            return f"{n}.step_ll_{mname}(ws, js, jp, dt, {q}, {z}, {r})"
        funcs.append(chain(f"step_ll_{mname}", "ws, js, jp, dt, jq, jz, jr", names, call, True))
    return funcs


def kernels(model, measurements: dict, built) -> list:
    """The family's entry (``derive.codegen.emitter``): the row variants of the model's kernels built so far."""
    return [("imm_rows", k) for k in imm_row_kernels(model, built.ordered())]
