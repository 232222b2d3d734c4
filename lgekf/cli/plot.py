"""`lgekf plot TRACKS [--measurements IN] -o FIG`: a picture of what the filter did (``lgekf.apps.plot_tracks``)."""

from __future__ import annotations

import os
import sys
import tempfile
from pathlib import Path

from ..io.files import check_output_path
from . import ArgumentParser

__all__ = ["cmd_plot"]

FORMATS = (".png", ".svg", ".pdf", ".html")


def cmd_plot(argv) -> int:
    ap = ArgumentParser(prog="lgekf plot", description="Draw the tracks of `lgekf track` (map with 95 %% ellipses and "
                        "flagged rows; speed, course and turn rate against time with ±2σ bands).")
    ap.add_argument("tracks", help="a track file written by lgekf track (CSV, .gz)")
    ap.add_argument("--measurements", default=None, metavar="IN",
                    help="the input file of that run (drawn as dots under the tracks; read like lgekf track reads it)")
    ap.add_argument("-o", "--output", required=True, help="the figure: .png, .svg, .pdf, or .html (a self-contained interactive page; needs lgekf[html])")
    ap.add_argument("--id", action="append", default=None, metavar="ID",
                    help="draw this object (repeatable; default: the first 12 of the file)")
    ap.add_argument("--every", type=int, default=None, metavar="N", help="a 95 %% ellipse every N rows of an object")
    ap.add_argument("--format", default="csv", choices=["csv", "pedestrian"], help="--measurements: its format (default csv)")
    ap.add_argument("--frame-dt", type=float, default=None, help="--measurements in the pedestrian format: seconds per frame unit")
    ap.add_argument("--time-unit", default="s", choices=["s", "ms", "us", "ns"], help="--measurements: its t unit (default s)")
    a = ap.parse_args(argv)
    suffix = Path(a.output).suffix.lower()
    if suffix not in FORMATS:
        raise ValueError(f"--output: {a.output}: write {', '.join(FORMATS)}")
    if a.every is not None and a.every < 1:
        raise ValueError(f"--every: must be at least 1, got {a.every}")
    check_output_path(a.output)
    if suffix == ".html":
        from ..apps.plot_tracks import HTML_INSTALL_HINT

        try:
            import plotly  # noqa: F401 - checked before any work: one line, no file
        except ImportError:
            raise ValueError(f"--output: {a.output}: {HTML_INSTALL_HINT}") from None
    import pandas as pd

    from ..apps.plot_tracks import object_column, plot_tracks

    try:
        tracks = pd.read_csv(a.tracks, dtype={"id": str, "track": str})
    except (OSError, ValueError) as e:
        raise ValueError(f"{a.tracks}: cannot read it as a track file ({e})") from None
    key = object_column(tracks.columns)
    missing = [c for c in ("t", "x", "y", "std_x", "std_y") if c not in tracks.columns]
    if missing:
        raise ValueError(f"{a.tracks}: no column {', '.join(missing)}; is it the output of lgekf track?")
    meas = None
    if a.measurements is not None:
        from ..io.readers import read_measurements
        from ..io.units import to_seconds

        m = read_measurements(a.measurements, a.format, a.frame_dt, False, "auto")
        t = to_seconds(m.t, a.time_unit)
        meas = {lab: (t[m.obj == i], m.z[m.obj == i]) for i, lab in enumerate(m.labels)}
    # written next to the output and renamed into place: no partly written figure
    fd, tmp = tempfile.mkstemp(suffix=suffix, dir=os.path.dirname(os.path.abspath(a.output)))
    os.close(fd)
    try:
        _, drawn = plot_tracks(tracks, meas, a.id, a.every, path=tmp, title=Path(a.tracks).name)
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)  # mkstemp's file is private (0600); a figure is not
        os.replace(tmp, a.output)
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)
    n = tracks[key].nunique()
    print(f"{a.output}: {len(drawn)} of {n} object{'s' if n != 1 else ''} drawn", file=sys.stderr)
    return 0
