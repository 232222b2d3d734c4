"""Fig. 1/2 and Fig. 3 (`lgekf.experiments.figures`): the density regions drawn, the claims of the Fig. 1/2 caption,
and Fig. 3's panels fitted to their own data."""

import math

import numpy as np
import pytest

from lgekf.experiments import figures
from lgekf.experiments.figures import BANANA_CAPTION, banana_panel, highest_density_region


def test_highest_density_region_of_a_standard_normal():
    rng = np.random.default_rng(0)
    edges = np.linspace(-5, 5, 121)
    region = highest_density_region(rng.standard_normal((40000, 2)), edges, edges)
    fresh = rng.standard_normal((40000, 2))
    assert np.mean(region.contains(fresh)) == pytest.approx(0.95, abs=0.01)
    # the exact 95 % region is the disc of radius sqrt(-2 ln 0.05) = 2.448
    r = math.sqrt(-2 * math.log(0.05))
    angles = np.linspace(0, 2 * np.pi, 16, endpoint=False)
    ring = np.column_stack([np.cos(angles), np.sin(angles)])
    assert region.contains(0.88 * r * ring).all()
    assert not region.contains(1.12 * r * ring).any()


def test_banana_caption_claims():
    """The concentrated Gaussian matches the exact motion at small σ_ω, wraps into a ring at σ_ω = 1."""
    rng = np.random.default_rng(7)
    shares = {}
    for sw in (0.1, 0.6, 1.0):
        p = banana_panel(sw, n=20000, rng=rng)
        fresh = banana_panel(sw, n=20000, rng=rng).exact
        # two steps of T = 1 s: heading = 1.5 n_1 + 0.5 n_2, so its std is sqrt(2.5) σ_ω
        assert p.heading_std == pytest.approx(math.sqrt(2.5) * sw, rel=1e-9)
        assert np.mean(p.exact_region.contains(fresh)) == pytest.approx(0.95, abs=0.015)
        shares[sw] = np.mean(p.cgd_region.contains(fresh))
        # the image of ε_y = a ε_θ under μ·exp is a circle through μ; ε_θ = ±π both land on its far point
        a = p.P[1, 2] / p.P[2, 2]
        far = p.mean[:2, 2] + p.mean[:2, :2] @ np.array([-2 * a, 0.0])
        assert p.cgd_region.contains(far[None])[0] == (sw == 1.0)  # closed into a ring only at σ_ω = 1
        assert not p.exact_region.contains(far[None])[0]  # where the exact motion does not go
    assert shares[0.1] == pytest.approx(0.95, abs=0.015)
    assert shares[0.6] < 0.85 and shares[1.0] < 0.7


def _capture(monkeypatch):
    """Keep the figure that would be saved (and skip writing it)."""
    seen = []

    def fake_save(fig, path, pdf):
        seen.append(fig)
        return []

    monkeypatch.setattr(figures, "_save", fake_save)
    monkeypatch.setattr(figures._plt(), "close", lambda fig: None)
    return seen


def test_banana_figure_draws_the_exact_region_and_explains_the_ring(monkeypatch, tmp_path):
    seen = _capture(monkeypatch)
    figures.banana_figure(tmp_path / "b.png", sigmas=(0.1, 1.0), n=2000)
    fig = seen[0]
    texts = [t.get_text() for f in [fig, *fig.subfigs] for t in f.texts]
    assert BANANA_CAPTION in texts and "ring" in BANANA_CAPTION
    labels = [t.get_text() for f in fig.subfigs for leg in f.legends for t in leg.get_texts()]
    assert any(label.startswith("exact distribution, 95 %") for label in labels)
    axes = fig.subfigs[0].axes
    assert all(len(ax.collections) >= 3 for ax in axes)  # samples + exact and LG-EKF contours
    assert any("heading std 1.58 rad" in t.get_text() for t in axes[1].texts)


def test_trajectory_panels_fit_their_own_data(monkeypatch, tmp_path):
    seen = _capture(monkeypatch)
    figures.trajectories_figure(tmp_path / "t.png")
    seen[0].canvas.draw()  # the limits as saved (an equal aspect on "datalim" only applies at drawing)
    axes = seen[0].axes
    assert len(axes) == 3
    for ax in axes:
        assert ax.get_aspect() == 1.0
        data = np.vstack([line.get_xydata() for line in ax.lines] + [c.get_offsets() for c in ax.collections])
        (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
        assert x0 <= data[:, 0].min() and data[:, 0].max() <= x1
        assert y0 <= data[:, 1].min() and data[:, 1].max() <= y1
        # no more than about a metre of empty margin beyond the data on any side
        assert data[:, 0].min() - x0 < 0.06 * np.ptp(data[:, 0]) + 0.5
        assert y1 - data[:, 1].max() < 0.06 * np.ptp(data[:, 1]) + 0.5
    # the nearly straight σ_ω = 0.01 track: a few metres high, not the ±15 m of a shared square axis
    assert np.diff(axes[0].get_ylim())[0] < 6.0
