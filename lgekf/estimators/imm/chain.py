"""The IMM's Markov chain learned from data: every transition probability by maximum likelihood, the IMM started
from the chain's stationary distribution.

The IMM (Blom and Bar-Shalom 1988) assumes the mode follows a Markov chain with transition matrix
PI[i, j] = P(mode j at k | mode i at k−1). Nothing in a motion model defines PI or the initial mode probabilities
μ₀; they are design parameters (Bar-Shalom, Li and Kirubarajan, *Estimation with Applications to Tracking and
Navigation*, 2001, ch. 11: the switching probabilities from the expected sojourn times). When tracks of the
motion are available, both follow from the IMM's own likelihood, the product over the steps of its predictive
density of each measurement, as the transition probabilities of a Markov-switching model are estimated by maximum
likelihood, its filter started from the chain's ergodic probabilities (Hamilton, "A new approach to the economic
analysis of nonstationary time series and the business cycle", *Econometrica* 57, 1989):

    log L(PI) = Σ_tracks Σ_k log Σ_j c̄_j,k N(ν_j,k; 0, S_j,k),   c̄_j,k = Σ_i PI[i, j] μ_i,k−1,

with every off-diagonal PI[i, j] a free parameter (M(M − 1) of them; each row's diagonal is 1 minus the rest)
and μ₀ = π(PI), the stationary distribution of the chain (π PI = π): a track observed from an arbitrary moment
of a chain that has been running finds it in its stationary law, so μ₀ is not a further parameter. An
asymmetric PI lets the data say which mode is the rule and which the exception (a mode entered rarely and left
quickly has a small stationary probability and starts small); the symmetric ``transition_matrix(M, p)`` has the
uniform stationary law.

Contrast :func:`lgekf.estimators.imm.tuning.learn_imm`, which fits one symmetric switching probability and the
modes' noise factors for tracks started from two measurements; here the modes' noise is given (e.g. matched to
the simulated truth) and every track starts from a given initial estimate (x0, P0) with all its steps counted,
as the Monte Carlo study runs its filters (``lgekf.experiments.imm_study``).

Optimiser: L-BFGS-B in θ_ij = logit PI[i, j] (bounded to ``CHAIN_BOUNDS``; each row's off-diagonal mass at
most the upper bound), finite differences of 1e-3, two starts (every off-diagonal 0.002 and 0.05), the better
kept. The likelihood of one θ is one IMM run over all the tracks in numba
(:func:`lgekf.estimators.imm.tuning.imm_loglik_batch`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from .estimator import _batch_inputs
from .tuning import imm_loglik_batch
from ..noise.tuning import MIN_UPDATES_PER_PARAMETER, PENALTY

__all__ = ["ChainFit", "learn_chain", "stationary_distribution", "chain_log_likelihood", "CHAIN_BOUNDS"]

#: search range of each off-diagonal transition probability (the upper bound shared by a row's off-diagonals)
CHAIN_BOUNDS = (1e-5, 0.5)
#: the optimiser's starts: every off-diagonal probability at these values (split over a row's M − 1 entries)
STARTS = (0.002, 0.05)


@dataclass
class ChainFit:
    """Result of :func:`learn_chain`.

    Attributes
    ----------
    transition : ndarray, (M, M)
        The fitted transition matrix PI[i, j] = P(mode j | mode i).
    mu0 : ndarray, (M,)
        Its stationary distribution, the IMM's initial mode probabilities.
    loglik : float
        The IMM log-likelihood at the optimum.
    n_updates : int
        Steps counted in the likelihood.
    n_evals : int
        Likelihood evaluations the fit took (each one IMM run over all the tracks).
    at_bound : list of tuple
        The (i, j) of the off-diagonal probabilities that ended on a search bound (a mode the data never leave
        or always leave at once).
    converged : bool
        Whether L-BFGS-B reported convergence for the best of the starts (``STARTS``).
    message : str
        The optimiser's message for that start.
    """

    transition: np.ndarray
    mu0: np.ndarray
    loglik: float
    n_updates: int
    n_evals: int
    at_bound: list
    converged: bool = True
    message: str = ""

    def to_dict(self) -> dict:
        """JSON-ready: the transition matrix (rows), the stationary probabilities, the log-likelihood, the
        counted steps, the evaluations, the (i, j) of the probabilities on a search bound and the optimiser's
        convergence flag and message."""
        return {"transition": self.transition.tolist(), "mu0": self.mu0.tolist(), "loglik": self.loglik,
                "n_updates": self.n_updates, "n_evals": self.n_evals, "at_bound": [list(ij) for ij in self.at_bound],
                "converged": self.converged, "message": self.message}


def stationary_distribution(PI: ArrayLike) -> np.ndarray:
    """The stationary distribution π of a transition matrix (π PI = π, Σ π = 1).

    Parameters
    ----------
    PI : array_like, (M, M)
        Row-stochastic (non-negative, each row sums to 1 within 1e-9); irreducible (every mode reachable from
        every other), so π is unique.

    Returns
    -------
    ndarray, (M,)
        By Grassmann–Taksar–Heyman elimination (GTH 1985: the states eliminated from the last, every step a sum
        of non-negative numbers, no subtraction; accurate even for switching probabilities near 0).

    Raises
    ------
    ValueError
        PI not square, not finite, negative, not row-stochastic, or reducible.
    """
    P = np.array(PI, dtype=float)
    if P.ndim != 2 or P.shape[0] != P.shape[1] or P.shape[0] < 1:
        raise ValueError(f"transition: expected a square matrix, got shape {P.shape}")
    if not np.all(np.isfinite(P)) or np.any(P < 0):
        raise ValueError("transition: entries must be finite and non-negative")
    if np.any(np.abs(P.sum(axis=1) - 1.0) > 1e-9):
        raise ValueError(f"transition: each row must sum to 1, got row sums {P.sum(axis=1).tolist()}")
    M = P.shape[0]
    reach = (P > 0) | np.eye(M, dtype=bool)
    for _ in range(max(1, M.bit_length())):  # transitive closure by squaring
        reach = (reach.astype(np.int64) @ reach.astype(np.int64)) > 0
    if not np.all(reach):
        raise ValueError("transition: the chain is reducible (some mode cannot reach another), so its stationary "
                         "distribution is not unique")
    for n in range(M - 1, 0, -1):  # GTH: censor the chain on states 0..n-1
        P[:n, n] /= P[n, :n].sum()  # > 0: irreducible
        P[:n, :n] += np.outer(P[:n, n], P[n, :n])
    pi = np.zeros(M)
    pi[0] = 1.0
    for j in range(1, M):
        pi[j] = pi[:j] @ P[:j, j]
    return pi / pi.sum()


def _transition_of(theta: np.ndarray, M: int) -> np.ndarray:
    """PI from the logits of its off-diagonal entries (row-major, the diagonal skipped)."""
    PI = np.zeros((M, M))
    off = ~np.eye(M, dtype=bool)
    PI[off] = 0.5 * (1.0 + np.tanh(0.5 * np.asarray(theta, dtype=float)))  # expit without overflow
    np.fill_diagonal(PI, 1.0 - PI.sum(axis=1))
    return PI


def _logit(p: float) -> float:
    return math.log(p / (1.0 - p))


class _ChainLikelihood:
    """log L of given tracks as a function of the transition matrix (the IMM started from its stationary law);
    the modes' initial states are converted once."""

    def __init__(self, modes, z, dt, meas_std, x0, P0, measurement):
        self.setup, self.z, self.dts, self.S0, self.Pp0 = _batch_inputs(z, modes, None, dt, meas_std, x0, P0, measurement, None)
        B, K = self.z.shape[:2]
        self.lengths = np.full(B, K, dtype=np.int64)
        self.skip = np.zeros(B, dtype=np.int64)
        self.n_updates = int(np.sum(~np.any(np.isnan(self.z), axis=2)))
        self.B = B

    def __call__(self, PI: np.ndarray) -> float:
        s = self.setup
        ll = np.empty(self.B)
        cnt = np.empty(self.B, dtype=np.int64)
        imm_loglik_batch(s.models, self.S0, self.Pp0, np.ascontiguousarray(stationary_distribution(PI)),
                         np.ascontiguousarray(PI), s.Q, s.r, self.z, self.dts, self.lengths, self.skip, s.same_group,
                         s.meas, ll, cnt)
        return float(np.sum(ll))


def chain_log_likelihood(modes, z: ArrayLike, transition: ArrayLike, *, dt, meas_std, x0: ArrayLike, P0: ArrayLike,
                         measurement: str = "position") -> float:
    """The IMM's log-likelihood (module docstring) of tracks z with the transition matrix ``transition``, the IMM
    started from (x0, P0) and the chain's stationary distribution.

    Parameters
    ----------
    modes : str or sequence
        As for :class:`lgekf.estimators.imm.IMM`.
    z : array_like, (B, K, m)
        Measurements (NaN rows: missed, not counted).
    transition : array_like, (M, M)
        Row-stochastic, irreducible.
    dt : float or array_like
        As for :func:`lgekf.estimators.imm.imm_batch`.
    meas_std : float or array_like
        Measurement-noise std(s).
    x0 : array_like, (B, 6) or (6,)
        Initial estimates in the common coordinates (x, y, θ, v_x, v_y, ω).
    P0 : array_like, (6, 6) or (B, 6, 6)
        Their covariance.
    measurement : {"position", "pose"}

    Returns
    -------
    float
    """
    lik = _ChainLikelihood(modes, z, dt, meas_std, x0, P0, measurement)
    PI = np.asarray(transition, dtype=float)
    if PI.shape != (lik.setup.M, lik.setup.M):
        raise ValueError(f"transition: expected ({lik.setup.M}, {lik.setup.M}), got {PI.shape}")
    return lik(PI)


def learn_chain(modes, z: ArrayLike, *, dt, meas_std, x0: ArrayLike, P0: ArrayLike,
                measurement: str = "position") -> ChainFit:
    """Fit the IMM's transition matrix by maximum likelihood, the IMM started from its stationary distribution.

    Parameters
    ----------
    modes : str or sequence
        The modes with their process noise (held fixed), as for :class:`lgekf.estimators.imm.IMM`.
    z : array_like, (B, K, m)
        Training tracks (NaN rows: missed detections).
    dt : float or array_like
        Step length(s), as for :func:`lgekf.estimators.imm.imm_batch`.
    meas_std : float or array_like
        Measurement-noise std(s) (given).
    x0 : array_like, (B, 6) or (6,)
        Each track's initial estimate in the common coordinates (x, y, θ, v_x, v_y, ω), at the time before
        its first measurement (every measurement is counted).
    P0 : array_like, (6, 6) or (B, 6, 6)
        Its covariance.
    measurement : {"position", "pose"}

    Returns
    -------
    ChainFit

    Raises
    ------
    ValueError
        Bad input, a single mode (no chain to fit), or fewer than ``MIN_UPDATES_PER_PARAMETER`` counted steps
        per transition probability.
    """
    from scipy.optimize import minimize

    lik = _ChainLikelihood(modes, z, dt, meas_std, x0, P0, measurement)
    M = lik.setup.M
    if M < 2:
        raise ValueError("modes: a chain needs two modes or more")
    d = M * (M - 1)
    if lik.n_updates < MIN_UPDATES_PER_PARAMETER * d:
        raise ValueError(f"too few measurements to fit the transition matrix: {lik.n_updates} steps for {d} "
                         f"probabilities; need at least {MIN_UPDATES_PER_PARAMETER * d}")
    lo, hi = CHAIN_BOUNDS[0], CHAIN_BOUNDS[1] / (M - 1)
    bounds = [(_logit(lo), _logit(hi))] * d
    evals = [0]

    def nll(theta):
        evals[0] += 1
        ll = lik(_transition_of(theta, M))
        return -ll if math.isfinite(ll) else PENALTY

    best = None
    for p in STARTS:
        th0 = np.full(d, _logit(min(max(p / (M - 1), lo), hi)))
        res = minimize(nll, th0, method="L-BFGS-B", bounds=bounds, options={"maxiter": 100, "eps": 1e-3})
        if best is None or res.fun < best.fun:
            best = res
    PI = _transition_of(best.x, M)
    off = [(i, j) for i in range(M) for j in range(M) if i != j]
    at_bound = [ij for ij, t in zip(off, best.x) if t <= bounds[0][0] + 0.05 or t >= bounds[0][1] - 0.05]
    return ChainFit(PI, stationary_distribution(PI), -float(best.fun), lik.n_updates, evals[0], at_bound,
                    bool(best.success), str(best.message))
