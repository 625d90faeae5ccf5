"""Names the dead-code check (vulture, `make lint`) reports as unused that are in use, each with why.

vulture reads this file as code that uses the names below; it is never imported or run. It scans
python/refracta with tests/ and benchmarks/ as its users (pyproject.toml, [tool.vulture]), so public
API that the tests exercise needs no entry here; pytest fixtures (used by name) are skipped there.
An entry belongs here only when the use is one vulture cannot see: a name looked up at run time,
read by the browser, or read by users of a public result.
"""

_ = object()

# Module __getattr__ / __dir__ (PEP 562): Python calls them for the lazy submodules and __all__
# (python/refracta/__init__.py, python/refracta/widgets/__init__.py).
__getattr__
__dir__

# Fields of public results that users read and the tests do not (yet) assert on.
_.converged  # refracta.edit.EditResult: whether the solver reported convergence
_.solver_report  # refracta.edit.EditResult: the backend's full report
_.stopped_by  # refracta.edit.EditResult: which budget limit stopped the solve
_.screen_triangles  # refracta.raster.RasterBuffers: triangles drawn after clipping (statistics)
_.generation_seconds  # refracta.Turbulence: documented attribute, the pattern's synthesis time [s]

# Developer tool: reproduces the table measurements cited in cpp/refracta/shading/color.cpp.
_._measure_table

# Fields of bound C++ option classes that Python only writes (C++ reads them: the render, the
# solve, validate()); add a field here when a new option is set from Python and never read there.
_.z_near  # MboitSettings: the depth range's near end [m] (refracta.oit.composite's z_range)
_.z_far  # MboitSettings: its far end [m]
_.trust_region  # SolveSettings, set by tests/edit/test_09_options.py for validate() to refuse
_.loss_scale  # SolveSettings, likewise

# Traits synced to the browser: refracta/widgets/canvas.js reads them, Python only writes them.
_.interactive  # MirageCanvas: whether clicks and drags are taken
_.cursor  # MirageCanvas: the pointer over the image
_.disabled  # ipywidgets.Button.disabled, set by the view, read by the browser

# MirageEditor view handlers: called by name, getattr(self, f"_show_{what}") (widgets/view.py),
# for each change the model announces.
_._show_image
_._show_straight
_._show_pairs
_._show_fan
_._show_field
_._show_message
_._show_busy
_._show_history
_._show_mode

# Attributes the tests set on third-party objects, read by that library.
_.sh_frame  # mitsuba SurfaceInteraction3f.sh_frame (tests/shading/*mitsuba*.py)
_.binary_location  # selenium ChromeOptions.binary_location (tests/widgets/test_07_browser.py)

# Read by tqdm on the bar's class when a bar is made: 0 turns its monitor thread off
# (refracta._progress: the progress calls come every 50 ms).
_.monitor_interval
