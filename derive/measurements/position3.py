"""3-D position: z = (x, y, z) ∈ G' = R³, Z = h(X)·exp(m), m ~ N(0, r² I) (the paper's measurement in space).

For every model of 3-D space (``derive.space.SPACE3``), h(X) is the position of the object
(``MotionModel.position``).
"""

import sympy as sp

from ..lie.groups import Rn
from ..space import SPACE3
from .base import MeasurementModel

R3 = Rn(3)


class Position3(MeasurementModel):
    description = "3-D position z = (x, y, z) with isotropic noise std r"
    space = SPACE3
    group = R3
    z_names = ("x", "y", "z")
    noise_names = ("r",)

    def R(self):
        (r,) = self.noise_symbols
        return r**2 * sp.eye(3)

    def h(self, model, X):
        return R3.exp(list(model.position(X)))

    def element(self, z):
        return R3.exp(list(z))

    def vector(self, Z):
        return list(R3.log(Z))


MEASUREMENT = Position3()
