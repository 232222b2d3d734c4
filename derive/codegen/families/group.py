"""The group family: SE(2)'s building blocks (``generated/se2.py``), SO(3)'s and SE(3)'s (``generated/se3.py``) and
the operations on a model's whole group (⊕, ⊖, Φ) that smoothing and mixing on the group use."""

from __future__ import annotations

import sympy as sp

from ...algebra import _changed
from ...lie.groups import SE2, SE3, SO3
from ...lie.so3 import so3_angle
from ..blocks import mat_inputs, matrix_kernel, vec_inputs, vector_kernel
from ..printer import Kernel

__all__ = ["se2_kernels", "se3_kernels", "group_operation_kernels", "kernels"]


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


def _log_kernel(name, doc, params, inputs, stages, outputs):
    """A log kernel: its near-π branches (a Piecewise) are printed as conditional expressions whose unused
    branches may divide by zero once CSE has hoisted them, hence IEEE division (error_model="numpy")."""
    return Kernel(name=name, doc=doc, params=params, inputs=inputs, stages=stages,
                  outputs=[(f"out[{i}]", e) for i, e in enumerate(outputs)],
                  prologue=[f"out = np.empty({len(outputs)})"], ret="out", error_model="numpy")


def se3_kernels():
    """hat, vee, exp, log of SO(3) and hat, vee, exp, log, inverse, Ad, ad, Φ, Φ⁻¹ of SE(3) (derive/lie/so3.py, se3.py).

    Tangent order (x, y, z, φx, φy, φz); T = μ·exp(ε); Φ the right Jacobian, log(exp(-ξ) exp(ξ + δ)) ≈ Φ(ξ) δ.
    """
    phis = sp.symbols("phix phiy phiz", real=True)
    xs = sp.symbols("x y z", real=True) + phis
    pin, xin = vec_inputs("phi", phis), vec_inputs("xi", xs)
    R, Rin = mat_inputs("R", 3, 3, "R")
    T, Tin = mat_inputs("T", 4, 4, "T")
    th = sp.Symbol("theta", real=True)
    ph = sp.symbols("phi0:3", real=True)
    log_doc = ("θ = atan2(|a|, (tr R - 1)/2), a = [(R - R^T)/2]^∨; φ = a/sinc(θ) if cos θ >= 0, else from the symmetric\n"
               "part (R + R^T)/2 - cos θ I = (1 - cos θ) u u^T (its largest column, signed by a): accurate up to |φ| = π.")
    return [
        matrix_kernel("so3_hat", "[φx, φy, φz]^ = [[0, -φz, φy], [φz, 0, -φx], [-φy, φx, 0]].", ["phi"], pin, SO3.hat(phis)),
        vector_kernel("so3_vee", "[M]^∨ = (M[2, 1], M[0, 2], M[1, 0]).", ["R"], Rin, SO3.vee(R)),
        matrix_kernel("so3_exp", "exp_SO(3)(φ^) = I + sinc(t) φ^ + cosc2(t) φ^², t = |φ| (Rodrigues), Taylor-safe at t = 0.",
                      ["phi"], pin, SO3.exp(phis)),
        _log_kernel("so3_log", "[log_SO(3)(R)]^∨ = φ, |φ| <= π: " + log_doc, ["R"], Rin, [[(th, so3_angle(R))]],
                    list(SO3.log(R, th))),
        matrix_kernel("se3_hat", "[x, y, z, φx, φy, φz]^ = [[φ^, ρ], [0, 0]] (4×4), ρ = (x, y, z).", ["xi"], xin, SE3.hat(xs)),
        vector_kernel("se3_vee", "[M]^∨ = (M[0, 3], M[1, 3], M[2, 3], M[2, 1], M[0, 2], M[1, 0]).", ["T"], Tin, SE3.vee(T)),
        matrix_kernel("se3_exp", "exp_SE(3)([ρ, φ]^) = [[exp_SO(3)(φ), V(φ) ρ], [0, 1]], V = I + cosc2(t) φ^ + sinc3(t) φ^²,\n"
                      "t = |φ|, Taylor-safe at t = 0.", ["xi"], xin, SE3.exp(xs)),
        _log_kernel("se3_log", "[log_SE(3)(T)]^∨ = (V(φ)^-1 t, φ), V^-1 = I - φ^/2 + halfcot2(θ) φ^², φ = log_SO(3)(R):\n" + log_doc,
                    ["T"], Tin, [[(th, so3_angle(T[:3, :3]))], list(zip(ph, SO3.log(T[:3, :3], th)))],
                    list(SE3.log(T, th, ph))),
        matrix_kernel("se3_inverse", "T^-1 = [[R^T, -R^T t], [0, 1]].", ["T"], Tin, SE3.inverse(T)),
        matrix_kernel("se3_adjoint", "Ad_SE(3)(T) = [[R, t^ R], [0, R]] (tangent order ρ, φ).", ["T"], Tin, SE3.Ad(T)),
        matrix_kernel("se3_ad", "ad_SE(3)(ρ, φ) = [[φ^, ρ^], [0, φ^]].", ["xi"], xin, SE3.ad(xs)),
        matrix_kernel("right_jacobian", "Φ_SE(3)(ξ) = [[J_r(φ), Q_r(ρ, φ)], [0, J_r(φ)]] = Σ (-1)^m/(m+1)! ad(ξ)^m (Barfoot's J_l(-ξ));\n"
                      "log(exp(-ξ) exp(ξ + δ)) ≈ Φ δ. J_r = I - cosc2 φ^ + sinc3 φ^², Q_r(ρ, φ) = Q_l(-ρ, -φ) (derive/lie/se3.py).",
                      ["xi"], xin, SE3.right_jacobian(xs)),
        matrix_kernel("right_jacobian_inv", "Φ_SE(3)(ξ)^-1 = [[J_r^-1, -J_r^-1 Q_r J_r^-1], [0, J_r^-1]], J_r^-1 = I + φ^/2 + halfcot2 φ^².",
                      ["xi"], xin, SE3.right_jacobian_inv(xs)),
    ]


def group_operation_kernels(model) -> list:
    """⊕, ⊖ and the right Jacobian of the model's whole group, for smoothing and mixing on the group.

    ``retract(s, eps)``: μ ← μ·exp([ε]^∧) in place (the update's eq:up_mu with a given ε);
    ``between(s, t)``: [log_G(μ_s^-1 μ_t)]^∨, angle coordinates of a Euclidean model wrapped to (-π, π];
    ``right_jacobian(eps)`` / ``right_jacobian_inv(eps)``: Φ_G(ε) and its inverse (block-diagonal over
    the factors; I for Rⁿ), log(exp(-ε) exp(ε + δ)) ≈ Φ_G(ε) δ.
    """
    from ...lie.special import wrap

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



def kernels(model, measurements: dict, built) -> list:
    """The family's entry (``derive.codegen.emitter``): the group operations of one model (slot ``group``)."""
    return [("group", k) for k in group_operation_kernels(model)]
