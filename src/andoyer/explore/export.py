"""Export of what the explorer shows: a NetCDF dataset of the seeded orbits, and a PNG.

:func:`orbits_dataset` gathers every orbit of a :class:`~andoyer.explore.state.Session`
into one self-describing dataset (dims ``orbit, crossing``): the section points in all
charts as :func:`andoyer.integrate.poincare` returns them, the plane coordinates as
drawn, the seeds and their colours, and the provenance (body, h, M, section, engine,
tolerances, version). :func:`plane_figure` draws that dataset and the plane's
accessible region and separatrices in andoyer's figure style.
"""

from __future__ import annotations

import io
import os
import tempfile
from pathlib import Path

import numpy as np
import xarray as xr
from matplotlib.figure import Figure

from andoyer.explore.chains import ChainOverlay
from andoyer.explore.state import PlaneView, Session
from andoyer.integrate.results import provenance
from andoyer.notation import section_symbol

__all__ = ["orbits_dataset", "plane_figure", "netcdf_bytes", "png_bytes", "save"]


def orbits_dataset(session: Session) -> xr.Dataset:
    """The orbits on screen as one dataset (dims ``orbit, crossing``).

    Orbits still queued (no point yet) are left out; an orbit still running holds the
    crossings found so far. Shorter orbits are NaN-padded (``singular`` with -1).

    Parameters
    ----------
    session : Session
        The orbits on screen.

    Returns
    -------
    xarray.Dataset
        The variables of :func:`andoyer.integrate.poincare` (states, chart coordinates,
        integrals, crossing times ``t``, ``crossings_found``, ``y0``,
        ``section_residual``), ``x_plane``/``y_plane`` (the plotted coordinates,
        theta1 reduced as on screen), per orbit ``orbit_id``, ``colour``, ``status``,
        ``engine``, ``t_max``, the click ``seed_x``/``seed_y``, the solved action
        ``seed_action`` and ``root_index``/``n_roots``; attrs: provenance of the body,
        ``h``, ``M``, the section, crossings asked for, tolerances, package version.

        With no orbit on screen: no variables, ``n_orbits = 0`` and the same attrs.
    """
    s = session.settings
    orbits = [o for o in session.orbits.values() if o.ds is not None]
    if not orbits:
        return xr.Dataset(attrs=provenance(s.body, **s.attrs(), created_by="andoyer explore",
                                           n_orbits=0, x_plane_period=s.x_period))
    n = max(int(o.ds.sizes["crossing"]) for o in orbits if o.ds is not None)
    parts = []
    for o in orbits:
        assert o.ds is not None
        d = o.ds.reindex(crossing=np.arange(n), fill_value={"singular": -1})
        d = d.drop_vars("orbit", errors="ignore")
        xp = np.full(n, np.nan)
        yp = np.full(n, np.nan)
        xp[:o.x.size], yp[:o.y.size] = o.x, o.y
        d = d.assign(
            x_plane=(("crossing",), xp), y_plane=(("crossing",), yp),
            orbit_id=o.id, colour=o.colour, status=o.status,
            engine=str(o.ds.attrs.get("engine", "")),
            t_max=float(o.ds.attrs.get("t_max", np.nan)),
            n_crossings_requested=o.settings.n_crossings,
            seed_x=o.seed.x, seed_y=o.seed.y, seed_action=o.seed.action,
            root_index=o.seed.root_index, n_roots=o.seed.n_roots)
        d.attrs = {}
        parts.append(d)
    ds = xr.concat(parts, dim="orbit", coords="minimal", compat="override",
                   combine_attrs="drop")
    ds = ds.assign_coords(orbit=np.arange(len(parts)))
    p = s.plane
    sym = p.symbols
    chart_text = ("Hess variables (14)-(15)" if p.chart == "hess"
                  else "Andoyer-Deprit variables (5)-(7)")
    ds.attrs = provenance(
        s.body, **s.attrs(), created_by="andoyer explore",
        n_orbits=len(parts), x_plane_period=s.x_period,
        equations="Euler-Poisson equations (1) of Kyrychenko integrated in the regular "
                  "variables (G, gamma); seeds on H = h with the missing action solved "
                  f"from H in the {chart_text}")
    ds.x_plane.attrs.update(long_name=f"{sym[0]} of the section point as drawn"
                            + (f" (mod {s.x_period:.6g})" if p.coord == "theta2" else ""),
                            symbol=sym[0], units="rad")
    ds.y_plane.attrs.update(long_name=f"{sym[1]} of the section point as drawn",
                            symbol=sym[1], units="1")
    ds.seed_x.attrs.update(long_name=f"{sym[0]} of the clicked plane point", units="rad")
    ds.seed_y.attrs.update(long_name=f"{sym[1]} of the clicked plane point", units="1")
    ds.seed_action.attrs.update(long_name=f"{sym[2]} solved from H = h at the seed")
    ds.root_index.attrs.update(long_name=f"index of the solution {sym[2]} (0 = smallest)")
    ds.n_roots.attrs.update(long_name=f"solutions {sym[2]} of H = h above the seed")
    ds.colour.attrs.update(long_name="colour of the orbit on screen")
    ds.t_max.attrs.update(long_name="integration stopped at this time at the latest",
                          units="body time units")
    return ds


def netcdf_bytes(ds: xr.Dataset) -> bytes:
    """``ds`` as NetCDF-4 bytes, written by :func:`andoyer.io.write_netcdf`.

    Parameters
    ----------
    ds : xarray.Dataset
        The dataset to encode.
    """
    from andoyer.io import write_netcdf

    with tempfile.TemporaryDirectory(prefix="andoyer-explore-") as tmp:
        path = write_netcdf(ds, Path(tmp) / "orbits.nc")
        return path.read_bytes()


def plane_figure(ds: xr.Dataset | None, view: PlaneView, *, title: str | None = None,
                 chains: ChainOverlay | None = None) -> Figure:
    """The section plane as on screen: orbits in their colours, accessible-region
    boundary, unperturbed separatrices, the predicted island chains where the page
    shows them (andoyer's figure style).

    Parameters
    ----------
    ds : xarray.Dataset or None
        :func:`orbits_dataset` (``x_plane``, ``y_plane``, ``colour``); None or a dataset
        without orbits draws the plane alone.
    view : PlaneView
        Boundary, separatrices and ranges of the plane.
    title : str, optional
        Default: body, h, M and the section.
    chains : ChainOverlay, optional
        The predicted chains (:func:`andoyer.explore.chains.chain_overlay`): centre lines
        dashed, separatrices solid, stable points o, unstable points x.
    """
    from andoyer.plot.section import LABELS
    from andoyer.plot.style import COLOURS, angle_ticks, new_figure, paper_style

    s = view.settings
    with paper_style():
        fig = new_figure(width=6.4, aspect=0.7)
        ax = fig.axes[0]
        if ds is not None:
            for k in range(ds.sizes.get("orbit", 0)):
                o = ds.isel(orbit=k)
                ax.scatter(o.x_plane.values, o.y_plane.values, s=1.5, marker=".",
                           linewidths=0, color=str(o.colour.values), rasterized=True)
        for x, y in view.separatrices:
            ax.plot(x, y, color=COLOURS["separatrix"], lw=0.8, ls="--")
        if chains is not None:
            for x, y, c in zip(chains.centre_x, chains.centre_y, chains.colours, strict=True):
                ax.plot(x, y, color=c, lw=0.7, ls=(0, (4, 2)))
            for x, y, c in zip(chains.separatrix_x, chains.separatrix_y,
                               chains.separatrix_colours, strict=True):
                ax.plot(x, y, color=c, lw=0.5)
            kinds = np.array(chains.points_kind)
            colours = np.array(chains.points_colour)
            st, un = kinds == "stable", kinds == "unstable"
            if st.any():
                ax.scatter(chains.points_x[st], chains.points_y[st], s=12, marker="o",
                           facecolors="none", edgecolors=list(colours[st]), linewidths=0.7)
            if un.any():
                ax.scatter(chains.points_x[un], chains.points_y[un], s=12, marker="x",
                           c=list(colours[un]), linewidths=0.7)
        ax.plot(view.boundary_x, view.boundary_y, color=COLOURS["boundary"], lw=0.8)
        ax.set_xlim(*view.x_range)
        ax.set_ylim(*view.y_range)
        ax.set_xlabel(LABELS[s.plane.x])
        ax.set_ylabel(LABELS[s.plane.y])
        angle_ticks(ax, *view.x_range)
        sym = section_symbol(s.plane.coord)
        ax.set_title(title if title is not None else
                     f"{s.body.name or 'body'}: $h = {s.h:.8g}$, $M = {s.M:.6g}$, "
                     f"${sym} = {s.section.value:.4g}$")
    return fig


def png_bytes(fig: Figure, dpi: int = 150) -> bytes:
    """The figure as PNG bytes (Agg canvas, no pyplot).

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure.
    dpi : int, default 150
        Resolution.
    """
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi)
    return buf.getvalue()


def _write_bytes(data: bytes, path: str | os.PathLike[str]) -> Path:
    from andoyer.atomic import atomic_path

    out = Path(path)
    with atomic_path(out) as tmp:
        tmp.write_bytes(data)
    return out


def save(session: Session, view: PlaneView, path: str | os.PathLike[str]) -> list[Path]:
    """Write ``path`` (``.nc``) and the PNG beside it, atomically.

    Parameters
    ----------
    session : Session
        The orbits on screen.
    view : PlaneView
        The plane they are drawn on (accessible region, separatrices).
    path : str or os.PathLike
        The NetCDF file to write (``.nc``); the PNG goes beside it.
    """
    ds = orbits_dataset(session)
    out = Path(path)
    nc = _write_bytes(netcdf_bytes(ds), out.with_suffix(".nc"))
    png = _write_bytes(png_bytes(plane_figure(ds, view)), out.with_suffix(".png"))
    return [nc, png]
