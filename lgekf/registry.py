"""The four models: their generated kernels, dimensions and state names (one table, no math)."""

from __future__ import annotations

from dataclasses import dataclass
from types import ModuleType

from .generated import ctrv, cv, se2r3, se2se2

__all__ = ["ModelSpec", "MODELS", "get_model"]


@dataclass(frozen=True)
class ModelSpec:
    name: str
    kernels: ModuleType
    state_names: tuple[str, ...]  # physical state, also the order of P's coordinates
    noise_names: tuple[str, ...]  # the entries of accel_std
    description: str

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
