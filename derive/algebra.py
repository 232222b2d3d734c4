"""The LG-EKF step as straight-line algebra, generic in the state dimension n and the measurement dimension m.

Paper (Sec. "EKF on matrix Lie groups"), right perturbation X = μ·exp(ε):

* prediction: μ ← μ·exp(Ω(μ)) (eq:pred_mu); P ← F P Fᵀ + Φ(Ω) Q Φ(Ω)ᵀ (eq:pred_cov),
  F = Ad(exp(−Ω)) + Φ(Ω)·𝒞, Q = G diag(σ²) Gᵀ;
* update: K = P ℋᵀ (ℋ P ℋᵀ + R)⁻¹, ν = K·[log_G'(h(μ)⁻¹ Z)]^∨ (eq:K), μ ← μ·exp(ν) (eq:up_mu),
  P ← Φ(ν) (I − Kℋ) P Φ(ν)ᵀ (eq:up_P).  For the applied gain K' = αK (α the gain damping, 1 in regular steps)
  the Joseph form (I − K'ℋ) P (I − K'ℋ)ᵀ + K' R K'ᵀ equals P − β K (ℋP), β = α(2 − α), exactly, because
  K S Kᵀ = P ℋᵀ S⁻¹ ℋ P = K (ℋP).  ``form="symmetric"`` computes that right-hand side on the upper triangle only
  (symmetric by construction, m multiply-adds per entry), ``form="joseph"`` the Joseph products.  Equal in regular
  steps to rounding; in a diverging filter (R ≪ ℋPℋᵀ, measured: tests/core/test_covariance_health.py extreme cases) the
  symmetric form cancels and can lose positive definiteness where the Joseph form keeps it.  So ``update_<meas>``
  uses the Joseph form and the fused ``step_<meas>`` the symmetric one, falling back to ``update_<meas>`` when a
  cheap screen flags the step (derive/codegen/fused.py).

Each function returns *stages* of named definitions (symbol, expression) for ``derive.codegen``; the
names are the legend of the generated kernels: ``cc`` 𝒞, ``f`` F, ``g`` Φ(Ω)G, ``hh`` ℋ, ``hp`` ℋP,
``inn`` the innovation, ``S``/``Si`` S and S⁻¹, ``k`` K, ``nk`` Kν before damping, ``nu`` ν, ``phi`` Φ(ν),
``a`` I − αKℋ, ``b`` A P, ``pj`` the Joseph-form P, ``beta``/``kb`` β and βK, ``cp`` Φ(ν) P_J, ``mu``/``e`` the new mean.
"""

from __future__ import annotations

import itertools

import sympy as sp

from .lie.special import angle_sum, gain_damping, wrap

__all__ = ["packed_index", "sym_cov", "symbolize", "kalman_gain", "lg_predict", "lg_update", "LEGEND"]

LEGEND = (
    "legend: cc = 𝒞 (eq:C), f = F = Ad(exp(−Ω)) + Φ(Ω)𝒞 (eq:pred_cov), g = Φ(Ω)G, hh = ℋ (eq:calH), "
    "hp = ℋP, inn = [log_G'(h(μ)⁻¹Z)]^∨, S = ℋPℋᵀ + R, Si = S⁻¹, k = K (eq:K), nk = Kν, alpha = gain damping, "
    "nu = ν, phi = Φ(ν) (eq:up_P), a = I − αKℋ, b = aP, beta = α(2 − α), kb = βK, pj = Joseph-form P "
    "(= P − βKℋP), cp = Φ(ν)·pj, mu/e = new mean"
)


def packed_index(n: int) -> dict:
    """{(i, j): k} for the packed upper triangle (row-major) of an n×n symmetric matrix."""
    idx, k = {}, 0
    for i in range(n):
        for j in range(i, n):
            idx[(i, j)] = idx[(j, i)] = k
            k += 1
    return idx


def sym_cov(n: int, name="p"):
    """A symmetric symbolic n×n covariance and its packed inputs [(symbol, "p[k]")]."""
    idx = packed_index(n)
    syms = {(i, j): sp.Symbol(f"{name}{i}_{j}" if n > 10 else f"{name}{i}{j}", real=True) for i in range(n) for j in range(i, n)}
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
            s = sp.Symbol(f"{prefix}{i}{j}" if max(Mx.shape) <= 10 else f"{prefix}{i}_{j}", real=True)
            defs.append((s, e))
            out[i, j] = s
        if only_upper:
            out[j, i] = out[i, j]
    return defs, out


def kalman_gain(H: sp.Matrix, P: sp.Matrix, e: sp.Matrix, R: sp.Matrix, scale=1):
    """Stages of a Kalman update with any m: ℋP, S = ℋPℋᵀ + R, S⁻¹ = adj(S)/det S (one reciprocal),
    K = Pℋᵀ S⁻¹, NIS = eᵀ S⁻¹ e; then the Joseph pieces A = I − K'ℋ, B = A P and
    P_J = B Aᵀ + K' R K'ᵀ for the applied gain K' = scale·K (``scale`` a symbol the caller defines)."""
    n, m = P.shape[0], H.shape[0]
    hdefs, Hs = symbolize(H, "hh")
    pdefs, HPs = symbolize(Hs * P, "hp")
    edefs, Es = symbolize(e, "inn")
    sdefs, Ss = symbolize(HPs * Hs.T + R, "S", only_upper=True)
    rdet = sp.Symbol("rdet", real=True)
    adj = Ss.adjugate()
    idefs, Is = symbolize(adj * rdet, "Si", only_upper=True)
    kdefs, Ks = symbolize(HPs.T * Is, "k")
    nis = sp.Symbol("nis", real=True)
    adefs, As = symbolize(sp.eye(n) - scale * Ks * Hs, "a")
    bdefs, Bs = symbolize(As * P, "b")
    det = (Ss * adj)[0, 0] if m > 1 else Ss[0, 0]
    return {
        "gain_stages": [hdefs, pdefs + edefs, sdefs, [(rdet, 1 / sp.expand(det) if m > 1 else 1 / Ss[0, 0])], idefs,
                        kdefs + [(nis, sp.expand((Es.T * Is * Es)[0, 0]))]],
        "joseph_stages": [adefs, bdefs],
        "K": Ks,
        "HP": HPs,
        "e": Es,
        "PJ": Bs * As.T + scale**2 * Ks * R * Ks.T,
    }


def _changed(model, exprs):
    """{internal index: expression} of the internal state entries an expression list changes."""
    out = {}
    for i, (sym, e) in enumerate(zip(model.internal, exprs)):
        e = angle_sums(model, model.to_internal(e))
        if e != sym:
            out[i] = e
    return out


def angle_sums(model, e):
    """atan2(sin(a + b), cos(a + b)) → angle_sum(a + b, sin(a + b)) where a is a carried angle that the internal state stores.

    A new stored angle is read off a composed rotation R_a R_b as atan2 of its entries (``internal_of``); the angle
    of R_a R_b is a + b modulo 2π, so wrap(a + b) is the same number up to rounding, without atan2; at the branch
    cut ±π its sign is taken from the composed sine, as atan2 would (``derive.lie.special.angle_sum``).  Applies only
    when the atan2 arguments simplify to sin/cos of one sum and every carried angle in it is stored.
    """
    e = sp.sympify(e)
    atoms = e.atoms(sp.atan2)
    if not atoms:
        return e
    back = {}
    for a, c, s_ in model.carried:
        back[c], back[s_] = sp.cos(a), sp.sin(a)
    stored = set(model.internal)
    carried = {a for a, _, _ in model.carried}
    rep = {}
    for at in atoms:
        Y, X = (sp.trigsimp(sp.expand(v.xreplace(back))) for v in at.args)
        if isinstance(Y, sp.sin) and isinstance(X, sp.cos) and Y.args == X.args:
            u = Y.args[0]
            if (u.free_symbols & carried) and (u.free_symbols & carried) <= stored:
                rep[at] = angle_sum(u, at.args[0])
    return e.xreplace(rep)


def lg_predict(model, P: sp.Matrix):
    """Stages and outputs of the fused prediction (eq:pred_mu, eq:pred_cov) for ``model``.

    Returns (stages, {internal index: new value}, P_new (symbolic, symmetric)).
    """
    G = model.group
    sub = model.to_internal
    Omega = model.Omega.applyfunc(sub)
    cdefs, Cs = symbolize(model.calC.applyfunc(sub), "cc")
    fdefs, Fs = symbolize(model.F_of(Cs).applyfunc(sub), "f")
    ndefs, Ns = symbolize((G.right_jacobian(Omega) * model.noise_input()).applyfunc(sub), "g")
    new_mean = _changed(model, model.internal_of(model.mean().applyfunc(sub) * G.exp(Omega)))
    edefs, Es = symbolize(sp.Matrix([list(new_mean.values())]), "e") if new_mean else ([], None)
    mdefs, Ms = symbolize(Fs * P, "m")
    Pn = Ms * Fs.T + Ns * sp.diag(*[s**2 for s in model.noise_stds()]) * Ns.T
    outs = {i: Es[0, k] for k, i in enumerate(new_mean)}
    return [cdefs, fdefs + ndefs + edefs, mdefs], outs, Pn


def lg_update(model, meas, P: sp.Matrix, z, noise, form: str = "joseph"):
    """Stages and outputs of the fused update (eq:K, eq:up_mu, eq:up_P) of ``model`` with ``meas``.

    ``z``: the measured vector's symbols; ``noise``: the measurement's noise symbols; ``form``: "joseph" or
    "symmetric", how the Joseph-form covariance is written (see the module docstring).
    Returns (stages, {internal index: new value}, P_new, nis symbol, transported) where
    ``transported`` tells whether Φ(ν) ≠ I (then rounding can cost positive definiteness).

    Safeguard: if a rotation angle of ν (a periodic tangent coordinate) exceeds π the gain is damped,
    K → αK, α = π/|angle| (``derive.lie.special.gain_damping``); α = 1 in every regular step.
    """
    G, Gp = model.group, meas.group
    sub = model.to_internal
    mu = model.mean().applyfunc(sub)
    H = model.calH_for(meas).applyfunc(sub)
    innov = Gp.log(Gp.inverse(meas.h(model, mu)) * meas.element(z)).applyfunc(sub)
    periodic = model.periodic_tangent()
    alpha = sp.Symbol("alpha", positive=True) if periodic else sp.Integer(1)
    kg = kalman_gain(H, P, innov, meas.R(), scale=alpha)
    n = model.n
    nu_raw = sp.Matrix(sp.symbols(f"nk0:{n}", real=True))
    nu = sp.Matrix(sp.symbols(f"nu0:{n}", real=True))
    stages = kg["gain_stages"] + [list(zip(nu_raw, kg["K"] * kg["e"]))]
    if periodic:
        a = [nu_raw[i] for i in periodic]
        if len(a) == 1:
            damp = gain_damping(a[0], 0)
        else:
            damp = gain_damping(a[0], sp.Max(*[sp.Abs(v) for v in a[1:]]) if len(a) > 2 else a[1])
        stages += [[(alpha, damp)], list(zip(nu, alpha * nu_raw))]
    else:
        nu = nu_raw
    Phi = G.right_jacobian(nu)
    phidefs, Phis = symbolize(Phi, "phi")
    new_mean = _changed(model, model.internal_of(mu * G.exp(nu)))
    mudefs, Mus = symbolize(sp.Matrix([list(new_mean.values())]), "mu")
    if form == "joseph":
        jdefs, PJs = symbolize(kg["PJ"], "pj", only_upper=True)
        cov_stages = kg["joseph_stages"] + [jdefs]
    else:  # P − β K (ℋP), β = α(2 − α): the Joseph form for the gain αK (see the module docstring)
        if periodic:
            beta = sp.Symbol("beta", positive=True)
            kbdefs, KBs = symbolize(beta * kg["K"], "kb")
            cov_stages = [[(beta, alpha * (2 - alpha))], kbdefs]
        else:
            KBs, cov_stages = kg["K"], []
        jdefs, PJs = symbolize(P - KBs * kg["HP"], "pj", only_upper=True)
        cov_stages = cov_stages + [jdefs]
    transported = Phi != sp.eye(n)
    if transported:
        cdefs, Cs = symbolize(Phis * PJs, "cp")
        Pu = Cs * Phis.T
        stages += [phidefs + mudefs] + cov_stages + [cdefs]
    else:
        Pu = PJs
        stages += [mudefs] + cov_stages
    outs = {i: Mus[0, k] for k, i in enumerate(new_mean)}
    return stages, outs, Pu, sp.Symbol("nis", real=True), transported
