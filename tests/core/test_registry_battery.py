"""The same battery for every registry model × every measurement that fits it.

The reference is a dense, generic LG-EKF in numpy built from the model's *definition* (SymPy, lambdified):
the group matrices of μ, Ω(X), G and h(X) come from ``derive/models/<name>.py`` and
``derive/measurements/<meas>.py``; everything else is numerics independent of the emitter and of the
generated code: exp/log of the group through scipy's expm/logm block by block, Ad by conjugation, ad from
the matrix bracket, Φ as the 40-term series, 𝒞 and ℋ as central differences of their definitions
(eq:C, eq:calH).  Central differences are accurate to about 1e-9, so the comparisons use 1e-6 relative;
the 1e-10/1e-12 comparisons against the paper's printed 𝒞 and ℋ are in test_lg_reference.py and
test_pose_reference.py for the paper's two models.  The 3-D models (SE(3) factors: matrix logarithm by scipy)
get the same battery; their 𝒞 and ℋ are derived to first order (``MotionModel.perturbed_mean``), so the central
differences of the exact exponential here are what checks that shortcut.

Also per pair: ``filter_batch`` equals the class API; the filter is consistent on simulations of its own
model (mean NEES ≈ n, NIS ≈ m); bad measurements give one clear ValueError.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import sympy as sp
from scipy.linalg import expm, logm
from scipy.spatial.transform import Rotation

import lgekf
from lgekf.core.registry import ALL_MODELS as MODELS  # every space: the battery covers the 3-D models too
from lgekf.core.registry import SPACES
from lgekf.derive.lie.groups import SE3, Product, Rn
from lgekf.derive.lie.so3 import rotation_vector_entry
from lgekf.derive.lie.special import ANGLE_FUNCTIONS, wrap
from lgekf.derive.measurements import load_measurements
from lgekf.derive.models import load_models

DEFS = load_models()
MEAS = load_measurements()
PAIRS = [(m, k) for m, spec in MODELS.items() for k in spec.measurements]
#: CI budget (15 min on 2 cores): the SE(3) models' pose kernels and SE(3)×SE(3)'s batch kernels take minutes of CPU to
#: compile cold. These pairs run with `-m budget` only (`pytest -m budget tests/core/test_registry_battery.py`):
#: SE(3)×SE(3)'s batch = class and NEES/NIS checks, its dense-reference check with poses, and SE(3)×R⁶'s batch = class
#: and NEES/NIS with poses. What runs always: every model's dense-reference check with positions and se3r6's with poses
#: (pose3's kernels exact against the numpy LG-EKF), se3r6's batch = class and NEES/NIS with positions, and every
#: log-det check.
BUDGET_BATCH = {("se3se3", "position3"), ("se3se3", "pose3"), ("se3r6", "pose3")}
BUDGET_CONSISTENT = {("se3se3", "position3"), ("se3se3", "pose3"), ("se3r6", "pose3")}
BUDGET_REFERENCE = {("se3se3", "pose3")}


def _pairs(slow: set) -> list:
    return [pytest.param(m, k, marks=pytest.mark.budget) if (m, k) in slow else (m, k) for m, k in PAIRS]


DT = sp.Symbol("dt", positive=True)


# ------------------------------------------------------------------------------ dense group numerics
def factors(group):
    """[(kind, algebra dim, matrix size)] of a group from derive.lie.groups."""
    fs = group.factors if isinstance(group, Product) else [group]
    out = []
    for f in fs:
        if isinstance(f, Rn):
            out.append(("rn", f.dim, f.dim + 1))
        elif getattr(f, "_cls", f) is SE3:
            out.append(("se3", 6, 4))
        else:
            out.append(("se2", 3, 3))
    return out


def _skew(w):
    return np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])


class Dense:
    def __init__(self, group):
        self.f = factors(group)
        self.n = sum(d for _, d, _ in self.f)
        self.size = sum(s for _, _, s in self.f)

    def _blocks(self):
        a = m = 0
        for kind, d, s in self.f:
            yield kind, slice(a, a + d), slice(m, m + s)
            a, m = a + d, m + s

    def hat(self, v):
        M = np.zeros((self.size, self.size))
        for kind, sa, sm in self._blocks():
            w = v[sa]
            if kind == "se2":
                M[sm, sm] = [[0, -w[2], w[0]], [w[2], 0, w[1]], [0, 0, 0]]
            elif kind == "se3":
                B = np.zeros((4, 4))
                B[:3, :3] = _skew(w[3:])
                B[:3, 3] = w[:3]
                M[sm, sm] = B
            else:
                B = np.zeros((len(w) + 1, len(w) + 1))
                B[:-1, -1] = w
                M[sm, sm] = B
        return M

    def vee(self, M):
        v = np.zeros(self.n)
        for kind, sa, sm in self._blocks():
            B = M[sm, sm]
            if kind == "se2":
                v[sa] = [B[0, 2], B[1, 2], B[1, 0]]
            elif kind == "se3":
                v[sa] = [B[0, 3], B[1, 3], B[2, 3], B[2, 1], B[0, 2], B[1, 0]]
            else:
                v[sa] = B[:-1, -1]
        return v

    def exp(self, v):
        return expm(self.hat(v))

    def log(self, X):
        v = np.zeros(self.n)
        for kind, sa, sm in self._blocks():
            B = X[sm, sm]
            if kind == "se2":
                L = np.real(logm(B))
                v[sa] = [L[0, 2], L[1, 2], L[1, 0]]
            elif kind == "se3":
                L = np.real(logm(B))
                v[sa] = [L[0, 3], L[1, 3], L[2, 3], L[2, 1], L[0, 2], L[1, 0]]
            else:
                v[sa] = B[:-1, -1]
        return v

    def Ad(self, X):
        Xi = np.linalg.inv(X)
        return np.column_stack([self.vee(X @ self.hat(e) @ Xi) for e in np.eye(self.n)])

    def Phi(self, v, terms=40):
        V = self.hat(v)
        ad = np.column_stack([self.vee(V @ self.hat(e) - self.hat(e) @ V) for e in np.eye(self.n)])
        out, term = np.zeros((self.n, self.n)), np.eye(self.n)
        for m in range(terms + 1):
            out += (-1) ** m / math.factorial(m + 1) * term
            term = term @ ad
        return out


def _rotation_vector_entry(k, *r):
    """[log_SO(3)(R)]^∨_k by SciPy (an implementation independent of derive.lie.so3)."""
    return Rotation.from_matrix(np.reshape(np.asarray(r, dtype=float), (3, 3))).as_rotvec()[int(k)]


def _numeric(expr, args):
    """lambdify with the angle functions of derive.lie.special evaluated through their definitions (in
    mpmath precision; the value at 0 is the limit). They are renamed first: the NumPy printer would print
    an unknown ``sinc`` with NumPy's convention sin(πx)/(πx)."""
    def value(f):
        return lambda x: float(f.definition(sp.Float(x, 30)).evalf(30)) if x != 0 else float(f.value_at_zero())

    expr = sp.sympify(expr).replace(lambda e: isinstance(e, ANGLE_FUNCTIONS), lambda e: sp.Function(f"af_{type(e).__name__}")(*e.args))
    expr = expr.replace(lambda e: isinstance(e, wrap), lambda e: sp.Function("af_wrap")(*e.args))
    expr = expr.replace(lambda e: isinstance(e, rotation_vector_entry), lambda e: sp.Function("af_rotvec")(*e.args))
    mods = [{f"af_{f.__name__}": value(f) for f in ANGLE_FUNCTIONS} | {"af_wrap": lambda a: (a + math.pi) % (2 * math.pi) - math.pi,
                                                                       "af_rotvec": _rotation_vector_entry},
            "math", "numpy"]
    return sp.lambdify(args, expr, modules=mods)


class Reference:
    """The dense LG-EKF of one model (and its measurements) from its definition."""

    def __init__(self, name):
        d = DEFS[name]
        self.d = d
        self.G = Dense(d.group)
        self.mean = _numeric(d.mean_physical, [list(d.physical)])
        size = self.G.size
        M = sp.Matrix(size, size, lambda i, j: sp.Symbol(f"M{i}_{j}", real=True))
        self.M = M
        self.Omega = _numeric(d.Omega_of(M), [list(M), DT])
        self.noise_input = _numeric(d.noise_input(), [list(d.physical), DT])
        self.noise_stds = _numeric(sp.Matrix(d.noise_stds()), [list(d.noise_symbols)])
        self.h = {k: _numeric(MEAS[k].h(d, M), [list(M)]) for k in MODELS[name].measurements}
        self.Gp = {k: Dense(MEAS[k].group) for k in MODELS[name].measurements}
        self.element = {k: _numeric(MEAS[k].element(MEAS[k].z_symbols), [list(MEAS[k].z_symbols)]) for k in MODELS[name].measurements}

    def Om(self, X, T):
        return np.asarray(self.Omega(X.ravel(), T), dtype=float).ravel()

    def predict(self, x, P, T, q):
        G = self.G
        mu = np.asarray(self.mean(x), dtype=float)
        Om = self.Om(mu, T)
        h = 1e-6
        C = np.column_stack([(self.Om(mu @ G.exp(h * e), T) - self.Om(mu @ G.exp(-h * e), T)) / (2 * h) for e in np.eye(G.n)])
        F = G.Ad(G.exp(-Om)) + G.Phi(Om) @ C
        Gn = G.Phi(Om) @ np.asarray(self.noise_input(x, T), dtype=float)
        S = np.diag(np.asarray(self.noise_stds(q), dtype=float).ravel() ** 2)
        return mu @ G.exp(Om), F @ P @ F.T + Gn @ S @ Gn.T

    def update(self, meas, mu, P, z, r):
        G, Gp = self.G, self.Gp[meas]
        hmu = np.asarray(self.h[meas](mu.ravel()), dtype=float)
        hinv = np.linalg.inv(hmu)
        hh = 1e-6
        H = np.column_stack([(Gp.log(hinv @ np.asarray(self.h[meas]((mu @ G.exp(hh * e)).ravel()), dtype=float))
                              - Gp.log(hinv @ np.asarray(self.h[meas]((mu @ G.exp(-hh * e)).ravel()), dtype=float))) / (2 * hh)
                             for e in np.eye(G.n)])
        R = np.diag(_per_entry(meas, r) ** 2)
        S = H @ P @ H.T + R
        K = np.linalg.solve(S, H @ P).T
        e = Gp.log(hinv @ np.asarray(self.element[meas](z), dtype=float))
        nu = K @ e
        Ph = G.Phi(nu)
        return mu @ G.exp(nu), Ph @ (np.eye(G.n) - K @ H) @ P @ Ph.T, float(e @ np.linalg.solve(S, e))


# ------------------------------------------------------------------------------ cases
def _common(space, rng):
    """A random common state of ``space``: position, attitude, body velocity (mostly forward), rate."""
    if SPACES[space]["dim"] == 2:
        return np.array([rng.normal() * 5, rng.normal() * 5, rng.uniform(-3, 3), 2 + rng.random(), 0.3 * rng.normal(),
                         rng.uniform(-1, 1)])
    return np.concatenate([rng.normal(size=3) * 5, [rng.uniform(-1, 1), rng.uniform(-0.6, 0.6), rng.uniform(-3, 3)],
                           [2 + rng.random(), 0.3 * rng.normal(), 0.3 * rng.normal()], rng.uniform(-1, 1, size=3)])


def _start(space):
    """A fixed common start of ``space`` (level, moving forward at 2 m/s, turning at 0.2 rad/s)."""
    return [0, 0, 0.3, 2.0, 0.0, 0.2] if SPACES[space]["dim"] == 2 else [0, 0, 0, 0.1, -0.1, 0.3, 2.0, 0, 0, 0.05, 0.0, 0.2]


def _case(name, rng):
    spec = MODELS[name]
    x = lgekf.state_from_common(name, _common(spec.space, rng))
    A = rng.normal(size=(spec.n, spec.n))
    P = A @ A.T / spec.n + 0.05 * np.eye(spec.n)
    q = np.asarray(spec.default_accel_std) * (0.5 + rng.random())
    return x, P, q


def _per_entry(meas, r):
    """The std of each entry of z from the measurement's noise stds (its ``noise_inputs``; one std for all)."""
    spec = lgekf.core.registry.get_measurement(meas)
    r = np.atleast_1d(np.asarray(r, dtype=float))
    return r[list(spec.noise_inputs)] if spec.noise_inputs is not None and r.size > 1 else np.broadcast_to(r, (spec.dim,))


def _meas_std(meas):
    return {"pose": (0.4, 0.3, 0.08), "pose3": (0.4, 0.08)}.get(meas, 0.4)


def _rel(a, b):
    return float(np.max(np.abs(np.asarray(a) - b)) / max(1e-300, np.max(np.abs(b))))


@pytest.mark.parametrize("name,meas", _pairs(BUDGET_REFERENCE))
def test_predict_and_update_match_the_dense_reference(name, meas):
    ref = Reference(name)
    rng = np.random.default_rng(abs(hash((name, meas))) % 2**32)
    for _ in range(6):
        x, P, q = _case(name, rng)
        T = float(rng.uniform(0.05, 0.5))
        f = lgekf.make_filter(name, dt=T, accel_std=q, meas_std=_meas_std(meas), x0=x, P0=P, measurement=meas)
        f.predict()
        mu_ref, P_ref = ref.predict(x, P, T, q)
        assert _rel(f.mean, mu_ref) < 1e-9 and _rel(f.P, P_ref) < 1e-6, (name, _rel(f.mean, mu_ref), _rel(f.P, P_ref))
        dim = SPACES[MODELS[name].space]["dim"]
        m = MODELS[name].measurement(meas).dim
        # the position, then (a pose) the model's heading or attitude angles, which follow it in every physical state
        z = np.array(f.x[:m]) + np.concatenate([rng.normal(size=dim) * 0.5, rng.normal(size=m - dim) * 0.1])
        nis = f.update(z)
        mu_u, P_u, nis_ref = ref.update(meas, mu_ref, P_ref, z, _meas_std(meas))
        assert _rel(f.mean, mu_u) < 1e-6, (name, meas, _rel(f.mean, mu_u))
        assert _rel(f.P, 0.5 * (P_u + P_u.T)) < 1e-6, (name, meas, _rel(f.P, P_u))
        assert nis == pytest.approx(nis_ref, rel=1e-6)


@pytest.mark.parametrize("name,meas", _pairs(BUDGET_BATCH))
def test_batch_equals_class(name, meas):
    rng = np.random.default_rng(5)
    B, K = 3, 25
    x, P, q = _case(name, rng)
    m = MODELS[name].measurement(meas).dim
    z = np.cumsum(rng.normal(size=(B, K, m)) * 0.3, axis=1) + np.linspace(0, 5, K)[None, :, None]
    dts = rng.uniform(0.05, 0.3, size=(B, K))
    est, cov, nis = lgekf.filter_batch(name, z, dt=dts, accel_std=q, meas_std=_meas_std(meas), x0=np.tile(x, (B, 1)), P0=P,
                                       measurement=meas, return_cov=True, return_nis=True)
    for b in range(B):
        f = lgekf.make_filter(name, dt=0.1, accel_std=q, meas_std=_meas_std(meas), x0=x, P0=P, measurement=meas)
        for k in range(K):
            f.predict(dts[b, k])
            assert f.update(z[b, k]) == pytest.approx(nis[b, k], rel=1e-12, abs=1e-12)
            np.testing.assert_allclose(est[b, k], f.x, rtol=1e-12, atol=1e-12)
            # the batch's fused step contracts FMAs (derive/codegen/families/fused.py), the class's update does not: on
            # the 12-dimensional SE(3) updates the two round apart by up to ~3e-14 per step on entries of order 0.01-0.2
            # (SE(3)xSE(3)'s longer expressions: 1.3e-13 after 25 steps)
            np.testing.assert_allclose(cov[b, k], f.P, rtol=1e-12, atol=1e-12)


def _tangent_errors(ref, est, truth, angles):
    out = np.empty_like(est)
    for i, (e, t) in enumerate(zip(est, truth)):
        d = ref.G.log(np.linalg.inv(np.asarray(ref.mean(e), dtype=float)) @ np.asarray(ref.mean(t), dtype=float))
        for a in angles:
            d[a] = (d[a] + math.pi) % (2 * math.pi) - math.pi
        out[i] = d
    return out


@pytest.mark.slow
@pytest.mark.parametrize("name,meas", _pairs(BUDGET_CONSISTENT))
def test_consistent_on_its_own_model(name, meas):
    """Simulated with the model's own exact motion and measurements: mean NEES ≈ n and NIS ≈ m."""
    spec = MODELS[name]
    k = spec.kernels
    rng = np.random.default_rng(17)
    B, K, T = 80, 40, 0.1
    x0 = np.tile(lgekf.state_from_common(name, _start(spec.space)), (B, 1))
    q = np.asarray(spec.default_accel_std) * 0.5
    stds = q[list(spec.noise_inputs)]
    truth = np.empty((B, K + 1, spec.n))
    k.simulate_batch(x0, np.full((B, K), T), np.ascontiguousarray(rng.standard_normal((B, K, len(stds))) * stds), truth)
    m = spec.measurement(meas).dim
    r = _per_entry(meas, _meas_std(meas))
    z = np.empty((B * K, m))
    getattr(k, f"measure_batch_{meas}")(np.ascontiguousarray(truth[:, 1:].reshape(-1, spec.n)),
                                         np.ascontiguousarray(rng.standard_normal((B * K, m)) * r), z)
    est, cov, nis = lgekf.filter_batch(name, z.reshape(B, K, m), dt=T, accel_std=q, meas_std=_meas_std(meas), x0=x0,
                                       P0=np.eye(spec.n) * 1e-8, measurement=meas, return_cov=True, return_nis=True)
    ref = Reference(name)
    skip = 10
    e = _tangent_errors(ref, est[:, skip:].reshape(-1, spec.n), truth[:, skip + 1:].reshape(-1, spec.n), spec.angles)
    sol = np.linalg.solve(cov[:, skip:].reshape(-1, spec.n, spec.n), e[..., None])[..., 0]
    ne = np.einsum("ij,ij->i", e, sol)
    assert abs(ne.mean() / spec.n - 1) < 0.15, (name, meas, ne.mean())
    assert abs(nis[:, skip:].mean() / m - 1) < 0.1, (name, meas, nis[:, skip:].mean())


@pytest.mark.parametrize("name,meas", PAIRS)
def test_wrong_measurement_shape_is_one_clear_error(name, meas):
    spec = MODELS[name]
    x, P, q = _case(name, np.random.default_rng(0))
    f = lgekf.make_filter(name, dt=0.1, accel_std=q, meas_std=_meas_std(meas), x0=x, P0=P, measurement=meas)
    with pytest.raises(ValueError, match=r"^z: expected shape"):
        f.update(np.zeros(4))
    with pytest.raises(ValueError, match=r"^z: expected shape"):
        lgekf.filter_batch(name, np.zeros((2, 3, 4)), dt=0.1, accel_std=q, meas_std=_meas_std(meas), x0=np.tile(x, (2, 1)), P0=P,
                           measurement=meas)
    assert spec.measurement(meas).dim in (2, 3, 6)


def test_every_model_refuses_what_does_not_fit_with_its_reason():
    for name, spec in MODELS.items():
        for meas, why in spec.refused.items():
            with pytest.raises(ValueError, match="no heading|no attitude|-D space"):
                lgekf.make_filter(name, dt=0.1, accel_std=spec.default_accel_std, meas_std=(0.3, 0.3, 0.1),
                                  x0=np.zeros(spec.n) + 1.0, P0=np.eye(spec.n), measurement=meas)
            assert why


@pytest.mark.parametrize("name,meas", PAIRS)
def test_innovation_logdet_is_log_det_of_s(name, meas):
    """``innovation_logdet_<meas>``: log det(ℋPℋᵀ + R) (the expanded determinant for m ≤ 3, the LDLᵀ pivots beyond:
    derive/codegen/families/smoother.py) against numpy's slogdet of the same S."""
    from lgekf.core.covariance import pack

    spec = MODELS[name]
    k = spec.kernels
    rng = np.random.default_rng(23)
    x, P, _ = _case(name, rng)
    s = k.state_from_physical(x)
    r = np.atleast_1d(np.asarray(_meas_std(meas), dtype=float))
    H = np.asarray(getattr(k, f"calH_{meas}")(s))
    S = H @ P @ H.T + np.diag(_per_entry(meas, r) ** 2)
    got = getattr(k, f"innovation_logdet_{meas}")(s, pack(P), *r)
    assert got == pytest.approx(np.linalg.slogdet(S)[1], rel=1e-12, abs=1e-12)
