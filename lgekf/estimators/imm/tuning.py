"""An IMM fitted to the data: its modes' noise levels and its switching probability by maximum likelihood.

The IMM's own likelihood is the product over the steps of its predictive density of each measurement, the
mixture of the mode-matched innovation densities (Blom and Bar-Shalom 1988):

    log L(θ) = Σ_tracks Σ_k log Σ_j c̄_j,k N(ν_j,k; 0, S_j,k),

with c̄_j,k the predicted mode probabilities and ν_j,k, S_j,k = ℋ_j P_j,k|k-1 ℋ_jᵀ + R mode j's innovation and
its covariance (eq:K), which :func:`lgekf.estimators.imm.kernels.imm_update` already returns each step.
The parameters θ are the log of one factor a_j per mode (mode j runs with process-noise stds a_j · q_j, q_j
its given ``accel_std``) and the logit of the switching probability p (the transition matrix
``transition_matrix(M, p)``); the measurement std is given (learned beforehand with the single models,
:func:`lgekf.estimators.noise.tuning.learn_noise`, or known).

Why: fitting each model alone (``learn_noise``) and giving the IMM's calm / manoeuvring modes fixed multiples of
the learned noise (0.2×, 4×) tunes the modes for a motion they do not each see. The joint fit lets the data
decide how calm the calm mode is, how hard the manoeuvres are and how often they start.

Each track starts like ``lgekf track --model imm``: the two-point estimate of its first two measurements
(``lgekf.core.initiation.two_point``), uniform mode probabilities, the IMM from the third measurement on. The
likelihood is conditioned on the first ``baseline`` seconds (their steps run but are not counted): the
two-point start's velocity is poor (error √2·r/Δ), and counting the steps that repair it would ask for more
process noise than the motion has (the reason for ``learn_noise``'s ``baseline``).

Optimiser and uncertainty as in :func:`lgekf.estimators.noise.tuning.learn_noise`: L-BFGS-B in θ (bounded, finite
differences of 1e-3, two starts), a Nelder–Mead polish, the observed information (central-difference Hessian of
−log L) for approximate 95 % intervals, and the same warnings when the data do not identify a parameter.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ...core.initiation import DEFAULT_OMEGA_STD, two_point
from ...core.registry import get_measurement, imm_kernel
from ..threads import run_on_threads
from .estimator import DEFAULT_SWITCH, Mode, _common_inputs, _modes, _Setup, transition_matrix
from .kernels import MEASUREMENT_NAMES
from ..noise.tracks import batch_tracks
from ..noise.tuning import FLAT_LIKELIHOOD, MIN_UPDATES_PER_PARAMETER, PENALTY, WIDE_FACTOR, _standard_errors

__all__ = ["ImmFit", "learn_imm", "imm_log_likelihood"]

#: search range of each mode's noise factor a_j and of the switching probability
FACTOR_BOUNDS = (1e-2, 1e2)
SWITCH_BOUNDS = (1e-4, 0.5)


@dataclass
class ImmFit:
    """Result of :func:`learn_imm`.

    Attributes
    ----------
    modes : list of Mode
        The fitted modes (each mode's ``accel_std`` times its factor; labels kept).
    switch : float
        The fitted probability of leaving a mode per step.
    factors : ndarray, (M,)
        The factors a_j applied to the given modes' noise.
    ci_low, ci_high : ndarray, (M + 1,)
        Approximate 95 % intervals of the factors and of the switching probability (NaN: none).
    loglik, loglik_start : float
        The IMM log-likelihood at the optimum and at the given modes and switch.
    n_updates, n_tracks : int
        Steps counted in the likelihood, and tracks used.
    problems : list of str
        Why a parameter may not be identified (empty when all are).
    n_params : int
        Number of fitted parameters (for comparing mode sets by AIC = 2 n_params − 2 loglik).
    n_evals : int
        Likelihood evaluations the fit took (each one IMM run over all the tracks).
    """

    modes: list
    switch: float
    factors: np.ndarray
    ci_low: np.ndarray
    ci_high: np.ndarray
    loglik: float
    loglik_start: float
    n_updates: int
    n_tracks: int
    problems: list = field(default_factory=list)
    n_params: int = 0
    n_evals: int = 0

    @property
    def names(self) -> tuple:
        """The parameters, as in ``values``: ``factor_<mode>`` per mode, then ``switch``."""
        return tuple(f"factor_{m.name}" for m in self.modes) + ("switch",)

    @property
    def values(self) -> np.ndarray:
        """The fitted factors then the switching probability (as ``ci_low``, ``ci_high``)."""
        return np.array([*self.factors, self.switch])

    @property
    def identified(self) -> bool:
        """True when no parameter was reported as not identified."""
        return not self.problems

    @property
    def aic(self) -> float:
        """Akaike's information criterion 2 n_params − 2 loglik (lower is better)."""
        return 2.0 * self.n_params - 2.0 * self.loglik

    def report(self) -> str:
        """A short human-readable summary (what ``lgekf track --model imm --tune`` prints)."""
        names = [m.name for m in self.modes] + (["switch"] if len(self.modes) > 1 else [])
        vals = list(self.factors) + [self.switch]
        parts = []
        for i, (nm, v, lo, hi) in enumerate(zip(names, vals, self.ci_low, self.ci_high)):
            what = f"×{v:.3g}" if i < len(self.modes) else f"{v:.3g}"
            if lo == hi == v:
                interval = " (given)"
            elif np.isfinite(lo) and np.isfinite(hi) and hi < 1e6 * lo:  # (no division: lo may be ~0)
                interval = f" [{lo:.3g}, {hi:.3g}]"
            else:
                interval = " [no interval]"
            parts.append(f"{nm} {what}{interval}")
        head = (f"IMM fitted ({self.n_tracks} tracks, {self.n_updates} steps, {self.n_evals} runs): " + ", ".join(parts)
                + f"; log-likelihood {self.loglik:.6g} (given modes {self.loglik_start:.6g})")
        if self.problems:
            head += "\n  not identified: " + "; ".join(self.problems)
        return head


def imm_loglik_batch(models, S0, P0, mu0, PI, Q, r, z, dts, lengths, skip, same_group, meas, ll, cnt) -> None:
    """Σ_k log Σ_j c̄_j N_j of each track b over its steps k in [skip[b], lengths[b]) (missed steps not counted).

    S0 (B, M, L), P0 (B, M, NP): each track's initial mode states and packed covariances; z (B, K, m), dts (B, K)
    padded beyond lengths[b]; ``meas`` the measurement's index (``MEASUREMENT_NAMES``). Writes ll (B,) (−inf once
    every mode's likelihood vanished) and cnt (B,) the steps counted. Runs the generated
    ``imm_loglik_batch_<measurement>`` (only that measurement's kernels compile; serial, without the GIL) on parts
    of the batch in threads (``lgekf.estimators.threads``); each track's sum is the same whatever the split.
    """
    kernel = imm_kernel("imm_loglik_batch", MEASUREMENT_NAMES[meas])
    run_on_threads(kernel, (models, S0, P0, mu0, PI, Q, r, z, dts, lengths, skip, same_group, ll, cnt),
                   (1, 2, 7, 8, 9, 10, 12, 13), z.shape[0])


class _Tracks:
    """Tracks padded for ``imm_loglik_batch``, with each one's two-point start in the common coordinates."""

    def __init__(self, tracks, m: int, meas_std: float, omega_std: float, baseline: float):
        tracks = list(tracks)
        skip = []
        for i, tr in enumerate(tracks):
            t, z = (np.asarray(a, dtype=float) for a in tr)
            if z.ndim == 2 and z.shape[0] >= 2 and np.any(np.isnan(z[:2])):
                raise ValueError(f"tracks[{i}]: the first two measurements start the IMM and must not be NaN")
            if t.ndim == 1 and len(t) >= 3:  # the tracks batch_tracks keeps, in its order: steps within ``baseline`` s of t0 not counted
                skip.append(int(np.searchsorted(t[2:] - t[0], baseline, side="left")))
        # padded like learn_noise's tracks, but started from the first two measurements (baseline 0)
        batch = batch_tracks(tracks, m, baseline=0.0)
        self.z, self.dts, self.lengths = batch.z, batch.dts, batch.lengths
        self.skip = np.array(skip, dtype=np.int64)
        B, K = self.z.shape[:2]
        # the positions (m: a position measurement of the plane or 3-D space) -> the common coordinates of their space
        self.c0, var0 = two_point(batch.t01.reshape(-1), batch.z01[:, :, :m].reshape(-1, m), np.arange(1, 2 * B, 2),
                                  meas_std, omega_std)
        nc = var0.shape[1]
        self.P0 = np.zeros((B, nc, nc))
        self.P0[:, range(nc), range(nc)] = var0
        counted = np.arange(K)[None, :]
        ok = (counted >= self.skip[:, None]) & (counted < self.lengths[:, None]) & ~np.any(np.isnan(self.z), axis=2)
        self.n_updates = int(ok.sum())
        self.B = B


class _Likelihood:
    """log L of the tracks as a function of the modes' noise factors and the switching probability. The modes'
    initial states and covariances depend on their models only, so they are converted once, not per evaluation."""

    def __init__(self, modes, meas_std, tr: _Tracks, measurement: str):
        self.setup = _Setup(modes, None, meas_std, measurement, None)
        self.S0, self.Pp0 = self.setup.initial(*_common_inputs(tr.c0, tr.P0, self.setup.space))
        self.tr = tr

    def __call__(self, factors, switch: float) -> tuple[float, int]:
        s, tr = self.setup, self.tr
        Q = np.ascontiguousarray(s.Q * np.asarray(factors, dtype=float)[:, None])
        PI = transition_matrix(s.M, switch) if s.M > 1 else s.PI
        ll = np.empty(tr.B)
        cnt = np.empty(tr.B, dtype=np.int64)
        imm_loglik_batch(s.models, self.S0, self.Pp0, s.mu0, PI, Q, s.r, tr.z, tr.dts, tr.lengths, tr.skip, s.same_group,
                         s.meas, ll, cnt)
        return float(np.sum(ll)), int(np.sum(cnt))


def _scaled(modes, factors) -> list:
    return [Mode(m.model, tuple(float(f) * float(v) for v in m.accel_std), m.label) for m, f in zip(modes, factors)]


def imm_log_likelihood(modes, tracks, *, meas_std: float, switch: float = DEFAULT_SWITCH, measurement: str = "position",
                       omega_std: float = DEFAULT_OMEGA_STD, baseline: float = 1.0) -> float:
    """The IMM's log-likelihood Σ log Σ_j c̄_j N_j of the tracks (module docstring).

    Parameters
    ----------
    modes : str or sequence
        As for :class:`lgekf.estimators.imm.IMM` (``parse_modes`` text or ``Mode`` objects).
    tracks : sequence of (t (K,), z (K, m))
        The measured tracks; the first two measurements of each start the IMM.
    meas_std : float
        Measurement std.
    switch : float
        Probability of leaving a mode per step.
    measurement : {"position"}
        Only position measurements (the two-point start of ``lgekf track --model imm``).
    omega_std : float
        Turn-rate std of the two-point start.
    baseline : float
        The steps within this many seconds of a track's first measurement are not counted.

    Returns
    -------
    float
    """
    modes = _modes(modes)
    m = _position_only(measurement)
    tr = _Tracks(tracks, m, meas_std, omega_std, baseline)
    return _Likelihood(modes, meas_std, tr, measurement)(np.ones(len(modes)), switch)[0]


def learn_imm(modes, tracks, *, meas_std: float, switch: float = DEFAULT_SWITCH, measurement: str = "position",
              omega_std: float = DEFAULT_OMEGA_STD, baseline: float = 1.0, fit_switch: bool = True,
              fixed=None, hessian: bool = True) -> ImmFit:
    """Fit the IMM's mode noise factors (and switching probability) by maximising its likelihood.

    Parameters
    ----------
    modes : str or sequence
        The modes to start from (``parse_modes`` text or ``Mode`` objects): mode j is fitted as a_j × its
        ``accel_std``. Typically the single models' learned noise times the named levels
        (``lgekf.apps.track_imm.ImmTrackOptions.with_learned_noise``).
    tracks : sequence of (t (K,), z (K, m))
        The measured tracks (NaN rows after the first two: missed detections).
    meas_std : float
        Measurement std (held fixed).
    switch : float
        The switching probability to start from (held fixed without ``fit_switch``).
    measurement : {"position"}
        As for :func:`imm_log_likelihood`.
    omega_std, baseline : float
        As for :func:`imm_log_likelihood`.
    fit_switch : bool
        Also fit the switching probability (needs two modes or more).
    fixed : sequence of bool, optional
        Modes whose noise is held as given (factor 1).
    hessian : bool
        Compute the 95 % intervals (2d² extra likelihood evaluations).

    Returns
    -------
    ImmFit

    Raises
    ------
    ValueError
        Bad input, or fewer than ``MIN_UPDATES_PER_PARAMETER`` counted steps per parameter.
    """
    from scipy.optimize import minimize

    modes = _modes(modes)
    M = len(modes)
    if not (math.isfinite(meas_std) and meas_std > 0):
        raise ValueError(f"meas_std: must be positive, got {meas_std}")
    transition_matrix(M, switch)  # checks the switching probability
    fit_switch = fit_switch and M > 1
    m = _position_only(measurement)
    fixed = np.zeros(M, dtype=bool) if fixed is None else np.asarray(fixed, dtype=bool).reshape(-1)
    if fixed.shape != (M,):
        raise ValueError(f"fixed: expected {M} flags, one per mode, got {fixed.shape[0]}")
    free = np.flatnonzero(~fixed)
    F = free.size
    tr = _Tracks(tracks, m, meas_std, omega_std, baseline)
    d = F + int(fit_switch)
    if d == 0:
        raise ValueError("nothing to fit: every mode's noise is fixed and the switching probability too")
    need = MIN_UPDATES_PER_PARAMETER * d
    if tr.n_updates < need:
        raise ValueError(f"too few measurements to fit the IMM: {tr.n_updates} counted steps in {tr.B} tracks (each "
                         f"track's first {baseline:g} s start the IMM) for {d} parameters; need at least {need}")
    flo, fhi = (math.log(v) for v in FACTOR_BOUNDS)
    slo, shi = (_logit(v) for v in SWITCH_BOUNDS)
    bounds = [(flo, fhi)] * F + ([(slo, shi)] if fit_switch else [])

    def params(th):
        th = np.asarray(th, dtype=float)
        a = np.ones(M)
        a[free] = np.exp(th[:F])
        return a, (_expit(th[F]) if fit_switch else switch)

    loglik = _Likelihood(modes, meas_std, tr, measurement)
    evals = [0]
    diverged = [False]

    def nll(th):
        evals[0] += 1
        a, p = params(th)
        ll, _ = loglik(a, p)
        if not math.isfinite(ll):
            diverged[0] = True
            return PENALTY
        return -ll

    th_given = np.concatenate([np.zeros(F), [_logit(min(max(switch, SWITCH_BOUNDS[0]), SWITCH_BOUNDS[1]))] if fit_switch else []])
    ll_start, _ = loglik(np.ones(M), switch)  # at the given values (not clipped to the bounds)
    starts = [th_given]
    if fit_switch:
        alt = th_given.copy()
        alt[F] = _logit(0.01) if switch > 0.02 else _logit(0.1)
        starts.append(alt)
    results = []
    for th0 in starts:
        results.append(minimize(nll, np.clip(th0, [b[0] + 1e-6 for b in bounds], [b[1] - 1e-6 for b in bounds]),
                                method="L-BFGS-B", bounds=bounds, options={"maxiter": 100, "eps": 1e-3}))
    best = min(results, key=lambda res: res.fun)
    lo_b = np.array([b[0] for b in bounds])
    hi_b = np.array([b[1] for b in bounds])
    nm = minimize(lambda x: nll(np.clip(x, lo_b, hi_b)), best.x, method="Nelder-Mead",
                  options={"xatol": 1e-3, "fatol": 1e-2, "maxfev": 40 * d})
    th = np.clip(nm.x, lo_b, hi_b) if nm.fun < best.fun else best.x
    fun = min(nm.fun, best.fun)
    a, p = params(th)
    problems = []
    ci_low = np.full(M + 1, np.nan)
    ci_high = np.full(M + 1, np.nan)
    se = np.full(d, np.nan)
    if hessian:
        diverged[0] = False
        se_fit = _standard_errors(nll, th)
        ok = se_fit is not None and not diverged[0]
        if ok:
            se = se_fit
            with np.errstate(over="ignore"):  # a flat direction: the interval reaches 0 or ∞
                ci_low[free], ci_high[free] = a[free] * np.exp(-1.96 * se[:F]), a[free] * np.exp(1.96 * se[:F])
            for i, j in enumerate(free):
                if 1.96 * se[i] > math.log(WIDE_FACTOR):
                    problems.append(f"{modes[j].name}: the 95 % interval of its factor spans more than ×/÷{WIDE_FACTOR:g}")
            if fit_switch:
                ci_low[M], ci_high[M] = _expit(th[F] - 1.96 * se[F]), _expit(th[F] + 1.96 * se[F])
                if 1.96 * se[F] > math.log(WIDE_FACTOR):
                    problems.append(f"switch: the 95 % interval of its odds spans more than ×/÷{WIDE_FACTOR:g}")
        elif diverged[0]:
            problems.append("the IMM diverged next to the optimum (no interval)")
        else:
            problems.append(FLAT_LIKELIHOOD)
    ci_low[:M][fixed] = ci_high[:M][fixed] = 1.0
    if not fit_switch:
        ci_low[M] = ci_high[M] = p
    for res in results:
        if res is not best and abs(res.fun - best.fun) < 0.5 and np.any(
                np.abs(res.x - best.x) > 2 * np.where(np.isfinite(se), se, 0.1) + 0.05):
            problems.append("several optima with the same likelihood (starts ended at different values)")
            break
    for i in range(d):
        if th[i] <= lo_b[i] + 0.05 or th[i] >= hi_b[i] - 0.05:
            what = modes[free[i]].name + " factor" if i < F else "switch"
            val = math.exp(th[i]) if i < F else _expit(th[i])
            problems.append(f"{what} at the search bound {val:.3g}")
    return ImmFit(_scaled(modes, a), float(p), a, ci_low, ci_high, -float(fun), ll_start, tr.n_updates, tr.B, problems, d, evals[0])


def _position_only(measurement: str) -> int:
    """The measurement dimension; the fit starts every track from two positions, so it takes a measurement without an
    angle (as its definition says: a position; a pose's heading would go unused)."""
    meas = get_measurement(measurement)
    if meas.angles:
        raise ValueError(f"measurement: the IMM's likelihood fit supports position measurements only (no angle), got {measurement!r}")
    return meas.dim


def _logit(p: float) -> float:
    return math.log(p / (1.0 - p))


def _expit(x: float) -> float:
    return 0.5 * (1.0 + math.tanh(0.5 * x))  # 1/(1 + e^-x) without overflow
