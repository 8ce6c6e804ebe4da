"""A signal whose exception Python cannot raise where it lands is not lost.

Python runs a signal handler in the main thread wherever that thread is, also inside a
finalizer (``__del__``), where an exception is passed to ``sys.unraisablehook`` and the
interrupted code goes on: the no-heyoka CI job once saw ``andoyer section`` take a
SIGTERM during its start-up and end with exit 0. Each case runs in a fresh interpreter,
which signals itself.
"""

from __future__ import annotations

import subprocess
import sys
import textwrap

#: A finalizer that runs for 0.3 s; the signal comes 0.1 s into it, then the work goes on
#: for 3 s of plain Python: the signal must end the work there, with nothing printed.
_FINALIZER = """
import os, signal, threading, time
from andoyer.cli._signals import interrupts

class Slow:
    def __del__(self):
        t = time.monotonic()
        while time.monotonic() - t < 0.3:
            pass

def work():
    threading.Timer(0.1, lambda: os.kill(os.getpid(), signal.SIGTERM)).start()
    s = Slow()
    del s
    t = time.monotonic()
    while time.monotonic() - t < 3.0:
        pass
    return "finished"

try:
    with interrupts() as seen:
        print(work(), seen)
except KeyboardInterrupt as exc:
    print("interrupted", type(exc).__name__, exc)
"""

#: A command whose library swallows the interruption with a bare ``except``.
_SWALLOWED = """
import os, signal, sys, time
import andoyer.cli as cli
import andoyer.cli.paper_check as paper_check

def run(args):
    try:
        os.kill(os.getpid(), signal.SIGTERM)
        time.sleep(1.0)
    except BaseException:
        pass  # a library that swallows everything
    return 0

paper_check.run = run  # the command's function, as register() finds it
cli.main(["paper-check"])
"""


def _run(code: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-c", textwrap.dedent(code)], capture_output=True,
                          text=True, timeout=120)


def test_a_signal_landing_in_a_finalizer_still_interrupts():
    """Before the fix: "finished [15]" after 3 s, and a traceback "Exception ignored"."""
    done = _run(_FINALIZER)
    assert done.stdout.strip() == "interrupted Interrupted SIGTERM", (done.stdout, done.stderr)
    assert "Exception ignored" not in done.stderr and "Traceback" not in done.stderr, \
        done.stderr


def test_a_command_that_swallowed_the_signal_ends_as_interrupted():
    """A command returning normally after a signal was taken exits 130, one line."""
    from andoyer.cli import EXIT_CODES

    done = _run(_SWALLOWED)
    assert done.returncode == EXIT_CODES["interrupted"], (done.returncode, done.stderr)
    lines = [ln for ln in done.stderr.splitlines() if ln.strip()]
    assert len(lines) == 1 and "interrupted (SIGTERM)" in lines[0], done.stderr
