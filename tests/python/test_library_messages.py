"""Nothing the libraries underneath print reaches the terminal: Ceres' glog lines go to Python's
logging (logger 'refracta.ceres'), OpenImageIO's debug notes are off. Each case runs in a fresh
interpreter whose stdout and stderr are captured whole (glog and OIIO write to the C streams,
which pytest's capsys cannot see)."""

import os
import subprocess
import sys
import textwrap

import numpy as np

TEXEL_TOL = 1e-7  # an 8-bit texel k/255 read back as float32: rounding below 6e-8

# A solve on which Ceres 2.1 logs through glog: numeric derivatives at the start humidity = 1,
# the top of its range; the central difference steps past it, the model rejects humidity > 1,
# the Jacobian evaluation fails and Ceres logs "E... Terminating: Residual and Jacobian
# evaluation failed." (trust_region_minimizer.cc, unconditionally: logging_type SILENT does not
# cover it).
CERES_SOLVE = """
import logging, sys
import numpy as np
import refracta
from refracta.edit import PointPair, solve

records = []
class Keep(logging.Handler):
    def emit(self, record):
        records.append(record)
logging.getLogger("refracta").addHandler(Keep())
logging.getLogger("refracta").setLevel(logging.DEBUG)

truth = refracta.PhysicalAtmosphere(surface_dt=10.0, surface_depth=0.1)
eye = np.array([0.0, 1.4, 0.0])
pairs = []
for e, d in zip([-0.22, -0.1, 0.05], [250.0, 400.0, 650.0]):
    direction = np.array([np.cos(np.radians(e)), np.sin(np.radians(e)), 0.0])
    path = refracta.trace_ray(truth, eye, direction, tol=1e-11, max_length=d + 10.0, stop_height=0.0)
    pairs.append(PointPair(eye + direction, path.point_at(d)[0]))
result = solve(truth.with_params(humidity=1.0), eye, pairs, free=["humidity", "surface_dt"], stop_height=0.0,
               derivatives="numeric", max_iterations=3)
logged = [(r.name, r.levelname, r.getMessage()) for r in records]
sys.stdout.write(repr((result.message, logged)))
"""


def run_isolated(code: str, tmp_path):
    """(stdout, stderr) of `code` in a fresh interpreter, run in tmp_path with its own empty
    temporary folder tmp_path/tmp (where glog would put log files, and textures are prepared)."""
    (tmp_path / "tmp").mkdir(exist_ok=True)
    out = subprocess.run(
        [sys.executable, "-c", textwrap.dedent(code)],
        cwd=tmp_path,
        capture_output=True,
        text=True,
        timeout=300,
        env={**os.environ, "TMPDIR": str(tmp_path / "tmp")},
    )
    assert out.returncode == 0, out.stderr
    return out.stdout, out.stderr


def test_ceres_glog_lines_reach_python_logging_not_stderr(tmp_path):
    stdout, stderr = run_isolated(CERES_SOLVE, tmp_path)
    message, logged = eval(stdout)  # our own repr
    # The precondition: this solve makes Ceres log (if it ever stops failing, find another).
    assert "Residual and Jacobian evaluation failed" in message
    assert stderr == ""
    assert ("refracta.ceres", "INFO", next(m for _, _, m in logged if "Terminating" in m)) in logged
    assert any(m.endswith("Terminating: Residual and Jacobian evaluation failed.") for _, _, m in logged)
    assert not list((tmp_path / "tmp").iterdir()), "glog wrote log files"


def test_ceres_messages_are_silent_without_logging_configuration(tmp_path):
    # No handler: Python's last-resort handler prints WARNING and above; Ceres' lines are INFO.
    code = CERES_SOLVE.replace('logging.getLogger("refracta").addHandler(Keep())', "")
    code = code.replace('logging.getLogger("refracta").setLevel(logging.DEBUG)', "")
    stdout, stderr = run_isolated(code, tmp_path)
    assert stderr == ""
    assert "Residual and Jacobian evaluation failed" in eval(stdout)[0]


def test_png_texture_with_an_icc_profile_prints_nothing(tmp_path):
    from PIL import Image, ImageCms  # Pillow: a dependency of matplotlib

    profile = ImageCms.ImageCmsProfile(ImageCms.createProfile("sRGB")).tobytes()
    texture = tmp_path / "icc.png"
    Image.new("RGB", (8, 8), (200, 120, 40)).save(texture, icc_profile=profile)
    with Image.open(texture) as saved:
        assert saved.info["icc_profile"] == profile
    # A fresh temporary folder: the texture is prepared (OIIO make_texture writes an EXR) here.
    code = f"""
    import os, sys
    import numpy as np
    import refracta
    scene = refracta.Scene()
    scene.add_ground(0.0, 10.0, texture={str(texture)!r}, texture_size=1.0)
    scene.set_sky((1.0, 1.0, 1.0))
    camera = refracta.Camera((0, 1, 0), (2, 0, 0), width=8, height=6)
    image = refracta.render(scene, camera, progress=False)
    assert np.isfinite(image).all()
    sys.stdout.write(repr(refracta.io.read_image({str(texture)!r})[0, 0].tolist()))
    """
    stdout, stderr = run_isolated(code, tmp_path)
    assert stderr == ""
    assert np.allclose(eval(stdout), [200 / 255, 120 / 255, 40 / 255], rtol=0, atol=TEXEL_TOL)
    assert list((tmp_path / "tmp" / "refracta-textures").glob("*.exr")), "the texture was not prepared here"
