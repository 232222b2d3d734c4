"""The four models: their generated kernels, dimensions and state names (one table, no math)."""

from __future__ import annotations

from dataclasses import dataclass
from types import ModuleType

import numpy as np

from .generated import ctrv, cv, se2r3, se2se2

__all__ = ["ModelSpec", "MODELS", "get_model"]


@dataclass(frozen=True)
class ModelSpec:
    name: str
    kernels: ModuleType
    state_names: tuple[str, ...]  # physical state, also the order of P's coordinates
    noise_names: tuple[str, ...]  # the entries of accel_std
    description: str

    def check_state(self, name: str, x) -> None:
        """Reject physical states the model cannot represent (ValueError naming ``name``).

        SE(2)×SE(2): ω is the angle of T_d's rotation, so only |ω| ≤ π rad/s exists; a larger turn rate
        would silently alias to ω − 2π.  Use SE2R3Filter (ω a plain number) for faster rotations.
        """
        if self.name == "se2se2":
            w = np.asarray(x, dtype=float)[..., 5]
            bad = np.abs(w) > np.pi * (1 + 1e-12)
            if np.any(bad):
                raise ValueError(
                    f"{name}: ω = {float(w[bad].flat[0]):.6g} rad/s is not representable in SE(2)xSE(2), where ω is the "
                    "angle of T_d (|ω| <= π); use the se2r3 model for faster rotations"
                )

    @property
    def n(self) -> int:
        return len(self.state_names)

    @property
    def n_packed(self) -> int:
        return self.n * (self.n + 1) // 2


MODELS: dict[str, ModelSpec] = {
    "se2se2": ModelSpec(
        "se2se2",
        se2se2,
        ("x", "y", "theta", "vx", "vy", "omega"),
        ("sigma_x", "sigma_y", "sigma_omega"),
        "LG-EKF on SE(2)xSE(2) (pose + body-frame velocity as a second SE(2) element)",
    ),
    "se2r3": ModelSpec(
        "se2r3",
        se2r3,
        ("x", "y", "theta", "vx", "vy", "omega"),
        ("sigma_x", "sigma_y", "sigma_omega"),
        "LG-EKF on SE(2)xR^3 (pose + body-frame velocity vector)",
    ),
    "ctrv": ModelSpec(
        "ctrv", ctrv, ("x", "y", "psi", "v", "omega"), ("sigma_a", "sigma_alpha"), "EKF with the constant turn rate and velocity model"
    ),
    "cv": ModelSpec("cv", cv, ("x", "y", "vx", "vy"), ("sigma_a",), "Kalman filter with the constant (world-frame) velocity model"),
}


def get_model(name: str) -> ModelSpec:
    try:
        return MODELS[name]
    except (KeyError, TypeError):
        raise ValueError(f"model: unknown model {name!r}; choose one of {', '.join(MODELS)}") from None
