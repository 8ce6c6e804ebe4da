"""One writer per output, no foreign file replaced (andoyer.outputs), in this process and
across processes; the command line's outputs go through it."""

from __future__ import annotations

import json
import os
import socket
import subprocess
import sys
import warnings

import pytest

from andoyer.cli import EXIT_CODES, main
from andoyer.errors import OutputInUseError, StaleLockWarning
from andoyer.outputs import (
    MANIFEST,
    Manifest,
    OutputLock,
    guard_folder,
    read_holder,
    release_all,
)

HOLD = ("import sys, time; from andoyer.outputs import OutputLock; "
        "lock = OutputLock(sys.argv[1]).acquire(); print('held', flush=True); time.sleep(60)")


@pytest.fixture
def other_process(tmp_path):
    """Another process holding the lock of an output until the test ends."""
    procs = []

    def hold(target):
        p = subprocess.Popen([sys.executable, "-c", HOLD, str(target)], stdout=subprocess.PIPE,
                             text=True)
        procs.append(p)
        assert p.stdout is not None and p.stdout.readline() == "held\n"
        return p

    yield hold
    for p in procs:
        p.kill()
        p.communicate(timeout=30)


def test_a_second_writer_is_refused_naming_the_holder(tmp_path, other_process):
    store = tmp_path / "s.zarr"
    holder = other_process(store)
    with pytest.raises(OutputInUseError, match=rf"being written by another andoyer run \(pid "
                                               rf"{holder.pid} on host {socket.gethostname()}"
                                               r", started 20\d\d-"):
        OutputLock(store).acquire()
    # in one process too: two locks on one output exclude each other
    with OutputLock(tmp_path / "o.nc"), pytest.raises(OutputInUseError):
        OutputLock(tmp_path / "o.nc").acquire()


def test_the_lock_dies_with_its_process_and_the_next_run_takes_it_over(tmp_path,
                                                                       other_process):
    store = tmp_path / "s.zarr"
    holder = other_process(store)
    left = read_holder(store)
    assert left is not None and left["pid"] == holder.pid
    holder.kill()  # SIGKILL: no clean-up; the kernel frees the lock, the sidecar stays
    holder.communicate(timeout=30)
    with pytest.warns(StaleLockWarning, match=rf"left by a run that did not finish \(pid "
                                              rf"{holder.pid} .*no longer running\): taking "
                                              "it over"):
        lock = OutputLock(store).acquire()
    try:
        assert lock.stale == left and read_holder(store)["pid"] == os.getpid()
    finally:
        lock.release()
    assert read_holder(store) is None
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # released cleanly: nothing stale any more
        OutputLock(store).acquire().release()


def test_the_manifest_knows_what_andoyer_wrote(tmp_path):
    out = tmp_path / "report"
    out.mkdir()
    guard_folder(out)  # new and empty: accepted
    (out / "fig.png").write_bytes(b"png")
    release_all()  # the command ends: fig.png is recorded
    assert json.loads((out / MANIFEST).read_text())["files"].keys() == {"fig.png"}
    guard_folder(out)  # what andoyer wrote is not foreign
    release_all()
    (out / "fig.png").write_bytes(b"changed by the user")
    (out / "notes.txt").write_text("mine")
    assert Manifest(out).foreign() == ["fig.png", "notes.txt"]
    with pytest.raises(ValueError, match=r"holds files andoyer did not write, or that changed "
                                         r"since it wrote them \(fig.png, notes.txt\)"):
        guard_folder(out)
    OutputLock(out).acquire().release()  # the refusal released the folder


def test_files_of_a_killed_run_are_adopted(tmp_path, other_process):
    out = tmp_path / "report"
    out.mkdir()
    holder = other_process(out)
    (out / "fig.png").write_bytes(b"written by the killed run")
    holder.kill()
    holder.communicate(timeout=30)
    with pytest.warns(StaleLockWarning):
        guard_folder(out)
    release_all()
    assert "fig.png" in Manifest(out).files()


def test_paper_refuses_a_folder_with_a_users_files(tmp_path, capsys):
    out = tmp_path / "site"
    out.mkdir()
    (out / "index.html").write_text("<p>my page</p>")
    (out / "summary.json").write_text("{}")
    with pytest.raises(SystemExit) as info:
        main(["paper", "--out", str(out), "--only", "paper-check", "--quick"])
    err = capsys.readouterr().err
    assert info.value.code == EXIT_CODES["bad input"] and err.count("\n") == 1
    assert "andoyer did not write" in err and "index.html, summary.json" in err
    assert (out / "index.html").read_text() == "<p>my page</p>"


def test_commands_refuse_an_output_another_run_writes(tmp_path, capsys, other_process):
    out = tmp_path / "o.nc"
    holder = other_process(out)
    with pytest.raises(SystemExit) as info:
        main(["orbit", "--andoyer", "0.3,1,0.2,1,0", "--t-end", "1", "--n-out", "3",
              "--out", str(out)])
    err = capsys.readouterr().err
    assert info.value.code == EXIT_CODES["bad input"] and err.count("\n") == 1
    assert f"pid {holder.pid}" in err and not out.exists()
    holder.kill()
    holder.communicate(timeout=30)
    main(["orbit", "--andoyer", "0.3,1,0.2,1,0", "--t-end", "1", "--n-out", "3",
          "--out", str(out)])
    assert "warning: the lock of" in capsys.readouterr().err  # one line, the CLI's own
    assert out.exists() and read_holder(out) is None  # released when the command ended


def test_scan_never_replaces_a_store_under_a_live_writer(tmp_path, other_process):
    from andoyer.scan.run import run_scan

    cfg = {"parameters": {"mu": [0.01, 0.1], "h": 0.3},
           "task": {"kind": "section", "n_orbits": 2, "n_crossings": 3}}
    store = tmp_path / "s.zarr"
    run_scan(cfg, store, scheduler="serial", progress=False)
    before = sorted(p.relative_to(store) for p in store.rglob("*"))
    holder = other_process(store)
    for overwrite in (False, True):
        with pytest.raises(OutputInUseError, match=f"pid {holder.pid}"):
            run_scan(cfg, store, scheduler="serial", overwrite=overwrite, progress=False)
    assert sorted(p.relative_to(store) for p in store.rglob("*")) == before
