"""Latitude/longitude (degrees, WGS84) to a local metric east/north frame and back.

The frame is the local equirectangular projection about an origin (lat0, lon0), with the WGS84 radii
of curvature at the origin (M0 along the meridian, N0 along the prime vertical)::

    x = N0 · cos(lat0) · (lon - lon0)      metres east   (angles in radians; lon - lon0 wrapped to ±180°)
    y = M0 · (lat - lat0)                  metres north

    M0 = a (1 - e²) / (1 - e² sin² lat0)^(3/2),   N0 = a / (1 - e² sin² lat0)^(1/2),
    a = 6378137 m, e² = f (2 - f), f = 1/298.257223563

It is exact at the origin to first order (the local tangent plane) and exactly invertible
(``to_latlon``). Away from the origin the east scale is off by about tan(lat0) · Δnorth / R
(0.016 % per km of north-south offset at 45°, 0.027 % at 60°; east-west offsets cost nothing to first
order) and directions turn by the meridian convergence Δlon · sin(lat0) (1.6e-4 rad per km east at
45°); ``max_scale_error`` measures it for the actual points. Fine for a city; not for areas of
hundreds of km or near the poles.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["WGS84_A", "WGS84_F", "radii", "to_local", "to_local_enu", "to_latlon", "max_scale_error"]

WGS84_A = 6378137.0
WGS84_F = 1.0 / 298.257223563
_E2 = WGS84_F * (2.0 - WGS84_F)
MAX_ABS_LAT0 = 89.9


def radii(lat_deg):
    """Meridional (M) and prime-vertical (N) radii of curvature of WGS84 at ``lat_deg``, in metres."""
    s2 = np.sin(np.radians(lat_deg)) ** 2
    w = 1.0 - _E2 * s2
    return WGS84_A * (1.0 - _E2) / w**1.5, WGS84_A / np.sqrt(w)


def _wrap180(d):
    return (np.asarray(d, dtype=float) + 180.0) % 360.0 - 180.0


def _check_origin(lat0):
    if not abs(lat0) <= MAX_ABS_LAT0:
        raise ValueError(f"origin latitude {lat0}° is too close to a pole for a local east/north frame (|lat| ≤ {MAX_ABS_LAT0}°)")


def to_local(lat, lon, lat0: float, lon0: float):
    """Metres east and north of (lat0, lon0) (see the module docstring).

    Parameters
    ----------
    lat, lon : array_like
        Degrees (WGS84).
    lat0, lon0 : float
        The origin in degrees.

    Returns
    -------
    x, y : ndarray
        Metres east and north.
    """
    _check_origin(lat0)
    M0, N0 = radii(lat0)
    x = N0 * math.cos(math.radians(lat0)) * np.radians(_wrap180(np.asarray(lon, dtype=float) - lon0))
    y = M0 * np.radians(np.asarray(lat, dtype=float) - lat0)
    return x, y


def to_local_enu(lat, lon, alt, lat0: float, lon0: float, alt0: float):
    """Local east-north-up metres of (lat0, lon0, alt0): x, y as ``to_local``, up = alt − alt0 (heights in metres).

    The up axis is the vertical at the origin; a point d metres away lies d²/(2R) below the tangent plane (8 cm at
    1 km, 2 m at 5 km), which this frame, like its x, y, does not correct: the same local-area approximation.

    Returns
    -------
    x, y, z : ndarray
        Metres east, north and up.
    """
    x, y = to_local(lat, lon, lat0, lon0)
    return x, y, np.asarray(alt, dtype=float) - float(alt0)


def to_latlon(x, y, lat0: float, lon0: float):
    """The inverse of ``to_local``: degrees (lon wrapped to [-180, 180)) of metres east/north of the origin.

    Parameters
    ----------
    x, y : array_like
        Metres east and north of the origin.
    lat0, lon0 : float
        The origin in degrees.

    Returns
    -------
    lat, lon : ndarray
        Degrees.
    """
    _check_origin(lat0)
    M0, N0 = radii(lat0)
    lat = lat0 + np.degrees(np.asarray(y, dtype=float) / M0)
    lon = _wrap180(lon0 + np.degrees(np.asarray(x, dtype=float) / (N0 * math.cos(math.radians(lat0)))))
    return lat, lon


def max_scale_error(lat, lat0: float) -> float:
    """The largest relative scale error of the frame at the given latitudes (0.001 = 0.1 %).

    East: N0 cos(lat0) / (N cos(lat)) - 1; north: M0 / M - 1 (the projection's scales relative to the
    ellipsoid's local ones).
    """
    lat = np.asarray(lat, dtype=float)
    if lat.size == 0:
        return 0.0
    M0, N0 = radii(lat0)
    M, N = radii(lat)
    east = N0 * math.cos(math.radians(lat0)) / (N * np.cos(np.radians(lat))) - 1.0
    north = M0 / M - 1.0
    return float(max(np.abs(east).max(), np.abs(north).max()))
