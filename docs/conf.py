"""Sphinx configuration of the urkin site: the lessons (student notebooks, executed at build
time), the API reference from docstrings, and the guides.  Builds offline."""

import shutil
from pathlib import Path

import urkin

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent

# The lessons are the generated student notebooks (no solutions), copied here and executed by
# myst-nb during the build; docs/lessons/ is not committed.
LESSONS = DOCS / "lessons"
shutil.rmtree(LESSONS, ignore_errors=True)
LESSONS.mkdir()
for notebook in sorted((ROOT / "course").glob("[0-9][0-9]_*.ipynb")):
    shutil.copyfile(notebook, LESSONS / notebook.name)

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

# notebooks: always execute, and fail the build on any error
nb_execution_mode = "force"
nb_execution_raise_on_error = True
nb_execution_show_tb = True
nb_execution_timeout = 300
nb_execution_allow_errors = False
myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence"]
myst_heading_anchors = 3

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
