"""lgekf.io and lgekf.files: readers (columns, ids as text, separators, lat/lon, gzip, stdin, line numbers in
errors), the numba number formatter, atomic (and gzip) writes, output names."""

import numpy as np
import pytest

from lgekf.io.files import AtomicFiles
from lgekf.io.formatting import format_g, format_rows, label_bytes, write_rows_made
from lgekf.io.readers import DataError, parse_delimiter, read_csv, read_pedestrian


def write(tmp_path, name, text):
    p = tmp_path / name
    p.write_text(text)
    return p


def test_csv_columns_aliases_blank_lines_and_quotes(tmp_path):
    p = write(tmp_path, "a.csv", 'Timestamp, X ,y,extra\n0,1,2,a\n\n   \n"0.5",1.5,2.5,b\n')
    m = read_csv(p)
    np.testing.assert_array_equal(m.t, [0.0, 0.5])
    np.testing.assert_array_equal(m.z, [[1, 2], [1.5, 2.5]])
    np.testing.assert_array_equal(m.line, [2, 5])
    assert m.labels == ["0"] and m.heading is None


def test_csv_ids_numeric_and_text_in_order_of_first_appearance(tmp_path):
    m = read_csv(write(tmp_path, "a.csv", "id,t,x,y\n7,0,0,0\n3,0,1,1\n7,1,0,0\n3.5,0,2,2\n"))
    assert m.labels == ["7", "3", "3.5"]
    np.testing.assert_array_equal(m.obj, [0, 1, 0, 2])
    m = read_csv(write(tmp_path, "b.csv", "t,x,y,id\n0,0,0,car b\n0,1,1,ped\n1,0,0,car b\n"))
    assert m.labels == ["car b", "ped"]
    np.testing.assert_array_equal(m.obj, [0, 1, 0])


def test_text_ids_after_the_first_chunk(tmp_path, monkeypatch):
    import lgekf.io.readers as lio

    monkeypatch.setattr(lio, "CHUNK_LINES", 2)
    m = read_csv(write(tmp_path, "a.csv", "id,t,x,y\n1,0,0,0\n1,1,0,0\nbob,0,0,0\nbob,1,0,0\n"))
    assert m.labels == ["1", "bob"]
    np.testing.assert_array_equal(m.line, [2, 3, 4, 5])


def test_grouped_sorts_by_object_and_checks_time(tmp_path):
    m = read_csv(write(tmp_path, "a.csv", "id,t,x,y\n1,0,0,0\n2,0,5,5\n1,1,1,0\n2,0.5,6,5\n1,3,2,0\n"))
    g, starts, dropped = m.grouped()
    np.testing.assert_array_equal(starts, [0, 3, 5])
    np.testing.assert_array_equal(g.t, [0, 1, 3, 0, 0.5])
    np.testing.assert_array_equal(g.line, [2, 4, 6, 3, 5])
    assert dropped == []
    bad = read_csv(write(tmp_path, "b.csv", "id,t,x,y\n1,0,0,0\n2,0,5,5\n1,1,1,0\n2,0.5,6,5\n1,1,2,0\n"))
    with pytest.raises(DataError, match=r"line 6: time is not increasing within object id 1"):
        bad.grouped()


def test_grouped_short_objects(tmp_path):
    m = read_csv(write(tmp_path, "a.csv", "id,t,x,y\n1,0,0,0\n2,0,5,5\n1,1,1,0\n"))
    with pytest.raises(DataError, match=r"object id 2 \(line 3\) has a single measurement"):
        m.grouped()
    g, starts, dropped = m.grouped(drop_short=True)
    assert dropped == ["2"] and g.labels == ["1"]
    np.testing.assert_array_equal(starts, [0, 2])


@pytest.mark.parametrize(
    "text, message",
    [
        ("", "empty file"),
        ("t,x,y\n", "no measurements"),
        ("t,x\n0,1\n", "missing column 'y'"),
        ("0,1,2\n1,2,3\n", "looks like data"),
        ("t,x,y\n0,1,2\n1,abc,3\n", "line 3: column 'x': 'abc' is not a number"),
        ("t,x,y\n0,1,2\n1,,3\n", "line 3: column 'x': '(empty)' is not a number"),
        ("t,x,y\n0,1,2\n1,2\n", "line 3: expected at least 3 columns"),
        ("t,x,y\n0,1,2\n1,nan,3\n", "line 3: column 'x' is nan"),
        ("t,x,y\n0,1,2\n1,2,-inf\n", "line 3: column 'y' is -inf"),
        ("t,x,y,t\n0,1,2,3\n", "more than one column for 't'"),
    ],
)
def test_csv_errors_name_the_problem(tmp_path, text, message):
    with pytest.raises(DataError, match=message.replace("(", r"\(").replace(")", r"\)")):
        read_csv(write(tmp_path, "bad.csv", text))


def test_heading_only_when_asked(tmp_path):
    p = write(tmp_path, "h.csv", "t,x,y,heading\n0,0,0,oops\n1,1,0,0.5\n")
    assert read_csv(p).heading is None  # ignored, not even parsed
    with pytest.raises(DataError, match="column 'heading': 'oops'"):
        read_csv(p, use_heading=True)
    with pytest.raises(DataError, match="needs a 'heading' column"):
        read_csv(write(tmp_path, "n.csv", "t,x,y\n0,0,0\n"), use_heading=True)


def test_unreadable_paths(tmp_path):
    with pytest.raises(DataError, match="cannot read"):
        read_csv(tmp_path / "missing.csv")
    with pytest.raises(DataError, match="is a directory"):
        read_csv(tmp_path)


def test_pedestrian_format(tmp_path):
    p = write(tmp_path, "p.txt", "780\t1.0\t8.46\t3.59\n790\t1.0\t9.57\t3.79\n790  2.0  1 2\n")
    m = read_pedestrian(p, 0.04)
    np.testing.assert_allclose(m.t, [31.2, 31.6, 31.6])
    assert m.labels == ["1", "2"]
    with pytest.raises(DataError, match="frame-dt"):
        read_pedestrian(p, None)
    with pytest.raises(DataError, match="frame-dt"):
        read_pedestrian(p, -1.0)
    with pytest.raises(DataError, match="line 1: column 'frame': 't' is not a number"):
        read_pedestrian(write(tmp_path, "q.txt", "t x y id\n"), 0.04)


@pytest.mark.parametrize("p", [1, 3, 6, 10, 15])
def test_format_g_matches_python(p):
    rng = np.random.default_rng(p)
    v = np.concatenate([
        rng.standard_normal(3000) * 10.0 ** rng.integers(-5, 9, 3000),
        [1.0, 0.5, 9.99999999999, 1e-5, 1e-4, 123456789012.0, 0.1 + 0.2, 1e16, -2.5e-7],
    ])
    assert format_g(v, p) == ["%.*g" % (p, x) for x in v]


def test_format_g_round_trips_at_17_digits_and_specials():
    rng = np.random.default_rng(0)
    v = rng.standard_normal(5000) * 10.0 ** rng.integers(-30, 30, 5000)
    back = np.array([float(s) for s in format_g(v, 17)])
    np.testing.assert_allclose(back, v, rtol=4e-16, atol=0)
    assert format_g([np.nan, np.inf, -np.inf, 0.0, -0.0], 10) == ["nan", "inf", "-inf", "0", "0"]


def test_format_rows_quotes_labels():
    lab = label_bytes(["a", 'b,"c"'])
    text = format_rows(lab, [0, 1], [0.5, 1.0], np.array([[1.0, 2.0], [3.0, np.nan]]), 6).decode()
    assert text == 'a,0.5,1,2\n"b,""c""",1,3,nan\n'


@pytest.mark.parametrize("cpus", [1, 3])
@pytest.mark.parametrize("n", [0, 1, 6, 7, 8, 50])
def test_rows_made_part_by_part_are_format_rows_bytes(monkeypatch, cpus, n):
    """Parts of 7 rows made by a callable, formatted in threads, written in order: the bytes of one call."""
    import io

    import lgekf.io.formatting as formatting

    monkeypatch.setattr(formatting, "PART_ROWS", 7)
    monkeypatch.setattr(formatting, "_cpus", lambda: cpus)
    rng = np.random.default_rng(n)
    lab = label_bytes(["a", "b,c", "d"])
    obj = rng.integers(0, 3, n)
    t = np.cumsum(rng.uniform(0.0, 1.0, n))
    values = rng.standard_normal((n, 4)) * 10.0 ** rng.integers(-5, 5, (n, 4))
    asked = []

    def values_of(lo, hi):
        asked.append((lo, hi))
        return values[lo:hi]

    out = io.BytesIO()
    write_rows_made(out, lab, obj, t, values_of, n, [3, 10, 17, 6])
    assert out.getvalue() == format_rows(lab, obj, t, values, [3, 10, 17, 6])
    assert asked == [(lo, min(lo + 7, n)) for lo in range(0, n, 7)]  # each part made once, in order


def test_rows_made_with_a_wrong_shape_or_a_failing_part(monkeypatch):
    import io

    import lgekf.io.formatting as formatting

    monkeypatch.setattr(formatting, "PART_ROWS", 4)
    monkeypatch.setattr(formatting, "_cpus", lambda: 2)
    lab = label_bytes(["a"])
    obj, t = np.zeros(20, dtype=np.int64), np.arange(20.0)
    with pytest.raises(ValueError, match=r"values_of\(0, 4\): expected 4 rows of values, got shape \(3, 2\)"):
        write_rows_made(io.BytesIO(), lab, obj, t, lambda lo, hi: np.ones((3, 2)), 20, 6)
    with pytest.raises(ValueError, match="expected 20 rows"):
        write_rows_made(io.BytesIO(), lab, obj[:19], t, lambda lo, hi: np.ones((hi - lo, 2)), 20, 6)

    def failing(lo, hi):
        if lo == 8:
            raise OSError("disk gone")
        return np.ones((hi - lo, 2))

    out = io.BytesIO()
    with pytest.raises(OSError, match="disk gone"):
        write_rows_made(out, lab, obj, t, failing, 20, 6)
    # at most the parts before it (those already formatted when it failed), whole lines, nothing of it or after it
    assert format_rows(lab, obj[:8], t[:8], np.ones((8, 2)), 6).startswith(out.getvalue())
    assert out.getvalue().count(b"\n") in (0, 4, 8) and out.getvalue()[-1:] in (b"", b"\n")
    with pytest.raises(ValueError, match="digits: must be between 1 and 17"):  # also with no rows to format
        write_rows_made(io.BytesIO(), lab, obj[:0], t[:0], lambda lo, hi: np.ones((hi - lo, 2)), 0, 0)
    with pytest.raises(ValueError, match=r"values_of\(4, 8\): 3 columns, the first part had 2"):
        write_rows_made(io.BytesIO(), lab, obj, t, lambda lo, hi: np.ones((hi - lo, 2 if lo == 0 else 3)), 20, 6)


@pytest.mark.parametrize("cpus", [1, 2])
def test_rows_made_with_a_failing_formatter_or_write(monkeypatch, cpus):
    """An error in a formatting thread or in fh.write reaches the caller; what was written is whole parts, in order."""
    import io

    import lgekf.io.formatting as formatting

    monkeypatch.setattr(formatting, "PART_ROWS", 4)
    monkeypatch.setattr(formatting, "_cpus", lambda: cpus)
    lab = label_bytes(["a"])
    obj, t, vals = np.zeros(20, dtype=np.int64), np.arange(20.0), np.arange(40.0).reshape(20, 2)
    full = format_rows(lab, obj, t, vals, 6)
    real = formatting._format_rows

    def formatter(lab_bytes, lab_off, row_lab, tt, t_digits, v, d):
        if tt[0] == 12.0:  # the part of rows 12..15
            raise RuntimeError("formatter failed")
        return real(lab_bytes, lab_off, row_lab, tt, t_digits, v, d)

    monkeypatch.setattr(formatting, "_format_rows", formatter)
    out = io.BytesIO()
    with pytest.raises(RuntimeError, match="formatter failed"):
        write_rows_made(out, lab, obj, t, lambda lo, hi: vals[lo:hi], 20, 6)
    assert full.startswith(out.getvalue()) and out.getvalue().count(b"\n") in (0, 4, 8, 12)
    monkeypatch.setattr(formatting, "_format_rows", real)

    class Full(io.BytesIO):
        def write(self, b):
            if self.tell() > 0:
                raise OSError("no space left")
            return super().write(b)

    out = Full()
    with pytest.raises(OSError, match="no space left"):
        write_rows_made(out, lab, obj, t, lambda lo, hi: vals[lo:hi], 20, 6)
    assert out.getvalue() == format_rows(lab, obj[:4], t[:4], vals[:4], 6)  # the first part only


@pytest.mark.parametrize("n", [5, 64, 1001])
def test_format_rows_in_threads_is_one_part(monkeypatch, n):
    """format_rows / write_rows cut the rows into PARTS_PER_THREAD parts per thread (PARALLEL_ROWS rows a thread):
    the bytes of one call on one thread, parts in order."""
    import io

    import lgekf.io.formatting as formatting
    from lgekf.io.formatting import write_rows

    rng = np.random.default_rng(n)
    lab = label_bytes(["x", "y"])
    obj, t, vals = rng.integers(0, 2, n), np.cumsum(rng.uniform(0, 1, n)), rng.standard_normal((n, 3))
    monkeypatch.setattr(formatting, "_cpus", lambda: 1)
    one = format_rows(lab, obj, t, vals, 8)
    monkeypatch.setattr(formatting, "PARALLEL_ROWS", 2)
    monkeypatch.setattr(formatting, "_cpus", lambda: 3)
    assert len(formatting._formatted_parts(lab, obj, t, vals, 8, 15)) == (3 * formatting.PARTS_PER_THREAD if n >= 6 else 2 * formatting.PARTS_PER_THREAD)
    assert format_rows(lab, obj, t, vals, 8) == one
    out = io.BytesIO()
    write_rows(out, lab, obj, t, vals, 8)
    assert out.getvalue() == one


def test_atomic_files_all_or_nothing(tmp_path):
    paths = [tmp_path / "a.csv", tmp_path / "b.csv"]
    with pytest.raises(RuntimeError):
        with AtomicFiles(paths) as f:
            f.open(0).write(b"x")
            raise RuntimeError("boom")
    assert list(tmp_path.iterdir()) == []
    with AtomicFiles(paths) as f:
        f.open(0).write(b"x")
        f.open(1).write(b"y")
        f.commit()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.csv", "b.csv"]


# ------------------------------------------------------------------ ids, separators, lat/lon, gzip, stdin
def test_ids_are_text_compared_as_written(tmp_path):
    # numeric parsing merged 007 with 7 and, above 2**53, 9007199254740993 with 9007199254740992
    text = ("id,t,x,y\n007,0,0,0\n7,0,50,0\n007,1,1,0\n7,1,51,0\n"
            "9007199254740993,0,0,5\n9007199254740992,0,0,9\n9007199254740993,1,1,5\n9007199254740992,1,1,9\n")
    m = read_csv(write(tmp_path, "a.csv", text))
    assert m.labels == ["007", "7", "9007199254740993", "9007199254740992"]
    np.testing.assert_array_equal(m.obj, [0, 1, 0, 1, 2, 3, 2, 3])
    m = read_csv(write(tmp_path, "b.csv", "id,t,x,y\n1.0,0,0,0\n1,0,0,0\n 1.0 ,1,0,0\n"))
    assert m.labels == ["1.0", "1"]  # surrounding spaces do not count, the text does
    np.testing.assert_array_equal(m.obj, [0, 1, 0])


def test_empty_id_is_an_error(tmp_path):
    with pytest.raises(DataError, match=r"line 3: column 'id' is empty"):
        read_csv(write(tmp_path, "a.csv", "id,t,x,y\n1,0,0,0\n,1,0,0\n"))


@pytest.mark.parametrize("sep", [";", "\t", "|", "  "])
def test_separator_found_from_the_header(tmp_path, sep):
    text = sep.join(["t", "x", "y", "id"]) + "\n" + "\n".join(sep.join(r) for r in [["0", "1.5", "2", "a"], ["1", "2.5", "3", "a"]]) + "\n"
    m = read_csv(write(tmp_path, "a.csv", text))
    np.testing.assert_array_equal(m.z, [[1.5, 2], [2.5, 3]])
    assert m.labels == ["a"]


def test_given_delimiter_and_the_hint_when_none_fits(tmp_path):
    p = write(tmp_path, "a.csv", "t:x:y\n0:1:2\n1:2:3\n")
    with pytest.raises(DataError, match=r"the header has: t:x:y \(if the columns are separated by something other than .* give --delimiter\)"):
        read_csv(p)
    np.testing.assert_array_equal(read_csv(p, delimiter=parse_delimiter(":")).z, [[1, 2], [2, 3]])
    assert parse_delimiter("tab") == "\t" and parse_delimiter("space") is None and parse_delimiter(None) == "auto"
    with pytest.raises(DataError, match="--delimiter"):
        parse_delimiter("::")


def test_decimal_comma_gets_a_hint(tmp_path):
    with pytest.raises(DataError, match=r"line 2: column 'x': '1,5' is not a number \(a decimal comma\?"):
        read_csv(write(tmp_path, "a.csv", "t;x;y\n0;1,5;2\n"))


def test_lat_lon_projected_about_the_first_row(tmp_path):
    # metres per degree on WGS84 written out here (not taken from lgekf.io.geo), with the published
    # a = 6378137 m and e² = 0.00669437999014: latitude π a (1 - e²) / (180 (1 - e² sin²φ)^1.5),
    # longitude π a cos φ / (180 (1 - e² sin²φ)^0.5); at 45°: 111 131.8 m and 78 846.8 m (the tables' values)
    a, e2, phi = 6378137.0, 0.00669437999014, np.radians(45.0)
    per_lat = np.pi * a * (1 - e2) / (180 * (1 - e2 * np.sin(phi) ** 2) ** 1.5)
    per_lon = np.pi * a * np.cos(phi) / (180 * (1 - e2 * np.sin(phi) ** 2) ** 0.5)
    assert round(per_lat, 1) == 111131.8 and round(per_lon, 1) == 78846.8
    text = "t,latitude,lon,id\n0,45.0,7.0,a\n1,45.001,7.0,a\n2,45.0,7.002,b\n3,45.0,7.0,b\n"
    m = read_csv(write(tmp_path, "a.csv", text))
    assert m.origin == (45.0, 7.0)
    np.testing.assert_allclose(m.z[:, 1], [0, 0.001 * per_lat, 0, 0], rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(m.z[:, 0], [0, 0, 0.002 * per_lon, 0], rtol=1e-9, atol=1e-9)
    both = read_csv(write(tmp_path, "b.csv", "t,x,y,lat,lon\n0,1,2,45,7\n"))  # x, y win when both are there
    assert both.origin is None and both.z.tolist() == [[1, 2]]
    with pytest.raises(DataError, match=r"line 3: column 'lat' is 91.0, not in \[-90, 90\] degrees"):
        read_csv(write(tmp_path, "c.csv", "t,lat,lon\n0,45,7\n1,91,7\n"))
    with pytest.raises(DataError, match="missing column 'lon'"):
        read_csv(write(tmp_path, "d.csv", "t,lat,long_name\n0,45,7\n"))


def test_gzip_input_recognised_by_content(tmp_path):
    import gzip

    text = "id,t,x,y\n1,0,0,0\n1,1,1,0\n"
    for name in ("a.csv.gz", "a_gzip_named.csv"):
        (tmp_path / name).write_bytes(gzip.compress(text.encode()))
        m = read_csv(tmp_path / name)
        np.testing.assert_array_equal(m.z, [[0, 0], [1, 0]])
    (tmp_path / "p.txt.gz").write_bytes(gzip.compress(b"780 1 0 0\n790 1 1 0\n"))
    assert read_pedestrian(tmp_path / "p.txt.gz", 0.04).t.tolist() == pytest.approx([31.2, 31.6])
    (tmp_path / "cut.csv.gz").write_bytes(gzip.compress((text * 50).encode())[:-12])
    with pytest.raises(DataError, match="cut.csv.gz: damaged or truncated gzip data"):
        read_csv(tmp_path / "cut.csv.gz")


@pytest.mark.parametrize("compress", [False, True])
def test_dash_reads_stdin(monkeypatch, compress):
    import gzip
    import io
    import sys

    data = b"t,x,y\n0,0,0\n1,1,0\n"
    raw = io.BufferedReader(io.BytesIO(gzip.compress(data) if compress else data))
    monkeypatch.setattr(sys, "stdin", io.TextIOWrapper(raw))
    m = read_csv("-")
    assert m.source == "<stdin>"
    np.testing.assert_array_equal(m.z, [[0, 0], [1, 0]])
    assert not raw.closed  # stdin is not closed by the reader


def test_atomic_files_gzip_by_name_and_reproducible(tmp_path):
    import gzip

    payload = b"id,t\n" + b"a,1\n" * 1000
    blobs = []
    for k in range(2):
        with AtomicFiles([tmp_path / "a.csv.gz", tmp_path / "b.csv"]) as f:
            f.open(0).write(payload)
            f.open(1).write(payload)
            f.commit()
        blobs.append((tmp_path / "a.csv.gz").read_bytes())
    assert blobs[0][:2] == b"\x1f\x8b" and gzip.decompress(blobs[0]) == payload
    assert blobs[0] == blobs[1]  # no time stamp in the gzip header
    assert (tmp_path / "b.csv").read_bytes() == payload
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.csv.gz", "b.csv"]


@pytest.mark.parametrize("name, message", [(".", "names a folder"), ("out/", "names a folder"), ("..", "names a folder"),
                                           ("missing/x.csv", "the output folder missing does not exist")])
def test_output_names_that_are_not_files(tmp_path, monkeypatch, name, message):
    from lgekf.io.files import check_output_path

    monkeypatch.chdir(tmp_path)
    with pytest.raises(ValueError, match=message):
        check_output_path(name)
    with pytest.raises(ValueError, match="is an existing folder"):
        check_output_path(str(tmp_path))
