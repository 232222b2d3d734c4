"""The hand-written C baseline of the SE(2)×SE(2) LG-EKF step (benchmarks/c/se2se2_step.c), through ctypes.

    from c_baseline import load_c_baseline
    c = load_c_baseline()          # raises CompilerMissing (with the reason) where no C compiler works
    c.run_batch(z, dts, x0, p0, q, r, out_x, out_nis)

The source is compiled at benchmark time with the system compiler (``$CC`` or ``cc``):
``cc -O3 -march=native -fopenmp -shared -fPIC`` into a temporary directory; nothing is built at install time.
The kernel is the same filter as ``generated/se2se2.py`` ``predict`` + ``update_position`` (see the header of the C
file for the two places it is written differently but equal to rounding: the covariance form and ω carried
without atan2).  Its batch loop runs OpenMP over trajectories with numba's thread count.
"""

from __future__ import annotations

import ctypes
import os
import shutil
import subprocess
import tempfile
from pathlib import Path

import numpy as np

__all__ = ["SOURCE", "CompilerMissing", "CBaseline", "load_c_baseline", "compiler"]

SOURCE = Path(__file__).resolve().parent / "c" / "se2se2_step.c"
FLAGS = ["-O3", "-march=native", "-fopenmp", "-shared", "-fPIC"]


class CompilerMissing(RuntimeError):
    """No working C compiler (or no OpenMP): the C baseline is skipped, with this reason."""


def compiler() -> str | None:
    """The C compiler to use: ``$CC`` if set, else ``cc``, ``gcc`` or ``clang`` on PATH (None if none)."""
    for c in ([os.environ["CC"]] if os.environ.get("CC") else []) + ["cc", "gcc", "clang"]:
        if shutil.which(c):
            return c
    return None


_D = ctypes.POINTER(ctypes.c_double)


def _ptr(a: np.ndarray | None):
    if a is None:
        return None
    assert a.dtype == np.float64 and a.flags.c_contiguous
    return a.ctypes.data_as(_D)


class CBaseline:
    """The compiled C kernels: ``run_batch`` (OpenMP over trajectories) and ``run_one`` (one trajectory)."""

    def __init__(self, lib: ctypes.CDLL, tmp: tempfile.TemporaryDirectory, cc: str):
        self._lib, self._tmp, self.compiler = lib, tmp, cc
        lib.se2se2_run_one_position.argtypes = [_D, _D, _D, _D, _D, ctypes.c_double, ctypes.c_long, _D, _D, _D]
        lib.se2se2_run_batch_position.argtypes = [_D, _D, _D, _D, _D, ctypes.c_double, ctypes.c_long, ctypes.c_long,
                                                  _D, _D, _D]
        lib.se2se2_run_one_position.restype = lib.se2se2_run_batch_position.restype = None

    def run_batch(self, z, dts, x0, p0, q, r, out_x, out_nis, out_p=None) -> None:
        """Same arrays as ``generated.se2se2.run_batch_position`` (out_p None: covariances not stored)."""
        B, K = z.shape[:2]
        self._lib.se2se2_run_batch_position(_ptr(z), _ptr(dts), _ptr(x0), _ptr(p0), _ptr(q), float(r[0]), B, K,
                                            _ptr(out_x), _ptr(out_p), _ptr(out_nis))

    def run_one(self, z, dts, x0, p0, q, r, out_x, out_nis, out_p=None) -> None:
        """Same arrays as ``generated.se2se2.run_one_position`` (out_p None: covariances not stored)."""
        self._lib.se2se2_run_one_position(_ptr(z), _ptr(dts), _ptr(x0), _ptr(p0), _ptr(q), float(r[0]), z.shape[0],
                                          _ptr(out_x), _ptr(out_p), _ptr(out_nis))


def load_c_baseline(threads: int | None = None) -> CBaseline:
    """Compile benchmarks/c/se2se2_step.c into a temporary directory and load it.

    ``threads``: OpenMP threads (default: numba's thread count).  Raises :class:`CompilerMissing` with the
    reason when no compiler is found or the compilation fails.
    """
    cc = compiler()
    if cc is None:
        raise CompilerMissing("no C compiler on PATH (cc, gcc, clang; or set $CC)")
    if threads is None:
        import numba

        threads = numba.get_num_threads()
    os.environ.setdefault("OMP_NUM_THREADS", str(threads))
    tmp = tempfile.TemporaryDirectory(prefix="lgekf_cbase_")
    so = Path(tmp.name) / "se2se2_step.so"
    r = subprocess.run([cc, *FLAGS, str(SOURCE), "-o", str(so), "-lm"], capture_output=True, text=True)
    if r.returncode != 0:
        tmp.cleanup()
        raise CompilerMissing(f"{cc} failed to build the C baseline: {r.stderr.strip().splitlines()[-1:] or r.returncode}")
    return CBaseline(ctypes.CDLL(str(so)), tmp, cc)
