"""The generic emitter: any motion-model definition × every measurement that fits it -> one numba module.

The emitter only loops over the kernel families (``derive/codegen/families/``, one module each, numba templates as
files in ``derive/codegen/templates/``): each family's ``kernels(model, measurements, built)`` returns (slot, kernel)
pairs, and ``LAYOUT`` orders the slots into the module (a slot ``(name, meas)`` belongs to one measurement's block).
``built`` holds what the families share: the symbolic covariance and state inputs, the prediction's stages, and the
kernels built so far (``named``, ``ordered``), which a later family extends (the SIMD lanes of the fused step, the
row variants of the IMM). Nothing here knows a model by name or by dimension.

Kernels of a model module (``s`` the internal state, ``p`` the packed covariance, upper triangle
row-major, in the tangent coordinates ε of X = μ·exp(ε)), by family:

* model (``families/model.py``): conversions ``state_from_physical``, ``state_to_physical``, ``physical_into``,
  ``group_mean``, ``common_to_state``, ``common_jacobian``, ``world_velocity``, ``world_velocity_into``,
  ``tangent_error``; the paper's quantities ``motion_omega`` (Ω), ``calC`` (𝒞), ``transition`` (F),
  ``process_noise`` (Q), ``calH_<meas>`` (ℋ); the steps ``predict`` and ``update_<meas>``; safeguards
  ``limit_angle_variance``, ``covariance_is_pd``, ``repair_pd``; ``propagate``, ``measure_<meas>``;
* fused (``families/fused.py``): ``step_try_<meas>`` / ``step_<meas>`` (predict and update in one kernel);
* filter (``families/filter.py``): the loops ``run_one_<meas>``, ``run_segments_<meas>``, ``run_one_from_<meas>``,
  ``run_segments_from_<meas>``, ``run_segments_noise_from_<meas>``, ``run_batch_<meas>``, ``simulate_batch``,
  ``propagate_rows``, ``measure_batch_<meas>``, ``world_velocities``, ``common_to_states``, ...;
* group (``families/group.py``): ``retract``, ``between``, ``right_jacobian`` / ``right_jacobian_inv``;
* bank (``families/bank.py``): multi-target loops ``innovation_bank_<meas>``, ``predict_bank``, ...;
* monitor (``families/monitor.py``): the divergence monitor ``recover_<meas>``, ``first_alarm``, ...;
* soa (``families/soa.py``): SIMD across trajectories, ``run_batch_soa_<meas>``;
* smoother (``families/smoother.py``, ``families/smooth_step.py``): ``innovation_logdet_<meas>``,
  ``run_one_store_<meas>``, ``loglik_batch_<meas>``, ``smooth_one`` / ``smooth_batch`` (RTS on the group);
* readout, mixing, imm_rows: the common coordinates, mixing on the group and the row variants of the IMM's loop.

Modules that are not a model's: ``generated/dispatch.py`` (``derive/codegen/dispatch.py``: every model's kernels behind
one signature), ``generated/imm.py`` (``families/imm.py``: the IMM's loop, its per-measurement parts from each
measurement definition), ``generated/monitor.py`` and ``generated/special.py`` (``build.py``, templates).
"""

from __future__ import annotations

from ..algebra import sym_cov
from .blocks import vec_inputs
from .families import bank, filter as filter_family, fused, group, imm_rows, mixing, model as model_family, monitor, readout
from .families import smoother, soa
from .families.group import se2_kernels, se3_kernels
from .families.model import PD_TOL

__all__ = ["se2_kernels", "se3_kernels", "model_kernels", "registry_entry", "PD_TOL", "FAMILIES", "LAYOUT"]

#: the kernel families, in the order they are built (a family may read the kernels of those before it)
FAMILIES = (model_family, group, fused, filter_family, bank, monitor, soa, smoother, readout, mixing, imm_rows)

#: the slots of a model module, in order; a tuple is a block of slots repeated for each measurement
LAYOUT = (
    "quantities",
    ("update", "step", "measure", "bank", "noise_loops", "monitor", "soa"),
    "safeguards", "soa_model", "simulation", "velocity", "common", "monitor_model", "error", "group", "bank_model",
    ("likelihood",),
    "smoother", "readout", "mixing", "imm_rows",
)


class Built:
    """What the families of one model module share: the symbolic inputs, and the kernels built so far by slot."""

    def __init__(self, model, measurements: dict):
        self.sin_ = vec_inputs("s", model.internal)
        self.P, self.pin = sym_cov(model.n)
        self.predict_parts = None  # (stages, outputs, P) of the prediction: set by the model family
        self._meas = [m.name for m in measurements.values()]
        self._items = []  # (order key, kernel)
        self._keys = {}
        for i, slot in enumerate(LAYOUT):
            if isinstance(slot, tuple):
                for j, sub in enumerate(slot):
                    self._keys[sub] = (i, j)
            else:
                self._keys[slot] = (i, 0)

    def add(self, slot, kernel) -> None:
        if isinstance(slot, tuple):
            name, meas = slot
            i, j = self._keys[name]
            key = (i, self._meas.index(meas), j)
        else:
            key = (*self._keys[slot], 0)
        self._items.append((key, kernel))

    def ordered(self) -> list:
        """The kernels built so far, in module order (slot order; within a slot, the order they were added)."""
        return [k for _, k in sorted(self._items, key=lambda item: item[0])]

    def named(self, name: str):
        """The kernel built so far called ``name``."""
        return next(k for _, k in self._items if getattr(k, "name", None) == name)


def model_kernels(model, measurements: dict) -> list:
    """Every kernel of one motion model, for the measurements that fit it: the families' kernels in ``LAYOUT`` order."""
    built = Built(model, measurements)
    for family in FAMILIES:
        for slot, kernel in family.kernels(model, measurements, built):
            built.add(slot, kernel)
    return built.ordered()


def registry_entry(model, measurements: dict, refused: dict) -> dict:
    """The plain-data description of a model that the runtime reads (generated/registry.py)."""
    return {
        "display_name": model.display_name,
        "description": model.description,
        "color": model.color,
        "space": model.space.name,
        "state_names": tuple(model.physical_names),
        "internal_names": tuple(str(s) for s in model.internal),
        "noise_names": tuple(model.noise_names),
        "default_accel_std": tuple(float(v) for v in model.default_accel_std),
        "matched_noise": tuple(model.matched_noise),
        "angles": tuple(model.angles),
        "periodic_tangent": tuple(model.periodic_tangent()),
        "bounds": {tuple(int(i) for i in (k if isinstance(k, tuple) else (k,))): float(v) for k, v in model.bounds.items()},
        "bound_reason": model.bound_reason,
        "forward_speed": tuple(model.forward_speed),
        "lifts": model.lifts,
        "noise_inputs": tuple(model.noise_symbols.index(sd) for sd in model.noise_stds()),
        "measurements": tuple(measurements),
        "refused": dict(refused),
        "linear": tuple(name for name, meas in measurements.items() if model.is_linear_gaussian(meas)),
    }
