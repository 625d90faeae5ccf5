"""refracta.DisplaySettings: io's display keywords as one bound options class (the RenderOptions
pattern): documented fields, pickling through them, validate() listing every problem, and taken
by write_image/to_display/exposure_of as an object or as its fields by keyword."""

import pickle

import numpy as np
import pytest

import refracta
from refracta import io

FIELDS = (
    "ev100",
    "exposure",
    "f_number",
    "gamma",
    "iso",
    "key",
    "luminous_efficacy",
    "shutter",
    "tonemap",
    "white",
    "white_balance",
)


def test_fields_are_documented_and_pickle():
    assert refracta._options.fields(refracta.DisplaySettings) == FIELDS
    for name in FIELDS:
        assert getattr(refracta.DisplaySettings, name).__doc__, name
    settings = refracta.DisplaySettings(tonemap="reinhard", white=4.0, gamma=2.4, shutter=0.01, f_number=16.0)
    copy = pickle.loads(pickle.dumps(settings))
    assert repr(copy) == repr(settings) and copy.gamma == 2.4 and copy.tonemap == "reinhard"
    assert refracta.DisplaySettings(gamma="linear").gamma == 1.0 and refracta.DisplaySettings().gamma == "srgb"


def test_validate_lists_every_problem():
    settings = refracta.DisplaySettings()  # the keyword constructor validates: set them after
    settings.exposure, settings.key, settings.gamma = -1.0, 0.0, 5.0
    with pytest.raises(ValueError) as error:
        settings.validate()
    for problem in ("exposure must be > 0", "key must be > 0", "gamma must be in [1, 3]"):
        assert problem in str(error.value)
    with pytest.raises(ValueError, match="gamma must be 'srgb', 'linear' or a number"):
        refracta.DisplaySettings(gamma="log")


def test_an_object_and_its_fields_by_keyword_display_alike():
    image = np.random.default_rng(3).random((6, 5, 3)) * 4.0
    settings = refracta.DisplaySettings(tonemap="reinhard", white=2.0, ev100=1.5)
    by_object = io.to_display(image, display=settings)
    by_keywords = io.to_display(image, tonemap="reinhard", white=2.0, ev100=1.5)
    np.testing.assert_array_equal(by_object, by_keywords)  # the same settings, the same pipeline
    # A keyword changes a copy of the object (None: left as it is); the object stays as it was.
    np.testing.assert_array_equal(io.to_display(image, display=settings, white=None), by_object)
    assert not np.array_equal(io.to_display(image, display=settings, gamma="linear"), by_object)
    assert settings.tonemap == "reinhard"
    assert io.exposure_of(image, display=settings) == io.exposure_of(image, ev100=1.5)
    with pytest.raises(ValueError, match="unknown option 'gama'"):
        io.settings(None, gama=2.2)
    with pytest.raises(ValueError, match="options must be a refracta.DisplaySettings"):
        io.to_display(image, display={"exposure": 1.0})


def test_an_image_beyond_float32_is_refused_saying_so(tmp_path):
    # Images cross as float32: 1e300 (finite) became inf with numpy's overflow warning on the way,
    # then was refused as "must be finite (got inf)" (a trial).
    with pytest.raises(ValueError, match=r"write_image: image values must fit float32 .*got 1e\+300"):
        io.write_image(tmp_path / "huge.png", np.full((2, 2, 3), 1e300))
    io.write_image(tmp_path / "fine.exr", np.full((2, 2, 3), 3e38))  # the largest float32s still pass
