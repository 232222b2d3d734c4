"""A batch Monte Carlo run with ``filter_batch``: accuracy and consistency (NEES) of two filters.

300 trajectories of the SE(2)×SE(2) model (σ_ω = 0.5 rad/s²) are filtered at once, entirely in numba,
by the SE(2)×SE(2) LG-EKF and by the CV Kalman filter. The normalised estimation error squared
NEES = eᵀ P⁻¹ e (e in each filter's own coordinates, ``lgekf.experiments.metrics.nees``) of a consistent filter is
χ²-distributed with n degrees of freedom (n = state dimension): mean n, and 5 % of the values above the
95 % quantile of χ²_n. The mean NIS of a consistent filter is 2.

What to expect: the LG-EKF's mean NEES starts at 6 and creeps up to about 8 over the 6 s (about 12 % of
the values above the quantile): slightly overconfident, as an EKF with an uncertain heading tends to be.
CV, with the small process noise of straight motion, cannot follow the turns and is grossly
overconfident (NEES in the hundreds).

Run: ``python examples/batch_monte_carlo_nees.py``
"""

import numpy as np

from lgekf import filter_batch
from lgekf.experiments.metrics import nees, position_rmse
from lgekf.experiments.simulate import simulate

B, DT, STEPS, SIGMA_W, MEAS_STD = 300, 0.1, 60, 0.5, 0.5
rng = np.random.default_rng(2016)

truth0 = np.tile([0.0, 0.0, 0.0, 3.0, 0.0, 0.0], (B, 1))
sim = simulate(truth0, dt=DT, steps=STEPS, sigma_v=0.1, sigma_w=SIGMA_W, meas_std=MEAS_STD, rng=rng)
truth = sim.truth[:, 1:]  # (B, STEPS, 6): the true state at each measurement

# initial estimates: truth + δ, δ ~ N(0, P0). The true heading is 0, where the LG filter's tangent
# coordinates and the physical ones agree to first order, so P0 serves both.
P0_lg = np.diag([0.25, 0.25, 0.01, 0.25, 0.25, 0.01])
x0_lg = truth0 + rng.multivariate_normal(np.zeros(6), P0_lg, size=B)
P0_cv = np.diag([0.25, 0.25, 0.25, 0.25])
x0_cv = np.column_stack([x0_lg[:, :2], x0_lg[:, 3:5]])  # (x, y, v_x, v_y): world = body frame at θ = 0

runs = {
    "se2se2": filter_batch("se2se2", sim.z, dt=DT, accel_std=(0.1, 0.1, SIGMA_W), meas_std=MEAS_STD,
                           x0=x0_lg, P0=P0_lg, return_cov=True, return_nis=True),
    "cv": filter_batch("cv", sim.z, dt=DT, accel_std=0.1, meas_std=MEAS_STD,
                       x0=x0_cv, P0=P0_cv, return_cov=True, return_nis=True),
}
CHI2_95 = {4: 9.488, 6: 12.592}  # 95 % quantiles of χ² with 4 and 6 degrees of freedom

print(f"{B} trajectories x {STEPS} steps, sigma_w = {SIGMA_W} rad/s^2, meas std {MEAS_STD} m")
print(f"{'model':<8} {'pos RMSE (m)':>12} {'mean NEES (n)':>14} {'NEES > chi2 95 % (5 %)':>23} {'mean NIS (2)':>13}")
for model, (x, P, nis_) in runs.items():
    n = x.shape[-1]
    e = nees(model, x, P, truth)  # (B, STEPS)
    rmse = position_rmse(x, truth).mean()
    above = np.mean(e > CHI2_95[n])
    print(f"{model:<8} {rmse:12.3f} {f'{e.mean():.2f} ({n})':>14} {f'{100 * above:.1f} %':>23} {nis_.mean():13.2f}")
