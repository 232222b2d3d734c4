"""`lgekf track --model imm`: argument checks, reading and the atomic output around ``lgekf.apps.track_imm``."""

from __future__ import annotations

import sys
import time

from ..apps.divergence import MonitorConfig
from ..apps.track_imm import ImmClasses, ImmTrackOptions, imm_noise, tune_imm, write_imm
from ..io.files import AtomicFiles, check_output_path, is_stdio
from ..io.readers import parse_delimiter, read_measurements
from ..io.units import to_seconds, unit_warnings
from .alarms import divergence_warnings, smooth_failure_warnings
from .progress import compile_notice

__all__ = ["cmd_track_imm", "check_imm_options"]


def check_imm_options(a) -> None:
    """--imm-modes / --imm-switch only with --model imm (one line otherwise)."""
    if a.model != "imm" and (a.imm_modes is not None or a.imm_switch is not None):
        raise ValueError("--imm-modes/--imm-switch: only with --model imm")


def _modes(opts) -> str:
    return ", ".join(f"{m.name} ({','.join(f'{v:.3g}' for v in m.accel_std)})" for m in opts.modes)


def cmd_track_imm(a) -> int:
    """Run ``lgekf track --model imm`` with the parsed arguments ``a`` of ``track_parser``."""
    opts = ImmTrackOptions(a.imm_modes, a.imm_switch)
    unsupported = [(a.accel_std, "--accel-std (give the modes' noise in --imm-modes, e.g. se2r3:0.2/0.2/0.5)"),
                   (a.measure != "position", "--measure pose"), (a.full_cov, "--full-cov"),
                   (getattr(a, "workers", None) or getattr(a, "scheduler", None), "--workers/--scheduler"),
                   (a.use_heading, "--use-heading")]
    for given, name in unsupported:
        if given:
            raise ValueError(f"--model imm: {name} is not supported")
    if not 1 <= a.precision <= 17:
        raise ValueError(f"--precision: must be between 1 and 17, got {a.precision}")
    check_output_path(a.output)
    say = (lambda text: print(f"lgekf track: {text}", file=sys.stderr)) if not a.quiet else (lambda text: None)
    t0 = time.perf_counter()
    meas = read_measurements(a.input, a.format, a.frame_dt, False, parse_delimiter(a.delimiter))
    meas, starts, _ = meas.grouped(min_length=2)
    meas.t = to_seconds(meas.t, a.time_unit)
    for w in unit_warnings(meas.t, meas.z, starts, a.time_unit, projected=meas.origin is not None, fmt=a.format):
        print(f"lgekf track: warning: {w}", file=sys.stderr)
    monitor = None if a.no_monitor else MonitorConfig()
    if getattr(a, "tune", False):
        r, fits, summary = tune_imm(meas, starts, opts, a.meas_std, a.omega_std, say=say,
                                    method=getattr(a, "tune_method", "lbfgs"))
        say(summary)
        classes = ImmClasses.of_all(opts, r, meas.n_objects)
        say(f"imm: modes {_modes(opts)}; switch {opts.switch:g} per step; meas-std {r:.3g} m (tuned)")
    else:
        classes, found = imm_noise(meas, starts, opts, a.meas_std, a.omega_std, monitor)
        if len(found.plans) > 1:
            say(found.describe(meas.labels))
        for c, ((o, r), plan) in enumerate(zip(classes.noise, found.plans)):
            head = f"class {c + 1}: " if len(found.plans) > 1 else ""
            if plan.estimated:
                say(head + plan.describe())
            say(f"{head}imm: modes {_modes(o)}; switch {o.switch:g} per step; meas-std {r:.3g} m "
                f"({'given' if a.meas_std is not None else plan.meas_source})")
    if getattr(a, "smooth", False):
        say("imm: smoothed columns after flag")
    with AtomicFiles([a.output]) as files, compile_notice("lgekf track", enabled=not a.quiet):
        fh = files.open(0)
        res = write_imm(fh, meas, starts, classes, a.omega_std, a.precision, smooth=getattr(a, "smooth", False), monitor=monitor)
        files.commit()
    flagged = int((res.flag & 1).sum())
    for line in divergence_warnings("imm", meas, res.alarms, flagged):
        print(f"lgekf track: warning: {line}", file=sys.stderr)
    for line in smooth_failure_warnings("imm", meas, res.smooth_failed):
        print(f"lgekf track: warning: {line}", file=sys.stderr)
    if not a.quiet:
        report = sys.stderr if is_stdio(a.output) else sys.stdout
        name = "<stdout>" if is_stdio(a.output) else a.output
        print(f"{name}: {meas.t.size} rows, {meas.n_objects} object{'s' if meas.n_objects != 1 else ''} (imm)", file=report)
        print(f"total {time.perf_counter() - t0:.2f} s", file=sys.stderr)
    return 0
