"""SE(3)×SE(3): the paper's SE(2)×SE(2) LG-EKF lifted to space, pose T_s and velocity T_d both in SE(3).

X = (T_s, T_d): T_s = (R, (x, y, z)) the pose; T_d = (R_ω, (v_x, v_y, v_z)) the body-frame velocity with the turn
rate ω as the rotation vector of T_d's rotation, ω = log_SO(3)(R_ω), |ω| ≤ π (a faster rotation would alias).
Ω(X) = [T v, T ω, 0, 0] (eq:motionG lifted: Ω = [T v_x, T v_y, T ω, 0, 0, 0] of SE(2)×SE(2)), n = (n_v, n_ω) through
G = [T²/2 I; T I], isotropic linear and angular acceleration stds (σ_a, σ_α). Tangent order ε = (ρ, φ, ρ_d, φ_d):
SE(3)'s (x, y, z, φx, φy, φz) for each factor, right perturbation X = μ·exp(ε).
𝒞 differentiates ω = log(R_ω) through ``derive.lie.so3.rotation_vector_entry``: d log(R_ω exp(δ^)) = J_r(ω)^-1 δ.
Physical state [x, y, z, roll, pitch, yaw, v_x, v_y, v_z, ω_x, ω_y, ω_z] (Z-Y-X Euler angles, ``derive.space``;
velocities in the body frame); internal [x, y, z, R (9, row-major), v_x, v_y, v_z, R_ω (9), ω_x, ω_y, ω_z]: both
rotations carried as matrices, ω beside R_ω (its log, computed once per update, read by every prediction).
"""

import math

import sympy as sp

from ..lie.so3 import SO3, rotation_vector
from ..space import SPACE3, euler_of_rotation, euler_rotation
from .base import SE3, MotionModel, PoseBodyVelocity3, Product, dt

x, y, z, roll, pitch, yaw, vx, vy, vz, wx, wy, wz = SPACE3.common
R_ENTRIES = sp.symbols("r_11 r_12 r_13 r_21 r_22 r_23 r_31 r_32 r_33", real=True)
W_ENTRIES = sp.symbols("q_11 q_12 q_13 q_21 q_22 q_23 q_31 q_32 q_33", real=True)
RMAT = sp.Matrix(3, 3, R_ENTRIES)
WMAT = sp.Matrix(3, 3, W_ENTRIES)


def _entries(M) -> list:
    return [M[i, j] for i in range(3) for j in range(3)]


class SE3SE3(PoseBodyVelocity3, MotionModel):
    display_name = "SE(3)×SE(3) LG-EKF"
    description = "LG-EKF on SE(3)xSE(3) (pose + body-frame velocity as a second SE(3) element), the paper's SE(2)xSE(2) in 3-D"
    color = "tab:blue"
    space = SPACE3
    lifts = "se2se2"
    group = Product(SE3, SE3)
    physical = SPACE3.common
    names = SPACE3.common_names
    internal = (x, y, z) + R_ENTRIES + (vx, vy, vz) + W_ENTRIES + (wx, wy, wz)
    carried_rotations = (((wx, wy, wz), W_ENTRIES),)
    noise_names = ("sigma_a", "sigma_alpha")
    default_accel_std = (0.5, 1.0)
    matched_noise = ("v", "w")
    angles = (3, 4, 5)
    bounds = {(9, 10, 11): math.pi}
    bound_reason = "ω is the rotation vector of T_d's rotation (|ω| <= π); use the se3r6 model for faster rotations"

    def mean(self):
        return sp.diag(SE3.element(RMAT, [x, y, z]), SE3.element(WMAT, [vx, vy, vz]))

    def internal_of(self, X):
        Td = X[4:8, 4:8]
        return ([X[0, 3], X[1, 3], X[2, 3]] + _entries(X[:3, :3]) + [Td[0, 3], Td[1, 3], Td[2, 3]] + _entries(Td[:3, :3])
                + list(rotation_vector(Td[:3, :3])))

    def internal_from_physical(self):
        return ([x, y, z] + _entries(euler_rotation(roll, pitch, yaw)) + [vx, vy, vz] + _entries(SO3.exp([wx, wy, wz]))
                + [wx, wy, wz])

    def physical_from_internal(self):
        return [x, y, z] + euler_of_rotation(RMAT) + [vx, vy, vz, wx, wy, wz]

    def Omega_of(self, X):
        Td = X[4:8, 4:8]
        return sp.Matrix([dt * Td[0, 3], dt * Td[1, 3], dt * Td[2, 3]] + list(dt * rotation_vector(Td[:3, :3])) + [0] * 6)


MODEL = SE3SE3()
