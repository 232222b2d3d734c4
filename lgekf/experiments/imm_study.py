"""The IMM as one more "filter" of the Monte Carlo study (``lgekf study --filters ...,imm``).

The IMM's modes get the study's matched process noise of their model at each σ_ω (times the study's
``--noise-scale`` of that model and the mode's named level factor: ``se2r3:calm`` is 0.2 × matched), or the
stds given in the mode (``se2r3:0.1/0.1/0.5``, used as given at every σ_ω); they start from the same initial
estimate as every filter (common coordinates, covariance P0_phys); common random numbers as for the filters.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..estimators.imm import NOISE_LEVELS, Mode, imm_batch, parse_modes
from .metrics import position_rmse

__all__ = ["IMM_FILTER", "ImmStudyOptions", "DEFAULT_STUDY_MODES", "DEFAULT_STUDY_SWITCH", "imm_study_rmse"]

IMM_FILTER = "imm"
#: the study's default modes (chosen by measurement, see README "The IMM in the study")
DEFAULT_STUDY_MODES = "cv,se2r3"
#: the study's default probability of leaving a mode per step (measured: 0.05 leaves the IMM 8 % behind CV at
#: σ_ω = 0, 0.002 2.8 %; see README)
DEFAULT_STUDY_SWITCH = 0.002


@dataclass(frozen=True)
class ImmStudyOptions:
    """The IMM of the study: its modes (``parse_modes`` syntax) and the probability of leaving a mode per step."""

    modes: str = DEFAULT_STUDY_MODES
    switch: float = DEFAULT_STUDY_SWITCH

    def validate(self) -> None:
        from ..estimators.imm import transition_matrix

        transition_matrix(len(parse_modes(self.modes)), self.switch)


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


def imm_study_rmse(cfg, opts: ImmStudyOptions, sim, sigma_w: float, est0: np.ndarray, P0_phys: np.ndarray,
                   pos: np.ndarray) -> np.ndarray:
    """Per-trajectory position RMSE (B,) of the study's IMM on one σ_ω's simulation."""
    modes = study_modes(cfg, opts, sigma_w)
    est, _ = imm_batch(sim.z if cfg.measurement != "position" else np.ascontiguousarray(sim.z[..., :2]), modes, opts.switch,
                       dt=cfg.dt, meas_std=cfg.meas_noise(cfg.measurement), x0=est0, P0=P0_phys, measurement=cfg.measurement)
    return position_rmse(est, pos)


def imm_options_from_args(modes: str | None, switch: float | None) -> ImmStudyOptions:
    """The study's IMM options from ``--imm-modes`` / ``--imm-switch`` (None: the defaults), validated."""
    opts = ImmStudyOptions(DEFAULT_STUDY_MODES if modes is None else modes,
                           DEFAULT_STUDY_SWITCH if switch is None else switch)
    opts.validate()
    return opts
