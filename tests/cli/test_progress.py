"""lgekf.cli.progress: the compile notice (cold numba cache only) and the tqdm bars (terminal only, not --quiet)."""

import io
import os
import shutil
import subprocess
import sys

import numba as nb
import numpy as np
import pytest
from _cli import cli_command

from lgekf.cli.progress import COMPILE_NOTICE, compile_notice, progress_bar


class _Terminal(io.StringIO):
    def isatty(self):
        return True


def test_notice_once_when_numba_compiles_and_never_when_compiled():
    @nb.njit  # a new function: compiled on its first call inside the block
    def f(x):
        return x + 1

    @nb.njit
    def g(x):
        return f(x) * 2

    buf = io.StringIO()
    with compile_notice("lgekf test", stream=buf):
        assert g(1) == 4  # compiles g and f: still one line
    assert buf.getvalue() == f"lgekf test: {COMPILE_NOTICE}\n"
    buf = io.StringIO()
    with compile_notice("lgekf test", stream=buf):
        assert g(2) == 6  # already compiled
    assert buf.getvalue() == ""


def test_notice_disabled():
    @nb.njit
    def h(x):
        return x - 1

    buf = io.StringIO()
    with compile_notice("lgekf test", enabled=False, stream=buf):
        assert h(1) == 0
    assert buf.getvalue() == ""


@pytest.mark.slow
def test_cold_cache_says_so_warm_cache_does_not(tmp_path):
    """A fresh numba cache: the first run compiles and says so, the second loads and does not; --quiet says nothing even
    when it compiles."""
    inp = tmp_path / "in.csv"
    inp.write_text("t,x,y\n0,0,0\n0.1,0.3,0\n0.25,0.75,0.01\n")

    def track(cache, *extra):
        env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / cache))
        # the noise given and no monitor: the notice is the same, the cold compile half as long (14 s against 26 s)
        r = subprocess.run([*cli_command(), "track", str(inp), "-o", str(tmp_path / "o.csv"), "--model", "cv", "--meas-std", "0.1",
                            "--accel-std", "1", "--no-monitor", *extra],
                           capture_output=True, text=True, env=env)
        assert r.returncode == 0, r.stderr
        return r.stderr

    assert "lgekf track: compiling kernels, once, about" in track("cache1")
    assert "compiling" not in track("cache1")  # warm: loaded from the cache
    # cold but quiet: a copy of the warm cache without two of the CV filter's kernels, which the run compiles again (a cold
    # cache of its own cost a third compile of everything; any compilation is what the notice reacts to)
    shutil.copytree(tmp_path / "cache1", tmp_path / "cache2")
    dropped = sorted((tmp_path / "cache2").rglob("cv.*.nbi"))[:2]
    assert dropped, "the CV filter's kernels are not in the cache"
    for p in dropped:
        p.unlink()
    assert track("cache2", "--quiet") == ""
    assert all(p.exists() for p in dropped)  # compiled anew: numba wrote their index files again


def test_progress_bar_on_and_off():
    term = _Terminal()
    with progress_bar(10, "work", True, unit="rows", stream=term) as bar:
        bar.update(10)
    assert "work" in term.getvalue() and "rows" in term.getvalue()
    term = _Terminal()
    with progress_bar(10, "work", False, stream=term) as bar:
        bar.update(10)
    assert term.getvalue() == ""


@pytest.mark.parametrize("terminal, quiet, expect_bar", [(True, False, True), (True, True, False), (False, False, False)])
def test_track_bar_only_on_a_terminal_and_not_quiet(tmp_path, monkeypatch, terminal, quiet, expect_bar):
    import lgekf.cli.track as track

    monkeypatch.setattr(track, "BAR_MIN_ROWS", 8)  # "a large file": more rows than that
    t = 0.1 * np.arange(40)
    inp = tmp_path / "in.csv"
    inp.write_text("t,x,y\n" + "".join(f"{a!r},{a!r},0\n" for a in t.tolist()))
    err = _Terminal() if terminal else io.StringIO()
    monkeypatch.setattr(sys, "stderr", err)
    assert track.cmd_track([str(inp), "-o", str(tmp_path / "o.csv"), "--model", "cv", *(["--quiet"] if quiet else [])]) == 0
    assert ("lgekf track:   0%|" in err.getvalue()) == expect_bar, err.getvalue()  # tqdm draws "desc:   0%|bar|" at once
