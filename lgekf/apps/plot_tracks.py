"""Pictures of tracks (``lgekf plot``, ``lgekf.plot_tracks``): the map of measurements and estimates with 95 %
position ellipses and the flagged rows, beside speed, course and turn rate against time with ±2σ bands.

Input: a track table as ``lgekf track`` writes it (``id`` or, from ``--multi``, ``track``; ``t``, ``x``, ``y``, the
model's state and ``std_<state>``; ``speed``/``course`` when present; ``flag``; ``smooth_*`` with ``--smooth``).
The bands are first-order, from the diagonal stds the file holds (correlations are not in it without ``--full-cov``):
the turn rate ω ± 2σ_ω where ω is a state; the speed |v| of a body or world velocity (v_x, v_y) with
σ² = (v_x σ_vx)² + (v_y σ_vy)² / |v|² (or σ_v of a speed state, CTRV and SE(2)×R²); the course with σ² = σ_θ² +
((v_y σ_vx)² + (v_x σ_vy)²) / |v|⁴ (σ_θ only where the course adds the heading θ to the velocity's angle), or σ_ψ of
CTRV's course ψ (drawn unwrapped, its band at most ±π). The ellipses: chi-square 95 % (2 dof, 2.4477 σ) of the
position from std_x, std_y (and cov_0_1 when the file has the covariances), in the body axes for the LG models (their
P is in the tangent of the group: turned by θ into the world frame), else in the world axes.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["plot_tracks", "object_column", "MAX_OBJECTS"]

MAX_OBJECTS = 12  # drawn by default (the first ones in the file); ``ids`` picks others
CHI2_95_2DOF = math.sqrt(5.991464547107979)  # the 95 % ellipse of a 2-D Gaussian: 2.4477 σ
ELLIPSES_PER_OBJECT = 15


def object_column(columns) -> str:
    """The column that names objects: ``id`` (``lgekf track``) or ``track`` (``lgekf track --multi``)."""
    for name in ("id", "track"):
        if name in columns:
            return name
    raise ValueError("the track table has no id (or track) column; is it the output of lgekf track?")


def _course_speed(df):
    """(speed, course, their stds or None) of the rows of one object (module docstring)."""
    cols = df.columns
    vx = df["vx"].to_numpy() if "vx" in cols else None
    vy = df["vy"].to_numpy() if "vy" in cols else None
    if "speed" in cols:
        speed, course = df["speed"].to_numpy(), df["course"].to_numpy()
    elif vx is not None:
        speed, course = np.hypot(vx, vy), np.arctan2(vy, vx) + (df["theta"].to_numpy() if "theta" in cols else 0.0)
    else:  # CTRV / SE(2)xR2 without the motion columns (an older file)
        speed = df["v"].to_numpy()
        course = df["psi" if "psi" in cols else "theta"].to_numpy()
    s_speed = s_course = None
    if "std_v" in cols:
        s_speed = df["std_v"].to_numpy()
        s_course = df["std_psi" if "std_psi" in cols else "std_theta"].to_numpy() if ("std_psi" in cols or "std_theta" in cols) else None
    elif vx is not None and "std_vx" in cols:
        with np.errstate(invalid="ignore", divide="ignore"):
            v = np.maximum(np.hypot(vx, vy), 1e-9)
            sx, sy = df["std_vx"].to_numpy(), df["std_vy"].to_numpy()
            s_speed = np.hypot(vx * sx, vy * sy) / v
            s_course = np.hypot(vy * sx, vx * sy) / v ** 2
            if "std_theta" in cols:
                s_course = np.hypot(s_course, df["std_theta"].to_numpy())
    return speed, np.angle(np.exp(1j * course)), s_speed, s_course


def body_frame_position(columns) -> bool:
    """Whether the file's position stds are along the body axes: the LG models' (a ``theta`` state, P in the tangent of
    the group, X = μ·exp(ε)); not the IMM's (``mu_`` columns: its combined covariance is in the common coordinates,
    world x, y), CTRV's (``psi``) or CV's (world frame)."""
    return "theta" in columns and not any(str(c).startswith("mu_") for c in columns)


def _ellipse(ax, x, y, sx, sy, cxy, color, theta=0.0):
    """The 95 % ellipse of a position covariance [[sx², cxy], [cxy, sy²]] given in axes turned by ``theta`` (the body
    axes of the LG models; 0: the world axes), turned into the world frame: R(θ) C R(θ)ᵀ."""
    from matplotlib.patches import Ellipse

    c, s = math.cos(theta), math.sin(theta)
    R = np.array([[c, -s], [s, c]])
    C = R @ np.array([[sx * sx, cxy], [cxy, sy * sy]]) @ R.T
    w, V = np.linalg.eigh(C)
    if not np.all(np.isfinite(w)) or w[0] < 0:
        return
    angle = math.degrees(math.atan2(V[1, 1], V[0, 1]))
    ax.add_patch(Ellipse((x, y), 2 * CHI2_95_2DOF * math.sqrt(w[1]), 2 * CHI2_95_2DOF * math.sqrt(w[0]), angle=angle,
                         fill=False, lw=0.6, color=color, alpha=0.7))


def plot_tracks(tracks, measurements=None, ids=None, ellipse_every: int | None = None, path=None, title: str | None = None):
    """Draw tracks (module docstring); returns (figure, the object ids drawn).

    Parameters
    ----------
    tracks : pandas.DataFrame
        A track table (``lgekf.track`` returns one; or ``pandas.read_csv`` of ``lgekf track``'s output, ``id`` as str).
    measurements : mapping, optional
        {id: (t (N,), z (N, 2))} of the measured positions, drawn as dots under the tracks.
    ids : sequence of str, optional
        The objects to draw (default: the first ``MAX_OBJECTS`` in the table).
    ellipse_every : int, optional
        A 95 % position ellipse every this many rows of an object (default: about ``ELLIPSES_PER_OBJECT`` per object).
    path : str or Path, optional
        Also save the figure there (.png, .svg or .pdf).
    """
    import matplotlib

    if matplotlib.get_backend().lower() not in ("agg", "pdf", "svg", "cairo") and path is not None:
        matplotlib.use("Agg", force=True)
    import matplotlib.pyplot as plt

    key = object_column(tracks.columns)
    order = list(dict.fromkeys(tracks[key].astype(str)))
    if ids is not None:
        wanted = [str(i) for i in ids]
        missing = [i for i in wanted if i not in order]
        if missing:
            raise ValueError(f"--id: no object {', '.join(missing)} in the track table (it has {', '.join(order[:5])}"
                             f"{', ...' if len(order) > 5 else ''})")
        chosen = wanted
    else:
        chosen = order[:MAX_OBJECTS]
    fig = plt.figure(figsize=(13, 7.5), layout="constrained")
    gs = fig.add_gridspec(3, 2, width_ratios=(1.25, 1))
    ax_map = fig.add_subplot(gs[:, 0])
    ax_v, ax_c, ax_w = (fig.add_subplot(gs[i, 1]) for i in range(3))
    colors = plt.get_cmap("tab10")
    smooth = "smooth_x" in tracks.columns
    flagged_label = True
    for n, name in enumerate(chosen):
        df = tracks[tracks[key].astype(str) == name]
        c = colors(n % 10)
        t = df["t"].to_numpy()
        if measurements is not None and name in measurements:
            _, z = measurements[name]
            ax_map.plot(z[:, 0], z[:, 1], ".", ms=2.5, color=c, alpha=0.35)
        ax_map.plot(df["x"], df["y"], "-", lw=1.3, color=c, label=name)
        if smooth:
            ax_map.plot(df["smooth_x"], df["smooth_y"], "--", lw=1.0, color=c, alpha=0.8)
        every = ellipse_every or max(1, len(df) // ELLIPSES_PER_OBJECT)
        cxy = df["cov_0_1"].to_numpy() if "cov_0_1" in df.columns else np.zeros(len(df))
        body = body_frame_position(df.columns)
        for i in range(0, len(df), every):
            _ellipse(ax_map, df["x"].iat[i], df["y"].iat[i], df["std_x"].iat[i], df["std_y"].iat[i], cxy[i], c,
                     df["theta"].iat[i] if body else 0.0)
        if "flag" in df.columns:
            bad = (df["flag"].to_numpy().astype(int) & 1) > 0
            if bad.any():
                ax_map.plot(df["x"][bad], df["y"][bad], "x", color="red", ms=5,
                            label="flagged (divergence)" if flagged_label else None)
                flagged_label = False
        speed, course, s_speed, s_course = _course_speed(df)
        course = np.unwrap(course)  # continuous through ±π (an object heading west would jump between the two)
        if s_course is not None:
            s_course = np.minimum(s_course, math.pi / 2)  # a band wider than ±π says only "unknown"
        for ax, val, sd in ((ax_v, speed, s_speed), (ax_c, course, s_course)):
            ax.plot(t, val, color=c, lw=1.0)
            if sd is not None:
                ax.fill_between(t, val - 2 * sd, val + 2 * sd, color=c, alpha=0.15, lw=0)
        if "omega" in df.columns:
            w = df["omega"].to_numpy()
            ax_w.plot(t, w, color=c, lw=1.0)
            if "std_omega" in df.columns:
                sd = df["std_omega"].to_numpy()
                ax_w.fill_between(t, w - 2 * sd, w + 2 * sd, color=c, alpha=0.15, lw=0)
        if smooth and "smooth_omega" in df.columns:
            ax_w.plot(t, df["smooth_omega"], "--", color=c, lw=0.8)
    ax_map.set_aspect("equal", adjustable="datalim")
    ax_map.set_xlabel("x (m)")
    ax_map.set_ylabel("y (m)")
    more = f" (first {len(chosen)} of {len(order)} objects)" if ids is None and len(order) > len(chosen) else ""
    ax_map.set_title((title or "tracks") + more + ": 95 % position ellipses" + (", smoothed dashed" if smooth else ""))
    ax_map.legend(fontsize=7, loc="best", ncols=2)
    ax_v.set_ylabel("speed (m/s)")
    ax_c.set_ylabel("course (rad, unwrapped)")
    ax_w.set_ylabel("turn rate (rad/s)")
    ax_w.set_xlabel("t (s)")
    ax_v.set_title("±2σ bands (first order, diagonal stds)", fontsize=9)
    if not ax_w.lines:
        ax_w.text(0.5, 0.5, "no turn rate in this model's state", transform=ax_w.transAxes, ha="center", va="center")
    if path is not None:
        fig.savefig(path, dpi=130)
    return fig, chosen
