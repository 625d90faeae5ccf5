"""Image files through OpenImageIO: EXR/HDR/TIFF stay linear float; PNG/JPEG are tone mapped.

Display encoding (shared/SHADING.md section 8; C++ shading/tonemap.h), after the exposure c:

- ``tonemap='linear'``: l = min(c L, 1) per channel.
- ``tonemap='film'``: the film response l = 1 - e^(-c L) per channel.
- ``tonemap='reinhard'``: Reinhard et al. 2002, "Photographic Tone Reproduction for Digital
  Images": on the luminance Lw (Y of linear sRGB) of c x the image, with ``key`` a the scaled
  L = (a / Lw_bar) Lw, Lw_bar = exp(mean(ln(1e-6 + Lw))) the log-average over the image (eq. 1-2;
  the exposure then cancels), without ``key`` L = c Lw; then Ld = L (1 + L / white^2) / (1 + L)
  (eq. 4; ``white=None``: Ld = L / (1 + L), eq. 3); the colour is scaled by Ld / Lw (hue kept)
  and each channel clamped to 1.
- ``gamma='srgb'`` (the IEC 61966-2-1 curve), ``'linear'`` (none) or a number g in [1, 3]:
  p = l^(1/g).

Finite input never gives NaN: c L is formed in double precision and clamped before mapping.
"""

from __future__ import annotations

import os

import numpy as np

from refracta import _core

__all__ = ["read_image", "to_display", "write_image"]


def write_image(path, image, exposure: float = 1.0, tonemap: str = "reinhard", gamma="srgb",
                key: float | None = None, white: float | None = None) -> None:
    """Write an (H, W, C) float image (C = 1..4; C = 2 and 4 carry alpha last).

    Float formats (.exr, .hdr, .pfm, .tif) get the linear values times `exposure` (no tone
    mapping). Others (.png, .jpg, ...) are encoded as to_display does (tonemap, key, white, gamma:
    see the module docstring) and quantised to 8 bits. Raises refracta.IoError when the file
    cannot be written, ValueError for a bad image or option.
    """
    _core._write_image(os.fspath(path), np.asarray(image), exposure, tonemap, gamma, key, white)


def read_image(path) -> np.ndarray:
    """Read any image OpenImageIO reads as float32 (H, W, C); 8-bit files come back in [0, 1]."""
    return _core._read_image(os.fspath(path))


def to_display(image, exposure: float = 1.0, tonemap: str = "reinhard", gamma="srgb",
               key: float | None = None, white: float | None = None) -> np.ndarray:
    """The display values write_image would store in a PNG, as float32 (H, W, C) in [0, 1] (for imshow).

    image: (H, W) or (H, W, C) linear radiance, C = 1..4 (alpha, the 2nd of 2 or the 4th of 4,
    passes unchanged). exposure c > 0 multiplies it first. tonemap: 'linear', 'film' or
    'reinhard'; key (Reinhard's a, e.g. 0.18) scales the log-average luminance to it, None keeps
    c L; white: Reinhard's L_white (None: infinite); gamma: 'srgb', 'linear' or g in [1, 3].
    The defaults (Reinhard without key, sRGB) map c L = 1 to 0.5 before the curve.
    """
    return _core._display(np.asarray(image), exposure, tonemap, gamma, key, white)
