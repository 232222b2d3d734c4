"""Cost of the study's learned IMM chain, measured in one run (ratios only; absolute times are noisy).

    .venv/bin/python benchmarks/bench_imm_chain.py [--sigmas N]

``run_study`` with the filter set (CV, SE(2)×R³, IMM) on the default protocol (100 trajectories of 100 steps),
once with the IMM's chain learned at each σ_ω (the default: ``learn_chain`` on 100 training trajectories per σ_ω)
and once with the fixed switching probability DEFAULT_STUDY_SWITCH (0.002); prints the time ratio learned / fixed and the likelihood
evaluations per fit. A warm-up run of both first (compilation not counted).
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from lgekf.experiments.imm_study import DEFAULT_STUDY_SWITCH, ImmStudyOptions
from lgekf.experiments.study import StudyConfig, run_study


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--sigmas", type=int, default=10, help="σ_ω values, numpy.linspace(0, 3, N) (default 10)")
    a = ap.parse_args()
    cfg = StudyConfig(sigmas=np.linspace(0.0, 3.0, a.sigmas).tolist(), filters=("cv", "se2r3", "imm"))
    small = StudyConfig(sigmas=[0.5], trajectories=4, steps=10, filters=cfg.filters)
    for opts in (ImmStudyOptions(), ImmStudyOptions(switch=DEFAULT_STUDY_SWITCH)):
        run_study(small, imm=opts)
    t = time.perf_counter()
    res = run_study(cfg, imm=ImmStudyOptions())
    learned = time.perf_counter() - t
    t = time.perf_counter()
    run_study(cfg, imm=ImmStudyOptions(switch=DEFAULT_STUDY_SWITCH))
    fixed = time.perf_counter() - t
    evals = [c["n_evals"] for c in res.imm_chains]
    print(f"{a.sigmas} σ_ω, filters cv, se2r3, imm: learned chain / fixed chain = {learned / fixed:.1f}x "
          f"({learned:.1f} s / {fixed:.1f} s in this run); {np.mean(evals):.0f} likelihood runs per fit "
          f"({min(evals)}–{max(evals)})")


if __name__ == "__main__":
    main()
