"""The ``--workers`` / ``--scheduler`` options shared by the commands that can run on Dask."""

from __future__ import annotations

from . import UsageError

__all__ = ["add_cluster_options", "cluster_requested", "check_cluster_options", "cluster_label"]


def add_cluster_options(ap, default_local: bool = False) -> None:
    """Add ``--workers N`` and ``--scheduler ADDRESS`` to a parser.

    Parameters
    ----------
    ap : argparse.ArgumentParser
        The command's parser.
    default_local : bool
        True when the command always runs on Dask (``sweep``: a local cluster unless ``--scheduler``);
        False when the options switch Dask on (``track``, ``evaluate``).
    """
    when = "default: one per core" if default_local else "runs on Dask; default: in this process, no Dask"
    ap.add_argument("--workers", type=int, default=None, metavar="N",
                    help=f"worker processes of a local Dask cluster on 127.0.0.1 ({when}); needs lgekf[dask]")
    ap.add_argument("--scheduler", default=None, metavar="ADDRESS",
                    help="run on the Dask cluster whose scheduler is at ADDRESS (tcp://host:8786); its workers need the same "
                         "lgekf and must see the same files; needs lgekf[dask]")


def check_cluster_options(a) -> None:
    """One ``UsageError`` line for an impossible combination (before any work)."""
    if a.workers is not None and a.scheduler:
        raise UsageError("--workers and --scheduler: give one (--workers starts a local cluster, --scheduler uses a running one)")
    if a.workers is not None and a.workers < 1:
        raise UsageError(f"--workers: must be at least 1, got {a.workers}")
    if a.scheduler is not None and not a.scheduler.strip():
        raise UsageError("--scheduler: give the scheduler's address, e.g. tcp://10.0.0.5:8786")


def cluster_requested(a) -> bool:
    """True when ``--workers`` or ``--scheduler`` was given."""
    return a.workers is not None or bool(a.scheduler)


def cluster_label(a, workers: int) -> str:
    """Where the tasks run, for messages and meta.json."""
    return f"scheduler {a.scheduler}" if a.scheduler else f"local cluster, {workers} worker{'s' if workers != 1 else ''}"
