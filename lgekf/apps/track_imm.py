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

__all__ = ["DEFAULT_TRACK_MODES", "ImmTrackOptions", "imm_columns", "write_imm", "COMMON_NAMES"]

#: ``lgekf track --model imm`` modes by default: a calm and a manoeuvring SE(2)×R³
DEFAULT_TRACK_MODES = "se2r3:calm,se2r3:manoeuvre"
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


def write_imm(fh, meas, starts, opts: ImmTrackOptions, meas_std: float, omega_std: float, digits: int, bar=None) -> int:
    """Track every object of ``meas`` (sorted, ``starts`` offsets, >= 2 rows each) and write the CSV to ``fh``."""
    origin = meas.origin is not None
    fh.write((",".join(imm_columns(opts, origin)) + "\n").encode())
    lab = label_bytes(meas.labels)
    M = len(opts.modes)
    t, z = np.ascontiguousarray(meas.t, float), np.ascontiguousarray(meas.z[:, :2], float)
    c0, var0 = initial_common(t, z, starts, meas_std, omega_std)
    ncol = 12 + M + (2 if origin else 0) + 1
    col_digits = np.full(ncol, digits, dtype=np.int64)
    if origin:
        col_digits[12 + M:12 + M + 2] = 17
    for b in range(len(starts) - 1):
        a, e = int(starts[b]), int(starts[b + 1])
        n = e - a
        vals = np.full((n, ncol), np.nan)
        vals[:, -1] = 0.0
        vals[0, :2] = z[a]
        vals[1, :6] = c0[b]
        vals[:2, 6:12] = np.sqrt(var0[b])
        vals[:2, 12:12 + M] = 1.0 / M
        if n > 2:
            dts = np.diff(t[a + 1:e])[None]
            est, mu, P = imm_batch(z[None, a + 2:e], opts.modes, opts.switch, dt=dts, meas_std=meas_std, x0=c0[b],
                                   P0=np.diag(var0[b]), return_cov=True)
            vals[2:, :6] = est[0]
            vals[2:, 6:12] = np.sqrt(np.maximum(np.diagonal(P[0], axis1=1, axis2=2), 0.0))
            vals[2:, 12:12 + M] = mu[0]
        if origin:
            vals[:, 12 + M:12 + M + 2] = np.asarray(meas.origin, dtype=float)
        fh.write(format_rows(lab, meas.obj[a:e], t[a:e], vals, col_digits))
        if bar is not None:
            bar.update(n)
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
