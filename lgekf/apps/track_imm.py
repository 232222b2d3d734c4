"""``lgekf track --model imm``: every object of a file through an IMM of registry models.

Each object starts like every ``lgekf track`` filter (the two-point estimate of its first two measurements in
the common coordinates, ``lgekf.apps.track.initial_common``; every mode converts it to its own coordinates)
and runs :func:`lgekf.estimators.imm.imm_batch` from its third measurement on. The measurement std is
``--meas-std`` or estimated from the data (``lgekf.apps.noise.measurement_std``, as for the filters); the modes'
process noise is given in ``--imm-modes`` (named levels × the model's default noise, or the stds). No
divergence monitor (the ``flag`` column is 0). Output columns: id, t, the combined estimate in the common
coordinates x, y, theta, vx, vy (body frame), omega, their stds, mu_<mode> (mode probabilities), and
origin_lat, origin_lon for lat/lon input, flag.
"""

from __future__ import annotations

import numpy as np

from ..estimators.imm import DEFAULT_SWITCH, imm_batch, parse_modes, transition_matrix
from ..io.formatting import format_rows, label_bytes
from .track import DEFAULT_MEAS_STD, ORIGIN_COLUMNS, initial_common

__all__ = ["DEFAULT_TRACK_MODES", "ImmTrackOptions", "imm_columns", "write_imm", "imm_track_common",
           "common_world_velocity", "COMMON_NAMES", "IMM_FILTER"]

IMM_FILTER = "imm"  # its name in the tables of ``lgekf evaluate``

#: ``lgekf track --model imm`` / ``lgekf evaluate --imm`` modes by default: CV and a calm and a manoeuvring SE(2)×R³
#: (measured on the real-data evaluation against se2r3:calm,se2r3:manoeuvre and cv,se2r3, see README)
DEFAULT_TRACK_MODES = "cv,se2r3:calm,se2r3:manoeuvre"
COMMON_NAMES = ("x", "y", "theta", "vx", "vy", "omega")


class ImmTrackOptions:
    """The IMM of ``lgekf track``: modes (``parse_modes`` syntax) and the per-step switching probability."""

    def __init__(self, modes: str | None = None, switch: float | None = None):
        self.modes_text = DEFAULT_TRACK_MODES if modes is None else modes
        self.switch = DEFAULT_SWITCH if switch is None else float(switch)
        self.modes = parse_modes(self.modes_text)
        transition_matrix(len(self.modes), self.switch)


def imm_columns(opts: ImmTrackOptions, origin: bool = False) -> list:
    """The header of an IMM track file (module docstring); mode columns are named mu_<model>[_<label>]."""
    mode_cols = []
    for m in opts.modes:
        base = f"mu_{m.name.replace(':', '_').replace('/', '-')}"
        name, k = base, 2
        while name in mode_cols:
            name, k = f"{base}_{k}", k + 1
        mode_cols.append(name)
    return (["id", "t", *COMMON_NAMES, *(f"std_{s}" for s in COMMON_NAMES), *mode_cols]
            + (list(ORIGIN_COLUMNS) if origin else []) + ["flag"])


def imm_track_common(t, z, starts, meas_std: float, omega_std: float, opts: ImmTrackOptions):
    """Every object's IMM estimate in the common coordinates: c (N, 6), their stds (N, 6), mode probabilities (N, M).

    Row 0 of an object is the two-point estimate at its first measurement's position, row 1 the two-point estimate
    (uniform mode probabilities), rows >= 2 the IMM's posteriors (as ``lgekf.apps.track.track_arrays``).
    """
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


def common_world_velocity(c: np.ndarray) -> np.ndarray:
    """World-frame velocity (N, 2) of common coordinates c (N, 6): R(θ)·(v_x, v_y)."""
    ct, st = np.cos(c[:, 2]), np.sin(c[:, 2])
    return np.stack([ct * c[:, 3] - st * c[:, 4], st * c[:, 3] + ct * c[:, 4]], axis=1)


def write_imm(fh, meas, starts, opts: ImmTrackOptions, meas_std: float, omega_std: float, digits: int, bar=None) -> int:
    """Track every object of ``meas`` (sorted, ``starts`` offsets, >= 2 rows each) and write the CSV to ``fh``."""
    origin = meas.origin is not None
    fh.write((",".join(imm_columns(opts, origin)) + "\n").encode())
    lab = label_bytes(meas.labels)
    M = len(opts.modes)
    t = np.ascontiguousarray(meas.t, float)
    c, sd, mu = imm_track_common(t, meas.z, starts, meas_std, omega_std, opts)
    ncol = 12 + M + (2 if origin else 0) + 1
    col_digits = np.full(ncol, digits, dtype=np.int64)
    parts = [c, sd, mu]
    if origin:
        col_digits[12 + M:12 + M + 2] = 17
        parts.append(np.broadcast_to(np.asarray(meas.origin, dtype=float), (t.size, 2)))
    parts.append(np.zeros((t.size, 1)))
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
    if est.windows:
        return float(est.meas_std), f"data: {est.describe()}"
    return float(DEFAULT_MEAS_STD), "default: too few measurements to estimate it"
