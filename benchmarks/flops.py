"""Floating-point operations per filter step, counted from the generated source (``ast``), not measured.

    from flops import step_flops
    step_flops("se2se2", "position")   # -> Counts(flops=..., div=..., sincos=..., sqrt=..., atan2=...)

What is counted: the fused step a loop runs per trajectory-step — ``step_<meas>`` when the module has one, else
``predict`` + ``update_<meas>`` — with every function it calls expanded (the angle functions of
generated/special.py, the safeguards), plus the output conversion ``physical_into``.

* ``flops``: every +, −, ×, ÷ of a binary operation (an FMA the compiler forms from a × and a + counts 2);
  unary minus, comparisons, abs/max/min are not counted;  ``x**k`` counts k − 1 multiplications;
* ``div``: the divisions among them (also in ``flops``);
* ``sincos``: sin and cos of one argument count as one sincos; ``sqrt``, ``atan2`` separately (not in ``flops``);
* branches: a two-way branch (Taylor series vs closed form, ``if ...: return``, ``a if c else b``) counts its more
  expensive side; an ``if`` without ``else`` whose body does not return is a safeguard for irregular steps (angle-variance
  cap, gain damping beyond π, PD repair) and counts as not taken (its test is counted).
"""

from __future__ import annotations

import ast
import importlib
from dataclasses import dataclass, field
from pathlib import Path

__all__ = ["Counts", "step_flops", "function_flops", "cost", "smoother_step_flops", "smoother_bound", "imm_step_flops", "imm_bound"]


@dataclass
class Counts:
    """Operation counts of one code path."""

    flops: int = 0
    div: int = 0
    sincos: int = 0
    sqrt: int = 0
    atan2: int = 0
    _trig: set = field(default_factory=set, repr=False)

    def __add__(self, o: "Counts") -> "Counts":
        return Counts(self.flops + o.flops, self.div + o.div, self.sincos + o.sincos, self.sqrt + o.sqrt,
                      self.atan2 + o.atan2)

    def key(self):
        return (self.flops + 20 * (self.sincos + self.sqrt + self.atan2), self.div)


def _max(a: Counts, b: Counts) -> Counts:
    return a if a.key() >= b.key() else b


class _Counter:
    def __init__(self, modules):
        self.defs = {}
        for mod in modules:
            tree = ast.parse(Path(mod.__file__).read_text())
            for node in tree.body:
                if isinstance(node, ast.FunctionDef):
                    self.defs.setdefault(node.name, node)

    # -------------------------------------------------------------- expressions
    def expr(self, e, trig) -> Counts:
        c = Counts()
        if isinstance(e, ast.BinOp):
            c = self.expr(e.left, trig) + self.expr(e.right, trig)
            if isinstance(e.op, ast.Pow) and isinstance(e.right, ast.Constant):
                c.flops += int(e.right.value) - 1
            else:
                c.flops += 1
                if isinstance(e.op, ast.Div):
                    c.div += 1
            return c
        if isinstance(e, ast.UnaryOp):
            return self.expr(e.operand, trig)
        if isinstance(e, ast.BoolOp):
            for v in e.values:
                c = c + self.expr(v, trig)
            return c
        if isinstance(e, ast.Compare):
            c = self.expr(e.left, trig)
            for v in e.comparators:
                c = c + self.expr(v, trig)
            return c
        if isinstance(e, ast.IfExp):
            return self.expr(e.test, trig) + _max(self.expr(e.body, trig), self.expr(e.orelse, trig))
        if isinstance(e, ast.Call):
            for a in e.args:
                c = c + self.expr(a, trig)
            f = e.func
            name = f.attr if isinstance(f, ast.Attribute) else getattr(f, "id", "")
            if name in ("sin", "cos"):
                arg = ast.dump(e.args[0])
                if arg not in trig:
                    trig.add(arg)
                    c.sincos += 1
            elif name == "sqrt":
                c.sqrt += 1
            elif name == "atan2":
                c.atan2 += 1
            elif name in self.defs:
                c = c + self.function(name)
            return c
        if isinstance(e, (ast.Tuple, ast.List)):
            for v in e.elts:
                c = c + self.expr(v, trig)
        if isinstance(e, ast.Subscript):
            return self.expr(e.slice, trig) if not isinstance(e.slice, (ast.Constant, ast.Tuple)) else c
        return c

    # -------------------------------------------------------------- statements
    def block(self, stmts, trig) -> Counts:
        c = Counts()
        for i, s in enumerate(stmts):
            if isinstance(s, ast.If):
                c = c + self.expr(s.test, trig)
                returns = any(isinstance(b, ast.Return) for b in s.body)
                if returns and not s.orelse:
                    return c + _max(self.block(s.body, set(trig)), self.block(stmts[i + 1:], trig))
                if s.orelse:
                    c = c + _max(self.block(s.body, set(trig)), self.block(s.orelse, set(trig)))
                # if without else: a safeguard of irregular steps, not taken
                continue
            if isinstance(s, (ast.Assign, ast.AugAssign, ast.AnnAssign)):
                c = c + self.expr(s.value, trig)
                if isinstance(s, ast.AugAssign):
                    c.flops += 1
                    c.div += isinstance(s.op, ast.Div)
            elif isinstance(s, ast.Return) and s.value is not None:
                c = c + self.expr(s.value, trig)
            elif isinstance(s, ast.Expr):
                c = c + self.expr(s.value, trig)
            elif isinstance(s, ast.For):
                raise ValueError("loops are not counted: count a straight-line kernel")
        return c

    def function(self, name) -> Counts:
        return self.block(self.defs[name].body, set())


def function_flops(module, names) -> Counts:
    """Summed counts of the functions ``names`` of a generated module (calls expanded, see the module docstring)."""
    special = importlib.import_module(module.__name__.rsplit(".", 1)[0] + ".special")
    cnt = _Counter([module, special])
    total = Counts()
    for n in names:
        total = total + cnt.function(n)
    return total


def step_names(module, meas: str) -> list[str]:
    """The kernels one trajectory-step runs: the fused ``step_try_<meas>`` (``step_<meas>`` in older modules) if
    generated, else predict + update (the rare fallback to ``update_<meas>`` is not counted)."""
    fused = [f for f in (f"step_try_{meas}", f"step_{meas}") if hasattr(module, f)]
    names = fused[:1] if fused else ["predict", f"update_{meas}"]
    return names + ["physical_into"]


def step_flops(model: str, meas: str = "position") -> Counts:
    """Counts of one predict + update + output step of a registry model (see the module docstring)."""
    from lgekf.core.registry import get_model

    mod = get_model(model).kernels
    return function_flops(mod, step_names(mod, meas))


# ---------------------------------------------------------------------------------------------------------------------
# bounds of the smoother and the IMM, in filter steps (what the goals are stated against)

def cost(c: Counts) -> int:
    """One number per code path: flops + 20 per sincos, sqrt or atan2 (``Counts.key``; the weight of a libm call)."""
    return c.key()[0]


def smoother_step_flops(model: str, meas: str = "position") -> Counts:
    """One trajectory-step of RTS smoothing: the forward pass's fused filter step (storing the prediction adds no
    arithmetic) plus the backward pass's ``smooth_step_at``."""
    from lgekf.core.registry import get_model

    mod = get_model(model).kernels
    return step_flops(model, meas) + function_flops(mod, ["smooth_step_at"])


def smoother_bound(model: str, meas: str = "position") -> float:
    """(forward + backward) / filter step, in ``cost``: the time ratio smoothing would have at the filter's speed
    per flop (what ``benchmarks/bench_smoother.py``'s same/scalar is compared with)."""
    return cost(smoother_step_flops(model, meas)) / cost(step_flops(model, meas))


# mixing in the common coordinates (6): per source and target, the mean's w·c (2 flops × 6) and the covariance's
# w·(P + d dᵀ) (4 flops × 36)
_COMMON_MIX = 2 * 6 + 4 * 36


def imm_step_flops(models, meas: str = "position", iterations: int = 2) -> int:
    """``cost`` of one IMM step of the modes' models (a list of registry names, one per mode), the rule of
    ``lgekf.estimators.imm`` with its overheads left out:

    * every mode's fused filter step (``step_ll_<meas>``, which also gives log det S) and its output conversion;
    * modes of one group: the mixing on the group for each target mode and once more for the combined output, each
      ``iterations`` mean iterations (M ``between_add`` and one ``retract`` each; two is typical) and M
      ``mix_transport``;
    * modes of different groups: every mode to the common coordinates (``common_of_state``), for each target mode
      and for the combined output a mixture of M sources in them (``_COMMON_MIX``), each target back to its state
      (``state_of_common``).
    """
    from lgekf.core.registry import get_model

    M = len(models)
    mods = [get_model(m).kernels for m in models]
    f = {}

    def c(mod, name):
        if (mod, name) not in f:
            f[mod, name] = cost(function_flops(mod, [name]))
        return f[mod, name]

    total = sum(c(mod, n) for mod in mods for n in step_names(mod, meas)[:-1]) + sum(c(mod, "physical_into") for mod in mods)
    if len(set(models)) == 1:
        mod = mods[0]
        one_mix = iterations * (M * c(mod, "between_add") + c(mod, "retract")) + M * c(mod, "mix_transport")
        return total + (M + 1) * one_mix
    total += sum(c(mod, "common_of_state") for mod in mods) + sum(c(mod, "state_of_common") for mod in mods)
    return total + (M + 1) * M * _COMMON_MIX


def imm_bound(models, meas: str = "position") -> float:
    """IMM step / (M × the modes' mean filter step), in ``cost``: the ratio ``benchmarks/bench_imm.py`` measures,
    at the filters' speed per flop."""
    mean_step = sum(cost(step_flops(m, meas)) for m in models) / len(models)
    return imm_step_flops(models, meas) / (len(models) * mean_step)
