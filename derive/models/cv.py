"""CV: the constant (world-frame) velocity Kalman filter with DWNA noise, the paper's second baseline.

State (x, y, w_x, w_y) on R⁴, (w_x, w_y) the world-frame velocity; Ω = [T w_x, T w_y, 0, 0], so
F = [[I, T I], [0, I]]; one isotropic acceleration std σ_a drives n = (n_x, n_y) through
G = [T²/2 I; T I].  CV has no heading: pose measurements do not fit it.
"""

import sympy as sp

from .base import Rn, VectorModel, dt, dwna_G, theta, vx, vy, x, y

wx, wy = sp.symbols("w_x w_y", real=True)


class CV(VectorModel):
    display_name = "CV KF"
    description = "Kalman filter with the constant (world-frame) velocity model"
    color = "tab:red"
    group = Rn(4)
    physical = (x, y, wx, wy)
    names = ("x", "y", "vx", "vy")  # world-frame velocity, named as in the output files
    noise_names = ("sigma_a",)
    default_accel_std = (0.5,)
    matched_noise = ("v",)

    def f(self, s):
        """x' = x + T w, w' = w."""
        X, Y, WX, WY = s
        return sp.Matrix([X + dt * WX, Y + dt * WY, WX, WY])

    def noise_input(self):
        return dwna_G(2)

    def noise_stds(self):
        (sa,) = self.noise_symbols
        return [sa, sa]

    def position(self, X):
        return X[0, 4], X[1, 4]

    def from_common(self):
        """(x, y, w_x, w_y) with (w_x, w_y) = R(θ) (v_x, v_y) the world-frame velocity."""
        w = sp.Matrix([[sp.cos(theta), -sp.sin(theta)], [sp.sin(theta), sp.cos(theta)]]) * sp.Matrix([vx, vy])
        return [x, y, w[0], w[1]]

    def world_velocity(self):
        return sp.Matrix([wx, wy])


MODEL = CV()
