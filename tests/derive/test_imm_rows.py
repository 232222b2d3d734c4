"""The IMM's row variants (derive/codegen/imm_rows.py) and its fused step path (lgekf.estimators.imm.kernels).

* every ``<kernel>_at`` equals its original kernel exactly when its arguments are rows of one workspace, and
  ``step_ll_<meas>`` equals ``step_try_<meas>`` with 1/det S equal to ``innovation_logdet_<meas>`` at the predicted
  state, for every registry model (the same generated arithmetic: only where the numbers are stored differs);
* ``imm_step`` (mixing + each mode's fused step) equals ``imm_predict`` then ``imm_update`` (the separate
  prediction, log det S and Joseph-form update) to rounding over a run with missed detections, and keeps the
  conventions of its return value (the step log-likelihood; NaN for a missed detection).
"""

from __future__ import annotations

import numpy as np
import pytest

from lgekf.core.covariance import pack
from lgekf.core.registry import MODELS, get_model


def _spd(n, rng):
    A = rng.normal(size=(n, n))
    return A @ A.T + 0.1 * np.eye(n)


def _state(spec, rng):
    x = rng.normal(size=len(spec.state_names))
    x[3] = 2.0 + abs(x[3])  # away from speed 0
    return spec.kernels.state_from_physical(x)


@pytest.mark.parametrize("model", list(MODELS))
def test_row_variants_equal_the_kernels(model):
    spec = get_model(model)
    k = spec.kernels
    n, L, npk = spec.n, len(spec.internal_names), spec.n_packed
    rng = np.random.default_rng(11)
    for _ in range(3):
        s, t = _state(spec, rng), _state(spec, rng)
        pt = pack(_spd(n, rng))
        acc = pack(_spd(n, rng))
        w = 0.37
        ws = np.zeros((8, 40))  # rows: 0 s, 1 t, 2 pt, 3 acc, 4 c, 5 Pc (row-major), 6 out s, 7 out p
        ws[0, :L], ws[1, :L], ws[2, :npk], ws[3, :npk] = s, t, pt, acc
        want = acc.copy()
        k.mix_transport(s, t, pt, w, want)
        k.mix_transport_at(ws, 0, 1, 2, w, 3)
        np.testing.assert_array_equal(ws[3, :npk], want)
        want = acc[:n].copy()
        ws[3, :npk] = acc
        k.between_add(s, t, w, want)
        k.between_add_at(ws, 0, 1, w, 3)
        np.testing.assert_array_equal(ws[3, :n], want)
        want = s.copy()
        k.retract(want, acc[:n])
        ws[3, :npk] = acc
        k.retract_at(ws, 0, 3)
        np.testing.assert_array_equal(ws[0, :L], want)
        ws[0, :L] = s
        c, Pc = np.empty(6), np.empty((6, 6))
        k.common_of_state(s, pt, c, Pc)
        k.common_of_state_at(ws, 0, 2, 4, 5)
        np.testing.assert_array_equal(ws[4, :6], c)
        np.testing.assert_array_equal(ws[5, :36], Pc.ravel())
        s_out, p_out = np.empty(L), np.empty(npk)
        Pc_in = _spd(6, rng)
        ws[5, :36] = Pc_in.ravel()
        k.state_of_common(c, Pc_in, s_out, p_out)
        k.state_of_common_at(ws, 4, 5, 6, 7)
        np.testing.assert_array_equal(ws[6, :L], s_out)
        np.testing.assert_array_equal(ws[7, :npk], p_out)


@pytest.mark.parametrize("model", list(MODELS))
@pytest.mark.parametrize("meas", ["position", "pose"])
def test_step_ll_is_the_fused_step_with_its_innovation_determinant(model, meas):
    spec = get_model(model)
    k = spec.kernels
    if not hasattr(k, f"step_ll_{meas}"):
        pytest.skip(f"{model} has no {meas} measurement")
    n, L, npk = spec.n, len(spec.internal_names), spec.n_packed
    q = [0.7, 0.2, 0.4][: len(spec.noise_names)]
    r = [0.5, 0.5, 0.05] if meas == "pose" else [0.5]
    rng = np.random.default_rng(5)
    for _ in range(4):
        s, p = _state(spec, rng), pack(_spd(n, rng))
        x = k.state_to_physical(s)
        z = list(x[:2] + rng.normal(size=2)) + ([float(x[2]) + 0.1] if meas == "pose" else [])
        s1, p1 = s.copy(), p.copy()
        want = getattr(k, f"step_try_{meas}")(s1, p1, 0.1, *q, *z, *r)
        ws = np.zeros((2, 40))
        ws[0, :L], ws[1, :npk] = s, p
        nis, rdet = getattr(k, f"step_ll_{meas}")(ws, 0, 1, 0.1, *q, *z, *r)
        assert nis == want
        np.testing.assert_array_equal(ws[0, :L], s1)
        np.testing.assert_array_equal(ws[1, :npk], p1)
        s2, p2 = s.copy(), p.copy()  # log det S at the predicted state, computed separately
        k.predict(s2, p2, 0.1, *q)
        logdet = getattr(k, f"innovation_logdet_{meas}")(s2, p2, *r)
        np.testing.assert_allclose(-np.log(rdet), logdet, rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("case,meas", [("se2r3:calm,se2r3:manoeuvre", "position"), ("cv,ctrv,se2r3", "position"),
                                       ("se2se2:calm,se2se2:manoeuvre", "pose")])
def test_imm_step_equals_predict_then_update(case, meas):
    from lgekf.estimators.imm.estimator import _common_inputs, _Setup
    from lgekf.estimators.imm.kernels import imm_predict, imm_step, imm_update, workspace

    r = [0.5, 0.5, 0.05] if meas == "pose" else 0.5
    s = _Setup(case, None, r, meas, None)
    c0 = np.array([[0.0, 0.0, 0.2, 3.0, 0.0, 0.1]])
    c, Pc = _common_inputs(c0, np.diag([0.25, 0.25, 0.01, 0.25, 0.25, 0.01]))
    S0, P0 = s.initial(c, Pc)
    m = 3 if meas == "pose" else 2
    A = (S0[0].copy(), P0[0].copy(), s.mu0.copy())
    B = (S0[0].copy(), P0[0].copy(), s.mu0.copy())
    wa, wb = workspace(s.M), workspace(s.M)
    nis_a, nis_b = np.empty(s.M), np.empty(s.M)
    rng = np.random.default_rng(2)
    for k in range(60):
        t = 0.1 * (k + 1)
        z = np.array([3 * t, 0.3 * t * t] + ([0.2 * t] if meas == "pose" else [])) + 0.3 * rng.normal(size=m)
        if k in (7, 30, 31):
            z[0] = np.nan
        ll_a = imm_step(s.models, *A, s.PI, s.Q, s.r, z, 0.1, s.same_group, s.meas, nis_a, wa)
        imm_predict(s.models, B[0], B[1], B[2], s.PI, s.Q, 0.1, s.same_group, wb)
        ll_b = imm_update(s.models, *B, s.r, z, s.meas, nis_b, wb)
        if k in (7, 30, 31):
            assert np.isnan(ll_a) and np.isnan(ll_b) and np.isnan(nis_a).all()
        else:
            assert np.isfinite(ll_a)
            np.testing.assert_allclose(ll_a, ll_b, rtol=1e-11, atol=1e-11)
            np.testing.assert_allclose(nis_a, nis_b, rtol=1e-10, atol=1e-11)
        for a, b in zip(A, B):
            np.testing.assert_allclose(a, b, rtol=1e-11, atol=1e-12)


def test_imm_loglik_one_sums_imm_step():
    """The log-likelihood runner on the workspace equals imm_step called step by step (missed steps not counted)."""
    from lgekf.estimators.imm.estimator import _common_inputs, _Setup
    from lgekf.estimators.imm.kernels import imm_loglik_one, imm_step, workspace

    s = _Setup("cv,se2r3", None, 0.5, "position", None)
    c, Pc = _common_inputs(np.array([[0.0, 0.0, 0.2, 3.0, 0.0, 0.1]]), np.diag([0.25, 0.25, 0.01, 0.25, 0.25, 0.01]))
    S0, P0 = s.initial(c, Pc)
    rng = np.random.default_rng(4)
    K = 40
    t = 0.1 * np.arange(1, K + 1)
    z = np.stack([3 * t, 0.3 * t * t], axis=-1) + 0.3 * rng.normal(size=(K, 2))
    z[[5, 20]] = np.nan
    dts = np.full(K, 0.1)
    S, Pp, mu = S0[0].copy(), P0[0].copy(), s.mu0.copy()
    ws, nis = workspace(s.M), np.empty(s.M)
    steps = [imm_step(s.models, S, Pp, mu, s.PI, s.Q, s.r, z[k], 0.1, s.same_group, s.meas, nis, ws) for k in range(30)]
    want = sum(v for v in steps[3:] if not np.isnan(v))
    S2, P2, mu2 = S0[0].copy(), P0[0].copy(), s.mu0.copy()
    tot, n = imm_loglik_one(s.models, S2, P2, mu2, s.PI, s.Q, s.r, z, dts, 3, 30, s.same_group, s.meas)
    assert n == 25  # steps 3..29 (27) without the missed steps 5 and 20
    np.testing.assert_allclose(tot, want, rtol=1e-13)
    for a, b in ((S, S2), (Pp, P2), (mu, mu2)):
        np.testing.assert_array_equal(a, b)
