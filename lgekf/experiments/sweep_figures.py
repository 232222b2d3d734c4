"""Figures of a protocol sweep: position RMSE against one swept axis, one line per filter.

For every value of the axis the line is the mean of ``mean_rmse`` over all the other cells of the sweep
(every combination of the other axes and σ_ω values, equally weighted), the band their minimum to maximum:
a marginal view; the full table is in ``cells.csv``. The RMSE axis is logarithmic when the values span
more than a factor ``LOG_SPAN`` (10), as when some protocols lose the track and others do not.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from ..core.registry import MODELS

__all__ = ["axis_figure", "AXIS_LABELS"]

AXIS_LABELS = {
    "sigma_w": "rotational process noise σ_ω [rad/s²]", "dt": "sampling period T [s]", "steps": "measurements per trajectory",
    "trajectories": "trajectories per cell", "v0": "initial body velocity v₀ = (v_x, v_y) [m/s]", "w0": "initial ω₀ [rad/s]",
    "sigma_v": "σ_v [m/s²]", "meas_std": "measurement noise std [m]", "init_std": "initial-error stds",
    "truth": "truth model", "seed": "base seed", "noise_scale": "process-noise scale", "measurement": "measurement model",
    "heading_std": "heading noise std [rad]",
}
LOG_SPAN = 10.0  # the RMSE axis is logarithmic when the values span more than this factor
_COLORS = {**{name: spec.color for name, spec in MODELS.items()}, "measurements": "0.45"}
_NAMES = {**{name: spec.display_name for name, spec in MODELS.items()}, "measurements": "measurements"}


def _is_numeric(values) -> bool:
    return all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values)


def axis_figure(rows, axis: str, filters, path, n_cells: int | None = None) -> Path:
    """Draw RMSE versus ``axis`` and save it as PNG (through a temporary file and a rename).

    Parameters
    ----------
    rows : list of dict
        Table rows (keys: the table's columns).
    axis : str
        The column on the x axis.
    filters : sequence of str
        The filters to draw, in legend order (``measurements`` is added, dashed).
    path : str or Path
        The PNG to write.
    n_cells : int, optional
        The number of cells, for the title.

    Returns
    -------
    Path
        ``path``.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    values = list(dict.fromkeys(r[axis] for r in rows))
    numeric = _is_numeric(values)
    if numeric:
        values = sorted(values)
    pos = {v: (float(v) if numeric else float(i)) for i, v in enumerate(values)}
    fig, ax = plt.subplots(figsize=(7.0, 4.2))
    others = 0
    lo, hi = np.inf, 0.0
    for name in (*filters, "measurements"):
        mine = [r for r in rows if r["filter"] == name]
        if not mine:
            continue
        by = {v: [] for v in values}
        for r in mine:
            by[r[axis]].append(r["mean_rmse"])
        xs = np.array([pos[v] for v in values if by[v]])
        ys = [np.asarray(by[v]) for v in values if by[v]]
        others = max(others, max(len(y) for y in ys))
        mean = np.array([y.mean() for y in ys])
        style = {"ls": "--", "lw": 1.2} if name == "measurements" else {"lw": 1.8, "marker": "o", "ms": 3}
        ax.plot(xs, mean, color=_COLORS.get(name, "k"), label=_NAMES.get(name, name), **style)
        ax.fill_between(xs, [y.min() for y in ys], [y.max() for y in ys], color=_COLORS.get(name, "k"), alpha=0.12, lw=0)
        lo, hi = min(lo, min(y.min() for y in ys)), max(hi, max(y.max() for y in ys))
    if not numeric:
        ax.set_xticks([pos[v] for v in values])
        ax.set_xticklabels([str(v) for v in values], rotation=20 if max(len(str(v)) for v in values) > 8 else 0)
    ax.set_xlabel(AXIS_LABELS.get(axis, axis))
    ax.set_ylabel("position RMSE [m]")
    cells = f"{n_cells} cells; " if n_cells else ""
    ax.set_title(f"position RMSE vs {axis} ({cells}line: mean over the other {others} protocol"
                 f"{'s' if others != 1 else ''}\nat each value, band: their min to max)", fontsize=9)
    if lo > 0 and hi / lo > LOG_SPAN:  # lost tracks next to good ones: a log axis shows both
        from matplotlib.ticker import FormatStrFormatter

        ax.set_yscale("log")
        ax.yaxis.set_major_formatter(FormatStrFormatter("%g"))
        ax.yaxis.set_minor_formatter(FormatStrFormatter("%g"))
    else:
        ax.set_ylim(bottom=0)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, ncol=2)
    fig.tight_layout()
    path = Path(path)
    tmp = path.with_name(f".{path.name}.tmp{os.getpid()}")
    try:
        fig.savefig(tmp, dpi=130, format="png")
        tmp.replace(path)
    finally:
        plt.close(fig)
        if tmp.exists():
            tmp.unlink()
    return path
