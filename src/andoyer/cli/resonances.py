"""``andoyer resonances``: the p/q island chains predicted at first order in mu (their
centres, half-widths, periodic orbits and stability); NetCDF + PNG, the chains drawn over
a computed section with ``--n-orbits``; with ``--order N``, the normal forms of degree N
near the centres (Birkhoff coefficients, each chain's resonant normal form) beside it."""

from __future__ import annotations

import argparse
from typing import Any

from andoyer.cli._common import (
    add_body_args,
    add_energy_args,
    add_engine_args,
    add_term,
    count,
    inputs_from_args,
)

NAME = "resonances"
ORDER = 48


#: The ending of the normal forms' NetCDF beside ``--out`` (``--order``).
NORMAL_FORM = "-normal-form.nc"
TWIST = "-twist.nc"
#: The ending of the chains to order N in mu beside ``--out`` (``--order-mu``).
ORDER_MU = "-order-mu.nc"


def _orders_in_mu(body: Any, h: float, M: float, pred: Any, order_mu: int) -> Any:
    """Each chain of ``pred`` (sign +1, width from an order <= ``order_mu``) predicted to
    ``order_mu`` by :func:`~andoyer.analysis.resonance.island_prediction` ((S1)-(S4)), on
    dims ``chain``, ``order_mu``; a chain the normal form cannot take (a torus too near the
    separatrix for its spectrum) is left out and named in ``attrs['skipped']``."""
    import numpy as np
    import xarray as xr

    from andoyer.analysis.resonance import island_prediction

    parts, labels, axes, skipped = [], [], [], []
    for i in range(pred.sizes["resonance"]):
        r = pred.isel(resonance=i)
        if int(r.sign) != 1 or int(r.p) > order_mu:
            continue
        label = str(r.label.values)
        try:
            parts.append(island_prediction(body, h, M, label, order_mu=order_mu,
                                           axis=int(r.axis)))
        except ValueError:
            skipped.append(f"{label} (axis {int(r.axis)})")
            continue
        labels.append(label)
        axes.append(int(r.axis))
    if not parts:
        return None
    out = xr.concat(parts, dim="chain", combine_attrs="drop_conflicts")
    out = out.assign_coords(chain=np.arange(len(parts)), label=("chain", np.array(labels)),
                            axis=("chain", np.array(axes, dtype=np.int64)))
    out.attrs["skipped"] = ", ".join(skipped)
    out.attrs["order_mu"] = order_mu
    return out


def _normal_forms(body: Any, h: float, M: float, pred: Any, order: int) -> Any:
    """The normal forms of degree ``order`` near the two centres of the level, as one
    dataset: per centre (dims ``centre``, ``power``) the Birkhoff coefficients ``c_k`` at
    the permanent rotation of energy ``h`` (:func:`~andoyer.analysis.resonance.
    birkhoff_normal_form`, (B4)); per chain of ``pred`` (dim ``resonance``) its resonant
    normal form (:func:`~andoyer.analysis.resonance.resonant_normal_form`, (N1)-(N5)) beside
    the torus route's half-width (``torus_half_width``, (R6)); NaN for the chains whose
    ``W = p/q`` is not reached near a centre (half-way to the separatrix)."""
    import math

    import numpy as np
    import xarray as xr

    from andoyer.analysis.resonance import birkhoff_normal_form, resonant_normal_form
    from andoyer.analysis.resonance.birkhoff import CENTRES
    from andoyer.integrate.results import provenance

    names = ("action", "G_action", "half_width_action", "half_width",
             "libration_frequency", "stable_angle", "dalembert_coefficient")
    cols: dict[str, list[float]] = {k: [] for k in names}
    meta: dict[str, Any] = {}
    for i in range(pred.sizes["resonance"]):
        r = pred.isel(resonance=i)
        try:
            nf = resonant_normal_form(body, h, M, f"{int(r.q)}:{int(r.p)}", axis=int(r.axis),
                                      sign=int(r.sign), order=order)
        except ValueError:   # W = p/q not reached near that centre (order checked before)
            nf = None
        for k in names:
            cols[k].append(float(nf[k]) if nf is not None else math.nan)
            if nf is not None:
                meta[k] = dict(nf[k].attrs)
    out = xr.Dataset({f"nf_{k}": ("resonance", np.array(v)) for k, v in cols.items()},
                     coords={"resonance": pred.resonance.values})
    for k in names:
        out[f"nf_{k}"].attrs.update(meta.get(k, {}))
    for k in ("p", "q", "axis", "sign", "G_action", "half_width"):
        out[f"torus_{k}" if k in ("G_action", "half_width") else k] = pred[k]
    centres = []
    for axis in (1, 2):
        G = math.sqrt(2.0 * h / (body.a, body.b)[axis - 1])   # H0 = h at the rotation
        lstar = min(k for k, a in CENTRES.items() if a == axis)   # pi/2 (x), 0 (y)
        nf = birkhoff_normal_form(body, G, order=order, lstar=lstar)
        centres.append(nf[["coefficient", "omega0", "H_star"]].assign(G_centre=G))
    birk = xr.concat(centres, dim="centre").assign_coords(centre=[1, 2])
    birk["G_centre"].attrs.update(symbol="G", long_name="|G| of the permanent rotation on "
                                  "the level", units="1", equation="(9)")
    birk["centre"].attrs.update(long_name="body axis of the centre", units="1")
    for var in birk.data_vars:
        out[var] = birk[var]
    out.attrs.update(provenance(body, h=h, M=M, order=order,
                                derivation="andoyer.analysis.resonance.birkhoff (B1)-(B4), "
                                           "resonant_normal_form (N1)-(N5)"))
    return out


def _twists(body: Any, h: float, M: float, g_star: float, degree: int, engine: Any
            ) -> tuple[Any, list[str]]:
    """The Birkhoff normal form of the section map at the level's two centres moved by
    ``mu`` (the rotations about x and y: seeds ``(pi/2, 0)``, ``(0, 0)``), on dim
    ``centre``; a centre the normal form cannot take is named in the second value."""
    import math

    import xarray as xr

    from andoyer.analysis.resonance import periodic_orbit_normal_form

    parts, skipped = [], []
    for axis, seed in ((1, (math.pi / 2, 0.0)), (2, (0.0, 0.0))):
        try:
            nf = periodic_orbit_normal_form(body, h, M, seed, degree=degree, g_star=g_star,
                                            engine=engine)
        except ValueError as exc:
            skipped.append(f"axis {axis}: {exc}")
            continue
        keep = ["fixed_l", "fixed_L", "fixed_G", "rotation", "residue", "twist",
                "small_divisor", "radial_defect"]
        parts.append(nf[keep].expand_dims(centre=[axis]))
    if not parts:
        return None, skipped
    out = xr.concat(parts, dim="centre")
    out["centre"].attrs.update(long_name="body axis of the free top's centre", units="1")
    out.attrs.update({k: v for k, v in parts[0].attrs.items()
                      if not k.startswith(("eigenvector", "dual", "conjugacy", "normal_form"))})
    out.attrs["skipped"] = "; ".join(skipped)
    return out, skipped


def run(args: argparse.Namespace) -> int:
    import math

    import matplotlib

    matplotlib.use("Agg")
    from andoyer.analysis.resonance import resonance_widths
    from andoyer.io import write_netcdf
    from andoyer.plot.resonance import plot_resonances
    from andoyer.plot.section import plot_section, save_figure

    if args.order and (args.order % 2 or args.order < 4):
        raise ValueError(f"--order must be 0 (no normal form) or even, 4 to 16 (the normal "
                         f"form has whole powers of the action), got {args.order}")
    if args.degree and args.degree < 3:
        raise ValueError(f"--degree must be 0 (none) or 3 to 15, got {args.degree}")
    if args.degree and not args.section.startswith("g="):
        raise ValueError(f"--degree needs a section g = g* (the plane (l, L)), got "
                         f"--section {args.section!r}")
    beside = (".png",) + ((NORMAL_FORM,) if args.order else ()) \
        + ((ORDER_MU,) if args.order_mu else ()) + ((TWIST,) if args.degree else ())
    inputs = inputs_from_args(args, level=True, beside=beside)
    out, body, h = inputs.out, inputs.body, inputs.h
    assert h is not None
    if args.order_mu and not body.mu > 0.0:
        raise ValueError("--order-mu needs mu > 0 (at mu = 0 there is no island)")
    ds = resonance_widths(body, h, args.M, args.section, max_order=args.max_order)
    write_netcdf(ds, out)
    written = [out]
    nfs = None
    if args.order:
        nfs = _normal_forms(body, h, args.M, ds, args.order)
        written.append(out.with_name(out.stem + NORMAL_FORM))
        write_netcdf(nfs, written[-1])
    orders = None
    if args.order_mu:
        orders = _orders_in_mu(body, h, args.M, ds, args.order_mu)
        if orders is not None:
            written.append(out.with_name(out.stem + ORDER_MU))
            write_netcdf(orders, written[-1])
    twists: Any = None
    skipped: list[str] = []
    if args.degree:
        twists, skipped = _twists(body, h, args.M, inputs.section.value, args.degree,
                                  args.engine)
        if twists is not None:
            written.append(out.with_name(out.stem + TWIST))
            write_netcdf(twists, written[-1])
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
    if nfs is not None:
        _print_normal_forms(nfs)
    if args.order_mu:
        _print_orders(orders, args.order_mu)
    if args.degree:
        _print_twists(twists, skipped, args.degree)
    print(f"wrote {', '.join(str(p) for p in written)} and {png}")
    return 0


def _print_normal_forms(nfs: Any) -> None:
    import math

    order = int(nfs.attrs["order"])
    print(f"normal forms of degree {order} about the centres (Birkhoff, mu = 0):")
    for c in nfs.centre.values:
        b = nfs.sel(centre=c)
        coef = ", ".join(f"{float(v):.6g}" for v in b.coefficient.values[1:3])
        print(f"  axis {int(c)}: |G| = {float(b.G_centre):.8f}, omega0 = "
              f"{abs(float(b.omega0)):.8g}, c_2, c_3 = {coef}")
    near = [i for i in range(nfs.sizes["resonance"])
            if math.isfinite(float(nfs.nf_G_action[i]))]
    if not near:
        print("  no chain near a centre (W = p/q reached within half-way to the separatrix)")
        return
    print("  chains near a centre, resonant normal form (N1)-(N5) vs the torus (R6):")
    print(f"  {'q:p':>6} {'axis':>4} {'sign':>4} {'I*':>10} {'G* (NF)':>12} "
          f"{'half-width NF':>13} {'torus':>13} {'rel. diff':>9}")
    for i in near:
        r = nfs.isel(resonance=i)
        nf, tor = float(r.nf_half_width), float(r.torus_half_width)
        text = (f"{nf:13.4e} {tor:13.4e} {nf / tor - 1:+9.1e}" if math.isfinite(nf)
                else f"{'(2nd order)':>13} {'':>13} {'':>9}")
        print(f"  {f'{int(r.q)}:{int(r.p)}':>6} {int(r.axis):>4} {int(r.sign):>4} "
              f"{float(r.nf_action):10.4e} {float(r.nf_G_action):12.8f} {text}")


def _print_twists(twists: Any, skipped: list[str], degree: int) -> None:
    print(f"normal forms of the section map at the centres moved by mu (jet transport, "
          f"degree {degree}; rho(I) = omega0 + tau_1 I + ...):")
    if twists is not None:
        for c in twists.centre.values:
            t = twists.sel(centre=c)
            taus = ", ".join(f"{float(v):.6g}" for v in t.twist.values[1:])
            print(f"  axis {int(c)}: (l, L) = ({float(t.fixed_l):.8f}, {float(t.fixed_L):+.8f}),"
                  f" omega0 = {float(t.rotation):.8f}, residue = {float(t.residue):.6f}, "
                  f"tau = {taus}")
    for text in skipped:
        print(f"  not taken: {text}")


def _print_orders(orders: Any, order_mu: int) -> None:
    import math

    print(f"chains to order {order_mu} in mu (Lie-Deprit normal form, (S1)-(S4); g = g* "
          "seed line through the first-order stable point):")
    if orders is None:
        print("  none (no chain the normal form takes)")
        return
    print(f"  {'q:p':>6} {'axis':>4} {'order':>5} {'stable s':>12} {'+- next':>9} "
          f"{'half-width':>11} {'Omega':>10}")
    for c in orders.chain.values:
        r = orders.sel(chain=c)
        for n in r.order_mu.values:
            v = r.sel(order_mu=n)
            w = float(v.half_width)
            text = f"{w:11.4e}" if math.isfinite(w) else f"{'-':>11}"
            om = float(v.libration_frequency)
            otext = f"{om:10.3e}" if math.isfinite(om) else f"{'-':>10}"
            print(f"  {str(r.label.values):>6} {int(r.axis):>4} {int(n):>5} "
                  f"{float(v.stable_s):+12.4e} {float(v.stable_s_error):9.1e} {text} {otext}")
    if orders.attrs.get("skipped"):
        print(f"  not taken: {orders.attrs['skipped']}")


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
    add_energy_args(p)
    add_term(p, "section", default="g=0",
             help="'g=VALUE' (plane l, L) or 'theta2=VALUE' (plane theta1, J1); append "
                  "':-' for the decreasing direction (default g=0)")
    add_term(p, "max_order", type=count(2, 100), default=12,
             help="largest order p + q of the chains (default 12)")
    add_term(p, "order", type=count(0, 16), default=0,
             help="degree N of the normal forms near the centres (even, 4 to 16), written "
                  f"beside --out as *{NORMAL_FORM}; default 0: none")
    add_term(p, "order_mu", type=count(0, 3), default=0,
             help="order N (1 to 3) in mu of the Lie-Deprit normal form of each chain "
                  "(stable point on a seed line with the size of the next order, "
                  f"half-width, libration frequency), written beside --out as *{ORDER_MU}; "
                  "default 0: none")
    add_term(p, "degree", type=count(0, 15), default=0,
             help="degree N (3 to 15) of the Birkhoff normal form of the section map at the "
                  "level's two centres moved by mu (rotation number and twist coefficients "
                  f"in the action), written beside --out as *{TWIST}; default 0: none")
    add_term(p, "n_orbits", type=count(0), default=0,
             help="orbits of a section drawn under the chains (default 0: none)")
    add_term(p, "n_crossings", type=count(1), default=300,
             help="crossings per orbit of that section (default 300)")
    add_engine_args(p)
    p.add_argument("--out", default="resonances.nc", help="output NetCDF (PNG beside it)")
    p.set_defaults(func=run)
