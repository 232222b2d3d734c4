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


from ..algebra import packed_index
from ..lie.special import ANGLE_FUNCTIONS, taylor_coefficients
from .printer import render_kernel

__all__ = ["LANES", "vector_helpers_source", "VECTOR_NAMES", "soa_model_kernels", "soa_measurement_kernels"]

LANES = 64
VECTOR_NAMES = ["sin_v", "cos_v", "atan2_v", "wrap_v", "wrap_sum_v", "gain_damping_v"] + [f"{f.__name__}_v" for f in ANGLE_FUNCTIONS]
_DECO = '@nb.njit(inline="always", fastmath={"contract"}, error_model="numpy")'


def _horner(coeffs, var="x2"):
    s = repr(float(coeffs[-1]))
    for c in reversed(coeffs[:-1]):
        s = f"{float(c)!r} + {var} * ({s})"
    return s


def vector_helpers_source() -> str:
    """numba source of the branch-free helpers (appended to generated/special.py)."""
    sin_c = [(-1) ** k / math.factorial(2 * k + 1) for k in range(1, 9)]
    cos_c = [(-1) ** k / math.factorial(2 * k) for k in range(1, 10)]
    atan_c = [(-1) ** k / (2 * k + 1) for k in range(0, 9)]
    tans = [math.tan(k * math.pi / 16) for k in range(5)]
    thr = [math.tan((2 * k + 1) * math.pi / 32) for k in range(4)]
    out = [f'''

# ---------------------------------------------------------------- branch-free helpers of the SIMD kernels
# (derive/codegen/soa.py): both sides of every branch are evaluated and selected, so LLVM can vectorise a loop
# whose body calls them (they are inlined by numba).

{_DECO}
def _sin_cos_r(x):
    """(r, q): x = q·π/2 + r, |r| ≤ π/4 (Cody–Waite, π/2 in three parts), q mod 4 as a float."""
    kf = math.floor(x * 0.6366197723675814 + 0.5)
    r = ((x - kf * 1.5707963267341256) - kf * 6.077100506506192e-11) - kf * 2.0222662487959506e-21
    return r, kf - 4.0 * math.floor(kf * 0.25)


{_DECO}
def sin_v(x):
    """sin x without branches: degree-17/18 Taylor polynomials on the reduced argument (error bound: soa.py)."""
    r, q = _sin_cos_r(x)
    r2 = r * r
    sp = r + r * r2 * ({_horner(sin_c, "r2")})
    cp = 1.0 + r2 * ({_horner(cos_c, "r2")})
    v = cp if (q == 1.0) | (q == 3.0) else sp
    return -v if q >= 2.0 else v


{_DECO}
def cos_v(x):
    """cos x without branches (as sin_v)."""
    r, q = _sin_cos_r(x)
    r2 = r * r
    sp = r + r * r2 * ({_horner(sin_c, "r2")})
    cp = 1.0 + r2 * ({_horner(cos_c, "r2")})
    v = sp if (q == 1.0) | (q == 3.0) else cp
    return -v if (q == 1.0) | (q == 2.0) else v


{_DECO}
def atan2_v(y, x):
    """atan2(y, x) ∈ [-π, π] without branches: t = min/max(|x|, |y|) ∈ [0, 1] reduced by the nearest tan(kπ/16),
    k = 0..4, to |t'| ≤ tan(π/32), Taylor polynomial of degree 17 (truncation < 1e-18)."""
    ax = abs(x)
    ay = abs(y)
    mx = max(ax, ay)
    t = min(ax, ay) / mx if mx > 0.0 else 0.0
    k = (1.0 if t > {thr[0]!r} else 0.0) + (1.0 if t > {thr[1]!r} else 0.0) + (1.0 if t > {thr[2]!r} else 0.0) + (1.0 if t > {thr[3]!r} else 0.0)
    c = {tans[1]!r} if k == 1.0 else ({tans[2]!r} if k == 2.0 else ({tans[3]!r} if k == 3.0 else (1.0 if k == 4.0 else 0.0)))
    u = (t - c) / (1.0 + t * c)
    u2 = u * u
    a = k * 0.19634954084936207 + u * ({_horner(atan_c, "u2")})
    a = 1.5707963267948966 - a if ay > ax else a
    a = 3.141592653589793 - a if x < 0.0 else a
    return -a if (y < 0.0) | ((y == 0.0) & (math.copysign(1.0, y) < 0.0)) else a


{_DECO}
def wrap_v(a):
    """a wrapped to (-π, π] without branches (wrap_angle's formula, selected)."""
    r = a - 6.283185307179586 * math.floor((a + 3.141592653589793) / 6.283185307179586)
    r = r + 6.283185307179586 if r <= -3.141592653589793 else r
    return a if (a > -3.141592653589793) & (a <= 3.141592653589793) else r


{_DECO}
def wrap_sum_v(a, y):
    """wrap_angle_sum without branches: wrap(a), with the sign of y beyond ±π/2."""
    w = wrap_v(a)
    return math.copysign(abs(w), y) if abs(w) > 1.5707963267948966 else w


{_DECO}
def gain_damping_v(a, b):
    """min(1, π / max(|a|, |b|)) without branches (gain_damping)."""
    m = max(abs(a), abs(b))
    return 1.0 if m <= 3.141592653589793 else 3.141592653589793 / m
''']
    for f in ANGLE_FUNCTIONS:
        coeffs = taylor_coefficients(f)
        if f.parity == 1:
            poly = _horner([coeffs[k] for k in range(0, len(coeffs), 2)])
        else:
            poly = f"x * ({_horner([coeffs[k] for k in range(1, len(coeffs), 2)])})"
        out.append(f'''

{_DECO}
def {f.__name__}_v(x, s, c):
    """{f.__name__} without branches: Taylor polynomial and closed form both evaluated, selected at |x| < {f.tau!r}."""
    x2 = x * x
    return ({poly}) if abs(x) < {f.tau!r} else ({f.stable})
''')
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
    src = _vectorise(render_kernel(phys)).replace("@nb.njit(cache=True)", _DECO, 1)
    return [("covariance_is_pd_lane", "\n".join(lines) + "\n"), ("physical_lane", src)]


# the block loop of the SIMD drivers (run_batch_soa_<meas> here, run_batch_store_soa_<meas> in smooth_step.py): a
# block's states into the work array W, then per step the lane kernel ``{lane}`` over the lanes and the LDLᵀ /
# NaN verdict per lane in row OK; the driver's own code follows (it redoes the failed lanes and writes its outputs)
SOA_BLOCK_LOOP = '''    nblk = (B + {lanes} - 1) // {lanes}
    for blk in nb.prange(nblk):
        lo = blk * {lanes}
        L = min({lanes}, B - lo)
        W = np.zeros({rows} * {lanes})
        s = np.empty({ni})
        p = np.empty({npk})
        for j in range(L):
            s0 = state_from_physical(x0[lo + j])
            for i in range({ni}):
                W[({S} + i) * {lanes} + j] = s0[i]
            for i in range({npk}):
                W[({P} + i) * {lanes} + j] = p0[lo + j, i]
        for k in range(K):
            for j in range(L):
                W[{DT} * {lanes} + j] = dts[lo + j, k]
{zload}
            for j in range(L):
                W[{NIS} * {lanes} + j] = {lane}(W, j, {qargs}, {rargs})
                good = covariance_is_pd_lane(W, j) & (W[{NIS} * {lanes} + j] == W[{NIS} * {lanes} + j])
                W[{OK} * {lanes} + j] = 1.0 if good else 0.0
'''

SOA_TEMPLATE = '''
@nb.njit(cache=True, parallel=True, fastmath=FASTMATH, error_model="numpy")
def run_batch_soa_{meas}(z, dts, x0, p0, q, r, out_x, out_p, out_nis):
    """run_batch_{meas} with trajectories in the SIMD lanes (derive/codegen/soa.py): same arguments and results.

    Blocks of {lanes} trajectories (prange over blocks); in a block every per-trajectory quantity is a row of one
    work array (rows × {lanes}) and lane_{meas} runs vectorised over the lanes; a lane failing the LDLᵀ test or with
    a NaN row (NaN NIS) is redone by the scalar predict / update_{meas}.
    """
    B = z.shape[0]
    K = z.shape[1]
    keep_p = out_p.shape[1] == K
''' + SOA_BLOCK_LOOP.replace("{lane}", "lane_{meas}") + '''            for j in range(L):
                if W[{OK} * {lanes} + j] == 0.0:
                    b = lo + j
                    for i in range({ni}):
                        s[i] = W[({S} + i) * {lanes} + j]
                    for i in range({npk}):
                        p[i] = W[({P} + i) * {lanes} + j]
                    predict(s, p, dts[b, k], {qargs})
                    if {nan_test}:
                        W[{NIS} * {lanes} + j] = np.nan
                    else:
                        W[{NIS} * {lanes} + j] = update_{meas}(s, p, {zargs}, {rargs})
                    for i in range({ni}):
                        W[({SN} + i) * {lanes} + j] = s[i]
                    for i in range({npk}):
                        W[({PN} + i) * {lanes} + j] = p[i]
            for j in range(L):
                out_nis[lo + j, k] = W[{NIS} * {lanes} + j]
                physical_lane(W, j, out_x, lo + j, k)
            if keep_p:
                for j in range(L):
                    for i in range({npk}):
                        out_p[lo + j, k, i] = W[({PN} + i) * {lanes} + j]
            for i in range({ni} + {npk}):
                for j in range(L):
                    W[({S} + i) * {lanes} + j] = W[({SN} + i) * {lanes} + j]
'''


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
    src = _vectorise(render_kernel(lane)).replace("@nb.njit(cache=True, fastmath=FASTMATH)", _DECO, 1)
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
