"""``python -m benchmarks.lane_blocks``: the blocks the lane kernels hand to threads,
fixed (four per thread, as before) against guided (:func:`andoyer.kernels.taylor.lanes.
block_starts`), side by side in one process.

* the **FLI map** of W3 (``chaos_map(..., indicator="fli")`` on taylor, ``--grid``
  squared starts, W3's ``t_end``): the map runs 1024 orbits per kernel call, and each
  call ends when its slowest block does;
* **propagate** of ``--orbits`` W2 starts to W3's ``t_end`` on taylor's lanes.

Interleaved rounds (one of each schedule per round, ``--repeat`` rounds after a warm-up
each), median wall and CPU time, CPU / wall (cores kept busy); the results of the two
schedules compared bit for bit. The load average is printed before and after. No timing
is asserted anywhere.
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


def fixed_starts(n: int, threads: int) -> list[int]:
    """The former blocks: four per thread, at least two orbits per lane."""
    from andoyer.kernels.taylor.lanes import LANES

    size = max(2 * LANES, -(-n // (4 * max(1, threads))))
    return list(range(0, n, size))


def main(argv: list[str] | None = None) -> None:
    from andoyer.analysis.chaos.lyapunov import chaos_map
    from andoyer.analysis.chaos.specs import IndicatorRun
    from andoyer.integrate import propagate
    from andoyer.kernels.taylor import lane_tangent, lanes

    def use(starts: Callable[[int, int], list[int]]) -> None:
        lanes.block_starts = lane_tangent.block_starts = starts  # type: ignore[assignment]

    ap = argparse.ArgumentParser(prog="python -m benchmarks.lane_blocks")
    ap.add_argument("--grid", type=int, default=128)
    ap.add_argument("--orbits", type=int, default=256)
    ap.add_argument("--repeat", type=int, default=3)
    a = ap.parse_args(argv)
    b = W.body()
    h = W.energy_level(b)
    tol = W.FULL.tol
    t_end = W.FULL.w3_t_end
    y0 = W.initial_states(a.orbits)
    guided = lanes.block_starts
    work: dict[str, Callable[[], Any]] = {
        f"FLI map {a.grid}^2": lambda: chaos_map(
            b, h, 0.0, ("theta2", 0.0), grid=a.grid,
            run=IndicatorRun("fli", t_end=t_end, tol=tol), engine="taylor").fli.values,
        f"propagate {a.orbits} orbits": lambda: propagate(
            b, y0, [0.0, t_end], engine="taylor", rtol=tol, atol=tol,
            progress=False).G3.values,
    }
    print(f"load average before: {os.getloadavg()[0]:.2f}")
    for name, fn in work.items():
        res: dict[str, dict[str, Any]] = {}
        for label, starts in (("fixed", fixed_starts), ("guided", guided)):
            use(starts)
            fn()  # warm-up
            res[label] = {"wall": [], "cpu": []}
        for _ in range(a.repeat):
            for label, starts in (("fixed", fixed_starts), ("guided", guided)):
                use(starts)
                c0, t0 = time.process_time(), time.perf_counter()
                res[label]["out"] = fn()
                res[label]["wall"].append(time.perf_counter() - t0)
                res[label]["cpu"].append(time.process_time() - c0)
        use(guided)
        same = np.array_equal(res["fixed"]["out"], res["guided"]["out"], equal_nan=True)
        print(f"\n{name} (median of {a.repeat}; results bit-identical: {same})")
        for label, r in res.items():
            wall, cpu = statistics.median(r["wall"]), statistics.median(r["cpu"])
            print(f"  {label:7s} wall {wall:8.3f} s  cpu {cpu:8.3f} s  cores {cpu / wall:.2f}")
        ratio = statistics.median(res["guided"]["wall"]) / statistics.median(res["fixed"]["wall"])
        print(f"  guided / fixed wall: {ratio:.3f}")
    print(f"\nload average after: {os.getloadavg()[0]:.2f}")


if __name__ == "__main__":
    main()
