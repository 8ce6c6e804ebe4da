"""Sphinx configuration of the andoyer documentation (``make docs``)."""

from __future__ import annotations

import os
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "src"))  # the checkout's andoyer, even beside an install
sys.path.insert(0, str(ROOT / "docs" / "_ext"))  # this site's own extensions

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
    "sphinx-mathjax-offline",  # MathJax shipped with the site: formulas render offline
    "sphinx.ext.intersphinx",
    "sphinx.ext.doctest",
    "numpydoc",
    "myst_nb",
    "summaries",  # docs/_ext/summaries.py: API summaries not cut at "Eq."
]

# Pages: MyST markdown and notebooks written as text (executed at build time).
source_suffix = {".rst": "restructuredtext", ".md": "myst-nb", ".ipynb": "myst-nb"}
exclude_patterns = ["_build", "**.ipynb_checkpoints", "*.png"]
master_doc = "index"
myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence"]
myst_heading_anchors = 3

# Notebooks run once per build (the html and doctest builders share the result) and are
# cached between builds by jupyter-cache; a failing cell fails the build; outputs are
# never stored in the sources. The cache is keyed by the notebook's code AND by the
# andoyer sources, so a change of the library re-executes every notebook.
nb_execution_mode = "cache"
nb_execution_raise_on_error = True
nb_execution_timeout = 300
nb_execution_show_tb = True


# Figures: one mechanism for every notebook. Each kernel starts with
# docs/_ext/notebook_figures.py (IPython's start-up file, in an IPython folder of the
# build), on Agg: every figure a cell creates is shown once as a PNG, never as
# "<Figure size ...>" text (tests/test_docs_site.py checks the built pages).
NOTEBOOK_STARTUP = ROOT / "docs" / "_ext" / "notebook_figures.py"
_IPYTHON_DIR = ROOT / "docs" / "_build" / ".ipython"
(_IPYTHON_DIR / "profile_default" / "startup").mkdir(parents=True, exist_ok=True)
_startup = _IPYTHON_DIR / "profile_default" / "startup" / "00-figures.py"
if not _startup.exists() or _startup.read_bytes() != NOTEBOOK_STARTUP.read_bytes():
    _startup.write_bytes(NOTEBOOK_STARTUP.read_bytes())
# the kernels' own log (a warning per kernel about its local TCP transport) kept out
(_IPYTHON_DIR / "profile_default" / "ipython_kernel_config.py").write_text(
    "c.IPKernelApp.log_level = 'ERROR'\n")
os.environ["IPYTHONDIR"] = str(_IPYTHON_DIR)
os.environ["MPLBACKEND"] = "agg"


def _source_stamp() -> str:
    """A hash of the andoyer sources (and pyproject.toml) the notebooks run against."""
    import hashlib

    digest = hashlib.sha256()
    files = sorted((ROOT / "src" / "andoyer").rglob("*.py")) + [ROOT / "pyproject.toml",
                                                                 NOTEBOOK_STARTUP]
    for path in files:
        digest.update(str(path.relative_to(ROOT)).encode())
        digest.update(path.read_bytes())
    return digest.hexdigest()[:16]


# docs/_build/.jupyter_cache/<stamp>: `make docs` keeps it (it clears html/ and doctest/
# only); caches of older sources are removed so the folder does not grow.
_CACHE_ROOT = ROOT / "docs" / "_build" / ".jupyter_cache"
nb_execution_cache_path = str(_CACHE_ROOT / _source_stamp())
if _CACHE_ROOT.is_dir():
    import shutil

    for _old in _CACHE_ROOT.iterdir():
        if _old.is_dir() and str(_old) != nb_execution_cache_path:
            shutil.rmtree(_old, ignore_errors=True)

# API reference: one page per public module, generated from the docstrings (rewritten
# only when their text changes, so an incremental build re-reads none); the page of a
# module that no longer exists is removed (its import would fail the build).
autosummary_generate = True
_GENERATED = ROOT / "docs" / "api" / "generated"
for _page in _GENERATED.glob("andoyer*.rst") if _GENERATED.is_dir() else ():
    _parts = _page.stem.split(".")
    _path = ROOT / "src" / Path(*_parts)
    if not (_path.with_suffix(".py").exists() or (_path / "__init__.py").exists()):
        _page.unlink()
autosummary_imported_members = False
autodoc_default_options = {"members": True, "undoc-members": False, "show-inheritance": False}
autodoc_typehints = "none"
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False
# Module docstrings list the paper under References without citing it in every
# paragraph; numpydoc renames the labels per docstring, so Sphinx would flag each one.
suppress_warnings = ["ref.citation"]

# Cross-links to the libraries andoyer builds on. The build is offline by default (the
# inventories would be fetched over the network, which CI and many machines do not
# reach): the links are left out with a note. ANDOYER_DOCS_ONLINE=1 fetches them.
DOCS_ONLINE = os.environ.get("ANDOYER_DOCS_ONLINE", "") not in ("", "0")
INTERSPHINX = {
    "python": ("https://docs.python.org/3", None),
    "numpy": ("https://numpy.org/doc/stable", None),
    "scipy": ("https://docs.scipy.org/doc/scipy", None),
    "xarray": ("https://docs.xarray.dev/en/stable", None),
    "matplotlib": ("https://matplotlib.org/stable", None),
    "dask": ("https://docs.dask.org/en/stable", None),
    "heyoka": ("https://bluescarni.github.io/heyoka.py", None),
}
intersphinx_mapping = INTERSPHINX if DOCS_ONLINE else {}
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


#: The module whose page autodoc is writing (set by its docstring, read for its members).
_DOCUMENTING: list[str] = [""]


def _note_module(app, what, name, obj, options, lines):  # noqa: ANN001, ARG001
    if what == "module":
        _DOCUMENTING[0] = name


def _skip_reexported_classes(app, what, name, obj, skip, options):  # noqa: ANN001, ARG001
    """A package's page lists the classes it re-exports (its ``__all__``) without
    describing them again: autodoc would add the defining module's name as a second
    (canonical) description of each, a duplicate of the module's own page."""
    module = sys.modules.get(_DOCUMENTING[0])
    if (what == "module" and module is not None and hasattr(module, "__path__")
            and isinstance(obj, type) and obj.__module__ != module.__name__):
        return True
    return _skip_type_aliases(app, what, name, obj, skip, options)


def _offline_note(app):  # noqa: ANN001
    if not DOCS_ONLINE:
        from sphinx.util import logging

        logging.getLogger("andoyer.docs").info(
            "offline build: links to %s left out (ANDOYER_DOCS_ONLINE=1 fetches their "
            "inventories)", ", ".join(INTERSPHINX))


# autosummary imports every module of the API at each build to regenerate its pages:
# most of a build with nothing changed. Skipped while no source, template or API index is
# newer than the last build that generated them (the stamp written when a build ends).
_AUTOSUMMARY_STAMP = ROOT / "docs" / "_build" / ".autosummary-stamp"


def _api_sources_unchanged() -> bool:
    if not _AUTOSUMMARY_STAMP.exists() or not _GENERATED.is_dir():
        return False
    stamp = _AUTOSUMMARY_STAMP.stat().st_mtime
    sources = [*(ROOT / "src" / "andoyer").rglob("*.py"), *(ROOT / "docs" / "api").glob("*.rst"),
               *(ROOT / "docs" / "_templates").rglob("*"), Path(__file__)]
    return all(path.stat().st_mtime < stamp for path in sources if path.is_file())


def _stamp_autosummary(app, exception):  # noqa: ANN001
    if exception is None:
        _AUTOSUMMARY_STAMP.parent.mkdir(parents=True, exist_ok=True)
        _AUTOSUMMARY_STAMP.touch()


def setup(app):  # noqa: ANN001, ANN201
    app.connect("autodoc-process-docstring", _note_module)
    app.connect("autodoc-skip-member", _skip_reexported_classes)
    app.connect("builder-inited", _offline_note)
    if _api_sources_unchanged():
        from sphinx.ext.autosummary import process_generate_options

        for listener in list(app.events.listeners.get("builder-inited", [])):
            if listener.handler is process_generate_options:
                app.disconnect(listener.id)
    app.connect("build-finished", _stamp_autosummary)
