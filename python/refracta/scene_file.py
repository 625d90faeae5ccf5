"""Scenes as TOML files: refracta.load_scene(path) -> (scene, camera, field).

    [camera]
    position = [0.0, 1.4, 0.0]          # [m]
    look_at = [300.0, 0.6, 0.0]
    up = [0.0, 1.0, 0.0]                # optional
    vfov = 2.2                          # [deg]
    size = [640, 240]                   # width, height [pixels]

    [atmosphere]                        # optional; no table = no atmosphere
    model = "PhysicalAtmosphere"        # or LogisticProfile, LinearSquaredProfile, TemperatureProfile
    surface_dt = 10.0                   # any parameter of the model, by name
    # TemperatureProfile: heights = [...], temperatures = [...]
    curved_earth = false                # true (or a radius [m]): CurvedEarth around the model

    [sun]                               # optional
    direction = [-0.35, 0.45, 0.25]
    radiance = [2.6e4, 2.45e4, 2.2e4]
    angular_diameter = 0.53

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
                                        # all: kd, ks, ns

File names (obj, textures, environment) are relative to the TOML file. Errors raise ValueError naming the file, the line
and the key; missing files raise refracta.IoError.
"""

from __future__ import annotations

import os
import re
import sys
from pathlib import Path
from typing import Any, NamedTuple, Optional

from refracta import _core

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
MATERIAL_KEYS = {"kd", "ks", "ns"}


class SceneFile(NamedTuple):
    """What a scene file describes; unpacks as (scene, camera, field)."""

    scene: _core.Scene
    camera: _core.Camera
    field: Optional[_core.IndexField]


class _Locator:
    """Finds the line of a key inside a table (or the n-th [[array]] entry) of a TOML text."""

    def __init__(self, path: Path, text: str):
        self.path = path
        self.lines = text.splitlines()

    def line_of(self, table: str, key: Optional[str] = None, index: Optional[int] = None) -> int:
        current, count, header_line = None, -1, 0
        for number, line in enumerate(self.lines, 1):
            header = re.match(r"\s*\[\[?\s*([A-Za-z0-9_.]+)\s*\]\]?", line)
            if header:
                current = header.group(1)
                if current == table:
                    count += 1
                    if index is None or count == index:
                        header_line = number
                continue
            if current == table and (index is None or count == index) and key is not None:
                if re.match(rf"\s*{re.escape(key)}\s*=", line):
                    return number
        return header_line

    def error(self, message: str, table: str, key: Optional[str] = None, index: Optional[int] = None) -> ValueError:
        line = self.line_of(table, key, index)
        where = f"[{table}]" if index is None else f"[[{table}]] #{index + 1}"
        name = f"{where} {key}" if key else where
        return ValueError(f"{self.path}:{line}: {name}: {message}")


def _number_list(value: Any, length: int) -> list:
    if not isinstance(value, list) or len(value) != length or not all(
            isinstance(v, (int, float)) and not isinstance(v, bool) for v in value):
        raise TypeError(f"must be a list of {length} numbers")
    return [float(v) for v in value]


def load_scene(path) -> SceneFile:
    """Read a TOML scene file (format in this module's docstring)."""
    path = Path(os.fspath(path))
    if not path.is_file():
        raise _core.IoError(f"no such scene file: '{path}'")
    text = path.read_text()
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise ValueError(f"{path}: malformed TOML: {error}") from None
    where = _Locator(path, text)

    def get(table: dict, name: str, key: str, convert, default=None, required=False, index=None):
        if key not in table:
            if required:
                raise where.error("missing", name, key, index)
            return default
        try:
            return convert(table[key])
        except (TypeError, ValueError, _core.IoError) as error:
            if isinstance(error, _core.IoError):
                raise
            raise where.error(str(error), name, key, index) from None

    unknown = set(data) - {"camera", "atmosphere", "sun", "sky", "objects"}
    if unknown:
        raise where.error(f"unknown table (expected camera, atmosphere, sun, sky, objects)", sorted(unknown)[0])
    if "camera" not in data:
        raise ValueError(f"{path}: the [camera] table is missing")

    cam = data["camera"]
    size = get(cam, "camera", "size", lambda v: [int(x) for x in _number_list(v, 2)], [640, 360])
    try:
        camera = _core.Camera(get(cam, "camera", "position", lambda v: _number_list(v, 3), required=True),
                              get(cam, "camera", "look_at", lambda v: _number_list(v, 3), required=True),
                              get(cam, "camera", "up", lambda v: _number_list(v, 3), [0.0, 1.0, 0.0]),
                              get(cam, "camera", "vfov", float, 45.0), size[0], size[1])
    except ValueError as error:
        raise where.error(str(error), "camera") from None

    scene = _core.Scene()
    if "sun" in data:
        sun = data["sun"]
        try:
            scene.set_sun(get(sun, "sun", "direction", lambda v: _number_list(v, 3), required=True),
                          get(sun, "sun", "radiance", lambda v: _number_list(v, 3), required=True),
                          get(sun, "sun", "angular_diameter", float, 0.53))
        except ValueError as error:
            raise where.error(str(error), "sun") from None
    if "sky" in data:
        sky = data["sky"]
        environment = get(sky, "sky", "environment", str, None)
        horizon = get(sky, "sky", "horizon", lambda v: _number_list(v, 3), required=environment is None)
        try:
            scene.set_sky(horizon, get(sky, "sky", "zenith", lambda v: _number_list(v, 3), horizon),
                          None if environment is None else str(path.parent / environment),
                          get(sky, "sky", "scale", float, 1.0))
        except ValueError as error:
            raise where.error(str(error), "sky") from None

    for index, obj in enumerate(data.get("objects", [])):
        kind = get(obj, "objects", "type", str, required=True, index=index)
        if kind not in OBJECT_KEYS:
            raise where.error(f"unknown type '{kind}' (expected {', '.join(OBJECT_KEYS)})", "objects", "type", index)
        extra = set(obj) - OBJECT_KEYS[kind] - MATERIAL_KEYS - {"type"}
        if extra:
            raise where.error(f"unknown key for a {kind}", "objects", sorted(extra)[0], index)
        material = dict(kd=get(obj, "objects", "kd", lambda v: _number_list(v, 3), [0.5, 0.5, 0.5], index=index),
                        ks=get(obj, "objects", "ks", lambda v: _number_list(v, 3), [0.0, 0.0, 0.0], index=index),
                        ns=get(obj, "objects", "ns", float, 1.0, index=index))
        texture = get(obj, "objects", "texture", str, None, index=index)
        texture = None if texture is None else str(path.parent / texture)
        try:
            if kind == "ground":
                scene.add_ground(get(obj, "objects", "height", float, 0.0, index=index),
                                 get(obj, "objects", "size", float, 20000.0, index=index), **material,
                                 texture=texture, texture_size=get(obj, "objects", "texture_size", float, 1.0, index=index))
            elif kind == "billboard":
                scene.add_billboard(get(obj, "objects", "centre", lambda v: _number_list(v, 3), required=True, index=index),
                                    get(obj, "objects", "width", float, required=True, index=index),
                                    get(obj, "objects", "height", float, required=True, index=index),
                                    get(obj, "objects", "texture", str, required=True, index=index) and texture,
                                    get(obj, "objects", "facing", lambda v: _number_list(v, 3), [-1.0, 0.0, 0.0],
                                        index=index), kd=material["kd"])
            elif kind == "box":
                scene.add_box(get(obj, "objects", "centre", lambda v: _number_list(v, 3), required=True, index=index),
                              get(obj, "objects", "size", lambda v: _number_list(v, 3), required=True, index=index),
                              **material)
            elif kind == "sphere":
                scene.add_sphere(get(obj, "objects", "centre", lambda v: _number_list(v, 3), required=True, index=index),
                                 get(obj, "objects", "radius", float, required=True, index=index), **material)
            elif kind == "obj":
                file = get(obj, "objects", "file", str, required=True, index=index)
                scene.add_obj(str(path.parent / file),
                              get(obj, "objects", "offset", lambda v: _number_list(v, 3), [0.0, 0.0, 0.0], index=index),
                              get(obj, "objects", "scale", float, 1.0, index=index))
            else:
                scene.add_mesh(get(obj, "objects", "vertices", list, required=True, index=index),
                               get(obj, "objects", "triangles", list, required=True, index=index), **material,
                               uvs=get(obj, "objects", "uvs", list, None, index=index), texture=texture)
        except ValueError as error:
            raise where.error(str(error), "objects", None, index) from None

    field = None
    if "atmosphere" in data:
        atmosphere = dict(data["atmosphere"])
        model = atmosphere.pop("model", "PhysicalAtmosphere")
        if model not in MODELS:
            raise where.error(f"unknown model '{model}' (expected {', '.join(MODELS)})", "atmosphere", "model")
        curved = atmosphere.pop("curved_earth", False)
        try:
            if model == "TemperatureProfile":
                heights = atmosphere.pop("heights", None)
                temperatures = atmosphere.pop("temperatures", None)
                if heights is None or temperatures is None:
                    raise where.error("TemperatureProfile needs heights and temperatures", "atmosphere")
                field = _core.TemperatureProfile(heights, temperatures, **atmosphere)
            else:
                field = MODELS[model](**atmosphere)
        except (ValueError, TypeError) as error:
            key = next((k for k in atmosphere if k in str(error)), None)
            raise where.error(str(error), "atmosphere", key) from None
        if curved:
            radius = 6371e3 if curved is True else float(curved)
            try:
                field = _core.CurvedEarth(field, radius)
            except ValueError as error:
                raise where.error(str(error), "atmosphere", "curved_earth") from None
    return SceneFile(scene, camera, field)


def _toml_value(value) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_toml_value(v) for v in value) + "]"
    return repr(float(value))


def atmosphere_table(field: _core.IndexField) -> str:
    """The [atmosphere] table that load_scene reads back as `field` (every parameter written)."""
    curved = None
    if isinstance(field, _core.CurvedEarth):
        curved, field = field.radius, field.base
    if field.type_name not in MODELS:
        raise ValueError(f"{field.type_name} cannot be written to a scene file (expected one of {', '.join(MODELS)})")
    lines = ["[atmosphere]", f'model = "{field.type_name}"']
    params = dict(field.params)
    if isinstance(field, _core.TemperatureProfile):
        count = len(field.heights)
        lines.append(f"heights = {_toml_value(list(field.heights))}")
        lines.append(f"temperatures = {_toml_value([params.pop(f't{i}') for i in range(count)])}")
    lines += [f"{name} = {_toml_value(value)}" for name, value in params.items()]
    if curved is not None:
        lines.append(f"curved_earth = {_toml_value(curved)}")
    return "\n".join(lines) + "\n"


def with_atmosphere(text: str, field: _core.IndexField) -> str:
    """A scene file's text with its [atmosphere] table replaced by `field` (appended if absent);
    everything else, comments included, is kept."""
    lines = text.splitlines(keepends=True)
    header = re.compile(r"^\s*\[\[?\s*([A-Za-z0-9_.\"-]+)\s*\]\]?")
    start = next((i for i, line in enumerate(lines) if (m := header.match(line)) and m.group(1) == "atmosphere"), None)
    table = atmosphere_table(field)
    if start is None:
        return text + ("" if text.endswith("\n") or not text else "\n") + "\n" + table
    end = next((i for i in range(start + 1, len(lines)) if header.match(lines[i])), len(lines))
    return "".join(lines[:start]) + table + "\n" + "".join(lines[end:]).lstrip("\n")
