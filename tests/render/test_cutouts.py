"""Cut-outs: a billboard picture with alpha, or an OBJ's map_d mask, clears the surface where the
picture is clear (Scene::set_cutout). Rays and shadow rays pass a point of opacity a with
probability 1 - a (pbrt-v4's stochastic alpha test); render_raster draws where a >= 1/2."""

import pickle

import numpy as np
import pytest

import refracta

SKY = (0.2, 0.4, 0.8)
RED = (1.0, 0.0, 0.0)


def write_picture(path, colour, alpha):
    """An RGBA PNG: `colour` (3,) or (H, W, 3) in [0, 1], `alpha` (H, W) in [0, 1] (linear, kept
    as stored); colours 0 and 1 survive the sRGB round trip exactly."""
    alpha = np.asarray(alpha, np.float32)
    rgb = np.broadcast_to(np.asarray(colour, np.float32), alpha.shape + (3,))
    refracta.io.write_image(path, np.dstack([rgb, alpha]), tonemap="linear", exposure=1.0)
    return str(path)


def left_opaque(size=64):
    """A picture opaque red on its left half, clear on its right, storing green there."""
    colour = np.zeros((size, size, 3), np.float32)
    colour[:, : size // 2] = RED
    colour[:, size // 2 :] = (0.0, 1.0, 0.0)
    alpha = np.zeros((size, size), np.float32)
    alpha[:, : size // 2] = 1.0
    return colour, alpha


# The wall glows and reflects nothing: what reaches the eye from it is WALL wherever the light
# falling on it comes from (the sky, partly hidden by the picture's opaque half, lights nothing).
WALL = (0.1, 0.2, 0.7)


def scene_with_wall(picture=None):
    """A glowing wall 40 m out under a constant sky, and the picture standing 10 m out, 4 m wide."""
    scene = refracta.Scene()
    scene.set_sky(SKY, SKY)
    scene.add_box((40.0, 0.0, 0.0), (1.0, 10.0, 20.0), emission=WALL, kd=(0.0, 0.0, 0.0))
    if picture is not None:
        scene.add_billboard((10.0, 0.0, 0.0), 4.0, 4.0, picture)
    return scene


CAMERA = refracta.Camera((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0, 1, 0), 30.0, 48, 48)
# The picture spans columns 24 -/+ 17 (atan(2 / 10) over a 15 deg half view), upright and facing
# the camera: its opaque left half on the image's left, its clear half on the right.
CLEAR = (slice(18, 30), slice(28, 38))
OPAQUE = (slice(18, 30), slice(10, 20))


@pytest.mark.parametrize("renderer", ["render", "render_raster"])
def test_a_billboard_shows_what_stands_behind_its_clear_parts(tmp_path, renderer):
    picture = write_picture(tmp_path / "half.png", *left_opaque())
    draw = getattr(refracta, renderer)
    kwargs = {"progress": False} if renderer == "render_raster" else {"method": "straight", "progress": False}
    with_picture = draw(scene_with_wall(picture), CAMERA, **kwargs)
    # Behind the clear half, the wall as if the picture were not there (float32 of WALL).
    np.testing.assert_array_equal(with_picture[CLEAR], np.broadcast_to(np.float32(WALL), with_picture[CLEAR].shape))
    # Its opaque half is the picture's red (lit by the sky), never the green its clear texels store.
    red = with_picture[OPAQUE]
    # No pixel there is the wall's (exactly WALL in float32).
    assert not (red == np.float32(WALL)).all(axis=-1).any()
    # The sky's red 0.2 times the picture's 1 (> 0.1); green: float32 round-off of 0 at most.
    assert np.all(red[..., 0] > 0.1) and np.all(red[..., 1] < 1e-3 * red[..., 0]), red[..., :2].max(axis=(0, 1))


VEIL = 128.0 / 255.0  # a black veil's opacity (alpha 128 of 255, stored linear)


def veils(tmp_path, distances):
    """A scene of black veils of opacity VEIL at these distances [m] (each wider than the one
    before) under the sky, and the fraction of the sky's blue its centre's rays see (144 pixels x
    256 rays)."""
    picture = write_picture(tmp_path / "veil.png", (0.0, 0.0, 0.0), np.full((4, 4), VEIL, np.float32))
    scene = refracta.Scene()
    scene.set_sky(SKY, SKY)
    for distance in distances:
        scene.add_billboard((distance, 0.0, 0.0), 0.4 * distance, 0.4 * distance, picture)
    image = refracta.render(scene, CAMERA, None, method="straight", spp=256, progress=False)
    return scene, image[18:30, 18:30, 2].mean() / SKY[2]


def test_a_half_clear_picture_lets_half_the_rays_through(tmp_path):
    # Black (absorbs everything) with opacity 0.50196: a ray passes with probability 1 - VEIL.
    scene, passed = veils(tmp_path, [10.0])
    # Bernoulli(1/2) over 36 864 rays: sigma 0.0026; 5 sigma (the hash is fixed: this is one draw).
    assert passed == pytest.approx(1.0 - VEIL, abs=0.013)
    # The raster draws it (opacity >= 1/2): black.
    raster = refracta.render_raster(scene, CAMERA, progress=False)
    assert np.all(raster[18:30, 18:30] == 0.0)


def test_each_layer_of_cut_outs_draws_its_own_chance(tmp_path):
    # Two veils: a ray passes both with probability (1 - a)^2 = 0.248. One number per ray for every
    # layer let it through both whenever it passed one: 1 - a = 0.498 (a review measured 49.6 %).
    _, passed = veils(tmp_path, [10.0, 12.0])
    # Bernoulli(0.248) over 36 864 rays: sigma 0.0023; 5 sigma.
    assert passed == pytest.approx((1.0 - VEIL) ** 2, abs=0.012)


@pytest.mark.parametrize("renderer", ["render", "render_raster"])
def test_light_passes_a_picture_where_it_is_clear(tmp_path, renderer):
    # A point light at the eye's height; the picture 5 m out, clear above its centre, opaque below;
    # a wall at 10 m. The picture's centre line projects to the wall at y = 0 (the light's
    # height): above it lit as without the picture, below it in the picture's shadow.
    alpha = np.zeros((64, 64), np.float32)
    alpha[32:] = 1.0  # image rows run down: the bottom half opaque
    picture = write_picture(tmp_path / "lower.png", (0.5, 0.5, 0.5), alpha)

    def scene(with_picture):
        s = refracta.Scene()
        s.add_box((10.5, 0.0, 0.0), (1.0, 20.0, 20.0), kd=(0.5, 0.5, 0.5))
        s.add_point_light((0.0, 0.0, 0.0), (200.0, 200.0, 200.0))
        if with_picture:
            s.add_billboard((5.0, 0.0, 0.0), 6.0, 6.0, picture)
        return s

    # Seen from behind the picture (x = 6), looking at the wall.
    camera = refracta.Camera((6.0, 0.0, 3.0), (10.0, 0.0, 0.0), (0, 1, 0), 40.0, 40, 40)
    draw = getattr(refracta, renderer)
    kwargs = {"progress": False} if renderer == "render_raster" else {"method": "straight", "progress": False}
    lit, free = draw(scene(True), camera, **kwargs), draw(scene(False), camera, **kwargs)
    upper, lower = (slice(8, 16), slice(16, 24)), (slice(24, 32), slice(16, 24))
    # Points 0.5 m or more above the shadow's edge (0.25 m on the picture, whose bilinear edge is
    # a texel, 0.094 m, wide): lit exactly as without the picture.
    np.testing.assert_array_equal(lit[upper], free[upper])
    # Lit without the picture (200 W/sr over 10 m: > 0.1), black in its shadow (no other light).
    assert free[lower].min() > 0.1 and lit[lower].max() == 0.0


def test_an_obj_map_d_mask_cuts_its_card_out(tmp_path):
    # A grey mask without alpha: its value is the opacity (MTL's map_d). Left half of the image 0.
    mask = np.zeros((64, 64, 3), np.float32)
    mask[:, 32:] = 1.0
    refracta.io.write_image(tmp_path / "mask.png", mask, tonemap="linear", exposure=1.0)
    refracta.io.write_image(tmp_path / "white.png", np.ones((8, 8, 3), np.float32), tonemap="linear", exposure=1.0)
    (tmp_path / "card.mtl").write_text("newmtl card\nKd 1 1 1\nmap_Kd white.png\nmap_d mask.png\n")
    # A 4 m card at x = 10 facing -x: u runs along -z (the camera's right to left), v up.
    (tmp_path / "card.obj").write_text(
        "mtllib card.mtl\nv 10 -2 2\nv 10 -2 -2\nv 10 2 -2\nv 10 2 2\n"
        "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl card\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n"
    )
    scene = scene_with_wall()
    scene.add_obj(str(tmp_path / "card.obj"))
    image = refracta.render(scene, CAMERA, None, method="straight", progress=False)
    # u < 1/2 (the camera's right) clear: the wall; the left half white, facing a hemisphere of
    # constant sky: radiance SKY (each cosine-distributed sky sample carries it exactly; 1e-6 is
    # float32's rounding of the sum).
    np.testing.assert_array_equal(image[CLEAR], np.broadcast_to(np.float32(WALL), image[CLEAR].shape))
    # rtol: float32's rounding of the sum, as above.
    np.testing.assert_allclose(image[OPAQUE], np.broadcast_to(np.float32(SKY), image[OPAQUE].shape), rtol=1e-6)


def test_a_grey_map_d_mask_is_read_as_data_not_colour(tmp_path):
    # A mask storing 128 of 255 everywhere is opacity 0.502 (as Blender reads masks), not the
    # 0.216 its sRGB decoding as a colour gave: a black card passes 1 - 0.502 of the rays.
    # An sRGB PNG (no gamma of its own): the linear value whose sRGB encoding is 128 of 255.
    linear = np.full((4, 4, 3), ((VEIL + 0.055) / 1.055) ** 2.4, np.float32)
    refracta.io.write_image(tmp_path / "grey.png", linear, tonemap="linear", exposure=1.0)
    (tmp_path / "black.mtl").write_text("newmtl black\nKd 0 0 0\nmap_d grey.png\n")
    (tmp_path / "card.obj").write_text(
        "mtllib black.mtl\nv 10 -2 2\nv 10 -2 -2\nv 10 2 -2\nv 10 2 2\n"
        "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl black\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n"
    )
    assert np.all(refracta.io.read_image(tmp_path / "grey.png", linear=False) == np.float32(VEIL))
    scene = refracta.Scene()
    scene.set_sky(SKY, SKY)
    scene.add_obj(str(tmp_path / "card.obj"))
    image = refracta.render(scene, CAMERA, None, method="straight", spp=256, progress=False)
    passed = image[18:30, 18:30, 2].mean() / SKY[2]
    # Bernoulli(1/2) over 36 864 rays: sigma 0.0026; 5 sigma (0.784 when decoded as a colour).
    assert passed == pytest.approx(1.0 - VEIL, abs=0.013)


def test_a_pickled_scene_keeps_its_cut_outs(tmp_path):
    picture = write_picture(tmp_path / "half.png", *left_opaque())
    scene = scene_with_wall(picture)
    copy = pickle.loads(pickle.dumps(scene))
    first = refracta.render(scene, CAMERA, None, method="straight", progress=False)
    np.testing.assert_array_equal(refracta.render(copy, CAMERA, None, method="straight", progress=False), first)


def test_a_texture_with_alpha_keeps_its_colour_where_nothing_is_cut_out(tmp_path):
    # A ground textured with a half-transparent red (no cut-out there): the stored colour, not the
    # colour times alpha (alpha is a cut-out's business alone).
    texture = write_picture(tmp_path / "red.png", RED, np.full((4, 4), 0.5, np.float32))
    plain = write_picture(tmp_path / "plain.png", RED, np.ones((4, 4), np.float32))
    images = []
    for path in (texture, plain):
        scene = refracta.Scene()
        scene.set_sky(SKY, SKY)
        scene.add_ground(-1.0, 100.0, texture=path)
        images.append(refracta.render(scene, CAMERA, None, method="straight", progress=False))
    # The same colour within the half-float texture's rounding of 0.5 x 1 / 0.5 (2^-11 relative).
    np.testing.assert_allclose(images[0][30:], images[1][30:], rtol=2e-3)
