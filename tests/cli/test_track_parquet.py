"""`lgekf track` with Parquet in and out (optional extra `parquet`: pyarrow)."""

import sys
from types import SimpleNamespace

import numpy as np
import pytest

from lgekf.cli import main

pa = pytest.importorskip("pyarrow", reason="pyarrow not installed (the optional extra lgekf[parquet])")
pq = pytest.importorskip("pyarrow.parquet")


@pytest.fixture
def run(capsys):
    """`lgekf track ARGS` in this process (the kernels stay loaded): returncode and stderr."""

    def go(*args):
        capsys.readouterr()
        rc = main(["track", *map(str, args)])
        return SimpleNamespace(returncode=rc, stderr=capsys.readouterr().err)

    return go


def _data(n_obj=3, K=40, seed=1):
    rng = np.random.default_rng(seed)
    rows = []
    for o in range(n_obj):
        t = np.cumsum(rng.uniform(0.08, 0.12, K))
        th = 0.2 * o + 0.3 * t
        x = np.cumsum(4 * np.cos(th) * 0.1) + 0.1 * rng.standard_normal(K)
        y = np.cumsum(4 * np.sin(th) * 0.1) + 0.1 * rng.standard_normal(K)
        rows += [(f"car {o}", a, b, c) for a, b, c in zip(t.tolist(), x.tolist(), y.tolist())]
    rows.sort(key=lambda r: r[1])  # interleaved in time
    return rows


def _csv(path, rows):
    path.write_text("id,t,x,y\n" + "".join(f"{i},{t!r},{x!r},{y!r}\n" for i, t, x, y in rows))


def _parquet(path, rows, id_type=pa.string()):
    ids = [r[0] for r in rows]
    if pa.types.is_integer(id_type):
        ids = [int(i.split()[1]) for i in ids]
    pq.write_table(pa.table({"id": pa.array(ids, id_type), "t": [r[1] for r in rows], "x": [r[2] for r in rows],
                             "y": [r[3] for r in rows]}), path)


def test_parquet_input_gives_the_csv_output_byte_for_byte(tmp_path, run):
    rows = _data()
    _csv(tmp_path / "in.csv", rows)
    _parquet(tmp_path / "in.parquet", rows)
    for src in ("in.csv", "in.parquet"):
        r = run(tmp_path / src, "-o", tmp_path / f"{src}.out.csv", "--meas-std", "0.1", "--accel-std", "0.5,0.5,1", "--quiet")
        assert r.returncode == 0, r.stderr
    assert (tmp_path / "in.csv.out.csv").read_bytes() == (tmp_path / "in.parquet.out.csv").read_bytes()


def test_integer_ids_read_as_their_text(tmp_path, run):
    rows = _data()
    _parquet(tmp_path / "in.pq", rows, pa.int64())
    r = run(tmp_path / "in.pq", "-o", tmp_path / "o.csv", "--model", "cv", "--meas-std", "0.1", "--accel-std", "0.5", "--quiet")
    assert r.returncode == 0, r.stderr
    ids = {line.split(",")[0] for line in (tmp_path / "o.csv").read_text().splitlines()[1:]}
    assert ids == {"0", "1", "2"}


def test_parquet_output_holds_the_csv_numbers(tmp_path, run):
    """Same columns as the CSV; numbers exact float64 (the CSV has them to --precision 17 digits, t to 15)."""
    rows = _data()
    _csv(tmp_path / "in.csv", rows)
    r = run(tmp_path / "in.csv", "-o", tmp_path / "o.csv", "--precision", "17", "--model", "all", "--quiet")
    assert r.returncode == 0, r.stderr
    r = run(tmp_path / "in.csv", "-o", tmp_path / "o.parquet", "--model", "all", "--quiet")
    assert r.returncode == 0, r.stderr
    for model in ("se2se2", "cv"):
        table = pq.read_table(tmp_path / f"o_{model}.parquet")
        lines = (tmp_path / f"o_{model}.csv").read_text().splitlines()
        header = lines[0].split(",")
        assert table.column_names == header
        assert table.schema.field("id").type == pa.string() and table.schema.field("flag").type == pa.int8()
        body = [line.split(",") for line in lines[1:]]
        assert table.column("id").to_pylist() == [b[0] for b in body]
        csv_numbers = np.array([[float(v) for v in b[1:]] for b in body])
        pq_numbers = np.column_stack([table.column(c).to_numpy().astype(float) for c in header[1:]])
        np.testing.assert_allclose(pq_numbers[:, 0], csv_numbers[:, 0], rtol=1e-14, atol=0)  # t: 15 digits in CSV
        np.testing.assert_array_equal(pq_numbers[:, 1:], csv_numbers[:, 1:])  # 17 digits round-trip float64 exactly


@pytest.mark.parametrize("case, args, message", [
    ("delimiter", ["--delimiter", ";"], "--delimiter: only for CSV input"),
    ("pedestrian", ["--format", "pedestrian", "--frame-dt", "0.4"], "is a Parquet file"),
])
def test_parquet_input_refuses_csv_options(tmp_path, run, case, args, message):
    _parquet(tmp_path / "in.parquet", _data())
    r = run(tmp_path / "in.parquet", "-o", tmp_path / "o.csv", *args)
    assert r.returncode == 2 and message in r.stderr and len(r.stderr.strip().splitlines()) == 1, r.stderr
    assert not (tmp_path / "o.csv").exists()


def test_bad_parquet_is_one_line_and_no_output(tmp_path, run):
    (tmp_path / "in.parquet").write_bytes(b"this is not parquet\n")
    r = run(tmp_path / "in.parquet", "-o", tmp_path / "o.parquet")
    assert r.returncode == 2 and "cannot read as Parquet" in r.stderr and len(r.stderr.strip().splitlines()) == 1, r.stderr
    assert list(tmp_path.iterdir()) == [tmp_path / "in.parquet"]
    pq.write_table(pa.table({"stamp": [0.0, 0.1], "x": [0.0, 1.0], "y": [0.0, 0.0]}), tmp_path / "cols.parquet")
    r = run(tmp_path / "cols.parquet", "-o", tmp_path / "o.csv")
    assert r.returncode == 2 and "missing column 't'" in r.stderr, r.stderr


def test_without_pyarrow_one_line_naming_the_extra(tmp_path, run, monkeypatch):
    """pyarrow hidden: a one-line error naming the extra, before any work, and no output."""
    _csv(tmp_path / "in.csv", _data())
    monkeypatch.setitem(sys.modules, "pyarrow", None)  # `import pyarrow` raises ImportError
    monkeypatch.setitem(sys.modules, "pyarrow.parquet", None)
    r = run(tmp_path / "in.csv", "-o", tmp_path / "o.parquet")
    assert r.returncode == 2, r.stderr
    assert r.stderr.strip() == f'lgekf track: error: --output {tmp_path / "o.parquet"}: Parquet needs pyarrow: pip install "lgekf[parquet]"'
    assert sorted(p.name for p in tmp_path.iterdir()) == ["in.csv"]
