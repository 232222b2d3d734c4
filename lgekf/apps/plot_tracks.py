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

``path`` ending in ``.html`` writes the same two figures as one self-contained interactive page (``plot_tracks_html``,
plotly, the optional extra ``lgekf[html]``; plotly.js is inlined, so the page works offline): zoom, pan, hover for
the values, click a legend entry to hide an object.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["plot_tracks", "plot_tracks_html", "object_column", "MAX_OBJECTS", "HTML_INSTALL_HINT"]

MAX_OBJECTS = 12  # drawn by default (the first ones in the file); ``ids`` picks others
CHI2_95_2DOF = math.sqrt(5.991464547107979)  # the 95 % ellipse of a 2-D Gaussian: 2.4477 σ
ELLIPSES_PER_OBJECT = 15
HTML_INSTALL_HINT = 'an .html page needs plotly: pip install "lgekf[html]" (or "plotly>=5")'


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


def _ellipse_axes(sx, sy, cxy, theta=0.0):
    """(eigenvalues ascending, eigenvectors) of the position covariance [[sx², cxy], [cxy, sy²]] given in axes turned
    by ``theta`` (the body axes of the LG models; 0: the world axes), turned into the world frame: R(θ) C R(θ)ᵀ; None
    when it is not a covariance (not finite, negative)."""
    c, s = math.cos(theta), math.sin(theta)
    R = np.array([[c, -s], [s, c]])
    C = R @ np.array([[sx * sx, cxy], [cxy, sy * sy]]) @ R.T
    if not np.all(np.isfinite(C)):
        return None
    w, V = np.linalg.eigh(C)
    if not np.all(np.isfinite(w)) or w[0] < 0:
        return None
    return w, V


def _ellipse(ax, x, y, sx, sy, cxy, color, theta=0.0):
    """The 95 % ellipse (``_ellipse_axes``) as a matplotlib patch on ``ax``."""
    from matplotlib.patches import Ellipse

    e = _ellipse_axes(sx, sy, cxy, theta)
    if e is None:
        return
    w, V = e
    angle = math.degrees(math.atan2(V[1, 1], V[0, 1]))
    ax.add_patch(Ellipse((x, y), 2 * CHI2_95_2DOF * math.sqrt(w[1]), 2 * CHI2_95_2DOF * math.sqrt(w[0]), angle=angle,
                         fill=False, lw=0.6, color=color, alpha=0.7))


def _ellipse_points(x, y, sx, sy, cxy, theta=0.0, n=48):
    """The 95 % ellipse (``_ellipse_axes``) as n + 1 points of a closed polyline, or None."""
    e = _ellipse_axes(sx, sy, cxy, theta)
    if e is None:
        return None
    w, V = e
    a = np.linspace(0.0, 2 * math.pi, n + 1)
    u = CHI2_95_2DOF * (np.sqrt(w[1]) * np.outer(np.cos(a), V[:, 1]) + np.sqrt(w[0]) * np.outer(np.sin(a), V[:, 0]))
    return x + u[:, 0], y + u[:, 1]


def _choose(tracks, ids):
    """(object column, every object in the table's order, the objects to draw)."""
    key = object_column(tracks.columns)
    order = list(dict.fromkeys(tracks[key].astype(str)))
    if ids is not None:
        wanted = [str(i) for i in ids]
        missing = [i for i in wanted if i not in order]
        if missing:
            raise ValueError(f"--id: no object {', '.join(missing)} in the track table (it has {', '.join(order[:5])}"
                             f"{', ...' if len(order) > 5 else ''})")
        return key, order, wanted
    return key, order, order[:MAX_OBJECTS]


def _flagged(df):
    """The rows of one object flagged as diverged (bit 1 of ``flag``), a boolean array."""
    if "flag" not in df.columns:
        return np.zeros(len(df), dtype=bool)
    return (df["flag"].to_numpy().astype(int) & 1) > 0


def _motion(df):
    """(speed, unwrapped course, their stds or None, the course's std at most π/2) of one object's rows."""
    speed, course, s_speed, s_course = _course_speed(df)
    course = np.unwrap(course)  # continuous through ±π (an object heading west would jump between the two)
    if s_course is not None:
        s_course = np.minimum(s_course, math.pi / 2)  # a band wider than ±π says only "unknown"
    return speed, course, s_speed, s_course


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
        Also save the figure there (.png, .svg or .pdf); a path ending in ``.html`` writes the interactive page of
        ``plot_tracks_html`` instead, and the figure returned is then plotly's (needs ``lgekf[html]``).
    """
    if path is not None and str(path).lower().endswith(".html"):
        return plot_tracks_html(tracks, measurements, ids, ellipse_every, path, title)
    import matplotlib

    if matplotlib.get_backend().lower() not in ("agg", "pdf", "svg", "cairo") and path is not None:
        matplotlib.use("Agg", force=True)
    import matplotlib.pyplot as plt

    key, order, chosen = _choose(tracks, ids)
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
        bad = _flagged(df)
        if bad.any():
            ax_map.plot(df["x"][bad], df["y"][bad], "x", color="red", ms=5,
                        label="flagged (divergence)" if flagged_label else None)
            flagged_label = False
        speed, course, s_speed, s_course = _motion(df)
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


def _rgb(n: int) -> str:
    """The n-th colour of matplotlib's tab10 (the PNG's colours), as ``rgb(r,g,b)``."""
    tab10 = ("#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf")
    h = tab10[n % 10]
    return f"rgb({int(h[1:3], 16)},{int(h[3:5], 16)},{int(h[5:7], 16)})"


def _rgba(rgb: str, alpha: float) -> str:
    return rgb.replace("rgb(", "rgba(").replace(")", f",{alpha})")


def _plotly():
    try:
        import plotly.graph_objects as go
        from plotly.subplots import make_subplots
    except ImportError:
        raise ImportError(HTML_INSTALL_HINT) from None
    return go, make_subplots


def _list(a) -> list:
    """Plain floats with None for NaN/inf: plotly draws None as a gap (and writes plain JSON, not base64 arrays)."""
    return [float(v) if math.isfinite(v) else None for v in np.asarray(a, dtype=float).tolist()]


def plot_tracks_html(tracks, measurements=None, ids=None, ellipse_every: int | None = None, path=None,
                     title: str | None = None):
    """The figure of ``plot_tracks`` as an interactive plotly figure; returns (figure, the object ids drawn).

    The same content as the PNG: on the map (left, equal axes) per object its measurements (dots), track (line),
    smoothed track (dashed, with ``smooth_x``), 95 % position ellipses (one trace per object) and flagged rows (red
    crosses); on the right speed, course and turn rate against time with their ±2σ bands (filled) and the smoothed
    turn rate. Every trace carries ``meta = {"object": id, "kind": ...}`` (``track``, ``measurements``, ``smoothed``,
    ``ellipses``, ``flagged``, ``speed``, ``course``, ``turn rate`` and ``... band``); an object's traces share one
    legend group, so a click on its name hides them all.

    Parameters
    ----------
    tracks, measurements, ids, ellipse_every, title
        As for ``plot_tracks``.
    path : str or Path, optional
        Write the page there: one self-contained HTML file (plotly.js inlined, about 5 MB; works offline).

    Raises
    ------
    ImportError
        plotly is not installed (the message names the extra, ``lgekf[html]``).
    """
    go, make_subplots = _plotly()
    key, order, chosen = _choose(tracks, ids)
    smooth = "smooth_x" in tracks.columns
    more = f" (first {len(chosen)} of {len(order)} objects)" if ids is None and len(order) > len(chosen) else ""
    fig = make_subplots(rows=3, cols=2, column_widths=[0.55, 0.45], horizontal_spacing=0.08, vertical_spacing=0.06,
                        specs=[[{"rowspan": 3}, {}], [None, {}], [None, {}]], shared_xaxes=False,
                        subplot_titles=("95 % position ellipses" + (", smoothed dashed" if smooth else ""),
                                        "speed, ±2σ (first order, diagonal stds)", "course (unwrapped), ±2σ",
                                        "turn rate, ±2σ"))
    any_omega = False
    flag_legend = True
    for n, name in enumerate(chosen):
        df = tracks[tracks[key].astype(str) == name]
        c = _rgb(n)
        group = dict(legendgroup=name)
        t = _list(df["t"])
        if measurements is not None and name in measurements:
            _, z = measurements[name]
            fig.add_trace(go.Scatter(x=_list(z[:, 0]), y=_list(z[:, 1]), mode="markers", name=f"{name} measurements",
                                     marker=dict(size=3, color=_rgba(c, 0.4)), showlegend=False,
                                     meta={"object": name, "kind": "measurements"}, **group), row=1, col=1)
        fig.add_trace(go.Scatter(x=_list(df["x"]), y=_list(df["y"]), mode="lines", name=name, line=dict(color=c, width=1.6),
                                 customdata=t, hovertemplate=f"{name}<br>t %{{customdata}} s<br>x %{{x}} m<br>y %{{y}} m"
                                 "<extra></extra>", meta={"object": name, "kind": "track"}, **group), row=1, col=1)
        if smooth:
            fig.add_trace(go.Scatter(x=_list(df["smooth_x"]), y=_list(df["smooth_y"]), mode="lines",
                                     name=f"{name} smoothed", line=dict(color=c, width=1.1, dash="dash"), showlegend=False,
                                     meta={"object": name, "kind": "smoothed"}, **group), row=1, col=1)
        every = ellipse_every or max(1, len(df) // ELLIPSES_PER_OBJECT)
        cxy = df["cov_0_1"].to_numpy() if "cov_0_1" in df.columns else np.zeros(len(df))
        body = body_frame_position(df.columns)
        ex, ey = [], []
        for i in range(0, len(df), every):
            pts = _ellipse_points(df["x"].iat[i], df["y"].iat[i], df["std_x"].iat[i], df["std_y"].iat[i], cxy[i],
                                  df["theta"].iat[i] if body else 0.0)
            if pts is not None:
                ex += _list(pts[0]) + [None]
                ey += _list(pts[1]) + [None]
        if ex:
            fig.add_trace(go.Scatter(x=ex, y=ey, mode="lines", name=f"{name} 95 % ellipses", showlegend=False,
                                     line=dict(color=_rgba(c, 0.7), width=0.8), hoverinfo="skip",
                                     meta={"object": name, "kind": "ellipses", "every": every}, **group), row=1, col=1)
        bad = _flagged(df)
        if bad.any():
            fig.add_trace(go.Scatter(x=_list(df["x"][bad]), y=_list(df["y"][bad]), mode="markers",
                                     name="flagged (divergence)", legendgroup="flagged", showlegend=flag_legend,
                                     marker=dict(symbol="x", size=7, color="red"), customdata=_list(df["t"][bad]),
                                     hovertemplate=f"{name} flagged<br>t %{{customdata}} s<extra></extra>",
                                     meta={"object": name, "kind": "flagged"}), row=1, col=1)
            flag_legend = False
        speed, course, s_speed, s_course = _motion(df)
        series = [(1, "speed", speed, s_speed), (2, "course", course, s_course)]
        if "omega" in df.columns:
            any_omega = True
            series.append((3, "turn rate", df["omega"].to_numpy(),
                           df["std_omega"].to_numpy() if "std_omega" in df.columns else None))
        for row, kind, val, sd in series:
            if sd is not None:  # the band: a closed polygon, upper edge forward, lower edge back
                fig.add_trace(go.Scatter(x=t + t[::-1], y=_list(val + 2 * sd) + _list(val - 2 * sd)[::-1], fill="toself",
                                         fillcolor=_rgba(c, 0.15), line=dict(width=0), mode="lines", hoverinfo="skip",
                                         name=f"{name} {kind} ±2σ", showlegend=False,
                                         meta={"object": name, "kind": f"{kind} band"}, **group), row=row, col=2)
            fig.add_trace(go.Scatter(x=t, y=_list(val), mode="lines", name=f"{name} {kind}", showlegend=False,
                                     line=dict(color=c, width=1.1), meta={"object": name, "kind": kind}, **group),
                          row=row, col=2)
        if smooth and "smooth_omega" in df.columns:
            fig.add_trace(go.Scatter(x=t, y=_list(df["smooth_omega"]), mode="lines", name=f"{name} smoothed turn rate",
                                     showlegend=False, line=dict(color=c, width=0.9, dash="dash"),
                                     meta={"object": name, "kind": "smoothed turn rate"}, **group), row=3, col=2)
    fig.update_xaxes(title_text="x (m)", row=1, col=1)
    fig.update_yaxes(title_text="y (m)", scaleanchor="x", scaleratio=1, row=1, col=1)  # equal axes, as the PNG
    fig.update_yaxes(title_text="speed (m/s)", row=1, col=2)
    fig.update_yaxes(title_text="course (rad)", row=2, col=2)
    fig.update_yaxes(title_text="turn rate (rad/s)", row=3, col=2)
    fig.update_xaxes(matches="x2", row=2, col=2)
    fig.update_xaxes(matches="x2", title_text="t (s)", row=3, col=2)
    if not any_omega:
        fig.add_annotation(text="no turn rate in this model's state", showarrow=False, row=3, col=2,
                           x=0.5, y=0.5, xref="x4 domain", yref="y4 domain")
    fig.update_layout(title=(title or "tracks") + more, height=760, template="plotly_white",
                      legend=dict(title="objects (click to hide)", font=dict(size=11)), margin=dict(l=60, r=20, t=70, b=50))
    if path is not None:
        fig.write_html(path, include_plotlyjs=True, full_html=True, config={"scrollZoom": True, "displaylogo": False})
    return fig, chosen
