"""The predicted island chains over the explorer's plane (issue 28), free of any GUI.

:func:`chain_overlay` turns :func:`andoyer.analysis.resonance.predict.resonance_widths`
(first order in ``mu``) for the explorer's body, level ``(h, M)`` and section into the
columns the page draws: per chain its centre line (the resonant torus of the free top),
its two separatrices (R9), its stable (o) and unstable (x) periodic points, with the
plane's angle reduced as the orbits' points are (:func:`andoyer.explore.state.
plane_coordinates`: mod :attr:`~andoyer.explore.state.Settings.x_period`) and the lines
broken where they wrap. :func:`shared_chain_overlay` computes it once per
``(body, h, M, section, max_order)`` and shares it read-only between the pages, as
:func:`~andoyer.explore.state.shared_plane_view` does for the plane.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from andoyer.explore.state import Settings, SharedCache
from andoyer.integrate import Section
from andoyer.validation import integer

__all__ = ["ChainOverlay", "chain_overlay", "shared_chain_overlay", "CHAINS_MAX_ORDER",
           "CHAINS_ORDER", "CHAINS_CACHE"]

#: Largest ``p + q`` the explorer offers: the cost of :func:`chain_overlay` grows with the
#: number of chains (about ``max_order**2 / 3`` resonant tori, each one FFT of its torus);
#: at 16 it is a few seconds on the paper's level.
CHAINS_MAX_ORDER = 16
#: The order of the explorer's control when the page opens.
CHAINS_ORDER = 10
#: Overlays kept for sharing between pages (the most recently used).
CHAINS_CACHE = 16

_EMPTY = np.empty(0)


@dataclass(frozen=True)
class ChainOverlay:
    """What the explorer draws of the predicted chains on one plane.

    Lines are tuples (one entry per chain; for the separatrices, upper then lower of each
    chain of first order in ``mu``) of arrays in plane coordinates with NaN where the line
    wraps; points are flat arrays, stable points then unstable points of each chain.

    Parameters
    ----------
    key : tuple
        ``(body, h, M, section, max_order)``: what the overlay was computed for.
    labels : tuple of str
        ``"q:p (axis k, +)"`` per chain (``+``/``-``: the sign of the momentum on the
        axis, the chain's two copies).
    colours : tuple of str
        One colour per chain (the orbit scale of :data:`andoyer.plot.style.SCALES`).
    centre_x, centre_y : tuple of ndarray
        The centre line of each chain (the resonant torus of the free top, (R9)).
    separatrix_x, separatrix_y : tuple of ndarray
        The separatrices (R9) of the first-order chains.
    separatrix_colours : tuple of str
        The colour of each separatrix (its chain's).
    points_x, points_y : ndarray
        The stable and unstable periodic points (R7) in the plane.
    points_kind, points_label, points_colour : tuple of str
        ``"stable"`` or ``"unstable"``, the chain's label and colour of each point.
    half_width : ndarray
        ``Delta G`` (R6) per chain, NaN where the width is of second order in ``mu``.
    mu_order : ndarray of int
        1, or 2 for a chain with ``p >= 2`` (centre line only).
    ds : xarray.Dataset
        The :func:`~andoyer.analysis.resonance.predict.resonance_widths` dataset.
    """

    key: tuple[Any, ...]
    labels: tuple[str, ...]
    colours: tuple[str, ...]
    centre_x: tuple[NDArray[np.float64], ...]
    centre_y: tuple[NDArray[np.float64], ...]
    separatrix_x: tuple[NDArray[np.float64], ...]
    separatrix_y: tuple[NDArray[np.float64], ...]
    separatrix_colours: tuple[str, ...]
    points_x: NDArray[np.float64]
    points_y: NDArray[np.float64]
    points_kind: tuple[str, ...]
    points_label: tuple[str, ...]
    points_colour: tuple[str, ...]
    half_width: NDArray[np.float64]
    mu_order: NDArray[np.int64]
    ds: xr.Dataset

    @property
    def n_chains(self) -> int:
        """Chains drawn (their centre lines)."""
        return len(self.labels)

    def message(self) -> str:
        """The status line's sentence for this overlay."""
        mu_order = self.key[-1]
        if self.n_chains == 0:
            return (f"no resonant torus with p + q ≤ {mu_order} on this level: no chain "
                    "to draw (raise the order)")
        first = int(np.sum(self.mu_order == 1))
        second = self.n_chains - first
        width = np.nanmax(self.half_width) if first else float("nan")
        text = (f"predicted chains (first order in μ, p + q ≤ {mu_order}): "
                f"{self.n_chains} centre lines, {first} with separatrices and periodic "
                f"points (largest half-width ΔG = {width:.2g})")
        if second:
            text += f"; {second} of width O(μ) (second order): centre line only"
        return text

    def columns(self) -> dict[str, dict[str, Any]]:
        """The columns of the page's three sources: ``centres`` and ``separatrices``
        (``xs, ys, colour, label``: one line per row) and ``points`` (``x, y, kind,
        marker, colour, label``)."""
        marker = {"stable": "circle", "unstable": "x"}
        return {
            "centres": {"xs": list(self.centre_x), "ys": list(self.centre_y),
                        "colour": list(self.colours), "label": list(self.labels)},
            "separatrices": {"xs": list(self.separatrix_x), "ys": list(self.separatrix_y),
                             "colour": list(self.separatrix_colours),
                             "label": [lb for lb, o in zip(self.labels, self.mu_order,
                                                           strict=True) if o == 1
                                       for _ in (0, 1)]},
            "points": {"x": self.points_x, "y": self.points_y,
                       "kind": list(self.points_kind),
                       "marker": [marker[k] for k in self.points_kind],
                       "colour": list(self.points_colour),
                       "label": list(self.points_label)}}


def empty_columns() -> dict[str, dict[str, Any]]:
    """The three sources' columns with no chain (the overlay switched off)."""
    return {"centres": {"xs": [], "ys": [], "colour": [], "label": []},
            "separatrices": {"xs": [], "ys": [], "colour": [], "label": []},
            "points": {"x": [], "y": [], "kind": [], "marker": [], "colour": [],
                       "label": []}}


def _wrapped(x: NDArray[np.float64], y: NDArray[np.float64], period: float
             ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The polyline with its angle reduced mod ``period`` and NaN where it then jumps."""
    ok = np.isfinite(x) & np.isfinite(y)
    x, y = np.mod(np.asarray(x, dtype=float)[ok], period), np.asarray(y, dtype=float)[ok]
    jump = np.nonzero(np.abs(np.diff(x)) > period / 2)[0] + 1
    return np.insert(x, jump, np.nan), np.insert(y, jump, np.nan)


def _section_text(section: Section) -> str:
    sign = {1: "+", -1: "-", 0: "0"}[section.direction]
    return f"{section.coord}={section.value!r}:{sign}"


def _colours(n: int) -> list[str]:
    """``n`` colours of the orbit scale of :data:`andoyer.plot.style.SCALES` (those of
    :func:`andoyer.plot.resonance.plot_resonances`)."""
    from matplotlib import colormaps
    from matplotlib.colors import to_hex

    from andoyer.plot.style import colour_scale

    cmap = colormaps[colour_scale("orbit").cmap]
    return [to_hex(cmap(i / max(n - 1, 1))) for i in range(n)]


def chain_overlay(settings: Settings, max_order: int = CHAINS_ORDER) -> ChainOverlay:
    """The predicted ``p/q`` island chains of the explorer's plane, ready to draw.

    The chains are those of
    :func:`~andoyer.analysis.resonance.predict.resonance_widths` (first order in ``mu``,
    (R1)-(R9)) for ``settings.body`` on ``H = h`` (Eq. (1)), area constant ``M`` and the
    explorer's section; the plane's angle (``theta1`` or ``l``) is reduced mod
    ``settings.x_period`` as the orbits' points are.

    Parameters
    ----------
    settings : Settings
        The explorer's body, level and section (its integration settings are unused).
    max_order : int, default :data:`CHAINS_ORDER`
        Largest ``p + q``, 2 to :data:`CHAINS_MAX_ORDER` (bounds the cost before any work).

    Returns
    -------
    ChainOverlay
        Centre lines of every chain; separatrices and periodic points of the chains of
        first order in ``mu`` (a chain with ``p >= 2`` has width ``O(mu)``: centre only).

    Raises
    ------
    ValueError
        Where :func:`resonance_widths` refuses the setting: ``h <= 0``, a body whose
        ``Oz`` is not the middle axis, a ``theta2`` section of a body with ``e3 != 0``,
        ``max_order`` out of range.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> ov = chain_overlay(Settings(RigidBody.paper(), 0.2466, section="g=0"), max_order=8)
    >>> ov.labels[:2], ov.n_chains
    (('7:1 (axis 1, +)', '7:1 (axis 1, −)'), 4)
    >>> bool(np.all((ov.points_x >= 0) & (ov.points_x < 2 * np.pi)))
    True
    """
    from andoyer.analysis.resonance.predict import resonance_widths

    if not isinstance(settings, Settings):
        raise TypeError(f"settings must be an explorer Settings, got {type(settings).__name__}")
    max_order = integer("max_order", max_order, 2, CHAINS_MAX_ORDER)
    s = settings
    ds = resonance_widths(s.body, s.h, s.M, _section_text(s.section), max_order=max_order)
    period = s.x_period
    n = ds.sizes.get("resonance", 0)
    colours = _colours(n)
    labels: list[str] = []
    cx: list[NDArray[np.float64]] = []
    cy: list[NDArray[np.float64]] = []
    sx: list[NDArray[np.float64]] = []
    sy: list[NDArray[np.float64]] = []
    scol: list[str] = []
    px: list[NDArray[np.float64]] = []
    py: list[NDArray[np.float64]] = []
    kind: list[str] = []
    plabel: list[str] = []
    pcol: list[str] = []
    for i in range(n):
        row = ds.isel(resonance=i)
        label = (f"{row.label.values} (axis {int(row.axis)}, "
                 f"{'+' if int(row.sign) > 0 else '−'})")
        labels.append(label)
        x, y = _wrapped(row.centre_x.values, row.centre_y.values, period)
        cx.append(x)
        cy.append(y)
        if int(row.mu_order) != 1:
            continue
        for part in ("upper", "lower"):
            x, y = _wrapped(row[f"{part}_x"].values, row[f"{part}_y"].values, period)
            sx.append(x)
            sy.append(y)
            scol.append(colours[i])
        for k in ("stable", "unstable"):
            x, y = row[f"{k}_x"].values, row[f"{k}_y"].values
            ok = np.isfinite(x) & np.isfinite(y)
            px.append(np.mod(x[ok], period))
            py.append(y[ok])
            kind += [k] * int(ok.sum())
            plabel += [label] * int(ok.sum())
            pcol += [colours[i]] * int(ok.sum())
    key = (s.body, s.h, s.M, s.section, max_order)
    return ChainOverlay(key, tuple(labels), tuple(colours), tuple(cx), tuple(cy), tuple(sx),
                        tuple(sy), tuple(scol),
                        np.concatenate(px) if px else _EMPTY.copy(),
                        np.concatenate(py) if py else _EMPTY.copy(), tuple(kind),
                        tuple(plabel), tuple(pcol),
                        np.asarray(ds.half_width.values, dtype=float) if n else _EMPTY.copy(),
                        np.asarray(ds.mu_order.values, dtype=np.int64) if n
                        else np.empty(0, dtype=np.int64), ds)


_OVERLAYS = SharedCache(CHAINS_CACHE)


def shared_chain_overlay(settings: Settings, max_order: int = CHAINS_ORDER) -> ChainOverlay:
    """:func:`chain_overlay`, computed once per ``(body, h, M, section, max_order)`` and
    shared, read-only, by every page of a server (the last :data:`CHAINS_CACHE` kept).

    Pages asking at once for the same chains wait for one computation.

    Parameters
    ----------
    settings : Settings
        As for :func:`chain_overlay` (only body, ``h``, ``M`` and section count).
    max_order : int, default :data:`CHAINS_ORDER`
        Largest ``p + q``, 2 to :data:`CHAINS_MAX_ORDER`.

    Returns
    -------
    ChainOverlay
        Read-only arrays, shared.

    Examples
    --------
    >>> from dataclasses import replace
    >>> from andoyer import RigidBody
    >>> s = Settings(RigidBody.paper(), 0.2466, section="g=0")
    >>> shared_chain_overlay(s, 6) is shared_chain_overlay(replace(s, n_crossings=50), 6)
    True
    """
    if not isinstance(settings, Settings):
        raise TypeError(f"settings must be an explorer Settings, got {type(settings).__name__}")
    max_order = integer("max_order", max_order, 2, CHAINS_MAX_ORDER)
    s = settings

    def compute() -> ChainOverlay:
        overlay = chain_overlay(settings, max_order)
        for arr in (overlay.points_x, overlay.points_y, overlay.half_width, overlay.mu_order,
                    *overlay.centre_x, *overlay.centre_y, *overlay.separatrix_x,
                    *overlay.separatrix_y):
            arr.flags.writeable = False
        return overlay

    overlay: ChainOverlay = _OVERLAYS.get((s.body, s.h, s.M, s.section, max_order), compute)
    return overlay
