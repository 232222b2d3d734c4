"""Reading measurement files, fast and with one clear error per bad input.

Readers
-------
* ``read_csv(path)``: a CSV file with a header line; columns ``t, x, y`` (s, m, m; also accepted:
  ``time``/``timestamp`` for t), optional ``id`` (also ``track_id``, ``object_id``) for several objects
  whose rows may be interleaved, optional ``heading`` (rad; also ``yaw``), read only when asked.
  Instead of ``x, y``: ``lat, lon`` in degrees (also ``latitude``, ``longitude``/``lng``/``long``),
  projected to metres east/north of the first row's position (``lgekf.io.geo``; the origin is kept in
  ``Measurements.origin``). A ``z`` column beside x, y (or ``alt``/``altitude`` in metres beside lat, lon) makes
  the positions 3-D (z (N, 3); lat, lon, alt: metres east, north and up of the first row's fix, ``origin`` then
  (lat0, lon0, alt0), ``lgekf.io.geo.to_local_enu``); the measured attitude of a 3-D pose is then the ``roll``,
  ``pitch`` and ``yaw`` (or ``heading``) columns, or a unit quaternion ``qw, qx, qy, qz`` (Hamilton, scalar first;
  normalised, and read as those angles: ``lgekf.io.attitude``). Ids are text, compared exactly as written (surrounding spaces removed):
  ``007`` and ``7`` are two objects. The separator is found from the header line (``,`` ``;`` tab ``|``
  or spaces) unless given. Other columns are ignored (with no id column they are listed in
  ``Measurements.unused``: ``unused_columns_warning``). Blank lines are skipped. Within ``named_columns``
  (``lgekf track --id-column NAME`` ...) the named columns replace the aliases. The t column holds numbers or
  ISO-8601 date-times (``lgekf.io.times``: seconds since the epoch, naive = UTC), as its first row says; date-times
  are read by the general reader (the fast parser takes numbers only).
* ``read_pedestrian(path, frame_dt)``: the ETH/UCY text format: whitespace separated ``frame id x y``,
  no header; t = frame * frame_dt, where ``frame_dt`` is the time per frame *unit* (ETH/UCY files step
  the frame number by 10 per sample: biwi_eth 10 frames = 0.6667 s -> frame_dt = 0.06667;
  hotel/zara/students 10 frames = 0.4 s -> frame_dt = 0.04).

Both read a path, ``-`` (stdin) or gzip data (``lgekf.io.files.open_input``) and parse with
``numpy.loadtxt`` in chunks of lines (its C parser: about 0.3 s per 10⁶ rows); only
when a chunk fails is it re-read line by line with the csv module to name the line, column and value.

``Measurements.grouped()`` sorts the rows by object (objects in order of first appearance, rows in file
order) and checks that every object has at least two measurements and strictly increasing times.

Writing: ``lgekf.io.formatting`` (numbers in numba) and ``lgekf.io.files`` (atomic output).
"""

from __future__ import annotations

import codecs
import csv
import gzip
import itertools
import math
import os
import re
import warnings
import zlib
from contextvars import ContextVar
from contextlib import contextmanager
from dataclasses import dataclass, field

import numpy as np

from . import fastcsv
from .fastcsv import group_order
from .files import is_stdio, open_input, source_name
from .attitude import MIN_QUATERNION_NORM, QUATERNION_COLUMNS, euler_of_quaternion, quaternion_norms
from .geo import to_local
from .mapped import MAP_MIN_BYTES, MappedFile, parse_mapped
from .times import ISO_HINT, IsoError, iso_seconds, looks_iso

__all__ = [
    "DataError", "Measurements", "read_csv", "read_pedestrian", "read_measurements", "parse_delimiter",
    "measurements_from_columns", "parse_number_column", "csv_header", "header_keys", "skipping_nonfinite_rows",
    "named_columns", "COLUMN_OPTIONS", "unused_columns_warning",
]

CHUNK_LINES = 1 << 18

COLUMN_ALIASES = {
    "t": ("t", "time", "timestamp"),
    "x": ("x",),
    "y": ("y",),
    "id": ("id", "track_id", "object_id"),
    "heading": ("heading", "yaw"),
    "lat": ("lat", "latitude"),
    "lon": ("lon", "lng", "long", "longitude"),
    "z": ("z",),
    "alt": ("alt", "altitude"),
    "roll": ("roll",),
    "pitch": ("pitch",),
    "qw": ("qw",),
    "qx": ("qx",),
    "qy": ("qy",),
    "qz": ("qz",),
}
#: the vertical coordinate of each horizontal pair: a file with it holds 3-D positions (x, y, z or lat, lon, alt)
VERTICAL = {"x": "z", "lat": "alt"}
# the options naming a column (``lgekf track --id-column NAME`` ...): key -> option
COLUMN_OPTIONS = {"id": "--id-column", "t": "--time-column", "x": "--x-column", "y": "--y-column", "z": "--z-column",
                  "heading": "--heading-column"}
# separators tried on the header line, in this order (None: runs of spaces/tabs)
AUTO_DELIMITERS = (",", ";", "\t", "|", None)
DELIMITER_NAMES = {"tab": "\t", "\\t": "\t", "space": None, "whitespace": None, "comma": ",", "semicolon": ";"}


class DataError(ValueError):
    """Bad input data: the message names the file, line and column where possible."""


@dataclass
class Measurements:
    """Rows of a measurement file (in file order).

    t (N,), z (N, 2) (or (N, 3) from a z or alt column: 3-D space), heading (N,) (in 3-D (N, 3): roll, pitch, yaw)
    or None; obj (N,) object index per row, objects numbered in order of
    first appearance; labels[i] the text of object i's id (as written in the output);
    line (N,) int64, the 1-based line number of each row in ``source`` (header = line 1; a table's row number counted
    from 1 when ``line_word`` is "row"), kept through sorting, cleaning and grouping for messages; extra: other
    numeric columns asked for (name -> (N,)); origin: (lat0, lon0) in degrees when z was projected
    from lat, lon columns (``lgekf.io.geo.to_local``; (lat0, lon0, alt0) with an alt column), else None.
    """

    t: np.ndarray
    z: np.ndarray
    heading: np.ndarray | None
    obj: np.ndarray
    labels: list
    line: np.ndarray
    source: str
    extra: dict = field(default_factory=dict)
    origin: tuple | None = None
    skipped: dict = field(default_factory=dict)  # reason -> line numbers of rows dropped while reading (--skip-invalid)
    unused: tuple = ()  # no id column was found: the header's columns that were not read (named in a warning)
    time_iso: bool = False  # t was read from ISO-8601 date-times (seconds since the epoch)
    line_word: str = "line"  # what ``line`` counts: "line" of a text file (header = line 1), "row" of a table (from 1)
    quaternion: bool = False  # the 3-D attitude was read from qw, qx, qy, qz (``lgekf.io.attitude``): radians by construction

    def where(self, k: int) -> str:
        """Where row k (an index into these rows) came from: ``line 1234`` (or ``row 1233`` of a table); "" without
        line numbers."""
        if self.line is None:
            return ""
        return f"{self.line_word} {int(self.line[k])}"

    @property
    def n_objects(self) -> int:
        return len(self.labels)

    def grouped(self, min_length: int = 2, drop_short: bool = False):
        """Rows sorted by object: returns (Measurements sorted, starts (n_obj + 1,), dropped labels).

        Objects with fewer than ``min_length`` measurements are an error unless ``drop_short``
        (then they are removed and listed). Times must increase strictly within each object.
        """
        order, counts = group_order(np.ascontiguousarray(self.obj, dtype=np.int64), self.n_objects)  # argsort(obj, stable)
        obj = self.obj[order]
        short = np.flatnonzero(counts < min_length)
        dropped = []
        if short.size:
            if not drop_short:
                i = int(short[0])
                first = int(self.line[np.flatnonzero(self.obj == i)[0]])
                what = "a single measurement" if counts[i] == 1 else f"only {counts[i]} measurements"
                more = f" ({short.size} objects in all)" if short.size > 1 else ""
                raise DataError(
                    f"{self.source}: object id {self.labels[i]} (line {first}) has {what}{more}; "
                    f"at least {min_length} are needed to initialise its velocity (--skip-invalid drops such objects)"
                )
            keep_obj = np.ones(self.n_objects, bool)
            keep_obj[short] = False
            dropped = [self.labels[i] for i in short]
            keep_rows = keep_obj[obj]
            order = order[keep_rows]
            obj = obj[keep_rows]
            new_index = np.cumsum(keep_obj) - 1
            obj = new_index[obj]
            labels = [lab for lab, k in zip(self.labels, keep_obj) if k]
            counts = counts[keep_obj]
        else:
            labels = list(self.labels)
        t = self.t[order]
        starts = np.zeros(len(labels) + 1, dtype=np.int64)
        np.cumsum(counts, out=starts[1:])
        if t.size > 1:
            bad = np.diff(t) <= 0
            bad[starts[1:-1] - 1] = False  # steps between objects do not count
            if bad.any():
                k = int(np.flatnonzero(bad)[0])
                o = int(obj[k])
                raise DataError(
                    f"{self.source} line {int(self.line[order[k + 1]])}: time is not increasing within object id {labels[o]} "
                    f"(t = {float(t[k + 1])!r} after t = {float(t[k])!r} on line {int(self.line[order[k]])}); "
                    "each object's rows must be in strictly increasing time (--sort sorts them, --skip-invalid drops repeated "
                    "times)"
                )
        out = Measurements(
            t, self.z[order], None if self.heading is None else self.heading[order], obj, labels,
            self.line[order], self.source, {k: v[order] for k, v in self.extra.items()}, self.origin,
            unused=self.unused, time_iso=self.time_iso, line_word=self.line_word, quaternion=self.quaternion,
        )
        return out, starts, dropped


# ----------------------------------------------------------------------------------- parsing
@contextmanager
def _reading(source):
    """Turn decoding and decompression failures while reading into one-line DataErrors."""
    try:
        yield
    except UnicodeDecodeError:
        raise DataError(f"{source}: not a text file (cannot decode as UTF-8)") from None
    except (gzip.BadGzipFile, EOFError, zlib.error) as e:
        raise DataError(f"{source}: damaged or truncated gzip data ({e})") from None


def parse_delimiter(text):
    """The separator of a ``--delimiter`` value.

    Parameters
    ----------
    text : str or None
        One character, or ``tab``, ``space`` (runs of whitespace), ``comma``, ``semicolon``; None when
        the option was not given.

    Returns
    -------
    str or None
        The character, None for whitespace, or ``"auto"`` (found from the header line) for None.
    """
    if text is None:
        return "auto"
    key = str(text)
    if key.lower() in DELIMITER_NAMES:
        return DELIMITER_NAMES[key.lower()]
    if len(key) != 1 or key in '"\n\r':
        raise DataError(f"--delimiter: expected one character or tab, space, comma, semicolon; got {text!r}")
    return None if key == " " else key


def _loadtxt(lines, delimiter, usecols, dtype=float):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # "input contained no data"
        return np.loadtxt(
            lines, delimiter=delimiter, usecols=usecols, dtype=dtype, comments=None, ndmin=2 if dtype is float else 1,
            quotechar='"' if delimiter is not None else None,
        )


def _split(line: str, delimiter):
    if delimiter is not None:
        return next(csv.reader([line], delimiter=delimiter), [])
    return line.split()


_DECIMAL_COMMA = re.compile(r"^[-+]?\d*,\d+$")


def _diagnose(source, lines, first_line, delimiter, usecols, colnames, numeric):
    """Find the first bad line of a chunk that numpy refused; raise a DataError naming it."""
    need = max(usecols) + 1
    for i, line in enumerate(lines):
        if not line.strip():
            continue
        fields = _split(line, delimiter)
        where = f"{source} line {first_line + i}"
        if len(fields) < need:
            raise DataError(f"{where}: expected at least {need} columns, got {len(fields)}")
        for c, name in zip(usecols, colnames):
            if not numeric.get(name, True):
                continue
            v = fields[c].strip()
            try:
                float(v)
            except ValueError:
                shown = v if v else "(empty)"
                hint = " (a decimal comma? write numbers with a decimal point)" if _DECIMAL_COMMA.match(v) else ""
                if name == "t" and not hint:
                    hint = f"; {ISO_HINT}"
                raise DataError(f"{where}: column {name!r}: {shown!r} is not a number{hint}") from None
    return None


def _parse_lines(source, lines, first_line, delimiter, usecols, colnames, str_cols=()):
    """Parse one chunk: float columns (rows, len(usecols)) and the line number of every row.

    ``str_cols``: names among ``colnames`` read as text instead (returned in a dict).
    """
    num_idx = [c for c, n in zip(usecols, colnames) if n not in str_cols]
    num_names = [n for n in colnames if n not in str_cols]
    rowlines = None
    try:
        arr = _loadtxt(lines, delimiter, num_idx)
    except ValueError:
        # retry without whitespace-only lines (numpy reads them as a one-column row)
        keep = [i for i, s in enumerate(lines) if s.strip()]
        sub = [lines[i] for i in keep]
        try:
            arr = _loadtxt(sub, delimiter, num_idx)
        except ValueError as e:
            _diagnose(source, lines, first_line, delimiter, usecols, colnames, {n: n not in str_cols for n in colnames})
            raise DataError(f"{source}: cannot parse lines {first_line}-{first_line + len(lines) - 1}: {e}") from None
        lines = sub
        rowlines = first_line + np.asarray(keep, dtype=np.int64)
    if arr.shape[0] == 0:
        arr = arr.reshape(0, len(num_idx))
    if rowlines is None:
        if arr.shape[0] == len(lines):
            rowlines = first_line + np.arange(len(lines), dtype=np.int64)
        else:  # empty lines were skipped by numpy
            rowlines = first_line + np.asarray([i for i, s in enumerate(lines) if s.strip()], dtype=np.int64)
    texts = {}
    for name in str_cols:
        c = usecols[colnames.index(name)]
        sub = [s for s in lines if s.strip()]
        try:
            col = _loadtxt(sub, delimiter, [c], dtype=str)
        except ValueError as e:
            _diagnose(source, lines, first_line, delimiter, usecols, colnames, {n: False for n in colnames})
            raise DataError(f"{source}: cannot parse lines {first_line}-{first_line + len(lines) - 1}: {e}") from None
        texts[name] = np.char.strip(np.atleast_1d(col).astype(str))
    return {n: arr[:, i] for i, n in enumerate(num_names)}, texts, rowlines


def _read_chunks(source, f, first_line, delimiter, usecols, colnames, str_cols=()):
    cols = {n: [] for n in colnames if n not in str_cols}
    texts = {n: [] for n in str_cols}
    lines_no = []
    line = first_line
    while True:
        lines = list(itertools.islice(f, CHUNK_LINES))
        if not lines:
            break
        num, txt, rl = _parse_lines(source, lines, line, delimiter, usecols, colnames, str_cols)
        for n in cols:
            cols[n].append(num[n])
        for n in texts:
            texts[n].append(txt[n])
        lines_no.append(rl)
        line += len(lines)
    cat = {n: np.concatenate(v) if v else np.empty(0) for n, v in cols.items()}
    cat.update({n: np.concatenate(v) if v else np.empty(0, dtype=str) for n, v in texts.items()})
    return cat, (np.concatenate(lines_no) if lines_no else np.empty(0, dtype=np.int64))


#: ``skipping_nonfinite_rows``: whether a row with a NaN or infinite number is dropped (recorded) instead of refused
_SKIP_NONFINITE: ContextVar[bool] = ContextVar("skip_nonfinite", default=False)


@contextmanager
def skipping_nonfinite_rows(skip: bool = True):
    """Within the block, the readers drop rows with a NaN or infinite number (``lgekf track --skip-invalid``) and
    record them in ``Measurements.skipped["non-finite"]`` (their line numbers) instead of refusing the file."""
    token = _SKIP_NONFINITE.set(bool(skip))
    try:
        yield
    finally:
        _SKIP_NONFINITE.reset(token)


def _check_finite(source, cols: dict, lines, names, line_word: str = "line"):
    """None when every number of the columns ``names`` is finite; else, within ``skipping_nonfinite_rows``, the mask
    of the rows to keep, and outside it one DataError naming the first bad line and column."""
    bad_rows = None
    for name in names:
        a = cols[name]
        bad = ~np.isfinite(a)
        if bad.any():
            if not _SKIP_NONFINITE.get():
                k = int(np.flatnonzero(bad)[0])
                raise DataError(
                    f"{source} {line_word} {int(lines[k])}: column {name!r} is {float(a[k])!r}; NaN and infinite values are not "
                    "allowed (--skip-invalid drops such rows)"
                )
            bad_rows = bad if bad_rows is None else bad_rows | bad
    return None if bad_rows is None else ~bad_rows


def _number_label(v: float) -> str:
    if v.is_integer() and abs(v) < 2.0**53:
        return str(int(v))
    return repr(v)


def _objects_from_numbers(ids: np.ndarray):
    uniq, first, inv = np.unique(ids, return_index=True, return_inverse=True)
    rank = np.empty(len(uniq), dtype=np.int64)
    rank[np.argsort(first, kind="stable")] = np.arange(len(uniq))
    labels = [None] * len(uniq)
    for u, rnk in zip(uniq.tolist(), rank.tolist()):
        labels[rnk] = _number_label(float(u))
    return rank[inv.ravel()], labels


def _objects_from_texts(ids: np.ndarray):
    uniq, first, inv = np.unique(ids, return_index=True, return_inverse=True)
    rank = np.empty(len(uniq), dtype=np.int64)
    rank[np.argsort(first, kind="stable")] = np.arange(len(uniq))
    labels = [None] * len(uniq)
    for u, rnk in zip(uniq.tolist(), rank.tolist()):
        labels[rnk] = str(u)
    return rank[inv.ravel()], labels


#: ``named_columns``: key (id, t, x, y, heading) -> the column's name given by the user (--id-column ...)
_COLUMN_NAMES: ContextVar[dict] = ContextVar("column_names", default={})


@contextmanager
def named_columns(names: dict | None = None):
    """Within the block, the readers take the columns named here instead of the automatic aliases
    (``COLUMN_ALIASES``).

    Parameters
    ----------
    names : dict, optional
        Key (``id``, ``t``, ``x``, ``y``, ``heading``) -> column name (compared without surrounding spaces, any
        case); None values are ignored. A named column absent from a header is one ``DataError`` listing the
        header's columns.
    """
    given = {k: str(v).strip() for k, v in (names or {}).items() if v is not None}
    for k in given:
        if k not in COLUMN_OPTIONS:
            raise ValueError(f"named_columns: unknown key {k!r}; choose among {', '.join(COLUMN_OPTIONS)}")
    token = _COLUMN_NAMES.set(given)
    try:
        yield
    finally:
        _COLUMN_NAMES.reset(token)


def _named(source, header, strict: bool = True) -> dict:
    """{key: column index} of the columns named by ``named_columns``; a DataError for a name the header lacks
    (``strict``; else that key is left out)."""
    names = [h.strip().lower() for h in header]
    where = {}
    for key, name in _COLUMN_NAMES.get().items():
        if name.lower() in names:
            where[key] = names.index(name.lower())
        elif strict:
            shown = ", ".join(h.strip() for h in header) or "(nothing)"
            raise DataError(f"{source}: {COLUMN_OPTIONS[key]} {name}: no such column; the header has: {shown}")
    return where


def _find_columns(header, source=None):
    """{key: column index} for the known columns of a header (None if a key matches twice); the columns named by
    ``named_columns`` take their key (``source`` given: a named column that is missing is a DataError)."""
    names = [h.strip().lower() for h in header]
    where = _named(source, header, strict=source is not None)
    taken = set(where.values())
    twice = {}
    for key, aliases in COLUMN_ALIASES.items():
        if key in where or (key in ("lat", "lon") and "x" in where and "y" in where):
            continue
        hits = [i for i, n in enumerate(names) if n in aliases and i not in taken]
        if len(hits) > 1:
            twice[key] = hits
        if hits:
            where[key] = hits[0]
    return where, twice


def _usable(where) -> bool:
    return "t" in where and (("x" in where and "y" in where) or ("lat" in where and "lon" in where))


def _choose_delimiter(first: str, delimiter):
    """The separator and header fields: ``delimiter`` if given, else the first of ``AUTO_DELIMITERS``
    that splits the header into usable columns (',' when none does)."""
    if delimiter != "auto":
        return delimiter, _split(first, delimiter)
    for d in AUTO_DELIMITERS:
        header = _split(first, d)
        if _usable(_find_columns(header)[0]) and len(_named(None, header, strict=False)) == len(_COLUMN_NAMES.get()):
            return d, header
    return ",", _split(first, ",")



def _resolve_columns(source, header, want_heading, auto):
    """{key: column index}; x, y when present, else lat, lon (degrees). Raises a DataError naming what is missing."""
    where, twice = _find_columns(header, source)
    for key, hits in twice.items():
        if key in ("lat", "lon") and "x" in where and "y" in where:
            continue  # not read
        raise DataError(f"{source}: header has more than one column for {key!r}: {', '.join(header[i].strip() for i in hits)}")
    if "x" in where and "y" in where:
        where.pop("lat", None)
        where.pop("lon", None)
        where.pop("alt", None)
    elif "lat" in where and "lon" in where:
        where.pop("x", None)
        where.pop("y", None)
        if "alt" in where:  # lat, lon, alt: the altitude is the vertical (a z column beside them is not read)
            where.pop("z", None)
        elif "z" in where:
            where["alt"] = where.pop("z")
    missing = [k for k in ("t",) if k not in where]
    if not (("x" in where and "y" in where) or ("lat" in where and "lon" in where)):
        pair = ("lat", "lon") if ("lat" in where or "lon" in where) and not ("x" in where or "y" in where) else ("x", "y")
        missing += [k for k in pair if k not in where]
    if missing:
        shown = ", ".join(h.strip() for h in header) or "(nothing)"
        hint = ""
        try:
            [float(h) for h in header if h.strip()]
            hint = " (the first line looks like data: the file needs a header line)"
        except ValueError:
            if auto and len(header) == 1 and re.search(r"[^\w\s]", header[0].strip()):
                hint = " (if the columns are separated by something other than , ; tab | or spaces, give --delimiter)"
        raise DataError(
            f"{source}: missing column{'s' if len(missing) > 1 else ''} {', '.join(repr(m) for m in missing)}; "
            f"the header has: {shown}{hint}; expected t, x, y (or t, lat, lon in degrees) and optionally id, heading"
        )
    pose3 = want_heading and ("z" in where or "alt" in where)
    if pose3:  # 3-D positions: the attitude is roll, pitch, yaw, or a quaternion qw, qx, qy, qz (``lgekf.io.attitude``)
        _attitude_columns(source, header, where)
    elif want_heading and "heading" not in where:
        raise DataError(f"{source}: --use-heading needs a 'heading' column (rad, or --heading-column NAME); the header has: "
                        f"{', '.join(h.strip() for h in header)}")
    if not pose3:
        for k in ("roll", "pitch", *QUATERNION_COLUMNS):
            where.pop(k, None)
    return where


def _attitude_columns(source, header, where) -> None:
    """The attitude of a 3-D pose among the columns ``where``: roll, pitch and yaw (or heading), or the quaternion
    qw, qx, qy, qz; the columns of the other kind dropped. A DataError when neither is complete, or both are."""
    euler = [k for k in ("roll", "pitch", "heading") if k in where]
    quat = [k for k in QUATERNION_COLUMNS if k in where]
    shown = ", ".join(h.strip() for h in header)
    if len(euler) == 3 and len(quat) == 4:
        raise DataError(f"{source}: the attitude is given twice, as roll, pitch, yaw and as qw, qx, qy, qz; keep one kind "
                        f"of column (the header has: {shown})")
    if len(quat) == 4:
        for k in euler:
            where.pop(k)
        return
    if len(euler) == 3:
        for k in quat:
            where.pop(k)
        return
    if quat:
        missing = [k for k in QUATERNION_COLUMNS if k not in where]
        raise DataError(f"{source}: a quaternion attitude needs the columns qw, qx, qy, qz; missing "
                        f"{', '.join(repr(m) for m in missing)}; the header has: {shown}")
    missing = [k for k in ("roll", "pitch", "heading") if k not in where]
    raise DataError(f"{source}: a pose in 3-D needs roll, pitch and yaw (or heading) columns (rad), or a quaternion qw, qx, qy, "
                    f"qz; missing {', '.join(repr('yaw' if m == 'heading' else m) for m in missing)}; the header has: {shown}")


def _unused(header, keys: dict, extra=()) -> tuple:
    """When ``keys`` has no id: the header's columns that are neither read nor a known column name (else ())."""
    if "id" in keys:
        return ()
    known = {a for aliases in COLUMN_ALIASES.values() for a in aliases} | {e.lower() for e in extra}
    used = set(keys.values())
    return tuple(h.strip() for i, h in enumerate(header) if i not in used and h.strip() and h.strip().lower() not in known)


def unused_columns_warning(meas) -> str | None:
    """The warning for a file read as one object while its header has columns that were not read (one of them may
    name the objects: ``--id-column``), else None."""
    if not meas.unused or meas.n_objects != 1:
        return None
    shown = ", ".join(repr(c) for c in meas.unused[:8]) + (", ..." if len(meas.unused) > 8 else "")
    return (f"no id column (id, track_id, object_id): all {meas.t.size} rows are read as one object; column"
            f"{'s' if len(meas.unused) > 1 else ''} not used: {shown}; if one of them names the objects, give --id-column NAME")


def _check_ids(source, ids, lines):
    empty = ids == ""
    if empty.any():
        k = int(np.flatnonzero(empty)[0])
        raise DataError(f"{source} line {int(lines[k])}: column 'id' is empty; every row needs an object id")


def _check_degrees(source, cols, lines):
    for name, lo, hi in (("lat", -90.0, 90.0), ("lon", -180.0, 360.0)):
        a = cols[name]
        bad = (a < lo) | (a > hi)
        if bad.any():
            k = int(np.flatnonzero(bad)[0])
            raise DataError(f"{source} line {int(lines[k])}: column {name!r} is {float(a[k])!r}, not in [{lo:g}, {hi:g}] degrees")


def header_keys(source, names, use_heading: bool = False, auto: bool = False) -> dict:
    """The columns lgekf reads among a header's names (aliases as in ``read_csv``).

    Parameters
    ----------
    source : str
        The file's name in messages.
    names : sequence of str
        The header (a CSV's fields, a Parquet file's column names).
    use_heading : bool
        The ``heading`` column is needed (an error when there is none).
    auto : bool
        The separator was guessed (adds a hint to the message about missing columns).

    Returns
    -------
    dict
        Key (``t``, ``x``, ``y`` or ``lat``, ``lon``, ``id``, ``heading``) -> index in ``names``.
    """
    where = _resolve_columns(source, list(names), use_heading, auto)
    return {k: where[k] for k in ("t", "x", "y", "z", "lat", "lon", "alt", "id", "roll", "pitch", "heading", *QUATERNION_COLUMNS)
            if k in where and (k != "heading" or use_heading)}


def _header_columns(source, first: str, use_heading: bool, extra, delimiter):
    """(separator, column keys, their indices) from a CSV's header line."""
    if not first.strip():
        raise DataError(f"{source}: empty file; expected a header line with columns t, x, y (and optionally id)")
    delim, header = _choose_delimiter(first.rstrip("\r\n"), delimiter)
    keys = header_keys(source, header, use_heading, delimiter == "auto")
    colnames, usecols = list(keys), list(keys.values())
    lower = [h.strip().lower() for h in header]
    for name in extra:
        if name in lower and name not in colnames:
            colnames.append(name)
            usecols.append(lower.index(name))
    return delim, colnames, usecols, _unused(header, keys, extra)


def csv_header(path, use_heading: bool = False, delimiter="auto"):
    """What ``read_csv`` finds in a file's header line, without reading the rest.

    Parameters
    ----------
    path : str or Path
        A file (plain or gzip-compressed).
    use_heading : bool
        The ``heading`` column is needed (an error when there is none).
    delimiter : str or None, optional
        As for ``read_csv``.

    Returns
    -------
    delimiter : str or None
        The separator (None: runs of whitespace).
    columns : dict
        Column key (``t``, ``x``, ``y`` or ``lat``, ``lon``, ``id``, ``heading``) -> index in the line.
    gzip : bool
        The file is gzip-compressed.
    """
    source = source_name(path)
    with open_input(path, DataError) as f, _reading(source):
        delim, colnames, usecols, _ = _header_columns(source, f.readline(), use_heading, (), delimiter)
    with open(path, "rb") as raw:
        gz = raw.read(2) == b"\x1f\x8b"
    return delim, dict(zip(colnames, usecols)), gz


def read_csv(path, use_heading: bool = False, extra=(), delimiter="auto") -> Measurements:
    """Read a ``t, x, y[, id][, heading]`` (or ``t, lat, lon, ...``) file with a header line.

    Parameters
    ----------
    path : str or Path
        A file (plain or gzip-compressed) or ``-`` for stdin.
    use_heading : bool
        Read the ``heading`` column (an error when there is none).
    extra : sequence of str
        Further numeric columns to read when the header has them (e.g. ``vx, vy``), in ``Measurements.extra``.
    delimiter : str or None, optional
        The separator (None: runs of whitespace); ``"auto"`` (default) finds it from the header line.

    Returns
    -------
    Measurements
        In file order. Ids are the text of the ``id`` column (surrounding spaces removed), so
        ``007`` and ``7`` are different objects; lat, lon are projected to metres (``origin`` set).
    """
    source = source_name(path)
    fast = _read_csv_fast(path, source, use_heading, extra, delimiter)
    if fast is not None:
        return fast
    with open_input(path, DataError) as f, _reading(source):
        delim, colnames, usecols, unused = _header_columns(source, f.readline(), use_heading, extra, delimiter)
        str_cols = ("id",) if "id" in colnames else ()
        head = []  # the first line with data decides whether t holds numbers or ISO-8601 date-times
        for line in f:
            head.append(line)
            if line.strip():
                fields = _split(line, delim)
                tc = usecols[colnames.index("t")]
                if tc < len(fields) and _iso_not_number(fields[tc]):
                    str_cols = (*str_cols, "t")
                break
        cols, lines = _read_chunks(source, itertools.chain(head, f), 2, delim, usecols, colnames, str_cols)
    if lines.size == 0:
        raise DataError(f"{source}: no measurements (the file has only a header line)")
    return measurements_from_columns(source, cols, lines, use_heading, extra=[n for n in extra if n in cols], unused=unused)


def _iso_not_number(text: str) -> bool:
    """A t value that is no number but starts like an ISO-8601 date."""
    try:
        float(text)
        return False
    except ValueError:
        return looks_iso(text)


def _read_csv_fast(path, source, use_heading, extra, delimiter):
    """``read_csv`` by the numba parser (``lgekf.io.fastcsv``) of a whole file's bytes, or None when the
    general reader must read it (stdin, anything the fast path does not take, any bad input: the general
    reader then names the line and column in its message)."""
    if is_stdio(path) or not os.path.isfile(path):  # a pipe (/dev/stdin, <(...)) cannot be read a second time
        return None
    if not fastcsv.compiled():  # a cold numba cache: the general reader now, and for a file large enough for the
        if os.path.getsize(path) >= fastcsv.COMPILE_MIN_BYTES:  # parser to pay off, it compiles for next time
            fastcsv.compile_in_background()
        return None
    mapped = None
    try:
        if os.path.getsize(path) >= MAP_MIN_BYTES:  # a large file: mapped and parsed in segments (lgekf.io.mapped)
            mapped = MappedFile(path)
            if mapped.data[:2] == b"\x1f\x8b":
                mapped.close()
                mapped = None
        if mapped is None:
            with open(path, "rb") as raw:
                data = raw.read()
            if data[:2] == b"\x1f\x8b":
                data = gzip.decompress(data)
        else:
            data = mapped.data
    except (OSError, EOFError, zlib.error, ValueError):
        return None
    held = [data]  # handed over: _parse_fast drops the bytes as soon as they are parsed
    del data
    try:
        return _parse_fast(source, held, mapped, use_heading, extra, delimiter)
    finally:
        if mapped is not None:
            mapped.close()


def _parse_fast(source, held, mapped, use_heading, extra, delimiter):
    """The rest of ``_read_csv_fast`` on the file's bytes ``held[0]`` (taken out of the list; ``mapped``: the
    ``MappedFile`` they are, else None)."""
    data = held.pop()
    off = 3 if data[:3] == b"\xef\xbb\xbf" else 0
    nl = data.find(b"\n", off)
    if nl < 0:
        return None  # no body
    head = data[off:nl]
    try:
        first = (head[:-1] if head.endswith(b"\r") else head).decode("utf-8")
        if "\r" in first:
            return None
        delim, colnames, usecols, unused = _header_columns(source, first, use_heading, extra, delimiter)
    except (UnicodeDecodeError, DataError):
        return None
    if delim not in fastcsv.FAST_DELIMITERS:
        return None
    num = [(n, c) for n, c in zip(colnames, usecols) if n != "id"]
    idcol = usecols[colnames.index("id")] if "id" in colnames else -1
    if mapped is not None:
        status, vals, lines, obj, lab, hard, nonascii = parse_mapped(mapped, nl + 1, -1 if delim is None else ord(delim),
                                                                     [c for _, c in num], idcol, 2)
    else:
        status, vals, lines, obj, lab, hard, nonascii = fastcsv.parse(data, nl + 1, -1 if delim is None else ord(delim),
                                                                     [c for _, c in num], idcol, 2)
    if status != fastcsv.OK or lines.size == 0:
        return None
    if nonascii and not _is_utf8(data):
        return None
    if hard.shape[0]:  # beyond the exact fast path: numpy's correctly rounded parser, all at once
        vals[hard[:, 1], hard[:, 0]] = fastcsv.hard_values(data, hard)
    if idcol >= 0:
        labels = [data[a:b].decode("utf-8") for a, b in lab.tolist()]
        if any(lb != lb.strip() for lb in labels):  # other whitespace than spaces/tabs around an id
            return None
    else:
        labels = ["0"]
    if mapped is not None:  # the pages the ids and hard numbers were read from again
        mapped.release(0, len(mapped))
    del data  # the file's bytes are no longer needed: less peak memory for what follows (the caller unmaps a mapped file)
    names = [n for n, _ in num]
    z = None
    if "x" in names and "y" in names and vals.flags.c_contiguous:
        other = {n: vals[:, i].copy() for i, n in enumerate(names) if n not in ("x", "y")}  # copies: vals's buffer is resized
        z = _positions_in_place(vals, names.index("x"), names.index("y"))  # vals's buffer reused: no second copy
        cols = {n: z[:, 0] if n == "x" else z[:, 1] if n == "y" else other[n] for n in names}  # in the header's order
        del other
    else:
        cols = {n: np.ascontiguousarray(vals[:, i]) for i, n in enumerate(names)}
    del vals
    return measurements_from_columns(source, cols, lines, use_heading, extra=[n for n in extra if n in cols], objects=(obj, labels),
                                     positions=z, unused=unused)


def _positions_in_place(vals, ix: int, iy: int, block: int = 1 << 16):
    """Columns ix, iy of the C-contiguous rows ``vals`` (N, k >= 2) as an (N, 2) array in the first 2N numbers of
    ``vals``'s own buffer, which is then shrunk to them when NumPy owns it and ``vals`` starts it
    (``ndarray.resize``: ``realloc``, the rest of the buffer returned; otherwise, or for N = 0, a view of the first
    2N numbers). Take the other columns out first, as copies, and use no view of ``vals`` afterwards.

    Row r's pair goes to numbers 2r, 2r + 1, never after row r's own place (k r), so copying a block of rows at a
    time, in order (each block taken out before it is written), never overwrites a row not yet moved.
    """
    n = vals.shape[0]
    flat = vals.reshape(-1)  # a view: vals is C-contiguous
    for r0 in range(0, n, block):
        r1 = min(r0 + block, n)
        flat[2 * r0:2 * r1] = vals[r0:r1][:, [ix, iy]].reshape(-1)
    owner = vals if vals.base is None else vals.base
    if n and owner.base is None and owner.flags.owndata and owner.flags.c_contiguous and owner.ctypes.data == vals.ctypes.data:
        del flat
        owner.resize((n, 2), refcheck=False)  # the first 2N numbers kept, the other columns' third returned
        return owner
    return flat[:2 * n].reshape(n, 2)


def _is_utf8(data) -> bool:
    """Whether bytes (or a mapped file) decode as UTF-8, checked a few MB at a time (no decoded copy of a file)."""
    dec = codecs.getincrementaldecoder("utf-8")()
    step = 1 << 22
    try:
        for a in range(0, len(data), step):
            dec.decode(data[a:a + step])
        dec.decode(b"", final=True)
    except UnicodeDecodeError:
        return False
    return True


def measurements_from_columns(source, cols: dict, lines, use_heading: bool = False, origin=None, extra=(),
                              objects=None, positions=None, unused=(), line_word: str = "line") -> Measurements:
    """Check parsed columns and assemble them into ``Measurements`` (the last step of ``read_csv``).

    Parameters
    ----------
    source : str
        The file's name in messages.
    cols : dict
        Column key (``t``, ``x``, ``y`` or ``lat``, ``lon``, optional ``id`` (text), ``heading`` and the
        ``extra`` names) -> array, one entry per row.
    lines : ndarray of int
        The line number of every row (named in messages).
    use_heading : bool
        Keep the ``heading`` column.
    origin : tuple of float, optional
        (lat0, lon0) of the projection of lat, lon (default: the first row's).
    extra : sequence of str
        Further numeric columns, kept in ``Measurements.extra``.
    objects : tuple, optional
        (object index per row, labels) already found (``read_csv``'s fast path); ``cols`` then has no ``id``.
    positions : ndarray, optional
        (N, 2): ``cols["x"]``, ``cols["y"]`` side by side, used as the positions instead of a stacked copy
        (``read_csv``'s fast path, where they are its two columns).
    unused : tuple of str
        The header's columns not read when there is no id column (``Measurements.unused``).
    line_word : str
        ``"line"`` (a text file, header = line 1) or ``"row"`` (a table's row, from 1), in messages.

    ``cols["t"]`` may be text: ISO-8601 date-times (``lgekf.io.times``), converted to seconds since the epoch
    (``Measurements.time_iso``); a value that is not one is a DataError naming its line.

    Returns
    -------
    Measurements
        Objects numbered in order of first appearance among these rows.
    """
    time_iso = cols["t"].dtype.kind in "UO"
    if time_iso:
        try:
            cols = {**cols, "t": iso_seconds(cols["t"])}
        except IsoError as e:
            shown = e.value if e.value else "(empty)"
            raise DataError(f"{source} {line_word} {int(lines[e.index])}: column 't': {shown!r} is neither a number nor an "
                            f"ISO-8601 date-time; {ISO_HINT}") from None
    keep = _check_finite(source, cols, lines, [n for n in cols if n != "id"], line_word)
    skipped = {}
    if keep is not None:  # skipping_nonfinite_rows: the rows with a NaN or infinite number dropped
        skipped["non-finite"] = lines[~keep].tolist()
        cols = {n: v[keep] for n, v in cols.items()}
        lines = lines[keep]
        positions = None if positions is None else positions[keep]
        if objects is not None:
            objects = (objects[0][keep], objects[1])
        if lines.size == 0:
            raise DataError(f"{source}: no measurements with finite numbers")
    if objects is not None:
        obj, labels = objects
    elif "id" in cols:
        _check_ids(source, cols["id"], lines)
        obj, labels = _objects_from_texts(cols["id"])
    else:
        obj, labels = np.zeros(lines.size, dtype=np.int64), ["0"]
    vertical = cols.get("alt" if "lat" in cols else "z")
    if "lat" in cols:
        _check_degrees(source, cols, lines)
        if origin is None:
            origin = (float(cols["lat"][0]), float(cols["lon"][0])) + (() if vertical is None else (float(vertical[0]),))
        try:
            x, y = to_local(cols["lat"], cols["lon"], *origin[:2])
        except ValueError as e:
            raise DataError(f"{source} line {int(lines[0])}: {e}") from None
        # lat, lon, alt: east, north, up of the first fix (``lgekf.io.geo.to_local_enu``)
        z = np.column_stack([x, y] if vertical is None else [x, y, vertical - origin[2]])
    else:
        origin = None
        if vertical is not None:
            z = np.column_stack([cols["x"], cols["y"], vertical] if positions is None else [positions, vertical])
        else:
            z = np.column_stack([cols["x"], cols["y"]]) if positions is None else positions
    heading = cols.get("heading") if use_heading else None
    if heading is not None and vertical is not None:  # 3-D: the attitude (roll, pitch, yaw), Z-Y-X Euler angles
        heading = np.column_stack([cols["roll"], cols["pitch"], heading])
    elif use_heading and vertical is not None and "qw" in cols:  # ... or of a quaternion (``lgekf.io.attitude``)
        heading = _quaternion_attitude(source, cols, lines, line_word)
    ext = {n: cols[n] for n in extra if n in cols}
    return Measurements(cols["t"], z, heading, obj, labels, lines, source, ext, origin,
                        skipped=skipped, unused=tuple(unused), time_iso=time_iso, line_word=line_word,
                        quaternion=use_heading and vertical is not None and "qw" in cols)


def _quaternion_attitude(source, cols, lines, line_word) -> np.ndarray:
    """roll, pitch, yaw (N, 3) of the quaternion columns qw, qx, qy, qz (Hamilton, scalar first; normalised:
    ``lgekf.io.attitude.euler_of_quaternion``); a DataError naming the first row whose quaternion is (nearly) zero."""
    q = np.column_stack([cols[k] for k in QUATERNION_COLUMNS])
    norm = quaternion_norms(q)
    short = norm < MIN_QUATERNION_NORM
    if short.any():
        k = int(np.flatnonzero(short)[0])
        raise DataError(f"{source} {line_word} {int(lines[k])}: the quaternion (qw, qx, qy, qz) = "
                        f"({', '.join(f'{v:g}' for v in q[k])}) has norm {norm[k]:.3g}: no rotation (at least "
                        f"{MIN_QUATERNION_NORM:g} is needed to normalise it)")
    return euler_of_quaternion(q)


def parse_number_column(source: str, name: str, texts, lines) -> np.ndarray:
    """Numbers (float64) of one column given as text, exactly as ``read_csv`` parses them.

    Parameters
    ----------
    source : str
        The file's name in messages.
    name : str
        The column's key (named in messages).
    texts : array_like of str
        One entry per row.
    lines : ndarray of int
        The line number of every row.

    Returns
    -------
    ndarray
        Correctly rounded float64 values (the same as ``numpy.loadtxt``'s).

    Raises
    ------
    DataError
        Naming the line, the column and the first value that is not a number.
    """
    a = np.asarray(texts, dtype=str)
    try:
        if np.any(np.char.find(a, "_") >= 0):  # Python's float() takes 1_000, numpy.loadtxt does not
            raise ValueError
        return a.astype(np.float64)
    except ValueError:
        for k, v in enumerate(a.tolist()):
            try:
                if "_" in v:
                    raise ValueError
                float(v)
            except ValueError:
                v = v.strip()
                shown = v if v else "(empty)"
                hint = " (a decimal comma? write numbers with a decimal point)" if _DECIMAL_COMMA.match(v) else ""
                raise DataError(f"{source} line {int(lines[k])}: column {name!r}: {shown!r} is not a number{hint}") from None
        raise


def read_pedestrian(path, frame_dt: float) -> Measurements:
    """Read the whitespace-separated ``frame id x y`` format (no header); t = frame * frame_dt.

    Parameters
    ----------
    path : str or Path
        A file (plain or gzip-compressed) or ``-`` for stdin.
    frame_dt : float
        Seconds per frame unit.

    Returns
    -------
    Measurements
        Ids are numbers in this format (``1`` and ``1.0`` are one object).
    """
    source = source_name(path)
    if frame_dt is None:
        raise DataError("--frame-dt: the pedestrian format needs the time per frame unit in seconds (e.g. 0.04 for 10 frames = 0.4 s)")
    if not (math.isfinite(frame_dt) and frame_dt > 0):
        raise DataError(f"--frame-dt: must be a positive number of seconds, got {frame_dt}")
    colnames = ["frame", "id", "x", "y"]
    with open_input(path, DataError) as f, _reading(source):
        cols, lines = _read_chunks(source, f, 1, None, [0, 1, 2, 3], colnames)
    if lines.size == 0:
        raise DataError(f"{source}: empty file; expected whitespace-separated lines 'frame id x y'")
    keep = _check_finite(source, cols, lines, colnames)
    skipped = {}
    if keep is not None:
        skipped["non-finite"] = lines[~keep].tolist()
        cols = {n: v[keep] for n, v in cols.items()}
        lines = lines[keep]
    obj, labels = _objects_from_numbers(cols["id"])
    z = np.column_stack([cols["x"], cols["y"]])
    return Measurements(cols["frame"] * frame_dt, z, None, obj, labels, lines, source, skipped=skipped)


def read_measurements(path, fmt: str = "csv", frame_dt: float | None = None, use_heading: bool = False,
                      delimiter="auto") -> Measurements:
    """Read a measurement file with ``read_csv`` or ``read_pedestrian``.

    Parameters
    ----------
    path : str or Path
        A file or ``-`` (stdin).
    fmt : str
        ``"csv"`` or ``"pedestrian"``.
    frame_dt : float, optional
        Pedestrian format: seconds per frame unit.
    use_heading : bool
        CSV: read the heading column.
    delimiter : str or None, optional
        CSV separator (``"auto"``: found from the header); an error with the pedestrian format.

    Returns
    -------
    Measurements
    """
    if fmt == "csv":
        return read_csv(path, use_heading=use_heading, delimiter=delimiter)
    if fmt == "pedestrian":
        if use_heading:
            raise DataError("--use-heading: the pedestrian format has no heading column")
        if delimiter != "auto":
            raise DataError("--delimiter: only for CSV input (the pedestrian format is whitespace separated)")
        return read_pedestrian(path, frame_dt)
    raise DataError(f"--format: unknown format {fmt!r}; choose csv or pedestrian")


# ----------------------------------------------------------------------------------- writing
