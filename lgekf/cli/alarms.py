"""The warning lines of ``lgekf track`` shared by every estimator (the single models, the IMM): divergence, failed
smoothing, a given measurement std that misfits the data."""

from __future__ import annotations

import sys

from ..apps.divergence import MonitorConfig
from ..apps.noise import measurement_std

__all__ = ["divergence_warnings", "smooth_failure_warnings", "warn_misfit", "misfit_line", "MAX_DIVERGENCE_LINES", "MEAS_STD_WARN_FACTOR"]

MAX_DIVERGENCE_LINES = 10  # per model; further diverged objects are summed up in one line
MEAS_STD_WARN_FACTOR = 2.0  # a given --meas-std this far from the data's estimate is warned about


def divergence_warnings(model, meas, alarms, flagged, statistic: str = "NIS") -> list:
    """One line per diverged object (at most MAX_DIVERGENCE_LINES, then one line for the rest), naming the input's line
    of its first diverged row (``Measurements.where``: "line N", "row N" of a table) and its t; ``statistic``: what the
    window test averages (the IMM's monitor: the posterior residuals' |e|²/r², not a NIS)."""
    first, count, scale = {}, {}, {}
    for al in alarms:
        first.setdefault(al.obj, al)
        count[al.obj] = count.get(al.obj, 0) + 1
        scale[al.obj] = al.scale
    lines = []
    for obj, al in list(first.items())[:MAX_DIVERGENCE_LINES]:
        if al.kind_name == "NIS":
            why = f"mean {statistic} {al.value:.3g} over its last {al.updates} updates > {al.limit:.3g}"
        elif al.kind_name == "speed":
            why = f"speed {al.value:.3g} m/s > {al.limit:.3g} m/s, far above the data's"
        else:
            why = "non-finite state or covariance"
        n = count[obj]
        cap = MonitorConfig().max_reinit
        stop = f"; monitoring stopped after {cap} re-initialisations (is the noise right?)" if n > cap else ""
        inflated = f"; its noise stds x{scale[obj]:.2g} from the repeated alarms on" if scale[obj] > 1 else ""
        where = getattr(meas, "where", lambda k: "")(al.row)  # the input's line of the row (grouping keeps them)
        at = f"{where} (t = {float(meas.t[al.row]):.15g} s)" if where else f"t = {meas.t[al.row]:.6g} s"
        lines.append(f"{model}: object {meas.labels[obj]} diverged at {at} ({why}); re-initialised "
                     f"from its last measurements{'' if n == 1 else f' ({min(n, cap)} times in all)'}{inflated}{stop}; "
                     f"rows flagged 1 in the flag column")
    rest = len(first) - MAX_DIVERGENCE_LINES
    if rest > 0:
        lines.append(f"{model}: {rest} more object{'s' if rest > 1 else ''} diverged and were re-initialised "
                     f"({flagged} rows flagged in all)")
    return lines


def smooth_failure_warnings(model, meas, failed, starts=None) -> list:
    """One line naming the objects (at most MAX_DIVERGENCE_LINES) whose smoother failed (``smooth_track.implausible_rows``),
    each with the input's line of its first row when ``starts`` (the objects' row offsets) is given."""
    if not failed:
        return []
    from ..apps.track import SMOOTH_FAILED

    def name(b):
        where = meas.where(int(starts[b])) if starts is not None and hasattr(meas, "where") else ""
        return f"{meas.labels[b]} ({where})" if where else str(meas.labels[b])

    names = ", ".join(name(b) for b in failed[:MAX_DIVERGENCE_LINES]) + (", ..." if len(failed) > MAX_DIVERGENCE_LINES else "")
    n = len(failed)
    return [f"{model}: the smoother failed (non-finite or far off the filter) on {n} object{'s' if n > 1 else ''} ({names}): their smooth_* "
            f"columns repeat the filter's; flag +{SMOOTH_FAILED} on their rows"]


def misfit_line(given: float, estimated: float | None) -> str | None:
    """The warning about a given ``--meas-std`` ``MEAS_STD_WARN_FACTOR`` or more off the data's estimate, else None."""
    if estimated is None or max(given / estimated, estimated / given) < MEAS_STD_WARN_FACTOR:
        return None
    return (f"--meas-std {given:g} m is {given / estimated:.2g}x the std estimated from the data ({estimated:.3g} m); "
            "leave --meas-std out to use the estimate")


def warn_misfit(meas_std, meas, starts) -> None:
    """One warning line when a given ``--meas-std`` is ``MEAS_STD_WARN_FACTOR`` or more off the data's estimate."""
    if meas_std is None:
        return
    est = measurement_std(meas.t, meas.z, starts)
    line = misfit_line(meas_std, est.meas_std if est.usable and not est.floored else None)
    if line is not None:
        print(f"lgekf track: warning: {line}", file=sys.stderr)
