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

# Solves on which Ceres 2.1 logs through glog: "Terminating: Residual and Jacobian evaluation
# failed." (trust_region_minimizer.cc, unconditionally: logging_type SILENT does not cover it),
# when an evaluation at Ceres' current point fails. The air here (a CustomField under CurvedEarth,
# earth_radius free, numeric derivatives, rk4: a fixed number of evaluations per trace) gives out
# after its k-th evaluation of the pair; for each k in turn a solve runs, and those where it gives
# out inside Ceres log (an earlier trigger, the central difference stepping past humidity's domain,
# went when numeric derivatives learned to step one-sided). Every record offered to a logger counted.
CERES_SOLVE = """
import logging, sys
import numpy as np
import refracta
from refracta.edit import PointPair, distances, solve

refracta.set_threads(1)
records = []
class Keep(logging.Handler):
    def emit(self, record):
        records.append(record)
logging.getLogger("refracta").addHandler(Keep())
logging.getLogger("refracta").setLevel(logging.DEBUG)
through = []  # the loggers asked whether they take a record (before any level decides)
enabled = logging.Logger.isEnabledFor
def counted(self, level):
    through.append(self.name)
    return enabled(self, level)
logging.Logger.isEnabledFor = counted

calls = {"n": 0, "limit": None}
def ior(p):
    calls["n"] += 1
    if calls["limit"] is not None and calls["n"] > calls["limit"]:
        raise RuntimeError("the test's air gives out")
    return 1.0003 - 1e-6 * np.asarray(p, float)[..., 1]
def grad(p):
    g = np.zeros_like(np.asarray(p, float))
    g[..., 1] = -1e-6
    return g
field = refracta.CurvedEarth(refracta.CustomField(ior, grad, height_only=True))
eye = np.array([0.0, 10.0, 0.0])
pairs = [PointPair(eye + [1.0, 0.0, 0.0], [2000.0, 9.8, 0.0])]
options = dict(trace="rk4", step=50.0, stop_height=0.0)
distances(field, eye, pairs, **options)
per_evaluation = calls["n"]
for k in range(2, 40):
    calls["n"], calls["limit"] = 0, k * per_evaluation
    try:
        solve(field, eye, pairs, free=["earth_radius"], derivatives="numeric", strategy="local", **options)
        break
    except (refracta.NumericalError, RuntimeError):
        pass
logged = [(r.name, r.levelname, r.getMessage()) for r in records]
sys.stdout.write(repr((through.count("refracta.ceres"), logged)))
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
    ceres_records, logged = eval(stdout)  # our own repr
    assert ceres_records > 0  # the precondition: these solves make Ceres log
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
    assert eval(stdout)[0] > 0  # Ceres did log: through refracta.ceres, with no handler to show it


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
