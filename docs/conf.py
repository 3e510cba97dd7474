"""Sphinx configuration of pamkit's documentation site (scripts/docs.sh builds it).

The Python API comes from the docstrings (autodoc, napoleon), the C++ API from the headers
(Doxygen's XML, read by breathe), the reference pages from the code's own field lists
(_ext/pamkit_reference.py), and the gallery from examples/gallery, each example run by the build
(sphinx-gallery): an example that fails fails the build.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

import pamkit

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(HERE / "_ext"))

project = "pamkit"
author = "the pamkit authors"
copyright = "the pamkit authors; MIT licence"
version = release = pamkit.__version__

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.napoleon",
    "myst_parser",
    "sphinx_gallery.gen_gallery",
    "breathe",
    "pamkit_reference",
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build", "auto_examples/*.ipynb", "auto_examples/*.py", "auto_examples/*.zip"]
myst_heading_anchors = 3
myst_enable_extensions = ["colon_fence"]
suppress_warnings = ["myst.header"]  # pages keep their own heading levels (some start at ##)

# The Python API: every public name, in the order the source gives it.
autodoc_member_order = "bysource"
autodoc_typehints = "description"
autodoc_default_options = {"members": True, "undoc-members": False, "show-inheritance": True}
napoleon_numpy_docstring = True
napoleon_google_docstring = True
napoleon_use_ivar = True  # a dataclass's Attributes section, not a second description of its fields

# The C++ API: Doxygen's XML of include/pamkit (scripts/docs.sh writes it).
breathe_projects = {"pamkit": os.environ.get("PAMKIT_DOXYGEN_XML", str(ROOT / "build" / "docs" / "doxygen" / "xml"))}
breathe_default_project = "pamkit"
breathe_default_members = ("members",)

# The gallery: examples/gallery/plot_*.py, each run once per build on the bundled data.
sphinx_gallery_conf = {
    "examples_dirs": [str(ROOT / "examples" / "gallery")],
    "gallery_dirs": ["auto_examples"],
    "filename_pattern": r"/plot_",
    "abort_on_example_error": True,
    "download_all_examples": False,
    "reset_modules": ("matplotlib",),
    "capture_repr": ("_repr_html_", "__repr__"),
    "show_memory": False,
    "min_reported_time": 1,
    "within_subsection_order": "FileNameSortKey",
}

html_theme = "alabaster"
html_title = f"pamkit {release}"
html_theme_options = {
    "description": "Simulate, test and diagnose pneumatic artificial muscles",
    "fixed_sidebar": True,
    "show_relbars": True,
}
html_static_path: list[str] = []

# No network in CI: links to other sites are not checked, links inside the site are.
linkcheck_ignore = [r"^https?://"]
