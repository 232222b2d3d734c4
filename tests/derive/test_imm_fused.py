"""The generated fused kernels of the IMM (derive/codegen/mixing.py) against the general kernels they replace.

``mix_transport`` against ``between`` + ``right_jacobian_inv`` + a dense congruence; ``between_add`` against
``between``; ``common_of_state`` against ``physical_to_common`` / ``physical_to_common_jacobian``;
``state_of_common`` against ``common_to_state`` / ``state_from_physical`` / ``common_jacobian``.  Every registry
model, random states with relative angles up to ±3 rad and near 0 (the Taylor branches).
"""

from __future__ import annotations

import numpy as np
import pytest

from lgekf.core.covariance import pack, unpack
from lgekf.core.registry import MODELS, get_model


def _random_pair(spec, rng, scale):
    """Two internal states of the model (physical states a small or a large step apart)."""
    n = len(spec.state_names)
    xa = rng.normal(size=n)
    xa[3] = 2.0 + abs(xa[3])  # away from speed 0 (the heading of a velocity)
    xb = xa + scale * rng.normal(size=n)
    k = spec.kernels
    return k.state_from_physical(xa), k.state_from_physical(xb)


def _spd(n, rng):
    A = rng.normal(size=(n, n))
    return A @ A.T + 0.1 * np.eye(n)


@pytest.mark.parametrize("model", list(MODELS))
@pytest.mark.parametrize("scale", [1e-6, 0.3, 1.5])
def test_mix_transport_and_between_add_match_the_general_kernels(model, scale):
    spec = get_model(model)
    k = spec.kernels
    n = spec.n
    rng = np.random.default_rng(7)
    for _ in range(5):
        s, t = _random_pair(spec, rng, scale)
        P = _spd(n, rng)
        w = rng.uniform(0.1, 1.0)
        acc0 = pack(_spd(n, rng))
        d = k.between(s, t)
        T = k.right_jacobian_inv(d)
        want = unpack(acc0, n) + w * (T @ P @ T.T + np.outer(d, d))
        acc = acc0.copy()
        k.mix_transport(s, t, pack(P), w, acc)
        np.testing.assert_allclose(unpack(acc, n), want, rtol=1e-12, atol=1e-12)
        delta = rng.normal(size=n)
        want_d = delta + w * d
        k.between_add(s, t, w, delta)
        np.testing.assert_allclose(delta, want_d, rtol=1e-13, atol=1e-14)


@pytest.mark.parametrize("model", list(MODELS))
def test_common_of_state_and_state_of_common_match_the_general_kernels(model):
    spec = get_model(model)
    k = spec.kernels
    n = spec.n
    rng = np.random.default_rng(3)
    for _ in range(5):
        s, _ = _random_pair(spec, rng, 0.0)
        P = _spd(n, rng)
        x = k.state_to_physical(s)
        A = k.physical_to_common_jacobian(x)
        c, Pc = np.empty(6), np.empty((6, 6))
        k.common_of_state(s, pack(P), c, Pc)
        np.testing.assert_allclose(c, k.physical_to_common(x), rtol=1e-13, atol=1e-13)
        np.testing.assert_allclose(Pc, A @ P @ A.T, rtol=1e-12, atol=1e-12)
        Pc_in = _spd(6, rng)
        s_out, p_out = np.empty(len(spec.internal_names)), np.empty(spec.n_packed)
        k.state_of_common(c, Pc_in, s_out, p_out)
        J = k.common_jacobian(c)
        np.testing.assert_allclose(s_out, k.state_from_physical(k.common_to_state(c)), rtol=1e-13, atol=1e-13)
        np.testing.assert_allclose(unpack(p_out, n), J @ Pc_in @ J.T, rtol=1e-12, atol=1e-12)
