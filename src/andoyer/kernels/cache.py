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

:func:`cached_njit` is ``numba.njit(cache=True, ...)`` with a subfolder of it named
after the kernels' sources (:func:`sources_stamp`). Numba picks a
function's cache locator when the function is decorated, reading the documented
setting ``numba.config.CACHE_DIR`` (the mirror of ``NUMBA_CACHE_DIR``); the decorator
sets it for the decoration only and restores it, so the user's own Numba functions and
environment are untouched. Numba keys an entry on the path, size and time stamp of the
file that defines the function only, not of the files whose functions it calls and
compiles into its own code: after an edit of one kernel module (a stepper, a jet
routine) the callers in other modules would load stale machine code (seen here:
tangent kernels that differed from their sources compiled fresh). The subfolder named
after a hash of every source of :mod:`andoyer.kernels` (:func:`sources_stamp`) closes
that hole for all kernels at once, so two installs, versions or edits never share an
entry (the per-module keys of :mod:`andoyer.kernels.dop853.flow` stay, as a second lock).
Folders of former sources are left in place (another install may still use them);
deleting ``cache_folder()`` is always safe.

Processes that compile the same function at once (the report's workers, a Dask scan, a
test suite under several workers, on a fresh install) take turns to write its entry:
Numba reads the function's index, picks the first data-file name the index does not
use, and writes index and data, with no lock between, so two processes adding
signatures at once pick the same name, and one index can name the other signature's
machine code (seen here: a DOP853 kernel stepping from a non-finite state, its arguments
read as another signature's). :func:`cached_njit`'s caches hold an exclusive lock
(``filelock``, an OS lock: released when a process dies) on the index while they write,
so each writer reads the index the one before it wrote. Readers take no lock: Numba
replaces each file whole (a temporary file, then a rename).

Numba names machine code after a function's qualified name and a counter of the process
that compiled it, so two variants of one factory's function (the same name, other closure
constants) cached by two processes can share a symbol, and a process loading both runs
one body for both (numba/numba#10486; seen here: tangent crossings running the state's
loop). Every factory-made kernel carries its variant in its name
(:func:`andoyer.kernels.common.variant`).

A damaged entry (an index or data file truncated by a full disk or a killed process,
or overwritten) is taken for a missing one: its files are removed, the kernel compiled
again and cached, and the run says so once, naming the folder
(:class:`~andoyer.errors.DamagedCacheWarning`), instead of ending in Numba's unpickling
error.

Where nothing is writable (a read-only install and a read-only home, as on many
clusters and containers: Numba finds no folder of its own either), the kernels are
compiled without a cache: andoyer runs, compiles in every process, and says so once
(:class:`~andoyer.errors.NoCacheWarning`, once per run: child processes inherit the
fact that it was said).

>>> cache_folder().name
'numba'
"""

from __future__ import annotations

import functools
import glob
import hashlib
import os
import threading
import warnings
from collections.abc import Callable
from pathlib import Path
from typing import Any

import filelock
import platformdirs

from andoyer.errors import DamagedCacheWarning, NoCacheWarning

__all__ = ["cache_folder", "cached_njit", "cache_library_kernels", "sources_stamp", "writable",
           "warn_no_cache", "warn_damaged_cache", "CACHE_ENV"]

#: Environment variable that moves andoyer's caches (Numba's under ``<dir>/numba``).
CACHE_ENV = "ANDOYER_CACHE_DIR"

#: Set in the environment once the missing cache was reported, so that the worker
#: processes of the same run (report jobs, Dask workers) do not report it again.
_WARNED_ENV = "ANDOYER_NO_CACHE_WARNED"

#: Longest wait (s) for another process's write of the same entry (a few ms each); past
#: it the kernel runs compiled but not cached in this process.
_WRITE_WAIT = 60.0

#: Held while :func:`cache_library_kernels` swaps Numba's process-wide cache setting.
_LIBRARY_LOCK = threading.Lock()
#: The packages :func:`cache_library_kernels` has seen to in this process.
_CACHED_LIBRARIES: set[str] = set()


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


@functools.cache
def sources_stamp() -> str:
    """The first 16 hex digits of the SHA-256 of every ``*.py`` of
    :mod:`andoyer.kernels` and its sub-packages (paths and bytes, in path order): the
    subfolder of :func:`cache_folder` that :func:`cached_njit` caches in.

    Reads about 0.3 MB once per process.

    Returns
    -------
    str
        16 hexadecimal digits; changes with any byte of any kernel source.

    Examples
    --------
    >>> len(sources_stamp()), sources_stamp() == sources_stamp()
    (16, True)
    """
    return _stamp(Path(__file__).parent)


def _stamp(folder: Path) -> str:
    """:func:`sources_stamp` of the ``*.py`` files of ``folder`` and its sub-folders."""
    h = hashlib.sha256()
    for f in sorted(folder.rglob("*.py")):
        h.update(f.relative_to(folder).as_posix().encode())
        h.update(f.read_bytes())
    return h.hexdigest()[:16]


@functools.cache
def _rebuilding_cache() -> type:
    """The class of :func:`cached_njit`'s caches, made at first use: Numba is imported by
    the first kernel, not by this module (heyoka's engine asks :func:`writable` and
    :func:`warn_no_cache` here, and a first heyoka call would pay Numba's import)."""
    from numba.core.caching import FunctionCache

    class _RebuildingCache(FunctionCache):
        """Numba's on-disk cache of one function, taking a damaged entry for a missing one
        (module notes): its files are removed, the function compiled and cached again."""

        def load_overload(self, sig: Any, target_context: Any) -> Any:
            try:
                return super().load_overload(sig, target_context)
            except Exception as exc:  # noqa: BLE001 -- any damage: unpickling, EOF, LLVM
                self._discard(exc)
                return None

        def save_overload(self, sig: Any, data: Any) -> None:
            try:
                self._impl.locator.ensure_cache_path()
                with self._writer():
                    super().save_overload(sig, data)
            except filelock.Timeout:
                pass  # another process holds the entry: this one's code stays uncached
            except Exception as exc:  # noqa: BLE001 -- a damaged index it cannot remove
                self._discard(exc)

        def _index(self) -> Path:
            files: Any = self._cache_file  # numba's IndexDataCacheFile
            return Path(files._index_path)

        def _writer(self) -> filelock.BaseFileLock:
            """The one-writer lock of this function's entry (module notes)."""
            index = self._index()
            return filelock.FileLock(index.with_name(index.name + ".lock"),
                                     timeout=_WRITE_WAIT)

        def _discard(self, exc: Exception) -> None:
            index = self._index()
            stem = index.name[: -len(".nbi")]
            try:
                with self._writer():
                    for f in [index, *index.parent.glob(glob.escape(stem) + ".*.nbc")]:
                        try:
                            f.unlink()
                        except OSError:
                            pass
            except (OSError, filelock.Timeout):
                pass  # nothing removable, or another process is rewriting it
            warn_damaged_cache(index.parent, f"{stem}: {type(exc).__name__}: {exc}")

    return _RebuildingCache


def cached_njit(**options: Any) -> Callable[[Callable[..., Any]], Any]:
    """``numba.njit(cache=True, **options)`` caching in :func:`cache_folder`.

    Parameters
    ----------
    **options
        Options of :func:`numba.njit` (``cache`` is always True).

    Returns
    -------
    callable
        A decorator caching in ``cache_folder() / ("kernels-" + sources_stamp())``.
        If the folder cannot be created or written, Numba falls back to
        its own locations (beside the source, then Numba's user folder); if none is
        writable, the function is compiled without a cache, with one
        :class:`~andoyer.errors.NoCacheWarning` per run.
    """
    import numba

    options["cache"] = True

    config: Any = numba.config  # untyped module: its settings are set at import

    def decorate(function: Callable[..., Any]) -> Any:
        previous = config.CACHE_DIR
        config.CACHE_DIR = str(cache_folder() / f"kernels-{sources_stamp()}")
        try:
            dispatcher = numba.njit(**options)(function)
            dispatcher._cache = _rebuilding_cache()(dispatcher.py_func)  # same locator
            return dispatcher
        except RuntimeError as exc:  # Numba's "cannot cache ...: no locator available"
            if "no locator" not in str(exc):
                raise
            warn_no_cache(f"{cache_folder()}, the package's folder and Numba's user folder")
            return numba.njit(**{**options, "cache": False})(function)
        finally:
            config.CACHE_DIR = previous

    return decorate


def cache_library_kernels(package: str) -> None:
    """Cache the Numba functions of a library compiled without ``cache=True`` as
    andoyer's own are (:func:`cached_njit`): in ``cache_folder() / "libraries"``, with the
    same one-writer lock and damaged-entry rule.

    nafflib's ``numba.jit`` functions compile in every process that calls them (2.2 s
    on the report's border item); cached, a second process loads them. Numba keys each
    entry on the library file's path, size and time stamp, so another version of the
    library compiles its own. Functions their library caches already, and those of
    modules not imported yet, are left alone; where no folder is writable they stay
    uncached (the library's own behaviour). It acts once per package and process (later
    calls return at once): call it once the package is imported and before its first
    call.

    Parameters
    ----------
    package : str
        The library's import name, e.g. ``"nafflib"``: every imported module of it.

    Examples
    --------
    >>> import nafflib
    >>> cache_library_kernels("nafflib")
    >>> from numba.core.caching import NullCache
    >>> isinstance(nafflib.optimize.expArray._cache, NullCache)
    False
    """
    import sys

    import numba
    from numba.core.caching import NullCache
    from numba.core.dispatcher import Dispatcher

    if package in _CACHED_LIBRARIES:    # once per process: NAFF calls it on every signal
        return
    config: Any = numba.config  # untyped module: its settings are set at import
    # one thread at a time: the report's items call NAFF from threads, and Numba's
    # setting is process-wide (two threads' save and restore could leave it changed)
    with _LIBRARY_LOCK:
        if package in _CACHED_LIBRARIES:
            return
        modules = [m for name, m in list(sys.modules.items())
                   if m is not None and (name == package or name.startswith(package + "."))]
        for module in modules:
            for value in list(vars(module).values()):
                if not (isinstance(value, Dispatcher)
                        and isinstance(getattr(value, "_cache", None), NullCache)):
                    continue
                dispatcher: Any = value
                previous = config.CACHE_DIR
                config.CACHE_DIR = str(cache_folder() / "libraries")
                try:
                    dispatcher._cache = _rebuilding_cache()(dispatcher.py_func)
                except RuntimeError as exc:  # Numba's "cannot cache ...: no locator"
                    if "no locator" not in str(exc):
                        raise
                finally:
                    config.CACHE_DIR = previous
        _CACHED_LIBRARIES.add(package)


def writable(folder: str | os.PathLike[str]) -> bool:
    """Whether a file can be created in ``folder`` (created if missing).

    Tried for real, not read off permission bits, which root ignores (a read-only
    mount refuses even root).

    Parameters
    ----------
    folder : str or os.PathLike
        The folder to try.

    Examples
    --------
    >>> writable("/proc")
    False
    """
    import tempfile

    try:
        Path(folder).mkdir(parents=True, exist_ok=True)
        with tempfile.TemporaryFile(dir=folder):
            return True
    except OSError:
        return False


_DAMAGE_REPORTED: list[bool] = []


def warn_damaged_cache(folder: str | os.PathLike[str], what: str) -> None:
    """Say once per process that a damaged cache entry in ``folder`` is being rebuilt.

    Parameters
    ----------
    folder : str or os.PathLike
        The folder holding the entry.
    what : str
        The entry and what was wrong with it.
    """
    if _DAMAGE_REPORTED:
        return
    _DAMAGE_REPORTED.append(True)
    warnings.warn(
        f"damaged entry of the compiled-kernel cache in {os.fspath(folder)} ({what}): "
        "removed; the kernels are compiled again and cached (seconds to a minute)",
        DamagedCacheWarning, stacklevel=3)


def warn_no_cache(tried: str) -> None:
    """Say once per run (this process and the ones it starts) that nothing is cached.

    Parameters
    ----------
    tried : str
        The folders that were tried, for the message.
    """
    if os.environ.get(_WARNED_ENV):
        return
    os.environ[_WARNED_ENV] = "1"
    warnings.warn(
        f"no writable folder for compiled code (tried {tried}): andoyer runs, but "
        "compiles its kernels again in every process (seconds to a minute); set "
        f"{CACHE_ENV} to a writable folder to keep them", NoCacheWarning, stacklevel=3)
