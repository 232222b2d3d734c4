"""Protocol grids for ``lgekf sweep``: a TOML declaration expanded into cells, one study protocol each.

The grid file
-------------
Two tables, both optional; every key is an option of ``lgekf study`` (a ``StudyConfig`` field; ``-`` may
be written for ``_``, and ``measure`` for ``measurement``)::

    [grid]                      # swept axes: a list of values each; one cell per combination
    sigmas = "0:3:7"            # START:STOP:COUNT (numpy.linspace) for any numeric axis
    dt = [0.05, 0.1, 0.2]
    noise_scale = [{}, {cv = 30}]

    [fixed]                     # the same in every cell (not given: the defaults of `lgekf study`)
    trajectories = 1000
    filters = ["se2se2", "se2r2", "ctrv", "cv"]

Values: numbers for ``dt, steps, trajectories, w0, sigma_v, meas_std, heading_std, seed``; strings for
``truth, measurement``; ``[vx, vy]`` for ``v0``; six numbers for ``init_std``; a table ``{cv = 30}`` for
``noise_scale`` (filters not named keep 1).

σ_ω (``sigmas``): in ``[grid]`` every value is **one** σ_ω, a cell of its own (its own draws); in
``[fixed]`` a number, a list or ``"START:STOP:COUNT"`` runs every cell over that whole set with common
random numbers, as ``lgekf study`` does. ``filters`` is not an axis: every cell runs every filter of
``[fixed] filters`` (default: all) on the same draws, and the results have one row per filter.

Seeds
-----
A cell is identified by its complete protocol: the defaults, ``[fixed]`` and its axis values, including
the base ``seed`` (default 2016) and excluding ``filters``. ``key`` (16 hex digits) and the seed of
its ``run_study`` both come from the SHA-256 of that protocol's canonical JSON, so a cell's numbers
depend on nothing but its own protocol: not on the other cells, their order, the number of workers, or
which filters run. Adding values to an axis adds cells and leaves the existing ones unchanged.
"""

from __future__ import annotations

import hashlib
import itertools
import json
import math
import tomllib
from dataclasses import dataclass, field, fields
from pathlib import Path

import numpy as np

from .study import FILTERS, StudyConfig

__all__ = ["Grid", "Cell", "GridError", "load_grid", "parse_grid", "value_text", "OPTION_KINDS", "SIGMA_COLUMN"]

# option -> kind: how a value is read, canonicalised and written in the results table
OPTION_KINDS = {
    "dt": "float", "steps": "int", "trajectories": "int", "sigmas": "sigmas", "v0": "floats2", "w0": "float",
    "sigma_v": "float", "meas_std": "float", "init_std": "floats6", "truth": "str", "seed": "int",
    "noise_scale": "scale", "filters": "filters", "measurement": "str", "heading_std": "float",
}
ALIASES = {"measure": "measurement"}
SIGMA_COLUMN = "sigma_w"  # the results column of σ_ω (the `sigmas` axis)
NOT_AN_AXIS = {
    "filters": "every cell runs every filter of [fixed] filters on the same draws (one row per filter in the results)",
}
_HASH_PREFIX = b"lgekf.sweep.cell/1\n"
#: StudyConfig fields a grid does not set: sweeps run the paper's protocol in the plane (the 3-D study is
#: ``lgekf study --space 3d``), and leaving the field out keeps the cells' keys of earlier sweeps
NOT_AN_OPTION = {"space"}
assert set(OPTION_KINDS) | NOT_AN_OPTION == {f.name for f in fields(StudyConfig)}, "a StudyConfig field has no grid kind"


class GridError(ValueError):
    """A grid file that cannot be used; the message names the file and the option."""


def _is_number(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def _linspace(text: str, where: str) -> list:
    parts = text.split(":")
    try:
        if len(parts) != 3:
            raise ValueError
        a, b, n = float(parts[0]), float(parts[1]), int(parts[2])
    except ValueError:
        raise GridError(f"{where}: expected a list or START:STOP:COUNT, got {text!r}") from None
    if n < 1:
        raise GridError(f"{where}: COUNT must be at least 1, got {text!r}")
    return np.linspace(a, b, n).tolist()


def _float(v, where):
    if not _is_number(v):
        raise GridError(f"{where}: expected a number, got {v!r}")
    return float(v)


def _floats(v, n, where):
    if not isinstance(v, list) or len(v) != n or not all(_is_number(x) for x in v):
        raise GridError(f"{where}: expected a list of {n} numbers, got {v!r}")
    return [float(x) for x in v]


def _normalise(name: str, kind: str, v, where: str):
    """One value of option ``name`` in canonical form (JSON-able; equal protocols give equal values)."""
    if kind == "float":
        return _float(v, where)
    if kind == "int":
        if not isinstance(v, int) or isinstance(v, bool):
            raise GridError(f"{where}: expected an integer, got {v!r}")
        return int(v)
    if kind == "str":
        if not isinstance(v, str):
            raise GridError(f"{where}: expected a string, got {v!r}")
        return v
    if kind == "floats2":
        return _floats(v, 2, where)
    if kind == "floats6":
        return _floats(v, 6, where)
    if kind == "scale":
        if not isinstance(v, dict):
            raise GridError(f"{where}: expected a table of FILTER = K, e.g. {{cv = 30}}, got {v!r}")
        out = {}
        for k, x in v.items():
            if k not in FILTERS:
                raise GridError(f"{where}: unknown filter {k!r}; choose one of {', '.join(FILTERS)}")
            x = _float(x, f"{where}.{k}")
            if x != 1.0:
                out[k] = x
        return {k: out[k] for k in FILTERS if k in out}  # registry order: {cv=30, ctrv=3} == {ctrv=3, cv=30}
    if kind == "filters":
        if not isinstance(v, list) or not v or not all(isinstance(x, str) for x in v):
            raise GridError(f"{where}: expected a list of filter names, got {v!r}")
        return list(dict.fromkeys(v))
    if kind == "sigmas":  # [fixed]: a number, a list or START:STOP:COUNT
        if isinstance(v, str):
            return _linspace(v, where)
        if _is_number(v):
            return [float(v)]
        if isinstance(v, list):
            return [_float(x, where) for x in v]
        raise GridError(f"{where}: expected a number, a list or START:STOP:COUNT, got {v!r}")
    raise AssertionError(kind)


def _axis_values(name: str, kind: str, v, where: str) -> list:
    """The values of a [grid] axis, each in canonical form."""
    if isinstance(v, str) and kind in ("float", "sigmas"):
        vals = _linspace(v, where)
    elif isinstance(v, list):
        vals = v
    else:
        raise GridError(f"{where}: a [grid] axis needs a list of values (or START:STOP:COUNT for numbers), got {v!r}")
    if not vals:
        raise GridError(f"{where}: an axis needs at least one value")
    if kind == "sigmas":  # one σ_ω per cell
        out = [[_float(x, f"{where}[{i}]")] for i, x in enumerate(vals)]
    else:
        out = [_normalise(name, kind, x, f"{where}[{i}]") for i, x in enumerate(vals)]
    seen = set()
    for x in out:
        k = json.dumps(x, sort_keys=True)
        if k in seen:
            raise GridError(f"{where}: the value {value_text(name, x)} is given twice")
        seen.add(k)
    return out


def value_text(name: str, v) -> str:
    """A canonical value as the results table writes it: numbers as numbers, lists as in the CLI (``3.0,0.0``),
    ``noise_scale`` as ``cv=30.0 ctrv=3.0`` (``none`` when every scale is 1)."""
    kind = OPTION_KINDS[name]
    if kind in ("floats2", "floats6", "filters"):
        return ",".join(repr(x) if isinstance(x, float) else str(x) for x in v)
    if kind == "sigmas":
        return ",".join(repr(x) for x in v)
    if kind == "scale":
        return " ".join(f"{k}={x!r}" for k, x in v.items()) or "none"
    return repr(v) if isinstance(v, float) else str(v)


def column_type(name: str) -> type:
    """The type of a table column holding option ``name`` (float, int or str)."""
    return {"float": float, "int": int, "sigmas": float}.get(OPTION_KINDS[name], str)


def _defaults() -> dict:
    c = StudyConfig()
    out = {}
    for f in fields(StudyConfig):
        if f.name in NOT_AN_OPTION:
            continue
        v = getattr(c, f.name)
        if isinstance(v, tuple):
            v = list(v)
        out[f.name] = _normalise(f.name, OPTION_KINDS[f.name], v, f"default {f.name}")
    return out


@dataclass(frozen=True)
class Cell:
    """One protocol of a grid.

    Attributes
    ----------
    index : int
        Position in the grid's expansion (the last axis varies fastest).
    axes : dict
        Axis name -> this cell's value (canonical form).
    options : dict
        Every study option of the cell (defaults, ``[fixed]``, axes), canonical form, with the base seed.
    key : str
        16 hex digits identifying the protocol (``filters`` excluded).
    seed : int
        The seed of the cell's ``run_study``, derived from the same digest.
    """

    index: int
    axes: dict
    options: dict
    key: str
    seed: int

    def config(self) -> StudyConfig:
        """The cell's ``StudyConfig`` (its derived seed in place of the base seed)."""
        return config_from_options(self.options, self.seed)


def config_from_options(options: dict, seed: int) -> StudyConfig:
    """A ``StudyConfig`` from canonical options (``lgekf.experiments.grid``) and a cell seed."""
    kw = dict(options)
    kw["seed"] = int(seed)
    kw["v0"] = tuple(kw["v0"])
    kw["init_std"] = tuple(kw["init_std"])
    kw["filters"] = tuple(kw["filters"])
    kw["noise_scale"] = {f: kw["noise_scale"].get(f, 1.0) for f in FILTERS}
    return StudyConfig(**kw)


def cell_identity(options: dict) -> tuple[str, int]:
    """(key, seed) of a cell from its canonical options: SHA-256 of their JSON without ``filters``."""
    ident = {k: v for k, v in options.items() if k != "filters"}
    digest = hashlib.sha256(_HASH_PREFIX + json.dumps(ident, sort_keys=True, separators=(",", ":")).encode()).hexdigest()
    return digest[:16], int(digest[16:31], 16)


@dataclass
class Grid:
    """A declared grid: axes (name -> values, file order) and fixed options (name -> value), canonical."""

    axes: dict
    fixed: dict
    source: str = "<grid>"
    _cells: list | None = field(default=None, repr=False)

    @property
    def filters(self) -> list:
        return list(self.fixed.get("filters", _defaults()["filters"]))

    @property
    def n_cells(self) -> int:
        return math.prod(len(v) for v in self.axes.values())

    def cells(self) -> list:
        """Every cell, validated (a ``GridError`` names the first invalid one)."""
        if self._cells is None:
            base = {**_defaults(), **self.fixed}
            names = list(self.axes)
            out = []
            for i, combo in enumerate(itertools.product(*self.axes.values())):
                axes = dict(zip(names, combo))
                options = {**base, **axes}
                key, seed = cell_identity(options)
                cell = Cell(i, axes, options, key, seed)
                try:
                    cell.config().validate()
                except ValueError as e:
                    where = ", ".join(f"{k}={value_text(k, v)}" for k, v in axes.items())
                    raise GridError(f"{self.source}: cell {i}{f' ({where})' if where else ''}: {e}") from None
                out.append(cell)
            self._cells = out
        return self._cells

    def axis_columns(self) -> list:
        """The results columns of the axes: each axis by its option name, ``sigmas`` as ``sigma_w``."""
        return [SIGMA_COLUMN if a == "sigmas" else a for a in self.axes]

    def describe(self) -> dict:
        """The grid as JSON-able data (for meta.json)."""
        return {"axes": {k: v for k, v in self.axes.items()}, "fixed": dict(self.fixed)}


def parse_grid(data: dict, source: str = "<grid>") -> Grid:
    """A ``Grid`` from the parsed TOML (``{"grid": {...}, "fixed": {...}}``).

    Raises
    ------
    GridError
        An unknown table or option, a value of the wrong type, an option in both tables, an option
        that cannot be an axis, or an invalid cell.
    """
    unknown = [k for k in data if k not in ("grid", "fixed")]
    if unknown:
        raise GridError(f"{source}: unknown table [{unknown[0]}]; a grid file has [grid] (swept options) and [fixed]")
    tables = {}
    for table in ("grid", "fixed"):
        raw = data.get(table, {})
        if not isinstance(raw, dict):
            raise GridError(f"{source}: [{table}] must be a table")
        out = {}
        for key, v in raw.items():
            name = ALIASES.get(key, key.replace("-", "_"))
            if name not in OPTION_KINDS:
                raise GridError(f"{source}: [{table}] {key}: not an option of `lgekf study`; choose from {', '.join(OPTION_KINDS)}")
            if name in out:
                raise GridError(f"{source}: [{table}] {key}: given twice")
            out[name] = (key, v)
        tables[table] = out
    both = set(tables["grid"]) & set(tables["fixed"])
    if both:
        raise GridError(f"{source}: {sorted(both)[0]} is in [grid] and in [fixed]; give it in one of them")
    axes = {}
    for name, (key, v) in tables["grid"].items():
        if name in NOT_AN_AXIS:
            raise GridError(f"{source}: [grid] {key}: not an axis: {NOT_AN_AXIS[name]}")
        axes[name] = _axis_values(name, OPTION_KINDS[name], v, f"{source}: [grid] {key}")
    fixed = {name: _normalise(name, OPTION_KINDS[name], v, f"{source}: [fixed] {key}") for name, (key, v) in tables["fixed"].items()}
    if "seed" in fixed and fixed["seed"] < 0:
        raise GridError(f"{source}: [fixed] seed: must be a non-negative integer, got {fixed['seed']}")
    return Grid(axes, fixed, source)


def load_grid(path) -> Grid:
    """Read and check a grid file (TOML).

    Parameters
    ----------
    path : str or Path
        The grid file.

    Returns
    -------
    Grid
        With every cell validated.

    Raises
    ------
    GridError
        An unreadable or invalid file (one line naming the file and the problem).
    """
    p = Path(path)
    try:
        text = p.read_text(encoding="utf-8")
    except IsADirectoryError:
        raise GridError(f"{p}: is a directory, expected a grid file (TOML)") from None
    except OSError as e:
        raise GridError(f"{p}: cannot read ({e.strerror or e})") from None
    except UnicodeDecodeError:
        raise GridError(f"{p}: not a text file (cannot decode as UTF-8)") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise GridError(f"{p}: not valid TOML ({e})") from None
    grid = parse_grid(data, str(p))
    grid.cells()
    return grid
