"""Monte Carlo truth: any registry model's exact motion, simulated in numba (generated ``simulate_batch``),
and its measurements through the generated ``measure_batch_<measurement>``.

Truth (eq:model): X_{k+1} = X_k exp([Ω(X_k) + G n_k]^∧) with the truth model's noise n_k, its stds
matched to (σ_v, σ_ω) through the definition's ``matched_noise`` (the paper's LG truths: n_x, n_y ~
N(0, σ_v²), n_ω ~ N(0, σ_ω²), G = [T²/2 I; T I]).  A truth model must have the common physical state
c = (x, y, θ, v_x, v_y, ω) (body-frame velocity): SE(2)×SE(2) (default) or SE(2)×R³.
Measurements Z = h(X)·exp(m) (position: z = (x, y) + m; pose: z = (x, y, θ) of h(X)·exp(m), m in the
tangent of SE(2)).

Subtlety (SE(2)×SE(2)): ω is the angle of the rotation in T_d, so it lives in [−π, π]; a random walk of ω
that crosses ±π wraps to the other sign.  ``Simulation.wrapped`` flags the trajectories where a bounded
coordinate of the truth model (``bounds`` in its definition) jumps by more than its bound.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..core.common import COMMON_NAMES
from ..core.registry import DEFAULT_SPACE, SPACES, get_measurement, get_model, models_of

__all__ = ["Simulation", "simulate", "truth_models", "COMMON_NAMES"]


def truth_models(space: str = DEFAULT_SPACE) -> tuple:
    """Registry models of ``space`` that can be a simulation truth (their physical state is the space's common state:
    in the plane SE(2)×SE(2) and SE(2)×R³, in 3-D SE(3)×R⁶)."""
    common = SPACES[space]["common_names"]
    return tuple(name for name, spec in models_of(space).items() if spec.state_names == common)


@dataclass
class Simulation:
    truth: np.ndarray  # (B, K + 1, n_common) common physical states, truth[:, 0] the initial state
    z: np.ndarray  # (B, K, m) measurements of truth[:, 1:]
    dt: float
    wrapped: np.ndarray  # (B,) bool: a bounded coordinate of the truth wrapped (e.g. ω at ±π)
    measurement: str = "position"


def simulate(
    x0,
    *,
    dt: float,
    steps: int,
    sigma_v: float,
    sigma_w: float,
    meas_std,
    truth: str = "se2se2",
    measurement: str = "position",
    std_normal_process: np.ndarray | None = None,
    std_normal_meas: np.ndarray | None = None,
    rng: np.random.Generator | None = None,
) -> Simulation:
    """Simulate B = len(x0) trajectories of ``steps`` steps with their measurements.

    ``meas_std``: one std (position) or (σ_x, σ_y, σ_θ) (pose). The standard-normal draws can be passed
    in (shapes (B, steps, q) for the truth's q noise inputs and (B, steps, m)) so that several noise
    levels share common random numbers; otherwise they are drawn from ``rng``.
    """
    spec = get_model(truth)
    if truth not in truth_models(spec.space):
        raise ValueError(f"truth: unknown truth model {truth!r}; choose one of {', '.join(truth_models())}")
    meas = spec.measurement(measurement)
    x0 = np.ascontiguousarray(np.atleast_2d(np.asarray(x0, dtype=float)))
    spec.check_state("x0", x0)
    B = x0.shape[0]
    q = len(spec.noise_inputs)
    rng = rng if rng is not None else np.random.default_rng()
    u = std_normal_process if std_normal_process is not None else rng.standard_normal((B, steps, q))
    m = std_normal_meas if std_normal_meas is not None else rng.standard_normal((B, steps, meas.dim))
    stds = np.asarray(spec.matched_accel_std(sigma_v, sigma_w), dtype=float)[list(spec.noise_inputs)]
    noise = np.ascontiguousarray(u[..., :q] * stds)
    dts = np.full((B, steps), float(dt))
    out = np.empty((B, steps + 1, spec.n))
    spec.kernels.simulate_batch(x0, dts, noise, out)
    r = np.broadcast_to(np.asarray(meas_std, dtype=float), (meas.dim,))
    mn = np.ascontiguousarray((m[..., : meas.dim] * r).reshape(-1, meas.dim))
    z = np.empty((B * steps, meas.dim))
    spec.kernel("measure_batch", measurement)(np.ascontiguousarray(out[:, 1:].reshape(-1, spec.n)), mn, z)
    wrapped = np.zeros(B, bool)
    for idx, bound in spec.bounds.items():
        wrapped |= np.any(spec.bounded_norm(np.diff(out, axis=1), idx) > bound, axis=1)
    return Simulation(out, z.reshape(B, steps, meas.dim), float(dt), wrapped, measurement)


def measurement_noise(measurement: str, meas_std: float, heading_std: float) -> tuple:
    """The noise stds of a measurement model from a position std and a heading std."""
    return get_measurement(measurement).stds(meas_std, heading_std)
