"""Scaling of `lgekf sweep` from 1 to 2 local Dask workers, and the per-task overhead.

    .venv/bin/python benchmarks/bench_sweep.py [--repeats 3]

Two grids, each run in this process (no Dask) and on local clusters of 1 and 2 workers (one thread each,
127.0.0.1 only), every run into a fresh folder, table written once at the end:

* "study cells": 48 cells (σ_ω 8 values × T 3 × CV noise scale 2), 400 trajectories × 100 steps, the five
  filters: about 50 ms of compute per cell;
* "tiny cells": 200 cells of 2 trajectories × 5 steps (about 1 ms each): nearly all overhead.

Reported per run: wall time of ``run_sweep`` (the cluster already started and every worker warmed up:
numba kernels loaded), the summed task time Σ measured inside the tasks, the speed-up over 1 worker,
and the overhead per task = (workers × wall − Σ) / tasks (the worker time per task not spent computing:
scheduling, serialisation, result transfer, the driver's bookkeeping), and the CPU time the workers used
(when it is well below Σ, the workers were waiting for a core: the machine is busy). Start-up (cluster +
warm-up) is reported separately. As a ceiling for the speed-up, the same cells also run on a plain
process pool of 1 and 2 processes (``concurrent.futures``, no Dask). The tables of all runs must be identical (checked). This process runs numba on one
thread too (``NUMBA_NUM_THREADS=1`` before numba is imported), so "in process" is one core.
"""

from __future__ import annotations

import os

os.environ.setdefault("NUMBA_NUM_THREADS", "1")

import argparse  # noqa: E402
import datetime  # noqa: E402
import shutil  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

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


def _pool_run(cells, workers):
    """The same cells on a plain process pool (no Dask): the machine's own ceiling for the speed-up."""
    import multiprocessing as mp
    from concurrent.futures import ProcessPoolExecutor

    with ProcessPoolExecutor(workers, mp_context=mp.get_context("spawn")) as pool:
        list(pool.map(_warm_one, range(workers)))
        t0 = time.perf_counter()
        list(pool.map(compute_cell, [c.options for c in cells], [c.seed for c in cells], chunksize=1))
        return time.perf_counter() - t0


def _warm_one(_):
    time.sleep(0.2)  # every pool process gets one
    return _warm()


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--repeats", type=int, default=3, help="runs per setting; the fastest is reported (default 3)")
    a = ap.parse_args()
    load0 = os.getloadavg()
    print(f"{datetime.date.today()}, {os.cpu_count()} cores, load average before: {load0[0]:.2f} {load0[1]:.2f} {load0[2]:.2f}")
    _warm()
    tmp = Path(tempfile.mkdtemp(prefix="bench_sweep."))
    tables = {}
    results = {}
    try:
        for label, spec in GRIDS.items():
            grid = parse_grid(spec, label)
            n = grid.n_cells
            for workers in (0, 1, 2):
                best = None
                if workers:
                    t0 = time.perf_counter()
                    ctx = dask_client(workers=workers)
                    client = ctx.__enter__()
                    t_start = time.perf_counter() - t0
                    t0 = time.perf_counter()
                    client.run(_warm)
                    t_warm = time.perf_counter() - t0
                else:
                    ctx = client = None
                    t_start = t_warm = 0.0
                try:
                    for r in range(a.repeats):
                        out = tmp / f"{label}-{workers}-{r}"
                        cpu0 = client.run(_cpu_seconds) if client else None
                        rep = run_sweep(grid, out, client, flush_seconds=float("inf"), figures=False)
                        if client:
                            cpu1 = client.run(_cpu_seconds)
                            rep.worker_cpu = sum(cpu1[w] - cpu0[w] for w in cpu1)
                        tables.setdefault(label, (out / "cells.csv").read_bytes())
                        assert (out / "cells.csv").read_bytes() == tables[label], "tables differ between runs"
                        shutil.rmtree(out)
                        if best is None or rep.wall_seconds < best.wall_seconds:
                            best = rep
                finally:
                    if ctx is not None:
                        ctx.__exit__(None, None, None)
                results[(label, workers)] = (best, t_start, t_warm)
                print(f"{label:12} {'in process' if not workers else f'{workers} worker' + ('s' if workers > 1 else ''):11} "
                      f"cells {n:4d}  wall {best.wall_seconds:7.3f} s  Σ tasks {best.task_seconds:7.3f} s  "
                      f"per cell {best.task_seconds / n * 1e3:7.2f} ms  "
                      + (f"overhead/task {best.overhead_per_task * 1e3:6.2f} ms  worker CPU {best.worker_cpu:6.3f} s  "
                         f"start {t_start:5.2f} s  warm-up {t_warm:5.2f} s" if workers else ""), flush=True)
            pool = {k: min(_pool_run(grid.cells(), k) for _ in range(a.repeats)) for k in (1, 2)}
            results[(label, "pool")] = pool
            print(f"{label:12} plain process pool (no Dask): 1 process {pool[1]:.3f} s, 2 processes {pool[2]:.3f} s, "
                  f"speed-up {pool[1] / pool[2]:.2f}x", flush=True)
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    print()
    print("| grid | cells | in process | 1 worker | 2 workers | speed-up 1 -> 2 | plain pool speed-up 1 -> 2 | "
          "overhead per task, 1 / 2 workers |")
    print("|---|---|---|---|---|---|---|---|")
    for label in GRIDS:
        p, w1, w2 = (results[(label, k)][0] for k in (0, 1, 2))
        pool = results[(label, "pool")]
        print(f"| {label} | {p.cells} | {p.wall_seconds:.2f} s | {w1.wall_seconds:.2f} s | {w2.wall_seconds:.2f} s | "
              f"{w1.wall_seconds / w2.wall_seconds:.2f}x | {pool[1] / pool[2]:.2f}x | "
              f"{w1.overhead_per_task * 1e3:.1f} / {w2.overhead_per_task * 1e3:.1f} ms |")
    start = [results[(label, k)][1] for label in GRIDS for k in (1, 2)]
    warm = [results[(label, k)][2] for label in GRIDS for k in (1, 2)]
    print(f"cluster start {min(start):.2f}-{max(start):.2f} s, worker warm-up (numba kernels from the cache) {min(warm):.2f}-{max(warm):.2f} s")
    load1 = os.getloadavg()
    print(f"load average after: {load1[0]:.2f} {load1[1]:.2f} {load1[2]:.2f}")


if __name__ == "__main__":
    main()
