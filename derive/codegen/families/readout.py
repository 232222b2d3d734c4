"""The readout family: the common coordinates read off a model's state, for estimators that combine several models
(the IMM), and the allocation-free ``<name>_into`` variants of the kernels the IMM's loop and the smoother's backward
step call (``INTO``).

* ``physical_to_common(x)``: c = (x, y, θ, v_x, v_y, ω) of a physical state (``MotionModel.common_of_physical``);
* ``physical_to_common_jacobian(x)``: ∂c/∂ε (6 × n) at x, for X = μ·exp(ε);
* ``common_missing()``: 1.0 for each common coordinate the model carries no information on (CV: ω), else 0.
"""

from __future__ import annotations

from dataclasses import replace

from ..blocks import matrix_kernel, vec_inputs, vector_kernel
from ..printer import Kernel
from ..template import load

__all__ = ["INTO", "INTO_PER_MEASUREMENT", "into_variant", "common_readout_kernels", "kernels"]


#: kernels that also get an allocation-free ``<name>_into(..., out)`` variant (the IMM's inner loop, the smoother's
#: backward step)
INTO = ("state_from_physical", "between", "right_jacobian", "right_jacobian_inv", "transition", "common_to_state",
        "common_jacobian", "physical_to_common", "physical_to_common_jacobian")
#: the per-measurement kernels (``<family>_<meas>``) that get one, for every measurement that fits the model
INTO_PER_MEASUREMENT = ("calH",)


def into_variant(k: Kernel) -> Kernel:
    """The same kernel writing into a caller's ``out`` (zeroed first) instead of allocating it."""
    matrix = any("np.zeros((" in line for line in k.prologue)
    return replace(k, name=f"{k.name}_into", params=[*k.params, "out"], ret=None,
                   prologue=["out[:, :] = 0.0" if matrix else "out[:] = 0.0"],
                   doc=f"{k.doc.rstrip()}\nWritten into ``out`` (no allocation).")


def common_readout_kernels(model, kernels=(), measurements=()) -> list:
    """``physical_to_common``, ``physical_to_common_jacobian`` and ``common_missing`` of one model, and the
    ``_into`` variants (``INTO``, ``INTO_PER_MEASUREMENT`` of the ``measurements``' names) of those and of ``kernels``
    (the model's other kernels)."""
    into = set(INTO) | {f"{family}_{meas}" for family in INTO_PER_MEASUREMENT for meas in measurements}
    xin = vec_inputs("xp", model.physical)
    nc, cdoc = model.n_common, model.space.common_doc
    missing = [1.0 if i in model.common_missing else 0.0 for i in range(nc)]
    frame = "a heading" if model.space.dim == 2 else "an attitude"
    angle = "θ" if model.space.dim == 2 else "the attitude"
    own = [
        vector_kernel("physical_to_common", f"c = {cdoc} of a physical state x ({angle} from the velocity for a model\n"
                      f"without {frame}; 0 for the coordinates of common_missing).", ["xp"], xin, model.common_of_physical),
        matrix_kernel("physical_to_common_jacobian", f"A = ∂c/∂ε ({nc} × n) at the physical state x (X = μ·exp ε): P_c = A P Aᵀ.",
                      ["xp"], xin, model.common_of_physical_jacobian),
        ("common_missing", load("common_missing.py.tmpl").format(missing=repr(missing), common=cdoc)),
    ]
    every = [k for k in (*kernels, *own) if isinstance(k, Kernel) and k.name in into]
    return own + [into_variant(k) for k in every]


def kernels(model, measurements: dict, built) -> list:
    """The family's entry (``derive.codegen.emitter``): the readout and the ``_into`` variants of the kernels so far."""
    return [("readout", k) for k in common_readout_kernels(model, built.ordered(), [m.name for m in measurements.values()])]
