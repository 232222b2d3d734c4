"""The equations of Ćesić, Marković, Petrović (ICRA 2016), transcribed EXACTLY AS PRINTED.

Paper: "Moving object tracking employing rigid body motion on matrix Lie groups" (LaTeX source in
``/work/shared/paper/000_dc0e19bb4ec6e560.txt``).  Every equation the filter depends on is typed
here as a SymPy object, typos included, next to what our own derivation (``derive.groups``,
``derive.models``) gives for the same quantity.  ``derive.verify`` compares the two and reports
each one as OK or ERRATUM; nothing here is corrected.

Symbols are those of ``derive.models``: the paper's ΔT and T are both ``dt``; ω, ω_k and θ_{k+1|k}
are ``omega`` and ``theta`` (the missing subscripts are notation, not errata); the Lie algebraic
error is ``EPS = (ε_x, ε_y, ε_θ, ε_vx, ε_vy, ε_ω)``.

Entries come in two kinds:

* ``kind="derived"``: ``derived`` obtains the quantity independently (matrix exponential, Lie
  bracket, conjugation, multivariate limits, first-order error propagation ...), so OK means the
  printed formula was re-derived.
* ``kind="structure"``: filter equations taken from Bourmaud et al. (2013/2015) that have nothing
  to re-derive here; both callables build the same construction from the model and the check only
  confirms the transcription is well-formed and has the form of the LG-EKF of Bourmaud.  The
  ``note`` says so for every such entry.

Not transcribed: eq:cgd (the concentrated Gaussian density, used by no computation) and the
signatures exp_G: g → G, [·]^∨: g → R^p (no content to check).  The LaTeX source defines
``\\label{eq:motionG}`` twice (on the Ω(X_k)/n_k align and on Ω(μ exp ε)); the entries are named
``Omega_se2se2``/``noise_nk`` and ``eq:motionG`` respectively.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from typing import Any, Callable

import sympy as sp

from ..lie.groups import SE2, Product, Rn
from ..lie.special import to_exact
from ..models.base import dt, dwna_G, omega, theta, vx, vy, x, y
from ..models.se2se2 import EPS, SE2SE2

__all__ = [
    "PrintedEquation",
    "PRINTED",
    "model",
    "principal_angle",
    "printed_hat_se2",
    "printed_exp_se2",
    "printed_log_se2",
    "printed_Ad_se2",
    "printed_ad_se2",
    "printed_Phi_series",
]


@dataclass(eq=False)
class PrintedEquation:
    """One printed equation (or one sub-part of it) and our derivation of the same quantity.

    ``printed`` and ``derived`` are zero-argument callables returning SymPy objects (expressions or
    matrices) that ``derive.verify`` compares entry by entry after rewriting the angle functions
    with ``to_exact``.  ``assume`` (optional) is applied to both sides before the comparison; it
    encodes an assumption stated in ``note`` (e.g. θ ∈ (-π, π]).
    """

    label: str
    description: str
    printed: Callable[[], Any]
    derived: Callable[[], Any]
    note: str = ""
    kind: str = "derived"
    assume: Callable[[Any], Any] | None = None


# --------------------------------------------------------------------------------------------
# shared, cached ingredients
# --------------------------------------------------------------------------------------------

@functools.cache
def model() -> SE2SE2:
    """The single SE(2)×SE(2) model instance (its calC/calH are cached properties)."""
    return SE2SE2()


GROUP = Product(SE2, SE2)
e_x, e_y, e_th, e_vx, e_vy, e_w = EPS
n_x, n_y, n_w = sp.symbols("n_x n_y n_omega", real=True)
NU = sp.symbols("nu_0:6", real=True)
_J = sp.Matrix([[0, 1], [-1, 0]])


def _cached(fn):
    """Zero-arg callable with a cached result (run_verify may be called more than once)."""
    return functools.cache(fn)


_c = _cached


def principal_angle(expr):
    """atan2(sin a, cos a) → a: valid for a ∈ (-π, π] (the range of log_SO(2))."""

    def is_wrapped(e):
        return (
            isinstance(e, sp.atan2)
            and isinstance(e.args[0], sp.sin)
            and isinstance(e.args[1], sp.cos)
            and e.args[0].args == e.args[1].args
        )

    return expr.replace(is_wrapped, lambda e: e.args[0].args[0])


def _vee_G(M: sp.Matrix) -> sp.Matrix:
    """[·]^∨ of se(2)×se(2) (block-diagonal 6×6)."""
    return sp.Matrix.vstack(SE2.vee(M[0:3, 0:3]), SE2.vee(M[3:6, 3:6]))


def _rot(a) -> sp.Matrix:
    return sp.Matrix([[sp.cos(a), -sp.sin(a)], [sp.sin(a), sp.cos(a)]])


def _by_continuity(build, values):
    """Evaluate a printed formula with removable singularities (1/θ ...) at ``values``.

    ``build`` takes symbols; entries that come out as 0/0 are replaced by their limit.
    """
    u = sp.symbols(f"_u0:{len(values)}", real=True)
    M = build(u)
    sub = dict(zip(u, values))

    def one(e):
        v = e.subs(sub)
        if v.has(sp.nan, sp.zoo, sp.oo, -sp.oo):
            for s, val in sub.items():
                e = sp.limit(e, s, val)
            return sp.simplify(e)
        return v

    return M.applyfunc(one)


# --------------------------------------------------------------------------------------------
# transcriptions of the SE(2) section (as printed)
# --------------------------------------------------------------------------------------------

def printed_hat_se2(v) -> sp.Matrix:
    """[x]^∧_SE(2) = [[0, -θ, x], [θ, 0, y], [0, 0, 0]]."""
    x_, y_, th = v
    return sp.Matrix([[0, -th, x_], [th, 0, y_], [0, 0, 0]])


def printed_exp_se2(v) -> sp.Matrix:
    """exp_SE(2)([x]^∧) = [[cos θ, -sin θ, t_x], [sin θ, cos θ, t_y], [0, 0, 1]],
    t_x = (1/θ)[x sin θ + y(-1 + cos θ)], t_y = (1/θ)[x(1 - cos θ) + y sin θ)] (stray ')' dropped)."""
    x_, y_, th = v
    tx = 1 / th * (x_ * sp.sin(th) + y_ * (-1 + sp.cos(th)))
    ty = 1 / th * (x_ * (1 - sp.cos(th)) + y_ * sp.sin(th))
    return sp.Matrix([[sp.cos(th), -sp.sin(th), tx], [sp.sin(th), sp.cos(th), ty], [0, 0, 1]])


def printed_log_se2(T: sp.Matrix) -> sp.Matrix:
    """log_SE(2)(T) = [v θ]^∧, θ = atan2(R_21, R_11), v = θ/(2(1-cos θ)) [[sin θ, 1-cos θ], [cos θ-1, sin θ]] t."""
    R, t = T[:2, :2], T[:2, 2]
    th = sp.atan2(R[1, 0], R[0, 0])
    v = th / (2 * (1 - sp.cos(th))) * sp.Matrix([[sp.sin(th), 1 - sp.cos(th)], [sp.cos(th) - 1, sp.sin(th)]]) * t
    return printed_hat_se2([v[0], v[1], th])


def printed_Ad_se2(T: sp.Matrix) -> sp.Matrix:
    """Ad_SE(2)(T) = [[R, J t], [0^{1×2}, 1]], J = [[0, 1], [-1, 0]]."""
    R, t = T[:2, :2], T[:2, 2]
    return sp.Matrix.vstack(sp.Matrix.hstack(R, _J * t), sp.Matrix([[0, 0, 1]]))


def printed_ad_se2(v) -> sp.Matrix:
    """ad_SE(2)(x) = [[-θ J, J v], [0^{1×2}, 1]] — with the printed 1 in the corner."""
    x_, y_, th = v
    return sp.Matrix.vstack(sp.Matrix.hstack(-th * _J, _J * sp.Matrix([x_, y_])), sp.Matrix([[0, 0, 1]]))


def printed_Phi_series(ad: sp.Matrix, order: int) -> sp.Matrix:
    """Φ_G(v) = Σ_{m=0}^{∞} (-1)^m/(m+1)! ad_G(v)^m, truncated after m = order."""
    out = sp.zeros(*ad.shape)
    P = sp.eye(ad.shape[0])
    for m in range(order + 1):
        out += sp.Rational((-1) ** m, sp.factorial(m + 1)) * P
        P = P * ad
    return out


def _Phi_exact_se2(v) -> sp.Matrix:
    """The printed series summed exactly (∫_0^1 exp(-s ad) ds), with the Lie-bracket ad."""
    if all(sp.sympify(c) == 0 for c in v):
        return sp.eye(3)
    return SE2.derived_right_jacobian(v)


def _Phi_exact_G(v) -> sp.Matrix:
    return sp.diag(_Phi_exact_se2(list(v[0:3])), _Phi_exact_se2(list(v[3:6])))


# --------------------------------------------------------------------------------------------
# transcriptions of the SE(2)^2 section (as printed)
# --------------------------------------------------------------------------------------------

def printed_Omega() -> sp.Matrix:
    """Ω(X_k) = [T v_xk, T v_yk, T ω_k, 0, 0, 0]^T (first eq:motionG)."""
    return sp.Matrix([dt * vx, dt * vy, dt * omega, 0, 0, 0])


def printed_noise() -> sp.Matrix:
    """n_k = [T²/2 n_x, T²/2 n_y, T²/2 n_ω, T n_x, T n_y, T n_ω]^T."""
    return sp.Matrix([dt**2 / 2 * n_x, dt**2 / 2 * n_y, dt**2 / 2 * n_w, dt * n_x, dt * n_y, dt * n_w])


def printed_v1():
    """eq:vs: v_1 = [ε_vx sin ε_ω + ε_vy (cos ε_ω - 1)] ε_ω^{-1}."""
    return (e_vx * sp.sin(e_w) + e_vy * (sp.cos(e_w) - 1)) * e_w**-1


def printed_v2():
    """eq:vs: v_2 = [ε_vx (1 - cos ε_ω) + ε_vy sin ε_ω] ε_ω^{-1}."""
    return (e_vx * (1 - sp.cos(e_w)) + e_vy * sp.sin(e_w)) * e_w**-1


def printed_Omega_perturbed() -> sp.Matrix:
    """eq:motionG: Ω(μ_k exp([ε]^∧)) = [ΔT v_x + ΔT cos ω v_1 - ΔT sin ω v_2,
    ΔT v_y + ΔT sin ω v_1 + ΔT cos ω v_2, ΔT ω + ΔT ε_ω, 0^{3×1}]."""
    v1, v2 = printed_v1(), printed_v2()
    return sp.Matrix(
        [
            dt * vx + dt * sp.cos(omega) * v1 - dt * sp.sin(omega) * v2,
            dt * vy + dt * sp.sin(omega) * v1 + dt * sp.cos(omega) * v2,
            dt * omega + dt * e_w,
            0,
            0,
            0,
        ]
    )


def printed_calC() -> sp.Matrix:
    """eq:calCFinal."""
    C = sp.zeros(6, 6)
    C[0:3, 3:6] = sp.Matrix(
        [
            [dt * sp.cos(omega), -dt * sp.sin(omega), 0],
            [dt * sp.sin(omega), dt * sp.cos(omega), 0],
            [0, 0, dt],
        ]
    )
    return C


# p_1 and the second line, also printed as "p_1" (it is p_2)
def printed_p_first():
    return (e_x * sp.sin(e_th) + e_y * (sp.cos(e_th) - 1)) * e_th**-1


def printed_p_second():
    return (e_x * (1 - sp.cos(e_th)) + e_y * sp.sin(e_th)) * e_th**-1


def printed_H_err() -> sp.Matrix:
    """eq:H_err: [cos θ p_1 - sin θ p_2, sin θ p_1 + cos θ p_2], the definitions of p_1, p_2 taken
    in the order printed (the second one is labelled p_1 in print)."""
    p1, p2 = printed_p_first(), printed_p_second()
    return sp.Matrix(
        [sp.cos(theta) * p1 - sp.sin(theta) * p2, sp.sin(theta) * p1 + sp.cos(theta) * p2]
    )


def printed_calH() -> sp.Matrix:
    """eq:calH_model."""
    c, s = sp.cos(theta), sp.sin(theta)
    return sp.Matrix([[c, -s, 0, 0, 0, 0], [s, c, 0, 0, 0, 0]])


def printed_X() -> sp.Matrix:
    """X = diag([[R_θ, t], [0^{1×2}, 1]], [[R_ω, t_v], [0^{1×2}, 1]])."""
    Ts = sp.Matrix.vstack(sp.Matrix.hstack(_rot(theta), sp.Matrix([x, y])), sp.Matrix([[0, 0, 1]]))
    Td = sp.Matrix.vstack(sp.Matrix.hstack(_rot(omega), sp.Matrix([vx, vy])), sp.Matrix([[0, 0, 1]]))
    return sp.diag(Ts, Td)


def printed_exp_G(v) -> sp.Matrix:
    """exp_G([x]^∧_G) = diag(exp_SE(2)(x_p), exp_SE(2)(x_d)); a zero-angle block by continuity."""
    blocks = []
    for part in (list(v[0:3]), list(v[3:6])):
        blocks.append(_by_continuity(printed_exp_se2, part))
    return sp.diag(*blocks)


def printed_F() -> sp.Matrix:
    """F_k = Ad_G(exp_G([-Ω]^∧)) + Φ_G(Ω) 𝒞_k built from the printed Ω, exp, Ad, Φ series, 𝒞."""
    Om = printed_Omega()
    E = printed_exp_G(-Om)
    Ad = sp.diag(printed_Ad_se2(E[0:3, 0:3]), printed_Ad_se2(E[3:6, 3:6]))
    return Ad + _Phi_exact_G(Om) * printed_calC()


# --------------------------------------------------------------------------------------------
# derivations of the same quantities
# --------------------------------------------------------------------------------------------

def _element(a, tx, ty) -> sp.Matrix:
    return SE2.element(sp.cos(a), sp.sin(a), tx, ty)


@_cached
def derived_hat_se2() -> sp.Matrix:
    """Tangent at s = 0 of the curve s ↦ (R(sθ), s·(x, y)) in SE(2)."""
    s = sp.Symbol("_s", real=True)
    return _element(s * theta, s * x, s * y).diff(s).subs(s, 0)


@_cached
def derived_log_se2() -> sp.Matrix:
    """Invert the matrix exponential: ρ solves derived_exp([ρ, θ])_t = t, angle θ (θ ∈ (-π, π])."""
    r1, r2 = sp.symbols("_r1 _r2", real=True)
    E = SE2.derived_exp([r1, r2, theta])
    sol = sp.solve([E[0, 2] - x, E[1, 2] - y], [r1, r2], dict=True)[0]
    return SE2.hat([sp.simplify(sol[r1]), sp.simplify(sol[r2]), theta])


@_cached
def derived_v() -> sp.Matrix:
    """(v_1, v_2) read off our Ω(μ exp ε): R(ω)^T (Ω_{1:2}/ΔT - (v_x, v_y))."""
    Om = model().Omega_perturbed
    v = _rot(omega).T * (sp.Matrix([Om[0], Om[1]]) / dt - sp.Matrix([vx, vy]))
    return v.applyfunc(lambda e: sp.simplify(sp.expand_trig(e)))


@_cached
def derived_p() -> sp.Matrix:
    """(p_1, p_2) read off our measurement error: R(θ)^T e."""
    e = model().measurement_error
    p = _rot(theta).T * e
    return p.applyfunc(lambda v: sp.simplify(sp.expand_trig(v)))


@_cached
def derived_hat_G() -> sp.Matrix:
    """Tangent at s = 0 of s ↦ diag((R(sθ), s(x, y)), (R(sω), s(v_x, v_y)))."""
    s = sp.Symbol("_s", real=True)
    return sp.diag(_element(s * theta, s * x, s * y), _element(s * omega, s * vx, s * vy)).diff(s).subs(s, 0)


XI = sp.Matrix([x, y, theta, vx, vy, omega])


@_cached
def derived_exp_G() -> sp.Matrix:
    """Matrix exponential of the 6×6 block-diagonal [ξ]^∧_G computed by SymPy."""
    E = GROUP.hat(list(XI)).exp()
    return E.applyfunc(lambda e: sp.simplify(sp.expand_complex(e)))


@_cached
def derived_Ad_G() -> sp.Matrix:
    """Ad_G(X) a = [X [a]^∧ X^{-1}]^∨ on the 6×6 group, X the state of eq. (X)."""
    X = model().mean()
    a = sp.Matrix(sp.symbols("_a0:6", real=True))
    w = _vee_G(X * GROUP.hat(list(a)) * GROUP.inverse(X))
    return w.jacobian(a).applyfunc(sp.simplify)


@_cached
def derived_ad_G() -> sp.Matrix:
    """ad_G(a) b = [a^∧ b^∧ - b^∧ a^∧]^∨ on se(2)×se(2)."""
    b = sp.Matrix(sp.symbols("_b0:6", real=True))
    A, B = GROUP.hat(list(XI)), GROUP.hat(list(b))
    return _vee_G(A * B - B * A).jacobian(b).applyfunc(sp.expand)


PHI_ORDER = 8
_s_phi = sp.Symbol("s", real=True)


@_cached
def printed_Phi_truncated() -> sp.Matrix:
    """The printed series to m = PHI_ORDER at v = s·(x, y, θ), ad from the Lie bracket."""
    v = [_s_phi * x, _s_phi * y, _s_phi * theta]
    return printed_Phi_series(SE2.derived_ad(v), PHI_ORDER).applyfunc(sp.expand)


@_cached
def derived_Phi_taylor() -> sp.Matrix:
    """Taylor polynomial in s (to s^PHI_ORDER) of our closed form SE2.right_jacobian(s·(x, y, θ))."""
    Phi = to_exact(SE2.right_jacobian([_s_phi * x, _s_phi * y, _s_phi * theta]))
    return Phi.applyfunc(
        lambda e: sp.expand(sp.series(e, _s_phi, 0, PHI_ORDER + 1).removeO()) if e.has(_s_phi) else e
    )


def _jacobian_at_identity(M: sp.Matrix, variables) -> sp.Matrix:
    """[∂M/∂v_j]^∨ at v = 0 for a curve M(v) in G with M(0) = I: the Jacobian of log_G(M) at 0.

    (d exp_G at 0 is the identity, so this equals ∂/∂v [log_G M(v)]^∨ without differentiating log.)
    """
    zero = {v: 0 for v in variables}
    M0 = M.subs(zero).applyfunc(lambda e: sp.simplify(to_exact(e)))
    if M0 != sp.eye(M.shape[0]):
        raise ValueError(f"curve does not start at the identity: {M0}")
    cols = [_vee_G(M.diff(v).subs(zero)) for v in variables]
    return sp.Matrix.hstack(*cols).applyfunc(sp.simplify)


@_cached
def derived_error_propagation() -> sp.Matrix:
    """First-order propagation of the error through the motion model eq:model.

    X_k = μ exp(ε), X_{k+1} = X_k exp([Ω(X_k) + n]^∧), μ_{k+1|k} = μ exp(Ω(μ)):
    ε_{k+1} = [log(μ_{k+1|k}^{-1} X_{k+1})]^∨ = A ε + B n + O(|ε, n|²); returns [A | B].
    Closed-form exp (angle functions analytic at 0), no limits needed.
    """
    m = model()
    G = m.group
    N = sp.symbols("_n0:6", real=True)
    Om_e = m.Omega_of(m.mean() * G.exp(EPS))
    M = G.exp(-m.Omega) * G.exp(EPS) * G.exp(Om_e + sp.Matrix(N))
    return _jacobian_at_identity(M, list(EPS) + list(N))


@_cached
def derived_recentering() -> sp.Matrix:
    """∂/∂δ [log(exp(-ν) exp(ν + δ))]^∨ at δ = 0: moving the posterior from μ_{k+1|k} to μ_{k+1}."""
    D = sp.symbols("_d0:6", real=True)
    nu = sp.Matrix(NU)
    M = GROUP.exp(-nu) * GROUP.exp(nu + sp.Matrix(D))
    return _jacobian_at_identity(M, list(D))


@_cached
def printed_Phi_nu() -> sp.Matrix:
    return _Phi_exact_G(list(NU))


@_cached
def _closed_form_calC() -> sp.Matrix:
    """eq:C evaluated with the closed-form exp (sinc/cosc analytic at 0): plain substitution ε = 0."""
    m = model()
    Om = m.Omega_of(m.mean() * m.group.exp(EPS))
    return Om.jacobian(sp.Matrix(EPS)).subs({e: 0 for e in EPS}).applyfunc(sp.simplify)


@_cached
def _closed_form_calH() -> sp.Matrix:
    """eq:calH with [·]^∨_{G'} and closed-form exp: plain substitution ε = 0."""
    m = model()
    R2 = Rn(2)
    X = m.mean() * m.group.exp(EPS)

    def h(M):
        return R2.exp([M[0, 2], M[1, 2]])

    e = R2.log(R2.inverse(h(m.mean())) * h(X))
    return e.jacobian(sp.Matrix(EPS)).subs({v: 0 for v in EPS}).applyfunc(sp.simplify)


# small generic Kalman quantities (p = 2 states, q = 2 measurements)
_Pa, _Pb, _Pc = sp.symbols("P_a P_b P_c", real=True)
_Ra, _Rb, _Rc = sp.symbols("R_a R_b R_c", real=True)
_P = sp.Matrix([[_Pa, _Pb], [_Pb, _Pc]])
_R = sp.Matrix([[_Ra, _Rb], [_Rb, _Rc]])
_H = sp.Matrix(2, 2, sp.symbols("H_0:4", real=True))


def printed_K(P=_P, H=_H, R=_R) -> sp.Matrix:
    """eq:K: K = P H^T (H P H^T + R)^{-1}."""
    return P * H.T * (H * P * H.T + R).inv()


@_cached
def derived_K_optimal() -> sp.Matrix:
    """The gain minimising tr E[(ε - K(Hε + m))(…)^T] = tr((I-KH)P(I-KH)^T + K R K^T), solved by SymPy."""
    K = sp.Matrix(2, 2, sp.symbols("_k0:4"))
    I2 = sp.eye(2)
    cost = ((I2 - K * _H) * _P * (I2 - K * _H).T + K * _R * K.T).trace()
    sol = sp.solve([sp.diff(cost, k) for k in K], list(K), dict=True)[0]
    return K.subs(sol).applyfunc(sp.simplify)


@_cached
def derived_posterior_cov() -> sp.Matrix:
    """Joseph form (I-KH)P(I-KH)^T + K R K^T with the optimal gain (covariance of the updated ε)."""
    K = derived_K_optimal()
    I2 = sp.eye(2)
    return ((I2 - K * _H) * _P * (I2 - K * _H).T + K * _R * K.T).applyfunc(sp.simplify)


def _h_of(X: sp.Matrix) -> sp.Matrix:
    """h: SE(2)^2 → G' = R^2 (as a 3×3 matrix group, eq:r): the position of T_s."""
    return Rn(2).exp([X[0, 2], X[1, 2]])


# --------------------------------------------------------------------------------------------
# the list
# --------------------------------------------------------------------------------------------

def _derC_entries():
    m = model
    out = []
    d = dt

    inter = {
        "dOmega1/deps_vx": (
            3,
            lambda: d * sp.cos(omega) * sp.sin(e_w) / e_w - d * sp.sin(omega) * (sp.cos(e_w) - 1) / e_w,
            "printed (cos ε_ω - 1)/ε_ω in the ΔT sin ω term; ∂v_2/∂ε_vx = (1 - cos ε_ω)/ε_ω (sign slip). "
            "Both vanish at ε = 0, so the printed value ΔT cos ω_k is still right.",
        ),
        "dOmega1/deps_vy": (
            4,
            lambda: d * sp.cos(omega) * (sp.cos(e_w) - 1) / e_w - d * sp.sin(omega) * sp.sin(e_w) / e_w,
            "",
        ),
        "dOmega1/deps_omega": (
            5,
            lambda: d * sp.cos(omega)
            * ((e_vx * sp.cos(e_w) - e_vy * sp.sin(e_w)) * e_w - (e_vx * sp.sin(e_w) + e_vy * (sp.cos(e_w) - 1)))
            / e_w**2
            - d * sp.sin(omega)
            * ((e_vx * sp.sin(e_w) + e_vy * sp.cos(e_w)) * e_w - (e_vx * (sp.cos(e_w) - 1) + e_vy * sp.sin(e_w)))
            / e_w**2,
            "second numerator prints [ε_vx (cos ε_ω - 1) + ε_vy sin ε_ω]; v_2 has ε_vx (1 - cos ε_ω) (sign slip). "
            "The printed expression still tends to 0 at ε = 0 ((3/2) ε_vx + O(ε)), so the value 0 is right.",
        ),
    }
    for name, (col, fn, slip) in inter.items():
        out.append(
            PrintedEquation(
                f"eq:derC[{name}] intermediate",
                f"∂Ω_1/∂{EPS[col]} before ε = 0, as printed in eq:derC",
                _c(fn),
                _c(lambda col=col: sp.diff(m().Omega_perturbed[0], EPS[col])),
                ("Compared with sp.diff of our raw Ω_1(μ exp ε) (models.SE2SE2.Omega_perturbed). " + slip).strip(),
            )
        )
    values = [
        ("dOmega1/deps_vx", 0, 3, lambda: d * sp.cos(omega)),
        ("dOmega1/deps_vy", 0, 4, lambda: -d * sp.sin(omega)),
        ("dOmega1/deps_omega", 0, 5, lambda: sp.Integer(0)),
        ("dOmega2/deps_vx", 1, 3, lambda: d * sp.sin(omega)),
        ("dOmega2/deps_vy", 1, 4, lambda: d * sp.cos(omega)),
        ("dOmega2/deps_omega", 1, 5, lambda: sp.Integer(0)),
        ("dOmega3/deps_vx", 2, 3, lambda: sp.Integer(0)),
        ("dOmega3/deps_vy", 2, 4, lambda: sp.Integer(0)),
        ("dOmega3/deps_omega", 2, 5, lambda: d),
    ]
    for name, i, j, fn in values:
        out.append(
            PrintedEquation(
                f"eq:derC[{name}] value",
                f"∂Ω_{i + 1}/∂{EPS[j]} at ε = 0 (multivariate limit), as printed in eq:derC",
                _c(fn),
                _c(lambda i=i, j=j: model().calC[i, j]),
                "Compared with models.SE2SE2.calC (directional limits of the raw derivative).",
            )
        )
    return out


def _derH_entries():
    out = []
    th = theta
    inter = {
        "dH1/deps_x": (
            0,
            lambda: sp.cos(th) * sp.sin(e_th) / e_th - sp.sin(th) * (sp.cos(e_th) - 1) / e_th,
            "printed (cos ε_θ - 1)/ε_θ in the sin θ term; ∂p_2/∂ε_x = (1 - cos ε_θ)/ε_θ (sign slip, as in eq:derC). "
            "Vanishes at ε = 0: the value cos θ is still right.",
        ),
        "dH1/deps_y": (
            1,
            lambda: sp.cos(th) * (sp.cos(e_th) - 1) / e_th - sp.sin(th) * sp.sin(e_th) / e_th,
            "",
        ),
        "dH1/deps_theta": (
            2,
            lambda: sp.cos(th)
            * ((e_x * sp.cos(e_th) - e_y * sp.sin(e_th)) * e_th - (e_x * sp.sin(e_th) + e_y * (sp.cos(e_th) - 1)))
            / e_th**2
            - sp.sin(th)
            * ((e_x * sp.sin(e_th) + e_y * sp.cos(e_th)) * e_th - (e_x * (sp.cos(e_th) - 1) + e_y * sp.sin(e_th)))
            / e_th**2,
            "second numerator prints [ε_x (cos ε_θ - 1) + ε_y sin ε_θ]; p_2 has ε_x (1 - cos ε_θ) (sign slip). "
            "Still tends to 0 at ε = 0, so the value 0 is right.",
        ),
    }
    for name, (col, fn, slip) in inter.items():
        out.append(
            PrintedEquation(
                f"eq:derH[{name}] intermediate",
                f"∂ℋ_1/∂{EPS[col]} before ε = 0, as printed in eq:derH",
                _c(fn),
                _c(lambda col=col: sp.diff(model().measurement_error[0], EPS[col])),
                ("Compared with sp.diff of our raw measurement error (models.SE2SE2.measurement_error). " + slip).strip(),
            )
        )
    values = [
        ("dH1/deps_x", 0, 0, lambda: sp.cos(th)),
        ("dH1/deps_y", 0, 1, lambda: -sp.sin(th)),
        ("dH1/deps_theta", 0, 2, lambda: sp.Integer(0)),
        ("dH2/deps_x", 1, 0, lambda: sp.sin(th)),
        ("dH2/deps_y", 1, 1, lambda: sp.cos(th)),
        ("dH2/deps_theta", 1, 2, lambda: sp.Integer(0)),
    ]
    for name, i, j, fn in values:
        out.append(
            PrintedEquation(
                f"eq:derH[{name}] value",
                f"∂ℋ_{i + 1}/∂{EPS[j]} at ε = 0 (multivariate limit), as printed in eq:derH",
                _c(fn),
                _c(lambda i=i, j=j: model().calH[i, j]),
                "Compared with models.SE2SE2.calH (directional limits of the raw derivative).",
            )
        )
    return out


_p1, _p2 = sp.symbols("p_1 p_2")
_G_sym, _Gp_sym = sp.Symbol("G"), sp.Symbol("G'")
_T_generic = _element(theta, x, y)


def _build() -> list[PrintedEquation]:
    m = model
    E: list[PrintedEquation] = []
    add = E.append

    # ---- SE(2) ------------------------------------------------------------------------------
    add(PrintedEquation(
        "se2_def",
        "SE(2) = {[[R, t], [0^{1×1}, 1]]}: bottom block row [0^{1×1}, 1] as printed",
        _c(lambda: sp.Matrix.hstack(sp.zeros(1, 1), sp.Matrix([[1]]))),
        _c(lambda: _T_generic[2, :]),
        "Printed bottom-left block 0^{1×1} gives a bottom row of length 2, which does not fit the "
        "3×3 matrix [[R (2×2), t (2×1)], ...]; it must be 0^{1×2} (the Ad/X/eq:r displays print 0^{1×2}). "
        "Derived: bottom row of a generic SE(2) element.",
    ))
    add(PrintedEquation(
        "hat_se2",
        "[x y θ]^∧_SE(2) = [[0, -θ, x], [θ, 0, y], [0, 0, 0]]",
        _c(lambda: printed_hat_se2([x, y, theta])),
        derived_hat_se2,
        "Derived as the tangent at s = 0 of s ↦ (R(sθ), s(x, y)).",
    ))
    add(PrintedEquation(
        "exp_se2",
        "exp_SE(2): [[cos θ, -sin θ, t_x], [sin θ, cos θ, t_y], [0, 0, 1]], t_x, t_y as printed",
        _c(lambda: printed_exp_se2([x, y, theta])),
        _c(lambda: SE2.derived_exp([x, y, theta])),
        "Derived: SymPy matrix exponential (SE2.derived_exp). The printed t_y has a stray ')' "
        "(typesetting only, dropped here); the argument is written [x]^∧_G for [x]^∧_SE(2) (notation).",
    ))
    add(PrintedEquation(
        "log_se2",
        "log_SE(2)(T) = [v θ]^∧, θ = atan2(R_21, R_11), v = θ/(2(1-cos θ)) [[sin θ, 1-cos θ], [cos θ-1, sin θ]] t",
        _c(lambda: printed_log_se2(_T_generic)),
        derived_log_se2,
        "T = (R(θ), (x, y)). Derived by inverting derived_exp (solve for ρ). Equal under θ ∈ (-π, π] "
        "(atan2(sin θ, cos θ) = θ) and θ ≠ 0 (printed form is 0/0 at θ = 0).",
        assume=principal_angle,
    ))
    add(PrintedEquation(
        "Ad_se2",
        "Ad_SE(2)(T) = [[R, J t], [0^{1×2}, 1]], J = [[0, 1], [-1, 0]]",
        _c(lambda: printed_Ad_se2(_T_generic)),
        _c(lambda: SE2.derived_Ad(_T_generic)),
        "Derived from Ad(T) a = [T a^∧ T^{-1}]^∨ (SE2.derived_Ad), T = (R(θ), (x, y)).",
    ))
    add(PrintedEquation(
        "ad_se2",
        "ad_SE(2)(x) = [[-θ J, J v], [0^{1×2}, 1]]",
        _c(lambda: printed_ad_se2([x, y, theta])),
        _c(lambda: SE2.derived_ad([x, y, theta])),
        "Derived from the Lie bracket ad(a) b = [a^∧ b^∧ - b^∧ a^∧]^∨ (SE2.derived_ad): the corner entry is 0 "
        "(ad of a 3-dim algebra whose θ-row of every bracket vanishes), not 1.",
    ))
    add(PrintedEquation(
        "Phi_series",
        f"Φ_G(v) = Σ_m (-1)^m/(m+1)! ad_G(v)^m, v = s(x, y, θ), to m = {PHI_ORDER}",
        printed_Phi_truncated,
        derived_Phi_taylor,
        f"Printed series (truncated at m = {PHI_ORDER}) with the Lie-bracket ad vs the Taylor polynomial in s "
        "of our closed form SE2.right_jacobian (the one the code generator emits). With the printed ad_se2 "
        "(corner 1) the series differs: see ad_se2.",
    ))

    # ---- filter on a generic group -----------------------------------------------------------
    add(PrintedEquation(
        "eq:model",
        "X_{k+1} = f(X_k, n_k) = X_k exp_G([Ω̂_k + n_k]^∧_G)",
        _c(lambda: printed_X() * printed_exp_G(printed_Omega() + printed_noise())),
        _c(lambda: m().mean() * m().group.exp(m().Omega + dwna_G(3) * sp.Matrix([n_x, n_y, n_w]))),
        "structure: the model definition (Bourmaud 2013), built from the printed pieces vs models.SE2SE2; "
        "nothing to derive.",
        kind="structure",
    ))
    add(PrintedEquation(
        "eq:pred_mu",
        "μ_{k+1|k} = μ_k exp_G([Ω̂_k]^∧_G)",
        _c(lambda: printed_X() * printed_exp_G(printed_Omega())),
        _c(lambda: m().mean() * m().group.exp(m().Omega)),
        "structure: transcribed; taken from Bourmaud 2015 (f(μ_k, 0) of eq:model), not re-derived.",
        kind="structure",
    ))
    add(PrintedEquation(
        "eq:pred_cov",
        "P_{k+1|k} = F P F^T + Φ_G(Ω̂) Q Φ_G(Ω̂)^T, compared as the linear map [F | Φ_G(Ω̂)] of (ε_k, n_k)",
        _c(lambda: sp.Matrix.hstack(printed_F(), _Phi_exact_G(printed_Omega()))),
        derived_error_propagation,
        "Derived: first-order propagation of the error, ε_{k+1} = log(μ_{k+1|k}^{-1} μ exp(ε) exp(Ω(μ exp ε) + n)) "
        "= A ε + B n; the printed covariance is A P A^T + B Q B^T iff [A | B] = [F | Φ(Ω)]. F from the printed "
        "pieces (see F_def), Φ the printed series summed exactly with the Lie-bracket ad.",
    ))
    add(PrintedEquation(
        "F_def",
        "F_k = Ad_G(exp_G([-Ω̂_k]^∧)) + Φ_G(Ω̂_k) 𝒞_k from the printed Ω, exp_SE(2), Ad_SE(2), Φ series, 𝒞",
        printed_F,
        _c(lambda: m().F),
        "vs models.SE2SE2().F (closed-form Ad/exp/Φ, 𝒞 by limits). The printed exp_SE(2) is 0/0 for the "
        "zero-angle velocity block; taken by continuity (= I). Φ is the printed series summed exactly "
        "(∫_0^1 exp(-s ad) ds) with the Lie-bracket ad, not the printed ad_se2.",
    ))
    add(PrintedEquation(
        "eq:C",
        "𝒞_k = ∂/∂ε Ω(μ_k exp_G([ε]^∧))|_{ε=0}",
        _closed_form_calC,
        _c(lambda: m().calC),
        "Definition evaluated two ways: closed-form exp (sinc/cosc, analytic at 0, plain substitution) vs "
        "models.SE2SE2.calC (raw form, directional limits).",
    ))
    add(PrintedEquation(
        "eq:K",
        "K = P H^T (H P H^T + R)^{-1} (generic symmetric P, R and general H, p = q = 2)",
        _c(lambda: printed_K().applyfunc(sp.simplify)),
        derived_K_optimal,
        "Derived: the gain minimising the trace of the updated error covariance, solved by SymPy. "
        "The formula is Bourmaud 2015's (standard Kalman gain).",
    ))
    add(PrintedEquation(
        "eq:K[nu]",
        "ν = K [log_G'(h(μ_{k+1|k})^{-1} Z)]^∨_G' with G' = R^2 (eq:r)",
        _c(lambda: printed_K() * Rn(2).log(Rn(2).inverse(_h_of(printed_X())) * Rn(2).exp(sp.symbols("z_1 z_2", real=True)))),
        _c(lambda: printed_K() * (sp.Matrix(sp.symbols("z_1 z_2", real=True)) - sp.Matrix([x, y]))),
        "structure: transcribed; taken from Bourmaud 2015, not re-derived. For G' = R^2 it reduces to the "
        "Euclidean innovation K (z - (x, y)) (checked).",
        kind="structure",
    ))
    add(PrintedEquation(
        "eq:calH",
        "ℋ = ∂/∂ε [log_G'(h(μ)^{-1} h(μ exp_G([ε]^∧)))]^∨|_{ε=0}, the vee read as G'",
        _closed_form_calH,
        _c(lambda: m().calH),
        "Definition evaluated two ways: closed-form exp with plain substitution vs models.SE2SE2.calH "
        "(directional limits). The printed vee subscript is G, see eq:calH[vee subscript].",
    ))
    add(PrintedEquation(
        "eq:calH[vee subscript]",
        "group whose [·]^∨ is applied to log_G'(·) in eq:calH",
        _c(lambda: _G_sym),
        _c(lambda: _Gp_sym),
        "Printed ]^∨_G; log_G' returns an element of g' (3×3, eq:r), so the map is [·]^∨_G' (Bourmaud 2013). "
        "Notation only; the dimension (q = 2) makes the intended map unambiguous.",
    ))
    add(PrintedEquation(
        "eq:up_mu",
        "μ_{k+1} = μ_{k+1|k} exp_G([ν_{k+1}]^∧)",
        _c(lambda: printed_X() * printed_exp_G(list(NU))),
        _c(lambda: m().mean() * m().group.exp(list(NU))),
        "structure: transcribed; taken from Bourmaud 2015, not re-derived (mean of μ exp(ε), E[ε] = ν). "
        "Printed exp vs closed-form exp at generic ν.",
        kind="structure",
    ))
    add(PrintedEquation(
        "eq:up_P[Phi(nu)]",
        "P_{k+1} = Φ_G(ν) (I - K H) P Φ_G(ν)^T: the outer factor Φ_G(ν)",
        printed_Phi_nu,
        derived_recentering,
        "Derived: re-centring the updated error δ ~ N(ν, (I-KH)P) from μ_{k+1|k} to μ_{k+1} = μ_{k+1|k} exp(ν) "
        "gives ε = log(exp(-ν) exp(ν + δ)) ≈ Φ(ν) δ; compared is that Jacobian with the printed series "
        "summed exactly (Lie-bracket ad). Confirms Φ is the right Jacobian in the paper's convention.",
    ))
    add(PrintedEquation(
        "eq:up_P[(I-KH)P]",
        "P_{k+1} = Φ_G(ν) (I - K H) P Φ_G(ν)^T: the inner factor (I - K H) P (p = q = 2 generic)",
        _c(lambda: ((sp.eye(2) - printed_K() * _H) * _P).applyfunc(sp.simplify)),
        derived_posterior_cov,
        "Derived: Joseph form (I-KH)P(I-KH)^T + K R K^T with the optimal gain (Bourmaud 2015 / standard KF).",
    ))

    # ---- SE(2)^2 -----------------------------------------------------------------------------
    add(PrintedEquation(
        "X_se2se2",
        "X = diag([[R_θ, t], [0^{1×2}, 1]], [[R_ω, t_v], [0^{1×2}, 1]])",
        printed_X,
        _c(lambda: m().mean()),
        "structure: the state representation vs models.SE2SE2.mean(); nothing to derive.",
        kind="structure",
    ))
    add(PrintedEquation(
        "hat_se2se2",
        "[x]^∧_G = diag([x_p]^∧_SE(2), [x_d]^∧_SE(2))",
        _c(lambda: sp.diag(printed_hat_se2([x, y, theta]), printed_hat_se2([vx, vy, omega]))),
        derived_hat_G,
        "Derived as the tangent at s = 0 of a curve in SE(2)^2 (block-diagonal).",
    ))
    add(PrintedEquation(
        "exp_se2se2",
        "exp_G([x]^∧_G) = diag(exp_SE(2)(x_p), exp_SE(2)(x_d))",
        _c(lambda: printed_exp_G(list(XI))),
        derived_exp_G,
        "Derived: SymPy matrix exponential of the 6×6 block-diagonal [x]^∧_G.",
    ))
    add(PrintedEquation(
        "Ad_se2se2",
        "Ad_G(X) = diag(Ad_SE(2)(T_s), Ad_SE(2)(T_d))",
        _c(lambda: sp.diag(printed_Ad_se2(printed_X()[0:3, 0:3]), printed_Ad_se2(printed_X()[3:6, 3:6]))),
        derived_Ad_G,
        "Derived from Ad(X) a = [X a^∧ X^{-1}]^∨ on the 6×6 group.",
    ))
    add(PrintedEquation(
        "ad_se2se2",
        "ad_G(x) = diag(ad_SE(2)(x_s), ad_SE(2)(x_d))",
        _c(lambda: sp.diag(SE2.derived_ad([x, y, theta]), SE2.derived_ad([vx, vy, omega]))),
        derived_ad_G,
        "Checks the block-diagonal structure only: blocks are the Lie-bracket ad (the printed ad_se2 has the "
        "corner erratum, see ad_se2). Derived from the bracket on se(2)×se(2). x_s is printed for x_p (notation).",
    ))
    add(PrintedEquation(
        "Omega_se2se2",
        "Ω(X_k) = [T v_xk, T v_yk, T ω_k, 0, 0, 0]^T (first \\label{eq:motionG})",
        printed_Omega,
        _c(lambda: m().Omega),
        "structure: the model choice vs models.SE2SE2.Omega; nothing to derive. The LaTeX source reuses "
        "\\label{eq:motionG} for this align and for Ω(μ exp ε).",
        kind="structure",
    ))
    add(PrintedEquation(
        "noise_nk",
        "n_k = [T²/2 n_x, T²/2 n_y, T²/2 n_ω, T n_x, T n_y, T n_ω]^T",
        printed_noise,
        _c(lambda: dwna_G(3) * sp.Matrix([n_x, n_y, n_w])),
        "vs G n with the DWNA input matrix G = [T²/2 I; T I] (models.dwna_G), so Q = G diag(σ²) G^T.",
    ))
    add(PrintedEquation(
        "eq:motionG",
        "Ω(μ_k exp_G([ε]^∧_G)) with v_1, v_2 of eq:vs (second \\label{eq:motionG})",
        printed_Omega_perturbed,
        _c(lambda: m().Omega_perturbed),
        "vs models.SE2SE2.Omega_perturbed (product μ exp ε with the exact exp). Row 3 ΔT(ω + ε_ω) takes the "
        "angle of R_ω R_{ε_ω} as ω + ε_ω, i.e. assumes ω + ε_ω ∈ (-π, π] (the model does the same).",
    ))
    add(PrintedEquation(
        "eq:vs[v_1]",
        "v_1 = [ε_vx sin ε_ω + ε_vy (cos ε_ω - 1)] ε_ω^{-1}",
        _c(printed_v1),
        _c(lambda: derived_v()[0]),
        "Derived: R(ω)^T (Ω_{1:2}(μ exp ε)/ΔT - (v_x, v_y)) from models.SE2SE2.Omega_perturbed.",
    ))
    add(PrintedEquation(
        "eq:vs[v_2]",
        "v_2 = [ε_vx (1 - cos ε_ω) + ε_vy sin ε_ω] ε_ω^{-1}",
        _c(printed_v2),
        _c(lambda: derived_v()[1]),
        "Derived as for v_1.",
    ))
    E.extend(_derC_entries())
    add(PrintedEquation(
        "eq:calCFinal",
        "𝒞_k = [[0, [[ΔT cos ω, -ΔT sin ω, 0], [ΔT sin ω, ΔT cos ω, 0], [0, 0, ΔT]]], [0, 0]]",
        printed_calC,
        _c(lambda: m().calC),
        "vs models.SE2SE2.calC (directional limits of ∂Ω(μ exp ε)/∂ε at 0).",
    ))
    add(PrintedEquation(
        "eq:r[Z]",
        "Z = [[I^{2×2}, z], [0^{1×2}, 1]]",
        _c(lambda: sp.Matrix([[1, 0, sp.Symbol("z_1", real=True)], [0, 1, sp.Symbol("z_2", real=True)], [0, 0, 1]])),
        _c(lambda: Rn(2).hat(sp.symbols("z_1 z_2", real=True)).exp()),
        "Derived: matrix exponential of [z]^∧_R2.",
    ))
    add(PrintedEquation(
        "eq:r[hat]",
        "[z]^∧_R2 = [[0^{2×2}, z], [0^{1×2}, 0]]",
        _c(lambda: sp.Matrix([[0, 0, sp.Symbol("z_1", real=True)], [0, 0, sp.Symbol("z_2", real=True)], [0, 0, 0]])),
        _c(lambda: Rn(2).hat(sp.symbols("z_1 z_2", real=True))),
        "structure: vs derive.groups.Rn(2).hat (the definition; nothing to derive).",
        kind="structure",
    ))
    add(PrintedEquation(
        "eq:meas",
        "Z_{k+1} = h(X_{k+1}) exp_G'([m_{k+1}]^∧_G')",
        _c(lambda: _h_of(printed_X()) * Rn(2).exp(sp.symbols("m_1 m_2", real=True))),
        _c(lambda: Rn(2).exp([x + sp.Symbol("m_1", real=True), y + sp.Symbol("m_2", real=True)])),
        "structure: transcribed (Bourmaud 2013); with G' = R^2 and h = position of T_s it is z = (x, y) + m.",
        kind="structure",
    ))
    add(PrintedEquation(
        "eq:H_err",
        "[log_G'(h(μ)^{-1} h(μ exp ε))]^∨ = [cos θ p_1 - sin θ p_2, sin θ p_1 + cos θ p_2], p's in print order",
        printed_H_err,
        _c(lambda: model().measurement_error),
        "vs models.SE2SE2.measurement_error. The two definitions are substituted in the order printed; "
        "the second is labelled p_1 in print (see eq:H_err[p_2]); the vee subscript is printed G "
        "(see eq:H_err[vee subscript]).",
    ))
    add(PrintedEquation(
        "eq:H_err[p_1]",
        "first definition: p_1 = [ε_x sin ε_θ + ε_y (cos ε_θ - 1)] ε_θ^{-1} (as [name, value])",
        _c(lambda: sp.Matrix([[_p1, printed_p_first()]])),
        _c(lambda: sp.Matrix([[_p1, derived_p()[0]]])),
        "Derived: R(θ)^T times our measurement error.",
    ))
    add(PrintedEquation(
        "eq:H_err[p_2]",
        "second definition, printed as p_1 = [ε_x (1 - cos ε_θ) + ε_y sin ε_θ] ε_θ^{-1} (as [name, value])",
        _c(lambda: sp.Matrix([[_p1, printed_p_second()]])),
        _c(lambda: sp.Matrix([[_p2, derived_p()[1]]])),
        "The value is p_2's; the printed name p_1 (defined twice) leaves p_2, used in eq:H_err, undefined.",
    ))
    add(PrintedEquation(
        "eq:H_err[vee subscript]",
        "group whose [·]^∨ is applied to log_G'(·) in eq:H_err",
        _c(lambda: _G_sym),
        _c(lambda: _Gp_sym),
        "Printed ]^∨_G, must be ]^∨_G' (as in eq:calH). Notation only.",
    ))
    E.extend(_derH_entries())
    add(PrintedEquation(
        "eq:calH_model",
        "ℋ = [[cos θ, -sin θ, 0, 0, 0, 0], [sin θ, cos θ, 0, 0, 0, 0]]",
        printed_calH,
        _c(lambda: model().calH),
        "vs models.SE2SE2.calH (directional limits).",
    ))
    return E


PRINTED: list[PrintedEquation] = _build()
