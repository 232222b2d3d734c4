"""Evaluate the four trackers on real ground-truth trajectories (`lgekf evaluate`).

Protocol
--------
* Every track of a dataset with at least ``min_length`` samples (default 5) is used; shorter ones are
  skipped and counted. Ground-truth positions get i.i.d. N(0, meas_std²) noise per axis (default
  0.3 m), one draw per seed (default 5 seeds); the same noisy measurements go to all four filters.
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

Datasets (under ``data_root``: --data-root, else $LGEKF_DATA, else ../shared/data relative to the current
folder; never shipped with the package; ``PRESET_SOURCES`` says where each comes from)
---------------------------------------------------------------------------------------------------------
``eth`` (biwi_eth, 10 frames = 0.6667 s), ``hotel``, ``zara1``, ``zara2``, ``univ`` (students001 + 003;
10 frames = 0.4 s) from eth_ucy_trajectronpp/; ``kitti`` (kitti_oxts/, car GPS/IMU, 0.1035 s steps (see ``load_kitti``), planar
Mercator position, velocity truth from ve/vn); ``cyclists`` (vru_cyclists_moving/, LiDAR at 12.5 Hz);
``dut`` (dut_vehicles/raw, cars from a drone at 23.98 fps, pixels / ratio -> m). ``ethucy`` is the five
pedestrian scenes. Any other argument is a path read with ``--format csv`` (t,x,y[,id][,vx,vy]) or
``--format pedestrian --frame-dt S``.
"""

from __future__ import annotations

import csv
import io
import json
import math
import os
import sys
import time
import zlib
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .io import DataError, read_csv, read_pedestrian
from .core.registry import MODELS, get_model
from .cli import ArgumentParser
from .track import DEFAULT_ACCEL_STD, TrackConfig, track_arrays

__all__ = [
    "Dataset", "PRESETS", "PRESET_SOURCES", "data_root", "load_dataset", "evaluate_dataset", "t_quantile",
    "bootstrap_ci", "world_velocity", "cmd_evaluate",
]

FILTERS = tuple(MODELS)
TUNE_SCALES = tuple(float(2.0**e) for e in np.arange(-3.0, 4.01, 0.5))
TUNE_RATIOS = tuple(float(2.0**e) for e in np.arange(-6.0, 3.01, 1.0))
TURNING = tuple(m for m, spec in MODELS.items() if "w" in spec.matched_noise)  # models with a rotational noise std
BASELINE = "cv"  # the paired differences are against this filter (the paper's simplest baseline)
TUNE_FRACTION = 0.3


# ------------------------------------------------------------------------------------ datasets
@dataclass
class Dataset:
    """Tracks sorted by object: t (N,), p (N, 2) truth positions, v (N, 2) truth velocity or None."""

    name: str
    t: np.ndarray
    p: np.ndarray
    v: np.ndarray | None
    starts: np.ndarray
    labels: list
    skipped: int = 0
    description: str = ""

    @property
    def n_tracks(self) -> int:
        return len(self.labels)

    def subset(self, tracks):
        tracks = np.asarray(tracks, dtype=np.int64)
        rows = np.concatenate([np.arange(self.starts[i], self.starts[i + 1]) for i in tracks]) if len(tracks) else np.empty(0, np.int64)
        lens = np.diff(self.starts)[tracks]
        starts = np.zeros(len(tracks) + 1, dtype=np.int64)
        np.cumsum(lens, out=starts[1:])
        return Dataset(self.name, self.t[rows], self.p[rows], None if self.v is None else self.v[rows], starts,
                       [self.labels[i] for i in tracks], self.skipped, self.description)


def _concat(name, parts, min_length, description):
    """parts: list of (label, t, p, v|None) tracks -> a Dataset (short tracks skipped)."""
    keep = [q for q in parts if len(q[1]) >= min_length]
    skipped = len(parts) - len(keep)
    if not keep:
        raise DataError(f"dataset {name}: no track has at least {min_length} samples ({len(parts)} tracks)")
    has_v = all(q[3] is not None for q in keep)
    starts = np.zeros(len(keep) + 1, dtype=np.int64)
    np.cumsum([len(q[1]) for q in keep], out=starts[1:])
    t = np.concatenate([q[1] for q in keep])
    p = np.concatenate([q[2] for q in keep])
    v = np.concatenate([q[3] for q in keep]) if has_v else None
    return Dataset(name, t, p, v, starts, [q[0] for q in keep], skipped, description)


def _from_measurements(meas, prefix=""):
    g, starts, _ = meas.grouped(min_length=1)
    has_v = "vx" in g.extra and "vy" in g.extra
    parts = []
    for i, lab in enumerate(g.labels):
        a, b = starts[i], starts[i + 1]
        v = np.column_stack([g.extra["vx"][a:b], g.extra["vy"][a:b]]) if has_v else None
        parts.append((prefix + lab, g.t[a:b], g.z[a:b], v))
    return parts


def load_pedestrian(paths, frame_dt, name, min_length=5, description=""):
    parts = []
    for i, path in enumerate(paths):
        parts += _from_measurements(read_pedestrian(path, frame_dt), f"{Path(path).stem}:" if len(paths) > 1 else "")
    return _concat(name, parts, min_length, description)


def load_csv_dataset(paths, name, min_length=5, description=""):
    parts = []
    for path in paths:
        parts += _from_measurements(read_csv(path, extra=("vx", "vy")), f"{Path(path).stem}:" if len(paths) > 1 else "")
    return _concat(name, parts, min_length, description)


def _files(folder: Path, pattern: str):
    files = sorted(folder.glob(pattern))
    if not files:
        raise DataError(f"{folder}: no files matching {pattern}")
    return files


KITTI_DT = 0.1035


def load_kitti(folder, name="kitti", min_length=5, description="", dt=KITTI_DT):
    """KITTI tracking OXTS: one sequence per file; devkit Mercator x, y (m); truth v = (ve, vn).

    The tracking benchmark has no timestamps and is nominally 10 Hz, but the data say otherwise: with
    0.1 s steps the finite-difference yaw rate is 1.034x the OXTS yaw rate (11 turning sequences,
    1.023-1.037) and the finite-difference speed 1.047x the OXTS speed; the step is taken as
    ``KITTI_DT`` = 0.1035 s.
    """
    R = 6378137.0
    parts = []
    for f in _files(Path(folder), "*.txt"):
        a = np.loadtxt(f, ndmin=2)
        if a.shape[1] < 30:
            raise DataError(f"{f}: expected 30 columns of OXTS data, got {a.shape[1]}")
        lat, lon = a[:, 0], a[:, 1]
        scale = math.cos(lat[0] * math.pi / 180.0)
        x = scale * R * lon * math.pi / 180.0
        y = scale * R * np.log(np.tan((90.0 + lat) * math.pi / 360.0))
        p = np.column_stack([x - x[0], y - y[0]])
        v = np.column_stack([a[:, 7], a[:, 6]])  # (ve, vn): east = Mercator x, north = y
        parts.append((f.stem, dt * np.arange(len(a)), p, v))
    return _concat(name, parts, min_length, description)


def load_cyclists(folder, name="cyclists", min_length=5, description=""):
    """VRU cyclists: one track per CSV file (``,timestamp,x,y``; s, m)."""
    parts = []
    for f in _files(Path(folder), "*.csv"):
        m = read_csv(f)
        parts += [(f.stem, q[1], q[2], None) for q in _from_measurements(m)]
    return _concat(name, parts, min_length, description)


def load_dut(folder, name="dut", min_length=5, description="", fps=23.98):
    """DUT drone vehicle tracks: raw/<clip>_traj_veh.csv in pixels, <clip>_ratio_pixel2meter.txt px/m.

    x = x_c/ratio, y = -y_c/ratio (image y points down; flipped to a right-handed frame), t = frame/fps.
    """
    parts = []
    for f in _files(Path(folder), "*_traj_veh.csv"):
        clip = f.name[: -len("_traj_veh.csv")]
        ratio = float(np.loadtxt(f.with_name(f"{clip}_ratio_pixel2meter.txt")))
        with open(f, newline="") as fh:
            header = [h.strip() for h in next(csv.reader(fh))]
        cols = [header.index(c) for c in ("id", "x_c", "y_c", "frame")]
        a = np.loadtxt(f, delimiter=",", skiprows=1, usecols=cols, ndmin=2)
        for vid in np.unique(a[:, 0]):
            r = a[a[:, 0] == vid]
            r = r[np.argsort(r[:, 3], kind="stable")]
            parts.append((f"{clip}:{int(vid)}", r[:, 3] / fps, np.column_stack([r[:, 1], -r[:, 2]]) / ratio, None))
    return _concat(name, parts, min_length, description)


PED = "eth_ucy_trajectronpp"
PRESETS = {
    "eth": ("pedestrian", [f"{PED}/biwi_eth.txt"], 0.6667 / 10, "ETH (BIWI) pedestrians, 0.667 s per step"),
    "hotel": ("pedestrian", [f"{PED}/biwi_hotel.txt"], 0.04, "ETH hotel pedestrians, 0.4 s per step"),
    "zara1": ("pedestrian", [f"{PED}/crowds_zara01.txt"], 0.04, "UCY zara1 pedestrians, 0.4 s per step"),
    "zara2": ("pedestrian", [f"{PED}/crowds_zara02.txt"], 0.04, "UCY zara2 pedestrians, 0.4 s per step"),
    "univ": ("pedestrian", [f"{PED}/students001.txt", f"{PED}/students003.txt"], 0.04, "UCY univ (students001+003), 0.4 s per step"),
    "kitti": ("kitti", ["kitti_oxts"], None, "KITTI car GPS/IMU (OXTS), 0.1035 s per step, velocity truth"),
    "cyclists": ("cyclists", ["vru_cyclists_moving"], None, "VRU cyclists (LiDAR), 12.5 Hz"),
    "dut": ("dut", ["dut_vehicles/raw"], None, "DUT cars at an intersection/roundabout (drone), 23.98 Hz"),
}
GROUPS = {"ethucy": ["eth", "hotel", "zara1", "zara2", "univ"]}


# Where each preset's files come from (as listed in SOURCES.md of the data folder): kind -> (folder
# under the data root, origin); named in the error message when a preset's files are missing.
PRESET_SOURCES = {
    "pedestrian": (PED, "the ETH/UCY text files of github.com/StanfordASL/Trajectron-plus-plus, "
                        "experiments/pedestrians/raw/raw/all_data/"),
    "kitti": ("kitti_oxts", "the KITTI tracking OXTS files of github.com/crowdbotp/OpenTraj, datasets/KITTI/data/oxts/"),
    "cyclists": ("vru_cyclists_moving", "the VRU cyclist tracks of github.com/crowdbotp/OpenTraj, datasets/VRU/cyclists/moving/"),
    "dut": ("dut_vehicles/raw", "the DUT *_traj_veh.csv and *_ratio_pixel2meter.txt files of "
                                "github.com/dongfang-steven-yang/vci-dataset-dut, data/trajectories/ and data/ratios/"),
}
DEFAULT_DATA_ROOT = Path("..") / "shared" / "data"


def data_root(arg=None) -> Path:
    """The folder holding the preset datasets.

    Parameters
    ----------
    arg : str or path-like, optional
        The ``--data-root`` option.

    Returns
    -------
    Path
        ``arg`` if given, else ``$LGEKF_DATA`` if set, else ``../shared/data`` relative to the current
        working directory. Nothing is looked up relative to the installed package (in a non-editable
        install that would point inside site-packages).
    """
    if arg:
        return Path(arg)
    env = os.environ.get("LGEKF_DATA")
    if env:
        return Path(env)
    return DEFAULT_DATA_ROOT


def _missing_data_message(spec: str, kind: str, missing: Path, arg) -> str:
    """One line: what is missing, where lgekf looked, where to get the data and how to point at it."""
    if arg:
        where = f"--data-root {arg}"
    elif os.environ.get("LGEKF_DATA"):
        where = f"$LGEKF_DATA = {os.environ['LGEKF_DATA']}"
    else:
        where = f"no --data-root or $LGEKF_DATA given, so {DEFAULT_DATA_ROOT} relative to the current folder {Path.cwd()}"
    folder, origin = PRESET_SOURCES[kind]
    return (f"dataset {spec}: {missing} not found (data root: {where}); the datasets are not shipped with lgekf: "
            f"put {folder}/ ({origin}) in a folder and give that folder with --data-root DIR or $LGEKF_DATA")


def load_dataset(spec: str, *, root=None, fmt=None, frame_dt=None, min_length=5) -> Dataset:
    """A preset name or a path (``fmt`` "csv" / "pedestrian"; inferred from a .csv suffix)."""
    if spec in PRESETS:
        kind, rel, fdt, desc = PRESETS[spec]
        base = data_root(root)
        paths = [base / r for r in rel]
        for p in paths:
            if not p.exists():
                raise DataError(_missing_data_message(spec, kind, p, root))
        if kind == "pedestrian":
            return load_pedestrian(paths, fdt, spec, min_length, desc)
        loader = {"kitti": load_kitti, "cyclists": load_cyclists, "dut": load_dut}[kind]
        return loader(paths[0], spec, min_length, desc)
    path = Path(spec)
    if not path.exists():
        raise DataError(f"dataset {spec!r}: neither a preset ({', '.join([*PRESETS, *GROUPS])}) nor an existing file")
    if fmt is None:
        if path.suffix.lower() == ".csv":
            fmt = "csv"
        else:
            raise DataError(f"dataset {spec}: cannot infer the format; give --format csv or --format pedestrian --frame-dt S")
    if fmt == "csv":
        if frame_dt is not None:
            raise DataError("--frame-dt: only for --format pedestrian (CSV input has a time column)")
        return load_csv_dataset([path], path.stem, min_length, f"CSV {path.name}")
    if fmt == "pedestrian":
        return load_pedestrian([path], frame_dt, path.stem, min_length, f"pedestrian format {path.name}, frame_dt {frame_dt} s")
    raise DataError(f"--format: unknown format {fmt!r}; choose csv or pedestrian")


# ------------------------------------------------------------------------------------ statistics
def t_quantile(p: float, nu: int) -> float:
    """Student-t quantile (Cornish-Fisher expansion in 1/ν; |error| < 2e-3 for ν >= 2, exact for ν = 1)."""
    if nu < 1:
        return float("nan")
    if nu == 1:
        return math.tan(math.pi * (p - 0.5))
    # normal quantile (Acklam's rational approximation, |rel error| < 1.2e-9)
    a = [-3.969683028665376e01, 2.209460984245205e02, -2.759285104469687e02, 1.383577518672690e02, -3.066479806614716e01, 2.506628277459239e00]
    b = [-5.447609879822406e01, 1.615858368580409e02, -1.556989798598866e02, 6.680131188771972e01, -1.328068155288572e01]
    c = [-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e00, -2.549732539343734e00, 4.374664141464968e00, 2.938163982698783e00]
    d = [7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e00, 3.754408661907416e00]
    if p < 0.02425:
        q = math.sqrt(-2 * math.log(p))
        z = (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) / ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1)
    elif p > 1 - 0.02425:
        q = math.sqrt(-2 * math.log(1 - p))
        z = -(((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) / ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1)
    else:
        q = p - 0.5
        r = q * q
        z = (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q / (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1)
    g1 = (z**3 + z) / 4
    g2 = (5 * z**5 + 16 * z**3 + 3 * z) / 96
    g3 = (3 * z**7 + 19 * z**5 + 17 * z**3 - 15 * z) / 384
    g4 = (79 * z**9 + 776 * z**7 + 1482 * z**5 - 1920 * z**3 - 945 * z) / 92160
    return z + g1 / nu + g2 / nu**2 + g3 / nu**3 + g4 / nu**4


BOOTSTRAP_RESAMPLES = 10000
BOOTSTRAP_SEED = 20160705
MIN_TRACKS_CI = 5


def bootstrap_ci(x, level=0.95, resamples=BOOTSTRAP_RESAMPLES, seed=BOOTSTRAP_SEED, min_n=MIN_TRACKS_CI):
    """Mean of independent values and an expanded percentile bootstrap interval for it.

    Parameters
    ----------
    x : array_like
        Independent values (nan-free), here one per track: a per-track RMSE or a paired difference.
    level : float
        Coverage of the interval (default 0.95).
    resamples : int
        Number of bootstrap resamples of ``x`` (with replacement, each of size ``len(x)``).
    seed : int
        Seed of the resampling, so that the same data always give the same interval.
    min_n : int
        Fewest values for which an interval is given; below it the bounds are nan.

    Returns
    -------
    mean, lo, hi : float
        The sample mean and the bounds; ``lo`` and ``hi`` are nan when ``len(x) < min_n``, all three
        nan for empty ``x``.

    Notes
    -----
    The bounds are the α'/2 and 1 - α'/2 quantiles of the resampled means with
    Φ⁻¹(α'/2) = -√(n/(n-1))·t_{(1+level)/2, n-1}: the "expanded percentile" interval (T. Hesterberg,
    What teachers should know about the bootstrap, The American Statistician 69 (2015) 371-386), which
    widens the plain percentile interval by the factor it is too narrow at small n and equals it for
    large n. Being quantiles of resampled means, the bounds lie in [min x, max x]: an interval for a
    mean of non-negative values (RMSEs) never reaches below zero.
    """
    x = np.asarray(x, dtype=float).ravel()
    n = x.size
    m = float(x.mean()) if n else float("nan")
    if n < max(min_n, 2):
        return m, float("nan"), float("nan")
    z = math.sqrt(n / (n - 1)) * t_quantile(0.5 + level / 2, n - 1)
    p = 0.5 * math.erfc(z / math.sqrt(2.0))  # Φ(-z)
    rng = np.random.default_rng(seed)
    means = np.empty(resamples)
    chunk = max(1, 2**20 // n)
    for a in range(0, resamples, chunk):
        b = min(resamples, a + chunk)
        means[a:b] = x[rng.integers(0, n, size=(b - a, n))].mean(axis=1)
    lo, hi = np.quantile(means, [p, 1.0 - p])
    return m, float(lo), float(hi)


# ------------------------------------------------------------------------------------ running
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


def run_filters(ds: Dataset, cfg: TrackConfig, seeds, stream, models=FILTERS):
    """Position (and velocity) RMSE per (model, seed, track): dict model -> (pos (S, J), vel (S, J) | None)."""
    out = {m: (np.empty((len(seeds), ds.n_tracks)), None if ds.v is None else np.empty((len(seeds), ds.n_tracks))) for m in models}
    out["measurements"] = (np.empty((len(seeds), ds.n_tracks)), None)
    for si, seed in enumerate(seeds):
        rng = _seed_rng(seed, stream, ds.name)
        z = ds.p + cfg.meas_std * rng.standard_normal(ds.p.shape)
        out["measurements"][0][si] = _per_track_rmse(ds, np.sum((z - ds.p) ** 2, axis=1))
        for m in models:
            x, _, _ = track_arrays(m, ds.t, z, ds.starts, cfg)
            out[m][0][si] = _per_track_rmse(ds, np.sum((x[:, :2] - ds.p) ** 2, axis=1))
            if ds.v is not None:
                out[m][1][si] = _per_track_rmse(ds, np.sum((world_velocity(m, x) - ds.v) ** 2, axis=1))
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


def evaluate_dataset(ds: Dataset, *, meas_std=0.3, seeds=5, base_seed=0, tune=False, progress=None):
    """Default-noise result (all tracks, or the evaluation split when tuning) and, with ``tune``, the tuned one."""
    seed_list = [base_seed + s for s in range(seeds)]
    default = {m: (1.0, 1.0) for m in FILTERS}
    if not tune:
        return [DatasetResult(ds, "default", default, run_filters(ds, _scaled(default, meas_std), seed_list, 0))]
    tune_idx, eval_idx = tune_split(ds.n_tracks)
    dtune, deval = ds.subset(tune_idx), ds.subset(eval_idx)
    tuning = []
    best = {m: (float("inf"), (1.0, 1.0)) for m in FILTERS}

    def score(stage, configs, models):
        """configs: list of {model: (k, ρ)}; evaluates each on the tuning split (noise stream 1)."""
        for conf in configs:
            res = run_filters(dtune, _scaled(conf, meas_std), seed_list, 1, models=models)
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
        out.append(DatasetResult(deval, noise, scale, run_filters(deval, _scaled(scale, meas_std), seed_list, 0), tuning, len(tune_idx)))
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


def evaluate_parser():
    ap = ArgumentParser(prog="lgekf evaluate", description="Evaluate the four trackers on real ground-truth trajectories with added position noise.")
    ap.add_argument("datasets", nargs="+", metavar="DATASET",
                    help=f"preset ({', '.join([*PRESETS, *GROUPS])}) or a file (--format csv | pedestrian --frame-dt S)")
    ap.add_argument("--format", choices=["csv", "pedestrian"], default=None, help="format of DATASET files (default: csv for *.csv)")
    ap.add_argument("--frame-dt", type=float, default=None, help="pedestrian format: seconds per frame unit")
    ap.add_argument("--data-root", default=None, help="folder of the presets (default: $LGEKF_DATA, else ../shared/data relative to the current folder)")
    ap.add_argument("--meas-std", type=float, default=0.3, help="std of the added position noise per axis, m (default 0.3)")
    ap.add_argument("--seeds", type=int, default=5, help="noise draws per track (default 5)")
    ap.add_argument("--seed", type=int, default=0, help="first seed (default 0)")
    ap.add_argument("--min-length", type=int, default=5, help="skip tracks with fewer samples (default 5)")
    ap.add_argument("--tune", action="store_true",
                    help="grid-search the process noise (scale k, turn-rate ratio ρ) per filter on the first 30 %% of tracks; evaluate on the rest")
    ap.add_argument("--out", type=Path, default=Path("evaluation"), help="output folder (default evaluation/)")
    ap.add_argument("--no-figure", action="store_true", help="skip evaluation.png")
    ap.add_argument("--markdown", action="store_true", help="print the table as Markdown")
    return ap


def cmd_evaluate(argv) -> int:
    from .output import staged_directory, write_atomic

    a = evaluate_parser().parse_args(argv)
    if not (math.isfinite(a.meas_std) and a.meas_std > 0):
        raise ValueError(f"--meas-std: must be a positive number, got {a.meas_std}")
    if a.seeds < 1:
        raise ValueError(f"--seeds: must be at least 1, got {a.seeds}")
    if a.min_length < 3:
        raise ValueError(f"--min-length: must be at least 3 (two samples initialise the filter), got {a.min_length}")
    names = []
    for d in a.datasets:
        names += GROUPS.get(d, [d])
    t0 = time.perf_counter()
    datasets = [load_dataset(d, root=a.data_root, fmt=a.format, frame_dt=a.frame_dt, min_length=a.min_length) for d in names]
    if len({d.name for d in datasets}) != len(datasets):
        raise ValueError("datasets: the same dataset (name) is given twice")
    rows, tuning, per_track = [], [], []
    for ds in datasets:
        for res in evaluate_dataset(ds, meas_std=a.meas_std, seeds=a.seeds, base_seed=a.seed, tune=a.tune):
            rows += res.summary()
            if res.noise == "tuned":
                tuning += [{"dataset": ds.name, "filter": m, "stage": st, "scale": k, "turn_ratio": rho, "tune_pos_rmse": sc,
                            "chosen": False, "tune_tracks": res.n_tune_tracks} for m, st, k, rho, sc in res.tuning]
                for m in FILTERS:  # mark the first row that reached the chosen value
                    mine = [r for r in tuning if r["dataset"] == ds.name and r["filter"] == m]
                    min(mine, key=lambda r: r["tune_pos_rmse"])["chosen"] = True
            for m, (pos, vel) in res.rmse.items():
                for si in range(pos.shape[0]):
                    for j, lab in enumerate(res.dataset.labels):
                        per_track.append([ds.name, res.noise, lab, a.seed + si, m, pos[si, j], np.nan if vel is None else vel[si, j]])
    if a.tune:  # the tuned rows and the measurements once; the default rows on the same split for reference
        seen = set()
        rows = [r for r in rows if not (r["filter"] == "measurements" and (r["dataset"] in seen or seen.add(r["dataset"])))]
    out = a.out
    with staged_directory(out) as stage:
        write_atomic(stage / "summary.csv", _csv_text(SUMMARY_FIELDS, rows))
        buf = io.StringIO()
        w = csv.writer(buf, lineterminator="\n")
        w.writerow(["dataset", "noise", "track", "seed", "filter", "pos_rmse", "vel_rmse"])
        for r in per_track:
            w.writerow(r[:5] + [_fmt(float(r[5]), 6), _fmt(float(r[6]), 6)])
        write_atomic(stage / "per_track.csv", buf.getvalue())
        if tuning:
            write_atomic(stage / "tuning.csv", _csv_text(["dataset", "filter", "stage", "scale", "turn_ratio", "tune_pos_rmse", "chosen", "tune_tracks"], tuning))
        meta = {
            "datasets": {d.name: {"description": d.description, "tracks": d.n_tracks, "skipped_short": d.skipped,
                                  "samples": int(d.t.size), "velocity_truth": d.v is not None} for d in datasets},
            "meas_std": a.meas_std, "seeds": a.seeds, "first_seed": a.seed, "min_length": a.min_length, "tune": a.tune,
            "tune_scales": list(TUNE_SCALES) if a.tune else None, "tune_turn_ratios": list(TUNE_RATIOS) if a.tune else None, "tune_split": "first 30 % of tracks" if a.tune else None,
            "default_accel_std": {m: list(v) for m, v in DEFAULT_ACCEL_STD.items()},
            "ci": (f"mean over tracks of the seed-averaged per-track RMSE; 95 % expanded percentile bootstrap interval over "
                   f"tracks ({BOOTSTRAP_RESAMPLES} resamples, seed {BOOTSTRAP_SEED}); none with fewer than {MIN_TRACKS_CI} tracks"),
            "seconds": round(time.perf_counter() - t0, 2),
        }
        write_atomic(stage / "meta.json", json.dumps(meta, indent=2) + "\n")
        if not a.no_figure:
            evaluation_figure(rows, stage / "evaluation.png", "tuned" if a.tune else "default")
    print(markdown_table(rows) if a.markdown else format_table(rows))
    print(f"95 % intervals: expanded percentile bootstrap over tracks ({BOOTSTRAP_RESAMPLES} resamples, fixed seed); "
          f"n/a with fewer than {MIN_TRACKS_CI} tracks", file=sys.stderr)
    for d in datasets:
        print(f"{d.name}: {d.n_tracks} tracks used, {d.skipped} shorter than {a.min_length} skipped ({d.description})", file=sys.stderr)
    if a.tune:
        for r in rows:
            if r["noise"] == "tuned":
                print(f"tuned {r['dataset']} {r['filter']}: k = {r['scale']:.3g}, ρ = {r['turn_ratio']:.3g} -> accel_std {r['accel_std']}", file=sys.stderr)
    print(f"wrote {out}/summary.csv, per_track.csv{', tuning.csv' if tuning else ''}, meta.json"
          f"{'' if a.no_figure else ', evaluation.png'} ({meta['seconds']:.1f} s)", file=sys.stderr)
    return 0
