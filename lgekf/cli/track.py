"""`lgekf track`: track every object of a measurement file with one model or all (one clear error line per bad input,
all-or-nothing output). The tracking itself is ``lgekf.apps.track``."""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path

import numpy as np

from ..apps.defaults import plan_noise_by_class
from ..apps.divergence import MonitorConfig
from ..apps.track import (
    DEFAULT_HEADING_STD, TRACK_HEADING_CAP, ClassConfigs, TrackConfig, default_model, output_path, write_model,
)
from ..core.registry import (
    ALL_MODELS, DEFAULT_SPACE, MODELS, base_measurement, get_measurement, get_model, measurement_in, measurements_of, models_of,
    space_of_positions,
)
from ..io.files import AtomicFiles, check_output_path, is_stdio
from ..io.grouping import objects_subset
from ..io.readers import COLUMN_OPTIONS
from .alarms import MAX_DIVERGENCE_LINES, divergence_warnings, smooth_failure_warnings, warn_misfit
from .cluster import check_cluster_options, cluster_requested
from .progress import compile_notice, progress_bar, stderr_is_terminal
from .track_options import check_estimator_options, column_names, track_parser
from .track_pipeline import SPACE_HINTS, SPACE_WORDS, TrackEstimator, frame_note, input_space
from .track_parquet import check_parquet_arguments, is_parquet
from .warmup import compile_estimate, track_jobs, warm_up

__all__ = ["cmd_track", "parse_accel_std", "MAX_DIVERGENCE_LINES"]

BAR_MIN_ROWS = 1 << 17  # rows x models above which a run draws a progress bar (on a terminal)


def parse_accel_std(items, models, known=MODELS):
    """``--accel-std`` values: ``A,B,C`` (for a single model) or ``MODEL=A,B,C`` (repeatable); ``known``: the models
    of the input's space (``models_of``; default the plane's).

    Returns {model: stds} for the models given (the others get their noise from the data)."""
    table = {}
    for item in items:
        if "=" in item:
            name, text = item.split("=", 1)
            name = name.strip()
            if name not in known:
                raise ValueError(f"--accel-std: unknown model {name!r}; choose one of {', '.join(known)}")
            targets = [name]
        else:
            if len(models) > 1:
                raise ValueError("--accel-std: with --model all give one MODEL=LIST per model, e.g. --accel-std cv=0.8")
            targets, text = list(models), item
        try:
            vals = tuple(float(v) for v in text.split(","))
        except ValueError:
            raise ValueError(f"--accel-std: expected comma-separated numbers, got {text!r}") from None
        for m in targets:
            need = len(known[m].noise_names)
            if len(vals) != need:
                raise ValueError(
                    f"--accel-std: {m} takes {need} value{'s' if need > 1 else ''} ({', '.join(known[m].noise_names)}), got {len(vals)}"
                )
            if any((not math.isfinite(v)) or v < 0 for v in vals):
                raise ValueError(f"--accel-std: noise stds must be non-negative numbers, got {text!r}")
            if m in models:
                table[m] = vals
    return table






def check_track_arguments(a, models):
    """Every argument error before any reading or computing (one line each, exit 2)."""
    if a.precision is not None and not 1 <= a.precision <= 17:
        raise ValueError(f"--precision: must be between 1 and 17, got {a.precision}")
    if a.format == "csv" and a.frame_dt is not None:
        raise ValueError("--frame-dt: only used with --format pedestrian")
    if a.format == "pedestrian" and a.time_unit != "s":
        raise ValueError("--time-unit: only for CSV input (the pedestrian format's time is frame * --frame-dt seconds)")
    if a.format == "pedestrian" and column_names(a):
        raise ValueError(f"{COLUMN_OPTIONS[next(iter(column_names(a)))]}: only for CSV or Parquet input (the pedestrian "
                         "format has no header)")
    if is_stdio(a.output) and len(models) > 1:
        raise ValueError("--output -: --model all writes one file per model; give a file name")
    check_output_path(a.output)
    outs = [output_path(a.output, m, len(models) > 1) for m in models]
    for o in outs:
        check_output_path(o, option=None)
    if not is_stdio(a.input) and any(not is_stdio(o) and Path(o).resolve() == Path(a.input).resolve() for o in outs):
        raise ValueError(f"--output: {a.output} would overwrite the input file")
    check_parquet_arguments(a, outs)
    return outs


class ModelsTrack(TrackEstimator):
    """The estimator of ``lgekf track --model MODEL|all`` in the pipeline of ``cmd_track``: one registry model (or every
    one) per output file, its noise from the data (per class of objects), ``--tune``, the divergence monitor, ``--smooth``."""

    def __init__(self, a, say):
        super().__init__(a, say)
        self.space = None  # the space of the input's positions (``input_space``): it selects the models
        self.models = []

    def check(self) -> None:
        """The models' own argument errors before any reading (one line each; the shared ones:
        ``check_track_arguments``). The space of the input (x, y or x, y, z: ``input_space``, from its header) selects
        the models and the measurement; from stdin, whose header cannot be read twice, the space of ``--model`` (the
        plane for none or ``all``) is assumed until the rows are read (``adopt_space``)."""
        space = input_space(self.a)
        self.space_known = space is not None
        guess = get_model(self.a.model).space if self.a.model in ALL_MODELS else DEFAULT_SPACE
        self.resolve(space or guess, announce=self.space_known)
        check_cluster_options(self.a)

    def resolve(self, space: str, announce: bool = True) -> None:
        """The models (``--model``, its default ``DEFAULT_MODELS[space]``, or ``all``: every model of ``space``), their
        measurement (``--measure`` as ``space`` measures it: ``measurement_in``) and given noise, for an input of
        ``space``; a model of another space is one error line naming the models that fit."""
        a = self.a
        table = models_of(space)
        if a.model is None:
            models = [default_model(space, a.measure)]
        elif a.model == "all":
            models = list(table)
        elif a.model not in table:
            other = get_model(a.model).space
            raise ValueError(f"--model {a.model}: a model of {SPACE_WORDS[other]}, and the input has {SPACE_HINTS[space]}; "
                             f"the models that fit: {', '.join(table)}")
        else:
            models = [a.model]
        self.space, self.models = space, models
        self.given_q = parse_accel_std(a.accel_std, models, table)
        # validate the given values before any reading (the estimated ones are valid by construction)
        TrackConfig(self.given_q, 1.0 if a.meas_std is None else a.meas_std, a.omega_std,
                    DEFAULT_HEADING_STD if a.heading_std is None else a.heading_std).validate()
        own = get_measurement(a.measure).space
        if own not in (space, DEFAULT_SPACE):  # position3 / pose3 named on a file of 2-D positions
            raise ValueError(f"--measure {a.measure}: observes {SPACE_WORDS[own]}, and the input has {SPACE_HINTS[space]}; "
                             f"choose {' or '.join(measurements_of(space))}")
        asked = measurement_in(space, a.measure)  # position, pose: as the input's space measures them
        base = base_measurement(space)
        measure = {m: asked if asked in table[m].measurements else None for m in models}
        if a.model not in (None, "all") and measure[a.model] is None:
            table[a.model].measurement(asked)  # raises with the definition's reason
        for m in models:
            if measure[m] is None:
                measure[m] = base
                if announce:
                    self.say(f"{m} cannot take {asked} measurements: it gets {base} only")
        self.measure = measure

    def adopt_space(self, meas) -> None:
        """After reading: the input's space from its positions (z (N, d)); an input whose space its header did not
        say (stdin) re-resolves the models, unless ``--model all`` already named its output files."""
        space = space_of_positions(meas.z.shape[1])
        if space == self.space:
            return
        if self.a.model == "all":
            raise ValueError(f"--model all: the input (stdin) has {SPACE_HINTS[space]}; its output files are "
                             f"named before reading: give the input as a file, or one --model")
        self.resolve(space)  # a model of the other space: one line naming those that fit

    def run_on_cluster(self) -> int | None:
        """``--workers/--scheduler``: the same output computed on Dask in partitions of whole objects (its exit status);
        None without them."""
        a, models, given_q = self.a, self.models, self.given_q
        if not cluster_requested(a):
            return None
        from ..apps.cluster import require_dask
        from .track_dask import cmd_track_dask

        require_dask("lgekf track --workers/--scheduler")  # first: without Dask nothing else matters
        if a.tune or a.smooth:
            raise ValueError("--tune/--smooth: not available with --workers/--scheduler (yet); run without them")
        if a.sort or a.skip_invalid:
            raise ValueError("--sort/--skip-invalid: not available with --workers/--scheduler (yet); clean the file first")
        if a.heading_unit == "deg":
            raise ValueError("--heading-unit deg: not available with --workers/--scheduler (yet); convert the column to radians")
        if column_names(a):
            raise ValueError(f"{COLUMN_OPTIONS[next(iter(column_names(a)))]}: not available with --workers/--scheduler (yet); "
                             "rename the columns in the file")
        # the noise estimate pools every object of the file: on a cluster it is not made (yet); the noise is given
        missing = [m for m in models if m not in given_q]
        if a.meas_std is None or missing:
            raise ValueError("--workers/--scheduler: give the noise (--meas-std and --accel-std"
                             + (f" for {', '.join(missing)}" if missing else "") + "); estimating it needs every object "
                             "in one process: run `lgekf track` on a sample of the file first, it prints the noise it used")
        cfg = TrackConfig(dict(given_q), a.meas_std, a.omega_std, DEFAULT_HEADING_STD if a.heading_std is None else a.heading_std,
                          TRACK_HEADING_CAP).validate()
        return cmd_track_dask(a, models, cfg, self.outs, self.measure, self.say, None if a.no_monitor else MonitorConfig())

    def compile_seconds(self):
        self.jobs = track_jobs(self.models, self.measure, self.a.full_cov)
        return compile_estimate([j.cost for j in self.jobs], workers=None if len(self.models) > 1 else 1)

    def warm_up(self) -> None:
        if len(self.models) > 1:
            warm_up(self.jobs)  # a cold cache: the models' kernels compile in parallel processes; warm: milliseconds

    def plan(self, meas, starts, monitor) -> None:
        """The noise of every model: from the data per class of objects (given values kept), ``--tune``'s fits."""
        a, say, models, measure = self.a, self.say, self.models, self.measure
        heading_std = DEFAULT_HEADING_STD if a.heading_std is None else a.heading_std
        classes = plan_noise_by_class(meas.t, meas.z, starts, models, meas_std=a.meas_std, accel_std=self.given_q,
                                      omega_std=a.omega_std, heading_std=heading_std, heading_cap=TRACK_HEADING_CAP,
                                      heading=meas.heading, measurement=measure, monitor=monitor)
        pose = any(get_measurement(v).angles for v in measure.values())  # a measured heading: its std is printed
        if len(classes.plans) > 1:
            say(classes.describe(meas.labels))
            for c, p in enumerate(classes.plans):
                say(f"  class {c + 1}: {p.describe(heading_std if pose else None, heading_given=a.heading_std is not None)}")
        elif classes.plans[0].estimated:
            say(classes.plans[0].describe(heading_std if pose else None, heading_given=a.heading_std is not None))
        for c, p in enumerate(classes.plans):  # an estimate at a floor or a bound: one warning line each
            for line in p.bound_warnings():
                head = f"class {c + 1}: " if len(classes.plans) > 1 else ""
                print(f"lgekf track: warning: {head}{line}", file=sys.stderr)
        warn_misfit(a.meas_std, meas, starts)
        configs = [TrackConfig(dict(p.accel_std), p.meas_std, a.omega_std, heading_std, TRACK_HEADING_CAP).validate()
                   for p in classes.plans]
        per_model = {m: list(configs) for m in models}
        if a.tune:  # each class of objects fitted on its own objects, from its own plan
            from ..apps.smooth_track import tune_models

            for c, plan in enumerate(classes.plans):
                rows, sub = objects_subset(starts, np.flatnonzero(classes.of_object == c))
                h = None if meas.heading is None else meas.heading[rows]
                head = f"class {c + 1}: " if len(classes.plans) > 1 else ""
                try:
                    fits = tune_models(meas.t[rows], meas.z[rows], sub, models, measure, a.meas_std, self.given_q, h,
                                       a.omega_std, a.tune_method, start_noise=plan.tune_starts(measure, heading_std))
                except ValueError as e:  # too few measurements: with one class that is the answer (exit 2), else the class
                    if len(classes.plans) == 1:  # keeps its noise from the data
                        raise
                    print(f"lgekf track: {head}not tuned ({e}): its noise from the data is kept", file=sys.stderr)
                    continue
                for m, fit in fits.items():
                    print(f"lgekf track: {head}{fit.report()}", file=sys.stderr)
                    r = fit.meas_std
                    per_model[m][c] = TrackConfig({**configs[c].accel_std, m: fit.accel_std}, r[0], a.omega_std,
                                                  r[-1] if get_measurement(measure[m]).angles else heading_std, TRACK_HEADING_CAP).validate()
        self.cfgs = {m: ClassConfigs(classes.of_object, per_model[m]) for m in models}

    def write(self, handles, meas, starts, monitor, bar) -> list:
        """Track and write every model's file; returns (what, extra) per file for its report line."""
        a, flagged = self.a, {}
        for fh, m, out in zip(handles, self.models, self.outs):
            w = write_model(fh, m, meas, starts, self.cfgs[m], a.full_cov, a.precision, bar, self.measure[m], monitor,
                            smooth=a.smooth, parquet=is_parquet(out))
            flagged[m] = w.flagged
            for line in divergence_warnings(m, meas, w.alarms, w.flagged) + smooth_failure_warnings(m, meas, w.smooth_failed, starts):
                print(f"lgekf track: warning: {line}", file=sys.stderr)
        return [(m, f", {flagged[m]} rows flagged" if flagged[m] else "") for m in self.models]


def cmd_track(argv, written: dict | None = None) -> int:
    """``lgekf track``: one pipeline for every estimator (``lgekf.cli.track_pipeline``): check → read → plan the noise →
    estimate (with the monitor, and smoothing) → write → report. The estimator is ``ModelsTrack`` (``--model
    MODEL|all``), ``ImmTrack`` (``--model imm``, ``lgekf.cli.track_imm``) or ``MultiTrack`` (``--multi``,
    ``lgekf.cli.track_multi``); one parser for all (``lgekf.cli.track_options``). ``written``: a dict filled with
    {model: output path} of the files written (``lgekf.track``)."""
    a = track_parser().parse_args(argv)
    check_estimator_options(a)
    say = (lambda text: print(f"lgekf track: {text}", file=sys.stderr)) if not a.quiet else (lambda text: None)
    if a.multi:  # the multi-target tracker's modules only then
        from .track_multi import MultiTrack

        est = MultiTrack(a, say)
    elif a.model == "imm":  # the IMM's modules only then (0.25 s); its options without it: check_estimator_options
        from .track_imm import ImmTrack

        est = ImmTrack(a, say)
    else:
        est = ModelsTrack(a, say)
    est.check()
    outs = est.outs = check_track_arguments(a, est.models)  # every estimator: format options, output paths, not the input
    t0 = time.perf_counter()
    status = est.run_on_cluster()
    if status is not None:
        return status
    meas, starts = est.read()
    est.adopt_space(meas)
    t_read = time.perf_counter() - t0
    if meas.origin is not None:
        say(frame_note(meas))
    for w in est.data_warnings(meas, starts):
        print(f"lgekf track: warning: {w}", file=sys.stderr)
    monitor = None if a.no_monitor else MonitorConfig()
    total = meas.t.size * len(outs)
    show_bar = not a.quiet and stderr_is_terminal() and total > BAR_MIN_ROWS
    with AtomicFiles(outs) as files, compile_notice("lgekf track", enabled=not a.quiet, seconds=est.compile_seconds()):
        handles = [files.open(i) for i in range(len(outs))]  # every output can be written before any work
        est.warm_up()
        est.plan(meas, starts, monitor)
        with progress_bar(total, "lgekf track", show_bar, unit="rows") as bar:
            what = est.write(handles, meas, starts, monitor, bar)
        files.commit()
    if written is not None:
        written.update(zip(est.models, outs))
    if not a.quiet:
        report = sys.stderr if is_stdio(a.output) else sys.stdout  # stdout is the data then
        for line in est.report(outs, what, meas):
            print(line, file=report)
        print(f"read {t_read:.2f} s, total {time.perf_counter() - t0:.2f} s", file=sys.stderr)
    return 0
