"""Command line of andoyer: one thin function per command, calling the library."""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Sequence
from dataclasses import asdict

from andoyer._version import __version__

__all__ = ["main", "build_parser"]


def _cmd_paper_check(args: argparse.Namespace) -> int:
    from andoyer.analysis.paper_check import format_table, paper_check

    rows = paper_check(n=args.points, seed=args.seed)
    if args.format == "json":
        print(json.dumps([asdict(r) for r in rows], indent=1))
    else:
        print("Every formula printed in the paper, checked against the derivation from "
              "H = (G, IG)/2 + mu (r, gamma)\n"
              f"({args.points} random points each; 'holds' = agreement to 1e-9)\n")
        print(format_table(rows))
    broken = [r for r in rows if r.corrected_holds is False]
    for r in broken:
        print(f"error: the corrected form of {r.label} {r.name!r} does not match the "
              "derivation", file=sys.stderr)
    return 1 if broken else 0


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of the ``andoyer`` command."""
    parser = argparse.ArgumentParser(
        prog="andoyer",
        description="Phase space of the heavy rigid body (Hess gyroscope) in "
                    "Andoyer-Deprit variables.")
    parser.add_argument("--version", action="version", version=f"andoyer {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")

    p = sub.add_parser("paper-check", help="check every formula of the paper against the "
                                           "derivation and list the misprints")
    p.add_argument("--points", type=int, default=200,
                   help="random points per formula (default: 200)")
    p.add_argument("--seed", type=int, default=20261121, help="seed of the random points")
    p.add_argument("--format", choices=("text", "json"), default="text",
                   help="output format (default: text)")
    p.set_defaults(func=_cmd_paper_check)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``andoyer`` console script."""
    parser = build_parser()
    args = parser.parse_args(argv)
    if getattr(args, "points", 1) < 1:
        parser.error("--points must be a positive integer")
    return int(args.func(args))


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
