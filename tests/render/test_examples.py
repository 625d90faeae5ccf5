"""The example scenes (refracta.examples): each builds and renders, and the hot road's mirage
shows the sky below the horizon."""

import numpy as np
import pytest

import refracta
from refracta import examples

WIDTH, HEIGHT = 48, 16


@pytest.mark.parametrize("name", sorted(examples.EXAMPLES))
def test_each_example_renders_finite_and_lit_through_its_field(name):
    example = examples.EXAMPLES[name](WIDTH, HEIGHT)
    assert example.name == name and example.description
    for transport in ("direct", "path"):
        image = refracta.render(example.scene, example.camera, example.field, transport=transport, spp=1,
                                max_length=example.max_length, progress=False)
        assert image.shape == (HEIGHT, WIDTH, 3)
        assert np.all(np.isfinite(image)) and image.min() >= 0.0
        assert image.mean() > 0.0  # lit: not black


# The mirage band: rays aimed between the horizon and theta_c = arccos(n(0)/n(h_eye)) below it
# turn above the hot road and end in the sky. Its radiance must exceed the road's own: the road
# (albedo 0.05) returns 0.05 E / pi of the sun and sky irradiance E, the sky near the horizon
# about 3x more (a property of the scene's physical sky, not a tuned number).
MIRAGE_OVER_ROAD = 1.5  # the mirage band at least 1.5x the road's mean luminance (measured ~3.5x)


def luminance(rgb):
    return rgb @ np.array([0.2126, 0.7152, 0.0722])


def test_hot_road_mirage_band_is_brighter_than_the_road():
    example = examples.hot_road(160, 60)
    camera, field = example.camera, example.field
    image = refracta.render(example.scene, camera, field, spp=4, max_length=example.max_length, progress=False)
    horizon = camera.project([1e6, camera.position[1], 0.0])[1]
    # The critical angle of the field: n(0) cos 0 = n(h_eye) cos theta_c (the ray grazes the road).
    n0, n_eye = field.ior(np.array([[0.0, 0.0, 0.0], [0.0, camera.position[1], 0.0]]))
    theta_c = np.degrees(np.arccos(n0 / n_eye))
    rows_per_degree = camera.height / camera.vfov
    band = slice(int(np.ceil(horizon)) + 1, int(np.floor(horizon + 0.8 * theta_c * rows_per_degree)))
    road = slice(int(np.ceil(horizon + 1.5 * theta_c * rows_per_degree)), camera.height)
    assert band.stop - band.start >= 3 and road.stop - road.start >= 10
    # Columns where nothing stands in the band (the open road between the cars and posts).
    open_columns = [c for c in range(camera.width)
                    if all(camera.pick(example.scene, c + 0.5, v + 0.5) is None or
                           abs(camera.pick(example.scene, c + 0.5, v + 0.5)[1]) < 1e-3
                           for v in range(band.start - 6, band.stop))]
    assert len(open_columns) > camera.width // 4
    mirage = luminance(image[band, open_columns]).mean()
    ground = luminance(image[road, open_columns]).mean()
    assert mirage > MIRAGE_OVER_ROAD * ground, (mirage, ground)
    # Without refraction the same rows show the far road itself: no band. Its radiance is then the
    # road's plus the haze of up to a few km of air (aerial perspective), well below the sky the
    # mirage shows.
    straight = refracta.render(example.scene, camera, None, spp=4, progress=False)
    assert luminance(straight[band, open_columns]).mean() < mirage / MIRAGE_OVER_ROAD
