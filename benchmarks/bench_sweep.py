"""Scaling of `lgekf sweep` from 1 to 2 local Dask workers, and the per-task overhead.

    .venv/bin/python benchmarks/bench_sweep.py [--repeats 5]

Two grids, each run in this process (no Dask) and on local clusters of 1 and 2 workers (one thread each,
127.0.0.1 only), every run into a fresh folder, table written once at the end:

* "study cells": 48 cells (σ_ω 8 values × T 3 × CV noise scale 2), 400 trajectories × 100 steps, the five
  filters: about 50 ms of compute per cell;
* "tiny cells": 200 cells of 2 trajectories × 5 steps (about 1 ms each): nearly all overhead.

The settings run interleaved, round after round (``--repeats``), so that a burst of load from other jobs
on the machine hits all of them alike; best and median over the rounds are reported. Per run: the wall
time of ``run_sweep`` (the clusters already started and every worker warmed up: numba kernels loaded), the
summed task time Σ measured inside the tasks, the speed-up over 1 worker,
and the overhead per task = (workers × wall − Σ) / tasks (the worker time per task not spent computing:
scheduling, serialisation, result transfer, the driver's bookkeeping), and the CPU time the workers used
relative to Σ (well below 1: the workers were waiting for a core, the machine was busy). Start-up (cluster +
warm-up) is reported separately. As a ceiling for the speed-up, the same cells also run on a plain
process pool of 1 and 2 processes (``concurrent.futures``, no Dask). The tables of all runs must be
identical (checked). This process runs numba on one thread too (``NUMBA_NUM_THREADS=1`` before numba is imported), so "in process" is one core.
"""

from __future__ import annotations

import os

os.environ.setdefault("NUMBA_NUM_THREADS", "1")

import argparse  # noqa: E402
import datetime  # noqa: E402
import logging  # noqa: E402
import shutil  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

from lgekf.apps.cluster import dask_client  # noqa: E402
from lgekf.apps.sweep import compute_cell, run_sweep  # noqa: E402
from lgekf.experiments.grid import parse_grid  # noqa: E402

GRIDS = {
    "study cells": {"grid": {"sigmas": "0:3:8", "dt": [0.05, 0.1, 0.2], "noise_scale": [{}, {"cv": 30}]},
                    "fixed": {"trajectories": 400, "steps": 100}},
    "tiny cells": {"grid": {"sigmas": "0:3:200"}, "fixed": {"trajectories": 2, "steps": 5}},
}


def _warm():
    g = parse_grid({"fixed": {"trajectories": 2, "steps": 3, "sigmas": 0.5}})
    c = g.cells()[0]
    compute_cell(c.options, c.seed)
    return os.getpid()


def _cpu_seconds():
    import psutil  # a dependency of distributed

    t = psutil.Process().cpu_times()
    return t.user + t.system


class _Pool:
    """A plain process pool (no Dask), warmed up: the machine's own ceiling for the speed-up."""

    def __init__(self, workers):
        import multiprocessing as mp
        from concurrent.futures import ProcessPoolExecutor

        self.pool = ProcessPoolExecutor(workers, mp_context=mp.get_context("spawn"))
        list(self.pool.map(_warm_one, range(workers)))

    def run(self, cells):
        t0 = time.perf_counter()
        list(self.pool.map(compute_cell, [c.options for c in cells], [c.seed for c in cells], chunksize=1))
        return time.perf_counter() - t0

    def close(self):
        self.pool.shutdown()


def _warm_one(_):
    time.sleep(0.2)  # every pool process gets one
    return _warm()


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeats", type=int, default=5, help="rounds; every setting runs once per round (default 5)")
    a = ap.parse_args()
    load0 = os.getloadavg()
    print(f"{datetime.date.today()}, {os.cpu_count()} cores, load average before: {load0[0]:.2f} {load0[1]:.2f} {load0[2]:.2f}")
    _warm()
    logging.getLogger("distributed").setLevel(logging.ERROR)  # two clusters: closing one resets the other's silencing
    tmp = Path(tempfile.mkdtemp(prefix="bench_sweep."))
    clients, contexts, start, warm = {0: None}, [], {}, {}
    pools = {}
    try:
        for workers in (1, 2):
            t0 = time.perf_counter()
            ctx = dask_client(workers=workers)
            clients[workers] = ctx.__enter__()
            contexts.append(ctx)
            start[workers] = time.perf_counter() - t0
            t0 = time.perf_counter()
            clients[workers].run(_warm)
            warm[workers] = time.perf_counter() - t0
            pools[workers] = _Pool(workers)
        runs = {}  # (grid, setting) -> list of (wall, Σ tasks, worker CPU)
        tables = {}
        for r in range(a.repeats):  # interleaved: a burst of load elsewhere hits every setting alike
            for label, spec in GRIDS.items():
                grid = parse_grid(spec, label)
                for workers, client in clients.items():
                    out = tmp / f"{label}-{workers}-{r}"
                    cpu0 = client.run(_cpu_seconds) if client else None
                    rep = run_sweep(grid, out, client, flush_seconds=float("inf"), figures=False)
                    cpu = sum(v - cpu0[w] for w, v in client.run(_cpu_seconds).items()) if client else rep.task_seconds
                    tables.setdefault(label, (out / "cells.csv").read_bytes())
                    assert (out / "cells.csv").read_bytes() == tables[label], "tables differ between runs"
                    shutil.rmtree(out)
                    runs.setdefault((label, workers), []).append((rep.wall_seconds, rep.task_seconds, cpu))
                for workers, pool in pools.items():
                    runs.setdefault((label, f"pool{workers}"), []).append((pool.run(grid.cells()), float("nan"), float("nan")))
            print(f"round {r + 1}/{a.repeats} done, load {os.getloadavg()[0]:.2f}", flush=True)
    finally:
        for ctx in contexts:
            ctx.__exit__(None, None, None)
        for pool in pools.values():
            pool.close()
        shutil.rmtree(tmp, ignore_errors=True)
    print()
    for label, spec in GRIDS.items():
        n = parse_grid(spec, label).n_cells
        for workers in (0, 1, 2):
            rs = runs[(label, workers)]
            wall = [x[0] for x in rs]
            best = min(rs)
            name = "in process" if not workers else f"{workers} worker" + ("s" if workers > 1 else "")
            over = f"overhead/task {(max(workers, 1) * best[0] - best[1]) / n * 1e3:6.2f} ms  " if workers else ""
            print(f"{label:12} {name:11} cells {n:4d}  wall best {best[0]:6.3f} s median {np.median(wall):6.3f} s  "
                  f"Σ tasks {best[1]:6.3f} s ({best[1] / n * 1e3:6.2f} ms per cell)  {over}worker CPU / Σ tasks {best[2] / best[1]:4.2f}")
        for workers in (1, 2):
            wall = [x[0] for x in runs[(label, f"pool{workers}")]]
            print(f"{label:12} pool of {workers}   wall best {min(wall):6.3f} s median {np.median(wall):6.3f} s (plain processes, no Dask)")
    print()
    print("| grid | cells | in process | 1 worker | 2 workers | speed-up 1 -> 2 workers (best / median) | plain pool speed-up | "
          "overhead per task, 1 / 2 workers |")
    print("|---|---|---|---|---|---|---|---|")
    for label, spec in GRIDS.items():
        n = parse_grid(spec, label).n_cells
        b = {k: min(runs[(label, k)]) for k in (0, 1, 2, "pool1", "pool2")}
        med = {k: float(np.median([x[0] for x in runs[(label, k)]])) for k in (1, 2)}
        o1, o2 = ((k * b[k][0] - b[k][1]) / n * 1e3 for k in (1, 2))
        print(f"| {label} | {n} | {b[0][0]:.2f} s | {b[1][0]:.2f} s | {b[2][0]:.2f} s | {b[1][0] / b[2][0]:.2f}x / "
              f"{med[1] / med[2]:.2f}x | {b['pool1'][0] / b['pool2'][0]:.2f}x | {o1:.1f} / {o2:.1f} ms |")
    print(f"cluster start: 1 worker {start[1]:.2f} s, 2 workers {start[2]:.2f} s; worker warm-up (numba kernels from the cache) "
          f"{warm[1]:.2f} / {warm[2]:.2f} s")
    load1 = os.getloadavg()
    print(f"load average after: {load1[0]:.2f} {load1[1]:.2f} {load1[2]:.2f}")


if __name__ == "__main__":
    main()
