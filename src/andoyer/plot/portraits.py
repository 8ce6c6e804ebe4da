"""Figures 1 and 2 of [1]_: unperturbed phase portraits, drawn from datasets only.

The datasets come from :func:`andoyer.analysis.unperturbed.portraits.portrait_andoyer` (plane
``(l, L)``) and :func:`andoyer.analysis.unperturbed.portraits.portrait_hess` (plane
``(theta1, J1)``); these functions compute nothing. Artists carry a ``gid``
(``"contour"``, ``"separatrix"``, ``"separatrix-hess"``, ``"singular"``,
``"fixed-point-<type>"``, ``"label"``) so that tests and users can find them.

References
----------
.. [1] V. V. Kyrychenko, "Andoyer-Deprit variables use to the Hess gyroscope phase
   trajectories exploring", National Aviation University, Kyiv (``andoyer.cite("paper")``).
"""

from __future__ import annotations

import numpy as np
import xarray as xr
from matplotlib.axes import Axes
from matplotlib.figure import Figure
from matplotlib.lines import Line2D

from andoyer.plot.style import COLOURS, MARKERS, angle_ticks, new_figure, paper_style

__all__ = ["plot_fig1", "plot_fig2", "draw_portrait"]

_REQUIRED = ("H0", "levels", "level_is_separatrix", "separatrix_kind", "separatrix_hess",
             "fp_type", "annotation_text")


def _plane(ds: xr.Dataset, what: str) -> tuple[str, str]:
    x, y = ds.attrs.get("plane_x"), ds.attrs.get("plane_y")
    if x is None or y is None:
        raise ValueError(f"{what}: the dataset has no attrs plane_x/plane_y; make it with "
                         "portrait_andoyer() or portrait_hess()")
    missing = [v for v in (*_REQUIRED, str(x), str(y), f"separatrix_{x}", f"fp_{x}")
               if v not in ds.variables]
    if missing:
        raise ValueError(f"{what} lacks the portrait variables {missing}; make it with "
                         "portrait_andoyer() or portrait_hess()")
    return str(x), str(y)


def draw_portrait(ax: Axes, ds: xr.Dataset, *, mark_hess: bool = True,
                  labels: bool = True) -> None:
    """Draw one unperturbed portrait on ``ax``.

    Level curves of H0 (ordinary levels, grey), the separatrices (red; the one the
    Hess solutions approach bold dotted black when ``mark_hess``), the singular lines
    (grey), the fixed points by chart type (:data:`andoyer.plot.style.MARKERS`) and,
    with ``labels``, the digits 1-4 of the uniform rotations.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw on.
    ds : xarray.Dataset
        From :func:`andoyer.analysis.unperturbed.portraits.portrait_andoyer` or
        :func:`~andoyer.analysis.unperturbed.portraits.portrait_hess`.
    mark_hess : bool, default True
        Draw the separatrix the Hess solutions approach bold dotted black.
    labels : bool, default True
        Write the fixed points' digits of Fig. 2.
    """
    x, y = _plane(ds, "draw_portrait")
    ordinary = ds.levels.values[~ds.level_is_separatrix.values.astype(bool)]
    if ordinary.size:
        cs = ax.contour(ds[x].values, ds[y].values, ds.H0.values, levels=np.sort(ordinary),
                        colors=COLOURS["orbit"], linewidths=0.5)
        cs.set_gid("contour")
    for v in ds[f"singular_{y}"].values:
        ax.axhline(float(v), color=COLOURS["singular"], lw=1.4, ls="-", zorder=2,
                   gid="singular")
    kinds = ds.separatrix_kind.values
    hess = ds.separatrix_hess.values.astype(bool)
    for k in range(ds.sizes["curve"]):
        if kinds[k] != "separatrix":
            continue
        qx, py = ds[f"separatrix_{x}"].values[k], ds[f"separatrix_{y}"].values[k]
        if mark_hess and hess[k]:
            ax.plot(qx, py, color=COLOURS["hess"], lw=2.4, ls=":", zorder=4,
                    gid="separatrix-hess")
        else:
            ax.plot(qx, py, color=COLOURS["separatrix"], lw=1.2, zorder=3, gid="separatrix")
    period = float(ds.attrs.get("angle_period", 2 * np.pi))
    types = ds.fp_type.values
    qf, pf = ds[f"fp_{x}"].values, ds[f"fp_{y}"].values
    # A point at q = 0 is drawn at q = period too (the right edge is the same line).
    edge = qf == 0.0
    types, qf, pf = (np.concatenate([types, types[edge]]),
                     np.concatenate([qf, np.full(int(edge.sum()), period)]),
                     np.concatenate([pf, pf[edge]]))
    for kind, style in MARKERS.items():
        sel = types == kind
        if sel.any():
            ax.scatter(qf[sel], pf[sel], clip_on=False, gid=f"fixed-point-{kind}", **style)
    if labels:
        for qv, pv, text, va in zip(ds[f"annotation_{x}"].values, ds[f"annotation_{y}"].values,
                                    ds.annotation_text.values, ds.annotation_va.values,
                                    strict=True):
            ax.text(float(qv), float(pv), str(text), ha="center", va=str(va), fontsize=9,
                    fontweight="bold", gid="label", zorder=6)
    ax.set_xlim(0.0, period)
    lo, hi = float(ds[y].values[0]), float(ds[y].values[-1])
    pad = 0.03 * (hi - lo)
    ax.set_ylim(lo - pad, hi + pad)
    angle_ticks(ax, 0.0, period)
    ax.set_xlabel(str(ds.attrs.get("x_label", x)))
    ax.set_ylabel(str(ds.attrs.get("y_label", y)))


def _legend(ax: Axes, ds_list: list[xr.Dataset], mark_hess: bool,
            anchor: tuple[float, float] | None = (0.5, -0.2)) -> None:
    """The portrait's legend under the axes (``anchor`` in axes coordinates), or with
    ``anchor=None`` under the whole figure (a figure of several panels: the legend then
    takes no room from one panel's column)."""
    handles = [Line2D([], [], color=COLOURS["separatrix"], lw=1.2, label="separatrix"),
               Line2D([], [], color=COLOURS["singular"], lw=1.4, label="singular line")]
    if mark_hess and any(bool(d.separatrix_hess.any()) for d in ds_list):
        handles.insert(1, Line2D([], [], color=COLOURS["hess"], lw=2.4, ls=":",
                                 label=r"Hess, $\mu \to 0$"))
    kinds = set().union(*(set(d.fp_type.values.tolist()) for d in ds_list))
    for kind in ("centre", "saddle", "degenerate"):
        if kind in kinds:
            st = MARKERS[kind]
            handles.append(Line2D([], [], ls="", marker=st["marker"], markersize=5,
                                  markerfacecolor=st.get("facecolors", st.get("color")),
                                  markeredgecolor=st.get("edgecolors", st.get("color")),
                                  label=kind))
    fig = ax.get_figure(root=True)
    if anchor is None and fig is not None:
        fig.legend(handles=handles, loc="outside lower center", ncol=5)
    else:
        ax.legend(handles=handles, loc="upper center", bbox_to_anchor=anchor, ncol=3)


def plot_fig1(ds: xr.Dataset) -> Figure:
    """Fig. 1: the phase portrait of the unperturbed system (9) in ``(l, L)``.

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`andoyer.analysis.unperturbed.portraits.portrait_andoyer`.

    Returns
    -------
    matplotlib.figure.Figure
        Level curves of H0, the separatrices, the singular lines ``L = +-G0`` and the
        fixed points marked by type.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> from andoyer.analysis.unperturbed.portraits import portrait_andoyer
    >>> fig = plot_fig1(portrait_andoyer(RigidBody.paper(), n=(33, 17), n_curve=11))
    >>> len(fig.axes)
    1
    """
    _plane(ds, "plot_fig1")
    with paper_style():
        fig = new_figure(1, 1, width=4.6, aspect=0.62)
        ax = fig.axes[0]
        draw_portrait(ax, ds, mark_hess=False, labels=False)
        G0 = ds.attrs.get("G_action", 1.0)
        ax.set_title(rf"Unperturbed system (9), $G_0 = {float(G0):g}$")
        _legend(ax, [ds], mark_hess=False)
    return fig


def plot_fig2(ds_andoyer: xr.Dataset, ds_hess: xr.Dataset) -> Figure:
    """Fig. 2: the unperturbed Euler-Poinsot portrait of a Hess body, (a) in ``(l, L)``,
    (b) in ``(theta1, J1)``.

    Separatrices in red, the separatrix ``theta1 = 0`` (``l = -phi0 mod pi``) that the
    Hess solutions approach as ``mu -> 0`` bold dotted black, singular lines grey, the
    uniform rotations labelled 1-4 (convention in ``attrs["label_convention"]``; the
    caption text is ``attrs["caption"]``), fixed points marked by chart type.

    Parameters
    ----------
    ds_andoyer, ds_hess : xarray.Dataset
        From :func:`~andoyer.analysis.unperturbed.portraits.portrait_andoyer` and
        :func:`~andoyer.analysis.unperturbed.portraits.portrait_hess` of the same body.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> from andoyer.analysis.unperturbed.portraits import portrait_andoyer, portrait_hess
    >>> body = RigidBody.paper()
    >>> fig = plot_fig2(portrait_andoyer(body, n=(33, 17), n_curve=11),
    ...                 portrait_hess(body, n=(33, 9), n_curve=11))
    >>> [ax.get_title() for ax in fig.axes]
    ['(a) Andoyer-Deprit variables', '(b) variables (14)']
    """
    _plane(ds_andoyer, "plot_fig2 (a)")
    _plane(ds_hess, "plot_fig2 (b)")
    with paper_style():
        fig = new_figure(1, 2, width=6.8, aspect=0.8)
        ax_a, ax_b = fig.axes
        draw_portrait(ax_a, ds_andoyer)
        draw_portrait(ax_b, ds_hess)
        ax_a.set_title("(a) Andoyer-Deprit variables")
        ax_b.set_title("(b) variables (14)")
        _legend(ax_a, [ds_andoyer, ds_hess], mark_hess=True, anchor=None)
    return fig
