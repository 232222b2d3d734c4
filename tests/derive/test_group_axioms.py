"""The group axioms over every group lgekf has: SE(2), SO(3), SE(3) and products (jaxlie's test battery, in numbers).

Each group is tested through its float64 implementation: the generated numba kernels where they exist
(``generated/se2.py``, ``generated/se3.py``), otherwise the closed forms of ``derive.lie`` compiled by
``sympy.lambdify`` with the generated (Taylor-safe) angle functions of ``generated/special.py``.  Conventions:
tangent order as in derive/lie (SE(3): x, y, z, φx, φy, φz); X = μ·exp(ε); Φ(v) with
log(exp(-v) exp(v + δ)) = Φ(v) δ + O(δ²).

Axioms: exp(0) = I; log(exp ξ) = ξ (|rotation angle| < π); X X^-1 = I; Ad(X) ξ = [X ξ^ X^-1]^∨; Ad(exp ξ) =
expm(ad ξ); Φ(v) equals the finite-difference Jacobian of δ ↦ log(exp(-v) exp(v + δ)).
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
import pytest
import sympy as sp
from scipy.linalg import expm

from lgekf.derive.lie import special as S
from lgekf.derive.lie.groups import SE2, SE3, SO3, Product, Rn
from lgekf.generated import se2 as gse2
from lgekf.generated import se3 as gse3
from lgekf.generated import special as gspecial

ANGLES = [0.0, 1e-12, 1e-6, 1e-3, 0.4, 1.3, 2.2, 3.0]


def _angle_module():
    """The generated angle functions f(x, sin x, cos x) as one-argument functions for lambdify."""
    return {f.__name__: (lambda g: lambda x: g(x, math.sin(x), math.cos(x)))(getattr(gspecial, f.__name__))
            for f in S.ANGLE_FUNCTIONS}


class Lambdified:
    """hat, vee, exp, log, inverse, Ad, ad, Φ of a derive.lie group, as float functions (sympy.lambdify)."""

    def __init__(self, G):
        self.G, self.n, self.m = G, G.dim, G.matrix_size
        v = sp.symbols(f"v0:{self.n}", real=True)
        Xs = sp.Matrix(self.m, self.m, lambda i, j: sp.Symbol(f"X{i}_{j}", real=True))
        mods = [_angle_module(), "math"]

        def vec(expr, args):
            return sp.lambdify(args, sp.Matrix(expr).tolist(), modules=mods)

        self._hat = vec(G.hat(list(v)), [v])
        self._exp = vec(G.exp(list(v)), [v])
        self._ad = vec(G.ad(list(v)), [v])
        self._jr = vec(G.right_jacobian(list(v)), [v])
        self._log = vec(G.log(Xs), [list(Xs)])
        self._inv = vec(G.inverse(Xs), [list(Xs)])
        self._Ad = vec(G.Ad(Xs), [list(Xs)])
        self._vee = vec(G.vee(Xs), [list(Xs)])

    def hat(self, v):
        return np.array(self._hat(list(v)), dtype=float)

    def vee(self, M):
        return np.array(self._vee(list(np.ravel(M))), dtype=float).ravel()

    def exp(self, v):
        return np.array(self._exp(list(v)), dtype=float)

    def log(self, X):
        return np.array(self._log(list(np.ravel(X))), dtype=float).ravel()

    def inverse(self, X):
        return np.array(self._inv(list(np.ravel(X))), dtype=float)

    def Ad(self, X):
        return np.array(self._Ad(list(np.ravel(X))), dtype=float)

    def ad(self, v):
        return np.array(self._ad(list(v)), dtype=float)

    def jr(self, v):
        return np.array(self._jr(list(v)), dtype=float)


class Generated:
    """The generated numba kernels of one group module (se2_*/se3_* and right_jacobian)."""

    def __init__(self, G, module, prefix):
        self.G, self.n, self.m = G, G.dim, G.matrix_size
        self.hat, self.vee = getattr(module, f"{prefix}_hat"), getattr(module, f"{prefix}_vee")
        self.exp, self.log = getattr(module, f"{prefix}_exp"), getattr(module, f"{prefix}_log")
        self.inverse, self.Ad = getattr(module, f"{prefix}_inverse"), getattr(module, f"{prefix}_adjoint")
        self.ad, self.jr = getattr(module, f"{prefix}_ad"), module.right_jacobian


GROUPS = {
    "SE2 (generated)": lambda: Generated(SE2, gse2, "se2"),
    "SE3 (generated)": lambda: Generated(SE3, gse3, "se3"),
    "SO3": lambda: Lambdified(SO3),
    "SE3": lambda: Lambdified(SE3),
    "SE3xR6": lambda: Lambdified(Product(SE3, Rn(6))),
    "SE3xSE3": lambda: Lambdified(Product(SE3, SE3)),
    "SE2xSE2": lambda: Lambdified(Product(SE2, SE2)),
}


@lru_cache(maxsize=None)
def group(name):
    return GROUPS[name]()


def _factors(G):
    return G.factors if isinstance(G, Product) else [G]


def tangents(g, seed=0):
    """Tangent vectors of every rotation angle in ANGLES (random axis per rotation block), other coordinates N(0, 1.5²)."""
    rng = np.random.default_rng(seed)
    out = []
    for a in ANGLES:
        v = 1.5 * rng.standard_normal(g.n)
        i = 0
        for f in _factors(g.G):
            rot = list(f.periodic_coordinates())
            if rot:
                u = rng.standard_normal(len(rot))
                u *= a / np.linalg.norm(u) if len(rot) > 1 else a / abs(u[0])
                v[[i + k for k in rot]] = u
            i += f.dim
        out.append(v)
    return out


NAMES = list(GROUPS)


@pytest.mark.parametrize("name", NAMES)
def test_exp_of_zero_is_identity(name):
    g = group(name)
    assert np.array_equal(g.exp(np.zeros(g.n)), np.eye(g.m))
    assert np.array_equal(g.log(np.eye(g.m)), np.zeros(g.n))


@pytest.mark.parametrize("name", NAMES)
def test_log_of_exp_is_identity(name):
    g = group(name)
    for v in tangents(g):
        assert np.allclose(g.log(g.exp(v)), v, rtol=1e-12, atol=1e-13), v


@pytest.mark.parametrize("name", NAMES)
def test_hat_vee_and_inverse(name):
    g = group(name)
    for v in tangents(g, seed=1):
        assert np.array_equal(g.vee(g.hat(v)), v)
        X = g.exp(v)
        assert np.allclose(X @ g.inverse(X), np.eye(g.m), atol=1e-13)
        assert np.allclose(g.inverse(X) @ X, np.eye(g.m), atol=1e-13)


@pytest.mark.parametrize("name", NAMES)
def test_Ad_is_conjugation(name):
    g = group(name)
    rng = np.random.default_rng(2)
    for v in tangents(g, seed=2):
        X, w = g.exp(v), rng.standard_normal(g.n)
        assert np.allclose(g.hat(g.Ad(X) @ w), X @ g.hat(w) @ g.inverse(X), atol=1e-12)


@pytest.mark.parametrize("name", NAMES)
def test_Ad_of_exp_is_expm_of_ad(name):
    g = group(name)
    for v in tangents(g, seed=3):
        assert np.allclose(g.Ad(g.exp(v)), expm(g.ad(v)), atol=1e-11)


@pytest.mark.parametrize("name", NAMES)
def test_right_jacobian_by_finite_differences(name):
    """Φ(v) δ ≈ log(exp(-v) exp(v + δ)), central differences with h = 1e-6 (error ~1e-10)."""
    g = group(name)
    h = 1e-6
    for v in tangents(g, seed=4):
        E = g.inverse(g.exp(v))
        fd = np.empty((g.n, g.n))
        for k in range(g.n):
            d = np.zeros(g.n)
            d[k] = h
            fd[:, k] = (g.log(E @ g.exp(v + d)) - g.log(E @ g.exp(v - d))) / (2 * h)
        assert np.allclose(g.jr(v), fd, atol=1e-8), (v, np.abs(g.jr(v) - fd).max())
