"""Shared test plumbing: a table of measured accuracies printed in the terminal summary."""

from __future__ import annotations

import pytest

_ACCURACY = pytest.StashKey[dict]()

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
