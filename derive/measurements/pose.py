"""Pose: z = (x, y, θ) ∈ G' = SE(2), Z = h(X)·exp(m), m ~ N(0, diag(r_x², r_y², r_θ²)) in the tangent
(x, y, θ) of SE(2): the noise is in the object's body frame.  h(X) is the object's pose (position and
heading, ``MotionModel.position``/``heading``); models without a heading (CV) do not fit.
The innovation [log_SE(2)(h(μ)⁻¹ Z)]^∨ wraps the heading difference to (−π, π] by construction.
"""

import sympy as sp

from ..lie.groups import SE2
from .base import MeasurementModel


class Pose(MeasurementModel):
    description = "2-D pose z = (x, y, θ) in SE(2) with noise stds (r_x, r_y, r_θ) in its tangent (body frame)"
    group = SE2
    z_names = ("x", "y", "theta")
    noise_names = ("r_x", "r_y", "r_theta")
    angles = (2,)

    def R(self):
        return sp.diag(*[r**2 for r in self.noise_symbols])

    def h(self, model, X):
        c, s = model.heading(X)
        px, py = model.position(X)
        return SE2.element(c, s, px, py)

    def element(self, z):
        zx, zy, zt = z
        return SE2.element(sp.cos(zt), sp.sin(zt), zx, zy)

    def vector(self, Z):
        return [Z[0, 2], Z[1, 2], sp.atan2(Z[1, 0], Z[0, 0])]

    def fits(self, model):
        other = super().fits(model)
        if other:
            return other
        if model.heading(model.mean()) is None:
            return f"the {model.name} model has no heading to measure; use the position measurement"
        return None


MEASUREMENT = Pose()
