"""Camera.geographic (issue 20): a camera placed by latitude, longitude and height. Attached to the
bound Camera class by refracta/__init__.py; refracta.geo (and so pyproj) loads on its first call."""

from __future__ import annotations

import math

from refracta._checks import no_unknown_keywords
from refracta._core import Camera

# Where width= or height= is meant as the image's size (height is the eye's here).
IMAGE_SIZE_HINT = "; the image's size is image_width= and image_height= (height is the eye's)"


def geographic_camera(
    lat,
    lon,
    height,
    azimuth=None,
    elevation=None,
    *,
    target=None,
    vfov=None,
    focal_length_mm=None,
    sensor_mm=None,
    image_width=None,
    image_height=None,
    roll=0.0,
    earth_radius=None,
    **unknown,
) -> Camera:
    """A camera at latitude ``lat``, longitude ``lon`` [deg], ``height`` [m] above the WGS84
    ellipsoid (the eye's height: the ground's height plus the eye above it), looking at ``azimuth``
    [deg clockwise from north] and ``elevation`` [deg above the horizontal] -- or, instead of those
    two, at ``target`` = (lat, lon[, height above the ellipsoid, default 0]): its bearing and its
    elevation with no air (``LocalFrame.aim``; refraction then lifts it a little above the centre).

    It sits at the origin of ``refracta.geo.LocalFrame(lat, lon, earth_radius=R)``, at scene
    position (0, R ln(1 + height / R), 0): build the rest of the scene with that frame
    (``to_scene``) and give the same R to CurvedEarth. earth_radius: R [m] (or a CurvedEarth, or
    math.inf for a flat-Earth scene); None: the ellipsoid's radius of curvature along
    ``azimuth``, ``geo.radius_of_curvature(lat, azimuth)`` (issue 20's convention for a
    geographic scene).

    Give exactly one of vfov [deg] (the vertical field of view) or focal_length_mm with sensor_mm
    = (width, height) [mm] (Camera.photographic's lens and sensor; None: its full-frame default).
    image_width, image_height [pixels]: the image's size (None: the bound constructor's default;
    named so as not to clash with the eye's height). roll [deg]: the camera turned clockwise about
    its view direction as seen from behind (the image's right side dips), 0 level. For a camera
    elsewhere in an existing frame use ``LocalFrame.camera``. Example::

        R = refracta.geo.radius_of_curvature(47.0, 120.0)
        camera = refracta.Camera.geographic(47.0, 8.0, 450.0, 120.0, 0.0, focal_length_mm=300.0,
                                            image_width=960, image_height=640, earth_radius=R)
        air = refracta.CurvedEarth(refracta.PhysicalAtmosphere(), radius=R)
    """
    from refracta import geo  # here: pyproj loads on first use, not with refracta

    no_unknown_keywords("Camera.geographic", unknown, geographic_camera, IMAGE_SIZE_HINT)

    if target is None and (azimuth is None or elevation is None):
        raise ValueError("Camera.geographic: give azimuth and elevation [deg], or target=(lat, lon[, height])")
    if earth_radius is None:  # azimuth checked first: an array of them made an array of radii
        along = azimuth
        if target is not None and azimuth is None:  # along the geodesic to the target
            along = geo.LocalFrame(lat, lon, earth_radius=math.inf).aim(target, height)[0]
        earth_radius = geo.radius_of_curvature(geo._number(lat, "lat"), geo._number(along, "azimuth"))
    frame = geo.LocalFrame(lat, lon, earth_radius=earth_radius)
    return frame.camera(
        height,
        azimuth,
        elevation,
        target=target,
        vfov=vfov,
        focal_length_mm=focal_length_mm,
        sensor_mm=sensor_mm,
        image_width=image_width,
        image_height=image_height,
        roll=roll,
    )
