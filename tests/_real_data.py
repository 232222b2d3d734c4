"""Where the tests find the real datasets (never shipped): $LGEKF_DATA, else ../shared/data beside the checkout; a test
that needs one skips with the reason when it is absent."""

import os
from pathlib import Path

import pytest

DATA = Path(os.environ.get("LGEKF_DATA") or Path(__file__).resolve().parents[1].parent / "shared" / "data")


def needs(rel):
    """The path of ``rel`` under ``DATA``; skips the test when it is not there."""
    p = DATA / rel
    if not p.exists():
        pytest.skip(f"real dataset {p} not available (set LGEKF_DATA to the data folder; the data are not shipped)")
    return p
