"""``lgekf evaluate`` on Dask: the filter runs of every dataset in partitions of whole tracks.

The datasets are read, and the measurement noise is drawn, in this process exactly as without Dask
(one noise stream over all the tracks of a dataset, ``lgekf.apps.evaluate``); what moves to the workers
is the work that grows with the data and the tuning grid: every filter on every seed and track
(``track_rmse``). Each partition holds whole tracks (contiguous ranges, about equal in rows), and a
track's RMSE depends on that track alone, so the per-track results, the tables and the intervals are the
single-process ones, bit for bit. A dataset's partitions are sent to the cluster once and reused by
every run of the tuning grid.
"""

from __future__ import annotations

import math

import numpy as np

from .evaluate import track_rmse

__all__ = ["DaskRunner", "track_ranges"]


def track_ranges(starts: np.ndarray, parts: int) -> list:
    """Contiguous ranges of whole tracks [(j0, j1)], about equal in rows, at most ``parts`` of them.

    Parameters
    ----------
    starts : ndarray (J + 1,)
        Row offsets of the tracks.
    parts : int
        The number of ranges wanted.
    """
    J = len(starts) - 1
    parts = max(1, min(parts, J))
    total = int(starts[-1])
    cuts = [0]
    for k in range(1, parts):
        j = int(np.searchsorted(starts, k * total / parts, side="left"))
        if cuts[-1] < j < J:
            cuts.append(j)
    return list(zip(cuts, cuts[1:] + [J]))


class DaskRunner:
    """A ``runner`` for ``lgekf.apps.evaluate.run_filters``: ``track_rmse`` over partitions on a Dask cluster.

    Parameters
    ----------
    client : distributed.Client
        The cluster.
    partition_rows : int, optional
        Rows per partition; default: the rows split into ``2 × workers`` partitions.
    workers : int
        The number of workers (for the default).
    """

    def __init__(self, client, partition_rows: int | None = None, workers: int = 1):
        self.client = client
        self.partition_rows = partition_rows
        self.workers = max(1, workers)
        self._scattered = {}  # id(dataset) -> (dataset, ranges, futures of the partition datasets)
        self.tasks = 0

    def _partitions(self, ds):
        hit = self._scattered.get(id(ds))
        if hit is not None and hit[0] is ds:
            return hit[1], hit[2]
        rows = int(ds.starts[-1])
        parts = math.ceil(rows / self.partition_rows) if self.partition_rows else 2 * self.workers
        ranges = track_ranges(ds.starts, parts)
        futures = self.client.scatter([ds.subset(np.arange(a, b)) for a, b in ranges])
        self._scattered[id(ds)] = (ds, ranges, futures)  # the dataset is kept: its id is not reused meanwhile
        return ranges, futures

    def __call__(self, ds, zs, cfg, models):
        """``track_rmse(ds, zs, cfg, models)``, computed per partition and joined in track order."""
        ranges, parts = self._partitions(ds)
        futures = []
        for (a, b), part in zip(ranges, parts):
            r0, r1 = int(ds.starts[a]), int(ds.starts[b])
            futures.append(self.client.submit(track_rmse, part, [z[r0:r1] for z in zs], cfg, tuple(models), pure=False))
        self.tasks += len(futures)
        results = self.client.gather(futures)
        out = {}
        for m in models:
            pos = np.concatenate([r[m][0] for r in results], axis=1)
            vel = None if results[0][m][1] is None else np.concatenate([r[m][1] for r in results], axis=1)
            out[m] = (pos, vel)
        return out
