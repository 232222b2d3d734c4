"""The base scenario (``lgekf.experiments.multi_scenarios``) with clutter that is not the same everywhere and always:
``lgekf study --multi --scenario burst|patch`` and the tests of ``lgekf.estimators.multitarget.clutter``.

* **burst** (clutter varying in time): the background λ₀ (default 1e-4 per m² per scan, 4 false alarms per scan
  over the 200 m × 200 m region) and, from ``BURST`` = (8, 13) s, λ₀ + λ_b (default λ_b = 1.5e-3: 64 false alarms
  per scan), over the crossing at 11.3 s and the birth at 8 s; a radar's rain or a lidar's spray;
* **patch** (clutter concentrated in space): the background λ₀ everywhere and λ₀ + λ_p (default λ_p = 1.25e-2: 20
  false alarms per scan) in the square ``PATCH`` = 40 m × 40 m around (0, 5) that the crossing pair, the close
  parallel pair and the target born at 5 s all pass through; a radar's sea clutter, a lidar's vegetation.

Each scenario keeps its true density as a function ``true_density(t, Z)`` and its mean over the scans and the region
(``mean_density``). The clutter densities the study gives the tracker (``STUDY_CLUTTERS``, ``study_clutter``):

* "true": the true mean density, a constant (for the base scenario its λ);
* "file": the per-file estimate of ``lgekf track --multi --clutter file`` (all detections per scan over their
  bounding box);
* "scan", "map": the tracker's estimators over the detections' bounding box, as ``lgekf track --multi --clutter
  scan|map`` (``lgekf.estimators.multitarget.clutter.clutter_from_data``);
* "oracle": the true λ(t, z) at every detection (``OracleClutter``), what no estimator can beat.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..estimators.multitarget.clutter import ClutterEstimator, clutter_from_data
from .multi_scenarios import BASE_TARGETS, REGION, MultiScenario, detection_stream, truth_trajectories

__all__ = ["ClutterScenario", "CLUTTER_SCENARIOS", "clutter_scenario", "BURST", "PATCH", "OracleClutter",
           "STUDY_CLUTTERS", "study_clutter"]

BURST = (8.0, 13.0)  # s: the burst's start and end
PATCH = (-20.0, 20.0, -15.0, 25.0)  # (x_min, x_max, y_min, y_max) of the dense patch
CLUTTER_SCENARIOS = ("base", "burst", "patch")
STUDY_CLUTTERS = ("true", "file", "scan", "map", "oracle")


@dataclass
class ClutterScenario(MultiScenario):
    """A ``MultiScenario`` with its true clutter density.

    Attributes
    ----------
    kind : str
        "base", "burst" or "patch".
    background, extra : float
        λ₀ everywhere and always, and λ_b (burst) or λ_p (patch) on top of it (per m² per scan).
    mean_density : float
        The true density averaged over the scans and the region.
    """

    kind: str = "base"
    background: float = 1e-4
    extra: float = 0.0
    mean_density: float = 1e-4

    def true_density(self, t: float, Z: np.ndarray) -> np.ndarray:
        """The true λ (per m² per scan) at time t at the positions Z (M, ≥2)."""
        lam = np.full(Z.shape[0], self.background)
        if self.kind == "burst" and BURST[0] - 1e-9 <= t <= BURST[1] + 1e-9:
            lam += self.extra
        elif self.kind == "patch":
            x0, x1, y0, y1 = PATCH
            lam += self.extra * ((Z[:, 0] >= x0) & (Z[:, 0] <= x1) & (Z[:, 1] >= y0) & (Z[:, 1] <= y1))
        return lam


def _uniform(rng, n, box, m):
    x0, x1, y0, y1 = box
    C = np.empty((n, m))
    C[:, 0] = rng.uniform(x0, x1, n)
    C[:, 1] = rng.uniform(y0, y1, n)
    if m == 3:
        C[:, 2] = rng.uniform(-np.pi, np.pi, n)
    return C


def clutter_scenario(kind: str, seed: int = 0, dt: float = 0.1, duration: float = 20.0, detection_prob: float = 0.9,
                     background: float = 1e-4, extra: float | None = None, meas_std=0.3,
                     measurement: str = "position") -> ClutterScenario:
    """The base scenario's targets with the clutter of ``kind`` (module docstring).

    Parameters
    ----------
    kind : {"base", "burst", "patch"}
        Uniform and constant (the base scenario's clutter), a burst in time, or a dense patch.
    seed : int
        Seed of the truth's random walk, the misses, the noise and the clutter (the base scenario's detections
        and truth for the same seed, the extra clutter added).
    dt, duration, detection_prob, meas_std, measurement
        As ``base_scenario``.
    background : float
        λ₀ (per m² per scan).
    extra : float, optional
        λ_b or λ_p (default 1.5e-3 for a burst, 1.25e-2 for a patch).

    Returns
    -------
    ClutterScenario
    """
    if kind not in CLUTTER_SCENARIOS:
        raise ValueError(f"scenario: one of {', '.join(CLUTTER_SCENARIOS)}, got {kind!r}")
    if extra is None:
        extra = {"base": 0.0, "burst": 1.5e-3, "patch": 1.25e-2}[kind]
    rng = np.random.default_rng(seed)
    times = np.round(np.arange(0.0, duration + dt / 2, dt), 10)
    truth = truth_trajectories(BASE_TARGETS, times, rng)
    dets, srcs = detection_stream(truth, rng, detection_prob, background, meas_std, REGION, measurement)
    area = (REGION[1] - REGION[0]) * (REGION[3] - REGION[2])
    patch_area = (PATCH[1] - PATCH[0]) * (PATCH[3] - PATCH[2])
    on = (times >= BURST[0] - 1e-9) & (times <= BURST[1] + 1e-9)
    mean = background + (extra * on.mean() if kind == "burst" else extra * patch_area / area if kind == "patch" else 0.0)
    if kind != "base":
        extra_rng = np.random.default_rng([seed, 1])  # the base scenario's stream is unchanged
        m = dets[0].shape[1] if dets else 2
        for k, t in enumerate(times):
            if kind == "burst":
                C = _uniform(extra_rng, extra_rng.poisson(extra * area) if on[k] else 0, REGION, m)
            else:
                C = _uniform(extra_rng, extra_rng.poisson(extra * patch_area), PATCH, m)
            Z = np.vstack([dets[k], C])
            src = np.concatenate([srcs[k], np.full(C.shape[0], -1)])
            order = extra_rng.permutation(Z.shape[0])
            dets[k], srcs[k] = Z[order], src[order]
    return ClutterScenario(times, truth, dets, srcs, tuple(REGION), kind, background, extra, mean)


class OracleClutter(ClutterEstimator):
    """The true clutter density of a ``ClutterScenario`` at every detection (the study's "oracle")."""

    name = "oracle"

    def __init__(self, scenario: ClutterScenario):
        self.scenario = scenario

    def fresh(self) -> "OracleClutter":
        return OracleClutter(self.scenario)

    def density(self, t, Z, expected):
        lam = self.scenario.true_density(t, Z)
        self.level = float(lam.mean()) if lam.size else self.scenario.background
        return lam


def study_clutter(kind: str, scenario: MultiScenario, constant: float):
    """The tracker's ``clutter_density`` argument for the study's clutter ``kind`` (module docstring) on a scenario;
    ``constant`` is the true density of a scenario that keeps none (the base scenario, real trajectories).

    Parameters
    ----------
    kind : {"true", "file", "scan", "map", "oracle"}
    scenario : MultiScenario or ClutterScenario
    constant : float

    Returns
    -------
    float or ClutterEstimator
    """
    known = isinstance(scenario, ClutterScenario)
    if kind == "true" or (kind == "oracle" and not known):
        return scenario.mean_density if known else constant
    if kind == "oracle":
        return OracleClutter(scenario)
    if kind not in STUDY_CLUTTERS:
        raise ValueError(f"clutter: one of {', '.join(STUDY_CLUTTERS)}, got {kind!r}")
    z = np.vstack(scenario.detections) if scenario.detections else np.zeros((0, 2))
    return clutter_from_data(kind, z, len(scenario.times))
