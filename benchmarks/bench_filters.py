"""Speed of every registry model, measured in one run (ratios are only meaningful within one run).

    .venv/bin/python benchmarks/bench_filters.py [--quick]

Reports ns per predict+update step: generated kernels over a batch (3000 trajectories × 200 steps,
numba prange over trajectories, all cores), over one long trajectory (one core), through the Python
classes (one call per step), the dense-numpy SE(2)×SE(2) LG-EKF, and FilterPy's KalmanFilter /
ExtendedKalmanFilter (CV resp. CTRV written in numpy) where FilterPy is installed; then the JIT cost: the first
call in a fresh process with an empty numba cache, and with a warm cache.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

import lgekf  # noqa: E402
from dense_numpy import run_dense  # noqa: E402

# every registry model: its default noise, started at the same common state (3 m/s, ω = 0.1)
MODELS = {name: (spec.default_accel_std, lgekf.state_from_common(name, [0, 0, 0, 3, 0, 0.1]).tolist())
          for name, spec in lgekf.MODELS.items()}


def best_of(fn, repeat=3):
    best = float("inf")
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t)
    return best


def data(B, K, seed=0):
    rng = np.random.default_rng(seed)
    t = np.arange(1, K + 1) * 0.1
    truth = np.stack([3 * t, np.sin(t)], axis=-1)
    return truth[None] + 0.5 * rng.standard_normal((B, K, 2))


def kernel_ns(model, B, K):
    q, x0 = MODELS[model]
    n = len(x0)
    z = data(B, K)
    X0 = np.tile(x0, (B, 1)).astype(float)
    P0 = np.eye(n) * 0.1

    def run():
        lgekf.filter_batch(model, z, dt=0.1, accel_std=q, meas_std=0.5, x0=X0, P0=P0)

    run()
    return best_of(run) / (B * K) * 1e9


def class_ns(model, K):
    q, x0 = MODELS[model]
    n = len(x0)
    z = data(1, K)[0]
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


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--quick", action="store_true", help="smaller sizes (for a smoke run)")
    a = ap.parse_args()
    B, K = (300, 200) if a.quick else (3000, 200)
    Kone = 20000 if a.quick else 200000
    import numba

    print(f"machine: {os.cpu_count()} cores, numba threads {numba.get_num_threads()}")
    rows = {}
    for m in MODELS:
        rows[m] = (kernel_ns(m, B, K), kernel_ns(m, 1, Kone), class_ns(m, 2000 if a.quick else 20000))
    dense = dense_ns(3 if a.quick else 10, 200)
    fp = filterpy_ns(2000 if a.quick else 20000)
    fpe = filterpy_ekf_ctrv_ns(2000 if a.quick else 20000)
    print(f"\nns per predict+update step (batch {B}x{K}; single trajectory {Kone} steps; class API)")
    print(f"{'model':8} {'batch':>10} {'single':>10} {'class API':>10}")
    for m, (b, s, c) in rows.items():
        print(f"{m:8} {b:10.1f} {s:10.1f} {c:10.0f}")
    print(f"\ndense numpy SE(2)xSE(2) LG-EKF: {dense:,.0f} ns/step")
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
    (imp0, jit0), (imp1, jit1) = jit_cost()
    print(f"\nJIT, first call of every model in a fresh process: empty cache {jit0:.2f} s, warm cache {jit1:.2f} s"
          f" (import lgekf {imp0:.2f} s / {imp1:.2f} s)")


if __name__ == "__main__":
    main()
