"""`lgekf track --multi` on detections in 3-D space (a z column): the default model of the space (ct3) with position3
detections, clutter per m³, one-point starts with a 3-D velocity prior, GOSPA in 3-D; the pieces against hand-computed
or independent values (the prior, the clutter volume, the quartile of the provisional noise, the volume of SO(3));
3-D models refused on planar input, the IMM on 3-D input (one line, exit 2).

One CLI run (module-scoped, in process: the 3-D bank kernels compile once) on a small scene: three objects (one
climbing straight, one turning and descending, one level), 10 Hz, 0.3 m noise per axis, P_D 0.9, 3 false alarms per
scan uniform in a 140 x 130 x 70 m box, epoch times."""

from __future__ import annotations

import contextlib
import io
import math

import numpy as np
import pytest
from scipy import integrate, stats
from _cli import track_error_line

import lgekf
from lgekf.apps.track_multi import nearest_distance_quartile
from lgekf.cli import main
from lgekf.estimators.multitarget.clutter import ClutterMap, ScanClutter, bounding_box_density, clutter_from_data, map_cell_from_counts
from lgekf.estimators.multitarget.tracker import HEADING_CAP, attitude_volume, one_point_prior

T, K, R, T0 = 0.1, 60, 0.3, 1.7e9
BOX = np.array([[-50.0, 90.0], [-40.0, 90.0], [30.0, 100.0]])
CLUTTER = 3.0  # false alarms per scan


def truth_at(k):
    t = k * T
    return np.array([[10 * t, 0.0, 50 + 1.0 * t],
                     [20 * math.sin(0.3 * t), 20 * (1 - math.cos(0.3 * t)) + 40, 80 - 2 * t],
                     [-30 + 5 * t, -20 + 5 * t, 60.0]])


@pytest.fixture(scope="module")
def scene(tmp_path_factory):
    """The detections file, the truth file, the output table (header, values) and stderr of `lgekf track --multi` with
    no option."""
    d = tmp_path_factory.mktemp("multi3")
    rng = np.random.default_rng(2)
    rows, truth = [], []
    for k in range(K):
        X = truth_at(k)
        truth += [[i, T0 + k * T, *X[i]] for i in range(3)]
        det = X[rng.random(3) < 0.9]
        det = det + R * rng.standard_normal(det.shape)
        clutter = BOX[:, 0] + (BOX[:, 1] - BOX[:, 0]) * rng.random((rng.poisson(CLUTTER), 3))
        rows += [[T0 + k * T, *z] for z in np.vstack([det, clutter])]
    src, tru, out = d / "detections.csv", d / "truth.csv", d / "tracks.csv"
    np.savetxt(src, np.array(rows), delimiter=",", header="t,x,y,z", comments="", fmt="%.6f")
    np.savetxt(tru, np.array(truth), delimiter=",", header="id,t,x,y,z", comments="", fmt="%.6f")
    return src, tru, out


@pytest.fixture(scope="module")
def tracked(scene):
    src, _, out = scene
    err = io.StringIO()
    with contextlib.redirect_stderr(err):
        status = main(["track", str(src), "--multi", "-o", str(out)])
    assert status == 0, err.getvalue()
    with open(out) as f:
        header = f.readline().strip().split(",")
    return header, np.loadtxt(out, delimiter=",", skiprows=1), err.getvalue()


@pytest.mark.slow
def test_multi_3d_output_has_the_3d_model_and_motion_columns(tracked):
    header, x, err = tracked
    assert header == ["track", "t", "x", "y", "z", "psi", "v", "omega", "vz", "std_x", "std_y", "std_z", "std_psi", "std_v",
                      "std_omega", "std_vz", "speed", "course", "climb", "turn_rate", "existence", "flag"]
    assert np.isfinite(x).all() and x.shape[0] > 2 * K
    assert "per m³ per scan" in err and "meas-std" in err  # the clutter and the noise came from the data, and say so


@pytest.mark.slow
def test_multi_3d_finds_the_three_objects_within_the_noise(scene, tracked):
    """After the first second (the tracks confirmed), per scan: no false track, at most one scan in ten with a missed
    object, and the mean localisation part of GOSPA (c = 5 m, p = 2) below what the measurements themselves would
    give: Σ over 3 objects of E|z − x|² = 3 · 3r² = 0.81 m²; no track switch."""
    _, tru, out = scene
    g = lgekf.gospa(out, tru, c=5.0)
    late = slice(10, None)
    assert np.all(g.n_false[late] == 0)
    assert np.mean(g.n_missed[late] > 0) <= 0.1
    assert np.mean(g.localisation[late]) < 9 * R**2, np.mean(g.localisation[late])
    assert g.switches == 0
    header, x, _ = tracked
    assert np.unique(x[:, 0]).size == 3


def test_one_point_prior_in_3d_by_hand():
    """Position detections (x, y, z): c = (x, y, z, 0 ... 0), var = r² (position), HEADING_CAP² (roll, pitch, yaw), σ_v²
    (body velocity), σ_ω² (rate); a pose3 detection's angles wrapped, with variance heading_std²."""
    c, var = one_point_prior(np.array([[1.0, 2.0, 3.0]]), 0.5, 4.0, 0.3, 0.1, dim=3)
    np.testing.assert_array_equal(c, [[1, 2, 3] + [0] * 9])
    np.testing.assert_allclose(var, [[0.25] * 3 + [HEADING_CAP**2] * 3 + [16.0] * 3 + [0.09] * 3])
    c, var = one_point_prior(np.array([[1.0, 2.0, 3.0, 0.1, -0.2, 2 * math.pi + 0.3]]), 0.5, 4.0, 0.3, 0.1, dim=3)
    np.testing.assert_allclose(c[0, 3:6], [0.1, -0.2, 0.3], atol=1e-15)
    np.testing.assert_allclose(var[0, 3:6], [0.01] * 3)
    c2, var2 = one_point_prior(np.array([[1.0, 2.0]]), 0.5, 4.0, 0.3, 0.1)  # the plane: unchanged (x, y, θ, vx, vy, ω)
    np.testing.assert_allclose(var2, [[0.25, 0.25, HEADING_CAP**2, 16.0, 16.0, 0.09]])


def test_clutter_per_cubic_metre():
    """10 detections per scan in a 2 x 5 x 10 m box: 10/100 per m³; the map's cube side from its counts,
    (V·30/(M̄/(1 − a)))^(1/3); a detection counted in the cube that holds it; the per-scan estimate over the box."""
    z = np.array([[0, 0, 0], [2, 5, 10.0]])
    z = np.vstack([z, np.full((8, 3), 1.0)])
    assert bounding_box_density(z, 1, 3) == pytest.approx(0.1)
    assert map_cell_from_counts(z, 1, 0.99, dim=3) == pytest.approx((100.0 * 30 / 1000.0) ** (1 / 3))
    m = clutter_from_data("map", z, 1, 3)
    assert isinstance(m, ClutterMap) and m.dim == 3 and m.surveillance_area == pytest.approx(100.0)
    m = ClutterMap(cell=2.0, area=1000.0, dim=3)
    Z = np.array([[0.5, 0.5, 0.5], [5.0, -3.0, 7.9]])
    lam = m.density(0.0, Z, 0.0)
    m.update(Z, np.array([1.0, 0.5]))
    cells = np.floor(Z / 2.0).astype(np.int64) - m.origin
    assert m.counts.ndim == 3 and m.counts[tuple(cells[0])] == pytest.approx(1.0) and m.counts[tuple(cells[1])] == pytest.approx(0.5)
    assert lam.shape == (2,)
    s = ScanClutter(dim=3)
    s.density(0.0, np.array([[0, 0, 0.0], [2, 3, 4.0]]), 0.0)
    assert s.surveillance_area == pytest.approx(24.0)


def test_provisional_quartile_and_attitude_volume_against_independent_values():
    """The lower quartile of |z1 − z0|/σ: √2 × the χ_d quartile (scipy.stats.chi); the volume of SO(3) in rotation
    vectors, ∫ over |φ| ≤ π of 2(1 − cos|φ|)/|φ|² (numerical quadrature), and of SO(2), 2π."""
    for d in (2, 3):
        assert nearest_distance_quartile(d) == pytest.approx(math.sqrt(2) * stats.chi.ppf(0.25, d), rel=1e-12)
    assert nearest_distance_quartile(2) == pytest.approx(2 * math.sqrt(math.log(4 / 3)), rel=1e-12)
    vol = integrate.quad(lambda r: 4 * math.pi * 2 * (1 - math.cos(r)), 0, math.pi)[0]
    assert attitude_volume("3d") == pytest.approx(vol, rel=1e-12)
    assert attitude_volume("2d") == 2 * math.pi


def test_gospa_of_3d_tables_by_hand():
    """The z column enters the distance when both tables have one: d = |(1, 2, 2)| = 3."""
    truth = {"id": [1], "t": [0.0], "x": [0.0], "y": [0.0], "z": [0.0]}
    tracks = {"track": [4], "t": [0.0], "x": [1.0], "y": [2.0], "z": [2.0]}
    assert lgekf.gospa(tracks, truth, c=5).distance.tolist() == [3.0]
    flat = {"track": [4], "t": [0.0], "x": [1.0], "y": [2.0]}
    assert lgekf.gospa(flat, truth, c=5).distance.tolist() == [pytest.approx(math.sqrt(5))]


GOOD3 = "t,x,y,z\n0,0,0,100\n0.2,1,0,100.2\n0.4,2,0.1,100.4\n0.6,3,0.1,100.7\n"
BAD = {
    "planar_model_on_3d": (GOOD3, ["--model", "se2r3"], "--model se2r3: a model of the plane, and the input has 3-D positions"),
    "3d_model_on_planar": ("t,x,y\n0,0,0\n1,1,0\n", ["--model", "cv3"], "--model cv3: a model of 3-D space, and the input has 2-D"),
    "imm_on_3d": (GOOD3, ["--model", "imm"], "--multi --model imm: the multi-target IMM runs in the plane only"),
    "position3_on_planar": ("t,x,y\n0,0,0\n1,1,0\n", ["--measure", "position3"], "--measure position3: observes 3-D space"),
    "pose3_on_ct3": (GOOD3, ["--model", "ct3", "--measure", "pose"], "the ct3 model has no attitude to measure"),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_multi_3d_input_is_one_line_and_exit_2(tmp_path, capsys, case):
    text, args, msg = BAD[case]
    assert msg in track_error_line(tmp_path, capsys, text, ["--multi", *args])


def test_bank_gate_of_a_pose3_detection_is_the_filter_nis():
    """The multi-target bank's d² = eᵀS⁻¹e of a pose3 detection (R = diag(r_p² I₃, r_a² I₃) from the two stds, by
    ``noise_inputs``) equals the NIS of the single-object se3r6 filter's update from the same state (the class API:
    an independent code path)."""
    from lgekf.estimators.multitarget.bank import ModelBank

    rng = np.random.default_rng(0)
    x0 = np.array([1, 2, 3, 0.2, -0.1, 0.7, 5, 0.3, -0.2, 0.1, 0.2, -0.1])
    A = rng.standard_normal((12, 12))
    P0 = 0.01 * (A @ A.T) + 0.01 * np.eye(12)
    z = np.array([1.3, 2.2, 2.9, 0.25, -0.05, 0.75])
    f = lgekf.make_filter("se3r6", dt=0.1, accel_std=(0.5, 1.0), meas_std=(0.3, 0.1), x0=x0, P0=P0, measurement="pose3")
    f.update(z)
    bank = ModelBank("se3r6", "pose3", (0.5, 1.0), (0.3, 0.1), capacity=2)
    bank.add(x0[None], P0[None])
    bank.gate(z[None], 100.0)
    np.testing.assert_allclose(np.diag(bank.R), [0.09] * 3 + [0.01] * 3)
    assert bank.d2[0, 0] == pytest.approx(f.nis, rel=1e-12)
