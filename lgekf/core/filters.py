"""Filters with one shape (FilterPy style): ``predict()``, ``update(z)``, ``x``, ``P``; one class per model.

Every model's mathematics lives in its generated kernels (``lgekf.generated.<model>``); a filter here only
validates its arguments, holds the internal state and the packed covariance, and calls the kernels.
The classes are made from the registry (``SE2SE2Filter``, ``SE2R3Filter``, ``SE2R2Filter``, ``CTRVFilter``,
``CVFilter``, ... one per model definition); ``Filter(model=...)`` and ``make_filter`` take the name.

Conventions
-----------
* The state X lives on the model's Lie group; perturbations act on the right, X = μ·exp(ε^∧), and ``P``
  is the covariance of ε, ordered like the physical state ``x`` (``state_names``). For the Euclidean
  models (CTRV on R⁵, CV on R⁴) ε is the plain state error, so the filter is the textbook EKF/KF.
* Physical states: SE(2)×SE(2), SE(2)×R³ ``[x, y, θ, v_x, v_y, ω]`` ((v_x, v_y) body-frame velocity);
  SE(2)×R² ``[x, y, θ, v, ω]``; CTRV ``[x, y, ψ, v, ω]``; CV ``[x, y, v_x, v_y]`` (world frame).
  In SE(2)×SE(2) ω is the angle of T_d's rotation and lives in [−π, π] rad/s.
* ``accel_std``: the model's process-noise stds (``noise_names``): SE(2)×SE(2), SE(2)×R³ (σ_x, σ_y, σ_ω)
  as n_k of the paper (Q = G diag(σ²) Gᵀ, G = [T²/2·I; T·I]); SE(2)×R² and CTRV (σ_a, σ_α) forward and
  yaw acceleration; CV σ_a (isotropic).
* ``measurement="position"`` (default in the plane; ``"position3"`` in space): z = (x, y) (or (x, y, z)), ``meas_std``
  one std r per axis.
  ``measurement="pose"``: z = (x, y, θ) ∈ SE(2), Z = h(X)·exp(m), m ~ N(0, diag(σ_x², σ_y², σ_θ²)) in
  the tangent of SE(2) (body frame), ``meas_std = (σ_x, σ_y, σ_θ)``; not for models without a heading (CV).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from .covariance import pack, unpack
from .registry import ALL_MODELS, ModelSpec, base_measurement, get_model
from .validate import as_float_array, positive_scalar, positive_vector, spd_matrix

__all__ = ["Filter", "make_filter", *[f"{name.upper()}Filter" for name in ALL_MODELS]]


def measurement_std(spec: ModelSpec, measurement: str, meas_std) -> np.ndarray:
    """``meas_std`` as the vector of the measurement's noise stds (one number for position)."""
    meas = spec.measurement(measurement)
    return positive_vector("meas_std", meas_std, len(meas.noise_names), allow_zero=False)


class Filter:
    """An LG-EKF (or EKF/KF for the Euclidean models) for one object, one step at a time.

    Parameters
    ----------
    dt : float
        Default step length in s (``predict()`` without an argument).
    accel_std : array_like
        Process-noise stds of the model (``noise_names``; see the module docstring).
    meas_std : float or array_like
        Measurement-noise std(s): one number for ``"position"``, (σ_x, σ_y, σ_θ) for ``"pose"``.
    x0 : array_like
        Initial state in physical coordinates (``state_names``).
    P0 : array_like
        Initial covariance (n × n, symmetric positive definite) in the filter's tangent coordinates;
        see ``lgekf.covariance_from_common`` to build it from a covariance of the common coordinates.
    measurement : str, optional
        The measurement model used by ``update`` (``"position"``, ``"pose"``; ``"position3"`` for a 3-D model); default:
        the position measurement of the model's space.
    model : str, optional
        The registry model (only for the generic ``Filter``; the per-model classes fix it).
    record : bool
        Keep every step's predicted and posterior state (a few hundred bytes per step) so that
        ``smooth()`` can run the RTS backward pass on the group after the run (default False).

    Attributes
    ----------
    x : ndarray
        The state in physical coordinates: a read-only copy (``f.x[0] = 5`` raises); assign a whole state with
        ``f.x = [...]`` (checked like ``x0``; the covariance is kept).
    P : ndarray
        The covariance in the filter's tangent coordinates: a read-only copy; ``f.P = ...`` sets it (symmetric positive
        definite, checked like ``P0``).
    nis : float
        Normalised innovation squared of the last update (NaN before the first).
    x_prior, P_prior : ndarray
        The state and covariance before the last ``update`` (FilterPy's names; None before the first).
    y, S, K : ndarray
        The last update's innovation y = [log_G'(h(μ)⁻¹ Z)]^∨ (eq:K), its covariance S = ℋ P ℋᵀ + R and the Kalman gain
        K = P ℋᵀ S⁻¹, all at the prior (the fused update damps K where a large heading correction would bend it:
        then its step is α K y; ``lgekf.estimators`` docs); None before the first update.
    log_likelihood : float
        log N(y; 0, S) of the last update (NaN before the first).
    """

    model = ""

    def __init__(self, dt: float, accel_std: ArrayLike, meas_std: float | ArrayLike, x0: ArrayLike, P0: ArrayLike, *,
                 measurement: str | None = None, model: str | None = None, record: bool = False):
        spec = get_model(model if model is not None else self.model)
        if measurement is None:
            measurement = base_measurement(spec.space)
        self._spec = spec
        self._k = spec.kernels
        self.measurement = measurement
        self.dt = positive_scalar("dt", dt)
        self.accel_std = accel_std
        self.meas_std = meas_std
        self._m = spec.measurement(measurement).dim
        self._update = spec.kernel("update", measurement)
        x0 = as_float_array("x0", x0, (spec.n,))
        spec.check_state("x0", x0)
        P0 = spd_matrix("P0", P0, spec.n)
        self._s = self._k.state_from_physical(x0)
        self._p = pack(P0)
        self.nis = float("nan")
        self._prior = None  # (s, p, z) before the last update: x_prior, P_prior, y, S, K are made from it on demand
        self.record = bool(record)
        self._history = []  # per predict: [dt, s_pred, p_pred, s_post, p_post]

    @property
    def accel_std(self) -> np.ndarray:
        """Process-noise stds (``noise_names``); settable between steps."""
        return np.array(self._q)

    @accel_std.setter
    def accel_std(self, value):
        # kept as Python floats: the cheapest arguments for numba's dispatcher
        self._q = tuple(float(v) for v in positive_vector("accel_std", value, len(self._spec.noise_names)))

    @property
    def meas_std(self) -> np.ndarray:
        """Measurement-noise stds (one for position, three for pose); settable between steps."""
        return np.array(self._r)

    @meas_std.setter
    def meas_std(self, value):
        self._r = tuple(float(v) for v in measurement_std(self._spec, self.measurement, value))

    @property
    def state_names(self) -> tuple:
        """Names of the physical state entries, also the order of P's coordinates."""
        return self._spec.state_names

    def predict(self, dt: float | None = None) -> None:
        """Propagate the state by ``dt`` seconds (default: the filter's ``dt``), eq:pred_mu, eq:pred_cov."""
        step = self.dt if dt is None else positive_scalar("dt", dt)
        self._k.predict(self._s, self._p, step, *self._q)
        if self.record:
            self._history.append([step, self._s.copy(), self._p.copy(), self._s.copy(), self._p.copy()])

    def update(self, z: ArrayLike) -> float:
        """Correct with one measurement z ((x, y) or (x, y, θ)); returns the NIS of the innovation."""
        z = as_float_array("z", z, (self._m,))
        self._prior = (self._s.copy(), self._p.copy(), z)
        self.nis = float(self._update(self._s, self._p, *z.tolist(), *self._r))
        if self.record and self._history:
            self._history[-1][3] = self._s.copy()
            self._history[-1][4] = self._p.copy()
        return self.nis

    def smooth(self) -> tuple[np.ndarray, np.ndarray]:
        """Rauch–Tung–Striebel smoothing on the group of the steps run so far (needs ``record=True``).

        One step per ``predict()`` call, with the posterior after that step's last ``update`` (or the
        prediction for a step without one); the derivation is in ``lgekf.estimators.smoother``.

        Returns
        -------
        x : ndarray, (K, n)
            Smoothed physical states.
        P : ndarray, (K, n, n)
            Smoothed covariances in the filter's tangent coordinates.
        """
        if not self.record:
            raise ValueError("smooth: create the filter with record=True to keep the history a smoother needs")
        if not self._history:
            raise ValueError("smooth: no step has been run")
        dts = np.array([h[0] for h in self._history])
        s_pred, p_pred, s_filt, p_filt = (np.array([h[i] for h in self._history]) for i in range(1, 5))
        s_sm = np.empty_like(s_filt)
        p_sm = np.empty_like(p_filt)
        self._k.smooth_one(dts, s_pred, p_pred, s_filt, p_filt, len(dts), s_sm, p_sm)
        x = np.array([self._k.state_to_physical(si) for si in s_sm])
        return x, unpack(p_sm, self._spec.n)

    @property
    def x(self) -> np.ndarray:
        return _read_only(self._k.state_to_physical(self._s))

    @x.setter
    def x(self, value):
        x = as_float_array("x", value, (self._spec.n,))
        self._spec.check_state("x", x)
        self._s = self._k.state_from_physical(x)

    @property
    def P(self) -> np.ndarray:
        return _read_only(unpack(self._p, self._spec.n))

    @P.setter
    def P(self, value):
        self._p = pack(spd_matrix("P", value, self._spec.n))

    @property
    def x_prior(self) -> np.ndarray | None:
        return None if self._prior is None else _read_only(self._k.state_to_physical(self._prior[0]))

    @property
    def P_prior(self) -> np.ndarray | None:
        return None if self._prior is None else _read_only(unpack(self._prior[1], self._spec.n))

    def _innovation(self):
        """(y, S, K) of the last update, at its prior (class docstring)."""
        s, p, z = self._prior
        H = np.asarray(self._spec.kernel("calH", self.measurement)(s), dtype=float)
        y = np.empty(self._m)
        self._spec.kernel("innovation_into", self.measurement)(s, *z.tolist(), y)
        meas = self._spec.measurement(self.measurement)
        r = np.asarray(self._r)
        R = np.diag(r[list(meas.noise_inputs)] ** 2) if meas.noise_inputs is not None else np.eye(self._m) * r[0] ** 2
        P = unpack(p, self._spec.n)
        S = H @ P @ H.T + R
        K = np.linalg.solve(S, H @ P).T
        return y, S, K

    @property
    def y(self) -> np.ndarray | None:
        return None if self._prior is None else _read_only(self._innovation()[0])

    @property
    def S(self) -> np.ndarray | None:
        return None if self._prior is None else _read_only(self._innovation()[1])

    @property
    def K(self) -> np.ndarray | None:
        return None if self._prior is None else _read_only(self._innovation()[2])

    @property
    def log_likelihood(self) -> float:
        if self._prior is None:
            return float("nan")
        y, S, _ = self._innovation()
        _, logdet = np.linalg.slogdet(S)
        return float(-0.5 * (y.size * np.log(2 * np.pi) + logdet + y @ np.linalg.solve(S, y)))

    @property
    def mean(self) -> np.ndarray:
        """The group mean μ as a matrix (block-diagonal for a product group; [[I, x], [0, 1]] on Rⁿ)."""
        return np.asarray(self._k.group_mean(self._s))

    def __repr__(self) -> str:
        xs = ", ".join(f"{n}={v:.4g}" for n, v in zip(self.state_names, self.x))
        return f"{type(self).__name__}({xs})"


def _read_only(a) -> np.ndarray:
    """A copy that refuses in-place assignment (``f.x[0] = 5`` would otherwise change nothing, silently)."""
    a = np.array(a, dtype=float)
    a.flags.writeable = False
    return a


def _model_class(spec: ModelSpec) -> type:
    doc = (
        f"{spec.display_name}: {spec.description}.\n\n"
        f"State x = [{', '.join(spec.state_names)}]; accel_std = ({', '.join(spec.noise_names)}); "
        f"measurements: {', '.join(spec.measurements)}.\n\n" + Filter.__doc__.split("\n\n", 1)[1]
    )
    return type(f"{spec.name.upper()}Filter", (Filter,), {"model": spec.name, "__doc__": doc, "__module__": __name__})


_CLASSES = {name: _model_class(spec) for name, spec in ALL_MODELS.items()}
globals().update({cls.__name__: cls for cls in _CLASSES.values()})


def make_filter(model: str, **kwargs) -> Filter:
    """The filter class of a registry model, by name.

    Parameters
    ----------
    model : str
        A registry model ("se2se2", "se2r3", "se2r2", "ctrv", "cv", ...).
    **kwargs
        The arguments of :class:`Filter` (dt, accel_std, meas_std, x0, P0, measurement).

    Returns
    -------
    Filter
        An instance of the model's class, e.g. ``SE2R2Filter``.

    Examples
    --------
    >>> f = make_filter("cv", dt=0.1, accel_std=0.5, meas_std=0.3, x0=[0, 0, 1, 0], P0=np.eye(4))
    >>> f.predict(); nis = f.update([0.1, 0.0])
    """
    get_model(model)
    return _CLASSES[model](**kwargs)
