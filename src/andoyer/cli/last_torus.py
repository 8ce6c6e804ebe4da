"""``andoyer last-torus``: Greene's residues of the convergents of a noble torus between two
main chains, the critical mu at which it breaks and the overlap estimate beside it
(:func:`andoyer.analysis.resonance.residues.last_torus`); NetCDF and a table."""

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
    real,
)

NAME = "last-torus"
ORDER = 49


def _head(text: str) -> tuple[int, ...]:
    try:
        out = tuple(int(x) for x in text.split(","))
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"--head must be whole numbers separated by commas (the continued fraction's "
            f"first partial quotients, e.g. 2 or 7,2), got {text!r}") from None
    return out


def _levels(text: str) -> tuple[float, ...]:
    try:
        out = tuple(float(x) for x in text.replace(" ", ",").split(",") if x)
    except ValueError:
        out = ()
    if not out:
        raise argparse.ArgumentTypeError(
            f"--h-values must be energy levels separated by commas (e.g. 0.5,1,2), got "
            f"{text!r}")
    return out


def _curve(args: argparse.Namespace) -> int:
    """``--h-values``: the critical mu over the levels (critical_mu_curve), NetCDF + table."""
    import math

    from andoyer.analysis.resonance.residues import critical_mu_curve
    from andoyer.io import write_netcdf

    if args.h is not None:
        raise ValueError("--h-values and --energy: give one (--h-values writes the curve "
                         "mu_c(h) over its levels)")
    if args.mu_range is None:
        raise ValueError("--h-values needs --mu-range MU_LOW MU_HIGH (where mu_c is sought "
                         "on the first level; scaled by h/h0 on the others)")
    inputs = inputs_from_args(args, level=False, beside=())
    out, body = inputs.out, inputs.body
    ds = critical_mu_curve(body, args.h_values, args.M, mu_range=tuple(args.mu_range),
                           head=args.head, axis=args.axis, n_convergents=args.n_convergents,
                           tol=args.tol, engine=args.engine, progress=True)
    write_netcdf(ds, out)
    print(f"mu_c(h) of the noble torus W = [0; {ds.attrs['head']}, 1, 1, ...] between the "
          f"chains {ds.attrs['main_chains']} about axis {ds.attrs['axis']}, M = {args.M:g} "
          f"({ds.attrs['method']}):")
    print(f"  {'h':>10} {'mu_c':>12} {'error':>10}")
    for h, m, e in zip(ds.h_level.values, ds.mu_critical.values, ds.mu_critical_error.values,
                       strict=True):
        mc = f"{m:12.6g}" if math.isfinite(m) else f"{chr(45):>12}"
        print(f"  {h:10.6g} {mc} {e:10.2g}")
    print(f"wrote {out}")
    return 0


def run(args: argparse.Namespace) -> int:
    import math

    from andoyer.analysis.resonance.residues import last_torus
    from andoyer.io import write_netcdf

    if args.h_values is not None:
        return _curve(args)
    inputs = inputs_from_args(args, level=True, beside=())
    out, body, h = inputs.out, inputs.body, inputs.h
    assert h is not None
    mu_range = None if args.mu_range is None else tuple(args.mu_range)
    ds = last_torus(body, h, args.M, head=args.head, axis=args.axis,
                    n_convergents=args.n_convergents, mu_range=mu_range, tol=args.tol,
                    engine=args.engine, progress=True)
    write_netcdf(ds, out)
    print(f"the noble torus W = [0; {ds.attrs['head']}, 1, 1, ...] = "
          f"{ds.attrs['rotation_number']:.12f} between the chains {ds.attrs['main_chains']} "
          f"about axis {ds.attrs['axis']}, H = {h:.6g}, M = {args.M:g}, "
          f"{body.name or 'body'} mu = {body.mu:g}:")
    print(f"  {'p/q':>9} {'R elliptic':>12} {'R hyperbolic':>13} {'mu_c(q)':>12} {'s':>6}")
    for i in range(ds.sizes["convergent"]):
        r = ds.isel(convergent=i)
        mc = float(r.mu_critical_convergent)
        print(f"  {f'{int(r.p)}/{int(r.q)}':>9} {float(r.residue_elliptic):12.4e} "
              f"{float(r.residue_hyperbolic):13.4e} "
              f"{(f'{mc:12.6g}' if math.isfinite(mc) else f'{chr(45):>12}')} "
              f"{float(r.seconds):6.1f}")
    mu_c = float(ds.mu_critical)
    if math.isfinite(mu_c):
        print(f"mu_c = {mu_c:.6g} +- {float(ds.mu_critical_error):.2g}; overlap (first order) "
              f"mu = {float(ds.mu_overlap):.4g}; mu_c / mu_overlap = {float(ds.mu_ratio):.3f}")
    else:
        print(f"mu_c not found ({'no --mu-range' if mu_range is None else 'not in --mu-range'}"
              f"); overlap (first order) mu = {float(ds.mu_overlap):.4g}")
    print(f"wrote {out}")
    return 0


def register(sub: Any) -> None:
    p = sub.add_parser(NAME, help="Greene's residues and the critical mu of a noble torus: "
                                  "NetCDF + table",
                       description="The noble torus W = [0; HEAD, 1, 1, ...] between the "
                                   "chains n:1 and (n+1):1 of one regime: the elliptic and "
                                   "hyperbolic symmetric periodic orbits of its convergents "
                                   "p/q, found on the symmetry lines L = 0 of g = pi/2, "
                                   "3 pi/2, their residues (6 - Tr Phi(T))/4, the mu at "
                                   "which the elliptic residues reach 1/4 (Greene) and the "
                                   "overlap mu of the two chains' first-order widths "
                                   "(andoyer.analysis.resonance.residues).")
    add_body_args(p)
    add_energy_args(p)
    add_term(p, "head", type=_head, default=(2,), metavar="A1[,A2,...]",
             help="partial quotients of W before the tail of ones: N for the golden-mean "
                  "torus between the chains N:1 and (N+1):1 (default 2)")
    add_term(p, "axis", type=count(1, 2), default=1,
             help="the regime: tori about body axis 1 or 2 (default 1)")
    add_term(p, "n_convergents", type=count(1, 16), default=6,
             help="convergents beyond the two chains (default 6)")
    add_term(p, "mu_range", type=real(), nargs=2, default=None,
             metavar=("MU_LOW", "MU_HIGH"),
             help="where the critical mu of each convergent is sought (default: none, the "
                  "residues at --mu only)")
    add_term(p, "tol", type=real(), default=1e-13, help="integration tolerance (default "
                                                        "1e-13)")
    add_term(p, "h_values", type=_levels, default=None, metavar="H1,H2,...",
             help="instead of --energy: the curve mu_c(h) over these levels (needs "
                  "--mu-range, for the first level; one computation scaled by h at --M 0, "
                  "one per level otherwise), for andoyer atlas --last-torus")
    add_engine_args(p, tolerances=False)
    p.add_argument("--out", default="last-torus.nc", help="output NetCDF")
    p.set_defaults(func=run, section="g=0")
