"""Sphinx configuration of the andoyer documentation (``make docs``)."""

from __future__ import annotations

import os
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))  # the checkout's andoyer, even beside an install

import andoyer  # noqa: E402

project = "andoyer"
author = "andoyer developers"
copyright = "2026, andoyer developers"
release = andoyer.__version__
version = release

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "sphinx.ext.intersphinx",
    "sphinx.ext.doctest",
    "numpydoc",
    "myst_nb",
]

# Pages: MyST markdown and notebooks written as text (executed at build time).
source_suffix = {".rst": "restructuredtext", ".md": "myst-nb", ".ipynb": "myst-nb"}
exclude_patterns = ["_build", "**.ipynb_checkpoints", "*.png"]
master_doc = "index"
myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence"]
myst_heading_anchors = 3

# Notebooks run at every build; a failing cell fails the build; outputs never stored.
nb_execution_mode = "force"
nb_execution_raise_on_error = True
nb_execution_timeout = 300
nb_execution_show_tb = True

# API reference: one page per public module, generated from the docstrings.
autosummary_generate = True
autosummary_imported_members = False
autodoc_default_options = {"members": True, "undoc-members": False, "show-inheritance": False}
autodoc_typehints = "none"
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False
# Module docstrings list the paper under References without citing it in every
# paragraph; numpydoc renames the labels per docstring, so Sphinx would flag each one.
suppress_warnings = ["ref.citation"]

# Cross-links to the libraries andoyer builds on. The inventories are fetched over the
# network; where it is not reachable (this project's CI reaches only package registries)
# set ANDOYER_DOCS_OFFLINE=1 and the links are left out instead of warning.
intersphinx_mapping = {} if os.environ.get("ANDOYER_DOCS_OFFLINE") else {
    "python": ("https://docs.python.org/3", None),
    "numpy": ("https://numpy.org/doc/stable", None),
    "scipy": ("https://docs.scipy.org/doc/scipy", None),
    "xarray": ("https://docs.xarray.dev/en/stable", None),
    "matplotlib": ("https://matplotlib.org/stable", None),
    "dask": ("https://docs.dask.org/en/stable", None),
    "heyoka": ("https://bluescarni.github.io/heyoka.py", None),
}
intersphinx_timeout = 10
# Doctests: the docstrings' examples run under pytest (--doctest-modules, with their
# modules' names); the doctest builder runs the {doctest} blocks of these pages.
doctest_test_doctest_blocks = ""

html_theme = "pydata_sphinx_theme"
html_title = f"andoyer {release}"
html_static_path: list[str] = []
html_theme_options = {
    "navigation_depth": 2,
    "show_toc_level": 2,
    "secondary_sidebar_items": ["page-toc"],
}
html_context = {"default_mode": "light"}


def _skip_type_aliases(app, what, name, obj, skip, options):  # noqa: ANN001, ARG001
    """Type aliases (``Params = tuple[float, ...]``) have no signature autodoc can format:
    documented in the module text, not as members."""
    import types
    import typing

    if isinstance(obj, types.GenericAlias | typing._GenericAlias):  # type: ignore[attr-defined]
        return True
    return skip


def setup(app):  # noqa: ANN001, ANN201
    app.connect("autodoc-skip-member", _skip_type_aliases)
