"""Figures of the paper: Fig. 1/2 (banana-shaped uncertainty), Fig. 3 (example tracks), Fig. 4 (study)."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..core.filters import SE2SE2Filter
from ..core.registry import ALL_MODELS, DEFAULT_SPACE, base_measurement
from ..generated import se2
from .simulate import simulate

__all__ = [
    "study_figure", "banana_figure", "banana_panel", "highest_density_region", "trajectories_figure", "COLORS", "LABELS",
]

COLORS = {**{name: spec.color for name, spec in ALL_MODELS.items()}, "measurements": "black", "imm": "tab:brown"}
LABELS = {**{name: spec.display_name for name, spec in ALL_MODELS.items()}, "measurements": "measurements", "imm": "IMM"}


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
    meas = "" if c.measurement == base_measurement(c.space) else f", {c.measurement} measurements"
    meas += "" if c.space == DEFAULT_SPACE else f", in {c.space}"
    ax.set_title(f"{c.trajectories} trajectories per σ_ω, T = {c.dt:g} s, {c.steps} steps, truth {c.truth}{meas}")
    ax.set_xlim(s.min(), s.max() if s.max() > s.min() else s.min() + 1)
    ax.set_ylim(bottom=0)
    ax.grid(alpha=0.3)
    ax.legend(loc="upper left", fontsize=8, ncols=2)
    out = _save(fig, path, pdf)
    plt.close(fig)
    return out


def _smooth(H, sigma_bins=1.5):
    """A 2-D histogram smoothed by a separable Gaussian of ``sigma_bins`` bins (a simple density estimate)."""
    k = np.arange(-4, 5)
    g = np.exp(-0.5 * (k / sigma_bins) ** 2)
    g /= g.sum()
    H = np.apply_along_axis(lambda r: np.convolve(r, g, mode="same"), 0, H)
    return np.apply_along_axis(lambda r: np.convolve(r, g, mode="same"), 1, H)


@dataclass
class DensityRegion:
    """A highest-density region of 2-D samples: smoothed histogram ``H`` on the grid ``xe`` × ``ye``
    (bin edges) and the density ``level`` whose super-level set {H >= level} is the region."""

    xe: np.ndarray
    ye: np.ndarray
    H: np.ndarray
    level: float

    def density(self, points) -> np.ndarray:
        """The smoothed density at ``points`` (N, 2); 0 outside the grid."""
        points = np.asarray(points, dtype=float)
        i = np.searchsorted(self.xe, points[:, 0]) - 1
        j = np.searchsorted(self.ye, points[:, 1]) - 1
        ok = (i >= 0) & (i < self.H.shape[0]) & (j >= 0) & (j < self.H.shape[1])
        out = np.zeros(len(points))
        out[ok] = self.H[i[ok], j[ok]]
        return out

    def contains(self, points) -> np.ndarray:
        """Whether each of ``points`` (N, 2) lies in the region."""
        return self.density(points) >= self.level

    def contour(self, ax, **kwargs):
        """Draw the region's boundary on ``ax``."""
        xc, yc = 0.5 * (self.xe[1:] + self.xe[:-1]), 0.5 * (self.ye[1:] + self.ye[:-1])
        return ax.contour(xc, yc, self.H.T, levels=[self.level], **kwargs)


def highest_density_region(points, xe, ye, mass: float = 0.95, sigma_bins: float = 1.5) -> DensityRegion:
    """The region of highest density holding ``mass`` of the distribution of 2-D ``points``.

    Parameters
    ----------
    points : ndarray, shape (N, 2)
        Samples of the distribution.
    xe, ye : ndarray
        Bin edges of the histogram grid (it should cover the samples).
    mass : float
        Probability the region holds (default 0.95).
    sigma_bins : float
        Width of the Gaussian smoothing of the histogram, in bins.

    Returns
    -------
    DensityRegion
        The density is a smoothed 2-D histogram; the level is the (1 - ``mass``) quantile of the density
        at the samples themselves (Hyndman, Computing and graphing highest density regions, The
        American Statistician 50 (1996)), so the region holds ``mass`` of the samples, and of new
        samples of the same distribution up to sampling error.
    """
    points = np.asarray(points, dtype=float)
    H, _, _ = np.histogram2d(points[:, 0], points[:, 1], bins=[xe, ye])
    region = DensityRegion(np.asarray(xe, float), np.asarray(ye, float), _smooth(H, sigma_bins), 0.0)
    region.level = float(np.quantile(region.density(points), 1.0 - mass))
    return region


@dataclass
class BananaPanel:
    """The data of one panel of Fig. 1/2 (see ``banana_panel``)."""

    sigma_w: float
    exact: np.ndarray  # (n, 2) positions of the exact compounded motion
    cgd: np.ndarray  # (n, 2) positions of samples μ·exp(ε), ε ~ N(0, P) of the LG-EKF prediction
    mean: np.ndarray  # (3, 3) the LG-EKF's SE(2) mean μ of the pose
    P: np.ndarray  # (3, 3) its tangent covariance of (x, y, θ)
    exact_region: DensityRegion  # 95 % highest-density region of the exact positions
    cgd_region: DensityRegion  # 95 % highest-density region of the LG-EKF's positions

    @property
    def heading_std(self) -> float:
        """Std of the tangent heading ε_θ of the concentrated Gaussian (rad)."""
        return float(np.sqrt(self.P[2, 2]))


def banana_panel(sigma_w: float, *, steps: int = 2, dt: float = 1.0, n: int = 20000, rng=None, bins: int = 121) -> BananaPanel:
    """Exact and LG-EKF (concentrated Gaussian) position distributions after compounding motions.

    Parameters
    ----------
    sigma_w : float
        Rotational process noise σ_ω (rad/s²) of the SE(2)×SE(2) model.
    steps, dt : int, float
        Number of compounded motions and their duration (s). The object starts at the origin,
        heading along x at 1 m/s; the translational noise is 0.05 m/s².
    n : int
        Samples of each distribution.
    rng : numpy.random.Generator, optional
        Source of the samples.
    bins : int
        Grid lines per axis of the density estimates.

    Returns
    -------
    BananaPanel
        Samples of both distributions, the LG-EKF's mean and covariance, and their 95 % highest-density
        regions (``highest_density_region``) on a common grid.
    """
    rng = np.random.default_rng() if rng is None else rng
    x0 = np.array([0.0, 0.0, 0.0, 1.0, 0.0, 0.0])
    sim = simulate(np.tile(x0, (n, 1)), dt=dt, steps=steps, sigma_v=0.05, sigma_w=sigma_w, meas_std=1.0, rng=rng)
    exact = np.ascontiguousarray(sim.truth[:, -1, :2])
    f = SE2SE2Filter(dt=dt, accel_std=(0.05, 0.05, sigma_w), meas_std=1.0, x0=x0, P0=np.eye(6) * 1e-12)
    for _ in range(steps):
        f.predict()
    mu = f.mean[:3, :3]
    P = f.P[:3, :3]
    eps = rng.multivariate_normal(np.zeros(3), P, size=n)
    cgd = np.array([(mu @ se2.se2_exp(e))[:2, 2] for e in eps])
    both = np.vstack([exact, cgd])
    lo, hi = both.min(axis=0), both.max(axis=0)
    pad = 0.1 * float(np.max(hi - lo))
    xe = np.linspace(lo[0] - pad, hi[0] + pad, bins)
    ye = np.linspace(lo[1] - pad, hi[1] + pad, bins)
    return BananaPanel(float(sigma_w), exact, cgd, mu, P, highest_density_region(exact, xe, ye),
                       highest_density_region(cgd, xe, ye))


BANANA_CAPTION = (
    "Why the blue region becomes a ring: the LG-EKF's concentrated Gaussian is Gaussian in the tangent ε = (ε_x, ε_y, ε_θ) "
    "at the mean μ and its positions are those of μ·exp(ε),\nso its 95 % region in the plane is the image of a tangent "
    "ellipsoid under exp. Lateral offset and heading are correlated, which makes that image an arc through μ; exp is periodic "
    "in ε_θ,\nand once the ellipsoid reaches |ε_θ| ≈ π (heading std ≳ π/2, here at σ_ω ≈ 1) the arc closes into a ring. "
    "The exact distribution of the compounded motion is not a concentrated Gaussian:\nits ends bend farther out than the "
    "arc (black), so the ring misses them and covers positions behind μ that the object never reaches. "
    "Boxes: heading std of the concentrated Gaussian, share of exact samples inside blue."
)


def banana_figure(path, pdf: bool = False, sigmas=(0.1, 0.3, 0.6, 1.0), steps: int = 2, dt: float = 1.0, n: int = 20000, seed: int = 1):
    """Fig. 1/2: compounding uncertain SE(2) motions.

    An object at the origin moving at 1 m/s (body frame) is propagated ``steps`` times through the
    SE(2)×SE(2) model with rotational noise σ_ω (``banana_panel``).  Grey: samples of the exact motion;
    black: their 95 % highest-density region.  Blue: the same region of the LG-EKF prediction (a
    concentrated Gaussian on SE(2), sampled as μ exp(ε), ε ~ N(0, P)).  Dashed grey: the 95 % ellipse
    of a Gaussian in R² fitted to the exact samples.  A caption explains why the blue region becomes a
    ring at large σ_ω (``BANANA_CAPTION``); each panel gives the concentrated Gaussian's heading std and
    the share of an independent set of exact samples inside the blue region.
    """
    plt = _plt()
    rng = np.random.default_rng(seed)
    fig = plt.figure(figsize=(3.2 * len(sigmas), 5.6), layout="constrained")
    top, bottom = fig.subfigures(2, 1, height_ratios=[4.0, 1.05])
    axes = top.subplots(1, len(sigmas), sharey=True)
    chi2_95 = 5.991464547107979  # 95 % quantile of chi-square with 2 dof
    for ax, sw in zip(np.atleast_1d(axes), sigmas):
        pan = banana_panel(sw, steps=steps, dt=dt, n=n, rng=rng)
        pts = pan.exact
        fresh = banana_panel(sw, steps=steps, dt=dt, n=n, rng=rng).exact  # independent samples for the share
        show = pts[rng.choice(n, size=min(300, n), replace=False)]
        ax.scatter(show[:, 0], show[:, 1], s=6, facecolors="none", edgecolors="0.55", lw=0.6)
        pan.exact_region.contour(ax, colors="black", linewidths=1.3)
        pan.cgd_region.contour(ax, colors="tab:blue", linewidths=1.8)
        m, C = pts.mean(axis=0), np.cov(pts.T)
        w, V = np.linalg.eigh(C)
        t = np.linspace(0, 2 * np.pi, 200)
        ell = m[:, None] + V @ (np.sqrt(chi2_95 * np.maximum(w, 0))[:, None] * np.vstack([np.cos(t), np.sin(t)]))
        ax.plot(ell[0], ell[1], "--", color="0.3", lw=1.2)
        ax.plot(*pan.mean[:2, 2], "+", color="tab:blue", ms=9)
        share = float(np.mean(pan.cgd_region.contains(fresh)))
        ax.text(0.03, 0.03, f"heading std {pan.heading_std:.2f} rad\nexact samples in blue: {100 * share:.0f} %",
                transform=ax.transAxes, fontsize=7.5, va="bottom", ha="left",
                bbox=dict(boxstyle="round,pad=0.25", fc="white", ec="0.8", alpha=0.9))
        ax.set_title(f"σ_ω = {sw:g} rad/s²")
        ax.set_xlabel("x [m]")
        ax.set_aspect("equal", adjustable="datalim")
        ax.grid(alpha=0.3)
    axes = np.atleast_1d(axes)
    axes[0].set_ylabel("y [m]")
    from matplotlib.lines import Line2D

    handles = [
        Line2D([], [], marker="o", ls="", mfc="none", mec="0.55", label="samples of the exact motion"),
        Line2D([], [], color="black", lw=1.3, label="exact distribution, 95 % (density of the samples)"),
        Line2D([], [], color="tab:blue", lw=1.8, label="LG-EKF prediction, 95 % (concentrated Gaussian on SE(2))"),
        Line2D([], [], color="0.3", ls="--", label="Gaussian in R² of the samples, 95 %"),
    ]
    bottom.legend(handles=handles, loc="upper center", ncols=4, fontsize=8, frameon=False)
    bottom.text(0.5, 0.62, BANANA_CAPTION, fontsize=7.5, ha="center", va="top", linespacing=1.4)
    top.suptitle(f"Compounding {steps} uncertain SE(2) motions (1 m/s, T = {dt:g} s)", fontsize=10)
    out = _save(fig, path, pdf)
    plt.close(fig)
    return out


def _fit_limits(ax, xs, ys, pad: float = 0.04, margin: float = 0.4):
    """Axis limits around the data (``pad`` of each span plus ``margin`` metres), equal aspect, box adjusted."""
    for lim, v in ((ax.set_xlim, xs), (ax.set_ylim, ys)):
        lo, hi = float(np.min(v)), float(np.max(v))
        m = pad * (hi - lo) + margin
        lim(lo - m, hi + m)
    ax.set_aspect("equal", adjustable="box")


def trajectories_figure(path, pdf: bool = False, sigmas=(0.01, 0.1, 1.0), seed: int = 3, dt: float = 0.1, steps: int = 100):
    """Fig. 3: example trajectories for small, medium and large σ_ω with SE(2)×SE(2) and CV estimates.

    Every panel is fitted to its own data with equal aspect (the nearly straight tracks of small σ_ω
    are long and flat). With several σ_ω the last (most turning) track gets the right column and the
    others are stacked on the left.
    """
    from ..core.batch import filter_batch

    plt = _plt()
    rng = np.random.default_rng(seed)
    x0 = np.array([[0.0, 0.0, 0.0, 3.0, 0.0, 0.0]])
    cv_x0 = np.array([[0.0, 0.0, 3.0, 0.0]])
    runs = []
    for sw in sigmas:
        sim = simulate(x0, dt=dt, steps=steps, sigma_v=0.1, sigma_w=sw, meas_std=0.5, rng=rng)
        lg = filter_batch("se2se2", sim.z, dt=dt, accel_std=(0.1, 0.1, sw), meas_std=0.5, x0=x0, P0=np.eye(6) * 0.1)
        cv = filter_batch("cv", sim.z, dt=dt, accel_std=0.1, meas_std=0.5, x0=cv_x0, P0=np.eye(4) * 0.1)
        runs.append((sw, sim.truth[0], sim.z[0], lg[0], cv[0]))
    n = len(runs)
    if n == 1:
        fig, ax = plt.subplots(figsize=(5.5, 5.0), layout="constrained")
        axes = [ax]
    else:
        mosaic = [[f"p{i}", f"p{n - 1}"] for i in range(n - 1)]
        # left rows as tall as their data's aspect (plus room for the labels): little empty space
        aspect = [np.ptp(np.r_[r[1][:, 1], r[2][:, 1]]) / np.ptp(np.r_[r[1][:, 0], r[2][:, 0]]) for r in runs[:-1]]
        fig = plt.figure(figsize=(12.0, 4.2), layout="constrained")
        named = fig.subplot_mosaic(mosaic, width_ratios=[1.3, 1.0], height_ratios=[a + 0.1 for a in aspect])
        axes = [named[f"p{i}"] for i in range(n)]
        mid = (n - 2) / 2  # the left column's middle row: boxes above it sit low, below it high (no gaps)
        for i, ax in enumerate(axes[:-1]):
            ax.set_anchor("S" if i < mid else "N" if i > mid else "C")
    for ax, (sw, tr, z, lg, cv) in zip(axes, runs):
        ax.plot(tr[:, 0], tr[:, 1], color="black", lw=1.5, label="truth")
        ax.scatter(z[:, 0], z[:, 1], s=5, color="0.6", label="measurements")
        ax.plot(lg[:, 0], lg[:, 1], color=COLORS["se2se2"], lw=1.3, label=LABELS["se2se2"])
        ax.plot(cv[:, 0], cv[:, 1], color=COLORS["cv"], lw=1.3, label=LABELS["cv"])
        xs = np.concatenate([tr[:, 0], z[:, 0], lg[:, 0], cv[:, 0]])
        ys = np.concatenate([tr[:, 1], z[:, 1], lg[:, 1], cv[:, 1]])
        _fit_limits(ax, xs, ys)
        ax.set_title(f"σ_ω = {sw:g} rad/s²", fontsize=10)
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        ax.grid(alpha=0.3)
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncols=4, fontsize=8, frameon=False)
    out = _save(fig, path, pdf)
    plt.close(fig)
    return out
