"""W3 side by side: ``chaos_map`` (default engine, FLI only) against the expert script.

Interleaved pairs in one process (andoyer, script, andoyer, script, ...) after one
warm-up of each, so that a shared machine's load falls on both alike; reports wall and
CPU time (all threads) of every pair, their medians, the ratios andoyer / script and
max |FLI_andoyer - FLI_script| over the accessible points. The script gets andoyer's
states and initial tangent vectors (``peers.fli_heyoka.inputs``, not timed)::

    python -m benchmarks.w3_pairs --n 64 --pairs 5
    python -m benchmarks.w3_pairs --n 256 --pairs 1
    python -m benchmarks.w3_pairs --n 64 --profile      # cProfile of one chaos_map call
"""

from __future__ import annotations

import argparse
import cProfile
import os
import pstats
import statistics
import time
from typing import Any

import numpy as np

from benchmarks import workloads as W


def _timed(fn: Any) -> tuple[float, float, Any]:
    c0, t0 = time.process_time(), time.perf_counter()
    out = fn()
    return time.perf_counter() - t0, time.process_time() - c0, out


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", type=int, default=64, help="grid n x n (default 64)")
    ap.add_argument("--pairs", type=int, default=5)
    ap.add_argument("--t-end", type=float, default=1000.0)
    ap.add_argument("--profile", action="store_true", help="cProfile one chaos_map call")
    args = ap.parse_args(argv)

    from andoyer.analysis.chaos.lyapunov import IndicatorRun, chaos_map
    from benchmarks.peers import fli_heyoka

    b = W.body()
    h = W.energy_level(b)
    p = W.params(b)

    def andoyer(n: int = args.n, t_end: float = args.t_end) -> Any:
        return chaos_map(b, h, 0.0, ("theta2", 0.0), (n, n),
                         IndicatorRun("fli", t_end=t_end), progress=False)

    # Warm-up of both on a 16 x 16 map (compiles or loads the integrators), then the
    # states and vectors of the timed map (its grid does not depend on t_end: taken
    # from a map to t = 0.01, not timed).
    ds = andoyer(16)
    fli_heyoka.fli_map(p, *fli_heyoka.inputs(ds, b, args.t_end), 1e-12)
    y0, w0, t = fli_heyoka.inputs(andoyer(t_end=0.01), b, args.t_end)
    if args.profile:
        prof = cProfile.Profile()
        c0, t0 = time.process_time(), time.perf_counter()
        prof.runcall(andoyer)
        print(f"chaos_map {args.n}^2 under cProfile: wall {time.perf_counter() - t0:.3f} s, "
              f"CPU {time.process_time() - c0:.3f} s")
        pstats.Stats(prof).sort_stats("cumulative").print_stats(30)
        return
    print(f"{args.n} x {args.n}, {y0.shape[0]} points, t = {args.t_end:g}; load before "
          f"{os.getloadavg()}")
    rows = []
    diff = 0.0
    for _ in range(args.pairs):
        wa, ca, ds = _timed(andoyer)
        ws, cs, f = _timed(lambda: fli_heyoka.fli_map(p, y0, w0, t, 1e-12))
        d = np.abs(ds.fli.values[ds.accessible.values] - f)
        diff = max(diff, float(np.nanmax(d)))
        rows.append((wa, ca, ws, cs))
        print(f"  andoyer wall {wa:7.3f} CPU {ca:7.3f} | script wall {ws:7.3f} CPU {cs:7.3f}"
              f" | ratio wall {wa / ws:5.2f} CPU {ca / cs:5.2f}", flush=True)
    wa, ca, ws, cs = (statistics.median(c) for c in zip(*rows, strict=True))
    rw = statistics.median(r[0] / r[2] for r in rows)
    rc = statistics.median(r[1] / r[3] for r in rows)
    print(f"median: andoyer wall {wa:.3f} CPU {ca:.3f} | script wall {ws:.3f} CPU {cs:.3f} | "
          f"median ratio andoyer/script wall {rw:.2f} CPU {rc:.2f}")
    print(f"max |FLI_andoyer - FLI_script| = {diff:.2e}; load after {os.getloadavg()}")


if __name__ == "__main__":
    main()
