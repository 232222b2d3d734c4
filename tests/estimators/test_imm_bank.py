"""The IMM bank of the multi-target tracker (``lgekf.estimators.multitarget.imm_bank``, ``model="imm"``, ``lgekf track
--multi --model imm``): against the single-target IMM, the IMM-PDA mode probabilities, a manoeuvring target in
clutter, bad input, the CLI."""

from __future__ import annotations

import math

import numpy as np
import pytest

from lgekf.estimators.imm.estimator import IMM
from lgekf.estimators.multitarget.imm_bank import IMMBank
from lgekf.estimators.multitarget.tracker import MultiTargetTracker
from lgekf.experiments.multi_scenarios import base_scenario

MIXED = "cv,se2r3:calm,se2r3:manoeuvre"  # the default modes: mixed in the common coordinates
SAME = "se2r3:calm,se2r3:manoeuvre"  # one model: mixed on the group
C0 = np.array([0.0, 0.0, 0.2, 5.0, 0.0, 0.1])
VAR0 = np.array([0.09, 0.09, 0.05, 1.0, 0.3, 0.25])


def turning_track(K=60, dt=0.1, v=5.0, seed=1, r=0.3):
    """Positions (K, 2) of an object turning at 0.3 rad/s, with noise r, and their times dt, 2 dt, ..."""
    t = dt * np.arange(1, K + 1)
    z = np.c_[v * t * np.cos(0.3 * t), v * t * np.sin(0.3 * t)]
    return t, z + r * np.random.default_rng(seed).standard_normal((K, 2))


@pytest.mark.parametrize("modes", [MIXED, SAME])
def test_bank_with_one_sure_detection_is_the_single_target_imm(modes):
    """β0 = 0, β = 1 for the one detection: the bank's cycle (mixing, the modes' bank predictions, gate, IMM-PDA update,
    combined estimate) is the IMM's (lgekf.estimators.imm.IMM). Differences are rounding only: the PDA update's
    covariance is (I − Kℋ)P, the IMM's the Joseph form (measured 1.6e-12 on the mixed modes)."""
    t, z = turning_track()
    bank = IMMBank(modes, "position", 0.3)
    bank.add(np.zeros((3, 6)), np.tile(np.diag(VAR0), (3, 1, 1)))  # rows 0-2 in use: the track is not row 0
    row = bank.add(C0[None], np.diag(VAR0)[None])
    bank.remove(np.array([1]))
    imm = IMM(modes, dt=0.1, meas_std=0.3, x0=C0, P0=np.diag(VAR0))
    N = bank.capacity
    beta = np.zeros((N, 1))
    beta[row] = 1.0
    beta0 = 1.0 - beta[:, 0]
    for k in range(t.size):
        imm.predict(0.1)
        imm.update(z[k])
        bank.predict(0.1)
        ll, gated = bank.gate(z[k:k + 1], 1e9)
        assert gated[row, 0] and ll[row, 0] == pytest.approx(imm.log_likelihood, rel=1e-9)
        bank.update(beta0, beta)
        np.testing.assert_allclose(bank.physical(row)[0], imm.x, rtol=1e-9, atol=1e-10)
        np.testing.assert_allclose(bank.covariances(row)[0], imm.P, rtol=1e-9, atol=1e-10)
        np.testing.assert_allclose(bank.mode_probabilities(row)[0], imm.mu, atol=1e-10)
    np.testing.assert_allclose(bank.stds(row)[0], np.sqrt(np.diag(imm.P)), rtol=1e-9)
    assert np.isnan(bank.stds()[1]).all() and np.isfinite(bank.stds()[row]).all()  # a free row: NaN


def _detections_scene(bank, rng):
    """One track (row), predicted; three detections around it, the gate and the mode likelihoods N_kj."""
    row = bank.add(C0[None], np.diag(VAR0)[None])
    bank.predict(0.1)
    bank.predict(0.1)
    x = bank.physical(row)[0]
    Z = x[:2] + np.array([[0.1, -0.2], [1.5, 0.8], [-2.0, 3.0]]) + 0.01 * rng.standard_normal((3, 2))
    ll, gated = bank.gate(Z, 1e4)
    Nk = np.stack([np.exp(-0.5 * b.d2[row[0]] - 0.5 * b.logdet[row[0]] - math.log(2 * math.pi)) for b in bank.banks])
    return row, Z, ll, gated, Nk


@pytest.mark.parametrize("modes", [MIXED, SAME])
def test_imm_pda_mode_probabilities_are_the_closed_form(modes):
    """With PDA weights, μ_k ∝ c̄_k [(1 − P_D P_G) + (P_D/λ) Σ_j N_kj] (Bar-Shalom, Li & Kirubarajan, IMM-PDAF); the
    gate's likelihood is log Σ_k c̄_k N_kj; the mode-conditioned weights of each mode sum to 1."""
    pd, pg, lam = 0.9, 0.99, 0.02
    bank = IMMBank(modes, "position", 0.3)
    row, Z, ll, gated, Nk = _detections_scene(bank, np.random.default_rng(0))
    cbar = bank.mu[row[0]].copy()
    assert gated[row[0]].all()
    np.testing.assert_allclose(np.exp(ll[row[0]]), cbar @ Nk, rtol=1e-12)
    Nbar = cbar @ Nk
    w = np.r_[1 - pd * pg, pd / lam * Nbar]
    b = w / w.sum()  # PDA: β0, β_j
    beta0 = np.ones(bank.capacity)
    beta = np.zeros((bank.capacity, 3))
    beta0[row], beta[row] = b[0], b[1:]
    bank.update(beta0, beta)
    want = cbar * ((1 - pd * pg) + pd / lam * Nk.sum(axis=1))
    np.testing.assert_allclose(bank.mu[row[0]], want / want.sum(), rtol=1e-12)
    D = b[0] + (b[1:] * Nk / Nbar).sum(axis=1)  # μ_k / c̄_k
    np.testing.assert_allclose(b[0] / D + (b[1:] * Nk / Nbar).sum(axis=1) / D, 1.0, rtol=1e-12)


def test_shared_weights_give_the_same_mode_probabilities_but_other_states():
    """``mode_weights="shared"``: every mode's correction with the mixed β; the mode probabilities are the same formula,
    the modes' states differ from the mode-conditioned ones (the wide mode weighs the far detections more)."""
    out = {}
    for how in ("conditioned", "shared"):
        bank = IMMBank(MIXED, "position", 0.3, mode_weights=how)
        row, Z, ll, gated, Nk = _detections_scene(bank, np.random.default_rng(0))
        beta0 = np.ones(bank.capacity)
        beta = np.zeros((bank.capacity, 3))
        beta0[row], beta[row] = 0.1, [0.6, 0.2, 0.1]
        bank.update(beta0, beta)
        out[how] = bank.mu[row[0]].copy(), bank.physical(row)[0]
    np.testing.assert_allclose(out["conditioned"][0], out["shared"][0], rtol=1e-12)
    assert np.abs(out["conditioned"][1] - out["shared"][1]).max() > 1e-3


def test_gate_passes_when_any_mode_passes():
    """A detection outside the calm mode's gate but inside the manoeuvring mode's is gated; d2 is the smaller d²."""
    bank = IMMBank(SAME, "position", 0.1, transition=0.01)
    row = bank.add(C0[None], np.diag(np.full(6, 0.01))[None])
    for _ in range(5):
        bank.predict(0.1)
    x = bank.physical(row)[0]
    Z = x[:2] + np.array([[0.0, 0.0], [0.5, 0.0], [500.0, 0.0]])  # d² 10.4 (calm) and 6.2 (manoeuvre) for the second
    ll, gated = bank.gate(Z, 9.21)
    d2 = np.stack([b.d2[row[0]] for b in bank.banks])
    assert d2[0, 1] > 9.21 >= d2[1, 1]  # calm: out, manoeuvre: in
    assert gated[row[0]].tolist() == [True, True, False] and np.isneginf(ll[row[0], 2])
    np.testing.assert_allclose(bank.d2[row[0]], d2.min(axis=0))


def test_tracker_on_one_clutter_free_target_is_lgekf_track_imm():
    """P_D = 1, (almost) no clutter, one object: the tracker's IMM (one-point start, started again by the two-point rule
    at the second detection, as ``lgekf track`` starts) gives the states, stds and mode probabilities of ``lgekf track
    --model imm`` from the third scan on, to the output's 10 significant digits (β0 ≈ 1e-12 λ-weighted: negligible)."""
    import lgekf

    K, dt = 60, 0.1
    t = dt * np.arange(K)
    th = np.where(t < 3, 0.3, 0.3 + 0.5 * (t - 3))
    x = np.cumsum(np.r_[0, 6 * dt * np.cos(th[:-1])])
    y = np.cumsum(np.r_[0, 6 * dt * np.sin(th[:-1])])
    z = np.c_[x, y] + 0.3 * np.random.default_rng(3).standard_normal((K, 2))
    modes = "cv:0.5,se2r3:0.1/0.1/0.2,se2r3:2/2/2"
    ref = lgekf.track({"id": np.zeros(K, int), "t": t, "x": z[:, 0], "y": z[:, 1]}, model="imm", meas_std=0.3,
                      imm_modes=modes, no_monitor=True)
    trk = MultiTargetTracker(model="imm", imm_modes=modes, meas_std=0.3, detection_prob=1.0, clutter_density=1e-12,
                             gate_prob=1 - 1e-12)
    cols = ["x", "y", "theta", "vx", "vy", "omega"]
    mus = [c for c in ref.columns if c.startswith("mu_")]
    n = 0
    for k in range(K):
        rep = trk.step(t[k], z[k:k + 1])
        if k < 2:
            continue
        assert rep.ids.tolist() == [0]
        np.testing.assert_allclose(rep.states[0], ref[cols].to_numpy()[k], rtol=1e-8, atol=1e-8)
        np.testing.assert_allclose(rep.stds[0], ref[[f"std_{c}" for c in cols]].to_numpy()[k], rtol=1e-8, atol=1e-9)
        np.testing.assert_allclose(rep.mu[0], ref[mus].to_numpy()[k], atol=1e-9)
        n += 1
    assert n == K - 2


def test_manoeuvring_target_in_clutter_is_held_by_one_track():
    """A target at 8 m/s turning at 1.5 rad/s from 4 to 7 s, P_D = 0.9, 4 false alarms per scan over 200 m × 200 m
    (λ = 1e-4): one track of the IMM bank holds it from 1 s on (position error median below 0.5 m) and the
    manoeuvring mode is the most probable in the turn."""
    rng = np.random.default_rng(7)
    t = np.round(0.1 * np.arange(121), 10)
    om = np.where((t >= 4) & (t < 7), 1.5, 0.0)
    th = np.r_[0.0, np.cumsum(om[:-1] * 0.1)]
    pos = np.cumsum(np.c_[8 * np.cos(th), 8 * np.sin(th)] * 0.1, axis=0) - [40.0, 20.0]
    trk = MultiTargetTracker(model="imm", clutter_density=1e-4, detection_prob=0.9, meas_std=0.3)
    err, ids, mu_turn = [], set(), []
    for k, tk in enumerate(t):
        det = pos[k:k + 1] + 0.3 * rng.standard_normal((1, 2)) if rng.random() < 0.9 else np.zeros((0, 2))
        clutter = rng.uniform(-100, 100, (rng.poisson(4), 2))
        rep = trk.step(tk, np.vstack([det, clutter]))
        if tk < 1.0:
            continue
        near = np.hypot(*(rep.states[:, :2] - pos[k]).T)
        assert near.size and near.min() < 2.0, tk
        j = int(np.argmin(near))
        err.append(near[j])
        ids.add(int(rep.ids[j]))
        if 5.0 <= tk < 7.0:
            mu_turn.append(rep.mu[j])
    assert len(ids) == 1, ids
    assert np.median(err) < 0.5, np.median(err)
    assert np.mean(mu_turn, axis=0).argmax() == 2  # cv, se2r3:calm, se2r3:manoeuvre


@pytest.mark.parametrize("kwargs, msg", [
    (dict(imm_modes="foo,cv"), "imm-modes: unknown model 'foo'"),
    (dict(imm_modes="cv"), "an IMM needs at least two modes, got 1 (cv)"),
    (dict(imm_modes="cv,se2r3:fast"), "level must be one of"),
    (dict(imm_modes="cv,se2r3", measurement="pose", meas_std=(0.3, 0.3, 0.05)), "the cv model has no heading"),
    (dict(accel_std=(1.0,)), "accel-std: not with the IMM"),
    (dict(imm_switch=1.5), "imm-switch: must be in [0, 1)"),
])
def test_bad_imm_input_is_one_clear_error(kwargs, msg):
    with pytest.raises(ValueError) as e:
        MultiTargetTracker(model="imm", **kwargs)
    assert msg in str(e.value)


def test_imm_options_need_the_imm():
    with pytest.raises(ValueError, match="imm-modes/imm-switch: only with the IMM"):
        MultiTargetTracker(model="cv", imm_modes=MIXED)


def test_same_group_modes_on_pose_detections():
    """Modes of one model from pose detections (SE(2)×R³ calm and manoeuvring): the objects are tracked (every target
    within 1 m of a confirmed track at the end)."""
    sc = base_scenario(seed=1, duration=6.0, measurement="pose", meas_std=(0.3, 0.05))
    trk = MultiTargetTracker(model="imm", imm_modes=SAME, measurement="pose", meas_std=(0.3, 0.3, 0.05), clutter_density=1e-4)
    for tk, Z in zip(sc.times, sc.detections):
        rep = trk.step(tk, Z)
    truth = sc.truth[-1][1][:, :2]
    d = np.hypot(rep.states[:, None, 0] - truth[None, :, 0], rep.states[:, None, 1] - truth[None, :, 1]).min(axis=0)
    assert np.all(d < 1.0), d
    assert rep.mu.shape == (rep.ids.size, 2) and np.allclose(rep.mu.sum(axis=1), 1.0)


def _detections_csv(path, seed=0, duration=6.0):
    sc = base_scenario(seed=seed, duration=duration)
    with open(path, "w") as f:
        f.write("t,x,y\n")
        for tk, Z in zip(sc.times, sc.detections):
            for z in Z:
                f.write(f"{tk:.3f},{z[0]:.4f},{z[1]:.4f}\n")
    return sc


def test_cli_multi_model_imm(tmp_path):
    """``lgekf track FILE --multi --model imm``: noise from the data, the columns of a single-model --multi run of the
    output model (se2r3: x, y, theta, vx, vy, omega) with the mode probabilities mu_<mode> after course, finite rows,
    every target of the last scan tracked."""
    import pandas as pd

    from lgekf.apps.track_multi import multi_output_columns
    from lgekf.cli import main

    sc = _detections_csv(tmp_path / "d.csv")
    out = tmp_path / "o.csv"
    assert main(["track", str(tmp_path / "d.csv"), "--multi", "--model", "imm", "-o", str(out), "--quiet"]) == 0
    df = pd.read_csv(out)
    mu = ["mu_cv", "mu_se2r3_calm", "mu_se2r3_manoeuvre"]
    single = multi_output_columns("se2r3")
    assert list(df.columns) == single[:single.index("existence")] + mu + single[single.index("existence"):]
    assert np.isfinite(df.to_numpy(float)).all()
    np.testing.assert_allclose(df[mu].sum(axis=1), 1.0, rtol=1e-8)
    last = df[df.t == df.t.max()]
    truth = sc.truth[-1][1][:, :2]
    d = np.hypot(last.x.to_numpy()[:, None] - truth[None, :, 0], last.y.to_numpy()[:, None] - truth[None, :, 1]).min(axis=0)
    assert np.all(d < 1.5), d


@pytest.mark.parametrize("extra, msg", [
    (["--imm-modes", "cv"], "an IMM needs at least two modes"),
    (["--imm-modes", "foo,cv"], "imm-modes: unknown model 'foo'"),
    (["--accel-std", "1"], "--accel-std is not supported"),
    (["--imm-switch", "2"], "imm-switch: must be in [0, 1)"),
])
def test_cli_multi_imm_bad_input(tmp_path, capsys, extra, msg):
    from lgekf.cli import main

    src = tmp_path / "in.csv"
    src.write_text("t,x,y\n0,0,0\n0.1,1,0\n")
    out = tmp_path / "out.csv"
    code = main(["track", str(src), "--multi", "--model", "imm", "-o", str(out), *extra])
    err = capsys.readouterr().err
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert code == 2 and len(lines) == 1 and msg in lines[0], err
    assert not out.exists()


def test_cli_imm_modes_without_the_imm(tmp_path, capsys):
    from lgekf.cli import main

    src = tmp_path / "in.csv"
    src.write_text("t,x,y\n0,0,0\n0.1,1,0\n")
    code = main(["track", str(src), "--multi", "--model", "cv", "--imm-modes", MIXED, "-o", str(tmp_path / "o.csv")])
    assert code == 2 and "only with --model imm" in capsys.readouterr().err


def test_cli_multi_imm_modes_in_numbers_with_meas_std_estimate_nothing(tmp_path, capsys):
    """Every mode's noise given as numbers and --meas-std: nothing comes from the data, no noise line; the modes line
    says what runs."""
    from lgekf.cli import main

    _detections_csv(tmp_path / "d.csv", duration=3.0)
    code = main(["track", str(tmp_path / "d.csv"), "--multi", "--model", "imm", "--imm-modes", "cv:0.5,se2r3:0.1/0.1/0.2",
                 "--meas-std", "0.3", "--clutter-density", "1e-4", "-o", str(tmp_path / "o.csv")])
    err = capsys.readouterr().err
    assert code == 0 and "noise from the data" not in err, err
    assert "imm: modes cv:0.5 (0.5), se2r3:0.1/0.1/0.2 (0.1,0.1,0.2); switch 0.05 per scan" in err, err


def test_multi_study_has_the_imm():
    """``lgekf study --multi --models ...,imm``: the IMM's cell beside the models' on the same detections."""
    from lgekf.experiments.multi_study import MultiStudyConfig, run_multi_study

    cells = run_multi_study(MultiStudyConfig(models=("cv", "imm"), associations=("jpda",), runs=1, duration=2.0))
    assert [c.model for c in cells] == ["cv", "imm"] and all(np.isfinite(c.gospa) for c in cells)
    with pytest.raises(ValueError, match="only with the model imm"):
        MultiStudyConfig(models=("cv",), imm_modes=MIXED).validate()
