"""White furnace scenes (shared/SHADING.md section 9): a convex object in a constant environment
of radiance 1 sees nothing but the environment, so a Diffuse(R) surface renders R after one bounce
and after any number ('direct' and 'path' alike), R = 1 renders 1, and a lossless smooth
Dielectric renders 1 (the (eta_i/eta_t)^2 radiance scalings cancel on the way out). Inside a
closed emissive enclosure of uniform emission Le and Diffuse(R) walls the radiance is the same
everywhere, L = Le sum_{k=0}^{D} R^k for max_depth D (Le / (1 - R) in the limit): a check of depth
counting, MIS against area-light sampling and Russian roulette (unbiased, so the limit holds)."""

import numpy as np
import pytest

import refracta
from refracta.lights import ConstantEnvironment
from refracta.shading import Dielectric, Diffuse

from .shading_scenes import box_mesh, check_against

EXACT = 1e-5  # float32 film: cosine-sampled constant sky against a Lambertian is zero-variance
SEEDS = 16  # per-pixel standard errors from 16 seeds (Student-t bound, shading_scenes.check_against)
MEAN_SIGMAS = 4.0  # the image mean's relative error, in its standard errors


def sphere_camera(size=12):
    return refracta.Camera([0.0, 0.0, 2.6], [0.0, 0.0, 0.0], vfov=30, width=size, height=size)


def renders(scene, camera, seeds=SEEDS, **options):
    return np.array(
        [refracta.render(scene, camera, None, seed=s, progress=False, **options)[..., 0] for s in range(seeds)]
    )


def assert_unbiased(images, expected, mask):
    worst, bound, relative, relative_stderr = check_against(images, expected, mask)
    assert worst <= bound, (worst, bound)
    assert relative <= MEAN_SIGMAS * relative_stderr + 1e-6, (relative, relative_stderr)


@pytest.mark.parametrize("transport", ["direct", "path"])
@pytest.mark.parametrize("reflectance", [1.0, 0.5])
def test_convex_diffuse_sphere_in_a_cosine_sampled_furnace_is_exactly_R(transport, reflectance):
    scene = refracta.Scene()
    scene.add_sphere([0, 0, 0], 1.0, material=Diffuse(reflectance))
    scene.set_environment((1.0, 1.0, 1.0))
    image = refracta.render(scene, sphere_camera(), None, transport=transport, spp=4, max_depth=50, progress=False)
    # Background pixels show the environment (1); sphere pixels R: every pixel is R or 1.
    values = image[..., 0].ravel()
    on_sphere = np.abs(values - reflectance) <= EXACT
    assert np.all(on_sphere | (np.abs(values - 1.0) <= EXACT))
    assert on_sphere.mean() > 0.3  # the sphere fills the middle of the frame


@pytest.mark.parametrize("transport", ["direct", "path"])
@pytest.mark.parametrize("reflectance", [1.0, 0.5])
def test_convex_diffuse_sphere_in_a_uniformly_sampled_furnace(transport, reflectance):
    # Uniform sphere sampling of the environment: NEE and BSDF sampling both noisy, MIS-weighted.
    scene = refracta.Scene()
    scene.add_sphere([0, 0, 0], 1.0, material=Diffuse(reflectance))
    scene.add_light(ConstantEnvironment((1.0, 1.0, 1.0), sampling="uniform"))
    camera = sphere_camera()
    images = renders(scene, camera, transport=transport, spp=8, max_depth=50)
    background = np.all(np.abs(images - 1.0) <= EXACT, axis=0)
    expected = np.where(background, 1.0, reflectance)
    assert_unbiased(images, expected, ~background)


@pytest.mark.parametrize("shape", ["sphere", "box"])
def test_lossless_glass_renders_the_furnace(shape):
    # Without Russian roulette every path through lossless smooth glass carries exactly 1: reflect
    # with probability F (weight 1) or refract (weight (eta_i/eta_t)^2, undone on the way out).
    scene = refracta.Scene()
    if shape == "sphere":
        scene.add_sphere([0, 0, 0], 1.0, material=Dielectric(1.5))
    else:
        scene.add_box([0, 0, 0], [1.2, 1.2, 1.2], material=Dielectric(1.5))
    scene.set_environment((1.0, 1.0, 1.0))
    camera = refracta.Camera([0.3, 0.4, 2.6], [0.0, 0.0, 0.0], vfov=30, width=12, height=12)
    exact = refracta.render(scene, camera, None, transport="path", spp=16, max_depth=64, rr_depth=1000, progress=False)
    assert np.all(np.abs(exact - 1.0) <= EXACT)
    # With roulette (from 3 events on) the paths are killed or boosted: unbiased only on average.
    # Its per-pixel noise is a rare-event (kill) distribution that a t-test from 16 seeds does not
    # describe, so the glass pixels are tested together: their mean over each seed's image.
    images = renders(scene, camera, transport="path", spp=16, max_depth=64)
    glass = images.std(0) > 0
    assert glass.mean() > 0.2  # the glass box covers a fifth of the view at least: the test is not vacuous
    means = images[:, glass].mean(1)
    assert abs(means.mean() - 1.0) <= MEAN_SIGMAS * means.std(ddof=1) / np.sqrt(SEEDS), means


def inward_cube(half):
    """A closed cube of side 2 half, every triangle's counter-clockwise front facing inward."""
    return box_mesh([-half] * 3, [half] * 3, inward=True)


@pytest.mark.parametrize(
    "transport,reflectance,depth",
    [("direct", 0.5, 1), ("path", 0.5, 1), ("path", 0.5, 3), ("path", 0.5, 60), ("path", 0.8, 80)],
)
def test_emissive_enclosure_radiance_is_the_truncated_series(transport, reflectance, depth):
    le = 1.0
    scene = refracta.Scene()
    scene.add_mesh(*inward_cube(1.0), material=Diffuse(reflectance), emission=(le, le, le))
    camera = refracta.Camera([0.1, 0.2, 0.3], [0.5, -0.4, -1.0], vfov=90, width=12, height=12)
    images = renders(scene, camera, transport=transport, spp=8, max_depth=depth)
    expected = le * sum(reflectance**k for k in range(depth + 1))
    worst, bound, relative, relative_stderr = check_against(
        images, np.full(images.shape[1:], expected), np.ones(images.shape[1:], bool)
    )
    # Without Russian roulette (depth below rr_depth = 3) every pixel's estimate is near-normal;
    # with it, rare survivors weighted 1/q make single pixels heavy-tailed (one in 144 reached
    # z = 6.8 against the 6.7 bound): there the image mean over all pixels and seeds carries the test.
    if depth < refracta.RenderOptions().rr_depth:
        assert worst <= bound, (worst, bound)
    assert relative <= MEAN_SIGMAS * relative_stderr + 1e-6, (relative, relative_stderr)
