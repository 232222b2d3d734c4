"""Noise levels from the data (what ``lgekf track`` uses when no noise option is given).

Measurement std (``measurement_std``)
-------------------------------------
For every four consecutive measurements of an object (times t0 < t1 < t2 < t3, irregular steps allowed)
the least-squares quadratic through them leaves a one-dimensional residual, proportional to the third
divided difference ``e = Σ_j w_j z_j`` with ``w_j = 1 / Π_{k≠j} (t_j − t_k)``. Because Σ_j w_j t_j^p = 0
for p ≤ 2, e does not depend on the position, velocity or acceleration of the object, and with i.i.d.
noise of std σ per axis ``e / ‖w‖`` has std σ exactly (no bias factor: the normalisation is derived, not
fitted; ``tests/tracking/test_noise.py`` checks it by simulation). The estimate pools both axes of every window
of every object: ``σ̂ = median|e/‖w‖| / Φ⁻¹(0.75)`` (the MAD, robust to the windows where the motion is
not locally quadratic — sharp turns, braking — and to outlying measurements; each measurement is in four
windows, so a fraction ε of gross outliers spoils about 4ε of them and the MAD reads high by about 5 %
at ε = 1 %, 19 % at ε = 3 %). Four points are the shortest window with a residual: over thousands of windows a wider one does not estimate σ better but
spans more time, so more of the motion's jerk leaks in. The estimate is biased upwards where the
motion's third derivative over three steps is not small against the noise (≈ |jerk|·Δt³ ≳ 0.5 σ in
more than a few per cent of the windows): low rates with small noise on a turning vehicle. Measured on
simulated urban driving (``tests/tracking/test_noise.py``: σ 0.05–2 m, 0–30 m/s, 1–25 Hz, irregular or regular
steps): within 15 % everywhere except 1 Hz with σ = 0.05 m on a moving car (+17 to +25 %).

Process noise (``process_noise_search``)
----------------------------------------
With the measurement std fixed, each model's process noise is chosen by the prediction-error method: the
one that minimises the mean squared one-step prediction error ‖z_k − h(f(x̂_{k−1}, Δt_k))‖² of the filter
over the data (for a linear-Gaussian model the true noise minimises the innovation variance; for a
mismatched one this is the best predictor the model can be, and an unstable filter scores badly). The
candidates: the translational stds (``matched_noise`` "v") are k × the model's defaults (σ_a = k·0.5 m/s²)
with k on the grid 2^-3 … 2^5 (factors √2); the rotational stds ("w") start at ``min(default, σ_a/v_typ)``
(the turn-rate noise that a lateral acceleration σ_a gives at the data's typical speed ``v_typ``) and are
then searched on the default × 2^-6 … 2^0; k is searched again at the chosen rotational std. The
rotational noise matters: at 1–2 Hz the LG filters and CTRV become unstable with a turn-rate noise of
0.2–0.3 rad/s² that is harmless at 10 Hz, and the NIS (the consistency check one might use instead) hardly
depends on it. The search runs on a subsample of whole objects (at most ``SEARCH_ROWS`` rows). The median
NIS at the choice is reported (a consistent filter has the chi-square median, 1.39 for 2 degrees of freedom).
The scans are ``search_stages`` (a generator of stages of independent candidates): ``process_noise_search``
runs them one after the other, ``lgekf.apps.search.process_noise_searches`` in threads with the same result.

Typical speed (``chord_speeds``): the speed of the chord between a measurement and the first one at least
``CHORD_S`` = 1 s later (noise contributes √2·σ/1 s instead of √2·σ/Δt), median over all objects.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numba as nb
import numpy as np

from ..core.registry import get_model

__all__ = [
    "measurement_std", "NoiseEstimate", "chord_speeds", "typical_speed", "accel_std_family", "process_noise_search",
    "one_step_errors", "angular_grid", "with_angular", "SearchResult", "subsample_objects",
    "chi2_quantile", "SEARCH_ROWS", "CHORD_S", "MIN_MEAS_STD", "K_GRID", "search_stages", "candidate_key", "run_score",
    "object_measurement_stds", "OBJECT_WINDOWS",
]

MAD_SCALE = 0.6744897501960817  # Φ⁻¹(0.75): median |N(0, 1)|
MIN_MEAS_STD = 1e-3  # floor of the estimate (m): noise-free input would otherwise give 0
CHORD_S = 1.0
SEARCH_ROWS = 30_000
K_GRID = tuple(float(2.0 ** (e / 2)) for e in range(-6, 11))  # 0.125 ... 32 by factors √2


@dataclass
class NoiseEstimate:
    """The measurement std from the data and how it was found."""

    meas_std: float
    windows: int  # number of 4-point windows pooled
    floored: bool = False
    nonfinite: bool = False  # the residuals' median is not finite (meas_std nan): times too close, positions too large
    raw: float = float("nan")  # the estimate before the floor (when ``floored``)

    @property
    def usable(self) -> bool:
        """Whether ``meas_std`` is an estimate (windows to pool, a finite median)."""
        return self.windows > 0 and not self.nonfinite

    def describe(self) -> str:
        if self.windows == 0:
            return "no object has 4 measurements"
        if self.nonfinite:
            return (f"the quadratic residuals of {self.windows} windows of 4 points are not finite (times too close "
                    "together or positions too large)")
        extra = f", floor {MIN_MEAS_STD:g} m" if self.floored else ""
        return f"quadratic residuals of {self.windows} windows of 4 points{extra}"


@nb.njit(cache=True, nogil=True, inline="always")
def _window_residual(t, z, i, w, e):
    """The normalised third divided difference e / ‖w‖ of the window of rows i .. i + 3 into e (d,), one entry per
    coordinate of z (N, d) (``w``: scratch (4,))."""
    s2 = 0.0
    for j in range(4):
        d = 1.0
        for k in range(4):
            if k != j:
                d *= t[i + j] - t[i + k]
        w[j] = 1.0 / d
        s2 += w[j] * w[j]
    norm = math.sqrt(s2)
    for c in range(z.shape[1]):
        acc = 0.0
        for j in range(4):
            acc += w[j] * z[i + j, c]
        e[c] = acc / norm


@nb.njit(cache=True, nogil=True, error_model="numpy")  # times too close for the products: inf and NaN, not an exception
def _dd3(t, z, starts, out):
    """Normalised third divided differences of every 4-point window inside an object into out; returns
    how many were written (``_third_divided_differences``: the residuals themselves, for tests and inspection;
    ``measurement_std`` takes their median without holding them, ``_median_abs_residual``)."""
    n = 0
    w = np.empty(4)
    for b in range(starts.shape[0] - 1):
        for i in range(starts[b], starts[b + 1] - 3):
            _window_residual(t, z, i, w, out[n])
            n += 1
    return n


def _third_divided_differences(t, z, starts):
    """Normalised residuals e/‖w‖ (W, d) of every 4-point window inside an object (z (N, d), d = 2 or 3)."""
    out = np.empty((max(len(t), 0), np.shape(z)[1]))
    n = _dd3(np.ascontiguousarray(t, dtype=float), np.ascontiguousarray(z, dtype=float),
             np.asarray(starts, dtype=np.int64), out)
    return out[:n]


SELECT_CANDIDATES = 1 << 17  # ``_median_abs_residual`` collects up to this many values (1 MB) for the exact selection,
SELECT_SHIFT = 5  # or up to 1/32 of them (0.25 bytes per value) when that is more: two passes on typical residuals
_DIGIT = 16  # bits of a value's key fixed per counting pass
_MASK = (1 << _DIGIT) - 1


@nb.njit(cache=True, nogil=True, error_model="numpy")
def _residual_pass(t, z, starts, mode, prefix, shift, hist, cand):
    """One pass over |e_x|, |e_y| (and |e_z| in 3-D) of every window (the numbers of ``np.abs(_third_divided_differences(...))``),
    each keyed by its bits read as an unsigned integer (for numbers >= 0, and NaN after +inf, in their order).

    mode 1: ``hist[(key >> shift) & 0xFFFF] += 1`` over the values whose
    ``key >> (shift + 16)`` is ``prefix`` (every value when shift = 48); 2: the values whose ``key >> shift`` is
    ``prefix`` into ``cand`` (how many returned); 3: the smallest key above ``prefix`` (2^64 - 1 for none)."""
    w = np.empty(4)
    n = 0
    best = np.uint64(0xFFFFFFFFFFFFFFFF)
    mask = np.uint64(_MASK)
    sh = np.uint64(shift)
    top = np.uint64(min(shift + _DIGIT, 63))
    every = shift + _DIGIT >= 64
    d = z.shape[1]
    one = np.empty(d)
    bits = one.view(np.uint64)
    for b in range(starts.shape[0] - 1):
        for i in range(starts[b], starts[b + 1] - 3):
            _window_residual(t, z, i, w, one)
            for c in range(d):
                one[c] = abs(one[c])
            for c in range(d):
                key = bits[c]
                if mode == 1:
                    if every or (key >> top) == prefix:
                        hist[(key >> sh) & mask] += 1
                elif mode == 2:
                    if (key >> sh) == prefix:
                        cand[n] = one[c]
                        n += 1
                elif key > prefix and key < best:
                    best = key
    return best if mode == 3 else np.uint64(n)


def _as_float(key) -> float:
    return float(np.array([key], dtype=np.uint64).view(np.float64)[0])


def _median_abs_residual(t, z, starts) -> tuple:
    """(``np.median(np.abs(_third_divided_differences(t, z, starts)))``, number of windows): the same number,
    without holding the dW values (16 MB at 10⁶ rows in the plane).

    The bits of numbers >= 0 read as unsigned integers sort as the numbers do. Counting passes over the windows
    (each computes every residual again) fix the median's leading 16 bits at a time until the values sharing
    them are at most ``SELECT_CANDIDATES`` or 1/32 of all (with 4 mantissa bits fixed, about 3 % of Gaussian
    residuals share the median's: one counting pass); those are collected and partitioned (NumPy's ``partition``, as in
    ``np.median``). An even count needs the next value too: in the same group, or else the smallest value above
    the group (one more pass); the two are averaged as ``np.median`` does. A NaN among the values gives NaN, as in
    ``np.median``.
    """
    windows = int(np.maximum(np.diff(starts) - 3, 0).sum())  # 4-point windows inside the objects
    total = np.shape(z)[1] * windows
    if total == 0:
        return float("nan"), 0
    hist = np.zeros(1 << _DIGIT, np.int64)
    rank = (total - 1) // 2  # the (lower) middle value's rank from 0; with an even count the upper one is rank + 1
    prefix, shift, below = 0, 64, 0
    while True:
        shift -= _DIGIT
        hist[:] = 0
        _residual_pass(t, z, starts, 1, np.uint64(prefix), shift, hist, np.zeros(0))
        if shift == 64 - _DIGIT and hist[0x7FF0 + 1:].sum():  # keys above +inf's leading bits: a NaN, np.median's NaN
            return float("nan"), windows
        cum = np.cumsum(hist)
        d = int(np.searchsorted(cum, rank - below, side="right"))  # the next 16 bits of the value of that rank
        below += int(cum[d - 1]) if d else 0
        prefix = (prefix << _DIGIT) | d
        if int(hist[d]) <= max(SELECT_CANDIDATES, total >> SELECT_SHIFT) or shift == 0:
            break
    k, size = rank - below, int(hist[d])  # the middle value's rank in its group, the group's size
    if shift == 0:  # the group shares all 64 bits: one number
        lo = hi = _as_float(prefix)
    else:
        cand = np.empty(size)
        _residual_pass(t, z, starts, 2, np.uint64(prefix), shift, hist, cand)
        cand.partition([k, k + 1] if k + 1 < size else [k])
        lo = float(cand[k])
        hi = float(cand[k + 1]) if k + 1 < size else lo
    if total % 2:
        return lo, windows
    if k + 1 >= size:  # the upper middle value: the smallest above this group's keys
        last = (((prefix + 1) << shift) - 1) if shift else prefix
        hi = _as_float(_residual_pass(t, z, starts, 3, np.uint64(last), 0, hist, np.zeros(0)))
    return float(np.mean(np.array([lo, hi]))), windows


def measurement_std(t, z, starts) -> NoiseEstimate:
    """Robust measurement-noise std per axis (m) from objects' local quadratic residuals.

    Parameters
    ----------
    t : ndarray, (N,)
        Times sorted within each object (s).
    z : ndarray, (N, d)
        Positions (m), d = 2 (the plane) or 3 (3-D space).
    starts : ndarray, (B + 1,)
        Object offsets.

    Returns
    -------
    NoiseEstimate
        ``meas_std`` = MAD of the normalised third divided differences, pooled over the d axes, at least
        ``MIN_MEAS_STD``; ``windows`` = 0 (and ``meas_std`` nan) when no object has four measurements;
        ``nonfinite`` (and ``meas_std`` nan) when the residuals' median is not finite: times so close (about
        1e-103 s apart) that a window's weights overflow, or positions so large that the residuals do. Use
        ``usable`` before ``meas_std``.
    """
    med, windows = _median_abs_residual(np.ascontiguousarray(t, dtype=float), np.ascontiguousarray(np.asarray(z, float)),
                                        np.asarray(starts, np.int64))
    if windows == 0:
        return NoiseEstimate(float("nan"), 0)
    if not math.isfinite(med):  # times so close (about 1e-103 s) or positions so large that residuals overflow: no estimate
        return NoiseEstimate(float("nan"), windows, nonfinite=True)
    s = med / MAD_SCALE
    if s < MIN_MEAS_STD:
        return NoiseEstimate(MIN_MEAS_STD, windows, floored=True, raw=s)
    return NoiseEstimate(s, windows)


OBJECT_WINDOWS = 4096  # an object's own measurement std uses at most its first this many windows (≈ 2 % relative error)


@nb.njit(cache=True, nogil=True, error_model="numpy")
def _object_median_abs(t, z, starts, cap, med, count):
    """med[b] = the median of |e_x|, |e_y| (, |e_z|) over the first ``cap`` 4-point windows of object b (nan without
    any), count[b] = the windows used."""
    w = np.empty(4)
    d = z.shape[1]
    buf = np.empty(d * cap)
    e = np.empty(d)
    for b in range(starts.shape[0] - 1):
        n = min(max(starts[b + 1] - starts[b] - 3, 0), cap)
        for j in range(n):
            _window_residual(t, z, starts[b] + j, w, e)
            for c in range(d):
                buf[d * j + c] = abs(e[c])
        count[b] = n
        med[b] = np.median(buf[:d * n]) if n > 0 else np.nan


def object_measurement_stds(t, z, starts, cap: int = OBJECT_WINDOWS) -> tuple:
    """Each object's own measurement std (B,) (``measurement_std``'s estimator on its first ``cap`` windows only; nan
    for an object with fewer than 4 measurements or non-finite residuals) and the windows behind it (B,)."""
    B = len(starts) - 1
    med, count = np.empty(B), np.empty(B, dtype=np.int64)
    _object_median_abs(np.ascontiguousarray(t, dtype=float), np.ascontiguousarray(np.asarray(z, float)),
                       np.asarray(starts, np.int64), int(cap), med, count)
    with np.errstate(invalid="ignore"):
        r = np.where(np.isfinite(med), np.maximum(med / MAD_SCALE, MIN_MEAS_STD), np.nan)
    return r, count


@nb.njit(cache=True, nogil=True)
def _chords(t, z, starts, lag, out):
    """out[i] = |z_j - z_i| / (t_j - t_i), j the first row of i's object with t_j - t_i >= lag (else its
    last row); nan for an object's last row."""
    for b in range(starts.shape[0] - 1):
        a, e = starts[b], starts[b + 1]
        j = a + 1
        for i in range(a, e):
            if i == e - 1:
                out[i] = np.nan
                continue
            if j <= i:
                j = i + 1
            while j < e - 1 and t[j] - t[i] < lag:
                j += 1
            s2 = 0.0
            for c in range(z.shape[1]):
                s2 += (z[j, c] - z[i, c]) ** 2
            out[i] = math.sqrt(s2) / (t[j] - t[i])


def chord_speeds(t, z, starts, lag: float = CHORD_S) -> np.ndarray:
    """Chord speed (N,) of each row over at least ``lag`` s (nan on each object's last row)."""
    out = np.empty(len(t))
    _chords(np.ascontiguousarray(t, dtype=float), np.ascontiguousarray(np.asarray(z, float)),
            np.asarray(starts, dtype=np.int64), float(lag), out)
    return out


def typical_speed(t, z, starts) -> float:
    """Median chord speed over all rows (m/s); 0 for no data."""
    c = chord_speeds(t, z, starts)
    n = 0
    for a in range(0, c.size, 1 << 16):  # the finite values moved to the front block by block: no copy of all of them
        blk = c[a:a + (1 << 16)]
        blk = blk[np.isfinite(blk)]
        c[n:n + blk.size] = blk
        n += blk.size
    return float(np.median(c[:n], overwrite_input=True)) if n else 0.0


def accel_std_family(model: str, k: float, v_typ: float) -> tuple:
    """q(k) of ``model``: translational stds k × default, rotational min(default, k·σ_a0 / v_typ).

    σ_a0 is the model's first translational default. With no translational entry the defaults are
    scaled by k.
    """
    spec = get_model(model)
    d = spec.default_accel_std
    lin = [v for v, kind in zip(d, spec.matched_noise) if kind == "v"]
    if not lin:
        return tuple(k * v for v in d)
    sa = k * lin[0]
    out = []
    for v, kind in zip(d, spec.matched_noise):
        if kind == "v":
            out.append(k * v)
        else:
            out.append(min(v, sa / v_typ) if v_typ > 0 else v)
    return tuple(float(x) for x in out)


# ------------------------------------------------------------------------- chi-square quantiles
def _gammainc_lower(a: float, x: float) -> float:
    """Regularised lower incomplete gamma P(a, x) (series for x < a + 1, continued fraction beyond)."""
    if x <= 0:
        return 0.0
    lg = math.lgamma(a)
    if x < a + 1:
        term = total = 1.0 / a
        n = a
        for _ in range(1000):
            n += 1
            term *= x / n
            total += term
            if abs(term) < abs(total) * 1e-15:
                break
        return total * math.exp(-x + a * math.log(x) - lg)
    b = x + 1 - a
    c = 1e300
    d = 1.0 / b
    h = d
    for i in range(1, 1000):
        an = -i * (i - a)
        b += 2
        d = an * d + b
        d = 1e-300 if abs(d) < 1e-300 else d
        c = b + an / c
        c = 1e-300 if abs(c) < 1e-300 else c
        d = 1.0 / d
        delta = d * c
        h *= delta
        if abs(delta - 1) < 1e-15:
            break
    return 1.0 - math.exp(-x + a * math.log(x) - lg) * h


@functools.lru_cache(maxsize=256)
def chi2_quantile(p: float, dof: float) -> float:
    """The p-quantile of the chi-square distribution with ``dof`` degrees of freedom (bisection on the
    regularised incomplete gamma; relative accuracy 1e-12)."""
    if not 0 < p < 1:
        raise ValueError(f"p must be in (0, 1), got {p}")
    lo, hi = 0.0, max(1.0, dof)
    while _gammainc_lower(dof / 2, hi / 2) < p:
        hi *= 2
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if _gammainc_lower(dof / 2, mid / 2) < p:
            lo = mid
        else:
            hi = mid
        if hi - lo <= 1e-12 * hi:
            break
    return 0.5 * (lo + hi)


def subsample_objects(starts, max_rows: int = SEARCH_ROWS) -> np.ndarray:
    """Indices of whole objects, spread evenly over the file, with at most ``max_rows`` rows in all (at
    least one object; an object longer than ``max_rows`` is kept whole)."""
    lens = np.diff(starts)
    B = lens.size
    if lens.sum() <= max_rows:
        return np.arange(B)
    order = np.argsort(np.arange(B) * 0.6180339887498949 % 1.0, kind="stable")  # a low-discrepancy spread
    cum = np.cumsum(lens[order])
    n = max(1, int(np.searchsorted(cum, max_rows, side="right")))
    return np.sort(order[:n])


def one_step_errors(model: str, t, z, x, starts) -> np.ndarray:
    """Squared one-step prediction errors (N,): ‖z_k − position of f(x_{k−1}, t_k − t_{k−1})‖², f the
    model's noise-free motion (generated ``propagate_positions``: the positions of ``propagate_rows``, ``simulate_batch`` with
    zero noise) from the posterior x_{k−1};
    nan on each object's rows 0 and 1."""
    spec = get_model(model)
    N = len(t)
    out = np.full(N, np.nan)
    if N < 2:
        return out
    first = np.asarray(starts[:-1], dtype=np.int64)
    # every row from its predecessor in one pass over contiguous rows (no gathers): the rows whose predecessor is
    # in another object (an object's rows 0 and 1) are set to nan afterwards
    dts = np.diff(np.asarray(t, dtype=float))
    dts[first[first > 0] - 1] = 1.0  # across an object boundary: any positive step (its row is discarded)
    d = np.shape(z)[1]
    pred = np.empty((N - 1, d))  # the positions of propagate_rows only (propagate_positions): serial, nogil (the search's threads)
    spec.kernels.propagate_positions(np.ascontiguousarray(x[:-1], dtype=float), dts, pred)
    e = z[1:, :d] - pred
    err2 = e[:, 0] * e[:, 0]
    for c in range(1, d):
        err2 += e[:, c] * e[:, c]
    out[1:] = err2
    out[first] = np.nan
    out[np.minimum(first + 1, N - 1)] = np.nan
    return out


def angular_grid(model: str) -> tuple:
    """Candidate rotational stds: the model's default × 2^-6 … 2^0."""
    spec = get_model(model)
    d = [v for v, kind in zip(spec.default_accel_std, spec.matched_noise) if kind == "w"]
    return tuple(float(d[0] * 2.0**-e) for e in range(6, -1, -1)) if d else ()


def with_angular(model: str, q: tuple, a: float) -> tuple:
    """q with every rotational entry set to a."""
    spec = get_model(model)
    return tuple(a if kind == "w" else v for v, kind in zip(q, spec.matched_noise))


@dataclass
class SearchResult:
    """The chosen process noise of one model and the evidence."""

    k: float
    q: tuple
    mse: float  # mean squared one-step prediction error at q (m²)
    median_nis: float
    runs: int


def process_noise_search(run, model: str, v_typ: float, grid=K_GRID) -> SearchResult:
    """Process noise minimising the mean squared one-step prediction error (prediction-error method).

    ``run(q) -> (nis (N,), err2 (N,))`` tracks the subsample with process noise q (``lgekf track`` runs
    it with the divergence monitor, so that the score is that of the filter the user gets: the errors
    made before an alarm count, the re-initialised filter's afterwards); rows with nan are skipped. Three scans: k over ``grid`` with the rotational
    entries at the heuristic ``accel_std_family`` (every other grid value, then the two neighbours of
    the best), the rotational entries over ``angular_grid`` at that k, and k again (the best ± two grid
    steps) at the chosen rotational std: about 20 runs. A filter that becomes unstable with some q makes
    large prediction errors there before each alarm, so the search avoids it. With nothing to score (every
    object too short) the model's defaults are returned (``mse`` inf).

    The runs one after the other, in the order of ``search_stages``; ``lgekf.apps.search`` runs the
    candidates of a stage (of several models) in threads, with the same result.
    """
    scores = {}
    stages = search_stages(model, v_typ, scores, grid)
    cands = next(stages)
    while True:
        for q in cands:
            key = candidate_key(q)
            if key not in scores:
                scores[key] = run_score(*run(q))
        try:
            cands = stages.send(None)
        except StopIteration as stop:
            return stop.value


def candidate_key(q) -> tuple:
    """The key of a candidate q in a search's score table (rounded: the same q reached by two products)."""
    return tuple(round(v, 12) for v in q)


def run_score(nis, err2) -> tuple:
    """(mse, median NIS) of one search run: the mean of the finite squared one-step errors (inf if none) and
    the median of the finite NIS (nan if none)."""
    e = err2[np.isfinite(err2)]
    n = nis[np.isfinite(nis)]
    mse = float(np.mean(e)) if e.size else float("inf")
    return (mse if math.isfinite(mse) else float("inf"), float(np.median(n)) if n.size else float("nan"))


def search_stages(model: str, v_typ: float, scores: dict, grid=K_GRID):
    """The scans of ``process_noise_search`` as a generator: yields each stage's candidates (a list of q),
    to be scored into ``scores`` (``candidate_key(q)`` -> ``run_score``) by the caller before it is resumed
    with ``send(None)``; the candidates of one stage are independent. Returns (``StopIteration.value``) the
    ``SearchResult``; ``runs`` = the number of entries of ``scores``. The choice of a stage is the first
    candidate of least mse in list order, whatever order the runs were made in.
    """

    def best(cands):
        yield [q for _, q in cands]
        return min(cands, key=lambda c: scores[candidate_key(c[1])][0])

    def around(i, steps):
        return [grid[j] for j in sorted({min(max(i + d, 0), len(grid) - 1) for d in steps})]

    spec = get_model(model)
    coarse = list(range(0, len(grid), 2))  # factors of 2
    k, q = yield from best([(grid[i], accel_std_family(model, grid[i], v_typ)) for i in coarse])
    k, q = yield from best([(kk, accel_std_family(model, kk, v_typ)) for kk in around(grid.index(k), (-1, 0, 1))])
    ang = angular_grid(model)
    if ang:
        _, q = yield from best([(k, with_angular(model, q, a)) for a in ang])
        a = [v for v, kind in zip(q, spec.matched_noise) if kind == "w"][0]
        k, q = yield from best([(kk, with_angular(model, accel_std_family(model, kk, v_typ), a))
                                for kk in around(grid.index(k), (-2, -1, 0, 1, 2))])
    mse, med = scores[candidate_key(q)]
    if not math.isfinite(mse):  # no update to score (objects too short): the model's defaults
        k, q = 1.0, tuple(float(v) for v in get_model(model).default_accel_std)
    return SearchResult(k, tuple(float(v) for v in q), mse, med, len(scores))
