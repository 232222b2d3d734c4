"""EM (lgekf.estimators.noise.em.learn_noise_em) against the likelihood optimiser (learn_noise, L-BFGS-B + Nelder–Mead)
for the CV model on real data: learned (σ_a, r), log-likelihood, EM iterations, and the time ratios EM / L-BFGS
measured in one run (this machine is shared: ratios only). EM runs its kernels on one numba thread below
``SINGLE_THREAD_CELLS`` track steps; the optimiser is timed as it runs (its likelihood kernel in parallel) and on
one thread too.

Usage: .venv/bin/python benchmarks/em_vs_lbfgs.py [--data-root DIR] [preset ...]   (default: zara1 hotel kitti)

The measurements are the datasets' positions as given (their own noise), both σ_a and r learned; each track
starts from its first two measurements ≥ 1 s apart, as in ``lgekf track --tune``.
"""

from __future__ import annotations

import argparse
import time

from lgekf.estimators.noise.em import EMTrace, _numba_threads, learn_noise_em
from lgekf.estimators.noise.tracks import batch_tracks
from lgekf.estimators.noise.tuning import learn_noise
from lgekf.io.datasets import load_dataset


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("presets", nargs="*", default=["zara1", "hotel", "kitti"])
    ap.add_argument("--data-root", default="/work/shared/data")
    a = ap.parse_args()
    for name in a.presets:
        ds = load_dataset(name, root=a.data_root)
        tracks = [(ds.t[s:e], ds.p[s:e]) for s, e in zip(ds.starts[:-1], ds.starts[1:])]
        batch = batch_tracks(tracks, 2, None, 1.0)
        learn_noise_em("cv", batch, hessian=False, max_iter=2)  # compile/warm both paths outside the timing
        learn_noise("cv", batch, n_starts=1, hessian=False)
        t0 = time.perf_counter()
        ref = learn_noise("cv", batch)
        t_lbfgs = time.perf_counter() - t0
        tr = EMTrace()
        t0 = time.perf_counter()
        em = learn_noise_em("cv", batch, trace=tr)
        t_em = time.perf_counter() - t0
        plain = EMTrace()
        t0 = time.perf_counter()
        learn_noise_em("cv", batch, trace=plain, accelerate=False)
        t_plain = time.perf_counter() - t0
        t0 = time.perf_counter()
        with _numba_threads(1):  # the optimiser with the likelihood kernel on one thread too, as EM runs here
            learn_noise("cv", batch)
        t_lbfgs1 = time.perf_counter() - t0
        print(f"{name}: {batch.z.shape[0]} tracks, {batch.n_updates} updates")
        print(f"  L-BFGS: sigma_a = {ref.values[0]:.5g}, r = {ref.values[1]:.5g}, log L = {ref.loglik:.6f}"
              f" {'identified' if ref.identified else ref.problems}")
        print(f"  EM    : sigma_a = {em.values[0]:.5g}, r = {em.values[1]:.5g}, log L = {em.loglik:.6f}"
              f" ({tr.e_steps} E-steps with SQUAREM, {plain.e_steps} plain; converged {tr.converged})"
              f" {'identified' if em.identified else em.problems}")
        print(f"  log L (EM − L-BFGS) = {em.loglik - ref.loglik:+.2e}; time EM / L-BFGS = {t_em / t_lbfgs:.2f}, "
              f"EM / L-BFGS on one thread = {t_em / t_lbfgs1:.2f}, plain EM / L-BFGS on one thread = {t_plain / t_lbfgs1:.2f}"
              f" (all with the Hessian interval)")


if __name__ == "__main__":
    main()
