"""The report's run: progress as items finish, no stray output, no worker left behind."""

from __future__ import annotations

import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from andoyer.report.paper import ITEMS, build_paper

ONLY = ["fig2", "heteroclinic", "paper-check"]


def test_items_announced_as_they_finish(tmp_path, capsys, monkeypatch):
    """With two processes the worker's item (fig2, the longest, started first) finishes
    after the two short ones built here: each line comes as its item ends, counting the
    items done, with its time; the report keeps its own order. The plain lines naming the
    items still running (every 50 ms here, as on a machine where an item takes over
    :data:`~andoyer.report.schedule.HEARTBEAT_S`) are told from the items' lines by their
    own words and do not count as items."""
    from andoyer.report import schedule

    monkeypatch.setattr(schedule, "HEARTBEAT_S", 0.0)
    monkeypatch.setattr(schedule, "_TICK_S", 0.05)
    build_paper(tmp_path / "p", quick=True, only=ONLY, jobs=2, progress=True)
    err = capsys.readouterr().err
    lines = err.splitlines()
    running = [line for line in lines if re.match(r"\[\d/3\] andoyer paper: running ", line)]
    assert running, lines  # the heartbeat ran while fig2 was built
    assert all(re.search(r"; \d+ s in all$", line) for line in running), running
    items = [line for line in lines if re.match(r"\[\d/3\] ", line) and line not in running]
    titles = {i.key: i.title for i in ITEMS if i.key in ONLY}
    assert [line[:6] for line in items] == ["[1/3] ", "[2/3] ", "[3/3] "]
    assert all(re.search(r" \.\.\. \d+\.\d s$", line) for line in items), items
    assert items[-1].startswith(f"[3/3] {titles['fig2']} ... "), items  # finished last
    assert "" not in lines  # no stray blank line when stderr is not a terminal
    assert lines[-1].startswith("wrote ")
    html = (tmp_path / "p" / "index.html").read_text()
    at = [html.find(titles[k]) for k in ONLY]
    assert all(x >= 0 for x in at) and at == sorted(at)  # the report in its order


def test_a_plain_line_names_the_items_running(monkeypatch):
    """Without a terminal a line names the items still running (and for how long)."""
    from andoyer.report import schedule

    a = schedule.Announcer([i for i in ITEMS if i.key in ONLY], enabled=True)
    try:
        item = next(i for i in ITEMS if i.key == "fig2")
        a.start(item)
        line = a.heartbeat(a.running["fig2"] + 42.0)
        assert line.startswith("[0/3] andoyer paper: running fig2 (42 s)"), line
    finally:
        a.close()


def _children(pid: int) -> set[int]:
    """Every live descendant of ``pid`` (a /proc scan by parent pid)."""
    parents: dict[int, int] = {}
    for d in Path("/proc").iterdir():
        if d.name.isdigit():
            try:
                stat = (d / "stat").read_text()
            except OSError:
                continue
            fields = stat.rsplit(")", 1)[1].split()
            if fields[0] != "Z":
                parents[int(d.name)] = int(fields[1])
    found, todo = set(), [pid]
    while todo:
        p = todo.pop()
        kids = {c for c, pp in parents.items() if pp == p}
        found |= kids
        todo += list(kids)
    return found


def _session(sid: int) -> set[int]:
    """Live processes of session ``sid`` (those the command started)."""
    out = set()
    for d in Path("/proc").iterdir():
        if d.name.isdigit():
            try:
                fields = (d / "stat").read_text().rsplit(")", 1)[1].split()
            except OSError:
                continue
            if fields[0] != "Z" and int(fields[4]) == sid:
                out.add(int(d.name))
    return out


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="/proc scan")
@pytest.mark.timeout(240)
def test_sigterm_leaves_no_worker(tmp_path):
    """SIGTERM to ``andoyer paper --jobs 2`` while its worker builds an item: the
    command ends and no process it started lives on."""
    cmd = [sys.executable, "-m", "andoyer", "paper", "--out", str(tmp_path / "p"),
           "--quick", "--jobs", "2", "--engine", "numba", "--only", "chaos", "border",
           "fig1"]
    log = (tmp_path / "stderr.txt").open("wb")
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=log,
                            start_new_session=True)
    try:
        deadline = time.monotonic() + 120
        worker = None
        while worker is None and time.monotonic() < deadline and proc.poll() is None:
            for c in _children(proc.pid):
                try:
                    if b"spawn_main" in Path(f"/proc/{c}/cmdline").read_bytes():
                        worker = c
                except OSError:
                    pass
            time.sleep(0.2)
        assert worker is not None, "the worker process never started"
        time.sleep(2.0)  # the worker is importing or building its item
        os.kill(proc.pid, signal.SIGTERM)
        proc.wait(timeout=60)
        deadline = time.monotonic() + 30
        while _session(proc.pid) and time.monotonic() < deadline:
            time.sleep(0.2)
        assert _session(proc.pid) == set(), "processes of the command survived SIGTERM"
    finally:
        for p in _session(proc.pid):
            os.kill(p, signal.SIGKILL)
        if proc.poll() is None:
            proc.kill()
            proc.wait(timeout=30)
        log.close()


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="needs a pty")
@pytest.mark.timeout(240)
def test_progress_bar_in_a_terminal(tmp_path):
    """In a terminal: the bar shows before the first item is done, item lines follow as
    items finish (one process: in the order built), and no line is blank."""
    import pty

    cmd = [sys.executable, "-m", "andoyer", "paper", "--out", str(tmp_path / "p"),
           "--quick", "--jobs", "1", "--engine", "numba", "--only", "heteroclinic",
           "paper-check"]
    pid, fd = pty.fork()
    if pid == 0:  # the child: the command, its stdout and stderr on a 40 x 120 terminal
        import fcntl
        import struct
        import termios

        fcntl.ioctl(0, termios.TIOCSWINSZ, struct.pack("HHHH", 40, 120, 0, 0))
        os.execv(cmd[0], cmd)
    chunks = []
    try:
        while True:
            try:
                data = os.read(fd, 4096)
            except OSError:  # the terminal closed: the command ended
                break
            if not data:
                break
            chunks.append(data)
    finally:
        _, status = os.waitpid(pid, 0)
        os.close(fd)
    assert os.waitstatus_to_exitcode(status) == 0
    text = b"".join(chunks).decode("utf-8", "replace")
    bar = text.find("andoyer paper:")
    first = text.find("[1/2] Heteroclinic")
    assert 0 <= bar < first, text
    assert text.find("[2/2] Every printed formula") > first
    # What stays on the screen: per line, the text after the last carriage return,
    # without the terminal's control sequences.
    screen = [re.sub(r"\x1b\[[0-9;]*[A-Za-z]", "", line).rsplit("\r", 1)[-1].strip()
              for line in text.replace("\r\n", "\n").split("\n")]
    assert "" not in screen[:-1], screen


def test_items_build_with_blas_on_one_thread():
    """An item runs with BLAS on one thread (the report shares the cores out itself), and
    the caller's BLAS threads are its own again afterwards."""
    import dataclasses

    from threadpoolctl import threadpool_info, threadpool_limits

    from andoyer.body import RigidBody
    from andoyer.report import schedule
    from andoyer.report.base import Context

    def blas_threads() -> set[int]:
        return {p["num_threads"] for p in threadpool_info() if p["user_api"] == "blas"}

    if not blas_threads():
        pytest.skip("NumPy's BLAS is not visible to threadpoolctl")
    seen: list[set[int]] = []
    item = dataclasses.replace(next(i for i in ITEMS if i.key == "fig2"),
                               build=lambda ctx: seen.append(blas_threads()))
    with threadpool_limits(limits=3, user_api="blas"):
        schedule._build_item(item, Context(Path("."), RigidBody.paper()))
        assert blas_threads() == {3}
    assert seen == [{1}]
