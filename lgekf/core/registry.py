"""The model registry, read from the generated model table (``lgekf.generated.registry``): no math here,
and no model is known by name: adding a definition in ``derive/models/`` and running ``lgekf derive``
is all it takes for a model to appear in every filter, command and table.
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass, field
from types import ModuleType

import numpy as np

from ..generated.registry import DEFAULT_SPACE, SPACES
from ..generated.registry import MEASUREMENTS as _MEASUREMENTS
from ..generated.registry import MODELS as _TABLE

__all__ = ["ModelSpec", "MeasurementSpec", "MODELS", "ALL_MODELS", "MEASUREMENTS", "ALL_MEASUREMENTS", "BASE_MEASUREMENT",
           "SPACES", "DEFAULT_SPACE", "models_of", "measurements_of", "base_measurement", "rotation_dims", "space_of_positions",
           "measurement_in", "get_model", "get_measurement",
           "imm_kernel", "imm_module", "dispatch_module"]


@dataclass(frozen=True)
class MeasurementSpec:
    """A measurement model: the measured vector (``z_names``) and its noise stds (``noise_names``)."""

    name: str
    description: str
    space: str  # the space it observes (``SPACES``): it fits the models of that space
    z_names: tuple
    noise_names: tuple
    angles: tuple
    dim: int
    noise_inputs: tuple | None = None  # per entry of z, the index of its std when R = diag(σ_idx²); else None

    @property
    def has_angle(self) -> bool:
        """Whether z has an angle entry (read from the file's heading column)."""
        return bool(self.angles)

    def stds(self, position_std: float, angle_std: float) -> tuple:
        """The noise stds (``noise_names``) from one std for the position entries and one for the angles.

        An std shared by several entries of z (``noise_inputs``) is an angle's only if every entry it serves is
        an angle (the position measurement's isotropic r is one std for x and y)."""
        inputs = self.noise_inputs if self.noise_inputs is not None else tuple(range(self.dim))
        return tuple(angle_std if all(i in self.angles for i, k in enumerate(inputs) if k == j) else position_std
                     for j in range(len(self.noise_names)))

    def columns(self, positions, heading=None):
        """z (N, dim) from the positions (N, 2) and, for a measurement with an angle, the heading (N,) in rad."""
        positions = np.asarray(positions, dtype=float)
        if not self.has_angle:
            return positions
        if heading is None:
            raise ValueError(f"the {self.name} measurement needs a heading column")
        return np.column_stack([positions, np.asarray(heading, dtype=float)])


@dataclass(frozen=True)
class ModelSpec:
    """One motion model as the runtime sees it (all fields from the generated table)."""

    name: str
    display_name: str
    description: str
    color: str
    space: str  # the space the object moves in (``SPACES``: its common coordinates)
    state_names: tuple  # physical state, also the order of P's coordinates
    internal_names: tuple
    noise_names: tuple  # the entries of accel_std
    default_accel_std: tuple
    matched_noise: tuple  # per noise std: "v" or "w" (the simulated truth's σ_v or σ_ω)
    angles: tuple  # physical coordinates that are angles
    periodic_tangent: tuple
    bounds: dict  # {(indices,): bound}: the Euclidean norm of those physical coordinates is at most the bound
    bound_reason: str
    noise_inputs: tuple  # for each entry of the noise n, the index of its std in accel_std
    measurements: tuple  # the measurement models this model supports
    refused: dict = field(default_factory=dict)  # {measurement: why not}
    linear: tuple = ()  # measurements with which the model is linear Gaussian (F, Q, ℋ state-free; EM applies)
    forward_speed: tuple = ()  # (heading, speed) physical indices: (heading + π, −speed) is the same motion; () for none
    lifts: str = ""  # the planar model this 3-D model lifts ("" for none): the study compares it where the paper compares that

    @property
    def kernels(self) -> ModuleType:
        """The generated numba module of this model (imported on first use)."""
        return importlib.import_module(f"lgekf.generated.{self.name}")

    def kernel(self, family: str, measurement: str, default=None):
        """The generated kernel of ``family`` for ``measurement`` (e.g. ``kernel("run_segments", "pose")``), named by
        ``kernel_name`` (``<family>_<measurement>``, as the emitter's templates name them). ``default``: returned when the model has no such
        kernel (a family that only some models emit); without it a missing kernel is an AttributeError."""
        name = kernel_name(family, measurement)
        if default is None:
            return getattr(self.kernels, name)
        return getattr(self.kernels, name, default)

    @property
    def n(self) -> int:
        return len(self.state_names)

    @property
    def n_packed(self) -> int:
        return self.n * (self.n + 1) // 2

    def check_state(self, name: str, x) -> None:
        """Reject physical states the model cannot represent (ValueError naming ``name``).

        E.g. SE(2)×SE(2): ω is the angle of T_d's rotation, so only |ω| ≤ π rad/s exists; a larger turn
        rate would silently alias to ω − 2π (the bound and its reason come from the definition).
        """
        x = np.asarray(x, dtype=float)
        for idx, bound in self.bounds.items():
            norm = self.bounded_norm(x, idx)
            bad = norm > bound * (1 + 1e-12)
            if np.any(bad):
                what = self.state_names[idx[0]] if len(idx) == 1 else f"|({', '.join(self.state_names[i] for i in idx)})|"
                raise ValueError(
                    f"{name}: {what} = {float(norm[bad].flat[0]):.6g} is not representable in the "
                    f"{self.name} model: {self.bound_reason}"
                )

    @staticmethod
    def bounded_norm(x: np.ndarray, idx: tuple) -> np.ndarray:
        """|x_i| for a bound on one coordinate, the Euclidean norm of the coordinates ``idx`` for a bound on several
        (SE(3)×SE(3)'s turn rate, a rotation vector), over the last axis of x."""
        return np.linalg.norm(np.asarray(x, dtype=float)[..., list(idx)], axis=-1)

    def wrap_bounded(self, x: np.ndarray) -> np.ndarray:
        """x with each bounded coordinate (or vector) brought inside its bound as the model would alias it: a
        coordinate to [−b, b) modulo 2b, a rotation vector of norm t > b to the same rotation's vector of norm
        2b − t (φ·(1 − 2b/t), b = π)."""
        x = np.array(x, dtype=float)
        for idx, b in self.bounds.items():
            if len(idx) == 1:
                x[..., idx[0]] = (x[..., idx[0]] + b) % (2 * b) - b
                continue
            v = x[..., list(idx)]
            t = np.linalg.norm(v, axis=-1, keepdims=True)
            x[..., list(idx)] = v * np.where(t > b, 1 - 2 * b / np.where(t > 0, t, 1.0), 1.0)
        return x

    def measurement_or_base(self, name: str) -> str:
        """``name`` if this model takes that measurement, else ``BASE_MEASUREMENT`` (e.g. CV given poses gets
        their position part)."""
        return name if name in self.measurements else base_measurement(self.space)

    def measurement(self, name: str) -> MeasurementSpec:
        """The measurement model ``name`` if this model supports it, else a ValueError saying why."""
        meas = get_measurement(name)
        if name not in self.measurements:
            raise ValueError(f"measurement: {self.refused.get(name, f'{name} measurements do not fit the {self.name} model')}")
        return meas

    def matched_accel_std(self, sigma_v: float, sigma_w: float) -> tuple:
        """The process-noise stds matching a truth with translational σ_v and rotational σ_ω noise."""
        return tuple(sigma_v if k == "v" else sigma_w for k in self.matched_noise)


#: every registered model, of every space
ALL_MODELS: dict[str, ModelSpec] = {name: ModelSpec(name=name, **entry) for name, entry in _TABLE.items()}
#: every registered measurement, of every space
ALL_MEASUREMENTS: dict[str, MeasurementSpec] = {name: MeasurementSpec(name=name, **entry) for name, entry in _MEASUREMENTS.items()}


def models_of(space: str) -> dict[str, ModelSpec]:
    """The registered models of one space (``SPACES``), in table order."""
    return {name: spec for name, spec in ALL_MODELS.items() if spec.space == space}


def measurements_of(space: str) -> dict[str, MeasurementSpec]:
    """The registered measurements of one space."""
    return {name: spec for name, spec in ALL_MEASUREMENTS.items() if spec.space == space}


def rotation_dims(space: str) -> int:
    """Rotational coordinates of the space (1 in the plane: θ and ω; 3 in 3-D: the attitude and the body rate): its
    common coordinates are position, attitude, velocity, rate."""
    return (len(SPACES[space]["common_names"]) - 2 * SPACES[space]["dim"]) // 2


def space_of_positions(d: int) -> str:
    """The space whose positions have d coordinates (2: the plane, 3: 3-D space): what a measurement file's columns
    select (``lgekf track``: x, y or x, y, z)."""
    for name, sp in SPACES.items():
        if sp["dim"] == d:
            return name
    raise ValueError(f"positions with {d} coordinates: no space of that dimension; the spaces: "
                     + ", ".join(f"{n} ({sp['dim']} coordinates)" for n, sp in SPACES.items()))


def measurement_in(space: str, name: str) -> str:
    """The measurement of ``space`` that measures what ``name`` measures: ``name`` itself if it observes that space,
    else the one of ``space`` that, like it, measures positions only or positions and the attitude (``has_angle``):
    ``lgekf track --measure pose`` on a file of 3-D positions is pose3. A ValueError when the space has none."""
    meas = get_measurement(name)
    if meas.space == space:
        return name
    same = [m for m, spec in measurements_of(space).items() if spec.has_angle == meas.has_angle]
    if not same:
        raise ValueError(f"measurement: {name} has no counterpart in {space} space; choose one of {', '.join(measurements_of(space))}")
    return min(same, key=lambda m: ALL_MEASUREMENTS[m].dim)


def base_measurement(space: str) -> str:
    """The measurement every model of ``space`` takes (the smallest one): the default of the commands, and what a model
    that cannot take a study's measurement gets instead (from the table, not by name)."""
    models = models_of(space).values()
    return min((m for m in measurements_of(space) if all(m in spec.measurements for spec in models)),
               key=lambda m: ALL_MEASUREMENTS[m].dim)


#: the models of the default space (the plane): what ``lgekf track``, ``study``, ``sweep`` and ``evaluate`` offer
MODELS: dict[str, ModelSpec] = models_of(DEFAULT_SPACE)
#: the measurements of the default space
MEASUREMENTS: dict[str, MeasurementSpec] = measurements_of(DEFAULT_SPACE)
BASE_MEASUREMENT: str = base_measurement(DEFAULT_SPACE)


def get_model(name: str) -> ModelSpec:
    """The registered model ``name``.

    Parameters
    ----------
    name : str
        A model name: the stem of its definition file in ``derive/models/``.

    Returns
    -------
    ModelSpec
        Its entry of the generated model table (state and noise names, measurements, kernels, ...).

    Raises
    ------
    ValueError
        For an unknown name, listing the registered ones.
    """
    try:
        return ALL_MODELS[name]
    except (KeyError, TypeError):
        raise ValueError(f"model: unknown model {name!r}; choose one of {', '.join(ALL_MODELS)}") from None


def get_measurement(name: str) -> MeasurementSpec:
    """The registered measurement model ``name`` or a ValueError listing the choices."""
    try:
        return ALL_MEASUREMENTS[name]
    except (KeyError, TypeError):
        raise ValueError(f"measurement: unknown measurement {name!r}; choose one of {', '.join(ALL_MEASUREMENTS)}") from None


def imm_module(space: str) -> ModuleType:
    """The generated IMM loop of the models of ``space`` (``SPACES[space]["imm_module"]``: ``generated/imm.py`` for the
    plane, ``generated/imm_3d.py`` for 3-D space); a ValueError for a space whose models the IMM does not mix."""
    entry = SPACES.get(space)
    if entry is None or not entry["mixes"]:
        raise ValueError(f"the IMM does not mix the models of space {space!r}")
    return importlib.import_module(f"lgekf.generated.{entry['imm_module']}")


def dispatch_module(space: str) -> ModuleType:
    """The generated model chains of ``space`` (``SPACES[space]["dispatch_module"]``): its ``MODEL_NAMES`` are the model
    indices of that space's IMM loop (``imm_module``)."""
    imm_module(space)
    return importlib.import_module(f"lgekf.generated.{SPACES[space]['dispatch_module']}")


def imm_kernel(family: str, measurement: str):
    """The generated IMM kernel of ``family`` for ``measurement`` (in the IMM loop of the measurement's space,
    ``imm_module``, e.g. ``imm_kernel("imm_run_batch", "pose")``): named ``<family>_<measurement>`` as
    ``ModelSpec.kernel`` names a model's kernels (the IMM's loop spans models, so it is one module, not a model's)."""
    return getattr(imm_module(get_measurement(measurement).space), kernel_name(family, measurement))


def kernel_name(family: str, measurement: str) -> str:
    """The name of a generated kernel of ``family`` for ``measurement``: ``<family>_<measurement>``, as the emitter
    names them (the templates' ``<family>_{meas}``); the one place of the runtime that forms
    one (``ModelSpec.kernel``, ``imm_kernel``)."""
    return f"{family}_{measurement}"
