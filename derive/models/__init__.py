"""Motion-model definitions, one file each (see ``base.MotionModel``); ``load_models`` finds them.

Adding a model = adding ``<name>.py`` here (with ``MODEL = <Subclass>()``) and running ``lgekf derive``.
"""

from __future__ import annotations

import importlib
import importlib.util
import sys
from pathlib import Path

__all__ = ["load_models"]


def _load_definitions(folder, package: str, attr: str) -> dict:
    """{stem: module.<attr>} for every ``*.py`` in ``folder`` except ``base.py`` and private files.

    Files of the package itself are imported as its submodules; files of another folder (a user's or a
    test's definitions) are imported under a private name, with the package's modules available to them.
    """
    own = Path(importlib.import_module(package).__file__).parent
    folder = own if folder is None else Path(folder)
    out = {}
    for path in sorted(folder.glob("*.py")):
        stem = path.stem
        if stem.startswith("_") or stem == "base":
            continue
        if folder.resolve() == own.resolve():
            mod = importlib.import_module(f"{package}.{stem}")
        else:
            name = f"{package}._external_{abs(hash(str(path.resolve())))}_{stem}"
            spec = importlib.util.spec_from_file_location(name, path)
            mod = importlib.util.module_from_spec(spec)
            sys.modules[name] = mod
            spec.loader.exec_module(mod)
        if not hasattr(mod, attr):
            raise ValueError(f"{path}: a definition file must define {attr}")
        obj = getattr(mod, attr)
        obj.name = stem
        out[stem] = obj
    return out


def load_models(folder=None) -> dict:
    """{name: MotionModel} of every definition file in ``folder`` (default: this package), sorted."""
    return _load_definitions(folder, __name__, "MODEL")
