"""The motion and measurement models of the paper, derived symbolically.

LG models (state on G = SE(2)×SE(2) or SE(2)×R^3, tangent order ε = (ε_x, ε_y, ε_θ, ε_vx, ε_vy, ε_ω)):

* X = (T_s, T_d): T_s the pose (R_θ, t = (x, y)); T_d the velocities: for SE(2)×SE(2) the SE(2)
  element with translation (v_x, v_y) (body-frame velocity) and angle ω; for SE(2)×R^3 the vector
  (v_x, v_y, ω).
* motion (eq:model): X_{k+1} = X_k exp([Ω(X_k) + n_k]^∧), Ω(X) = [T v_x, T v_y, T ω, 0, 0, 0]
  (eq:motionG), n_k = G n, G = [T²/2 I; T I], n ~ N(0, diag(σ_x², σ_y², σ_ω²)).
* 𝒞 = ∂Ω(μ exp ε)/∂ε at ε = 0 (eq:C), through the multivariate limits (derive.limits).
* F = Ad_G(exp(-Ω)) + Φ_G(Ω) 𝒞, Q = G diag(σ²) G^T, prediction eq:pred_mu / eq:pred_cov.
* measurement (eq:meas): h(X) = position of T_s as an element of G' = R^2 (eq:r), ℋ from
  eq:calH; update eq:K, eq:up_mu, eq:up_P.

Baselines (Euclidean, Schubert 2012 / Bar-Shalom 2002):

* CTRV: state (x, y, ψ, v, ω); the exact discretisation of ẋ = v cos ψ, ẏ = v sin ψ, ψ̇ = ω is
  integrated by SymPy and written as x' = x + vT cos(ψ + ωT/2) sinc(ωT/2), finite at ω = 0.
* CV: state (x, y, v_x, v_y) in the world frame, DWNA noise.
"""

from __future__ import annotations

from functools import cached_property

import sympy as sp

from .groups import SE2, Product, Rn
from .limits import jacobian_at_zero
from .special import sinc, to_exact

__all__ = [
    "x", "y", "theta", "vx", "vy", "omega", "dt", "EPS", "SIGMA",
    "LGModel", "SE2SE2", "SE2R3", "CTRV", "CV", "angle_of", "dwna_G",
]

x, y, theta = sp.symbols("x y theta", real=True)
vx, vy, omega = sp.symbols("v_x v_y omega", real=True)
dt = sp.Symbol("dt", positive=True)
EPS = sp.symbols("epsilon_x epsilon_y epsilon_theta epsilon_vx epsilon_vy epsilon_omega", real=True)
SIGMA = sp.symbols("sigma_x sigma_y sigma_omega", nonnegative=True)


def angle_of(R: sp.Matrix):
    """The angle a of a rotation matrix R = [[cos a, -sin a], [sin a, cos a]] (trigsimp'd)."""
    c, s = sp.trigsimp(R[0, 0]), sp.trigsimp(R[1, 0])
    if isinstance(c, sp.cos) and isinstance(s, sp.sin) and c.args == s.args:
        return c.args[0]
    return sp.atan2(s, c)


def dwna_G(n: int, T=dt) -> sp.Matrix:
    """G = [T²/2 I_n; T I_n]: discrete white-noise acceleration input matrix."""
    return sp.Matrix.vstack(T**2 / 2 * sp.eye(n), T * sp.eye(n))


class LGModel:
    """Common derivation for the two LG-EKF state spaces."""

    name = ""
    group: Product
    state = (x, y, theta, vx, vy, omega)

    def mean(self) -> sp.Matrix:  # pragma: no cover - abstract
        raise NotImplementedError

    def velocities(self, X: sp.Matrix):
        """(v_x, v_y, ω) read off the velocity block of X."""
        raise NotImplementedError

    def Omega_of(self, X: sp.Matrix) -> sp.Matrix:
        """Ω(X) = [T v_x, T v_y, T ω, 0, 0, 0] (eq:motionG, first line)."""
        v1, v2, w = self.velocities(X)
        return sp.Matrix([dt * v1, dt * v2, dt * w, 0, 0, 0])

    @cached_property
    def Omega(self) -> sp.Matrix:
        return self.Omega_of(self.mean())

    @cached_property
    def Omega_perturbed(self) -> sp.Matrix:
        """Ω(μ exp([ε]^∧)) in raw form (sin/cos divided by ε), as the paper prints eq:motionG."""
        X = self.mean() * to_exact(self.group.exp(EPS))
        return self.Omega_of(X).applyfunc(sp.expand)

    @cached_property
    def calC(self) -> sp.Matrix:
        """𝒞 = ∂Ω(μ exp ε)/∂ε |_{ε=0} (eq:C), every singular entry by directional limits."""
        self.limit_report_C = []
        return jacobian_at_zero(self.Omega_perturbed, EPS, report=self.limit_report_C)

    @cached_property
    def measurement_error(self) -> sp.Matrix:
        """[log_G'(h(μ)^-1 h(μ exp ε))]^∨ (eq:H_err), raw form."""
        R2 = Rn(2)
        X = self.mean() * to_exact(self.group.exp(EPS))

        def h(M):
            return R2.exp([M[0, 2], M[1, 2]])

        e = R2.log(R2.inverse(h(self.mean())) * h(X))
        return e.applyfunc(lambda v: sp.expand(sp.simplify(v)))

    @cached_property
    def calH(self) -> sp.Matrix:
        """ℋ = ∂/∂ε [log_G'(h(μ)^-1 h(μ exp ε))]^∨ |_{ε=0} (eq:calH)."""
        self.limit_report_H = []
        return jacobian_at_zero(self.measurement_error, EPS, report=self.limit_report_H)

    def F_of(self, C: sp.Matrix) -> sp.Matrix:
        """F = Ad_G(exp(-Ω)) + Φ_G(Ω) 𝒞 for a given 𝒞 (paper, below eq:pred_cov)."""
        G = self.group
        return G.Ad(G.exp(-self.Omega)) + G.right_jacobian(self.Omega) * C

    @cached_property
    def F(self) -> sp.Matrix:
        return self.F_of(self.calC)

    def propagated(self, n) -> sp.Matrix:
        """The exact motion X exp([Ω(X) + G n]^∧) of eq:model for a noise sample n = (n_x, n_y, n_ω)."""
        Gn = dwna_G(3)
        return self.mean() * self.group.exp(self.Omega + Gn * sp.Matrix(n))

    @cached_property
    def common_jacobian(self) -> sp.Matrix:
        """∂ε/∂c at the mean: tangent coordinates ε (X = μ exp ε) w.r.t. the physical state c.

        To first order log(μ^-1 X(c + d)) = [μ^-1 X(c + d) - I]^∨, so J = ∂/∂d of that at d = 0.
        """
        d = sp.symbols("_d0:6", real=True)
        mu = self.mean()
        Xd = mu.subs({c: c + di for c, di in zip(self.state, d)}, simultaneous=True)
        E = self.group.inverse(mu) * Xd - sp.eye(mu.shape[0])
        J = self.group.vee(E).jacobian(sp.Matrix(d)).subs({di: 0 for di in d})
        return J.applyfunc(sp.trigsimp)

    @property
    def from_common(self) -> sp.Matrix:
        """The LG filters' physical state is the common one."""
        return sp.Matrix(self.state)

    @property
    def world_velocity(self) -> sp.Matrix:
        """R(θ) (v_x, v_y): the body-frame velocity in the world frame."""
        return sp.Matrix([[sp.cos(theta), -sp.sin(theta)], [sp.sin(theta), sp.cos(theta)]]) * sp.Matrix([vx, vy])

    @cached_property
    def Q(self) -> sp.Matrix:
        """Q = G diag(σ_x², σ_y², σ_ω²) G^T for n_k of eq:motionG."""
        Gn = dwna_G(3)
        return Gn * sp.diag(*[s**2 for s in SIGMA]) * Gn.T


class SE2SE2(LGModel):
    """G = SE(2)×SE(2): X = (T_s, T_d), T_d = (R_ω, (v_x, v_y)), ω = log_SO(2)(R_ω) ∈ [-π, π]."""

    name = "se2se2"
    group = Product(SE2, SE2)

    def mean(self):
        return sp.diag(SE2.element(sp.cos(theta), sp.sin(theta), x, y), SE2.element(sp.cos(omega), sp.sin(omega), vx, vy))

    def velocities(self, X):
        Td = X[3:6, 3:6]
        return Td[0, 2], Td[1, 2], angle_of(Td[:2, :2])


class SE2R3(LGModel):
    """G = SE(2)×R^3: X = (T_s, v), v = (v_x, v_y, ω) a plain vector."""

    name = "se2r3"
    group = Product(SE2, Rn(3))

    def mean(self):
        return sp.diag(SE2.element(sp.cos(theta), sp.sin(theta), x, y), Rn(3).exp([vx, vy, omega]))

    def velocities(self, X):
        V = X[3:7, 3:7]
        return V[0, 3], V[1, 3], V[2, 3]


class CTRV:
    """Constant turn rate and velocity, state (x, y, ψ, v, ω)."""

    name = "ctrv"
    psi, v = sp.symbols("psi v", real=True)
    state = (x, y, psi, v, omega)
    SIGMA = sp.symbols("sigma_a sigma_alpha", nonnegative=True)

    @cached_property
    def integrated(self) -> sp.Matrix:
        """x(T), y(T), ψ(T) integrated by SymPy from ẋ = v cos ψ, ẏ = v sin ψ, ψ = ψ0 + ω t."""
        t = sp.Symbol("_t", real=True)
        psi_t = self.psi + omega * t
        dx = sp.integrate(self.v * sp.cos(psi_t), (t, 0, dt))
        dy = sp.integrate(self.v * sp.sin(psi_t), (t, 0, dt))
        return sp.Matrix([x + dx, y + dy, psi_t.subs(t, dt), self.v, omega])

    @cached_property
    def f(self) -> sp.Matrix:
        """x' = x + vT cos(ψ + ωT/2) sinc(ωT/2), y' = y + vT sin(ψ + ωT/2) sinc(ωT/2), ψ' = ψ + ωT."""
        h = omega * dt / 2
        return sp.Matrix(
            [
                x + self.v * dt * sp.cos(self.psi + h) * sinc(h),
                y + self.v * dt * sp.sin(self.psi + h) * sinc(h),
                self.psi + omega * dt,
                self.v,
                omega,
            ]
        )

    @cached_property
    def F(self) -> sp.Matrix:
        """EKF Jacobian ∂f/∂state (d sinc/dx = -dsinc, finite at ω = 0)."""
        return self.f.jacobian(sp.Matrix(self.state))

    @cached_property
    def G(self) -> sp.Matrix:
        c, s = sp.cos(self.psi), sp.sin(self.psi)
        return sp.Matrix([[dt**2 / 2 * c, 0], [dt**2 / 2 * s, 0], [0, dt**2 / 2], [dt, 0], [0, dt]])

    @cached_property
    def Q(self) -> sp.Matrix:
        return self.G * sp.diag(*[s**2 for s in self.SIGMA]) * self.G.T

    H = sp.Matrix([[1, 0, 0, 0, 0], [0, 1, 0, 0, 0]])

    @property
    def from_common(self) -> sp.Matrix:
        """(x, y, ψ, v, ω) from the common physical state (x, y, θ, v_x, v_y, ω), v_x, v_y body-frame:
        ψ = θ + atan2(v_y, v_x) is the heading of the velocity, v its magnitude."""
        return sp.Matrix([x, y, theta + sp.atan2(vy, vx), sp.sqrt(vx**2 + vy**2), omega])

    @property
    def common_jacobian(self) -> sp.Matrix:
        """Singular at v = 0, where the heading of the velocity is undefined."""
        return self.from_common.jacobian(sp.Matrix([x, y, theta, vx, vy, omega])).applyfunc(sp.simplify)

    @property
    def world_velocity(self) -> sp.Matrix:
        return self.v * sp.Matrix([sp.cos(self.psi), sp.sin(self.psi)])


class CV:
    """Constant velocity, state (x, y, v_x, v_y) in the world frame, DWNA noise σ_a."""

    name = "cv"
    wx, wy = sp.symbols("w_x w_y", real=True)
    state = (x, y, wx, wy)
    sigma_a = sp.Symbol("sigma_a", nonnegative=True)

    @cached_property
    def F(self) -> sp.Matrix:
        return sp.Matrix([[1, 0, dt, 0], [0, 1, 0, dt], [0, 0, 1, 0], [0, 0, 0, 1]])

    @cached_property
    def Q(self) -> sp.Matrix:
        G = dwna_G(2)
        return self.sigma_a**2 * G * G.T

    H = sp.Matrix([[1, 0, 0, 0], [0, 1, 0, 0]])

    @property
    def from_common(self) -> sp.Matrix:
        """(x, y, w_x, w_y) with (w_x, w_y) = R(θ) (v_x, v_y) the world-frame velocity."""
        w = sp.Matrix([[sp.cos(theta), -sp.sin(theta)], [sp.sin(theta), sp.cos(theta)]]) * sp.Matrix([vx, vy])
        return sp.Matrix([x, y, w[0], w[1]])

    @property
    def common_jacobian(self) -> sp.Matrix:
        return self.from_common.jacobian(sp.Matrix([x, y, theta, vx, vy, omega]))

    @property
    def world_velocity(self) -> sp.Matrix:
        return sp.Matrix([self.wx, self.wy])
