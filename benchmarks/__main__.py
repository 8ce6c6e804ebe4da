"""``python -m benchmarks [--quick]``: run the side-by-side benchmarks.

Writes ``benchmarks/results.json``, ``RESULTS.md`` and ``SUMMARY.md`` (or into ``--out``);
``--tables`` rewrites the tables from ``results.json`` without running.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from benchmarks.harness import regenerate, run

RUNNERS = ("andoyer heyoka", "andoyer numba", "andoyer taylor", "andoyer scipy",
           "heyoka plain",
           "heyoka ensemble", "heyoka hand-tuned", "scipy DOP853", "scipy DOP853 serial",
           "scipy DOP853 pool(2)")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m benchmarks", description=__doc__)
    ap.add_argument("--quick", action="store_true",
                    help="small sizes (8 orbits x 50 crossings, 8 x 8 map, warm caches "
                         "only): under a minute, a smoke run")
    ap.add_argument("--workloads", default="W1,W2,W3,W4,W5,W6,W7,S",
                    help="comma-separated subset of W1,W2,W3,W4,W5,W6,W7,S (default: all; "
                         "W5 is `andoyer paper`, W6 sections against the bare lane flow, W7 "
                         "the lane kernels at 4 and 8 lanes, S the scaling table and plot)")
    ap.add_argument("--runners", default=None,
                    help=f"comma-separated subset of: {', '.join(RUNNERS)}")
    ap.add_argument("--full-scipy", action="store_true",
                    help="run the scipy W2 runners on every orbit (about 12 minutes for "
                         "the pool, 25 serial, per section) instead of a subset "
                         "extrapolated by integrated time")
    ap.add_argument("--no-cold", action="store_true",
                    help="W4: skip the cold-cache processes (Numba compiles for ~15 s)")
    ap.add_argument("--out", type=Path, default=None,
                    help="directory for results.json and RESULTS.md (default: benchmarks/)")
    ap.add_argument("--tables", action="store_true",
                    help="run nothing: rewrite RESULTS.md, SUMMARY.md and the README's block "
                         "from results.json (after a change of the tables or of the "
                         "defaults they state)")
    args = ap.parse_args(argv)
    if args.tables:
        regenerate(args.out)
        return 0
    workloads = tuple(w.strip().upper() for w in args.workloads.split(",") if w.strip())
    bad = [w for w in workloads if w not in ("W1", "W2", "W3", "W4", "W5", "W6", "W7", "S")]
    runners = None
    if args.runners:
        runners = {r.strip() for r in args.runners.split(",") if r.strip()}
        bad += sorted(runners - set(RUNNERS))
    if bad:
        ap.error(f"unknown workload(s)/runner(s): {', '.join(bad)}")
    result = run(quick=args.quick, workloads=workloads, runners=runners,
                 full_scipy=args.full_scipy, cold=False if args.no_cold else None,
                 out_dir=args.out)
    for t in result["targets"]:
        print(f"{'ok  ' if t['met'] else 'MISS'} {t['target']}: {t['value']}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
