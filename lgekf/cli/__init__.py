"""The `lgekf` command line: one subcommand per job; bad input gives one line on stderr and exit 2."""

from __future__ import annotations

import argparse
import gc
import os
import re
import sys

__all__ = ["main", "run", "UsageError", "ArgumentParser"]


class UsageError(ValueError):
    """A user-facing error: printed as one line, exit status 2."""


class ArgumentParser(argparse.ArgumentParser):
    """argparse that reports a bad option as one line (UsageError) instead of usage + message, accepts
    negative values after an option (``--v0 -3,0``, not only ``--v0=-3,0``), and takes no abbreviated option
    (``--mult`` is an error, not a silent ``--multi`` that another parser would not see)."""

    _NEGATIVE = re.compile(r"^-(\d|\.\d)")

    def __init__(self, *args, **kwargs):
        kwargs.setdefault("allow_abbrev", False)
        super().__init__(*args, **kwargs)

    def error(self, message):
        raise UsageError(f"{message} (see `{self.prog} --help`)")

    def parse_known_args(self, args=None, namespace=None):
        args = list(sys.argv[1:] if args is None else args)
        takes_value = {o for a in self._actions if a.nargs is None and a.option_strings for o in a.option_strings}
        merged, i = [], 0
        while i < len(args):
            if args[i] in takes_value and i + 1 < len(args) and self._NEGATIVE.match(args[i + 1]):
                merged.append(f"{args[i]}={args[i + 1]}")
                i += 2
            else:
                merged.append(args[i])
                i += 1
        return super().parse_known_args(merged, namespace)


# name -> (module, function, help); the module is imported only when its command runs, so that
# `lgekf derive` does not pay numba's start-up and the runtime commands never import SymPy
COMMANDS = {
    "study": ("lgekf.cli.study", "cmd_study",
              "run the paper's Monte Carlo study (main job): results/summary.csv, rmse.csv, meta.json, study.png"),
    "figures": ("lgekf.cli.figures", "cmd_figures", "reproduce Fig. 1/2 (banana-shaped uncertainty) and Fig. 3 (example trajectories)"),
    "track": ("lgekf.cli.track", "cmd_track",
              "track the objects of a measurement file (CSV t,x,y[,id] or pedestrian format) with one or all filters"),
    "evaluate": ("lgekf.cli.evaluate", "cmd_evaluate",
                 "evaluate every filter on real ground-truth trajectories (ETH/UCY, KITTI, cyclists, DUT or your CSV)"),
    "sweep": ("lgekf.cli.sweep", "cmd_sweep",
              "run a grid of study protocols (GRID.toml) as Dask tasks: cells.csv, meta.json, a figure per swept axis; resumable"),
    "plot": ("lgekf.cli.plot", "cmd_plot",
             "draw a track file: the map with 95 % ellipses and flagged rows, speed, course and turn rate against time"),
    "derive": ("lgekf.cli.derive", "cmd_derive",
               "derive the model ingredients with SymPy and regenerate the numba kernels (--check, --verify)"),
}


def _silence_stdout():
    """Point stdout at /dev/null so that Python's final flush does not fail again on the closed pipe."""
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, ValueError):
        pass


def main(argv=None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)

    parser = argparse.ArgumentParser(
        prog="lgekf",
        description="Tracking with the extended Kalman filter on matrix Lie groups (SE(2)xSE(2), SE(2)xR3) and CTRV/CV baselines.",
    )
    parser.add_argument("command", choices=sorted(COMMANDS), help="; ".join(f"{k}: {v[2]}" for k, v in sorted(COMMANDS.items())))
    parser.add_argument("--version", action="store_true", help="print the version and exit")
    if not argv or argv[0] in ("-h", "--help"):
        parser.print_help()
        return 0 if argv else 2
    if argv[0] == "--version":
        from .. import __version__

        print(f"lgekf {__version__}")
        return 0
    if argv[0] not in COMMANDS:
        print(f"lgekf: error: unknown command {argv[0]!r}; choose one of {', '.join(sorted(COMMANDS))}", file=sys.stderr)
        return 2
    import importlib

    module, name, _ = COMMANDS[argv[0]]
    func = getattr(importlib.import_module(module), name)
    try:
        return int(func(argv[1:]) or 0)
    except BrokenPipeError:
        _silence_stdout()
        return 141  # 128 + SIGPIPE: `lgekf track in.csv -o - | head`, the reader left; not worth a line
    except (UsageError, ValueError, OSError) as e:
        print(f"lgekf {argv[0]}: error: {e}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("lgekf: interrupted", file=sys.stderr)
        return 130


def run() -> None:
    """The ``lgekf`` script (and ``python -m lgekf``): ``main`` on ``sys.argv``, then exit with its status.

    Two things only a whole process may decide, both about time, neither about results:

    * ``OPENBLAS_NUM_THREADS=1`` unless set: NumPy and SciPy each load an OpenBLAS whose worker threads spin for
      about 0.1 s after loading, on the core that reads the file. lgekf's BLAS calls are on matrices too small
      for OpenBLAS to split over threads, so nothing else changes (the variable is read when NumPy is imported,
      which ``main`` does later). A value the user gave ``OPENBLAS_NUM_THREADS`` is kept; one given only to
      ``OMP_NUM_THREADS`` or ``GOTO_NUM_THREADS`` no longer reaches OpenBLAS, which reads ``OPENBLAS_NUM_THREADS``
      first.
    * ``gc.freeze()`` before exiting: the interpreter's final garbage collections walk every object the run made
      (numba's and the data's; about 0.1 s) to free memory the operating system takes back anyway. Every output
      of a command is closed inside ``main``; objects are still freed by reference counting, but the finalizers of
      objects in reference cycles at that moment do not run.
    """
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    status = main()
    gc.freeze()
    sys.exit(status)
