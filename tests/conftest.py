"""Shared test plumbing: a table of measured accuracies printed in the terminal summary."""

from __future__ import annotations

import pytest

_ACCURACY = pytest.StashKey[dict]()


def pytest_configure(config):
    """Byte-compile the project's own sources once, before any test process starts (the xdist controller, or the one
    process without xdist). Where ``PYTHONDONTWRITEBYTECODE`` is set (this project's CI machine sets it) no process
    writes byte code, and an editable install has none of its own: every process the tests start (the CLI runs, the
    documented commands, Dask workers) compiled the generated modules from source on import (SE(3)×SE(3)'s 0.58 s, 0.05 s
    from byte code). Python reads byte code whatever that variable says, and recompiles a stale file itself."""
    if hasattr(config, "workerinput"):
        return
    import compileall
    from pathlib import Path

    root = Path(__file__).resolve().parents[1]
    for folder in ("lgekf", "derive", "generated"):
        compileall.compile_dir(str(root / folder), quiet=1, workers=0)

# The tests work with many tiny (≤ 7×7) matrices; OpenBLAS's worker threads only add overhead there
# and, on a loaded 2-core machine, slow the reference tests down several-fold: one BLAS thread.
try:
    from threadpoolctl import threadpool_limits
except ImportError:  # pragma: no cover
    threadpool_limits = None


@pytest.fixture(autouse=True, scope="session")
def _single_blas_thread():
    if threadpool_limits is None:
        yield
    else:
        with threadpool_limits(limits=1, user_api="blas"):
            yield


@pytest.fixture(scope="session")
def accuracy_table(request):
    """{kernel name: (max relative error, entry, angle)}; printed at the end of the run."""
    return request.config.stash.setdefault(_ACCURACY, {})


def pytest_terminal_summary(terminalreporter, exitstatus, config):
    table = config.stash.get(_ACCURACY, None)
    if not table:
        return
    tr = terminalreporter
    tr.section("max relative error per kernel near theta = 0 (vs 50-digit SymPy/mpmath)")
    tr.write_line(f"{'kernel':<28} {'max rel. error':>14}  {'ulp(1)':>7}  {'entry':<8} {'at angle':>24}")
    for name in sorted(table):
        err, entry, angle = table[name]
        tr.write_line(f"{name:<28} {err:14.3e}  {err / 2.220446049250313e-16:7.1f}  {entry!s:<8} {angle!r:>24}")


@pytest.fixture(scope="session")
def dask_scheduler():
    """The address of a local Dask cluster (2 worker processes, 127.0.0.1 only) shared by the tests that
    pass ``--scheduler``; the ``--workers`` tests start their own, as a user's command does."""
    pytest.importorskip("distributed")
    from lgekf.apps.cluster import dask_client

    with dask_client(workers=2) as client:
        yield client.scheduler.address
