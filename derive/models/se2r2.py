"""SE(2)×R²: the LG-EKF with pose T_s in SE(2) and (v, ω) forward speed and turn rate, no side slip.

The Lie-group counterpart of CTRV (a unicycle): X = (T_s, [[I, (v, ω)], [0, 1]]),
Ω(X) = [T v, 0, T ω, 0, 0], so each step moves along the arc exp([T v, 0, T ω]^∧), like CTRV's exact
discretisation, but the uncertainty is a concentrated Gaussian on SE(2) (banana-shaped) instead of a
Gaussian in (x, y, ψ).  Noise: forward and yaw acceleration (σ_a, σ_α) through
G = [[T²/2, 0], [0, 0], [0, T²/2], [T, 0], [0, T]].  It tells whether the LG filters' advantage comes
from the group or from the holonomic (v_x, v_y) velocity of the paper's models.
Physical state [x, y, θ, v, ω]; internal [x, y, cos θ, sin θ, v, ω].
"""

import sympy as sp

from ..lie.special import wrap
from .base import SE2, MotionModel, Product, Rn, dt, omega, theta, vx, vy, x, y

v = sp.Symbol("v", real=True)
cth, sth = sp.symbols("c_theta s_theta", real=True)


class SE2R2(MotionModel):
    display_name = "SE(2)×R² LG-EKF (unicycle)"
    description = "LG-EKF on SE(2)xR^2 (pose + forward speed and turn rate, no side slip)"
    color = "tab:purple"
    group = Product(SE2, Rn(2))
    physical = (x, y, theta, v, omega)
    internal = (x, y, cth, sth, v, omega)
    carried = ((theta, cth, sth),)
    noise_names = ("sigma_a", "sigma_alpha")
    default_accel_std = (0.5, 1.0)
    matched_noise = ("v", "w")
    angles = (2,)
    forward_speed = (2, 3)  # (heading, v): (heading + π, −v) is the same motion

    def mean(self):
        return sp.diag(SE2.element(sp.cos(theta), sp.sin(theta), x, y), Rn(2).exp([v, omega]))

    def internal_of(self, X):
        return [X[0, 2], X[1, 2], X[0, 0], X[1, 0], X[3, 5], X[4, 5]]

    def internal_from_physical(self):
        return [x, y, sp.cos(theta), sp.sin(theta), v, omega]

    def physical_from_internal(self):
        return [x, y, wrap(sp.atan2(sth, cth)), v, omega]

    def Omega_of(self, X):
        V = X[3:6, 3:6]
        return sp.Matrix([dt * V[0, 2], 0, dt * V[1, 2], 0, 0])

    def noise_input(self):
        h = dt**2 / 2
        return sp.Matrix([[h, 0], [0, 0], [0, h], [dt, 0], [0, dt]])

    def position(self, X):
        return X[0, 2], X[1, 2]

    def heading(self, X):
        return X[0, 0], X[1, 0]

    def from_common(self):
        """θ' = θ + atan2(v_y, v_x): the heading of motion, v = |(v_x, v_y)| (singular at v = 0)."""
        return [x, y, theta + sp.atan2(vy, vx), sp.sqrt(vx**2 + vy**2), omega]

    def world_velocity(self):
        return v * sp.Matrix([sp.cos(theta), sp.sin(theta)])


MODEL = SE2R2()
