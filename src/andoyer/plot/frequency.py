"""The figure of one orbit's NAFF frequencies: its signals read with the measured values.

Panel (a) folds ``L(t)`` on the measured period ``T = 2 pi / omega_l`` of the ``(l, L)``
motion (Eq. (9)): where the period is right, every turn falls on one curve; a wrong one
smears them. Panel (b) draws ``g(t) - omega_g t`` (``g`` unwrapped, Eq. (7)): where the
mean rate is right the curve stays bounded; a wrong one leaves a slope. The figure only
arranges the orbit and the frequencies the library computed
(:func:`andoyer.integrate.propagate`, :func:`andoyer.analysis.chaos.frequency.orbit_frequencies`).
"""

from __future__ import annotations

import math

import numpy as np
import xarray as xr
from matplotlib.figure import Figure

from andoyer.plot.style import WIDTH, new_figure, paper_style

__all__ = ["plot_orbit_frequencies"]


def plot_orbit_frequencies(orbit: xr.Dataset, frequencies: xr.Dataset, *, k: int = 0,
                           width: float = WIDTH, title: str | None = None) -> Figure:
    """Orbit ``k``'s ``L(t)`` folded on its measured period and ``g(t) - omega_g t``.

    Parameters
    ----------
    orbit : xarray.Dataset
        Samples of the orbits, with ``L_action`` and ``g_angle`` over ``(orbit, time)``
        (:func:`andoyer.integrate.propagate` on the times the frequencies were measured
        on).
    frequencies : xarray.Dataset
        ``omega_l``, ``omega_g``, ``period``, ``frequency_ratio`` and ``status`` over
        ``orbit`` (:func:`andoyer.analysis.chaos.frequency.orbit_frequencies`).
    k : int, default 0
        Which orbit of the two datasets.
    width : float
        Figure width, inches (default :data:`andoyer.plot.style.WIDTH`).
    title : str, optional
        Figure title (default: the measured frequencies).

    Returns
    -------
    matplotlib.figure.Figure
        Two panels: (a) ``L`` against the phase ``t / T mod 1`` (against ``t`` where the
        orbit has no ``(l, L)`` period: ``status`` not ``"ok"``); (b) ``g - omega_g t``
        against ``t`` (empty where ``omega_g`` is NaN).

    Examples
    --------
    A signal of period 2 and rate 0.5, read back:

    >>> t = np.linspace(0.0, 20.0, 401)
    >>> orbit = xr.Dataset({"L_action": (("orbit", "time"), [np.cos(np.pi * t)]),
    ...                     "g_angle": (("orbit", "time"), [np.mod(0.5 * t, 2 * np.pi)])},
    ...                    coords={"time": t})
    >>> freq = xr.Dataset({"omega_l": ("orbit", [np.pi]), "omega_g": ("orbit", [0.5]),
    ...                    "period": ("orbit", [2.0]), "status": ("orbit", ["ok"]),
    ...                    "frequency_ratio": ("orbit", [0.5 / np.pi])})
    >>> fig = plot_orbit_frequencies(orbit, freq)
    >>> [ax.get_title()[:3] for ax in fig.axes]
    ['(a)', '(b)']

    Every turn of ``L`` on one curve, and ``g - omega_g t`` flat:

    >>> phase, L = fig.axes[0].lines[0].get_data()
    >>> bool(np.allclose(L, np.cos(2 * np.pi * phase), atol=1e-9))
    True
    >>> bool(np.ptp(fig.axes[1].lines[0].get_ydata()) < 1e-12)
    True
    """
    t = orbit.time.values
    L = orbit.L_action.values[k]
    g = np.unwrap(orbit.g_angle.values[k])
    f = frequencies.isel(orbit=k)
    status = str(f.status.values)
    period = float(f.period)
    omega_g = float(f.omega_g)
    with paper_style():
        fig = new_figure(1, 2, width=width, aspect=0.7)
        ax_l, ax_g = fig.axes
        if status == "ok" and math.isfinite(period):
            ax_l.plot(np.mod(t / period, 1.0), L, ".", ms=1.0, color="C0", rasterized=True)
            ax_l.set_xlim(0.0, 1.0)
            ax_l.set_xlabel(r"phase $t/T$ mod 1 ($T = 2\pi/\omega_l$)")
            ax_l.set_title(f"(a) $L$ folded on $T$ = {period:.8g}", fontsize=8)
        else:
            ax_l.plot(t, L, lw=0.8, color="C0")
            ax_l.set_xlabel("time $t$")
            ax_l.set_title(f"(a) $L$: no $(l, L)$ period ({status})", fontsize=8)
        ax_l.set_ylabel("$L$")
        if math.isfinite(omega_g):
            ax_g.plot(t, g - omega_g * t, lw=0.8, color="C1")
            ax_g.set_title(rf"(b) $g - \omega_g t$, $\omega_g$ = {omega_g:.10g}", fontsize=8)
        else:
            ax_g.set_title(rf"(b) no $\omega_g$ ({status})", fontsize=8)
        ax_g.set_xlabel("time $t$")
        ax_g.set_ylabel(r"$g - \omega_g t$ (rad)")
        if title is None:
            title = (f"NAFF: frequency_ratio $\\omega_g/\\omega_l$ = "
                     f"{float(f.frequency_ratio):.10g}")
        fig.suptitle(title, fontsize=8, wrap=True)
    return fig
