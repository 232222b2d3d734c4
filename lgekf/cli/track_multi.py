"""`lgekf track DETECTIONS.csv --multi`: many objects from unlabelled detections in clutter, the estimator
``MultiTrack`` of `lgekf track`'s pipeline (``lgekf.cli.track_pipeline``: one clear error line per bad input,
all-or-nothing output). The tracking, the scans and the noise from the data are
``lgekf.apps.track_multi``; on stderr: the scan window, the noise and the clutter density when they come from the data (not with
--quiet), and, also with --quiet, warnings: a given --meas-std 2x or more off the data's estimate, no
confirmed track (one line saying why), a confirmed track near the default --max-speed."""

from __future__ import annotations

import sys

import numpy as np

from ..apps.track import DEFAULT_HEADING_STD, DEFAULT_MEAS_STD, default_model
from ..apps.track_multi import (
    AGREE, clutter_line, fastest_track_speed, fit_noise, multi_alarm_line, no_track_reason, scan_window_from_data, scans,
    volume_unit, write_multi,
)
from ..core.registry import ALL_MODELS, DEFAULT_SPACE, get_measurement, get_model, measurement_in, models_of, space_of_positions
from ..core.validate import positive_scalar
from ..estimators.multitarget.clutter import DEFAULT_CLUTTER_SOURCE, clutter_from_data
from ..estimators.multitarget.tracker import IMM_MODEL
from ..io.files import is_stdio
from ..io.cleaning import check_time_order, skipped_summary, sort_by_time
from ..io.readers import named_columns, parse_delimiter, read_measurements, skipping_nonfinite_rows
from ..io.units import to_seconds
from .track_options import DEFAULT_MAX_SPEED, SPEED_WARN_FRACTION, column_names
from .track_parquet import is_parquet
from .track_pipeline import SPACE_HINTS, SPACE_WORDS, TrackEstimator, check_time_unit, input_space
from .alarms import misfit_line  # the same rule and words as `lgekf track`

__all__ = ["MultiTrack", "read_multi_input"]


def _accel_std(items, model):
    """``--accel-std A,B,C`` (or ``MODEL=A,B,C`` naming the tracked model) -> the stds, None when not given;
    the number and sign of the values are checked by the tracker."""
    if not items:
        return None
    text = items[-1]
    if "=" in text:
        name, text = text.split("=", 1)
        if name.strip() != model:
            raise ValueError(f"--accel-std: {name.strip()!r} is not the tracked model ({model})")
    try:
        return tuple(float(v) for v in text.split(","))
    except ValueError:
        raise ValueError(f"--accel-std: expected comma-separated numbers, got {text!r}") from None


def _check_arguments(a, measure):
    """The multi-target options' errors before any reading (one line each, exit 2; --precision and the paths are
    the pipeline's, ``lgekf.cli.track.check_track_arguments``; the IMM's modes and their measurement: the tracker's);
    ``measure``: the measurement as the input's space measures it (``measurement_in``)."""
    if a.meas_std is not None:
        positive_scalar("meas-std", a.meas_std)
    if a.max_speed is not None:
        positive_scalar("max-speed", a.max_speed)
    if a.scan_window is not None:
        positive_scalar("scan-window", a.scan_window, allow_zero=True)
    if a.clutter is not None and a.clutter_density is not None:
        raise ValueError("--clutter: not with --clutter-density (a given density is used as it is)")
    if a.model == IMM_MODEL:
        if a.accel_std:
            raise ValueError("--multi --model imm: --accel-std is not supported (give the modes' noise in --imm-modes, "
                             "e.g. se2r3:0.2/0.2/0.5)")
        return None
    q = _accel_std(a.accel_std, a.model)
    get_model(a.model).measurement(measure)
    return q


def read_multi_input(a):
    """The detections of ``--multi``'s input in non-decreasing time: rows going back in time are refused unless
    ``--sort`` (then sorted, stable, with one line saying how many moved), rows with NaN/inf refused unless
    ``--skip-invalid`` (then dropped, one summary line): the rules of single-object tracking for a file of scans."""
    with skipping_nonfinite_rows(a.skip_invalid), named_columns(column_names(a)):
        meas = read_measurements(a.input, "csv", None, get_measurement(a.measure).has_angle, parse_delimiter(a.delimiter))
    check_time_unit(meas, a.time_unit)
    if a.sort:
        meas, moved = sort_by_time(meas)
        _warn(f"--sort: {moved} row{'s' if moved != 1 else ''} moved into time order")
    else:
        check_time_order(meas)
    for line in skipped_summary(meas):
        _warn(line)
    return meas


def _warn(text):
    print(f"lgekf track: warning: {text}", file=sys.stderr)


class MultiTrack(TrackEstimator):
    """The estimator of ``lgekf track --multi`` in the pipeline of ``lgekf.cli.track.cmd_track``: unlabelled detections
    read in time order (``read_multi_input``), grouped into scans; the measurement std, the process noise and the
    clutter density from the data (``lgekf.apps.track_multi.fit_noise``: tracking passes); every confirmed track under
    the divergence monitor (``lgekf.apps.multi_monitor``); one output of the confirmed tracks."""

    def __init__(self, a, say):
        super().__init__(a, say)
        self.model_given = a.model is not None
        self.models = [a.model]  # one output file

    def check(self) -> None:
        """Every argument error before any reading (one line each, exit 2); the tracker built once to check them. The
        space of the input (x, y or x, y, z: ``input_space``, from its header) selects the default model and the
        measurement; from stdin the space of ``--model`` (the plane without one) is assumed until the rows are read
        (``adopt_space``)."""
        a = self.a
        if is_parquet(a.input) or is_parquet(a.output):
            raise ValueError("--multi: Parquet input or output is not supported (yet); use CSV")
        guess = get_model(a.model).space if a.model in ALL_MODELS else DEFAULT_SPACE
        self.resolve(input_space(a) or guess)

    def resolve(self, space: str) -> None:
        """The model (``--model`` or the default of ``space``: ``default_model``), the measurement (``--measure`` as
        ``space`` measures it) and the tracker's arguments for an input of ``space``; a model of another space, or the
        IMM in a space whose models it does not mix (3-D, yet), is one error line."""
        a = self.a
        self.space = space
        if not self.model_given:
            a.model = default_model(space, a.measure)
        elif a.model == IMM_MODEL and space != DEFAULT_SPACE:  # the multi-target IMM bank is the plane's (yet)
            raise ValueError(f"--multi --model imm: the multi-target IMM runs in the plane only (yet), and the input has "
                             f"{SPACE_HINTS[space]}; choose one of {', '.join(models_of(space))}")
        elif a.model != IMM_MODEL and get_model(a.model).space != space:
            raise ValueError(f"--model {a.model}: a model of {SPACE_WORDS[get_model(a.model).space]}, and the input has "
                             f"{SPACE_HINTS[space]}; the models that fit: {', '.join(models_of(space))}")
        self.models = [a.model]
        own = get_measurement(a.measure).space
        if own not in (space, DEFAULT_SPACE):  # position3 / pose3 named on a file of 2-D positions
            raise ValueError(f"--measure {a.measure}: observes {SPACE_WORDS[own]}, and the input has {SPACE_HINTS[space]}")
        self.measure = measurement_in(space, a.measure)
        self.q = _check_arguments(a, self.measure)
        self.max_speed = DEFAULT_MAX_SPEED if a.max_speed is None else a.max_speed
        self.heading_std = DEFAULT_HEADING_STD if a.heading_std is None else a.heading_std
        self.args = dict(model=a.model, association=a.association, detection_prob=a.detection_prob, measurement=self.measure,
                         gate_prob=a.gate_prob, survival_prob=a.survival_prob, birth_existence=a.birth_existence,
                         initiation=a.initiation, birth_density=a.birth_density,
                         confirm_existence=a.confirm_existence, delete_existence=a.delete_existence,
                         max_speed=self.max_speed, omega_std=a.omega_std,
                         max_hypotheses=a.max_hypotheses, hypothesis_prune=a.hypothesis_prune,
                         clutter_density=1.0 if a.clutter_density is None else a.clutter_density)
        self.noise_fixed = self.q is not None  # the process noise is not for the data to set
        if a.model == IMM_MODEL:
            from ..apps.track_imm import ImmTrackOptions

            self.args.update(imm_modes=a.imm_modes, imm_switch=a.imm_switch)
            self.noise_fixed = not ImmTrackOptions(a.imm_modes, a.imm_switch).tunable_models()  # every mode's in numbers
        from ..estimators.multitarget.tracker import MultiTargetTracker

        r = DEFAULT_MEAS_STD if a.meas_std is None else a.meas_std
        MultiTargetTracker(**self.args, accel_std=self.q, meas_std=get_measurement(self.measure).stds(r, self.heading_std))

    def adopt_space(self, meas) -> None:
        """After reading: the input's space from its positions (z (N, d)); an input whose space its header did not say
        (stdin) re-resolves the model and the measurement."""
        space = space_of_positions(meas.z.shape[1])
        if space != self.space:
            self.resolve(space)

    def compile_seconds(self):
        """The compile notice's estimate with the IMM (``lgekf.apps.warmup.imm_compile_seconds``); None otherwise."""
        if self.a.model != IMM_MODEL:
            return None
        from ..apps.warmup import imm_compile_seconds

        return imm_compile_seconds(False, False)

    def read(self):
        """The detections in time order, t in seconds; no objects (starts None)."""
        meas = read_multi_input(self.a)
        meas.t = to_seconds(meas.t, self.a.time_unit)
        return meas, None

    def data_warnings(self, meas, starts) -> list:
        return []  # the unit checks need objects; a detection file has none

    def plan(self, meas, starts, monitor) -> None:
        """Scans, the clutter density and the noise from the data: the tracking passes of ``fit_noise`` (their last
        run is the output)."""
        a, say, args, q = self.a, self.say, self.args, self.q
        t = meas.t
        self.Z = get_measurement(self.measure).columns(meas.z, meas.heading)
        window = scan_window_from_data(t, meas.z) if a.scan_window is None else a.scan_window
        self.sc = sc = scans(t, window)
        if a.scan_window is None and window > 0:
            say(f"scans: the detections within {window:.3g} s of a scan's first grouped into one (from the data: "
                f"{np.unique(t).size} distinct times, {sc.count} scans, period {sc.period:.3g} s); --scan-window sets it")
        source = None if a.clutter_density is not None else a.clutter or DEFAULT_CLUTTER_SOURCE
        if source is not None:
            args["clutter_density"] = clutter_from_data(source, meas.z, sc.count, meas.z.shape[1])
        if source == "file":
            box = "area" if meas.z.shape[1] == 2 else "volume"
            say(f"clutter density {args['clutter_density']:.3g} per {volume_unit(meas.z.shape[1])} per scan (estimated: "
                f"detections per scan / bounding-box {box}; give --clutter-density to set it)")
        fit_args = dict(heading_std=self.heading_std, omega_std=a.omega_std, monitor=monitor is not None)
        self.run, fit = fit_noise(t, self.Z, sc, args, meas_std=a.meas_std, accel_std=q, **fit_args)
        if a.meas_std is None or not self.noise_fixed:
            say(fit.describe(a.model, q is not None, self.heading_std if get_measurement(self.measure).has_angle else None,
                             a.heading_std is not None))
        if source in ("scan", "map"):
            say(clutter_line(self.run))
        if a.model == IMM_MODEL:
            from .track_imm import imm_modes_line

            bank = self.run.tracker.bank
            say(f"imm: modes {imm_modes_line(bank.modes)}; switch {1.0 - bank.setup.PI[0, 0]:.3g} per scan")
        if a.meas_std is not None:
            e = fit.check
            if e is None or not 1 / AGREE <= e / a.meas_std <= AGREE:  # the given value disagrees: the data's own estimate
                _, own = fit_noise(t, self.Z, sc, args, accel_std=q, **fit_args)
                e = own.meas_std if own.meas_source == "data" else None
            line = misfit_line(a.meas_std, e)
            if line is not None:
                _warn(line)
        self.fit = fit

    def write(self, handles, meas, starts, monitor, bar) -> list:
        """The warnings about the run (no track and why, a track near --max-speed, the monitor's alarms), then the
        confirmed tracks' rows."""
        a, run = self.a, self.run
        n_conf = run.n_confirmed
        if n_conf == 0 or run.fragments_only:
            _warn(no_track_reason(run, self.sc, meas.t.size, self.max_speed, self.fit.meas_std, a.confirm_existence,
                                  self.fit.wider))
        elif a.max_speed is None:
            v = fastest_track_speed(run)
            if v >= SPEED_WARN_FRACTION * self.max_speed:
                _warn(f"a confirmed track moves at {v:.3g} m/s, {'above' if v > self.max_speed else 'near'} --max-speed "
                      f"{self.max_speed:g} m/s (the speed scale of new tracks): faster objects may have no track; give a "
                      "larger --max-speed if there are any")
        if run.alarms:
            _warn(multi_alarm_line(run))
        write_multi(handles[0], a.model, run, a.precision, meas.z)
        return [(a.model, "")]

    def report(self, outs, what, meas) -> list:
        n = self.run.n_confirmed
        return [f"{'<stdout>' if is_stdio(outs[0]) else outs[0]}: {self.run.ids.size} rows, {n} confirmed "
                f"track{'s' if n != 1 else ''} from {meas.t.size} detections in {self.sc.count} scans "
                f"({self.a.model}, {self.a.association})"]
