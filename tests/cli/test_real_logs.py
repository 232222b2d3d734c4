"""Real logs that are almost right (issue 27): each case a file made for it, run as a user runs ``lgekf track``."""

from __future__ import annotations

import csv

import numpy as np

from lgekf.cli import main


def _turning_car(path, heading_unit="rad", n=120, seed=0):
    """A car at 10 m/s turning at 0.2 rad/s, 10 Hz, 0.5 m position noise, a heading column (0.05 rad noise) in
    ``heading_unit``. Returns the true positions."""
    rng = np.random.default_rng(seed)
    t = 0.1 * np.arange(n)
    psi = 0.4 + 0.2 * t
    p = np.column_stack([50 * (np.sin(psi) - np.sin(0.4)), -50 * (np.cos(psi) - np.cos(0.4))])
    z = p + 0.5 * rng.standard_normal(p.shape)
    h = np.angle(np.exp(1j * (psi + 0.05 * rng.standard_normal(n))))
    h = np.degrees(h) if heading_unit == "deg" else h
    rows = ["id,t,x,y,heading"] + [f"car,{t[k]:.2f},{z[k, 0]:.4f},{z[k, 1]:.4f},{h[k]:.5f}" for k in range(n)]
    path.write_text("\n".join(rows) + "\n")
    return p


def _pos_rmse(out, p):
    rows = list(csv.DictReader(open(out)))
    x = np.array([[float(r["x"]), float(r["y"])] for r in rows])
    return float(np.sqrt(np.mean(np.sum((x[2:] - p[2:]) ** 2, axis=1))))


def test_heading_in_degrees_is_refused_with_a_hint_and_converted_on_request(tmp_path, capsys):
    src = tmp_path / "deg.csv"
    p = _turning_car(src, "deg")
    out = tmp_path / "out.csv"
    assert main(["track", str(src), "--measure", "pose", "-o", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--heading-unit deg" in err[0] and not out.exists()
    assert main(["track", str(src), "--measure", "pose", "--heading-unit", "deg", "-o", str(out), "--quiet"]) == 0
    in_deg = _pos_rmse(out, p)
    rad = tmp_path / "rad.csv"
    _turning_car(rad, "rad")
    assert main(["track", str(rad), "--measure", "pose", "-o", str(out), "--quiet"]) == 0
    assert abs(in_deg - _pos_rmse(out, p)) < 1e-6  # the numbers of the file in radians (up to the 5 written digits)
    assert in_deg < 0.5  # and better than the raw 0.5 m per axis (0.71 m)


def test_an_unwrapped_heading_in_radians_is_kept(tmp_path, capsys):
    """A heading beyond ±2π that follows the motion as radians (an unwrapped yaw) is not mistaken for degrees."""
    src = tmp_path / "unwrapped.csv"
    rng = np.random.default_rng(3)
    t = 0.1 * np.arange(200)
    psi = 0.5 + 0.6 * t  # two full turns: the yaw grows past 2π
    p = np.column_stack([20 * np.sin(psi), -20 * np.cos(psi)])
    z = p + 0.2 * rng.standard_normal(p.shape)
    src.write_text("t,x,y,heading\n" + "".join(f"{t[k]:.2f},{z[k, 0]:.4f},{z[k, 1]:.4f},{psi[k]:.5f}\n" for k in range(t.size)))
    out = tmp_path / "out.csv"
    assert main(["track", str(src), "--measure", "pose", "-o", str(out), "--quiet"]) == 0
    assert _pos_rmse(out, p) < 0.2


def _two_objects_rows(seed=1):
    """Rows id,t,x,y of a car (60 rows, 10 Hz) and a cyclist (40 rows), 0.2 m noise, in file order."""
    rng = np.random.default_rng(seed)
    rows = []
    for name, v, n in (("car", 8.0, 60), ("bike", 4.0, 40)):
        for k in range(n):
            rows.append([name, round(0.1 * k, 2), v * 0.1 * k + 0.2 * rng.standard_normal(), 0.2 * rng.standard_normal()])
    return rows


def _write(path, rows):
    path.write_text("id,t,x,y\n" + "".join(f"{r[0]},{r[1]},{r[2]},{r[3]}\n" for r in rows))
    return path


def _run(tmp_path, capsys, rows, *opts):
    src = _write(tmp_path / "in.csv", rows)
    out = tmp_path / "out.csv"
    code = main(["track", str(src), "--model", "cv", "--meas-std", "0.2", "--accel-std", "1", "-o", str(out), "--quiet", *opts])
    err = capsys.readouterr().err
    return code, err, (out.read_text() if out.exists() else None)


def test_each_defect_is_refused_naming_the_option_that_takes_it(tmp_path, capsys):
    good = _two_objects_rows()
    cases = {
        "--skip-invalid drops such objects": good + [["lone", 0.0, 1.0, 1.0]],  # a single-row object
        "--sort sorts them, --skip-invalid drops repeated times": good[:10] + [good[9]] + good[10:],  # a duplicate time
        "--skip-invalid drops such rows": good[:5] + [["car", 0.45, float("nan"), 0.0]] + good[5:],  # a NaN
    }
    for hint, rows in cases.items():
        code, err, text = _run(tmp_path, capsys, rows)
        assert code == 2 and text is None and len(err.strip().splitlines()) == 1 and hint in err, err


def test_skip_invalid_drops_the_defects_and_tracks_the_rest_as_the_clean_file(tmp_path, capsys):
    good = _two_objects_rows()
    code, _, clean = _run(tmp_path, capsys, good)
    assert code == 0
    dirty = good[:5] + [["car", 0.45, float("nan"), 0.0]] + good[5:10] + [good[9]] + good[10:] + [["lone", 0.0, 1.0, 1.0]]
    code, err, text = _run(tmp_path, capsys, dirty, "--skip-invalid")
    assert code == 0 and text == clean
    lines = err.strip().splitlines()
    assert len(lines) == 3 and all(line.startswith("lgekf track: warning: skipped 1 row (") for line in lines), err
    assert "non-finite; line 7" in err and "time not after the previous row's; line 13" in err and "fewer than 2 rows" in err


def test_sort_puts_unsorted_rows_in_time_order(tmp_path, capsys):
    good = _two_objects_rows()
    code, _, clean = _run(tmp_path, capsys, good)
    shuffled = list(good)
    shuffled[3], shuffled[7] = shuffled[7], shuffled[3]  # two rows of the car swapped
    shuffled[50], shuffled[70] = shuffled[70], shuffled[50]  # a car row and a bike row: objects' rows interleaved
    code, err, _ = _run(tmp_path, capsys, shuffled)
    assert code == 2 and "--sort" in err
    code, err, text = _run(tmp_path, capsys, shuffled, "--sort")
    # rows whose place among their object's rows changed: the car's rows 3 and 7, and its last 10 (its t = 5.0 row now
    # last); the bike's first 11 (its t = 1.0 row, now in the car's block, comes before its t = 0.0 row)
    assert code == 0 and "--sort: 23 rows moved into time order" in err
    assert text == clean


def test_skip_invalid_drops_an_object_whose_every_row_is_not_finite(tmp_path, capsys):
    good = _two_objects_rows()
    rows = good + [["ghost", 0.0, "1e999", 0.0], ["ghost", 0.1, "1e999", 0.0]]  # read as inf by the fast reader
    code, _, clean = _run(tmp_path, capsys, good)
    code, err, text = _run(tmp_path, capsys, rows, "--skip-invalid")
    assert code == 0 and text == clean and "skipped 2 rows (non-finite" in err


def test_the_imm_refuses_to_overwrite_its_input(tmp_path, capsys):
    src = _write(tmp_path / "in.csv", _two_objects_rows())
    before = src.read_bytes()
    assert main(["track", str(src), "--model", "imm", "-o", str(src)]) == 2
    assert "would overwrite the input" in capsys.readouterr().err and src.read_bytes() == before
