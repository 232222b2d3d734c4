"""One-point initiation of the multi-target tracker (``MultiTargetTracker(initiation="one-point")``): a track from
the first detection with the stated prior, its existence from the birth and clutter densities and the IPDA
recursion, confirmation earlier than the two-point start, a lone false alarm never confirmed, the restart by the
two-point rule at the second detection, and the argument checks. Expected values come from the formulas of the
module docstring of ``lgekf.estimators.multitarget.tracker``, written out here, not from the code under test."""

from __future__ import annotations

import math

import numpy as np
import pytest

from lgekf.core.covariance import unpack
from lgekf.core.registry import MODELS
from lgekf.estimators.multitarget.tracker import MultiTargetTracker
from lgekf.experiments.gospa import gospa
from lgekf.experiments.multi_scenarios import BASE_TARGETS, base_scenario

R = 0.3  # position std (m)
MAX_SPEED = 12.0  # m/s: σ_v = 4 m/s per axis
SIGMA_V = MAX_SPEED / 3
OMEGA_STD = 0.5
HEADING_CAP = 0.3  # the two-point start's largest heading std, the one-point θ std of a position detection
LAMBDA = 1e-4
PD, PG, PS = 0.9, 0.99, 0.99


def tracker(model="cv", measurement="position", meas_std=R, **kw):
    return MultiTargetTracker(model=model, measurement=measurement, meas_std=meas_std, clutter_density=LAMBDA,
                              detection_prob=PD, gate_prob=PG, survival_prob=PS, max_speed=MAX_SPEED,
                              omega_std=OMEGA_STD, initiation="one-point", **kw)


def only_row(trk):
    rows = np.flatnonzero(trk.bank.live)
    assert rows.size == 1
    return int(rows[0])


def expected_prior_variances(model, heading_var):
    """The one-point prior in the model's tangent coordinates at heading 0, coordinate by coordinate: positions r²,
    velocity components σ_v², a forward speed σ_v², ω σ_ω²; a heading that is the direction of motion (a model with
    a forward speed) π² (unknown, the cap of an angle's variance), a body heading ``heading_var``."""
    spec = MODELS[model]
    var = {"x": R**2, "y": R**2, "vx": SIGMA_V**2, "vy": SIGMA_V**2, "v": SIGMA_V**2, "omega": OMEGA_STD**2}
    heading = math.pi**2 if spec.forward_speed else heading_var
    return np.array([var.get(name, heading) for name in spec.state_names])


@pytest.mark.parametrize("model", list(MODELS))
def test_a_track_starts_on_the_first_detection_with_the_stated_prior(model):
    trk = tracker(model)
    rep = trk.step(0.0, np.array([[3.0, -4.0]]))
    assert trk.n_tracks == 1 and rep.ids.size == 0  # tentative: not reported
    i = only_row(trk)
    assert trk.r[i] == pytest.approx(0.02)  # the default birth existence of one-point tracks
    x = trk.bank.physical([i])[0]
    assert x[:2].tolist() == [3.0, -4.0] and np.all(x[2:] == 0.0)  # at the detection, at rest
    P = unpack(trk.bank.p[i], MODELS[model].n)
    np.testing.assert_allclose(P, np.diag(expected_prior_variances(model, HEADING_CAP**2)), rtol=1e-9, atol=1e-12)


@pytest.mark.parametrize("model", [m for m, s in MODELS.items() if "pose" in s.measurements])
def test_a_pose_detection_gives_the_heading_and_its_std(model):
    r_theta = 0.05
    trk = tracker(model, "pose", (R, R, r_theta))
    trk.step(0.0, np.array([[1.0, 2.0, 0.0]]))
    i = only_row(trk)
    P = unpack(trk.bank.p[i], MODELS[model].n)
    np.testing.assert_allclose(P, np.diag(expected_prior_variances(model, r_theta**2)), rtol=1e-9, atol=1e-12)


def test_the_birth_existence_from_the_densities():
    """r₀ = β/(β + λ): new objects' first detections and false alarms as two Poisson processes."""
    beta = 3e-6
    trk = tracker(birth_density=beta)
    trk.step(0.0, np.array([[0.0, 0.0]]))
    assert trk.r[only_row(trk)] == pytest.approx(beta / (beta + LAMBDA), rel=1e-12)


def existence_after_one_detection(r, e2, s, dt_var=0.0):
    """The IPDA existence after a scan in which a track of existence r (before prediction) gates one detection at
    squared distance e2 from its predicted position, with isotropic innovation variance s per axis (2-D):
    r' = p_S r, w0 = 1 − r' P_D P_G, W = r' P_D N(e; 0, s I)/λ, r⁺ = (W + r'(1 − P_D P_G))/(w0 + W)."""
    rp = PS * r
    w0 = 1.0 - rp * PD * PG
    W = rp * PD * math.exp(-0.5 * e2 / s) / (2.0 * math.pi * s) / LAMBDA
    return (W + rp * (1.0 - PD * PG)) / (w0 + W)


def test_second_detection_existence_and_restart_by_the_two_point_rule():
    """CV (linear: the innovation variance per axis after Δt is 2r² + σ_v²Δt² + σ_a²Δt⁴/4): the existence after the
    second detection is the IPDA formula's, and the state is the two-point estimate: position the second detection,
    velocity the chord over Δt."""
    dt, sigma_a = 0.1, 0.5
    z0, z1 = np.array([0.0, 0.0]), np.array([0.4, -0.3])
    trk = tracker(accel_std=(sigma_a,))
    trk.step(0.0, z0[None])
    trk.step(dt, z1[None])
    i = only_row(trk)
    s = 2 * R**2 + SIGMA_V**2 * dt**2 + sigma_a**2 * dt**4 / 4
    assert trk.r[i] == pytest.approx(existence_after_one_detection(0.02, float(np.sum((z1 - z0) ** 2)), s), rel=1e-9)
    x = trk.bank.physical([i])[0]
    np.testing.assert_allclose(x, [*z1, *(z1 - z0) / dt], rtol=1e-12, atol=1e-12)
    assert trk.ids[i] == 0  # the same track (id kept by the restart)


def first_confirmed_scan(initiation, dt=0.1, scans=10):
    """The scan at which a lone target moving at 5 m/s, detected every scan without noise or clutter, is first
    reported."""
    trk = MultiTargetTracker(model="se2r3", meas_std=R, clutter_density=LAMBDA, detection_prob=PD, gate_prob=PG,
                             survival_prob=PS, max_speed=MAX_SPEED, initiation=initiation)
    for k in range(scans):
        rep = trk.step(k * dt, np.array([[5.0 * k * dt, 2.0]]))
        if rep.ids.size:
            return k
    return None


def test_a_clutter_free_target_is_confirmed_earlier_than_with_two_points():
    """One-point: the track exists from scan 0 and its existence after scan 1 (formula, with SE(2)×R³'s predicted
    position variance r² + σ_v²Δt² (process noise on velocity and turn rate, O(Δt³) on position, neglected) and
    the measurement's r²) is above the confirmation threshold 0.9: reported at scan 1. Two-point: the track
    starts at scan 1 from two detections, is first updated (and confirmed) at scan 2."""
    dt = 0.1
    r1 = existence_after_one_detection(0.02, (5.0 * dt) ** 2, 2 * R**2 + SIGMA_V**2 * dt**2)
    assert r1 > 0.9
    assert first_confirmed_scan("one-point") == 1
    assert first_confirmed_scan("two-point") == 2


def test_a_lone_false_alarm_is_never_confirmed():
    """A detection, then scans without any detection near it: one miss takes the existence from r' = p_S r₀ to
    r' (1 − P_D P_G)/(1 − r' P_D P_G) < 0.01, the deletion threshold: the track is gone after one scan, never
    reported."""
    rp = PS * 0.02
    assert rp * (1 - PD * PG) / (1 - rp * PD * PG) < 0.01
    trk = tracker()
    reports = [trk.step(0.0, np.array([[10.0, 10.0]]))]
    assert trk.n_tracks == 1
    far = np.array([[90.0, -90.0]])  # other false alarms, far away and from each other: each starts its own track
    reports += [trk.step(0.1 * k, far + 20.0 * k) for k in range(1, 6)]
    assert all(rep.ids.size == 0 for rep in reports)
    assert trk.n_tracks == 1 and trk.ids[only_row(trk)] == 5  # only the last scan's own new track is left


def test_one_point_jpda_holds_the_crossing_and_parallel_targets():
    """The four targets of the base scenario's crossing and parallel pairs in clutter (4 false alarms per scan,
    P_D 0.9), two seeds: each target held by a confirmed track within 5 m in at least 95 % of the scans after
    the first second (the same bar as the two-point start's test in test_multi_tracker.py)."""
    for seed in (0, 1):
        sc = base_scenario(seed=seed, targets=BASE_TARGETS[:4], duration=10.0)
        trk = MultiTargetTracker(model="se2r3", meas_std=R, clutter_density=LAMBDA, initiation="one-point")
        held = np.zeros(4)
        n = 0
        for t, Z, (ids, X) in zip(sc.times, sc.detections, sc.truth):
            rep = trk.step(t, Z)
            if t >= 1.0:
                n += 1
                for i, _ in gospa(X[:, :2], rep.states[:, :2], c=5.0, p=2).assignment:
                    held[ids[i]] += 1
        assert np.all(held / n >= 0.95), held / n


@pytest.mark.parametrize("kw, msg", [
    (dict(initiation="three-point"), "initiation: unknown method 'three-point'"),
    (dict(initiation="two-point", birth_density=1e-6), "birth-density: only with one-point initiation"),
    (dict(initiation="two-point", speed_std=2.0), "speed-std: only with one-point initiation"),
    (dict(initiation="one-point", birth_density=1e-6, birth_existence=0.1), "birth-density: not with birth-existence"),
    (dict(initiation="one-point", birth_density=-1.0), "birth-density: must be a positive number"),
    (dict(initiation="one-point", speed_std=0.0), "speed-std: must be a positive number"),
])
def test_initiation_arguments_are_checked(kw, msg):
    with pytest.raises(ValueError, match=msg):
        MultiTargetTracker(model="cv", **kw)


def test_default_initiation_by_association():
    """One-point with JPDA and GNN, two-point with PDA (what measured better: docs/multi_target.md)."""
    assert {a: MultiTargetTracker(model="cv", association=a).initiation for a in ("jpda", "gnn", "pda")} == {
        "jpda": "one-point", "gnn": "one-point", "pda": "two-point"}
    assert MultiTargetTracker(model="cv", association="pda").r_birth == 0.1
