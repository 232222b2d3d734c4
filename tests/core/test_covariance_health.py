"""Covariance health over 10⁵ steps: every posterior covariance finite, symmetric, positive definite.

All four models run (``filter_batch``, B = 1, K = 10⁵, ``return_cov=True``: 10⁵ × 36 floats ≈ 29 MB)
on the same plausible target: a vehicle at ~5 m/s whose turn rate varies smoothly within ±0.5 rad/s,
sampled every dt, measured with white noise of std ``meas_std``; each filter starts at the true state.

* ``test_covariance_stays_spd_extreme``: the extreme but valid settings dt = 1, σ_ω = 3 (the
  rotational / yaw-acceleration std; σ_a = 1 resp. σ_x = σ_y = 1, CV σ_a = 3), meas_std 1e-4 and 1e3.
* ``test_covariance_stays_spd_moderate``: dt = 0.1, moderate noise, meas_std 1e-2 and 10 — a regime in
  which every filter's linearisation is valid, so a failure there is a numerical defect.
* ``test_mean_stays_on_the_group``: the rotation blocks of the LG means stay orthonormal (the kernels
  carry cos/sin and never renormalise).
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.signal import lfilter

from lgekf import SE2R3Filter, SE2SE2Filter, filter_batch

pytestmark = pytest.mark.slow  # long runs (10⁵ steps each, about 10 s for the module on 2 cores)

K = 100_000
MODELS = ("se2se2", "se2r3", "ctrv", "cv")


def target_track(dt, K=K, seed=0):
    """(positions (K, 2), initial physical states per model): speed 5 ± 0.5 m/s, turn rate an AR(1)
    process with |ω| ≲ 0.5 rad/s (time constant 50 s), integrated exactly per step."""
    rng = np.random.RandomState(seed)
    a = np.exp(-dt / 50.0)
    om = lfilter([np.sqrt(1 - a * a) * 0.2], [1, -a], rng.randn(K))
    om = np.clip(om, -0.5, 0.5)
    v = 5.0 + lfilter([np.sqrt(1 - a * a) * 0.25], [1, -a], rng.randn(K))
    psi0 = 0.3
    psi = psi0 + np.concatenate([[0.0], np.cumsum(om[:-1] * dt)])
    # exact CTRV step with (v_k, ω_k) held over [t_k, t_k+1]
    h = om * dt / 2
    step = v * dt * np.sinc(h / np.pi)
    d = np.stack([step * np.cos(psi + h), step * np.sin(psi + h)], axis=1)
    pos = np.cumsum(d, axis=0)
    vx0, w0 = v[0], om[0]
    x0 = {
        "se2se2": [0.0, 0.0, psi0, vx0, 0.0, w0],
        "se2r3": [0.0, 0.0, psi0, vx0, 0.0, w0],
        "ctrv": [0.0, 0.0, psi0, vx0, w0],
        "cv": [0.0, 0.0, vx0 * np.cos(psi0), vx0 * np.sin(psi0)],
    }
    return pos, {m: np.array([x]) for m, x in x0.items()}, rng


def run(model, dt, accel_std, meas_std, seed=0):
    pos, x0, rng = target_track(dt, seed=seed)
    z = (pos + meas_std * rng.randn(*pos.shape))[None]
    n = x0[model].shape[1]
    P0 = np.eye(n) * 0.1
    return filter_batch(model, z, dt=dt, accel_std=accel_std, meas_std=meas_std, x0=x0[model], P0=P0, return_cov=True, return_nis=True)


def check_health(model, xs, Ps, nis):
    assert xs.shape == (1, K, len(Ps[0, 0])) and Ps.shape[:2] == (1, K)
    P = Ps[0]
    assert np.all(np.isfinite(xs)), "non-finite state"
    assert np.all(np.isfinite(P)), f"non-finite covariance from step {np.argmax(~np.isfinite(P).all(axis=(1, 2)))}"
    np.testing.assert_array_equal(P, np.swapaxes(P, 1, 2))
    diag = np.diagonal(P, axis1=1, axis2=2)
    ev = np.linalg.eigvalsh(P)
    bad = np.flatnonzero(ev[:, 0] <= 0)
    cond = ev[:, -1] / np.abs(ev[:, 0])
    msg = (
        f"{model}: {bad.size} of {K} covariances not positive definite (first at steps {bad[:5].tolist()}); "
        f"min eigenvalue {ev[:, 0].min():.3g}, max eigenvalue {ev[:, -1].max():.3g}, max condition number {cond.max():.3g}; "
        f"{np.sum(diag <= 0)} non-positive diagonal entries; NIS median {np.median(nis):.3g}, min {np.min(nis):.3g}, max {np.max(nis):.3g}"
    )
    assert bad.size == 0 and np.all(diag > 0), msg
    np.linalg.cholesky(P)  # the same, as the filters' own users would test it
    assert np.all(nis >= 0), msg


EXTREME_Q = {"se2se2": (1.0, 1.0, 3.0), "se2r3": (1.0, 1.0, 3.0), "ctrv": (1.0, 3.0), "cv": 3.0}
MODERATE_Q = {"se2se2": (0.5, 0.5, 0.3), "se2r3": (0.5, 0.5, 0.3), "ctrv": (0.5, 0.3), "cv": 1.5}


@pytest.mark.parametrize("meas_std", [1e-4, 1e3])
@pytest.mark.parametrize("model", MODELS)
def test_covariance_stays_spd_extreme(model, meas_std):
    # Observed at the time of writing: CTRV and CV pass; SE2SE2/SE2R3 fail for both meas_std.
    # meas_std = 1e-4: the EKF diverges (alternating corrections of growing size, states ~1e12,
    #   condition numbers ~1e30+; the CTRV EKF diverges statistically too, NIS ~1e5, but its
    #   linear Joseph update keeps P positive definite).
    # meas_std = 1e3: the heading is unobservable, P_θθ grows to ~1e4 rad², updates carry
    #   |ν_θ| of tens of radians, and Φ(ν) (singular at ν_θ ∈ 2πℤ∖{0}) collapses the rank of
    #   P⁺ = Φ(ν)(·)Φ(ν)ᵀ: condition numbers 1e18–1e21, eigenvalues negative by rounding.
    xs, Ps, nis = run(model, dt=1.0, accel_std=EXTREME_Q[model], meas_std=meas_std)
    check_health(model, xs, Ps, nis)


@pytest.mark.parametrize("meas_std", [1e-2, 10.0])
@pytest.mark.parametrize("model", MODELS)
def test_covariance_stays_spd_moderate(model, meas_std):
    xs, Ps, nis = run(model, dt=0.1, accel_std=MODERATE_Q[model], meas_std=meas_std)
    check_health(model, xs, Ps, nis)
    # in this regime the filters are also statistically sane
    assert 0.5 < np.mean(nis) < 10, np.mean(nis)


@pytest.mark.parametrize("cls", [SE2SE2Filter, SE2R3Filter])
def test_mean_stays_on_the_group(cls):
    pos, x0, rng = target_track(0.1, K=K)
    f = cls(dt=0.1, accel_std=MODERATE_Q["se2se2"], meas_std=0.1, x0=x0["se2se2"][0], P0=np.eye(6) * 0.1)
    z = pos + 0.1 * rng.randn(*pos.shape)
    for k in range(K):
        f.predict()
        f.update(z[k])
    M = f.mean
    for R in (M[:2, :2], M[3:5, 3:5]) if cls is SE2SE2Filter else (M[:2, :2],):
        np.testing.assert_allclose(R.T @ R, np.eye(2), atol=1e-12)
    assert np.all(np.isfinite(f.P))
