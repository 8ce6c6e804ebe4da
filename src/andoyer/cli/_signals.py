"""Every signal is Ctrl-C: SIGINT, SIGTERM and SIGHUP end a command the same way.

The first one raises :class:`andoyer.errors.Interrupted` (a ``KeyboardInterrupt``) in
the main thread, after ending the command's child processes (worker processes of a pool,
Dask's workers: :func:`andoyer.processes.end_children`), so that every ``finally`` runs:
temporary files are removed, locks released, a local Dask cluster closed, and the error
boundary of :func:`andoyer.cli.main` prints one line and exits with
``EXIT_CODES["interrupted"]``. Signals that come while the command unwinds are ignored
(a second Ctrl-C would otherwise break the clean-up half-way).

Python runs a signal handler in the main thread wherever that thread is, also inside a
finalizer (``__del__``, a weakref or garbage-collector callback): there an exception
cannot propagate, Python passes it to :func:`sys.unraisablehook` (which prints "Exception
ignored in ..." with a traceback) and the interrupted code goes on. A signal that lands
there (compiling code creates and frees many objects with finalizers) used to be lost:
the command ran to its end and exited 0. Within :func:`interrupts`, an ``Interrupted``
that reaches the unraisable hook is not printed; the signal is delivered again
(:func:`_thread.interrupt_main`, from a short-lived thread, once the finalizer has
returned). And a command that returns normally after a signal was taken (some
library swallowed the exception with a bare ``except``) still ends as interrupted:
:func:`andoyer.cli.main` checks the list :func:`interrupts` yields.
"""

from __future__ import annotations

import _thread
import contextlib
import logging
import signal
import sys
import threading
import time
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

    lost = [False]  # the last Interrupted was swallowed by a finalizer: deliver it again
    active = [True]  # our handlers are installed

    def redeliver(signum: int) -> None:
        """Deliver ``signum`` to the main thread again, once the finalizer that swallowed
        its exception has returned (a short pause: the main thread is running)."""
        time.sleep(0.02)
        if active[0]:
            _thread.interrupt_main(signal.Signals(signum))

    def handler(signum: int, frame: Any) -> None:
        if seen and not lost[0]:
            return  # already unwinding
        lost[0] = False
        if not seen:
            seen.append(signum)
            _quiet_shutdown()
            from andoyer.processes import end_children

            end_children()
        raise Interrupted(signal.Signals(seen[0]).name)

    former_hook = sys.unraisablehook

    def unraisable(info: Any) -> None:
        if seen and isinstance(info.exc_value, Interrupted):
            lost[0] = True
            # a C-level thread start (threading.Thread.start would wait in Python code,
            # where the signal could land again, in this hook)
            _thread.start_new_thread(redeliver, (seen[0],))
            return
        former_hook(info)

    old = {sig: signal.signal(sig, handler) for sig in SIGNALS}
    sys.unraisablehook = unraisable
    try:
        yield seen
    finally:
        active[0] = False
        sys.unraisablehook = former_hook
        for sig, h in old.items():
            signal.signal(sig, h if h is not None else signal.SIG_DFL)


def ignore_until_exit() -> None:
    """Ignore the signals from now on: the command has ended (its exit code is set), and
    the interpreter's shutdown, which resets Python's handlers to the default, would
    otherwise die of a late signal with no exit code of ours."""
    if threading.current_thread() is threading.main_thread():
        for sig in SIGNALS:
            signal.signal(sig, signal.SIG_IGN)
