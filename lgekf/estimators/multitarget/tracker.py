"""Multi-target tracking from unlabelled detections in clutter: ``MultiTargetTracker``.

One call ``step(t, detections)`` per scan (all detections of one time):

1. **predict** every track to t (``ModelBank.predict``: the model's fused LG-EKF prediction) and its
   existence r ← p_S r (``survival_prob`` per scan);
2. **gate** every track × detection with the model's innovation covariance S = ℋPℋᵀ + R
   (``lgekf.estimators.multitarget.gating``: d² ≤ γ, γ the χ²_m quantile of ``gate_prob``);
3. **associate** (``lgekf.estimators.multitarget.association``): PDA, JPDA (JIPDA: joint events with existence) or
   GNN marginals from the weights w0_i = 1 − r_i P_D P_G and W_ij = r_i P_D N(e_ij; 0, S_i)/κ_j, κ_j the
   clutter density at detection j (λ per m² per scan for position; λ/(2π) per m²·rad for pose), from the
   tracker's clutter component (``lgekf.estimators.multitarget.clutter``: a given constant, or estimated per scan
   from Σ_i P_D P_G r_i of the predicted tracks, or a spatial map; after the association it gets each detection's
   probability of not being a confirmed track's);
4. **update** the existence r_i⁺ = Σ_j p_ij + p_i0 r_i(1 − P_D P_G)/w0_i (integrated track existence,
   IPDA/JIPDA) and the state by the PDA correction on the group (``lgekf.estimators.multitarget.pda``:
   μ ← μ·exp(ν), P ← Φ(ν) P_c Φ(ν)ᵀ);
5. **manage tracks** (the choice: integrated track existence, not M-of-N):

   * a track is *confirmed* the first time r ≥ ``confirm_existence`` (default 0.9) and from then on
     *reported* in every scan with r ≥ ``report_existence`` (default 0.5);
   * a track is *deleted* when r < ``delete_existence`` (default 0.01);
   * *initiation* from the *unused* detections, those no track claims (Σ_i p_ij < 0.5), by one of two rules
     (``initiation``; default one-point with JPDA and GNN, two-point with PDA: what measured better,
     docs/multi_target.md):

     - **one-point**: every unused detection starts a track at once (``one_point_prior``): position the
       detection's (variance r² per axis), velocity zero with std σ_v = ``speed_std`` per axis (default
       ``max_speed``/3: an object moving at ``max_speed`` lands 3σ_v away at its second detection, at the edge
       of the default 99 % gate), the direction of motion unknown, ω = 0 with std ``omega_std``; any model's x0
       and P0 from these through its own ``common_to_state`` / ``common_jacobian``
       (``lgekf.core.initiation.initial_estimates``). Its existence is r₀ = β/(β + λ)
       (``one_point_existence``) for a density β of new objects' first detections (``birth_density``, per
       m² per scan) against the clutter density λ, or ``birth_existence`` (default 0.02) without β. The
       existence recursion of step 4 then confirms or deletes it. At the first detection it *holds* (β_ij ≥
       0.5, ``held``) after the one that started it, its state is started again by the two-point rule from
       those two detections (id, existence and confirmation kept): the zero-velocity prior has no heading, and
       a model whose heading is its direction of motion (CTRV, SE(2)×R²) cannot turn its heading from it by
       the linearised update, while SE(2)×SE(2) and SE(2)×R³ would keep an arbitrary body heading θ
       (measured: docs/multi_target.md);
     - **two-point** (the rule of ``lgekf track``, ``lgekf.core.initiation.two_point``): each unused
       detection of this scan is paired with the nearest unused detection of the previous ``seed_scans``
       scans (default 1: the previous scan only) within ``max_speed``·Δt + 3√2 r (each used once, nearest
       pairs first) and starts a track with existence ``birth_existence`` (default 0.1), position from this
       detection and velocity from the pair; unpaired unused detections wait up to ``seed_scans`` scans.

   Every track gets a unique integer id (0, 1, 2, ... in order of initiation), never reused.

The per-track filters are a ``TrackFilterBank`` (``lgekf.estimators.multitarget.bank``): ``ModelBank`` for any
registry model, or with ``model="imm"`` an ``IMMBank`` (``lgekf.estimators.multitarget.imm_bank``: an IMM of
``imm_modes`` per track, the mode-mixed likelihood in the association, the IMM-PDA correction; its states are the
combined estimate in the common coordinates x, y, θ, v_x, v_y, ω, as ``lgekf track --model imm`` reports); any other
bank implementing the same calls plugs in unchanged (``bank=`` argument).

With r ≈ 1, P_D P_G ≈ 1 and no clutter the JPDA/PDA update is the ordinary LG-EKF update (tests).

``association="pmbm"`` replaces steps 3–5 by the Poisson multi-Bernoulli mixture filter
(``lgekf.estimators.multitarget.pmbm``): each bank row is a local hypothesis of a Bernoulli (a track id), global
hypotheses per cluster by Murty's k best assignments (``murty.py``), births from its Poisson part (one-point
priors); the prediction, the gates and likelihoods, the clutter component and the one-point restart are this
tracker's.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numba as nb
import numpy as np

from ...core.initiation import DEFAULT_HEADING_STD, DEFAULT_OMEGA_STD, initial_estimates, two_point
from ...core.registry import DEFAULT_SPACE, SPACES, get_measurement, get_model, rotation_dims, space_of_positions
from ...core.validate import positive_scalar
from .association import association_marginals, association_weights, existence_and_weights
from .bank import ModelBank, TrackFilterBank
from .clutter import ClutterEstimator, ConstantClutter, clutter_estimator
from .gating import gate_threshold
from .jpda import MAX_EVENTS
from .pmbm import PMBM
from .settings import (ASSOCIATIONS, BIRTH_EXISTENCE, DEFAULT_INITIATION, INITIATIONS, PMBM_DEFAULTS,
                       SPEED_STD_FRACTION)

__all__ = ["MultiTargetTracker", "ScanReport", "Track", "ASSOCIATIONS", "IMM_MODEL", "HEADING_CAP", "INITIATIONS", "DEFAULT_INITIATION", "BIRTH_EXISTENCE",
           "SPEED_STD_FRACTION", "one_point_prior", "one_point_existence", "attitude_volume"]

IMM_MODEL = "imm"  # ``model`` of a tracker whose per-track filters are IMMs (``IMMBank``)
HEADING_CAP = 0.3  # initial heading std cap (rad), as `lgekf track` (TRACK_HEADING_CAP; see lgekf.apps.track)
UNUSED_BELOW = 0.5  # a detection with Σ_i p_ij below this is unused (can start a track)
HELD_FROM = 0.5  # a track holds detection j when β_ij (the probability that j is its, given that it exists) ≥ this


@nb.njit(cache=True)
def nearest_pairs(new, old, reach, dim):
    """Greedy nearest pairs (i of ``new``, j of ``old``) with distance ≤ reach[j], nearest first, each point used
    at most once; new (A, ≥dim), old (B, ≥dim) positions in the first ``dim`` columns (2 in the plane, 3 in 3-D
    space). Returns (K, 2) indices."""
    A, B = new.shape[0], old.shape[0]
    ci = np.empty(A * B, dtype=np.int64)
    cj = np.empty(A * B, dtype=np.int64)
    cd = np.empty(A * B)
    k = 0
    for i in range(A):
        for j in range(B):
            d2 = 0.0
            for c in range(dim):
                dc = new[i, c] - old[j, c]
                d2 += dc * dc
            if d2 <= reach[j] * reach[j]:
                ci[k] = i
                cj[k] = j
                cd[k] = d2
                k += 1
    order = np.argsort(cd[:k], kind="mergesort")
    used_i = np.zeros(A, dtype=np.bool_)
    used_j = np.zeros(B, dtype=np.bool_)
    out = np.empty((min(A, B), 2), dtype=np.int64)
    n = 0
    for o in order:
        i, j = ci[o], cj[o]
        if not used_i[i] and not used_j[j]:
            used_i[i] = True
            used_j[j] = True
            out[n, 0] = i
            out[n, 1] = j
            n += 1
    return out[:n]


def attitude_volume(space: str) -> float:
    """The volume of the rotations of ``space`` in the measure of their tangent coordinates (the Haar measure that is
    the Lebesgue measure at the identity): the plane's SO(2) 2π (the heading angle); 3-D space's SO(3) 8π²
    (rotation vectors in the ball |φ| ≤ π with density 2(1 − cos|φ|)/|φ|²: 4π ∫₀^π 2(1 − cos r) dr = 8π²). A
    clutter pose uniform in attitude has the density 1/volume there (κ = λ/volume, ``MultiTargetTracker``)."""
    r = rotation_dims(space)
    return {1: 2.0 * math.pi, 3: 8.0 * math.pi**2}[r]


def one_point_prior(Z: np.ndarray, pos_std: float, speed_std: float, omega_std: float, heading_std: float, dim: int = 2):
    """The one-point prior of a track started by each detection of Z (B, m) (rows of ``dim`` position coordinates,
    then a pose's attitude), in the common coordinates of the space of its positions (``derive/space.py``: position,
    attitude, body-frame velocity, rate; the plane c = (x, y, θ, v_x, v_y, ω), 3-D space c = (x, y, z, roll, pitch,
    yaw, v_x, v_y, v_z, ω_x, ω_y, ω_z)) with diagonal variances:

    * the position the detection's, variance r² each (r = ``pos_std``);
    * the velocity 0, variance σ_v² each (σ_v = ``speed_std``): an isotropic velocity, the direction of motion
      unknown;
    * the rate 0, variance σ_ω² each (``omega_std``);
    * the attitude: a pose detection's (each angle wrapped to (−π, π]) with variance ``heading_std``²; from a
      position detection 0 with variance ``HEADING_CAP``² each. With zero speed θ is no direction of motion: a model
      whose heading is its direction of motion (``ModelSpec.forward_speed``: CTRV's ψ, SE(2)×R²'s θ) gets
      heading variance π² from the isotropic velocity (``initial_estimates`` takes the Jacobian just off
      speed 0 and caps an angle's variance at π²), and SE(2)×SE(2) / SE(2)×R³, whose body velocity (v_x, v_y)
      is free in direction, carry the unknown direction in it, θ being the orientation of the body frame.

    Returns c (B, n_c) and var (B, n_c), n_c = 6 in the plane, 12 in 3-D (``lgekf.core.initiation.initial_estimates``
    makes any model's x0, P0 of them).
    """
    Z = np.asarray(Z, dtype=float)
    B = Z.shape[0]
    d = int(dim)
    a = rotation_dims(space_of_positions(d))  # attitude (and rate) coordinates: 1 in the plane, 3 in 3-D
    c = np.zeros((B, 2 * (d + a)))
    c[:, :d] = Z[:, :d]
    var = np.empty((B, 2 * (d + a)))
    var[:, :d] = pos_std**2
    var[:, d + a:2 * d + a] = speed_std**2
    var[:, 2 * d + a:] = omega_std**2
    if Z.shape[1] > d:
        c[:, d:d + a] = np.arctan2(np.sin(Z[:, d:d + a]), np.cos(Z[:, d:d + a]))
        var[:, d:d + a] = heading_std**2
    else:
        var[:, d:d + a] = HEADING_CAP**2
    return c, var


def one_point_existence(birth_density: float, clutter_density: float) -> float:
    """The existence of a one-point track: r₀ = β/(β + λ).

    A detection that no track claims is either a new object's first detection or a false alarm; with both
    independent Poisson processes, of densities β (``birth_density``) and λ (``clutter_density``, per m² per
    scan), it is a new object's with probability β/(β + λ). (With pose detections both are spread uniformly in
    heading: the 2π cancels.)"""
    return birth_density / (birth_density + clutter_density)


@dataclass
class ScanReport:
    """The confirmed tracks after one scan.

    Attributes
    ----------
    t : float
        Scan time.
    ids : ndarray of int, (K,)
        Track ids.
    states : ndarray, (K, n)
        Physical states (the model's ``state_names``; the IMM: its combined estimate in the common coordinates).
    stds : ndarray, (K, n)
        Std of each tangent coordinate (square roots of P's diagonal; the IMM: of the common coordinates).
    existence : ndarray, (K,)
        Existence probabilities (the PMBM: marginalised over its global hypotheses, r̄).
    mu : ndarray, (K, M) or None
        The IMM's mode probabilities (``model="imm"``), else None.
    """

    t: float
    ids: np.ndarray
    states: np.ndarray
    stds: np.ndarray
    existence: np.ndarray
    mu: np.ndarray | None = None


@dataclass
class Track:
    """One track's history: the scans at which it was reported (confirmed, existence ≥ ``report_existence``).

    Attributes
    ----------
    id : int
        The track id (as in ``ScanReport.ids`` and the ``id`` column of ``lgekf track --multi``).
    t : ndarray, (K,)
        Scan times.
    states : ndarray, (K, n)
        Physical states (the model's ``state_names``).
    covariances : ndarray, (K, n, n)
        Covariances in the tangent of each scan's mean (right perturbation X = μ·exp(ε), the model's tangent order;
        the IMM: the combined covariance in the common coordinates; the square roots of their diagonals are
        ``ScanReport.stds``).
    existence : ndarray, (K,)
        Existence probabilities.
    """

    id: int
    t: np.ndarray
    states: np.ndarray
    covariances: np.ndarray
    existence: np.ndarray


class MultiTargetTracker:
    """Track many objects from unlabelled detections with clutter and misses (module docstring).

    Parameters
    ----------
    model : str
        A registry model (``se2se2``, ``se2r3``, ``se2r2``, ``ctrv``, ``cv``, ...), or ``"imm"`` (``IMM_MODEL``):
        an IMM of ``imm_modes`` per track (``IMMBank``); its states, stds and covariances are the combined
        estimate in the common coordinates (x, y, θ, v_x, v_y, ω).
    association : {"jpda", "jpdastar", "pda", "gnn", "pmbm"}
        JPDA (JIPDA; exact joint events up to ``max_events`` per cluster, loopy belief propagation beyond),
        JPDA* (JPDA with only the most probable of the events that permute the same detections among the same
        tracks: no coalescence of close tracks; ``lgekf.estimators.multitarget.association``), PDA per track, global
        nearest neighbour, or the Poisson multi-Bernoulli mixture filter (``lgekf.estimators.multitarget.pmbm``: multiple
        hypotheses, Murty's k best assignments; its births are its Poisson part's, one-point).
    detection_prob : float
        P_D in (0, 1].
    clutter_density : float, str or ClutterEstimator
        λ > 0, expected false alarms per m² (per m³ in 3-D) per scan, the same in every scan and place; or "scan" (estimated per
        scan), "map" (a spatial clutter map times the per-scan level), or an estimator of
        ``lgekf.estimators.multitarget.clutter`` (the tracker uses an unused copy of it: ``fresh``).
    meas_std : float or tuple
        Position noise std r (m), or (r_x, r_y, r_θ) for pose measurements ((r_p, r_a) for pose3).
    accel_std : tuple, optional
        The model's process-noise stds (default the model's ``default_accel_std``); not with ``"imm"`` (each
        mode's noise is in ``imm_modes``).
    measurement : {"position", "pose", "position3", "pose3"}
        Detections (x, y) or (x, y, θ); in 3-D space (a model of that space) "position3", (x, y, z), or "pose3",
        (x, y, z, roll, pitch, yaw). The clutter density is then per m³ per scan.
    gate_prob : float
        P_G: the gate is d² ≤ the χ²_m quantile of P_G.
    survival_prob : float
        Probability that a target survives one scan.
    birth_existence : float, optional
        Existence probability r₀ of a new track (default ``BIRTH_EXISTENCE`` of the initiation: 0.02 one-point,
        0.1 two-point); not with ``birth_density``.
    confirm_existence, report_existence, delete_existence : float
        Existence probability of confirmation, of reporting a confirmed track, of deletion.
    max_speed : float
        Speed scale of new tracks (m/s): two-point, the largest speed of the two detections that start a track;
        one-point, 3× the default ``speed_std``.
    initiation : {"one-point", "two-point"}, optional
        How tracks start (module docstring); default ``DEFAULT_INITIATION[association]`` (one-point with JPDA and
        GNN, two-point with PDA).
    speed_std : float, optional
        One-point: the std σ_v (m/s) of each velocity component of a new track's prior (default
        ``max_speed``/3).
    birth_density : float, optional
        One-point: β, new objects' first detections per m² per scan; a new track's existence is then
        r₀ = β/(β + λ) (``one_point_existence``) instead of ``birth_existence``.
    omega_std : float
        Initial turn-rate std (rad/s) of a new track.
    max_events : int
        JPDA: clusters with more joint events use loopy belief propagation.
    seed_scans : int
        Two-point: how many scans an unused detection waits for a partner (1: consecutive detections only; 2
        tolerates one missed detection at the start, at the price of more false tracks).
    bank : TrackFilterBank, optional
        The per-track filters (default a ``ModelBank`` of ``model``); e.g. an IMM bank.
    history : bool
        Keep every reported track's states, covariances and existence scan by scan (``tracks()``).
    imm_modes : str or list, optional
        ``model="imm"``: the modes (``lgekf.estimators.imm.parse_modes`` syntax or ``Mode`` objects, at least two;
        default ``DEFAULT_MODES``, the modes of ``lgekf track --model imm``: CV and a calm and a manoeuvring
        SE(2)×R³).
    imm_switch : float, optional
        ``model="imm"``: the probability of leaving a mode per scan (default ``DEFAULT_SWITCH``, 0.05).
    max_hypotheses : int, optional
        PMBM: at most this many global hypotheses per cluster of interacting tracks, and N_h of the k-best rule (a
        global hypothesis of weight w gets its ⌈N_h w⌉ best assignments); default 50.
    hypothesis_prune : float, optional
        PMBM: global hypotheses of normalised weight below this are dropped (default 1e-3).

    Attributes
    ----------
    held : (ndarray of int, ndarray of int)
        After each ``step``: the ids of the tracks that *hold* a detection of that scan and its row in the
        scan's detections: β_ij ≥ ``HELD_FROM`` (0.5), the probability that detection j is track i's given that
        the track exists (at most one detection per track; e.g. the sequences ``lgekf track --multi``
        estimates the noise from).
    held_nis : ndarray, (H,)
        After each ``step``: the normalised innovation squared d² = eᵀS⁻¹e of each held detection against its
        track's prediction (the order of ``held``; what a divergence monitor tests).
    max_existence : float
        The largest existence probability any track has had after an update (or at its start).
    initiation : str
        The initiation in use ("one-point" or "two-point").
    r_birth : float
        The existence probability r₀ of a new track (with ``birth_density`` and an estimated clutter density:
        β/(β + λ) at the last scan's mean level λ; each new track gets β/(β + λ(z)) at its detection z).
    clutter : ClutterEstimator
        The clutter component (``lgekf.estimators.multitarget.clutter``).
    clutter_density : float
        The mean clutter density of the last scan (``clutter.level``; the given one when constant).
    speed_std : float
        One-point: the std σ_v (m/s) of each velocity component of a new track's prior.
    next_id : int
        The number of tracks started so far (the next track's id).

    Examples
    --------
    >>> trk = MultiTargetTracker(model="cv", clutter_density=1e-4, meas_std=0.3, detection_prob=0.9)
    >>> for k in range(6):
    ...     rep = trk.step(0.1 * k, np.array([[1.0 * k * 0.1, 0.0], [50.0, 0.5 * k * 0.1]]))
    >>> sorted(rep.ids.tolist()), bool(np.all(rep.existence > 0.9))
    ([0, 1], True)
    """

    def __init__(self, model: str, association: str = "jpda", detection_prob: float = 0.9,
                 clutter_density: float | str | ClutterEstimator = 1e-4, meas_std=0.3, accel_std=None,
                 measurement: str = "position",
                 gate_prob: float = 0.99, survival_prob: float = 0.99, birth_existence: float | None = None,
                 confirm_existence: float = 0.9, report_existence: float = 0.5, delete_existence: float = 0.01,
                 max_speed: float = 30.0, omega_std: float = DEFAULT_OMEGA_STD, max_events: int = MAX_EVENTS,
                 seed_scans: int = 1, bank: TrackFilterBank | None = None, initiation: str | None = None,
                 speed_std: float | None = None, birth_density: float | None = None, history: bool = False,
                 imm_modes=None, imm_switch: float | None = None, max_hypotheses: int | None = None,
                 hypothesis_prune: float | None = None):
        if model == IMM_MODEL:
            if accel_std is not None:
                raise ValueError("accel-std: not with the IMM; give each mode's noise in the modes (e.g. "
                                 "se2r3:0.2/0.2/0.5)")
            spec, meas = None, get_measurement(measurement)
            if meas.space != DEFAULT_SPACE:  # the IMM bank (imm_bank.py) runs the plane's loop (yet)
                raise ValueError(f"measurement: the multi-target IMM runs in the plane only (yet); {measurement} observes "
                                 f"{meas.space} space")
        else:
            if imm_modes is not None or imm_switch is not None:
                raise ValueError("imm-modes/imm-switch: only with the IMM (model imm)")
            spec = get_model(model)
            meas = spec.measurement(measurement)
        if association not in ASSOCIATIONS:
            raise ValueError(f"association: unknown method {association!r}; choose one of {', '.join(ASSOCIATIONS)}")
        initiation = DEFAULT_INITIATION[association] if initiation is None else initiation
        if initiation not in INITIATIONS:
            raise ValueError(f"initiation: unknown method {initiation!r}; choose one of {', '.join(INITIATIONS)}")
        if association == "pmbm":
            if initiation != "one-point":
                raise ValueError("initiation: the PMBM starts targets from its Poisson part (one-point); "
                                 f"{initiation} is not available with it")
            max_hypotheses = PMBM_DEFAULTS["max_hypotheses"] if max_hypotheses is None else max_hypotheses
            hypothesis_prune = PMBM_DEFAULTS["hypothesis_prune"] if hypothesis_prune is None else hypothesis_prune
            if isinstance(max_hypotheses, bool) or not float(max_hypotheses).is_integer() or max_hypotheses < 1:
                raise ValueError(f"max-hypotheses: must be a positive integer, got {max_hypotheses}")
            positive_scalar("hypothesis-prune", hypothesis_prune)
            if hypothesis_prune >= 1:
                raise ValueError(f"hypothesis-prune: must be a weight in (0, 1), got {hypothesis_prune}")
        elif max_hypotheses is not None or hypothesis_prune is not None:
            raise ValueError("max-hypotheses/hypothesis-prune: only with the PMBM (association pmbm)")
        one_point = initiation == "one-point"
        if not one_point:
            for name, v in (("birth-density", birth_density), ("speed-std", speed_std)):
                if v is not None:
                    raise ValueError(f"{name}: only with one-point initiation (initiation is {initiation})")
        elif seed_scans != 1:
            raise ValueError(f"seed-scans: only with two-point initiation (initiation is {initiation})")
        if birth_density is not None and birth_existence is not None:
            raise ValueError("birth-density: not with birth-existence (β sets a new track's existence, β/(β + λ))")
        if birth_existence is None:
            birth_existence = BIRTH_EXISTENCE[initiation]
        for name, v in (("detection-prob", detection_prob), ("gate-prob", gate_prob), ("survival-prob", survival_prob),
                        ("birth-existence", birth_existence), ("confirm-existence", confirm_existence),
                        ("report-existence", report_existence), ("delete-existence", delete_existence)):
            positive_scalar(name, v)
            if v > 1:
                raise ValueError(f"{name}: must be a probability in (0, 1], got {v}")
        self.clutter = clutter_estimator(clutter_density)
        self.clutter_density = self.clutter.level
        constant = isinstance(self.clutter, ConstantClutter)
        self.max_speed = positive_scalar("max-speed", max_speed)
        self.omega_std = positive_scalar("omega-std", omega_std)
        self.initiation = initiation
        self.speed_std = (SPEED_STD_FRACTION * self.max_speed if speed_std is None
                          else positive_scalar("speed-std", speed_std))
        if birth_density is not None:
            birth_density = positive_scalar("birth-density", birth_density)
            if constant:
                birth_existence = one_point_existence(birth_density, self.clutter_density)
        self.birth_density = birth_density
        self._birth_per_detection = birth_density is not None and not constant  # r₀ = β/(β + λ(z)) at each start
        r = np.atleast_1d(np.asarray(meas_std, dtype=float))
        if r.size == 1:
            r = np.full(len(meas.noise_names), r[0])
        if r.size != len(meas.noise_names) or not np.all(np.isfinite(r)) or np.any(r <= 0):
            raise ValueError(f"meas-std: {measurement} takes {len(meas.noise_names)} positive value(s) "
                             f"({', '.join(meas.noise_names)}), got {np.asarray(meas_std).tolist()}")
        if spec is not None:
            q = spec.default_accel_std if accel_std is None else accel_std
            q = np.atleast_1d(np.asarray(q, dtype=float))
            if q.size != len(spec.noise_names) or not np.all(np.isfinite(q)) or np.any(q < 0):
                raise ValueError(f"accel-std: {model} takes {len(spec.noise_names)} non-negative value(s) "
                                 f"({', '.join(spec.noise_names)}), got {np.asarray(accel_std).tolist()}")
        self.model, self.measurement, self.association = model, measurement, association
        self.spec, self.meas = spec, meas
        self.pd, self.pg, self.ps = float(detection_prob), float(gate_prob), float(survival_prob)
        self.r_birth, self.r_confirm = float(birth_existence), float(confirm_existence)
        self.r_report, self.r_delete = float(report_existence), float(delete_existence)
        self.meas_std = r
        self.dim = SPACES[meas.space]["dim"]  # the detections' position coordinates (their first columns)
        std_of = meas.noise_inputs if meas.noise_inputs is not None else tuple(range(meas.dim))
        self.pos_std = float(np.sqrt(np.mean(r[list(std_of[:self.dim])] ** 2)))
        self.angle_std = float(r[std_of[meas.angles[0]]]) if meas.angles else DEFAULT_HEADING_STD
        self.max_events = int(max_events)
        # κ = λ / volume of the attitudes (clutter uniform in heading or attitude: ``attitude_volume``); 1 for positions
        self.angle_volume = attitude_volume(meas.space) if meas.angles else 1.0
        self.kappa = self.clutter_density / self.angle_volume
        self.gamma = gate_threshold(self.pg, meas.dim)
        # a held track's gate radius (S ≈ 2R), and the positions' coordinates: the clutter density is per m^dim
        self.clutter.configure(math.sqrt(2.0 * self.gamma) * self.pos_std, self.dim)
        if bank is None and spec is None:
            from ..imm.estimator import DEFAULT_MODES, DEFAULT_SWITCH
            from .imm_bank import IMMBank

            bank = IMMBank(DEFAULT_MODES if imm_modes is None else imm_modes, measurement, r,
                           DEFAULT_SWITCH if imm_switch is None else imm_switch)
        self.bank = bank if bank is not None else ModelBank(model, measurement, q, r)
        cap = self.bank.live.size
        self.r = np.zeros(cap)
        self.ids = np.full(cap, -1, dtype=np.int64)
        self.confirmed = np.zeros(cap, dtype=bool)
        self.history = {} if history else None  # id -> [(t, state, covariance, existence), ...]
        self._recorded = None  # the last scan time recorded (report() may be called more than once per scan)
        self.first_t = np.zeros(cap)  # one-point: the time and detection that started a track still on its prior
        self.first_z = np.zeros((cap, meas.dim))
        self.on_prior = np.zeros(cap, dtype=bool)
        self.next_id = 0
        self.t = None
        self.seeds = np.zeros((0, meas.dim))
        self.seed_t = np.zeros(0)
        self.seed_scans = int(seed_scans)
        if self.seed_scans < 1:
            raise ValueError(f"seed-scans: must be at least 1, got {seed_scans}")
        self._scan_times = []
        self.last_exact = True
        self.held = (np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64))
        self.held_nis = np.zeros(0)
        self.max_existence = 0.0
        self.pmbm_r0 = self.r_birth  # the PMBM's steady-state new-Bernoulli existence without birth_density
        self.pmbm = (PMBM(self, int(max_hypotheses), float(hypothesis_prune), 0.0 if birth_density is None else birth_density)
                     if association == "pmbm" else None)

    # ------------------------------------------------------------------ one scan
    def step(self, t: float, detections) -> ScanReport:
        """Process the scan at time t with its detections (M, m) (rows (x, y) or (x, y, θ); in 3-D (x, y, z) or
        (x, y, z, roll, pitch, yaw)); M may be 0.

        Parameters
        ----------
        t : float
            Scan time in seconds, increasing from call to call.
        detections : array_like, (M, m)
            The scan's detections, unlabelled.

        Returns
        -------
        ScanReport
            The confirmed tracks after the scan.
        """
        Z = np.ascontiguousarray(detections, dtype=float)
        if Z.size == 0:
            Z = np.zeros((0, self.meas.dim))
        elif Z.ndim != 2 or Z.shape[1] != self.meas.dim:
            raise ValueError(f"detections at t = {t}: expected shape (M, {self.meas.dim}) ({', '.join(self.meas.z_names)}), "
                             f"got {Z.shape}")
        if not np.all(np.isfinite(Z)):
            raise ValueError(f"detections at t = {t}: contain NaN or infinite values")
        t = float(t)
        dt = 0.0 if self.t is None else t - self.t
        if self.t is not None and not dt > 0:
            raise ValueError(f"scan times must increase: t = {t} after {self.t}")
        bank = self.bank
        self._sync()
        live = bank.live
        M = Z.shape[0]
        claimed = np.zeros(M)
        restart = (np.zeros(0, dtype=np.int64), Z[:0])
        self.held = (np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64))
        self.held_nis = np.zeros(0)
        if live.any():
            bank.predict(dt)
            self.r[live] *= self.ps
        if self.pmbm is not None:
            return self._step_pmbm(t, Z)
        lam = self._clutter_at(t, Z, float(self.r[live].sum()) * self.pd * self.pg)
        not_confirmed = np.ones(M)  # each detection's probability of not being a confirmed track's
        if live.any():
            ll, gated = bank.gate(Z, self.gamma)
            N = live.size
            w0 = np.empty(N)
            W = np.empty((N, M))
            association_weights(ll, gated, live, self.r, self.pd, self.pg, self.kappa, w0, W)
            if np.ndim(lam):  # λ(z_j): W_ij ∝ 1/λ(z_j), computed above with the scan's mean level
                W *= self.clutter_density / lam[None, :]
            p0, P, exact = association_marginals(self.association, w0, W, gated, live, self.max_events, self.r)
            self.last_exact = bool(exact[live].all())
            beta0 = np.ones(N)
            beta = np.zeros((N, M))
            r_new = self.r.copy()
            existence_and_weights(p0, P, w0, self.r, live, self.pd, self.pg, r_new, beta0, beta)
            bank.update(beta0, beta)
            self.r = r_new
            rows = np.flatnonzero(live)
            self.max_existence = max(self.max_existence, float(np.max(r_new[rows])))
            if M:
                best = np.argmax(beta[rows], axis=1)
                ok = beta[rows, best] >= HELD_FROM
                self.held = (self.ids[rows[ok]].copy(), best[ok])
                self.held_nis = bank.d2[rows[ok], best[ok]].copy()
                fresh = ok & self.on_prior[rows]
                restart = (rows[fresh], Z[best[fresh]])
            claimed = P[live].sum(axis=0)
            self.confirmed |= live & (self.r >= self.r_confirm)
            not_confirmed -= P[live & self.confirmed].sum(axis=0)
            dead = np.flatnonzero(live & ((self.r < self.r_delete) | ~np.isfinite(self.r)))
            if dead.size:
                bank.remove(dead)
                self.ids[dead] = -1
                self.confirmed[dead] = False
                self.on_prior[dead] = False
                self.r[dead] = 0.0
            still = bank.live[restart[0]]
            if still.any():
                self._restart(restart[0][still], restart[1][still], t)  # after all that is indexed by this scan's rows
        self.clutter.update(Z, not_confirmed)
        unused = claimed < UNUSED_BELOW
        r0 = None
        if self._birth_per_detection:  # β/(β + λ(z)) at each new track's detection
            self.r_birth = one_point_existence(self.birth_density, self.clutter_density)
            r0 = one_point_existence(self.birth_density, lam[unused] if np.ndim(lam) else np.full(int(unused.sum()), lam))
        self._initiate(t, dt, Z[unused], r0)
        self.t = t
        return self.report()

    def _step_pmbm(self, t, Z):
        """The PMBM update of the predicted tracks (``lgekf.estimators.multitarget.pmbm``): the Poisson part predicted
        with its birth β (``birth_density``, or without it β = λ r₀/(1 − r₀)·(1 − p_S(1 − P_D))/P_D at the scan's
        clutter level λ: the steady-state new Bernoulli then has existence r₀ = ``birth_existence``), the clutter
        from the best global hypothesis's expected detections, the update, the held detections of the best global
        hypothesis."""
        pm, bank = self.pmbm, self.bank
        lam = self._clutter_at(t, Z, float(pm.best_existence().sum()) * self.pd * self.pg)
        if self.birth_density is None:
            r0 = self.pmbm_r0
            pm.birth = self.clutter_density * r0 / (1.0 - r0) * (1.0 - self.ps * (1.0 - self.pd)) / self.pd
        pm.predict_poisson()
        M = Z.shape[0]
        N = bank.live.size
        if bank.live.any():
            ll, gated = bank.gate(Z, self.gamma)
            d2 = bank.d2
        else:
            ll, gated, d2 = np.full((N, M), -np.inf), np.zeros((N, M), dtype=bool), np.full((N, M), np.inf)
        ids, dets, nis = pm.scan(t, Z, lam, ll, gated, d2)
        self.held, self.held_nis = (ids, dets), nis
        self.r_birth = one_point_existence(pm.e_last, self.clutter_density)  # this scan's e/(e + λ)
        not_confirmed = np.ones(M)
        conf = np.isin(ids, np.fromiter(pm.confirmed_ids, dtype=np.int64, count=len(pm.confirmed_ids)))
        not_confirmed[dets[conf]] = 0.0
        self.clutter.update(Z, not_confirmed)
        live = bank.live
        if live.any():
            self.max_existence = max(self.max_existence, float(self.r[live].max()))
        self.t = t
        return self.report()

    def _clutter_at(self, t, Z, expected):
        """λ of this scan at its detections Z (a float or (M,)) from the clutter component, given the expected
        number of track detections; the tracker's ``clutter_density`` and ``kappa`` (the mean level)."""
        lam = self.clutter.density(t, Z, expected)
        level = self.clutter.level
        if not (np.all(np.isfinite(lam)) and np.all(np.asarray(lam) > 0) and math.isfinite(level) and level > 0):
            raise ValueError(f"clutter density at t = {t}: the {self.clutter.name} estimate is not a positive number "
                             f"({level}); give a clutter density")
        self.clutter_density = level
        self.kappa = level / self.angle_volume
        return lam

    def _sync(self):
        """Grow the per-track arrays when the bank has grown."""
        cap = self.bank.live.size
        if self.r.size < cap:
            k = cap - self.r.size
            self.r = np.concatenate([self.r, np.zeros(k)])
            self.ids = np.concatenate([self.ids, np.full(k, -1, dtype=np.int64)])
            self.confirmed = np.concatenate([self.confirmed, np.zeros(k, dtype=bool)])
            self.first_t = np.concatenate([self.first_t, np.zeros(k)])
            self.first_z = np.vstack([self.first_z, np.zeros((k, self.first_z.shape[1]))])
            self.on_prior = np.concatenate([self.on_prior, np.zeros(k, dtype=bool)])

    def _initiate(self, t, dt, unused, r0=None):
        """New tracks from this scan's unused detections (Z rows (U, m)) by the tracker's ``initiation``; r0 (U,):
        one-point, their existences (default ``r_birth``)."""
        if self.initiation == "one-point":
            self._one_point(t, unused, r0)
        else:
            self._two_point(t, dt, unused)

    def _start(self, x0, P0, r0=None):
        """Tracks at x0 (B, n), P0 (B, n, n): tentative, existence r0 (B,) (default ``r_birth``), the next ids;
        returns their rows."""
        B = x0.shape[0]
        rows = self.bank.add(x0, P0)
        self._sync()
        self.r[rows] = self.r_birth if r0 is None else r0
        self.ids[rows] = np.arange(self.next_id, self.next_id + B)
        self.next_id += B
        self.confirmed[rows] = False
        self.on_prior[rows] = False
        return rows

    def _pair_estimates(self, t0, z0, t1, z1):
        """x0, P0 (B, n), (B, n, n) of the two-point rule from detections z0 (B, m) at times t0 (B,) to z1 at t1:
        position z1's, velocity (z1 − z0)/(t1 − t0), variances of ``lgekf.core.initiation.two_point`` (heading std
        capped at ``HEADING_CAP``; a pose detection's heading, or attitude in 3-D, from z1)."""
        B = z0.shape[0]
        d = self.dim
        tt = np.concatenate([t0, t1])
        zz = np.concatenate([z0, z1])
        heading = zz[:, d:] if self.meas.angles else None  # the plane's heading (N, 1), 3-D roll, pitch, yaw (N, 3)
        c, var = two_point(tt, np.ascontiguousarray(zz[:, :d]), np.arange(B, 2 * B), self.pos_std, self.omega_std,
                           heading, self.angle_std, HEADING_CAP, first=np.arange(B))
        return self._initial(c, var)

    def _initial(self, c, var):
        """x0 (B, n), P0 (B, n, n) of the bank from common coordinates c (B, n_c) and their variances (B, n_c): the
        model's (``initial_estimates``); the IMM's bank takes the common coordinates themselves (each mode converts
        them, ``IMMBank.add``)."""
        if self.spec is None:
            return c, var[:, :, None] * np.eye(c.shape[1])
        return initial_estimates(self.model, c, var)

    def _one_point_estimates(self, Z):
        """x0, P0 of the bank from the one-point prior (``one_point_prior``) at each detection of Z (U, m)."""
        return self._initial(*one_point_prior(Z, self.pos_std, self.speed_std, self.omega_std, self.angle_std, self.dim))

    def _one_point(self, t, unused, r0=None):
        """A track from each unused detection (U, m): ``one_point_prior``, existence r0 (U,) (default ``r_birth``);
        the detection and t are kept for the restart at its first held detection."""
        if unused.shape[0] == 0:
            return
        rows = self._start(*self._one_point_estimates(unused), r0)
        self.max_existence = max(self.max_existence, self.r_birth if r0 is None else float(np.max(r0)))
        self.first_t[rows] = t
        self.first_z[rows] = unused
        self.on_prior[rows] = True

    def _restart(self, rows, z, t):
        """One-point tracks (``rows``) holding their first detection since the one that started them: their states
        started again by the two-point rule from that detection to z (B, m) at t; id, existence and confirmation
        kept. Through the bank's ``remove`` / ``add`` (its interface), which may give other rows."""
        x0, P0 = self._pair_estimates(self.first_t[rows], self.first_z[rows], np.full(rows.size, t), z)
        kept = (self.r[rows].copy(), self.ids[rows].copy(), self.confirmed[rows].copy())
        self.bank.remove(rows)
        self.r[rows], self.ids[rows], self.confirmed[rows], self.on_prior[rows] = 0.0, -1, False, False
        new = self.bank.add(x0, P0)
        self._sync()
        self.r[new], self.ids[new], self.confirmed[new] = kept
        self.on_prior[new] = False

    def _two_point(self, t, dt, unused):
        """Two-point initiation from this scan's unused detections and those of the previous ``seed_scans`` scans
        (module docstring)."""
        self._scan_times = (self._scan_times + [t])[-(self.seed_scans + 1):]
        oldest = self._scan_times[0]
        keep = self.seed_t >= oldest  # seeds of the last ``seed_scans`` scans
        seeds, st = self.seeds[keep], self.seed_t[keep]
        new_t = np.full(unused.shape[0], t)
        if seeds.shape[0] == 0 or unused.shape[0] == 0 or dt <= 0:
            self.seeds, self.seed_t = np.vstack([seeds, unused]), np.concatenate([st, new_t])
            return
        reach = self.max_speed * (t - st) + 3.0 * math.sqrt(2.0) * self.pos_std  # 3σ of a coordinate of z1 − z0
        pairs = nearest_pairs(unused, seeds, reach, self.dim)
        used_new = np.zeros(unused.shape[0], dtype=bool)
        used_new[pairs[:, 0]] = True
        used_old = np.zeros(seeds.shape[0], dtype=bool)
        used_old[pairs[:, 1]] = True
        # detections that started a track are no seeds any more; the others wait up to ``seed_scans`` scans
        self.seeds = np.vstack([seeds[~used_old], unused[~used_new]])
        self.seed_t = np.concatenate([st[~used_old], new_t[~used_new]])
        B = pairs.shape[0]
        if B == 0:
            return
        self._start(*self._pair_estimates(st[pairs[:, 1]], seeds[pairs[:, 1]], np.full(B, t), unused[pairs[:, 0]]))

    def drop(self, ids) -> None:
        """Delete the tracks with these ids now (e.g. a divergence monitor's verdict); their detections are gone,
        the next scans may start new tracks (new ids) where they are."""
        if self.pmbm is not None:
            self.pmbm.drop(ids)
        rows = np.flatnonzero(np.isin(self.ids, np.asarray(ids, dtype=np.int64)) & self.bank.live)
        if rows.size:
            self.bank.remove(rows)
            self.ids[rows] = -1
            self.confirmed[rows] = False
            self.on_prior[rows] = False
            self.r[rows] = 0.0

    # ------------------------------------------------------------------ reading out
    def report(self) -> ScanReport:
        """The confirmed tracks now (confirmed and existence ≥ ``report_existence``), sorted by id."""
        live = self.bank.live
        if self.pmbm is not None:  # the best global hypothesis's confirmed Bernoullis with r ≥ report; existence r̄
            best, ex = self.pmbm.best_rows(), self.pmbm.best_existence()
            conf = np.fromiter(self.pmbm.confirmed_ids, dtype=np.int64, count=len(self.pmbm.confirmed_ids))
            ok = np.isin(self.ids[best], conf) & (self.r[best] >= self.r_report)
            sel, ex = best[ok], ex[ok]
        else:
            sel = np.flatnonzero(live & self.confirmed & (self.r >= self.r_report))
            ex = self.r[sel]
        order = np.argsort(self.ids[sel], kind="stable")
        sel, ex = sel[order], ex[order]
        X = self.bank.physical(sel)
        mu = self.bank.mode_probabilities(sel) if hasattr(self.bank, "mode_probabilities") else None
        rep = ScanReport(self.t, self.ids[sel].copy(), X, self.bank.stds(sel), ex.copy(), mu)
        if self.history is not None and self.t is not None and self._recorded != self.t:
            self._recorded = self.t
            for k, P in enumerate(self.bank.covariances(sel)):
                self.history.setdefault(int(rep.ids[k]), []).append((self.t, X[k], P, rep.existence[k]))
        return rep

    def tracks(self) -> list:
        """Every track reported so far with its history (``history=True``), sorted by id: a list of ``Track``."""
        if self.history is None:
            raise ValueError("tracks(): the tracker keeps no history; create it with history=True")
        out = []
        for i in sorted(self.history):
            rows = self.history[i]
            out.append(Track(i, np.array([r[0] for r in rows], dtype=float), np.array([r[1] for r in rows]),
                             np.array([r[2] for r in rows]), np.array([r[3] for r in rows], dtype=float)))
        return out

    @property
    def n_tracks(self) -> int:
        """Number of live tracks (tentative and confirmed; the PMBM: Bernoullis)."""
        if self.pmbm is not None:
            return self.pmbm.n_bernoullis()
        return int(self.bank.live.sum())
