"""Image files through OpenImageIO: EXR/HDR/TIFF stay linear float; PNG/JPEG are tone mapped."""

from __future__ import annotations

import os

import numpy as np

from refracta import _core


def write_image(path, image, exposure: float = 1.0, tonemap: str = "reinhard", gamma: str = "srgb") -> None:
    """Write an (H, W, C) float image (C = 1..4).

    Float formats (.exr, .hdr, .pfm, .tif) get the linear values times `exposure`. Others (.png,
    .jpg, ...) are tone mapped ('reinhard' x/(1+x), 'film' 1-e^-x, or 'linear' clamp) after the
    exposure, encoded with the sRGB curve (gamma='srgb') or not ('linear'), and quantised to 8 bits.
    Raises refracta.IoError when the file cannot be written, ValueError for a bad image.
    """
    _core._write_image(os.fspath(path), np.asarray(image), exposure, tonemap, gamma)


def read_image(path) -> np.ndarray:
    """Read any image OpenImageIO reads as float32 (H, W, C); 8-bit files come back in [0, 1]."""
    return _core._read_image(os.fspath(path))


def to_display(image, exposure: float = 1.0, tonemap: str = "reinhard", gamma: str = "srgb") -> np.ndarray:
    """The display values write_image would store in a PNG, as float32 in [0, 1] (for imshow)."""
    return _core._display(np.asarray(image), exposure, tonemap, gamma)
