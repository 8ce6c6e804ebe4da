"""``andoyer manifolds``: invariant manifolds, separatrix splitting vs Melnikov; NetCDF + PNG."""

from __future__ import annotations

import argparse
from typing import Any

from andoyer.cli._common import add_body_args, body_from_args, count, output_folder, real

NAME = "manifolds"
ORDER = 60

DEFAULT_MU = "0.0025,0.005,0.01"


def _mu_list(text: str) -> list[float]:
    try:
        vals = sorted(float(v) for v in text.replace(",", " ").split())
    except ValueError:
        raise ValueError(f"--mu-list: {text!r} is not a list of numbers") from None
    if not vals or any(not v > 0.0 for v in vals):
        raise ValueError(f"--mu-list needs values mu > 0, got {text!r}")
    if len(set(vals)) != len(vals):
        raise ValueError(f"--mu-list has repeated values: {text!r}")
    return vals


def run(args: argparse.Namespace) -> int:
    import matplotlib

    matplotlib.use("Agg")
    import numpy as np
    import xarray as xr

    from andoyer.analysis.splitting.measure import separatrix_splitting
    from andoyer.io import write_netcdf
    from andoyer.plot.manifolds import plot_manifolds_summary
    from andoyer.plot.section import save_figure

    out = output_folder(args.out)
    body = body_from_args(args)
    if args.mu_list is None:
        mus = [args.mu] if args.mu is not None else _mu_list(DEFAULT_MU)
    else:
        mus = _mu_list(args.mu_list)
    if args.body not in ("paper", "hess"):
        raise ValueError("andoyer manifolds follows the heteroclinic lines theta1 = 0 and "
                         "theta1 = 4 phi0 of a Hess body: use --body paper or --body hess "
                         "--A .. --B .. --C .. (and --epsilon to turn its centre of mass)")
    epsilon = body.hess_epsilon
    out.mkdir(parents=True, exist_ok=True)
    common: dict[str, Any] = {"G": args.G, "psi0": args.psi0, "delta": args.delta,
                              "n_phase": args.n_phase, "tol": args.tol,
                              "long_double": args.long_double, "progress": True}
    print(f"{body.name or 'body'}: A={body.A:g}, B={body.B:g}, C={body.C:g}; level "
          f"h = c G^2/2 with G = {args.G:g}; mu = {', '.join(f'{m:g}' for m in mus)}")
    res = separatrix_splitting(body, mus, branch="theta1=4phi0", **common)
    hess = None
    if args.hess_check:
        hess = separatrix_splitting(body, [mus[-1]], branch="theta1=0", **common)["splitting"]
    files = [write_netcdf(res["splitting"], out / "splitting.nc"),
             write_netcdf(res["intersections"], out / "intersections.nc"),
             write_netcdf(res["melnikov"], out / "melnikov.nc"),
             write_netcdf(res["curve_unstable"], out / "manifold_unstable.nc"),
             write_netcdf(res["curve_stable"], out / "manifold_stable.nc")]
    orbits = xr.concat([res["orbit_leaves"].expand_dims(orbit=["leaves"]),
                        res["orbit_reaches"].expand_dims(orbit=["reaches"])], dim="orbit",
                       combine_attrs="drop_conflicts")
    orbits["rotation_sign"] = ("orbit", [res["orbit_leaves"].attrs["rotation_sign"],
                                         res["orbit_reaches"].attrs["rotation_sign"]])
    orbits["rotation_sign"].attrs.update(long_name="sign of L = G3 at the rotation", units="1")
    files.append(write_netcdf(orbits, out / "periodic_orbits.nc"))
    if hess is not None:
        files.append(write_netcdf(hess, out / "hess_branch.nc"))
    sp = res["splitting"]
    it = res["intersections"]
    fig = plot_manifolds_summary(res, hess, title=(
        f"{body.name or 'body'} (A, B, C) = ({body.A:g}, {body.B:g}, {body.C:g}): "
        f"splitting of theta1 = 4 phi0, rho = {sp.attrs['rho']:.4g}"))
    files += save_figure(fig, out / "manifolds.png")
    print(f"rho = c J2/lambda = {sp.attrs['rho']:.6g}; multipliers of the rotation orbits "
          f"{float(res['orbit_leaves'].Lambda_u[-1]):.10g}")
    print(f"{'mu':>9} {'max|dG| measured':>17} {'mu*Melnikov':>13} {'rel.err':>8} "
          f"{'angle':>11} {'lobe area':>11} {'g* - pi/2':>10}")
    for k, m in enumerate(sp.mu.values):
        g0 = it.g.values[k, 0] if it.sizes["intersection"] else np.nan
        ang = it.angle.values[k, 0] if it.sizes["intersection"] else np.nan
        lobe = it.lobe_area.values[k, 0] if it.sizes["intersection"] else np.nan
        print(f"{m:9.5g} {sp.amplitude.values[k]:17.6e} {sp.amplitude_melnikov.values[k]:13.6e}"
              f" {sp.relative_error.values[k]:8.2e} {ang:11.4e} {lobe:11.4e} "
              f"{g0 - np.pi / 2:10.1e}")
    if hess is not None and body.is_hess:
        print(f"theta1 = 0 (Hess solutions) at mu = {mus[-1]:g}: max |dG| = "
              f"{float(hess.amplitude[0]):.1e} (the manifolds coincide)")
    elif hess is not None:
        print(f"theta1 = 0 (the former Hess separatrix) at mu = {mus[-1]:g}, epsilon = "
              f"{epsilon:g}: max |dG| = {float(hess.amplitude[0]):.6e}, mu*Melnikov "
              f"{float(hess.amplitude_melnikov[0]):.6e}, rel.err "
              f"{float(hess.relative_error[0]):.2e}")
    print("wrote " + ", ".join(str(f) for f in files))
    return 0


def register(sub: Any) -> None:
    p = sub.add_parser(NAME, help="stable/unstable manifolds of the rotations about the "
                                  "middle axis, separatrix splitting vs Melnikov: NetCDF + PNG")
    add_body_args(p)
    p.add_argument("--mu-list", default=None,
                   help=f"values of mu, comma-separated (default {DEFAULT_MU}, or --mu)")
    p.add_argument("--G", type=real(positive=True), default=1.0,
                   help="energy level h = c G^2/2 of the rotation with |G| = G (default 1)")
    p.add_argument("--n-phase", type=count(1), default=16,
                   help="phases g at which the splitting is measured (even, default 16)")
    p.add_argument("--delta", type=real(positive=True), default=1e-5,
                   help="fundamental domain's distance from the periodic orbit (default 1e-5)")
    p.add_argument("--psi0", type=real(), default=0.0,
                   help="section psi = atan2(gamma1, gamma2) = psi0 of the orbits (default 0)")
    p.add_argument("--tol", type=real(positive=True), default=1e-15,
                   help="integration tolerance (default 1e-15; numba uses at least 1e-13)")
    p.add_argument("--long-double", action="store_true",
                   help="integrate in 80-bit extended precision")
    p.add_argument("--no-hess-check", dest="hess_check", action="store_false",
                   help="skip the Hess branch theta1 = 0 (shown not to split)")
    p.add_argument("--out", default="manifolds", help="output folder (default ./manifolds)")
    p.set_defaults(func=run)
