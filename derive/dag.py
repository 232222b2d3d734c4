"""SymPy traversals that visit each distinct subexpression once.

The derived kernels of the 3-D models are expression DAGs: the same subexpression (a rotation entry, a 1/sinc of an
angle) is shared by many entries of a Jacobian.  SymPy's ``atoms``, ``free_symbols``, ``has``, ``replace`` and
``xreplace`` walk an expression as a tree, so a shared subtree is walked once per path that reaches it (the
emitter's cold render of SE(3)×SE(3) spent most of its time in such walks).  The functions here compute the same
results memoised per distinct node (SymPy nodes are hashable and immutable): ``dag_replace`` and ``dag_xreplace``
rebuild exactly the nodes ``Basic.replace`` and ``Basic.xreplace`` would (same order of rebuilding, same
evaluation), so the generated code is unchanged.
"""

from __future__ import annotations

import sympy as sp

__all__ = ["dag_atoms", "dag_free_symbols", "dag_has", "dag_replace", "dag_xreplace"]


def _nodes(exprs):
    """Every distinct node of ``exprs`` (an iterable of expressions), each once."""
    seen = set()
    stack = [sp.sympify(e) for e in exprs]
    while stack:
        node = stack.pop()
        if node in seen:
            continue
        seen.add(node)
        stack.extend(getattr(node, "args", ()))
    return seen


def dag_atoms(exprs, *types) -> set:
    """The subexpressions of ``exprs`` that are instances of ``types`` (``Basic.atoms(*types)`` over all of them)."""
    return {n for n in _nodes(exprs) if isinstance(n, types)}


def dag_free_symbols(exprs) -> set:
    """The symbols of ``exprs`` (``free_symbols`` of each, joined; no bound variables occur in emitted kernels)."""
    return {n for n in _nodes(exprs) if isinstance(n, sp.Symbol)}


def dag_has(expr, *types) -> bool:
    """Whether ``expr`` holds an instance of ``types`` (``Basic.has`` with classes)."""
    return any(isinstance(n, types) for n in _nodes([expr]))


def dag_replace(expr, query, value, memo: dict | None = None):
    """``expr.replace(query, value)`` for callables (simultaneous, as SymPy's default), each distinct node rebuilt
    once.  ``memo`` may be shared between calls with the same ``query`` and ``value``."""
    memo = {} if memo is None else memo

    def walk(rv):
        hit = memo.get(rv)
        if hit is not None:
            return hit
        key = rv
        args = getattr(rv, "args", None)
        if args is not None:
            if args:
                newargs = tuple(walk(a) for a in args)
                if args != newargs:
                    rv = rv.func(*newargs)
                    for i, e in enumerate(args):
                        if rv == e and e != newargs[i]:
                            memo[key] = rv
                            return rv
            if query(rv):
                v = value(rv)
                if v is not None and v != rv:
                    rv = v
        memo[key] = rv
        return rv

    return walk(sp.sympify(expr))


def dag_xreplace(expr, rule: dict, memo: dict | None = None):
    """``expr.xreplace(rule)``, each distinct node rebuilt once (``memo`` may be shared between calls with one rule)."""
    memo = {} if memo is None else memo
    if not rule:
        return sp.sympify(expr)

    def walk(node):
        """(the node after the rule, whether anything in it was replaced), as ``Basic._xreplace``."""
        if node in rule:
            return rule[node], True
        hit = memo.get(node)
        if hit is not None:
            return hit
        out = (node, False)
        args = getattr(node, "args", ())
        if args:
            new = [walk(a) for a in args]
            if any(changed for _, changed in new):
                out = (node.func(*(a for a, _ in new)), True)
        memo[node] = out
        return out

    return walk(sp.sympify(expr))[0]
