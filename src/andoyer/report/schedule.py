"""Build the report's items: in this process and ``jobs - 1`` worker processes
(:class:`concurrent.futures.ProcessPoolExecutor`), longest first, with one progress bar.

Each worker takes the next item as it frees up and so does this process, so the
workers' start-up (their imports, about 2 s) overlaps the first item here. Each item is
announced as it finishes, with its time (the report keeps its own order); on a terminal a
bar names the items running, elsewhere (a pipe, a log) a plain line does every
:data:`HEARTBEAT_S` while items run. Figures are drawn on
each process's main thread (matplotlib is not thread-safe). On every way out (an error,
Ctrl-C, SIGTERM turned into an exception) the pool is shut down with its queued items
cancelled and its workers terminated; a worker also ends when this process dies
without a word (Linux: ``PR_SET_PDEATHSIG``), and ignores Ctrl-C, which this process
handles.
"""

from __future__ import annotations

import multiprocessing
import signal
import sys
import threading
import time
from collections import deque
from collections.abc import Callable
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from typing import Any

from threadpoolctl import threadpool_limits

from andoyer.processes import child_signals, children_ignore_interrupts
from andoyer.progress import Progress, on_terminal, silenced
from andoyer.report.base import Context, Item, Result

__all__ = ["run_items", "Announcer"]

#: Seconds between redraws of the bar while items run (its clock keeps moving).
_TICK_S = 1.0
#: Seconds between the plain lines naming the items still running (no terminal).
HEARTBEAT_S = 30.0
#: Seconds a terminated worker gets to end before it is killed.
_GRACE_S = 5.0


class Announcer:
    """The report's progress on stderr: a line per item as it finishes, with its time.

    Each line reads ``[k/n] title ... t s`` (``k`` items done so far); on a terminal a bar
    of items names those running, elsewhere a plain line names them every
    :data:`HEARTBEAT_S`.

    Parameters
    ----------
    items : list of Item
        The items, in report order.
    enabled : bool
        Show the bar and the lines (False: silent).

    Examples
    --------
    >>> a = Announcer([], enabled=False)
    >>> a.close()
    """

    def __init__(self, items: list[Item], enabled: bool) -> None:
        self.items = list(items)
        self.enabled = enabled
        self.bar = Progress(len(self.items), "andoyer paper",
                            enabled=bool(enabled and on_terminal()))
        self.running: dict[str, float] = {}
        self.seconds: dict[str, float] = {}
        self.order: list[str] = []  # the items in the order they finished
        self._t0 = time.perf_counter()
        self._stop = threading.Event()
        self._ticker = threading.Thread(target=self._tick, daemon=True)
        if self.bar.enabled or enabled:
            self._ticker.start()

    def _tick(self) -> None:
        last = time.perf_counter()
        while not self._stop.wait(_TICK_S):
            if self.bar.enabled:
                self.bar.refresh()
            elif time.perf_counter() - last >= HEARTBEAT_S and self.running:
                last = time.perf_counter()
                self.bar.write(self.heartbeat(last))

    def heartbeat(self, now: float) -> str:
        """The plain line naming the items running at ``now`` (perf_counter seconds)."""
        names = ", ".join(f"{key} ({now - t:.0f} s)" for key, t in self.running.items())
        return (f"[{len(self.seconds)}/{len(self.items)}] andoyer paper: running {names}; "
                f"{now - self._t0:.0f} s in all")

    def start(self, item: Item) -> None:
        """``item`` starts."""
        self.running[item.key] = time.perf_counter()
        self.bar.describe(", ".join(self.running))

    def finish(self, item: Item, seconds: float) -> None:
        """``item`` is done: count it and announce it, with its time."""
        self.running.pop(item.key, None)
        self.seconds[item.key] = seconds
        self.order.append(item.key)
        self.bar.update(1)
        self.bar.describe(", ".join(self.running))
        if self.enabled:
            self.bar.write(f"[{len(self.seconds)}/{len(self.items)}] {item.title} ... "
                           f"{seconds:.1f} s")

    def close(self) -> None:
        """End the bar and its clock."""
        self._stop.set()
        if self._ticker.is_alive():
            self._ticker.join()
        self.bar.close()


def _build_item(item: Item, ctx: Context) -> tuple[Result, float]:
    """Build one item (its own progress bars hidden: the report has one), with BLAS on
    one thread: the report shares the cores out itself (processes, then each item's
    threads), and an idle OpenBLAS thread spins about 0.1 s of CPU after every call
    (benchmarks/NOTES.md#blas-one-thread)."""
    t0 = time.perf_counter()
    with silenced(), threadpool_limits(limits=1, user_api="blas"):
        res = item.build(ctx)
    return res, time.perf_counter() - t0


def _die_with_parent() -> None:
    """In a worker: the signal rules of every child process
    (:func:`andoyer.processes.child_signals`: SIGINT and SIGHUP left to the parent,
    SIGTERM removes the temporary files being written), and end with the parent."""
    child_signals()
    if sys.platform.startswith("linux"):
        import ctypes

        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(1, int(signal.SIGTERM))  # PR_SET_PDEATHSIG


def _end_workers(workers: set[Any]) -> None:
    """Terminate ``workers`` (multiprocessing processes) and wait for them, bounded."""
    for p in workers:
        if p.is_alive():
            p.terminate()
    deadline = time.monotonic() + _GRACE_S
    for p in workers:
        p.join(max(0.0, deadline - time.monotonic()))
        if p.is_alive():
            p.kill()
            p.join(1.0)


def run_items(items: list[Item], ctx: Context, jobs: int, progress: bool
              ) -> dict[str, tuple[Result, float]]:
    """Build ``items`` with ``jobs`` processes (this one and ``jobs - 1`` workers).

    Returns, per item key, its result and the seconds it took. The results do not
    depend on ``jobs``; the first error of an item is raised (the other items are
    cancelled and the workers ended).

    Parameters
    ----------
    items : list of Item
        The items to build.
    ctx : Context
        Output folder, body, engine, quick.
    jobs : int
        Processes (this one and ``jobs - 1`` workers).
    progress : bool
        Show the progress (:class:`Announcer`).
    """
    announcer = Announcer(items, progress)
    out: dict[str, tuple[Result, float]] = {}

    def here(item: Item) -> None:
        announcer.start(item)
        res, seconds = _build_item(item, ctx)
        out[item.key] = (res, seconds)
        announcer.finish(item, seconds)

    def announce(item: Item) -> Callable[[Future[tuple[Result, float]]], None]:
        # a worker's item is announced when it ends, also while this process builds one
        def done(f: Future[tuple[Result, float]]) -> None:
            if not f.cancelled() and f.exception() is None:
                announcer.finish(item, f.result()[1])
        return done

    try:
        if jobs <= 1:
            for item in items:
                here(item)
            return out
        queue = deque(sorted(items, key=lambda i: -i.cost))
        before = set(multiprocessing.active_children())
        # spawn: a fresh interpreter (forking a process that may run threads is unsafe).
        # Started with SIGINT/SIGHUP blocked (multiprocessing's resource tracker too).
        with children_ignore_interrupts():
            pool = ProcessPoolExecutor(jobs - 1,
                                       mp_context=multiprocessing.get_context("spawn"),
                                       initializer=_die_with_parent)
        running: dict[Future[tuple[Result, float]], Item] = {}
        try:
            while queue or running:
                while queue and len(running) < jobs - 1:
                    item = queue.popleft()
                    future = pool.submit(_build_item, item, ctx)
                    running[future] = item
                    announcer.start(item)
                    future.add_done_callback(announce(item))
                if queue:
                    here(queue.popleft())
                    finished = {f for f in running if f.done()}
                else:
                    finished, _ = wait(running, return_when=FIRST_COMPLETED)
                for f in finished:
                    out[running.pop(f).key] = f.result()
            pool.shutdown(wait=True)
        finally:
            for f in running:
                f.cancel()
            _end_workers(set(multiprocessing.active_children()) - before)
            # Joins the pool's manager thread, its workers ended: one still tearing down
            # at exit races CPython 3.11's exit hook, which writes to the wake-up pipe
            # the thread closes ("OSError: Bad file descriptor" after a SIGTERM).
            pool.shutdown(wait=True, cancel_futures=True)
        return out
    finally:
        announcer.close()
