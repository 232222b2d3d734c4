"""`lgekf track --workers N | --scheduler ADDRESS`: the same output as in one process, computed in partitions
that hold whole objects (``lgekf.apps.track_dask``), written all or nothing."""

from __future__ import annotations

import sys
import time

import numpy as np

from ..apps.cluster import dask_client, require_dask, worker_count
from ..apps.track import output_columns
from ..apps.track_dask import open_source, plan_partitions, track_partitions
from ..core.registry import get_measurement
from ..io.files import AtomicFiles, is_stdio
from ..io.readers import parse_delimiter
from ..io.units import unit_warnings
from .cluster import cluster_label
from .progress import progress_bar, stderr_is_terminal
from .track_pipeline import projection_line

__all__ = ["cmd_track_dask"]


def cmd_track_dask(a, models, cfg, outs, measure, say, monitor=None) -> int:
    """Run ``lgekf track`` on Dask (arguments already checked by ``cmd_track``)."""
    require_dask("lgekf track --workers/--scheduler")
    if a.format != "csv":
        raise ValueError("--format pedestrian: not with --workers or --scheduler; convert the file to CSV (t,x,y,id)")
    if a.partition_rows < 2:
        raise ValueError(f"--partition-rows: must be at least 2, got {a.partition_rows}")
    t0 = time.perf_counter()
    use_heading = a.use_heading or get_measurement(a.measure).has_angle
    src = open_source(a.input, use_heading, parse_delimiter(a.delimiter))
    with dask_client(workers=a.workers, scheduler=a.scheduler, what="lgekf track --workers/--scheduler") as client:
        where = cluster_label(a, worker_count(client))
        plan = plan_partitions(client, src, a.partition_rows)
        results = track_partitions(client, src, plan, models, measure, cfg, a.full_cov, a.precision, a.time_unit, use_heading,
                                   monitor)
        samples, scale_error = [], 0.0
        show_bar = not a.quiet and stderr_is_terminal()
        with AtomicFiles(outs) as files, progress_bar(plan.rows * len(models), "lgekf track", show_bar, unit="rows") as bar:
            if any(is_stdio(o) for o in outs):
                results = list(results)  # stdout cannot be taken back: every partition first, then the output
            handles = [files.open(i) for i in range(len(models))]
            for fh, m in zip(handles, models):
                fh.write((",".join(output_columns(m, a.full_cov, src.projected)) + "\n").encode())
            for res in results:
                for fh, b in zip(handles, res.data):
                    fh.write(b)
                samples.append(res.sample)
                scale_error = max(scale_error, res.scale_error)
                bar.update(res.rows * len(models))
            files.commit()
    if src.projected:
        say(projection_line(plan.origin, scale_error))
    t, z, starts = _joined(samples)
    for w in unit_warnings(t, z, starts, a.time_unit, projected=src.projected, fmt="csv"):
        print(f"lgekf track: warning: {w} (from a sample of {t.size} rows)", file=sys.stderr)
    if not a.quiet:
        report = sys.stderr if is_stdio(a.output) else sys.stdout
        n = len(plan.labels)
        for m, o in zip(models, outs):
            name = "<stdout>" if is_stdio(o) else o
            print(f"{name}: {plan.rows} rows, {n} object{'s' if n != 1 else ''} ({m})", file=report)
        print(f"{plan.n_partitions} partition{'s' if plan.n_partitions != 1 else ''} of whole objects, total "
              f"{time.perf_counter() - t0:.2f} s on {where}", file=sys.stderr)
    return 0


def _joined(samples):
    """One (t, z, starts) of the partitions' samples (objects stay whole)."""
    ts, zs, st, off = [], [], [np.zeros(1, dtype=np.int64)], 0
    for t, z, s in samples:
        ts.append(t)
        zs.append(z)
        st.append(np.asarray(s[1:], dtype=np.int64) + off)
        off += t.size
    return np.concatenate(ts), np.concatenate(zs), np.concatenate(st)
