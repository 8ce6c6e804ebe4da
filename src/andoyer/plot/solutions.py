"""The Hess solution and the physical pendulum: periods, the reduced portrait, stability.

Datasets in (built by ``andoyer paper`` from :mod:`andoyer.analysis.hess.solution` and
:mod:`andoyer.analysis.hess.pendulum`), a figure out; nothing computed here.
"""

from __future__ import annotations

import xarray as xr
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.ticker import NullFormatter

from andoyer.plot.style import COLOURS, angle_ticks, new_figure, paper_style

__all__ = ["plot_solutions"]


def plot_solutions(periods: xr.Dataset, portrait: xr.Dataset, floquet: xr.Dataset) -> Figure:
    """(a) period of the Hess solution vs energy, (b) its reduced portrait, (c) Floquet
    multipliers of the physical pendulum vs energy.

    Parameters
    ----------
    periods : xarray.Dataset
        Dim ``h``: ``T_elliptic`` (dims ``M, h``), and the integration check
        ``T_integrated`` at energies ``h_check`` (dims ``M, check``).
    portrait : xarray.Dataset
        ``H`` on (``J2``, ``theta2``) with attrs ``mu``, ``separatrix``.
    floquet : xarray.Dataset
        :func:`andoyer.analysis.hess.floquet.floquet_scan` output(s), stacked on dim ``body``.
    """
    with paper_style():
        fig = new_figure(1, 3, aspect=0.95)
        ax_a, ax_b, ax_c = fig.axes
        mu = float(periods.attrs["body_mu"])
        for k, M in enumerate(periods.M.values):
            T = periods.T_elliptic.sel(M=M)
            line, = ax_a.plot(periods.h / mu, T, lw=1.0, label=f"closed form, $M = {M:g}$")
            ax_a.plot(periods.h_check.sel(M=M) / mu, periods.T_integrated.sel(M=M), "o",
                      ms=3.5, mfc="none", color=line.get_color(),
                      label="integration" if k == 0 else None)
        ax_a.axvline(1.0, color=COLOURS["separatrix"], lw=0.7, ls=":")
        ax_a.set_yscale("log")
        ax_a.set_xlabel(r"$h / \mu$")
        ax_a.set_ylabel("period $T$")
        ax_a.set_title(r"(a) Hess solution, $\theta_1 = 0$")
        _below(ax_a)

        th, J2 = portrait.theta2.values, portrait.J2.values
        ax_b.contour(th, J2, portrait.H.values.T, levels=portrait.levels.values,
                     colors=COLOURS["orbit"], linewidths=0.6,
                     negative_linestyles="solid")
        ax_b.contour(th, J2, portrait.H.values.T, levels=[float(portrait.attrs["separatrix"])],
                     colors=COLOURS["separatrix"], linewidths=1.2)
        ax_b.axhline(0.0, color=COLOURS["singular"], lw=0.8, ls="--",
                     label="$G = 0$: the charts fail")
        ax_b.plot([], [], color=COLOURS["separatrix"], lw=1.2, label="separatrix")
        ax_b.set_xlim(th[0], th[-1])
        angle_ticks(ax_b, th[0], th[-1])
        ax_b.set_xlabel(r"$\theta_2$")
        ax_b.set_ylabel(r"$J_2 = G$ (signed)")
        ax_b.set_title(r"(b) $cJ_2^2/2 + \mu \sin\theta_2$, $M = 0$")
        _below(ax_b)

        for name in floquet.body.values:
            f = floquet.sel(body=name)
            ax_c.plot(f.H_over_mu, f.abs_multiplier, "o-", ms=2.5, lw=0.8,
                      label=_body_words(str(name)))
        ax_c.axhline(1.0, color="0.6", lw=0.6)
        ax_c.axvline(1.0, color=COLOURS["separatrix"], lw=0.7, ls=":")
        ax_c.set_xlabel(r"$h / \mu$")
        ax_c.set_ylabel(r"largest $|\lambda|$")
        ax_c.set_yscale("log")
        ax_c.yaxis.set_minor_formatter(NullFormatter())  # 3x10^0 and 4x10^0 would collide
        ax_c.set_title("(c) pendulum: Floquet")
        _below(ax_c)
    return fig


def _below(ax: Axes) -> None:
    """The panel's legend under its axes, clear of the data."""
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.3), fontsize=6.5, frameon=False)


def _body_words(name: str) -> str:
    """A body of the Floquet scan in words: the paper's, or the one with centre of mass
    ``r = (...)``."""
    if name == "paper":
        return "the paper's body"
    return name.replace("r = ", "centre of mass $r$ = ") if name.startswith("r = ") else name
