"""The kernels to generate: building blocks and fused filter steps, assembled from derive.models.

Internal state layouts (what the fused kernels read and write in place):

* se2se2: s = [x, y, cos θ, sin θ, v_x, v_y, ω, cos ω, sin ω]   (ω = atan2(sin ω, cos ω), the log
  of T_d's rotation, so equal means always predict alike)
* se2r3:  s = [x, y, cos θ, sin θ, v_x, v_y, ω]
* ctrv:   s = [x, y, ψ, v, ω]
* cv:     s = [x, y, v_x, v_y]

Carrying (cos, sin) of the angles means a step needs one sincos for the prediction (of Tω) and one
per angle of the correction ν. Covariances are packed as their upper triangle, row-major
(21 entries for n = 6); ``P`` is always in the filter's own coordinates (the tangent coordinates
ε of X = μ exp(ε) for the LG filters).
"""

from __future__ import annotations

import itertools

import sympy as sp

from . import models as M
from .codegen import Kernel
from .groups import SE2, Rn
from .special import gain_damping, wrap

__all__ = ["MODULES", "packed_index", "LG_LAYOUTS"]


# --------------------------------------------------------------------------- helpers
def packed_index(n: int):
    """{(i, j): k} for the packed upper triangle (row-major) of an n×n symmetric matrix."""
    idx, k = {}, 0
    for i in range(n):
        for j in range(i, n):
            idx[(i, j)] = idx[(j, i)] = k
            k += 1
    return idx


def sym_cov(n: int, name="p"):
    """Symmetric symbolic covariance and its packed-input list."""
    idx = packed_index(n)
    syms = {}
    for i in range(n):
        for j in range(i, n):
            syms[(i, j)] = sp.Symbol(f"{name}{i}{j}", real=True)
    P = sp.Matrix(n, n, lambda i, j: syms[(min(i, j), max(i, j))])
    inputs = [(syms[(i, j)], f"p[{idx[(i, j)]}]") for i in range(n) for j in range(i, n)]
    return P, inputs


def symbolize(Mx: sp.Matrix, prefix: str, only_upper=False):
    """Replace every non-trivial entry of Mx by a fresh symbol; returns (definitions, symbolic matrix)."""
    defs, out = [], sp.zeros(*Mx.shape)
    for i, j in itertools.product(range(Mx.shape[0]), range(Mx.shape[1])):
        if only_upper and j < i:
            continue
        e = sp.sympify(Mx[i, j])
        if e.is_Number or isinstance(e, sp.Symbol):
            out[i, j] = e
        else:
            s = sp.Symbol(f"{prefix}{i}{j}", real=True)
            defs.append((s, e))
            out[i, j] = s
        if only_upper:
            out[j, i] = out[i, j]
    return defs, out


def matrix_outputs(Mx: sp.Matrix, name="out"):
    return [(f"{name}[{i}, {j}]", Mx[i, j]) for i in range(Mx.shape[0]) for j in range(Mx.shape[1])]


def new_matrix_kernel(name, doc, params, inputs, Mx, subs=None, stages=None):
    return Kernel(
        name=name,
        doc=doc,
        params=params,
        inputs=inputs,
        outputs=matrix_outputs(Mx),
        prologue=[f"out = np.zeros(({Mx.shape[0]}, {Mx.shape[1]}))"],
        ret="out",
        substitutions=subs or {},
        skip_zero_outputs=True,
        stages=stages or [],
    )


def new_vector_kernel(name, doc, params, inputs, v, subs=None, stages=None):
    v = list(v)
    return Kernel(
        name=name,
        doc=doc,
        params=params,
        inputs=inputs,
        outputs=[(f"out[{i}]", e) for i, e in enumerate(v)],
        prologue=[f"out = np.zeros({len(v)})"],
        ret="out",
        substitutions=subs or {},
        skip_zero_outputs=True,
        stages=stages or [],
    )


def physical_into_kernel(inputs, v, doc):
    """In-place variant of state_to_physical for loops: writes into ``out`` (no allocation)."""
    return Kernel(
        name="physical_into",
        doc=doc + " Written into ``out`` (no allocation).",
        params=["s", "out"],
        inputs=inputs,
        outputs=[(f"out[{i}]", e) for i, e in enumerate(v)],
    )


BATCH_TEMPLATE = '''
@nb.njit(cache=True)
def run_one(z, dts, x0, p0, q, r, out_x, out_p, out_nis):
    """Filter one trajectory: z (K, 2), dts (K,), x0 ({n},), p0 ({npk},); see run_batch."""
    s = state_from_physical(x0)
    p = p0.copy()
    K = z.shape[0]
    keep_p = out_p.shape[0] == K
    for k in range(K):
        predict(s, p, dts[k], {qargs})
        out_nis[k] = update(s, p, z[k, 0], z[k, 1], r)
        physical_into(s, out_x[k])
        if keep_p:
            for i in range({npk}):
                out_p[k, i] = p[i]


@nb.njit(cache=True, parallel=True)
def run_batch(z, dts, x0, p0, q, r, out_x, out_p, out_nis):
    """Filter B trajectories in parallel (numba prange), predict then update at every step.

    z (B, K, 2) positions; dts (B, K) step lengths; x0 (B, {n}) physical initial states; p0 (B, {npk})
    packed initial covariances; q ({nq},) noise stds; r the measurement std. Writes the posterior
    physical states into out_x (B, K, {n}), the packed covariances into out_p (B, K, {npk}) when
    out_p.shape[1] == K (pass shape (B, 0, {npk}) to skip), and the NIS into out_nis (B, K).
    """
    for b in nb.prange(z.shape[0]):
        run_one(z[b], dts[b], x0[b], p0[b], q, r, out_x[b], out_p[b], out_nis[b])
'''


def batch_kernel(n: int, nq: int):
    npk = n * (n + 1) // 2
    qargs = ", ".join(f"q[{i}]" for i in range(nq))
    return ("run_one", BATCH_TEMPLATE.format(n=n, npk=npk, nq=nq, qargs=qargs))


PD_TOL = 1e-13  # LDLᵀ pivot / largest variance below which a covariance counts as lost to rounding


def pd_check_kernels(n: int):
    """``covariance_is_pd(p)`` and ``repair_pd(p)`` for a packed n×n covariance (scalar-unrolled LDLᵀ).

    At condition numbers beyond ~1e13 (e.g. a position known to 1e-4 m next to a heading variance of
    1e5 rad² in a diverging filter) rounding alone can make the smallest eigenvalue of
    Φ(ν) P_J Φ(ν)ᵀ negative.  ``covariance_is_pd`` runs LDLᵀ and requires every pivot
    d_j > PD_TOL · max_i P_ii (a condition-number bound that float64 eigen-solvers can still certify);
    ``repair_pd`` adds the smallest diagonal jitter (PD_TOL · max_i P_ii, growing ×4) that passes.
    Regular steps never trigger it (their condition numbers are many orders smaller).
    """
    idx = packed_index(n)
    lines = ["@nb.njit(cache=True)", "def covariance_is_pd(p):",
             f'    """LDLᵀ test of the packed covariance: every pivot d_j > {PD_TOL!r} · max_i P_ii (NaN fails)."""']
    for i in range(n):
        for j in range(i, n):
            lines.append(f"    p{i}{j} = p[{idx[(i, j)]}]")
    lines.append(f"    tol = {PD_TOL!r} * max({', '.join(f'p{j}{j}' for j in range(n))})")
    for j in range(n):
        terms = "".join(f" - l{j}{k} * l{j}{k} * d{k}" for k in range(j))
        lines.append(f"    d{j} = p{j}{j}{terms}")
        lines.append(f"    if not d{j} > tol:")
        lines.append("        return False")
        if j < n - 1:
            lines.append(f"    r{j} = 1.0 / d{j}")
        for i in range(j + 1, n):
            terms = "".join(f" - l{i}{k} * l{j}{k} * d{k}" for k in range(j))
            lines.append(f"    l{i}{j} = (p{j}{i}{terms}) * r{j}")
    lines.append("    return True")
    check = "\n".join(lines)
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
    return [("covariance_is_pd", check), ("repair_pd", repair)]


def angle_limit_kernel(n: int, angles: tuple[int, ...]):
    """``limit_angle_variance(p)``: cap the std of the tangent angle coordinates at π (congruence scaling).

    A concentrated Gaussian is only meaningful where exp is bijective, |ε_θ| < π (paper, Sec. II-B); an
    angle std beyond π says "heading unknown", which the CGD cannot express.  With position-only
    measurements the heading and the direction of the body-frame velocity are observable only as a sum,
    so that variance can otherwise grow without bound (and with it the condition number of P).
    P ← D P D with D = diag(1, ..., π/σ_θ, ...) keeps P symmetric positive definite.  Inactive while
    σ_θ ≤ π, i.e. in every regular step.
    """
    idx = packed_index(n)
    lines = ["@nb.njit(cache=True)", "def limit_angle_variance(p):",
             '    """Cap the std of the angle coordinates ' + str(list(angles)) + ' of P at π by congruence scaling (see derive/steps.py)."""']
    for a in angles:
        d = idx[(a, a)]
        lines.append(f"    if p[{d}] > math.pi * math.pi:")
        lines.append(f"        f = math.pi / math.sqrt(p[{d}])")
        for j in range(n):
            if j != a:
                lines.append(f"        p[{idx[(a, j)]}] *= f")
        lines.append(f"        p[{d}] = math.pi * math.pi")
    return ("limit_angle_variance", "\n".join(lines))


def vec_inputs(name, syms):
    return [(s, f"{name}[{i}]") for i, s in enumerate(syms)]


def mat_inputs(name, rows, cols, prefix):
    syms = sp.Matrix(rows, cols, lambda i, j: sp.Symbol(f"{prefix}{i}{j}", real=True))
    return syms, [(syms[i, j], f"{name}[{i}, {j}]") for i in range(rows) for j in range(cols)]


def cov_outputs(Pn: sp.Matrix):
    n = Pn.shape[0]
    idx = packed_index(n)
    return [(f"p[{idx[(i, j)]}]", Pn[i, j]) for i in range(n) for j in range(i, n)]


# --------------------------------------------------------------------------- SE(2) blocks
def se2_kernels():
    xs = sp.symbols("x y theta", real=True)
    xin = vec_inputs("xi", xs)
    T, Tin = mat_inputs("T", 3, 3, "T")
    th = sp.Symbol("theta", real=True)
    ks = [
        new_matrix_kernel("se2_hat", "[x, y, θ]^∧ (paper, hat_SE(2)).", ["xi"], xin, SE2.hat(xs)),
        new_vector_kernel("se2_vee", "[M]^∨ = (M[0, 2], M[1, 2], M[1, 0]).", ["T"], Tin, SE2.vee(T)),
        new_matrix_kernel(
            "se2_exp",
            "exp_SE(2)([x, y, θ]^∧) (paper, exp_SE(2)); translation V(θ)[x, y], Taylor-safe at θ = 0.",
            ["xi"],
            xin,
            SE2.exp(xs),
        ),
        Kernel(
            name="se2_log",
            doc="[log_SE(2)(T)]^∨ = [V(θ)^-1 t, θ], θ = atan2(T[1, 0], T[0, 0]) ∈ (-π, π] (paper, log_SE(2)).",
            params=["T"],
            inputs=Tin,
            stages=[[(th, sp.atan2(T[1, 0], T[0, 0]))]],
            outputs=[(f"out[{i}]", e) for i, e in enumerate(list(SE2.V_inv(th) * T[:2, 2]) + [th])],
            prologue=["out = np.empty(3)"],
            ret="out",
        ),
        new_matrix_kernel("se2_inverse", "T^-1 = [[R^T, -R^T t], [0, 1]].", ["T"], Tin, SE2.inverse(T)),
        new_matrix_kernel("se2_adjoint", "Ad_SE(2)(T) = [[R, J t], [0, 1]], J = [[0, 1], [-1, 0]] (paper, Ad_SE(2)).", ["T"], Tin, SE2.Ad(T)),
        new_matrix_kernel("se2_ad", "ad_SE(2)([x, y, θ]) = [[-θ J, J v], [0, 0]] (paper's ad_SE(2), corner corrected to 0).", ["xi"], xin, SE2.ad(xs)),
        new_matrix_kernel(
            "right_jacobian",
            "Φ_SE(2)(ξ) = Σ (-1)^m/(m+1)! ad(ξ)^m, closed form (paper, Φ_G); log(exp(-ξ) exp(ξ + δ)) ≈ Φ δ.",
            ["xi"],
            xin,
            SE2.right_jacobian(xs),
        ),
        new_matrix_kernel("right_jacobian_inv", "Φ_SE(2)(ξ)^-1, closed form.", ["xi"], xin, SE2.right_jacobian_inv(xs)),
    ]
    return ks


# --------------------------------------------------------------------------- LG models
cth, sth, cw, sw = sp.symbols("c_theta s_theta c_omega s_omega", real=True)
CARRIED_THETA = {sp.cos(M.theta): cth, sp.sin(M.theta): sth}
CARRIED_OMEGA = {sp.cos(M.omega): cw, sp.sin(M.omega): sw}

LG_LAYOUTS = {
    "se2se2": [M.x, M.y, cth, sth, M.vx, M.vy, M.omega, cw, sw],
    "se2r3": [M.x, M.y, cth, sth, M.vx, M.vy, M.omega],
}


def kalman_gain(H, P, e, r, scale=1):
    """Stages of a position update shared by every filter: HP, S = H P Hᵀ + r² I, S⁻¹ (2×2, by its
    determinant), K = P Hᵀ S⁻¹, the innovation e and NIS = eᵀ S⁻¹ e; then the Joseph form pieces
    A = I - K' H, B = A P and the posterior P_J = B Aᵀ + r² K' K'ᵀ (symmetric, PSD by construction)
    for the applied gain K' = scale·K (scale a symbol defined by the caller between the two parts)."""
    n = P.shape[0]
    hdefs, HPs = symbolize(H * P, "hp")
    edefs, Es = symbolize(e, "inn")
    sdefs, Ss = symbolize(HPs * H.T + r**2 * sp.eye(2), "S", only_upper=True)
    det = sp.Symbol("det", real=True)
    idefs, Is = symbolize(sp.Matrix([[Ss[1, 1], -Ss[0, 1]], [-Ss[0, 1], Ss[0, 0]]]) / det, "Si", only_upper=True)
    kdefs, Ks = symbolize(HPs.T * Is, "k")
    nis = sp.Symbol("nis", real=True)
    adefs, As = symbolize(sp.eye(n) - scale * Ks * H, "a")
    bdefs, Bs = symbolize(As * P, "b")
    return {
        "gain_stages": [hdefs + edefs, sdefs, [(det, Ss[0, 0] * Ss[1, 1] - Ss[0, 1] ** 2)], idefs, kdefs + [(nis, (Es.T * Is * Es)[0, 0])]],
        "joseph_stages": [adefs, bdefs],
        "K": Ks,
        "e": Es,
        "PJ": Bs * As.T + (r * scale) ** 2 * Ks * Ks.T,
    }


def internal_from_matrix(name, X):
    """{index in the internal state: entry of the block matrix X} (ω of SE(2)×SE(2) handled apart)."""
    if name == "se2se2":
        return {0: X[0, 2], 1: X[1, 2], 2: X[0, 0], 3: X[1, 0], 4: X[3, 5], 5: X[4, 5], 7: X[3, 3], 8: X[4, 3]}
    return {0: X[0, 2], 1: X[1, 2], 2: X[0, 0], 3: X[1, 0], 4: X[3, 6], 5: X[4, 6], 6: X[5, 6]}


SIMULATE_TEMPLATE = '''
@nb.njit(cache=True, parallel=True)
def simulate_batch(x0, dts, noise, out_x):
    """Simulate the motion model X_{k+1} = X_k exp([Ω(X_k) + G n_k]^) for B trajectories (prange).

    x0 (B, 6) physical initial states; dts (B, K) step lengths; noise (B, K, 3) samples of
    n = (n_x, n_y, n_ω) (already scaled by their stds); out_x (B, K + 1, 6) receives the physical
    states, out_x[:, 0] = x0 (for SE(2)×SE(2) ω is the log of T_d's rotation, in [-π, π]).
    """
    B = x0.shape[0]
    K = dts.shape[1]
    for b in nb.prange(B):
        s = state_from_physical(x0[b])
        physical_into(s, out_x[b, 0])
        for k in range(K):
            propagate(s, dts[b, k], noise[b, k, 0], noise[b, k, 1], noise[b, k, 2])
            physical_into(s, out_x[b, k + 1])
'''


WORLD_VELOCITY_TEMPLATE = '''
@nb.njit(cache=True)
def world_velocities(X, out):
    """world_velocity of every row of X (N, n) into out (N, 2)."""
    for i in range(X.shape[0]):
        v = world_velocity(X[i])
        out[i, 0] = v[0]
        out[i, 1] = v[1]
'''


def common_kernels(model):
    """Conversion from the common physical state c = (x, y, θ, v_x, v_y, ω) (body-frame velocity),
    and the world-frame velocity of a physical state."""
    c = sp.Matrix(sp.symbols("x y theta v_x v_y omega", real=True))
    cin = vec_inputs("c", list(c))
    sub = dict(zip([M.x, M.y, M.theta, M.vx, M.vy, M.omega], list(c)))
    phys = list(model.state)
    return [
        new_vector_kernel(
            "world_velocity",
            "World-frame velocity (2,) of a physical state x of this model.",
            ["x"],
            vec_inputs("x", phys),
            model.world_velocity,
        ),
        ("world_velocities", WORLD_VELOCITY_TEMPLATE),
        new_vector_kernel(
            "common_to_state",
            "The model's physical state from the common c = (x, y, θ, v_x, v_y, ω), (v_x, v_y) in the body frame.",
            ["c"],
            cin,
            model.from_common.subs(sub, simultaneous=True),
        ),
        new_matrix_kernel(
            "common_jacobian",
            "J = ∂(filter coordinates)/∂c at c: maps a covariance of c to the filter's P (P = J P_c J^T).",
            ["c"],
            cin,
            model.common_jacobian.subs(sub, simultaneous=True),
        ),
    ]


def lg_kernels(model: M.LGModel):
    layout = LG_LAYOUTS[model.name]
    subs = dict(CARRIED_THETA)
    if model.name == "se2se2":
        subs.update(CARRIED_OMEGA)
    sin_ = vec_inputs("s", layout)
    dt = M.dt
    sig = M.SIGMA
    G = model.group
    phys = sp.symbols("x y theta v_x v_y omega", real=True)
    # physical <-> internal
    X, Y, TH, VX, VY, W = phys
    to_int = [X, Y, sp.cos(TH), sp.sin(TH), VX, VY]
    if model.name == "se2se2":
        # ω is always the log of the stored rotation: atan2(sin ω, cos ω) (so equal means predict alike)
        to_int += [sp.atan2(sp.sin(W), sp.cos(W)), sp.cos(W), sp.sin(W)]
    else:
        to_int += [W]
    to_phys = [M.x, M.y, wrap(sp.atan2(sth, cth)), M.vx, M.vy, M.omega]

    P, pin = sym_cov(6)
    Omega = model.Omega
    F = model.F
    Phi_O = G.right_jacobian(Omega)
    Gn = M.dwna_G(3)

    ks = [
        new_vector_kernel(
            "state_from_physical",
            f"Internal state {[str(v) for v in layout]} from the physical [x, y, θ, v_x, v_y, ω].",
            ["xp"],
            vec_inputs("xp", phys),
            to_int,
        ),
        new_vector_kernel(
            "state_to_physical",
            "Physical [x, y, θ, v_x, v_y, ω] (θ in (-π, π]) from the internal state.",
            ["s"],
            sin_,
            to_phys,
        ),
        physical_into_kernel(sin_, to_phys, "Physical [x, y, θ, v_x, v_y, ω] from the internal state."),
        new_matrix_kernel(
            "group_mean",
            "The mean μ as a block-diagonal matrix: diag(T_s, T_d) (SE(2)×SE(2), 6×6) or diag(T_s, [[I, v], [0, 1]]) (SE(2)×R^3, 7×7).",
            ["s"],
            sin_,
            model.mean(),
            subs,
        ),
        new_vector_kernel("motion_omega", "Ω(μ) = [T v_x, T v_y, T ω, 0, 0, 0] (eq:motionG).", ["s", "dt"], sin_ + [(dt, "dt")], Omega, subs),
        new_matrix_kernel("calC", "𝒞 = ∂Ω(μ exp ε)/∂ε at ε = 0 (eq:C, eq:calCFinal).", ["s", "dt"], sin_ + [(dt, "dt")], model.calC, subs),
        new_matrix_kernel("calH", "ℋ = ∂[log_G'(h(μ)^-1 h(μ exp ε))]^∨/∂ε at ε = 0 (eq:calH, eq:calH_model).", ["s"], sin_, model.calH, subs),
        new_matrix_kernel("transition", "F = Ad_G(exp(-Ω)) + Φ_G(Ω) 𝒞 (paper, below eq:pred_cov).", ["s", "dt"], sin_ + [(dt, "dt")], F, subs),
        new_matrix_kernel(
            "process_noise",
            "Q = G diag(σ_x², σ_y², σ_ω²) G^T, G = [T²/2 I; T I] (noise n_k of eq:motionG).",
            ["dt", "sigma_x", "sigma_y", "sigma_omega"],
            [(dt, "dt"), (sig[0], "sigma_x"), (sig[1], "sigma_y"), (sig[2], "sigma_omega")],
            model.Q,
        ),
    ]

    # ---- fused prediction (eq:pred_mu, eq:pred_cov)
    fdefs, Fs = symbolize(F, "f")
    ndefs, Ns = symbolize(Phi_O * Gn, "g")
    Ts = SE2.element(sp.cos(M.theta), sp.sin(M.theta), M.x, M.y)
    Ts_new = Ts * SE2.exp(Omega[:3])
    edefs, Es = symbolize(sp.Matrix([Ts_new[0, 2], Ts_new[1, 2], Ts_new[0, 0], Ts_new[1, 0]]).T, "e")
    mdefs, Ms = symbolize(Fs * P, "m")
    Pn = Ms * Fs.T + Ns * sp.diag(*[s**2 for s in sig]) * Ns.T
    outs = cov_outputs(Pn) + [(f"s[{i}]", Es[0, i]) for i in range(4)]
    angle_coords = (2, 5) if model.name == "se2se2" else (2,)
    ks.append(angle_limit_kernel(6, angle_coords))
    ks.append(
        Kernel(
            name="predict",
            doc=(
                "Fused LG-EKF prediction, in place: μ ← μ exp(Ω(μ)) (eq:pred_mu),\n"
                "P ← F P F^T + Φ(Ω) Q Φ(Ω)^T (eq:pred_cov), Q = G diag(σ²) G^T.\n"
                "s: internal state (see module doc), p: packed covariance (21), dt > 0.\n"
                "Then the std of the tangent angles is capped at π (limit_angle_variance; inactive while ≤ π)."
            ),
            params=["s", "p", "dt", "sigma_x", "sigma_y", "sigma_omega"],
            inputs=sin_ + pin + [(dt, "dt"), (sig[0], "sigma_x"), (sig[1], "sigma_y"), (sig[2], "sigma_omega")],
            stages=[fdefs + ndefs + edefs, mdefs],
            outputs=outs,
            substitutions=subs,
            epilogue=["limit_angle_variance(p)"],
            fastmath=True,
        )
    )

    # ---- fused update (eq:K, eq:up_mu, eq:up_P) with the Joseph form inside Φ(ν)(·)Φ(ν)^T
    zx, zy, r = sp.symbols("z_x z_y r", real=True)
    R2 = Rn(2)
    h_mu = R2.exp([M.x, M.y])
    innov = R2.log(R2.inverse(h_mu) * R2.exp([zx, zy]))  # [log_G'(h(μ)^-1 Z)]^∨
    alpha = sp.Symbol("alpha", positive=True)
    kg = kalman_gain(model.calH, P, innov, r, scale=alpha)
    nu_raw = sp.Matrix(sp.symbols("nk0:6", real=True))
    nu = sp.Matrix(sp.symbols("nu0:6", real=True))
    angles = (nu_raw[2], nu_raw[5]) if model.name == "se2se2" else (nu_raw[2], sp.Integer(0))
    nudefs = [list(zip(nu_raw, kg["K"] * kg["e"])), [(alpha, gain_damping(*angles))], list(zip(nu, alpha * nu_raw))]
    phidefs, Phis = symbolize(G.right_jacobian(nu), "phi")
    Xn = model.mean().subs(subs) * G.exp(nu)
    mean_out = internal_from_matrix(model.name, Xn)
    mudefs, Mus = symbolize(sp.Matrix([list(mean_out.values())]), "mu")
    jdefs, PJs = symbolize(kg["PJ"], "pj", only_upper=True)
    cdefs, Cs = symbolize(Phis * PJs, "cp")
    Pu = Cs * Phis.T
    outs = cov_outputs(Pu) + [(f"s[{i}]", Mus[0, n]) for n, i in enumerate(mean_out)]
    if model.name == "se2se2":
        # ω ← log of the new rotation of T_d, atan2(sin, cos) ∈ [-π, π]
        outs.append(("s[6]", sp.atan2(Mus[0, list(mean_out).index(8)], Mus[0, list(mean_out).index(7)])))
    ks.append(
        Kernel(
            name="update",
            doc=(
                "Fused LG-EKF update with a position measurement z = (z_x, z_y), noise std r, in place.\n"
                "K = P ℋ^T (ℋ P ℋ^T + r² I)^-1, ν = K [log_G'(h(μ)^-1 Z)]^∨ (eq:K), μ ← μ exp(ν) (eq:up_mu),\n"
                "P ← Φ(ν) [(I - Kℋ) P (I - Kℋ)^T + r² K K^T] Φ(ν)^T: eq:up_P in Joseph form (equal for the\n"
                "optimal gain, positive semidefinite by construction). Returns the NIS e^T S^-1 e.\n"
                "Safeguards (inactive in regular steps): if a rotation angle of ν exceeds π the gain is damped,\n"
                "K → αK with α = π/|angle| (derive.special.gain_damping); if rounding leaves P not positive\n"
                "definite (condition numbers ≳ 1e15) a rounding-level diagonal jitter restores it (repair_pd)."
            ),
            params=["s", "p", "z_x", "z_y", "r"],
            inputs=sin_ + pin + [(zx, "z_x"), (zy, "z_y"), (r, "r")],
            stages=kg["gain_stages"] + nudefs + [phidefs + mudefs] + kg["joseph_stages"] + [jdefs, cdefs],
            outputs=outs,
            substitutions=subs,
            ret="nis",
            epilogue=["if not covariance_is_pd(p):", "    repair_pd(p)"],
            fastmath=True,
        )
    )
    ks.extend(pd_check_kernels(6))
    ks.append(batch_kernel(6, 3))

    # ---- exact motion for simulation (eq:model with a given noise sample)
    nn = sp.symbols("n_x n_y n_omega", real=True)
    Xp = model.propagated(nn).subs(subs)
    prop = internal_from_matrix(model.name, Xp)
    pdefs, Ps = symbolize(sp.Matrix([list(prop.values())]), "xn")
    pouts = [(f"s[{i}]", Ps[0, n]) for n, i in enumerate(prop)]
    if model.name == "se2se2":
        pouts.append(("s[6]", sp.atan2(Ps[0, list(prop).index(8)], Ps[0, list(prop).index(7)])))
    ks.append(
        Kernel(
            name="propagate",
            doc="Exact motion X ← X exp([Ω(X) + G n]^∧) (eq:model) for one noise sample n = (n_x, n_y, n_ω), in place.",
            params=["s", "dt", "n_x", "n_y", "n_omega"],
            inputs=sin_ + [(dt, "dt"), (nn[0], "n_x"), (nn[1], "n_y"), (nn[2], "n_omega")],
            stages=[pdefs],
            outputs=pouts,
            substitutions=subs,
        )
    )
    ks.append(("simulate_batch", SIMULATE_TEMPLATE))
    ks.extend(common_kernels(model))

    # ---- estimation error in the filter's tangent coordinates, for NEES
    c = sp.symbols("xt yt thetat vxt vyt omegat", real=True)
    true_mean = model.mean().subs(dict(zip(model.state, c)), simultaneous=True)
    rel = G.inverse(model.mean()).subs(subs) * true_mean
    ks.append(
        new_vector_kernel(
            "tangent_error",
            "ε = [log_G(μ^-1 X)]^∨: the error of the estimate μ (internal state s) w.r.t. a true physical state c,\n"
            "in the coordinates of P (for NEES = εᵀ P^-1 ε).",
            ["s", "c"],
            sin_ + vec_inputs("c", c),
            G.log(rel),
            subs,
        )
    )
    return ks


# --------------------------------------------------------------------------- Euclidean baselines
def euclid_update_kernel(n, H, state_syms, doc_model):
    """Linear position update with the Joseph form, P ← (I-KH)P(I-KH)^T + r² K K^T."""
    zx, zy, r = sp.symbols("z_x z_y r", real=True)
    P, pin = sym_cov(n)
    sin_ = vec_inputs("s", state_syms)
    xs = sp.Matrix(state_syms)
    kg = kalman_gain(H, P, sp.Matrix([zx, zy]) - H * xs, r)
    Pn = kg["PJ"]
    xn = xs + kg["K"] * kg["e"]
    outs = cov_outputs(Pn) + [(f"s[{i}]", xn[i]) for i in range(n)]
    return Kernel(
        name="update",
        doc=(
            f"{doc_model} Kalman update with a position measurement z = (z_x, z_y), noise std r, in place.\n"
            "K = P H^T S^-1, S = H P H^T + r² I, x ← x + K e, P ← (I-KH)P(I-KH)^T + r² K K^T (Joseph form).\n"
            "Returns the NIS e^T S^-1 e."
        ),
        params=["s", "p", "z_x", "z_y", "r"],
        inputs=sin_ + pin + [(zx, "z_x"), (zy, "z_y"), (r, "r")],
        stages=kg["gain_stages"] + kg["joseph_stages"],
        outputs=outs,
        ret="nis",
        fastmath=True,
    )


def ctrv_kernels():
    m = M.CTRV()
    st = list(m.state)
    sin_ = vec_inputs("s", st)
    dt = M.dt
    sa, sal = m.SIGMA
    P, pin = sym_cov(5)
    phys = sp.symbols("x y psi v omega", real=True)
    ks = [
        new_vector_kernel("state_from_physical", "Internal state = physical [x, y, ψ, v, ω].", ["xp"], vec_inputs("xp", phys), list(phys)),
        new_vector_kernel(
            "state_to_physical", "Physical [x, y, ψ, v, ω] with ψ wrapped to (-π, π].", ["s"], sin_,
            [M.x, M.y, wrap(m.psi), m.v, M.omega],
        ),
        new_vector_kernel("motion", "CTRV exact discretisation f(s): x' = x + vT cos(ψ + ωT/2) sinc(ωT/2), ...", ["s", "dt"], sin_ + [(dt, "dt")], m.f),
        new_matrix_kernel("transition", "CTRV EKF Jacobian F = ∂f/∂s, finite at ω = 0.", ["s", "dt"], sin_ + [(dt, "dt")], m.F),
        new_matrix_kernel(
            "process_noise", "Q = G diag(σ_a², σ_α²) G^T, G's columns (T²/2 cos ψ, T²/2 sin ψ, 0, T, 0), (0, 0, T²/2, 0, T).",
            ["s", "dt", "sigma_a", "sigma_alpha"], sin_ + [(dt, "dt"), (sa, "sigma_a"), (sal, "sigma_alpha")], m.Q,
        ),
    ]
    fdefs, Fs = symbolize(m.F, "f")
    gdefs, Gs = symbolize(m.G, "g")
    xdefs, Xs = symbolize(m.f, "xn")
    mdefs, Ms = symbolize(Fs * P, "m")
    Pn = Ms * Fs.T + Gs * sp.diag(sa**2, sal**2) * Gs.T
    outs = cov_outputs(Pn) + [(f"s[{i}]", Xs[i]) for i in range(3)]
    ks.append(
        Kernel(
            name="predict",
            doc="Fused CTRV EKF prediction in place: s ← f(s), P ← F P F^T + Q (Q at the state before the step).",
            params=["s", "p", "dt", "sigma_a", "sigma_alpha"],
            inputs=sin_ + pin + [(dt, "dt"), (sa, "sigma_a"), (sal, "sigma_alpha")],
            stages=[fdefs + gdefs + xdefs, mdefs],
            outputs=outs,
            fastmath=True,
        )
    )
    ks.append(euclid_update_kernel(5, m.H, st, "CTRV EKF"))
    ks.append(physical_into_kernel(sin_, [M.x, M.y, wrap(m.psi), m.v, M.omega], "Physical [x, y, ψ, v, ω], ψ in (-π, π]."))
    ks.append(batch_kernel(5, 2))
    ks.extend(common_kernels(m))
    return ks


def cv_kernels():
    m = M.CV()
    st = list(m.state)
    sin_ = vec_inputs("s", st)
    dt = M.dt
    P, pin = sym_cov(4)
    ks = [
        new_matrix_kernel("transition", "CV transition F = [[I, T I], [0, I]].", ["dt"], [(dt, "dt")], m.F),
        new_matrix_kernel("process_noise", "Q = σ_a² G G^T, G = [T²/2 I; T I] (DWNA).", ["dt", "sigma_a"], [(dt, "dt"), (m.sigma_a, "sigma_a")], m.Q),
    ]
    mdefs, Ms = symbolize(m.F * P, "m")
    Pn = Ms * m.F.T + m.Q
    xn = m.F * sp.Matrix(st)
    outs = cov_outputs(Pn) + [(f"s[{i}]", xn[i]) for i in range(2)]
    ks.append(
        Kernel(
            name="predict",
            doc="CV Kalman prediction in place: x ← F x, P ← F P F^T + Q.",
            params=["s", "p", "dt", "sigma_a"],
            inputs=sin_ + pin + [(dt, "dt"), (m.sigma_a, "sigma_a")],
            stages=[mdefs],
            outputs=outs,
            fastmath=True,
        )
    )
    ks.append(euclid_update_kernel(4, m.H, st, "CV"))
    ks.append(new_vector_kernel("state_from_physical", "Internal state = physical [x, y, v_x, v_y].", ["xp"], vec_inputs("xp", st), st))
    ks.append(new_vector_kernel("state_to_physical", "Physical state [x, y, v_x, v_y].", ["s"], sin_, st))
    ks.append(physical_into_kernel(sin_, st, "Physical [x, y, v_x, v_y]."))
    ks.append(batch_kernel(4, 1))
    ks.extend(common_kernels(m))
    return ks


# module name -> (title, builder)
MODULES = {
    "se2": ("SE(2) building blocks: hat, vee, exp, log, inverse, Ad, ad, right Jacobian Φ and Φ^-1.", se2_kernels),
    "se2se2": ("LG-EKF on SE(2)×SE(2): model quantities and fused predict/update steps.", lambda: lg_kernels(M.SE2SE2())),
    "se2r3": ("LG-EKF on SE(2)×R^3: model quantities and fused predict/update steps.", lambda: lg_kernels(M.SE2R3())),
    "ctrv": ("CTRV EKF: exact motion, Jacobian, noise and fused predict/update steps.", ctrv_kernels),
    "cv": ("CV Kalman filter: transition, noise and fused predict/update steps.", cv_kernels),
}
