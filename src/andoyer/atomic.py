"""Atomic file output: write to a temporary file beside the target, then rename.

A full file system is named: whatever library did the writing (Python's own files, Zarr,
the NetCDF/HDF5 C library, whose message is only "HDF error"), running out of space
while writing under a folder raises :class:`~andoyer.errors.NoSpaceError` naming it.
"""

from __future__ import annotations

import contextlib
import errno
import os
import shutil
import tempfile
from collections.abc import Iterator
from pathlib import Path

from andoyer.errors import NoSpaceError

__all__ = ["atomic_path", "named_when_full", "FULL_BELOW", "remove_pending"]

#: Temporary files of this process being written now (removed on any failure, and by
#: :func:`remove_pending` when a signal ends a worker process at once).
_PENDING: set[Path] = set()

#: A write that failed while fewer bytes than this were free on its file system failed
#: for want of space (libraries such as HDF5 do not pass ``ENOSPC`` on).
FULL_BELOW = 1 << 20


def _full(exc: BaseException, where: Path) -> bool:
    if isinstance(exc, NoSpaceError) or not isinstance(exc, OSError | RuntimeError):
        return False
    if isinstance(exc, OSError) and exc.errno == errno.ENOSPC:
        return True
    folder = where if where.is_dir() else where.parent
    try:
        return shutil.disk_usage(folder).free < FULL_BELOW
    except OSError:
        return False


@contextlib.contextmanager
def named_when_full(where: str | os.PathLike[str]) -> Iterator[None]:
    """Turn running out of space while writing under ``where`` into
    :class:`~andoyer.errors.NoSpaceError` naming it; other errors pass unchanged.

    Parameters
    ----------
    where : str or os.PathLike
        The file or folder being written, named in the error.

    Examples
    --------
    >>> import errno
    >>> with named_when_full("/data/out"):
    ...     raise OSError(errno.ENOSPC, "No space left on device")
    Traceback (most recent call last):
    ...
    andoyer.errors.NoSpaceError: [Errno 28] no space left on /data/out: '/data/out'
    """
    try:
        yield
    except (OSError, RuntimeError) as exc:
        if _full(exc, Path(where)):
            raise NoSpaceError(where) from exc
        raise


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


@contextlib.contextmanager
def atomic_path(final: str | os.PathLike[str]) -> Iterator[Path]:
    """Yield a temporary path in ``final``'s folder; rename it to ``final`` on success.

    On any exception the temporary file is removed and ``final`` is left untouched; a
    full file system raises :class:`~andoyer.errors.NoSpaceError` naming ``final``.
    The file gets the ordinary permissions (``0o666 & ~umask``), not mkstemp's 0o600.

    Parameters
    ----------
    final : str or os.PathLike
        The file to write.
    """
    out = Path(final)
    if not out.parent.exists():
        raise ValueError(f"folder {str(out.parent)!r} does not exist; create it first")
    fd, tmp = tempfile.mkstemp(dir=out.parent, prefix=f".{out.name}.", suffix=".tmp")
    os.close(fd)
    _PENDING.add(Path(tmp))
    try:
        yield Path(tmp)
        os.chmod(tmp, 0o666 & ~_umask())
        os.replace(tmp, out)
    except BaseException as exc:
        full = _full(exc, out)  # before the partial file is removed and frees its space
        Path(tmp).unlink(missing_ok=True)
        if full:
            raise NoSpaceError(out) from exc
        raise
    finally:
        _PENDING.discard(Path(tmp))


def remove_pending() -> None:
    """Remove the temporary files of :func:`atomic_path` this process is writing now
    (for a process that must end at once, without unwinding)."""
    for tmp in list(_PENDING):
        tmp.unlink(missing_ok=True)
        _PENDING.discard(tmp)
