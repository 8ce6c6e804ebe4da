"""Items of the unperturbed system and the formulas: Fig. 1, Fig. 2 and all fixed points,
the heteroclinic orbits in closed form, every printed formula against the derivation.

Each builder computes with :mod:`andoyer.analysis`, draws with :mod:`andoyer.plot` and
returns a :class:`~andoyer.report.base.Result`; its prose is
``templates/items/<key>.html.j2``.
"""

from __future__ import annotations

from dataclasses import asdict
from typing import Any

from andoyer.report.base import Context, Result, Table

__all__ = ["fig1", "fig2", "heteroclinic", "paper_check"]


def paper_check(ctx: Context) -> Result:
    """Every formula printed in the paper, evaluated against the derivation.

    Parameters
    ----------
    ctx : Context
        Output folder, body, engine, quick.
    """
    from andoyer.analysis.paper.check import paper_check as check
    from andoyer.io.tables import format_table

    rows = check(n=50 if ctx.quick else 200)
    files = [ctx.text("paper-check.txt", format_table(rows) + "\n"),
             ctx.json("paper-check.json", [asdict(r) for r in rows])]
    counts = {v: sum(r.verdict == v for r in rows) for v in ("holds", "misprint", "omission")}
    table = Table(["place", "verdict", "formula", "what is wrong / missing", "corrected form"],
                  [[r.label, r.verdict, r.name, r.nature, r.corrected] for r in rows])
    return Result(files, {k: float(v) for k, v in counts.items()},
                  {"n_formulas": len(rows), **counts}, table)


def fig1(ctx: Context) -> Result:
    """Fig. 1: the unperturbed portrait in (l, L).

    Parameters
    ----------
    ctx : Context
        Output folder, body, engine, quick.
    """
    from andoyer.analysis.unperturbed.portraits import portrait_andoyer
    from andoyer.plot.portraits import plot_fig1

    ds = portrait_andoyer(ctx.body, 1.0)
    files = ctx.figure(plot_fig1(ds), "fig1")
    files.append(ctx.data(ds, "fig1-portrait"))
    return Result(files)


def fig2(ctx: Context) -> Result:
    """Fig. 2: both unperturbed portraits and every fixed point, with their tables.

    Parameters
    ----------
    ctx : Context
        Output folder, body, engine, quick.
    """
    from andoyer.analysis.unperturbed.equilibria import euler_poisson_equilibria
    from andoyer.analysis.unperturbed.fixed_points import andoyer_fixed_points, hess_fixed_points
    from andoyer.analysis.unperturbed.portraits import portrait_andoyer, portrait_hess
    from andoyer.analysis.unperturbed.separatrix import FIG2_CAPTION
    from andoyer.io.tables import format_table
    from andoyer.plot.portraits import plot_fig2

    ds_a = portrait_andoyer(ctx.body, 1.0)
    ds_h = portrait_hess(ctx.body, 1.0)
    files = ctx.figure(plot_fig2(ds_a, ds_h), "fig2")
    files.append(ctx.data(ds_h, "fig2b-portrait"))
    fp_a = andoyer_fixed_points(ctx.body, 1.0)
    fp_h = hess_fixed_points(ctx.body, 1.0)
    eq = euler_poisson_equilibria(ctx.body)
    files.append(ctx.data(fp_h.to_dataset(), "fixed-points-hess"))
    files.append(ctx.data(fp_a.to_dataset(), "fixed-points-andoyer"))
    tables = "\n\n".join(format_table(x) for x in (fp_a, fp_h, eq))
    files.append(ctx.text("fixed-points.txt", tables + "\n"))
    return Result(files, values={"caption": FIG2_CAPTION}, pre=tables)


def heteroclinic(ctx: Context) -> Result:
    """The heteroclinic orbits of the free top in closed form, checked by integration.

    Parameters
    ----------
    ctx : Context
        Output folder, body, engine, quick.
    """
    import numpy as np
    import xarray as xr

    from andoyer.analysis.unperturbed.separatrix import BRANCHES, heteroclinic, heteroclinic_rate
    from andoyer.integrate.api import propagate

    body0 = ctx.body.with_mu(0.0)
    lam = heteroclinic_rate(ctx.body, 1.0)
    t = np.linspace(-60.0, 60.0, 241)
    tol = 1e-13
    rows: list[list[Any]] = []
    errs: list[float] = []
    sets: list[xr.Dataset] = []
    engine = ctx.engine_name()
    for branch in BRANCHES:
        for sign in (+1, -1):
            ds = heteroclinic(ctx.body, 1.0, t, branch=branch, sign=sign)
            run = propagate(body0, ds.y.values[0], t - t[0], engine=engine, rtol=tol,
                            atol=tol, progress=False)
            engine = str(run.attrs["engine"])  # what ran, as the run records it
            ys = np.stack([run[v].values[0] for v in
                           ("G1", "G2", "G3", "gamma1", "gamma2", "gamma3")], -1)
            err = float(np.max(np.abs(ys - ds.y.values)))
            errs.append(err)
            rows.append([branch, sign, ds.attrs["J1_direction"], f"{err:.1e}"])
            sets.append(ds.expand_dims(orbit=[len(sets)]))
    files = [ctx.data(xr.concat(sets, "orbit", combine_attrs="drop_conflicts"),
                      "heteroclinic")]
    return Result(files, {"lambda": lam, "max_error": max(errs)},
                  {"lam": lam, "max_error": max(errs), "engine": engine, "tol": tol},
                  Table(["branch", "sign", "J1", "max |closed form − integration|"], rows))
