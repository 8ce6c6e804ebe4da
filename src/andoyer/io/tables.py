"""Plain-text tables of analysis results (presentation only: nothing is computed here).

:func:`format_table` takes a fixed-point set (:mod:`andoyer.analysis.unperturbed.fixed_points`), the
Euler-Poisson equilibria (:mod:`andoyer.analysis.unperturbed.equilibria`) or the rows of the paper
check (:mod:`andoyer.analysis.paper.check`) and returns the table the report writes and
the command line prints.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from andoyer.analysis.paper.check import CheckRow
    from andoyer.analysis.unperturbed.equilibria import EquilibriumSet
    from andoyer.analysis.unperturbed.fixed_points import FixedPointSet

__all__ = ["format_table", "eigenvalue_text"]


def eigenvalue_text(ev: Sequence[complex]) -> str:
    """The distinct ``+-`` pairs of a Hamiltonian spectrum, e.g. ``"+-0.5 i"``.

    Parameters
    ----------
    ev : sequence of complex
        The eigenvalues (pairs ``+-lambda``).

    Examples
    --------
    >>> eigenvalue_text([0.5j, -0.5j, 2.0, -2.0])
    '+-0.5 i, +-2'
    """
    vals = sorted({(round(abs(v.real), 10), round(abs(v.imag), 10)) for v in ev})
    parts = []
    for re, im in vals:
        if im == 0.0:
            parts.append(f"+-{re:.10g}")
        elif re == 0.0:
            parts.append(f"+-{im:.10g} i")
        else:
            parts.append(f"+-{re:.6g} +-{im:.6g} i")
    return ", ".join(parts)


def format_table(result: FixedPointSet | EquilibriumSet | Sequence[CheckRow]) -> str:
    """A plain-text table of a fixed-point set, the Euler-Poisson equilibria or a paper check.

    Parameters
    ----------
    result : FixedPointSet, EquilibriumSet or sequence of CheckRow
        What to tabulate (:func:`andoyer.analysis.unperturbed.fixed_points.fixed_points`,
        :func:`~andoyer.analysis.unperturbed.equilibria.euler_poisson_equilibria`,
        :func:`~andoyer.analysis.paper.check.paper_check`).

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> from andoyer.analysis.unperturbed.fixed_points import hess_fixed_points
    >>> print(format_table(hess_fixed_points(RigidBody.paper())).splitlines()[0])
    Fixed points of the unperturbed system in (theta1, J1), J2 = 1, theta1 in [0, 2 pi)
    """
    from andoyer.analysis.unperturbed.equilibria import EquilibriumSet
    from andoyer.analysis.unperturbed.fixed_points import FixedPointSet

    if isinstance(result, EquilibriumSet):
        return _equilibria_table(result)
    if isinstance(result, FixedPointSet):
        return _fixed_point_table(result)
    if isinstance(result, Sequence):
        return _paper_check_table(result)
    raise TypeError("format_table takes a FixedPointSet, an EquilibriumSet or a list of "
                    f"CheckRow, got {type(result).__name__}")


def _equilibria_table(result: EquilibriumSet) -> str:
    lines = [f"Equilibria G = 0 of the Euler-Poisson equations (1), mu = "
             f"{result.body.mu:g}, r = ({', '.join(f'{v:.6g}' for v in result.body.r)})",
             f"{'name':<9} {'gamma':<34} {'type':<15} eigenvalues on the leaf"]
    for e in result.equilibria:
        g = "(" + ", ".join(f"{v + 0.0:.6g}" for v in e.y[3:]) + ")"  # + 0.0: no "-0"
        lines.append(f"{e.name:<9} {g:<34} {e.linear_type:<15} "
                     f"{eigenvalue_text(e.eigenvalues)}")
    return "\n".join(lines)


def _fixed_point_table(result: FixedPointSet) -> str:
    qn, pn = ("l", "L") if result.chart == "andoyer" else ("theta1", "J1")
    an = "G0" if result.chart == "andoyer" else "J2"
    rng = "2 pi" if result.period < 7.0 else "4 pi"
    lines = [f"Fixed points of the unperturbed system in ({qn}, {pn}), {an} = "
             f"{result.action:g}, {qn} in [0, {rng})",
             f"{'#':>2} {qn:>10} {pn:>9}  {'closed form':<24} {'chart type':<10} "
             f"{'chart eigenvalues':<22} {'motion':<8} {'physical':<9} {'real':<5} label"]
    for i, fp in enumerate(result.points):
        lines.append(
            f"{i:>2} {fp.q:>10.6f} {fp.p:>9.5f}  {fp.closed_form:<24} {fp.linear_type:<10} "
            f"{eigenvalue_text(fp.eigenvalues):<22} {fp.motion:<8} {fp.physical_type:<9} "
            f"{'yes' if fp.real_equilibrium else 'no':<5} {fp.label}")
    lines.append("Permanent rotations (Euler equations on |G| = G0, the regular route):")
    for r in result.rotations:
        lines.append(f"   {r.name:<3} moment {r.moment} = {r.moment_value:<8g} "
                     f"{r.inertia_rank:<7} {r.linear_type:<7} "
                     f"{eigenvalue_text(r.eigenvalues):<22} label {r.label}")
    lines.append("real = no: a point of a singular line of the chart (the whole line is one "
                 "state, the rotation about +-z); its chart eigenvalues are not physical.")
    return "\n".join(lines)


def _paper_check_table(rows: Sequence[CheckRow]) -> str:
    lines = []
    for r in rows:
        lines.append(f"{r.label:<13} {r.verdict:<9} {r.name}")
        if r.verdict != "holds":
            lines.append(f"{'':<23}max rel. error {r.max_rel_error:.2e}: {r.nature}")
            if r.corrected:
                lines.append(f"{'':<23}corrected: {r.corrected}")
    n_mis = sum(r.verdict == "misprint" for r in rows)
    n_om = sum(r.verdict == "omission" for r in rows)
    lines.append("")
    lines.append(f"{len(rows)} formulas: {len(rows) - n_mis - n_om} hold, {n_mis} misprints, "
                 f"{n_om} omissions or remarks. The code uses the derived forms.")
    return "\n".join(lines)
