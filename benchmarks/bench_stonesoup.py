"""lgekf's multi-target tracker against Stone Soup's JPDA + constant-velocity Kalman tracker on the same detections.

    .venv/bin/python benchmarks/bench_stonesoup.py [--runs 3] [--seed 2016] [--duration 20]
    .venv/bin/python benchmarks/bench_stonesoup.py --dataset eth [--stonesoup-q 0.25,matched] [--noise default,data]
        [any option of lgekf study --multi: --runs 5 --meas-std 0.1 --clutter-density 0.01 --max-speed 5 --gospa-c 2
         --models cv,se2r3 --association jpda,gnn --scans 400 ...] [--csv runs.csv]

Optional dependency: ``pip install "lgekf[stonesoup]"`` (Stone Soup); without it the script says so and exits 0.

**With --dataset** (the real scenes): the detection streams, seeds, P_D, λ, r, GOSPA c and p and the lgekf cells are
those of ``lgekf study --multi --dataset NAME`` given the same options (parsed by that command's own parser, the
cells run by ``run_multi_study``; each ``--noise`` a set of cells), and Stone Soup's JPDA + CV runs on the same
streams, scored by the same ``run_tracker_on`` (``gospa_series``, the function under ``lgekf.gospa``; switches
counted the same way). Stone Soup's association there is ``JPDAwithEHM2``: the exact JPDA marginals (the same
numbers as ``JPDA``: equal GOSPA, parts and switches on 5 s of the base scenario), by efficient hypothesis
management per cluster, where ``JPDA`` enumerates the joint events of all tracks at once and did not get through the
fourth scan of the DUT cars (21 tracks) in 2 minutes. Its prior velocity std is lgekf's one-point prior, ``--max-speed``/3; gate, P_D, λ, r
as lgekf's. One Stone Soup row per ``--stonesoup-q`` (its ``ConstantVelocity`` noise diffusion coefficient q, m²/s³):
a number, or ``matched``: q = σ_a²·Δt with lgekf cv's default σ_a = 0.5 m/s² and the scene's median scan interval
Δt, so that both add the same velocity variance per scan. Printed: mean ± the half-width of the 95 % Student-t
interval over the runs (``lgekf.experiments.statistics.t_interval``) of GOSPA, its parts and the switches per run,
and each lgekf cell's paired GOSPA and switch differences from the best Stone Soup row (per-seed differences, their
t-interval: the same seeds for both, so the interval of the difference is what decides).

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


def stonesoup_step(pd=PD, lam=LAM, r=R, q=Q**2, speed_std=5.0, exact_by_clusters=False):
    """A fresh Stone Soup JPDA + CV tracker as a ``step(t, Z) -> (ids, positions)`` function.

    P_D ``pd``, clutter density ``lam`` (/m²/scan), position noise std ``r`` (m), CV noise diffusion coefficient ``q``
    (m²/s³), prior velocity std ``speed_std`` (m/s); ``exact_by_clusters``: ``JPDAwithEHM2`` (the exact JPDA
    marginals by efficient hypothesis management) instead of ``JPDA`` (all joint events of all tracks)."""
    from stonesoup.dataassociator.neighbour import GNNWith2DAssignment
    from stonesoup.dataassociator.probability import JPDA, JPDAwithEHM2
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

    transition = CombinedLinearGaussianTransitionModel([ConstantVelocity(q), ConstantVelocity(q)])
    meas = LinearGaussian(ndim_state=4, mapping=(0, 2), noise_covar=np.diag([r**2, r**2]))
    predictor = KalmanPredictor(transition)
    updater = KalmanUpdater(meas)
    hyp = PDAHypothesiser(predictor=predictor, updater=updater, clutter_spatial_density=lam, prob_detect=pd, prob_gate=0.99)
    associator = (JPDAwithEHM2 if exact_by_clusters else JPDA)(hypothesiser=hyp)
    deleter = UpdateTimeStepsDeleter(time_steps_since_update=5)
    init_assoc = GNNWith2DAssignment(DistanceHypothesiser(predictor, updater, Mahalanobis(), missed_distance=3))
    prior = GaussianState(np.zeros((4, 1)), np.diag([r**2, speed_std**2, r**2, speed_std**2]))
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


def stonesoup_q(text: str, dt: float, accel_std: float) -> float:
    """A ``--stonesoup-q`` entry: a number, or "matched" = σ_a²·Δt (Stone Soup's velocity variance per scan q·Δt equal
    to lgekf cv's σ_a²·Δt²)."""
    return accel_std**2 * dt if text == "matched" else float(text)


def dataset_main(argv) -> int:
    """``--dataset``: lgekf's cells of ``lgekf study --multi`` and Stone Soup's JPDA + CV on the same streams."""
    from dataclasses import replace

    from lgekf.cli.study_multi import study_multi_config, study_multi_parser
    from lgekf.core.registry import get_model
    from lgekf.estimators.multitarget.settings import SPEED_STD_FRACTION
    from lgekf.experiments.multi_study import (RUN_PARTS, format_interval, format_multi_table, multi_cell, run_multi_study,
                                               scenarios, score_runs)
    from lgekf.experiments.statistics import t_interval

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0] + " (--dataset: the real scenes)")
    ap.add_argument("--stonesoup-q", default="0.25,matched",
                    help="Stone Soup CV noise diffusion coefficients q (m²/s³), one row each; matched = lgekf cv's "
                         "default σ_a² × the scene's median scan interval (default 0.25,matched)")
    ap.add_argument("--noise", default="default", help="lgekf cells' process noise, one set of cells each: default, data")
    ap.add_argument("--csv", default=None, help="write one row per tracker × run here")
    own, rest = ap.parse_known_args(argv)
    cfg = study_multi_config(study_multi_parser().parse_args(["--multi", *rest]))
    try:
        import stonesoup  # noqa: F401
    except ImportError:
        print('skipped: Stone Soup is not installed (pip install "lgekf[stonesoup]")')
        return 0
    scen = scenarios(cfg)
    dt = float(np.median(np.diff(scen[0].times)))
    cells = []
    for noise in [v.strip() for v in own.noise.split(",") if v.strip()]:
        fit = None
        if noise == "data":
            from lgekf.apps.track_multi import study_process_noise as fit
        for c in run_multi_study(replace(cfg, noise=noise), noise_fit=fit,
                                 progress=lambda c: print(f"  {c.model} {c.association}: {c.gospa:.3f}", file=sys.stderr)):
            c.accel_std = noise if noise == "default" else "data"
            cells.append(c)
    accel = get_model("cv").default_accel_std[0]
    ss = []
    for text in own.stonesoup_q.split(","):
        q = stonesoup_q(text.strip(), dt, accel)
        per_run, wall, scans = score_runs(scen, lambda sc, q=q: stonesoup_step(
            cfg.detection_prob, cfg.clutter_density, cfg.meas_std, q, SPEED_STD_FRACTION * cfg.max_speed,
            exact_by_clusters=True), cfg.c, cfg.p)
        ss.append(multi_cell("stonesoup", "jpda", "3-point", per_run, wall, scans, accel_std=f"q={q:.4g}"))
        print(f"  Stone Soup q = {q:.4g}: {ss[-1].gospa:.3f}", file=sys.stderr)
    best = min(ss, key=lambda c: c.gospa)
    print(format_multi_table(cells + ss, cfg).splitlines()[0])
    print(f"scene Δt = {dt:.4g} s; last two columns: lgekf − Stone Soup ({best.accel_std}) paired over the seeds, mean ± "
          "95 % t-interval (negative: lgekf better)")
    print(f"{'tracker':<10} {'assoc':<8} {'noise':<9} " + " ".join(f"{h:>15}" for h in (*RUN_PARTS[:4], "switches/run"))
          + f" {'scans/s':>8} {'ΔGOSPA':>15} {'Δswitches/run':>15}")
    for c in cells + ss:
        vals = [format_interval(*c.interval(part), 3) for part in RUN_PARTS[:4]] + [format_interval(*c.interval("switches"), 1)]
        diff = ["", ""] if c is best else [format_interval(*t_interval(c.per_run[:, 0] - best.per_run[:, 0]), 3),
                                           format_interval(*t_interval(c.per_run[:, 4] - best.per_run[:, 4]), 1)]
        print(f"{c.model:<10} {c.association:<8} {c.accel_std:<9} " + " ".join(f"{v:>15}" for v in vals)
              + f" {c.scans_per_s:8.0f} {diff[0]:>15} {diff[1]:>15}")
    print(f"load average {os.getloadavg()[0]:.2f}, {os.cpu_count()} cores")
    if own.csv:
        with open(own.csv, "w") as f:
            f.write("tracker,association,noise,run,seed," + ",".join(RUN_PARTS) + "\n")
            for c in cells + ss:
                for k, row in enumerate(c.per_run):
                    f.write(f"{c.model},{c.association},{c.accel_std},{k},{cfg.seed + k}," + ",".join(f"{v:.6g}" for v in row) + "\n")
    return 0


def main():
    if "--dataset" in sys.argv[1:] or any(v.startswith("--dataset=") for v in sys.argv[1:]):
        try:
            return dataset_main(sys.argv[1:])
        except ValueError as e:  # bad options (UsageError) or data (DataError): one line, status 2
            print(f"bench_stonesoup.py: error: {e}", file=sys.stderr)
            return 2
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
