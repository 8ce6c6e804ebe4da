"""``andoyer paper``: rebuild the paper's figures and checks from nothing, into one folder.

Each *item* of the report is built by one function of this module from the library's
analysis (data) and plot (figures) layers. It writes its figures (PNG and PDF), their
data (NetCDF) and says, for ``index.html``, what the paper prints there and what this
package corrected or added. :func:`build_paper` runs the items with a progress line
each -- on two cores the longest first, in this process and one worker process that
take the next item as they free up -- and writes ``index.html`` last (atomically), so a
folder with an index is a complete one.

Examples
--------
>>> [item.key for item in ITEMS][:3]
['fig1', 'fig2', 'heteroclinic']
"""

from __future__ import annotations

import json
import multiprocessing
import os
import sys
import threading
import time
from collections.abc import Callable
from concurrent.futures import ProcessPoolExecutor
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import xarray as xr

from andoyer._version import __version__
from andoyer.atomic import atomic_path
from andoyer.body import RigidBody
from andoyer.io import write_netcdf
from andoyer.plot.section import save_figure
from andoyer.validation import integer

__all__ = ["Item", "Result", "Context", "ITEMS", "build_paper", "default_jobs", "DEFAULT_OUT"]

#: Default output folder of ``andoyer paper``.
DEFAULT_OUT = "andoyer-paper"


@dataclass
class Context:
    """What every item builder gets: the output folder, the paper's body, the engine."""

    out: Path
    body: RigidBody
    engine: str | None = None
    quick: bool = False

    def figure(self, fig: Any, name: str) -> list[Path]:
        """Write a figure as ``name.png`` and ``name.pdf``."""
        return save_figure(fig, self.out / name, pdf=True, dpi=200)

    def data(self, ds: xr.Dataset, name: str) -> Path:
        """Write a dataset as ``name.nc`` (atomically)."""
        return write_netcdf(ds, self.out / f"{name}.nc")


@dataclass
class Result:
    """What an item wrote and what ``index.html`` says about it."""

    files: list[Path]
    paper: str
    found: list[str] = field(default_factory=list)
    html: str = ""
    numbers: dict[str, float] = field(default_factory=dict)


@dataclass(frozen=True)
class Item:
    """One section of the report: a key, a title and the function that builds it."""

    key: str
    title: str
    build: Callable[[Context], Result]
    #: Seconds it takes (measured, warm caches, 2 cores): items start longest first.
    cost: float = 1.0


# ---------------------------------------------------------------------- items
def _paper_check(ctx: Context) -> Result:
    from andoyer.analysis.paper_check import paper_check
    from andoyer.io.tables import format_table

    rows = paper_check(n=50 if ctx.quick else 200)
    text = format_table(rows)
    txt = ctx.out / "paper-check.txt"
    with atomic_path(txt) as tmp:
        tmp.write_text(text + "\n", encoding="utf-8")
    js = ctx.out / "paper-check.json"
    with atomic_path(js) as tmp:
        tmp.write_text(json.dumps([asdict(r) for r in rows], indent=1), encoding="utf-8")
    counts = {v: sum(r.verdict == v for r in rows) for v in ("holds", "misprint", "omission")}
    html = _table(["place", "verdict", "formula", "what is wrong / missing", "corrected form"],
                  [[r.label, r.verdict, r.name, r.nature, r.corrected] for r in rows])
    return Result(
        [txt, js],
        f"{len(rows)} formulas printed in the paper, each typed as printed and evaluated at "
        "random points against the derivation from H = (G, IG)/2 + mu (r, gamma).",
        [f"{counts['holds']} hold, {counts['misprint']} are misprints, "
         f"{counts['omission']} are incomplete or missing (the table below gives each "
         "one's nature and its corrected form, itself checked against the derivation)."],
        html, {k: float(v) for k, v in counts.items()})


def _fig3(ctx: Context) -> Result:
    from andoyer.analysis.trajectories import fig3_section, fig3_trajectories
    from andoyer.plot.fig3 import plot_fig3

    traj = fig3_trajectories(ctx.body, engine=ctx.engine,
                             t_end=200.0 if ctx.quick else 400.0)
    sec, fill = fig3_section(ctx.body, engine=ctx.engine,
                             n_crossings=100 if ctx.quick else 400)
    files = ctx.figure(plot_fig3(traj, sec, fill), "fig3")
    files.append(ctx.data(traj, "fig3-trajectories"))
    files.append(ctx.data(sec.drop_vars("y0"), "fig3-section"))
    return Result(
        files,
        "Fig. 3: 'Projection of phase trajectories of the dynamic system (16) on the plane "
        "R^2(theta1, J1)' for mu = 0.01, A1 = 2.5, A2 = 2.0, A3 = 2.2; 'Area, separated by "
        "dot-dash line, is shown at the right side in the extended form.'",
        ["Trajectories are integrated in the regular Euler-Poisson variables and read in "
         "the Hess chart (14), not integrated in the chart (16), which is singular at "
         "J1 = 0, J1 = J2 (the corners the separatrix runs into).",
         "Added: the same phase space as a Poincare section theta2 = 0 at the separatrix "
         f"energy h = c/2 = {ctx.body.c / 2:.6g} (J2 = 1), which shows what the projection "
         "smears: invariant curves, islands, and the thin chaotic layer along the "
         "separatrix theta1 = 4 phi0 (enlarged in (d)); along theta1 = 0 (the Hess "
         "solution, drawn bold) there is none.",
         f"Energy conserved to {traj.attrs['H_max_drift']:.1e} (relative) along the "
         "trajectories; crossings satisfy theta2 = 0 to "
         f"{float(abs(sec.section_residual).max()):.1e}."],
        numbers={"H_max_drift": float(traj.attrs["H_max_drift"])})


def _pre(text: str) -> str:
    return f"<pre>{_esc(text)}</pre>"


def _fig1(ctx: Context) -> Result:
    from andoyer.analysis.portraits import portrait_andoyer
    from andoyer.plot.portraits import plot_fig1

    ds = portrait_andoyer(ctx.body, 1.0)
    files = ctx.figure(plot_fig1(ds), "fig1")
    files.append(ctx.data(ds, "fig1-portrait"))
    return Result(
        files,
        "Fig. 1: 'the phase portrait of system (12)' -- the unperturbed system (9) in "
        "(l, L) at fixed G0; the list of its fixed points that should follow 'With any "
        "G0 > 0 the system (4) has fixed points' is missing from the text.",
        ["Drawn from the level curves of H0 (13) (G0 = 1), with all 12 fixed points of "
         "the fundamental domain found numerically and matched with their closed forms "
         "(see the table under Fig. 2).",
         "The paper's (9) prints dL/dt with the wrong sign; the figure uses the derived "
         "field (the level curves of H0 do not depend on it, the arrows of time do)."])


def _fig2(ctx: Context) -> Result:
    from andoyer.analysis.equilibria import euler_poisson_equilibria
    from andoyer.analysis.fixed_points import andoyer_fixed_points, hess_fixed_points
    from andoyer.analysis.portraits import portrait_andoyer, portrait_hess
    from andoyer.analysis.separatrix import FIG2_CAPTION
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
    txt = ctx.out / "fixed-points.txt"
    with atomic_path(txt) as tmp:
        tmp.write_text(tables + "\n", encoding="utf-8")
    files.append(txt)
    return Result(
        files,
        "Fig. 2: 'Phase portrait of unperturbed Euler-Poinsot system: (a) in the variables "
        "Andoyer-Deprit; (b) in new variables'. 'Separatrices, to which Hess' solutions are "
        "approached with mu -> 0, are marked with a bold line and a dotted line. Uniform "
        "rotations are noted with digits 1-4.' After Fig. 3: the unperturbed system 'has "
        "four fixed points (0, 0), (0, J2), (4 phi0, 0), (4 phi0, J2), 0 <= theta1 < 2 pi'.",
        [FIG2_CAPTION,
         "All fixed points: 12 in (l, L) and 6 in (theta1, J1) with theta1 in [0, 2 pi) "
         "(12 in the double cover [0, 4 pi)). The paper lists four; all four lie on the "
         "charts' singular lines J1 = 0, J2 (L = -+G), where a whole line is one physical "
         "state, the rotation about -+z (the middle axis: unstable). Their chart "
         "eigenvalues +-2 sigma J2 are twice the physical exponent sigma G of that "
         "rotation, sigma = sqrt((b - c)(c - a)). Missing in the paper: the centres "
         "(2 phi0, J2/2) (rotations about +-y) and (2 phi0 + pi, J2/2) (about +-x).",
         "The paper's phi0 = arctg(sqrt(c - b)/sqrt(a - c)) has negative radicands for "
         f"the paper's ordering a < c < b; phi0 = atan2(e2, e1) = {ctx.body.phi0:.10f}.",
         "Added: the equilibria G = 0 of the Euler-Poisson system: hanging "
         "(centre-centre) and upright (saddle-saddle), eigenvalues on the symplectic leaf."],
        _pre(tables))


def _heteroclinic(ctx: Context) -> Result:
    import numpy as np

    from andoyer.analysis.separatrix import BRANCHES, heteroclinic, heteroclinic_rate
    from andoyer.integrate.api import propagate

    body0 = ctx.body.with_mu(0.0)
    lam = heteroclinic_rate(ctx.body, 1.0)
    t = np.linspace(-60.0, 60.0, 241)
    rows: list[list[Any]] = []
    errs: list[float] = []
    sets: list[xr.Dataset] = []
    for branch in BRANCHES:
        for sign in (+1, -1):
            ds = heteroclinic(ctx.body, 1.0, t, branch=branch, sign=sign)
            run = propagate(body0, ds.y.values[0], t - t[0], engine=ctx.engine,
                            rtol=1e-13, atol=1e-13)
            ys = np.stack([run[v].values[0] for v in
                           ("G1", "G2", "G3", "gamma1", "gamma2", "gamma3")], -1)
            err = float(np.max(np.abs(ys - ds.y.values)))
            errs.append(err)
            rows.append([branch, sign, ds.attrs["J1_direction"], f"{err:.1e}"])
            sets.append(ds.expand_dims(orbit=[len(sets)]))
    ctx_files = [ctx.data(xr.concat(sets, "orbit", combine_attrs="drop_conflicts"),
                          "heteroclinic")]
    return Result(
        ctx_files,
        "'The heteroclinic trajectories of the dynamic system are explored with the help "
        "of the canonical variables' -- no formula is given.",
        [f"Closed form (μ = 0, M = 0): θ1 ≡ 0 or 4φ0, J1(t) = J2 / (1 + exp(∓λ(t − t0))), "
         f"λ = 2 J2 sqrt((b − c)(c − a)) = {lam:.10f} for J2 = 1, θ2 = θ2(t0) + c J2 (t − t0).",
         f"Checked against integration of the Euler-Poisson equations (heyoka, tol 1e-13) "
         f"from t − t0 = −60 to 60: largest state error {max(errs):.1e}."],
        _table(["branch", "sign", "J1", "max |closed form − integration|"], rows),
        {"lambda": lam, "max_error": max(errs)})


def _solutions(ctx: Context) -> Result:
    import numpy as np

    from andoyer.analysis.floquet import floquet_scan, hess_rotation_multiplier
    from andoyer.analysis.hess_periods import hess_periods
    from andoyer.analysis.hess_solution import reduced_hamiltonian
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
    floq = xr.concat([floquet_scan(b, energies).expand_dims(body=[b.name])
                      for b in (body, other)], "body", combine_attrs="drop_conflicts")
    files = ctx.figure(plot_solutions(periods, portrait, floq), "solutions")
    files.append(ctx.data(periods, "hess-periods"))
    files.append(ctx.data(floq, "pendulum-floquet"))
    lam = hess_rotation_multiplier(body)
    return Result(
        files,
        "'When e1 sin l + e2 cos l = 0 we have the Hess' condition, and when G^2 = L^2 and "
        "M = 0 -- physical pendulum.' 'On the Hess' solution Pi = mu sin g, on solution, "
        "which describes the physical pendulum motion Pi = mu^-1 sin(g + l - phi0).' No "
        "periods, solutions or stability are given.",
        ["Hess solution (theta1 = 0): the reduced Hamiltonian is H = c J2^2/2 + "
         "mu sqrt(J2^2 - M^2) sin(theta2)/J2, a pendulum at M = 0; periods through K(m) "
         "(closed form also for M != 0, from the roots of a cubic), checked against "
         f"integrated crossing times to {float(rel.max()):.1e} (relative).",
         "Every M = 0 libration passes through G = 0, where all charts fail: the orbit is "
         "integrated in Euler-Poisson variables, and the chart values jump (theta1, theta2, "
         "J1, J2, m) -> (theta1 + 2 pi, pi - theta2, J1 - J2, -J2, m + pi) with J1, J2 "
         "taken signed (panel (b) draws the signed-J2 picture).",
         "Potential: Pi = mu sin g on the Hess solution holds only on theta1 = 0 at M = 0. "
         "On the physical pendulum Pi = mu sin(g + l + phi0) on L = G and mu sin(g - l - "
         "phi0) on L = -G, not the printed mu^-1 sin(g + l - phi0).",
         f"Stability (added): the pendulum rotations of the Hess body are unstable at every "
         f"energy, multiplier exp(2 pi sigma / c) = {lam:.6f}; its librations have multipliers "
         "1 but a Jordan block (a 1:1 resonance of the transverse and pendulum "
         "frequencies), so they are linearly unstable: a perturbation off the Hess manifold "
         "returns shifted along it, growing in proportion to time and more so at higher "
         "energy. "
         "For a non-Hess centre of mass r = (0.6, 0.8, 0) the librations have alternating "
         "stable and unstable tongues."],
        numbers={"max_rel_period_error": float(rel.max()), "rotation_multiplier": lam})


def _manifolds(ctx: Context) -> Result:
    import numpy as np

    from andoyer.analysis.splitting import separatrix_splitting
    from andoyer.plot.manifolds import plot_manifolds_summary

    mus = [0.0025, 0.005, 0.01] if not ctx.quick else [0.005, 0.01]
    body = ctx.body
    res = separatrix_splitting(body, mus, n_phase=8 if ctx.quick else 16, progress=False,
                               branch="theta1=4phi0")
    hess = separatrix_splitting(body, [mus[-1]], branch="theta1=0", n_phase=8,
                                progress=False)["splitting"]
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
        "The abstract and introduction speak of 'splitting separatrix surfaces' and "
        "'heteroclinic motions'; the paper stops at the unperturbed picture.",
        ["Added: for mu > 0 the rotations about the middle axis z become hyperbolic "
         "periodic orbits (on M = 0 exactly the physical-pendulum rotations), found by "
         "Newton's method on the Poincare map with continuation in mu; their stable and "
         "unstable manifolds are grown on the section L = 0 and the splitting of the "
         "separatrix theta1 = 4 phi0 is measured as Delta G along the section.",
         "Melnikov function of mu H1 along the heteroclinic orbit: M(theta2) = "
         "-s pi rho / sinh(pi rho) [sin(theta1 + theta2) - sin theta2], rho = c/(2 sigma) "
         f"= {body.c / (2 * body.sigma):.4f} "
         "for this body: the splitting is exponentially small, and first order holds with "
         "a relative error that halves with mu (table).",
         f"The separatrix theta1 = 0 of the Hess solution does not split: max |Delta G| = "
         f"{hess_max:.1e} at mu = {mus[-1]:g} (the Hess relation (3) is an invariant "
         "manifold for all mu)."],
        _table(["mu", "max |Delta G| measured", "mu x Melnikov", "relative difference"],
               rows),
        {"hess_max_splitting": hess_max,
         **{f"splitting_mu_{m:g}": float(a) for m, a in zip(mus, meas, strict=True)}})


def _chaos(ctx: Context) -> Result:
    import numpy as np

    from andoyer.analysis.chaos import chaos_map
    from andoyer.plot.chaos import plot_chaos_map
    from andoyer.plot.style import new_figure, paper_style

    body = ctx.body
    other = RigidBody.hess(3.0, 1.0, 2.0, mu=1.0)
    maps = [
        chaos_map(body, body.c / 2, 0.0, "theta2=0", n=(64, 16) if ctx.quick else (128, 32),
                  t_end=300.0 if ctx.quick else 1000.0, progress=False),
        chaos_map(other, 1.0, 0.0, "theta2=0", n=24 if ctx.quick else 64,
                  t_end=200.0 if ctx.quick else 500.0, progress=False),
    ]
    with paper_style():
        fig = new_figure(1, 2, aspect=0.85)
        for ax, ds, label in zip(fig.axes, maps, ("(a) the paper's body, h = c/2",
                                                  "(b) Hess body (3, 1, 2), mu = 1, h = 1"),
                                 strict=True):
            plot_chaos_map(ds, ax=ax, title=label)
    files = ctx.figure(fig, "chaos-maps")
    files.append(ctx.data(maps[0], "chaos-map-paper"))
    files.append(ctx.data(maps[1], "chaos-map-hess-3-1-2"))
    fli = [float(np.nanmax(m["fli"].values)) for m in maps]
    return Result(
        files,
        "The introduction: 'Two-dimensional invariant varieties, that contain the Hess' "
        "solution, determine the border of chaos in a dynamic system.' No chaos indicator "
        "is computed.",
        ["Added: the fast Lyapunov indicator FLI = sup ln |w| of the tangent vector w of "
         "the variational equations of (1) (heyoka, tol 1e-12, w tangent to the Casimir "
         "level), over the section theta2 = 0 at M = 0; dark = regular (FLI ~ ln t), "
         "bright = chaotic.",
         "(a) The paper's body on the separatrix level h = c/2 of Fig. 3: regular almost "
         f"everywhere (FLI close to ln t); the largest values (up to {fli[0]:.1f} at "
         "t = 1000) lie along the separatrices theta1 = 4 phi0 and theta1 = 0, where "
         "orbits linger near the hyperbolic rotations. The chaotic layer itself is "
         "exponentially thin (the splitting is ~1e-6, see the manifolds item) and below "
         "the resolution of this map; the Hess separatrix theta1 = 0 does not split.",
         "(b) A Hess body with visible chaos, (A, B, C) = (3, 1, 2), mu = 1, at the energy "
         f"of the upright top h = mu: a wide chaotic sea with islands (largest FLI "
         f"{fli[1]:.1f} at t = 500)."],
        numbers={"fli_max_paper": fli[0], "fli_max_other": fli[1]})


def _border(ctx: Context) -> Result:
    import numpy as np

    from andoyer.analysis.chaos_border import chaos_border_map
    from andoyer.analysis.frequency import frequency_map
    from andoyer.analysis.separatrix import separatrix_energy
    from andoyer.analysis.splitting import splitting_vs_epsilon
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
        "The introduction: the invariant surfaces carrying the Hess solution 'determine "
        "the border of chaos'; the Hess problem shows 'frequency resonances, splitting "
        "separatrix surfaces' and transitions from regular to chaotic motion. Nothing is "
        "computed.",
        ["Added: the centre of mass turned by epsilon off the Hess direction in the "
         "(e1, e2) plane (RigidBody.near_hess). The Hess relation (3) is then no longer "
         "invariant: d(G, r)/dt = G3 [(a - b) e1 e2 (G, r) + kappa_H (G, n)], kappa_H = "
         "2 sigma epsilon + O(epsilon^2).",
         "(a) The former Hess separatrix theta1 = 0 splits: the Melnikov function of the "
         "turned centre of mass is M = -2 s (pi rho/sinh pi rho) sin(theta1/2 + epsilon) "
         "cos(theta2 + theta1/2); on theta1 = 0 its amplitude is linear in epsilon and zero "
         "at epsilon = 0. Measured with the manifolds of the rotations (table, mu = 0.01, "
         "body (A, B, C) = (2.5, 1, 1.6), rho = "
         f"{float(split.rho):.3f}).",
         "(b) The chaotic fraction of the section theta2 = 0 at h = c/2 (MEGNO above the "
         "largest value on the free top, mu = 0, plus 1; in brackets the fraction with the "
         f"threshold moved by -+1/2): from {np.nanmin(frac):.2f} to {np.nanmax(frac):.2f} "
         "over the grid, set by mu; epsilon changes it little. The Hess surface theta1 = 0 "
         "itself is regular, yet it lies inside a chaotic layer as wide as that of the "
         "split branch theta1 = 4 phi0: orbits beside it pass by the hyperbolic rotations "
         "and leave along the split branch. The full-resolution map: "
         "examples/border_of_chaos.toml.",
         "(c) Frequency-map analysis (NAFF on the two halves of each orbit, t = 1000) at "
         f"mu = 0.04: {100 * tori:.0f} % of the seeds drift by less than 1e-4 (tori, "
         f"down to 10^{np.nanmin(drift):.1f}); the chaotic layer along the separatrices "
         f"drifts by up to 10^{np.nanmax(drift):.1f}."],
        _table(["epsilon", "max |Delta G| measured", "mu x Melnikov", "relative difference"],
               rows),
        {"border_splitting_eps_max": float(amp[-1]),
         "border_splitting_eps0": float(amp[0]),
         "border_chaotic_fraction_min": float(np.nanmin(frac)),
         "border_chaotic_fraction_max": float(np.nanmax(frac)),
         "frequency_map_torus_share": tori})


ITEMS: list[Item] = [
    Item("fig1", "Fig. 1 — the unperturbed system (9) in (l, L)", _fig1, 1.4),
    Item("fig2", "Fig. 2 — the unperturbed Euler–Poinsot portrait; all fixed points", _fig2,
         0.7),
    Item("heteroclinic", "Heteroclinic orbits in closed form", _heteroclinic, 0.1),
    Item("solutions", "The Hess solution and the physical pendulum", _solutions, 1.2),
    Item("fig3", "Fig. 3 — trajectories of (16) near the separatrix, and the section "
         "θ2 = 0", _fig3, 2.0),
    Item("manifolds", "Beyond the paper: separatrix splitting and the Melnikov function",
         _manifolds, 2.2),
    Item("chaos", "Beyond the paper: chaos maps (FLI)", _chaos, 6.2),
    Item("border", "Beyond the paper: the border of chaos near the Hess case", _border, 4.6),
    Item("paper-check", "Every printed formula against the derivation", _paper_check, 0.0),
]


# ---------------------------------------------------------------------- html
def _esc(text: Any) -> str:
    import html

    return html.escape(str(text))


def _table(head: list[str], rows: list[list[Any]]) -> str:
    out = ["<table><thead><tr>" + "".join(f"<th>{_esc(h)}</th>" for h in head)
           + "</tr></thead><tbody>"]
    for row in rows:
        out.append("<tr>" + "".join(f"<td>{_esc(c)}</td>" for c in row) + "</tr>")
    out.append("</tbody></table>")
    return "\n".join(out)


_CSS = """
body { font-family: system-ui, sans-serif; max-width: 72rem; margin: 2rem auto;
       padding: 0 1rem; color: #222; line-height: 1.45; }
h1 { font-size: 1.6rem; } h2 { font-size: 1.25rem; margin-top: 2.5rem;
  border-bottom: 1px solid #ccc; }
.item { display: grid; grid-template-columns: minmax(0, 3fr) minmax(0, 2fr); gap: 1.5rem; }
.item img { width: 100%; border: 1px solid #ddd; }
.paper { background: #f6f6f0; border-left: 4px solid #b9a; padding: .5rem .8rem; }
.found li { margin: .2rem 0; }
table { border-collapse: collapse; font-size: .85rem; margin-top: 1rem; }
td, th { border: 1px solid #ccc; padding: .2rem .4rem; vertical-align: top; }
.files { font-size: .85rem; color: #555; }
"""


def _write_index(out: Path, ctx: Context, done: list[tuple[Item, Result, float]]) -> Path:
    parts = [
        "<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'>",
        "<title>andoyer: the paper's results, reproduced and completed</title>",
        f"<style>{_CSS}</style></head><body>",
        "<h1>Kyrychenko, <i>Andoyer–Deprit variables use to the Hess gyroscope phase "
        "trajectories exploring</i>: results reproduced, checked and completed</h1>",
        f"<p>Built by andoyer {_esc(__version__)} for the body {_esc(ctx.body.name)} "
        f"(A, B, C) = ({ctx.body.A:g}, {ctx.body.B:g}, {ctx.body.C:g}), μ = "
        f"{ctx.body.mu:g}, φ0 = {ctx.body.phi0:.10f}, κ = a − b = {ctx.body.kappa:.6g}. "
        "Everything is derived from H = ½(G, IG) + μ(r, γ); where the paper and the "
        "derivation disagree, the derivation is used and the difference is listed. "
        "Each item: the figure (PDF beside it), what the paper says, and what was "
        "corrected or added.</p>",
    ]
    for item, res, seconds in done:
        images = [f for f in res.files if f.suffix == ".png"]
        parts.append(f"<h2 id='{_esc(item.key)}'>{_esc(item.title)}</h2>"
                     + ("<div class='item'><div>" if images else "<div><div>"))
        parts.append("".join(f"<img src='{_esc(f.name)}' alt='{_esc(item.title)}'>"
                             for f in images) + "</div>")
        parts.append(f"<div><p class='paper'><b>The paper:</b> {_esc(res.paper)}</p>")
        if res.found:
            parts.append("<p><b>Corrected or added:</b></p><ul class='found'>"
                         + "".join(f"<li>{_esc(s)}</li>" for s in res.found) + "</ul>")
        parts.append("<p class='files'>Files: " + ", ".join(
            f"<a href='{_esc(f.name)}'>{_esc(f.name)}</a>" for f in res.files)
            + f" (built in {seconds:.1f} s)</p></div></div>")
        if res.html:
            parts.append(res.html)
    parts.append("</body></html>")
    index = out / "index.html"
    with atomic_path(index) as tmp:
        tmp.write_text("\n".join(parts), encoding="utf-8")
    return index


# ---------------------------------------------------------------------- driver
#: A worker process starts in about 2 s (its imports): worth it above this much work.
_WORKER_WORTH_S = 5.0


def default_jobs(items: list[Item]) -> int:
    """Processes for ``items``: 2 when two cores are free and the items take more than
    :data:`_WORKER_WORTH_S` (the heavy items use every core themselves; two processes
    keep the cores busy between them), else 1.

    >>> default_jobs(ITEMS[2:3])  # one item of 0.1 s
    1
    """
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else (
        os.cpu_count() or 1)
    if len(items) < 2 or sum(i.cost for i in items) < _WORKER_WORTH_S:
        return 1
    return max(1, min(2, cores))


def _build_item(item: Item, ctx: Context) -> tuple[Result, float]:
    t0 = time.perf_counter()
    res = item.build(ctx)
    return res, time.perf_counter() - t0


def _run_items(items: list[Item], ctx: Context, jobs: int, progress: bool
               ) -> dict[str, tuple[Result, float]]:
    """Build ``items``: here, and with ``jobs = 2`` in one worker process too.

    Both take the next item from one queue, longest first (:attr:`Item.cost`), so the
    worker's start-up (its imports) overlaps the first item here. Figures are drawn on
    each process's main thread (matplotlib is not thread-safe); a thread here only
    hands items to the worker and waits.
    """
    queue = sorted(items, key=lambda i: -i.cost) if jobs > 1 else list(items)
    lock = threading.Lock()
    out: dict[str, tuple[Result, float]] = {}
    failed: list[BaseException] = []

    def take() -> Item | None:
        with lock:
            return queue.pop(0) if queue and not failed else None

    def record(item: Item, res: Result, dt: float) -> None:
        with lock:
            out[item.key] = (res, dt)
            k = len(out)
        if progress:
            print(f"[{k}/{len(items)}] {item.title} ... {dt:.1f} s", file=sys.stderr,
                  flush=True)

    def feed(pool: ProcessPoolExecutor) -> None:
        try:
            while (item := take()) is not None:
                record(item, *pool.submit(_build_item, item, ctx).result())
        except BaseException as exc:  # re-raised on the main thread
            with lock:
                failed.append(exc)

    pool = helper = None
    if jobs > 1:
        # spawn: a fresh interpreter (forking a process that may run threads is unsafe).
        pool = ProcessPoolExecutor(1, mp_context=multiprocessing.get_context("spawn"))
        helper = threading.Thread(target=feed, args=(pool,), daemon=True)
        helper.start()
    try:
        while (item := take()) is not None:
            record(item, *_build_item(item, ctx))
    except BaseException as exc:
        with lock:
            failed.append(exc)
    finally:
        if helper is not None and pool is not None:
            helper.join()
            pool.shutdown(cancel_futures=True)
    if failed:
        raise failed[0]
    return out


def build_paper(out: str | Path = DEFAULT_OUT, *, body: RigidBody | None = None,
                engine: str | None = None, quick: bool = False,
                only: list[str] | None = None, progress: bool = True,
                jobs: int | None = None
                ) -> tuple[Path, list[tuple[Item, Result, float]]]:
    """Build the report: every item's figures and data, then ``index.html``.

    Parameters
    ----------
    out : path-like
        Output folder (created).
    body : RigidBody, optional
        Default: the paper's body, :meth:`RigidBody.paper`.
    engine : str, optional
        Integration engine (default: heyoka where installed).
    quick : bool
        Smaller grids and shorter runs (for tests).
    only : list of str, optional
        Keys of the items to build (default: all, see :data:`ITEMS`).
    progress : bool
        One line per item on stderr (as items finish).
    jobs : int, optional
        Processes building items at once (default :func:`default_jobs`: 2 on two or
        more cores). The results do not depend on it.

    Returns
    -------
    (index, done)
        The path of ``index.html`` and, per item, the item, its result and seconds.
    """
    keys = [i.key for i in ITEMS]
    if only:
        unknown = sorted(set(only) - set(keys))
        if unknown:
            raise ValueError(f"unknown item(s) {unknown}; choose from {keys}")
    items = [i for i in ITEMS if not only or i.key in only]
    ctx = Context(Path(out), RigidBody.paper() if body is None else body, engine, quick)
    ctx.out.mkdir(parents=True, exist_ok=True)
    t_all = time.perf_counter()
    n_jobs = default_jobs(items) if jobs is None else integer("jobs", jobs, 1)
    times = _run_items(items, ctx, min(n_jobs, len(items)), progress)
    done = [(item, *times[item.key]) for item in items]
    summary = {"andoyer_version": __version__, "body": ctx.body.attrs(),
               "engine": ctx.engine or "default", "quick": quick,
               "items": {i.key: {"title": i.title, "seconds": round(dt, 3),
                                 "numbers": r.numbers, "files": [f.name for f in r.files]}
                         for i, r, dt in done}}
    with atomic_path(ctx.out / "summary.json") as tmp:
        tmp.write_text(json.dumps(summary, indent=1), encoding="utf-8")
    index = _write_index(ctx.out, ctx, done)
    if progress:
        print(f"wrote {index} ({time.perf_counter() - t_all:.1f} s in all)", file=sys.stderr)
    return index, done
