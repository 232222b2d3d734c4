"""``lgekf.track``: the main job from Python gives exactly what ``lgekf track`` writes (the same engine)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

import lgekf
from lgekf.cli import main

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "data" / "detections.csv"


def _example(tmp_path):
    """The README's example input (examples/data/make_detections.py makes it)."""
    return EXAMPLE


@pytest.mark.parametrize("extra", [[], ["--model", "imm", "--smooth"]])
def test_track_from_python_equals_the_cli_byte_for_byte(tmp_path, capsys, extra):
    src = _example(tmp_path)
    cli_out, api_out = tmp_path / "cli.csv", tmp_path / "api.csv"
    assert main(["track", str(src), "-o", str(cli_out), "--quiet", *extra]) == 0
    kw = {"model": "imm", "smooth": True} if extra else {}
    df = lgekf.track(src, output=api_out, **kw)
    assert api_out.read_bytes() == cli_out.read_bytes()
    pd.testing.assert_frame_equal(df, pd.read_csv(cli_out, dtype={"id": str}), check_exact=True)
    assert list(df.columns) == cli_out.read_text().splitlines()[0].split(",")


def test_track_takes_a_dataframe_and_a_dict(tmp_path):
    src = _example(tmp_path)
    ref = lgekf.track(src)
    table = pd.read_csv(src, dtype={"id": str})
    from_df = lgekf.track(table)
    from_dict = lgekf.track({c: table[c].to_numpy() for c in table.columns})
    pd.testing.assert_frame_equal(from_df, ref, check_exact=True)
    pd.testing.assert_frame_equal(from_dict, ref, check_exact=True)


def test_track_options_and_errors(tmp_path):
    src = _example(tmp_path)
    df = lgekf.track(src, model="cv", meas_std=0.5, no_monitor=True)
    assert "vx" in df.columns and (df["flag"] == 0).all()
    with pytest.raises(ValueError, match="meas-std"):
        lgekf.track(src, model="cv", meas_std=-1.0)
    with pytest.raises(ValueError, match="invalid choice"):
        lgekf.track(src, model="nope")
    with pytest.raises(ValueError, match="same length"):
        lgekf.track({"t": [0.0, 1.0], "x": [0.0], "y": [0.0, 1.0]})


def test_track_takes_a_dataframe_with_nan_rows_and_writes_parquet(tmp_path):
    table = pd.read_csv(EXAMPLE, dtype={"id": str})
    dirty = table.copy()
    dirty.loc[5, "x"] = np.nan  # NaN in a DataFrame: written as the reader's nan, dropped by skip_invalid
    clean = table.drop(index=5).reset_index(drop=True)
    pd.testing.assert_frame_equal(lgekf.track(dirty, skip_invalid=True), lgekf.track(clean), check_exact=True)
    pytest.importorskip("pyarrow", reason="Parquet output needs the optional pyarrow (lgekf[parquet])")
    df = lgekf.track(EXAMPLE, output=tmp_path / "tracks.parquet")
    assert list(df.columns) == list(lgekf.track(EXAMPLE).columns) and len(df) == len(table)
