"""A technical artist's trial of animation, exposure and denoising (6 December): images of tiny
values denoised to black and exposed dark, identical frames rendered at full cost, a frame folder
blocked by a file found only after rendering, a stack of frames refused by exposure_of, and an
integer option's range not named."""

import numpy as np
import pytest

import refracta
from refracta import examples, io


def noisy_image(seed=1):
    rng = np.random.default_rng(seed)
    return (0.25 + 0.5 * rng.random((24, 24, 3))).astype(np.float32)


@pytest.mark.parametrize("scale", [1e-10, 1e-20, 1e-30])
def test_denoising_an_image_of_tiny_values_is_the_same_picture_scaled(scale):
    """Open Image Denoise gave all zeros for an image scaled by 1e-10 (and, guided, values 700x its
    largest): such images are denoised scaled to 1 and scaled back."""
    image = noisy_image()
    albedo, normal = np.full_like(image, 0.5), np.zeros_like(image)
    normal[..., 1] = 1.0
    for guides in ((), (albedo, normal)):
        reference = refracta.denoise(image, *guides)
        scaled = refracta.denoise(image * np.float32(scale), *guides) / np.float32(scale)
        # float32 rounding of the scaled image and of the scale back: measured 2.7e-6 of the
        # largest value; the failure was all zeros (or 700x).
        assert np.abs(scaled - reference).max() <= 1e-4 * reference.max()


def test_denoising_a_black_image_gives_black():
    """Guided by an albedo and a normal, Open Image Denoise put back light of ~1.5e-6."""
    black = np.zeros((16, 16, 3), np.float32)
    albedo, normal = np.full_like(black, 0.5), np.zeros_like(black)
    normal[..., 1] = 1.0
    for guided in (False, True):
        assert not refracta.denoise(black, albedo, normal, guided=guided).any()  # exact zeros


@pytest.mark.parametrize("scale", [1e-3, 1e-7, 1e-9, 1e-20])
def test_automatic_exposure_is_the_same_whatever_the_units(scale):
    """A scene scaled by 1e-7 came out at half its key and by 1e-9 black: Reinhard's delta of 1e-6
    outweighed every pixel. With some black pixels (the delta's reason) it is now the same picture."""
    image = noisy_image()
    image[:3] = 0.0
    reference = io.exposure_of(image)
    # The exposure scales exactly as 1 / scale up to float32's rounding of the scaled pixels.
    assert io.exposure_of(image * np.float32(scale)) * scale == pytest.approx(reference, rel=1e-5)


def test_exposure_of_a_stack_of_frames_is_their_joint_exposure():
    """animate's docstring gives its frames one exposure by exposure_of: a (T, H, W, 3) stack is
    taken as the frames together (it was refused)."""
    frames = np.stack([noisy_image(seed) * np.float32(1 + seed) for seed in range(3)])
    joint = io.exposure_of(np.concatenate(list(frames), axis=0))
    assert io.exposure_of(frames) == joint  # the same pixels in the same order: exactly equal
    with pytest.raises(ValueError, match=r"stack of frames must have shape \(T, H, W, C\)"):
        io.exposure_of(np.ones((0, 4, 4, 3), np.float32))  # the stack named, not its reshaped (0, 4, 3)


@pytest.mark.parametrize(("setting", "said"), [({"wind": (0.0, 0.0)}, "no wind"), ({"cn2": 0.0}, "no strength")])
def test_animating_turbulence_that_cannot_move_is_refused_before_rendering(setting, said):
    """Frozen turbulence moves with its wind alone: without wind or strength every frame was the
    same, each at full cost (45 s for the README's example)."""
    example = examples.hot_road(16, 8)
    with pytest.raises(ValueError, match=f"turbulence has {said}.*every frame is the same"):
        refracta.animate(
            example.scene, example.camera, example.field, [0.0, 0.1], turbulence=refracta.Turbulence(**setting)
        )


def test_a_frame_folder_blocked_by_a_file_is_named_before_rendering(tmp_path):
    """Frame files' folders are made when written: a file in the way raised a bare FileExistsError
    after every frame had rendered."""
    blocker = tmp_path / "shots.png"
    blocker.write_bytes(b"")
    frames = np.ones((2, 4, 4, 3), np.float32)
    with pytest.raises(NotADirectoryError, match="is a file"):
        io.write_animation(str(blocker / "f{}.png"), frames)
    io.write_animation(str(tmp_path / "new" / "deeper" / "f{}.png"), frames)  # folders still made
    assert sorted(p.name for p in (tmp_path / "new" / "deeper").iterdir()) == ["f0.png", "f1.png"]


def test_an_integer_option_out_of_range_names_its_range():
    example = examples.hot_road(8, 4)
    with pytest.raises(ValueError, match=r"out of the range of RenderOptions.seed \(0 \.\. 2\^64 - 1\)"):
        refracta.render(example.scene, example.camera, example.field, seed=-1, progress=False)
