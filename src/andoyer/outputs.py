"""One writer per output, and no file replaced that andoyer did not write.

Two rules for every output of a run (a file, a folder, a scan's Zarr store):

* **One writer.** :class:`OutputLock` holds an exclusive lock (``filelock``: an OS lock
  the kernel releases when the process dies) on a hidden file beside the output,
  ``.NAME.andoyer-lock``, for the whole run (removed at its end). A sidecar
  ``.NAME.andoyer-lock.json`` says who holds it (pid, host, start time, command); a
  second writer is refused with :class:`~andoyer.errors.OutputInUseError` naming that
  holder. The sidecar is removed when the run ends; one found while taking a free lock
  was left by a run that was killed: the new run reports it
  (:class:`~andoyer.errors.StaleLockWarning`) and takes the lock over.
* **No foreign file replaced.** A folder written by a command keeps a manifest,
  ``.andoyer-manifest.json``: the files andoyer wrote there, with their SHA-256. A run
  refuses a folder holding files that are not in it, or that changed since (a user's
  ``index.html``): :func:`guard_folder`. The manifest is brought up to date when the run
  ends, however it ends (the files are written atomically, so each one is whole).
* **Files, the same rule.** A command writing files (``--out sec.nc`` and the
  ``sec.png`` beside it) records them in the manifest of *their* folder, which stays the
  user's: only those files are listed there. An existing file is replaced only if that
  manifest lists it with its checksum (andoyer wrote it and nobody changed it since);
  any other file is refused, naming it: :func:`guard_file`. There is no flag to force it,
  as there is none for folders: choose another name, or move the file away. A file being
  written by a run that was killed (written after it started) is adopted, as in folders.

Examples
--------
>>> import tempfile, pathlib
>>> folder = pathlib.Path(tempfile.mkdtemp())
>>> with OutputLock(folder / "s.zarr") as lock:
...     holder = read_holder(folder / "s.zarr")
...     print(holder["pid"] == os.getpid(), lock.lock_path.name)
True .s.zarr.andoyer-lock
>>> read_holder(folder / "s.zarr") is None  # released
True
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import socket
import sys
import time
import warnings
from collections.abc import Iterator
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

import filelock

from andoyer.errors import ManifestWarning, OutputInUseError, StaleLockWarning

__all__ = ["OutputLock", "read_holder", "lock_path", "Manifest", "MANIFEST", "guard_folder",
           "guard_file", "hold", "release", "release_all"]

#: The manifest of a folder andoyer writes (hidden, inside the folder).
MANIFEST = ".andoyer-manifest.json"
_LOCK_SUFFIX = ".andoyer-lock"


def lock_path(target: str | os.PathLike[str]) -> Path:
    """The lock file of an output: hidden, beside it (outside a folder that may be replaced).

    Parameters
    ----------
    target : str or os.PathLike
        The output file, folder or store.

    Examples
    --------
    >>> lock_path("out/s.zarr")
    PosixPath('out/.s.zarr.andoyer-lock')
    """
    t = Path(target)
    return t.parent / f".{t.name}{_LOCK_SUFFIX}"


def _info_path(target: Path) -> Path:
    p = lock_path(target)
    return p.with_name(p.name + ".json")


def read_holder(target: str | os.PathLike[str]) -> dict[str, Any] | None:
    """Who holds (or held, if it was killed) the lock of ``target``: pid, host, started
    (ISO time, UTC), start (seconds since the epoch), command; None if nobody.

    Parameters
    ----------
    target : str or os.PathLike
        The output file, folder or store.
    """
    try:
        info = json.loads(_info_path(Path(target)).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    return info if isinstance(info, dict) else None


def _describe(info: dict[str, Any] | None) -> str:
    if not info:
        return "holder unknown"
    return (f"pid {info.get('pid')} on host {info.get('host')}, started "
            f"{info.get('started')}: {info.get('command', '?')}")


def _alive_here(info: dict[str, Any]) -> bool | None:
    """Whether the holder's process still runs (None: another host, cannot tell)."""
    if info.get("host") != socket.gethostname():
        return None
    try:
        os.kill(int(info.get("pid", -1)), 0)
    except (ProcessLookupError, ValueError, OverflowError):
        return False
    except PermissionError:
        return True
    return True


class OutputLock:
    """An exclusive lock on one output (file, folder or store) for the whole run.

    Parameters
    ----------
    target : path
        The output; the lock is the hidden file :func:`lock_path` beside it.

    Raises
    ------
    andoyer.errors.OutputInUseError
        On :meth:`acquire` (or ``with``), when another run holds the lock.

    Notes
    -----
    The lock is the operating system's (released by the kernel when the process ends,
    even on SIGKILL), so it is never stale itself; what a killed run leaves is its
    sidecar, which the next run reports (:class:`~andoyer.errors.StaleLockWarning`) as
    :attr:`stale`, then replaces with its own.
    """

    def __init__(self, target: str | os.PathLike[str]) -> None:
        self.target = Path(target)
        self.lock_path = lock_path(self.target)
        self._info = _info_path(self.target)
        self._lock = filelock.FileLock(self.lock_path, timeout=0)
        #: The sidecar of a killed run found when the lock was taken (None if none).
        self.stale: dict[str, Any] | None = None
        #: When this run took the lock (seconds since the epoch).
        self.start = 0.0

    def acquire(self) -> OutputLock:
        if not self.lock_path.parent.is_dir():
            raise ValueError(f"folder {str(self.lock_path.parent)!r} of {str(self.target)!r} "
                             "does not exist; create it first")
        try:
            self._lock.acquire(timeout=0)
        except filelock.Timeout:
            raise OutputInUseError(
                f"{str(self.target)!r} is being written by another andoyer run "
                f"({_describe(read_holder(self.target))}); wait for it to end, or choose "
                "another output") from None
        self.stale = read_holder(self.target)
        if self.stale is not None:
            alive = _alive_here(self.stale)
            state = {False: "no longer running", None: "on another host",
                     True: "running, but no longer holding the lock"}[alive]
            warnings.warn(
                f"the lock of {str(self.target)!r} was left by a run that did not finish "
                f"({_describe(self.stale)}; {state}): taking it over", StaleLockWarning,
                stacklevel=2)
        self.start = time.time()
        info = {"pid": os.getpid(), "host": socket.gethostname(),
                "started": datetime.fromtimestamp(self.start, UTC).isoformat(timespec="seconds"),
                "start": self.start, "command": " ".join(sys.argv)[:300]}
        tmp = self._info.with_name(f"{self._info.name}.{os.getpid()}.tmp")
        try:
            tmp.write_text(json.dumps(info), encoding="utf-8")
            os.replace(tmp, self._info)
        except BaseException:
            tmp.unlink(missing_ok=True)
            self._lock.release()
            raise
        return self

    def release(self) -> None:
        if self._lock.is_locked:
            # Removed while held, so nothing is left beside the output; a run that opened
            # the file just before sees an unlinked inode when it gets the lock and
            # tries again (filelock >= 4.3 checks).
            self._info.unlink(missing_ok=True)
            self.lock_path.unlink(missing_ok=True)
            self._lock.release()

    def __enter__(self) -> OutputLock:
        return self.acquire()

    def __exit__(self, *exc: object) -> None:
        self.release()


# ---------------------------------------------------------------------- the manifest
def _sha256(path: Path) -> str:
    with path.open("rb") as f:
        return hashlib.file_digest(f, "sha256").hexdigest()


class Manifest:
    """The files andoyer wrote in ``folder``, with their SHA-256 (``.andoyer-manifest.json``).

    Hidden entries (names starting with ``.``: the manifest, locks, temporary files) are
    never listed nor counted as foreign.

    Parameters
    ----------
    folder : str or os.PathLike
        The output folder.
    """

    def __init__(self, folder: str | os.PathLike[str]) -> None:
        self.folder = Path(folder)
        self.path = self.folder / MANIFEST

    def files(self) -> dict[str, str]:
        """``{name: sha256}`` recorded (empty if there is no manifest)."""
        try:
            data = json.loads(self.path.read_text(encoding="utf-8"))
        except FileNotFoundError:
            return {}
        except (OSError, ValueError) as e:
            raise ValueError(f"{str(self.path)!r} is damaged ({e}); remove it (andoyer then "
                             "takes every file of the folder for yours)") from None
        files = data.get("files", {}) if isinstance(data, dict) else {}
        return {str(k): str(v) for k, v in files.items()} if isinstance(files, dict) else {}

    def _entries(self) -> Iterator[Path]:
        if self.folder.is_dir():
            yield from (p for p in sorted(self.folder.iterdir())
                        if not p.name.startswith("."))

    def foreign(self) -> list[str]:
        """Entries andoyer did not write here, or that changed since it wrote them."""
        known = self.files()
        return [p.name for p in self._entries()
                if not p.is_file() or p.is_symlink() or known.get(p.name) != _sha256(p)]

    def owns(self, name: str) -> bool:
        """Whether the entry ``name`` is a file andoyer wrote here, unchanged since."""
        p = self.folder / name
        return (p.is_file() and not p.is_symlink()
                and self.files().get(name) == _sha256(p))

    def record(self, since: float) -> None:
        """Record the files written since ``since`` (seconds since the epoch), and keep
        those recorded before that are still there (with their new checksums)."""
        with self._updating():
            known = self.files()
            files = {p.name: _sha256(p) for p in self._entries()
                     if p.is_file() and not p.is_symlink()
                     and (p.name in known or p.stat().st_mtime >= since - 1.0)}
            self._write(files)

    def add(self, names: list[str], since: float) -> None:
        """Record the files ``names`` that were written since ``since`` (the outputs of one
        run in a folder that is not andoyer's); the other entries are kept as they are,
        those whose file is gone are dropped."""
        with self._updating():
            files = {k: v for k, v in self.files().items() if (self.folder / k).is_file()}
            for name in names:
                p = self.folder / name
                if p.is_file() and not p.is_symlink() and p.stat().st_mtime >= since - 1.0:
                    files[name] = _sha256(p)
            self._write(files)

    @contextlib.contextmanager
    def _updating(self) -> Iterator[None]:
        """Runs writing different files of one folder update its manifest in turn (its
        own short-lived lock, removed while held as :class:`OutputLock` does)."""
        lock = filelock.FileLock(self.folder / f"{MANIFEST}{_LOCK_SUFFIX}", timeout=30)
        with lock:
            try:
                yield
            finally:
                Path(lock.lock_file).unlink(missing_ok=True)

    def _write(self, files: dict[str, str]) -> None:
        if not files and not self.path.exists():
            return
        tmp = self.path.with_name(f"{MANIFEST}.{os.getpid()}.tmp")
        try:
            tmp.write_text(json.dumps({"written_by": "andoyer", "files": files}, indent=1),
                           encoding="utf-8")
            os.replace(tmp, self.path)
        finally:
            tmp.unlink(missing_ok=True)


# ---------------------------------------------------------------------- a run's outputs
_HELD: dict[Path, tuple[OutputLock, contextlib.ExitStack]] = {}


def hold(target: str | os.PathLike[str]) -> OutputLock:
    """Lock ``target`` until :func:`release_all` (the end of a command); a path this
    process already holds is not locked twice.

    Parameters
    ----------
    target : str or os.PathLike
        The output file, folder or store.
    """
    key = Path(os.path.abspath(target))
    if key in _HELD:
        return _HELD[key][0]
    stack = contextlib.ExitStack()
    lock = stack.enter_context(OutputLock(target))
    _HELD[key] = (lock, stack)
    return lock


def guard_folder(folder: str | os.PathLike[str], flag: str = "--out") -> OutputLock:
    """Hold ``folder`` for this run and refuse it if it holds files andoyer did not write.

    The folder may be new, empty, or hold only what andoyer wrote there (its manifest,
    checksums unchanged). Files of a killed run (written after it started) are adopted.
    When the run ends (:func:`release_all`) the manifest records what it wrote.

    Parameters
    ----------
    folder : str or os.PathLike
        The output folder (it may not exist yet).
    flag : str, default "--out"
        The flag or argument that named it, for the error.
    """
    path = Path(folder)
    lock = hold(path)
    manifest = Manifest(path)
    stack = _HELD[Path(os.path.abspath(path))][1]
    if lock.stale is not None and isinstance(lock.stale.get("start"), int | float):
        manifest.record(since=float(lock.stale["start"]))
    foreign = manifest.foreign()
    if foreign:
        listed = ", ".join(foreign[:5]) + (f" and {len(foreign) - 5} more"
                                           if len(foreign) > 5 else "")
        release(path)
        raise ValueError(f"{flag} {str(path)!r} holds files andoyer did not write, or that "
                         f"changed since it wrote them ({listed}): they could be replaced; "
                         "choose a new or empty folder, or move them away")
    stack.callback(_safely, manifest.record, lock.start)
    return lock


def guard_file(path: str | os.PathLike[str], flag: str = "--out") -> OutputLock:
    """Hold the output file ``path`` for this run and refuse it if it exists and andoyer did
    not write it (the manifest of its folder, :class:`Manifest`, lists it with its checksum).

    Also refused: a file inside a folder another run is writing (``andoyer paper --out``).
    When the run ends (:func:`release_all`) the manifest of the folder records the file,
    if this run wrote it. A file written by a killed run (after it started) is adopted.

    Parameters
    ----------
    path : str or os.PathLike
        The output file.
    flag : str, default "--out"
        The flag or argument that named it, for the error.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> _ = (folder / "mine.png").write_text("a user's file")
    >>> guard_file(folder / "mine.png")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: --out '...mine.png' exists and andoyer did not write it (or it changed since ...
    """
    out = Path(path)
    key = Path(os.path.abspath(out))
    if key in _HELD:
        return _HELD[key][0]
    _refuse_folder_in_use(out.parent, flag, out)
    lock = hold(out)
    manifest = Manifest(out.parent)
    if (lock.stale is not None and isinstance(lock.stale.get("start"), int | float)
            and out.exists()):
        manifest.add([out.name], float(lock.stale["start"]))
    if (out.exists() or out.is_symlink()) and not manifest.owns(out.name):
        release(out)
        what = "a folder" if out.is_dir() else "it"
        raise ValueError(f"{flag} {str(out)!r} exists and andoyer did not write {what} (or it "
                         "changed since andoyer wrote it): it would be replaced; choose "
                         f"another {flag}, or move the file away")
    _HELD[key][1].callback(_safely, manifest.add, [out.name], lock.start)
    return lock


def _refuse_folder_in_use(folder: Path, flag: str, out: Path) -> None:
    """``OutputInUseError`` if another run holds ``folder`` (writes it as a whole)."""
    if not lock_path(folder).exists() or Path(os.path.abspath(folder)) in _HELD:
        return
    probe = filelock.FileLock(lock_path(folder), timeout=0)
    try:
        probe.acquire()
    except filelock.Timeout:
        raise OutputInUseError(
            f"{flag} {str(out)!r}: its folder {str(folder)!r} is being written by another "
            f"andoyer run ({_describe(read_holder(folder))}); wait for it to end, or choose "
            "another folder") from None
    probe.release()


def _safely(update: Any, *args: Any) -> None:
    """Bring a manifest up to date at the end of a run, or say why not: a manifest that
    cannot be written (a full disk, a folder made read-only meanwhile) must not hide the
    run's own outcome nor keep its other outputs locked. The files it did not record are
    then refused as foreign by the next run: the safe side."""
    try:
        update(*args)
    except (OSError, ValueError, filelock.Timeout) as exc:
        warnings.warn(f"could not record the files andoyer wrote in its manifest ({exc}); "
                      "a later run will take them for yours and not replace them",
                      ManifestWarning, stacklevel=2)


def release(target: str | os.PathLike[str]) -> None:
    """Release one output held by :func:`hold` (its callbacks run first).

    Parameters
    ----------
    target : str or os.PathLike
        The output held by :func:`hold`.
    """
    entry = _HELD.pop(Path(os.path.abspath(target)), None)
    if entry is not None:
        entry[1].close()


def release_all() -> None:
    """Release every output this process holds (the end of a command)."""
    for key in list(_HELD)[::-1]:
        release(key)
