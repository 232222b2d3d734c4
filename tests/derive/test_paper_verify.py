"""The paper's printed equations vs our derivation (derive.paper, derive.verify)."""

from __future__ import annotations

import io

import pytest
import sympy as sp

from lgekf.derive.paper import transcription as paper, verify
from lgekf.derive.lie.limits import limit_at_zero
from lgekf.derive.models.base import dt, omega, vx, vy
from lgekf.derive.models.se2se2 import EPS
from lgekf.derive.paper.verify import KNOWN_ERRATA, errata_table_markdown, run_verify

pytestmark = pytest.mark.slow

EXPECTED_ERRATA = [
    "se2_def",
    "ad_se2",
    "eq:derC[dOmega1/deps_vx] intermediate",
    "eq:derC[dOmega1/deps_omega] intermediate",
    "eq:derH[dH1/deps_x] intermediate",
    "eq:derH[dH1/deps_theta] intermediate",
    "eq:H_err[p_2]",
]
CORE_OK = ["eq:calCFinal", "eq:calH_model", "exp_se2", "log_se2", "Ad_se2", "Phi_series"]


def _verdicts(text: str) -> dict[str, str]:
    out = {}
    lines = text.splitlines()
    for entry in paper.PRINTED:
        for line in lines:
            if line.startswith(entry.label + " "):
                out[entry.label] = line[len(entry.label) + 1 :].split()[0]
                break
    return out


@pytest.fixture(scope="module")
def report():
    """``lgekf derive --verify``'s code and report: ``run_verify`` of the current sources, or its report of the same
    sources from the render cache (``cached_verify``; the README's ``lgekf derive --verify`` then reads it, or fills
    it for this test). The tests that alter the transcription call ``run_verify`` themselves."""
    from lgekf.derive.codegen.build import cached_verify

    rc, text, _ = cached_verify()
    return rc, text


def test_run_verify_exit_zero(report):
    rc, text = report
    assert rc == 0, text
    assert "MISMATCH" not in text and "STALE" not in text
    n = len(paper.PRINTED)
    assert text.strip().splitlines()[-1] == f"{n} equations: {n - len(KNOWN_ERRATA)} OK, {len(KNOWN_ERRATA)} errata"


def test_every_entry_reported_once(report):
    _, text = report
    labels = [e.label for e in paper.PRINTED]
    assert len(labels) == len(set(labels))
    assert set(_verdicts(text)) == set(labels)


@pytest.mark.parametrize("label", EXPECTED_ERRATA)
def test_expected_errata(report, label):
    assert _verdicts(report[1])[label] == "ERRATUM"


@pytest.mark.parametrize("label", CORE_OK)
def test_core_equations_ok(report, label):
    assert _verdicts(report[1])[label] == "OK"


def test_derivative_values_ok(report):
    v = _verdicts(report[1])
    for label, verdict in v.items():
        if label.startswith(("eq:derC[", "eq:derH[")) and label.endswith(" value"):
            assert verdict == "OK", label


def test_wrong_printed_equation_is_a_mismatch(report, monkeypatch):
    entry = next(e for e in paper.PRINTED if e.label == "eq:calCFinal")
    wrong = entry.printed().copy()
    wrong[0, 3] = dt * sp.sin(omega)
    monkeypatch.setattr(entry, "printed", lambda: wrong)
    buf = io.StringIO()
    assert run_verify(buf, only={"eq:calCFinal"}) == 1  # the one entry (the whole report: the fixture's, 40 s)
    assert "eq:calCFinal MISMATCH" in buf.getvalue()
    assert buf.getvalue().strip().splitlines()[-1] == "1 equations: 0 OK, 0 errata, 1 unexpected (MISMATCH/STALE)"


def test_stale_erratum_is_reported(report, monkeypatch):
    entry = next(e for e in paper.PRINTED if e.label == "ad_se2")
    monkeypatch.setattr(entry, "printed", entry.derived)
    buf = io.StringIO()
    assert run_verify(buf, only={"ad_se2"}) == 1
    assert "ad_se2 STALE" in buf.getvalue()


def test_errata_table():
    assert set(verify.ERRATA_TABLE) == set(KNOWN_ERRATA)
    table = errata_table_markdown()
    assert table.startswith("| label | printed | correct | affects filter output? |")
    for label in KNOWN_ERRATA:
        assert f"`{label}`" in table


@pytest.mark.parametrize(
    "label, value",
    [
        ("eq:derC[dOmega1/deps_vx] intermediate", "eq:derC[dOmega1/deps_vx] value"),
        ("eq:derC[dOmega1/deps_omega] intermediate", "eq:derC[dOmega1/deps_omega] value"),
        ("eq:derH[dH1/deps_x] intermediate", "eq:derH[dH1/deps_x] value"),
        ("eq:derH[dH1/deps_theta] intermediate", "eq:derH[dH1/deps_theta] value"),
    ],
)
def test_intermediate_typos_do_not_change_the_value(label, value):
    """The mistyped intermediates still have the printed (correct) multivariate limit at ε = 0."""
    by = {e.label: e for e in paper.PRINTED}
    lim = limit_at_zero(by[label].printed(), EPS)
    assert sp.simplify(lim - by[value].printed()) == 0


def test_printed_ad_would_change_phi():
    """With the printed ad_se2 (corner 1) the Φ series has Φ_33 = 1 - 1/e instead of 1."""
    num = {dt: sp.Rational(1, 10), vx: 2, vy: sp.Rational(1, 2), omega: sp.Rational(3, 10)}
    v = [(dt * vx).subs(num), (dt * vy).subs(num), (dt * omega).subs(num)]
    bad = paper.printed_Phi_series(paper.printed_ad_se2(v), 30)
    good = paper.printed_Phi_series(paper.SE2.derived_ad(v), 30)
    assert abs(float(bad[2, 2]) - (1 - float(sp.exp(-1)))) < 1e-12
    assert good[2, 2] == 1
    assert abs(float(bad[0, 2] - good[0, 2])) > 1e-3
