"""Protocol grids (`lgekf.experiments.grid`): expansion, canonical values, cell seeds that depend on the cell
alone, and one clear error per bad grid file (`lgekf sweep --dry-run` needs no Dask)."""

from __future__ import annotations

import subprocess
import tomllib

import numpy as np
import pytest
from _cli import cli_command

from lgekf.experiments.grid import GridError, load_grid, parse_grid, value_text
from lgekf.experiments.study import FILTERS, StudyConfig


def grid(text: str):
    return parse_grid(tomllib.loads(text), "g.toml")


def test_cells_are_the_product_of_the_axes_last_axis_fastest():
    g = grid('[grid]\nsigmas = [0.0, 1.0]\ndt = [0.1, 0.2, 0.5]\n[fixed]\ntrajectories = 7\n')
    cells = g.cells()
    assert g.n_cells == len(cells) == 6
    assert [(c.axes["sigmas"], c.axes["dt"]) for c in cells] == [
        ([0.0], 0.1), ([0.0], 0.2), ([0.0], 0.5), ([1.0], 0.1), ([1.0], 0.2), ([1.0], 0.5)]
    cfg = cells[4].config()
    assert isinstance(cfg, StudyConfig)
    assert cfg.sigmas == [1.0] and cfg.dt == 0.2 and cfg.trajectories == 7 and cfg.seed == cells[4].seed
    assert g.axis_columns() == ["sigma_w", "dt"]


def test_linspace_shorthand_and_fixed_sigma_set():
    g = grid('[grid]\ndt = "0.1:0.3:3"\n[fixed]\nsigmas = "0:3:4"\n')
    assert g.axes["dt"] == pytest.approx([0.1, 0.2, 0.3])
    assert g.cells()[0].config().sigmas == np.linspace(0, 3, 4).tolist()  # every cell runs the whole set


def test_seeds_depend_on_the_cell_alone():
    small = grid('[grid]\nsigmas = [0.5, 1.0]\n[fixed]\nsteps = 20\n').cells()
    big = grid('[grid]\nsigmas = [2.0, 1.0, 0.5, 3.0]\n[fixed]\nsteps = 20\n').cells()
    by_sigma = {c.axes["sigmas"][0]: (c.key, c.seed) for c in big}
    for c in small:  # adding values and reordering the axis leaves the existing cells as they were
        assert by_sigma[c.axes["sigmas"][0]] == (c.key, c.seed)
    assert len({c.seed for c in big}) == 4 and len({c.key for c in big}) == 4
    other_base = grid('[grid]\nsigmas = [0.5, 1.0]\n[fixed]\nsteps = 20\nseed = 7\n').cells()
    assert {c.seed for c in other_base}.isdisjoint({c.seed for c in small})
    other_protocol = grid('[grid]\nsigmas = [0.5, 1.0]\n[fixed]\nsteps = 21\n').cells()
    assert {c.key for c in other_protocol}.isdisjoint({c.key for c in small})


def test_filters_do_not_change_a_cells_identity():
    a = grid('[grid]\nsigmas = [1.0]\n[fixed]\nfilters = ["cv"]\n').cells()[0]
    b = grid('[grid]\nsigmas = [1.0]\n[fixed]\nfilters = ["se2se2", "cv"]\n').cells()[0]
    assert (a.key, a.seed) == (b.key, b.seed)  # the same draws, whichever filters run on them


def test_equal_protocols_written_differently_are_one_cell():
    a = grid('[grid]\ndt = [1]\n[fixed]\nnoise_scale = {cv = 30, ctrv = 3, se2r3 = 1}\nv0 = [3, 0]\n').cells()[0]
    b = grid('[grid]\ndt = [1.0]\n[fixed]\nnoise-scale = {ctrv = 3.0, cv = 30.0}\nv0 = [3.0, 0.0]\n').cells()[0]
    assert (a.key, a.seed) == (b.key, b.seed)
    assert value_text("noise_scale", a.options["noise_scale"]) == "ctrv=3.0 cv=30.0"
    assert value_text("noise_scale", {}) == "none"
    assert value_text("v0", [3.0, 0.0]) == "3.0,0.0"


def test_every_study_option_can_be_an_axis_except_filters():
    g = grid('[grid]\ntruth = ["se2se2", "se2r3"]\nmeasure = ["position", "pose"]\nv0 = [[3, 0], [1, 0]]\n'
             'noise_scale = [{}, {cv = 30}]\nsteps = [10, 20]\ninit_std = [[0.5, 0.5, 0.1, 0.5, 0.5, 0.1]]\n')
    assert g.n_cells == 2 * 2 * 2 * 2 * 2
    assert g.cells()[-1].config().noise_scale == {**{f: 1.0 for f in FILTERS}, "cv": 30.0}
    assert "measurement" in g.axes


BAD_GRIDS = {
    "unknown_option": ('[grid]\nsigma = [1.0]\n', "[grid] sigma: not an option of `lgekf study`"),
    "unknown_table": ('[grids]\ndt = [1.0]\n', "unknown table [grids]"),
    "filters_axis": ('[grid]\nfilters = [["cv"], ["ctrv"]]\n', "filters: not an axis"),
    "both_tables": ('[grid]\ndt = [0.1]\n[fixed]\ndt = 0.2\n', "dt is in [grid] and in [fixed]"),
    "scalar_axis": ('[grid]\ndt = 0.1\n', "a [grid] axis needs a list"),
    "empty_axis": ('[grid]\ndt = []\n', "at least one value"),
    "type": ('[grid]\nsteps = [10, "many"]\n', "steps[1]: expected an integer"),
    "duplicate": ('[grid]\ndt = [0.1, 0.1]\n', "the value 0.1 is given twice"),
    "invalid_cell": ('[grid]\ndt = [0.1, -1.0]\n', "cell 1 (dt=-1.0): dt: must be a positive number"),
    "unknown_filter": ('[fixed]\nfilters = ["ukf"]\n', "unknown model 'ukf'"),
    "noise_scale_filter": ('[fixed]\nnoise_scale = {ukf = 2}\n', "unknown filter 'ukf'"),
    "linspace": ('[grid]\nsigmas = "0:3"\n', "expected a list or START:STOP:COUNT"),
    "v0_length": ('[grid]\nv0 = [[1, 2, 3]]\n', "expected a list of 2 numbers"),
    "truth": ('[grid]\ntruth = ["cv"]\n', "unknown truth model 'cv'"),
}


@pytest.mark.parametrize("case", sorted(BAD_GRIDS))
def test_bad_grid_raises_one_clear_error(case):
    text, message = BAD_GRIDS[case]
    with pytest.raises(GridError) as e:
        grid(text).cells()
    assert message in str(e.value) and str(e.value).startswith("g.toml")
    assert "\n" not in str(e.value)


def test_load_grid_errors_name_the_file(tmp_path):
    with pytest.raises(GridError, match="not valid TOML"):
        (tmp_path / "a.toml").write_text("[grid\n")
        load_grid(tmp_path / "a.toml")
    with pytest.raises(GridError, match="cannot read"):
        load_grid(tmp_path / "missing.toml")
    with pytest.raises(GridError, match="is a directory"):
        load_grid(tmp_path)


def run(*args, cwd=None):
    return subprocess.run([*cli_command(), "sweep", *map(str, args)], capture_output=True, text=True, cwd=cwd)


def test_dry_run_counts_cells_without_dask(tmp_path):
    (tmp_path / "g.toml").write_text('[grid]\nsigmas = "0:3:4"\ndt = [0.1, 0.2]\n')
    r = run("g.toml", "-o", "res", "--dry-run", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip() == "g.toml: 8 cells (axes: sigmas (4), dt (2)), 0 in res, 8 to run"
    assert not (tmp_path / "res").exists()


@pytest.mark.parametrize("args, message", [
    (["bad.toml", "-o", "res"], "bad.toml: [grid] sigma: not an option"),
    (["missing.toml", "-o", "res"], "missing.toml: cannot read"),
    (["g.toml"], "the following arguments are required: -o/--out"),
    (["g.toml", "-o", "res", "--workers", "0"], "--workers: must be at least 1"),
    (["g.toml", "-o", "res", "--workers", "2", "--scheduler", "tcp://127.0.0.1:1"], "--workers and --scheduler: give one"),
    (["g.toml", "-o", "res", "--format", "xlsx"], "invalid choice: 'xlsx'"),
    (["g.toml", "-o", "g.toml"], "g.toml: exists and is not a folder"),
])
def test_bad_sweep_arguments_one_line_exit_2(tmp_path, args, message):
    (tmp_path / "g.toml").write_text('[grid]\nsigmas = [0.0, 1.0]\n')
    (tmp_path / "bad.toml").write_text('[grid]\nsigma = [0.0, 1.0]\n')
    r = run(*args, cwd=tmp_path)
    assert r.returncode == 2, r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("lgekf sweep: error: ") and message in lines[0], r.stderr
    assert not (tmp_path / "res").exists()
