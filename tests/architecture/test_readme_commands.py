"""Every `lgekf ...` command the documentation shows runs and exits with status 0 — on small inputs.

The commands are collected from the code blocks and inline code (``lgekf ...``) of the README and of every
chapter in ``docs/``, plus the `lgekf study` options in the table of the study chapter (``--noise-scale cv=30
ctrv=3`` and others, run as ``lgekf study OPTIONS``). The README's first block (setup, the full study, the test
suite) is what CI runs (`.ci/run`) and is left out. ``README_TO_RUN`` maps each collected command to what is run;
when the documentation gains a command the test fails until it is added there. Substitutions, all for size:

* synopses (``[...]``, ``{a,b,...}``, ``INPUT``, ``GRID.toml``) and bare mentions (``lgekf track``) become
  concrete commands (one per model for ``{se2se2,...}``, each option of ``[--check | --verify]``);
* every ``lgekf study`` gets ``--trajectories 3 --sigmas 0,1 --steps 10`` where it does not set them;
* every ``lgekf evaluate`` reads a stand-in data folder (``$LGEKF_DATA``: the presets' file layout
  with a few synthetic tracks each, built below) and gets ``--seeds 1``;
* ``lgekf derive`` (which rewrites the package's ``generated/``) gets ``--out`` a temporary folder;
* the files the commands name (``detections.csv``, ``poses.csv``, ``biwi_eth.txt``, ``phone.csv.gz``, ``year.csv``,
  ``detections.parquet``, ``grid.toml``) are small synthetic stand-ins written into the temporary working folder;
  ``cars.csv`` and ``my_tracks.csv`` / ``scene.txt`` are run as ``poses.csv`` (a heading column) and
  ``detections.csv`` / ``biwi_eth.txt``; ``examples/data/detections.csv`` is the shipped example itself, and
  ``examples/sweep_sigma_dt.toml`` the real example with 5 trajectories of 10 steps per cell;
* a scheduler address (``tcp://10.0.0.5:8786``) becomes the address of a local test cluster (``{scheduler}``).

The ``lgekf derive`` runs are SymPy work (30-45 s each on 2 cores) and are marked slow.
"""

from __future__ import annotations

import gzip
import os
import re
import shlex
import subprocess
from pathlib import Path

import numpy as np
import pytest
from _cli import cli_command

ROOT = Path(__file__).resolve().parents[2]
README = (ROOT / "README.md").read_text(encoding="utf-8")
DOCS = {p.name: p.read_text(encoding="utf-8") for p in sorted((ROOT / "docs").glob("*.md"))}
MODELS = ("se2se2", "se2r3", "ctrv", "cv")
STUDY_CHAPTER = "study.md"  # its "## The Monte Carlo study" section has the table of study protocols


def _commands(text: str) -> list[str]:
    """The `lgekf ...` lines of the code blocks of ``text``, then its inline ``lgekf ...`` code."""
    cmds = []
    for block in re.finditer(r"```[^\n]*\n(.*?)```", text, re.S):
        cmds += [re.sub(r"\s+#.*$", "", ln).strip() for ln in block.group(1).splitlines()
                 if ln.startswith("lgekf ") and not re.match(r"lgekf [a-z]+: ", ln)]  # "lgekf track: ..." is output
    prose = re.sub(r"```.*?```", "", text, flags=re.S)
    cmds += [" ".join(m.group(1).split()) for m in re.finditer(r"`(lgekf(?: [^`]*)?)`", prose)]
    return cmds


def readme_commands() -> list[str]:
    """The `lgekf ...` commands of the README (first block excluded) and of docs/*.md, in order, without duplicates."""
    first = re.search(r"```\n(.*?)```", README, re.S)
    cmds = _commands(README[:first.start()] + README[first.end():])
    for text in DOCS.values():
        cmds += _commands(text)
    prose = re.sub(r"```.*?```", "", DOCS[STUDY_CHAPTER], flags=re.S)
    study = re.search(r"\n## The Monte Carlo study.*?(?=\n## )", prose, re.S).group(0)
    cmds += ["lgekf study " + m.group(1) for m in re.finditer(r"^\| `(--[^`]*)` \|", study, re.M)]
    return list(dict.fromkeys(cmds))


STUDY_SYNOPSIS = ("lgekf study [--trajectories N] [--sigmas 0:3:30] [--seed S] [--dt T] [--steps K] [--v0 vx,vy] [--w0 w] "
                  "[--truth se2se2|se2r3] [--filters se2se2,se2r3,se2r2,ctrv,cv] [--measure position|pose] [--heading-std S] "
                  "[--noise-scale cv=10 ...] [--out results/] [--quiet]")

# documented command -> the commands run for it (None: run as written)
README_TO_RUN = {
    "lgekf track detections.csv --multi --model se2se2 -o tracks.csv --clutter-density 1e-4 --detection-prob 0.9 --association jpda": None,
    "lgekf study --multi": ["lgekf study --multi --runs 1 --duration 2 --models cv,se2se2"],
    "lgekf track detections.csv --multi --model imm -o tracks.csv": None,
    "lgekf track detections.csv --multi --model imm --imm-modes cv,se2r3:manoeuvre --imm-switch 0.02 -o tracks.csv": None,
    "lgekf study --multi --models se2r3,cv,imm --association jpda":
        ["lgekf study --multi --models cv,imm --association jpda --runs 1 --duration 2 --out results_imm"],
    "lgekf study --multi --initiation one-point,two-point":
        ["lgekf study --multi --initiation one-point,two-point --runs 1 --duration 2 --models cv --out results_init"],
    "lgekf study --multi --scenario patch --models se2r3,cv --association jpda --clutter true,file,scan,map,oracle":
        ["lgekf study --multi --scenario patch --models cv --association jpda --clutter true,file,scan,map,oracle --runs 1 "
         "--duration 2 --out results_clutter"],
    "lgekf study --multi --scenario base|burst|patch --clutter true,file,scan,map,oracle":
        [f"lgekf study --multi --scenario {s} --models cv --association jpda --clutter true,file,scan,map,oracle --runs 1 "
         f"--duration 2 --out results_clutter_{s}" for s in ("base", "burst")],
    "lgekf track detections.csv --multi -o tracks.csv --clutter scan": None,
    "lgekf track detections.csv --multi --association jpdastar -o tracks.csv": None,
    "lgekf track detections.csv --multi --association pmbm -o tracks.csv [--max-hypotheses 50] [--hypothesis-prune 1e-3]":
        ["lgekf track detections.csv --multi --association pmbm -o tracks_pmbm.csv --max-hypotheses 50 --hypothesis-prune 1e-3"],
    "lgekf study --multi --models se2r3,cv --association jpda,gnn,pmbm":
        ["lgekf study --multi --models cv --association jpda,pmbm --runs 1 --duration 2 --out results_pmbm"],
    "lgekf study --multi --dataset eth --meas-std 0.1 --clutter-density 0.01 --max-speed 5 --gospa-c 2 --runs 3 --noise data":
        ["lgekf study --multi --dataset eth --meas-std 0.1 --clutter-density 0.01 --max-speed 5 --gospa-c 2 --runs 1 --models cv "
         "--association gnn --noise data --out results_noise_data"],
    "lgekf study --multi --dataset eth --meas-std 0.1 --clutter-density 0.01 --max-speed 5 --gospa-c 2 --runs 3 --models cv,se2r3 --association jpda,jpdastar,gnn":
        ["lgekf study --multi --dataset eth --meas-std 0.1 --clutter-density 0.01 --max-speed 5 --gospa-c 2 --runs 1 --models cv "
         "--association jpdastar --out results_jpdastar"],
    "lgekf track DETECTIONS.csv --multi -o OUT.csv --clutter file|scan|map":
        # scan: the command above
        [f"lgekf track detections.csv --multi -o out_clutter_{c}.csv --clutter {c}" for c in ("file", "map")],
    "lgekf study --multi --dataset NAME ...":
        ["lgekf study --multi --dataset eth --meas-std 0.1 --clutter-density 0.01 --max-speed 5 --gospa-c 2 --runs 1 --models cv "
         "--scans 20 --out results_dataset"],
    "lgekf study --multi --dataset eth --meas-std 0.1 --clutter-density 0.01 --max-speed 5 --gospa-c 2 --runs 1":
        ["lgekf study --multi --dataset eth --meas-std 0.1 --clutter-density 0.01 --max-speed 5 --gospa-c 2 --runs 1 --models cv"],
    "lgekf track detections.csv -o tracks.csv --model se2se2": None,
    # Parquet in and out with one model (--model all on one file: the pedestrian-text and pose runs)
    "lgekf track detections.parquet -o tracks.parquet --model all": ["lgekf track detections.parquet -o tracks.parquet --model cv"],
    "lgekf track biwi_eth.txt --format pedestrian --frame-dt 0.06667 -o eth.csv --model all": None,
    "lgekf track phone.csv.gz --time-unit ms -o phone_tracks.csv.gz": None,
    "lgekf track - -o - --model cv < detections.csv > tracks_cv.csv": None,
    STUDY_SYNOPSIS: ["lgekf study --trajectories 3 --sigmas 0:3:2 --seed 1 --dt 0.1 --steps 10 --v0 3,0 --w0 0 "
                     "--truth se2r3 --filters se2se2,se2r2,cv --measure pose --heading-std 0.1 --noise-scale cv=10 ctrv=3 "
                     "--out results/ --quiet"],
    "lgekf figures [--out figures/] [--pdf]": ["lgekf figures --out figures/ --pdf"],
    "lgekf track INPUT -o OUTPUT [--model {se2se2,se2r3,se2r2,ctrv,cv,all,imm}] [--measure position|pose] [--smooth] [--tune]":
        [f"lgekf track detections.csv -o out_{m}.csv --model {m}" for m in (*MODELS, "se2r2", "all", "imm")]
        + ["lgekf track poses.csv -o out_pose.csv --model all --measure pose",
           "lgekf track detections.csv -o out_smooth_tune.csv --model cv --smooth --tune"],
    "lgekf study --filters se2se2,se2r3,se2r2,ctrv,cv": None,
    "lgekf study --measure pose --heading-std 0.1": None,
    "lgekf derive [--check | --verify]": ["lgekf derive --check", "lgekf derive --verify"],
    "lgekf --version": None,
    "lgekf derive": ["lgekf derive"],
    "lgekf derive --verify": None,
    "lgekf derive --check": None,
    "lgekf study": None,
    "lgekf figures": None,
    "lgekf track": ["lgekf track detections.csv -o tracks.csv"],
    "lgekf evaluate": ["lgekf evaluate ethucy kitti cyclists dut"],
    "lgekf evaluate ethucy kitti cyclists dut [--tune]": ["lgekf evaluate ethucy kitti cyclists dut",
                                                         "lgekf evaluate ethucy kitti cyclists dut --tune"],
    "lgekf study --noise-scale cv=30": None,
    "lgekf study --noise-scale cv=30 ctrv=3": None,
    "lgekf study --truth se2r3 --noise-scale cv=30": None,
    "lgekf study --dt 0.5 --steps 20 --noise-scale cv=30 ctrv=3": None,
    "lgekf study --v0 1,0 --noise-scale cv=30": None,
    "lgekf sweep GRID.toml -o DIR [--workers N | --scheduler ADDRESS] [--format csv|parquet] [--dry-run]":
        ["lgekf sweep grid.toml -o sweep_a/ --workers 2 --format parquet", "lgekf sweep grid.toml -o sweep_b/ --scheduler {scheduler}",
         "lgekf sweep grid.toml -o sweep_b/ --dry-run"],
    "lgekf sweep": ["lgekf sweep grid.toml -o sweep_c/ --workers 1"],
    "lgekf sweep examples/sweep_sigma_dt.toml -o sweep_results/": None,
    "lgekf sweep grid.toml -o grid_results/ --scheduler tcp://10.0.0.5:8786": ["lgekf sweep grid.toml -o grid_results/ --scheduler {scheduler}"],
    "lgekf track year.csv -o tracks.csv --model ctrv --meas-std 1 --accel-std 2.8,0.13 --workers 2": None,
    "lgekf track detections.parquet -o tracks.csv --model cv --meas-std 1 --accel-std 2.8 --scheduler tcp://10.0.0.5:8786":
        ["lgekf track detections.parquet -o tracks.csv --model cv --meas-std 1 --accel-std 2.8 --scheduler {scheduler}"],
    "lgekf evaluate ethucy --tune --workers 2": None,
    # the stand-in detections are too few to learn SE(2)xR3's four noise stds: CV (two) on the same file
    "lgekf track detections.csv --model se2r3 --tune --smooth -o tracks.csv": ["lgekf track detections.csv --model cv --tune --smooth -o tracks.csv",
                                                                              "lgekf track detections.csv --model se2r3 --smooth -o tracks.csv"],
    "lgekf evaluate ethucy kitti cyclists dut --tune --smooth": None,
    "lgekf evaluate --tune": ["lgekf evaluate ethucy --tune"],
    "lgekf track detections.csv --model cv --tune --tune-method em -o tracks.csv": None,
    "lgekf study --filters se2se2,se2r3,se2r2,ctrv,cv,imm": None,
    "lgekf study --space 3d": ["lgekf study --space 3d --out results3d"],  # one run for both
    "lgekf study --space 3d --out results3d": None,
    "lgekf track detections.csv --model imm -o tracks_imm.csv": None,
    "lgekf track detections.csv --model imm --imm-modes se2r3:calm,se2r3:manoeuvre --imm-switch 0.02 -o tracks_imm2.csv": None,
    # as above: too few stand-in detections to learn SE(2)xR3's noise; CV modes tuned, the default modes smoothed
    # (tests/estimators/test_imm_smoother.py runs the command as written on a larger file)
    "lgekf track data.csv --model imm --tune --smooth -o out.csv": [
        "lgekf track detections.csv --model imm --imm-modes cv,cv:calm,cv:manoeuvre --tune --smooth -o out.csv",
        "lgekf track detections.csv --model imm --smooth -o out.csv"],
    # KITTI in 3-D (docs/space3d.md): one run for both (--tune adds the likelihood's kernels of three 3-D models, ~40 s
    # of compiling on a cold cache, for no other code path than the planar --tune's)
    "lgekf evaluate kitti3d": None,
    "lgekf evaluate kitti3d --tune": ["lgekf evaluate kitti3d"],
    "lgekf evaluate ethucy kitti cyclists dut --imm": None,
    "lgekf evaluate ethucy kitti cyclists dut --imm --tune": None,
    # the quick start: the shipped example input (copied into the working folder)
    "lgekf track examples/data/detections.csv -o tracks.csv": None,
    # lgekf plot draws a track file: made first, in the same run (the runs may go in any order)
    "lgekf plot tracks.csv --measurements examples/data/detections.csv -o tracks.png":
        ["lgekf track examples/data/detections.csv -o plot_in.csv && "
         "lgekf plot plot_in.csv --measurements examples/data/detections.csv -o tracks.png"],
    "lgekf plot": ["lgekf track examples/data/detections.csv -o plot_in2.csv --smooth && lgekf plot plot_in2.csv -o tracks.svg"],
    "lgekf track --help": None,
    "lgekf track --tune": ["lgekf track detections.csv --model cv --tune -o tracks.csv"],
    "lgekf track --multi": ["lgekf track detections.csv --multi -o tracks_multi.csv"],
    "lgekf track detections.csv --multi -o tracks.csv": None,
    "lgekf track DETECTIONS.csv --multi -o OUT.csv": ["lgekf track detections.csv --multi -o out_multi.csv"],
    "lgekf track detections.csv --multi -o tracks.csv --meas-std 1 --accel-std 0.5,0.5,0.1 --scan-window 0.01": None,
    "lgekf track cars.csv -o cars.csv --model ctrv --accel-std 1,0.5 --meas-std 0.5 --use-heading --full-cov":
        ["lgekf track poses.csv -o cars.csv --model ctrv --accel-std 1,0.5 --meas-std 0.5 --use-heading --full-cov"],
    "lgekf track detections.csv --model imm --smooth -o tracks_imm.csv": None,
    "lgekf evaluate ethucy kitti cyclists dut": None,
    "lgekf evaluate ethucy kitti cyclists dut --tune": None,
    "lgekf evaluate ethucy kitti cyclists dut --markdown": None,
    "lgekf evaluate ethucy kitti cyclists dut --tune --tune-method grid --markdown": None,
    "lgekf evaluate my_tracks.csv": ["lgekf evaluate detections.csv --out evaluation_mine/"],
    "lgekf evaluate scene.txt --format pedestrian --frame-dt 0.04": ["lgekf evaluate biwi_eth.txt --format pedestrian --frame-dt 0.04 --out evaluation_scene/"],
}


def reduce(cmd: str) -> str:
    """The size reductions of the module docstring."""
    words = cmd.split()
    if words[1] == "study" and "--multi" not in words:
        for flag, value in (("--trajectories", "3"), ("--sigmas", "0,1"), ("--steps", "10")):
            if flag not in words:
                cmd += f" {flag} {value}"
    elif words[1] == "evaluate" and "--seeds" not in words:
        cmd += " --seeds 1"
    elif words[1] == "derive" and "--check" not in words and "--verify" not in words:
        cmd += " --out generated_copy"
    return cmd


def to_run() -> list[str]:
    out = []
    for readme, runs in README_TO_RUN.items():
        out += [reduce(c) for c in (runs or [readme])]
    return list(dict.fromkeys(out))


def test_every_readme_command_is_covered():
    assert set(readme_commands()) == set(README_TO_RUN)


# ------------------------------------------------------------------------------ small stand-in inputs
def _tracks(n_obj, n, dt=0.4, seed=0):
    """n_obj gently turning synthetic tracks of n samples: (id, k, x, y)."""
    rng = np.random.default_rng(seed)
    rows = []
    for i in range(n_obj):
        th = rng.uniform(-np.pi, np.pi) + 0.05 * np.arange(n)
        x = rng.uniform(-5, 5) + np.cumsum(1.2 * dt * np.cos(th))
        y = rng.uniform(-5, 5) + np.cumsum(1.2 * dt * np.sin(th))
        rows += [(i + 1, k, x[k], y[k]) for k in range(n)]
    return rows


def _data_root(root: Path):
    """The presets' layout (lgekf.io.datasets.PRESETS) with a few synthetic tracks per dataset."""
    ped = root / "eth_ucy_trajectronpp"
    ped.mkdir(parents=True)
    for j, name in enumerate(("biwi_eth", "biwi_hotel", "crowds_zara01", "crowds_zara02", "students001", "students003")):
        (ped / f"{name}.txt").write_text("".join(f"{10 * k}\t{i}.0\t{x:.3f}\t{y:.3f}\n" for i, k, x, y in _tracks(6, 10, seed=j)))
    kitti = root / "kitti_oxts"
    kitti.mkdir()
    for s in range(4):
        a = np.zeros((12, 30))
        a[:, 0] = 49.0 + 1e-5 * np.arange(12) * (s + 1)
        a[:, 1] = 8.4 + 1e-5 * np.arange(12)
        a[:, 6], a[:, 7] = 1.0, 0.7
        np.savetxt(kitti / f"{s:04d}.txt", a)
    cyc = root / "vru_cyclists_moving"
    cyc.mkdir()
    for s in range(4):
        (cyc / f"{s + 1}.csv").write_text(",timestamp,x,y\n" + "".join(
            f"{k},{0.08 * k:.2f},{x:.3f},{y:.3f}\n" for _, k, x, y in _tracks(1, 12, 0.08, seed=10 + s)))
    dut = root / "dut_vehicles" / "raw"
    dut.mkdir(parents=True)
    (dut / "clip_ratio_pixel2meter.txt").write_text("10.0\n")
    (dut / "clip_traj_veh.csv").write_text("id,x_c,y_c,frame\n" + "".join(
        f"{i},{10 * x:.2f},{10 * y:.2f},{k}\n" for i, k, x, y in _tracks(5, 12, 1 / 23.98, seed=20)))


@pytest.fixture(scope="module")
def workdir(tmp_path_factory):
    d = tmp_path_factory.mktemp("readme")
    (d / "detections.csv").write_text("t,x,y,id\n" + "".join(  # in time order, as a sensor logs (--multi needs it)
        f"{0.4 * k:.1f},{x:.3f},{y:.3f},{i}\n" for i, k, x, y in sorted(_tracks(3, 12), key=lambda r: r[1])))
    (d / "poses.csv").write_text("t,x,y,heading,id\n" + "".join(  # a heading column for --measure pose
        f"{0.4 * k:.1f},{x:.3f},{y:.3f},{0.05 * k:.3f},{i}\n" for i, k, x, y in _tracks(3, 12)))
    (d / "biwi_eth.txt").write_text("".join(f"{10 * k}\t{i}.0\t{x:.3f}\t{y:.3f}\n" for i, k, x, y in _tracks(3, 10, 0.6667)))
    lat0, lon0 = 48.137, 11.575
    phone = "t,lat,lon\n" + "".join(f"{1000 * k},{lat0 + 1e-5 * y:.8f},{lon0 + 1e-5 * x:.8f}\n" for _, k, x, y in _tracks(1, 12, 1.0))
    (d / "phone.csv.gz").write_bytes(gzip.compress(phone.encode()))
    _data_root(d / "data")
    (d / "year.csv").write_text((d / "detections.csv").read_text())
    import pandas as pd

    pd.read_csv(d / "detections.csv", dtype={"id": str}).to_parquet(d / "detections.parquet")
    (d / "grid.toml").write_text('[grid]\nsigmas = [0.0, 2.0]\n[fixed]\ntrajectories = 3\nsteps = 10\n')
    example = (ROOT / "examples" / "sweep_sigma_dt.toml").read_text(encoding="utf-8")
    small = example.replace("trajectories = 1000", "trajectories = 5").replace("steps = 100", "steps = 10")
    assert small.count("= 5\n") == 1 and "steps = 10\n" in small, "the example's sizes changed: update this stand-in"
    (d / "examples").mkdir()
    (d / "examples" / "sweep_sigma_dt.toml").write_text(small, encoding="utf-8")
    (d / "examples" / "data").mkdir()
    (d / "examples" / "data" / "detections.csv").write_bytes((ROOT / "examples" / "data" / "detections.csv").read_bytes())
    return d


# every run is a CLI process (about 1.5 s each, 30 of them): slow, so the quick loop stays under 2 min; CI runs them
#: CI budget: the IMM bank of --multi compiles every planar model's IMM kernels (about 95 s of CPU cold) and
#: tests/estimators/test_imm_bank.py::test_cli_multi_model_imm runs the same command line: here with `-m budget` only
BUDGET = {"lgekf track detections.csv --multi --model imm -o tracks.csv"}


@pytest.mark.slow
@pytest.mark.parametrize("cmd", [pytest.param(c, marks=pytest.mark.budget) if c in BUDGET else c for c in to_run()])
def test_readme_command_runs(workdir, cmd, request):
    if "{scheduler}" in cmd:
        cmd = cmd.replace("{scheduler}", request.getfixturevalue("dask_scheduler"))
    script = f"lgekf() {{ {shlex.join(cli_command())} \"$@\"; }}\n{cmd}\n"
    env = dict(os.environ, LGEKF_DATA=str(workdir / "data"), MPLBACKEND="Agg")
    r = subprocess.run(["bash", "-c", script], cwd=workdir, env=env, capture_output=True, text=True)
    assert r.returncode == 0, f"{cmd}\n{r.stdout[-2000:]}\n{r.stderr[-3000:]}"
    assert "Traceback" not in r.stderr
