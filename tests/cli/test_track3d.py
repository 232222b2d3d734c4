"""`lgekf track` on files of 3-D positions (a z column, or lat, lon, alt): the space of the input selects the models
(default ct3; se3r6 for poses) and the measurement (position3, pose3); the two-point start in 3-D against a hand-computed case;
lat, lon, alt to east-north-up metres against hand-computed values; bad input -> one line, exit 2, no output.

One CLI run of the default model on a small synthetic drone (module-scoped: the 3-D kernels compile slowly); the
bad inputs fail before any kernel is compiled."""

from __future__ import annotations

import math
import subprocess

import numpy as np
import pytest
from _cli import cli_command

from lgekf.apps.track import default_model
from lgekf.cli import main
from lgekf.core.initiation import two_point
from lgekf.io.geo import WGS84_A, WGS84_F, to_local_enu
from lgekf.io.readers import read_csv

R_HELIX, SPEED, CLIMB, DT, N, SIGMA = 40.0, 8.0, 1.5, 0.2, 120, 0.5  # a drone climbing in a helix, 5 Hz, 0.5 m noise
T0 = 1.7e9  # epoch seconds


def run(*args, cwd=None):
    return subprocess.run([*cli_command(), "track", *map(str, args)], capture_output=True, text=True, cwd=cwd)


def helix_truth():
    """t (N,), positions (N, 3) of a helix: radius 40 m, 8 m/s horizontal, 1.5 m/s climb from 300 m, turn rate 0.2."""
    t = T0 + DT * np.arange(N)
    ph = SPEED / R_HELIX * (t - T0)
    return t, np.column_stack([R_HELIX * np.sin(ph), R_HELIX * (1 - np.cos(ph)), 300.0 + CLIMB * (t - T0)])


@pytest.fixture(scope="module")
def drone(tmp_path_factory):
    """The default `lgekf track` (no option) of the noisy helix: (header, values (N, k), truth positions, stderr)."""
    d = tmp_path_factory.mktemp("drone")
    t, p = helix_truth()
    z = p + SIGMA * np.random.default_rng(5).standard_normal(p.shape)
    src = d / "drone.csv"
    np.savetxt(src, np.column_stack([t, z]), delimiter=",", header="t,x,y,z", comments="", fmt="%.6f")
    r = run(src, "-o", d / "out.csv")
    assert r.returncode == 0, r.stderr
    with open(d / "out.csv") as f:
        header = f.readline().strip().split(",")
    return header, np.loadtxt(d / "out.csv", delimiter=",", skiprows=1), p, r.stderr, z


@pytest.mark.slow
def test_default_track_of_a_3d_file_is_ct3_with_3d_columns(drone):
    header, x, _, err, _ = drone
    assert header == ["id", "t", "x", "y", "z", "psi", "v", "omega", "vz", "std_x", "std_y", "std_z", "std_psi", "std_v",
                      "std_omega", "std_vz", "speed", "course", "climb", "turn_rate", "nis", "flag"]
    assert "ct3" in err and "meas-std" in err  # the noise came from the data and says so
    nis = header.index("nis")
    assert np.isnan(x[:2, nis]).all() and np.isfinite(np.delete(x, nis, axis=1)).all() and np.isfinite(x[2:, nis]).all()


@pytest.mark.slow
def test_3d_track_errors_are_near_the_truth(drone):
    header, x, p, _, z = drone
    col = {c: i for i, c in enumerate(header)}
    late = slice(20, None)  # after the two-point start has settled
    pos = np.sqrt(np.mean(np.sum((x[late, 2:5] - p[late]) ** 2, axis=1)))
    meas = np.sqrt(np.mean(np.sum((z[late] - p[late]) ** 2, axis=1)))
    assert pos < 0.7 * meas  # the filter beats its measurements (0.86 m here)
    assert abs(np.median(x[late, col["speed"]]) - math.hypot(SPEED, CLIMB)) < 0.3
    assert abs(np.median(x[late, col["climb"]]) - CLIMB) < 0.3
    assert abs(np.median(x[late, col["turn_rate"]]) - SPEED / R_HELIX) < 0.03
    # the course of the helix at time τ is the phase ω τ (wrapped)
    t = x[late, col["t"]]
    course = np.angle(np.exp(1j * (x[late, col["course"]] - SPEED / R_HELIX * (t - T0))))
    assert np.sqrt(np.mean(course ** 2)) < 0.1


@pytest.mark.slow
def test_lat_lon_alt_file_is_tracked_in_east_north_up(drone, tmp_path):
    """The drone's positions as lat, lon, alt about (49°, 8.4°, 112 m) (``to_latlon``, the inverse of the reader's
    projection): the same track in metres east, north, up of the first fix, the fix in origin_lat, origin_lon,
    origin_alt."""
    from lgekf.io.geo import to_latlon

    header, x, _, _, z = drone
    lat, lon = to_latlon(z[:, 0] - z[0, 0], z[:, 1] - z[0, 1], 49.0, 8.4)
    t = T0 + DT * np.arange(N)
    src = tmp_path / "geo.csv"
    np.savetxt(src, np.column_stack([t, lat, lon, 112.0 + z[:, 2] - z[0, 2]]), delimiter=",", header="t,lat,lon,alt",
               comments="", fmt="%.12f")
    assert main(["track", str(src), "-o", str(tmp_path / "out.csv"), "--quiet"]) == 0
    with open(tmp_path / "out.csv") as f:
        h2 = f.readline().strip().split(",")
    y = np.loadtxt(tmp_path / "out.csv", delimiter=",", skiprows=1)
    assert h2[-4:] == ["origin_lat", "origin_lon", "origin_alt", "flag"]
    np.testing.assert_allclose(y[:, h2.index("origin_lat"):h2.index("flag")], np.tile([lat[0], lon[0], 112.0], (N, 1)), rtol=1e-15)
    np.testing.assert_allclose(y[0, 2:5], 0.0, atol=1e-6)  # the first fix is the origin
    enu = z - z[0]
    assert np.max(np.abs(enu)) > 50  # a flight of some size
    # the same track, shifted to the fix: the reader's projection inverts to_latlon about the same origin (5e-7 m here)
    assert np.max(np.abs(y[:, 2:5] - x[:, 2:5] + z[0])) < 1e-5


def test_default_model_by_space_and_measurement():
    """Positions: se2se2 in the plane, ct3 in 3-D (docs/space3d.md); a pose in 3-D: se3r6, the model that takes it."""
    assert default_model("2d", "position") == "se2se2" and default_model("2d", "pose") == "se2se2"
    assert default_model("3d", "position") == "ct3" and default_model("3d", "position3") == "ct3"
    assert default_model("3d", "pose") == "se3r6" and default_model("3d", "pose3") == "se3r6"


def test_two_point_start_in_3d_by_hand():
    """w = (z1 − z0)/Δt = (3, 4, 12): yaw = atan2(4, 3), pitch = −atan2(12, 5), roll 0, body velocity (13, 0, 0);
    r = 0.5: σ_v² = 2r²/Δt² = 0.5; var yaw = σ_v²/|w_h|² = 0.02, var pitch = σ_v²/|w|² = 0.5/169, var roll = cap² (π²),
    var v_y = max(σ_v² − 25 · 0.02, 0.1² σ_v²) = 0.005, var v_z = max(σ_v² − 169 · 0.5/169, 0.005) = 0.005."""
    t = np.array([10.0, 11.0])
    z = np.array([[1.0, 2.0, 300.0], [4.0, 6.0, 312.0]])
    c, var = two_point(t, z, np.array([1]), 0.5, omega_std=0.4)
    want = [4, 6, 312, 0, -math.atan2(12, 5), math.atan2(4, 3), 13, 0, 0, 0, 0, 0]
    np.testing.assert_allclose(c[0], want, rtol=0, atol=1e-12)
    np.testing.assert_allclose(var[0], [0.25] * 3 + [math.pi ** 2, 0.5 / 169, 0.02, 0.5, 0.005, 0.005] + [0.16] * 3, rtol=1e-12)
    # a slow object: the heading's variance at the cap, the rest of the lateral velocity error in v_y
    c, var = two_point(t, np.array([[0.0, 0.0, 0.0], [0.1, 0.0, 0.0]]), np.array([1]), 0.5, heading_cap=0.3)
    assert var[0, 5] == pytest.approx(0.09) and var[0, 3] == pytest.approx(0.09)
    assert var[0, 7] == pytest.approx(0.5 - 0.01 * 0.09) and var[0, 4] == pytest.approx(0.09)


def test_two_point_start_with_a_measured_attitude():
    """roll, pitch, yaw measured: taken as they are (var heading_std²); body v_x = w · R e_x with
    R e_x = (cos yaw cos pitch, sin yaw cos pitch, −sin pitch), v_y = v_z = 0 with the side-slip floor."""
    t = np.array([0.0, 0.5])
    z = np.array([[0.0, 0.0, 0.0], [2.0, 1.0, -0.5]])
    att = np.array([[0.0, 0.0, 0.0], [0.1, -0.2, 0.3]])
    c, var = two_point(t, z, np.array([1]), 0.2, heading=att, heading_std=0.05)
    w = np.array([4.0, 2.0, -1.0])
    ex = np.array([math.cos(0.3) * math.cos(-0.2), math.sin(0.3) * math.cos(-0.2), -math.sin(-0.2)])
    np.testing.assert_allclose(c[0, 3:9], [0.1, -0.2, 0.3, w @ ex, 0, 0], atol=1e-12)
    sv2 = 2 * 0.2 ** 2 / 0.5 ** 2
    np.testing.assert_allclose(var[0, 3:9], [0.0025] * 3 + [sv2, 0.01 * sv2, 0.01 * sv2], rtol=1e-12)


def test_lat_lon_alt_to_east_north_up_by_hand(tmp_path):
    """At the equator N0 = a and M0 = a(1 − e²): 0.001° east is a·π/180·0.001 m, 0.001° north a(1 − e²)·π/180·0.001 m;
    up = alt − alt0. The reader's x, y, z of a t, lat, lon, alt file and its origin (lat0, lon0, alt0)."""
    e2 = WGS84_F * (2 - WGS84_F)
    step = math.pi / 180 * 0.001
    x, y, z = to_local_enu([0.0, 0.0, 0.001], [0.0, 0.001, 0.001], [100.0, 110.0, 95.0], 0.0, 0.0, 100.0)
    np.testing.assert_allclose(x, [0, WGS84_A * step, WGS84_A * step], rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(y, [0, 0, WGS84_A * (1 - e2) * step], rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(z, [0, 10, -5], atol=1e-12)
    f = tmp_path / "geo.csv"
    f.write_text("t,lat,lon,alt\n0,0,0,100\n1,0,0.001,110\n2,0.001,0.001,95\n")
    m = read_csv(f)
    assert m.origin == (0.0, 0.0, 100.0) and m.z.shape == (3, 3)
    np.testing.assert_allclose(m.z, np.column_stack([x, y, z]), atol=1e-9)


GOOD3 = "t,x,y,z\n0,0,0,100\n0.2,1,0,100.2\n0.4,2,0.1,100.4\n0.6,3,0.1,100.7\n"

BAD3 = {
    "planar_model_on_3d": (GOOD3, ["--model", "se2r3"], "--model se2r3: a model of the plane, and the input has 3-D positions"),
    "3d_model_on_planar": ("t,x,y\n0,0,0\n1,1,0\n2,2,0\n", ["--model", "cv3"], "--model cv3: a model of 3-D space, and the input has 2-D"),
    "lat_without_lon": ("t,lat,alt\n0,49,100\n1,49.0001,101\n", [], "missing column 'lon'"),
    "nan_in_z": ("t,x,y,z\n0,0,0,0\n1,1,0,nan\n2,2,0,0\n", [], "line 3: column 'z' is nan"),
    "pose_without_attitude": (GOOD3, ["--measure", "pose"], "a pose in 3-D needs roll, pitch and yaw"),
    "pose3_on_cv3": (GOOD3, ["--model", "cv3", "--measure", "pose3"], "the cv3 model has no attitude to measure"),
    "planar_imm_modes_on_3d": (GOOD3, ["--model", "imm", "--imm-modes", "cv,se2r3"],
                               "--imm-modes: cv,se2r3 are models of the plane, and the input has 3-D positions"),
    "position3_on_planar": ("t,x,y\n0,0,0\n1,1,0\n2,2,0\n", ["--measure", "position3"],
                            "--measure position3: observes 3-D space, and the input has 2-D positions"),
    "planar_accel_std_on_3d": (GOOD3, ["--accel-std", "cv=1", "--model", "cv3"], "unknown model 'cv'; choose one of ct3, cv3, se3r6"),
}


@pytest.mark.parametrize("case", sorted(BAD3))
def test_bad_3d_input_is_one_line_and_exit_2(tmp_path, capsys, case):
    """In process (``lgekf.cli.main``, what the command runs); the first case also as the command itself."""
    text, args, msg = BAD3[case]
    src = tmp_path / "in.csv"
    src.write_text(text)
    out = tmp_path / "out.csv"
    if case == "planar_model_on_3d":
        r = run(src, "-o", out, *args)
        status, err = r.returncode, r.stderr
    else:
        status = main(["track", str(src), "-o", str(out), *args])
        err = capsys.readouterr().err
    assert status == 2, err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and msg in lines[0], err
    assert not out.exists()
