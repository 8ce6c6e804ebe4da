"""The explorer's integrations of an orbit: its section points in growing stages
(:func:`crossing_stages`) and the drift of its integrals (:func:`integral_drifts`), its
chaos indicators for the side panel (:func:`orbit_indicators`), and the chaos-map
underlay of the section plane (:func:`chaos_underlay`).

The records they fill (:class:`~andoyer.explore.state.Stage`,
:class:`~andoyer.explore.state.Orbit`) and the settings they run with
(:class:`~andoyer.explore.state.Settings`) are in :mod:`andoyer.explore.state`.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from typing import Literal

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from andoyer.analysis.chaos.registry import MAP_EXTRAS, PANEL_INDICATORS
from andoyer.body import RigidBody
from andoyer.charts.euler_poisson import STATE
from andoyer.charts.integrals import INTEGRALS, integrals_of
from andoyer.explore.state import PlaneView, Settings, Stage, plane_coordinates
from andoyer.validation import finite as _finite

__all__ = ["crossing_stages", "integral_drifts", "FIRST_STAGE", "STAGE_GROWTH",
           "orbit_indicators", "chaos_underlay", "UNDERLAY_N", "UNDERLAY_T_END"]


#: Crossings of the first stage of an orbit (what the responsiveness target is about).
FIRST_STAGE = 100
#: Each later stage asks for this many times the crossings of the one before.
STAGE_GROWTH = 4


def crossing_stages(settings: Settings, y0: NDArray[np.float64], *,
                    first: int = FIRST_STAGE, growth: int = STAGE_GROWTH
                    ) -> Iterator[Stage]:
    """The section points of the orbit from ``y0`` in stages of growing length.

    Parameters
    ----------
    settings : Settings
        Section, crossings ``N = settings.n_crossings``, engine and tolerances.
    y0 : ndarray, shape (6,)
        Euler-Poisson initial state.
    first : int
        Crossings of the first stage.
    growth : int
        Each stage asks for ``growth`` times the crossings of the one before (up to N).

    Yields
    ------
    Stage
        New points ``[start, stop)``; ``done`` on the last stage (N crossings, or fewer
        if the orbit reached ``t_max`` first).

    Notes
    -----
    Every stage is one call ``poincare(body, y0, section, n_k, t_max=1000 N)`` from
    ``t = 0``: ``t_max`` is what one ``poincare(body, y0, section, N)`` call uses, the
    engines are deterministic and their step sequence does not depend on how many
    crossings are asked for, so the first ``n_k`` crossings of a stage are those of the
    single call, bit for bit (``tests/explore/test_explore.py`` checks it for every engine).
    Restarting from the last crossing instead would change the step sequence, and the
    points by ~1e-11 already on a regular orbit (more on a chaotic one). The price is
    the recomputed prefixes: less than ``(2 growth - 1)/(growth - 1)`` times one call
    (7/3 for growth 4; 2 for the default 100, 400, 500 crossings), a few tens of
    milliseconds with heyoka for 500 crossings.
    """
    from andoyer.integrate.api import poincare

    if first < 1 or growth < 2:
        raise ValueError(f"need first >= 1 and growth >= 2, got {first}, {growth}")
    N = settings.n_crossings
    t_max = 1000.0 * N
    n = min(first, N)
    start = 0
    while True:
        ds = poincare(settings.body, y0, settings.section, n, engine=settings.engine,
                      rtol=settings.rtol, atol=settings.atol, t_max=t_max, progress=False)
        ds = ds.isel(orbit=0)
        found = int(ds.crossings_found)
        x, y = plane_coordinates(settings, ds)
        done = found < n or n >= N
        yield Stage(start, found, x[start:found], y[start:found], ds, done)
        if done:
            return
        start = found
        n = min(N, n * growth)


def integral_drifts(ds: xr.Dataset, h: float, M: float, body: RigidBody
                    ) -> dict[str, float]:
    """Largest drift of the integrals over the section points of one orbit.

    Each of the body's integrals (:func:`andoyer.charts.integrals.integrals_of`) from its
    level -- ``h`` for ``H``, ``M`` for ``(G, gamma)``, 1 for ``|gamma|^2``, the first
    point's value for the others (Kovalevskaya's ``K``) -- relative to the scale the
    datasets use (:data:`andoyer.charts.integrals.INTEGRALS`: ``max(|h|, mu)`` for
    ``H``, the first point's ``|G|`` for the area). NaN when there are no points.

    Parameters
    ----------
    ds : xarray.Dataset
        The section points of one orbit (:func:`~andoyer.integrate.poincare`).
    h : float
        The energy level.
    M : float
        The area constant.
    body : RigidBody
        The body (its integrals, and ``mu``: the energy's scale where ``|h|`` is small).
    """
    names = integrals_of(body)
    ok = np.isfinite(ds.H.values).ravel()
    if not ok.any():
        return dict.fromkeys(names, math.nan)
    y = np.stack([ds[s].values.ravel() for s in STATE], axis=-1)[ok]
    levels = {"H": h, "area": M, "geometric": 1.0}
    out = {}
    for name in names:
        integral = INTEGRALS[name]
        values = ds[name].values.ravel()[ok] if name in ds else integral(body, y)
        out[name] = float(np.max(np.abs(integral.drift(body, values, y[:1], levels.get(name)))))
    return out


#: The indicators of the side panel's line (the registry's panel indicators and the MLE).
EXPLORER_INDICATORS = (*PANEL_INDICATORS, *MAP_EXTRAS)

#: Grid and integration time of the chaos-map underlay (a few seconds on two cores).
UNDERLAY_N = 48
UNDERLAY_T_END = 300.0


def orbit_indicators(settings: Settings, y0: NDArray[np.float64], t_end: float = 1000.0
                     ) -> dict[str, float]:
    """FLI, MEGNO ``<Y>`` and the finite-time Lyapunov exponent of one orbit at ``t_end``
    (:func:`andoyer.analysis.chaos.lyapunov.indicators`), and the relative energy drift.

    Parameters
    ----------
    settings : Settings
        Body and engine.
    y0 : ndarray, shape (6,)
        The orbit's initial Euler-Poisson state.
    t_end : float, default 1000.0
        Integration time.
    """
    from andoyer.analysis.chaos.lyapunov import indicators

    # The orbit engine's name (it must have the tangent capability: heyoka, taylor,
    # numba, scipy), or the default of tangent flows (heyoka where installed, else taylor).
    ds = indicators(settings.body, y0, _finite("t_end", t_end), engine=settings.engine,
                    tol=min(settings.rtol, settings.atol)).isel(orbit=0, time=-1)
    return {**{k: float(ds[k]) for k in EXPLORER_INDICATORS},
            "H_drift": float(ds.H_drift), "t_end": float(t_end)}


def chaos_underlay(settings: Settings, view: PlaneView, n: int = UNDERLAY_N,
                   t_end: float = UNDERLAY_T_END) -> xr.Dataset:
    """FLI over the plane of ``view`` (:func:`andoyer.analysis.chaos.lyapunov.chaos_map`), on the
    same box, for the underlay of the section plane.

    Parameters
    ----------
    settings : Settings
        Body, level, section and engine.
    view : PlaneView
        The plane (its box).
    n : int, default 48
        Grid ``n x n``.
    t_end : float, default 300.0
        Integration time of every orbit.
    """
    from andoyer.analysis.chaos.lyapunov import IndicatorRun, MapGrid, chaos_map

    sec = settings.section
    root: Literal["largest", "smallest"] = ("smallest" if settings.root == "smallest"
                                            else "largest")
    return chaos_map(settings.body, settings.h, settings.M, (sec.coord, sec.value),
                     MapGrid(n, plane_bounds=(view.x_range, view.y_range), root=root),
                     IndicatorRun("fli", t_end=t_end, tol=min(settings.rtol, settings.atol)),
                     progress=False)
