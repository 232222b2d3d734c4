"""`lgekf study --multi`: GOSPA of every model × association on simulated multi-target scenarios in clutter."""

from __future__ import annotations

import csv
import io
import sys
from pathlib import Path

from ..io.output import write_atomic
from . import ArgumentParser, UsageError
from .progress import compile_notice

__all__ = ["cmd_study_multi", "study_multi_parser", "study_multi_config", "multi_rows"]


def study_multi_parser():
    from ..core.registry import MODELS
    from ..estimators.multitarget.settings import ASSOCIATIONS as ALL_ASSOCIATIONS
    from ..estimators.multitarget.settings import MARGINAL_ASSOCIATIONS as ASSOCIATIONS
    from ..experiments.clutter_scenarios import CLUTTER_SCENARIOS

    ap = ArgumentParser(prog="lgekf study --multi",
                        description="Multi-target tracking in clutter: GOSPA of every model × association on the base scenario "
                                    "(8 targets, births, deaths, crossings, close parallel targets).")
    ap.add_argument("--multi", action="store_true", required=True, help="the multi-target study")
    ap.add_argument("--out", type=Path, default=Path("results"), help="results folder (default results/): multi_gospa.csv")
    ap.add_argument("--models", default=",".join(MODELS), metavar="LIST",
                    help=f"models (default all: {','.join(MODELS)}); imm: an IMM of --imm-modes per track")
    ap.add_argument("--imm-modes", default=None, metavar="LIST",
                    help="with imm in --models: its modes (default those of lgekf track --model imm, "
                         "cv,se2r3:calm,se2r3:manoeuvre)")
    ap.add_argument("--association", default=",".join(ASSOCIATIONS), metavar="LIST",
                    help=f"associations of {','.join(ALL_ASSOCIATIONS)} (default {','.join(ASSOCIATIONS)})")
    ap.add_argument("--initiation", default=None, metavar="LIST",
                    help="track initiations to compare, one-point,two-point (default: the tracker's default for each "
                         "association, one-point with jpda, gnn and pmbm, two-point with pda; pmbm is one-point only)")
    ap.add_argument("--runs", type=int, default=5, help="Monte Carlo runs (default 5)")
    ap.add_argument("--seed", type=int, default=2016, help="seed of the first run (default 2016)")
    ap.add_argument("--detection-prob", type=float, default=0.9, help="P_D (default 0.9)")
    ap.add_argument("--clutter-density", type=float, default=1e-4,
                    help="false alarms per m² per scan (default 1e-4: 4 per scan; with --scenario burst|patch the background)")
    ap.add_argument("--scenario", default="base", choices=list(CLUTTER_SCENARIOS),
                    help="the base scenario's clutter: base = uniform and constant, burst = 1.5e-3 more from 8 to 13 s, "
                         "patch = 1.25e-2 more in 40 m x 40 m around (0, 5) (default base; docs/multi_target.md)")
    ap.add_argument("--clutter", default="true", metavar="LIST",
                    help="the clutter densities the tracker gets, one cell each: true (the true mean, a constant), file (the "
                         "per-file estimate), scan (estimated per scan), map (a clutter map), oracle (the true density at "
                         "each detection) (default true)")
    ap.add_argument("--meas-std", type=float, default=0.3, help="measurement std in m (default 0.3)")
    ap.add_argument("--noise", default="default", choices=["default", "data"],
                    help="the trackers' process noise: the models' defaults, or estimated from each run's detections as "
                         "lgekf track --multi does (the measurement std stays --meas-std) (default: default)")
    ap.add_argument("--dt", type=float, default=0.1, help="scan interval in s (default 0.1)")
    ap.add_argument("--duration", type=float, default=20.0, help="scenario length in s (default 20)")
    ap.add_argument("--gospa-c", type=float, default=5.0, help="GOSPA cut-off c in m (default 5)")
    ap.add_argument("--gospa-p", type=float, default=2.0, help="GOSPA order p (default 2)")
    ap.add_argument("--measure", default="position", choices=["position", "pose"],
                    help="position or pose detections (heading noise --heading-std; models without a heading get the positions)")
    ap.add_argument("--heading-std", type=float, default=0.05, help="pose: heading noise std in rad (default 0.05)")
    ap.add_argument("--max-speed", type=float, default=30.0, help="largest speed of a new track in m/s (default 30)")
    ap.add_argument("--dataset", default=None, metavar="NAME",
                    help="real trajectories of `lgekf evaluate` (eth, hotel, zara1, zara2, univ, ...) as detection streams "
                         "(truth + noise + misses + clutter) instead of the simulated scenario")
    ap.add_argument("--scans", type=int, default=None, metavar="N",
                    help="with --dataset: only the first N scans of every stream (default all)")
    ap.add_argument("--data-root", default=None, help="folder of the datasets (default $LGEKF_DATA, else ../shared/data)")
    ap.add_argument("--quiet", action="store_true", help="print only the output file")
    return ap


def _names(option, text, allowed):
    names = [v.strip() for v in str(text).split(",") if v.strip()]
    bad = [v for v in names if v not in allowed]
    if bad or not names:
        raise UsageError(f"{option}: unknown name {bad[0] if bad else text!r}; choose from {', '.join(allowed)}")
    return tuple(dict.fromkeys(names))


def study_multi_config(a):
    """The study's protocol (``MultiStudyConfig``, validated) from the parsed options of ``study_multi_parser``."""
    from ..core.registry import MODELS
    from ..estimators.multitarget.settings import ASSOCIATIONS, INITIATIONS
    from ..estimators.multitarget.tracker import IMM_MODEL
    from ..experiments.clutter_scenarios import STUDY_CLUTTERS
    from ..experiments.multi_study import MultiStudyConfig

    return MultiStudyConfig(models=_names("--models", a.models, [*MODELS, IMM_MODEL]), imm_modes=a.imm_modes,
                            associations=_names("--association", a.association, list(ASSOCIATIONS)),
                            initiations=(None,) if a.initiation is None else _names("--initiation", a.initiation,
                                                                                    list(INITIATIONS)),
                            runs=a.runs, seed=a.seed, dt=a.dt, duration=a.duration, detection_prob=a.detection_prob,
                            clutter_density=a.clutter_density, meas_std=a.meas_std, c=a.gospa_c, p=a.gospa_p,
                            dataset=a.dataset, data_root=a.data_root, max_speed=a.max_speed,
                            measurement=a.measure, heading_std=a.heading_std, scenario=a.scenario,
                            clutters=_names("--clutter", a.clutter, list(STUDY_CLUTTERS)), noise=a.noise,
                            scans=a.scans).validate()


def multi_rows(cells) -> list:
    """The rows of multi_gospa.csv (``MULTI_COLUMNS``): the means, then the runs and the half-widths of the 95 %
    t-intervals over them (empty for a single run), switches per run."""
    def half(c, part):
        h = c.interval(part)[1]
        return "" if h != h else f"{h:.6g}"

    return [[c.model, c.association, c.initiation, c.clutter, f"{c.gospa:.6g}", f"{c.localisation:.6g}",
             f"{c.missed:.6g}", f"{c.false:.6g}", c.switches, f"{c.scans_per_s:.4g}", c.accel_std, len(c.per_run),
             half(c, "gospa"), half(c, "localisation"), half(c, "missed"), half(c, "false"),
             f"{c.interval('switches')[0]:.6g}", half(c, "switches")] for c in cells]


def cmd_study_multi(argv) -> int:
    from ..experiments.multi_study import MULTI_COLUMNS, format_multi_table, run_multi_study

    a = study_multi_parser().parse_args(argv)
    cfg = study_multi_config(a)
    say = (lambda s: None) if a.quiet else (lambda s: print(s, file=sys.stderr))
    with compile_notice("lgekf study", enabled=not a.quiet):
        fit = None
        if cfg.noise == "data":
            from ..apps.track_multi import study_process_noise as fit
        cells = run_multi_study(cfg, noise_fit=fit, progress=lambda c: say(
            f"  {c.model} {c.association} {c.initiation} {c.clutter}: GOSPA {c.gospa:.3f}"
            + (f" (accel-std {c.accel_std})" if cfg.noise == "data" else "")))
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(MULTI_COLUMNS)
    w.writerows(multi_rows(cells))
    a.out.mkdir(parents=True, exist_ok=True)
    path = a.out / "multi_gospa.csv"
    write_atomic(path, buf.getvalue())
    if not a.quiet:
        print(format_multi_table(cells, cfg))
    print(path)
    return 0
