"""Evaluate every registry filter on real ground-truth trajectories (`lgekf evaluate`).

Protocol
--------
* Every track of a dataset with at least ``min_length`` samples (default 5) is used; shorter ones are
  skipped and counted. Ground-truth positions get i.i.d. N(0, meas_std²) noise per axis (default
  0.3 m), one draw per seed (default 5 seeds); the same noisy measurements go to every filter.
* Each filter is initialised from the first two noisy measurements (``lgekf.track``) and run over the
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
* Process noise: the defaults of ``lgekf.track.DEFAULT_ACCEL_STD``, or with ``tune`` values chosen per
  filter and dataset on a tuning split = the first 30 % of the tracks (in order of first appearance, i.e.
  the earliest part of a recording), with separate noise seeds; all reported numbers then come from
  the other 70 % only. The search (mean position RMSE on the tuning split) is over accel_std =
  k · default, with the turn-rate entry (σ_ω of the LG models, σ_ω̇ of CTRV) further multiplied by ρ:
  (1) k in 2^-3 ... 2^4 by factors √2 with ρ = 1 (all filters); (2) ρ in 2^-6 ... 2^3 by factors 2 at
  that k (LG, CTRV); (3) k again over its grid at the chosen ρ. CV has only k.

Datasets: ``lgekf.io.datasets``; intervals: ``lgekf.experiments.statistics``.
"""

from __future__ import annotations

import csv
import io
import math
import zlib
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..core.registry import MODELS, get_model
from ..experiments.statistics import MIN_TRACKS_CI, bootstrap_ci
from ..io.datasets import Dataset
from ..io.readers import DataError
from .track import DEFAULT_ACCEL_STD, TrackConfig, track_arrays

__all__ = [
    "evaluate_dataset", "run_filters", "track_rmse", "world_velocity", "tune_split", "DatasetResult", "format_table", "markdown_table",
    "evaluation_figure", "FILTERS", "TURNING", "BASELINE",
]

FILTERS = tuple(MODELS)
TUNE_SCALES = tuple(float(2.0**e) for e in np.arange(-3.0, 4.01, 0.5))
TUNE_RATIOS = tuple(float(2.0**e) for e in np.arange(-6.0, 3.01, 1.0))
TURNING = tuple(m for m, spec in MODELS.items() if "w" in spec.matched_noise)  # models with a rotational noise std
BASELINE = "cv"  # the paired differences are against this filter (the paper's simplest baseline)
TUNE_FRACTION = 0.3


# ------------------------------------------------------------------------------------ datasets
def world_velocity(model: str, x: np.ndarray) -> np.ndarray:
    """World-frame velocity (N, 2) from a model's physical states (N, n) (generated world_velocity)."""
    out = np.empty((x.shape[0], 2))
    get_model(model).kernels.world_velocities(np.ascontiguousarray(x, dtype=float), out)
    return out


def _seed_rng(seed, stream, name):
    return np.random.default_rng([int(seed), int(stream), zlib.crc32(name.encode())])


def _per_track_rmse(ds: Dataset, err2: np.ndarray) -> np.ndarray:
    """RMSE per track over rows k >= 2 of each track."""
    J = ds.n_tracks
    obj = np.repeat(np.arange(J), np.diff(ds.starts))
    k = np.arange(ds.t.size) - ds.starts[obj]
    w = (k >= 2).astype(float)
    num = np.bincount(obj, weights=err2 * w, minlength=J)
    den = np.bincount(obj, weights=w, minlength=J)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.sqrt(num / den)


def track_rmse(ds: Dataset, zs, cfg: TrackConfig, models=FILTERS):
    """Every model on the noisy measurements ``zs`` (one (N, 2) array per seed) of the tracks of ``ds``.

    Returns dict model -> (pos (S, J), vel (S, J) | None), per seed and track. Each track is filtered
    and scored on its own, so the result for a subset of the tracks is the same subset of this one (the
    Dask runner of ``lgekf.apps.evaluate_dask`` relies on it).
    """
    S = len(zs)
    out = {m: (np.empty((S, ds.n_tracks)), None if ds.v is None else np.empty((S, ds.n_tracks))) for m in models}
    for si, z in enumerate(zs):
        for m in models:
            x, _, _ = track_arrays(m, ds.t, z, ds.starts, cfg)
            out[m][0][si] = _per_track_rmse(ds, np.sum((x[:, :2] - ds.p) ** 2, axis=1))
            if ds.v is not None:
                out[m][1][si] = _per_track_rmse(ds, np.sum((world_velocity(m, x) - ds.v) ** 2, axis=1))
    return out


def run_filters(ds: Dataset, cfg: TrackConfig, seeds, stream, models=FILTERS, runner=None):
    """Position (and velocity) RMSE per (model, seed, track): dict model -> (pos (S, J), vel (S, J) | None).

    ``runner``: None, or a callable with ``track_rmse``'s signature that computes it elsewhere (Dask).
    """
    zs = []
    meas = np.empty((len(seeds), ds.n_tracks))
    for si, seed in enumerate(seeds):
        rng = _seed_rng(seed, stream, ds.name)
        z = ds.p + cfg.meas_std * rng.standard_normal(ds.p.shape)
        meas[si] = _per_track_rmse(ds, np.sum((z - ds.p) ** 2, axis=1))
        zs.append(z)
    out = (runner or track_rmse)(ds, zs, cfg, models)
    out["measurements"] = (meas, None)
    return out


def accel_std_for(model, k=1.0, rho=1.0):
    """k · default accel_std, the turn-rate entry (the last one of the LG and CTRV models) also times ρ."""
    q = [k * v for v in DEFAULT_ACCEL_STD[model]]
    if model in TURNING:
        q[-1] *= rho
    return tuple(q)


def _scaled(scale: dict, meas_std):
    """TrackConfig from {model: (k, ρ)}."""
    return TrackConfig({m: accel_std_for(m, *scale.get(m, (1.0, 1.0))) for m in FILTERS}, meas_std).validate()


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

    def summary(self):
        rows = []
        base = np.nanmean(self.rmse[BASELINE][0], axis=0)
        for m, (pos, vel) in self.rmse.items():
            per_track = np.nanmean(pos, axis=0)
            diverged = int(np.sum(~np.isfinite(pos)))
            ok = np.isfinite(per_track)
            pm, plo, phi = bootstrap_ci(per_track[ok])
            pmed = float(np.median(per_track[ok])) if ok.any() else float("nan")
            row = {
                "dataset": self.dataset.name, "filter": m, "noise": self.noise if m != "measurements" else "-",
                "scale": self.scale[m][0] if m in self.scale else float("nan"),
                "turn_ratio": self.scale[m][1] if m in self.scale else float("nan"),
                "accel_std": ";".join(f"{v:.4g}" for v in accel_std_for(m, *self.scale[m])) if m in self.scale else "",
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
            rows.append(row)
        return rows


def evaluate_dataset(ds: Dataset, *, meas_std=0.3, seeds=5, base_seed=0, tune=False, progress=None, runner=None):
    """Default-noise result (all tracks, or the evaluation split when tuning) and, with ``tune``, the tuned one.

    ``runner``: passed to ``run_filters`` (None: everything in this process).
    """
    seed_list = [base_seed + s for s in range(seeds)]
    default = {m: (1.0, 1.0) for m in FILTERS}
    if not tune:
        return [DatasetResult(ds, "default", default, run_filters(ds, _scaled(default, meas_std), seed_list, 0, runner=runner))]
    tune_idx, eval_idx = tune_split(ds.n_tracks)
    dtune, deval = ds.subset(tune_idx), ds.subset(eval_idx)
    tuning = []
    best = {m: (float("inf"), (1.0, 1.0)) for m in FILTERS}

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

    score(1, [{m: (k, 1.0) for m in FILTERS} for k in TUNE_SCALES], FILTERS)
    score(2, [{m: (best[m][1][0], r) for m in TURNING} for r in TUNE_RATIOS], TURNING)
    score(3, [{m: (k, best[m][1][1]) for m in TURNING} for k in TUNE_SCALES], TURNING)
    chosen = {m: best[m][1] for m in FILTERS}
    out = []
    for noise, scale in (("default", default), ("tuned", chosen)):
        out.append(DatasetResult(deval, noise, scale, run_filters(deval, _scaled(scale, meas_std), seed_list, 0, runner=runner), tuning,
                                 len(tune_idx)))
    return out


# ------------------------------------------------------------------------------------ output
SUMMARY_FIELDS = ["dataset", "filter", "noise", "scale", "turn_ratio", "accel_std", "tracks", "skipped_short", "seeds", "diverged",
                  "pos_rmse", "pos_ci_lo", "pos_ci_hi", "pos_median", "dpos_vs_cv", "dpos_ci_lo", "dpos_ci_hi",
                  "vel_rmse", "vel_ci_lo", "vel_ci_hi"]


def _fmt(v, nd=4):
    if isinstance(v, float):
        return "" if math.isnan(v) else f"{v:.{nd}f}"
    return str(v)


def interval_text(row, key: str, signed: bool = False) -> str:
    """"mean [lo, hi]" of a summary row, or "mean n/a (J tracks)" when there are too few tracks.

    ``key`` is "pos", "dpos" or "vel" (the mean is ``pos_rmse``, ``dpos_vs_cv``, ``vel_rmse``).
    """
    mean = row[{"pos": "pos_rmse", "dpos": "dpos_vs_cv", "vel": "vel_rmse"}[key]]
    f = "+.3f" if signed else ".3f"
    if math.isnan(mean):
        return "n/a"
    lo, hi = row[f"{key}_ci_lo"], row[f"{key}_ci_hi"]
    if math.isnan(lo) or math.isnan(hi):
        n = row[f"{key}_n"]
        return f"{mean:{f}} n/a ({n} track{'' if n == 1 else 's'})"
    return f"{mean:{f}} [{lo:{f}}, {hi:{f}}]"


def format_table(rows) -> str:
    has_vel = any(not math.isnan(r["vel_rmse"]) for r in rows)
    head = f"{'dataset':<10} {'filter':<12} {'noise':<8} {'accel_std':<16} {'tracks':>6}  {'pos RMSE [95% CI] (m)':<26} {'median':>6}  {'Δ vs CV [95% CI] (m)':<28}"
    if has_vel:
        head += f" {'vel RMSE [95% CI] (m/s)':<26}"
    lines = [head, "-" * len(head)]
    for r in rows:
        pos = interval_text(r, "pos")
        dlt = "" if r["filter"] in (BASELINE, "measurements") else interval_text(r, "dpos", signed=True)
        line = f"{r['dataset']:<10} {r['filter']:<12} {r['noise']:<8} {r['accel_std']:<16} {r['tracks']:>6}  {pos:<26} {r['pos_median']:>6.3f}  {dlt:<28}"
        if has_vel:
            line += " " + ("" if math.isnan(r["vel_rmse"]) else interval_text(r, "vel"))
        lines.append(line.rstrip())
    return "\n".join(lines)


def markdown_table(rows) -> str:
    has_vel = any(not math.isnan(r["vel_rmse"]) for r in rows)
    head = "| dataset | filter | noise (σ) | tracks | pos RMSE m [95 % CI] | median | Δ vs CV m [95 % CI] |" + (" vel RMSE m/s [95 % CI] |" if has_vel else "")
    sep = "|---|---|---|---|---|---|---|" + ("---|" if has_vel else "")
    lines = [head, sep]
    for r in rows:
        noise = "-" if r["filter"] == "measurements" else f"{r['noise']} ({r['accel_std'].replace(';', ', ')})"
        pos = interval_text(r, "pos")
        dlt = "" if r["filter"] in (BASELINE, "measurements") else interval_text(r, "dpos", signed=True)
        line = f"| {r['dataset']} | {r['filter']} | {noise} | {r['tracks']} | {pos} | {r['pos_median']:.3f} | {dlt} |"
        if has_vel:
            line += " " + ("" if math.isnan(r["vel_rmse"]) else interval_text(r, "vel")) + " |"
        lines.append(line)
    return "\n".join(lines)


def _csv_text(fieldnames, rows) -> str:
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(fieldnames)
    for r in rows:
        w.writerow([_fmt(r[k], 6) if isinstance(r[k], float) else r[k] for k in fieldnames])
    return buf.getvalue()


def evaluation_figure(rows, path: Path, noise: str):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows = [r for r in rows if r["noise"] in (noise, "-")]
    datasets = list(dict.fromkeys(r["dataset"] for r in rows))
    vel_sets = [d for d in datasets if any(r["dataset"] == d and not math.isnan(r["vel_rmse"]) for r in rows)]
    names = [*FILTERS, "measurements"]
    panels = [("pos", datasets, "m")] + ([("vel", vel_sets, "m/s")] if vel_sets else [])
    widths = [len(d) + 0.6 for _, d, _ in panels]
    # at least 7 in wide: the legend and the two-line title must fit even for a single dataset
    fig, axes = plt.subplots(1, len(panels), figsize=(max(1.0 * sum(widths) + 1.5, 7.0), 4.6), squeeze=False,
                             gridspec_kw={"width_ratios": widths})
    colors = {**{name: spec.color for name, spec in MODELS.items()}, "measurements": "0.7"}
    for ax, (key, sets, unit) in zip(axes[0], panels):
        width = 0.8 / len(names)
        for i, m in enumerate(names):
            xs, ys, lo, hi = [], [], [], []
            for j, d in enumerate(sets):
                r = next((q for q in rows if q["dataset"] == d and q["filter"] == m), None)
                if r is None or math.isnan(r[f"{key}_rmse"]):
                    continue
                xs.append(j - 0.4 + (i + 0.5) * width)
                ys.append(r[f"{key}_rmse"])
                lo.append(r[f"{key}_rmse"] - r[f"{key}_ci_lo"])
                hi.append(r[f"{key}_ci_hi"] - r[f"{key}_rmse"])
            if xs:
                ax.bar(xs, ys, width, yerr=[lo, hi], capsize=2, color=colors[m], label=m)
        ax.set_xticks(range(len(sets)))
        ax.set_xticklabels(sets)
        ax.set_xlim(-0.6, len(sets) - 0.4)
        ax.set_ylabel(f"{'position' if key == 'pos' else 'velocity'} RMSE ({unit})")
        ax.grid(axis="y", alpha=0.3)
    handles, labels = axes[0][0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="upper center", ncol=len(names), fontsize=8, bbox_to_anchor=(0.5, 0.90), frameon=False)
    fig.suptitle(f"Tracking error on real trajectories ({noise} process noise)\nbars: mean over tracks; whiskers: "
                 f"95 % bootstrap CI (none with fewer than {MIN_TRACKS_CI} tracks)", fontsize=10)
    fig.tight_layout(rect=(0, 0, 1, 0.84))
    try:
        fig.savefig(Path(path), dpi=120)
    finally:
        plt.close(fig)
