"""No file replaced that andoyer did not write: every command writing files (``--out
FILE`` and the PNG/PDF written beside it) refuses an existing file unless the manifest of
its folder lists it, unchanged, as andoyer's (:func:`andoyer.outputs.guard_file`), the
same rule as for output folders (:func:`andoyer.outputs.guard_folder`)."""

from __future__ import annotations

import json

import pytest

from andoyer.cli import EXIT_CODES, main
from andoyer.outputs import MANIFEST, OutputLock, guard_file, release_all

ORBIT = ["orbit", "--andoyer", "0.3,1,0.2,1,0", "--t-end", "1", "--n-out", "3",
         "--engine", "numba"]

#: Every command that writes files: (argv without --out, its --out name, the files it
#: writes beside it). Each must refuse a user's file at each of these names.
COMMANDS = {
    "orbit": (ORBIT, "o.nc", ()),
    "section": (["section", "--n-orbits", "2", "--n-crossings", "2"], "s.nc", ("s.png",)),
    "chaos-map": (["chaos-map", "--n", "3", "--t-end", "2"], "c.nc", ("c.png",)),
    "chaos-map both": (["chaos-map", "--n", "3", "--t-end", "2", "--indicator", "both"],
                       "c.nc", ("c-fli.png", "c-megno.png")),
    "indicators": (["indicators", "--andoyer", "0.3,0,0.3,1,0", "--t-end", "2"], "i.nc",
                   ("i.png",)),
    "frequencies orbit": (["frequencies", "--andoyer", "0.3,0,0.3,1,0", "--t-end", "50"],
                          "f.nc", ("f.png",)),
    "resonances": (["resonances", "--n-crossings", "2"], "r.nc", ("r.png",)),
    "resonances order": (["resonances", "--order", "8"], "r.nc",
                         ("r.png", "r-normal-form.nc")),
    "animate": (["animate", "--andoyer", "0.3,0,0.3,1,0", "--frames", "2"], "g.gif", ()),
    "frequencies map": (["frequencies", "--n-orbits", "2", "--t-end", "50"], "f.nc",
                        ("f.png",)),
    "atlas": (["atlas", "missing.zarr"], "a.png", ()),
    "atlas pdf": (["atlas", "missing.zarr", "--pdf"], "a.png", ("a.pdf",)),
}


def _run(argv, capsys):
    with pytest.raises(SystemExit) as info:
        main(argv)
    return info.value.code, capsys.readouterr().err


@pytest.mark.parametrize("command", sorted(COMMANDS))
def test_every_command_refuses_a_users_file_at_each_name_it_writes(command, tmp_path,
                                                                   capsys):
    argv, out, beside = COMMANDS[command]
    for name in (out, *beside):
        user = tmp_path / name
        user.write_bytes(b"a user's file")
        code, err = _run([*argv, "--out", str(tmp_path / out)], capsys)
        assert code == EXIT_CODES["bad input"], (name, err)
        assert err.count("\n") == 1 and "Traceback" not in err, err
        assert f"{str(user)!r} exists and andoyer did not write it" in err, err
        assert user.read_bytes() == b"a user's file"  # untouched
        user.unlink()
    # the refusals released every lock: nothing left beside the outputs
    assert sorted(p.name for p in tmp_path.iterdir()) == []


def test_a_file_andoyer_wrote_is_replaced_and_a_changed_one_is_refused(tmp_path, capsys):
    out = tmp_path / "o.nc"
    assert main([*ORBIT, "--out", str(out)]) == 0
    files = json.loads((tmp_path / MANIFEST).read_text())["files"]
    assert set(files) == {"o.nc"}  # only what andoyer wrote is listed
    assert main([*ORBIT, "--out", str(out)]) == 0  # its own file: replaced
    (tmp_path / "mine.txt").write_text("the folder stays the user's")
    assert main([*ORBIT, "--out", str(out)]) == 0
    out.write_bytes(out.read_bytes() + b"\0")  # changed by the user since
    code, err = _run([*ORBIT, "--out", str(out)], capsys)
    assert code == EXIT_CODES["bad input"] and "or it changed since andoyer wrote it" in err
    assert sorted(p.name for p in tmp_path.iterdir()) == [MANIFEST, "mine.txt", "o.nc"]


def test_a_file_in_a_folder_another_run_writes_is_refused(tmp_path, capsys):
    folder = tmp_path / "site"
    folder.mkdir()
    with OutputLock(folder):  # e.g. andoyer paper --out site, running
        code, err = _run([*ORBIT, "--out", str(folder / "o.nc")], capsys)
    assert code == EXIT_CODES["bad input"] and "is being written by another andoyer run" in err
    assert not (folder / "o.nc").exists()


def test_a_symlink_or_a_folder_at_the_name_is_refused(tmp_path, capsys):
    target = tmp_path / "elsewhere.nc"
    target.write_bytes(b"a user's file")
    (tmp_path / "o.nc").symlink_to(target)
    code, err = _run([*ORBIT, "--out", str(tmp_path / "o.nc")], capsys)
    assert code == EXIT_CODES["bad input"] and "andoyer did not write it" in err
    assert target.read_bytes() == b"a user's file"
    (tmp_path / "s.png").mkdir()
    code, err = _run(["section", "--out", str(tmp_path / "s.nc")], capsys)
    assert code == EXIT_CODES["bad input"] and "is an existing folder" in err


def test_guard_file_adopts_nothing_it_did_not_write(tmp_path):
    out = tmp_path / "x.nc"
    guard_file(out)
    release_all()  # nothing written: nothing recorded, no manifest
    assert not (tmp_path / MANIFEST).exists()
    guard_file(out)
    out.write_bytes(b"written by andoyer")
    release_all()
    assert json.loads((tmp_path / MANIFEST).read_text())["files"].keys() == {"x.nc"}
    out.unlink()
    guard_file(tmp_path / "y.nc")
    release_all()  # a file gone is dropped from the manifest
    assert json.loads((tmp_path / MANIFEST).read_text())["files"] == {}


def test_two_runs_writing_files_in_one_folder_both_get_recorded(tmp_path):
    """Two writers of different files in one folder update its manifest in turn (its own
    short-lived lock): neither run's files are lost from it."""
    import subprocess
    import sys

    code = ("import sys, pathlib\n"
            "from andoyer.outputs import guard_file, release_all\n"
            "folder, tag = pathlib.Path(sys.argv[1]), sys.argv[2]\n"
            "for i in range(40):\n"
            "    f = folder / f'{tag}{i}.nc'\n"
            "    guard_file(f)\n"
            "    f.write_bytes(tag.encode() * (i + 1))\n"
            "    release_all()\n")
    procs = [subprocess.Popen([sys.executable, "-c", code, str(tmp_path), tag])
             for tag in ("a", "b")]
    assert [p.wait(timeout=120) for p in procs] == [0, 0]
    files = json.loads((tmp_path / MANIFEST).read_text())["files"]
    assert set(files) == {f"{t}{i}.nc" for t in "ab" for i in range(40)}
    assert not [p.name for p in tmp_path.iterdir() if "lock" in p.name]


def test_a_manifest_that_cannot_be_written_neither_hides_the_outcome_nor_keeps_a_lock(
        tmp_path, capsys):
    """The manifest is brought up to date when the run ends; if it cannot be written (here
    a folder in its place; a full disk alike) the run still ends with its own outcome, one
    warning line, and every output released."""
    (tmp_path / MANIFEST).mkdir()
    assert main([*ORBIT, "--out", str(tmp_path / "o.nc")]) == 0
    err = capsys.readouterr().err
    assert "could not record the files andoyer wrote" in err and "Traceback" not in err
    assert sorted(p.name for p in tmp_path.iterdir()) == [MANIFEST, "o.nc"]  # no lock left
