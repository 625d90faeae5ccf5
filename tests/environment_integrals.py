"""Closed-form references for lights given as equirectangular maps (tests of both renderers)."""

import numpy as np


def irradiance_under_map(radiance_map, shading_normal=(0.0, 1.0, 0.0), rows=2048, columns=4096):
    """E = integral of L(d) (d . ns) over the directions above both the geometric plane (y > 0) and
    the shading normal ns's (ns = +y: the upper hemisphere's irradiance on an upward surface), L by
    the EnvironmentLight's orientation and bilinear interpolation (rows at v = j / (H - 1), columns
    centred at (i + 1/2) / W; d = (sin phi sin theta, cos theta, -cos phi sin theta)), by the
    midpoint rule on a grid far finer than the map."""
    radiance_map = np.asarray(radiance_map, dtype=float)
    normal = np.asarray(shading_normal, dtype=float) / np.linalg.norm(shading_normal)
    height, width = radiance_map.shape
    v = (np.arange(rows) + 0.5) / rows
    u = (np.arange(columns) + 0.5) / columns
    row = v * (height - 1)
    j = np.clip(np.floor(row).astype(int), 0, height - 2)
    fv = (row - j)[:, None]
    column = u * width - 0.5
    i = np.floor(column).astype(int)
    fu = column - i
    left, right = i % width, (i + 1) % width
    upper = radiance_map[j][:, left] * (1 - fu) + radiance_map[j][:, right] * fu
    lower = radiance_map[j + 1][:, left] * (1 - fu) + radiance_map[j + 1][:, right] * fu
    radiance = upper * (1 - fv) + lower * fv
    theta, phi = np.pi * v[:, None], 2.0 * np.pi * u[None, :]
    d = np.stack(np.broadcast_arrays(np.sin(phi) * np.sin(theta), np.cos(theta), -np.cos(phi) * np.sin(theta)), -1)
    cosine = d @ normal
    allowed = (d[..., 1] > 0.0) & (cosine > 0.0)
    weight = np.sin(theta) * (np.pi / rows) * (2.0 * np.pi / columns)
    return float(np.sum(np.where(allowed, radiance * cosine, 0.0) * weight))
