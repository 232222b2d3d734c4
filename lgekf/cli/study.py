"""`lgekf study`: the paper's Monte Carlo study (Fig. 4) with its claims check."""

from __future__ import annotations

import csv
import io
import json
import platform
import time
from pathlib import Path

from ..io.output import staged_directory, write_atomic
from . import ArgumentParser, UsageError
from .progress import compile_notice, progress_bar, stderr_is_terminal

__all__ = ["cmd_study", "study_parser", "format_table"]


def _floats(name, text, n=None):
    try:
        vals = [float(v) for v in str(text).split(",") if v.strip() != ""]
    except ValueError:
        raise UsageError(f"{name}: expected comma-separated numbers, got {text!r}") from None
    if n is not None and len(vals) != n:
        raise UsageError(f"{name}: expected {n} comma-separated numbers, got {text!r}")
    return vals


def parse_sigmas(text: str):
    """"a:b:n" (n equidistant values, numpy.linspace) or a comma-separated list."""
    import numpy as np

    if ":" in text:
        parts = text.split(":")
        if len(parts) != 3:
            raise UsageError(f"--sigmas: expected START:STOP:COUNT or a list, got {text!r}")
        try:
            a, b, n = float(parts[0]), float(parts[1]), int(parts[2])
        except ValueError:
            raise UsageError(f"--sigmas: expected START:STOP:COUNT, got {text!r}") from None
        if n < 1:
            raise UsageError("--sigmas: COUNT must be at least 1")
        return np.linspace(a, b, n).tolist()
    return _floats("--sigmas", text)


def study_parser():
    ap = ArgumentParser(prog="lgekf study", description="Run the paper's Monte Carlo study (Fig. 4) and check its claims.")
    ap.add_argument("--out", type=Path, default=Path("results"), help="results folder (default: results/)")
    ap.add_argument("--trajectories", type=int, default=100, help="trajectories per σ_ω (default 100)")
    ap.add_argument("--sigmas", default="0:3:30", help="σ_ω values: START:STOP:COUNT (linspace) or a list (default 0:3:30)")
    ap.add_argument("--seed", type=int, default=2016, help="random seed (default 2016)")
    ap.add_argument("--dt", type=float, default=0.1, help="sampling period T in s (default 0.1)")
    ap.add_argument("--steps", type=int, default=100, help="measurements per trajectory (default 100)")
    ap.add_argument("--space", default=None, metavar="2d|3d",
                    help="the space of motion: 2d (the paper's plane, default) or 3d (the protocol lifted to SE(3): "
                         "truth se3r6, filters se3r6, se3se3, ct3, cv3, 3-D position measurements)")
    ap.add_argument("--v0", default=None, help="initial body velocity v_x,v_y (3d: v_x,v_y,v_z) in m/s (default 3,0 / 3,0,0)")
    ap.add_argument("--w0", default=None, help="initial angular velocity in rad/s (3d: ω_x,ω_y,ω_z) (default 0)")
    ap.add_argument("--sigma-v", type=float, default=0.1, help="std of n_x, n_y (default 0.1)")
    ap.add_argument("--meas-std", type=float, default=0.5, help="measurement noise std per axis in m (default 0.5)")
    from ..experiments.simulate import truth_models
    from ..core.registry import ALL_MEASUREMENTS, MODELS

    from ..core.registry import SPACES

    truths = [t for sp_ in SPACES for t in truth_models(sp_)]
    ap.add_argument("--truth", default=None, choices=truths, help="truth motion model (default se2se2; 3d: se3r6, or se3se3)")
    ap.add_argument("--filters", default=None, metavar="LIST",
                    help=f"comma-separated filters to run (default: all of the space, {','.join(MODELS)})")
    ap.add_argument("--measure", default=None, choices=list(ALL_MEASUREMENTS),
                    help="measurement model: position (x, y) or pose (x, y, θ) in SE(2); filters without a heading (CV) get the position part")
    ap.add_argument("--heading-std", type=float, default=0.1, help="pose measurements: std of the heading noise in rad (default 0.1)")
    ap.add_argument(
        "--noise-scale", action="extend", nargs="+", default=[], metavar="FILTER=K",
        help="multiply a filter's process-noise stds by K; several after one flag or the flag repeated, e.g. --noise-scale cv=30 ctrv=3",
    )
    ap.add_argument("--imm-modes", default=None, metavar="LIST",
                    help="modes of the imm filter (with --filters ...,imm): MODEL[:calm|manoeuvre|a/b/c],... (default cv,se2r3)")
    ap.add_argument("--imm-switch", type=float, default=None, metavar="P",
                    help="imm: a fixed probability of leaving a mode per step (default: the transition matrix is "
                         "learned at each σ_ω on training trajectories)")
    ap.add_argument("--imm-train", type=int, default=None, metavar="N",
                    help="imm: training trajectories per σ_ω for the learned transition matrix (default 100)")
    ap.add_argument("--no-figure", action="store_true", help="skip study.png")
    ap.add_argument("--pdf", action="store_true", help="also write study.pdf")
    ap.add_argument("--quiet", action="store_true", help="print only the output folder")
    ap.add_argument("--multi", action="store_true", help="the multi-target study in clutter instead (see `lgekf study --multi --help`)")
    return ap


def config_from_args(a):
    from ..core.registry import DEFAULT_SPACE, SPACES, models_of, rotation_dims
    from ..experiments.study import StudyConfig

    space = DEFAULT_SPACE if a.space is None else a.space.lower()
    if space not in SPACES:
        raise UsageError(f"--space: unknown space {a.space!r}; choose one of {', '.join(SPACES)}")
    base = StudyConfig.for_space(space)
    own = models_of(space)
    scale = dict(base.noise_scale)
    for item in a.noise_scale:
        if "=" not in item:
            raise UsageError(f"--noise-scale: expected FILTER=K, got {item!r}")
        k, v = item.split("=", 1)
        if k not in own:
            raise UsageError(f"--noise-scale: unknown filter {k!r}; choose one of {', '.join(own)}")
        scale[k] = _floats("--noise-scale", v, 1)[0]
    dim = SPACES[space]["dim"]
    rot = rotation_dims(space)
    v0 = base.v0 if a.v0 is None else tuple(_floats("--v0", a.v0, dim))
    if a.w0 is None:
        w0 = base.w0
    else:
        w = _floats("--w0", a.w0, rot)
        w0 = w[0] if space == DEFAULT_SPACE else tuple(w)
    cfg = StudyConfig.for_space(
        space, dt=a.dt, steps=a.steps, trajectories=a.trajectories, sigmas=parse_sigmas(a.sigmas),
        v0=v0, w0=w0, sigma_v=a.sigma_v, meas_std=a.meas_std,
        truth=base.truth if a.truth is None else a.truth, seed=a.seed, noise_scale=scale,
        filters=base.filters if a.filters is None else _filter_list(a.filters, own),
        measurement=base.measurement if a.measure is None else a.measure, heading_std=a.heading_std,
    )
    cfg.validate()
    return cfg


def _filter_list(text, own=None):
    from ..core.registry import MODELS, SPACES

    own = MODELS if own is None else own
    imm = ["imm"] if SPACES[next(iter(own.values())).space]["mixes"] else []
    names = [v.strip() for v in str(text).split(",") if v.strip()]
    bad = [v for v in names if v not in own and v not in imm]
    if bad or not names:
        raise UsageError(f"--filters: unknown filter {bad[0] if bad else text!r}; choose from {', '.join([*own, *imm])}")
    return tuple(dict.fromkeys(names))


def format_table(res) -> str:
    names = (*res.filters, "measurements")
    lines = ["σ_ω     " + "".join(f"{n:>16}" for n in names)]
    for i, s in enumerate(res.sigmas):
        row = "".join(f"{res.mean(n)[i]:8.3f}±{res.std(n)[i]:<7.3f}" for n in names)
        lines.append(f"{s:6.3f}  {row}")
    return "\n".join(lines)


def cmd_study(argv) -> int:
    if "--multi" in argv:  # multi-target tracking in clutter: lgekf.cli.study_multi
        from .study_multi import cmd_study_multi

        return cmd_study_multi(argv)
    from .. import __version__
    from ..core.registry import get_measurement
    from ..core.registry import SPACES
    from ..experiments.study import claims_check, config_dict, paper_names, run_study

    a = study_parser().parse_args(argv)
    cfg = config_from_args(a)
    from ..experiments.imm_study import imm_options_from_args, imm_options_record

    if a.imm_train is not None and "imm" not in cfg.filters:
        raise UsageError("--imm-train: only with imm in --filters")
    if a.imm_train is not None and a.imm_switch is not None:
        raise UsageError("--imm-train: only for the learned chain, not with --imm-switch")
    imm = imm_options_from_args(a.imm_modes, a.imm_switch, a.imm_train, cfg.space)
    if "imm" in cfg.filters:
        imm.validate(cfg.steps)  # the training draws' size, before any compile or draw
    t0 = time.perf_counter()
    from .warmup import compile_estimate, study_jobs, warm_up

    jobs = study_jobs(cfg)
    with compile_notice("lgekf study", enabled=not a.quiet, seconds=compile_estimate(j.cost for j in jobs)):
        warm_up(jobs)  # a cold cache: the kernels compile in parallel processes; warm: milliseconds
        with progress_bar(len(cfg.sigmas), "lgekf study", not a.quiet and stderr_is_terminal(), unit="σ_ω") as bar:
            try:
                res = run_study(cfg, progress=lambda done, total: bar.update(1), imm=imm)
            except MemoryError:
                raise ValueError("lgekf study: out of memory; give fewer --trajectories, --steps or --imm-train") from None
    claims = claims_check(res)
    out = a.out
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(["sigma_w", "filter", "mean_rmse", "std_rmse", "n"])
    for s, name, m, sd, n in res.summary_rows():
        w.writerow([f"{s:.6g}", name, f"{m:.6f}", f"{sd:.6f}", n])
    summary = buf.getvalue()
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(["sigma_w", "trajectory", "filter", "rmse"])
    for name, arr in res.rmse.items():
        for i, s in enumerate(res.sigmas):
            for b, v in enumerate(arr[i]):
                w.writerow([f"{s:.6g}", b, name, f"{v:.6f}"])
    rmse_csv = buf.getvalue()
    import numba
    import numpy

    meta = {
        "protocol": config_dict(cfg),
        "wrapped_trajectories_per_sigma": {f"{s:.6g}": int(k) for s, k in zip(res.sigmas, res.wrapped)},
        "aliased_trajectories": {name: int(c.sum()) for name, c in res.aliased.items()},
        "filter_measurements": {f: cfg.filter_measurement(f) for f in res.filters},
        **({"imm": {**imm_options_record(imm), **({"chains": res.imm_chains} if res.imm_chains else {})}}
           if "imm" in res.filters else {}),
        "claims": [{"claim": c.text, "holds": c.holds, "evidence": c.evidence} for c in claims],
        "compute_seconds": round(res.compute_seconds, 4),
        "wall_seconds": None,
        "versions": {"lgekf": __version__, "numpy": numpy.__version__, "numba": numba.__version__, "python": platform.python_version()},
        "notes": [
            "P0 of each filter = J P0_phys J^T with J the Jacobian of its coordinates w.r.t. the common coordinates "
            f"({', '.join(SPACES[cfg.space]['common_names'])}) at the initial estimate",
            "common random numbers: the same standard-normal draws for every sigma_w and every filter",
            "SE(2)xSE(2) truth: omega is the angle of T_d and wraps at +-pi; see wrapped_trajectories_per_sigma",
        ],
    }
    with staged_directory(out) as stage:
        write_atomic(stage / "summary.csv", summary)
        write_atomic(stage / "rmse.csv", rmse_csv)
        if not a.no_figure:
            from ..experiments.figures import study_figure

            study_figure(res, stage / "study.png", pdf=a.pdf)
        meta["wall_seconds"] = round(time.perf_counter() - t0, 3)
        write_atomic(stage / "meta.json", json.dumps(meta, indent=2) + "\n")
    if a.quiet:
        print(out)
        return 0
    print(format_table(res))
    print(f"\ntrajectories whose ω wrapped at ±π: {int(res.wrapped.sum())} of {res.wrapped.size * cfg.trajectories}")
    for name, counts in res.aliased.items():
        if counts.sum():
            print(f"trajectories the {name} filter cannot represent (its estimate aliases): {int(counts.sum())} of {counts.size * cfg.trajectories}")
    if get_measurement(cfg.measurement).has_angle:
        pos_only = [f for f in res.filters if cfg.filter_measurement(f) != cfg.measurement]
        print(f"measurements: {cfg.measurement} (heading std {cfg.heading_std} rad)"
              + (f"; {', '.join(pos_only)} got the position part only (no heading)" if pos_only else ""))
    names = paper_names(res.filters)
    lifted = {k: f for k, f in names.items() if k != f}
    print("\nclaims of the paper about Fig. 4 under this protocol"
          + (f" (in {cfg.space}: {', '.join(f'{f} stands for {k}' for k, f in lifted.items())}):" if lifted else ":"))
    for c in claims:
        print(f"  [{'holds' if c.holds else 'does not hold'}] {c.text}: {c.evidence}")
    print(f"\nwrote {out}/summary.csv, rmse.csv, meta.json{'' if a.no_figure else ', study.png'}  "
          f"(compute {res.compute_seconds:.2f} s, wall {meta['wall_seconds']:.2f} s)")
    return 0
