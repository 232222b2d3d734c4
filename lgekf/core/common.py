"""The common physical coordinates c = (x, y, θ, v_x, v_y, ω) ((v_x, v_y) body-frame velocity) and how
every model's state and covariance are made from them (what ``lgekf track`` and the study do inside)."""

from __future__ import annotations

import numpy as np

from .registry import get_model
from .validate import as_float_array

__all__ = ["state_from_common", "covariance_from_common"]


def state_from_common(model: str, c) -> np.ndarray:
    """The physical state of ``model`` for common coordinates c (6,) or (B, 6).

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


def covariance_from_common(model: str, c, P_common) -> np.ndarray:
    """P0 in the filter's coordinates from a covariance of the common coordinates: P = J P_c Jᵀ, J the
    (generated) Jacobian of the filter's tangent coordinates w.r.t. c at c. c (6,) or (B, 6); P_common
    (6, 6) or (B, 6, 6). Symmetrised; singular where the model's coordinates are (CTRV, SE(2)×R² at v = 0)."""
    spec = get_model(model)
    c = as_float_array("c", c)
    Pc = as_float_array("P_common", P_common)
    if c.shape[-1:] != (6,) or Pc.shape[-2:] != (6, 6):
        raise ValueError(f"c, P_common: expected (…, 6) and (…, 6, 6), got {c.shape} and {Pc.shape}")
    J = np.array([spec.kernels.common_jacobian(ci) for ci in c.reshape(-1, 6)]).reshape(c.shape[:-1] + (spec.n, 6))
    P = J @ Pc @ np.swapaxes(J, -1, -2)
    return 0.5 * (P + np.swapaxes(P, -1, -2))
