"""``write_model``'s writer thread: chunk i is formatted and written while chunk i + 1 is tracked.

The file must be that of doing one chunk after the other (order, bytes), an error of the writer must stop the
run with that error (and the CLI with one line and no file), and the progress bar must count written rows.
"""

from __future__ import annotations

import errno

import numpy as np
import pytest

import lgekf.apps.track as track
import lgekf.io.formatting as formatting
from lgekf.cli import main


def _file(path, objects=12, steps=30, seed=3):
    rng = np.random.default_rng(seed)
    lines = ["id,t,x,y"]
    for k in range(steps):
        for o in range(objects):
            t = 0.1 * k + 0.001 * o
            lines.append(f"car{o},{t!r},{float(o + 2.0 * t + 0.05 * rng.standard_normal())!r},{float(np.sin(t) + 0.05 * rng.standard_normal())!r}")
    path.write_text("\n".join(lines) + "\n")
    return path


@pytest.mark.parametrize("model", ["cv", "se2se2"])
def test_many_chunks_write_the_bytes_of_one(tmp_path, monkeypatch, model):
    inp = _file(tmp_path / "in.csv")
    args = ["track", str(inp), "--model", model, "--quiet", "--meas-std", "0.05"]
    assert main([*args, "-o", str(tmp_path / "one.csv")]) == 0  # 360 rows: one chunk
    monkeypatch.setattr(track, "ROWS_PER_CHUNK", 31)  # about one object per chunk: 12 chunks through the writer
    monkeypatch.setattr(formatting, "PART_ROWS", 7)
    calls = []
    real = track.track_monitored
    monkeypatch.setattr(track, "track_monitored", lambda *a, **k: calls.append(1) or real(*a, **k))
    assert main([*args, "-o", str(tmp_path / "many.csv")]) == 0
    assert len(calls) == 12
    one = (tmp_path / "one.csv").read_bytes()
    assert (tmp_path / "many.csv").read_bytes() == one
    assert one.count(b"\n") == 361


def test_a_writer_error_stops_the_run(tmp_path, monkeypatch, capsys):
    """The writer fails on its second chunk: the run stops with that error within one more chunk of tracking,
    the CLI says it in one line and leaves no output file."""
    inp = _file(tmp_path / "in.csv")
    monkeypatch.setattr(track, "ROWS_PER_CHUNK", 31)
    written = []

    def failing(fh, *a, **k):
        if len(written) == 1:
            raise OSError(errno.ENOSPC, "No space left on device")
        written.append(1)
        return real_write(fh, *a, **k)

    real_write = track.write_rows_made
    monkeypatch.setattr(track, "write_rows_made", failing)
    calls = []
    real = track.track_monitored
    monkeypatch.setattr(track, "track_monitored", lambda *a, **k: calls.append(1) or real(*a, **k))
    out = tmp_path / "o.csv"
    assert main(["track", str(inp), "-o", str(out), "--model", "cv", "--quiet", "--meas-std", "0.05"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err == ["lgekf track: error: [Errno 28] No space left on device"]
    assert not out.exists() and list(tmp_path.iterdir()) == [inp]
    assert 2 <= len(calls) <= 3  # chunk 1's failure is seen once chunk 2 is tracked: not the other 9 chunks


def test_the_bar_counts_written_rows(tmp_path, monkeypatch):
    inp = _file(tmp_path / "in.csv")
    monkeypatch.setattr(track, "ROWS_PER_CHUNK", 31)
    updates = []

    class Bar:
        def update(self, n):
            updates.append(n)

    meas, starts = _grouped(inp)
    with open(tmp_path / "o.csv", "wb") as fh:
        rows = track.write_model(fh, "cv", meas, starts, track.TrackConfig(meas_std=0.05), False, 10, Bar()).rows
    assert updates == [30] * 12 and rows == 360


def _grouped(path):
    from lgekf.io.grouping import grouped_consuming
    from lgekf.io.readers import read_measurements

    return grouped_consuming(read_measurements(str(path)), min_length=2)
