"""The numba templates of the kernel families, kept as files in ``derive/codegen/templates/`` (not Python strings).

A template is numba source with ``str.format`` placeholders (``{meas}``, ``{n}``, ...; a literal brace is doubled),
formatted by its family (``derive/codegen/families/``); a few hold a ``$name`` line that the family replaces with
another template's text before formatting (the SIMD block loop shared by two drivers). Files are read as UTF-8,
byte for byte: the generated modules depend on their exact text.
"""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path

__all__ = ["TEMPLATES", "load"]

TEMPLATES = Path(__file__).resolve().parent / "templates"


@lru_cache(maxsize=None)
def load(name: str) -> str:
    """The text of ``templates/<name>`` (e.g. ``load("monitor_recover.py.tmpl")``)."""
    with open(TEMPLATES / name, encoding="utf-8", newline="") as fh:
        return fh.read()
