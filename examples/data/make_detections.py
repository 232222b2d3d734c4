"""Writes examples/data/detections.csv, the README's example input: three objects seen at 10 Hz with 0.3 m position
noise (a car turning at 0.3 rad/s, a cyclist, a pedestrian), columns id, t, x, y in seconds and metres.

    python examples/data/make_detections.py
"""

from pathlib import Path

import numpy as np


def main() -> None:
    rng = np.random.default_rng(2026)
    rows = ["id,t,x,y"]
    for name, speed, turn, n in (("car", 12.0, 0.3, 80), ("cyclist", 5.0, -0.15, 80), ("pedestrian", 1.4, 0.05, 60)):
        t0 = rng.uniform(0.0, 2.0)
        psi, p = rng.uniform(-np.pi, np.pi), rng.uniform(-20.0, 20.0, 2)
        for k in range(n):
            t = t0 + 0.1 * k
            w = turn if 20 <= k < 50 else 0.0  # straight, a turn, straight
            z = p + 0.3 * rng.standard_normal(2)
            rows.append(f"{name},{t:.2f},{z[0]:.3f},{z[1]:.3f}")
            psi += w * 0.1
            p = p + speed * 0.1 * np.array([np.cos(psi), np.sin(psi)])
    (Path(__file__).resolve().parent / "detections.csv").write_text("\n".join(rows) + "\n")


if __name__ == "__main__":
    main()
