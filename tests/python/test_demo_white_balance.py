"""The demo's cold sea balanced on its sunlight (cli._demo_white_balance, refracta.io white_balance):
what the sun lights or mirrors -- the glitter -- shows neutral, not the low sun's orange."""

from pathlib import Path

import numpy as np
import pytest

import refracta
from refracta import cli, examples, io

# The glitter is the sun mirrored by sea facets, dimmed and lit along ~10-20 km of air whose
# in-scatter (the horizon sky's colour, warmer than the sun: a longer path) adds a little: measured
# r/g 1.011 and b/g 0.978 of the balanced glitter at 160 x 60, 1 spp (as rendered 1.46 and 0.51);
# 0.05 allows twice that drift.
GLITTER_NEUTRAL = 0.05


@pytest.mark.slow
def test_the_cold_sea_demo_shows_its_glitter_white():
    example = examples.cold_sea(160, 60)
    image = refracta.render(example.scene, example.camera, example.field, max_length=example.max_length, progress=False)
    white = cli._demo_white_balance("cold_sea")
    assert white is not None
    # The sunlight at the ground, from the same physical sky: orange (sun 10 deg high, 80 km visibility).
    assert white[2] / white[1] == pytest.approx(0.52, abs=0.02)  # 0.36 / 0.69 in RGB
    # The glitter: the brightest 1 % of the sea's lower-right quarter (the sun is beyond the right edge).
    sea = image[45:, 80:].reshape(-1, 3).astype(np.float64)
    glitter = sea[sea[:, 1] >= np.quantile(sea[:, 1], 0.99)].mean(axis=0)
    raw = glitter / glitter[1]
    balanced = io.white_balance_of(image, white) @ glitter
    balanced /= balanced[1]
    assert raw[2] < 0.6  # as rendered: the low sun's orange
    np.testing.assert_allclose(balanced, 1.0, atol=GLITTER_NEUTRAL)


def test_the_render_command_takes_a_white_balance(tmp_path, capsys):
    scene_file = Path(__file__).resolve().parents[1] / "data" / "hot_road.toml"
    exr, png = tmp_path / "image.exr", tmp_path / "image.png"
    assert cli.main(["render", str(scene_file), "-o", str(exr), "--size", "24x8"]) == 0
    image = io.read_image(exr)
    for balance, value in (("3200", 3200.0), ("shade", "shade"), ("1,0.7,0.4", (1.0, 0.7, 0.4))):
        assert cli.main(["render", str(scene_file), "-o", str(png), "--size", "24x8", "--white-balance", balance]) == 0
        expected = io.to_display(image, white_balance=value)
        # The PNG holds the render's display with that balance: 8-bit, so within half a level of
        # rounding (plus float32's own rounding of the display values).
        np.testing.assert_allclose(io.read_image(png), expected, atol=0.5 / 255 + 1e-6)
    # A bad one: one line naming white_balance, exit status 1 (cli.main's user errors).
    assert cli.main(["render", str(scene_file), "-o", str(png), "--size", "24x8", "--white-balance", "500"]) == 1
    assert "white_balance must be a colour temperature in [1000, 40000] K (got 500)" in capsys.readouterr().err
