"""``andoyer resonances``: the p/q island chains predicted at first order in mu (their
centres, half-widths, periodic orbits and stability); NetCDF + PNG, the chains drawn over
a computed section with ``--n-orbits``."""

from __future__ import annotations

import argparse
from typing import Any

from andoyer.cli._common import (
    add_body_args,
    add_engine_args,
    add_term,
    count,
    inputs_from_args,
    real,
)

NAME = "resonances"
ORDER = 48


def run(args: argparse.Namespace) -> int:
    import math

    import matplotlib

    matplotlib.use("Agg")
    from andoyer.analysis.resonance import resonance_widths
    from andoyer.io import write_netcdf
    from andoyer.plot.resonance import plot_resonances
    from andoyer.plot.section import plot_section, save_figure

    inputs = inputs_from_args(args, level=True)
    out, body, h = inputs.out, inputs.body, inputs.h
    assert h is not None
    ds = resonance_widths(body, h, args.M, args.section, max_order=args.max_order)
    write_netcdf(ds, out)
    ax = None
    if args.n_orbits:
        import warnings

        from andoyer.errors import SingularPassageWarning
        from andoyer.integrate.api import poincare
        from andoyer.integrate.fill import fill_section

        sec = inputs.section
        fill = fill_section(body, h, args.M, (sec.coord, sec.value), n_orbits=args.n_orbits,
                            root="smallest")
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", SingularPassageWarning)
            pts = poincare(body, fill.y0.values, sec, args.n_crossings, engine=args.engine,
                           rtol=args.rtol, atol=args.atol, progress=True)
        ax = plot_section(pts, boundary=fill)
    ax = plot_resonances(ds, ax=ax, title=f"{body.name or 'body'}: chains of order <= "
                         f"{args.max_order} predicted on H = {h:.6g}, M = {args.M:g}, "
                         f"{args.section}, mu = {body.mu:g}")
    ax.title.set_fontsize(8)
    fig = ax.get_figure(root=True)
    assert fig is not None
    (png,) = save_figure(fig, out.with_suffix(".png"))
    print(f"{ds.sizes['resonance']} resonant tori (p + q <= {args.max_order}) on H = {h:.6g}, "
          f"M = {args.M:g}, {body.name or 'body'} mu = {body.mu:g}:")
    print(f"  {'q:p':>6} {'axis':>4} {'sign':>4} {'G*':>12} {'half-width G':>13} "
          f"{'Omega':>10} {'residue':>10}")
    for i in range(ds.sizes["resonance"]):
        r = ds.isel(resonance=i)
        width = float(r.half_width)
        text = f"{width:13.4e}" if math.isfinite(width) else f"{'(2nd order)':>13}"
        print(f"  {str(r.label.values):>6} {int(r.axis):>4} {int(r.sign):>4} "
              f"{float(r.G_action):12.8f} {text} {float(r.libration_frequency):10.3e} "
              f"{float(r.residue_stable):10.3e}")
    print(f"wrote {out} and {png}")
    return 0


def register(sub: Any) -> None:
    p = sub.add_parser(NAME, help="p/q island chains predicted at first order in mu: "
                                  "NetCDF + PNG",
                       description="The resonant tori W = p/q of the free top on the energy "
                                   "level and the first-order pendulum of each chain "
                                   "(andoyer.analysis.resonance): centre G*, half-width in "
                                   "G, stable and unstable periodic points in the section "
                                   "plane, libration frequency and Greene's residue. The "
                                   "PNG draws the chains (centre line dashed, separatrices, "
                                   "o stable, x unstable), over --n-orbits orbits of the "
                                   "section when asked.")
    add_body_args(p)
    add_term(p, "h", type=real(), default=None, metavar="H",
             help="energy level H = h (default: H of (l, g, L, G, M) = (0.3, 0, 0.3, 1, M))")
    add_term(p, "M", type=real(), default=0.0,
             help="area constant (G, gamma) = M (default 0)")
    add_term(p, "section", default="g=0",
             help="'g=VALUE' (plane l, L) or 'theta2=VALUE' (plane theta1, J1); append "
                  "':-' for the decreasing direction (default g=0)")
    add_term(p, "max_order", type=count(2, 100), default=12,
             help="largest order p + q of the chains (default 12)")
    add_term(p, "n_orbits", type=count(0), default=0,
             help="orbits of a section drawn under the chains (default 0: none)")
    add_term(p, "n_crossings", type=count(1), default=300,
             help="crossings per orbit of that section (default 300)")
    add_engine_args(p)
    p.add_argument("--out", default="resonances.nc", help="output NetCDF (PNG beside it)")
    p.set_defaults(func=run)
