"""One style for every figure of andoyer: sizes, fonts, colours and markers by meaning.

Figures are made with :func:`new_figure` (a :class:`matplotlib.figure.Figure`, no pyplot)
inside :func:`paper_style`, and written with :func:`andoyer.plot.section.save_figure`.
Plot functions take datasets and compute nothing themselves.

Colour-mapped quantities (chaos indicators, frequency drift, chaotic fraction, ...) have
one colour scale each, :data:`SCALES`: the colour map, its range and the colour bar's
label, used by every figure, the tutorials and the explorer. Indicators of chaos run
pale (regular) to dark (chaotic).

Examples
--------
>>> from andoyer.plot.style import new_figure, paper_style, COLOURS
>>> with paper_style():
...     fig = new_figure(ncols=2)
>>> len(fig.axes)
2
>>> SCALES["log10_drift"].cmap == SCALES["fli"].cmap
True
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from typing import Any

import matplotlib as mpl
import numpy as np
from matplotlib.colors import Normalize
from matplotlib.figure import Figure

from andoyer.analysis.chaos.registry import INDICATORS

__all__ = ["RC", "COLOURS", "COLOUR_MAPS", "MARKERS", "WIDTH", "SCALES", "ColourScale",
           "colour_scale",
           "colour_bar", "paper_style", "new_figure", "angle_ticks"]

#: Width of a one-column figure, inches (a journal column is about 3.3 in; a page 6.7 in).
WIDTH = 6.4

#: rcParams of all andoyer figures.
RC: dict[str, Any] = {
    "font.size": 9.0,
    "axes.titlesize": 9.5,
    "axes.labelsize": 10.0,
    "legend.fontsize": 7.5,
    "xtick.labelsize": 8.0,
    "ytick.labelsize": 8.0,
    "lines.linewidth": 0.9,
    "axes.linewidth": 0.6,
    "xtick.direction": "in",
    "ytick.direction": "in",
    "xtick.top": True,
    "ytick.right": True,
    "legend.frameon": False,
    "savefig.bbox": "tight",
    "savefig.pad_inches": 0.03,
    "pdf.fonttype": 42,
    "mathtext.fontset": "dejavuserif",
}

#: Colours by meaning, the same in every figure.
COLOURS: dict[str, str] = {
    "orbit": "0.35",            # ordinary level curves / trajectories
    "separatrix": "#c0392b",    # separatrices (red)
    "hess": "black",            # separatrices the Hess solutions approach (bold / dotted)
    "singular": "#7f8c8d",      # singular lines of a chart (L = +-G, J1 = 0, J2)
    "centre": "#1f77b4",        # stable (elliptic) fixed points
    "saddle": "#d62728",        # unstable (hyperbolic) fixed points
    "boundary": "black",        # boundary of an accessible region
    "chaotic": "#ff7f0e",
}

#: Marker style by linear type of a fixed point.
MARKERS: dict[str, dict[str, Any]] = {
    "centre": {"marker": "o", "s": 22, "facecolors": "white", "edgecolors": COLOURS["centre"],
               "linewidths": 1.0, "zorder": 5},
    "saddle": {"marker": "X", "s": 30, "color": COLOURS["saddle"], "zorder": 5},
    "degenerate": {"marker": "s", "s": 18, "color": "0.3", "zorder": 5},
}


@dataclass(frozen=True)
class ColourScale:
    """How one quantity is coloured: its colour map, range and colour-bar label.

    ``vmin`` / ``vmax`` left ``None`` follow the data (:meth:`norm`).

    Attributes
    ----------
    cmap : str
        Matplotlib colour map.
    label : str
        The colour-bar label.
    vmin, vmax : float, optional
        The range (None: follow the data).
    """

    cmap: str
    label: str
    vmin: float | None = None
    vmax: float | None = None

    def norm(self, data: Any = None) -> Normalize:
        """The colour range: the fixed ends, the others from the finite ``data``.

        >>> SCALES["megno"].norm([1.0, 30.0]).vmax
        8.0
        """
        v = np.asarray(data if data is not None else [], dtype=float)
        v = v[np.isfinite(v)]
        lo = self.vmin if self.vmin is not None else (float(v.min()) if v.size else 0.0)
        hi = self.vmax if self.vmax is not None else (float(v.max()) if v.size else 1.0)
        return Normalize(lo, hi if hi > lo else lo + 1.0)


#: Colour conventions -> colour map: ``"chaos"`` runs pale (regular) to dark (chaotic).
COLOUR_MAPS = {"chaos": "magma_r"}

#: Colour-mapped quantity (its storage name) -> its colour scale, the same in every
#: figure, tutorial and in the explorer. Chaos runs pale (regular) to dark (chaotic); the
#: chaos indicators' scales are their rows of the registry
#: (:data:`andoyer.analysis.chaos.registry.INDICATORS`).
SCALES: dict[str, ColourScale] = {
    **{k: ColourScale(COLOUR_MAPS[s.colours], s.label, s.vmin, s.vmax)
       for k, s in INDICATORS.items() if s.colours is not None},
    "log10_drift": ColourScale("magma_r", r"$\log_{10}$ frequency drift", None, 0.0),
    "chaotic_fraction": ColourScale("magma_r", "chaotic fraction", 0.0, None),
    "layer_width": ColourScale("viridis", "layer width (rad)", 0.0, None),
    "orbit": ColourScale("turbo", "orbit"),
}


def colour_scale(quantity: str) -> ColourScale:
    """The colour scale of ``quantity`` (a key of :data:`SCALES`).

    Parameters
    ----------
    quantity : str
        A key of :data:`SCALES` (``"fli"``, ``"megno"``, ``"log10_drift"``, ...).

    Examples
    --------
    >>> colour_scale("fli").cmap
    'magma_r'
    """
    try:
        return SCALES[quantity]
    except KeyError:
        raise ValueError(f"no colour scale for {quantity!r}; choose from "
                         f"{', '.join(SCALES)}") from None


def colour_bar(mappable: Any, ax: Any, quantity: str, **kwargs: Any) -> Any:
    """A colour bar beside ``ax`` for ``mappable``, labelled with ``quantity``'s label.

    Parameters
    ----------
    mappable : matplotlib.cm.ScalarMappable
        What is coloured (an image, a scatter).
    ax : matplotlib.axes.Axes
        The axes it stands beside.
    quantity : str
        A key of :data:`SCALES`.
    **kwargs
        Passed to :meth:`matplotlib.figure.Figure.colorbar`.
    """
    fig = ax.get_figure(root=True)
    return fig.colorbar(mappable, ax=ax, label=colour_scale(quantity).label, **kwargs)


@contextmanager
def paper_style() -> Iterator[None]:
    """Context in which figures get andoyer's rcParams (restored on exit)."""
    with mpl.rc_context(RC):  # type: ignore[arg-type]
        yield


def new_figure(nrows: int = 1, ncols: int = 1, *, width: float = WIDTH,
               aspect: float = 0.75, **subplot_kw: Any) -> Figure:
    """A figure of ``nrows x ncols`` axes, ``width`` inches wide, constrained layout.

    Parameters
    ----------
    nrows, ncols : int
        Grid of axes.
    width : float
        Figure width in inches (default :data:`WIDTH`).
    aspect : float
        Height of one row over the width of one column.
    **subplot_kw
        Passed to :meth:`Figure.subplots` as ``subplot_kw``.
    """
    height = width / ncols * aspect * nrows
    fig = Figure(figsize=(width, height), layout="constrained")
    fig.subplots(nrows, ncols, squeeze=False, subplot_kw=subplot_kw or None)
    return fig


def angle_ticks(ax: Any, lo: float, hi: float, *, axis: str = "x") -> None:
    """Ticks at multiples of pi/2 between ``lo`` and ``hi`` on an angle axis.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes.
    lo, hi : float
        The angle range (rad).
    axis : {"x", "y"}, default "x"
        Which axis.
    """
    import numpy as np

    k = np.arange(np.ceil(lo / (np.pi / 2) - 1e-9), np.floor(hi / (np.pi / 2) + 1e-9) + 1)
    names = {0: "0", 1: r"$\pi/2$", 2: r"$\pi$", 3: r"$3\pi/2$", 4: r"$2\pi$", -1: r"$-\pi/2$",
             -2: r"$-\pi$"}

    def name(i: int) -> str:
        if i in names:
            return names[i]
        return rf"${i // 2}\pi$" if i % 2 == 0 else rf"${i}\pi/2$"

    setter = ax.set_xticks if axis == "x" else ax.set_yticks
    setter(k * np.pi / 2, [name(int(i)) for i in k])
