"""The paper's Fig. 3: trajectories of (16) on (theta1, J1), enlarged near the separatrix,
and the same phase space as a Poincare section theta2 = const.

Datasets in (from :mod:`andoyer.analysis.paper.trajectories`), a figure out; nothing computed.
"""

from __future__ import annotations

import numpy as np
import xarray as xr
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.patches import Rectangle

from andoyer.plot.style import COLOURS, angle_ticks, colour_scale, new_figure, paper_style

__all__ = ["plot_fig3"]


def _separatrices(ax: Axes, phi0: float, J2: float) -> None:
    """The unperturbed separatrices theta1 = 0, 4 phi0 (bold / dotted as in Fig. 2)."""
    ax.axvline(0.0, color=COLOURS["hess"], lw=1.6)
    ax.axvline(2 * np.pi, color=COLOURS["hess"], lw=1.6)
    ax.axvline(4 * phi0, color=COLOURS["separatrix"], lw=1.0, ls=":")
    ax.axhline(0.0, color=COLOURS["singular"], lw=0.6)
    ax.axhline(J2, color=COLOURS["singular"], lw=0.6)


def _trajectories(ax: Axes, traj: xr.Dataset) -> None:
    th = np.asarray(traj.theta1.values)
    J1 = np.asarray(traj.J1.values)
    colours = [COLOURS["orbit"], "#2c7fb8"]
    for i in range(th.shape[0]):
        # Break the line where theta1 wraps (mod 2 pi), not to draw chords across the plane.
        x = th[i].copy()
        y = J1[i].copy()
        jump = np.abs(np.diff(x)) > np.pi
        x = np.insert(x, np.flatnonzero(jump) + 1, np.nan)
        y = np.insert(y, np.flatnonzero(jump) + 1, np.nan)
        ax.plot(x, y, lw=0.45, color=colours[i % 2], rasterized=True)


def _points(ax: Axes, sec: xr.Dataset, size: float) -> None:
    x = np.mod(np.asarray(sec.theta1.values, dtype=float), 2 * np.pi)
    y = np.asarray(sec.J1.values, dtype=float)
    ok = np.isfinite(x) & np.isfinite(y)
    colour = np.broadcast_to(np.arange(x.shape[0])[:, None], x.shape)
    ax.scatter(x[ok], y[ok], c=colour[ok], s=size, marker=".", linewidths=0,
               cmap=colour_scale("orbit").cmap, rasterized=True)


def plot_fig3(traj: xr.Dataset, section: xr.Dataset, fill: xr.Dataset | None = None
              ) -> Figure:
    """Fig. 3 redrawn: (a) projections of trajectories of (16) on (theta1, J1), the
    dot-dash box enlarged in (b); (c) the Poincare section theta2 = const at the
    separatrix energy, its box enlarged in (d).

    Parameters
    ----------
    traj : xarray.Dataset
        :func:`andoyer.analysis.paper.trajectories.fig3_trajectories`.
    section : xarray.Dataset
        :func:`andoyer.analysis.paper.trajectories.fig3_section` (first item).
    fill : xarray.Dataset, optional
        Its second item: the accessible region's boundary is drawn in (c).

    Returns
    -------
    matplotlib.figure.Figure
    """
    a = traj.attrs
    need = ("phi0", "J2", "zoom_theta1_min", "zoom_theta1_max", "zoom_J1_min", "zoom_J1_max")
    missing = [k for k in need if k not in a]
    if missing:
        raise ValueError(f"plot_fig3: traj lacks attrs {missing}; build it with "
                         "andoyer.analysis.paper.trajectories.fig3_trajectories")
    phi0, J2 = float(a["phi0"]), float(a["J2"])
    box = (float(a["zoom_theta1_min"]), float(a["zoom_theta1_max"]),
           float(a["zoom_J1_min"]), float(a["zoom_J1_max"]))
    with paper_style():
        fig = new_figure(2, 2, aspect=0.72)
        (ax_a, ax_b), (ax_c, ax_d) = np.asarray(fig.axes).reshape(2, 2)
        for ax, draw, zoom in ((ax_a, "traj", False), (ax_b, "traj", True),
                               (ax_c, "sec", False), (ax_d, "sec", True)):
            _separatrices(ax, phi0, J2)
            if draw == "traj":
                _trajectories(ax, traj)
            else:
                _points(ax, section, 2.5 if zoom else 0.6)
                if fill is not None and not zoom and "boundary_x" in fill:
                    ax.plot(np.mod(fill.boundary_x.values, 2 * np.pi),
                            fill.boundary_y.values, ",", color=COLOURS["boundary"])
            if zoom:
                ax.set_xlim(box[0], box[1])
                ax.set_ylim(box[2], box[3])
                ax.set_xticks([4 * phi0 - 0.2, 4 * phi0, 4 * phi0 + 0.2],
                              [r"$4\varphi_0-0.2$", r"$4\varphi_0$", r"$4\varphi_0+0.2$"])
            else:
                ax.set_xlim(-0.05, 2 * np.pi + 0.05)
                ax.set_ylim(-0.03 * J2, 1.05 * J2)
                angle_ticks(ax, 0.0, 2 * np.pi)
                ax.add_patch(Rectangle((box[0], box[2]), box[1] - box[0], box[3] - box[2],
                                       fill=False, ls="-.", lw=0.9, color="black", zorder=6))
            ax.set_xlabel(r"$\theta_1$")
            ax.set_ylabel(r"$J_1$")
        sa = section.attrs
        mu = float(a.get("body_mu", float("nan")))
        ax_a.set_title(rf"(a) trajectories of (16), $\mu = {mu:g}$, $M = 0$")
        ax_b.set_title("(b) the dot-dash box of (a), enlarged")
        ax_c.set_title(rf"(c) section $\theta_2 = {float(sa.get('section_value', 0.0)):g}$, "
                       rf"$h = {float(sa.get('h', float('nan'))):.5g}$")
        ax_d.set_title("(d) the dot-dash box of (c), enlarged")
    return fig
