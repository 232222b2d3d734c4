"""Maximum-likelihood noise learning (lgekf.estimators.noise.tuning): recovery of known noise on simulated data
within the stated uncertainty, and the clear refusal when there are too few points."""

import numpy as np
import pytest

from lgekf.estimators.noise.tuning import MIN_UPDATES_PER_PARAMETER, learn_noise, log_likelihood
from lgekf.estimators.noise.tracks import batch_tracks
from lgekf.experiments.simulate import simulate


def _tracks(sim):
    t = sim.dt * np.arange(sim.z.shape[1])
    return [(t, zb) for zb in sim.z]


def test_learns_known_noise_of_the_paper_model():
    """SE(2)×SE(2) truth (lgekf.experiments.simulate), σ_v = 0.5 m/s², σ_ω = 0.2 rad/s², r = 0.2 m, 60 tracks
    of 20 s: the learned (σ_x, σ_y, σ_ω, r) cover the truth with their 95 % intervals (measured: 0.514 [0.479,
    0.552], 0.461 [0.376, 0.565], 0.2105 [0.191, 0.232], 0.1986 [0.197, 0.201])."""
    rng = np.random.default_rng(5)
    B = 60
    x0 = np.tile([0, 0, 0, 3.0, 0, 0], (B, 1))
    sim = simulate(x0, dt=0.1, steps=200, sigma_v=0.5, sigma_w=0.2, meas_std=0.2, rng=rng)
    fit = learn_noise("se2se2", _tracks(sim), n_starts=1)
    truth = np.array([0.5, 0.5, 0.2, 0.2])
    assert fit.identified, fit.report()
    assert np.all(fit.ci_low <= truth) and np.all(truth <= fit.ci_high), fit.report()
    # informative: every interval within ×/÷ 1.5 of its value
    assert np.all(fit.ci_high / fit.ci_low < 2.25), fit.report()
    assert "se2se2" in fit.report() and "95 %" in fit.report()


def test_learns_cv_noise_with_fixed_measurement_std_and_likelihood_is_maximal():
    rng = np.random.default_rng(9)
    B, K, dt = 80, 50, 0.1
    # CV truth: white acceleration noise 0.8 m/s² per axis, position noise 0.3
    a = 0.8 * rng.standard_normal((B, K, 2))
    v = np.cumsum(a * dt, axis=1) + np.array([2.0, 0.5])
    p = np.cumsum(v * dt + 0.5 * a * dt**2, axis=1)
    z = p + 0.3 * rng.standard_normal(p.shape)
    tracks = [zb for zb in z]
    fit = learn_noise("cv", tracks, dt=dt, meas_std=0.3)
    assert fit.fixed == (False, True)
    assert fit.ci_low[0] <= 0.8 <= fit.ci_high[0], fit.report()
    batch = batch_tracks(tracks, 2, dt, baseline=1.0)  # the start learn_noise uses
    best = log_likelihood("cv", batch, fit.accel_std, 0.3)
    assert best == pytest.approx(fit.loglik, rel=1e-9)
    for f in (0.7, 1.4):
        assert log_likelihood("cv", batch, np.array(fit.accel_std) * f, 0.3) < best


def test_too_few_points_is_refused_clearly():
    z = np.array([[0, 0], [0.3, 0.0], [0.6, 0.1], [0.9, 0.1], [1.2, 0.2]])
    with pytest.raises(ValueError, match=r"too few measurements to learn the noise of se2r2: 3 filter updates .* need at least 30"):
        learn_noise("se2r2", [z], dt=0.1, baseline=0.1)
    assert MIN_UPDATES_PER_PARAMETER >= 5


def test_flat_likelihood_is_reported():
    """Straight constant-velocity motion without process noise: the turn-rate noise of CTRV cannot be
    told from zero, and the fit says so instead of giving a number as if it were learned."""
    rng = np.random.default_rng(2)
    B, K, dt = 10, 20, 0.1
    t = dt * np.arange(K)
    tracks = [(t, np.column_stack([2.0 * t, 0.5 * t]) + 0.3 * rng.standard_normal((K, 2))) for _ in range(B)]
    fit = learn_noise("ctrv", tracks, meas_std=0.3)
    assert not fit.identified
    assert "not identified: sigma_alpha: the 95 % interval spans more than" in fit.report()
