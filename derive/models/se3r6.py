"""SE(3)×R⁶: the paper's SE(2)×R³ LG-EKF lifted to space, pose T in SE(3) and the body twist ξ = (v, ω) in R⁶.

X = (T, [[I, ξ], [0, 1]]); Ω(X) = [T v, T ω, 0, 0] (eq:motionG lifted: a constant twist, so the pose moves on the
screw exp(T ξ)), n = (n_v, n_ω) through G = [T²/2 I; T I], isotropic linear and angular acceleration stds
(σ_a, σ_α).  Tangent order ε = (ρ, φ, δv, δω): SE(3)'s (x, y, z, φx, φy, φz), right perturbation X = μ·exp(ε).
Physical state [x, y, z, roll, pitch, yaw, v_x, v_y, v_z, ω_x, ω_y, ω_z] (Z-Y-X Euler angles, ``derive.space``;
velocities in the body frame); internal [x, y, z, R (9 entries, row-major), v_x, v_y, v_z, ω_x, ω_y, ω_z]: the
rotation is carried as its matrix, so a step needs no Euler angles (singular at pitch = ±π/2) and no sincos.
"""

import sympy as sp

from ..space import SPACE3, euler_of_rotation, euler_rotation
from .base import SE3, MotionModel, PoseBodyVelocity3, Product, Rn, dt

x, y, z, roll, pitch, yaw, vx, vy, vz, wx, wy, wz = SPACE3.common
R_ENTRIES = sp.symbols("r_11 r_12 r_13 r_21 r_22 r_23 r_31 r_32 r_33", real=True)
RMAT = sp.Matrix(3, 3, R_ENTRIES)


class SE3R6(PoseBodyVelocity3, MotionModel):
    display_name = "SE(3)×R⁶ LG-EKF"
    description = "LG-EKF on SE(3)xR^6 (pose + body twist as a vector), the paper's SE(2)xR^3 in 3-D"
    color = "tab:orange"
    space = SPACE3
    lifts = "se2r3"
    group = Product(SE3, Rn(6))
    physical = SPACE3.common
    names = SPACE3.common_names
    internal = (x, y, z) + R_ENTRIES + (vx, vy, vz, wx, wy, wz)
    noise_names = ("sigma_a", "sigma_alpha")
    default_accel_std = (0.5, 1.0)
    matched_noise = ("v", "w")
    angles = (3, 4, 5)

    def mean(self):
        return sp.diag(SE3.element(RMAT, [x, y, z]), Rn(6).exp([vx, vy, vz, wx, wy, wz]))

    def internal_of(self, X):
        return [X[0, 3], X[1, 3], X[2, 3]] + [X[i, j] for i in range(3) for j in range(3)] + [X[4 + i, 10] for i in range(6)]

    def internal_from_physical(self):
        R = euler_rotation(roll, pitch, yaw)
        return [x, y, z] + [R[i, j] for i in range(3) for j in range(3)] + [vx, vy, vz, wx, wy, wz]

    def physical_from_internal(self):
        return [x, y, z] + euler_of_rotation(RMAT) + [vx, vy, vz, wx, wy, wz]

    def Omega_of(self, X):
        V = X[4:11, 4:11]
        return sp.Matrix([dt * V[i, 6] for i in range(6)] + [0] * 6)


MODEL = SE3R6()
