"""Invariant manifolds and separatrix splitting: datasets in, figures out (nothing computed).

The datasets come from :func:`andoyer.analysis.splitting.measure.separatrix_splitting`: the
manifold curves on the section ``L = 0`` in its Darboux coordinates ``(g, G)``, the
heteroclinic points, and the splitting ``Delta G`` as a function of the phase ``g`` and
of ``mu`` with its first-order (Melnikov) prediction.

Examples
--------
>>> import numpy as np, xarray as xr
>>> mu = np.array([0.005, 0.01])
>>> sp = xr.Dataset({"amplitude": ("mu", 0.7 * mu), "amplitude_melnikov": ("mu", 0.7 * mu),
...                  "relative_error": ("mu", 3 * mu)}, coords={"mu": mu})
>>> fig = plot_splitting_vs_mu(sp)
>>> len(fig.axes)
2
"""

from __future__ import annotations

import numpy as np
import xarray as xr
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.ticker import NullFormatter

from andoyer.plot.style import COLOURS, angle_ticks, new_figure, paper_style
from andoyer.plot.words import branch_words

__all__ = ["plot_manifold_curves", "plot_splitting_phase", "plot_splitting_vs_mu",
           "plot_manifolds_summary"]

_U = COLOURS["saddle"]      # unstable manifold
_S = COLOURS["centre"]      # stable manifold


def _graph(ds: xr.Dataset) -> tuple[np.ndarray, np.ndarray]:
    """The curve as a graph G(g), g in [0, 2 pi), sorted (it is a graph over the phase)."""
    g = np.asarray(ds.g_angle.values, dtype=float)
    G = np.asarray(ds.G_action.values, dtype=float)
    order = np.argsort(g)
    return g[order], G[order]


def plot_manifold_curves(unstable: xr.Dataset, stable: xr.Dataset,
                         intersections: xr.Dataset | None = None, *, ax: Axes | None = None,
                         title: str | None = None) -> Axes:
    """``W^u`` and ``W^s`` on the section ``L = 0`` in ``(g, G)``, with heteroclinic points.

    Parameters
    ----------
    unstable, stable : xarray.Dataset
        Curves of :meth:`andoyer.analysis.splitting.manifolds.ManifoldCurve.dataset`.
    intersections : xarray.Dataset, optional
        Heteroclinic points (variables ``g``, ``G``; a ``mu`` dim is reduced to its last
        value, the ``mu`` of the curves).
    ax : matplotlib.axes.Axes, optional
        The axes to draw on (default: a new figure).
    title : str, optional
        The axes title.
    """
    if ax is None:
        with paper_style():
            ax = new_figure().axes[0]
    for ds, colour, label in ((unstable, _U, "$W^u$"), (stable, _S, "$W^s$")):
        g, G = _graph(ds)
        ax.plot(g, G, color=colour, lw=0.9, label=label)
        ax.plot(g, G, ".", color=colour, ms=1.5)
    if intersections is not None and intersections.sizes.get("intersection", 0):
        it = intersections.isel(mu=-1) if "mu" in intersections.dims else intersections
        ok = np.isfinite(it.g.values)
        ax.scatter(it.g.values[ok], it.G.values[ok], marker="o", s=26, facecolors="none",
                   edgecolors="black", linewidths=0.9, zorder=6, label="heteroclinic points")
    ax.set_xlim(0.0, 2 * np.pi)
    angle_ticks(ax, 0.0, 2 * np.pi)
    ax.ticklabel_format(axis="y", useOffset=False)
    ax.set_xlabel("$g$ (on $L = 0$)")
    ax.set_ylabel("$G$")
    mu = unstable.attrs.get("body_mu")
    ax.set_title(title if title is not None else
                 f"manifolds on $L = 0$, branch "
                 f"{branch_words(str(unstable.attrs.get('branch', '')))}, "
                 f"$\\mu = {float(mu):g}$" if mu is not None else "manifolds on $L = 0$")
    ax.legend(loc="best", frameon=True, framealpha=0.85, edgecolor="none")
    return ax


def _hess_label(hess: xr.Dataset) -> str:
    eps = float(hess.epsilon) if "epsilon" in hess else 0.0
    return r"$\theta_1 = 0$ (Hess)" if eps == 0.0 else f"$\\theta_1 = 0$, $\\epsilon = {eps:g}$"


def plot_splitting_phase(splitting: xr.Dataset, *, ax: Axes | None = None,
                         hess: xr.Dataset | None = None) -> Axes:
    """``Delta G / mu`` against the phase ``g``: measured (markers) and ``-M/(c G)`` (line).

    Divided by ``mu`` the first-order prediction is one curve for every ``mu``; the
    measured points approach it as ``mu -> 0``. ``hess``: the same on the Hess branch
    ``theta1 = 0`` (its profile, squares, and its prediction, dashed), drawn where it
    splits (a body turned off the Hess direction).

    Parameters
    ----------
    splitting : xarray.Dataset
        The splitting measured on the branch ``theta1 = 4 phi0``
        (:func:`andoyer.analysis.splitting.measure.separatrix_splitting`).
    ax : matplotlib.axes.Axes, optional
        The axes to draw on (default: a new figure).
    hess : xarray.Dataset, optional
        The same on the Hess branch ``theta1 = 0`` of a turned body.
    """
    if ax is None:
        with paper_style():
            ax = new_figure().axes[0]
    g = np.asarray(splitting.phase.values, dtype=float)
    mus = np.asarray(splitting.mu.values, dtype=float)
    colours = [f"C{i}" for i in range(mus.size)]
    room = 0.45
    fine = splitting.Delta_G_melnikov.isel(mu=-1).values / mus[-1]
    ax.plot(g, fine, "-", color="black", lw=1.0, label=r"$-M/(cG)$ (Melnikov)")
    for i, m in enumerate(mus):
        ax.plot(g, splitting.Delta_G.isel(mu=i).values / m, "o", ms=3, color=colours[i],
                label=f"$\\mu = {m:g}$")
    if hess is not None and float(np.nanmax(np.abs(hess.Delta_G_melnikov.values))) > 0.0:
        m = float(hess.mu.values[-1])
        hg = np.asarray(hess.phase.values, dtype=float)
        ax.plot(hg, hess.Delta_G_melnikov.isel(mu=-1).values / m, "--", color="0.3",
                lw=1.0, label=_hess_label(hess) + ": Melnikov")
        ax.plot(hg, hess.Delta_G.isel(mu=-1).values / m, "s", ms=3,
                color=COLOURS["hess"], label=_hess_label(hess) + f", $\\mu = {m:g}$")
        room = 0.9
    ax.axhline(0.0, color=COLOURS["singular"], lw=0.5)
    ax.set_xlim(0.0, 2 * np.pi)
    angle_ticks(ax, 0.0, 2 * np.pi)
    lo, hi = ax.get_ylim()
    ax.set_ylim(lo, hi + room * (hi - lo))          # room for the legend
    ax.set_xlabel("phase $g$ on $L = 0$")
    ax.set_ylabel(r"$\Delta G / \mu$")
    ax.set_title("splitting along $g = $ const")
    ax.legend(loc="upper center", ncols=2, frameon=True, framealpha=0.85, edgecolor="none",
              fontsize="x-small")
    return ax


def plot_splitting_vs_mu(splitting: xr.Dataset, *, axes: tuple[Axes, Axes] | None = None,
                         hess: xr.Dataset | None = None) -> Figure:
    """Log-log: splitting amplitude against ``mu`` with ``mu M``, and the relative error.

    Parameters
    ----------
    splitting : xarray.Dataset
        With ``amplitude``, ``amplitude_melnikov``, ``relative_error`` over ``mu``.
    axes : pair of Axes, optional
    hess : xarray.Dataset, optional
        The same measurement on the Hess branch ``theta1 = 0`` (``amplitude``): drawn as
        the level at which the manifolds coincide.
    """
    if axes is None:
        with paper_style():
            fig = new_figure(1, 2, aspect=0.8)
        ax1, ax2 = fig.axes
    else:
        ax1, ax2 = axes
        fig = ax1.get_figure(root=True)  # type: ignore[assignment]
    mus = np.asarray(splitting.mu.values, dtype=float)
    ax1.loglog(mus, splitting.amplitude_melnikov.values, "-", color="black",
               label=r"$\mu\,\max|M|/(cG)$")
    ax1.loglog(mus, splitting.amplitude.values, "o", color=_U, ms=4,
               label=r"measured $\max|\Delta G|$")
    if hess is not None:
        ax1.loglog(hess.mu.values, np.maximum(hess.amplitude.values, 1e-17), "s",
                   color=COLOURS["hess"], ms=4,
                   label=_hess_label(hess) + r": $\max|\Delta G|$")
    ax1.set_xlabel(r"$\mu$")
    ax1.set_ylabel(r"$\max_g |\Delta G|$")
    ax1.set_title("splitting amplitude")
    ax1.legend(loc="best", fontsize="x-small")
    rel = np.asarray(splitting.relative_error.values, dtype=float)
    ax2.loglog(mus, rel, "o-", color=_U, ms=4, label="measured vs first order")
    ok = np.isfinite(rel) & (rel > 0)
    if ok.any():
        ref = rel[ok][-1] * mus / mus[ok][-1]
        ax2.loglog(mus, ref, ":", color="0.4", label=r"$\propto \mu$")
    for ax in (ax1, ax2):
        ax.set_xticks(mus, [f"{m:g}" for m in mus])
        ax.xaxis.set_minor_formatter(NullFormatter())
    ax2.set_xlabel(r"$\mu$")
    ax2.set_ylabel(r"$\max_g|\Delta G - \mu\,\Delta G_1| / \max|\mu\,\Delta G_1|$")
    ax2.set_title("error of the first-order prediction")
    ax2.legend(loc="best")
    assert fig is not None
    return fig


def plot_manifolds_summary(result: dict[str, xr.Dataset], hess: xr.Dataset | None = None,
                           *, title: str | None = None) -> Figure:
    """The four panels of ``andoyer manifolds``: curves, splitting vs phase, vs mu, error.

    Parameters
    ----------
    result : dict of xarray.Dataset
        What :func:`andoyer.analysis.splitting.measure.separatrix_splitting` returns.
    hess : xarray.Dataset, optional
        The ``"splitting"`` dataset of the Hess branch ``theta1 = 0``.
    title : str, optional
        The figure title.
    """
    with paper_style():
        fig = new_figure(2, 2, aspect=0.78)
        a, b, c, d = fig.axes
        plot_manifold_curves(result["curve_unstable"], result["curve_stable"],
                             result["intersections"], ax=a)
        plot_splitting_phase(result["splitting"], ax=b, hess=hess)
        plot_splitting_vs_mu(result["splitting"], axes=(c, d), hess=hess)
        if title:
            fig.suptitle(title, wrap=True)
    return fig
