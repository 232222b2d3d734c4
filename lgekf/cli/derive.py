"""`lgekf derive`: regenerate generated/ from the model definitions (SymPy, imported only here)."""

from __future__ import annotations

import sys

__all__ = ["cmd_derive"]


def cmd_derive(argv) -> int:
    from ..derive.codegen.build import main as derive_main

    if not {"-h", "--help"} & set(argv):
        # derive is SymPy work (about a minute; the render cache serves unchanged sources in seconds)
        print("lgekf derive: deriving with SymPy, up to about 60 s...", file=sys.stderr, flush=True)
    return derive_main(argv)
