"""Consistency of the LG filters on data from their own model: NEES ≈ 6, NIS ≈ 2 (generated tangent_error)."""

from __future__ import annotations

import numpy as np
import pytest

import lgekf
from lgekf.experiments.metrics import nees, position_rmse
from lgekf.experiments.simulate import simulate


@pytest.mark.parametrize("model", ["se2se2", "se2r3"])
@pytest.mark.parametrize("sigma_w", [0.1, 0.8])
def test_lg_filter_consistent_on_its_own_model(model, sigma_w):
    rng = np.random.default_rng(11)
    B, K = 150, 60
    x0 = np.tile([0.0, 0.0, 0.3, 2.0, 0.1, 0.2], (B, 1))
    sim = simulate(x0, dt=0.1, steps=K, sigma_v=0.2, sigma_w=sigma_w, meas_std=0.3, truth=model, rng=rng)
    est, cov, nis = lgekf.filter_batch(
        model, sim.z, dt=0.1, accel_std=(0.2, 0.2, sigma_w), meas_std=0.3, x0=x0, P0=np.eye(6) * 1e-8,
        return_cov=True, return_nis=True,
    )
    # skip the first steps (the tiny P0 is exact but the filter needs a few updates to settle)
    ne = nees(model, est[:, 10:], cov[:, 10:], sim.truth[:, 11:])
    # errors are correlated in time, so compare the mean with the dof, not a chi-square band
    assert abs(ne.mean() / 6 - 1) < 0.1, ne.mean()
    assert abs(nis[:, 10:].mean() / 2 - 1) < 0.05, nis[:, 10:].mean()
    assert np.all(position_rmse(est, sim.truth[:, 1:]) < 0.3)


def test_nees_zero_for_exact_estimate():
    x = np.array([[1.0, -2.0, 0.4, 1.5, -0.2, 0.3]])
    for model in ("se2se2", "se2r3"):
        assert nees(model, x, np.eye(6)[None], x)[0] == pytest.approx(0.0, abs=1e-24)
    assert nees("cv", lgekf.core.registry.MODELS["cv"].kernels.common_to_state(x[0])[None], np.eye(4)[None], x)[0] == pytest.approx(0, abs=1e-24)
