"""The robustness set of ``lgekf track``: simulated and real runs on which no filter may diverge when
``lgekf track`` is run with no options (``benchmarks/robustness.py`` prints the table,
``tests/tracking/test_robustness.py`` asserts it on a reduced set).

Each case is a set of tracks (objects) with truth positions, truth speeds (and turn rates where known)
and noisy positions. Two runs per case and model:

* **before** — the tracker as it was before issue #14: measurement std 0.3 m, the model's default
  process noise, no divergence monitor (``track_arrays``);
* **after** — ``lgekf track`` with no options: noise from the data (``defaults.plan_noise``) and the
  divergence monitor with recovery (``track_monitored``).

Criteria, over the rows k ≥ 2 of every track that are not flagged (``flag`` = 0: the rows ``lgekf
track`` vouches for; the flagged rows are the diverged-and-recovered ones, counted separately):

* the case's position RMSE (all tracks pooled) must be below the raw measurements' RMSE on the same rows;
* no track may diverge: a track diverges when on any row its position error exceeds both 10 σ (σ the
  true measurement std) and 5 × the position std the filter reports (√(P_xx + P_yy)): a gross error that
  the filter does not know about (a 3 m error right after a 2 s gap, with the filter's own std saying
  so, is not divergence); or when its speed RMSE
  (|speed estimate| − |true speed|) exceeds max(2 m/s, the RMSE of the raw finite-difference speed
  |z_k − z_{k−1}|/Δt against the mean true speed of the step).

A case without speed truth is judged on the positions only. "before" has no flags (all rows count).
A case is reported as **hard** for a model when it passes but more than 2 % of its rows are flagged, or
its position RMSE over all rows (flagged included) is not below the raw RMSE.
"""

from __future__ import annotations

import math
import zlib
from dataclasses import dataclass, field

import numpy as np

from ..core.covariance import packed_diagonal
from ..core.registry import MODELS, get_model
from ..experiments.scenarios import drive, parking, sample, sample_times, urban_drive, Segment
from ..io.datasets import data_root, load_kitti, load_pedestrian, load_smartloc
from .defaults import plan_noise
from .divergence import MonitorConfig, speeds
from .track import DEFAULT_HEADING_STD, DEFAULT_OMEGA_STD, TRACK_HEADING_CAP, TrackConfig, track_arrays, track_monitored

HARD_FLAGGED = 0.02
GROSS_ERROR = 10.0  # a position error above GROSS_ERROR x the true noise std ...
GROSS_STD = 5.0  # ... and above GROSS_STD x the filter's position std is a diverged track

__all__ = ["Case", "Result", "simulated_cases", "real_cases", "run_case", "markdown_table", "summary_table"]


@dataclass
class Case:
    """Tracks sorted by object: truth t, p (N, 2), speed (N,) or None, turn rate w (N,) or None; noisy z."""

    name: str
    description: str
    t: np.ndarray
    p: np.ndarray
    speed: np.ndarray | None
    w: np.ndarray | None
    z: np.ndarray
    starts: np.ndarray
    meas_std: float

    @property
    def n_tracks(self) -> int:
        return len(self.starts) - 1


@dataclass
class Result:
    """One case × model × run ("before" / "after")."""

    case: str
    model: str
    run: str
    pos: float
    raw: float
    speed: float  # nan without speed truth
    speed_bound: float
    omega: float  # turn-rate RMSE (nan without truth or for a model without ω)
    tracks: int
    diverged_tracks: int
    flagged: float  # share of rows flagged
    alarms: int
    pos_all: float = float("nan")  # position RMSE over all rows k >= 2, flagged included
    raw_all: float = float("nan")
    noise: str = ""
    track_detail: list = field(default_factory=list)

    @property
    def diverged(self) -> bool:
        return self.diverged_tracks > 0 or not self.pos < self.raw

    @property
    def hard(self) -> bool:
        return not self.diverged and (self.flagged > HARD_FLAGGED or not self.pos_all < self.raw_all)


def _case_from_tracks(name, description, tracks, meas_std, rng):
    """tracks: list of (t, p, speed, w) -> a Case with noisy positions."""
    lens = [len(tr[0]) for tr in tracks]
    starts = np.zeros(len(tracks) + 1, dtype=np.int64)
    np.cumsum(lens, out=starts[1:])
    t = np.concatenate([tr[0] for tr in tracks])
    p = np.concatenate([tr[1] for tr in tracks])
    speed = None if any(tr[2] is None for tr in tracks) else np.concatenate([tr[2] for tr in tracks])
    w = None if any(tr[3] is None for tr in tracks) else np.concatenate([tr[3] for tr in tracks])
    z = p + meas_std * rng.standard_normal(p.shape)
    return Case(name, description, t, p, speed, w, z, starts, meas_std)


def _simulated(name, description, make_drive, times, meas_std, seed, n_tracks=3):
    rng = np.random.default_rng(seed)
    tracks = []
    for _ in range(n_tracks):
        d = make_drive(rng)
        tt = times(rng, d.t[-1])
        t, p, v, w, _ = sample(d, tt, 0.0, rng)
        tracks.append((t, p, np.hypot(v[:, 0], v[:, 1]), w))
    return _case_from_tracks(name, description, tracks, meas_std, rng)


def _regular(rate):
    return lambda rng, T: sample_times(T, rng, (1.0 / rate,))


def simulated_cases(names=None) -> list:
    """The simulated cases (fixed seeds): see ``docs/robustness.md`` for the list."""
    car = lambda rng: drive(urban_drive(280.0, rng))  # noqa: E731
    ped = lambda rng: drive(urban_drive(120.0, rng, cruise=(1.0, 1.6), turn_speed=(0.8, 1.2), radius=(1.0, 3.0),  # noqa: E731
                                        accel=(0.5, 1.0), brake=(0.5, 1.0), wait=(1.0, 5.0), cruise_time=(3.0, 10.0)))
    stopgo = lambda rng: drive(urban_drive(200.0, rng, cruise=(3.0, 8.0), cruise_time=(2.0, 6.0), wait=(2.0, 8.0),  # noqa: E731
                                           events=("stop", "stop", "turn")))
    straight = lambda rng: drive([Segment(5.0, 2.0), Segment(20.0), Segment(4.0, -1.0), Segment(10.0),  # noqa: E731
                                  Segment(6.0, 1.5), Segment(20.0), Segment(8.0, -2.0), Segment(10.0)],
                                 heading0=float(rng.uniform(-math.pi, math.pi)))
    parked = lambda rng: drive([Segment(60.0)], heading0=float(rng.uniform(-math.pi, math.pi)))  # noqa: E731
    gnss_times = lambda rng, T: sample_times(T, rng, (0.2, 0.3), (0.93, 0.07))  # noqa: E731
    gappy = lambda rng, T: sample_times(T, rng, (0.1, 0.2, 0.5, 2.0), (0.6, 0.2, 0.15, 0.05))  # noqa: E731
    specs = {
        "gnss-car": ("urban car, 280 s, 1 m noise, 5 Hz with 0.2/0.3 s steps (the issue's run)", car, gnss_times, 1.0),
        "noise-0.3x": ("urban car, 10 Hz, 0.09 m noise (0.3x the old 0.3 m default)", car, _regular(10), 0.09),
        "noise-3x": ("urban car, 10 Hz, 0.9 m noise (3x the old default)", car, _regular(10), 0.9),
        "rate-1Hz": ("urban car, 1 Hz, 1 m noise (GNSS at 1 Hz)", car, _regular(1), 1.0),
        "rate-2Hz": ("urban car, 2 Hz, 0.3 m noise", car, _regular(2), 0.3),
        "irregular": ("urban car, steps 0.1/0.2/0.5/2 s (gaps), 0.3 m noise", car, gappy, 0.3),
        "stop-and-go": ("car stopping every few seconds (v = 0 held 2-8 s), 10 Hz, 0.3 m", stopgo, _regular(10), 0.3),
        "reversals": ("parking: forward, stop, reverse on a curve, stop (x5), 10 Hz, 0.1 m", lambda rng: drive(parking(rng)),
                      _regular(10), 0.1),
        "straight": ("straight line (ω = 0 exactly), speed changes, 10 Hz, 0.3 m", straight, _regular(10), 0.3),
        "parked": ("stationary object (v = 0, ω = 0), 60 s, 10 Hz, 0.3 m", parked, _regular(10), 0.3),
        "pedestrian": ("walker 1-1.6 m/s, sharp turns, stops, 2.5 Hz, 0.3 m", ped, _regular(2.5), 0.3),
    }
    out = []
    for i, (name, (desc, make, times, r)) in enumerate(specs.items()):
        if names is None or name in names:
            out.append(_simulated(name, desc, make, times, r, seed=1400 + i))
    return out


def real_cases(root=None, names=None) -> tuple:
    """The real cases whose data exist under the data root: (cases, {name: reason skipped})."""
    base = data_root(root)
    cases, skipped = [], {}

    def want(n):
        return names is None or n in names

    def rng(name):
        return np.random.default_rng([1414, zlib.crc32(name.encode())])

    if want("berlin-gnss"):
        folder = base / "tuc_smartloc"
        if (folder / "Berlin_Potsdamer_Platz_GT.txt").exists():
            d = load_smartloc(folder)
            tracks = [(d.t, d.p, np.hypot(*d.v.T), d.w)] * 3  # three noise draws of the one drive
            cases.append(_case_from_tracks("berlin-gnss", "smartLoc Berlin car (real, 283 s, 5 Hz, 0.2/0.3 s), truth "
                                           "+ 1 m noise, odometry speed/yaw rate", tracks, 1.0, rng("berlin-gnss")))
        else:
            skipped["berlin-gnss"] = f"{folder}/Berlin_Potsdamer_Platz_GT.txt not found"
    folder = base / "kitti_oxts"
    if want("kitti-1m") or want("kitti-1Hz"):
        if folder.exists() and any(folder.glob("*.txt")):
            k = load_kitti(folder)
            tracks = [(k.t[a:b], k.p[a:b], np.hypot(*k.v[a:b].T), k.w[a:b]) for a, b in zip(k.starts[:-1], k.starts[1:])]
            if want("kitti-1m"):
                cases.append(_case_from_tracks("kitti-1m", "KITTI OXTS car (21 sequences, 9.7 Hz) + 1 m noise", tracks, 1.0,
                                               rng("kitti-1m")))
            if want("kitti-1Hz"):
                sub = [(tr[0][::10], tr[1][::10], tr[2][::10], tr[3][::10]) for tr in tracks if len(tr[0]) >= 50]
                cases.append(_case_from_tracks("kitti-1Hz", "KITTI every 10th sample (0.97 Hz) + 1 m noise", sub, 1.0,
                                               rng("kitti-1Hz")))
        else:
            for n in ("kitti-1m", "kitti-1Hz"):
                if want(n):
                    skipped[n] = f"{folder} not found"
    if want("eth"):
        f = base / "eth_ucy_trajectronpp" / "biwi_eth.txt"
        if f.exists():
            e = load_pedestrian([f], 0.6667 / 10, "eth", 5)
            tracks = [(e.t[a:b], e.p[a:b], None, None) for a, b in zip(e.starts[:-1], e.starts[1:])]
            cases.append(_case_from_tracks("eth", "ETH pedestrians (real, 0.667 s steps) + 0.3 m noise (no speed truth)",
                                           tracks, 0.3, rng("eth")))
        else:
            skipped["eth"] = f"{f} not found"
    return cases, skipped


# --------------------------------------------------------------------------------------- metrics
def _per_track(case: Case, err2: np.ndarray, use: np.ndarray | None = None, rows_from: int = 2) -> tuple:
    """(pooled RMSE, per-track RMSE (J,)) of squared errors over rows k >= rows_from of each track (and
    where ``use``)."""
    J = case.n_tracks
    obj = np.repeat(np.arange(J), np.diff(case.starts))
    k = np.arange(case.t.size) - case.starts[obj]
    w = (k >= rows_from) & np.isfinite(err2)
    if use is not None:
        w &= use
    num = np.bincount(obj, weights=np.where(w, err2, 0.0), minlength=J)
    den = np.bincount(obj, weights=w.astype(float), minlength=J)
    with np.errstate(invalid="ignore", divide="ignore"):
        return float(math.sqrt(num.sum() / den.sum())) if den.sum() else float("nan"), np.sqrt(num / den)


def _fd_speed_err2(case: Case) -> np.ndarray:
    """Squared error of the raw finite-difference speed of each step (row k: step k-1 -> k; nan on row 0)."""
    e = np.full(case.t.size, np.nan)
    d = np.hypot(*np.diff(case.z, axis=0).T) / np.diff(case.t)
    truth = 0.5 * (case.speed[1:] + case.speed[:-1])
    e[1:] = (d - truth) ** 2
    e[case.starts[:-1]] = np.nan
    return e


def evaluate_run(case: Case, model: str, run: str, x: np.ndarray, p: np.ndarray, flag: np.ndarray, alarms: int,
                 noise: str = "") -> Result:
    """Metrics and the divergence verdict of one run (x states, p packed covariances; module docstring)."""
    use = np.asarray(flag) == 0
    pe2 = np.sum((x[:, :2] - case.p) ** 2, axis=1)
    re2 = np.sum((case.z - case.p) ** 2, axis=1)
    pos, pos_t = _per_track(case, pe2, use)
    raw, raw_t = _per_track(case, re2, use)
    pos_all, _ = _per_track(case, pe2)
    raw_all, _ = _per_track(case, re2)
    J = case.n_tracks
    obj = np.repeat(np.arange(J), np.diff(case.starts))
    k = np.arange(case.t.size) - case.starts[obj]
    diag = packed_diagonal(get_model(model).n)
    std = np.sqrt(np.maximum(p[:, diag[0]], 0) + np.maximum(p[:, diag[1]], 0))
    gross = (np.sqrt(pe2) > GROSS_ERROR * case.meas_std) & (np.sqrt(pe2) > GROSS_STD * std)
    bad = np.zeros(J, bool)
    bad[np.unique(obj[use & (k >= 2) & gross])] = True
    nonfinite = use & (k >= 2) & ~np.isfinite(pe2)
    bad[np.unique(obj[nonfinite])] = True
    speed = bound = float("nan")
    if case.speed is not None:
        speed, speed_t = _per_track(case, (speeds(model, x) - np.abs(case.speed)) ** 2, use)
        fd, fd_t = _per_track(case, _fd_speed_err2(case), rows_from=1)
        bound_t = np.maximum(2.0, fd_t)
        bound = float(max(2.0, fd))
        with np.errstate(invalid="ignore"):
            bad |= speed_t > bound_t
    spec = get_model(model)
    omega = float("nan")
    if case.w is not None and "omega" in spec.state_names:
        omega, _ = _per_track(case, (x[:, spec.state_names.index("omega")] - case.w) ** 2, use)
    return Result(case.name, model, run, pos, raw, speed, bound, omega, case.n_tracks, int(bad.sum()),
                  float(np.mean(~use)), alarms, pos_all, raw_all, noise, [int(i) for i in np.flatnonzero(bad)])


def run_case(case: Case, models=None, runs=("before", "after")) -> list:
    """Every model on ``case``: "before" (0.3 m, default process noise, no monitor) and "after" (``lgekf
    track`` with no options). Returns a list of Result."""
    models = list(models or MODELS)
    out = []
    if "before" in runs:
        cfg = TrackConfig()
        for m in models:
            x, p, _ = track_arrays(m, case.t, case.z, case.starts, cfg)
            out.append(evaluate_run(case, m, "before", x, p, np.zeros(case.t.size), 0, "meas-std 0.3 (default)"))
    if "after" in runs:
        plan = plan_noise(case.t, case.z, case.starts, models, omega_std=DEFAULT_OMEGA_STD, heading_std=DEFAULT_HEADING_STD,
                          heading_cap=TRACK_HEADING_CAP)
        for m in models:
            cfg = TrackConfig(dict(plan.accel_std), plan.meas_std, heading_cap=TRACK_HEADING_CAP)
            r = track_monitored(m, case.t, case.z, case.starts, cfg, monitor=MonitorConfig())
            noise = f"meas-std {plan.meas_std:.3g}, accel-std {','.join(f'{v:.3g}' for v in plan.accel_std[m])}"
            out.append(evaluate_run(case, m, "after", r.x, r.p, r.flag, len(r.alarms), noise))
    return out


# ---------------------------------------------------------------------------------------- tables
def _fmt(v, d=3):
    return "n/a" if not np.isfinite(v) else f"{v:.{d}f}"


def markdown_table(results: list) -> str:
    """Case × model: before and after side by side (position RMSE vs raw, speed and turn-rate RMSE, verdict)."""
    by = {(r.case, r.model, r.run): r for r in results}
    keys = list(dict.fromkeys((r.case, r.model) for r in results))
    lines = ["| case | model | raw pos | before: pos | speed | ω | verdict | after: pos (all rows) | speed | ω | flagged "
             "| verdict |", "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for c, m in keys:
        b, a = by.get((c, m, "before")), by.get((c, m, "after"))
        ref = b or a
        cells = [c, m, _fmt(ref.raw_all)]
        if b is None:
            cells += [""] * 4
        else:
            cells += [_fmt(b.pos), _fmt(b.speed, 2), _fmt(b.omega, 2), _verdict(b)]
        if a is None:
            cells += [""] * 5
        else:
            cells += [f"{_fmt(a.pos)} ({_fmt(a.pos_all)})", _fmt(a.speed, 2), _fmt(a.omega, 2),
                      f"{100 * a.flagged:.1f} % ({a.alarms})", _verdict(a)]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def _verdict(r: Result) -> str:
    """"**diverged** (j/J)" (j of J tracks diverged), "**worse than raw**", "hard" (passes, see Result.hard), "ok"."""
    if r.diverged_tracks:
        return f"**diverged** ({r.diverged_tracks}/{r.tracks})"
    if r.diverged:
        return "**worse than raw**"
    return "hard" if r.run == "after" and r.hard else "ok"


def summary_table(results: list, cases: list) -> str:
    """One row per case: models that failed before / after ("(w)": no track diverged but the position RMSE was
    not below the raw measurements'), hard models, worst after-fix margin, flagged rows."""
    lines = ["| case | description | failed before | failed after | hard after | worst pos/raw after | "
             "rows flagged after (max) |", "|---|---|---|---|---|---|---|"]
    desc = {c.name: c.description for c in cases}
    for name in dict.fromkeys(r.case for r in results):
        rs = [r for r in results if r.case == name]
        before = [r.model + ("" if r.diverged_tracks else " (w)") for r in rs if r.run == "before" and r.diverged]
        after = [r for r in rs if r.run == "after"]
        worst = max((r.pos / r.raw for r in after), default=float("nan"))
        flagged = max((r.flagged for r in after), default=0.0)
        lines.append(f"| {name} | {desc.get(name, '')} | {', '.join(before) or 'none'} | "
                     f"{', '.join(r.model for r in after if r.diverged) or 'none'} | "
                     f"{', '.join(r.model for r in after if r.hard) or 'none'} | {worst:.2f} | {100 * flagged:.1f} % |")
    return "\n".join(lines)
