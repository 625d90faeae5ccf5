"""Scenes as TOML files: refracta.load_scene(path) -> (scene, camera, field). The format::

    [camera]
    position = [0.0, 1.4, 0.0]          # [m]
    look_at = [300.0, 0.6, 0.0]
    up = [0.0, 1.0, 0.0]                # optional
    vfov = 2.2                          # [deg]
    size = [640, 240]                   # width, height [pixels]
    # or as a photographer (Camera.photographic), instead of vfov:
    # focal_length_mm = 300.0           # on sensor_mm = [36.0, 24.0] (optional)
    # f_number = 4.0                    # optional: thin-lens depth of field, focused at
    # focus_distance = 250.0            # [m] (optional; default: the look_at distance)
    # (with vfov: aperture_diameter [m] and focus_distance, Camera.with_lens)

    [atmosphere]                        # optional; no table = no atmosphere
    model = "PhysicalAtmosphere"        # or LogisticProfile, LinearSquaredProfile, TemperatureProfile
    surface_dt = 10.0                   # any parameter of the model, by name
    # TemperatureProfile: heights = [...], temperatures = [...]
    curved_earth = false                # true (or a radius [m], >= 1000): CurvedEarth around the model

    [[atmosphere.hot_spots]]            # any number (PhysicalAtmosphere, LogisticProfile): HotSpot
    x = 120.0                           # centre on the ground [m]
    z = 0.0
    radius = 6.0                        # [m] gaussian: 1 sigma; compact: the support
    dt = 8.0                            # [K] (LogisticProfile: strength of its hot term, 1 = all)
    depth = 0.1                         # [m] optional (PhysicalAtmosphere only; absent: surface_depth)
    footprint = "gaussian"              # or "compact"; optional, default gaussian
    # (the spots' numbers are the field's parameters hot_spot<i>_x, _z, _radius, _dt, _depth,
    #  i counting the entries from 0)

    [atmosphere.turbulence]             # optional (PhysicalAtmosphere, LogisticProfile): the
    cn2 = 1e-10                         # settings of a refracta.Turbulence, which makes the same
    seed = 3                            # pattern again from them (deterministic in the seed);
    cells = 64                          # any left out take Turbulence's defaults: outer_scale
    depth = 0.1                         # (inf), inner_scale, wind = [u, w], spacing, cells (256),
                                        # depth (inf: uniform, Turbulence(depth=None)), yaw_deg
                                        # [deg] (yaw [rad]: deprecated), and time [s]
                                        # (Turbulence.at_time; default 0)

    [sun]                               # optional
    direction = [-0.35, 0.45, 0.25]
    radiance = [2.6e4, 2.45e4, 2.2e4]
    angular_diameter = 0.53
    limb_darkening = 0.6                # optional: u of I(mu) = 1 - u (1 - mu) (default 0)

    [sky]                               # optional
    horizon = [0.75, 0.82, 0.92]
    zenith = [0.22, 0.42, 0.85]
    # or: environment = "sky.exr" (equirectangular, y up), scale = 1.0

    [[objects]]                         # any number
    type = "ground"                     # ground | box | sphere | obj | mesh | billboard
    height = 0.0                        # per type: ground (height, size, texture, texture_size),
    kd = [0.1, 0.1, 0.1]                # box (centre, size), sphere (centre, radius), obj (file,
                                        # offset, scale), mesh (vertices, triangles, uvs, texture),
                                        # billboard (centre, width, height, texture, facing);
                                        # all: kd, ks, ns (Blinn-Phong shorthand; defaults
                                        # as Scene.add_*'s: kd 0.5, a ground's 0.3, a
                                        # billboard's 1), or
    material = "paint"                  # a [[materials]] entry by name (not obj, billboard);
    emission = [5.0, 5.0, 5.0]          # box, sphere, mesh: an area light [W/(m^2 sr), RGB]
                                        # (mesh: two_sided = true emits from both faces)

    [[materials]]                       # any number, referenced by name from objects
    name = "paint"
    type = "principled"                 # and the constructor parameters of refracta.shading:
    base_color = [0.6, 0.04, 0.03]      # diffuse (reflectance, texture), blinn_phong (kd, ks,
    metallic = 0.75                     # ns, texture, alpha), conductor (eta, k),
    roughness = 0.35                    # rough_conductor (alpha, alpha_u, alpha_v, eta, k),
    clearcoat = 1.0                     # dielectric (ior, sellmeier, priority), rough_dielectric
                                        # (alpha, alpha_u, alpha_v, ior, sellmeier, priority),
                                        # thin_dielectric (ior), plastic (reflectance, ior, alpha),
                                        # principled (base_color, metallic, roughness, anisotropic,
                                        # specular, specular_tint, sheen, sheen_tint, clearcoat,
                                        # clearcoat_gloss, texture), thin_film (thickness,
                                        # film_ior, eta, k, alpha), water (wind_speed,
                                        # temperature_c, salinity, body = true/false, priority)

    [geographic]                        # optional: the scene's origin on the WGS84 Earth
    lat = 28.0975                       # [deg] in (-90, 90) (not a pole) and lon [deg]: the
    lon = -15.7125                      # refracta.geo.LocalFrame of SceneFile.frame (x east, y up,
                                        # z south); its Earth radius is the [atmosphere]'s
                                        # CurvedEarth's (a flat Earth without one): render(...,
                                        # frame=) for aovs 'geographic' (refracta render --aovs)

    [[lights]]                          # any number (area lights: emission on objects)
    type = "point"                      # point (position, intensity [W/sr]),
    position = [0.0, 5.0, 0.0]          # spot (position, direction, angle [deg], intensity,
    intensity = [100.0, 100.0, 100.0]   # inner_angle, radius: soft 'embree' shadows), sun (direction,
                                        # radiance, angular_diameter, limb_darkening)

    [environment]                       # optional, instead of [sky]
    type = "physical_sky"               # constant (radiance), map (file, rotation [deg about y],
    sun_direction = [-0.5, 0.6, 0.6]    # scale), gradient (horizon, zenith, scale), physical_sky
    aerosol = 1.0                       # (sun_direction, aerosol or visibility [km],
                                        # aerial_perspective = true/false, scale: also sets the sun)

File names (obj, textures, environment) are relative to the TOML file (relocate(text, source, target) rewrites them for
a copy saved in another folder). Errors raise ValueError naming the file, the line and the key; missing files raise
refracta.IoError.

Writing: camera_table(camera) and atmosphere_table(field, turbulence) give the [camera] and
[atmosphere] tables load_scene reads back as the same camera and field; with_camera and
with_atmosphere put them into a scene file's text in place of the file's own, keeping the rest.
A field keeps only the TurbulenceLayer its turbulence made, not the settings (seed, wind, ...)
that make it again: a field with turbulence is written with the refracta.Turbulence it came from,
``atmosphere_table(field, turbulence=t)`` (a loaded file's is SceneFile.turbulence)::

    loaded = refracta.load_scene("road.toml")
    solved = refracta.edit.solve(loaded.field, loaded.camera, pairs).field
    text = Path("road.toml").read_text(encoding="utf-8")
    Path("solved.toml").write_text(with_atmosphere(text, solved, turbulence=loaded.turbulence), encoding="utf-8")
"""

from __future__ import annotations

import difflib
import math
import os
import re
import sys
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from refracta import _core
from refracta._warn import deprecated

if TYPE_CHECKING:
    from refracta.geo import LocalFrame
    from refracta.turbulence import Turbulence

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

MODELS = {
    "PhysicalAtmosphere": _core.PhysicalAtmosphere,
    "LogisticProfile": _core.LogisticProfile,
    "LinearSquaredProfile": _core.LinearSquaredProfile,
    "TemperatureProfile": _core.TemperatureProfile,
}
OBJECT_KEYS = {
    "ground": {"height", "size", "texture", "texture_size"},
    "box": {"centre", "size"},
    "sphere": {"centre", "radius"},
    "obj": {"file", "offset", "scale"},
    "mesh": {"vertices", "triangles", "uvs", "texture"},
    "billboard": {"centre", "width", "height", "texture", "facing"},
}
MATERIAL_KEYS = {"kd", "ks", "ns", "material"}
EMITTERS = {"box", "sphere", "mesh"}  # object types that take emission=
# [[materials]] type -> (refracta.shading class name, parameters); "texture" is a file name.
MATERIAL_TYPES = {
    "diffuse": ("Diffuse", {"reflectance", "texture"}),
    "blinn_phong": ("BlinnPhong", {"kd", "ks", "ns", "texture", "alpha"}),
    "conductor": ("Conductor", {"eta", "k"}),
    "rough_conductor": ("RoughConductor", {"alpha", "alpha_u", "alpha_v", "eta", "k"}),
    "dielectric": ("Dielectric", {"ior", "sellmeier", "priority"}),
    "rough_dielectric": ("RoughDielectric", {"alpha", "alpha_u", "alpha_v", "ior", "sellmeier", "priority"}),
    "thin_dielectric": ("ThinDielectric", {"ior"}),
    "plastic": ("Plastic", {"reflectance", "ior", "alpha"}),
    "principled": (
        "Principled",
        {
            "base_color",
            "metallic",
            "roughness",
            "anisotropic",
            "specular",
            "specular_tint",
            "sheen",
            "sheen_tint",
            "clearcoat",
            "clearcoat_gloss",
            "texture",
        },
    ),
    "thin_film": ("ThinFilm", {"thickness", "film_ior", "eta", "k", "alpha"}),
    "water": ("Water", {"wind_speed", "temperature_c", "salinity", "body", "priority"}),
}
LIGHT_KEYS = {
    "point": {"position", "intensity"},
    "spot": {"position", "direction", "angle", "intensity", "inner_angle", "radius"},
    "sun": {"direction", "radiance", "angular_diameter", "limb_darkening"},
}
CAMERA_KEYS = {
    "position",
    "look_at",
    "up",
    "vfov",
    "size",
    "focal_length_mm",
    "sensor_mm",
    "f_number",
    "focus_distance",
    "aperture_diameter",
}
SUN_KEYS = {"direction", "radiance", "angular_diameter", "limb_darkening"}
SKY_KEYS = {"horizon", "zenith", "environment", "scale"}
ENVIRONMENT_KEYS = {
    "constant": {"radiance"},
    "map": {"file", "rotation", "scale"},
    "gradient": {"horizon", "zenith", "scale"},
    "physical_sky": {"sun_direction", "aerosol", "visibility", "aerial_perspective", "scale"},
}


# [[atmosphere.hot_spots]] and [atmosphere.turbulence]: the models that take them, their keys.
LOCAL_MODELS = {"PhysicalAtmosphere", "LogisticProfile"}
HOT_SPOT_KEYS = {"x", "z", "radius", "dt", "depth", "footprint"}
GEOGRAPHIC_KEYS = {"lat", "lon"}
# yaw [rad]: the deprecated spelling of yaw_deg, read for one release with a DeprecationWarning.
TURBULENCE_KEYS = {
    "cn2",
    "outer_scale",
    "inner_scale",
    "seed",
    "wind",
    "spacing",
    "cells",
    "depth",
    "yaw_deg",
    "yaw",
    "time",
}
_SPOT_PARAMETER = re.compile(r"hot_spot\d+_")  # the fields' parameter names of spot i
# A table header on a line of its own: [name] or [[name]], a comment after it allowed.
_HEADER = re.compile(r"^\s*\[\[?\s*([A-Za-z0-9_.\"'-]+)\s*\]\]?\s*(#.*)?$")


class _NestedTooDeepError(ValueError):
    """TOML whose arrays or inline tables nest deeper than the parser can follow."""


# What _loads raises for text it cannot read as TOML.
_TOML_ERRORS = (tomllib.TOMLDecodeError, _NestedTooDeepError)


def _loads(text: str) -> dict:
    """tomllib.loads(text); arrays nested thousands deep raise _NestedTooDeepError (a ValueError)
    where tomllib, which recurses once per level, raised a bare RecursionError."""
    try:
        return tomllib.loads(text)
    except RecursionError:
        raise _NestedTooDeepError(
            "arrays or inline tables nested too deeply to read (Python's recursion limit)"
        ) from None


class SceneFile(tuple):
    """What a scene file describes; unpacks as (scene, camera, field), which are also attributes.

    Attributes:
        scene: the refracta.Scene; camera: the refracta.Camera; field: the atmosphere (an
            IndexField) or None without an [atmosphere] table.
        turbulence: the refracta.Turbulence of [atmosphere.turbulence] (``field.turbulence`` is its
            ``layer``), or None. Pass it to atmosphere_table / with_atmosphere to write the field
            (or one solved from it) again: the field keeps the layer, not the settings.
        frame: the refracta.geo.LocalFrame of the [geographic] table (its Earth radius the
            field's CurvedEarth's, math.inf without one), or None. ``render(..., frame=)`` takes it
            for the 'geographic' readout.
    """

    turbulence: Turbulence | None
    frame: LocalFrame | None

    def __new__(
        cls,
        scene: _core.Scene,
        camera: _core.Camera,
        field: _core.IndexField | None,
        turbulence: Turbulence | None = None,
        frame: LocalFrame | None = None,
    ):
        self = super().__new__(cls, (scene, camera, field))
        self.turbulence = turbulence
        self.frame = frame
        return self

    # As a NamedTuple's: the names of the three unpacked values (turbulence is an attribute beside them).
    _fields = ("scene", "camera", "field")

    scene = property(lambda self: self[0])
    camera = property(lambda self: self[1])
    field = property(lambda self: self[2])

    def __reduce__(self):
        return (SceneFile, (self[0], self[1], self[2], self.turbulence, self.frame))

    def __repr__(self) -> str:
        return (
            f"SceneFile(scene={self[0]!r}, camera={self[1]!r}, field={self[2]!r}, "
            f"turbulence={self.turbulence!r}, frame={self.frame!r})"
        )


class _Locator:
    """Finds the line of a key inside a table (or the n-th [[array]] entry) of a TOML text."""

    def __init__(self, path: Path, text: str):
        self.path = path
        self.lines = text.splitlines()

    def line_of(self, table: str, key: str | None = None, index: int | None = None) -> int:
        current, count, header_line = None, -1, 0
        for number, line in enumerate(self.lines, 1):
            header = _HEADER.match(line)
            if header:
                current = re.sub("[\"']", "", header.group(1))  # ["camera"] and ['camera'] are [camera]
                if current == table:
                    count += 1
                    if index is None or count == index:
                        header_line = number
                continue
            if current == table and (index is None or count == index) and key is not None:
                if re.match(rf"\s*[\"']?{re.escape(key)}[\"']?\s*=", line):
                    return number
            if current is None and not header_line and re.match(rf"\s*{re.escape(table)}\s*=", line):
                header_line = number  # a top-level key where a table belongs: camera = 5
        return header_line

    def error(self, message: str, table: str, key: str | None = None, index: int | None = None) -> ValueError:
        line = self.line_of(table, key, index)
        if not line and "." in table:  # a sub-table written inline: hot_spots = [{x = 1, ...}]
            parent, _, child = table.rpartition(".")
            line = self.line_of(parent, child)
        where = f"[{table}]" if index is None else f"[[{table}]] #{index + 1}"
        name = f"{where} {key}" if key else where
        return ValueError(f"{self.path}:{line}: {name}: {message}")

    def located(self, error: Exception, table: str, key: str | None = None, index: int | None = None) -> Exception:
        """`error` again, of its own class (refracta.IoError, TextureNotFoundError, ...), its message
        led by the file, line and key as error() writes them."""
        if str(error).startswith(str(self.path)):
            return error
        return type(error)(str(self.error(str(error), table, key, index)))


def _unknown_key_message(key: str, allowed, what: str) -> str:
    """'unknown key for a <what> (did you mean vfov?; expected ...)'."""
    close = difflib.get_close_matches(key, sorted(allowed), n=1)
    hint = f"did you mean {close[0]}? " if close else ""
    return f"unknown key for {what} ({hint}expected {', '.join(sorted(allowed))})"


def _article(word: str) -> str:
    """'an' before a vowel ('an obj object'), else 'a'."""
    return "an" if word[:1].lower() in "aeiou" else "a"


def _check_keys(table: dict, allowed, where: _Locator, name: str, what: str, index: int | None = None) -> None:
    """ValueError naming file, line and the first key of `table` not in `allowed`."""
    extra = sorted(set(table) - set(allowed))
    if extra:
        raise where.error(_unknown_key_message(extra[0], allowed, what), name, extra[0], index)


def _image_size(value: Any) -> list:
    """[width, height]: two whole numbers >= 1 (32.7 is refused, not truncated)."""
    if (
        not isinstance(value, list)
        or len(value) != 2
        or not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in value)
    ):
        raise TypeError("must be a list of 2 numbers [width, height]")
    most = _core.Camera.max_side
    if not all(v == v and abs(v) != float("inf") and float(v).is_integer() and 1 <= v <= most for v in value):
        raise ValueError(f"must be two whole numbers of pixels in [1, {most}] (got {value})")
    return [int(v) for v in value]


def _number_list(value: Any, length: int) -> list:
    if (
        not isinstance(value, list)
        or len(value) != length
        or not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in value)
    ):
        raise TypeError(f"must be a list of {length} numbers")
    return [float(v) for v in value]


def _colour(value: Any, name: str = "colour") -> list:
    """A colour: one number (grey) or three (linear RGB), each finite and >= 0."""
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        value = [value] * 3
    values = _number_list(value, 3)
    if not all(v >= 0.0 and v < float("inf") for v in values):
        raise ValueError(f"{name} must be finite and >= 0 (got {value})")
    return values


def _boolean(value: Any) -> bool:
    if not isinstance(value, bool):
        raise TypeError(f"must be true or false (got {value!r})")
    return value


def _offending_key(message: str, keys) -> str | None:
    """The parameter a constructor's error message names: the first whole word that is a key,
    then the longest key that begins a word of it (alpha -> 'alpha_u must be ...')."""
    words = re.findall(r"[A-Za-z_][A-Za-z0-9_]*", message)
    exact = [word for word in words if word in keys]
    if exact:
        return exact[0]  # the first the message names
    # A key that begins a word, not one inside it ('size' in 'texture_size' blamed a box's size).
    contained = sorted((k for k in keys if any(word.startswith(k) for word in words)), key=len, reverse=True)
    return contained[0] if contained else None


def _material_texture_entry(entries: list, name, message: str, path: Path) -> int | None:
    """The index of the [[materials]] entry `name` when `message` (a texture's IoError) is about its
    texture file, else None."""
    for index, entry in enumerate(entries):
        texture = entry.get("texture") if isinstance(entry, dict) else None
        if entry.get("name") == name and isinstance(texture, str) and str(path.parent / texture) in message:
            return index
    return None


def _materials(entries: list, where: _Locator, get, path: Path) -> dict:
    """[[materials]] -> {name: refracta.shading material}."""
    from refracta import shading

    materials = {}
    for index, entry in enumerate(entries):
        name = get(entry, "materials", "name", _text, required=True, index=index)
        kind = get(entry, "materials", "type", _text, required=True, index=index)
        if kind not in MATERIAL_TYPES:
            raise where.error(
                f"unknown material type '{kind}' (expected {', '.join(MATERIAL_TYPES)})", "materials", "type", index
            )
        if name in materials:
            raise where.error(f"material '{name}' is defined twice", "materials", "name", index)
        class_name, keys = MATERIAL_TYPES[kind]
        _check_keys(entry, keys | {"name", "type"}, where, "materials", f"{_article(kind)} {kind} material", index)
        params = {}
        for key in sorted(set(entry) & keys):
            value = entry[key]
            number = isinstance(value, (int, float)) and not isinstance(value, bool)
            numbers = (
                isinstance(value, list)
                and value
                and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in value)
            )
            if key == "texture":
                if not isinstance(value, str):
                    raise where.error("must be a file name", "materials", key, index)
                value = str(path.parent / value)
                if not Path(value).is_file():
                    raise _core.MissingFileError(f"{path}: [[materials]] #{index + 1} texture: no such file '{value}'")
            elif key == "body":  # Water's deep water body: a TOML boolean
                if not isinstance(value, bool):
                    raise where.error(f"must be true or false (got {value!r})", "materials", key, index)
            elif not (number or numbers or (key in ("ior", "eta") and isinstance(value, str))):
                raise where.error(f"must be a number or a list of numbers (got {value!r})", "materials", key, index)
            params[key] = value
        try:
            materials[name] = getattr(shading, class_name)(**params)
        except (ValueError, TypeError) as error:
            raise where.error(
                str(error).splitlines()[0], "materials", _offending_key(str(error), params), index
            ) from None
    return materials


def _environment(scene: _core.Scene, table: dict, where: _Locator, get, path: Path) -> None:
    """[environment]: constant, map, gradient or physical_sky."""
    kind = get(table, "environment", "type", _text, required=True)
    if kind not in ENVIRONMENT_KEYS:
        raise where.error(
            f"unknown environment type '{kind}' (expected {', '.join(ENVIRONMENT_KEYS)})", "environment", "type"
        )
    _check_keys(table, ENVIRONMENT_KEYS[kind] | {"type"}, where, "environment", f"{_article(kind)} {kind} environment")

    def positive(value):
        value = _real(value)
        if not (value >= 0.0 and value < float("inf")):
            raise ValueError(f"must be finite and >= 0 (got {value})")
        return value

    scale = get(table, "environment", "scale", positive, 1.0)
    try:
        if kind == "constant":
            scene.set_environment(
                get(table, "environment", "radiance", lambda v: _colour(v, "radiance"), required=True)
            )
        elif kind == "map":
            file = get(table, "environment", "file", _text, required=True)
            scene.set_environment(str(path.parent / file), get(table, "environment", "rotation", _real, None), scale)
        elif kind == "gradient":
            horizon = get(table, "environment", "horizon", lambda v: _colour(v, "horizon"), required=True)
            scene.set_sky(
                horizon, get(table, "environment", "zenith", lambda v: _colour(v, "zenith"), horizon), None, scale
            )
        else:

            def unit(value):
                vector = _number_list(value, 3)
                norm = sum(v * v for v in vector) ** 0.5
                if not norm > 0.0:
                    raise ValueError("must be a non-zero direction")
                return [v / norm for v in vector]

            def flag(value):
                if not isinstance(value, bool):
                    raise ValueError("must be true or false")
                return value

            # Only the keys given reach set_physical_sky: its defaults stay C++'s.
            given = {
                key: get(table, "environment", key, convert, None)
                for key, convert in (("aerosol", positive), ("visibility", positive), ("aerial_perspective", flag))
            }
            scene.set_physical_sky(
                get(table, "environment", "sun_direction", unit, required=True),
                scale=scale,
                below_horizon="horizon",
                **{k: v for k, v in given.items() if v is not None},
            )
    except ValueError as error:
        if str(error).startswith(str(where.path)):  # already located (a key's own check)
            raise
        raise where.error(str(error), "environment", _offending_key(str(error), table)) from None
    except _core.IoError as error:  # a file the table names: located, its kind kept
        raise where.located(error, "environment", _offending_key(str(error), table) or "file") from None


def _lights(scene: _core.Scene, entries: list, data: dict, where: _Locator, get, present) -> None:
    """[[lights]]: point, spot and sun lights (area lights are objects with emission)."""

    vector = lambda v: _number_list(v, 3)  # noqa: E731
    suns = 0
    for index, entry in enumerate(entries):
        kind = get(entry, "lights", "type", _text, required=True, index=index)
        if kind == "area":
            raise where.error("area lights are objects with emission = [r, g, b]", "lights", "type", index)
        if kind not in LIGHT_KEYS:
            raise where.error(
                f"unknown light type '{kind}' (expected {', '.join(LIGHT_KEYS)}; area lights: objects with emission)",
                "lights",
                "type",
                index,
            )
        _check_keys(entry, LIGHT_KEYS[kind] | {"type"}, where, "lights", f"{_article(kind)} {kind} light", index)
        try:
            if kind == "point":
                scene.add_point_light(
                    get(entry, "lights", "position", vector, required=True, index=index),
                    get(entry, "lights", "intensity", lambda v: _colour(v, "intensity"), required=True, index=index),
                )
            elif kind == "spot":
                position = get(entry, "lights", "position", vector, required=True, index=index)
                direction = get(entry, "lights", "direction", vector, required=True, index=index)
                intensity = get(
                    entry, "lights", "intensity", lambda v: _colour(v, "intensity"), required=True, index=index
                )
                cone = present(entry, "lights", ("angle", "inner_angle", "radius"), _real, index=index)
                if "inner_angle" in cone and "angle" not in cone:  # a falloff inside a cone the file names
                    raise where.error("inner_angle needs the cone's angle", "lights", "inner_angle", index)
                scene.add_spot_light(position, direction, intensity=intensity, **cone)
            else:
                if "sun" in data or data.get("environment", {}).get("type") == "physical_sky":
                    raise where.error("a second sun ([sun] or the physical sky has one)", "lights", "type", index)
                suns += 1
                if suns > 1:
                    raise where.error("a second sun (another [[lights]] entry has type 'sun')", "lights", "type", index)
                scene.set_sun(
                    get(entry, "lights", "direction", vector, required=True, index=index),
                    get(entry, "lights", "radiance", lambda v: _colour(v, "radiance"), required=True, index=index),
                    **present(entry, "lights", ("angular_diameter", "limb_darkening"), _real, index=index),
                )
        except ValueError as error:
            if str(error).startswith(str(where.path)):
                raise
            raise where.error(str(error), "lights", _offending_key(str(error), entry), index) from None


def _real(value: Any) -> float:
    """A number (int or float; not a bool or a string) as a float."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise TypeError(f"must be a number (got {value!r})")
    return float(value)


def _text(value: Any) -> str:
    """A TOML string (not a number or a boolean read as one: name = 5 met material = "5")."""
    if not isinstance(value, str):
        raise TypeError(f"must be a string (got {value!r})")
    return value


def _whole(value: Any) -> int:
    """A whole number (an int; not a bool, not 16.0)."""
    if isinstance(value, bool) or not isinstance(value, int):
        raise TypeError(f"must be a whole number (got {value!r})")
    return value


def _hot_spots(entries: Any, where: _Locator, get) -> list:
    """[[atmosphere.hot_spots]] -> a list of refracta.HotSpot."""
    name = "atmosphere.hot_spots"
    if not (isinstance(entries, list) and all(isinstance(e, dict) for e in entries)):
        raise where.error("must be an array of tables ([[atmosphere.hot_spots]])", "atmosphere", "hot_spots")
    spots = []
    for index, entry in enumerate(entries):
        _check_keys(entry, HOT_SPOT_KEYS, where, name, "a hot spot", index)
        numbers = {key: get(entry, name, key, _real, required=True, index=index) for key in ("x", "z", "radius", "dt")}
        depth = get(entry, name, "depth", _real, None, index=index)
        footprint = get(entry, name, "footprint", _text, "gaussian", index=index)
        try:
            spots.append(_core.HotSpot(**numbers, depth=depth, footprint=footprint))
        except ValueError as error:
            raise where.error(str(error), name, _offending_key(str(error), entry), index) from None
    return spots


def _turbulence(table: Any, where: _Locator, get):
    """[atmosphere.turbulence] -> the refracta.Turbulence its settings make (the same pattern for
    the same settings: the noise is drawn from the seed)."""
    from refracta.turbulence import Turbulence

    name = "atmosphere.turbulence"
    if not isinstance(table, dict):
        raise where.error("must be a table ([atmosphere.turbulence])", "atmosphere", "turbulence")
    _check_keys(table, TURBULENCE_KEYS, where, name, "[atmosphere.turbulence]")
    converters = dict(
        cn2=_real,
        outer_scale=_real,
        inner_scale=_real,
        seed=_whole,
        wind=lambda v: _number_list(v, 2),
        spacing=_real,
        cells=_whole,
        depth=_real,
        yaw_deg=_real,
        yaw=_real,
    )
    settings = {key: get(table, name, key, convert) for key, convert in converters.items() if key in table}
    if "yaw" in settings:
        deprecated(f"{where.path}: [atmosphere.turbulence] yaw [rad] is deprecated; write yaw_deg [deg]")
        if "yaw_deg" in settings:
            raise where.error("give yaw_deg or the deprecated yaw, not both", name, "yaw")
        settings["yaw_deg"] = math.degrees(settings.pop("yaw"))
    if settings.get("depth") == math.inf:
        settings["depth"] = None  # no envelope: uniform in height
    time = get(table, name, "time", _real, 0.0)
    try:
        turbulence = Turbulence(**settings)
        return turbulence.at_time(time) if time else turbulence
    except ValueError as error:
        raise where.error(str(error), name, _offending_key(str(error), table)) from None


def _atmosphere(table: dict, where: _Locator, get):
    """[atmosphere] (with its hot spots and turbulence) -> (field, refracta.Turbulence or None)."""
    atmosphere = dict(table)
    model = atmosphere.pop("model", "PhysicalAtmosphere")
    if model not in MODELS:
        raise where.error(f"unknown model '{model}' (expected {', '.join(MODELS)})", "atmosphere", "model")
    curved = atmosphere.pop("curved_earth", False)
    if model == "TemperatureProfile":
        allowed = {"heights", "temperatures", "pressure", "humidity", "wavelength"}
    else:
        allowed = set(dict(MODELS[model]().params))
    if model in LOCAL_MODELS:
        allowed |= {"hot_spots", "turbulence"}
    else:
        for key, what in (("hot_spots", "hot spots"), ("turbulence", "turbulence")):
            if key in atmosphere:
                raise where.error(
                    f"{model} takes no {what} (PhysicalAtmosphere and LogisticProfile do)",
                    f"atmosphere.{key}",
                    None,
                    0 if key == "hot_spots" else None,
                )
    spot_keys = sorted(k for k in atmosphere if _SPOT_PARAMETER.match(k))
    if spot_keys:
        raise where.error(
            "a hot spot is an [[atmosphere.hot_spots]] entry (x, z, radius, dt, depth, footprint), "
            "not a parameter" + ("" if model in LOCAL_MODELS else f"; {model} takes none"),
            "atmosphere",
            spot_keys[0],
        )
    _check_keys(atmosphere, allowed | {"model", "curved_earth"}, where, "atmosphere", f"a {model}")
    # A TOML boolean or string where a number belongs: the models refuse it too, but only this check
    # can name the file, line and key.
    for key in atmosphere:
        if key not in ("hot_spots", "turbulence", "heights", "temperatures"):
            get(atmosphere, "atmosphere", key, _real)
    if not isinstance(curved, bool):
        get(table, "atmosphere", "curved_earth", _real)
    spots = _hot_spots(atmosphere.pop("hot_spots"), where, get) if "hot_spots" in atmosphere else []
    turbulence = _turbulence(atmosphere.pop("turbulence"), where, get) if "turbulence" in atmosphere else None
    extra = {}
    if spots:
        extra["hot_spots"] = spots
    if turbulence is not None:
        extra["turbulence"] = turbulence.layer
    if model == "TemperatureProfile" and not {"heights", "temperatures"} <= set(atmosphere):
        raise where.error("TemperatureProfile needs heights and temperatures", "atmosphere")
    field: _core.IndexField
    try:
        if model == "TemperatureProfile":
            heights, temperatures = atmosphere.pop("heights"), atmosphere.pop("temperatures")
            field = _core.TemperatureProfile(heights, temperatures, **atmosphere)
        else:
            field = MODELS[model](**atmosphere, **extra)
    except (ValueError, TypeError) as error:
        spot = re.search(r"hot_spots\[(\d+)\]", str(error))
        if spot:  # the model refuses a spot: 'LogisticProfile: hot_spots[0] has depth 0.3; ...'
            index = int(spot.group(1))
            raise where.error(
                str(error),
                "atmosphere.hot_spots",
                _offending_key(str(error).replace(spot.group(0), ""), table["hot_spots"][index]),
                index,
            ) from None
        offending = next((k for k in atmosphere if k in str(error)), None)
        raise where.error(str(error), "atmosphere", offending) from None
    if curved is not False:  # true (CurvedEarth's own radius), or a radius: 0 and below are refused
        try:
            field = _core.CurvedEarth(field) if curved is True else _core.CurvedEarth(field, float(curved))
        except ValueError as error:
            raise where.error(str(error), "atmosphere", "curved_earth") from None
    return field, turbulence


def _refuse_non_regular(path: Path) -> None:
    """refracta.IoError for a path that exists but is not a regular file (a folder, a FIFO, a
    device): reading a FIFO waits for a writer that may never come."""
    if path.exists() and not path.is_file():
        raise _core.IoError(f"cannot read scene file '{path}': not a regular file")


def read_scene_text(path) -> str:
    """A scene file's text as load_scene reads it: UTF-8 (TOML's encoding), a byte-order mark
    (Windows editors write one) read past, as TOML parsers commonly do (tomllib refused it:
    "Invalid statement (at line 1, column 1)"). UnicodeDecodeError for text that is not UTF-8;
    refracta.IoError for a path that is not a regular file (a folder, or a FIFO, which would
    block), FileNotFoundError for a missing one."""
    path = Path(os.fspath(path))
    _refuse_non_regular(path)
    return path.read_text(encoding="utf-8-sig")


def load_scene(path, size=None) -> SceneFile:
    """Read a TOML scene file (format in this module's docstring): a SceneFile, which unpacks as
    (scene, camera, field) and has the [atmosphere.turbulence]'s refracta.Turbulence as .turbulence.
    size: (width, height) [pixels] in place of the file's [camera] size, the camera built at it as
    if the file said so (a focal_length_mm lens fits its sensor at that size: Camera.resized keeps
    the vertical field of view instead)."""
    path = Path(os.fspath(path))
    if size is not None:
        try:  # a tuple or array of numpy's ints as a list of Python's (the camera takes them)
            if isinstance(size, (tuple, list, np.ndarray)):
                size = [v.item() if isinstance(v, np.generic) else v for v in size]
            size = _image_size(size)
        except (TypeError, ValueError) as error:
            raise ValueError(f"load_scene: size {error}") from None
    if not path.exists():
        raise _core.MissingFileError(f"no such scene file: '{path}'")
    try:
        text = read_scene_text(path)  # refuses a folder or a FIFO
    except UnicodeDecodeError as error:
        raise ValueError(
            f"{path}: not a TOML scene file (not UTF-8 text: {error.reason} at byte {error.start})"
        ) from None
    try:
        data = _loads(text)
    except _TOML_ERRORS as error:
        raise ValueError(f"{path}: malformed TOML: {error}") from None
    where = _Locator(path, text)

    def get(table: dict, name: str, key: str, convert, default=None, required=False, index=None):
        if key not in table:
            if required:
                raise where.error("missing", name, key, index)
            return default
        try:
            return convert(table[key])
        except (TypeError, ValueError, OverflowError, _core.IoError) as error:
            if isinstance(error, _core.IoError):
                raise
            raise where.error(str(error), name, key, index) from None

    def present(table: dict, name: str, keys, convert, index=None) -> dict:
        """The keys the table gives, converted, as keywords: the rest take the call's own defaults."""
        return {key: get(table, name, key, convert, index=index) for key in keys if key in table}

    tables = ("camera", "atmosphere", "geographic", "sun", "sky", "environment", "materials", "lights", "objects")
    unknown = set(data) - set(tables)
    if unknown:
        first = sorted(unknown)[0]
        value = data[first]
        if isinstance(value, dict) or (isinstance(value, list) and value and all(isinstance(e, dict) for e in value)):
            raise where.error(f"unknown table (expected {', '.join(tables)})", first)
        # A key outside every table (version = 2): the format has no version; a newer file's
        # keys are refused by name, never ignored.
        raise where.error(f"unknown key outside the tables (a scene file holds only {', '.join(tables)})", first)
    for name in ("materials", "lights", "objects"):
        if name in data and not (isinstance(data[name], list) and all(isinstance(e, dict) for e in data[name])):
            raise where.error("must be an array of tables ([[" + name + "]])", name)
    for name in ("camera", "atmosphere", "geographic", "sun", "sky", "environment"):
        if name in data and not isinstance(data[name], dict):
            raise where.error("must be a table ([" + name + "])", name)
    if "camera" not in data:
        raise ValueError(f"{path}: the [camera] table is missing")

    cam = data["camera"]
    _check_keys(cam, CAMERA_KEYS, where, "camera", "[camera]")
    # No size: the camera's own default (Camera's 640 x 360, a lens's sensor shape 960 px long).
    size = get(cam, "camera", "size", _image_size, [None, None]) if size is None else size
    # A field of view, or a lens on a sensor; a thin lens from either (f_number with the focal
    # length, aperture_diameter with vfov).
    for a, b in (
        ("vfov", "focal_length_mm"),
        ("vfov", "f_number"),
        ("vfov", "sensor_mm"),
        ("focal_length_mm", "aperture_diameter"),
    ):
        if a in cam and b in cam:
            raise where.error(f"give {a} or {b}, not both", "camera", b)
    for key, needs in (
        ("f_number", "focal_length_mm"),
        ("sensor_mm", "focal_length_mm"),
        ("focus_distance", "f_number or aperture_diameter"),
    ):
        if key in cam and not any(k in cam for k in needs.split(" or ")):
            raise where.error(f"needs {needs}", "camera", key)
    position = get(cam, "camera", "position", lambda v: _number_list(v, 3), required=True)
    look_at = get(cam, "camera", "look_at", lambda v: _number_list(v, 3), required=True)
    up = get(cam, "camera", "up", lambda v: _number_list(v, 3), [0.0, 1.0, 0.0])
    lens = {key: get(cam, "camera", key, _real) for key in ("f_number", "focus_distance") if key in cam}
    if "sensor_mm" in cam:
        lens["sensor_mm"] = tuple(get(cam, "camera", "sensor_mm", lambda v: _number_list(v, 2)))
    focal_length = get(cam, "camera", "focal_length_mm", _real)
    vfov = get(cam, "camera", "vfov", _real)
    aperture = get(cam, "camera", "aperture_diameter", _real)
    try:
        if focal_length is not None:
            camera = _core.Camera.photographic(
                position, look_at, focal_length, width=size[0], height=size[1], up=up, **lens
            )
        else:
            view = {} if vfov is None else {"vfov": vfov}  # none: Camera's default
            camera = _core.Camera(position, look_at, up, width=size[0], height=size[1], **view)
            if aperture is not None:
                if "focus_distance" not in lens:
                    raise where.error("needs focus_distance", "camera", "aperture_diameter")
                camera = camera.with_lens(aperture, lens["focus_distance"])
    except ValueError as error:
        if str(error).startswith(str(path)):
            raise
        raise where.error(str(error), "camera", _offending_key(str(error), cam)) from None

    scene = _core.Scene()
    materials = _materials(data.get("materials", []), where, get, path)
    if "sky" in data and "environment" in data:
        raise where.error("give [sky] or [environment], not both", "environment")
    if "environment" in data:
        _environment(scene, data["environment"], where, get, path)
    if "sun" in data:
        if data.get("environment", {}).get("type") == "physical_sky":
            raise where.error("the physical sky sets its own sun: remove [sun]", "sun")
        sun = data["sun"]
        _check_keys(sun, SUN_KEYS, where, "sun", "[sun]")
        try:
            scene.set_sun(
                get(sun, "sun", "direction", lambda v: _number_list(v, 3), required=True),
                get(sun, "sun", "radiance", lambda v: _colour(v, "radiance"), required=True),
                **present(sun, "sun", ("angular_diameter", "limb_darkening"), _real),
            )
        except ValueError as error:
            if str(error).startswith(str(where.path)):  # already located (a key's own check)
                raise
            raise where.error(str(error), "sun", _offending_key(str(error), sun)) from None
    if "sky" in data:
        sky = data["sky"]
        _check_keys(sky, SKY_KEYS, where, "sky", "[sky]")
        environment = get(sky, "sky", "environment", _text, None)
        horizon = get(sky, "sky", "horizon", lambda v: _number_list(v, 3), required=environment is None)
        try:
            scene.set_sky(
                horizon,
                get(sky, "sky", "zenith", lambda v: _number_list(v, 3), horizon),
                None if environment is None else str(path.parent / environment),
                get(sky, "sky", "scale", _real, 1.0),
            )
        except ValueError as error:  # zenith left out is horizon's: a bad one is horizon's fault
            blamed = _offending_key(str(error), sky) or ("horizon" if "horizon" in sky else None)
            raise where.error(str(error), "sky", blamed) from None
        except _core.IoError as error:  # the environment file: located, its kind kept (as [environment]'s)
            raise where.located(error, "sky", "environment") from None

    _lights(scene, data.get("lights", []), data, where, get, present)

    for index, obj in enumerate(data.get("objects", [])):
        kind = get(obj, "objects", "type", _text, required=True, index=index)
        if kind not in OBJECT_KEYS:
            raise where.error(f"unknown type '{kind}' (expected {', '.join(OBJECT_KEYS)})", "objects", "type", index)
        allowed = (
            OBJECT_KEYS[kind]
            | {"type"}
            | (
                MATERIAL_KEYS
                if kind in ("ground", "box", "sphere", "mesh")
                else {"kd"}
                if kind == "billboard"
                else set()
            )
        )
        allowed |= {"emission"} if kind in EMITTERS else set()
        allowed |= {"two_sided"} if kind == "mesh" else set()
        _check_keys(obj, allowed, where, "objects", f"{_article(kind)} {kind} object", index)
        # The shorthand's defaults are the Scene.add_* calls' own (None: theirs; a ground's kd 0.3).
        material = dict(
            kd=get(obj, "objects", "kd", lambda v: _number_list(v, 3), None, index=index),
            ks=get(obj, "objects", "ks", lambda v: _number_list(v, 3), None, index=index),
            ns=get(obj, "objects", "ns", _real, None, index=index),
        )
        if "material" in obj:
            name = get(obj, "objects", "material", _text, index=index)
            if name not in materials:
                known = ", ".join(materials) or "none defined"
                raise where.error(f"unknown material '{name}' (materials: {known})", "objects", "material", index)
            shorthand = sorted({"kd", "ks", "ns"} & set(obj))
            if shorthand:
                raise where.error("give material or the kd/ks/ns shorthand, not both", "objects", shorthand[0], index)
            material = dict(material=materials[name])
        if kind in EMITTERS:
            material["emission"] = get(obj, "objects", "emission", lambda v: _colour(v, "emission"), None, index=index)
        if kind == "mesh":
            material |= present(obj, "objects", ("two_sided",), _boolean, index=index)
        texture = get(obj, "objects", "texture", _text, None, index=index)
        texture = None if texture is None else str(path.parent / texture)
        try:
            if kind == "ground":
                scene.add_ground(
                    **present(obj, "objects", ("height", "size", "texture_size"), _real, index=index),
                    **material,
                    texture=texture,
                )
            elif kind == "billboard":
                image = get(obj, "objects", "texture", _text, required=True, index=index)
                scene.add_billboard(
                    get(obj, "objects", "centre", lambda v: _number_list(v, 3), required=True, index=index),
                    get(obj, "objects", "width", _real, required=True, index=index),
                    get(obj, "objects", "height", _real, required=True, index=index),
                    str(path.parent / image) if image else "",
                    get(obj, "objects", "facing", lambda v: _number_list(v, 3), [-1.0, 0.0, 0.0], index=index),
                    kd=material["kd"],
                )
            elif kind == "box":
                scene.add_box(
                    get(obj, "objects", "centre", lambda v: _number_list(v, 3), required=True, index=index),
                    get(obj, "objects", "size", lambda v: _number_list(v, 3), required=True, index=index),
                    **material,
                )
            elif kind == "sphere":
                scene.add_sphere(
                    get(obj, "objects", "centre", lambda v: _number_list(v, 3), required=True, index=index),
                    get(obj, "objects", "radius", _real, required=True, index=index),
                    **material,
                )
            elif kind == "obj":
                file = get(obj, "objects", "file", _text, required=True, index=index)
                scene.add_obj(
                    str(path.parent / file),
                    get(obj, "objects", "offset", lambda v: _number_list(v, 3), [0.0, 0.0, 0.0], index=index),
                    get(obj, "objects", "scale", _real, 1.0, index=index),
                )
            else:
                scene.add_mesh(
                    get(obj, "objects", "vertices", list, required=True, index=index),
                    get(obj, "objects", "triangles", list, required=True, index=index),
                    **material,
                    uvs=get(obj, "objects", "uvs", list, None, index=index),
                    texture=texture,
                )
        except ValueError as error:
            if str(error).startswith(str(where.path)):  # already located (a key's own check)
                raise
            # A texture the geometry cannot take came with its material (a box has no uvs).
            blamed = _offending_key(str(error), obj) or (
                "material" if "texture" in str(error) and "material" in obj else None
            )
            raise where.error(str(error), "objects", blamed, index) from None
        except _core.IoError as error:  # a file the entry names (an OBJ, its MTL, a texture): located
            source = _material_texture_entry(data.get("materials", []), obj.get("material"), str(error), path)
            if source is not None:  # its material's texture: read when the object takes the material
                raise where.located(error, "materials", "texture", source) from None
            raise where.located(error, "objects", _offending_key(str(error), obj) or "file", index) from None

    field, turbulence = None, None
    if "atmosphere" in data:
        field, turbulence = _atmosphere(data["atmosphere"], where, get)
    frame = _geographic(data["geographic"], field, where, get) if "geographic" in data else None
    return SceneFile(scene, camera, field, turbulence, frame)


def _geographic(table: dict, field, where: _Locator, get) -> LocalFrame:
    """The [geographic] table's refracta.geo.LocalFrame: the origin (lat, lon) [deg], the Earth
    radius of the field's CurvedEarth (math.inf, a flat Earth, without one)."""
    from refracta import geo

    _check_keys(table, GEOGRAPHIC_KEYS, where, "geographic", "[geographic]")

    def degrees(value: Any) -> float:
        number = _real(value)
        if not math.isfinite(number):
            raise ValueError(f"must be a finite number of degrees (got {value!r})")
        return number

    lat = get(table, "geographic", "lat", degrees, required=True)
    lon = get(table, "geographic", "lon", degrees, required=True)
    if not -90.0 < lat < 90.0:
        raise where.error(f"must be in (-90, 90) deg, not a pole (got {lat!r})", "geographic", "lat")
    if not -360.0 <= lon <= 360.0:  # refracta.geo's range: east of Greenwich, [-180, 180] or [0, 360]
        raise where.error(f"must be in [-360, 360] deg (got {lon!r})", "geographic", "lon")
    radius = math.inf if field is None else field.earth_radius
    return geo.LocalFrame(lat, lon, earth_radius=radius)


def _toml_value(value) -> str:
    """A TOML literal: booleans, whole numbers, strings, lists; every other number as a float
    (repr: exact round trip; inf and nan are TOML too)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return _toml_string(value)
    if isinstance(value, int):
        return str(value)
    if isinstance(value, (list, tuple, np.ndarray)):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    return repr(float(value))


# TOML's escapes of a basic string; the other control characters (TOML refuses them raw) as \uXXXX.
_STRING_ESCAPES = {"\\": "\\\\", '"': '\\"', "\b": "\\b", "\t": "\\t", "\n": "\\n", "\f": "\\f", "\r": "\\r"}


def _toml_string(value: str) -> str:
    """`value` as a TOML basic string: a file name holding a newline ("a\\nb.obj" in the file)
    was written back with a raw one, which is not TOML."""
    escaped = (_STRING_ESCAPES.get(c) or (f"\\u{ord(c):04X}" if ord(c) < 0x20 or ord(c) == 0x7F else c) for c in value)
    return '"' + "".join(escaped) + '"'


def camera_table(camera: _core.Camera) -> str:
    """The [camera] table that load_scene reads back as `camera` (position, look_at, up [m], vfov
    [deg], size [pixels]; a thin lens as aperture_diameter and focus_distance [m]).

    Raises:
        ValueError: not a refracta.Camera; a jittered camera (a scene file has no jitter map:
            camera.without_jitter() writes the rest).
    """
    if not isinstance(camera, _core.Camera):
        raise ValueError(f"camera_table: camera must be a refracta.Camera (got {type(camera).__name__})")
    if camera.jitter is not None:
        raise ValueError(
            "camera_table: a scene file keeps no jitter map, and this camera has one: write "
            "camera.without_jitter(), and keep the map beside the file (np.save)"
        )
    lines = [
        "[camera]",
        f"position = {_toml_value([float(x) for x in camera.position])}",
        f"look_at = {_toml_value([float(x) for x in camera.look_at])}",
        f"up = {_toml_value([float(x) for x in camera.up])}",
        f"vfov = {_toml_value(camera.vfov)}",
        f"size = [{int(camera.width)}, {int(camera.height)}]",
    ]
    if camera.aperture_diameter > 0:
        lines += [
            f"aperture_diameter = {_toml_value(camera.aperture_diameter)}",
            f"focus_distance = {_toml_value(camera.focus_distance)}",
        ]
    return "\n".join(lines) + "\n"


def _same_layer(a: _core.TurbulenceLayer, b: _core.TurbulenceLayer) -> bool:
    """Whether two TurbulenceLayers are the same turbulence: the same object, or (a pickled copy)
    the same placement and grid, and the same values at a few points."""
    if a is b:
        return True
    if (a.scale, a.depth, a.yaw, a.grid.shape, a.grid.spacing, a.grid.bound) != (
        b.scale,
        b.depth,
        b.yaw,
        b.grid.shape,
        b.grid.spacing,
        b.grid.bound,
    ) or not np.array_equal(a.offset, b.offset):
        return False
    # 16 points spread over a tile, low in the envelope: another seed differs at every one of them.
    size = a.grid.shape[0] * a.grid.spacing
    points = np.random.default_rng(0).uniform(0.0, 1.0, (16, 3)) * [size, 0.05 * size, size]
    return np.array_equal(a.evaluate(points)[0], b.evaluate(points)[0])


def _turbulence_lines(layer: _core.TurbulenceLayer | None, turbulence) -> list:
    """The [atmosphere.turbulence] table of `turbulence` (a refracta.Turbulence) after checking that
    it made `layer`, the field's (ValueError otherwise)."""
    if layer is None and turbulence is None:
        return []
    if layer is None:
        raise ValueError("atmosphere_table: turbulence was given but the field carries none")
    if turbulence is None:
        raise ValueError(
            "atmosphere_table: the field carries turbulence, and a field keeps only its TurbulenceLayer, "
            "not the settings (seed, wind, ...) that make it: pass turbulence=the refracta.Turbulence "
            "whose layer it is (load_scene(...).turbulence for a field read from a file)"
        )
    if not _same_layer(layer, turbulence.layer):
        raise ValueError(
            "atmosphere_table: turbulence is not the refracta.Turbulence whose layer the field carries "
            "(another seed, grid, strength, depth, yaw or time)"
        )
    settings = [
        ("cn2", turbulence.cn2),
        ("outer_scale", turbulence.outer_scale),
        ("inner_scale", turbulence.inner_scale),
        ("seed", int(turbulence.seed)),
        ("wind", list(turbulence.wind)),
        ("spacing", turbulence.spacing),
        ("cells", int(turbulence.cells)),
        ("depth", math.inf if turbulence.depth is None else turbulence.depth),
        ("yaw_deg", turbulence.yaw_deg),
        ("time", turbulence.time),
    ]
    return ["", "[atmosphere.turbulence]"] + [f"{name} = {_toml_value(value)}" for name, value in settings]


def atmosphere_table(field: _core.IndexField, turbulence=None) -> str:
    """The [atmosphere] table that load_scene reads back as `field`: every parameter, the hot spots
    (their current values, field.hot_spots) as [[atmosphere.hot_spots]] entries, and the
    turbulence as [atmosphere.turbulence].

    Args:
        field: PhysicalAtmosphere, LogisticProfile, LinearSquaredProfile or TemperatureProfile,
            or a CurvedEarth around one.
        turbulence: the refracta.Turbulence whose layer the field carries (field.turbulence), whose
            settings are written; None for a field without turbulence.

    Raises:
        ValueError: another kind of field (or not a field); a field with turbulence and no
            `turbulence` (or another one than it carries); `turbulence` for a field without.
    """
    if not isinstance(field, _core.IndexField):
        raise ValueError(
            f"atmosphere_table: field must be a refracta field, one of {', '.join(MODELS)} (got {type(field).__name__})"
        )
    curved = None
    if isinstance(field, _core.CurvedEarth):
        curved, field = field.radius, field.base
    if field.type_name not in MODELS:
        raise ValueError(f"{field.type_name} cannot be written to a scene file (expected one of {', '.join(MODELS)})")
    local = field if isinstance(field, (_core.PhysicalAtmosphere, _core.LogisticProfile)) else None
    layer = local.turbulence if local is not None else None
    turbulence_lines = _turbulence_lines(layer, turbulence)
    lines = ["[atmosphere]", f'model = "{field.type_name}"']
    params = {name: value for name, value in field.params.items() if not _SPOT_PARAMETER.match(name)}
    if isinstance(field, _core.TemperatureProfile):
        count = len(field.heights)
        lines.append(f"heights = {_toml_value(list(field.heights))}")
        lines.append(f"temperatures = {_toml_value([params.pop(f't{i}') for i in range(count)])}")
    lines += [f"{name} = {_toml_value(value)}" for name, value in params.items()]
    if curved is not None:
        lines.append(f"curved_earth = {_toml_value(curved)}")
    for spot in local.hot_spots if local is not None else []:
        lines += ["", "[[atmosphere.hot_spots]]"] + [
            f"{name} = {_toml_value(getattr(spot, name))}" for name in ("x", "z", "radius", "dt")
        ]
        if spot.depth is not None:
            lines.append(f"depth = {_toml_value(spot.depth)}")
        lines.append(f"footprint = {_toml_value(spot.footprint)}")
    return "\n".join(lines + turbulence_lines) + "\n"


def _toml_lines(text: str) -> list[str]:
    """A TOML text's lines, their ends kept: split at line feeds only (TOML's newline; str.splitlines
    also splits at U+2028 and U+0085, which a quoted key may hold)."""
    return re.findall(r"[^\n]*\n|[^\n]+$", text)


def _lines_at_top_level(text: str) -> list[tuple[str, bool]]:
    """The lines of a TOML text (_toml_lines), each with whether its first
    character after blanks is code at the top level: outside comments and strings (multi-line ones
    too: a "[camera]" line inside one is text) and outside arrays spanning lines. Only such a
    line can be a table header or a root key."""
    code = _code_positions(text)
    brackets = [(m.start(), 1 if m[0] in "[{" else -1) for m in re.finditer(r"[\[\]{}]", text) if code[m.start()]]
    lines, depth, offset, k = [], 0, 0, 0
    for line in _toml_lines(text):
        first = offset + len(line) - len(line.lstrip(" \t"))
        lines.append((line, depth == 0 and bool(code[first])))
        offset += len(line)
        while k < len(brackets) and brackets[k][0] < offset:
            depth += brackets[k][1]
            k += 1
    return lines


def _table_headers(text: str) -> dict[int, str]:
    """{line index: the table's first key} of the table headers of a TOML text ([a.b] and [[a.b]],
    keys bare or quoted: ["camera"] is [camera])."""
    headers = {}
    for index, (line, top) in enumerate(_lines_at_top_level(text)):
        if top and line.lstrip(" \t").startswith("["):
            try:
                headers[index] = next(iter(tomllib.loads(line)))
            except (tomllib.TOMLDecodeError, StopIteration):
                raise ValueError(f"line {index + 1}: cannot read the table header {line.strip()!r}") from None
    return headers


def _with_table(text: str, name: str, table: str, first: bool) -> str:
    """`text` (a scene file) with its table `name` and every sub-table of it ([name.*], [[name.*]];
    the name bare or quoted) replaced by `table`, at the place of the first of them; without them,
    `table` is put first (`first`; after any keys before the first header, which would otherwise
    become the table's) or last. Everything else, comments included, is kept (the comment lines
    after a replaced table's last key too: they are the next table's); the replaced tables' own
    comments go with them. A byte-order mark (a text read without encoding="utf-8-sig") is dropped,
    or the first header would go unseen."""
    text = _without_root_keys(text.removeprefix("\ufeff"), name)
    newline = "\r\n" if "\r\n" in text else "\n"  # a Windows file's line ends kept in the new lines too
    table = table.replace("\n", newline)
    lines = _toml_lines(text)
    headers = _table_headers(text)
    starts = list(headers)
    ends = starts[1:] + [len(lines)]
    owned = [(start, end) for start, end in zip(starts, ends) if headers[start] == name]
    if not owned:
        if not first:
            return text + ("" if text.endswith("\n") or not text else newline) + newline + table
        top = starts[0] if starts else len(lines)
        keys = [line for line, code in _lines_at_top_level(text)[:top] if code and line.strip()[:1] not in ("", "#")]
        if not keys:
            return table + newline + text
        before = "".join(lines[:top])
        return before + ("" if before.endswith("\n") else newline) + table + newline + "".join(lines[top:])
    loose = _loose_lines(text)
    kept, previous = [], 0
    for start, end in owned:
        kept.append("".join(lines[previous:start]))
        while end > start + 1 and loose[end - 1]:  # comments before the next table are that table's
            end -= 1
        previous = end
    rest = "".join(lines[previous:])
    # The new table where the first old one was; the others' lines dropped (with the blank lines after them).
    return kept[0] + table + newline + "".join(part.lstrip("\r\n") for part in kept[1:] + [rest])


def _loose_lines(text: str) -> list[bool]:
    """Per line of a TOML text: whether it is blank or a comment line (not a line of a multi-line
    string that starts with #)."""
    code = _code_positions(text)
    loose, offset = [], 0
    for line in _toml_lines(text):
        stripped = line.strip()
        outside = offset == 0 or bool(code[offset - 1])  # the line break before it is not in a string
        loose.append(outside and (not stripped or stripped.startswith("#")))
        offset += len(line)
    return loose


def _without_root_keys(text: str, name: str) -> str:
    """`text` without the lines before its first table header that define table `name` as a key
    (``name = { ... }``, an inline table, or dotted ``name.key = ...``): _with_table replaces the
    table, so such a line would define it twice (tomllib: "Cannot declare ('atmosphere',) twice"),
    its comment with it. ValueError where such a definition spans lines (a multi-line array inside it)."""
    key = re.compile(rf"^\s*(?:{re.escape(name)}|\"{re.escape(name)}\"|'{re.escape(name)}')\s*[=.]")
    lines = _lines_at_top_level(text)
    kept: list[str] = []
    for number, (line, top) in enumerate(lines, 1):
        if top and line.lstrip(" \t").startswith("["):  # the first header: tables from here on
            return "".join(kept + [line for line, _ in lines[number - 1 :]])
        if top and key.match(line):
            try:
                tomllib.loads(line)
            except tomllib.TOMLDecodeError:
                raise ValueError(
                    f"line {number}: {name} is written over several lines there; write it as a table under a "
                    f"[{name}] header so that it can be replaced"
                ) from None
            continue
        kept.append(line)
    return "".join(kept)


def _same_toml(a, b) -> bool:
    """Whether two parsed TOML values are the same (tables in any order; NaN equal to NaN)."""
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(_same_toml(a[key], b[key]) for key in a)
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(_same_toml(x, y) for x, y in zip(a, b))
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    return type(a) is type(b) and a == b


def _table_edited(caller: str, text: str, name: str, table: str | None, first: bool = False) -> str:
    """`text` (a scene file) with its table `name` replaced by `table` (_with_table; None: removed,
    _without_table), checked: ValueError for a text that is not TOML (before anything is changed),
    and for a result that is not TOML, or does not hold exactly `table` as `name` and everything
    else as the text did (a table the edit could not find in place), rather than broken text."""
    if not isinstance(text, str):
        raise ValueError(f"{caller}: text must be a scene file's text, a str (got {type(text).__name__})")
    try:
        expected = _loads(text.removeprefix("\ufeff"))
    except _TOML_ERRORS as error:
        raise ValueError(f"{caller}: the text is not TOML: {error}") from None
    expected.pop(name, None)
    if table is None:
        out = _without_table(text, name)
    else:
        expected[name] = tomllib.loads(table)[name]
        out = _with_table(text, name, table, first)
    try:
        same = _same_toml(_loads(out), expected)
        problem = f"it would not hold {'no' if table is None else 'the new'} [{name}] and the rest as it was"
    except _TOML_ERRORS as error:
        same, problem = False, f"it would not be TOML: {error}"
    if not same:
        raise ValueError(
            f"{caller}: cannot {'remove' if table is None else 'replace'} the [{name}] table of this text in "
            f"place ({problem}); write [{name}] as one table under a [{name}] header"
        )
    return out


def relocate(text: str, source, target) -> str:
    """A scene file's text with its relative file names (objects' `file` and `texture`, materials'
    `texture`, [environment] `file`, [sky] `environment`) rewritten so that they name the same
    files when the text is saved in folder `target` instead of folder `source` (the folder the
    names are relative to: the file's own). Names that cannot be made relative (another drive)
    become absolute; absolute names are kept. Everything else, comments and strings included, is
    kept. Symbolic links are followed as opening the file would ("link/../x" is beside the
    link's target).

    Raises:
        ValueError: text that is not TOML; a file name written so that it cannot be rewritten in
            place (a key spelled with escapes, "fi\\u006ce"; bare and quoted keys are rewritten).
    """
    try:
        expected_names = _file_names(_loads(text))
    except _TOML_ERRORS as error:
        raise ValueError(f"relocate: the text is not TOML: {error}") from None
    source, target = Path(os.fspath(source)), Path(os.fspath(target))
    if source.resolve() == target.resolve():
        return text
    real_target = os.path.realpath(target)

    def moved(name: str) -> str:
        if not name or Path(name).is_absolute():
            return name  # a billboard's "" (no image) too
        full = os.path.realpath(source / name)
        try:
            return Path(os.path.relpath(full, real_target)).as_posix()
        except ValueError:  # another drive
            return Path(full).as_posix()

    code = _code_positions(text)

    def rewritten(match: re.Match) -> str:
        if not (match.start() == 0 or code[match.start() - 1]):
            return match[0]  # in a comment or a string (a key's own quotes, "file" = ..., are its)
        return match["key"] + _toml_value(moved(tomllib.loads("v = " + match["value"])["v"]))

    out = _FILE_VALUE.sub(rewritten, text)
    expected = sorted(moved(name) for name in expected_names)
    try:
        found = sorted(_file_names(_loads(out)))
    except _TOML_ERRORS as error:
        raise ValueError(
            f"relocate: the file names cannot be rewritten in place (the text would not be TOML: {error})"
        ) from None
    if expected != found:
        missed = sorted(set(expected) - set(found))
        raise ValueError(f"relocate: cannot rewrite the file name(s) {missed} where they are written")
    return out


# The keys whose string values are file names (relocate), wherever their table.
_FILE_KEYS = ("file", "texture", "environment")
# A file name's key (a whole key, bare or quoted: not my-file's) and its string value, as a scene file writes
# them: multi-line strings first, then one-line ones.
_FILE_KEY = "|".join(_FILE_KEYS)
_FILE_VALUE = re.compile(
    rf"""(?P<key>(?<![A-Za-z0-9_-])(?:"(?:{_FILE_KEY})"|'(?:{_FILE_KEY})'|(?:{_FILE_KEY}))\s*=\s*)"""
    r"""(?P<value>\"\"\"(?:[^"\\]|\\.|"(?!""))*\"\"\"|'\'\'[\s\S]*?'\'\'|"(?:[^"\\\n]|\\.)*"|'[^'\n]*')"""
)


# Where _code_positions looks next: a comment or a string opens at these characters only.
_COMMENT_OR_QUOTE = re.compile("[#\"']")
# The rest of a string after its opening quote(s), up to and with its closing one(s) (escapes, \\ and
# \" among them, are two characters; a multi-line basic string's body may hold one or two quotes).
_STRING_REST = {
    '"""': re.compile(r'(?:[^"\\]|\\[\s\S]|"(?!""))*(?:"""|\Z)'),
    "'''": re.compile(r"[\s\S]*?(?:'''|\Z)"),
    '"': re.compile(r'(?:[^"\\\n]|\\[\s\S])*(?:["\n]|\Z)'),
    "'": re.compile(r"[^'\n]*(?:['\n]|\Z)"),
}


def _code_positions(text: str) -> bytearray:
    """Per character of a TOML text: whether (1) or not (0) it lies outside comments and strings."""
    code = bytearray(b"\x01") * (len(text) + 1)
    i, n = 0, len(text)
    while True:
        found = _COMMENT_OR_QUOTE.search(text, i)
        if found is None:
            return code
        i = found.start()
        if text[i] == "#":
            end = text.find("\n", i)
            end = n if end < 0 else end
        else:
            quote = text[i : i + 3] if text.startswith(('"""', "'''"), i) else text[i]
            rest = _STRING_REST[quote].match(text, i + len(quote))
            end = rest.end() if rest is not None else n  # (each pattern matches an unterminated rest)
            while len(quote) == 3 and end < n and text[end] == quote[0]:  # """a"""": 'a"'
                end += 1
        code[i:end] = bytes(end - i)
        i = end


def _file_names(data) -> list[str]:
    """Every string under a file-name key (relocate's) in parsed TOML, at any depth."""
    names: list[str] = []
    if isinstance(data, dict):
        for key, value in data.items():
            if key in _FILE_KEYS and isinstance(value, str):
                names.append(value)
            else:
                names += _file_names(value)
    elif isinstance(data, list):
        for value in data:
            names += _file_names(value)
    return names


def with_atmosphere(text: str, field: _core.IndexField | None, turbulence=None) -> str:
    """A scene file's text with its [atmosphere] table (its hot spots and turbulence included)
    replaced by atmosphere_table(field, turbulence) (appended if absent); everything else,
    comments included, is kept. field None (load_scene's field of a file without air, rendered
    straight): the [atmosphere] tables removed. ValueError for a text that is not TOML, and
    where the table cannot be replaced in place (the result is checked: never broken TOML)."""
    if field is None:
        if turbulence is not None:
            raise ValueError("with_atmosphere: turbulence was given for no field (None)")
        return _table_edited("with_atmosphere", text, "atmosphere", None)
    return _table_edited("with_atmosphere", text, "atmosphere", atmosphere_table(field, turbulence))


def _without_table(text: str, name: str) -> str:
    """`text` (a scene file) without its table `name` and its sub-tables (see _with_table)."""
    text = _without_root_keys(text.removeprefix("\ufeff"), name)
    marker = "# refracta: a removed table\n"
    replaced = _with_table(text, name, marker, first=False)
    if marker not in replaced.replace(marker, "", 1) and not replaced.endswith(marker):
        return replaced.replace(marker + "\n", "", 1)
    return text  # no such table: appended, so nothing to remove


def with_camera(text: str, camera: _core.Camera) -> str:
    """A scene file's text with its [camera] table replaced by camera_table(camera) (if absent, put
    before the first table, after any root keys); everything else, comments included, is kept.
    ValueError for a text that is not TOML, and where the table cannot be replaced in place (the
    result is checked: never broken TOML)."""
    return _table_edited("with_camera", text, "camera", camera_table(camera), first=True)
