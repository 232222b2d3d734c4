"""The generated group operations of every model: retract (μ·exp ε), between (log(μ_s⁻¹μ_t)) and Φ_G.

Checked against dense matrix exp/log of the model's group matrix (``group_mean``), independent of the
generated closed forms, for every registry model, at ordinary and near-zero rotation angles.
"""

import numpy as np
import pytest

from lgekf.core.registry import MODELS, get_model

RNG = np.random.default_rng(7)


def _expm(A):
    """Matrix exponential by scaling and squaring of a Taylor series (dense reference)."""
    k = max(0, int(np.ceil(np.log2(max(np.abs(A).sum(), 1e-300)))) + 4)
    B = A / 2.0**k
    E, term = np.eye(len(A)), np.eye(len(A))
    for i in range(1, 30):
        term = term @ B / i
        E = E + term
    for _ in range(k):
        E = E @ E
    return E


def _random_state(spec, scale):
    x = RNG.normal(size=len(spec.state_names)) * scale
    return spec.kernels.state_from_physical(x)


def _hat_blocks(spec, eps):
    """[ε]^∧ of the model's group, built from group_mean's block structure (SE(2) or Rⁿ factors)."""
    k = spec.kernels
    G0 = k.group_mean(k.state_from_physical(np.zeros(len(spec.state_names))))
    n = len(eps)
    # probe each tangent direction with a tiny retract and read the generator from the group matrix
    gens = []
    for i in range(n):
        s0 = k.state_from_physical(np.zeros(len(spec.state_names)))
        e = np.zeros(n)
        e[i] = 1e-7
        k.retract(s0, e)
        gens.append((k.group_mean(s0) - G0) / 1e-7)
    return sum(eps[i] * np.round(gens[i], 5) for i in range(n))


@pytest.mark.parametrize("name", sorted(MODELS))
@pytest.mark.parametrize("angle_scale", [1.0, 1e-9])
def test_retract_matches_dense_exponential(name, angle_scale):
    spec = get_model(name)
    k = spec.kernels
    for _ in range(5):
        s = _random_state(spec, 1.0)
        eps = RNG.normal(size=k.between(s, s).shape[0])
        for i in spec.periodic_tangent:
            eps[i] *= angle_scale
        t = s.copy()
        k.retract(t, eps)
        dense = k.group_mean(s) @ _expm(_hat_blocks(spec, eps))
        np.testing.assert_allclose(k.group_mean(t), dense, atol=1e-12)


@pytest.mark.parametrize("name", sorted(MODELS))
def test_between_inverts_retract(name):
    spec = get_model(name)
    k = spec.kernels
    for scale in (1.0, 1e-9, 0.0):
        s = _random_state(spec, 2.0)
        eps = RNG.normal(size=k.between(s, s).shape[0])
        for i in spec.periodic_tangent:
            eps[i] = np.clip(eps[i], -3.0, 3.0) * (scale if scale else 1.0)
        if scale == 0.0:
            eps[:] = 0.0
        t = s.copy()
        k.retract(t, eps)
        np.testing.assert_allclose(k.between(s, t), eps, atol=1e-11)


@pytest.mark.parametrize("name", sorted(MODELS))
def test_between_wraps_euclidean_angles(name):
    """An angle coordinate of a Euclidean model differs by the wrapped difference, as on the group."""
    spec = get_model(name)
    k = spec.kernels
    for i in spec.angles:
        if i in spec.periodic_tangent:
            continue
        x = np.zeros(len(spec.state_names))
        y = x.copy()
        x[i], y[i] = 3.0, -3.0
        d = k.between(k.state_from_physical(x), k.state_from_physical(y))
        assert d[i] == pytest.approx(2 * np.pi - 6.0, abs=1e-12)


@pytest.mark.parametrize("name", sorted(MODELS))
@pytest.mark.parametrize("angle", [0.7, 1e-9, 0.0])
def test_right_jacobian_by_differences(name, angle):
    """log(exp(-ε) exp(ε + δ)) ≈ Φ_G(ε) δ, with Φ_G⁻¹ its inverse."""
    spec = get_model(name)
    k = spec.kernels
    n = k.between(*(2 * [k.state_from_physical(np.zeros(len(spec.state_names)))])).shape[0]
    eps = RNG.normal(size=n) * 0.8
    for i in spec.periodic_tangent:
        eps[i] = angle
    s0 = k.state_from_physical(np.zeros(len(spec.state_names)))
    a = s0.copy()
    k.retract(a, eps)
    J = np.empty((n, n))
    h = 1e-6
    for j in range(n):
        cols = []
        for sgn in (1.0, -1.0):
            d = eps.copy()
            d[j] += sgn * h
            b = s0.copy()
            k.retract(b, d)
            cols.append(k.between(a, b))
        J[:, j] = (cols[0] - cols[1]) / (2 * h)
    np.testing.assert_allclose(k.right_jacobian(eps), J, atol=1e-8)
    np.testing.assert_allclose(k.right_jacobian(eps) @ k.right_jacobian_inv(eps), np.eye(n), atol=1e-12)
