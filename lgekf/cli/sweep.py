"""`lgekf sweep`: a grid of study protocols (``lgekf.experiments.grid``) run as tasks on Dask (``lgekf.apps.sweep``)."""

from __future__ import annotations

import sys
from pathlib import Path

from ..apps.cluster import dask_client, default_workers, require_dask, worker_count
from ..apps.sweep import FLUSH_SECONDS, CellFailed, check_folder, run_sweep
from ..apps.sweep_table import TABLE_FORMATS, read_table, table_columns, table_name
from ..apps.sweep_warmup import compile_seconds, warmup_configs
from ..experiments.grid import load_grid
from . import ArgumentParser
from .cluster import add_cluster_options, check_cluster_options, cluster_label
from .progress import _write_line, compile_notice_text, progress_bar, stderr_is_terminal
from .warmup import compile_estimate
from .warmup import worker_count as warm_workers

__all__ = ["cmd_sweep", "sweep_parser"]


def sweep_parser():
    ap = ArgumentParser(prog="lgekf sweep",
                        description="Run a grid of study protocols (GRID.toml: [grid] swept options, [fixed] the rest) as Dask tasks.")
    ap.add_argument("grid", help="the grid file (TOML): [grid] lists of values of any `lgekf study` option, [fixed] the others")
    ap.add_argument("-o", "--out", required=True, type=Path,
                    help="results folder: cells.csv (or .parquet), meta.json, sweep_<axis>.png; cells already there are skipped")
    add_cluster_options(ap, default_local=True)
    ap.add_argument("--format", default="csv", choices=list(TABLE_FORMATS), help="results table format (default csv)")
    ap.add_argument("--flush-seconds", type=float, default=FLUSH_SECONDS,
                    help=f"rewrite the table with the finished cells at most this often (default {FLUSH_SECONDS:g} s)")
    ap.add_argument("--no-figures", action="store_true", help="skip the sweep_<axis>.png figures")
    ap.add_argument("--dry-run", action="store_true", help="only check the grid and say how many cells there are and are to run")
    ap.add_argument("--quiet", action="store_true", help="print only the output folder")
    return ap


def cmd_sweep(argv) -> int:
    a = sweep_parser().parse_args(argv)
    check_cluster_options(a)
    if not a.flush_seconds >= 0:
        raise ValueError(f"--flush-seconds: must be a non-negative number, got {a.flush_seconds}")
    grid = load_grid(a.grid)
    cells = grid.cells()
    check_folder(grid, a.out, a.format)  # another grid's folder is refused before a cluster starts
    done = {r[0] for r in read_table(a.out / table_name(a.format), table_columns(grid.axis_columns()), a.format)}
    todo = sum(c.key not in done for c in cells)
    if a.dry_run:
        axes = ", ".join(f"{k} ({len(v)})" for k, v in grid.axes.items()) or "none"
        print(f"{a.grid}: {len(cells)} cells (axes: {axes}), {len(cells) - todo} in {a.out}, {todo} to run")
        return 0
    require_dask("lgekf sweep")
    say = (lambda text: print(f"lgekf sweep: {text}", file=sys.stderr)) if not a.quiet else (lambda text: None)
    workers = a.workers or default_workers()
    with dask_client(workers=workers, scheduler=a.scheduler, what="lgekf sweep") as client:
        n = worker_count(client)
        where = cluster_label(a, n)
        say(f"{len(cells)} cells, {todo} to run, on {where}")
        bar_on = not a.quiet and stderr_is_terminal()
        # the kernels are compiled (cold cache) or loaded in child processes before any cell: the notice when they compile
        jobs = warmup_configs([c.config() for c in cells if c.key not in done])
        procs = max(1, min(warm_workers(), len(jobs)))
        tell = (lambda text: _write_line(text, sys.stderr)) if not a.quiet else (lambda text: None)  # not through the bar
        notice = compile_notice_text(compile_estimate(compile_seconds(jobs), workers=procs))
        with progress_bar(todo, "lgekf sweep", bar_on, unit="cells") as bar:
            try:
                rep = run_sweep(grid, a.out, client, a.format, progress=bar.update, flush_seconds=a.flush_seconds,
                                figures=not a.no_figures, where=where, warm_processes=procs,
                                on_compile=lambda: tell(f"lgekf sweep: {notice}"))
            except CellFailed as e:
                print(f"lgekf sweep: error: {e} (the finished cells are in {a.out}; a rerun resumes)", file=sys.stderr)
                return 1
    if a.quiet:
        print(a.out)
        return 0
    print(f"{rep.cells} cells: {rep.computed} computed, {rep.skipped} already in {a.out}")
    if rep.computed:
        print(f"wall {rep.wall_seconds:.2f} s on {where}; task compute {rep.task_seconds:.2f} s in all, "
              f"{rep.task_seconds / rep.computed * 1e3:.1f} ms per cell; overhead {rep.overhead_per_task * 1e3:.1f} ms per task "
              "((workers x wall - task compute) / tasks)")
        if rep.warmup_compiled:
            print(f"before the cells: {rep.warmup_seconds:.1f} s compiling the kernels into numba's cache (once)")
    figs = ", ".join(p.name for p in rep.figures)
    print(f"wrote {rep.table}, {a.out / 'meta.json'}{', ' + figs if figs else ''}")
    return 0
