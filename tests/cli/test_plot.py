"""`lgekf plot` and `lgekf.plot_tracks`: a picture of a track file, from the example input and from real data; the
interactive .html page (plotly, self-contained) with the same content."""

from __future__ import annotations

import json
import os
import sys
from collections import Counter
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


def _html_traces(path):
    """The traces of the plotly page at ``path`` (the JSON argument of its ``Plotly.newPlot`` call)."""
    html = path.read_text(encoding="utf-8")
    dec = json.JSONDecoder()
    j = html.rindex("Plotly.newPlot(") + len("Plotly.newPlot(")
    while html[j].isspace():
        j += 1
    _, j = dec.raw_decode(html, j)  # the div's id
    data, _ = dec.raw_decode(html, html.index("[", j))
    return data


def _kinds(traces, kind):
    return [d for d in traces if d["meta"]["kind"] == kind]


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
    for args, msg in ((["--id", "bus"], "no object bus"), (["-o", str(tmp_path / "x.jpg")], "write .png, .svg, .pdf, .html"),
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
    try:
        import plotly  # noqa: F401
    except ImportError:
        return
    page = tmp_path / "eth.html"
    assert main(["plot", str(tracks), "-o", str(page)]) == 0
    traces = _html_traces(page)
    assert len(_kinds(traces, "track")) == min(n, MAX_OBJECTS) == len(_kinds(traces, "ellipses"))


def test_plot_html_is_a_self_contained_page_with_the_same_content(example_tracks, tmp_path, capsys):
    pytest.importorskip("plotly")
    df = pd.read_csv(example_tracks, dtype={"id": str})
    df.loc[(df["id"] == "cyclist") & (df["t"] > 3) & (df["t"] < 4), "flag"] = 1  # the map marks what the file flags
    n_flagged = int(((df["flag"] & 1) > 0).sum())
    assert n_flagged >= 5
    flagged = tmp_path / "flagged.csv"
    df.to_csv(flagged, index=False)
    page = tmp_path / "fig.html"
    assert main(["plot", str(flagged), "--measurements", str(EXAMPLE), "-o", str(page), "--every", "5"]) == 0
    assert "3 of 3 objects drawn" in capsys.readouterr().err
    html = page.read_text(encoding="utf-8")
    assert html.lstrip().lower().startswith("<!doctype html>") and html.rstrip().endswith("</html>")
    assert "<script src=" not in html and 'src="http' not in html  # works offline: nothing loaded from elsewhere
    assert len(html) > 3_000_000 and "plotly.js v" in html  # plotly.js itself is inlined
    traces = _html_traces(page)
    assert [d["name"] for d in _kinds(traces, "track")] == ["car", "cyclist", "pedestrian"]  # one trace per object
    assert len({d["line"]["color"] for d in _kinds(traces, "track")}) == 3  # one colour per object
    assert [d["meta"]["object"] for d in _kinds(traces, "measurements")] == ["car", "cyclist", "pedestrian"]
    assert len(_kinds(traces, "smoothed")) == 3  # the file has smooth_* columns
    rows = df.groupby("id").size()
    for d in _kinds(traces, "ellipses"):  # a 95 % ellipse every 5 rows: closed polylines separated by None
        assert d["meta"]["every"] == 5
        assert d["x"].count(None) == -(-rows[d["meta"]["object"]] // 5)
    [flags] = _kinds(traces, "flagged")
    assert flags["meta"]["object"] == "cyclist" and len(flags["x"]) == n_flagged and flags["marker"]["symbol"] == "x"
    per_object = Counter((d["meta"]["object"], d["meta"]["kind"]) for d in traces)
    for name in ("car", "cyclist", "pedestrian"):
        for kind in ("speed", "speed band", "course", "course band", "turn rate", "turn rate band", "smoothed turn rate"):
            assert per_object[name, kind] == 1, (name, kind)
    speed = _kinds(traces, "speed")[0]
    assert len(speed["x"]) == rows["car"] and all(v is not None and v > 0 for v in speed["y"])
    band = _kinds(traces, "speed band")[0]  # a closed polygon: upper edge forward, lower edge back
    assert len(band["x"]) == 2 * rows["car"] and band["fill"] == "toself"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["fig.html", "flagged.csv"]  # no temporary file left


def test_plot_tracks_html_from_python(example_tracks, tmp_path):
    pytest.importorskip("plotly")
    import lgekf

    df = pd.read_csv(example_tracks, dtype={"id": str})
    fig, drawn = lgekf.plot_tracks(df, ids=["pedestrian"], path=tmp_path / "p.html")
    assert drawn == ["pedestrian"] and type(fig).__module__.startswith("plotly")
    assert [d["name"] for d in _kinds(_html_traces(tmp_path / "p.html"), "track")] == ["pedestrian"]


def test_plot_html_without_plotly_says_which_extra(example_tracks, tmp_path, capsys, monkeypatch):
    monkeypatch.setitem(sys.modules, "plotly", None)  # import plotly raises ImportError
    page = tmp_path / "fig.html"
    assert main(["plot", str(example_tracks), "-o", str(page)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and 'pip install "lgekf[html]"' in err[0], err
    assert list(tmp_path.iterdir()) == []


def test_plot_draws_a_multi_target_output(tmp_path, capsys):
    """`lgekf track --multi`'s output (the tracks' ids in a `track` column, existence and flag) is drawn like any track
    file: one line per confirmed track (issue #29 item 5)."""
    out, fig = tmp_path / "multi.csv", tmp_path / "multi.png"
    assert main(["track", str(EXAMPLE), "--multi", "--sort", "-o", str(out), "--quiet"]) == 0
    n_tracks = pd.read_csv(out)["track"].nunique()
    assert n_tracks == 3  # the three objects of the example (tests/cli/test_track_multi_defaults.py)
    assert main(["plot", str(out), "-o", str(fig)]) == 0
    assert _png(fig)
    assert f"{n_tracks} of {n_tracks} objects drawn" in capsys.readouterr().err
