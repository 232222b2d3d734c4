"""`lgekf sweep` on Dask: the results table is the same, byte for byte, whatever the number of workers, the
scheduler, the batches and interruptions; it resumes; each cell's numbers are its own `run_study`; a figure
per swept axis; one clear line for a folder of another grid; and without Dask, how to install it."""

from __future__ import annotations

import csv
import json
import os
import subprocess
import sys
import textwrap

import numpy as np
import pytest
from _cli import cli_command

from lgekf.apps.sweep import compute_cell, run_sweep
from lgekf.apps.sweep_table import read_table, table_columns
from lgekf.experiments.grid import load_grid
from lgekf.experiments.study import run_study

pytestmark = pytest.mark.slow  # Dask clusters start in seconds each; the quick loop skips them, CI runs them

pytest.importorskip("distributed")

GRID = """\
[grid]
sigmas = [0.0, 1.5, 3.0]
dt = [0.1, 0.2]

[fixed]
trajectories = 6
steps = 12
filters = ["se2se2", "ctrv", "cv"]
noise_scale = {cv = 10}
"""


def run(*args, cwd):
    return subprocess.run([*cli_command(), "sweep", *map(str, args)], capture_output=True, text=True, cwd=cwd)


@pytest.fixture
def folder(tmp_path):
    (tmp_path / "grid.toml").write_text(GRID)
    return tmp_path


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def test_same_table_with_1_and_2_local_workers_and_in_process(folder):
    for n in (1, 2):
        r = run("grid.toml", "-o", f"w{n}", "--workers", n, cwd=folder)
        assert r.returncode == 0, r.stderr
        assert f"6 cells: 6 computed, 0 already in w{n}" in r.stdout
        assert f"local cluster, {n} worker" in r.stderr
    run_sweep(load_grid(folder / "grid.toml"), folder / "here", client=None, figures=False)
    one = (folder / "w1" / "cells.csv").read_bytes()
    assert one == (folder / "w2" / "cells.csv").read_bytes() == (folder / "here" / "cells.csv").read_bytes()
    table = rows(folder / "w1" / "cells.csv")
    assert len(table) == 6 * 4  # cells x (3 filters + measurements)
    assert list(table[0]) == ["cell", "seed", "dt", "sigma_w", "filter", "mean_rmse", "std_rmse", "n", "wrapped", "aliased"]
    assert [r["filter"] for r in table[:4]] == ["se2se2", "ctrv", "cv", "measurements"]
    assert [(r["sigma_w"], r["dt"]) for r in table[::4]] == [(s, d) for s in ("0.0", "1.5", "3.0") for d in ("0.1", "0.2")]
    meta = json.loads((folder / "w2" / "meta.json").read_text())
    assert meta["runs"][0]["workers"] == 2 and meta["runs"][0]["computed"] == 6 and meta["grid"]["fixed"]["steps"] == 12
    assert sorted(p.name for p in (folder / "w2").glob("*.png")) == ["sweep_dt.png", "sweep_sigma_w.png"]
    assert (folder / "w2" / "sweep_dt.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_same_table_on_an_existing_cluster(folder, dask_scheduler):
    run_sweep(load_grid(folder / "grid.toml"), folder / "here", client=None, figures=False)
    r = run("grid.toml", "-o", "remote", "--scheduler", dask_scheduler, "--no-figures", cwd=folder)
    assert r.returncode == 0, r.stderr
    assert f"scheduler {dask_scheduler}" in r.stderr
    assert (folder / "remote" / "cells.csv").read_bytes() == (folder / "here" / "cells.csv").read_bytes()
    assert not list((folder / "remote").glob("*.png"))


def test_each_cell_is_its_own_run_study(folder):
    g = load_grid(folder / "grid.toml")
    run_sweep(g, folder / "here", client=None, figures=False)
    table = read_table(folder / "here" / "cells.csv", table_columns(g.axis_columns()), "csv")
    cell = g.cells()[3]
    res = run_study(cell.config())
    mine = [r for r in table if r[0] == cell.key]
    assert [r[4] for r in mine] == ["se2se2", "ctrv", "cv", "measurements"]
    for r in mine:  # bit for bit: the table's text is the float's repr
        assert r[1] == cell.seed and r[2] == cell.axes["dt"] and r[3] == cell.axes["sigmas"][0]
        assert r[5] == float(res.rmse[r[4]][0].mean()) and r[6] == float(res.rmse[r[4]][0].std(ddof=1)) and r[7] == 6


def test_resume_computes_only_the_new_cells_and_gives_the_fresh_table(folder):
    (folder / "part.toml").write_text(GRID.replace("sigmas = [0.0, 1.5, 3.0]", "sigmas = [3.0, 0.0]"))
    run_sweep(load_grid(folder / "grid.toml"), folder / "fresh", client=None, figures=False)
    rep = run_sweep(load_grid(folder / "part.toml"), folder / "grown", client=None, figures=False)
    assert (rep.computed, rep.skipped) == (4, 0)
    r = run("grid.toml", "-o", "grown", "--workers", 2, cwd=folder)
    assert r.returncode == 0, r.stderr
    assert "6 cells: 2 computed, 4 already in grown" in r.stdout
    assert (folder / "grown" / "cells.csv").read_bytes() == (folder / "fresh" / "cells.csv").read_bytes()
    r = run("grid.toml", "-o", "grown", "--workers", 1, "--dry-run", cwd=folder)
    assert r.stdout.strip().endswith("6 cells (axes: sigmas (3), dt (2)), 6 in grown, 0 to run")
    meta = json.loads((folder / "grown" / "meta.json").read_text())
    assert [(m["computed"], m["skipped"]) for m in meta["runs"]] == [(4, 0), (2, 4)]


def test_an_interrupted_sweep_keeps_whole_cells_and_resumes(folder):
    g = load_grid(folder / "grid.toml")
    run_sweep(g, folder / "fresh", client=None, figures=False)
    done = []

    def crash(n):
        done.append(n)
        if len(done) == 4:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        run_sweep(load_grid(folder / "grid.toml"), folder / "cut", client=None, progress=crash, flush_seconds=0.0, figures=False)
    kept = rows(folder / "cut" / "cells.csv")
    assert len(kept) == 4 * 4 and len({r["cell"] for r in kept}) == 4  # the finished cells, each complete
    rep = run_sweep(load_grid(folder / "grid.toml"), folder / "cut", client=None, figures=False)
    assert (rep.computed, rep.skipped) == (2, 4)
    assert (folder / "cut" / "cells.csv").read_bytes() == (folder / "fresh" / "cells.csv").read_bytes()


def test_parquet_table_holds_the_same_values(folder, dask_scheduler):
    g = load_grid(folder / "grid.toml")
    run_sweep(g, folder / "here", client=None, figures=False)
    r = run("grid.toml", "-o", "pq", "--format", "parquet", "--scheduler", dask_scheduler, "--quiet", cwd=folder)
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip() == "pq"
    cols = table_columns(g.axis_columns())
    assert read_table(folder / "pq" / "cells.parquet", cols, "parquet") == read_table(folder / "here" / "cells.csv", cols, "csv")
    again = run("grid.toml", "-o", "pq", "--format", "parquet", "--scheduler", dask_scheduler, cwd=folder)
    assert again.returncode == 0 and "6 cells: 0 computed, 6 already in pq" in again.stdout


def test_a_folder_of_another_grid_or_command_is_refused_unchanged(folder):
    run_sweep(load_grid(folder / "grid.toml"), folder / "res", client=None, figures=False)
    before = (folder / "res" / "cells.csv").read_bytes()
    (folder / "other.toml").write_text(GRID.replace("steps = 12", "steps = 13"))
    (folder / "axes.toml").write_text(GRID.replace("dt = [0.1, 0.2]", "w0 = [0.0, 0.5]"))
    (folder / "study").mkdir()
    (folder / "study" / "meta.json").write_text('{"protocol": {}}\n')
    cases = [
        (["other.toml", "-o", "res"], "holds a sweep with other [fixed] options"),
        (["axes.toml", "-o", "res"], "holds a sweep over other axes"),
        (["grid.toml", "-o", "res", "--format", "parquet"], "holds a sweep in csv format"),
        (["grid.toml", "-o", "study"], "holds the output of another command"),
    ]
    for args, message in cases:
        r = run(*args, "--workers", 1, cwd=folder)
        assert r.returncode == 2, r.stderr
        lines = r.stderr.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith("lgekf sweep: error: ") and message in lines[0], r.stderr
    assert (folder / "res" / "cells.csv").read_bytes() == before


def test_compute_cell_rows_follow_the_study():
    from lgekf.experiments.grid import parse_grid

    cell = parse_grid({"fixed": {"sigmas": [0.5, 2.0], "trajectories": 3, "steps": 5, "filters": ["cv"]}}).cells()[0]
    rows, seconds = compute_cell(cell.options, cell.seed)
    assert [(r[0], r[1]) for r in rows] == [(0.5, "cv"), (0.5, "measurements"), (2.0, "cv"), (2.0, "measurements")]
    assert all(r[4] == 3 for r in rows) and seconds > 0
    assert np.isfinite([r[2] for r in rows]).all()


NO_DASK = textwrap.dedent("""\
    import sys
    for name in ("dask", "distributed"):
        sys.modules[name] = None  # import dask -> ImportError, as when it is not installed
    from lgekf.cli import main
    sys.exit(main(sys.argv[1:]))
""")


@pytest.mark.parametrize("args", [
    ["sweep", "grid.toml", "-o", "res"],
    ["track", "in.csv", "-o", "out.csv", "--workers", "2"],
    ["evaluate", "in.csv", "--out", "ev", "--scheduler", "tcp://127.0.0.1:8786"],
])
def test_without_dask_the_commands_say_how_to_install_it(folder, args):
    (folder / "in.csv").write_text("t,x,y\n0,0,0\n0.1,0.3,0\n0.2,0.6,0\n0.3,0.9,0\n0.4,1.2,0\n")
    r = subprocess.run([sys.executable, "-c", NO_DASK, *args], capture_output=True, text=True, cwd=folder)
    assert r.returncode == 2, r.stderr
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and 'needs Dask' in lines[0] and 'pip install "lgekf[dask]"' in lines[0], r.stderr
    assert sorted(p.name for p in folder.iterdir()) == ["grid.toml", "in.csv"]


def test_lgekf_never_imports_dask_unless_asked(folder):
    (folder / "in.csv").write_text("t,x,y\n0,0,0\n0.1,0.3,0\n0.2,0.6,0\n")
    code = textwrap.dedent("""\
        import sys
        import lgekf.cli.sweep, lgekf.cli.track, lgekf.cli.evaluate, lgekf.apps.track_dask, lgekf.apps.evaluate_dask
        from lgekf.cli import main
        assert main(["track", "in.csv", "-o", "out.csv", "--quiet"]) == 0
        assert main(["sweep", "grid.toml", "-o", "res", "--dry-run"]) == 0
        loaded = sorted(m for m in sys.modules if m.split(".")[0] in ("dask", "distributed", "pandas", "pyarrow"))
        print(loaded)
    """)
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=folder)
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip().splitlines()[-1] == "[]"


def test_the_imm_options_are_recorded_and_compared_on_resume(tmp_path):
    """A sweep with the imm filter records its chain (learned on 100 training trajectories: the study's default)
    in meta.json; a folder whose meta.json records another chain, or none (a sweep from before the chain was
    learned), is refused rather than mixing fixed- and learned-chain rows under the same cell keys."""
    import json

    from lgekf.apps.sweep import check_folder
    from lgekf.experiments.grid import parse_grid
    from lgekf.apps.sweep_table import TableError

    fixed = {"sigmas": [0.5], "trajectories": 3, "steps": 5}
    g = parse_grid({"fixed": {**fixed, "filters": ["cv", "imm"]}})
    meta = check_folder(g, tmp_path / "res", "csv")
    assert meta["imm"] == {"modes": "cv,se2r3", "switch": None, "train_trajectories": 100}
    assert "imm" not in check_folder(parse_grid({"fixed": {**fixed, "filters": ["cv"]}}), tmp_path / "x", "csv")
    (tmp_path / "res").mkdir()
    for recorded in ({"modes": "cv,se2r3", "switch": 0.002}, None):
        old = {k: v for k, v in meta.items() if k != "imm"}
        if recorded is not None:
            old["imm"] = recorded
        (tmp_path / "res" / "meta.json").write_text(json.dumps(old))
        with pytest.raises(TableError, match="imm filter ran with other options"):
            check_folder(g, tmp_path / "res", "csv")
    (tmp_path / "res" / "meta.json").write_text(json.dumps(meta))
    assert check_folder(g, tmp_path / "res", "csv")["imm"] == meta["imm"]


SIMD_GRID = """\
[grid]
sigmas = [1.0]

[fixed]
trajectories = 1000
steps = 40
filters = ["se2r2"]
"""


def test_a_cold_and_a_warm_run_write_the_same_bytes(tmp_path):
    """The example grid's cold run differed from its warm run in 71 of 168 rows (LG models only; up to 1.8 % where the
    filters lose the track): numba's freshly compiled SIMD kernel (1000 trajectories x more than 2^15 steps) does not
    give the numbers of its cached copy.
    This one-cell grid took that kernel (SE(2)×SE(2)'s) and differed too (mean_rmse ...632167 cold, ...6321663 warm)
    before the warm-up: now the kernels are compiled in child processes and every cell loads them from the cache. The
    grid runs SE(2)×R², an LG model with a smaller module (a shorter cold compile)."""
    (tmp_path / "grid.toml").write_text(SIMD_GRID)
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / "numba"))  # a cold cache of its own
    err = {}
    for name in ("cold", "warm"):
        r = subprocess.run([*cli_command(), "sweep", "grid.toml", "-o", name, "--workers", "1", "--no-figures"],
                           capture_output=True, text=True, cwd=tmp_path, env=env)
        assert r.returncode == 0, r.stderr
        err[name] = r.stderr
        meta = json.loads((tmp_path / name / "meta.json").read_text())
        assert meta["runs"][0]["warmup_compiled"] is (name == "cold")
    assert "lgekf sweep: compiling kernels, once, about" in err["cold"]  # the first run says why it is slow
    assert "compiling" not in err["warm"]
    assert (tmp_path / "cold" / "cells.csv").read_bytes() == (tmp_path / "warm" / "cells.csv").read_bytes()
    assert len(rows(tmp_path / "warm" / "cells.csv")) == 2  # se2r2 and the measurements


def _on_a_terminal(args, cwd, env):
    """(return code, stdout, stderr) of ``lgekf sweep ARGS`` whose stderr is a pseudo-terminal (where the bar shows)."""
    import fcntl
    import pty
    import struct
    import termios

    master, slave = pty.openpty()
    fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 24, 120, 0, 0))  # a 0-column terminal gets no bar
    p = subprocess.Popen([*cli_command(), "sweep", *args], stdout=subprocess.PIPE, stderr=slave, cwd=cwd, env=env)
    os.close(slave)
    err = b""
    while True:
        try:
            chunk = os.read(master, 4096)
        except OSError:  # EIO: the child closed the terminal
            break
        if not chunk:
            break
        err += chunk
    out = p.stdout.read()
    os.close(master)
    return p.wait(), out.decode(), err.decode(errors="replace")


def test_notice_and_progress_bar_on_a_terminal_and_nothing_with_quiet(tmp_path):
    # the grid's six cells with CV alone: the cold cache compiles the study's truth and one filter (not three)
    (tmp_path / "grid.toml").write_text(GRID.replace('filters = ["se2se2", "ctrv", "cv"]', 'filters = ["cv"]'))
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / "numba"))  # cold: the notice
    rc, out, err = _on_a_terminal(["grid.toml", "-o", "res", "--workers", "1"], tmp_path, env)
    assert rc == 0, err
    assert "lgekf sweep: compiling kernels, once, about" in err
    assert "lgekf sweep:   0%|" in err and "/6.00 [" in err and "cells/s]" in err  # the tqdm bar over the 6 cells
    assert "6 cells: 6 computed" in out
    r = subprocess.run([*cli_command(), "sweep", "grid.toml", "-o", "res2", "--workers", "1", "--quiet"],
                       capture_output=True, text=True, cwd=tmp_path, env=env)
    assert r.returncode == 0, r.stderr
    assert r.stderr.strip() == "" and r.stdout.strip() == "res2"
    assert (tmp_path / "res" / "cells.csv").read_bytes() == (tmp_path / "res2" / "cells.csv").read_bytes()
