"""The IMM's per-step loop in numba: mixing (on the group or in the common coordinates), mode-matched
predict/update, mode probabilities from the innovation likelihoods, and the combined estimate.

The numba is generated: ``generated/imm.py`` (``derive/codegen/families/imm.py``), its model-independent part from the
template ``derive/codegen/templates/imm_helpers.py.tmpl`` and its per-measurement parts (``imm_update_<meas>``,
``imm_run_batch_<meas>``, ...) from ``imm_measurement.py.tmpl`` for each measurement definition. This module is the
runtime's door to it: the kernels, ``measurement_index`` (the ``meas`` argument of the generic kernels) and
``run_batch`` (the batch loop of one measurement); no code here names a measurement.

Every model is reached through ``lgekf.generated.dispatch`` (its kernels by model index, the chains inlined), so
one compiled loop runs any set of registry models. Storage of one IMM (M modes): ``models`` (M,) model indices; ``S``
(M, L) internal states (row j holds mode j's state in its first ``N_INTERNAL[models[j]]`` entries); ``Pp``
(M, N) packed covariances (upper triangle, row-major, of each mode's own n); ``mu`` (M,) mode probabilities;
``PI`` (M, M) the transition matrix, PI[i, j] = P(mode j at k | mode i at k-1).

Mixing on one group (every mode the same model, ``same_group``). Each mode i is a concentrated Gaussian
X = μ_i·exp(ε_i), ε_i ~ N(0, P_i). The mixture Σ w_i N_G(μ_i, P_i) is reduced to one N_G(μ, P):

* mean: iterate μ ← μ·exp(Σ w_i d_i), d_i = [log(μ⁻¹μ_i)]^∨ (generated ``between_add``, ``retract``), from
  the most probable μ_i, until |Σ w_i d_i| < 1e-12 (at most 50 iterations); then Σ w_i d_i = 0;
* covariance: X = μ_i·exp(ε_i) = μ·exp(d_i)·exp(ε_i). With the right Jacobian Φ = Φ_G of the generated
  ``right_jacobian`` (log(exp(−d) exp(d + δ)) ≈ Φ(d) δ, i.e. exp(d + δ) ≈ exp(d)·exp(Φ(d) δ)), putting
  δ = Φ(d_i)⁻¹ ε_i gives exp(d_i)·exp(ε_i) ≈ exp(d_i + Φ(d_i)⁻¹ ε_i), so to first order in ε_i the error
  about μ is ε = d_i + Φ(d_i)⁻¹ ε_i and
  P = Σ w_i [Φ(d_i)⁻¹ P_i Φ(d_i)⁻ᵀ + d_i d_iᵀ]  (``right_jacobian_inv``; tests/estimators/test_imm.py checks it
  against samples pushed through dense expm/logm). Each term comes from the generated ``mix_transport``
  (between, Φ⁻¹ and the congruence in one straight-line kernel over the packed covariances; derive/codegen/mixing.py).

Mixing across models (``same_group`` false): in the common coordinates c = (x, y, θ, v_x, v_y, ω) (body
velocity; in 3-D space (x, y, z, roll, pitch, yaw, body velocity, body rate), the loop of ``generated/imm_3d.py``:
``loop_of``, the same template sized by the space, its three angles wrapped and capped as θ is). Mode i's Gaussian is mapped to c_i = ``physical_to_common``(x_i), P_c,i = A_i P_i A_iᵀ with
A_i = ∂c/∂ε_i (``physical_to_common_jacobian``). A model carries no information on some coordinates
(``common_missing``: CV has no ω; its θ is the direction of its velocity and v_y = 0, no side slip, as for
CTRV and SE(2)×R²): for mixing into mode j those coordinates of mode i are replaced by mode j's own
(mean, variance; no correlation), i.e. only the shared components are mixed and each mode keeps its own
others. The mixture is moment-matched in c (θ differences wrapped to (−π, π] about the most probable
source) and converted to mode j: s_j = ``common_to_state``(c̄), P_j = J P̄_c Jᵀ, J = ``common_jacobian``(c̄) (both
directions through the generated straight-line ``common_of_state`` / ``state_of_common``).
A heading read off a velocity (CV) is singular at speed 0: the Jacobians are taken at speed ≥ 1e-9 m/s
(``SPEED_FLOOR``) and the std of the common θ is capped at π (congruence scaling, as the filters'
``limit_angle_variance``), so a stopped CV mode hands on "heading unknown", not an infinite variance.

Likelihood of mode j: N(ν; 0, S) with log det S, S = ℋ P ℋᵀ + R, from the generated ``innovation_logdet_<meas>`` at
the predicted state, and νᵀS⁻¹ν the NIS returned by the fused update; a missed detection (NaN in z) leaves the
predicted probabilities. The combined output is in the common coordinates (the same reduction with the
mode probabilities, on the group when ``same_group``, then converted to c).

Speed (issue #11; docs/performance.md, "Speed of the IMM"). numba brackets a function with atomic reference counting
(``NRT_incref``/``NRT_decref``) of the arrays it receives when it passes arrays on to a call that is not inlined or
can raise; views (``S[j]``) and tuples of arrays multiply the count. So the step loop works on arrays it already
holds: ONE 2-D float workspace per IMM (``workspace(M)``) carries everything the step reads and writes, a quantity
per row at offsets fixed by M (``_R_*``, ``_r_*``): the model indices, the modes' internal states and packed
covariances, μ, the transition matrix, the noise stds, the measurement and every scratch quantity. The helpers take
that one array (two atomic operations per call, however many quantities it holds) and the generated kernels are
called in their row variants (``<kernel>_at(ws, row, ...)``, derive/codegen/imm_rows.py, ``error_model="numpy"``),
which count nothing themselves; the inlined dispatch chain before them counts ``ws`` once per call, and the mixing
on the group is one generated loop per model (``mix_on_group_at``) that calls them directly. The public functions
copy their arguments in and the results out (``_load`` / ``_store``); ``imm_batch`` does so once per trajectory.
``imm_step`` and ``imm_batch`` run each mode's prediction and update as the filter's fused step (``step_ll_<meas>``:
``step_try_<meas>`` on rows, which also returns 1/det S for the likelihood; a step that fails its LDLᵀ test is
redone by ``update_<meas>`` from the prediction, as in the filter loops). ``imm_predict`` / ``imm_update`` (the IMM
class, the smoother's forward pass) keep the separate prediction, log det S and update.
"""

from __future__ import annotations

from ...core.registry import get_measurement, imm_kernel, imm_module
from ..threads import run_on_threads
from ...generated.imm import (
    MEASUREMENT_NAMES,
    _mix,
    combined_common,
    imm_loglik_one,
    imm_predict,
    imm_run_one,
    imm_step,
    imm_update,
    mix_common,
    mix_on_group,
    workspace,
)

__all__ = ["imm_predict", "imm_update", "imm_step", "imm_loglik_one", "imm_run_one", "run_batch", "measurement_index",
           "mix_on_group", "combined_common", "workspace", "mix_common", "_mix", "loop_of"]


def loop_of(space: str):
    """The generated IMM loop of the models of ``space`` (``lgekf.core.registry.imm_module``): the module whose
    ``imm_predict``, ``imm_update``, ``combined_common``, ``workspace``, ... this module exports for the plane
    (``generated/imm.py``); 3-D space has its own (``generated/imm_3d.py``), sized by its 12 common coordinates."""
    return imm_module(space)


def measurement_index(measurement: str) -> int:
    """The index of ``measurement`` in the ``MEASUREMENT_NAMES`` of the generated IMM loop of its space: the ``meas``
    argument of ``imm_update``, ``imm_step``, ``imm_loglik_one`` and ``imm_run_one``."""
    names = MEASUREMENT_NAMES
    try:
        names = loop_of(get_measurement(measurement).space).MEASUREMENT_NAMES
    except ValueError:
        pass
    if measurement not in names:
        raise ValueError(f"measurement: the IMM supports {', '.join(names)}, got {measurement!r}")
    return names.index(measurement)


def run_batch(measurement: str):
    """``imm_run_one`` over B trajectories, compiling only that measurement's kernels: the generated
    ``imm_run_batch_<measurement>`` (serial, without the GIL) on parts of the batch in threads
    (``lgekf.estimators.threads``). The returned function takes models, S0 (B, M, L), P0 (B, M, N), mu0, PI, Q, r,
    z (B, K, m), dts (B, K), same_group, out_c, out_P, out_mu."""
    kernel = imm_kernel("imm_run_batch", measurement)

    def run(*args):
        run_on_threads(kernel, args, (1, 2, 7, 8, 10, 11, 12), args[7].shape[0])

    return run
