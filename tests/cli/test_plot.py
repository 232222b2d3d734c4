"""`lgekf plot` and `lgekf.plot_tracks`: a picture of a track file, from the example input and from real data."""

from __future__ import annotations

import os
from pathlib import Path

import pandas as pd
import pytest

from lgekf.apps.plot_tracks import MAX_OBJECTS, plot_tracks
from lgekf.cli import main

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples" / "data" / "detections.csv"
DATA = Path(os.environ.get("LGEKF_DATA") or ROOT.parent / "shared" / "data")


@pytest.fixture(scope="module")
def example_tracks(tmp_path_factory):
    out = tmp_path_factory.mktemp("plot") / "tracks.csv"
    assert main(["track", str(EXAMPLE), "--smooth", "-o", str(out), "--quiet"]) == 0
    return out


def _png(path):
    data = path.read_bytes()
    return data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 20_000


def test_plot_draws_every_object_of_the_example(example_tracks, tmp_path, capsys):
    fig = tmp_path / "fig.png"
    assert main(["plot", str(example_tracks), "--measurements", str(EXAMPLE), "-o", str(fig)]) == 0
    assert _png(fig)
    assert "3 of 3 objects drawn" in capsys.readouterr().err
    df = pd.read_csv(example_tracks, dtype={"id": str})
    figure, drawn = plot_tracks(df)
    assert drawn == ["car", "cyclist", "pedestrian"]
    ax_map = figure.axes[0]
    assert len([ln for ln in ax_map.lines if ln.get_label() in drawn]) == 3  # one track line per object
    assert len(ax_map.patches) >= 3 * 10  # the 95 % ellipses, about 15 per object


def test_plot_picks_objects_and_refuses_what_it_cannot_do(example_tracks, tmp_path, capsys):
    fig = tmp_path / "one.svg"
    assert main(["plot", str(example_tracks), "--id", "cyclist", "-o", str(fig)]) == 0
    assert fig.read_text().lstrip().startswith("<?xml") and "1 of 3 objects drawn" in capsys.readouterr().err
    for args, msg in ((["--id", "bus"], "no object bus"), (["-o", str(tmp_path / "x.html")], ".html page is not made"),
                      (["--every", "0"], "--every")):
        out = ["-o", str(tmp_path / "f.png")] if "-o" not in args else []
        assert main(["plot", str(example_tracks), *args, *out]) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and msg in err[0], err
        assert not (tmp_path / "f.png").exists()


@pytest.mark.skipif(not (DATA / "eth_ucy_trajectronpp" / "biwi_eth.txt").exists(),
                    reason="real data absent: ../shared/data/eth_ucy_trajectronpp/biwi_eth.txt (set LGEKF_DATA)")
def test_plot_real_pedestrians(tmp_path, capsys):
    tracks = tmp_path / "eth.csv"
    src = DATA / "eth_ucy_trajectronpp" / "biwi_eth.txt"
    assert main(["track", str(src), "--format", "pedestrian", "--frame-dt", "0.06667", "-o", str(tracks), "--quiet",
                 "--skip-invalid"]) == 0
    n = pd.read_csv(tracks, dtype={"id": str})["id"].nunique()
    fig = tmp_path / "eth.png"
    assert main(["plot", str(tracks), "-o", str(fig)]) == 0
    assert _png(fig)
    assert f"{min(n, MAX_OBJECTS)} of {n} objects drawn" in capsys.readouterr().err
