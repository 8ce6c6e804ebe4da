"""Every signal is Ctrl-C: SIGINT, SIGTERM and SIGHUP end a command the same way.

The first one raises :class:`andoyer.errors.Interrupted` (a ``KeyboardInterrupt``) in
the main thread, after ending the command's child processes (worker processes of a pool,
Dask's workers: :func:`andoyer.processes.end_children`), so that every ``finally`` runs:
temporary files are removed, locks released, a local Dask cluster closed, and the error
boundary of :func:`andoyer.cli.main` prints one line and exits with
``EXIT_CODES["interrupted"]``. Signals that come while the command unwinds are ignored
(a second Ctrl-C would otherwise break the clean-up half-way).
"""

from __future__ import annotations

import contextlib
import logging
import signal
import threading
import warnings
from collections.abc import Iterator
from typing import Any

__all__ = ["SIGNALS", "interrupts", "ignore_until_exit"]

#: The signals a command ends on, cleanly.
SIGNALS = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)


def _quiet_shutdown() -> None:
    """Dask's and Tornado's loggers report the closing of killed workers and streams as
    errors, with tracebacks, and Zarr's interrupted writes leave coroutines that Python
    reports as never awaited: the run is ending on purpose, so they are silenced."""
    for name in ("distributed", "tornado", "asyncio", "bokeh"):
        logging.getLogger(name).setLevel(logging.CRITICAL + 1)
    warnings.filterwarnings("ignore", message="coroutine .* was never awaited",
                            category=RuntimeWarning)


@contextlib.contextmanager
def interrupts() -> Iterator[list[int]]:
    """Within the block, SIGINT, SIGTERM and SIGHUP raise ``Interrupted`` once; the
    former handlers come back after it. Yields the list of signals received (what else
    fails while the command unwinds, e.g. a pool whose worker was ended, is a
    consequence). Outside the main thread, does nothing."""
    seen: list[int] = []
    if threading.current_thread() is not threading.main_thread():
        yield seen
        return
    from andoyer.errors import Interrupted

    def handler(signum: int, frame: Any) -> None:
        if seen:
            return  # already unwinding
        seen.append(signum)
        _quiet_shutdown()
        from andoyer.processes import end_children

        end_children()
        raise Interrupted(signal.Signals(signum).name)

    old = {sig: signal.signal(sig, handler) for sig in SIGNALS}
    try:
        yield seen
    finally:
        for sig, h in old.items():
            signal.signal(sig, h if h is not None else signal.SIG_DFL)


def ignore_until_exit() -> None:
    """Ignore the signals from now on: the command has ended (its exit code is set), and
    the interpreter's shutdown, which resets Python's handlers to the default, would
    otherwise die of a late signal with no exit code of ours."""
    if threading.current_thread() is threading.main_thread():
        for sig in SIGNALS:
            signal.signal(sig, signal.SIG_IGN)
