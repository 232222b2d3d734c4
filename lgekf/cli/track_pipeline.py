"""The pipeline of `lgekf track` that every estimator plugs into (``lgekf.cli.track.cmd_track``):

    check -> read -> (data warnings) -> plan the noise -> estimate with the monitor (and smoothing) -> write -> report

``TrackEstimator`` holds the stages an estimator shares with the others (reading labelled objects, the data's unit and
per-object warnings, the report line); ``ModelsTrack`` (``--model MODEL|all``, ``lgekf.cli.track``), ``ImmTrack``
(``--model imm``, ``lgekf.cli.track_imm``) and ``MultiTrack`` (``--multi``, ``lgekf.cli.track_multi``) add their
own ``check``, ``plan`` and ``write`` (and ``--multi`` its own reading of unlabelled detections).
"""

from __future__ import annotations

import sys

import numpy as np

from ..core.registry import DEFAULT_SPACE, get_measurement, models_of, space_of_positions
from ..io.cleaning import drop_invalid, skipped_summary, sort_within_objects
from ..io.files import is_stdio
from ..io.geo import max_scale_error, to_latlon
from ..io.grouping import grouped_consuming
from ..io.readers import (
    csv_header, header_keys, named_columns, parse_delimiter, read_measurements, skipping_nonfinite_rows, unused_columns_warning,
)
from ..io.units import heading_in_radians, object_warnings, to_seconds, unit_warnings
from .memory import single_heap
from .track_options import column_names
from .track_parquet import is_parquet, read_parquet

__all__ = ["TrackEstimator", "read_track_input", "frame_note", "projection_line", "check_time_unit", "input_space", "SPACE_WORDS", "SPACE_HINTS"]

#: the spaces as the messages name them
SPACE_WORDS = {"2d": "the plane", "3d": "3-D space"}
SPACE_HINTS = {"2d": "2-D positions (no z or alt column)", "3d": "3-D positions (a z or alt column)"}


class TrackEstimator:
    """The stages of ``cmd_track`` an estimator shares (subclasses add ``check``, ``plan`` and ``write``).

    ``models``: one name per output file. ``read()`` -> (meas, starts); ``data_warnings(meas, starts)`` -> lines;
    ``run_on_cluster()`` -> an exit status when the work ran on Dask, else None; ``compile_seconds()`` and
    ``warm_up()`` for the compile notice; ``report(outs, what, meas)`` -> the lines of the summary (stdout).
    """

    def __init__(self, a, say):
        self.a, self.say = a, say

    def read(self):
        return read_track_input(self.a)

    def adopt_space(self, meas) -> None:
        """After reading: refuse an input whose space the estimator does not track (the IMM: the plane only, yet);
        ``ModelsTrack`` and ``MultiTrack`` select their models by the space."""
        space = space_of_positions(meas.z.shape[1])
        if space != DEFAULT_SPACE:
            raise ValueError(f"{'--multi' if self.a.multi else '--model imm'}: tracks in the plane only (yet); the input "
                             f"has {SPACE_HINTS[space]}: use --model {', '.join(models_of(space))}")

    def data_warnings(self, meas, starts) -> list:
        """The unit checks over the file and per object (``lgekf.io.units``)."""
        a = self.a
        return (unit_warnings(meas.t, meas.z, starts, a.time_unit, projected=meas.origin is not None, fmt=a.format)
                + object_warnings(meas.t, meas.z, starts, meas.labels, a.time_unit if a.format == "csv" else "s", meas.where))

    def run_on_cluster(self):
        return None

    def compile_seconds(self):
        return None

    def warm_up(self) -> None:
        pass

    def report(self, outs, what, meas) -> list:
        """One line per output file: its rows and objects, and what the estimator adds (``write``'s (what, extra))."""
        n = meas.n_objects
        return [f"{'<stdout>' if is_stdio(o) else o}: {meas.t.size} rows, {n} object{'s' if n != 1 else ''} ({w}){extra}"
                for o, (w, extra) in zip(outs, what)]


def frame_note(meas) -> str:
    """The stderr line saying that lat, lon were projected, about which origin and how accurately."""
    lat0, lon0 = meas.origin[:2]
    lat, _ = to_latlon(meas.z[:, 0], meas.z[:, 1], lat0, lon0)
    return projection_line(meas.origin, max_scale_error(lat, lat0))


def projection_line(origin, scale_error: float) -> str:
    """The stderr line saying that lat, lon (, alt) were projected about ``origin`` (lat0, lon0[, alt0]) with a scale
    error of at most ``scale_error`` (a fraction)."""
    lat0, lon0 = origin[:2]
    err = 100.0 * scale_error
    if len(origin) == 3:
        return (f"lat, lon, alt projected to x, y, z in metres east, north and up of ({lat0!r}, {lon0!r}, {origin[2]!r}) "
                f"(the first row; local equirectangular on WGS84, scale error at most {err:.2g} % here); the output's "
                f"origin_lat, origin_lon, origin_alt columns hold it")
    return (f"lat, lon projected to x, y in metres east and north of ({lat0!r}, {lon0!r}) (the first row; local "
            f"equirectangular on WGS84, scale error at most {err:.2g} % here); the output's origin_lat, origin_lon columns hold it")


def check_time_unit(meas, time_unit: str) -> None:
    """ISO-8601 stamps are read as seconds: a --time-unit beside them is an error (one line)."""
    if meas.time_iso and time_unit != "s":
        raise ValueError(f"--time-unit {time_unit}: the t column holds ISO-8601 date-times, read as seconds; leave --time-unit out")


def input_space(a):
    """The space of the input's positions from its header, before reading its rows: "3d" with a z column (or lat, lon,
    alt), else "2d"; None when the header cannot be read now (stdin, a bad file: the reading then says why)."""
    if a.format != "csv":
        return "2d"  # the pedestrian format: x, y
    if is_stdio(a.input):
        return None
    try:
        with named_columns(column_names(a)):
            if is_parquet(a.input):
                import pyarrow.parquet as pq

                keys = header_keys(str(a.input), pq.read_schema(a.input).names)
            else:
                keys = csv_header(a.input, delimiter=parse_delimiter(a.delimiter))[1]
    except Exception:  # noqa: BLE001 - any failure is reported by the reading itself, with its line
        return None
    return "3d" if ("z" in keys or "alt" in keys) else "2d"


def read_track_input(a):
    """The measurements of ``lgekf track``'s input (CSV, pedestrian format or Parquet), grouped by object (objects of
    at least 2 rows, t increasing: else one clear error; ``--sort`` and ``--skip-invalid``: ``lgekf.io.cleaning``), t in
    seconds. Returns (meas, starts)."""
    single_heap()  # the threads' freed chunk buffers reused from one heap, not kept in an arena per thread
    heading = a.use_heading or bool(get_measurement(a.measure).angles)  # a measurement with an angle reads the column
    with skipping_nonfinite_rows(a.skip_invalid), named_columns(column_names(a)):
        if is_parquet(a.input):
            meas = read_parquet(a.input, heading)
        else:
            meas = read_measurements(a.input, a.format, a.frame_dt, heading, parse_delimiter(a.delimiter))
    check_time_unit(meas, a.time_unit)
    note = unused_columns_warning(meas)
    if note is not None:
        print(f"lgekf track: warning: {note}", file=sys.stderr)
    if a.sort:
        meas, moved = sort_within_objects(meas)
        print(f"lgekf track: warning: --sort: {moved} row{'s' if moved != 1 else ''} moved into time order", file=sys.stderr)
    if a.skip_invalid:
        meas = drop_invalid(meas)
        for line in skipped_summary(meas):
            print(f"lgekf track: warning: {line}", file=sys.stderr)
    meas, starts = grouped_consuming(meas, min_length=2)  # the file-order rows released
    meas.t = to_seconds(meas.t, a.time_unit)
    if meas.quaternion and a.heading_unit == "deg":
        raise ValueError("--heading-unit deg: the attitude is a quaternion (qw, qx, qy, qz), which has no unit; leave "
                         "--heading-unit out")
    if meas.quaternion:
        pass  # roll, pitch, yaw of the quaternion (``lgekf.io.attitude``): radians
    elif meas.heading is not None and meas.heading.ndim == 2:  # 3-D: roll, pitch, yaw; the unit is told by the yaw
        yaw = meas.heading[:, 2]
        meas.heading = meas.heading if heading_in_radians(yaw, a.heading_unit, meas.z, starts) is yaw else np.radians(meas.heading)
    elif meas.heading is not None:
        meas.heading = heading_in_radians(meas.heading, a.heading_unit, meas.z, starts)
    return meas, starts


