"""The warm-up jobs of the commands (``lgekf.apps.warmup``: compile a command's numba kernels in parallel processes
when the cache is cold): a miniature study per filter (``study_jobs``) and a tiny ``lgekf track`` per model
(``track_jobs``)."""

from __future__ import annotations

from ..apps.warmup import Job, compile_estimate, model_compile_seconds, warm_up, worker_count

__all__ = ["Job", "warm_up", "study_jobs", "track_jobs", "tiny_track", "model_compile_seconds", "compile_estimate", "worker_count"]


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
