"""The divergence monitor of ``lgekf track --multi``: the single-model monitor's rules (``lgekf.apps.divergence``)
applied to every confirmed track of the multi-target tracker, scan by scan.

* **NIS window**: the normalised innovation squared d² = eᵀS⁻¹e of the detection a track *holds* in a scan
  (``MultiTargetTracker.held_nis``: β ≥ 0.5, against the track's prediction), each clipped at its 99.99 % χ²_m
  quantile, summed over the track's last W = ``window`` held detections (and over the last ``short``) and
  compared with the (1 − α) χ² quantile with W·m (short·m) degrees of freedom (``MonitorConfig``: α = 10⁻⁶).
  Held detections passed the gate, so a single one cannot trigger; a track whose detections sit persistently at
  the edge of its gate (an over-confident filter drifting off its object) does.
* **Absurd speed**: the track's speed (``track_speed_course``: |world velocity| of its state) above
  ``speed_factor`` × ``--max-speed`` + ``speed_margin`` (2 × 30 + 1 = 61 m/s by default): twice the fastest
  speed at which the tracker starts a track. (The point estimate: a new track's speed is at most
  ``--max-speed`` by construction, so only a filter that ran away gets there.)
* **Non-finite**: a NaN or infinite state or std.

Recovery: the track is deleted (``MultiTargetTracker.drop``); the tracker's two-point initiation starts a new
track (a new id) from the next detections of the object. Flags (the output's ``flag`` column): 1 on the alarm's
row and on the track's rows of the window before it (at most W + 1 rows), 0 elsewhere. A row with a non-finite
value is not written (the track ends at its previous row, which is flagged).
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass, field

import numpy as np

from ..core.common import common_world_velocity
from ..estimators.multitarget.tracker import IMM_MODEL
from .divergence import MonitorConfig
from .track import speed_and_course, speed_course

__all__ = ["MultiAlarm", "MultiMonitor", "track_speed_course"]


def track_speed_course(model: str, x: np.ndarray) -> np.ndarray:
    """(N, 2) speed and course of a multi-target tracker's states x (N, n): the model's (``track.speed_course``), or
    with the IMM (``IMM_MODEL``) of its combined estimate in the common coordinates (x, y, θ, v_x, v_y, ω)."""
    if model == IMM_MODEL:
        return speed_and_course(common_world_velocity(np.asarray(x, dtype=float)))
    return speed_course(model, x)


@dataclass(frozen=True)
class MultiAlarm:
    """One alarm: the track id, its kind (1 NIS, 2 speed, 3 non-finite, as ``divergence.KIND_NAMES``), the scan
    time, the monitored value and its threshold."""

    track: int
    kind: int
    t: float
    value: float
    limit: float


@dataclass
class MultiMonitor:
    """Scan-by-scan monitor of a tracker's confirmed tracks (module docstring).

    ``scan(trk, report, first_row)`` after each ``trk.step``: returns the rows to flag (indices into the output
    rows, the report's rows numbered from ``first_row``), the report rows to keep (finite ones) and drops the
    alarmed tracks from ``trk``.
    """

    model: str
    m: int
    max_speed: float
    config: MonitorConfig = field(default_factory=MonitorConfig)
    alarms: list = field(default_factory=list)

    def __post_init__(self):
        self.clip, self.long_limit, self.short_limit = self.config.nis_thresholds(self.m)
        self.speed_limit = self.config.speed_factor * self.max_speed + self.config.speed_margin
        self._nis: dict[int, deque] = {}
        self._rows: dict[int, deque] = {}

    def scan(self, trk, report, first_row: int) -> tuple[list, np.ndarray]:
        """Test the tracks after one scan: (output rows to flag, boolean mask of the report's rows to write)."""
        cfg = self.config
        alarmed: dict[int, tuple] = {}
        hid, _ = trk.held
        for i, d in zip(hid.tolist(), np.minimum(trk.held_nis, self.clip).tolist()):
            w = self._nis.setdefault(i, deque(maxlen=cfg.window))
            w.append(d)
            recent = sum(list(w)[-cfg.short:])
            if len(w) >= cfg.short and recent > self.short_limit:
                alarmed[i] = (1, recent, self.short_limit)
            elif len(w) == cfg.window and sum(w) > self.long_limit:
                alarmed[i] = (1, sum(w), self.long_limit)
        ids = report.ids.tolist()
        finite = np.isfinite(report.states).all(axis=1) & np.isfinite(report.stds).all(axis=1)
        speed = np.full(len(ids), np.nan)
        if finite.any():
            speed[finite] = track_speed_course(self.model, report.states[finite])[:, 0]
        for k, i in enumerate(ids):
            if not finite[k]:
                alarmed[i] = (3, float("nan"), float("nan"))
            elif speed[k] > self.speed_limit:
                alarmed.setdefault(i, (2, float(speed[k]), self.speed_limit))
        flag = []
        row = first_row
        for k, i in enumerate(ids):
            if finite[k]:
                self._rows.setdefault(i, deque(maxlen=cfg.window + 1)).append(row)
                row += 1
        for i, (kind, value, limit) in alarmed.items():
            flag.extend(self._rows.pop(i, ()))
            self._nis.pop(i, None)
            self.alarms.append(MultiAlarm(int(i), kind, float(report.t), value, limit))
        if alarmed:
            trk.drop(list(alarmed))
        return flag, finite
