"""The spaces an object moves in: the plane and 3-D space, each with its common physical coordinates.

A motion model declares its ``space`` (``derive.models.base.MotionModel.space``, the plane by default); a
measurement declares the space it observes (``derive.measurements.base.MeasurementModel.space``) and fits only the
models of that space.  The space is what makes models comparable: its *common coordinates* c are how every model
of the space is initialised alike, how the IMM mixes models of different groups and how the study compares them
(``from_common``, ``common_of_physical``).  Models of different spaces never meet: the registry records each
model's space, and the runtime offers ``--model all`` and IMM modes within one space.

* ``PLANE``: c = (x, y, θ, v_x, v_y, ω): position, heading, body-frame velocity, turn rate (SE(2) tangent order);
* ``SPACE3``: c = (x, y, z, roll, pitch, yaw, v_x, v_y, v_z, ω_x, ω_y, ω_z): position, attitude as Z-Y-X Euler
  angles (R = R_z(yaw) R_y(pitch) R_x(roll), the aerospace convention), body-frame velocity and body-frame angular
  rate (SE(3) twist order (ρ, φ) for the velocities).

Nothing here knows a model; a space only knows its own coordinates and how to read them off a model's
``position``, ``attitude`` (or ``heading``) and ``world_velocity``.
"""

from __future__ import annotations

import sympy as sp

__all__ = ["Space", "PLANE", "SPACE3", "DEFAULT_SPACE", "euler_rotation", "euler_of_rotation", "angle_of"]


def angle_of(R: sp.Matrix):
    """The angle a of a rotation matrix R = [[cos a, −sin a], [sin a, cos a]] (trigsimp'd)."""
    c, s = sp.trigsimp(R[0, 0]), sp.trigsimp(R[1, 0])
    if isinstance(c, sp.cos) and isinstance(s, sp.sin) and c.args == s.args:
        return c.args[0]
    return sp.atan2(s, c)


def euler_rotation(roll, pitch, yaw) -> sp.Matrix:
    """R = R_z(yaw)·R_y(pitch)·R_x(roll) (Z-Y-X Euler angles: yaw about z, then pitch about y, then roll about x)."""
    cr, sr, cp, spi, cy, sy = sp.cos(roll), sp.sin(roll), sp.cos(pitch), sp.sin(pitch), sp.cos(yaw), sp.sin(yaw)
    Rz = sp.Matrix([[cy, -sy, 0], [sy, cy, 0], [0, 0, 1]])
    Ry = sp.Matrix([[cp, 0, spi], [0, 1, 0], [-spi, 0, cp]])
    Rx = sp.Matrix([[1, 0, 0], [0, cr, -sr], [0, sr, cr]])
    return Rz * Ry * Rx


def euler_of_rotation(R) -> list:
    """(roll, pitch, yaw) of a rotation matrix R = R_z(yaw) R_y(pitch) R_x(roll): roll = atan2(R₃₂, R₃₃),
    pitch = atan2(−R₃₁, √(R₃₂² + R₃₃²)) ∈ [−π/2, π/2], yaw = atan2(R₂₁, R₁₁) (singular at pitch = ±π/2)."""
    return [sp.atan2(R[2, 1], R[2, 2]), sp.atan2(-R[2, 0], sp.sqrt(R[2, 1] ** 2 + R[2, 2] ** 2)), sp.atan2(R[1, 0], R[0, 0])]


class Space:
    """A space of motion: its dimension and common coordinates (see the module docstring)."""

    name = ""
    dim = 0
    common: tuple = ()
    common_names: tuple = ()
    common_doc = ""  # the common coordinates as docstrings write them
    position_names: tuple = ()
    #: the generated IMM loop mixes the models of this space: its model chains ``generated/<dispatch_module>.py`` and its
    #: loop ``generated/<imm_module>.py`` (``derive/codegen/dispatch.py``, ``derive/codegen/families/imm.py``)
    mixes = False
    dispatch_module = ""
    imm_module = ""
    #: the indices of the common coordinates that are angles: the IMM wraps them to (−π, π] when it mixes and caps their
    #: std at π (a heading read off a velocity near zero is unknown, not infinitely uncertain)
    common_angles: tuple = ()
    #: the indices of the body-frame velocity in c, the forward speed first: below ``SPEED_FLOOR`` the IMM evaluates the
    #: conversions' Jacobians at that forward speed (an attitude read off the velocity is singular at rest)
    common_velocity: tuple = ()
    #: the modes of ``lgekf track --model imm`` (and ``lgekf evaluate --imm``) in this space (measured: docs/imm.md,
    #: docs/space3d.md)
    default_imm_modes = ""
    #: the divergence monitor's kernels (its two-point restart, ``derive/codegen/families/monitor.py``) serve this space
    monitored = False

    def __repr__(self):
        return f"Space({self.name!r})"

    def common_of_physical(self, model) -> list:  # pragma: no cover - abstract
        """c read off the physical state of ``model`` (the inverse direction of its ``from_common``)."""
        raise NotImplementedError


class Plane(Space):
    """The plane: c = (x, y, θ, v_x, v_y, ω), (v_x, v_y) in the body frame."""

    name = "2d"
    dim = 2
    common = tuple(sp.symbols("x y theta", real=True)) + tuple(sp.symbols("v_x v_y omega", real=True))
    common_names = ("x", "y", "theta", "vx", "vy", "omega")
    common_doc = "(x, y, θ, v_x, v_y, ω)"
    position_names = ("x", "y")
    mixes = True
    dispatch_module, imm_module = "dispatch", "imm"
    common_angles = (2,)
    common_velocity = (3, 4)
    #: CV and a calm and a manoeuvring SE(2)×R³ (measured on the real-data evaluation against se2r3:calm,se2r3:manoeuvre
    #: and cv,se2r3, docs/imm.md)
    default_imm_modes = "cv,se2r3:calm,se2r3:manoeuvre"
    monitored = True

    def common_of_physical(self, model) -> list:
        """(x, y) = ``position``; θ = the ``heading`` or, for a model without one, the direction of the world
        velocity; (v_x, v_y) = R(θ)ᵀ·``world_velocity``; ω = the physical coordinate that ``from_common`` sets to ω."""
        X = model.mean_physical
        px, py = model.position(X)
        w = model.world_velocity()
        h = model.heading(X)
        if h is None:
            th = sp.atan2(w[1], w[0])
            vb = [sp.sqrt(w[0] ** 2 + w[1] ** 2), sp.Integer(0)]
        else:
            ch, sh = h
            th = angle_of(sp.Matrix([[ch, -sh], [sh, ch]]))
            vb = [sp.simplify(ch * w[0] + sh * w[1]), sp.simplify(-sh * w[0] + ch * w[1])]
        return [px, py, th, vb[0], vb[1], _set_to(model, self.common[5])]


class Space3(Space):
    """3-D space: c = (x, y, z, roll, pitch, yaw, v_x, v_y, v_z, ω_x, ω_y, ω_z), velocities in the body frame."""

    name = "3d"
    dim = 3
    common = (tuple(sp.symbols("x y z", real=True)) + tuple(sp.symbols("roll pitch yaw", real=True))
              + tuple(sp.symbols("v_x v_y v_z", real=True)) + tuple(sp.symbols("omega_x omega_y omega_z", real=True)))
    common_names = ("x", "y", "z", "roll", "pitch", "yaw", "vx", "vy", "vz", "wx", "wy", "wz")
    common_doc = "(x, y, z, roll, pitch, yaw, v_x, v_y, v_z, ω_x, ω_y, ω_z)"
    position_names = ("x", "y", "z")
    mixes = True
    dispatch_module, imm_module = "dispatch_3d", "imm_3d"
    common_angles = (3, 4, 5)
    common_velocity = (6, 7, 8)
    #: CV3 and a calm and a manoeuvring CT3, as in the plane: best of the mode sets tried on KITTI 3-D, second to
    #: ct3:calm,ct3:manoeuvre on a climbing turn (docs/space3d.md, "The IMM in 3-D")
    default_imm_modes = "cv3,ct3:calm,ct3:manoeuvre"
    monitored = True

    def common_of_physical(self, model) -> list:
        """(x, y, z) = ``position``; the attitude from ``attitude`` (Euler angles of R) or, for a model without one,
        the direction of the world velocity (yaw its course, pitch its climb angle, roll 0: the body's x axis along
        the velocity); body velocity Rᵀ·``world_velocity``; body rate: the physical coordinates that ``from_common``
        sets to ω_x, ω_y, ω_z (0 for the others)."""
        X = model.mean_physical
        p = list(model.position(X))
        w = model.world_velocity()
        R = model.attitude(X)
        if R is None:
            yaw = sp.atan2(w[1], w[0])
            pitch = sp.atan2(-w[2], sp.sqrt(w[0] ** 2 + w[1] ** 2))
            ang = [sp.Integer(0), pitch, yaw]
            vb = [sp.sqrt(w[0] ** 2 + w[1] ** 2 + w[2] ** 2), sp.Integer(0), sp.Integer(0)]
        else:
            own = dict(zip(model.physical, model.from_common()))
            # the model's own Euler angles when they are the common ones (exact for every pitch), else read off R
            ang = (list(self.common[3:6]) if all(own.get(a) == a for a in self.common[3:6])
                   else [sp.simplify(a) for a in euler_of_rotation(R)])
            vb = list((R.T * w).applyfunc(lambda e: sp.simplify(sp.expand(e))))
        body_rate = model.body_rate()
        rate = list(body_rate) if body_rate is not None else [_set_to(model, c) for c in self.common[9:]]
        return p + ang + vb + rate


def _set_to(model, c):
    """The physical coordinate that ``model.from_common`` sets to the common coordinate c, else 0."""
    return next((p for p, e in zip(model.physical, model.from_common()) if sp.sympify(e) == c), sp.Integer(0))


PLANE = Plane()
SPACE3 = Space3()
#: the space of the commands' defaults (``lgekf track``, ``lgekf study``): the paper's plane
DEFAULT_SPACE = PLANE
