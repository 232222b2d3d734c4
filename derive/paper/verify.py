"""Check every equation of the paper, as printed, against our derivation.

``python -m lgekf.derive.verify`` evaluates each :class:`derive.paper.PrintedEquation` and prints one
line per entry::

    <label> OK
    <label> ERRATUM <printed> -> <derived>      (a recorded erratum, KNOWN_ERRATA)
    <label> MISMATCH <printed> -> <derived>     (differs and is not recorded: exit status 1)
    <label> STALE ...                           (recorded as erratum but now matches: exit status 1)

followed by ``N equations: a OK, b errata``.  Two sides are equal when every entry of
``to_exact(printed) - to_exact(derived)`` simplifies to 0 (after the entry's stated ``assume``
rewrite); shapes must agree.
"""

from __future__ import annotations

import sys
import time

import sympy as sp

from .transcription import PRINTED, PrintedEquation
from ..lie.special import to_exact

__all__ = ["KNOWN_ERRATA", "ERRATA_TABLE", "run_verify", "compare", "errata_table_markdown", "main"]


# label -> one-line explanation, including whether the typo changes a filter's output
KNOWN_ERRATA: dict[str, str] = {
    "se2_def": (
        "SE(2) definition prints the bottom-left block as 0^{1×1}; it must be 0^{1×2}. "
        "Typesetting only: does not change any filter output."
    ),
    "ad_se2": (
        "ad_SE(2) prints the bottom-right entry as 1; the Lie bracket gives 0. WOULD change the filter: "
        "Φ computed from the printed series with this ad gets Φ_33 = 1 - 1/e (≈ 0.632) instead of 1 and a "
        "different third column, hence wrong F (F_36 = ΔT(1 - 1/e)), Φ Q Φ^T and the update's Φ(ν)."
    ),
    "eq:derC[dOmega1/deps_vx] intermediate": (
        "prints -ΔT sin ω (cos ε_ω - 1)/ε_ω; the derivative is -ΔT sin ω (1 - cos ε_ω)/ε_ω (sign). "
        "Intermediate only: the term vanishes at ε = 0, the value ΔT cos ω and 𝒞 are right; no effect on the filter."
    ),
    "eq:derC[dOmega1/deps_omega] intermediate": (
        "second numerator prints ε_vx (cos ε_ω - 1); it must be ε_vx (1 - cos ε_ω) (sign). "
        "Intermediate only: its limit is still 0 and 𝒞 is right; no effect on the filter."
    ),
    "eq:derH[dH1/deps_x] intermediate": (
        "prints -sin θ (cos ε_θ - 1)/ε_θ; the derivative is -sin θ (1 - cos ε_θ)/ε_θ (same sign slip as eq:derC). "
        "Intermediate only: ℋ is right; no effect on the filter."
    ),
    "eq:derH[dH1/deps_theta] intermediate": (
        "second numerator prints ε_x (cos ε_θ - 1); it must be ε_x (1 - cos ε_θ) (sign). "
        "Intermediate only: its limit is still 0 and ℋ is right; no effect on the filter."
    ),
    "eq:H_err[p_2]": (
        "the definition of p_2 is labelled p_1 (p_1 printed twice, p_2 never defined). "
        "Labelling only: no effect on the filter."
    ),
    "eq:H_err[vee subscript]": (
        "the vee is printed [·]^∨_G; log_G' gives an element of g', so it must be [·]^∨_G'. "
        "Notation only: no effect on the filter."
    ),
    "eq:calH[vee subscript]": (
        "the vee in the definition of ℋ is printed [·]^∨_G; it must be [·]^∨_G' (Bourmaud 2013). "
        "Notation only: no effect on the filter."
    ),
}

# label -> (printed, correct, affects filter output?) for the README table
ERRATA_TABLE: dict[str, tuple[str, str, str]] = {
    "se2_def": ("bottom-left block `0^{1×1}`", "`0^{1×2}`", "no (typesetting)"),
    "ad_se2": (
        "`[[-θJ, Jv], [0^{1×2}, 1]]`",
        "`[[-θJ, Jv], [0^{1×2}, 0]]`",
        "**yes**, if Φ is computed from the printed series: Φ₃₃ = 1 − 1/e instead of 1, wrong F, ΦQΦᵀ, Φ(ν)",
    ),
    "eq:derC[dOmega1/deps_vx] intermediate": (
        "`ΔT cos ω sin ε_ω/ε_ω − ΔT sin ω (cos ε_ω − 1)/ε_ω`",
        "`ΔT cos ω sin ε_ω/ε_ω − ΔT sin ω (1 − cos ε_ω)/ε_ω`",
        "no (value at ε = 0, ΔT cos ω, is right)",
    ),
    "eq:derC[dOmega1/deps_omega] intermediate": (
        "second numerator `… − [ε_vx (cos ε_ω − 1) + ε_vy sin ε_ω]`",
        "`… − [ε_vx (1 − cos ε_ω) + ε_vy sin ε_ω]`",
        "no (limit 0 is right)",
    ),
    "eq:derH[dH1/deps_x] intermediate": (
        "`cos θ sin ε_θ/ε_θ − sin θ (cos ε_θ − 1)/ε_θ`",
        "`cos θ sin ε_θ/ε_θ − sin θ (1 − cos ε_θ)/ε_θ`",
        "no (value cos θ is right)",
    ),
    "eq:derH[dH1/deps_theta] intermediate": (
        "second numerator `… − [ε_x (cos ε_θ − 1) + ε_y sin ε_θ]`",
        "`… − [ε_x (1 − cos ε_θ) + ε_y sin ε_θ]`",
        "no (limit 0 is right)",
    ),
    "eq:H_err[p_2]": (
        "`p_1 = [ε_x (1 − cos ε_θ) + ε_y sin ε_θ] ε_θ⁻¹` (p_1 defined twice)",
        "`p_2 = …`",
        "no (labelling)",
    ),
    "eq:H_err[vee subscript]": ("`[·]^∨_G`", "`[·]^∨_{G'}`", "no (notation)"),
    "eq:calH[vee subscript]": ("`[·]^∨_G`", "`[·]^∨_{G'}`", "no (notation)"),
}


def _exact(obj):
    obj = sp.sympify(obj)
    if isinstance(obj, sp.MatrixBase):
        return sp.Matrix(obj).applyfunc(to_exact)
    return to_exact(obj)


def _is_zero(e) -> bool:
    e = sp.sympify(e)
    if e == 0:
        return True
    for simp in (
        sp.simplify,
        lambda v: sp.simplify(sp.expand_trig(sp.expand(v))),
        lambda v: sp.trigsimp(sp.expand_trig(sp.together(v))),
    ):
        if simp(e) == 0:
            return True
    return False


def compare(entry: PrintedEquation):
    """Evaluate an entry: returns (equal, printed, derived) with the raw (unrewritten) objects."""
    P = sp.sympify(entry.printed())
    D = sp.sympify(entry.derived())
    Pe, De = _exact(P), _exact(D)
    if entry.assume is not None:
        Pe, De = entry.assume(Pe), entry.assume(De)
    p_mat, d_mat = isinstance(Pe, sp.MatrixBase), isinstance(De, sp.MatrixBase)
    if p_mat != d_mat:
        return False, P, D
    if p_mat:
        if Pe.shape != De.shape:
            return False, P, D
        return all(_is_zero(a - b) for a, b in zip(Pe, De)), P, D
    return _is_zero(Pe - De), P, D


def _one_line(obj) -> str:
    return " ".join(sp.sstr(obj).split())


def run_verify(stream=sys.stdout, only=None) -> int:
    """Check every printed equation (``only``: the entries of these labels alone); 0 if each is OK or a recorded
    erratum, else 1."""
    n_ok = n_err = n_bad = 0
    seen = set()
    entries = [e for e in PRINTED if only is None or e.label in only]
    for entry in entries:
        seen.add(entry.label)
        ok, P, D = compare(entry)
        known = entry.label in KNOWN_ERRATA
        if ok and not known:
            n_ok += 1
            print(f"{entry.label} OK", file=stream)
        elif ok and known:
            n_bad += 1
            print(f"{entry.label} STALE recorded erratum now matches: {KNOWN_ERRATA[entry.label]}", file=stream)
        elif known:
            n_err += 1
            print(f"{entry.label} ERRATUM {_one_line(P)} -> {_one_line(D)}", file=stream)
        else:
            n_bad += 1
            print(f"{entry.label} MISMATCH {_one_line(P)} -> {_one_line(D)}", file=stream)
    for label in KNOWN_ERRATA:
        if label not in seen and only is None:
            n_bad += 1
            print(f"{label} STALE recorded erratum has no entry in paper.PRINTED", file=stream)
    summary = f"{len(entries)} equations: {n_ok} OK, {n_err} errata"
    if n_bad:
        summary += f", {n_bad} unexpected (MISMATCH/STALE)"
    print(summary, file=stream)
    return 1 if n_bad else 0


def errata_table_markdown() -> str:
    """Markdown table of the recorded errata (label | printed | correct | affects filter output?)."""
    rows = [
        "| label | printed | correct | affects filter output? |",
        "|---|---|---|---|",
    ]
    for label in KNOWN_ERRATA:
        printed, correct, affects = ERRATA_TABLE[label]
        rows.append(f"| `{label}` | {printed} | {correct} | {affects} |")
    return "\n".join(rows) + "\n"


def main(argv=None) -> int:
    t0 = time.perf_counter()
    rc = run_verify(sys.stdout)
    print(f"({time.perf_counter() - t0:.1f} s)")
    return rc


if __name__ == "__main__":
    raise SystemExit(main())
