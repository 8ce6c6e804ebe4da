"""``python -m benchmarks.section_cost``: what a section costs over the bare flow.

The W2 orbits (``workloads.initial_states``), in one process, on the taylor kernels:

* the **bare flow** of the orbits over the span ``T`` of the section run (SIMD lanes,
  :func:`andoyer.kernels.taylor.lanes.propagate` to ``[0, T]``, no output in between);
* each **section** (``G3 = 0``, ``theta2 = 0``, ``g = 0``, upward) to ``T`` on the lanes
  (:mod:`andoyer.kernels.taylor.lane_crossings`) and on the scalar kernel
  (:func:`andoyer.kernels.taylor.flow.locate_crossings`), with ``n`` crossings asked
  (``T`` is the earliest time any orbit reaches its ``n``-th crossing of theta2 = 0, so
  every orbit integrates over ``[0, T]`` in every run);
* with ``--engines``: ``poincare`` through the taylor and heyoka engines (datasets out).

Runs are interleaved (one of each, ``--repeat`` rounds); the table gives each run's
median CPU time (``time.process_time``: one thread, so the other users of a shared
machine count less than in wall time; heyoka's own threads count too), the step counts,
the ratio section / bare flow and, for ``poincare`` on taylor, the ratio to heyoka's,
with the load average before and after. No timing is asserted anywhere.
"""

from __future__ import annotations

import argparse
import os
import statistics
import time
from collections.abc import Callable
from typing import Any

import numpy as np

from benchmarks import workloads as W

SECTIONS = (("G3", 0.0), ("theta2", 0.0), ("g", 0.0))


def _kind(name: str) -> int:
    from andoyer.kernels.generated import equations

    return (equations.SECTION_KINDS + equations.EXTRA_SECTION_KINDS).index(name)


def measure(n: int, N: int, repeat: int, engines: bool = False, scalar: bool = True,
            sections: tuple[tuple[str, float], ...] = SECTIONS) -> dict[str, Any]:
    """Median CPU time and steps of each run (the module's docstring), interleaved.

    Returns ``{"T", "tol", "lanes", "repeat", "load": (before, after), "cpu": {label:
    median s}, "steps": {label: steps}}``; the bare flow is ``"bare flow (lanes)"``, a
    section ``"G3 = 0 lanes"`` (``"... scalar"``, ``"... poincare taylor"`` and
    ``"... poincare heyoka"`` with ``scalar`` and ``engines``).
    """
    import numba

    from andoyer.kernels.taylor import flow, lane_crossings, lanes

    threads = numba.get_num_threads()
    numba.set_num_threads(1)
    try:
        b = W.body()
        p = np.ascontiguousarray(b.engine_params, dtype=float)
        tol = W.FULL.tol
        order = flow.order_for(tol)
        y0 = np.ascontiguousarray(W.initial_states(n))
        big = 10**9
        tc, *_ = lane_crossings.locate_crossings(y0, p, _kind("theta2"), 0.0, 1, N, 1e9,
                                                 tol, big)
        T = float(np.nanmin(tc[:, -1]))
        t = np.array([0.0, T])

        runs: dict[str, Callable[[], Any]] = {
            "bare flow (lanes)": lambda: lanes.propagate(y0, t, p, order, big, threads=1)[1],
        }
        for name, value in sections:
            k = _kind(name)
            runs[f"{name} = {value:g} lanes"] = (
                lambda k=k, value=value: lane_crossings.locate_crossings(
                    y0, p, k, value, 1, N, T, tol, big, threads=1)[3])
            if scalar:
                runs[f"{name} = {value:g} scalar"] = (
                    lambda k=k, value=value: flow.locate_crossings(
                        y0, p, k, value, 1, N, T, tol, big, threads=1)[3])
        if engines:
            from andoyer.integrate import Section, poincare

            for name, value in sections:
                for engine in ("taylor", "heyoka"):
                    runs[f"{name} = {value:g} poincare {engine}"] = (
                        lambda name=name, value=value, engine=engine: poincare(
                            b, y0, Section(name, value, 1), N, engine=engine, rtol=tol,
                            atol=tol, t_max=T, progress=False))
        steps = {}
        for label, fn in runs.items():  # warm: compile or load every kernel first
            out = fn()
            if isinstance(out, np.ndarray):
                steps[label] = int(out[:, 1].sum())
        load0 = os.getloadavg()
        cpu: dict[str, list[float]] = {label: [] for label in runs}
        for _ in range(repeat):
            for label, fn in runs.items():
                c0 = time.process_time()
                fn()
                cpu[label].append(time.process_time() - c0)
        load1 = os.getloadavg()
    finally:
        numba.set_num_threads(threads)
    return {"T": T, "tol": tol, "lanes": lanes.LANES, "repeat": repeat,
            "load": (load0, load1), "steps": steps,
            "cpu": {label: statistics.median(values) for label, values in cpu.items()}}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m benchmarks.section_cost", description=__doc__)
    ap.add_argument("--orbits", type=int, default=16)
    ap.add_argument("--crossings", type=int, default=300)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--engines", action="store_true",
                    help="also poincare through the taylor and heyoka engines")
    args = ap.parse_args(argv)
    n, N = args.orbits, args.crossings
    r = measure(n, N, args.repeat, engines=args.engines)
    (load0, load1), med, steps = r["load"], r["cpu"], r["steps"]
    bare = med["bare flow (lanes)"]
    print(f"{n} orbits, {N} crossings of theta2 = 0 asked, T = {r['T']:.1f}, tol {r['tol']:g}, "
          f"one thread, {r['lanes']} lanes, {args.repeat} rounds; "
          f"load {load0[0]:.2f} -> {load1[0]:.2f}")
    print(f"{'run':34s} {'CPU ms':>9s} {'steps':>9s} {'ns/step':>8s} {'/ bare':>7s} "
          f"{'/ heyoka':>8s}")
    for label, m in med.items():
        s = steps.get(label)
        per = f"{m / s * 1e9:8.0f}" if s else f"{'':8s}"
        hey = med.get(label.replace("poincare taylor", "poincare heyoka"))
        vs = f"{m / hey:8.2f}" if hey and "poincare taylor" in label else ""
        print(f"{label:34s} {m * 1e3:9.1f} {s if s else '':>9} {per} {m / bare:7.2f} {vs}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
