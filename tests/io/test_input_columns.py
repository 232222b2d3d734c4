"""Input columns (issue 27): columns named by the user, a warning naming the columns not read, ISO-8601 times, line
numbers kept with the rows, output digits chosen from the data, detections' time order. Each case a small file made
for it; the expected values come from the standard library (datetime) or are written out by hand."""

from __future__ import annotations

import datetime as dt

import numpy as np
import pytest

from lgekf.io import fastcsv, readers
from lgekf.io.cleaning import check_time_order, sort_by_time
from lgekf.io.formatting import data_digits, format_rows, label_bytes, output_digits
from lgekf.io.readers import DataError, named_columns, read_csv, unused_columns_warning
from lgekf.io.times import IsoError, iso_seconds


@pytest.fixture(scope="module", autouse=True)
def compiled_parser():
    fastcsv.warm()  # the fast path is taken (else read_csv reads every file with the general reader)


@pytest.fixture(params=["fast", "general"])
def reader(request, monkeypatch):
    """Each reading test by the fast parser and by the general reader."""
    if request.param == "general":
        monkeypatch.setattr(readers, "_read_csv_fast", lambda *a, **k: None)
    return request.param


def _utc(*args) -> float:
    return dt.datetime(*args, tzinfo=dt.timezone.utc).timestamp()


# ------------------------------------------------------------------------------------------ ISO-8601
def test_iso_seconds_of_every_accepted_form():
    texts = ["2024-05-01T12:00:00.125Z", "2024-05-01T12:00:00.125", "2024-05-01 12:00:00.125", "2024-05-01T14:00:00.125+02:00",
             "2024-05-01T07:00:00.125-0500", "2024-05-01T12:00:00z", "  2024-05-01T12:00Z ", "2024-05-01"]
    want = [_utc(2024, 5, 1, 12) + 0.125] * 5 + [_utc(2024, 5, 1, 12)] * 2 + [_utc(2024, 5, 1)]
    assert iso_seconds(texts).tolist() == want


def test_iso_seconds_keeps_microseconds_at_epoch_scale():
    got = iso_seconds(["2024-05-01T12:00:00.000001Z", "2024-05-01T12:00:00.999999Z"])
    assert abs(got[0] - (_utc(2024, 5, 1, 12) + 1e-6)) < 3e-7 and abs(got[1] - (_utc(2024, 5, 1, 12) + 0.999999)) < 3e-7


@pytest.mark.parametrize("bad, index", [(["2024-05-01T12:00:00Z", "noon"], 1), (["2024-13-01T00:00:00"], 0),
                                        (["2024-05-01T12:00:00Z", "1714564800"], 1)])
def test_iso_seconds_names_the_first_bad_value(bad, index):
    with pytest.raises(IsoError) as e:
        iso_seconds(bad)
    assert e.value.index == index and e.value.value == bad[index]


def test_read_csv_iso_t_column(tmp_path, reader):
    p = tmp_path / "iso.csv"
    p.write_text("id,timestamp,x,y\na,2024-05-01T12:00:00.125Z,1.5,2\n\na,2024-05-01T12:00:01.250Z,3,4\nb,2024-05-01T12:00:02Z,5,6\n")
    m = read_csv(p)
    assert m.time_iso and m.t.tolist() == [_utc(2024, 5, 1, 12) + 0.125, _utc(2024, 5, 1, 12, 0, 1) + 0.25, _utc(2024, 5, 1, 12, 0, 2)]
    assert m.line.tolist() == [2, 4, 5] and m.labels == ["a", "b"] and m.z.tolist() == [[1.5, 2], [3, 4], [5, 6]]


def test_read_csv_numeric_t_is_not_iso(tmp_path, reader):
    p = tmp_path / "epoch.csv"
    p.write_text("t,x,y\n1714564800.125,1,2\n1714564800.25,3,4\n")
    m = read_csv(p)
    assert not m.time_iso and m.t.tolist() == [1714564800.125, 1714564800.25]


@pytest.mark.parametrize("text, line, value", [("t,x,y\nnoon,1,2\n", 2, "noon"),
                                               ("t,x,y\n2024-05-01T12:00:00Z,1,2\n2024-05-01T12:00:01Z,1,2\nlater,3,4\n", 4, "later"),
                                               ("t,x,y\n1.0,1,2\n2024-05-01T12:00:00Z,1,2\n", 3, "2024-05-01T12:00:00Z")])
def test_a_t_that_is_neither_number_nor_iso_is_one_error_naming_line_and_value(tmp_path, reader, text, line, value):
    p = tmp_path / "bad.csv"
    p.write_text(text)
    with pytest.raises(DataError) as e:
        read_csv(p)
    msg = str(e.value)
    assert f"line {line}" in msg and repr(value) in msg and "ISO-8601" in msg and "--time-unit" in msg


# ------------------------------------------------------------------------------------------ named columns
def test_named_columns_replace_the_aliases(tmp_path, reader):
    p = tmp_path / "named.csv"
    p.write_text("vehicle;when;east;north;yaw_deg;x\nA;0.0;1;2;10;99\nB;0.5;3;4;20;99\nA;1.0;5;6;30;99\n")
    with named_columns({"id": "Vehicle", "t": "when", "x": "east", "y": "north", "heading": "yaw_deg"}):
        m = read_csv(p, use_heading=True)
    assert m.labels == ["A", "B"] and m.obj.tolist() == [0, 1, 0]
    assert m.t.tolist() == [0.0, 0.5, 1.0] and m.z.tolist() == [[1, 2], [3, 4], [5, 6]] and m.heading.tolist() == [10, 20, 30]
    assert m.unused == ()  # an id column was found: nothing to warn about


@pytest.mark.parametrize("key, option", [("id", "--id-column"), ("t", "--time-column"), ("x", "--x-column"),
                                         ("heading", "--heading-column")])
def test_a_named_column_that_is_absent_is_one_error_listing_the_header(tmp_path, reader, key, option):
    p = tmp_path / "plain.csv"
    p.write_text("t,x,y,speed\n0,1,2,3\n1,2,3,4\n")
    with named_columns({key: "nothere"}), pytest.raises(DataError) as e:
        read_csv(p, use_heading=key == "heading")
    assert f"{option} nothere: no such column; the header has: t, x, y, speed" in str(e.value)


def test_no_id_column_names_the_columns_not_read(tmp_path, reader):
    p = tmp_path / "vehicle.csv"
    p.write_text("vehicle,t,x,y,heading,lane\nc1,0,0,0,0,1\nc2,0.1,50,0,0,2\nc3,0.2,99,0,0,1\n")
    m = read_csv(p)
    assert m.n_objects == 1 and m.unused == ("vehicle", "lane")  # heading: a known column, not "unrecognised"
    w = unused_columns_warning(m)
    assert "all 3 rows are read as one object" in w and "'vehicle', 'lane'" in w and "--id-column" in w
    with named_columns({"id": "vehicle"}):
        m = read_csv(p)
    assert m.n_objects == 3 and unused_columns_warning(m) is None


# ------------------------------------------------------------------------------------------ Parquet
def test_parquet_timestamps_iso_text_and_row_numbers(tmp_path):
    pa = pytest.importorskip("pyarrow")
    pq = pytest.importorskip("pyarrow.parquet")
    from lgekf.io.parquet import read_parquet

    base = dt.datetime(2024, 5, 1, 12)
    stamps = pa.array([base, base + dt.timedelta(milliseconds=125)], pa.timestamp("us"))
    pq.write_table(pa.table({"car": ["a", "a"], "when": stamps, "x": [1.0, 2.0], "y": [3.0, 4.0]}), tmp_path / "ts.parquet")
    with named_columns({"id": "car", "t": "when"}):
        m = read_parquet(tmp_path / "ts.parquet")
    assert m.t.tolist() == [_utc(2024, 5, 1, 12), _utc(2024, 5, 1, 12) + 0.125] and m.labels == ["a"] and m.line_word == "row"
    pq.write_table(pa.table({"t": ["2024-05-01T12:00:00Z", "2024-05-01T12:00:01Z"], "x": [1.0, 2.0], "y": [3.0, 4.0]}),
                   tmp_path / "iso.parquet")
    assert read_parquet(tmp_path / "iso.parquet").t.tolist() == [_utc(2024, 5, 1, 12), _utc(2024, 5, 1, 12, 0, 1)]
    pq.write_table(pa.table({"t": [0.0, 1.0, 2.0], "x": [1.0, float("nan"), 2.0], "y": [3.0, 4.0, 5.0]}), tmp_path / "nan.parquet")
    with pytest.raises(DataError, match=r"nan.parquet row 2: column 'x' is nan"):
        read_parquet(tmp_path / "nan.parquet")


# ------------------------------------------------------------------------------------------ lines and where()
def test_where_names_the_line_or_the_row(tmp_path, reader):
    p = tmp_path / "lines.csv"
    p.write_text("id,t,x,y\nb,0,0,0\na,0,1,1\n\nb,1,2,2\na,1,3,3\n")
    g, starts, _ = read_csv(p).grouped()
    assert [g.where(k) for k in range(4)] == ["line 2", "line 5", "line 3", "line 6"]


# ------------------------------------------------------------------------------------------ output digits
def test_data_digits_by_hand():
    assert data_digits(1e9, 1e-4, 10) == 14  # 1000000000.0001
    assert data_digits(5e6, 1e-4, 10) == 11  # 5000000.0001
    assert data_digits(1.7e9, 1e-6, 15) == 16  # epoch seconds to 1 µs
    assert data_digits(120.0, 1e-4, 10) == 10  # small values: the default
    assert data_digits(1e20, 1e-4, 10) == 17  # at most 17


def test_positions_near_1e9_and_epoch_times_are_written_to_0_1_mm_and_1_us():
    rng = np.random.default_rng(0)
    x = 1e9 + rng.uniform(0, 1000, 200)
    y = 5e6 + rng.uniform(0, 1000, 200)
    t = 1714564800.0 + np.round(rng.uniform(0, 1e4, 200), 6)
    cols = ["x", "y", "vx"]
    digits, t_digits = output_digits(cols, None, np.column_stack([x, y]), t)
    assert digits.tolist() == [14, 14, 10] and t_digits == 16
    text = format_rows(label_bytes(["o"]), np.zeros(200, np.int64), t, np.column_stack([x, y, x]), digits, t_digits).decode()
    back = np.array([[float(v) for v in line.split(",")[1:]] for line in text.splitlines()])
    assert np.max(np.abs(back[:, 1] - x)) <= 5e-5 and np.max(np.abs(back[:, 2] - y)) <= 5e-5
    assert np.max(np.abs(back[:, 0] - t)) <= 5e-7
    assert np.max(np.abs(back[:, 3] - x)) > 0.1  # vx: 10 digits, as before (the test can see the difference)
    given, _ = output_digits(cols, 10, np.column_stack([x, y]), t)  # --precision given: every column gets it
    assert given.tolist() == [10, 10, 10]


# ------------------------------------------------------------------------------------------ detections' time order
def test_detections_time_order_check_and_sort(tmp_path, reader):
    p = tmp_path / "det.csv"
    p.write_text("t,x,y\n0,0,0\n0,5,5\n1,1,1\n0.5,9,9\n1,2,2\n")
    m = read_csv(p)
    with pytest.raises(DataError, match=r"det.csv line 5: time goes back \(t = 0.5 after t = 1.0 on line 4\).*--sort"):
        check_time_order(m)
    s, moved = sort_by_time(m)
    assert moved == 2 and s.t.tolist() == [0, 0, 0.5, 1, 1] and s.line.tolist() == [2, 3, 5, 4, 6]
    check_time_order(s)  # rows of equal time (a scan) are in order
