"""Small scenes of every kind of geometry, material and light, and module-level work functions
(they pickle by name into worker processes) for the scale-out tests."""

from __future__ import annotations

import numpy as np

import refracta
from refracta import lights, shading

# A tiny image: every pixel is a separate seeded computation, so 24 x 16 exercises the whole
# pipeline in well under a second.
WIDTH, HEIGHT = 24, 16


def write_texture(path) -> str:
    """A 16 x 16 RGB checker (values in [0, 1]) as an EXR file; returns its path."""
    y, x = np.mgrid[0:16, 0:16]
    checker = ((x // 4 + y // 4) % 2).astype(np.float32)
    image = np.stack([0.2 + 0.6 * checker, 0.3 + 0.2 * checker, 0.9 - 0.7 * checker], axis=-1)
    refracta.io.write_image(str(path), image)
    return str(path)


def environment_map() -> np.ndarray:
    """An 8 x 16 equirectangular map, brighter toward the zenith and with a warm patch."""
    rows = np.linspace(1.0, 0.2, 8, dtype=np.float32)[:, None, None]
    image = np.broadcast_to(rows * np.array([0.5, 0.6, 0.9], np.float32), (8, 16, 3)).copy()
    image[2, 5] = (4.0, 3.0, 1.0)
    return image


def every_kind_scene(texture: str, sky: str) -> refracta.Scene:
    """Meshes (uvs, normals, a texture), a box, exact spheres, a billboard, every material, an
    emissive mesh and sphere, point and spot lights, a sun, and the sky `sky`: 'environment' (a
    map), 'physical' (set_physical_sky, scaled: a tabulated sun), 'gradient' or 'constant'."""
    scene = refracta.Scene()
    scene.add_ground(0.0, 200.0, texture=texture, texture_size=2.0)
    vertices = np.array([[8, 0, -2], [8, 0, 2], [8, 3, 2], [8, 3, -2]], float)
    uvs = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float)
    normals = np.array([[-1, 0.1, 0], [-1, 0, 0.1], [-1, 0, 0], [-1, -0.1, 0]], float)
    scene.add_mesh(
        vertices,
        [[0, 2, 1], [0, 3, 2]],
        uvs=uvs,
        normals=normals,
        kd=(0.6, 0.5, 0.4),
        ks=(0.2, 0.2, 0.2),
        ns=30.0,
        texture=texture,
    )
    materials = [
        shading.Diffuse((0.7, 0.2, 0.1)),
        shading.BlinnPhong(0.3, (0.4, 0.4, 0.2), 50.0, alpha=0.8),
        shading.Conductor((0.2, 0.9, 1.1), (3.9, 2.4, 2.2)),
        shading.RoughConductor(alpha_u=0.1, alpha_v=0.3, eta=1.5, k=4.0),
        shading.Dielectric("bk7", priority=1),
        shading.RoughDielectric(0.2, ior=1.33),
        shading.ThinDielectric(1.52),
        shading.Plastic((0.1, 0.3, 0.6), ior=1.45, alpha=0.15),
        shading.Principled((0.6, 0.1, 0.1), metallic=0.5, roughness=0.3, clearcoat=1.0, sheen=0.2),
        shading.ThinFilm(420.0, film_ior=1.4, eta=1.2, k=2.0, alpha=0.05),
    ]
    for i, material in enumerate(materials):
        z = -4.5 + i
        if i % 2:
            scene.add_sphere((6.0, 0.45, z), 0.4, material=material)
        else:
            scene.add_box((6.0, 0.4, z), (0.7, 0.8, 0.7), material=material)
    scene.add_billboard((10.0, 1.5, 0.0), 2.0, 1.0, texture)
    scene.add_mesh([[7, 2.5, -1], [7, 2.5, 1], [7, 3.5, 0]], [[0, 1, 2]], emission=(3.0, 2.0, 1.0), two_sided=True)
    scene.add_sphere((7.5, 2.0, 2.5), 0.3, emission=(5.0, 5.0, 4.0))
    scene.add_point_light((3.0, 3.0, 1.0), (20.0, 20.0, 15.0))
    scene.add_spot_light((2.0, 4.0, -1.0), (1.0, -1.0, 0.2), angle=50.0, intensity=(40.0, 30.0, 30.0), radius=0.2)
    if sky == "environment":
        scene.set_environment(environment_map(), rotation=30.0, scale=0.8)
        scene.set_sun((0.6, 0.5, 0.3), (200.0, 190.0, 170.0), angular_diameter=2.0, limb_darkening=0.4)
    elif sky == "physical":
        scene.set_physical_sky((0.5, 0.2, 0.4), aerosol=2.0, scale=0.01)
    elif sky == "gradient":
        scene.set_sky(horizon=(0.8, 0.8, 0.9), zenith=(0.2, 0.3, 0.8))
        scene.add_light(lights.SunLight((0.3, 0.8, 0.1), 100.0))
    elif sky == "constant":
        scene.set_environment((0.4, 0.45, 0.5))
    else:
        raise ValueError(sky)
    return scene


def camera() -> refracta.Camera:
    return refracta.Camera((0.0, 1.2, 0.3), (8.0, 0.9, -0.2), vfov=60.0, width=WIDTH, height=HEIGHT)


def hot_road() -> refracta.PhysicalAtmosphere:
    return refracta.PhysicalAtmosphere(surface_dt=12.0, surface_depth=0.3)


def render_quietly(scene, camera, field, **options) -> np.ndarray:
    """refracta.render without a progress bar (run in worker processes)."""
    return refracta.render(scene, camera, field, progress=False, **options)


def ior_and_gradient(field, points) -> tuple:
    return field.ior(points), field.grad_ior(points)


def custom_ior(points):
    """A module-level CustomField index: a warm layer near y = 0 (n rises with height)."""
    return 1.0 + 2.7e-4 * (1.0 - 0.03 * np.exp(-points[:, 1] / 0.5))


def custom_grad(points):
    grad = np.zeros_like(points)
    grad[:, 1] = 2.7e-4 * 0.03 / 0.5 * np.exp(-points[:, 1] / 0.5)
    return grad
