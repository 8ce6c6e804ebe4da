"""andoyer runs where it installs: a read-only package folder and a read-only home.

Many clusters and containers install into a folder nobody may write and give a home that
is read-only too, so no compiled-code cache can be kept (Numba's, heyoka's). andoyer must
then run without one and say so once; ``--version`` and ``--help`` must not compile or
import anything heavy at all.

Root ignores permission bits, so the read-only places are made real: read-only bind
mounts in a private mount namespace (``unshare --mount``; ``unshare -r`` without root).
Where that cannot be done the tests skip with the reason.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import textwrap
from collections.abc import Callable, Sequence
from pathlib import Path

import pytest

import andoyer

Runner = Callable[[Sequence[str]], subprocess.CompletedProcess[str]]

#: Mount each folder given before "--" read-only (over itself), check that a file cannot
#: be created there, then run the command after "--".
_MOUNT_READ_ONLY = textwrap.dedent("""
    while [ "$1" != "--" ]; do
        mount --bind "$1" "$1" && mount -o remount,bind,ro "$1" || exit 97
        if touch "$1/.andoyer-probe" 2>/dev/null; then rm -f "$1/.andoyer-probe"; exit 98; fi
        shift
    done
    shift
    exec "$@"
""")

HEAVY = ("numba", "llvmlite", "xarray", "scipy", "sympy", "matplotlib", "zarr", "dask",
         "distributed", "heyoka", "panel", "netCDF4")


def _unshare() -> list[str] | None:
    tool = shutil.which("unshare")
    if tool is None or not sys.platform.startswith("linux"):
        return None
    return [tool, "--mount"] if os.geteuid() == 0 else [tool, "-r", "--mount"]


@pytest.fixture
def read_only(tmp_path: Path) -> tuple[Runner, dict[str, str]]:
    """Run a command with andoyer's package folder and a new home read-only."""
    unshare = _unshare()
    if unshare is None:
        pytest.skip("no unshare(1) here: cannot make a read-only folder that root respects")
    home = tmp_path / "home"
    home.mkdir()
    package = Path(andoyer.__file__).parent
    env = {k: v for k, v in os.environ.items()
           if k not in ("NUMBA_CACHE_DIR", "ANDOYER_CACHE_DIR", "MPLCONFIGDIR",
                        "XDG_CONFIG_HOME", "ANDOYER_NO_CACHE_WARNED")}
    env.update(HOME=str(home), XDG_CACHE_HOME=str(home / ".cache"))

    def run(command: Sequence[str]) -> subprocess.CompletedProcess[str]:
        return subprocess.run([*unshare, "sh", "-c", _MOUNT_READ_ONLY, "sh", str(package),
                               str(home), "--", *command], capture_output=True, text=True,
                              env=env, cwd=tmp_path, timeout=600)

    probe = run(["true"])
    if probe.returncode != 0:
        pytest.skip(f"cannot mount a read-only folder here (unshare: exit "
                    f"{probe.returncode} {probe.stderr.strip()[:200]})")
    return run, env


def test_version_and_help_import_nothing_heavy() -> None:
    script = textwrap.dedent("""
        import sys
        from andoyer.cli import main
        for argv in (["--version"], ["--help"], ["paper", "--help"], ["scan", "--help"],
                     ["atlas", "--help"], ["explore", "--help"]):
            try:
                main(argv)
            except SystemExit as exc:
                assert exc.code == 0, (argv, exc.code)
        print(" ".join(sorted({m.split(".")[0] for m in sys.modules})), file=sys.stderr)
    """)
    run = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                         timeout=120)
    assert run.returncode == 0, run.stderr
    loaded = set(run.stderr.split())
    assert not loaded & set(HEAVY), sorted(loaded & set(HEAVY))


def test_version_on_a_read_only_install(read_only) -> None:
    run, _ = read_only
    out = run([sys.executable, "-m", "andoyer", "--version"])
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == f"andoyer {andoyer.__version__}"
    assert out.stderr == ""


def test_computes_without_a_cache_with_one_warning(read_only) -> None:
    """Kernels of both engines compile without a cache; one warning says so."""
    run, _ = read_only
    script = textwrap.dedent("""
        import warnings
        warnings.simplefilter("always")
        from andoyer import RigidBody, poincare, propagate
        from andoyer.integrate.engines.lazy import heyoka_available
        body = RigidBody.paper()
        ds = propagate(body, [0.3, 0, 0.3, 1, 0], [0, 1, 2], chart="andoyer", engine="numba")
        assert float(abs(ds.H_drift).max()) < 1e-12
        if heyoka_available():
            ds = poincare(body, [0.3, 0, 0.3, 1, 0], "theta2=0", 3, chart="andoyer",
                          engine="heyoka")
            assert int(ds.crossings_found[0]) == 3
        print("ok")
    """)
    out = run([sys.executable, "-c", script])
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "ok"
    assert out.stderr.count("NoCacheWarning") == 1, out.stderr
    assert "Traceback" not in out.stderr and "heyoka" not in out.stderr.replace(
        "heyoka's", ""), out.stderr


def test_cli_prints_the_one_warning_as_one_line(read_only, tmp_path: Path) -> None:
    run, _ = read_only
    out = run([sys.executable, "-m", "andoyer", "orbit", "--andoyer", "0.3,1,0.2,1,0", "--t-end",
               "1", "--n-out", "3", "--engine", "numba", "--out", str(tmp_path / "orbit.nc")])
    assert out.returncode == 0, out.stderr
    lines = [x for x in out.stderr.splitlines() if "warning" in x.lower()]
    assert len(lines) == 1 and lines[0].startswith("andoyer orbit: warning: no writable folder"), \
        out.stderr
