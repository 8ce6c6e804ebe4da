"""Items beyond the paper: the p/q island chains predicted at first and second order in
mu and measured on sections; the Birkhoff normal form at the centres against the closed form.

The builder computes with :mod:`andoyer.analysis.resonance`, draws with
:mod:`andoyer.plot` and returns a :class:`~andoyer.report.base.Result`; its prose is
``templates/items/resonances.html.j2``.
"""

from __future__ import annotations

from collections.abc import Callable
from functools import partial
from typing import Any

from andoyer.body import RigidBody
from andoyer.report.base import Context, Result, Table, concurrently

__all__ = ["resonances"]

#: The body of the comparison: low-order chains (``|V_k| ~ 1e-2``), a level h = 1, M = 0.
BODY = RigidBody.hess(3.0, 1.0, 2.0, mu=1e-3, name="hess(3, 1, 2)")
#: The body of the resonant normal form: off Hess, tilted; its 2:1 chain about y on h = 1
#: sits at a small Birkhoff action (I* = 0.27), where the Birkhoff polynomial holds.
TILTED = RigidBody(2.5, 1.0, 2.0, 1e-3, (0.6, 0.48, 0.64), name="tilted(2.5, 1, 2)")


def resonances(ctx: Context) -> Result:
    """Predicted chains over a section; predicted vs measured half-widths; the normal form.

    Parameters
    ----------
    ctx : Context
        Output folder, body, engine, quick.
    """
    import math
    import warnings

    import numpy as np
    from scipy.optimize import brentq

    from andoyer.analysis.resonance import (
        birkhoff_normal_form,
        island_prediction,
        normal_form_frequency,
        resonance_widths,
        resonant_normal_form,
    )
    from andoyer.analysis.resonance.measure import measure_island
    from andoyer.analysis.unperturbed.euler_poinsot import euler_poinsot_frequencies
    from andoyer.charts.andoyer_deprit import from_andoyer
    from andoyer.errors import SingularPassageWarning
    from andoyer.integrate.api import poincare
    from andoyer.integrate.engines.base import Capability
    from andoyer.integrate.fill import fill_section, section_roots
    from andoyer.plot.resonance import plot_resonances
    from andoyer.plot.section import plot_section
    from andoyer.plot.words import body_words

    # every section here is g = 0: an angle section (MEASURED_DEFAULTS)
    engine = ctx.engine_name(Capability.CROSSINGS, workload="angle_section")
    body = BODY
    pred = resonance_widths(body, 1.0, 0.0, "g=0", max_order=5)
    fill = fill_section(body, 1.0, 0.0, ("g", 0.0), n_orbits=4, root="smallest")
    # Orbits seeded across each first-order chain, at its first stable point: between the
    # centre line and the predicted separatrix (f < 1: inside) and beyond it.
    seeds = []
    for i in range(pred.sizes["resonance"]):
        r = pred.isel(resonance=i)
        if int(r.mu_order) != 1 or int(r.sign) != 1:
            continue
        sx, sy = float(r.stable_x[0]), float(r.stable_y[0])
        j = int(np.argmin(np.hypot(r.centre_x.values - sx, r.centre_y.values - sy)))
        ux, uy = float(r.upper_x[j]), float(r.upper_y[j])
        for f in ((0.5, 1.5) if ctx.quick else (0.3, 0.7, 1.3, 2.0)):
            x, y = sx + f * (ux - sx), sy + f * (uy - sy)
            roots = section_roots(body, 1.0, 0.0, ("g", 0.0), [x], [y])[0]
            if roots.size:
                G = float(roots[np.argmin(np.abs(roots - float(r.G_action)))])
                seeds.append(from_andoyer([x, 0.0, y, G, 0.0]))
    y0 = np.concatenate([np.array(seeds).reshape(-1, 6), fill.y0.values])

    def section() -> Any:
        with warnings.catch_warnings():   # orbits of the fill passing L = +-G: no crossings
            warnings.simplefilter("ignore", SingularPassageWarning)
            return poincare(body, y0, "g=0", 400 if ctx.quick else 1200,
                            engine=engine, rtol=1e-10, atol=1e-10)

    # The section and every measurement are independent: they share the cores.
    chains = [("3:1", 1, 1e-3)] if ctx.quick else [("3:1", 1, 1e-3), ("3:1", 1, 1e-4),
                                                   ("2:1", 1, 1e-3)]
    near_mus = (1e-3,) if ctx.quick else (1e-4, 1e-3)
    tasks: list[Callable[[], Any]] = [section]
    tasks += [partial(measure_island, body.with_mu(mu), 1.0, 0.0, label, axis=axis,
                      n_seeds=3, n_rounds=3 if ctx.quick else 4, engine=engine)
              for label, axis, mu in chains]
    paper_body = RigidBody.paper(0.01)
    if not ctx.quick:
        tasks += [partial(measure_island, paper_body, 0.2466, 0.0, "7:1", axis=1, n_seeds=2,
                          n_rounds=4, engine=engine),
                  # the half-width to orders 1-3 (S1)-(S4) beside it
                  partial(island_prediction, paper_body, 0.2466, 0.0, "7:1", axis=1,
                          order_mu=3)]
    for mu in near_mus:
        tasks += [partial(resonant_normal_form, TILTED.with_mu(mu), 1.0, 0.0, "2:1", axis=2,
                          order=8),
                  partial(measure_island, TILTED.with_mu(mu), 1.0, 0.0, "2:1", axis=2,
                          n_seeds=3, n_rounds=3 if ctx.quick else 5, engine=engine)]
    done = iter(concurrently(tasks))
    pts = next(done)
    from matplotlib.figure import Figure

    fig = Figure(figsize=(10.0, 4.5), layout="constrained")
    whole, zoom = fig.subplots(1, 2)
    for ax in (whole, zoom):
        plot_section(pts, ax=ax, boundary=fill)
        plot_resonances(pred, ax=ax, labels=False)
    whole.set_title("predicted chains over the section", fontsize=8)
    handles, names = whole.get_legend_handles_labels()
    keep = [i for i, n in enumerate(names) if not n.startswith("_")]
    fig.legend([handles[i] for i in keep], [names[i] for i in keep], fontsize=7.5,
               loc="outside lower center", ncols=4, frameon=False,
               title="predicted chains q:p (dashed: the resonant torus; o stable, x unstable "
                     "periodic points)", title_fontsize=7.5)
    # The widest chain, around its first stable point: the separatrices against the orbits.
    first = pred.where((pred.mu_order == 1) & (pred.sign == 1), drop=True)
    k = int(np.nanargmax(first.half_width.values))
    r = first.isel(resonance=k)
    sx, sy = float(r.stable_x[0]), float(r.stable_y[0])
    j = int(np.argmin(np.hypot(r.centre_x.values - sx, r.centre_y.values - sy)))
    span = 4.0 * float(np.hypot(r.upper_x[j] - sx, r.upper_y[j] - sy))
    zoom.set_xlim(sx - 3 * span, sx + 3 * span)
    zoom.set_ylim(sy - span, sy + span)
    # the whole plane's ticks are multiples of pi/2: the zoom needs its own
    from matplotlib.ticker import MaxNLocator, ScalarFormatter

    zoom.xaxis.set_major_locator(MaxNLocator(5))
    zoom.xaxis.set_major_formatter(ScalarFormatter())
    zoom.set_title(f"the {r.label.values} chain about axis {int(r.axis)}, near a stable point",
                   fontsize=8)
    fig.suptitle(body_words(body.A, body.B, body.C, body.mu)
                 + ", energy $H = 1$, $M = 0$, section $g = 0$", fontsize=9)
    files = ctx.figure(fig, "resonances")
    files.append(ctx.data(pred, "resonances"))
    rows = []
    numbers = {}
    for label, axis, mu in chains:
        m = next(done)
        p, q = float(m.predicted_half_width), float(m.measured_half_width)
        rows.append([body.name, f"{label} (axis {axis})", f"{mu:g}", f"{p:.4e}", "-",
                     f"{q:.4e}", f"{(q - p) / p:+.2%}", f"{float(m.edge_uncertainty):.1e}",
                     f"{float(m.stable_s):+.4e}", f"{float(m.predicted_stable_s):+.4e}",
                     f"{float(m.predicted_stable_s_2):+.4e}"])
        numbers[f"half_width_{label}_mu_{mu:g}"] = q
    # The paper's body at its mu: thin chains whose position is decided at second order
    # (R12): first order misses the island, the Lie-Deprit normal form (S1)-(S4) does not.
    second_order = []
    if not ctx.quick:
        m, orders = next(done), next(done)
        p, q = float(m.predicted_half_width), float(m.measured_half_width)
        rows.append(["paper", "7:1 (axis 1)", "0.01", f"{p:.4e}", "-", f"{q:.4e}",
                     f"{(q - p) / p:+.2%}", f"{float(m.edge_uncertainty):.1e}",
                     f"{float(m.stable_s):+.4e}", f"{float(m.predicted_stable_s):+.4e}",
                     f"{float(m.predicted_stable_s_2):+.4e}"])
        hw = float(m.measured_half_width)
        # the half-width to orders 1-3 (S1)-(S4): for p = 1 the resonant harmonic enters at
        # the odd orders only, so order 2 gains nothing on it and order 3 does
        widths = [float(w) / hw - 1.0 for w in orders.half_width.values]
        miss1 = (float(m.stable_s) - float(m.predicted_stable_s)) / hw
        miss2 = (float(m.stable_s) - float(m.predicted_stable_s_2)) / hw
        second_order.append({"first": miss1, "second": miss2, "width_r6": p / hw - 1.0,
                             "widths": widths})
        numbers["paper_7:1_stable_miss_first_half_widths"] = miss1
        numbers["paper_7:1_stable_miss_second_half_widths"] = miss2
        for order, w in enumerate(widths, 1):
            numbers[f"paper_7:1_half_width_error_order_{order}"] = w
    # Near a centre, at a resonance: the resonant normal form (N1)-(N5) of the tilted
    # body's 2:1 chain about y, against the torus route and the sections.
    near = []
    for mu in near_mus:
        rnf, m = next(done), next(done)
        p, n, q = (float(m.predicted_half_width), float(rnf.half_width),
                   float(m.measured_half_width))
        rows.append([TILTED.name, "2:1 (axis 2, near the centre)", f"{mu:g}", f"{p:.4e}",
                     f"{n:.4e}", f"{q:.4e}", f"{(q - n) / n:+.2%}",
                     f"{float(m.edge_uncertainty):.1e}", f"{float(m.stable_s):+.4e}",
                     f"{float(m.predicted_stable_s):+.4e}",
                     f"{float(m.predicted_stable_s_2):+.4e}"])
        numbers[f"normal_form_half_width_2:1_mu_{mu:g}"] = n
        numbers[f"half_width_near_centre_2:1_mu_{mu:g}"] = q
        numbers[f"torus_half_width_2:1_mu_{mu:g}"] = p
        numbers[f"edge_uncertainty_near_centre_2:1_mu_{mu:g}"] = float(m.edge_uncertainty)
        near.append({"mu": mu, "action": float(rnf.action), "nf": n, "torus": p,
                     "measured": q, "unc": float(m.edge_uncertainty)})
    # The normal form at the rotation about y of the paper's body, against the closed form.
    # At growing amplitude (0.05, 0.1, 0.2 rad): the error must fall like amplitude^N.
    paper = ctx.body
    amps = (0.05, 0.1, 0.2)
    nf_rows = []
    lines = ["Birkhoff normal form at the rotation about y, |G| = 1, the paper's body: "
             "relative error of omega_l against the closed form",
             f"{'order N':>8} " + " ".join(f"{a:>9g} rad" for a in amps)
             + f" {'fitted slope':>13}"]
    for order in (2, 4, 6, 8):
        nf = birkhoff_normal_form(paper, 1.0, order=order, lstar=0.0)
        errs = []
        for amp in amps:
            h = 0.5 * (paper.a * math.sin(amp) ** 2 + paper.b * math.cos(amp) ** 2)
            exact = 2 * math.pi / euler_poinsot_frequencies(paper, h, 1.0).period
            action = brentq(lambda a, nf=nf, h=h: float(
                normal_form_frequency(nf, [a]).energy[0]) - h, 0.0, 0.1, xtol=1e-16)
            w = abs(float(normal_form_frequency(nf, [action]).omega_l[0]))
            errs.append(abs(w - exact) / exact)
        slope = float(np.polyfit(np.log(amps), np.log(errs), 1)[0])
        lines.append(f"{order:>8} " + " ".join(f"{e:>13.2e}" for e in errs)
                     + f" {slope:>13.2f}")
        numbers[f"birkhoff_slope_order_{order}"] = slope
        if order in (4, 8):
            nf_rows.append((order, errs[:2], math.log2(errs[1] / errs[0])))
    return Result(
        files, numbers,
        {"engine": engine, "n_chains": int(pred.sizes["resonance"]),
         "nf": nf_rows, "near": near, "second_order": second_order},
        Table(["body", "chain", "mu", "predicted half-width (G), torus (R6)",
               "normal form (N5)", "measured", "difference (to the normal form where "
               "given)", "edge uncertainty", "stable point, measured",
               "stable point, (R10)", "stable point, second order (S4)"], rows),
        pre="\n".join(lines))
