"""Micro-benchmark of the CSV number formatter (``lgekf.io.formatting._format_rows``) on one thread.

Old (the formatter before the fast path, vendored in tests/_formatting_old.py) and new (the library's) are run
interleaved in one process on the same realistic rows of ``lgekf track`` output: label, t (0..1e4 s, 15 digits),
positions ±500 m, an angle, velocities, a turn rate, six standard deviations 1e-3..1, NIS (χ², 2 dof), a 0/1
flag (15 numbers a row, 10 digits). Both must give the same bytes (checked). Printed: ns per value and per
output byte, best of ``--repeat`` runs each, and the ratio old/new. Absolute times depend on the machine's
load; the ratio is the figure to quote.

    .venv/bin/python benchmarks/bench_format.py [--rows 65536] [--repeat 15] [--digits 10]
"""

from __future__ import annotations

import argparse
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests"))

import _formatting_old as old  # noqa: E402

from lgekf.io import formatting as new  # noqa: E402


def realistic_rows(n: int, seed: int = 0):
    """(labels bytes, offsets, row labels, t, values (n, 14)) like one model's ``lgekf track`` rows."""
    rng = np.random.default_rng(seed)
    labels = [f"obj{i}" for i in range(max(1, n // 100))]
    lab = new.label_bytes(labels)
    row = np.sort(rng.integers(0, len(labels), n)).astype(np.int64)
    t = np.sort(rng.uniform(0.0, 1e4, n))
    cols = [
        rng.uniform(-500.0, 500.0, n), rng.uniform(-500.0, 500.0, n),  # x, y
        rng.uniform(-np.pi, np.pi, n),  # heading
        rng.normal(0.0, 8.0, n), rng.normal(0.0, 2.0, n),  # velocities
        rng.normal(0.0, 0.3, n),  # turn rate
    ]
    cols += [10.0 ** rng.uniform(-3.0, 0.0, n) for _ in range(6)]  # standard deviations
    cols.append(rng.chisquare(2.0, n))  # NIS
    cols.append((rng.random(n) < 0.01).astype(float))  # flag
    return lab, row, t, np.ascontiguousarray(np.column_stack(cols))


def main(argv=None) -> None:
    """Run the benchmark and print old vs new."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rows", type=int, default=65536)
    ap.add_argument("--repeat", type=int, default=15)
    ap.add_argument("--digits", type=int, default=10)
    ap.add_argument("--t-digits", type=int, default=15)
    a = ap.parse_args(argv)
    lab, row, t, vals = realistic_rows(a.rows)
    d = np.full(vals.shape[1], a.digits, dtype=np.int64)
    impl = {"old": old._format_rows, "new": new._format_rows}
    outs = {k: f(lab[0], lab[1], row, t, a.t_digits, vals, d) for k, f in impl.items()}  # compile, warm up
    if outs["old"].tobytes() != outs["new"].tobytes():
        raise SystemExit("old and new formatter differ on the benchmark rows")
    best = {k: np.inf for k in impl}
    for _ in range(a.repeat):
        for k, f in impl.items():  # interleaved: the same machine load for both
            t0 = time.perf_counter()
            f(lab[0], lab[1], row, t, a.t_digits, vals, d)
            best[k] = min(best[k], time.perf_counter() - t0)
    nval = vals.size + len(t)
    nbytes = len(outs["new"])
    print(f"{a.rows} rows x {vals.shape[1] + 1} values, digits {a.digits} (t {a.t_digits}), {nbytes / 1e6:.1f} MB, "
          f"best of {a.repeat}, one thread, load average {os.getloadavg()[0]:.2f}")
    for k in impl:
        print(f"  {k}: {best[k] * 1e9 / nval:6.2f} ns/value  {best[k] * 1e9 / nbytes:5.2f} ns/byte")
    print(f"  ratio old/new: {best['old'] / best['new']:.2f}x")


if __name__ == "__main__":
    main()
