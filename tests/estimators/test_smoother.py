"""The RTS smoother on the group (lgekf.estimators.smoother) for every registry model.

* against an independent batch solution: the Gauss–Newton MAP of the whole trajectory, written here in
  dense numpy over the initial state and the noise sequence (exact motion through the generated
  ``propagate``, finite-difference Jacobians), to which the smoother's mean must converge as the noise
  shrinks;
* against Monte Carlo truth of the model's own motion: smoothed NEES close to n, smoothed RMSE below the
  filter's;
* missed detections, the class API (record=True, smooth()) against filter_batch(smooth=True).
"""

import numpy as np
import pytest

from lgekf import filter_batch, make_filter
from lgekf.core.registry import MODELS, get_model

MODEL_NAMES = tuple(MODELS)
DT = 0.1


def _initial(spec):
    """A moving, turning initial physical state of any model (from common coordinates)."""
    return np.asarray(spec.kernels.common_to_state(np.array([1.0, -2.0, 0.3, 3.0, 0.0, 0.4])))


def _simulate(spec, B, K, q, r, P0, rng):
    """B trajectories of the model's own exact motion, position measurements, initial estimates drawn from P0."""
    x_true0 = np.tile(_initial(spec), (B, 1))
    stds = np.asarray(q)[list(spec.noise_inputs)]
    noise = np.ascontiguousarray(rng.standard_normal((B, K, len(stds))) * stds)
    X = np.empty((B, K + 1, spec.n))
    spec.kernels.simulate_batch(x_true0, np.full((B, K), DT), noise, X)
    z = np.empty((B * K, 2))
    spec.kernels.measure_batch_position(np.ascontiguousarray(X[:, 1:].reshape(-1, spec.n)),
                                        np.ascontiguousarray(r * rng.standard_normal((B * K, 2))), z)
    # the estimate at time 0: truth·exp(ε), ε ~ N(0, P0)
    L = np.linalg.cholesky(P0)
    x0 = np.empty((B, spec.n))
    for b in range(B):
        s = spec.kernels.state_from_physical(X[b, 0])
        spec.kernels.retract(s, L @ rng.standard_normal(spec.n))
        x0[b] = spec.kernels.state_to_physical(s)
    return X, z.reshape(B, K, 2), x0


def _p0(spec, scale=1.0):
    sd = np.array([0.3 if i in spec.angles else 0.5 for i in range(spec.n)]) * scale
    return np.diag(sd**2)


# --------------------------------------------------------------------------- the batch MAP, independently
def _map_trajectory(spec, z, x0, P0, q, r, iters=30):
    """Gauss–Newton MAP over (ξ, n_0..n_{K-1}): X_{-1} = μ0·exp(ξ), X_k = X_{k-1}·exp(Ω(X_{k-1}) + G n_k)
    (the generated exact motion ``propagate``), cost |L0⁻¹ξ|² + Σ|n_k/σ|² + Σ|(z_k − pos(X_k))/r|².
    Returns the internal states X_0 .. X_{K-1}."""
    k = spec.kernels
    K = z.shape[0]
    stds = np.asarray(q)[list(spec.noise_inputs)]
    nq = len(stds)
    n = spec.n
    Li = np.linalg.inv(np.linalg.cholesky(P0))
    s0 = k.state_from_physical(x0)

    def states(v):
        s = s0.copy()
        k.retract(s, v[:n].copy())
        out = []
        for j in range(K):
            k.propagate(s, DT, *v[n + j * nq:n + (j + 1) * nq])
            out.append(s.copy())
        return out

    def residual(v):
        ss = states(v)
        res = [Li @ v[:n], v[n:] / np.tile(stds, K)]
        res += [(z[j] - ss[j][:2]) / r for j in range(K)]
        return np.concatenate(res)

    v = np.zeros(n + K * nq)
    for _ in range(iters):
        r0 = residual(v)
        J = np.empty((r0.size, v.size))
        h = 1e-7
        for i in range(v.size):
            e = np.zeros(v.size)
            e[i] = h
            J[:, i] = (residual(v + e) - residual(v - e)) / (2 * h)
        step = np.linalg.lstsq(J, -r0, rcond=None)[0]
        v = v + step
        if np.max(np.abs(step)) < 1e-10:
            break
    return np.array(states(v))


@pytest.mark.parametrize("model", MODEL_NAMES)
def test_smoother_mean_converges_to_the_batch_map(model):
    """The position of every state reads (x, y) from the internal state's first two entries in every model."""
    spec = get_model(model)
    assert spec.internal_names[:2] == ("x", "y")
    rng = np.random.default_rng(7)
    K = 20
    gaps = []
    for scale in (1.0, 0.01):
        q = np.asarray(spec.default_accel_std) * scale
        r = 0.3 * scale
        P0 = _p0(spec, scale)
        _, z, x0 = _simulate(spec, 1, K, q, r, P0, rng)
        xf, Pf, xs, Ps = filter_batch(model, z, dt=DT, accel_std=q, meas_std=r, x0=x0, P0=P0, return_cov=True, smooth=True)
        s_map = _map_trajectory(spec, z[0], x0[0], P0, q, r)
        k = spec.kernels
        def gap(x, P):
            worst = 0.0
            for j in range(K):
                e = k.between(k.state_from_physical(x[j]), s_map[j])
                worst = max(worst, float(np.max(np.abs(e) / np.sqrt(np.diag(P[j])))))
            return worst
        gaps.append((gap(xs[0], Ps[0]), gap(xf[0], Pf[0])))
    (sm_big, f_big), (sm_small, f_small) = gaps
    # the smoother is far closer to the MAP than the filter (which misses the future measurements), and its
    # gap, in units of its own std, shrinks with the noise like the linearisation error (measured: 0.23-0.49 σ
    # at scale 1, 0.005-0.007 σ at scale 0.01 for the nonlinear models; 0 for the linear CV)
    assert sm_small < 0.02, gaps
    assert f_small > 0.2, gaps
    assert sm_small < 0.1 * sm_big or sm_big < 1e-6, gaps


@pytest.mark.slow
@pytest.mark.parametrize("model", MODEL_NAMES)
def test_smoothed_nees_and_rmse_monte_carlo(model):
    spec = get_model(model)
    rng = np.random.default_rng(11)
    B, K = 300, 40
    q = np.asarray(spec.default_accel_std)
    P0 = _p0(spec, 0.3)  # an initial error the filters linearise well (at 1.0 SE(2)×SE(2)'s own NEES is 9.1 for n = 6)
    X, z, x0 = _simulate(spec, B, K, q, 0.3, P0, rng)
    xf, Pf, xs, Ps = filter_batch(model, z, dt=DT, accel_std=q, meas_std=0.3, x0=x0, P0=P0, return_cov=True, smooth=True)
    k = spec.kernels
    nees_s = np.empty((B, K))
    nees_f = np.empty((B, K))
    for b in range(B):
        for j in range(K):
            t = k.state_from_physical(X[b, j + 1])
            for out, x, P in ((nees_s, xs, Ps), (nees_f, xf, Pf)):
                e = k.between(k.state_from_physical(x[b, j]), t)
                out[b, j] = e @ np.linalg.solve(P[b, j], e)
    n = spec.n
    # mean NEES over B·K samples; a consistent estimator gives n. Measured (smoothed / filtered): CTRV 5.32 / 5.16
    # (n 5), CV 3.98 / 4.05 (4), SE(2)×R² 5.16 / 5.05 (5), SE(2)×R³ 6.24 / 6.27 (6), SE(2)×SE(2) 6.64 / 6.58 (6)
    assert 0.85 * n < nees_s.mean() < 1.15 * n, (nees_s.mean(), nees_f.mean())
    assert abs(nees_s.mean() - nees_f.mean()) < 0.05 * n, (nees_s.mean(), nees_f.mean())
    rmse_s = np.sqrt(np.mean(np.sum((xs[..., :2] - X[:, 1:, :2]) ** 2, axis=-1)))
    rmse_f = np.sqrt(np.mean(np.sum((xf[..., :2] - X[:, 1:, :2]) ** 2, axis=-1)))
    assert rmse_s < 0.75 * rmse_f, (rmse_s, rmse_f)  # measured 0.55-0.60


@pytest.mark.parametrize("model", MODEL_NAMES)
def test_missed_detections_and_class_api(model):
    spec = get_model(model)
    rng = np.random.default_rng(3)
    K = 15
    q = np.asarray(spec.default_accel_std)
    P0 = _p0(spec)
    _, z, x0 = _simulate(spec, 2, K, q, 0.3, P0, rng)
    z[:, [4, 5, 11]] = np.nan
    xf, xs = filter_batch(model, z, dt=DT, accel_std=q, meas_std=0.3, x0=x0, P0=P0, smooth=True)
    assert np.all(np.isfinite(xs))
    # the last step is the filter's; the plain filter gives the same filtered states
    np.testing.assert_allclose(xs[:, -1], xf[:, -1], rtol=0, atol=1e-12)
    np.testing.assert_allclose(xf, filter_batch(model, z, dt=DT, accel_std=q, meas_std=0.3, x0=x0, P0=P0), rtol=0, atol=1e-12)
    f = make_filter(model, dt=DT, accel_std=q, meas_std=0.3, x0=x0[1], P0=P0, record=True)
    for j in range(K):
        f.predict()
        if not np.isnan(z[1, j, 0]):
            f.update(z[1, j])
    xc, Pc = f.smooth()
    np.testing.assert_allclose(xc, xs[1], rtol=0, atol=1e-10)
    _, _, _, Pb = filter_batch(model, z, dt=DT, accel_std=q, meas_std=0.3, x0=x0, P0=P0, smooth=True, return_cov=True)
    np.testing.assert_allclose(Pc, Pb[1], rtol=0, atol=1e-10)
    assert np.all(np.linalg.eigvalsh(Pc) > 0)


def test_smooth_needs_record():
    f = make_filter("cv", dt=0.1, accel_std=0.5, meas_std=0.3, x0=[0, 0, 1, 0], P0=np.eye(4))
    f.predict()
    with pytest.raises(ValueError, match="record=True"):
        f.smooth()


@pytest.mark.parametrize("model", [m for m in MODEL_NAMES if "pose" in get_model(m).measurements])
def test_pose_measurements_smooth_and_class_agrees(model):
    spec = get_model(model)
    rng = np.random.default_rng(4)
    K = 12
    q = np.asarray(spec.default_accel_std)
    P0 = _p0(spec, 0.3)
    X, _, x0 = _simulate(spec, 1, K, q, 0.3, P0, rng)
    z = np.empty((K, 3))
    spec.kernels.measure_batch_pose(np.ascontiguousarray(X[0, 1:]), np.ascontiguousarray(rng.standard_normal((K, 3)) * [0.3, 0.3, 0.05]), z)
    r = (0.3, 0.3, 0.05)
    xf, _, xs, Ps = filter_batch(model, z[None], dt=DT, accel_std=q, meas_std=r, x0=x0, P0=P0, measurement="pose", smooth=True,
                                 return_cov=True)
    f = make_filter(model, dt=DT, accel_std=q, meas_std=r, x0=x0[0], P0=P0, measurement="pose", record=True)
    for j in range(K):
        f.predict()
        f.update(z[j])
    xc, Pc = f.smooth()
    np.testing.assert_allclose(xc, xs[0], rtol=0, atol=1e-10)
    np.testing.assert_allclose(Pc, Ps[0], rtol=0, atol=1e-10)
    assert np.all(np.isfinite(xs)) and not np.allclose(xs[0, :-1], xf[0, :-1])
