"""``lgekf.track``: the main job from Python, on the engine of ``lgekf track`` (the same checks, noise from the data,
divergence monitor, smoothing and output columns; the CLI and this function differ only in how they are called)."""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

import numpy as np

__all__ = ["track"]


def _write_input(data, path: Path) -> None:
    """A DataFrame or a mapping of equal-length columns as a CSV the reader of ``lgekf track`` takes (floats
    written with 17 significant digits: read back bit for bit)."""
    if hasattr(data, "to_csv"):  # a pandas DataFrame
        data.to_csv(path, index=False, float_format="%.17g", na_rep="nan")  # NaN as the reader's nan (skip_invalid)
        return
    cols = {str(k): np.asarray(v) for k, v in dict(data).items()}
    if not cols:
        raise ValueError("lgekf.track: the data has no columns; expected t, x, y[, id][, heading]")
    n = {len(v) for v in cols.values()}
    if len(n) != 1 or any(v.ndim != 1 for v in cols.values()):
        raise ValueError("lgekf.track: every column must be one-dimensional and of the same length, got "
                         + ", ".join(f"{k} {v.shape}" for k, v in cols.items()))
    text = [",".join(cols)]
    fmt = [(lambda v: repr(float(v))) if np.issubdtype(v.dtype, np.floating) else str for v in cols.values()]
    for row in zip(*cols.values()):
        text.append(",".join(f(v) for f, v in zip(fmt, row)))
    path.write_text("\n".join(text) + "\n")


def _argv(source: str, out: str, model, measure, tune, smooth, multi, quiet, options: dict) -> list:
    argv = [source, "-o", out]
    if multi:
        argv.append("--multi")
    if model is not None:
        argv += ["--model", str(model)]
    if measure is not None:
        argv += ["--measure", str(measure)]
    argv += ["--tune"] * bool(tune) + ["--smooth"] * bool(smooth) + ["--quiet"] * bool(quiet)
    for key, value in options.items():
        flag = "--" + key.replace("_", "-")
        if value is None or value is False:
            continue
        if value is True:
            argv.append(flag)
        elif isinstance(value, (list, tuple)) and key == "accel_std":  # repeatable MODEL=LIST
            for v in value:
                argv += [flag, str(v)]
        else:
            argv += [flag, str(value)]
    return argv


def track(data, model: str | None = None, measure: str | None = None, tune: bool = False, smooth: bool = False,
          multi: bool = False, output: str | os.PathLike | None = None, quiet: bool = True, **options):
    """Track every object of ``data`` as ``lgekf track`` does and return its output as a pandas DataFrame.

    Parameters
    ----------
    data : str, path, pandas.DataFrame or mapping of column -> array
        A measurement file (CSV, gzip, Parquet, the pedestrian format), or the columns themselves: ``t``, ``x``,
        ``y`` (or ``lat``, ``lon``), ``z`` (or ``alt``) for 3-D positions, and optionally ``id`` and ``heading`` (the
        CLI's input columns; 3-D poses: ``roll``, ``pitch``, ``yaw``).
    model : str, optional
        ``--model``: a registry model, ``all`` (then a dict {model: DataFrame} of the models of the input's space is
        returned) or ``imm``; default the CLI's (se2se2; ct3 on 3-D positions).
    measure : {"position", "pose"}, optional
    tune, smooth, multi : bool
        ``--tune``, ``--smooth``, ``--multi``.
    output : path, optional
        Also keep the output file there (the CLI's bytes); default a temporary file, removed.
    quiet : bool
        ``--quiet`` (default): only warnings are printed (to stderr).
    **options
        Any other option of ``lgekf track`` with ``_`` for ``-``: ``meas_std=1.0``, ``accel_std="cv=0.8"`` (or a
        list of ``MODEL=LIST``), ``imm_modes="cv,se2r3:manoeuvre"``, ``no_monitor=True``, ``precision=17``, ...

    Returns
    -------
    pandas.DataFrame
        Exactly the columns of the CLI's output file (``docs/track.md``), ``id`` as str.

    Raises
    ------
    ValueError
        The CLI's one-line message for bad input or options (the CLI exits 2 with it).
    """
    import pandas as pd

    from . import UsageError
    from .track import cmd_track
    from .track_parquet import is_parquet

    with tempfile.TemporaryDirectory(prefix="lgekf-track-") as tmp:
        tmp = Path(tmp)
        if isinstance(data, (str, os.PathLike)):
            source = os.fspath(data)
        else:
            source = str(tmp / "input.csv")
            _write_input(data, Path(source))
        out = os.fspath(output) if output is not None else str(tmp / "tracks.csv")
        argv = _argv(source, out, model, measure, tune, smooth, multi, quiet, options)
        written = {}
        try:
            status = cmd_track(argv, written)
        except UsageError as e:  # a bad option: the CLI's one line
            raise ValueError(str(e)) from None
        if status:
            raise RuntimeError(f"lgekf track exited with status {status}")
        def read(path):
            return pd.read_parquet(path) if is_parquet(path) else pd.read_csv(path, dtype={"id": str, "track": str})

        if model == "all":  # the models of the input's space (the plane's, or 3-D space's for a z column)
            return {m: read(path) for m, path in written.items()}
        return read(out)
