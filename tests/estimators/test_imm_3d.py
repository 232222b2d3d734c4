"""The IMM of 3-D space (``generated/imm_3d.py`` through ``lgekf.estimators.imm``): against a numpy IMM of CV3 modes
(tests/_imm_numpy.py), one mode ≡ the model's own filter, mode probabilities, ``lgekf track --model imm`` on a 3-D file
and its one-line refusals.

The 3-D loop reaches every model of 3-D space through ``generated/dispatch_3d.py``, so its first call compiles all of
them (docs/space3d.md, "The IMM in 3-D"), about 150 s of CPU on a cold cache: every check that runs the loop is marked
``budget`` (CI's 15 minutes; ``pytest -m budget`` runs them). The default run checks the conversions the loop mixes
through and the one-line refusals; the loop's template is the plane's, which the planar IMM tests run by default."""

from __future__ import annotations

import csv

import numpy as np
import pytest

from lgekf import filter_batch
from lgekf.cli import main
from lgekf.core.common import common_world_velocity, covariance_from_common, state_from_common
from lgekf.core.registry import get_model, models_of
from lgekf.estimators.imm.estimator import IMM, imm_batch, transition_matrix

from _imm_numpy import numpy_cv_imm

DT, R = 0.05, 0.4


def _helix(K=80, seed=3):
    """Positions (K, 3) of a climbing turn (r = 40 m, 10 m/s, climb 1.5 m/s) at 20 Hz with 0.4 m noise, and its
    common coordinates at the first position (yaw along the velocity, pitch its climb angle, body velocity forward)."""
    rng = np.random.default_rng(seed)
    t = DT * np.arange(1, K + 1)
    w = 10.0 / 40.0
    p = np.column_stack([40 * np.sin(w * t), 40 - 40 * np.cos(w * t), 1.5 * t])
    v0 = np.array([10.0, 0.0, 1.5])
    c0 = np.zeros(12)
    c0[4] = -np.arctan2(v0[2], v0[0])
    c0[6] = np.linalg.norm(v0)
    return p + R * rng.standard_normal(p.shape), c0


P0C = np.diag([1.0, 1.0, 1.0, 0.01, 0.01, 0.01, 1.0, 1.0, 1.0, 0.01, 0.01, 0.01])


@pytest.mark.budget
def test_cv3_imm_matches_the_numpy_imm():
    """Two CV3 modes (mixed on the group ℝ⁶): combined position, world velocity, mode probabilities and the
    step likelihoods' sum equal an IMM written out in numpy (tests/_imm_numpy.py), probabilities summing to 1."""
    z, c0 = _helix()
    PI = transition_matrix(2, 0.05)
    est, mu, P = imm_batch(z[None], "cv3:0.3,cv3:4", PI, dt=DT, meas_std=R, x0=c0, P0=P0C, return_cov=True)
    assert est.shape == (1, z.shape[0], 12) and P.shape == (1, z.shape[0], 12, 12)
    x0 = state_from_common("cv3", c0)
    P0 = covariance_from_common("cv3", c0, P0C) + 1e-12 * np.eye(6)  # as every mode starts (estimator._Setup)
    _, ref, ref_mu = numpy_cv_imm(x0, P0, z, np.full(z.shape[0], DT), [0.3, 4.0], PI, R, [0.5, 0.5])
    np.testing.assert_allclose(est[0, :, :3], ref[:, :3], rtol=0, atol=1e-8)
    np.testing.assert_allclose(common_world_velocity(est[0]), ref[:, 3:], rtol=0, atol=1e-8)
    np.testing.assert_allclose(mu[0], ref_mu, rtol=0, atol=1e-9)
    np.testing.assert_allclose(mu.sum(axis=-1), 1.0, rtol=0, atol=1e-12)


@pytest.mark.parametrize("model", list(models_of("3d")))
def test_state_to_common_and_back_is_the_identity(model):
    """x → c → x (``physical_to_common`` then ``common_to_state``) is the identity on a climbing, turning state: the
    IMM across models converts every mode so at each step (CT3's body rate was (0, 0, ω) in a pitched body frame,
    and every round trip shrank its turn rate by cos(pitch))."""
    k = get_model(model).kernels
    c = np.array([1.0, 2.0, 3.0, 0.0, -0.15, 0.7, 10.1, 0.0, 0.0, 0.0, 0.0, 0.25])
    x = np.asarray(k.common_to_state(c))
    back = np.asarray(k.common_to_state(np.asarray(k.physical_to_common(x))))
    np.testing.assert_allclose(back, x, rtol=0, atol=1e-12)


@pytest.mark.budget
@pytest.mark.parametrize("model", list(models_of("3d")))
def test_one_mode_is_the_single_filter_3d(model):
    """With one mode the 3-D IMM is the model's own filter (its common coordinates, those it carries)."""
    spec = get_model(model)
    z, c0 = _helix(K=40)
    q = [0.3] * len(spec.noise_names)
    est, mu = imm_batch(z[None], [(model, q)], dt=DT, meas_std=R, x0=c0, P0=P0C)
    x0 = state_from_common(model, c0)
    P0 = covariance_from_common(model, c0, P0C) + 1e-12 * np.eye(spec.n)
    ref = filter_batch(model, z[None], dt=DT, accel_std=q, meas_std=R, x0=x0[None], P0=P0[None], measurement="position3")
    ref_c = np.array([spec.kernels.physical_to_common(x) for x in ref[0]])
    miss = np.asarray(spec.kernels.common_missing()) > 0.5
    np.testing.assert_allclose(est[0][:, ~miss], ref_c[:, ~miss], rtol=0, atol=1e-9)
    assert np.all(mu == 1.0)
    f = IMM([(model, q)], dt=DT, meas_std=R, x0=c0, P0=P0C)  # the class API: the same numbers
    for k in range(5):
        f.predict()
        f.update(z[k])
    np.testing.assert_allclose(f.x[~miss], est[0, 4, ~miss], rtol=0, atol=1e-9)


@pytest.mark.budget
def test_imm_across_3d_models_tracks_the_helix():
    """CV3 and CT3 mixed in the 12 common coordinates: finite, probabilities summing to 1, CT3 (the turn's model)
    the more probable after the start, the position error below the measurement noise."""
    z, c0 = _helix(K=200)
    t = DT * np.arange(1, 201)
    truth = np.column_stack([40 * np.sin(0.25 * t), 40 - 40 * np.cos(0.25 * t), 1.5 * t])
    est, mu = imm_batch(z[None], "cv3,ct3", dt=DT, meas_std=R, x0=c0, P0=P0C)
    assert np.all(np.isfinite(est)) and np.all(np.isfinite(mu))
    np.testing.assert_allclose(mu.sum(axis=-1), 1.0, rtol=0, atol=1e-12)
    assert mu[0, 100:, 1].mean() > 0.5
    rmse = np.sqrt(np.mean(np.sum((est[0, 50:, :3] - truth[50:]) ** 2, axis=1)))
    raw = np.sqrt(np.mean(np.sum((z[50:] - truth[50:]) ** 2, axis=1)))
    assert rmse < 0.7 * raw, (rmse, raw)


def _helix_csv(path, n_obj=2, K=120):
    rows = ["id,t,x,y,z"]
    for b in range(n_obj):
        z, _ = _helix(K=K, seed=10 + b)
        rows += [f"h{b},{1.7e9 + DT * k:.3f},{z[k, 0]:.4f},{z[k, 1]:.4f},{z[k, 2]:.4f}" for k in range(K)]
    path.write_text("\n".join(rows) + "\n")
    return path


@pytest.mark.budget
def test_track_imm_on_a_3d_file(tmp_path, capsys):
    """No option but --model imm on x, y, z input: the space's default modes, noise from the data, 12 common
    coordinates, their stds, speed, course, climb, turn_rate, the mode probabilities summing to 1."""
    src = _helix_csv(tmp_path / "in.csv")
    out = tmp_path / "out.csv"
    assert main(["track", str(src), "--model", "imm", "-o", str(out)]) == 0
    err = capsys.readouterr().err
    assert "noise from the data" in err and "imm: modes cv3 (" in err, err
    rows = list(csv.DictReader(out.open()))
    assert len(rows) == 240
    head = list(rows[0])
    assert head[2:14] == ["x", "y", "z", "roll", "pitch", "yaw", "vx", "vy", "vz", "wx", "wy", "wz"]
    mus = ["mu_cv3", "mu_ct3_calm", "mu_ct3_manoeuvre"]
    assert head[-4:] == [*mus, "flag"] and "climb" in head and "turn_rate" in head
    mu = np.array([[float(r[c]) for c in mus] for r in rows])
    np.testing.assert_allclose(mu.sum(axis=1), 1.0, atol=1e-9)
    speed = np.array([float(r["speed"]) for r in rows[10:120]])
    climb = np.array([float(r["climb"]) for r in rows[10:120]])
    assert abs(np.median(speed) - np.hypot(10.0, 1.5)) < 0.5 and abs(np.median(climb) - 1.5) < 0.3


@pytest.mark.parametrize("args, msg", [
    (["--imm-modes", "cv3,se2r3"], "imm-modes: the modes are models of different spaces"),
    (["--imm-modes", "cv,se2r3"], "--imm-modes: cv,se2r3 are models of the plane, and the input has 3-D positions"),
    (["--smooth"], "--smooth (the IMM smoother) runs in the plane only (yet)"),
])
def test_track_imm_3d_bad_input(tmp_path, capsys, args, msg):
    """Planar modes for a 3-D file, or an option the 3-D IMM does not have: one line, exit 2, no output."""
    src = _helix_csv(tmp_path / "in.csv", n_obj=1, K=10)
    out = tmp_path / "out.csv"
    assert main(["track", str(src), "--model", "imm", *args, "-o", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and msg in err[0], err
    assert not out.exists()


@pytest.mark.budget
def test_study_3d_with_the_imm(tmp_path):
    """The study in 3-D takes the IMM among its filters (the space's default modes, the chain learned): finite RMSE
    per σ_ω, below the measurements'."""
    out = tmp_path / "study"
    assert main(["study", "--space", "3d", "--filters", "cv3,ct3,imm", "--trajectories", "3", "--sigmas", "0,0.1",
                 "--steps", "30", "--imm-train", "4", "--out", str(out)]) == 0
    rows = list(csv.DictReader((out / "summary.csv").open()))
    imm = np.array([float(r["mean_rmse"]) for r in rows if r["filter"] == "imm"])
    meas = np.array([float(r["mean_rmse"]) for r in rows if r["filter"] == "measurements"])
    assert imm.shape == (2,) and np.all(np.isfinite(imm)) and np.all(imm < meas)
