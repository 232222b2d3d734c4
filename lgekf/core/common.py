"""The common physical coordinates c = (x, y, θ, v_x, v_y, ω) ((v_x, v_y) body-frame velocity) and how
every model's state and covariance are made from them (what ``lgekf track`` and the study do inside)."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from .registry import get_model
from .validate import as_float_array

__all__ = ["state_from_common", "covariance_from_common", "common_world_velocity", "COMMON_NAMES"]

#: the names of the common coordinates (the physical state of SE(2)×SE(2) and SE(2)×R³)
COMMON_NAMES = ("x", "y", "theta", "vx", "vy", "omega")


def state_from_common(model: str, c: ArrayLike) -> np.ndarray:
    """The physical state of ``model`` for common coordinates c (6,) or (B, 6).

    Parameters
    ----------
    model : str
        A registry model.
    c : array_like, (6,) or (B, 6)
        Common coordinates (x, y, θ, v_x, v_y, ω), (v_x, v_y) in the body frame.

    Returns
    -------
    ndarray, (n,) or (B, n)

    Examples
    --------
    >>> state_from_common("ctrv", [0, 0, 0.1, 3.0, 0.0, 0.2])   # (x, y, ψ, v, ω)
    array([0. , 0. , 0.1, 3. , 0.2])
    """
    spec = get_model(model)
    c = as_float_array("c", c)
    flat = c.reshape(-1, 6) if c.shape[-1:] == (6,) else None
    if flat is None:
        raise ValueError(f"c: expected shape (6,) or (B, 6), got {c.shape}")
    out = np.array([spec.kernels.common_to_state(ci) for ci in flat])
    return out.reshape(c.shape[:-1] + (spec.n,))


def covariance_from_common(model: str, c: ArrayLike, P_common: ArrayLike) -> np.ndarray:
    """P0 in the filter's coordinates from a covariance of the common coordinates.

    P = J P_c Jᵀ with J the (generated) Jacobian of the filter's tangent coordinates ε (X = μ·exp ε) with
    respect to c = (x, y, θ, v_x, v_y, ω) at c. This is what ``lgekf track`` and the study do inside.

    Parameters
    ----------
    model : str
        A registry model.
    c : array_like, (6,) or (B, 6)
        Common coordinates of the estimate.
    P_common : array_like, (6, 6) or (B, 6, 6)
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
    c = as_float_array("c", c)
    Pc = as_float_array("P_common", P_common)
    if c.shape[-1:] != (6,) or Pc.shape[-2:] != (6, 6):
        raise ValueError(f"c, P_common: expected (…, 6) and (…, 6, 6), got {c.shape} and {Pc.shape}")
    J = np.array([spec.kernels.common_jacobian(ci) for ci in c.reshape(-1, 6)]).reshape(c.shape[:-1] + (spec.n, 6))
    P = J @ Pc @ np.swapaxes(J, -1, -2)
    return 0.5 * (P + np.swapaxes(P, -1, -2))


def common_world_velocity(c: np.ndarray) -> np.ndarray:
    """World-frame velocity (N, 2) of common coordinates c (N, 6): R(θ)·(v_x, v_y)."""
    ct, st = np.cos(c[:, 2]), np.sin(c[:, 2])
    return np.stack([ct * c[:, 3] - st * c[:, 4], st * c[:, 3] + ct * c[:, 4]], axis=1)
