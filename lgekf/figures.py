"""Figures of the paper: Fig. 1/2 (banana-shaped uncertainty), Fig. 3 (example tracks), Fig. 4 (study)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .core.filters import SE2SE2Filter
from .core.registry import MODELS
from .generated import se2
from .experiments.simulate import simulate

__all__ = ["study_figure", "banana_figure", "trajectories_figure", "COLORS", "LABELS"]

COLORS = {**{name: spec.color for name, spec in MODELS.items()}, "measurements": "black"}
LABELS = {**{name: spec.display_name for name, spec in MODELS.items()}, "measurements": "measurements"}


def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _save(fig, path: Path, pdf: bool):
    """PNG (and PDF); the CLI writes into a staged folder, so no partial set is left on failure."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=150, bbox_inches="tight")
    written = [path]
    if pdf:
        fig.savefig(path.with_suffix(".pdf"), bbox_inches="tight")
        written.append(path.with_suffix(".pdf"))
    return written


def study_figure(result, path, pdf: bool = False):
    """Fig. 4: mean position RMSE (line) and ±1 std (band) per filter versus σ_ω."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=(7.0, 4.2))
    s = result.sigmas
    for name in ("measurements", *reversed(result.filters)):
        m, sd = result.mean(name), result.std(name)
        ax.plot(s, m, color=COLORS[name], lw=1.8 if name != "measurements" else 1.2, label=LABELS[name])
        ax.fill_between(s, m - sd, m + sd, color=COLORS[name], alpha=0.15, lw=0)
    c = result.config
    ax.set_xlabel("rotational process noise σ_ω [rad/s²]")
    ax.set_ylabel("position RMSE [m]")
    meas = "" if c.measurement == "position" else f", {c.measurement} measurements"
    ax.set_title(f"{c.trajectories} trajectories per σ_ω, T = {c.dt:g} s, {c.steps} steps, truth {c.truth}{meas}")
    ax.set_xlim(s.min(), s.max() if s.max() > s.min() else s.min() + 1)
    ax.set_ylim(bottom=0)
    ax.grid(alpha=0.3)
    ax.legend(loc="upper left", fontsize=8, ncols=2)
    out = _save(fig, path, pdf)
    plt.close(fig)
    return out


def _hist_contour_level(H, mass=0.95):
    """The density level whose super-level set holds ``mass`` of a 2-D histogram."""
    flat = np.sort(H.ravel())[::-1]
    cum = np.cumsum(flat)
    cum /= cum[-1]
    return flat[np.searchsorted(cum, mass)]


def _smooth(H, sigma_bins=1.5):
    k = np.arange(-4, 5)
    g = np.exp(-0.5 * (k / sigma_bins) ** 2)
    g /= g.sum()
    H = np.apply_along_axis(lambda r: np.convolve(r, g, mode="same"), 0, H)
    return np.apply_along_axis(lambda r: np.convolve(r, g, mode="same"), 1, H)


def banana_figure(path, pdf: bool = False, sigmas=(0.1, 0.3, 0.6, 1.0), steps: int = 2, dt: float = 1.0, n: int = 20000, seed: int = 1):
    """Fig. 1/2: compounding uncertain SE(2) motions.

    An object at the origin moving at 1 m/s (body frame) is propagated ``steps`` times through the
    SE(2)×SE(2) model with rotational noise σ_ω.  Grey: samples of the exact motion.  Blue: the 95 %
    contour of the LG-EKF prediction (a concentrated Gaussian on SE(2), sampled as μ exp(ε),
    ε ~ N(0, P)).  Dashed grey: the 95 % ellipse of a Gaussian in R² fitted to the same samples.
    """
    plt = _plt()
    rng = np.random.default_rng(seed)
    fig, axes = plt.subplots(1, len(sigmas), figsize=(3.2 * len(sigmas), 3.9), sharey=True, layout="constrained")
    x0 = np.array([0.0, 0.0, 0.0, 1.0, 0.0, 0.0])
    chi2_95 = 5.991464547107979  # 95 % quantile of chi-square with 2 dof
    for ax, sw in zip(np.atleast_1d(axes), sigmas):
        sim = simulate(np.tile(x0, (n, 1)), dt=dt, steps=steps, sigma_v=0.05, sigma_w=sw, meas_std=1.0, rng=rng)
        pts = sim.truth[:, -1, :2]
        f = SE2SE2Filter(dt=dt, accel_std=(0.05, 0.05, sw), meas_std=1.0, x0=x0, P0=np.eye(6) * 1e-12)
        for _ in range(steps):
            f.predict()
        mu = f.mean[:3, :3]
        P = f.P[:3, :3]
        eps = rng.multivariate_normal(np.zeros(3), P, size=n)
        cg = np.array([(mu @ se2.se2_exp(e))[:2, 2] for e in eps])
        lim = np.array([min(pts[:, 0].min(), cg[:, 0].min()), max(pts[:, 0].max(), cg[:, 0].max()),
                        min(pts[:, 1].min(), cg[:, 1].min()), max(pts[:, 1].max(), cg[:, 1].max())])
        pad = 0.1 * max(lim[1] - lim[0], lim[3] - lim[2])
        xe = np.linspace(lim[0] - pad, lim[1] + pad, 121)
        ye = np.linspace(lim[2] - pad, lim[3] + pad, 121)
        H, _, _ = np.histogram2d(cg[:, 0], cg[:, 1], bins=[xe, ye])
        H = _smooth(H)
        xc, yc = 0.5 * (xe[1:] + xe[:-1]), 0.5 * (ye[1:] + ye[:-1])
        show = pts[rng.choice(n, size=min(300, n), replace=False)]
        ax.scatter(show[:, 0], show[:, 1], s=6, facecolors="none", edgecolors="0.55", lw=0.6, label="samples of the motion")
        ax.contour(xc, yc, H.T, levels=[_hist_contour_level(H)], colors="tab:blue", linewidths=1.8)
        m, C = pts.mean(axis=0), np.cov(pts.T)
        w, V = np.linalg.eigh(C)
        t = np.linspace(0, 2 * np.pi, 200)
        ell = m[:, None] + V @ (np.sqrt(chi2_95 * np.maximum(w, 0))[:, None] * np.vstack([np.cos(t), np.sin(t)]))
        ax.plot(ell[0], ell[1], "--", color="0.3", lw=1.2)
        ax.plot(*mu[:2, 2], "+", color="tab:blue", ms=9)
        ax.set_title(f"σ_ω = {sw:g} rad/s²")
        ax.set_xlabel("x [m]")
        ax.set_aspect("equal", adjustable="datalim")
        ax.grid(alpha=0.3)
    axes = np.atleast_1d(axes)
    axes[0].set_ylabel("y [m]")
    from matplotlib.lines import Line2D

    handles = [
        Line2D([], [], marker="o", ls="", mfc="none", mec="0.55", label="samples of the exact motion"),
        Line2D([], [], color="tab:blue", lw=1.8, label="LG-EKF prediction, 95 % (concentrated Gaussian on SE(2))"),
        Line2D([], [], color="0.3", ls="--", label="Gaussian in R² of the samples, 95 %"),
    ]
    fig.legend(handles=handles, loc="outside lower center", ncols=3, fontsize=8, frameon=False)
    fig.suptitle(f"Compounding {steps} uncertain SE(2) motions (1 m/s, T = {dt:g} s)", fontsize=10)
    out = _save(fig, path, pdf)
    plt.close(fig)
    return out


def trajectories_figure(path, pdf: bool = False, sigmas=(0.01, 0.1, 1.0), seed: int = 3, dt: float = 0.1, steps: int = 100):
    """Fig. 3: example trajectories for small, medium and large σ_ω with SE(2)×SE(2) and CV estimates."""
    from .core.batch import filter_batch

    plt = _plt()
    rng = np.random.default_rng(seed)
    fig, axes = plt.subplots(1, len(sigmas), figsize=(4.0 * len(sigmas), 4.0), layout="constrained")
    x0 = np.array([[0.0, 0.0, 0.0, 3.0, 0.0, 0.0]])
    for ax, sw in zip(np.atleast_1d(axes), sigmas):
        sim = simulate(x0, dt=dt, steps=steps, sigma_v=0.1, sigma_w=sw, meas_std=0.5, rng=rng)
        lg = filter_batch("se2se2", sim.z, dt=dt, accel_std=(0.1, 0.1, sw), meas_std=0.5, x0=x0, P0=np.eye(6) * 0.1)
        cv_x0 = np.array([[0.0, 0.0, 3.0, 0.0]])
        cv = filter_batch("cv", sim.z, dt=dt, accel_std=0.1, meas_std=0.5, x0=cv_x0, P0=np.eye(4) * 0.1)
        tr = sim.truth[0]
        ax.plot(tr[:, 0], tr[:, 1], color="black", lw=1.5, label="truth")
        ax.scatter(sim.z[0, :, 0], sim.z[0, :, 1], s=5, color="0.6", label="measurements")
        ax.plot(lg[0, :, 0], lg[0, :, 1], color=COLORS["se2se2"], lw=1.3, label=LABELS["se2se2"])
        ax.plot(cv[0, :, 0], cv[0, :, 1], color=COLORS["cv"], lw=1.3, label=LABELS["cv"])
        ax.set_title(f"σ_ω = {sw:g} rad/s²")
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        ax.set_aspect("equal", adjustable="datalim")
        ax.grid(alpha=0.3)
    np.atleast_1d(axes)[0].legend(fontsize=8, loc="best")
    out = _save(fig, path, pdf)
    plt.close(fig)
    return out

