"""``andoyer paper``: the main job -- the paper's figures, data and checks, rebuilt."""

from __future__ import annotations

import argparse
from typing import Any

from andoyer.cli._common import ENGINE_HELP, count
from andoyer.integrate.engines import ENGINES

NAME = "paper"
ORDER = 10


def run(args: argparse.Namespace) -> int:
    from andoyer.cli._common import output_folder
    from andoyer.report.paper import build_paper

    output_folder(args.out)
    index, done = build_paper(args.out, engine=args.engine, quick=args.quick,
                              only=args.only or None, progress=True, jobs=args.jobs)
    print(f"andoyer paper: {len(done)} items written to {index.parent}/; open {index}")
    return 0


def register(sub: Any) -> None:
    from andoyer.report import DEFAULT_OUT

    p = sub.add_parser(NAME, help="rebuild the paper's figures, their data and the formula "
                                  "check into a folder with an index.html (the main job)")
    p.add_argument("--out", default=DEFAULT_OUT,
                   help=f"output folder (default: {DEFAULT_OUT})")
    p.add_argument("--engine", choices=tuple(ENGINES), default=None, help=ENGINE_HELP)
    p.add_argument("--quick", action="store_true",
                   help="smaller grids and shorter runs (a smoke test, not the figures)")
    p.add_argument("--jobs", type=count(1), default=None, metavar="N",
                   help="processes building items at once (default: 2 on two or more "
                        "cores, else 1)")
    p.add_argument("--only", nargs="+", metavar="ITEM",
                   help="build only these items (e.g. fig3 paper-check)")
    p.set_defaults(func=run)
