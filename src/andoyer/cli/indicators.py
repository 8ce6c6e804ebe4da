"""``andoyer indicators``: FLI, MEGNO and the Lyapunov exponent of one orbit, NetCDF + PNG."""

from __future__ import annotations

import argparse
from typing import Any

from andoyer.cli._common import (
    add_body_args,
    add_engine_args,
    add_state_args,
    add_term,
    count,
    inputs_from_args,
    real,
)

NAME = "indicators"
ORDER = 48


def run(args: argparse.Namespace) -> int:
    import matplotlib

    matplotlib.use("Agg")
    from andoyer.analysis.chaos.lyapunov import indicators
    from andoyer.analysis.chaos.registry import INDICATORS, MAP_EXTRAS, PANEL_INDICATORS
    from andoyer.io import write_netcdf
    from andoyer.plot.chaos import plot_indicators
    from andoyer.plot.section import save_figure

    out, body, state, chart, _, _ = inputs_from_args(args, state="required")
    assert state is not None and chart is not None  # required: given, or refused
    ds = indicators(body, state, args.t_end, n_times=args.n_times, chart=chart,
                    tangent=args.tangent, tol=args.tol, engine=args.engine)
    write_netcdf(ds, out)
    title = (f"{body.name or 'body'}: FLI and MEGNO from {chart} state {state}, engine "
             f"{ds.attrs['engine']}, tol {args.tol:g}, tangent space {args.tangent}")
    (png,) = save_figure(plot_indicators(ds, title=title), out.with_suffix(".png"))
    end = ds.isel(orbit=0, time=-1)
    values = ", ".join(
        f"{INDICATORS[k].title} {float(end[k]):.4g}"
        + (f" ({INDICATORS[k].reading})" if INDICATORS[k].reading else "")
        for k in (*PANEL_INDICATORS, *MAP_EXTRAS))
    print(f"{body.name or 'body'}: to t = {args.t_end:g} (engine {ds.attrs['engine']}): "
          f"{values}; max |relative energy drift| {float(abs(ds.H_drift).max()):.1e}")
    print(f"wrote {out} and {png}")
    return 0


def register(sub: Any) -> None:
    p = sub.add_parser(NAME, help="chaos indicators (FLI, MEGNO, mLE) of one orbit: NetCDF "
                                  "+ PNG",
                       description="Fast Lyapunov indicator, MEGNO and the maximal Lyapunov "
                                   "exponent of one orbit against time, from the "
                                   "variational equations (andoyer.analysis.chaos."
                                   "indicators).")
    add_body_args(p)
    add_state_args(p)
    add_term(p, "t_end", type=real(positive=True), default=1000.0,
             help="integration time (default 1000)")
    add_term(p, "n_times", type=count(2), default=101,
             help="output times linspace(0, t_end, n_times) (default 101)")
    add_term(p, "tangent", choices=("leaf", "energy"), default="leaf",
             help="space of the initial tangent vector (default leaf)")
    add_term(p, "tol", type=real(positive=True), default=1e-12,
             help="tolerance of the variational integration (default 1e-12)")
    add_engine_args(p, tolerances=False)
    p.add_argument("--out", default="indicators.nc", help="output NetCDF (PNG beside it)")
    p.set_defaults(func=run)
