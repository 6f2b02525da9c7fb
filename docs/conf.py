"""Sphinx configuration of the urkin site: the lessons (student notebooks, executed once before
the build), the API reference from docstrings, and the guides.  Builds offline."""

from pathlib import Path

import urkin
from urkin.course import build

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent

# The lessons are the generated student notebooks (no solutions), executed once into
# docs/lessons/ (not committed) and reused while neither they nor urkin change; a lesson that
# raises fails the build.
build.render(ROOT, DOCS / "lessons")

project = "urkin"
author = "urkin developers"
copyright = "2026, urkin developers"
release = urkin.__version__

extensions = [
    "myst_nb",
    "sphinx.ext.autodoc",
    "sphinx.ext.napoleon",
    "sphinx.ext.mathjax",
    "sphinx-mathjax-offline",
]

exclude_patterns = ["_build", "**.ipynb_checkpoints", "Thumbs.db", ".DS_Store"]

# notebooks were executed by build.render above; an error there has already failed the build
nb_execution_mode = "off"
myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence"]
myst_heading_anchors = 3
# Nothing is loaded from another host. No page runs a kernel, so a live widget (lesson 08's jog
# panel) would be dead: its output also carries a recording of the session as an animation
# (text/html), which is shown instead, and ipywidgets' embedding scripts (from CDNs) are off.
nb_ipywidgets_js = {}
nb_mime_priority_overrides = [("*", "application/vnd.jupyter.widget-view+json", None)]

# API reference
autodoc_default_options = {"members": True, "member-order": "bysource"}
autodoc_typehints = "description"
napoleon_numpy_docstring = True
napoleon_google_docstring = False
napoleon_use_rtype = False

html_theme = "sphinx_book_theme"
html_title = "urkin — kinematics of Universal Robots arms"
html_theme_options = {
    "show_toc_level": 2,
    "use_download_button": True,
}
html_static_path = []
