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
from lgekf.track import TrackConfig, initial_common, initial_estimates, output_columns, track_arrays




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
                      "std_x", "std_y", "std_theta", "std_vx", "std_vy", "std_omega", "nis"]
    assert data.shape == (4, len(header))
    vals = data[:, 1:].astype(float)
    np.testing.assert_allclose(vals[0, 1:3], [0, 0])  # row 0: the first measurement
    np.testing.assert_allclose(vals[:2, 3:7], [[0, 3, 0, 0]] * 2, atol=1e-12)  # two-point velocity (3, 0), heading 0
    np.testing.assert_allclose(vals[:2, 7:9], 0.2)  # position std = meas std
    assert np.isnan(vals[:2, -1]).all() and np.isfinite(vals[2:, -1]).all()


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
        cov = unpack(vals[:, 1 + 2 * n:-1], n)
        np.testing.assert_allclose(std**2, np.diagonal(cov, axis1=1, axis2=2), rtol=1e-8)
    assert not (tmp_path / "tracks.csv").exists()


def _x0_P0(model, t, z, r):
    c, var = initial_common(t, z, np.array([0, len(t)]), r)
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
    r = run(inp, "-o", out, "--model", model, "--accel-std", q, "--meas-std", "0.15", "--precision", "17", "--full-cov")
    assert r.returncode == 0, r.stderr
    _, data = read_out(out)
    vals = data[:, 1:].astype(float)
    n = MODELS[model].n
    x0, P0 = _x0_P0(model, t, z, 0.15)
    xs, Ps, nis = filter_batch(model, z[None, 2:], dt=np.diff(t)[None, 1:], accel_std=[float(v) for v in q.split(",")],
                               meas_std=0.15, x0=x0, P0=P0, return_cov=True, return_nis=True)
    np.testing.assert_allclose(vals[:, 0], t, rtol=1e-14)
    np.testing.assert_allclose(vals[2:, 1:1 + n], xs[0], rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(unpack(vals[2:, 1 + 2 * n:-1], n), Ps[0], rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(vals[2:, -1], nis[0], rtol=1e-12, atol=1e-12)
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
    r = run(write(tmp_path, "in.csv", text), "-o", out, "--model", "ctrv", "--precision", "17")
    assert r.returncode == 0, r.stderr
    _, data = read_out(out)
    first = [data[0, 0]] + [data[i, 0] for i in range(1, len(data)) if data[i, 0] != data[i - 1, 0]]
    assert first == sorted(per, key=lambda k: per[k][0][0])  # objects in order of first appearance
    cfg = TrackConfig()
    for lab, (t, z) in per.items():
        mine = data[data[:, 0] == lab, 1:].astype(float)
        x, p, nis = track_arrays("ctrv", t, z, np.array([0, len(t)]), cfg)
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
