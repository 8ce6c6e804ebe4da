"""Predicted island chains drawn over a section plane (nothing computed here).

The dataset is :func:`andoyer.analysis.resonance.predict.resonance_widths`: each chain's
centre line (the resonant torus of the free top), its two separatrices (R9), its stable
(o) and unstable (x) periodic points. Draw it alone or over :func:`andoyer.plot.section.
plot_section` on the same axes to compare prediction and measurement.
"""

from __future__ import annotations

import numpy as np
import xarray as xr
from matplotlib import colormaps
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from numpy.typing import NDArray

from andoyer.plot.section import LABELS
from andoyer.plot.style import colour_scale

__all__ = ["plot_resonances", "plot_residues", "convergent_ticks"]


def _broken(x: NDArray[np.float64], y: NDArray[np.float64], period: float
            ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The polyline with NaN where it jumps across the angle's wrap."""
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    jump = np.nonzero(np.abs(np.diff(x)) > period / 2)[0] + 1
    return np.insert(x, jump, np.nan), np.insert(y, jump, np.nan)


def plot_resonances(ds: xr.Dataset, *, ax: Axes | None = None, separatrices: bool = True,
                    labels: bool = True, title: str | None = None) -> Axes:
    """Draw the predicted chains of a
    :func:`~andoyer.analysis.resonance.predict.resonance_widths` dataset in its section
    plane.

    Parameters
    ----------
    ds : xarray.Dataset
        The predictions (variables ``centre_x``, ``centre_y``, ``upper_*``, ``lower_*``,
        ``stable_*``, ``unstable_*``; attrs ``plane_x``, ``plane_y``).
    ax : matplotlib Axes, optional
        Draw into it (e.g. the axes of :func:`andoyer.plot.section.plot_section`); by
        default a new figure.
    separatrices : bool
        Draw each chain's separatrices (first-order chains only).
    labels : bool
        Write ``q:p`` beside each chain's first stable point.
    title : str, optional
        Set the title (default: leave the axes' title, or name the level on a new figure).

    Returns
    -------
    matplotlib.axes.Axes
    """
    if not {"centre_x", "centre_y", "stable_x"} <= set(ds.data_vars):
        raise ValueError("plot_resonances needs a resonance_widths dataset (centre_x, "
                         "centre_y, stable_x, ...)")
    new = ax is None
    if ax is None:
        fig = Figure(figsize=(6.0, 4.5), layout="constrained")
        ax = fig.add_subplot()
    xname = str(ds.attrs.get("plane_x", "l_angle"))
    yname = str(ds.attrs.get("plane_y", "L_action"))
    period = 4 * np.pi if xname == "theta1" else 2 * np.pi
    n = ds.sizes.get("resonance", 0)
    cmap = colormaps[colour_scale("orbit").cmap]
    for i in range(n):
        row = ds.isel(resonance=i)
        colour = cmap(i / max(n - 1, 1))
        x, y = _broken(row.centre_x.values, row.centre_y.values, period)
        ax.plot(x, y, ls="--", lw=0.8, color=colour,
                label=f"{row.label.values} (axis {int(row.axis)})" if int(row.sign) == 1
                else None)
        if separatrices and int(row.mu_order) == 1:
            for part in ("upper", "lower"):
                x, y = _broken(row[f"{part}_x"].values, row[f"{part}_y"].values, period)
                ax.plot(x, y, lw=0.6, color=colour)
        sx, sy = row.stable_x.values, row.stable_y.values
        ux, uy = row.unstable_x.values, row.unstable_y.values
        ax.plot(sx, sy, "o", ms=3, mfc="none", color=colour)
        ax.plot(ux, uy, "x", ms=3, color=colour)
        if labels and np.isfinite(sx).any():
            j = int(np.nonzero(np.isfinite(sx))[0][0])
            ax.annotate(str(row.label.values), (sx[j], sy[j]), fontsize=6, color=colour,
                        xytext=(3, 3), textcoords="offset points")
    if new:
        ax.set_xlabel(LABELS.get(xname, xname))
        ax.set_ylabel(LABELS.get(yname, yname))
    if title is not None:
        ax.set_title(title)
    elif new:
        ax.set_title(f"predicted chains on H = {ds.attrs.get('h', float('nan')):.6g}, "
                     f"M = {ds.attrs.get('M', float('nan')):g}, "
                     f"{ds.attrs.get('section', '')}, mu = {ds.attrs.get('body_mu', 0):g}",
                     fontsize=8)
    return ax


def plot_residues(datasets: list[xr.Dataset], *, ax: Axes | None = None) -> Axes:
    """Draw the elliptic residues of the convergents of
    :func:`~andoyer.analysis.resonance.residues.last_torus` datasets against their period
    ``q`` (log-log), one line per dataset (its ``mu``), with Greene's threshold 1/4 (G5).

    Parameters
    ----------
    datasets : list of xarray.Dataset
        ``last_torus`` results (of one torus at several ``mu``).
    ax : matplotlib Axes, optional
        Where to draw (default: a new figure's).

    Returns
    -------
    matplotlib.axes.Axes
    """
    if ax is None:
        ax = Figure(figsize=(5.0, 3.8), layout="constrained").add_subplot()
    for i, ds in enumerate(datasets):
        R = np.abs(ds.residue_elliptic.values)
        floor = ds.residue_resolution_elliptic.values
        keep = np.isfinite(R) & (R > floor)          # above the integration's error only
        ax.plot(ds.q.values[keep], R[keep], "o-", color=f"C{i}", ms=3.5,
                label=f"$\\mu = {float(ds.attrs['body_mu']):.4g}$")
    ax.axhline(0.25, color="0.3", ls="--", lw=0.8, label="$R = 1/4$ (Greene)")
    ax.set_yscale("log")
    convergent_ticks(ax, np.concatenate([ds.q.values for ds in datasets]))
    ax.set_xlabel("period $q$ of the convergent $p/q$")
    ax.set_ylabel("elliptic residue $R$")
    # beside the axes: the residues fill any corner (falling below mu_c, growing above)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0)
    return ax


def convergent_ticks(ax: Axes, q: NDArray[np.integer]) -> None:
    """A log axis of periods ``q`` ticked at the convergents' periods themselves (a few
    consecutive Fibonacci-like periods span less than a decade: no decade tick in view).

    Parameters
    ----------
    ax : matplotlib Axes
        The axes whose x axis shows ``q``.
    q : array of int
        The convergents' periods.
    """
    from matplotlib.ticker import FixedLocator, NullLocator, StrMethodFormatter

    ticks = np.unique(np.asarray(q, dtype=int))
    ax.set_xscale("log")
    ax.xaxis.set_major_locator(FixedLocator([float(x) for x in ticks]))
    ax.xaxis.set_major_formatter(StrMethodFormatter("{x:.0f}"))
    ax.xaxis.set_minor_locator(NullLocator())
    if len(ticks):
        ax.set_xlim(ticks[0] / 1.15, ticks[-1] * 1.15)
