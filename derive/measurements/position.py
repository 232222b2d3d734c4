"""Position: z = (x, y) ∈ G' = R², Z = h(X)·exp(m), m ~ N(0, r² I) (the paper's measurement, eq:meas, eq:r).

For every model, h(X) is the position of the object (``MotionModel.position``).
"""

import sympy as sp

from ..lie.groups import Rn
from .base import MeasurementModel

R2 = Rn(2)


class Position(MeasurementModel):
    description = "2-D position z = (x, y) with isotropic noise std r (the paper's measurement)"
    group = R2
    z_names = ("x", "y")
    noise_names = ("r",)

    def R(self):
        (r,) = self.noise_symbols
        return r**2 * sp.eye(2)

    def h(self, model, X):
        return R2.exp(list(model.position(X)))

    def element(self, z):
        return R2.exp(list(z))

    def vector(self, Z):
        return list(R2.log(Z))


MEASUREMENT = Position()
