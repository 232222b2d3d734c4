"""The robustness set of `lgekf track` (issue #14): every model on simulated and real cases, before (0.3 m,
default process noise, no monitor) and after (`lgekf track` with no options: noise from the data,
divergence monitor and recovery). Prints two markdown tables: the per-case summary and case x model.

    python benchmarks/robustness.py [--cases gnss-car,kitti-1m,...] [--data-root DIR] [--out FILE.md]

The cases, the criteria and what "hard" means: lgekf/apps/robustness.py (and docs/robustness.md,
"Robustness"). Real cases are skipped, with the reason, when their data are absent.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", default=None, help="comma-separated case names (default: all)")
    ap.add_argument("--data-root", default=None, help="folder of the real data (default: $LGEKF_DATA or ../shared/data)")
    ap.add_argument("--out", type=Path, default=None, help="also write the tables to this markdown file")
    a = ap.parse_args(argv)

    from lgekf.apps.robustness import markdown_table, real_cases, run_case, simulated_cases, summary_table

    names = a.cases.split(",") if a.cases else None
    cases = simulated_cases(names)
    real, skipped = real_cases(a.data_root, names)
    cases += real
    results = []
    t0 = time.perf_counter()
    for c in cases:
        t1 = time.perf_counter()
        results += run_case(c)
        print(f"{c.name}: {c.n_tracks} tracks, {c.t.size} rows, {time.perf_counter() - t1:.1f} s", file=sys.stderr)
    text = ["## Summary", "", summary_table(results, cases), "", "## Case x model", "",
            "Position RMSE (m) over the rows k >= 2 that are not flagged (after: in parentheses over all rows), "
            "speed RMSE (m/s), turn-rate RMSE (rad/s), share of rows flagged (alarms).", "", markdown_table(results)]
    if skipped:
        text += ["", "Skipped: " + "; ".join(f"{k} ({v})" for k, v in skipped.items())]
    out = "\n".join(text)
    print(out)
    print(f"total {time.perf_counter() - t0:.1f} s", file=sys.stderr)
    if a.out:
        a.out.write_text(out + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
