"""lgekf.io.grouping: ``grouped_consuming`` gives ``Measurements.grouped``'s rows (and its errors) while taking
the file-order rows over; ``row_objects`` gives the grouped rows' object indices from ``starts``."""

import numpy as np
import pytest

from lgekf.io.grouping import grouped_consuming, row_objects
from lgekf.io.readers import DataError, Measurements


def _measurements(obj, n_obj, heading=True, extra=True, seed=0):
    """Rows of objects ``obj`` (file order), times increasing within each object."""
    rng = np.random.default_rng(seed)
    obj = np.asarray(obj, dtype=np.int64)
    n = obj.size
    t = np.empty(n)
    for o in range(n_obj):
        rows = np.flatnonzero(obj == o)
        t[rows] = np.cumsum(rng.uniform(0.05, 0.2, rows.size))
    return Measurements(
        t, rng.standard_normal((n, 2)), rng.standard_normal(n) if heading else None, obj, [f"id{o}" for o in range(n_obj)],
        np.arange(2, n + 2), "test.csv", {"vx": rng.standard_normal(n)} if extra else {}, (47.0, 8.0),
    )


def _copy(m):
    return Measurements(m.t.copy(), m.z.copy(), None if m.heading is None else m.heading.copy(), m.obj.copy(), list(m.labels),
                        m.line.copy(), m.source, {k: v.copy() for k, v in m.extra.items()}, m.origin)


@pytest.mark.parametrize("case", ["interleaved", "grouped already", "one object", "no heading"])
def test_grouped_consuming_gives_the_rows_of_grouped(case):
    rng = np.random.default_rng(1)
    if case == "interleaved":
        obj, n_obj = rng.permutation(np.repeat(np.arange(5), [3, 7, 2, 9, 4])), 5
    elif case == "grouped already":
        obj, n_obj = np.repeat(np.arange(4), [2, 5, 3, 6]), 4
    elif case == "one object":
        obj, n_obj = np.zeros(11, np.int64), 1
    else:
        obj, n_obj = rng.permutation(np.repeat(np.arange(3), [4, 4, 5])), 3
    m = _measurements(obj, n_obj, heading=case != "no heading")
    want, want_starts, _ = _copy(m).grouped(min_length=2)
    t_in, z_in = m.t, m.z
    got, starts = grouped_consuming(m, min_length=2)
    if case in ("grouped already", "one object"):  # already in object order: no copy made
        assert got.t is t_in and got.z is z_in
    assert starts.tolist() == want_starts.tolist()
    assert got.t.tolist() == want.t.tolist()
    assert got.z.tolist() == want.z.tolist()
    assert (got.heading is None) == (want.heading is None)
    if want.heading is not None:
        assert got.heading.tolist() == want.heading.tolist()
    assert got.extra["vx"].tolist() == want.extra["vx"].tolist()
    assert got.labels == want.labels and got.origin == want.origin and got.source == want.source
    assert got.obj is None and got.line.tolist() == want.line.tolist()  # the lines kept, sorted with the rows
    assert m.t is None and m.z is None and m.obj is None  # taken over: the file-order columns released
    assert row_objects(starts, 0, len(starts) - 1).tolist() == want.obj.tolist()
    for first, last in [(0, 1), (1, len(starts) - 1), (len(starts) - 2, len(starts) - 1)]:
        assert row_objects(starts, first, last).tolist() == want.obj[starts[first]:starts[last]].tolist()


def _error(fn):
    with pytest.raises(DataError) as e:
        fn()
    return str(e.value)


def test_grouped_consuming_raises_the_errors_of_grouped():
    # an object with a single measurement
    m = _measurements(np.array([0, 1, 0, 2, 2, 0]), 3)
    assert _error(lambda: grouped_consuming(_copy(m))) == _error(lambda: m.grouped(min_length=2))
    assert "id1" in _error(lambda: grouped_consuming(_copy(m)))
    # time not increasing within an object (interleaved and grouped files)
    for obj in (np.array([0, 1, 0, 1, 0, 1]), np.array([0, 0, 0, 1, 1, 1])):
        m = _measurements(obj, 2)
        rows = np.flatnonzero(obj == 1)
        m.t[rows[2]] = m.t[rows[1]]
        msg = _error(lambda: grouped_consuming(_copy(m)))
        assert msg == _error(lambda: m.grouped(min_length=2))
        assert "not increasing" in msg and f"line {int(m.line[rows[2]])}" in msg


def test_times_increase_is_the_grouped_check():
    """fastcsv.times_increase (file order, before grouping) says what np.diff(t[order]) <= 0 within objects says."""
    from lgekf.io.fastcsv import group_order, times_increase

    rng = np.random.default_rng(7)
    for trial in range(300):
        obj = np.unique(rng.integers(0, 4, int(rng.integers(1, 12))), return_inverse=True)[1]  # every object has rows
        n_obj = int(obj.max()) + 1
        t = rng.integers(0, 6, obj.size).astype(float)  # ties and decreases are common
        t[rng.random(obj.size) < 0.15] = rng.choice([np.inf, -np.inf, np.nan])  # np.diff's rule for them too
        order, counts = group_order(obj, n_obj)
        starts = np.concatenate([[0], np.cumsum(counts)])
        with np.errstate(invalid="ignore"):  # inf - inf
            bad = np.diff(t[order]) <= 0
        inner = np.ones(bad.size, bool)
        inner[starts[1:-1] - 1] = False
        assert times_increase(t, obj, n_obj) == (not (bad & inner).any()), (obj, t)


@pytest.mark.parametrize("t", [[-np.inf, 1.0, 2.0], [1.0, np.inf, np.inf], [1.0, np.nan, 0.5]])
def test_grouped_consuming_takes_what_grouped_takes(t):
    """Non-finite times (the API's; the readers refuse them) pass or fail as in Measurements.grouped."""
    m = _measurements(np.zeros(3, np.int64), 1)
    m.t[:] = t
    with np.errstate(invalid="ignore"):  # inf - inf in grouped's np.diff
        want = _copy(m).grouped(min_length=2)[0]
    got, _ = grouped_consuming(_copy(m))
    assert np.array_equal(got.t, want.t, equal_nan=True)
