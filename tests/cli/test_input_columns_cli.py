"""`lgekf track`'s input columns and units on real-log shapes (issue 27): an id column of another name, columns named
by option, ISO-8601 and epoch time stamps, coordinates near 1e9 m written to 0.1 mm, `--multi` with unsorted or NaN
rows. Each case a file made for it, run as a user runs the command."""

from __future__ import annotations

import csv
import datetime as dt
import re

import numpy as np
import pytest

from lgekf.cli import main

T0 = dt.datetime(2024, 5, 1, 12, tzinfo=dt.timezone.utc)


def _cars(n_obj=3, n=40, seed=0, x0=0.0, y0=0.0, dt_s=0.125):
    """Rows (label, t seconds from 0, x, y) of cars driving straight at 10 m/s, 5 cm noise; times distinct across
    objects and whole milliseconds (object v at t = k dt + 0.01 v)."""
    rng = np.random.default_rng(seed)
    rows = []
    for v in range(n_obj):
        for k in range(n):
            t = k * dt_s + 0.01 * v
            rows.append((f"car{v}", t, x0 + 100.0 * v + 10.0 * t + 0.05 * rng.standard_normal(),
                         y0 + 30.0 * v + 2.0 * t + 0.05 * rng.standard_normal()))
    rows.sort(key=lambda r: r[1])  # interleaved as a log is
    return rows


def _write(path, header, rows, fmt):
    path.write_text(header + "\n" + "".join(fmt(*r) + "\n" for r in rows))
    return path


def _read(path):
    return list(csv.DictReader(open(path)))


def _run(capsys, *args):
    code = main(["track", *map(str, args)])
    out, err = capsys.readouterr()
    return code, err.strip().splitlines()


# ------------------------------------------------------------------------------------------ columns
def test_vehicle_column_warns_that_all_rows_are_one_object_and_id_column_reads_three(tmp_path, capsys):
    src = _write(tmp_path / "veh.csv", "vehicle,t,x,y", _cars(), lambda v, t, x, y: f"{v},{t!r},{x!r},{y!r}")
    code, err = _run(capsys, src, "-o", tmp_path / "one.csv", "--quiet")
    assert code == 0
    warn = [ln for ln in err if "no id column" in ln]
    assert len(warn) == 1 and "all 120 rows are read as one object" in warn[0]
    assert "'vehicle'" in warn[0] and "--id-column" in warn[0]
    assert {r["id"] for r in _read(tmp_path / "one.csv")} == {"0"}
    code, err = _run(capsys, src, "-o", tmp_path / "three.csv", "--quiet", "--id-column", "vehicle")
    assert code == 0 and not any("no id column" in ln or "median speed" in ln for ln in err)
    rows = _read(tmp_path / "three.csv")
    assert sorted({r["id"] for r in rows}) == ["car0", "car1", "car2"] and len(rows) == 120


def test_named_columns_track_as_the_standard_names(tmp_path, capsys):
    rows = _cars(n_obj=2)
    std = _write(tmp_path / "std.csv", "id,t,x,y", rows, lambda v, t, x, y: f"{v},{t!r},{x!r},{y!r}")
    odd = _write(tmp_path / "odd.csv", "when,north,east,car,x", rows, lambda v, t, x, y: f"{t!r},{y!r},{x!r},{v},7")
    assert _run(capsys, std, "-o", tmp_path / "a.csv", "--quiet")[0] == 0
    code, err = _run(capsys, odd, "-o", tmp_path / "b.csv", "--quiet", "--id-column", "car", "--time-column", "when",
                     "--x-column", "east", "--y-column", "north")
    assert code == 0, err
    assert (tmp_path / "a.csv").read_bytes() == (tmp_path / "b.csv").read_bytes()


def test_an_absent_named_column_is_one_error_listing_the_header(tmp_path, capsys):
    src = _write(tmp_path / "veh.csv", "vehicle,t,x,y", _cars(n_obj=1), lambda v, t, x, y: f"{v},{t!r},{x!r},{y!r}")
    out = tmp_path / "o.csv"
    code, err = _run(capsys, src, "-o", out, "--id-column", "car")
    assert code == 2 and len(err) == 1 and not out.exists()
    assert "--id-column car: no such column; the header has: vehicle, t, x, y" in err[0]


def test_id_column_from_python(tmp_path):
    pd = pytest.importorskip("pandas")
    import lgekf

    rows = _cars()
    df = pd.DataFrame(rows, columns=["vehicle", "t", "x", "y"])
    got = lgekf.track(df, id_column="vehicle")
    assert sorted(got["id"].unique()) == ["car0", "car1", "car2"] and len(got) == 120


# ------------------------------------------------------------------------------------------ times
def _iso(t):
    return (T0 + dt.timedelta(seconds=t)).isoformat(timespec="milliseconds").replace("+00:00", "Z")


def _epoch_text(t):
    ms = round(t * 1000)
    return f"{int(T0.timestamp()) + ms // 1000}.{ms % 1000:03d}"


def test_iso_stamps_track_as_epoch_seconds(tmp_path, capsys):
    rows = _cars(n_obj=2)
    iso = _write(tmp_path / "iso.csv", "id,timestamp,x,y", rows, lambda v, t, x, y: f"{v},{_iso(t)},{x!r},{y!r}")
    epoch = _write(tmp_path / "epoch.csv", "id,t,x,y", rows, lambda v, t, x, y: f"{v},{_epoch_text(t)},{x!r},{y!r}")
    code, err = _run(capsys, iso, "-o", tmp_path / "iso_out.csv", "--quiet")
    assert code == 0, err
    assert _run(capsys, epoch, "-o", tmp_path / "epoch_out.csv", "--quiet")[0] == 0
    assert (tmp_path / "iso_out.csv").read_bytes() == (tmp_path / "epoch_out.csv").read_bytes()
    t = sorted(float(r["t"]) for r in _read(tmp_path / "iso_out.csv"))
    want = sorted(T0.timestamp() + r[1] for r in rows)
    assert max(abs(a - b) for a, b in zip(t, want)) < 1e-6  # written to 1 µs (16 digits at 1.7e9 s)


def test_iso_stamps_with_a_time_unit_and_bad_stamps_are_refused(tmp_path, capsys):
    rows = _cars(n_obj=1, n=10)
    iso = _write(tmp_path / "iso.csv", "t,x,y", rows, lambda v, t, x, y: f"{_iso(t)},{x!r},{y!r}")
    out = tmp_path / "o.csv"
    code, err = _run(capsys, iso, "-o", out, "--time-unit", "ms")
    assert code == 2 and len(err) == 1 and "ISO-8601" in err[0] and "--time-unit" in err[0] and not out.exists()
    text = iso.read_text().splitlines()
    text[5] = "12:00:00.5," + text[5].split(",", 1)[1]  # a time of day without its date, on line 6
    iso.write_text("\n".join(text) + "\n")
    code, err = _run(capsys, iso, "-o", out)
    assert code == 2 and len(err) == 1 and not out.exists()
    assert "line 6" in err[0] and "'12:00:00.5'" in err[0] and "ISO-8601" in err[0]


def test_epoch_milliseconds_keep_the_times_and_positions(tmp_path, capsys):
    rows = _cars(n_obj=2)
    ms = _write(tmp_path / "ms.csv", "id,t,x,y", rows,
                lambda v, t, x, y: f"{v},{round((T0.timestamp() + t) * 1000)},{x!r},{y!r}")
    code, err = _run(capsys, ms, "-o", tmp_path / "o.csv", "--time-unit", "ms", "--quiet")
    assert code == 0, err
    assert not any("median time step" in ln for ln in err)
    got = _read(tmp_path / "o.csv")
    t = sorted(float(r["t"]) for r in got)
    want = sorted(T0.timestamp() + r[1] for r in rows)
    assert max(abs(a - b) for a, b in zip(t, want)) < 1e-6


# ------------------------------------------------------------------------------------------ precision
def test_positions_near_1e9_keep_0_1_mm(tmp_path, capsys):
    """The same cars at x + 1e9, y + 5e6 (m) with epoch times: the output, read back, is the near-origin run's output
    shifted by the offsets to 0.1 mm (the default 10 digits rounded x to 1 m)."""
    near = _cars(n_obj=2)
    far = [(v, t, x + 1e9, y + 5e6) for v, t, x, y in near]
    fmt = lambda v, t, x, y: f"{v},{T0.timestamp() + t!r},{x!r},{y!r}"  # noqa: E731
    a = _write(tmp_path / "near.csv", "id,t,x,y", near, fmt)
    b = _write(tmp_path / "far.csv", "id,t,x,y", far, fmt)
    for src, out in ((a, "near_out.csv"), (b, "far_out.csv")):
        assert _run(capsys, src, "-o", tmp_path / out, "--quiet", "--model", "cv", "--meas-std", "0.05",
                    "--accel-std", "0.5")[0] == 0
    ra, rb = _read(tmp_path / "near_out.csv"), _read(tmp_path / "far_out.csv")
    dx = [abs(float(q["x"]) - 1e9 - float(p["x"])) for p, q in zip(ra, rb)]
    dy = [abs(float(q["y"]) - 5e6 - float(p["y"])) for p, q in zip(ra, rb)]
    assert max(dx) < 1e-4 and max(dy) < 1e-4
    assert _run(capsys, b, "-o", tmp_path / "p10.csv", "--quiet", "--model", "cv", "--meas-std", "0.05",
                "--accel-std", "0.5", "--precision", "10")[0] == 0
    assert all(float(r["x"]) == round(float(r["x"])) for r in _read(tmp_path / "p10.csv"))  # --precision 10: whole metres


# ------------------------------------------------------------------------------------------ --multi
def _scans(path, order=None, nan_rows=()):
    """Detections of three objects, 60 scans of 0.2 s (one t per scan); rows in time order unless ``order``."""
    rng = np.random.default_rng(3)
    rows = []
    for k in range(60):
        t = 0.2 * k
        for j, (x0, vx) in enumerate([(0.0, 5.0), (50.0, -3.0), (-40.0, 2.0)]):
            rows.append((round(t, 6), x0 + vx * t + 0.3 * rng.standard_normal(), 10.0 * j + 0.3 * rng.standard_normal()))
    if order is not None:
        rows = [rows[i] for i in order]
    lines = [f"{t!r},{'nan' if i in nan_rows else repr(x)},{y!r}" for i, (t, x, y) in enumerate(rows)]
    path.write_text("t,x,y\n" + "\n".join(lines) + "\n")
    return rows


def test_multi_refuses_unsorted_rows_and_sort_sorts_them(tmp_path, capsys):
    _scans(tmp_path / "sorted.csv")
    order = list(range(180))
    order[30], order[40] = order[40], order[30]  # scans 10 and 13 swap one detection
    _scans(tmp_path / "unsorted.csv", order)
    assert _run(capsys, tmp_path / "sorted.csv", "--multi", "-o", tmp_path / "a.csv", "--quiet")[0] == 0
    out = tmp_path / "b.csv"
    code, err = _run(capsys, tmp_path / "unsorted.csv", "--multi", "-o", out)
    assert code == 2 and len(err) == 1 and not out.exists()
    assert "line 33" in err[0] and "--sort" in err[0] and "non-decreasing time" in err[0]
    code, err = _run(capsys, tmp_path / "unsorted.csv", "--multi", "-o", out, "--quiet", "--sort")
    assert code == 0
    moved = [ln for ln in err if "--sort:" in ln]
    # by hand: places 30..32 get the t = 2.0 rows of places 31, 32, 40 (3 moved); places 39..41 the t = 2.6 rows of
    # places 30, 39, 41 (2 moved: 41 stays); places 33..38 keep theirs
    assert len(moved) == 1 and re.search(r"--sort: (\d+) rows moved", moved[0]).group(1) == "5"
    assert out.read_bytes() == (tmp_path / "a.csv").read_bytes()


def test_multi_refuses_nan_rows_and_skip_invalid_drops_them(tmp_path, capsys):
    rows = _scans(tmp_path / "nan.csv", nan_rows=(7, 100))
    keep = [r for i, r in enumerate(rows) if i not in (7, 100)]
    (tmp_path / "clean.csv").write_text("t,x,y\n" + "".join(f"{t!r},{x!r},{y!r}\n" for t, x, y in keep))
    out = tmp_path / "b.csv"
    code, err = _run(capsys, tmp_path / "nan.csv", "--multi", "-o", out)
    assert code == 2 and len(err) == 1 and not out.exists()
    assert "line 9" in err[0] and "--skip-invalid" in err[0]
    code, err = _run(capsys, tmp_path / "nan.csv", "--multi", "-o", out, "--quiet", "--skip-invalid")
    assert code == 0
    assert [ln for ln in err if "skipped" in ln] == ["lgekf track: warning: skipped 2 rows (non-finite; lines 9, 102)"]
    assert _run(capsys, tmp_path / "clean.csv", "--multi", "-o", tmp_path / "c.csv", "--quiet")[0] == 0
    assert out.read_bytes() == (tmp_path / "c.csv").read_bytes()


# ------------------------------------------------------------------------------------------ real data
DUT = "/work/shared/data/dut_vehicles/raw/intersection_01_traj_veh.csv"


def test_real_dut_file_read_with_named_columns(tmp_path, capsys):
    """A real drone log (DUT vehicles: ``id,x_c,y_c,...,frame,label``, pixels, one row per video frame) is read with
    --time-column frame --x-column x_c --y-column y_c: every vehicle tracked, positions those of the file."""
    import os

    if not os.path.exists(DUT):
        pytest.skip(f"real data not available ({DUT})")
    rows = list(csv.DictReader(open(DUT)))
    out = tmp_path / "o.csv"
    code, err = _run(capsys, DUT, "-o", out)
    assert code == 2 and len(err) == 1 and "missing column" in err[0] and "frame" in err[0]  # no t: the header listed
    code, err = _run(capsys, DUT, "-o", out, "--quiet", "--time-column", "frame", "--x-column", "x_c", "--y-column", "y_c",
                     "--model", "cv")
    assert code == 0, err
    got = _read(out)
    assert len(got) == len(rows) and sorted({r["id"] for r in got}) == sorted({r["id"] for r in rows})
    want = {(r["id"], float(r["frame"])): (float(r["x_c"]), float(r["y_c"])) for r in rows}
    err_px = [np.hypot(float(g["x"]) - want[g["id"], float(g["t"])][0], float(g["y"]) - want[g["id"], float(g["t"])][1])
              for g in got]
    assert np.median(err_px) < 2.0  # the filtered centre stays within a few pixels of the measured one
