"""The divergence monitor of `lgekf track --multi` (lgekf.apps.multi_monitor): its three rules on a stub tracker
(thresholds from SciPy's chi-square, not from the code under test), and the flag column from the command line."""

import subprocess

import numpy as np
import pytest
from scipy.stats import chi2

from _cli import cli_command
from lgekf.apps.divergence import MonitorConfig
from lgekf.apps.multi_monitor import MultiMonitor
from lgekf.estimators.multitarget.tracker import ScanReport




class StubTracker:
    """What the monitor reads from a MultiTargetTracker: held (ids, rows), held_nis; and drop(ids)."""

    def __init__(self):
        self.held = (np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64))
        self.held_nis = np.zeros(0)
        self.dropped = []

    def drop(self, ids):
        self.dropped += list(ids)


def cv_report(t, ids, speeds):
    """CV states (x, y, vx, vy) moving along x at the given speeds."""
    ids = np.asarray(ids, dtype=np.int64)
    x = np.zeros((ids.size, 4))
    x[:, 2] = speeds
    return ScanReport(t, ids, x, np.ones((ids.size, 4)), np.full(ids.size, 0.99))


def test_nis_window_alarms_when_the_clipped_sum_exceeds_the_chi_square_quantile():
    cfg = MonitorConfig()
    mon = MultiMonitor("cv", 2, max_speed=30.0, config=cfg)
    trk = StubTracker()
    short = chi2.ppf(1 - cfg.alpha, 2 * cfg.short)
    long = chi2.ppf(1 - cfg.alpha, 2 * cfg.window)
    d = 0.95 * short / cfg.short  # three in a row stay below the short threshold
    assert cfg.window * d > long  # ... but ten of them exceed the long one
    row = 0
    for k in range(cfg.window):
        trk.held, trk.held_nis = (np.array([7]), np.array([0])), np.array([d])
        flags, keep = mon.scan(trk, cv_report(0.1 * k, [7], [5.0]), row)
        row += int(keep.sum())
        if k < cfg.window - 1:
            assert flags == [] and trk.dropped == [], k
    assert trk.dropped == [7]
    assert flags == list(range(cfg.window))  # the track's rows of the window (it has only W rows so far)
    a = mon.alarms[0]
    assert a.kind == 1 and a.track == 7 and a.value == pytest.approx(cfg.window * d) and a.limit == pytest.approx(long)


def test_one_nis_at_the_gate_does_not_alarm_but_three_clipped_ones_do():
    cfg = MonitorConfig()
    clip = chi2.ppf(1 - cfg.clip, 2)
    assert 3 * clip > chi2.ppf(1 - cfg.alpha, 2 * cfg.short)
    mon, trk = MultiMonitor("cv", 2, max_speed=30.0, config=cfg), StubTracker()
    for k, d in enumerate([1e6, 1.0, 1.0, 1e6, 1e6, 1e6]):
        trk.held, trk.held_nis = (np.array([3]), np.array([0])), np.array([d])
        mon.scan(trk, cv_report(0.1 * k, [3], [5.0]), k)
        assert (trk.dropped == [3]) == (k == 5), k  # clipped: one huge NIS counts as `clip`, 2 + 2 clip < short limit


def test_speed_rule_uses_twice_max_speed_plus_margin():
    cfg = MonitorConfig()
    limit = cfg.speed_factor * 10.0 + cfg.speed_margin
    mon, trk = MultiMonitor("cv", 2, max_speed=10.0, config=cfg), StubTracker()
    flags, keep = mon.scan(trk, cv_report(0.0, [1, 2, 3], [limit - 0.01, limit + 0.01, 5.0]), 0)
    assert trk.dropped == [2] and flags == [1] and keep.all()
    assert mon.alarms[0].kind == 2 and mon.alarms[0].value == pytest.approx(limit + 0.01)


def test_non_finite_row_is_not_written_and_the_tracks_previous_rows_are_flagged():
    mon, trk = MultiMonitor("cv", 2, max_speed=30.0), StubTracker()
    mon.scan(trk, cv_report(0.0, [4, 5], [1.0, 1.0]), 0)  # rows 0 (track 4), 1 (track 5)
    rep = cv_report(0.1, [4, 5], [1.0, 1.0])
    rep.states[1, 0] = np.nan
    flags, keep = mon.scan(trk, rep, 2)
    assert keep.tolist() == [True, False] and flags == [1] and trk.dropped == [5] and mon.alarms[0].kind == 3


def _fast_object_csv(path, rng):
    """One object accelerating along x from 3 to 30 m/s over 12 s, 10 Hz, 0.1 m noise (one detection per scan)."""
    t = np.arange(0.0, 12.0, 0.1)
    v = 3.0 + 27.0 * np.clip((t - 2.0) / 8.0, 0.0, 1.0)
    x = np.cumsum(v) * 0.1
    z = np.column_stack([x, np.zeros_like(x)]) + 0.1 * rng.standard_normal((t.size, 2))
    path.write_text("t,x,y\n" + "".join(f"{a:.2f},{b:.4f},{c:.4f}\n" for a, (b, c) in zip(t, z)))


@pytest.mark.slow
def test_cli_multi_flags_a_track_that_runs_past_the_speed_limit(tmp_path):
    _fast_object_csv(tmp_path / "fast.csv", np.random.default_rng(1))
    # two-point: its track follows the object past the limit (one-point's, at the process noise estimated then,
    # loses it at 9.6 m/s, below the limit of 11 m/s, and no new track starts on an object faster than --max-speed)
    base = [*cli_command(), "track", str(tmp_path / "fast.csv"), "--multi", "--model", "cv", "--max-speed", "5",
            "--meas-std", "0.1", "--clutter-density", "1e-6", "--initiation", "two-point"]
    r = subprocess.run([*base, "-o", str(tmp_path / "on.csv")], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert "possible divergence: 1 track deleted by the monitor (speed)" in r.stderr
    on = np.loadtxt(tmp_path / "on.csv", delimiter=",", skiprows=1, ndmin=2)
    assert np.all(np.isfinite(on))
    speed, flag = on[:, 10], on[:, -1]
    assert flag.sum() >= 1 and speed[flag == 1].max() > 2 * 5 + 1  # the alarm's row is past the limit, flagged
    assert speed[flag == 0].max() <= 2 * 5 + 1
    r = subprocess.run([*base, "--no-monitor", "-o", str(tmp_path / "off.csv")], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert "possible divergence" not in r.stderr
    off = np.loadtxt(tmp_path / "off.csv", delimiter=",", skiprows=1, ndmin=2)
    assert np.all(off[:, -1] == 0) and off[:, 10].max() > 2 * 5 + 1  # unmonitored: past the limit, no flag
    first = int(np.argmax(flag == 1))
    np.testing.assert_array_equal(on[:first, :-1], off[:first, :-1])  # the monitor changes nothing before its alarm
