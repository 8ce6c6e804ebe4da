"""``python -m benchmarks.megno_map``: the MEGNO map on taylor's lanes, its scalar route
and heyoka, side by side in one process.

* the **map**: ``chaos_map(..., indicator="megno")`` of W3's plane (``theta2 = 0`` at
  W3's energy level, ``--grid`` squared starts, ``t_end`` of W3) through the taylor
  engine on SIMD lanes (:mod:`andoyer.kernels.taylor.lane_tangent`, the default route
  from ``LANES_FROM`` orbits), through the taylor engine with the lanes turned off
  (``taylor_engine.LANES_FROM`` raised: the scalar kernel
  :mod:`andoyer.kernels.taylor.tangent`, one orbit at a time) and through heyoka (batch
  mode and threads), runs interleaved (one of each per round, ``--repeat`` rounds after
  one warm-up each), median wall and CPU time; the MEGNO values compared between the
  routes;
* the **kernels** on one thread: ns per orbit-step of the lane and scalar kernels on
  ``--orbits`` W2 starts with one tangent vector to ``t_end`` (CPU time over the steps
  taken, ``time.process_time``).

The load average is printed before and after. No timing is asserted anywhere.
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


def _kernels(n: int, t_end: float, repeat: int) -> list[str]:
    """ns per orbit-step of the lane and scalar renormalised tangent kernels (one thread)."""
    from andoyer.integrate.engines.values import unit_vectors
    from andoyer.kernels.taylor import lane_tangent, tangent

    b = W.body()
    p = np.ascontiguousarray(b.engine_params, dtype=float)
    y0 = np.ascontiguousarray(W.initial_states(n))
    u, rho = unit_vectors(np.random.default_rng(1).normal(size=(n, 1, 6)))
    z0 = np.ascontiguousarray(np.concatenate([y0, u[:, 0]], axis=1))
    t = np.linspace(0.0, t_end, 65)
    runs: dict[str, Callable[[], Any]] = {
        "lanes": lambda: lane_tangent.propagate(z0, rho, t, p, W.FULL.tol, 10**9, threads=1),
        "scalar": lambda: tangent.propagate(z0, rho, t, p, W.FULL.tol, 10**9, threads=1),
    }
    cpu: dict[str, list[float]] = {k: [] for k in runs}
    steps: dict[str, int] = {}
    for fn in runs.values():
        fn()
    for _ in range(repeat):
        for name, fn in runs.items():
            c0 = time.process_time()
            _, info = fn()
            cpu[name].append(time.process_time() - c0)
            steps[name] = int(info[:, 1].sum())
    lines = [f"kernels, one thread, {n} orbits x 1 vector to t = {t_end:g} "
             f"(median of {repeat}):", "",
             "| kernel | CPU (s) | steps | ns per orbit-step |", "|---|---|---|---|"]
    for name in runs:
        c = statistics.median(cpu[name])
        lines.append(f"| {name} | {c:.3f} | {steps[name]} | {1e9 * c / steps[name]:.0f} |")
    same = steps["lanes"] == steps["scalar"]
    lines += ["", f"steps equal: {same}; lanes / scalar CPU: "
                  f"{statistics.median(cpu['lanes']) / statistics.median(cpu['scalar']):.3f}"]
    return lines


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m benchmarks.megno_map", description=__doc__)
    ap.add_argument("--grid", type=int, default=W.FULL.w3_grid)
    ap.add_argument("--t-end", type=float, default=W.FULL.w3_t_end)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--orbits", type=int, default=64, help="orbits of the kernel rows")
    ap.add_argument("--no-heyoka", action="store_true", help="leave heyoka out")
    args = ap.parse_args(argv)

    from andoyer.analysis.chaos.lyapunov import IndicatorRun, chaos_map
    from andoyer.integrate.engines import heyoka_available
    from andoyer.integrate.engines import taylor_engine as TE

    print(f"load before: {os.getloadavg()}")
    for line in _kernels(args.orbits, args.t_end, args.repeat):
        print(line)
    b = W.body()
    h = W.energy_level(b)
    job = IndicatorRun("megno", t_end=args.t_end, tol=W.FULL.tol)
    lanes_from = TE.LANES_FROM

    def megno_map(engine: str, lanes: bool = True) -> Any:
        TE.LANES_FROM = lanes_from if lanes else 10**12
        try:
            return chaos_map(b, h, 0.0, ("theta2", 0.0), (args.grid, args.grid), job,
                             engine=engine, progress=False)
        finally:
            TE.LANES_FROM = lanes_from

    runs: dict[str, Callable[[], Any]] = {
        "taylor (lanes)": lambda: megno_map("taylor"),
        "taylor (scalar)": lambda: megno_map("taylor", lanes=False),
    }
    if heyoka_available() and not args.no_heyoka:
        runs["heyoka"] = lambda: megno_map("heyoka")
    walls: dict[str, list[float]] = {k: [] for k in runs}
    cpus: dict[str, list[float]] = {k: [] for k in runs}
    maps: dict[str, Any] = {k: fn() for k, fn in runs.items()}  # warm-up (compiles)
    for _ in range(args.repeat):
        for name, fn in runs.items():
            c0, t0 = time.process_time(), time.perf_counter()
            maps[name] = fn()
            walls[name].append(time.perf_counter() - t0)
            cpus[name].append(time.process_time() - c0)
    base = "heyoka" if "heyoka" in runs else "taylor (scalar)"
    print(f"\nMEGNO map {args.grid} x {args.grid}, t = {args.t_end:g}, tol {W.FULL.tol:g}, "
          f"interleaved, median of {args.repeat} (walls in s):\n")
    print(f"| route | wall (s) | CPU (s) | wall / {base} | runs |")
    print("|---|---|---|---|---|")
    ref_wall = statistics.median(walls[base])
    for name in runs:
        w, c = statistics.median(walls[name]), statistics.median(cpus[name])
        runs_s = ", ".join(f"{x:.2f}" for x in walls[name])
        print(f"| {name} | {w:.2f} | {c:.2f} | {w / ref_wall:.3f} | {runs_s} |")
    ref = np.asarray(maps["taylor (scalar)"].megno.values)
    for name in runs:
        d = np.abs(np.asarray(maps[name].megno.values) - ref)
        d = d[np.isfinite(d)]
        print(f"|MEGNO {name} - MEGNO taylor (scalar)|: median {np.median(d):.2e}, "
              f"max {np.max(d):.2e} over {d.size} points; failed "
              f"{int(maps[name].attrs['n_failed'])}")
    print(f"load after: {os.getloadavg()}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
