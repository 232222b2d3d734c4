"""The four trackers with one shape (FilterPy style): ``predict()``, ``update(z)``, ``x``, ``P``.

Every model's mathematics lives in the generated kernels (``lgekf.generated``); a filter here only
validates its arguments, holds the internal state and the packed covariance, and calls the kernels.

Conventions
-----------
* ``SE2SE2Filter`` / ``SE2R3Filter``: ``x = [x, y, θ, v_x, v_y, ω]`` with (v_x, v_y) the body-frame
  velocity and ω the angular velocity; the mean is X = (T_s, T_d) (resp. (T_s, v)), see ``mean``.
  ``P`` is 6×6 in the right-perturbation tangent coordinates X = μ·exp(ε), ε ordered like ``x``.
  In SE(2)×SE(2) ω is the angle of T_d's rotation (its log, atan2(sin, cos)), so it lives in
  [-π, π] rad/s: a larger turn rate aliases (Ω = T·ω uses that angle, as in the paper).
* ``CTRVFilter``: ``x = [x, y, ψ, v, ω]``; ``CVFilter``: ``x = [x, y, v_x, v_y]`` (world frame);
  their ``P`` is in those coordinates.
* ``accel_std``: SE(2) filters (σ_x, σ_y, σ_ω) entering as n_k of the paper (Q = G diag(σ²) Gᵀ,
  G = [T²/2·I; T·I]); CTRV (σ_a, σ_ω̇) longitudinal and yaw acceleration; CV σ_a (isotropic).
* ``meas_std``: std of each position component of z = (x, y).
"""

from __future__ import annotations

import numpy as np

from .covariance import pack, unpack
from .registry import get_model
from .validate import as_float_array, positive_scalar, positive_vector, spd_matrix

__all__ = ["SE2SE2Filter", "SE2R3Filter", "CTRVFilter", "CVFilter", "make_filter"]


class _KernelFilter:
    model = ""

    def __init__(self, dt, accel_std, meas_std, x0, P0):
        spec = get_model(self.model)
        self._spec = spec
        self._k = spec.kernels
        self.dt = positive_scalar("dt", dt)
        self.accel_std = positive_vector("accel_std", accel_std, len(spec.noise_names))
        self.meas_std = positive_scalar("meas_std", meas_std)
        x0 = as_float_array("x0", x0, (spec.n,))
        spec.check_state("x0", x0)
        P0 = spd_matrix("P0", P0, spec.n)
        self._s = self._k.state_from_physical(x0)
        self._p = pack(P0)
        self.nis = float("nan")  #: NIS of the last update

    @property
    def state_names(self) -> tuple[str, ...]:
        return self._spec.state_names

    def predict(self, dt=None) -> None:
        """Propagate the state by ``dt`` (default: the filter's dt)."""
        step = self.dt if dt is None else positive_scalar("dt", dt)
        self._k.predict(self._s, self._p, step, *self.accel_std)

    def update(self, z) -> float:
        """Correct with a position measurement z = (x, y); returns the NIS of the innovation."""
        z = as_float_array("z", z, (2,))
        self.nis = float(self._k.update(self._s, self._p, z[0], z[1], self.meas_std))
        return self.nis

    @property
    def x(self) -> np.ndarray:
        """The state in physical coordinates (a copy)."""
        return np.asarray(self._k.state_to_physical(self._s))

    @property
    def P(self) -> np.ndarray:
        """The covariance in the filter's own coordinates (a copy)."""
        return unpack(self._p, self._spec.n)

    def __repr__(self) -> str:
        xs = ", ".join(f"{n}={v:.4g}" for n, v in zip(self.state_names, self.x))
        return f"{type(self).__name__}({xs})"


class _LGFilter(_KernelFilter):
    @property
    def mean(self) -> np.ndarray:
        """The group mean μ as a block-diagonal matrix (T_s, T_d) resp. (T_s, [[I, v], [0, 1]])."""
        return np.asarray(self._k.group_mean(self._s))


class SE2SE2Filter(_LGFilter):
    """LG-EKF on SE(2)×SE(2) (Ćesić et al.): pose T_s and velocity T_d both in SE(2)."""

    model = "se2se2"


class SE2R3Filter(_LGFilter):
    """LG-EKF on SE(2)×R³: pose T_s in SE(2), velocity (v_x, v_y, ω) a vector."""

    model = "se2r3"


class CTRVFilter(_KernelFilter):
    """EKF with the constant turn rate and velocity model (exact discretisation, Joseph update)."""

    model = "ctrv"


class CVFilter(_KernelFilter):
    """Linear Kalman filter with the constant velocity model (Joseph update)."""

    model = "cv"


_CLASSES = {c.model: c for c in (SE2SE2Filter, SE2R3Filter, CTRVFilter, CVFilter)}


def make_filter(model: str, **kwargs) -> _KernelFilter:
    """The filter class for a model name ("se2se2", "se2r3", "ctrv", "cv")."""
    get_model(model)
    return _CLASSES[model](**kwargs)
