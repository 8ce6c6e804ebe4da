"""Chaos maps: an indicator over a section's plane, drawn from a dataset (nothing computed).

Takes the dataset of :func:`andoyer.analysis.chaos.lyapunov.chaos_map`: the indicator as an
image over the plane, blank where the energy level does not meet the plane, the
accessible region's boundary on top, a colour bar named after the indicator (colour map,
range and label from :data:`andoyer.plot.style.SCALES`: pale regular, dark chaotic).
"""

from __future__ import annotations

from typing import Any

import numpy as np
import xarray as xr
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from andoyer.analysis.chaos.registry import INDICATORS, PANEL_INDICATORS
from andoyer.notation import ANGLES, section_symbol
from andoyer.plot.section import LABELS
from andoyer.plot.style import COLOURS, SCALES, WIDTH, angle_ticks, colour_scale, paper_style

__all__ = ["plot_chaos_map", "plot_indicators", "COLOUR_BAR_LABELS"]

#: Indicator -> colour-bar label (from :data:`andoyer.plot.style.SCALES`, the registry's
#: colour-mapped indicators).
COLOUR_BAR_LABELS: dict[str, str] = {k: SCALES[k].label for k in INDICATORS if k in SCALES}
_ANGLES = ANGLES
# FLI and the others: the colour range spans these percentiles of the data.
_PERCENTILES = (0.5, 99.0)


def _edges(c: np.ndarray, lo: float, hi: float) -> np.ndarray:
    """Cell edges of cell-centred coordinates ``c`` spanning ``[lo, hi]``."""
    mid = 0.5 * (c[1:] + c[:-1])
    return np.concatenate([[lo], mid, [hi]])


def plot_chaos_map(ds: xr.Dataset, ax: Axes | None = None, *, indicator: str | None = None,
                   vmin: float | None = None, vmax: float | None = None,
                   cmap: str | None = None, title: str | None = None) -> Axes:
    """Draw a chaos map: indicator image, accessible boundary, colour bar.

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`andoyer.analysis.chaos.lyapunov.chaos_map` (dims ``(y, x)`` of the plane,
        attrs ``plane_x``, ``plane_y``, ``plane_*_min/max``).
    ax : matplotlib Axes, optional
        Draw into it; by default a new figure in andoyer's style (no pyplot).
    indicator : {"fli", "megno", "mle"}, optional
        Default: ``attrs["indicator"]`` (``"fli"`` for ``"both"``).
    vmin, vmax : float, optional
        Colour range. Default for MEGNO ``[0, 8]`` (2 = quasi-periodic, the scale
        saturates at 4x that); for the others
        the 0.5 and 99th percentiles of the data (values beyond are drawn in the end
        colours, the colour bar says so).
    cmap : str, optional
        Colour map; default the indicator's (:data:`andoyer.plot.style.SCALES`: pale
        regular, dark chaotic).
    title : str, optional
        Default: body, section, h, M and t_end from the attrs.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax.figure`` is the figure to save with :func:`andoyer.plot.section.save_figure`.

    Examples
    --------
    >>> import xarray as xr
    >>> ds = xr.Dataset({"fli": (("J1", "theta1"), [[1.0, 2.0], [3.0, np.nan]]),
    ...                  "boundary_x": ("boundary_vertex", [0.0, 6.0]),
    ...                  "boundary_y": ("boundary_vertex", [1.0, 1.0])},
    ...                 coords={"J1": [0.25, 0.75], "theta1": [1.0, 4.0]},
    ...                 attrs={"plane_x": "theta1", "plane_y": "J1", "indicator": "fli"})
    >>> ax = plot_chaos_map(ds)
    >>> ax.get_xlabel()
    '$\\\\theta_1$'
    """
    a = ds.attrs
    xname, yname = str(a.get("plane_x", "")), str(a.get("plane_y", ""))
    if xname not in ds.coords or yname not in ds.coords:
        raise ValueError("plot_chaos_map: the dataset lacks the plane coordinates named by "
                         f"attrs plane_x = {xname!r}, plane_y = {yname!r}; pass the dataset "
                         "of andoyer.analysis.chaos.lyapunov.chaos_map")
    name = indicator or str(a.get("indicator", "fli"))
    if name == "both":
        name = "fli"
    if name not in ds:
        raise ValueError(f"plot_chaos_map: no variable {name!r} in the dataset (it holds "
                         f"{', '.join(str(v) for v in ds.data_vars)})")
    xs = np.asarray(ds[xname].values, dtype=float)
    ys = np.asarray(ds[yname].values, dtype=float)
    z = np.ma.masked_invalid(np.asarray(ds[name].transpose(yname, xname).values, dtype=float))
    x0 = float(a.get("plane_x_min", xs[0] - 0.5 * (xs[1] - xs[0]) if xs.size > 1 else xs[0]))
    x1 = float(a.get("plane_x_max", xs[-1] + 0.5 * (xs[-1] - xs[-2]) if xs.size > 1 else xs[0]))
    y0 = float(a.get("plane_y_min", ys[0] - 0.5 * (ys[1] - ys[0]) if ys.size > 1 else ys[0]))
    y1 = float(a.get("plane_y_max", ys[-1] + 0.5 * (ys[-1] - ys[-2]) if ys.size > 1 else ys[0]))
    scale = colour_scale(name) if name in SCALES else colour_scale("fli")
    if scale.vmin is not None and scale.vmax is not None:
        lo, hi = scale.vmin, scale.vmax
    elif z.count():
        # Percentiles: one thin chaotic layer must not flatten the regular structure.
        lo, hi = (float(v) for v in np.percentile(z.compressed(), _PERCENTILES))
        hi = hi if hi > lo else lo + 1.0
    else:
        lo, hi = 0.0, 1.0
    lo = lo if vmin is None else float(vmin)
    hi = hi if vmax is None else float(vmax)
    with paper_style():
        if ax is None:
            fig = Figure(figsize=(WIDTH, 0.75 * WIDTH), layout="constrained")
            ax = fig.add_subplot()
        mesh = ax.pcolormesh(_edges(xs, x0, x1), _edges(ys, y0, y1), z,
                             cmap=scale.cmap if cmap is None else cmap,
                             vmin=lo, vmax=hi, shading="flat", rasterized=True)
        fig_ = ax.get_figure(root=True)
        assert fig_ is not None
        bar = fig_.colorbar(mesh, ax=ax, extend=_extend(z, lo, hi))
        bar.set_label(scale.label if name in SCALES else name)
        if "boundary_x" in ds and "boundary_y" in ds:
            ax.plot(ds.boundary_x.values, ds.boundary_y.values, color=COLOURS["boundary"],
                    lw=0.8, label="boundary of the accessible region")
        ax.set_xlim(x0, x1)
        ax.set_ylim(y0, y1)
        ax.set_xlabel(LABELS.get(xname, xname))
        ax.set_ylabel(LABELS.get(yname, yname))
        if xname in _ANGLES and x1 - x0 >= np.pi:  # narrower windows keep plain numbers
            angle_ticks(ax, x0, x1)
            ax.set_xlim(x0, x1)
        ax.set_title(_title(a, name) if title is None else title)
    return ax


def _extend(z: np.ma.MaskedArray, lo: float, hi: float) -> str:
    """Colour-bar extension arrows for data beyond the colour range."""
    below = bool(z.count()) and float(z.min()) < lo
    above = bool(z.count()) and float(z.max()) > hi
    return {(False, False): "neither", (True, False): "min", (False, True): "max",
            (True, True): "both"}[(below, above)]


def _title(a: dict[Any, Any], name: str) -> str:
    parts = []
    if a.get("body_name"):
        mu = a.get("body_mu")
        parts.append(f"{a['body_name']}" + (f" ($\\mu = {float(mu):.4g}$)" if mu is not None
                                            else ""))
    coord = a.get("section_coord")
    if coord is not None and "section_value" in a:
        sym = section_symbol(str(coord))
        parts.append(f"${sym} = {float(a['section_value']):.4g}$")
    for key in ("h", "M"):
        if key in a:
            parts.append(f"${key} = {float(a[key]):.6g}$")
    if "t_end" in a:
        parts.append(f"$t = {float(a['t_end']):g}$")
    return (INDICATORS[name].title if name in INDICATORS else name) + " map: " \
        + ", ".join(parts)


def plot_indicators(ds: xr.Dataset, *, width: float = WIDTH, title: str | None = None
                    ) -> Figure:
    """FLI and MEGNO of each orbit against time, from
    :func:`andoyer.analysis.chaos.lyapunov.indicators` (two panels; MEGNO's regular value 2
    dashed).

    Parameters
    ----------
    ds : xarray.Dataset
        With ``fli`` and ``megno`` over ``(orbit, time)``.
    width : float
        Figure width, inches.
    title : str, optional
        Figure title (default: the tangent space of the dataset).

    Returns
    -------
    matplotlib.figure.Figure

    Examples
    --------
    >>> t = np.linspace(0.0, 10.0, 11)
    >>> ds = xr.Dataset({"fli": (("orbit", "time"), [np.log1p(t)]),
    ...                  "megno": (("orbit", "time"), [np.full(11, 2.0)])},
    ...                 coords={"time": t}, attrs={"tangent": "leaf"})
    >>> [ax.get_ylabel()[:4] for ax in plot_indicators(ds).axes]
    ['FLI ', 'MEGN']
    """
    from andoyer.plot.style import new_figure

    with paper_style():
        fig = new_figure(1, len(PANEL_INDICATORS), width=width, aspect=0.7)
        for ax, name in zip(fig.axes, PANEL_INDICATORS, strict=True):
            for k in range(ds.sizes.get("orbit", 1)):
                v = ds[name].isel(orbit=k) if "orbit" in ds[name].dims else ds[name]
                ax.plot(ds.time.values, v.values, lw=1.0, label=f"orbit {k}")
            ax.set_xlabel("time $t$")
            ax.set_ylabel(INDICATORS[name].label)
            regular = INDICATORS[name].regular
            if regular is not None:
                ax.axhline(regular, color="0.5", lw=0.8, ls="--",
                           label=f"regular: {regular:g}")
        if ds.sizes.get("orbit", 1) > 1:
            fig.axes[0].legend(fontsize=6, frameon=False)
        fig.suptitle(title or f"chaos indicators (tangent space "
                              f"{ds.attrs.get('tangent', '?')})", fontsize=8, wrap=True)
    return fig
