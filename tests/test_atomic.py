"""A full disk, for real: a 256 kB tmpfs mounted in a private mount namespace.

NetCDF (HDF5) reports a full disk as "NetCDF: HDF error"; andoyer must say "no space left
on <path>" (exit code 4) and leave nothing half-written. Skipped where a tmpfs cannot be
mounted (no unshare, or no permission).
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from andoyer.cli import EXIT_CODES

_MOUNT_TMPFS = 'mount -t tmpfs -o size=256k tmpfs "$1" || exit 97; shift; exec "$@"'


def _in_full_folder(folder: Path, command: list[str]) -> subprocess.CompletedProcess[str]:
    tool = shutil.which("unshare")
    if tool is None or not sys.platform.startswith("linux"):
        pytest.skip("no unshare(1) here: cannot mount a small file system")
    unshare = [tool, "--mount"] if os.geteuid() == 0 else [tool, "-r", "--mount"]
    run = subprocess.run([*unshare, "sh", "-c", _MOUNT_TMPFS, "sh", str(folder), *command],
                         capture_output=True, text=True, timeout=600)
    if run.returncode == 97 or "unshare:" in run.stderr:
        pytest.skip(f"cannot mount a tmpfs here: {run.stderr.strip()[:200]}")
    return run


def test_netcdf_on_a_full_disk_says_no_space_left(tmp_path):
    folder = tmp_path / "small"
    folder.mkdir()
    out = folder / "orbit.nc"
    run = _in_full_folder(folder, [
        sys.executable, "-m", "andoyer", "orbit", "--andoyer", "0.3,1,0.2,1,0",
        "--t-end", "10", "--n-out", "20000", "--engine", "numba", "--out", str(out)])
    assert run.returncode == EXIT_CODES["file system"], run.stderr
    assert f"error: no space left on {out}" in run.stderr, run.stderr
    assert "HDF error" not in run.stderr and "internal error" not in run.stderr


def test_nothing_half_written_is_left_on_the_full_disk(tmp_path):
    folder = tmp_path / "small"
    folder.mkdir()
    script = (
        "import os, sys, numpy as np, xarray as xr\n"
        "from andoyer.errors import NoSpaceError\n"
        "from andoyer.io import write_netcdf\n"
        "ds = xr.Dataset({'a': (('x',), np.random.default_rng(0).random(100_000))})\n"
        "try:\n"
        "    write_netcdf(ds, sys.argv[1] + '/big.nc')\n"
        "except NoSpaceError as exc:\n"
        "    print('refused:', exc.strerror)\n"
        "print('left:', sorted(os.listdir(sys.argv[1])))\n")
    run = _in_full_folder(folder, [sys.executable, "-c", script, str(folder)])
    assert run.returncode == 0, run.stderr
    assert f"refused: no space left on {folder / 'big.nc'}" in run.stdout
    assert "left: []" in run.stdout
