"""CTRV: the constant turn rate and velocity EKF (Schubert 2012), the paper's first baseline.

State (x, y, ψ, v, ω) on R⁵ (so the LG-EKF machinery reduces to the plain EKF: Φ = I, Ad = I).
The exact discretisation of ẋ = v cos ψ, ẏ = v sin ψ, ψ̇ = ω is x' = x + vT cos(ψ + ωT/2) sinc(ωT/2),
y' = y + vT sin(ψ + ωT/2) sinc(ωT/2), ψ' = ψ + ωT (finite at ω = 0; ``integrated`` checks it against
SymPy's integral); Ω(x) = f(x) − x.  Noise: longitudinal and yaw acceleration (σ_a, σ_α) through
G(ψ) = [[T²/2 cos ψ, 0], [T²/2 sin ψ, 0], [0, T²/2], [T, 0], [0, T]], taken at the state before the step.
"""

import sympy as sp

from ..lie.special import sinc
from .base import Rn, VectorModel, dt, omega, theta, vx, vy, x, y

psi, v = sp.symbols("psi v", real=True)


class CTRV(VectorModel):
    display_name = "CTRV EKF"
    description = "EKF with the constant turn rate and velocity model"
    color = "tab:green"
    group = Rn(5)
    physical = (x, y, psi, v, omega)
    noise_names = ("sigma_a", "sigma_alpha")
    default_accel_std = (0.5, 1.0)
    matched_noise = ("v", "w")
    angles = (2,)
    forward_speed = (2, 3)  # (heading, v): (heading + π, −v) is the same motion

    def f(self, s):
        """The exact discretisation x' = f(x) (sinc form)."""
        X, Y, P, V, W = s
        h = W * dt / 2
        return sp.Matrix([X + V * dt * sp.cos(P + h) * sinc(h), Y + V * dt * sp.sin(P + h) * sinc(h), P + W * dt, V, W])

    def integrated(self):
        """x(T), y(T), ψ(T) integrated by SymPy from ẋ = v cos ψ, ẏ = v sin ψ, ψ = ψ0 + ω t."""
        t = sp.Symbol("_t", real=True)
        psi_t = psi + omega * t
        dx = sp.integrate(v * sp.cos(psi_t), (t, 0, dt))
        dy = sp.integrate(v * sp.sin(psi_t), (t, 0, dt))
        return sp.Matrix([x + dx, y + dy, psi_t.subs(t, dt), v, omega])

    def noise_input(self):
        c, s = sp.cos(psi), sp.sin(psi)
        return sp.Matrix([[dt**2 / 2 * c, 0], [dt**2 / 2 * s, 0], [0, dt**2 / 2], [dt, 0], [0, dt]])

    def position(self, X):
        return X[0, 5], X[1, 5]

    def heading(self, X):
        return sp.cos(X[2, 5]), sp.sin(X[2, 5])

    def from_common(self):
        """ψ = θ + atan2(v_y, v_x) is the heading of the velocity, v its magnitude (singular at v = 0)."""
        return [x, y, theta + sp.atan2(vy, vx), sp.sqrt(vx**2 + vy**2), omega]

    def world_velocity(self):
        return v * sp.Matrix([sp.cos(psi), sp.sin(psi)])


MODEL = CTRV()
