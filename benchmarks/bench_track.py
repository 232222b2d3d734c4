"""Time `lgekf track` on 10⁶ measurements: end to end (a subprocess, as a user runs it) and its parts.

    python benchmarks/bench_track.py [--objects 10000] [--steps 100] [--model se2se2] [--keep DIR]
                                     [--one-object] [--no-parts] [--no-parquet] [--compare LGEKF] [--repeat N]

Writes a CSV of OBJECTS x STEPS rows (``id,t,x,y``; objects interleaved in time order, irregular steps
around 0.1 s, turning trajectories (turn rate a mean-reverting random walk) with 0.2 m noise) to a
temporary folder, then reports:
  read     lgekf.io.read_csv + grouping/validation
  init     two-point initialisation of every object (x0, P0 via common_jacobian)
  noise    the noise from the data (lgekf.apps.defaults.plan_noise: measurement std, process-noise search in
           threads), and the same with 1 thread (their ratio)
  filter   the filter over all objects (generated run_batch kernels, objects bucketed by length)
  monitor  the divergence monitor and any re-initialisations (track_monitored minus the filter)
  format   CSV text of the output (numba formatter) and writing it
  end2end  `lgekf track IN -o OUT --model M` in a fresh process (imports and numba cache loading included),
           for M and for `--model all`, CSV out and (with pyarrow) Parquet out and in, on the same file and
           (``--one-object``, default on) on one object of the same number of measurements; each with its
           peak memory (max RSS of the process) next to the baseline RSS of ``python -c "import numpy, numba"``
           and the input file's size; "fixed" is the max RSS of `lgekf track` on a file of 20 rows (numba's
           LLVM and the loaded kernels: what any run holds whatever the input), "data" the max RSS minus it.
  --compare LGEKF  the end-to-end runs also with another ``lgekf`` executable (e.g. /work/main/.venv/bin/lgekf),
           interleaved with this one's, best of ``--repeat`` runs each, with the ratio of their times and the
           check that both wrote the same bytes (both checkouts byte-compiled first: ``byte_compile_other``).
"""

from __future__ import annotations

import argparse
import hashlib
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np


def generate(path: Path, objects: int, steps: int, seed: int = 0) -> None:
    from lgekf.io.formatting import format_rows, label_bytes

    rng = np.random.default_rng(seed)
    dt = rng.uniform(0.07, 0.13, (objects, steps))
    t = np.cumsum(dt, axis=1) + rng.uniform(0, 5, (objects, 1))
    # turn rate: mean-reverting (AR(1), stationary std ~0.35 rad/s), so that a long object stays a plausible one
    from scipy.signal import lfilter

    w = lfilter([1.0], [1.0, -0.99], 0.05 * rng.standard_normal((objects, steps)), axis=1) + rng.uniform(-0.5, 0.5, (objects, 1))
    th = rng.uniform(-np.pi, np.pi, (objects, 1)) + np.cumsum(w * dt, axis=1)
    speed = rng.uniform(0.5, 15.0, (objects, 1))
    x = np.cumsum(speed * np.cos(th) * dt, axis=1) + rng.uniform(-500, 500, (objects, 1))
    y = np.cumsum(speed * np.sin(th) * dt, axis=1) + rng.uniform(-500, 500, (objects, 1))
    x += 0.2 * rng.standard_normal(x.shape)
    y += 0.2 * rng.standard_normal(y.shape)
    order = np.argsort(t.ravel(), kind="stable")  # interleave the objects in time order
    obj = np.repeat(np.arange(objects), steps)[order]
    lab = label_bytes([str(i) for i in range(objects)])
    with open(path, "wb") as f:
        f.write(b"id,t,x,y\n")
        f.write(format_rows(lab, obj, t.ravel()[order], np.column_stack([x.ravel()[order], y.ravel()[order]]), 9, t_digits=9))


def byte_compile() -> str:
    """Byte-compile lgekf's modules and the generated kernels' (``compileall``), as ``pip install`` does for an installed package, and say so.

    An editable install writes the ``.pyc`` files on its first run, unless ``PYTHONDONTWRITEBYTECODE`` is set
    (as on the machine of 2026-11-24): then every run compiles the generated kernel modules from source, about
    0.07 s and 23 MB of peak memory in a `lgekf track` of one model. Runs compare like with like either way.
    """
    import compileall

    import lgekf.generated as generated
    import lgekf

    roots = [Path(m.__file__).resolve().parent for m in (lgekf, generated)]
    ok = all(compileall.compile_dir(str(r), quiet=1) for r in roots)
    env = os.environ.get("PYTHONDONTWRITEBYTECODE")
    return (f"modules byte-compiled ({', '.join(r.name for r in roots)}{'' if ok else ', with errors'}), as an installed package has them"
            + (f"; PYTHONDONTWRITEBYTECODE={env} is set here" if env else ""))


def byte_compile_other(lgekf_exe: str) -> str:
    """``byte_compile`` for the checkout of another ``lgekf`` executable (``--compare``), through the Python of its
    script (its ``#!`` line): without it, with ``PYTHONDONTWRITEBYTECODE`` set, every run of the other would compile
    its generated modules from source (about 0.07 s and 23 MB each) and the comparison would favour this checkout.
    Stops the benchmark (SystemExit) when that fails."""
    exe = shutil.which(lgekf_exe) or lgekf_exe
    try:
        with open(exe, "rb") as f:
            first = f.readline().decode(errors="replace").strip()
    except OSError as e:
        raise SystemExit(f"--compare {lgekf_exe}: cannot read the script ({e})")
    if not first.startswith("#!"):
        raise SystemExit(f"--compare {lgekf_exe}: not a Python script with a #! line; cannot byte-compile its checkout")
    python = first[2:].strip().split()[0]
    code = ("import compileall, pathlib, lgekf, lgekf.generated as g; "
            "print(all(compileall.compile_dir(str(pathlib.Path(m.__file__).resolve().parent), quiet=1) for m in (lgekf, g)))")
    r = subprocess.run([python, "-c", code], capture_output=True, text=True)
    if r.returncode != 0 or r.stdout.strip() != "True":
        raise SystemExit(f"--compare {lgekf_exe}: byte-compiling its checkout with {python} failed: {(r.stderr or r.stdout).strip()}")
    return f"the other checkout's modules byte-compiled too (with {python})"


def cli_command():
    exe = Path(sys.executable).with_name("lgekf")
    return [str(exe)] if exe.exists() else [sys.executable, "-c", "from lgekf.cli import run; run()"]


def measured_run(cmd) -> tuple:
    """(seconds, max RSS in MB, stderr, CPU seconds (user + system)) of ``cmd`` run in a fresh process (through a Python wrapper, so
    that RUSAGE_CHILDREN holds that command alone)."""
    wrapper = ("import resource, subprocess, sys, time; t = time.perf_counter(); "
               "r = subprocess.run(sys.argv[1:], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE); "
               "dt = time.perf_counter() - t; sys.stderr.buffer.write(r.stderr); "
               "u = resource.getrusage(resource.RUSAGE_CHILDREN); print(r.returncode, dt, u.ru_maxrss, u.ru_utime + u.ru_stime)")
    r = subprocess.run([sys.executable, "-c", wrapper, *cmd], capture_output=True, text=True)
    rc, sec, kb, cpu = r.stdout.split()
    if int(rc) != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed: {r.stderr}")
    return float(sec), int(kb) / 1024, r.stderr, float(cpu)


def fixed_rss(tmp: Path, cli=None, model: str = "se2se2") -> float:
    """Max RSS (MB) of `lgekf track --model MODEL` on a file of 20 rows: what a run holds whatever its input."""
    tiny = tmp / "tiny.csv"
    tiny.write_text("id,t,x,y\n" + "".join(f"{i % 2},{0.1 * (i // 2):.1f},{0.5 * i:.1f},{0.1 * i:.1f}\n" for i in range(20)))
    out = tmp / "tiny_out.csv"
    mb = min(measured_run([*(cli or cli_command()), "track", str(tiny), "-o", str(out), "--model", model, "--quiet"])[1] for _ in range(2))
    for f in tmp.glob("tiny_out*.csv"):
        f.unlink()
    return mb


def end_to_end(inp: Path, tmp: Path, model: str, parquet: bool, compare=None, repeat: int = 1) -> list:
    """Rows (what, seconds, CPU s, max RSS MB, output MB[, other's seconds, other's max RSS MB, same bytes]) of
    `lgekf track` on ``inp``: the model, ``all``, Parquet; with ``compare`` (another lgekf command) both, interleaved,
    best of ``repeat``."""
    if compare is not None:
        return _compared(inp, tmp, model, compare, repeat)
    rows = []
    runs = [(model, "csv", inp), ("all", "csv", inp)]
    if parquet:
        pq_in = inp.with_suffix(".parquet")
        import pyarrow as pa
        import pyarrow.csv as pc
        import pyarrow.parquet as pq

        pq.write_table(pc.read_csv(inp, convert_options=pc.ConvertOptions(column_types={"id": pa.string()})), pq_in)
        runs += [(model, "parquet", inp), ("all", "parquet", inp), (model, "parquet", pq_in)]
    for m, kind, src in runs:
        out = tmp / f"tracks.{kind}"
        sec, mb, _, cpu = measured_run([*cli_command(), "track", str(src), "-o", str(out), "--model", m, "--quiet"])
        outs = [out] if m != "all" else sorted(tmp.glob(f"tracks_*.{kind}"))
        size = sum(o.stat().st_size for o in outs) / 1e6
        what = f"--model {m}, {src.suffix[1:]} in, {kind} out"
        rows.append((what, sec, cpu, mb, size))
        for o in outs:
            o.unlink()
    return rows


def _compared(inp: Path, tmp: Path, model: str, compare, repeat: int) -> list:
    """Both commands on ``inp`` (CSV out; ``model`` and ``all``), interleaved, best of ``repeat`` each."""
    rows = []
    for m in (model, "all"):
        best = {}
        outs = {}
        for _ in range(max(1, repeat)):
            for who, cli in (("this", cli_command()), ("other", compare)):
                out = tmp / f"{who}.csv"
                sec, mb, _, cpu = measured_run([*cli, "track", str(inp), "-o", str(out), "--model", m, "--quiet"])
                b = best.get(who)
                best[who] = (min(sec, b[0]), min(cpu, b[1]), max(mb, b[2])) if b else (sec, cpu, mb)
                files = [out] if m != "all" else sorted(tmp.glob(f"{who}_*.csv"))
                outs[who] = [hashlib.sha256(f.read_bytes()).hexdigest() for f in files]
                size = sum(f.stat().st_size for f in files) / 1e6
                for f in files:
                    f.unlink()
        same = outs["this"] == outs["other"]
        rows.append((f"--model {m}, csv in, csv out", *best["this"], size, best["other"][0], best["other"][2], same))
    return rows


def print_end_to_end(title, inp: Path, rows, base_mb: float, fixed_mb: dict | None = None, other_fixed: dict | None = None) -> None:
    """The table of ``end_to_end``'s rows; ``fixed_mb`` {"one": MB, "all": MB}: ``fixed_rss`` of one model and of all."""
    mb_in = inp.stat().st_size / 1e6
    fixed = (f"; fixed RSS (lgekf track on 20 rows) {fixed_mb['one']:.0f} MB, --model all {fixed_mb['all']:.0f} MB"
             if fixed_mb else "")
    print(f"\n{title}: input {mb_in:.1f} MB CSV; baseline RSS (python -c 'import numpy, numba') {base_mb:.0f} MB{fixed}")
    head = f"{'end to end':<40}{'seconds':>9}{'CPU s':>8}{'max RSS MB':>12}{'minus base':>12}{'/ input':>9}"
    head += f"{'data / in':>10}" if fixed_mb else ""
    head += f"{'output MB':>11}"
    if rows and len(rows[0]) > 5:
        head += f"{'other s':>9}{'time ratio':>11}{'other RSS':>10}{'/ input':>9}{'data / in':>10}{'same':>6}"
    print(head)
    for what, sec, cpu, mb, size, *other in rows:
        key = "all" if "--model all" in what else "one"
        line = f"{what:<40}{sec:9.2f}{cpu:8.2f}{mb:12.0f}{mb - base_mb:12.0f}{(mb - base_mb) / mb_in:9.2f}"
        line += f"{(mb - fixed_mb[key]) / mb_in:10.2f}" if fixed_mb else ""
        line += f"{size:11.1f}"
        if other:
            o_sec, o_mb, same = other
            o_fixed = (other_fixed or fixed_mb or {key: base_mb})[key]
            line += f"{o_sec:9.2f}{sec / o_sec:11.2f}{o_mb:10.0f}{(o_mb - base_mb) / mb_in:9.2f}{(o_mb - o_fixed) / mb_in:10.2f}{'yes' if same else 'NO':>6}"
        print(line)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--objects", type=int, default=10_000)
    ap.add_argument("--steps", type=int, default=100)
    ap.add_argument("--model", default="se2se2")
    ap.add_argument("--keep", type=Path, default=None, help="write the files here and keep them")
    ap.add_argument("--no-one-object", dest="one_object", action="store_false",
                    help="skip the end-to-end runs on one object of OBJECTS x STEPS measurements")
    ap.add_argument("--no-parts", dest="parts", action="store_false", help="skip the in-process timing of the parts")
    ap.add_argument("--no-parquet", dest="parquet", action="store_false", help="skip the Parquet runs")
    ap.add_argument("--compare", default=None, metavar="LGEKF",
                    help="another lgekf executable: end-to-end runs (CSV) of both, interleaved, with time ratios and a byte check")
    ap.add_argument("--repeat", type=int, default=3, help="with --compare: best of this many runs each (default 3)")
    ap.add_argument("--no-byte-compile", dest="byte_compile", action="store_false",
                    help="measure without first byte-compiling lgekf's modules (see byte_compile)")
    a = ap.parse_args(argv)
    if a.byte_compile:
        print(byte_compile())
        if a.compare is not None:
            print(byte_compile_other(a.compare))
    try:
        import pyarrow  # noqa: F401
    except ImportError:
        if a.parquet:
            print("pyarrow is not installed: no Parquet runs (pip install \"lgekf[parquet]\")")
        a.parquet = False

    from lgekf.io.formatting import format_rows, label_bytes
    from lgekf.io.readers import read_csv
    from lgekf.core.registry import MODELS
    from lgekf.apps.defaults import plan_noise
    from lgekf.apps.track import (
        TRACK_HEADING_CAP, TrackConfig, initial_common, initial_estimates, output_columns, track_arrays, track_monitored,
    )

    tmp = Path(tempfile.mkdtemp(prefix="bench_track_")) if a.keep is None else a.keep
    tmp.mkdir(parents=True, exist_ok=True)
    try:
        inp, out = tmp / "measurements.csv", tmp / "tracks.csv"
        t0 = time.perf_counter()
        generate(inp, a.objects, a.steps)
        n = a.objects * a.steps
        print(f"{n} measurements ({a.objects} objects x {a.steps} steps), {inp.stat().st_size / 1e6:.1f} MB, "
              f"generated in {time.perf_counter() - t0:.2f} s; {os.cpu_count()} CPUs")

        # warm the numba caches (not timed), then each part once
        subprocess.run([*cli_command(), "track", str(inp), "-o", str(tmp / "warm.csv"), "--model", "all", "--quiet"],
                       capture_output=True)
        base_mb = measured_run([sys.executable, "-c", "import numpy, numba"])[1]
        print(f"load average {' '.join(f'{v:.1f}' for v in os.getloadavg())}")
        if not a.parts:
            return _end_to_end_only(a, inp, tmp, n, base_mb)
        small = read_csv(inp).grouped()
        track_arrays(a.model, small[0].t[:1000], small[0].z[:1000], np.array([0, 1000]), TrackConfig())
        track_monitored(a.model, small[0].t[:1000], small[0].z[:1000], np.array([0, 1000]), TrackConfig())
        rows = []
        t0 = time.perf_counter()
        meas, starts, _ = read_csv(inp).grouped()
        rows.append(("read", time.perf_counter() - t0))
        t0 = time.perf_counter()
        plan = plan_noise(meas.t, meas.z, starts, [a.model], omega_std=0.5, heading_std=0.1, heading_cap=TRACK_HEADING_CAP)
        rows.append(("noise", time.perf_counter() - t0))
        print(plan.describe())
        t0 = time.perf_counter()  # the same search serially: the threads' gain (benchmarks/bench_noise_search.py: best of N)
        plan_noise(meas.t, meas.z, starts, [a.model], omega_std=0.5, heading_std=0.1, heading_cap=TRACK_HEADING_CAP, workers=1)
        t_serial = time.perf_counter() - t0
        print(f"noise with 1 thread: {t_serial:.3f} s, {t_serial / rows[-1][1]:.2f}x the threaded search")
        cfg = TrackConfig(dict(plan.accel_std), plan.meas_std, heading_cap=TRACK_HEADING_CAP)
        t0 = time.perf_counter()
        c, var = initial_common(meas.t, meas.z, starts, cfg.meas_std, heading_cap=TRACK_HEADING_CAP)
        x0, P0 = initial_estimates(a.model, c, var)
        rows.append(("init", time.perf_counter() - t0))
        t0 = time.perf_counter()
        x, p, nis = track_arrays(a.model, meas.t, meas.z, starts, cfg, x0=x0, P0=P0)
        t_filter = time.perf_counter() - t0
        rows.append(("filter", t_filter))
        t0 = time.perf_counter()
        res = track_monitored(a.model, meas.t, meas.z, starts, cfg)
        rows.append(("monitor", time.perf_counter() - t0 - t_filter))
        print(f"{len(res.alarms)} alarms, {int(res.flag.sum())} rows flagged")
        t0 = time.perf_counter()
        spec = MODELS[a.model]
        diag = [i * spec.n - i * (i - 1) // 2 for i in range(spec.n)]
        body = format_rows(label_bytes(meas.labels), meas.obj, meas.t,
                           np.hstack([x, np.sqrt(p[:, diag]), nis[:, None], res.flag[:, None].astype(float)]), 10)
        with open(out, "wb") as f:
            f.write((",".join(output_columns(a.model)) + "\n").encode())
            f.write(body)
        rows.append(("format+write", time.perf_counter() - t0))
        rows.append(("sum of parts", sum(r[1] for r in rows)))
        t0 = time.perf_counter()
        r = subprocess.run([*cli_command(), "track", str(inp), "-o", str(out), "--model", a.model, "--quiet"], capture_output=True, text=True)
        if r.returncode != 0:
            print(r.stderr, file=sys.stderr)
            return 1
        rows.append(("end2end (lgekf track)", time.perf_counter() - t0))

        print(f"\nmodel {a.model}, output {out.stat().st_size / 1e6:.1f} MB")
        print(f"{'part':<24}{'seconds':>9}{'ns/measurement':>16}")
        for name, sec in rows:
            print(f"{name:<24}{sec:9.3f}{1e9 * sec / n:16.0f}")
        _end_to_end_only(a, inp, tmp, n, base_mb)
    finally:
        if a.keep is None:
            shutil.rmtree(tmp, ignore_errors=True)
    return 0


def _end_to_end_only(a, inp, tmp, n, base_mb) -> int:
    compare = None if a.compare is None else [a.compare]
    fixed_mb = {"one": fixed_rss(tmp, None, a.model), "all": fixed_rss(tmp, None, "all")}
    other_fixed = None if compare is None else {"one": fixed_rss(tmp, compare, a.model), "all": fixed_rss(tmp, compare, "all")}
    print_end_to_end(f"{a.objects} objects x {a.steps} steps", inp, end_to_end(inp, tmp, a.model, a.parquet, compare, a.repeat), base_mb,
                     fixed_mb, other_fixed)
    if a.one_object:
        one = tmp / "one_object.csv"
        generate(one, 1, n)
        print_end_to_end(f"one object of {n} measurements", one, end_to_end(one, tmp, a.model, a.parquet, compare, a.repeat), base_mb,
                         fixed_mb, other_fixed)
    if compare is not None:
        print(f"(other: {a.compare}; its fixed RSS {other_fixed['one']:.0f} MB, --model all {other_fixed['all']:.0f} MB; "
              f"time ratio = this / other, best of {a.repeat} each, interleaved)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
