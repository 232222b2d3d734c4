"""A fast first run: compile a command's numba kernels in parallel processes when the cache is cold.

numba compiles one function at a time in one process (a global compiler lock), and a fresh install's
first ``lgekf study`` spends almost all of its time there (about 20 s on 2 cores, five models). Every
kernel is compiled with ``cache=True``, so a kernel compiled by *another* process is loaded from the
cache here in milliseconds. ``warm_up`` exploits that:

* the command describes its work as a few small **jobs**, each a miniature run of the real code path
  (the same kernels with the same argument types; sizes do not enter numba's signatures), e.g. the
  study with two trajectories of two steps for one or two filters;
* the jobs are split into as many groups as there are CPUs (longest first, by their estimated compile
  cost, ``model_compile_seconds``);
* group 0 runs in this process; the first time numba *compiles* inside it (its ``"numba:compile"``
  event: a cache miss, so never when the cache is warm) the other groups are handed to worker processes
  (``python -m lgekf.apps.warmup``), which compile their kernels into the same cache;
* this process waits for them, and the real run then loads every kernel from the cache.

A warm cache costs nothing: no compile event, no worker. A worker that fails changes nothing but the
time (the real run compiles what is missing itself). On a busy machine (load average at least the CPU
count) a worker would only compete for the same cores, so there is none (``worker_count``).
``LGEKF_COMPILE_WORKERS=N`` sets the number of processes (1: no workers).
"""

from __future__ import annotations

import importlib
import importlib.util
import os
import pickle
import subprocess
import sys
import threading
from dataclasses import dataclass, field

from ..io.cpus import usable_cpus

__all__ = ["Job", "warm_up", "compile_in_children", "model_compile_seconds", "compile_estimate", "worker_count",
           "SECONDS_PER_BYTE", "IMM_COMPILE_SECONDS", "imm_compile_seconds"]

COMPILED = b"compiling\n"  # a worker's one line on stdout when it starts compiling (a cache miss)

# compile seconds per byte of a generated model module (only its predict/update/run kernels compile in a
# study, but they grow with the module), measured on the 2-core x86-64 machine on 2026-11-24 (load < 1): the
# first `lgekf study` took 12.8 s cold with two workers and 19.3 s with one (1.7 s warm), for 481 kB of modules
SECONDS_PER_BYTE = 0.4e-4
# compile seconds of ``lgekf track --model imm`` on a cold cache, and what --tune and --smooth add (the IMM's loop
# reaches every registry model through generated/dispatch.py, so it compiles all of them whatever its modes):
# CPU seconds of one process on the 2-core x86-64 machine, 2026-11-29 12:19 UTC (load 1.0, a 1 000-row file):
# 88 s alone, 98 s with --tune, 105 s with --smooth, 115 s with both (wall 90, 104, 108, 121 s)
IMM_COMPILE_SECONDS = {"imm": 88.0, "tune": 10.0, "smooth": 17.0}
# the part of the IMM's compile that does not grow with its space's models (the loop's own functions, the noise search's
# shared leaves): the line through the plane's 88 s and 3-D space's 202 s (CPU, a 1 200-row 3-D file, load 3,
# 2026-11-30) against the sizes of their generated model modules
IMM_FIXED_SECONDS = 39.0
# numba's own start in a worker and the kernels every job shares (special functions, helpers)
WORKER_OVERHEAD_SECONDS = 1.5


@dataclass
class Job:
    """One miniature run: ``module.function(*args)``, with its estimated compile seconds."""

    module: str
    function: str
    args: tuple = ()
    cost: float = 1.0
    kwargs: dict = field(default_factory=dict)

    def run(self):
        return getattr(importlib.import_module(self.module), self.function)(*self.args, **self.kwargs)


def model_compile_seconds(model: str) -> float:
    """Estimated seconds to compile a model's filter kernels cold (from the size of its generated module).

    Parameters
    ----------
    model : str
        A registry model name.

    Returns
    -------
    float
        ``SECONDS_PER_BYTE`` times the size of ``lgekf/generated/<model>.py`` (without importing it).
    """
    try:
        spec = importlib.util.find_spec(f"lgekf.generated.{model}")
        return SECONDS_PER_BYTE * os.path.getsize(spec.origin)
    except (ImportError, AttributeError, OSError, TypeError):
        return 3.0


def imm_compile_seconds(tune: bool, smooth: bool, space: str | None = None) -> float:
    """Estimated seconds to compile ``lgekf track --model imm`` cold, with ``--tune`` and/or ``--smooth``
    (``IMM_COMPILE_SECONDS``, one process: the IMM's kernels share the models' leaves, so parallel processes would
    compile the same leaves twice). The figures are the plane's; the IMM of another ``space`` compiles every model of
    that space, so the part of its estimate above ``IMM_FIXED_SECONDS`` is scaled by the size of their generated
    modules against the plane's (3-D: about 200 s, measured 202 s)."""
    from ..core.registry import DEFAULT_SPACE, models_of

    c = IMM_COMPILE_SECONDS
    base = c["imm"] + (c["tune"] if tune else 0.0) + (c["smooth"] if smooth else 0.0)
    if space is None or space == DEFAULT_SPACE:
        return base
    plane = sum(model_compile_seconds(m) for m in models_of(DEFAULT_SPACE))
    return IMM_FIXED_SECONDS + (base - IMM_FIXED_SECONDS) * sum(model_compile_seconds(m) for m in models_of(space)) / plane


def worker_count() -> int:
    """How many processes compile at once: the CPUs this process may use, minus those the load average says
    are busy (compiling in a second process only pays on a free core), at least 1; ``LGEKF_COMPILE_WORKERS``
    sets it."""
    n = usable_cpus()
    given = os.environ.get("LGEKF_COMPILE_WORKERS", "").strip()
    if given.isdigit():
        return max(1, int(given))
    try:
        busy = os.getloadavg()[0]
    except (AttributeError, OSError):
        busy = 0.0
    return max(1, min(n, int(n - busy + 1)))


def _groups(jobs: list, n: int) -> list:
    """Jobs split into at most n groups of similar total cost (longest processing time first)."""
    n = max(1, min(n, len(jobs)))
    groups = [[] for _ in range(n)]
    load = [0.0] * n
    for job in sorted(jobs, key=lambda j: -j.cost):
        i = load.index(min(load))
        groups[i].append(job)
        load[i] += job.cost
    return [g for g in groups if g]


def compile_estimate(costs, workers: int | None = None) -> float:
    """Estimated wall seconds to compile jobs of the given costs on ``workers`` processes.

    Parameters
    ----------
    costs : iterable of float
        Estimated compile seconds of each job (``model_compile_seconds``).
    workers : int, optional
        Processes compiling at once (default ``worker_count()``).

    Returns
    -------
    float
        The largest group's cost plus a worker's start-up when there is more than one group.
    """
    jobs = [Job("", "", cost=float(c)) for c in costs]
    if not jobs:
        return 0.0
    groups = _groups(jobs, worker_count() if workers is None else workers)
    return max(sum(j.cost for j in g) for g in groups) + (WORKER_OVERHEAD_SECONDS if len(groups) > 1 else 0.0)


def _spawn(group: list, stdout=subprocess.DEVNULL, **env_vars):
    env = dict(os.environ, LGEKF_COMPILE_WORKERS="1", **env_vars)
    p = subprocess.Popen([sys.executable, "-m", "lgekf.apps.warmup"], stdin=subprocess.PIPE, stdout=stdout,
                         stderr=subprocess.DEVNULL, env=env)
    try:
        p.stdin.write(pickle.dumps(group))
        p.stdin.close()
    except OSError:
        pass
    return p


def warm_up(jobs: list, workers: int | None = None) -> int:
    """Run ``jobs`` so that every kernel they use is in numba's cache; in parallel processes when cold.

    Parameters
    ----------
    jobs : list of Job
        Miniature runs of the command's code path (picklable arguments).
    workers : int, optional
        Processes compiling at once (default ``worker_count()``).

    Returns
    -------
    int
        The number of worker processes started (0: the cache was warm, or one CPU).
    """
    groups = _groups(list(jobs), worker_count() if workers is None else workers)
    if len(groups) < 2:
        return 0
    from numba.core import event

    procs = []
    pending = []

    class Spawner(event.Listener):
        def on_start(self, ev):
            while pending:  # the first cache miss: hand the groups not yet run to workers
                procs.append(_spawn(pending.pop(0)))

        def on_end(self, ev):
            pass

    try:
        with event.install_listener("numba:compile", Spawner()):
            for i, group in enumerate(groups):  # in this process until one compiles (a warm group costs ms)
                pending[:] = groups[i + 1:]
                for job in group:
                    job.run()
                if procs:
                    break
    finally:
        for p in procs:
            try:
                p.wait()
            except KeyboardInterrupt:
                p.kill()
                raise
    return len(procs)


def compile_in_children(jobs: list, processes: int = 1, on_compile=None) -> int:
    """Run ``jobs`` in ``processes`` worker processes (none in this one) and wait for them: afterwards this process
    loads every kernel they use from the cache, never compiling a copy of its own (``lgekf.apps.sweep_warmup``: a
    freshly compiled SIMD kernel is not the machine code numba caches).

    Parameters
    ----------
    jobs : list of Job
        Miniature runs (picklable), split among the processes by their cost.
    processes : int
        Worker processes.
    on_compile : callable, optional
        Called once, with no argument, as soon as a worker starts compiling (a cold cache): the compile notice.

    Returns
    -------
    int
        The number of workers that compiled something (0: the cache was warm).
    """
    if not jobs:
        return 0
    procs, compiled, threads = [], [], []
    lock = threading.Lock()

    def watch(p):  # a worker writes one line when it starts compiling, then nothing until it exits
        if p.stdout.readline() == COMPILED:
            with lock:
                compiled.append(p)
                if len(compiled) == 1 and on_compile is not None:
                    on_compile()
        p.stdout.read()

    try:
        for g in _groups(list(jobs), processes):
            # one numba thread, as the Dask workers: the threads do not change the kernels' code
            procs.append(_spawn(g, stdout=subprocess.PIPE, NUMBA_NUM_THREADS="1"))
            threads.append(threading.Thread(target=watch, args=(procs[-1],), daemon=True))
            threads[-1].start()
        for p in procs:
            p.wait()
        for t in threads:
            t.join()
        return len(compiled)
    finally:
        for p in procs:
            if p.poll() is None:
                p.kill()
                p.wait()


def _worker() -> int:
    """A worker: run the pickled jobs of stdin, say ``COMPILED`` on stdout at the first compilation, go on past a job
    that fails (the real run compiles what it missed)."""
    from numba.core import event

    jobs = pickle.loads(sys.stdin.buffer.read())
    out = sys.stdout.buffer

    class Tell(event.Listener):
        said = False

        def on_start(self, ev):
            if not self.said:
                self.said = True
                out.write(COMPILED)
                out.flush()

        def on_end(self, ev):
            pass

    failed = 0
    with event.install_listener("numba:compile", Tell()):
        for job in jobs:
            try:
                job.run()
            except Exception:  # noqa: BLE001 - the others still warm the cache
                failed += 1
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(_worker())
