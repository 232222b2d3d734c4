"""The pose update (G' = SE(2)) against a dense, independent transcription of the paper's LG-EKF update.

Measurement: Z = h(X)·exp(m^∧), h(X) = T_s the pose, m ~ N(0, diag(r_x², r_y², r_θ²)) in the tangent
(x, y, θ) of SE(2).  The reference (nothing from lgekf): e = [logm(h(μ)⁻¹ Z)]^∨ (scipy), ℋ = [I₃, 0]
(checked against central differences of its definition eq:calH), K = Pℋᵀ(ℋPℋᵀ + R)⁻¹, ν = K e,
μ⁺ = μ·expm(ν^∧), P⁺ = Φ(ν)(I − Kℋ)PΦ(ν)ᵀ (eq:K, eq:up_mu, eq:up_P as printed), Φ the 40-term series
of ad from the matrix bracket.  The library's update uses the Joseph form, equal in exact arithmetic.
Headings of the state include 0, ±1e-9 and ±(π − 1e-9); the measured heading then crosses ±π.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.linalg import logm

from lgekf import SE2R3Filter, SE2SE2Filter
from test_lg_reference import P_DIM, Phi, _rel, gexp, mean_from_physical, random_spd

CLASSES = {"se2se2": SE2SE2Filter, "se2r3": SE2R3Filter}
TOL = 1e-12
HEADINGS = [0.0, 1e-9, -1e-9, math.pi - 1e-9, -(math.pi - 1e-9), 0.7, -2.5]


def se2_hat(v):
    return np.array([[0.0, -v[2], v[0]], [v[2], 0.0, v[1]], [0.0, 0.0, 0.0]])


def se2_log(T):
    L = np.real(logm(T))
    return np.array([L[0, 2], L[1, 2], L[1, 0]])


def pose_of(mu):
    return mu[:3, :3].copy()


def calH_pose_fd(model, mu, h=1e-6):
    hinv = np.linalg.inv(pose_of(mu))
    cols = []
    for e in np.eye(P_DIM):
        fp = se2_log(hinv @ pose_of(mu @ gexp(model, h * e)))
        fm = se2_log(hinv @ pose_of(mu @ gexp(model, -h * e)))
        cols.append((fp - fm) / (2 * h))
    return np.column_stack(cols)


def ref_update_pose(model, mu, P, Z, r):
    H = np.hstack([np.eye(3), np.zeros((3, 3))])
    R = np.diag(np.square(r))
    S = H @ P @ H.T + R
    K = np.linalg.solve(S, H @ P).T
    e = se2_log(np.linalg.inv(pose_of(mu)) @ Z)
    nu = K @ e
    mu_new = mu @ gexp(model, nu)
    Ph = Phi(model, nu)
    P_new = Ph @ (np.eye(P_DIM) - K @ H) @ P @ Ph.T
    return mu_new, 0.5 * (P_new + P_new.T), float(e @ np.linalg.solve(S, e))


def cases(seed):
    rng = np.random.RandomState(seed)
    for i in range(120):
        th = HEADINGS[i % len(HEADINGS)]
        om = rng.uniform(-3, 3)
        x0 = np.array([rng.randn() * 10, rng.randn() * 10, th, rng.randn() * 3, rng.randn(), om])
        P0 = random_spd(rng, "dense")
        r = np.exp(rng.uniform(np.log(0.05), np.log(2.0), size=3))
        r[2] = min(r[2], 0.5)
        off = rng.randn(3) * np.array([1.0, 1.0, 0.3]) * (0.0 if i % 11 == 0 else 1.0)
        yield x0, P0, r, off


@pytest.mark.parametrize("model", ["se2se2", "se2r3"])
def test_pose_calH_is_identity_block(model):
    """ℋ for G' = SE(2), h(X) = T_s: [I₃, 0] (central differences of eq:calH) and the generated calH_pose."""
    from lgekf.core.registry import get_model

    k = get_model(model).kernels
    rng = np.random.RandomState(1)
    for th in HEADINGS:
        x0 = np.array([1.0, -2.0, th, 0.5, 0.1, 0.3])
        mu = mean_from_physical(model, x0)
        np.testing.assert_allclose(calH_pose_fd(model, mu), np.hstack([np.eye(3), np.zeros((3, 3))]), atol=1e-8)
        np.testing.assert_array_equal(k.calH_pose(k.state_from_physical(x0)), np.hstack([np.eye(3), np.zeros((3, 3))]))
    assert rng is not None


@pytest.mark.parametrize("model", ["se2se2", "se2r3"])
def test_pose_update_matches_dense_reference(model):
    worst = {"mean": 0.0, "P": 0.0, "nis": 0.0}
    for i, (x0, P0, r, off) in enumerate(cases(7 if model == "se2se2" else 8)):
        mu = mean_from_physical(model, x0)
        Z = pose_of(mu) @ gexp("se2se2", np.concatenate([off, np.zeros(3)]))[:3, :3]
        z = np.array([Z[0, 2], Z[1, 2], math.atan2(Z[1, 0], Z[0, 0])])
        f = CLASSES[model](dt=0.1, accel_std=(0.1, 0.1, 0.1), meas_std=r, x0=x0, P0=P0, measurement="pose")
        nis = f.update(z)
        mu_ref, P_ref, nis_ref = ref_update_pose(model, mu, P0, Z, r)
        e = {"mean": _rel(f.mean, mu_ref), "P": _rel(f.P, P_ref), "nis": abs(nis - nis_ref) / max(1.0, nis_ref)}
        for k, v in e.items():
            worst[k] = max(worst[k], v)
            assert v < TOL, f"case {i} (θ = {x0[2]!r}, offset {off}): {k} error {v:.3g}"
    print(model, "worst relative errors", worst)


def test_pose_refused_for_cv_with_a_clear_error():
    from lgekf import CVFilter

    with pytest.raises(ValueError, match="no heading"):
        CVFilter(dt=0.1, accel_std=0.5, meas_std=(0.3, 0.3, 0.1), x0=[0, 0, 1, 0], P0=np.eye(4), measurement="pose")


def test_pose_meas_std_needs_three_values():
    with pytest.raises(ValueError, match="meas_std"):
        SE2SE2Filter(dt=0.1, accel_std=(0.1, 0.1, 0.1), meas_std=0.3, x0=np.zeros(6), P0=np.eye(6), measurement="pose")
