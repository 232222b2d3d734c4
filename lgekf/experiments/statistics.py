"""Intervals over tracks: Student-t quantiles and the expanded-percentile bootstrap (``bootstrap_ci``); over seeds:
the Student-t interval of a mean (``t_interval``).

See ``lgekf.apps.evaluate`` for why the bootstrap (never a negative RMSE bound) and ``MIN_TRACKS_CI``.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["t_quantile", "t_interval", "bootstrap_ci", "BOOTSTRAP_RESAMPLES", "BOOTSTRAP_SEED", "MIN_TRACKS_CI"]


def t_quantile(p: float, nu: int) -> float:
    """Student-t quantile (Cornish-Fisher expansion in 1/ν; exact for ν = 1, |error| 0.032 at ν = 2, 0.004 at ν = 3,
    < 1e-3 for ν >= 4)."""
    if nu < 1:
        return float("nan")
    if nu == 1:
        return math.tan(math.pi * (p - 0.5))
    # normal quantile (Acklam's rational approximation, |rel error| < 1.2e-9)
    a = [-3.969683028665376e01, 2.209460984245205e02, -2.759285104469687e02, 1.383577518672690e02, -3.066479806614716e01, 2.506628277459239e00]
    b = [-5.447609879822406e01, 1.615858368580409e02, -1.556989798598866e02, 6.680131188771972e01, -1.328068155288572e01]
    c = [-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e00, -2.549732539343734e00, 4.374664141464968e00, 2.938163982698783e00]
    d = [7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e00, 3.754408661907416e00]
    if p < 0.02425:
        q = math.sqrt(-2 * math.log(p))
        z = (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) / ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1)
    elif p > 1 - 0.02425:
        q = math.sqrt(-2 * math.log(1 - p))
        z = -(((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) / ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1)
    else:
        q = p - 0.5
        r = q * q
        z = (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q / (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1)
    g1 = (z**3 + z) / 4
    g2 = (5 * z**5 + 16 * z**3 + 3 * z) / 96
    g3 = (3 * z**7 + 19 * z**5 + 17 * z**3 - 15 * z) / 384
    g4 = (79 * z**9 + 776 * z**7 + 1482 * z**5 - 1920 * z**3 - 945 * z) / 92160
    return z + g1 / nu + g2 / nu**2 + g3 / nu**3 + g4 / nu**4


def t_interval(x, level: float = 0.95) -> tuple:
    """Mean of independent values (here one per seed) and the half-width of its Student-t interval.

    The interval is mean ± t_{(1+level)/2, n-1}·s/√n, s the sample standard deviation (ddof = 1): exact for normal
    values, and the usual choice for a handful of Monte Carlo runs (the t quantile is SciPy's, exact, not
    ``t_quantile``'s expansion, which is 0.03 off at n = 3). For a paired comparison (two trackers on the same
    seeds) give the per-seed differences.

    Returns
    -------
    mean, half : float
        The sample mean and the half-width; ``half`` is nan for fewer than 2 values, both nan for none.
    """
    from scipy.stats import t as student_t

    x = np.asarray(x, dtype=float).ravel()
    n = x.size
    if n == 0:
        return float("nan"), float("nan")
    m = float(x.mean())
    if n < 2:
        return m, float("nan")
    return m, float(student_t.ppf(0.5 + level / 2, n - 1) * x.std(ddof=1) / math.sqrt(n))


BOOTSTRAP_RESAMPLES = 10000
BOOTSTRAP_SEED = 20160705
MIN_TRACKS_CI = 5


def bootstrap_ci(x, level=0.95, resamples=BOOTSTRAP_RESAMPLES, seed=BOOTSTRAP_SEED, min_n=MIN_TRACKS_CI):
    """Mean of independent values and an expanded percentile bootstrap interval for it.

    Parameters
    ----------
    x : array_like
        Independent values (nan-free), here one per track: a per-track RMSE or a paired difference.
    level : float
        Coverage of the interval (default 0.95).
    resamples : int
        Number of bootstrap resamples of ``x`` (with replacement, each of size ``len(x)``).
    seed : int
        Seed of the resampling, so that the same data always give the same interval.
    min_n : int
        Fewest values for which an interval is given; below it the bounds are nan.

    Returns
    -------
    mean, lo, hi : float
        The sample mean and the bounds; ``lo`` and ``hi`` are nan when ``len(x) < min_n``, all three
        nan for empty ``x``.

    Notes
    -----
    The bounds are the α'/2 and 1 - α'/2 quantiles of the resampled means with
    Φ⁻¹(α'/2) = -√(n/(n-1))·t_{(1+level)/2, n-1}: the "expanded percentile" interval (T. Hesterberg,
    What teachers should know about the bootstrap, The American Statistician 69 (2015) 371-386), which
    widens the plain percentile interval by the factor it is too narrow at small n and equals it for
    large n. Being quantiles of resampled means, the bounds lie in [min x, max x]: an interval for a
    mean of non-negative values (RMSEs) never reaches below zero.
    """
    x = np.asarray(x, dtype=float).ravel()
    n = x.size
    m = float(x.mean()) if n else float("nan")
    if n < max(min_n, 2):
        return m, float("nan"), float("nan")
    z = math.sqrt(n / (n - 1)) * t_quantile(0.5 + level / 2, n - 1)
    p = 0.5 * math.erfc(z / math.sqrt(2.0))  # Φ(-z)
    rng = np.random.default_rng(seed)
    means = np.empty(resamples)
    chunk = max(1, 2**20 // n)
    for a in range(0, resamples, chunk):
        b = min(resamples, a + chunk)
        means[a:b] = x[rng.integers(0, n, size=(b - a, n))].mean(axis=1)
    lo, hi = np.quantile(means, [p, 1.0 - p])
    return m, float(lo), float(hi)


# ------------------------------------------------------------------------------------ running
