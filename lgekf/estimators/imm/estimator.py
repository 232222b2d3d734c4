"""Interacting multiple model (IMM) estimator whose modes are registry models with their own noise levels.

Two kinds (chosen automatically from the modes, never from a model's name):

* **on one group**: every mode is the same model with different process noise (e.g. SE(2)×R³ calm and
  manoeuvring); the mode Gaussians are mixed on the group (μ ← μ·exp(Σ wᵢ log(μ⁻¹μᵢ)), covariances
  transported with Φ(dᵢ)⁻¹);
* **across models** (e.g. CV, CTRV and an LG model): mixed in the common physical coordinates
  c = (x, y, θ, v_x, v_y, ω) through the generated conversions; components a model lacks (CV: ω) are
  taken from the receiving mode itself.

The modes are models of one space: in 3-D space (cv3, ct3, se3r6, se3se3) c = (x, y, z, roll, pitch, yaw, v_x,
v_y, v_z, ω_x, ω_y, ω_z) and the loop is the space's own (``lgekf.core.registry.imm_module``: ``generated/imm_3d.py``;
``generated/imm.py`` in the plane), found from the modes' space; "position" means the space's position measurement.

The mathematics and the exact Jacobians are in :mod:`lgekf.estimators.imm.kernels` (the numba loop).
The combined estimate ``x`` is always in the common coordinates, with its covariance ``P``; ``mu`` holds
the mode probabilities. The cycle is the standard IMM (Blom and Bar-Shalom 1988): interaction (mixing),
mode-matched filtering (the models' own fused LG-EKF kernels), mode probability update from the innovation
likelihoods N(ν; 0, ℋPℋᵀ + R), combination.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from ...core.batch import measurements_array, step_lengths
from ...core.common import covariance_from_common, state_from_common
from ...core.covariance import pack
from ...core.filters import measurement_std
from ...core.registry import ALL_MODELS, DEFAULT_SPACE, SPACES, dispatch_module, get_model, imm_module, measurement_in
from ...core.validate import as_float_array, positive_scalar, positive_vector, spd_matrix

__all__ = [
    "Mode", "IMM", "imm_batch", "parse_modes", "transition_matrix", "NOISE_LEVELS", "DEFAULT_SWITCH", "DEFAULT_MODES",
    "default_modes", "space_of_modes",
]

#: named noise levels of a mode, as factors of the model's ``default_accel_std``
NOISE_LEVELS = {"calm": 0.2, "default": 1.0, "manoeuvre": 4.0, "maneuver": 4.0}
#: default probability of leaving a mode per step (the transition matrix's off-diagonal mass)
DEFAULT_SWITCH = 0.05
def default_modes(space: str) -> str:
    """The modes of ``lgekf track --model imm`` and ``lgekf evaluate --imm`` in ``space`` by default (the space's
    definition, ``derive.space.Space.default_imm_modes``; why: docs/imm.md, docs/space3d.md)."""
    return SPACES[space]["imm_modes"]


#: the modes of ``lgekf track --model imm``, ``lgekf evaluate --imm`` and the multi-target tracker's IMM by default in
#: the plane: CV and a calm and a manoeuvring SE(2)×R³ (measured on the real-data evaluation against
#: se2r3:calm,se2r3:manoeuvre and cv,se2r3, see docs/imm.md)
DEFAULT_MODES = default_modes(DEFAULT_SPACE)
#: below this speed (m/s) the conversions' Jacobians are evaluated at this speed (singular at 0)
SPEED_FLOOR = 1e-9


@dataclass(frozen=True)
class Mode:
    """One mode of an IMM: a registry model and its process-noise stds (``accel_std``)."""

    model: str
    accel_std: tuple
    label: str = ""

    @property
    def name(self) -> str:
        """How the mode is shown (``model:label`` or the model)."""
        return f"{self.model}:{self.label}" if self.label else self.model


def make_mode(model: str, accel_std=None, label: str = "") -> Mode:
    """A validated :class:`Mode` (default noise: the model's ``default_accel_std``)."""
    spec = get_model(model)
    q = spec.default_accel_std if accel_std is None else accel_std
    q = positive_vector(f"accel_std of mode {model}", q, len(spec.noise_names))
    return Mode(model, tuple(float(v) for v in q), label)


def parse_modes(text: str) -> list[Mode]:
    """Modes from ``MODEL[:LEVEL],...``: LEVEL a named level (calm, default, manoeuvre: × 0.2, 1, 4 of the
    model's default noise) or the noise stds themselves separated by ``/`` (``se2r3:0.1/0.1/0.5``).

    Raises
    ------
    ValueError
        One line naming the bad entry.
    """
    modes = []
    items = [t.strip() for t in str(text).split(",")]
    if not items or any(not t for t in items):
        raise ValueError(f"imm-modes: expected MODEL[:LEVEL],... (e.g. se2r3:calm,se2r3:manoeuvre), got {text!r}")
    for item in items:
        model, _, level = item.partition(":")
        if model not in ALL_MODELS:
            raise ValueError(f"imm-modes: unknown model {model!r} in {item!r}; choose one of {', '.join(ALL_MODELS)}")
        spec = get_model(model)
        if not level:
            modes.append(make_mode(model))
        elif level in NOISE_LEVELS:
            modes.append(make_mode(model, [NOISE_LEVELS[level] * v for v in spec.default_accel_std], level))
        else:
            try:
                q = [float(v) for v in level.split("/")]
            except ValueError:
                raise ValueError(f"imm-modes: {item!r}: level must be one of {', '.join(NOISE_LEVELS)} or "
                                 f"{len(spec.noise_names)} numbers a/b/... ({', '.join(spec.noise_names)})") from None
            if len(q) != len(spec.noise_names) or not all(math.isfinite(v) and v >= 0 for v in q):
                raise ValueError(f"imm-modes: {item!r}: expected {len(spec.noise_names)} non-negative numbers "
                                 f"({'/'.join(spec.noise_names)})")
            modes.append(make_mode(model, q, level))
    return modes


def transition_matrix(M: int, switch: float = DEFAULT_SWITCH) -> np.ndarray:
    """PI[i, j] = P(mode j | mode i): 1 − switch on the diagonal, switch/(M − 1) elsewhere (M > 1).

    Parameters
    ----------
    M : int
        Number of modes.
    switch : float
        Probability of leaving the current mode per step, in [0, 1).

    Returns
    -------
    ndarray, (M, M)
    """
    if not (0.0 <= switch < 1.0) or not math.isfinite(switch):
        raise ValueError(f"imm-switch: must be in [0, 1), got {switch}")
    if M == 1:
        return np.ones((1, 1))
    PI = np.full((M, M), switch / (M - 1))
    np.fill_diagonal(PI, 1.0 - switch)
    return PI


def _check_transition(PI, M: int) -> np.ndarray:
    PI = as_float_array("transition", PI)
    if PI.shape != (M, M):
        raise ValueError(f"transition: expected ({M}, {M}) for {M} modes, got {PI.shape}")
    if np.any(PI < 0) or not np.allclose(PI.sum(axis=1), 1.0, atol=1e-9):
        raise ValueError("transition: rows must be probabilities summing to 1")
    return np.ascontiguousarray(PI)


def space_of_modes(modes) -> str:
    """The space of the modes' models (``Mode`` list); a ValueError (one line) when they are of different spaces or of
    a space whose models the IMM does not mix."""
    spaces = {get_model(m.model).space for m in modes}
    if len(spaces) != 1:
        raise ValueError("imm-modes: the modes are models of different spaces ("
                         + ", ".join(f"{m.name}: {get_model(m.model).space}" for m in modes)
                         + "); an IMM mixes the models of one space")
    space = spaces.pop()
    if not SPACES[space]["mixes"]:
        raise ValueError(f"imm-modes: the IMM does not mix the models of space {space!r}")
    return space


def _modes(modes) -> list[Mode]:
    if isinstance(modes, str):
        return parse_modes(modes)
    out = []
    for m in modes:
        if isinstance(m, Mode):
            out.append(make_mode(m.model, m.accel_std, m.label))
        elif isinstance(m, str):
            out.extend(parse_modes(m))
        else:
            model, q = m
            out.append(make_mode(model, q))
    if not out:
        raise ValueError("modes: give at least one mode")
    return out


class _Setup:
    """The arrays the numba loop needs for a list of modes (validated)."""

    def __init__(self, modes, transition, meas_std, measurement, mu0):
        self.modes = _modes(modes)
        M = len(self.modes)
        self.M = M
        self.space = space_of_modes(self.modes)
        # the generated loop and model chains of the modes' space (their model indices); "position" means the
        # space's own position measurement (position3 in 3-D), as for lgekf track
        self.loop, D = imm_module(self.space), dispatch_module(self.space)
        self.nc = len(SPACES[self.space]["common_names"])
        self.velocity = list(SPACES[self.space]["common_velocity"])
        measurement = measurement_in(self.space, measurement)
        self.measurement = measurement
        self.models = np.array([D.MODEL_NAMES.index(m.model) for m in self.modes], dtype=np.int64)
        for m in self.modes:
            get_model(m.model).measurement(measurement)
        self.r = np.ascontiguousarray(measurement_std(get_model(self.modes[0].model), measurement, meas_std), dtype=float)
        from .kernels import measurement_index

        self.meas = measurement_index(measurement)  # the generated IMM kernels' measurement argument
        nq = max(len(m.accel_std) for m in self.modes)
        self.Q = np.zeros((M, nq))
        for j, m in enumerate(self.modes):
            self.Q[j, :len(m.accel_std)] = m.accel_std
        PI = transition_matrix(M) if transition is None else transition
        if np.ndim(PI) == 0:
            PI = transition_matrix(M, float(PI))
        self.PI = _check_transition(PI, M)
        mu0 = np.full(M, 1.0 / M) if mu0 is None else positive_vector("mu0", mu0, M)
        if not mu0.sum() > 0:
            raise ValueError("mu0: mode probabilities must not all be zero")
        self.mu0 = np.ascontiguousarray(mu0 / mu0.sum(), dtype=float)
        self.same_group = len({m.model for m in self.modes}) == 1
        self.L = int(max(D.N_INTERNAL[i] for i in self.models))
        self.NP = int(max(D.N_TANGENT[i] * (D.N_TANGENT[i] + 1) // 2 for i in self.models))

    def initial(self, c0: np.ndarray, P0c: np.ndarray):
        """(S0 (B, M, L), P0 (B, M, NP)) from common c0 (B, n_c) and P0c (B, n_c, n_c)."""
        B = c0.shape[0]
        S0 = np.zeros((B, self.M, self.L))
        P0 = np.zeros((B, self.M, self.NP))
        for j, m in enumerate(self.modes):
            spec = get_model(m.model)
            x = state_from_common(m.model, c0)
            spec.check_state("c0", x)
            # a heading-of-motion coordinate (CTRV's ψ) has a singular Jacobian at speed 0: evaluate it just off
            # zero, as lgekf track does
            cj = c0.copy()
            slow = np.linalg.norm(cj[:, self.velocity], axis=1) < SPEED_FLOOR
            cj[slow, self.velocity[0]] = SPEED_FLOOR
            P = covariance_from_common(m.model, cj, P0c) + 1e-12 * np.eye(spec.n)
            for b in range(B):
                s = spec.kernels.state_from_physical(x[b])
                S0[b, j, :s.shape[0]] = s
            P0[:, j, :spec.n_packed] = pack(P)
        return S0, P0


def _common_inputs(c0, P0c, space: str = DEFAULT_SPACE, B=None):
    nc = len(SPACES[space]["common_names"])
    c0 = as_float_array("c0", c0)
    if c0.ndim == 1:
        c0 = c0[None]
    if c0.ndim != 2 or c0.shape[1] != nc or (B is not None and c0.shape[0] != B):
        raise ValueError(f"c0: expected common coordinates ({', '.join(SPACES[space]['common_names'])}) of shape ({nc},) or "
                         f"({B or 'B'}, {nc}), got {c0.shape}")
    P0c = spd_matrix("P0", P0c, nc, batch=True)
    P0c = np.broadcast_to(P0c, (c0.shape[0], nc, nc))
    return np.ascontiguousarray(c0), np.ascontiguousarray(P0c)


class IMM:
    """An IMM for one object, FilterPy-style: ``predict()``, ``update(z)``, ``x``, ``P``, ``mu``.

    Parameters
    ----------
    modes : list of Mode, (model, accel_std) pairs or str
        The modes, e.g. ``"se2r3:calm,se2r3:manoeuvre"`` or ``[("cv", [0.1]), ("se2r3", [0.1, 0.1, 1.0])]``.
    transition : float or array_like, optional
        The probability of leaving a mode per step (default ``DEFAULT_SWITCH``) or the (M, M) matrix
        PI[i, j] = P(mode j | mode i).
    dt : float
        Default step length in s.
    meas_std : float or array_like
        Measurement-noise std(s), as for the filters.
    x0 : array_like, (n_c,)
        Initial estimate in the common coordinates of the modes' space: (x, y, θ, v_x, v_y, ω) in the plane,
        (x, y, z, roll, pitch, yaw, v_x, v_y, v_z, ω_x, ω_y, ω_z) in 3-D; body-frame velocity.
    P0 : array_like, (n_c, n_c)
        Its covariance; each mode starts from it converted to its own coordinates.
    measurement : str
        A measurement of the modes' space ("position", "pose"; in 3-D "position3", "pose3"; "position" means the
        space's own position measurement).
    mu0 : array_like, optional
        Initial mode probabilities (default uniform).

    Attributes
    ----------
    x : ndarray, (n_c,)
        Combined estimate in the common coordinates.
    P : ndarray, (n_c, n_c)
        Its covariance.
    mu : ndarray, (M,)
        Mode probabilities.
    nis : ndarray, (M,)
        Each mode's NIS of the last update.
    """

    def __init__(self, modes, transition=None, *, dt: float, meas_std, x0: ArrayLike, P0: ArrayLike,
                 measurement: str = "position", mu0=None):
        self._set = _Setup(modes, transition, meas_std, measurement, mu0)
        self.dt = positive_scalar("dt", dt)
        c0, P0c = _common_inputs(x0, P0, self._set.space, 1)
        S0, Pp0 = self._set.initial(c0, P0c)
        self._S = S0[0]
        self._p = Pp0[0]
        self._mu = self._set.mu0.copy()
        self._m = get_model(self._set.modes[0].model).measurement(self._set.measurement).dim
        self.nis = np.full(self._set.M, np.nan)
        self.log_likelihood = float("nan")
        self._ws = self._set.loop.workspace(self._set.M)

    @property
    def modes(self) -> list:
        """The modes (:class:`Mode`)."""
        return list(self._set.modes)

    @property
    def transition(self) -> np.ndarray:
        """The transition matrix PI (M, M)."""
        return self._set.PI.copy()

    def predict(self, dt: float | None = None) -> None:
        """Interaction (mixing) and every mode's prediction by ``dt`` (default: the IMM's ``dt``)."""
        step = self.dt if dt is None else positive_scalar("dt", dt)
        s = self._set
        s.loop.imm_predict(s.models, self._S, self._p, self._mu, s.PI, s.Q, step, s.same_group, self._ws)

    def update(self, z: ArrayLike) -> float:
        """Every mode's update with z and the new mode probabilities; returns log p(z | past)."""
        z = as_float_array("z", z, (self._m,))
        s = self._set
        self.log_likelihood = float(s.loop.imm_update(s.models, self._S, self._p, self._mu, s.r, z, s.meas, self.nis,
                                               self._ws))
        return self.log_likelihood

    def _combined(self):
        s = self._set
        c = np.empty(s.nc)
        P = np.empty((s.nc, s.nc))
        s.loop.combined_common(s.models, self._S, self._p, self._mu, s.same_group, c, P, self._ws)
        return c, P

    @property
    def x(self) -> np.ndarray:
        return self._combined()[0]

    @property
    def P(self) -> np.ndarray:
        return self._combined()[1]

    @property
    def mu(self) -> np.ndarray:
        return self._mu.copy()

    def mode_state(self, j: int) -> tuple[np.ndarray, np.ndarray]:
        """Mode j's (x, P) in its own model's physical state and tangent coordinates."""
        from ...core.covariance import unpack

        spec = get_model(self._set.modes[j].model)
        s = self._S[j, :len(spec.internal_names)].copy()
        return np.asarray(spec.kernels.state_to_physical(s)), unpack(self._p[j, :spec.n_packed], spec.n)

    def __repr__(self) -> str:
        probs = ", ".join(f"{m.name}={p:.3f}" for m, p in zip(self._set.modes, self._mu))
        return f"IMM({probs})"


def _batch_inputs(z, modes, transition, dt, meas_std, x0, P0, measurement, mu0):
    """The checked inputs of a batch IMM run (``imm_batch``, ``lgekf.estimators.imm.smoother``): the set-up
    ``_Setup``, z (B, K, m), dts (B, K) and each trajectory's initial mode states and packed covariances."""
    s = _Setup(modes, transition, meas_std, measurement, mu0)
    z = measurements_array(z, get_model(s.modes[0].model).measurement(s.measurement).dim)
    B, K = z.shape[:2]
    dts = step_lengths(dt, B, K)
    c0, P0c = _common_inputs(x0, P0, s.space)
    if c0.shape[0] == 1 and B > 1:
        c0 = np.ascontiguousarray(np.broadcast_to(c0, (B, s.nc)))
        P0c = np.ascontiguousarray(np.broadcast_to(P0c, (B, s.nc, s.nc)))
    if c0.shape[0] != B:
        raise ValueError(f"x0: expected {B} initial estimates, got {c0.shape[0]}")
    S0, Pp0 = s.initial(c0, P0c)
    return s, z, dts, S0, Pp0


def imm_batch(z: ArrayLike, modes, transition=None, *, dt, meas_std, x0: ArrayLike, P0: ArrayLike,
              measurement: str = "position", mu0=None, return_cov: bool = False):
    """Run an IMM over many trajectories, entirely in numba (prange over the batch).

    Parameters
    ----------
    z : array_like, (B, K, m)
        Measurements (a NaN row: missed detection).
    modes, transition, meas_std, measurement, mu0
        As for :class:`IMM`.
    dt : float or array_like
        A number, (K,) or (B, K).
    x0 : array_like, (B, n_c) or (n_c,)
        Initial estimates in the common coordinates of the modes' space (n_c = 6 in the plane: x, y, θ, v_x, v_y,
        ω; 12 in 3-D).
    P0 : array_like, (n_c, n_c) or (B, n_c, n_c)
        Their covariance.
    return_cov : bool
        Also return the combined covariances (B, K, n_c, n_c).

    Returns
    -------
    x : ndarray, (B, K, n_c)
        Combined posterior estimates in the common coordinates.
    mu : ndarray, (B, K, M)
        Mode probabilities after each update.
    P : ndarray, (B, K, n_c, n_c)
        Only with ``return_cov``.
    """
    from .kernels import run_batch

    s, z, dts, S0, Pp0 = _batch_inputs(z, modes, transition, dt, meas_std, x0, P0, measurement, mu0)
    B, K = z.shape[:2]
    out_c = np.empty((B, K, s.nc))
    out_P = np.empty((B, K if return_cov else 0, s.nc, s.nc))
    out_mu = np.empty((B, K, s.M))
    run = run_batch(s.measurement)  # the generated loop of the measurement: compiles its kernels only
    run(s.models, S0, Pp0, s.mu0, s.PI, s.Q, s.r, z, dts, s.same_group, out_c, out_P, out_mu)
    return (out_c, out_mu, out_P) if return_cov else (out_c, out_mu)
