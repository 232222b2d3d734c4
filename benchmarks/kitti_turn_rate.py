"""Turn-rate and heading errors on KITTI (car, OXTS truth), filters and smoothers with MLE-learned noise.

    python benchmarks/kitti_turn_rate.py [DATA_ROOT]

The protocol of ``lgekf evaluate kitti --tune --smooth``: N(0, 0.3²) noise on the OXTS positions (5 seeds), noise
learned by maximum likelihood on the first 30 % of the sequences, scores on the other 70 % over rows k >= 2:
the RMSE of the turn rate ω against the OXTS yaw rate (``wu``; models with an ``omega`` state) and of the
heading of motion atan2(v) against atan2 of the OXTS velocity (every model), both on the rows with a true
speed above 2 m/s (at a standstill neither is observable from positions). Prints one line per model and role.
"""

import sys

import numpy as np

from lgekf.apps.evaluate import FILTERS, _seed_rng, tune_split, world_velocity
from lgekf.apps.smooth_track import learn_on_dataset, smoothed_columns
from lgekf.apps.track import DEFAULT_ACCEL_STD, TrackConfig, Tracked, smoothing_inputs, track_arrays
from lgekf.core.registry import get_model
from lgekf.io.datasets import load_dataset


def main(root=None, seeds=5, meas_std=0.3):
    ds = load_dataset("kitti", root=root)
    ti, ei = tune_split(ds.n_tracks)
    dtune, dev = ds.subset(ti), ds.subset(ei)
    fits = learn_on_dataset(dtune, meas_std, list(range(seeds)), _seed_rng, FILTERS)
    cfg = TrackConfig({m: DEFAULT_ACCEL_STD[m] if isinstance(f, str) else f.accel_std for m, f in fits.items()}, meas_std).validate()
    obj = np.repeat(np.arange(dev.n_tracks), np.diff(dev.starts))
    k = np.arange(dev.t.size) - dev.starts[obj]
    keep = k >= 2
    moving = keep & (np.hypot(dev.v[:, 0], dev.v[:, 1]) > 2.0)
    true_head = np.arctan2(dev.v[:, 1], dev.v[:, 0])
    print(f"KITTI evaluation split: {dev.n_tracks} sequences, {int(keep.sum())} scored rows per seed, {seeds} seeds; "
          f"{int(moving.sum())} of them moving faster than 2 m/s; true yaw rate RMS there {np.sqrt(np.mean(dev.w[moving] ** 2)):.3f} rad/s")
    print(f"{'model':<8} {'role':<9} {'turn-rate RMSE (rad/s)':>23} {'heading RMSE (rad)':>19}")
    for m in FILTERS:
        spec = get_model(m)
        iw = spec.state_names.index("omega") if "omega" in spec.state_names else None
        errs = {"filter": ([], []), "smoother": ([], [])}
        for seed in range(seeds):
            z = dev.p + meas_std * _seed_rng(seed, 0, dev.name).standard_normal(dev.p.shape)
            x, p, nis = track_arrays(m, dev.t, z, dev.starts, cfg)
            zm, q, r = smoothing_inputs(m, z, cfg)
            xs = smoothed_columns(m, "position", dev.t, zm, dev.starts, Tracked(x, p, nis, None, []), q, r)[0][:, :spec.n]
            for role, st in (("filter", x), ("smoother", xs)):
                if iw is not None:
                    errs[role][0].append(st[moving, iw] - dev.w[moving])
                v = world_velocity(m, st)
                d = np.arctan2(v[:, 1], v[:, 0]) - true_head
                errs[role][1].append(np.arctan2(np.sin(d), np.cos(d))[moving])
        for role, (ew, eh) in errs.items():
            rw = f"{np.sqrt(np.mean(np.concatenate(ew) ** 2)):.3f}" if ew else "-"
            print(f"{m:<8} {role:<9} {rw:>23} {np.sqrt(np.mean(np.concatenate(eh) ** 2)):>19.4f}")


if __name__ == "__main__":
    main(*(sys.argv[1:2] or [None]))
