"""The LG filters' numerical safeguards: inactive in regular steps, effective in the extreme ones.

* gain damping: a correction whose rotation angle exceeds π is scaled back to π (K → αK);
* angle-variance cap: after a prediction the std of the tangent angles is at most π;
* PD repair: a covariance that rounding left indefinite gets a rounding-level diagonal jitter.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from lgekf import SE2R3Filter, SE2SE2Filter
from lgekf.core.covariance import pack, unpack
from lgekf.generated import se2r3, se2se2


@pytest.mark.parametrize("cls", [SE2SE2Filter, SE2R3Filter])
def test_large_heading_correction_is_damped_to_pi(cls):
    # heading strongly correlated with position, far-off measurement: the raw ν_θ would be ~20 rad
    P0 = np.diag([1.0, 1.0, 1.0, 0.1, 0.1, 0.1])
    P0[1, 2] = P0[2, 1] = 0.99
    f = cls(dt=0.1, accel_std=(0.1, 0.1, 0.1), meas_std=0.01, x0=[0, 0, 0, 1, 0, 0], P0=P0)
    f.update([0.0, 20.0])
    assert abs(f.x[2]) == pytest.approx(math.pi, abs=1e-12) or abs(f.x[2]) < math.pi
    rot = math.atan2(f.mean[1, 0], f.mean[0, 0])
    assert abs(rot) <= math.pi + 1e-12
    np.linalg.cholesky(f.P)


@pytest.mark.parametrize("cls", [SE2SE2Filter, SE2R3Filter])
def test_regular_update_is_not_damped(cls):
    P0 = np.diag([0.3, 0.3, 0.05, 0.2, 0.2, 0.05])
    f = cls(dt=0.1, accel_std=(0.1, 0.1, 0.1), meas_std=0.5, x0=[0, 0, 0.2, 1, 0, 0.1], P0=P0)
    # paper's eq:up_P (non-Joseph) for the undamped gain: P⁺ = Φ(ν)(I - KH)P Φ(ν)ᵀ, Φ by its series
    f.update([0.5, -0.4])
    H = np.zeros((2, 6))
    c, s = math.cos(0.2), math.sin(0.2)
    H[:, :2] = [[c, -s], [s, c]]
    K = P0 @ H.T @ np.linalg.inv(H @ P0 @ H.T + 0.25 * np.eye(2))
    nu = K @ (np.array([0.5, -0.4]) - 0.0)

    def phi(xi, se2=True):
        if not se2:
            return np.eye(3)
        x, y, t = xi
        ad = np.array([[0, -t, y], [t, 0, -x], [0, 0, 0.0]])
        out, term = np.zeros((3, 3)), np.eye(3)
        for m in range(30):
            out += term / math.factorial(m + 1)
            term = term @ (-ad)
        return out

    Ph = np.zeros((6, 6))
    Ph[:3, :3] = phi(nu[:3])
    Ph[3:, 3:] = phi(nu[3:], cls is SE2SE2Filter)
    np.testing.assert_allclose(f.P, Ph @ (np.eye(6) - K @ H) @ P0 @ Ph.T, atol=1e-14)


@pytest.mark.parametrize("kern,angles", [(se2se2, (2, 5)), (se2r3, (2,))])
def test_angle_variance_cap(kern, angles):
    P = np.diag([1.0, 1.0, 100.0, 1.0, 1.0, 50.0])
    P[0, 2] = P[2, 0] = 5.0
    s = kern.state_from_physical(np.array([0, 0, 0.1, 1.0, 0, 0.2]))
    p = pack(P)
    kern.predict(s, p, 0.1, 0.1, 0.1, 0.1)
    Pn = unpack(p, 6)
    for a in angles:
        assert Pn[a, a] == pytest.approx(math.pi**2, rel=1e-12)
    np.linalg.cholesky(Pn)
    # below the cap the prediction is the paper's F P Fᵀ + Φ Q Φᵀ: compare with the same P scaled down
    P2 = P / 100.0
    p2 = pack(P2)
    s2 = kern.state_from_physical(np.array([0, 0, 0.1, 1.0, 0, 0.2]))
    kern.predict(s2, p2, 0.1, 0.0, 0.0, 0.0)
    F = kern.transition(kern.state_from_physical(np.array([0, 0, 0.1, 1.0, 0, 0.2])), 0.1)
    np.testing.assert_allclose(unpack(p2, 6), F @ P2 @ F.T, atol=1e-14)


def test_repair_pd_restores_a_rounding_broken_covariance():
    rng = np.random.default_rng(0)
    A = rng.standard_normal((6, 6))
    P = A @ A.T
    w, V = np.linalg.eigh(P)
    w[0] = -1e-12 * w[-1]  # indefinite at the level of rounding
    P = V @ np.diag(w) @ V.T
    P = 0.5 * (P + P.T)
    p = pack(P)
    assert not se2se2.covariance_is_pd(p)
    before = p.copy()
    se2se2.repair_pd(p)
    assert se2se2.covariance_is_pd(p)
    np.linalg.cholesky(unpack(p, 6))
    # only the diagonal moved, and only by a rounding-level amount
    diag = np.array([0, 6, 11, 15, 18, 20])
    off = np.setdiff1d(np.arange(21), diag)
    np.testing.assert_array_equal(p[off], before[off])
    assert np.max(np.abs(p[diag] - before[diag])) < 1e-9 * np.max(np.abs(before[diag]))


def test_regular_covariance_is_pd():
    assert se2se2.covariance_is_pd(pack(np.diag([0.25, 0.25, 0.01, 0.1, 0.1, 0.01])))
    assert not se2se2.covariance_is_pd(pack(np.diag([1.0, 1.0, 1.0, 1.0, 1.0, np.nan])))
