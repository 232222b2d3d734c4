"""IMM (lgekf.estimators.imm.estimator): mixing on the group against a dense Monte Carlo reference, the common-coordinate
read-out, reduction to the single filter with one mode, mode switching, bad options."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest
import scipy.linalg as sla

from lgekf import filter_batch
from lgekf.core.common import covariance_from_common, state_from_common
from lgekf.core.covariance import pack
from lgekf.core.registry import MODELS, get_model
from lgekf.estimators.imm.estimator import IMM, imm_batch, parse_modes, transition_matrix
from lgekf.generated.dispatch import MODEL_NAMES

LG_MODELS = [m for m in MODELS if get_model(m).periodic_tangent]


def _generators(spec, s):
    """The Lie algebra basis E_k of the model's group (dense, n matrices), from the group mean of retract(s, t e_k)."""
    k = spec.kernels
    M0 = np.asarray(k.group_mean(s))
    out = []
    for i in range(spec.n):
        e = np.zeros(spec.n)
        h = 1e-6
        sp_, sm = s.copy(), s.copy()
        e[i] = h
        k.retract(sp_, e)
        e[i] = -h
        k.retract(sm, e)
        out.append(np.linalg.solve(M0, (np.asarray(k.group_mean(sp_)) - np.asarray(k.group_mean(sm))) / (2 * h)))
    return np.array(out)


def _vee(L, E):
    A = E.reshape(len(E), -1).T
    return np.linalg.lstsq(A, L.ravel(), rcond=None)[0]


def _dense_mixture(mus, Ps, w, E, rng, N=120, iters=3):
    """Reference: 2N samples of each N_G(μ_i, P_i) through dense expm (antithetic, whitened so that the tangent
    samples have exactly mean 0 and covariance P_i: what remains is the group's nonlinearity, not Monte Carlo
    noise), the weighted Karcher mean through dense logm (iterated), and the weighted covariance of
    vee(logm(M̄⁻¹X)) about it."""
    X, wt = [], []
    for mu, P, wi in zip(mus, Ps, w):
        u = rng.standard_normal((N, len(P)))
        u = np.vstack([u, -u])
        u = u @ np.linalg.inv(np.linalg.cholesky(u.T @ u / len(u))).T
        eps = u @ np.linalg.cholesky(P).T
        N2 = len(eps)
        for e in eps:
            X.append(mu @ sla.expm(np.tensordot(e, E, 1)))
            wt.append(wi / N2)
    wt = np.array(wt)
    Mbar = mus[int(np.argmax(w))].copy()
    for _ in range(iters):
        Mi = np.linalg.inv(Mbar)
        logs = np.array([_vee(np.real(sla.logm(Mi @ x)), E) for x in X])
        delta = wt @ logs
        Mbar = Mbar @ sla.expm(np.tensordot(delta, E, 1))
    Mi = np.linalg.inv(Mbar)
    logs = np.array([_vee(np.real(sla.logm(Mi @ x)), E) for x in X])
    mean = wt @ logs
    cov = (logs - mean).T @ ((logs - mean) * wt[:, None])
    return Mbar, cov


@pytest.mark.slow
@pytest.mark.parametrize("model", ["se2se2"])
def test_group_mixing_matches_dense_monte_carlo(model):
    """Two concentrated Gaussians on the group, 0.5 rad apart: our reduction (iterated mean, Φ(dᵢ)⁻¹-transported
    covariances + dᵢdᵢᵀ) against the Monte Carlo mixture through dense expm/logm; the untransported covariance
    (Φ = I) is measurably further off, so the check can tell the Jacobian."""
    from lgekf.estimators.imm.kernels import mix_on_group, workspace

    spec = get_model(model)
    k = spec.kernels
    rng = np.random.default_rng(5)
    x1 = np.array([1.0, 2.0, 0.3, 3.0, 0.2, 0.4])
    x2 = np.array([2.0, 1.2, 1.1, 2.2, -0.5, -0.2])
    s1, s2 = k.state_from_physical(x1), k.state_from_physical(x2)
    A = rng.standard_normal((6, 6)) * 0.03
    P1 = A @ A.T + np.diag([4e-3, 2e-3, 1e-3, 3e-3, 3e-3, 1e-3])
    B = rng.standard_normal((6, 6)) * 0.03
    P2 = B @ B.T + np.diag([2e-3, 4e-3, 2e-3, 2e-3, 1e-3, 2e-3])
    w = np.array([0.6, 0.4])
    S = np.zeros((2, len(s1)))
    S[0], S[1] = s1, s2
    Pp = np.array([pack(P1), pack(P2)])
    s_out = np.zeros(len(s1))
    P_out = np.zeros((6, 6))
    mix_on_group(MODEL_NAMES.index(model), S, Pp, w, s_out, P_out, workspace(2))

    E = _generators(spec, s1)
    mus = [np.asarray(k.group_mean(s1)), np.asarray(k.group_mean(s2))]
    Mref, Cref = _dense_mixture(mus, [P1, P2], w, E, rng)
    # the mean: log(M_ref⁻¹ μ) small compared with the spread of the modes (|d| ~ 0.5)
    d = _vee(np.real(sla.logm(np.linalg.inv(Mref) @ np.asarray(k.group_mean(s_out)))), E)
    assert np.linalg.norm(d) < 5e-3, d
    # the covariance, in the reference's tangent (μ and M_ref agree to 5e-3)
    err = np.linalg.norm(P_out - Cref) / np.linalg.norm(Cref)
    assert err < 0.02, err
    # without the transport (Φ = I) the same comparison is clearly worse
    P_plain = np.zeros((6, 6))
    for si, Pi, wi in zip((s1, s2), (P1, P2), w):
        di = np.asarray(k.between(s_out, si))
        P_plain += wi * (Pi + np.outer(di, di))
    err_plain = np.linalg.norm(P_plain - Cref) / np.linalg.norm(Cref)
    print(f"relative error: transported {err:.2e}, untransported {err_plain:.2e}")
    assert err_plain > 3 * err, (err, err_plain)


def test_right_jacobian_convention_for_transport():
    """exp(d)·exp(ε) = exp(d + Φ(d)⁻¹ε + O(ε²)) with Φ the generated right_jacobian (dense expm/logm)."""
    spec = get_model("se2se2")
    k = spec.kernels
    s = k.state_from_physical(np.array([0.0, 0.0, 0.0, 1.0, 0.0, 0.0]))
    E = _generators(spec, s)
    d = np.array([0.4, -0.3, 0.9, 0.2, 0.5, -0.7])
    eps = 1e-5 * np.array([1.0, -2.0, 0.5, 1.5, -1.0, 2.0])
    lhs = _vee(np.real(sla.logm(sla.expm(np.tensordot(d, E, 1)) @ sla.expm(np.tensordot(eps, E, 1)))), E)
    rhs = d + np.asarray(k.right_jacobian_inv(d)) @ eps
    assert np.linalg.norm(lhs - rhs) < 1e-9
    wrong = d + np.asarray(k.right_jacobian(d)) @ eps
    assert np.linalg.norm(lhs - wrong) > 1e-7


@pytest.mark.parametrize("model", list(MODELS))
def test_common_readout_inverts_from_common(model):
    """physical_to_common(common_to_state(c)) = c on the coordinates the model carries (CTRV/SE(2)×R²: c with
    v_y = 0; CV: θ the direction of motion), and ∂c/∂ε against central differences through retract."""
    spec = get_model(model)
    k = spec.kernels
    c = np.array([1.0, -2.0, 0.7, 2.5, 0.0, 0.3])
    x = k.common_to_state(c)
    back = np.asarray(k.physical_to_common(x))
    miss = np.asarray(k.common_missing()) > 0.5
    np.testing.assert_allclose(back[~miss], c[~miss], atol=1e-12)
    s = k.state_from_physical(x)
    A = np.asarray(k.physical_to_common_jacobian(x))
    h = 1e-6
    num = np.zeros_like(A)
    for i in range(spec.n):
        e = np.zeros(spec.n)
        e[i] = h
        sp_, sm = s.copy(), s.copy()
        k.retract(sp_, e)
        k.retract(sm, -e)
        num[:, i] = (np.asarray(k.physical_to_common(k.state_to_physical(sp_)))
                     - np.asarray(k.physical_to_common(k.state_to_physical(sm)))) / (2 * h)
    np.testing.assert_allclose(A, num, atol=1e-7)


def _straight_data(B=4, K=60, seed=0):
    rng = np.random.default_rng(seed)
    t = 0.1 * np.arange(1, K + 1)
    z = np.stack([3 * t, 0.2 * t**2], axis=-1)[None] + 0.3 * rng.standard_normal((B, K, 2))
    c0 = np.tile([0.0, 0.0, 0.0, 3.0, 0.0, 0.0], (B, 1)) + 0.05 * rng.standard_normal((B, 6))
    return z, c0


@pytest.mark.parametrize("model", list(MODELS))
def test_one_mode_is_the_single_filter(model):
    """With one mode the IMM is exactly the model's filter (combined estimate in common coordinates)."""
    spec = get_model(model)
    z, c0 = _straight_data()
    P0c = np.diag([0.25, 0.25, 0.01, 0.25, 0.25, 0.01])
    q = [0.3] * len(spec.noise_names)
    est, mu = imm_batch(z, [(model, q)], dt=0.1, meas_std=0.3, x0=c0, P0=P0c)
    x0 = state_from_common(model, c0)
    P0 = covariance_from_common(model, c0, P0c) + 1e-12 * np.eye(spec.n)
    ref = filter_batch(model, z, dt=0.1, accel_std=q, meas_std=0.3, x0=x0, P0=P0)
    ref_c = np.array([[spec.kernels.physical_to_common(x) for x in row] for row in ref])
    miss = np.asarray(spec.kernels.common_missing()) > 0.5
    np.testing.assert_allclose(est[..., ~miss], ref_c[..., ~miss], rtol=0, atol=1e-12)
    assert np.all(mu == 1.0)
    # the class API gives the same numbers
    f = IMM([(model, q)], dt=0.1, meas_std=0.3, x0=c0[0], P0=P0c)
    for kk in range(5):
        f.predict()
        f.update(z[0, kk])
    np.testing.assert_allclose(f.x[~miss], est[0, 4, ~miss], rtol=0, atol=1e-12)


def _calm_then_turning(K1=60, K2=60, dt=0.1, r=0.15, seed=1):
    """Straight at 4 m/s for K1 steps, then a hard sinusoidal turn (ω up to 2 rad/s) for K2 steps."""
    rng = np.random.default_rng(seed)
    x, y, th, v = 0.0, 0.0, 0.0, 4.0
    pos = []
    for kk in range(K1 + K2):
        w = 0.0 if kk < K1 else 2.0 * np.sin(0.15 * (kk - K1) + 0.5)
        th += w * dt
        x += v * dt * np.cos(th)
        y += v * dt * np.sin(th)
        pos.append((x, y))
    pos = np.array(pos)
    return pos + r * rng.standard_normal(pos.shape), pos


def test_mode_probabilities_switch_from_calm_to_manoeuvre():
    z, _ = _calm_then_turning()
    c0 = [0.0, 0.0, 0.0, 4.0, 0.0, 0.0]
    P0 = np.diag([0.05, 0.05, 0.01, 0.1, 0.1, 0.01])
    _, mu = imm_batch(z[None], "se2r3:calm,se2r3:manoeuvre", 0.05, dt=0.1, meas_std=0.15, x0=c0, P0=P0)
    man = mu[0, :, 1]
    calm, turning = man[20:60], man[62:]
    assert calm.mean() < 0.3 and calm.max() < 0.4, calm
    assert turning.mean() > 0.6 and turning.max() > 0.85 and turning.mean() > 2.5 * calm.mean(), turning
    assert np.argmax(man > 0.5) in range(60, 68)  # the switch follows the onset of the turn within 0.8 s


def test_heterogeneous_imm_is_as_good_as_its_best_mode():
    """CV, CTRV and SE(2)×R³ (default noise) mixed in the common coordinates: within 5 % of the best of the three
    run alone, and CV's probability is higher on the straight part than in the turn."""
    z, pos = _calm_then_turning(seed=2)
    c0 = [0.0, 0.0, 0.0, 4.0, 0.0, 0.0]
    P0 = np.diag([0.05, 0.05, 0.01, 0.1, 0.1, 0.01])

    def rmse(e):
        return np.sqrt(np.mean(np.sum((e[0, :, :2] - pos) ** 2, -1)))

    est, mu = imm_batch(z[None], "cv,ctrv,se2r3", 0.05, dt=0.1, meas_std=0.15, x0=c0, P0=P0)
    assert np.all(np.isfinite(est)) and np.allclose(mu.sum(-1), 1.0)
    alone = [rmse(imm_batch(z[None], m, dt=0.1, meas_std=0.15, x0=c0, P0=P0)[0]) for m in ("cv", "ctrv", "se2r3")]
    assert rmse(est) < 1.05 * min(alone), (rmse(est), alone)
    assert mu[0, 20:60, 0].mean() > mu[0, 62:100, 0].mean() + 0.2


@pytest.mark.parametrize("text, msg", [
    ("foo,se2r3", "unknown model 'foo'"),
    ("se2r3:fast", "level must be one of"),
    ("se2r3:1/2", "expected 3 non-negative numbers"),
    ("se2r3,,cv", "expected MODEL[:LEVEL]"),
])
def test_bad_modes_are_one_line_errors(text, msg):
    with pytest.raises(ValueError, match=msg.replace("[", r"\[")):
        parse_modes(text)


def test_bad_transition_and_measurement():
    with pytest.raises(ValueError, match="imm-switch"):
        transition_matrix(2, 1.0)
    with pytest.raises(ValueError, match="transition"):
        IMM("cv,se2r3", [[0.5, 0.4], [0.1, 0.9]], dt=0.1, meas_std=0.3, x0=np.zeros(6), P0=np.eye(6))
    with pytest.raises(ValueError, match="heading"):
        IMM("cv,se2r3", dt=0.1, meas_std=(0.3, 0.3, 0.1), x0=np.zeros(6), P0=np.eye(6), measurement="pose")


@pytest.mark.parametrize("args, msg", [
    (["--filters", "cv,imm", "--imm-modes", "cv,bogus"], "unknown model 'bogus'"),
    (["--filters", "cv,imm", "--imm-switch", "1.5"], "imm-switch"),
])
def test_study_cli_bad_imm_options(tmp_path, args, msg):
    r = subprocess.run([sys.executable, "-m", "lgekf", "study", "--trajectories", "2", "--sigmas", "0", "--steps", "3",
                        "--out", str(tmp_path / "o"), *args], capture_output=True, text=True)
    assert r.returncode == 2
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and msg in lines[0], r.stderr
    assert not (tmp_path / "o").exists()


def test_missed_detections_pose_and_a_stationary_cv_mode():
    """NaN rows predict only (probabilities follow the transition matrix), pose measurements work, and a CV mode
    at exactly zero velocity (heading undefined) keeps the heterogeneous mixing finite."""
    z, pos = _calm_then_turning(K1=30, K2=10)
    z[10:13] = np.nan
    c0 = [0.0, 0.0, 0.0, 4.0, 0.0, 0.0]
    P0 = np.diag([0.05, 0.05, 0.01, 0.1, 0.1, 0.01])
    est, mu = imm_batch(z[None], "cv,se2r3", 0.1, dt=0.1, meas_std=0.15, x0=c0, P0=P0)
    assert np.all(np.isfinite(est))
    PI = transition_matrix(2, 0.1)
    np.testing.assert_allclose(mu[0, 10], mu[0, 9] @ PI, atol=1e-12)
    heading = np.arctan2(np.gradient(pos[:, 1]), np.gradient(pos[:, 0]))
    zp = np.column_stack([z, heading])[None]
    est, mu = imm_batch(zp, "se2r3:calm,se2r3:manoeuvre", dt=0.1, meas_std=(0.15, 0.15, 0.05), x0=c0, P0=P0,
                        measurement="pose")
    assert np.all(np.isfinite(est))
    still = np.zeros((1, 20, 2)) + 0.01 * np.random.default_rng(0).standard_normal((1, 20, 2))
    est, mu = imm_batch(still, "cv,ctrv,se2r3", dt=0.1, meas_std=0.01, x0=np.zeros(6), P0=np.diag([1e-4, 1e-4, 0.01, 1e-2, 1e-2, 0.01]))
    assert np.all(np.isfinite(est)) and np.all(np.isfinite(mu))
