"""Sphinx configuration of refracta's documentation: the API reference from the docstrings
(autodoc + napoleon for the Google-style Args/Returns sections) and the tutorial notebooks
(myst-nb, shown with their stored outputs, not executed). Built by `make docs`."""

import refracta

project = "refracta"
author = "the refracta developers"
release = version = refracta.__version__

extensions = ["sphinx.ext.autodoc", "sphinx.ext.napoleon", "myst_nb"]

# The notebooks live at the repository's top level; python/docs/notebooks is a symbolic link to
# them (Sphinx reads sources only below this folder).
nb_execution_mode = "off"  # the notebooks run in `make test` (nbmake); here their outputs are shown
exclude_patterns = ["_build", "notebooks/.ipynb_checkpoints"]
autodoc_default_options = {"members": True, "undoc-members": False, "show-inheritance": True}
autodoc_member_order = "bysource"
napoleon_google_docstring = True
napoleon_numpy_docstring = False
napoleon_use_ivar = True  # Attributes: sections as fields, not entries duplicating dataclass members
html_theme = "alabaster"
