"""The process-level suite: every signal is Ctrl-C, nothing is left behind, every server
listens on the loopback interface only.

Each long command runs in a fresh process (its own session, as under a terminal or a
batch scheduler) and gets SIGINT, SIGTERM or SIGHUP; then: the documented exit code
(130), one line on stderr (no traceback), no process of its tree alive, no temporary
file, no lock sidecar, and for a scan the exact store after resuming. SIGINT and SIGHUP
go to the whole process group (what a terminal sends), SIGTERM to the command's
process only (what ``kill``, a batch scheduler or a container stop sends).

``make test`` runs one case per kind of child (none, a process pool, a Dask cluster);
the ``slow`` sweep sends each signal to each long command at random moments (seeded).
"""

from __future__ import annotations

import ipaddress
import os
import random
import re
import signal
import subprocess
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pytest

psutil = pytest.importorskip("psutil")

ANDOYER = [sys.executable, "-m", "andoyer"]
#: Progress output on stderr (tqdm bars, the report's "[k/n] item ... s" lines).
PROGRESS = re.compile(r"\d+%\||^\[\d+/\d+\] ")
TIMEOUT = 300.0  # seconds for any one command, after which the test fails

#: A small scan whose chunks take a while each (so that it can be interrupted); numba:
#: its machine code is cached on disk, where heyoka would compile in every worker.
SCAN_TOML = """\
[body]
kind = "hess"
name = "paper"
[parameters]
mu = [0.01, 0.1, 0.2, 0.3]
h = 0.3
[task]
kind = "section"
section = "theta2=0"
n_orbits = 3
n_crossings = 300
[integrator]
engine = "numba"
"""

#: The long commands, each small enough for a test.
COMMANDS: dict[str, list[str]] = {
    "section": ["section", "--n-orbits", "20", "--n-crossings", "20000", "--out", "s.nc"],
    "orbit": ["orbit", "--andoyer", "0.3,1,0.2,1,0", "--t-end", "30000", "--n-out",
              "30001", "--out", "o.nc"],
    "chaos-map": ["chaos-map", "--n", "8", "--t-end", "300", "--out", "c.nc"],
    "manifolds": ["manifolds", "--mu-list", "0.01", "--n-phase", "8", "--no-hess-check",
                  "--out", "m"],
    "paper": ["paper", "--out", "p", "--quick", "--only", "fig1", "fig2", "fig3",
              "paper-check", "--jobs", "2"],
    "scan": ["scan", "cfg.toml", "--store", "s.zarr", "--workers", "2", "--no-progress"],
    "frequencies": ["frequencies", "--n-orbits", "8", "--t-end", "3000", "--engine", "numba",
                    "--out", "f.nc"],
    "indicators": ["indicators", "--andoyer", "0.3,0,0.3,1,0", "--t-end", "30000",
                   "--engine", "numba", "--out", "i.nc"],
    "paper-check": ["paper-check", "--points", "20000"],
    "resonances": ["resonances", "--n-orbits", "8", "--n-crossings", "300", "--engine",
                   "numba", "--out", "r.nc"],
    "animate": ["animate", "--andoyer", "0.3,0,0.3,1,0", "--frames", "400", "--out",
                "g.gif"],
    "last-torus": ["last-torus", "--body", "hess", "--A", "3", "--B", "1", "--C", "2", "--mu",
                   "0.001", "--energy", "1", "--n-convergents", "6", "--mu-range", "0.001",
                   "0.1", "--engine", "numba", "--out", "t.nc"],
}
#: Commands the sweep leaves out, and why: ``explore`` has its own test below (it stops
#: with exit 0); ``atlas`` draws a store in about a second (its only outputs are written
#: atomically by ``save_figure``, its lock released by ``cli.main`` on every way out);
#: ``prove`` and ``verify`` take about 2 s, start no process, and ``prove`` writes its one
#: certificate through ``cli._common.output_file`` (atomic, locked).
NOT_SWEPT = {"explore", "atlas", "prove", "verify"}


@dataclass
class Outcome:
    """What a signalled command did and left."""

    returncode: int
    out: str
    err: str
    signalled: bool
    seen: set[int] = field(default_factory=set)  # pids of its tree while it ran
    listening: set[tuple[str, int]] = field(default_factory=set)


def _tree(pid: int) -> list[psutil.Process]:
    try:
        root = psutil.Process(pid)
        return [root, *root.children(recursive=True)]
    except psutil.Error:
        return []


def _threads(p: psutil.Process) -> int:
    """Threads of ``p`` (0 once it has ended)."""
    try:
        return p.num_threads()
    except psutil.Error:
        return 0


def handles_sigterm(pid: int) -> bool:
    """Whether the process catches SIGTERM: ``andoyer.cli.main`` has started (Python
    itself catches SIGINT only). Read from ``/proc/PID/status`` (Linux)."""
    try:
        with open(f"/proc/{pid}/status") as f:
            mask = next(int(ln.split()[1], 16) for ln in f if ln.startswith("SigCgt:"))
    except (OSError, StopIteration):
        return False
    return bool(mask >> (signal.SIGTERM - 1) & 1)


def listening_sockets(procs: list[psutil.Process]) -> set[tuple[str, int]]:
    """(address, port) of every listening TCP socket of ``procs``."""
    found = set()
    for p in procs:
        try:
            conns = p.net_connections(kind="inet")
        except psutil.Error:
            continue
        found |= {(c.laddr.ip, c.laddr.port) for c in conns if c.status == psutil.CONN_LISTEN}
    return found


def _alive(pids: set[int]) -> list[str]:
    out = []
    for pid in pids:
        try:
            p = psutil.Process(pid)
            if p.status() != psutil.STATUS_ZOMBIE:
                out.append(f"{pid} {' '.join(p.cmdline())[:120]}")
        except psutil.Error:
            pass
    return out


def run_signalled(args: list[str], cwd: Path, sig: signal.Signals | None,
                  ready: Callable[..., bool]) -> Outcome:
    """Run ``andoyer ARGS`` in ``cwd``; send ``sig`` once ``ready(tree, seconds,
    listening)``, the seconds counted from when the command started (its signal handlers
    installed), ``listening`` the sockets seen so far."""
    proc = subprocess.Popen([*ANDOYER, *args], cwd=cwd, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, start_new_session=True)
    t0 = time.monotonic()
    started: float | None = None
    seen: set[int] = set()
    listening: set[tuple[str, int]] = set()
    signalled = False
    try:
        while proc.poll() is None and time.monotonic() - t0 < TIMEOUT:
            tree = _tree(proc.pid)
            seen |= {p.pid for p in tree}
            listening |= listening_sockets(tree)
            if started is None and handles_sigterm(proc.pid):
                started = time.monotonic()
            if (sig is not None and not signalled and started is not None
                    and ready(tree, time.monotonic() - started, listening)):
                if sig == signal.SIGTERM:
                    proc.send_signal(sig)
                else:  # a terminal sends these to the whole foreground group
                    os.killpg(proc.pid, sig)
                signalled = True
            time.sleep(0.05)
        out, err = proc.communicate(timeout=max(1.0, TIMEOUT - (time.monotonic() - t0)))
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.communicate()
    return Outcome(proc.returncode, out, err, signalled, seen - {proc.pid}, listening)


def assert_clean_end(o: Outcome, cwd: Path, command: str) -> None:
    """Exit code, one line, no process, no temporary file, no lock left."""
    from andoyer.cli import EXIT_CODES

    deadline = time.monotonic() + 15  # the resource tracker exits after its parent
    while _alive(o.seen) and time.monotonic() < deadline:
        time.sleep(0.1)
    assert not _alive(o.seen), f"processes left by {command}: {_alive(o.seen)}"
    left = [str(p.relative_to(cwd)) for p in cwd.rglob("*")
            if p.name.endswith((".tmp", ".partial", ".andoyer-lock.json", ".andoyer-lock"))
            or ".init-" in p.name]
    assert not left, f"{command} left {left}"
    assert "Traceback" not in o.err and "leaked" not in o.err, o.err
    if o.returncode == 0:  # it finished before the signal was handled
        return
    assert o.returncode == EXIT_CODES["interrupted"], (o.returncode, o.err)
    lines = [ln for ln in re.split(r"[\r\n]", o.err) if ln.strip() and not PROGRESS.search(ln)]
    assert len(lines) == 1, o.err  # progress bars and [k/n] item lines aside: one line
    assert lines[0].startswith(f"andoyer {command}: error: interrupted (SIG"), o.err


def _prepare(cwd: Path) -> None:
    (cwd / "cfg.toml").write_text(SCAN_TOML)


def _same_store(a: Path, b: Path) -> None:
    import xarray as xr

    da, db = xr.open_zarr(a).load(), xr.open_zarr(b).load()
    assert sorted(da.variables) == sorted(db.variables)
    for name in da.variables:
        assert np.array_equal(da[name].values, db[name].values,
                              equal_nan=da[name].dtype.kind == "f"), name
    assert {k: v for k, v in da.attrs.items() if k != "created"} == \
        {k: v for k, v in db.attrs.items() if k != "created"}


def _done_chunks(store: Path) -> int:
    c = store / "done" / "c"
    return len([p for p in c.rglob("*") if p.is_file()]) if c.exists() else 0


def _resume_is_exact(cwd: Path) -> None:
    """The interrupted store, resumed (what the same command does, here in-process and
    serially), equals a store computed in one go."""
    from andoyer.scan.run import run_scan

    report = run_scan(cwd / "cfg.toml", cwd / "s.zarr", scheduler="serial", progress=False)
    assert report.resumed >= 1 or report.computed == report.tasks
    run_scan(cwd / "cfg.toml", cwd / "whole.zarr", scheduler="serial", progress=False)
    _same_store(cwd / "whole.zarr", cwd / "s.zarr")


# ---------------------------------------------------------------------- make test
def test_sigterm_ends_a_command_without_children_cleanly(tmp_path):
    """SIGTERM to ``andoyer section`` (no children) once its work has started."""
    # Ready once its integration runs: a second thread (the kernels' pool or heyoka's)
    # after a second. A fixed 1 s once signalled the no-heyoka run during its imports,
    # which then ended with exit 0.
    o = run_signalled(COMMANDS["section"], tmp_path, signal.SIGTERM,
                      lambda tree, t, *_: t > 1.0 and _threads(tree[0]) >= 3)
    assert o.signalled and o.returncode == 130, (o.returncode, o.err)
    assert_clean_end(o, tmp_path, "section")


def test_sigterm_ends_a_process_pool_and_its_worker(tmp_path):
    """SIGTERM to ``andoyer paper --jobs 2`` once its worker process runs: the worker
    ends too (it used to live on), its temporary files are removed, one line."""
    # Ready once a pool worker has run its initializer (it catches SIGTERM): a fixed
    # delay raced a faster machine, where the whole command ended in 3.0 s.
    o = run_signalled(COMMANDS["paper"], tmp_path, signal.SIGTERM,
                      lambda tree, *_: any(handles_sigterm(p.pid) for p in tree[1:]))
    assert o.signalled and o.seen, "the worker process never started"
    assert o.returncode == 130, (o.returncode, o.err)
    assert_clean_end(o, tmp_path, "paper")


_CHILD_WITH_A_BAR = """
import concurrent.futures as cf, multiprocessing as mp, os, signal
from andoyer.processes import child_signals
if __name__ == "__main__":
    with cf.ProcessPoolExecutor(1, mp_context=mp.get_context("spawn"),
                                initializer=child_signals) as pool:
        code = ("from tqdm import tqdm; tqdm(range(1), disable=True); "
                "import os, signal; os.kill(os.getpid(), signal.SIGTERM)")
        try:
            pool.submit(exec, code).result()
        except Exception:
            pass  # the worker ended by SIGTERM (BrokenProcessPool): what is tested
"""


def test_a_child_ended_by_sigterm_leaves_no_semaphore_to_report():
    """A pool worker that drew a progress bar and was ended by SIGTERM: no "leaked
    semaphore" from multiprocessing's resource tracker on the parent's stderr (tqdm's
    default lock is a named semaphore; the noheyoka CI job saw the message under
    ``andoyer paper``'s one line)."""
    done = subprocess.run([sys.executable, "-c", _CHILD_WITH_A_BAR], capture_output=True,
                          text=True, timeout=120)
    assert "leaked" not in done.stderr and "Traceback" not in done.stderr, done.stderr


def test_ctrl_c_on_a_local_cluster_scan_is_one_line_and_resumes_exactly(tmp_path):
    """Ctrl-C (SIGINT to the group) on a scan on a local Dask cluster, once a chunk is
    done: one line (no tracebacks of the workers), every process ended, every server
    of the cluster listened on 127.0.0.1 only, and the resumed store is exact."""
    _prepare(tmp_path)
    o = run_signalled(COMMANDS["scan"], tmp_path, signal.SIGINT,
                      lambda tree, t, *_: _done_chunks(tmp_path / "s.zarr") >= 1)
    assert o.signalled and len(o.seen) >= 2, "no worker process started"
    assert_clean_end(o, tmp_path, "scan")
    assert o.listening, "no listening socket seen (scheduler, workers, dashboard)"
    assert all(ipaddress.ip_address(ip).is_loopback for ip, _ in o.listening), o.listening
    if o.returncode == 130:
        assert "run the same command to resume" in o.err
    _resume_is_exact(tmp_path)


def test_the_explorer_listens_on_loopback_only():
    """``serve`` (what ``andoyer explore`` runs) opens loopback sockets only."""
    pytest.importorskip("panel")
    from andoyer.explore.server import serve

    me = psutil.Process()
    before = listening_sockets([me])
    handle = serve(threaded=True, n_crossings=5)
    assert handle is not None
    try:
        new = listening_sockets([me]) - before
        assert any(port == handle.port for _, port in new), new
        assert all(ipaddress.ip_address(ip).is_loopback for ip, _ in new), new
    finally:
        handle.stop()


# ---------------------------------------------------------------------- the sweep
SWEEP_SEED = 20261126


def test_every_command_is_swept_or_placed():
    from andoyer.cli import build_parser

    parser = build_parser()
    sub = next(a for a in parser._actions if a.__class__.__name__ == "_SubParsersAction")
    assert set(sub.choices) == set(COMMANDS) | NOT_SWEPT, set(sub.choices) ^ (
        set(COMMANDS) | NOT_SWEPT)


def _moments() -> list[tuple[str, signal.Signals, float]]:
    """(command, signal, seconds after start): each signal to each command, at a random
    moment in its first 15 s (seeded: a failure reproduces)."""
    rng = random.Random(SWEEP_SEED)
    return [(c, s, round(rng.uniform(0.0, 15.0), 2)) for c in COMMANDS
            for s in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)]


@pytest.mark.slow
@pytest.mark.parametrize("command, sig, when", _moments(),
                         ids=[f"{c}-{s.name}-{w}s" for c, s, w in _moments()])
def test_every_signal_to_every_long_command(tmp_path, command, sig, when):
    _prepare(tmp_path)
    o = run_signalled(COMMANDS[command], tmp_path, sig, lambda tree, t, *_: t > when)
    assert_clean_end(o, tmp_path, command)
    assert all(ipaddress.ip_address(ip).is_loopback for ip, _ in o.listening), o.listening
    if command == "scan" and o.returncode == 130:
        _resume_is_exact(tmp_path)


@pytest.mark.slow  # a fresh interpreter imports Panel and serves: ~10-20 s
@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM, signal.SIGHUP])
def test_andoyer_explore_listens_on_loopback_and_stops_on_every_signal(tmp_path, sig):
    """``andoyer explore``: every listening socket of its tree is on 127.0.0.1; each
    signal stops it as Ctrl-C does (it says "stopped", exit 0), nothing left."""
    o = run_signalled(["explore", "--port", "0", "--no-browser"], tmp_path, sig,
                      lambda tree, t, seen: bool(seen) and t > 1.0)
    assert o.signalled and o.listening, (o.returncode, o.err)
    assert all(ipaddress.ip_address(ip).is_loopback for ip, _ in o.listening), o.listening
    assert o.returncode == 0 and "stopped" in o.out, (o.returncode, o.out, o.err)
    assert "Traceback" not in o.err, o.err
