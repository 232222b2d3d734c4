"""A fast first run (issue 10, item 4): parallel compile on a cold cache, the notice's estimate, small
batches without the parallel kernel, and the linear-time recovery of a long object."""

import os
import subprocess
import sys
import textwrap

import numpy as np
import pytest

import lgekf.apps.divergence as divergence
import lgekf.core.batch as batch
from lgekf.cli.progress import compile_notice_text
from lgekf.apps.warmup import Job, _groups, compile_estimate


def test_groups_balance_the_cost_and_keep_every_job():
    jobs = [Job("m", f"f{i}", cost=c) for i, c in enumerate([5.0, 4.4, 3.8, 2.7, 2.1])]
    groups = _groups(jobs, 2)
    assert sorted(j.function for g in groups for j in g) == sorted(j.function for j in jobs)
    loads = sorted(sum(j.cost for j in g) for g in groups)
    assert loads == pytest.approx([8.2, 9.8])  # longest first: {4.4, 3.8} and {5.0, 2.7, 2.1}
    assert max(loads) <= 4 / 3 * 18.0 / 2  # within the LPT bound of the best split
    assert len(_groups(jobs, 1)) == 1 and len(_groups(jobs[:2], 8)) == 2


def test_estimate_and_notice_text():
    assert compile_estimate([5.0, 4.4, 3.8, 2.7, 2.1], workers=1) == pytest.approx(18.0)
    two = compile_estimate([5.0, 4.4, 3.8, 2.7, 2.1], workers=2)
    assert 9.2 < two < 18.0  # the larger group plus a worker's start-up
    assert compile_notice_text(11.9).startswith("compiling kernels, once, about 10 s")
    assert "about 5 s" in compile_notice_text(0.4)  # never "about 0 s"
    assert "10-60 s" in compile_notice_text(None)


def test_imm_notice_counts_what_its_options_compile():
    """`--model imm` compiles every registry model's leaves (about 100 s cold, issue #26): its notice must not
    promise the single model's 10-60 s; --tune and --smooth each add their kernels."""
    from argparse import Namespace

    from lgekf.cli.track_imm import ImmTrack

    def est(**kw):
        a = Namespace(imm_modes=None, imm_switch=None, tune=False, smooth=False)
        vars(a).update(kw)
        return ImmTrack(a, print).compile_seconds()

    plain, tune, smooth, both = est(), est(tune=True), est(smooth=True), est(tune=True, smooth=True)
    assert plain > 60.0  # beyond the general notice's range
    assert plain < tune < both and plain < smooth < both
    assert both == pytest.approx(tune + smooth - plain)
    assert "10-60 s" not in compile_notice_text(both)


_KERNELS = '''
import numba as nb

@nb.njit(cache=True)
def first(x):
    return x + 1.0

@nb.njit(cache=True)
def second(x):
    return x * 3.0

def run_first():
    return first(1.0)

def run_second():
    return second(1.0)
'''

_DRIVER = '''
import sys
from numba.core import event
from lgekf.apps.warmup import Job, warm_up
jobs = [Job("tiny_kernels", "run_first", cost=2.0), Job("tiny_kernels", "run_second", cost=1.0)]
print(warm_up(jobs, workers=2))
'''

_CHECK = '''
from numba.core import event
compiled = []
class L(event.Listener):
    def on_start(self, ev): compiled.append(ev.data["dispatcher"].py_func.__name__)
    def on_end(self, ev): pass
event.register("numba:compile", L())
import tiny_kernels
assert tiny_kernels.run_second() == 3.0 and tiny_kernels.run_first() == 2.0
print(",".join(compiled))
'''


@pytest.mark.slow
def test_cold_cache_hands_jobs_to_a_worker_and_the_cache_serves_them(tmp_path):
    """Cold: the second job's kernel is compiled by a worker process into the cache; a new process then
    loads both kernels without compiling; warm: no worker at all."""
    (tmp_path / "tiny_kernels.py").write_text(_KERNELS)
    env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp_path / "cache"), PYTHONPATH=str(tmp_path) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    env.pop("LGEKF_COMPILE_WORKERS", None)

    def py(code):
        r = subprocess.run([sys.executable, "-c", textwrap.dedent(code)], capture_output=True, text=True, env=env, cwd=tmp_path)
        assert r.returncode == 0, r.stderr
        return r.stdout.strip()

    assert py(_DRIVER) == "1"  # cold: one worker took the other group
    assert py(_CHECK) == ""  # both kernels in the cache: nothing compiles
    assert py(_DRIVER) == "0"  # warm: no worker


def test_small_batches_take_the_serial_kernel_with_the_same_numbers(monkeypatch):
    rng = np.random.default_rng(3)
    B, K = 4, 30
    t = 0.1 * np.arange(1, K + 1)
    z = np.stack([3 * t, 0.2 * t**2], axis=-1)[None] + 0.3 * rng.standard_normal((B, K, 2))
    x0 = np.tile([0, 0, 0, 3, 0, 0], (B, 1)).astype(float)
    P0 = np.diag([0.25, 0.25, 0.01, 0.25, 0.25, 0.01])
    kw = dict(dt=0.1, accel_std=(0.1, 0.1, 1.0), meas_std=0.5, x0=x0, P0=P0, return_cov=True, return_nis=True)
    assert B * K <= batch.SERIAL_STEPS
    serial = batch.filter_batch("se2se2", z, **kw)
    monkeypatch.setattr(batch, "SERIAL_STEPS", 0)
    parallel = batch.filter_batch("se2se2", z, **kw)
    for a, b in zip(serial, parallel):
        np.testing.assert_array_equal(a, b)


def test_windowed_rerun_after_an_alarm_equals_one_rerun_to_the_end(monkeypatch):
    """A long object with alarms: re-running a doubling window after each re-initialisation gives the
    numbers of a rerun to the object's end, bit for bit."""
    from lgekf.apps.track import TrackConfig, track_monitored

    rng = np.random.default_rng(5)
    K = 1500
    t = np.cumsum(rng.uniform(0.08, 0.12, K))
    th = np.cumsum(0.1 * rng.standard_normal(K))  # a jerky turn rate: alarms with small process noise
    z = np.column_stack([np.cumsum(5 * np.cos(th) * 0.1), np.cumsum(5 * np.sin(th) * 0.1)]) + 0.2 * rng.standard_normal((K, 2))
    starts = np.array([0, K])
    cfg = TrackConfig({"se2se2": (0.05, 0.05, 0.05)}, 0.2)
    monkeypatch.setattr(divergence, "RERUN_ROWS", 1 << 40)
    whole = track_monitored("se2se2", t, z, starts, cfg)
    monkeypatch.setattr(divergence, "RERUN_ROWS", 8)
    windowed = track_monitored("se2se2", t, z, starts, cfg)
    assert len(whole.alarms) >= 2
    assert [(a.row, a.kind) for a in windowed.alarms] == [(a.row, a.kind) for a in whole.alarms]
    for name in ("x", "p", "nis", "flag"):
        np.testing.assert_array_equal(getattr(windowed, name), getattr(whole, name))


def test_worker_count_follows_free_cpus_and_the_variable(monkeypatch):
    import lgekf.apps.warmup as warmup

    monkeypatch.delenv("LGEKF_COMPILE_WORKERS", raising=False)
    monkeypatch.setattr(warmup.os, "sched_getaffinity", lambda pid: {0, 1, 2, 3}, raising=False)
    monkeypatch.setattr(warmup.os, "getloadavg", lambda: (0.2, 0.2, 0.2))
    assert warmup.worker_count() == 4  # a quiet machine: every CPU
    monkeypatch.setattr(warmup.os, "getloadavg", lambda: (2.5, 2.5, 2.5))
    assert warmup.worker_count() == 2  # two and a half CPUs busy
    monkeypatch.setattr(warmup.os, "getloadavg", lambda: (9.0, 9.0, 9.0))
    assert warmup.worker_count() == 1  # busy: no worker
    monkeypatch.setenv("LGEKF_COMPILE_WORKERS", "3")
    assert warmup.worker_count() == 3


def test_output_in_blocks_and_threads_is_the_same_bytes(tmp_path, monkeypatch):
    """Text made, formatted and written PART_ROWS rows at a time in threads: the bytes of one piece."""
    import lgekf.io.formatting as formatting
    from lgekf.cli.track import cmd_track

    rng = np.random.default_rng(2)
    lines = ["id,t,x,y"]
    for o in range(4):
        t = np.cumsum(rng.uniform(0.08, 0.12, 60))
        lines += [f"{o},{a!r},{b!r},{c!r}" for a, b, c in zip(t.tolist(), (2 * t + 0.1 * rng.standard_normal(60)).tolist(),
                                                            (0.1 * t**2 + 0.1 * rng.standard_normal(60)).tolist())]
    (tmp_path / "in.csv").write_text("\n".join(lines) + "\n")
    args = ["--model", "se2r3", "--meas-std", "0.1", "--accel-std", "0.5,0.5,1", "--quiet"]
    assert cmd_track([str(tmp_path / "in.csv"), "-o", str(tmp_path / "one.csv"), *args]) == 0
    monkeypatch.setattr(formatting, "PART_ROWS", 7)
    monkeypatch.setattr(formatting, "_cpus", lambda: 3)
    assert cmd_track([str(tmp_path / "in.csv"), "-o", str(tmp_path / "blocks.csv"), *args]) == 0
    assert (tmp_path / "blocks.csv").read_bytes() == (tmp_path / "one.csv").read_bytes()
