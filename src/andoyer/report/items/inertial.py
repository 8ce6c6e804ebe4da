"""Item of the body in inertial space: the Hess motions in the laboratory and the heteroclinic
cycle between the two pendulum-like rotations.

The builder computes with :mod:`andoyer.analysis.space`, draws with
:mod:`andoyer.plot.space` and returns a :class:`~andoyer.report.base.Result`; its prose
is ``templates/items/space.html.j2``.
"""

from __future__ import annotations

from andoyer.report.base import Context, Result, Table

__all__ = ["space"]


def space(ctx: Context) -> Result:
    """The heteroclinic cycle of the Hess case in space, with its attitude checks.

    Parameters
    ----------
    ctx : Context
        Output folder, body, engine, quick.
    """
    import numpy as np

    from andoyer.analysis.space.inertial import axis_trace, heteroclinic_cycle
    from andoyer.integrate.engines.base import Capability
    from andoyer.plot.space import plot_heteroclinic_cycle

    engine = ctx.engine_name(Capability.ATTITUDE)
    cycle = heteroclinic_cycle(ctx.body, engine=engine, n_times=801 if ctx.quick else 2401)
    trace = axis_trace(cycle, "z")
    files = ctx.figure(plot_heteroclinic_cycle(cycle, trace), "space")
    files.append(ctx.data(cycle.drop_vars(["rotation"]), "space-cycle"))
    LG = cycle.L_over_G
    hess = LG.sel(branch="theta1=0").values
    other = LG.sel(branch="theta1=4phi0").values
    R = cycle.rotation.values
    orth = float(np.abs(np.einsum("btki,btkj->btij", R, R) - np.eye(3)).max())
    vertical = float(np.abs(cycle.space_momentum.values[..., 2]).max())
    relation = float(np.nanmax(np.abs(np.sin(cycle.theta1.sel(branch="theta1=0").values
                                             / 2))))
    numbers = {"hess_branch_start": float(hess[0]), "hess_branch_end": float(hess[-1]),
               "orthogonality": orth, "vertical_momentum": vertical,
               "hess_relation": relation}
    table = Table(["separatrix branch", "L/G at t = −t½", "L/G at t = 0", "L/G at t = +t½",
                   "least L/G", "largest L/G"],
                  [[str(b), f"{v[0]:+.6f}", f"{v[v.size // 2]:+.2e}", f"{v[-1]:+.6f}",
                    f"{v.min():+.6f}", f"{v.max():+.6f}"] for b, v in
                   (("θ₁ = 0", hess), ("θ₁ = 4φ₀", other))])
    return Result(files, numbers,
                  {**numbers, "t_half": float(cycle.attrs["t_half"]),
                   "other_min": float(other.min()), "other_max": float(other.max()),
                   "lam": float(cycle.attrs["lambda_rate"]), "mu": ctx.body.mu,
                   "engine": str(cycle.attrs["engine"])}, table)
