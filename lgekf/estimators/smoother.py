r"""Rauch–Tung–Striebel smoothing on the group, for every registry model.

Derivation (right perturbation X = μ·exp(ε), Φ the right Jacobian: exp(v + δ) ≈ exp(v)·exp(Φ(v)δ))
------------------------------------------------------------------------------------------------------
The forward LG-EKF (the paper's eq:pred_mu, eq:pred_cov, eq:K, eq:up_mu, eq:up_P) leaves at every step k the
posterior X_k = μ_k·exp(ε_k), ε_k ~ N(0, P_k), and the prediction X_{k+1} = μ_{k+1|k}·exp(ε'), ε' ~
N(0, P_{k+1|k}) with, to first order, ε' = F_k ε_k + w_k, F_k = Ad(exp(−Ω)) + Φ(Ω)𝒞 the generated
``transition(μ_k, dt_{k+1})`` (the F of the predict), w_k ~ N(0, Φ(Ω)GQGᵀΦ(Ω)ᵀ) independent of ε_k. So in the
tangents at (μ_k, μ_{k+1|k}) the pair (ε_k, ε') is jointly Gaussian with cross-covariance P_k F_kᵀ, which is
the linear-Gaussian setting of the RTS smoother (Rauch, Tung, Striebel, "Maximum likelihood estimates of
linear dynamic systems", AIAA J. 3(8), 1965; the extended form: Särkkä, *Bayesian Filtering and Smoothing*,
2013, Ch. 9).

Suppose the smoothed X_{k+1} = μˢ_{k+1}·exp(η), η ~ N(0, Pˢ_{k+1}). In the tangent at μ_{k+1|k}:
μˢ_{k+1} = μ_{k+1|k}·exp(d), d = [log(μ_{k+1|k}⁻¹ μˢ_{k+1})]^∨ (generated ``between``), and
exp(d)·exp(η) ≈ exp(d + Φ(d)⁻¹η), so ε' ~ N(d, P̄), P̄ = Φ(d)⁻¹ Pˢ_{k+1} Φ(d)⁻ᵀ (``right_jacobian_inv``).
Conditioning ε_k on ε' (the RTS step in these coordinates):

    G_k = P_k F_kᵀ P_{k+1|k}⁻¹,     δ = G_k d,     P̃ = P_k + G_k (P̄ − P_{k+1|k}) G_kᵀ,

i.e. ε_k ~ N(δ, P̃) in the tangent at μ_k. Re-centring this concentrated Gaussian at its mean, exactly as the
update does (eq:up_mu, eq:up_P; Bourmaud, Mégret, Arnaudon, Giremus, "Continuous-discrete extended Kalman
filter on matrix Lie groups using concentrated Gaussian distributions", J. Math. Imaging Vis. 51, 2015):
X_k = μ_k·exp(δ + ζ) ≈ μ_k·exp(δ)·exp(Φ(δ)ζ), hence

    μˢ_k = μ_k·exp(δ)   (generated ``retract``),     Pˢ_k = Φ(δ) P̃ Φ(δ)ᵀ   (``right_jacobian``).

The recursion starts at the last step with μˢ = μ, Pˢ = P. For the Euclidean models (CV, CTRV) ``between``
is the difference (CTRV's heading wrapped), ``retract`` the sum and Φ = I: the textbook (extended) RTS
smoother. A missed detection (NaN row) has μ_k = μ_{k|k-1}, P_k = P_{k|k-1} and needs nothing special.
Without the two transports (Φ(d)⁻¹, Φ(δ)) the step is the "tangent RTS" of the issue; they change Pˢ by
O(|d|, |δ|) and make the smoothed covariance consistent (NEES) when the corrections are large.

Where it is computed
--------------------
The backward step is one straight-line kernel emitted into every model module from its definition
(``smooth_step``, ``derive/codegen/smooth_step.py``; no model is known here): F, Φ(d)⁻¹ and Φ(δ) are symbolic
(their structural zeros never reach the code; Φ = I of a Euclidean model disappears), the covariances stay packed
and every symmetric product is formed on its upper triangle, and G = P_k F_kᵀ P_{k+1|k}⁻¹ is computed without an
inverse: with the square-root-free LDLᵀ factorisation P_{k+1|k} = L Δ Lᵀ (L unit lower triangular), each row g of G
solves L y = c, Lᵀ g = Δ⁻¹ y, c the row of C = P_k F_kᵀ (a pivot below 1e-300, impossible for a positive
definite P_{k+1|k}, is replaced by 1e-300 rather than divided by). ``smooth_one`` / ``smooth_batch`` call it once per step;
``smooth_batch_soa`` runs it with trajectories in the SIMD lanes. The forward pass that keeps the predicted and
posterior states is ``run_batch_store_<measurement>``: the filter's fused step writing the prediction it holds in
registers (``step_store_<measurement>``), and its SIMD version ``run_batch_store_soa_<measurement>`` (the states
kept in blocks of 64 trajectories, ``ForwardPass.blocks``, which ``smooth_batch_soa`` reads). The SIMD kernels run
from ``lgekf.core.rts.SOA_SMOOTH_MIN_BATCH`` trajectories on (``filter_batch``), never for :func:`smooth_segments`. Entry points: ``filter_batch(..., smooth=True)``, a filter
class's ``smooth()`` after a run with ``record=True``, :func:`smooth_tracks` (the files of ``lgekf track``).
"""

from __future__ import annotations

import numpy as np

from ..core.covariance import pack
from ..core.registry import get_model
from ..core.rts import ForwardPass, forward_store, smooth_stored

__all__ = ["smooth_segments", "ForwardPass", "forward_store", "smooth_stored"]


def smooth_segments(model: str, measurement: str, t, zm, first, lengths, x0, P0, accel_std, meas_std,
                    max_cells: int = 1 << 20) -> tuple[np.ndarray, np.ndarray]:
    """Filter and RTS-smooth segments of rows of a measurement table.

    Parameters
    ----------
    model, measurement : str
        Registry model and measurement model.
    t : ndarray, (N,)
        Times.
    zm : ndarray, (N, m)
        Measurements (NaN row: missed detection).
    first, lengths : ndarray, (S,)
        Segment i is rows first[i] .. first[i] + lengths[i] - 1, predicted from (x0[i], P0[i]) at time
        t[first[i] - 1].
    x0 : ndarray, (S, n)
        Physical initial states.
    P0 : ndarray, (S, n, n)
        Initial covariances in the filter's coordinates.
    accel_std, meas_std : array_like
        Process and measurement noise stds.
    max_cells : int
        Segments are padded into batches of at most about this many steps.

    Returns
    -------
    x : ndarray, (N, n)
        Smoothed physical states on the segments' rows (NaN elsewhere).
    p : ndarray, (N, n(n+1)/2)
        Smoothed packed covariances on those rows (NaN elsewhere).
    """
    spec = get_model(model)
    N = len(t)
    x_out = np.full((N, spec.n), np.nan)
    p_out = np.full((N, spec.n_packed), np.nan)
    first = np.asarray(first, dtype=np.int64)
    lengths = np.asarray(lengths, dtype=np.int64)
    q = np.asarray(accel_std, dtype=float)
    r = np.asarray(meas_std, dtype=float).reshape(-1)
    p0 = pack(np.asarray(P0, dtype=float))
    order = np.argsort(lengths, kind="stable")
    order = order[lengths[order] > 0]
    i = 0
    m = zm.shape[1]
    while i < len(order):
        lo = int(lengths[order[i]])
        j = i
        while j < len(order) and lengths[order[j]] <= max(int(lo * 1.25), lo + 4):
            j += 1
        j = min(j, i + max(1, max_cells // max(int(lengths[order[j - 1]]), 1)))
        objs = order[i:j]
        K = int(lengths[objs].max())
        B = len(objs)
        zb = np.full((B, K, m), np.nan)
        dts = np.ones((B, K))
        for bi, o in enumerate(objs):
            a, L = int(first[o]), int(lengths[o])
            zb[bi, :L] = zm[a:a + L]
            dts[bi, :L] = t[a:a + L] - t[a - 1:a + L - 1]
        fp = forward_store(spec, measurement, zb, dts, np.ascontiguousarray(x0[objs]), np.ascontiguousarray(p0[objs]), q, r,
                           simd=False)
        fp.lengths = np.ascontiguousarray(lengths[objs])
        xs, _, ps = smooth_stored(spec, fp)  # scalar pass (simd=False): no SIMD compile (10-90 s a model) for a file
        for bi, o in enumerate(objs):
            a, L = int(first[o]), int(lengths[o])
            x_out[a:a + L] = xs[bi, :L]
            p_out[a:a + L] = ps[bi, :L]
        i = j
    return x_out, p_out
