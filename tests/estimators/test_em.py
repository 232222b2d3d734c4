"""EM for the noise of the linear Gaussian models (lgekf.estimators.noise.em): recovery of known CV noise, the EM
property (likelihood non-decreasing), agreement with the L-BFGS maximum likelihood, the clear refusals, and the
model table's ``linear`` flag checked against the generated kernels."""

import subprocess

import numpy as np
import pytest
from _cli import cli_command

from lgekf.core.registry import MODELS
from lgekf.estimators.noise.em import EMTrace, em_models, em_or_lbfgs, learn_noise_em
from lgekf.estimators.noise.tracks import batch_tracks
from lgekf.estimators.noise.tuning import learn_noise, log_likelihood

SIGMA_A, R = 0.3, 0.2


def _cv_tracks(seed: int, n_tracks: int = 16, steps: int = 50, v0=None):
    """CV truth simulated here (not by the code under test): DWNA x_k = F x_{k-1} + G n_k with
    G = [dt²/2 I; dt I], n ~ N(0, σ_a² I), irregular dt in [0.2, 0.6] s; z = position + N(0, r² I)."""
    rng = np.random.default_rng(seed)
    tracks = []
    for _ in range(n_tracks):
        dts = rng.uniform(0.2, 0.6, steps - 1)
        p = np.zeros(2)
        v = rng.normal(0, 1.0, 2) if v0 is None else np.asarray(v0, dtype=float)
        ps = [p.copy()]
        for dt in dts:
            a = rng.normal(0, SIGMA_A, 2)
            p = p + dt * v + 0.5 * dt * dt * a
            v = v + dt * a
            ps.append(p.copy())
        z = np.array(ps) + rng.normal(0, R, (steps, 2))
        tracks.append((np.concatenate([[0.0], np.cumsum(dts)]), z))
    return tracks


@pytest.fixture(scope="module")
def data():
    tracks = _cv_tracks(3)
    for b in range(0, len(tracks), 3):  # missed detections (NaN rows) in every third track
        tracks[b][1][[20, 21, 35]] = np.nan
    trace = EMTrace()
    fit = learn_noise_em("cv", tracks, init=(2.0, 1.0), trace=trace, accelerate=False)  # plain EM
    return tracks, fit, trace


def test_em_recovers_known_cv_noise_within_the_stated_uncertainty(data):
    """Truth (σ_a, r) = (0.3, 0.2); measured: 0.2729 [0.244, 0.305], 0.2029 [0.195, 0.211] in 98 E-steps of plain EM (32 with SQUAREM)."""
    _, fit, trace = data
    assert trace.converged and fit.identified, fit.report()
    truth = np.array([SIGMA_A, R])
    z = np.abs(np.log(fit.values / truth)) / fit.log_se
    assert np.all(z < 2.5), (fit.report(), z)
    assert np.all(fit.ci_high / fit.ci_low < 1.6), fit.report()  # informative
    assert fit.names == ("sigma_a", "meas_r") and "cv" in fit.report()


def test_em_likelihood_never_decreases(data):
    _, fit, trace = data
    ll = np.array(trace.loglik)
    assert len(ll) > 5
    assert np.all(np.diff(ll) >= -1e-9 * (1 + np.abs(ll[1:]))), np.diff(ll).min()
    assert ll[-1] - ll[0] > 100  # from a start far off (σ_a = 2, r = 1) EM climbs a long way
    assert fit.loglik == pytest.approx(ll[-1], abs=1e-9)


def test_em_likelihood_is_the_filters_innovation_likelihood(data):
    tracks, fit, _ = data
    batch = batch_tracks(tracks, 2, None, baseline=1.0)  # the start learn_noise(_em) uses
    assert log_likelihood("cv", batch, fit.accel_std, fit.meas_std) == pytest.approx(fit.loglik, rel=1e-10)


def test_em_and_lbfgs_agree_on_the_maximum_likelihood(data):
    tracks, fit, trace = data
    ref = learn_noise("cv", tracks, n_starts=1, hessian=False)
    assert fit.loglik >= ref.loglik - 1e-4
    assert fit.loglik - ref.loglik < 1e-2
    np.testing.assert_allclose(fit.values, ref.values, rtol=2e-3)
    # SQUAREM (the default): the same maximum in fewer E-steps, its recorded likelihood never decreasing either
    fast_trace = EMTrace()
    fast = learn_noise_em("cv", tracks, init=(2.0, 1.0), trace=fast_trace, hessian=False)
    assert fast_trace.converged and fast_trace.e_steps < trace.e_steps / 2 and trace.e_steps == len(trace.loglik)
    ll = np.array(fast_trace.loglik)
    assert np.all(np.diff(ll) >= -1e-9 * (1 + np.abs(ll[1:])))
    np.testing.assert_allclose(fast.values, fit.values, rtol=2e-4)
    assert fast.loglik >= ref.loglik - 1e-4


def test_numeric_measurement_m_step_matches_the_closed_form():
    """Fast objects (the two-point start's heading variance below its cap): P_0(r) = r² A and r's M-step is the
    closed form; forcing the numeric M-step must reach the same maximum, and the optimiser's."""
    tracks = _cv_tracks(5, n_tracks=10, steps=40, v0=(3.0, 1.0))
    closed, numeric = EMTrace(), EMTrace()
    fit = learn_noise_em("cv", tracks, hessian=False, trace=closed, init=(0.4, 0.3))
    num = learn_noise_em("cv", tracks, hessian=False, _numeric_r=True, init=fit.values * 1.2, trace=numeric)
    assert closed.closed_form_r and not numeric.closed_form_r
    assert np.all(np.diff(closed.loglik) >= -1e-9 * (1 + np.abs(closed.loglik[1:])))
    np.testing.assert_allclose(num.values, fit.values, rtol=1e-4)
    batch = batch_tracks(tracks, 2, None, baseline=1.0)
    best = log_likelihood("cv", batch, fit.accel_std, fit.meas_std)
    for f in (0.99, 1.01):
        assert log_likelihood("cv", batch, fit.accel_std, np.array(fit.meas_std) * f) < best
        assert log_likelihood("cv", batch, np.array(fit.accel_std) * f, fit.meas_std) < best


def test_fixed_measurement_std_learns_process_noise_only(data):
    tracks, _, _ = data
    fit = learn_noise_em("cv", tracks, meas_std=R, hessian=False, init=(SIGMA_A, R))
    assert fit.fixed == (False, True) and fit.meas_std == (R,)
    batch = batch_tracks(tracks, 2, None, baseline=1.0)
    best = log_likelihood("cv", batch, fit.accel_std, R)
    assert best == pytest.approx(fit.loglik, rel=1e-10)
    for f in (0.99, 1.01):  # a maximum in σ_a (the likelihood of the optimiser's objective)
        assert log_likelihood("cv", batch, np.array(fit.accel_std) * f, R) < best


def test_too_few_points_gives_the_same_error_as_learn_noise():
    z = np.array([[0, 0], [0.3, 0.0], [0.6, 0.1], [0.9, 0.1], [1.2, 0.2]])
    with pytest.raises(ValueError) as ref:
        learn_noise("cv", [z], dt=0.1, baseline=0.1)
    with pytest.raises(ValueError) as got:
        learn_noise_em("cv", [z], dt=0.1, baseline=0.1)
    assert str(got.value) == str(ref.value)
    assert "too few measurements to learn the noise of cv" in str(got.value)


@pytest.mark.parametrize("model", [m for m in MODELS if "position" not in MODELS[m].linear])
def test_nonlinear_models_are_refused_naming_the_supported_ones(model):
    z = np.zeros((40, 2))
    with pytest.raises(ValueError, match=r"EM applies only to linear Gaussian models.*EM supports: cv with position"):
        learn_noise_em(model, [z], dt=0.1)


def test_linear_flag_agrees_with_the_generated_kernels():
    """``linear`` (derived symbolically from the definition) against the numbers: for a linear model F and ℋ
    are the same at two random states and Φ = I; every other model fails one of these."""
    assert em_models() == {"cv": ("position",)}
    rng = np.random.default_rng(0)
    for name, spec in MODELS.items():
        k = spec.kernels
        s1, s2 = (k.state_from_physical(rng.normal(0, 1, spec.n) * 0.5) for _ in range(2))
        eps = rng.normal(0, 0.3, spec.n)
        same = (np.allclose(k.transition(s1, 0.3), k.transition(s2, 0.3))
                and np.allclose(k.calH_position(s1), k.calH_position(s2))
                and np.allclose(k.right_jacobian(eps), np.eye(spec.n)))
        assert same == ("position" in spec.linear), name


def test_track_tune_method_em_learns_cv_noise_by_em(tmp_path):
    """``lgekf track --tune --tune-method em``: the printed fit is EM's on the file's tracks (same numbers as
    calling learn_noise_em on them), and the other models of the same run fall back to the optimiser."""
    tracks = _cv_tracks(4, n_tracks=6, steps=40)
    lines = ["id,t,x,y"] + [f"{b},{float(t)!r},{float(x)!r},{float(y)!r}" for b, (ts, z) in enumerate(tracks) for t, (x, y) in zip(ts, z)]
    (tmp_path / "cv.csv").write_text("\n".join(lines) + "\n")
    r = subprocess.run([*cli_command(), "track", "cv.csv", "--model", "cv", "--tune", "--tune-method", "em", "-o", "out.csv"],
                       capture_output=True, text=True, cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    fit = learn_noise_em("cv", tracks)
    assert f"learned noise for cv by EM (position, 6 tracks, {fit.n_updates} updates" in r.stderr, r.stderr
    assert f"sigma_a = {fit.values[0]:.4g}" in r.stderr and f"meas_r = {fit.values[1]:.4g}" in r.stderr, (r.stderr, fit.report())
    assert (tmp_path / "out.csv").exists()
    assert em_or_lbfgs("cv", "position", "em") == "em"
    assert em_or_lbfgs("se2se2", "position", "em") == em_or_lbfgs("cv", "position", "lbfgs") == "lbfgs"


def test_evaluate_tuning_uses_em_for_cv_only():
    """``lgekf evaluate --tune --tune-method em`` learns through ``learn_on_dataset(..., method="em")``: CV by EM,
    with the same value as learn_noise_em on the same noisy tracks (measurement std held at the known one)."""
    from lgekf.apps.smooth_track import learn_on_dataset
    from lgekf.io.datasets import Dataset

    tracks = _cv_tracks(6, n_tracks=8, steps=40)
    t = np.concatenate([ts for ts, _ in tracks])
    p = np.concatenate([z for _, z in tracks])
    starts = np.concatenate([[0], np.cumsum([len(ts) for ts, _ in tracks])])
    ds = Dataset("toy", t, p, None, starts, [str(i) for i in range(len(tracks))])

    def rng(seed, stream, name):
        return np.random.default_rng([seed, stream])

    fits = learn_on_dataset(ds, 0.1, [0], rng, ("cv",), method="em")
    noisy = p + 0.1 * rng(0, 1, "toy").standard_normal(p.shape)
    ref = learn_noise_em("cv", [(t[a:b], noisy[a:b]) for a, b in zip(starts[:-1], starts[1:])], meas_std=0.1, hessian=False)
    assert fits["cv"].method == "em" and "by EM" in fits["cv"].report()
    np.testing.assert_allclose(fits["cv"].values, ref.values, rtol=1e-12)
