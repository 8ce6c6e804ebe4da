"""Item beyond the paper: where the last torus breaks -- Greene's residues of a noble
torus's convergents, the critical mu, and the overlap estimate beside it.

The builder computes with :func:`andoyer.analysis.resonance.last_torus`, draws with
:func:`andoyer.plot.resonance.plot_residues` and returns a
:class:`~andoyer.report.base.Result`; its prose is ``templates/items/last-torus.html.j2``.
"""

from __future__ import annotations

from collections.abc import Callable
from functools import partial
from typing import Any

from andoyer.body import RigidBody
from andoyer.report.base import Context, Result, Table, concurrently

__all__ = ["last_torus"]

#: The body of the critical torus: strong low-order chains (resonant Fourier coefficients
#: ~ 1e-2) on h = 1, M = 0.
BODY = RigidBody.hess(3.0, 1.0, 2.0, mu=1e-3, name="hess(3, 1, 2)")


def last_torus(ctx: Context) -> Result:
    """The golden torus between the 2:1 and 3:1 chains of Hess(3, 1, 2): residues, mu_c(q),
    the overlap mu; the paper's body: the golden torus between its main chains 7:1, 8:1.

    Parameters
    ----------
    ctx : Context
        Output folder, body, engine, quick.
    """
    import math
    import time

    from andoyer.analysis.resonance import last_torus as greene
    from andoyer.integrate.engines.base import Capability
    from andoyer.integrate.fill import default_h
    from andoyer.plot.resonance import convergent_ticks, plot_residues
    from andoyer.plot.style import new_figure, paper_style

    # the residues' searches are one orbit's g sections at a time: angle sections
    engine = ctx.engine_name(Capability.TANGENT_CROSSINGS, workload="angle_section")
    n = 2 if ctx.quick else 7

    def critical() -> tuple[Any, float]:
        t0 = time.perf_counter()
        crit = greene(BODY, 1.0, head=(2,), axis=1, n_convergents=n, mu_range=(1e-3, 0.1),
                      engine=engine, progress=False)
        return crit, time.perf_counter() - t0

    # The paper body's tori do not depend on the critical mu: they share the cores with it.
    body = ctx.body
    h = default_h(body)
    tasks: list[Callable[[], Any]] = [critical]
    if not ctx.quick:
        tasks += [partial(greene, body, h, head=(7,), axis=1, n_convergents=4, engine=engine,
                          progress=False),
                  # near the separatrix the chains crowd: the golden torus between 30:1, 31:1
                  partial(greene, body, h, head=(30,), axis=1, n_convergents=5,
                          mu_range=(1e-3, 0.03), engine=engine, progress=False)]
    (crit, seconds), *paper_tori = concurrently(tasks)
    mu_c = float(crit.mu_critical)
    # the residues' trend in q on both sides of mu_c (Greene: to 0 below, growing above)
    factors = (0.5, 2.0) if math.isfinite(mu_c) else ()
    sides = dict(zip(factors, concurrently([
        partial(greene, BODY.with_mu(factor * mu_c), 1.0, head=(2,), axis=1, n_convergents=n,
                engine=engine, progress=False) for factor in factors]), strict=True))
    with paper_style():
        fig = new_figure(1, 2, width=9.0, aspect=0.85)
        left, right = fig.axes
        plot_residues([crit, *sides.values()], ax=left)
        left.set_title("elliptic residues of the convergents $p/q$", fontsize=8)
        good = crit.where(crit.mu_critical_convergent.notnull(), drop=True)
        right.plot(good.q.values, good.mu_critical_convergent.values, "o-", color="C3",
                   ms=3.5)
        right.axhline(float(crit.mu_overlap), color="0.4", ls="--",
                      label=f"overlap estimate $\\mu = {float(crit.mu_overlap):.4f}$")
        convergent_ticks(right, crit.q.values)
        right.set_xlabel("period $q$ of the convergent $p/q$")
        right.set_ylabel(r"$\mu_c(q)$: elliptic residue $R = 1/4$")
        # one legend under both panels: beside each it would narrow them
        legend = left.get_legend()
        if legend is not None:
            legend.remove()
        handles, names = zip(*(pair for ax in (left, right)
                               for pair in zip(*ax.get_legend_handles_labels(),
                                               strict=True)), strict=True)
        fig.legend(handles, names, loc="outside lower center", ncols=len(names),
                   fontsize=7.5, frameon=False)
        right.set_title(r"the critical $\mu$ of each convergent", fontsize=8)
        # the body's own mu is none of the figure's: its moments only
        fig.suptitle(f"Hess body $(A, B, C) = ({BODY.A:g}, {BODY.B:g}, {BODY.C:g})$"
                     r": the golden torus $W = [0; 2, 1, 1, \dots]$ between the 2:1 and "
                     "3:1 chains about axis 1, $H = 1$, $M = 0$", fontsize=9)
    files = ctx.figure(fig, "last-torus")
    files.append(ctx.data(crit, "last-torus"))
    rows = []
    for i in range(crit.sizes["convergent"]):
        r = crit.isel(convergent=i)
        rows.append([BODY.name, f"{int(r.p)}/{int(r.q)}", f"{float(r.residue_elliptic):.4e}",
                     f"{float(r.residue_hyperbolic):.4e}",
                     f"{float(r.mu_critical_convergent):.6g}",
                     f"{float(r.residue_hyperbolic_critical):+.4f}", f"{float(r.seconds):.1f}"])
    numbers = {"mu_critical": mu_c, "mu_critical_error": float(crit.mu_critical_error),
               "mu_overlap": float(crit.mu_overlap), "mu_ratio": float(crit.mu_ratio),
               "seconds": seconds}
    trend = {k: [float(x) for x in v.residue_elliptic.values] for k, v in sides.items()}
    paper: dict[str, Any] | None = None
    if not ctx.quick:
        ds, sep = paper_tori
        ds_rows = [(int(p), int(q), float(e), float(res)) for p, q, e, res in zip(
            ds.p.values, ds.q.values, ds.residue_elliptic.values,
            ds.residue_resolution_elliptic.values, strict=True)]
        paper = {"h": h, "mu": body.mu, "rows": ds_rows, "mu_overlap": float(ds.mu_overlap),
                 "sep_mu_c": float(sep.mu_critical), "sep_err": float(sep.mu_critical_error),
                 "sep_overlap": float(sep.mu_overlap), "sep_ratio": float(sep.mu_ratio),
                 "sep_residues": [float(x) for x in sep.residue_elliptic.values],
                 "sep_q": [int(x) for x in sep.q.values]}
        for p, q, e, _res in ds_rows:
            rows.append(["paper (7:1, 8:1)", f"{p}/{q}", f"{e:.4e}", "-", "-", "-", "-"])
        for i in range(sep.sizes["convergent"]):
            r = sep.isel(convergent=i)
            rows.append(["paper (30:1, 31:1)", f"{int(r.p)}/{int(r.q)}",
                         f"{float(r.residue_elliptic):.4e}",
                         f"{float(r.residue_hyperbolic):.4e}",
                         f"{float(r.mu_critical_convergent):.6g}",
                         f"{float(r.residue_hyperbolic_critical):+.4f}",
                         f"{float(r.seconds):.1f}"])
        numbers["paper_mu_overlap"] = paper["mu_overlap"]
        numbers["paper_separatrix_mu_critical"] = paper["sep_mu_c"]
        numbers["paper_separatrix_mu_overlap"] = paper["sep_overlap"]
    return Result(
        files, numbers,
        {"engine": engine, "mu_c": mu_c, "err": float(crit.mu_critical_error),
         "mu_overlap": float(crit.mu_overlap), "ratio": float(crit.mu_ratio),
         "s": float(crit.chirikov_parameter), "qmax": int(crit.q.values[-1]),
         "convergence": float(crit.convergence_ratio), "trend": trend, "paper": paper},
        Table(["body", "p/q", "R elliptic (at the body's mu)", "R hyperbolic",
               "mu_c(q): R elliptic = 1/4", "R hyperbolic at mu_c(q)", "seconds"], rows))
