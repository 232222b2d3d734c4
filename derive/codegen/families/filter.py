"""The filter family: the loops over rows that call a model's steps (templates ``filter_*.py.tmpl``, ...).

* ``run_one_<meas>`` / ``run_segments_<meas>`` (segments of rows) / ``run_one_from_<meas>`` / ``run_segments_from_<meas>``
  (the same from internal states, which they leave at the last row's posterior: a long object in windows) /
  ``run_batch_<meas>`` (prange over trajectories; a NaN measurement row is a missed detection: predict only);
* ``run_segments_noise_from_<meas>`` (noise stds per segment: the divergence monitor's reruns);
* ``measure_batch_<meas>`` (simulated measurements), ``simulate_batch`` / ``states_from_physical`` /
  ``propagate_rows`` / ``propagate_positions`` (the exact motion), ``world_velocities``, ``common_to_states`` /
  ``common_jacobians`` (rows of the model family's kernels).
"""

from __future__ import annotations

from ..blocks import arg_list
from ..template import load

__all__ = ["kernels", "FILTER_LOOP", "BATCH_TEMPLATE", "SEGMENT_NOISE_TEMPLATE"]

# the loop over segments of rows (each segment's steps dts from t, then one call per segment): one text for
# run_segments_<meas>, run_segments_from_<meas> and run_segments_noise_from_<meas>, formatted with the call
SEGMENT_LOOP = load("filter_segment_loop.py.tmpl")


def _segments(call: str) -> str:
    """SEGMENT_LOOP with ``call`` (a template line of the kernel it runs per segment) as its body."""
    return SEGMENT_LOOP.replace("{call}", call)


# the filter loop over the rows of one trajectory from (s, p): one text for run_one_<meas> and run_one_from_<meas>,
# so that both compile to the same numbers (a long object filtered in windows = in one call)
FILTER_LOOP = load("filter_loop.py.tmpl")

BATCH_TEMPLATE = (load("filter_batch.py.tmpl")
                  .replace("{segments}", _segments("run_one_{meas}(z[a:b], dts[:b - a], x0[i], p0[i], q, r, out_x[a:b], out_p[a:b], out_nis[a:b])"))
                  .replace("{segments_from}",
                           _segments("run_one_from_{meas}(z[a:b], dts[:b - a], s0[i], p0[i], q, r, out_x[a:b], out_p[a:b], out_nis[a:b])")))
SEGMENT_NOISE_TEMPLATE = load("filter_segments_noise.py.tmpl").replace(
    "{segments_noise}", _segments("run_one_from_{meas}(z[a:b], dts[:b - a], s0[i], p0[i], q[i], r[i], out_x[a:b], out_p[a:b], out_nis[a:b])"))

SIMULATE_TEMPLATE = load("simulate.py.tmpl")
MEASURE_TEMPLATE = load("measure_batch.py.tmpl")
COMMON_BATCH_TEMPLATE = load("common_batch.py.tmpl")
WORLD_VELOCITY_TEMPLATE = load("world_velocities.py.tmpl")


def kernels(model, measurements: dict, built) -> list:
    """The family's entry (``derive.codegen.emitter``): (slot, kernel) pairs of one model module."""
    out = []
    for meas in measurements.values():
        m = meas.m
        nan_test = " or ".join(f"np.isnan(z[k, {i}])" for i in range(m))
        fmt = dict(meas=meas.name, m=m, n=model.n, npk=model.n * (model.n + 1) // 2, ni=len(model.internal),
                   nq=len(model.noise_names), nr=len(meas.noise_names), qargs=arg_list("q", len(model.noise_names)),
                   zargs=arg_list("z[k]", m).replace("z[k][", "z[k, "), rargs=arg_list("r", len(meas.noise_names)), nan_test=nan_test)
        out.append((("measure", meas.name), (f"run_one_{meas.name}", BATCH_TEMPLATE.format(loop=FILTER_LOOP.format(**fmt), **fmt))))
        out.append((("measure", meas.name), (f"measure_batch_{meas.name}", MEASURE_TEMPLATE.format(
            meas=meas.name, n=model.n, m=m, margs=arg_list("noise[i]", m).replace("noise[i][", "noise[i, ")))))
        out.append((("noise_loops", meas.name), (f"run_segments_noise_from_{meas.name}", SEGMENT_NOISE_TEMPLATE.format(
            meas=meas.name, nq=len(model.noise_names), nr=len(meas.noise_names)))))
    nn = len(model.noise_stds())
    out.append(("simulation", ("simulate_batch", SIMULATE_TEMPLATE.format(
        n=model.n, nq=nn, nargs=arg_list("noise[b, k]", nn).replace("noise[b, k][", "noise[b, k, "),
        zeros=", ".join(["0.0"] * nn), ni=len(model.internal)))))
    d = model.space.dim  # |v| over the space's d axes (math.hypot in the plane, as ever)
    speed = "math.hypot(v[0], v[1])" if d == 2 else "math.sqrt(" + " + ".join(f"v[{k}] * v[{k}]" for k in range(d)) + ")"
    out.append(("velocity", ("world_velocities", WORLD_VELOCITY_TEMPLATE.replace("{d}", str(d)).replace("{speed}", speed))))
    out.append(("common", ("common_to_states", COMMON_BATCH_TEMPLATE)))
    return out
