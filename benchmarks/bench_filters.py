"""Speed of every registry model, measured in one run (ratios are only meaningful within one run).

    .venv/bin/python benchmarks/bench_filters.py [--quick] [--repeat N]

Per model, interleaved (every round times every kernel once; the best of N rounds is reported), in ns per
trajectory-step (one predict + update + output conversion):

* ``batch``: the generated ``run_batch_position`` over 3000 trajectories × 200 steps, numba prange over trajectories;
* ``SIMD``: the structure-of-arrays kernel ``run_batch_soa_position`` (trajectories in the vector lanes; ``-`` where a
  model has none); ``filter_batch`` picks between the two (``lgekf.core.batch.batch_kernel``);
* ``one``: ``run_one_position`` over one trajectory of 200 000 steps (one core);
* ``flops``: operations of one step counted from the generated code (benchmarks/flops.py says what counts);
* ``÷C``: the ratio to the hand-written scalar C kernel of the SE(2)×SE(2) step (benchmarks/c/se2se2_step.c,
  compiled now with ``cc -O3 -march=native -fopenmp``; OpenMP over 2 threads for the batch), batch and one trajectory.
  The C kernel implements SE(2)×SE(2) only: the other models' ratios use it as a yardstick.

The kernels are called directly with preallocated arrays (no ``filter_batch`` validation), like the C through ctypes.
Then, as before: the Python classes (one call per step), the dense-numpy SE(2)×SE(2) LG-EKF, FilterPy (where
installed), and the JIT cost (first call in a fresh process, empty and warm numba cache).
The header gives the date, the load (``uptime``) and the CPU: quote ratios, never absolute times, from a loaded machine.
"""

from __future__ import annotations

import argparse
import datetime
import os
import platform
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
# idle OpenMP threads (numba's omp layer and the C baseline's libgomp) sleep instead of spinning after a parallel
# loop: spinning threads would steal the core from the one-trajectory timings that follow
os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")

import lgekf  # noqa: E402
from c_baseline import CompilerMissing, load_c_baseline  # noqa: E402
from dense_numpy import run_dense  # noqa: E402
from flops import step_flops  # noqa: E402

from lgekf.core.registry import ALL_MODELS, SPACES, base_measurement  # noqa: E402


def _start(space: str) -> list:
    """The common start of every model of ``space``: 3 m/s forward, turning at 0.1 rad/s about the vertical."""
    return [0, 0, 0, 3, 0, 0.1] if SPACES[space]["dim"] == 2 else [0] * 6 + [3, 0, 0] + [0, 0, 0.1]


# every registry model of every space: its default noise, started at its space's common start; its position measurement
MODELS = {name: (spec.default_accel_std, lgekf.state_from_common(name, _start(spec.space)).tolist())
          for name, spec in ALL_MODELS.items()}
MEAS = {name: base_measurement(spec.space) for name, spec in ALL_MODELS.items()}
DIM = {name: SPACES[spec.space]["dim"] for name, spec in ALL_MODELS.items()}


def best_of(fn, repeat=3):
    best = float("inf")
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t)
    return best


def data(B, K, seed=0, dim=2):
    rng = np.random.default_rng(seed)
    t = np.arange(1, K + 1) * 0.1
    truth = np.stack([3 * t, np.sin(t), 0.1 * t][:dim], axis=-1)
    return truth[None] + 0.5 * rng.standard_normal((B, K, dim))


def kernel_timers(model, B, K, Kone):
    """{column: zero-argument callable} running the model's generated loops on preallocated arrays."""
    spec = lgekf.get_model(model)
    kern = spec.kernels
    q, x0 = MODELS[model]
    meas, dim = MEAS[model], DIM[model]
    n, npk = spec.n, spec.n_packed
    z = data(B, K, dim=dim)
    dts = np.full((B, K), 0.1)
    X0 = np.ascontiguousarray(np.tile(x0, (B, 1)), dtype=float)
    p0 = np.tile(np.eye(n)[np.triu_indices(n)] * 0.1, (B, 1))
    q, r = np.asarray(q, dtype=float), np.array([0.5])
    ox, on, op = np.empty((B, K, n)), np.empty((B, K)), np.empty((B, 0, npk))
    z1, d1 = data(1, Kone, seed=1, dim=dim)[0], np.full(Kone, 0.1)
    ox1, on1, op1 = np.empty((Kone, n)), np.empty(Kone), np.empty((0, npk))
    batch = getattr(kern, f"run_batch_{meas}")
    one = getattr(kern, f"run_one_{meas}")
    timers = {"batch": (lambda: batch(z, dts, X0, p0, q, r, ox, op, on), B * K),
              "one": (lambda: one(z1, d1, X0[0], p0[0], q, r, ox1, op1, on1), Kone)}
    soa = getattr(kern, f"run_batch_soa_{meas}", None)
    if soa is not None:
        timers["SIMD"] = (lambda: soa(z, dts, X0, p0, q, r, ox, op, on), B * K)
    return timers


def c_timers(B, K, Kone):
    """The C baseline's batch and one-trajectory loops on the SE(2)×SE(2) problem (None: no compiler, with why)."""
    try:
        c = load_c_baseline()
    except CompilerMissing as e:
        return None, str(e)
    _, x0 = MODELS["se2se2"]
    z = data(B, K)
    dts = np.full((B, K), 0.1)
    X0 = np.ascontiguousarray(np.tile(x0, (B, 1)), dtype=float)
    p0 = np.tile(np.eye(6)[np.triu_indices(6)] * 0.1, (B, 1))
    q, r = np.asarray(MODELS["se2se2"][0], dtype=float), np.array([0.5])
    ox, on = np.empty((B, K, 6)), np.empty((B, K))
    z1, d1 = data(1, Kone, seed=1)[0], np.full(Kone, 0.1)
    ox1, on1 = np.empty((Kone, 6)), np.empty(Kone)
    return {"batch": (lambda: c.run_batch(z, dts, X0, p0, q, r, ox, on), B * K),
            "one": (lambda: c.run_one(z1, d1, X0[0], p0[0], q, r, ox1, on1), Kone)}, f"{c.compiler} {' '.join(c_flags())}"


def c_flags():
    from c_baseline import FLAGS

    return FLAGS


def interleaved(timers: dict, repeat: int) -> dict:
    """Best-of-``repeat`` ns per trajectory-step of every timer, rounds interleaved over all of them."""
    for fn, _ in timers.values():
        fn()  # compile / warm
    best = {k: float("inf") for k in timers}
    for _ in range(repeat):
        for k, (fn, steps) in timers.items():
            t = time.perf_counter()
            fn()
            best[k] = min(best[k], (time.perf_counter() - t) / steps * 1e9)
    return best


def class_ns(model, K):
    q, x0 = MODELS[model]
    n = len(x0)
    z = data(1, K, dim=DIM[model])[0]
    f = lgekf.make_filter(model, dt=0.1, accel_std=q, meas_std=0.5, x0=x0, P0=np.eye(n) * 0.1)
    f.predict()
    f.update(z[0])

    def run():
        for k in range(K):
            f.predict()
            f.update(z[k])

    return best_of(run, 2) / K * 1e9


def dense_ns(B, K):
    z = data(B, K)
    x0 = np.tile([0, 0, 0, 3, 0, 0.1], (B, 1)).astype(float)
    t = time.perf_counter()
    run_dense(z, 0.1, (0.1, 0.1, 1.0), 0.5, x0, np.eye(6) * 0.1)
    return (time.perf_counter() - t) / (B * K) * 1e9


def filterpy_ns(K):
    try:
        from filterpy.kalman import KalmanFilter
    except ImportError:
        return None

    z = data(1, K)[0]
    dt, sa = 0.1, 0.5
    kf = KalmanFilter(dim_x=4, dim_z=2)
    kf.x = np.array([0.0, 0.0, 3.0, 0.0])
    kf.F = np.array([[1, 0, dt, 0], [0, 1, 0, dt], [0, 0, 1, 0], [0, 0, 0, 1.0]])
    kf.H = np.array([[1, 0, 0, 0], [0, 1, 0, 0.0]])
    G = np.vstack([dt**2 / 2 * np.eye(2), dt * np.eye(2)])
    kf.Q = sa**2 * G @ G.T
    kf.R = 0.25 * np.eye(2)
    kf.P = np.eye(4) * 0.1
    t = time.perf_counter()
    for k in range(K):
        kf.predict()
        kf.update(z[k])
    return (time.perf_counter() - t) / K * 1e9


def filterpy_ekf_ctrv_ns(K):
    """FilterPy's ExtendedKalmanFilter with a CTRV model written in numpy (as FilterPy users do)."""
    try:
        from filterpy.kalman import ExtendedKalmanFilter
    except ImportError:
        return None

    dt, sa, sw = 0.1, 0.1, 1.0

    def f(x):
        px, py, psi, v, w = x
        if abs(w) > 1e-6:
            return np.array([px + v / w * (np.sin(psi + w * dt) - np.sin(psi)),
                             py + v / w * (np.cos(psi) - np.cos(psi + w * dt)), psi + w * dt, v, w])
        return np.array([px + v * dt * np.cos(psi), py + v * dt * np.sin(psi), psi, v, w])

    def jac(x, eps=1e-6):
        J = np.empty((5, 5))
        for i in range(5):
            d = np.zeros(5)
            d[i] = eps
            J[:, i] = (f(x + d) - f(x - d)) / (2 * eps)
        return J

    class CTRVEKF(ExtendedKalmanFilter):
        def predict_x(self, u=0):
            self.x = f(self.x)

    z = data(1, K)[0]
    ekf = CTRVEKF(dim_x=5, dim_z=2)
    ekf.x = np.array([0.0, 0.0, 0.0, 3.0, 0.1])
    ekf.P = np.eye(5) * 0.1
    ekf.R = 0.25 * np.eye(2)
    H = np.array([[1, 0, 0, 0, 0], [0, 1, 0, 0, 0.0]])
    t = time.perf_counter()
    for k in range(K):
        ekf.F = jac(ekf.x)
        c, s = np.cos(ekf.x[2]), np.sin(ekf.x[2])
        G = np.array([[dt**2 / 2 * c, 0], [dt**2 / 2 * s, 0], [0, dt**2 / 2], [dt, 0], [0, dt]])
        ekf.Q = G @ np.diag([sa**2, sw**2]) @ G.T
        ekf.predict()
        ekf.update(z[k], HJacobian=lambda x: H, Hx=lambda x: x[:2])
    return (time.perf_counter() - t) / K * 1e9


JIT_SNIPPET = """
import time, numpy as np
t0 = time.perf_counter()
import lgekf
t1 = time.perf_counter()
for m, spec in lgekf.MODELS.items():
    lgekf.filter_batch(m, np.zeros((2, 3, 2)), dt=0.1, accel_std=spec.default_accel_std, meas_std=0.5, x0=np.ones((2, spec.n)),
                       P0=np.eye(spec.n))
t2 = time.perf_counter()
print(f"{t1 - t0:.3f} {t2 - t1:.3f}")
"""


def jit_cost():
    with tempfile.TemporaryDirectory() as cache:
        env = dict(os.environ, NUMBA_CACHE_DIR=cache)
        out = []
        for _ in range(2):
            r = subprocess.run([sys.executable, "-c", JIT_SNIPPET], env=env, capture_output=True, text=True, check=True)
            out.append([float(v) for v in r.stdout.split()])
    return out


def header(threads: int) -> list[str]:
    """Date, load, CPU and versions: the context every ratio of this run belongs to."""
    import numba

    cpu = platform.processor() or "?"
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    try:
        load = subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip()
    except OSError:
        load = "uptime not available: load " + " ".join(f"{v:.2f}" for v in os.getloadavg())
    flags = Path("/proc/cpuinfo").read_text() if Path("/proc/cpuinfo").exists() else ""
    simd = "AVX-512" if " avx512f" in flags else "AVX2" if " avx2" in flags else "no AVX2"
    return [f"date: {datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC",
            f"load: {load}",
            f"cpu: {cpu} ({os.cpu_count()} cores, {simd}); numba {numba.__version__}, {threads} threads; "
            f"numpy {np.__version__}; python {platform.python_version()}"]


def speed_table(B, K, Kone, repeat):
    """Rows per model (ns per trajectory-step, flops, ratios to C) and the C line, all measured in one run."""
    timers = {}
    for m in MODELS:
        for col, t in kernel_timers(m, B, K, Kone).items():
            timers[(m, col)] = t
    ct, cinfo = c_timers(B, K, Kone)
    if ct is not None:
        for col, t in ct.items():
            timers[("C", col)] = t
    best = interleaved(timers, repeat)
    return best, ct is not None, cinfo


def markdown(best, have_c, B, K, Kone):
    fmt = lambda v: "-" if v is None else f"{v:.0f}"  # noqa: E731
    rat = lambda v, c: "-" if v is None or c is None else f"{v / c:.2f}×"  # noqa: E731
    cb, co = (best[("C", "batch")], best[("C", "one")]) if have_c else (None, None)
    lines = [f"| model | batch ns | SIMD ns | one ns | flops/step (div, sincos) | batch ÷ C | SIMD ÷ C | one ÷ C | "
             "ns/flop ÷ se2r3's (batch, SIMD, one) |",
             "|---|---:|---:|---:|---:|---:|---:|---:|---:|"]
    per_flop = {}
    for m in MODELS:
        fc = step_flops(m, MEAS[m])
        per_flop[m] = [None if best.get((m, c)) is None else best[(m, c)] / fc.flops for c in ("batch", "SIMD", "one")]
    ref = per_flop.get("se2r3")
    for m in MODELS:
        b, s, o = best[(m, "batch")], best.get((m, "SIMD")), best[(m, "one")]
        fc = step_flops(m, MEAS[m])
        npf = ", ".join("-" if v is None or ref is None or r is None else f"{v / r:.2f}" for v, r in zip(per_flop[m], ref or [None] * 3))
        lines.append(f"| {m} | {fmt(b)} | {fmt(s)} | {fmt(o)} | {fc.flops} ({fc.div}, {fc.sincos}) | {rat(b, cb)} | "
                     f"{rat(s, cb)} | {rat(o, co)} | {npf} |")
    if have_c:
        lines.append(f"| C se2se2 | {fmt(cb)} | - | {fmt(co)} | | 1.00× | | 1.00× |")
    lines.append(f"\nbatch {B}×{K}, one trajectory {Kone} steps; ns per trajectory-step, best of the interleaved rounds.")
    return lines


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--quick", action="store_true", help="smaller sizes (for a smoke run)")
    ap.add_argument("--repeat", type=int, default=7, help="interleaved rounds (best of)")
    a = ap.parse_args()
    B, K = (300, 200) if a.quick else (3000, 200)
    Kone = 20000 if a.quick else 200000
    import numba

    for line in header(numba.get_num_threads()):
        print(line)
    best, have_c, cinfo = speed_table(B, K, Kone, 3 if a.quick else a.repeat)
    print(f"C baseline: {cinfo}" if have_c else f"C baseline skipped: {cinfo}")
    print()
    for line in markdown(best, have_c, B, K, Kone):
        print(line)
    print()
    rows = {m: (best[(m, "batch")], best[(m, "one")]) for m in MODELS}
    cls = {m: class_ns(m, 2000 if a.quick else 20000) for m in MODELS}
    dense = dense_ns(3 if a.quick else 10, 200)
    fp = filterpy_ns(2000 if a.quick else 20000)
    fpe = filterpy_ekf_ctrv_ns(2000 if a.quick else 20000)
    print("class API (one Python call per predict / update), ns per step: "
          + ", ".join(f"{m} {v:,.0f}" for m, v in cls.items()))
    print(f"dense numpy SE(2)xSE(2) LG-EKF: {dense:,.0f} ns/step")
    print(f"  ratio dense / generated batch   : {dense / rows['se2se2'][0]:8.0f}x")
    print(f"  ratio dense / generated single  : {dense / rows['se2se2'][1]:8.0f}x")
    if fp is not None:
        print(f"FilterPy KalmanFilter (CV): {fp:,.0f} ns/step")
        print(f"  ratio FilterPy / generated CV batch : {fp / rows['cv'][0]:8.0f}x")
        print(f"  ratio FilterPy / generated CV single: {fp / rows['cv'][1]:8.0f}x")
        print(f"FilterPy ExtendedKalmanFilter (CTRV in numpy): {fpe:,.0f} ns/step")
        print(f"  ratio FilterPy EKF / generated CTRV batch : {fpe / rows['ctrv'][0]:8.0f}x")
        print(f"  ratio FilterPy EKF / generated CTRV single: {fpe / rows['ctrv'][1]:8.0f}x")
    else:
        print("FilterPy not installed: no FilterPy comparison")
    if not a.quick or os.environ.get("BENCH_JIT"):
        (imp0, jit0), (imp1, jit1) = jit_cost()
        print(f"\nJIT, first call of every model in a fresh process: empty cache {jit0:.2f} s, warm cache {jit1:.2f} s"
              f" (import lgekf {imp0:.2f} s / {imp1:.2f} s)")


if __name__ == "__main__":
    main()
