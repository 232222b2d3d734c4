"""`lgekf evaluate`: statistics helpers, a synthetic dataset end to end (no real data needed), the
loaders of the real datasets (skipped when ../shared/data or $LGEKF_DATA is absent)."""

import csv
import os
import subprocess

import numpy as np
import pytest
from _cli import cli_command

from lgekf.apps.evaluate import FILTERS, TURNING, evaluate_dataset, run_filters, tune_split, world_velocity
from lgekf.apps.report import evaluation_figure, format_table, markdown_table
from lgekf.experiments.statistics import MIN_TRACKS_CI, bootstrap_ci, t_interval, t_quantile
from lgekf.io.datasets import Dataset, data_root, load_dataset
from lgekf.apps.track import TrackConfig, track_arrays
from _real_data import DATA, needs
from _synthetic_tracks import synthetic_tracks, write_synthetic


def evaluate(*args, cwd=None, env=None):
    return subprocess.run([*cli_command(), "evaluate", *map(str, args)], capture_output=True, text=True, cwd=cwd, env=env)


def test_t_quantile_against_scipy():
    stats = pytest.importorskip("scipy.stats")
    for nu in (1, 2, 3, 5, 10, 20, 100, 1000):
        assert t_quantile(0.975, nu) == pytest.approx(stats.t.ppf(0.975, nu), rel=2e-3 if nu > 2 else 1e-2)


def test_t_interval_hand_computed():
    """1, 2, 3, 4, 5: mean 3, s = √2.5, t_{0.975, 4} = 2.776445 (printed tables): half-width 2.776445·√2.5/√5 = 1.96324;
    two values 1 and 3: t_{0.975, 1} = 12.706205, s = √2, half 12.706205; one value: no interval."""
    m, h = t_interval([5.0, 1.0, 4.0, 2.0, 3.0])
    assert m == 3.0 and h == pytest.approx(2.776445 * np.sqrt(0.5), abs=1e-5)
    assert h == pytest.approx(1.96324, abs=1e-5)
    assert t_interval([1.0, 3.0]) == pytest.approx((2.0, 12.706205), abs=1e-6)
    assert t_interval([1.0, 3.0], level=0.9)[1] == pytest.approx(6.313752, abs=1e-6)  # t_{0.95, 1}
    m, h = t_interval([4.0])
    assert m == 4.0 and np.isnan(h)
    assert all(np.isnan(t_interval([])))


def test_bootstrap_ci_never_below_zero_where_the_t_interval_is():
    stats = pytest.importorskip("scipy.stats")
    x = np.array([0.21, 0.24, 0.22, 0.25, 2.9])  # four good tracks and a lost one
    n = x.size
    t_lo = x.mean() - stats.t.ppf(0.975, n - 1) * x.std(ddof=1) / np.sqrt(n)
    assert t_lo < 0  # the case of the issue: a t-interval for an RMSE reaching below zero
    m, lo, hi = bootstrap_ci(x)
    assert m == pytest.approx(x.mean())
    assert x.min() <= lo < m < hi <= x.max()


def test_bootstrap_ci_agrees_with_the_t_interval_for_many_normal_values():
    stats = pytest.importorskip("scipy.stats")
    x = np.random.default_rng(3).normal(0.3, 0.05, 400)
    half = stats.t.ppf(0.975, x.size - 1) * x.std(ddof=1) / np.sqrt(x.size)
    m, lo, hi = bootstrap_ci(x)
    assert lo == pytest.approx(x.mean() - half, abs=0.06 * half)
    assert hi == pytest.approx(x.mean() + half, abs=0.06 * half)


def test_bootstrap_ci_covers_the_true_mean():
    """Coverage of the known mean exp(μ + σ²/2) of lognormal per-track RMSEs (skewed, like real ones)."""
    rng = np.random.default_rng(11)
    mu, sigma, reps = -1.2, 0.5, 400
    true_mean = np.exp(mu + sigma**2 / 2)
    # expected about 0.89 at n = 5 and 0.93 at n = 20 (3000 repetitions); the bounds are 3 binomial sd wide
    for n, least in ((MIN_TRACKS_CI, 0.84), (20, 0.89)):
        hits = 0
        for r in range(reps):
            _, lo, hi = bootstrap_ci(rng.lognormal(mu, sigma, n), resamples=2000, seed=r)
            hits += lo <= true_mean <= hi
        assert least <= hits / reps <= 0.99, (n, hits / reps)


def test_bootstrap_ci_too_few_values_and_reproducible():
    x = [0.3, 0.1, 0.2, 0.4]
    assert len(x) < MIN_TRACKS_CI
    m, lo, hi = bootstrap_ci(x)
    assert m == pytest.approx(0.25) and np.isnan(lo) and np.isnan(hi)
    assert all(np.isnan(bootstrap_ci([])))
    y = [0.3, 0.1, 0.2, 0.4, 0.35, 0.5]
    assert bootstrap_ci(y) == bootstrap_ci(y)  # fixed seed: reruns print the same intervals
    assert bootstrap_ci(y) != bootstrap_ci(y, seed=1)


def test_world_velocity_of_each_model():
    th, v = 0.7, 2.0
    expect = [v * np.cos(th), v * np.sin(th)]
    np.testing.assert_allclose(world_velocity("se2se2", np.array([[0, 0, th, v, 0, 0.1]])), [expect])
    np.testing.assert_allclose(world_velocity("ctrv", np.array([[0, 0, th, v, 0.1]])), [expect])
    np.testing.assert_allclose(world_velocity("cv", np.array([[0, 0, *expect]])), [expect])


def test_evaluate_synthetic_end_to_end(tmp_path):
    data = write_synthetic(tmp_path / "synth.csv", synthetic_tracks(), short=3)
    out = tmp_path / "ev"
    r = evaluate(data, "--seeds", "2", "--out", out)
    assert r.returncode == 0, r.stderr
    assert "synth: 12 tracks used, 1 shorter than 5 skipped" in r.stderr
    rows = list(csv.DictReader(open(out / "summary.csv")))
    assert [x["filter"] for x in rows] == [*FILTERS, "measurements"]
    by = {x["filter"]: x for x in rows}
    for m in FILTERS:
        assert 0 <= float(by[m]["pos_ci_lo"]) <= float(by[m]["pos_rmse"]) <= float(by[m]["pos_ci_hi"])
        assert float(by[m]["vel_rmse"]) > 0 and by[m]["tracks"] == "12" and by[m]["seeds"] == "2"
        assert float(by[m]["pos_median"]) < float(by["measurements"]["pos_median"])  # filtering helps
    # constant-turn truth: the turning models beat CV, which lags in the faster turns
    for m in TURNING:
        assert float(by[m]["pos_rmse"]) < float(by["measurements"]["pos_rmse"])
        assert float(by[m]["dpos_vs_cv"]) < -0.05
    assert (out / "evaluation.png").stat().st_size > 1000
    per = list(csv.DictReader(open(out / "per_track.csv")))
    assert len(per) == 12 * 2 * (len(FILTERS) + 1)
    assert "pos RMSE" in r.stdout and "se2r3" in r.stdout


@pytest.mark.slow
def test_evaluate_tune_uses_only_the_tuning_split(tmp_path):
    data = write_synthetic(tmp_path / "synth.csv", synthetic_tracks(n=10))
    out = tmp_path / "ev"
    r = evaluate(data, "--seeds", "1", "--tune", "--tune-method", "grid", "--out", out, "--no-figure")
    assert r.returncode == 0, r.stderr
    rows = list(csv.DictReader(open(out / "summary.csv")))
    assert {x["noise"] for x in rows} == {"default", "tuned", "-"}
    assert all(x["tracks"] == "7" for x in rows)  # 3 of 10 tracks tune, 7 evaluate
    tun = list(csv.DictReader(open(out / "tuning.csv")))
    assert all(x["tune_tracks"] == "3" for x in tun)
    for m in FILTERS:
        chosen = [x for x in tun if x["filter"] == m and x["chosen"] == "True"]
        assert len(chosen) == 1
        best = min(float(x["tune_pos_rmse"]) for x in tun if x["filter"] == m)
        assert float(chosen[0]["tune_pos_rmse"]) == best
        tuned = next(x for x in rows if x["filter"] == m and x["noise"] == "tuned")
        assert float(tuned["scale"]) == float(chosen[0]["scale"])
        assert float(tuned["turn_ratio"]) == float(chosen[0]["turn_ratio"])
        stages = {x["stage"] for x in tun if x["filter"] == m}
        assert stages == ({"1", "2", "3"} if m in TURNING else {"1"})


@pytest.mark.slow
def test_tuning_never_sees_the_evaluation_tracks():
    rows = synthetic_tracks(n=10, K=20)
    t = np.array([r[1] for r in rows])
    p = np.array([[r[2], r[3]] for r in rows])
    starts = np.arange(0, 201, 20)
    ds = Dataset("s", t, p, None, starts, [str(i) for i in range(10)])
    tune_idx, eval_idx = tune_split(ds.n_tracks)
    assert set(tune_idx).isdisjoint(eval_idx) and len(tune_idx) == 3
    # poisoning the evaluation part does not change the chosen scales
    a = evaluate_dataset(ds, seeds=1, tune=True, tune_method="grid")[1].scale
    ds.p[starts[3]:] += 1e3 * np.random.default_rng(0).standard_normal(ds.p[starts[3]:].shape)
    b = evaluate_dataset(ds, seeds=1, tune=True, tune_method="grid")[1].scale
    assert a == b


def test_run_filters_uses_common_noise_and_track_arrays():
    rows = synthetic_tracks(n=3, K=15)
    t = np.array([r[1] for r in rows])
    p = np.array([[r[2], r[3]] for r in rows])
    ds = Dataset("s", t, p, None, np.array([0, 15, 30, 45]), ["0", "1", "2"])
    cfg = TrackConfig()
    res = run_filters(ds, cfg, [4], 0)
    from lgekf.apps.evaluate import _seed_rng

    z = ds.p + cfg.meas_std * _seed_rng(4, 0, "s").standard_normal(ds.p.shape)
    x, _, _ = track_arrays("se2r3", t, z, ds.starts, cfg)
    e = np.sqrt(np.mean(np.sum((x[17:30, :2] - p[17:30]) ** 2, axis=1)))  # track 1, rows k >= 2
    assert res["se2r3"][0][0, 1] == pytest.approx(e)


@pytest.mark.slow
def test_evaluate_pedestrian_file_and_errors(tmp_path):
    text = "".join(f"{10 * k}\t{i}\t{0.5 * k}\t{1.0 * i + 0.02 * k * k}\n" for k in range(12) for i in range(1, 5))
    data = tmp_path / "ped.txt"
    data.write_text(text)
    r = evaluate(data, "--format", "pedestrian", "--frame-dt", "0.04", "--seeds", "1", "--out", tmp_path / "ev", "--no-figure")
    assert r.returncode == 0, r.stderr
    for args, message in (
        (["nosuchset"], "neither a preset"),
        ([data], "cannot infer the format"),
        ([data, "--format", "pedestrian"], "frame-dt"),
        (["eth", "--data-root", tmp_path / "empty"], "--data-root"),
        ([data, "--format", "pedestrian", "--frame-dt", "0.04", "--meas-std", "-1"], "meas-std"),
        ([data, "--format", "pedestrian", "--frame-dt", "0.04", "--seeds", "0"], "seeds"),
    ):
        r = evaluate(*args, "--out", tmp_path / "bad")
        assert r.returncode == 2 and "Traceback" not in r.stderr, r.stderr
        assert len(r.stderr.strip().splitlines()) == 1 and message in r.stderr, r.stderr
    assert not (tmp_path / "bad").exists()


def _synthetic_dataset(n_tracks, K=40):
    rows = synthetic_tracks(n=n_tracks, K=K)
    return Dataset("few", np.array([r[1] for r in rows]), np.array([[r[2], r[3]] for r in rows]),
                   np.array([[r[4], r[5]] for r in rows]), np.arange(0, K * n_tracks + 1, K),
                   [str(i) for i in range(n_tracks)])


@pytest.mark.parametrize("n_tracks", [1, 2])
def test_tables_say_when_there_are_too_few_tracks_for_an_interval(n_tracks):
    rows = evaluate_dataset(_synthetic_dataset(n_tracks), seeds=2)[0].summary()
    label = f"n/a ({n_tracks} track{'s' if n_tracks > 1 else ''})"
    for table in (format_table(rows), markdown_table(rows)):
        lines = [line for line in table.splitlines() if "few" in line]
        assert len(lines) == len(FILTERS) + 1
        for line in lines:
            assert label in line and "nan" not in line and "[-" not in line, line
        for line in lines:  # the filters compared with CV: position, paired difference, velocity
            if not any(f" {b} " in line for b in ("cv", "measurements")):
                assert line.count(label) == 3, line
    assert all(np.isnan(r["pos_ci_lo"]) and np.isnan(r["pos_ci_hi"]) and r["pos_rmse"] > 0 for r in rows)


def test_tables_give_intervals_from_five_tracks_on():
    rows = evaluate_dataset(_synthetic_dataset(MIN_TRACKS_CI), seeds=1)[0].summary()
    for r in rows:
        assert 0 <= r["pos_ci_lo"] <= r["pos_rmse"] <= r["pos_ci_hi"]
    assert "n/a" not in format_table(rows)


def test_evaluation_figure_of_one_dataset_keeps_title_and_legend_inside(monkeypatch, tmp_path):
    import matplotlib.pyplot as plt

    rows = evaluate_dataset(_synthetic_dataset(2), seeds=1)[0].summary()
    monkeypatch.setattr(plt, "close", lambda fig: None)  # keep the figure to inspect it
    evaluation_figure(rows, tmp_path / "e.png", "default")
    fig = plt.gcf()
    fig.canvas.draw()
    box = fig.bbox
    for artist in (fig._suptitle, *fig.legends):
        ext = artist.get_window_extent()
        assert box.x0 <= ext.x0 and ext.x1 <= box.x1 and ext.y1 <= box.y1, (artist, ext, box)
    monkeypatch.undo()
    plt.close(fig)


def test_evaluate_cli_with_two_tracks_prints_no_negative_or_nan_bound(tmp_path):
    data = write_synthetic(tmp_path / "few.csv", synthetic_tracks(n=2))
    out = tmp_path / "ev"
    r = evaluate(data, "--seeds", "2", "--out", out)
    assert r.returncode == 0, r.stderr
    table = [line for line in r.stdout.splitlines() if line.startswith("few ")]
    assert len(table) == len(FILTERS) + 1
    assert all("n/a (2 tracks)" in line and "nan" not in line and "[-" not in line for line in table)
    rows = list(csv.DictReader(open(out / "summary.csv")))
    assert all(x["pos_ci_lo"] == "" and x["pos_ci_hi"] == "" and float(x["pos_rmse"]) > 0 for x in rows)
    assert (out / "evaluation.png").stat().st_size > 1000


def test_data_root_is_option_then_env_then_cwd_relative(monkeypatch, tmp_path):
    monkeypatch.delenv("LGEKF_DATA", raising=False)
    monkeypatch.chdir(tmp_path)
    assert data_root().resolve() == (tmp_path.parent / "shared" / "data").resolve()
    monkeypatch.setenv("LGEKF_DATA", str(tmp_path / "env"))
    assert data_root() == tmp_path / "env"
    assert data_root(tmp_path / "opt") == tmp_path / "opt"


def test_evaluate_finds_presets_relative_to_the_working_directory(tmp_path):
    """../shared/data next to the current folder, wherever lgekf is installed."""
    folder = tmp_path / "shared" / "data" / "eth_ucy_trajectronpp"
    folder.mkdir(parents=True)
    (folder / "biwi_eth.txt").write_text("".join(f"{10 * k}\t{i}\t{0.5 * k}\t{1.0 * i + 0.02 * k * k}\n" for k in range(12) for i in range(1, 7)))
    (tmp_path / "work").mkdir()
    env = {k: v for k, v in os.environ.items() if k != "LGEKF_DATA"}
    r = evaluate("eth", "--seeds", "1", "--no-figure", "--out", tmp_path / "ev", cwd=tmp_path / "work", env=env)
    assert r.returncode == 0, r.stderr
    assert "eth: 6 tracks used" in r.stderr


def test_missing_dataset_names_its_source_and_how_to_point_at_it(tmp_path):
    env = {k: v for k, v in os.environ.items() if k != "LGEKF_DATA"}
    for args, env_extra, source in (
        (["eth"], {}, "github.com/StanfordASL/Trajectron-plus-plus"),
        (["kitti"], {"LGEKF_DATA": str(tmp_path / "nothing")}, "github.com/crowdbotp/OpenTraj"),
        (["dut", "--data-root", tmp_path], {}, "github.com/dongfang-steven-yang/vci-dataset-dut"),
    ):
        r = evaluate(*args, "--out", tmp_path / "ev", cwd=tmp_path, env={**env, **env_extra})
        assert r.returncode == 2 and "Traceback" not in r.stderr, r.stderr
        assert len(r.stderr.strip().splitlines()) == 1, r.stderr
        assert source in r.stderr and "--data-root" in r.stderr and "$LGEKF_DATA" in r.stderr, r.stderr
        if not env_extra and "--data-root" not in args:
            assert f"relative to the current folder {tmp_path}" in r.stderr, r.stderr
    assert not (tmp_path / "ev").exists()


# ------------------------------------------------------------------ real data (skipped when absent)
def test_eth_ucy_presets_and_time_step():
    needs("eth_ucy_trajectronpp/biwi_eth.txt")
    eth = load_dataset("eth", root=DATA, min_length=2)
    assert eth.n_tracks == 360 and eth.t.size == 5492
    # SOURCES.md: 10 frames = 0.6667 s; median speed then ~1.47 m/s (the obsmat velocity median)
    with np.errstate(divide="ignore", invalid="ignore"):  # steps between tracks are masked below
        step = np.diff(eth.p, axis=0) / np.diff(eth.t)[:, None]
    inside = np.ones(len(step), bool)
    inside[eth.starts[1:-1] - 1] = False
    assert np.median(np.hypot(*step[inside].T)) == pytest.approx(1.47, abs=0.05)
    assert np.allclose(np.diff(eth.t)[inside], 0.6667)
    eth5 = load_dataset("eth", root=DATA)
    assert eth5.n_tracks + eth5.skipped == 360 and eth5.skipped > 0
    univ = load_dataset("univ", root=DATA, min_length=2)
    assert univ.n_tracks == 415 + 434 and np.allclose(np.diff(univ.t[:2]), 0.4)


def test_kitti_loader_velocity_truth_matches_positions():
    needs("kitti_oxts/0000.txt")
    ds = load_dataset("kitti", root=DATA)
    assert ds.n_tracks == 21 and ds.v is not None
    fds, vs = [], []
    for i in range(ds.n_tracks):
        a, b = ds.starts[i], ds.starts[i + 1]
        fds.append((ds.p[a + 2:b] - ds.p[a:b - 2]) / (ds.t[a + 2:b] - ds.t[a:b - 2])[:, None])
        vs.append(ds.v[a + 1:b - 1])
    fd, v = np.concatenate(fds), np.concatenate(vs)
    moving = np.hypot(*v.T) > 2.0
    fd, v = fd[moving], v[moving]
    # 0.1035 s steps: finite-difference speed within ~2 % of the OXTS speed (it is 4.7 % off with 0.1 s)
    assert np.median(np.hypot(*fd.T) / np.hypot(*v.T)) == pytest.approx(1.0, abs=0.025)
    cos = np.sum(fd * v, axis=1) / np.hypot(*fd.T) / np.hypot(*v.T)
    assert np.median(cos) > 0.999  # (ve, vn) point along the Mercator track


def test_cyclists_and_dut_loaders():
    needs("vru_cyclists_moving")
    needs("dut_vehicles/raw")
    cyc = load_dataset("cyclists", root=DATA)
    assert cyc.n_tracks == 86 and np.median(np.diff(cyc.t[:50])) == pytest.approx(0.08)
    dut = load_dataset("dut", root=DATA)
    assert dut.n_tracks == 69 and dut.t.size == 18765
    a, b = dut.starts[0], dut.starts[1]
    speed = np.median(np.hypot(*np.diff(dut.p[a:b], axis=0).T) / np.diff(dut.t[a:b]))
    assert 1.0 < speed < 20.0  # metres per second, not pixels


def test_evaluate_real_subset_runs():
    needs("eth_ucy_trajectronpp/crowds_zara01.txt")
    ds = load_dataset("zara1", root=DATA)
    res = evaluate_dataset(ds.subset(range(20)), seeds=1)[0]
    rows = {r["filter"]: r for r in res.summary()}
    assert all(np.isfinite(rows[m]["pos_rmse"]) for m in FILTERS)
    assert rows["cv"]["pos_rmse"] < rows["measurements"]["pos_rmse"]
