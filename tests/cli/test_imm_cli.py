"""`lgekf track --model imm`, `lgekf evaluate --imm` and `lgekf study --filters ...,imm` from the command line."""

from __future__ import annotations

import csv
import re

import numpy as np
import pytest

from lgekf.cli import main


def _tracks_csv(path, n_obj=3, K=60, seed=0):
    rng = np.random.default_rng(seed)
    rows = ["t,x,y,id"]
    for obj in range(n_obj):
        th = x = y = 0.0
        for k in range(K):
            th += (0.0 if k < K // 2 else 0.6) * 0.1
            x += 4 * 0.1 * np.cos(th)
            y += 4 * 0.1 * np.sin(th)
            rows.append(f"{k * 0.1:.1f},{x + 0.2 * rng.standard_normal():.4f},{y + 0.2 * rng.standard_normal():.4f},o{obj}")
    path.write_text("\n".join(rows) + "\n")
    return path


def test_track_imm_writes_mode_probabilities(tmp_path, capsys):
    src = _tracks_csv(tmp_path / "in.csv")
    out = tmp_path / "out.csv"
    assert main(["track", str(src), "--model", "imm", "--imm-modes", "cv,se2r3:calm,se2r3:manoeuvre", "--imm-switch", "0.02",
                 "-o", str(out)]) == 0
    err = capsys.readouterr().err
    # the modes' noise: the data's estimate of each model (printed first) times the level (calm 0.2, manoeuvre 4)
    cv = float(re.search(r"accel-std cv ([0-9.e+-]+) ", err).group(1))
    se = [float(v) for v in re.search(r"; se2r3 ([0-9.e+-]+,[0-9.e+-]+,[0-9.e+-]+) ", err).group(1).split(",")]
    modes = re.search(r"imm: modes cv \(([^)]*)\), se2r3:calm \(([^)]*)\), se2r3:manoeuvre \(([^)]*)\); switch 0.02", err)
    assert modes, err
    np.testing.assert_allclose(float(modes.group(1)), cv, rtol=2e-3)
    np.testing.assert_allclose([float(v) for v in modes.group(2).split(",")], [0.2 * v for v in se], rtol=2e-2)
    np.testing.assert_allclose([float(v) for v in modes.group(3).split(",")], [4 * v for v in se], rtol=2e-2)
    rows = list(csv.DictReader(out.open()))
    assert len(rows) == 180
    assert list(rows[0])[-4:] == ["mu_cv", "mu_se2r3_calm", "mu_se2r3_manoeuvre", "flag"]
    mu = np.array([[float(r[c]) for c in ("mu_cv", "mu_se2r3_calm", "mu_se2r3_manoeuvre")] for r in rows])
    np.testing.assert_allclose(mu.sum(axis=1), 1.0, atol=1e-9)
    assert np.all(np.isfinite([float(r["x"]) for r in rows]))


@pytest.mark.parametrize("args, msg", [
    (["--model", "imm", "--imm-switch", "2"], "imm-switch: must be in [0, 1)"),
    (["--model", "imm", "--imm-modes", "se2r3:1/2"], "expected 3 non-negative numbers"),
    (["--model", "cv", "--imm-modes", "cv"], "only with --model imm"),
    (["--model", "imm", "--accel-std", "1,1,1"], "--accel-std"),
    (["--model", "imm", "--tune", "--imm-modes", "cv:0.5,se2r3:1/1/2"], "--tune: every mode's noise is given as numbers"),
    (["--model", "imm", "--smooth", "--full-cov"], "--model imm: --full-cov is not supported"),
])
def test_track_imm_bad_options(tmp_path, capsys, args, msg):
    src = _tracks_csv(tmp_path / "in.csv", n_obj=1, K=10)
    out = tmp_path / "out.csv"
    assert main(["track", str(src), *args, "-o", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and msg in err[0], err
    assert not out.exists()


def test_evaluate_imm_row(tmp_path, capsys):
    src = _tracks_csv(tmp_path / "truth.csv", n_obj=5, K=40)
    out = tmp_path / "ev"
    assert main(["evaluate", str(src), "--imm", "--seeds", "2", "--no-figure", "--out", str(out), "--quiet"]) == 0
    rows = {r["filter"]: r for r in csv.DictReader((out / "summary.csv").open())}
    assert "imm" in rows and "cv" in rows
    assert 0 < float(rows["imm"]["pos_rmse"]) < float(rows["measurements"]["pos_rmse"])


def test_study_with_imm(tmp_path, capsys):
    out = tmp_path / "st"
    assert main(["study", "--trajectories", "4", "--steps", "20", "--sigmas", "0,1", "--filters", "cv,se2r3,imm",
                 "--imm-modes", "cv,se2r3", "--no-figure", "--out", str(out), "--quiet"]) == 0
    rows = [r for r in csv.DictReader((out / "summary.csv").open()) if r["filter"] == "imm"]
    assert len(rows) == 2 and all(float(r["mean_rmse"]) > 0 for r in rows)


def test_docs_imm_example_runs():
    from pathlib import Path
    import re

    chapter = (Path(__file__).resolve().parents[2] / "docs" / "imm.md").read_text(encoding="utf-8")
    block = re.search(r"# Interacting multiple models \(IMM\)\n.*?```python\n(.*?)```", chapter, re.S).group(1)
    ns: dict = {}
    exec(compile(block, "docs/imm.md", "exec"), ns)  # noqa: S102 - our own documentation
    imm = ns["imm"]
    assert imm.x.shape == (6,) and imm.P.shape == (6, 6) and abs(imm.mu.sum() - 1) < 1e-12


def _turning_tracks(n_obj=4, K=60, seed=0):
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n_obj):
        th = np.cumsum(np.where((np.arange(K) > K // 3) & (np.arange(K) < 2 * K // 3), 0.08, 0.0))
        xy = np.cumsum(0.5 * np.stack([np.cos(th), np.sin(th)], axis=1), axis=0)
        out.append((0.1 * np.arange(K), xy + 0.2 * rng.standard_normal((K, 2))))
    return out


def test_fit_imm_keeps_the_lowest_aic_and_given_modes():
    """`--tune` of the IMM (lgekf.apps.track_imm.fit_imm): without --imm-modes every set of TUNE_MODE_SETS is
    fitted and the lowest AIC kept, each mode = learned noise × level × fitted factor; given modes and a given
    switching probability are the only candidate and stay fixed, numbers included."""
    from lgekf.apps.track_imm import TUNE_MODE_SETS, ImmTrackOptions, fit_imm

    tracks = _turning_tracks()
    learned = {"cv": (0.7,), "se2r3": (0.5, 0.5, 1.0)}
    opts = ImmTrackOptions()
    fit, table = fit_imm(opts, tracks, 0.2, 0.5, learned)
    assert [text for text, _ in table] == list(TUNE_MODE_SETS)
    kept_text, kept = min(table, key=lambda tf: tf[1].aic)
    assert fit is kept and opts.modes_text == kept_text and opts.switch == fit.switch
    levels = {"calm": 0.2, "manoeuvre": 4.0, "": 1.0}
    for mode, f in zip(opts.modes, fit.factors):
        np.testing.assert_allclose(mode.accel_std, [levels[mode.label] * f * v for v in learned[mode.model]], rtol=1e-12)
    assert all(f.n_params == len(text.split(",")) + 1 for text, f in table)  # factors + switch

    given = ImmTrackOptions("cv,se2r3:0.3/0.3/0.6", 0.02)
    fit2, table2 = fit_imm(given, tracks, 0.2, 0.5, learned)
    assert len(table2) == 1 and given.switch == 0.02 and fit2.n_params == 1
    assert given.modes[1].accel_std == (0.3, 0.3, 0.6) and fit2.factors[1] == 1.0
    np.testing.assert_allclose(given.modes[0].accel_std, [0.7 * fit2.factors[0]], rtol=1e-12)


def test_fit_imm_subsamples_long_files(monkeypatch):
    """Beyond FIT_MAX_STEPS filter steps the IMM's fit uses a seeded random subset of whole tracks (just over the
    limit), and says what it fits."""
    import lgekf.apps.track_imm as ti

    tracks = _turning_tracks(n_obj=8, K=30)
    monkeypatch.setattr(ti, "FIT_MAX_STEPS", 60)  # 28 filter steps per track: 3 tracks reach it
    lines = []
    fit, _ = ti.fit_imm(ti.ImmTrackOptions("cv:calm,cv:manoeuvre"), tracks, 0.2, 0.5, {"cv": (0.7,)}, say=lines.append)
    assert fit.n_tracks == 3
    assert len(lines) == 1 and "mode set 1/1 (cv:calm,cv:manoeuvre)" in lines[0] and "90 measurements of 3 tracks" in lines[0]


def test_evaluate_imm_fit_falls_back_when_it_cannot_fit():
    """`evaluate --imm --tune` on a tuning split too small for the IMM's fit (or with nothing free) keeps the run
    going: the modes take their models' learned noise × level, and the reason takes the fit's place."""
    from types import SimpleNamespace

    from lgekf.apps.evaluate import _imm_fitted
    from lgekf.apps.track_imm import ImmTrackOptions

    (t, z), = _turning_tracks(n_obj=1, K=6)
    tiny = SimpleNamespace(t=t, p=z, starts=np.array([0, 6]), name="tiny")
    opts = ImmTrackOptions("cv,se2r3:calm,se2r3:0.3/0.3/0.6", 0.05)
    tuned, why, sets = _imm_fitted(opts, tiny, 0.2, [0], 0.5, {"cv": SimpleNamespace(accel_std=(0.7,)), "se2r3": "too few points"})
    assert isinstance(why, str) and "too few measurements to fit the IMM" in why and sets == []
    assert [m.accel_std for m in tuned.modes] == [(0.7,), opts.modes[1].accel_std, (0.3, 0.3, 0.6)]
    assert _imm_fitted(None, tiny, 0.2, [0], 0.5, {}) == (None, None, [])
