"""The CSV number formatter (lgekf.io.formatting) writes exactly the bytes of the formatter it replaced
(vendored in tests/_formatting_old.py) for every double and every number of digits, and Python's
``'%.{p}g' % v`` wherever that old formatter was exact (|p - 1 - e| <= 21 for the decimal exponent e).

Inputs: hypothesis doubles over all binades, crafted near-ties (the scaled value's fraction within 1e-12 of
1/2, exact ties and decimal ties not representable in binary), powers of ten and their neighbours,
subnormals, huge values, signs, -0.0, inf, nan, and 10^6 random doubles (random bit patterns and
log-uniform magnitudes) with every number of digits 1..17 in one table.
"""

from __future__ import annotations

import math
from decimal import Decimal

import numpy as np
import pytest
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

import _formatting_old as old
from lgekf.io import formatting as new


def python_exact_range(v: float, p: int) -> bool:
    """True where the old formatter's digits are Python's (but for near-ties): finite v with |p - 1 - e| <= 21
    and 10^-22 <= |v| < 10^22 (its exponent from a table, not log10), e = floor(log10|v|); zero, inf, nan."""
    if v == 0.0 or not math.isfinite(v):
        return True
    e = Decimal(abs(v)).adjusted()  # floor(log10|v|), exactly
    return -20 + p <= e <= 20 + p and -22 <= e <= 21  # one-wide margins


def near_tie(v: float, p: int) -> bool:
    """|v|·10^(p-1-e) (exact, e = floor(log10|v|)) has a fractional part within 1e-15 of 1/2 but is no tie."""
    d = Decimal(abs(v))
    scaled = d.scaleb(p - 1 - d.adjusted())
    off = abs(scaled - scaled.to_integral_value(rounding="ROUND_FLOOR") - Decimal("0.5"))
    return 0 < off < Decimal("1e-15")


def check(values, p: int) -> None:
    """New == old for every value; new == Python's %g where the old formatter was exact, except at near-ties
    (where the old formatter's double-double can round the wrong way, and the new one does the same)."""
    values = np.asarray(values, dtype=float).ravel()
    got = new.format_g(values, p)
    assert got == old.format_g(values, p), p
    for v, s in zip(values, got):
        if python_exact_range(float(v), p):
            want = f"%.{p}g" % v if v != 0.0 else "0"  # -0.0 is written as 0
            assert s == want or near_tie(float(v), p), (repr(float(v)), p)


@settings(max_examples=400, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.too_slow])
@given(st.floats(allow_nan=True, allow_infinity=True, allow_subnormal=True), st.integers(1, 17))
@example(0.5, 1)
@example(2.5, 1)
@example(9.5, 1)
@example(0.125, 2)
@example(1e22, 17)
@example(9007199254740993.0, 17)
def test_any_double_any_digits(v, p):
    check([v, -v], p)


@pytest.mark.parametrize("p", [1, 2, 3, 6, 10, 15, 16, 17])
def test_random_doubles_across_binades(p):
    rng = np.random.default_rng(100 + p)
    mant = rng.uniform(1.0, 10.0, 4000) * rng.choice([-1.0, 1.0], 4000)
    check(mant * 10.0 ** rng.integers(-40, 40, 4000), p)
    check(rng.uniform(-500.0, 500.0, 2000), p)  # lgekf track's positions, angles, NIS ...
    check(10.0 ** rng.uniform(-3.0, 0.0, 2000), p)  # ... and standard deviations


def near_ties(p: int, rng, count: int) -> list:
    """Doubles nearest to d_1...d_p 5 · 10^(e-p) ± δ (δ from 0 to 1e-12 of the last digit's unit): the scaled
    value's fraction at or within 1e-12 of 1/2, for decimal exponents e from -8 to 20."""
    out = []
    for _ in range(count):
        digits = int(rng.integers(10 ** (p - 1), 10 ** p))
        e = int(rng.integers(-8, 21))
        for delta in ("0", "1e-12", "-1e-12", "1e-14", "-1e-14", "3e-16", "-3e-16"):
            x = (Decimal(digits) + Decimal("0.5") + Decimal(delta)).scaleb(e - p + 1)
            out.append(float(x))
    return out


@pytest.mark.parametrize("p", [1, 3, 10, 15, 17])
def test_near_ties(p):
    rng = np.random.default_rng(p)
    check(near_ties(p, rng, 300), p)


def test_exact_binary_ties_round_half_even():
    """Values whose scaled value is exactly n + 1/2 in binary (the fast path's one undecided case)."""
    vals = [n + 0.5 for n in range(0, 200)] + [(n + 0.5) / 8 for n in range(200)] + [(2 * n + 1) * 2.0 ** -20 for n in range(200)]
    for p in (1, 2, 3, 6, 10):
        check(vals, p)


def test_powers_of_ten_and_neighbours():
    vals = []
    for e in range(-320, 309):
        ten = float(f"1e{e}")
        if ten == 0.0 or not math.isfinite(ten):
            continue
        a = b = ten
        vals.append(ten)
        for _ in range(3):
            a, b = np.nextafter(a, np.inf), np.nextafter(b, 0.0)
            vals += [a, b]
    vals = [v for v in vals if v > 0 and math.isfinite(v)]
    for p in range(1, 18):
        check(vals, p)


def test_subnormals_huge_and_specials():
    rng = np.random.default_rng(7)
    tiny = np.float64(5e-324)
    sub = [tiny, 2 * tiny, 3 * tiny, 2.2250738585072014e-308, np.nextafter(2.2250738585072014e-308, 0.0)]
    sub += list(rng.integers(1, 2**52, 200).astype(np.uint64).view(np.float64))  # random subnormals
    huge = [np.finfo(float).max, 1e308, 1.7e308, np.nextafter(np.finfo(float).max, 0.0), 2.0**1023]
    special = [0.0, -0.0, np.inf, -np.inf, np.nan, 1.0, -1.0, 2.0**53, 2.0**53 + 2, 1e16, 1e17, 123456789012345678.0]
    for p in range(1, 18):
        check(np.concatenate([sub, huge, special]), p)
    assert new.format_g([np.nan, np.inf, -np.inf, 0.0, -0.0], 10) == ["nan", "inf", "-inf", "0", "0"]


def test_fast_rounding_is_the_double_double_rounding():
    """``_round_scaled_fast`` (one product, the double-double only where undecided) against the old
    ``_round_scaled`` for every k in -22..22, on random values and on values scaled to n + 1/2 exactly."""
    rng = np.random.default_rng(3)
    for k in range(-22, 23):
        a = rng.uniform(1.0, 10.0, 300) * 10.0 ** float(rng.integers(-k - 1, -k + 16))
        halves = (rng.integers(0, 2**40, 50) + 0.5) / new._P10F[k] if k >= 0 else (rng.integers(0, 2**40, 50) + 0.5) * new._P10F[-k]
        for x in np.concatenate([a, halves[halves > 0]]):
            assert new._round_scaled_fast(float(x), k) == old._round_scaled(float(x), k), (x, k)


def test_a_million_values_as_the_old_formatter():
    """10^6 doubles (random bit patterns: every binade, subnormals, nan, inf; and log-uniform magnitudes),
    one column per number of digits 1..17, with labels: the same bytes as the old formatter."""
    rng = np.random.default_rng(2026)
    rows = 1_000_000 // 17 + 1
    bits = rng.integers(-2**63, 2**63, (rows, 17), dtype=np.int64).view(np.float64)  # both signs
    mags = rng.uniform(1.0, 10.0, (rows, 17)) * 10.0 ** rng.integers(-25, 25, (rows, 17)) * rng.choice([-1.0, 1.0], (rows, 17))
    vals = np.ascontiguousarray(np.where(rng.random((rows, 17)) < 0.5, bits, mags))
    t = rng.uniform(0.0, 1e4, rows)
    lab = new.label_bytes(["a", "b,c", ""])
    row = rng.integers(0, 3, rows).astype(np.int64)
    digits = np.arange(1, 18, dtype=np.int64)
    got = new._format_rows(lab[0], lab[1], row, t, 15, vals, digits)
    want = old._format_rows(lab[0], lab[1], row, t, 15, vals, digits)
    assert got.tobytes() == want.tobytes()


@pytest.mark.parametrize("args", [["--model", "all"], ["--model", "se2se2", "--full-cov", "--precision", "17"]])
def test_track_output_as_with_the_old_formatter(tmp_path, monkeypatch, args):
    """``lgekf track`` writes the same bytes with the new formatter as with the old one (monkeypatched in)."""
    from lgekf.cli import main

    rng = np.random.default_rng(5)
    objects, steps = 40, 50
    t = np.cumsum(rng.uniform(0.07, 0.13, (objects, steps)), axis=1)
    th = rng.uniform(-np.pi, np.pi, (objects, 1)) + np.cumsum(rng.normal(0.0, 0.05, (objects, steps)), axis=1)
    x = np.cumsum(5.0 * np.cos(th) * 0.1, axis=1) + rng.uniform(-500, 500, (objects, 1)) + 0.2 * rng.standard_normal((objects, steps))
    y = np.cumsum(5.0 * np.sin(th) * 0.1, axis=1) + rng.uniform(-500, 500, (objects, 1)) + 0.2 * rng.standard_normal((objects, steps))
    order = np.argsort(t.ravel(), kind="stable")
    obj = np.repeat(np.arange(objects), steps)[order]
    inp = tmp_path / "in.csv"
    inp.write_text("id,t,x,y\n" + "".join(f"o{o},{a!r},{b!r},{c!r}\n" for o, a, b, c in
                                          zip(obj, t.ravel()[order].tolist(), x.ravel()[order].tolist(), y.ravel()[order].tolist())))
    written = {}
    for which, rows in [("new", new._format_rows), ("old", old._format_rows)]:
        monkeypatch.setattr(new, "_format_rows", rows)
        (tmp_path / which).mkdir()
        assert main(["track", str(inp), "-o", str(tmp_path / which / "out.csv"), "--quiet", *args]) in (0, None)
        written[which] = {p.name: p.read_bytes() for p in sorted((tmp_path / which).iterdir())}
    assert len(written["new"]) == (5 if "all" in args else 1)
    assert written["new"] == written["old"]
