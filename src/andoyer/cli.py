"""Command line of andoyer: one thin function per command, calling the library."""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Sequence
from dataclasses import asdict
from typing import Any

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


# ---------------------------------------------------------------------- bodies
def _add_body_args(p: argparse.ArgumentParser) -> None:
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


def _body(args: argparse.Namespace) -> Any:
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


def _floats(text: str, n: int, what: str) -> list[float]:
    try:
        vals = [float(v) for v in text.replace(",", " ").split()]
    except ValueError:
        raise ValueError(f"{what}: {text!r} is not a list of numbers") from None
    if len(vals) != n:
        raise ValueError(f"{what} needs {n} numbers, got {len(vals)}")
    return vals


def _add_engine_args(p: argparse.ArgumentParser) -> None:
    p.add_argument("--engine", choices=("heyoka", "numba", "scipy"), default=None,
                   help="integration engine (default: heyoka where installed, else numba)")
    p.add_argument("--rtol", type=float, default=1e-12, help="relative tolerance")
    p.add_argument("--atol", type=float, default=1e-12, help="absolute tolerance")


def _cmd_orbit(args: argparse.Namespace) -> int:
    import numpy as np

    from andoyer.integrate.api import propagate
    from andoyer.io import write_netcdf

    body = _body(args)
    given = [(n, v) for n, v in (("euler_poisson", args.y0), ("andoyer", args.andoyer),
                                 ("hess", args.hess)) if v is not None]
    if len(given) != 1:
        raise ValueError("give exactly one initial state: --y0, --andoyer or --hess")
    chart, text = given[0]
    state = _floats(text, 6 if chart == "euler_poisson" else 5, f"--{chart.split('_')[0]}")
    if args.t_end <= 0 or args.n_out < 2:
        raise ValueError("--t-end must be > 0 and --n-out >= 2")
    t = np.linspace(0.0, args.t_end, args.n_out)
    ds = propagate(body, state, t, engine=args.engine, rtol=args.rtol, atol=args.atol,
                   chart=chart, progress=True)
    out = write_netcdf(ds, args.out)
    drift = float(abs(ds.H_drift).max())
    print(f"wrote {out}: {args.n_out} states to t = {args.t_end:g} "
          f"(engine {ds.attrs['engine']}, max |relative energy drift| {drift:.2e})")
    return 0


def _cmd_section(args: argparse.Namespace) -> int:
    from pathlib import Path

    import matplotlib

    matplotlib.use("Agg")
    from andoyer.integrate.api import poincare
    from andoyer.integrate.fill import fill_section
    from andoyer.integrate.section import Section
    from andoyer.io import write_netcdf
    from andoyer.plot.section import plot_section, save_figure

    body = _body(args)
    sec = Section.parse(args.section)
    if sec.coord not in ("g", "theta2"):
        raise ValueError("andoyer section fills the planes of 'g=...' (l, L) and "
                         "'theta2=...' (theta1, J1) sections; use the Python API poincare() "
                         "for other sections")
    if args.energy is None:
        from andoyer import from_andoyer
        from andoyer.charts.euler_poisson import energy

        args.energy = float(energy(body, from_andoyer([0.3, 0.0, 0.3, 1.0, args.area])))
    fill = fill_section(body, args.energy, args.area, (sec.coord, sec.value),
                        n=args.orbits, method=args.sampling)
    y0 = fill["y0"].values
    print(f"{y0.shape[0]} orbits on H = {args.energy:g}, M = {args.area:g}; "
          f"{args.crossings} crossings each")
    ds = poincare(body, y0, sec, args.crossings, engine=args.engine, rtol=args.rtol,
                  atol=args.atol, progress=True)
    ds.attrs.update(energy=args.energy, area=args.area)
    out = Path(args.out)
    write_netcdf(ds, out)
    ax = plot_section(ds, boundary=fill,
                      title=f"{body.name or 'body'}: H = {args.energy:.6g}, M = {args.area:g}, "
                            f"{sec.coord} = {sec.value:g}")
    fig = ax.get_figure(root=True)
    assert fig is not None
    (png,) = save_figure(fig, out.with_suffix(".png"))
    print(f"wrote {out} and {png}; max |section residual| "
          f"{float(abs(ds.section_residual).max()):.1e}")
    return 0


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

    p = sub.add_parser("orbit", help="integrate one orbit; write NetCDF")
    _add_body_args(p)
    st = p.add_argument_group("initial state (one of)")
    st.add_argument("--y0", help="Euler-Poisson state 'G1,G2,G3,gamma1,gamma2,gamma3'")
    st.add_argument("--andoyer", help="Andoyer-Deprit state 'l,g,L,G,M'")
    st.add_argument("--hess", help="Hess-chart state 'theta1,theta2,J1,J2,J3'")
    p.add_argument("--t-end", type=float, default=1000.0, help="final time (default 1000)")
    p.add_argument("--n-out", type=int, default=1001, help="output times (default 1001)")
    _add_engine_args(p)
    p.add_argument("--out", default="orbit.nc", help="output NetCDF file")
    p.set_defaults(func=_cmd_orbit)

    p = sub.add_parser("section", help="Poincare section on an energy level: NetCDF + PNG")
    _add_body_args(p)
    p.add_argument("--energy", type=float, default=None,
                   help="energy level H (default: H of (l, g, L, G, M) = (0.3, 0, 0.3, 1, M))")
    p.add_argument("--area", type=float, default=0.0, help="area constant M (default 0)")
    p.add_argument("--section", default="theta2=0",
                   help="'theta2=VALUE' (plane theta1, J1) or 'g=VALUE' (plane l, L); "
                        "append ':-' for the decreasing direction (default theta2=0)")
    p.add_argument("--orbits", type=int, default=40, help="orbits (default 40)")
    p.add_argument("--crossings", type=int, default=300,
                   help="crossings per orbit (default 300)")
    p.add_argument("--sampling", choices=("grid", "sobol", "halton"), default="grid",
                   help="initial conditions on the plane (default grid)")
    _add_engine_args(p)
    p.add_argument("--out", default="section.nc", help="output NetCDF (PNG beside it)")
    p.set_defaults(func=_cmd_section)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``andoyer`` console script."""
    parser = build_parser()
    args = parser.parse_args(argv)
    if getattr(args, "points", 1) < 1:
        parser.error("--points must be a positive integer")
    try:
        return int(args.func(args))
    except ValueError as exc:  # bad input: a clear message, no traceback
        parser.exit(2, f"andoyer {args.command}: error: {exc}\n")


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
