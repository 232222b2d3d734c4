"""The common physical coordinates c of a model's space and how every model's state and covariance are made from them
(what ``lgekf track`` and the study do inside): in the plane c = (x, y, θ, v_x, v_y, ω) ((v_x, v_y) body-frame
velocity), in 3-D c = (x, y, z, roll, pitch, yaw, v_x, v_y, v_z, ω_x, ω_y, ω_z) (Z-Y-X Euler angles, body-frame
velocity and rate; ``lgekf.core.registry.SPACES``)."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from .registry import DEFAULT_SPACE, SPACES, get_model
from .validate import as_float_array

__all__ = ["state_from_common", "covariance_from_common", "common_world_velocity", "common_turn_rate", "euler_rotations",
           "COMMON_NAMES"]

#: the names of the common coordinates (the physical state of SE(2)×SE(2) and SE(2)×R³)
COMMON_NAMES = SPACES[DEFAULT_SPACE]["common_names"]  # the plane's: ("x", "y", "theta", "vx", "vy", "omega")


def state_from_common(model: str, c: ArrayLike) -> np.ndarray:
    """The physical state of ``model`` for common coordinates c (n_c,) or (B, n_c) of its space (n_c = 6 in the plane,
    12 in 3-D).

    Parameters
    ----------
    model : str
        A registry model.
    c : array_like, (n_c,) or (B, n_c)
        Common coordinates (x, y, θ, v_x, v_y, ω), (v_x, v_y) in the body frame; in 3-D
        (x, y, z, roll, pitch, yaw, v_x, v_y, v_z, ω_x, ω_y, ω_z).

    Returns
    -------
    ndarray, (n,) or (B, n)

    Examples
    --------
    >>> state_from_common("ctrv", [0, 0, 0.1, 3.0, 0.0, 0.2])   # (x, y, ψ, v, ω)
    array([0. , 0. , 0.1, 3. , 0.2])
    """
    spec = get_model(model)
    nc = len(SPACES[spec.space]["common_names"])
    c = as_float_array("c", c)
    flat = c.reshape(-1, nc) if c.shape[-1:] == (nc,) else None
    if flat is None:
        raise ValueError(f"c: expected shape ({nc},) or (B, {nc}), got {c.shape}")
    out = np.array([spec.kernels.common_to_state(ci) for ci in flat])
    return out.reshape(c.shape[:-1] + (spec.n,))


def covariance_from_common(model: str, c: ArrayLike, P_common: ArrayLike) -> np.ndarray:
    """P0 in the filter's coordinates from a covariance of the common coordinates.

    P = J P_c Jᵀ with J the (generated) Jacobian of the filter's tangent coordinates ε (X = μ·exp ε) with
    respect to the common coordinates c at c (in the plane (x, y, θ, v_x, v_y, ω)). This is what ``lgekf track`` and the
    study do inside.

    Parameters
    ----------
    model : str
        A registry model.
    c : array_like, (n_c,) or (B, n_c)
        Common coordinates of the estimate (n_c = 6 in the plane, 12 in 3-D).
    P_common : array_like, (n_c, n_c) or (B, n_c, n_c)
        Their covariance.

    Returns
    -------
    ndarray, (n, n) or (B, n, n)
        Symmetrised. Singular where the model's coordinates are (CTRV's ψ, SE(2)×R²'s θ at v = 0).

    Examples
    --------
    >>> P = covariance_from_common("se2se2", [0, 0, 0, 3, 0, 0], np.diag([1, 1, 0.01, 1, 1, 0.01]))
    >>> bool(np.allclose(P, np.diag([1, 1, 0.01, 1, 1, 0.01])))
    True
    """
    spec = get_model(model)
    nc = len(SPACES[spec.space]["common_names"])
    c = as_float_array("c", c)
    Pc = as_float_array("P_common", P_common)
    if c.shape[-1:] != (nc,) or Pc.shape[-2:] != (nc, nc):
        raise ValueError(f"c, P_common: expected (…, {nc}) and (…, {nc}, {nc}), got {c.shape} and {Pc.shape}")
    J = np.array([spec.kernels.common_jacobian(ci) for ci in c.reshape(-1, nc)]).reshape(c.shape[:-1] + (spec.n, nc))
    P = J @ Pc @ np.swapaxes(J, -1, -2)
    return 0.5 * (P + np.swapaxes(P, -1, -2))


def common_world_velocity(c: np.ndarray) -> np.ndarray:
    """World-frame velocity (N, d) of common coordinates c (N, n_c): in the plane (n_c = 6) R(θ)·(v_x, v_y); in 3-D
    (n_c = 12) R·(v_x, v_y, v_z) with R = R_z(yaw) R_y(pitch) R_x(roll) (``derive.space.euler_rotation``)."""
    if c.shape[1] == 6:
        ct, st = np.cos(c[:, 2]), np.sin(c[:, 2])
        return np.stack([ct * c[:, 3] - st * c[:, 4], st * c[:, 3] + ct * c[:, 4]], axis=1)
    return np.einsum("nij,nj->ni", euler_rotations(c[:, 3:6]), c[:, 6:9])


def euler_rotations(rpy: np.ndarray) -> np.ndarray:
    """R = R_z(yaw) R_y(pitch) R_x(roll) (N, 3, 3) of Z-Y-X Euler angles rpy (N, 3) = (roll, pitch, yaw) (the common
    attitude of 3-D space, ``derive.space.euler_rotation``)."""
    cr, sr = np.cos(rpy[:, 0]), np.sin(rpy[:, 0])
    cp, sp = np.cos(rpy[:, 1]), np.sin(rpy[:, 1])
    cy, sy = np.cos(rpy[:, 2]), np.sin(rpy[:, 2])
    return np.stack([np.stack([cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr], axis=-1),
                     np.stack([sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr], axis=-1),
                     np.stack([-sp, cp * sr, cp * cr], axis=-1)], axis=1)


def common_turn_rate(c: np.ndarray) -> np.ndarray:
    """The turn rate dχ/dt (N,) (rad/s) of 3-D common coordinates c (N, 12), χ = atan2(v_y, v_x) the course of the world
    velocity v = R v_b: with the body velocity v_b constant in the body frame and the body rate ω, the world
    acceleration is a = R (ω × v_b), and dχ/dt = (v_x a_y − v_y a_x)/(v_x² + v_y²) (NaN where the horizontal speed
    is 0); for a level turn at rate ω_z this is ω_z, the CT3 model's turn rate."""
    R = euler_rotations(c[:, 3:6])
    v = np.einsum("nij,nj->ni", R, c[:, 6:9])
    a = np.einsum("nij,nj->ni", R, np.cross(c[:, 9:12], c[:, 6:9]))
    h2 = v[:, 0] ** 2 + v[:, 1] ** 2
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(h2 > 0, (v[:, 0] * a[:, 1] - v[:, 1] * a[:, 0]) / h2, np.nan)
