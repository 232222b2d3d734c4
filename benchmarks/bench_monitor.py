"""Time the divergence monitor and the noise search of ``lgekf track`` (issue 10), against a baseline tree.

    python benchmarks/bench_monitor.py [--input FILE] [--objects 10000] [--steps 100] [--repeat 3]
                                       [--baseline DIR] [--models se2se2,se2r3,se2r2,ctrv,cv]

On the file of ``benchmarks/bench_track.py`` (generated unless ``--input`` names one), in one process:
  filter    ``track_arrays`` of every object, per model (no monitor)
  monitored ``track_monitored`` (the filter, the divergence monitor and its re-initialisations), per model;
            "monitor" = monitored − filter
  plan      ``lgekf.apps.defaults.plan_noise`` (measurement std and process-noise search, threads as in
            ``lgekf track``) for the first model alone and for all the models
each the best of ``--repeat`` runs after one warm-up run. ``--baseline DIR``: the same in a process whose
``lgekf`` is imported from DIR (an other checkout, e.g. ``git worktree add /tmp/base <commit>`` with
``ln -s ../generated /tmp/base/lgekf/generated`` and ``ln -s ../derive /tmp/base/lgekf/derive``), the two
processes interleaved ``--repeat`` times, and prints baseline / this tree ratios (quote ratios: absolute
times depend on the machine's load) and whether the outputs (states, covariances, NIS, flags; the plans)
are the same bits.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))


def measure(path: Path, models: list, repeat: int) -> dict:
    """Best-of-``repeat`` times (s) of each part in this process, and a digest of each output."""
    import numpy as np

    from lgekf.apps.defaults import plan_noise
    from lgekf.apps.track import TRACK_HEADING_CAP, TrackConfig, track_arrays, track_monitored
    from lgekf.io.readers import read_csv

    meas, starts, _ = read_csv(path).grouped()
    t, z = meas.t, meas.z
    out: dict = {"time": {}, "digest": {}}

    def best(name, fn, digest=None):
        res = fn()  # warm-up: numba caches loaded
        if digest is not None:
            out["digest"][name] = digest(res)
        del res  # not held while timing: fresh pages for a second 10^6-row output would cost more than the filter
        b = float("inf")
        for _ in range(repeat):
            t0 = time.perf_counter()
            fn()
            b = min(b, time.perf_counter() - t0)
        out["time"][name] = b

    def plan(ms):
        return plan_noise(t, z, starts, ms, omega_std=0.5, heading_std=0.1, heading_cap=TRACK_HEADING_CAP)

    def tracked_digest(r):
        h = hashlib.sha256()
        for a in (r.x, r.p, r.nis, r.flag):
            h.update(np.ascontiguousarray(a).tobytes())
        return h.hexdigest() + f" ({len(r.alarms)} alarms)"

    for name, ms in ((f"plan {models[0]}", models[:1]), (f"plan {len(models)} models", models)):
        best(name, lambda ms=ms: plan(ms), lambda p, ms=ms: repr([(m, p.search[m]) for m in ms]))
    cfg = TrackConfig(dict(plan(models).accel_std), 0.2, heading_cap=TRACK_HEADING_CAP)
    for m in models:
        best(f"filter {m}", lambda m=m: track_arrays(m, t, z, starts, cfg))
        best(f"monitored {m}", lambda m=m: track_monitored(m, t, z, starts, cfg), tracked_digest)
    return out


def _child(path: Path, models: list, repeat: int, pythonpath: str | None) -> dict:
    env = dict(os.environ)
    if pythonpath:
        env["PYTHONPATH"] = pythonpath
    cmd = [sys.executable, __file__, "--input", str(path), "--models", ",".join(models), "--repeat", str(repeat), "--json"]
    res = subprocess.run(cmd, env=env, capture_output=True, text=True, check=True)
    return json.loads(res.stdout.strip().splitlines()[-1])


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--input", type=Path, default=None)
    ap.add_argument("--objects", type=int, default=10_000)
    ap.add_argument("--steps", type=int, default=100)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--models", default="se2se2,se2r3,se2r2,ctrv,cv")
    ap.add_argument("--baseline", default=None, metavar="DIR", help="compare with the lgekf of this checkout")
    ap.add_argument("--json", action="store_true", help=argparse.SUPPRESS)
    a = ap.parse_args(argv)
    models = a.models.split(",")
    with tempfile.TemporaryDirectory(prefix="bench_monitor_") as tmp:
        path = a.input
        if path is None:
            from bench_track import generate

            path = Path(tmp) / "measurements.csv"
            generate(path, a.objects, a.steps)
        if a.json:
            print(json.dumps(measure(path, models, a.repeat)))
            return 0
        if a.baseline is None:
            res = measure(path, models, a.repeat)
            for k, v in res["time"].items():
                print(f"{k:<22} {v:.4f} s")
            return 0
        here = str(Path(__file__).resolve().parents[1])
        runs = {"base": [], "this": []}
        for _ in range(a.repeat):  # interleaved processes; inside each, best of 1 after a warm-up
            runs["base"].append(_child(path, models, 1, a.baseline))
            runs["this"].append(_child(path, models, 1, here))
    best = {k: {n: min(r["time"][n] for r in v) for n in v[0]["time"]} for k, v in runs.items()}
    for k in best:
        for m in models:
            best[k][f"monitor {m}"] = best[k][f"monitored {m}"] - best[k][f"filter {m}"]
    same = True
    print(f"{'':<22} {'baseline':>9} {'this':>9} {'ratio':>6}  same output")
    for n in best["base"]:
        b, h = best["base"][n], best["this"][n]
        d = runs["base"][0]["digest"].get(n)
        eq = "" if d is None else ("yes" if d == runs["this"][0]["digest"][n] else "NO")
        same &= eq != "NO"
        print(f"{n:<22} {b:9.4f} {h:9.4f} {b / h if h > 0 else float('nan'):6.2f}  {eq}")
    return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main())
