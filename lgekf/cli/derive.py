"""`lgekf derive`: regenerate generated/ from the model definitions (SymPy, imported only here)."""

from __future__ import annotations

import sys

__all__ = ["cmd_derive"]


def cmd_derive(argv) -> int:
    from ..derive.codegen.build import main as derive_main

    if not {"-h", "--help"} & set(argv):
        # derive is SymPy work (not numba, not cached): it takes this long on every run
        print("lgekf derive: deriving with SymPy, about 30-60 s...", file=sys.stderr, flush=True)
    return derive_main(argv)
