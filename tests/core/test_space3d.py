"""Models of 3-D space from their definitions: the space mechanism (derive/space.py) in the registry, measurements
that fit by space, the common coordinates and the Euler-angle convention, the filters' defaults.

The filters themselves (predict/update against a dense numpy LG-EKF from the definition, batch = class, NEES/NIS on
their own motion) are in test_registry_battery.py, which runs over every space.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import lgekf
from lgekf.core.registry import (ALL_MODELS, DEFAULT_SPACE, MODELS, SPACES, base_measurement, dispatch_module, get_model,
                                 imm_module, models_of)
from lgekf.generated import dispatch, imm

THREE = models_of("3d")


def test_the_registry_knows_both_spaces_and_keeps_the_commands_in_the_plane():
    assert DEFAULT_SPACE == "2d" and SPACES["2d"]["dim"] == 2 and SPACES["3d"]["dim"] == 3
    assert set(THREE) == {"se3r6", "se3se3", "ct3", "cv3"}
    assert not set(THREE) & set(MODELS)  # the planar commands (track, sweep, evaluate) offer the plane's models
    assert set(ALL_MODELS) == set(MODELS) | set(THREE)
    assert base_measurement("3d") == "position3" and base_measurement("2d") == "position"
    assert len(SPACES["3d"]["common_names"]) == 12


@pytest.mark.parametrize("name", sorted(THREE))
def test_planar_measurements_are_refused_with_the_reason(name):
    spec = get_model(name)
    assert "position3" in spec.measurements and set(spec.measurements) <= {"position3", "pose3"}
    if "pose3" not in spec.measurements:  # no attitude to measure
        assert "no attitude" in spec.refused["pose3"]
    for meas in ("position", "pose"):
        assert "3-D space" in spec.refused[meas]
        with pytest.raises(ValueError, match="3-D space"):
            lgekf.make_filter(name, dt=0.1, accel_std=spec.default_accel_std, meas_std=0.3, x0=np.ones(spec.n),
                              P0=np.eye(spec.n), measurement=meas)
    for planar in MODELS.values():
        assert "position3" in planar.refused


def test_each_space_has_its_imm_loop_and_the_monitor_serves_both_spaces():
    """The IMM's generated loop is emitted per space that declares it (derive.space.Space.mixes): the planar dispatch
    holds the plane's models only (the 3-D models do not compile into it), the 3-D loop the 3-D models and
    measurements. The divergence monitor serves every space that declares it (``Space.monitored``, its two-point
    restart generic over the space): every model has its ``recover_<meas>``."""
    assert not set(dispatch.MODEL_NAMES) & set(THREE) and set(dispatch.MODEL_NAMES) == set(MODELS)
    assert "position3" not in imm.MEASUREMENT_NAMES
    assert SPACES["3d"]["mixes"] and (SPACES["2d"]["imm_module"], SPACES["2d"]["dispatch_module"]) == ("imm", "dispatch")
    assert set(dispatch_module("3d").MODEL_NAMES) == set(THREE)
    assert set(imm_module("3d").MEASUREMENT_NAMES) == {"position3", "pose3"}
    assert imm_module("3d").NC == 12 and list(imm_module("3d").IS_ANGLE.nonzero()[0]) == [3, 4, 5]
    assert SPACES["3d"]["monitored"] and SPACES["2d"]["monitored"]
    for name, spec in ALL_MODELS.items():
        assert all(hasattr(spec.kernels, f"recover_{m}") for m in spec.measurements), name


def _common(rng):
    return np.concatenate([rng.normal(size=3) * 5, [rng.uniform(-3, 3), rng.uniform(-1.4, 1.4), rng.uniform(-3, 3)],
                           [1 + 2 * rng.random(), 0.4 * rng.normal(), 0.4 * rng.normal()], rng.uniform(-1, 1, size=3)])


def test_euler_convention_is_z_y_x_as_scipy_states_it():
    """se3r6 carries R = R_z(yaw) R_y(pitch) R_x(roll) (body to world): scipy's intrinsic "ZYX" Euler angles."""
    k = get_model("se3r6").kernels
    rng = np.random.default_rng(3)
    for _ in range(20):
        c = _common(rng)
        s = k.state_from_physical(lgekf.state_from_common("se3r6", c))
        R = Rotation.from_euler("ZYX", [c[5], c[4], c[3]]).as_matrix()
        np.testing.assert_allclose(s[3:12].reshape(3, 3), R, atol=1e-14)
        np.testing.assert_allclose(k.state_to_physical(s), lgekf.state_from_common("se3r6", c), atol=1e-12)


def _world_velocity(c):
    return Rotation.from_euler("ZYX", [c[5], c[4], c[3]]).as_matrix() @ c[6:9]


@pytest.mark.parametrize("name", sorted(THREE))
def test_common_coordinates_round_trip(name):
    """physical_to_common(state_from_common(c)): se3r6 and se3se3 (whose state is c) give c back; the others keep what they carry: the position
    and the world velocity (CV3), and CT3's course, horizontal and vertical speed."""
    k = get_model(name).kernels
    rng = np.random.default_rng(11)
    for _ in range(20):
        c = _common(rng)
        x = lgekf.state_from_common(name, c)
        back = np.asarray(k.physical_to_common(x))
        np.testing.assert_allclose(back[:3], c[:3], atol=1e-12)
        w, wb = _world_velocity(c), _world_velocity(back)
        if name in ("se3r6", "se3se3"):
            np.testing.assert_allclose(back, c, atol=1e-12)
        else:
            np.testing.assert_allclose(wb, w, atol=1e-12)  # a model without attitude: velocity along its x axis
            assert abs(back[3]) < 1e-15 and np.allclose(back[7:9], 0, atol=1e-15)
        if name == "ct3":
            world_rate = Rotation.from_euler("ZYX", [c[5], c[4], c[3]]).as_matrix() @ c[9:]
            assert x[5] == pytest.approx(world_rate[2], abs=1e-12)  # ω: the world yaw rate


@pytest.mark.parametrize("name", sorted(THREE))
def test_a_3d_filter_defaults_to_the_3d_position_and_tracks_a_line(name):
    spec = get_model(name)
    c0 = np.zeros(12)
    c0[6] = 2.0  # 2 m/s along x, level
    x0 = lgekf.state_from_common(name, c0)
    P0 = lgekf.covariance_from_common(name, c0, np.diag([1.0] * 3 + [0.1] * 3 + [1.0] * 3 + [0.1] * 3)) + 1e-9 * np.eye(spec.n)
    f = lgekf.make_filter(name, dt=0.1, accel_std=spec.default_accel_std, meas_std=0.2, x0=x0, P0=P0)
    assert f.measurement == "position3"
    rng = np.random.default_rng(0)
    for k in range(1, 60):
        f.predict()
        f.update(np.array([2.0 * 0.1 * k, 0.0, 0.0]) + 0.2 * rng.normal(size=3))
    assert abs(f.x[0] - 2.0 * 0.1 * 59) < 0.5 and abs(f.x[1]) < 0.5 and abs(f.x[2]) < 0.5
    assert np.all(np.linalg.eigvalsh(f.P) > 0)
