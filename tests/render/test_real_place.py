"""examples.real_place (issue 20's README scene): Teide from Agaete across ~93 km, terrain from the
shipped synthetic GeoTIFF placed by geo.LocalFrame. A narrow view of the summit rendered with
readouts checks the scene's physics against refracta.geo and refraction_coefficient."""

import numpy as np
import pytest

import refracta
from refracta import examples, geo, terrain

SIZE = 12  # [px] a square view around the summit
VFOV = 0.1  # [deg]: pixels of 0.0083 deg, ~14 m across at 93 km
SUMMIT_ELEVATION = 1.9  # [deg] where the view looks: the summit's apparent elevation is ~1.90 deg


def test_shipped_elevation_file_holds_the_published_summits():
    grid = terrain.read_elevation(examples.real_place_elevation_path())
    assert grid.epsg == 4326 and grid.heights.shape == (257, 345)
    for lat, lon, height in examples.REAL_PLACE_SUMMITS.values():
        row, col = round((grid.y0 - lat) / grid.dy), round((lon - grid.x0) / grid.dx)
        assert grid.heights[row, col] == height  # the generator sets the summits exactly (whole metres)
    assert grid.heights.max() == examples.REAL_PLACE_SUMMITS["Teide"][2]


@pytest.mark.slow  # ~5 s: the scene (the GeoTIFF through pyproj) and 144 curved rays of 93 km with readouts
def test_summit_readouts_agree_with_geodesy_and_refraction_coefficient():
    example = examples.real_place(8, 8)
    lat0, lon0 = examples.REAL_PLACE_OBSERVER
    s_lat, s_lon, _ = examples.REAL_PLACE_SUMMITS["Teide"]
    _, azimuth, _ = geo.inverse(lat0, lon0, s_lat, s_lon)
    eye = examples.REAL_PLACE_EYE
    camera = example.frame.camera(
        eye, azimuth % 360.0, SUMMIT_ELEVATION, vfov=VFOV, image_width=SIZE, image_height=SIZE
    )
    _, aovs = refracta.render(
        example.scene,
        camera,
        example.field,
        transport="direct",
        spp=1,
        max_length=example.max_length,
        progress=False,
        aovs=["distance", "geographic", "true_elevation", "apparent_elevation", "hidden_height"],
        frame=example.frame,
    )
    distance, g = aovs["distance"], aovs["geographic"]
    hit = np.isfinite(distance)
    assert hit.any() and not hit.all()  # the summit against the sky
    # The pixel whose hit lies nearest the summit: within one pixel's footprint of it (the largest
    # separation between neighbouring pixels' hits), and the summit's true height within that.
    apart, _, _ = geo.inverse(np.where(hit, g[..., 0], 0.0), np.where(hit, g[..., 1], 0.0), s_lat, s_lon)
    apart = np.where(hit, apart, np.inf)
    r, c = np.unravel_index(np.argmin(apart), hit.shape)
    neighbours = [(r + dr, c + dc) for dr, dc in ((-1, 0), (1, 0), (0, -1), (0, 1))]
    neighbours = [(i, j) for i, j in neighbours if 0 <= i < SIZE and 0 <= j < SIZE and hit[i, j]]
    footprint = max(geo.inverse(g[r, c, 0], g[r, c, 1], g[i, j, 0], g[i, j, 1])[0] for i, j in neighbours)
    assert apart[r, c] <= footprint
    # The distance readout is the path's true length: the straight chord between the eye and the
    # hit on the sphere (radius R + h, central angle = geodesic / R). Equal within the pixel's
    # footprint along the line of sight (the readout's step to the neighbours); the curved path is
    # longer than the chord by ~d^3 c^2 / 24 < 1 m. (The flat frame's own length, hypot(ground,
    # flat rise), is 28 m shorter here: lengths there are scaled by R / r.)
    ground, _, _ = geo.inverse(lat0, lon0, g[r, c, 0], g[r, c, 1])
    radius = example.frame.earth_radius
    r0, r1, angle = radius + eye, radius + float(g[r, c, 2]), ground / radius
    chord = np.sqrt(r0**2 + r1**2 - 2.0 * r0 * r1 * np.cos(angle))
    along = max(abs(distance[i, j] - distance[r, c]) for i, j in neighbours)
    assert abs(distance[r, c] - chord) <= along
    # The readouts against refraction_coefficient's exact traces for a target at the hit.
    k = refracta.refraction_coefficient(example.field, eye, ground, target_height=g[r, c, 2])
    assert abs(aovs["true_elevation"][r, c] - k.true_elevation) < 1e-4  # [deg] float32 readout of ~1.84 deg
    assert abs(aovs["apparent_elevation"][r, c] - k.apparent_elevation) < VFOV / SIZE / 2  # within half a pixel
    geometric, refracted = aovs["hidden_height"][r, c]
    assert abs(geometric - k.hidden_height_straight) < 0.05  # [m] float32 readout of ~427 m (measured 1e-4)
    assert abs(refracted - k.hidden_height_refracted) < 0.05  # [m] float32 readout of ~336 m (measured 1e-4)
    assert 0.15 < k.k < 0.19  # the standard atmosphere's k near the sea (~0.17: 503 P/T^2 (0.0343 - 0.0065))
    # The surveyors' formula with that k: hidden = (d - sqrt(2 R' h))^2 / (2 R'), R' = R / (1 - k).
    effective = k.earth_radius / (1.0 - k.k)
    surveyors = (ground - np.sqrt(2.0 * effective * eye)) ** 2 / (2.0 * effective)
    # 1 %: k is the horizontal ray's; the grazing ray dips below it into other air (measured 0.17 %)
    assert refracted == pytest.approx(surveyors, rel=0.01)
    assert geometric > refracted  # the air lifts the island into view
