"""The results table of ``lgekf sweep``: one row per cell × σ_ω × filter, as CSV or Parquet.

Columns: ``cell`` (the cell's key), ``seed`` (its derived seed), one column per grid axis (the option's
name; σ_ω as ``sigma_w``), ``sigma_w`` (when σ_ω is not an axis), ``filter`` (every filter of the cell
and ``measurements``), ``mean_rmse``, ``std_rmse`` (position RMSE over the cell's trajectories, m; std
with ddof 1), ``n`` (trajectories), ``wrapped`` (trajectories whose truth ω wrapped at ±π at this σ_ω)
and ``aliased`` (trajectories this filter cannot represent; 0 for the others).

CSV numbers are written as Python's shortest round-trip text (``repr``), so reading a table and writing
it again gives the same bytes and the same float64 values. Every write replaces the whole file through
a temporary file and a rename: after a crash the table holds complete cells only. Parquet needs pyarrow
(installed with the ``dask`` extra).
"""

from __future__ import annotations

import csv
import io
import os
from pathlib import Path

from ..experiments.grid import SIGMA_COLUMN, column_type
from ..io.output import write_atomic

__all__ = ["TABLE_FORMATS", "RESULT_COLUMNS", "table_columns", "table_name", "read_table", "write_table", "TableError"]

TABLE_FORMATS = ("csv", "parquet")
RESULT_COLUMNS = [("filter", str), ("mean_rmse", float), ("std_rmse", float), ("n", int), ("wrapped", int), ("aliased", int)]


class TableError(ValueError):
    """An existing results table that does not belong to this grid or cannot be read."""


def table_columns(axis_columns) -> list:
    """[(name, type)] of a sweep's table for its axis columns (``Grid.axis_columns()``)."""
    cols = [("cell", str), ("seed", int)]
    cols += [(a, float if a == SIGMA_COLUMN else column_type(a)) for a in axis_columns if a != SIGMA_COLUMN]
    cols.append((SIGMA_COLUMN, float))
    return cols + RESULT_COLUMNS


def table_name(fmt: str) -> str:
    """``cells.csv`` or ``cells.parquet``."""
    return f"cells.{fmt}"


def _text(v) -> str:
    return repr(v) if isinstance(v, float) else str(v)


def _csv_bytes(columns, rows) -> str:
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow([c for c, _ in columns])
    for r in rows:
        w.writerow([_text(v) for v in r])
    return buf.getvalue()


def _pyarrow():
    try:
        import pyarrow as pa
        import pyarrow.parquet as pq
    except ImportError:
        from .cluster import INSTALL_HINT

        raise TableError(f"--format parquet needs pyarrow: {INSTALL_HINT}") from None
    return pa, pq


def _schema(pa, columns):
    kinds = {str: pa.string(), int: pa.int64(), float: pa.float64()}
    return pa.schema([(c, kinds[t]) for c, t in columns])


def write_table(path: Path, columns, rows, fmt: str) -> None:
    """Replace ``path`` by the table ``rows`` (tuples in the order of ``columns``), atomically."""
    path = Path(path)
    if fmt == "csv":
        write_atomic(path, _csv_bytes(columns, rows))
        return
    pa, pq = _pyarrow()
    data = {c: [r[i] for r in rows] for i, (c, _) in enumerate(columns)}
    table = pa.Table.from_pydict(data, schema=_schema(pa, columns))
    tmp = path.with_name(f".{path.name}.tmp{os.getpid()}")
    try:
        pq.write_table(table, tmp)
        tmp.replace(path)
    finally:
        if tmp.exists():
            tmp.unlink()


def read_table(path: Path, columns, fmt: str) -> list:
    """The rows of an existing table as tuples (typed like ``columns``); [] when there is none.

    Raises
    ------
    TableError
        The file's columns are not ``columns`` (another grid's table) or a value does not parse.
    """
    path = Path(path)
    if not path.exists():
        return []
    names = [c for c, _ in columns]
    if fmt == "csv":
        with open(path, newline="", encoding="utf-8") as f:
            r = csv.reader(f)
            header = next(r, None)
            if header != names:
                raise TableError(f"{path}: has the columns {', '.join(header or [])}; this grid's are {', '.join(names)} "
                                 "(results of another grid: give another output folder)")
            rows = []
            for k, rec in enumerate(r, 2):
                try:
                    rows.append(tuple(t(v) for (_, t), v in zip(columns, rec, strict=True)))
                except ValueError:
                    raise TableError(f"{path} line {k}: not a row of this table ({rec!r}); remove the file to start over") from None
            return rows
    pa, pq = _pyarrow()
    try:
        table = pq.read_table(path)
    except (OSError, pa.ArrowException) as e:
        raise TableError(f"{path}: cannot read ({e}); remove the file to start over") from None
    if table.column_names != names:
        raise TableError(f"{path}: has the columns {', '.join(table.column_names)}; this grid's are {', '.join(names)} "
                         "(results of another grid: give another output folder)")
    cols = [table.column(c).to_pylist() for c in names]
    return [tuple(t(v) for (_, t), v in zip(columns, rec)) for rec in zip(*cols)]
