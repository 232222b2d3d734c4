"""The architecture as a test: imports go one way between layers, there are no import cycles, the runtime
never imports SymPy, and no module outside the definitions branches on a model's name.

Runtime layers (lower may not import higher): generated (0) < core, io (1) < estimators (2) < experiments (3) < apps (4)
< cli (5).  derive/: lie (0) < models, measurements (1) < algebra (2)
< codegen, paper (3).
"""

from __future__ import annotations

import ast
import functools
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
RUNTIME_LAYERS = {"generated": 0, "core": 1, "io": 1, "estimators": 2, "experiments": 3, "apps": 4, "cli": 5}
DERIVE_LAYERS = {"lie": 0, "models": 1, "measurements": 1, "algebra": 2, "codegen": 3, "paper": 3}


def _modules(pkg_dir: Path, pkg: str):
    for path in sorted(pkg_dir.rglob("*.py")):
        rel = path.relative_to(pkg_dir).with_suffix("")
        parts = [p for p in rel.parts if p != "__init__"]
        yield ".".join([pkg, *parts]), path, path.name == "__init__.py"


_IMPORT = re.compile(r"^[ \t]*(?:from[ \t]+[\w.]+[ \t]+)?import[ \t]")


def _import_lines(text: str) -> str:
    """The import statements of ``text`` (top-level and indented alike, a parenthesised list with its continuation
    lines), dedented, one per line: what ``ast`` needs to name a module's imports, without parsing its code."""
    out, lines, i = [], text.splitlines(), 0
    while i < len(lines):
        if _IMPORT.match(lines[i]):
            stmt = [lines[i].strip()]
            while " ".join(stmt).count("(") > " ".join(stmt).count(")") or stmt[-1].endswith("\\"):
                i += 1
                stmt.append(lines[i].strip())
            out.append(" ".join(stmt).replace("\\", " "))
        i += 1
    return "\n".join(out) + "\n"


@functools.lru_cache(maxsize=None)
def _imports(name: str, path: Path, is_pkg: bool) -> frozenset:
    """Absolute names of the modules ``path`` imports (relative imports resolved); parsed once per run (the generated
    modules are megabytes of source: parsing them for every test cost seconds each). A generated module is parsed
    from its import statements only (``_import_lines``: a whole parse of the 3-D models' modules took 10 s of CPU)."""
    text = path.read_text(encoding="utf-8")
    tree = ast.parse(_import_lines(text) if path.parent.name == "generated" else text)
    base = name.split(".") if is_pkg else name.split(".")[:-1]
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            out |= {a.name for a in node.names}
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                anchor = base[: len(base) - node.level + 1]
                mod = ".".join(anchor + ([node.module] if node.module else []))
            else:
                mod = node.module or ""
            out.add(mod)
            out |= {f"{mod}.{a.name}" for a in node.names}
    return frozenset(out)


def _layer(name: str, table: dict, pkg: str):
    parts = name.split(".")
    if len(parts) < 2 or parts[0] != pkg.split(".")[0]:
        return None
    key = parts[len(pkg.split("."))] if len(parts) > len(pkg.split(".")) else None
    return table.get(key)


def _runtime_graph():
    mods = {}
    for name, path, is_pkg in _modules(ROOT / "lgekf", "lgekf"):
        mods[name] = (path, is_pkg)
    for name, path, is_pkg in _modules(ROOT / "generated", "lgekf.generated"):
        mods[name] = (path, is_pkg)
    return mods


def test_runtime_imports_go_one_way():
    bad = []
    for name, (path, is_pkg) in _runtime_graph().items():
        if name in ("lgekf", "lgekf.__main__"):
            continue
        me = _layer(name, RUNTIME_LAYERS, "lgekf")
        for imp in _imports(name, path, is_pkg):
            if imp.startswith("lgekf.io") and name.startswith("lgekf.io") is False and me == 1:
                bad.append(f"{name} (core) imports {imp}: core and io are independent")
            if imp.startswith("lgekf.core") and name.startswith("lgekf.io"):
                bad.append(f"{name} (io) imports {imp}: core and io are independent")
            if imp.startswith("lgekf.derive") and not name.startswith("lgekf.cli"):
                bad.append(f"{name} imports {imp} (only the CLI may import derive/, lazily)")
            if imp.startswith("lgekf.derive") or me is None:
                continue
            if not imp.startswith("lgekf.") or imp.startswith("lgekf.derive"):
                continue
            other = _layer(imp, RUNTIME_LAYERS, "lgekf")
            if other is not None and me is not None and other > me:
                bad.append(f"{name} (layer {me}) imports {imp} (layer {other})")
    assert not bad, "\n".join(bad)


def test_every_runtime_module_is_in_a_layer():
    loose = [n for n in _runtime_graph() if n not in ("lgekf", "lgekf.__main__") and _layer(n, RUNTIME_LAYERS, "lgekf") is None]
    assert not loose, f"modules outside the layers: {loose}"


def _find_cycle(mods: dict) -> None:
    """AssertionError naming the first import cycle among ``mods`` ({name: (path, is_pkg)}), top-level imports and
    imports inside functions alike (a lazy import is still a dependency)."""
    graph = {}
    for name, (path, is_pkg) in mods.items():
        graph[name] = {i for i in _imports(name, path, is_pkg) if i in mods and i != name and not name.startswith(i + ".")}
    state, stack = {}, []
    roots = {n for n in mods if "." not in n or n.count(".") == 1 and n.endswith(".derive")}

    def visit(n):
        state[n] = 1
        stack.append(n)
        for m in sorted(graph[n]):
            if m in roots or n in roots:
                continue
            if state.get(m) == 1:
                raise AssertionError("import cycle: " + " -> ".join(stack[stack.index(m):] + [m]))
            if not state.get(m):
                visit(m)
        stack.pop()
        state[n] = 2

    for n in sorted(graph):
        if not state.get(n):
            visit(n)


def test_no_import_cycles_in_the_runtime():
    _find_cycle(_runtime_graph())


def test_no_import_cycles_in_derive():
    _find_cycle({name: (path, is_pkg) for name, path, is_pkg in _modules(ROOT / "derive", "lgekf.derive")})


def test_kernel_names_are_formed_in_one_place():
    """Only ``ModelSpec.kernel`` (lgekf/core/registry.py) turns a family and a measurement into a kernel's name: no
    ``getattr(..., f"..._{measurement}")`` anywhere else in the runtime."""
    pat = re.compile(r"getattr\([^)]*f[\"']")
    hits = [f"{p.relative_to(ROOT)}:{i}: {line.strip()}" for p in sorted((ROOT / "lgekf").rglob("*.py"))
            if p.name != "registry.py" for i, line in enumerate(p.read_text(encoding="utf-8").splitlines(), 1) if pat.search(line)]
    assert not hits, "\n".join(hits)


def test_derive_imports_go_one_way():
    bad = []
    for name, path, is_pkg in _modules(ROOT / "derive", "lgekf.derive"):
        me = _layer(name, DERIVE_LAYERS, "lgekf.derive")
        for imp in _imports(name, path, is_pkg):
            if imp.startswith("lgekf.") and not imp.startswith("lgekf.derive"):
                bad.append(f"{name} imports the runtime ({imp})")
            if not imp.startswith("lgekf.derive."):
                continue
            other = _layer(imp, DERIVE_LAYERS, "lgekf.derive")
            if other is not None and me is not None and other > me and not (me == 1 and imp.endswith("position")):
                bad.append(f"{name} (layer {me}) imports {imp} (layer {other})")
    assert not bad, "\n".join(bad)


MODEL_NAMES = ("se2se2", "se2r3", "se2r2", "ctrv", "cv")


@pytest.mark.parametrize("folder", ["lgekf", "derive/codegen", "derive/algebra.py", "derive/lie", "derive/measurements"])
def test_no_branch_on_a_model_name(folder):
    """`if ... == "cv"`, `in ("se2se2", ...)`, `model.name ==` are model knowledge outside a definition."""
    pat = re.compile(r"(==|!=|\bin)\s*\(?\s*[\"'](" + "|".join(MODEL_NAMES) + r")[\"']|\.name\s*==")
    target = ROOT / folder
    files = [target] if target.is_file() else sorted(target.rglob("*.py"))
    hits = [f"{p.relative_to(ROOT)}:{i}: {line.strip()}" for p in files
            for i, line in enumerate(p.read_text(encoding="utf-8").splitlines(), 1) if pat.search(line)]
    assert not hits, "\n".join(hits)


def _measurement_names() -> set:
    """The registered measurements (generated/registry.py, plain data)."""
    tree = ast.parse((ROOT / "generated" / "registry.py").read_text(encoding="utf-8"))
    for node in tree.body:
        if isinstance(node, ast.Assign) and any(getattr(t, "id", None) == "MEASUREMENTS" for t in node.targets):
            return set(ast.literal_eval(node.value))
    raise AssertionError("generated/registry.py has no MEASUREMENTS")


def _names_a_measurement(node, names: set) -> bool:
    if isinstance(node, ast.Constant):
        return node.value in names
    if isinstance(node, (ast.Tuple, ast.List, ast.Set)):
        return any(isinstance(e, ast.Constant) and e.value in names for e in node.elts)
    return False


def test_no_branch_on_a_measurement_name():
    """No comparison against a measurement's name (``== "pose"``, ``!= "position"``, ``in ("pose", ...)``) in the
    kernel code of ``derive/codegen/`` (its modules and its templates) and of ``lgekf/estimators/``: a per-measurement
    loop is emitted from the measurement definitions (``derive/measurements/``, the only place that knows them), and the
    runtime reaches it through ``ModelSpec.kernel`` / ``lgekf.core.registry.imm_kernel``. Scope: only these two
    folders for now; ``lgekf/apps``, ``lgekf/cli`` and ``lgekf/experiments`` are being cleaned of their comparisons
    separately (issue #26) and join this test when they are."""
    names = _measurement_names()
    assert {"pose", "position"} <= names
    ops = (ast.Eq, ast.NotEq, ast.In, ast.NotIn, ast.Is, ast.IsNot)
    hits = []
    files = sorted((ROOT / "derive" / "codegen").rglob("*.py")) + sorted((ROOT / "lgekf" / "estimators").rglob("*.py"))
    for path in files:
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Compare) and any(isinstance(op, ops) for op in node.ops) and any(
                    _names_a_measurement(o, names) for o in (node.left, *node.comparators)):
                hits.append(f"{path.relative_to(ROOT)}:{node.lineno}: {ast.unparse(node)}")
    quoted = "|".join(re.escape(n) for n in sorted(names))
    pat = re.compile(rf"(==|!=|\bin|\bis)\s*[(\[{{]?\s*[\"']({quoted})[\"']|[\"']({quoted})[\"']\s*(==|!=)")
    for path in sorted((ROOT / "derive" / "codegen" / "templates").glob("*.tmpl")):  # numba templates: not Python yet
        for i, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
            if pat.search(line):
                hits.append(f"{path.relative_to(ROOT)}:{i}: {line.strip()}")
    assert not hits, "comparisons against a measurement name:\n" + "\n".join(hits)
