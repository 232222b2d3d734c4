"""A measured attitude given as a unit quaternion, read as the Z-Y-X Euler angles of 3-D space.

Convention (the Hamilton quaternion, scalar first): q = (q_w, q_x, q_y, q_z) = (cos(α/2), sin(α/2)·u) rotates by the
angle α about the unit axis u, and stands for the rotation matrix (body to world, as the attitude of
``derive/space.py``)

    R(q) = [[1 − 2(y² + z²),  2(xy − wz),      2(xz + wy)    ],
            [2(xy + wz),      1 − 2(x² + z²),  2(yz − wx)    ],
            [2(xz − wy),      2(yz + wx),      1 − 2(x² + y²)]]

(Sola, *Quaternion kinematics for the error-state Kalman filter*, 2017, eq. 115; scipy's
``Rotation.from_quat(..., scalar_first=True)``). q and −q are the same rotation: R is quadratic in q, so the angles of
both are the same numbers, bit for bit. The angles are those of ``derive.space.euler_of_rotation``: R = R_z(yaw)
R_y(pitch) R_x(roll), roll = atan2(R₃₂, R₃₃), pitch = atan2(−R₃₁, √(R₃₂² + R₃₃²)), yaw = atan2(R₂₁, R₁₁): the
attitude columns ``roll, pitch, yaw`` of a 3-D pose and of ``lgekf track``'s output (the pose3 measurement builds its
rotation from them, so a quaternion and the angles of the same rotation give the same measurement; singular at
pitch = ±90°, as every Euler convention).
"""

from __future__ import annotations

import numpy as np

__all__ = ["QUATERNION_COLUMNS", "MIN_QUATERNION_NORM", "quaternion_norms", "euler_of_quaternion"]

#: the columns of a quaternion attitude, scalar first
QUATERNION_COLUMNS = ("qw", "qx", "qy", "qz")
#: a quaternion shorter than this is no rotation (all four entries zero, or nearly): refused, not normalised
MIN_QUATERNION_NORM = 1e-6


def quaternion_norms(q: np.ndarray) -> np.ndarray:
    """|q| of quaternions q (N, 4)."""
    return np.sqrt(np.einsum("ij,ij->i", q, q))


def euler_of_quaternion(q: np.ndarray) -> np.ndarray:
    """(N, 3) roll, pitch, yaw (rad) of quaternions q (N, 4) = (q_w, q_x, q_y, q_z), normalised here (each row's norm
    must be at least ``MIN_QUATERNION_NORM``: the reader refuses shorter ones, naming the row): the angles of R(q) (module
    docstring)."""
    q = np.asarray(q, dtype=float)
    u = q / quaternion_norms(q)[:, None]
    w, x, y, z = u.T
    r11 = 1.0 - 2.0 * (y * y + z * z)
    r21 = 2.0 * (x * y + w * z)
    r31 = 2.0 * (x * z - w * y)
    r32 = 2.0 * (y * z + w * x)
    r33 = 1.0 - 2.0 * (x * x + y * y)
    return np.column_stack([np.arctan2(r32, r33), np.arctan2(-r31, np.hypot(r32, r33)), np.arctan2(r21, r11)])
