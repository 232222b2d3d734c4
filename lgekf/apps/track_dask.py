"""``lgekf track`` on Dask: a large CSV or Parquet file tracked in partitions that hold whole objects.

The output is the single-process output, byte for byte: the same rows (objects in order of first
appearance in the file, each object's rows in file order), the same numbers, the same text.

How
---
1. The file is read as a Dask dataframe (``dask.dataframe.read_csv`` in blocks of about
   ``partition_rows`` rows, every field as text; or ``read_parquet``). A first pass over the blocks reads
   the id column only, counts each object's rows and finds its first row (block, position): the driver
   turns that into the object table (id, first row, rows), checks that every object has two rows, and
   ranks the objects by their first row.
2. The ranks are cut into ranges of about ``partition_rows`` rows, and a second pass parses the numbers
   (the line of a bad value is named, as in ``read_csv``) and moves every row to the partition of its
   object's rank range (``set_index`` with those divisions: a shuffle on the cluster). A partition thus
   holds whole objects, and the partitions in order hold the objects in order.
3. Each partition is checked and tracked by the single-process code (``Measurements.grouped``,
   ``lgekf.apps.track.write_model``, one filter run per object, independent of the other objects) and
   returns its rows as CSV bytes; the driver writes the partitions in order, as they arrive.

Unit warnings (``lgekf.io.units``) are computed on a sample: the first objects of every partition, up to
``SAMPLE_ROWS`` rows each. Line numbers in messages count the header as line 1 (CSV) or are row numbers
from 1 (Parquet). A quoted field must not contain a line break (the blocks are cut at line breaks).
"""

from __future__ import annotations

import io
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..io.attitude import QUATERNION_COLUMNS
from ..io.files import is_stdio, source_name
from ..io.geo import max_scale_error
from ..io.readers import DataError, csv_header, header_keys, measurements_from_columns, parse_number_column
from ..io.units import to_seconds
from .track import output_columns, write_model

__all__ = ["TrackSource", "open_source", "plan_partitions", "track_partitions", "PartitionResult", "PARTITION_ROWS", "SAMPLE_ROWS"]

PARTITION_ROWS = 1 << 18
SAMPLE_ROWS = 1 << 13
# the numeric columns read (3-D: z or alt, and a pose's attitude: roll, pitch, heading (yaw) or a quaternion)
NUMERIC = ("t", "x", "y", "z", "lat", "lon", "alt", "roll", "pitch", "heading", *QUATERNION_COLUMNS)
PARQUET_SUFFIXES = (".parquet", ".pq")
MIN_BLOCK_BYTES = 1 << 10
MAX_BLOCK_BYTES = 1 << 28


@dataclass
class TrackSource:
    """A measurement file as the Dask reader sees it: kind (``csv``/``parquet``) and the columns it reads."""

    path: str
    kind: str
    columns: dict  # key -> column index (CSV) or name (Parquet)
    delimiter: str | None = ","
    gzip: bool = False
    first_line: int = 2  # the line number of data row 0 (CSV: after the header)

    @property
    def source(self) -> str:
        return source_name(self.path)

    @property
    def keys(self) -> list:
        return list(self.columns)

    @property
    def projected(self) -> bool:
        return "lat" in self.columns


def open_source(path, use_heading: bool = False, delimiter="auto") -> TrackSource:
    """Check a file for the Dask reader and find its columns (``read_csv``'s rules and aliases).

    Parameters
    ----------
    path : str or Path
        A CSV file (plain or gzip) or a Parquet file or folder (``.parquet``, ``.pq`` or a folder).
    use_heading : bool
        The ``heading`` column is needed.
    delimiter : str or None
        CSV separator as for ``read_csv`` (``"auto"``: from the header line).

    Returns
    -------
    TrackSource
    """
    if is_stdio(path):
        raise DataError("INPUT -: with --workers or --scheduler the workers read the file themselves; give a file name, not stdin")
    p = Path(path)
    if not p.exists():
        raise DataError(f"{p}: cannot read (No such file or directory)")
    if p.is_dir() or p.suffix.lower() in PARQUET_SUFFIXES:
        if delimiter != "auto":
            raise DataError("--delimiter: only for CSV input (this is Parquet)")
        try:
            import pyarrow.dataset as pads

            names = pads.dataset(str(p), format="parquet").schema.names
        except (OSError, ValueError) as e:
            raise DataError(f"{p}: cannot read as Parquet ({e})") from None
        keys = header_keys(str(p), names, use_heading)
        return TrackSource(str(p), "parquet", {k: names[i] for k, i in keys.items()}, None, False, 1)
    delim, cols, gz = csv_header(p, use_heading, delimiter)
    return TrackSource(str(p), "csv", cols, delim, gz, 2)


def _read_frame(src: TrackSource, partition_rows: int, keys=None):
    """The Dask dataframe of the columns ``keys`` (default: all that lgekf reads), named by key; CSV fields as
    text. The blocks depend on the file and ``partition_rows`` only, so two reads have the same rows per block."""
    import dask.dataframe as dd

    cols = {k: v for k, v in src.columns.items() if keys is None or k in keys}
    if src.kind == "parquet":
        df = dd.read_parquet(src.path, columns=list(cols.values()))
        return df.rename(columns={v: k for k, v in cols.items()})
    order = sorted(cols.items(), key=lambda kv: kv[1])  # pandas returns usecols in file order
    with open(src.path, "rb") as f:
        head = f.read(1 << 16)
    per_row = max(len(head) / max(head.count(b"\n"), 1), 8.0)
    block = int(min(max(partition_rows * per_row, MIN_BLOCK_BYTES), MAX_BLOCK_BYTES))
    df = dd.read_csv(
        src.path, sep=src.delimiter if src.delimiter is not None else r"\s+", header=0, usecols=[i for _, i in order],
        dtype=str, keep_default_na=False, na_filter=False, skip_blank_lines=False, encoding="utf-8-sig",
        blocksize=None if src.gzip else block, compression="gzip" if src.gzip else None,
    )
    return df.rename(columns=dict(zip(df.columns, [k for k, _ in order])))


def _stripped(series):
    """Text with surrounding whitespace removed, like ``read_csv`` does with ids (pandas string methods: fast)."""
    return series.astype(str).str.strip()


def _ids(df, kind: str) -> np.ndarray:
    """The object ids as text (one object "0" without an id column); Parquet numbers as in the pedestrian reader."""
    if "id" not in df.columns:
        return np.full(len(df), "0")
    s = df["id"]
    if kind == "parquet" and s.dtype.kind in "iu":
        return s.to_numpy().astype(str)
    if kind == "parquet" and s.dtype.kind == "f":
        v = s.to_numpy()
        return np.array([str(int(x)) if math.isfinite(x) and x.is_integer() and abs(x) < 2.0**53 else repr(float(x)) for x in v], dtype=str)
    return _stripped(s).to_numpy(dtype=str)


def _blank(df, kind: str) -> np.ndarray:
    """Rows that are blank lines (every field empty): skipped, like ``read_csv`` does."""
    if kind != "csv" or len(df) == 0:
        return np.zeros(len(df), dtype=bool)
    blank = (_stripped(df.iloc[:, 0]) == "").to_numpy(dtype=bool, copy=True)
    for c in df.columns[1:]:  # only the few rows whose first field is empty
        if not blank.any():
            break
        rows = np.flatnonzero(blank)
        blank[rows] = (_stripped(df[c].iloc[rows]) == "").to_numpy(dtype=bool)
    return blank


def _scan(df, kind: str):
    """First pass over one block, read with the id column only (or t without ids): (rows, {id: (first local
    row, rows)} as a frame). A row whose id is empty counts as blank here; the second pass, which sees every
    column, tells a blank line from a row without an id (an error)."""
    import pandas as pd

    keep = ~_blank(df, kind)
    local = np.flatnonzero(keep)
    ids = _ids(df, kind)[keep]
    table = pd.DataFrame({"id": ids, "row": local}).groupby("id", sort=False)["row"].agg(["min", "size"])
    return len(df), table


def _first_row(src: TrackSource):
    """(lat, lon) of the file's first data row, as ``read_csv`` takes the origin of its projection; (lat, lon, alt)
    with an alt column (3-D: east, north, up of the first fix)."""
    import csv

    from ..io.files import open_input

    keys = ("lat", "lon", "alt") if "alt" in src.columns else ("lat", "lon")
    if src.kind == "parquet":
        import pyarrow.dataset as pads

        head = pads.dataset(src.path, format="parquet").head(1, columns=[src.columns[k] for k in keys])
        return tuple(float(head.column(i)[0].as_py()) for i in range(len(keys)))
    with open_input(src.path, DataError) as f:
        f.readline()
        for n, line in enumerate(f, src.first_line):
            if line.strip():
                fields = line.split() if src.delimiter is None else next(csv.reader([line], delimiter=src.delimiter))
                lines = np.array([n])
                return tuple(float(parse_number_column(src.source, k, [fields[src.columns[k]] if src.columns[k] < len(fields)
                                                                       else ""], lines)[0]) for k in keys)
    raise DataError(f"{src.source}: no measurements (the file has only a header line)")


def _numbers(col, name: str, lines, source: str) -> np.ndarray:
    """float64 of a text column: Arrow's parser (correctly rounded like ``numpy.loadtxt``, and it accepts a
    subset of what loadtxt accepts: no surrounding spaces), else ``parse_number_column`` (spaces, errors)."""
    import pyarrow as pa
    import pyarrow.compute as pc

    try:
        return pc.cast(pa.array(col, type=pa.string()), pa.float64()).to_numpy(zero_copy_only=False)
    except (pa.ArrowInvalid, pa.ArrowTypeError):
        return parse_number_column(source, name, col.to_numpy(dtype=str, na_value=""), lines)


def _annotate(df, kind: str, offset: int, ranks, first_line: int, source: str):
    """Second pass over one block: numbers parsed (bad values named by line), the global row and the object rank."""
    import pandas as pd

    keep = ~_blank(df, kind)
    local = np.flatnonzero(keep)
    row = offset + local
    ids = _ids(df, kind)[keep]
    if "id" in df.columns and (ids == "").any():
        k = int(np.flatnonzero(ids == "")[0])
        raise DataError(f"{source} line {int(row[k]) + first_line}: column 'id' is empty; every row needs an object id")
    out = {"rank": ranks.reindex(ids).to_numpy(dtype=np.int64), "row": row.astype(np.int64), "id": ids}
    for k in NUMERIC:
        if k in df.columns:
            col = df[k].iloc[local]
            if kind == "csv":
                out[k] = _numbers(col, k, row + first_line, source)
            else:
                out[k] = col.to_numpy(dtype=np.float64, na_value=np.nan)
    return pd.DataFrame(out)


def _annotate_meta(src: TrackSource):
    import pandas as pd

    cols = {"rank": np.empty(0, np.int64), "row": np.empty(0, np.int64), "id": np.empty(0, dtype=str)}
    cols.update({k: np.empty(0) for k in NUMERIC if k in src.columns})
    return pd.DataFrame(cols)


@dataclass
class ObjectPlan:
    """The object table and the partitions: ``labels`` in order of first appearance, their row counts."""

    labels: list
    counts: np.ndarray
    divisions: list  # rank divisions of the partitions (len = partitions + 1)
    frame: object  # Dask dataframe of the annotated rows (before the shuffle)
    origin: tuple | None = None
    rows: int = 0

    @property
    def n_partitions(self) -> int:
        return len(self.divisions) - 1


def _divisions(counts: np.ndarray, partition_rows: int) -> list:
    """Rank boundaries so that each partition holds about ``partition_rows`` rows (whole objects)."""
    B = len(counts)
    cum = np.cumsum(counts)
    total = int(cum[-1])
    parts = max(1, math.ceil(total / partition_rows))
    starts = sorted({0, *(int(np.searchsorted(cum, k * partition_rows, side="right")) for k in range(1, parts))})
    starts = [s for s in starts if s < B]
    if len(starts) > 1 and starts[-1] == B - 1:
        starts.pop()  # the last object alone would need the division [B-1, B-1]: it joins the previous partition
    return starts + [B - 1]


def plan_partitions(client, src: TrackSource, partition_rows: int = PARTITION_ROWS) -> ObjectPlan:
    """First pass: the object table, checks of the object sizes, and the partitions' divisions.

    Raises
    ------
    DataError
        No measurements, or an object with a single measurement (the same message as ``read_csv`` +
        ``grouped``), or a bad origin row.
    """
    import pandas as pd
    from dask import delayed

    first = ["id"] if "id" in src.columns else ["t"]
    scans = client.gather(client.compute([delayed(_scan)(b, src.kind) for b in _read_frame(src, partition_rows, first).to_delayed()]))
    lengths = np.array([s[0] for s in scans], dtype=np.int64)
    offsets = np.concatenate([[0], np.cumsum(lengths)[:-1]])
    tables = []
    for (n, table), off in zip(scans, offsets):
        if len(table):
            t = table.reset_index()
            t["min"] += off
            tables.append(t)
    if not tables:
        raise DataError(f"{src.source}: no measurements (the file has only a header line)")
    objects = pd.concat(tables).groupby("id", sort=False).agg(first=("min", "min"), rows=("size", "sum"))
    objects = objects.sort_values("first", kind="stable")
    labels = objects.index.to_list()
    counts = objects["rows"].to_numpy(dtype=np.int64)
    firsts = objects["first"].to_numpy(dtype=np.int64)
    short = np.flatnonzero(counts < 2)
    if short.size:
        i = int(short[0])
        more = f" ({short.size} objects in all)" if short.size > 1 else ""
        raise DataError(f"{src.source}: object id {labels[i]} (line {int(firsts[i]) + src.first_line}) has a single measurement{more}; "
                        "at least 2 are needed to initialise its velocity")
    origin = _first_row(src) if src.projected else None
    ranks = pd.Series(np.arange(len(labels), dtype=np.int64), index=pd.Index(labels, dtype=object))
    ranks_f = client.scatter(ranks, broadcast=True)
    blocks = _read_frame(src, partition_rows).to_delayed()
    if len(blocks) != len(offsets):  # pragma: no cover - the two reads cut the same blocks
        raise RuntimeError("the two reads of the file gave different blocks")
    annotated = [delayed(_annotate)(b, src.kind, int(off), ranks_f, src.first_line, src.source) for b, off in zip(blocks, offsets)]
    import dask.dataframe as dd

    frame = dd.from_delayed(annotated, meta=_annotate_meta(src), verify_meta=False)
    return ObjectPlan(labels, counts, _divisions(counts, partition_rows), frame, origin, int(counts.sum()))


@dataclass
class PartitionResult:
    """One partition's output: CSV rows per model (no header), a sample for the unit warnings."""

    data: list
    rows: int
    objects: int
    sample: tuple = field(default=None)
    scale_error: float = 0.0


def _track_partition(df, src: TrackSource, origin, models, measure: dict, cfg, full_cov: bool, digits: int, time_unit: str,
                     use_heading: bool, monitor=None):
    """Check and track the whole objects of one partition with every model; CSV bytes per model."""
    if "rank" not in df.columns:
        df = df.reset_index()
    order = np.lexsort((df["row"].to_numpy(), df["rank"].to_numpy()))
    df = df.iloc[order]
    lines = df["row"].to_numpy(dtype=np.int64) + src.first_line
    cols = {k: df[k].to_numpy(dtype=np.float64) for k in NUMERIC if k in df.columns and (k != "heading" or use_heading)}
    if "id" in src.columns:
        cols["id"] = df["id"].to_numpy(dtype=str)
    meas = measurements_from_columns(src.source, cols, lines, use_heading, origin=origin)
    meas, starts, _ = meas.grouped(min_length=2)
    meas.t = to_seconds(meas.t, time_unit)
    data = []
    for m in models:
        buf = io.BytesIO()
        write_model(buf, m, meas, starts, cfg, full_cov, digits, None, measure[m], monitor)
        head = (",".join(output_columns(m, full_cov, meas.origin is not None)) + "\n").encode()
        b = buf.getvalue()
        assert b.startswith(head)
        data.append(b[len(head):])
    k = max(1, int(np.searchsorted(starts, SAMPLE_ROWS, side="right")) - 1)
    a = int(starts[k])
    sample = (meas.t[:a].copy(), meas.z[:a].copy(), starts[:k + 1].copy())
    err = max_scale_error(df["lat"].to_numpy(), origin[0]) if origin is not None else 0.0
    return PartitionResult(data, int(meas.t.size), meas.n_objects, sample, err)


def _concat(frames):
    import pandas as pd

    return pd.concat(frames, ignore_index=True)


def track_partitions(client, src: TrackSource, plan: ObjectPlan, models, measure: dict, cfg, full_cov: bool = False,
                     digits: int = 10, time_unit: str = "s", use_heading: bool = False, monitor=None):
    """Submit every partition and yield their ``PartitionResult``s in partition order.

    Parameters
    ----------
    client : distributed.Client
    src : TrackSource
    plan : ObjectPlan
        From ``plan_partitions``.
    models : list of str
        The models to run (each partition runs them all).
    measure : dict
        Model -> measurement (``position``/``pose``).
    cfg : TrackConfig
    full_cov, digits, time_unit, use_heading
        As for ``lgekf track``.

    Yields
    ------
    PartitionResult
        In order; a partition's ``DataError`` is raised when it is reached.
    """
    from dask import delayed

    if plan.n_partitions == 1:
        parts = [delayed(_concat)(plan.frame.to_delayed())]
    else:
        shuffled = plan.frame.set_index("rank", divisions=plan.divisions, sorted=False)
        parts = shuffled.to_delayed()
    tasks = [delayed(_track_partition)(p, src, plan.origin, list(models), dict(measure), cfg, full_cov, digits, time_unit, use_heading,
                                              monitor)
             for p in parts]
    futures = client.compute(tasks)
    try:
        for fut in futures:
            res = fut.result()
            fut.release()
            yield res
    finally:
        client.cancel(futures)
