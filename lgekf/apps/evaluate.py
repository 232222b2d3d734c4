"""Evaluate every registry filter on real ground-truth trajectories (`lgekf evaluate`).

Protocol
--------
* Every track of a dataset with at least ``min_length`` samples (default 5) is used; shorter ones are
  skipped and counted. Ground-truth positions get i.i.d. N(0, meas_std²) noise per axis (default
  0.3 m), one draw per seed (default 5 seeds); the same noisy measurements go to every filter.
* Each filter is initialised from the first two noisy measurements (``lgekf.apps.track``) and run over the
  rest with each step's own dt; its measurement std is the true ``meas_std``.
* Metric per track, seed and filter: RMSE over the filtered steps (rows k >= 2) of the position error
  and, where the dataset has velocity truth, of the world-frame velocity error.
* Mean and 95 % confidence interval: the seeds of one track share its trajectory, so they are not
  independent; each track's RMSE is first averaged over the seeds, the table gives the mean over the J
  tracks and a bootstrap interval over tracks (``bootstrap_ci``): the tracks are resampled with
  replacement ``BOOTSTRAP_RESAMPLES`` times (fixed seed ``BOOTSTRAP_SEED``, so reruns print the same
  numbers) and the interval is the expanded percentile interval of the resampled means (Hesterberg
  2015): percentiles α'/2 and 1 - α'/2 with Φ⁻¹(α'/2) = -√(J/(J-1))·t(0.975, J-1), which removes the
  percentile interval's narrowness at small J. A resampled mean of RMSEs is never negative, so neither
  is a bound (a t-interval, mean ± t·sd/√J, went below zero on skewed data with few tracks). "Δ vs CV"
  is the same bootstrap over the paired per-track differences filter - CV. With fewer than
  ``MIN_TRACKS_CI`` (5) tracks there is no interval ("n/a (J tracks)"): in simulations with lognormal
  per-track RMSEs (log-std 0.2-0.5) the coverage was 0.89-0.94 for J = 5 ... 20, close to the
  t-interval's, but about 0.72 at J = 3. A few lost tracks among many good ones (a heavy right tail)
  make any interval over few tracks optimistic (coverage about 0.6 at J = 10 in the same simulations).
* Process noise: the defaults of ``lgekf.apps.track.DEFAULT_ACCEL_STD``, or with ``tune`` values chosen per
  filter and dataset on a tuning split = the first 30 % of the tracks (in order of first appearance, i.e.
  the earliest part of a recording), with separate noise seeds; all reported numbers then come from
  the other 70 % only. The search (mean position RMSE on the tuning split) is over accel_std =
  k · default, with the turn-rate entry (σ_ω of the LG models, σ_ω̇ of CTRV) further multiplied by ρ:
  (1) k in 2^-3 ... 2^4 by factors √2 with ρ = 1 (all filters); (2) ρ in 2^-6 ... 2^3 by factors 2 at
  that k (LG, CTRV); (3) k again over its grid at the chosen ρ. CV has only k.

* ``tune_method="mle"`` (the default of ``lgekf evaluate --tune``): each filter's process noise is instead
  learned by maximum likelihood (``lgekf.estimators.noise.tuning.learn_noise``) from the noisy measurements of the
  tuning split (every seed's draw a track of its own, noise stream 1), with the measurement std held at the
  known ``meas_std``; ``"grid"`` is the search above. ``smooth=True`` adds a row ``<model>:smoothed`` per
  filter: the RTS smoother on the group (``lgekf.apps.smooth_track``) on the same measurements and noise,
  scored on the same rows.

Datasets: ``lgekf.io.datasets``; intervals: ``lgekf.experiments.statistics``.
"""

from __future__ import annotations

import zlib
from dataclasses import dataclass, field

import numpy as np

from ..core.registry import DEFAULT_SPACE, MODELS, SPACES, get_model, models_of
from ..core.common import euler_rotations
from ..experiments.statistics import bootstrap_ci
from ..io.datasets import Dataset
from ..io.readers import DataError
from .track import DEFAULT_ACCEL_STD, TrackConfig, Tracked, own_measurement, smoothing_inputs, speed_course, track_arrays
from .track_imm import IMM_FILTER, common_world_velocity, imm_track_common

__all__ = [
    "evaluate_dataset", "run_filters", "track_rmse", "world_velocity", "tune_split", "DatasetResult",
    "FILTERS", "TURNING", "BASELINE", "filters_of", "baseline_of", "motion_errors", "MOTION_METRICS", "COURSE_MIN_SPEED",
]

FILTERS = tuple(MODELS)
TUNE_SCALES = tuple(float(2.0**e) for e in np.arange(-3.0, 4.01, 0.5))
TUNE_RATIOS = tuple(float(2.0**e) for e in np.arange(-6.0, 3.01, 1.0))
TURNING = tuple(m for m, spec in MODELS.items() if "w" in spec.matched_noise)  # models with a rotational noise std
BASELINE = "cv"  # the paired differences are against this filter (the paper's simplest baseline)
TUNE_FRACTION = 0.3
#: the motion errors of a 3-D dataset (``motion_errors``): name -> unit
MOTION_METRICS = {"speed": "m/s", "course": "rad", "climb": "m/s", "turn_rate": "rad/s", "attitude": "rad"}
COURSE_MIN_SPEED = 1.0  # m/s: the course (and the turn rate) is scored where the truth's horizontal speed is at least this


def filters_of(ds: Dataset) -> tuple:
    """The filters evaluated on a dataset: every registered model of its space (``FILTERS`` in the plane)."""
    return tuple(models_of(ds.space))


def baseline_of(space: str) -> str:
    """The baseline of the paired differences in ``space``: CV, or the model of that space that lifts it (CV3)."""
    return next(m for m, spec in models_of(space).items() if BASELINE in (m, spec.lifts))


def _seed_means(err: np.ndarray) -> np.ndarray:
    """Each track's mean over the seeds of its finite values: (S, J) -> (J,), nan for a track with none (a car at rest
    has no course to score)."""
    ok = np.isfinite(err)
    n = ok.sum(axis=0)
    return np.where(n > 0, np.where(ok, err, 0.0).sum(axis=0) / np.maximum(n, 1), np.nan)


def _turning(model: str) -> bool:
    """Whether the model has a rotational noise std (the grid search's ρ applies to it)."""
    return "w" in get_model(model).matched_noise


# ------------------------------------------------------------------------------------ datasets
def world_velocity(model: str, x: np.ndarray) -> np.ndarray:
    """World-frame velocity (N, d) from a model's physical states (N, n) (generated world_velocity; d = 2 in the plane,
    3 in 3-D space)."""
    out = np.empty((x.shape[0], SPACES[get_model(model).space]["dim"]))
    get_model(model).kernels.world_velocities(np.ascontiguousarray(x, dtype=float), out)
    return out


def _seed_rng(seed, stream, name):
    return np.random.default_rng([int(seed), int(stream), zlib.crc32(name.encode())])


def _per_track_rmse(ds: Dataset, err2: np.ndarray, rows=None) -> np.ndarray:
    """RMSE per track over rows k >= 2 of each track (and among ``rows`` (N,) bool when given: the rows where the
    quantity is scored; a track without such a row: nan)."""
    J = ds.n_tracks
    obj = np.repeat(np.arange(J), np.diff(ds.starts))
    k = np.arange(ds.t.size) - ds.starts[obj]
    w = (k >= 2).astype(float)
    if rows is not None:
        w = w * rows
        err2 = np.where(rows, err2, 0.0)
    num = np.bincount(obj, weights=err2 * w, minlength=J)
    den = np.bincount(obj, weights=w, minlength=J)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.sqrt(num / den)


def motion_errors(model: str, x: np.ndarray, ds: Dataset) -> dict:
    """Squared errors (N,) of a 3-D track's motion against the dataset's truth, and the rows each is scored on:
    {name: (err2, rows)} for the names of ``MOTION_METRICS``:

    * speed |v| (m/s), climb rate v_z (m/s), turn rate (rad/s, the course's rate: ``lgekf.apps.track.turn_rates``;
      truth ``ds.w``) and course atan2(v_y, v_x) (rad, wrapped to ±π) from the model's state (``speed_course``), the
      course and turn rate only where the truth's horizontal speed is at least ``COURSE_MIN_SPEED`` (a car at rest
      has no course);
    * attitude: the angle of R_est⁻¹ R_true (rad, the geodesic distance on SO(3)) for a model with an attitude
      (roll, pitch, yaw in its state), absent for the others.
    """
    mot = speed_course(model, x)  # speed, course, climb, turn rate
    v = ds.v
    hs = np.hypot(v[:, 0], v[:, 1])
    moving = hs >= COURSE_MIN_SPEED
    dchi = np.angle(np.exp(1j * (mot[:, 1] - np.arctan2(v[:, 1], v[:, 0]))))
    out = {"speed": ((mot[:, 0] - np.sqrt(np.sum(v ** 2, axis=1))) ** 2, None), "course": (dchi ** 2, moving),
           "climb": ((mot[:, 2] - v[:, 2]) ** 2, None)}
    if ds.w is not None:
        out["turn_rate"] = ((mot[:, 3] - ds.w) ** 2, moving & np.isfinite(mot[:, 3]))
    names = list(get_model(model).state_names)
    if ds.attitude is not None and all(a in names for a in ("roll", "pitch", "yaw")):
        est = x[:, [names.index(a) for a in ("roll", "pitch", "yaw")]]
        out["attitude"] = (_rotation_angle(est, ds.attitude) ** 2, None)
    return out


def _rotation_angle(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """(N,): the angle of the rotation R(a)ᵀ R(b) between two attitudes given as Euler angles (N, 3), in [0, π]."""
    tr = np.einsum("nij,nij->n", euler_rotations(a), euler_rotations(b))  # trace(R_aᵀ R_b)
    return np.arccos(np.clip(0.5 * (tr - 1.0), -1.0, 1.0))


def track_rmse(ds: Dataset, zs, cfg: TrackConfig, models=FILTERS, imm=None, motion=None):
    """Every model on the noisy measurements ``zs`` (one (N, d) array per seed) of the tracks of ``ds``.

    Returns dict model -> (pos (S, J), vel (S, J) | None), per seed and track. Each track is filtered
    and scored on its own, so the result for a subset of the tracks is the same subset of this one (the
    Dask runner of ``lgekf.apps.evaluate_dask`` relies on it). ``motion``: a dict filled, for a 3-D dataset with
    velocity truth, with model -> {name: RMSE (S, J)} of ``motion_errors``.
    """
    S = len(zs)
    d = ds.p.shape[1]
    out = {m: (np.empty((S, ds.n_tracks)), None if ds.v is None else np.empty((S, ds.n_tracks))) for m in models}
    for si, z in enumerate(zs):
        for m in models:
            base, _, variant = m.partition(":")  # "<model>:smoothed": the RTS smoother of the model
            if m == IMM_FILTER:  # lgekf.apps.track_imm: the IMM of ``imm`` (ImmTrackOptions)
                x, _, _ = imm_track_common(ds.t, z, ds.starts, cfg.meas_std, cfg.omega_std, imm)
                vel = common_world_velocity(x) if ds.v is not None else None
            else:
                x, p, nis = track_arrays(base, ds.t, z, ds.starts, cfg)
                if variant == "smoothed":
                    from .smooth_track import smoothed_columns

                    zm, q, r = smoothing_inputs(base, z, cfg)
                    x = smoothed_columns(base, own_measurement(base, "position"), ds.t, zm, ds.starts, Tracked(x, p, nis, None, []),
                                         q, r)[0][:, :get_model(base).n]
                vel = world_velocity(base, x) if ds.v is not None else None
                if motion is not None and d == 3 and ds.v is not None:
                    for name, (err2, rows) in motion_errors(base, x, ds).items():
                        motion.setdefault(m, {}).setdefault(name, np.full((S, ds.n_tracks), np.nan))[si] = _per_track_rmse(ds, err2, rows)
            out[m][0][si] = _per_track_rmse(ds, np.sum((x[:, :d] - ds.p) ** 2, axis=1))
            if ds.v is not None:
                out[m][1][si] = _per_track_rmse(ds, np.sum((vel - ds.v) ** 2, axis=1))
    return out


def run_filters(ds: Dataset, cfg: TrackConfig, seeds, stream, models=FILTERS, runner=None, imm=None, motion=None):
    """Position (and velocity) RMSE per (model, seed, track): dict model -> (pos (S, J), vel (S, J) | None).

    ``runner``: None, or a callable with ``track_rmse``'s signature that computes it elsewhere (Dask). ``motion``: a
    dict filled with the 3-D motion errors (``track_rmse``; not with a runner).
    """
    if runner is not None and ds.space != DEFAULT_SPACE:
        raise ValueError("--workers/--scheduler: the evaluation of a 3-D dataset runs in one process (yet)")
    zs = []
    meas = np.empty((len(seeds), ds.n_tracks))
    for si, seed in enumerate(seeds):
        rng = _seed_rng(seed, stream, ds.name)
        z = ds.p + cfg.meas_std * rng.standard_normal(ds.p.shape)
        meas[si] = _per_track_rmse(ds, np.sum((z - ds.p) ** 2, axis=1))
        zs.append(z)
    if imm is not None and not SPACES[ds.space]["mixes"]:
        raise ValueError(f"--imm: the IMM does not mix the models of the dataset's space ({ds.space})")
    if imm is not None:
        imm = imm.for_space(ds.space)  # the modes of the dataset's space (its default ones unless --imm-modes)
    if runner is not None and imm is None:
        out = runner(ds, zs, cfg, models)
    else:
        out = track_rmse(ds, zs, cfg, models if imm is None else (*models, IMM_FILTER), imm, motion)
    out["measurements"] = (meas, None)
    return out


def accel_std_for(model, k=1.0, rho=1.0):
    """k · default accel_std, the turn-rate entry (the last one of the LG and CTRV models) also times ρ."""
    q = [k * v for v in DEFAULT_ACCEL_STD[model]]
    if _turning(model):
        q[-1] *= rho
    return tuple(q)


def _scaled(scale: dict, meas_std):
    """TrackConfig from {model: (k, ρ)}."""
    return TrackConfig({m: accel_std_for(m, *scale.get(m, (1.0, 1.0))) for m in scale}, meas_std).validate()


def tune_split(n_tracks: int):
    """(tuning track indices, evaluation track indices): the first 30 % of the tracks tune."""
    k = max(1, int(round(TUNE_FRACTION * n_tracks)))
    if n_tracks - k < 2:
        raise DataError(f"--tune needs at least 4 tracks (2 to evaluate), got {n_tracks}")
    return np.arange(k), np.arange(k, n_tracks)


@dataclass
class DatasetResult:
    dataset: Dataset  # the evaluated tracks
    noise: str  # "default" or "tuned"
    scale: dict  # model -> (k, ρ)
    rmse: dict  # model -> (pos (S, J), vel (S, J) | None)
    tuning: list = field(default_factory=list)  # (model, stage, k, ρ, mean pos rmse on the tuning split)
    n_tune_tracks: int = 0
    accel: dict | None = None  # model -> accel_std when learned (tune_method "mle"), else k·default (scale)
    fits: dict = field(default_factory=dict)  # model -> NoiseFit, or why it could not be learned (tune_method "mle")
    imm_sets: list = field(default_factory=list)  # the fitted IMM's candidate mode sets: (text, ImmFit or why not, kept)
    motion: dict = field(default_factory=dict)  # model -> {name: RMSE (S, J)} (3-D datasets: ``motion_errors``)

    def summary(self):
        rows = []
        base = np.nanmean(self.rmse[baseline_of(self.dataset.space)][0], axis=0)
        for m_row, (pos, vel) in self.rmse.items():
            m = m_row.split(":")[0]  # a smoothed row's settings are its model's
            per_track = np.nanmean(pos, axis=0)
            diverged = int(np.sum(~np.isfinite(pos)))
            ok = np.isfinite(per_track)
            pm, plo, phi = bootstrap_ci(per_track[ok])
            pmed = float(np.median(per_track[ok])) if ok.any() else float("nan")
            row = {
                "dataset": self.dataset.name, "filter": m_row, "noise": self.noise if m != "measurements" else "-",
                "scale": self.scale[m][0] if m in self.scale else float("nan"),
                "turn_ratio": self.scale[m][1] if m in self.scale else float("nan"),
                "accel_std": ";".join(f"{v:.4g}" for v in (self.accel[m] if self.accel and m in self.accel else accel_std_for(m, *self.scale[m])))
                if m in self.scale else "",
                "tracks": self.dataset.n_tracks, "skipped_short": self.dataset.skipped, "seeds": pos.shape[0],
                "diverged": diverged, "pos_rmse": pm, "pos_ci_lo": plo, "pos_ci_hi": phi, "pos_median": pmed,
                "pos_n": int(ok.sum()),
            }
            d = per_track - base
            row["dpos_n"] = int(np.isfinite(d).sum())
            row["dpos_vs_cv"], row["dpos_ci_lo"], row["dpos_ci_hi"] = bootstrap_ci(d[np.isfinite(d)])
            if vel is not None:
                vt = np.nanmean(vel, axis=0)
                row["vel_n"] = int(np.isfinite(vt).sum())
                row["vel_rmse"], row["vel_ci_lo"], row["vel_ci_hi"] = bootstrap_ci(vt[np.isfinite(vt)])
            else:
                row["vel_rmse"] = row["vel_ci_lo"] = row["vel_ci_hi"] = float("nan")
                row["vel_n"] = 0
            for name in MOTION_METRICS if self.dataset.space != DEFAULT_SPACE else ():
                err = self.motion.get(m_row, {}).get(name)  # (S, J)
                per = _seed_means(err) if err is not None else np.full(1, np.nan)
                row[f"{name}_rmse"] = float(np.mean(per[np.isfinite(per)])) if np.isfinite(per).any() else float("nan")
            rows.append(row)
        return rows


def _imm_fitted(imm, dtune, meas_std: float, seed_list, omega_std: float, fits: dict):
    """A copy of the IMM options fitted on the tuning split by the IMM's own likelihood
    (``lgekf.apps.track_imm.fit_imm``: each candidate mode set from its models' learned noise, the lowest AIC
    kept), the fit, and every candidate set as (text, ImmFit or why it could not be fitted, kept); (None, None, [])
    without an IMM. When it cannot be fitted (too few steps, nothing free) the modes take their models' learned
    noise × level as given and the fit is the reason (a str)."""
    if imm is None:
        return None, None, []
    import copy

    from .smooth_track import noisy_tracks
    from .track_imm import fit_imm

    tuned = copy.deepcopy(imm)
    learned = {m: f.accel_std for m, f in fits.items() if not isinstance(f, str)}
    try:
        fit, table = fit_imm(tuned, noisy_tracks(dtune, meas_std, seed_list, _seed_rng), meas_std, omega_std, learned)
    except ValueError as e:
        tuned = copy.deepcopy(imm)
        tuned.with_learned_noise({m: learned[m] for m in tuned.tunable_models() if m in learned})
        return tuned, str(e), []
    return tuned, fit, [(text, f, f is fit) for text, f in table]


def evaluate_dataset(ds: Dataset, *, meas_std=0.3, seeds=5, base_seed=0, tune=False, progress=None, runner=None,
                     tune_method="mle", smooth=False, imm=None):
    """Default-noise result (all tracks, or the evaluation split when tuning) and, with ``tune``, the tuned one.

    ``runner``: passed to ``run_filters`` (None: everything in this process). ``tune_method``: "grid",
    "mle" or "em" (as "mle", with EM for the linear Gaussian models, ``lgekf.estimators.noise.em``);
    ``smooth``: also the ``<model>:smoothed`` rows (module docstring). ``imm``: an
    ``lgekf.apps.track_imm.ImmTrackOptions`` adds an "imm" row: with its modes' noise as given there in the
    default run, and with ``tune`` (MLE) in the tuned run fitted on the tuning split by its own likelihood
    (``_imm_fitted``; the fit is in the tuned result's ``fits["imm"]``). The grid search does not tune the IMM.
    """
    if imm is not None and runner is not None:
        raise ValueError("--imm: not with --workers/--scheduler (the IMM runs in one process)")
    if imm is not None and SPACES[ds.space]["mixes"]:
        imm = imm.for_space(ds.space)  # the modes of the dataset's space (its default ones unless --imm-modes)
    seed_list = [base_seed + s for s in range(seeds)]
    filters = filters_of(ds)  # the models of the dataset's space
    turning = tuple(m for m in filters if _turning(m))
    default = {m: (1.0, 1.0) for m in filters}
    models = filters + (tuple(f"{m}:smoothed" for m in filters) if smooth else ())

    def run(d, cfg, stream=0, models=models, imm=imm):  # run_filters with the 3-D motion errors kept
        motion = {}
        rmse = run_filters(d, cfg, seed_list, stream, models=models, runner=runner, imm=imm, motion=None if runner else motion)
        return rmse, motion

    if not tune:
        rmse, motion = run(ds, _scaled(default, meas_std))
        return [DatasetResult(ds, "default", default, rmse, motion=motion)]
    tune_idx, eval_idx = tune_split(ds.n_tracks)
    dtune, deval = ds.subset(tune_idx), ds.subset(eval_idx)
    if tune_method in ("mle", "em"):
        from .smooth_track import learn_on_dataset

        fits = learn_on_dataset(dtune, meas_std, seed_list, _seed_rng, filters, method="em" if tune_method == "em" else "lbfgs")
        accel = {m: DEFAULT_ACCEL_STD[m] if isinstance(fits[m], str) else fits[m].accel_std for m in filters}
        cfg = TrackConfig(dict(accel), meas_std).validate()
        imm_tuned, imm_fit, imm_sets = _imm_fitted(imm, dtune, meas_std, seed_list, cfg.omega_std, fits)
        if progress:
            progress(1)
        rmse, motion = run(deval, _scaled(default, meas_std))
        out = [DatasetResult(deval, "default", default, rmse, [], len(tune_idx), motion=motion)]
        rmse, motion = run(deval, cfg, imm=imm_tuned)
        out.append(DatasetResult(deval, "tuned", default, rmse, [], len(tune_idx), accel,
                                 dict(fits, imm=imm_fit) if imm_fit is not None else fits, imm_sets, motion=motion))
        return out
    tuning = []
    best = {m: (float("inf"), (1.0, 1.0)) for m in filters}

    def score(stage, configs, models):
        """configs: list of {model: (k, ρ)}; evaluates each on the tuning split (noise stream 1)."""
        for conf in configs:
            res = run_filters(dtune, _scaled(conf, meas_std), seed_list, 1, models=models, runner=runner)
            for m in models:
                per_track = np.nanmean(res[m][0], axis=0)
                val = float(np.mean(per_track)) if np.all(np.isfinite(per_track)) else float("inf")
                tuning.append((m, stage, *conf[m], val))
                if val < best[m][0]:
                    best[m] = (val, conf[m])
            if progress:
                progress(stage)

    score(1, [{m: (k, 1.0) for m in filters} for k in TUNE_SCALES], filters)
    score(2, [{m: (best[m][1][0], r) for m in turning} for r in TUNE_RATIOS], turning)
    score(3, [{m: (k, best[m][1][1]) for m in turning} for k in TUNE_SCALES], turning)
    chosen = {m: best[m][1] for m in filters}
    out = []
    for noise, scale in (("default", default), ("tuned", chosen)):
        rmse, motion = run(deval, _scaled(scale, meas_std))
        out.append(DatasetResult(deval, noise, scale, rmse, tuning, len(tune_idx), motion=motion))
    return out


# ------------------------------------------------------------------------------------ output
