"""``andoyer section``: a filled Poincare section on an energy level, NetCDF + PNG."""

from __future__ import annotations

import argparse
from typing import Any

from andoyer.cli._common import (
    add_body_args,
    add_engine_args,
    add_level_args,
    add_term,
    count,
    inputs_from_args,
)

NAME = "section"
ORDER = 40


def run(args: argparse.Namespace) -> int:
    import matplotlib

    matplotlib.use("Agg")
    from andoyer.integrate import budget
    from andoyer.integrate.api import poincare
    from andoyer.integrate.fill import fill_section
    from andoyer.io import write_netcdf
    from andoyer.plot.section import plot_section, save_figure

    out, body, _, _, sec, h = inputs_from_args(args, level=True)
    assert h is not None  # a level command without a state has its level
    if sec.coord not in ("g", "theta2"):
        raise ValueError("andoyer section fills the planes of 'g=...' (l, L) and "
                         "'theta2=...' (theta1, J1) sections; use the Python API poincare() "
                         "for other sections")
    # Costed before the fill seeds a single orbit, naming the flags.
    budget.check(f"--n-orbits {args.n_orbits} x --n-crossings {args.n_crossings}",
                 memory=budget.DATASET_BYTES * float(args.n_orbits) * args.n_crossings)
    fill = fill_section(body, h, args.M, (sec.coord, sec.value),
                        n_orbits=args.n_orbits, sampling=args.sampling)
    y0 = fill["y0"].values
    print(f"{y0.shape[0]} orbits on H = {h:g}, M = {args.M:g}; "
          f"{args.n_crossings} crossings each")
    ds = poincare(body, y0, sec, args.n_crossings, engine=args.engine, rtol=args.rtol,
                  atol=args.atol, progress=True)
    ds.attrs.update(h=h, M=args.M)
    write_netcdf(ds, out)
    ax = plot_section(ds, boundary=fill,
                      title=f"{body.name or 'body'}: H = {h:.6g}, M = {args.M:g}, "
                            f"{sec.coord} = {sec.value:g}")
    fig = ax.get_figure(root=True)
    assert fig is not None
    (png,) = save_figure(fig, out.with_suffix(".png"))
    print(f"wrote {out} and {png}; max |section residual| "
          f"{float(abs(ds.section_residual).max()):.1e}")
    return 0


def register(sub: Any) -> None:
    p = sub.add_parser(NAME, help="Poincare section on an energy level: NetCDF + PNG")
    add_body_args(p)
    add_level_args(p)
    add_term(p, "n_orbits", type=count(1), default=40,
             help="orbits seeded on the plane (default 40)")
    add_term(p, "n_crossings", type=count(1), default=300,
             help="crossings per orbit (default 300)")
    add_term(p, "sampling", choices=("grid", "sobol", "halton"), default="grid",
             help="initial conditions on the plane (default grid)")
    add_engine_args(p)
    p.add_argument("--out", default="section.nc", help="output NetCDF (PNG beside it)")
    p.set_defaults(func=run)
