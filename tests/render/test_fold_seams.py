"""The hot road's fold is clean (issue 19 section 5, "is the image clean?").

At the inferior mirage's fold, rays launched a hair below the critical depression dip a few
millimetres under the ground (the air under y = 0 continues the hot layer) and rise again within
one segment of their path. The caster meets the ground on the chord from above, then refines the
hit onto the path's curve; Newton, started near the dip's bottom where the path runs level, slid
onto the rising side and returned a point under the ground heading up: the sand met from below,
its normal turned down, shaded black -- a dark line one pixel high across the whole 640 x 320 demo
at row 168 (luminance ~1 against ~13 above and ~8 below). The exact trace (table=False, or strict
rk45) shows no such line: the path meets the sand where it first crosses it, from above.
"""

import numpy as np
import pytest

import refracta
from refracta import examples

# Luminance of linear Rec.709 / sRGB.
LUMA = np.array([0.2126, 0.7152, 0.0722])
# Crops of the 640 x 320 hot road over the fold (row 168): the sand left and right of the road.
CROPS = {"left": (96, 160, 112, 176), "right": (520, 160, 536, 176)}


@pytest.mark.parametrize("crop", sorted(CROPS))
def test_the_ground_at_the_fold_is_met_from_above(crop: str) -> None:
    example = examples.hot_road()
    image, aovs = refracta.render(
        example.scene,
        example.camera,
        example.field,
        progress=False,
        max_length=example.max_length,
        spp=1,
        pixel_bounds=CROPS[crop],
        aovs=["normal", "object_id"],
    )
    hit = aovs["object_id"] >= 0
    assert hit.any(axis=1).sum() >= 8, "the crop should reach the ground below the fold"
    # Nothing in the crops is seen from below (the exact trace, table=False: no normal with y < 0;
    # the paint's sides read y = 0): the normal AOV faces the arriving path, so the ground met from
    # under it reads (0, -1, 0).
    up = aovs["normal"][..., 1][hit]
    assert (up > -0.5).all(), f"{int((up <= -0.5).sum())} pixels meet a surface from below"
    # No dark row: the fold's rows hold ground and mirrored sky, each at least as bright as the
    # ground itself (Lambertian: lit alike at every grazing angle). Row means of 16 pixels at
    # 1 spp scatter ~10 % from the sky's sampled light: 0.7 of the ground rows' mean leaves room
    # for that and still fails the black line (0.13 of it before the fix).
    luminance = image @ LUMA
    ground_rows = hit.all(axis=1)
    ground = luminance[ground_rows][-4:].mean()
    rows = luminance.mean(axis=1)
    assert (rows >= 0.7 * ground).all(), f"row means {np.round(rows / ground, 2)} of the ground's"
