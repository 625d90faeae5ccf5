"""Hovering over a render shows its readouts: the text at a pixel (Python's readout_text, which
matplotlib's status bar shows) and the widget that sends the readouts to the browser once."""

import numpy as np
import pytest

import refracta
from refracta.widgets import readout_text


@pytest.fixture(scope="module")
def rendered():
    scene = refracta.Scene()
    scene.set_sky((1.0, 1.0, 1.0))
    scene.add_ground(0.0, 1000.0)
    box = scene.add_box((50.0, 2.0, 0.0), (2.0, 4.0, 4.0))
    camera = refracta.Camera((0.0, 1.5, 0.0), (50.0, 1.5, 0.0), (0, 1, 0), 20.0, 12, 8)
    image, aovs = refracta.render(
        scene,
        camera,
        None,
        method="straight",
        aovs=["distance", "position", "object_id", "hidden_height"],
        progress=False,
    )
    return image, aovs, box


def test_readout_text_is_the_pixel_under_the_point(rendered):
    _, aovs, box = rendered
    j, i = np.argwhere(aovs["object_id"] == box)[0]
    text = readout_text(aovs, i + 0.7, j + 0.2).splitlines()
    assert text[0] == f"pixel ({i}, {j})"
    assert text[1] == f"distance: {aovs['distance'][j, i]:.2f} m"
    assert text[3] == f"object_id: {box}"
    sky = np.argwhere(aovs["object_id"] == -1)[0]
    assert "distance: inf m" in readout_text(aovs, sky[1] + 0.5, sky[0] + 0.5)
    assert "position: x none, y none, z none\n" in readout_text(aovs, sky[1] + 0.5, sky[0] + 0.5)  # no unit for none


def test_matplotlib_status_bar_shows_the_readouts(rendered):
    image, aovs, box = rendered
    figure = refracta.plot.readouts_figure(image, aovs)
    j, i = np.argwhere(aovs["object_id"] == box)[0]
    # imshow's data coordinates put pixel (i, j)'s centre at (i, j)
    assert figure.axes[0].format_coord(float(i), float(j)) == readout_text(aovs, i + 0.5, j + 0.5).replace("\n", "; ")
    import matplotlib.pyplot as plt

    plt.close(figure)


def test_the_widget_carries_every_readout_to_the_browser(rendered):
    pytest.importorskip("anywidget", reason="the viewer needs anywidget (pip install refracta[widgets])")
    from refracta.widgets import show_readouts

    image, aovs, _ = rendered
    viewer = show_readouts(image, aovs)
    assert (viewer.width, viewer.height) == (12, 8) and viewer.image.startswith(b"\x89PNG")
    values = np.frombuffer(viewer.values, dtype="<f4").reshape(8, 12, -1)
    for item in viewer.layout:  # each readout where the layout says, as readouts.js reads it
        block = values[..., item["offset"] : item["offset"] + len(item["labels"])]
        expected = np.asarray(aovs[item["name"]], dtype=np.float32).reshape(8, 12, -1)
        assert np.array_equal(block, expected, equal_nan=True), item["name"]
    with pytest.raises(ValueError, match="aovs\\['distance'\\] is"):
        show_readouts(image, {"distance": aovs["distance"][:4]})
