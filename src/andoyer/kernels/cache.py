"""Where Numba keeps andoyer's compiled machine code: a folder in the user's cache.

Numba's ``cache=True`` writes next to the source file by default (a ``__pycache__`` in
the installed package), which fails or litters on a read-only or shared install, and
falls back to a folder chosen per file. andoyer's kernels are cached in one folder
under the user's cache directory instead (:func:`cache_folder`):

* ``$ANDOYER_CACHE_DIR/numba`` when that variable is set;
* otherwise Numba's own ``$NUMBA_CACHE_DIR`` when the user set it (andoyer then follows
  the user's choice for all of Numba);
* otherwise ``platformdirs.user_cache_dir("andoyer")/numba`` (on Linux
  ``~/.cache/andoyer/numba``).

:func:`cached_njit` is ``numba.njit(cache=True, ...)`` with that folder. Numba picks a
function's cache locator when the function is decorated, reading the documented
setting ``numba.config.CACHE_DIR`` (the mirror of ``NUMBA_CACHE_DIR``); the decorator
sets it for the decoration only and restores it, so the user's own Numba functions and
environment are untouched. Entries are keyed by Numba on the source file's path, size
and time stamp (and by andoyer on a hash of the generated kernels, see
:mod:`andoyer.kernels.dop853`), so two installs or versions never share an entry.

>>> cache_folder().name
'numba'
"""

from __future__ import annotations

import os
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numba
import platformdirs

__all__ = ["cache_folder", "cached_njit", "CACHE_ENV"]

#: Environment variable that moves andoyer's caches (Numba's under ``<dir>/numba``).
CACHE_ENV = "ANDOYER_CACHE_DIR"


def cache_folder() -> Path:
    """The folder of andoyer's Numba cache (not created here).

    Returns
    -------
    pathlib.Path
        ``$ANDOYER_CACHE_DIR/numba``, else ``$NUMBA_CACHE_DIR``, else
        ``<user cache dir>/andoyer/numba``.
    """
    own = os.environ.get(CACHE_ENV)
    if own:
        return Path(own).expanduser() / "numba"
    numba_dir = os.environ.get("NUMBA_CACHE_DIR")
    if numba_dir:
        return Path(numba_dir).expanduser()
    return Path(platformdirs.user_cache_dir("andoyer", appauthor=False)) / "numba"


def cached_njit(**options: Any) -> Callable[[Callable[..., Any]], Any]:
    """``numba.njit(cache=True, **options)`` caching in :func:`cache_folder`.

    Parameters
    ----------
    **options
        Options of :func:`numba.njit` (``cache`` is always True).

    Returns
    -------
    callable
        A decorator. If the folder cannot be created or written, Numba falls back to
        its own locations (a read-only install then caches in Numba's user folder).
    """
    options["cache"] = True

    config: Any = numba.config  # untyped module: its settings are set at import

    def decorate(function: Callable[..., Any]) -> Any:
        previous = config.CACHE_DIR
        config.CACHE_DIR = str(cache_folder())
        try:
            return numba.njit(**options)(function)
        finally:
            config.CACHE_DIR = previous

    return decorate
