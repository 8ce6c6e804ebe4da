"""Items of the Hess case: the Hess solution and the physical pendulum (periods,
potential, stability), and Fig. 3 (trajectories near the separatrix, the section
theta2 = 0).

Each builder computes with :mod:`andoyer.analysis`, draws with :mod:`andoyer.plot` and
returns a :class:`~andoyer.report.base.Result`; its prose is
``templates/items/<key>.html.j2``.
"""

from __future__ import annotations

from andoyer.body import RigidBody
from andoyer.report.base import Context, Result

__all__ = ["solutions", "fig3"]

def fig3(ctx: Context) -> Result:
    """Fig. 3: trajectories in the Hess chart and the section theta2 = 0.

    Parameters
    ----------
    ctx : Context
        Output folder, body, engine, quick.
    """
    from andoyer.analysis.paper.trajectories import fig3_section, fig3_trajectories
    from andoyer.analysis.unperturbed.separatrix import separatrix_energy
    from andoyer.plot.fig3 import plot_fig3

    traj = fig3_trajectories(ctx.body, engine=ctx.engine,
                             t_end=200.0 if ctx.quick else 400.0)
    sec, fill = fig3_section(ctx.body, engine=ctx.engine,
                             n_crossings=100 if ctx.quick else 400)
    files = ctx.figure(plot_fig3(traj, sec, fill), "fig3")
    files.append(ctx.data(traj, "fig3-trajectories"))
    files.append(ctx.data(sec.drop_vars("y0"), "fig3-section"))
    drift = float(traj.attrs["H_max_drift"])
    return Result(files, {"H_max_drift": drift},
                  {"h": separatrix_energy(ctx.body), "H_max_drift": drift,
                   "residual": float(abs(sec.section_residual).max()),
                   "engine": str(traj.attrs.get("engine", ctx.engine_name()))})


def solutions(ctx: Context) -> Result:
    """The Hess solution and the physical pendulum: periods, portrait, Floquet.

    Parameters
    ----------
    ctx : Context
        Output folder, body, engine, quick.
    """
    import numpy as np
    import xarray as xr

    from andoyer.analysis.hess.floquet import floquet_scan, hess_rotation_multiplier
    from andoyer.analysis.hess.periods import hess_periods
    from andoyer.analysis.hess.solution import reduced_hamiltonian
    from andoyer.integrate.engines.base import Capability
    from andoyer.plot.solutions import plot_solutions

    body, mu = ctx.body, ctx.body.mu
    periods = hess_periods(body, (0.0, 0.05), 60 if ctx.quick else 160,
                           2 if ctx.quick else 5, engine=ctx.engine)
    rel = np.abs(periods.T_integrated / periods.T_elliptic_check - 1.0)
    th = np.linspace(0.0, 2 * np.pi, 181)
    J = np.linspace(-1.2, 1.2, 121) * np.sqrt(2 * 3 * mu / body.c)
    H = reduced_hamiltonian(body, th[:, None], J[None, :], 0.0)
    portrait = xr.Dataset({"H": (("theta2", "J2"), H),
                           "levels": ("level", mu * np.array([-0.8, -0.5, -0.2, 0.3, 0.7,
                                                              1.4, 2.0, 2.8]))},
                          coords={"theta2": th, "J2": J}, attrs={"separatrix": mu})
    other = RigidBody(body.A, body.B, body.C, mu, (0.6, 0.8, 0.0), "r = (0.6, 0.8, 0)")
    energies = mu * np.linspace(-0.95, 5.0, 13 if ctx.quick else 37)
    energies = energies[np.abs(energies - mu) > 0.02 * mu]
    floquet_engine = ctx.engine_name(Capability.TANGENT)  # the variational monodromy
    floq = xr.concat([floquet_scan(b, energies, engine=floquet_engine).expand_dims(
        body=[b.name]) for b in (body, other)], "body", combine_attrs="drop_conflicts")
    files = ctx.figure(plot_solutions(periods, portrait, floq), "solutions")
    files.append(ctx.data(periods, "hess-periods"))
    files.append(ctx.data(floq, "pendulum-floquet"))
    lam = hess_rotation_multiplier(body)
    return Result(files, {"max_rel_period_error": float(rel.max()), "rotation_multiplier": lam},
                  {"max_rel_period_error": float(rel.max()), "lam": lam,
                   "engine": str(periods.attrs.get("engine", ctx.engine_name())),
                   "floquet_engine": floquet_engine})
