"""Machine-code evidence for the SIMD kernels: packed instructions in run_batch_soa_position of every model.

    .venv/bin/python benchmarks/simd_asm.py [model ...]

Compiles each kernel afresh (numba does not show the assembly of cached code: a temporary NUMBA_CACHE_DIR is used,
so this takes ~10-30 s per model) and counts the vector instructions of ``kernel.inspect_asm``: packed double
(``...pd``) on zmm (AVX-512, 8 lanes) and ymm (AVX2, 4 lanes) registers, FMAs among them, and scalar ``...sd``.
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile

CHILD = r"""
import re, sys, numpy as np
from collections import Counter
import lgekf
for name in sys.argv[1:]:
    spec = lgekf.get_model(name)
    n, B, K = spec.n, 70, 3
    k = spec.kernels.run_batch_soa_position
    x0 = np.tile(lgekf.state_from_common(name, [0, 0, 0, 3, 0, 0.1]), (B, 1))
    k(np.zeros((B, K, 2)), np.full((B, K), 0.1), x0, np.tile(np.eye(n)[np.triu_indices(n)], (B, 1)),
      np.asarray(spec.default_accel_std, float), np.array([0.5]), np.empty((B, K, n)), np.empty((B, 0, spec.n_packed)),
      np.empty((B, K)))
    asm = k.inspect_asm(k.signatures[0])
    c = Counter()
    for op, args in re.findall(r"^\s+(v\w+)\s+([^\n]*)", asm, flags=re.M):
        c[(op, "zmm" if "zmm" in args else "ymm" if "ymm" in args else "xmm")] += 1
    pd = lambda w: sum(v for (o, ww), v in c.items() if ww == w and o.endswith("pd"))
    fma = sum(v for (o, w), v in c.items() if w != "xmm" and re.search("fn?m(add|sub)", o) and o.endswith("pd"))
    sd = sum(v for (o, w), v in c.items() if o.endswith("sd"))
    top = ", ".join(f"{o} {v}" for (o, w), v in c.most_common(200) if w == "zmm")
    print(f"{name}: packed-double zmm {pd('zmm')}, ymm {pd('ymm')} (packed FMAs {fma}); scalar sd {sd}")
    print(f"  zmm: {top[:300]}")
"""


def main():
    import lgekf

    models = sys.argv[1:] or list(lgekf.MODELS)
    with tempfile.TemporaryDirectory() as cache:
        env = dict(os.environ, NUMBA_CACHE_DIR=cache)
        subprocess.run([sys.executable, "-c", CHILD, *models], env=env, check=True)


if __name__ == "__main__":
    main()
