"""Speed of the multi-target tracker: 100 targets and 200 false alarms per scan.

    .venv/bin/python benchmarks/bench_multi.py [--targets 100] [--clutter 200] [--scans 300] [--model se2se2]
                                               [--association jpda] [--repeat 3]

100 targets (random positions in a 2 km × 2 km square, headings, speeds 3-15 m/s, turn rates ±0.1 rad/s),
P_D = 0.9, r = 0.3 m, scans every 0.1 s, Poisson clutter with mean ``--clutter`` per scan uniform in the
square. Prints scans per second of ``MultiTargetTracker.step`` in the steady state (after the first 20
scans, when every target has a confirmed track), the time split of one scan, the confirmed tracks at the
end, and the load average (2-core machine shared with others: absolute figures are noisy; the
coordinator re-measures on a quiet machine). The first run of each process compiles (not timed).
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np

from lgekf.estimators.multitarget.tracker import MultiTargetTracker
from lgekf.experiments.multi_scenarios import detection_stream, truth_trajectories

SIDE = 2000.0


def scenario(n_targets, clutter_per_scan, scans, dt=0.1, seed=0):
    rng = np.random.default_rng(seed)
    targets = [(0.0, 1e9, *rng.uniform(-SIDE / 2 + 200, SIDE / 2 - 200, 2), rng.uniform(-180, 180), rng.uniform(3, 15),
                rng.uniform(-0.1, 0.1)) for _ in range(n_targets)]
    times = np.round(dt * np.arange(scans), 10)
    truth = truth_trajectories(targets, times, rng)
    lam = clutter_per_scan / SIDE**2
    dets, _ = detection_stream(truth, rng, 0.9, lam, 0.3, (-SIDE / 2, SIDE / 2, -SIDE / 2, SIDE / 2))
    return times, truth, dets, lam


def run(times, dets, lam, model, association, warm=20):
    trk = MultiTargetTracker(model=model, association=association, detection_prob=0.9, clutter_density=lam, meas_std=0.3)
    for t, Z in zip(times[:warm], dets[:warm]):
        trk.step(t, Z)
    t0 = time.perf_counter()
    for t, Z in zip(times[warm:], dets[warm:]):
        rep = trk.step(t, Z)
    wall = time.perf_counter() - t0
    return (len(times) - warm) / wall, rep, trk


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--targets", type=int, default=100)
    ap.add_argument("--clutter", type=float, default=200.0)
    ap.add_argument("--scans", type=int, default=300)
    ap.add_argument("--model", default="se2se2")
    ap.add_argument("--association", default="jpda,gnn,pda", help="comma-separated (default jpda,gnn,pda)")
    ap.add_argument("--repeat", type=int, default=3)
    a = ap.parse_args()
    times, truth, dets, lam = scenario(a.targets, a.clutter, a.scans)
    print(f"{a.targets} targets, {a.clutter:g} false alarms per scan (λ = {lam:.3g} /m²), "
          f"{np.mean([z.shape[0] for z in dets]):.0f} detections per scan, model {a.model}")
    for assoc in a.association.split(","):
        run(times[:25], dets[:25], lam, a.model, assoc)  # compile
        best, rep, trk = 0.0, None, None
        for _ in range(a.repeat):
            rate, rep, trk = run(times, dets, lam, a.model, assoc)
            best = max(best, rate)
        X = truth[-1][1][:, :2]
        d = np.hypot(rep.states[:, None, 0] - X[None, :, 0], rep.states[:, None, 1] - X[None, :, 1])
        held = int((d.min(axis=0) < 2.0).sum()) if rep.states.size else 0
        print(f"  {assoc}: {best:.0f} scans/s (best of {a.repeat}, {a.scans - 20} steady-state scans each); "
              f"{rep.ids.size} confirmed tracks at the end, {held}/{a.targets} targets within 2 m of one; "
              f"{trk.n_tracks} live tracks (tentative included)")
    print(f"load average {os.getloadavg()[0]:.2f} on {os.cpu_count()} cores")


if __name__ == "__main__":
    main()
