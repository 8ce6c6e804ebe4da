"""Child processes of a run: they ignore the terminal's signals and end with their parent.

Ctrl-C in a terminal, and a hang-up, reach every process of the foreground group, so a
worker process would print its own ``KeyboardInterrupt`` traceback while its parent
cleans up. The rule here: **the parent alone handles a signal**; its children ignore
SIGINT and SIGHUP, and the parent ends them (:func:`end_children`) when it is
interrupted (``andoyer.cli`` does, for SIGINT, SIGTERM and SIGHUP alike).

* A process pool: ``ProcessPoolExecutor(..., initializer=child_signals)``.
* Processes started by a library (Dask's local cluster): start them inside
  :func:`children_ignore_interrupts`; a child inherits the blocked signals.

Examples
--------
>>> with children_ignore_interrupts():
...     pass
>>> end_children()  # no children here: nothing to do
[]
"""

from __future__ import annotations

import contextlib
import os
import signal
import threading
from collections.abc import Iterator

__all__ = ["CHILD_IGNORES", "child_signals", "children_ignore_interrupts", "end_children"]

#: Signals a child process ignores (its parent handles them and ends it).
CHILD_IGNORES = (signal.SIGINT, signal.SIGHUP)


def child_signals() -> None:
    """In a child process (an ``initializer=`` of a pool): ignore SIGINT and SIGHUP, and
    on SIGTERM (its parent ending it) remove the temporary files it is writing
    (:func:`andoyer.atomic.remove_pending`) and exit at once."""
    for sig in CHILD_IGNORES:
        signal.signal(sig, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, _end_now)
    # tqdm's default lock is a multiprocessing RLock: a named semaphore registered with
    # the resource tracker, which a child ended by SIGTERM (os._exit) never unlinks, so
    # the tracker printed "leaked semaphore objects" under the parent's one-line message.
    # A child's bars are its own (silenced in report workers): a thread lock suffices.
    from tqdm import tqdm

    tqdm.set_lock(threading.RLock())


def _end_now(signum: int, frame: object) -> None:
    from andoyer.atomic import remove_pending

    remove_pending()
    os._exit(128 + signum)


@contextlib.contextmanager
def children_ignore_interrupts() -> Iterator[None]:
    """Start child processes (and the threads that will start them) inside this block:
    SIGINT and SIGHUP never reach them.

    The block blocks both signals in this thread; a thread or process started meanwhile
    inherits the blocked mask (and keeps it across ``exec``), so a worker restarted later
    by such a thread has them blocked too. SIGTERM is held back in the block (children
    must keep it: it is how they are ended). A signal that comes during the block is
    delivered when it ends, once whatever the block started can be closed: delayed,
    never lost. Outside the main thread, does nothing (the main thread handles signals).
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    held: list[int] = []
    old_term = signal.signal(signal.SIGTERM, lambda signum, frame: held.append(signum))
    # Multiprocessing's resource tracker (a child too) ignores SIGINT and SIGTERM but
    # not SIGHUP, and starting it *unblocks* SIGINT in the calling thread: it is started
    # here with both blocked (it inherits the blocked SIGHUP), then they are blocked
    # again.
    from multiprocessing import resource_tracker

    signal.pthread_sigmask(signal.SIG_BLOCK, CHILD_IGNORES)
    try:
        resource_tracker.ensure_running()
        signal.pthread_sigmask(signal.SIG_BLOCK, CHILD_IGNORES)
        yield
    finally:
        signal.signal(signal.SIGTERM, old_term)
        signal.pthread_sigmask(signal.SIG_UNBLOCK, CHILD_IGNORES)
        if held:
            signal.raise_signal(signal.SIGTERM)


def end_children(timeout: float = 2.0) -> list[int]:
    """End every descendant process: SIGTERM, then SIGKILL to those alive after
    ``timeout`` seconds. Returns their pids.

    Multiprocessing's resource tracker is left alone: it ignores signals on purpose and
    exits by itself when its parent does (it then frees what the workers left).

    Parameters
    ----------
    timeout : float, default 2.0
        Seconds between SIGTERM and SIGKILL.
    """
    import psutil

    try:
        children = [c for c in psutil.Process().children(recursive=True)
                    if not _is_resource_tracker(c)]
    except psutil.Error:
        return []
    for child in children:
        with contextlib.suppress(psutil.Error):
            child.terminate()
    _, alive = psutil.wait_procs(children, timeout=timeout)
    for child in alive:
        with contextlib.suppress(psutil.Error):
            child.kill()
    psutil.wait_procs(alive, timeout=timeout)
    return [c.pid for c in children]


def _is_resource_tracker(proc: object) -> bool:
    import psutil

    try:
        return "multiprocessing.resource_tracker" in " ".join(proc.cmdline())  # type: ignore[attr-defined]
    except psutil.Error:
        return False
