"""Poincare-section portraits: datasets in, matplotlib figures out (nothing computed here).

Figures are built with :class:`matplotlib.figure.Figure` directly, not through pyplot,
so that no display and no global backend are needed; PNG and PDF are written by the
Agg and PDF canvases.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import xarray as xr
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from andoyer.atomic import atomic_path
from andoyer.notation import ANGLES, COORDINATES, SECTION_PLANES, section_symbol
from andoyer.plot.style import colour_scale

__all__ = ["plot_section", "save_figure", "PLANES", "LABELS"]

#: Section coordinate (code or storage name) -> storage names of the plane (x, y),
#: from the one definition :data:`andoyer.notation.SECTION_PLANES`.
PLANES: dict[str, tuple[str, str]] = {
    **{k: (p.x, p.y) for k, p in SECTION_PLANES.items()},
    **{p.storage[1]: (p.x, p.y) for p in SECTION_PLANES.values()},
}

#: Storage name -> axis label with the paper's symbol (mathtext), from :mod:`andoyer.notation`.
LABELS: dict[str, str] = {c.storage: c.label for c in COORDINATES if c.symbol}
_ANGLES = ANGLES



def _plane(ds: xr.Dataset, what: str) -> tuple[str, str]:
    """The plane's variable names, from attrs ``plane_x``/``plane_y`` or ``section_coord``."""
    if "plane_x" in ds.attrs and "plane_y" in ds.attrs:
        x, y = str(ds.attrs["plane_x"]), str(ds.attrs["plane_y"])
    else:
        coord = ds.attrs.get("section_coord")
        if coord not in PLANES:
            raise ValueError(
                f"{what}: cannot tell the section's plane from attrs section_coord = "
                f"{coord!r}; portraits are drawn for 'g' (plane (l, L)) and 'theta2' "
                "(plane (theta1, J1)) sections")
        x, y = PLANES[str(coord)]
    missing = [v for v in (x, y) if v not in ds.variables]
    if missing:
        raise ValueError(f"{what} lacks the plane variables {missing}")
    return x, y


def _angle_ticks(ax: Axes, lo: float, hi: float) -> None:
    """Ticks at multiples of pi/2 on an angle axis."""
    k = np.arange(np.ceil(lo / (np.pi / 2) - 1e-9), np.floor(hi / (np.pi / 2) + 1e-9) + 1)
    names = {0: "0", 1: r"$\pi/2$", 2: r"$\pi$", 3: r"$3\pi/2$", 4: r"$2\pi$"}

    def name(i: int) -> str:
        if i in names:
            return names[i]
        return rf"${i // 2}\pi$" if i % 2 == 0 else rf"${i}\pi/2$"

    ax.set_xticks(k * np.pi / 2, [name(int(i)) for i in k])


def plot_section(ds: xr.Dataset, *, ax: Axes | None = None, boundary: xr.Dataset | None = None,
                 title: str | None = None) -> Axes:
    """Draw the points of a Poincare section, one colour per orbit.

    Parameters
    ----------
    ds : xarray.Dataset
        Section points with dim ``orbit`` (and usually ``crossing``), holding the plane
        coordinates (``l_angle``, ``L_action`` for ``g`` sections; ``theta1``, ``J1`` for
        ``theta2`` sections) and ``attrs["section_coord"]`` (or ``plane_x``/``plane_y``
        attrs naming the plane variables). NaN points (padding) are skipped. The
        dataset of :func:`andoyer.integrate.fill.fill_section` (initial states) works too.
    ax : matplotlib Axes, optional
        Draw into it; by default a new 6 x 4.5 in figure (no pyplot) is made.
    boundary : xarray.Dataset, optional
        A :func:`~andoyer.integrate.fill.fill_section` dataset of the same section: its
        accessible-region boundary (``boundary_x``, ``boundary_y``) is drawn and the
        axes span its plane. When that plane is ``theta1`` in ``[0, 2 pi)`` (an
        ``M = 0`` Hess section, where H is 2 pi-periodic in theta1), ``theta1`` is
        shown mod 2 pi as in the paper's Fig. 3.
    title : str, optional
        Default: the section, energy and area constant found in the attrs.

    Returns
    -------
    matplotlib.axes.Axes
        ``ax.figure`` is the figure to save with :func:`save_figure`.
    """
    xname, yname = _plane(ds, "plot_section: the section dataset")
    if ax is None:
        fig = Figure(figsize=(6.0, 4.5), layout="constrained")
        ax = fig.add_subplot()
    x = np.asarray(ds[xname].values, dtype=float)
    y = np.asarray(ds[yname].values, dtype=float)
    # One colour per orbit: the orbit index broadcast over the other dims.
    orbit = ds[xname].dims.index("orbit") if "orbit" in ds[xname].dims else None
    if orbit is None:
        colour = np.zeros(x.shape)
    else:
        shape = [1] * x.ndim
        shape[orbit] = x.shape[orbit]
        colour = np.broadcast_to(np.arange(x.shape[orbit]).reshape(shape), x.shape)
    period = None if boundary is None else _period_of(boundary)
    if xname == "theta1" and period is not None and np.isclose(period, 2 * np.pi):
        # The fill plane of an M = 0 section is theta1 mod 2 pi (the period of H there);
        # the states at theta1 and theta1 + 2 pi are symmetric images, drawn as one.
        x = np.mod(x, 2 * np.pi)
    ok = np.isfinite(x) & np.isfinite(y)
    n_orbits = max(int(colour.max()) + 1 if colour.size else 1, 1)
    ax.scatter(x[ok], y[ok], c=colour[ok], s=1.5, marker=".", linewidths=0,
               cmap=colour_scale("orbit").cmap, vmin=0, vmax=max(n_orbits - 1, 1), rasterized=True)
    if boundary is not None:
        bx, by = _plane(boundary, "plot_section: the boundary dataset")
        if (bx, by) != (xname, yname):
            raise ValueError(f"plot_section: the boundary is drawn in the plane ({bx}, {by}) "
                             f"but the section in ({xname}, {yname}); fill the same section")
        if "boundary_x" not in boundary or "boundary_y" not in boundary:
            raise ValueError("plot_section: boundary must be a fill_section dataset "
                             "(variables boundary_x, boundary_y)")
        ax.plot(boundary.boundary_x.values, boundary.boundary_y.values, color="black",
                lw=0.8, label="boundary of the accessible region")
        if "plane_x_min" in boundary.attrs:
            ax.set_xlim(boundary.attrs["plane_x_min"], boundary.attrs["plane_x_max"])
            ax.set_ylim(boundary.attrs["plane_y_min"], boundary.attrs["plane_y_max"])
    ax.set_xlabel(LABELS.get(xname, xname))
    ax.set_ylabel(LABELS.get(yname, yname))
    if xname in _ANGLES:
        lo, hi = ax.get_xlim()
        _angle_ticks(ax, lo, hi)
        ax.set_xlim(lo, hi)
    ax.set_title(_default_title(ds) if title is None else title)
    return ax


def _period_of(boundary: xr.Dataset) -> float | None:
    a = boundary.attrs
    if "plane_x_min" not in a or "plane_x_max" not in a:
        return None
    return float(a["plane_x_max"]) - float(a["plane_x_min"])


def _default_title(ds: xr.Dataset) -> str:
    a = ds.attrs
    parts = []
    coord = a.get("section_coord")
    if coord is not None and "section_value" in a:
        parts.append(f"${section_symbol(str(coord))} = {float(a['section_value']):.4g}$")
    for key, sym in (("h", "h"), ("M", "M")):
        if key in a:
            parts.append(f"${sym} = {float(a[key]):.6g}$")
    body = a.get("body_name")
    if body:
        parts.append(f"body: {body}")
    return "Poincaré section" + (": " + ", ".join(parts) if parts else "")


def save_figure(fig: Figure, path: str | os.PathLike[str], *, pdf: bool = False,
                dpi: int = 150) -> list[Path]:
    """Write ``fig`` as PNG (and PDF) atomically: a temporary file in the same folder, renamed.

    Parameters
    ----------
    fig : matplotlib Figure
        E.g. ``plot_section(ds).figure``.
    path : path-like
        The PNG file; its suffix is replaced by ``.png`` (and ``.pdf`` for the PDF copy).
    pdf : bool, default False
        Also write a PDF next to the PNG.
    dpi : int, default 150
        Resolution of the PNG.

    Returns
    -------
    list of Path
        The files written. Nothing is left behind, and no existing file is touched, if
        writing fails.
    """
    target = Path(path)
    out = []
    engine = fig.get_layout_engine()
    try:
        for fmt in ("png", "pdf") if pdf else ("png",):
            final = target.with_suffix("." + fmt)
            final.parent.mkdir(parents=True, exist_ok=True)
            with atomic_path(final) as tmp:
                fig.savefig(tmp, format=fmt, dpi=dpi)
            out.append(final)
            if engine is not None:
                # the PDF takes the PNG's layout: the same page, one layout pass fewer
                # (a fifth to a third of a report figure's saving time)
                fig.set_layout_engine("none")
    finally:
        if engine is not None:
            fig.set_layout_engine(engine)
    return out
