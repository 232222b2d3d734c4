"""The IMM fitted by maximum likelihood (lgekf.estimators.imm.tuning): its likelihood against an independent
numpy Kalman filter, its reduction with identical modes, and recovery of known noise levels and switching."""

import math

import numpy as np
import pytest
from _imm_numpy import numpy_cv_imm_loglik

from lgekf.core.common import covariance_from_common, state_from_common
from lgekf.core.initiation import DEFAULT_OMEGA_STD, two_point
from lgekf.estimators.imm.estimator import Mode
from lgekf.estimators.imm.tuning import imm_log_likelihood, learn_imm


def _simulate_cv(rng, n_tracks, steps, dt, stds, switch, r):
    """Tracks of a CV object (DWNA, world-frame velocity) whose acceleration std switches between ``stds``
    with probability ``switch`` per step (a Markov chain, the IMM's own assumption); noisy positions."""
    F = np.eye(4)
    F[0, 2] = F[1, 3] = dt
    G = np.array([[dt**2 / 2, 0], [0, dt**2 / 2], [dt, 0], [0, dt]])
    tracks = []
    for _ in range(n_tracks):
        x = np.array([*rng.uniform(-50, 50, 2), *rng.normal(0, 1.5, 2)])
        mode = rng.integers(len(stds))
        z = np.empty((steps, 2))
        for k in range(steps):
            z[k] = x[:2] + r * rng.standard_normal(2)
            if rng.random() < switch:
                mode = (mode + 1 + rng.integers(len(stds) - 1)) % len(stds)
            x = F @ x + G @ (stds[mode] * rng.standard_normal(2))
        tracks.append((dt * np.arange(steps) + rng.uniform(0, 3), z))
    return tracks


def _numpy_cv_loglik(tracks, sigma_a, r, baseline):
    """The CV Kalman filter's innovation log-likelihood, written out in numpy, from the IMM's start: the
    two-point estimate of the first two measurements converted to (x, y, w_x, w_y)."""
    total = 0.0
    for t, z in tracks:
        c0, var0 = two_point(t[:2], z[:2], np.array([1]), r, DEFAULT_OMEGA_STD)
        x = state_from_common("cv", c0)[0]
        P = covariance_from_common("cv", c0, np.diag(var0[0])[None])[0] + 1e-12 * np.eye(4)
        for k in range(2, len(t)):
            T = t[k] - t[k - 1]
            F = np.eye(4)
            F[0, 2] = F[1, 3] = T
            G = np.array([[T**2 / 2, 0], [0, T**2 / 2], [T, 0], [0, T]])
            x = F @ x
            P = F @ P @ F.T + sigma_a**2 * G @ G.T
            H = np.eye(2, 4)
            S = H @ P @ H.T + r**2 * np.eye(2)
            nu = z[k] - H @ x
            if t[k] - t[0] >= baseline:
                total += -0.5 * (np.linalg.slogdet(S)[1] + nu @ np.linalg.solve(S, nu) + 2 * math.log(2 * math.pi))
            K = P @ H.T @ np.linalg.inv(S)
            x = x + K @ nu
            P = (np.eye(4) - K @ H) @ P
    return total


def test_one_mode_likelihood_is_the_kalman_filters():
    rng = np.random.default_rng(3)
    tracks = _simulate_cv(rng, 6, 40, 0.1, [0.5], 0.0, 0.2)
    got = imm_log_likelihood([Mode("cv", (0.7,))], tracks, meas_std=0.2, baseline=0.5)
    want = _numpy_cv_loglik(tracks, 0.7, 0.2, 0.5)
    assert got == pytest.approx(want, rel=1e-9, abs=1e-7)


def _numpy_cv_imm_loglik(tracks, stds, PI, r, baseline):
    """A two-mode CV IMM written out in numpy (tests/_imm_numpy.py), started by the two-point initiation with
    uniform mode probabilities, the steps within the first ``baseline`` seconds not counted."""
    M = len(stds)
    total = 0.0
    for t, z in tracks:
        c0, var0 = two_point(t[:2], z[:2], np.array([1]), r, DEFAULT_OMEGA_STD)
        x0 = state_from_common("cv", c0)[0]
        P0 = covariance_from_common("cv", c0, np.diag(var0[0])[None])[0] + 1e-12 * np.eye(4)
        total += numpy_cv_imm_loglik(x0, P0, z[2:], np.diff(t)[1:], stds, PI, r, np.full(M, 1.0 / M),
                                     counted=t[2:] - t[0] >= baseline)
    return total


def test_two_mode_likelihood_is_a_numpy_imms():
    """Two CV modes of different noise against the IMM written out in numpy: checks the predicted mode
    probabilities c̄ in the mixture, the mixing and the conditioning on the first ``baseline`` seconds."""
    rng = np.random.default_rng(8)
    tracks = _simulate_cv(rng, 4, 40, 0.1, [0.2, 2.0], 0.05, 0.2)
    PI = np.array([[0.9, 0.1], [0.1, 0.9]])
    got = imm_log_likelihood([Mode("cv", (0.2,), "calm"), Mode("cv", (2.0,), "manoeuvre")], tracks, meas_std=0.2,
                             switch=0.1, baseline=0.5)
    want = _numpy_cv_imm_loglik(tracks, [0.2, 2.0], PI, 0.2, 0.5)
    assert got == pytest.approx(want, rel=1e-9, abs=1e-7)


def test_identical_modes_give_the_single_modes_likelihood():
    rng = np.random.default_rng(4)
    tracks = _simulate_cv(rng, 5, 30, 0.1, [0.5], 0.0, 0.2)
    one = imm_log_likelihood([Mode("cv", (0.6,))], tracks, meas_std=0.2)
    two = imm_log_likelihood([Mode("cv", (0.6,), "a"), Mode("cv", (0.6,), "b")], tracks, meas_std=0.2, switch=0.3)
    assert two == pytest.approx(one, rel=1e-10)


@pytest.mark.slow
def test_learn_imm_recovers_noise_levels_and_switching():
    """Truth: acceleration std 0.3 (calm) and 3.0 (manoeuvring), switching 0.03 per step, steps of 0.5 s.
    The fit starts from modes of 0.6 and 1.5 and switching 0.1; the truth must lie in its 95 % intervals.
    (With a calm std of 0.1 at 0.1 s steps the calm mode is indistinguishable from no noise at all: the fit
    then ends on the search bound and says so, see ``problems``.)"""
    rng = np.random.default_rng(11)
    tracks = _simulate_cv(rng, 30, 120, 0.5, [0.3, 3.0], 0.03, 0.2)
    modes = [Mode("cv", (0.6,), "calm"), Mode("cv", (1.5,), "manoeuvre")]
    fit = learn_imm(modes, tracks, meas_std=0.2, switch=0.1)
    truth = np.array([0.3 / 0.6, 3.0 / 1.5, 0.03])
    est = np.array([*fit.factors, fit.switch])
    assert np.all(np.isfinite(fit.ci_low)) and np.all(np.isfinite(fit.ci_high)), fit.report()
    assert np.all(fit.ci_low <= truth) and np.all(truth <= fit.ci_high), (fit.report(), truth)
    assert np.all(fit.ci_low <= est) and np.all(est <= fit.ci_high)
    assert fit.loglik > fit.loglik_start
    assert [m.accel_std[0] for m in fit.modes] == pytest.approx([0.6 * fit.factors[0], 1.5 * fit.factors[1]])
    assert "manoeuvre" in fit.report() and not fit.problems


def test_learn_imm_refuses_too_few_measurements():
    rng = np.random.default_rng(5)
    tracks = _simulate_cv(rng, 2, 8, 0.1, [0.5], 0.0, 0.2)
    with pytest.raises(ValueError, match="too few measurements to fit the IMM"):
        learn_imm("cv:calm,cv:manoeuvre", tracks, meas_std=0.2)


@pytest.mark.parametrize("bad, match", [
    (lambda tr: [(tr[0][0][::-1], tr[0][1])], "times must be finite and increase"),
    (lambda tr: [(tr[0][0], tr[0][1][:, :1])], "expected t"),
])
def test_learn_imm_bad_tracks(bad, match):
    rng = np.random.default_rng(6)
    tracks = _simulate_cv(rng, 1, 10, 0.1, [0.5], 0.0, 0.2)
    with pytest.raises(ValueError, match=match):
        learn_imm("cv:calm,cv:manoeuvre", bad(tracks), meas_std=0.2)


def test_learn_imm_rejects_bad_noise():
    with pytest.raises(ValueError, match="meas_std"):
        learn_imm("cv:calm,cv:manoeuvre", [], meas_std=-1.0)


def test_learn_imm_position_only_and_finite_times():
    rng = np.random.default_rng(7)
    tracks = _simulate_cv(rng, 2, 10, 0.1, [0.5], 0.0, 0.2)
    with pytest.raises(ValueError, match="position measurements only"):
        learn_imm("cv:calm,cv:manoeuvre", tracks, meas_std=0.2, measurement="pose")
    t, z = tracks[0]
    t = t.copy()
    t[3] = np.nan
    with pytest.raises(ValueError, match="finite and increase"):
        imm_log_likelihood("cv", [(t, z)], meas_std=0.2)


def test_report_of_an_unbounded_interval_warns_nothing():
    """An interval from ~0 to a huge bound (a flat direction) is reported as "[no interval]", without numpy's overflow
    warning on the user's terminal (lgekf evaluate printed one); a finite one with its bounds; given values as such."""
    import warnings

    from lgekf.estimators.imm.estimator import Mode
    from lgekf.estimators.imm.tuning import ImmFit

    fit = ImmFit([Mode("cv", (0.1,), "calm"), Mode("cv", (2.0,), "manoeuvre")], 0.02, np.array([0.01, 0.5]),
                 np.array([1e-300, 0.4, 0.02]), np.array([1e300, 0.6, 0.02]), -10.0, -12.0, 100, 3, [], 2, 50)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        text = fit.report()
    assert "cv:calm ×0.01 [no interval]" in text and "cv:manoeuvre ×0.5 [0.4, 0.6]" in text and "switch 0.02 (given)" in text


@pytest.mark.parametrize("modes", ["cv,se2r3:calm,se2r3:manoeuvre", "se2r3:calm,se2r3:manoeuvre", "cv,ctrv,se2se2"])
def test_likelihood_batch_on_threads_equals_the_generic_loop(modes, monkeypatch):
    """The fit's batch (the generated imm_loglik_batch_position, parts of the batch on threads) gives each track
    bit for bit the sum of imm_loglik_one (the generic loop, the measurement as an argument), missed steps and the
    skipped start included, whatever the number of threads."""
    from lgekf.estimators import threads
    from lgekf.estimators.imm import tuning
    from lgekf.estimators.imm.estimator import parse_modes
    from lgekf.estimators.imm.kernels import imm_loglik_one

    rng = np.random.default_rng(3)
    tracks = []
    for b in range(40):
        K = 30 + b
        t = 0.1 * np.arange(K) + 0.01 * rng.random(K)
        th = 0.3 * b + 0.2 * np.sin(t)
        z = np.stack([np.cumsum(4 * np.cos(th)), np.cumsum(4 * np.sin(th))], 1) * 0.1 + 0.3 * rng.standard_normal((K, 2))
        z[5 + b % 7] = np.nan
        tracks.append((t, z))
    tr = tuning._Tracks(tracks, 2, 0.3, 0.5, 0.5)
    L = tuning._Likelihood(parse_modes(modes), 0.3, tr, "position")
    s = L.setup
    want = [imm_loglik_one(s.models, L.S0[b].copy(), L.Pp0[b].copy(), s.mu0.copy(), s.PI, s.Q, s.r, tr.z[b], tr.dts[b],
                           tr.skip[b], tr.lengths[b], s.same_group, s.meas) for b in range(tr.B)]
    for cpus in (1, 3):
        monkeypatch.setattr(threads, "usable_cpus", lambda: cpus)
        ll, cnt = np.full(tr.B, np.nan), np.zeros(tr.B, dtype=np.int64)
        tuning.imm_loglik_batch(s.models, L.S0, L.Pp0, s.mu0, s.PI, s.Q, s.r, tr.z, tr.dts, tr.lengths, tr.skip,
                                s.same_group, s.meas, ll, cnt)
        assert ll.tolist() == [w[0] for w in want] and cnt.tolist() == [w[1] for w in want]
    assert tr.skip.max() > 0 and np.isnan(tr.z).any()  # the case covers the skipped start and missed steps
