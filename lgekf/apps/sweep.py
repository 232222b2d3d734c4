"""Run a protocol grid (``lgekf.experiments.grid``) as tasks, one per cell, into a resumable results folder.

``run_sweep(grid, out, client)`` submits every cell that is not yet in ``out`` to a ``distributed.Client``
(``client=None`` runs them here, one after the other), and as cells finish it rewrites the table
(``lgekf.apps.sweep_table``) every ``flush_seconds`` and at the end, so an interrupted sweep keeps its
finished cells and a second run computes only the rest. The rows are always in the grid's order (cells
as expanded, σ_ω, then the filters and ``measurements``), never in the order the workers finished: with
the cell seeds of ``lgekf.experiments.grid`` the table is the same, byte for byte, whatever the number of
workers, the batches or the interruptions.

Before the first cell, the kernels the cells need are compiled (a cold cache) or loaded (a warm one) in child
processes (``lgekf.apps.sweep_warmup``), so that every cell runs kernels loaded from numba's cache: a cold and a warm
run write the same table, byte for byte (numba's freshly compiled SIMD kernels can differ from their cached copy in
the last bits; that module says why).

``out/meta.json`` holds the grid, the columns, the versions and one entry per run (workers, cells
computed and skipped, wall time, summed task time) and, with the ``imm`` filter, its options (the study's
default: the chain learned on 100 training trajectories per σ_ω; a grid cannot change them); a folder holding
another grid's results, or imm results of other (or unrecorded) options, is refused before any work.
"""

from __future__ import annotations

import json
import platform
import time
from dataclasses import dataclass, field
from datetime import datetime, timezone
from pathlib import Path

import numpy as np

from ..experiments.grid import SIGMA_COLUMN, Grid, config_from_options, value_text
from ..experiments.imm_study import IMM_FILTER, ImmStudyOptions, imm_options_record
from ..experiments.study import run_study
from ..io.output import write_atomic
from .sweep_table import TableError, read_table, table_columns, table_name, write_table
from .sweep_warmup import warm_cache, warmup_configs

__all__ = ["compute_cell", "run_sweep", "SweepReport", "CellFailed", "check_folder", "figure_paths", "FLUSH_SECONDS"]

FLUSH_SECONDS = 10.0
META = "meta.json"


class CellFailed(RuntimeError):
    """A cell's task raised; the finished cells are saved, a rerun resumes after them."""


def compute_cell(options: dict, seed: int):
    """Run one cell's study: the task each worker executes.

    Parameters
    ----------
    options : dict
        The cell's canonical options (``Cell.options``).
    seed : int
        The cell's derived seed.

    Returns
    -------
    rows : list of tuple
        ``(sigma_w, filter, mean_rmse, std_rmse, n, wrapped, aliased)`` per σ_ω and filter (then
        ``measurements``), in that order.
    seconds : float
        The compute time of the task (wall clock on the worker).
    """
    t0 = time.perf_counter()
    res = run_study(config_from_options(options, seed))
    rows = []
    for i, s in enumerate(res.sigmas):
        for name in (*res.filters, "measurements"):
            r = res.rmse[name][i]
            aliased = int(res.aliased[name][i]) if name in res.aliased else 0
            rows.append((float(s), name, float(r.mean()), float(r.std(ddof=1)), int(r.size), int(res.wrapped[i]), aliased))
    return rows, time.perf_counter() - t0


def _cell_rows(grid: Grid, cell, result_rows) -> list:
    """Table rows of a finished cell: key, seed, axis values, then the result columns."""
    axes = [a for a in grid.axes if a != "sigmas"]
    head = [cell.key, cell.seed] + [cell.axes[a] if isinstance(cell.axes[a], (int, float, str)) and not isinstance(cell.axes[a], bool)
                                    else value_text(a, cell.axes[a]) for a in axes]
    return [tuple(head + [r[0], *r[1:]]) for r in result_rows]


@dataclass
class SweepReport:
    """What a run did: cells in the grid, computed now, found in the folder; times in seconds (``wall_seconds`` from the
    first cell on; the warm-up before it, compiling or loading the kernels, is ``warmup_seconds``)."""

    cells: int
    computed: int
    skipped: int
    wall_seconds: float
    task_seconds: float
    workers: int
    table: Path
    figures: list = field(default_factory=list)
    warmup_seconds: float = 0.0
    warmup_compiled: bool = False

    @property
    def overhead_per_task(self) -> float:
        """(workers × wall − Σ task time) / tasks: the time per task a worker spent not computing (s)."""
        if not self.computed:
            return float("nan")
        return (self.workers * self.wall_seconds - self.task_seconds) / self.computed


def _versions() -> dict:
    import numba

    from .. import __version__

    return {"lgekf": __version__, "numpy": np.__version__, "numba": numba.__version__, "python": platform.python_version()}


def check_folder(grid: Grid, out: Path, fmt: str) -> dict:
    """The existing meta.json of ``out`` (or a new one) after checking that it holds this grid's sweep.

    Raises
    ------
    TableError
        ``out`` is a file, holds another command's meta.json, another grid's fixed options or axes, or
        results in the other format.
    """
    out = Path(out)
    if out.exists() and not out.is_dir():
        raise TableError(f"{out}: exists and is not a folder")
    columns = [c for c, _ in table_columns(grid.axis_columns())]
    fresh = {"command": "lgekf sweep", "format": fmt, "columns": columns, "filters": grid.filters,
             "grid": grid.describe(), "runs": []}
    if IMM_FILTER in grid.filters:  # the study's default IMM (compute_cell): its chain, learned or fixed
        fresh["imm"] = imm_options_record(ImmStudyOptions())
    meta_path = out / META
    other = out / table_name("parquet" if fmt == "csv" else "csv")
    if not meta_path.exists():
        if (out / table_name(fmt)).exists() or other.exists():
            raise TableError(f"{out}: has a results table but no {META}; give another output folder")
        return fresh
    try:
        meta = json.loads(meta_path.read_text(encoding="utf-8"))
    except (OSError, ValueError) as e:
        raise TableError(f"{meta_path}: cannot read ({e})") from None
    if not isinstance(meta, dict) or meta.get("command") != "lgekf sweep":
        raise TableError(f"{out}: holds the output of another command ({META} is not a sweep's); give another output folder")
    if meta.get("format") != fmt:
        raise TableError(f"{out}: holds a sweep in {meta.get('format')} format; run with --format {meta.get('format')} to resume it")

    def same(a, b):
        return json.dumps(a, sort_keys=True) == json.dumps(b, sort_keys=True)

    if not same(meta.get("grid", {}).get("fixed"), fresh["grid"]["fixed"]) or not same(meta.get("filters"), fresh["filters"]):
        raise TableError(f"{out}: holds a sweep with other [fixed] options or filters; give another output folder "
                         "(only the values of the axes may change between runs)")
    if not same(meta.get("imm"), fresh.get("imm")):
        raise TableError(f"{out}: holds a sweep whose imm filter ran with other options ({meta.get('imm', 'not recorded')}; "
                         f"now {fresh.get('imm')}); give another output folder")
    if meta.get("columns") != columns:
        raise TableError(f"{out}: holds a sweep over other axes ({', '.join(meta.get('columns', []))}); give another output folder")
    meta["grid"] = fresh["grid"]  # the axes' values may have grown
    return meta


def figure_paths(grid: Grid, out: Path, rows) -> dict:
    """{axis column: sweep_<axis>.png} for every axis with more than one value in the table (σ_ω too)."""
    names = [c for c, _ in table_columns(grid.axis_columns())]
    cols = [c for c in names[2:names.index(SIGMA_COLUMN) + 1]]
    i = {c: names.index(c) for c in cols}
    return {c: Path(out) / f"sweep_{c}.png" for c in cols if len({r[i[c]] for r in rows}) > 1}


def _results_here(tasks):
    for cell in tasks:
        yield cell, compute_cell(cell.options, cell.seed)


def _results_dask(client, tasks):
    from distributed import as_completed

    futures = {client.submit(compute_cell, c.options, c.seed, key=f"lgekf-sweep-{c.key}", pure=False): c for c in tasks}
    try:
        for fut in as_completed(futures):
            cell = futures[fut]
            try:
                res = fut.result()
            except Exception as e:  # noqa: BLE001 - reported with the cell, the finished cells are kept
                raise CellFailed(f"cell {cell.index} ({cell.key}) failed on a worker: {type(e).__name__}: {e}") from e
            yield cell, res
            fut.release()
    finally:
        client.cancel(list(futures))


def run_sweep(grid: Grid, out, client=None, fmt: str = "csv", progress=None, flush_seconds: float = FLUSH_SECONDS,
              figures: bool = True, where: str | None = None, warm_up: bool = True, warm_processes: int = 1,
              on_compile=None) -> SweepReport:
    """Compute the cells of ``grid`` missing from ``out`` and write the table, meta.json and the figures.

    Parameters
    ----------
    grid : Grid
        The protocol grid.
    out : str or Path
        The results folder (created if needed).
    client : distributed.Client, optional
        Where the tasks run; None computes them in this process.
    fmt : str
        ``"csv"`` or ``"parquet"``.
    progress : callable, optional
        ``progress(n)`` after every finished cell (a tqdm bar's ``update``).
    flush_seconds : float
        The table is rewritten when this much time has passed since the last write (and at the end).
    figures : bool
        Write ``sweep_<axis>.png`` for every axis with more than one value.
    where : str, optional
        Where the tasks ran, for meta.json (``local cluster``, the scheduler's address).
    warm_up : bool
        First compile (or load) the cells' kernels in child processes, so that every cell runs kernels loaded from the
        cache (``lgekf.apps.sweep_warmup``): cold and warm runs then write the same bytes. False skips it.
    warm_processes : int
        Child processes compiling at once.
    on_compile : callable, optional
        Called once, with no argument, when the warm-up starts compiling (a cold cache): the CLI's compile notice.

    Returns
    -------
    SweepReport
    """
    out = Path(out)
    cells = grid.cells()
    meta = check_folder(grid, out, fmt)
    columns = table_columns(grid.axis_columns())
    path = out / table_name(fmt)
    existing = read_table(path, columns, fmt)
    table: dict = {}
    for r in existing:
        table.setdefault(r[0], []).append(r)
    pending = [c for c in cells if c.key not in table]
    order = {c.key: c.index for c in cells}

    def rows_in_order():
        keys = sorted(table, key=lambda k: (0, order[k]) if k in order else (1, 0))  # stable: old cells keep their order
        return [r for k in keys for r in table[k]]

    out.mkdir(parents=True, exist_ok=True)
    workers = 1 if client is None else max(1, _workers(client))
    run = {"started": datetime.now(timezone.utc).isoformat(timespec="seconds"), "workers": workers,
           "where": where or ("this process" if client is None else "dask"),
           "cells": len(cells), "skipped": len(cells) - len(pending), "computed": 0, "wall_seconds": None,
           "task_seconds": None, "versions": _versions()}
    meta["runs"].append(run)
    write_atomic(out / META, json.dumps(meta, indent=2) + "\n")
    warm_seconds, warm_compiled = 0.0, False
    if warm_up and pending:
        w0 = time.perf_counter()
        warm_compiled = warm_cache(warmup_configs([c.config() for c in pending]), warm_processes, on_compile) > 0
        warm_seconds = time.perf_counter() - w0
        run.update(warmup_compiled=warm_compiled, warmup_seconds=round(warm_seconds, 4))
    t0 = time.perf_counter()
    task_seconds, done, last = 0.0, 0, time.perf_counter()
    dirty = False
    try:
        results = _results_here(pending) if client is None else _results_dask(client, pending)
        for cell, (rows, seconds) in results:
            table[cell.key] = _cell_rows(grid, cell, rows)
            task_seconds += seconds
            done += 1
            dirty = True
            if progress is not None:
                progress(1)
            if time.perf_counter() - last >= flush_seconds:
                write_table(path, columns, rows_in_order(), fmt)
                dirty, last = False, time.perf_counter()
    finally:
        if dirty or not path.exists():
            write_table(path, columns, rows_in_order(), fmt)
        wall = time.perf_counter() - t0
        run.update(computed=done, wall_seconds=round(wall, 4), task_seconds=round(task_seconds, 4))
        write_atomic(out / META, json.dumps(meta, indent=2) + "\n")
    all_rows = rows_in_order()
    written = []
    if figures:
        from ..experiments.sweep_figures import axis_figure

        names = [c for c, _ in columns]
        dicts = [dict(zip(names, r)) for r in all_rows]
        for axis, fig_path in figure_paths(grid, out, all_rows).items():
            written.append(axis_figure(dicts, axis, grid.filters, fig_path, n_cells=len(table)))
    return SweepReport(len(cells), done, len(cells) - len(pending), wall, task_seconds, workers, path, written, warm_seconds,
                       warm_compiled)


def _workers(client) -> int:
    from .cluster import worker_count

    return worker_count(client)
