"""``lgekf track --model imm``: every object of a file through an IMM of registry models.

Each object starts like every ``lgekf track`` filter (the two-point estimate of its first two measurements in
the common coordinates, ``lgekf.apps.track.initial_common``; every mode converts it to its own coordinates)
and runs :func:`lgekf.estimators.imm.imm_batch` from its third measurement on. The measurement std is
``--meas-std`` or estimated from the data (``lgekf.apps.noise.measurement_std``, as for the filters); the modes'
process noise is given in ``--imm-modes`` (named levels × the model's default noise, or the stds). No
divergence monitor (the ``flag`` column is 0). Output columns: id, t, the combined estimate in the common
coordinates x, y, theta, vx, vy (body frame), omega, their stds, mu_<mode> (mode probabilities), and
origin_lat, origin_lon for lat/lon input, flag.

``--tune`` (:func:`tune_imm`): every distinct model of the modes whose noise is not given as numbers is fitted by
maximum likelihood on the file's own tracks (``lgekf.apps.smooth_track.tune_models``, as ``lgekf track MODEL
--tune``); a plain mode ``MODEL`` runs with the learned process noise, ``MODEL:calm`` / ``MODEL:manoeuvre`` with
the learned noise × their level factor (0.2, 4; ``lgekf.estimators.imm.NOISE_LEVELS``), ``MODEL:a/b/c`` keeps
its numbers. The measurement std is ``--meas-std`` when given (then held fixed in the fits), else the one
learned by the fit with the highest log-likelihood. Then the IMM itself is fitted by its own likelihood
(:func:`fit_imm`, ``lgekf.estimators.imm_tuning.learn_imm``): one factor per mode on that noise, and the
switching probability unless ``--imm-switch`` is given. Without ``--imm-modes`` the mode sets of
``TUNE_MODE_SETS`` are fitted (the default; CV calm and manoeuvring; those two and a manoeuvring SE(2)×R³) and
the one of lowest AIC is kept.

``--smooth``: after ``flag``, the IMM smoother's (``lgekf.estimators.imm_smoother``) combined estimate
``smooth_<x|y|theta|vx|vy|omega>``, its stds ``smooth_std_<...>`` and the smoothed mode probabilities
``smooth_mu_<mode>``; rows 0 and 1 of an object (its two-point start) repeat the filter columns, as for
``lgekf track --smooth``.
"""

from __future__ import annotations

import numpy as np

from ..estimators.imm import DEFAULT_SWITCH, NOISE_LEVELS, Mode, imm_batch, parse_modes, transition_matrix
from ..io.formatting import format_rows, label_bytes
from .track import DEFAULT_MEAS_STD, ORIGIN_COLUMNS, initial_common

__all__ = ["DEFAULT_TRACK_MODES", "TUNE_MODE_SETS", "ImmTrackOptions", "fit_imm", "imm_columns", "write_imm", "imm_track_common", "tune_imm",
           "common_world_velocity", "COMMON_NAMES", "IMM_FILTER"]

IMM_FILTER = "imm"  # its name in the tables of ``lgekf evaluate``

#: ``lgekf track --model imm`` / ``lgekf evaluate --imm`` modes by default: CV and a calm and a manoeuvring SE(2)×R³
#: (measured on the real-data evaluation against se2r3:calm,se2r3:manoeuvre and cv,se2r3, see README)
DEFAULT_TRACK_MODES = "cv,se2r3:calm,se2r3:manoeuvre"
COMMON_NAMES = ("x", "y", "theta", "vx", "vy", "omega")
#: the mode sets ``--tune`` fits when ``--imm-modes`` is not given; the one of lowest AIC is kept (README, real
#: data: two CV modes win on pedestrians, a manoeuvring SE(2)×R³ added to them or the default on cars and cyclists)
TUNE_MODE_SETS = (DEFAULT_TRACK_MODES, "cv:calm,cv:manoeuvre", "cv:calm,cv:manoeuvre,se2r3:manoeuvre")
#: at most about this many steps (whole tracks, a seeded random subset) enter the IMM's joint fit
FIT_MAX_STEPS = 20_000


class ImmTrackOptions:
    """The IMM of ``lgekf track``: modes (``parse_modes`` syntax) and the per-step switching probability."""

    def __init__(self, modes: str | None = None, switch: float | None = None):
        self.modes_given = modes is not None
        self.switch_given = switch is not None
        self.modes_text = DEFAULT_TRACK_MODES if modes is None else modes
        self.switch = DEFAULT_SWITCH if switch is None else float(switch)
        self.modes = parse_modes(self.modes_text)
        transition_matrix(len(self.modes), self.switch)

    def candidates(self) -> list:
        """The mode sets ``--tune`` fits: the given ``--imm-modes``, else every set of ``TUNE_MODE_SETS``."""
        return [self.modes_text] if self.modes_given else list(TUNE_MODE_SETS)

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


def _mode_columns(opts: ImmTrackOptions, prefix: str) -> list:
    mode_cols = []
    for m in opts.modes:
        base = f"{prefix}{m.name.replace(':', '_').replace('/', '-')}"
        name, k = base, 2
        while name in mode_cols:
            name, k = f"{base}_{k}", k + 1
        mode_cols.append(name)
    return mode_cols


def imm_columns(opts: ImmTrackOptions, origin: bool = False, smooth: bool = False) -> list:
    """The header of an IMM track file (module docstring); mode columns are named mu_<model>[_<label>]
    (the labels of modes given as numbers: their labels at the time of parsing, i.e. the numbers)."""
    smoothed = ([*(f"smooth_{s}" for s in COMMON_NAMES), *(f"smooth_std_{s}" for s in COMMON_NAMES),
                 *_mode_columns(opts, "smooth_mu_")] if smooth else [])
    return (["id", "t", *COMMON_NAMES, *(f"std_{s}" for s in COMMON_NAMES), *_mode_columns(opts, "mu_")]
            + (list(ORIGIN_COLUMNS) if origin else []) + ["flag"] + smoothed)


def imm_track_common(t, z, starts, meas_std: float, omega_std: float, opts: ImmTrackOptions, smooth: bool = False):
    """Every object's IMM estimate in the common coordinates: c (N, 6), their stds (N, 6), mode probabilities (N, M).

    Row 0 of an object is the two-point estimate at its first measurement's position, row 1 the two-point estimate
    (uniform mode probabilities), rows >= 2 the IMM's posteriors (as ``lgekf.apps.track.track_arrays``).
    With ``smooth`` also the smoothed (c, stds, mode probabilities) (rows 0, 1: the filter's), a 6-tuple.
    """
    if smooth:
        return _imm_track_smoothed(t, z, starts, meas_std, omega_std, opts)
    t = np.ascontiguousarray(t, float)
    z = np.ascontiguousarray(z, float)[:, :2]
    N, M = t.size, len(opts.modes)
    c = np.full((N, 6), np.nan)
    sd = np.full((N, 6), np.nan)
    mu = np.full((N, M), 1.0 / M)
    c0, var0 = initial_common(t, z, starts, meas_std, omega_std)
    for b in range(len(starts) - 1):
        a, e = int(starts[b]), int(starts[b + 1])
        c[a] = c0[b]  # as the filters of lgekf track: the two-point estimate, at the first measurement's position
        c[a, :2] = z[a]
        c[a + 1] = c0[b]
        sd[a:a + 2] = np.sqrt(var0[b])
        if e - a > 2:
            est, m, P = imm_batch(z[None, a + 2:e], opts.modes, opts.switch, dt=np.diff(t[a + 1:e])[None], meas_std=meas_std,
                                  x0=c0[b], P0=np.diag(var0[b]), return_cov=True)
            c[a + 2:e] = est[0]
            sd[a + 2:e] = np.sqrt(np.maximum(np.diagonal(P[0], axis1=1, axis2=2), 0.0))
            mu[a + 2:e] = m[0]
    return c, sd, mu


def _imm_track_smoothed(t, z, starts, meas_std: float, omega_std: float, opts: ImmTrackOptions):
    from ..estimators.imm_smoother import imm_smooth_batch

    t = np.ascontiguousarray(t, float)
    z = np.ascontiguousarray(z, float)[:, :2]
    N, M = t.size, len(opts.modes)
    c, sd, mu = np.full((N, 6), np.nan), np.full((N, 6), np.nan), np.full((N, M), 1.0 / M)
    c0, var0 = initial_common(t, z, starts, meas_std, omega_std)
    for b in range(len(starts) - 1):
        a, e = int(starts[b]), int(starts[b + 1])
        c[a] = c0[b]
        c[a, :2] = z[a]
        c[a + 1] = c0[b]
        sd[a:a + 2] = np.sqrt(var0[b])
    cs, sds, mus = c.copy(), sd.copy(), mu.copy()
    for b in range(len(starts) - 1):
        a, e = int(starts[b]), int(starts[b + 1])
        if e - a > 2:
            out = imm_smooth_batch(z[None, a + 2:e], opts.modes, opts.switch, dt=np.diff(t[a + 1:e])[None],
                                   meas_std=meas_std, x0=c0[b], P0=np.diag(var0[b]))
            for dst, dsd, dmu, key in ((c, sd, mu, "filt"), (cs, sds, mus, "smooth")):
                dst[a + 2:e] = out[f"c_{key}"][0]
                dsd[a + 2:e] = np.sqrt(np.maximum(np.diagonal(out[f"P_{key}"][0], axis1=1, axis2=2), 0.0))
                dmu[a + 2:e] = out[f"mu_{key}"][0]
    return c, sd, mu, cs, sds, mus


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
    from .smooth_track import data_starts, tune_models

    models = []
    for text in opts.candidates():
        for m in ImmTrackOptions(text).tunable_models():
            if m not in models:
                models.append(m)
    if not models:
        raise ValueError("--tune: every mode's noise is given as numbers in --imm-modes; nothing to learn")
    fits = tune_models(meas.t, meas.z, starts, models, {m: "position" for m in models}, meas_std, None, None, omega_std, method,
                       start_noise=data_starts(meas.t, meas.z, starts, models, meas_std, omega_std))
    best = max(fits, key=lambda m: fits[m].loglik)
    r = float(meas_std) if meas_std is not None else float(np.asarray(fits[best].meas_std).reshape(-1)[0])
    learned = "; ".join(f"{m} accel-std {','.join(f'{v:.3g}' for v in f.accel_std)} (log-likelihood {f.loglik:.6g}"
                        + (f"; not identified: {', '.join(f.problems)}" if f.problems else "") + ")" for m, f in fits.items())
    src = "given" if meas_std is not None else f"learned with {best}, the best log-likelihood"
    t = np.asarray(meas.t, float)
    z = np.asarray(meas.z, float)[:, :2]
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
    """The IMM fitted to ``tracks`` by its own likelihood (``lgekf.estimators.imm_tuning.learn_imm``), in place.

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
    from ..estimators.imm_tuning import learn_imm

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
        cand = ImmTrackOptions(text, opts.switch if opts.switch_given else None)
        cand.with_learned_noise({m: learned[m] for m in cand.tunable_models() if m in learned})
        fixed = [bool(m.label) and m.label not in NOISE_LEVELS for m in cand.modes]
        try:
            table.append((text, learn_imm(cand.modes, tracks, meas_std=meas_std, switch=cand.switch, omega_std=omega_std,
                                          fit_switch=not opts.switch_given, fixed=fixed)))
        except ValueError as e:
            table.append((text, str(e)))
    fitted = [(text, f) for text, f in table if not isinstance(f, str)]
    if not fitted:
        why = table[0][1] if len(table) == 1 else "; ".join(f"{text}: {f}" for text, f in table)
        raise ValueError(f"--tune: the IMM could not be fitted: {why}")
    text, fit = min(fitted, key=lambda tf: tf[1].aic)
    opts.modes_text, opts.modes, opts.switch = text, list(fit.modes), fit.switch
    return fit, table


def common_world_velocity(c: np.ndarray) -> np.ndarray:
    """World-frame velocity (N, 2) of common coordinates c (N, 6): R(θ)·(v_x, v_y)."""
    ct, st = np.cos(c[:, 2]), np.sin(c[:, 2])
    return np.stack([ct * c[:, 3] - st * c[:, 4], st * c[:, 3] + ct * c[:, 4]], axis=1)


def write_imm(fh, meas, starts, opts: ImmTrackOptions, meas_std: float, omega_std: float, digits: int, bar=None,
              smooth: bool = False) -> int:
    """Track every object of ``meas`` (sorted, ``starts`` offsets, >= 2 rows each) and write the CSV to ``fh``
    (with ``smooth``: the smoothed columns after ``flag``, module docstring)."""
    origin = meas.origin is not None
    fh.write((",".join(imm_columns(opts, origin, smooth)) + "\n").encode())
    lab = label_bytes(meas.labels)
    M = len(opts.modes)
    t = np.ascontiguousarray(meas.t, float)
    res = imm_track_common(t, meas.z, starts, meas_std, omega_std, opts, smooth)
    c, sd, mu = res[:3]
    ncol = 12 + M + (2 if origin else 0) + 1 + ((12 + M) if smooth else 0)
    col_digits = np.full(ncol, digits, dtype=np.int64)
    parts = [c, sd, mu]
    if origin:
        col_digits[12 + M:12 + M + 2] = 17
        parts.append(np.broadcast_to(np.asarray(meas.origin, dtype=float), (t.size, 2)))
    parts.append(np.zeros((t.size, 1)))
    if smooth:
        parts.extend(res[3:])
    fh.write(format_rows(lab, meas.obj, t, np.hstack(parts), col_digits))
    if bar is not None:
        bar.update(t.size)
    return int(starts[-1])


def imm_meas_std(meas, starts, given: float | None) -> tuple[float, str]:
    """The measurement std the IMM runs with and where it came from (given, data, default)."""
    from .noise import measurement_std

    if given is not None:
        return float(given), "given"
    est = measurement_std(meas.t, meas.z, starts)
    if est.usable:
        return float(est.meas_std), f"data: {est.describe()}"
    return float(DEFAULT_MEAS_STD), "default: " + (est.describe() if est.windows else "too few measurements to estimate it")
