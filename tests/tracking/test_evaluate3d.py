"""`lgekf evaluate` in 3-D: the kitti3d loader (skipped when ../shared/data or $LGEKF_DATA is absent) against its own
truth, the motion errors against independent computations (scipy's rotations, the cars' own turn rate), the turn
rate of the track output against the models' own rates."""

from __future__ import annotations

import math

import numpy as np
import pytest
from _real_data import DATA, needs
from scipy.spatial.transform import Rotation

from lgekf.apps.evaluate import COURSE_MIN_SPEED, _rotation_angle, filters_of, baseline_of, track_rmse
from lgekf.apps.track import TrackConfig, turn_rates
from lgekf.io.datasets import KITTI_DT, load_dataset


@pytest.fixture(scope="module")
def kitti3d():
    needs("kitti_oxts/0000.txt")
    return load_dataset("kitti3d", root=DATA)


def test_kitti3d_truth_is_consistent(kitti3d):
    """ENU positions from 0 at each first fix; (ve, vn, vu) along their finite differences (speed within 2.5 %, as the
    planar loader's); the attitude in lgekf's convention: yaw = the course and the body velocity along +x when moving."""
    ds = kitti3d
    assert ds.n_tracks == 21 and ds.space == "3d" and ds.p.shape[1] == 3 and ds.v.shape[1] == 3 and ds.attitude.shape[1] == 3
    assert np.all(ds.p[ds.starts[:-1]] == 0.0)
    fds, vs, att = [], [], []
    for a, b in zip(ds.starts[:-1], ds.starts[1:]):
        fds.append((ds.p[a + 2:b] - ds.p[a:b - 2]) / (2 * KITTI_DT))
        vs.append(ds.v[a + 1:b - 1])
        att.append(ds.attitude[a + 1:b - 1])
    fd, v, att = np.concatenate(fds), np.concatenate(vs), np.concatenate(att)
    moving = np.hypot(v[:, 0], v[:, 1]) > 2.0
    fd, v, att = fd[moving], v[moving], att[moving]
    assert np.median(np.linalg.norm(fd, axis=1) / np.linalg.norm(v, axis=1)) == pytest.approx(1.0, abs=0.025)
    assert np.median(np.abs(fd[:, 2] - v[:, 2])) < 0.05  # climb: the altitude's rate is vu
    dyaw = np.angle(np.exp(1j * (att[:, 2] - np.arctan2(v[:, 1], v[:, 0]))))
    assert np.sqrt(np.mean(dyaw ** 2)) < math.radians(5)
    R = Rotation.from_euler("ZYX", att[:, ::-1]).as_matrix()  # scipy's intrinsic ZYX: R_z(yaw) R_y(pitch) R_x(roll)
    body = np.einsum("nji,nj->ni", R, v)  # Rᵀ v
    assert np.median(body[:, 0] / np.linalg.norm(v, axis=1)) > 0.99


def test_motion_errors_of_cv3_against_the_truth(kitti3d):
    """CV3's turn rate is 0, so its turn-rate RMSE per track is the RMS of the truth's wu over the scored rows (rows k ≥ 2
    moving at ≥ 1 m/s); it has no attitude. The 3-D filters and baseline of the space."""
    assert filters_of(kitti3d) == ("ct3", "cv3", "se3r6", "se3se3") and baseline_of("3d") == "cv3"
    ds = kitti3d.subset([0, 7])
    z = ds.p + 0.3 * np.random.default_rng(0).standard_normal(ds.p.shape)
    motion = {}
    out = track_rmse(ds, [z], TrackConfig({"cv3": (2.0,)}, 0.3), models=("cv3",), motion=motion)
    assert set(motion["cv3"]) == {"speed", "course", "climb", "turn_rate"}
    for j, (a, b) in enumerate(zip(ds.starts[:-1], ds.starts[1:])):
        rows = np.arange(a, b)[2:]
        rows = rows[np.hypot(ds.v[rows, 0], ds.v[rows, 1]) >= COURSE_MIN_SPEED]
        assert motion["cv3"]["turn_rate"][0, j] == pytest.approx(np.sqrt(np.mean(ds.w[rows] ** 2)), rel=1e-12)
    assert np.all(out["cv3"][0] < 0.3 * math.sqrt(3))  # better than its measurements


def test_rotation_angle_against_scipy():
    rng = np.random.default_rng(1)
    a = np.column_stack([rng.uniform(-3, 3, 50), rng.uniform(-1.5, 1.5, 50), rng.uniform(-3, 3, 50)])
    b = a + rng.normal(0, 0.7, a.shape)
    ra, rb = Rotation.from_euler("ZYX", a[:, ::-1]), Rotation.from_euler("ZYX", b[:, ::-1])
    np.testing.assert_allclose(_rotation_angle(a, b), (ra.inv() * rb).magnitude(), atol=1e-7)


def test_turn_rate_is_the_models_own_course_rate():
    """CT3 turns its course at ω (a constant-turn model): the central difference of the course along its motion gives
    ω; CV3's course does not turn."""
    rng = np.random.default_rng(2)
    x = np.column_stack([rng.normal(size=(20, 3)) * 10, rng.uniform(-3, 3, 20), rng.uniform(1, 10, 20),
                         rng.uniform(-0.5, 0.5, 20), rng.normal(size=20)])  # x, y, z, psi, v, omega, vz
    np.testing.assert_allclose(turn_rates("ct3", x), x[:, 5], atol=1e-9)
    xc = np.column_stack([rng.normal(size=(20, 3)), rng.normal(size=(20, 3)) * 5])
    np.testing.assert_allclose(turn_rates("cv3", xc), 0.0, atol=1e-9)
