"""The `lgekf` script's entry point ``lgekf.cli:run`` (pyproject ``[project.scripts]``, ``python -m lgekf``): main's
exit status passed on, ``OPENBLAS_NUM_THREADS`` set to 1 before NumPy is imported unless the user set it."""

from __future__ import annotations

import os
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

PROBE = """
import sys
import lgekf.cli as cli
def main(argv=None):
    import os
    print(os.environ.get("OPENBLAS_NUM_THREADS"), "numpy" in sys.modules)
    return 3
cli.main = main
cli.run()
"""


@pytest.mark.parametrize("given", [None, "4"])
def test_run_sets_openblas_threads_before_numpy_and_passes_the_status(given):
    env = {k: v for k, v in os.environ.items() if k != "OPENBLAS_NUM_THREADS"}
    if given is not None:
        env["OPENBLAS_NUM_THREADS"] = given
    r = subprocess.run([sys.executable, "-c", PROBE], capture_output=True, text=True, env=env)
    assert r.returncode == 3, r.stderr
    assert r.stdout.split() == [given or "1", "False"]  # the user's value kept; NumPy not imported yet


def test_the_script_and_python_m_lgekf_call_run():
    scripts = tomllib.loads((Path(__file__).resolve().parents[2] / "pyproject.toml").read_text())["project"]["scripts"]
    assert scripts["lgekf"] == "lgekf.cli:run"
    r = subprocess.run([sys.executable, "-m", "lgekf", "nonsense"], capture_output=True, text=True)
    assert r.returncode == 2 and "unknown command 'nonsense'" in r.stderr
