"""The divergence monitor and the noise search do less work (issue #10): the generated ``row_speeds`` kernel of
every model against an independent speed (numpy cos/sin of the common heading times the body velocity), the
speeds of chosen rows, the speed limits' per-object maximum and the re-initialisation baseline search, each
against the straightforward numpy formula it replaced; ``track_monitored`` with a given start and speed
limits, and the noise search that makes them once per model, against the per-run path (the same bits)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from lgekf.apps import defaults
from lgekf.apps.defaults import plan_noise
from lgekf.apps.divergence import MonitorConfig, speed_limits, speeds
from lgekf.apps.noise import CHORD_S, chord_speeds
from _reinit_rows import reinit_first_rows
from lgekf.apps.track import TRACK_HEADING_CAP, TrackConfig, initial_common, initial_estimates, track_monitored
from lgekf.core.initiation import moving_backwards
from lgekf.core.covariance import pack
from lgekf.core.registry import MODELS, get_model


def _common_states(rng, n):
    """Common states c = (x, y, θ, v_x, v_y, ω) (body-frame velocity) with speeds 0.1 .. 30 m/s."""
    c = np.empty((n, 6))
    c[:, :2] = rng.uniform(-1e3, 1e3, (n, 2))
    c[:, 2] = rng.uniform(-math.pi, math.pi, n)
    c[:, 3] = rng.uniform(0.1, 30.0, n)
    c[:, 4] = rng.uniform(-3.0, 3.0, n)
    c[:, 5] = rng.uniform(-1.0, 1.0, n)
    return c


@pytest.mark.parametrize("model", sorted(MODELS))
def test_row_speeds_is_the_world_speed_of_every_model(model):
    """The speed of each model's state made from a common state is |R(θ) (v_x, v_y)|, computed here with numpy."""
    rng = np.random.default_rng(3)
    c = _common_states(rng, 500)
    spec = get_model(model)
    x = np.empty((c.shape[0], spec.n))
    spec.kernels.common_to_states(c, x)
    wx = np.cos(c[:, 2]) * c[:, 3] - np.sin(c[:, 2]) * c[:, 4]
    wy = np.sin(c[:, 2]) * c[:, 3] + np.cos(c[:, 2]) * c[:, 4]
    np.testing.assert_allclose(speeds(model, x), np.sqrt(wx * wx + wy * wy), rtol=1e-12)
    v = np.empty((c.shape[0], 2))  # and the no-allocation world velocity behind it, component by component
    spec.kernels.world_velocities(x, v)
    np.testing.assert_allclose(v, np.column_stack([wx, wy]), rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("model", sorted(MODELS))
def test_speeds_of_rows_equal_hypot_of_the_world_velocity_bit_for_bit(model):
    """``speeds(model, x, rows)`` is exactly np.hypot of the allocating ``world_velocity`` of each row (the monitor's
    former computation; numba's math.hypot is the C library's, as numpy's, not Python's), in any row order, with
    repeats; a non-finite state gives nan, not an error."""
    rng = np.random.default_rng(4)
    spec = get_model(model)
    x = 10.0 * rng.standard_normal((400, spec.n))
    x[7, :] = np.nan
    x[9, -1] = np.inf
    rows = rng.integers(0, x.shape[0], 1000)
    w = np.array([spec.kernels.world_velocity(x[r]) for r in rows])
    expect = np.where(np.isfinite(x[rows]).all(axis=1), np.hypot(w[:, 0], w[:, 1]), np.nan)
    got = speeds(model, x, rows)
    ok = np.isfinite(expect)
    assert np.array_equal(got[ok], expect[ok])
    assert np.isnan(got[rows == 7]).all()
    assert np.array_equal(speeds(model, x)[rows], got, equal_nan=True)
    assert speeds(model, x, np.empty(0, np.int64)).shape == (0,)


def test_speed_limits_take_each_objects_largest_finite_chord():
    """The per-object maximum against np.maximum.at over the finite chords (objects of 1, 2 and many rows)."""
    rng = np.random.default_rng(5)
    lens = np.array([1, 2, 5, 1, 40, 3, 17])
    starts = np.concatenate([[0], np.cumsum(lens)])
    t = np.concatenate([np.cumsum(rng.uniform(0.05, 0.6, n)) for n in lens])
    z = np.cumsum(rng.normal(0, 1.0, (t.size, 2)), axis=0)
    cfg = MonitorConfig()
    c = chord_speeds(t, z, starts)
    obj = np.repeat(np.arange(lens.size), lens)
    top = np.zeros(lens.size)
    ok = np.isfinite(c)
    np.maximum.at(top, obj[ok], c[ok])
    expect = cfg.speed_factor * top + 5.0 * math.sqrt(2.0) * 0.3 / CHORD_S + cfg.speed_margin
    assert np.array_equal(speed_limits(t, z, starts, 0.3, cfg), expect)
    assert top[0] == 0.0 and top[3] == 0.0  # one-row objects: no chord


def test_reinit_first_rows_is_the_per_row_searchsorted():
    """The compiled baseline search against numpy's searchsorted per row (irregular steps, equal times too)."""
    rng = np.random.default_rng(6)
    lens = rng.integers(2, 80, 300)
    starts = np.concatenate([[0], np.cumsum(lens)])
    steps = [rng.choice([0.0, 0.05, 0.1, 0.25, 0.5, 0.7], n) for n in lens]
    t = np.concatenate([5.0 * rng.random() + np.cumsum(s) for s in steps])
    obj_first = np.repeat(starts[:-1], lens)
    rows = np.flatnonzero(np.arange(t.size) > obj_first)
    rng.shuffle(rows)
    a = obj_first[rows]
    expect = np.array([max(int(f), int(np.searchsorted(t[f:g], t[g] - 0.5, side="right")) + int(f) - 1) for g, f in zip(rows, a)])
    expect = np.minimum(expect, rows - 1)
    got = reinit_first_rows(t, rows, a, 0.5)
    assert got.dtype == np.int64
    assert np.array_equal(got, expect)
    assert (got >= a).all() and (got < rows).all()


def _objects(B=40, K=70, seed=8):
    """B turning objects of K measurements (irregular steps, 0.2 m noise, some 20 m outliers: alarms)."""
    rng = np.random.default_rng(seed)
    dt = rng.uniform(0.07, 0.13, (B, K))
    t = np.cumsum(dt, axis=1)
    th = rng.uniform(-np.pi, np.pi, (B, 1)) + np.cumsum(np.cumsum(0.1 * rng.standard_normal((B, K)), axis=1) * dt, axis=1)
    v = rng.uniform(1.0, 15.0, (B, 1))
    z = np.stack([np.cumsum(v * np.cos(th) * dt, axis=1), np.cumsum(v * np.sin(th) * dt, axis=1)], -1).reshape(-1, 2)
    z += 0.2 * rng.standard_normal(z.shape)
    out = rng.random(B * K) < 0.01
    z[out] += 20.0 * rng.standard_normal((int(out.sum()), 2))
    heading = (th.ravel() + 0.05 * rng.standard_normal(B * K) + np.pi) % (2 * np.pi) - np.pi
    return t.ravel(), z, K * np.arange(B + 1), heading


@pytest.mark.parametrize("model", sorted(MODELS))
def test_track_monitored_with_a_given_start_and_limits_is_the_same(model):
    """Start and limits made beforehand (as the noise search does) give the same bits, alarms included."""
    t, z, starts, heading = _objects()
    cfg = TrackConfig({model: tuple(0.3 * np.asarray(get_model(model).default_accel_std))}, 0.2, heading_cap=TRACK_HEADING_CAP)
    ref = track_monitored(model, t, z, starts, cfg, heading=heading)
    assert len(ref.alarms) > 0  # the recovery path is exercised
    start = initial_estimates(model, *initial_common(t, z, starts, cfg.meas_std, cfg.omega_std, heading, cfg.heading_std, cfg.heading_cap),
                              moving_backwards(t, z, starts, cfg.meas_std))
    limits = speed_limits(t, z, starts, cfg.meas_std, MonitorConfig())
    got = track_monitored(model, t, z, starts, cfg, heading=heading, start=start, limits=limits)
    for a, b in ((ref.x, got.x), (ref.p, got.p), (ref.nis, got.nis), (ref.flag, got.flag)):
        assert np.array_equal(a, b, equal_nan=True)
    assert ref.alarms == got.alarms


def test_the_search_with_its_shared_start_gives_the_per_run_plan(monkeypatch):
    """plan_noise makes each model's start and the speed limits once; forcing every run to make its own (the
    former path) gives the same NoisePlan exactly: q, k, mse, median NIS and runs of every model."""
    t, z, starts, heading = _objects(B=30, K=60, seed=9)
    models = list(MODELS)

    def plan():
        return plan_noise(t, z, starts, models, omega_std=0.5, heading_std=0.1, heading_cap=TRACK_HEADING_CAP, heading=heading,
                          measurement={"se2se2": "pose"}, workers=1)

    shared = plan()
    real = defaults.track_monitored
    seen = []

    def per_run(*a, start=None, limits=None, **kw):
        seen.append(start is not None and limits is not None)
        return real(*a, **kw)  # the start and the limits made inside, as every run did before

    monkeypatch.setattr(defaults, "track_monitored", per_run)
    alone = plan()
    assert len(seen) > 15 * len(models) and all(seen)  # the search did hand its shared start to every run
    for m in models:
        assert alone.search[m] == shared.search[m], m
        assert (alone.accel_std[m], alone.accel_k[m], alone.median_nis[m]) == (shared.accel_std[m], shared.accel_k[m], shared.median_nis[m])


@pytest.mark.parametrize("model", sorted(MODELS))
def test_run_segments_noise_from_is_run_segments_per_noise_level(model):
    """The reruns' one call with noise stds per segment from internal states (generated
    ``run_segments_noise_from_position``) against ``run_segments_position`` called once per distinct inflation with
    q·s, r·s (the former reruns): same bits; and the states it leaves continue a segment exactly (a segment run
    in two calls = in one)."""
    t, z, starts, _ = _objects(B=12, K=50, seed=10)
    spec = get_model(model)
    k = spec.kernels
    cfg = TrackConfig({}, 0.2)
    x0, P0 = initial_estimates(model, *initial_common(t, z, starts, cfg.meas_std))
    p0 = pack(P0)
    first = starts[:-1] + 2 + np.arange(12) % 5
    lengths = starts[1:] - first - np.arange(12) % 3
    scale = np.array([1.0, 2.0, 1.0, 3.7, 2.0, 1.0, 1.5, 1.5, 3.7, 1.0, 2.0, 1.25])
    q = cfg.q(model)
    r = np.array([cfg.meas_std])
    qs, rs = q[None, :] * scale[:, None], r[None, :] * scale[:, None]
    outs = [(np.zeros((t.size, spec.n)), np.zeros((t.size, spec.n_packed)), np.zeros(t.size)) for _ in range(3)]
    for s in np.unique(scale):
        j = np.flatnonzero(scale == s)
        k.run_segments_position(z, t, first[j], lengths[j], x0[j], p0[j], q * s, r * s, *outs[0])
    s0 = np.empty((12, k.state_from_physical(x0[0]).size))
    k.states_from_physical(x0, s0)
    for i in range(12):
        assert np.array_equal(s0[i], k.state_from_physical(x0[i]))
    s1, p1 = s0.copy(), p0.copy()
    k.run_segments_noise_from_position(z, t, first, lengths, s1, p1, qs, rs, *outs[1])
    for a, b in zip(*outs[:2]):
        assert np.array_equal(a, b)
    assert np.count_nonzero(outs[1][2]) > 0.8 * lengths.sum()
    # in two calls: the first part of every segment, then the rest from the states the first call left
    cut = lengths // 3
    s2, p2 = s0.copy(), p0.copy()
    k.run_segments_noise_from_position(z, t, first, cut, s2, p2, qs, rs, *outs[2])
    k.run_segments_noise_from_position(z, t, first + cut, lengths - cut, s2, p2, qs, rs, *outs[2])
    for a, b in zip(outs[1], outs[2]):
        assert np.array_equal(a, b)
    assert np.array_equal(s1, s2) and np.array_equal(p1, p2)
    last = first + lengths - 1
    assert np.array_equal(p1, outs[1][1][last])  # left at the posterior of each segment's last row


@pytest.mark.parametrize("model", sorted(MODELS))
def test_propagate_positions_are_the_positions_of_propagate_rows(model):
    """The noise search's one-step predictions: ``propagate_positions`` gives exactly the first two columns of
    ``propagate_rows`` (the former computation), every other coordinate left out."""
    rng = np.random.default_rng(11)
    spec = get_model(model)
    c = _common_states(rng, 300)
    x = np.empty((c.shape[0], spec.n))
    spec.kernels.common_to_states(c, x)
    dts = rng.uniform(0.01, 1.0, c.shape[0])
    full = np.empty_like(x)
    spec.kernels.propagate_rows(x, dts, full)
    pos = np.empty((c.shape[0], 2))
    spec.kernels.propagate_positions(x, dts, pos)
    assert np.array_equal(pos, full[:, :2])
    assert not np.array_equal(pos, x[:, :2])  # the states did move
