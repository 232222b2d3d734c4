"""A serial batch kernel run on parts of its batch in threads (the kernel compiled ``nogil=True``).

numba's ``parallel=True`` loop costs seconds of compiling per kernel (the IMM's loop: 11.6 s against 2.8 s serial,
``docs/performance.md``); a serial kernel without the GIL on a few Python threads uses the same cores. Each item of
the batch is computed by the same code whatever the split, so the results are the same bit for bit.
"""

from __future__ import annotations

from concurrent.futures import ThreadPoolExecutor

import numpy as np

from ..io.cpus import usable_cpus

__all__ = ["run_on_threads", "ITEMS_PER_THREAD"]

#: batch items per thread below which the kernel runs in the calling thread only (a thread's start costs ~0.1 ms)
ITEMS_PER_THREAD = 8


def run_on_threads(kernel, args: tuple, batched, n: int, threads: int | None = None) -> None:
    """``kernel(*args)`` with the arguments at positions ``batched`` split along their first axis (n items) into
    contiguous parts, one call per part, in up to ``threads`` threads (default ``usable_cpus()``).

    Parameters
    ----------
    kernel : callable
        A numba kernel compiled ``nogil=True`` that loops over the first axis of its ``batched`` arguments, each item
        independent of the others, and writes its results into (batched) output arrays.
    args : tuple
        All its arguments.
    batched : iterable of int
        The positions in ``args`` of the arrays with the batch axis first (inputs and outputs).
    n : int
        The batch size.
    threads : int, optional
        Most threads (the calling one included); default the usable CPUs, at most ``NUMBA_NUM_THREADS`` (so that a
        limit set for numba's parallel loops holds here too).
    """
    batched = set(batched)
    if threads is None:
        import numba

        threads = min(usable_cpus(), numba.config.NUMBA_NUM_THREADS)
    parts = max(1, min(threads, n // ITEMS_PER_THREAD))
    if parts == 1:
        kernel(*args)
        return
    cuts = np.linspace(0, n, parts + 1).astype(int)

    def part(a, b):
        return tuple(v[a:b] if i in batched else v for i, v in enumerate(args))

    with ThreadPoolExecutor(parts - 1, thread_name_prefix="lgekf-batch") as pool:
        futures = [pool.submit(kernel, *part(a, b)) for a, b in zip(cuts[1:-1], cuts[2:])]
        kernel(*part(0, cuts[1]))
        for f in futures:
            f.result()
