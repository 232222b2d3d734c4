"""``lgekf track --model imm``: every object of a file through an IMM of registry models.

Each object starts like every ``lgekf track`` filter (the two-point estimate of its first two measurements in
the common coordinates, ``lgekf.apps.track.initial_common``, heading std capped at ``TRACK_HEADING_CAP``; every
mode converts it to its own coordinates) and runs :func:`lgekf.estimators.imm.imm_batch` from its third measurement
on. The noise comes from the data as for the filters (:func:`imm_noise`): the measurement std (unless
``--meas-std``) and each mode model's process noise from ``lgekf.apps.defaults.plan_noise``, a named level
(calm, manoeuvre) a factor on that estimate; modes given as numbers in ``--imm-modes`` keep them. The divergence
monitor and recovery of ``lgekf.apps.imm_monitor`` watch the combined estimate (``--no-monitor``: off); ``flag``
is 1 on the rows of an alarm. Output columns: id, t, the combined estimate in the common
coordinates x, y, theta, vx, vy (body frame), omega, their stds, speed and course (the world velocity's norm and
direction), mu_<mode> (mode probabilities), and
origin_lat, origin_lon for lat/lon input, flag.

``--tune`` (:func:`tune_imm`): every distinct model of the modes whose noise is not given as numbers is fitted by
maximum likelihood on the file's own tracks (``lgekf.apps.smooth_track.tune_models``, as ``lgekf track MODEL
--tune``); a plain mode ``MODEL`` runs with the learned process noise, ``MODEL:calm`` / ``MODEL:manoeuvre`` with
the learned noise × their level factor (0.2, 4; ``lgekf.estimators.imm.NOISE_LEVELS``), ``MODEL:a/b/c`` keeps
its numbers. The measurement std is ``--meas-std`` when given (then held fixed in the fits), else the one
learned by the fit with the highest log-likelihood. Then the IMM itself is fitted by its own likelihood
(:func:`fit_imm`, ``lgekf.estimators.imm.tuning.learn_imm``): one factor per mode on that noise, and the
switching probability unless ``--imm-switch`` is given. Without ``--imm-modes`` the mode sets of
``TUNE_MODE_SETS`` are fitted (the default; CV calm and manoeuvring; those two and a manoeuvring SE(2)×R³) and
the one of lowest AIC is kept.

``--smooth``: after ``flag``, the IMM smoother's (``lgekf.estimators.imm.smoother``) combined estimate
``smooth_<x|y|theta|vx|vy|omega>``, its stds ``smooth_std_<...>`` and the smoothed mode probabilities
``smooth_mu_<mode>``, over each monitored segment (split at re-initialisations; the rows of a start or
re-initialisation repeat the filter columns, as for ``lgekf track --smooth``); the filter columns are the same
with and without ``--smooth``. An object whose smoother yields a non-finite or implausible value (far off the filter's) keeps the filter's values in its
smoothed columns and has ``SMOOTH_FAILED`` (2) added to its ``flag``.
"""

from __future__ import annotations

from dataclasses import dataclass
from types import SimpleNamespace

import numpy as np

from ..core.common import COMMON_NAMES, common_turn_rate, common_world_velocity
from ..core.registry import BASE_MEASUREMENT, DEFAULT_SPACE, SPACES, measurement_in, models_of
from ..estimators.imm.estimator import (DEFAULT_MODES, DEFAULT_SWITCH, NOISE_LEVELS, Mode, default_modes, parse_modes,
                                        space_of_modes, transition_matrix)
from ..io.formatting import format_rows, label_bytes, output_digits
from ..io.grouping import objects_subset, row_objects
from .divergence import MonitorConfig, speed_limits
from .imm_monitor import imm_monitored, scaled_modes
from .track import (MOTION_COLUMNS, MOTION_COLUMNS_3D, speed_and_course, ORIGIN_COLUMNS, REINIT_BASELINE, SMOOTH_FAILED,
                    TRACK_HEADING_CAP, initial_common)

__all__ = ["DEFAULT_TRACK_MODES", "TUNE_MODE_SETS", "ImmTrackOptions", "ImmTracked", "ImmClasses", "imm_track_classes", "fit_imm", "imm_columns", "write_imm",
           "imm_track_common", "imm_noise", "tune_imm", "common_world_velocity", "mode_columns", "COMMON_NAMES", "IMM_FILTER"]

IMM_FILTER = "imm"  # its name in the tables of ``lgekf evaluate``

#: ``lgekf track --model imm`` / ``lgekf evaluate --imm`` / ``--multi --model imm`` modes by default (``DEFAULT_MODES``)
DEFAULT_TRACK_MODES = DEFAULT_MODES
#: the mode sets ``--tune`` fits when ``--imm-modes`` is not given; the one of lowest AIC is kept (docs/imm.md, real
#: data: two CV modes win on pedestrians, a manoeuvring SE(2)×R³ added to them or the default on cars and cyclists)
TUNE_MODE_SETS = (DEFAULT_TRACK_MODES, "cv:calm,cv:manoeuvre", "cv:calm,cv:manoeuvre,se2r3:manoeuvre")
#: at most about this many steps (whole tracks, a seeded random subset) enter the IMM's joint fit
FIT_MAX_STEPS = 20_000


class ImmTrackOptions:
    """The IMM of ``lgekf track``: modes (``parse_modes`` syntax; by default the space's, ``default_modes``) and the
    per-step switching probability, for an input of ``space`` (the modes must be models of it: one line otherwise)."""

    def __init__(self, modes: str | None = None, switch: float | None = None, space: str = DEFAULT_SPACE):
        self.modes_given = modes is not None
        self.switch_given = switch is not None
        self.space = space
        self.modes_text = default_modes(space) if modes is None else modes
        self.switch = DEFAULT_SWITCH if switch is None else float(switch)
        self.modes = parse_modes(self.modes_text)
        own = space_of_modes(self.modes)
        if own != space:
            words = {DEFAULT_SPACE: "the plane"}.get(own, f"{own} space")
            raise ValueError(f"--imm-modes: {self.modes_text} are models of {words}, and the input has "
                             f"{SPACES[space]['dim']}-D positions; the models that fit: "
                             f"{', '.join(models_of(space))} (default modes {default_modes(space)})")
        transition_matrix(len(self.modes), self.switch)

    def for_space(self, space: str) -> "ImmTrackOptions":
        """These options for an input of ``space``: the given modes and switch (the modes must be models of it), else
        that space's default modes."""
        if space == self.space:
            return self
        return ImmTrackOptions(self.modes_text if self.modes_given else None, self.switch if self.switch_given else None,
                               space)

    @property
    def common_names(self) -> tuple:
        """The names of the common coordinates of the modes' space (the IMM's output columns)."""
        return SPACES[self.space]["common_names"]

    def candidates(self) -> list:
        """The mode sets ``--tune`` fits: the given ``--imm-modes``, else every set of ``TUNE_MODE_SETS`` in the plane
        and the space's default modes elsewhere."""
        if self.modes_given or self.space != DEFAULT_SPACE:
            return [self.modes_text]
        return list(TUNE_MODE_SETS)

    def tunable_models(self) -> list:
        """The distinct models of modes whose noise is a named level or the default (not given as numbers)."""
        out = []
        for m in self.modes:
            if (not m.label or m.label in NOISE_LEVELS) and m.model not in out:
                out.append(m.model)
        return out

    def with_learned_noise(self, learned: dict) -> None:
        """Replace the noise of the modes of the models in ``learned`` ({model: accel_std}): a plain mode gets
        the learned values, a named level the learned values × its factor; modes given as numbers are kept."""
        modes = []
        for m in self.modes:
            if m.model in learned and (not m.label or m.label in NOISE_LEVELS):
                f = NOISE_LEVELS[m.label] if m.label else 1.0
                modes.append(Mode(m.model, tuple(f * float(v) for v in learned[m.model]), m.label))
            else:
                modes.append(m)
        self.modes = modes


@dataclass
class ImmTracked:
    """``imm_track_common(..., full=True)``: the combined estimate c (N, 6), stds sd (N, 6), mode probabilities
    mu (N, M), flags (N,), the monitor's alarms (object indices and rows of the input), the objects whose smoothing
    failed (they keep the filter's values), and with smoothing the smoothed c, sd, mu (else None)."""

    c: np.ndarray
    sd: np.ndarray
    mu: np.ndarray
    flag: np.ndarray
    alarms: list
    smooth_failed: list
    c_smooth: np.ndarray | None = None
    sd_smooth: np.ndarray | None = None
    mu_smooth: np.ndarray | None = None


def mode_columns(modes, prefix: str = "mu_") -> list:
    """The column names of the mode probabilities of ``modes`` (``Mode`` list): <prefix><model>[_<label>], a repeated
    name numbered _2, _3, ... (``/`` of a label given as numbers written ``-``)."""
    mode_cols = []
    for m in modes:
        base = f"{prefix}{m.name.replace(':', '_').replace('/', '-')}"
        name, k = base, 2
        while name in mode_cols:
            name, k = f"{base}_{k}", k + 1
        mode_cols.append(name)
    return mode_cols


def imm_motion_columns(opts: ImmTrackOptions) -> tuple:
    """The motion columns of an IMM track file: speed, course; in 3-D also climb and turn_rate (as the single models')."""
    return MOTION_COLUMNS if SPACES[opts.space]["dim"] == 2 else MOTION_COLUMNS_3D


def imm_origin_columns(opts: ImmTrackOptions) -> tuple:
    """origin_lat, origin_lon (, origin_alt in 3-D) of an IMM track file from lat, lon (, alt) input."""
    return ORIGIN_COLUMNS + (("origin_alt",) if SPACES[opts.space]["dim"] == 3 else ())


def imm_motion(opts: ImmTrackOptions, c: np.ndarray) -> np.ndarray:
    """The motion columns (``imm_motion_columns``) of combined estimates c (N, n_c): speed and course of the world
    velocity; in 3-D its climb rate v_z and the turn rate (``lgekf.core.common.common_turn_rate``)."""
    v = common_world_velocity(c)
    if v.shape[1] == 2:
        return speed_and_course(v)
    return np.column_stack([np.linalg.norm(v, axis=1), np.arctan2(v[:, 1], v[:, 0]), v[:, 2], common_turn_rate(c)])


def imm_columns(opts: ImmTrackOptions, origin: bool = False, smooth: bool = False) -> list:
    """The header of an IMM track file (module docstring); mode columns are named mu_<model>[_<label>]
    (the labels of modes given as numbers: their labels at the time of parsing, i.e. the numbers)."""
    names = opts.common_names
    smoothed = ([*(f"smooth_{s}" for s in names), *(f"smooth_std_{s}" for s in names),
                 *mode_columns(opts.modes, "smooth_mu_")] if smooth else [])
    return (["id", "t", *names, *(f"std_{s}" for s in names), *imm_motion_columns(opts), *mode_columns(opts.modes, "mu_")]
            + (list(imm_origin_columns(opts)) if origin else []) + ["flag"] + smoothed)


def imm_track_common(t, z, starts, meas_std: float, omega_std: float, opts: ImmTrackOptions, smooth: bool = False,
                     monitor: MonitorConfig | None = None, full: bool = False):
    """Every object's IMM estimate in the common coordinates: c (N, 6), their stds (N, 6), mode probabilities (N, M).

    Row 0 of an object is the two-point estimate at its first measurement's position, row 1 the two-point estimate
    (uniform mode probabilities), rows >= 2 the IMM's posteriors (as ``lgekf.apps.track.track_arrays``).
    ``monitor``: the divergence monitor and recovery of ``lgekf.apps.imm_monitor`` (None: unmonitored).
    With ``smooth`` also the smoothed (c, stds, mode probabilities), a 6-tuple: the IMM smoother
    (``lgekf.estimators.imm.smoother``) over each monitored segment (split at re-initialisations) from the same start
    and noise as the filter; the filter's rows are never changed by it. A row the smoother leaves non-finite gets the
    filter's values (the object is named in ``failed``). ``full``: return ``ImmTracked`` (adds flags, alarms, the
    objects whose smoothing failed).
    """
    dim, nc = SPACES[opts.space]["dim"], len(opts.common_names)
    t = np.ascontiguousarray(t, float)
    z = np.ascontiguousarray(np.asarray(z, float)[:, :dim])
    starts = np.asarray(starts, dtype=np.int64)
    N, M = t.size, len(opts.modes)
    c = np.full((N, nc), np.nan)
    sd = np.full((N, nc), np.nan)
    mu = np.full((N, M), 1.0 / M)
    flag = np.zeros(N, np.int8)
    alarms, failed = [], []
    c0, var0 = initial_common(t, z, starts, meas_std, omega_std, heading_cap=TRACK_HEADING_CAP)
    limits = speed_limits(t, z, starts, meas_std, monitor) if monitor is not None else np.full(len(starts) - 1, np.inf)
    smoothed = (np.full((N, nc), np.nan), np.full((N, nc), np.nan), np.full((N, M), 1.0 / M)) if smooth else None
    for b in range(len(starts) - 1):
        a, e = int(starts[b]), int(starts[b + 1])
        c[a] = c0[b]  # as the filters of lgekf track: the two-point estimate, at the first measurement's position
        c[a, :dim] = z[a]
        c[a + 1] = c0[b]
        sd[a:a + 2] = np.sqrt(var0[b])
        run = imm_monitored(t[a:e], z[a:e], opts.modes, opts.switch, meas_std, omega_std, c0[b], var0[b], float(limits[b]),
                            monitor, REINIT_BASELINE, TRACK_HEADING_CAP)
        if e - a > 2:
            c[a + 2:e] = run.c[2:]
            sd[a + 2:e] = np.sqrt(np.maximum(np.diagonal(run.P[2:], axis1=1, axis2=2), 0.0))
            mu[a + 2:e] = run.mu[2:]
        flag[a:e] = run.flag
        for al in run.alarms:
            al.obj, al.row = b, al.row + a
        alarms.extend(run.alarms)
        if smooth:
            if not _smooth_object(t[a:e], z[a:e], run, opts, meas_std, (c[a:e], sd[a:e], mu[a:e]), [s[a:e] for s in smoothed]):
                failed.append(b)
    out = (c, sd, mu) + (smoothed if smooth else ())
    return ImmTracked(*out[:3], flag, alarms, failed, *(smoothed or (None, None, None))) if full else out


def _smooth_object(t, z, run, opts: ImmTrackOptions, meas_std: float, filt, out) -> bool:
    """The smoothed columns of one object (``out`` = (c, sd, mu) views of its rows), segment by segment; rows outside
    the segments (the starts and re-initialisations) repeat the filter's. False when a smoothed row is implausible
    (``smooth_track.implausible_rows``: non-finite, or far off the filter's): then every row keeps the filter's values."""
    from ..estimators.imm.smoother import imm_smooth_batch

    for dst, src in zip(out, filt):
        dst[:] = src
    for seg in run.segments:
        if seg.end - seg.first < 1:
            continue
        r = imm_smooth_batch(z[None, seg.first:seg.end], scaled_modes(opts.modes, seg.scale), opts.switch,
                             dt=np.diff(t[seg.first - 1:seg.end])[None], meas_std=meas_std * seg.scale, x0=seg.c0, P0=seg.P0)
        out[0][seg.first:seg.end] = r["c_smooth"][0]
        out[1][seg.first:seg.end] = np.sqrt(np.maximum(np.diagonal(r["P_smooth"][0], axis1=1, axis2=2), 0.0))
        out[2][seg.first:seg.end] = r["mu_smooth"][0]
    from .smooth_track import implausible_rows

    if not implausible_rows(filt[0], filt[1], out[0], out[1], meas_std).any() and np.isfinite(out[2]).all():
        return True
    for dst, src in zip(out, filt):
        dst[:] = src
    return False


def tune_imm(meas, starts, opts: ImmTrackOptions, meas_std: float | None, omega_std: float, say=None, method: str = "lbfgs"):
    """Learn the IMM from the file (module docstring) and set ``opts``' modes, their noise and the switching.

    Returns
    -------
    r : float
        The measurement std to run with.
    fits : dict
        {model: NoiseFit} of the single models, and "imm": the kept ``ImmFit`` (or why it could not be fitted:
        then the modes take the learned noise × their level).
    summary : str
        What was learned and used (one line per step).

    ``say`` (optional) gets a line before each of the IMM's fits (they take seconds to minutes); ``method``: of the
    single-model fits (``lgekf.apps.smooth_track.tune_models``).
    """
    from .defaults import data_starts
    from .smooth_track import tune_models

    models = []
    for text in opts.candidates():
        for m in ImmTrackOptions(text, space=opts.space).tunable_models():
            if m not in models:
                models.append(m)
    if not models:
        raise ValueError("--tune: every mode's noise is given as numbers in --imm-modes; nothing to learn")
    position = measurement_in(opts.space, BASE_MEASUREMENT)
    fits = tune_models(meas.t, meas.z, starts, models, {m: position for m in models}, meas_std, None, None, omega_std, method,
                       start_noise=data_starts(meas.t, meas.z, starts, models, meas_std, omega_std))
    best = max(fits, key=lambda m: fits[m].loglik)
    r = float(meas_std) if meas_std is not None else float(np.asarray(fits[best].meas_std).reshape(-1)[0])
    learned = "; ".join(f"{m} accel-std {','.join(f'{v:.3g}' for v in f.accel_std)} (log-likelihood {f.loglik:.6g}"
                        + (f"; not identified: {', '.join(f.problems)}" if f.problems else "") + ")" for m, f in fits.items())
    src = "given" if meas_std is not None else f"learned with {best}, the best log-likelihood"
    t = np.asarray(meas.t, float)
    z = np.asarray(meas.z, float)[:, :SPACES[opts.space]["dim"]]
    tracks = [(t[a:b], z[a:b]) for a, b in zip(starts[:-1], starts[1:]) if b - a >= 3]
    learned_q = {m: f.accel_std for m, f in fits.items()}
    try:
        fit, table = fit_imm(opts, tracks, r, omega_std, learned_q, say=say)
    except ValueError as e:  # too few steps for the IMM's own fit: the learned noise × the levels, as given
        opts.with_learned_noise({m: learned_q[m] for m in opts.tunable_models() if m in learned_q})
        fit, table, why = str(e), [], str(e)
    modes = ", ".join(f"{m.name} ({','.join(f'{v:.3g}' for v in m.accel_std)})" for m in opts.modes)
    if isinstance(fit, str):
        return r, dict(fits, imm=fit), (f"imm --tune: learned {learned}; meas-std {r:.3g} m ({src})\n"
                                        f"  the IMM itself is not fitted ({why.removeprefix('--tune: the IMM could not be fitted: ')}): "
                                        f"the modes take the learned noise × their level\n  modes {modes}; switch {opts.switch:.3g}")
    fits = dict(fits, imm=fit)
    sets = "; ".join(f"{text}: " + (f"AIC {f.aic:.6g}" if not isinstance(f, str) else f"not fitted ({f})") for text, f in table)
    return r, fits, (f"imm --tune: learned {learned}; meas-std {r:.3g} m ({src})\n"
                     + (f"  mode sets compared: {sets}; kept {opts.modes_text}\n" if len(table) > 1 else "")
                     + f"  {fit.report()}\n  modes {modes}; switch {opts.switch:.3g}")


def fit_imm(opts: ImmTrackOptions, tracks, meas_std: float, omega_std: float, learned: dict, seed: int = 0, say=None):
    """The IMM fitted to ``tracks`` by its own likelihood (``lgekf.estimators.imm.tuning.learn_imm``), in place.

    Every candidate mode set (``opts.candidates()``) starts from its models' learned noise ``learned``
    ({model: accel_std}) times the named levels, and its modes' factors and the switching probability (unless
    ``--imm-switch`` was given) are fitted; modes given as numbers keep them. The set of lowest AIC is kept in
    ``opts``. With more than ``FIT_MAX_STEPS`` steps a seeded random subset of whole tracks is used. ``say``
    (optional) gets one line before each mode set's fit.

    Returns
    -------
    fit : ImmFit
        The kept set's fit.
    table : list of (str, ImmFit or str)
        Every candidate with its fit, or why it could not be fitted.
    """
    from ..estimators.imm.tuning import learn_imm

    tracks = list(tracks)
    steps = np.array([max(len(t) - 2, 0) for t, _ in tracks])
    if steps.sum() > FIT_MAX_STEPS:
        order = np.random.default_rng(seed).permutation(len(tracks))
        keep = order[:max(1, int(np.searchsorted(np.cumsum(steps[order]), FIT_MAX_STEPS)) + 1)]
        tracks = [tracks[i] for i in np.sort(keep)]
    table = []
    texts = opts.candidates()
    for i, text in enumerate(texts):
        if say is not None:
            say(f"imm --tune: fitting mode set {i + 1}/{len(texts)} ({text}) on {sum(len(t) for t, _ in tracks)} measurements "
                f"of {len(tracks)} tracks")
        cand = ImmTrackOptions(text, opts.switch if opts.switch_given else None, opts.space)
        cand.with_learned_noise({m: learned[m] for m in cand.tunable_models() if m in learned})
        fixed = [bool(m.label) and m.label not in NOISE_LEVELS for m in cand.modes]
        try:
            table.append((text, learn_imm(cand.modes, tracks, meas_std=meas_std, switch=cand.switch, omega_std=omega_std,
                                          fit_switch=not opts.switch_given, fixed=fixed,
                                          measurement=measurement_in(opts.space, BASE_MEASUREMENT))))
        except ValueError as e:
            table.append((text, str(e)))
    fitted = [(text, f) for text, f in table if not isinstance(f, str)]
    if not fitted:
        why = table[0][1] if len(table) == 1 else "; ".join(f"{text}: {f}" for text, f in table)
        raise ValueError(f"--tune: the IMM could not be fitted: {why}")
    text, fit = min(fitted, key=lambda tf: tf[1].aic)
    opts.modes_text, opts.modes, opts.switch = text, list(fit.modes), fit.switch
    return fit, table


@dataclass
class ImmClasses:
    """The IMM's noise per class of objects (``lgekf.apps.defaults.noise_classes``): object b runs with
    ``noise[of_object[b]]`` = (``ImmTrackOptions`` with the class's mode noise, measurement std)."""

    of_object: np.ndarray
    noise: list

    @classmethod
    def of_all(cls, opts: ImmTrackOptions, meas_std: float, objects: int) -> "ImmClasses":
        return cls(np.zeros(objects, dtype=np.int64), [(opts, float(meas_std))])


def imm_track_classes(t, z, starts, classes: ImmClasses, omega_std: float, smooth: bool = False,
                      monitor: MonitorConfig | None = MonitorConfig()) -> ImmTracked:
    """``imm_track_common(..., full=True)`` with each class of objects' own noise: the rows of a class gathered, tracked
    and put back in place (alarms and failures in objects and rows of t, z)."""

    if len(classes.noise) == 1:
        opts, r = classes.noise[0]
        return imm_track_common(t, z, starts, r, omega_std, opts, smooth, monitor=monitor, full=True)
    N, M = len(t), len(classes.noise[0][0].modes)
    nc = len(classes.noise[0][0].common_names)
    out = ImmTracked(np.empty((N, nc)), np.empty((N, nc)), np.empty((N, M)), np.zeros(N, np.int8), [], [],
                     *((np.empty((N, nc)), np.empty((N, nc)), np.empty((N, M))) if smooth else ()))
    for c, (opts, r) in enumerate(classes.noise):
        objs = np.flatnonzero(classes.of_object == c)
        if objs.size == 0:
            continue
        rows, sub = objects_subset(starts, objs)
        res = imm_track_common(np.asarray(t)[rows], np.asarray(z)[rows], sub, r, omega_std, opts, smooth, monitor=monitor, full=True)
        for name in ("c", "sd", "mu", "flag") + (("c_smooth", "sd_smooth", "mu_smooth") if smooth else ()):
            getattr(out, name)[rows] = getattr(res, name)
        for al in res.alarms:
            al.obj, al.row = int(objs[al.obj]), int(rows[al.row])
        out.alarms.extend(res.alarms)
        out.smooth_failed.extend(int(objs[b]) for b in res.smooth_failed)
    out.alarms.sort(key=lambda al: (al.obj, al.row))
    out.smooth_failed.sort()
    return out


def write_imm(fh, meas, starts, classes: ImmClasses, omega_std: float, digits: int, bar=None,
              smooth: bool = False, monitor: MonitorConfig | None = MonitorConfig()) -> ImmTracked:
    """Track every object of ``meas`` (sorted, ``starts`` offsets, >= 2 rows each) with the noise of its class and write
    the CSV to ``fh`` (with ``smooth``: the smoothed columns after ``flag``, module docstring). ``flag``: 1 on the rows
    of a detected divergence (``lgekf.apps.imm_monitor``), + ``SMOOTH_FAILED`` on every row of an object whose smoother
    gave a non-finite value (its smoothed columns then repeat the filter's). Returns the ``ImmTracked``."""
    opts = classes.noise[0][0]
    origin = meas.origin is not None
    fh.write((",".join(imm_columns(opts, origin, smooth)) + "\n").encode())
    lab = label_bytes(meas.labels)
    M = len(opts.modes)
    t = np.ascontiguousarray(meas.t, float)
    res = imm_track_classes(t, meas.z, starts, classes, omega_std, smooth, monitor)
    for b in res.smooth_failed:
        res.flag[starts[b]:starts[b + 1]] |= SMOOTH_FAILED
    col_digits, t_digits = output_digits(imm_columns(opts, origin, smooth)[2:], digits, meas.z, t)  # None: 0.1 mm, 1 µs
    motion = imm_motion(opts, res.c)
    parts = [res.c, res.sd, motion, res.mu]
    if origin:
        first, n_origin = 2 * res.c.shape[1] + motion.shape[1] + M, len(imm_origin_columns(opts))
        col_digits[first:first + n_origin] = 17
        parts.append(np.broadcast_to(np.asarray(meas.origin, dtype=float), (t.size, n_origin)))
    parts.append(res.flag[:, None])
    if smooth:
        parts.extend([res.c_smooth, res.sd_smooth, res.mu_smooth])
    fh.write(format_rows(lab, row_objects(starts, 0, len(starts) - 1), t, np.hstack(parts), col_digits, t_digits))
    if bar is not None:
        bar.update(t.size)
    return res


def tune_imm_classes(meas, starts, opts: ImmTrackOptions, meas_std: float | None, omega_std: float,
                     monitor: MonitorConfig | None = MonitorConfig(), say=None, method: str = "lbfgs"):
    """``--tune`` per class of objects: the classes of ``imm_noise`` (``lgekf.apps.defaults.noise_classes``), each
    class's IMM learned on its own objects (``tune_imm``). With one class the fit covers every object (a fit that
    cannot be made is the answer: ValueError). With several, the output has one set of mode columns, so one mode
    set: it is chosen (unless ``--imm-modes`` gives it) by the class with the most measurements among the mode sets
    compared, and the other classes fit that set; a class too small to learn keeps its noise from the data (that
    set with its data's noise × the levels; said in its line). Returns (``ImmClasses``, the ``NoiseClasses``, one
    summary per class)."""
    classes, found = imm_noise(meas, starts, opts, meas_std, omega_std, monitor)
    if len(found.plans) == 1:
        r, _, summary = tune_imm(meas, starts, opts, meas_std, omega_std, say=say, method=method)
        return ImmClasses.of_all(opts, r, meas.n_objects), found, [summary]
    t, z = np.asarray(meas.t), np.asarray(meas.z)
    switch = opts.switch if opts.switch_given else None
    chosen = opts.modes_text if opts.modes_given else None
    sizes = np.bincount(classes.of_object, weights=np.diff(starts),
                        minlength=len(found.plans))
    noise, summaries = [None] * len(found.plans), [None] * len(found.plans)
    for c in np.argsort(-sizes, kind="stable").tolist():  # the largest class first: it chooses the mode set
        rows, sub = objects_subset(starts, np.flatnonzero(classes.of_object == c))
        o = ImmTrackOptions(chosen, switch, opts.space)
        try:
            r, _, summary = tune_imm(SimpleNamespace(t=t[rows], z=z[rows]), sub, o, meas_std, omega_std, say=say,
                                     method=method)
        except ValueError as e:
            summaries[c] = f"class {c + 1}: not tuned ({e}): its noise from the data is kept"
            continue
        chosen = o.modes_text
        noise[c], summaries[c] = (o, r), f"class {c + 1}: " + summary
    for c, plan in enumerate(found.plans):
        if noise[c] is None:  # not tuned: the chosen mode set with the class's noise from the data
            o = ImmTrackOptions(chosen, switch, opts.space)
            o.with_learned_noise({m: q for m, q in plan.accel_std.items() if plan.accel_source.get(m) == "data"})
            noise[c] = (o, classes.noise[c][1])
    return ImmClasses(classes.of_object, noise), found, summaries


def imm_noise(meas, starts, opts: ImmTrackOptions, meas_std: float | None, omega_std: float,
              monitor: MonitorConfig | None = MonitorConfig()):
    """The noise the IMM runs with, from the data as for the single models (``lgekf.apps.defaults.plan_noise_by_class``):
    per class of objects the measurement std (``meas_std`` when given) and, for every model of a mode whose noise is a
    named level or the default, that model's process noise estimated from the data; the class's modes take it × their
    level factor (``ImmTrackOptions.with_learned_noise``: calm × 0.2, manoeuvre × 4 of the data's estimate instead of
    the model's fixed default). Returns (``ImmClasses``, the ``NoiseClasses``)."""
    from .defaults import plan_noise_by_class
    from .track import DEFAULT_HEADING_STD

    models = opts.tunable_models()
    position = measurement_in(opts.space, BASE_MEASUREMENT)  # the positions of the modes' space (position3 in 3-D)
    found = plan_noise_by_class(meas.t, meas.z, starts, models, meas_std=meas_std, omega_std=omega_std,
                                heading_std=DEFAULT_HEADING_STD, heading_cap=TRACK_HEADING_CAP, monitor=monitor,
                                measurement={m: position for m in models})
    noise = []
    for plan in found.plans:
        o = ImmTrackOptions(opts.modes_text if opts.modes_given else None, opts.switch if opts.switch_given else None,
                            opts.space)
        o.with_learned_noise({m: q for m, q in plan.accel_std.items() if plan.accel_source.get(m) == "data"})
        noise.append((o, float(plan.meas_std)))
    return ImmClasses(found.of_object, noise), found
