"""``andoyer paper-check``: every formula printed in the paper vs the derivation."""

from __future__ import annotations

import argparse
import json
import sys
from dataclasses import asdict
from typing import Any

from andoyer.cli._common import count

NAME = "paper-check"
ORDER = 20


def run(args: argparse.Namespace) -> int:
    from andoyer.analysis.paper.check import paper_check
    from andoyer.io.tables import format_table

    if args.points < 1:
        raise ValueError("--points must be a positive integer")
    rows = paper_check(n=args.points, seed=args.seed)
    if args.format == "json":
        print(json.dumps([asdict(r) for r in rows], indent=1))
    else:
        print("Every formula printed in the paper, checked against the derivation from "
              "H = (G, I^-1 G)/2 + mu (r, gamma)\n"
              f"({args.points} random points each; 'holds' = agreement to 1e-9)\n")
        print(format_table(rows))
    broken = [r for r in rows if r.corrected_holds is False]
    for r in broken:
        print(f"error: the corrected form of {r.label} {r.name!r} does not match the "
              "derivation", file=sys.stderr)
    return 1 if broken else 0


def register(sub: Any) -> None:
    p = sub.add_parser(NAME, help="check every formula of the paper against the "
                                  "derivation and list the misprints")
    p.add_argument("--points", type=count(1), default=200,
                   help="random points per formula (default: 200)")
    p.add_argument("--seed", type=count(0), default=20261121, help="seed of the random points")
    p.add_argument("--format", choices=("text", "json"), default="text",
                   help="output format (default: text)")
    p.set_defaults(func=run)
