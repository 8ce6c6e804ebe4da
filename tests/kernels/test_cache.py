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
import pytest

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


_TINY = '''
from andoyer.kernels.cache import cached_njit

@cached_njit(nogil=True)
def thrice(x):
    return 3.0 * x
'''

_RUN_TINY = textwrap.dedent("""
    import json, sys, warnings
    sys.path.insert(0, sys.argv[1])
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        import tiny
        value = tiny.thrice(1.5)
    stats = tiny.thrice.stats
    print(json.dumps({"value": value, "hits": sum(stats.cache_hits.values()),
                      "warnings": [[w.category.__name__, str(w.message)] for w in seen]}))
""")


def _run_tiny(folder: Path, cache_dir: Path) -> dict:
    env = dict(os.environ, ANDOYER_CACHE_DIR=str(cache_dir))
    env.pop("NUMBA_CACHE_DIR", None)
    run = subprocess.run([sys.executable, "-c", _RUN_TINY, str(folder)], capture_output=True,
                         text=True, env=env, timeout=300)
    assert run.returncode == 0, run.stderr
    return json.loads(run.stdout.strip().splitlines()[-1])


def _damage(files: list[Path], how: str) -> None:
    for f in files:
        data = f.read_bytes()
        f.write_bytes({"truncated": data[:20], "empty": b"",
                       "foreign": b"\x80\x05not numba's" * 40}[how])


@pytest.fixture(scope="module")
def warm_tiny(tmp_path_factory) -> Path:
    """A module using cached_njit, run once: its cache entry written."""
    root = tmp_path_factory.mktemp("tiny")
    (root / "src").mkdir()
    (root / "src" / "tiny.py").write_text(_TINY)
    first = _run_tiny(root / "src", root / "cache")
    assert first["value"] == 4.5 and first["warnings"] == []
    return root


@pytest.mark.parametrize("what, how", [("nbi", "truncated"), ("nbc", "truncated"),
                                       ("nbc", "foreign"), ("nbi", "empty")])
def test_a_damaged_entry_is_rebuilt_with_one_warning_naming_the_folder(
        warm_tiny: Path, tmp_path: Path, what, how) -> None:
    """A truncated or overwritten index or data file of Numba's cache ended every command
    with 'internal error (UnpicklingError ...)', naming no cache. Now: removed, compiled
    again and cached, one DamagedCacheWarning naming the folder; the next run is quiet and
    loads the rebuilt entry."""
    import shutil

    shutil.copytree(warm_tiny / "cache", tmp_path / "cache")
    files = sorted((tmp_path / "cache").rglob(f"tiny.thrice-*.{what}"))
    assert files
    _damage(files, how)
    second = _run_tiny(warm_tiny / "src", tmp_path / "cache")
    assert second["value"] == 4.5
    assert [w[0] for w in second["warnings"]] == ["DamagedCacheWarning"], second
    assert f"in {files[0].parent} (tiny.thrice-" in second["warnings"][0][1]
    third = _run_tiny(warm_tiny / "src", tmp_path / "cache")
    assert third == {"value": 4.5, "hits": 1, "warnings": []}


@pytest.mark.slow
def test_a_command_with_a_damaged_cache_warns_once_and_succeeds(tmp_path: Path) -> None:
    """The command line: one warning line naming the folder, exit 0, no internal error
    (two compiles of the numba engine's propagate: a minute under load)."""
    env = dict(os.environ, ANDOYER_CACHE_DIR=str(tmp_path / "cache"))
    env.pop("NUMBA_CACHE_DIR", None)
    argv = [sys.executable, "-m", "andoyer", "orbit", "--andoyer", "0.3,1,0.2,1,0",
            "--t-end", "1", "--n-out", "3", "--engine", "numba"]
    first = subprocess.run([*argv, "--out", str(tmp_path / "a.nc")], capture_output=True,
                           text=True, env=env, timeout=900)
    assert first.returncode == 0, first.stderr
    _damage(sorted((tmp_path / "cache").rglob("*.nbi")), "truncated")
    second = subprocess.run([*argv, "--out", str(tmp_path / "b.nc")], capture_output=True,
                            text=True, env=env, timeout=900)
    assert second.returncode == 0, second.stderr
    warned = [line for line in second.stderr.splitlines() if "warning" in line]
    assert len(warned) == 1 and "damaged entry of the compiled-kernel cache in " + str(
        tmp_path / "cache") in warned[0], second.stderr
    assert "internal error" not in second.stderr and "Traceback" not in second.stderr


_RACE = textwrap.dedent("""
    import json, sys, time
    from pathlib import Path
    from numba.core import caching
    sys.path.insert(0, sys.argv[1])
    go, arg = Path(sys.argv[2]), sys.argv[3]
    write_index = caching.IndexDataCacheFile._save_index

    def slow(self, overloads):  # a slow disk: the index is read, its write comes late
        time.sleep(1.5)
        write_index(self, overloads)

    caching.IndexDataCacheFile._save_index = slow
    import tiny
    while not go.exists():  # both processes compile and save together
        time.sleep(0.005)
    print(json.dumps(tiny.thrice(int(arg) if arg.isdigit() else float(arg))))
""")


def test_two_processes_adding_signatures_at_once_both_land(tmp_path: Path) -> None:
    """Numba's save reads the index, picks the first unused data name and writes, with no
    lock: two processes adding signatures of one function at once picked the same name,
    one index entry was lost and the other could name the other signature's code (make
    test under two workers: a kernel stepping from a non-finite state). With the writers'
    lock both entries land, and a third process loads each signature's own code."""
    (tmp_path / "src").mkdir()
    (tmp_path / "src" / "tiny.py").write_text(_TINY)
    env = dict(os.environ, ANDOYER_CACHE_DIR=str(tmp_path / "cache"))
    env.pop("NUMBA_CACHE_DIR", None)
    go = tmp_path / "go"
    runs = [subprocess.Popen([sys.executable, "-c", _RACE, str(tmp_path / "src"), str(go), arg],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
            for arg in ("2", "0.5")]
    try:
        import time

        time.sleep(3.0)  # both imported and waiting (their compile follows the go)
        go.touch()
        outs = [r.communicate(timeout=300) for r in runs]
    finally:
        for r in runs:
            r.kill()
    assert [r.returncode for r in runs] == [0, 0], [o[1] for o in outs]
    assert [json.loads(o[0]) for o in outs] == [6.0, 1.5]
    check = textwrap.dedent("""
        import json, sys
        sys.path.insert(0, sys.argv[1])
        import tiny
        values = [tiny.thrice(2), tiny.thrice(0.5)]
        print(json.dumps({"values": values, "hits": len(tiny.thrice.stats.cache_hits),
                          "misses": len(tiny.thrice.stats.cache_misses)}))
    """)
    run = subprocess.run([sys.executable, "-c", check, str(tmp_path / "src")],
                         capture_output=True, text=True, env=env, timeout=300)
    assert run.returncode == 0, run.stderr
    assert json.loads(run.stdout.strip().splitlines()[-1]) == {
        "values": [6.0, 1.5], "hits": 2, "misses": 0}
    assert len(list((tmp_path / "cache").rglob("tiny.thrice-*.nbc"))) == 2


def test_nafflib_is_compiled_once_then_loaded(tmp_path: Path) -> None:
    """A library's uncached Numba functions (nafflib's) are cached as andoyer's kernels:
    the first process compiles and writes them under ``libraries``, the second loads
    them (a cache hit, no miss), and the lines found are the same."""
    script = textwrap.dedent("""
        import json
        import numpy as np
        from andoyer.analysis.chaos.frequency import naff
        r = naff(np.exp(0.3j * 0.1 * np.arange(2000)), 0.1, 1)
        import nafflib.optimize as o
        s = o.expArray.stats
        print(json.dumps({"path": s.cache_path, "hits": sum(s.cache_hits.values()),
                          "misses": sum(s.cache_misses.values()),
                          "omega": float(r.frequency[0])}))
    """)
    env = dict(os.environ, ANDOYER_CACHE_DIR=str(tmp_path))
    env.pop("NUMBA_CACHE_DIR", None)
    runs = []
    for _ in range(2):
        run = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                             env=env, timeout=300)
        assert run.returncode == 0, run.stderr
        runs.append(json.loads(run.stdout.strip().splitlines()[-1]))
    first, second = runs
    assert Path(first["path"]).is_relative_to(tmp_path / "numba" / "libraries")
    assert (first["hits"], first["misses"]) == (0, 1)
    assert (second["hits"], second["misses"]) == (1, 0)
    assert first["omega"] == second["omega"] and abs(first["omega"] - 0.3) < 1e-9
