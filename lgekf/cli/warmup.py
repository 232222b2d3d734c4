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
  (``python -m lgekf.cli.warmup``), which compile their kernels into the same cache;
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
from dataclasses import dataclass, field

from ..io.cpus import usable_cpus

__all__ = ["Job", "warm_up", "study_jobs", "track_jobs", "tiny_track", "model_compile_seconds", "compile_estimate", "worker_count"]

# compile seconds per byte of a generated model module (only its predict/update/run kernels compile in a
# study, but they grow with the module), measured on the 2-core x86-64 machine on 2026-11-24 (load < 1): the
# first `lgekf study` took 12.8 s cold with two workers and 19.3 s with one (1.7 s warm), for 481 kB of modules
SECONDS_PER_BYTE = 0.4e-4
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


def _spawn(group: list):
    env = dict(os.environ, LGEKF_COMPILE_WORKERS="1")
    p = subprocess.Popen([sys.executable, "-m", "lgekf.cli.warmup"], stdin=subprocess.PIPE, stdout=subprocess.DEVNULL,
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


def study_jobs(cfg) -> list:
    """The study's warm-up: one miniature study (2 trajectories, 2 steps, one σ_ω) per filter of ``cfg``.

    Parameters
    ----------
    cfg : lgekf.experiments.study.StudyConfig
        The study to be run.

    Returns
    -------
    list of Job
        ``run_study`` on the same truth, measurement and filter, costed by ``model_compile_seconds``.
    """
    from dataclasses import replace

    jobs = []
    for name in cfg.filters:
        small = replace(cfg, filters=(name,), trajectories=2, steps=2, sigmas=list(cfg.sigmas)[:1])
        jobs.append(Job("lgekf.experiments.study", "run_study", (small,), cost=model_compile_seconds(name)))
    return jobs


def tiny_track(model: str, measure: str = "position", full_cov: bool = False) -> None:
    """``lgekf track`` on a small made-up file (3 turning objects of 40 measurements): compiles what a
    real ``track`` run of ``model`` compiles (the kernels' types do not depend on the file's size).

    Parameters
    ----------
    model : str
        A registry model name.
    measure : str
        ``position`` or ``pose`` (the file has a heading column).
    full_cov : bool
        Write every covariance entry (``--full-cov``).
    """
    import contextlib
    import io
    import tempfile
    from pathlib import Path

    import numpy as np

    from . import main  # the command table, not lgekf.cli.track itself (which imports this module)

    rng = np.random.default_rng(0)
    lines = ["id,t,x,y,heading"]
    for o in range(3):
        t = 0.1 * np.arange(40) + 0.013 * rng.random(40)
        th = 0.3 * o + 0.4 * t
        x, y = 20 * o + 3 * np.cumsum(np.cos(th)) * 0.1, 3 * np.cumsum(np.sin(th)) * 0.1
        lines += [f"{o},{a!r},{b!r},{c!r},{d!r}" for a, b, c, d in zip(t.tolist(), (x + 0.05 * rng.standard_normal(40)).tolist(),
                                                                       (y + 0.05 * rng.standard_normal(40)).tolist(), th.tolist())]
    with tempfile.TemporaryDirectory(prefix="lgekf-warmup.") as d:
        inp = Path(d) / "in.csv"
        inp.write_text("\n".join(lines) + "\n")
        argv = [str(inp), "-o", str(Path(d) / "out.csv"), "--model", model, "--measure", measure, "--quiet"]
        with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
            main(["track", *argv, *(["--full-cov"] if full_cov else [])])


def track_jobs(models, measure: dict, full_cov: bool = False) -> list:
    """``lgekf track --model all``'s warm-up: one ``tiny_track`` per model.

    Parameters
    ----------
    models : sequence of str
        The models tracked.
    measure : dict
        Model -> the measurement it gets (``position`` or ``pose``).
    full_cov : bool
        ``--full-cov``.

    Returns
    -------
    list of Job
    """
    return [Job("lgekf.cli.warmup", "tiny_track", (m, measure.get(m, "position"), full_cov), cost=model_compile_seconds(m))
            for m in models]


def _worker() -> int:
    for job in pickle.loads(sys.stdin.buffer.read()):
        job.run()
    return 0


if __name__ == "__main__":
    sys.exit(_worker())
