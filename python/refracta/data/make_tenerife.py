"""Generate tenerife_synthetic.tif, the elevation file of refracta.examples.real_place.

Run from the repository: ``python3 python/refracta/data/make_tenerife.py`` (deterministic: the
same bytes every run). Nothing is downloaded: the heights are SYNTHETIC -- an island shaped after
Tenerife (a shield volcano about 80 x 45 km, its long axis toward azimuth 55 deg; the Las Canadas
caldera floor at ~2100 m with Teide's cone to 3715 m and Pico Viejo's to 3135 m at their real
positions; the Anaga ridge to the north-east, ~1000 m; fractal ridges and gullies from
refracta.examples._fbm) on the real latitudes and longitudes. Summit heights and positions follow
published figures (Teide 28.2724 N 16.6425 W, 3715 m; Pico Viejo 28.2567 N 16.6622 W, 3135 m); the
rest of the relief is invented and is NOT the real topography.

The file: a GeoTIFF of int16 heights [m] above the ellipsoid (the sea at 0, the sea bed below it),
geographic WGS84 (EPSG:4326), pixel-is-point, 0.0025 deg spacing (~245 m east, ~278 m north),
north-up, uncompressed (tifffile reads it without imagecodecs); about 170 KB.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

# The grid: its north-west sample and spacing [deg].
LON0, LAT0 = -16.95, 28.62
STEP = 0.0025
COLUMNS, ROWS = 345, 257
# Summits (name: lat, lon [deg], height [m]) -- published positions and heights.
SUMMITS = {
    "Teide": (28.2724, -16.6425, 3715.0),
    "Pico Viejo": (28.2567, -16.6622, 3135.0),
}
SEED = 20
PATH = Path(__file__).with_name("tenerife_synthetic.tif")


def _smoothstep(t):
    t = np.clip(t, 0.0, 1.0)
    return t * t * (3.0 - 2.0 * t)


def heights() -> np.ndarray:
    """(ROWS, COLUMNS) heights [m]; row 0 the northern edge."""
    from refracta.examples import _fbm

    rng = np.random.default_rng(SEED)
    lat = LAT0 - STEP * np.arange(ROWS)[:, None] + np.zeros((1, COLUMNS))
    lon = LON0 + STEP * np.arange(COLUMNS)[None, :] + np.zeros((ROWS, 1))
    # Local metres about the caldera's centre (an equirectangular map is ample for a synthetic shape).
    lat_c, lon_c = 28.27, -16.62
    east = (lon - lon_c) * 111320.0 * math.cos(math.radians(lat_c))
    north = (lat - lat_c) * 110950.0
    # The island: an ellipse (semi-axes 42 x 20 km) along azimuth 55 deg, its centre 8 km south-west
    # of the caldera, the coast wandering by a few km.
    a = math.radians(55.0)
    along = east * math.sin(a) + north * math.cos(a) + 8000.0
    across = east * math.cos(a) - north * math.sin(a)
    wobble = 0.12 * _fbm(rng, east, north, 9000.0, octaves=4)
    r = np.hypot(along / 42000.0, across / 20000.0) * (1.0 + wobble)
    # A shield rising from the coast (r = 1) to ~2000 m at the caldera rim.
    shield = 2300.0 * np.clip(1.0 - r, 0.0, None) ** 1.3
    shield = np.where(r < 1.0, shield, -80.0 * (r - 1.0) * 30.0)  # the sea bed: ~80 m down per 3 % of r
    # The Anaga ridge: the island's north-eastern arm, a crest ~1000 m.
    anaga = 1100.0 * np.exp(-((across / 3500.0) ** 2)) * _smoothstep((along - 18000.0) / 6000.0)
    anaga *= _smoothstep((44000.0 - along) / 5000.0)
    relief = np.maximum(shield, anaga * (r < 1.08))
    # The caldera: a floor at ~2100 m, 16 x 11 km, under a wall to ~2500 m on its southern side
    # (the northern side lies open, buried by Teide's lavas), blended into the shield.
    d_cal = np.hypot((east - 1500.0) / 8000.0, (north + 1500.0) / 5500.0)
    rim = 2100.0 + 400.0 * _smoothstep((d_cal - 0.7) / 0.3) * _smoothstep(-north / 3000.0)
    relief = np.maximum(relief, rim * (1.0 - _smoothstep((d_cal - 1.0) / 0.8)))
    # Fractal ridges and gullies on the land, stronger on the steep middle slopes.
    land = _smoothstep(relief / 200.0)
    relief = relief + land * (140.0 * _fbm(rng, east, north, 4000.0, octaves=6))
    # The two cones (published summits): Teide steep above the floor, Pico Viejo broad beside it.
    for name, slope_scale in (("Teide", 4200.0), ("Pico Viejo", 3200.0)):
        s_lat, s_lon, top = SUMMITS[name]
        dx = (lon - s_lon) * 111320.0 * math.cos(math.radians(lat_c))
        dy = (lat - s_lat) * 110950.0
        cone = top - (top - 2000.0) * (np.hypot(dx, dy) / slope_scale) ** 0.8
        relief = np.maximum(relief, cone)
    # The summits exactly at their heights (the noise may not add to a cone's tip).
    for s_lat, s_lon, top in SUMMITS.values():
        row, col = round((LAT0 - s_lat) / STEP), round((s_lon - LON0) / STEP)
        relief[row, col] = top
    return np.round(relief).astype(np.int16)


def write(path: Path = PATH) -> None:
    """Write the GeoTIFF: ModelPixelScale, ModelTiepoint and GeoKeys (GeoTIFF 1.1, OGC 19-008r4)."""
    import tifffile

    geokeys = (1, 1, 0, 3, 1024, 0, 1, 2, 1025, 0, 1, 2, 2048, 0, 1, 4326)  # geographic, pixel-is-point, WGS84
    tags = [
        (33550, "d", 3, (STEP, STEP, 0.0), True),
        (33922, "d", 6, (0.0, 0.0, 0.0, LON0, LAT0, 0.0), True),
        (34735, "H", len(geokeys), geokeys, True),
    ]
    tifffile.imwrite(path, heights(), extratags=tags, metadata=None)


if __name__ == "__main__":
    write()
    print(f"wrote {PATH} ({PATH.stat().st_size} bytes)")
