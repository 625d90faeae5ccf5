"""Image files through OpenImageIO: EXR/HDR/TIFF stay linear float; PNG/JPEG are tone mapped.

Display encoding (C++ shading/tonemap.h, where the math and the
defaults live; this module passes its arguments through, None meaning "not given"):

Exposure c, the scale applied to the linear radiance first:

- automatic, the default (no exposure argument): c = key / Lw_bar, Lw_bar = exp(mean(ln(delta +
  Lw))) the log-average luminance (Y of linear sRGB) of the image, key 0.18 (middle grey;
  Reinhard et al. 2002, eq. 1-2; delta = 1e-6 times the mean luminance, so that black pixels
  keep the logarithm finite at any scale). A render of any scene comes out with its average at
  middle grey, whatever the light's units: c scales exactly as 1 / the units. ``key`` (e.g. 0.09 for a
  dusk, 0.36 for snow) sets the grey; given, it overrides the manual settings below.
- manual: ``exposure`` (c itself), or photographic units: ``ev100``, or a camera's ``shutter`` [s]
  and ``f_number`` (with ``iso``, default 100): EV100 = log2(N^2 / t) - log2(ISO / 100) and
  c = 1 / (1.2 x 2^EV100) (ISO 12232 saturation-based sensitivity; Lagarde & de Rousiers 2014,
  "Moving Frostbite to Physically Based Rendering", eq. 51-53). Give at most one of the three.
  These need the image in luminance: c = K / (1.2 x 2^EV100) with ``luminous_efficacy`` K
  [cd/m^2 per image unit], default 683 (lm/W: radiance in W m^-2 sr^-1 whose Y is
  photometrically weighted, the unit of refracta.examples, i.e. Scene.set_physical_sky(...,
  scale=examples.RADIANCE_SCALE)). The sunlit hot_road example is then well exposed near sunny
  16 (its automatic exposure at its 640 x 320 is EV100 13.9; f/16, 1/100 s, ISO 100 is 14.6).

Tone curve, ``tonemap``:

- ``'aces'`` (default): filmic, the ACES RRT + sRGB ODT as fitted by Stephen Hill (BakingLab
  ACES.hlsl, 2016; with three.js's 1/0.6 exposure boost, so middle grey shows at ~0.5), per
  channel in the fit's working space: a toe in the shadows, a shoulder rolling highlights off to
  white, bright colours desaturating as on film. The default because it looks like a photograph
  where Reinhard's curve looks flat: measured on examples.hot_road() (480 x 160, 4 spp, automatic
  exposure) the displayed (sRGB-encoded) luminance spans 0.10-0.83 (1st-99th percentile, median
  0.66) against Reinhard's 0.17-0.66 (median 0.53), whose sky never gets near white; on cold_sea()
  0.23-0.93 against 0.27-0.80. Its price: hues of saturated highlights shift toward white (a clear
  sky's pale blue goes greyer). OpenColorIO's ACES would be the reference, but
  the OpenImageIO here (2.4 on OCIO 2.1) has no ACES config, only linear/sRGB/Rec709.
- ``'reinhard'``: Reinhard et al. 2002, "Photographic Tone Reproduction for Digital Images": on
  the luminance L = c Lw, Ld = L (1 + L / white^2) / (1 + L) (eq. 4; ``white=None``:
  Ld = L / (1 + L), eq. 3), at most 1; the colour is scaled by Ld / Lw (hue kept: a colour whose L
  exceeds ``white`` shows at display luminance 1 in its own hue, e.g. (3, 1, 0.2) with white=1 as
  (1, 0.73, 0.15), not burnt to white) and each channel clamped to 1.
- ``'linear'``: l = min(c L, 1) per channel; ``'film'``: the film response l = 1 - e^(-c L).
- ``gamma='srgb'`` (the IEC 61966-2-1 curve), ``'linear'`` (none) or a number g in [1, 3]:
  p = l^(1/g).

White balance, ``white_balance`` (before the exposure's scale and the tone curve, as a camera
balances its raw image; C++ tonemap.h): the light named is adapted to the display's D65 white by
the Bradford transform in XYZ, so a grey lit by it shows neutral, its luminance kept:

- ``'none'`` (default): the render's own white (D65), images as they always were;
- a colour temperature [K] in [1000, 40000]: Planck's radiator (the Planckian locus);
- ``'daylight'`` (CIE D55, 5503 K), ``'cloudy'`` (D65 from the daylight locus at 6504 K: within
  0.09 % of 'none'), ``'shade'`` (D75), ``'tungsten'`` (3200 K Planckian);
- an RGB white (r, g, b), linear sRGB, whose X, Y and Z are > 0 (a light's colour, which may lie
  outside sRGB's gamut as a low sun's does): e.g. the pixel of a grey card;
- ``'auto'``: grey world (Buchsbaum 1980): the image's mean linear RGB is taken as the light.

The exposure meters the unbalanced image; ``white_balance_of`` gives the matrix (use it, or a
measured RGB white, to balance several images alike). Float files are written unbalanced.

Finite input never gives NaN: c L is formed in double precision and clamped before mapping.
Colours outside sRGB's gamut (a spectral render's pure spectral light has negative channels:
520 nm is (-1.30, 1.79, -0.08)) have those channels clipped to 0, in the exposure meter too,
which shifts their hue and raises their luminance (+28 % at 520 nm); map them into the gamut
first where that matters (refracta.examples_chroma.gamut_map keeps the luminance).

A PNG carries its transfer curve (its sRGB chunk, or gAMA for ``gamma=`` 'linear' or a number);
float files are linear in sRGB's primaries (OpenEXR's default).
"""

from __future__ import annotations

import os
import unicodedata
import warnings
from typing import Any

import numpy as np

from refracta import _core
from refracta._animate import write_animation
from refracta._checks import is_flag, number

__all__ = [
    "channel_names",
    "ev100",
    "exposure_of",
    "read_image",
    "read_layers",
    "settings",
    "to_display",
    "write_animation",
    "write_image",
    "white_balance_of",
    "write_layers",
]


def _image_array(image, where: str) -> np.ndarray:
    """`image` as an array; a render's (image, aovs) pair (render(aovs=...) returns one) is named."""
    if isinstance(image, (tuple, list)) and len(image) >= 2 and isinstance(image[1], dict):
        raise ValueError(
            f"{where}: got render's (image, aovs) pair, not an image: pass its image (image, aovs = "
            "refracta.render(..., aovs=[...])), and write the AOVs with refracta.io.write_layers"
        )
    array = np.asarray(image)
    _check_fits_float32(array, f"{where}: image values")
    return array


def _check_fits_float32(array: np.ndarray, what: str) -> None:
    """ValueError naming `what` when a float array wider than float32 holds a finite value beyond
    float32's range: images cross as float32, and such a value became inf on the way (with numpy's
    overflow warning; write_layers wrote it to the file so)."""
    if array.dtype.kind == "f" and array.dtype.itemsize > 4 and array.size:
        with np.errstate(invalid="ignore"):
            largest = np.nanmax(np.where(np.isfinite(array), np.abs(array), 0.0))
        if largest > np.finfo(np.float32).max:
            raise ValueError(f"{what} must fit float32 (|value| <= 3.4e38; got {largest:.3g})")


def settings(display: _core.DisplaySettings | None = None, **fields) -> _core.DisplaySettings:
    """A validated refracta.DisplaySettings: a copy of `display` (None: the defaults) with the
    given fields set (a None value: left as it is), by the package's one keyword rule."""
    given = {name: value for name, value in fields.items() if value is not None}
    reinhard_white = isinstance(display, _core.DisplaySettings) and display.white is not None
    if reinhard_white and given.get("tonemap", "reinhard") != "reinhard":
        given.setdefault("white", None)  # Reinhard's white goes with Reinhard's curve (another refuses it)
    # A manual exposure given as a keyword replaces the display's (one of exposure, ev100, or a
    # camera's shutter, f_number and iso): display=DisplaySettings(ev100=10), exposure=2 was refused.
    if isinstance(display, _core.DisplaySettings):
        for group in _MANUAL_EXPOSURES:
            if any(name in given for name in group):
                for other in _MANUAL_EXPOSURES:
                    if other is not group:
                        given.update({name: None for name in other if getattr(display, name) is not None})
    return _core._build_options(_core.DisplaySettings, display, "refracta.io", given)


# The ways to give a manual exposure, one at a time (DisplaySettings.validate).
_MANUAL_EXPOSURES = (("exposure",), ("ev100",), ("shutter", "f_number", "iso"))


def write_image(
    path,
    image,
    exposure: float | None = None,
    tonemap: str | None = None,
    gamma: str | float | None = None,
    key: float | None = None,
    white: float | None = None,
    *,
    display: _core.DisplaySettings | None = None,
    ev100: float | None = None,
    iso: float | None = None,
    shutter: float | None = None,
    f_number: float | None = None,
    luminous_efficacy: float | None = None,
    white_balance: str | float | tuple[float, float, float] | None = None,
) -> None:
    """Write an (H, W, C) float image (C = 1..4; C = 2 and 4 carry alpha last, colour not
    premultiplied by it; a format without alpha, JPEG, gets the colour alone).

    Float formats (.exr, .hdr, .tif) get the linear values times the manual exposure
    (exposure, ev100 or shutter/f_number/iso; none: unchanged, never automatic); display settings
    they leave unused (tonemap, key, white, gamma, white_balance away from their defaults) raise
    a UserWarning naming them. Others (.png,
    .jpg, ...) are encoded as to_display does -- by default automatically exposed (log-average
    to middle grey) and tone mapped by the ACES curve, see the module docstring -- and quantised to 8 bits.
    The display settings are a refracta.DisplaySettings (``display``, or its defaults) changed
    by the other keywords, its fields (None: left as they are). Radiance HDR keeps no negative
    values (a UserWarning counts those written as 0; EXR, TIFF and PFM keep them); JPEG 2000 takes
    images of at least 32 pixels a side.
    Raises refracta.IoError when the file cannot be written, ValueError for a bad image or option.
    """
    fields: dict[str, Any] = dict(exposure=exposure, tonemap=tonemap, gamma=gamma, key=key, white=white, ev100=ev100)
    fields.update(iso=iso, shutter=shutter, f_number=f_number, luminous_efficacy=luminous_efficacy)
    fields.update(white_balance=white_balance)
    _core._write_image(os.fspath(path), _image_array(image, "write_image"), settings(display, **fields))


# Channel suffixes of a layer in write_layers, by its number of channels (EXR's layer.channel names).
_LAYER_SUFFIXES = {1: ("Y",), 2: ("X", "Y"), 3: ("X", "Y", "Z"), 4: ("X", "Y", "Z", "W")}


# EXR channel names of render's readouts whose channels are not X, Y, Z (write_layers' defaults).
READOUT_CHANNELS = {
    "albedo": ("R", "G", "B"),
    "hidden_height": ("geometric", "refracted"),
    "geographic": ("lat", "lon", "height"),
}


def write_layers(path, image, layers: dict, suffixes: dict | None = None) -> None:
    """Write a linear float image with extra named layers to a float file (EXR): the image's
    channels as R, G, B (A), then each layer's as ``name.Y`` (one channel), ``name.X``,
    ``name.Y``, ``name.Z`` (two to four; e.g. position.X), render's readouts as their channels
    are (READOUT_CHANNELS: albedo.R, hidden_height.geometric, geographic.lat, .lon, .height), or
    the names ``suffixes[name]`` gives (e.g. {"hidden_height": ("geometric", "refracted")}).
    Layers are (H, W) or (H, W, C) arrays of the image's size, stored as float32 as they are (inf
    and NaN kept; integers as floats). A layer's name is a non-empty string (dots allowed between
    parts: EXR's nested layers); a suffix a non-empty string without a dot. Raises ValueError for
    a bad layer (complex or non-numeric values, finite values beyond float32's range, a bad name,
    a name longer than EXR's 255 bytes) or a non-float format, refracta.IoError when the file
    cannot be written. EXR keeps channels sorted by name: read_layers gives them back in this
    order (read_image in the file's: geographic.height before .lat)."""
    base = _layer_values(_image_array(image, "write_layers"), "write_layers: image")
    if base.ndim == 2:
        base = base[..., None]
    if base.ndim != 3 or not 1 <= base.shape[2] <= 4:
        raise ValueError(f"write_layers: image must be (H, W) or (H, W, 1..4) (got shape {base.shape})")
    if not isinstance(layers, dict):
        raise ValueError(f"write_layers: layers must be a dict of name: array (got {type(layers).__name__})")
    names = list(("R", "G", "B", "A")[: base.shape[2]]) if base.shape[2] >= 3 else ["Y", "A"][: base.shape[2]]
    planes = [base]
    for name, layer in layers.items():
        _check_channel_name(name, "layer name")
        values = _layer_values(layer, f"write_layers: layer {name!r}")
        if values.ndim == 2:
            values = values[..., None]
        if values.ndim != 3 or values.shape[:2] != base.shape[:2]:
            raise ValueError(
                f"write_layers: layer {name!r} must be (H, W) or (H, W, C) of the image's {base.shape[:2]} "
                f"(got shape {np.shape(layer)})"
            )
        given = (suffixes or {}).get(name)
        if given is not None and (isinstance(given, str) or not isinstance(given, (list, tuple, np.ndarray))):
            raise ValueError(f"write_layers: suffixes[{name!r}] must be a sequence of channel names (got {given!r})")
        given = None if given is None else [str(suffix) if isinstance(suffix, str) else suffix for suffix in given]
        for suffix in given or ():
            _check_channel_name(suffix, f"suffixes[{name!r}]", dots=False)
        readout = READOUT_CHANNELS.get(name)
        own = given or (
            readout if readout and len(readout) == values.shape[2] else _LAYER_SUFFIXES.get(values.shape[2])
        )
        if own is None:
            raise ValueError(f"write_layers: layer {name!r} has {values.shape[2]} channels; give its channel names")
        if len(own) != values.shape[2]:
            raise ValueError(
                f"write_layers: suffixes[{name!r}] gives {len(own)} names for {values.shape[2]} channel"
                f"{'s' if values.shape[2] > 1 else ''}"
            )
        names += [f"{name}.{suffix}" for suffix in own]
        planes.append(values)
    repeated = sorted({n for n in names if names.count(n) > 1})
    if repeated:
        raise ValueError(f"write_layers: channel names repeat: {', '.join(map(repr, repeated))}")
    _core._write_image_channels(os.fspath(path), np.ascontiguousarray(np.concatenate(planes, axis=2)), names)


def _check_channel_name(name, what: str, dots: bool = True) -> None:
    """ValueError unless `name` is a channel name part write_layers can write and read back: a
    non-empty string, not blank, without control characters (OpenImageIO cut 'a\\x00b' to 'a'),
    and without a dot (`dots` False) or with dots only between non-empty parts ('a.b', not '.a',
    'a.' or 'a..b', which make an empty layer name in EXR's layer.channel)."""
    if not isinstance(name, str):
        raise ValueError(f"write_layers: {what} must be a string (got {name!r})")
    if not name.strip() or any(unicodedata.category(c) == "Cc" for c in name):
        raise ValueError(f"write_layers: {what} must be a non-empty name without control characters (got {name!r})")
    if "." in name and (not dots or "" in name.split(".")):
        rule = "hold no dot" if not dots else "have dots only between non-empty parts"
        raise ValueError(f"write_layers: {what} must {rule} (got {name!r})")


def _layer_values(values, what: str) -> np.ndarray:
    """`values` (an image or a layer of write_layers) as float32, else ValueError naming `what`:
    complex values (numpy dropped the imaginary part), strings and other non-numbers, and
    finite values beyond float32's range (they became inf)."""
    array = np.asarray(values)
    if array.dtype.kind not in "biuf":
        raise ValueError(f"{what} must hold real numbers (got dtype {array.dtype})")
    _check_fits_float32(array, what)
    return array.astype(np.float32)


def channel_names(path) -> list[str]:
    """The channel names of an image file, as OpenImageIO reads them (an EXR's layer.channel).
    Raises refracta.IoError for a missing file or one that is not a regular file (a folder, or a
    FIFO, which would block)."""
    return list(_core._channel_names(os.fspath(path)))


def read_layers(path) -> tuple[np.ndarray, dict[str, np.ndarray]]:
    """(image, layers) of a float file as write_layers wrote it: the image from its unnamed channels
    (R, G, B, A, or Y), each layer ``name`` from its ``name.<suffix>`` channels, (H, W) for one
    channel, (H, W, C) otherwise, its channels in the order write_layers gives them
    (READOUT_CHANNELS for render's readouts, X, Y, Z, W otherwise) -- not the file's: EXR keeps
    channels sorted by name, so read_image puts geographic.height before .lat and .lon. A layer
    of other suffixes keeps the file's order. Raises refracta.IoError as read_image does."""
    names, pixels = channel_names(path), read_image(path)
    base = [i for i, name in enumerate(names) if "." not in name]
    order = {"R": 0, "G": 1, "B": 2, "Y": 0, "A": 3}
    base.sort(key=lambda i: order.get(names[i], len(order)))
    groups: dict[str, dict[str, int]] = {}
    for i, name in enumerate(names):
        if "." in name:
            layer, suffix = name.rsplit(".", 1)
            groups.setdefault(layer, {})[suffix] = i
    layers = {}
    for layer, channels in groups.items():
        wanted = READOUT_CHANNELS.get(layer) or _LAYER_SUFFIXES.get(len(channels))
        suffixes = list(wanted) if wanted and set(wanted) == set(channels) else list(channels)
        values = pixels[..., [channels[suffix] for suffix in suffixes]]
        layers[layer] = values[..., 0] if values.shape[-1] == 1 else values
    image = pixels[..., base]
    return (image[..., 0] if image.shape[-1] == 1 else image), layers


def read_image(path, linear: bool = False) -> np.ndarray:
    """Read any image OpenImageIO reads as float32 (H, W, C).

    linear=False: the values as the file stores them: float files (EXR, HDR, PFM, float TIFF)
    their linear values, 8- and 16-bit files (PNG, JPEG, TIFF) their display-encoded values
    scaled to [0, 1] (128 of 255 reads 0.502). linear=True: 8- and 16-bit files decoded to linear
    values, as textures and environment maps are: by the transfer curve the file names (a PNG's
    gAMA chunk: write_image's gamma='linear' PNGs read as stored, gamma=2.2 ones as v^2.2), else
    from sRGB (128 of 255 reads 0.216); alpha as stored; float files as they are. WebP colour reads
    straight (not premultiplied by alpha), as every other format's. Raises refracta.IoError for a
    missing or unreadable file.
    """
    if not is_flag(linear):
        raise ValueError(f"read_image: linear must be True or False (got {linear!r})")
    return _core._read_image(os.fspath(path), bool(linear))


def to_display(
    image,
    exposure: float | None = None,
    tonemap: str | None = None,
    gamma: str | float | None = None,
    key: float | None = None,
    white: float | None = None,
    *,
    display: _core.DisplaySettings | None = None,
    ev100: float | None = None,
    iso: float | None = None,
    shutter: float | None = None,
    f_number: float | None = None,
    luminous_efficacy: float | None = None,
    white_balance: str | float | tuple[float, float, float] | None = None,
) -> np.ndarray:
    """The display values write_image would store in a PNG, as float32 (H, W, C) in [0, 1] (for imshow).

    image: (H, W) or (H, W, C) linear radiance, C = 1..4 (alpha, the 2nd of 2 or the 4th of 4,
    passes unchanged). The settings are a refracta.DisplaySettings (``display``, or its defaults)
    changed by the other keywords, its fields (None: left as they are). Exposure: automatic by
    default (the image's log-average luminance to ``key``, 0.18), or manual: ``exposure`` c > 0
    multiplying it, ``ev100``, or ``shutter`` [s] and ``f_number`` (``iso`` 100 unless given;
    these two with ``luminous_efficacy`` K, the luminance [cd/m^2] of a value of 1, default 683);
    a ``key`` overrides the manual one. tonemap: 'aces' (default, filmic), 'reinhard', 'linear' or
    'film'; white: Reinhard's L_white (None: infinite); gamma: 'srgb' (default), 'linear' or g in
    [1, 3]; white_balance: the light shown white, 'none' (default), 'auto' (grey world), a preset
    ('daylight', 'cloudy', 'shade', 'tungsten'), a colour temperature [K] or an RGB white. See the
    module docstring for the formulas.
    """
    fields: dict[str, Any] = dict(exposure=exposure, tonemap=tonemap, gamma=gamma, key=key, white=white, ev100=ev100)
    fields.update(iso=iso, shutter=shutter, f_number=f_number, luminous_efficacy=luminous_efficacy)
    fields.update(white_balance=white_balance)
    return _core._display(_image_array(image, "to_display"), settings(display, **fields))


def exposure_of(
    image,
    exposure: float | None = None,
    key: float | None = None,
    *,
    display: _core.DisplaySettings | None = None,
    ev100: float | None = None,
    iso: float | None = None,
    shutter: float | None = None,
    f_number: float | None = None,
    luminous_efficacy: float | None = None,
) -> float:
    """The exposure c (the scale of the radiance) to_display would apply to this image with these settings
    (a refracta.DisplaySettings ``display`` changed by the keywords, as to_display).

    Automatic by default (0.18 / the log-average luminance); use it to give several images (the
    frames of an animation, a with/without pair) one exposure: ``to_display(img, exposure=c)``. A
    stack of frames (T, H, W, C) gives the exposure of all of them together. An image without light
    (no pixel of positive luminance) has nothing to meter: the manual exposure (1 unless given), with a
    RuntimeWarning.
    """
    fields = dict(exposure=exposure, key=key, ev100=ev100, iso=iso, shutter=shutter, f_number=f_number)
    array = _image_array(image, "exposure_of")
    if array.ndim == 4:  # frames, stacked as one tall image (animate's joint exposure)
        if 0 in array.shape[:3]:
            raise ValueError(
                f"exposure_of: a stack of frames must have shape (T, H, W, C), T, H, W >= 1 (got {array.shape})"
            )
        array = array.reshape(-1, *array.shape[2:])
    exposure, metered_nothing = _core._display_exposure(
        array, settings(display, **fields, luminous_efficacy=luminous_efficacy)
    )
    if metered_nothing:
        warnings.warn(
            "exposure_of: the image has no light (no pixel of positive luminance), so automatic exposure meters "
            f"nothing: {exposure:g} (the manual exposure) is returned; give exposure= for images that share it",
            RuntimeWarning,
            stacklevel=2,
        )
    return exposure


def white_balance_of(
    image,
    white_balance: str | float | tuple[float, float, float] | None = None,
    *,
    display: _core.DisplaySettings | None = None,
) -> np.ndarray:
    """The (3, 3) matrix B, linear sRGB to linear sRGB (rgb' = B @ rgb), that to_display applies to
    this image for the white balance (``white_balance``, else ``display``'s; the module docstring):
    xyz_to_rgb @ Bradford(light's white -> D65) @ rgb_to_xyz. Only 'auto' reads the image (its mean
    RGB); the identity for 'none', for grey images, and for 'auto' on an image with a channel
    without light (an all-red one: grey world has nothing to balance by). ValueError for a bad white
    balance."""
    return _core._white_balance_matrix(
        _image_array(image, "white_balance_of"), settings(display, white_balance=white_balance)
    )


def ev100(f_number: float, shutter: float, iso: float | None = None) -> float:
    """EV100 = log2(N^2 / t) - log2(ISO / 100) of an f-number N, a shutter time t [s] and an ISO
    (None: 100).

    Sunny 16 (f/16, 1/100 s, ISO 100) is EV100 = 14.6. ValueError for values <= 0 or NaN.
    """
    f_number, shutter = number(f_number, "ev100: f_number"), number(shutter, "ev100: shutter")
    camera = (f_number, shutter) if iso is None else (f_number, shutter, number(iso, "ev100: iso"))
    try:
        return _core._ev100(*camera)
    except ValueError as error:  # the library's check of the values, named as the call
        raise ValueError(f"ev100: {error}") from None
