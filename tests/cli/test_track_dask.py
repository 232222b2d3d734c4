"""`lgekf track` and `lgekf evaluate` with `--workers`/`--scheduler`: partitions of whole objects, and output
files equal to the single-process run byte for byte (CSV and Parquet input, gzip in and out, pose, lat/lon,
every model); bad input still gives one line, exit 2 and no output."""

from __future__ import annotations

import math
import subprocess

import numpy as np
import pytest
from _cli import cli_command

from lgekf.apps.evaluate_dask import track_ranges
from lgekf.apps.track_dask import _divisions
from lgekf.core.registry import MODELS

pytestmark = pytest.mark.slow  # Dask clusters start in seconds each; the quick loop skips them, CI runs them

pytest.importorskip("distributed")


# On a cluster `track` takes the noise as given (the estimate from the data pools every object in one
# process); both runs of every comparison get the same given noise, for every model.
NOISE = ("--meas-std", "0.3", *[a for m, s in MODELS.items() for a in ("--accel-std", f"{m}=" + ",".join(map(str, s.default_accel_std)))])


def run(cmd, *args, cwd):
    args = [*map(str, args)]
    if cmd == "track" and "--meas-std" not in args:
        args += NOISE
    return subprocess.run([*cli_command(), cmd, *args], capture_output=True, text=True, cwd=cwd)


def detections(n_obj=30, seed=5, blank_after=40):
    """Objects of 2-25 rows, interleaved in time as a detector writes them; ids of mixed form; a blank line."""
    rng = np.random.default_rng(seed)
    rows = []
    for i in range(n_obj):
        n = int(rng.integers(2, 26))
        t = rng.uniform(0, 10) + np.cumsum(rng.uniform(0.05, 0.3, n))
        th = rng.uniform(-3, 3) + 0.15 * np.arange(n)
        x = np.cumsum(1.5 * np.cos(th)) + rng.normal(0, 0.3, n)
        y = np.cumsum(1.5 * np.sin(th)) + rng.normal(0, 0.3, n)
        h = th + rng.normal(0, 0.05, n)
        lab = f"car {i:02d}" if i % 3 else f"00{i}"
        rows += [(float(a), lab, float(b), float(c), float(d)) for a, b, c, d in zip(t, x, y, h)]
    rows.sort(key=lambda r: r[0])
    lines = ["time,id,x,y,yaw"] + [f"{t!r},{i},{x!r},{y!r},{h!r}" for t, i, x, y, h in rows]
    lines.insert(blank_after, "")
    return "\n".join(lines) + "\n", rows


@pytest.fixture(scope="module")
def data(tmp_path_factory):
    d = tmp_path_factory.mktemp("trackdask")
    text, rows = detections()
    (d / "det.csv").write_text(text)
    return d, rows


def same_files(a, b):
    assert a.read_bytes() == b.read_bytes(), f"{a} and {b} differ"


def test_every_model_equals_the_single_process_output_with_local_workers(data, tmp_path):
    d, rows = data
    for sub in ("one", "dask"):
        (tmp_path / sub).mkdir()
    r = run("track", d / "det.csv", "-o", tmp_path / "one" / "t.csv", "--model", "all", "--quiet", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    r = run("track", d / "det.csv", "-o", tmp_path / "dask" / "t.csv", "--model", "all", "--workers", 2, "--partition-rows", 40,
            cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    partitions = int(r.stderr.split(" partitions of whole objects")[0].split()[-1])
    assert partitions >= 5  # several input blocks and several output partitions
    for m in MODELS:
        same_files(tmp_path / "one" / f"t_{m}.csv", tmp_path / "dask" / f"t_{m}.csv")
    assert f"t_se2se2.csv: {len(rows)} rows, 30 objects (se2se2)" in r.stdout


@pytest.mark.parametrize("options", [
    ["--model", "se2r2", "--measure", "pose", "--full-cov", "--precision", "17"],
    ["--model", "ctrv", "--use-heading", "--meas-std", "0.2", "--accel-std", "0.3,0.8", "--time-unit", "ms"],
])
def test_options_and_gzip_equal_the_single_process_output(data, tmp_path, dask_scheduler, options):
    d, _ = data
    for sub in ("one", "dask"):
        (tmp_path / sub).mkdir()
    r = run("track", d / "det.csv", "-o", tmp_path / "one" / "t.csv.gz", *options, "--quiet", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    r = run("track", d / "det.csv", "-o", tmp_path / "dask" / "t.csv.gz", *options, "--scheduler", dask_scheduler,
            "--partition-rows", 64, "--quiet", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    same_files(tmp_path / "one" / "t.csv.gz", tmp_path / "dask" / "t.csv.gz")


def test_gzip_and_parquet_input(data, tmp_path, dask_scheduler):
    import gzip

    import pandas as pd

    d, _ = data
    (tmp_path / "det.csv.gz").write_bytes(gzip.compress((d / "det.csv").read_bytes()))
    df = pd.read_csv(d / "det.csv", dtype={"id": str})
    df.to_parquet(tmp_path / "det.parquet", row_group_size=50)
    r = run("track", d / "det.csv", "-o", tmp_path / "one.csv", "--model", "cv", "--quiet", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    for name in ("det.csv.gz", "det.parquet"):
        r = run("track", tmp_path / name, "-o", tmp_path / f"{name}.out.csv", "--model", "cv", "--scheduler", dask_scheduler,
                "--partition-rows", 50, "--quiet", cwd=tmp_path)
        assert r.returncode == 0, r.stderr
        same_files(tmp_path / "one.csv", tmp_path / f"{name}.out.csv")


def test_latitude_longitude_input(data, tmp_path, dask_scheduler):
    _, rows = data
    text = "t,id,lat,lon\n" + "".join(f"{t!r},{i},{45 + y / 111000!r},{7 + x / 80000!r}\n" for t, i, x, y, _ in rows)
    (tmp_path / "ll.csv").write_text(text)
    one = run("track", "ll.csv", "-o", "one.csv", "--model", "se2r3", cwd=tmp_path)
    many = run("track", "ll.csv", "-o", "many.csv", "--model", "se2r3", "--scheduler", dask_scheduler, "--partition-rows", 60,
               cwd=tmp_path)
    assert one.returncode == 0 and many.returncode == 0, many.stderr
    same_files(tmp_path / "one.csv", tmp_path / "many.csv")
    note = [ln for ln in one.stderr.splitlines() if "projected" in ln]
    assert note and note[0] in many.stderr  # the same origin and scale error


def test_3d_latitude_longitude_altitude_and_quaternion_input(data, tmp_path, dask_scheduler):
    """3-D space on a cluster: lat, lon, alt (east, north, up of the first fix) and the attitude as a quaternion
    (a rotation by the yaw h about z, (cos h/2, 0, 0, sin h/2), which --use-heading starts ct3 from): the same bytes as one
    process, partitions of whole objects, the same projection line."""
    _, rows = data
    text = "t,id,lat,lon,alt,qw,qx,qy,qz\n" + "".join(
        f"{t!r},{i},{45 + y / 111000!r},{7 + x / 80000!r},{300 + 0.2 * x!r},{math.cos(h / 2)!r},0,0,{math.sin(h / 2)!r}\n"
        for t, i, x, y, h in rows)
    (tmp_path / "lla.csv").write_text(text)
    args = ("--model", "ct3", "--use-heading", "--meas-std", "0.3", "--accel-std", "0.5,1,0.5")
    one = run("track", "lla.csv", "-o", "one.csv", *args, cwd=tmp_path)
    many = run("track", "lla.csv", "-o", "many.csv", *args, "--scheduler", dask_scheduler, "--partition-rows", 60, cwd=tmp_path)
    assert one.returncode == 0 and many.returncode == 0, many.stderr
    same_files(tmp_path / "one.csv", tmp_path / "many.csv")
    with open(tmp_path / "many.csv") as f:
        assert f.readline().rstrip().endswith("nis,origin_lat,origin_lon,origin_alt,flag")
    note = [ln for ln in one.stderr.splitlines() if "projected" in ln]
    assert note and "lat, lon, alt projected" in note[0] and note[0] in many.stderr
    assert "partitions" in many.stderr


def test_unit_warning_from_the_sample(tmp_path, dask_scheduler):
    text = "t,x,y\n" + "".join(f"{1000 * k},{0.5 * k},0\n" for k in range(20))  # milliseconds
    (tmp_path / "ms.csv").write_text(text)
    r = run("track", "ms.csv", "-o", "o.csv", "--scheduler", dask_scheduler, "--quiet", cwd=tmp_path)
    assert r.returncode == 0
    assert "warning: the median time step is 1000 s: if t is in milliseconds, add --time-unit ms" in r.stderr


BAD = {
    "single": ("id,t,x,y\n1,0,0,0\n1,0.1,0.3,0\n2,0,5,5\n", [], "object id 2 (line 4) has a single measurement"),
    "number": ("t,x,y\n0,0,0\n0.1,abc,0\n0.2,0.6,0\n", [], "line 3: column 'x': 'abc' is not a number"),
    "underscore": ("t,x,y\n0,0,0\n0.1,1_0,0\n0.2,0.6,0\n", [], "line 3: column 'x': '1_0' is not a number"),
    "nan": ("t,x,y\n0,0,0\n0.1,nan,0\n0.2,0.6,0\n", [], "line 3: column 'x' is nan; NaN and infinite values are not allowed"),
    "time": ("t,x,y\n0,0,0\n0.2,0.3,0\n0.1,0.6,0\n", [], "line 4: time is not increasing within object id 0"),
    "header_only": ("t,x,y\n", [], "no measurements"),
    "missing_column": ("t,x\n0,1\n1,2\n", [], "missing column 'y'"),
    "empty_id": ("id,t,x,y\n1,0,0,0\n,0.1,0.3,0\n1,0.2,0.3,0\n", [], "line 3: column 'id' is empty"),
    "stdin": ("t,x,y\n0,0,0\n0.1,0.3,0\n", ["-"], "give a file name, not stdin"),
    "pedestrian": ("0 1 0 0\n10 1 1 0\n", ["--format", "pedestrian", "--frame-dt", "0.04"], "--format pedestrian: not with --workers"),
    "partition_rows": ("t,x,y\n0,0,0\n0.1,0.3,0\n", ["--partition-rows", "1"], "--partition-rows: must be at least 2"),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_input_one_line_exit_2_no_output(tmp_path, dask_scheduler, case):
    text, extra, message = BAD[case]
    (tmp_path / "in.csv").write_text(text)
    inp = "-" if extra[:1] == ["-"] else "in.csv"
    r = subprocess.run([*cli_command(), "track", inp, "-o", "out.csv", *extra[1 if inp == "-" else 0:], "--scheduler", dask_scheduler,
                        *NOISE],
                       input=text, capture_output=True, text=True, cwd=tmp_path)
    assert r.returncode == 2, r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("lgekf track: error: ") and message in lines[0], r.stderr
    assert sorted(p.name for p in tmp_path.iterdir()) == ["in.csv"]


def test_divisions_keep_objects_whole_and_balance_rows():
    counts = np.array([5, 1, 9, 3, 3, 2, 8, 4, 4, 2])
    for rows in (1, 4, 7, 10, 100):
        div = _divisions(counts, rows)
        assert div[0] == 0 and div[-1] == len(counts) - 1 and div == sorted(set(div))
        bounds = div[:-1] + [len(counts)]
        sizes = [int(counts[a:b].sum()) for a, b in zip(bounds, bounds[1:])]
        assert sum(sizes) == counts.sum()
        assert max(sizes) <= max(rows, counts.max()) + counts.max()  # at most one object over the target
    assert _divisions(np.array([3]), 2) == [0, 0]


def test_track_ranges_are_whole_tracks_in_order():
    starts = np.array([0, 5, 6, 15, 18, 21, 23, 31, 35, 39, 41])
    for parts in (1, 2, 3, 5, 10, 50):
        ranges = track_ranges(starts, parts)
        assert ranges[0][0] == 0 and ranges[-1][1] == 10 and len(ranges) <= min(parts, 10)
        assert all(a < b for a, b in ranges) and all(b == c for (_, b), (c, _) in zip(ranges, ranges[1:]))


def evaluate_csv(path):
    rng = np.random.default_rng(2)
    lines = ["t,x,y,id,vx,vy"]
    for i in range(14):
        n = int(rng.integers(6, 30))
        th = rng.uniform(-3, 3) + 0.05 * np.arange(n)
        v = rng.uniform(0.5, 2.0)
        x, y = np.cumsum(0.4 * v * np.cos(th)), np.cumsum(0.4 * v * np.sin(th))
        vals = np.column_stack([0.4 * np.arange(n), x, y, v * np.cos(th), v * np.sin(th)]).tolist()  # Python floats: repr exact
        lines += [f"{t!r},{a!r},{b!r},p{i},{c!r},{e!r}" for t, a, b, c, e in vals]
    path.write_text("\n".join(lines) + "\n")


@pytest.mark.parametrize("tune", [False, pytest.param(True, marks=pytest.mark.slow)])
def test_evaluate_equals_the_single_process_run(tmp_path, dask_scheduler, tune):
    evaluate_csv(tmp_path / "walk.csv")
    extra = ["--tune", "--tune-method", "grid"] if tune else []
    one = run("evaluate", "walk.csv", "--out", "one", "--seeds", 2, "--no-figure", "--quiet", *extra, cwd=tmp_path)
    assert one.returncode == 0, one.stderr
    many = run("evaluate", "walk.csv", "--out", "many", "--seeds", 2, "--no-figure", "--quiet", "--scheduler", dask_scheduler,
               "--partition-rows", 60, *extra, cwd=tmp_path)
    assert many.returncode == 0, many.stderr
    names = ["per_track.csv", "summary.csv"] + (["tuning.csv"] if tune else [])
    assert sorted(p.name for p in (tmp_path / "many").iterdir()) == sorted(names + ["meta.json"])
    for name in names:
        same_files(tmp_path / "one" / name, tmp_path / "many" / name)


def test_evaluate_with_local_workers(tmp_path):
    evaluate_csv(tmp_path / "walk.csv")
    one = run("evaluate", "walk.csv", "--out", "one", "--seeds", 1, "--no-figure", "--quiet", cwd=tmp_path)
    many = run("evaluate", "walk.csv", "--out", "many", "--seeds", 1, "--no-figure", "--quiet", "--workers", 2, cwd=tmp_path)
    assert one.returncode == 0 and many.returncode == 0, many.stderr
    same_files(tmp_path / "one" / "summary.csv", tmp_path / "many" / "summary.csv")


@pytest.mark.parametrize("sep, option", [("\t", ["--delimiter", "tab"]), (";", []), (" ", ["--delimiter", "space"])])
def test_other_separators(data, tmp_path, dask_scheduler, sep, option):
    d, _ = data
    text = (d / "det.csv").read_text().replace("car ", "car_").replace(",", sep)  # ids without spaces
    (tmp_path / "in.txt").write_text(text)
    one = run("track", "in.txt", "-o", "one.csv", "--model", "cv", "--quiet", *option, cwd=tmp_path)
    many = run("track", "in.txt", "-o", "many.csv", "--model", "cv", "--quiet", *option, "--scheduler", dask_scheduler,
               "--partition-rows", 80, cwd=tmp_path)
    assert one.returncode == 0 and many.returncode == 0, many.stderr
    same_files(tmp_path / "one.csv", tmp_path / "many.csv")


def test_cluster_run_needs_the_noise_given(tmp_path, dask_scheduler):
    """The noise estimate pools every object of the file, so on a cluster `track` asks for the noise."""
    (tmp_path / "in.csv").write_text("t,x,y\n0,0,0\n0.1,0.3,0\n0.2,0.6,0\n")
    r = subprocess.run([*cli_command(), "track", "in.csv", "-o", "out.csv", "--model", "cv", "--scheduler", dask_scheduler],
                       capture_output=True, text=True, cwd=tmp_path)
    assert r.returncode == 2 and r.stderr.count("\n") == 1 and "give the noise (--meas-std and --accel-std for cv)" in r.stderr
    assert not (tmp_path / "out.csv").exists()
