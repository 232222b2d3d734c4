"""An IMM per track for the multi-target tracker: ``IMMBank``, a ``TrackFilterBank`` (``bank.py``) whose row i is
one track's IMM (Blom & Bar-Shalom 1988) of registry-model modes, with the IMM-PDA / IMM-JPDA correction.

Storage: one ``ModelBank`` per mode (mode k's model, its own process noise), all with the same rows (a track is
row i of every mode bank), and the mode probabilities ``mu`` (N, M). Per scan, for all tracks at once:

* ``predict(dt)``: the IMM interaction of every live row (the generated ``_mix`` of ``generated/imm.py``, the
  single-target IMM's own mixing: on the group when every mode is the same model, else in the common
  coordinates c = (x, y, θ, v_x, v_y, ω); ``lgekf.estimators.imm.kernels``), μ ← c̄ = PIᵀμ (the predicted mode
  probabilities), then each mode bank's fused prediction (``predict_bank`` of its model);
* ``gate(Z, γ)``: each mode bank's gate (S_k = ℋP_kℋᵀ + R, the innovations e_kj, d²_kj), and the mode-mixed
  likelihood of each track i and detection j,

      ℓ_ij = log Σ_k c̄_ik N(e_ikj; 0, S_ik),

  the exact predictive density of the detection under the IMM's Gaussian mixture. **The gate**: a detection is
  in track i's gate when it is in the gate of *any* mode, min_k d²_ikj ≤ γ (so its probability P_G is at least
  that of each mode's gate; the tracker keeps P_G in its weights w0 = 1 − r P_D P_G). ``d2`` is that minimum
  (the statistic of the gate; what the divergence monitor sums over held detections);
* ``update(β0, β)``: the IMM-PDA correction. With the association probabilities β_ij of the mixed likelihoods
  (β_i0 + Σ_j β_ij = 1, given that the track exists; PDA, JPDA or GNN marginals), the joint posterior of the
  track's association event θ_i and its mode factorises, because the mode enters only the likelihood of the
  track's own detection:

      P(θ_i = j, mode k | Z) = β_ij · c̄_ik N_ikj / N̄_ij,      N̄_ij = Σ_l c̄_il N_ilj,
      P(θ_i = 0, mode k | Z) = β_i0 · c̄_ik                        (no detection of the track: no information),

  so the mode probabilities are

      μ_ik = c̄_ik (β_i0 + Σ_j β_ij N_ikj / N̄_ij)                (they sum to β_i0 + Σ_j β_ij = 1),

  and mode k's association probabilities (conditioned on the mode) are β_ikj = β_ij N_ikj / (N̄_ij D_ik),
  β_ik0 = β_i0 / D_ik, D_ik = μ_ik / c̄_ik. Each mode bank then makes its PDA correction on the group
  (``pda.py``) with its own β_ik. With PDA weights this is the IMM-PDAF (Houles & Bar-Shalom, *Multisensor
  tracking of a maneuvering target in clutter*, IEEE TAES 25(2), 1989; the IMM as in Bar-Shalom, Li &
  Kirubarajan, *Estimation with Applications to Tracking and Navigation*, 2001): the formula above becomes
  μ_k ∝ c̄_k [(1 − P_D P_G) + (P_D/λ) Σ_j N_kj] (a test checks it); with JPDA marginals it is the IMM-JPDA of
  Blom & Bloem, *Combining IMM and JPDA for tracking multiple maneuvering targets in clutter*, FUSION 2002
  (the joint association probabilities from the mode-mixed likelihoods, then conditioned on each mode).
  ``mode_weights="shared"`` gives every mode the same β_ij instead (the mode probabilities by the same
  formula; on the base scenario of ``lgekf study --multi`` both gave the same GOSPA to 1e-4, docs/multi_target.md);
* ``physical(rows)`` / ``covariances(rows)`` / ``stds(rows)``: the combined estimate (the single-target IMM's,
  ``combined_common``: the modes' moment-matched mixture, on the group when every mode is the same model) in
  the common coordinates c and its covariance there: what ``lgekf track --model imm`` reports (the state
  columns x, y, theta, vx, vy, omega, body-frame velocity). ``mode_probabilities(rows)``: μ.

``add(x0, P0)`` takes the common coordinates: x0 = c (B, 6) and a diagonal covariance P0 (B, 6, 6) (the
tracker's one-point and two-point priors); each mode starts from them by ``initial_estimates`` of its model, as
a single-model track does.

With one detection per scan, β_i0 = 0 and β_i1 = 1 the cycle is the single-target IMM's (``lgekf.estimators.imm``):
the PDA correction is then the LG-EKF update (its covariance in the standard form (I − Kℋ)P, the IMM's update
in the Joseph form: equal to rounding); ``tests/estimators/test_imm_bank.py``.

Per scan the cost is the IMM's: one mixing per live track (a compiled loop over the rows) and M times a model
bank's gate and update (numpy over the rows and the detections for the likelihoods and weights); no Python loop
per track.
"""

from __future__ import annotations

import math

import numba as nb
import numpy as np

from ...core.common import COMMON_NAMES
from ...core.initiation import initial_estimates
from ..imm.estimator import _Setup
from ..imm.kernels import _mix, combined_common, workspace
from .bank import ModelBank

__all__ = ["IMMBank", "MODE_WEIGHTS"]

MODE_WEIGHTS = ("conditioned", "shared")


@nb.njit(cache=True)
def mix_rows(models, S, Pp, mu, PI, same_group, live):
    """The IMM interaction of every live row i, in place: mode states S[i] (M, L) and packed covariances Pp[i]
    (M, NP) become the mixed ones (generated ``_mix``), mu[i] the predicted probabilities c̄ = PIᵀμ."""
    M = models.shape[0]
    ws = workspace(M)
    cbar = np.empty(M)
    for i in range(S.shape[0]):
        if live[i]:
            _mix(models, S[i], Pp[i], mu[i], PI, same_group, cbar, ws)
            for j in range(M):
                mu[i, j] = cbar[j]


@nb.njit(cache=True)
def combined_rows(models, S, Pp, mu, same_group, rows, C, PC):
    """The combined estimate (generated ``combined_common``) of rows: C (R, 6), PC (R, 6, 6) in the common
    coordinates."""
    ws = workspace(models.shape[0])
    for k in range(rows.shape[0]):
        i = rows[k]
        combined_common(models, S[i], Pp[i], mu[i], same_group, C[k], PC[k], ws)


class IMMBank:
    """Per-track IMMs of registry-model modes, as a ``TrackFilterBank`` (module docstring).

    Parameters
    ----------
    modes : str or list
        The modes (``lgekf.estimators.imm.parse_modes`` syntax, e.g. ``"cv,se2r3:calm,se2r3:manoeuvre"``, or
        ``Mode`` objects / (model, accel_std) pairs); at least two.
    measurement : {"position", "pose"}
        A measurement every mode's model supports.
    meas_std : float or array_like
        The measurement's noise stds.
    transition : float or array_like, optional
        The probability of leaving a mode per scan (default ``lgekf.estimators.imm.DEFAULT_SWITCH``) or the
        (M, M) matrix PI[i, j] = P(mode j | mode i).
    capacity : int
        Initial number of rows.
    mu0 : array_like, optional
        A new track's mode probabilities (default uniform).
    mode_weights : {"conditioned", "shared"}
        Each mode's PDA correction with the association probabilities conditioned on the mode (the exact
        IMM-PDA / IMM-JPDA, default) or with the shared β of the mixed likelihoods.

    Attributes
    ----------
    banks : list of ModelBank
        One per mode, the same rows.
    mu : ndarray, (N, M)
        Mode probabilities (after ``predict``: the predicted ones c̄; after ``update``: the posterior ones).
    modes : list of Mode
    live, d2
        As ``ModelBank``'s (``d2``: min over the modes of d²_kij after ``gate``).
    """

    state_names = COMMON_NAMES

    def __init__(self, modes, measurement: str = "position", meas_std=0.3, transition=None, capacity: int = 64,
                 mu0=None, mode_weights: str = "conditioned"):
        s = _Setup(modes, transition, meas_std, measurement, mu0)
        if s.M < 2:
            raise ValueError(f"imm-modes: an IMM needs at least two modes, got {s.M} ({s.modes[0].name}); to track "
                             f"with one model, use that model ({s.modes[0].model}) instead of the IMM")
        if mode_weights not in MODE_WEIGHTS:
            raise ValueError(f"mode_weights: one of {', '.join(MODE_WEIGHTS)}, got {mode_weights!r}")
        self.setup = s
        self.modes = list(s.modes)
        self.M = s.M
        self.conditioned = mode_weights == "conditioned"
        self.banks = [ModelBank(m.model, measurement, m.accel_std, s.r, capacity) for m in s.modes]
        self.m = self.banks[0].m
        self._c0 = 0.5 * self.m * math.log(2.0 * math.pi)
        self.mu = np.zeros((capacity, s.M))
        self._work(capacity)
        self.d2 = np.zeros((0, 0))
        self._pairs = None  # after gate: the gated pairs (i, j) and log N_kij / N̄_ij (M, G) on them
        self._bk = np.zeros((0, 0))
        self._cache = None  # (rows, C, PC) of the last combined estimate

    def _work(self, cap):
        """The gathered mode states (N, M, L) and packed covariances (N, M, NP) of the interaction step."""
        self.S = np.zeros((cap, self.M, self.setup.L))
        self.Pp = np.zeros((cap, self.M, self.setup.NP))

    @property
    def live(self) -> np.ndarray:
        return self.banks[0].live

    @property
    def capacity(self) -> int:
        return self.live.size

    def add(self, x0: np.ndarray, P0: np.ndarray) -> np.ndarray:
        """Start tracks at common coordinates x0 (B, 6) with diagonal covariances P0 (B, 6, 6); returns their rows.
        Each mode starts from ``initial_estimates`` of its model; mode probabilities ``mu0``."""
        c = np.atleast_2d(np.asarray(x0, dtype=float))
        P0 = np.asarray(P0, dtype=float).reshape(c.shape[0], 6, 6)
        var = np.ascontiguousarray(np.diagonal(P0, axis1=1, axis2=2))
        if c.shape[1] != 6 or np.any(P0 != var[:, :, None] * np.eye(6)):
            raise ValueError("IMMBank.add: expected common coordinates (B, 6) and diagonal covariances (B, 6, 6)")
        rows = self._same_rows([bank.add(*initial_estimates(m.model, c, var)) for m, bank in zip(self.modes, self.banks)])
        self.mu[rows] = self.setup.mu0
        self._cache = None
        return rows

    def _same_rows(self, per_mode):
        """The rows every mode bank gave to the same new tracks (they have the same free rows), with ``mu`` and the
        mixing workspace grown to the capacity."""
        rows = per_mode[0]
        assert all(np.array_equal(r, rows) for r in per_mode[1:])
        cap = self.capacity
        if self.mu.shape[0] < cap:
            self.mu = np.vstack([self.mu, np.zeros((cap - self.mu.shape[0], self.M))])
            self._work(cap)
        return rows

    def remove(self, rows: np.ndarray) -> None:
        """End the tracks of ``rows`` in every mode."""
        for bank in self.banks:
            bank.remove(rows)
        self._cache = None

    def copy(self, rows: np.ndarray) -> np.ndarray:
        """Duplicate the live ``rows`` in every mode (state, covariance, the last ``gate``'s quantities), their mode
        probabilities and gated pairs; returns the new rows (the PMBM's local hypotheses, ``ModelBank.copy``)."""
        rows = np.asarray(rows, dtype=np.int64)
        new = self._same_rows([bank.copy(rows) for bank in self.banks])
        cap = self.capacity
        self.mu[new] = self.mu[rows]
        if self._pairs is not None and self.d2.ndim == 2 and self.d2.shape[1] > 0:
            d2 = np.full((cap, self.d2.shape[1]), np.inf)
            d2[:self.d2.shape[0]] = self.d2
            d2[new] = d2[rows]
            self.d2 = d2
            ii, jj, lr = self._pairs
            order = np.argsort(ii, kind="stable")
            cnt = np.bincount(ii, minlength=cap)[rows]  # the gated pairs of each copied row
            start = np.searchsorted(ii[order], rows)
            sel = order[np.arange(cnt.sum()) - np.repeat(np.cumsum(cnt) - cnt, cnt) + np.repeat(start, cnt)]
            self._pairs = (np.concatenate([ii, np.repeat(new, cnt)]), np.concatenate([jj, jj[sel]]),
                           np.concatenate([lr, lr[:, sel]], axis=1))
        self._cache = None
        return new

    def _gather(self):
        for k, b in enumerate(self.banks):
            self.S[:, k, :b.s.shape[1]] = b.s
            self.Pp[:, k, :b.p.shape[1]] = b.p

    def _scatter(self):
        for k, b in enumerate(self.banks):
            b.s[:] = self.S[:, k, :b.s.shape[1]]
            b.p[:] = self.Pp[:, k, :b.p.shape[1]]

    def predict(self, dt: float) -> None:
        """The interaction (mixing) of every live track, μ ← c̄, then every mode's prediction by dt (nothing when
        dt ≤ 0: no step)."""
        if not dt > 0:
            return
        s = self.setup
        self._gather()
        mix_rows(s.models, self.S, self.Pp, self.mu, s.PI, s.same_group, self.live)
        self._scatter()
        for bank in self.banks:
            bank.predict(dt)
        self._cache = None

    def gate(self, Z: np.ndarray, gamma: float) -> tuple[np.ndarray, np.ndarray]:
        """The mode-mixed log-likelihoods log Σ_k c̄_k N(e_kij; 0, S_ki) (N, D) of detections Z (D, m) and the gate
        (N, D): in the gate of any mode (module docstring); −inf outside it. The mixture is formed on the gated pairs
        only (the others get no weight in the association)."""
        live = self.live
        for k, bank in enumerate(self.banks):
            bank.gate(Z, gamma)
            self.d2 = bank.d2.copy() if k == 0 else np.minimum(self.d2, bank.d2)
        gated = (self.d2 <= gamma) & live[:, None]
        ii, jj = np.nonzero(gated)
        with np.errstate(divide="ignore"):
            a = np.stack([-0.5 * b.d2[ii, jj] - 0.5 * b.logdet[ii] - self._c0 for b in self.banks])  # log N_kij (M, G)
            w = a + np.log(self.mu[ii].T)  # log c̄_k N_kij
        top = w.max(axis=0)
        mixed = top + np.log(np.exp(w - top).sum(axis=0))  # finite: every gated pair has a mode with d² ≤ γ
        ll = np.full(gated.shape, -np.inf)
        ll[ii, jj] = mixed
        self._pairs = (ii, jj, a - mixed)  # log N_kij / N̄_ij on the gated pairs
        return ll, gated

    def update(self, beta0: np.ndarray, beta: np.ndarray) -> None:
        """The IMM-PDA correction with β_i0 (N,) and β_ij (N, D) of the last ``gate`` (module docstring): the mode
        probabilities, then each mode bank's PDA correction with its mode-conditioned (or the shared) weights. β is 0
        outside the gate (the association gives no weight there)."""
        ii, jj, log_ratio = self._pairs
        beta0 = np.ascontiguousarray(beta0, dtype=float)
        beta = np.ascontiguousarray(beta, dtype=float)
        N = beta0.size
        b = beta[ii, jj]
        terms = b * np.exp(log_ratio)  # β_ij N_kij / N̄_ij (M, G)
        D = beta0 + np.stack([np.bincount(ii, weights=t, minlength=N) for t in terms])  # μ_ik / c̄_ik (M, N)
        mu = self.mu.T * D
        tot = mu.sum(axis=0)
        ok = self.live & (tot > 0) & np.isfinite(tot)
        self.mu[ok] = (mu[:, ok] / tot[ok]).T
        for k, bank in enumerate(self.banks):
            if not self.conditioned:
                bank.update(beta0, beta)
                continue
            good = D[k] > 0.0
            inv = np.where(good, 1.0 / np.where(good, D[k], 1.0), 0.0)
            bk = self._weights(beta.shape)
            bk[ii, jj] = terms[k] * inv[ii]
            bank.update(np.where(good, beta0 * inv, 1.0), bk)
            bk[ii, jj] = 0.0  # zero again for the next mode and scan
        self._cache = None

    def _weights(self, shape):
        """A zero (N, D) array for a mode's weights, kept between calls (zeroing a fresh one per mode and scan cost a
        tenth of the scan in dense clutter)."""
        if self._bk.shape != shape:
            self._bk = np.zeros(shape)
        return self._bk

    def _combined(self, rows: np.ndarray):
        rows = np.asarray(rows, dtype=np.int64)
        if self._cache is not None and np.array_equal(self._cache[0], rows):
            return self._cache[1], self._cache[2]
        s = self.setup
        self._gather()
        C = np.zeros((rows.size, 6))
        PC = np.zeros((rows.size, 6, 6))
        combined_rows(s.models, self.S, self.Pp, self.mu, s.same_group, rows, C, PC)
        self._cache = (rows.copy(), C, PC)
        return C, PC

    def physical(self, rows: np.ndarray) -> np.ndarray:
        """The combined estimates (len(rows), 6) in the common coordinates (x, y, θ, v_x, v_y, ω)."""
        return self._combined(rows)[0].copy()

    def covariances(self, rows: np.ndarray) -> np.ndarray:
        """Their covariances (len(rows), 6, 6) in the common coordinates."""
        return self._combined(rows)[1].copy()

    def stds(self, rows: np.ndarray | None = None) -> np.ndarray:
        """Square roots of the combined covariances' diagonals (len(rows), 6); with None every row (N, 6), NaN on
        the rows not in use."""
        if rows is None:
            out = np.full((self.capacity, 6), np.nan)
            live = np.flatnonzero(self.live)
            out[live] = self.stds(live)
            return out
        P = self._combined(rows)[1]
        return np.sqrt(np.maximum(np.diagonal(P, axis1=1, axis2=2), 0.0))

    def mode_probabilities(self, rows: np.ndarray) -> np.ndarray:
        """μ (len(rows), M) of the given rows."""
        return self.mu[np.asarray(rows, dtype=np.int64)].copy()
