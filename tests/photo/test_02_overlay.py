"""refracta.photo.overlay on a tiny synthetic pair: a render of one box (rows 3-5, columns 2-6 of a
8 x 10 image) over a grey photograph, with and without its readouts."""

import numpy as np
import pytest

from refracta import photo

H, W = 8, 10
BOX = (slice(3, 6), slice(2, 7))
GREY = 0.5
RED = (1.0, 0.0, 0.0)


def _pair():
    picture = np.full((H, W, 3), GREY, dtype=np.float32)
    render = np.zeros((H, W, 3), dtype=np.float32)
    render[BOX] = 1.0
    inside = np.zeros((H, W), dtype=bool)
    inside[BOX] = True
    readouts = {
        "object_id": np.where(inside, 0, -1).astype(np.float32),
        "distance": np.where(inside, 100.0, np.inf).astype(np.float32),
    }
    return picture, render, inside, readouts


def _expected_edges(inside):
    """The box's boundary on both sides: pixels with a 4-neighbour on the other side."""
    edges = np.zeros_like(inside)
    for axis in (0, 1):
        differs = np.diff(inside, axis=axis)
        if axis == 0:
            edges[1:] |= differs
            edges[:-1] |= differs
        else:
            edges[:, 1:] |= differs
            edges[:, :-1] |= differs
    return edges


@pytest.mark.parametrize("readout", ["object_id", "distance"])
def test_edges_of_a_known_box_land_on_its_boundary(readout):
    picture, render, inside, readouts = _pair()
    result = photo.overlay(picture, (render, {readout: readouts[readout]}), mode="edges", color=RED)
    expected = _expected_edges(inside)
    assert expected.sum() == (3 * 5 - 1 * 3) + 2 * (3 + 5)  # 12 on the box's rim, 16 just outside it
    np.testing.assert_array_equal(result.edges, expected)
    np.testing.assert_array_equal(result.skyline, [-1, -1, 3, 3, 3, 3, 3, -1, -1, -1])
    np.testing.assert_array_equal(result.image[expected], np.tile(RED, (expected.sum(), 1)))
    np.testing.assert_array_equal(result.image[~expected], picture[~expected])  # the photograph elsewhere


def test_blend_and_difference_mix_the_display_values():
    picture, render, inside, readouts = _pair()
    blend = photo.overlay(picture, render, mode="blend", aovs=readouts, alpha=0.25, linear=False)
    plain = ~blend.edges
    mixed = 0.75 * picture[plain] + 0.25 * render[plain]
    np.testing.assert_allclose(blend.image[plain], mixed, rtol=0, atol=1e-7)  # float32 round-off of the mix
    difference = photo.overlay(picture, render, mode="difference", linear=False)
    np.testing.assert_allclose(difference.image, np.abs(picture - render), rtol=0, atol=0)
    # Without readouts the edges are the render's luminance steps (here the same boundary) and there is no skyline.
    assert difference.skyline is None
    np.testing.assert_array_equal(difference.edges, _expected_edges(inside))


def test_the_figure_shows_the_image():
    picture, render, _, readouts = _pair()
    result = photo.overlay(photo.Photo(picture, linear=False), (render, readouts), mode="edges")
    shown = result.figure.axes[0].get_images()[0].get_array()
    np.testing.assert_array_equal(np.asarray(shown), result.image)


def test_bad_input_is_refused():
    picture, render, _, readouts = _pair()
    with pytest.raises(ValueError, match="mode must be one of .*blend.*difference.*edges"):
        photo.overlay(picture, render, mode="sum")
    with pytest.raises(ValueError, match="the render is 5x8 pixels but the photograph 10x8"):
        photo.overlay(picture, render[:, :5])
    with pytest.raises(ValueError, match="readout 'distance' has shape"):
        photo.overlay(picture, render, aovs={"distance": readouts["distance"][:4]})
    with pytest.raises(ValueError, match="alpha must be in"):
        photo.overlay(picture, render, alpha=2.0)


def test_a_photo_overshooting_by_resampling_is_clipped_not_refused():
    picture, render, _, _ = _pair()
    ringing = np.clip(picture, 0.0, 1.0) * 1.005 - 0.002  # bicubic resampling overshoots a little
    np.testing.assert_array_equal(photo.overlay(ringing, render, mode="edges").image >= 0.0, True)


@pytest.mark.parametrize(
    "change, match",
    [
        (dict(picture=np.nan), "photo holds NaN or inf"),  # was an all-NaN image without an error
        (dict(picture=200.0), r"photo holds display values, which must be in \[0, 1\] \(got 200 to 200; 8-bit"),
        (dict(picture="photo.png"), "photo must be an image array \\(got the path 'photo.png'"),
        (dict(render=np.inf), "render holds NaN or inf"),
        (dict(color="red"), "color must be 3 values"),
        (dict(alpha="0.5"), "alpha must be a number"),
        (dict(threshold=True), "threshold must be a number"),
    ],
)
def test_bad_pictures_and_options_are_named(change, match):
    picture, render, _, _ = _pair()
    options = {k: v for k, v in change.items() if k not in ("picture", "render")}
    if "picture" in change:
        value = change["picture"]
        picture = value if isinstance(value, str) else np.full_like(picture, value)
    if "render" in change:
        render = np.full_like(render, change["render"])
    with pytest.raises(ValueError, match=match):
        photo.overlay(picture, render, **options)


def test_edges_of_a_rendered_box_land_on_its_projection():
    """A real render with readouts: a 2 m cube whose front face, 20 m from the eye, spans exactly
    8 x 8 pixels of 0.25 m (tan(vfov / 2) = 0.2 over 32 rows), its edges on pixel boundaries, so
    every sample of a pixel sees the same thing and the expected edges are exact."""
    import refracta

    scene = refracta.Scene()
    scene.set_sky((0.2, 0.3, 0.5))
    scene.add_box((0.0, 1.0, -21.0), (2.0, 2.0, 2.0))
    vfov = float(np.degrees(2.0 * np.arctan(0.2)))
    camera = refracta.Camera((0.0, 1.0, 0.0), (0.0, 1.0, -21.0), (0.0, 1.0, 0.0), vfov, 48, 32)
    rendered = refracta.render(scene, camera, None, spp=2, progress=False, aovs=["object_id", "distance"])
    inside = np.zeros((32, 48), dtype=bool)
    inside[12:20, 20:28] = True  # rows 16 -+ 4, columns 24 -+ 4
    expected = _expected_edges(inside)
    for readout in ("object_id", "distance"):
        result = photo.overlay(np.full((32, 48, 3), GREY), (rendered[0], {readout: rendered[1][readout]}), mode="edges")
        np.testing.assert_array_equal(result.edges, expected)
        np.testing.assert_array_equal(result.skyline, np.where((np.arange(48) >= 20) & (np.arange(48) < 28), 12, -1))


def test_an_object_id_readout_of_fractions_is_refused():
    # A new user's trial: overlay took an 'object_id' of 0.5s and drew edges from it.
    picture, render, _, readouts = _pair()
    with pytest.raises(ValueError, match="'object_id' must hold whole numbers.*0.5"):
        photo.overlay(picture, render, aovs={"object_id": np.full((H, W), 0.5)})
    photo.overlay(picture, render, aovs={"object_id": readouts["object_id"]})  # whole floats are ids
