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
maximises it: L-BFGS-B on log θ (bounded, finite-difference steps of 1e-3) from every start, then a
Nelder–Mead polish of the best end (on real data the likelihood has small kinks, e.g. from the angle-variance
cap, and gradient steps alone can stall at a start).

Starts: the caller's (``starts``, e.g. the noise ``lgekf track`` estimates from the data without ``--tune``,
``lgekf.apps.defaults.plan_noise``), then the model's defaults (``default_accel_std`` ×1, ×4, ÷4 with a
second-difference guess of the measurement std). From a start far from the data's noise (the defaults on fast
objects: 0.5 m/s² and 1 rad/s² at 136 m/s) the filter loses its tracks, log L is dominated by a few huge
innovations, and the optimiser can end anywhere. So every start and every optimiser end is evaluated and
checked (``filter_lost``): a point is *valid* when log L is finite, every filtered state is finite, and the
filter keeps every track (the median NIS of a track's updates at most the 99.9 % point of χ²_m, 13.8 for
positions; a consistent filter's median is 1.39, and one outlying measurement does not move it, a lost track
keeps it high). The fit is the best valid end, and never below the best valid start: when no valid end
reaches that start's log L, the start itself is returned (without intervals: it is not an optimum) and
``problems`` says so; with no valid point at all, the highest finite log L, said so as well.

Uncertainty: the observed information, the Hessian H of −log L in log θ at the optimum by central
differences; cov(log θ) ≈ H⁻¹, and the approximate 95 % interval of each std is exp(log θ̂ ± 1.96 se).
The fit says when the data do not identify the noise (``NoiseFit.problems``): fewer than
``MIN_UPDATES_PER_PARAMETER`` updates per parameter is refused (ValueError); a Hessian that is not positive
definite (flat likelihood), an interval wider than a factor ``WIDE_FACTOR`` either way, an optimum on a
bound, or starts ending at different optima are reported. So is an interval narrower than the data can give:
n scalar measurements hold at most 2n of information about a log std (for z ~ N(μ, σ²A + B), of any
dimension n, the Fisher information of log σ is 2 tr((σ²A Σ⁻¹)²) ≤ 2n), so se(log σ̂) ≥ 1/√(2n); a standard
error below 1/(``NARROW_FACTOR``·√(2n)) is curvature of a numerically rough likelihood (a filter near losing
tracks), not precision, and that parameter gets no interval. The report prints "not identified" for every
parameter without an interval.

Measured (tests/estimators/test_tuning.py): with SE(2)×SE(2) truth (σ_v, σ_ω, r) = (0.5, 0.2, 0.2) the 95 % intervals
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

from ...core.covariance import pack
from ...core.registry import get_model
from .tracks import TrackBatch, batch_tracks, two_point_prior

__all__ = ["NoiseFit", "StartRecord", "learn_noise", "log_likelihood", "filter_lost", "MIN_UPDATES_PER_PARAMETER"]

MIN_UPDATES_PER_PARAMETER = 10
WIDE_FACTOR = 10.0  # a 95 % interval beyond ×/÷ this counts as not identified
NARROW_FACTOR = 4.0  # a log std's standard error below 1/(this·√(2n)), n scalar measurements, counts as not identified
LOST_QUANTILE = 0.999  # a track whose median NIS is above this quantile of χ²_m is lost by its filter
DEFAULT_FACTORS = (1.0, 4.0, 0.25, 16.0, 1 / 16)  # the default starts: default_accel_std times these
BOUNDS = (1e-4, 1e3)  # every std is searched in this range
PENALTY = 1e15  # −log L of a diverged filter (NaN)


@dataclass
class StartRecord:
    """One start of a noise fit and the end of the optimiser's run from it (``NoiseFit.starts``).

    ``start``/``end``: all stds (fixed ones included); ``*_loglik``: log L there; ``*_lost``: why the filter is not
    valid there (``filter_lost``), None when it is. ``end`` is None for a start the optimiser did not run from (EM
    runs from the best start only)."""

    label: str
    start: np.ndarray
    start_loglik: float
    start_lost: str | None
    end: np.ndarray | None = None
    end_loglik: float = math.nan
    end_lost: str | None = None

    def describe(self) -> str:
        """One phrase: the label, log L at the start (why it is not valid), → log L at the end (why)."""
        def point(ll, lost):
            return f"{ll:.6g}" + (f" ({lost})" if lost else "")
        text = f"{self.label} {point(self.start_loglik, self.start_lost)}"
        return text + (f" → {point(self.end_loglik, self.end_lost)}" if self.end is not None else "")


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
        Approximate 95 % intervals; NaN where the parameter is not identified (no positive definite Hessian, an
        interval narrower than the data can give, or values kept at a start, which is not an optimum); equal to
        the value for a fixed one.
    log_se : ndarray
        Standard errors of the log stds from the Hessian (NaN: not available or fixed).
    loglik : float
        The innovation log-likelihood at ``values`` (the maximum found).
    n_updates, n_tracks : int
        Measurements that updated a filter, and tracks used.
    fixed : tuple of bool
        Which parameters were held fixed.
    starts : list of StartRecord
        Every start: its log-likelihood and that of the optimiser's end, and why either is not valid.
    problems : list of str
        Why the noise may not be identified, or why the values are a start (empty when identified).
    method : str
        "lbfgs" (the likelihood optimiser) or "em" (``lgekf.estimators.noise.em``).
    kept : str
        Where ``values`` come from: "the optimum from the <label> start" (the optimiser's end, maybe polished),
        or "start <label>" / "best point" when no valid optimiser end reached the best start (see ``problems``).
    hessian : bool
        Whether the intervals were computed (``learn_noise(hessian=False)``: no interval, not a problem).
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
    kept: str = "optimum"
    hessian: bool = True

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
        """A few lines for a human: every value with its interval ("not identified" without one), the
        log-likelihood, every start's log-likelihood and its optimiser end's, and the problems."""
        parts = []
        for nm, v, lo, hi, fx in zip(self.names, self.values, self.ci_low, self.ci_high, self.fixed):
            if fx:
                parts.append(f"{nm} = {v:.4g} (fixed)")
            elif np.isfinite(lo) and np.isfinite(hi):
                parts.append(f"{nm} = {v:.4g} [95 %: {lo:.3g}, {hi:.3g}]")
            else:
                parts.append(f"{nm} = {v:.4g} [{'not identified' if self.hessian else 'no interval computed'}]")
        head = (f"learned noise for {self.model}{' by EM' if self.method == 'em' else ''} ({self.measurement}, {self.n_tracks} tracks, {self.n_updates} updates, "
                f"log-likelihood {self.loglik:.6g}): " + ", ".join(parts))
        if self.starts:
            head += ("\n  starts (log-likelihood at the start → at the optimiser's end): "
                     + "; ".join(s.describe() for s in self.starts) + f"; kept: {self.kept}")
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
        The tracks (``lgekf.estimators.noise.tracks.batch_tracks``).
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
    """The checked inputs of a noise fit (``learn_noise``, ``lgekf.estimators.noise.em.learn_noise_em``): the tracks'
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


class _Likelihood:
    """The innovation log-likelihood of a batch of tracks as a function of all stds (process then measurement),
    every track started from its two-point prior; θ are the logs of the stds not held fixed (``free``)."""

    def __init__(self, spec, measurement: str, batch: TrackBatch, fixed_r, omega_std: float, heading_cap: float):
        meas = spec.measurement(measurement)
        self.spec, self.measurement, self.batch, self.m = spec, measurement, batch, meas.dim
        self.nq, self.nr = len(spec.noise_names), len(meas.noise_names)
        self.angles = bool(meas.angles)
        self.fixed_r = fixed_r
        self.free = np.array([True] * self.nq + [fixed_r is None] * self.nr)
        self.x0, self.prior = two_point_prior(spec, batch, _angle_index(meas), omega_std, heading_cap)

    def split(self, values) -> tuple[np.ndarray, np.ndarray]:
        v = np.asarray(values, dtype=float)
        return v[:self.nq], v[self.nq:]

    def p0(self, r) -> np.ndarray:
        """The packed two-point priors for measurement stds r."""
        return pack(self.prior(r[0], r[-1] if self.angles else None))

    def loglik(self, values) -> float:
        q, r = self.split(values)
        return float(np.sum(_loglik_tracks(self.spec, self.measurement, self.batch, q, r, self.x0, self.p0(r))[0]))

    def values(self, th) -> np.ndarray:
        v = np.empty(self.nq + self.nr)
        v[self.free] = np.exp(th)
        if self.fixed_r is not None:
            v[self.nq:] = self.fixed_r
        return v

    def theta(self, values) -> np.ndarray:
        return np.log(np.asarray(values, dtype=float)[self.free])

    def nll(self, th) -> float:
        """−log L at θ (``PENALTY`` where it is not finite), the optimisers' objective."""
        tot = self.loglik(self.values(th))
        return -tot if math.isfinite(tot) else PENALTY

    def assess(self, values) -> tuple[float, str | None]:
        """(log L, why the filter is not a valid fit there or None): ``filter_lost`` unless log L is not finite."""
        ll = self.loglik(values)
        if not math.isfinite(ll):
            return ll, "non-finite log-likelihood"
        q, r = self.split(values)
        return ll, filter_lost(self.spec, self.measurement, self.batch, self.x0, self.p0(r), q, r)


def filter_lost(spec, measurement: str, batch: TrackBatch, x0: np.ndarray, p0: np.ndarray, q, r) -> str | None:
    """Why the filter of ``spec`` with process-noise stds q and measurement stds r is not a valid fit of the tracks
    of ``batch`` (started from physical states x0 (B, n) and packed covariances p0), or None when it is.

    Not valid: a non-finite state or NIS within a track, or a lost track, whose median NIS over its updates is
    above the ``LOST_QUANTILE`` (99.9 %) point of χ²_m (m the measurement dimension; a consistent filter's median
    is the χ²_m median, 1.39 for positions; an outlying measurement does not move it, a lost filter keeps it high).
    One pass of the generated ``run_batch_<measurement>`` (the same filter as the likelihood's), without covariances.
    """
    from scipy.stats import chi2

    B, K, m = batch.z.shape
    out_x = np.empty((B, K, spec.n))
    nis = np.empty((B, K))
    spec.kernel("run_batch", measurement)(batch.z, batch.dts, x0, p0, np.asarray(q, dtype=float), np.asarray(r, dtype=float),
                                          out_x, np.empty((B, 0, spec.n_packed)), nis)
    inside = np.arange(K)[None, :] < batch.lengths[:, None]
    updated = inside & ~np.any(np.isnan(batch.z), axis=2)
    if not (np.all(np.isfinite(out_x[inside])) and np.all(np.isfinite(nis[updated]))):
        return "non-finite filter states"
    limit = float(chi2.ppf(LOST_QUANTILE, m))
    has = updated.any(axis=1)
    median = np.nanmedian(np.where(updated[has], nis[has], np.nan), axis=1)
    lost = int(np.sum(median > limit))
    return f"the filter loses {lost} of {B} tracks" if lost else None


def _start_points(spec, meas, batch: TrackBatch, fixed_r, starts, n_default: int) -> list:
    """[(label, stds)]: the caller's ``starts`` ({label: (accel_std, meas_std)}; a measurement std given as one
    number serves every entry; a fixed ``fixed_r`` replaces it), then ``n_default`` of the model's defaults
    (``default_accel_std`` × ``DEFAULT_FACTORS``, with the second-difference guess of the measurement std and
    0.1 rad for an angle; at least one when no start is given). ValueError for a start that is not positive stds."""
    nq, nr = len(spec.noise_names), len(meas.noise_names)
    points = []
    for label, (q, r) in dict(starts or {}).items():
        q = np.asarray(q, dtype=float).reshape(-1)
        r = np.asarray(r if fixed_r is None else fixed_r, dtype=float).reshape(-1)
        if (q.shape != (nq,) or r.size not in (1, nr) or not (np.all(np.isfinite(q)) and np.all(np.isfinite(r)))
                or np.any(q < 0) or np.any(r <= 0)):
            raise ValueError(f"start {label!r} of {spec.name}: expected {nq} non-negative process-noise stds "
                             f"({', '.join(spec.noise_names)}) and a positive measurement std, got {q.tolist()} and {r.tolist()}")
        points.append((label, np.concatenate([q, np.broadcast_to(r, (nr,))])))
    q0 = np.asarray(spec.default_accel_std, dtype=float)
    if fixed_r is not None:
        r0 = fixed_r
    else:
        r0 = np.full(nr, _meas_guess(batch, meas.dim))
        r0[list(meas.angles)] = 0.1
    for f in DEFAULT_FACTORS[:max(n_default, 0 if points else 1)]:
        label = "default" + ("" if f == 1 else f" ×{f:g}" if f > 1 else f" ÷{1 / f:g}")
        points.append((label, np.concatenate([q0 * f, r0])))
    return points


def _fallback(records: list, best_ll: float):
    """None when the best valid optimiser end (log L ``best_ll``, −inf if there is none) is at least the best
    valid start's log L; else (stds, log L, kept, problem) of that start, or with no valid start and no valid
    end, of the point of highest finite log L (starts and ends)."""
    valid = [r for r in records if r.start_lost is None]
    floor = max(valid, key=lambda r: r.start_loglik, default=None)
    if floor is not None:
        if best_ll >= floor.start_loglik:
            return None
        return (floor.start, floor.start_loglik, f"start {floor.label}",
                f"no valid optimiser end reached the log-likelihood of the {floor.label} start ({floor.start_loglik:.6g}): "
                f"the noise is kept at that start, without intervals (it is not an optimum)")
    if best_ll > -math.inf:
        return None
    points = [(r.start, r.start_loglik, r.start_lost) for r in records]
    points += [(r.end, r.end_loglik, r.end_lost) for r in records if r.end is not None]
    finite = [pt for pt in points if math.isfinite(pt[1])]
    v, ll, why = max(finite, key=lambda pt: pt[1]) if finite else points[0]
    return (v, ll, "best point", f"no start and no optimiser end is a valid fit ({why} at the best): kept the highest "
                                 f"log-likelihood, without intervals")


def _intervals(names, values, log_se, free, n_obs: int):
    """(ci_low, ci_high, problems): the 95 % intervals exp(log θ̂ ± 1.96 se) of the free stds, NaN where there is no
    standard error or where it is below the information bound 1/(``NARROW_FACTOR``·√(2·n_obs)) (module docstring;
    n_obs scalar measurements), and the problems: such a too narrow interval, or one wider than ×/÷``WIDE_FACTOR``."""
    ci_low = np.asarray(values, dtype=float).copy()
    ci_high = ci_low.copy()
    se_min = 1.0 / (NARROW_FACTOR * math.sqrt(2.0 * max(n_obs, 1)))
    problems = []
    for i in np.flatnonzero(free):
        se = log_se[i]
        if not np.isfinite(se) or se < se_min:
            ci_low[i] = ci_high[i] = np.nan
            if np.isfinite(se):
                problems.append(f"{names[i]}: its 95 % interval ×/÷(1 + {math.expm1(1.96 * se):.2g}) is narrower than "
                                f"{n_obs} measured values can give (×/÷(1 + {math.expm1(1.96 * se_min * NARROW_FACTOR):.2g}) "
                                f"at best): the curvature of log L there is numerical, not information")
            continue
        with np.errstate(over="ignore"):
            ci_low[i] = values[i] * math.exp(-1.96 * se)
            ci_high[i] = values[i] * np.exp(1.96 * se)
        if 1.96 * se > math.log(WIDE_FACTOR):
            problems.append(f"{names[i]}: the 95 % interval spans more than ×/÷{WIDE_FACTOR:g}")
    return ci_low, ci_high, problems


def _optimum_uncertainty(lik: _Likelihood, names, values, hessian: bool, n_obs: int):
    """(log_se, ci_low, ci_high, problems) at an optimum: the standard errors from the Hessian (``hessian``), the
    intervals (``_intervals``; NaN without the Hessian) and the free parameters on a search bound."""
    log_se = np.full(len(values), np.nan)
    problems = []
    if hessian:
        se = _standard_errors(lik.nll, lik.theta(values))
        if se is not None:
            log_se[lik.free] = se
        else:
            problems.append(FLAT_LIKELIHOOD)
    ci_low, ci_high, more = _intervals(names, values, log_se, lik.free, n_obs)
    problems += more
    for i in np.flatnonzero(lik.free):
        if not BOUNDS[0] * math.exp(0.05) < values[i] < BOUNDS[1] * math.exp(-0.05):
            problems.append(f"{names[i]} at the search bound {values[i]:.3g}")
    return log_se, ci_low, ci_high, problems


def learn_noise(model: str, tracks, *, dt: float | None = None, measurement: str = "position",
                meas_std: float | ArrayLike | None = None, n_starts: int = 3, omega_std: float = 0.5,
                heading_cap: float = math.pi, hessian: bool = True, baseline: float = 1.0,
                starts: dict | None = None) -> NoiseFit:
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
        Number of the model's default starts (``default_accel_std`` ×1, ×4, ÷4, ...), after ``starts``; 0 with
        ``starts`` given runs from those only.
    omega_std, heading_cap : float
        Of the two-point prior (``lgekf.estimators.noise.tracks.two_point_prior``).
    hessian : bool
        Compute the intervals (2d² extra likelihood evaluations).
    baseline : float
        Each track starts from its first measurement and the first one at least ``baseline`` s later (the
        two-point prior, ``lgekf.estimators.noise.tracks.batch_tracks``); the measurements in between are not used.
        Two points 0.1 s apart leave the heading almost unknown (velocity error √2·r/Δ), and the likelihood
        of the steps that follow then asks for a much larger process noise than the motion has.
    starts : dict, optional
        Further starting points {label: (accel_std, meas_std)}, tried first, e.g. {"data": (q, r)} with the
        noise estimated from the data (``lgekf.apps.defaults.NoisePlan.tune_starts``, ``data_starts``). The
        returned log-likelihood is never below the best valid start's (module docstring).

    Returns
    -------
    NoiseFit
        Learned stds, 95 % intervals, log-likelihood, every start's record and ``problems`` (empty when identified).

    Raises
    ------
    ValueError
        Bad input (a start included), or fewer than ``MIN_UPDATES_PER_PARAMETER`` updates per learned parameter.

    See Also
    --------
    lgekf.estimators.noise.em.learn_noise_em : the same maximum likelihood by EM, for the linear Gaussian models (CV).

    Examples
    --------
    >>> fit = learn_noise("cv", [(t, z) for t, z in my_tracks])          # doctest: +SKIP
    >>> fit.accel_std, fit.meas_std, fit.report()                         # doctest: +SKIP
    """
    from scipy.optimize import minimize

    spec = get_model(model)
    meas = spec.measurement(measurement)
    batch, nq, nr, names, fixed_r, d, n_upd = _noise_problem(model, spec, meas, tracks, dt, meas_std, baseline)
    points = _start_points(spec, meas, batch, fixed_r, starts, n_starts)
    lik = _Likelihood(spec, measurement, batch, fixed_r, omega_std, heading_cap)
    lo, hi = math.log(BOUNDS[0]), math.log(BOUNDS[1])
    records = []
    for label, v0 in points:
        th0 = np.clip(lik.theta(v0), lo + 0.1, hi - 0.1)
        rec = StartRecord(label, lik.values(th0), *lik.assess(lik.values(th0)))
        # finite-difference gradient steps of 1e-3 in log θ: the likelihood of a real run has small kinks
        # (angle-variance cap, heading of slow objects) that make steps near machine precision useless
        res = minimize(lik.nll, th0, method="L-BFGS-B", bounds=[(lo, hi)] * d, options={"maxiter": 200, "eps": 1e-3})
        rec.end = lik.values(res.x)
        rec.end_loglik, rec.end_lost = lik.assess(rec.end)
        records.append(rec)
    best = max((r for r in records if r.end_lost is None), key=lambda r: r.end_loglik, default=None)
    values, ll = (best.end, best.end_loglik) if best is not None else (None, -math.inf)
    if best is not None:
        # polish the best with Nelder–Mead (derivative-free, indifferent to the kinks), inside the bounds
        nm = minimize(lambda x: lik.nll(np.clip(x, lo, hi)), lik.theta(values), method="Nelder-Mead",
                      options={"xatol": 1e-3, "fatol": 1e-3, "maxfev": 400 * d})
        if -nm.fun > ll:
            v = lik.values(np.clip(nm.x, lo, hi))
            ll_nm, why = lik.assess(v)
            if why is None and ll_nm > ll:
                values, ll = v, ll_nm
    fixed = tuple(not f for f in lik.free)
    n_obs = n_upd * meas.dim
    fallback = _fallback(records, ll)
    if fallback is not None:
        values, ll, kept, why = fallback
        nan = np.where(lik.free, np.nan, values)
        return NoiseFit(model, measurement, names, values, nan, nan.copy(), np.full(nq + nr, np.nan), float(ll), n_upd,
                        int(batch.z.shape[0]), fixed, records, [why], kept=kept)
    log_se, ci_low, ci_high, problems = _optimum_uncertainty(lik, names, values, hessian, n_obs)
    th = lik.theta(values)
    se = log_se[lik.free]
    for r in records:
        if r is not best and r.end_lost is None and abs(r.end_loglik - ll) < 0.5:
            if np.any(np.abs(lik.theta(r.end) - th) > 2 * np.where(np.isfinite(se), se, 0.1) + 0.05):
                problems.append("several optima with the same likelihood (starts ended at different values)")
                break
    return NoiseFit(model, measurement, names, values, ci_low, ci_high, log_se, float(ll), n_upd,
                    int(batch.z.shape[0]), fixed, records, problems, kept=f"the optimum from the {best.label} start",
                    hessian=hessian)


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
