"""Progress bars for long work: one place, on ``tqdm`` (notebook-aware through tqdm.auto).

Shown on stderr when it is a terminal (or in a notebook), hidden otherwise, unless the
caller says ``enabled=True`` or ``False``: the ``progress=`` keyword of the public
functions. Asked for (``enabled=True``, as the commands do) where stderr is a pipe or a
log file, a bar's redraws would pile up there: plain lines take its place, ``[k/n] label:
p %, t s``, one per tenth of the work at most every few seconds, and one when it ends
(:func:`plain_line`).

Examples
--------
>>> bar = Progress(3, "demo", enabled=False)
>>> bar.update(2); bar.update(1); bar.close()
>>> bar.done
3

Inside :func:`silenced` no bar is shown (a caller that draws its own bar, such as
``andoyer paper``, keeps the bars of the work it calls off the screen):

>>> with silenced():
...     Progress(3, "inner", enabled=True).enabled
False
"""

from __future__ import annotations

import importlib.util
import sys
import threading
import time
from collections.abc import Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from functools import cache
from typing import Any

__all__ = ["Progress", "silenced", "close_all", "plain_line", "on_terminal"]

#: Seconds between two plain lines of one bar (the last one is always printed).
PLAIN_INTERVAL_S = 5.0

#: True inside :func:`silenced`: every new bar is hidden.
_SILENCED: ContextVar[bool] = ContextVar("andoyer_progress_silenced", default=False)


@contextmanager
def silenced() -> Iterator[None]:
    """Hide every :class:`Progress` bar made inside this context (this thread)."""
    token = _SILENCED.set(True)
    try:
        yield
    finally:
        _SILENCED.reset(token)


def _in_notebook() -> bool:
    """Whether this process is a running Jupyter kernel (importing ipykernel is not)."""
    ipython = sys.modules.get("IPython")
    shell = ipython.get_ipython() if ipython is not None else None
    return shell is not None and getattr(shell, "kernel", None) is not None


def on_terminal() -> bool:
    """Whether a bar can redraw itself: stderr is a terminal, or this is a notebook."""
    if _in_notebook():
        return True
    isatty = getattr(sys.stderr, "isatty", None)
    return bool(isatty and isatty())


def plain_line(done: int, total: int, label: str, seconds: float,
               postfix: str | None = None) -> str:
    """The line a bar prints in place of a redraw where stderr is no terminal.

    Parameters
    ----------
    done, total : int
        Units done, and in all.
    label : str
        What the bar counts.
    seconds : float
        Time since the bar started.
    postfix : str, optional
        The bar's fixed text (e.g. a dashboard address), after a semicolon.

    Examples
    --------
    >>> plain_line(3, 12, "chaos map", 4.25)
    '[3/12] chaos map: 25 %, 4.2 s'
    >>> plain_line(2, 4, "scan", 0.0, "dashboard http://127.0.0.1:8787/status")
    '[2/4] scan: 50 %, 0.0 s; dashboard http://127.0.0.1:8787/status'
    """
    pct = 100.0 * done / total if total else 100.0
    line = f"[{done}/{total}] {label}: {pct:.0f} %, {seconds:.1f} s"
    return f"{line}; {postfix}" if postfix else line


@cache
def _widgets() -> bool:
    """Whether ipywidgets is installed (looked up once: a short call makes many bars)."""
    return importlib.util.find_spec("ipywidgets") is not None


class _Hidden:
    """What :class:`Progress` needs of a tqdm bar that is never shown."""

    disable = True

    def __init__(self, tqdm: Any) -> None:
        self.tqdm = tqdm

    def update(self, k: int) -> None:
        pass

    def write(self, line: str, file: Any) -> None:
        self.tqdm.write(line, file=file)

    def set_postfix_str(self, postfix: str, refresh: bool) -> None:
        pass

    def refresh(self) -> None:
        pass

    def close(self) -> None:
        pass


class Progress:
    """A progress bar of ``total`` units labelled ``label``.

    Parameters
    ----------
    total : int
    label : str
    enabled : bool or None
        ``None``: shown when stderr is a terminal (tqdm's own test).
    postfix : str, optional
        Fixed text after the bar (e.g. a dashboard address).
    initial : int, default 0
        Units already done when the bar starts (a resumed scan).
    """

    def __init__(self, total: int, label: str, enabled: bool | None = None,
                 postfix: str | None = None, initial: int = 0) -> None:
        if _widgets():
            from tqdm.auto import tqdm  # a widget bar in notebooks
        else:  # tqdm.auto would warn in a notebook without ipywidgets: a text bar
            from tqdm.std import tqdm

        if not hasattr(tqdm, "_lock"):
            # tqdm's default lock holds a multiprocessing semaphore: a worker process
            # ended by its parent (andoyer.processes) would leave it to multiprocessing's
            # resource tracker, which prints "leaked semaphore" on stderr. Bars of
            # andoyer need a thread lock only.
            tqdm.set_lock(threading.RLock())
        self.total, self.done = int(total), int(initial)
        self.label, self._postfix = label, postfix
        if _SILENCED.get():
            enabled = False
        #: Plain lines instead of a bar: asked for, where stderr is a pipe or a file.
        self.plain = enabled is True and not on_terminal()
        if self.plain:
            enabled = False
        self._t0 = self._last = time.perf_counter()
        self._tenth = 10 * self.done // self.total if self.total else 0
        # tqdm's disable=None hides the bar when the stream is not a terminal. A bar
        # hidden for sure is no tqdm at all (its start costs a short call's time).
        self._bar: Any = _Hidden(tqdm) if enabled is False else tqdm(
            total=self.total, desc=label, file=sys.stderr, initial=initial,
            disable=None if enabled is None else not enabled, mininterval=0.5, unit="",
            dynamic_ncols=True, postfix=postfix)
        self.enabled = not self._bar.disable or self.plain

    def update(self, k: int = 1) -> None:
        """``k`` more units done."""
        self.done += k
        self._bar.update(k)
        if self.plain and self.total and self.done < self.total:
            tenth = 10 * self.done // self.total
            now = time.perf_counter()
            if tenth > self._tenth and now - self._last >= PLAIN_INTERVAL_S:
                self._tenth, self._last = tenth, now
                self.write(plain_line(self.done, self.total, self.label, now - self._t0,
                                      self._postfix))

    def write(self, line: str) -> None:
        """Print ``line`` on stderr above the bar (also when the bar is hidden)."""
        self._bar.write(line, file=sys.stderr)

    def describe(self, postfix: str) -> None:
        """Show ``postfix`` after the bar (e.g. what is running now)."""
        self._bar.set_postfix_str(postfix, refresh=True)

    def refresh(self) -> None:
        """Redraw the bar (its clock moves on while a long unit runs)."""
        if self.enabled:
            self._bar.refresh()

    def close(self) -> None:
        """End the bar (its line stays; a plain bar prints its last line once)."""
        if self.plain:
            self.plain = False
            self.write(plain_line(self.done, self.total, self.label,
                                  time.perf_counter() - self._t0, self._postfix))
        self._bar.close()

    def __enter__(self) -> Progress:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def close_all() -> None:
    """Close every bar still open (a command ended by an error or a signal mid-way), so
    that the message that follows starts on a line of its own."""
    from tqdm.std import tqdm

    for bar in list(getattr(tqdm, "_instances", ())):
        bar.close()
