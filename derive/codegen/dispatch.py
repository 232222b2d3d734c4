"""Kernels for estimators that combine several models (the IMM): the common coordinates read off a state,
and ``generated/dispatch.py`` (one module per mixing space, ``derive.space.Space.dispatch_module``: ``dispatch.py``
for the plane, ``dispatch_3d.py`` for 3-D space), which calls any of the space's models' kernels by its index with
one signature.

Per model (appended to ``generated/<model>.py``):

* ``physical_to_common(x)``: c of a physical state (``MotionModel.common_of_physical``; in the plane
  (x, y, θ, v_x, v_y, ω));
* ``physical_to_common_jacobian(x)``: ∂c/∂ε (n_c × n) at x, for X = μ·exp(ε);
* ``common_missing()``: 1.0 for each common coordinate the model carries no information on (CV: ω), else 0;
* ``between_add``, ``mix_transport``: the fused terms of mixing on the group; ``common_of_state``,
  ``state_of_common``: a Gaussian to and from the common coordinates in one kernel (``derive.codegen.mixing``);
* their row variants ``*_at`` and ``step_ll_<meas>`` (the fused step on rows, with 1/det S) for the IMM's loop
  (``derive.codegen.imm_rows``).

``generated/dispatch.py``: ``predict(model, s, p, dt, q)``, ``update_<meas>(model, s, p, z, r)``,
``calH_<meas>(model, s)``, ``innovation_logdet_<meas>(model, s, p, r)`` (log det S), and the conversions and group
operations, each an ``if model == i`` chain over the registry (sorted names), so that one compiled numba loop
runs any mixture of models. The chain is generated, so no runtime code knows a model by name; it is inlined into
its caller (``inline="always"``), so selecting the kernel costs a branch, not a call.
"""

from __future__ import annotations


from .printer import HEADER

__all__ = ["render_dispatch"]


def _chain(fname: str, params: str, names: list, call, ret: bool) -> str:
    # inlined into the caller (numba IR): the chain adds no call of its own (and no reference counting of its array
    # arguments, ~30 ns a call in the IMM's loop); the model's kernel it selects stays one call
    lines = ['@nb.njit(cache=True, inline="always")', f"def {fname}(model, {params}):"]
    first = True
    for i, name in enumerate(names):
        body = call(name)
        if body is None:
            continue
        lines.append(f"    {'if' if first else 'elif'} model == {i}:")
        lines.append(f"        {'return ' if ret else ''}{body}")
        first = False
    if ret:
        lines.append("    raise ValueError('dispatch: model index out of range')")
    return "\n".join(lines) + "\n"


def render_dispatch(models: dict, fits: dict, measurements: dict) -> str:
    """generated/dispatch.py (or a space's ``dispatch_module``) for the models of one space (sorted names = model
    indices) and the measurements they fit."""
    names = sorted(models)
    out = [HEADER.format(title="Every model's kernels behind one signature, selected by the model index (sorted names).",
                         source="derive/codegen/dispatch.py (from the model table)")]
    out.append("import numba as nb\nimport numpy as np\n\n")
    out.append("from . import " + ", ".join(names) + "\n\n")
    out.append(f"MODEL_NAMES = {tuple(names)!r}\n")
    out.append(f"N_TANGENT = np.array({[models[n].n for n in names]!r})\n")
    out.append(f"N_INTERNAL = np.array({[len(models[n].internal) for n in names]!r})\n")
    out.append("#: COMMON_MISSING[model, k] = 1.0 where the model carries no information on common coordinate k (common_missing)\n")
    out.append(f"COMMON_MISSING = np.array({[[1.0 if i in models[n].common_missing else 0.0 for i in range(models[n].n_common)] for n in names]!r})\n")
    funcs = []
    funcs.append(_chain("predict", "s, p, dt, q", names,
                        lambda n: f"{n}.predict(s, p, dt, {', '.join(f'q[{i}]' for i in range(len(models[n].noise_names)))})", False))
    for mname, meas in sorted(measurements.items()):
        k = len(meas.noise_names)
        funcs.append(_chain(f"update_{mname}", "s, p, z, r", names,
                            lambda n, mname=mname, meas=meas, k=k: None if mname not in fits[n] else
                            f"{n}.update_{mname}(s, p, {', '.join(f'z[{i}]' for i in range(meas.m))}, {', '.join(f'r[{i}]' for i in range(k))})",
                            True))
        funcs.append(_chain(f"calH_{mname}", "s", names,
                            lambda n, mname=mname: None if mname not in fits[n] else f"{n}.calH_{mname}(s)", True))
        funcs.append(_chain(f"innovation_logdet_{mname}", "s, p, r", names,
                            lambda n, mname=mname, k=k: None if mname not in fits[n] else
                            f"{n}.innovation_logdet_{mname}(s, p, {', '.join(f'r[{i}]' for i in range(k))})", True))
    for fname, params in [("state_from_physical", "x"), ("state_to_physical", "s"), ("physical_to_common", "x"),
                          ("physical_to_common_jacobian", "x"), ("common_to_state", "c"), ("common_jacobian", "c"),
                          ("common_missing", ""), ("between", "s, t"), ("right_jacobian_inv", "eps"),
                          ("tangent_error", "s, c")]:
        funcs.append(_chain(fname, params, names, lambda n, fname=fname, params=params: f"{n}.{fname}({params})", True)
                     .replace("(model, )", "(model)"))
    funcs.append(_chain("retract", "s, eps", names, lambda n: f"{n}.retract(s, eps)", False))
    funcs.append(_chain("common_of_state", "s, p, c, Pc", names, lambda n: f"{n}.common_of_state(s, p, c, Pc)", False))
    funcs.append(_chain("state_of_common", "c, Pc, s, p", names, lambda n: f"{n}.state_of_common(c, Pc, s, p)", False))
    funcs.append(_chain("between_add", "s, t, w, acc", names, lambda n: f"{n}.between_add(s, t, w, acc)", False))
    funcs.append(_chain("mix_transport", "s, t, pt, w, acc", names, lambda n: f"{n}.mix_transport(s, t, pt, w, acc)", False))
    into_params = {"state_from_physical": "x", "between": "s, t", "right_jacobian_inv": "eps", "common_to_state": "c",
                   "common_jacobian": "c", "physical_to_common": "x", "physical_to_common_jacobian": "x"}
    for fname, params in into_params.items():
        funcs.append(_chain(f"{fname}_into", f"{params}, out", names, lambda n, fname=fname, params=params: f"{n}.{fname}_into({params}, out)", False))
    funcs.append(_chain("physical_into", "s, out", names, lambda n: f"{n}.physical_into(s, out)", False))
    for mname in sorted(measurements):
        funcs.append(_chain(f"calH_{mname}_into", "s, out", names,
                            lambda n, mname=mname: None if mname not in fits[n] else f"{n}.calH_{mname}_into(s, out)", False))
    from .families.imm_rows import dispatch_chains

    funcs += dispatch_chains(_chain, names, models, fits, measurements)  # the IMM's row variants
    out.append("\n\n" + "\n\n".join(funcs))
    return "".join(out)
