"""The editor in a real browser: Voilà serves a notebook that shows a MirageEditor, Debian's headless
Chromium opens it (through Selenium and Debian's chromedriver: nothing is downloaded), two clicks
on the image add a pair, the Solve button runs a solve, and screenshots show the new image.

The server and the browser start and stop inside the test (fixtures, stopped in teardown even on
failure); the server listens on a free loopback port only.
"""

import io
import os
import shutil
import socket
import subprocess
import sys
import time

import numpy as np
import pytest

from .conftest import CAR, HEIGHT, WIDTH

pytestmark = pytest.mark.slow

CHROMIUM, CHROMEDRIVER = "/usr/bin/chromium", "/usr/bin/chromedriver"  # Debian's chromium, chromium-driver
DESTINATION = (189.1, 62.0)  # where the car bottom's mirage image should appear: below the mirror line,
# reachable with surface_dt and surface_depth (60 K, 0.21 m)
SERVER_START = 60.0  # [s] bounds on waiting (a hang fails the test instead of blocking the suite)
PAGE_LOAD = 90.0  # [s] the page runs the notebook: import, the example's sky table, the first render
SOLVE = 60.0  # [s] the solve and the render after it
IMAGE_CHANGE = 0.01  # mean |difference| of screenshot values in [0, 1] over the canvas, markers masked,
# that counts as a new image (measured ~0.05 for this edit)
MARKER_MASK = 12.0  # [image pixels] around the pair's markers left out of the comparison (their
# drawing may change with the solve: met or not)

NOTEBOOK_SOURCE = f"""\
import refracta
from refracta import examples
from refracta.widgets import MirageEditor

road = examples.hot_road({WIDTH}, {HEIGHT})
editor = MirageEditor(road.scene, road.camera, road.field, free=["surface_dt", "surface_depth"], stop_height=0.0,
                      max_length=road.max_length)
editor
"""


def free_port() -> int:
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return probe.getsockname()[1]


@pytest.fixture
def voila_url(tmp_path):
    """A Voilà server for a notebook with the editor, on a free loopback port; its URL."""
    pytest.importorskip("voila", reason="the browser test serves its notebook with voila (refracta[test])")
    import nbformat

    notebook = tmp_path / "editor.ipynb"
    nbformat.write(nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(NOTEBOOK_SOURCE)]), notebook)
    port = free_port()
    env = dict(os.environ, JUPYTER_RUNTIME_DIR=str(tmp_path / "runtime"), JUPYTER_DATA_DIR=str(tmp_path / "data"))
    log = open(tmp_path / "voila.log", "w")
    server = subprocess.Popen(
        [sys.executable, "-m", "voila", str(notebook), "--no-browser", f"--port={port}", "--Voila.ip=127.0.0.1"],
        cwd=tmp_path,
        env=env,
        stdout=log,
        stderr=subprocess.STDOUT,
    )
    try:
        deadline = time.monotonic() + SERVER_START
        while True:
            try:
                socket.create_connection(("127.0.0.1", port), timeout=0.5).close()
                break
            except OSError:
                if server.poll() is not None or time.monotonic() > deadline:
                    raise RuntimeError(f"voila did not start:\n{(tmp_path / 'voila.log').read_text()}") from None
                time.sleep(0.2)
        yield f"http://127.0.0.1:{port}/"
    finally:
        server.terminate()
        try:
            server.wait(timeout=15)
        except subprocess.TimeoutExpired:
            server.kill()
            server.wait()
        log.close()


@pytest.fixture
def browser(monkeypatch):
    """Headless Debian Chromium driven by Selenium through Debian's chromedriver."""
    if not (shutil.which(CHROMIUM) and shutil.which(CHROMEDRIVER)):
        pytest.skip(f"{CHROMIUM} and {CHROMEDRIVER} are needed (Debian packages chromium, chromium-driver)")
    webdriver = pytest.importorskip("selenium.webdriver", reason="selenium is needed (refracta[test])")
    from selenium.webdriver.chrome.service import Service

    monkeypatch.setenv("SE_OFFLINE", "true")  # Selenium Manager must never try to download a driver
    options = webdriver.ChromeOptions()
    options.binary_location = CHROMIUM
    for argument in (
        "--headless=new",
        "--no-sandbox",
        "--disable-gpu",
        "--disable-dev-shm-usage",
        "--window-size=1400,1000",
        "--force-device-scale-factor=1",
    ):
        options.add_argument(argument)
    driver = webdriver.Chrome(service=Service(CHROMEDRIVER), options=options)
    yield driver
    driver.quit()


def screenshot(element, path) -> np.ndarray:
    """The element's pixels as float RGB in [0, 1]; also saved to `path`."""
    from PIL import Image

    png = element.screenshot_as_png
    path.write_bytes(png)
    return np.asarray(Image.open(io.BytesIO(png)).convert("RGB"), dtype=float) / 255.0


def test_a_click_adds_a_pair_and_a_solve_shows_the_new_image(voila_url, browser, tmp_path):
    from selenium.webdriver.common.action_chains import ActionChains
    from selenium.webdriver.common.by import By
    from selenium.webdriver.support.ui import WebDriverWait

    browser.get(voila_url)
    canvas = WebDriverWait(browser, PAGE_LOAD).until(
        lambda d: d.find_element(By.CSS_SELECTOR, "canvas.refracta-canvas[data-level='full']")
    )
    pair_count = browser.find_element(By.CSS_SELECTOR, ".refracta-pair-count")
    message = browser.find_element(By.CSS_SELECTOR, ".refracta-message")
    assert pair_count.text == "0 pairs"

    def click(u, v):
        """A click at image pixel (u, v) (Selenium's offsets are from the element's centre)."""
        size = canvas.size
        x, y = (u / WIDTH - 0.5) * size["width"], (v / HEIGHT - 0.5) * size["height"]
        ActionChains(browser).move_to_element_with_offset(canvas, round(x), round(y)).click().perform()

    click(*CAR)
    WebDriverWait(browser, SOLVE).until(lambda d: "now click where" in message.text)
    click(*DESTINATION)
    # The count and the message are two widget updates that reach the page one after the other:
    # wait for both (asserting the message after the count raced on a busy machine).
    WebDriverWait(browser, SOLVE).until(lambda d: pair_count.text == "1 pair" and "Pair 0 added" in message.text)

    before = screenshot(canvas, tmp_path / "before.png")
    generation = int(canvas.get_attribute("data-generation"))
    browser.find_element(By.XPATH, "//button[normalize-space()='Solve']").click()
    WebDriverWait(browser, SOLVE).until(lambda d: not message.text.startswith(("Pair 0 added", "Solving")))
    assert "Solved: every pair met" in message.text
    WebDriverWait(browser, SOLVE).until(  # the render after the solve: its preview, then the full image
        lambda d: (
            int(canvas.get_attribute("data-generation")) >= generation + 2
            and canvas.get_attribute("data-level") == "full"
        )
    )
    after = screenshot(canvas, tmp_path / "after.png")
    assert before.shape == after.shape
    rows, columns = np.mgrid[0 : before.shape[0], 0 : before.shape[1]]
    u, v = (columns + 0.5) * WIDTH / before.shape[1], (rows + 0.5) * HEIGHT / before.shape[0]
    away = np.ones(before.shape[:2], dtype=bool)
    for mu, mv in (CAR, DESTINATION):
        away &= np.hypot(u - mu, v - mv) > MARKER_MASK
    assert np.abs(after - before)[away].mean() > IMAGE_CHANGE
