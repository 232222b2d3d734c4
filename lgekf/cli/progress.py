"""What a long command tells the user while it works (on stderr): a one-line notice when numba
compiles, and a tqdm progress bar.

* ``compile_notice(prog, seconds)``: a context manager; the first time numba *compiles* a function inside
  it, one line ``{prog}: compiling kernels, once, about N s (...)`` goes to stderr (N the command's
  estimate, ``lgekf.cli.warmup.compile_estimate``; without one, the general range). Numba broadcasts its
  ``"numba:compile"`` event (``numba.core.event``, a documented API) only on a cache miss — a kernel
  found in the cache (next to the module in ``__pycache__`` or in ``NUMBA_CACHE_DIR``) is loaded
  without it — so the notice appears exactly when the cache is cold and never when it is warm, and
  costs nothing to detect.
* ``progress_bar(total, desc, enabled)``: a ``tqdm`` bar on stderr, or a do-nothing stand-in when
  disabled (``--quiet``, stderr not a terminal, or a run too short to need one).
"""

from __future__ import annotations

import sys
from contextlib import contextmanager

__all__ = ["COMPILE_NOTICE", "compile_notice", "compile_notice_text", "progress_bar", "stderr_is_terminal"]

COMPILE_NOTICE = "compiling kernels, once, about 10-60 s (later runs load them from the cache)..."


def compile_notice_text(seconds: float | None = None) -> str:
    """The notice, with an estimate of the compile time in seconds (rounded to 5 s) when one is given."""
    if seconds is None:
        return COMPILE_NOTICE
    return f"compiling kernels, once, about {max(5, 5 * round(seconds / 5))} s (later runs load them from the cache)..."


def stderr_is_terminal() -> bool:
    """True when stderr is a terminal (where a progress bar makes sense)."""
    try:
        return sys.stderr.isatty()
    except (AttributeError, ValueError):
        return False


def _write_line(text, stream):
    from tqdm import tqdm

    tqdm.write(text, file=stream)  # does not tear an active bar apart


@contextmanager
def compile_notice(prog: str, enabled: bool = True, stream=None, seconds: float | None = None):
    """Print ``{prog}: compiling kernels, once, about N s ...`` once if numba compiles anything inside the block.

    Parameters
    ----------
    prog : str
        The command's name (``lgekf track``), the prefix of the line.
    enabled : bool
        False (``--quiet``) prints nothing.
    stream : file, optional
        Where to write (default: ``sys.stderr`` at the time of the compilation).
    seconds : float, optional
        The estimated compile time (``compile_notice_text``); None gives the general range.
    """
    if not enabled:
        yield
        return
    from numba.core import event

    class Notice(event.Listener):
        said = False

        def on_start(self, ev):
            if not self.said:
                self.said = True
                _write_line(f"{prog}: {compile_notice_text(seconds)}", stream or sys.stderr)

        def on_end(self, ev):
            pass

    with event.install_listener("numba:compile", Notice()):
        yield


class _NoBar:
    """The stand-in for a disabled bar: accepts the calls, shows nothing."""

    def update(self, n=1):
        pass

    def close(self):
        pass

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        return False


def progress_bar(total: int, desc: str, enabled: bool, unit: str = "it", stream=None):
    """A tqdm progress bar on stderr, or a stand-in with the same ``update``/``close`` when disabled.

    Parameters
    ----------
    total : int
        The count at completion.
    desc : str
        The text in front of the bar.
    enabled : bool
        Whether to show it (callers pass ``not quiet and stderr_is_terminal() and <long run>``).
    unit : str
        The unit of ``total`` (``rows``).
    stream : file, optional
        Where to draw it (default ``sys.stderr``).

    Returns
    -------
    tqdm.tqdm or a stand-in
        Use as a context manager; call ``update(n)``.
    """
    if not enabled:
        return _NoBar()
    from tqdm import tqdm

    return tqdm(total=total, desc=desc, unit=unit, unit_scale=True, file=stream or sys.stderr, leave=False, dynamic_ncols=True)
