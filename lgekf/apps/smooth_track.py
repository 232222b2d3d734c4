"""`lgekf track --smooth` and `--tune`: smoothed columns and noise learned from the file's own tracks.

Smoothed columns (``smooth_<state>``, ``smooth_std_<state>``, after ``flag``): the RTS smoother on the group
(``lgekf.estimators.smoother``) over each monitored segment of an object (its rows 2, 3, ... up to its first
re-initialisation, then from each re-initialisation to the next), from the filter's estimate at the segment's
start with the noise the filter used there. The rows of a start or re-initialisation (an object's rows 0 and 1, an
alarm's row) repeat the filter columns; the filter columns are those of the run without ``--smooth``. An object
whose smoothed values are not all finite keeps the filter's values in its smoothed columns (the caller flags it).

``--tune``: ``lgekf.estimators.noise.tuning.learn_noise`` on all objects of the file (each object's first
measurement and the first one at least 1 s later start it), per model; a given ``--meas-std`` is held fixed,
a given ``--accel-std`` is kept (that model is not tuned). The optimiser starts from the noise ``lgekf track``
estimates from the data without ``--tune`` (``lgekf.apps.defaults.NoisePlan.tune_starts``, ``data_starts``) and
from the model's defaults; the fit is never below the best valid start's log-likelihood (``learn_noise``).
"""

from __future__ import annotations

import numpy as np

from ..core.covariance import unpack
from ..core.registry import base_measurement, get_measurement, get_model
from ..estimators.smoother import smooth_segments
from ..estimators.noise.em import em_or_lbfgs, learn_noise_em
from ..estimators.noise.tuning import NoiseFit, learn_noise

__all__ = ["smoothed_columns", "smooth_segments_of", "implausible_rows", "SMOOTH_GATE", "tune_models", "learn_on_dataset",
           "noisy_tracks", "DATA_START"]

#: the label of the start taken from the data's noise estimate (``NoiseFit.starts``, the report)
DATA_START = "data"


def smooth_segments_of(starts, alarms) -> tuple:
    """The monitored segments of every object: (first rows (S,), lengths (S,), start rows (S,), noise scales (S,)).

    An object's first segment starts at its row 2 from its two-point start at row 1; each re-initialisation at a row g
    (``alarms`` of ``track_monitored``, rows counted as in ``starts``) ends the segment before it and starts one at
    g + 1 from the re-initialised estimate at g, with the alarm's noise inflation ``Alarm.scale``."""
    starts = np.asarray(starts, dtype=np.int64)
    cuts = {}
    for al in alarms:
        if al.reinitialised:
            cuts.setdefault(al.obj, []).append((al.row, al.scale))
    first, length, start, scale = [], [], [], []
    for b in range(len(starts) - 1):
        a, e = int(starts[b]), int(starts[b + 1])
        bounds = [(a + 1, 1.0)] + sorted(cuts.get(b, []))
        for i, (g, sc) in enumerate(bounds):
            end = bounds[i + 1][0] if i + 1 < len(bounds) else e
            first.append(g + 1)
            length.append(max(end - g - 1, 0))
            start.append(g)
            scale.append(sc)
    return (np.array(first, dtype=np.int64), np.array(length, dtype=np.int64), np.array(start, dtype=np.int64),
            np.array(scale, dtype=float))


SMOOTH_GATE = 20.0  # a smoothed position this many (filter position std + measurement std) from the filter's: failed


def implausible_rows(x_f, sd_f, x_s, sd_s, meas_std) -> np.ndarray:
    """Rows (N,) where a smoother failed: a non-finite smoothed value (x_s, sd_s), or a smoothed position (columns 0, 1)
    further from the filter's than ``SMOOTH_GATE`` × (the filter's position std + ``meas_std``), or a smoothed position
    std above that bound (a smoothed estimate is at least as certain as the filtered one; a numerically broken backward
    pass is not)."""
    bound = SMOOTH_GATE * (np.hypot(sd_f[:, 0], sd_f[:, 1]) + meas_std)
    with np.errstate(invalid="ignore", over="ignore"):
        far = np.hypot(x_s[:, 0] - x_f[:, 0], x_s[:, 1] - x_f[:, 1]) > bound
        wide = np.hypot(sd_s[:, 0], sd_s[:, 1]) > bound
    return ~np.isfinite(x_s).all(axis=1) | ~np.isfinite(sd_s).all(axis=1) | far | wide


def smoothed_columns(model, measurement, t, zm, starts, tracked, q, r):
    """(values (N, 2n), failed objects): smoothed states and stds of every row (module docstring).

    The RTS smoother on the group runs over each monitored segment of ``tracked`` (``track_monitored``'s output: its
    states, packed covariances and alarms), from the filter's own estimate at the segment's start row (the two-point
    start or a re-initialisation) with the noise the filter used there (q, r × the object's inflation), so that the
    smoothed and the filtered columns describe the same run. Rows that start a segment repeat the filter's values. An
    object with a non-finite smoothed value keeps the filter's values on all its rows and is listed in ``failed``.
    zm (N, m) the measurements and r their noise stds, q the process-noise stds.
    """
    spec = get_model(model)
    starts = np.asarray(starts, dtype=np.int64)
    t = np.asarray(t, float)
    first, length, start, scale = smooth_segments_of(starts, tracked.alarms)
    xs = tracked.x.copy()
    ps = tracked.p.copy()
    for sc in np.unique(scale):  # one smoother call per noise level (the kernels take one q, r)
        sel = np.flatnonzero((scale == sc) & (length > 0))
        if sel.size == 0:
            continue
        x0 = tracked.x[start[sel]]
        P0 = unpack(tracked.p[start[sel]], spec.n)
        xk, pk = smooth_segments(model, measurement, t, zm, first[sel], length[sel], x0, P0, np.asarray(q) * sc, np.asarray(r) * sc)
        rows = np.concatenate([np.arange(f, f + n) for f, n in zip(first[sel], length[sel])])
        xs[rows] = xk[rows]
        ps[rows] = pk[rows]
    i, j = np.triu_indices(spec.n)
    diag = np.flatnonzero(i == j)
    out = np.hstack([xs, np.sqrt(np.maximum(ps[:, diag], 0.0))])
    failed = []
    filt = np.hstack([tracked.x, np.sqrt(np.maximum(tracked.p[:, diag], 0.0))])
    n = spec.n
    bad = implausible_rows(filt[:, :n], filt[:, n:], out[:, :n], out[:, n:], float(np.asarray(r).reshape(-1)[0]))
    for b in np.unique(np.searchsorted(starts, np.flatnonzero(bad), side="right") - 1):
        a, e = starts[b], starts[b + 1]
        out[a:e] = filt[a:e]
        failed.append(int(b))
    return out, failed


def tune_models(t, z, starts, models, measurement: dict, meas_std=None, given_q=None, heading=None, omega_std=0.5,
                method="lbfgs", start_noise: dict | None = None):
    """{model: NoiseFit} for every model not in ``given_q`` (learned from all objects of the file); ``method`` "em":
    EM where it applies (``lgekf.estimators.noise.em.em_or_lbfgs``), else the likelihood optimiser.

    ``start_noise`` ({model: (accel_std, meas_std)}, e.g. ``NoisePlan.tune_starts``): a further start of each model's fit,
    labelled ``DATA_START`` and tried before the model's defaults; the fit's log-likelihood is never below the best
    valid start's (``lgekf.estimators.noise.tuning.learn_noise``)."""
    fits: dict[str, NoiseFit] = {}
    starts = np.asarray(starts, dtype=np.int64)
    for m in models:
        if given_q and m in given_q:
            continue
        meas = measurement[m]
        spec = get_measurement(meas)
        zz = spec.columns(z, heading)
        tracks = [(t[a:b], zz[a:b]) for a, b in zip(starts[:-1], starts[1:])]
        fixed = meas_std if meas_std is not None and not spec.has_angle else None  # a scalar fixes no heading std
        learn = learn_noise_em if em_or_lbfgs(m, meas, method) == "em" else learn_noise
        first = {DATA_START: start_noise[m]} if start_noise and m in start_noise else None
        fits[m] = learn(m, tracks, measurement=meas, meas_std=fixed, omega_std=omega_std, starts=first)
    return fits


def noisy_tracks(ds, meas_std: float, seeds, seed_rng) -> list:
    """[(t, z)]: a ``lgekf.io.datasets.Dataset``'s tracks with N(0, meas_std²) noise added (noise stream 1 of
    ``lgekf evaluate``), every seed's draw a track of its own."""
    tracks = []
    for seed in seeds:
        z = ds.p + meas_std * seed_rng(seed, 1, ds.name).standard_normal(ds.p.shape)
        tracks += [(ds.t[a:b], z[a:b]) for a, b in zip(ds.starts[:-1], ds.starts[1:])]
    return tracks


def learn_on_dataset(ds, meas_std: float, seeds, seed_rng, models, method="lbfgs") -> dict:
    """{model: NoiseFit} learned on ``noisy_tracks`` of a dataset, the measurement std held at ``meas_std``.
    A model whose noise cannot be learned (too few points) maps to the reason (a str). ``method`` "em": EM for
    the models where it applies (``em_or_lbfgs``)."""
    tracks = noisy_tracks(ds, meas_std, seeds, seed_rng)
    out = {}
    for m in models:
        meas = base_measurement(get_model(m).space)  # the positions of the model's space (position, position3)
        try:
            learn = learn_noise_em if em_or_lbfgs(m, meas, method) == "em" else learn_noise
            out[m] = learn(m, tracks, meas_std=meas_std, measurement=meas)
        except ValueError as e:  # too few points: the caller keeps the default noise and says why
            out[m] = str(e)
    return out
