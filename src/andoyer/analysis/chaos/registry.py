"""The chaos indicators, listed once: what each needs, how it is computed, how it is shown.

Every list of indicators in andoyer is derived from :data:`INDICATORS`: the variables of
:func:`~andoyer.analysis.chaos.lyapunov.indicators` and
:func:`~andoyer.analysis.chaos.lyapunov.chaos_map` and their attributes, the choices of
:class:`~andoyer.analysis.chaos.specs.IndicatorRun`, of ``andoyer chaos-map
--indicator`` and of a scan's ``chaos_map`` task, the colour scales and labels of the
figures (:data:`andoyer.plot.style.SCALES`, :mod:`andoyer.plot.chaos`,
:mod:`andoyer.plot.atlas`) and the explorer's indicator line
(:func:`andoyer.explore.orbits.orbit_indicators`). ``tests/analysis/chaos/test_registry.py``
fails when any of them differs from this table.

A new indicator computed from a tangent flow (the states ``flow.y``, the log norms
``flow.rho``, the MEGNO quadratures ``flow.megno`` of
:class:`~andoyer.integrate.engines.values.TangentFlow` at the output times) is a
function ``f(flow, t) -> array (orbit, time)`` in its own module and one row here.

This module imports nothing heavy: the command line's argument parsers read it.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

__all__ = ["IndicatorSpec", "INDICATORS", "MAP_INDICATORS", "PANEL_INDICATORS",
           "MAP_EXTRAS", "ALL_OF_THEM", "MAP_CHOICES", "chosen"]


@dataclass(frozen=True)
class IndicatorSpec:
    """One chaos indicator: its storage name, what it needs, how it is computed and shown.

    Parameters
    ----------
    name : str
        Its name in datasets, the API, the CLI and scan configs.
    title : str
        Its short name in titles and printed lines (``"FLI"``).
    label : str
        Axis and colour-bar label (Matplotlib mathtext).
    text : str
        Its name in the explorer's plain text (Unicode).
    long_name, symbol, units : str
        The dataset variable's attributes.
    compute : str
        ``"module:function"``, the function ``f(flow, t)`` of a
        :class:`~andoyer.integrate.engines.values.TangentFlow` (one tangent vector) and
        its output times ``t`` that returns the indicator, shape ``(orbit, time)``.
    definition : str, optional
        Where it is defined (reference) and how to read it (attribute ``definition``).
    capability : str, default "tangent"
        The engine capability it needs (a value of
        :class:`~andoyer.integrate.engines.values.Capability`).
    renormalised : bool, default True
        Whether it needs the renormalised tangent flow with the MEGNO quadratures
        (False for the FLI and the MLE only: the FLI map's faster flow of the raw
        tangent vector gives them too).
    on_map : bool, default False
        A choice of ``chaos_map(run=IndicatorRun(indicator=...))``.
    panel : bool, default False
        Drawn against time by :func:`andoyer.plot.chaos.plot_indicators` and shown by
        the explorer.
    colours : str, optional
        Its colour convention, a key of :data:`andoyer.plot.style.COLOUR_MAPS`
        (``"chaos"``: pale regular, dark chaotic; None: never colour-mapped).
    vmin, vmax : float, optional
        Fixed ends of its colour range (None: from the data).
    regular : float, optional
        Its value on a regular orbit, drawn as a reference line.
    reading : str, optional
        How to read it, in the explorer's line.

    Examples
    --------
    >>> INDICATORS["megno"].regular, INDICATORS["fli"].on_map
    (2.0, True)
    """

    name: str
    title: str
    label: str
    text: str
    long_name: str
    symbol: str
    units: str
    compute: str
    definition: str = ""
    capability: str = "tangent"
    renormalised: bool = True
    on_map: bool = False
    panel: bool = False
    colours: str | None = None
    vmin: float | None = None
    vmax: float | None = None
    regular: float | None = None
    reading: str = ""

    def function(self) -> Callable[[Any, Any], Any]:
        """The function ``f(flow, t)`` that computes it (imported on first use)."""
        module, _, name = self.compute.partition(":")
        fn: Callable[[Any, Any], Any] = getattr(importlib.import_module(module), name)
        return fn

    @property
    def attrs(self) -> dict[str, str]:
        """Its dataset variable's attributes."""
        out = {"long_name": self.long_name, "symbol": self.symbol, "units": self.units}
        if self.definition:
            out["definition"] = self.definition
        return out


_L = "andoyer.analysis.chaos.lyapunov"

#: Every chaos indicator of a tangent flow, by storage name (the order of datasets,
#: figures and printed lines).
INDICATORS: dict[str, IndicatorSpec] = {s.name: s for s in (
    IndicatorSpec(
        "fli", "FLI", r"FLI $= \sup_{s \leq t}\, \ln\|w(s)\|$", "FLI",
        "fast Lyapunov indicator sup_s ln|w(s)| (sup over output times)", "FLI", "1",
        f"{_L}:fli_of_flow",
        "Froeschle, Lega & Gonczi (1997); w(0) unit tangent vector",
        renormalised=False, on_map=True, panel=True, colours="chaos"),
    IndicatorSpec(
        "megno", "MEGNO", r"MEGNO $\langle Y\rangle$", "MEGNO ⟨Y⟩", "mean MEGNO <Y>", "<Y>",
        "1", f"{_L}:megno_of_flow",
        "Cincotta & Simo (2000); -> 2 quasi-periodic, -> 0 stable periodic, "
        "~ lambda t / 2 chaotic",
        on_map=True, panel=True, colours="chaos", vmin=0.0, vmax=8.0, regular=2.0,
        reading="2: regular, grows: chaotic"),
    IndicatorSpec(
        "mle", "Lyapunov", r"$\ln\|w(t)\|\,/\,t$", "λ",
        "finite-time maximal Lyapunov exponent ln|w(t)|/t", "lambda",
        "1 / body time unit", f"{_L}:mle_of_flow", renormalised=False, colours="chaos"),
    IndicatorSpec(
        "log_norm", "ln|w|", r"$\ln\|w(t)\|$", "ln|w|", "ln of the tangent-vector norm",
        "ln|w|", "1", f"{_L}:log_norm_of_flow", renormalised=False),
    IndicatorSpec(
        "megno_y", "MEGNO Y", r"MEGNO $Y$", "Y", "MEGNO Y", "Y", "1",
        f"{_L}:megno_y_of_flow", "Y(t) = (2/t) int_0^t s (w'.w)/(w.w) ds"),
)}

#: What a chaos map can hold (the choices of ``IndicatorRun(indicator=...)``).
MAP_INDICATORS = tuple(k for k, s in INDICATORS.items() if s.on_map)
#: Stored by every chaos map beside the chosen indicators (the same integration gives it).
MAP_EXTRAS = ("mle",)
#: Drawn against time and shown by the explorer.
PANEL_INDICATORS = tuple(k for k, s in INDICATORS.items() if s.panel)
#: The choice that asks a chaos map for every indicator it can hold (one integration).
ALL_OF_THEM = "both"
#: The choices of a chaos map's indicator: one of :data:`MAP_INDICATORS` or all of them.
MAP_CHOICES = (*MAP_INDICATORS, ALL_OF_THEM)


def chosen(indicator: str) -> tuple[str, ...]:
    """The indicators a chaos map's choice ``indicator`` stores.

    Parameters
    ----------
    indicator : str
        One of :data:`MAP_CHOICES`.

    Examples
    --------
    >>> chosen("both"), chosen("megno")
    (('fli', 'megno'), ('megno',))
    """
    if not isinstance(indicator, str) or indicator not in MAP_CHOICES:
        raise ValueError(f"indicator must be one of {MAP_CHOICES}, got {indicator!r:.60}")
    return MAP_INDICATORS if indicator == ALL_OF_THEM else (indicator,)
