r"""Expectation–maximisation (EM) for the noise of a linear Gaussian model (Shumway & Stoffer 1982).

Where it applies
----------------
EM needs the complete-data likelihood of the states and its expectation under the smoothed posterior; both
are exact only when the model is linear Gaussian: the group is a vector space in its tangent coordinates
(Φ_G = I, so X = μ·exp(ε) is μ + ε), and F (eq:pred_cov), Q = G diag(σ²) Gᵀ (eq:motionG) and ℋ (eq:calH) do
not depend on the state. The model definition says so (``MotionModel.is_linear_gaussian``, the generated
``ModelSpec.linear``: the measurements with which a model is linear): of the registry models only CV with
position measurements. Then the LG-EKF is the Kalman filter, the innovation likelihood of
:func:`~lgekf.estimators.noise.tuning.learn_noise` is the exact likelihood, and EM maximises the same function. For
the Lie-group models (and CTRV) an EM around the smoothed trajectory would be an approximation whose
iterations need not increase the likelihood; :func:`learn_noise_em` refuses them (ValueError naming the
models it supports) and :func:`~lgekf.estimators.noise.tuning.learn_noise` (L-BFGS-B) serves every model.
Measured (``benchmarks/em_lie_groups.py``, that approximate EM on simulated SE(2)×SE(2) motion): on CTRV and
SE(2)×R² the likelihood rose to near its maximum and then fell in 90 of 200 iterations, ending with the turn noise
at half its maximum-likelihood value; on SE(2)×SE(2) the approximate E[n_y²] turned negative at once.

The model of one track (states in tangent coordinates τ, k = 1..L; step lengths dt_k vary)
------------------------------------------------------------------------------------------
    τ_0 ~ N(μ_0, P_0(r))                                (the two-point start, ``two_point_prior``)
    τ_k = F_k τ_{k-1} + b_k + G_k n_k,   n_k ~ N(0, diag(σ_{i(j)}²)),   Q_k = G_k diag(σ²) G_kᵀ
    z_k = ℋ τ_k + c + m_k,               m_k ~ N(0, R),  R = diag(r_{j(d)}²)   (NaN row: no z_k)

with F_k = ``transition``, b_k the constant part of ``motion``, and for each std σ_i a shape
Q_i(dt) = ``process_noise`` with σ_i = 1 and the others 0 (Q_k = Σ_i σ_i² Q_i(dt_k)). Q_k is singular (CV: rank 2
of 4), so the complete data are (τ_0, n_1..n_L, m_k): the map to (τ, z) has a Jacobian free of the parameters.

E-step (RTS smoother with the lag-one cross-covariance)
------------------------------------------------------
Forward Kalman filter and RTS backward pass (``forward_store``, ``smooth_stored``; the smoothed τˢ_k, Pˢ_k), the
smoother gain J_{k-1} = P_{k-1|k-1} F_kᵀ P_{k|k-1}⁻¹ and the lag-one cross-covariance
Cov(τ_k, τ_{k-1} | z_{1:L}) = Pˢ_k J_{k-1}ᵀ (de Jong 1989; equal to Shumway & Stoffer's recursion for P_{k,k-1|L}).
One more backward step gives the smoothed start τˢ_0 = μ_0 + J_0 (τˢ_1 − τ_{1|0}), Pˢ_0 = P_0 + J_0 (Pˢ_1 − P_{1|0}) J_0ᵀ.
The expected sufficient statistics are

    M_k = E[w_k w_kᵀ] = ē ēᵀ + Pˢ_k + F_k Pˢ_{k-1} F_kᵀ − Pˢ_k J_{k-1}ᵀ F_kᵀ − F_k J_{k-1} Pˢ_k,
          ē = τˢ_k − F_k τˢ_{k-1} − b_k,   w_k = G_k n_k;
    V_k = E[(z_k − ℋτ_k − c)(·)ᵀ] = ū ūᵀ + ℋ Pˢ_k ℋᵀ,  ū = z_k − ℋ τˢ_k − c;
    S_0 = E[(τ_0 − μ_0)(·)ᵀ] = (τˢ_0 − μ_0)(·)ᵀ + Pˢ_0.

M-step (closed form)
--------------------
Factor each shape Q_i(dt_k) = G_{k,i} G_{k,i}ᵀ (rank ρ_i) and stack G_k = [G_{k,1} … G_{k,p}]. When G_k has full
column rank (the shapes do not overlap: every registry model), n_k = G_k⁺ w_k exactly, E[n_k n_kᵀ] = G_k⁺ M_k G_k⁺ᵀ,
and the expected complete-data log-likelihood Σ_k Σ_i −½(ρ_i log σ_i² + tr[(G_k⁺ M_k G_k⁺ᵀ)_{ii}] / σ_i²) is
maximised by the weighted trace average

    σ_i² = Σ_k tr[(G_k⁺ M_k G_k⁺ᵀ)_{ii}] / Σ_k ρ_i          (one std: σ² = Σ_k tr(Q_{1}(dt_k)⁺ M_k) / (ρ K)),

the dt_k entering through the shapes. For the measurement std r_j (the entries d of z with R_dd = r_j²), when
the start's covariance scales as P_0(r) = r² A (checked numerically; true for CV), the prior's term joins the
measurements':

    r² = (Σ_k Σ_{d: j(d)=j} (V_k)_dd + Σ_tracks tr(A⁻¹ S_0)) / (N_j + n·n_tracks),

N_j the number of measured entries with std r_j. Otherwise (or with several measurement stds) the r-part of
the expected log-likelihood, −½ Σ_k Σ_d (log r_{j(d)}² + (V_k)_dd / r_{j(d)}²) − ½ Σ_tracks (log det P_0(r) +
tr(P_0(r)⁻¹ S_0)), is maximised numerically in log r from the current value (a generalised M-step, still
monotone). With ``meas_std`` given, r is held fixed.

Each iteration cannot decrease the likelihood (Dempster, Laird, Rubin 1977); :class:`EMTrace` records it.
EM converges linearly, slowly where the data identify a parameter weakly; by default it is accelerated by
SQUAREM (Varadhan & Roland 2008), safeguarded so that the recorded likelihood still never decreases (on the
test data 32 instead of 98 E-steps). The interval and the identification checks are those of
:func:`~lgekf.estimators.noise.tuning.learn_noise` (Hessian of −log L in log θ at the optimum). The E-step's kernels
run on one numba thread below ``SINGLE_THREAD_CELLS`` track steps.

References: R. H. Shumway, D. S. Stoffer, "An approach to time series smoothing and forecasting using the EM
algorithm", J. Time Series Anal. 3(4), 1982; Z. Ghahramani, G. E. Hinton, "Parameter estimation for linear
dynamical systems", Tech. Rep. CRG-TR-96-2, Univ. Toronto, 1996; P. de Jong, "Smoothing and interpolation with
the state-space model", JASA 84, 1989.
"""

from __future__ import annotations

import math
from contextlib import contextmanager
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike

from ...core.covariance import pack, unpack
from ...core.registry import MODELS, get_model
from ...core.rts import forward_store, smooth_stored
from .tracks import TrackBatch
from .tuning import (BOUNDS, NoiseFit, StartRecord, _fallback, _Likelihood, _noise_problem, _optimum_uncertainty,
                     _start_points)

__all__ = ["learn_noise_em", "EMTrace", "em_models", "em_or_lbfgs"]

_RANK_TOL = 1e-10  # eigenvalues of a shape Q_i below this × its largest are zero
_AFFINE_TOL = 1e-9
#: below this many track steps the E-step's numba kernels run on one thread: EM calls them hundreds of times on
#: little work each, and waking the thread pool cost 10-30 ms per call on the shared 2-core machine (0.04 ms of
#: work for 8 tracks × 38 steps; 3.4 ms single-threaded against 31 ms on two threads for 150 × 100)
SINGLE_THREAD_CELLS = 100_000


@contextmanager
def _numba_threads(n: int):
    """Run the block with at most ``n`` numba threads (numba's setting is per calling thread; restored after)."""
    import numba

    old = numba.get_num_threads()
    numba.set_num_threads(max(1, min(n, old)))
    try:
        yield
    finally:
        numba.set_num_threads(old)


@dataclass
class EMTrace:
    """The iterations of :func:`learn_noise_em`: the parameters (stds) before each E-step and the exact
    log-likelihood there (``loglik[i]`` at ``values[i]``); EM makes ``loglik`` non-decreasing. ``closed_form_r``:
    the measurement std's M-step was the closed form (the start's covariance scales as r²), else numeric.
    ``e_steps``: smoother passes run (with SQUAREM also those of rejected extrapolations, not in ``loglik``)."""

    values: list = field(default_factory=list)
    loglik: list = field(default_factory=list)
    converged: bool = False
    closed_form_r: bool = False
    e_steps: int = 0


def em_models() -> dict:
    """The registry models EM applies to, with their linear measurements ({model: (measurement, ...)})."""
    return {name: spec.linear for name, spec in MODELS.items() if spec.linear}


def em_or_lbfgs(model: str, measurement: str, method: str) -> str:
    """"EM where it applies": "em" (use :func:`learn_noise_em`) when ``method`` is "em" and the model is linear
    Gaussian with ``measurement``, else "lbfgs" (``learn_noise``, the likelihood optimiser, serves every model)."""
    return "em" if method == "em" and measurement in get_model(model).linear else "lbfgs"


def _refusal(model: str, measurement: str) -> str:
    ok = "; ".join(f"{n} with {', '.join(ms)}" for n, ms in em_models().items()) or "none"
    return (f"EM applies only to linear Gaussian models (a vector-space group with F, Q and ℋ independent of the "
            f"state, so that the smoothed expectations are exact): {model} with {measurement} measurements is not; "
            f"EM supports: {ok}. Use the likelihood optimiser (learn_noise; --tune-method lbfgs or mle on the command line), which serves every model")


class _Linear:
    """The linear Gaussian model of one registry model and measurement, read off its generated kernels once:
    the affine map internal state → tangent coordinates τ, F(dt), b(dt), the noise shapes Q_i(dt), ℋ and c."""

    def __init__(self, spec, measurement: str, dts_unique: np.ndarray):
        K = spec.kernels
        n = spec.n
        self.n = n
        self.ni = len(spec.internal_names)
        s0 = np.ascontiguousarray(K.state_from_physical(np.zeros(n)), dtype=float)
        self.s_ref = s0
        # τ(s) = between(s_ref, s) = A (s − s_ref) for a vector group; A from unit steps, checked at random points
        A = np.empty((n, self.ni))
        for j in range(self.ni):
            e = s0.copy()
            e[j] += 1.0
            A[:, j] = K.between(s0, e)
        self.A = A
        rng = np.random.default_rng(0)
        for _ in range(3):
            s = s0 + rng.normal(size=self.ni)
            if not np.allclose(K.between(s0, s), A @ (s - s0), rtol=_AFFINE_TOL, atol=_AFFINE_TOL):
                raise ValueError(f"EM: the tangent coordinates of {spec.name} are not affine in its state")
        nq = len(spec.noise_names)
        self.F = np.empty((len(dts_unique), n, n))
        self.b = np.empty((len(dts_unique), n))
        self.Qs = np.empty((len(dts_unique), nq, n, n))
        for u, dt in enumerate(dts_unique):
            self.F[u] = K.transition(s0, dt)
            self.b[u] = K.between(s0, K.motion(s0, dt))
            for i in range(nq):
                q = np.zeros(nq)
                q[i] = 1.0
                self.Qs[u, i] = K.process_noise(s0, dt, *q)
        self.H = np.asarray(spec.kernel("calH", measurement)(s0), dtype=float)
        m = self.H.shape[0]
        out = np.empty(m)
        spec.kernel("innovation_into", measurement)(s0, *np.zeros(m), out)
        self.c = -out  # h(s_ref): z − h(s) = z − c − ℋ τ(s)

    def tau(self, s: np.ndarray) -> np.ndarray:
        """Tangent coordinates of internal states (..., n_int)."""
        return (s - self.s_ref) @ self.A.T

    def noise_factors(self) -> tuple[np.ndarray, np.ndarray]:
        """G⁺ (U, Σρ, n) of the stacked factors of the shapes per distinct dt, and the block of each column (Σρ,)."""
        U, nq, n, _ = self.Qs.shape
        blocks = None
        pinv = []
        for u in range(U):
            cols, owner = [], []
            for i in range(nq):
                w, V = np.linalg.eigh(self.Qs[u, i])
                keep = w > _RANK_TOL * max(w.max(), 1e-300)
                cols.append(V[:, keep] * np.sqrt(w[keep]))
                owner += [i] * int(keep.sum())
            G = np.concatenate(cols, axis=1)
            if np.linalg.matrix_rank(G) < G.shape[1]:
                raise ValueError("EM: the process-noise shapes of this model overlap (G has dependent columns); "
                                 "the closed-form M-step does not apply; use learn_noise")
            if blocks is None:
                blocks = np.asarray(owner)
            elif not np.array_equal(blocks, owner):
                raise ValueError("EM: the rank of the process-noise shapes changes with dt; use learn_noise")
            pinv.append(np.linalg.pinv(G))
        return np.asarray(pinv), blocks


class _Cells:
    """The valid steps (b, k) of a TrackBatch, flattened (k < length of track b), with their F, b, G⁺."""

    def __init__(self, batch: TrackBatch, lin: _Linear, inv: np.ndarray, Gp: np.ndarray):
        B, K, m = batch.z.shape
        valid = np.arange(K)[None, :] < batch.lengths[:, None]
        self.bi, self.ki = np.nonzero(valid)
        self.first = self.ki == 0                      # every track has k = 0 (length ≥ 1), in track order
        u = inv[self.bi, self.ki]
        self.F = lin.F[u]
        self.b = lin.b[u]
        self.Gp = Gp[u]
        self.z = batch.z[self.bi, self.ki]
        self.obs = ~np.any(np.isnan(self.z), axis=1)
        self.z = np.where(self.obs[:, None], self.z, 0.0)
        self.m = m


def _estep(spec, measurement, lin, batch, cells, x0, tau0, P0, q, r):
    """Filter + RTS smoother over all tracks; returns (log L, M (N, n, n), V (N, m), S_0 (B, n, n)) over the
    valid steps (module docstring)."""
    n, m = lin.n, cells.m
    bi, ki, F = cells.bi, cells.ki, cells.F
    fp = forward_store(spec, measurement, batch.z, batch.dts, x0, pack(P0), q, r, simd=False)
    ll = float(np.sum(-0.5 * (fp.logdet[bi, ki][cells.obs] + fp.nis[bi, ki][cells.obs] + m * math.log(2 * math.pi))))
    fp.lengths = np.ascontiguousarray(batch.lengths, dtype=np.int64)
    _, s_sm, p_sm = smooth_stored(spec, fp)
    s_pred, p_pred, s_filt, p_filt = fp.states()
    ts = lin.tau(s_sm[bi, ki])                 # (N, n) smoothed means of the valid steps
    Ps = unpack(p_sm[bi, ki], n)
    tp = lin.tau(s_pred[bi, ki])
    Pp = unpack(p_pred[bi, ki], n)
    # the previous step's posterior (k = 0: the start): row k of the arrays extended by the start
    p0 = pack(P0)
    Pf_prev = unpack(np.concatenate([p0[:, None], p_filt], axis=1)[bi, ki], n)
    # smoother gain J_{k-1} = P_{k-1|k-1} F_kᵀ P_{k|k-1}⁻¹ (P_{k|k-1} symmetric: solve P_{k|k-1} Jᵀ = F_k P_{k-1|k-1})
    J = np.swapaxes(np.linalg.solve(Pp, F @ Pf_prev), -1, -2)
    # smoothed start: one more backward step
    f0 = cells.first
    J0 = J[f0]
    ts0 = tau0 + (J0 @ (ts[f0] - tp[f0])[..., None])[..., 0]
    Ps0 = P0 + J0 @ (Ps[f0] - Pp[f0]) @ np.swapaxes(J0, -1, -2)
    # the previous step's smoothed moments: the step before in the flat order, or the smoothed start
    prev = np.arange(len(bi)) - 1
    ts_prev = np.where(f0[:, None], ts0[bi], ts[prev])
    Ps_prev = np.where(f0[:, None, None], Ps0[bi], Ps[prev])
    e = ts - (F @ ts_prev[..., None])[..., 0] - cells.b
    C = Ps @ np.swapaxes(J, -1, -2)            # Cov(τ_k, τ_{k-1} | all)
    FC = F @ np.swapaxes(C, -1, -2)
    M = e[:, :, None] * e[:, None, :] + Ps + F @ Ps_prev @ np.swapaxes(F, -1, -2) - FC - np.swapaxes(FC, -1, -2)
    u = cells.z - lin.c - ts @ lin.H.T
    V = u**2 + np.einsum("di,kij,dj->kd", lin.H, Ps, lin.H)
    d00 = ts0 - tau0
    S0 = d00[:, :, None] * d00[:, None, :] + Ps0
    return ll, M, V[cells.obs], S0


def learn_noise_em(model: str, tracks, *, dt: float | None = None, measurement: str = "position",
                   meas_std: float | ArrayLike | None = None, omega_std: float = 0.5, heading_cap: float = math.pi,
                   hessian: bool = True, baseline: float = 1.0, max_iter: int = 2000, tol: float = 1e-7,
                   init: ArrayLike | None = None, trace: EMTrace | None = None, accelerate: bool = True,
                   starts: dict | None = None, _numeric_r: bool = False) -> NoiseFit:
    r"""Maximum-likelihood noise of a linear Gaussian model by EM (E: RTS smoother, M: closed form).

    The same inputs and result as :func:`~lgekf.estimators.noise.tuning.learn_noise`, the same likelihood (the
    innovation likelihood given each track's two-point start); the formulas are in the module docstring.

    Parameters
    ----------
    model : str
        A registry model whose ``linear`` measurements include ``measurement`` (:func:`em_models`; CV).
    tracks : sequence or TrackBatch
        As for ``learn_noise``: pairs (t (K,), z (K, m)), or arrays z (K, m) with ``dt``, or a TrackBatch.
    dt : float, optional
        Sampling period of tracks given without times.
    measurement : str
        "position".
    meas_std : float or array_like, optional
        Fixed measurement std(s); then only the process noise is learned.
    omega_std, heading_cap, baseline : float
        Of the two-point start (as for ``learn_noise``).
    hessian : bool
        Compute the 95 % intervals from the Hessian of −log L in log θ at the optimum.
    max_iter : int
        Iteration limit (``problems`` says when it was reached).
    tol : float
        Stop when the log-likelihood gains less than ``tol`` × (1 + |log L|) in an iteration and no std
        changes by more than 1e-5 relative.
    init : array_like, optional
        Starting stds (process then measurement), a start labelled "init".
    starts : dict, optional
        Further starts {label: (accel_std, meas_std)} (as for ``learn_noise``). Every start's log-likelihood
        is evaluated and EM runs from the best valid one (``lgekf.estimators.noise.tuning.filter_lost``); EM never
        lowers the likelihood, and the returned fit is never below that start's (else the start is kept, said in
        ``problems``). Without ``init`` and ``starts``: the model's ``default_accel_std`` and a second-difference
        guess of r.
    trace : EMTrace, optional
        Filled with every iteration's stds and log-likelihood.
    accelerate : bool
        SQUAREM (Varadhan & Roland, "Simple and globally convergent methods for accelerating the convergence
        of any EM algorithm", Scand. J. Stat. 35, 2008; scheme SqS3) on the variances: after two EM steps an
        extrapolated point, kept (with one EM step from it) only when its likelihood is higher than the second
        step's, so the recorded likelihood still never decreases; the same fixed point in several times fewer
        E-steps. False: plain EM (``max_iter`` counts E-steps either way).

    Returns
    -------
    NoiseFit
        As from ``learn_noise`` (``starts``: every start, the end only for the one EM ran from).

    Raises
    ------
    ValueError
        A model/measurement that is not linear Gaussian (naming those EM supports), bad input, or fewer
        than ``MIN_UPDATES_PER_PARAMETER`` updates per learned parameter.
    """
    from scipy.optimize import minimize

    spec = get_model(model)
    meas = spec.measurement(measurement)
    if measurement not in spec.linear:
        raise ValueError(_refusal(model, measurement))
    m = meas.dim
    batch, nq, nr, names, fixed_r, d, n_upd = _noise_problem(model, spec, meas, tracks, dt, meas_std, baseline)
    if meas.noise_inputs is None:
        raise ValueError(f"EM: the noise of the {measurement} measurement is not diagonal with one std per entry")
    lik = _Likelihood(spec, measurement, batch, fixed_r, omega_std, heading_cap)
    x0, prior = lik.x0, lik.prior
    B, K, _ = batch.z.shape
    n = spec.n
    dts_u, inv = np.unique(batch.dts, return_inverse=True)
    inv = inv.reshape(batch.dts.shape)
    lin = _Linear(spec, measurement, dts_u)
    Gp, owner = lin.noise_factors()
    cells = _Cells(batch, lin, inv, Gp)
    rank = np.array([np.sum(owner == i) for i in range(nq)])
    meas_idx = np.asarray(meas.noise_inputs)
    tau0 = lin.tau(np.stack([spec.kernels.state_from_physical(x) for x in x0]))

    def P0_of(r):
        return prior(r[0], r[-1] if meas.angles else None)

    A1 = P0_of(np.ones(nr))
    homogeneous = (nr == 1 and not _numeric_r
                   and np.allclose(P0_of(np.full(nr, 2.0)), 4.0 * A1, rtol=1e-10, atol=1e-12))
    A1inv = np.linalg.inv(A1) if homogeneous else None

    given = dict(starts or {})
    if init is not None:
        th = np.asarray(init, dtype=float).reshape(-1)
        if th.shape != (nq + nr,) or np.any(~np.isfinite(th)) or np.any(th <= 0):
            raise ValueError(f"init: expected {nq + nr} positive stds, got {np.asarray(init).tolist()}")
        given = {"init": (th[:nq], th[nq:]), **given}
    records = [StartRecord(label, v, *lik.assess(v)) for label, v in _start_points(spec, meas, batch, fixed_r, given, 0)]
    # EM from the best valid start (the highest log L if none is valid): monotone, it cannot end below it
    run = max(records, key=lambda rec: (rec.start_lost is None, np.nan_to_num(rec.start_loglik, nan=-np.inf)))
    q, r = run.start[:nq].copy(), run.start[nq:].copy()
    threads = 1 if batch.z.shape[0] * batch.z.shape[1] < SINGLE_THREAD_CELLS else 1 << 30

    def em_map(q, r):
        """The log-likelihood at (q, r) and the EM update (q', r') (None, None if the filter diverged)."""
        ll, M, V, S0 = _estep(spec, measurement, lin, batch, cells, x0, tau0, P0_of(r), q, r)
        tr.e_steps += 1
        if not math.isfinite(ll):
            return ll, None, None
        # process noise: E[n nᵀ] = G⁺ M G⁺ᵀ per step, summed per std over the valid steps
        Enn = np.einsum("kai,kij,kaj->ka", cells.Gp, M, cells.Gp)        # (N, Σρ): diagonal of G⁺ M G⁺ᵀ
        q_new = np.sqrt(np.array([Enn[:, owner == i].sum() for i in range(nq)]) / (rank * len(M)))
        r_new = r
        if fixed_r is None:
            Vsum = np.array([V[:, meas_idx == j].sum() for j in range(nr)])
            Nj = np.array([len(V) * np.sum(meas_idx == j) for j in range(nr)])
            if homogeneous:
                prior_term = float(np.einsum("bij,bji->", A1inv, S0))
                r_new = np.sqrt((Vsum + prior_term) / (Nj + n * B))
            else:
                def f(lr):
                    rr = np.exp(lr)
                    P0 = P0_of(rr)
                    sign, logdet = np.linalg.slogdet(P0)
                    tr0 = np.einsum("bij,bji->", np.linalg.inv(P0), S0)
                    return 0.5 * (np.sum(Nj * 2 * lr) + np.sum(Vsum / rr**2) + np.sum(logdet) + tr0)
                res = minimize(f, np.log(r), method="L-BFGS-B", bounds=[(math.log(BOUNDS[0]), math.log(BOUNDS[1]))] * nr)
                r_new = np.exp(res.x) if res.fun <= f(np.log(r)) else r
        return ll, np.clip(q_new, *BOUNDS), np.clip(np.asarray(r_new, dtype=float), *BOUNDS)

    def done(ll, ll_prev, th, th_new):
        return ll - ll_prev < tol * (1 + abs(ll)) and np.all(np.abs(th_new / th - 1) < 1e-5)

    tr = trace if trace is not None else EMTrace()
    converged = False
    ll_prev = -math.inf
    with _numba_threads(threads):
        it = 0
        while it < max_iter:
            ll0, q1, r1 = em_map(q, r)
            it += 1
            if q1 is None:
                raise ValueError("EM: the filter diverged (non-finite likelihood); try init= or learn_noise")
            tr.values.append(np.concatenate([q, r]))
            tr.loglik.append(ll0)
            if done(ll0, ll_prev, np.concatenate([q, r]), np.concatenate([q1, r1])):
                q, r = q1, r1
                converged = True
                break
            ll_prev = ll0
            if not accelerate:
                q, r = q1, r1
                continue
            # SQUAREM (Varadhan & Roland 2008, SqS3) on the variances: two EM steps, an extrapolation, one EM step
            # from it; kept only if it beats the second point's likelihood, so the recorded likelihood never drops
            ll1, q2, r2 = em_map(q1, r1)
            it += 1
            if q2 is None:
                raise ValueError("EM: the filter diverged (non-finite likelihood); try init= or learn_noise")
            tr.values.append(np.concatenate([q1, r1]))
            tr.loglik.append(ll1)
            ll_prev = ll1
            th0, th1, th2 = (np.concatenate([a, b]) ** 2 for a, b in ((q, r), (q1, r1), (q2, r2)))
            rho, v = th1 - th0, th2 - 2 * th1 + th0
            nv = float(np.linalg.norm(v))
            alpha = min(-float(np.linalg.norm(rho)) / nv, -1.0) if nv > 0 else -1.0
            thx = th0 - 2 * alpha * rho + alpha**2 * v
            q, r = q2, r2
            if alpha < -1.0 and np.all(thx > 0):
                sx = np.clip(np.sqrt(thx), *BOUNDS)
                qx, rx = sx[:nq], (sx[nq:] if fixed_r is None else fixed_r)
                llx, qy, ry = em_map(qx, rx)
                it += 1
                if qy is not None and llx >= ll1:
                    tr.values.append(np.concatenate([qx, rx]))
                    tr.loglik.append(llx)
                    ll_prev = llx
                    q, r = qy, ry
        tr.converged = converged
        tr.closed_form_r = bool(homogeneous and fixed_r is None)
        ll = _estep(spec, measurement, lin, batch, cells, x0, tau0, P0_of(r), q, r)[0]
        tr.e_steps += 1
        tr.values.append(np.concatenate([q, r]))
        tr.loglik.append(ll)
    values = np.concatenate([q, r])
    fixed = tuple(not f for f in lik.free)
    run.end = values
    run.end_loglik, run.end_lost = lik.assess(values)
    ll = run.end_loglik
    fallback = _fallback(records, ll if run.end_lost is None else -math.inf)
    if fallback is not None:
        values, ll, kept, why = fallback
        nan = np.where(lik.free, np.nan, values)
        return NoiseFit(model, measurement, names, values, nan, nan.copy(), np.full(nq + nr, np.nan), float(ll), n_upd,
                        int(B), fixed, records, [why], "em", kept)
    with _numba_threads(threads):
        log_se, ci_low, ci_high, problems = _optimum_uncertainty(lik, names, values, hessian, n_upd * m)
    if not converged:
        problems.insert(0, f"EM did not converge in {max_iter} iterations")
    return NoiseFit(model, measurement, names, values, ci_low, ci_high, log_se, float(ll), n_upd, int(B), fixed,
                    records, problems, "em", f"the optimum from the {run.label} start", hessian)
