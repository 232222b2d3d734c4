"""The clutter density λ of the multi-target tracker (expected false alarms per m² per scan in the plane, per m³ in
3-D space: per unit of the d-dimensional volume of the positions, d = ``dim``; "area" below is that volume): one
component with one job, next to the association and the track management of ``MultiTargetTracker`` (as Stone Soup composes a tracker
of initiator, deleter and associator).

The tracker talks to it twice per scan:

1. before the association, ``density(t, Z, expected)`` gives λ at the detections Z (M, m) of the scan at time t:
   a float (the same everywhere) or an array (M,), with ``expected`` = Σ_i P_D P_G r_i over the tracks after
   prediction (the number of this scan's detections the tracks are expected to explain); λ enters the likelihood ratio
   W_ij = r_i P_D N(e_ij; 0, S_i)/λ(z_j) and a one-point track's existence β/(β + λ(z_j));
2. after it, ``update(Z, clutter_weight)`` with the probability of each detection that it is *not* a confirmed
   track's (1 − Σ_{i confirmed} p_ij).

The estimators:

* ``ConstantClutter(λ)``: a given density (``--clutter-density``; the tracker's float argument), the default.
* ``ScanClutter``: **per scan**, the moment estimate of the clutter measurement density used with IPDA/JIPDA
  (Musicki & Evans 2004): of the M_k detections of scan k the tracks explain Σ_i P_D P_G r_i on average,
  the rest are false alarms, m̂_k = M_k − Σ_i P_D P_G r_i; averaged over scans with the forgetting factor a
  (``forgetting``, default 0.9: weights a^(k−l), an effective memory of 1/(1 − a) = 10 scans) and divided by the
  surveillance area V (``area``; default the bounding box of the detections seen so far, at least 1 m²):

      λ_k = max(Σ_l a^(k−l) m̂_l / Σ_l a^(k−l), 1 − a) / V.

  The average is clipped, not each m̂_l (clipping each scan would bias a low clutter upwards); its floor, 1 − a
  false alarms per scan (one per memory), is what the memory cannot tell from none. The current scan is in its own
  estimate (a burst is seen in the scan it starts), steady-state std √(λV (1 − a)/(1 + a))/V for Poisson clutter
  (11 % at a = 0.9 and 4 false alarms per scan). A new object's detections count as clutter until its track's
  existence rises (two scans with one-point initiation); a target detected more often than the assumed P_D makes
  λ too high by (P_D,true − P_D) per target and scan.
* ``ClutterMap``: **in space**, λ(z) = λ_k ρ(c(z)): the per-scan level λ_k (a ``ScanClutter``, which follows a
  burst within a few scans) times a slow spatial shape ρ on a grid of square cells c of side h (``cell``; cubes in 3-D). Each cell
  keeps a recursive average of the clutter weights w_j of the detections that fell into it, S_c ← a_m S_c +
  Σ_{j in c} w_j (``forgetting``, default 0.99: a memory of 100 scans, as clutter maps keep long memories), and

      ρ_c = K (S_c + m₀) / (Σ_c' S_c' + K m₀),    K = V / h^d cells in the surveillance area,

  the share of the clutter in cell c against the uniform share 1/K, with m₀ = ``prior`` (default 1) counts of
  uniform clutter per cell (Laplace smoothing): a cell that has seen few detections stays near the mean level,
  and the mean of ρ over the area is 1, so the map's mean density is the per-scan level. The cell side: for a
  file (``clutter_from_data``, ``lgekf track --multi``) from its counts, the side at which each cell would hold
  ``MAP_COUNTS`` = 30 counts over the map's memory if all detections were clutter spread evenly
  (``map_cell_from_counts``: a cell's Poisson noise then about 1/√30 = 18 %; smaller cells are noisier, larger
  ones blur a patch); for the tracker alone, which has not seen the data, ``CELL_GATES`` = 8 gate diameters, the
  gate radius √(2γ)·r of a held track (S ≈ 2R) (4, 6, 8 and 12 gate diameters measured: docs/multi_target.md).
  The grid grows with the detections; beyond ``MAX_CELLS`` cells its cells are doubled (2 × 2, or 2 × 2 × 2, summed).
* ``bounding_box_density(z, scans)``: the per-file estimate of ``lgekf track --multi`` before the estimators
  (``--clutter file``): all detections per scan over the data's bounding-box area (an over-estimate: the targets'
  detections count too).

``clutter_estimator(value)`` makes the tracker's component from its ``clutter_density`` argument (a number, a name
of ``CLUTTER_ESTIMATORS`` or an estimator); ``fresh()`` gives an unused copy with the same settings (a tracker
never changes an estimator it was given). ``clutter_from_data(source, z, scans)`` is the choice of ``lgekf track
--multi --clutter file|scan|map`` (the estimators over the area of the file's bounding box).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from ...core.validate import positive_scalar

__all__ = ["ClutterEstimator", "ConstantClutter", "ScanClutter", "ClutterMap", "CLUTTER_ESTIMATORS", "clutter_estimator",
           "bounding_box_density", "bounding_box_area", "clutter_from_data", "map_cell_from_counts", "CLUTTER_SOURCES",
           "DEFAULT_CLUTTER_SOURCE", "CELL_GATES", "MAP_COUNTS", "MAX_CELLS", "MIN_AREA"]

CELL_GATES = 8.0  # ClutterMap: default cell side, in gate diameters (measured: docs/multi_target.md)
MAX_CELLS = 1_000_000  # ClutterMap: the grid's size at most (8 MB); beyond, the cells are doubled
MIN_AREA = 1.0  # m² (m³ in 3-D): the surveillance area at least (detections on a line or a point)
MAP_COUNTS = 30.0  # clutter_from_data: a map's cells hold this many counts per memory if the detections were even


def bounding_box_area(z: np.ndarray, dim: int = 2) -> float:
    """The area (m²; the volume, m³, for dim = 3) of the bounding box of positions z (N, ≥dim) (their first ``dim``
    columns), at least ``MIN_AREA``."""
    span = np.ptp(z[:, :dim], axis=0) if z.shape[0] else np.zeros(dim)
    return max(float(np.prod(span)), MIN_AREA)


def bounding_box_density(z: np.ndarray, scans: int, dim: int = 2) -> float:
    """All detections per scan over the area of their bounding box (per m² per scan; per m³ for dim = 3): the
    per-file estimate (module docstring), at least 1e-12.

    Parameters
    ----------
    z : ndarray, (N, ≥dim)
        Every detection of the file (positions in the first ``dim`` columns).
    scans : int
        The number of scans.
    dim : int
        The positions' coordinates (2 in the plane, 3 in 3-D space).

    Returns
    -------
    float
    """
    return max((z.shape[0] / max(scans, 1)) / bounding_box_area(z, dim), 1e-12)


def _check_forgetting(name: str, a: float) -> float:
    a = float(a)
    if not 0.0 <= a < 1.0:
        raise ValueError(f"{name}: a forgetting factor must be in [0, 1), got {a}")
    return a


class ClutterEstimator:
    """The interface of the tracker's clutter component (module docstring).

    Attributes
    ----------
    name : str
        What ``lgekf track --multi`` calls it ("given", "scan", "map").
    level : float
        The mean density of the last scan (per m² per scan; nan before the first).
    """

    name = "?"
    level = math.nan
    dim = 2  # the positions' coordinates: the density is per m^dim

    def fresh(self) -> "ClutterEstimator":
        """An unused estimator with the same settings."""
        return dataclasses.replace(self)

    def configure(self, gate_radius: float, dim: int = 2) -> None:
        """The tracker's typical gate radius (m), for defaults that scale with it, and the coordinates of its
        positions (``dim``: 2 in the plane, 3 in 3-D space; the first ``dim`` columns of the detections)."""
        self.dim = int(dim)

    def density(self, t: float, Z: np.ndarray, expected: float):
        """λ at the detections Z (M, m) of the scan at time t, given ``expected`` = Σ_i P_D P_G r_i: a float or an
        array (M,)."""
        raise NotImplementedError

    def update(self, Z: np.ndarray, clutter_weight: np.ndarray) -> None:
        """After the association: each detection's probability of not being a confirmed track's."""

    def describe(self) -> str:
        """What the estimate is (for a line on stderr)."""
        return self.name


@dataclass(eq=False)
class ConstantClutter(ClutterEstimator):
    """A given clutter density λ > 0 (per m² per scan), the same everywhere and in every scan."""

    value: float
    name = "given"

    def __post_init__(self):
        self.value = positive_scalar("clutter-density", self.value)
        self.level = self.value

    def density(self, t, Z, expected):
        return self.value


@dataclass(eq=False)
class ScanClutter(ClutterEstimator):
    """The per-scan moment estimate of the module docstring.

    Parameters
    ----------
    forgetting : float
        a in [0, 1): the weight of the previous scans' average (0: each scan on its own).
    area : float, optional
        The surveillance area V (m²; the volume, m³, in 3-D); default the bounding box of the detections seen so far.
    dim : int
        The positions' coordinates (2 or 3; the tracker sets it: ``configure``).
    """

    forgetting: float = 0.9
    area: float | None = None
    dim: int = 2
    name = "scan"

    def __post_init__(self):
        self.forgetting = _check_forgetting("clutter forgetting", self.forgetting)
        if self.area is not None:
            self.area = positive_scalar("clutter area", self.area)
        self._sum = 0.0  # Σ a^(k−l) m̂_l
        self._weight = 0.0  # Σ a^(k−l)
        self._lo = np.full(self.dim, np.inf)  # the bounding box of the detections so far
        self._hi = np.full(self.dim, -np.inf)
        self.level = math.nan
        self.count = math.nan  # false alarms per scan, the average before dividing by V

    def configure(self, gate_radius: float, dim: int = 2) -> None:
        if int(dim) != self.dim:
            self.dim = int(dim)
            self._lo, self._hi = np.full(self.dim, np.inf), np.full(self.dim, -np.inf)

    @property
    def surveillance_area(self) -> float:
        """V (m², m³ in 3-D): given, or the bounding box of the detections so far (at least ``MIN_AREA``)."""
        if self.area is not None:
            return self.area
        if not np.all(self._hi >= self._lo):
            return MIN_AREA
        return max(float(np.prod(self._hi - self._lo)), MIN_AREA)

    def density(self, t, Z, expected):
        if Z.shape[0]:
            P = Z[:, :self.dim]
            np.minimum(self._lo, P.min(axis=0), out=self._lo)
            np.maximum(self._hi, P.max(axis=0), out=self._hi)
        a = self.forgetting
        self._sum = a * self._sum + (Z.shape[0] - float(expected))
        self._weight = a * self._weight + 1.0
        self.count = max(self._sum / self._weight, 1.0 - a)
        self.level = self.count / self.surveillance_area
        return self.level

    def describe(self) -> str:
        return f"per scan (the moment estimate, forgetting {self.forgetting:g})"


@dataclass(eq=False)
class ClutterMap(ClutterEstimator):
    """The spatial clutter map of the module docstring: λ(z) = per-scan level × the shape of a grid.

    Parameters
    ----------
    cell : float, optional
        The cell side h (m); default ``CELL_GATES`` gate diameters (``configure``; ``clutter_from_data`` gives
        ``map_cell_from_counts``).
    forgetting : float
        a_m in [0, 1): the cells' recursive average.
    prior : float
        m₀ > 0, counts of uniform clutter per cell.
    scan_forgetting : float
        The per-scan level's forgetting factor (``ScanClutter``).
    area : float, optional
        The surveillance area V (m²; the volume, m³, in 3-D); default the bounding box of the detections seen so far.
    dim : int
        The positions' coordinates (2 or 3): the grid's dimension (the tracker sets it: ``configure``).

    Attributes
    ----------
    scan : ScanClutter
        The per-scan level.
    coarsened : int
        How many times the grid's cells were doubled to stay within ``MAX_CELLS``.
    """

    cell: float | None = None
    forgetting: float = 0.99
    prior: float = 1.0
    scan_forgetting: float = 0.9
    area: float | None = None
    dim: int = 2
    name = "map"

    def __post_init__(self):
        self.forgetting = _check_forgetting("clutter-map forgetting", self.forgetting)
        self.prior = positive_scalar("clutter-map prior", self.prior)
        if self.cell is not None:
            self.cell = positive_scalar("clutter-map cell", self.cell)
        self.scan = ScanClutter(self.scan_forgetting, self.area, self.dim)
        # S_c = _stored[c] / _scale (the decay a_m per scan is a growing scale, not a pass over every cell), cell
        # (ix, iy[, iz]) = floor(z / h) at _stored[ix − origin[0], iy − origin[1], ...]; _total = Σ_c _stored[c]
        self._stored = np.zeros((0,) * self.dim)
        self._total = 0.0
        self._scale = 1.0
        self.origin = np.zeros(self.dim, dtype=np.int64)
        self.coarsened = 0
        self.level = math.nan

    def configure(self, gate_radius: float, dim: int = 2) -> None:
        if self.cell is None:
            self.cell = CELL_GATES * 2.0 * positive_scalar("gate radius", gate_radius)
        if int(dim) != self.dim:
            self.dim = int(dim)
            self.scan.configure(gate_radius, dim)
            self._stored, self.origin = np.zeros((0,) * self.dim), np.zeros(self.dim, dtype=np.int64)

    @property
    def counts(self) -> np.ndarray:
        """S_c of every cell of the grid (axis k the k-th coordinate, from ``origin`` · h)."""
        return self._stored / self._scale

    def _grow(self, lo, hi):
        """The grid extended to the cells lo..hi (dim,) of the current h, coarsened (h doubled, 2 × 2 (× 2) cells
        summed) while it would exceed ``MAX_CELLS``."""
        if self._stored.size:
            lo = np.minimum(lo, self.origin)
            hi = np.maximum(hi, self.origin + np.array(self._stored.shape) - 1)
        while int(np.prod(hi - lo + 1)) > MAX_CELLS:
            lo, hi = lo // 2, hi // 2
            if self._stored.size:
                ij = np.nonzero(self._stored)
                merged = np.zeros(tuple(np.array(self._stored.shape) // 2 + 2))
                o = self.origin // 2
                np.add.at(merged, tuple((self.origin[k] + ij[k]) // 2 - o[k] for k in range(self.dim)), self._stored[ij])
                self._stored, self.origin = merged, o
            self.cell *= 2.0
            self.coarsened += 1
        grown = np.zeros(tuple(hi - lo + 1))
        if self._stored.size:
            o = self.origin - lo
            n = np.minimum(np.array(self._stored.shape), np.array(grown.shape) - o)
            grown[tuple(slice(o[k], o[k] + n[k]) for k in range(self.dim))] = self._stored[tuple(slice(0, n[k]) for k in range(self.dim))]
        self._stored, self.origin = grown, lo

    def _cells(self, Z):
        """The grid indices (M, dim) of the detections' cells, the grid grown to hold them."""
        if self.cell is None:
            raise ValueError("clutter map: no cell size (give cell= or let the tracker configure it)")
        ij = np.floor(Z[:, :self.dim] / self.cell).astype(np.int64)
        if ij.shape[0]:
            lo, hi = ij.min(axis=0), ij.max(axis=0)
            if (not self._stored.size or np.any(lo < self.origin)
                    or np.any(hi >= self.origin + np.array(self._stored.shape))):
                self._grow(lo, hi)
                ij = np.floor(Z[:, :self.dim] / self.cell).astype(np.int64)  # h may have doubled
        return ij - self.origin

    @property
    def surveillance_area(self) -> float:
        """V (m², m³ in 3-D) of the per-scan level (``ScanClutter.surveillance_area``)."""
        return self.scan.surveillance_area

    def _cells_in_area(self) -> float:
        return max(self.surveillance_area / self.cell**self.dim, 1.0)

    def shape(self, cells: np.ndarray) -> np.ndarray:
        """ρ at grid cells (M, dim) (indices into ``counts``)."""
        K = self._cells_in_area()
        S = self._stored[tuple(cells.T)] / self._scale if cells.shape[0] else np.zeros(0)
        return K * (S + self.prior) / (self._total / self._scale + K * self.prior)

    def density(self, t, Z, expected):
        self._ij = self._cells(Z)
        self.level = self.scan.density(t, Z, expected)
        return self.level * self.shape(self._ij)

    def update(self, Z, clutter_weight):
        if self.forgetting == 0.0:
            self._stored[:] = 0.0
            self._total, self._scale = 0.0, 1.0
        else:
            self._scale /= self.forgetting
            if self._scale > 1e100:
                self._stored /= self._scale
                self._total /= self._scale
                self._scale = 1.0
        if Z.shape[0]:
            w = np.clip(clutter_weight, 0.0, 1.0) * self._scale
            np.add.at(self._stored, tuple(self._ij.T), w)
            self._total += float(w.sum())

    def peak(self) -> float:
        """The largest ρ over the grid (how many times the mean density the densest cell has); 1 before any count."""
        if self._stored.size == 0:
            return 1.0
        K = self._cells_in_area()
        return float(K * (self._stored.max() / self._scale + self.prior) / (self._total / self._scale + K * self.prior))

    def describe(self) -> str:
        return (f"a map of {self.cell:.3g} m {'cubes' if self.dim == 3 else 'cells'} (forgetting {self.forgetting:g}) times the per-scan level "
                f"(forgetting {self.scan.forgetting:g})")


CLUTTER_ESTIMATORS = {"scan": ScanClutter, "map": ClutterMap}


def clutter_estimator(value) -> ClutterEstimator:
    """The tracker's clutter component from its ``clutter_density`` argument: a number λ > 0 (``ConstantClutter``),
    a name of ``CLUTTER_ESTIMATORS`` ("scan", "map": the estimator with its defaults) or a ``ClutterEstimator``
    (an unused copy: ``fresh``).

    Parameters
    ----------
    value : float, str or ClutterEstimator

    Returns
    -------
    ClutterEstimator
    """
    if isinstance(value, ClutterEstimator):
        return value.fresh()
    if isinstance(value, str):
        if value not in CLUTTER_ESTIMATORS:
            raise ValueError(f"clutter-density: a number or one of {', '.join(CLUTTER_ESTIMATORS)}, got {value!r}")
        return CLUTTER_ESTIMATORS[value]()
    return ConstantClutter(value)


CLUTTER_SOURCES = ("file", "scan", "map")  # what `lgekf track --multi --clutter` chooses from
DEFAULT_CLUTTER_SOURCE = "map"  # without --clutter-density and --clutter (measured: docs/multi_target.md)


def map_cell_from_counts(z: np.ndarray, scans: int, forgetting: float = 0.99, dim: int = 2) -> float:
    """The cell side h (m) at which a clutter map of a file would hold ``MAP_COUNTS`` counts per cell over its memory
    if all the file's detections were clutter spread evenly over their bounding box: h = (V·n/(M̄/(1 − a)))^(1/d), M̄
    detections per scan, a the map's forgetting factor, d = ``dim`` (V/h^d cells).

    Parameters
    ----------
    z : ndarray, (N, ≥dim)
        Every detection of the file.
    scans : int
        The number of scans.
    forgetting : float
        The map's forgetting factor.
    dim : int
        The positions' coordinates (2 or 3).

    Returns
    -------
    float
    """
    per_memory = z.shape[0] / max(scans, 1) / (1.0 - forgetting)
    return (bounding_box_area(z, dim) * MAP_COUNTS / max(per_memory, 1e-12)) ** (1.0 / dim)


def clutter_from_data(source: str, z: np.ndarray, scans: int, dim: int = 2):
    """The tracker's ``clutter_density`` argument for a file of detections without a given density: "file" the
    per-file ``bounding_box_density`` (a float), "scan" a ``ScanClutter`` and "map" a ``ClutterMap`` (cells of
    ``map_cell_from_counts``), both over the area V of the file's bounding box (the surveillance area as the data
    show it).

    Parameters
    ----------
    source : {"file", "scan", "map"}
    z : ndarray, (N, ≥dim)
        Every detection of the file.
    scans : int
        The number of scans.
    dim : int
        The positions' coordinates (2 in the plane, 3 in 3-D space): the density is per m^dim.

    Returns
    -------
    float or ClutterEstimator
    """
    if source == "file":
        return bounding_box_density(z, scans, dim)
    if source not in CLUTTER_ESTIMATORS:
        raise ValueError(f"clutter: one of {', '.join(CLUTTER_SOURCES)}, got {source!r}")
    if source == "map":
        return ClutterMap(cell=map_cell_from_counts(z, scans, dim=dim), area=bounding_box_area(z, dim), dim=dim)
    return ScanClutter(area=bounding_box_area(z, dim), dim=dim)
