"""A 3-D pose's attitude given as a quaternion qw, qx, qy, qz (Hamilton, scalar first; ``lgekf.io.attitude``): the angles
against scipy's rotations and hand-computed cases, q and −q alike bit for bit, a file of quaternions read and tracked
as the same file of roll, pitch, yaw, and malformed quaternions one error line (exit 2, no output).

The tracking check runs se3r6's filter class with pose3 (its ``predict`` and ``update_pose3`` kernels, which the registry
battery's dense-reference check compiles too; the batch kernel of pose3 is a minute of CPU to compile cold); the CLI
cases fail while reading, before any kernel is compiled."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.spatial.transform import Rotation
from _cli import track_error_line

import lgekf
from lgekf.io.attitude import euler_of_quaternion
from lgekf.io.readers import DataError, read_csv

N, DT = 30, 0.2


def wrapped(a):
    return np.angle(np.exp(1j * np.asarray(a)))


def test_angles_of_hand_computed_quaternions():
    """A rotation by a about x, y or z: q = (cos(a/2), sin(a/2) u) is roll, pitch or yaw a; a quaternion of any length
    is normalised; (0.5, 0.5, 0.5, 0.5) (120° about (1, 1, 1)) maps x → y → z → x: R = [[0,0,1],[1,0,0],[0,1,0]], so
    yaw = atan2(1, 0) = π/2, pitch = atan2(0, 1) = 0, roll = atan2(1, 0) = π/2."""
    a = 0.7
    c, s = math.cos(a / 2), math.sin(a / 2)
    q = np.array([[c, s, 0, 0], [c, 0, s, 0], [c, 0, 0, s], [3 * c, 0, 0, 3 * s], [0.5, 0.5, 0.5, 0.5]])
    want = np.array([[a, 0, 0], [0, a, 0], [0, 0, a], [0, 0, a], [math.pi / 2, 0, math.pi / 2]])
    np.testing.assert_allclose(euler_of_quaternion(q), want, atol=1e-15)


def test_angles_agree_with_scipy_and_minus_q_is_the_same_rotation():
    """Random quaternions (and some near pitch ±90°): roll, pitch, yaw of R(q) = R_z(yaw) R_y(pitch) R_x(roll) against
    scipy's intrinsic "ZYX" angles of ``Rotation.from_quat(q, scalar_first=True)``; −q gives the same numbers exactly."""
    rng = np.random.default_rng(7)
    q = rng.standard_normal((400, 4))
    near = Rotation.from_euler("ZYX", np.column_stack([rng.uniform(-3, 3, 20), np.full(20, math.pi / 2 - 1e-3),
                                                       rng.uniform(-3, 3, 20)])).as_quat(scalar_first=True)
    q = np.vstack([q, near])
    ref = Rotation.from_quat(q, scalar_first=True).as_euler("ZYX")[:, ::-1]  # (roll, pitch, yaw)
    e = euler_of_quaternion(q)
    assert np.max(np.abs(wrapped(e - ref))) < 1e-11
    assert np.array_equal(euler_of_quaternion(-q), e)


@pytest.fixture(scope="module")
def pose_files(tmp_path_factory):
    """One climbing, rolled turn as two files: t, x, y, z with roll, pitch, yaw, and with a quaternion (every third
    row's sign flipped, every row scaled by 1.7: not unit)."""
    d = tmp_path_factory.mktemp("quat")
    rng = np.random.default_rng(3)
    t = 100.0 + DT * np.arange(N)
    ph = 0.2 * (t - t[0])
    z = np.column_stack([40 * np.sin(ph), 40 * (1 - np.cos(ph)), 300 + 1.5 * (t - t[0])]) + 0.5 * rng.standard_normal((N, 3))
    R = (Rotation.from_euler("ZYX", np.column_stack([ph, np.full(N, -0.18), np.full(N, 0.3)]))
         * Rotation.from_rotvec(0.02 * rng.standard_normal((N, 3))))
    rpy = R.as_euler("ZYX")[:, ::-1]
    q = R.as_quat(scalar_first=True)
    q[::3] *= -1
    q *= 1.7
    a, b = d / "rpy.csv", d / "quat.csv"
    np.savetxt(a, np.column_stack([t, z, rpy]), delimiter=",", header="t,x,y,z,roll,pitch,yaw", comments="", fmt="%.17g")
    np.savetxt(b, np.column_stack([t, z, q]), delimiter=",", header="t,x,y,z,qw,qx,qy,qz",
               comments="", fmt="%.17g")
    return a, b, rpy


def test_a_quaternion_file_reads_as_its_angles(pose_files):
    a, b, rpy = pose_files
    ma, mb = read_csv(a, use_heading=True), read_csv(b, use_heading=True)
    assert mb.quaternion and not ma.quaternion
    np.testing.assert_array_equal(ma.z, mb.z)
    assert mb.heading.shape == (N, 3)
    assert np.max(np.abs(wrapped(mb.heading - ma.heading))) < 1e-12
    assert np.max(np.abs(wrapped(mb.heading - rpy))) < 1e-12


def test_the_same_track_from_angles_and_from_quaternions(pose_files):
    """se3r6 with pose3 measurements (the filter class, ``predict`` / ``update``) on both files: the same estimates to
    1e-9."""
    a, b, _ = pose_files
    est = []
    for f in (a, b):
        m = read_csv(f, use_heading=True)
        z = np.column_stack([m.z, m.heading])
        x0 = np.zeros(12)
        x0[:6] = z[0]
        x0[6] = 8.0
        filt = lgekf.make_filter("se3r6", dt=DT, accel_std=(0.5, 0.5), meas_std=(0.5, 0.05), x0=x0, P0=np.eye(12),
                                 measurement="pose3")
        rows = []
        for zk in z[1:]:
            filt.predict()
            filt.update(zk)
            rows.append(np.array(filt.x))
        est.append(np.array(rows))
    assert np.isfinite(est[0]).all()
    d = est[0] - est[1]
    d[:, 3:6] = wrapped(d[:, 3:6])
    assert np.max(np.abs(d)) < 1e-9
    assert np.max(np.abs(est[0][-5:, :3] - z[-5:, :3])) < 2.0  # a track, not a no-op


HEAD = "t,x,y,z,qw,qx,qy,qz\n"
ROWS = "0,0,0,100,1,0,0,0\n0.2,1,0,100.2,0.9,0.1,0,0\n0.4,2,0.1,100.4,1,0,0,0\n"
BAD = {
    "zero_quaternion": (HEAD + ROWS + "0.6,3,0.1,100.7,0,0,0,0\n", [], "line 5: the quaternion (qw, qx, qy, qz) = (0, 0, 0, 0) has norm 0"),
    "nan_in_qx": (HEAD + ROWS.replace("0.9,0.1", "0.9,nan"), [], "line 3: column 'qx' is nan"),
    "missing_qz": (HEAD.replace(",qz", "") + "0,0,0,100,1,0,0\n0.2,1,0,100,1,0,0\n", [], "missing 'qz'"),
    "both_kinds": (HEAD.replace("\n", ",roll,pitch,yaw\n") + "0,0,0,100,1,0,0,0,0,0,0\n0.2,1,0,100,1,0,0,0,0,0,0\n", [],
                   "the attitude is given twice"),
    "degrees": (HEAD + ROWS, ["--heading-unit", "deg"], "--heading-unit deg: the attitude is a quaternion"),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_malformed_quaternions_are_one_line_and_exit_2(tmp_path, capsys, case):
    text, args, msg = BAD[case]
    assert msg in track_error_line(tmp_path, capsys, text, ["--measure", "pose", *args])


def test_reader_refuses_a_zero_quaternion_naming_its_line(tmp_path):
    f = tmp_path / "z.csv"
    f.write_text(HEAD + "0,0,0,0,1e-9,0,0,0\n1,1,0,0,1,0,0,0\n")
    with pytest.raises(DataError, match="line 2: the quaternion"):
        read_csv(f, use_heading=True)
