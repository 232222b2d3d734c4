"""CV3: the constant (world-frame) velocity Kalman filter in 3-D space with DWNA noise, CV lifted to space.

State (x, y, z, w_x, w_y, w_z) on R⁶, (w_x, w_y, w_z) the world-frame velocity; Ω = [T w, 0], so
F = [[I, T I], [0, I]]; one isotropic acceleration std σ_a drives n = (n_x, n_y, n_z) through G = [T²/2 I; T I].
CV3 has no attitude: it fits the 3-D position measurement only.
"""

import sympy as sp

from ..space import SPACE3, euler_rotation
from .base import Rn, VectorModel, dt, dwna_G

x, y, z, roll, pitch, yaw, vx, vy, vz = SPACE3.common[:9]
wx, wy, wz = sp.symbols("w_x w_y w_z", real=True)


class CV3(VectorModel):
    display_name = "CV3 KF"
    description = "Kalman filter with the constant (world-frame) velocity model in 3-D"
    color = "tab:red"
    space = SPACE3
    lifts = "cv"
    group = Rn(6)
    physical = (x, y, z, wx, wy, wz)
    names = ("x", "y", "z", "vx", "vy", "vz")  # world-frame velocity, named as in the output files
    noise_names = ("sigma_a",)
    default_accel_std = (0.5,)
    matched_noise = ("v",)

    def f(self, s):
        """x' = x + T w, w' = w."""
        X, Y, Z, WX, WY, WZ = s
        return sp.Matrix([X + dt * WX, Y + dt * WY, Z + dt * WZ, WX, WY, WZ])

    def noise_input(self):
        return dwna_G(3)

    def noise_stds(self):
        (sa,) = self.noise_symbols
        return [sa, sa, sa]

    def position(self, X):
        return X[0, 6], X[1, 6], X[2, 6]

    def from_common(self):
        """(x, y, z, w) with w = R(roll, pitch, yaw)·(v_x, v_y, v_z) the world-frame velocity."""
        w = euler_rotation(roll, pitch, yaw) * sp.Matrix([vx, vy, vz])
        return [x, y, z, w[0], w[1], w[2]]

    def world_velocity(self):
        return sp.Matrix([wx, wy, wz])


MODEL = CV3()
