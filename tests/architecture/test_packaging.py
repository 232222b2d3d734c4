"""Project hygiene that a user of the installed package relies on: the licence and PEP 561 marker.

(Building a wheel needs the network for the build backend, so it is not done here; a wheel built with
`pip wheel . --no-deps` contains lgekf/py.typed and dist-info/licenses/LICENSE, checked by hand.)
"""

import tomllib
from importlib import resources
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
PYPROJECT = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))


def test_py_typed_is_package_data():
    assert resources.files("lgekf").joinpath("py.typed").is_file()
    assert "py.typed" in PYPROJECT["tool"]["setuptools"]["package-data"]["lgekf"]


def test_license_file_matches_pyproject():
    assert PYPROJECT["project"]["license"] == {"text": "MIT"}
    text = (ROOT / "LICENSE").read_text(encoding="utf-8")
    assert text.startswith("MIT License")
    assert "Copyright (c)" in text and "lgekf contributors" in text
    assert "THE SOFTWARE IS PROVIDED \"AS IS\"" in text


def test_changelog_has_unreleased_and_current_version():
    text = (ROOT / "CHANGELOG.md").read_text(encoding="utf-8")
    assert "## [Unreleased]" in text
    assert f"## [{PYPROJECT['project']['version']}]" in text
