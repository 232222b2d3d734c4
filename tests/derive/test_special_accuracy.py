"""Accuracy of the generated kernels near θ = 0 (and up to ±π) against 50-digit references.

Every kernel is compared with the *same* SymPy expression it was generated from (SE2.exp,
SE2.right_jacobian, CTRV's f, ...), with exact (rational) inputs equal to the float inputs, the
angle functions evaluated by their ``_eval_evalf`` (a series near 0) at 50 digits.

Requirement: |computed - true| <= 1e-13 * max(|true|, tiny) for every entry, i.e. relative error
1e-13 and an (essentially) exact zero where the true value is 0.

Run with ``-s`` or look at the terminal summary for the table of the maximum error per kernel.
"""

from __future__ import annotations

import functools
import math

import mpmath as mp
import numpy as np
import pytest
import sympy as sp

from lgekf.derive.lie import special as S
from lgekf.derive.lie.groups import SE2
from lgekf.derive.models import ctrv as CTRV
from lgekf.derive.models.ctrv import MODEL as CTRV_MODEL
from lgekf.derive.models.base import dt as DT
from lgekf.derive.models.base import omega as OMEGA
from lgekf.derive.models.base import x as X
from lgekf.derive.models.base import y as Y
from lgekf.generated import ctrv as gctrv
from lgekf.generated import se2 as gse2
from lgekf.generated import special as gspecial

REL_TOL = 1e-13
ZERO_FLOOR = 1e-300  # "tiny floor": a true 0 must come out as (essentially) exactly 0
DIGITS = 50

# generic non-angle inputs
PX, PY = 0.7, -1.3
CT_PSI, CT_V, CT_DT = 0.37, 2.1, 0.1

# ------------------------------------------------------------------ angles
_DECADES = [m * 10.0**k for k in range(-15, -1) for m in (1.0, 3.0)] + [0.1]
_GRID = [round(0.2 * k, 12) for k in range(1, 16)] + [math.pi - 1e-3, math.pi - 1e-8, math.pi]
TAUS = sorted({f.tau for f in S.ANGLE_FUNCTIONS})
_NEAR_TAU = [t * f for t in TAUS for f in (1 - 1e-9, 1.0, 1 + 1e-9)]
_POS = sorted(set(_DECADES + _GRID + _NEAR_TAU))
# 0, ±1e-15 ... ±1e-1, a grid up to ±π, and both sides of every threshold.  Everything lies in
# (-π, π] for the float π (math.pi < π), which is the range of halfcot / log.
ANGLES = [0.0] + _POS + [-a for a in _POS]
# CTRV: the angle is the turn ω·dt over a step; sinc and dsinc see ω·dt/2, so the thresholds are
# hit at ω·dt = 2 tau (1 ± 1e-9).  (ω·dt/2 stays in [-π/2, π/2]: away from the zero of sinc at π,
# where the rounding of ω·dt alone would make any relative comparison meaningless.)
_CTRV_POS = sorted(set(_DECADES + _GRID + [2 * a for a in _NEAR_TAU]))
CTRV_ANGLES = [0.0] + _CTRV_POS + [-a for a in _CTRV_POS]


# ------------------------------------------------------------------ reference evaluation
@pytest.fixture(scope="module", autouse=True)
def _fast_series():
    """AngleFunction._eval_evalf rebuilds a degree-40 Taylor series (~2 s) at every small-angle call.

    Memoise it for this module (same values, just cached) so that ~1000 references take seconds.
    """
    with pytest.MonkeyPatch.context() as mpatch:
        mpatch.setattr(S, "taylor_polynomial", functools.lru_cache(maxsize=None)(S.taylor_polynomial))
        yield


def Q(v: float) -> sp.Rational:
    """The exact rational value of a float."""
    return sp.Rational(float(v))


def to_mp(e) -> mp.mpf:
    v = sp.sympify(e).evalf(DIGITS)
    if not v.is_Number:
        raise AssertionError(f"reference did not evaluate to a number: {v}")
    return mp.mpf(str(v))


def reference(expr, subs) -> list:
    """Entries of a SymPy matrix (or scalar) at exact inputs, as mpf (row-major)."""
    M = expr.subs(subs) if subs else expr
    M = sp.Matrix([M]) if not isinstance(M, sp.MatrixBase) else M
    return [to_mp(e) for e in M]


TH = sp.Symbol("theta", real=True)
XI = [X, Y, TH]
SE2_EXP = SE2.exp(XI)
SE2_AD_EXP = SE2.Ad(SE2_EXP)
SE2_PHI = SE2.right_jacobian(XI)
SE2_PHI_INV = SE2.right_jacobian_inv(XI)
_ctrv = CTRV_MODEL
CTRV_F = _ctrv.f(list(_ctrv.physical))
CTRV_JAC = _ctrv.F


def _xi(a):
    return np.array([PX, PY, a])


def _xi_subs(a):
    return {X: Q(PX), Y: Q(PY), TH: Q(a)}


def _ctrv_state(a):
    """CTRV state whose turn over one step is ω·dt = a (sinc/dsinc are evaluated at a/2)."""
    return np.array([PX, PY, CT_PSI, CT_V, a / CT_DT])


def _ctrv_subs(a):
    s = _ctrv_state(a)
    return {X: Q(s[0]), Y: Q(s[1]), CTRV.psi: Q(s[2]), CTRV.v: Q(s[3]), OMEGA: Q(s[4]), DT: Q(CT_DT)}


def _log_case(a):
    T = gse2.se2_exp(_xi(a))
    return gse2.se2_log(T), reference(SE2.log(sp.Matrix(3, 3, [Q(t) for t in T.ravel()])), None)


def _special_case(f):
    g = getattr(gspecial, f.__name__)

    def case(a):
        return np.array([g(a, math.sin(a), math.cos(a))]), reference(f(Q(a)), None)

    return case


def _family_case(a):
    """sinc_family: (sinc, cosc, sinc2, cosc2) with shared reciprocals, against the four definitions."""
    got = np.array(gspecial.sinc_family(a, math.sin(a), math.cos(a)))
    return got, reference(sp.Matrix([S.sinc(Q(a)), S.cosc(Q(a)), S.sinc2(Q(a)), S.cosc2(Q(a))]), None)


KERNELS = {f"special.{f.__name__}": _special_case(f) for f in S.ANGLE_FUNCTIONS}
KERNELS["special.sinc_family"] = _family_case
KERNEL_ANGLES = {"ctrv.motion": CTRV_ANGLES, "ctrv.transition": CTRV_ANGLES}
KERNELS.update(
    {
        "se2.se2_exp": lambda a: (gse2.se2_exp(_xi(a)), reference(SE2_EXP, _xi_subs(a))),
        "se2.se2_log(se2_exp)": _log_case,
        "se2.se2_adjoint(se2_exp)": lambda a: (gse2.se2_adjoint(gse2.se2_exp(_xi(a))), reference(SE2_AD_EXP, _xi_subs(a))),
        "se2.right_jacobian": lambda a: (gse2.right_jacobian(_xi(a)), reference(SE2_PHI, _xi_subs(a))),
        "se2.right_jacobian_inv": lambda a: (gse2.right_jacobian_inv(_xi(a)), reference(SE2_PHI_INV, _xi_subs(a))),
        "ctrv.motion": lambda a: (gctrv.motion(_ctrv_state(a), CT_DT), reference(CTRV_F, _ctrv_subs(a))),
        "ctrv.transition": lambda a: (gctrv.transition(_ctrv_state(a), CT_DT), reference(CTRV_JAC, _ctrv_subs(a))),
    }
)


def _entry_name(shape, k):
    if len(shape) <= 1:
        return f"[{k}]"
    return str(tuple(int(i) for i in np.unravel_index(k, shape)))


@pytest.mark.parametrize("name", list(KERNELS))
def test_kernel_accuracy_near_zero(name, accuracy_table):
    case = KERNELS[name]
    worst = (0.0, None, None)
    failures = []
    with mp.workdps(DIGITS + 10):
        for a in KERNEL_ANGLES.get(name, ANGLES):
            got, true = case(a)
            got = np.asarray(got, dtype=float)
            assert got.size == len(true), (name, got.shape, len(true))
            for k, (g, t) in enumerate(zip(got.ravel(), true)):
                scale = max(abs(t), mp.mpf(ZERO_FLOOR))
                if not math.isfinite(g):
                    rel = math.inf
                else:
                    rel = float(abs(mp.mpf(g) - t) / scale)
                entry = _entry_name(got.shape, k)
                if rel > worst[0]:
                    worst = (rel, entry, a)
                if not rel <= REL_TOL:
                    failures.append(
                        f"{name} entry {entry} at angle {a!r}: computed {g!r}, true {mp.nstr(t, 20)}, rel. error {rel:.3e}"
                    )
    accuracy_table[name] = worst
    print(f"\n{name}: max relative error {worst[0]:.3e} (entry {worst[1]}, angle {worst[2]!r})")
    assert not failures, f"{len(failures)} entries above {REL_TOL:g} relative:\n" + "\n".join(failures[:25])


# ------------------------------------------------------------------ thresholds
def _closed_form(f, x):
    """The closed form ``f.stable`` (the kernel's branch for |x| >= tau), in IEEE float64."""
    return eval(f.stable, {"x": x, "s": math.sin(x), "c": math.cos(x)})


# 64 angles in [tau (1 - 1e-3), tau (1 - 1e-9)]: just below the switch, on both sides of 0
_BELOW = [1 - 1e-9] + [1 - k * 1e-3 / 63 for k in range(1, 64)]


#: relative error allowed of each branch just below tau: the Taylor branch (truncation below 1e-17, the rest rounding
#: of a Horner evaluation) within 2 ulp, the closed form within the "few ulp" that chose tau (4.5 ulp)
ULP = 2.220446049250313e-16
TAYLOR_TOL, CLOSED_TOL = 2 * ULP, 1e-15


@pytest.mark.parametrize("f", S.ANGLE_FUNCTIONS, ids=lambda f: f.__name__)
def test_both_branches_are_accurate_just_below_the_threshold(f):
    """Just below tau both branches are accurate against a 50-digit reference, so they agree at the switch.

    derive/lie/special.py: "tau is the smallest angle above which the float64 closed form stays within
    a few ulp of a 50-digit mpmath reference, and the Taylor order is the smallest whose truncation
    error at tau is below 1e-17 relative". Each branch is checked against the reference (the Taylor branch within
    2 ulp, the closed form within 4.5 ulp), not their difference alone: a difference of 4.6 ulp made of the closed
    form's 4 ulp and one ulp of the compiled Horner's rounding (which can vary with LLVM's instruction selection)
    is not an inaccurate branch.
    """
    g = getattr(gspecial, f.__name__)
    worst_t, worst_c = (0.0, None), (0.0, None)
    with mp.workdps(DIGITS + 10):
        for sign in (1.0, -1.0):
            for k in _BELOW:
                x = sign * f.tau * k
                assert abs(x) < f.tau
                taylor = g(x, math.sin(x), math.cos(x))  # |x| < tau: the Taylor branch
                closed = _closed_form(f, x)
                true = to_mp(f(Q(x)))
                assert math.isfinite(taylor) and math.isfinite(closed), (f.__name__, x, taylor, closed)
                e_t = float(abs(mp.mpf(taylor) - true) / abs(true))
                e_c = float(abs(mp.mpf(closed) - true) / abs(true))
                worst_t, worst_c = max(worst_t, (e_t, x)), max(worst_c, (e_c, x))
    what = f"{f.__name__} (tau={f.tau}, order={f.order})"
    assert worst_t[0] <= TAYLOR_TOL, f"{what}: the Taylor branch is {worst_t[0] / ULP:.1f} ulp off at x={worst_t[1]!r}"
    assert worst_c[0] <= CLOSED_TOL, f"{what}: the closed form is {worst_c[0] / ULP:.1f} ulp off at x={worst_c[1]!r}"


@pytest.mark.parametrize("f", S.ANGLE_FUNCTIONS, ids=lambda f: f.__name__)
def test_branch_switch_is_continuous(f):
    """Across tau (tau(1 - 1e-9) -> tau(1 + 1e-9)) the kernel moves by ~ f' * 2e-9 tau, nothing more."""
    g = getattr(gspecial, f.__name__)
    lo, hi = f.tau * (1 - 1e-9), f.tau * (1 + 1e-9)
    vlo, vhi = g(lo, math.sin(lo), math.cos(lo)), g(hi, math.sin(hi), math.cos(hi))
    with mp.workdps(DIGITS + 10):
        tlo, thi = to_mp(f(Q(lo))), to_mp(f(Q(hi)))
        jump = float(abs((mp.mpf(vhi) - mp.mpf(vlo)) - (thi - tlo)) / abs(thi))
    assert jump <= REL_TOL, f"{f.__name__}: jump of {jump:.2e} (relative) across tau={f.tau}"


# ------------------------------------------------------------------ the reference itself
@pytest.mark.parametrize("f", S.ANGLE_FUNCTIONS, ids=lambda f: f.__name__)
@pytest.mark.parametrize("x", [1e-15, -3e-9, 1e-5, 1.0001e-4, 0.25, -1.7, 3.0])
def test_reference_matches_independent_mpmath(f, x):
    """The 50-digit SymPy reference (``_eval_evalf``) agrees with the definition at 150 digits."""
    with mp.workdps(150):
        xm = mp.mpf(x)
        true = _mp_definition(f.__name__)(xm)
        got = to_mp(f(Q(x)))
        assert abs(got - true) <= mp.mpf("1e-45") * abs(true)


# ------------------------------------------------------------------ dense scan of the angle functions
def _mp_definition(name):
    return {
        "sinc": lambda t: mp.sin(t) / t,
        "cosc": lambda t: (1 - mp.cos(t)) / t,
        "sinc2": lambda t: (t - mp.sin(t)) / t**2,
        "cosc2": lambda t: (1 - mp.cos(t)) / t**2,
        "dsinc": lambda t: (mp.sin(t) - t * mp.cos(t)) / t**2,
        "halfcot": lambda t: t * mp.sin(t) / (2 * (1 - mp.cos(t))),
        "halfcot1": lambda t: (1 - t * mp.sin(t) / (2 * (1 - mp.cos(t)))) / t,
        "sinc3": lambda t: (t - mp.sin(t)) / t**3,
        "cosc4": lambda t: (t**2 / 2 + mp.cos(t) - 1) / t**4,
        "sincos5": lambda t: (2 * t - 3 * mp.sin(t) + t * mp.cos(t)) / (2 * t**5),
        "halfcot2": lambda t: (1 - t * mp.sin(t) / (2 * (1 - mp.cos(t)))) / t**2,
    }[name]


@pytest.mark.parametrize("f", S.ANGLE_FUNCTIONS, ids=lambda f: f.__name__)
def test_special_dense_scan(f):
    """3000 log-uniform angles in ±[1e-16, π] (fixed seed): every angle function within 1e-13.

    The reference is the definition in 120-digit mpmath (cancellation costs at most ~35 digits).
    """
    g = getattr(gspecial, f.__name__)
    d = _mp_definition(f.__name__)
    rng = np.random.default_rng(20240611)
    xs = 10.0 ** rng.uniform(-16, math.log10(math.pi), 3000) * rng.choice([-1.0, 1.0], 3000)
    worst = (0.0, None)
    with mp.workdps(120):
        for x in xs:
            x = float(x)
            t = d(mp.mpf(x))
            rel = float(abs(mp.mpf(g(x, math.sin(x), math.cos(x))) - t) / abs(t))
            if rel > worst[0]:
                worst = (rel, x)
    assert worst[0] <= REL_TOL, f"{f.__name__}: rel. error {worst[0]:.2e} at x={worst[1]!r}"
