"""filter_batch against the single-filter classes, and argument validation of both."""

from __future__ import annotations

import re

import numpy as np
import pytest

from lgekf import CTRVFilter, CVFilter, SE2R3Filter, SE2SE2Filter, filter_batch, make_filter

CLASSES = {"se2se2": SE2SE2Filter, "se2r3": SE2R3Filter, "ctrv": CTRVFilter, "cv": CVFilter}
N = {"se2se2": 6, "se2r3": 6, "ctrv": 5, "cv": 4}
Q = {"se2se2": (0.4, 0.3, 0.5), "se2r3": (0.4, 0.3, 0.5), "ctrv": (0.6, 0.4), "cv": 0.7}
MODELS = list(CLASSES)
B, K = 5, 40
RTOL = 1e-10  # batch (fused step kernel) against the classes (predict, update): see test_batch_matches_classes


def random_problem(model, seed):
    rng = np.random.RandomState(seed)
    n = N[model]
    x0 = rng.randn(B, n)
    x0[:, :2] *= 5
    if model in ("se2se2", "se2r3", "ctrv"):
        x0[:, 2] = rng.uniform(-np.pi, np.pi, B)
        x0[:, -1] = rng.uniform(-1, 1, B)  # turn rate
    if model in ("se2se2", "se2r3"):
        x0[:, 3] = rng.uniform(1, 5, B)
    if model == "ctrv":
        x0[:, 3] = rng.uniform(1, 5, B)
    A = rng.randn(B, n, n)
    P0 = A @ np.swapaxes(A, 1, 2) / n + 0.2 * np.eye(n)
    z = x0[:, None, :2] + np.cumsum(rng.randn(B, K, 2) * 0.8, axis=1)
    return rng, x0, P0, z


def run_classes(model, z, dts, x0, P0, r):
    """States, covariances and NIS of the filter classes, step by step."""
    n = N[model]
    xs = np.empty((B, K, n))
    Ps = np.empty((B, K, n, n))
    nis = np.empty((B, K))
    for b in range(B):
        f = CLASSES[model](dt=1.0, accel_std=Q[model], meas_std=r, x0=x0[b], P0=P0[b] if P0.ndim == 3 else P0)
        for k in range(K):
            f.predict(dt=dts[b, k])
            nis[b, k] = f.update(z[b, k])
            xs[b, k] = f.x
            Ps[b, k] = f.P
    return xs, Ps, nis


def _rel(a, b):
    return float(np.max(np.abs(a - b)) / max(1e-300, np.max(np.abs(b))))


@pytest.mark.parametrize("dt_form", ["K", "BK", "scalar"])
@pytest.mark.parametrize("model", MODELS)
def test_batch_matches_classes(model, dt_form):
    rng, x0, P0, z = random_problem(model, seed=MODELS.index(model) * 10 + ["K", "BK", "scalar"].index(dt_form))
    r = 0.6
    if dt_form == "K":
        dt_arg = rng.uniform(0.05, 0.8, K)
        dts = np.broadcast_to(dt_arg, (B, K))
    elif dt_form == "BK":
        dt_arg = rng.uniform(0.05, 0.8, (B, K))
        dts = dt_arg
    else:
        dt_arg = 0.3
        dts = np.full((B, K), 0.3)
    xs, Ps, nis = filter_batch(model, z, dt=dt_arg, accel_std=Q[model], meas_std=r, x0=x0, P0=P0, return_cov=True, return_nis=True)
    assert xs.shape == (B, K, N[model]) and Ps.shape == (B, K, N[model], N[model]) and nis.shape == (B, K)
    xr, Pr, nisr = run_classes(model, z, dts, x0, P0, r)
    # the batch loop runs the fused step_position (predict and update in one kernel), the classes predict and
    # update: the same algebra, compiled separately, so they differ by rounding (~1e-16 a step) that these random,
    # strongly nonlinear 40-step problems amplify to ~1e-12
    assert _rel(xs, xr) < RTOL
    assert _rel(Ps, Pr) < RTOL
    assert _rel(nis, nisr) < RTOL
    # the optional outputs do not change the states
    np.testing.assert_array_equal(filter_batch(model, z, dt=dt_arg, accel_std=Q[model], meas_std=r, x0=x0, P0=P0), xs)


@pytest.mark.parametrize("model", MODELS)
def test_batch_shared_P0_and_output_forms(model):
    _, x0, P0, z = random_problem(model, seed=99)
    P = P0[0]
    xs, Ps = filter_batch(model, z, dt=0.2, accel_std=Q[model], meas_std=0.5, x0=x0, P0=P, return_cov=True)
    xs2, nis = filter_batch(model, z, dt=0.2, accel_std=Q[model], meas_std=0.5, x0=x0, P0=np.broadcast_to(P, (B,) + P.shape), return_nis=True)
    np.testing.assert_array_equal(xs, xs2)
    assert nis.shape == (B, K) and np.all(nis >= 0)
    xr, Pr, _ = run_classes(model, z, np.full((B, K), 0.2), x0, P, 0.5)
    assert _rel(xs, xr) < RTOL and _rel(Ps, Pr) < RTOL
    # inputs are not modified
    z_copy, x0_copy = z.copy(), x0.copy()
    filter_batch(model, z, dt=0.2, accel_std=Q[model], meas_std=0.5, x0=x0, P0=P)
    np.testing.assert_array_equal(z, z_copy)
    np.testing.assert_array_equal(x0, x0_copy)


def test_make_filter():
    f = make_filter("cv", dt=0.1, accel_std=1.0, meas_std=0.5, x0=np.zeros(4), P0=np.eye(4))
    assert isinstance(f, CVFilter)
    with pytest.raises(ValueError, match=r"\bmodel\b"):
        make_filter("ekf", dt=0.1, accel_std=1.0, meas_std=0.5, x0=np.zeros(4), P0=np.eye(4))


# ---------------------------------------------------------------------------------------------
# Validation: ValueError whose message names the offending argument
# ---------------------------------------------------------------------------------------------


def names(arg):
    return pytest.raises(ValueError, match=rf"(?<![A-Za-z0-9_]){re.escape(arg)}(?![A-Za-z0-9_])")


def good_args(model):
    _, x0, P0, z = random_problem(model, seed=5)
    return dict(z=z, dt=0.1, accel_std=Q[model], meas_std=0.5, x0=x0, P0=P0)


def call(model, **override):
    kw = good_args(model)
    kw.update(override)
    z = kw.pop("z")
    return filter_batch(model, z, **kw)


def _bad_spd(n, kind):
    P = np.eye(n)
    if kind == "negative":
        P[1, 1] = -0.5
    elif kind == "singular":
        P[1, 1] = 0.0
    elif kind == "asymmetric":
        P[0, 1] = 0.3
    elif kind == "nan":
        P[0, 0] = np.nan
    elif kind == "indefinite":
        P[0, 1] = P[1, 0] = 2.0
    return P


BATCH_BAD = [
    # (argument name, override builder(model) -> dict)
    ("z", lambda m: dict(z=np.zeros((B, K)))),
    ("z", lambda m: dict(z=np.zeros((B, K, 3)))),
    ("z", lambda m: dict(z=np.zeros((K, 2)))),
    ("z", lambda m: dict(z=np.full((B, K, 2), np.inf))),
    ("z", lambda m: dict(z="positions")),
    ("x0", lambda m: dict(x0=np.zeros((B + 1, N[m])))),
    ("x0", lambda m: dict(x0=np.zeros((B, N[m] + 1)))),
    ("x0", lambda m: dict(x0=np.zeros(N[m]))),
    ("x0", lambda m: dict(x0=np.full((B, N[m]), np.nan))),
    ("P0", lambda m: dict(P0=np.eye(N[m] + 1))),
    ("P0", lambda m: dict(P0=np.zeros((B, N[m], N[m] + 1)))),
    # a per-trajectory P0 for the wrong number of trajectories (numpy's broadcast error must not leak)
    ("P0", lambda m: dict(P0=np.broadcast_to(np.eye(N[m]), (B + 2, N[m], N[m])).copy())),
    ("P0", lambda m: dict(P0=np.eye(N[m])[None, None])),
    ("P0", lambda m: dict(P0=_bad_spd(N[m], "negative"))),
    ("P0", lambda m: dict(P0=_bad_spd(N[m], "singular"))),
    ("P0", lambda m: dict(P0=_bad_spd(N[m], "asymmetric"))),
    ("P0", lambda m: dict(P0=_bad_spd(N[m], "nan"))),
    ("P0", lambda m: dict(P0=_bad_spd(N[m], "indefinite"))),
    ("P0", lambda m: dict(P0=np.stack([np.eye(N[m])] * (B - 1) + [_bad_spd(N[m], "negative")]))),
    ("dt", lambda m: dict(dt=0.0)),
    ("dt", lambda m: dict(dt=-0.1)),
    ("dt", lambda m: dict(dt=np.nan)),
    ("dt", lambda m: dict(dt=np.r_[np.full(K - 1, 0.1), 0.0])),
    ("dt", lambda m: dict(dt=np.full((B, K), -1.0))),
    ("dt", lambda m: dict(dt=np.full(K + 1, 0.1))),
    ("dt", lambda m: dict(dt=np.full((B + 1, K), 0.1))),
    ("dt", lambda m: dict(dt=np.full((B, K, 1), 0.1))),
    ("meas_std", lambda m: dict(meas_std=-0.5)),
    ("meas_std", lambda m: dict(meas_std=0.0)),
    ("meas_std", lambda m: dict(meas_std=np.nan)),
    ("meas_std", lambda m: dict(meas_std=[0.5, 0.5])),
    ("accel_std", lambda m: dict(accel_std=-np.abs(np.atleast_1d(Q[m])))),
    ("accel_std", lambda m: dict(accel_std=np.r_[np.atleast_1d(Q[m]), 1.0])),
    ("accel_std", lambda m: dict(accel_std=np.full(np.size(Q[m]), np.nan))),
]


@pytest.mark.parametrize("case", range(len(BATCH_BAD)), ids=[f"{a}-{i}" for i, (a, _) in enumerate(BATCH_BAD)])
@pytest.mark.parametrize("model", MODELS)
def test_batch_validation(model, case):
    arg, build = BATCH_BAD[case]
    with names(arg):
        call(model, **build(model))


@pytest.mark.parametrize("bad", ["ekf", "SE2SE2", "", None, 3, ["cv"]])
def test_batch_unknown_model(bad):
    kw = good_args("cv")
    z = kw.pop("z")
    with names("model"):
        filter_batch(bad, z, **kw)


def test_batch_zero_accel_std_is_allowed():
    call("cv", accel_std=0.0)
    call("se2se2", accel_std=(0.0, 0.0, 0.0))


CTOR_BAD = [
    ("dt", lambda m: dict(dt=0.0)),
    ("dt", lambda m: dict(dt=-1.0)),
    ("dt", lambda m: dict(dt=np.nan)),
    ("dt", lambda m: dict(dt=[0.1, 0.2])),
    ("accel_std", lambda m: dict(accel_std=-np.abs(np.atleast_1d(Q[m])))),
    ("accel_std", lambda m: dict(accel_std=np.r_[np.atleast_1d(Q[m]), 1.0])),
    ("accel_std", lambda m: dict(accel_std=np.full(np.size(Q[m]), np.inf))),
    ("meas_std", lambda m: dict(meas_std=-1.0)),
    ("meas_std", lambda m: dict(meas_std=0.0)),
    ("meas_std", lambda m: dict(meas_std="big")),
    ("x0", lambda m: dict(x0=np.zeros(N[m] + 1))),
    ("x0", lambda m: dict(x0=np.zeros((1, N[m])))),
    ("x0", lambda m: dict(x0=np.r_[np.nan, np.zeros(N[m] - 1)])),
    ("P0", lambda m: dict(P0=np.eye(N[m] + 1))),
    ("P0", lambda m: dict(P0=np.eye(N[m])[None])),
    ("P0", lambda m: dict(P0=_bad_spd(N[m], "negative"))),
    ("P0", lambda m: dict(P0=_bad_spd(N[m], "singular"))),
    ("P0", lambda m: dict(P0=_bad_spd(N[m], "asymmetric"))),
    ("P0", lambda m: dict(P0=_bad_spd(N[m], "nan"))),
    ("P0", lambda m: dict(P0=_bad_spd(N[m], "indefinite"))),
]


def ctor_args(model):
    return dict(dt=0.1, accel_std=Q[model], meas_std=0.5, x0=np.r_[1.0, 2.0, np.full(N[model] - 2, 0.3)], P0=np.eye(N[model]))


@pytest.mark.parametrize("case", range(len(CTOR_BAD)), ids=[f"{a}-{i}" for i, (a, _) in enumerate(CTOR_BAD)])
@pytest.mark.parametrize("model", MODELS)
def test_constructor_validation(model, case):
    arg, build = CTOR_BAD[case]
    kw = ctor_args(model)
    kw.update(build(model))
    with names(arg):
        CLASSES[model](**kw)


@pytest.mark.parametrize("model", MODELS)
def test_predict_update_validation_leaves_state_unchanged(model):
    f = CLASSES[model](**ctor_args(model))
    f.predict()
    f.update([1.1, 2.2])
    x, P, nis = f.x, f.P, f.nis
    for bad in (-1.0, 0.0, np.nan, np.inf, [0.1, 0.1], "soon"):
        with names("dt"):
            f.predict(dt=bad)
    for bad in ([np.nan, 1.0], [1.0, np.inf], [1.0, 2.0, 3.0], 1.0, [[1.0, 2.0]], "here"):
        with names("z"):
            f.update(bad)
    np.testing.assert_array_equal(f.x, x)
    np.testing.assert_array_equal(f.P, P)
    assert f.nis == nis
    # and the filter still works
    f.predict(dt=0.05)
    f.update(np.array([1.0, 2.0]))
    assert np.all(np.isfinite(f.P))


@pytest.mark.parametrize("model", ["se2se2", "ctrv", "cv"])
def test_nan_measurement_row_is_a_missed_detection(model):
    """A NaN row of z predicts only: the same as the class API calling predict() without update()."""
    kw = good_args(model)
    z = np.array(kw["z"], dtype=float)
    z[:, 3] = np.nan
    z[0, 5, 1] = np.nan  # one NaN entry makes the whole row a miss
    kw = {k: v for k, v in kw.items() if k != "z"}
    est, cov, nis = filter_batch(model, z, return_cov=True, return_nis=True, **kw)
    assert np.all(np.isnan(nis[:, 3])) and np.isnan(nis[0, 5]) and np.all(np.isfinite(nis[:, :3]))
    P0 = kw["P0"] if np.ndim(kw["P0"]) == 2 else kw["P0"][0]
    f = make_filter(model, dt=0.1, accel_std=kw["accel_std"], meas_std=kw["meas_std"], x0=kw["x0"][0], P0=P0)
    for k in range(z.shape[1]):
        f.predict(float(np.broadcast_to(kw["dt"], z.shape[:2])[0, k]))
        if not np.any(np.isnan(z[0, k])):
            f.update(z[0, k])
        np.testing.assert_allclose(est[0, k], f.x, rtol=1e-12, atol=1e-12)
        np.testing.assert_allclose(cov[0, k], f.P, rtol=1e-12, atol=1e-14)
