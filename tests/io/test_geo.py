"""lgekf.io.geo: the local east/north frame of lat/lon input (exact inverse, accuracy as documented)."""

import math

import numpy as np
import pytest

from lgekf.io.geo import max_scale_error, to_latlon, to_local


def _haversine(lat1, lon1, lat2, lon2, R=6371008.8):
    """Great-circle distance on the mean sphere: an independent distance, good to ~0.5 %."""
    p1, p2 = np.radians(lat1), np.radians(lat2)
    dp, dl = p2 - p1, np.radians(lon2 - lon1)
    h = np.sin(dp / 2) ** 2 + np.cos(p1) * np.cos(p2) * np.sin(dl / 2) ** 2
    return 2 * R * np.arcsin(np.sqrt(h))


def test_round_trip_is_exact_to_rounding():
    rng = np.random.default_rng(0)
    lat0, lon0 = 48.137154, 11.575382
    lat = lat0 + rng.uniform(-0.05, 0.05, 1000)
    lon = lon0 + rng.uniform(-0.05, 0.05, 1000)
    x, y = to_local(lat, lon, lat0, lon0)
    la, lo = to_latlon(x, y, lat0, lon0)
    np.testing.assert_allclose(la, lat, rtol=0, atol=1e-12)
    np.testing.assert_allclose(lo, lon, rtol=0, atol=1e-12)


def test_distances_agree_with_great_circle_nearby():
    lat0, lon0 = 52.5, 13.4
    lat, lon = 52.505, 13.41  # about 0.9 km away
    x, y = to_local(lat, lon, lat0, lon0)
    d = _haversine(lat0, lon0, lat, lon)
    assert math.hypot(x, y) == pytest.approx(d, rel=5e-3)  # sphere vs ellipsoid: < 0.5 %


def test_antimeridian_is_continuous():
    x, y = to_local([0.0, 0.0], [-179.999, 179.999], 0.0, 179.9995)
    # 0.002° of longitude apart at the equator (111 319.49 m per degree there), not 40 000 km
    assert x[0] > 0 > x[1] and x[0] - x[1] == pytest.approx(0.002 * 111_319.49, rel=1e-6)
    lat, lon = to_latlon(x, y, 0.0, 179.9995)
    np.testing.assert_allclose(lon, [-179.999, 179.999], atol=1e-9)


def test_documented_scale_error():
    # the module docstring: about tan(lat0) · Δnorth / R, 0.016 % per km at 45° and 0.027 % at 60°
    km_in_deg = 1000.0 / 111_200.0
    assert max_scale_error([45.0 + km_in_deg], 45.0) == pytest.approx(1.6e-4, rel=0.05)
    assert max_scale_error([60.0 + km_in_deg], 60.0) == pytest.approx(2.7e-4, rel=0.05)
    assert max_scale_error([45.0], 45.0) < 1e-15


def test_pole_is_refused():
    with pytest.raises(ValueError, match="too close to a pole"):
        to_local([89.95], [0.0], 89.95, 0.0)
