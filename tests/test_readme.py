"""The README stays true: its Python example runs, its first block holds the two CI commands."""

from __future__ import annotations

import re
from pathlib import Path

README = (Path(__file__).resolve().parents[1] / "README.md").read_text(encoding="utf-8")


def test_python_example_runs():
    block = re.search(r"## Use from Python\n\n```python\n(.*?)```", README, re.S).group(1)
    ns: dict = {}
    exec(compile(block, "README.md", "exec"), ns)  # noqa: S102 - our own documentation
    assert ns["states"].shape == (100, 50, 6)
    assert ns["f"].x.shape == (6,)


def test_first_block_has_setup_and_test_commands():
    first = re.search(r"```\n(.*?)```", README, re.S).group(1).strip().splitlines()
    assert len(first) == 2
    assert "pip install" in first[0] and "lgekf study" in first[0]
    assert "pytest" in first[1]
