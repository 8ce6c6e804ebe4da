"""The border of chaos near the Hess case in one figure: the splitting of the former Hess
separatrix against the turn ``epsilon`` of the centre of mass, the chaotic fraction over
``(mu, epsilon)``, and a frequency map.

Every panel takes a dataset of the analysis layer
(:func:`andoyer.analysis.splitting.measure.splitting_vs_epsilon`,
:func:`andoyer.analysis.chaos.border.chaos_border_map`,
:func:`andoyer.analysis.chaos.frequency.frequency_map`).
"""

from __future__ import annotations

from typing import Any

import numpy as np
import xarray as xr
from matplotlib.figure import Figure

from andoyer.plot.atlas import border_panel
from andoyer.plot.section import LABELS
from andoyer.plot.style import COLOURS, angle_ticks, colour_bar, colour_scale, paper_style

__all__ = ["plot_splitting_vs_epsilon", "plot_frequency_map", "plot_border_of_chaos"]


def plot_splitting_vs_epsilon(ds: xr.Dataset, *, ax: Any) -> Any:
    """Measured splitting amplitude (markers) and the first-order Melnikov prediction
    (line) against ``epsilon``, one colour per ``mu`` (linear axes: the amplitude of the
    Hess branch is linear in ``sin epsilon`` and zero at ``epsilon = 0``).

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`andoyer.analysis.splitting.measure.splitting_vs_epsilon`.
    ax : matplotlib.axes.Axes
        The axes to draw on.
    """
    eps = np.asarray(ds.epsilon.values, dtype=float)
    palette = (COLOURS["centre"], COLOURS["saddle"], COLOURS["chaotic"], COLOURS["orbit"])
    for k, m in enumerate(np.asarray(ds.mu.values, dtype=float)):
        c = palette[k % len(palette)]
        meas = np.asarray(ds.amplitude.values[:, k], dtype=float)
        pred = np.asarray(ds.amplitude_melnikov.values[:, k], dtype=float)
        ax.plot(eps, pred, "-", color=c, lw=1.0, label=f"$\\mu = {m:g}$: Melnikov")
        ax.plot(eps, meas, "o", color=c, ms=3.5, mfc="none", label="measured")
    ax.set_ylim(bottom=0.0)
    ax.set_xlabel("$\\epsilon$ (rad)")
    ax.set_ylabel("max $|\\Delta G|$ on $L = 0$")
    ax.legend(fontsize=6.5, frameon=False)
    return ax


def plot_frequency_map(ds: xr.Dataset, *, ax: Any) -> Any:
    """Seeds of a frequency map on their section plane, coloured by ``log10`` of the
    frequency drift (its colour scale :data:`andoyer.plot.style.SCALES`: pale on tori,
    dark in chaos). Returns the scatter.

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`andoyer.analysis.chaos.frequency.frequency_map`.
    ax : matplotlib.axes.Axes
        The axes to draw on.
    """
    x = str(ds.attrs.get("plane_x", "theta1"))
    y = str(ds.attrs.get("plane_y", "J1"))
    X = np.asarray(ds[x].values, dtype=float)
    Y = np.asarray(ds[y].values, dtype=float)
    d = np.asarray(ds.log10_drift.values, dtype=float)
    ok = np.isfinite(X) & np.isfinite(Y) & np.isfinite(d)
    scale = colour_scale("log10_drift")
    norm = scale.norm(np.maximum(d[ok], -14.0))  # below 1e-14: round-off, not drift
    sc = ax.scatter(X[ok], Y[ok], c=d[ok], s=9, cmap=scale.cmap, norm=norm, linewidths=0)
    if x in ("theta1", "l", "g", "theta2"):
        angle_ticks(ax, 0.0, 2 * np.pi)
        ax.set_xlim(0.0, 2 * np.pi)
    ax.set_xlabel(LABELS.get(x, x))
    ax.set_ylabel(LABELS.get(y, y))
    return sc


def plot_border_of_chaos(splitting: xr.Dataset, border: xr.Dataset,
                         frequencies: xr.Dataset, *, width: float = 7.5) -> Figure:
    """Three panels on a grid: (a) :func:`plot_splitting_vs_epsilon` and (b) the chaotic
    fraction over ``(epsilon, mu)`` (:func:`~andoyer.plot.atlas.border_panel`) side by
    side, (c) :func:`plot_frequency_map` across the width below; every colour bar
    labelled.

    Parameters
    ----------
    splitting : xarray.Dataset
        From :func:`andoyer.analysis.splitting.measure.splitting_vs_epsilon`.
    border : xarray.Dataset
        From :func:`andoyer.analysis.chaos.border.chaos_border_map`.
    frequencies : xarray.Dataset
        From :func:`andoyer.analysis.chaos.frequency.frequency_map`.
    width : float, default 7.5
        Figure width, inches.
    """
    with paper_style():
        fig = Figure(figsize=(width, 0.8 * width), layout="constrained")
        axes = fig.subplot_mosaic([["a", "b"], ["c", "c"]], height_ratios=[1.0, 0.9])
        a, b, c = axes["a"], axes["b"], axes["c"]
        plot_splitting_vs_epsilon(splitting, ax=a)
        a.set_title(f"(a) splitting of $\\theta_1 = 0$, $\\rho = {float(splitting.rho):.3g}$")
        mesh = border_panel(b, border, "chaotic_fraction", x="epsilon", y="mu",
                            label="(b) chaotic fraction (MEGNO)")
        colour_bar(mesh, b, "chaotic_fraction", shrink=0.9)
        sc = plot_frequency_map(frequencies, ax=c)
        mu = frequencies.attrs.get("body_mu", frequencies.attrs.get("mu", ""))
        c.set_title(f"(c) frequency drift, $\\mu = {float(mu):g}$")
        colour_bar(sc, c, "log10_drift", shrink=0.9)
    return fig
