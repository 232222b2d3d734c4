"""Noise learned from the data: maximum-likelihood process and measurement noise of any registry model.

The filter's innovations e_k = [log_G'(h(μ_{k|k-1})⁻¹ Z_k)]^∨ with covariance S_k = ℋ P_{k|k-1} ℋᵀ + R (eq:K)
give the prediction-error decomposition of the likelihood of the measurements (Schweppe 1965; Harvey,
*Forecasting, structural time series models and the Kalman filter*, 1989, §3.4):

    log L(θ) = Σ_tracks Σ_k −½ (log det S_k + e_kᵀ S_k⁻¹ e_k + m log 2π),

exact for a linear Gaussian model (CV) and the usual EKF approximation otherwise. Each track is conditioned
on its first measurement and the first one at least ``baseline`` (1 s) later, which start the filter
(``two_point_prior``). The parameters θ are the logs
of the model's process-noise stds (``accel_std``, its ``noise_names``) and of the measurement stds (one for
position; (σ_x, σ_y, σ_θ) for pose), unless ``meas_std`` is given (then fixed). The generated
``loglik_batch_<measurement>`` evaluates log L over all tracks in numba (prange); ``scipy.optimize``
maximises it: L-BFGS-B on log θ (bounded, several starts, finite-difference steps of 1e-3), then a
Nelder–Mead polish of the best (on real data the likelihood has small kinks, e.g. from the angle-variance cap,
and gradient steps alone can stall at a start).

Uncertainty: the observed information, the Hessian H of −log L in log θ at the optimum by central
differences; cov(log θ) ≈ H⁻¹, and the approximate 95 % interval of each std is exp(log θ̂ ± 1.96 se).
The fit says when the data do not identify the noise (``NoiseFit.problems``): fewer than
``MIN_UPDATES_PER_PARAMETER`` updates per parameter is refused (ValueError); a Hessian that is not positive
definite (flat likelihood), an interval wider than a factor ``WIDE_FACTOR`` either way, an optimum on a
bound, or starts ending at different optima are reported.

Measured (tests/test_tuning.py): with SE(2)×SE(2) truth (σ_v, σ_ω, r) = (0.5, 0.2, 0.2) the 95 % intervals
cover the truth on 60 tracks of 20 s. From positions alone the lateral-velocity std of SE(2)×SE(2) and
SE(2)×R³ trades against the turn-rate std (both bend the path) and on 6 s tracks it is reported as not
identified. The two-point start needs a baseline: with the first two measurements 0.1 s apart (heading
almost unknown) the same data gave σ_ω = 0.35 [0.29, 0.42], far above the truth, hence ``baseline`` = 1 s.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike

from ..core.covariance import pack
from ..core.registry import get_model
from .tracks import TrackBatch, batch_tracks, two_point_prior

__all__ = ["NoiseFit", "learn_noise", "log_likelihood", "MIN_UPDATES_PER_PARAMETER"]

MIN_UPDATES_PER_PARAMETER = 10
WIDE_FACTOR = 10.0  # a 95 % interval beyond ×/÷ this counts as not identified
BOUNDS = (1e-4, 1e3)  # every std is searched in this range
PENALTY = 1e15  # −log L of a diverged filter (NaN)


@dataclass
class NoiseFit:
    """Result of :func:`learn_noise`.

    Attributes
    ----------
    model, measurement : str
    names : tuple of str
        The parameters: the model's ``noise_names`` then the measurement's noise names.
    values : ndarray
        The learned stds (a fixed measurement std is included as given).
    ci_low, ci_high : ndarray
        Approximate 95 % intervals (NaN where the Hessian gives none; equal to the value for a fixed one).
    log_se : ndarray
        Standard errors of the log stds (NaN: not available or fixed).
    loglik : float
        The maximised innovation log-likelihood.
    n_updates, n_tracks : int
        Measurements that updated a filter, and tracks used.
    fixed : tuple of bool
        Which parameters were held fixed.
    starts : list
        (start values, end values, log-likelihood) of every start.
    problems : list of str
        Why the noise may not be identified (empty when it is).
    method : str
        "lbfgs" (the likelihood optimiser) or "em" (``lgekf.estimators.em``).
    """

    model: str
    measurement: str
    names: tuple
    values: np.ndarray
    ci_low: np.ndarray
    ci_high: np.ndarray
    log_se: np.ndarray
    loglik: float
    n_updates: int
    n_tracks: int
    fixed: tuple
    starts: list = field(default_factory=list)
    problems: list = field(default_factory=list)
    method: str = "lbfgs"

    @property
    def accel_std(self) -> tuple:
        """The learned process-noise stds (the model's ``accel_std``)."""
        nq = len(get_model(self.model).noise_names)
        return tuple(float(v) for v in self.values[:nq])

    @property
    def meas_std(self) -> tuple:
        """The measurement stds (learned, or as given)."""
        nq = len(get_model(self.model).noise_names)
        return tuple(float(v) for v in self.values[nq:])

    @property
    def identified(self) -> bool:
        """True when no problem was found (see ``problems``)."""
        return not self.problems

    def report(self) -> str:
        """A few lines for a human: every value with its interval, the likelihood and the problems."""
        parts = []
        for nm, v, lo, hi, fx in zip(self.names, self.values, self.ci_low, self.ci_high, self.fixed):
            if fx:
                parts.append(f"{nm} = {v:.4g} (fixed)")
            elif np.isfinite(lo):
                parts.append(f"{nm} = {v:.4g} [95 %: {lo:.3g}, {hi:.3g}]")
            else:
                parts.append(f"{nm} = {v:.4g} [no interval]")
        head = (f"learned noise for {self.model}{' by EM' if self.method == 'em' else ''} ({self.measurement}, {self.n_tracks} tracks, {self.n_updates} updates, "
                f"log-likelihood {self.loglik:.6g}): " + ", ".join(parts))
        if self.problems:
            head += "\n  not identified: " + "; ".join(self.problems)
        return head


def log_likelihood(model: str, batch: TrackBatch, accel_std: ArrayLike, meas_std: ArrayLike, *,
                   measurement: str = "position", x0=None, P0=None) -> float:
    """Innovation log-likelihood Σ −½(log det S + eᵀS⁻¹e + m log 2π) of the tracks of ``batch``.

    Parameters
    ----------
    model : str
        A registry model.
    batch : TrackBatch
        The tracks (``lgekf.estimators.tracks.batch_tracks``).
    accel_std, meas_std : array_like
        Process-noise stds (``noise_names``) and measurement stds (one for position, three for pose).
    measurement : {"position", "pose"}
    x0, P0 : ndarray, optional
        Initial states (B, n) and covariances (B, n, n); default the two-point prior of each track.

    Returns
    -------
    float
        The log-likelihood (NaN if a filter diverged).
    """
    spec = get_model(model)
    meas = spec.measurement(measurement)
    r = np.asarray(meas_std, dtype=float).reshape(-1)
    if x0 is None or P0 is None:
        x0, prior = two_point_prior(spec, batch, _angle_index(meas))
        P0 = prior(r[0], r[-1] if meas.angles else None)
    return float(np.sum(_loglik_tracks(spec, measurement, batch, np.asarray(accel_std, float), r, x0, pack(P0))[0]))


def _angle_index(meas):
    return meas.angles[0] if meas.angles else None


def _loglik_tracks(spec, measurement, batch, q, r, x0, p0):
    B = batch.z.shape[0]
    ll = np.empty(B)
    cnt = np.empty(B, dtype=np.int64)
    spec.kernel("loglik_batch", measurement)(batch.z, batch.dts, x0, p0, q, r, batch.lengths, ll, cnt)
    return ll, cnt


def _meas_guess(batch: TrackBatch, m: int) -> float:
    """A rough position-noise std from the data: second differences of evenly spaced positions are
    dominated by the noise (var 6 r²) when the motion is smooth; an overestimate otherwise."""
    d2 = np.diff(batch.z[:, :, :2], n=2, axis=1)
    d2 = d2[np.all(np.isfinite(d2), axis=2)]
    if d2.size == 0:
        return 0.3
    return float(np.clip(np.sqrt(np.median(d2**2) / 6.0 / 0.455), 1e-3, 1e2))  # median of χ²₁ = 0.455


def _noise_problem(model, spec, meas, tracks, dt, meas_std, baseline):
    """The checked inputs of a noise fit (``learn_noise``, ``lgekf.estimators.em.learn_noise_em``): the tracks'
    batch, the numbers of process and measurement stds, the parameter names, the fixed measurement stds (or
    None), the number of learned parameters and of filter updates. ValueError for a bad ``meas_std`` or fewer
    than ``MIN_UPDATES_PER_PARAMETER`` updates per learned parameter."""
    batch = tracks if isinstance(tracks, TrackBatch) else batch_tracks(tracks, meas.dim, dt, baseline)
    nq = len(spec.noise_names)
    nr = len(meas.noise_names)
    names = tuple(spec.noise_names) + tuple(f"meas_{nm}" for nm in meas.noise_names)
    fixed_r = None
    if meas_std is not None:
        fixed_r = np.broadcast_to(np.asarray(meas_std, dtype=float).reshape(-1), (nr,)).copy()
        if np.any(~np.isfinite(fixed_r)) or np.any(fixed_r <= 0):
            raise ValueError(f"meas_std: must be positive, got {fixed_r.tolist()}")
    d = nq + (0 if fixed_r is not None else nr)
    n_upd = batch.n_updates
    need = MIN_UPDATES_PER_PARAMETER * d
    if n_upd < need:
        raise ValueError(
            f"too few measurements to learn the noise of {model}: {n_upd} filter updates in {batch.z.shape[0]} tracks "
            f"(each track's two-point start uses its first measurement and one ≥ baseline s later) for {d} parameters; need at least {need}")
    return batch, nq, nr, names, fixed_r, d, n_upd


def learn_noise(model: str, tracks, *, dt: float | None = None, measurement: str = "position",
                meas_std: float | ArrayLike | None = None, n_starts: int = 3, omega_std: float = 0.5,
                heading_cap: float = math.pi, hessian: bool = True, baseline: float = 1.0) -> NoiseFit:
    """Maximum-likelihood process noise (and measurement noise) of ``model`` from measured tracks.

    Parameters
    ----------
    model : str
        A registry model ("se2se2", "se2r3", "se2r2", "ctrv", "cv", ...).
    tracks : sequence or TrackBatch
        The user's trajectories: pairs (t (K,), z (K, m)), or arrays z (K, m) with ``dt``; NaN rows are
        missed detections (not the first two, which start each filter). Or a ready ``TrackBatch``.
    dt : float, optional
        Sampling period of tracks given without times.
    measurement : {"position", "pose"}
    meas_std : float or array_like, optional
        The measurement std(s), if known: then held fixed and only the process noise is learned.
    n_starts : int
        Number of starting points of the optimiser (the defaults of the model, ×4 and ÷4).
    omega_std, heading_cap : float
        Of the two-point prior (``lgekf.estimators.tracks.two_point_prior``).
    hessian : bool
        Compute the intervals (2d² extra likelihood evaluations).
    baseline : float
        Each track starts from its first measurement and the first one at least ``baseline`` s later (the
        two-point prior, ``lgekf.estimators.tracks.batch_tracks``); the measurements in between are not used.
        Two points 0.1 s apart leave the heading almost unknown (velocity error √2·r/Δ), and the likelihood
        of the steps that follow then asks for a much larger process noise than the motion has.

    Returns
    -------
    NoiseFit
        Learned stds, 95 % intervals, log-likelihood and ``problems`` (empty when identified).

    Raises
    ------
    ValueError
        Bad input, or fewer than ``MIN_UPDATES_PER_PARAMETER`` updates per learned parameter.

    See Also
    --------
    lgekf.estimators.em.learn_noise_em : the same maximum likelihood by EM, for the linear Gaussian models (CV).

    Examples
    --------
    >>> fit = learn_noise("cv", [(t, z) for t, z in my_tracks])          # doctest: +SKIP
    >>> fit.accel_std, fit.meas_std, fit.report()                         # doctest: +SKIP
    """
    from scipy.optimize import minimize

    spec = get_model(model)
    meas = spec.measurement(measurement)
    m = meas.dim
    batch, nq, nr, names, fixed_r, d, n_upd = _noise_problem(model, spec, meas, tracks, dt, meas_std, baseline)
    x0, prior = two_point_prior(spec, batch, _angle_index(meas), omega_std, heading_cap)

    def unpack_theta(th):
        v = np.exp(th)
        q = v[:nq]
        r = fixed_r if fixed_r is not None else v[nq:]
        return q, r

    def nll(th):
        q, r = unpack_theta(th)
        P0 = prior(r[0], r[-1] if meas.angles else None)
        ll, _ = _loglik_tracks(spec, measurement, batch, q, r, x0, pack(P0))
        tot = float(np.sum(ll))
        return -tot if math.isfinite(tot) else PENALTY

    q0 = np.asarray(spec.default_accel_std, dtype=float)
    r0 = np.full(nr, _meas_guess(batch, m))
    if nr > 1:
        r0[list(meas.angles)] = 0.1
    lo, hi = math.log(BOUNDS[0]), math.log(BOUNDS[1])
    bounds = [(lo, hi)] * d
    starts = []
    factors = [1.0, 4.0, 0.25, 16.0, 1 / 16][:max(1, n_starts)]
    for f in factors:
        th0 = np.log(np.concatenate([q0 * f, r0 if fixed_r is None else []]))
        th0 = np.clip(th0, lo + 0.1, hi - 0.1)
        # finite-difference gradient steps of 1e-3 in log θ: the likelihood of a real run has small kinks
        # (angle-variance cap, heading of slow objects) that make steps near machine precision useless
        res = minimize(nll, th0, method="L-BFGS-B", bounds=bounds, options={"maxiter": 200, "eps": 1e-3})
        starts.append((np.exp(th0), np.exp(res.x), -float(res.fun), res))
    best = max(starts, key=lambda s: s[2])
    # polish the best with Nelder–Mead (derivative-free, indifferent to the kinks), inside the bounds
    nm = minimize(lambda x: nll(np.clip(x, lo, hi)), best[3].x, method="Nelder-Mead",
                  options={"xatol": 1e-3, "fatol": 1e-3, "maxfev": 400 * d})
    if nm.fun < best[3].fun:
        nm.x = np.clip(nm.x, lo, hi)
        best = (best[0], np.exp(nm.x), -float(nm.fun), nm)
    th = best[3].x
    q, r = unpack_theta(th)
    values = np.concatenate([q, r])
    fixed = tuple([False] * nq + [fixed_r is not None] * nr)
    problems = []
    log_se = np.full(nq + nr, np.nan)
    if hessian:
        se = _standard_errors(nll, th)
        if se is not None:
            log_se[:d] = se  # the free parameters come first
        else:
            problems.append(FLAT_LIKELIHOOD)
    free = [i for i in range(nq + nr) if not fixed[i]]
    ci_low = values.copy()
    ci_high = values.copy()
    for i in free:
        with np.errstate(over="ignore"):  # a flat direction: the interval reaches 0 or ∞
            ci_low[i] = values[i] * np.exp(-1.96 * log_se[i]) if np.isfinite(log_se[i]) else np.nan
            ci_high[i] = values[i] * np.exp(1.96 * log_se[i]) if np.isfinite(log_se[i]) else np.nan
        if np.isfinite(log_se[i]) and 1.96 * log_se[i] > math.log(WIDE_FACTOR):
            problems.append(f"{names[i]}: the 95 % interval spans more than ×/÷{WIDE_FACTOR:g}")
    for j, i in enumerate(free):
        if th[j] <= lo + 0.05 or th[j] >= hi - 0.05:
            problems.append(f"{names[i]} at the search bound {math.exp(th[j]):.3g}")
    others = [s for s in starts if s is not best and abs(s[2] - best[2]) < 0.5]
    for s in others:
        diff = np.abs(np.log(s[1][:d]) - th)
        se = log_se[:d]
        if np.any(diff > 2 * np.where(np.isfinite(se), se, 0.1) + 0.05):
            problems.append("several optima with the same likelihood (starts ended at different values)")
            break
    return NoiseFit(model, measurement, names, values, ci_low, ci_high, log_se, float(best[2]), n_upd,
                    int(batch.z.shape[0]), fixed, [(s[0], s[1], s[2]) for s in starts], problems)


#: what the fits report when the observed information is not positive definite
FLAT_LIKELIHOOD = "flat likelihood (the Hessian of −log L is not positive definite)"


def _standard_errors(nll, th, h: float = 0.02):
    """Standard errors of the parameters th (log scale) from the observed information: the square roots of the
    diagonal of the inverse central-difference Hessian of −log L (``_hessian``, step h), or None when that Hessian
    is singular or not positive definite (a flat direction)."""
    H = _hessian(nll, th, h)
    try:
        cov = np.linalg.inv(H)
        ok = bool(np.all(np.linalg.eigvalsh(0.5 * (H + H.T)) > 0))
    except np.linalg.LinAlgError:
        ok = False
    return np.sqrt(np.diag(cov)) if ok else None


def _hessian(f, x, h):
    """Central-difference Hessian of f at x with step h (in log θ)."""
    d = len(x)
    H = np.empty((d, d))
    f0 = f(x)
    for i in range(d):
        e_i = np.zeros(d)
        e_i[i] = h
        H[i, i] = (f(x + e_i) - 2 * f0 + f(x - e_i)) / h**2
        for j in range(i + 1, d):
            e_j = np.zeros(d)
            e_j[j] = h
            H[i, j] = H[j, i] = (f(x + e_i + e_j) - f(x + e_i - e_j) - f(x - e_i + e_j) + f(x - e_i - e_j)) / (4 * h * h)
    return H
