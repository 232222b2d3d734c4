"""The fused RTS backward step ``smooth_step`` and the storing forward step ``step_store_<meas>``.

``smooth_step(sf, pf, sq, pq, ss, ps, dt, so, po)`` is one step of the Rauch–Tung–Striebel backward pass on the
group (derivation: ``lgekf.estimators.smoother``) as a single straight-line kernel, generated from the model
definition like the fused filter step (no model is known here). It is emitted on the rows of the stored passes
(``smooth_step_at``, ``derive/codegen/families/smoother.py``) and in SIMD lanes (``lane_smooth``), not as itself:

* F = transition(μ_k, dt) and Φ(d)⁻¹, Φ(δ) are symbolic, so their structural zeros never reach the code
  (F of SE(2)×R³ has 17 non-zeros of 36, Φ of a Euclidean model is I and disappears);
* the covariances are read and written packed (upper triangle), every symmetric product is formed on its upper
  triangle only, and SymPy's CSE runs over each stage;
* G = P_k Fᵀ P_{k+1|k}⁻¹ by an unrolled, square-root-free LDLᵀ of P_{k+1|k} = L Δ Lᵀ (L unit lower triangular):
  each row g of G solves L y = c, then Lᵀ g = Δ⁻¹ y, with c the row of C = P_k Fᵀ (a pivot below 1e-300, which a
  positive definite P_{k+1|k} never has, is replaced by 1e-300 instead of dividing by zero, like the loop
  version did);
* then δ = G d, P̃ = P_k + G (P̄ − P_{k+1|k}) Gᵀ, μˢ_k = μ_k·exp(δ), Pˢ_k = Φ(δ) P̃ Φ(δ)ᵀ, as derived.

Inputs: ``sf``/``pf`` the posterior internal state and packed covariance at step k, ``sq``/``pq`` the predicted
ones at k+1, ``ss``/``ps`` the smoothed ones at k+1, ``dt`` the step from k to k+1; outputs ``so``/``po``
(the smoothed ones at k; they may not alias the inputs).

``step_store_<meas>(s, p, dt, *q, *z, *r, sq, pq) -> (nis, log det S)`` is the fused filter step ``step_<meas>``
(derive/codegen/fused.py) that also writes the predicted internal state and packed covariance it holds in
registers (after the angle-variance cap) into ``sq``/``pq``, and returns log det S = −log(1/det S) beside the
NIS: the forward pass of the smoother then costs one filter step plus the stores.

SIMD versions (trajectories in the vector lanes, the work-array scheme of derive/codegen/soa.py):
``lane_store_<meas>`` / ``run_batch_store_soa_<meas>`` and ``lane_smooth`` / ``smooth_batch_soa``, the same results
(to ~1e-14) as ``run_batch_store_<meas>`` and ``smooth_batch``, with the states kept in blocks (nblk, K,
n_int + n(n+1)/2, LANES) that the forward pass writes and the backward pass reads row by row (vector copies).
Measured on a first version that gathered and scattered per lane from (B, K, ·) arrays: with the vector step
removed, the loads and stores alone took 70–90 % of the time (memory traffic, not arithmetic, bounds these passes);
the block layout did not change the times beyond the noise of the shared machine.

Cost, and why the backward step stays about twice a filter step.  Counted in the generated SE(2)×SE(2) code:
``smooth_step`` has about 1 000 multiplications, the fused ``step_position`` 451.  The backward step is dominated
by dense n×n work the filter does not have (n = 6, m = 2: the filter's update is O(n²m)): G (the LDLᵀ, ≈ 65,
and the two triangular solves of each of its n rows, 90 + 126), G D (216) and (G D) Gᵀ on the upper triangle (126).  Equivalent forms were
counted and are no cheaper: through V = C L⁻ᵀ and E = L⁻¹ D L⁻ᵀ (G D Gᵀ = VΔ⁻¹ E Δ⁻¹Vᵀ, ≈ 590 against 560 here);
P̃ = P_k − G Cᵀ + (G Φ(d)⁻¹) Pˢ (G Φ(d)⁻¹)ᵀ (≈ 550 against 430).  Storing the prediction or recomputing it in
the backward step: measured (benchmarks/bench_store_prediction.py, 2000 × 200, three runs, shared machine), the
fused step writing s_filt, p_filt and x costs 1.00–1.10 filter steps, also writing the prediction 1.14–1.19
(SE(2)×SE(2)) and 1.25–1.54 (CV);
recomputing it would add F C on the upper triangle, Φ(Ω)QΦ(Ω)ᵀ and the angle cap (≈ 80–100 of the ≈ 1 000
multiplications of SE(2)×SE(2)) and a second set of kernels (the IMM smoother and the filter classes pass their own
predictions), so it is stored.
"""


from __future__ import annotations

from dataclasses import replace

import sympy as sp

from ...algebra import _changed, packed_index, sym_cov
from ..printer import Kernel
from ..template import load
from .soa import SOA_BLOCK_LOOP

__all__ = ["smooth_step_kernel", "store_step_kernel", "staged"]


def staged(defs: list) -> list:
    """Definitions (symbol, expr), each using only inputs and earlier symbols, grouped into dependency levels:
    a definition lands one stage after the latest definition it reads, so that the CSE of a stage never
    reads a symbol of the same stage before it is assigned."""
    level: dict = {}
    out: list = []
    for s, e in defs:
        e = sp.sympify(e)
        lv = 1 + max((level[x] for x in e.free_symbols if x in level), default=-1)
        level[s] = lv
        while len(out) <= lv:
            out.append([])
        out[lv].append((s, e))
    return out


def _named(Mx: sp.Matrix, prefix: str, defs: list, upper: bool = False) -> sp.Matrix:
    """Mx with every entry that is not a number or a symbol replaced by a new symbol ``<prefix>i_j`` whose
    definition is appended to ``defs``; ``upper``: Mx symmetric, only the upper triangle is defined."""
    r, c = Mx.shape
    out = sp.zeros(r, c)
    for i in range(r):
        for j in range(i if upper else 0, c):
            e = sp.sympify(Mx[i, j])
            if not (e.is_Number or isinstance(e, sp.Symbol)):
                s = sp.Symbol(f"{prefix}{i}_{j}", real=True)
                defs.append((s, e))
                e = s
            out[i, j] = e
            if upper:
                out[j, i] = e
    return out


def _ldl_solve_rows(C: sp.Matrix, Pq: sp.Matrix, defs: list) -> sp.Matrix:
    """G = C Pq⁻¹ through an unrolled LDLᵀ of Pq = L Δ Lᵀ (definitions appended to ``defs``)."""
    n = Pq.shape[0]
    L = sp.eye(n)
    rd = [None] * n
    dg = [None] * n
    for j in range(n):
        w = [_one(defs, f"lw{j}_{a}", L[j, a] * dg[a]) for a in range(j)]
        dg[j] = _one(defs, f"ld{j}", Pq[j, j] - sum((L[j, a] * w[a] for a in range(j)), sp.Integer(0)))
        rd[j] = _one(defs, f"lr{j}", 1 / sp.Max(dg[j], sp.Float(1e-300)))
        for i in range(j + 1, n):
            L[i, j] = _one(defs, f"ll{i}_{j}", (Pq[i, j] - sum((L[i, a] * w[a] for a in range(j)), sp.Integer(0))) * rd[j])
    G = sp.zeros(C.shape[0], n)
    for r in range(C.shape[0]):
        y = [None] * n
        for i in range(n):
            y[i] = _one(defs, f"ly{r}_{i}", C[r, i] - sum((L[i, a] * y[a] for a in range(i)), sp.Integer(0)))
        for i in range(n - 1, -1, -1):
            G[r, i] = _one(defs, f"gg{r}_{i}", y[i] * rd[i] - sum((L[a, i] * G[r, a] for a in range(i + 1, n)), sp.Integer(0)))
    return G


def _one(defs: list, name: str, e):
    """A named definition of ``e`` (appended to ``defs``), or ``e`` itself when it is a number or a symbol."""
    e = sp.sympify(e)
    if e.is_Number or isinstance(e, sp.Symbol):
        return e
    s = sp.Symbol(name, real=True)
    defs.append((s, e))
    return s


def smooth_step_kernel(model) -> Kernel:
    """The fused RTS backward step of ``model`` (module docstring)."""
    from ..blocks import vec_inputs

    n = model.n
    G = model.group
    sub = model.to_internal
    dt = sp.Symbol("dt", positive=True)
    sf = vec_inputs("sf", model.internal)
    qsyms = [sp.Symbol(f"q_{v}", real=True) for v in model.internal]
    tsyms = [sp.Symbol(f"t_{v}", real=True) for v in model.internal]
    Pf, pfin = sym_cov(n, "pf")
    Pq, pqin = sym_cov(n, "pq")
    Ps, psin = sym_cov(n, "ps")
    pfin = [(s, src.replace("p[", "pf[")) for s, src in pfin]
    pqin = [(s, src.replace("p[", "pq[")) for s, src in pqin]
    psin = [(s, src.replace("p[", "ps[")) for s, src in psin]
    defs: list = []
    # F = Ad(exp(−Ω)) + Φ(Ω)𝒞 at μ_k (the predict's F, with its zeros), C = P_k Fᵀ
    Cc = _named(model.calC.applyfunc(sub), "cc", defs)
    F = _named(model.F_of(Cc).applyfunc(sub), "ff", defs)
    C = _named(Pf * F.T, "cf", defs)
    # d = log(μ_{k+1|k}⁻¹ μˢ_{k+1}) (between, with the Euclidean models' angles wrapped) and P̄ − P_{k+1|k}
    from ...lie.special import wrap

    mu = model.mean().applyfunc(sub)
    mu_q = mu.subs(dict(zip(model.internal, qsyms)), simultaneous=True)
    mu_t = mu.subs(dict(zip(model.internal, tsyms)), simultaneous=True)
    dv = G.log(G.inverse(mu_q) * mu_t)
    dv = sp.Matrix([wrap(e) if i in model.angles and i not in model.periodic_tangent() else e for i, e in enumerate(dv)])
    d = _named(dv.applyfunc(sub).T, "dd", defs).T
    Ji = _named(G.right_jacobian_inv(list(d)), "ji", defs)
    JP = _named(Ji * Ps, "jp", defs)
    D = _named(JP * Ji.T - Pq, "dm", defs, upper=True)
    # G = C P_{k+1|k}⁻¹ (LDLᵀ), δ = G d, P̃ = P_k + G D Gᵀ
    Gm = _ldl_solve_rows(C, Pq, defs)
    delta = _named(Gm * d, "de", defs)
    GD = _named(Gm * D, "gd", defs)
    Pt = _named(Pf + GD * Gm.T, "pt", defs, upper=True)
    # μˢ_k = μ_k·exp(δ), Pˢ_k = Φ(δ) P̃ Φ(δ)ᵀ
    new = _changed(model, model.internal_of(mu * G.exp(list(delta))))
    Phi = G.right_jacobian(list(delta))
    if Phi != sp.eye(n):
        Phi = _named(Phi, "ph", defs)
        Pt = _named(Phi * Pt, "tp", defs) * Phi.T
    idx = packed_index(n)
    outputs = [(f"po[{idx[(i, j)]}]", Pt[i, j]) for i in range(n) for j in range(i, n)]
    outputs += [(f"so[{i}]", new.get(i, v)) for i, v in enumerate(model.internal)]
    return Kernel(
        name="smooth_step",
        doc=("One Rauch–Tung–Striebel backward step on the group (lgekf.estimators.smoother), straight-line:\n"
             "from the posterior (sf, pf) at k, the prediction (sq, pq) at k+1 and the smoothed (ss, ps) at k+1, with\n"
             "F = transition(μ_k, dt): d = log(μ_{k+1|k}⁻¹ μˢ_{k+1}), G = P_k Fᵀ P_{k+1|k}⁻¹ (LDLᵀ), δ = G d,\n"
             "P̃ = P_k + G (Φ(d)⁻¹ Pˢ_{k+1} Φ(d)⁻ᵀ − P_{k+1|k}) Gᵀ; writes μˢ_k = μ_k·exp(δ) into so and\n"
             "Pˢ_k = Φ(δ) P̃ Φ(δ)ᵀ (packed) into po (derive/codegen/smooth_step.py).\n"
             "legend: cc = 𝒞, ff = F, cf = P_k Fᵀ, dd = d, ji = Φ(d)⁻¹, jp = Φ(d)⁻¹Pˢ, dm = P̄ − P_{k+1|k},\n"
             "ld/ll/lr = LDLᵀ pivots, factor and reciprocal pivots, ly/gg = the solves for G, de = δ, gd = G·dm,\n"
             "pt = P̃, ph = Φ(δ), tp = Φ(δ)P̃."),
        params=["sf", "pf", "sq", "pq", "ss", "ps", "dt", "so", "po"],
        inputs=sf + pfin + [(s, f"sq[{i}]") for i, s in enumerate(qsyms)] + pqin
        + [(s, f"ss[{i}]") for i, s in enumerate(tsyms)] + psin + [(dt, "dt")],
        stages=staged(defs), outputs=outputs, fastmath=True,
    )


def store_step_kernel(model, step: Kernel) -> Kernel:
    """``step_store_<meas>``: the fused ``step`` (a ``step_<meas>`` Kernel) also writing its prediction (module
    docstring)."""
    n = model.n
    idx = packed_index(n)
    Pp, _ = sym_cov(n, "pp")
    # the predicted state: a predicted entry is the symbol <name>_p, an entry the prediction leaves is the input
    names = {s.name for st in step.stages if not hasattr(st, "lines") for s, _ in st}
    sq = []
    for i, v in enumerate(model.internal):
        ps = sp.Symbol(f"{v.name}_p", real=True)
        sq.append((f"sq[{i}]", ps if ps.name in names else v))
    pq = [(f"pq[{idx[(i, j)]}]", Pp[i, j]) for i in range(n) for j in range(i, n)]
    meas = step.name[len("step_try_"):] if step.name.startswith("step_try_") else step.name[len("step_"):]
    return replace(
        step, name=f"step_store_{meas}", params=[*step.params, "sq", "pq"], outputs=[*sq, *pq, *step.outputs],
        ret="nis, -math.log(rdet)",
        doc=(f"step_try_{meas} that also writes the predicted internal state into sq and the predicted packed covariance\n"
             "(after the angle-variance cap) into pq, and returns (NIS, log det S) (derive/codegen/smooth_step.py); a NIS\n"
             f"of -1 means the caller must run update_{meas} (derive/codegen/fused.py).\n"
             + step.doc.split("\n", 1)[1]),
    )


SOA_SMOOTH_TEMPLATE = load("smooth_soa.py.tmpl")


def smooth_soa_kernels(model, step: Kernel, physical: Kernel) -> list:
    """``lane_smooth`` (``smooth_step`` on lane j of a work array, branch-free), ``physical_smooth_lane`` (from the
    ``physical_into`` Kernel) and ``smooth_batch_soa`` (the backward pass with trajectories in the SIMD lanes over
    a forward pass stored in blocks, as derive/codegen/soa.py runs the filter)."""
    import re

    from ..printer import render_kernel
    from .soa import LANES, _vectorise, as_lane

    ni, npk = len(model.internal), model.n * (model.n + 1) // 2
    rows = {}
    at = 0
    for name, size in (("sf", ni), ("pf", npk), ("sq", ni), ("pq", npk), ("ss", ni), ("ps", npk), ("so", ni), ("po", npk),
                       ("dt", 1), ("act", 1), ("start", 1)):
        rows[name] = at
        at += size

    def row(src: str) -> str:
        m = re.fullmatch(r"(\w+)\[(\d+)\]", src)
        r = rows[m.group(1)] + int(m.group(2)) if m else rows[src]
        return f"W[{r * LANES} + j]"

    lane = replace(step, name="lane_smooth", params=["W", "j"], inputs=[(s, row(src)) for s, src in step.inputs],
                   outputs=[(row(t), e) for t, e in step.outputs],
                   doc="smooth_step on lane j of the work array W (rows: derive/codegen/smooth_step.py), without branches (SIMD).")
    src = as_lane(_vectorise(render_kernel(lane)))
    # the smoothed physical state of lane j, read from the rows ss (physical_into on the work array)
    phys_in = [(s, re.sub(r"^s\[(\d+)\]$", lambda mm: f"W[{(rows['ss'] + int(mm.group(1))) * LANES} + j]", src))
               for s, src in physical.inputs]
    phys = replace(physical, name="physical_smooth_lane", params=["W", "j", "out", "b", "k"], inputs=phys_in,
                   outputs=[(re.sub(r"out\[(\d+)\]", r"out[b, k, \1]", tt), e) for tt, e in physical.outputs],
                   doc="The physical state of lane j of the smoothed rows of the work array W into out[b, k] (SIMD).")
    psrc = as_lane(_vectorise(render_kernel(phys)))
    driver = SOA_SMOOTH_TEMPLATE.format(lanes=LANES, rows=at, n=model.n, R=ni + npk, **{k.upper(): v for k, v in rows.items()})
    return [("lane_smooth", src), ("physical_smooth_lane", psrc), ("smooth_batch_soa", driver)]


SOA_STORE_TEMPLATE = load("store_soa.py.tmpl").replace("$block_loop\n", SOA_BLOCK_LOOP.replace("{lane}", "lane_store_{meas}"))


def store_soa_kernels(model, meas, store: Kernel) -> list:
    """``lane_store_<meas>`` (``step_store_<meas>`` on lane j of a work array, branch-free) and
    ``run_batch_store_soa_<meas>`` (the storing forward pass with trajectories in the SIMD lanes), on the work-array
    layout of derive/codegen/soa.py with rows for the prediction and 1/det S after its own."""
    import re

    from ..printer import render_kernel
    from .soa import LANES, Layout, _soa_sources, _vectorise, as_lane

    lay = Layout(model, meas.m)
    SQ, PQ = lay.rows, lay.rows + lay.ni
    LD = PQ + lay.npk
    rows = LD + 1
    z_params = [f"z_{nm}" for nm in meas.z_names]
    extra = {"dt": lay.at(lay.DT)}
    extra.update({zp: lay.at(lay.Z + i) for i, zp in enumerate(z_params)})
    base = {"s": lay.SN, "p": lay.PN, "sq": SQ, "pq": PQ}
    outputs = []
    for t, e in store.outputs:
        mm = re.fullmatch(r"(sq|pq|s|p)\[(\d+)\]", t) or re.fullmatch(r"out_(s|p)(\d+)", t)  # the fused step's out_p<k>
        outputs.append((lay.at(base[mm.group(1)] + int(mm.group(2))), e))
    outputs.append((lay.at(LD), sp.Symbol("rdet", real=True)))
    params = [x for x in store.params[2:] if x not in ("dt", "sq", "pq") and x not in z_params]
    lane = replace(store, name=f"lane_store_{meas.name}", params=["W", "j", *params],
                   inputs=_soa_sources(store.inputs, lay, extra), outputs=outputs, epilogue=[], ret="nis", error_model=None,
                   doc=(f"step_store_{meas.name} on lane j of the work array W (rows: derive/codegen/smooth_step.py), without "
                        "branches (SIMD); 1/det S in a row of W."))
    src = as_lane(_vectorise(render_kernel(lane)))
    args = lambda pre, k: ", ".join(f"{pre}[{i}]" for i in range(k))  # noqa: E731
    m = meas.m
    zload = "\n".join(f"                W[{lay.Z + i} * {LANES} + j] = z[lo + j, k, {i}]" for i in range(m))
    driver = SOA_STORE_TEMPLATE.format(
        meas=meas.name, lanes=LANES, ni=lay.ni, npk=lay.npk, rows=rows, S=lay.S, P=lay.P, SN=lay.SN, PN=lay.PN,
        DT=lay.DT, NIS=lay.NIS, OK=lay.OK, SQ=SQ, PQ=PQ, LD=LD, zload=zload, R=lay.ni + lay.npk,
        qargs=args("q", len(model.noise_names)), rargs=args("r", len(meas.noise_names)),
        zargs=", ".join(f"z[b, k, {i}]" for i in range(m)),
        nan_test=" or ".join(f"np.isnan(z[b, k, {i}])" for i in range(m)),
    )
    return [(f"lane_store_{meas.name}", src), (f"run_batch_store_soa_{meas.name}", driver)]
