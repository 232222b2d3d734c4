"""lgekf.io.mapped: a mapped file parsed in segments gives fastcsv.parse's result bit for bit (rows, line numbers,
objects in order of first appearance across segments, the numbers left to numpy), and read_csv reads a file
the same way mapped or not."""

import numpy as np
import pytest

import lgekf.io.fastcsv as fastcsv
import lgekf.io.readers as readers
from lgekf.io.mapped import MappedFile, parse_mapped


@pytest.fixture(scope="module", autouse=True)
def compiled_parser():
    fastcsv.warm()


def _text(rng, n_rows=6000, n_ids=5000):
    """Interleaved ids (more than the first hash table holds), blank lines, CRLF lines, long numbers, no final LF."""
    lines = ["id,t,x,y"]
    ids = rng.integers(0, n_ids, n_rows)
    for k, o in enumerate(ids):
        x = rng.standard_normal()
        xs = f"{x:.20g}" if k % 7 == 0 else f"{x:.6f}"  # 20 digits: parsed by numpy afterwards (hard_values)
        end = "\r" if k % 11 == 0 else ""
        lines.append(f"o{o:05d} ,{0.1 * k:.3f},{xs},{1e-3 * k:.4e}{end}")
        if k % 97 == 0:
            lines.append("")
    return "\n".join(lines)


@pytest.mark.parametrize("segment", [64, 1000, 1 << 20])
@pytest.mark.parametrize("threads", [1, 2])
def test_segments_give_the_result_of_parse(tmp_path, monkeypatch, segment, threads):
    monkeypatch.setattr(fastcsv, "_cpus", lambda: threads)
    p = tmp_path / "in.csv"
    p.write_bytes(_text(np.random.default_rng(segment)).encode())
    data = p.read_bytes()
    start = data.find(b"\n") + 1
    want = fastcsv.parse(data, start, 44, [1, 2, 3], 0, 2)
    mf = MappedFile(p)
    try:
        got = parse_mapped(mf, start, 44, [1, 2, 3], 0, 2, segment_bytes=segment)
    finally:
        mf.close()
    assert got[0] == want[0] == fastcsv.OK
    assert got[6] == want[6]
    for a, b in zip(got[1:6], want[1:6]):
        assert a.shape == b.shape
        assert np.array_equal(a.view(np.int64) if a.dtype == float else a, b.view(np.int64) if b.dtype == float else b)
    assert want[5].shape[0] > 0 and want[4].shape[0] > 2048  # what this test is about: hard numbers, more ids than a 4096-slot table holds at load 1/2


def test_read_csv_mapped_or_read_whole(tmp_path, monkeypatch):
    p = tmp_path / "in.csv"
    p.write_bytes(_text(np.random.default_rng(3), n_rows=3000, n_ids=40).encode())
    monkeypatch.setattr(readers, "MAP_MIN_BYTES", 1 << 40)
    whole = readers.read_csv(p)
    monkeypatch.setattr(readers, "MAP_MIN_BYTES", 0)
    import lgekf.io.mapped as mapped

    monkeypatch.setattr(mapped, "SEGMENT_BYTES", 500)
    seg = readers.read_csv(p)
    for name in ("t", "z", "obj", "line"):
        assert np.array_equal(getattr(seg, name), getattr(whole, name)), name
    assert seg.labels == whole.labels and seg.labels[0] == "o" + seg.labels[0][1:]


def test_every_segment_is_released_once_parsed(tmp_path):
    p = tmp_path / "in.csv"
    p.write_bytes(_text(np.random.default_rng(5), n_rows=400, n_ids=30).encode())
    data = p.read_bytes()
    start = data.find(b"\n") + 1
    mf = MappedFile(p)
    released = []
    mf.release = lambda a, b: released.append((a, b))
    try:
        parse_mapped(mf, start, 44, [1, 2, 3], 0, 2, segment_bytes=1000)
    finally:
        mf.close()
    import lgekf.io.mapped as mapped

    segs = mapped._segments(np.frombuffer(data, np.uint8), start, 1000)
    n = len(segs)
    assert n > 5 and segs[0][0] == start and segs[-1][1] == len(data)
    assert all(b1 == a2 for (_, b1), (a2, _) in zip(segs, segs[1:]))  # the whole body, in pieces
    assert released[:n] == segs  # after counting each segment's lines
    assert sorted(released[n:2 * n]) == segs  # after parsing each (two threads: any order)


def test_track_output_the_same_mapped_and_whole(tmp_path, monkeypatch):
    """lgekf track: the same bytes when the input is mapped in segments."""
    import lgekf.io.mapped as mapped
    from lgekf.cli.track import cmd_track

    rng = np.random.default_rng(8)
    rows = []
    for o in range(30):
        t = np.cumsum(rng.uniform(0.08, 0.12, 25)) + rng.uniform(0, 1)
        x, y = 3 * t + 0.1 * rng.standard_normal(25), np.sin(t) + 0.1 * rng.standard_normal(25)
        rows += [(tk, f"{o},{tk!r},{xk!r},{yk!r}") for tk, xk, yk in zip(t.tolist(), x.tolist(), y.tolist())]
    rows.sort()  # objects interleaved in time
    (tmp_path / "in.csv").write_text("id,t,x,y\n" + "\n".join(r for _, r in rows) + "\n")
    args = [str(tmp_path / "in.csv"), "--model", "cv", "--quiet"]
    monkeypatch.setattr(readers, "MAP_MIN_BYTES", 1 << 40)
    assert cmd_track([*args, "-o", str(tmp_path / "whole.csv")]) == 0
    monkeypatch.setattr(readers, "MAP_MIN_BYTES", 0)
    monkeypatch.setattr(mapped, "SEGMENT_BYTES", 300)
    assert cmd_track([*args, "-o", str(tmp_path / "mapped.csv")]) == 0
    assert (tmp_path / "mapped.csv").read_bytes() == (tmp_path / "whole.csv").read_bytes()


@pytest.mark.parametrize("k, ix, iy", [(2, 0, 1), (2, 1, 0), (3, 1, 2), (3, 2, 0), (5, 4, 1)])
def test_positions_moved_within_the_buffer(k, ix, iy):
    """read_csv's fast path puts x, y into the first 2N numbers of the parsed rows' own buffer, block by block."""
    vals = np.random.default_rng(k + ix).standard_normal((1001, k))
    want = vals[:, [ix, iy]].copy()
    z = readers._positions_in_place(vals, ix, iy, block=7)
    assert np.shares_memory(z, vals) and z.flags.c_contiguous
    assert np.array_equal(z, want)


@pytest.mark.parametrize("k, ix, iy", [(2, 1, 0), (3, 1, 2), (5, 4, 1)])
def test_positions_buffer_shrunk_to_them(k, ix, iy):
    """The parser's rows are a prefix view of a larger buffer (blank lines leave room): x, y end up in that buffer
    shrunk to exactly the N x 2 positions (its other columns' memory returned), with the same numbers."""
    buf = np.random.default_rng(k).standard_normal((1200, k))
    vals = buf[:1001]
    want = vals[:, [ix, iy]].copy()
    del buf
    z = readers._positions_in_place(vals, ix, iy, block=7)
    del vals
    assert z.base is None and z.flags.owndata and z.shape == (1001, 2) and z.nbytes == 1001 * 2 * 8
    assert np.array_equal(z, want)


@pytest.mark.parametrize("rows", [1, 2, 5])
@pytest.mark.parametrize("whole", [True, False])
def test_parsed_columns_do_not_share_the_shrunk_buffer(tmp_path, monkeypatch, rows, whole):
    """After the parsed buffer is shrunk to the positions, t, heading and the extra columns are copies of their
    own (a view into the returned third would read freed memory), in both the whole-file and the mapped path."""
    if not whole:
        monkeypatch.setattr(readers, "MAP_MIN_BYTES", 0)
    p = tmp_path / "m.csv"
    p.write_text("id,t,x,y,heading,speed\n" + "".join(f"a,{i}.5,{i}.25,-{i}.75,0.{i},{i}.125\n" for i in range(rows)))
    m = readers.read_csv(p, use_heading=True, extra=("speed",))
    assert m.z.tolist() == [[i + 0.25, -(i + 0.75)] for i in range(rows)]
    assert m.t.tolist() == [i + 0.5 for i in range(rows)] and m.extra["speed"].tolist() == [i + 0.125 for i in range(rows)]
    assert m.heading.tolist() == [float(f"0.{i}") for i in range(rows)]
    for v in (m.t, m.heading, m.extra["speed"]):
        assert not np.shares_memory(v, m.z)
