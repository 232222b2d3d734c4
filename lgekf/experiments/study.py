"""The paper's Monte Carlo study (Fig. 4): every registry filter (or a chosen set) on simulated trajectories.

Protocol (defaults; every value is an option and is written to meta.json):

* T = 0.1 s, 100 measurements per trajectory, truth starts at pose (0, 0, 0) with body velocity
  (3, 0) m/s and ω = 0;
* process noise n_x, n_y ~ N(0, 0.1²), n_ω ~ N(0, σ_ω²), σ_ω = numpy.linspace(0, 3, 30);
  100 trajectories per σ_ω; measurement noise N(0, 0.5²) per axis;
* common random numbers: one set of standard-normal draws (process, measurement, initial error)
  is shared by every σ_ω and every filter; the initial estimate is truth + δ,
  δ ~ N(0, diag(0.5², 0.5², 0.1², 0.5², 0.5², 0.1²)) in (x, y, θ, v_x, v_y, ω); each filter starts
  from its own coordinates of that estimate with P0 = J P0_phys Jᵀ (J evaluated at the estimate);
* matched process noise (each definition's ``matched_noise``): LG filters (0.1, 0.1, σ_ω); SE(2)×R² and
  CTRV (0.1, σ_ω); CV 0.1; each optionally multiplied by a per-filter scale (``noise_scale``).  For
  σ_ω = 0 the filters still get σ_ω = 0 (a valid, if overconfident, model);
* measurements: ``position`` (z = (x, y) + N(0, 0.5² I)) or ``pose`` (Z = h(X)·exp(m), m ~
  N(0, diag(0.5², 0.5², heading_std²)) in the tangent of SE(2)); with ``pose`` every filter that has a
  heading gets the pose, the others (CV) its position part;
* a filter that cannot represent the truth (SE(2)×SE(2) beyond |ω| = π, e.g. with the SE(2)×R³ truth and
  a large w0) starts from the wrapped estimate and aliases; ``StudyResult.aliased`` counts those trajectories;
* metric: per-trajectory position RMSE of the posterior over the 100 steps; per σ_ω the mean and std
  over trajectories, for every filter of the set and the raw measurements.
"""

from __future__ import annotations

import math
import time
from dataclasses import asdict, dataclass, field

import numpy as np

from ..core.batch import filter_batch
from ..core.common import covariance_from_common, state_from_common
from .metrics import position_rmse
from ..core.registry import DEFAULT_SPACE, MODELS, SPACES, base_measurement, get_model, models_of, rotation_dims
from ..core.validate import positive_scalar
from .imm_study import IMM_FILTER, MAX_TRAJECTORY_STEPS, ImmStudyOptions, imm_options_from_args, imm_study_rmse
from .simulate import measurement_noise, simulate, truth_models

__all__ = ["StudyConfig", "StudyResult", "run_study", "claims_check", "FILTERS", "PAPER_FILTERS"]

FILTERS = tuple(MODELS)  # every registry model, the default filter set
PAPER_FILTERS = ("se2se2", "se2r3", "ctrv", "cv")  # the filters of the paper's Fig. 4 (its claims name them)
PAPER_LG, PAPER_BASELINES = PAPER_FILTERS[:2], PAPER_FILTERS[2:]  # its two LG filters, its two baselines


@dataclass
class StudyConfig:
    dt: float = 0.1
    steps: int = 100
    trajectories: int = 100
    sigmas: list = field(default_factory=lambda: np.linspace(0.0, 3.0, 30).tolist())
    v0: tuple = (3.0, 0.0)
    w0: float = 0.0
    sigma_v: float = 0.1
    meas_std: float = 0.5
    init_std: tuple = (0.5, 0.5, 0.1, 0.5, 0.5, 0.1)
    truth: str = "se2se2"
    seed: int = 2016
    noise_scale: dict = field(default_factory=lambda: {f: 1.0 for f in FILTERS})
    filters: tuple = FILTERS
    measurement: str = "position"
    heading_std: float = 0.1
    space: str = DEFAULT_SPACE  # the space of motion (lgekf.core.registry.SPACES): "2d" the paper's plane, "3d"

    @classmethod
    def for_space(cls, space: str, **overrides) -> "StudyConfig":
        """The protocol lifted to ``space`` ("3d": truth SE(3)×R⁶ with body velocity (3, 0, 0) m/s and a twist random
        walk, filters = the space's models, 3-D position measurements; init stds 0.5 m / 0.1 rad / 0.5 m/s / 0.1 rad/s
        per coordinate), then ``overrides``; "2d" is the paper's protocol."""
        if space not in SPACES:
            raise ValueError(f"space: unknown space {space!r}; choose one of {', '.join(SPACES)}")
        if space == DEFAULT_SPACE:
            return cls(**overrides)
        dim, r = SPACES[space]["dim"], rotation_dims(space)
        filters = tuple(models_of(space))
        base = dict(space=space, v0=(3.0,) + (0.0,) * (dim - 1), w0=(0.0,) * r,
                    init_std=(0.5,) * dim + (0.1,) * r + (0.5,) * dim + (0.1,) * r, truth=truth_models(space)[0],
                    filters=filters, noise_scale={f: 1.0 for f in filters}, measurement=base_measurement(space))
        return cls(**{**base, **overrides})

    @property
    def dim(self) -> int:
        """2 in the plane, 3 in space: the position coordinates."""
        return SPACES[self.space]["dim"]

    @property
    def start(self) -> np.ndarray:
        """The truth's initial common state: at the origin, level, with body velocity v0 and rate w0."""
        v0, w0 = np.atleast_1d(np.asarray(self.v0, float)), np.atleast_1d(np.asarray(self.w0, float))
        nc = len(SPACES[self.space]["common_names"])
        return np.concatenate([np.zeros(nc - v0.size - w0.size), v0, w0])

    def validate(self) -> None:
        positive_scalar("dt", self.dt)
        if self.space not in SPACES:
            raise ValueError(f"space: unknown space {self.space!r}; choose one of {', '.join(SPACES)}")
        dim, nc = self.dim, len(SPACES[self.space]["common_names"])
        if len(self.v0) != dim or not all(math.isfinite(v) for v in self.v0):
            raise ValueError(f"v0: expected {dim} finite numbers (body velocity in m/s), got {list(self.v0)}")
        w0 = np.atleast_1d(np.asarray(self.w0, float))
        if w0.size != rotation_dims(self.space) or not np.all(np.isfinite(w0)):
            raise ValueError(f"w0: expected {rotation_dims(self.space)} finite number(s) (angular velocity in rad/s), got {self.w0}")
        if len(self.init_std) != nc:
            raise ValueError(f"init_std: expected {nc} stds (one per common coordinate), got {len(self.init_std)}")
        if self.truth not in truth_models(self.space):
            raise ValueError(f"truth: unknown truth model {self.truth!r}; choose one of {', '.join(truth_models(self.space))}")
        truth = get_model(self.truth)
        for idx, bound in truth.bounds.items():
            if truth.bounded_norm(np.asarray(self.start), idx) > bound:
                raise ValueError(f"w0: not representable by the {self.truth} truth ({truth.bound_reason}); got w0 = {self.w0}")
        if self.seed < 0:
            raise ValueError(f"seed: must be a non-negative integer, got {self.seed}")
        if self.steps < 1:
            raise ValueError(f"steps: must be at least 1, got {self.steps}")
        if self.trajectories < 2:
            raise ValueError(f"trajectories: must be at least 2 (a std is reported), got {self.trajectories}")
        if self.trajectories * self.steps > MAX_TRAJECTORY_STEPS:
            raise ValueError(f"trajectories: trajectories × steps must be at most {MAX_TRAJECTORY_STEPS:,} (held in memory), "
                             f"got {self.trajectories} × {self.steps}")
        if len(self.sigmas) < 1 or any((not math.isfinite(s)) or s < 0 for s in self.sigmas):
            raise ValueError("sigmas: need at least one finite, non-negative σ_ω")
        positive_scalar("meas_std", self.meas_std)
        positive_scalar("sigma_v", self.sigma_v, allow_zero=True)
        if any(s < 0 for s in self.init_std):
            raise ValueError("init_std: stds must be non-negative")
        if not self.filters:
            raise ValueError("filters: choose at least one filter")
        own = models_of(self.space)
        for f in self.filters:
            if f != IMM_FILTER and get_model(f).space != self.space:
                raise ValueError(f"filters: {f} is a model of {get_model(f).space}, the study runs in {self.space}; "
                                 f"choose from {', '.join(own)}")
        if IMM_FILTER in self.filters and not SPACES[self.space]["mixes"]:
            raise ValueError(f"filters: the imm filter does not mix the models of {self.space}")
        if self.measurement != base_measurement(self.space):
            get_model(self.truth).measurement(self.measurement)
            positive_scalar("heading_std", self.heading_std)
        for k, v in self.noise_scale.items():
            if k not in own:
                raise ValueError(f"noise scale: unknown filter {k!r}; choose one of {', '.join(own)}")
            positive_scalar(f"noise scale for {k}", v)

    def filter_noise(self, name: str, sigma_w: float):
        """The matched process-noise stds of filter ``name`` at rotational noise σ_ω (times its scale)."""
        s = self.noise_scale.get(name, 1.0)
        return tuple(s * v for v in get_model(name).matched_accel_std(self.sigma_v, sigma_w))

    def filter_measurement(self, name: str) -> str:
        """The measurement a filter gets: the study's, or position where the filter cannot take it (CV, pose)."""
        if name == IMM_FILTER:
            return self.measurement
        return get_model(name).measurement_or_base(self.measurement)

    def meas_noise(self, measurement: str):
        return measurement_noise(measurement, self.meas_std, self.heading_std)


@dataclass
class StudyResult:
    config: StudyConfig
    sigmas: np.ndarray  # (S,)
    rmse: dict  # name -> (S, B) position RMSE per trajectory ("measurements" included)
    wrapped: np.ndarray  # (S,) number of trajectories whose ω wrapped
    compute_seconds: float
    aliased: dict = field(default_factory=dict)  # filter -> (S,) trajectories whose truth it cannot represent
    imm_chains: list = field(default_factory=list)  # the IMM's learned chain per σ_ω (imm_study.imm_study_rmse)

    @property
    def filters(self) -> tuple:
        return tuple(self.config.filters)

    def summary_rows(self):
        rows = []
        for i, s in enumerate(self.sigmas):
            for name in (*self.filters, "measurements"):
                r = self.rmse[name][i]
                rows.append((float(s), name, float(r.mean()), float(r.std(ddof=1)), int(r.size)))
        return rows

    def mean(self, name):
        return self.rmse[name].mean(axis=1)

    def std(self, name):
        return self.rmse[name].std(axis=1, ddof=1)


def run_study(cfg: StudyConfig, progress=None, imm: ImmStudyOptions | None = None) -> StudyResult:
    """Run the whole protocol; the same config (seed included) gives the same numbers.

    ``progress``: None, or a callable ``progress(done, total)`` called after each σ_ω value (the CLI
    passes a tqdm bar's update). ``imm``: the IMM's options when ``cfg.filters`` has "imm".
    """
    cfg.validate()
    imm = imm_options_from_args(None, None, None, cfg.space) if imm is None else imm
    if IMM_FILTER in cfg.filters:
        imm.validate(cfg.steps)
    rng = np.random.default_rng(cfg.seed)
    B, K = cfg.trajectories, cfg.steps
    truth = get_model(cfg.truth)
    # common random numbers, shared by every σ_ω and every filter
    u_proc = rng.standard_normal((B, K, 3))
    u_meas = rng.standard_normal((B, K, 2))
    u_init = rng.standard_normal((B, len(cfg.init_std)))
    extra = get_model(cfg.truth).measurement(cfg.measurement).dim - 2
    if extra:  # extra draws after the default ones: position studies are unchanged
        u_meas = np.concatenate([u_meas, rng.standard_normal((B, K, extra))], axis=-1)
    if len(truth.noise_inputs) > 3:
        u_proc = np.concatenate([u_proc, rng.standard_normal((B, K, len(truth.noise_inputs) - 3))], axis=-1)
    truth0 = np.tile(cfg.start, (B, 1))
    est0 = truth0 + u_init * np.asarray(cfg.init_std)
    P0_phys = np.diag(np.square(cfg.init_std))
    # each filter's initial state and covariance in its own coordinates
    inits = {}
    for name in cfg.filters:
        if name == IMM_FILTER:
            continue
        spec = get_model(name)
        e0 = spec.wrap_bounded(est0)  # a copy: a filter that cannot represent the estimate starts wrapped
        x0 = state_from_common(name, e0)
        P0 = covariance_from_common(name, e0, P0_phys)
        # a zero init std makes P0 singular: keep it positive definite with a tiny floor
        P0 += 1e-12 * np.eye(P0.shape[-1])
        inits[name] = (x0, P0)

    sigmas = np.asarray(cfg.sigmas, dtype=float)
    S = len(sigmas)
    rmse = {name: np.empty((S, B)) for name in (*cfg.filters, "measurements")}
    wrapped = np.zeros(S, dtype=int)
    aliased = {name: np.zeros(S, dtype=int) for name in cfg.filters if name != IMM_FILTER and get_model(name).bounds}
    imm_chains: list = []
    t0 = time.perf_counter()
    for i, sw in enumerate(sigmas):
        sim = simulate(
            truth0, dt=cfg.dt, steps=K, sigma_v=cfg.sigma_v, sigma_w=sw, meas_std=cfg.meas_noise(cfg.measurement),
            truth=cfg.truth, measurement=cfg.measurement, std_normal_process=u_proc, std_normal_meas=u_meas,
        )
        pos = sim.truth[:, 1:, :cfg.dim]
        wrapped[i] = int(sim.wrapped.sum())
        rmse["measurements"][i] = position_rmse(sim.z, pos, cfg.dim)
        for name in aliased:
            spec = get_model(name)
            aliased[name][i] = int(np.any([spec.bounded_norm(sim.truth, j) > v for j, v in spec.bounds.items()],
                                          axis=(0, 2)).sum())
        for name in cfg.filters:
            if name == IMM_FILTER:
                rmse[name][i] = imm_study_rmse(cfg, imm, sim, sw, est0, P0_phys, pos, imm_chains)
                continue
            x0, P0 = inits[name]
            meas = cfg.filter_measurement(name)
            z = sim.z if meas == cfg.measurement else np.ascontiguousarray(sim.z[..., :cfg.dim])
            est = filter_batch(
                name, z, dt=cfg.dt, accel_std=cfg.filter_noise(name, sw), meas_std=cfg.meas_noise(meas), x0=x0, P0=P0,
                measurement=meas,
            )
            rmse[name][i] = position_rmse(est, pos, cfg.dim)
        if progress is not None:
            progress(i + 1, S)
    return StudyResult(cfg, sigmas, rmse, wrapped, time.perf_counter() - t0, aliased, imm_chains)


# ------------------------------------------------------------------------------------ claims
@dataclass
class Claim:
    text: str
    holds: bool
    evidence: str


def _spearman(a, b):
    ra = np.argsort(np.argsort(a))
    rb = np.argsort(np.argsort(b))
    if np.std(ra) == 0 or np.std(rb) == 0:
        return float("nan")
    return float(np.corrcoef(ra, rb)[0, 1])


def claims_check(res: StudyResult, close_tol: float = 0.05) -> list[Claim]:
    """The paper's statements about Fig. 4, each checked with the numbers behind it.

    Thresholds: "close" = within ``close_tol`` (5 %) relative; "small σ_ω" = the lowest sixth of the
    σ_ω range, "large σ_ω" = the highest sixth.
    """
    names = paper_names(res.filters)
    lgs = [names[k] for k in PAPER_LG if k in names]
    if not lgs or not set(PAPER_BASELINES) <= set(names):
        return []  # the claims compare the paper's filters (or, in 3-D, the models that lift them)
    s = res.sigmas
    m = {k: res.mean(k) for k in res.rmse}
    for k, f in names.items():  # the paper's names for the study's filters
        m[k] = m[f]
    lg_best = np.minimum.reduce([m[f] for f in lgs])
    lg_worst = np.maximum.reduce([m[f] for f in lgs])
    S = len(s)
    order = np.argsort(s, kind="stable")  # by value: --sigmas may be given in any order
    lo = order[: max(1, S // 6)]
    hi = order[S - max(1, S // 6):]
    out = []

    if len(lgs) == 2:
        rel = np.abs(m["se2se2"] - m["se2r3"]) / lg_best
        out.append(Claim(
            "SE(2)xSE(2) and SE(2)xR3 are close (within 5 %)" if lgs == list(PAPER_LG) else
            f"{lgs[0]} and {lgs[1]} are close (within 5 %)",
            bool(np.all(rel <= close_tol)),
            f"max relative difference {rel.max():.1%} at σ_ω={s[rel.argmax()]:.2f}",
        ))
    base_best = np.minimum(m["ctrv"], m["cv"])
    wins = lg_worst < base_best
    ctrv, cv = names["ctrv"], names["cv"]
    out.append(Claim(
        "the two LG filters are the best filters at every σ_ω" if len(lgs) == 2 else
        f"the LG filter ({lgs[0]}) is the best filter at every σ_ω",
        bool(np.all(wins)),
        (f"both LG filters beat CTRV and CV at {int(wins.sum())}/{S} σ_ω values" if len(lgs) == 2 else
         f"{lgs[0]} beats {ctrv} and {cv} at {int(wins.sum())}/{S} σ_ω values")
        + ("" if wins.all() else f"; not at σ_ω = {', '.join(f'{v:.2f}' for v in s[~wins][:6])}"),
    ))
    cv_gap_lo = float(np.mean(m["cv"][lo] / lg_best[lo] - 1))
    out.append(Claim(
        "CV is good at small σ_ω (within 5 % of the LG filters)",
        bool(cv_gap_lo <= close_tol),
        f"CV vs best LG at small σ_ω: {cv_gap_lo:+.1%}",
    ))
    rho = _spearman(s, m["cv"]) if S > 2 else float("nan")
    grow = float(np.mean(m["cv"][hi]) / np.mean(m["cv"][lo]))
    out.append(Claim(
        "CV degrades as σ_ω grows (large-σ_ω RMSE at least 1.5x the small-σ_ω RMSE)",
        bool(S > 1 and grow >= 1.5),
        f"CV RMSE large/small σ_ω = {grow:.2f}x; Spearman ρ(σ_ω, CV RMSE) = {rho:.2f}",
    ))
    ctrv_lo = float(np.mean(m["ctrv"][lo] / lg_best[lo] - 1))
    ctrv_hi = float(np.mean(m["ctrv"][hi] / lg_best[hi] - 1))
    out.append(Claim(
        "CTRV is weaker at small σ_ω (more than 5 % worse than LG)",
        bool(ctrv_lo > close_tol),
        f"CTRV vs best LG at small σ_ω: {ctrv_lo:+.1%}",
    ))
    out.append(Claim(
        "CTRV approaches the LG filters at large σ_ω",
        bool(S > 1 and ctrv_hi < ctrv_lo),
        f"CTRV gap to best LG: {ctrv_lo:+.1%} (small σ_ω) -> {ctrv_hi:+.1%} (large σ_ω)",
    ))
    worst = np.max(np.vstack([m[names[f]] for f in PAPER_FILTERS if f in names]), axis=0)
    ratio = worst / m["measurements"]
    out.append(Claim(
        "every filter beats the raw measurements at every σ_ω",
        bool(np.all(ratio < 1)),
        f"worst filter / measurement RMSE: max {ratio.max():.2f} at σ_ω={s[ratio.argmax()]:.2f}",
    ))
    return out


def paper_names(filters) -> dict:
    """{the paper's filter: the study's filter standing for it}: a planar filter stands for itself, a 3-D one for the
    planar model it lifts (its definition's ``lifts``: se3r6 for se2r3, ct3 for ctrv, cv3 for cv)."""
    out = {}
    for f in filters:
        if f != IMM_FILTER:
            key = get_model(f).lifts or f
            if key in PAPER_FILTERS:
                out.setdefault(key, f)
    return out


def config_dict(cfg: StudyConfig) -> dict:
    d = asdict(cfg)
    d["v0"] = list(cfg.v0)
    d["w0"] = list(cfg.w0) if isinstance(cfg.w0, (tuple, list)) else cfg.w0
    d["init_std"] = list(cfg.init_std)
    d["filters"] = list(cfg.filters)
    return d
