"""Which protocol changes make the paper's claims about Fig. 4 hold?  A grid of study variants.

    .venv/bin/python benchmarks/study_protocols.py [--trajectories 100]

Each row is one protocol (options of `lgekf study`), each column one claim of `lgekf.experiments.study.claims_check`
(H = holds, . = does not hold).  Nothing is tuned per claim: the variants are fixed here, in advance.
"""

from __future__ import annotations

import argparse

from lgekf.experiments.study import FILTERS, StudyConfig, claims_check, run_study

SHORT = ["LG close", "LG best", "CV good small", "CV degrades", "CTRV weak small", "CTRV approaches", "all < meas"]

VARIANTS = [
    ("default (matched noise)", {}),
    ("--noise-scale cv=3", {"noise_scale": {"cv": 3.0}}),
    ("--noise-scale cv=10", {"noise_scale": {"cv": 10.0}}),
    ("--noise-scale cv=30", {"noise_scale": {"cv": 30.0}}),
    ("--noise-scale cv=30 ctrv=3", {"noise_scale": {"cv": 30.0, "ctrv": 3.0}}),
    ("--truth se2r3 --noise-scale cv=30", {"truth": "se2r3", "noise_scale": {"cv": 30.0}}),
    ("--truth se2r3 --noise-scale cv=30 ctrv=3", {"truth": "se2r3", "noise_scale": {"cv": 30.0, "ctrv": 3.0}}),
    ("--dt 0.5 --steps 20 --noise-scale cv=30 ctrv=3", {"dt": 0.5, "steps": 20, "noise_scale": {"cv": 30.0, "ctrv": 3.0}}),
    ("--v0 1,0 --noise-scale cv=30", {"v0": (1.0, 0.0), "noise_scale": {"cv": 30.0}}),
    ("--v0 3,1 --noise-scale cv=30", {"v0": (3.0, 1.0), "noise_scale": {"cv": 30.0}}),
    ("--w0 0.5 --noise-scale cv=30", {"w0": 0.5, "noise_scale": {"cv": 30.0}}),
    ("--dt 0.05 --steps 200 --noise-scale cv=30", {"dt": 0.05, "steps": 200, "noise_scale": {"cv": 30.0}}),
    ("--dt 0.5 --steps 20 --noise-scale cv=30", {"dt": 0.5, "steps": 20, "noise_scale": {"cv": 30.0}}),
]


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--trajectories", type=int, default=100)
    a = ap.parse_args()
    print(f"{'protocol':44} " + " ".join(f"{s:>15}" for s in SHORT))
    for label, kw in VARIANTS:
        scale = {f: 1.0 for f in FILTERS}
        scale.update(kw.pop("noise_scale", {}))
        res = run_study(StudyConfig(trajectories=a.trajectories, noise_scale=scale, **kw))
        cl = claims_check(res)
        print(f"{label:44} " + " ".join(f"{'H' if c.holds else '.':>15}" for c in cl))


if __name__ == "__main__":
    main()
