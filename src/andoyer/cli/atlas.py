"""``andoyer atlas``: a grid of sections or chaos maps drawn from a scan store."""

from __future__ import annotations

import argparse
from typing import Any

from andoyer.cli._common import real

NAME = "atlas"
ORDER = 65


def _read_curve(path: Any) -> Any:
    """The mu_c(h) file of ``andoyer last-torus --h-values``, checked (one line naming the
    file where it is missing, damaged or another file)."""
    import xarray as xr

    from andoyer.plot.atlas import check_critical_mu

    what = f"--last-torus {str(path)!r}"
    if not path.is_file():
        raise ValueError(f"{what}: no such file")
    try:
        curve = xr.load_dataset(path)
    except Exception as exc:   # netCDF4/h5netcdf/scipy each raise their own on damage
        raise ValueError(f"{what}: not a readable NetCDF file ({type(exc).__name__}); give "
                         "the file written by andoyer last-torus --h-values") from None
    if curve.attrs.get("kind") != "critical_mu_curve":
        raise ValueError(f"{what}: not a mu_c(h) curve (no kind = critical_mu_curve); give "
                         "the file written by andoyer last-torus --h-values")
    try:
        return check_critical_mu(curve)
    except ValueError as exc:
        raise ValueError(f"{what}: {exc}") from None


def run(args: argparse.Namespace) -> int:
    from pathlib import Path

    import matplotlib

    matplotlib.use("Agg")
    from andoyer.cli._common import distinct_outputs, floats, output_file
    from andoyer.plot.atlas import plot_atlas, plot_border
    from andoyer.plot.section import save_figure
    from andoyer.scan.store import open_store

    png = output_file(args.out, ".png", beside=(".pdf",) if args.pdf else ())
    store = Path(args.store)
    curve_file = Path(args.last_torus) if args.last_torus is not None else None
    distinct_outputs([png, png.with_suffix(".pdf")],
                     [store] + ([curve_file] if curve_file is not None else []))
    if not (store / "zarr.json").is_file() and not (store / ".zgroup").is_file():
        raise ValueError(f"{store} is not a Zarr store; give the store written by "
                         "andoyer scan")
    ds = open_store(store)  # every point marked done checked: missing or damaged refused
    select = {}
    for item in args.select or []:
        name, sep, value = item.partition("=")
        if not sep:
            raise ValueError(f"--select {item!r}: write NAME=VALUE, e.g. M_level=0")
        select[name.strip()] = floats(value, 1, f"--select {name}")[0]
    border = ds.attrs.get("scan_task") == "chaos_border" and not args.maps
    curve = None
    if curve_file is not None:
        if not border:
            raise ValueError("--last-torus draws mu_c(h) on the border of chaos: give a "
                             "chaos_border store, without --maps")
        curve = _read_curve(curve_file)
    if border:
        fig = plot_border(ds, x=args.cols, y=args.rows, select=select, width=args.width,
                          critical_mu=curve)
    else:
        fig = plot_atlas(ds, rows=args.rows, cols=args.cols, select=select, width=args.width)
    out = save_figure(fig, png, pdf=args.pdf)
    done = int(ds["done"].sum())
    print(f"wrote {', '.join(map(str, out))} ({done} of {ds['done'].size} points done)")
    return 0


def register(sub: Any) -> None:
    p = sub.add_parser(NAME, help="grid of sections or chaos maps from a scan store (PNG)")
    p.add_argument("store", help="Zarr store written by andoyer scan")
    p.add_argument("--out", default="atlas.png", help="output PNG (default atlas.png)")
    p.add_argument("--pdf", action="store_true", help="also write a PDF beside the PNG")
    p.add_argument("--rows", default=None,
                   help="swept dim along the rows (mu, epsilon, h_level, M_level, A, B, C; "
                        "default: the first swept; for the border of chaos: mu)")
    p.add_argument("--cols", default=None,
                   help="swept dim along the columns (default: the second swept; for the "
                        "border of chaos: epsilon)")
    p.add_argument("--select", action="append", metavar="NAME=VALUE",
                   help="value of another swept dim (nearest; default: its first value)")
    p.add_argument("--maps", action="store_true",
                   help="for a chaos_border scan: draw its MEGNO maps instead of the "
                        "border of chaos (chaotic fraction and layer width)")
    p.add_argument("--width", type=real(positive=True), default=7.0,
                   help="figure width, inches")
    p.add_argument("--last-torus", default=None, metavar="FILE.nc",
                   help="draw the critical mu of the last torus, mu_c(h), on the border of "
                        "chaos (the file of andoyer last-torus --h-values; the panels must "
                        "be over h_level and mu)")
    p.set_defaults(func=run)
