"""The multi-target study (``lgekf study --multi``): every chosen model × association on Monte Carlo runs of
the base scenario (``lgekf.experiments.multi_scenarios``), scored by GOSPA (α = 2, cut-off c, order p;
``lgekf.experiments.gospa``) per scan and averaged, its localisation / missed / false parts, the track
switches and the wall time of the tracker.

Every cell sees the same detections (one stream per run seed). A model ``imm`` (``IMM_MODEL``) is the tracker with
an IMM per track (``imm_modes``, default the modes of ``lgekf track --model imm``), each mode with its model's
default noise × its level, as the models of the other cells have their defaults. With ``dataset`` the streams are the real
trajectories of ``lgekf evaluate`` (``lgekf.experiments.multi_scenarios.dataset_scenario``: truth + noise +
misses + clutter) instead of the base scenario; with ``scenario`` "burst" or "patch" the base scenario's targets
with clutter varying in time or concentrated in space (``lgekf.experiments.clutter_scenarios``). ``clutters``
chooses the clutter densities the tracker is given or estimates (``clutter_scenarios.study_clutter``: the true
constant, the per-file estimate, the per-scan estimate, the clutter map, the true λ(t, z)), one cell each.
"""

from __future__ import annotations

import itertools
import time
from dataclasses import dataclass

import numpy as np

from ..core.registry import MEASUREMENTS, get_measurement, get_model
from ..estimators.multitarget.settings import INITIATIONS, MARGINAL_ASSOCIATIONS
from ..estimators.multitarget.tracker import IMM_MODEL, MultiTargetTracker
from .clutter_scenarios import CLUTTER_SCENARIOS, STUDY_CLUTTERS, clutter_scenario, study_clutter
from .gospa import gospa_series
from .statistics import t_interval
from ..io.datasets import load_dataset
from .multi_scenarios import base_scenario, dataset_scenario

__all__ = ["NOISES", "RUN_PARTS", "MultiStudyConfig", "MultiCell", "multi_cell", "run_tracker_on", "score_runs", "scenarios", "run_multi_study", "format_multi_table", "format_interval", "MULTI_COLUMNS"]

RUN_PARTS = ("gospa", "localisation", "missed", "false", "switches")  # what run_tracker_on scores per run
MULTI_COLUMNS = ("model", "association", "initiation", "clutter", "gospa", "localisation", "missed", "false", "switches",
                 "scans_per_s", "accel_std", "runs", "gospa_ci95", "localisation_ci95", "missed_ci95", "false_ci95",
                 "switches_per_run", "switches_per_run_ci95")
NOISES = ("default", "data")  # the process noise of the cells: the models' defaults, or estimated from each stream


@dataclass
class MultiStudyConfig:
    """The protocol of ``lgekf study --multi`` (defaults: the table of docs/multi_target.md)."""

    models: tuple = ("se2se2", "se2r3", "se2r2", "ctrv", "cv")
    associations: tuple = MARGINAL_ASSOCIATIONS
    initiations: tuple = (None,)  # None: the tracker's default for the association (DEFAULT_INITIATION)
    runs: int = 5
    seed: int = 2016
    dt: float = 0.1
    duration: float = 20.0
    detection_prob: float = 0.9
    clutter_density: float = 1e-4
    meas_std: float = 0.3
    c: float = 5.0
    p: float = 2.0
    dataset: str | None = None  # a preset of ``lgekf evaluate`` (e.g. eth): its trajectories as detection streams
    data_root: str | None = None
    max_speed: float = 30.0
    measurement: str = "position"  # or "pose" (models without a heading get the position part)
    heading_std: float = 0.05
    imm_modes: str | None = None  # the modes of the model "imm" (None: the tracker's default, DEFAULT_MODES)
    scenario: str = "base"  # or "burst", "patch" (clutter_scenarios; clutter_density is then the background λ₀)
    clutters: tuple = ("true",)  # the clutter densities compared (clutter_scenarios.STUDY_CLUTTERS)
    noise: str = "default"  # the process noise: the models' defaults, or "data" (as lgekf track --multi estimates it)
    scans: int | None = None  # with dataset: only the first this many scans of every stream (None: all)

    def validate(self):
        for m in self.models:
            if m != IMM_MODEL:
                get_model(m)
        if self.imm_modes is not None and IMM_MODEL not in self.models:
            raise ValueError(f"--imm-modes: only with the model {IMM_MODEL} in --models")
        if IMM_MODEL in self.models:  # the modes' errors now, not after the other cells
            MultiTargetTracker(model=IMM_MODEL, imm_modes=self.imm_modes, measurement=self.measurement,
                               meas_std=get_measurement(self.measurement).stds(self.meas_std, self.heading_std))
        bad = [i for i in self.initiations if i is not None and i not in INITIATIONS]
        if bad or not self.initiations:
            raise ValueError(f"--initiation: unknown name {bad[0] if bad else ''!r}; choose from {', '.join(INITIATIONS)}")
        if self.scans is not None and not (self.dataset and self.scans >= 1):
            raise ValueError(f"--scans: a positive number of scans, with --dataset only, got {self.scans}")
        if self.runs < 1:
            raise ValueError(f"--runs: must be at least 1, got {self.runs}")
        if self.scenario not in CLUTTER_SCENARIOS:
            raise ValueError(f"--scenario: one of {', '.join(CLUTTER_SCENARIOS)}, got {self.scenario!r}")
        if self.dataset and self.scenario != "base":
            raise ValueError("--scenario: not with --dataset (the real trajectories have their own scenes)")
        bad = [c for c in self.clutters if c not in STUDY_CLUTTERS]
        if bad or not self.clutters:
            raise ValueError(f"--clutter: unknown name {bad[0] if bad else ''!r}; choose from {', '.join(STUDY_CLUTTERS)}")
        for name, v in (("--dt", self.dt), ("--duration", self.duration), ("--clutter-density", self.clutter_density),
                        ("--meas-std", self.meas_std), ("--gospa-c", self.c)):
            if not v > 0:
                raise ValueError(f"{name}: must be a positive number, got {v}")
        if not 0 < self.detection_prob <= 1:
            raise ValueError(f"--detection-prob: must be a probability in (0, 1], got {self.detection_prob}")
        if self.measurement not in MEASUREMENTS:
            raise ValueError(f"--measure: one of {', '.join(MEASUREMENTS)}, got {self.measurement!r}")
        if not self.p >= 1:
            raise ValueError(f"--gospa-p: must be at least 1, got {self.p}")
        if self.noise not in NOISES:
            raise ValueError(f"--noise: one of {', '.join(NOISES)}, got {self.noise!r}")
        return self


@dataclass
class MultiCell:
    """One model × association × initiation × clutter: per-scan GOSPA means over all runs and scans, switches summed
    over runs; ``per_run`` keeps each run's values (``RUN_PARTS``) for intervals over seeds (``interval``)."""

    model: str
    association: str
    initiation: str
    gospa: float
    localisation: float
    missed: float
    false: float
    switches: int
    scans_per_s: float
    clutter: str = "true"
    accel_std: str = "default"  # the process noise used: "default", or per run the values estimated from the data
    per_run: np.ndarray | None = None  # (runs, 5): per run the mean GOSPA, its parts, the switches (RUN_PARTS)

    def interval(self, part: str, level: float = 0.95) -> tuple:
        """(mean over runs, half-width of its Student-t interval; ``statistics.t_interval``) of one of ``RUN_PARTS``
        (switches: per run, not summed)."""
        return t_interval(self.per_run[:, RUN_PARTS.index(part)], level)


def multi_cell(model: str, association: str, initiation: str, per_run, wall: float, scans: int, **kw) -> MultiCell:
    """A ``MultiCell`` from each run's (GOSPA, localisation, missed, false, switches) (``run_tracker_on``), the wall
    seconds of its ``step`` calls and the scans tracked."""
    per_run = np.asarray(per_run, dtype=float).reshape(-1, len(RUN_PARTS))
    g, lo, mi, fa = map(float, per_run[:, :4].mean(axis=0))
    return MultiCell(model, association, initiation, g, lo, mi, fa, int(per_run[:, 4].sum()),
                     scans / wall if wall > 0 else float("inf"), per_run=per_run, **kw)


def run_tracker_on(scenario, step, c: float, p: float):
    """Score a tracker (``step(t, Z) -> (ids, positions (K, 2))``) on a scenario: per-scan GOSPA parts and switches
    (``gospa_series``).

    Returns (mean GOSPA, mean localisation, mean missed, mean false (the parts per scan, p-th powers),
    switches, wall seconds of the ``step`` calls)."""
    tracks = []
    wall = 0.0
    for t, Z in zip(scenario.times, scenario.detections):
        t0 = time.perf_counter()
        tracks.append(step(t, Z))
        wall += time.perf_counter() - t0
    truth = [(ids, X[:, :2]) for ids, X in scenario.truth]
    s = gospa_series(truth, tracks, c=c, p=p).summary()
    return s["gospa"], s["localisation"], s["missed"], s["false"], s["switches"], wall


def score_runs(scenarios: list, make_step, c: float, p: float) -> tuple:
    """``run_tracker_on`` on every scenario with a fresh tracker (``make_step(scenario) -> step``).

    Returns (per run (GOSPA, localisation, missed, false, switches) as a (runs, 5) array, wall seconds of the
    ``step`` calls, scans)."""
    per_run, wall, scans = [], 0.0, 0
    for sc in scenarios:
        *parts, w = run_tracker_on(sc, make_step(sc), c, p)
        per_run.append(parts)
        wall += w
        scans += len(sc.times)
    return np.array(per_run, dtype=float), wall, scans


def scenarios(cfg: MultiStudyConfig) -> list:
    """The detection streams of the study: ``cfg.runs`` seeds of the base scenario, or of the real
    trajectories of ``cfg.dataset`` (``lgekf.io.datasets.load_dataset``; DataError when the data is absent; their
    first ``cfg.scans`` scans)."""
    if cfg.scenario != "base":
        r = (cfg.meas_std, cfg.heading_std) if measures_heading(cfg) else cfg.meas_std
        return [clutter_scenario(cfg.scenario, seed=cfg.seed + k, dt=cfg.dt, duration=cfg.duration,
                                 detection_prob=cfg.detection_prob, background=cfg.clutter_density, meas_std=r,
                                 measurement=cfg.measurement) for k in range(cfg.runs)]
    if cfg.dataset:
        ds = load_dataset(cfg.dataset, root=cfg.data_root)
        if measures_heading(cfg):
            raise ValueError("--measure pose: the real trajectories have no measured heading; use position")
        return [dataset_scenario(ds, seed=cfg.seed + k, detection_prob=cfg.detection_prob, clutter_density=cfg.clutter_density,
                                 meas_std=cfg.meas_std).head(cfg.scans) for k in range(cfg.runs)]
    r = (cfg.meas_std, cfg.heading_std) if measures_heading(cfg) else cfg.meas_std
    return [base_scenario(seed=cfg.seed + k, dt=cfg.dt, duration=cfg.duration, detection_prob=cfg.detection_prob,
                          clutter_density=cfg.clutter_density, meas_std=r, measurement=cfg.measurement)
            for k in range(cfg.runs)]


def measures_heading(cfg: MultiStudyConfig) -> bool:
    """Whether the study's measurement has an angle (a pose's heading)."""
    return get_measurement(cfg.measurement).has_angle


def run_multi_study(cfg: MultiStudyConfig, progress=None, noise_fit=None) -> list:
    """Every model × association × initiation × clutter of ``cfg`` on ``cfg.runs`` scenarios (the same detections
    for every cell); a list of ``MultiCell``.

    ``noise_fit``: with ``cfg.noise == "data"``, ``noise_fit(times, detections, tracker_args, meas_std, heading_std)
    -> (noise arguments, text)`` estimates each cell's process noise from each scenario's detections before it is
    tracked (``lgekf.apps.track_multi.study_process_noise``: what ``lgekf track --multi`` does; the study's
    measurement std is given)."""
    cfg.validate()
    if cfg.noise == "data" and noise_fit is None:
        raise ValueError("noise='data' needs noise_fit (lgekf.apps.track_multi.study_process_noise)")
    scen = scenarios(cfg)
    cells = []
    for model, assoc, init, clutter in itertools.product(cfg.models, cfg.associations, cfg.initiations, cfg.clutters):
        if assoc == "pmbm" and init == "two-point":
            continue  # the PMBM's births are its Poisson part's (one-point)
        fitted, trackers = [], []
        imm = model == IMM_MODEL
        meas = get_measurement(cfg.measurement if imm else get_model(model).measurement_or_base(cfg.measurement))
        extra = {"imm_modes": cfg.imm_modes} if imm else {}

        def make_step(sc):  # called within this iteration (score_runs)
            args = dict(model=model, association=assoc, detection_prob=cfg.detection_prob,
                        clutter_density=study_clutter(clutter, sc, cfg.clutter_density), max_speed=cfg.max_speed,
                        measurement=meas.name, initiation=init, **extra)
            if cfg.noise == "data":
                noise, text = noise_fit(sc.times, [Z[:, :meas.dim] for Z in sc.detections], args, cfg.meas_std,
                                        cfg.heading_std)
                args.update(noise)
                fitted.append(text)
            trk = MultiTargetTracker(meas_std=meas.stds(cfg.meas_std, cfg.heading_std), **args)
            trackers.append(trk)

            def step(t, Z, trk=trk, m=meas.dim):
                rep = trk.step(t, Z[:, :m])
                return rep.ids, rep.states[:, :2]

            return step

        per_run, wall, scans = score_runs(scen, make_step, cfg.c, cfg.p)
        cells.append(multi_cell(model, assoc, trackers[-1].initiation, per_run, wall, scans, clutter=clutter,
                                accel_std=" | ".join(fitted) if fitted else "default"))
        if progress is not None:
            progress(cells[-1])
    return cells


def format_multi_table(cells: list, cfg: MultiStudyConfig) -> str:
    """The GOSPA table as text: per cell the mean per scan over all runs (parts in m^p) and, over two or more runs,
    ± the half-width of the 95 % Student-t interval over the runs (``MultiCell.interval``); switches per run."""
    what = f"the {cfg.dataset} trajectories" if cfg.dataset else f"{int(round(cfg.duration / cfg.dt)) + 1} scans"
    if cfg.dataset and cfg.scans:
        what += f" (first {cfg.scans} scans)"
    if cfg.scenario != "base":
        what += f" of the {cfg.scenario} scenario"
    lam = "λ" if cfg.scenario == "base" else "background λ"
    head = (f"GOSPA (c = {cfg.c:g} m, p = {cfg.p:g}, α = 2) per scan, {cfg.runs} runs × {what}; "
            f"P_D = {cfg.detection_prob:g}, {lam} = {cfg.clutter_density:g} /m²/scan, r = {cfg.meas_std:g} m"
            + (f", pose (heading std {cfg.heading_std:g} rad; models without a heading get the positions)" if measures_heading(cfg) else "")
            + ("; process noise estimated from each run's detections (as lgekf track --multi), in the accel_std column"
               if cfg.noise == "data" else "")
            + ("; ± the 95 % t-interval over the runs" if cfg.runs > 1 else ""))
    w = 15 if cfg.runs > 1 else 7
    lines = [head, f"{'model':<8} {'assoc':<5} {'start':<9} {'clutter':<7} " + " ".join(
        f"{h:>{w}}" for h in ("GOSPA", "loc.", "missed", "false", "switches/run")) + f" {'scans/s':>8}"]
    for c in cells:
        vals = " ".join(f"{format_interval(*c.interval(part), 3):>{w}}" for part in RUN_PARTS[:4])
        sw = format_interval(*c.interval("switches"), 1)
        lines.append(f"{c.model:<8} {c.association:<5} {c.initiation:<9} {c.clutter:<7} {vals} {sw:>{w}} {c.scans_per_s:8.0f}")
    return "\n".join(lines)


def format_interval(mean: float, half: float, digits: int) -> str:
    """The text "mean ± half" (``mean`` alone when the half-width is nan: a single run)."""
    return f"{mean:.{digits}f}" if np.isnan(half) else f"{mean:.{digits}f} ± {half:.{digits}f}"
