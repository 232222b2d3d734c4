"""lgekf's multi-target tracker against Stone Soup's JPDA + constant-velocity Kalman tracker on the same detections.

    .venv/bin/python benchmarks/bench_stonesoup.py [--runs 3] [--seed 2016] [--duration 20]

Optional dependency: ``pip install "lgekf[stonesoup]"`` (Stone Soup); without it the script says so and exits 0.

The detections are the base scenario of ``lgekf study --multi`` (8 targets, births, deaths, crossings, close
parallel targets; P_D = 0.9, λ = 1e-4 /m² (4 false alarms per scan), r = 0.3 m, scans every 0.1 s).
Stone Soup: ``MultiTargetMixtureTracker`` with ``JPDA(PDAHypothesiser)`` (same P_D, clutter density, gate
P_G = 0.99), ``KalmanPredictor``/``KalmanUpdater`` on the constant-velocity model (q = 0.5² m²/s³ per axis, as
lgekf's cv σ_a = 0.5), a ``MultiMeasurementInitiator`` (GNN on a Mahalanobis-distance hypothesiser, 3 points
to confirm; the prior's velocity std 5 m/s) and an ``UpdateTimeStepsDeleter`` (deleted after 5 scans without
a detection). GOSPA (c = 5 m, p = 2, α = 2) per scan, track switches and the tracker's wall time, lgekf
(``cv`` and ``se2se2`` with JPDA) and Stone Soup in the same run. Stone Soup's continuous white-noise
acceleration q gives a velocity variance q·Δt per scan, lgekf cv's discrete σ_a gives σ_a²Δt²: the row
"q as SS" runs lgekf cv with σ_a = √(q/Δt) (= 1.58 m/s²), the same velocity noise as Stone Soup's.
"""

from __future__ import annotations

import argparse
import datetime as dt_
import os
import sys
import time

import numpy as np

from lgekf.estimators.multitarget.tracker import MultiTargetTracker
from lgekf.experiments.multi_scenarios import base_scenario
from lgekf.experiments.multi_study import run_tracker_on

PD, LAM, R, Q = 0.9, 1e-4, 0.3, 0.5


def stonesoup_step():
    """A fresh Stone Soup JPDA + CV tracker as a ``step(t, Z) -> (ids, positions)`` function."""
    from stonesoup.dataassociator.neighbour import GNNWith2DAssignment
    from stonesoup.dataassociator.probability import JPDA
    from stonesoup.deleter.time import UpdateTimeStepsDeleter
    from stonesoup.hypothesiser.distance import DistanceHypothesiser
    from stonesoup.hypothesiser.probability import PDAHypothesiser
    from stonesoup.initiator.simple import MultiMeasurementInitiator
    from stonesoup.measures import Mahalanobis
    from stonesoup.models.measurement.linear import LinearGaussian
    from stonesoup.models.transition.linear import CombinedLinearGaussianTransitionModel, ConstantVelocity
    from stonesoup.predictor.kalman import KalmanPredictor
    from stonesoup.types.detection import Detection
    from stonesoup.types.state import GaussianState
    from stonesoup.updater.kalman import KalmanUpdater
    from stonesoup.tracker.simple import MultiTargetMixtureTracker

    transition = CombinedLinearGaussianTransitionModel([ConstantVelocity(Q**2), ConstantVelocity(Q**2)])
    meas = LinearGaussian(ndim_state=4, mapping=(0, 2), noise_covar=np.diag([R**2, R**2]))
    predictor = KalmanPredictor(transition)
    updater = KalmanUpdater(meas)
    hyp = PDAHypothesiser(predictor=predictor, updater=updater, clutter_spatial_density=LAM, prob_detect=PD, prob_gate=0.99)
    associator = JPDA(hypothesiser=hyp)
    deleter = UpdateTimeStepsDeleter(time_steps_since_update=5)
    init_assoc = GNNWith2DAssignment(DistanceHypothesiser(predictor, updater, Mahalanobis(), missed_distance=3))
    prior = GaussianState(np.zeros((4, 1)), np.diag([R**2, 25.0, R**2, 25.0]))
    initiator = MultiMeasurementInitiator(prior_state=prior, measurement_model=meas, deleter=UpdateTimeStepsDeleter(2),
                                          data_associator=init_assoc, updater=updater, min_points=3)

    class Feed:
        """A detector fed one scan at a time."""

        def __init__(self):
            self.item = None

        def __iter__(self):
            return self

        def __next__(self):
            return self.item

        @property
        def detections_gen(self):
            return self

    feed = Feed()

    class Reader:
        def __iter__(self):
            return feed

    tracker = MultiTargetMixtureTracker(initiator=initiator, deleter=deleter, detector=Reader(), data_associator=associator,
                                        updater=updater)
    it = iter(tracker)
    t0 = dt_.datetime(2026, 1, 1)
    ids = {}

    def step(t, Z):
        stamp = t0 + dt_.timedelta(seconds=float(t))
        feed.item = (stamp, {Detection(np.array([[z[0]], [z[1]]]), timestamp=stamp, measurement_model=meas) for z in Z})
        _, tracks = next(it)
        tracks = sorted(tracks, key=lambda tr: tr.id)
        tid = np.array([ids.setdefault(tr.id, len(ids)) for tr in tracks], dtype=np.int64)
        pos = np.array([[float(tr.state_vector[0, 0]), float(tr.state_vector[2, 0])] for tr in tracks]).reshape(-1, 2)
        return tid, pos

    return step


def lgekf_step(model, accel_std=None):
    trk = MultiTargetTracker(model=model, association="jpda", detection_prob=PD, clutter_density=LAM, meas_std=R,
                             accel_std=accel_std)

    def step(t, Z):
        rep = trk.step(t, Z)
        return rep.ids, rep.states[:, :2]

    return step


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--seed", type=int, default=2016)
    ap.add_argument("--duration", type=float, default=20.0)
    a = ap.parse_args()
    try:
        import stonesoup  # noqa: F401
    except ImportError:
        print('skipped: Stone Soup is not installed (pip install "lgekf[stonesoup]")')
        return 0
    scen = [base_scenario(seed=a.seed + k, duration=a.duration, detection_prob=PD, clutter_density=LAM, meas_std=R)
            for k in range(a.runs)]
    for model in ("cv", "se2se2"):  # compile outside the timing
        step = lgekf_step(model)
        for t, Z in zip(scen[0].times[:10], scen[0].detections[:10]):
            step(t, Z)
    rows = []
    matched = (Q / np.sqrt(0.1),)  # lgekf cv's σ_a with the velocity variance per scan of Stone Soup's q = Q²
    for name, make in (("lgekf cv JPDA", lambda: lgekf_step("cv")), ("lgekf cv JPDA, q as SS", lambda: lgekf_step("cv", matched)),
                       ("lgekf se2se2 JPDA", lambda: lgekf_step("se2se2")), ("Stone Soup JPDA + CV", stonesoup_step)):
        res = [run_tracker_on(sc, make(), 5.0, 2.0) for sc in scen]
        r = np.array([x[:5] for x in res])
        wall = sum(x[5] for x in res)
        scans = sum(len(sc.times) for sc in scen)
        rows.append((name, *r[:, :4].mean(axis=0), int(r[:, 4].sum()), scans / wall))
    print(f"{a.runs} runs × {len(scen[0].times)} scans of the base scenario; GOSPA c = 5 m, p = 2 (mean per scan)")
    print(f"{'tracker':<22} {'GOSPA':>7} {'loc.':>7} {'missed':>7} {'false':>7} {'switches':>8} {'scans/s':>9}")
    for name, g, lo, mi, fa, sw, rate in rows:
        print(f"{name:<22} {g:7.3f} {lo:7.3f} {mi:7.3f} {fa:7.3f} {sw:8d} {rate:9.1f}")
    print(f"speed ratio lgekf cv / Stone Soup: {rows[0][-1] / rows[3][-1]:.0f}x  (load average {os.getloadavg()[0]:.2f}, "
          f"{os.cpu_count()} cores)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
