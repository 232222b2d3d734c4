"""`lgekf track` run as a user would: bad input -> one line on stderr, exit 2, no output file;
happy paths (columns, ids, irregular dt, formats, --model all, --full-cov) and correctness against
filter_batch (same x0/P0, to 1e-12) and against noise-free trajectories."""

import math
import subprocess

import numpy as np
import pytest
from _cli import cli_command

from lgekf.core.batch import filter_batch
from lgekf.core.covariance import unpack
from lgekf.core.registry import MODELS
from lgekf.apps.track import (
    TRACK_HEADING_CAP, TrackConfig, initial_common, initial_estimates, output_columns, track_arrays, track_monitored,
)




def run(*args, cwd=None):
    return subprocess.run([*cli_command(), "track", *map(str, args)], capture_output=True, text=True, cwd=cwd)


def read_out(path):
    with open(path) as f:
        header = f.readline().strip().split(",")
    data = np.genfromtxt(path, delimiter=",", skip_header=1, dtype=str, ndmin=2)
    return header, data


def write(tmp_path, name, text):
    p = tmp_path / name
    p.write_text(text)
    return p


GOOD = "t,x,y\n0,0,0\n0.1,0.3,0\n0.25,0.75,0.01\n0.3,0.9,0\n"

BAD_CASES = {
    "missing_column": ("t,x\n0,1\n1,2\n", [], "missing column 'y'"),
    "non_numeric": ("t,x,y\n0,0,0\n0.1,abc,0\n0.2,0.6,0\n", [], "line 3: column 'x': 'abc' is not a number"),
    "nan": ("t,x,y\n0,0,0\n0.1,nan,0\n0.2,0.6,0\n", [], "NaN"),
    "inf": ("t,x,y\n0,0,0\n0.1,0.3,inf\n0.2,0.6,0\n", [], "infinite"),
    "time_decreasing": ("t,x,y\n0,0,0\n0.2,0.3,0\n0.1,0.6,0\n", [], "time is not increasing"),
    "time_repeated": ("id,t,x,y\n1,0,0,0\n2,0,0,0\n1,0.1,0,0\n2,0.1,0,0\n1,0.1,0,0\n", [], "time is not increasing within object id 1"),
    "single_measurement": ("id,t,x,y\n1,0,0,0\n1,0.1,0.3,0\n2,0,5,5\n", [], "object id 2 (line 4) has a single measurement"),
    "empty_file": ("", [], "empty file"),
    "header_only": ("t,x,y\n", [], "no measurements"),
    "too_few_fields": ("t,x,y\n0,0,0\n0.1,0.3\n", [], "expected at least 3 columns"),
    "unknown_model": (GOOD, ["--model", "ukf"], "invalid choice: 'ukf'"),
    "negative_meas_std": (GOOD, ["--meas-std", "-0.3"], "meas-std: must be a positive number"),
    "zero_meas_std": (GOOD, ["--meas-std", "0"], "meas-std: must be a positive number"),
    "negative_accel_std": (GOOD, ["--model", "cv", "--accel-std", "-1"], "accel-std: noise stds must be non-negative"),
    "accel_std_arity": (GOOD, ["--model", "ctrv", "--accel-std", "1,2,3"], "accel-std: ctrv takes 2 values"),
    "accel_std_text": (GOOD, ["--accel-std", "a,b,c"], "accel-std: expected comma-separated numbers"),
    "bare_accel_std_with_all": (GOOD, ["--model", "all", "--accel-std", "1"], "MODEL=LIST"),
    "use_heading_without_column": (GOOD, ["--use-heading"], "needs a 'heading' column"),
    "pedestrian_without_frame_dt": ("780 1 0 0\n790 1 1 0\n", ["--format", "pedestrian"], "frame-dt"),
    "precision": (GOOD, ["--precision", "30"], "precision"),
    "abbreviated_multi": (GOOD, ["--mult"], "unrecognized arguments: --mult"),  # was a silent single-object run
    "abbreviated_option": (GOOD, ["--meas", "0.3"], "unrecognized arguments: --meas"),
    "multi_option_without_multi": (GOOD, ["--association", "gnn", "--max-speed", "9"],
                                   "--association, --max-speed: only with --multi"),
    "initiation_without_multi": (GOOD, ["--initiation", "one-point", "--birth-density", "1e-6"],
                                 "--initiation, --birth-density: only with --multi"),
}


@pytest.mark.parametrize("case", sorted(BAD_CASES))
def test_bad_input_one_line_exit_2_no_output(tmp_path, case):
    text, extra, message = BAD_CASES[case]
    inp = write(tmp_path, "in.csv", text)
    out = tmp_path / "out.csv"
    r = run(inp, "-o", out, *extra)
    assert r.returncode == 2, r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1, r.stderr
    assert lines[0].startswith("lgekf track: error: ")
    assert message in lines[0], lines[0]
    assert "Traceback" not in r.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["in.csv"]  # no output, no temporary file


def test_unreadable_and_directory_input(tmp_path):
    for inp, message in ((tmp_path / "nope.csv", "cannot read"), (tmp_path, "is a directory")):
        r = run(inp, "-o", tmp_path / "out.csv")
        assert r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1
        assert message in r.stderr and "Traceback" not in r.stderr
        assert not (tmp_path / "out.csv").exists()


def test_model_all_is_all_or_nothing(tmp_path):
    inp = write(tmp_path, "in.csv", GOOD)
    (tmp_path / "out_cv.csv").mkdir()  # the last file of the four cannot be written
    r = run(inp, "-o", tmp_path / "out.csv", "--model", "all")
    assert r.returncode == 2 and "Traceback" not in r.stderr and len(r.stderr.strip().splitlines()) == 1
    assert sorted(p.name for p in tmp_path.iterdir()) == ["in.csv", "out_cv.csv"]


def test_columns_rows_and_first_rows(tmp_path):
    inp = write(tmp_path, "in.csv", GOOD)
    out = tmp_path / "tracks.csv"
    r = run(inp, "-o", out, "--model", "se2se2", "--meas-std", "0.2")
    assert r.returncode == 0, r.stderr
    header, data = read_out(out)
    assert header == ["id", "t", "x", "y", "theta", "vx", "vy", "omega",
                      "std_x", "std_y", "std_theta", "std_vx", "std_vy", "std_omega", "speed", "course", "nis", "flag"]
    assert data.shape == (4, len(header))
    vals = data[:, 1:].astype(float)
    np.testing.assert_allclose(vals[0, 1:3], [0, 0])  # row 0: the first measurement
    np.testing.assert_allclose(vals[:2, 3:7], [[0, 3, 0, 0]] * 2, atol=1e-12)  # two-point velocity (3, 0), heading 0
    np.testing.assert_allclose(vals[:2, 7:9], 0.2)  # position std = meas std
    np.testing.assert_allclose(vals[:2, 13:15], [[3, 0]] * 2, atol=1e-12)  # speed 3 m/s, course 0 (east)
    th, vx, vy = vals[:, 3], vals[:, 4], vals[:, 5]  # speed and course: the body velocity turned into the world frame
    np.testing.assert_allclose(vals[:, 13], np.hypot(vx, vy), rtol=1e-9)
    np.testing.assert_allclose(np.cos(vals[:, 14] - th - np.arctan2(vy, vx)), 1.0, atol=1e-9)
    assert np.isnan(vals[:2, -2]).all() and np.isfinite(vals[2:, -2]).all()
    assert list(data[:, -1]) == ["0"] * 4  # flag: written as 0 / 1


def test_model_all_and_full_cov(tmp_path):
    inp = write(tmp_path, "in.csv", GOOD)
    r = run(inp, "-o", tmp_path / "tracks.csv", "--model", "all", "--full-cov", "--accel-std", "cv=0.7", "--quiet")
    assert r.returncode == 0 and r.stdout == ""
    for name, spec in MODELS.items():
        header, data = read_out(tmp_path / f"tracks_{name}.csv")
        assert header == output_columns(name, full_cov=True)
        n = spec.n
        assert len([h for h in header if h.startswith("cov_")]) == n * (n + 1) // 2
        vals = data[:, 1:].astype(float)
        std = vals[:, 1 + n:1 + 2 * n]
        cov = unpack(vals[:, 3 + 2 * n:-2], n)  # after state, stds, speed, course
        np.testing.assert_allclose(std**2, np.diagonal(cov, axis1=1, axis2=2), rtol=1e-8)
    assert not (tmp_path / "tracks.csv").exists()


def _x0_P0(model, t, z, r):
    c, var = initial_common(t, z, np.array([0, len(t)]), r, heading_cap=TRACK_HEADING_CAP)  # as lgekf track does
    x0, P0 = initial_estimates(model, c, var)
    return x0, P0[0]


@pytest.mark.parametrize("model", list(MODELS))
def test_irregular_dt_equals_filter_batch(tmp_path, model):
    rng = np.random.default_rng(3)
    K = 40
    t = np.cumsum(rng.uniform(0.03, 0.3, K))
    z = np.column_stack([2.0 * t + 0.1 * rng.standard_normal(K), np.sin(t) + 0.1 * rng.standard_normal(K)])
    rows = "".join(f"{a!r},{b!r},{c!r}\n" for a, b, c in zip(t.tolist(), z[:, 0].tolist(), z[:, 1].tolist()))
    inp = write(tmp_path, "in.csv", "t,x,y\n" + rows)
    out = tmp_path / "o.csv"
    q = ",".join(["0.3", "0.4", "0.9"][-len(MODELS[model].noise_names):] if len(MODELS[model].noise_names) > 1 else ["0.3"])
    r = run(inp, "-o", out, "--model", model, "--accel-std", q, "--meas-std", "0.15", "--precision", "17", "--full-cov",
            "--no-monitor")
    assert r.returncode == 0, r.stderr
    _, data = read_out(out)
    vals = data[:, 1:].astype(float)
    n = MODELS[model].n
    x0, P0 = _x0_P0(model, t, z, 0.15)
    xs, Ps, nis = filter_batch(model, z[None, 2:], dt=np.diff(t)[None, 1:], accel_std=[float(v) for v in q.split(",")],
                               meas_std=0.15, x0=x0, P0=P0, return_cov=True, return_nis=True)
    np.testing.assert_allclose(vals[:, 0], t, rtol=1e-14)
    np.testing.assert_array_equal(vals[:, -1], 0)  # --no-monitor: flag 0
    np.testing.assert_allclose(vals[2:, 1:1 + n], xs[0], rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(unpack(vals[2:, 3 + 2 * n:-2], n), Ps[0], rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(vals[2:, -2], nis[0], rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(vals[1, 1:1 + n], x0[0], atol=1e-12)


def test_interleaved_text_ids_equal_separate_runs(tmp_path):
    rng = np.random.default_rng(5)
    rows, per = [], {}
    for lab, v in (("car 1", (8.0, 1.0)), ("ped", (1.2, -0.5)), ("7", (3.0, 3.0))):
        t = np.cumsum(rng.uniform(0.05, 0.15, 30))
        z = np.column_stack([v[0] * t, v[1] * t]) + 0.05 * rng.standard_normal((30, 2))
        per[lab] = (t, z)
        rows += [(tt, lab, zz) for tt, zz in zip(t.tolist(), z.tolist())]
    rows.sort(key=lambda r: r[0])  # interleaved by time
    text = "x,id,y,t\n" + "".join(f"{z[0]!r},{lab},{z[1]!r},{t!r}\n" for t, lab, z in rows)
    out = tmp_path / "o.csv"
    r = run(write(tmp_path, "in.csv", text), "-o", out, "--model", "ctrv", "--precision", "17", "--meas-std", "0.3",
            "--accel-std", "0.5,1")
    assert r.returncode == 0, r.stderr
    _, data = read_out(out)
    first = [data[0, 0]] + [data[i, 0] for i in range(1, len(data)) if data[i, 0] != data[i - 1, 0]]
    assert first == sorted(per, key=lambda k: per[k][0][0])  # objects in order of first appearance
    cfg = TrackConfig({"ctrv": (0.5, 1.0)}, 0.3, heading_cap=TRACK_HEADING_CAP)
    for lab, (t, z) in per.items():
        mine = data[data[:, 0] == lab, 1:].astype(float)
        x = track_monitored("ctrv", t, z, np.array([0, len(t)]), cfg).x
        np.testing.assert_allclose(mine[:, 0], t, rtol=1e-14)
        np.testing.assert_allclose(mine[:, 1:6], x, rtol=1e-12, atol=1e-12)


def test_pedestrian_format_and_heading_column_ignored(tmp_path):
    text = "".join(f"{780 + 10 * k}\t{float(i)}\t{0.5 * k + i}\t{1.0 * i}\n" for k in range(6) for i in (1, 2))
    out = tmp_path / "o.csv"
    r = run(write(tmp_path, "p.txt", text), "-o", out, "--format", "pedestrian", "--frame-dt", "0.04", "--model", "cv")
    assert r.returncode == 0, r.stderr
    _, data = read_out(out)
    assert data.shape[0] == 12 and list(data[:6, 0]) == ["1"] * 6
    np.testing.assert_allclose(data[:6, 1].astype(float), 0.04 * (780 + 10 * np.arange(6)))
    np.testing.assert_allclose(data[2:6, 4].astype(float), 1.25, rtol=1e-6)  # 0.5 m per 0.4 s


def test_use_heading_sets_initial_heading(tmp_path):
    text = "t,x,y,heading\n0,0,0,junk\n0.1,0.1,0.1,0.6\n0.2,0.2,0.2,0.7\n"
    for model, col in (("se2r3", 3), ("ctrv", 3)):
        out = tmp_path / f"{model}.csv"
        r = run(write(tmp_path, "in.csv", text.replace("junk", "0.5")), "-o", out, "--model", model, "--use-heading")
        assert r.returncode == 0, r.stderr
        _, data = read_out(out)
        assert float(data[1, col + 1]) == pytest.approx(0.6)
    r = run(write(tmp_path, "in.csv", text), "-o", tmp_path / "x.csv")  # heading column ignored unless asked
    assert r.returncode == 0, r.stderr


@pytest.mark.parametrize("model", list(MODELS))
def test_noise_free_straight_line_and_circle(model):
    dt = 0.1
    t = np.arange(80) * dt
    cfg = TrackConfig(meas_std=0.05)
    line = np.column_stack([1.0 + 2.0 * t, -3.0 + 1.0 * t])
    x, _, _ = track_arrays(model, t, line, np.array([0, len(t)]), cfg)
    assert np.abs(x[2:, :2] - line[2:]).max() < 1e-6
    w, R = 0.4, 6.0
    circle = np.column_stack([R * np.sin(w * t), R * (1 - np.cos(w * t))])
    x, _, _ = track_arrays(model, t, circle, np.array([0, len(t)]), cfg)
    err = np.hypot(*(x[-30:, :2] - circle[-30:]).T).max()
    assert err < (0.1 if model == "cv" else 0.005), err  # CV lags in a turn (centripetal 0.96 m/s² vs σ_a 0.5)
    if model != "cv":
        assert x[-1, -1] == pytest.approx(w, abs=0.01)  # turn rate found


def test_stationary_start_is_finite(tmp_path):
    # two identical first positions: heading undefined, CTRV Jacobian singular at v = 0
    t = np.arange(10) * 0.1
    z = np.zeros((10, 2))
    z[5:, 0] = np.arange(5) * 0.1
    for model in MODELS:
        x, p, nis = track_arrays(model, t, z, np.array([0, 10]), TrackConfig())
        assert np.isfinite(x).all() and np.isfinite(p).all(), model
        c, var = initial_common(t, z, np.array([0, 10]), 0.3)
        _, P0 = initial_estimates(model, c, var)
        np.linalg.cholesky(P0[0])
        if model != "cv":
            assert P0[0, 2, 2] <= math.pi**2 * (1 + 1e-12)


# ------------------------------------------------------------------ issue #9: a user's first hour
BAD_CASES_9 = {
    "output_dot": (GOOD, ["-o", "."], "--output .: names a folder; give a file name"),
    "output_slash": (GOOD, ["-o", "sub/"], "--output sub/: names a folder"),
    "all_to_stdout": (GOOD, ["-o", "-", "--model", "all"], "--model all writes one file per model"),
    "time_unit_unknown": (GOOD, ["--time-unit", "min"], "invalid choice: 'min'"),
    "time_unit_pedestrian": ("780 1 0 0\n790 1 1 0\n", ["--format", "pedestrian", "--frame-dt", "0.04", "--time-unit", "ms"],
                             "--time-unit: only for CSV input"),
    "delimiter_two_chars": (GOOD, ["--delimiter", "ab"], "--delimiter: expected one character"),
    "no_separator_fits": ("t:x:y\n0:0:0\n1:1:0\n", [], "give --delimiter"),
    "empty_id": ("id,t,x,y\n1,0,0,0\n,0.1,0,0\n", [], "line 3: column 'id' is empty"),
    "latitude_out_of_range": ("t,lat,lon\n0,45,7\n1,145,7\n", [], "column 'lat' is 145.0"),
    "gzip_truncated": (None, [], "damaged or truncated gzip data"),
}


@pytest.mark.parametrize("case", sorted(BAD_CASES_9))
def test_bad_input_9_one_line_exit_2_no_output(tmp_path, case):
    import gzip

    text, extra, message = BAD_CASES_9[case]
    inp = tmp_path / "in.csv"
    if text is None:
        inp.write_bytes(gzip.compress(GOOD.encode() * 20)[:-10])
    else:
        inp.write_text(text)
    args = extra if "-o" in extra else ["-o", tmp_path / "out.csv", *extra]
    r = run(inp, *args, cwd=tmp_path)
    lines = r.stderr.strip().splitlines()
    assert r.returncode == 2 and len(lines) == 1, r.stderr
    assert lines[0].startswith("lgekf track: error: ") and message in lines[0], lines[0]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["in.csv"]


def _rows(text):
    lines = text.strip().splitlines()
    return lines[0].split(","), [ln.split(",") for ln in lines[1:]]


def test_ids_007_and_7_are_two_objects(tmp_path):
    # before: ids were numbers, 007 == 7, and the merged track jumped 50 m between consecutive rows
    t = (0.1 * np.arange(6)).tolist()
    rows = []
    for k, tt in enumerate(t):
        rows.append(f"007,{tt!r},{1.0 * k},0")
        rows.append(f"7,{tt!r},{50.0 + 1.0 * k},0")
    rows += [f"9007199254740993,{tt!r},{k},5" for k, tt in enumerate(t)] + [f"9007199254740992,{tt!r},{k},-5" for k, tt in enumerate(t)]
    out = tmp_path / "o.csv"
    r = run(write(tmp_path, "in.csv", "id,t,x,y\n" + "\n".join(rows) + "\n"), "-o", out, "--model", "cv")
    assert r.returncode == 0, r.stderr
    assert "4 objects" in r.stdout
    _, data = read_out(out)
    assert list(dict.fromkeys(data[:, 0])) == ["007", "7", "9007199254740993", "9007199254740992"]
    for lab, x0, y in (("007", 0.0, 0.0), ("7", 50.0, 0.0), ("9007199254740993", 0.0, 5.0), ("9007199254740992", 0.0, -5.0)):
        mine = data[data[:, 0] == lab, 1:].astype(float)
        np.testing.assert_allclose(mine[:, 1], x0 + np.arange(6), atol=1e-6)  # a straight line, no jump
        np.testing.assert_allclose(mine[:, 2], y, atol=1e-6)


def test_time_unit_ms_equals_seconds_and_warnings(tmp_path):
    t = np.cumsum(np.full(20, 0.1))
    z = np.column_stack([1.5 * t, 0.2 * t])
    body = "".join(f"{a!r},{b!r},{c!r}\n" for a, b, c in zip(t.tolist(), z[:, 0].tolist(), z[:, 1].tolist()))
    body_ms = "".join(f"{round(a * 1000)},{b!r},{c!r}\n" for a, b, c in zip(t.tolist(), z[:, 0].tolist(), z[:, 1].tolist()))
    noise = ["--meas-std", "0.3", "--accel-std", "0.5,0.5,1"]  # fixed: the comparison below is of the time unit only
    r_s = run(write(tmp_path, "s.csv", "t,x,y\n" + body), "-o", tmp_path / "s_out.csv", *noise)
    assert r_s.returncode == 0 and "warning" not in r_s.stderr, r_s.stderr
    r_plain = run(write(tmp_path, "ms.csv", "t,x,y\n" + body_ms), "-o", tmp_path / "plain.csv", "--quiet")
    warn = [ln for ln in r_plain.stderr.splitlines() if "warning" in ln]
    assert r_plain.returncode == 0 and len(warn) == 1, r_plain.stderr  # shown even with --quiet
    assert warn[0].startswith("lgekf track: warning: the median time step is 100 s") and "--time-unit ms" in warn[0]
    r_ms = run(tmp_path / "ms.csv", "-o", tmp_path / "ms_out.csv", "--time-unit", "ms", *noise)
    assert r_ms.returncode == 0 and "warning" not in r_ms.stderr, r_ms.stderr
    _, a = read_out(tmp_path / "s_out.csv")
    _, b = read_out(tmp_path / "ms_out.csv")
    np.testing.assert_allclose(b[:, 1].astype(float), t, rtol=1e-12)  # written in seconds
    np.testing.assert_allclose(b[:, 2:].astype(float), a[:, 2:].astype(float), rtol=1e-8, atol=1e-10)


def test_degrees_in_x_y_and_huge_speeds_warn(tmp_path):
    t = 0.1 * np.arange(10)
    deg = "t,x,y\n" + "".join(f"{a!r},{11.5 + 1.3e-5 * a!r},48.1\n" for a in t.tolist())
    r = run(write(tmp_path, "deg.csv", deg), "-o", tmp_path / "o.csv")
    assert r.returncode == 0 and "lgekf track: warning: the median speed is" in r.stderr and "lon, lat" in r.stderr, r.stderr
    fast = "t,x,y\n" + "".join(f"{a!r},{3e6 * a!r},0\n" for a in t.tolist())
    r = run(write(tmp_path, "fast.csv", fast), "-o", tmp_path / "o.csv")
    assert r.returncode == 0 and "warning: the median speed is 3e+06 m/s" in r.stderr, r.stderr


def test_lat_lon_input_gives_metres_and_the_origin(tmp_path):
    # a straight walk north-east at 45° N; metres per degree written out here (see test_io) from WGS84's a, e²
    a, e2, phi = 6378137.0, 0.00669437999014, np.radians(45.0)
    per_lat = np.pi * a * (1 - e2) / (180 * (1 - e2 * np.sin(phi) ** 2) ** 1.5)
    per_lon = np.pi * a * np.cos(phi) / (180 * (1 - e2 * np.sin(phi) ** 2) ** 0.5)
    t = 0.5 * np.arange(12)
    lat = 45.0 + 1e-5 * t
    lon = 7.25 + 1e-5 * t
    text = "t,lat,lon\n" + "".join(f"{a!r},{b!r},{c!r}\n" for a, b, c in zip(t.tolist(), lat.tolist(), lon.tolist()))
    out = tmp_path / "o.csv"
    r = run(write(tmp_path, "ll.csv", text), "-o", out, "--model", "cv", "--precision", "17")
    assert r.returncode == 0, r.stderr
    note = [ln for ln in r.stderr.splitlines() if "projected" in ln]
    assert len(note) == 1 and "(45.0, 7.25)" in note[0] and "origin_lat, origin_lon" in note[0], r.stderr
    header, data = read_out(out)
    assert header[-3:] == ["origin_lat", "origin_lon", "flag"] and header[-4] == "nis"
    vals = data[:, 1:].astype(float)
    np.testing.assert_array_equal(vals[:, -3:-1], [[45.0, 7.25]] * len(t))
    np.testing.assert_allclose(vals[:, 1], 1e-5 * t * per_lon, atol=1e-6)  # x east, m (noise-free line: filter = truth)
    np.testing.assert_allclose(vals[:, 2], 1e-5 * t * per_lat, atol=1e-6)
    r = run(tmp_path / "ll.csv", "-o", tmp_path / "q.csv", "--quiet")
    assert r.returncode == 0 and r.stderr == "" and r.stdout == ""


def test_gzip_output_and_input(tmp_path):
    import gzip

    inp = write(tmp_path, "in.csv", GOOD)
    assert run(inp, "-o", tmp_path / "plain.csv", "--model", "all").returncode == 0
    r = run(inp, "-o", tmp_path / "z.csv.gz", "--model", "all")
    assert r.returncode == 0, r.stderr
    for m in MODELS:
        blob = (tmp_path / f"z_{m}.csv.gz").read_bytes()
        assert blob[:2] == b"\x1f\x8b"
        assert gzip.decompress(blob) == (tmp_path / f"plain_{m}.csv").read_bytes()
    assert not (tmp_path / "z.csv.gz").exists() and not list(tmp_path.glob("*.csv_*"))
    (tmp_path / "in.csv.gz").write_bytes(gzip.compress(GOOD.encode()))
    r = run(tmp_path / "in.csv.gz", "-o", tmp_path / "from_gz.csv", "--model", "cv")
    assert r.returncode == 0, r.stderr
    assert (tmp_path / "from_gz.csv").read_bytes() == (tmp_path / "plain_cv.csv").read_bytes()


def test_dash_is_stdin_and_stdout(tmp_path):
    inp = write(tmp_path, "in.csv", GOOD)
    assert run(inp, "-o", tmp_path / "file.csv", "--model", "ctrv").returncode == 0
    r = subprocess.run([*cli_command(), "track", "-", "-o", "-", "--model", "ctrv"], input=GOOD, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert r.stdout == (tmp_path / "file.csv").read_text()  # only the data on stdout
    assert "<stdout>: 4 rows" in r.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["file.csv", "in.csv"]


def test_closed_stdout_is_not_an_error(tmp_path):
    t = 0.1 * np.arange(3000)
    inp = write(tmp_path, "in.csv", "t,x,y\n" + "".join(f"{a!r},{a!r},0\n" for a in t.tolist()))
    p = subprocess.Popen([*cli_command(), "track", str(inp), "-o", "-", "--model", "cv"], stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    assert p.stdout.readline().startswith(b"id,t,")
    p.stdout.close()  # like `| head -1`
    err = p.stderr.read().decode()
    assert p.wait() == 141 and "Traceback" not in err and "error" not in err, err


@pytest.mark.parametrize("sep, extra", [(";", []), ("\t", []), (":", ["--delimiter", ":"]), (" ", ["--delimiter", "space"])])
def test_separators(tmp_path, sep, extra):
    inp = write(tmp_path, "in.csv", GOOD)
    assert run(inp, "-o", tmp_path / "ref.csv", "--model", "cv").returncode == 0
    other = write(tmp_path, "other.txt", GOOD.replace(",", sep))
    r = run(other, "-o", tmp_path / "o.csv", "--model", "cv", *extra)
    assert r.returncode == 0, r.stderr
    assert (tmp_path / "o.csv").read_bytes() == (tmp_path / "ref.csv").read_bytes()


def test_version():
    from importlib.metadata import version

    r = subprocess.run([*cli_command(), "--version"], capture_output=True, text=True)
    assert r.returncode == 0 and r.stdout == f"lgekf {version('lgekf')}\n"


def test_output_path_for_model_all():
    from pathlib import Path

    from lgekf.apps.track import output_path

    assert output_path(Path("d/tracks.csv"), "cv", True) == Path("d/tracks_cv.csv")
    assert output_path(Path("d/tracks.csv.gz"), "cv", True) == Path("d/tracks_cv.csv.gz")
    assert output_path(Path("tracks"), "ctrv", True) == Path("tracks_ctrv")
    assert output_path("-", "cv", False) == "-"


def _pose_file(tmp_path, heading_noise=0.02, seed=9):
    """A car on a circle of radius 20 m at 5 m/s, 10 Hz: positions with 0.5 m noise, heading with small noise."""
    rng = np.random.default_rng(seed)
    t = 0.1 * np.arange(150)
    a = 5.0 / 20.0 * t
    x, y = 20 * np.sin(a), 20 * (1 - np.cos(a))
    h = a + heading_noise * rng.standard_normal(t.size)
    zx, zy = x + 0.5 * rng.standard_normal(t.size), y + 0.5 * rng.standard_normal(t.size)
    rows = "".join(f"{ti!r},{xi!r},{yi!r},{hi!r}\n" for ti, xi, yi, hi in zip(t.tolist(), zx.tolist(), zy.tolist(), h.tolist()))
    return write(tmp_path, "poses.csv", "t,x,y,heading\n" + rows), np.column_stack([x, y, a])


@pytest.mark.parametrize("model", [m for m, s in MODELS.items() if "pose" in s.measurements])
def test_measure_pose_uses_the_heading_column(tmp_path, model):
    """--measure pose: the heading column is a measurement; the heading error drops well below the
    position-only run's (same file, same noise settings), and the output is the model's usual columns."""
    inp, truth = _pose_file(tmp_path)
    err = {}
    for measure in ("position", "pose"):
        out = tmp_path / f"{measure}.csv"
        r = run(inp, "-o", out, "--model", model, "--measure", measure, "--meas-std", "0.5", "--heading-std", "0.02",
                "--use-heading", "--quiet")
        assert r.returncode == 0, r.stderr
        cols, data = read_out(out)
        assert cols == output_columns(model)
        th = data[20:, cols.index(MODELS[model].state_names[2])].astype(float)
        err[measure] = np.sqrt(np.mean(((th - truth[20:, 2] + np.pi) % (2 * np.pi) - np.pi) ** 2))
    assert err["pose"] < 0.5 * err["position"] and err["pose"] < 0.03, err


def test_measure_pose_refused_for_cv_and_positions_for_cv_under_all(tmp_path):
    inp, _ = _pose_file(tmp_path)
    r = run(inp, "-o", tmp_path / "cv.csv", "--model", "cv", "--measure", "pose")
    assert r.returncode == 2 and r.stderr.count("\n") == 1 and "no heading" in r.stderr
    assert not (tmp_path / "cv.csv").exists()
    r = run(inp, "-o", tmp_path / "all.csv", "--model", "all", "--measure", "pose")
    assert r.returncode == 0, r.stderr
    assert "cv cannot take pose measurements: it gets position only" in r.stderr
    assert (tmp_path / "all_cv.csv").exists() and (tmp_path / "all_se2r2.csv").exists()


def test_measure_pose_needs_a_heading_column(tmp_path):
    r = run(write(tmp_path, "a.csv", GOOD), "-o", tmp_path / "o.csv", "--measure", "pose")
    assert r.returncode == 2 and r.stderr.count("\n") == 1 and "heading" in r.stderr
    assert not (tmp_path / "o.csv").exists()


# ------------------------------------------------------------------ issue #14: robust by default
def _noisy_tracks(tmp_path, sigma=0.5, n_obj=2, seed=0):
    rng = np.random.default_rng(seed)
    rows = []
    for j in range(n_obj):
        t = 0.2 * np.arange(150)
        z = np.column_stack([6.0 * t, 20.0 * np.sin(0.05 * t) + 10 * j]) + sigma * rng.standard_normal((150, 2))
        rows += [f"o{j},{a!r},{b!r},{c!r}" for a, b, c in zip(t.tolist(), z[:, 0].tolist(), z[:, 1].tolist())]
    return write(tmp_path, "in.csv", "id,t,x,y\n" + "\n".join(rows) + "\n")


def test_noise_from_the_data_is_said_and_options_override(tmp_path):
    inp = _noisy_tracks(tmp_path)
    r = run(inp, "-o", tmp_path / "a.csv", "--model", "cv")
    line = [ln for ln in r.stderr.splitlines() if ln.startswith("lgekf track: noise from the data: ")]
    assert r.returncode == 0 and len(line) == 1, r.stderr
    assert float(line[0].split("meas-std ")[1].split(" m")[0]) == pytest.approx(0.5, rel=0.15)
    assert "accel-std cv " in line[0] and "k = " in line[0]
    r = run(inp, "-o", tmp_path / "b.csv", "--model", "cv", "--quiet")
    assert r.returncode == 0 and r.stderr == "" and r.stdout == ""
    r = run(inp, "-o", tmp_path / "c.csv", "--model", "cv", "--meas-std", "0.45")
    assert "meas-std 0.45 m (given)" in r.stderr and "warning" not in r.stderr
    r = run(inp, "-o", tmp_path / "d.csv", "--model", "cv", "--meas-std", "0.45", "--accel-std", "0.8")
    assert "noise from the data" not in r.stderr
    _, d = read_out(tmp_path / "d.csv")  # run with exactly the given noise
    inp_rows = np.genfromtxt(inp, delimiter=",", skip_header=1, usecols=(1, 2, 3))
    cfg = TrackConfig({"cv": (0.8,)}, 0.45, heading_cap=TRACK_HEADING_CAP)
    x = track_monitored("cv", inp_rows[:150, 0], inp_rows[:150, 1:], np.array([0, 150]), cfg).x
    np.testing.assert_allclose(d[:150, 2:6].astype(float), x, rtol=1e-8, atol=1e-8)


def test_wrong_noise_is_warned_and_divergence_reported_once_per_object(tmp_path):
    inp = _noisy_tracks(tmp_path, sigma=1.0, n_obj=3, seed=2)
    r = run(inp, "-o", tmp_path / "o.csv", "--model", "ctrv", "--meas-std", "0.1", "--accel-std", "0.5,1")
    assert r.returncode == 0, r.stderr
    warn = [ln for ln in r.stderr.splitlines() if ln.startswith("lgekf track: warning: ")]
    assert "--meas-std 0.1 m is 0.095x the std estimated from the data (1.05 m)" in warn[0]
    div = [ln for ln in warn if "diverged at line " in ln and " (t = " in ln]
    assert sorted(ln.split("object ")[1].split(" ")[0] for ln in div) == ["o0", "o1", "o2"]
    assert all("re-initialised from its last measurements" in ln for ln in div)
    _, data = read_out(tmp_path / "o.csv")
    assert (data[:, -1] == "1").sum() > 0 and "rows flagged" in r.stdout
    r = run(inp, "-o", tmp_path / "n.csv", "--model", "ctrv", "--meas-std", "0.1", "--accel-std", "0.5,1", "--no-monitor")
    assert "diverged" not in r.stderr
    _, data = read_out(tmp_path / "n.csv")
    assert set(data[:, -1]) == {"0"}


def test_heading_cap_moves_lateral_uncertainty_to_the_body_velocity():
    # a slow object: the two-point heading is uncertain; with the cap its variance is cap² and the rest of
    # the lateral velocity variance is in v_y; models without side slip fold it back (their P0 unchanged)
    t = np.array([0.0, 0.5])
    z = np.array([[0.0, 0.0], [0.2, 0.1]])
    st = np.array([0, 2])
    c, var_pi = initial_common(t, z, st, 0.3)
    _, var_cap = initial_common(t, z, st, 0.3, heading_cap=0.3)
    var_v = 2 * 0.3**2 / 0.5**2
    speed2 = (0.2**2 + 0.1**2) / 0.25
    assert var_pi[0, 2] == pytest.approx(min(var_v / speed2, math.pi**2))
    assert var_cap[0, 2] == pytest.approx(0.09)
    assert var_cap[0, 4] == pytest.approx(var_v - speed2 * 0.09)
    for model, spec in MODELS.items():
        _, P_pi = initial_estimates(model, c, var_pi)
        _, P_cap = initial_estimates(model, c, var_cap)
        if "vy" in spec.state_names and spec.angles:  # heading + side-slip velocity: the heading keeps the cap
            assert P_cap[0, 2, 2] == pytest.approx(0.09)
        elif spec.angles:  # heading of motion: the same prior either way, but for the 10 % side-slip floor
            np.testing.assert_allclose(P_cap, P_pi, rtol=0.02, atol=1e-12)
