"""SE2SE2Filter / SE2R3Filter against a dense, independent transcription of the paper's LG-EKF.

Reference: Ćesić, Marković, Petrović, "Moving object tracking employing rigid body motion on matrix
Lie groups", sections "EKF on matrix Lie groups" (eq:pred_mu, eq:pred_cov, eq:C, eq:K, eq:calH,
eq:up_mu, eq:up_P) and "LG-EKF on SE(2)^2" (eq:motionG, eq:calCFinal, eq:calH_model).

Nothing in the reference below calls ``lgekf``: the group mean is a block-diagonal matrix, exp is
``scipy.linalg.expm`` of the hat, log is ``scipy.linalg.logm`` (real part), Ad(X) is (X v^ X⁻¹)^∨
evaluated column by column, ad(v) is the matrix bracket [v^, ·]^∨, Φ is the truncated series
Σ_{m≤40} (-1)^m/(m+1)! ad^m, and 𝒞, ℋ are central finite differences of their definitions.

Finite differences are only accurate to ~1e-9, so the 1e-10 comparisons of the filters use the
paper's printed 𝒞 (eq:calCFinal: 𝒞 = [[0, T·R(ω) ⊕ T], [0, 0]] for SE(2)², [[0, T·I], [0, 0]] for
SE(2)×R³) and ℋ (eq:calH_model: ℋ = [R(θ), 0]); ``test_paper_jacobians_match_finite_differences``
checks those printed matrices against the finite differences at 1e-7 (and the library's own
``calC``/``calH``/``transition`` kernels likewise), so the chain reference ← definitions is closed.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.linalg import expm, logm

from lgekf import SE2R3Filter, SE2SE2Filter



# ---------------------------------------------------------------------------------------------
# Dense reference: matrix Lie group G = SE(2)×SE(2) ("se2se2") or SE(2)×R³ ("se2r3")
# ---------------------------------------------------------------------------------------------

# Each factor: (kind, algebra dimension, matrix size). R³ is the group {[[I3, v], [0, 1]]}.
GROUPS = {
    "se2se2": (("se2", 3, 3), ("se2", 3, 3)),
    "se2r3": (("se2", 3, 3), ("r3", 3, 4)),
}
CLASSES = {"se2se2": SE2SE2Filter, "se2r3": SE2R3Filter}
P_DIM = 6


def _hat_factor(kind, v):
    if kind == "se2":
        x, y, th = v
        return np.array([[0.0, -th, x], [th, 0.0, y], [0.0, 0.0, 0.0]])
    M = np.zeros((4, 4))
    M[:3, 3] = v
    return M


def _vee_factor(kind, M):
    if kind == "se2":
        return np.array([M[0, 2], M[1, 2], M[1, 0]])
    return M[:3, 3].copy()


def _blocks(model):
    """(algebra slice, matrix slice, kind) per factor."""
    out, a, m = [], 0, 0
    for kind, p, n in GROUPS[model]:
        out.append((slice(a, a + p), slice(m, m + n), kind))
        a, m = a + p, m + n
    return out


def mat_size(model):
    return sum(n for _, _, n in GROUPS[model])


def hat(model, v):
    M = np.zeros((mat_size(model), mat_size(model)))
    for sa, sm, kind in _blocks(model):
        M[sm, sm] = _hat_factor(kind, v[sa])
    return M


def vee(model, M):
    v = np.zeros(P_DIM)
    for sa, sm, kind in _blocks(model):
        v[sa] = _vee_factor(kind, M[sm, sm])
    return v


def gexp(model, v):
    return expm(hat(model, v))


def glog(model, X):
    """[log_G(X)]^∨ via scipy's logm (block by block, real part; valid for rotation angles |θ| < π)."""
    v = np.zeros(P_DIM)
    for sa, sm, kind in _blocks(model):
        v[sa] = _vee_factor(kind, np.real(logm(X[sm, sm])))
    return v


def Ad(model, X):
    """Ad_G(X) by its definition: column i is (X E_i X⁻¹)^∨."""
    Xi = np.linalg.inv(X)
    return np.column_stack([vee(model, X @ hat(model, e) @ Xi) for e in np.eye(P_DIM)])


def ad(model, v):
    """ad_G(v) by the bracket: column i is (v^ E_i - E_i v^)^∨."""
    V = hat(model, v)
    return np.column_stack([vee(model, V @ hat(model, e) - hat(model, e) @ V) for e in np.eye(P_DIM)])


def Phi(model, v, terms=40):
    """Φ_G(v) = Σ_{m=0}^{terms} (-1)^m/(m+1)! ad_G(v)^m (the right Jacobian)."""
    A = ad(model, v)
    out = np.zeros((P_DIM, P_DIM))
    term = np.eye(P_DIM)
    for m in range(terms + 1):
        out += (-1) ** m / math.factorial(m + 1) * term
        term = term @ A
    return out


def rot(a):
    return np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])


def mean_from_physical(model, xp):
    """μ = diag(T_s, T_d) (resp. diag(T_s, [[I3, v], [0, 1]])) from x = [x, y, θ, v_x, v_y, ω]."""
    x, y, th, vx, vy, om = xp
    X = np.zeros((mat_size(model), mat_size(model)))
    X[:2, :2] = rot(th)
    X[:2, 2] = (x, y)
    X[2, 2] = 1.0
    if model == "se2se2":
        X[3:5, 3:5] = rot(om)
        X[3:5, 5] = (vx, vy)
        X[5, 5] = 1.0
    else:
        X[3:6, 3:6] = np.eye(3)
        X[3:6, 6] = (vx, vy, om)
        X[6, 6] = 1.0
    return X


def so2_angle(R):
    """log_SO(2)(R) = atan2(R21, R11) (the paper's SE(2) log), in (-π, π]."""
    return math.atan2(R[1, 0], R[0, 0])


def velocity(model, X, omega_ref=None):
    """(v_x, v_y, ω) of the mean. In SE(2)² ω is the angle of T_d's rotation; with ``omega_ref`` it is
    taken on the branch continuous around omega_ref (only used for finite differences near ±π)."""
    if model == "se2se2":
        R = X[3:5, 3:5]
        if omega_ref is None:
            om = so2_angle(R)
        else:
            om = omega_ref + so2_angle(rot(omega_ref).T @ R)
        return np.array([X[3, 5], X[4, 5], om])
    return X[3:6, 6].copy()


def physical_from_mean(model, X):
    return np.concatenate([[X[0, 2], X[1, 2], so2_angle(X[:2, :2])], velocity(model, X)])


def Omega(model, X, T, omega_ref=None):
    """Ω(X) = [T v_x, T v_y, T ω, 0, 0, 0] (eq:motionG)."""
    v = velocity(model, X, omega_ref)
    return np.array([T * v[0], T * v[1], T * v[2], 0.0, 0.0, 0.0])


def calC_fd(model, mu, T, h=1e-5):
    """𝒞 = ∂Ω(μ exp ε)/∂ε at 0 (eq:C), central differences."""
    om0 = velocity(model, mu)[2]
    cols = []
    for e in np.eye(P_DIM):
        fp = Omega(model, mu @ gexp(model, h * e), T, om0)
        fm = Omega(model, mu @ gexp(model, -h * e), T, om0)
        cols.append((fp - fm) / (2 * h))
    return np.column_stack(cols)


def calC_paper(model, mu, T):
    """eq:calCFinal (SE(2)²): [[0, T R(ω) ⊕ T], [0, 0]]; for SE(2)×R³ the velocity block is T·I."""
    C = np.zeros((P_DIM, P_DIM))
    if model == "se2se2":
        C[0:2, 3:5] = T * mu[3:5, 3:5]
    else:
        C[0:2, 3:5] = T * np.eye(2)
    C[2, 5] = T
    return C


def h_meas(X):
    """h(X) ∈ R² as the matrix group element Z = [[I, t], [0, 1]] (eq:r), t the position of T_s."""
    Z = np.eye(3)
    Z[:2, 2] = X[:2, 2]
    return Z


def log_r2(Z):
    """[log_{R²}(Z)]^∨ via logm."""
    return np.real(logm(Z))[:2, 2]


def calH_fd(model, mu, h=1e-5):
    """ℋ = ∂/∂ε [log_{R²}(h(μ)⁻¹ h(μ exp ε))]^∨ at 0 (eq:calH), central differences."""
    hinv = np.linalg.inv(h_meas(mu))
    cols = []
    for e in np.eye(P_DIM):
        fp = log_r2(hinv @ h_meas(mu @ gexp(model, h * e)))
        fm = log_r2(hinv @ h_meas(mu @ gexp(model, -h * e)))
        cols.append((fp - fm) / (2 * h))
    return np.column_stack(cols)


def calH_paper(mu):
    """eq:calH_model: ℋ = [R(θ), 0_{2×4}]."""
    H = np.zeros((2, P_DIM))
    H[:, :2] = mu[:2, :2]
    return H


def process_noise(T, sig):
    """Q = G diag(σ²) Gᵀ with n_k = G n, G = [T²/2 I3; T I3] (eq:motionG)."""
    G = np.vstack([T * T / 2 * np.eye(3), T * np.eye(3)])
    return G @ np.diag(np.square(sig)) @ G.T


def transition_ref(model, mu, T, C=None):
    """F = Ad_G(exp(-Ω)) + Φ_G(Ω) 𝒞."""
    Om = Omega(model, mu, T)
    C = calC_paper(model, mu, T) if C is None else C
    return Ad(model, gexp(model, -Om)) + Phi(model, Om) @ C


def ref_predict(model, mu, P, T, sig):
    """eq:pred_mu, eq:pred_cov."""
    Om = Omega(model, mu, T)
    F = transition_ref(model, mu, T)
    Ph = Phi(model, Om)
    mu_new = mu @ gexp(model, Om)
    P_new = F @ P @ F.T + Ph @ process_noise(T, sig) @ Ph.T
    return mu_new, P_new


def ref_update(model, mu, P, z, r):
    """eq:K, eq:up_mu, eq:up_P (plain, non-Joseph form, as printed). Returns (μ⁺, P⁺, NIS).

    The library's documented safeguard: when a rotation angle of ν = K e exceeds π (outside the
    concentrated Gaussian's bijective domain) the gain is damped, K → αK, α = π / max|angle|, and the
    covariance is the Joseph form for that gain.  Regular corrections (|angle| ≤ π) use the paper's
    equations unchanged."""
    H = calH_paper(mu)
    S = H @ P @ H.T + r * r * np.eye(2)
    K = np.linalg.solve(S, H @ P).T  # = P Hᵀ S⁻¹ (S, P symmetric)
    Z = np.eye(3)
    Z[:2, 2] = z
    e = log_r2(np.linalg.inv(h_meas(mu)) @ Z)
    nu = K @ e
    angles = [abs(nu[2])] + ([abs(nu[5])] if model == "se2se2" else [])
    if max(angles) > math.pi:
        alpha = math.pi / max(angles)
        K = alpha * K
        nu = K @ e
        mu_new = mu @ gexp(model, nu)
        Ph = Phi(model, nu)
        A = np.eye(P_DIM) - K @ H
        P_new = Ph @ (A @ P @ A.T + r * r * K @ K.T) @ Ph.T
        P_new = 0.5 * (P_new + P_new.T)
        return mu_new, P_new, float(e @ np.linalg.solve(S, e))
    mu_new = mu @ gexp(model, nu)
    Ph = Phi(model, nu)
    P_new = Ph @ (np.eye(P_DIM) - K @ H) @ P @ Ph.T
    P_new = 0.5 * (P_new + P_new.T)  # symmetric in exact arithmetic; drop the rounding asymmetry
    return mu_new, P_new, float(e @ np.linalg.solve(S, e))


# ---------------------------------------------------------------------------------------------
# Random cases (fixed seeds)
# ---------------------------------------------------------------------------------------------

SPECIAL_ANGLES = [0.0, 1e-12, -1e-12, 1e-6, -1e-6, math.pi - 1e-9, -(math.pi - 1e-9), math.pi, -math.pi]
N_CASES = 200
TOL = 1e-10

# maximum relative discrepancies seen (printed by test_report_max_discrepancies with -s)
MAX_SEEN: dict = {}


def _note(key, value):
    MAX_SEEN[key] = max(MAX_SEEN.get(key, 0.0), float(value))


def random_spd(rng, kind):
    """A random SPD 6×6 covariance with mixed scales; ``kind`` selects special structures."""
    scales = np.array([rng.uniform(0.05, 3), rng.uniform(0.05, 3), rng.uniform(0.005, 0.5), rng.uniform(0.05, 2), rng.uniform(0.05, 2), rng.uniform(0.005, 0.5)])
    A = rng.randn(6, 6)
    if kind in ("blockdiag", "tinycorr"):
        # no position–(θ, ω) correlation: ν_θ = ν_ω = 0 exactly in the update ("blockdiag"),
        # or correlations of 1e-12 so that ν_θ, ν_ω ~ 1e-12 ("tinycorr")
        for i in (0, 1, 3, 4):
            for j in (2, 5):
                A[i, j] = A[j, i] = 0.0
    P = scales[:, None] * (A @ A.T / 6 + 0.05 * np.eye(6)) * scales[None, :]
    if kind == "tinycorr":
        for i in (0, 1):
            for j in (2, 5):
                P[i, j] = P[j, i] = 1e-12 * rng.randn()
    P = 0.5 * (P + P.T)
    np.linalg.cholesky(P)
    return P


def random_cases(seed, n=N_CASES, wide_omega=False):
    """n cases (x0, P0, dt, z_offset kind, r): the first covers every pair of special (θ, ω).
    ``wide_omega`` (SE(2)×R³, where ω is a plain number): some ω in (-5, 5), so |Tω| > π occurs."""
    rng = np.random.RandomState(seed)
    cases = []
    grid = [(a, b) for a in SPECIAL_ANGLES for b in SPECIAL_ANGLES]
    for i in range(n):
        if i < len(grid):
            th, om = grid[i]
        else:
            th = rng.choice(SPECIAL_ANGLES) if rng.rand() < 0.3 else rng.uniform(-math.pi, math.pi)
            om = rng.choice(SPECIAL_ANGLES) if rng.rand() < 0.3 else rng.uniform(-math.pi, math.pi)
            if wide_omega and rng.rand() < 0.3:
                om = rng.uniform(-5, 5)
        x0 = np.array([rng.randn() * 20, rng.randn() * 20, th, rng.randn() * 3, rng.randn() * 3, om])
        if rng.rand() < 0.1:
            x0[3:5] = 0.0
        kind = rng.choice(["dense", "dense", "blockdiag", "tinycorr"])
        P0 = random_spd(rng, kind)
        dt = float(rng.choice([rng.uniform(0.01, 1.5), 1e-6, 1.0])) if rng.rand() < 0.2 else float(rng.uniform(0.01, 1.5))
        innov = rng.choice(["normal", "normal", "normal", "zero", "tiny", "large"])
        r = float(np.exp(rng.uniform(np.log(1e-2), np.log(5.0))))
        cases.append(dict(x0=x0, P0=P0, dt=dt, innov=innov, r=r, rng=np.random.RandomState(seed * 1000 + i)))
    return cases


def _measurement(case, mu, P):
    """A position measurement: t + offset, offset 0, ~1e-12, ~√S or ~5√S."""
    t = mu[:2, 2]
    rng = case["rng"]
    kind = case["innov"]
    if kind == "zero":
        return t.copy()
    if kind == "tiny":
        return t + 1e-12 * rng.randn(2)
    s = math.sqrt(np.trace(P[:2, :2]) / 2 + case["r"] ** 2)
    return t + s * rng.randn(2) * (5.0 if kind == "large" else 1.0)


def _rel(a, b):
    """max|a - b| relative to max|b| (matrices: the max-norm of the reference)."""
    return float(np.max(np.abs(a - b)) / max(1e-300, np.max(np.abs(b))))


def _angle_diff(a, b):
    return abs((a - b + math.pi) % (2 * math.pi) - math.pi)


def _check_physical(model, f, mu_ref, where):
    xr = physical_from_mean(model, mu_ref)
    x = f.x
    d = np.abs(x - xr)
    d[2] = _angle_diff(x[2], xr[2])
    if model == "se2se2":
        d[5] = _angle_diff(x[5], xr[5])
    err = float(np.max(d) / max(1.0, np.max(np.abs(xr))))
    _note((model, "physical x"), err)
    assert err < TOL, f"{where}: x {x} vs reference {xr}"


# ---------------------------------------------------------------------------------------------
# Self-checks of the reference (so that a wrong reference cannot make a wrong filter pass)
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize("model", ["se2se2", "se2r3"])
def test_reference_building_blocks(model):
    rng = np.random.RandomState(7)
    for _ in range(20):
        v = rng.randn(6) * np.array([2, 2, 1, 2, 2, 1])
        X = mean_from_physical(model, rng.randn(6))
        # log inverts exp (|angles| < π)
        np.testing.assert_allclose(glog(model, gexp(model, v)), v, atol=1e-12)
        # Ad: X exp(v) X⁻¹ = exp(Ad(X) v)
        np.testing.assert_allclose(X @ gexp(model, v) @ np.linalg.inv(X), gexp(model, Ad(model, X) @ v), atol=1e-11)
        # Φ is the right Jacobian: exp(a + δ) ≈ exp(a) exp(Φ(a) δ)
        a = rng.randn(6) * 0.8
        d = rng.randn(6)
        h = 1e-6
        lhs = (glog(model, np.linalg.inv(gexp(model, a)) @ gexp(model, a + h * d)) - glog(model, np.linalg.inv(gexp(model, a)) @ gexp(model, a - h * d))) / (2 * h)
        np.testing.assert_allclose(lhs, Phi(model, a) @ d, atol=1e-7)
        # ad(v) = d/dt Ad(exp(t v)) at 0
        D = (Ad(model, gexp(model, h * v)) - Ad(model, gexp(model, -h * v))) / (2 * h)
        np.testing.assert_allclose(D, ad(model, v), atol=1e-7)
    # the paper's SE(2) Ad block: [[R, J t], [0, 1]], J = [[0, 1], [-1, 0]]
    X = mean_from_physical(model, [1.3, -0.4, 0.7, 0.2, 0.1, 0.3])
    A = Ad(model, X)
    np.testing.assert_allclose(A[:2, :2], rot(0.7), atol=1e-14)
    np.testing.assert_allclose(A[:2, 2], [-0.4, -1.3], atol=1e-14)
    if model == "se2r3":
        np.testing.assert_allclose(A[3:, 3:], np.eye(3), atol=1e-14)
        np.testing.assert_allclose(ad(model, rng.randn(6))[3:, 3:], 0.0, atol=0)


@pytest.mark.parametrize("model", ["se2se2", "se2r3"])
def test_paper_jacobians_match_finite_differences(model):
    """eq:calCFinal and eq:calH_model (used in the 1e-10 comparisons) equal the finite-difference
    derivatives of their definitions eq:C / eq:calH to 1e-7; so do the library's kernels."""
    from lgekf.core.registry import get_model

    kern = get_model(model).kernels
    worst = {"C": 0.0, "H": 0.0, "F": 0.0, "lib_C": 0.0, "lib_H": 0.0, "lib_F": 0.0}
    for case in random_cases(seed=11, n=120, wide_omega=model == "se2r3"):
        T = case["dt"]
        mu = mean_from_physical(model, case["x0"])
        C_fd = calC_fd(model, mu, T)
        H_fd = calH_fd(model, mu)
        F_fd = transition_ref(model, mu, T, C=C_fd)
        s = kern.state_from_physical(case["x0"])
        for key, a, b in [
            ("C", calC_paper(model, mu, T), C_fd),
            ("H", calH_paper(mu), H_fd),
            ("F", transition_ref(model, mu, T), F_fd),
            ("lib_C", kern.calC(s, T), C_fd),
            ("lib_H", kern.calH_position(s), H_fd),
            ("lib_F", kern.transition(s, T), F_fd),
        ]:
            err = _rel(np.asarray(a), b)
            worst[key] = max(worst[key], err)
            assert err < 1e-7, f"{key}: x0={case['x0']}, dt={T}: {err:.3g}\n{np.asarray(a)}\n{b}"
    for key, v in worst.items():
        _note((model, "fd", key), v)


# ---------------------------------------------------------------------------------------------
# The filters against the reference
# ---------------------------------------------------------------------------------------------


@pytest.mark.parametrize("model", ["se2se2", "se2r3"])
def test_predict_matches_reference(model):
    cls = CLASSES[model]
    sig = np.array([0.3, 0.2, 0.7])
    for i, case in enumerate(random_cases(seed=1 if model == "se2se2" else 2, wide_omega=model == "se2r3")):
        f = cls(dt=case["dt"], accel_std=sig, meas_std=case["r"], x0=case["x0"], P0=case["P0"])
        mu0 = mean_from_physical(model, case["x0"])
        np.testing.assert_allclose(f.mean, mu0, atol=1e-15, rtol=0)
        if i % 2:
            f.predict()
        else:
            f.predict(dt=case["dt"])
        mu_ref, P_ref = ref_predict(model, mu0, case["P0"], case["dt"], sig)
        where = f"case {i}: x0={case['x0'].tolist()}, dt={case['dt']}"
        e_mu, e_P = _rel(f.mean, mu_ref), _rel(f.P, P_ref)
        _note((model, "predict", "mean"), e_mu)
        _note((model, "predict", "P"), e_P)
        assert e_mu < TOL, f"{where}: mean error {e_mu:.3g}"
        assert e_P < TOL, f"{where}: P error {e_P:.3g}\n{f.P}\n{P_ref}"
        _check_physical(model, f, mu_ref, where)


@pytest.mark.parametrize("model", ["se2se2", "se2r3"])
def test_update_matches_reference(model):
    cls = CLASSES[model]
    for i, case in enumerate(random_cases(seed=3 if model == "se2se2" else 4, wide_omega=model == "se2r3")):
        f = cls(dt=0.1, accel_std=(0.1, 0.1, 0.1), meas_std=case["r"], x0=case["x0"], P0=case["P0"])
        mu0 = mean_from_physical(model, case["x0"])
        z = _measurement(case, mu0, case["P0"])
        nis = f.update(z)
        mu_ref, P_ref, nis_ref = ref_update(model, mu0, case["P0"], z, case["r"])
        where = f"case {i}: x0={case['x0'].tolist()}, r={case['r']}, innovation {case['innov']}"
        e_mu, e_P = _rel(f.mean, mu_ref), _rel(f.P, P_ref)
        e_nis = abs(nis - nis_ref) / max(1.0, nis_ref)
        _note((model, "update", "mean"), e_mu)
        _note((model, "update", "P"), e_P)
        _note((model, "update", "nis"), e_nis)
        assert e_mu < TOL, f"{where}: mean error {e_mu:.3g}"
        assert e_P < TOL, f"{where}: P error {e_P:.3g}\n{f.P}\n{P_ref}"
        assert e_nis < TOL, f"{where}: NIS {nis} vs {nis_ref}"
        assert f.nis == nis
        _check_physical(model, f, mu_ref, where)


@pytest.mark.parametrize("model", ["se2se2", "se2r3"])
def test_update_with_zero_innovation_keeps_mean(model):
    """z = h(μ): ν = 0, so μ⁺ = μ exactly and P⁺ = (I - Kℋ)P (Φ(0) = I)."""
    cls = CLASSES[model]
    rng = np.random.RandomState(5)
    for th in SPECIAL_ANGLES:
        x0 = np.array([3.0, -2.0, th, 1.0, 0.5, 0.3])
        P0 = random_spd(rng, "dense")
        f = cls(dt=0.1, accel_std=(0.1, 0.1, 0.1), meas_std=0.5, x0=x0, P0=P0)
        mu0 = f.mean
        f.update(mu0[:2, 2])
        np.testing.assert_allclose(f.mean, mu0, atol=1e-15, rtol=0)
        _, P_ref, _ = ref_update(model, mean_from_physical(model, x0), P0, mu0[:2, 2], 0.5)
        assert _rel(f.P, P_ref) < TOL


@pytest.mark.parametrize("model", ["se2se2", "se2r3"])
def test_sequence_matches_reference(model):
    """60 alternating predict/update steps (irregular dt) stay within 1e-10 of the reference."""
    cls = CLASSES[model]
    rng = np.random.RandomState(17 if model == "se2se2" else 18)
    sig = np.array([0.5, 0.3, 0.4])
    for run in range(4):
        x0 = np.array([rng.randn() * 5, rng.randn() * 5, rng.uniform(-3, 3), 2 + rng.rand(), rng.randn() * 0.3, rng.uniform(-0.8, 0.8)])
        P0 = random_spd(rng, "dense")
        r = 0.3
        f = cls(dt=0.1, accel_std=sig, meas_std=r, x0=x0, P0=P0)
        mu, P = mean_from_physical(model, x0), P0.copy()
        truth = mu.copy()
        for k in range(60):
            dt = float(rng.uniform(0.05, 0.3))
            f.predict(dt=dt)
            mu, P = ref_predict(model, mu, P, dt, sig)
            truth = truth @ gexp(model, Omega(model, truth, dt))
            z = truth[:2, 2] + r * rng.randn(2)
            nis = f.update(z)
            mu, P, nis_ref = ref_update(model, mu, P, z, r)
            e_mu, e_P = _rel(f.mean, mu), _rel(f.P, P)
            _note((model, "sequence", "mean"), e_mu)
            _note((model, "sequence", "P"), e_P)
            assert e_mu < TOL and e_P < TOL, f"run {run} step {k}: mean {e_mu:.3g}, P {e_P:.3g}"
            assert abs(nis - nis_ref) < TOL * max(1.0, nis_ref)


def test_report_max_discrepancies():
    """Print the worst relative discrepancies seen above (run with -s to see them)."""
    for key in sorted(MAX_SEEN, key=str):
        print(f"  max rel. discrepancy {key}: {MAX_SEEN[key]:.3g}")


@pytest.mark.parametrize("model", ["se2se2", "se2r3"])
def test_physical_angles_in_documented_range(model):
    """``x`` documents θ in (-π, π]; on SE(2)² ω is the log of T_d's rotation, atan2(sin, cos) ∈ [-π, π]
    (the inputs ±π denote the same rotation)."""
    for a in (math.pi, -math.pi, 3 * math.pi, -3 * math.pi):
        w = (a if abs(a) <= math.pi else 0.3) if model == "se2se2" else 0.2
        f = CLASSES[model](dt=0.1, accel_std=(0.1, 0.1, 0.1), meas_std=0.5, x0=[0.0, 0.0, a, 1.0, 0.0, w], P0=np.eye(6))
        x = f.x
        assert -math.pi < x[2] <= math.pi, f"θ = {a!r} -> {x[2]!r}"
        if model == "se2se2":
            assert -math.pi <= x[5] <= math.pi, f"ω = {w!r} -> {x[5]!r}"
            assert x[5] == math.atan2(f.mean[4, 3], f.mean[3, 3]), "ω must be the log of the stored rotation"
        np.testing.assert_allclose(f.mean, mean_from_physical(model, [0.0, 0.0, a, 1.0, 0.0, w]), atol=1e-15)
    if model == "se2se2":
        # |ω| > π is not representable (it would alias to ω - 2π): rejected, naming x0
        for w in (3 * math.pi, -3.5):
            with pytest.raises(ValueError, match="x0"):
                CLASSES[model](dt=0.1, accel_std=(0.1, 0.1, 0.1), meas_std=0.5, x0=[0.0, 0.0, 0.0, 1.0, 0.0, w], P0=np.eye(6))


def test_same_mean_same_prediction_at_omega_minus_pi():
    """SE(2)²: two filters holding the same group mean (T_d a rotation by π) must predict the same.
    Ω = Tω uses ω = log(R_ω) = atan2(sin, cos) of the stored rotation, both at construction and after
    an update, so a zero-innovation update (ν = 0, μ unchanged) cannot flip the turn direction."""
    kw = dict(dt=0.5, accel_std=(0.1, 0.1, 0.1), meas_std=1.0, x0=[0.0, 0.0, 0.0, 1.0, 0.0, -math.pi], P0=np.eye(6))
    a, b = SE2SE2Filter(**kw), SE2SE2Filter(**kw)
    b.update([0.0, 0.0])  # z = h(μ): ν = 0
    np.testing.assert_array_equal(a.mean, b.mean)
    a.predict()
    b.predict()
    np.testing.assert_allclose(a.mean, b.mean, atol=1e-12)
