"""Track objects in a measurement file with any registry model (`lgekf track`).

Initialisation (per object, from its first two measurements z0 at t0 and z1 at t1, Δ = t1 - t0)
---------------------------------------------------------------------------------------------
The estimate is made at t1 in the common physical coordinates c = (x, y, θ, v_x, v_y, ω) (body-frame
velocity) and converted to each model with the generated ``common_to_state`` / ``common_jacobian``
(P0_model = J P0_c Jᵀ):

* position (x, y) = z1, variance r² (r = measurement std);
* world velocity v = (z1 - z0)/Δ, each component with variance σ_v² = 2r²/Δ²;
* heading θ = atan2(v) (0 if v = 0), body velocity (|v|, 0), ω = 0;
* var θ = min(σ_v²/|v|², cap²) (the lateral velocity error seen as a heading error, at most cap², cap =
  ``heading_cap``: π for the library functions, ``TRACK_HEADING_CAP`` = 0.3 rad in ``lgekf track``);
* var v_x = σ_v²; var v_y = max(σ_v² - |v|² var θ, (0.1 σ_v)²): the lateral velocity the heading
  cannot explain (slow objects, or beyond the cap), and at least a small side-slip prior (10 % of σ_v)
  otherwise. The split between θ and v_y matters only to the models with a side-slip velocity
  (SE(2)×SE(2), SE(2)×R³; for the others the conversion folds var v_y back into the heading): their
  LG-EKF update turns a position innovation into a rotation when the heading is very uncertain and
  bends the correction (docs/evaluate.md), so ``lgekf track`` keeps the heading std at most
  0.3 rad and lets the body velocity carry the rest (ETH pedestrians, robustness set: the lost tracks of
  the first updates disappear);
* var ω = ``omega_std``² (default 0.5 rad/s: a pedestrian or car turns at well under 1 rad/s);
* with ``use_heading`` the measured heading h1 at t1 replaces atan2(v) (variance ``heading_std``²,
  default 0.1 rad) and the body velocity is (v·(cos h1, sin h1), 0) with var v_y = (0.1 σ_v)²;
* P0_c is diagonal; after conversion any angle variance of the model (θ, ψ) is capped at π² by scaling
  its row and column (CTRV's ψ variance grows like var v_y/|v|² for slow objects).

The filter then runs predict(t_k - t_{k-1}) + update(z_k) for k = 2, 3, ... Output rows exist for every
measurement: row 0 holds z0 as position with the two-point velocity/heading and covariance P0 (nis empty
= nan), row 1 the initial estimate (x0, P0) at t1 (nis nan), rows k >= 2 the filter's posterior.
``track_monitored`` adds the divergence monitor (``lgekf.apps.divergence``): at an alarm the object is
re-initialised by the same two-point rule from its measurement at the alarm row and the latest one at
least ``REINIT_BASELINE`` = 0.5 s earlier (the object's first if none), and continues; the rows of the
alarm are flagged.

Noise: ``lgekf track`` takes each value given as an option and estimates the others from the data
(``lgekf.apps.defaults``). The library defaults (``TrackConfig``) are the models' ``default_accel_std``
(SE(2)xSE(2), SE(2)xR3 (σ_x, σ_y, σ_ω) = (0.5 m/s², 0.5 m/s², 1.0 rad/s²); SE(2)xR2, CTRV (σ_a, σ_α) =
(0.5, 1.0); CV σ_a = 0.5 m/s²) and a measurement std of 0.3 m.

Measurements: ``position`` (x, y) or ``pose`` (x, y and the ``heading`` column as θ ∈ SE(2), noise
(meas_std, meas_std, heading_std) in the tangent of SE(2)); a model without a heading (CV) is refused
with pose, except under ``--model all`` where it gets the positions (said on stderr).
"""

from __future__ import annotations

import math
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..core.covariance import pack, packed_diagonal
from ..core.initiation import (  # noqa: F401
    DEFAULT_HEADING_STD, DEFAULT_OMEGA_STD, SIDESLIP_FRACTION, initial_estimates, moving_backwards, two_point,
)
from ..core.registry import ALL_MODELS, SPACES, get_model, measurement_in, models_of
from ..core.validate import positive_scalar
from .divergence import FirstPass, MonitorConfig, Restart, recover, speed_limits
from .windows import WINDOW_ROWS, filter_windows
from ..io.files import is_stdio
from ..io.formatting import label_bytes, output_digits, write_rows_made
from ..io.grouping import objects_subset, row_objects
from ..io.parquet import ParquetRows

__all__ = [
    "DEFAULT_ACCEL_STD", "DEFAULT_MEAS_STD", "DEFAULT_MODELS", "default_model", "own_measurement", "motion_columns", "turn_rates",
    "DEFAULT_OMEGA_STD", "DEFAULT_HEADING_STD", "TrackConfig",
    "initial_common", "initial_estimates", "two_point", "track_arrays", "track_monitored", "Tracked", "output_columns",
    "output_path", "write_model", "Written", "SMOOTH_FAILED", "ClassConfigs", "track_chunk", "TRACK_HEADING_CAP", "REINIT_BASELINE", "smoothing_inputs", "restart_inputs", "track_windows",
]

DEFAULT_ACCEL_STD = {name: spec.default_accel_std for name, spec in ALL_MODELS.items()}  # from each definition
#: ``lgekf track``'s model when none is given, per space of the input's positions (for a measurement it cannot take: the
#: first model of the space that takes it, ``default_model``): in the plane SE(2)×SE(2); in 3-D CT3, the best of the
#: three with the noise from the data on 3-D positions of a car (KITTI), a drone's helix and a climbing turn
#: (docs/space3d.md, "Which model by default"); given roll, pitch, yaw (pose3) SE(3)×R⁶, the only one that takes them
DEFAULT_MODELS = {"2d": "se2se2", "3d": "ct3"}


def default_model(space: str, measurement: str) -> str:
    """``lgekf track``'s model of ``space`` for ``measurement`` (as that space measures it): ``DEFAULT_MODELS[space]``
    if it takes it, else the first registered model of the space that does."""
    table = models_of(space)
    meas = measurement_in(space, measurement)
    if meas in table[DEFAULT_MODELS[space]].measurements:
        return DEFAULT_MODELS[space]
    return next((m for m, spec in table.items() if meas in spec.measurements), DEFAULT_MODELS[space])
DEFAULT_MEAS_STD = 0.3
TRACK_HEADING_CAP = 0.3  # `lgekf track`'s cap on the initial heading std (rad); see two_point
REINIT_BASELINE = 0.5  # a re-initialisation's two measurements are at least this far apart (s), if the object allows

#: the ``flag`` column's bit set on every row of an object whose smoothed values were not all finite (its smooth_*
#: columns then repeat the filter's); bit 0 (1) marks the rows of a detected divergence
SMOOTH_FAILED = 2
ROWS_PER_CHUNK = 1 << 15  # rows (whole objects) tracked and written at a time: bounds the memory of the outputs (two chunks in flight)
FORMAT_ROWS = 1 << 15  # rows of a Parquet row group made at a time (CSV text: lgekf.io.formatting.PART_ROWS)


@dataclass
class TrackConfig:
    """Noise and initialisation parameters of one tracking run (validated by ``validate``)."""

    accel_std: dict = field(default_factory=lambda: dict(DEFAULT_ACCEL_STD))
    meas_std: float = DEFAULT_MEAS_STD
    omega_std: float = DEFAULT_OMEGA_STD
    heading_std: float = DEFAULT_HEADING_STD
    heading_cap: float = math.pi  # largest initial heading std of the two-point prior (rad); see two_point

    def validate(self):
        for name, val in (("meas_std", self.meas_std), ("omega_std", self.omega_std), ("heading_std", self.heading_std)):
            positive_scalar(name.replace("_", "-"), val)
        for model, q in self.accel_std.items():
            spec = get_model(model)
            q = tuple(q)
            if len(q) != len(spec.noise_names):
                raise ValueError(f"accel-std for {model}: expected {len(spec.noise_names)} values ({', '.join(spec.noise_names)}), got {len(q)}")
            if any((not math.isfinite(v)) or v < 0 for v in q):
                raise ValueError(f"accel-std for {model}: must be non-negative numbers, got {list(q)}")
        return self

    def q(self, model):
        return np.asarray(self.accel_std.get(model, DEFAULT_ACCEL_STD[model]), dtype=float)


def initial_common(t, z, starts, meas_std, omega_std=DEFAULT_OMEGA_STD, heading=None, heading_std=DEFAULT_HEADING_STD,
                   heading_cap=math.pi):
    """Common-coordinate initial states c (B, 6) and their diagonal variances (B, 6), one per object.

    t (N,), z (N, 2) sorted by object with ``starts`` (B + 1,); every object has >= 2 rows.
    """
    return two_point(t, z, np.asarray(starts)[:-1] + 1, meas_std, omega_std, heading, heading_std, heading_cap)


def own_measurement(model: str, measurement: str) -> str:
    """``measurement`` as the model's space measures it (``measurement_in``): the library's default "position" is
    position3 for a model of 3-D space, "pose" its pose3."""
    return measurement_in(get_model(model).space, measurement)


def _measurement_inputs(spec, z, heading, cfg, measurement):
    """(measurements (N, m), noise stds r) of the measurement model."""
    meas = spec.measurement(measurement)
    if meas.has_angle and heading is None:
        raise ValueError(f"--measure {measurement}: the input needs a heading column")
    return (np.ascontiguousarray(meas.columns(z[:, :position_dims(spec.name)], heading)),
            np.array(meas.stds(float(cfg.meas_std), cfg.heading_std), dtype=float))


def _run_segments(model, measurement, t, zm, first, lengths, x0, p0, q, r, out_x, out_p, out_nis):
    """Filter segments of rows: segment i is rows first[i] .. first[i] + lengths[i] - 1, predicted from
    (x0[i], p0[i]) at time t[first[i] - 1] with the noise stds q (nq,), r (nr,); outputs written in place,
    straight on the rows (no padded copies).

    One call of the generated ``run_segments_<meas>``: ``run_one`` segment after segment, no Python per segment or
    step. It is serial and releases the GIL, so that the writer thread (``write_model``) and the process-noise
    search's threads (``lgekf.apps.search``) run beside it; no numba parallel kernel is used. (With the divergence
    monitor on, the first pass is made by the monitor's compiled ``recover_<meas>`` instead: ``track_monitored``.)
    """
    lengths = np.asarray(lengths, dtype=np.int64)
    keep = np.flatnonzero(lengths > 0)
    run = get_model(model).kernel("run_segments", measurement)
    run(zm, t, np.ascontiguousarray(np.asarray(first, dtype=np.int64)[keep]), np.ascontiguousarray(lengths[keep]),
        np.ascontiguousarray(x0[keep]), np.ascontiguousarray(p0[keep]), q, r, out_x, out_p, out_nis)


def track_arrays(model, t, z, starts, cfg: TrackConfig, heading=None, x0=None, P0=None, measurement="position"):
    """Track every object of sorted measurements; no Python per filter step.

    t (N,), z (N, 2) sorted by object (``starts`` (B + 1,) offsets; >= 2 rows and increasing t each).
    Returns states (N, n) in the model's physical coordinates, packed covariances (N, n(n+1)/2) in
    its filter coordinates, nis (N,) (nan for the first two rows of each object). ``x0``/``P0``
    (B, n), (B, n, n) override the two-point initialisation. ``measurement="pose"`` uses ``heading`` (N,)
    as the measured angle (noise stds meas_std, meas_std, heading_std in the tangent of SE(2)).
    No divergence monitoring: that is ``track_monitored``.
    """
    measurement = own_measurement(model, measurement)
    spec = get_model(model)
    t = np.ascontiguousarray(t, dtype=float)
    z = np.ascontiguousarray(z, dtype=float)
    starts = np.asarray(starts, dtype=np.int64)
    zm, r = _measurement_inputs(spec, z, heading, cfg, measurement)
    x0, p0, out_x, out_p, out_nis = _started(model, t, z, starts, cfg, heading, x0, P0)
    _run_segments(model, measurement, t, zm, starts[:-1] + 2, np.diff(starts) - 2, x0, p0, cfg.q(model), r, out_x, out_p, out_nis)
    return out_x, out_p, out_nis


def _started(model, t, z, starts, cfg: TrackConfig, heading, x0, P0):
    """(x0 (B, n), packed p0, out_x, out_p, out_nis): every object's two-point start (given or made) on its rows 0
    and 1 of the outputs (row 0 with its measured position), the other rows to be filtered (NIS nan)."""
    spec = get_model(model)
    if x0 is None or P0 is None:
        c, var = initial_common(t, z, starts, cfg.meas_std, cfg.omega_std, heading, cfg.heading_std, cfg.heading_cap)
        x0, P0 = initial_estimates(model, c, var, moving_backwards(t, z, starts, cfg.meas_std))
    p0 = pack(P0)
    N = t.size
    out_x = np.empty((N, spec.n))
    out_p = np.empty((N, spec.n_packed))
    out_nis = np.full(N, np.nan)
    i0 = starts[:-1]
    out_x[i0] = x0
    out_x[i0, :z.shape[1]] = z[i0]  # every model's state starts with the position (x, y or x, y, z)
    out_x[i0 + 1] = x0
    out_p[i0] = p0
    out_p[i0 + 1] = p0
    return x0, p0, out_x, out_p, out_nis


def smoothing_inputs(model, z, cfg: TrackConfig, heading=None, measurement="position"):
    """(zm, q, r): the measurements and noise stds that ``lgekf.apps.smooth_track.smoothed_columns`` needs besides the
    filter's output (``Tracked``), as ``track_arrays`` / ``track_monitored`` used them."""
    measurement = own_measurement(model, measurement)
    zm, r = _measurement_inputs(get_model(model), z, heading, cfg, measurement)
    return zm, cfg.q(model), r


@dataclass
class Tracked:
    """Output of ``track_monitored``: states, packed covariances, NIS, flags (N,) and the alarms."""

    x: np.ndarray
    p: np.ndarray
    nis: np.ndarray
    flag: np.ndarray
    alarms: list


def restart_inputs(measurement, t, z, heading, zm, q, r, cfg: TrackConfig, obj_first) -> Restart:
    """The re-initialisation of ``lgekf track``'s divergence recovery (``divergence.recover``) and the filter it runs
    again: the two-point estimate (``two_point``) at an alarm row from its measurement (t, z, heading) and the latest
    earlier one at least ``REINIT_BASELINE`` s back (else the object's first row, ``obj_first`` (B,)), the
    measurement std times the object's noise inflation; the filter's measurements zm and noise stds q, r (outputs
    row for row; ``lgekf.apps.windows`` sets the ``offset`` of each window's rows)."""
    return Restart(measurement, t, z, heading, zm, q, r, obj_first, cfg.meas_std, cfg.omega_std, cfg.heading_std, cfg.heading_cap,
                   REINIT_BASELINE)


def track_monitored(model, t, z, starts, cfg: TrackConfig, heading=None, measurement="position",
                    monitor: MonitorConfig | None = MonitorConfig(), start=None, limits=None) -> Tracked:
    """``track_arrays`` with divergence monitoring and recovery (``lgekf.apps.divergence``).

    Objects whose filter never raises an alarm get exactly the ``track_arrays`` output (flag 0); at an
    alarm the object is re-initialised from its last two measurements and continues, and the rows of the
    alarm through the re-initialisation are flagged 1. ``monitor=None``: no monitoring (all flags 0).

    ``start`` = (x0 (B, n), P0 (B, n, n)) and ``limits`` (B,): the objects' two-point start (``initial_common``
    + ``initial_estimates``) and speed limits (``divergence.speed_limits``) when already made from the same t,
    z, heading and cfg (they do not depend on the process noise: the noise search makes them once for its
    ~22 runs, ``lgekf.apps.defaults``); default (None): made here.
    """
    measurement = own_measurement(model, measurement)
    spec = get_model(model)
    t = np.ascontiguousarray(t, dtype=float)
    z = np.ascontiguousarray(z, dtype=float)
    starts = np.asarray(starts, dtype=np.int64)
    x0, P0 = (None, None) if start is None else start
    if monitor is None:
        x, p, nis = track_arrays(model, t, z, starts, cfg, heading=heading, x0=x0, P0=P0, measurement=measurement)
        return Tracked(x, p, nis, np.zeros(t.size, np.int8), [])
    zm, r = _measurement_inputs(spec, z, heading, cfg, measurement)
    x0, p0, x, p, nis = _started(model, t, z, starts, cfg, heading, x0, P0)
    s0 = np.empty((len(starts) - 1, len(spec.internal_names)))
    spec.kernels.states_from_physical(np.ascontiguousarray(x0, dtype=float), s0)
    if limits is None:
        limits = speed_limits(t, z, starts, cfg.meas_std, monitor)
    restart = restart_inputs(measurement, t, z, heading, zm, cfg.q(model), r, cfg, starts[:-1])
    # the first pass (the rows track_arrays filters) is made by the monitor's compiled loop too
    flag, alarms = recover(model, x, p, nis, starts, limits, zm.shape[1], monitor, restart,
                           first_pass=FirstPass(starts[:-1] + 2, s0, p0, np.ones(len(starts) - 1)))
    return Tracked(x, p, nis, flag, alarms)


def track_windows(model, t, z, cfg: TrackConfig, heading=None, measurement="position",
                  monitor: MonitorConfig | None = MonitorConfig(), rows: int = WINDOW_ROWS):
    """``track_monitored`` of ONE object (every row of t, z), a window of ``rows`` rows at a time: the same numbers,
    bit for bit, with the memory of a window (``lgekf.apps.windows``).

    Yields (a, Tracked) for consecutive row ranges [a, a + len) covering the object in order; each Tracked holds
    the alarms detected since the previous one (object 0), their rows counted from the object's first row (not
    from a) and possibly among the rows of the next piece (held back for its flags).
    """
    measurement = own_measurement(model, measurement)
    spec = get_model(model)
    t = np.ascontiguousarray(t, dtype=float)
    z = np.ascontiguousarray(z, dtype=float)
    starts = np.array([0, t.size], dtype=np.int64)
    c, var = initial_common(t, z, starts, cfg.meas_std, cfg.omega_std, heading, cfg.heading_std, cfg.heading_cap)
    x0, P0 = initial_estimates(model, c, var, moving_backwards(t, z, starts, cfg.meas_std))
    zm, r = _measurement_inputs(spec, z, heading, cfg, measurement)
    limit = 0.0 if monitor is None else float(speed_limits(t, z, starts, cfg.meas_std, monitor)[0])

    restart = restart_inputs(measurement, t, z, heading, zm, cfg.q(model), r, cfg, np.zeros(1, np.int64))
    for a, x, p, nis, flag, alarms in filter_windows(model, x0[0], pack(P0)[0], restart, monitor, limit, rows):
        yield a, Tracked(x, p, nis, flag, alarms)


# ------------------------------------------------------------------------------------------ CLI
ORIGIN_COLUMNS = ("origin_lat", "origin_lon")


def origin_columns(model: str) -> tuple:
    """The origin columns of a track file from lat, lon (, alt) input: origin_lat, origin_lon (, origin_alt in 3-D)."""
    return ORIGIN_COLUMNS + (("origin_alt",) if position_dims(model) == 3 else ())
MOTION_COLUMNS = ("speed", "course")  # beside every model's own state (``speed_course``)
MOTION_COLUMNS_3D = MOTION_COLUMNS + ("climb", "turn_rate")  # ... of a model of 3-D space
TURN_RATE_STEP = 1e-3  # s: the half step of the turn rate's central difference of the course along the model's motion


def position_dims(model: str) -> int:
    """The coordinates of the model's position (its space's dimension: 2 or 3)."""
    return SPACES[get_model(model).space]["dim"]


def motion_columns(model: str) -> tuple:
    """The motion columns of a track file of ``model`` beside its own state (``speed_course``)."""
    return MOTION_COLUMNS_3D if position_dims(model) == 3 else MOTION_COLUMNS


def speed_course(model: str, x: np.ndarray) -> np.ndarray:
    """(N, k): the speed |v| (m/s) and the course atan2(v_y, v_x) (rad, the direction of motion in the world frame) of
    physical states x (N, n), v the world velocity of the model's definition (``world_velocity``); for a model of
    3-D space also the climb rate v_z (m/s, up) and the turn rate (rad/s, the rate of change of the course along the
    model's own noise-free motion, ``turn_rates``): the columns ``motion_columns(model)``."""
    d = position_dims(model)
    x = np.ascontiguousarray(x, dtype=float)
    v = np.empty((x.shape[0], d))
    get_model(model).kernels.world_velocities(x, v)
    if d == 2:
        return speed_and_course(v)
    return np.column_stack([np.linalg.norm(v, axis=1), np.arctan2(v[:, 1], v[:, 0]), v[:, 2], turn_rates(model, x)])


def turn_rates(model: str, x: np.ndarray, h: float = TURN_RATE_STEP) -> np.ndarray:
    """(N,): the turn rate dχ/dt (rad/s) of physical states x (N, n), χ = atan2(v_y, v_x) the course: the central
    difference (χ(x(h)) − χ(x(−h)))/(2h) (wrapped to ±π) of the course along the model's noise-free motion x(τ)
    (the generated ``propagate_rows``), the same rule for every model: ω of the horizontal turn for CT3, the course's
    rate of a screw motion for SE(3)×R⁶ (not its body rate ω_z when the body is pitched or rolled), 0 for CV3.
    Nan where the horizontal speed is 0 (no course)."""
    k = get_model(model).kernels
    N = x.shape[0]
    d = position_dims(model)
    course = []
    for dt in (h, -h):
        xs = np.empty_like(x)
        k.propagate_rows(x, np.full(N, dt), xs)
        v = np.empty((N, d))
        k.world_velocities(xs, v)
        course.append(np.arctan2(v[:, 1], v[:, 0]))
    dchi = np.angle(np.exp(1j * (course[0] - course[1])))
    v = np.empty((N, d))
    k.world_velocities(x, v)
    return np.where(np.hypot(v[:, 0], v[:, 1]) > 0, dchi / (2 * h), np.nan)


def speed_and_course(v: np.ndarray) -> np.ndarray:
    """(N, 2): |v| and atan2(v_y, v_x) of world velocities v (N, 2)."""
    return np.column_stack([np.hypot(v[:, 0], v[:, 1]), np.arctan2(v[:, 1], v[:, 0])])


def output_columns(model, full_cov=False, origin=False, smooth=False):
    """The header of a track file: id, t, state, std_<state>, speed, course, [cov_<i>_<j>], nis, [origin_lat,
    origin_lon], flag.

    ``speed`` and ``course`` (``speed_course``): every model's speed and direction of motion in the world frame, the
    same quantities whatever the state (SE(2)×SE(2) / SE(2)×R³: θ is the body heading, the course is θ +
    atan2(v_y, v_x); CTRV: ψ is the course; CV: atan2(v_y, v_x)).

    ``origin``: the input had lat, lon columns; those two columns then hold the origin (degrees) of
    the east/north frame of x, y (``lgekf.io.geo``), the same on every row. ``flag``: 1 on the rows of a
    detected divergence through the object's re-initialisation, else 0 (``lgekf.apps.divergence``).
    """
    spec = get_model(model)
    names = list(spec.state_names)
    cols = ["id", "t", *names, *(f"std_{s}" for s in names), *motion_columns(model)]
    if full_cov:
        i, j = np.triu_indices(spec.n)
        cols += [f"cov_{a}_{b}" for a, b in zip(i, j)]
    cols = cols + ["nis"] + (list(origin_columns(model)) if origin else []) + ["flag"]
    if smooth:  # `--smooth`: smooth_<state>, smooth_std_<state> (lgekf.apps.smooth_track)
        cols += [f"smooth_{s}" for s in names] + [f"smooth_std_{s}" for s in names]
    return cols


def output_path(out, model: str, all_models: bool):
    """The file of ``model``: ``out`` itself, or with ``--model all`` the model name inserted before the
    suffix (``tracks.csv`` -> ``tracks_cv.csv``, ``tracks.csv.gz`` -> ``tracks_cv.csv.gz``)."""
    if not all_models or is_stdio(out):
        return out
    out = Path(out)
    gz = out.name.endswith(".gz")
    base = Path(out.name[:-3] if gz else out.name)
    return out.with_name(f"{base.stem}_{model}{base.suffix}{'.gz' if gz else ''}")


@dataclass
class ClassConfigs:
    """Noise per class of objects (``lgekf.apps.defaults.plan_noise_by_class``): object b runs with
    ``configs[of_object[b]]``."""

    of_object: np.ndarray
    configs: list

    @classmethod
    def of_all(cls, cfg: TrackConfig, objects: int) -> "ClassConfigs":
        return cls(np.zeros(objects, dtype=np.int64), [cfg])

    def of(self, b: int) -> TrackConfig:
        """The configuration of object b."""
        return self.configs[int(self.of_object[b])]

    def slice(self, o: int, o2: int) -> "ClassConfigs":
        """The classes of objects o .. o2 - 1."""
        return ClassConfigs(self.of_object[o:o2], self.configs)


def _smoothed_chunk(model, t, z, h, sub_starts, cfg, measurement, r):
    from .smooth_track import smoothed_columns

    zm, q, rr = smoothing_inputs(model, z, cfg, h, measurement)
    cols, failed = smoothed_columns(model, measurement, t, zm, sub_starts, r, q, rr)
    for f in failed:  # its smoothed columns repeat the filter's (smoothed_columns)
        r.flag[sub_starts[f]:sub_starts[f + 1]] |= SMOOTH_FAILED
    return cols, failed


def track_chunk(model, t, z, heading, starts, classes: ClassConfigs, measurement="position",
                monitor: MonitorConfig | None = MonitorConfig(), smooth: bool = False):
    """``track_monitored`` (and with ``smooth`` the smoothed columns) of the objects of t, z (``starts``), each class of
    objects with its own noise: the rows of one class gathered, tracked together, and put back in place (alarms' objects
    and rows counted in t, z; in order of object and row). Returns (Tracked, [smoothed columns] or [], objects whose
    smoother failed)."""
    present = np.unique(classes.of_object)

    def run(cfg, t, z, h, st):
        r = track_monitored(model, t, z, st, cfg, heading=h, measurement=measurement, monitor=monitor)
        if not smooth:
            return r, [], []
        cols, failed = _smoothed_chunk(model, t, z, h, st, cfg, measurement, r)
        return r, [cols], failed

    if present.size == 1:
        return run(classes.configs[int(present[0])], t, z, heading, starts)
    spec = get_model(model)
    N = t.size
    out = Tracked(np.empty((N, spec.n)), np.empty((N, spec.n_packed)), np.empty(N), np.empty(N, np.int8), [])
    extra = [np.empty((N, 2 * spec.n))] if smooth else []
    failed = []
    for c in present:
        objs = np.flatnonzero(classes.of_object == c)
        rows, st = objects_subset(starts, objs)
        r, ex, fl = run(classes.configs[int(c)], t[rows], z[rows], None if heading is None else heading[rows], st)
        out.x[rows], out.p[rows], out.nis[rows], out.flag[rows] = r.x, r.p, r.nis, r.flag
        for dst, src in zip(extra, ex):
            dst[rows] = src
        for al in r.alarms:
            al.obj, al.row = int(objs[al.obj]), int(rows[al.row])
        out.alarms.extend(r.alarms)
        failed.extend(int(objs[f]) for f in fl)
    out.alarms.sort(key=lambda al: (al.obj, al.row))
    return out, extra, sorted(failed)


def write_model(fh, model, meas, starts, cfg, full_cov, digits, bar, measurement="position",
                monitor: MonitorConfig | None = MonitorConfig(), smooth: bool = False, parquet: bool = False):
    """Track and write one model's file in chunks of objects (bounded memory; ``cfg`` a ``TrackConfig`` or the
    ``ClassConfigs`` of objects with noise of their own); ``bar.update`` per chunk
    written (``bar`` None: no progress). ``smooth``: also the smoothed columns (``lgekf.apps.smooth_track``).
    ``parquet``: a Parquet file (``lgekf.io.parquet``, a row group per ``FORMAT_ROWS`` rows of a chunk) instead of
    CSV text; CSV text is made, formatted and written a few thousand rows at a time (``write_rows_made``).

    The two jobs overlap: one writer thread formats and writes chunk i while this thread tracks chunk i + 1
    (the formatter and the file writes release the GIL), so that at most two chunks' outputs (and a few parts'
    text) are held. The
    chunks are written in order: the file's bytes are those of doing one after the other.

    Returns a ``Written`` (rows, alarms (``divergence.Alarm``, object indices of ``meas``), flagged rows, objects whose
    smoother failed).
    """
    spec = get_model(model)
    cfg = ClassConfigs.of_all(cfg, len(starts) - 1) if isinstance(cfg, TrackConfig) else cfg
    origin = meas.origin is not None
    columns = output_columns(model, full_cov, origin, smooth)
    sink = ParquetRows(fh, columns) if parquet else None
    if sink is None:
        fh.write((",".join(columns) + "\n").encode())
    lab = label_bytes(meas.labels)
    diag = packed_diagonal(spec.n)
    m = spec.n * 2 + len(motion_columns(model)) + (spec.n_packed if full_cov else 0) + 1
    n_origin = len(origin_columns(model))
    col_digits, t_digits = output_digits(columns[2:], digits, meas.z, meas.t)  # digits None: positions to 0.1 mm, t to 1 µs
    col_digits[m:m + (n_origin if origin else 0)] = 17  # the origin exactly: to_latlon(x, y, origin_lat, origin_lon) inverts it

    def emit(parts, row_obj, a, b):  # the writer thread: chunk rows a..b as text (or row groups)
        def block(lo, hi):  # the output values of the chunk's rows lo..hi-1 (r.p at 1: its diagonal's stds)
            return np.hstack([np.sqrt(np.maximum(v[lo:hi][:, diag], 0.0)) if i == 1 else v[lo:hi] for i, v in enumerate(parts)])

        if sink is None:  # made, formatted and written part by part in threads
            write_rows_made(fh, lab, row_obj, meas.t[a:b], block, b - a, col_digits, t_digits)
            return b - a
        for lo in range(0, b - a, FORMAT_ROWS):  # a row group at a time
            hi = min(lo + FORMAT_ROWS, b - a)
            sink.write_rows(meas.labels, row_obj[lo:hi], meas.t[a + lo:a + hi], block(lo, hi))
        return b - a

    B = len(starts) - 1
    o = 0
    alarms = []
    smooth_failed = []
    flagged = 0
    with ThreadPoolExecutor(1) as writer:  # on an error here, leaving the block waits for the chunk being written
        pending = None

        def submit(r, o, o2, a, extra=(), alarm_row0=None):
            # the rows a .. a + len(r.x) of objects o .. o2 - 1 to the writer thread; r.alarms' rows count from row
            # alarm_row0 (default a: a chunk's; a window's count from its object's first row)
            nonlocal pending, flagged
            b = a + r.x.shape[0]
            for al in r.alarms:
                al.obj += o
                al.row += a if alarm_row0 is None else alarm_row0
            alarms.extend(r.alarms)
            flagged += int((r.flag & 1).sum())
            parts = [r.x, r.p, speed_course(model, r.x)] + ([r.p] if full_cov else []) + [r.nis[:, None]]  # r.p at 1: stds
            if origin:
                parts.append(np.broadcast_to(np.asarray(meas.origin, dtype=float), (b - a, n_origin)))
            parts.append(r.flag[:, None])
            parts.extend(extra)
            row_obj = row_objects(starts, o, o2) if o2 > o + 1 else np.full(b - a, o, dtype=np.int64)  # meas.obj of grouped rows
            _written(pending, bar)
            pending = writer.submit(emit, parts, row_obj, a, b)

        while o < B:
            o2 = int(np.searchsorted(starts, starts[o] + ROWS_PER_CHUNK, side="right")) - 1
            o2 = min(max(o2, o + 1), B)
            a, b = int(starts[o]), int(starts[o2])
            sub_starts = starts[o:o2 + 1] - a
            h = None if meas.heading is None else meas.heading[a:b]
            if b - a > ROWS_PER_CHUNK and not smooth:  # one long object: a window of rows at a time (lgekf.apps.windows)
                for a2, r in track_windows(model, meas.t[a:b], meas.z[a:b], cfg.of(o), h, measurement, monitor, ROWS_PER_CHUNK):
                    submit(r, o, o2, a + a2, alarm_row0=a)
                    del r
            else:
                r, extra, failed = track_chunk(model, meas.t[a:b], meas.z[a:b], h, sub_starts, cfg.slice(o, o2), measurement,
                                               monitor, smooth)
                smooth_failed.extend(o + f for f in failed)
                submit(r, o, o2, a, extra)
                del r, extra
            o = o2
        _written(pending, bar)
    if sink is not None:
        sink.close()
    return Written(int(starts[-1]), alarms, flagged, smooth_failed)


@dataclass
class Written:
    """What ``write_model`` wrote: rows, the monitor's alarms (object indices of ``meas``), the rows flagged by them,
    and the objects whose smoother failed (flag + ``SMOOTH_FAILED``; their smoothed columns repeat the filter's)."""

    rows: int
    alarms: list
    flagged: int
    smooth_failed: list


def _written(pending, bar) -> None:
    """Wait for the writer's chunk (its error raised here) and count its rows on the progress bar."""
    if pending is None:
        return
    rows = pending.result()
    if bar is not None:
        bar.update(rows)
