"""Noise per class of objects: a file that mixes sensors (or kinds of objects) gets each class's own measurement std and
process noise (``lgekf.apps.defaults.noise_classes``, ``plan_noise_by_class``), in ``lgekf track`` and ``--model imm``."""

from __future__ import annotations

import csv
import re

import numpy as np
import pytest

from lgekf.apps.defaults import noise_classes, plan_noise, plan_noise_by_class
from lgekf.io.grouping import objects_subset
from lgekf.apps.noise import measurement_std, object_measurement_stds
from lgekf.cli import main

KINDS = {"ped": (1.4, 0.2, 0.1), "car": (15.0, 0.5, 0.1), "boat": (12.0, 8.0, 0.1), "air": (136.0, 20.0, 1.0)}  # speed, noise, dt


def _objects(kinds, n_each=4, K=150, seed=0):
    """t, z, truth, starts, labels of objects moving at constant speed with gentle turns, per kind (speed, noise, dt)."""
    rng = np.random.default_rng(seed)
    ts, zs, ps, labels = [], [], [], []
    for name in kinds:
        speed, noise, dt = KINDS[name]
        for i in range(n_each):
            t = dt * np.arange(K)
            psi = rng.uniform(-np.pi, np.pi) + 0.02 * np.cumsum(np.full(K, dt)) * rng.choice([-1, 1])
            step = speed * dt * np.column_stack([np.cos(psi), np.sin(psi)])
            p = rng.uniform(-100, 100, 2) + np.vstack([[0, 0], np.cumsum(step[:-1], axis=0)])
            ts.append(t)
            ps.append(p)
            zs.append(p + noise * rng.standard_normal(p.shape))
            labels.append(f"{name}{i}")
    starts = np.r_[0, np.cumsum([len(t) for t in ts])]
    return np.concatenate(ts), np.vstack(zs), np.vstack(ps), starts, labels


def test_object_stds_find_each_objects_noise():
    t, z, _, starts, _ = _objects(["ped", "boat"], n_each=2)
    r, n = object_measurement_stds(t, z, starts)
    assert (n == 147).all()
    np.testing.assert_allclose(r, [0.2, 0.2, 8.0, 8.0], rtol=0.25)
    # a 3-row object has no window: no estimate of its own
    r3, n3 = object_measurement_stds(t[:3], z[:3], np.array([0, 3]))
    assert n3[0] == 0 and np.isnan(r3[0])


def test_classes_separate_sensors_and_keep_one_sensor_together():
    t, z, _, starts, labels = _objects(["ped", "car", "boat", "air"])
    pooled = measurement_std(t, z, starts).meas_std
    label, std = noise_classes(t, z, starts, pooled)
    assert label.tolist() == [0] * 4 + [1] * 4 + [2] * 4 + [3] * 4  # by increasing std, one class per kind
    t1, z1, _, s1, _ = _objects(["car"], n_each=8, seed=1)
    label1, _ = noise_classes(t1, z1, s1, measurement_std(t1, z1, s1).meas_std)
    assert (label1 == 0).all()


def test_a_short_object_takes_the_pooled_std():
    t, z, _, starts, _ = _objects(["car"], n_each=3)
    t = np.r_[t, 100.0, 100.1, 100.2]  # a 3-row object far off: no window, the pooled class
    z = np.vstack([z, [[1e3, 1e3], [1e3 + 50, 1e3], [1e3, 1e3 + 50]]])
    starts = np.r_[starts, starts[-1] + 3]
    label, std = noise_classes(t, z, starts, measurement_std(t, z, starts).meas_std)
    assert (label == 0).all() and std[-1] == pytest.approx(measurement_std(t, z, starts).meas_std)


def test_one_class_is_plan_noise_itself():
    t, z, _, starts, _ = _objects(["car"], n_each=6, seed=2)
    kw = dict(omega_std=0.5, heading_std=0.1, heading_cap=0.3)
    classes = plan_noise_by_class(t, z, starts, ["cv", "se2r3"], **kw)
    plan = plan_noise(t, z, starts, ["cv", "se2r3"], **kw)
    assert len(classes.plans) == 1
    assert classes.plans[0].meas_std == plan.meas_std and classes.plans[0].accel_std == plan.accel_std


def test_objects_subset_rows_in_order():
    rows, sub = objects_subset(np.array([0, 3, 5, 9]), np.array([0, 2]))
    assert rows.tolist() == [0, 1, 2, 5, 6, 7, 8] and sub.tolist() == [0, 3, 7]


def rmse_per_kind(rows, truth) -> dict:
    """Position RMSE per kind of object (the id without its number) of output rows against the truth."""
    err2 = {}
    for r in rows:
        tx = truth[(r["id"], round(float(r["t"]), 2))]
        err2.setdefault(r["id"].rstrip("0123456789"), []).append((float(r["x"]) - tx[0]) ** 2 + (float(r["y"]) - tx[1]) ** 2)
    return {k: float(np.sqrt(np.mean(v))) for k, v in err2.items()}


@pytest.fixture(scope="module")
def mixed_file(tmp_path_factory):
    t, z, p, starts, labels = _objects(["ped", "car", "air"], n_each=3, K=120, seed=4)
    path = tmp_path_factory.mktemp("mixed") / "mixed.csv"
    rows = ["id,t,x,y"]
    truth = {}
    for b, lab in enumerate(labels):
        for i in range(starts[b], starts[b + 1]):
            rows.append(f"{lab},{t[i]:.2f},{float(z[i, 0])!r},{float(z[i, 1])!r}")
            truth[(lab, round(t[i], 2))] = p[i]
    path.write_text("\n".join(rows) + "\n")
    return path, truth


@pytest.mark.parametrize("model", ["se2se2", "imm"])
def test_track_gives_each_class_its_noise(mixed_file, tmp_path, capsys, model):
    src, truth = mixed_file
    out = tmp_path / "out.csv"
    assert main(["track", str(src), "--model", model, "-o", str(out)]) == 0
    err = capsys.readouterr().err
    assert "objects differ" in err and "3 classes" in err, err
    stds = [float(v) for v in re.findall(r"class \d: noise from the data: meas-std ([0-9.e+-]+) m", err)]
    np.testing.assert_allclose(stds, [0.2, 0.5, 20.0], rtol=0.3)
    rows = list(csv.DictReader(out.open()))
    rmse = rmse_per_kind(rows, truth)
    # every kind tracked well below its own raw noise (with one pooled std the pedestrians and cars were not)
    for kind in ("ped", "car", "air"):
        raw = KINDS[kind][1] * np.sqrt(2)
        assert rmse[kind] < 0.75 * raw, kind
    assert all(r["flag"] == "0" for r in rows if r["id"].startswith("ped"))


def test_tune_fits_each_class_on_its_own_objects(mixed_file, tmp_path, capsys):
    src, truth = mixed_file
    out = tmp_path / "out.csv"
    assert main(["track", str(src), "--model", "cv", "--tune", "-o", str(out)]) == 0
    err = capsys.readouterr().err
    fitted = [float(v) for v in re.findall(r"class \d: learned noise for cv .*?meas_r = ([0-9.e+-]+)", err)]
    np.testing.assert_allclose(fitted, [0.2, 0.5, 20.0], rtol=0.3)  # one fit per class, each its own sensor's noise


@pytest.mark.slow
def test_imm_tune_fits_each_class_on_its_own_objects_with_one_mode_set(mixed_file, tmp_path, capsys):
    """--model imm --tune on three sensors in one file: one IMM fit per class (one fit for the whole file gave
    RMSE 0.36 / 0.88 / 25.2 m for pedestrians / cars / aircraft; per class 0.11 / 0.35 / 20.2 m), every class
    with the same mode set (one set of mu_ columns)."""
    src, truth = mixed_file
    out = tmp_path / "out.csv"
    assert main(["track", str(src), "--model", "imm", "--tune", "-o", str(out)]) == 0
    err = capsys.readouterr().err
    stds = [float(v) for v in re.findall(r"class \d: imm: modes .*? meas-std ([0-9.e+-]+) m", err)]
    np.testing.assert_allclose(stds, [0.2, 0.5, 20.0], rtol=0.3)
    modes = re.findall(r"class \d: imm: modes (.*?); switch", err)
    assert len(modes) == 3 and len({tuple(n.split(" (")[0] for n in m.split("), ")) for m in modes}) == 1, modes
    rows = list(csv.DictReader(out.open()))
    rmse = rmse_per_kind(rows, truth)
    for kind in ("ped", "car", "air"):
        assert rmse[kind] < 0.8 * KINDS[kind][1] * np.sqrt(2), kind


def test_short_objects_join_the_class_of_most_windows():
    """Objects of 3 rows have no estimate of their own: with the pooled std between two sensors' they would make a class
    whose plan is the library default; they join the class of most windows instead."""
    t, z, _, starts, _ = _objects(["ped", "air"], n_each=3)
    rng = np.random.default_rng(9)
    for _ in range(3):  # three short objects
        t = np.r_[t, 0.1 * np.arange(3)]
        z = np.vstack([z, rng.uniform(-50, 50, 2) + 5.0 * rng.standard_normal((3, 2))])
        starts = np.r_[starts, starts[-1] + 3]
    label, _ = noise_classes(t, z, starts, measurement_std(t, z, starts).meas_std)
    assert label.max() == 1  # the two sensors' classes, no third one
    assert (label[-3:] == label[0]).all() or (label[-3:] == label[3]).all()


def test_interleaved_classes_are_put_back_in_place(tmp_path, capsys):
    """Objects of different classes alternating in the file: a class's rows are gathered and put back, row by row."""
    t, z, p, starts, labels = _objects(["ped", "air"], n_each=3, K=80, seed=5)
    order = [0, 3, 1, 4, 2, 5]  # ped0, air0, ped1, air1, ...
    src = tmp_path / "alternating.csv"
    rows, truth = ["id,t,x,y"], {}
    for b in order:
        for i in range(starts[b], starts[b + 1]):
            rows.append(f"{labels[b]},{t[i]:.2f},{float(z[i, 0])!r},{float(z[i, 1])!r}")
            truth[(labels[b], round(t[i], 2))] = p[i]
    src.write_text("\n".join(rows) + "\n")
    for model in ("se2se2", "imm"):
        out = tmp_path / f"{model}.csv"
        assert main(["track", str(src), "--model", model, "--smooth", "-o", str(out), "--quiet"]) == 0
        got = list(csv.DictReader(out.open()))
        assert [r["id"] for r in got][::80] == [labels[b] for b in order]  # the file's object order
        for kind in ("ped", "air"):
            e = [np.hypot(float(r["smooth_x"]) - truth[(r["id"], round(float(r["t"]), 2))][0],
                          float(r["smooth_y"]) - truth[(r["id"], round(float(r["t"]), 2))][1]) for r in got if r["id"].startswith(kind)]
            assert np.sqrt(np.mean(np.square(e))) < 0.75 * KINDS[kind][1] * np.sqrt(2), (model, kind)
