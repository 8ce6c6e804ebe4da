"""The compiled kernels are cached in the user's cache folder, never in the package.

A read-only install (site-packages owned by root, a shared cluster image) must still
cache, and nothing may be written next to the sources: the machine code goes to
:func:`andoyer.kernels.cache.cache_folder`, which ``ANDOYER_CACHE_DIR`` moves.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import numba

from andoyer.kernels import cache


def test_folder_follows_the_environment(monkeypatch, tmp_path: Path) -> None:
    monkeypatch.delenv("NUMBA_CACHE_DIR", raising=False)
    monkeypatch.setenv(cache.CACHE_ENV, str(tmp_path))
    assert cache.cache_folder() == tmp_path / "numba"
    monkeypatch.delenv(cache.CACHE_ENV)
    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path / "mine"))
    assert cache.cache_folder() == tmp_path / "mine"
    monkeypatch.delenv("NUMBA_CACHE_DIR")
    default = cache.cache_folder()
    assert default.name == "numba" and default.parent.name == "andoyer"
    assert not default.is_relative_to(Path(cache.__file__).parents[1])


def test_decoration_leaves_numba_setting_alone(tmp_path: Path, monkeypatch) -> None:
    monkeypatch.setenv(cache.CACHE_ENV, str(tmp_path))
    before = numba.config.CACHE_DIR

    @cache.cached_njit(nogil=True)
    def twice(x: float) -> float:
        return 2.0 * x

    assert numba.config.CACHE_DIR == before
    assert twice(1.5) == 3.0
    assert Path(twice._cache._cache_path).is_relative_to(tmp_path / "numba")


def test_a_fresh_process_caches_outside_the_package(tmp_path: Path) -> None:
    script = textwrap.dedent("""
        import json
        from pathlib import Path
        import numpy as np
        import andoyer.kernels.dop853.fields as k
        k.ep_hamiltonian(1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 2.0, 2.5, 2.2, 1.0, 0.0, 0.0, 1.0)
        print(json.dumps({"path": k.ep_hamiltonian._cache._cache_path,
                          "package": str(Path(k.__file__).parents[2])}))
    """)
    env = dict(os.environ, ANDOYER_CACHE_DIR=str(tmp_path))
    env.pop("NUMBA_CACHE_DIR", None)
    run = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                         env=env, timeout=300)
    assert run.returncode == 0, run.stderr
    out = json.loads(run.stdout.strip().splitlines()[-1])
    path = Path(out["path"])
    assert path.is_relative_to(tmp_path / "numba")
    assert not path.is_relative_to(out["package"])
    assert any(path.glob("*.nbi")) and any(path.glob("*.nbc"))


def test_the_cache_subfolder_follows_every_kernel_source(tmp_path: Path,
                                                          monkeypatch) -> None:
    """Numba keys an entry on the defining file only: an edit of a module whose functions
    a kernel calls (a stepper, a jet routine, the shared definitions, a generated file),
    in any sub-package, must still move every kernel to a new folder, or the callers
    load stale machine code."""
    src = Path(cache.__file__).parent
    copy = tmp_path / "kernels"
    for f in src.rglob("*.py"):
        target = copy / f.relative_to(src)
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_bytes(f.read_bytes())
    assert cache._stamp(copy) == cache.sources_stamp()
    for callee in ("dop853/stepper.py", "taylor/jets.py", "generated/recurrences.py",
                   "common.py"):
        source = (copy / callee).read_bytes()
        (copy / callee).write_bytes(source + b"\n")
        assert cache._stamp(copy) != cache.sources_stamp(), callee
        (copy / callee).write_bytes(source)
    assert cache._stamp(copy) == cache.sources_stamp()
    (copy / "taylor" / "jets.py").rename(copy / "taylor" / "steps.py")  # a moved module
    assert cache._stamp(copy) != cache.sources_stamp()
    monkeypatch.setenv(cache.CACHE_ENV, str(tmp_path))

    @cache.cached_njit(nogil=True)
    def thrice(x: float) -> float:
        return 3.0 * x

    assert thrice(1.0) == 3.0
    assert Path(thrice._cache._cache_path).is_relative_to(
        tmp_path / "numba" / f"kernels-{cache.sources_stamp()}")
