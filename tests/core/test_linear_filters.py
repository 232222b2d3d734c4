"""The baselines: CVFilter against a textbook Kalman filter (and FilterPy), NEES/NIS consistency on
simulated CV data; CTRVFilter against a direct numpy implementation of the CTRV equations."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.stats import chi2

from lgekf import CTRVFilter, CVFilter
from lgekf.generated import ctrv as ctrv_kernels

# ---------------------------------------------------------------------------------------------
# CV: textbook Kalman filter
# ---------------------------------------------------------------------------------------------

H_CV = np.hstack([np.eye(2), np.zeros((2, 2))])


def cv_F(T):
    return np.block([[np.eye(2), T * np.eye(2)], [np.zeros((2, 2)), np.eye(2)]])


def cv_G(T):
    return np.vstack([T * T / 2 * np.eye(2), T * np.eye(2)])


def cv_Q(T, sa):
    G = cv_G(T)
    return sa * sa * G @ G.T


class TextbookKF:
    """x = Fx, P = FPFᵀ + Q; K = PHᵀS⁻¹; x += K(z - Hx); P = (I - KH)P."""

    def __init__(self, x, P, sa, r):
        self.x, self.P, self.sa, self.r = np.array(x, float), np.array(P, float), sa, r

    def predict(self, T):
        F = cv_F(T)
        self.x = F @ self.x
        self.P = F @ self.P @ F.T + cv_Q(T, self.sa)

    def update(self, z):
        H = H_CV
        S = H @ self.P @ H.T + self.r**2 * np.eye(2)
        K = self.P @ H.T @ np.linalg.inv(S)
        e = z - H @ self.x
        self.x = self.x + K @ e
        self.P = (np.eye(4) - K @ H) @ self.P
        return float(e @ np.linalg.solve(S, e))


def _rel(a, b):
    return float(np.max(np.abs(np.asarray(a) - b)) / max(1e-300, np.max(np.abs(b))))


def _random_spd(rng, n, scale=1.0):
    A = rng.randn(n, n)
    return scale * (A @ A.T / n + 0.1 * np.eye(n))


def _cv_run(seed):
    rng = np.random.RandomState(seed)
    x0 = np.array([rng.randn() * 10, rng.randn() * 10, rng.randn() * 2, rng.randn() * 2])
    P0 = _random_spd(rng, 4)
    dts = rng.uniform(0.02, 1.0, size=100)
    truth = x0.copy()
    zs = []
    for T in dts:
        truth = cv_F(T) @ truth + cv_G(T) @ (0.5 * rng.randn(2))
        zs.append(truth[:2] + 0.3 * rng.randn(2))
    return x0, P0, dts, np.array(zs)


def test_cv_matches_textbook_kf():
    worst = 0.0
    for seed in range(5):
        x0, P0, dts, zs = _cv_run(seed)
        f = CVFilter(dt=0.1, accel_std=0.5, meas_std=0.3, x0=x0, P0=P0)
        ref = TextbookKF(x0, P0, 0.5, 0.3)
        for T, z in zip(dts, zs):
            f.predict(dt=T)
            ref.predict(T)
            assert _rel(f.x, ref.x) < 1e-12
            assert _rel(f.P, ref.P) < 1e-12
            nis = f.update(z)
            nis_ref = ref.update(z)
            errs = (_rel(f.x, ref.x), _rel(f.P, 0.5 * (ref.P + ref.P.T)), abs(nis - nis_ref) / max(1.0, nis_ref))
            worst = max(worst, *errs)
            assert max(errs) < 1e-12, errs
    print(f"CV vs textbook KF: max rel. discrepancy {worst:.3g}")


def test_cv_default_dt_and_accel_std_forms():
    """predict() uses the constructor's dt; accel_std may be a scalar or a 1-vector."""
    x0 = np.array([1.0, 2.0, 3.0, -1.0])
    a = CVFilter(dt=0.25, accel_std=0.7, meas_std=1.0, x0=x0, P0=np.eye(4))
    b = CVFilter(dt=1.0, accel_std=[0.7], meas_std=1.0, x0=x0, P0=np.eye(4))
    a.predict()
    b.predict(dt=0.25)
    np.testing.assert_array_equal(a.x, b.x)
    np.testing.assert_array_equal(a.P, b.P)
    ref = TextbookKF(x0, np.eye(4), 0.7, 1.0)
    ref.predict(0.25)
    np.testing.assert_allclose(a.P, ref.P, rtol=1e-14, atol=1e-15)


def test_cv_matches_filterpy():
    kfm = pytest.importorskip("filterpy.kalman")
    worst = 0.0
    for seed in range(3):
        x0, P0, dts, zs = _cv_run(seed)
        f = CVFilter(dt=0.1, accel_std=0.5, meas_std=0.3, x0=x0, P0=P0)
        kf = kfm.KalmanFilter(dim_x=4, dim_z=2)
        kf.x = x0.reshape(4, 1).copy()
        kf.P = P0.copy()
        kf.H = H_CV.copy()
        kf.R = 0.09 * np.eye(2)
        for T, z in zip(dts, zs):
            kf.F = cv_F(T)
            kf.Q = cv_Q(T, 0.5)
            kf.predict()
            f.predict(dt=T)
            kf.update(z.reshape(2, 1))
            f.update(z)
            errs = (_rel(f.x, kf.x.ravel()), _rel(f.P, kf.P))
            worst = max(worst, *errs)
            assert max(errs) < 1e-12, errs
    print(f"CV vs FilterPy: max rel. discrepancy {worst:.3g}")


# ---------------------------------------------------------------------------------------------
# CV: NEES / NIS consistency on data simulated from the CV model itself (DWNA)
# ---------------------------------------------------------------------------------------------

N_RUNS, N_STEPS = 200, 50


def _nees_nis(sa_true, sa_filter, seed=2024, T=0.5, r=0.8):
    rng = np.random.RandomState(seed)
    P0 = np.diag([4.0, 4.0, 1.0, 1.0])
    nees = np.empty((N_RUNS, N_STEPS))
    nis = np.empty((N_RUNS, N_STEPS))
    F, G = cv_F(T), cv_G(T)
    for run in range(N_RUNS):
        truth = np.array([0.0, 0.0, 3.0, -1.0]) + rng.randn(4) * 2
        x0 = truth + np.linalg.cholesky(P0) @ rng.randn(4)  # x0 ~ N(truth, P0): consistent start
        f = CVFilter(dt=T, accel_std=sa_filter, meas_std=r, x0=x0, P0=P0)
        for k in range(N_STEPS):
            truth = F @ truth + G @ (sa_true * rng.randn(2))  # DWNA: one random acceleration per step
            z = truth[:2] + r * rng.randn(2)
            f.predict()
            nis[run, k] = f.update(z)
            e = f.x - truth
            nees[run, k] = e @ np.linalg.solve(f.P, e)
    return nees.mean(axis=0), nis.mean(axis=0)


def test_cv_nees_nis_consistent():
    nees, nis = _nees_nis(sa_true=1.5, sa_filter=1.5)
    lo, hi = chi2.ppf([0.025, 0.975], 4 * N_RUNS) / N_RUNS
    lo2, hi2 = chi2.ppf([0.025, 0.975], 2 * N_RUNS) / N_RUNS
    inside = np.mean((nees > lo) & (nees < hi))
    inside2 = np.mean((nis > lo2) & (nis < hi2))
    print(f"NEES: {inside:.0%} of steps in [{lo:.3f}, {hi:.3f}], mean {nees.mean():.3f}; NIS: {inside2:.0%} in band")
    # each step's average is inside the 95% band with probability 0.95 (fixed seed)
    assert inside >= 0.9, nees
    assert inside2 >= 0.9, nis
    # the average over all runs and steps lies in the band for 4·N_RUNS dof as well (conservative:
    # averaging over correlated steps narrows the spread less than independent samples would)
    assert lo < nees.mean() < hi and lo2 < nis.mean() < hi2
    assert abs(nees.mean() - 4) < 0.2 and abs(nis.mean() - 2) < 0.1


def test_cv_nees_detects_mismatched_noise():
    """Sensitivity check: a filter with 4× too small σ_a is overconfident."""
    nees, _ = _nees_nis(sa_true=1.5, sa_filter=1.5 / 4)
    hi = chi2.ppf(0.975, 4 * N_RUNS) / N_RUNS
    assert np.mean(nees[5:] > hi) > 0.9


# ---------------------------------------------------------------------------------------------
# CTRV: direct numpy implementation
# ---------------------------------------------------------------------------------------------


def _dsin(psi, k):
    """k-th derivative of sin at psi."""
    return [math.sin, math.cos, lambda p: -math.sin(p), lambda p: -math.cos(p)][k % 4](psi)


def _series(psi, a, kind, terms=30):
    """Taylor series (the ω → 0 limit and its corrections) in a = ωT of
    S1 = (sin(ψ+a) - sin ψ)/a, S2 = (cos ψ - cos(ψ+a))/a and their derivatives."""
    out = 0.0
    for k in range(1, terms):
        if kind == "S1":  # Σ a^{k-1}/k! sin^{(k)} ψ
            out += a ** (k - 1) / math.factorial(k) * _dsin(psi, k)
        elif kind == "S2":  # cos ψ - cos(ψ+a) = sin-shift: -Σ a^k/k! cos^{(k)} ψ ; cos^{(k)} = sin^{(k+1)}
            out -= a ** (k - 1) / math.factorial(k) * _dsin(psi, k + 1)
        elif kind == "dS1":
            if k >= 2:
                out += (k - 1) * a ** (k - 2) / math.factorial(k) * _dsin(psi, k)
        elif kind == "dS2":
            if k >= 2:
                out -= (k - 1) * a ** (k - 2) / math.factorial(k) * _dsin(psi, k + 1)
    return out


def _S(psi, a):
    """(S1, S2, dS1/da, dS2/da): classic closed form for |a| > 0.5, Taylor series below."""
    if abs(a) > 0.5:
        d1 = math.sin(psi + a) - math.sin(psi)
        d2 = math.cos(psi) - math.cos(psi + a)
        return d1 / a, d2 / a, (a * math.cos(psi + a) - d1) / a**2, (a * math.sin(psi + a) - d2) / a**2
    return tuple(_series(psi, a, k) for k in ("S1", "S2", "dS1", "dS2"))


def ctrv_motion_classic(s, T):
    """The textbook CTRV equations: (v/ω)(sin(ψ+ωT) - sin ψ) for |ω| > 1e-3, the ω → 0 limit below."""
    x, y, psi, v, om = s
    if abs(om) > 1e-3:
        xn = x + v / om * (math.sin(psi + om * T) - math.sin(psi))
        yn = y + v / om * (math.cos(psi) - math.cos(psi + om * T))
    else:
        xn = x + v * T * math.cos(psi)
        yn = y + v * T * math.sin(psi)
    return np.array([xn, yn, psi + om * T, v, om])


def ctrv_motion(s, T):
    """The same motion, accurate everywhere (series in a = ωT for |a| ≤ 0.5; exact at ω = 0)."""
    x, y, psi, v, om = s
    S1, S2, _, _ = _S(psi, om * T)
    return np.array([x + v * T * S1, y + v * T * S2, psi + om * T, v, om])


def ctrv_jacobian(s, T):
    x, y, psi, v, om = s
    a = om * T
    S1, S2, dS1, dS2 = _S(psi, a)
    # ∂S1/∂ψ = -S2, ∂S2/∂ψ = S1
    F = np.eye(5)
    F[0, 2], F[0, 3], F[0, 4] = -v * T * S2, T * S1, v * T * T * dS1
    F[1, 2], F[1, 3], F[1, 4] = v * T * S1, T * S2, v * T * T * dS2
    F[2, 4] = T
    return F


def ctrv_jacobian_fd(s, T, h=1e-6):
    cols = []
    for i in range(5):
        e = np.zeros(5)
        e[i] = h * max(1.0, abs(s[i]))
        cols.append((ctrv_motion(s + e, T) - ctrv_motion(s - e, T)) / (2 * e[i]))
    return np.column_stack(cols)


def ctrv_Q(s, T, sa, sw):
    psi = s[2]
    G = np.array([[T * T / 2 * math.cos(psi), 0], [T * T / 2 * math.sin(psi), 0], [0, T * T / 2], [T, 0], [0, T]])
    return G @ np.diag([sa * sa, sw * sw]) @ G.T


OMEGAS = [0.0, 1e-12, -1e-12, 1e-6, -1e-6, 1e-3, -1e-3, 1.0001e-3, 0.05, -0.3, 1.0, -2.5, 6.0]


def _ctrv_cases(seed, n=150):
    rng = np.random.RandomState(seed)
    for i in range(n):
        om = OMEGAS[i % len(OMEGAS)] if i < 3 * len(OMEGAS) else rng.uniform(-3, 3)
        s = np.array([rng.randn() * 20, rng.randn() * 20, rng.uniform(-4, 4), rng.uniform(-2, 15), om])
        yield s, _random_spd(rng, 5) * rng.uniform(0.01, 3), float(rng.uniform(0.01, 1.5))


def _wrapped(a):
    return (a + math.pi) % (2 * math.pi) - math.pi


def test_ctrv_reference_consistency():
    """The accurate reference agrees with the classic textbook equations (to their cancellation
    error) and its analytic Jacobian with central finite differences, including ω = 0."""
    for s, _, T in _ctrv_cases(0):
        m1, m2 = ctrv_motion(s, T), ctrv_motion_classic(s, T)
        # classic form: (v/ω)·Δsin loses ~ε·v/ω; the ω → 0 limit ignores O(vωT²) (≤ 1e-3·vT²)
        tol = 1e-12 * (1 + abs(s[3]) / max(abs(s[4]), 1e-3)) if abs(s[4]) > 1e-3 else 1e-3 * abs(s[3]) * T * T + 1e-12
        assert np.max(np.abs(m1 - m2)) <= tol * max(1.0, np.max(np.abs(m1))), (s, T)
        assert _rel(ctrv_jacobian(s, T), ctrv_jacobian_fd(s, T)) < 1e-7, (s, T)


def test_ctrv_transition_matches_finite_differences():
    worst = 0.0
    for s, _, T in _ctrv_cases(1):
        F = np.asarray(ctrv_kernels.transition(s.copy(), T))
        err = _rel(F, ctrv_jacobian_fd(s, T))
        worst = max(worst, err)
        assert err < 1e-7, (s, T, F)
        assert _rel(F, ctrv_jacobian(s, T)) < 1e-12, (s, T)
    print(f"CTRV F vs central FD: max rel. discrepancy {worst:.3g}")


def test_ctrv_predict_matches_reference():
    worst = {"x": 0.0, "P": 0.0}
    for s, P0, T in _ctrv_cases(2):
        sa, sw = 0.8, 0.3
        f = CTRVFilter(dt=T, accel_std=(sa, sw), meas_std=1.0, x0=s, P0=P0)
        f.predict()
        xr = ctrv_motion(s, T)
        F = ctrv_jacobian(s, T)
        Pr = F @ P0 @ F.T + ctrv_Q(s, T, sa, sw)
        x = f.x
        d = np.abs(x - xr)
        d[2] = abs(_wrapped(x[2] - xr[2]))
        ex, eP = float(np.max(d) / max(1.0, np.max(np.abs(xr)))), _rel(f.P, Pr)
        worst["x"], worst["P"] = max(worst["x"], ex), max(worst["P"], eP)
        assert ex < 1e-12, (s, T, x, xr)
        assert eP < 1e-12, (s, T)
        # the classic form agrees as well, for |ω| > 1e-3 (to its cancellation error)
        if abs(s[4]) > 1e-3:
            xc = ctrv_motion_classic(s, T)
            assert np.max(np.abs(x[:2] - xc[:2])) < 1e-12 * (1 + abs(s[3]) / abs(s[4])) * max(1.0, np.max(np.abs(xc)))
    print(f"CTRV predict vs reference: max rel. discrepancy {worst}")


def test_ctrv_omega_zero_is_straight_line():
    s = np.array([1.0, -2.0, 0.7, 4.0, 0.0])
    f = CTRVFilter(dt=0.5, accel_std=(0.1, 0.1), meas_std=1.0, x0=s, P0=np.eye(5))
    f.predict()
    np.testing.assert_allclose(f.x, [1.0 + 2.0 * math.cos(0.7), -2.0 + 2.0 * math.sin(0.7), 0.7, 4.0, 0.0], rtol=0, atol=1e-15)


def test_ctrv_update_matches_textbook_ekf():
    """H = [I2 0]; K = PHᵀS⁻¹; x += K(z - Hx); P Joseph form (equal to (I - KH)P)."""
    H = np.hstack([np.eye(2), np.zeros((2, 3))])
    worst = 0.0
    for s, P0, _ in _ctrv_cases(3, n=100):
        r = 0.5
        f = CTRVFilter(dt=0.1, accel_std=(0.1, 0.1), meas_std=r, x0=s, P0=P0)
        z = s[:2] + np.array([0.3, -0.7])
        nis = f.update(z)
        S = H @ P0 @ H.T + r * r * np.eye(2)
        K = P0 @ H.T @ np.linalg.inv(S)
        e = z - s[:2]
        xr = s + K @ e
        A = np.eye(5) - K @ H
        Pr = A @ P0 @ A.T + r * r * K @ K.T
        x = f.x
        d = np.abs(x - xr)
        d[2] = abs(_wrapped(x[2] - xr[2]))
        errs = (float(np.max(d) / max(1.0, np.max(np.abs(xr)))), _rel(f.P, Pr), _rel(f.P, A @ P0), abs(nis - e @ np.linalg.solve(S, e)) / max(1.0, nis))
        worst = max(worst, *errs)
        assert max(errs) < 1e-12, errs
    print(f"CTRV update vs textbook EKF: max rel. discrepancy {worst:.3g}")


def test_ctrv_sequence_matches_reference():
    """40 predict/update steps with irregular dt through a turn (ω passing through 0)."""
    rng = np.random.RandomState(9)
    H = np.hstack([np.eye(2), np.zeros((2, 3))])
    s = np.array([0.0, 0.0, 0.3, 5.0, 0.4])
    P = np.diag([1.0, 1.0, 0.1, 1.0, 0.1])
    sa, sw, r = 0.5, 0.2, 0.4
    f = CTRVFilter(dt=0.1, accel_std=(sa, sw), meas_std=r, x0=s, P0=P)
    truth = s.copy()
    for k in range(40):
        T = float(rng.uniform(0.05, 0.4))
        truth[4] = 0.4 * math.cos(0.2 * k)
        truth = ctrv_motion(truth, T)
        F = ctrv_jacobian(s, T)
        P = F @ P @ F.T + ctrv_Q(s, T, sa, sw)
        s = ctrv_motion(s, T)
        f.predict(dt=T)
        z = truth[:2] + r * rng.randn(2)
        S = H @ P @ H.T + r * r * np.eye(2)
        K = P @ H.T @ np.linalg.inv(S)
        s = s + K @ (z - s[:2])
        A = np.eye(5) - K @ H
        P = A @ P @ A.T + r * r * K @ K.T
        f.update(z)
        d = np.abs(f.x - s)
        d[2] = abs(_wrapped(f.x[2] - s[2]))
        assert np.max(d) < 1e-11 * max(1.0, np.max(np.abs(s))), (k, f.x, s)
        assert _rel(f.P, P) < 1e-11, k


def test_ctrv_heading_output_in_documented_range():
    """``state_to_physical`` documents ψ wrapped to (-π, π]."""
    for a in (math.pi, -math.pi, 3 * math.pi, -3 * math.pi, 7.0):
        f = CTRVFilter(dt=0.1, accel_std=(0.1, 0.1), meas_std=0.5, x0=[0.0, 0.0, a, 1.0, 0.0], P0=np.eye(5))
        assert -math.pi < f.x[2] <= math.pi, f"ψ = {a!r} -> {f.x[2]!r}"
