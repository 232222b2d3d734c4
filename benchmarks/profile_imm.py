"""Where an IMM step's time goes: the IMM loop with parts left out, measured in one run (ns per trajectory-step).

    .venv/bin/python benchmarks/profile_imm.py [--quick] [CASE ...]

Variants of ``imm_run_one``'s step (same kernels and workspace as lgekf.estimators.imm_kernels, one numba thread,
best of 3): ``full`` (mixing, each mode's fused step with its likelihood, mode probabilities, combined output),
``no combined``, ``no mixing``, ``filters only`` (the modes' fused steps ``step_ll_position`` and the mode
probabilities). The differences estimate each part: mixing = full − no mixing, combined output = full − no
combined. (The likelihood's log det S is no separate part any more: the fused step returns 1/det S.) The states
differ slightly between variants (a variant without mixing runs M independent filters), so the differences are
estimates; absolute times are noisy on a shared machine, compare within a run. The variant loop compiles on the
first run (~1 min).
"""

from __future__ import annotations

import argparse
import os

os.environ.setdefault("NUMBA_NUM_THREADS", "1")

import numba as nb  # noqa: E402
import numpy as np  # noqa: E402

from lgekf.estimators import imm_kernels as IK  # noqa: E402
from lgekf.estimators.imm import _common_inputs, _Setup  # noqa: E402
from lgekf.generated import dispatch as D  # noqa: E402

from bench_imm import best_of  # noqa: E402  (this folder: the same best-of timer)

CASES = ["se2r3:calm,se2r3:manoeuvre", "cv,se2r3", "cv,ctrv,se2r3", "se2se2:calm,se2se2:manoeuvre"]
VARIANTS = {"full": (1, 1), "no combined": (1, 0), "no mixing": (0, 1), "filters only": (0, 0)}


@nb.njit(cache=True)
def _run(models, S0, P0, mu0, PI, Q, r, z, dts, same_group, do_mix, do_comb, out_c):
    """imm_run_one's steps (position measurements) over a batch, with parts switched off."""
    M = models.shape[0]
    ws = IK.workspace(M)
    for b in range(z.shape[0]):
        IK._load(ws, models, S0[b], P0[b], mu0, PI, Q, r)
        for k in range(z.shape[1]):
            ws[IK._R_Z, 0] = z[b, k, 0]
            ws[IK._R_Z, 1] = z[b, k, 1]
            if do_mix:
                IK._mix_rows(ws, M, same_group)
            IK._modes_position(ws, M, 2, dts[b, k])  # each mode's fused step and likelihood
            IK._posterior(ws, M)
            if do_comb:
                for j in range(M):
                    ws[IK._R_MU, j] = ws[IK._R_MUV, j]
                IK._combined(ws, M, same_group)
                out_c[b, k, 0] = ws[IK._R_CM, 0]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="a small batch (a smoke test)")
    ap.add_argument("cases", nargs="*", default=CASES)
    a = ap.parse_args(argv)
    B, K = (10, 50) if a.quick else (100, 200)
    rng = np.random.default_rng(0)
    t = 0.1 * np.arange(1, K + 1)
    z = np.stack([3 * t, 0.2 * t**2], axis=-1)[None] + 0.5 * rng.standard_normal((B, K, 2))
    c0 = np.tile([0.0, 0.0, 0.0, 3.0, 0.0, 0.1], (B, 1))
    P0c = np.diag([0.25, 0.25, 0.01, 0.25, 0.25, 0.01])
    dts = np.full((B, K), 0.1)
    out_c = np.empty((B, K, 6))
    print(f"batch {B} × {K} steps, position measurements, 1 numba thread; ns per trajectory-step, best of 3")
    print(f"{'IMM modes':32s} " + " ".join(f"{v:>13s}" for v in VARIANTS) + f" {'mixing':>8s} {'combined':>9s}")
    for case in a.cases:
        s = _Setup(case, None, 0.5, "position", None)
        c, Pc = _common_inputs(c0, P0c)
        S0, Pp0 = s.initial(c, np.ascontiguousarray(np.broadcast_to(Pc, (B, 6, 6))))
        res = {}
        for name, flags in VARIANTS.items():
            args = (s.models, S0, Pp0, s.mu0, s.PI, s.Q, s.r)
            _run(*args, z[:1, :2], dts[:1, :2], s.same_group, *flags, out_c)
            res[name] = best_of(lambda: _run(*args, z, dts, s.same_group, *flags, out_c), repeat=3) * 1e9 / (B * K)
        print(f"{case:32s} " + " ".join(f"{res[v]:13.0f}" for v in VARIANTS)
              + f" {res['full'] - res['no mixing']:8.0f} {res['full'] - res['no combined']:9.0f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
