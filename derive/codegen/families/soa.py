"""SIMD across trajectories: structure-of-arrays batch kernels ``run_batch_soa_<meas>``.

The scalar loops run one trajectory per thread; here a block of ``LANES`` trajectories advances together, every
per-trajectory quantity stored as a row of a (quantity, LANES) array contiguous in the trajectories, and the
innermost loop runs over the trajectories of the block with the whole fused step inlined in its body
(``lane_<meas>``), so that LLVM vectorises it (packed AVX2/AVX-512 instructions, one trajectory per vector lane).
The outer loop is a prange over blocks.

For that the step must be branch-free straight-line code without calls:

* sin and cos are the polynomial ``sin_v`` / ``cos_v`` (Cody–Waite reduction by π/2 in three parts, Taylor
  polynomials of degree 17 and 18 on |r| ≤ π/4: truncation error below 1e-19, well under the rounding of the
  Horner evaluation; measured against math.sin/cos in tests/derive/test_soa.py), the output heading's atan2 the polynomial
  ``atan2_v`` (reduction to |t| ≤ tan(π/32) by a table of tan(kπ/16), Taylor degree 17);
* the angle functions, the gain damping and the wrap evaluate both branches and select (``<name>_v``);
* the LDLᵀ test is branch-free (``covariance_is_pd_lane``: all pivots, one combined comparison).

A lane whose step fails the LDLᵀ test, or has a missed detection (a NaN row: its NIS is NaN), is redone after the vector loop by the scalar ``predict`` and ``update_<meas>`` from the state before the step
(the arrays are double-buffered), exactly the scalar kernel's fallback.  Per-step dt per trajectory is read as in
the scalar loop.
"""

from __future__ import annotations

import math
import re
from dataclasses import replace


from ...algebra import packed_index
from ...lie.special import ANGLE_FUNCTIONS, taylor_coefficients
from ..printer import render_kernel
from ..template import load

__all__ = ["LANES", "vector_helpers_source", "VECTOR_NAMES", "soa_model_kernels", "soa_measurement_kernels", "kernels"]

LANES = 64
VECTOR_NAMES = ["sin_v", "cos_v", "atan2_v", "wrap_v", "wrap_sum_v", "gain_damping_v"] + [f"{f.__name__}_v" for f in ANGLE_FUNCTIONS]
_DECO = '@nb.njit(inline="always", fastmath={"contract"}, error_model="numpy")'


def as_lane(src: str) -> str:
    """A rendered kernel with its decorator (the first line, whatever ``render_kernel`` chose) replaced by the lanes'
    ``_DECO``: inlined into the SIMD loop, contracted, IEEE division."""
    head, sep, rest = src.partition("\n")
    if not head.startswith("@nb.njit("):
        raise ValueError(f"expected a numba decorator on the first line, got {head!r}")
    return _DECO + sep + rest


def _horner(coeffs, var="x2"):
    s = repr(float(coeffs[-1]))
    for c in reversed(coeffs[:-1]):
        s = f"{float(c)!r} + {var} * ({s})"
    return s


def vector_helpers_source() -> str:
    """numba source of the branch-free helpers (appended to generated/special.py; templates soa_vector_helpers.py.tmpl
    and soa_angle_v.py.tmpl)."""
    sin_c = [(-1) ** k / math.factorial(2 * k + 1) for k in range(1, 9)]
    cos_c = [(-1) ** k / math.factorial(2 * k) for k in range(1, 10)]
    atan_c = [(-1) ** k / (2 * k + 1) for k in range(0, 9)]
    tans = {f"tan{k}": repr(math.tan(k * math.pi / 16)) for k in range(5)}
    thr = {f"thr{k}": repr(math.tan((2 * k + 1) * math.pi / 32)) for k in range(4)}
    out = [load("soa_vector_helpers.py.tmpl").format(deco=_DECO, sin_poly=_horner(sin_c, "r2"), cos_poly=_horner(cos_c, "r2"),
                                                       atan_poly=_horner(atan_c, "u2"), **tans, **thr)]
    for f in ANGLE_FUNCTIONS:
        coeffs = taylor_coefficients(f)
        if f.parity == 1:
            poly = _horner([coeffs[k] for k in range(0, len(coeffs), 2)])
        else:
            poly = f"x * ({_horner([coeffs[k] for k in range(1, len(coeffs), 2)])})"
        out.append(load("soa_angle_v.py.tmpl").format(deco=_DECO, name=f.__name__, tau=repr(f.tau), poly=poly, stable=f.stable))
    return "".join(out)


_REPL = [(r"\bmath\.sin\(", "sin_v("), (r"\bmath\.cos\(", "cos_v("), (r"\bmath\.atan2\(", "atan2_v("),
         (r"\bwrap_angle\(", "wrap_v("), (r"\bwrap_angle_sum\(", "wrap_sum_v("), (r"\bgain_damping\(", "gain_damping_v(")]
_REPL += [(rf"\b{f.__name__}\(", f"{f.__name__}_v(") for f in ANGLE_FUNCTIONS]


def _vectorise(src: str) -> str:
    for a, b in _REPL:
        src = re.sub(a, b, src)
    return src


class Layout:
    """Rows of the one work array W (rows × LANES, flattened) of a block: constant offsets, so that LLVM sees every
    access as W[constant + j] of one array (no aliasing to check at run time)."""

    def __init__(self, model, m=0):
        ni, npk = len(model.internal), model.n * (model.n + 1) // 2
        self.S, self.P = 0, ni
        self.SN, self.PN = ni + npk, 2 * ni + npk
        self.DT = 2 * (ni + npk)
        self.NIS, self.OK, self.Z = self.DT + 1, self.DT + 2, self.DT + 3
        self.rows = self.Z + m
        self.ni, self.npk = ni, npk

    def at(self, row: int) -> str:
        return f"W[{row * LANES} + j]"


def _soa_sources(inputs, lay: Layout, extra=None):
    out = []
    for sym, src in inputs:
        m = re.fullmatch(r"([sp])\[(\d+)\]", src)
        if m:
            out.append((sym, lay.at((lay.S if m.group(1) == "s" else lay.P) + int(m.group(2)))))
        elif extra and src in extra:
            out.append((sym, extra[src]))
        else:
            out.append((sym, src))
    return out


def soa_model_kernels(model, physical_kernel) -> list:
    """``covariance_is_pd_lane`` and ``physical_lane`` of a model (inlined into the SoA loops)."""
    n = model.n
    idx = packed_index(n)
    lay = Layout(model)
    lines = [_DECO, "def covariance_is_pd_lane(W, j):",
             '    """covariance_is_pd of lane j of the new covariance rows of W, without branches (all pivots)."""']
    for i in range(n):
        for k in range(i, n):
            lines.append(f"    p{i}_{k} = {lay.at(lay.PN + idx[(i, k)])}")
    lines.append(f"    tol = 1e-13 * max({', '.join(f'p{k}_{k}' for k in range(n))})")
    for jj in range(n):
        terms = "".join(f" - l{jj}_{k} * l{jj}_{k} * d{k}" for k in range(jj))
        lines.append(f"    d{jj} = p{jj}_{jj}{terms}")
        if jj < n - 1:
            lines.append(f"    r{jj} = 1.0 / d{jj}")
        for i in range(jj + 1, n):
            terms = "".join(f" - l{i}_{k} * l{jj}_{k} * d{k}" for k in range(jj))
            lines.append(f"    l{i}_{jj} = (p{jj}_{i}{terms}) * r{jj}")
    lines.append("    return " + " & ".join(f"(d{k} > tol)" for k in range(n)))
    shifted = [(sym, re.sub(r"^s\[(\d+)\]$", lambda mm: f"s[{int(mm.group(1)) + lay.SN}]", src)) for sym, src in physical_kernel.inputs]
    phys = replace(physical_kernel, name="physical_lane", params=["W", "j", "out", "b", "k"],
                   inputs=_soa_sources(shifted, lay),
                   outputs=[(re.sub(r"out\[(\d+)\]", r"out[b, k, \1]", t), e) for t, e in physical_kernel.outputs])
    src = as_lane(_vectorise(render_kernel(phys)))
    return [("covariance_is_pd_lane", "\n".join(lines) + "\n"), ("physical_lane", src)]


# the block loop of the SIMD drivers (run_batch_soa_<meas> here, run_batch_store_soa_<meas> in smooth_step.py): a
# block's states into the work array W, then per step the lane kernel ``{lane}`` over the lanes and the LDLᵀ /
# NaN verdict per lane in row OK; the driver's own code follows (it redoes the failed lanes and writes its outputs)
SOA_BLOCK_LOOP = load("soa_block_loop.py.tmpl")

SOA_TEMPLATE = load("soa_batch.py.tmpl").replace("$block_loop\n", SOA_BLOCK_LOOP.replace("{lane}", "lane_{meas}"))


def soa_measurement_kernels(model, meas, step_kernel) -> list:
    """``lane_<meas>`` (the fused step on lane j of the work array) and ``run_batch_soa_<meas>``."""
    n = model.n
    m = meas.m
    lay = Layout(model, m)
    z_params = [f"z_{nm}" for nm in meas.z_names]
    extra = {"dt": lay.at(lay.DT)}
    extra.update({zp: lay.at(lay.Z + i) for i, zp in enumerate(z_params)})
    outputs = []
    for t, e in step_kernel.outputs:
        mm = re.fullmatch(r"([sp])\[(\d+)\]", t) or re.fullmatch(r"out_([sp])(\d+)", t)  # the fused step's p[i] / out_p<i>
        outputs.append((lay.at((lay.SN if mm.group(1) == "s" else lay.PN) + int(mm.group(2))), e))
    params = [x for x in step_kernel.params[2:] if x != "dt" and x not in z_params]
    lane = replace(step_kernel, name=f"lane_{meas.name}", params=["W", "j", *params],
                   inputs=_soa_sources(step_kernel.inputs, lay, extra), outputs=outputs, epilogue=[], error_model=None,
                   doc=f"step_{meas.name} on lane j of the work array W (rows: derive/codegen/soa.py Layout), without branches (SIMD).")
    src = as_lane(_vectorise(render_kernel(lane)))
    args = lambda pre, k: ", ".join(f"{pre}[{i}]" for i in range(k))  # noqa: E731
    zload = "\n".join(f"                W[{lay.Z + i} * {LANES} + j] = z[lo + j, k, {i}]" for i in range(m))
    driver = SOA_TEMPLATE.format(
        meas=meas.name, lanes=LANES, ni=lay.ni, npk=lay.npk, rows=lay.rows, S=lay.S, P=lay.P, SN=lay.SN, PN=lay.PN,
        DT=lay.DT, NIS=lay.NIS, OK=lay.OK, zload=zload,
        qargs=args("q", len(model.noise_names)), rargs=args("r", len(meas.noise_names)),
        zargs=", ".join(f"z[b, k, {i}]" for i in range(m)),
        nan_test=" or ".join(f"np.isnan(z[b, k, {i}])" for i in range(m)),
    )
    return [(f"lane_{meas.name}", src), (f"run_batch_soa_{meas.name}", driver)]


def kernels(model, measurements: dict, built) -> list:
    """The family's entry (``derive.codegen.emitter``): per measurement ``lane_<meas>`` and ``run_batch_soa_<meas>``
    (slot ``soa``), and the model's ``covariance_is_pd_lane``, ``physical_lane`` (slot ``soa_model``)."""
    out = []
    for meas in measurements.values():
        out += [(("soa", meas.name), k) for k in soa_measurement_kernels(model, meas, built.named(f"step_try_{meas.name}"))]
    return out + [("soa_model", k) for k in soa_model_kernels(model, built.named("physical_into"))]
