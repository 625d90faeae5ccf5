"""Make README's "A real place" figures: ``python3 notebooks/real_place_readme.py [FOLDER]``.

Renders refracta.examples.real_place at 640 x 320 with its readouts, prints the summit's readouts
and refraction_coefficient's k (the figures quoted in the README), writes
notebooks/images/real_place.png; then a stand-in for a photograph (a render, NOT a photograph: the
camera turned 0.1 deg left and 0.04 deg up, and a cool marine layer instead of the standard
atmosphere) at 320 x 160, notebooks/images/real_place_photo.png, and the standard-atmosphere
render's edges and skyline drawn on it, notebooks/images/real_place_overlay.png. FOLDER (default
notebooks/images, the README's own figures) takes the three images instead.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np
from PIL import Image

import refracta
from refracta import examples, geo, photo

IMAGES = Path(__file__).resolve().parent / "images"
READOUTS = ["distance", "object_id", "geographic", "true_elevation", "apparent_elevation", "hidden_height"]
# The photograph's stand-in: the sea 4 K cooler than the air above, the deficit e-folding over
# 60 m (a marine layer: k larger than the standard atmosphere's, the island looms).
MARINE_LAYER = dict(surface_dt=-4.0, surface_depth=60.0)
PHOTO_TURN = (0.10, 0.04)  # [deg] the stand-in camera's azimuth and elevation offsets (left, up)


def save(path: Path, display: np.ndarray) -> None:
    Image.fromarray((np.clip(display, 0.0, 1.0) * 255.0 + 0.5).astype(np.uint8)).save(path, optimize=True)


def summit_pixel(aovs) -> tuple[int, int]:
    """The pixel whose hit lies nearest Teide's summit (geodesic distance on the ellipsoid)."""
    lat, lon, _ = examples.REAL_PLACE_SUMMITS["Teide"]
    g = aovs["geographic"]
    hit = np.isfinite(aovs["distance"])
    d, _, _ = geo.inverse(np.where(hit, g[..., 0], 0.0), np.where(hit, g[..., 1], 0.0), lat, lon)
    row, col = np.unravel_index(np.argmin(np.where(hit, d, np.inf)), hit.shape)
    return int(row), int(col)


def main(images: Path = IMAGES) -> None:
    images.mkdir(parents=True, exist_ok=True)
    example = examples.real_place(640, 320)
    settings = dict(transport="direct", spp=1, denoise=True, max_length=example.max_length, progress=False)
    start = time.perf_counter()
    image = refracta.render(example.scene, example.camera, example.field, **settings)
    print(f"real_place 640x320 (no readouts): {time.perf_counter() - start:.1f} s")
    save(images / "real_place.png", refracta.io.to_display(image))

    small = examples.real_place(320, 160)
    start = time.perf_counter()
    render, aovs = refracta.render(small.scene, small.camera, small.field, aovs=READOUTS, frame=small.frame, **settings)
    print(f"real_place 320x160 with readouts: {time.perf_counter() - start:.1f} s")
    row, col = summit_pixel(aovs)
    lat, lon, height = aovs["geographic"][row, col]
    s_lat, s_lon, s_height = examples.REAL_PLACE_SUMMITS["Teide"]
    geodesic, azimuth, _ = geo.inverse(*examples.REAL_PLACE_OBSERVER, s_lat, s_lon)
    print(f"summit pixel (col {col}, row {row}): hit {lat:.5f} N {lon:.5f} E, {height:.0f} m")
    print(f"  distance readout {aovs['distance'][row, col]:.0f} m; geodesic to the summit {geodesic:.0f} m")
    print(
        f"  true elevation {aovs['true_elevation'][row, col]:.3f} deg; "
        f"apparent {aovs['apparent_elevation'][row, col]:.3f} deg"
    )
    print(
        f"  hidden height: geometric {aovs['hidden_height'][row, col, 0]:.0f} m, "
        f"refracted {aovs['hidden_height'][row, col, 1]:.0f} m"
    )
    k = refracta.refraction_coefficient(small.field, examples.REAL_PLACE_EYE, geodesic, target_height=s_height)
    print(f"  refraction_coefficient: {k}")

    # The photograph's stand-in: another camera and another air, rendered (not photographed).
    marine = examples.real_place(320, 160, field=refracta.PhysicalAtmosphere(**MARINE_LAYER))
    camera = marine.frame.camera(
        examples.REAL_PLACE_EYE,
        (azimuth - PHOTO_TURN[0]) % 360.0,
        examples.REAL_PLACE_TILT + PHOTO_TURN[1],
        focal_length_mm=examples.REAL_PLACE_FOCAL_LENGTH,
        image_width=320,
        image_height=160,
    )
    stand_in = refracta.render(marine.scene, camera, marine.field, **settings)
    k_marine = refracta.refraction_coefficient(marine.field, examples.REAL_PLACE_EYE, geodesic)
    print(f"stand-in's air: k = {k_marine.k:.3f}")
    save(images / "real_place_photo.png", refracta.io.to_display(stand_in))
    picture = photo.load(images / "real_place_photo.png")
    result = photo.overlay(picture, (render, aovs), mode="edges")
    save(images / "real_place_overlay.png", result.image)
    columns = result.skyline >= 0
    print(f"overlay: skyline drawn in {columns.sum()} of {columns.size} columns")


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else IMAGES)
