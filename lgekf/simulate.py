"""Monte Carlo truth: the paper's motion models, simulated in numba (generated ``simulate_batch``).

Truth models (eq:model): X_{k+1} = X_k exp([Ω(X_k) + G n_k]^∧), n_k = (n_x, n_y, n_ω) with
n_x, n_y ~ N(0, σ_v²), n_ω ~ N(0, σ_ω²), G = [T²/2 I; T I], on SE(2)×SE(2) (default) or SE(2)×R³.
The common physical state is c = (x, y, θ, v_x, v_y, ω) with (v_x, v_y) the body-frame velocity.

Subtlety (SE(2)×SE(2)): ω is the angle of the rotation in T_d, so it lives in [-π, π]; a random walk
of ω that crosses ±π wraps to the other sign (the object suddenly turns the other way at π rad per
step/T).  ``Simulation.wrapped`` flags the trajectories where that happens; the SE(2)×R³ truth has
no such wrap.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .generated import se2r3, se2se2

__all__ = ["Simulation", "simulate", "TRUTH_MODELS"]

TRUTH_MODELS = {"se2se2": se2se2, "se2r3": se2r3}


@dataclass
class Simulation:
    truth: np.ndarray  # (B, K + 1, 6) common physical states, truth[:, 0] the initial state
    z: np.ndarray  # (B, K, 2) position measurements of truth[:, 1:]
    dt: float
    wrapped: np.ndarray  # (B,) bool: ω crossed ±π (SE(2)×SE(2) truth only)


def simulate(
    x0,
    *,
    dt: float,
    steps: int,
    sigma_v: float,
    sigma_w: float,
    meas_std: float,
    truth: str = "se2se2",
    std_normal_process: np.ndarray | None = None,
    std_normal_meas: np.ndarray | None = None,
    rng: np.random.Generator | None = None,
) -> Simulation:
    """Simulate B = len(x0) trajectories of ``steps`` steps with position measurements.

    The standard-normal draws can be passed in (shapes (B, steps, 3) and (B, steps, 2)) so that
    several noise levels share common random numbers; otherwise they are drawn from ``rng``.
    """
    if truth not in TRUTH_MODELS:
        raise ValueError(f"truth: unknown truth model {truth!r}; choose se2se2 or se2r3")
    x0 = np.ascontiguousarray(np.atleast_2d(np.asarray(x0, dtype=float)))
    B = x0.shape[0]
    rng = rng if rng is not None else np.random.default_rng()
    u = std_normal_process if std_normal_process is not None else rng.standard_normal((B, steps, 3))
    m = std_normal_meas if std_normal_meas is not None else rng.standard_normal((B, steps, 2))
    noise = np.ascontiguousarray(u * np.array([sigma_v, sigma_v, sigma_w]))
    dts = np.full((B, steps), float(dt))
    out = np.empty((B, steps + 1, 6))
    TRUTH_MODELS[truth].simulate_batch(x0, dts, noise, out)
    z = out[:, 1:, :2] + meas_std * m
    w = out[:, :, 5]
    wrapped = np.any(np.abs(np.diff(w, axis=1)) > np.pi, axis=1) if truth == "se2se2" else np.zeros(B, bool)
    return Simulation(out, np.ascontiguousarray(z), float(dt), wrapped)
