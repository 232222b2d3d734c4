"""Real ground-truth trajectories for ``lgekf evaluate``: loaders and the preset datasets.

Datasets (under ``data_root``: --data-root, else $LGEKF_DATA, else ../shared/data relative to the current
folder; never shipped with the package; ``PRESET_SOURCES`` says where each comes from)
---------------------------------------------------------------------------------------------------------
``eth`` (biwi_eth, 10 frames = 0.6667 s), ``hotel``, ``zara1``, ``zara2``, ``univ`` (students001 + 003;
10 frames = 0.4 s) from eth_ucy_trajectronpp/; ``kitti`` (kitti_oxts/, car GPS/IMU, 0.1035 s steps (see ``load_kitti``), planar
Mercator position, velocity truth from ve/vn); ``kitti3d`` (the same files in 3-D: east, north, up of lat, lon, alt,
attitude, velocity, climb and turn-rate truth; ``load_kitti3d``); ``cyclists`` (vru_cyclists_moving/, LiDAR at 12.5 Hz);
``dut`` (dut_vehicles/raw, cars from a drone at 23.98 fps, pixels / ratio -> m). ``ethucy`` is the five
pedestrian scenes. Any other argument is a path read with ``--format csv`` (t,x,y[,id][,vx,vy]) or
``--format pedestrian --frame-dt S``.
"""

from __future__ import annotations

import csv
import math
import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .readers import DataError, read_csv, read_pedestrian

__all__ = ["Dataset", "load_dataset", "data_root", "load_kitti", "load_kitti3d", "load_cyclists", "load_dut", "load_pedestrian", "load_smartloc",
           "load_csv_dataset", "PRESETS", "GROUPS", "PRESET_SOURCES", "KITTI_DT", "DEFAULT_DATA_ROOT"]


@dataclass
class Dataset:
    """Tracks sorted by object: t (N,), p (N, d) truth positions (d = 2 in the plane, 3 in 3-D space), v (N, d)
    truth world velocity or None, w (N,) truth turn rate (rad/s, the rate of the course) or None, attitude (N, 3)
    truth roll, pitch, yaw (rad, Z-Y-X Euler angles as ``derive/space.py``; 3-D only) or None."""

    name: str
    t: np.ndarray
    p: np.ndarray
    v: np.ndarray | None
    starts: np.ndarray
    labels: list
    skipped: int = 0
    description: str = ""
    w: np.ndarray | None = None
    attitude: np.ndarray | None = None

    @property
    def n_tracks(self) -> int:
        return len(self.labels)

    @property
    def space(self) -> str:
        """The space of the positions: "2d" or "3d" (``lgekf.core.registry.SPACES``)."""
        return "3d" if self.p.shape[1] == 3 else "2d"

    def subset(self, tracks):
        tracks = np.asarray(tracks, dtype=np.int64)
        rows = np.concatenate([np.arange(self.starts[i], self.starts[i + 1]) for i in tracks]) if len(tracks) else np.empty(0, np.int64)
        lens = np.diff(self.starts)[tracks]
        starts = np.zeros(len(tracks) + 1, dtype=np.int64)
        np.cumsum(lens, out=starts[1:])
        return Dataset(self.name, self.t[rows], self.p[rows], None if self.v is None else self.v[rows], starts,
                       [self.labels[i] for i in tracks], self.skipped, self.description,
                       None if self.w is None else self.w[rows], None if self.attitude is None else self.attitude[rows])


def _concat(name, parts, min_length, description):
    """parts: list of (label, t, p, v|None[, w|None[, attitude|None]]) tracks -> a Dataset (short tracks skipped)."""
    parts = [(*q, *([None] * (6 - len(q)))) for q in parts]
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
    w = np.concatenate([q[4] for q in keep]) if all(q[4] is not None for q in keep) else None
    att = np.concatenate([q[5] for q in keep]) if all(q[5] is not None for q in keep) else None
    return Dataset(name, t, p, v, starts, [q[0] for q in keep], skipped, description, w, att)


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
    """KITTI tracking OXTS: one sequence per file; devkit Mercator x, y (m); truth v = (ve, vn), w = wu.

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
        parts.append((f.stem, dt * np.arange(len(a)), p, v, a[:, 22]))  # wu: yaw rate about the vertical
    return _concat(name, parts, min_length, description)


def load_kitti3d(folder, name="kitti3d", min_length=5, description="", dt=KITTI_DT):
    """KITTI tracking OXTS in 3-D space: one sequence per file (``SOURCES.md`` §6 of the data folder).

    Truth: position = lat, lon, alt (columns 0-2) in metres east, north and up of each sequence's first fix
    (``lgekf.io.geo.to_local_enu``, the frame ``lgekf track`` makes of lat, lon, alt columns); attitude = roll, pitch,
    yaw (columns 3-5: 0 = level, roll positive = left side up, pitch positive = front down, yaw 0 = east,
    counter-clockwise), which is R = R_z(yaw) R_y(pitch) R_x(roll) of the body frame x forward, y left, z up, the
    convention of lgekf's 3-D space (and of the KITTI devkit's ``convertOxtsToPose``); world velocity = (ve, vn,
    vu) (columns 7, 6, 10: east, north, up; its z entry is the climb rate); turn rate = wu (column 22, the rate about
    the vertical, the course's rate for a car). Steps of ``KITTI_DT`` s (``load_kitti``).
    """
    from .geo import to_local_enu

    parts = []
    for f in _files(Path(folder), "*.txt"):
        a = np.loadtxt(f, ndmin=2)
        if a.shape[1] < 30:
            raise DataError(f"{f}: expected 30 columns of OXTS data, got {a.shape[1]}")
        x, y, z = to_local_enu(a[:, 0], a[:, 1], a[:, 2], a[0, 0], a[0, 1], a[0, 2])
        v = np.column_stack([a[:, 7], a[:, 6], a[:, 10]])  # (ve, vn, vu)
        parts.append((f.stem, dt * np.arange(len(a)), np.column_stack([x, y, z]), v, a[:, 22], a[:, 3:6].copy()))
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


def _ecef_to_enu(X):
    """ECEF points (N, 3) to east/north metres of the tangent plane at the first point (WGS84 geodetic)."""
    a, f = 6378137.0, 1.0 / 298.257223563
    e2 = f * (2 - f)
    x0 = X[0]
    lon = math.atan2(x0[1], x0[0])
    r = math.hypot(x0[0], x0[1])
    lat = math.atan2(x0[2], r * (1 - e2))
    for _ in range(10):  # fixed point for the geodetic latitude
        n = a / math.sqrt(1 - e2 * math.sin(lat) ** 2)
        h = r / math.cos(lat) - n
        lat = math.atan2(x0[2], r * (1 - e2 * n / (n + h)))
    east = np.array([-math.sin(lon), math.cos(lon), 0.0])
    north = np.array([-math.sin(lat) * math.cos(lon), -math.sin(lat) * math.sin(lon), math.cos(lat)])
    d = X - x0
    return np.column_stack([d @ east, d @ north])


def load_smartloc(folder, name="smartloc", min_length=5, description="", scenes=("Berlin_Potsdamer_Platz",)):
    """TU Chemnitz smartLoc (car, urban): ``<scene>_GT.txt`` ECEF truth -> east/north m of the first point;
    ``<scene>_odom3_only.txt`` (same time stamps): forward speed and yaw rate.

    The truth velocity is the odometry speed along the direction of travel of the truth positions
    (central differences); w is the odometry yaw rate. Scenes without an odometry file are skipped.
    """
    parts = []
    for scene in scenes:
        gt = Path(folder) / f"{scene}_GT.txt"
        od = Path(folder) / f"{scene}_odom3_only.txt"
        if not gt.exists() or not od.exists():
            continue
        g = np.loadtxt(gt, usecols=(1, 2, 3, 4), ndmin=2)
        o = np.loadtxt(od, usecols=(1, 2, 7), ndmin=2)
        if g.shape[0] != o.shape[0] or not np.allclose(g[:, 0], o[:, 0]):
            raise DataError(f"{od}: time stamps differ from {gt}")
        p = _ecef_to_enu(g[:, 1:4])
        d = np.gradient(p, g[:, 0], axis=0)
        heading = np.arctan2(d[:, 1], d[:, 0])
        v = o[:, 1, None] * np.column_stack([np.cos(heading), np.sin(heading)])
        parts.append((scene, g[:, 0], p, v, o[:, 2]))
    if not parts:
        raise DataError(f"{folder}: no smartLoc scene with GT and odometry ({', '.join(scenes)})")
    return _concat(name, parts, min_length, description)


PED = "eth_ucy_trajectronpp"
PRESETS = {
    "eth": ("pedestrian", [f"{PED}/biwi_eth.txt"], 0.6667 / 10, "ETH (BIWI) pedestrians, 0.667 s per step"),
    "hotel": ("pedestrian", [f"{PED}/biwi_hotel.txt"], 0.04, "ETH hotel pedestrians, 0.4 s per step"),
    "zara1": ("pedestrian", [f"{PED}/crowds_zara01.txt"], 0.04, "UCY zara1 pedestrians, 0.4 s per step"),
    "zara2": ("pedestrian", [f"{PED}/crowds_zara02.txt"], 0.04, "UCY zara2 pedestrians, 0.4 s per step"),
    "univ": ("pedestrian", [f"{PED}/students001.txt", f"{PED}/students003.txt"], 0.04, "UCY univ (students001+003), 0.4 s per step"),
    "kitti": ("kitti", ["kitti_oxts"], None, "KITTI car GPS/IMU (OXTS), 0.1035 s per step, velocity truth"),
    "kitti3d": ("kitti3d", ["kitti_oxts"], None, "KITTI car GPS/IMU (OXTS) in 3-D: lat, lon, alt, attitude, velocity, "
                                                 "climb and turn-rate truth, 0.1035 s per step"),
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
    "kitti3d": ("kitti_oxts", "the KITTI tracking OXTS files of github.com/crowdbotp/OpenTraj, datasets/KITTI/data/oxts/"),
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
        loader = {"kitti": load_kitti, "kitti3d": load_kitti3d, "cyclists": load_cyclists, "dut": load_dut}[kind]
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
