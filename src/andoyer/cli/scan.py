"""``andoyer scan``: a parameter scan on Dask, streamed into a Zarr store, resumable."""

from __future__ import annotations

import argparse
from typing import Any

from andoyer.cli._common import count, real

NAME = "scan"
ORDER = 60


def run(args: argparse.Namespace) -> int:
    from pathlib import Path

    from andoyer.scan.config import STORAGE_NAMES, load_config
    from andoyer.scan.cost import check_size
    from andoyer.scan.run import run_scan, summary
    from andoyer.scan.store import check_store

    cfg = load_config(args.config)
    store = Path(args.store) if args.store else Path(Path(args.config).stem + ".zarr")
    # a store the scan cannot use is refused before anything is said, by a dry run too
    check_store(store, cfg, overwrite=args.overwrite)
    cost = check_size(cfg, args.max_core_hours, args.max_store_gb)
    grid = " x ".join(f"{STORAGE_NAMES[k]}[{len(cfg.values(k))}]" for k in cfg.swept)
    print(f"scan {args.config}: task {cfg.task} over {grid} "
          f"(engine {cfg.integrator.engine}): {cost.describe()}")
    if args.dry_run:
        return 0
    where = {"serial": "in this process (no Dask)", "local": "on a local cluster",
             None: "on a local cluster"}.get(args.scheduler, f"on {args.scheduler}")
    print(f"store {store}, computed {where}; interrupt at will: the same command resumes")
    try:
        report = run_scan(cfg, store, scheduler=args.scheduler, n_workers=args.workers,
                          overwrite=args.overwrite, retries=args.retries,
                          progress=None if args.progress is None else args.progress,
                          max_core_hours=args.max_core_hours,
                          max_store_gb=args.max_store_gb)
    except KeyboardInterrupt as exc:  # the boundary prints it, with how to resume
        from andoyer.errors import Interrupted

        raise Interrupted(getattr(exc, "signal", "SIGINT"),
                          f"the chunks marked done in {store} are kept; run the same "
                          "command to resume") from None
    if report.dashboard:
        print(f"dashboard was at {report.dashboard}")
    print(summary(report))
    print(f"read it with xarray.open_zarr({str(store)!r}); draw it with "
          f"andoyer atlas {store}")
    return 0


def register(sub: Any) -> None:
    p = sub.add_parser(NAME, help="parameter scan (mu, h, M, A, B, C) on Dask into a "
                                  "resumable Zarr store",
                       description="Run the scan described by a TOML file (see "
                                   "examples/atlas.toml and the README) and stream its "
                                   "results into a Zarr store. Rerunning the same command "
                                   "after an interruption computes only what is missing.")
    p.add_argument("config", help="the scan's TOML configuration")
    p.add_argument("--store", default=None,
                   help="Zarr store (default: CONFIG's name with .zarr, in the current "
                        "folder)")
    p.add_argument("--scheduler", default=None, metavar="ADDRESS",
                   help="tcp://HOST:PORT of a running Dask scheduler; 'local' (default): "
                        "a local cluster on all cores; 'serial': no Dask")
    p.add_argument("--workers", type=count(1), default=None,
                   help="workers of the local cluster (default: all cores)")
    p.add_argument("--overwrite", action="store_true",
                   help="start again in an existing store")
    p.add_argument("--retries", type=count(0), default=2, help="retries of a failing task")
    p.add_argument("--dry-run", action="store_true",
                   help="check the configuration and the store, print the estimated cost, stop")
    p.add_argument("--max-core-hours", type=real(positive=True), default=100.0,
                   help="refuse scans estimated above this CPU time (default 100)")
    p.add_argument("--max-store-gb", type=real(positive=True), default=50.0,
                   help="refuse scans estimated above this storage (default 50)")
    prog = p.add_mutually_exclusive_group()
    prog.add_argument("--progress", dest="progress", action="store_true", default=None,
                      help="progress line (default: when stderr is a terminal)")
    prog.add_argument("--no-progress", dest="progress", action="store_false")
    p.set_defaults(func=run)
