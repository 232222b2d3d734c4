"""`lgekf track DETECTIONS.csv --multi`: many objects from unlabelled detections in clutter (one clear error
line per bad input, all-or-nothing output). The tracking, the scans and the noise from the data are
``lgekf.apps.track_multi``; on stderr: the scan window and the noise when they come from the data (not with
--quiet), and, also with --quiet, warnings: a given --meas-std 2x or more off the data's estimate, no
confirmed track (one line saying why), a confirmed track near the default --max-speed."""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

from ..apps.track import DEFAULT_HEADING_STD, DEFAULT_MEAS_STD
from ..apps.track_multi import (
    AGREE, estimated_clutter_density, fastest_track_speed, fit_noise, multi_alarm_line, no_track_reason,
    scan_window_from_data, scans, write_multi,
)
from ..core.registry import MODELS, get_measurement
from ..core.validate import positive_scalar
from ..io.files import AtomicFiles, check_output_path, is_stdio
from ..io.cleaning import check_time_order, skipped_summary, sort_by_time
from ..io.readers import named_columns, parse_delimiter, read_measurements, skipping_nonfinite_rows
from ..io.units import to_seconds
from .progress import compile_notice
from .track_options import DEFAULT_MAX_SPEED, SPEED_WARN_FRACTION, column_names
from .alarms import misfit_line  # the same rule and words as `lgekf track`

__all__ = ["cmd_track_multi"]


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


def _check_arguments(a):
    """Every argument error before any reading (one line each, exit 2)."""
    if a.precision is not None and not 1 <= a.precision <= 17:
        raise ValueError(f"--precision: must be between 1 and 17, got {a.precision}")
    if a.meas_std is not None:
        positive_scalar("meas-std", a.meas_std)
    if a.max_speed is not None:
        positive_scalar("max-speed", a.max_speed)
    if a.scan_window is not None:
        positive_scalar("scan-window", a.scan_window, allow_zero=True)
    q = _accel_std(a.accel_std, a.model)
    MODELS[a.model].measurement(a.measure)
    check_output_path(a.output)
    return q


def read_multi_input(a):
    """The detections of ``--multi``'s input in non-decreasing time: rows going back in time are refused unless
    ``--sort`` (then sorted, stable, with one line saying how many moved), rows with NaN/inf refused unless
    ``--skip-invalid`` (then dropped, one summary line): the rules of single-object tracking for a file of scans."""
    with skipping_nonfinite_rows(a.skip_invalid), named_columns(column_names(a)):
        meas = read_measurements(a.input, "csv", None, get_measurement(a.measure).has_angle, parse_delimiter(a.delimiter))
    if meas.time_iso and a.time_unit != "s":
        raise ValueError(f"--time-unit {a.time_unit}: the t column holds ISO-8601 date-times, read as seconds; leave --time-unit out")
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


def cmd_track_multi(a) -> int:
    """``lgekf track --multi`` on the parsed options of ``lgekf.cli.track_options.track_parser`` (the labelled-object
    options refused and the multi-target defaults filled in by ``check_estimator_options``)."""
    q = _check_arguments(a)
    say = (lambda text: print(f"lgekf track: {text}", file=sys.stderr)) if not a.quiet else (lambda text: None)
    max_speed = DEFAULT_MAX_SPEED if a.max_speed is None else a.max_speed
    heading_std = DEFAULT_HEADING_STD if a.heading_std is None else a.heading_std
    args = dict(model=a.model, association=a.association, detection_prob=a.detection_prob, measurement=a.measure,
                gate_prob=a.gate_prob, survival_prob=a.survival_prob, birth_existence=a.birth_existence,
                confirm_existence=a.confirm_existence, delete_existence=a.delete_existence, max_speed=max_speed,
                omega_std=a.omega_std, clutter_density=1.0 if a.clutter_density is None else a.clutter_density)
    from ..estimators.multitarget.tracker import MultiTargetTracker

    r = DEFAULT_MEAS_STD if a.meas_std is None else a.meas_std
    MultiTargetTracker(**args, accel_std=q, meas_std=get_measurement(a.measure).stds(r, heading_std))  # every option checked before reading
    t0 = time.perf_counter()
    meas = read_multi_input(a)
    if not is_stdio(a.input) and not is_stdio(a.output):
        if Path(a.output).resolve() == Path(a.input).resolve():
            raise ValueError(f"--output: {a.output} would overwrite the input file")
    t = to_seconds(meas.t, a.time_unit)
    if meas.origin is not None:
        say(f"lat, lon projected to x, y in metres east and north of {meas.origin} (the first row; local equirectangular)")
    Z = get_measurement(a.measure).columns(meas.z, meas.heading)
    window = scan_window_from_data(t, meas.z) if a.scan_window is None else a.scan_window
    sc = scans(t, window)
    if a.scan_window is None and window > 0:
        say(f"scans: the detections within {window:.3g} s of a scan's first grouped into one (from the data: "
            f"{np.unique(t).size} distinct times, {sc.count} scans, period {sc.period:.3g} s); --scan-window sets it")
    if a.clutter_density is None:
        args["clutter_density"] = estimated_clutter_density(sc, meas.z)
        say(f"clutter density {args['clutter_density']:.3g} per m² per scan (estimated: detections per scan / "
            "bounding-box area; give --clutter-density to set it)")
    fit_args = dict(heading_std=heading_std, omega_std=a.omega_std, monitor=not a.no_monitor)
    with AtomicFiles([a.output]) as files, compile_notice("lgekf track", enabled=not a.quiet):
        fh = files.open(0)
        run, fit = fit_noise(t, Z, sc, args, meas_std=a.meas_std, accel_std=q, **fit_args)
        if a.meas_std is None or q is None:
            say(fit.describe(a.model, q is not None, heading_std if get_measurement(a.measure).has_angle else None, a.heading_std is not None))
        if a.meas_std is not None:
            e = fit.check
            if e is None or not 1 / AGREE <= e / a.meas_std <= AGREE:  # the given value disagrees: the data's own estimate
                _, own = fit_noise(t, Z, sc, args, accel_std=q, **fit_args)
                e = own.meas_std if own.meas_source == "data" else None
            line = misfit_line(a.meas_std, e)
            if line is not None:
                _warn(line)
        n_conf = run.n_confirmed
        if n_conf == 0:
            _warn(no_track_reason(run, sc, t.size, max_speed, fit.meas_std, a.confirm_existence, fit.wider))
        elif a.max_speed is None:
            v = fastest_track_speed(run)
            if v >= SPEED_WARN_FRACTION * max_speed:
                _warn(f"a confirmed track moves at {v:.3g} m/s, {'above' if v > max_speed else 'near'} --max-speed "
                      f"{max_speed:g} m/s (the fastest start of a track): faster objects may have no track; give a larger "
                      "--max-speed if there are any")
        if run.alarms:
            _warn(multi_alarm_line(run))
        write_multi(fh, a.model, run, a.precision, meas.z)
        files.commit()
    if not a.quiet:
        report = sys.stderr if is_stdio(a.output) else sys.stdout
        name = "<stdout>" if is_stdio(a.output) else a.output
        print(f"{name}: {run.ids.size} rows, {n_conf} confirmed track{'s' if n_conf != 1 else ''} from {t.size} detections "
              f"in {sc.count} scans ({a.model}, {a.association})", file=report)
        print(f"total {time.perf_counter() - t0:.2f} s", file=sys.stderr)
    return 0
