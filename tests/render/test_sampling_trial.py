"""A sampling and denoising trial: refracta.denoise refuses what is not linear radiance, and says
why for any negative image."""

import numpy as np
import pytest

import refracta


@pytest.mark.parametrize("dtype", [np.uint8, np.uint16, np.int32, bool])
def test_denoise_refuses_a_picture_that_is_not_float_radiance(dtype):
    # An 8-bit picture came back as float radiance of 111-143, its display encoding taken as light.
    with pytest.raises(ValueError, match=r"denoise: image must be floats, linear \(got dtype"):
        refracta.denoise(np.ones((8, 8, 3), dtype))


def test_denoise_says_why_an_all_negative_image_is_refused():
    # One negative pixel got the spectral-gamut hint; an all-negative image only "must lie in".
    with pytest.raises(ValueError, match="image must be >= 0 .* outside sRGB's gamut"):
        refracta.denoise(np.full((8, 8, 3), -1.0))
