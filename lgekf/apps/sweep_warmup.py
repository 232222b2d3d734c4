"""The numba kernels of a sweep compiled in separate processes before any cell runs, so that every cell runs kernels
*loaded from the cache*: a cold and a warm sweep then write the same table, byte for byte.

Why: numba's freshly compiled copy of a kernel and the copy it loads from its cache are not always the same machine
code. The SIMD batch kernels (``run_batch_soa_<meas>``, run from ``SOA_MIN_BATCH`` trajectories and more than
``SERIAL_STEPS`` trajectory-steps; ``parallel=True`` with ``fastmath={"contract"}``) give, in the process that compiled
them, other numbers (in the last bits) than in a process that loads them from the cache; most likely the two copies
are optimised in different contexts and FMA contraction (allowed by ``contract``) fuses other products. On the
example grid (1000 trajectories × 100 steps) a cold run differed from a warm one in 71 of its 168 rows, the LG models
only (CTRV and CV agreed): relative 7e-16 at the median, up to 1.8 % where the filters lose the track (T = 0.4 s),
since rounding differences grow there. A process that loads every kernel from the cache runs the cached copy,
whichever process compiled it.

So ``lgekf sweep`` (and ``run_sweep``) first runs one miniature study per filter and kernel path of the grid
(``warmup_configs``: the cell's trajectories, a single σ_ω, as few steps as keep the same kernel) in child processes
(``lgekf.apps.warmup.compile_in_children``); they compile into the cache (a cold cache) or only load (a warm one, about a
second), and the cells, on Dask workers or in this process, then load every kernel. A child that fails changes nothing
but the guarantee (the cell compiles what is missing itself).

Limits: a process that has already compiled a kernel itself keeps its own copy (``run_sweep`` in a Python session that
ran a large ``filter_batch`` before); workers on other machines have their own caches (``--scheduler``): their first
cells compile unless their cache is warm or shared (``NUMBA_CACHE_DIR`` on a shared file system).
"""

from __future__ import annotations

from dataclasses import replace

from .warmup import Job, compile_in_children, model_compile_seconds

__all__ = ["warmup_configs", "warm_cache", "compile_seconds"]

# the SIMD kernel's compilation per model and measurement (lgekf.core.batch: ~15 s), on top of the model's others
SOA_COMPILE_SECONDS = 15.0


def _path(cfg) -> tuple:
    """Which batch kernel ``filter_batch`` runs for this config: (SIMD, serial) as in ``lgekf.core.batch``."""
    from ..core.batch import SERIAL_STEPS, SOA_MIN_BATCH

    big = cfg.trajectories * cfg.steps > SERIAL_STEPS
    return (big and cfg.trajectories >= SOA_MIN_BATCH, not big)


def warmup_configs(configs) -> list:
    """Miniature studies that compile every kernel the study configs ``configs`` run: one per filter, truth model,
    measurement and kernel path (``_path``), with the trajectories of the first such config, one σ_ω and as few steps
    as keep the same path (sizes do not enter numba's signatures)."""
    from ..core.batch import SERIAL_STEPS
    from ..experiments.imm_study import IMM_FILTER, ImmStudyOptions

    seen, out = set(), []
    for cfg in configs:
        simd, serial = _path(cfg)
        for name in cfg.filters:
            key = (name, cfg.truth, cfg.measurement, simd, serial)
            if key in seen:
                continue
            seen.add(key)
            steps = min(2, cfg.steps) if serial else SERIAL_STEPS // cfg.trajectories + 1
            if name == IMM_FILTER:  # the IMM learns its chain from training draws that need enough steps
                try:
                    ImmStudyOptions().validate(steps)
                except ValueError:
                    steps = cfg.steps
            out.append(replace(cfg, filters=(name,), steps=steps, sigmas=list(cfg.sigmas)[:1]))
    return out


def compile_seconds(configs) -> list:
    """The estimated cold compile seconds of each warm-up config (``lgekf.apps.warmup.model_compile_seconds`` of its
    filter, plus ``SOA_COMPILE_SECONDS`` when it runs the SIMD kernel)."""
    return [model_compile_seconds(c.filters[0]) + (SOA_COMPILE_SECONDS if _path(c)[0] else 0.0) for c in configs]


def warm_cache(configs, processes: int = 1, on_compile=None) -> int:
    """Run the warm-up studies ``configs`` (``warmup_configs``) in ``processes`` child processes and wait for them
    (``lgekf.apps.warmup.compile_in_children``; ``on_compile``: called once when a child starts compiling). Returns
    the number of children that compiled something (0: the cache was warm)."""
    jobs = [Job("lgekf.experiments.study", "run_study", (cfg,), cost=c) for cfg, c in zip(configs, compile_seconds(configs))]
    return compile_in_children(jobs, processes, on_compile)
