"""The compiled divergence monitor (the generated ``recover_<meas>``, ``derive/codegen/monitor.py``) against the
algorithm it replaced: rounds of Python over all objects at once (``_recover_in_rounds`` below, the recovery of
lgekf 0.x up to commit de5a4c2), which re-initialise through ``two_point`` / ``initial_estimates`` and rerun
through ``run_segments_noise_from_<meas>`` from Python. The two must agree bit for bit: states, covariances, NIS,
flags, and every alarm (value, limit, window, noise inflation), for every model and measurement, several objects
(objects of 2 and 3 rows among them),
monitors that are quiet, busy (noise inflation), exhausted (``max_reinit``), raising speed alarms, and first
rerun windows of several sizes; with the heading column used for the re-initialisations too.
"""

from __future__ import annotations

import numpy as np
import pytest

import lgekf.apps.divergence as divergence
import lgekf.apps.track as track
from lgekf.apps.divergence import Alarm, MonitorConfig, MonitorMemory, first_alarms, speed_limits
from _reinit_rows import reinit_first_rows
from lgekf.apps.track import TrackConfig, track_arrays, track_monitored
from lgekf.core.covariance import pack
from lgekf.core.registry import MODELS, get_model


def _recover_in_rounds(model, x, p, nis, starts, limits, m, cfg, reinit, rerun, rerun_rows):
    """The round-based recovery: each round scans one segment per object (``first_alarms``), handles every alarm
    at once (numpy), re-initialises through ``reinit(rows, scale)`` and reruns through ``rerun(first, lengths, s0, p0,
    scale)`` (windows of ``rerun_rows`` rows doubling until the next alarm, going on from the previous state)."""
    B = len(starts) - 1
    flag = np.zeros(x.shape[0], np.int8)
    alarms = []
    first = starts[:-1] + 2
    seg_obj = np.flatnonzero(first < starts[1:])
    seg_first, seg_end = first[seg_obj], starts[seg_obj + 1]
    reach = max(cfg.window, cfg.short)
    kernels, ni = get_model(model).kernels, len(get_model(model).internal_names)
    scan_end, scan_from = seg_end.copy(), seg_first.copy()
    seg_s = seg_p = None
    memory = MonitorMemory.fresh(B)
    count, scale, last = memory.count, memory.scale, memory.last
    seg_scale = scale[seg_obj].copy()
    while seg_obj.size:
        row, kind, val, start, lim = first_alarms(model, x, p, nis, scan_from, scan_end, limits[seg_obj], m, cfg)
        hit = np.flatnonzero(row >= 0)
        grow = np.flatnonzero((row < 0) & (scan_end < seg_end))
        if hit.size == 0 and grow.size == 0:
            break
        o, g, k, v = seg_obj[hit], row[hit], kind[hit], val[hit]
        count[o] += 1
        again = (k == 1) & (g - last[o] <= cfg.repeat * cfg.window)
        scale[o[again]] *= np.minimum(np.sqrt(np.maximum(v[again] / m, 1.0)), cfg.max_inflation)
        ok = count[o] <= cfg.max_reinit
        alarms.extend(map(Alarm, o.tolist(), g.tolist(), k.tolist(), v.tolist(), lim[hit].tolist(),
                          np.where(k == 1, g - start[hit] + 1, 0).tolist(), ok.tolist(), scale[o].tolist()))
        for lo, hi in zip(np.maximum(np.maximum(start[hit], seg_first[hit]) - 1, 0), g):
            flag[lo:hi + 1] = 1
        keep = hit[ok]
        last[o[ok]] = g[ok]
        finish = hit[~ok & (scan_end[hit] < seg_end[hit])]
        if finish.size:
            rerun(scan_end[finish], seg_end[finish] - scan_end[finish], seg_s[finish], seg_p[finish], seg_scale[finish])
        g, obj = row[keep], seg_obj[keep]
        x0, p0 = reinit(g, scale[obj]) if keep.size else (x[:0], p[:0])
        x[g], p[g], nis[g] = x0, p0, np.nan
        end = seg_end[keep]
        more = g + 1 < end
        new_first = g[more] + 1
        s0 = np.empty((int(more.sum()), ni))
        kernels.states_from_physical(np.ascontiguousarray(x0[more]), s0)
        nxt = [(obj[more], new_first, end[more], new_first, np.minimum(end[more], new_first + rerun_rows), new_first, s0,
                np.array(p0[more]), scale[obj[more]])]
        if grow.size:
            width = scan_end[grow] - seg_first[grow]
            nxt.append((seg_obj[grow], seg_first[grow], seg_end[grow], np.maximum(seg_first[grow], scan_end[grow] - reach),
                        np.minimum(seg_end[grow], seg_first[grow] + 2 * width), scan_end[grow], seg_s[grow], seg_p[grow], seg_scale[grow]))
        seg_obj, seg_first, seg_end, scan_from, scan_end, run_from, seg_s, seg_p, seg_scale = (np.concatenate(c) for c in zip(*nxt))
        if seg_obj.size:
            rerun(run_from, scan_end - run_from, seg_s, seg_p, seg_scale)
    return flag, alarms


def _reference(model, t, z, starts, cfg, monitor, heading, measurement, rerun_rows):
    """``track_monitored`` through ``_recover_in_rounds``."""
    spec = get_model(model)
    x, p, nis = track_arrays(model, t, z, starts, cfg, heading=heading, measurement=measurement)
    zm, r = track._measurement_inputs(spec, z, heading, cfg, measurement)
    q = cfg.q(model)

    def reinit(rows, scale):
        first = reinit_first_rows(t, rows, starts[np.searchsorted(starts, rows, side="right") - 1], track.REINIT_BASELINE)
        c, var = track.two_point(t, z, rows, cfg.meas_std * np.asarray(scale), cfg.omega_std, heading, cfg.heading_std, cfg.heading_cap, first)
        x0, P0 = track.initial_estimates(model, c, var)
        return x0, pack(P0)

    kernel = getattr(spec.kernels, f"run_segments_noise_from_{measurement}")

    def rerun(first, lengths, s0, p0, scale):
        kernel(zm, t, np.asarray(first, np.int64), np.asarray(lengths, np.int64), s0, p0, q[None, :] * scale[:, None], r[None, :] * scale[:, None],
               x, p, nis)

    limits = speed_limits(t, z, starts, cfg.meas_std, monitor)
    flag, alarms = _recover_in_rounds(model, x, p, nis, starts, limits, zm.shape[1], monitor, reinit, rerun, rerun_rows)
    return x, p, nis, flag, alarms


def _objects(sizes=(400, 2, 300, 3, 500), seed=21):
    """Cars at about 8 m/s whose turn rate jumps now and then, 0.1 m noise and runs of outliers; a heading column
    (the true heading plus 0.05 rad noise)."""
    rng = np.random.default_rng(seed)
    ts, zs, hs = [], [], []
    for i, n in enumerate(sizes):
        dt = rng.uniform(0.08, 0.12, n)
        t = np.cumsum(dt) + 1000.0 * i
        w = np.repeat(rng.choice([0.0, 0.6, -0.9, 1.5], n // 40 + 1), 40)[:n]
        th = np.cumsum(w * dt)
        v = 8.0 + np.cumsum(0.05 * rng.standard_normal(n))
        z = np.column_stack([np.cumsum(v * np.cos(th) * dt), np.cumsum(v * np.sin(th) * dt)]) + 0.1 * rng.standard_normal((n, 2))
        for k in (rng.choice(np.arange(30, n - 10), 3, replace=False) if n > 40 else []):  # runs of outliers
            z[k:k + 4] += rng.normal(0.0, 3.0, 2)
        ts.append(t), zs.append(z), hs.append(th + 0.05 * rng.standard_normal(n))
    starts = np.concatenate([[0], np.cumsum(sizes)])
    return np.concatenate(ts), np.concatenate(zs), np.concatenate(hs), starts


MONITORS = {
    "default": MonitorConfig(),
    "busy": MonitorConfig(alpha=0.2, repeat=20),  # many alarms, the noise inflated again and again
    "exhausted": MonitorConfig(alpha=0.2, max_reinit=3),  # each object runs unmonitored after its 4th alarm
    "speed": MonitorConfig(speed_factor=0.8, speed_margin=0.0, n_sigma=0.0, alpha=1e-12),  # speed alarms
}


def _key(alarms):  # repr: NaN compares equal to itself; each object's alarms in order (the rounds interleave objects)
    return sorted((a.obj, i, repr((a.row, a.kind, a.value, a.limit, a.updates, bool(a.reinitialised), a.scale))) for i, a in
                  enumerate(sorted(alarms, key=lambda a: a.obj)))


@pytest.mark.parametrize("model", list(MODELS))
def test_compiled_recovery_is_the_rounds_bit_for_bit(model, monkeypatch):
    t, z, heading, starts = _objects()
    cfg = TrackConfig(dict(track.DEFAULT_ACCEL_STD), meas_std=0.1, heading_cap=track.TRACK_HEADING_CAP)
    cases = [(None, "position"), (heading, "position")] + ([(heading, "pose")] if "pose" in MODELS[model].measurements else [])
    kinds = set()
    for name, monitor in MONITORS.items():
        for h, measurement in cases:
            for rows in (4, 256):
                monkeypatch.setattr(divergence, "RERUN_ROWS", rows)
                got = track_monitored(model, t, z, starts, cfg, heading=h, measurement=measurement, monitor=monitor)
                x, p, nis, flag, alarms = _reference(model, t, z, starts, cfg, monitor, h, measurement, rows)
                what = f"{model}, {name}, {measurement}{' with heading' if h is not None else ''}, first rerun {rows} rows"
                assert len(alarms) >= 3, what
                assert np.array_equal(got.x, x), what
                assert np.array_equal(got.p, p), what
                assert np.array_equal(got.nis, nis, equal_nan=True), what
                assert np.array_equal(got.flag, flag), what
                assert _key(got.alarms) == _key(alarms), what
                assert [a.obj for a in got.alarms] == sorted(a.obj for a in got.alarms), what  # object after object
                kinds |= {a.kind for a in alarms}
    assert {1, 2} <= kinds  # NIS and speed alarms both went through the comparison


def _two_point_numpy(t, z, i0, i1, meas_std, omega_std, heading, heading_std, heading_cap, sideslip):
    """The two-point rule in NumPy (the form of ``lgekf.core.initiation`` before it was compiled)."""
    dt = t[i1] - t[i0]
    v = (z[i1] - z[i0]) / dt[:, None]
    speed = np.hypot(v[:, 0], v[:, 1])
    r2 = meas_std ** 2
    var_v = 2.0 * r2 / dt ** 2
    c = np.zeros((len(i1), 6))
    c[:, :2] = z[i1]
    var = np.empty((len(i1), 6))
    var[:, 0] = var[:, 1] = r2
    var[:, 3] = var_v
    var[:, 5] = omega_std ** 2
    if heading is None:
        c[:, 2] = np.where(speed > 0, np.arctan2(v[:, 1], v[:, 0]), 0.0)
        c[:, 3] = speed
        with np.errstate(divide="ignore"):
            var[:, 2] = np.minimum(np.where(speed > 0, var_v / np.where(speed > 0, speed, 1.0) ** 2, np.inf), heading_cap ** 2)
        var[:, 4] = np.maximum(var_v - speed ** 2 * var[:, 2], sideslip ** 2 * var_v)
    else:
        h = heading[i1]
        c[:, 2] = np.arctan2(np.sin(h), np.cos(h))
        c[:, 3] = v[:, 0] * np.cos(h) + v[:, 1] * np.sin(h)
        var[:, 2] = heading_std ** 2
        var[:, 4] = sideslip ** 2 * var_v
    return c, var


@pytest.mark.parametrize("model", list(MODELS))
def test_compiled_two_point_start_is_the_numpy_rule(model):
    """``two_point`` and ``initial_estimates`` (the generated ``two_points``, ``initial_covariances``, which the
    compiled monitor's re-initialisations call) against the rule written in NumPy: the same numbers, except the
    heading's atan2 (libm's, where NumPy's SIMD arctan2 may differ by an ulp); P0 = J diag(var) Jᵀ symmetrised with
    each angle's variance capped at π², standing still included (speed 0: heading std at its cap)."""
    from lgekf.core.initiation import SIDESLIP_FRACTION, initial_estimates, two_point

    t, z, heading, _ = _objects((300,), seed=4)
    z[150] = z[149]  # standing still for one step
    rows = np.arange(5, 300, 7)
    rows = np.append(rows, 150)
    first = rows - np.arange(len(rows)) % 3 - 1
    first[-1] = 149  # the standing-still step
    std = 0.05 + 0.01 * np.arange(len(rows))
    spec = get_model(model)
    for h in (None, heading):
        for cap in (np.pi, track.TRACK_HEADING_CAP):
            c, var = two_point(t, z, rows, std, 0.5, h, 0.1, cap, first)
            c_ref, var_ref = _two_point_numpy(t, z, first, rows, std, 0.5, h, 0.1, cap, SIDESLIP_FRACTION)
            assert np.array_equal(np.delete(c, 2, axis=1), np.delete(c_ref, 2, axis=1))
            np.testing.assert_allclose(c[:, 2], c_ref[:, 2], rtol=2.5e-16, atol=5e-324)  # an ulp at most
            assert np.array_equal(var, var_ref)
            x0, P0 = initial_estimates(model, c, var)
            cj = c.copy()
            tiny = 1e-9 * np.sqrt(var[:, 3])
            cj[:, 3] = np.where(np.abs(cj[:, 3]) < tiny, np.where(cj[:, 3] < 0, -tiny, tiny), cj[:, 3])
            J = np.array([spec.kernels.common_jacobian(row) for row in cj])
            P_ref = np.einsum("bij,bj,bkj->bik", J, var, J)
            P_ref = 0.5 * (P_ref + np.swapaxes(P_ref, 1, 2))
            for a in spec.angles:
                big = P_ref[:, a, a] > np.pi ** 2
                s = np.ones((int(big.sum()), spec.n))
                s[:, a] = np.pi / np.sqrt(P_ref[big, a, a])
                P_ref[big] *= s[:, :, None] * s[:, None, :]
            assert np.array_equal(P0, P_ref), model
            assert np.array_equal(x0, np.array([spec.kernels.common_to_state(row) for row in c]))
            if h is None:  # standing still: no heading from the motion, its std at the cap
                assert c[-1, 3] == 0.0 and var[-1, 2] == cap ** 2


def test_largest_eigenvalue_is_lapacks():
    """The speed std's λ_max (the generated ``largest_eigenvalue``, cyclic Jacobi rotations, no LAPACK in the compiled
    monitor) against LAPACK's ``eigvalsh`` on random symmetric positive semi-definite matrices of every size the
    models need, over twelve orders of magnitude, ill-conditioned and rank-deficient ones included."""
    from lgekf.generated.monitor import largest_eigenvalue

    rng = np.random.default_rng(7)
    for k in range(1, 7):
        for trial in range(300):
            A = rng.standard_normal((k, k)) * 10.0 ** rng.uniform(-6, 6)
            if trial % 4 == 0:
                A[:, 0] *= 1e-7  # ill-conditioned
            if trial % 5 == 0 and k > 1:
                A[:, -1] = 0.0  # rank-deficient
            S = A @ A.T
            ref = np.linalg.eigvalsh(S)[-1]
            assert largest_eigenvalue(S.copy(), k) == pytest.approx(ref, rel=1e-14, abs=0.0), (k, trial)
    D = np.diag([3.0, 1.0, 2.0])  # diagonal already: no rotation
    assert largest_eigenvalue(D.copy(), 3) == 3.0


def _speed_std_numpy(model, x, p):
    """The speed std as NumPy computed it before the monitor was compiled (de5a4c2): central differences of the
    speed over whole columns, LAPACK's ``eigvalsh`` on the block of the coordinates the speed depends on."""
    from lgekf.apps.divergence import speeds
    from lgekf.core.covariance import unpack

    n = get_model(model).n
    grad = np.empty((x.shape[0], n))
    for i in range(n):
        h = 1e-6 * np.maximum(1.0, np.abs(x[:, i]))
        xp, xm = x.copy(), x.copy()
        xp[:, i] += h
        xm[:, i] -= h
        grad[:, i] = (speeds(model, xp) - speeds(model, xm)) / (2 * h)
    P = unpack(p, n)
    out = np.zeros(x.shape[0])
    for r in range(x.shape[0]):
        s = np.flatnonzero(np.abs(grad[r]) > 1e-9 * max(1.0, np.abs(grad[r]).max()))
        if s.size:
            out[r] = np.sqrt(max(np.linalg.eigvalsh(P[r][np.ix_(s, s)])[-1], 0.0)) * np.linalg.norm(grad[r, s])
    return out


@pytest.mark.parametrize("model", list(MODELS))
def test_compiled_speed_std_is_the_numpy_one(model):
    """``speed_std`` (the generated ``speed_stds`` / ``speed_std_at``, which the compiled monitor calls) against the
    NumPy computation it replaced, on random states and full random covariances (correlated, so that the packing
    order and the choice of the coordinates the speed depends on matter), standing still included."""
    from lgekf.apps.divergence import speed_std

    spec = get_model(model)
    rng = np.random.default_rng(3)
    c = np.column_stack([rng.normal(0, 50, 200), rng.normal(0, 50, 200), rng.uniform(-3, 3, 200), rng.uniform(-2, 20, 200),
                         rng.normal(0, 0.5, 200), rng.normal(0, 0.5, 200)])
    c[:5, 3:5] = 0.0  # standing still
    x = np.array([spec.kernels.common_to_state(row) for row in c])
    A = rng.standard_normal((200, spec.n, spec.n)) * rng.uniform(0.01, 3.0, (200, 1, 1))
    p = pack(A @ np.swapaxes(A, 1, 2))
    got = speed_std(model, x, p)
    ref = _speed_std_numpy(model, x, p)
    np.testing.assert_allclose(got, ref, rtol=1e-13, atol=1e-300)
    assert np.all(got[5:] > 0)


@pytest.mark.parametrize("model", [m for m in MODELS if "pose" in MODELS[m].measurements])
def test_windows_with_heading_are_one_run(model):
    """``track_windows`` of one object whose re-initialisations read the heading column (position with heading,
    and pose): the rows, flags and alarms of ``track_monitored`` over the object, with windows of 97 rows."""
    from lgekf.apps.track import track_windows

    t, z, heading, _ = _objects((700,), seed=9)
    cfg = TrackConfig(dict(track.DEFAULT_ACCEL_STD), meas_std=0.1, heading_cap=track.TRACK_HEADING_CAP)
    for measurement in ("position", "pose"):
        ref = track_monitored(model, t, z, np.array([0, t.size]), cfg, heading=heading, measurement=measurement, monitor=MONITORS["busy"])
        assert len(ref.alarms) >= 3
        pieces = list(track_windows(model, t, z, cfg, heading, measurement, MONITORS["busy"], rows=97))
        x = np.concatenate([r.x for _, r in pieces])
        assert np.array_equal(x, ref.x) and np.array_equal(np.concatenate([r.p for _, r in pieces]), ref.p), measurement
        assert np.array_equal(np.concatenate([r.flag for _, r in pieces]), ref.flag), measurement
        assert _key([a for _, r in pieces for a in r.alarms]) == _key(ref.alarms), measurement


def test_two_point_with_no_time_between_gives_inf_not_an_exception():
    """The compiled two-point rule divides as NumPy does (``error_model="numpy"``): two measurements at the same
    time (possible through the library, never through ``lgekf track``, which requires increasing times) give an
    infinite velocity variance instead of raising ZeroDivisionError."""
    from lgekf.core.initiation import two_point

    t = np.array([0.0, 1.0, 1.0])
    z = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 0.5]])
    c, var = two_point(t, z, np.array([2]), 0.2, first=np.array([1]))
    assert np.isinf(var[0, 3]) and np.isinf(c[0, 3])
