"""What a new user's run through the README and the docstrings found (December 2026): each test
fails on the code or the text before the fix."""

import warnings

import numpy as np
import pytest

import refracta
from refracta import spectrum


def test_a_bad_choice_does_not_hide_the_other_bad_options():
    # validate() lists every problem; a refused choice used to raise alone, before it ran.
    with pytest.raises(ValueError) as error:
        refracta.RenderOptions(spp=0, transport="paths")
    message = str(error.value)
    assert message.startswith("RenderOptions: ")
    assert "transport must be 'direct' or 'path'" in message and "spp must be >= 1" in message


def test_keywords_of_a_render_name_every_problem_once():
    scene = refracta.Scene()
    camera = refracta.Camera((0, 1, 0), (1, 1, 0), width=4, height=4)
    with pytest.raises(ValueError) as error:
        refracta.render(scene, camera, None, spp=0, transport="paths", method="straight")
    message = str(error.value)
    assert "transport must be" in message and "spp must be >= 1" in message
    assert "RenderOptions: " not in message  # the owner is named once, at the start


def test_an_unknown_option_alone_keeps_its_message():
    with pytest.raises(ValueError, match=r"^RenderOptions: unknown option 'bogus' \(options: adaptive, "):
        refracta.RenderOptions(bogus=1)


def test_the_fog_warning_without_multiple_scattering_names_single_scattering():
    with pytest.warns(UserWarning) as caught:
        spectrum.PhysicalSky((0, 1, 0), visibility=0.5, multiple_scattering=False)
    message = " ".join(str(w.message) for w in caught)
    assert "single scattering alone" in message and "table" not in message
    with pytest.warns(UserWarning, match="multiple-scattering table does not resolve"):
        spectrum.PhysicalSky((0, 1, 0), visibility=0.5)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        spectrum.PhysicalSky((0, 1, 0), visibility=20.0, multiple_scattering=False)


def test_rgb_radiances_are_per_nanometre_as_their_docstrings_say():
    # Linear sRGB of XYZ / integral ybar: for the sun's smooth spectrum G is close to its spectral
    # radiance near 555 nm (the helper's trial: 21 359 against 22 332 at 550 nm), not ~107x that.
    sky = spectrum.PhysicalSky((0, 1, 0))
    ratio = sky.sun_radiance_rgb()[1] / sky.sun_radiance(550.0)
    assert 0.8 < ratio < 1.2  # a smooth spectrum's luminance-weighted mean within 20 % of its 550 nm value
    assert "[W/(m^2 sr nm)]" in type(sky).sun_radiance_rgb.__doc__
    assert "[W/(m^2 sr nm)]" in type(sky).rgb_radiance.__doc__


def test_cloudy_white_balance_is_as_close_to_none_as_documented():
    image = np.full((4, 4, 3), 0.3)
    white = refracta.io.white_balance_of(image, "cloudy") @ np.ones(3)
    assert np.max(np.abs(white - 1.0)) < 9e-4  # the docstring's "within 0.09 %"
    assert "0.09 %" in refracta.io.__doc__
