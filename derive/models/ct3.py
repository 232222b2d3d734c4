"""CT3: the 3-D coordinated-turn EKF of air-traffic tracking: CTRV in the horizontal plane and a constant
vertical speed (e.g. Bar-Shalom, Li & Kirubarajan, *Estimation with Applications to Tracking and Navigation*,
§11.7; Blom's horizontal CT with a vertical CV channel).

State (x, y, z, ψ, v, ω, v_z) on R⁷: ψ the course (direction of the horizontal velocity), v the horizontal speed,
ω the turn rate, v_z the vertical speed.  The exact discretisation x' = x + vT cos(ψ + ωT/2) sinc(ωT/2),
y' = y + vT sin(ψ + ωT/2) sinc(ωT/2), z' = z + v_z T, ψ' = ψ + ωT is finite at ω = 0; Ω(x) = f(x) − x.  Noise:
along-track, yaw and vertical accelerations (σ_a, σ_α, σ_z) through G(ψ) = [[T²/2 cos ψ, 0, 0],
[T²/2 sin ψ, 0, 0], [0, 0, T²/2], [0, T²/2, 0], [T, 0, 0], [0, T, 0], [0, 0, T]], taken at the state before the
step.  CT3 has no attitude of its own: its common attitude is level flight along the course (roll 0, pitch from
the climb), its body rate Rᵀ·(0, 0, ω) (the turn about the vertical, in that body frame).
"""

import sympy as sp

from ..lie.special import sinc
from ..space import SPACE3, euler_rotation
from .base import Rn, VectorModel, dt

x, y, z, roll, pitch, yaw, vx, vy, vz, wx, wy, wz = SPACE3.common
psi, v, omega = sp.symbols("psi v omega", real=True)
vz_ = sp.Symbol("v_up", real=True)


class CT3(VectorModel):
    display_name = "CT3 EKF"
    description = "EKF with the 3-D coordinated-turn model (horizontal CTRV, constant vertical speed)"
    color = "tab:green"
    space = SPACE3
    lifts = "ctrv"
    group = Rn(7)
    physical = (x, y, z, psi, v, omega, vz_)
    names = ("x", "y", "z", "psi", "v", "omega", "vz")
    noise_names = ("sigma_a", "sigma_alpha", "sigma_z")
    default_accel_std = (0.5, 1.0, 0.5)
    matched_noise = ("v", "w", "v")
    angles = (3,)
    forward_speed = (3, 4)  # (course, v): (course + π, −v) is the same motion

    def f(self, s):
        """The exact discretisation x' = f(x) (sinc form)."""
        X, Y, Z, P, V, W, VZ = s
        h = W * dt / 2
        return sp.Matrix([X + V * dt * sp.cos(P + h) * sinc(h), Y + V * dt * sp.sin(P + h) * sinc(h), Z + VZ * dt,
                          P + W * dt, V, W, VZ])

    def noise_input(self):
        c, s = sp.cos(psi), sp.sin(psi)
        h = dt**2 / 2
        return sp.Matrix([[h * c, 0, 0], [h * s, 0, 0], [0, 0, h], [0, h, 0], [dt, 0, 0], [0, dt, 0], [0, 0, dt]])

    def position(self, X):
        return X[0, 7], X[1, 7], X[2, 7]

    def from_common(self):
        """ψ and v of the horizontal world velocity w = R(roll, pitch, yaw)·(v_x, v_y, v_z), v_z = w_z, ω the world
        yaw rate (R·ω_body)_z (singular at zero horizontal speed, like CTRV's)."""
        R = euler_rotation(roll, pitch, yaw)
        w = R * sp.Matrix([vx, vy, vz])
        rate = R * sp.Matrix([wx, wy, wz])
        return [x, y, z, sp.atan2(w[1], w[0]), sp.sqrt(w[0] ** 2 + w[1] ** 2), rate[2], w[2]]

    def world_velocity(self):
        return sp.Matrix([v * sp.cos(psi), v * sp.sin(psi), vz_])

    def body_rate(self):
        """The body rate of the turn at ω about the world's vertical, in the common body frame (level along the
        course, pitched by the climb: pitch = −atan2(v_z, v)): ω_body = Rᵀ·(0, 0, ω) = ω·(v_z, 0, v)/√(v² + v_z²),
        so that ``from_common``'s (R·ω_body)_z gives ω back (a round trip c → state → c is the identity; with
        (0, 0, ω) it shrank ω by cos(pitch), which the IMM's mixing across models applies every step)."""
        h = sp.sqrt(v**2 + vz_**2)
        return [omega * vz_ / h, 0, omega * v / h]


MODEL = CT3()
