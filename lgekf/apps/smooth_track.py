"""`lgekf track --smooth` and `--tune`: smoothed columns and noise learned from the file's own tracks.

Smoothed columns (``smooth_<state>``, ``smooth_std_<state>``, after ``flag``): the RTS smoother on the group
(``lgekf.estimators.smoother``) over each object's rows 2, 3, ... from the same two-point start as the
filter columns, with the same noise. Rows 0 and 1 of an object (its two-point initialisation) repeat the
filter columns. The smoother runs without the divergence monitor: for an object with an alarm (flag 1
somewhere) the smoothed columns are those of the unmonitored filter from its first start.

``--tune``: ``lgekf.estimators.tuning.learn_noise`` on all objects of the file (each object's first
measurement and the first one at least 1 s later start it), per model; a given ``--meas-std`` is held fixed,
a given ``--accel-std`` is kept (that model is not tuned). The optimiser starts from the noise ``lgekf track``
estimates from the data without ``--tune`` (``lgekf.apps.defaults.plan_noise``; ``plan_starts``) and from the
model's defaults; the fit is never below the best valid start's log-likelihood (``learn_noise``).
"""

from __future__ import annotations

import numpy as np

from ..core.registry import get_model
from ..estimators.smoother import smooth_segments
from ..estimators.em import em_or_lbfgs, learn_noise_em
from ..estimators.tuning import NoiseFit, learn_noise
from .defaults import plan_noise
from .divergence import MonitorConfig
from .track import DEFAULT_HEADING_STD, DEFAULT_OMEGA_STD, TRACK_HEADING_CAP

__all__ = ["smoothed_columns", "smooth_column_names", "tune_models", "plan_starts", "data_starts", "learn_on_dataset",
           "noisy_tracks", "DATA_START"]

#: the label of the start taken from the data's noise estimate (``NoiseFit.starts``, the report)
DATA_START = "data"


def smooth_column_names(model: str) -> list:
    """The header of the smoothed columns of ``model``."""
    names = get_model(model).state_names
    return [f"smooth_{s}" for s in names] + [f"smooth_std_{s}" for s in names]


def smoothed_columns(model, measurement, t, zm, starts, x0, P0, q, r, x_filt, p_filt):
    """(N, 2n): smoothed states and stds of every row (module docstring).

    zm (N, m) the measurements and r their noise stds, x0 (B, n) / P0 (B, n, n) each object's two-point start
    at its row 1, q the process-noise stds (``lgekf.apps.track.smoothing_inputs`` gives them all);
    x_filt, p_filt the filter's columns (kept for each object's first two rows).
    """
    spec = get_model(model)
    starts = np.asarray(starts, dtype=np.int64)
    xs, ps = smooth_segments(model, measurement, np.asarray(t, float), zm, starts[:-1] + 2, np.diff(starts) - 2, x0, P0, q, r)
    i0 = starts[:-1]
    for off in (0, 1):
        xs[i0 + off] = x_filt[i0 + off]
        ps[i0 + off] = p_filt[i0 + off]
    i, j = np.triu_indices(spec.n)
    diag = np.flatnonzero(i == j)
    return np.hstack([xs, np.sqrt(np.maximum(ps[:, diag], 0.0))])


def tune_models(t, z, starts, models, measurement: dict, meas_std=None, given_q=None, heading=None, omega_std=0.5,
                method="lbfgs", start_noise: dict | None = None):
    """{model: NoiseFit} for every model not in ``given_q`` (learned from all objects of the file); ``method`` "em":
    EM where it applies (``lgekf.estimators.em.em_or_lbfgs``), else the likelihood optimiser.

    ``start_noise`` ({model: (accel_std, meas_std)}, e.g. ``plan_starts``): a further start of each model's fit,
    labelled ``DATA_START`` and tried before the model's defaults; the fit's log-likelihood is never below the best
    valid start's (``lgekf.estimators.tuning.learn_noise``)."""
    fits: dict[str, NoiseFit] = {}
    starts = np.asarray(starts, dtype=np.int64)
    for m in models:
        if given_q and m in given_q:
            continue
        meas = measurement[m]
        cols = [z] if meas == "position" else [z, heading[:, None]]
        zz = np.hstack(cols)
        tracks = [(t[a:b], zz[a:b]) for a, b in zip(starts[:-1], starts[1:])]
        fixed = None
        if meas_std is not None:
            fixed = meas_std if meas == "position" else None
        learn = learn_noise_em if em_or_lbfgs(m, meas, method) == "em" else learn_noise
        first = {DATA_START: start_noise[m]} if start_noise and m in start_noise else None
        fits[m] = learn(m, tracks, measurement=meas, meas_std=fixed, omega_std=omega_std, starts=first)
    return fits


def plan_starts(plan, measurement: dict, heading_std: float = DEFAULT_HEADING_STD) -> dict:
    """{model: (accel_std, meas_std)}: the noise a ``lgekf.apps.defaults.NoisePlan`` gives each of its models, as
    the starts of ``tune_models``: the plan's measurement std, for pose measurements (``measurement[model]``) with
    ``heading_std`` for the heading entry."""
    out = {}
    for m, q in plan.accel_std.items():
        meas = get_model(m).measurement(measurement.get(m, "position"))
        r = np.full(len(meas.noise_names), float(plan.meas_std))
        r[list(meas.angles)] = heading_std
        out[m] = (tuple(q), tuple(r))
    return out


def data_starts(t, z, starts, models, meas_std=None, omega_std: float = DEFAULT_OMEGA_STD) -> dict:
    """``plan_starts`` of the noise ``lgekf track`` estimates from the data (position measurements, the divergence
    monitor on, the heading prior of ``lgekf track``), for callers that have no plan yet (the IMM's ``--tune``)."""
    plan = plan_noise(t, z, starts, list(models), meas_std=meas_std, omega_std=omega_std, heading_std=DEFAULT_HEADING_STD,
                      heading_cap=TRACK_HEADING_CAP, monitor=MonitorConfig())
    return plan_starts(plan, {})


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
        try:
            learn = learn_noise_em if em_or_lbfgs(m, "position", method) == "em" else learn_noise
            out[m] = learn(m, tracks, meas_std=meas_std)
        except ValueError as e:  # too few points: the caller keeps the default noise and says why
            out[m] = str(e)
    return out
