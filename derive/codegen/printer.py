"""SymPy -> numba source.

A :class:`Kernel` is a straight-line program: named inputs (scalars and array elements), a list of
*stages* of intermediate definitions, and the outputs.  Each stage is printed as

1. the angles it needs: for every distinct argument ``a`` of ``sin``/``cos``/an angle function
   (derive.special) one ``math.sin``/``math.cos`` pair and the angle functions as calls
   ``f(a, sin a, cos a)`` (Taylor branch inside, see generated/special.py);
2. common subexpressions (``sympy.cse``) over all definitions of the stage;
3. the definitions themselves.

Structural zeros are dropped, symmetric outputs are given once by the caller, every number is printed
as a correctly rounded float literal, integer powers are unrolled, and everything is sorted so that
the output is byte-identical from run to run (the regeneration test relies on it).
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

import sympy as sp

from ..dag import dag_atoms, dag_free_symbols, dag_has, dag_replace, dag_xreplace
from ..lie.special import ANGLE_FUNCTIONS, RUNTIME_FUNCTIONS, AngleFunction

#: the generated special function that returns (sinc, cosc, sinc2, cosc2) of one angle with shared reciprocals
#: (derive/codegen/build.py ``family_source``); a stage that needs two or more of them for an angle calls it once
SINC_FAMILY = "sinc_family"
SINC_FAMILY_MEMBERS = ("sinc", "cosc", "sinc2", "cosc2")

__all__ = ["Kernel", "RawStage", "Printer", "render_kernel", "render_module", "HEADER"]

HEADER = '''"""{title}

GENERATED FILE: DO NOT EDIT.
Source: {source}
Regenerate with: lgekf derive      (check freshness with: lgekf derive --check)
"""
'''


class Printer:
    """A deliberately small printer: Add, Mul, Pow, numbers, symbols, a few math functions, and Piecewise as a
    conditional expression (relations, And, Or in its conditions)."""

    FUNCS = {sp.sin: "math.sin", sp.cos: "math.cos", sp.tan: "math.tan", sp.atan2: "math.atan2", sp.Abs: "abs", sp.Max: "max"}

    def __init__(self, names: dict[sp.Symbol, str] | None = None):
        self.names = names or {}

    def __call__(self, e) -> str:
        return self.p(sp.sympify(e))

    # precedence: 0 Add, 1 Mul/Div, 2 unary minus, 3 atom
    def p(self, e) -> str:
        return self._p(e)[0]

    def _wrap(self, e, min_prec):
        s, prec = self._p(e)
        return f"({s})" if prec < min_prec else s

    def _p(self, e):
        if isinstance(e, sp.Symbol):
            return self.names.get(e, e.name), 3
        if e is sp.S.NaN or e.has(sp.zoo, sp.oo, sp.nan):
            raise ValueError(f"cannot print non-finite expression {e}")
        if isinstance(e, (sp.Integer, sp.Rational, sp.Float)) or e.is_Number:
            v = float(e)
            s = repr(v)
            return (s, 3) if v >= 0 else (s, 2)
        if isinstance(e, sp.Add):
            terms = e.as_ordered_terms()
            out = self._wrap(terms[0], 0)
            for t in terms[1:]:
                if t.could_extract_minus_sign():
                    out += " - " + self._wrap(-t, 1)
                else:
                    out += " + " + self._wrap(t, 1)
            return out, 0
        if isinstance(e, sp.Mul):
            if e.could_extract_minus_sign():
                return "-" + self._wrap(-e, 2), 2
            num, den = [], []
            for f in e.as_ordered_factors():
                if isinstance(f, sp.Pow) and f.exp.is_Integer and f.exp < 0:
                    den.append(sp.Pow(f.base, -f.exp))
                elif isinstance(f, sp.Rational) and not f.is_Integer and f.p == 1:
                    den.append(sp.Integer(f.q))
                else:
                    num.append(f)
            ns = "*".join(self._wrap(f, 2) for f in num) if num else "1.0"
            if not den:
                return ns, 1
            ds = "*".join(self._wrap(f, 2) for f in den)
            if len(den) > 1 or self._p(den[0])[1] < 3:
                ds = f"({ds})"
            return f"{ns}/{ds}", 1
        if isinstance(e, sp.Pow):
            b, n = e.base, e.exp
            if n == sp.Rational(1, 2):
                return f"math.sqrt({self.p(b)})", 3
            if n == sp.Rational(-1, 2):
                return f"1.0/math.sqrt({self.p(b)})", 1
            if n == sp.Rational(3, 2):
                return f"{self._wrap(b, 2)}*math.sqrt({self.p(b)})", 1
            if n == sp.Rational(-3, 2):
                return f"1.0/({self._wrap(b, 2)}*math.sqrt({self.p(b)}))", 1
            if n.is_Integer:
                k = int(n)
                if k == -1:
                    return f"1.0/{self._wrap(b, 3)}", 1
                if k < 0:
                    inner = self._p(sp.Pow(b, -k, evaluate=False))
                    d = inner[0] if inner[1] >= 3 else f"({inner[0]})"
                    return f"1.0/{d}", 1
                if 1 < k <= 4:
                    bs = self._wrap(b, 3)
                    return "*".join([bs] * k), 1
                return f"{self._wrap(b, 3)}**{k}", 1
            raise ValueError(f"unsupported power {e}")
        if isinstance(e, sp.Piecewise):
            # (a if c1 else (b if c2 else ...)): only the chosen branch runs (log_SO(3)'s near-π branches)
            *branches, (last, cond) = e.args
            if cond != sp.true:
                raise ValueError(f"Piecewise without a final True branch: {e}")
            out = self.p(last)
            for val, c in reversed(branches):
                out = f"({self.p(val)} if {self.p(c)} else {out})"
            return out, 3
        if isinstance(e, sp.core.relational.Relational):
            return f"{self._wrap(e.lhs, 0)} {e.rel_op} {self._wrap(e.rhs, 0)}", -1
        if isinstance(e, (sp.And, sp.Or)):
            op = " and " if isinstance(e, sp.And) else " or "
            return op.join(f"({self.p(a)})" for a in sorted(e.args, key=sp.default_sort_key)), -1
        if isinstance(e, (sp.Function, sp.Max)) and type(e) in self.FUNCS:  # Max is no sp.Function
            return f"{self.FUNCS[type(e)]}({', '.join(self.p(a) for a in e.args)})", 3
        if isinstance(e, RUNTIME_FUNCTIONS):
            return f"{type(e).numba_name}({', '.join(self.p(a) for a in e.args)})", 3
        raise ValueError(f"unsupported expression for numba printing: {e!r} ({type(e)})")


@dataclass
class RawStage:
    """Literal source lines between two stages (e.g. a safeguard that branches), printed as they are.

    ``uses``: the symbols the lines read or rewrite (kept alive by dead-code pruning).
    """

    lines: list[str]
    uses: tuple = ()


@dataclass
class Kernel:
    """One generated function.

    ``inputs``: (symbol, source) pairs, e.g. (x, "s[0]") or (dt, "dt"): the symbol is read from the
    Python expression ``source``.  ``params``: the function's parameter list.  ``stages``: lists of
    (symbol, expr) definitions, printed in order.  ``outputs``: (target code, expr) assignments,
    e.g. ("s[0]", x + ...), ("out[1, 2]", ...).  ``prologue``: lines before the outputs (array
    allocation).  ``ret``: the return expression (code) or None.
    """

    name: str
    doc: str
    params: list[str]
    inputs: list[tuple[sp.Symbol, str]]
    outputs: list[tuple[str, sp.Expr]]
    stages: list[list[tuple[sp.Symbol, sp.Expr]]] = field(default_factory=list)
    prologue: list[str] = field(default_factory=list)
    epilogue: list[str] = field(default_factory=list)
    ret: str | None = None
    substitutions: dict = field(default_factory=dict)
    skip_zero_outputs: bool = False
    fastmath: bool = False
    error_model: str | None = None
    #: sin/cos of an angle atan2(y, x) as y/r, x/r, r = √(x² + y²) (no math.sin/math.cos calls; equal to rounding)
    sincos_of_atan2: bool = False


def _prune_dead(stages, outputs, ret):
    """Drop intermediate definitions that no output (nor the returned name) depends on."""
    needed = {x.name for x in dag_free_symbols([e for _, e in outputs])}
    if ret is not None:
        needed |= set(re.findall(r"[A-Za-z_]\w*", ret))
    kept = []
    for st in reversed(stages):
        if isinstance(st, RawStage):
            needed |= {u.name for u in st.uses}
            kept.append(st)
            continue
        keep = [(s, e) for s, e in st if getattr(s, "name", s) in needed]
        needed |= {x.name for x in dag_free_symbols([e for _, e in keep])}
        kept.append(keep)
    return [st for st in reversed(kept) if isinstance(st, RawStage) or st]


def _sort_key(e):
    return sp.default_sort_key(e)


def _angle_atoms(exprs):
    """All sin(a), cos(a), f(a) atoms (f an angle function) in ``exprs``, grouped by argument a."""
    by_arg: dict = {}
    for atom in dag_atoms(exprs, sp.sin, sp.cos, *ANGLE_FUNCTIONS):
        by_arg.setdefault(atom.args[0], set()).add(atom)
    return sorted(by_arg.items(), key=lambda kv: _sort_key(kv[0]))


def _hoisted(defs, names):
    """(stages to emit before, defs): every argument of an angle atom (sin, cos, an angle function) that holds an angle
    function itself becomes a temporary ``_hK`` of a stage before (recursively), so that the angle functions of each
    stage have arguments free of them (SE(3)'s Jacobian of a logarithm: sinc3 of |φ|, φ holding 1/sinc of the rotation
    angle). Stages without such nesting (every planar kernel) are returned unchanged."""
    kinds = (sp.sin, sp.cos, *ANGLE_FUNCTIONS)
    repl = {}
    pre = []
    nested: dict = {}  # argument -> whether it holds an angle function
    for _, ex in defs:
        atoms = dag_atoms([ex], *kinds)
        if not any(isinstance(a, ANGLE_FUNCTIONS) for a in atoms):  # nothing can be nested in it (most expressions)
            continue
        for atom in sorted(atoms, key=_sort_key):
            arg = atom.args[0]
            if arg not in nested:
                nested[arg] = dag_has(arg, *ANGLE_FUNCTIONS)
            if arg not in repl and nested[arg]:
                repl[arg] = next(names)
                pre.append((repl[arg], arg))
    if not repl:
        return [], defs
    memo: dict = {}
    new = [(t, dag_replace(e, lambda a: isinstance(a, kinds) and a.args[0] in repl, lambda a: a.func(repl[a.args[0]]), memo))
           for t, e in defs]
    before, pre = _hoisted(pre, names)
    return before + [pre], new


def _safe(name: str) -> str:
    return re.sub(r"[^0-9a-zA-Z_]", "_", name)


def render_kernel(k: Kernel) -> str:
    subs = k.substitutions
    stages = [st if isinstance(st, RawStage) else [(s, sp.sympify(e).subs(subs)) for s, e in st] for st in k.stages]
    outputs = [(t, sp.sympify(e).subs(subs)) for t, e in k.outputs]
    if k.skip_zero_outputs:
        outputs = [(t, e) for t, e in outputs if e != 0]
    stages = _prune_dead(stages, outputs, k.ret)
    hoist = sp.numbered_symbols("_h", real=True)
    unnested = []
    for st in stages:
        if isinstance(st, RawStage):
            unnested.append(st)
        else:
            before, st = _hoisted(st, hoist)
            unnested += before + [st]
    before, outputs = _hoisted(outputs, hoist)
    stages = unnested + before

    all_exprs = [e for st in stages if not isinstance(st, RawStage) for _, e in st] + [e for _, e in outputs]
    used = dag_free_symbols(all_exprs)
    used |= {u for st in stages if isinstance(st, RawStage) for u in st.uses}
    pr = Printer()
    lines = []
    deco = "@nb.njit(cache=True, fastmath=FASTMATH)" if k.fastmath else "@nb.njit(cache=True)"
    # CSE hoists the parts of every branch of a Piecewise (log of SO(3) near π beside its generic branch) out of the
    # condition, so a branch that is not taken may divide by zero: IEEE division then (inf, not an exception)
    error_model = k.error_model or ("numpy" if dag_atoms(all_exprs, sp.Piecewise) else None)
    if error_model:
        deco = deco[:-1] + f', error_model="{error_model}")'
    lines.append(deco)
    lines.append(f"def {k.name}({', '.join(k.params)}):")
    doc = k.doc.strip("\n")
    lines.append('    """' + doc.replace("\n", "\n    ") + '\n    """')
    body = []
    for sym, src in k.inputs:
        if sym in used and pr(sym) != src:
            body.append(f"{pr(sym)} = {src}")

    tmp = sp.numbered_symbols("_t")
    angle_count = [0]

    # angles already evaluated in an earlier stage: arg -> (base, arg code, {emitted names}); a later
    # stage reuses their sin/cos/angle-function values instead of calling math.sin again
    seen_angles: dict = {}
    # compound angle arguments held in ``_aK``: arg -> Symbol("_aK"), so that the stage's other uses of the
    # argument (a bare atan2 beside halfcot(atan2(...)), say) read the variable instead of computing it again
    arg_names: dict = {}

    def emit_stage(defs, is_output):
        exprs = [e for _, e in defs]
        repl = {}
        for arg, atoms in _angle_atoms(exprs):
            if arg in seen_angles:
                base, arg_code, done = seen_angles[arg]
            else:
                done = set()
                if isinstance(arg, sp.Symbol):
                    base = _safe(arg.name)
                    arg_code = pr(arg)
                else:
                    base = f"_a{angle_count[0]}"
                    angle_count[0] += 1
                    if k.sincos_of_atan2 and isinstance(arg, sp.atan2):
                        ya, xa = (pr(a) for a in arg.args)
                        body.extend([f"_y_{base} = {ya}", f"_x_{base} = {xa}", f"{base} = math.atan2(_y_{base}, _x_{base})",
                                     f"_r_{base} = math.sqrt(_x_{base}*_x_{base} + _y_{base}*_y_{base})",
                                     f"_sin_{base} = _y_{base}/_r_{base}", f"_cos_{base} = _x_{base}/_r_{base}"])
                        done |= {"sin", "cos"}
                    else:
                        body.append(f"{base} = {pr(arg)}")
                    arg_code = base
                    arg_names[arg] = sp.Symbol(base, real=True)
                seen_angles[arg] = (base, arg_code, done)
            s_sym, c_sym = sp.Symbol(f"_sin_{base}"), sp.Symbol(f"_cos_{base}")
            need_sc = any(isinstance(a, AngleFunction) for a in atoms)
            kinds = {type(a) for a in atoms}
            if (need_sc or sp.sin in kinds) and "sin" not in done:
                body.append(f"{s_sym.name} = math.sin({arg_code})")
                done.add("sin")
            if (need_sc or sp.cos in kinds) and "cos" not in done:
                body.append(f"{c_sym.name} = math.cos({arg_code})")
                done.add("cos")
            family = [f for f in SINC_FAMILY_MEMBERS if f in {type(a).__name__ for a in atoms} and f not in done]
            if len(family) >= 2:
                names = ", ".join(f"_{f}_{base}" for f in SINC_FAMILY_MEMBERS)
                body.append(f"{names} = {SINC_FAMILY}({arg_code}, {s_sym.name}, {c_sym.name})")
                done.update(SINC_FAMILY_MEMBERS)
            for atom in sorted(atoms, key=_sort_key):
                if isinstance(atom, sp.sin):
                    repl[atom] = s_sym
                elif isinstance(atom, sp.cos):
                    repl[atom] = c_sym
                else:
                    fname = type(atom).__name__
                    fs = sp.Symbol(f"_{fname}_{base}")
                    if fname not in done:
                        body.append(f"{fs.name} = {fname}({arg_code}, {s_sym.name}, {c_sym.name})")
                        done.add(fname)
                    repl[atom] = fs
        m1, m2 = {}, {}
        exprs = [dag_xreplace(dag_xreplace(e, repl, m1), arg_names, m2) for e in exprs]
        reps, reduced = sp.cse(exprs, symbols=tmp, order="canonical")
        for s, e in reps:
            body.append(f"{s.name} = {pr(e)}")
        for (target, _), e in zip(defs, reduced):
            tcode = target if isinstance(target, str) else pr(target)
            body.append(f"{tcode} = {pr(e)}")

    for st in stages:
        if isinstance(st, RawStage):
            body.extend(st.lines)
        else:
            emit_stage(st, False)
    body.extend(k.prologue)
    if outputs:
        emit_stage(outputs, True)
    body.extend(k.epilogue)
    if k.ret is not None:
        body.append(f"return {k.ret}")
    lines.extend("    " + b for b in body)
    return "\n".join(lines) + "\n"


def render_module(title: str, source: str, kernels: list, imports: list[str], preamble: str = "") -> str:
    """A module: header, imports, then each kernel (a Kernel, or a (name, source) pair for templates)."""
    out = [HEADER.format(title=title, source=source)]
    out.append("import math\n\nimport numba as nb\nimport numpy as np\n")
    for imp in imports:
        out.append(imp + "\n")
    if preamble:
        out.append("\n" + preamble.strip("\n") + "\n")
    names = []
    for k in kernels:
        if isinstance(k, Kernel):
            names.append(k.name)
        else:  # a template: every function it defines
            names.extend(re.findall(r"^def (\w+)\(", k[1], flags=re.M))
    out.append("\n__all__ = [" + ", ".join(repr(n) for n in names) + "]\n")
    for k in kernels:
        out.append("\n\n" + (render_kernel(k) if isinstance(k, Kernel) else k[1].strip("\n") + "\n"))
    return "".join(out)
