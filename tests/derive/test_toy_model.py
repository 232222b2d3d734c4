"""Adding a model = one definition file: a throw-away toy model, written into a temporary folder, goes
through the same emitter as the real models and its generated filter runs.

The toy: an SE(2) pose doing a random walk, X_{k+1} = X_k·exp([T n]^∧), n ~ N(0, diag(σ²)) (Ω = 0, G = T·I₃).
So the prediction is μ ← μ, P ← P + T² diag(σ²) exactly, and a position update must equal the LG-EKF
update written out densely here (ℋ = [R(θ), 0], ν = K e, μ⁺ = μ·expm(ν^∧), P⁺ = Φ(ν)(I − Kℋ)PΦ(ν)ᵀ).
"""

from __future__ import annotations

import importlib
import math
import sys
import textwrap

import numpy as np
import pytest
from scipy.linalg import expm

TOY = '''
"""A toy model: an SE(2) pose doing a random walk (Ω = 0, G = T I)."""
import sympy as sp

from lgekf.derive.lie.special import wrap
from lgekf.derive.models.base import COMMON, SE2, MotionModel, dt, theta, x, y

c, s = sp.symbols("c_theta s_theta", real=True)


class Walk(MotionModel):
    display_name = "toy random walk on SE(2)"
    description = "toy random walk on SE(2)"
    group = SE2
    physical = (x, y, theta)
    internal = (x, y, c, s)
    carried = ((theta, c, s),)
    noise_names = ("sigma_x", "sigma_y", "sigma_theta")
    default_accel_std = (1.0, 1.0, 0.1)
    matched_noise = ("v", "v", "w")
    angles = (2,)

    def mean(self):
        return SE2.element(sp.cos(theta), sp.sin(theta), x, y)

    def internal_of(self, X):
        return [X[0, 2], X[1, 2], X[0, 0], X[1, 0]]

    def internal_from_physical(self):
        return [x, y, sp.cos(theta), sp.sin(theta)]

    def physical_from_internal(self):
        return [x, y, wrap(sp.atan2(s, c))]

    def Omega_of(self, X):
        return sp.zeros(3, 1)

    def noise_input(self):
        return dt * sp.eye(3)

    def position(self, X):
        return X[0, 2], X[1, 2]

    def heading(self, X):
        return X[0, 0], X[1, 0]

    def from_common(self):
        return list(COMMON[:3])

    def world_velocity(self):
        return sp.zeros(2, 1)


MODEL = Walk()
'''


pytestmark = pytest.mark.slow  # one SymPy derivation of the toy (about 10 s); CI runs it


@pytest.fixture(scope="module")
def toy(tmp_path_factory):
    from lgekf.derive.codegen.build import write_all

    root = tmp_path_factory.mktemp("toy")
    defs = root / "defs"
    defs.mkdir()
    (defs / "walk.py").write_text(textwrap.dedent(TOY))
    pkg = root / "toygen"
    names = write_all(pkg, jobs=1, models_dir=defs)
    sys.path.insert(0, str(root))
    try:
        yield importlib.import_module("toygen.walk"), importlib.import_module("toygen.registry"), names
    finally:
        sys.path.remove(str(root))


def _hat(v):
    return np.array([[0.0, -v[2], v[0]], [v[2], 0.0, v[1]], [0.0, 0.0, 0.0]])


def _phi(v, terms=40):
    ad = np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [0.0, 0.0, 0.0]])
    out, term = np.zeros((3, 3)), np.eye(3)
    for m in range(terms + 1):
        out += (-1) ** m / math.factorial(m + 1) * term
        term = term @ ad
    return out


def test_toy_definition_is_emitted_with_registry_entry(toy):
    walk, registry, names = toy
    assert "walk.py" in names and "registry.py" in names
    entry = registry.MODELS["walk"]
    assert entry["state_names"] == ("x", "y", "theta")
    assert set(entry["measurements"]) == {"position", "pose"}
    assert entry["periodic_tangent"] == (2,)


def test_toy_filter_runs_and_matches_dense_lg_ekf(toy):
    walk, _, _ = toy
    rng = np.random.default_rng(4)
    for th in (0.0, 1e-9, 2.0, -(math.pi - 1e-9)):
        xp = np.array([1.0, -2.0, th])
        A = rng.normal(size=(3, 3))
        P = A @ A.T + 0.1 * np.eye(3)
        iu = np.triu_indices(3)
        s = walk.state_from_physical(xp)
        p = P[iu].copy()
        sig, T, r = np.array([0.3, 0.2, 0.1]), 0.5, 0.4
        walk.predict(s, p, T, *sig)
        P_pred = P + T * T * np.diag(sig**2)
        np.testing.assert_allclose(walk.state_to_physical(s), xp, atol=1e-15)
        np.testing.assert_allclose(p, P_pred[iu], rtol=1e-14)
        z = xp[:2] + rng.normal(size=2)
        nis = walk.update_position(s, p, z[0], z[1], r)
        # dense reference
        mu = np.array([[math.cos(th), -math.sin(th), xp[0]], [math.sin(th), math.cos(th), xp[1]], [0, 0, 1.0]])
        H = np.hstack([mu[:2, :2], np.zeros((2, 1))])
        S = H @ P_pred @ H.T + r * r * np.eye(2)
        K = P_pred @ H.T @ np.linalg.inv(S)
        e = z - xp[:2]
        nu = K @ e
        mu_new = mu @ expm(_hat(nu))
        P_new = _phi(nu) @ (np.eye(3) - K @ H) @ P_pred @ _phi(nu).T
        np.testing.assert_allclose(walk.group_mean(s), mu_new, atol=1e-12)
        full = np.zeros((3, 3))
        full[iu] = p
        full = full + np.triu(full, 1).T
        np.testing.assert_allclose(full, P_new, rtol=1e-11, atol=1e-13)
        assert nis == pytest.approx(float(e @ np.linalg.solve(S, e)), rel=1e-12)


def test_toy_batch_loop_runs(toy):
    walk, _, _ = toy
    B, K = 3, 20
    z = np.cumsum(np.random.default_rng(0).normal(size=(B, K, 2)), axis=1)
    out_x, out_p, out_nis = np.empty((B, K, 3)), np.empty((B, 0, 6)), np.empty((B, K))
    p0 = np.tile(np.eye(3)[np.triu_indices(3)], (B, 1))
    walk.run_batch_position(z, np.full((B, K), 1.0), np.zeros((B, 3)), p0, np.array([1.0, 1.0, 0.1]), np.array([0.5]),
                            out_x, out_p, out_nis)
    assert np.all(np.isfinite(out_x)) and np.all(out_nis > 0)
    assert np.max(np.abs(out_x[:, -1, :2] - z[:, -1])) < 3.0  # tracks the walk
