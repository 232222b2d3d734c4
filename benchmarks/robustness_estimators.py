"""Every estimator of `lgekf track` with no options, on files unlike the shared data and on the real data: does any
diverge, write a non-finite value, or leave a row the monitor should have flagged with flag 0?

    python benchmarks/robustness_estimators.py [--cases aircraft,mixed-noise,kitti-1m,...] [--out FILE.md]

Estimators: each model (cv, ctrv, se2r2, se2r3, se2se2) and `--model imm`, each plain, `--smooth`, `--tune` and
`--tune --smooth`, run through `lgekf.track` (the CLI's engine). Cases:

* aircraft: 40 objects at 136 m/s turning at ±0.05 rad/s, ~1 Hz jittered stamps, 20 m noise per axis (the
  character of the aircraft logs the one-pipeline issue reports);
* mixed-noise: one file of aircraft-like objects (20 m noise, 1 Hz), boats (8 m, 10 Hz), cars (0.5 m) and pedestrians
  (0.2 m): objects of very different measurement noise;
* the robustness set's simulated and real cases (``lgekf.apps.robustness``; real ones skipped, with the reason, when
  ../shared/data is absent).

With ``--multi``: the same cases as unlabelled detections (ids dropped, rows sorted by time: ``--multi --sort``), each
model through the multi-target tracker with no other option; per run the confirmed tracks against the objects,
rows with a non-finite value, and runaway rows (speed above 3 × the fastest true speed of the case + 5 m/s) and how
many of them carry flag 0.

Per run: rows with a non-finite output value (NIS, empty by design on each object's first two rows, excepted);
diverged rows (position error above 10 σ, σ the true noise of the row's object, and above 5 × the position std the
filter reports: a gross error the filter does not know about) and how many of them carry flag 0; diverged objects;
position RMSE of the unflagged rows k ≥ 2 against the raw measurements' (and of the smoothed columns).
"""

from __future__ import annotations

import argparse
import io
import contextlib
import sys
import time

import numpy as np
import pandas as pd

ESTIMATORS = ["cv", "ctrv", "se2r2", "se2r3", "se2se2", "imm"]
OPTIONS = {"": {}, "--smooth": {"smooth": True}, "--tune": {"tune": True}, "--tune --smooth": {"tune": True, "smooth": True}}


def _fast(rng, oid, n, speed, turn, dt, noise, jitter=0.2):
    t = np.cumsum(np.r_[0.0, dt * (1 + rng.uniform(-jitter, jitter, n - 1))])
    psi, p, w, pts = rng.uniform(-np.pi, np.pi), rng.uniform(-5e3, 5e3, 2), 0.0, []
    for k in range(n):
        if k % 30 == 0:
            w = rng.choice([0.0, turn, -turn])
        pts.append(p.copy())
        if k < n - 1:
            h = t[k + 1] - t[k]
            psi += w * h
            p = p + speed * h * np.array([np.cos(psi), np.sin(psi)])
    p = np.array(pts)
    return t, p, p + noise * rng.standard_normal(p.shape), np.full(n, noise)


def synthetic_cases():
    """(name, description, t, p (truth), z, sigma per row, starts, ids)."""
    out = []
    for name, desc, kinds in (
        ("aircraft", "40 aircraft-like objects: 136 m/s, ±0.05 rad/s turns, ~1 Hz jittered, 20 m noise",
         [("air", 40, 200, 136.0, 0.05, 1.0, 20.0)]),
        ("mixed-noise", "one file: 10 aircraft-like (20 m, 1 Hz), 10 boats (8 m, 12 m/s, 10 Hz), 10 cars (0.5 m, 15 m/s), "
         "10 pedestrians (0.2 m, 1.4 m/s)",
         [("air", 10, 200, 136.0, 0.05, 1.0, 20.0), ("boat", 10, 300, 12.0, 0.2, 0.1, 8.0),
          ("car", 10, 300, 15.0, 0.3, 0.1, 0.5), ("ped", 10, 300, 1.4, 0.5, 0.1, 0.2)]),
    ):
        rng = np.random.default_rng(1)
        ts, ps, zs, ss, ids = [], [], [], [], []
        for kind, count, n, speed, turn, dt, noise in kinds:
            for i in range(count):
                t, p, z, s = _fast(rng, i, n, speed, turn, dt, noise)
                for acc, v in zip((ts, ps, zs, ss), (t, p, z, s)):
                    acc.append(v)
                ids += [f"{kind}{i}"] * n
        starts = np.r_[0, np.cumsum([len(t) for t in ts])]
        out.append((name, desc, np.concatenate(ts), np.vstack(ps), np.vstack(zs), np.concatenate(ss), starts, np.array(ids)))
    return out


def robustness_cases(names):
    from lgekf.apps.robustness import real_cases, simulated_cases

    cases = simulated_cases(names)
    real, skipped = real_cases(None, names)
    out = []
    for c in cases + real:
        ids = np.repeat([f"o{b}" for b in range(c.n_tracks)], np.diff(c.starts))
        out.append((c.name, c.description, c.t, c.p, c.z, np.full(c.t.size, c.meas_std), c.starts, ids))
    return out, skipped


def score(df, t, p, z, sigma, starts):
    """The criteria of the module docstring for one output table (rows in the input's object order)."""
    cols = [c for c in df.columns if c not in ("id", "nis")]
    vals = df[cols].to_numpy(dtype=float)
    nonfinite = int((~np.isfinite(vals)).any(axis=1).sum())
    err = np.hypot(df["x"].to_numpy() - p[:, 0], df["y"].to_numpy() - p[:, 1])
    std = np.hypot(df["std_x"].to_numpy(), df["std_y"].to_numpy())
    flag = df["flag"].to_numpy().astype(int)
    k = np.arange(t.size) - np.repeat(starts[:-1], np.diff(starts))
    diverged = (err > 10 * sigma) & (err > 5 * std) & (k >= 2)
    obj = np.repeat(np.arange(len(starts) - 1), np.diff(starts))
    keep = (k >= 2) & ((flag & 1) == 0)  # rows the monitor vouches for (bit 2: only the smoothing failed)
    raw = np.hypot(*(z - p).T)
    row = {"nonfinite": nonfinite, "diverged rows": int(diverged.sum()), "unflagged": int((diverged & ((flag & 1) == 0)).sum()),
           "diverged objects": int(np.unique(obj[diverged]).size), "flagged": int(((flag & 1) > 0).sum()),
           "rmse": float(np.sqrt(np.mean(err[keep] ** 2))) if keep.any() else float("nan"),
           "raw": float(np.sqrt(np.mean(raw[k >= 2] ** 2)))}
    if "smooth_x" in df:
        es = np.hypot(df["smooth_x"].to_numpy() - p[:, 0], df["smooth_y"].to_numpy() - p[:, 1])
        row["smooth rmse"] = float(np.sqrt(np.mean(es[keep] ** 2))) if keep.any() else float("nan")
        row["smooth failed"] = int(((flag & 2) > 0).sum())
    return row


def score_multi(df, t, p, starts):
    """``--multi`` criteria (module docstring) of one output table."""
    vals = df[[c for c in df.columns if c != "track"]].to_numpy(dtype=float)
    fastest = 0.0
    for a, b in zip(starts[:-1], starts[1:]):
        if b - a >= 2:
            fastest = max(fastest, float(np.max(np.hypot(*np.diff(p[a:b], axis=0).T) / np.diff(t[a:b]))))
    runaway = df["speed"].to_numpy() > 3 * fastest + 5.0
    flag = df["flag"].to_numpy().astype(int) if len(df) else np.zeros(0, int)
    return {"tracks": int(df["track"].nunique()) if len(df) else 0, "nonfinite": int((~np.isfinite(vals)).any(axis=1).sum()),
            "runaway": int(runaway.sum()), "unflagged": int((runaway & (flag == 0)).sum()), "flagged": int(flag.sum())}


def main_multi(cases, estimators) -> tuple[list, int]:
    """The ``--multi`` runs: one table row per case and model."""
    import lgekf

    lines = ["| case | model | objects | confirmed tracks | non-finite rows | runaway rows (flag 0) | flagged rows | s |",
             "|---|---|---|---|---|---|---|---|"]
    bad = 0
    for name, desc, t, p, z, sigma, starts, ids in cases:
        df_in = pd.DataFrame({"t": t, "x": z[:, 0], "y": z[:, 1]})
        print(f"{name}: {desc}; {len(starts) - 1} objects, {t.size} rows (--multi)", file=sys.stderr)
        for est in estimators:
            if est == "imm":
                continue  # the multi-target tracker runs the registry models
            t0 = time.perf_counter()
            with contextlib.redirect_stderr(io.StringIO()):
                df = lgekf.track(df_in, model=est, multi=True, sort=True)
            s = score_multi(df, t, p, starts)
            bad += s["nonfinite"] + s["unflagged"]
            lines.append(f"| {name} | {est} | {len(starts) - 1} | {s['tracks']} | {s['nonfinite']} | {s['runaway']} "
                         f"({s['unflagged']}) | {s['flagged']} | {time.perf_counter() - t0:.1f} |")
            print(lines[-1], file=sys.stderr)
    return lines, bad


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", default=None, help="comma-separated case names (default: the two synthetic ones and every "
                    "robustness case)")
    ap.add_argument("--estimators", default=",".join(ESTIMATORS))
    ap.add_argument("--out", default=None, help="also write the markdown table here")
    ap.add_argument("--multi", action="store_true", help="the cases as unlabelled detections through --multi instead")
    a = ap.parse_args(argv)
    import lgekf

    names = a.cases.split(",") if a.cases else None
    cases = [c for c in synthetic_cases() if names is None or c[0] in names]
    more, skipped = robustness_cases(names)
    cases += more
    lines = ["| case | estimator | options | non-finite rows | diverged rows (flag 0) | diverged objects | flagged rows | "
             "RMSE m (raw) | smoothed RMSE m (failed rows) | s |", "|---|---|---|---|---|---|---|---|---|---|"]
    bad = 0
    if a.multi:
        lines, bad = main_multi(cases, a.estimators.split(","))
        cases = []
    for name, desc, t, p, z, sigma, starts, ids in cases:
        df_in = pd.DataFrame({"id": ids, "t": t, "x": z[:, 0], "y": z[:, 1]})
        print(f"{name}: {desc}; {len(starts) - 1} objects, {t.size} rows", file=sys.stderr)
        for est in a.estimators.split(","):
            for opt, kw in OPTIONS.items():
                t0 = time.perf_counter()
                with contextlib.redirect_stderr(io.StringIO()):
                    df = lgekf.track(df_in, model=est, **kw)
                s = score(df, t, p, z, sigma, starts)
                bad += s["nonfinite"] + s["unflagged"]
                sm = f"{s['smooth rmse']:.3g} ({s['smooth failed']})" if "smooth rmse" in s else ""
                lines.append(f"| {name} | {est} | {opt or '(none)'} | {s['nonfinite']} | {s['diverged rows']} ({s['unflagged']}) | "
                             f"{s['diverged objects']} | {s['flagged']} | {s['rmse']:.3g} ({s['raw']:.3g}) | {sm} | "
                             f"{time.perf_counter() - t0:.1f} |")
                print(lines[-1], file=sys.stderr)
    text = "\n".join(lines)
    if skipped:
        text += "\n\nSkipped: " + "; ".join(f"{k} ({v})" for k, v in skipped.items())
    print(text)
    if a.out:
        with open(a.out, "w") as fh:
            fh.write(text + "\n")
    print(f"runs with a non-finite value or an unflagged diverged row: {bad}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
