"""`lgekf track --model imm`: the IMM as an estimator of ``lgekf track``'s pipeline (``ImmTrack``; the tracking is
``lgekf.apps.track_imm``)."""

from __future__ import annotations

import sys

from ..apps.track_imm import ImmTrackOptions, imm_noise, tune_imm_classes, write_imm
from ..apps.warmup import imm_compile_seconds
from ..core.registry import BASE_MEASUREMENT
from .alarms import divergence_warnings, smooth_failure_warnings, warn_misfit
from .track_options import check_imm_options
from .track_parquet import is_parquet
from .track_pipeline import SPACE_HINTS, SPACE_WORDS, TrackEstimator, input_space
from ..core.registry import DEFAULT_SPACE, SPACES, models_of, space_of_positions
from ..estimators.imm.estimator import parse_modes, space_of_modes

__all__ = ["ImmTrack", "check_imm_options", "imm_modes_line"]


def imm_modes_line(modes) -> str:
    """The modes and their noise, for the stderr lines (``MODE (stds), ...``)."""
    return ", ".join(f"{m.name} ({','.join(f'{v:.3g}' for v in m.accel_std)})" for m in modes)


class ImmTrack(TrackEstimator):
    """The estimator of ``lgekf track --model imm`` in the pipeline of ``lgekf.cli.track.cmd_track``: an IMM of
    ``--imm-modes``, its modes' noise from the data per class of objects (or ``--tune``), the divergence monitor on the
    combined estimate, ``--smooth``."""

    def __init__(self, a, say):
        super().__init__(a, say)
        self.opts = ImmTrackOptions(a.imm_modes, a.imm_switch, self._modes_space(a))
        self.models = ["imm"]  # one output file

    @staticmethod
    def _modes_space(a) -> str:
        """The space the IMM is set up for before its input is looked at: that of the given modes, else the plane
        (``check`` then takes the input's, from its header, and ``adopt_space`` the one of the rows read)."""
        return space_of_modes(parse_modes(a.imm_modes)) if a.imm_modes is not None else DEFAULT_SPACE

    def adopt_space(self, meas) -> None:
        """After reading: the IMM of the input's space (its default modes, or ``--imm-modes``, which must be models of
        it); a space whose models the IMM does not mix, or ``--smooth`` outside the plane, is one line."""
        space = space_of_positions(meas.z.shape[1])
        if not SPACES[space]["mixes"]:
            raise ValueError(f"--model imm: the IMM does not mix the models of {SPACE_WORDS[space]}; use --model "
                             f"{', '.join(models_of(space))}")
        if space != self.opts.space:
            self.opts = ImmTrackOptions(self.a.imm_modes, self.a.imm_switch, space)
        if space != DEFAULT_SPACE and getattr(self.a, "smooth", False):  # the IMM smoother is the plane's (yet)
            raise ValueError(f"--model imm: --smooth (the IMM smoother) runs in the plane only (yet); the input has "
                             f"{SPACE_HINTS[space]}")

    def check(self) -> None:
        """The IMM's own argument errors (the shared ones: ``lgekf.cli.track.check_track_arguments``)."""
        a = self.a
        unsupported = [(a.accel_std, "--accel-std (give the modes' noise in --imm-modes, e.g. se2r3:0.2/0.2/0.5)"),
                       (a.measure != BASE_MEASUREMENT, f"--measure {a.measure}"), (a.full_cov, "--full-cov"),
                       (getattr(a, "workers", None) or getattr(a, "scheduler", None), "--workers/--scheduler"),
                       (a.use_heading, "--use-heading")]
        for given, name in unsupported:
            if given:
                raise ValueError(f"--model imm: {name} is not supported")
        if is_parquet(a.input) or is_parquet(a.output):
            raise ValueError("--model imm: Parquet input or output is not supported (yet); use CSV")
        space = input_space(a)  # from the header (None from stdin: adopt_space decides after reading)
        if space is not None and space != self.opts.space:
            self.opts = ImmTrackOptions(a.imm_modes, a.imm_switch, space)

    def compile_seconds(self):
        """The compile notice's estimate (``lgekf.apps.warmup.imm_compile_seconds``): the IMM compiles much more
        than one model does."""
        return imm_compile_seconds(bool(getattr(self.a, "tune", False)), bool(getattr(self.a, "smooth", False)),
                                   self.opts.space)

    def plan(self, meas, starts, monitor) -> None:
        """The IMM's noise: from the data per class of objects, or ``--tune``'s fit."""
        a, say, opts = self.a, self.say, self.opts
        if getattr(a, "tune", False):  # each class of objects learned on its own objects
            self.classes, found, summaries = tune_imm_classes(meas, starts, opts, a.meas_std, a.omega_std, monitor,
                                                              say=say, method=getattr(a, "tune_method", "lbfgs"))
            if len(found.plans) > 1:
                say(found.describe(meas.labels))
            for c, (summary, (o, r)) in enumerate(zip(summaries, self.classes.noise)):
                head = f"class {c + 1}: " if len(found.plans) > 1 else ""
                say(summary)
                say(f"{head}imm: modes {imm_modes_line(o.modes)}; switch {o.switch:g} per step; meas-std {r:.3g} m")
            warn_misfit(a.meas_std, meas, starts)
        else:
            self.classes, found = imm_noise(meas, starts, opts, a.meas_std, a.omega_std, monitor)
            if len(found.plans) > 1:
                say(found.describe(meas.labels))
            for c, ((o, r), plan) in enumerate(zip(self.classes.noise, found.plans)):
                head = f"class {c + 1}: " if len(found.plans) > 1 else ""
                if plan.estimated:
                    say(head + plan.describe())
                say(f"{head}imm: modes {imm_modes_line(o.modes)}; switch {o.switch:g} per step; meas-std {r:.3g} m "
                    f"({'given' if a.meas_std is not None else plan.meas_source})")
            warn_misfit(a.meas_std, meas, starts)
        if getattr(a, "smooth", False):
            say("imm: smoothed columns after flag")

    def write(self, handles, meas, starts, monitor, bar) -> list:
        res = write_imm(handles[0], meas, starts, self.classes, self.a.omega_std, self.a.precision, bar,
                        smooth=getattr(self.a, "smooth", False), monitor=monitor)
        flagged = int((res.flag & 1).sum())
        lines = divergence_warnings("imm", meas, res.alarms, flagged, statistic="residual²/r²")
        for line in lines + smooth_failure_warnings("imm", meas, res.smooth_failed, starts):
            print(f"lgekf track: warning: {line}", file=sys.stderr)
        return [("imm", f", {flagged} rows flagged" if flagged else "")]
