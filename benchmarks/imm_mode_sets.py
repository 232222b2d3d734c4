"""The fitted IMM's candidate mode sets against tuned CV on a real dataset, and the reference's own noise.

    python benchmarks/imm_mode_sets.py [DATASET] [--seeds 5] [--root DATA_ROOT] [--sets SET;SET;...]

The protocol of ``lgekf evaluate DATASET --imm --tune`` (N(0, 0.3²) noise on the reference positions; every model's
noise learned by maximum likelihood on the first 30 % of the tracks; the IMM fitted by its own likelihood there;
scores on the other 70 %, rows k >= 2, mean over tracks of the per-track RMSE). Prints

1. the reference positions' own white noise: ``learn_noise`` (CV and SE(2)×R³) on the *reference* tracks with the
   measurement std free (the added measurement noise rides on it: every estimate follows part of it and is scored
   against all of it; no correction is attempted, the two are not independent);
2. for each mode set (``--sets``; default: the three of ``TUNE_MODE_SETS`` and the two CV modes with a manoeuvring
   mode of every other model): its AIC and the fitted IMM's RMSE against tuned CV;
3. for the set of lowest AIC: the RMSE of tuned CV and the IMM by position along the track (the start's
   transient against the steady state).
The data are read from DATA_ROOT (default ``../shared/data``); without them the script says so and exits.
"""

from __future__ import annotations

import argparse
import copy
import sys

import numpy as np

from lgekf.apps.evaluate import FILTERS, _imm_fitted, _per_track_rmse, _seed_rng, tune_split
from lgekf.apps.smooth_track import learn_on_dataset
from lgekf.apps.track import DEFAULT_ACCEL_STD, TrackConfig, track_arrays
from lgekf.apps.track_imm import TUNE_MODE_SETS, ImmTrackOptions, imm_track_common
from lgekf.estimators.noise.tuning import learn_noise
from lgekf.io.datasets import load_dataset

BINS = ((2, 5), (5, 12), (12, 25), (25, 50), (50, 100), (100, 10**9))


def reference_noise(ds) -> dict:
    """{model: per-axis std} of the reference positions' own white noise (measurement std learned freely)."""
    tracks = [(ds.t[a:b], ds.p[a:b]) for a, b in zip(ds.starts[:-1], ds.starts[1:])]
    return {m: float(np.mean(learn_noise(m, tracks, hessian=False).meas_std)) for m in ("cv", "se2r3")}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("dataset", nargs="?", default="cyclists")
    ap.add_argument("--seeds", type=int, default=5)
    ap.add_argument("--root", default=None)
    ap.add_argument("--sets", default=None, help="mode sets separated by ';' (default: see the docstring)")
    a = ap.parse_args(argv)
    try:
        ds = load_dataset(a.dataset, root=a.root)
    except (FileNotFoundError, ValueError) as e:
        print(f"skipped: {e}")
        return 0
    meas_std = 0.3
    seeds = list(range(a.seeds))
    sets = a.sets.split(";") if a.sets else list(TUNE_MODE_SETS) + [
        f"cv:calm,cv:manoeuvre,{m}:manoeuvre" for m in FILTERS if m not in ("cv", "se2r3")]
    ref = reference_noise(ds)
    print(f"{ds.name}: {ds.n_tracks} tracks; the reference positions' own white noise, learned: "
          + ", ".join(f"{m} {v:.4f} m" for m, v in ref.items()) + " per axis")
    ti, ei = tune_split(ds.n_tracks)
    dtune, dev = ds.subset(ti), ds.subset(ei)
    fits = learn_on_dataset(dtune, meas_std, seeds, _seed_rng, FILTERS)
    cfg = TrackConfig({m: DEFAULT_ACCEL_STD[m] if isinstance(f, str) else f.accel_std for m, f in fits.items()}, meas_std).validate()
    zs = [dev.p + meas_std * _seed_rng(s, 0, dev.name).standard_normal(dev.p.shape) for s in seeds]
    obj = np.repeat(np.arange(dev.n_tracks), np.diff(dev.starts))
    k = np.arange(dev.t.size) - dev.starts[obj]

    def scores(run):
        """(mean per-track RMSE over seeds, squared errors per row summed over seeds)."""
        rm, e2 = [], np.zeros(dev.t.size)
        for z in zs:
            x = run(z)
            err2 = np.sum((x[:, :2] - dev.p) ** 2, axis=1)
            rm.append(np.mean(_per_track_rmse(dev, err2)))
            e2 += err2
        return float(np.mean(rm)), e2 / len(zs)

    cv, cv_e2 = scores(lambda z: track_arrays("cv", dev.t, z, dev.starts, cfg)[0])
    print(f"tuned CV {cv:.4f} m; {a.seeds} seeds")
    print(f"{'mode set':<44} {'AIC':>10} {'IMM':>7} {'vs CV':>7}")
    best = None
    for text in sets:
        imm, fit, _ = _imm_fitted(ImmTrackOptions(text), dtune, meas_std, seeds, cfg.omega_std, fits)
        if isinstance(fit, str):
            print(f"{text:<44} not fitted: {fit}")
            continue
        rmse, e2 = scores(lambda z: imm_track_common(dev.t, z, dev.starts, meas_std, cfg.omega_std, imm)[0])
        print(f"{text:<44} {fit.aic:>10.1f} {rmse:>7.4f} {100 * (rmse / cv - 1):>+6.1f}%", flush=True)
        if best is None or fit.aic < best[0]:
            best = (fit.aic, text, copy.deepcopy(e2))
    if best is not None:
        print(f"along the track (lowest AIC: {best[1]}), RMSE over all rows of each bin of k:")
        for lo, hi in BINS:
            sel = (k >= lo) & (k < hi)
            if sel.any():
                c, i = np.sqrt(cv_e2[sel].mean()), np.sqrt(best[2][sel].mean())
                print(f"  k in [{lo}, {hi if hi < 10**9 else 'end'}): {int(sel.sum()):>6} rows  CV {c:.4f}  IMM {i:.4f}  ({100 * (i / c - 1):+.1f}%)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
