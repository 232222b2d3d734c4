"""The IMM as one more "filter" of the Monte Carlo study (``lgekf study --filters ...,imm``).

The IMM's modes get the study's matched process noise of their model at each σ_ω (times the study's
``--noise-scale`` of that model and the mode's named level factor: ``se2r3:calm`` is 0.2 × matched), or the
stds given in the mode (``se2r3:0.1/0.1/0.5``, used as given at every σ_ω); they start from the same initial
estimate as every filter (common coordinates, covariance P0_phys); common random numbers as for the filters.

The IMM's Markov chain (the transition matrix and the initial mode probabilities; nothing in the truth defines
them) is, by default, **learned at each σ_ω** like the noise is matched: :func:`lgekf.estimators.imm.chain.learn_chain`
fits every transition probability by the IMM's own likelihood on ``train_trajectories`` independent training
trajectories simulated with the study's protocol at that σ_ω (their own random numbers, from the seed sequence
[seed, 1]; common to every σ_ω), each started like the study's filters; the IMM then starts from the fitted
chain's stationary distribution. Only the training draws are used for the fit, never the scored ones. With
``switch`` given the chain is the symmetric ``transition_matrix(M, switch)`` with uniform initial probabilities
(the study's IMM before the fit; see docs/study.md, "The IMM: best of both worlds?").
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..core.registry import DEFAULT_SPACE
from ..estimators.imm.estimator import NOISE_LEVELS, Mode, default_modes, imm_batch, parse_modes, space_of_modes
from .metrics import position_rmse

if TYPE_CHECKING:
    from ..estimators.imm.chain import ChainFit

__all__ = ["IMM_FILTER", "ImmStudyOptions", "DEFAULT_STUDY_MODES", "DEFAULT_STUDY_SWITCH", "DEFAULT_TRAIN_TRAJECTORIES",
           "imm_options_record", "imm_study_rmse", "study_chain", "training_draws"]

IMM_FILTER = "imm"
#: the study's default modes (chosen by measurement, see docs/study.md, "The IMM: best of both worlds?")
DEFAULT_STUDY_MODES = "cv,se2r3"
#: the study's fixed switching probability before the chain was learned (0.05 left the IMM 8 % behind CV at
#: σ_ω = 0, 0.002 2.8 %; README); the comparison of ``--imm-switch``
DEFAULT_STUDY_SWITCH = 0.002
#: training trajectories per σ_ω for the learned chain (measured: 100 and 200 give the same gaps, README)
DEFAULT_TRAIN_TRAJECTORIES = 100
#: the largest trajectories × steps per σ_ω of the study (the draws and the filters' estimates are held in memory;
#: the default study has 10⁴), scored (``StudyConfig.validate``) or the IMM's training draws
MAX_TRAJECTORY_STEPS = 10_000_000
#: the training draws come from the seed sequence [seed, TRAIN_STREAM] (the scored ones from [seed])
TRAIN_STREAM = 1


@dataclass(frozen=True)
class ImmStudyOptions:
    """The IMM of the study: its modes (``parse_modes`` syntax) and its chain: ``switch`` None (default) learns
    the transition matrix at each σ_ω on ``train_trajectories`` training trajectories (module docstring); a
    number is the fixed probability of leaving a mode per step (symmetric, uniform start)."""

    modes: str = DEFAULT_STUDY_MODES
    switch: float | None = None
    train_trajectories: int = DEFAULT_TRAIN_TRAJECTORIES

    def validate(self, steps: int | None = None) -> None:
        """Check the options; with the study's ``steps`` also the training draws' size of a learned chain.

        Parameters
        ----------
        steps : int, optional
            Measurements per trajectory: the training draws (``train_trajectories`` × ``steps``) must be at
            most ``MAX_TRAJECTORY_STEPS`` and give at least ``MIN_UPDATES_PER_PARAMETER`` counted steps
            per transition probability (M (M − 1) of them).

        Raises
        ------
        ValueError
            Bad modes or switch, fewer than 2 training trajectories, or training draws too few or too many.
        """
        from ..estimators.imm.estimator import transition_matrix
        from ..estimators.noise.tuning import MIN_UPDATES_PER_PARAMETER

        M = len(parse_modes(self.modes))
        if self.switch is not None:
            transition_matrix(M, self.switch)
            return
        if M < 2:
            return
        n = self.train_trajectories
        if isinstance(n, bool) or not isinstance(n, (int, float, np.integer, np.floating)) or not math.isfinite(n) \
                or int(n) != n or n < 2:
            raise ValueError(f"imm-train: need a whole number of at least 2 training trajectories, got {n}")
        if steps is None:
            return
        n, d = int(n), M * (M - 1)
        if n * steps > MAX_TRAJECTORY_STEPS:
            raise ValueError(f"imm-train: training trajectories × steps must be at most {MAX_TRAJECTORY_STEPS:,} "
                             f"(held in memory), got {n} × {steps}")
        if n * steps < MIN_UPDATES_PER_PARAMETER * d:
            raise ValueError(f"imm-train: {n} training trajectories × {steps} steps are too few to learn the {d} "
                             f"transition probabilities; need at least {MIN_UPDATES_PER_PARAMETER * d} steps")


def study_modes(cfg, opts: ImmStudyOptions, sigma_w: float) -> list[Mode]:
    """The modes with their process noise at σ_ω (module docstring)."""
    out = []
    for m in parse_modes(opts.modes):
        if m.label in NOISE_LEVELS or not m.label:
            k = NOISE_LEVELS.get(m.label, 1.0)
            q = tuple(k * v for v in cfg.filter_noise(m.model, sigma_w))
            out.append(Mode(m.model, q, m.label))
        else:
            out.append(m)
    return out


def training_draws(cfg, B: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The training trajectories' standard-normal draws, shaped as the study's own (``run_study``) but from the
    seed sequence [seed, TRAIN_STREAM].

    Parameters
    ----------
    cfg : lgekf.experiments.study.StudyConfig
        The study's protocol (seed, steps, truth, measurement).
    B : int
        Training trajectories.

    Returns
    -------
    u_proc : ndarray, (B, K, ≥3)
        Process-noise draws.
    u_meas : ndarray, (B, K, ≥2)
        Measurement-noise draws.
    u_init : ndarray, (B, n_c)
        Initial-error draws (one per common coordinate of the study's space).
    """
    from ..core.registry import get_model

    rng = np.random.default_rng([cfg.seed, TRAIN_STREAM])
    K = cfg.steps
    truth = get_model(cfg.truth)
    n_meas = truth.measurement(cfg.measurement).dim
    return (rng.standard_normal((B, K, max(3, len(truth.noise_inputs)))), rng.standard_normal((B, K, n_meas)),
            rng.standard_normal((B, len(cfg.init_std))))


def _measured(cfg, sim) -> np.ndarray:
    from ..core.registry import get_measurement

    return np.ascontiguousarray(sim.z[..., :get_measurement(cfg.measurement).dim])


def study_chain(cfg, opts: ImmStudyOptions, sigma_w: float) -> "ChainFit":
    """The study IMM's chain learned at σ_ω on the training draws (module docstring).

    Parameters
    ----------
    cfg : lgekf.experiments.study.StudyConfig
        The study's protocol.
    opts : ImmStudyOptions
        The IMM's modes and ``train_trajectories``.
    sigma_w : float
        The σ_ω of the truth and of the modes' matched noise.

    Returns
    -------
    lgekf.estimators.imm.chain.ChainFit
    """
    from ..estimators.imm.chain import learn_chain
    from .simulate import simulate

    B = int(opts.train_trajectories)
    u_proc, u_meas, u_init = training_draws(cfg, B)
    truth0 = np.tile(cfg.start, (B, 1))
    sim = simulate(truth0, dt=cfg.dt, steps=cfg.steps, sigma_v=cfg.sigma_v, sigma_w=sigma_w,
                   meas_std=cfg.meas_noise(cfg.measurement), truth=cfg.truth, measurement=cfg.measurement,
                   std_normal_process=u_proc, std_normal_meas=u_meas)
    return learn_chain(study_modes(cfg, opts, sigma_w), _measured(cfg, sim), dt=cfg.dt,
                       meas_std=cfg.meas_noise(cfg.measurement), x0=truth0 + u_init * np.asarray(cfg.init_std),
                       P0=np.diag(np.square(cfg.init_std)), measurement=cfg.measurement)


def imm_study_rmse(cfg, opts: ImmStudyOptions, sim, sigma_w: float, est0: np.ndarray, P0_phys: np.ndarray,
                   pos: np.ndarray, chains: list | None = None) -> np.ndarray:
    """Per-trajectory position RMSE (B,) of the study's IMM on one σ_ω's simulation; a learned chain is appended
    to ``chains`` (``{"sigma_w": ..., **ChainFit.to_dict()}``) when given."""
    modes = study_modes(cfg, opts, sigma_w)
    transition, mu0 = opts.switch, None
    if opts.switch is None and len(modes) > 1:
        fit = study_chain(cfg, opts, sigma_w)
        transition, mu0 = fit.transition, fit.mu0
        if chains is not None:
            chains.append({"sigma_w": float(sigma_w), **fit.to_dict()})
    est, _ = imm_batch(_measured(cfg, sim), modes, transition, dt=cfg.dt, meas_std=cfg.meas_noise(cfg.measurement),
                       x0=est0, P0=P0_phys, measurement=cfg.measurement, mu0=mu0)
    return position_rmse(est, pos, cfg.dim)


def imm_options_record(opts: ImmStudyOptions) -> dict:
    """The IMM's options as written to meta.json (``lgekf study``, ``lgekf sweep``).

    Parameters
    ----------
    opts : ImmStudyOptions

    Returns
    -------
    dict
        ``modes``, ``switch`` (None: the chain is learned) and, for a learned chain of two modes or more,
        ``train_trajectories``.
    """
    learned = opts.switch is None and len(parse_modes(opts.modes)) > 1
    return {"modes": opts.modes, "switch": opts.switch,
            **({"train_trajectories": int(opts.train_trajectories)} if learned else {})}


def study_default_modes(space: str) -> str:
    """The study's IMM modes by default in ``space``: ``DEFAULT_STUDY_MODES`` in the plane (measured on the paper's
    protocol, docs/study.md), else the space's own default modes (``default_modes``; docs/space3d.md)."""
    return DEFAULT_STUDY_MODES if space == DEFAULT_SPACE else default_modes(space)


def imm_options_from_args(modes: str | None, switch: float | None, train: int | None = None,
                          space: str = DEFAULT_SPACE) -> ImmStudyOptions:
    """The study's IMM options from ``--imm-modes`` / ``--imm-switch`` / ``--imm-train`` (None: the defaults of the
    study's ``space``; no switch: the chain is learned), validated."""
    if modes is not None and space_of_modes(parse_modes(modes)) != space:
        raise ValueError(f"imm-modes: {modes} are models of space {space_of_modes(parse_modes(modes))!r}, and the study "
                         f"runs in {space!r}")
    opts = ImmStudyOptions(study_default_modes(space) if modes is None else modes, switch,
                           DEFAULT_TRAIN_TRAJECTORIES if train is None else train)
    opts.validate()
    return opts
