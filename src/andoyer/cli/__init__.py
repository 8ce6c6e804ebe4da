"""Command line of andoyer: one module per command, each a thin layer over the library.

Every public module of this package is a command. It defines ``NAME`` (the command word),
``ORDER`` (its place in ``andoyer --help``), ``register(sub)`` which adds its parser to the
sub-parsers and sets ``func``, and imports the heavy parts of the library only inside the
function that runs, so that ``andoyer --help`` stays fast.
"""

from __future__ import annotations

import argparse
import atexit
import contextlib
import errno
import importlib
import logging
import os
import pkgutil
import shutil
import sys
import tempfile
import warnings
from collections.abc import Iterator, Sequence
from pathlib import Path

from andoyer._version import __version__
from andoyer.cli._signals import ignore_until_exit, interrupts
from andoyer.outputs import release_all

__all__ = ["main", "build_parser", "EXIT_CODES"]


def _command_modules() -> list:
    mods = [importlib.import_module(f"{__name__}.{m.name}")
            for m in pkgutil.iter_modules(__path__) if not m.name.startswith("_")]
    return sorted(mods, key=lambda m: (getattr(m, "ORDER", 100), m.NAME))


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of the ``andoyer`` command."""
    parser = argparse.ArgumentParser(
        prog="andoyer",
        description="Phase space of the heavy rigid body (Hess gyroscope) in "
                    "Andoyer-Deprit variables.",
        epilog="exit codes: " + ", ".join(f"{code} {kind}" for kind, code in
                                          EXIT_CODES.items()) + "; 0 success")
    parser.add_argument("--version", action="version", version=f"andoyer {__version__}")
    parser.add_argument("--debug", action="store_true",
                        help="show the Python traceback of a failure")
    parser.add_argument("--no-limits", action="store_true",
                        help="lift the cost guards (estimated integration steps and memory "
                             "of one call; see andoyer.integrate.budget)")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for mod in _command_modules():
        mod.register(sub)
    for command in sub.choices.values():  # --debug after the command word too
        command.add_argument("--debug", action="store_true", default=argparse.SUPPRESS,
                             help="show the Python traceback of a failure")
    return parser


#: Exit codes of ``andoyer``, one per class of expected failure (argparse's usage errors
#: are 2 as well). Documented in ``andoyer --help``.
EXIT_CODES = {
    "bad input": 2,
    "cost limit": 3,
    "file system": 4,
    "out of memory": 5,
    "integration failed": 6,
    "missing dependency": 7,
    "encoder failed": 8,
    "internal error": 70,
    "interrupted": 130,
}


def _classify(exc: BaseException) -> tuple[str, str]:
    """``(class, message)`` of an exception that ends a command."""
    from andoyer.errors import CostLimitError, EncoderError, IntegrationError

    if isinstance(exc, KeyboardInterrupt):
        signame = getattr(exc, "signal", "SIGINT")
        note = getattr(exc, "note", None) or ("files already written are complete, nothing "
                                              "half-written was left behind")
        return "interrupted", f"interrupted ({signame}); {note}"
    if isinstance(exc, CostLimitError):
        return "cost limit", str(exc)
    if isinstance(exc, MemoryError):
        return "out of memory", ("out of memory; ask for less (fewer orbits, crossings, grid "
                                 "points or output times)")
    if isinstance(exc, EncoderError):
        return "encoder failed", str(exc)
    if isinstance(exc, ModuleNotFoundError):
        return "missing dependency", f"{exc}; install it or choose another --engine"
    if isinstance(exc, OSError) and exc.errno == errno.ENOSPC:
        where = exc.filename or "the device"
        return "file system", (f"no space left on {where}; free some space or write "
                               "elsewhere (nothing half-written was left behind)")
    if isinstance(exc, OSError):
        where = f" {exc.filename!r}" if getattr(exc, "filename", None) else ""
        return "file system", f"{exc.strerror or exc}{':' if where else ''}{where}"
    if isinstance(exc, IntegrationError | FloatingPointError):
        return "integration failed", f"integration failed: {exc}"
    if isinstance(exc, ValueError | TypeError):
        return "bad input", str(exc)
    return "internal error", (f"internal error ({type(exc).__name__}: {exc}); rerun with "
                              "--debug for the traceback and report it")


#: Flags users reach for that a command spells otherwise.
_SYNONYMS = {"--out": "--store", "--output": "--out", "--h": "--energy"}


def _unrecognized(parser: argparse.ArgumentParser, command: str, extra: list[str]) -> None:
    """Report arguments the command does not take with the command's own usage (argparse
    would print the top-level one), suggesting the nearest flag of the command."""
    import difflib

    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    p = sub.choices[command]
    flags = [s for a in p._actions if a.help != argparse.SUPPRESS for s in a.option_strings]
    hints = []
    for word in extra:
        flag = word.split("=")[0]
        close = ([_SYNONYMS[flag]] if _SYNONYMS.get(flag) in flags else
                 difflib.get_close_matches(flag, flags, n=1, cutoff=0.6))
        if word.startswith("-") and close:
            hints.append(f"{flag}: did you mean {close[0]}?")
    p.error(f"unrecognized arguments: {' '.join(extra)}"
            + (f" ({'; '.join(hints)})" if hints else "")
            + f"; see andoyer {command} --help")


#: Who speaks on stderr: ``andoyer COMMAND`` once :func:`main` has parsed the command
#: (as in its error line), ``andoyer`` before.
_speaker = ["andoyer"]


def _warning_line(text: object) -> None:
    """The command line's warning: one line on stderr, ``andoyer COMMAND: warning: ...``
    (the prefix of the command's error line)."""
    sys.stderr.write(f"{_speaker[0]}: warning: {' '.join(str(text).split())}\n")


def _show_warning(message: Warning | str, category: type[Warning], filename: str,
                  lineno: int, file: object = None, line: str | None = None) -> None:
    """andoyer's own warnings as the warning line; others as Python's."""
    if category.__module__ == "andoyer.errors":
        _warning_line(message)
    else:
        _python_show_warning(message, category, filename, lineno, file, line)  # type: ignore[arg-type]


_python_show_warning = warnings.showwarning

#: Libraries whose logged warnings reach a command's stderr: Matplotlib logs
#: "findfont: Font family ... not found" (once per text drawn) and "Matplotlib is
#: building the font cache", which Python's last-resort handler printed as raw lines.
LOGGED_WARNINGS = ("matplotlib",)


class _LoggedWarning(logging.Handler):
    """A library's logged warning as the warning line, each distinct message once."""

    def __init__(self) -> None:
        super().__init__(logging.WARNING)
        self.seen: set[str] = set()

    def emit(self, record: logging.LogRecord) -> None:
        try:
            text = f"{record.name.split('.')[0]}: {record.getMessage()}"
        except Exception:  # a record whose message cannot be formatted
            self.handleError(record)
            return
        if text not in self.seen:
            self.seen.add(text)
            _warning_line(text)


@contextlib.contextmanager
def _logged_warnings() -> Iterator[None]:
    """Within the block the loggers of :data:`LOGGED_WARNINGS` write the warning line
    (and nothing else: they do not propagate to the root logger); restored after."""
    handler = _LoggedWarning()
    loggers = [logging.getLogger(name) for name in LOGGED_WARNINGS]
    propagate = [logger.propagate for logger in loggers]
    for logger in loggers:
        logger.addHandler(handler)
        logger.propagate = False
    try:
        yield
    finally:
        for logger, before in zip(loggers, propagate, strict=True):
            logger.removeHandler(handler)
            logger.propagate = before


def _writable(folder: Path) -> bool:
    try:
        folder.mkdir(parents=True, exist_ok=True)
        with tempfile.TemporaryFile(dir=folder):
            return True
    except OSError:
        return False


def _matplotlib_config() -> None:
    """A private Matplotlib folder for this run where the user's is not writable.

    Matplotlib keeps its font cache in its configuration folder and, where that is read
    only (a read-only home), warns in every process that imports it; this run (and the
    processes it starts, which inherit ``MPLCONFIGDIR``) uses a temporary folder
    instead, removed at exit. Nothing is imported.
    """
    if os.environ.get("MPLCONFIGDIR"):
        return
    if sys.platform.startswith("linux"):
        base = Path(os.environ.get("XDG_CONFIG_HOME") or Path.home() / ".config")
        folder = base / "matplotlib"
    else:
        folder = Path.home() / ".matplotlib"
    if _writable(folder):
        return
    tmp = tempfile.mkdtemp(prefix="andoyer-matplotlib-")
    atexit.register(shutil.rmtree, tmp, ignore_errors=True)
    os.environ["MPLCONFIGDIR"] = tmp


def _interrupted(signals: list[int]) -> KeyboardInterrupt:
    """The ``Interrupted`` of the first signal the command took."""
    import signal

    from andoyer.errors import Interrupted

    return Interrupted(signal.Signals(signals[0]).name)


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``andoyer`` console script.

    Every expected failure ends with one line on stderr and ``SystemExit`` with the exit
    code of its class (:data:`EXIT_CODES`), as argparse's usage errors do; never a
    traceback (``--debug`` shows it).

    Parameters
    ----------
    argv : sequence of str, optional
        The arguments (default: ``sys.argv[1:]``).
    """
    parser = build_parser()
    args, extra = parser.parse_known_args(argv)
    if extra:  # the command's usage, not the top-level one, with a suggestion
        _unrecognized(parser, args.command, extra)
    _speaker[0] = f"andoyer {args.command}"
    warnings.showwarning = _show_warning
    _matplotlib_config()
    try:
        with interrupts() as signals, _logged_warnings():
            try:
                if args.no_limits:
                    import math

                    from andoyer.integrate.budget import set_limits

                    set_limits(steps=math.inf, memory=math.inf)
                code = int(args.func(args))
                # taken, then swallowed by a library: still an interruption -- except for
                # a server (``serves``), whose normal stop is a signal (it says "stopped")
                if signals and not getattr(args, "serves", False):
                    raise _interrupted(signals)
                return code
            finally:
                release_all()
    except (Exception, KeyboardInterrupt) as exc:
        if getattr(args, "debug", False):
            raise
        if signals and not isinstance(exc, KeyboardInterrupt):
            # a failure caused by the interruption (a pool whose worker was ended)
            exc = _interrupted(signals)
        kind, message = _classify(exc)
        from andoyer.progress import close_all

        close_all()  # a bar left open would run into the message
        sys.stderr.write(f"andoyer {args.command}: error: {message}\n")
        raise SystemExit(EXIT_CODES[kind]) from None
    finally:
        if argv is None:  # the command line: the process exits next
            ignore_until_exit()


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
