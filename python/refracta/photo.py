"""refracta.photo: a photograph to match -- its pixels, its EXIF, its camera, and overlays of a render.

A photograph of a distant coast or skyline is compared with a render of the same view: ``load``
reads it (OpenImageIO, through refracta.io) with its EXIF (Pillow: focal length, 35 mm
equivalent, sensor size from the focal-plane resolution, orientation, which is applied to the
pixels); ``Photo.vfov`` and ``Photo.camera`` set a Camera's field of view from it; ``overlay``
draws the render's skyline and edges on the photograph. ``refracta.edit.solve(...,
free=["camera_yaw", "camera_pitch", "camera_roll", "camera_vfov", ...])`` then solves the camera
and the air together from pairs whose destinations are pixels of the photograph.

Example::

    from refracta import photo
    picture = photo.load("coast.jpg")
    camera = picture.camera(position=(0.0, 12.0, 0.0), look_at=(0.0, 12.0, -1000.0), width=480)
    image, aovs = refracta.render(scene, camera, field, aovs=["distance", "object_id"])
    result = photo.overlay(picture, (image, aovs), mode="edges")
    result.figure.savefig("overlay.png")

Field of view (vertical, degrees, of the image as displayed, orientation applied):

* focal length f [mm] and sensor size (EXIF FocalPlaneX/YResolution with the EXIF image size,
  PixelX/YDimension -- the sensor's, which a resized copy keeps -- or ``sensor_mm=`` given):
  vfov = 2 atan(h / 2f), h the sensor side along the image's height;
* else the 35 mm equivalent focal length f35 (EXIF FocalLengthIn35mmFilm), read as CIPA DC-008
  defines it: the lens that gives a full-frame (36 x 24 mm, diagonal 43.27 mm) camera the same
  diagonal angle of view. The diagonal angle 2 atan(43.27 / 2 f35) is shared out by the image's
  aspect: vfov = 2 atan(tan(dfov / 2) H / sqrt(W^2 + H^2)) -- exact for a 3:2 image, and the
  definition's meaning for any other.
"""

from __future__ import annotations

import math
import os
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from refracta import _core
from refracta import io as _io
from refracta._checks import is_number, number_pair
from refracta._render import AOV_NAMES

__all__ = ["Exif", "OverlayResult", "Photo", "load", "overlay", "read_exif", "OVERLAY_MODES"]

#: The modes of overlay().
OVERLAY_MODES = ("blend", "difference", "edges")

# [mm] the diagonal of a full-frame (36 x 24 mm) sensor: the reference of 35 mm equivalent focal lengths.
_FULL_FRAME_DIAGONAL = math.hypot(36.0, 24.0)

# EXIF tags (CIPA DC-008-2019, section 4.6).
_TAG_ORIENTATION = 0x0112
_TAG_MAKE = 0x010F
_TAG_MODEL = 0x0110
_IFD_EXIF = 0x8769
_TAG_FOCAL_LENGTH = 0x920A
_TAG_FOCAL_35MM = 0xA405
_TAG_PIXEL_X = 0xA002
_TAG_PIXEL_Y = 0xA003
_TAG_PLANE_X = 0xA20E
_TAG_PLANE_Y = 0xA20F
_TAG_PLANE_UNIT = 0xA210
# FocalPlaneResolutionUnit: millimetres per unit (1: none given, read as inches as EXIF's default).
_PLANE_UNIT_MM = {1: 25.4, 2: 25.4, 3: 10.0, 4: 1.0, 5: 1e-3}

# File formats that hold linear radiance (float); a TIFF holds it when its samples are floats.
_LINEAR_SUFFIXES = (".exr", ".hdr", ".pfm")


def _holds_linear(path: Path) -> bool:
    """Whether a photograph file holds linear radiance: a float format, or a TIFF of float samples
    (an 8- or 16-bit TIFF is display-encoded, as JPEG and PNG are)."""
    suffix = path.suffix.lower()
    if suffix in (".tif", ".tiff"):
        import tifffile

        try:
            with tifffile.TiffFile(path) as tif:
                return tif.pages.first.dtype is not None and tif.pages.first.dtype.kind == "f"
        except Exception:  # read by OpenImageIO above; a TIFF tifffile cannot parse: as 8-bit
            return False
    return suffix in _LINEAR_SUFFIXES


@dataclass(frozen=True)
class Exif:
    """What a photograph's EXIF says about its camera (None where it says nothing).

    focal_length_mm: the lens's focal length [mm]; focal_length_35mm: its 35 mm equivalent [mm];
    sensor_mm: the sensor's (width, height) [mm] along the image as stored (before orientation),
    from the focal-plane resolution and EXIF's image size (PixelX/YDimension); orientation: the EXIF orientation
    code 1..8 (1: as stored); make, model: the camera's.
    """

    focal_length_mm: float | None = None
    focal_length_35mm: float | None = None
    sensor_mm: tuple[float, float] | None = None
    orientation: int = 1
    make: str | None = None
    model: str | None = None

    def __post_init__(self):
        # Refused here, where they are named: a focal length of -50 mm gave a vfov of -34 deg.
        for name in ("focal_length_mm", "focal_length_35mm"):
            value = getattr(self, name)
            if value is not None and not (is_number(value) and 0.0 < float(value) < math.inf):
                raise ValueError(f"Exif: {name} must be None or a finite number of mm > 0 (got {value!r})")
        if self.sensor_mm is not None:
            _sensor(self.sensor_mm, "Exif: sensor_mm")
        code = self.orientation
        if isinstance(code, bool) or not isinstance(code, (int, np.integer)) or not 1 <= code <= 8:
            raise ValueError(f"Exif: orientation must be an EXIF orientation code 1..8 (got {self.orientation!r})")


@dataclass(eq=False)  # arrays: == would be ambiguous (equal by identity)
class Photo:
    """A photograph as displayed (EXIF orientation applied).

    image: float32 (H, W, C) -- for 8-bit formats (JPEG, PNG) the display-encoded values in [0, 1]
    as stored, for float formats (EXR, HDR) linear radiance; ``linear`` says which. exif: an Exif
    (fields None where the file has none). path: where it was read from.
    """

    image: np.ndarray
    linear: bool
    exif: Exif = field(default_factory=Exif)
    path: Path | None = None

    def __post_init__(self) -> None:
        # A nested list (a user's own photograph) as the array it stands for: .width read its .shape.
        if not isinstance(self.image, np.ndarray):
            try:
                self.image = np.asarray(self.image, dtype=np.float32)
            except (TypeError, ValueError):
                raise ValueError(
                    f"Photo: image must be an array of numbers (H, W) or (H, W, C) (got {type(self.image).__name__})"
                ) from None

    @property
    def width(self) -> int:
        return int(self.image.shape[1])

    @property
    def height(self) -> int:
        return int(self.image.shape[0])

    def display(self) -> np.ndarray:
        """float32 (H, W, 3) display values in [0, 1] (a linear photograph through refracta.io.to_display)."""
        return _as_display(self.image, self.linear, what="photo")

    def sensor_mm(self) -> tuple[float, float] | None:
        """The sensor's (width, height) [mm] along the image as displayed, or None if EXIF does not say."""
        if self.exif.sensor_mm is None:
            return None
        w, h = self.exif.sensor_mm
        return (h, w) if self.exif.orientation in (5, 6, 7, 8) else (w, h)

    def _check_size(self) -> None:
        """ValueError for an image without pixels (its aspect and field of view are undefined)."""
        shape = np.shape(self.image)
        if len(shape) < 2 or shape[0] < 1 or shape[1] < 1:
            raise ValueError(f"the photograph's image is empty (shape {shape}): it has no aspect or field of view")

    def vfov(self, sensor_mm: tuple[float, float] | None = None) -> float:
        """The vertical field of view [deg] of the image as displayed, from EXIF (module docstring).

        sensor_mm: the sensor's (width, height) [mm] along the displayed image, overriding EXIF's.
        The picture spans the sensor's width when it is relatively wider than the sensor (a 16:9
        frame from a 3:2 sensor), else its height, as Camera.photographic fits it. Without a sensor
        size, a 35 mm equivalent focal length is taken on the picture's diagonal, as EXIF (CIPA
        DC-008) defines it: the camera scales it by the diagonal of the picture's own area.
        Raises ValueError when EXIF gives no focal length, or a focal length but neither a sensor
        size nor a 35 mm equivalent (naming what to pass).
        """
        self._check_size()
        exif = self.exif
        sensor = self.sensor_mm() if sensor_mm is None else _sensor(sensor_mm)
        if exif.focal_length_mm is not None and sensor is not None:
            # Camera.photographic's fit: a picture relatively wider than the sensor spans its width.
            return _core.Camera.photographic_vfov(exif.focal_length_mm, sensor, self.width, self.height)
        if exif.focal_length_35mm is not None:
            half_diagonal = math.atan(_FULL_FRAME_DIAGONAL / (2.0 * exif.focal_length_35mm))
            share = self.height / math.hypot(self.width, self.height)
            return math.degrees(2.0 * math.atan(math.tan(half_diagonal) * share))
        where = f" of {self.path}" if self.path is not None else ""
        if exif.focal_length_mm is None:
            raise ValueError(
                f"the EXIF{where} gives no focal length (FocalLength or FocalLengthIn35mmFilm): "
                "give it yourself, as Photo.camera(position, look_at, vfov=...) [deg]"
            )
        raise ValueError(
            f"the EXIF{where} gives the focal length ({exif.focal_length_mm:g} mm) but neither the sensor size "
            "nor a 35 mm equivalent: pass sensor_mm=(width, height)"
        )

    def camera(
        self,
        position,
        look_at,
        up=(0.0, 1.0, 0.0),
        *,
        width: int | None = None,
        sensor_mm: tuple[float, float] | None = None,
        vfov: float | None = None,
    ) -> _core.Camera:
        """A Camera at `position` looking at `look_at` with the photograph's vertical field of view
        (vfov(sensor_mm), or `vfov` [deg] given: a photograph whose EXIF says nothing of its lens)
        and aspect. width: the render's width in pixels (default the photograph's); the height
        follows the photograph's aspect (rounded, at least 1)."""
        self._check_size()
        if vfov is not None and sensor_mm is not None:
            raise ValueError("Photo.camera: give vfov or sensor_mm, not both (sensor_mm sets the field of view)")
        w = self.width if width is None else width
        if not (is_number(w) and math.isfinite(w) and w == int(w) and 1 <= w <= _core.Camera.max_side):
            raise ValueError(f"width must be a whole number of pixels in [1, {_core.Camera.max_side}] (got {width!r})")
        h = max(1, round(int(w) * self.height / self.width))
        return _core.Camera(position, look_at, up, self.vfov(sensor_mm) if vfov is None else vfov, int(w), h)


def _sensor(value, name: str = "sensor_mm") -> tuple[float, float]:
    sides = number_pair(value)
    if sides is None:
        raise ValueError(f"{name} must be (width, height) in mm (got {value!r})")
    w, h = sides
    if not (w > 0.0 and h > 0.0 and math.isfinite(w) and math.isfinite(h)):
        raise ValueError(f"{name} must be two finite sizes > 0 mm (got {value!r})")
    return w, h


# [mm] the sides an EXIF-derived sensor may have: 0.5 mm is below the short side of the smallest
# sensor type in cameras that write EXIF (1/10 inch, 1.28 x 0.96 mm), 500 mm twice the long side
# of 8 x 10-inch sheet film (254 mm). Beyond them the focal-plane resolution is wrong (a trial's
# 1e-9 pixels per cm gave a 3.2e11 mm sensor and a vfov of 179.99999993 deg).
_SENSOR_SIDES_MM = (0.5, 500.0)


def _rational(value) -> float | None:
    try:
        number = float(value)
    except (TypeError, ValueError, ZeroDivisionError):
        return None
    return number if math.isfinite(number) and number > 0.0 else None


def _existing_file(path, what: str) -> Path:
    """`path` as a Path; refracta.IoError naming it when it is not a file (MissingFileError when
    it is not there)."""
    path = Path(os.fspath(path))
    if not path.exists():
        raise _core.MissingFileError(f"cannot read {what} {path}: no such file")
    if not path.is_file():
        reason = "it is a folder, not a file" if path.is_dir() else "not a regular file (a FIFO or a device)"
        raise _core.IoError(f"cannot read {what} {path}: {reason}")
    return path


def read_exif(path) -> Exif:
    """The EXIF of an image file (Pillow); an Exif of Nones for a file without EXIF or one Pillow
    cannot open (an EXR); refracta.IoError for a path that is not a file. Malformed tags read as
    none, and so does a sensor size no camera has (a side outside 0.5 to 500 mm: a wrong
    focal-plane resolution), with a UserWarning naming the tags."""
    from PIL import Image, UnidentifiedImageError

    path = _existing_file(path, "EXIF of")
    try:
        with Image.open(path) as image:
            exif = image.getexif()
    except (UnidentifiedImageError, OSError):
        return Exif()
    sub = exif.get_ifd(_IFD_EXIF)

    def tag(key):
        return sub.get(key, exif.get(key))

    sensor = None
    plane_x, plane_y = _rational(tag(_TAG_PLANE_X)), _rational(tag(_TAG_PLANE_Y))
    pixels_x, pixels_y = _rational(tag(_TAG_PIXEL_X)), _rational(tag(_TAG_PIXEL_Y))
    unit_code = _rational(tag(_TAG_PLANE_UNIT) or 2)  # a malformed tag (a string) reads as none
    unit = _PLANE_UNIT_MM.get(int(unit_code)) if unit_code is not None and unit_code.is_integer() else None
    if plane_x and plane_y and pixels_x and pixels_y and unit:
        sensor = (pixels_x / plane_x * unit, pixels_y / plane_y * unit)
        low, high = _SENSOR_SIDES_MM
        if not all(low <= side <= high for side in sensor):
            # As a malformed tag: read as none (vfov falls back to the 35 mm equivalent), said.
            warnings.warn(
                f"{path}: the EXIF sensor size {sensor[0]:.3g} x {sensor[1]:.3g} mm (PixelXDimension / "
                "FocalPlaneXResolution and PixelYDimension / FocalPlaneYResolution, in FocalPlaneResolutionUnit) "
                f"is no camera's ({low:g} to {high:g} mm a side): ignored, as if the tags were absent",
                UserWarning,
                stacklevel=2,
            )
            sensor = None
    orientation = exif.get(_TAG_ORIENTATION, 1)
    try:
        orientation = int(orientation)
    except (TypeError, ValueError):
        orientation = 1

    def text(key):
        value = exif.get(key)
        return str(value).strip("\x00 ") or None if value is not None else None

    return Exif(
        focal_length_mm=_rational(tag(_TAG_FOCAL_LENGTH)),
        focal_length_35mm=_rational(tag(_TAG_FOCAL_35MM)),
        sensor_mm=sensor,
        orientation=orientation if 1 <= orientation <= 8 else 1,
        make=text(_TAG_MAKE),
        model=text(_TAG_MODEL),
    )


def _orient(image: np.ndarray, orientation: int) -> np.ndarray:
    """The stored pixels turned as EXIF orientation `orientation` says they are displayed (as
    Pillow's ImageOps.exif_transpose)."""
    turned = {
        1: lambda a: a,
        2: lambda a: a[:, ::-1],
        3: lambda a: a[::-1, ::-1],
        4: lambda a: a[::-1],
        5: lambda a: a.swapaxes(0, 1),
        6: lambda a: np.rot90(a, k=-1),
        7: lambda a: a[::-1, ::-1].swapaxes(0, 1),
        8: lambda a: np.rot90(a, k=1),
    }[orientation](image)
    return np.ascontiguousarray(turned)


def load(path) -> Photo:
    """Read a photograph (any format OpenImageIO reads) and its EXIF; the EXIF orientation is applied.

    Returns a Photo: its image float32 (H, W, C), display-encoded in [0, 1] for 8-bit formats
    (JPEG, PNG, 8- and 16-bit TIFF) or linear for float ones (EXR, HDR, PFM, float TIFF). Raises refracta.IoError for a
    missing or unreadable file.
    """
    path = _existing_file(path, "photograph")
    image = _io.read_image(path)
    exif = read_exif(path)
    return Photo(
        image=_orient(image, exif.orientation),
        linear=_holds_linear(path),
        exif=exif,
        path=path,
    )


def _as_display(image, linear: bool, what: str = "image") -> np.ndarray:
    """float32 (H, W, 3) display values of an image: linear ones through refracta.io.to_display,
    display ones as they are (grey repeated, alpha dropped). ValueError naming `what` for a path,
    non-numbers, a bad shape, NaN or inf, and display values outside [0, 1]."""
    if isinstance(image, (str, os.PathLike)):
        raise ValueError(
            f"{what} must be an image array (got the path {os.fspath(image)!r}: read it with refracta.photo.load)"
        )
    try:
        image = np.asarray(image, dtype=np.float32)
    except (TypeError, ValueError):
        raise ValueError(f"{what} must be an array of numbers (got {type(image).__name__})") from None
    if image.ndim == 2:
        image = image[..., None]
    if image.ndim != 3 or image.shape[2] not in (1, 2, 3, 4):
        raise ValueError(f"{what} must be (H, W) or (H, W, C) with C = 1..4 (got shape {image.shape})")
    if not np.isfinite(image).all():
        raise ValueError(f"{what} holds NaN or inf")
    # Display values: a resampled photograph overshoots [0, 1] a little (bicubic ringing), clipped
    # here; beyond a few levels of 8 bits the values are not display values at all.
    slack = 0.01
    if not linear and image.size and not (image.min() >= -slack and image.max() <= 1.0 + slack):
        raise ValueError(
            f"{what} holds display values, which must be in [0, 1] (got {image.min():g} to {image.max():g}; "
            "8-bit values: divide by 255)"
        )
    shown = _io.to_display(image) if linear else np.clip(image, 0.0, 1.0)
    shown = shown[..., :3] if shown.shape[2] >= 3 else np.repeat(shown[..., :1], 3, axis=2)
    return np.ascontiguousarray(shown, dtype=np.float32)


@dataclass(eq=False)  # arrays: == would be ambiguous (equal by identity)
class OverlayResult:
    """What overlay() made.

    image: float32 (H, W, 3) display values in [0, 1] -- the blend, the difference or the
    photograph with the render's edges -- with the skyline (if known) and edges drawn in `color`
    (blend and edges modes). edges: bool (H, W), the render's edge pixels. skyline: int (W,), per
    column the row of the render's topmost surface pixel (-1: none), or None when the render came
    without readouts. mode: the mode. figure: a matplotlib Figure showing the image (made on
    first access; matplotlib is imported then).
    """

    image: np.ndarray
    edges: np.ndarray
    skyline: np.ndarray | None
    mode: str
    _figure: Any = field(default=None, repr=False)

    @property
    def figure(self):
        if self._figure is None:
            import matplotlib.pyplot as plt

            height, width = self.edges.shape
            figure, axes = plt.subplots(figsize=(8.0, 8.0 * height / width), layout="constrained")
            axes.imshow(self.image, interpolation="nearest")
            axes.set_title(f"render over photograph ({self.mode})")
            axes.set_axis_off()
            plt.close(figure)  # kept by the result, not shown by pyplot's state machine
            self._figure = figure
        return self._figure


def _hits(aovs: dict) -> np.ndarray | None:
    """Where the render met a surface (bool (H, W)), from its 'object_id' or 'distance' readout."""
    if "object_id" in aovs:
        return np.asarray(aovs["object_id"]).reshape(np.shape(aovs["object_id"])[:2]) >= 0
    if "distance" in aovs:
        return np.isfinite(np.asarray(aovs["distance"]).reshape(np.shape(aovs["distance"])[:2]))
    return None


def _boundaries(labels: np.ndarray, differ) -> np.ndarray:
    """Pixels whose label differs (differ(a, b) True) from their right or lower neighbour, or from
    their left or upper one: the boundary on both sides."""
    edges = np.zeros(labels.shape[:2], dtype=bool)
    horizontal = differ(labels[:, 1:], labels[:, :-1])
    vertical = differ(labels[1:], labels[:-1])
    edges[:, 1:] |= horizontal
    edges[:, :-1] |= horizontal
    edges[1:] |= vertical
    edges[:-1] |= vertical
    return edges


def _render_edges(shown: np.ndarray, aovs: dict, threshold: float) -> np.ndarray:
    """The render's edges: object boundaries (object_id), depth jumps (distance: a relative change
    above `threshold`, or hit against none), else luminance steps above `threshold` of its display
    values."""
    if "object_id" in aovs:
        ids = np.asarray(aovs["object_id"])
        return _boundaries(ids.reshape(ids.shape[:2]), lambda a, b: a != b)
    if "distance" in aovs:
        d = np.asarray(aovs["distance"], dtype=float)
        d = d.reshape(d.shape[:2])

        def jump(a, b):
            finite = np.isfinite(a) & np.isfinite(b)
            with np.errstate(invalid="ignore", divide="ignore"):
                relative = np.abs(a - b) / np.minimum(np.abs(a), np.abs(b))
            return np.where(finite, relative > threshold, np.isfinite(a) != np.isfinite(b))

        return _boundaries(d, jump)
    luminance = shown @ np.array([0.2126, 0.7152, 0.0722], dtype=np.float32)  # Rec. 709 / sRGB weights
    return _boundaries(luminance, lambda a, b: np.abs(a - b) > threshold)


def overlay(
    photo,
    render,
    mode: str = "blend",
    *,
    aovs: dict | None = None,
    alpha: float = 0.5,
    threshold: float = 0.1,
    color=(1.0, 0.0, 0.0),
    linear: bool | None = None,
) -> OverlayResult:
    """The render's skyline and edges drawn on the photograph.

    Args:
        photo: a Photo, or an (H, W[, C]) display-encoded array in [0, 1].
        render: the rendered image (H, W[, C]) of linear radiance (as refracta.render returns it;
            shown through refracta.io.to_display), or the ``(image, {name: array})`` pair
            ``render(..., aovs=[...])`` returns. Same size as the photograph.
        mode: 'blend' (photograph and render mixed, (1 - alpha) photo + alpha render, with the
            render's edges and skyline in `color`), 'difference' (the absolute difference per channel,
            nothing drawn) or 'edges' (the photograph with the render's edges and skyline in
            `color`).
        aovs: readouts of the render ({name: (H, W) array}); 'object_id' (-1: no surface) gives
            the edges as object boundaries and the skyline, else 'distance' (inf: none) gives
            them as depth jumps; without either the edges are luminance steps of the render's
            display image and there is no skyline. Also taken from a (image, aovs) `render`.
        alpha: the render's share in 'blend', in [0, 1].
        threshold: an edge is a relative distance jump above it ('distance'), or a display
            luminance step above it (no readouts).
        color: RGB in [0, 1] of the drawn edges and skyline.
        linear: whether `render` is linear radiance (default True; False: display values).

    Returns:
        An OverlayResult: .image (float32 (H, W, 3) display values), .edges, .skyline and
        .figure (a matplotlib Figure of the image).

    Raises:
        ValueError: an unknown mode (listing the valid ones), images of different sizes, a bad
            alpha, threshold or color.
    """
    if mode not in OVERLAY_MODES:
        raise ValueError(f"mode must be one of {OVERLAY_MODES} (got {mode!r})")
    if isinstance(render, tuple):
        if len(render) != 2 or not isinstance(render[1], dict):
            raise ValueError("render must be an image or the (image, {name: array}) pair render(..., aovs=) returns")
        render, given = render
        aovs = {**given, **(aovs or {})}
    aovs = dict(aovs or {})
    unknown = sorted(name for name in aovs if name not in AOV_NAMES)
    if unknown:  # a misspelt readout would leave the edges to the luminance, silently
        raise ValueError(f"overlay: unknown readouts {unknown} in aovs (render's names: {', '.join(AOV_NAMES)})")
    for name, value in (("alpha", alpha), ("threshold", threshold)):
        if not is_number(value):
            raise ValueError(f"{name} must be a number (got {value!r})")
    if not (0.0 <= float(alpha) <= 1.0):
        raise ValueError(f"alpha must be in [0, 1] (got {alpha!r})")
    if not (float(threshold) > 0.0 and math.isfinite(float(threshold))):
        raise ValueError(f"threshold must be > 0 and finite (got {threshold!r})")
    try:
        rgb = np.asarray(color, dtype=np.float32)
    except (TypeError, ValueError):
        rgb = np.zeros(0, np.float32)  # named below
    if isinstance(color, str) or rgb.shape != (3,) or not np.all((rgb >= 0.0) & (rgb <= 1.0)):
        raise ValueError(f"color must be 3 values in [0, 1] (got {color!r})")
    base = photo.display() if isinstance(photo, Photo) else _as_display(photo, linear=False, what="photo")
    if linear is not None and not isinstance(linear, (bool, np.bool_)):  # bool("no") is True
        raise ValueError(f"linear must be True, False or None (got {linear!r})")
    shown = _as_display(render, linear=True if linear is None else bool(linear), what="render")
    if shown.shape[:2] != base.shape[:2]:
        raise ValueError(
            f"the render is {shown.shape[1]}x{shown.shape[0]} pixels but the photograph "
            f"{base.shape[1]}x{base.shape[0]}: render at the photograph's size (Photo.camera)"
        )
    for name, value in aovs.items():
        if np.shape(value)[:2] != base.shape[:2]:
            raise ValueError(f"readout '{name}' has shape {np.shape(value)}, not the image's {base.shape[:2]}")
    # The readouts the edges and the skyline are drawn from: a number per pixel, as render gives them.
    readouts = (("object_id", "an object id per pixel (-1: none)"), ("distance", "a distance per pixel (inf: none)"))
    for name, holds in readouts:
        values = np.asarray(aovs.get(name, np.zeros(base.shape[:2])))
        if values.shape not in (base.shape[:2], base.shape[:2] + (1,)):
            raise ValueError(
                f"overlay: readout '{name}' must be (H, W) or (H, W, 1), {holds} (got shape {values.shape})"
            )
        if values.dtype.kind not in "iuf":
            raise ValueError(f"overlay: readout '{name}' must hold numbers, {holds} (got dtype {values.dtype})")
    distances = np.asarray(aovs.get("distance", np.zeros(0)), dtype=np.float64)
    wrong = ~(distances >= 0.0)  # NaN too: render gives inf where nothing was hit
    if wrong.any():
        raise ValueError(
            "overlay: readout 'distance' must hold distances >= 0 [m], inf where nothing was hit, as render gives "
            f"it (got {distances[wrong].flat[0].item()!r})"
        )
    ids = np.asarray(aovs.get("object_id", np.zeros(0, dtype=np.int32)))
    if ids.dtype.kind not in "iu":
        whole = np.mod(ids, 1.0) == 0.0 if ids.dtype.kind == "f" else np.zeros(ids.shape, dtype=bool)
        if not whole.all():
            raise ValueError(
                "overlay: readout 'object_id' must hold whole numbers, an id per pixel (-1: none) as render gives "
                f"it (got {ids[~whole].flat[0].item()!r})"
            )

    edges = _render_edges(shown, aovs, float(threshold))
    hits = _hits(aovs)
    skyline = None
    if hits is not None:
        any_hit = hits.any(axis=0)
        skyline = np.where(any_hit, np.argmax(hits, axis=0), -1).astype(np.int64)

    if mode == "difference":
        return OverlayResult(np.abs(base - shown), edges, skyline, mode)
    image = base.copy() if mode == "edges" else (1.0 - float(alpha)) * base + float(alpha) * shown
    image[edges] = rgb
    if skyline is not None:
        columns = np.nonzero(skyline >= 0)[0]
        image[skyline[columns], columns] = rgb
    return OverlayResult(image.astype(np.float32), edges, skyline, mode)
