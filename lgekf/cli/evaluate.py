"""`lgekf evaluate`: every filter on real ground-truth trajectories (``lgekf.apps.evaluate``), tables and figure
into an all-or-nothing output folder."""

from __future__ import annotations

import csv
import io
import json
import sys
import time
from pathlib import Path

import numpy as np

from ..apps.evaluate import TUNE_RATIOS, TUNE_SCALES, evaluate_dataset, filters_of
from ..core.registry import DEFAULT_SPACE
from ..apps.report import _csv_text, _fmt, evaluation_figure, format_table, markdown_table, motion_table, summary_fields
from ..apps.track import DEFAULT_ACCEL_STD
from ..experiments.statistics import BOOTSTRAP_RESAMPLES, BOOTSTRAP_SEED, MIN_TRACKS_CI
from ..core.validate import positive_scalar
from ..io.datasets import GROUPS, PRESETS, load_dataset
from ..io.output import staged_directory, write_atomic
from . import ArgumentParser
from .cluster import add_cluster_options, check_cluster_options, cluster_requested
from .progress import compile_notice, progress_bar, stderr_is_terminal

__all__ = ["cmd_evaluate", "evaluate_parser"]


def evaluate_parser():
    ap = ArgumentParser(prog="lgekf evaluate", description="Evaluate every registry filter on real ground-truth trajectories with added position noise.")
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
                    help="tune each filter's process noise on the first 30 %% of tracks (--tune-method), evaluate on the rest")
    ap.add_argument("--tune-method", choices=["mle", "grid", "em"], default="mle",
                    help="with --tune: mle = maximum-likelihood process noise learned on the tuning split (default), "
                         "grid = the RMSE grid search over k·default noise and the turn-rate ratio, "
                         "em = as mle, by EM for the linear Gaussian filters (CV), the optimiser for the others")
    ap.add_argument("--smooth", action="store_true", help="also rows <model>:smoothed, the RTS smoother on the group")
    ap.add_argument("--imm", action="store_true",
                    help="add an IMM row (modes --imm-modes; with --tune (mle) its modes take their models' learned noise; one process only)")
    ap.add_argument("--imm-modes", default=None, metavar="LIST", help="--imm: modes (default cv,se2r3:calm,se2r3:manoeuvre)")
    ap.add_argument("--imm-switch", type=float, default=None, metavar="P", help="--imm: probability of leaving a mode per step (default 0.05)")
    ap.add_argument("--out", type=Path, default=Path("evaluation"), help="output folder (default evaluation/)")
    ap.add_argument("--no-figure", action="store_true", help="skip evaluation.png")
    ap.add_argument("--markdown", action="store_true", help="print the table as Markdown")
    ap.add_argument("--quiet", action="store_true", help="print only the output folder (no notes, progress or table)")
    add_cluster_options(ap)
    ap.add_argument("--partition-rows", type=int, default=None, metavar="N",
                    help="with --workers/--scheduler: rows per partition of whole tracks (default: 2 partitions per worker)")
    return ap


def cmd_evaluate(argv) -> int:
    a = evaluate_parser().parse_args(argv)
    check_cluster_options(a)
    if a.partition_rows is not None and a.partition_rows < 1:
        raise ValueError(f"--partition-rows: must be at least 1, got {a.partition_rows}")
    with compile_notice("lgekf evaluate", enabled=not a.quiet):
        if not cluster_requested(a):
            return _evaluate(a)
        from ..apps.cluster import dask_client, require_dask, worker_count
        from ..apps.evaluate_dask import DaskRunner

        require_dask("lgekf evaluate --workers/--scheduler")
        with dask_client(workers=a.workers, scheduler=a.scheduler, what="lgekf evaluate --workers/--scheduler") as client:
            return _evaluate(a, DaskRunner(client, a.partition_rows, worker_count(client)))


def _evaluate(a, runner=None) -> int:
    positive_scalar("--meas-std", a.meas_std)
    if a.seeds < 1:
        raise ValueError(f"--seeds: must be at least 1, got {a.seeds}")
    if a.min_length < 3:
        raise ValueError(f"--min-length: must be at least 3 (two samples initialise the filter), got {a.min_length}")
    from ..apps.track_imm import ImmTrackOptions

    if not a.imm and (a.imm_modes is not None or a.imm_switch is not None):
        raise ValueError("--imm-modes/--imm-switch: only with --imm")
    imm = None
    if a.imm:  # for the space of the given modes (else the plane's defaults; each dataset takes its own space's)
        from ..estimators.imm.estimator import parse_modes, space_of_modes

        imm = ImmTrackOptions(a.imm_modes, a.imm_switch,
                              space_of_modes(parse_modes(a.imm_modes)) if a.imm_modes is not None else DEFAULT_SPACE)
    names = []
    for d in a.datasets:
        names += GROUPS.get(d, [d])
    t0 = time.perf_counter()
    datasets = [load_dataset(d, root=a.data_root, fmt=a.format, frame_dt=a.frame_dt, min_length=a.min_length) for d in names]
    if len({d.name for d in datasets}) != len(datasets):
        raise ValueError("datasets: the same dataset (name) is given twice")
    rows, tuning, per_track, fits, learned, imm_sets = [], [], [], [], [], []
    steps = 1 + ((2 * len(TUNE_SCALES) + len(TUNE_RATIOS) if a.tune_method == "grid" else 1) if a.tune else 0)  # runs per dataset (tuning grid + evaluation)
    bar = progress_bar(len(datasets) * steps, "lgekf evaluate", not a.quiet and stderr_is_terminal(), unit="runs")
    for ds in datasets:
        results = evaluate_dataset(ds, meas_std=a.meas_std, seeds=a.seeds, base_seed=a.seed, tune=a.tune,
                                   progress=lambda stage: bar.update(1), runner=runner, tune_method=a.tune_method, smooth=a.smooth, imm=imm)
        bar.update(1)
        for res in results:
            rows += res.summary()
            if res.noise == "tuned":
                tuning += [{"dataset": ds.name, "filter": m, "stage": st, "scale": k, "turn_ratio": rho, "tune_pos_rmse": sc,
                            "chosen": False, "tune_tracks": res.n_tune_tracks} for m, st, k, rho, sc in res.tuning]
                for m in filters_of(ds):  # mark the first row that reached the chosen value
                    mine = [r for r in tuning if r["dataset"] == ds.name and r["filter"] == m]
                    if mine:  # (none with --tune-method mle)
                        min(mine, key=lambda r: r["tune_pos_rmse"])["chosen"] = True
                for m, fit in res.fits.items():
                    if isinstance(fit, str):
                        kept = ("the modes take their models' learned noise × level" if m == "imm" else "the default noise is kept")
                        fits.append(f"{ds.name}: {m}: {fit}; {kept}")
                        continue
                    fits.append(f"{ds.name}: {fit.report()}")
                    learned += [{"dataset": ds.name, "filter": m, "parameter": nm, "value": v, "ci_lo": lo, "ci_hi": hi,
                                 "loglik": fit.loglik, "updates": fit.n_updates, "identified": fit.identified,
                                 "tune_tracks": res.n_tune_tracks}
                                for nm, v, lo, hi in zip(fit.names, fit.values, fit.ci_low, fit.ci_high)]
                for text, fit, kept in res.imm_sets:  # every mode set the IMM fit compared (--imm --tune)
                    ok = not isinstance(fit, str)
                    imm_sets.append({"dataset": ds.name, "modes": text, "kept": kept, "aic": fit.aic if ok else np.nan,
                                     "loglik": fit.loglik if ok else np.nan, "params": fit.n_params if ok else "",
                                     "switch": fit.switch if ok else np.nan,
                                     "factors": ";".join(f"{v:.4g}" for v in fit.factors) if ok else "",
                                     "problems": "; ".join(fit.problems) if ok else fit})
            for m, (pos, vel) in res.rmse.items():
                for si in range(pos.shape[0]):
                    for j, lab in enumerate(res.dataset.labels):
                        per_track.append([ds.name, res.noise, lab, a.seed + si, m, pos[si, j], np.nan if vel is None else vel[si, j]])
    if a.tune:  # the tuned rows and the measurements once; the default rows on the same split for reference
        seen = set()
        rows = [r for r in rows if not (r["filter"] == "measurements" and (r["dataset"] in seen or seen.add(r["dataset"])))]
    out = a.out
    with staged_directory(out) as stage:
        write_atomic(stage / "summary.csv", _csv_text(summary_fields(rows), rows))
        buf = io.StringIO()
        w = csv.writer(buf, lineterminator="\n")
        w.writerow(["dataset", "noise", "track", "seed", "filter", "pos_rmse", "vel_rmse"])
        for r in per_track:
            w.writerow(r[:5] + [_fmt(float(r[5]), 6), _fmt(float(r[6]), 6)])
        write_atomic(stage / "per_track.csv", buf.getvalue())
        if learned:  # --tune-method mle: the learned noise, its 95 % interval and likelihood
            write_atomic(stage / "learned.csv", _csv_text(["dataset", "filter", "parameter", "value", "ci_lo", "ci_hi", "loglik", "updates",
                                                           "identified", "tune_tracks"], learned))
        if imm_sets:
            write_atomic(stage / "imm_sets.csv", _csv_text(["dataset", "modes", "kept", "aic", "loglik", "params", "switch", "factors",
                                                            "problems"], imm_sets))
        if tuning:
            write_atomic(stage / "tuning.csv", _csv_text(["dataset", "filter", "stage", "scale", "turn_ratio", "tune_pos_rmse", "chosen", "tune_tracks"], tuning))
        meta = {
            "datasets": {d.name: {"description": d.description, "tracks": d.n_tracks, "skipped_short": d.skipped,
                                  "samples": int(d.t.size), "velocity_truth": d.v is not None} for d in datasets},
            "meas_std": a.meas_std, "seeds": a.seeds, "first_seed": a.seed, "min_length": a.min_length, "tune": a.tune, "tune_method": a.tune_method if a.tune else None, "smooth": a.smooth,
            "tune_scales": list(TUNE_SCALES) if a.tune and a.tune_method == "grid" else None, "tune_turn_ratios": list(TUNE_RATIOS) if a.tune and a.tune_method == "grid" else None, "tune_split": "first 30 % of tracks" if a.tune else None,
            "default_accel_std": {m: list(v) for m, v in DEFAULT_ACCEL_STD.items()},
            "ci": (f"mean over tracks of the seed-averaged per-track RMSE; 95 % expanded percentile bootstrap interval over "
                   f"tracks ({BOOTSTRAP_RESAMPLES} resamples, seed {BOOTSTRAP_SEED}); none with fewer than {MIN_TRACKS_CI} tracks"),
            "seconds": round(time.perf_counter() - t0, 2),
        }
        write_atomic(stage / "meta.json", json.dumps(meta, indent=2) + "\n")
        if not a.no_figure:
            evaluation_figure(rows, stage / "evaluation.png", "tuned" if a.tune else "default")
    bar.close()
    if a.quiet:
        print(out)
        return 0
    print(markdown_table(rows) if a.markdown else format_table(rows))
    if motion_table(rows):  # the 3-D datasets' motion errors
        print("\n" + motion_table(rows))
    print(f"95 % intervals: expanded percentile bootstrap over tracks ({BOOTSTRAP_RESAMPLES} resamples, fixed seed); "
          f"n/a with fewer than {MIN_TRACKS_CI} tracks", file=sys.stderr)
    for d in datasets:
        print(f"{d.name}: {d.n_tracks} tracks used, {d.skipped} shorter than {a.min_length} skipped ({d.description})", file=sys.stderr)
    for line in fits:
        print(f"learned {line}", file=sys.stderr)
    if a.tune and a.tune_method == "grid":
        for r in rows:
            if r["noise"] == "tuned":
                print(f"tuned {r['dataset']} {r['filter']}: k = {r['scale']:.3g}, ρ = {r['turn_ratio']:.3g} -> accel_std {r['accel_std']}", file=sys.stderr)
    print(f"wrote {out}/summary.csv, per_track.csv{', tuning.csv' if tuning else ''}{', learned.csv' if learned else ''}"
          f"{', imm_sets.csv' if imm_sets else ''}, meta.json"
          f"{'' if a.no_figure else ', evaluation.png'} ({meta['seconds']:.1f} s)", file=sys.stderr)
    return 0
