"""Astronomical refraction: how much higher than it is a star (or the sun) appears through the
air over a spherical Earth -- the ray from the eye traced up to the top of the air by the same
stratified tracer that renders (cpp/refracta/rays/astronomical_refraction.h)."""

from __future__ import annotations

import numpy as np

from refracta import _core
from refracta._checks import number, real_array

ARCMIN_PER_RADIAN = 180.0 * 60.0 / np.pi


def astronomical_refraction(
    field: _core.IndexField,
    apparent_elevation_deg,
    eye_height: float | None = None,
    *,
    wavelength: float | None = None,
    top: float | None = None,
    earth_radius: float | None = None,
    tol: float | None = None,
) -> float | np.ndarray:
    """Refraction [arcmin] of a star seen at `apparent_elevation_deg` [deg, in [-90, 90]].

    The star's true elevation is the apparent one less the refraction. `field` is the air with
    true heights (a height-only field: PhysicalAtmosphere, TemperatureProfile, ...; not a
    CurvedEarth -- the Earth's curvature, `earth_radius` [m] (default 6371 km, the mean radius), is
    applied here); the ray is traced from `eye_height` [m] (default 0: the ground) to `top` [m]
    (default: where the field becomes uniform, 86 km for PhysicalAtmosphere, the top of the U.S.
    Standard Atmosphere 1976, or a metre above an eye higher than that: from a spacecraft, a star
    setting through the limb) to within `tol` [m] (default 1e-7). `wavelength` [nm]: the air
    dispersed to that wavelength (refracta.dispersed_field), default the field's own. The defaults
    are C++'s (AstronomicalRefractionOptions): None takes them.

    For the standard atmosphere at 550 nm: 33.0' at the horizon, 9.66' at 5 deg, 0.953' at 45 deg;
    blue (450 nm) is lifted 33" more than red (650 nm) at the horizon.

    Returns a float for a scalar elevation, else an array of the elevations' shape. Raises
    ValueError for an elevation outside [-90, 90] deg, a field that is not height-only, or a ray
    that meets the ground (eye_height 0 and a negative elevation); NumericalError for a ducted ray.
    """
    if not isinstance(field, _core.IndexField):
        raise ValueError(f"field must be an IndexField (got {type(field).__name__})")
    elevations = real_array(apparent_elevation_deg, "apparent elevation")  # not "0", nor True
    if not np.all(np.isfinite(elevations)):
        raise ValueError(f"apparent elevation must be finite (got {apparent_elevation_deg!r})")
    if np.any(np.abs(elevations) > 90.0):
        bad = elevations[np.abs(elevations) > 90.0].ravel()[0]
        raise ValueError(f"apparent elevation must be in [-90, 90] deg (got {bad:g})")
    if wavelength is not None:
        field = _core.dispersed_field(field, number(wavelength, "wavelength"))
    radians = _core._astronomical_refraction(  # numbers, not "5" (float() read it) nor True
        field,
        np.radians(elevations).ravel(),
        None if eye_height is None else number(eye_height, "eye_height"),
        None if top is None else number(top, "top"),
        None if earth_radius is None else number(earth_radius, "earth_radius"),
        None if tol is None else number(tol, "tol"),
    )
    out = radians.reshape(elevations.shape) * ARCMIN_PER_RADIAN
    return float(out) if out.ndim == 0 else out
