"""`lgekf track` with Parquet files: the argument checks (before any reading or computing)."""

from __future__ import annotations

from ..io.parquet import is_parquet, read_parquet, require_pyarrow

__all__ = ["check_parquet_arguments", "is_parquet", "read_parquet"]


def check_parquet_arguments(a, outs) -> None:
    """One-line errors for what Parquet input or output cannot do, and for a missing pyarrow.

    Parameters
    ----------
    a : argparse.Namespace
        The parsed ``lgekf track`` arguments.
    outs : list
        The output paths (one per model).
    """
    if is_parquet(a.input):
        if a.format != "csv":
            raise ValueError(f"--format {a.format}: {a.input} is a Parquet file (its columns are named like a CSV header's)")
        if a.delimiter is not None:
            raise ValueError("--delimiter: only for CSV input (this is Parquet)")
        require_pyarrow(str(a.input))
    parquet_out = [o for o in outs if is_parquet(o)]
    if parquet_out:
        if getattr(a, "workers", None) or getattr(a, "scheduler", None):
            raise ValueError("--output: Parquet output is written by one process; with --workers/--scheduler write CSV")
        require_pyarrow(f"--output {parquet_out[0]}")
