"""Command line of andoyer: one module per command, each a thin layer over the library.

Every public module of this package is a command. It defines ``NAME`` (the command word),
``ORDER`` (its place in ``andoyer --help``), ``register(sub)`` which adds its parser to the
sub-parsers and sets ``func``, and imports the heavy parts of the library only inside the
function that runs, so that ``andoyer --help`` stays fast.
"""

from __future__ import annotations

import argparse
import importlib
import pkgutil
import sys
from collections.abc import Sequence

from andoyer._version import __version__

__all__ = ["main", "build_parser"]


def _command_modules() -> list:
    mods = [importlib.import_module(f"{__name__}.{m.name}")
            for m in pkgutil.iter_modules(__path__) if not m.name.startswith("_")]
    return sorted(mods, key=lambda m: (getattr(m, "ORDER", 100), m.NAME))


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of the ``andoyer`` command."""
    parser = argparse.ArgumentParser(
        prog="andoyer",
        description="Phase space of the heavy rigid body (Hess gyroscope) in "
                    "Andoyer-Deprit variables.")
    parser.add_argument("--version", action="version", version=f"andoyer {__version__}")
    sub = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    for mod in _command_modules():
        mod.register(sub)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``andoyer`` console script."""
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return int(args.func(args))
    except ValueError as exc:  # bad input: a clear message, no traceback
        parser.exit(2, f"andoyer {args.command}: error: {exc}\n")


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
