"""The C baseline of the benchmarks (benchmarks/c/se2se2_step.c) is the same filter as the generated kernels.

It is compiled here with the system compiler (skipped with the reason where there is none) and run on a few
trajectories: random step lengths, a turning start, a negative turn rate, a missed detection, covariances kept.
The states, covariances and NIS of the C kernel and of ``generated.se2se2.run_batch_position`` must agree to 1e-9
(relative to each quantity's scale): the C writes the covariance update as P − β K H P (the Joseph form in exact
arithmetic) and carries ω without atan2, so they differ by rounding only.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))

from c_baseline import CompilerMissing, load_c_baseline  # noqa: E402

from lgekf.generated import se2se2  # noqa: E402


@pytest.fixture(scope="module")
def cbase():
    try:
        return load_c_baseline(threads=2)
    except CompilerMissing as e:
        pytest.skip(f"C baseline not built: {e}")


def _problem(B=6, K=300, seed=1):
    rng = np.random.default_rng(seed)
    t = np.arange(1, K + 1) * 0.1
    z = np.stack([3 * t, np.sin(t)], -1)[None] + 0.5 * rng.standard_normal((B, K, 2))
    z[0, 5] = np.nan
    z[3, 40:43, 1] = np.nan
    dts = 0.05 + 0.1 * rng.random((B, K))
    x0 = np.tile([0, 0, 0, 3, 0, 0.1], (B, 1)).astype(float)
    x0[1, 2] = 3.0
    x0[2, 5] = -2.5
    x0[4, 3] = 0.0
    p0 = np.tile(np.diag([0.3, 0.3, 0.05, 0.2, 0.2, 0.05])[np.triu_indices(6)], (B, 1))
    return z, dts, x0, p0, np.array([0.5, 0.5, 1.0]), np.array([0.5])


@pytest.mark.slow
def test_c_baseline_equals_generated_kernel(cbase):
    z, dts, x0, p0, q, r = _problem()
    B, K = z.shape[:2]
    ref = np.empty((B, K, 6)), np.empty((B, K, 21)), np.empty((B, K))
    se2se2.run_batch_position(z, dts, x0, p0, q, r, ref[0], ref[1], ref[2])
    out = np.empty((B, K, 6)), np.empty((B, K, 21)), np.empty((B, K))
    cbase.run_batch(z, dts, x0, p0, q, r, out[0], out[2], out_p=out[1])
    for a, b in zip(ref, out):
        assert np.array_equal(np.isnan(a), np.isnan(b))
    assert np.nanmax(np.abs(out[0] - ref[0]) / np.maximum(1.0, np.abs(ref[0]))) < 1e-9
    for i in range(B):
        scale = np.abs(ref[1][i]).max()
        assert np.max(np.abs(out[1][i] - ref[1][i])) < 1e-9 * scale
    assert np.nanmax(np.abs(out[2] - ref[2]) / np.maximum(1.0, np.abs(ref[2]))) < 1e-9
    # the one-trajectory entry point runs the same loop
    one = np.empty((K, 6)), np.empty((K, 21)), np.empty(K)
    cbase.run_one(z[2], dts[2], x0[2], p0[2], q, r, one[0], one[2], out_p=one[1])
    np.testing.assert_array_equal(one[0], out[0][2])
    np.testing.assert_array_equal(one[1], out[1][2])
