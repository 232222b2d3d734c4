"""The definition type of a motion model: everything the emitter and the runtime know about a model.

A motion model is one file ``derive/models/<name>.py`` holding one subclass of :class:`MotionModel`
and ``MODEL = <Subclass>()``.  The subclass *declares* (class attributes and a few small methods);
this base class *derives* everything else (Ω, Ω(μ·exp ε), 𝒞, F, Q, ℋ for each measurement, the
exact motion, the Jacobian of the common coordinates) with no knowledge of any particular model.

Conventions (every model)
-------------------------
* The state is X ∈ G, a matrix Lie group (SE(2), Rⁿ or a direct product, ``derive.lie.groups``).
  Perturbations act on the right, X = μ·exp(ε^∧); P is the covariance of ε.
* The tangent coordinates ε are ordered like the physical state (``physical``), e.g.
  (x, y, θ, v_x, v_y, ω) for the paper's LG models; for a model on Rⁿ (the Euclidean CTRV, CV) ε is
  simply the error of the physical state, so the LG-EKF *is* the EKF there.
* Motion (eq:model): X_{k+1} = X_k·exp([Ω(X_k) + G n_k]^∧), n_k ~ N(0, diag(σ²)), σ the model's noise
  parameters (``noise_names``, the user's ``accel_std``).  A Euclidean model x' = f(x) + G n has
  Ω(x) = f(x) − x.
* The internal state (``internal``) is the storage the kernels read and write in place; it may carry
  (cos, sin) of angles (``carried``) so that a step needs few sincos.
* The common physical coordinates c = (x, y, θ, v_x, v_y, ω) (body-frame velocity) are how models are
  initialised alike and compared (``from_common``).
"""

from __future__ import annotations

from functools import cached_property

import sympy as sp

from ..dag import dag_replace
from ..lie.groups import SE2, SE3, Product, Rn
from ..lie.limits import jacobian_at_zero
from ..lie.so3 import orthonormal_reduce, rotation_matrix, rotation_vector, rotation_vector_entry
from ..lie.special import to_exact, wrap
from ..space import PLANE, SPACE3, angle_of, euler_rotation

__all__ = [
    "MotionModel", "VectorModel", "PoseBodyVelocity3", "x", "y", "theta", "vx", "vy", "omega", "dt", "COMMON",
    "COMMON_NAMES", "dwna_G", "rotation", "angle_of", "SE2", "SE3", "Rn", "Product", "PLANE", "SPACE3",
]

x, y, theta = sp.symbols("x y theta", real=True)
vx, vy, omega = sp.symbols("v_x v_y omega", real=True)
dt = sp.Symbol("dt", positive=True)
#: the common physical coordinates c of the plane (body-frame velocity), shared by every planar model
COMMON = PLANE.common
COMMON_NAMES = PLANE.common_names
assert COMMON == (x, y, theta, vx, vy, omega)


def dwna_G(n: int, T=dt) -> sp.Matrix:
    """G = [T²/2 I_n; T I_n]: the discrete white-noise acceleration input matrix."""
    return sp.Matrix.vstack(T**2 / 2 * sp.eye(n), T * sp.eye(n))


def rotation(a) -> sp.Matrix:
    """R(a) = [[cos a, −sin a], [sin a, cos a]]."""
    return sp.Matrix([[sp.cos(a), -sp.sin(a)], [sp.sin(a), sp.cos(a)]])


class MotionModel:
    """A motion model on a matrix Lie group, declared by a subclass (see the module docstring).

    Declared by every definition
    ----------------------------
    display_name, description, color : how the model is shown (tables, figures)
    space : the space the object moves in (``derive.space.PLANE``, the default, or ``SPACE3``): its common
        coordinates c (``from_common``) and the measurements that fit
    group : the Lie group G
    physical : the physical state symbols, also the order of the tangent coordinates and of P
    internal : the internal state symbols (the kernels' storage layout)
    noise_names : names of the process-noise stds (``accel_std``)
    default_accel_std : defaults for tracking real data (``lgekf track``)
    matched_noise : for each noise std, "v" or "w": the simulated truth's σ_v or σ_ω it matches
        (the paper's Monte Carlo study gives every filter its matched noise)
    angles : physical coordinates that are angles (wrapped to (−π, π] on output and in differences)
    carried : (angle, cos symbol, sin symbol) carried in the internal state
    carried_rotations : ((rotation vector symbols), (its matrix's nine entry symbols, row-major)) carried in the
        internal state (``derive.lie.so3.rotation_vector``: its log is the vector)
    bounds : {physical index, or a tuple of indices (their Euclidean norm): largest representable |value|}, with
        ``bound_reason``
    lifts : the name of the planar model this model lifts to 3-D space ("" for none): the study compares a 3-D model
        where the paper compares the planar one
    forward_speed : (heading index, speed index) of a model that moves along its heading at a signed scalar speed
        (CTRV's ψ, v; SE(2)×R²'s θ, v): the state with (heading + π, −speed) is the same motion, and the runtime
        chooses the one whose heading is the direction of motion at a start (``lgekf.core.initiation``); () for none
    mean(), internal_of(X), internal_from_physical(), physical_from_internal(), Omega_of(X),
    noise_input(), position(X), heading(X) (plane) or attitude(X) (space), from_common(), world_velocity()
    """

    name: str = ""  # the definition file's stem, set by the loader
    display_name: str = ""
    description: str = ""
    color: str = "C7"
    space = PLANE
    group = None
    physical: tuple = ()
    internal: tuple = ()
    noise_names: tuple = ()
    default_accel_std: tuple = ()
    matched_noise: tuple = ()
    angles: tuple = ()
    carried: tuple = ()
    carried_rotations: tuple = ()
    bounds: dict = {}
    bound_reason: str = ""
    forward_speed: tuple = ()
    lifts: str = ""
    names: tuple = ()

    # ------------------------------------------------------------------ declared (abstract)
    def mean(self) -> sp.Matrix:  # pragma: no cover - abstract
        """μ as a group matrix, written in the physical symbols (cos/sin of carried angles allowed) or in internal
        symbols that ``internal_from_physical`` expresses in the physical ones (a rotation matrix's entries)."""
        raise NotImplementedError

    def internal_of(self, X: sp.Matrix) -> list:  # pragma: no cover - abstract
        """The internal state read off a group matrix X."""
        raise NotImplementedError

    def internal_from_physical(self) -> list:  # pragma: no cover - abstract
        """The internal state from the physical symbols."""
        raise NotImplementedError

    def physical_from_internal(self) -> list:  # pragma: no cover - abstract
        """The physical state from the internal symbols (angles wrapped)."""
        raise NotImplementedError

    def Omega_of(self, X: sp.Matrix) -> sp.Matrix:  # pragma: no cover - abstract
        """Ω(X), the tangent increment of one step of length ``dt`` (eq:motionG)."""
        raise NotImplementedError

    def noise_input(self) -> sp.Matrix:  # pragma: no cover - abstract
        """G: how the noise n (one entry per noise std) enters the tangent increment, X exp(Ω + G n)."""
        raise NotImplementedError

    def noise_stds(self) -> list:
        """The std of each entry of n (default: one noise std per entry, in order)."""
        return list(self.noise_symbols)

    def position(self, X: sp.Matrix) -> tuple:  # pragma: no cover - abstract
        """(x, y) (plane) or (x, y, z) (space) of the object in the world frame, read off X."""
        raise NotImplementedError

    def heading(self, X: sp.Matrix):
        """(cos, sin) of the object's heading read off X, or None when the model has none (plane)."""
        return None

    def attitude(self, X: sp.Matrix):
        """The rotation matrix R (3 × 3, body to world) read off X, or None when the model has none (space)."""
        return None

    def body_rate(self):
        """The body-frame angular rate (ω_x, ω_y, ω_z) in the physical symbols when no physical coordinate is one of
        them (space); None: read off ``from_common``."""
        return None

    def from_common(self) -> list:  # pragma: no cover - abstract
        """The physical state from the common coordinates c of the model's space (``space.common``: in the plane
        (x, y, θ, v_x, v_y, ω))."""
        raise NotImplementedError

    def world_velocity(self) -> sp.Matrix:  # pragma: no cover - abstract
        """The world-frame velocity (2,) or (3,) in the physical symbols."""
        raise NotImplementedError

    # ------------------------------------------------------------------ derived
    @property
    def n(self) -> int:
        """Dimension of the tangent space (= length of the physical state)."""
        return len(self.physical)

    @property
    def physical_names(self) -> tuple:
        """Names of the physical state entries (output columns); ``names`` overrides the symbols' names."""
        return tuple(self.names) if self.names else tuple(_plain_name(s) for s in self.physical)

    @cached_property
    def noise_symbols(self) -> tuple:
        return tuple(sp.Symbol(nm, nonnegative=True) for nm in self.noise_names)

    @cached_property
    def EPS(self) -> tuple:
        """The tangent coordinates ε, named after the physical state."""
        return tuple(sp.Symbol(f"epsilon_{_eps_name(s)}", real=True) for s in self.physical)

    @cached_property
    def carried_substitutions(self) -> dict:
        """cos(a) → c, sin(a) → s for every carried angle (applied to every expression emitted)."""
        out = {}
        for a, c, s in self.carried:
            out[sp.cos(a)] = c
            out[sp.sin(a)] = s
        return out

    @cached_property
    def carried_identities(self) -> dict:
        """atan2(s, c) → a: the carried angle is the log of its own rotation, so this is exact; likewise the log of a
        carried rotation matrix (``carried_rotations``) → its carried rotation vector."""
        out = {sp.atan2(s, c): a for a, c, s in self.carried}
        for vec, entries in self.carried_rotations:
            out.update(zip(rotation_vector(sp.Matrix(3, 3, list(entries))), vec))
        return out

    def to_internal(self, e):
        """An expression with the carried substitutions and identities applied; a log of a rotation that is not
        carried (``rotation_vector_entry`` of a computed matrix) in its closed form, as kernels compute it."""
        e = sp.sympify(e).subs(self.carried_substitutions).xreplace(self.carried_identities)
        return dag_replace(e, lambda a: isinstance(a, rotation_vector_entry), lambda a: a.closed_form())

    @cached_property
    def Omega(self) -> sp.Matrix:
        """Ω(μ) (eq:motionG)."""
        return self.Omega_of(self.mean())

    @cached_property
    def perturbed_mean(self) -> sp.Matrix:
        """μ·exp([ε]^∧), for the derivatives at ε = 0 (𝒞, ℋ).

        In full (raw form, sin/cos divided by ε, as the paper prints eq:motionG) when the group's exponential goes
        through the directional limits quickly (SE(2), Rⁿ: ``exact_limits``); otherwise (a factor SO(3) or SE(3),
        whose limits through |φ| take SymPy minutes) to first order, μ·(I + ε^∧): exp(ε) = I + ε^∧ + O(|ε|²), so every
        first derivative at ε = 0 of a function smooth at μ is the same (tests/derive/test_models3.py checks 𝒞 and ℋ
        against finite differences of the exact exponential).
        """
        if self.group.exact_limits:
            return self.mean() * to_exact(self.group.exp(self.EPS))
        return self.mean() * (sp.eye(self.group.matrix_size) + self.group.hat(self.EPS))

    @cached_property
    def Omega_perturbed(self) -> sp.Matrix:
        """Ω(μ·exp([ε]^∧)) (``perturbed_mean``): in the plane in raw form, as the paper prints eq:motionG."""
        return self.Omega_of(self.perturbed_mean).applyfunc(sp.expand)

    @cached_property
    def calC(self) -> sp.Matrix:
        """𝒞 = ∂Ω(μ·exp ε)/∂ε at ε = 0 (eq:C), every singular entry through directional limits.

        With a carried rotation (``carried_rotations``) the log of its perturbed matrix differentiates to
        J_r(ω)⁻¹·[(RᵀR δ^ − δ^ᵀRᵀR)/2]^∨; RᵀR = I is applied (``orthonormal_reduce``), leaving J_r(ω)⁻¹ δ.
        """
        self.limit_report_C = []
        C = jacobian_at_zero(self.Omega_perturbed, self.EPS, report=self.limit_report_C)
        if self.carried_rotations:
            C = C.applyfunc(self.to_internal)
            for _, entries in self.carried_rotations:
                C = C.applyfunc(lambda e, entries=entries: orthonormal_reduce(e, entries))
        return C

    def F_of(self, C: sp.Matrix) -> sp.Matrix:
        """F = Ad_G(exp(−Ω)) + Φ_G(Ω)·𝒞 for a given 𝒞 (paper, below eq:pred_cov)."""
        G = self.group
        return G.Ad(G.exp(-self.Omega)) + G.right_jacobian(self.Omega) * C

    @cached_property
    def F(self) -> sp.Matrix:
        return self.F_of(self.calC)

    @cached_property
    def Q(self) -> sp.Matrix:
        """Q = G diag(σ²) Gᵀ: covariance of the noise G n in the tangent increment (eq:motionG)."""
        Gn = self.noise_input()
        return Gn * sp.diag(*[s**2 for s in self.noise_stds()]) * Gn.T

    def propagated(self, n) -> sp.Matrix:
        """The exact motion μ·exp([Ω(μ) + G n]^∧) of eq:model for a noise sample n."""
        return self.mean() * self.group.exp(self.Omega + self.noise_input() * sp.Matrix(n))

    def measurement_error_for(self, meas) -> sp.Matrix:
        """[log_G'(h(μ)⁻¹ h(μ·exp ε))]^∨ (eq:H_err) to first order in ε, raw form.

        log_G'(I + E) = E + O(E²), so [h(μ)⁻¹ h(μ·exp ε) − I]^∨ has the same derivative at ε = 0 as the
        log; for G' = Rⁿ the two are identical.
        """
        Gp = meas.group
        X = self.perturbed_mean
        mu = self.mean()
        E = Gp.inverse(meas.h(self, mu)) * meas.h(self, X) - sp.eye(Gp.matrix_size)
        return Gp.vee(E).applyfunc(lambda v: sp.expand(sp.simplify(v)))

    def calH_for(self, meas) -> sp.Matrix:
        """ℋ = ∂/∂ε [log_G'(h(μ)⁻¹ h(μ·exp ε))]^∨ at ε = 0 (eq:calH), through directional limits; computed once per
        measurement (the limits are most of a render's time, and several kernel families need ℋ)."""
        cache = self.__dict__.setdefault("_calH_for", {})
        key = meas.name or id(meas)  # a definition's name (a measurement made outside the loader: the object)
        if key not in cache:
            cache[key] = jacobian_at_zero(self.measurement_error_for(meas), self.EPS)
        return cache[key].copy()

    @cached_property
    def measurement_error(self) -> sp.Matrix:
        """The paper's measurement (position, G' = R²): see ``measurement_error_for``."""
        from ..measurements.position import MEASUREMENT

        return self.measurement_error_for(MEASUREMENT)

    @cached_property
    def calH(self) -> sp.Matrix:
        """ℋ of the paper's position measurement (eq:calH, eq:calH_model)."""
        self.limit_report_H = []
        return jacobian_at_zero(self.measurement_error, self.EPS, report=self.limit_report_H)

    @cached_property
    def mean_physical(self) -> sp.Matrix:
        """μ written in the physical symbols only: ``mean()`` with every internal symbol that is not physical (a
        rotation's entries) replaced by its ``internal_from_physical`` expression."""
        sub = {s: e for s, e in zip(self.internal, self.internal_from_physical()) if s not in self.physical}
        return self.mean().subs(sub, simultaneous=True) if sub else self.mean()

    @cached_property
    def mean_of_common(self) -> sp.Matrix:
        """μ as a function of the common coordinates c (through ``from_common``)."""
        return self.mean_physical.subs(dict(zip(self.physical, self.from_common())), simultaneous=True)

    @property
    def n_common(self) -> int:
        """Number of common coordinates of the model's space."""
        return len(self.space.common)

    @cached_property
    def common_jacobian(self) -> sp.Matrix:
        """∂ε/∂c at the mean: the tangent coordinates ε (X = μ·exp ε) w.r.t. the common coordinates c.

        To first order log(μ⁻¹ X(c + d)) = [μ⁻¹ X(c + d) − I]^∨, so J = ∂/∂d of that at d = 0; P = J P_c Jᵀ.
        A carried rotation (``carried_rotations``) enters as ``derive.lie.so3.rotation_matrix`` of its rotation vector,
        so its derivative is R·(J_r(ω) dω)^ (no division by |ω|); RᵀR = I is applied (``orthonormal_reduce``) before
        the closed form of exp replaces it.
        """
        common = self.space.common
        d = sp.symbols(f"_d0:{len(common)}", real=True)
        mu = self._mean_with_differentiable_rotations().subs(dict(zip(self.physical, self.from_common())), simultaneous=True)
        Xd = mu.subs({c: c + di for c, di in zip(common, d)}, simultaneous=True)
        E = self.group.inverse(mu) * Xd - sp.eye(mu.shape[0])
        J = self.group.vee(E).jacobian(sp.Matrix(d)).subs({di: 0 for di in d})
        for vec, entries in self.carried_rotations:
            vec = [sp.sympify(e).subs(dict(zip(self.physical, self.from_common())), simultaneous=True) for e in vec]
            R = rotation_matrix(vec)
            J = J.xreplace({R[k // 3, k % 3]: q for k, q in enumerate(entries)})
            J = J.applyfunc(lambda e, entries=entries: orthonormal_reduce(e, entries))
            J = J.xreplace({q: R[k // 3, k % 3].closed_form() for k, q in enumerate(entries)})
        return J.applyfunc(_tidy)

    def _mean_with_differentiable_rotations(self) -> sp.Matrix:
        """``mean_physical`` with each carried rotation as ``rotation_matrix`` of its rotation vector (unevaluated)."""
        if not self.carried_rotations:
            return self.mean_physical
        carried = {q: e for vec, entries in self.carried_rotations for q, e in zip(entries, rotation_matrix(list(vec)))}
        sub = {s: carried.get(s, e) for s, e in zip(self.internal, self.internal_from_physical()) if s not in self.physical}
        return self.mean().subs(sub, simultaneous=True)

    @cached_property
    def common_of_physical(self) -> list:
        """c read off the physical state (the inverse direction of ``from_common``), by the model's space
        (``derive.space``: in the plane (x, y) = ``position``, θ = the ``heading`` or the direction of the world
        velocity, (v_x, v_y) = R(θ)ᵀ·``world_velocity``, ω the coordinate ``from_common`` sets to ω).  Components in
        ``common_missing`` (the model carries no information on them, e.g. CV's ω) are 0 here.
        """
        return self.space.common_of_physical(self)

    @cached_property
    def common_missing(self) -> tuple:
        """Indices of the common coordinates the model does not depend on (``from_common`` ignores them)."""
        used = set().union(*(sp.sympify(e).free_symbols for e in self.from_common()))
        return tuple(i for i, c in enumerate(self.space.common) if c not in used)

    @cached_property
    def physical_of_tangent_jacobian(self) -> sp.Matrix:
        """∂x/∂ε at the mean (n × n): the physical state x of X = μ·exp(ε) differentiated at ε = 0.

        Computed forward, x(μ·(I + ε^)) through ``internal_of`` and ``physical_from_internal`` (exp(ε^) = I + ε^ to
        first order), not by inverting ∂ε/∂x: a carried rotation vector (``carried_rotations``) then differentiates
        through ``derive.lie.so3.rotation_vector_entry`` to J_r(ω)^-1 in closed form (``orthonormal_reduce`` applies
        RᵀR = I), where a symbolic inverse of SE(3)×SE(3)'s 12 × 12 ∂ε/∂x does not finish. Output wrapping of angles
        (``wrap``) has derivative 1 and is dropped.
        """
        eps = list(self.EPS)
        X = self.mean() * (sp.eye(self.group.matrix_size) + self.group.hat(eps))
        perturbed = dict(zip(self.internal, self.internal_of(X)))
        x = sp.Matrix(self.physical_from_internal()).replace(lambda a: isinstance(a, wrap), lambda a: a.args[0])
        J = x.subs(perturbed, simultaneous=True).jacobian(sp.Matrix(eps)).subs({e: 0 for e in eps})
        J = J.applyfunc(self.to_internal)
        for _, entries in self.carried_rotations:
            J = J.applyfunc(lambda e, entries=entries: orthonormal_reduce(e, entries))
        rest = {s: e for s, e in zip(self.internal, self.internal_from_physical()) if s not in self.physical}
        return J.subs(rest, simultaneous=True).applyfunc(_tidy)

    @cached_property
    def common_of_physical_jacobian(self) -> sp.Matrix:
        """∂c/∂ε at the mean (n_common × n): a covariance P of ε maps to the common coordinates as A P Aᵀ.

        A = ∂c/∂x · ∂x/∂ε (chain rule through the physical coordinates x, ``physical_of_tangent_jacobian``); rows of
        ``common_missing`` are zero.
        """
        c = sp.Matrix(self.common_of_physical)
        A = c.jacobian(sp.Matrix(self.physical)) * self.physical_of_tangent_jacobian
        return A.applyfunc(_tidy)

    def periodic_tangent(self) -> tuple:
        """Tangent coordinates that are rotation angles of SE(2) factors (exp is periodic in them)."""
        return tuple(self.group.periodic_coordinates())

    def is_linear_gaussian(self, meas) -> bool:
        """True when this model with measurement ``meas`` is a linear Gaussian state-space model.

        That is: the group is a vector space in its tangent coordinates (Φ_G = I and Φ_G' = I, so μ·exp(ε)
        is μ + ε and the innovation a difference), and F (eq:pred_cov), Q = G diag(σ²) Gᵀ and ℋ (eq:calH)
        do not depend on the state.  Then x_k = F x_{k-1} + G n_k, z_k = ℋ x_k + m_k exactly, the filter is
        the Kalman filter, its innovation likelihood is exact, and EM (Shumway & Stoffer 1982) applies
        (``lgekf.estimators.noise.em``).
        """
        state = set(self.physical) | set(self.internal) | {s for _, c, s_ in self.carried for s in (c, s_)}
        eps = sp.Matrix(self.EPS)
        if sp.simplify(self.group.right_jacobian(list(eps)) - sp.eye(self.n)) != sp.zeros(self.n, self.n):
            return False
        m = meas.group.dim
        if sp.simplify(meas.group.right_jacobian([sp.Symbol(f"_u{i}") for i in range(m)]) - sp.eye(m)) != sp.zeros(m, m):
            return False
        for M in (self.to_internal(self.F), self.to_internal(self.Q), self.to_internal(self.calH_for(meas))):
            if sp.Matrix(M).free_symbols & state:
                return False
        return True


class VectorModel(MotionModel):
    """A motion model on Rⁿ (the Euclidean EKF, or the KF when linear): μ = exp(x) with x the physical state, so the
    tangent ε is the error of the physical state and the LG-EKF machinery is the EKF (Φ = I, Ad = I); the internal
    state is the physical one, read back with the ``angles`` wrapped to (−π, π]; Ω(x) = f(x) − x from the model's
    exact discretisation ``f(s)`` (a list of the physical symbols in, the next state out).  CTRV, CT3, CV, CV3."""

    @property
    def internal(self) -> tuple:
        return tuple(self.physical)

    def f(self, s) -> sp.Matrix:  # pragma: no cover - abstract
        """The exact discretisation x' = f(x) over one step of length ``dt``."""
        raise NotImplementedError

    def mean(self):
        return self.group.exp(self.physical)

    def internal_of(self, X):
        return list(self.group.log(X))

    def internal_from_physical(self):
        return list(self.physical)

    def physical_from_internal(self):
        return [wrap(p) if i in self.angles else p for i, p in enumerate(self.physical)]

    def Omega_of(self, X):
        s = self.group.log(X)
        return self.f(list(s)) - s


class PoseBodyVelocity3:
    """What the 3-D models whose physical state is the common state (pose, body velocity and rate: se3r6, se3se3)
    share: the pose is the first SE(3) factor (position its translation, attitude its rotation), the body-frame
    velocity turns into the world by the Z-Y-X Euler rotation, and the noise n = (n_a, n_α) is white linear and
    angular acceleration (σ_a, σ_α) entering the velocity factor's tangent through G = [T²/2 I; T I] (for se3r6 the
    twist itself; for se3se3 the tangent of T_d, so ω moves by J_r(ω)⁻¹·T·n_α and v by R_ω-rotated T·n_a)."""

    def noise_input(self):
        return dwna_G(6)

    def noise_stds(self):
        sa, sal = self.noise_symbols
        return [sa] * 3 + [sal] * 3

    def position(self, X):
        return X[0, 3], X[1, 3], X[2, 3]

    def attitude(self, X):
        return X[:3, :3]

    def from_common(self):
        return list(SPACE3.common)

    def world_velocity(self):
        roll, pitch, yaw, vx, vy, vz = SPACE3.common[3:9]
        return euler_rotation(roll, pitch, yaw) * sp.Matrix([vx, vy, vz])


#: entries with more operations than this are emitted as they are (CSE shares their parts); simplifying them takes
#: SymPy minutes (a 3-D model's Euler-angle Jacobians) for little gain; every planar entry is below it
TIDY_OPS = 60


def _tidy(e):
    """trigsimp + simplify of a small entry (``TIDY_OPS``), the entry itself otherwise."""
    return sp.simplify(sp.trigsimp(e)) if sp.count_ops(e) <= TIDY_OPS else e


def _plain_name(s) -> str:
    return {"v_x": "vx", "v_y": "vy"}.get(s.name, s.name)


def _eps_name(s) -> str:
    return {"v_x": "vx", "v_y": "vy"}.get(s.name, s.name)
