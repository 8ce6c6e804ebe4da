"""One style for every figure of andoyer: sizes, fonts, colours and markers by meaning.

Figures are made with :func:`new_figure` (a :class:`matplotlib.figure.Figure`, no pyplot)
inside :func:`paper_style`, and written with :func:`andoyer.plot.section.save_figure`.
Plot functions take datasets and compute nothing themselves.

Examples
--------
>>> from andoyer.plot.style import new_figure, paper_style, COLOURS
>>> with paper_style():
...     fig = new_figure(ncols=2)
>>> len(fig.axes)
2
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

import matplotlib as mpl
from matplotlib.figure import Figure

__all__ = ["RC", "COLOURS", "MARKERS", "WIDTH", "paper_style", "new_figure", "angle_ticks"]

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
    """Ticks at multiples of pi/2 between ``lo`` and ``hi`` on an angle axis."""
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
