"""``andoyer chaos-map``: FLI / MEGNO over a section's plane on an energy level, NetCDF + PNG."""

from __future__ import annotations

import argparse
from typing import Any

from andoyer.analysis.chaos.registry import ALL_OF_THEM, MAP_CHOICES, MAP_INDICATORS, chosen
from andoyer.cli._common import (
    add_body_args,
    add_level_args,
    count,
    inputs_from_args,
    real,
)
from andoyer.integrate.engines import ENGINES
from andoyer.validation import integer

NAME = "chaos-map"
ORDER = 50


def _grid(text: str) -> int | tuple[int, int]:
    parts = text.replace("x", ",").split(",")
    try:
        vals = [int(p) for p in parts]
    except ValueError:
        raise ValueError(f"--n: {text!r} is not N or NX,NY (integers)") from None
    if len(vals) not in (1, 2):
        raise ValueError(f"--n: {text!r} is not N or NX,NY")
    # checked here, before the variational integrator is compiled
    vals = [integer("--n", v, 2) for v in vals]
    return vals[0] if len(vals) == 1 else (vals[0], vals[1])


def run(args: argparse.Namespace) -> int:
    import time

    import matplotlib
    import numpy as np

    matplotlib.use("Agg")
    from andoyer.analysis.chaos.lyapunov import IndicatorRun, MapGrid, chaos_map
    from andoyer.integrate.variational import warm_up
    from andoyer.io import write_netcdf
    from andoyer.plot.chaos import plot_chaos_map
    from andoyer.plot.section import save_figure

    out, body, _, _, _, h = inputs_from_args(
        args, level=True, beside=(".png",) if args.indicator != ALL_OF_THEM
        else tuple(f"-{k}.png" for k in MAP_INDICATORS))
    assert h is not None  # a level command without a state has its level
    grid = _grid(args.n)
    source, seconds = warm_up(tol=args.tol, engine=args.engine)
    if source != "ready":  # an engine that compiles per setting (heyoka)
        print(f"variational integrator: {source} in {seconds:.2f} s")
    t0 = time.perf_counter()
    ds = chaos_map(body, h, args.M, args.section, MapGrid(grid, root=args.root),
                   IndicatorRun(args.indicator, t_end=args.t_end, tangent=args.tangent,
                                tol=args.tol),
                   engine=args.engine, chunk=args.chunk, progress=True)
    elapsed = time.perf_counter() - t0
    ds.attrs["elapsed_seconds"] = round(elapsed, 3)
    write_netcdf(ds, out)
    figures = []
    for name in chosen(args.indicator):
        png = out.with_suffix(".png") if args.indicator != ALL_OF_THEM else \
            out.with_name(f"{out.stem}-{name}.png")
        ax = plot_chaos_map(ds, indicator=name)
        fig = ax.get_figure(root=True)
        assert fig is not None
        figures += save_figure(fig, png)
    n_ok = int(ds.attrs["n_accessible"]) - int(ds.attrs["n_failed"])
    what = ", ".join(f"{v} in [{float(np.nanmin(ds[v])):.3g}, {float(np.nanmax(ds[v])):.3g}]"
                     for v in MAP_INDICATORS if v in ds)
    print(f"{n_ok} orbits on H = {h:g}, M = {args.M:g} to t = {args.t_end:g} in "
          f"{elapsed:.1f} s; {what}; max energy error {float(ds.H_error.max()):.1e}")
    print(f"wrote {out} and {', '.join(str(f) for f in figures)}")
    return 0


def register(sub: Any) -> None:
    p = sub.add_parser(NAME, help="chaos map (FLI / MEGNO) over a section's plane: NetCDF + PNG",
                       description="Fast Lyapunov indicator and/or mean MEGNO of the orbits "
                                   "started on a grid of a section's plane, on one energy "
                                   "level and area constant.")
    add_body_args(p)
    add_level_args(p, directed=False)
    p.add_argument("--n", default="128", help="grid: N (N x N) or NX,NY (default 128)")
    p.add_argument("--t-end", type=real(positive=True), default=1000.0,
                   help="integration time of every orbit (default 1000)")
    p.add_argument("--indicator", choices=MAP_CHOICES, default="fli",
                   help=f"indicator to store and draw ({ALL_OF_THEM!r}: "
                        f"{', '.join(MAP_INDICATORS)}; default fli)")
    p.add_argument("--engine", choices=tuple(ENGINES), default=None,
                   help="integrator of the variational equations, an engine with the "
                        "'tangent' capability (default taylor for the FLI alone, measured faster; "
                        "else heyoka where installed, else taylor; "
                        "scipy is a slow independent check)")
    p.add_argument("--tol", type=real(positive=True), default=1e-12,
                   help="tolerance (default 1e-12)")
    p.add_argument("--root", choices=("largest", "smallest"), default="largest",
                   help="where the level has several sheets over a point, which action "
                        "(default largest)")
    p.add_argument("--tangent", choices=("leaf", "energy"), default="leaf",
                   help="space of the initial tangent vectors (default leaf)")
    p.add_argument("--chunk", type=count(1), default=1024,
                   help="orbits per chunk: bounds memory (default 1024)")
    p.add_argument("--out", default="chaos-map.nc", help="output NetCDF (PNG beside it)")
    p.set_defaults(func=run)
