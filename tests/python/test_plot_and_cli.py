"""The ray-fan plot and the command line."""

from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
import pytest

import refracta
from refracta import cli, plot


def test_ray_fan_draws_one_line_per_ray_and_the_profiles(hot_road):
    elevations = np.linspace(-0.5, 0.3, 9)
    figure = plot.ray_fan(hot_road, 1.5, elevations, 800.0)
    rays, temperature, index = figure.axes[:3]
    ray_lines = [line for line in rays.get_lines() if len(line.get_xdata()) > 2]
    assert len(ray_lines) == len(elevations)
    # Rays steeper than the critical depression (~0.25 deg) end on the road, drawn dashed.
    dashed = [line for line in ray_lines if line.get_linestyle() == "--"]
    assert len(dashed) == int(np.sum(elevations < -0.26))
    for line in dashed:
        assert line.get_ydata()[-1] == pytest.approx(0.0, abs=1e-9)
    # The temperature panel shows the surface layer: 25 C at the road.
    t = temperature.get_lines()[0]
    assert t.get_xdata()[np.argmin(np.abs(t.get_ydata()))] == pytest.approx(25.0, abs=0.5)
    assert len(index.get_lines()) == 1
    plt.close(figure)


def test_ray_fan_without_temperature_or_ground():
    figure = plot.ray_fan(refracta.LogisticProfile(), 1.5, [-5, 0, 5], 30.0, stop_height=None)
    assert len(figure.axes) == 3  # rays, index, colour bar
    plt.close(figure)


def test_ray_fan_ground_and_method_are_the_deprecated_spellings(hot_road):
    """ground= and method= warn and draw exactly the rays of stop_height= and trace=."""
    new = plot.ray_fan(hot_road, 1.5, [-1.0, 0.5], 200.0, stop_height=0.2, trace="rk45")
    with pytest.warns(DeprecationWarning, match="ground= is deprecated; call it stop_height="):
        with pytest.warns(DeprecationWarning, match="method= is deprecated; call it trace="):
            old = plot.ray_fan(hot_road, 1.5, [-1.0, 0.5], 200.0, ground=0.2, method="rk45")
    for line_new, line_old in zip(new.axes[0].get_lines(), old.axes[0].get_lines(), strict=True):
        np.testing.assert_array_equal(line_new.get_xydata(), line_old.get_xydata())  # the same traces: bit-identical
    plt.close(new)
    plt.close(old)


def test_ray_fan_rejects_bad_input(hot_road):
    with pytest.raises(ValueError, match="elevations"):
        plot.ray_fan(hot_road, 1.5, [], 100.0)
    with pytest.raises(ValueError, match="eye_height"):
        plot.ray_fan(hot_road, -1.0, [0.0], 100.0)


def test_demo_writes_the_renders_and_ray_fans(tmp_path):
    assert cli.main(["demo", "--out", str(tmp_path), "--size", "72x24"]) == 0
    written = sorted(p.name for p in tmp_path.glob("*.png"))
    assert written == [
        "cold_sea.png",
        "fata_morgana.png",
        "green_flash.png",
        "hot_road.png",
        "hot_spot.png",
        "rays_cold_sea.png",
        "rays_editor.png",
        "rays_hot_road.png",
    ]
    assert all((tmp_path / name).stat().st_size > 5_000 for name in written)
    from PIL import Image  # (Pillow: matplotlib's dependency, which animate writes GIFs with)

    for name in ("shimmer.gif", "shimmer_noise.gif"):
        with Image.open(tmp_path / name) as gif:
            assert gif.n_frames > 1
    with pytest.raises(SystemExit):
        cli.main(["demo", "--size", "0x5"])


def test_cli_renders_a_scene_file_with_path_tracing_and_spectral_colour(tmp_path):
    scene_file = Path(__file__).resolve().parents[1] / "data" / "hot_road.toml"
    for extra in (["--transport", "path", "--spp", "4", "--max-depth", "3"], ["--spectral"]):
        output = tmp_path / "image.exr"
        assert cli.main(["render", str(scene_file), "-o", str(output), "--size", "48x16", *extra]) == 0
        image = refracta.io.read_image(output)
        assert image.shape[:2] == (16, 48) and np.all(np.isfinite(image)) and image.max() > 0.0


def test_cli_size_builds_a_lens_camera_at_that_size(tmp_path):
    # A trial: --size resized the file's camera keeping its vfov, so a 300 mm lens rendered at
    # 48 x 48 saw 2.29 deg where the same file saying size = [48, 48] sees 4.58 (24 mm high).
    data = Path(__file__).resolve().parents[1] / "data"
    text = (data / "hot_road.toml").read_text()
    assert "vfov = 2.2" in text and "size = [96, 32]" in text
    for name in ("tent.obj", "tent.mtl"):  # the file's objects, by relative path
        (tmp_path / name).write_bytes((data / name).read_bytes())
    lens = text.replace("vfov = 2.2", "focal_length_mm = 300.0")
    (tmp_path / "lens.toml").write_text(lens)
    camera = refracta.load_scene(tmp_path / "lens.toml", size=(48, 48)).camera
    expected = refracta.Camera.photographic((0, 0, 0), (1, 0, 0), 300.0, width=48, height=48).vfov
    assert camera.vfov == pytest.approx(expected, rel=1e-12)  # the same closed form: round-off only
    assert (camera.width, camera.height) == (48, 48)
    assert cli.main(["render", str(tmp_path / "lens.toml"), "-o", str(tmp_path / "a.exr"), "--size", "48x48"]) == 0
    (tmp_path / "sized.toml").write_text(lens.replace("size = [96, 32]", "size = [48, 48]"))
    assert cli.main(["render", str(tmp_path / "sized.toml"), "-o", str(tmp_path / "b.exr")]) == 0
    np.testing.assert_array_equal(
        refracta.io.read_image(tmp_path / "a.exr"), refracta.io.read_image(tmp_path / "b.exr")
    )
    with pytest.raises(ValueError, match="load_scene: size must be two whole numbers"):
        refracta.load_scene(tmp_path / "lens.toml", size=(48, 0))


def test_edit_report_draws_into_a_given_figure_outside_pyplot(hot_road):
    """figure=matplotlib.figure.Figure(): the same drawing, and pyplot never knows of it (the
    editor draws it on a worker thread)."""
    from matplotlib.figure import Figure

    from refracta.edit import PointPair, solve

    eye = np.array([0.0, 1.4, 0.0])
    pairs = []
    for elevation in (-0.2, -0.12):
        e = np.radians(elevation)
        direction = np.array([np.cos(e), np.sin(e), 0.0])
        path = refracta.trace_ray(hot_road, eye, direction, tol=1e-10, max_length=450.0, stop_height=0.0)
        pairs.append(PointPair(eye + direction, path.point_at(400.0)[0]))
    result = solve(hot_road.with_params(surface_dt=8.0), eye, pairs, free=["surface_dt"], stop_height=0.0)
    open_figures = plt.get_fignums()
    figure = plot.edit_report(result, figure=Figure(figsize=(6.0, 2.5)))
    assert plt.get_fignums() == open_figures
    paths_axis, cost_axis = figure.axes
    assert len(paths_axis.lines) == 2 * len(pairs) + len(pairs) + 1  # before, after, sources, eye
    assert len(cost_axis.lines[0].get_ydata()) == len(result.history)
    with pytest.raises(ValueError, match="figure must be empty"):
        plot.edit_report(result, figure=figure)
    shown = plot.edit_report(result)  # without figure=: a pyplot figure, as notebooks show it
    assert shown.number in plt.get_fignums()
    plt.close(shown)
