"""FilterPy habits on the filter classes: ``x`` and ``P`` assignable, read-only copies that refuse item assignment,
and ``x_prior``, ``P_prior``, ``y``, ``S``, ``K``, ``log_likelihood`` after ``update``."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.stats import multivariate_normal

import lgekf


def _cv():
    return lgekf.CVFilter(dt=0.5, accel_std=0.7, meas_std=0.4, x0=[1.0, 2.0, 3.0, -1.0], P0=np.diag([1.0, 2.0, 3.0, 4.0]))


def test_before_any_update_the_innovation_is_absent():
    f = _cv()
    assert f.x_prior is None and f.y is None and f.S is None and f.K is None and np.isnan(f.log_likelihood)


def test_cv_update_is_the_textbook_kalman_update_with_these_quantities():
    f = _cv()
    f.predict()
    x_pred, P_pred = f.x.copy(), f.P.copy()
    z = np.array([2.9, 1.2])
    nis = f.update(z)
    H = np.array([[1.0, 0, 0, 0], [0, 1.0, 0, 0]])
    R = 0.4 ** 2 * np.eye(2)
    # the textbook quantities, computed here from the prior, independently of the filter
    S = H @ P_pred @ H.T + R
    K = P_pred @ H.T @ np.linalg.inv(S)
    y = z - H @ x_pred
    np.testing.assert_allclose(f.x_prior, x_pred, rtol=0, atol=1e-12)
    np.testing.assert_allclose(f.P_prior, P_pred, rtol=1e-12)
    np.testing.assert_allclose(f.y, y, atol=1e-12)
    np.testing.assert_allclose(f.S, S, rtol=1e-12)
    np.testing.assert_allclose(f.K, K, rtol=1e-10)
    np.testing.assert_allclose(f.x, x_pred + K @ y, atol=1e-12)
    assert nis == pytest.approx(y @ np.linalg.solve(S, y), rel=1e-12)
    assert f.log_likelihood == pytest.approx(multivariate_normal(np.zeros(2), S).logpdf(y), rel=1e-12)


def test_lie_group_update_matches_its_nis_and_moves_by_the_gain():
    f = lgekf.SE2SE2Filter(dt=0.1, accel_std=(0.5, 0.5, 1.0), meas_std=0.3, x0=[0, 0, 0.1, 5, 0, 0.2], P0=np.eye(6) * 0.05)
    f.predict()
    nis = f.update([0.52, 0.06])
    assert f.y @ np.linalg.solve(f.S, f.y) == pytest.approx(nis, rel=1e-10)
    step = f.K @ f.y  # the tangent correction; small here: the position moves by it to first order
    np.testing.assert_allclose(f.x[:2] - f.x_prior[:2], step[:2], atol=5e-3)


def test_x_and_P_are_assignable_and_refuse_item_assignment():
    f = _cv()
    with pytest.raises(ValueError, match="read-only"):
        f.x[0] = 5.0
    with pytest.raises(ValueError, match="read-only"):
        f.P[0, 0] = 5.0
    f.x = [5.0, 6.0, 0.0, 0.0]
    f.P = np.eye(4) * 2.0
    np.testing.assert_array_equal(f.x, [5.0, 6.0, 0.0, 0.0])
    np.testing.assert_array_equal(f.P, np.eye(4) * 2.0)
    with pytest.raises(ValueError, match="P"):
        f.P = -np.eye(4)
    with pytest.raises(ValueError, match="x"):
        f.x = [1.0, 2.0]
    g = lgekf.SE2SE2Filter(dt=0.1, accel_std=(0.5, 0.5, 1.0), meas_std=0.3, x0=[0, 0, 0, 1, 0, 0], P0=np.eye(6))
    with pytest.raises(ValueError, match="omega"):
        g.x = [0, 0, 0, 1, 0, 7.0]  # not representable in SE(2)xSE(2) (|ω| <= π), checked like x0
