"""The generic emitter: any motion-model definition × every measurement that fits it -> one numba module.

Nothing here knows a model by name or by dimension: n, the internal layout, the noise inputs, the
periodic (angle) coordinates and the measurements all come from the definitions
(``derive.models``, ``derive.measurements``); the filter algebra from ``derive.algebra``.

Kernels of a model module (``s`` the internal state, ``p`` the packed covariance, upper triangle
row-major, in the tangent coordinates ε of X = μ·exp(ε)):

* conversions: ``state_from_physical``, ``state_to_physical``, ``physical_into``, ``group_mean``,
  ``common_to_state``, ``common_jacobian`` (``common_to_states`` / ``common_jacobians`` over rows),
  ``world_velocity``, ``world_velocity_into``, ``world_velocities``, ``row_speeds`` (|world velocity| of
  given rows), ``tangent_error``;
* the paper's quantities: ``motion_omega`` (Ω), ``calC`` (𝒞), ``transition`` (F), ``process_noise`` (Q),
  ``calH_<meas>`` (ℋ);
* the fused steps: ``predict`` and ``update_<meas>`` (CSE over each whole step), ``step_<meas>`` (both in one
  kernel, what the loops call; derive/codegen/fused.py), safeguards
  ``limit_angle_variance``, ``covariance_is_pd``, ``repair_pd``;
* loops: ``run_one_<meas>`` / ``run_segments_<meas>`` (segments of rows) / ``run_one_from_<meas>`` /
  ``run_segments_from_<meas>`` (the same from internal states, which they leave at the last row's posterior: a long
  object in windows) / ``run_segments_noise_from_<meas>`` (with noise stds per segment: the divergence monitor's
  reruns) / ``states_from_physical`` (internal states of many rows) / ``run_batch_<meas>`` (prange over trajectories; a NaN measurement row is a
  missed detection: predict only), ``propagate`` / ``simulate_batch`` / ``propagate_rows`` /
  ``propagate_positions`` (the exact motion),
  ``measure_<meas>`` / ``measure_batch_<meas>`` (simulated measurements Z = h(X)·exp(m));
* group operations: ``retract`` (μ·exp ε), ``between`` (log(μ_s⁻¹μ_t)), ``right_jacobian`` / ``right_jacobian_inv``
  of the whole group (smoothing and mixing on the group);
* bank loops for multi-target tracking (``derive/codegen/bank.py``): ``innovation_into_<meas>``,
  ``innovation_bank_<meas>``, ``calH_bank_<meas>``, ``predict_bank``, ``retract_bank``, ``right_jacobian_bank``.
* estimators (``derive.codegen.estimators``): ``innovation_logdet_<meas>``, ``run_one_store_<meas>`` /
  ``run_batch_store_<meas>``, ``loglik_batch_<meas>``, ``smooth_one`` / ``smooth_batch`` (RTS on the group).
"""

from __future__ import annotations

import sympy as sp

from ..algebra import LEGEND, _changed, lg_predict, lg_update, packed_index, sym_cov, symbolize
from ..lie.groups import SE2
from ..models.base import COMMON
from .bank import bank_measurement_kernels, bank_model_kernels
from .monitor import measurement_monitor_kernels, model_monitor_kernels
from .estimators import estimator_kernels
from .blocks import arg_list, cov_outputs, mat_inputs, matrix_kernel, vec_inputs, vector_kernel
from .printer import Kernel

__all__ = ["se2_kernels", "model_kernels", "registry_entry", "PD_TOL"]


# --------------------------------------------------------------------------- SE(2) building blocks
def se2_kernels():
    """hat, vee, exp, log, inverse, Ad, ad, Φ and Φ⁻¹ of SE(2) (paper, Sec. "The SE(2) group")."""
    xs = sp.symbols("x y theta", real=True)
    xin = vec_inputs("xi", xs)
    T, Tin = mat_inputs("T", 3, 3, "T")
    th = sp.Symbol("theta", real=True)
    return [
        matrix_kernel("se2_hat", "[x, y, θ]^∧ (paper, hat_SE(2)).", ["xi"], xin, SE2.hat(xs)),
        vector_kernel("se2_vee", "[M]^∨ = (M[0, 2], M[1, 2], M[1, 0]).", ["T"], Tin, SE2.vee(T)),
        matrix_kernel("se2_exp", "exp_SE(2)([x, y, θ]^∧) (paper, exp_SE(2)); translation V(θ)[x, y], Taylor-safe at θ = 0.",
                      ["xi"], xin, SE2.exp(xs)),
        Kernel(
            name="se2_log",
            doc="[log_SE(2)(T)]^∨ = [V(θ)^-1 t, θ], θ = atan2(T[1, 0], T[0, 0]) ∈ (-π, π] (paper, log_SE(2)).",
            params=["T"], inputs=Tin, stages=[[(th, sp.atan2(T[1, 0], T[0, 0]))]],
            outputs=[(f"out[{i}]", e) for i, e in enumerate(list(SE2.V_inv(th) * T[:2, 2]) + [th])],
            prologue=["out = np.empty(3)"], ret="out",
        ),
        matrix_kernel("se2_inverse", "T^-1 = [[R^T, -R^T t], [0, 1]].", ["T"], Tin, SE2.inverse(T)),
        matrix_kernel("se2_adjoint", "Ad_SE(2)(T) = [[R, J t], [0, 1]], J = [[0, 1], [-1, 0]] (paper, Ad_SE(2)).", ["T"], Tin, SE2.Ad(T)),
        matrix_kernel("se2_ad", "ad_SE(2)([x, y, θ]) = [[-θ J, J v], [0, 0]] (paper's ad_SE(2), corner corrected to 0).",
                      ["xi"], xin, SE2.ad(xs)),
        matrix_kernel("right_jacobian", "Φ_SE(2)(ξ) = Σ (-1)^m/(m+1)! ad(ξ)^m, closed form (paper, Φ_G); log(exp(-ξ) exp(ξ + δ)) ≈ Φ δ.",
                      ["xi"], xin, SE2.right_jacobian(xs)),
        matrix_kernel("right_jacobian_inv", "Φ_SE(2)(ξ)^-1, closed form.", ["xi"], xin, SE2.right_jacobian_inv(xs)),
    ]


# --------------------------------------------------------------------------- safeguards
PD_TOL = 1e-13  # LDLᵀ pivot / largest variance below which a covariance counts as lost to rounding
# the same test inlined into the fused steps runs under their FMA contraction, whose rounding differs from the IEEE
# test's; it asks for 100× larger pivots, so that it accepts no covariance that covariance_is_pd rejects (measured on
# tests/core/test_covariance_health.py; derive/codegen/fused.py)
PD_TOL_FUSED = 1e-11


def pd_check_kernels(n: int):
    """``covariance_is_pd(p)`` and ``repair_pd(p)`` for a packed n×n covariance (scalar-unrolled LDLᵀ).

    At condition numbers beyond ~1e13 rounding alone can make the smallest eigenvalue of
    Φ(ν) P_J Φ(ν)ᵀ negative.  ``covariance_is_pd`` runs LDLᵀ and requires every pivot
    d_j > PD_TOL · max_i P_ii; ``repair_pd`` adds the smallest diagonal jitter (PD_TOL · max_i P_ii,
    growing ×4) that passes.  Regular steps never trigger it.
    """
    idx = packed_index(n)
    lines = ["@nb.njit(cache=True)", "def covariance_is_pd(p):",
             f'    """LDLᵀ test of the packed covariance: every pivot d_j > {PD_TOL!r} · max_i P_ii (NaN fails)."""']
    for i in range(n):
        for j in range(i, n):
            lines.append(f"    p{i}_{j} = p[{idx[(i, j)]}]")
    lines.append(f"    tol = {PD_TOL!r} * max({', '.join(f'p{j}_{j}' for j in range(n))})")
    for j in range(n):
        terms = "".join(f" - l{j}_{k} * l{j}_{k} * d{k}" for k in range(j))
        lines.append(f"    d{j} = p{j}_{j}{terms}")
        lines.append(f"    if not d{j} > tol:")
        lines.append("        return False")
        if j < n - 1:
            lines.append(f"    r{j} = 1.0 / d{j}")
        for i in range(j + 1, n):
            terms = "".join(f" - l{i}_{k} * l{j}_{k} * d{k}" for k in range(j))
            lines.append(f"    l{i}_{j} = (p{j}_{i}{terms}) * r{j}")
    lines.append("    return True")
    diag = [idx[(j, j)] for j in range(n)]
    repair = f'''
@nb.njit(cache=True)
def repair_pd(p):
    """Add the smallest diagonal jitter ({PD_TOL!r} · max_i P_ii, growing ×4) that makes covariance_is_pd pass."""
    scale = 0.0
    for i in {tuple(diag)!r}:
        scale = max(scale, abs(p[i]))
    delta = {PD_TOL!r} * scale
    for _ in range(60):
        if covariance_is_pd(p):
            return
        for i in {tuple(diag)!r}:
            p[i] += delta
        delta *= 4.0
'''
    names = [f"p{i}_{j}" for i in range(n) for j in range(i, n)]
    fused = [ln.replace(f"{PD_TOL!r} * max(", f"{PD_TOL_FUSED!r} * max(") for ln in lines[3 + len(names):]]
    fused = ['@nb.njit(cache=True, inline="always", error_model="numpy")',
             f"def covariance_is_pd_fused({', '.join(names)}):",
             f'    """covariance_is_pd of the entries p<i>_<j> (upper triangle, row-major) as numbers, inlined into the fused\n'
             f'    steps (derive/codegen/fused.py), with pivots > {PD_TOL_FUSED!r} · max_i P_ii."""'] + fused
    return [("covariance_is_pd", "\n".join(lines)), ("covariance_is_pd_fused", "\n".join(fused)), ("repair_pd", repair)]


def angle_limit_kernel(n: int, angles: tuple):
    """``limit_angle_variance(p)``: cap the std of the periodic tangent coordinates at π (congruence scaling).

    A concentrated Gaussian is only meaningful where exp is bijective, |ε_θ| < π (paper, Sec. II-B); an
    angle std beyond π says "heading unknown", which the CGD cannot express.  With position-only
    measurements the heading and the direction of the body-frame velocity are observable only as a sum,
    so that variance can otherwise grow without bound.  P ← D P D, D = diag(1, ..., π/σ_θ, ...), keeps P
    symmetric positive definite.  Inactive while σ_θ ≤ π, i.e. in every regular step.
    """
    idx = packed_index(n)
    lines = ["@nb.njit(cache=True)", "def limit_angle_variance(p):",
             '    """Cap the std of the angle coordinates ' + str(list(angles)) + ' of P at π by congruence scaling (see derive/codegen/emitter.py)."""']
    for a in angles:
        d = idx[(a, a)]
        lines.append(f"    if p[{d}] > math.pi * math.pi:")
        lines.append(f"        f = math.pi / math.sqrt(p[{d}])")
        for j in range(n):
            if j != a:
                lines.append(f"        p[{idx[(a, j)]}] *= f")
        lines.append(f"        p[{d}] = math.pi * math.pi")
    if not angles:
        lines.append("    return")
    return ("limit_angle_variance", "\n".join(lines))


# --------------------------------------------------------------------------- loop templates
# the loop over segments of rows (each segment's steps dts from t, then one call per segment): one text for
# run_segments_<meas>, run_segments_from_<meas> and run_segments_noise_from_<meas>, formatted with the call
SEGMENT_LOOP = '''    longest = 0
    for i in range(first.shape[0]):
        longest = max(longest, lengths[i])
    dts = np.empty(longest)
    for i in range(first.shape[0]):
        a = first[i]
        b = a + lengths[i]
        for k in range(a, b):
            dts[k - a] = t[k] - t[k - 1]
        {call}
'''


def _segments(call: str) -> str:
    """SEGMENT_LOOP with ``call`` (a template line of the kernel it runs per segment) as its body."""
    return SEGMENT_LOOP.replace("{call}", call)


# the filter loop over the rows of one trajectory from (s, p): one text for run_one_<meas> and run_one_from_<meas>,
# so that both compile to the same numbers (a long object filtered in windows = in one call)
FILTER_LOOP = '''    K = z.shape[0]
    keep_p = out_p.shape[0] == K
    for k in range(K):
        if {nan_test}:
            predict(s, p, dts[k], {qargs})
            out_nis[k] = np.nan
        else:
            nis = step_try_{meas}(s, p, dts[k], {qargs}, {zargs}, {rargs})
            if nis < 0.0:  # rare: the cheap covariance failed the LDLᵀ test; Joseph form from the prediction
                nis = update_{meas}(s, p, {zargs}, {rargs})
            out_nis[k] = nis
        physical_into(s, out_x[k])
        if keep_p:
            for i in range({npk}):
                out_p[k, i] = p[i]
'''

BATCH_TEMPLATE = '''
@nb.njit(cache=True, nogil=True)  # nogil: the process-noise search (lgekf.apps.search) runs filters in threads
def run_one_{meas}(z, dts, x0, p0, q, r, out_x, out_p, out_nis):
    """Filter one trajectory with {meas} measurements: z (K, {m}), dts (K,), x0 ({n},), p0 ({npk},).

    A row of z containing NaN is a missed detection: the step predicts only (its NIS is NaN).
    """
    s = state_from_physical(x0)
    p = p0.copy()
{loop}

@nb.njit(cache=True, nogil=True)
def run_segments_{meas}(z, t, first, lengths, x0, p0, q, r, out_x, out_p, out_nis):
    """``run_one_{meas}`` on segments of rows, one after the other (no Python per segment).

    Segment i is rows first[i] .. first[i] + lengths[i] - 1 (first[i] >= 1) of z (N, {m}) and t (N,), filtered
    from x0[i] ({n},), p0[i] ({npk},) at time t[first[i] - 1]; its outputs go to the same rows of out_x (N, {n}),
    out_p (N, {npk}) and out_nis (N,). The numbers of ``run_one_{meas}`` called per segment with
    dts = t[a:b] - t[a - 1:b - 1].
    """
{segments}

@nb.njit(cache=True, nogil=True)
def run_one_from_{meas}(z, dts, s0, p0, q, r, out_x, out_p, out_nis):
    """``run_one_{meas}`` from the internal state s0 ({ni},) (the layout of ``state_from_physical``) and p0 ({npk},),
    which on return hold the posterior of the last row: a later call from them continues exactly (the numbers
    of one call over both rows). ``lgekf track`` filters a long object in windows of rows with it.
    """
    s = s0.copy()
    p = p0.copy()
{loop}    s0[:] = s
    p0[:] = p


@nb.njit(cache=True, nogil=True)
def run_segments_from_{meas}(z, t, first, lengths, s0, p0, q, r, out_x, out_p, out_nis):
    """``run_segments_{meas}`` from internal states s0 (S, {ni}) and p0 (S, {npk}) (``run_one_from_{meas}``): on
    return s0[i], p0[i] hold the posterior of segment i's last row (unchanged for an empty segment).
    """
{segments_from}

@nb.njit(cache=True, parallel=True)
def run_batch_{meas}(z, dts, x0, p0, q, r, out_x, out_p, out_nis):
    """Filter B trajectories in parallel (numba prange), predict then update at every step.

    z (B, K, {m}) {meas} measurements (a NaN row = missed detection); dts (B, K) step lengths; x0 (B, {n})
    physical initial states; p0 (B, {npk}) packed initial covariances; q ({nq},) process-noise stds;
    r ({nr},) measurement-noise stds. Writes the posterior physical states into out_x (B, K, {n}), the
    packed covariances into out_p (B, K, {npk}) when out_p.shape[1] == K (pass (B, 0, {npk}) to skip),
    and the NIS into out_nis (B, K).
    """
    for b in nb.prange(z.shape[0]):
        run_one_{meas}(z[b], dts[b], x0[b], p0[b], q, r, out_x[b], out_p[b], out_nis[b])
'''

SEGMENT_NOISE_TEMPLATE = '''
@nb.njit(cache=True, nogil=True)
def run_segments_noise_from_{meas}(z, t, first, lengths, s0, p0, q, r, out_x, out_p, out_nis):
    """``run_segments_from_{meas}`` with noise stds of each segment's own: q (S, {nq}), r (S, {nr}) (the divergence
    recovery's reruns, each object's noise inflated by its own factor). On return s0[i], p0[i] hold the posterior
    of segment i's last row, from which a later call continues exactly. The numbers of ``run_one_from_{meas}``
    called per segment i with q[i], r[i]."""
{segments_noise}'''

BATCH_TEMPLATE = (BATCH_TEMPLATE
                  .replace("{segments}", _segments("run_one_{meas}(z[a:b], dts[:b - a], x0[i], p0[i], q, r, out_x[a:b], out_p[a:b], out_nis[a:b])"))
                  .replace("{segments_from}",
                           _segments("run_one_from_{meas}(z[a:b], dts[:b - a], s0[i], p0[i], q, r, out_x[a:b], out_p[a:b], out_nis[a:b])")))
SEGMENT_NOISE_TEMPLATE = SEGMENT_NOISE_TEMPLATE.replace(
    "{segments_noise}", _segments("run_one_from_{meas}(z[a:b], dts[:b - a], s0[i], p0[i], q[i], r[i], out_x[a:b], out_p[a:b], out_nis[a:b])"))

SIMULATE_TEMPLATE = '''
@nb.njit(cache=True, parallel=True)
def simulate_batch(x0, dts, noise, out_x):
    """Simulate the motion model X_{{k+1}} = X_k exp([Ω(X_k) + G n_k]^) for B trajectories (prange).

    x0 (B, {n}) physical initial states; dts (B, K) step lengths; noise (B, K, {nq}) samples of n (already
    scaled by their stds); out_x (B, K + 1, {n}) receives the physical states, out_x[:, 0] = x0.
    """
    B = x0.shape[0]
    K = dts.shape[1]
    for b in nb.prange(B):
        s = state_from_physical(x0[b])
        physical_into(s, out_x[b, 0])
        for k in range(K):
            propagate(s, dts[b, k], {nargs})
            physical_into(s, out_x[b, k + 1])


@nb.njit(cache=True, nogil=True)
def states_from_physical(x, out):
    """state_from_physical of every row: physical states x (N, {n}) into internal states out (N, {ni})."""
    for i in range(x.shape[0]):
        state_from_physical_into(x[i], out[i])


@nb.njit(cache=True, nogil=True)  # serial and nogil: threads may run it at once (lgekf.apps.search)
def propagate_rows(x, dts, out_x):
    """The noise-free exact motion of each row: out_x[i] = X_i exp([Ω(X_i)]^) over dts[i] (simulate_batch with
    zero noise, one step per row); x (N, {n}) and out_x (N, {n}) physical states, dts (N,)."""
    s = np.empty({ni})
    for i in range(x.shape[0]):
        state_from_physical_into(x[i], s)
        propagate(s, dts[i], {zeros})
        physical_into(s, out_x[i])


@nb.njit(cache=True, nogil=True)  # serial and nogil: threads may run it at once (lgekf.apps.search)
def propagate_positions(x, dts, out_xy):
    """The position (the first two physical coordinates) of ``propagate_rows``'s rows, bit for bit, into
    out_xy (N, 2): the other coordinates are not converted (the noise search's one-step errors)."""
    s = np.empty({ni})
    for i in range(x.shape[0]):
        state_from_physical_into(x[i], s)
        propagate(s, dts[i], {zeros})
        position_into(s, out_xy[i])
'''

MEASURE_TEMPLATE = '''
@nb.njit(cache=True)
def measure_batch_{meas}(X, noise, out):
    """Simulated {meas} measurements z = vector(h(X)·exp(m)) of every physical state X (N, {n}),
    noise samples m (N, {m}) (already scaled), into out (N, {m})."""
    for i in range(X.shape[0]):
        s = state_from_physical(X[i])
        z = measure_{meas}(s, {margs})
        for j in range({m}):
            out[i, j] = z[j]
'''

COMMON_BATCH_TEMPLATE = '''
@nb.njit(cache=True, nogil=True)
def common_to_states(c, out):
    """common_to_state of every row of c (B, 6) into out (B, n) (the two-point initialisation of many objects)."""
    for b in range(c.shape[0]):
        x = common_to_state(c[b])
        for i in range(out.shape[1]):
            out[b, i] = x[i]


@nb.njit(cache=True, nogil=True)
def common_jacobians(c, out):
    """common_jacobian of every row of c (B, 6) into out (B, n, 6)."""
    for b in range(c.shape[0]):
        J = common_jacobian(c[b])
        for i in range(out.shape[1]):
            for j in range(out.shape[2]):
                out[b, i, j] = J[i, j]
'''

WORLD_VELOCITY_TEMPLATE = '''
@nb.njit(cache=True, nogil=True)
def world_velocities(X, out):
    """world_velocity of every row of X (N, n) into out (N, 2)."""
    for i in range(X.shape[0]):
        world_velocity_into(X[i], out[i])


@nb.njit(cache=True, nogil=True)
def row_speeds(X, rows, out):
    """Speed |world_velocity| of the rows X[rows[i]] of physical states X (N, n) into out (R,): no per-row
    allocation nor gathered copy of X (the divergence monitor's speeds)."""
    v = np.empty(2)
    for i in range(rows.shape[0]):
        world_velocity_into(X[rows[i]], v)
        out[i] = math.hypot(v[0], v[1])
'''


# --------------------------------------------------------------------------- one model
def _measurement_kernels(model, meas, P, pin, sin_, predict_parts=None):
    m = meas.m
    z = meas.z_symbols
    noise = meas.noise_symbols
    stages, outs, Pu, nis, transported = lg_update(model, meas, P, z, noise)
    z_params = [f"z_{nm}" for nm in meas.z_names]
    r_params = list(meas.noise_names)
    doc = (
        f"Fused update with a {meas.name} measurement ({meas.description}), in place.\n"
        f"z = ({', '.join(z_params)}), noise stds ({', '.join(r_params)}); Z = h(μ)·exp(m), m ~ N(0, R) in the tangent of G'.\n"
        "K = P ℋ^T (ℋ P ℋ^T + R)^-1, ν = K [log_G'(h(μ)^-1 Z)]^∨ (eq:K), μ ← μ exp(ν) (eq:up_mu),\n"
        "P ← Φ(ν) [(I - Kℋ) P (I - Kℋ)^T + K R K^T] Φ(ν)^T: eq:up_P in Joseph form. Returns the NIS e^T S^-1 e.\n"
    )
    if model.periodic_tangent():
        doc += ("Safeguard: if a rotation angle of ν exceeds π the gain is damped, K → αK, α = π/|angle|\n"
                "(derive.lie.special.gain_damping; α = 1 in every regular step).\n")
    if transported:
        doc += "If rounding leaves P not positive definite (condition numbers ≳ 1e15) a rounding-level jitter restores it (repair_pd).\n"
    doc += LEGEND
    outputs = cov_outputs(Pu) + [(f"s[{i}]", e) for i, e in outs.items()]
    upd = Kernel(
        name=f"update_{meas.name}", doc=doc, params=["s", "p", *z_params, *r_params],
        inputs=sin_ + pin + list(zip(z, z_params)) + list(zip(noise, r_params)),
        stages=stages, outputs=outputs, ret="nis",
        epilogue=["if not covariance_is_pd(p):", "    repair_pd(p)"] if transported else [],
        fastmath=True,
    )
    sub = model.to_internal
    calH = matrix_kernel(
        f"calH_{meas.name}", f"ℋ = ∂[log_G'(h(μ)^-1 h(μ exp ε))]^∨/∂ε at ε = 0 (eq:calH, eq:calH_model) for {meas.name} measurements.",
        ["s"], sin_, model.calH_for(meas).applyfunc(sub),
    )
    ms = sp.symbols(f"m0:{m}", real=True)
    Z = meas.h(model, model.mean()) * meas.group.exp(list(ms))
    measure = vector_kernel(
        f"measure_{meas.name}", f"Simulated {meas.name} measurement vector(h(X)·exp(m)) of the state s for a noise sample m.",
        ["s", *[f"m{i}" for i in range(m)]], sin_ + [(mi, f"m{i}") for i, mi in enumerate(ms)],
        [sub(e) for e in meas.vector(Z)],
    )
    nan_test = " or ".join(f"np.isnan(z[k, {i}])" for i in range(m))
    fmt = dict(meas=meas.name, m=m, n=model.n, npk=model.n * (model.n + 1) // 2, ni=len(model.internal), nq=len(model.noise_names),
               nr=len(meas.noise_names), qargs=arg_list("q", len(model.noise_names)), zargs=arg_list("z[k]", m).replace("z[k][", "z[k, "),
               rargs=arg_list("r", len(meas.noise_names)), nan_test=nan_test)
    batch = (f"run_one_{meas.name}", BATCH_TEMPLATE.format(loop=FILTER_LOOP.format(**fmt), **fmt))
    meas_loop = (f"measure_batch_{meas.name}", MEASURE_TEMPLATE.format(meas=meas.name, n=model.n, m=m, margs=arg_list("noise[i]", m).replace("noise[i][", "noise[i, ")))
    kernels = [calH, upd, measure, batch, meas_loop, *bank_measurement_kernels(model, meas, sin_)]
    kernels.append((f"run_segments_noise_from_{meas.name}", SEGMENT_NOISE_TEMPLATE.format(
        meas=meas.name, nq=len(model.noise_names), nr=len(meas.noise_names))))
    kernels.extend(measurement_monitor_kernels(meas.name))  # the divergence monitor: rerun_<meas>, recover_<meas> (codegen/monitor.py)
    if predict_parts is not None:  # the fused step the loops call (derive/codegen/fused.py)
        from .fused import fused_step_kernel, step_wrapper

        from .soa import soa_measurement_kernels

        step = fused_step_kernel(model, meas, P, pin, sin_, predict_parts, sp.Symbol("dt", positive=True))
        kernels.insert(2, step)
        kernels.insert(3, step_wrapper(model, meas))
        kernels.extend(soa_measurement_kernels(model, meas, step))  # SIMD across trajectories (derive/codegen/soa.py)
    return kernels


def model_kernels(model, measurements: dict) -> list:
    """Every kernel of one motion model (see the module docstring), for the measurements that fit it."""
    n = model.n
    sub = model.to_internal
    dt = sp.Symbol("dt", positive=True)
    sig = model.noise_symbols
    sin_ = vec_inputs("s", model.internal)
    phys_in = vec_inputs("xp", model.physical)
    P, pin = sym_cov(n)
    layout = "[" + ", ".join(str(v) for v in model.internal) + "]"
    phys = "[" + ", ".join(model.physical_names) + "]"
    ks = [
        vector_kernel("state_from_physical", f"Internal state {layout} from the physical {phys}.", ["xp"], phys_in,
                      model.internal_from_physical()),
        vector_kernel("state_to_physical", f"Physical {phys} (angles in (-π, π]) from the internal state.", ["s"], sin_,
                      model.physical_from_internal()),
        Kernel(name="physical_into", doc=f"Physical {phys} from the internal state, written into ``out`` (no allocation).",
               params=["s", "out"], inputs=sin_, outputs=[(f"out[{i}]", e) for i, e in enumerate(model.physical_from_internal())]),
        matrix_kernel("group_mean", "The mean μ as a group matrix (block-diagonal for a product group).", ["s"], sin_,
                      model.mean().applyfunc(sub)),
        vector_kernel("motion_omega", "Ω(μ), the tangent increment of one step (eq:motionG).", ["s", "dt"], sin_ + [(dt, "dt")],
                      model.Omega.applyfunc(sub)),
        vector_kernel("motion", "The internal state after one noise-free step, μ exp(Ω(μ)) (eq:pred_mu); x' = f(x) for a Euclidean model.",
                      ["s", "dt"], sin_ + [(dt, "dt")],
                      [sub(e) for e in model.internal_of(model.mean().applyfunc(sub) * model.group.exp(model.Omega.applyfunc(sub)))]),
        matrix_kernel("calC", "𝒞 = ∂Ω(μ exp ε)/∂ε at ε = 0 (eq:C, eq:calCFinal).", ["s", "dt"], sin_ + [(dt, "dt")],
                      model.calC.applyfunc(sub)),
        matrix_kernel("transition", "F = Ad_G(exp(-Ω)) + Φ_G(Ω) 𝒞 (paper, below eq:pred_cov).", ["s", "dt"], sin_ + [(dt, "dt")],
                      model.F.applyfunc(sub)),
        matrix_kernel("process_noise", f"Q = G diag(σ²) G^T: the noise n ({', '.join(model.noise_names)}) of eq:motionG in the tangent.",
                      ["s", "dt", *model.noise_names], sin_ + [(dt, "dt")] + list(zip(sig, model.noise_names)),
                      model.Q.applyfunc(sub)),
    ]
    # ---- fused prediction
    stages, outs, Pn = lg_predict(model, P)
    periodic = model.periodic_tangent()
    ks.append(angle_limit_kernel(n, periodic))
    ks.append(Kernel(
        name="predict",
        doc=("Fused LG-EKF prediction, in place: μ ← μ exp(Ω(μ)) (eq:pred_mu),\n"
             "P ← F P F^T + Φ(Ω) Q Φ(Ω)^T (eq:pred_cov), Q = G diag(σ²) G^T.\n"
             f"s: internal state {layout}, p: packed covariance ({n * (n + 1) // 2}), dt > 0.\n"
             + ("Then the std of the tangent angles is capped at π (limit_angle_variance; inactive while ≤ π).\n" if periodic else "")
             + LEGEND),
        params=["s", "p", "dt", *model.noise_names],
        inputs=sin_ + pin + [(dt, "dt")] + list(zip(sig, model.noise_names)),
        stages=stages, outputs=cov_outputs(Pn) + [(f"s[{i}]", e) for i, e in outs.items()],
        epilogue=["limit_angle_variance(p)"] if periodic else [], fastmath=True,
    ))
    for meas in measurements.values():
        ks.extend(_measurement_kernels(model, meas, P, pin, sin_, (stages, outs, Pn)))
    ks.extend(pd_check_kernels(n))
    from .soa import soa_model_kernels

    ks.extend(soa_model_kernels(model, ks[2]))  # covariance_is_pd_lane, physical_lane (ks[2] = physical_into)
    # ---- exact motion for simulation
    nn = sp.symbols(f"n0:{len(model.noise_stds())}", real=True)
    new = {i: e for i, e in enumerate(model.internal_of(model.propagated(nn).applyfunc(sub)))}
    new = {i: model.to_internal(e) for i, e in new.items() if model.to_internal(e) != model.internal[i]}
    pdefs, Ps = symbolize(sp.Matrix([list(new.values())]), "xn")
    nparams = [f"n{i}" for i in range(len(nn))]
    ks.append(Kernel(
        name="propagate",
        doc="Exact motion X ← X exp([Ω(X) + G n]^∧) (eq:model) for one noise sample n, in place.",
        params=["s", "dt", *nparams], inputs=sin_ + [(dt, "dt")] + list(zip(nn, nparams)),
        stages=[pdefs], outputs=[(f"s[{i}]", Ps[0, k]) for k, i in enumerate(new)],
    ))
    ks.append(Kernel(name="position_into", doc="The position (the first two physical coordinates) of the internal state into ``out`` (2,).",
                     params=["s", "out"], inputs=sin_, outputs=[(f"out[{i}]", e) for i, e in enumerate(model.physical_from_internal()[:2])]))
    ks.append(("simulate_batch", SIMULATE_TEMPLATE.format(n=n, nq=len(nn), nargs=arg_list("noise[b, k]", len(nn)).replace("noise[b, k][", "noise[b, k, "),
                                                    zeros=", ".join(["0.0"] * len(nn)), ni=len(model.internal))))
    # ---- common coordinates
    cs = sp.symbols(f"c0:{len(COMMON)}", real=True)
    csub = dict(zip(COMMON, cs))
    cin = vec_inputs("c", cs)
    ks.append(vector_kernel("world_velocity", "World-frame velocity (2,) of a physical state x of this model.", ["x"],
                            vec_inputs("x", model.physical), model.world_velocity()))
    ks.append(Kernel(name="world_velocity_into", doc="world_velocity of a physical state x written into out (2,) (no allocation).",
                     params=["x", "out"], inputs=vec_inputs("x", model.physical),
                     outputs=[(f"out[{i}]", e) for i, e in enumerate(model.world_velocity())]))
    ks.append(("world_velocities", WORLD_VELOCITY_TEMPLATE))
    ks.append(vector_kernel("common_to_state", "The model's physical state from the common c = (x, y, θ, v_x, v_y, ω), (v_x, v_y) in the body frame.",
                            ["c"], cin, [sp.sympify(e).subs(csub, simultaneous=True) for e in model.from_common()]))
    ks.append(matrix_kernel("common_jacobian", "J = ∂(filter coordinates ε)/∂c at c: maps a covariance of c to the filter's P (P = J P_c J^T).",
                            ["c"], cin, model.common_jacobian.subs(csub, simultaneous=True)))
    ks.append(("common_to_states", COMMON_BATCH_TEMPLATE))
    ks.extend(model_monitor_kernels())  # the divergence monitor: re-initialisation, speed std, first alarm (codegen/monitor.py)
    # ---- estimation error in the filter's tangent coordinates (NEES)
    G = model.group
    true_mean = model.mean_of_common.subs(csub, simultaneous=True)
    err = G.log(G.inverse(model.mean()).applyfunc(sub) * true_mean)
    from ..lie.special import wrap

    err = sp.Matrix([wrap(e) if i in model.angles else e for i, e in enumerate(err)])
    ks.append(vector_kernel(
        "tangent_error",
        "ε = [log_G(μ^-1 X)]^∨: the error of the estimate μ (internal state s) w.r.t. a true common state c,\n"
        "in the coordinates of P (for NEES = εᵀ P^-1 ε); angle coordinates wrapped to (-π, π].",
        ["s", "c"], sin_ + cin, err.applyfunc(sub),
    ))
    ks.extend(group_operation_kernels(model))
    ks.extend(bank_model_kernels(model))
    ks.extend(estimator_kernels(model, measurements, P, pin, sin_, ks))  # likelihood, store loops, RTS smoother
    from .dispatch import common_readout_kernels

    ks.extend(common_readout_kernels(model, ks))
    return ks


def group_operation_kernels(model) -> list:
    """⊕, ⊖ and the right Jacobian of the model's whole group, for smoothing and mixing on the group.

    ``retract(s, eps)``: μ ← μ·exp([ε]^∧) in place (the update's eq:up_mu with a given ε);
    ``between(s, t)``: [log_G(μ_s^-1 μ_t)]^∨, angle coordinates of a Euclidean model wrapped to (-π, π];
    ``right_jacobian(eps)`` / ``right_jacobian_inv(eps)``: Φ_G(ε) and its inverse (block-diagonal over
    the factors; I for Rⁿ), log(exp(-ε) exp(ε + δ)) ≈ Φ_G(ε) δ.
    """
    from ..lie.special import wrap

    n = model.n
    G = model.group
    sub = model.to_internal
    sin_ = vec_inputs("s", model.internal)
    eps = sp.symbols(f"eps0:{n}", real=True)
    ein = vec_inputs("eps", eps)
    mu = model.mean().applyfunc(sub)
    new = _changed(model, model.internal_of(mu * G.exp(list(eps))))
    tsyms = [sp.Symbol(f"t_{v}", real=True) for v in model.internal]
    tin = vec_inputs("t", tsyms)
    mu_t = mu.subs(dict(zip(model.internal, tsyms)), simultaneous=True)
    d = G.log(G.inverse(mu) * mu_t)
    d = sp.Matrix([wrap(e) if i in model.angles and i not in model.periodic_tangent() else e for i, e in enumerate(d)])
    return [
        Kernel(name="retract", doc="μ ← μ·exp([ε]^∧) in place (right perturbation; the update's eq:up_mu for a given ε).",
               params=["s", "eps"], inputs=sin_ + ein, outputs=[(f"s[{i}]", e) for i, e in new.items()]),
        vector_kernel("between", "[log_G(μ_s^-1 μ_t)]^∨: the tangent ε with μ_t = μ_s·exp(ε) (s ⊖: μ_s, t: μ_t, internal states);\n"
                      "angle coordinates of a Euclidean model wrapped to (-π, π].",
                      ["s", "t"], sin_ + tin, d.applyfunc(sub)),
        matrix_kernel("right_jacobian", "Φ_G(ε) of the whole group (block-diagonal over its factors, I for Rⁿ);\n"
                      "log(exp(-ε) exp(ε + δ)) ≈ Φ_G(ε) δ.", ["eps"], ein, G.right_jacobian(list(eps))),
        matrix_kernel("right_jacobian_inv", "Φ_G(ε)^-1 of the whole group.", ["eps"], ein, G.right_jacobian_inv(list(eps))),
    ]


def registry_entry(model, measurements: dict, refused: dict) -> dict:
    """The plain-data description of a model that the runtime reads (generated/registry.py)."""
    return {
        "display_name": model.display_name,
        "description": model.description,
        "color": model.color,
        "state_names": tuple(model.physical_names),
        "internal_names": tuple(str(s) for s in model.internal),
        "noise_names": tuple(model.noise_names),
        "default_accel_std": tuple(float(v) for v in model.default_accel_std),
        "matched_noise": tuple(model.matched_noise),
        "angles": tuple(model.angles),
        "periodic_tangent": tuple(model.periodic_tangent()),
        "bounds": {int(k): float(v) for k, v in model.bounds.items()},
        "bound_reason": model.bound_reason,
        "forward_speed": tuple(model.forward_speed),
        "noise_inputs": tuple(model.noise_symbols.index(sd) for sd in model.noise_stds()),
        "measurements": tuple(measurements),
        "refused": dict(refused),
        "linear": tuple(name for name, meas in measurements.items() if model.is_linear_gaussian(meas)),
    }
