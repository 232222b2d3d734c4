"""The process-noise search in threads (lgekf.apps.search): the same NoisePlan as the serial search on
simulated data with every model (exactly: k, q, mse, median NIS, runs), the serial tie-breaking whatever
order the runs finish in, the serial search's error when a run fails (also through the CLI: one line, no
traceback), threads really used, and no numba parallel kernel on a search run's path."""

from __future__ import annotations

import random
import threading
import time

import numba
import numpy as np
import pytest

from lgekf.apps import defaults, search
from lgekf.apps.defaults import plan_noise
from lgekf.apps.noise import K_GRID, accel_std_family, process_noise_search
from lgekf.apps.search import process_noise_searches, usable_cpus
from lgekf.cli import main
from lgekf.core.registry import MODELS, get_model


def turning_objects(B=48, K=90, seed=5):
    """B objects of K measurements each (irregular steps around 0.1 s, turn rate a random walk, 0.2 m noise,
    a few 15 m outliers so that the divergence monitor raises alarms), with headings; sorted by object."""
    rng = np.random.default_rng(seed)
    dt = rng.uniform(0.07, 0.13, (B, K))
    t = np.cumsum(dt, axis=1)
    w = np.cumsum(0.08 * rng.standard_normal((B, K)), axis=1) + rng.uniform(-0.4, 0.4, (B, 1))
    th = rng.uniform(-np.pi, np.pi, (B, 1)) + np.cumsum(w * dt, axis=1)
    speed = rng.uniform(1.0, 15.0, (B, 1))
    x = np.cumsum(speed * np.cos(th) * dt, axis=1)
    y = np.cumsum(speed * np.sin(th) * dt, axis=1)
    z = np.stack([x, y], axis=-1).reshape(-1, 2) + 0.2 * rng.standard_normal((B * K, 2))
    out = rng.random(B * K) < 0.004
    z[out] += 15.0 * rng.standard_normal((int(out.sum()), 2))
    heading = (th.ravel() + 0.05 * rng.standard_normal(B * K) + np.pi) % (2 * np.pi) - np.pi
    return t.ravel(), z, K * np.arange(B + 1), heading


@pytest.fixture(scope="module")
def data():
    return turning_objects()


def _plan(data, workers, **kw):
    t, z, starts, heading = data
    return plan_noise(t, z, starts, list(MODELS), omega_std=0.5, heading_std=0.1, heading=heading, workers=workers, **kw)


def test_parallel_plan_equals_the_serial_plan(data):
    serial = _plan(data, workers=1, measurement={"se2se2": "pose", "ctrv": "pose"})
    assert all(serial.accel_source[m] == "data" for m in MODELS)
    assert len({serial.search[m].k for m in MODELS}) > 1 or len({serial.search[m].q for m in MODELS}) > 1  # models differ
    for workers in (2, 3):  # 3 threads on (at most) 2 CPUs: other interleavings of the runs
        par = _plan(data, workers=workers, measurement={"se2se2": "pose", "ctrv": "pose"})
        for m in MODELS:
            assert par.search[m] == serial.search[m], m  # k, q, mse, median NIS and number of runs, exactly
            assert (par.accel_std[m], par.accel_k[m], par.median_nis[m]) == (serial.accel_std[m], serial.accel_k[m], serial.median_nis[m])
        assert par.describe() == serial.describe()


def test_the_search_runs_in_several_threads_with_the_serial_runs(data, monkeypatch):
    """The runs of the parallel search (all models' stages in one pool) are the serial search's runs, made in
    more than one thread."""
    calls = {1: [], 2: []}
    threads = set()
    real = defaults.track_monitored
    current = []

    def spy(model, *a, **kw):
        calls[current[0]].append((model, tuple(a[3].accel_std[model])))
        threads.add(threading.get_ident())
        return real(model, *a, **kw)

    monkeypatch.setattr(defaults, "track_monitored", spy)
    t, z, starts, heading = data
    for w in (1, 2):
        current[:] = [w]
        plan_noise(t, z, starts, ["cv", "se2r2"], omega_std=0.5, heading_std=0.1, workers=w)
    assert sorted(calls[1]) == sorted(calls[2]) and len(calls[1]) > 20
    assert len(threads - {threading.get_ident()}) >= 2  # the pool's threads, not (only) the caller's


def _fake_runs(models, score_of, delays=None, fail=None):
    """run(q) -> (nis, err2) with err2 = score_of(model, q) everywhere; a random delay per call (other finishing
    orders); ``fail`` = {model: set of q} raise ValueError(f"boom {model} {q}")."""

    def make(m):
        def run(q):
            if delays is not None:
                time.sleep(delays.random() * 0.002)
            if fail and q in fail.get(m, ()):
                raise ValueError(f"boom {m} {q}")
            v = score_of(m, q)
            return np.full(10, 1.5), np.full(10, v)
        return run

    return {m: make(m) for m in models}


def test_ties_go_to_the_first_candidate_in_list_order_whatever_the_finishing_order():
    """Scores with many exact ties (coarse levels of k): the parallel search with runs finishing in random
    order chooses what the serial search chooses, over many orders."""
    models = ["se2se2", "ctrv", "cv"]

    def score_of(m, q):  # flat valleys: many candidates tie at the minimum
        return float(round(abs(np.log2(q[0] + 1e-9) - len(m) % 3) / 2.0)) + 0.01 * (q[-1] > 0.2 and m == "ctrv")

    serial = {m: process_noise_search(_fake_runs([m], score_of)[m], m, 7.0) for m in models}
    for seed in range(15):
        par = process_noise_searches(_fake_runs(models, score_of, random.Random(seed)), 7.0, workers=4)
        assert par == serial, seed


@pytest.mark.parametrize("workers", [1, 2, 4])
def test_a_failing_run_raises_the_serial_searchs_error(workers):
    """cv fails at its first stage, se2se2 (before it in model order) only at its last run: the serial search
    meets se2se2's error first, and so must the parallel one, whatever the threads."""
    v_typ = 7.0
    order = []

    def record(q):
        order.append(q)
        return np.full(10, 1.5), np.full(10, 1.0)

    process_noise_search(record, "se2se2", v_typ)
    cv_first = [tuple(float(v) for v in accel_std_family("cv", K_GRID[i], v_typ)) for i in range(0, len(K_GRID), 2)]
    fail = {"se2se2": {order[-1]}, "cv": {cv_first[2], cv_first[1]}}  # se2se2's last run (of its last stage)
    for seed in range(5):
        runs = _fake_runs(["se2se2", "cv"], lambda m, q: 1.0, random.Random(seed), fail)
        with pytest.raises(ValueError, match=r"^boom se2se2 "):
            process_noise_searches(runs, v_typ, workers=workers)
    only_cv = _fake_runs(["cv"], lambda m, q: 1.0, random.Random(0), fail)
    with pytest.raises(ValueError) as e:  # within a stage: the first failing candidate in list order
        process_noise_searches(only_cv, v_typ, workers=workers)
    assert str(e.value) == f"boom cv {cv_first[1]}"


def test_a_failing_run_is_one_clear_line_in_the_cli(tmp_path, monkeypatch, capsys):
    t, z, starts, _ = turning_objects(B=30, K=80, seed=2)
    inp = tmp_path / "in.csv"
    obj = np.repeat(np.arange(30), 80)
    np.savetxt(inp, np.column_stack([obj, t, z]), delimiter=",", header="id,t,x,y", comments="", fmt=["%d", "%.6f", "%.6f", "%.6f"])
    real = defaults.track_monitored

    def failing(model, *a, **kw):
        if model == "cv" and a[3].accel_std["cv"][0] > 3.0:
            raise ValueError("search run failed: test")
        return real(model, *a, **kw)

    monkeypatch.setattr(defaults, "track_monitored", failing)
    monkeypatch.setattr(search, "usable_cpus", lambda: 2)
    monkeypatch.setattr(defaults, "usable_cpus", lambda: 2)
    out = tmp_path / "out.csv"
    rc = main(["track", str(inp), "-o", str(out), "--model", "all", "--quiet"])
    err = capsys.readouterr().err
    assert rc != 0
    assert err.strip().splitlines() == ["lgekf track: error: search run failed: test"], err
    assert "Traceback" not in err
    assert not list(tmp_path.glob("out*.csv"))  # no partial output


def test_no_numba_parallel_kernel_on_a_search_run(data, monkeypatch):
    """Two threads must never enter numba's threading layer at once (the workqueue layer aborts): every
    parallel=True kernel of the generated modules replaced by one that raises, the parallel search still runs."""
    replaced = 0
    for m in MODELS:
        kern = get_model(m).kernels
        for name in dir(kern):
            f = getattr(kern, name)
            if isinstance(f, numba.core.registry.CPUDispatcher) and f.targetoptions.get("parallel"):
                def boom(*a, _n=f"{m}.{name}", **k):
                    raise AssertionError(f"parallel kernel {_n} called in the search")
                monkeypatch.setattr(kern, name, boom)
                replaced += 1
    assert replaced >= 2 * len(MODELS)  # at least run_batch_position and simulate_batch of every model
    t, z, starts, heading = data
    plan = plan_noise(t, z, starts, list(MODELS), omega_std=0.5, heading_std=0.1, heading=heading, workers=2,
                      measurement={"se2se2": "pose"})
    assert all(plan.accel_source[m] == "data" for m in MODELS)


def test_usable_cpus_and_the_serial_fallback(data, monkeypatch):
    assert 1 <= usable_cpus()
    seen = []
    real = search.process_noise_searches

    def spy(runs, v_typ, grid=K_GRID, workers=None):
        seen.append(workers)
        return real(runs, v_typ, grid, workers=workers)

    monkeypatch.setattr(defaults, "process_noise_searches", spy)
    monkeypatch.setattr(defaults, "usable_cpus", lambda: 2)
    t, z, starts, _ = data
    assert 900 < search.PARALLEL_MIN_ROWS <= t.size
    plan_noise(t[:900], z[:900], starts[:11], ["cv"], omega_std=0.5, heading_std=0.1)  # 900 rows: serial
    plan_noise(t, z, starts, ["cv"], omega_std=0.5, heading_std=0.1)  # 4320 rows (>= PARALLEL_MIN_ROWS): every usable CPU
    assert seen == [1, 2]
