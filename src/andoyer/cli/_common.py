"""Arguments shared by the commands: the body and the integration engine."""

from __future__ import annotations

import argparse
from typing import Any

__all__ = ["add_body_args", "body_from_args", "add_engine_args", "add_level_args",
           "floats"]


# ---------------------------------------------------------------------- bodies
def add_body_args(p: argparse.ArgumentParser) -> None:
    g = p.add_argument_group("body")
    g.add_argument("--body", default="paper",
                   choices=("paper", "hess", "custom", "lagrange", "kovalevskaya",
                            "goryachev-chaplygin"),
                   help="paper: Hess body A=2.5, B=2.0, C=2.2, mu=0.01 (default); hess: "
                        "Hess body from --A --B --C --mu; custom: --A --B --C --mu --r")
    g.add_argument("--A", type=float, help="moment of inertia A")
    g.add_argument("--B", type=float, help="moment of inertia B")
    g.add_argument("--C", type=float, help="moment of inertia C")
    g.add_argument("--mu", type=float, help="weight x distance of the centre of mass")
    g.add_argument("--r", type=float, nargs=3, metavar=("E1", "E2", "E3"),
                   help="direction of the centre of mass (custom bodies)")


def body_from_args(args: argparse.Namespace) -> Any:
    from andoyer.body import RigidBody

    mu = 0.01 if args.mu is None else args.mu
    if args.body == "paper":
        return RigidBody.paper(mu)
    if args.body in ("kovalevskaya", "goryachev-chaplygin"):
        make = (RigidBody.kovalevskaya if args.body == "kovalevskaya"
                else RigidBody.goryachev_chaplygin)
        return make(args.C or 1.0, 1.0 if args.mu is None else args.mu)
    missing = [n for n in ("A", "B", "C") if getattr(args, n) is None
               and not (args.body == "lagrange" and n == "B")]
    if missing:
        raise ValueError(f"--body {args.body} needs --{', --'.join(missing)}")
    if args.body == "hess":
        return RigidBody.hess(args.A, args.B, args.C, mu)
    if args.body == "lagrange":
        return RigidBody.lagrange(args.A, args.C, mu)
    if args.r is None:
        raise ValueError("--body custom needs --r E1 E2 E3 (direction of the centre of mass)")
    return RigidBody(args.A, args.B, args.C, mu, tuple(args.r), "custom")


def floats(text: str, n: int, what: str) -> list[float]:
    try:
        vals = [float(v) for v in text.replace(",", " ").split()]
    except ValueError:
        raise ValueError(f"{what}: {text!r} is not a list of numbers") from None
    if len(vals) != n:
        raise ValueError(f"{what} needs {n} numbers, got {len(vals)}")
    return vals


def add_engine_args(p: argparse.ArgumentParser) -> None:
    p.add_argument("--engine", choices=("heyoka", "numba", "scipy"), default=None,
                   help="integration engine (default: heyoka where installed, else numba)")
    p.add_argument("--rtol", type=float, default=1e-12, help="relative tolerance")
    p.add_argument("--atol", type=float, default=1e-12, help="absolute tolerance")


def add_level_args(p: argparse.ArgumentParser, *, directed: bool = True) -> None:
    """``--energy``, ``--area``, ``--section``: an energy level, area constant and section."""
    p.add_argument("--energy", type=float, default=None,
                   help="energy level H (default: H of (l, g, L, G, M) = (0.3, 0, 0.3, 1, M))")
    p.add_argument("--area", type=float, default=0.0, help="area constant M (default 0)")
    p.add_argument("--section", default="theta2=0",
                   help="'theta2=VALUE' (plane theta1, J1) or 'g=VALUE' (plane l, L)"
                        + ("; append ':-' for the decreasing direction" if directed else "")
                        + " (default theta2=0)")
