"""The one parser of `lgekf track`, its options in groups (input, model and noise, IMM, multi-target, output, Dask),
and the rule that an estimator's own options are refused with another (one line, exit 2).

Every estimator (``--model MODEL|all``, ``--model imm``, ``--multi``) is read from this parser; the options of one
estimator given to another are errors, not silently ignored: ``check_estimator_options``.
"""

from __future__ import annotations

from ..apps.track import DEFAULT_HEADING_STD, DEFAULT_MODELS, DEFAULT_OMEGA_STD
from ..apps.track_dask import PARTITION_ROWS
from ..core.registry import ALL_MEASUREMENTS, ALL_MODELS, BASE_MEASUREMENT, MEASUREMENTS, MODELS, models_of
from ..estimators.multitarget.clutter import CLUTTER_SOURCES, DEFAULT_CLUTTER_SOURCE
from ..estimators.multitarget.settings import (ASSOCIATIONS, BIRTH_EXISTENCE, DEFAULT_INITIATION, INITIATIONS,
                                              PMBM_DEFAULTS, SPEED_STD_FRACTION)
from ..io.readers import COLUMN_OPTIONS
from ..io.units import TIME_UNITS
from . import ArgumentParser
from .cluster import add_cluster_options

__all__ = ["track_parser", "add_column_options", "column_names", "check_estimator_options", "check_imm_options",
           "MULTI_DEFAULTS", "DEFAULT_MAX_SPEED", "SPEED_WARN_FRACTION"]

SPEED_WARN_FRACTION = 0.8  # --multi: a confirmed track this close to the default --max-speed is warned about
DEFAULT_MAX_SPEED = 30.0  # m/s
# the multi-target options (their parser default is None, so that "given" can be told from "default")
# (--initiation and --birth-existence stay None when not given: their defaults depend on --association and
# --initiation, and the tracker fills them in)
MULTI_DEFAULTS = {"association": "jpda", "detection_prob": 0.9, "gate_prob": 0.99, "survival_prob": 0.99,
                  "confirm_existence": 0.9, "delete_existence": 0.01}
MULTI_ONLY = ("association", "initiation", "detection_prob", "clutter_density", "clutter", "gate_prob", "survival_prob",
              "birth_existence", "birth_density", "confirm_existence", "delete_existence", "max_speed", "scan_window",
              "max_hypotheses", "hypothesis_prune")
# options of the labelled-object estimators that --multi does not take: (attribute, its default, the option's name)
SINGLE_ONLY = (("format", "csv", "--format"), ("frame_dt", None, "--frame-dt"), ("id_column", None, "--id-column"),
               ("use_heading", False, "--use-heading"), ("heading_unit", None, "--heading-unit"),
               ("full_cov", False, "--full-cov"), ("tune", False, "--tune"), ("tune_method", "lbfgs", "--tune-method"),
               ("smooth", False, "--smooth"),
               ("workers", None, "--workers"), ("scheduler", None, "--scheduler"),
               ("partition_rows", PARTITION_ROWS, "--partition-rows"))

COLUMN_HELP = {
    "id": "the column of object ids (default: id, track_id or object_id)",
    "t": "the time column (default: t, time or timestamp); numbers (seconds, or --time-unit) or ISO-8601 date-times",
    "x": "the x column in m (default: x)",
    "y": "the y column in m (default: y)",
    "z": "the z column in m, up (default: z; or alt/altitude beside lat, lon): a file with one holds 3-D positions",
    "heading": "the heading column (default: heading or yaw)",
}


def add_column_options(ap, keys=tuple(COLUMN_OPTIONS)) -> None:
    """``--id-column NAME`` ... (``readers.COLUMN_OPTIONS``): a column of another name taken for that key instead of
    the automatic aliases."""
    for k in keys:
        ap.add_argument(COLUMN_OPTIONS[k], default=None, metavar="NAME", help=COLUMN_HELP[k])


def column_names(a) -> dict:
    """{key: NAME} of the column options given (``readers.named_columns``'s argument)."""
    return {k: getattr(a, opt[2:].replace("-", "_"), None) for k, opt in COLUMN_OPTIONS.items()
            if getattr(a, opt[2:].replace("-", "_"), None) is not None}


def track_parser():
    ap = ArgumentParser(
        prog="lgekf track",
        description="Track every object of a measurement file with an LG-EKF (SE(2)xSE(2), SE(2)xR3, SE(2)xR2), a "
                    "CTRV-EKF, a CV-KF or an IMM of them; or, with --multi, many objects from unlabelled detections in "
                    "clutter. The noise comes from the data unless given; see docs/track.md and docs/track_multi.md.",
    )
    ap.add_argument("input", help="measurements: CSV with header t,x,y[,id][,heading] (or t,lat,lon,...), the pedestrian "
                    "format, or Parquet; - reads stdin; gzip input is recognised")
    ap.add_argument("-o", "--output", required=True,
                    help="output CSV (or .parquet); - writes to stdout; a name ending in .gz is gzip-compressed "
                         "(with --model all: one file per model, OUTPUT_<model>.csv)")

    g = ap.add_argument_group("input")
    g.add_argument("--format", default="csv", choices=["csv", "pedestrian"], help="input format (default csv)")
    g.add_argument("--frame-dt", type=float, default=None, help="pedestrian format: seconds per frame unit (t = frame * frame_dt)")
    g.add_argument("--time-unit", default="s", choices=list(TIME_UNITS), help="unit of the CSV's t column, converted to seconds (default s)")
    g.add_argument("--delimiter", default=None, metavar="CHAR",
                   help="CSV separator: one character, tab or space (default: found from the header: , ; tab | or spaces)")
    add_column_options(g)
    g.add_argument("--sort", action="store_true",
                   help="sort the rows by time first (each object's; --multi: all rows, stably) and say how many moved; "
                        "without it rows out of time order are refused")
    g.add_argument("--skip-invalid", action="store_true",
                   help="drop what no filter can take, with one line per reason: rows with NaN/inf, a time not after the "
                        "object's previous row (duplicates), objects left with a single row; without it they are refused")
    g.add_argument("--heading-unit", choices=["rad", "deg"], default=None,
                   help="unit of the heading column (default rad, but values beyond ±2π that follow the direction of "
                        "motion as degrees, not as radians, are refused: give deg)")
    g.add_argument("--use-heading", action="store_true", help="initialise the heading from the 'heading' column (rad)")

    g = ap.add_argument_group("model and noise")
    g.add_argument("--model", default=None, choices=[*ALL_MODELS, "all", "imm"],
                   help="filter (default se2se2 on x, y; on 3-D positions (a z or alt column) ct3, or se3r6 with --measure "
                        "pose (roll, pitch, yaw); the models of the "
                        "plane: " + ", ".join(MODELS) + "; of 3-D space: " + ", ".join(models_of("3d")) + "); all: one "
                        "output per model of the input's space; imm: an IMM of --imm-modes (plane)")
    g.add_argument("--measure", default=BASE_MEASUREMENT, choices=list(ALL_MEASUREMENTS),
                   help=f"measurement model (default {BASE_MEASUREMENT}): "
                   + "; ".join(f"{m}: {s.description}" for m, s in MEASUREMENTS.items())
                   + " (angles from the heading column; noise: --meas-std for positions, --heading-std for angles); "
                   "on 3-D positions position and pose are position3 and pose3 (the attitude from roll, pitch, yaw columns)")
    g.add_argument("--meas-std", type=float, default=None,
                   help="measurement std per axis in m (default: estimated from the data, local quadratic residuals; printed)")
    g.add_argument("--accel-std", action="append", default=[], metavar="[MODEL=]LIST",
                   help="process noise stds (" + "; ".join(f"{m}: {','.join(s.noise_names)}" for m, s in MODELS.items())
                   + "); repeatable MODEL=LIST (default: from the data, see docs/track.md)")
    g.add_argument("--omega-std", type=float, default=DEFAULT_OMEGA_STD,
                   help=f"initial angular-velocity std in rad/s (default {DEFAULT_OMEGA_STD})")
    g.add_argument("--heading-std", type=float, default=None,
                   help=f"std of the heading column (3-D: of each of roll, pitch, yaw) in rad (default {DEFAULT_HEADING_STD})")
    g.add_argument("--tune", action="store_true",
                   help="learn each model's process noise (and the measurement std unless --meas-std) by maximum likelihood "
                        "on the file's own tracks (per class of objects), print it with 95 %% intervals, then track with it")
    g.add_argument("--tune-method", choices=["lbfgs", "em"], default="lbfgs",
                   help="with --tune: lbfgs = the likelihood optimiser (default), em = expectation-maximisation for the "
                        "linear Gaussian models (cv), the optimiser for the others")

    g = ap.add_argument_group("IMM (--model imm; with --multi an IMM per track)")
    g.add_argument("--imm-modes", default=None, metavar="LIST",
                   help="modes MODEL[:calm|manoeuvre|a/b/c],... (default cv,se2r3:calm,se2r3:manoeuvre; with --multi at "
                        "least two)")
    g.add_argument("--imm-switch", type=float, default=None, metavar="P",
                   help="probability of leaving a mode per step (per scan with --multi; default 0.05)")

    g = ap.add_argument_group("multi-target tracking (--multi: unlabelled detections with clutter and misses)")
    g.add_argument("--multi", action="store_true",
                   help="track many objects from unlabelled detections (JPDA/JPDA*/PDA/GNN with integrated track existence; an "
                        "id column is ignored); see docs/track_multi.md")
    g.add_argument("--association", default=None, choices=list(ASSOCIATIONS),
                   help="jpda (joint, exact up to 5000 events per cluster, loopy belief propagation beyond), jpdastar (JPDA* "
                        "with the best of permuted events only: close tracks do not coalesce), pda, gnn or "
                        "pmbm (Poisson multi-Bernoulli mixture: multiple hypotheses by Murty's k best assignments, births "
                        f"from its Poisson part) (default {MULTI_DEFAULTS['association']})")
    g.add_argument("--initiation", default=None, choices=list(INITIATIONS),
                   help="how tracks start: one-point = a tentative track from every detection no track claims, velocity "
                        "0 +- --max-speed/3 per axis, confirmed by its existence probability; two-point = from two "
                        "detections of consecutive scans within --max-speed (default: "
                        + "; ".join(f"{i} with {', '.join(k for k, v in DEFAULT_INITIATION.items() if v == i)}"
                                    for i in INITIATIONS) + ", as measured in docs/multi_target.md)")
    g.add_argument("--detection-prob", type=float, default=None,
                   help=f"probability of detecting an object in a scan (default {MULTI_DEFAULTS['detection_prob']})")
    g.add_argument("--clutter-density", type=float, default=None,
                   help="expected false alarms per m² (per m³ on 3-D detections) per scan, the same everywhere and always (default: estimated from "
                        "the data, --clutter)")
    g.add_argument("--clutter", default=None, choices=list(CLUTTER_SOURCES),
                   help="without --clutter-density, how the tracker estimates it: map = a spatial clutter map times the "
                        "per-scan level, scan = per scan (detections minus those the tracks explain, over the data's "
                        "bounding box), file = all detections per scan over the bounding box (an over-estimate: targets "
                        f"count too) (default {DEFAULT_CLUTTER_SOURCE}; see docs/track_multi.md)")
    g.add_argument("--gate-prob", type=float, default=None, help=f"gate probability P_G (default {MULTI_DEFAULTS['gate_prob']})")
    g.add_argument("--survival-prob", type=float, default=None,
                   help=f"probability that an object survives one scan (default {MULTI_DEFAULTS['survival_prob']})")
    g.add_argument("--birth-existence", type=float, default=None,
                   help="existence probability of a new track (default "
                        + ", ".join(f"{v:g} {k}" for k, v in BIRTH_EXISTENCE.items()) + ")")
    g.add_argument("--birth-density", type=float, default=None, metavar="BETA",
                   help="one-point: new objects' first detections per m² per scan; a new track's existence is then "
                        "BETA/(BETA + clutter density) instead of --birth-existence")
    g.add_argument("--confirm-existence", type=float, default=None,
                   help=f"existence that confirms a track (default {MULTI_DEFAULTS['confirm_existence']})")
    g.add_argument("--delete-existence", type=float, default=None,
                   help=f"existence below which a track is deleted (default {MULTI_DEFAULTS['delete_existence']})")
    g.add_argument("--max-hypotheses", type=int, default=None, metavar="N",
                   help="pmbm: at most N global hypotheses per cluster of interacting tracks; a hypothesis of weight w "
                        f"gets its ceil(N w) best assignments (default {PMBM_DEFAULTS['max_hypotheses']})")
    g.add_argument("--hypothesis-prune", type=float, default=None, metavar="W",
                   help="pmbm: drop global hypotheses of normalised weight below W "
                        f"(default {PMBM_DEFAULTS['hypothesis_prune']:g})")
    g.add_argument("--max-speed", type=float, default=None,
                   help=f"speed scale of new tracks in m/s (default {DEFAULT_MAX_SPEED:g}): one-point, a new track's velocity "
                        f"std per axis is {SPEED_STD_FRACTION:.3g}x it; two-point, the largest speed of its two detections; a "
                        f"confirmed track faster than {SPEED_WARN_FRACTION:g}x the default is warned about")
    g.add_argument("--scan-window", type=float, default=None, metavar="SECONDS",
                   help="one scan = the detections at most SECONDS after the scan's first; its time the midpoint of its "
                        "first and last (default: from the gaps between the distinct times)")

    g = ap.add_argument_group("output")
    g.add_argument("--smooth", action="store_true",
                   help="also write RTS-smoothed columns smooth_<state>, smooth_std_<state> (after flag; "
                        "with --model imm also smooth_mu_<mode>)")
    g.add_argument("--full-cov", action="store_true", help="also write every covariance entry cov_<i>_<j> (upper triangle)")
    g.add_argument("--precision", type=int, default=None,
                   help="significant digits of the output numbers, at most 17 (default 10, and the positions as many as "
                        "keep 0.1 mm, t 1 µs)")
    g.add_argument("--no-monitor", action="store_true",
                   help="no divergence monitoring and recovery (the flag column is then all 0)")
    g.add_argument("--quiet", action="store_true", help="print nothing on success but warnings (about the data, divergence)")

    g = ap.add_argument_group("Dask (one output, computed in partitions of whole objects)")
    add_cluster_options(g)
    g.add_argument("--partition-rows", type=int, default=PARTITION_ROWS, metavar="N",
                   help=f"with --workers/--scheduler: rows per partition (whole objects; default {PARTITION_ROWS})")
    return ap


def check_imm_options(a) -> None:
    """--imm-modes / --imm-switch only with --model imm (one line otherwise)."""
    if a.model != "imm" and (a.imm_modes is not None or a.imm_switch is not None):
        raise ValueError("--imm-modes/--imm-switch: only with --model imm")


def check_estimator_options(a) -> None:
    """One line (ValueError) for an option of another estimator: a multi-target option without ``--multi``, or an
    option of the labelled-object estimators with it, an IMM option without ``--model imm``; then the multi-target
    defaults filled in."""
    check_imm_options(a)
    # --multi without --model: the default model of the input's space (``MultiTrack.check``, from its header)
    if a.multi:
        given = [name for attr, default, name in SINGLE_ONLY if getattr(a, attr) != default]
        if a.model == "all":
            given.insert(0, f"--model {a.model}")
        if given:
            raise ValueError(f"{', '.join(given)}: not available with --multi (see docs/track_multi.md)")
        for k, v in MULTI_DEFAULTS.items():
            if getattr(a, k) is None:
                setattr(a, k, v)
    else:
        given = ["--" + k.replace("_", "-") for k in MULTI_ONLY if getattr(a, k) is not None]
        if given:
            raise ValueError(f"{', '.join(given)}: only with --multi (tracking unlabelled detections)")
