"""One odd object among normal ones (issue 27): each case a file made for it, run as a user runs ``lgekf track``
(per-object unit checks, noise pooled robustly, an estimate at a floor said, v ≥ 0 for the forward-speed models)."""

from __future__ import annotations

import csv
import re

import numpy as np
import pytest

from lgekf.cli import main


def _car(rng, K=200, dt=0.1):
    """A car at 5-12 m/s turning at up to 0.2 rad/s, 10 Hz: (t, x, y) true."""
    t = np.arange(K) * dt
    sp, th0, w = rng.uniform(5, 12), rng.uniform(-np.pi, np.pi), rng.uniform(-0.2, 0.2)
    x0, y0 = rng.uniform(-200, 200, 2)
    th = th0 + w * t
    return t, x0 + sp / w * (np.sin(th) - np.sin(th0)), y0 - sp / w * (np.cos(th) - np.cos(th0))


def _write(path, objs, sigma=0.3, seed=1):
    """objs: (id, t, x, y, scale): positions with noise sigma (m) written in units of scale (1000: mm, 1e-3: km);
    returns {id: true positions (K, 2) in metres}."""
    rng = np.random.default_rng(seed)
    truth = {}
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["id", "t", "x", "y"])
        for oid, t, x, y, scale in objs:
            zx, zy = (x + rng.normal(0, sigma, x.size)) * scale, (y + rng.normal(0, sigma, y.size)) * scale
            w.writerows([oid, repr(float(a)), repr(float(b)), repr(float(c))] for a, b, c in zip(t, zx, zy))
            truth[oid] = np.column_stack([x, y])
    return path


def _cars(n=5, seed=0):
    rng = np.random.default_rng(seed)
    return [(f"car{i}", *_car(rng), 1.0) for i in range(n)], rng


def _track(tmp_path, capsys, name, objs, *opts):
    src = _write(tmp_path / f"{name}.csv", objs)
    out = tmp_path / f"{name}_out.csv"
    code = main(["track", str(src), "-o", str(out), *opts])
    err = capsys.readouterr().err
    assert code == 0, err
    rows = list(csv.DictReader(open(out)))
    return err, rows


def _rmse(rows, objs, ids):
    """Position RMSE (m) of the objects ``ids`` against the truth (rows 2 on)."""
    truth = {o[0]: np.column_stack([o[2], o[3]]) for o in objs}
    e = []
    for oid in ids:
        est = np.array([[float(r["x"]), float(r["y"])] for r in rows if r["id"] == oid])
        e.append(np.sum((est[2:] - truth[oid][2:]) ** 2, axis=1))
    return float(np.sqrt(np.mean(np.concatenate(e))))


def _accel(err, model="se2se2"):
    """The first process-noise std of ``model`` in each 'noise from the data' line of stderr."""
    return [float(v) for v in re.findall(rf"accel-std {model} ([0-9.e+-]+),", err)]


def _warnings(err):
    return [ln for ln in err.splitlines() if ln.startswith("lgekf track: warning: ")]


def test_one_object_in_mm_is_named_and_leaves_the_others_alone(tmp_path, capsys):
    cars, rng = _cars()
    odd = ("odd_mm", *_car(rng), 1000.0)
    err0, rows0 = _track(tmp_path, capsys, "base", cars)
    err1, rows1 = _track(tmp_path, capsys, "mm", cars + [odd])
    lines = [w for w in _warnings(err1) if "odd_mm" in w]
    assert len(lines) == 1 and "mm" in lines[0] and "t = 0" in lines[0], err1
    assert not any("car" in w for w in _warnings(err1)), err1  # the normal objects are not named
    ids = [c[0] for c in cars]
    r0, r1 = _rmse(rows0, cars, ids), _rmse(rows1, cars, ids)
    assert abs(r1 / r0 - 1) < 0.10, (r0, r1)
    assert abs(_accel(err1)[0] / _accel(err0)[0] - 1) < 0.2, (err0, err1)  # the others' class: their own noise


def test_an_hour_long_gap_in_one_object_does_not_raise_the_others_process_noise(tmp_path, capsys):
    cars, rng = _cars()
    t, x, y = _car(rng)
    t = t.copy()
    t[100:] += 3600.0
    err0, rows0 = _track(tmp_path, capsys, "base", cars)
    err1, rows1 = _track(tmp_path, capsys, "gap", cars + [("gap1h", t, x, y, 1.0)])
    q0, q1 = _accel(err0), _accel(err1)
    assert len(q0) == len(q1) == 1 and abs(q1[0] / q0[0] - 1) < 0.2, (err0, err1)  # ×8 before
    gap = [w for w in _warnings(err1) if "gap1h" in w and "gap of 3600 s" in w]
    assert len(gap) == 1 and "t = 3610" in gap[0], err1  # the first row after the gap (row 100: 10 s + 1 h)
    lines = (tmp_path / "gap.csv").read_text().splitlines()
    line = next(i + 1 for i, s in enumerate(lines) if s.startswith("gap1h,") and float(s.split(",")[1]) == 3610.0)
    assert f"line {line} (t = 3610" in gap[0], gap[0]  # and its line in the file
    ids = [c[0] for c in cars]
    assert _rmse(rows1, cars, ids) < 1.1 * _rmse(rows0, cars, ids)


def test_coordinates_in_km_are_said_at_the_floor(tmp_path, capsys):
    cars, _ = _cars()
    err, _ = _track(tmp_path, capsys, "km", [(o, t, x, y, 1e-3) for o, t, x, y, _ in cars])
    floor = [w for w in _warnings(err) if "floor 0.001 m" in w]
    assert len(floor) == 1 and "km" in floor[0], err
    errm, _ = _track(tmp_path, capsys, "m", cars)
    assert not _warnings(errm), errm  # the same file in metres: no warning


def _walker(path, backwards_start=True, seed=3):
    """A pedestrian walking in -x at 1.3 m/s, 2.5 Hz, 0.1 m noise; its second measurement 0.3 m in +x of its first
    (a noisy start whose first step points against the motion)."""
    rng = np.random.default_rng(seed)
    t = 0.4 * np.arange(150)
    x, y = 50 - 1.3 * t + rng.normal(0, 0.1, t.size), 3 + 0.3 * np.sin(0.2 * t) + rng.normal(0, 0.1, t.size)
    if backwards_start:
        x[1] = x[0] + 0.3
    path.write_text("id,t,x,y\n" + "".join(f"walker,{float(a)!r},{float(b)!r},{float(c)!r}\n" for a, b, c in zip(t, x, y)))
    return path


@pytest.mark.parametrize("model,heading", [("ctrv", "psi"), ("se2r2", "theta")])
def test_a_pedestrian_whose_first_step_points_back_gets_v_positive_and_its_heading_along_the_motion(tmp_path, capsys, model, heading):
    src = _walker(tmp_path / "walker.csv")
    out = tmp_path / "out.csv"
    assert main(["track", str(src), "-o", str(out), "--model", model, "--quiet"]) == 0
    rows = list(csv.DictReader(open(out)))
    v = np.array([float(r["v"]) for r in rows])
    h = np.array([float(r[heading]) for r in rows])
    course = np.array([float(r["course"]) for r in rows])
    assert np.mean(v >= 0) >= 0.95, v[:20]  # 1 % before (v < 0 from row 2 on)
    off = np.abs(np.angle(np.exp(1j * (h - course))))
    assert np.mean(off < 0.3) >= 0.9, off[:20]
    assert np.mean(np.abs(np.angle(np.exp(1j * (h - np.pi)))) < 0.3) >= 0.9  # the walker heads in -x
