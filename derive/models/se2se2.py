"""SE(2)×SE(2): the paper's LG-EKF with pose T_s and velocity T_d both in SE(2) (Sec. "LG-EKF on SE(2)²").

X = (T_s, T_d): T_s = (R_θ, (x, y)) the pose; T_d = (R_ω, (v_x, v_y)) the body-frame velocity with the
turn rate ω as the angle of T_d's rotation, so ω = log_SO(2)(R_ω) ∈ [−π, π] (a larger turn rate would
alias).  Ω(X) = [T v_x, T v_y, T ω, 0, 0, 0] (eq:motionG), n = (n_x, n_y, n_ω) through G = [T²/2 I; T I].
Physical state [x, y, θ, v_x, v_y, ω]; internal [x, y, cos θ, sin θ, v_x, v_y, ω, cos ω, sin ω].
"""

import math

import sympy as sp

from ..lie.special import wrap
from .base import COMMON, SE2, MotionModel, Product, angle_of, dt, dwna_G, omega, theta, vx, vy, x, y

cth, sth, cw, sw = sp.symbols("c_theta s_theta c_omega s_omega", real=True)


class SE2SE2(MotionModel):
    display_name = "SE(2)×SE(2) LG-EKF"
    description = "LG-EKF on SE(2)xSE(2) (pose + body-frame velocity as a second SE(2) element)"
    color = "tab:blue"
    group = Product(SE2, SE2)
    physical = (x, y, theta, vx, vy, omega)
    internal = (x, y, cth, sth, vx, vy, omega, cw, sw)
    carried = ((theta, cth, sth), (omega, cw, sw))
    noise_names = ("sigma_x", "sigma_y", "sigma_omega")
    default_accel_std = (0.5, 0.5, 1.0)
    matched_noise = ("v", "v", "w")
    angles = (2,)
    bounds = {5: math.pi}
    bound_reason = "ω is the angle of T_d (|ω| <= π); use the se2r3 model for faster rotations"

    def mean(self):
        return sp.diag(SE2.element(sp.cos(theta), sp.sin(theta), x, y), SE2.element(sp.cos(omega), sp.sin(omega), vx, vy))

    def internal_of(self, X):
        return [X[0, 2], X[1, 2], X[0, 0], X[1, 0], X[3, 5], X[4, 5], sp.atan2(X[4, 3], X[3, 3]), X[3, 3], X[4, 3]]

    def internal_from_physical(self):
        return [x, y, sp.cos(theta), sp.sin(theta), vx, vy, sp.atan2(sp.sin(omega), sp.cos(omega)), sp.cos(omega), sp.sin(omega)]

    def physical_from_internal(self):
        return [x, y, wrap(sp.atan2(sth, cth)), vx, vy, omega]

    def Omega_of(self, X):
        Td = X[3:6, 3:6]
        return sp.Matrix([dt * Td[0, 2], dt * Td[1, 2], dt * angle_of(Td[:2, :2]), 0, 0, 0])

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


MODEL = SE2SE2()
EPS = MODEL.EPS
