"""All-or-nothing output folders for the commands that write several files."""

from __future__ import annotations

import os
import shutil
import tempfile
from contextlib import contextmanager
from pathlib import Path

__all__ = ["staged_directory", "write_atomic"]


def write_atomic(path: Path, text: str) -> None:
    """Write ``text`` to ``path`` through a temporary file and a rename (no partial files)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.name}.tmp{os.getpid()}")
    try:
        tmp.write_text(text, encoding="utf-8")
        tmp.replace(path)
    finally:
        if tmp.exists():
            tmp.unlink()


@contextmanager
def staged_directory(target):
    """Yield a temporary folder next to ``target``; on success move every file written there into
    ``target`` (created if needed), on any error remove it and leave ``target`` as it was.

    Before anything is moved, every destination is checked (a folder or an unwritable file in the way
    fails the whole set), so a failure cannot leave half of the files behind.
    """
    target = Path(target)
    target.parent.mkdir(parents=True, exist_ok=True)
    stage = Path(tempfile.mkdtemp(prefix=f".{target.name}.", dir=target.parent))
    try:
        yield stage
        files = sorted(stage.iterdir())
        if target.exists() and not target.is_dir():
            raise OSError(f"{target}: exists and is not a folder")
        for f in files:
            dest = target / f.name
            if dest.is_dir() or (dest.exists() and not os.access(dest, os.W_OK)):
                raise OSError(f"{dest}: cannot be replaced")
        target.mkdir(exist_ok=True)
        for f in files:
            f.replace(target / f.name)
    finally:
        shutil.rmtree(stage, ignore_errors=True)
