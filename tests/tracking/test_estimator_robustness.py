"""Every estimator of ``lgekf track`` is monitored and writes finite values: the IMM's monitor and recovery
(``lgekf.apps.imm_monitor``), its noise from the data, and ``--smooth`` over monitored segments (single models and
the IMM), on fast objects of the kind that made them diverge (aircraft-like: ~136 m/s, ~1 Hz, 20 m noise)."""

from __future__ import annotations

import csv

import numpy as np
import pytest

from lgekf.apps import smooth_track
from lgekf.apps.divergence import Alarm, MonitorConfig
from lgekf.apps.imm_monitor import first_imm_alarm, imm_monitored
from lgekf.apps.track import TRACK_HEADING_CAP, REINIT_BASELINE, Tracked, initial_common
from lgekf.cli import main
from lgekf.estimators.imm.estimator import parse_modes

CFG = MonitorConfig()


def _fast_objects(path, n_obj=6, K=120, speed=136.0, turn=0.05, noise=20.0, seed=3):
    """Aircraft-like tracks: constant speed, turns of ±``turn`` rad/s switched every 30 steps, ~1 Hz jittered stamps.
    Returns the truth {(id, t): (x, y)}."""
    rng = np.random.default_rng(seed)
    rows, truth = ["id,t,x,y"], {}
    for o in range(n_obj):
        t = np.cumsum(np.r_[0.0, 1.0 + rng.uniform(-0.2, 0.2, K - 1)])
        psi, p, w = rng.uniform(-np.pi, np.pi), rng.uniform(-3e3, 3e3, 2), 0.0
        for k in range(K):
            if k % 30 == 0:
                w = rng.choice([0.0, turn, -turn])
            z = p + noise * rng.standard_normal(2)
            rows.append(f"a{o},{t[k]:.3f},{z[0]:.3f},{z[1]:.3f}")
            truth[(f"a{o}", round(t[k], 3))] = p.copy()
            if k < K - 1:
                h = t[k + 1] - t[k]
                psi += w * h
                p = p + speed * h * np.array([np.cos(psi), np.sin(psi)])
    path.write_text("\n".join(rows) + "\n")
    return truth


def _read(path):
    return list(csv.DictReader(open(path)))


def _floats(rows, col):
    return np.array([float(r[col]) for r in rows])


# ----------------------------------------------------------------------------------------- the IMM's monitor

def test_first_imm_alarm_quiet_on_a_consistent_estimate():
    rng = np.random.default_rng(0)
    K, r = 400, 2.0
    z = np.cumsum(rng.standard_normal((K, 2)), axis=0)
    c = np.zeros((K, 6))
    c[:, :2] = z + 0.5 * r * rng.standard_normal((K, 2))  # posterior residuals smaller than the measurement noise
    c[:, 3] = 10.0
    P = np.tile(np.eye(6) * 0.25, (K, 1, 1))
    assert first_imm_alarm(z, c, P, r, limit=50.0, cfg=CFG) is None


def test_first_imm_alarm_finds_each_kind_at_its_row():
    rng = np.random.default_rng(1)
    K, r = 100, 1.0
    z = rng.standard_normal((K, 2))
    c = np.zeros((K, 6))
    c[:, :2] = z
    P = np.tile(np.eye(6) * 0.01, (K, 1, 1))
    drift = c.copy()
    drift[60:, 0] += 30.0  # the estimate leaves the measurements at row 60
    k, kind, value, thr, updates, k_flag = first_imm_alarm(z, drift, P, r, 1e9, CFG)
    # each residual is clipped at its 99.99 % quantile (one outlier cannot raise an alarm): the short window of 3
    # updates is the first to exceed its threshold, on its third row; flagged from the row before the window
    assert kind == 1 and k == 60 + CFG.short - 1 and updates == CFG.short and value > thr and k_flag == 59
    fast = c.copy()
    fast[40, 3] = 80.0  # 80 m/s against a limit of 20 m/s, the std tiny
    assert first_imm_alarm(z, fast, P, r, 20.0, CFG)[:2] == (40, 2)
    uncertain = P.copy()
    uncertain[40, 3, 3] = 30.0 ** 2  # ... but not when the filter's own 3 sigma covers it
    assert first_imm_alarm(z, fast, uncertain, r, 20.0, CFG) is None
    bad = c.copy()
    bad[7, 5] = np.nan
    assert first_imm_alarm(z, bad, P, r, 20.0, CFG)[:2] == (7, 3)


def _one_object(seed=5, K=150):
    rng = np.random.default_rng(seed)
    t = np.cumsum(np.r_[0.0, 1.0 + rng.uniform(-0.2, 0.2, K - 1)])
    psi, p, pts = 0.3, np.zeros(2), []
    for k in range(K):
        pts.append(p.copy())
        if k < K - 1:
            psi += (0.05 if (k // 30) % 2 else -0.05) * (t[k + 1] - t[k])
            p = p + 136.0 * (t[k + 1] - t[k]) * np.array([np.cos(psi), np.sin(psi)])
    truth = np.array(pts)
    return t, truth + 20.0 * rng.standard_normal(truth.shape), truth


def test_imm_monitor_recovers_what_the_unmonitored_imm_loses():
    t, z, truth = _one_object()  # 20 m noise ...
    starts = np.array([0, t.size])
    r = 1.0  # ... but a std of 1 m, as a pooled estimate gives such an object in a file of cars and pedestrians
    modes = parse_modes("cv,se2r3:calm,se2r3:manoeuvre")  # and the models' fixed defaults: too small for 136 m/s turns
    c0, var0 = initial_common(t, z, starts, r, 0.5, heading_cap=TRACK_HEADING_CAP)
    limit = 2 * 140.0 + 50.0
    free = imm_monitored(t, z, modes, 0.05, r, 0.5, c0[0], var0[0], limit, None, REINIT_BASELINE, TRACK_HEADING_CAP)
    watched = imm_monitored(t, z, modes, 0.05, r, 0.5, c0[0], var0[0], limit, CFG, REINIT_BASELINE, TRACK_HEADING_CAP)
    err = lambda run: np.hypot(*(run.c[2:, :2] - truth[2:]).T)  # noqa: E731
    assert err(free).max() > 500.0  # the premise: unmonitored, this IMM loses the object
    assert watched.alarms and watched.flag.any()
    assert np.isfinite(watched.c[2:]).all()
    assert err(watched).max() < 150.0
    # no row the monitor would call diverged is left unflagged: every segment, scanned again, raises at most the
    # alarm that ended it, and that alarm's row is flagged
    for seg in watched.segments:
        hit = first_imm_alarm(z[seg.first:seg.end], watched.c[seg.first:seg.end], watched.P[seg.first:seg.end], r * seg.scale,
                              limit, CFG)
        assert hit is None
    for al in watched.alarms:
        assert watched.flag[al.row] == 1


# ----------------------------------------------------------------------------------------- smoothing segments

def test_smooth_segments_split_at_re_initialisations():
    starts = np.array([0, 10, 30])
    alarms = [Alarm(1, 18, 1, 5.0, 3.0, scale=2.0), Alarm(1, 25, 2, 99.0, 50.0, scale=2.0),
              Alarm(0, 6, 1, 5.0, 3.0, reinitialised=False)]
    first, length, start, scale = smooth_track.smooth_segments_of(starts, alarms)
    assert first.tolist() == [2, 12, 19, 26]
    assert length.tolist() == [8, 6, 6, 4]
    assert start.tolist() == [1, 11, 18, 25]
    assert scale.tolist() == [1.0, 1.0, 2.0, 2.0]


def test_smoothed_columns_keep_the_filter_where_the_smoother_fails(monkeypatch):
    from lgekf.apps.track import TrackConfig, smoothing_inputs, track_monitored

    t, z, _ = _one_object(K=40)
    t2, z2 = np.r_[t, t], np.vstack([z, z + 5.0])
    starts = np.array([0, 40, 80])
    cfg = TrackConfig({"cv": (8.0,)}, 20.0)
    tr = track_monitored("cv", t2, z2, starts, cfg)
    zm, q, r = smoothing_inputs("cv", z2, cfg)
    real = smooth_track.smooth_segments

    def broken(model, meas, t, zm, first, lengths, *args, **kw):  # the second object's smoother blows up
        x, p = real(model, meas, t, zm, first, lengths, *args, **kw)
        x[60] = np.inf
        return x, p

    monkeypatch.setattr(smooth_track, "smooth_segments", broken)
    out, failed = smooth_track.smoothed_columns("cv", "position", t2, zm, starts, tr, q, r)
    assert failed == [1]
    assert np.isfinite(out).all()
    np.testing.assert_array_equal(out[40:, :4], tr.x[40:])  # the filter's values
    assert not np.array_equal(out[2:40, :4], tr.x[2:40])  # the first object smoothed


# ----------------------------------------------------------------------------------------- the CLI, no options

@pytest.fixture(scope="module")
def fast_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("fast") / "fast.csv"
    truth = _fast_objects(path)
    return path, truth


@pytest.mark.parametrize("model", ["imm", "se2r3"])
def test_track_with_defaults_on_fast_objects_is_finite_and_smooth_leaves_the_filter_alone(fast_file, tmp_path, capsys, model):
    src, truth = fast_file
    plain, smooth = tmp_path / "plain.csv", tmp_path / "smooth.csv"
    assert main(["track", str(src), "--model", model, "-o", str(plain), "--quiet"]) == 0
    assert main(["track", str(src), "--model", model, "--smooth", "-o", str(smooth), "--quiet"]) == 0
    a, b = _read(plain), _read(smooth)
    cols = [c for c in a[0] if c not in ("nis",)]
    for c in cols:  # the filter's columns are the same with and without --smooth
        assert [r[c] for r in a] == [r[c] for r in b], c
    values = np.array([[float(v) for k, v in r.items() if k not in ("id", "nis")] for r in b])
    assert np.isfinite(values).all()
    tx = np.array([truth[(r["id"], round(float(r["t"]), 3))] for r in b])
    err = np.hypot(_floats(b, "x") - tx[:, 0], _floats(b, "y") - tx[:, 1])
    serr = np.hypot(_floats(b, "smooth_x") - tx[:, 0], _floats(b, "smooth_y") - tx[:, 1])
    raw = 20.0 * np.sqrt(2.0)
    assert np.sqrt(np.mean(err ** 2)) < raw and np.sqrt(np.mean(serr ** 2)) < np.sqrt(np.mean(err ** 2))
    if "omega" in a[0]:
        assert np.abs(_floats(a, "omega")).max() < 1.0  # the turns are 0.05 rad/s; the defaults diverged to ~14


def test_imm_smoother_stays_bounded_where_the_pairwise_gain_blew_up():
    """Boats (12 m/s, 10 Hz, 8 m noise) under the IMM's default modes: with the mixed prediction alone as the pairwise
    RTS step's prediction, every object's smoothed std grew to ~1e41 m (the guard then kept the filter's values); with
    the prediction floored at mode i's own re-prediction (imm_smoother._prediction_floor) the smoother succeeds and
    improves on the filter."""
    from lgekf.apps.track_imm import ImmTrackOptions, imm_track_common

    rng = np.random.default_rng(1)
    ts, zs, ps = [], [], []
    for _ in range(3):
        t = np.cumsum(np.r_[0.0, 0.1 * (1 + rng.uniform(-0.2, 0.2, 299))])
        psi = rng.uniform(-np.pi, np.pi) + np.cumsum(np.r_[0.0, 0.2 * np.sign(np.sin(t[1:] / 3.0)) * np.diff(t)])
        p = np.vstack([[0.0, 0.0], np.cumsum(12.0 * np.diff(t)[:, None] * np.column_stack([np.cos(psi[:-1]), np.sin(psi[:-1])]), 0)])
        ts.append(t), ps.append(p), zs.append(p + 8.0 * rng.standard_normal(p.shape))
    starts = np.r_[0, np.cumsum([len(t) for t in ts])]
    t, z, p = np.concatenate(ts), np.vstack(zs), np.vstack(ps)
    res = imm_track_common(t, z, starts, 8.0, 0.5, ImmTrackOptions(), smooth=True, full=True)
    assert res.smooth_failed == []
    keep = np.ones(t.size, bool)
    keep[np.r_[starts[:-1], starts[:-1] + 1]] = False
    e_f = np.hypot(*(res.c[keep, :2] - p[keep]).T)
    e_s = np.hypot(*(res.c_smooth[keep, :2] - p[keep]).T)
    assert np.sqrt(np.mean(e_s ** 2)) < 0.8 * np.sqrt(np.mean(e_f ** 2))
    assert np.nanmax(res.sd_smooth[:, :2]) < 10.0
