"""The exceptions and warnings andoyer raises on purpose, in one place.

Every expected failure is one of these or a plain ``ValueError``/``TypeError`` (bad
input); the command line turns each into one line on stderr and its own exit code.

Examples
--------
>>> issubclass(CostLimitError, ValueError), issubclass(IntegrationError, FloatingPointError)
(True, True)
"""

from __future__ import annotations

import errno
import os

__all__ = ["ArgumentTypeError", "CertificateError", "CostLimitError", "DamagedCacheWarning",
           "DamagedFileError", "DamagedStoreWarning", "EncoderError", "IntegrationError",
           "Interrupted",
           "ManifestWarning", "NoCacheWarning", "NoSpaceError", "OutputInUseError",
           "SingularChartWarning", "SingularPassageWarning", "StaleLockWarning"]


class ArgumentTypeError(TypeError, ValueError):
    """An argument of the wrong type (a string where a :class:`~andoyer.RigidBody` belongs).

    Both a ``TypeError`` and a ``ValueError``, so that code catching either sees it.
    """


class CertificateError(ValueError):
    """A certificate that does not verify: not one andoyer wrote, a field missing, its
    content altered, a claim its boxes do not prove, or another arithmetic's balls."""


class CostLimitError(ValueError):
    """The estimated time or memory of a request exceeds a documented limit.

    The message gives the estimate, the limit and the argument that overrides it.
    """


class DamagedFileError(ValueError):
    """An input file or store is damaged, truncated or not what it should be.

    The message names the file (or the points of a store) and what is wrong with it.
    """


class NoSpaceError(OSError):
    """The file system ran out of space while andoyer wrote under ``where``.

    An ``OSError`` with ``errno.ENOSPC``; the message names the folder or file. What was
    being written was removed (files are written atomically; a scan chunk not marked
    done is computed again on resume).

    Parameters
    ----------
    where : str or os.PathLike
        The file or folder being written.
    """

    def __init__(self, where: str | os.PathLike[str]) -> None:
        super().__init__(errno.ENOSPC, f"no space left on {os.fspath(where)}",
                         os.fspath(where))


class IntegrationError(FloatingPointError):
    """An integrator failed (step size underflow, non-finite field, too many steps).

    A ``FloatingPointError``, which is what the engines raised before it existed.
    """


class EncoderError(RuntimeError):
    """An external encoder (ffmpeg writing an MP4) failed.

    The message names the encoder, its exit status and the last line of its error
    output; nothing was written (files are written atomically).
    """


class OutputInUseError(ValueError):
    """The output is being written by another run (named in the message, with its pid,
    host and start time); see :mod:`andoyer.outputs`."""


class Interrupted(KeyboardInterrupt):
    """The run was ended by a signal: Ctrl-C (SIGINT), SIGTERM or SIGHUP, all alike.

    A ``KeyboardInterrupt``, so that every ``finally`` and every handler of Ctrl-C
    cleans up the same way. ``signal`` is the signal's name; ``note`` says what was kept
    (e.g. how to resume), for the one line the command line prints.

    Parameters
    ----------
    signal : str, default "SIGINT"
        The signal's name.
    note : str, optional
        What was kept of the work (e.g. the chunks of a scan already stored).
    """

    def __init__(self, signal: str = "SIGINT", note: str | None = None) -> None:
        super().__init__(signal)
        self.signal = signal
        self.note = note


class StaleLockWarning(UserWarning):
    """The lock of an output was left by a run that did not finish (killed); this run
    takes it over (see :mod:`andoyer.outputs`)."""


class ManifestWarning(UserWarning):
    """The manifest of a folder could not record the files a run wrote there (a full
    disk, a folder made read-only): a later run takes them for the user's and leaves
    them (see :mod:`andoyer.outputs`)."""


class SingularChartWarning(UserWarning):
    """Chart coordinates were asked for states on the chart's singular set.

    There (``G = 0``, ``L = +-G``, ``|M| = G``) an angle is undefined and the value
    returned is a convention, not data; ``with_mask=True`` returns the flags that say
    which points they are (:class:`andoyer.charts.andoyer_deprit.Singular`).
    """


class SingularPassageWarning(UserWarning):
    """An orbit passed through a chart's singular set where a section angle is undefined.

    Such passages are not crossings: they are counted and timed apart
    (``singular_passages``, ``singular_passage_t`` in the section dataset).
    """


class NoCacheWarning(UserWarning):
    """No folder was writable for the compiled kernels: they are compiled in every run.

    Set ``ANDOYER_CACHE_DIR`` to a writable folder (see :mod:`andoyer.kernels.cache`).
    """


class DamagedCacheWarning(UserWarning):
    """An entry of the compiled-kernel cache was damaged (a truncated or foreign file):
    it was removed and the kernel compiled again and cached (the folder is named; see
    :mod:`andoyer.kernels.cache`)."""


class DamagedStoreWarning(UserWarning):
    """Points of a scan store marked done had missing or damaged data: they are named
    and computed again (:func:`andoyer.scan.damage.verify`)."""
