"""The mechanism SE(3)×SE(3) added for a model that carries a rotation whose log is a state coordinate
(``derive.lie.so3``: ``rotation_vector_entry``, ``rotation_matrix_entry``, ``orthonormal_reduce``), checked against
SciPy's rotations by finite differences; and the 3-D models' common-coordinate Jacobians (the generated
``common_jacobian`` ∂ε/∂c and ``physical_to_common_jacobian`` ∂c/∂ε) against each other and against finite
differences through the generated ``retract`` (X = μ·exp ε), at ω = 0, at a generic ω and near |ω| = π.
"""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp
from scipy.linalg import expm
from scipy.spatial.transform import Rotation

from lgekf.core.registry import ALL_MODELS, SPACES, get_model
from lgekf.derive.lie.so3 import SO3, orthonormal_reduce, rotation_matrix, rotation_vector, skew

PHI = [(0.4, -0.9, 1.3), (1e-9, 0.0, 0.0), (0.0, 0.0, 0.0), (2.0, -1.5, 1.0)]


def _hat(v):
    return np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]], dtype=float)


@pytest.mark.parametrize("phi", PHI[:2] + PHI[3:], ids=str)
def test_log_differentiates_through_the_inverse_right_jacobian(phi):
    """d/dδ [log(R·exp(δ^))]^∨ at δ = 0, from ``rotation_vector_entry``'s derivative, equals central differences of
    SciPy's rotation vector of R·expm(δ^) (R = exp(φ^))."""
    r = sp.symbols("r0:9", real=True)
    d = sp.symbols("d0:3", real=True)
    R = sp.Matrix(3, 3, r)
    v = rotation_vector(R * (sp.eye(3) + skew(d)))
    R0 = Rotation.from_rotvec(phi).as_matrix()
    at = {**dict(zip(r, R0.ravel())), **{di: 0 for di in d}}
    J = np.array(v.jacobian(sp.Matrix(d)).subs(at).evalf(), dtype=float)
    h = 1e-6
    fd = np.column_stack([(Rotation.from_matrix(R0 @ expm(_hat(h * e))).as_rotvec()
                           - Rotation.from_matrix(R0 @ expm(_hat(-h * e))).as_rotvec()) / (2 * h) for e in np.eye(3)])
    np.testing.assert_allclose(J, fd, atol=1e-8)


@pytest.mark.parametrize("phi", PHI, ids=str)
def test_exp_differentiates_through_the_right_jacobian(phi):
    """∂ exp(φ^)/∂φ_k from ``rotation_matrix_entry`` (R·(J_r(φ) e_k)^, finite at φ = 0) equals central differences of
    SciPy's rotation matrix; its closed form is SciPy's matrix."""
    p = sp.symbols("p0:3", real=True)
    M = rotation_matrix(list(p))
    at = dict(zip(p, phi))
    closed = np.array(M.applyfunc(lambda e: e.closed_form()).subs(at).evalf(), dtype=float)
    np.testing.assert_allclose(closed, Rotation.from_rotvec(phi).as_matrix(), atol=1e-14)
    h = 1e-6
    for k in range(3):
        D = np.array(M.diff(p[k]).subs(at).evalf(), dtype=float)
        e = h * np.eye(3)[k]
        fd = (Rotation.from_rotvec(np.add(phi, e)).as_matrix() - Rotation.from_rotvec(np.subtract(phi, e)).as_matrix()) / (2 * h)
        np.testing.assert_allclose(D, fd, atol=1e-8)


def test_orthonormal_reduce_applies_only_the_gram_identity():
    q = sp.symbols("q0:9", real=True)
    R = sp.Matrix(3, 3, q)
    a, b = sp.symbols("a b", real=True)
    G = R.T * R
    assert orthonormal_reduce(a * G[0, 0] + b * G[1, 2] + 3, q) == a + 3
    assert orthonormal_reduce((a * R.T * R * SO3.hat([1, 2, 3]))[0, 1], q) == -3 * a
    # not a function of the Gram entries alone (one column entry squared; a linear term): returned as given
    for e in (a * q[0] ** 2, a * G[0, 0] + q[4], sp.sin(q[0]) * G[0, 0]):
        assert orthonormal_reduce(e, q) is e
    assert orthonormal_reduce(a + b, q) == a + b


THREE_FULL = [n for n, s in ALL_MODELS.items() if s.space == "3d" and s.state_names == SPACES["3d"]["common_names"]]


def _common(w):
    return np.array([1.0, -2.0, 0.5, 0.3, -0.2, 1.1, 3.0, 0.2, -0.1, *w])


@pytest.mark.parametrize("name", THREE_FULL)
@pytest.mark.parametrize("w", [(0.0, 0.0, 0.0), (0.3, -0.5, 0.7), (1.7, -1.5, 1.9)], ids=["w=0", "generic", "near pi"])
def test_common_jacobians_are_inverse_and_match_finite_differences(name, w):
    """For the 3-D models whose state is the common state: ∂c/∂ε · ∂ε/∂c = I, and ∂c/∂ε equals central differences of
    c(retract(s, h e_k)) (the wrap of angles taken into account)."""
    k = get_model(name).kernels
    c = _common(w)
    s = k.state_from_physical(c)
    A = np.asarray(k.physical_to_common_jacobian(k.state_to_physical(s)))
    J = np.asarray(k.common_jacobian(c))
    np.testing.assert_allclose(A @ J, np.eye(12), atol=1e-10)
    h = 1e-6
    cols = []
    def moved(eps):
        t = np.array(s)
        k.retract(t, eps)  # in place: t ← t·exp(ε^)
        return np.asarray(k.physical_to_common(k.state_to_physical(t)))

    for e in np.eye(12):
        d = moved(h * e) - moved(-h * e)
        d[3:6] = (d[3:6] + np.pi) % (2 * np.pi) - np.pi
        cols.append(d / (2 * h))
    np.testing.assert_allclose(A, np.column_stack(cols), atol=2e-7)


def test_a_rotation_vector_bound_is_on_its_norm():
    """SE(3)×SE(3)'s turn rate is the rotation vector of R_ω: |ω| <= π, whatever its components (each < π here)."""
    spec = get_model("se3se3")
    x = np.zeros(12)
    x[9:] = 2.0, 2.0, 2.0  # |ω| = 3.46
    with pytest.raises(ValueError, match=r"\|\(wx, wy, wz\)\| = 3.46.* not representable"):
        spec.check_state("x0", x)
    w = spec.wrap_bounded(x)[9:]
    # the same rotation, the vector of norm 2π − 3.46 pointing the other way
    np.testing.assert_allclose(Rotation.from_rotvec(w).as_matrix(), Rotation.from_rotvec(x[9:]).as_matrix(), atol=1e-12)
    assert np.linalg.norm(w) == pytest.approx(2 * np.pi - np.sqrt(12))
    spec.check_state("x0", spec.wrap_bounded(x))
