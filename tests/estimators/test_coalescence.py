"""JPDA's track coalescence and JPDA* (``association="jpdastar"``, Blom & Bloem 2000) on the textbook case: two
targets moving side by side one measurement std apart."""

from __future__ import annotations

import numpy as np

from lgekf.estimators.multitarget.tracker import MultiTargetTracker

R = 0.5  # measurement std (m); the targets are R apart


def coalesced_fraction(association: str, seed: int, scans: int = 120, dt: float = 0.1) -> float:
    """The fraction of scans (after the first 20) in which the two confirmed tracks are less than half the targets'
    separation apart across the direction of motion."""
    rng = np.random.default_rng(seed)
    trk = MultiTargetTracker(model="cv", association=association, detection_prob=0.9, clutter_density=1e-4, meas_std=R,
                             max_speed=10, accel_std=(0.5,))
    close = []
    for k in range(scans):
        t = dt * k
        truth = np.array([[5.0 * t, 0.0], [5.0 * t, R]])
        Z = np.array([x + R * rng.standard_normal(2) for x in truth if rng.random() < 0.9]).reshape(-1, 2)
        rep = trk.step(t, Z)
        if k >= 20 and len(rep.ids) >= 2:
            y = np.sort(rep.states[:, 1])
            close.append(y[-1] - y[0] < R / 2)
    return float(np.mean(close))


def test_jpda_star_keeps_close_parallel_tracks_apart():
    """JPDA weighs each detection-to-track event and its swap alike and pulls both tracks to the middle: on 6 seeds
    its tracks are within half the separation in 29-94 % of the scans; JPDA* (only the better permutation) in
    0-25 %, less on every seed."""
    jpda = np.array([coalesced_fraction("jpda", s) for s in range(6)])
    star = np.array([coalesced_fraction("jpdastar", s) for s in range(6)])
    assert np.all(star < jpda), (jpda, star)
    assert jpda.mean() > 0.4 and star.mean() < jpda.mean() / 3, (jpda, star)
