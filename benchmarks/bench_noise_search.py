"""Time the noise from the data (``lgekf.apps.defaults.plan_noise``) serial vs in threads (``lgekf.apps.search``).

    python benchmarks/bench_noise_search.py [--objects 10000] [--steps 100] [--repeat 5] [--model se2se2]
                                            [--input FILE]

On the file of ``benchmarks/bench_track.py`` (OBJECTS x STEPS rows, generated unless ``--input`` names one):
``plan_noise`` for one model and for all five models, with ``workers=1`` (the serial search) and with every
usable CPU, interleaved, best of ``--repeat`` each; prints the times, their ratio (serial / threads) and
checks that both give the same plan. Quote the ratios: absolute times depend on the machine's load.
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--objects", type=int, default=10_000)
    ap.add_argument("--steps", type=int, default=100)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--model", default="se2se2")
    ap.add_argument("--input", type=Path, default=None, help="a measurement file (id,t,x,y) instead of a generated one")
    a = ap.parse_args(argv)

    from bench_track import generate

    from lgekf.apps.defaults import plan_noise
    from lgekf.apps.search import usable_cpus
    from lgekf.apps.track import TRACK_HEADING_CAP
    from lgekf.core.registry import MODELS
    from lgekf.io.readers import read_csv

    with tempfile.TemporaryDirectory(prefix="bench_noise_") as tmp:
        inp = a.input
        if inp is None:
            inp = Path(tmp) / "measurements.csv"
            generate(inp, a.objects, a.steps)
        meas, starts, _ = read_csv(inp).grouped()
    cpus = usable_cpus()
    print(f"{meas.t.size} measurements, {len(starts) - 1} objects; {cpus} usable CPUs")
    for models in ([a.model], list(MODELS)):
        def plan(workers):
            return plan_noise(meas.t, meas.z, starts, models, omega_std=0.5, heading_std=0.1, heading_cap=TRACK_HEADING_CAP,
                              workers=workers)

        plans = {1: plan(1), cpus: plan(cpus)}  # warm: numba caches loaded, not timed
        best = {1: float("inf"), cpus: float("inf")}
        for _ in range(a.repeat):
            for w in best:
                t0 = time.perf_counter()
                plans[w] = plan(w)
                best[w] = min(best[w], time.perf_counter() - t0)
        same = all(plans[1].search[m] == plans[cpus].search[m] for m in models)
        name = models[0] if len(models) == 1 else f"all {len(models)} models"
        print(f"plan_noise {name:<16} serial {best[1]:.3f} s, {cpus} threads {best[cpus]:.3f} s: "
              f"ratio {best[1] / best[cpus]:.2f}; same plan: {'yes' if same else 'NO'}")
        if not same:
            return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
