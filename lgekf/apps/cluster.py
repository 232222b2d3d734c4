"""Dask for the distributed commands (``lgekf sweep``, ``track``/``evaluate`` with ``--workers``/``--scheduler``).

Dask is an optional extra (``pip install "lgekf[dask]"``): it is imported only here and only when one of
those commands asks for a cluster; without it they stop with one line saying how to install it.

* ``dask_client(workers=N)``: a local cluster of N worker processes with one thread each, every socket
  bound to 127.0.0.1 (scheduler, workers, nannies, the HTTP endpoints), Dask's own logs silenced
  (a failing task reaches the caller as its exception, which the commands report in one line). The
  workers run numba's parallel kernels on one thread (``NUMBA_NUM_THREADS=1``, same for BLAS/OpenMP):
  one process per core instead of N processes fighting over every core.
* ``dask_client(scheduler=ADDRESS)``: a client of a running cluster (``tcp://host:8786``); its workers
  must have the same lgekf version installed (checked) and see the same files as this machine.
"""

from __future__ import annotations

import logging
from contextlib import contextmanager

from ..io.cpus import usable_cpus

__all__ = ["INSTALL_HINT", "DaskMissing", "require_dask", "dask_client", "default_workers", "worker_count", "WORKER_ENV"]

INSTALL_HINT = 'pip install "lgekf[dask]"'
LOOPBACK = "127.0.0.1"
WORKER_ENV = {"NUMBA_NUM_THREADS": "1", "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1", "MKL_NUM_THREADS": "1"}
CONNECT_TIMEOUT = "20s"


class DaskMissing(ValueError):
    """Dask is needed but not installed (the message says how to install it)."""


def require_dask(what: str):
    """Import and return ``dask.distributed``, or raise ``DaskMissing`` naming ``what`` needs it.

    Parameters
    ----------
    what : str
        The command or option that needs Dask (``lgekf sweep``, ``--workers``), named in the message.
    """
    try:
        import dask.dataframe  # noqa: F401  (track reads through dask.dataframe; pandas and pyarrow with it)
        import distributed
    except ImportError as e:
        raise DaskMissing(f"{what} needs Dask ({e.name or 'dask'} is not installed): {INSTALL_HINT}") from None
    return distributed


def default_workers() -> int:
    """The number of cores this process may use (the default ``--workers``)."""
    return usable_cpus()


def _lgekf_version():
    from .. import __version__

    return __version__


def _check_versions(client, address):
    from .. import __version__

    try:
        found = client.run(_lgekf_version)
    except Exception as e:  # noqa: BLE001 - a worker without lgekf cannot even unpickle the function
        raise OSError(f"--scheduler {address}: the workers cannot run lgekf ({type(e).__name__}: {e}); install lgekf "
                      f"{__version__} on every worker") from None
    if not found:
        raise OSError(f"--scheduler {address}: the cluster has no workers")
    bad = {w: v for w, v in found.items() if v != __version__}
    if bad:
        w, v = next(iter(bad.items()))
        raise OSError(f"--scheduler {address}: worker {w} has lgekf {v}, this machine {__version__}; install the same version everywhere")


@contextmanager
def dask_client(workers: int | None = None, scheduler: str | None = None, what: str = "lgekf"):
    """A ``distributed.Client``: of a new local cluster (``workers``) or of the scheduler at ``scheduler``.

    Parameters
    ----------
    workers : int, optional
        Worker processes of the local cluster (default: ``default_workers()``); ignored with ``scheduler``.
    scheduler : str, optional
        Address of a running scheduler (``tcp://host:8786``).
    what : str
        Named in the message when Dask is missing.

    Yields
    ------
    distributed.Client
        Closed, with its local cluster, when the block ends.
    """
    distributed = require_dask(what)
    if scheduler:
        try:
            client = distributed.Client(scheduler, timeout=CONNECT_TIMEOUT)
        except (OSError, ValueError, TypeError) as e:
            raise OSError(f"--scheduler {scheduler}: cannot connect ({e})") from None
        try:
            _check_versions(client, scheduler)
            yield client
        finally:
            client.close()
        return
    n = workers or default_workers()
    cluster = distributed.LocalCluster(
        n_workers=n, threads_per_worker=1, processes=True, host=LOOPBACK, dashboard_address=f"{LOOPBACK}:0",
        worker_dashboard_address=f"{LOOPBACK}:0", silence_logs=logging.CRITICAL, env=dict(WORKER_ENV),
    )
    try:
        client = distributed.Client(cluster)
        try:
            yield client
        finally:
            client.close()
    finally:
        cluster.close()


def worker_count(client) -> int:
    """The number of workers the client's scheduler has now."""
    return len(client.nthreads())
