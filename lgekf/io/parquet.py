"""Parquet in and out for ``lgekf track`` (a path ending in ``.parquet`` or ``.pq``); needs pyarrow.

* ``read_parquet(path)``: the measurements of a Parquet file, with ``read_csv``'s column names and
  aliases, checks and messages (``measurements_from_columns``); integer ids become their decimal text,
  float ids as the pedestrian reader writes them, text ids are stripped of surrounding spaces.
* ``ParquetRows(fh, columns)``: a track file written in row groups (one per chunk of objects, so the
  whole output is never in memory) to an open binary file (the temporary of ``AtomicFiles``: a failed
  run leaves no partial file). Columns: ``id`` text, ``flag`` int8, everything else float64 stored
  exactly (``--precision`` applies to CSV only).

pyarrow is optional: ``pip install "lgekf[parquet]"``; without it ``require_pyarrow`` raises a one-line
``FileError`` saying so. Nothing else in lgekf imports pyarrow.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from .files import FileError, is_stdio, source_name
from .readers import DataError, Measurements, _unused, header_keys, measurements_from_columns

__all__ = ["PARQUET_SUFFIXES", "INSTALL_HINT", "is_parquet", "require_pyarrow", "read_parquet", "ParquetRows"]

PARQUET_SUFFIXES = (".parquet", ".pq")
INSTALL_HINT = 'pip install "lgekf[parquet]"'


def is_parquet(path) -> bool:
    """True for a file name ending in ``.parquet`` or ``.pq`` (any case); never for ``-``."""
    return not is_stdio(path) and Path(str(path)).suffix.lower() in PARQUET_SUFFIXES


def require_pyarrow(what: str):
    """``(pyarrow, pyarrow.parquet)``, or a one-line ``FileError`` naming the extra that installs it.

    Parameters
    ----------
    what : str
        What needs it (the path), the start of the message.
    """
    try:
        import pyarrow as pa
        import pyarrow.parquet as pq
    except ImportError:
        raise FileError(f"{what}: Parquet needs pyarrow: {INSTALL_HINT}") from None
    return pa, pq


def _id_texts(col) -> np.ndarray:
    import pyarrow as pa

    t = col.type
    if pa.types.is_integer(t):
        return np.asarray(col.to_numpy(zero_copy_only=False)).astype(str)
    if pa.types.is_floating(t):
        v = np.asarray(col.to_numpy(zero_copy_only=False), dtype=float)
        return np.array([str(int(x)) if math.isfinite(x) and x.is_integer() and abs(x) < 2.0**53 else repr(float(x)) for x in v], dtype=str)
    return np.char.strip(np.asarray(col.cast(pa.string()).fill_null("").to_numpy(zero_copy_only=False), dtype=str))


def read_parquet(path, use_heading: bool = False, extra=()) -> Measurements:
    """Read the ``t, x, y[, id][, heading]`` (or ``t, lat, lon, ...``) columns of a Parquet file.

    Parameters
    ----------
    path : str or Path
        A Parquet file.
    use_heading : bool
        Read the ``heading`` column (an error when there is none).
    extra : sequence of str
        Further numeric columns to read when present, in ``Measurements.extra``.

    Returns
    -------
    Measurements
        In file order; row i is reported as "row i + 1" in messages (the row number, counted from 1). A t column of
        Parquet timestamps (or dates) is read as seconds since the epoch (a naive timestamp is UTC), one of text as
        ISO-8601 date-times (``lgekf.io.times``).
    """
    source = source_name(path)
    pa, pq = require_pyarrow(source)
    try:
        pf = pq.ParquetFile(str(path))
        names = list(pf.schema_arrow.names)
    except FileNotFoundError:
        raise DataError(f"{source}: cannot read (No such file or directory)") from None
    except (OSError, ValueError, pa.ArrowException) as e:
        raise DataError(f"{source}: cannot read as Parquet ({e})") from None
    keys = header_keys(source, names, use_heading)
    lower = [n.strip().lower() for n in names]
    for name in extra:
        if name in lower and name not in keys:
            keys[name] = lower.index(name)
    try:
        table = pf.read(columns=[names[i] for i in keys.values()])
    except (OSError, ValueError, pa.ArrowException) as e:
        raise DataError(f"{source}: cannot read as Parquet ({e})") from None
    if table.num_rows == 0:
        raise DataError(f"{source}: no measurements (the table has no rows)")
    cols = {}
    for k, i in keys.items():
        col = table.column(names[i]).combine_chunks() if table.column(names[i]).num_chunks != 1 else table.column(names[i]).chunk(0)
        if k == "id":
            cols[k] = _id_texts(col)
            continue
        if k == "t" and (pa.types.is_timestamp(col.type) or pa.types.is_date(col.type)):  # seconds since the epoch (UTC)
            ns = np.asarray(col.cast(pa.timestamp("ns", tz=getattr(col.type, "tz", None))).cast(pa.int64()).fill_null(0)
                            .to_numpy(zero_copy_only=False), dtype=np.int64)
            whole = np.floor_divide(ns, 1_000_000_000)
            v = whole.astype(float) + (ns - whole * 1_000_000_000).astype(float) * 1e-9
            if col.null_count:
                v[np.asarray(col.is_null().to_numpy(zero_copy_only=False), bool)] = math.nan
            cols[k] = v
            continue
        if k == "t" and (pa.types.is_string(col.type) or pa.types.is_large_string(col.type)):  # ISO-8601 date-times
            cols[k] = np.asarray(col.fill_null("").to_numpy(zero_copy_only=False), dtype=str)
            continue
        if not (pa.types.is_integer(col.type) or pa.types.is_floating(col.type)):
            raise DataError(f"{source}: column {names[i]!r} is {col.type}, expected numbers")
        cols[k] = np.asarray(col.cast(pa.float64()).fill_null(math.nan).to_numpy(zero_copy_only=False), dtype=float)
    lines = np.arange(1, table.num_rows + 1, dtype=np.int64)
    return measurements_from_columns(source, cols, lines, use_heading, extra=[n for n in extra if n in cols],
                                     unused=_unused(names, keys, extra), line_word="row")


class ParquetRows:
    """A track file in Parquet: ``write_rows`` appends one row group; ``close`` writes the footer.

    Parameters
    ----------
    fh : binary file
        Where the bytes go (an ``AtomicFiles`` temporary); left open.
    columns : sequence of str
        The header (``lgekf.apps.track.output_columns``): ``id`` first, then ``t``, the numbers and ``flag`` last.
    name : str
        The output's name, for the message when pyarrow is missing.
    """

    def __init__(self, fh, columns, name="output"):
        self.pa, pq = require_pyarrow(name)
        pa = self.pa
        self.columns = list(columns)
        self.schema = pa.schema([(c, pa.string() if c == "id" else pa.int8() if c == "flag" else pa.float64()) for c in self.columns])
        self.writer = pq.ParquetWriter(fh, self.schema, compression="zstd")

    def write_rows(self, labels, row_label, t, values) -> None:
        """Append rows: ``labels[row_label[i]]``, ``t[i]``, ``values[i]`` (its last column the flag).

        Parameters
        ----------
        labels : sequence of str
            The object names.
        row_label : ndarray of int, (N,)
            Each row's index into ``labels``.
        t : ndarray, (N,)
        values : ndarray, (N, len(columns) - 2)
        """
        pa = self.pa
        ids = pa.DictionaryArray.from_arrays(pa.array(np.asarray(row_label, dtype=np.int32)), pa.array(list(labels), pa.string()))
        arrays = [ids.cast(pa.string()), pa.array(np.asarray(t, dtype=float))]
        values = np.asarray(values, dtype=float)
        for j in range(values.shape[1] - 1):
            arrays.append(pa.array(np.ascontiguousarray(values[:, j])))
        arrays.append(pa.array(values[:, -1].astype(np.int8)))
        self.writer.write_table(pa.Table.from_arrays(arrays, schema=self.schema))

    def close(self) -> None:
        """Write the footer (the file is complete only then)."""
        self.writer.close()
