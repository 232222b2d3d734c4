"""3-D pose: z = (x, y, z, roll, pitch, yaw) ∈ G' = SE(3), Z = h(X)·exp(m), m ~ N(0, diag(r_p² I₃, r_a² I₃)) in the
tangent (ρ, φ) of SE(3): position noise r_p and attitude noise r_a (a rotation vector), both in the object's body
frame.  The attitude is given as Z-Y-X Euler angles (``derive.space``: R = R_z(yaw) R_y(pitch) R_x(roll)).
h(X) is the object's pose (``MotionModel.position`` and ``attitude``); models without an attitude (CT3, CV3) do not
fit.  The innovation [log_SE(3)(h(μ)⁻¹ Z)]^∨ is the same whichever Euler angles stand for the attitude.
"""

import sympy as sp

from ..lie.groups import SE3
from ..space import SPACE3, euler_of_rotation, euler_rotation
from .base import MeasurementModel


class Pose3(MeasurementModel):
    description = ("3-D pose z = (x, y, z, roll, pitch, yaw) in SE(3) with noise stds (r_p, r_a) in its tangent "
                   "(position, rotation vector; body frame)")
    space = SPACE3
    group = SE3
    z_names = ("x", "y", "z", "roll", "pitch", "yaw")
    noise_names = ("r_p", "r_a")
    angles = (3, 4, 5)

    def R(self):
        rp, ra = self.noise_symbols
        return sp.diag(*([rp**2] * 3 + [ra**2] * 3))

    def h(self, model, X):
        return SE3.element(model.attitude(X), list(model.position(X)))

    def element(self, z):
        return SE3.element(euler_rotation(*z[3:6]), list(z[:3]))

    def vector(self, Z):
        return [Z[0, 3], Z[1, 3], Z[2, 3]] + euler_of_rotation(Z[:3, :3])

    def fits(self, model):
        other = super().fits(model)
        if other:
            return other
        if model.attitude(model.mean()) is None:
            return f"the {model.name} model has no attitude to measure; use the position3 measurement"
        return None


MEASUREMENT = Pose3()
