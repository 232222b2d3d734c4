"""read_csv's numba fast path (lgekf.io.fastcsv): numbers bit for bit as Python's float (random and edge values),
and on every unusual or bad input exactly what the general reader gives (the same Measurements or the same
one-line error)."""

import gzip

import numpy as np
import pytest

import lgekf.io.fastcsv as fastcsv
import lgekf.io.mapped as mapped
import lgekf.io.readers as readers
from lgekf.io.fastcsv import group_order
from lgekf.io.readers import DataError, read_csv


@pytest.fixture(scope="module", autouse=True)
def compiled_parser():
    """The parser compiled in this process (on a cold cache read_csv would use the general reader)."""
    fastcsv.warm()


@pytest.fixture(params=["one part", "two parts", "mapped segments"], autouse=True)
def parts(request, monkeypatch):
    """Every test three ways: the body parsed in one piece, split in two halves parsed in two threads, and
    (``lgekf.io.mapped``) the file mapped and parsed in segments of a few lines, two threads at a time."""
    if request.param == "two parts":
        monkeypatch.setattr(fastcsv, "PARALLEL_BYTES", 8)
        monkeypatch.setattr(fastcsv, "_cpus", lambda: 2)
    if request.param == "mapped segments":
        monkeypatch.setattr(readers, "MAP_MIN_BYTES", 0)
        monkeypatch.setattr(mapped, "SEGMENT_BYTES", 97)
        monkeypatch.setattr(fastcsv, "_cpus", lambda: 2)
    return request.param


def general(path, **kw):
    """read_csv by the general (numpy.loadtxt) reader only."""
    saved = readers._read_csv_fast
    readers._read_csv_fast = lambda *a, **k: None
    try:
        return readers.read_csv(path, **kw)
    finally:
        readers._read_csv_fast = saved


def outcome(read, path, **kw):
    """Measurements (as plain data) or the DataError text of one reader, including the grouping step."""
    try:
        m = read(path, **kw)
        g, starts, _ = m.grouped()
    except DataError as e:
        return ("error", str(e))
    return ("ok", m.t.view(np.int64).tolist(), m.z.view(np.int64).tolist(), m.obj.tolist(), m.labels, m.line.tolist(),
            None if m.heading is None else m.heading.view(np.int64).tolist(), starts.tolist(), g.line.tolist(), m.origin)


def _bits(a):
    return np.asarray(a, dtype=float).view(np.int64)


def _number_texts(rng, n):
    """Decimal texts of many shapes: 1-25 significant digits, exponents up to ±330, signs, leading and
    trailing zeros, integers, '.5', '5.', upper-case E."""
    out = []
    for _ in range(n):
        kind = rng.integers(8)
        v = float(rng.standard_normal() * 10.0 ** rng.integers(-12, 13))
        if kind == 0:
            s = f"%.{rng.integers(1, 18)}g" % v
        elif kind == 1:
            s = repr(v)
        elif kind == 2:
            s = f"%.{rng.integers(0, 12)}f" % v
        elif kind == 3:  # random digit strings, long ones too
            digits = "".join(rng.choice(list("0123456789"), rng.integers(1, 26)))
            cut = rng.integers(0, len(digits) + 1)
            s = ("-" if rng.random() < 0.5 else "") + digits[:cut] + "." + digits[cut:]
            if s.endswith(".") and cut == 0:
                s += "0"
            if s in (".", "-."):
                s = "0"
        elif kind == 4:
            s = f"{rng.integers(1, 10**15)}e{rng.integers(-330, 310)}"
        elif kind == 5:
            s = f"%.{rng.integers(0, 17)}E" % (v * 10.0 ** rng.integers(-280, 280))
        elif kind == 6:
            s = str(int(rng.integers(-10**12, 10**12)))
        else:
            s = "+" + ("0" * int(rng.integers(0, 4))) + f"{abs(v):.6f}" + "0" * int(rng.integers(0, 8))
        if abs(float(s)) < float("inf"):  # infinite values are an error of their own (tested below)
            out.append(s)
    return out


def test_numbers_bit_for_bit_as_python_float(tmp_path):
    rng = np.random.default_rng(7)
    texts = _number_texts(rng, 30000)
    texts += ["0", "-0", "0.0", "-0.0", "1e22", "1e23", "9007199254740993", "123456789012345", "1234567890123456",
              "0.1", "0.3", "2.2250738585072014e-308", "4.9e-324", "1.7976931348623157e308", "5e-324", "1e-400",
              ".5", "5.", "-.5e-3", "+7", "0.000000000000000000000000001", "100000000000000000000000", "1E5"]
    rows = [f"{i},{' ' * (i % 3)}{s}{chr(9) if i % 5 == 0 else ''},{s}" for i, s in enumerate(texts)]
    p = tmp_path / "n.csv"
    p.write_text("t,x,y\n" + "\n".join(rows) + "\n")
    fast = readers._read_csv_fast(p, str(p), False, (), "auto")
    assert fast is not None, "the fast path refused valid numbers"
    expect = np.array([float(s) for s in texts])
    np.testing.assert_array_equal(_bits(fast.z[:, 0]), _bits(expect))
    np.testing.assert_array_equal(_bits(fast.z[:, 1]), _bits(expect))
    np.testing.assert_array_equal(_bits(fast.t), _bits(np.arange(len(texts), dtype=float)))
    # and numpy's loadtxt (the general reader) gives the same doubles
    slow = general(p)
    np.testing.assert_array_equal(_bits(fast.z), _bits(slow.z))


def test_same_as_general_reader_on_a_large_interleaved_file(tmp_path):
    rng = np.random.default_rng(3)
    n = 20000
    ids = rng.integers(0, 3000, n)
    t = np.sort(rng.uniform(0, 100, n))
    lines = [f"{i}{' ' if k % 7 == 0 else ''},{tt:.9g},{x:.9g},{float(y)!r}" for k, (i, tt, x, y) in
             enumerate(zip(ids, t, rng.standard_normal(n) * 300, rng.standard_normal(n)))]
    p = tmp_path / "big.csv"
    p.write_text("id,t,x,y\n" + "\n".join(lines) + "\n")
    assert readers._read_csv_fast(p, str(p), False, (), "auto") is not None
    assert outcome(read_csv, p) == outcome(general, p)


# inputs the fast path must read as the general reader does, or hand over to it (same data or same error)
CASES = {
    "crlf": "id,t,x,y\r\na,0,1,2\r\na,1,2,3\r\nb,0,1,1\r\nb,2,0,0\r\n",
    "no final newline": "t,x,y\n0,1,2\n1,2,3",
    "blank and space lines": "t,x,y\n0,1,2\n\n  \n\t\n1,2,3\n",
    "bom": "\ufefft,x,y\n0,1,2\n1,2,3\n",
    "spaces around": "id , t , x , y\n  car 1  , 0 , 1 ,2 \n car 1,1,2,3\n",
    "trailing separator": "t,x,y,\n0,1,2,\n1,2,3,\n",
    "extra columns": "t,x,y,note\n0,1,2,hello\n1,2,3,x,y,z\n",
    "semicolon": "t;x;y\n0;1;2\n1;2;3\n",
    "tab": "t\tx\ty\tid\n0\t1\t2\tp\n1\t2\t3\tp\n",
    "pipe": "id|t|x|y\n1|0|1|2\n1|1|2|3\n",
    "whitespace": "t x y id\n0 1 2 a\n  1\t\t2   3 a  \n",
    "non-ascii ids": "id,t,x,y\nfußgänger,0,1,2\nfußgänger,1,2,3\n車,0,0,0\n車,1,1,1\n",
    "nbsp around an id": "id,t,x,y\n\u00a0a,0,1,2\na,1,2,3\n\u00a0a,2,2,2\n",
    "quotes": 'id,t,x,y\n"a,b",0,1,2\n"a,b",1,2,3\n',
    "numeric ids kept as text": "id,t,x,y\n007,0,0,0\n7,0,1,1\n007,1,0,0\n7,1,1,1\n",
    "heading": "t,x,y,heading\n0,1,2,0.5\n1,2,3,0.25\n",
    "lat lon": "t,lat,lon\n0,45.1,15.2\n1,45.1001,15.2001\n",
    # errors: the general reader's messages
    "empty field": "t,x,y\n0,1,2\n1,,3\n",
    "nan": "t,x,y\n0,1,2\n1,nan,3\n",
    "inf": "t,x,y\n0,1,2\n1,inf,3\n",
    "huge number": "t,x,y\n0,1,2\n1,1e999,3\n",
    "too few columns": "t,x,y\n0,1,2\n1,2\n",
    "text in a number": "t,x,y\n0,1,2\n1,2,abc\n",
    "decimal comma": "t;x;y\n0;1,5;2\n1;2;3\n",
    "underscore": "t,x,y\n0,1_0,2\n1,2,3\n",
    "hex": "t,x,y\n0,0x10,2\n1,2,3\n",
    "exponent without digits": "t,x,y\n0,1e,2\n1,2,3\n",
    "lone sign": "t,x,y\n0,-,2\n1,2,3\n",
    "lone dot": "t,x,y\n0,.,2\n1,2,3\n",
    "empty id": "id,t,x,y\na,0,1,2\n,1,2,3\n",
    "lone cr": "t,x,y\r0,1,2\r1,2,3\r",
    "lone cr in the body": "t,x,y\n0,1,2\r1,2,3\n",
    "form feed": "t,x,y\n\x0c0,1,2\n1,2,3\n",
    "time not increasing": "id,t,x,y\n1,0,0,0\n2,0,5,5\n1,1,1,0\n2,0.5,6,5\n1,1,2,0\n",
    "single measurement": "id,t,x,y\n1,0,0,0\n2,0,5,5\n1,1,1,0\n",
    "header only": "t,x,y\n",
    "no header": "0,1,2\n1,2,3\n",
    "missing column": "t,x\n0,1\n",
    "latitude out of range": "t,lat,lon\n0,95,15\n1,45,15\n",
}


@pytest.mark.parametrize("name", list(CASES))
def test_same_outcome_as_the_general_reader(tmp_path, name):
    p = tmp_path / "in.csv"
    p.write_bytes(CASES[name].encode("utf-8"))
    kw = {"use_heading": True} if name == "heading" else {}
    got, want = outcome(read_csv, p, **kw), outcome(general, p, **kw)
    assert got == want
    if name == "crlf":  # the common shapes really take the fast path
        assert readers._read_csv_fast(p, str(p), False, (), "auto") is not None


def test_invalid_utf8_and_gzip(tmp_path):
    p = tmp_path / "bad.csv"
    p.write_bytes(b"id,t,x,y\n\xff\xfe,0,1,2\n\xff\xfe,1,2,3\n")
    assert outcome(read_csv, p)[0] == "error" and outcome(read_csv, p) == outcome(general, p)
    g = tmp_path / "in.csv.gz"
    g.write_bytes(gzip.compress(b"id,t,x,y\na,0,1,2\na,1,2,3\n"))
    assert readers._read_csv_fast(g, str(g), False, (), "auto") is not None
    assert outcome(read_csv, g) == outcome(general, g)


def test_group_order_is_the_stable_argsort():
    rng = np.random.default_rng(1)
    obj = rng.integers(0, 50, 5000).astype(np.int64)
    order, counts = group_order(obj, 50)
    np.testing.assert_array_equal(order, np.argsort(obj, kind="stable"))
    np.testing.assert_array_equal(counts, np.bincount(obj, minlength=50))


def test_formatter_next_to_powers_of_ten_is_pythons_g():
    """The output formatter's decimal exponent (frexp and one comparison, no log10) next to powers of ten and
    where rounding carries into a new digit: Python's %g wherever the digits are exact (|p - 1 - e| <= 21)."""
    from lgekf.io.formatting import format_g

    for p in range(1, 18):
        vals = []
        for e in range(-20 + p, 21):
            ten = float(f"1e{e}")
            a = b = ten
            vals.append(ten)
            for _ in range(3):
                a, b = np.nextafter(a, np.inf), np.nextafter(b, 0.0)
                vals += [a, b]
            nines = float(f"{'9' * (p + 2)}e{e - p - 2}")  # p + 2 nines: rounds up to 10^e (a carry, not a near tie)
            vals += [nines, np.nextafter(nines, 0.0)]
        vals = np.array([v for v in vals if v > 0])
        vals = np.concatenate([vals, -vals])
        assert format_g(vals, p) == [f"%.{p}g" % v for v in vals], p


def test_extra_columns_as_the_general_reader(tmp_path):
    p = tmp_path / "v.csv"
    p.write_text("id,t,x,y,vx,vy,note\na,0,1,2,0.5,-1e-3,x\na,1,2,3,0.25,7,y\nb,0,0,0,1,1,z\nb,1,1,1,2,2,w\n")
    fast, slow = read_csv(p, extra=("vx", "vy", "vz")), general(p, extra=("vx", "vy", "vz"))
    assert readers._read_csv_fast(p, str(p), False, ("vx", "vy"), "auto") is not None
    assert sorted(fast.extra) == sorted(slow.extra) == ["vx", "vy"]
    for k in fast.extra:
        np.testing.assert_array_equal(_bits(fast.extra[k]), _bits(slow.extra[k]))


def test_long_mantissas_and_rounding_midpoints(tmp_path):
    """16-19 significant digits (double-double in the fast path): repr'd doubles, and decimals within one unit
    of the 19th digit of the exact midpoint between two neighbouring doubles, bit for bit as float."""
    from decimal import Decimal, getcontext

    getcontext().prec = 60
    rng = np.random.default_rng(5)
    v = rng.standard_normal(4000) * 10.0 ** rng.integers(-6, 7, 4000)
    texts = [repr(float(x)) for x in v]
    for x in v[:1500]:
        mid = (Decimal(float(x)) + Decimal(float(np.nextafter(x, np.inf)))) / 2
        for d in (16, 17, 19):
            t = format(mid, f".{d - 1}e")
            m, e = t.split("e")
            last = int(m[-1])
            texts += [t] + [f"{m[:-1]}{last + k}e{e}" for k in (-1, 1) if 0 <= last + k <= 9]
    p = tmp_path / "long.csv"
    p.write_text("t,x,y\n" + "\n".join(f"{i},{s},{s}" for i, s in enumerate(texts)) + "\n")
    fast = readers._read_csv_fast(p, str(p), False, (), "auto")
    assert fast is not None
    want = np.array([float(s) for s in texts])
    np.testing.assert_array_equal(_bits(fast.z[:, 0]), _bits(want))
    # most of them are decided in the fast path, not handed to the general parser
    _, _, _, _, _, hard, _ = fastcsv.parse(p.read_bytes(), 6, 44, [1], -1, 2)
    assert 0 < len(hard) < len(texts) // 2


def test_cold_cache_reads_with_the_general_reader_and_compiles_for_next_time(tmp_path, monkeypatch):
    p = tmp_path / "a.csv"
    p.write_text("id,t,x,y\na,0,1,2\na,1,2,3\n")
    started = []
    monkeypatch.setattr(fastcsv, "compiled", lambda: False)
    monkeypatch.setattr(fastcsv, "compile_in_background", lambda: started.append(1))
    assert readers._read_csv_fast(p, str(p), False, (), "auto") is None and started == []  # too small to pay off
    monkeypatch.setattr(fastcsv, "COMPILE_MIN_BYTES", 10)
    assert readers._read_csv_fast(p, str(p), False, (), "auto") is None and started == [1]
    assert outcome(read_csv, p) == outcome(general, p)
