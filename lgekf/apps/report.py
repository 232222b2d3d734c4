"""The tables (text, Markdown, CSV) and the figure of `lgekf evaluate`, from the rows of ``DatasetResult.summary``."""

from __future__ import annotations

import csv
import io
import math
from pathlib import Path

from ..core.registry import ALL_MODELS, SPACES
from ..experiments.statistics import MIN_TRACKS_CI
from .evaluate import MOTION_METRICS, baseline_of

__all__ = ["SUMMARY_FIELDS", "MOTION_FIELDS", "summary_fields", "format_table", "markdown_table", "motion_table", "evaluation_figure",
           "interval_text"]

BASELINES = {baseline_of(s) for s in SPACES}  # the filter of each space the Δ column is against
MOTION_FIELDS = [f"{name}_rmse" for name in MOTION_METRICS]  # the rows of a 3-D dataset (``DatasetResult.summary``)


SUMMARY_FIELDS = ["dataset", "filter", "noise", "scale", "turn_ratio", "accel_std", "tracks", "skipped_short", "seeds", "diverged",
                  "pos_rmse", "pos_ci_lo", "pos_ci_hi", "pos_median", "dpos_vs_cv", "dpos_ci_lo", "dpos_ci_hi",
                  "vel_rmse", "vel_ci_lo", "vel_ci_hi"]


def summary_fields(rows) -> list:
    """The columns of summary.csv: ``SUMMARY_FIELDS``, and ``MOTION_FIELDS`` when a row has them (3-D datasets; empty
    in the other rows)."""
    return SUMMARY_FIELDS + (MOTION_FIELDS if any(MOTION_FIELDS[0] in r for r in rows) else [])


def motion_table(rows) -> str:
    """The Markdown table of the motion errors of the 3-D datasets' rows (mean over tracks of the per-track RMSE):
    position, velocity, speed, course, climb, turn rate, attitude; "" when no row has them."""
    rows = [r for r in rows if MOTION_FIELDS[0] in r and r["filter"] != "measurements"]
    if not rows:
        return ""
    units = {"pos": "m", "vel": "m/s", **MOTION_METRICS}
    names = ["pos", "vel", *MOTION_METRICS]
    head = "| dataset | filter | noise | " + " | ".join(f"{n.replace('_', ' ')} ({units[n]})" for n in names) + " |"
    lines = [head, "|" + "---|" * (3 + len(names))]
    for r in rows:
        vals = [r["pos_rmse"], r["vel_rmse"], *(r[f] for f in MOTION_FIELDS)]
        lines.append(f"| {r['dataset']} | {r['filter']} | {r['noise']} | " + " | ".join("–" if math.isnan(v) else f"{v:.3f}" for v in vals) + " |")
    return "\n".join(lines)


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
        dlt = "" if r["filter"] in (*BASELINES, "measurements") else interval_text(r, "dpos", signed=True)
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
        dlt = "" if r["filter"] in (*BASELINES, "measurements") else interval_text(r, "dpos", signed=True)
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
        w.writerow([_fmt(r.get(k, ""), 6) if isinstance(r.get(k), float) else r.get(k, "") for k in fieldnames])
    return buf.getvalue()


def evaluation_figure(rows, path: Path, noise: str):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows = [r for r in rows if r["noise"] in (noise, "-")]
    datasets = list(dict.fromkeys(r["dataset"] for r in rows))
    vel_sets = [d for d in datasets if any(r["dataset"] == d and not math.isnan(r["vel_rmse"]) for r in rows)]
    names = [m for m in (*ALL_MODELS, "measurements") if any(r["filter"] == m for r in rows)]  # the space's filters
    panels = [("pos", datasets, "m")] + ([("vel", vel_sets, "m/s")] if vel_sets else [])
    widths = [len(d) + 0.6 for _, d, _ in panels]
    # at least 7 in wide: the legend and the two-line title must fit even for a single dataset
    fig, axes = plt.subplots(1, len(panels), figsize=(max(1.0 * sum(widths) + 1.5, 7.0), 4.6), squeeze=False,
                             gridspec_kw={"width_ratios": widths})
    colors = {**{name: spec.color for name, spec in ALL_MODELS.items()}, "measurements": "0.7", "imm": "tab:brown"}
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
