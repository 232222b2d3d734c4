"""Where an IMM step's time goes: the IMM loop with parts left out, measured in one run (ns per trajectory-step).

    .venv/bin/python benchmarks/profile_imm.py [--quick] [CASE ...]

Variants of ``imm_run_one``'s step (same kernels as lgekf.estimators.imm_kernels, one numba thread, best of 3):
``full`` (mixing, mode-matched predict/update, likelihood, combined output), ``no combined``, ``no mixing``,
``no likelihood`` (log det S skipped), ``filters only`` (the modes' predict + update through the dispatch). The
differences estimate each part: mixing = full − no mixing, combined output = full − no combined, likelihood =
full − no likelihood. The states differ slightly between variants (a variant without mixing runs M independent
filters), so the differences are estimates; absolute times are noisy on a shared machine, compare within a run.
The variant loop compiles on the first run (~1 min).
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
VARIANTS = {"full": (1, 1, 1), "no combined": (1, 1, 0), "no mixing": (0, 1, 1), "no likelihood": (1, 0, 1),
            "filters only": (0, 0, 0)}


@nb.njit(cache=True)
def _run(models, S0, P0, mu0, PI, Q, r, z, dts, same_group, do_mix, do_ll, do_comb, out_c):
    """imm_run_one's steps (position measurements) over a batch, with parts switched off."""
    M = models.shape[0]
    ws = IK.workspace(M)
    Pc = np.empty((6, 6))
    for b in range(z.shape[0]):
        S = S0[b].copy()
        Pp = P0[b].copy()
        mu = mu0.copy()
        for k in range(z.shape[1]):
            if do_mix:
                IK._mix(models, S, Pp, mu, PI, same_group, ws[16], ws)
            for j in range(M):
                D.predict(models[j], S[j], Pp[j], dts[b, k], Q[j])
            for j in range(M):
                sj, pj = S[j], Pp[j]
                ld = D.innovation_logdet_position(models[j], sj, pj, r) if do_ll else 0.0
                ws[17][j] = -0.5 * (D.update_position(models[j], sj, pj, z[b, k], r) + ld)
            if do_comb:
                IK.combined_common(models, S, Pp, mu, same_group, out_c[b, k], Pc, ws)


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
    print(f"{'IMM modes':32s} " + " ".join(f"{v:>13s}" for v in VARIANTS) + f" {'mixing':>8s} {'combined':>9s} {'likelihood':>10s}")
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
              + f" {res['full'] - res['no mixing']:8.0f} {res['full'] - res['no combined']:9.0f}"
              f" {res['full'] - res['no likelihood']:10.0f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
