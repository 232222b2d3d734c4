"""`lgekf derive`: regenerate generated/ from the symbolic source, or check that it is fresh."""

from __future__ import annotations

import difflib
import hashlib
import io
import os
import sys
import time
from functools import lru_cache
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import sympy as sp

from ..lie.special import ANGLE_FUNCTIONS, taylor_coefficients
from ..measurements import load_measurements
from ..models import load_models
from ..space import DEFAULT_SPACE
from .emitter import model_kernels, registry_entry, se2_kernels, se3_kernels
from .families.imm import render_imm
from .families.monitor import MONITOR_HELPERS, MONITOR_NAMES, TEMPLATE_HELPERS
from .printer import HEADER, SINC_FAMILY, render_module
from .template import load
from .families.soa import VECTOR_NAMES, vector_helpers_source

__all__ = ["render_all", "write_all", "check", "GENERATED_DIR", "main"]

GENERATED_DIR = Path(__file__).resolve().parent.parent.parent / "generated"

PREAMBLE = '''
# fused steps use FMA contraction only ("contract"); every other IEEE rule holds
FASTMATH = {"contract"}
'''


def _horner(coeffs, var="x2"):
    """Horner form of Σ coeffs[k] var^k (coefficients as correctly rounded floats)."""
    s = repr(float(coeffs[-1]))
    for c in reversed(coeffs[:-1]):
        s = f"{float(c)!r} + {var} * ({s})"
    return s


FAMILY = SINC_FAMILY  # the angle functions of Φ and of the SE(2) exponential, computed together (printer.py)


def family_source(polys: dict) -> str:
    """``sinc_family(x, s, c) -> (sinc, cosc, sinc2, cosc2)`` with one reciprocal of x and one division by 1 + c.

    The same Taylor polynomials and thresholds as the four functions (their ``tau``; the code asserts that sinc,
    cosc and cosc2 share theirs), and the same closed forms with the divisions shared: h = 1 − cos x (as
    sin²x/(1 + cos x) when cos x > 0), sinc = s·(1/x), cosc = h·(1/x), cosc2 = h·(1/x)², sinc2 = (x − s)·(1/x)².
    A multiplication by a rounded reciprocal adds at most half an ulp to each (tests/derive/test_special_accuracy.py
    checks the family against mpmath on both sides of every threshold). The printer calls it when a stage needs
    two or more of the four for one angle (derive/codegen/printer.py). Inlined by numba (``inline="always"``):
    LLVM would not inline it by itself, and a call left in a fused step keeps numba's reference counting of the
    step's arrays (derive/codegen/fused.py).
    """
    from ..lie.special import cosc, cosc2, sinc, sinc2

    small = sinc.tau
    assert cosc.tau == small and cosc2.tau == small and sinc2.tau > small
    return load("sinc_family.py.tmpl").format(family=FAMILY, small=repr(small), sinc2_tau=repr(sinc2.tau), **polys)


def render_special() -> str:
    out = [HEADER.format(title="Angle functions with removable singularities, Taylor-safe near 0.", source="derive/lie/special.py")]
    out.append("import math\n\nimport numba as nb\n")
    # IEEE division (inf/NaN) instead of ZeroDivisionError paths: the closed forms divide only away from 0, and the
    # fused steps that inline these functions need no exception exits (derive/codegen/fused.py)
    out.append('\nSCALAR_ERRORS = "numpy"\n')
    names = [f.__name__ for f in ANGLE_FUNCTIONS] + [FAMILY, "wrap_angle", "wrap_angle_sum", "gain_damping"] + VECTOR_NAMES
    out.append("\n__all__ = [" + ", ".join(repr(n) for n in names) + "]\n")
    polys = {}
    for f in ANGLE_FUNCTIONS:
        coeffs = taylor_coefficients(f)
        parity = f.parity
        # keep the non-zero (even or odd) coefficients, in powers of x^2
        if parity == 1:
            c = [coeffs[k] for k in range(0, len(coeffs), 2)]
            poly = _horner(c)
        else:
            c = [coeffs[k] for k in range(1, len(coeffs), 2)]
            poly = f"x * ({_horner(c)})"
        xs = sp.Symbol("x")
        doc = f"{f.__name__}(x) = {sp.sstr(f.definition(xs))}; s = sin x, c = cos x.\n\n"
        doc += f"    |x| < {f.tau!r}: Taylor polynomial of degree {f.order} (coefficients from SymPy);\n"
        doc += f"    otherwise the cancellation-free closed form `{f.stable}`."
        polys[f.__name__] = poly
        out.append(load("angle_function.py.tmpl").format(name=f.__name__, doc=doc, tau=repr(f.tau), poly=poly, stable=f.stable))
    out.append(family_source(polys))
    out.append(load("special_helpers.py.tmpl"))  # wrap_angle, wrap_angle_sum, gain_damping
    out.append(vector_helpers_source())
    return "".join(out)


IMPORTS = ["from .special import " + ", ".join(f.__name__ for f in ANGLE_FUNCTIONS) + f", {SINC_FAMILY}, gain_damping, wrap_angle, wrap_angle_sum  # noqa: F401"]
IMPORTS.append("from .special import " + ", ".join(VECTOR_NAMES) + "  # noqa: F401")  # SIMD kernels (codegen/soa.py)
IMPORTS.append("from .monitor import " + ", ".join(TEMPLATE_HELPERS) + "  # noqa: F401")  # the divergence monitor (codegen/monitor.py)


def render_monitor() -> str:
    """``generated/monitor.py``: the divergence monitor's model-independent kernels (``derive/codegen/monitor.py``)."""
    return HEADER.format(title="The divergence monitor's model-independent kernels (two-point start, scan, speed std).",
                         source="derive/codegen/monitor.py") + MONITOR_HELPERS.replace(
        "import numpy as np\n", f"import numpy as np\n\n__all__ = {MONITOR_NAMES!r}\n", 1)


def _fitting(model, measurements):
    """(measurements that fit ``model``, {name: reason} of those that do not)."""
    fit, refused = {}, {}
    for name, meas in measurements.items():
        why = meas.fits(model)
        if why is None:
            fit[name] = meas
        else:
            refused[name] = why
    return fit, refused


#: where rendered model modules are kept, keyed by a digest of every derive/ source (``render_cache_dir``)
CACHE_ENV = "LGEKF_DERIVE_CACHE"


def render_cache_dir() -> Path | None:
    """The folder of rendered model modules: ``$LGEKF_DERIVE_CACHE`` ("off" for none), else
    ``$XDG_CACHE_HOME/lgekf/derive`` (``~/.cache/lgekf/derive``).

    A model's module is SymPy work (seconds for a planar model, about a minute for SE(3)×R⁶), and ``lgekf derive``,
    ``--check`` and the tests render the same sources several times; the cache keys each module by a digest of every
    file under derive/ (and of a user's definition folders), SymPy's and Python's versions and the model's name, so a
    change anywhere in the derivation renders again (``sources_digest``)."""
    env = os.environ.get(CACHE_ENV)
    if env is not None:
        return None if env.strip().lower() in ("off", "0", "") else Path(env)
    return Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache") / "lgekf" / "derive"


@lru_cache(maxsize=None)
def sources_digest(models_dir=None, meas_dir=None) -> str:
    """SHA-256 of every .py and .tmpl file under derive/ (path and bytes), of the definition folders given, and of
    SymPy's and Python's versions: what a rendered module depends on."""
    h = hashlib.sha256()
    root = Path(__file__).resolve().parent.parent
    folders = [(root, "derive")] + [(Path(d), f"defs{i}") for i, d in enumerate((models_dir, meas_dir)) if d is not None]
    for folder, label in folders:
        for path in sorted(folder.rglob("*")):
            if path.suffix in (".py", ".tmpl") and "__pycache__" not in path.parts:
                h.update(f"{label}/{path.relative_to(folder).as_posix()}\0".encode())
                h.update(path.read_bytes())
    h.update(f"sympy {sp.__version__}; python {sys.version}".encode())
    return h.hexdigest()


def cached_text(name: str, compute, cache: bool = True, models_dir=None, meas_dir=None) -> tuple[str, bool]:
    """``compute()`` (a str that depends on the derivation's sources only), read from the render cache when the same
    sources made it before (``render_cache_dir``, file ``<sources_digest>-<name>``), else computed and kept there.
    Returns (text, whether it came from the cache)."""
    folder = render_cache_dir() if cache else None
    if folder is not None:
        path = folder / f"{sources_digest(models_dir, meas_dir)[:40]}-{name}"
        try:
            return path.read_text(encoding="utf-8"), True
        except OSError:
            pass
    text = compute()
    if folder is not None:
        try:  # written whole and renamed: a concurrent render reads the old file or the new, never a part
            folder.mkdir(parents=True, exist_ok=True)
            tmp = path.with_suffix(f".{os.getpid()}.tmp")
            tmp.write_text(text, encoding="utf-8")
            os.replace(tmp, path)
            _prune(folder)
        except OSError:  # a read-only or full cache folder only costs the next render its time
            pass
    return text, False


def _render_model(args) -> tuple[str, str]:
    name, models_dir, meas_dir, cache = args
    src, _ = cached_text(f"{name}.py", lambda: _render_model_now(name, models_dir, meas_dir)[1], cache, models_dir, meas_dir)
    return f"{name}.py", src


def cached_verify(cache: bool = True) -> tuple[int, str, bool]:
    """``derive.paper.verify.run_verify``'s exit code and report, from the render cache when the same derivation
    sources (the transcription of the paper among them) were verified before. Returns (code, report, from cache)."""
    from ..paper.verify import run_verify

    def compute():
        buf = io.StringIO()
        rc = run_verify(buf)
        return f"{rc}\n{buf.getvalue()}"

    text, hit = cached_text("verify.txt", compute, cache)
    rc, _, report = text.partition("\n")
    return int(rc), report, hit


#: rendered modules and verification reports kept in the cache folder (the newest): a few generations of each
CACHE_KEEP = 64


def _prune(folder: Path) -> None:
    """Delete all but the ``CACHE_KEEP`` newest modules and reports of the cache folder (each source change adds a
    generation)."""
    files = sorted([*folder.glob("*.py"), *folder.glob("*.txt")], key=lambda p: p.stat().st_mtime, reverse=True)
    for old in files[CACHE_KEEP:]:
        old.unlink(missing_ok=True)


def _render_model_now(name, models_dir, meas_dir) -> tuple[str, str]:
    model = load_models(models_dir)[name]
    fit, _ = _fitting(model, load_measurements(meas_dir))
    title = f"{model.description}: model quantities, fused predict/update steps and loops."
    src_path = f"derive/models/{name}.py" if models_dir is None else f"{Path(models_dir).name}/{name}.py"
    src = render_module(title, f"{src_path} (definition) through derive/codegen/emitter.py and derive/algebra.py",
                        model_kernels(model, fit), IMPORTS, PREAMBLE)
    return f"{name}.py", src


def _noise_inputs(meas) -> tuple | None:
    """For each entry of z, the index of its std in ``noise_names`` when R = diag(σ_idx²); None otherwise."""
    R = sp.Matrix(meas.R())
    syms = meas.noise_symbols
    if R != sp.diag(*[R[i, i] for i in range(R.rows)]):
        return None
    out = []
    for i in range(R.rows):
        idx = [j for j, sd in enumerate(syms) if sp.simplify(R[i, i] - sd**2) == 0]
        if len(idx) != 1:
            return None
        out.append(idx[0])
    return tuple(out)


def render_registry(models: dict, measurements: dict) -> str:
    """generated/registry.py: the plain-data model table the runtime reads (no SymPy at run time)."""
    import pprint

    table = {}
    for name, model in models.items():
        fit, refused = _fitting(model, measurements)
        table[name] = registry_entry(model, fit, refused)
    meas = {
        name: {"description": m.description, "space": m.space.name, "z_names": tuple(m.z_names), "noise_names": tuple(m.noise_names),
               "angles": tuple(m.angles), "dim": m.m, "noise_inputs": _noise_inputs(m)}
        for name, m in measurements.items()
    }
    out = [HEADER.format(title="The model table: one entry per motion-model definition, read by lgekf.core.registry.",
                         source="derive/models/*.py, derive/measurements/*.py through derive/codegen/build.py")]
    out.append("\n__all__ = [\"SPACES\", \"DEFAULT_SPACE\", \"MODELS\", \"MEASUREMENTS\"]\n")
    spaces = {}
    for sp_ in [DEFAULT_SPACE] + [m.space for m in models.values()] + [m.space for m in measurements.values()]:
        spaces.setdefault(sp_.name, {"dim": sp_.dim, "common_names": tuple(sp_.common_names),
                                     "position_names": tuple(sp_.position_names), "mixes": sp_.mixes,
                                     "monitored": sp_.monitored, "common_angles": tuple(sp_.common_angles),
                                     "common_velocity": tuple(sp_.common_velocity),
                                     "dispatch_module": sp_.dispatch_module, "imm_module": sp_.imm_module,
                                     "imm_modes": sp_.default_imm_modes})
    out.append("\n#: the spaces of motion (derive/space.py): their common coordinates and what the generated loops serve\n")
    out.append("SPACES = " + pprint.pformat(spaces, sort_dicts=False, width=110) + "\n")
    out.append(f"\n#: the space of the commands' defaults (the paper's plane)\nDEFAULT_SPACE = {DEFAULT_SPACE.name!r}\n")
    out.append("\nMODELS = " + pprint.pformat(table, sort_dicts=False, width=110) + "\n")
    out.append("\nMEASUREMENTS = " + pprint.pformat(meas, sort_dicts=False, width=110) + "\n")
    return "".join(out)


class _NoBar:
    def update(self, n=1):
        pass

    def close(self):
        pass


def _bar(total: int):
    """A tqdm bar over the models on a terminal (an uncached derivation takes about a minute), nothing otherwise."""
    if not sys.stderr.isatty():
        return _NoBar()
    try:
        from tqdm import tqdm
    except ImportError:  # pragma: no cover - tqdm is a dependency
        return _NoBar()
    return tqdm(total=total, desc="lgekf derive", unit="model", leave=False, file=sys.stderr)


def _mixing_spaces(models: dict) -> list:
    """The spaces of the models whose IMM loop is generated (``Space.mixes``), in order of first appearance."""
    out = []
    for m in models.values():
        if m.space.mixes and m.space not in out:
            out.append(m.space)
    return out


def render_all(jobs: int = 2, models_dir=None, meas_dir=None, cache: bool = True) -> dict[str, str]:
    """{file name: source} for every generated module (deterministic).

    ``models_dir`` / ``meas_dir``: folders of definitions other than the package's own (a test's toy
    model, a user's model): rendered by the same emitter. ``cache``: reuse model modules rendered from the same
    sources (``render_cache_dir``); False renders every one.
    """
    models = load_models(models_dir)
    measurements = load_measurements(meas_dir)
    files = {"special.py": render_special(), "monitor.py": render_monitor()}
    files["se2.py"] = render_module(
        "SE(2) building blocks: hat, vee, exp, log, inverse, Ad, ad, right Jacobian Φ and Φ^-1.",
        "derive/lie/groups.py through derive/codegen/emitter.py", se2_kernels(), IMPORTS, PREAMBLE)
    files["se3.py"] = render_module(
        "SO(3) and SE(3) building blocks: hat, vee, exp, log (also near |φ| = π), inverse, Ad, ad, right Jacobian Φ and Φ^-1;\n"
        "tangent order (x, y, z, φx, φy, φz), T = μ·exp(ε), log(exp(-ξ) exp(ξ + δ)) ≈ Φ(ξ) δ.",
        "derive/lie/so3.py, derive/lie/se3.py through derive/codegen/families/group.py", se3_kernels(), IMPORTS, PREAMBLE)
    # the largest state first (its module takes longest: SE(3)×R⁶ about as long as all the others), so that the
    # processes finish together
    jobs_args = [(n, models_dir, meas_dir, cache) for n in sorted(models, key=lambda n: (-models[n].n, n))]
    bar = _bar(len(jobs_args))
    if jobs > 1 and len(jobs_args) > 1:
        with ProcessPoolExecutor(max_workers=jobs) as ex:
            for fname, src in ex.map(_render_model, jobs_args):
                files[fname] = src
                bar.update(1)
    else:
        for a in jobs_args:
            fname, src = _render_model(a)
            files[fname] = src
            bar.update(1)
    bar.close()
    files["registry.py"] = render_registry(models, measurements)
    from .dispatch import render_dispatch

    # the IMM's loop mixes the models of each space it is written for (derive.space.Space.mixes): one dispatch module
    # and one loop per space, named by the space
    for space in _mixing_spaces(models):
        mixed = {n: m for n, m in models.items() if m.space is space}
        mixed_meas = {n: m for n, m in measurements.items() if m.space is space}
        files[f"{space.dispatch_module}.py"] = render_dispatch(mixed, {n: _fitting(m, mixed_meas)[0] for n, m in mixed.items()},
                                                               mixed_meas)
        files[f"{space.imm_module}.py"] = render_imm(space, mixed_meas)  # per measurement from its definition (families/imm.py)
    files["__init__.py"] = HEADER.format(
        title="Numba kernels generated from derive/ (SymPy): one module per motion model, SE(2) and SE(3) blocks, the model table.",
        source="derive/codegen/build.py",
    )
    return dict(sorted(files.items()))


def write_all(outdir: Path = GENERATED_DIR, jobs: int = 2, models_dir=None, meas_dir=None, cache: bool = True) -> list[str]:
    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    files = render_all(jobs, models_dir, meas_dir, cache)
    for name, src in files.items():
        (outdir / name).write_text(src, encoding="utf-8")
    return list(files)


def check(outdir: Path = GENERATED_DIR, jobs: int = 2, stream=sys.stdout, rendered: dict[str, str] | None = None,
          cache: bool = True) -> int:
    """0 if ``outdir`` equals a fresh regeneration, else 1 with a unified diff.

    ``rendered``: the regeneration ({file name: text}, as ``render_all`` returns it) when the caller has it
    already (the tests render once per session); None renders now.
    """
    files = render_all(jobs, cache=cache) if rendered is None else rendered
    stale = 0
    for name in sorted(files):
        new = files[name]
        old_path = Path(outdir) / name
        old = old_path.read_text(encoding="utf-8") if old_path.exists() else ""
        if new != old:
            stale += 1
            diff = difflib.unified_diff(
                old.splitlines(True), new.splitlines(True), f"generated/{name} (checked in)", f"generated/{name} (regenerated)"
            )
            stream.writelines(list(diff)[:200])
    extra = {p.name for p in Path(outdir).glob("*.py")} - set(files)
    for name in sorted(extra):
        stale += 1
        stream.write(f"generated/{name}: not produced by derive (stale file)\n")
    if stale:
        stream.write(f"generated/ is stale: {stale} file(s) differ; run `lgekf derive`\n")
        return 1
    stream.write("generated/ is up to date\n")
    return 0


def main(argv=None) -> int:
    import argparse

    ap = argparse.ArgumentParser(prog="lgekf derive", description="Derive the LG-EKF ingredients with SymPy and emit numba kernels.")
    ap.add_argument("--check", action="store_true", help="regenerate into a temporary folder and fail with a diff if generated/ is stale")
    ap.add_argument("--verify", action="store_true", help="compare every equation printed in the paper with the derivation")
    ap.add_argument("--out", type=Path, default=GENERATED_DIR, help="output folder (default: the package's generated/)")
    ap.add_argument("--jobs", type=int, default=2, help="processes used for code generation (default 2)")
    ap.add_argument("--no-cache", action="store_true",
                    help="render every model module anew (default: reuse those rendered from the same sources, "
                         f"kept in ${CACHE_ENV} or ~/.cache/lgekf/derive)")
    a = ap.parse_args(argv)
    t0 = time.perf_counter()
    if a.verify:
        rc, report, hit = cached_verify(cache=not a.no_cache)
        sys.stdout.write(report)
        print(f"verify: {time.perf_counter() - t0:.1f} s" + (" (the report of the same sources, from the render cache)" if hit else ""))
        return rc
    if a.check:
        rc = check(a.out, a.jobs, cache=not a.no_cache)
        print(f"check: {time.perf_counter() - t0:.1f} s")
        return rc
    names = write_all(a.out, a.jobs, cache=not a.no_cache)
    print(f"wrote {len(names)} files to {a.out} in {time.perf_counter() - t0:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
