"""Progress a person can follow: a bar on a terminal, plain lines in a pipe or a log."""

from __future__ import annotations

import re

import pytest

from andoyer import progress
from andoyer.progress import Progress


def test_plain_lines_where_stderr_is_no_terminal(capsys, monkeypatch):
    """Asked for (``enabled=True``, as the commands ask) with stderr captured (no
    terminal): no bar redraws, ``[k/n] label: p %, t s`` lines at tenths and one at the
    end."""
    monkeypatch.setattr(progress, "PLAIN_INTERVAL_S", 0.0)
    bar = Progress(10, "chaos map", enabled=True)
    assert bar.plain and bar.enabled
    for _ in range(10):
        bar.update(1)
    bar.close()
    err = capsys.readouterr().err
    assert "\r" not in err and "|" not in err
    lines = err.splitlines()
    assert all(re.fullmatch(r"\[\d+/10\] chaos map: \d+ %, \d+\.\d s", ln) for ln in lines), lines
    assert lines[0].startswith("[1/10] ") and lines[-1].startswith("[10/10] chaos map: 100 %")
    assert len(lines) == 10  # nine tenths on the way, the end once


def test_plain_lines_are_rate_limited(capsys):
    """A fast loop prints its last line only (not a line per tenth)."""
    bar = Progress(1000, "orbits", enabled=True)
    for _ in range(1000):
        bar.update(1)
    bar.close()
    bar.close()  # closing twice prints nothing more
    lines = capsys.readouterr().err.splitlines()
    assert len(lines) == 1 and lines[0].startswith("[1000/1000] orbits: 100 %, "), lines

def test_default_stays_quiet_and_silenced_wins(capsys):
    """``enabled=None`` (the library's default) stays hidden without a terminal, and
    :func:`progress.silenced` hides even a bar asked for."""
    bar = Progress(3, "quiet")
    bar.update(3)
    bar.close()
    with progress.silenced():
        inner = Progress(3, "inner", enabled=True)
        inner.update(3)
        inner.close()
    assert not bar.enabled and not inner.plain
    assert capsys.readouterr().err == ""


def test_an_imported_kernel_module_is_no_notebook(capsys):
    """Importing ipykernel (a test or a library may) does not make a pipe a notebook:
    plain lines stay plain."""
    pytest.importorskip("ipykernel")
    import ipykernel.kernelapp  # noqa: F401

    bar = Progress(2, "after ipykernel", enabled=True)
    bar.update(2)
    bar.close()
    err = capsys.readouterr().err
    assert bar.plain is False and "\r" not in err, err  # closed: plain turned off
    assert err.splitlines() == [err.splitlines()[-1]] and err.startswith("[2/2] ")
