"""`lgekf track` on 10⁶ measurements: one process against local Dask clusters of 1 and 2 workers.

    python benchmarks/bench_track_dask.py [--objects 10000] [--steps 100] [--model se2se2] [--partition-rows 262144]

Writes the CSV of ``bench_track.py`` (objects interleaved in time order) to a temporary folder, runs
``lgekf track IN -o OUT --model M`` end to end in a fresh process (imports, cluster start and numba cache
loading included), without Dask and with ``--workers 1`` and ``--workers 2``, checks that the three
outputs are byte-identical, and prints the wall times (best of ``--repeats``) and the load average.
"""

from __future__ import annotations

import argparse
import datetime
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_track import cli_command, generate  # noqa: E402


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--objects", type=int, default=10_000)
    ap.add_argument("--steps", type=int, default=100)
    ap.add_argument("--model", default="se2se2")
    ap.add_argument("--partition-rows", type=int, default=1 << 18)
    ap.add_argument("--repeats", type=int, default=2)
    a = ap.parse_args(argv)
    tmp = Path(tempfile.mkdtemp(prefix="bench_track_dask."))
    try:
        src = tmp / "in.csv"
        generate(src, a.objects, a.steps)
        load = os.getloadavg()
        print(f"{datetime.date.today()}: {a.objects * a.steps} rows ({src.stat().st_size / 1e6:.0f} MB), model {a.model}, "
              f"load average before {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}")
        outputs = {}
        for label, extra in (("one process", []), ("1 worker", ["--workers", "1"]), ("2 workers", ["--workers", "2"])):
            best = float("inf")
            for r in range(a.repeats):
                out = tmp / f"out_{len(outputs)}_{r}.csv"
                t0 = time.perf_counter()
                subprocess.run([*cli_command(), "track", str(src), "-o", str(out), "--model", a.model, "--quiet",
                                "--partition-rows", str(a.partition_rows), *extra], check=True)
                best = min(best, time.perf_counter() - t0)
                data = out.read_bytes()
                outputs.setdefault("first", data)
                assert data == outputs["first"], f"{label}: output differs from the single-process run"
                out.unlink()
            outputs[label] = best
            print(f"{label:12} {best:6.2f} s", flush=True)
        load = os.getloadavg()
        print(f"outputs identical; load average after {load[0]:.2f} {load[1]:.2f} {load[2]:.2f}")
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
