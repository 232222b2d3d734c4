"""The README stays true: its Python example runs, its first block holds the two CI commands."""

from __future__ import annotations

import re
from pathlib import Path

README = (Path(__file__).resolve().parents[2] / "README.md").read_text(encoding="utf-8")


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


def _quick_start() -> str:
    return re.search(r"\n## Quick start: track a CSV\n(.*?)\n## ", README, re.S).group(1)


def test_quick_start_tracks_the_example_early():
    """The quick start tracks the shipped example within the README's first 60 lines."""
    line = next(i for i, ln in enumerate(README.splitlines(), 1) if ln.startswith("lgekf track examples/data/detections.csv"))
    assert line <= 60
    assert (Path(__file__).resolve().parents[2] / "examples" / "data" / "detections.csv").is_file()


def test_quick_start_python_gives_the_documented_columns(monkeypatch):
    """The quick start's Python line runs (from the project folder) and returns the columns the README lists."""
    quick = _quick_start()
    header = re.search(r"```\n(id,t,[^\n]*)\n```", quick).group(1).split(",")
    block = re.search(r"```python\n(.*?)```", quick, re.S).group(1)
    monkeypatch.chdir(Path(__file__).resolve().parents[2])
    ns: dict = {}
    exec(compile(block, "README.md", "exec"), ns)  # noqa: S102 - our own documentation
    assert list(ns["df"].columns) == header
    assert len(ns["df"]) == 220 and set(ns["df"]["id"]) == {"car", "cyclist", "pedestrian"}


def test_table_of_contents_lists_every_section():
    toc = re.search(r"\n## Contents\n(.*?)\n## ", README, re.S).group(1)
    sections = re.findall(r"^## (.*)$", README, re.M)
    assert [s for s in sections if s != "Contents"] == re.findall(r"\[([^\]]*)\]\(#", toc)
