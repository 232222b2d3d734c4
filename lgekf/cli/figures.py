"""`lgekf figures`: the paper's Fig. 1/2 (banana-shaped uncertainty) and Fig. 3 (example tracks)."""

from __future__ import annotations

from pathlib import Path

from ..io.output import staged_directory
from . import ArgumentParser
from .progress import compile_notice

__all__ = ["cmd_figures"]


def cmd_figures(argv) -> int:
    from ..experiments.figures import banana_figure, trajectories_figure

    ap = ArgumentParser(prog="lgekf figures", description="Reproduce the paper's Fig. 1/2 (banana-shaped uncertainty) and Fig. 3 (example tracks).")
    ap.add_argument("--out", type=Path, default=Path("figures"), help="output folder (default: figures/)")
    ap.add_argument("--pdf", action="store_true", help="also write PDF files")
    a = ap.parse_args(argv)
    with staged_directory(a.out) as stage, compile_notice("lgekf figures"):
        written = banana_figure(stage / "fig2_banana.png", pdf=a.pdf)
        written += trajectories_figure(stage / "fig3_trajectories.png", pdf=a.pdf)
    for p in written:
        print(a.out / p.name)
    print("Fig. 4 is written by `lgekf study` (study.png)")
    return 0
