"""Code generation: freshness, headers, determinism, runtime without SymPy, and the generated
kernels against finite differences of the exact (noise-free) error propagation."""

from __future__ import annotations

import io
import json
import math
import os
import shutil
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest
import scipy.linalg as sla

import lgekf.generated as generated_pkg
from lgekf.core.covariance import pack, unpack
from lgekf.generated import ctrv, se2r3, se2se2

GENERATED = Path(generated_pkg.__file__).resolve().parent
GENERATED_FILES = sorted(GENERATED.glob("*.py"))


def _run(code_or_args, env_extra=None, timeout=600):
    env = dict(os.environ)
    env.update(env_extra or {})
    args = [sys.executable, "-c", code_or_args] if isinstance(code_or_args, str) else [sys.executable, *code_or_args]
    return subprocess.run(args, capture_output=True, text=True, env=env, timeout=timeout)


# ------------------------------------------------------------------ freshness
_RENDER = textwrap.dedent(
    """
    import json, sys
    from lgekf.derive.codegen.build import render_all
    files = render_all(jobs=int(sys.argv[2]))
    with open(sys.argv[1], "w", encoding="utf-8") as fh:
        json.dump(files, fh)
    """
)


def _render_in_subprocess(out: Path, seed: str, jobs: int, cache: bool = True) -> subprocess.Popen:
    """render_all in a fresh interpreter with PYTHONHASHSEED=seed, written to ``out`` as JSON; ``cache``: whether model
    modules rendered from the same sources may be reused (``derive.codegen.build.render_cache_dir``)."""
    env = {**os.environ, "PYTHONHASHSEED": seed, **({} if cache else {"LGEKF_DERIVE_CACHE": "off"})}
    return subprocess.Popen([sys.executable, "-c", _RENDER, str(out), str(jobs)], env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


@pytest.fixture(scope="module")
def rendered(tmp_path_factory):
    """One regeneration of every generated module (PYTHONHASHSEED=0), shared by the freshness tests: the
    SymPy derivation is the suite's most expensive step (the CLI's own `lgekf derive --check` runs in
    tests/architecture/test_readme_commands.py)."""
    out = tmp_path_factory.mktemp("render") / "render_0.json"
    p = _render_in_subprocess(out, "0", 2)
    _, err = p.communicate(timeout=900)
    assert p.returncode == 0, err[-3000:]
    return json.loads(out.read_text(encoding="utf-8"))


@pytest.mark.slow
def test_derive_check_passes(rendered):
    """generated/ equals a fresh regeneration (what `lgekf derive --check` tests; exit status 0)."""
    from lgekf.derive.codegen.build import check

    buf = io.StringIO()
    assert check(GENERATED, stream=buf, rendered=rendered) == 0, f"generated/ is stale:\n{buf.getvalue()[-5000:]}"
    assert "up to date" in buf.getvalue()


@pytest.mark.slow
def test_check_detects_stale_and_extra_files(tmp_path, rendered):
    from lgekf.derive.codegen.build import check

    for f in GENERATED_FILES:
        shutil.copy(f, tmp_path / f.name)
    target = tmp_path / "se2.py"
    lines = target.read_text(encoding="utf-8").splitlines(keepends=True)
    i = next(k for k, line in enumerate(lines) if line.strip() == "out[2, 2] = 1.0")
    lines[i] = lines[i].replace("1.0", "2.0")
    target.write_text("".join(lines), encoding="utf-8")
    (tmp_path / "leftover.py").write_text("# an old module derive no longer produces\n", encoding="utf-8")

    buf = io.StringIO()
    rc = check(tmp_path, stream=buf, rendered=rendered)
    out = buf.getvalue()
    assert rc == 1, out
    assert "generated/se2.py (checked in)" in out and "generated/se2.py (regenerated)" in out, out
    assert "@@" in out
    assert "-    out[2, 2] = 2.0\n" in out and "+    out[2, 2] = 1.0\n" in out, out
    # the diff of se2.py shows the one changed line (exact counts only hold while generated/ is fresh,
    # which test_derive_check_passes asserts separately)
    se2_diff = out.split("generated/se2.py (regenerated)")[1].split("\n--- ")[0]
    changed = [ln for ln in se2_diff.splitlines() if ln[:1] in "+-"]
    assert "-    out[2, 2] = 2.0" in changed and "+    out[2, 2] = 1.0" in changed, changed
    assert "generated/leftover.py: not produced by derive" in out
    assert "file(s) differ" in out
    # the checked-in folder itself is untouched
    assert (GENERATED / "se2.py").read_text(encoding="utf-8") != target.read_text(encoding="utf-8")


@pytest.mark.parametrize("path", GENERATED_FILES, ids=lambda p: p.name)
def test_generated_files_have_header(path):
    text = path.read_text(encoding="utf-8")
    assert text.startswith('"""'), f"{path.name} does not start with its header docstring"
    header = text.split('"""')[1]
    assert "GENERATED FILE: DO NOT EDIT" in header, f"{path.name}: header lacks 'GENERATED FILE: DO NOT EDIT'"
    assert "lgekf derive" in header


def test_generated_files_cover_the_models():
    names = {p.name for p in GENERATED_FILES}
    assert {"__init__.py", "special.py", "se2.py", "se2se2.py", "se2r3.py", "ctrv.py", "cv.py"} <= names


_RENDER_MODELS = textwrap.dedent(
    """
    import json, sys
    from lgekf.derive.codegen.build import _render_model_now
    out = dict(_render_model_now(name, None, None) for name in sys.argv[2].split(","))
    with open(sys.argv[1], "w", encoding="utf-8") as fh:
        json.dump(out, fh)
    """
)


@pytest.mark.slow
def test_render_is_deterministic(tmp_path, rendered):
    """The same sources give the same bytes whatever the hash seed. Every module: ``rendered`` (PYTHONHASHSEED=0,
    perhaps from the render cache) equals generated/ (``test_derive_check_passes``), which `lgekf derive` wrote under
    a random seed. Here, without the cache, two model modules (a planar and a 3-D one) rendered anew under seed 4242
    equal ``rendered``'s, so the cache serves what a fresh derivation gives (a whole second derivation would cost the
    suite a minute on both cores)."""
    out = tmp_path / "render_4242.json"
    p = subprocess.Popen([sys.executable, "-c", _RENDER_MODELS, str(out), "se2r2,ct3"],
                         env={**os.environ, "PYTHONHASHSEED": "4242"}, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    _, err = p.communicate(timeout=900)
    assert p.returncode == 0, err[-3000:]
    b = json.loads(out.read_text(encoding="utf-8"))
    differ = [name for name in b if rendered[name].encode() != b[name].encode()]
    assert sorted(b) == ["ct3.py", "se2r2.py"] and not differ, f"render output depends on PYTHONHASHSEED: {differ}"


def test_render_cache_key_follows_the_sources(tmp_path, monkeypatch):
    """A change to any definition (here a copy of the models with one comment added) gives another digest, so the
    cache never serves a module derived from other sources."""
    import shutil

    from lgekf.derive.codegen.build import render_cache_dir, sources_digest

    models = Path(__file__).resolve().parents[2] / "derive" / "models"
    a, b = tmp_path / "a", tmp_path / "b"
    shutil.copytree(models, a, ignore=shutil.ignore_patterns("__pycache__"))
    shutil.copytree(models, b, ignore=shutil.ignore_patterns("__pycache__"))
    assert sources_digest(a) == sources_digest(b) != sources_digest()
    (b / "cv.py").write_text((b / "cv.py").read_text(encoding="utf-8") + "# one more line\n", encoding="utf-8")
    sources_digest.cache_clear()
    assert sources_digest(a) != sources_digest(b)
    monkeypatch.setenv("LGEKF_DERIVE_CACHE", "off")
    assert render_cache_dir() is None
    monkeypatch.setenv("LGEKF_DERIVE_CACHE", str(tmp_path / "c"))
    assert render_cache_dir() == tmp_path / "c"


def test_cached_text_computes_once_per_sources_and_name(tmp_path, monkeypatch):
    """The render cache (modules, the verification report): the first call computes and keeps the text, the next
    reads it; another name is another entry; with the cache off every call computes."""
    from lgekf.derive.codegen.build import cached_text

    calls = []

    def compute(text):
        calls.append(text)
        return text

    monkeypatch.setenv("LGEKF_DERIVE_CACHE", str(tmp_path / "c"))
    assert cached_text("verify.txt", lambda: compute("0\nreport")) == ("0\nreport", False)
    assert cached_text("verify.txt", lambda: compute("changed")) == ("0\nreport", True)
    assert cached_text("other.txt", lambda: compute("x")) == ("x", False)
    assert calls == ["0\nreport", "x"] and len(list((tmp_path / "c").glob("*-verify.txt"))) == 1
    monkeypatch.setenv("LGEKF_DERIVE_CACHE", "off")
    assert cached_text("verify.txt", lambda: compute("y")) == ("y", False)
    assert cached_text("verify.txt", lambda: compute("z"), cache=True) == ("z", False) and calls[-2:] == ["y", "z"]


def test_runtime_does_not_import_sympy():
    code = textwrap.dedent(
        """
        import sys
        import numpy as np
        import lgekf
        assert "sympy" not in sys.modules, "import lgekf imported sympy"
        rng = np.random.default_rng(0)
        B, K = 3, 6
        t = np.arange(K) * 0.1
        z = np.stack([np.stack([1.0 * t + 0.1 * b, 0.5 * t], axis=-1) for b in range(B)]) + 0.01 * rng.standard_normal((B, K, 2))
        cases = {
            "se2se2": ([0.0, 0.0, 0.1, 1.0, 0.0, 0.05], [0.5, 0.5, 0.1]),
            "se2r3": ([0.0, 0.0, 0.1, 1.0, 0.0, 0.05], [0.5, 0.5, 0.1]),
            "ctrv": ([0.0, 0.0, 0.1, 1.0, 0.05], [0.5, 0.1]),
            "cv": ([0.0, 0.0, 1.0, 0.0], [0.5]),
        }
        for model, (x0, q) in cases.items():
            n = len(x0)
            x, P, nis = lgekf.filter_batch(model, z, dt=0.1, accel_std=q, meas_std=0.1, x0=np.tile(x0, (B, 1)),
                                           P0=np.eye(n), return_cov=True, return_nis=True)
            assert x.shape == (B, K, n) and P.shape == (B, K, n, n) and nis.shape == (B, K), model
            assert np.all(np.isfinite(x)) and np.all(np.isfinite(P)) and np.all(np.isfinite(nis)), model
        bad = sorted(m for m in sys.modules if m == "sympy" or m.startswith(("sympy.", "lgekf.derive")))
        assert not bad, bad
        print("OK")
        """
    )
    r = _run(code)
    assert r.returncode == 0 and "OK" in r.stdout, r.stdout[-3000:] + r.stderr[-3000:]


# ------------------------------------------------------------------ exact error propagation (dense)
def _se2(c, s, tx, ty):
    return np.array([[c, -s, tx], [s, c, ty], [0.0, 0.0, 1.0]])


def _hat_se2(v):
    return np.array([[0.0, -v[2], v[0]], [v[2], 0.0, v[1]], [0.0, 0.0, 0.0]])


def _hat_r3(v):
    M = np.zeros((4, 4))
    M[:3, 3] = v
    return M


class DenseModel:
    """G = SE(2)×SE(2) (6×6) or SE(2)×R^3 (7×7) with exp/log by scipy expm/logm, per block."""

    def __init__(self, name):
        self.name = name
        self.kernels = {"se2se2": se2se2, "se2r3": se2r3}[name]

    def mean(self, xp):
        x, y, th, vx, vy, w = xp
        Ts = _se2(math.cos(th), math.sin(th), x, y)
        if self.name == "se2se2":
            return sla.block_diag(Ts, _se2(math.cos(w), math.sin(w), vx, vy))
        return sla.block_diag(Ts, np.eye(4) + _hat_r3([vx, vy, w]))

    def hat(self, eps):
        second = _hat_se2(eps[3:]) if self.name == "se2se2" else _hat_r3(eps[3:])
        return sla.block_diag(_hat_se2(eps[:3]), second)

    def exp(self, eps):
        return sla.expm(self.hat(eps))

    def log(self, X):
        L1 = np.real(sla.logm(X[:3, :3]))
        out = [L1[0, 2], L1[1, 2], L1[1, 0]]
        L2 = np.real(sla.logm(X[3:, 3:]))
        if self.name == "se2se2":
            out += [L2[0, 2], L2[1, 2], L2[1, 0]]
        else:
            out += list(L2[:3, 3])
        return np.array(out)

    def velocities(self, X):
        if self.name == "se2se2":
            Td = X[3:6, 3:6]
            return Td[0, 2], Td[1, 2], math.atan2(Td[1, 0], Td[0, 0])
        V = X[3:7, 3:7]
        return V[0, 3], V[1, 3], V[2, 3]

    def Omega(self, X, dt):
        vx, vy, w = self.velocities(X)
        return np.array([dt * vx, dt * vy, dt * w, 0.0, 0.0, 0.0])

    def motion(self, X, dt):
        """The exact noise-free motion f(X) = X exp(Ω(X))."""
        return X @ self.exp(self.Omega(X, dt))


def _central(fun, n, h=1e-6):
    cols = []
    for j in range(n):
        e = np.zeros(n)
        e[j] = h
        cols.append((np.asarray(fun(e)) - np.asarray(fun(-e))) / (2 * h))
    return np.array(cols).T


LG_STATES = [
    # x, y, θ, v_x, v_y, ω
    (0.7, -1.3, 0.4, 2.1, 0.3, 0.5),
    (0.7, -1.3, 0.4, 2.1, 0.3, 0.0),
    (0.7, -1.3, -2.9, 2.1, -0.4, 1e-9),
    (-3.0, 2.0, 3.0, 1.5, 0.0, -1e-12),
    (1.0, 2.0, -0.5, -1.2, 0.8, -2.5),
    (1.0, 2.0, 1.2, 0.5, 0.2, 3.0),
]
DTS = [0.1, 1.0]


@pytest.mark.parametrize("name", ["se2se2", "se2r3"])
@pytest.mark.parametrize("xp", LG_STATES)
@pytest.mark.parametrize("dt", DTS)
def test_lg_transition_matches_exact_error_propagation(name, xp, dt):
    """F = ∂/∂ε log(μ'^-1 f(μ exp ε)) at ε = 0, μ' = f(μ), f(X) = X exp(Ω(X))."""
    G = DenseModel(name)
    k = G.kernels
    s = k.state_from_physical(np.array(xp, dtype=float))
    mu = G.mean(xp)
    np.testing.assert_allclose(k.group_mean(s), mu, rtol=0, atol=1e-15)
    np.testing.assert_allclose(k.motion_omega(s, dt), G.Omega(mu, dt), rtol=0, atol=1e-15)
    mu_next = G.motion(mu, dt)
    mu_next_inv = np.linalg.inv(mu_next)

    F_fd = _central(lambda e: G.log(mu_next_inv @ G.motion(mu @ G.exp(e), dt)), 6)
    F = k.transition(s, dt)
    np.testing.assert_allclose(F, F_fd, rtol=0, atol=1e-7 * (1 + dt * np.abs(xp[3:]).max()))

    C_fd = _central(lambda e: G.Omega(mu @ G.exp(e), dt), 6)
    np.testing.assert_allclose(k.calC(s, dt), C_fd, rtol=0, atol=1e-8)


@pytest.mark.parametrize("name", ["se2se2", "se2r3"])
@pytest.mark.parametrize("xp", LG_STATES)
def test_lg_calH_matches_measurement_error(name, xp):
    """ℋ = ∂/∂ε [log_R²(h(μ)^-1 h(μ exp ε))]^∨ at 0, h(X) = position of the pose block."""
    G = DenseModel(name)
    s = G.kernels.state_from_physical(np.array(xp, dtype=float))
    mu = G.mean(xp)

    def h(X):
        return np.array([X[0, 2], X[1, 2]])

    H_fd = _central(lambda e: h(mu @ G.exp(e)) - h(mu), 6)
    np.testing.assert_allclose(G.kernels.calH_position(s), H_fd, rtol=0, atol=1e-9)


@pytest.mark.parametrize("name", ["se2se2", "se2r3"])
@pytest.mark.parametrize("xp", LG_STATES[:4])
def test_lg_predict_is_consistent_with_building_blocks(name, xp):
    """Fused predict with zero noise: μ ← f(μ) and P ← F P Fᵀ (F from `transition`).

    P is scaled so that the angle stds stay below π, where the predict's angle-variance cap
    (limit_angle_variance) is inactive; the cap itself is tested in tests/core/test_safeguards.py."""
    G = DenseModel(name)
    k = G.kernels
    dt = 0.1
    s = k.state_from_physical(np.array(xp, dtype=float))
    A = np.random.default_rng(1).standard_normal((6, 6))
    P = (A @ A.T + 6 * np.eye(6)) / 4
    F = k.transition(s, dt)
    p = pack(P)
    mu_next = G.motion(G.mean(xp), dt)
    k.predict(s, p, dt, 0.0, 0.0, 0.0)
    np.testing.assert_allclose(k.group_mean(s), mu_next, rtol=0, atol=1e-13)
    np.testing.assert_allclose(unpack(p, 6), F @ P @ F.T, rtol=1e-12, atol=1e-12)


CTRV_STATES = [
    # x, y, ψ, v, ω
    (0.7, -1.3, 0.37, 2.1, 0.0),
    (0.7, -1.3, 0.37, 2.1, 1e-9),
    (0.7, -1.3, 0.37, 2.1, -1e-9),
    (0.7, -1.3, -2.5, 2.1, 0.8),
    (0.7, -1.3, 3.0, 5.0, -4.0),
    (-2.0, 4.0, 1.0, 0.0, 2.0),
]


@pytest.mark.parametrize("xs", CTRV_STATES)
@pytest.mark.parametrize("dt", DTS)
def test_ctrv_transition_matches_motion_differences(xs, dt):
    s = np.array(xs, dtype=float)
    F_fd = _central(lambda e: ctrv.motion(s + e, dt), 5)
    np.testing.assert_allclose(ctrv.transition(s, dt), F_fd, rtol=0, atol=1e-7 * (1 + abs(xs[3]) * dt))


@pytest.mark.parametrize("w0", [0.0, -0.0])
def test_ctrv_motion_at_zero_turn_rate_is_straight(w0):
    xs = (0.7, -1.3, 0.37, 2.1, w0)
    s = np.array(xs, dtype=float)
    dt = 0.1
    out = ctrv.motion(s, dt)
    x, y, psi, v, w = xs
    np.testing.assert_allclose(
        out, [x + v * dt * math.cos(psi), y + v * dt * math.sin(psi), psi + w * dt, v, w], rtol=0, atol=1e-12
    )
