"""`lgekf track --tune --smooth` and `lgekf evaluate --tune --smooth` (MLE) end to end, as a user runs them."""

import csv
import subprocess

import numpy as np
import pytest
from _cli import cli_command
from _synthetic_tracks import synthetic_tracks, write_synthetic

from lgekf.apps.evaluate import FILTERS
from lgekf.experiments.simulate import simulate


def run(*args, cwd):
    return subprocess.run([*cli_command(), *map(str, args)], capture_output=True, text=True, cwd=cwd)


def _simulated_file(path, B=4, K=80, missing=(40, 41)):
    rng = np.random.default_rng(1)
    sim = simulate(np.tile([0, 0, 0, 3.0, 0, 0], (B, 1)), dt=0.1, steps=K, sigma_v=0.5, sigma_w=0.3, meas_std=0.3, rng=rng)
    lines = ["id,t,x,y"]
    for b in range(B):
        for k in range(K):
            if k not in missing:  # a gap: two missed detections
                lines.append(f"{b},{0.1 * (k + 1):.2f},{float(sim.z[b, k, 0])!r},{float(sim.z[b, k, 1])!r}")
    path.write_text("\n".join(lines) + "\n")
    return sim


def test_track_tune_smooth_writes_smoothed_columns_closer_to_the_truth(tmp_path):
    sim = _simulated_file(tmp_path / "obj.csv")
    r = run("track", "obj.csv", "--model", "se2r3", "--tune", "--smooth", "-o", "out.csv", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert "learned noise for se2r3 (position, 4 tracks" in r.stderr and "95 %" in r.stderr
    rows = list(csv.DictReader(open(tmp_path / "out.csv")))
    head = list(rows[0])
    assert head[-12:] == [f"smooth_{s}" for s in ("x", "y", "theta", "vx", "vy", "omega")] + \
        [f"smooth_std_{s}" for s in ("x", "y", "theta", "vx", "vy", "omega")]
    err_f, err_s = [], []
    for row in rows:
        b, k = int(row["id"]), int(round(float(row["t"]) / 0.1))
        truth = sim.truth[b, k, :2]
        if k >= 5:
            err_f.append(np.hypot(float(row["x"]) - truth[0], float(row["y"]) - truth[1]))
            err_s.append(np.hypot(float(row["smooth_x"]) - truth[0], float(row["smooth_y"]) - truth[1]))
        assert float(row["smooth_std_x"]) > 0
    rmse_f, rmse_s = np.sqrt(np.mean(np.square(err_f))), np.sqrt(np.mean(np.square(err_s)))
    assert rmse_s < 0.8 * rmse_f, (rmse_s, rmse_f)


def test_track_tune_with_too_few_points_is_one_line_and_no_output(tmp_path):
    (tmp_path / "few.csv").write_text("t,x,y\n0,0,0\n0.1,0.3,0\n0.2,0.6,0.1\n1.5,4.4,0.2\n1.6,4.8,0.2\n")
    r = run("track", "few.csv", "--model", "cv", "--tune", "--quiet", "-o", "out.csv", cwd=tmp_path)
    assert r.returncode == 2
    assert r.stderr.strip().count("\n") == 0, r.stderr
    assert r.stderr.startswith("lgekf track: error: too few measurements to learn the noise of cv: 1 filter updates"), r.stderr
    assert not (tmp_path / "out.csv").exists()


@pytest.mark.slow
def test_evaluate_tune_mle_and_smoothed_rows(tmp_path):
    """`evaluate --tune --smooth --imm` (one run for the three, to keep CI short): the learned noise in the tuned
    rows, smoothed rows better than the filters, and the IMM's fit with every candidate mode set in imm_sets.csv."""
    from lgekf.apps.track_imm import TUNE_MODE_SETS

    write_synthetic(tmp_path / "synth.csv", synthetic_tracks(n=8, K=40))
    r = run("evaluate", "synth.csv", "--seeds", "1", "--tune", "--smooth", "--imm", "--out", "ev", "--no-figure", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    rows = list(csv.DictReader(open(tmp_path / "ev" / "summary.csv")))
    tuned = {x["filter"]: x for x in rows if x["noise"] == "tuned"}
    assert set(tuned) == set(FILTERS) | {f"{m}:smoothed" for m in FILTERS} | {"imm"}
    # every candidate mode set of the IMM's fit: AIC = 2 n_params - 2 log L (n_params = a factor per mode + the
    # switching probability), the lowest AIC kept, and it is the fit learned.csv reports for the IMM
    sets = list(csv.DictReader(open(tmp_path / "ev" / "imm_sets.csv")))
    assert [x["modes"] for x in sets] == list(TUNE_MODE_SETS) and all(x["aic"] for x in sets), sets
    for x in sets:
        assert int(x["params"]) == len(x["modes"].split(",")) + 1
        np.testing.assert_allclose(float(x["aic"]), 2 * int(x["params"]) - 2 * float(x["loglik"]), atol=2e-6)
    kept = [x for x in sets if x["kept"] == "True"]
    assert len(kept) == 1 and float(kept[0]["aic"]) == min(float(x["aic"]) for x in sets)
    imm_learned = [x for x in csv.DictReader(open(tmp_path / "ev" / "learned.csv")) if x["filter"] == "imm"]
    assert imm_learned and float(imm_learned[0]["loglik"]) == pytest.approx(float(kept[0]["loglik"]), abs=1e-6)
    learned = list(csv.DictReader(open(tmp_path / "ev" / "learned.csv")))
    for m in FILTERS:
        mine = [x for x in learned if x["filter"] == m]
        # the tuned row runs with the learned process noise; the measurement std is the known one, held fixed
        np.testing.assert_allclose([float(v) for v in tuned[m]["accel_std"].split(";")], [float(x["value"]) for x in mine[:-1]],
                                   rtol=1e-3)
        assert mine[-1]["parameter"] == "meas_r" and float(mine[-1]["value"]) == 0.3
        # smoothing uses the future measurements too: better than the filter on every model here
        assert float(tuned[f"{m}:smoothed"]["pos_rmse"]) < float(tuned[m]["pos_rmse"])
    assert "learned synth: learned noise for cv" in r.stderr
