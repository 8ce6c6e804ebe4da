"""An atlas of a parameter scan: a grid of small Poincare sections or chaos maps.

Rows and columns run over two swept parameters of a scan store
(:mod:`andoyer.scan`); each panel is labelled with its parameter values. Datasets in,
a :class:`matplotlib.figure.Figure` out; nothing is computed here.
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from typing import Any

import matplotlib as mpl
import numpy as np
import xarray as xr
from matplotlib import patheffects
from matplotlib.figure import Figure

from andoyer.analysis.chaos.registry import MAP_INDICATORS
from andoyer.notation import ANGLES, section_symbol
from andoyer.plot.section import LABELS, PLANES
from andoyer.plot.style import angle_ticks, colour_bar, colour_scale, new_figure, paper_style

__all__ = ["plot_atlas", "plot_border", "border_panel", "check_critical_mu", "SYMBOLS"]

#: Storage name of a swept parameter -> its symbol (mathtext).
SYMBOLS = {"mu": r"\mu", "epsilon": r"\epsilon", "h_level": "h", "M_level": "M", "A": "A",
           "B": "B", "C": "C"}
_INDICATORS = MAP_INDICATORS
_ANGLES = ANGLES


def _swept(ds: xr.Dataset) -> list[str]:
    if "scan_dims" not in ds.attrs:
        raise ValueError("plot_atlas: the dataset is not a scan store (no scan_dims attr); "
                         "open the store written by andoyer scan")
    return [str(d) for d in json.loads(str(ds.attrs["scan_dims"]))]


def _label(dim: str, value: float) -> str:
    return f"${SYMBOLS.get(dim, dim)} = {value:.4g}$"


def _section_plane(ds: xr.Dataset) -> tuple[str, str]:
    coord = str(ds.attrs.get("section_coord", ""))
    if coord not in PLANES:
        raise ValueError(f"plot_atlas: cannot draw sections of {coord!r}; sections of "
                         "'g' and 'theta2' are drawn")
    return PLANES[coord]


def _indicator(ds: xr.Dataset, swept: list[str]) -> str:
    for name in _INDICATORS:
        if name in ds.data_vars:
            return name
    for key, v in ds.data_vars.items():
        if v.dtype.kind == "f" and v.ndim == len(swept) + 2:
            return str(key)
    raise ValueError(f"plot_atlas: no chaos indicator ({', '.join(_INDICATORS)}) in the "
                     "dataset")


def _panel_section(ax: Any, p: xr.Dataset, x: str, y: str, fold: bool) -> None:
    X = np.asarray(p[x].values, dtype=float)
    Y = np.asarray(p[y].values, dtype=float)
    if fold:  # at M = 0, H is 2 pi-periodic in theta1: fold the double cover (Fig. 3)
        X = np.mod(X, 2 * np.pi)
    colour = np.broadcast_to(np.arange(X.shape[0])[:, None], X.shape)
    ok = np.isfinite(X) & np.isfinite(Y)
    # Dots small enough for thousands of points, visible for a few dozen.
    size = float(np.clip(2000.0 / max(int(ok.sum()), 1), 0.4, 4.0))
    ax.scatter(X[ok], Y[ok], c=colour[ok], s=size, marker=".", linewidths=0,
               cmap=colour_scale("orbit").cmap, vmin=0, vmax=max(X.shape[0] - 1, 1),
               rasterized=True)
    if x in _ANGLES:
        hi = 2 * np.pi if fold or x != "theta1" else 4 * np.pi
        ax.set_xlim(0.0, hi)
        angle_ticks(ax, 0.0, hi)


def _panel_map(ax: Any, p: xr.Dataset, name: str, norm: tuple[float, float]) -> Any:
    v = p[name]
    dy, dx = (str(d) for d in v.dims)  # chaos maps are (y, x), named after the plane
    xs = p[f"{dx}_values"].values if f"{dx}_values" in p else np.arange(v.shape[1])
    ys = p[f"{dy}_values"].values if f"{dy}_values" in p else np.arange(v.shape[0])
    mesh = ax.pcolormesh(xs, ys, np.asarray(v.values, dtype=float), shading="nearest",
                         cmap=colour_scale(name).cmap, vmin=norm[0], vmax=norm[1],
                         rasterized=True)
    if dx in _ANGLES:
        angle_ticks(ax, float(xs.min()), float(xs.max()))
    return mesh


def _heading(ds: xr.Dataset, task: str, fixed: Mapping[str, float]) -> str:
    a = ds.attrs
    parts = [f"body {a.get('body_name', '?')}"]
    if "section_coord" in a:
        sym = section_symbol(str(a["section_coord"]))
        what = "sections" if task == "section" else "chaos maps on"
        parts.append(f"{what} ${sym} = {float(a['section_value']):.4g}$")
    for key, dim in (("h_level", "h_level"), ("M_level", "M_level")):
        if key in a:
            parts.append(_label(dim, float(a[key])))
    parts += [_label(d, v) for d, v in fixed.items()]
    return ", ".join(parts)


def plot_atlas(ds: xr.Dataset, *, rows: str | None = None, cols: str | None = None,
               select: Mapping[str, float] | None = None, width: float = 7.0) -> Figure:
    """Grid of panels, one per pair of values of two swept parameters.

    Parameters
    ----------
    ds : xarray.Dataset
        A scan store (``xarray.open_zarr(store)``) of a ``section`` or ``chaos_map`` task.
    rows, cols : str, optional
        Swept dims along the rows and the columns (storage names: ``mu``, ``h_level``,
        ``M_level``, ``A``, ``B``, ``C``). Default: the first two swept dims (one row if
        only one is swept).
    select : mapping, optional
        Values of the other swept dims (nearest grid value); default: their first value.
    width : float
        Figure width in inches.

    Returns
    -------
    matplotlib.figure.Figure
        Sections as points (one colour per orbit; ``theta1`` folded mod 2 pi at
        ``M = 0``), chaos maps as images; points not done yet, or empty, are marked.
    """
    swept = _swept(ds)
    rows = rows if rows is not None else (swept[0] if len(swept) > 1 else None)
    cols = cols if cols is not None else (swept[1] if len(swept) > 1 else swept[0])
    for name, d in (("rows", rows), ("cols", cols)):
        if d is not None and d not in swept:
            raise ValueError(f"plot_atlas: {name} = {d!r} is not a swept dim "
                             f"({', '.join(swept)})")
    if rows == cols:
        raise ValueError(f"plot_atlas: rows and cols are both {rows!r}")
    sel = dict(select or {})
    unknown = [k for k in sel if k not in swept or k in (rows, cols)]
    if unknown:
        raise ValueError(f"plot_atlas: select {unknown[0]!r}: choose among the swept dims "
                         f"other than rows and cols: "
                         f"{', '.join(d for d in swept if d not in (rows, cols)) or 'none'}")
    fixed = {d: sel.get(d, float(ds[d].values[0])) for d in swept if d not in (rows, cols)}
    sub = ds.sel(fixed, method="nearest") if fixed else ds
    task = str(ds.attrs.get("scan_task", "section"))
    nr = 1 if rows is None else sub.sizes[rows]
    nc = sub.sizes[cols]
    if task == "section":
        x, y = _section_plane(ds)
    else:
        ind = _indicator(ds, swept)
        vals = sub[ind].values
        finite = vals[np.isfinite(vals)]
        norm = ((float(np.percentile(finite, 1)), float(np.percentile(finite, 99)))
                if finite.size else (0.0, 1.0))
    with paper_style():
        fig = new_figure(nr, nc, width=width, aspect=0.8)
        axes = np.asarray(fig.axes).reshape(nr, nc)
        image = None
        for i in range(nr):
            for j in range(nc):
                ax = axes[i, j]
                at = {cols: j} if rows is None else {rows: i, cols: j}
                p = sub.isel(at)
                title = ", ".join(_label(d, float(p[d].values))
                                  for d in ((cols,) if rows is None else (rows, cols)))
                ax.set_title(title, fontsize=7.5, pad=2)
                if not bool(p["done"].values) or bool(p["empty"].values):
                    ax.text(0.5, 0.5, "empty" if bool(p["empty"].values) else "not done",
                            transform=ax.transAxes, ha="center", va="center",
                            fontsize=7, color="0.5")
                    continue
                if task == "section":
                    M = float(p["M_level"].values) if "M_level" in p.coords else float(
                        ds.attrs.get("M_level", np.nan))
                    _panel_section(ax, p, x, y, fold=(x == "theta1" and M == 0.0))
                else:
                    image = _panel_map(ax, p, ind, norm)
                ax.tick_params(labelsize=6.5)
        if task == "section":
            for ax in axes[-1]:
                ax.set_xlabel(LABELS.get(x, x))
            for ax in axes[:, 0]:
                ax.set_ylabel(LABELS.get(y, y))
        else:
            dy, dx = (str(d) for d in ds[ind].dims[-2:])
            for ax in axes[-1]:
                ax.set_xlabel(LABELS.get(dx, dx))
            for ax in axes[:, 0]:
                ax.set_ylabel(LABELS.get(dy, dy))
            if image is not None:
                fig.colorbar(image, ax=list(axes.ravel()), shrink=0.8,
                             label=colour_scale(ind).label)
        fig.suptitle(_heading(ds, task, {d: float(sub[d].values) for d in fixed}),
                     fontsize=8)
    return fig


def _grid_edges(v: np.ndarray) -> np.ndarray:
    """Cell edges around grid values (uniform or not) for ``pcolormesh``."""
    v = np.asarray(v, dtype=float)
    if v.size == 1:
        return np.array([v[0] - 0.5, v[0] + 0.5]) if v[0] == 0 else v[0] * np.array([0.5, 1.5])
    mid = 0.5 * (v[1:] + v[:-1])
    return np.concatenate([[2 * v[0] - mid[0]], mid, [2 * v[-1] - mid[-1]]])


def _border_dims(ds: xr.Dataset) -> list[str]:
    if "chaotic_fraction" not in ds:
        raise ValueError("plot_border: no chaotic_fraction in the dataset: give a "
                         "chaos_border scan store or chaos_border_map's result")
    if "scan_dims" in ds.attrs:
        if str(ds.attrs.get("scan_task")) != "chaos_border":
            raise ValueError("plot_border: the store is not of a chaos_border scan "
                             f"(scan_task = {ds.attrs.get('scan_task')!r}); use plot_atlas")
        return _swept(ds)
    return [str(d) for d in ds["chaotic_fraction"].dims]


#: Annotations of a heat map's cells: largest and smallest font size (points).
_CELL_FONT = (7.0, 4.5)
#: Tick labels of a heat map (points).
_TICK_FONT = 6.5


def _cells_points(ax: Any, nx: int, ny: int) -> tuple[float, float]:
    """Estimated width and height (points) of one cell of an ``nx x ny`` heat map in
    ``ax``: about 60 % of the axes' share of the figure is left to the cells once labels
    and colour bars are placed."""
    fig = ax.get_figure(root=True)
    width, height = fig.get_size_inches()
    spec = ax.get_subplotspec()
    if spec is not None:
        rows, cols = spec.get_gridspec().get_geometry()
        width *= len(spec.colspan) / cols
        height *= len(spec.rowspan) / rows
    return 0.6 * 72.0 * width / max(nx, 1), 0.6 * 72.0 * height / max(ny, 1)


def _annotation_size(ax: Any, nx: int, ny: int, ranges: bool) -> tuple[float, bool] | None:
    """Font size of the cell annotations of an ``nx x ny`` heat map in ``ax``, and whether
    the bracketed range fits below the value; ``None`` where not even the value fits.

    Text of about 0.6 em per character, lines 1.3 em apart, must fit inside 85 % of a
    cell (:func:`_cells_points`).
    """
    cell_w, cell_h = (0.85 * v for v in _cells_points(ax, nx, ny))
    for lines, chars in (((2, 12),) if ranges else ()) + ((1, 4),):
        size = min(_CELL_FONT[0], cell_w / (0.6 * chars), cell_h / (1.3 * lines))
        if size >= _CELL_FONT[1]:
            return size, lines == 2
    return None


def _tick_step(cell: float, labels: list[str], vertical: bool) -> int:
    """Every how many cells a tick label fits (labels ``_TICK_FONT`` points high and
    0.6 em per character wide, with 1 em between them)."""
    need = _TICK_FONT * (1.6 if vertical else 0.6 * max(map(len, labels), default=1) + 1.0)
    return max(1, int(np.ceil(need / max(cell, 1e-9))))


def check_critical_mu(curve: xr.Dataset) -> xr.Dataset:
    """Check that ``curve`` is a ``mu_c(h)`` curve of
    :func:`andoyer.analysis.resonance.residues.critical_mu_curve`: ``mu_critical`` (and
    ``mu_critical_error``) over a strictly increasing ``h_level``. Returns it.

    Parameters
    ----------
    curve : xarray.Dataset
        The curve (or a file's dataset read back).

    Raises
    ------
    ValueError
        Naming what is missing or wrong.
    """
    if not isinstance(curve, xr.Dataset):
        raise ValueError(f"critical_mu must be the dataset of critical_mu_curve, got "
                         f"{type(curve).__name__}")
    for name in ("mu_critical", "mu_critical_error"):
        if name not in curve.data_vars or curve[name].dims != ("h_level",):
            raise ValueError(f"critical_mu: no {name} over h_level: not a mu_c(h) curve of "
                             "critical_mu_curve (andoyer last-torus --h-values)")
    h = np.asarray(curve["h_level"].values, dtype=float)
    if h.size == 0 or not np.all(np.isfinite(h)) or np.any(np.diff(h) <= 0):
        raise ValueError("critical_mu: h_level must be finite and strictly increasing")
    mu = np.asarray(curve["mu_critical"].values, dtype=float)
    if not np.any(np.isfinite(mu)):
        raise ValueError("critical_mu: mu_critical is NaN on every level (mu_c not found "
                         "in its mu_range): nothing to draw")
    if np.any(mu[np.isfinite(mu)] <= 0):
        raise ValueError("critical_mu: mu_critical must be > 0")
    return curve


def _cell_coordinate(values: np.ndarray, grid: np.ndarray) -> np.ndarray:
    """Where ``values`` fall on a heat map whose cell ``i`` is centred on ``grid[i]``:
    linear between neighbouring grid values (in the logarithm where the grid and the
    values are > 0, as the swept grids of ``mu`` often are), extended linearly beyond the
    ends (the axes clip the line there)."""
    g = np.asarray(grid, dtype=float)
    v = np.asarray(values, dtype=float)
    idx = np.arange(g.size, dtype=float)
    if g.size == 1:
        return np.where(v == g[0], 0.0, np.nan)
    order = np.argsort(g)
    g, idx = g[order], idx[order]
    if np.all(g > 0) and np.all(v[np.isfinite(v)] > 0):
        g, v = np.log(g), np.log(np.where(v > 0, v, np.nan))
    out = np.interp(v, g, idx)
    lo, hi = v < g[0], v > g[-1]
    out[lo] = idx[0] + (v[lo] - g[0]) * (idx[1] - idx[0]) / (g[1] - g[0])
    out[hi] = idx[-1] + (v[hi] - g[-1]) * (idx[-1] - idx[-2]) / (g[-1] - g[-2])
    return out


def _draw_critical_mu(ax: Any, ds: xr.Dataset, curve: xr.Dataset, x: str,
                      y: str | None) -> Any:
    """The line ``mu_c(h)`` and its error band on a border panel over ``(h_level, mu)``."""
    if {x, y} != {"h_level", "mu"}:
        raise ValueError(f"critical_mu: the mu_c(h) overlay needs a panel over h_level and "
                         f"mu (either way round), this one is x = {x!r}, y = {y!r}; sweep "
                         "h and mu in the chaos_border scan, or choose them with --rows "
                         "and --cols")
    h = np.asarray(curve["h_level"].values, dtype=float)
    mu = np.asarray(curve["mu_critical"].values, dtype=float)
    err = np.asarray(curve["mu_critical_error"].values, dtype=float)
    hc = _cell_coordinate(h, np.asarray(ds["h_level"].values, dtype=float))
    mc = _cell_coordinate(mu, np.asarray(ds["mu"].values, dtype=float))
    label = r"$\mu_c(h)$ (last torus)"
    limits = ax.get_xlim(), ax.get_ylim()
    # black with a white edge: visible on the pale and the dark cells alike
    style = {"color": "k", "lw": 1.2, "marker": "o", "ms": 2.5, "label": label,
             "path_effects": [patheffects.withStroke(linewidth=2.6, foreground="w")]}
    if x == "h_level":
        (line,) = ax.plot(hc, mc, **style)
    else:
        (line,) = ax.plot(mc, hc, **style)
    ok = np.isfinite(err) & np.isfinite(mu) & (mu - err > 0)
    if ok.sum() >= 2:
        grid_mu = np.asarray(ds["mu"].values, dtype=float)
        lo = _cell_coordinate(mu[ok] - err[ok], grid_mu)
        hi = _cell_coordinate(mu[ok] + err[ok], grid_mu)
        if x == "h_level":
            ax.fill_between(hc[ok], lo, hi, color="k", alpha=0.2, lw=0)
        else:
            ax.fill_betweenx(hc[ok], lo, hi, color="k", alpha=0.2, lw=0)
    ax.set_xlim(*limits[0])
    ax.set_ylim(*limits[1])
    return line


def border_panel(ax: Any, ds: xr.Dataset, name: str = "chaotic_fraction", *, x: str,
                 y: str | None, label: str | None = None, annotate: bool = True,
                 critical_mu: xr.Dataset | None = None) -> Any:
    """One heat map of ``name`` over the swept ``(x, y)`` of a border-of-chaos dataset
    (other dims already selected); the chaotic fraction is annotated with its range under
    ``threshold -+ margin/2`` where the cells leave room for it (the font follows the
    cell size; no annotation where even the value does not fit). Returns the colour
    mesh.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw on.
    ds : xarray.Dataset
        A border-of-chaos dataset with the other dimensions selected.
    name : str, default "chaotic_fraction"
        The variable drawn.
    x : str
        The swept dimension along the horizontal axis.
    y : str or None
        The one along the vertical axis (None: a single row).
    label : str, optional
        The colour-bar label (default: that of :data:`andoyer.plot.style.SCALES`).
    annotate : bool, default True
        Write the chaotic fraction's range in the cells where it fits.
    critical_mu : xarray.Dataset, optional
        A ``mu_c(h)`` curve (:func:`andoyer.analysis.resonance.residues.critical_mu_curve`,
        checked by :func:`check_critical_mu`), drawn as a black line with its error band
        ``mu_c -+ mu_critical_error`` where the panel is over ``h_level`` and ``mu``
        (either way round; a ``ValueError`` on other axes). The line's points lie at the
        cells' coordinates of ``(h, mu_c)``: linear between neighbouring grid values, in
        their logarithm.
    """
    dims = (y, x) if y is not None else (x,)
    ok = np.ones(ds["chaotic_fraction"].shape, dtype=bool)
    if "done" in ds:
        ok = np.asarray(ds["done"].values, dtype=bool) & ~np.asarray(ds["empty"].values,
                                                                      dtype=bool)
    okg = xr.DataArray(ok, dims=ds["chaotic_fraction"].dims).transpose(*dims).values

    def grid(var: str) -> np.ndarray:
        v = np.where(okg, np.asarray(ds[var].transpose(*dims).values, dtype=float), np.nan)
        return v if y is not None else v[None, :]

    v = grid(name)
    # One equal cell per grid value (parameter grids are often uneven), ticked with it.
    xv = np.asarray(ds[x].values, dtype=float)
    yv = np.asarray(ds[y].values, dtype=float) if y is not None else np.array([0.0])
    xs, ys = np.arange(xv.size, dtype=float), np.arange(yv.size, dtype=float)
    scale = colour_scale("chaotic_fraction" if name.startswith("chaotic") else name)
    norm = scale.norm(v)
    mesh = ax.pcolormesh(_grid_edges(xs), _grid_edges(ys), v, shading="flat", norm=norm,
                         cmap=scale.cmap)
    # Tick labels at every cell where they fit, else at every k-th.
    cell_w, cell_h = _cells_points(ax, xs.size, ys.size)
    xl, yl = [f"{t:.3g}" for t in xv], [f"{t:.3g}" for t in yv]
    kx, ky = _tick_step(cell_w, xl, False), _tick_step(cell_h, yl, True)
    ax.set_xticks(xs[::kx], xl[::kx])
    ax.set_yticks(ys[::ky], yl[::ky])
    ax.set_xlabel(f"${SYMBOLS.get(x, x)}$" + (" (rad)" if x == "epsilon" else ""))
    if y is not None:
        ax.set_ylabel(f"${SYMBOLS.get(y, y)}$")
    else:
        ax.set_yticks([])
    size = _annotation_size(ax, xs.size, ys.size, name == "chaotic_fraction")
    if annotate and size is not None:
        fontsize, ranges = size
        lo, hi = (grid("chaotic_fraction_high"), grid("chaotic_fraction_low"))
        cmap = mpl.colormaps[scale.cmap]
        for i in range(v.shape[0]):
            for j in range(v.shape[1]):
                if not np.isfinite(v[i, j]):
                    continue
                text = f"{v[i, j]:.2f}"
                if ranges:
                    text += f"\n[{lo[i, j]:.2f}, {hi[i, j]:.2f}]"
                # Dark text on pale cells, white on dark ones (by the cell's luminance).
                r, g, b, _ = cmap(norm(v[i, j]))
                ax.text(xs[j], ys[i], text, ha="center", va="center", fontsize=fontsize,
                        color="k" if 0.299 * r + 0.587 * g + 0.114 * b > 0.5 else "w")
    if critical_mu is not None:
        _draw_critical_mu(ax, ds, check_critical_mu(critical_mu), x, y)
    if label:
        ax.set_title(label)
    ax.tick_params(labelsize=_TICK_FONT)
    return mesh


def _same_problem(curve: xr.Dataset, sub: xr.Dataset) -> None:
    """The curve's body moments and area constant are those of the atlas (where both
    say)."""
    for key in ("body_A", "body_B", "body_C"):
        a, b = curve.attrs.get(key), sub.attrs.get(key)
        if isinstance(a, int | float) and isinstance(b, int | float) and not np.isclose(
                float(a), float(b), rtol=1e-12, atol=0.0):
            raise ValueError(f"critical_mu: the curve's body has {key[5:]} = {a!r}, the "
                             f"atlas's {b!r}: not the same body")
    M_atlas = (float(sub["M_level"].values) if "M_level" in sub.coords and sub["M_level"].ndim == 0
               else sub.attrs.get("M_level"))
    M_curve = curve.attrs.get("M")
    if M_atlas is not None and M_curve is not None and not np.isclose(
            float(M_atlas), float(M_curve), rtol=0.0, atol=1e-12):
        raise ValueError(f"critical_mu: the curve is on M = {float(M_curve):g}, the atlas "
                         f"on M = {float(M_atlas):g}")


def plot_border(ds: xr.Dataset, *, x: str | None = None, y: str | None = None,
                select: Mapping[str, float] | None = None, width: float = 7.0,
                critical_mu: xr.Dataset | None = None) -> Figure:
    """The border of chaos: the chaotic fraction and the width of the chaotic layer
    around the former Hess separatrix over two swept parameters (by default
    ``epsilon`` across and ``mu`` up).

    Each cell is annotated with the fraction and, below it, the fraction's range when the
    MEGNO threshold moves by ``-+ margin/2`` (its sensitivity). Points not done are blank.

    Parameters
    ----------
    ds : xarray.Dataset
        The store of a ``chaos_border`` scan (``xarray.open_zarr``), or the result of
        :func:`andoyer.analysis.chaos.border.chaos_border_map`.
    x, y : str, optional
        Swept dims across and up (default ``epsilon`` and ``mu`` when swept, else the
        first two swept dims).
    select : mapping, optional
        Values of the other swept dims (nearest); default their first value.
    width : float
        Figure width in inches.
    critical_mu : xarray.Dataset, optional
        A ``mu_c(h)`` curve of the last torus
        (:func:`andoyer.analysis.resonance.residues.critical_mu_curve`) drawn on both
        panels, which must then be over ``h_level`` and ``mu`` (:func:`border_panel`); its
        body's moments and its ``M`` must be the atlas's.
    """
    swept = _border_dims(ds)
    if x is None:
        x = "epsilon" if "epsilon" in swept else swept[-1]
    if y is None:
        rest = [d for d in swept if d != x]
        y = "mu" if "mu" in rest else (rest[0] if rest else None)
    for name, d in (("x", x), ("y", y)):
        if d is not None and d not in swept:
            raise ValueError(f"plot_border: {name} = {d!r} is not a swept dim "
                             f"({', '.join(swept)})")
    sel = dict(select or {})
    fixed = {d: sel.get(d, float(ds[d].values[0])) for d in swept if d not in (x, y)}
    sub = ds.sel(fixed, method="nearest") if fixed else ds
    if critical_mu is not None:
        _same_problem(check_critical_mu(critical_mu), sub)
    with paper_style():
        fig = new_figure(1, 2, width=width, aspect=0.8)
        for ax, name in zip(fig.axes[:2], ("chaotic_fraction", "layer_width"), strict=True):
            mesh = border_panel(ax, sub, name, x=x, y=y, critical_mu=critical_mu)
            colour_bar(mesh, ax, name, shrink=0.85)
        if critical_mu is not None:
            # above the cells, not over their annotations
            fig.axes[0].legend(loc="lower left", bbox_to_anchor=(0.0, 1.0), fontsize=6.5,
                               frameon=False, borderaxespad=0.2)
        a = ds.attrs
        head = [f"body {a.get('body_name', '?')}: border of chaos (MEGNO > reference + "
                f"{float(a.get('margin', 1.0)):g})"]
        for key in ("h_level", "M_level"):
            if key in a:
                head.append(_label(key, float(a[key])))
        head += [_label(d, float(sub[d].values)) for d in fixed]
        fig.suptitle(", ".join(head), fontsize=8)
    return fig
