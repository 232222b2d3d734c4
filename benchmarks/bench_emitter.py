"""Speed before and after the generic emitter, in one run: the hand-wired kernels of commit 93684c8 (read
from git into a temporary package) against today's generated kernels, interleaved, best of several repeats.

    .venv/bin/python benchmarks/bench_emitter.py [--repeat 7] [--batch 3000] [--steps 200]

For each of the paper's four models: ns per predict+update step over a batch (numba prange over the
trajectories, all cores) and over one long trajectory (one core), old and new, and the ratio new/old.
Today's se2r2 and the pose update have no "before"; they are listed for scale. Needs git and the repository's
history (skipped with a reason otherwise). Run it on a quiet machine (no tests, no other benchmarks).
"""

from __future__ import annotations

import argparse
import importlib
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
BEFORE = "93684c8"  # the last commit with the hand-wired emitter (derive/steps.py)
FILES = ("__init__.py", "special.py", "se2.py", "se2se2.py", "se2r3.py", "ctrv.py", "cv.py")


def old_package(tmp: Path):
    pkg = tmp / "gen_before"
    pkg.mkdir()
    for f in FILES:
        src = subprocess.run(["git", "-C", str(ROOT), "show", f"{BEFORE}:generated/{f}"], capture_output=True, text=True, check=True).stdout
        (pkg / f).write_text(src)
    sys.path.insert(0, str(tmp))
    return lambda name: importlib.import_module(f"gen_before.{name}")


def problem(model_spec, B, K, m=2, seed=0):
    from lgekf import state_from_common

    rng = np.random.default_rng(seed)
    t = np.arange(1, K + 1) * 0.1
    # a gently weaving path at 3 m/s (heading within ±0.3 rad), pose heading along it
    y = 3 * np.sin(0.1 * t)
    truth = np.stack([3 * t, y, np.arctan2(0.3 * np.cos(0.1 * t), 3)], axis=-1)[:, :m]
    z = np.ascontiguousarray(truth[None] + 0.3 * rng.standard_normal((B, K, m)))
    x0 = np.tile(state_from_common(model_spec.name, [0, 0, 0, 3, 0, 0.1]), (B, 1))
    n = model_spec.n
    p0 = np.tile(np.eye(n)[np.triu_indices(n)] * 0.1, (B, 1))
    q = np.asarray(model_spec.default_accel_std, dtype=float)
    return z, np.full((B, K), 0.1), np.ascontiguousarray(x0), np.ascontiguousarray(p0), q


def run_ns(fn, args, B, K, repeat):
    out_x = np.empty((B, K, args[2].shape[1]))
    out_p = np.empty((B, 0, args[3].shape[1]))
    out_nis = np.empty((B, K))
    fn(*args, out_x, out_p, out_nis)  # compile / warm
    best = float("inf")
    for _ in range(repeat):
        t = time.perf_counter()
        fn(*args, out_x, out_p, out_nis)
        best = min(best, time.perf_counter() - t)
    return best / (B * K) * 1e9, out_x


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=7)
    ap.add_argument("--batch", type=int, default=3000)
    ap.add_argument("--steps", type=int, default=200)
    a = ap.parse_args(argv)
    from lgekf.core.registry import MODELS

    try:
        tmp = Path(tempfile.mkdtemp(prefix="lgekf_before_"))
        old = old_package(tmp)
    except (subprocess.CalledProcessError, FileNotFoundError) as e:
        print(f"skipped: the kernels of {BEFORE} are not available from git ({e})")
        return 0
    B, K = a.batch, a.steps
    print(f"{time.strftime('%Y-%m-%d %H:%M')} load {os.getloadavg()[0]:.2f}; batch {B} x {K}, one trajectory {B * K // 10} steps; "
          f"best of {a.repeat}; ns per predict+update step")
    print(f"{'model':8} {'batch old':>10} {'batch new':>10} {'new/old':>8} {'one old':>9} {'one new':>9} {'new/old':>8}")
    for name in ("se2se2", "se2r3", "ctrv", "cv"):
        spec = MODELS[name]
        new = spec.kernels
        o = old(name)
        r = np.array([0.3])
        rows, worst = [], 0.0
        for BB, KK in ((B, K), (1, B * K // 10)):  # the batch (all cores), then one long trajectory (one core)
            zz, dd, xx, pp, q = problem(spec, BB, KK)
            # interleave old and new, best of the repeats each
            t_old, x_old = run_ns(o.run_batch, (zz, dd, xx, pp, q, r[0]), BB, KK, a.repeat)
            t_new, x_new = run_ns(new.run_batch_position, (zz, dd, xx, pp, q, r), BB, KK, a.repeat)
            d = np.abs(x_old - x_new)
            for ia in spec.angles:  # the same angle printed as +π or −π
                d[..., ia] = np.abs((x_old[..., ia] - x_new[..., ia] + np.pi) % (2 * np.pi) - np.pi)
            worst = max(worst, float(np.max(d / (1 + np.abs(x_old)))))
            rows.append((t_old, t_new))
        (bo, bn), (so, sn) = rows
        print(f"{name:8} {bo:10.1f} {bn:10.1f} {bn / bo:8.2f} {so:9.1f} {sn:9.1f} {sn / so:8.2f}   max |old - new| / (1 + |old|) = {worst:.1e}")
    for name, meas in (("se2r2", "position"), ("se2se2", "pose"), ("se2r2", "pose"), ("ctrv", "pose")):
        spec = MODELS[name]
        m = 3 if meas == "pose" else 2
        z, dts, x0, p0, q = problem(spec, B, K, m=m)
        r = np.array([0.3, 0.3, 0.05]) if meas == "pose" else np.array([0.3])
        t_new, _ = run_ns(getattr(spec.kernels, f"run_batch_{meas}"), (z, dts, x0, p0, q, r), B, K, a.repeat)
        print(f"{name:8} {meas:8} batch {t_new:8.1f} ns (new only)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
