"""A long object tracked in windows of rows (``lgekf.apps.track.track_windows``, ``lgekf.apps.windows``) gives the rows of one run, bit for bit.

Compared with ``track_monitored`` over the whole object (the path of every object up to ``ROWS_PER_CHUNK`` rows):
states, covariances, NIS, flags and alarms, for every model, with the monitor quiet, busy (noise inflation), out of
re-initialisations (``max_reinit``) and off, and windows shorter than the monitor's NIS window; then `lgekf track`
on a file whose long object goes through the windows against the same file in one chunk.
"""

from __future__ import annotations

import re

import numpy as np
import pytest

import lgekf.apps.track as track
from lgekf.apps.divergence import MonitorConfig
from lgekf.apps.track import TrackConfig, track_monitored
from lgekf.apps.track import track_windows
from lgekf.cli import main
from lgekf.core.registry import MODELS


def _long_object(n=1500, seed=11):
    """A car at about 8 m/s whose turn rate jumps now and then (manoeuvres the filters with little process noise
    lose), positions with 0.1 m noise and a few runs of outliers; steps of 0.08-0.12 s."""
    rng = np.random.default_rng(seed)
    dt = rng.uniform(0.08, 0.12, n)
    t = np.cumsum(dt)
    w = np.repeat(rng.choice([0.0, 0.0, 0.6, -0.9, 1.5], n // 50 + 1), 50)[:n]
    th = np.cumsum(w * dt)
    v = 8.0 + np.cumsum(0.05 * rng.standard_normal(n))
    x = np.cumsum(v * np.cos(th) * dt)
    y = np.cumsum(v * np.sin(th) * dt)
    z = np.column_stack([x, y]) + 0.1 * rng.standard_normal((n, 2))
    for k in rng.choice(np.arange(50, n - 10), 6, replace=False):
        z[k:k + 4] += rng.normal(0.0, 3.0, 2)
    return t, z


MONITORS = {
    "default": MonitorConfig(),
    "busy": MonitorConfig(alpha=0.2, repeat=20),  # many alarms, noise inflated again and again
    "exhausted": MonitorConfig(alpha=0.2, max_reinit=3),  # the object runs unmonitored after its 4th alarm
    "short > window": MonitorConfig(window=2, short=6, alpha=0.05),  # the scan restarts max(window, short) rows back
    "off": None,
}


def _alarms(alarms):  # repr: a non-finite alarm's value (NaN) compares equal to itself
    return [repr((a.obj, a.row, a.kind, a.value, a.limit, a.updates, bool(a.reinitialised), a.scale)) for a in alarms]


@pytest.mark.parametrize("model", list(MODELS))
def test_windows_give_the_rows_of_one_run(model):
    t, z = _long_object()
    cfg = TrackConfig(dict(track.DEFAULT_ACCEL_STD), meas_std=0.1, heading_cap=track.TRACK_HEADING_CAP)
    seen_kinds = set()
    for name, mon in MONITORS.items():
        ref = track_monitored(model, t, z, np.array([0, t.size]), cfg, monitor=mon)
        if mon is not None:
            assert ref.alarms, f"{name}: the test object should raise alarms"
        if name == "exhausted":
            assert any(not a.reinitialised for a in ref.alarms)
        if name == "busy":
            assert any(a.scale > 1.0 for a in ref.alarms)
        seen_kinds |= {a.kind for a in ref.alarms}
        for rows in (4, 97, 700):
            pieces = list(track_windows(model, t, z, cfg, monitor=mon, rows=rows))
            assert [a for a, _ in pieces] == list(np.cumsum([0] + [r.x.shape[0] for _, r in pieces[:-1]]))
            got = {k: np.concatenate([getattr(r, k) for _, r in pieces]) for k in ("x", "p", "nis", "flag")}
            what = f"{model}, monitor {name}, windows of {rows} rows"
            assert np.array_equal(got["x"], ref.x), what
            assert np.array_equal(got["p"], ref.p), what
            assert np.array_equal(got["nis"], ref.nis, equal_nan=True), what
            assert np.array_equal(got["flag"], ref.flag), what
            assert _alarms([a for _, r in pieces for a in r.alarms]) == _alarms(ref.alarms), what
    assert 1 in seen_kinds


def test_rows_must_be_positive():
    t, z = _long_object(200)
    with pytest.raises(ValueError, match="rows"):
        next(track_windows("cv", t, z, TrackConfig(), rows=0))


def _file(path, long_rows=700, seed=5):
    t, z = _long_object(long_rows, seed)
    lines = ["id,t,x,y"]
    rows = [(float(t[k]), "long", z[k]) for k in range(t.size)]
    rng = np.random.default_rng(seed)
    for o in range(3):  # short objects around it
        for k in range(40):
            rows.append((0.1 * k + 0.01 * o, f"walker{o}", np.array([o + 1.2 * 0.1 * k, 0.3 * o]) + 0.05 * rng.standard_normal(2)))
    rows.sort(key=lambda r: r[0])
    lines += [f"{lab},{tt!r},{float(p[0])!r},{float(p[1])!r}" for tt, lab, p in rows]
    path.write_text("\n".join(lines) + "\n")
    return path


@pytest.mark.parametrize("model", ["cv", "se2se2"])
@pytest.mark.parametrize("extra", [[], ["--no-monitor"], ["--full-cov", "--meas-std", "0.03"]])
def test_cli_long_object_in_windows_writes_the_bytes_of_one_chunk(tmp_path, monkeypatch, model, extra):
    inp = _file(tmp_path / "in.csv")
    args = ["track", str(inp), "--model", model, "--quiet", "--accel-std", ",".join(["0.5"] * len(MODELS[model].noise_names)), *extra]
    assert main([*args, "-o", str(tmp_path / "one.csv")]) == 0  # 820 rows: one chunk, no windows
    monkeypatch.setattr(track, "ROWS_PER_CHUNK", 64)  # the long object (700 rows) in windows of 64 rows
    windows = []
    real = track.track_windows

    def counted(*a, **k):
        for piece in real(*a, **k):
            windows.append(piece[0])
            yield piece

    monkeypatch.setattr(track, "track_windows", counted)
    assert main([*args, "-o", str(tmp_path / "windows.csv")]) == 0
    assert len(windows) >= 700 // 64
    assert (tmp_path / "windows.csv").read_bytes() == (tmp_path / "one.csv").read_bytes()


def test_cli_long_object_alarms_after_the_first_window_warn_as_one_chunk(tmp_path, monkeypatch, capsys):
    """The divergence warnings (alarm rows, times) of a long object in windows are those of one chunk: an object that
    jumps by 5 m at row 400, in windows of 64 and 128 rows (the alarm well after the first window)."""
    rng = np.random.default_rng(1)
    t = 0.1 * np.arange(700)
    z = np.column_stack([8.0 * t, 0.0 * t]) + 0.1 * rng.standard_normal((700, 2))
    z[400:] += 5.0
    inp = tmp_path / "in.csv"
    inp.write_text("id,t,x,y\n" + "".join(f"long,{float(a)!r},{float(b)!r},{float(c)!r}\n" for a, (b, c) in zip(t, z)))
    args = ["track", str(inp), "--model", "cv", "--accel-std", "0.5", "--meas-std", "0.1", "--quiet"]
    assert main([*args, "-o", str(tmp_path / "one.csv")]) == 0
    one = capsys.readouterr().err
    hit = re.search(r"diverged at line (\d+) \(t = (40\.\d*) s\)", one)
    assert hit, one  # the input's line of the alarm row: row k of the object is line k + 2 (t = 0.1 k, header line 1)
    assert int(hit.group(1)) == round(float(hit.group(2)) / 0.1) + 2
    for rows in (64, 128):
        monkeypatch.setattr(track, "ROWS_PER_CHUNK", rows)
        assert main([*args, "-o", str(tmp_path / f"w{rows}.csv")]) == 0
        assert capsys.readouterr().err == one
        assert (tmp_path / f"w{rows}.csv").read_bytes() == (tmp_path / "one.csv").read_bytes()


@pytest.mark.parametrize("model", list(MODELS))
def test_rerun_windows_continue_exactly(model, monkeypatch):
    """After a re-initialisation the monitor reruns the filter over windows that double, each going on from the
    internal state where the previous one ended and scanned from max(window, short) rows before it
    (``divergence.RERUN_ROWS`` the first): the rows, flags and alarms of one rerun to the object's end scanned at
    once (RERUN_ROWS larger than the object), bit for bit, also with several objects, noise inflation, speed alarms
    and a monitor that stops at max_reinit. (Before the windows went on from their predecessor's state, each restarted
    from the re-initialisation; this test would have passed for that too.)"""
    import lgekf.apps.divergence as divergence

    parts = [_long_object(700, seed=s) for s in (11, 12, 13)]
    t = np.concatenate([p[0] + 1000.0 * i for i, p in enumerate(parts)])
    z = np.concatenate([p[1] for p in parts])
    starts = np.array([0, 700, 1400, 2100])
    cfg = TrackConfig(dict(track.DEFAULT_ACCEL_STD), meas_std=0.1, heading_cap=track.TRACK_HEADING_CAP)
    monitors = {name: MONITORS[name] for name in ("default", "busy", "exhausted", "short > window")}
    # speed alarms too (their first flagged row counts the run of rows over the limit, which the resumed scan rebuilds):
    # a limit below the object's own speed, no margin, NIS tests all but off
    monitors["speed"] = MonitorConfig(speed_factor=0.8, speed_margin=0.0, n_sigma=0.0, alpha=1e-12)
    kinds = set()
    for name, mon in monitors.items():
        monkeypatch.setattr(divergence, "RERUN_ROWS", 10**6)
        ref = track_monitored(model, t, z, starts, cfg, monitor=mon)
        assert len(ref.alarms) >= 3, name
        kinds |= {a.kind for a in ref.alarms}
        for rows in (1, 3, 16):
            monkeypatch.setattr(divergence, "RERUN_ROWS", rows)
            got = track_monitored(model, t, z, starts, cfg, monitor=mon)
            what = f"{model}, monitor {name}, first rerun window {rows} rows"
            assert np.array_equal(got.x, ref.x), what
            assert np.array_equal(got.p, ref.p), what
            assert np.array_equal(got.nis, ref.nis, equal_nan=True), what
            assert np.array_equal(got.flag, ref.flag), what
            # the same alarms, each object's in the same order (the compiled monitor lists them object after object;
            # comparing per object keeps this test about the windows, not the listing)
            by_object = lambda alarms: sorted(_alarms(alarms), key=lambda a: int(a[1:a.index(",")]))  # noqa: E731
            assert by_object(got.alarms) == by_object(ref.alarms), what
    assert {1, 2} <= kinds  # NIS and speed alarms
