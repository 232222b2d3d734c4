"""Noise from the data (lgekf.apps.noise, lgekf.apps.defaults): the measurement std from local quadratic
residuals (exactness, simulated recovery over noise levels, speeds and rates, robustness), chord speeds,
chi-square quantiles, and the process-noise search on a truth with known noise."""

from __future__ import annotations

import math

import numpy as np
import pytest

from lgekf.apps.defaults import plan_noise
from lgekf.apps.noise import (
    MIN_MEAS_STD, _third_divided_differences, accel_std_family, chi2_quantile, chord_speeds, measurement_std,
    subsample_objects, typical_speed,
)
from lgekf.core.registry import MODELS
from lgekf.experiments.scenarios import Segment, drive, sample, sample_times, urban_drive


def test_quadratic_motion_leaves_no_residual():
    # any quadratic in t (irregular steps) is annihilated: the residual measures the noise only
    rng = np.random.default_rng(0)
    t = np.cumsum(rng.uniform(0.05, 0.4, 200))
    z = np.column_stack([3.0 + 7.0 * t - 0.8 * t**2, -2.0 + 0.3 * t + 1.1 * t**2])
    e = _third_divided_differences(t, z, np.array([0, t.size]))
    assert e.shape == (t.size - 3, 2)
    assert np.abs(e).max() < 1e-8 * np.abs(z).max()


def test_residual_normalisation_is_exact():
    # for fixed irregular times, e/‖w‖ of pure noise has variance σ² (no bias factor to fit)
    rng = np.random.default_rng(1)
    t = np.array([0.0, 0.13, 0.52, 0.61])
    sigma = 0.7
    z = sigma * rng.standard_normal((200_000, 4, 2))
    e = np.array([_third_divided_differences(t, zz, np.array([0, 4]))[0] for zz in z[:20_000]])
    assert np.std(e) == pytest.approx(sigma, rel=0.02)


def test_windows_stay_inside_objects():
    # two objects far apart: a window across the boundary would see a huge jump
    t = np.concatenate([np.arange(10) * 0.1, np.arange(10) * 0.1])
    z = np.concatenate([np.zeros((10, 2)), np.full((10, 2), 1e6)])
    e = _third_divided_differences(t, z, np.array([0, 10, 20]))
    assert e.shape == (14, 2) and np.abs(e).max() < 1e-3  # a window across the jump would give ~1e5


@pytest.fixture(scope="module")
def drives():
    rng = np.random.default_rng(7)
    return {
        "parked (0 m/s)": drive([Segment(200.0)]),
        "4-6 m/s": drive(urban_drive(200.0, rng, cruise=(4.0, 6.0), turn_speed=(2.0, 4.0))),
        "8-14 m/s": drive(urban_drive(200.0, rng)),
        "25-30 m/s": drive(urban_drive(200.0, rng, cruise=(25.0, 30.0), turn_speed=(8.0, 12.0), radius=(40.0, 80.0))),
    }


@pytest.mark.parametrize("rate", [1.0, 2.0, 5.0, 25.0])
def test_measurement_std_recovered_in_simulation(drives, rate):
    """σ in 0.05–2 m, speeds 0–30 m/s, rates 1–25 Hz: within 15 %; the one exception is the documented
    corner (1 Hz, σ = 0.05 m, a moving and turning car) where the motion's jerk leaks in: biased up, < 35 %."""
    for name, d in drives.items():
        for sigma in (0.05, 0.3, 1.0, 2.0):
            ratios = []
            for seed in range(3):
                rng = np.random.default_rng([seed, int(rate), int(100 * sigma)])
                times = sample_times(d.t[-1], rng, (1.0 / rate,))
                t, p, _, _, z = sample(d, times, sigma, rng)
                ratios.append(measurement_std(t, z, np.array([0, t.size])).meas_std / sigma)
            r = float(np.mean(ratios))
            if rate == 1.0 and sigma == 0.05 and not name.startswith("parked"):
                assert 1.0 < r < 1.35, (name, rate, sigma, r)
            else:
                assert abs(r - 1) < 0.15, (name, rate, sigma, r)


def test_measurement_std_robust_to_outliers_and_pooled_over_objects():
    rng = np.random.default_rng(3)
    sigma = 0.5
    starts = [0]
    ts, zs = [], []
    for _ in range(20):  # 20 objects of 100 steps at 5 Hz, straight at 10 m/s
        t = 0.2 * np.arange(100)
        z = np.column_stack([10 * t, 0 * t]) + sigma * rng.standard_normal((100, 2))
        bad = rng.random(100) < 0.01  # 1 % gross outliers (20 σ): 4 % of the windows (each is in 4)
        z[bad] += 20 * sigma * rng.standard_normal((int(bad.sum()), 2))
        ts.append(t)
        zs.append(z)
        starts.append(starts[-1] + 100)
    est = measurement_std(np.concatenate(ts), np.concatenate(zs), np.array(starts))
    assert est.windows == 20 * 97
    assert est.meas_std == pytest.approx(sigma, rel=0.1)


def test_noise_free_input_is_floored_and_short_input_has_no_estimate():
    t = 0.1 * np.arange(20)
    est = measurement_std(t, np.column_stack([t, 2 * t]), np.array([0, 20]))
    assert est.floored and est.meas_std == MIN_MEAS_STD
    est = measurement_std(t[:3], np.zeros((3, 2)), np.array([0, 3]))
    assert est.windows == 0 and math.isnan(est.meas_std)


def test_chord_speeds_of_a_straight_line():
    t = np.cumsum(np.r_[0.0, np.full(40, 0.25)])
    z = np.column_stack([3.0 * t, -4.0 * t])  # 5 m/s
    c = chord_speeds(t, z, np.array([0, t.size]))
    np.testing.assert_allclose(c[:-1], 5.0, rtol=1e-12)
    assert np.isnan(c[-1])
    assert typical_speed(t, z, np.array([0, t.size])) == pytest.approx(5.0)


def test_chi2_quantile_matches_scipy():
    from scipy.stats import chi2

    for dof in (1, 2, 3, 6, 20, 30):
        for p in (0.5, 0.999, 1 - 1e-4):
            assert chi2_quantile(p, dof) == pytest.approx(chi2.ppf(p, dof), rel=1e-9)


def test_accel_std_family():
    # translational entries scale with k, rotational ones are σ_a / v_typ capped at the default
    for name, spec in MODELS.items():
        q = accel_std_family(name, 4.0, 10.0)
        for v, d, kind in zip(q, spec.default_accel_std, spec.matched_noise):
            if kind == "v":
                assert v == pytest.approx(4.0 * d)
            else:
                lin = [dd for dd, kk in zip(spec.default_accel_std, spec.matched_noise) if kk == "v"][0]
                assert v == pytest.approx(min(d, 4.0 * lin / 10.0))
        q0 = accel_std_family(name, 1.0, 0.0)  # no motion: rotational defaults
        assert all(v == d for v, d, kind in zip(q0, spec.default_accel_std, spec.matched_noise) if kind == "w")


def test_subsample_keeps_whole_objects():
    starts = np.cumsum(np.r_[0, np.full(1000, 100)])
    objs = subsample_objects(starts, max_rows=5000)
    assert 1 <= objs.size <= 50 and np.all(np.diff(objs) > 0)
    assert objs.max() > 500  # spread over the file, not its beginning
    np.testing.assert_array_equal(subsample_objects(starts[:11], max_rows=5000), np.arange(10))


def test_process_noise_search_finds_the_truths_level():
    """A constant-velocity truth with white acceleration σ_a = 2 m/s² (k = 4 × the 0.5 default), 0.5 m
    noise at 10 Hz: the search, scored by one-step prediction errors, lands within a factor 2 of it."""
    rng = np.random.default_rng(11)
    B, K, dt, sa, r = 40, 300, 0.1, 2.0, 0.5
    acc = sa * rng.standard_normal((B, K, 2))
    v = np.cumsum(acc * dt, axis=1) + rng.uniform(-5, 5, (B, 1, 2))
    p = np.cumsum(v * dt + 0.5 * acc * dt**2, axis=1)
    t = np.tile(dt * np.arange(K), B)
    z = p.reshape(-1, 2) + r * rng.standard_normal((B * K, 2))
    starts = K * np.arange(B + 1)
    plan = plan_noise(t, z, starts, ["cv"], omega_std=0.5, heading_std=0.1)
    assert plan.meas_std == pytest.approx(r, rel=0.1)
    assert plan.accel_source["cv"] == "data"
    assert 1.0 <= plan.accel_std["cv"][0] <= 4.0, plan.describe()
    assert plan.median_nis["cv"] == pytest.approx(chi2_quantile(0.5, 2), rel=0.25)  # consistent


def test_given_values_are_kept():
    t = 0.1 * np.arange(50)
    z = np.column_stack([t, t]) + 0.1 * np.random.default_rng(0).standard_normal((50, 2))
    plan = plan_noise(t, z, np.array([0, 50]), ["cv", "ctrv"], meas_std=0.25, accel_std={"cv": (0.7,)},
                      omega_std=0.5, heading_std=0.1)
    assert plan.meas_std == 0.25 and plan.meas_source == "given"
    assert plan.accel_std["cv"] == (0.7,) and plan.accel_source["cv"] == "given"
    assert plan.accel_source["ctrv"] == "data"
    line = plan.describe()
    assert "meas-std 0.25 m (given)" in line and "cv 0.7 (given)" in line and "ctrv" in line


def test_objects_too_short_to_learn_from_keep_the_defaults():
    # three measurements per object: no update survives the burn-in, and no 4-point window exists
    t = np.tile([0.0, 0.1, 0.2], 5)
    z = np.column_stack([t, t]) + 0.01 * np.arange(15)[:, None]
    plan = plan_noise(t, z, 3 * np.arange(6), ["ctrv"], omega_std=0.5, heading_std=0.1)
    assert plan.meas_source == "default" and plan.meas_std == 0.3
    assert plan.accel_source["ctrv"] == "default" and plan.accel_std["ctrv"] == MODELS["ctrv"].default_accel_std
    assert "default: no object has" in plan.describe() and "no object has 4 measurements" in plan.describe()


def _median_reference(t, z, starts):
    """What measurement_std took before its counting selection: the median of all |residuals|, held at once."""
    e = _third_divided_differences(t, z, starts)
    return (float(np.median(np.abs(e))) if e.size else float("nan")), e.shape[0]


@pytest.mark.parametrize("cap", [3, 1 << 17])
def test_median_abs_residual_is_numpys_median(monkeypatch, cap):
    """The counting (radix) selection gives np.median's number bit for bit: odd and even counts, ties across
    the candidate cap, all residuals equal (zero), few distinct values, several objects, no window, NaN."""
    import lgekf.apps.noise as noise

    monkeypatch.setattr(noise, "SELECT_CANDIDATES", cap)
    monkeypatch.setattr(noise, "SELECT_SHIFT", 62 if cap < 100 else noise.SELECT_SHIFT)  # a small cap at every size
    rng = np.random.default_rng(1)
    cases = []
    for n in (3, 4, 5, 6, 7, 9, 50, 333):
        t = np.cumsum(rng.uniform(0.05, 0.2, n))
        z = rng.normal(0, 1, (n, 2))
        cases += [(t, z, np.array([0, n])), (t, z, np.array([0, n // 2, n])), (t, z.round(0), np.array([0, n]))]
    n = 4000
    t = np.arange(n) * 0.1
    cases += [(t, np.zeros((n, 2)), np.array([0, n])),  # every residual 0: the group of one key
              (t, np.repeat(rng.normal(size=(n // 4, 2)).round(0), 4, axis=0), np.array([0, n])),
              (t, rng.normal(size=(n, 2)).round(1), np.array([0, 1000, 2500, n])),
              (np.array([0.0, 1e-120, 2e-120, 3e-120, 1.0]), rng.normal(size=(5, 2)), np.array([0, 5]))]  # NaN
    for t, z, starts in cases:
        got, ref = noise._median_abs_residual(t, z, starts), _median_reference(t, z, starts)
        assert got[1] == ref[1]
        assert got[0] == ref[0] or (np.isnan(got[0]) and np.isnan(ref[0])), (got, ref)


def test_measurement_std_of_nonfinite_residuals_is_no_estimate():
    """Times about 1e-120 s apart make a residual NaN (1/0 in the weights), positions of 1e306 m overflow: no
    estimate (not usable, said why; the default applies), not an exception."""
    from lgekf.apps.defaults import plan_noise

    t = np.array([0.0, 1e-120, 2e-120, 3e-120, 1.0])
    est = measurement_std(t, np.zeros((5, 2)), np.array([0, 5]))
    assert est.windows == 2 and est.nonfinite and not est.usable and np.isnan(est.meas_std)
    assert "not finite" in est.describe()
    t = 0.1 * np.arange(8)
    z = np.tile([[1e306, -1e306], [-1e306, 1e306]], (4, 1))
    est = measurement_std(t, z, np.array([0, 8]))
    assert est.nonfinite and not est.usable
    plan = plan_noise(t, z, np.array([0, 8]), ["cv"], accel_std={"cv": (0.5,)}, omega_std=0.5, heading_std=0.1)
    assert plan.meas_source == "default" and np.isfinite(plan.meas_std)
    assert measurement_std(0.1 * np.arange(3), np.zeros((3, 2)), np.array([0, 3])).describe() == "no object has 4 measurements"


def test_typical_speed_is_the_median_of_the_finite_chords():
    """typical_speed compacts the finite chord speeds in place: np.median of the finite ones, across blocks."""
    rng = np.random.default_rng(5)
    starts = np.array([0, 70_000, 70_001, 140_000])
    t = np.concatenate([np.cumsum(rng.uniform(0.05, 0.2, b - a)) for a, b in zip(starts[:-1], starts[1:])])
    z = np.cumsum(rng.normal(size=(t.size, 2)), axis=0)
    c = chord_speeds(t, z, starts)
    assert typical_speed(t, z, starts) == float(np.median(c[np.isfinite(c)]))
