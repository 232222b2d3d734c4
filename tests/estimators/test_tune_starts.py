"""`--tune`'s starts (issue #26): the noise fit starts from the data-based estimate and the model's defaults, never
ends below the best valid start's log-likelihood, rejects fits whose filter loses tracks, and reports intervals the
data cannot give as not identified."""

import re
import subprocess

import numpy as np
import pytest
from _cli import cli_command

from lgekf.apps.defaults import plan_noise
from lgekf.apps.divergence import MonitorConfig
from lgekf.apps.track import DEFAULT_HEADING_STD, DEFAULT_OMEGA_STD, TRACK_HEADING_CAP
from lgekf.core.registry import get_model
from lgekf.estimators.noise import tuning
from lgekf.estimators.noise.em import learn_noise_em
from lgekf.estimators.noise.tracks import batch_tracks
from lgekf.estimators.noise.tuning import learn_noise, log_likelihood

NOISE = 20.0  # m per axis
#: near the noise of the simulated motion (turn rates ±0.05 rad/s switched now and then, no speed change)
DATA_START = ((0.7, 0.0156), NOISE)


def fast_objects(n_obj=6, n=60, speed=120.0, seed=3):
    """[(t, z, truth)]: aircraft-like objects at ``speed`` m/s, turn rate 0 or ±0.05 rad/s switched every 20 steps,
    ~1 Hz irregular stamps (steps 0.8-1.2 s), ``NOISE`` m position noise per axis."""
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n_obj):
        t = np.concatenate([[0.0], np.cumsum(rng.uniform(0.8, 1.2, n - 1))])
        psi, p, w = rng.uniform(-np.pi, np.pi), rng.uniform(-5e3, 5e3, 2), 0.0
        truth = np.empty((n, 2))
        for k in range(n):
            if k % 20 == 0:
                w = rng.choice([0.0, 0.05, -0.05])
            truth[k] = p
            if k < n - 1:
                h = t[k + 1] - t[k]
                psi += w * h
                p = p + speed * h * np.array([np.cos(psi), np.sin(psi)])
        out.append((t, truth + NOISE * rng.standard_normal(truth.shape), truth))
    return out


def _tracks():
    return [(t, z) for t, z, _ in fast_objects()]


def _record(fit, label):
    return next(s for s in fit.starts if s.label == label)


def test_fit_never_ends_below_the_data_start_when_the_default_start_diverges():
    """se2r2 on fast objects: from the model's default noise (σ_a 0.5 m/s², σ_α 1 rad/s²) the filter loses most
    tracks and the optimiser's run from there alone ends far below the data-based start (the failure of issue
    #26); with the data start the fit ends at or above it, and its log-likelihood is that of the returned noise."""
    tracks = _tracks()
    batch = batch_tracks(tracks, 2, baseline=1.0)  # the tracks learn_noise uses
    fit = learn_noise("se2r2", tracks, n_starts=1, starts={"data": DATA_START})
    data, default = _record(fit, "data"), _record(fit, "default")
    # the records' log-likelihoods are those of their noise
    assert data.start_loglik == pytest.approx(log_likelihood("se2r2", batch, *DATA_START), rel=1e-12)
    assert default.start_loglik == pytest.approx(log_likelihood("se2r2", batch, default.start[:2], default.start[2:]), rel=1e-12)
    assert np.allclose(default.start[:2], get_model("se2r2").default_accel_std)
    # the default start is a lost filter, and its optimiser run alone ends far below the data start
    assert default.start_lost is not None and "loses" in default.start_lost
    assert default.end_loglik < data.start_loglik - 1000, fit.report()
    assert data.start_lost is None
    # the fit: never below the best valid start, and its log-likelihood is the returned noise's
    assert fit.loglik >= data.start_loglik, fit.report()
    assert fit.loglik == pytest.approx(log_likelihood("se2r2", batch, fit.accel_std, fit.meas_std), rel=1e-12)
    assert fit.kept == "the optimum from the data start"
    assert "starts (log-likelihood" in fit.report() and "data -3" in fit.report()


def test_optimiser_ending_below_the_start_keeps_the_start_and_says_so(monkeypatch):
    """An optimiser that ends far from the data (here every run is replaced by a jump to the lower search bound,
    where the filter loses its tracks): the fit is the best valid start, without intervals, and the report says so."""
    import scipy.optimize

    real = scipy.optimize.minimize

    def bad(fun, x0, *args, **kwargs):
        res = real(fun, x0, *args, **{**kwargs, "options": {"maxiter": 1}})
        res.x = np.full_like(np.asarray(x0, dtype=float), np.log(tuning.BOUNDS[0]))
        res.fun = fun(res.x)
        return res

    monkeypatch.setattr(scipy.optimize, "minimize", bad)
    tracks = _tracks()
    fit = learn_noise("se2r2", tracks, n_starts=1, starts={"data": DATA_START})
    assert fit.values == pytest.approx([*DATA_START[0], NOISE])
    assert fit.loglik == pytest.approx(log_likelihood("se2r2", batch_tracks(tracks, 2, baseline=1.0), *DATA_START), rel=1e-12)
    assert fit.kept == "start data" and not fit.identified
    assert np.all(np.isnan(fit.ci_low)) and np.all(np.isnan(fit.ci_high))
    rep = fit.report()
    assert rep.count("[not identified]") == 3, rep
    assert "no valid optimiser end reached the log-likelihood of the data start" in rep, rep


def test_zero_width_interval_is_reported_as_not_identified(monkeypatch):
    """A Hessian far more curved than any 344 measurements allow (standard error 1e-7 of the log stds: an interval
    of ×/÷1.0000002, printed [0.135, 0.135] in the issue): no interval, each parameter reported as not identified."""
    monkeypatch.setattr(tuning, "_standard_errors", lambda nll, th, h=0.02: np.full(len(th), 1e-7))
    fit = learn_noise("se2r2", _tracks(), n_starts=1, starts={"data": DATA_START})
    assert not fit.identified
    assert np.all(np.isnan(fit.ci_low)) and np.all(np.isnan(fit.ci_high))
    rep = fit.report()
    for name in fit.names:
        assert f"{name} = " in rep and re.search(rf"{name} = [0-9.e+-]+ \[not identified\]", rep), rep
        assert f"{name}: its 95 % interval ×/÷(1 + 2e-07) is narrower than 688 measured values can give (×/÷(1 + 0.054) at best)" in rep, rep
    assert "95 %:" not in rep


def test_realistic_standard_errors_keep_their_intervals(monkeypatch):
    """The bound is not a hair trigger: 688 scalar measurements give at best se(log σ) = 1/√1376 = 0.027; a standard
    error of 0.05 is an interval ×/÷e^(1.96·0.05) around the value."""
    monkeypatch.setattr(tuning, "_standard_errors", lambda nll, th, h=0.02: np.full(len(th), 0.05))
    fit = learn_noise("se2r2", _tracks(), n_starts=1, starts={"data": DATA_START})
    np.testing.assert_allclose(fit.ci_high / fit.values, np.exp(1.96 * 0.05), rtol=1e-12)
    np.testing.assert_allclose(fit.values / fit.ci_low, np.exp(1.96 * 0.05), rtol=1e-12)
    assert "[not identified]" not in fit.report()


def test_em_runs_from_the_best_start():
    """CV by EM: every start evaluated, EM from the best valid one (the data start here, far above the defaults ×1
    for 120 m/s objects), the fit at or above it."""
    tracks = _tracks()
    fit = learn_noise_em("cv", tracks, starts={"data": ((10.0,), NOISE)}, hessian=False)
    data = _record(fit, "data")
    assert data.end is not None and fit.loglik >= data.start_loglik
    assert fit.loglik == pytest.approx(log_likelihood("cv", batch_tracks(tracks, 2, baseline=1.0), fit.accel_std, fit.meas_std),
                                       rel=1e-12)


def test_a_bad_start_is_one_clear_error():
    with pytest.raises(ValueError, match=r"start 'data' of se2r2: expected 2 non-negative process-noise stds"):
        learn_noise("se2r2", _tracks(), starts={"data": ((0.5,), NOISE)})


def _write(path, objs):
    lines = ["id,t,x,y"] + [f"{i},{float(tt)!r},{float(x)!r},{float(y)!r}" for i, (t, z, _) in enumerate(objs) for tt, (x, y) in zip(t, z)]
    path.write_text("\n".join(lines) + "\n")


def test_cli_track_tune_ends_at_or_above_the_data_based_start(tmp_path):
    """`lgekf track FILE --model se2r2 --tune` on fast objects: the printed learned log-likelihood is at least that
    of the noise `lgekf track` estimates from the data without --tune (recomputed here from plan_noise)."""
    objs = fast_objects()
    _write(tmp_path / "fast.csv", objs)
    r = subprocess.run([*cli_command(), "track", "fast.csv", "--model", "se2r2", "--tune", "-o", "out.csv"],
                       capture_output=True, text=True, cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    learned = float(re.search(r"learned noise for se2r2 \(position, 6 tracks, \d+ updates, log-likelihood (\S+)\)", r.stderr)[1])
    # the data-based start as cli/track.py computes it (sorted by id, like the file)
    t = np.concatenate([o[0] for o in objs])
    z = np.concatenate([o[1] for o in objs])
    starts = np.cumsum([0] + [len(o[0]) for o in objs])
    plan = plan_noise(t, z, starts, ["se2r2"], omega_std=DEFAULT_OMEGA_STD, heading_std=DEFAULT_HEADING_STD,
                      heading_cap=TRACK_HEADING_CAP, monitor=MonitorConfig())
    batch = batch_tracks([(o[0], o[1]) for o in objs], 2, baseline=1.0)
    at_start = log_likelihood("se2r2", batch, plan.accel_std["se2r2"], plan.meas_std)
    at_default = log_likelihood("se2r2", batch, get_model("se2r2").default_accel_std, plan.meas_std)
    assert at_default < at_start - 1000  # a file where the model's default noise is a bad start
    assert learned >= at_start - 5e-6 * abs(at_start), (learned, at_start, r.stderr)  # printed to 6 significant digits
    assert f"data {at_start:.6g}" in r.stderr, r.stderr
    assert "[not identified]" not in r.stderr.split("learned noise")[1].split("\n")[0]
