"""lgekf.io.units: --time-unit conversion and the warnings about implausible units."""

import numpy as np
import pytest

from lgekf.io.units import to_seconds, unit_warnings


def _line(n=20, dt=0.1, speed=1.5, start=(0.0, 0.0)):
    t = dt * np.arange(n)
    z = np.column_stack([start[0] + speed * t, np.full(n, start[1])])
    return t, z, np.array([0, n])


def test_to_seconds():
    t = np.array([0.0, 100.0, 250.0])
    np.testing.assert_allclose(to_seconds(t, "ms"), [0.0, 0.1, 0.25])
    np.testing.assert_allclose(to_seconds(t, "us"), [0.0, 1e-4, 2.5e-4])
    np.testing.assert_allclose(to_seconds(t, "ns"), [0.0, 1e-7, 2.5e-7])
    assert to_seconds(t, "s") is t
    with pytest.raises(ValueError, match="--time-unit"):
        to_seconds(t, "min")


def test_plausible_data_has_no_warning():
    for speed in (0.0, 1.5, 30.0):  # standing, walking, driving
        assert unit_warnings(*_line(speed=speed, start=(500.0, 200.0))) == []


@pytest.mark.parametrize("factor, unit", [(1e3, "ms"), (1e6, "us"), (1e9, "ns")])
def test_time_step_suggests_the_unit(factor, unit):
    t, z, starts = _line(dt=0.1)
    (w,) = unit_warnings(t * factor, z, starts)
    assert f"--time-unit {unit}" in w and "median time step" in w


def test_speeds_of_degrees_and_of_wrong_scales():
    t, z, starts = _line(speed=1.5)
    (w,) = unit_warnings(t, z * 2e6, starts)  # 3e6 m/s
    assert "median speed is 3e+06 m/s" in w
    deg = np.column_stack([11.5 + 1.3e-5 * t, 48.1 + 0 * t])  # walking, written in degrees
    (w,) = unit_warnings(t, deg, starts)
    assert "lon, lat" in w
    assert unit_warnings(t, deg, starts, projected=True) == []


def test_steps_across_objects_do_not_count():
    # two objects far apart, one row after the other: the jump between them is no step of either
    t1, z1, _ = _line(n=10)
    t2, z2, _ = _line(n=10, start=(1e7, 0.0))
    t, z = np.concatenate([t1, t2]), np.concatenate([z1, z2])
    assert unit_warnings(t, z, np.array([0, 10, 20])) == []


def test_pedestrian_format_gets_frame_dt_advice():
    t, z, starts = _line(dt=0.4)
    (w,) = unit_warnings(t * 25, z, starts, fmt="pedestrian")  # --frame-dt 1 instead of 0.04
    assert "--frame-dt" in w and "--time-unit" not in w
    deg = np.column_stack([11.5 + 1.3e-5 * t, 48.1 + 0 * t])
    assert unit_warnings(t, deg, starts, fmt="pedestrian") == []  # no columns to rename there


@pytest.mark.parametrize("block", [1, 3, 7, 1 << 16])
def test_step_values_blockwise_equal_whole_array(monkeypatch, block):
    """The block-wise steps and speeds are the whole-array np.diff expressions, bit for bit, with object boundaries
    on and across block edges (and objects of one row)."""
    import lgekf.io.units as units

    monkeypatch.setattr(units, "STEP_BLOCK", block)
    rng = np.random.default_rng(3)
    starts = np.array([0, 1, 4, 7, 8, 15, 21, 22])
    n = starts[-1]
    t = np.concatenate([np.cumsum(rng.uniform(0.05, 0.2, b - a)) for a, b in zip(starts[:-1], starts[1:])])
    z = rng.normal(0, 50, (n, 2))
    keep = np.ones(n - 1, dtype=bool)
    keep[starts[1:-1] - 1] = False
    dt = np.diff(t)[keep]
    speed = (np.hypot(*np.diff(z, axis=0).T))[keep] / dt
    out = np.full(n - 1, np.nan)
    k = units._step_values(t, z, starts, "dt", out)
    assert k == dt.size and np.array_equal(out[:k], dt)
    k = units._step_values(t, z, starts, "speed", out)
    assert k == speed.size and np.array_equal(out[:k], speed)
