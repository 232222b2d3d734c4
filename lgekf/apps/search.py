"""The process-noise searches of ``lgekf track`` on every usable CPU (``lgekf.apps.noise.search_stages``).

A search is a few stages of independent candidate runs (about 22 in all per model); the candidates of a
stage — of every model at once under ``--model all`` — run in a pool of threads, one per usable CPU
(``usable_cpus``). The kernels of a run release the GIL (``nogil=True``: the generated ``recover_<meas>`` — the
filter's first pass, the divergence monitor and its re-initialisations and reruns in one call —, the two-point
start's ``two_points`` / ``initial_covariances``, ``propagate_positions``), so the threads overlap; none of them is a
numba ``parallel=True`` one (``tests/tracking/test_search.py`` replaces every parallel kernel by one that raises), so no two
threads enter numba's threading layer at once.

The result is that of the serial search, exactly: every run is deterministic, each stage's choice is made
only after all its candidates are scored, and it is the first candidate of least mse in list order
whatever the order the runs finished in. A run that raises: the error raised is the one the serial search
(model after model, candidates in list order) would meet first.
"""

from __future__ import annotations

from concurrent.futures import Future, ThreadPoolExecutor

from ..io.cpus import usable_cpus
from .noise import K_GRID, SearchResult, candidate_key, process_noise_search, run_score, search_stages

__all__ = ["usable_cpus", "process_noise_searches", "in_thread", "PARALLEL_MIN_ROWS"]

PARALLEL_MIN_ROWS = 4_000  # subsamples with fewer rows search serially: threads cost more than they gain (2 cores, quiet:
# serial / 2 threads 0.60 at 500 rows, 0.94 at 2 000, 1.21 at 5 000, 1.4 at 10 000, 1.5 at 30 000; one model)


def in_thread(fn, *args) -> Future:
    """``fn(*args)`` started in a thread of its own; its ``Future`` (``result()`` waits, and raises what fn raised)."""
    pool = ThreadPoolExecutor(max_workers=1, thread_name_prefix="lgekf-search")
    try:
        return pool.submit(fn, *args)
    finally:
        pool.shutdown(wait=False)  # the thread ends when fn returns


def _scored(run, q):
    return run_score(*run(q))


def process_noise_searches(runs: dict, v_typ: float, grid=K_GRID, workers: int | None = None) -> dict:
    """``process_noise_search`` of several models, their runs in ``workers`` threads.

    Parameters
    ----------
    runs : dict
        Model name -> ``run(q) -> (nis (N,), err2 (N,))`` (as for ``process_noise_search``); called from
        several threads at once, so it must not share mutable state between calls.
    v_typ : float
        The data's typical speed (m/s).
    grid : tuple of float
        The k grid.
    workers : int, optional
        Threads (default ``usable_cpus()``); 1: the serial search, model after model.

    Returns
    -------
    dict
        Model name -> ``SearchResult``, in the order of ``runs``; the same as the serial search's.
    """
    models = list(runs)
    workers = usable_cpus() if workers is None else int(workers)
    if workers <= 1:
        return {m: process_noise_search(runs[m], m, v_typ, grid) for m in models}
    scores = {m: {} for m in models}
    stages = {m: search_stages(m, v_typ, scores[m], grid) for m in models}
    pending = {m: next(stages[m]) for m in models}  # each model's current stage (its candidates)
    results: dict[str, SearchResult] = {}
    errors: dict[str, BaseException] = {}
    with ThreadPoolExecutor(max_workers=workers, thread_name_prefix="lgekf-search") as pool:
        try:
            while pending:
                jobs = []  # (model, key, future), in the serial order: model after model, candidates in list order
                for m in models:
                    seen = set()
                    for q in pending.get(m, ()):
                        key = candidate_key(q)
                        if key not in scores[m] and key not in seen:
                            seen.add(key)
                            jobs.append((m, key, pool.submit(_scored, runs[m], q)))
                for m, key, fut in jobs:
                    if m in errors:  # the serial search stopped at this model's earlier failure
                        fut.cancel()
                        continue
                    exc = fut.exception()
                    if exc is not None:
                        errors[m] = exc
                    else:
                        scores[m][key] = fut.result()
                for m in list(pending):
                    if m in errors:
                        del pending[m]
                        continue
                    try:
                        pending[m] = stages[m].send(None)
                    except StopIteration as stop:
                        results[m] = stop.value
                        del pending[m]
                if errors:  # the serial search meets the first failing model's error once the models before it are done
                    first = min(models.index(m) for m in errors)
                    for m in models[first + 1:]:
                        pending.pop(m, None)
                    if all(m in results for m in models[:first]):
                        raise errors[models[first]]
        finally:
            pool.shutdown(wait=True, cancel_futures=True)
    return {m: results[m] for m in models}
