"""A bank of per-track filters of one registry model, stored as arrays (one row per track), and the small
interface the multi-target tracker needs from it (``TrackFilterBank``).

The tracker (``lgekf.estimators.multitarget.tracker``) talks to its filters only through this interface, once per
scan for all tracks (no Python per track):

* ``add(x0, P0) -> rows`` / ``remove(rows)``: start and end tracks;
* ``predict(dt)``: every live track to the scan time;
* ``gate(Z, gamma) -> (loglik, gated)``: log N(e_ij; 0, S_i) and the gate d² ≤ γ of every live track i
  and detection j (the quantities PDA/JPDA/GNN weigh);
* ``update(beta0, beta)``: the PDA correction of every track with the association weights β of the last
  gated scan;
* ``copy(rows) -> new_rows``: duplicates of rows, with their state and the quantities of the last ``gate`` (the
  PMBM's local hypotheses: a copy updated by ``update`` with β_ij = 1 for one detection j is the hard update with
  that detection, the original stays the missed-detection hypothesis);
* ``physical(rows)``, ``covariances(rows)`` and ``stds(rows)``: the estimates to report.

``ModelBank`` implements it with the generated kernels of a model (fused ``predict``, ``calH_<meas>``,
the innovation, ``retract``, ``right_jacobian``; see ``derive/codegen/bank.py``). ``IMMBank``
(``imm_bank.py``) implements the same calls with an IMM per track: ``gate`` with the mode-mixed likelihood
Σ_k c̄_k N_k, ``update`` with the IMM-PDA per-mode corrections; the tracker uses it unchanged.
"""

from __future__ import annotations

from typing import Protocol

import numpy as np

from ...core.covariance import pack, packed_diagonal, unpack
from ...core.registry import get_model
from .gating import gate_scores, innovation_covariances
from .pda import pda_corrections, transport_covariances

__all__ = ["TrackFilterBank", "ModelBank"]


class TrackFilterBank(Protocol):
    """What the multi-target tracker needs from its per-track filters (see the module docstring)."""

    live: np.ndarray
    d2: np.ndarray  # after ``gate``: (N, M) the normalised innovations squared eᵀS⁻¹e of every row and detection

    def add(self, x0: np.ndarray, P0: np.ndarray) -> np.ndarray: ...

    def remove(self, rows: np.ndarray) -> None: ...

    def predict(self, dt: float) -> None: ...

    def gate(self, Z: np.ndarray, gamma: float) -> tuple[np.ndarray, np.ndarray]: ...

    def update(self, beta0: np.ndarray, beta: np.ndarray) -> None: ...

    def copy(self, rows: np.ndarray) -> np.ndarray: ...

    def physical(self, rows: np.ndarray) -> np.ndarray: ...

    def covariances(self, rows: np.ndarray) -> np.ndarray: ...

    def stds(self, rows: np.ndarray | None = None) -> np.ndarray: ...


class ModelBank:
    """Per-track LG-EKFs (or EKF/KF) of one registry model, in arrays that grow as tracks are added.

    Parameters
    ----------
    model : str
        A registry model (``lgekf.core.registry.MODELS``).
    measurement : str
        ``"position"`` or ``"pose"`` (a measurement the model supports).
    accel_std : array_like
        The model's process-noise stds (its ``noise_names``).
    meas_std : array_like
        The measurement's noise stds (its ``noise_names``: ``r`` for position; ``r_x, r_y, r_theta`` for pose; ``r_p,
        r_a`` for pose3), or one number for all.
    capacity : int
        Initial number of rows.

    Notes
    -----
    Row i holds the internal state ``s[i]`` and the packed covariance ``p[i]`` (tangent coordinates of
    X = μ·exp(ε), right perturbation); ``live[i]`` marks rows in use. Removed rows are reused.
    """

    def __init__(self, model: str, measurement: str, accel_std, meas_std, capacity: int = 64):
        self.spec = get_model(model)
        self.state_names = tuple(self.spec.state_names)
        self.meas = self.spec.measurement(measurement)
        self.kern = self.spec.kernels
        self.q = np.ascontiguousarray(accel_std, dtype=float)
        r = np.ascontiguousarray(meas_std, dtype=float).reshape(-1)
        if r.size == 1 and self.meas.dim > 1:
            r = np.full(len(self.meas.noise_names), r[0])
        # R = diag(σ_k²) with σ_k the std of entry k of z (``noise_inputs``: pose3's (r_p, r_a) serve 3 entries each)
        inputs = self.meas.noise_inputs if self.meas.noise_inputs is not None else tuple(range(self.meas.dim))
        self.R = np.diag(r[list(inputs)] ** 2)
        n, m = self.spec.n, self.meas.dim
        self.n, self.m = n, m
        self.periodic = np.asarray(self.spec.periodic_tangent, dtype=np.int64)
        self._innov = self.spec.kernel("innovation_bank", measurement)
        self._calH = self.spec.kernel("calH_bank", measurement)
        self._diag = packed_diagonal(n)
        self._alloc(capacity)
        self._last = None

    def _alloc(self, cap):
        n, m = self.n, self.m
        self.s = np.zeros((cap, len(self.spec.internal_names)))
        self.p = np.zeros((cap, self.spec.n_packed))
        self.live = np.zeros(cap, dtype=bool)
        self.H = np.zeros((cap, m, n))
        self.S = np.zeros((cap, m, m))
        self.Sinv = np.zeros((cap, m, m))
        self.logdet = np.zeros(cap)

    def _grow(self, need):
        """More rows; the rows in use keep their state and the quantities of the last ``gate`` (ℋ, S, S⁻¹, log det S,
        d², innovations), so that ``copy`` between ``gate`` and ``update`` may grow the bank."""
        cap = self.live.size
        new = max(2 * cap, need)
        old = (self.s, self.p, self.live, self.H, self.S, self.Sinv, self.logdet)
        self._alloc(new)
        self.s[:cap], self.p[:cap], self.live[:cap], self.H[:cap], self.S[:cap], self.Sinv[:cap], self.logdet[:cap] = old
        if self._last is not None:
            E = np.zeros((new,) + self._last.shape[1:])
            E[:cap] = self._last
            self._last = E
            d2 = np.full((new, self.d2.shape[1]), np.inf)
            d2[:cap] = self.d2
            self.d2 = d2

    def add(self, x0: np.ndarray, P0: np.ndarray) -> np.ndarray:
        """Start tracks at physical states x0 (B, n) with covariances P0 (B, n, n); returns their rows."""
        x0 = np.atleast_2d(np.asarray(x0, dtype=float))
        B = x0.shape[0]
        free = np.flatnonzero(~self.live)
        if free.size < B:
            self._grow(self.live.size + B - free.size)
            free = np.flatnonzero(~self.live)
        rows = free[:B]
        s = np.empty((B, self.s.shape[1]))
        self.kern.states_from_physical(np.ascontiguousarray(x0), s)
        self.s[rows] = s
        self.p[rows] = pack(np.asarray(P0, dtype=float).reshape(B, self.n, self.n))
        self.live[rows] = True
        return rows

    def remove(self, rows: np.ndarray) -> None:
        """End the tracks of ``rows`` (their rows are reused)."""
        self.live[np.asarray(rows, dtype=np.int64)] = False

    def copy(self, rows: np.ndarray) -> np.ndarray:
        """Duplicate the live ``rows``: state, covariance and the quantities of the last ``gate`` (so ``update`` treats a
        copy as its original); returns the new rows, in the order of ``rows``."""
        rows = np.asarray(rows, dtype=np.int64)
        B = rows.size
        free = np.flatnonzero(~self.live)
        if free.size < B:
            self._grow(self.live.size + B - free.size)
            free = np.flatnonzero(~self.live)
        new = free[:B]
        for a in (self.s, self.p, self.H, self.S, self.Sinv, self.logdet):
            a[new] = a[rows]
        if self._last is not None and self._last.shape[0] == self.live.size:
            self._last[new] = self._last[rows]
            self.d2[new] = self.d2[rows]
        self.live[new] = True
        return new

    def predict(self, dt: float) -> None:
        """Predict every live track by dt > 0 (the generated fused ``predict``)."""
        if dt > 0:
            self.kern.predict_bank(self.s, self.p, self.live, float(dt), self.q)

    def gate(self, Z: np.ndarray, gamma: float) -> tuple[np.ndarray, np.ndarray]:
        """Log-likelihoods (N, M) and gate membership (N, M) of detections Z (M, m) for every row.

        Computes ℋ (``calH_bank_<meas>``), S = ℋPℋᵀ + R, the innovations (``innovation_bank_<meas>``)
        and keeps them for the next ``update``."""
        Z = np.ascontiguousarray(Z, dtype=float).reshape(-1, self.m)
        N, M = self.live.size, Z.shape[0]
        self._calH(self.s, self.live, self.H)
        innovation_covariances(self.H, self.p, self.live, self.R, self.S, self.Sinv, self.logdet)
        E = np.zeros((N, M, self.m))
        self._innov(self.s, self.live, Z, E)
        d2 = np.empty((N, M))
        ll = np.empty((N, M))
        g = np.empty((N, M), dtype=bool)
        gate_scores(E, self.Sinv, self.logdet, self.live, float(gamma), d2, ll, g)
        self._last = E
        self.d2 = d2
        return ll, g

    def update(self, beta0: np.ndarray, beta: np.ndarray) -> None:
        """The PDA correction (``lgekf.estimators.multitarget.pda``) of every live track with weights β_i0 (N,) and
        β_ij (N, M) for the detections of the last ``gate`` call."""
        E = self._last
        N = self.live.size
        eps = np.zeros((N, self.n))
        Pc = np.zeros((N, self.n, self.n))
        upd = np.zeros(N, dtype=bool)
        pda_corrections(self.p, self.live, self.H, self.S, self.Sinv, E, np.ascontiguousarray(beta0),
                        np.ascontiguousarray(beta), self.periodic, eps, Pc, upd)
        if upd.any():
            self.kern.retract_bank(self.s, upd, eps)
            Phi = np.zeros((N, self.n, self.n))
            self.kern.right_jacobian_bank(upd, eps, Phi)
            transport_covariances(Phi, Pc, upd, self.p)

    def physical(self, rows: np.ndarray) -> np.ndarray:
        """Physical states (len(rows), n) of the given live rows."""
        rows = np.asarray(rows, dtype=np.int64)
        out = np.zeros((rows.size, self.n))
        for k, i in enumerate(rows):
            self.kern.physical_into(self.s[i], out[k])
        return out

    def covariances(self, rows: np.ndarray) -> np.ndarray:
        """The covariances P (len(rows), n, n) of the given live rows, in the tangent of each track's mean (right
        perturbation X = μ·exp(ε), the model's tangent order)."""
        return unpack(self.p[np.asarray(rows, dtype=np.int64)], self.n)

    def stds(self, rows: np.ndarray | None = None) -> np.ndarray:
        """Square roots of P's diagonal: the std of each tangent coordinate, (len(rows), n) of the given rows, or
        (N, n) of every row when None."""
        p = self.p if rows is None else self.p[np.asarray(rows, dtype=np.int64)]
        return np.sqrt(np.maximum(p[:, self._diag], 0.0))
