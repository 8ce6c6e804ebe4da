"""Items of the perturbed body, beyond the paper: the splitting of the separatrices and the
Melnikov function, chaos maps (FLI), and the border of chaos near the Hess case.

Each builder computes with :mod:`andoyer.analysis`, draws with :mod:`andoyer.plot` and
returns a :class:`~andoyer.report.base.Result`; its prose is
``templates/items/<key>.html.j2``.
"""

from __future__ import annotations

from andoyer.body import RigidBody
from andoyer.report.base import Context, Result, Table

__all__ = ["manifolds", "chaos", "border"]

def manifolds(ctx: Context) -> Result:
    """Hyperbolic rotations, their manifolds, the splitting against the Melnikov function.

    Parameters
    ----------
    ctx : Context
        Output folder, body, engine, quick.
    """
    import numpy as np

    from andoyer.analysis.splitting.measure import separatrix_splitting
    from andoyer.integrate.engines.base import Capability
    from andoyer.plot.manifolds import plot_manifolds_summary

    mus = [0.0025, 0.005, 0.01] if not ctx.quick else [0.005, 0.01]
    body = ctx.body
    engine = ctx.engine_name(Capability.TANGENT_CROSSINGS)  # the flow to the section
    res = separatrix_splitting(body, mus, n_phase=8 if ctx.quick else 16, progress=False,
                               branch="theta1=4phi0", engine=engine)
    hess = separatrix_splitting(body, [mus[-1]], branch="theta1=0", n_phase=8,
                                progress=False, engine=engine)["splitting"]
    files = ctx.figure(plot_manifolds_summary(res, hess), "manifolds")
    files.append(ctx.data(res["splitting"], "splitting"))
    files.append(ctx.data(res["melnikov"], "melnikov"))
    sp = res["splitting"]
    meas = sp["amplitude"].values
    pred = sp["amplitude_melnikov"].values
    hess_max = float(np.nanmax(np.abs(hess["Delta_G"].values)))
    rows = [[f"{m:g}", f"{a:.4e}", f"{b:.4e}", f"{e:.3f}"]
            for m, a, b, e in zip(mus, meas, pred, sp["relative_error"].values, strict=True)]
    return Result(
        files,
        {"hess_max_splitting": hess_max,
         **{f"splitting_mu_{m:g}": float(a) for m, a in zip(mus, meas, strict=True)}},
        {"rho": body.c / (2 * body.sigma), "hess_max": hess_max, "mu_max": mus[-1],
         "engine": engine},
        Table(["mu", "max |Delta G| measured", "mu x Melnikov", "relative difference"], rows))


def chaos(ctx: Context) -> Result:
    """FLI maps of the section theta2 = 0: the paper's body and a Hess body with chaos.

    Parameters
    ----------
    ctx : Context
        Output folder, body, engine, quick.
    """
    import numpy as np

    from andoyer.analysis.chaos.lyapunov import IndicatorRun, chaos_map
    from andoyer.analysis.unperturbed.separatrix import separatrix_energy
    from andoyer.plot.chaos import plot_chaos_map
    from andoyer.plot.style import new_figure, paper_style

    body = ctx.body
    other = RigidBody.hess(3.0, 1.0, 2.0, mu=1.0)
    maps = [
        chaos_map(body, separatrix_energy(body), 0.0, "theta2=0",
                  (64, 16) if ctx.quick else (128, 32),
                  IndicatorRun(t_end=300.0 if ctx.quick else 1000.0), progress=False,
                  engine=ctx.engine),
        chaos_map(other, 1.0, 0.0, "theta2=0", 24 if ctx.quick else 64,
                  IndicatorRun(t_end=200.0 if ctx.quick else 500.0), progress=False,
                  engine=ctx.engine),
    ]
    with paper_style():
        fig = new_figure(1, 2, width=9.0, aspect=0.85)
        for ax, ds, label in zip(fig.axes, maps, ("(a) the paper's body, $h = c/2$",
                                                  "(b) Hess body $(A, B, C) = (3, 1, 2)$, "
                                                  r"$\mu = 1$, $h = 1$"),
                                 strict=True):
            plot_chaos_map(ds, ax=ax, title=label)
    files = ctx.figure(fig, "chaos-maps")
    files.append(ctx.data(maps[0], "chaos-map-paper"))
    files.append(ctx.data(maps[1], "chaos-map-hess-3-1-2"))
    fli = [float(np.nanmax(m["fli"].values)) for m in maps]
    return Result(files, {"fli_max_paper": fli[0], "fli_max_other": fli[1]},
                  {"fli": fli, "engine": str(maps[0].attrs["engine"]),
                   "tol": float(maps[0].attrs["tolerance"])})


def border(ctx: Context) -> Result:
    """The border of chaos off the Hess direction: splitting against epsilon, the
    chaotic fraction over (mu, epsilon), a frequency map.

    Parameters
    ----------
    ctx : Context
        Output folder, body, engine, quick.
    """
    import numpy as np

    from andoyer.analysis.chaos.border import chaos_border_map
    from andoyer.analysis.chaos.frequency import frequency_map
    from andoyer.analysis.splitting.measure import splitting_vs_epsilon
    from andoyer.analysis.unperturbed.separatrix import separatrix_energy
    from andoyer.plot.border import plot_border_of_chaos

    # A Hess body whose separatrices split by O(mu) (rho = 1.08): on the paper's body
    # (rho = 4.56) the splitting and the chaotic layers are exponentially small.
    body = RigidBody.hess(2.5, 1.0, 1.6, name="rho~1")
    h = separatrix_energy(body)            # the level of the rotations with |G| = 1
    eps = [0.0, 0.1, 0.2, 0.4] if not ctx.quick else [0.0, 0.2]
    split = splitting_vs_epsilon(body, eps, [0.01], n_phase=8, progress=False,
                                 engine=ctx.engine)
    border = chaos_border_map(body, [0.01, 0.04, 0.1] if not ctx.quick else [0.01, 0.1],
                              [0.0, 0.2, 0.4] if not ctx.quick else [0.0, 0.4], h,
                              n=(24, 12) if not ctx.quick else (12, 6),
                              t_end=200.0 if not ctx.quick else 60.0, engine=ctx.engine,
                              progress=False)
    fmap = frequency_map(body.with_mu(0.04), h, 0.0, ("theta2", 0.0),
                         n_orbits=40 if not ctx.quick else 12,
                         t_end=1000.0 if not ctx.quick else 200.0, engine=ctx.engine,
                         progress=False)
    files = ctx.figure(plot_border_of_chaos(split, border, fmap), "border-of-chaos")
    files += [ctx.data(split, "splitting-vs-epsilon"), ctx.data(border, "border-of-chaos"),
              ctx.data(fmap, "frequency-map")]
    amp, pred = split.amplitude.values[:, 0], split.amplitude_melnikov.values[:, 0]
    rel = split.relative_error.values[:, 0]
    rows = [[f"{e:g}", f"{a:.4e}", f"{b:.4e}", "-" if not np.isfinite(r) else f"{r:.2e}"]
            for e, a, b, r in zip(eps, amp, pred, rel, strict=True)]
    frac = border.chaotic_fraction.values
    drift = fmap.log10_drift.values
    tori = float(np.mean(drift < -4)) if drift.size else float("nan")
    return Result(
        files,
        {"border_splitting_eps_max": float(amp[-1]),
         "border_splitting_eps0": float(amp[0]),
         "border_chaotic_fraction_min": float(np.nanmin(frac)),
         "border_chaotic_fraction_max": float(np.nanmax(frac)),
         "frequency_map_torus_share": tori},
        {"rho": float(split.rho), "frac_min": float(np.nanmin(frac)),
         "frac_max": float(np.nanmax(frac)), "tori": tori,
         "drift_min": float(np.nanmin(drift)), "drift_max": float(np.nanmax(drift)),
         "engine": str(border.attrs.get("engine", ctx.engine_name()))},
        Table(["epsilon", "max |Delta G| measured", "mu x Melnikov", "relative difference"],
              rows))
