"""SE(2)×R³: the paper's LG-EKF with pose T_s in SE(2) and velocity v = (v_x, v_y, ω) a plain vector.

X = (T_s, [[I, v], [0, 1]]); Ω(X) = [T v_x, T v_y, T ω, 0, 0, 0] (eq:motionG), n = (n_x, n_y, n_ω)
through G = [T²/2 I; T I].  Physical state [x, y, θ, v_x, v_y, ω]; internal
[x, y, cos θ, sin θ, v_x, v_y, ω].
"""

import sympy as sp

from ..lie.special import wrap
from .base import COMMON, SE2, MotionModel, Product, Rn, dt, dwna_G, omega, theta, vx, vy, x, y

cth, sth = sp.symbols("c_theta s_theta", real=True)


class SE2R3(MotionModel):
    display_name = "SE(2)×R³ LG-EKF"
    description = "LG-EKF on SE(2)xR^3 (pose + body-frame velocity vector)"
    color = "tab:orange"
    group = Product(SE2, Rn(3))
    physical = (x, y, theta, vx, vy, omega)
    internal = (x, y, cth, sth, vx, vy, omega)
    carried = ((theta, cth, sth),)
    noise_names = ("sigma_x", "sigma_y", "sigma_omega")
    default_accel_std = (0.5, 0.5, 1.0)
    matched_noise = ("v", "v", "w")
    angles = (2,)

    def mean(self):
        return sp.diag(SE2.element(sp.cos(theta), sp.sin(theta), x, y), Rn(3).exp([vx, vy, omega]))

    def internal_of(self, X):
        return [X[0, 2], X[1, 2], X[0, 0], X[1, 0], X[3, 6], X[4, 6], X[5, 6]]

    def internal_from_physical(self):
        return [x, y, sp.cos(theta), sp.sin(theta), vx, vy, omega]

    def physical_from_internal(self):
        return [x, y, wrap(sp.atan2(sth, cth)), vx, vy, omega]

    def Omega_of(self, X):
        V = X[3:7, 3:7]
        return sp.Matrix([dt * V[0, 3], dt * V[1, 3], dt * V[2, 3], 0, 0, 0])

    def noise_input(self):
        return dwna_G(3)

    def position(self, X):
        return X[0, 2], X[1, 2]

    def heading(self, X):
        return X[0, 0], X[1, 0]

    def from_common(self):
        return list(COMMON)

    def world_velocity(self):
        return sp.Matrix([[sp.cos(theta), -sp.sin(theta)], [sp.sin(theta), sp.cos(theta)]]) * sp.Matrix([vx, vy])


MODEL = SE2R3()
