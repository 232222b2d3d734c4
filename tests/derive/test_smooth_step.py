"""The fused kernels of the smoother (derive/codegen/smooth_step.py) against independent computations.

* ``smooth_step_at`` (the straight-line backward step, on rows of the stored passes) against the derivation of ``lgekf.estimators.smoother``
  written here in dense numpy (np.linalg.solve), fed by the separately generated ``transition``, ``between``,
  ``right_jacobian(_inv)`` and ``retract``, at arbitrary smoothed inputs (not only the filter's own);
* ``step_store_<meas>`` (the storing forward step) against ``predict`` then ``step_<meas>`` and
  ``innovation_logdet_<meas>``;
* ``smooth_batch_soa`` (the backward pass in SIMD lanes) against ``smooth_batch``, with ragged lengths (0, 1, K).
"""

import numpy as np
import pytest

from lgekf.core.covariance import pack, unpack
from lgekf.core.registry import MODELS, get_model
from lgekf.core.rts import forward_store, smooth_stored

MODEL_NAMES = tuple(MODELS)
DT = 0.1


def _x0(spec, B):
    return np.tile(spec.kernels.common_to_state(np.array([0.0, 0.0, 0.1, 3.0, 0.0, 0.2])), (B, 1))


def _forward(spec, B=3, K=25, seed=0):
    """A stored forward pass of a turning, accelerating track with position measurements and missed detections."""
    rng = np.random.default_rng(seed)
    t = DT * np.arange(1, K + 1)
    z = np.stack([3 * t + np.sin(t), 0.2 * t**2], axis=-1)[None] + 0.3 * rng.standard_normal((B, K, 2))
    z[:, 5] = np.nan
    x0 = _x0(spec, B)
    p0 = pack(np.broadcast_to(np.eye(spec.n) * 0.25, (B, spec.n, spec.n)))
    q = np.asarray(spec.default_accel_std, dtype=float)
    return forward_store(spec, "position", np.ascontiguousarray(z), np.full((B, K), DT), x0, p0, q, np.array([0.3])), z, q


def _dense_step(k, sf, Pf, sq, Pq, ss, Ps, dt):
    """The backward step of lgekf.estimators.smoother in dense numpy."""
    F = k.transition(sf, dt)
    d = k.between(sq, ss)
    Ji = k.right_jacobian_inv(d)
    Pbar = Ji @ Ps @ Ji.T
    G = np.linalg.solve(Pq, F @ Pf).T  # P_k Fᵀ Pq⁻¹ (Pq, P_k symmetric)
    delta = G @ d
    Pt = Pf + G @ (Pbar - Pq) @ G.T
    so = sf.copy()
    k.retract(so, delta.copy())
    Phi = k.right_jacobian(delta)
    return so, Phi @ Pt @ Phi.T


@pytest.mark.parametrize("model", MODEL_NAMES)
def test_smooth_step_equals_the_dense_derivation(model):
    spec = get_model(model)
    k = spec.kernels
    fp, _, _ = _forward(spec)
    rng = np.random.default_rng(1)
    n = spec.n
    for b, i in [(0, 0), (1, 4), (1, 5), (2, 17)]:  # step 5 is a missed detection, 4 predicts into it
        sf, sq = fp.s_filt[b, i], fp.s_pred[b, i + 1]
        Pf, Pq = unpack(fp.p_filt[b, i], n), unpack(fp.p_pred[b, i + 1], n)
        # an arbitrary smoothed estimate at i+1: the prediction moved by a sizeable ε, a random SPD covariance
        ss = sq.copy()
        k.retract(ss, 0.3 * rng.standard_normal(n))
        A = rng.standard_normal((n, n))
        Ps = 0.5 * Pq + 0.05 * A @ A.T
        # smooth_step_at on rows 0 (k) and 1 (k + 1) of two-row arrays: writes the smoothed row 0
        S_sm, P_sm = np.stack([np.empty_like(sf), ss]), np.stack([np.empty(spec.n_packed), pack(Ps)])
        k.smooth_step_at(np.stack([sf, sf]), np.stack([fp.p_filt[b, i]] * 2), np.stack([sq, sq]),
                         np.stack([fp.p_pred[b, i + 1]] * 2), S_sm, P_sm, 0, DT)
        so, po = S_sm[0], P_sm[0]
        so_ref, Po_ref = _dense_step(k, sf, Pf, sq, Pq, ss, Ps, DT)
        assert np.allclose(k.state_to_physical(so), k.state_to_physical(so_ref), rtol=1e-11, atol=1e-12)
        assert np.allclose(unpack(po, n), Po_ref, rtol=1e-11, atol=1e-12 * np.abs(Po_ref).max())
        # the step is not the identity on these inputs (the check above could not pass by copying)
        assert np.abs(unpack(po, n) - Pf).max() > 1e-4 * np.abs(Pf).max()


@pytest.mark.parametrize("model", MODEL_NAMES)
def test_store_step_is_predict_then_the_fused_step(model):
    spec = get_model(model)
    k = spec.kernels
    fp, z, q = _forward(spec)
    n, r = spec.n, 0.3
    for b, i in [(0, 3), (2, 20)]:
        s, p = fp.s_filt[b, i].copy(), fp.p_filt[b, i].copy()
        sq, pq = np.empty_like(s), np.empty_like(p)
        s1, p1 = s.copy(), p.copy()
        nis, logdet = k.step_store_position(s, p, DT, *q, z[b, i + 1, 0], z[b, i + 1, 1], r, sq, pq)
        nis1 = k.step_position(s1, p1, DT, *q, z[b, i + 1, 0], z[b, i + 1, 1], r)
        assert np.allclose(s, s1, rtol=1e-13, atol=1e-14) and np.allclose(p, p1, rtol=1e-13, atol=1e-14 * np.abs(p1).max())
        assert nis == pytest.approx(nis1, rel=1e-12)
        s2, p2 = fp.s_filt[b, i].copy(), fp.p_filt[b, i].copy()
        k.predict(s2, p2, DT, *q)
        assert np.allclose(sq, s2, rtol=1e-13, atol=1e-14) and np.allclose(pq, p2, rtol=1e-13, atol=1e-14 * np.abs(p2).max())
        assert logdet == pytest.approx(k.innovation_logdet_position(s2, p2, r), rel=1e-12, abs=1e-12)
        assert np.allclose(unpack(pq, n), unpack(pq, n).T)


def test_simd_backward_equals_scalar_backward():
    """smooth_batch_soa on 70 trajectories (two blocks of lanes, a partial one) of ragged lengths, CV (the cheapest
    compile, ~5 s; the SIMD kernels of the other models were compared the same way when written, to ≤ 5e-15)."""
    spec = get_model("cv")
    fp, z, q = _forward(spec, B=70, K=30)
    fs = forward_store(spec, "position", np.ascontiguousarray(z), np.full((70, 30), DT), _x0(spec, 70),
                       pack(np.broadcast_to(np.eye(spec.n) * 0.25, (70, spec.n, spec.n))), q, np.array([0.3]), simd=True)
    fp.lengths = np.random.default_rng(2).integers(2, 31, 70)
    fp.lengths[:3] = [0, 1, 30]
    fs.lengths = fp.lengths
    xa, sa, pa = smooth_stored(spec, fp)
    xb, sb, pb = smooth_stored(spec, fs)
    assert np.array_equal(np.isnan(xa), np.isnan(xb))
    assert np.isnan(xa[0]).all() and not np.isnan(xa[1, 0]).any() and np.isnan(xa[1, 1:]).all()
    for b in range(70):
        L = fp.lengths[b]
        assert np.allclose(xb[b, :L], xa[b, :L], rtol=1e-12, atol=1e-12)
        assert np.allclose(pb[b, :L], pa[b, :L], rtol=1e-12, atol=1e-12 * np.abs(pa[b, :L]).max(initial=1.0))
    # the trajectory of length 1 is its filtered estimate; a long one is smoothed (differs from the filter)
    assert np.allclose(xb[1, 0], fp.x_filt[1, 0])
    assert np.abs(xb[2, :10] - fp.x_filt[2, :10]).max() > 1e-3


def test_simd_forward_pass_equals_scalar_forward_pass():
    """run_batch_store_soa_position against run_batch_store_position: 70 trajectories (a partial block of lanes),
    missed detections (scalar fallback lanes), CV (the cheapest compile)."""
    spec = get_model("cv")
    rng = np.random.default_rng(3)
    B, K = 70, 30
    t = DT * np.arange(1, K + 1)
    z = np.stack([3 * t + np.sin(t), 0.2 * t**2], axis=-1)[None] + 0.3 * rng.standard_normal((B, K, 2))
    z[:, 4] = np.nan
    z[7, 10:14] = np.nan
    z = np.ascontiguousarray(z)
    x0 = _x0(spec, B)
    p0 = pack(np.broadcast_to(np.eye(spec.n) * 0.25, (B, spec.n, spec.n)))
    q = np.asarray(spec.default_accel_std, dtype=float)
    a = forward_store(spec, "position", z, np.full((B, K), DT), x0, p0, q, np.array([0.3]), simd=False)
    b = forward_store(spec, "position", z, np.full((B, K), DT), x0, p0, q, np.array([0.3]), simd=True)
    assert b.s_filt is None and b.blocks is not None  # kept in blocks of lanes
    for name, u, v in zip(("s_pred", "p_pred", "s_filt", "p_filt", "x_filt", "nis", "logdet"), (*a.states(), a.x_filt, a.nis, a.logdet),
                          (*b.states(), b.x_filt, b.nis, b.logdet)):
        assert np.array_equal(np.isnan(u), np.isnan(v)), name
        assert u.shape == v.shape and np.allclose(v, u, rtol=1e-12, atol=1e-12, equal_nan=True), name
    assert np.isnan(a.nis[:, 4]).all() and np.isfinite(a.nis[:, 5]).all()
