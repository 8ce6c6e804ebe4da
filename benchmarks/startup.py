"""W4, one fresh process: import, first call (compilation or cache load), second call.

Run by the harness as ``python -m benchmarks.startup RUNNER`` in a new process; prints
one JSON line ``{"import_s": .., "first_s": .., "second_s": ..}``: importing the
runner's packages, then the same work twice. The first call
minus the second is what the process paid to compile or to load compiled code.

With ``BENCH_COLD_CACHE=<dir>`` every on-disk cache (heyoka's, Numba's, andoyer's)
points into that empty directory: the first process on a fresh machine.

Runners: ``andoyer-heyoka``, ``andoyer-numba``, ``andoyer-taylor`` (``propagate`` of one
orbit to
t = 1e4, then a 8-orbit x 20-crossing ``poincare``) and ``heyoka-plain`` (the plain
heyoka script on the same two problems).
"""

from __future__ import annotations

import json
import os
import sys
import time


def _cold_caches() -> None:
    cold = os.environ.get("BENCH_COLD_CACHE")
    if not cold:
        return
    import heyoka as hy

    hy.llvm_state.set_diskcache_path(os.path.join(cold, "heyoka"))


def main(runner: str) -> dict[str, float]:
    _cold_caches()
    from benchmarks import workloads as W

    b = W.body()
    y0 = W.initial_states(8)  # setup (andoyer's fill_section), not timed
    t = W.w1_times(W.FULL)
    t0 = time.perf_counter()
    if runner.startswith("andoyer-"):
        from andoyer.integrate import Section, poincare, propagate
        from andoyer.integrate.engines import get_engine

        engine = runner.removeprefix("andoyer-")
        get_engine(engine)  # imports the engine's package (heyoka, numba)
        section = Section("G3", 0.0, 1)

        def work() -> None:
            propagate(b, y0[0], t, engine=engine, progress=False)
            poincare(b, y0, section, 20, engine=engine, progress=False)
    elif runner == "heyoka-plain":
        from benchmarks.peers import heyoka_scripts as hs

        p = W.params(b)

        def work() -> None:
            hs.plain_orbit(p, y0[0], t, 1e-12)
            hs.plain_section(p, y0, "G3", 0.0, 20, 1e-12)
    else:
        raise SystemExit(f"unknown runner {runner!r}")
    imports = time.perf_counter() - t0
    t1 = time.perf_counter()
    work()
    first = time.perf_counter() - t1
    t2 = time.perf_counter()
    work()
    second = time.perf_counter() - t2
    return {"import_s": imports, "first_s": first, "second_s": second}


if __name__ == "__main__":
    print(json.dumps(main(sys.argv[1])))
