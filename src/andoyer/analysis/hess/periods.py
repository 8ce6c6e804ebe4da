"""Periods of the Hess solution against the energy: the closed form through complete
elliptic integrals K(m) (:func:`andoyer.analysis.hess.solution.period`) beside periods
measured on integrated Euler-Poisson orbits (crossings of a level of ``|G|``).

Examples
--------
>>> from andoyer import RigidBody
>>> ds = hess_periods(RigidBody.paper(), (0.0,), 8, 1, engine="numba")
>>> bool(abs(ds.T_integrated / ds.T_elliptic_check - 1).max() < 1e-9)
True
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
import xarray as xr
from scipy.optimize import brentq

from andoyer.analysis.hess.solution import cubic_roots, energy_minimum, period
from andoyer.body import RigidBody, checks_body
from andoyer.charts.hess import from_hess
from andoyer.integrate import Section, poincare
from andoyer.validation import finite_array

__all__ = ["hess_periods"]


@checks_body(ranges={"n": "count", "n_check": "count"})
def hess_periods(body: RigidBody, M_values: Sequence[float], n: int, n_check: int, *,
                 engine: str | None = None) -> xr.Dataset:
    """Hess-solution periods vs energy: closed form on ``n`` levels, and ``n_check`` levels
    per ``M`` checked by integration.

    Parameters
    ----------
    body : RigidBody
        A Hess body.
    M_values : sequence of float
        Area constants.
    n, n_check : int
        Energy levels of the closed-form curve (``h`` in ``[-0.98 mu, 5 mu]``) and of the
        integrated check (in ``[h_min + 0.1 mu, 4.2 mu]``).
    engine : str, optional
        Integration engine of the check.

    Returns
    -------
    xarray.Dataset
        ``T_elliptic`` (dims ``M, h``), and on the check levels ``h_check``,
        ``T_integrated`` (crossings of ``G = const``, started at the bottom
        ``theta2 = 3 pi/2`` of the reduced system, ``J1 = J2/2``) and
        ``T_elliptic_check`` (dims ``M, check``).
    """
    body.require_hess("hess_periods")
    M_values = finite_array("M_values", M_values, ndim=1).tolist()
    mu, c = body.mu, body.c
    h = np.linspace(-0.98 * mu, 5.0 * mu, int(n))
    T = np.full((len(M_values), h.size), np.nan)
    hc = np.full((len(M_values), int(n_check)), np.nan)
    Tc = np.full_like(hc, np.nan)
    Te = np.full_like(hc, np.nan)
    for i, M in enumerate(M_values):
        Jstar, hmin = energy_minimum(body, M)
        for j, hj in enumerate(h):
            if hj > hmin and abs(hj - mu) > 1e-9 * mu:
                T[i, j] = period(body, float(hj), M)
        for j, hj in enumerate(np.linspace(hmin + 0.1 * mu, 4.2 * mu, int(n_check))):
            hj = float(hj) if abs(hj - mu) > 0.05 * mu else float(hj) + 0.1 * mu

            def excess(J: float, hj: float = hj, M: float = M) -> float:
                return c * J * J / 2 - mu * math.sqrt(max(1.0 - M * M / (J * J), 0.0)) - hj

            J2 = brentq(excess, max(Jstar, 1e-12), 10.0)
            Tj = period(body, hj, M)
            _, ub, uc = cubic_roots(body, hj, M)
            x0 = np.array([0.0, 1.5 * np.pi, J2 / 2, J2, M])
            sec = poincare(body, from_hess(body, x0),
                           Section("G", math.sqrt(0.5 * (ub + uc)), 1), 3, t_max=5 * Tj,
                           engine=engine, rtol=1e-13, atol=1e-13)
            dt = float(np.mean(np.diff(sec.t.values[0])))
            # On an M = 0 libration |G| = |J2| repeats every half period (G = 0 passage).
            half = M == 0.0 and hj < mu
            hc[i, j], Tc[i, j], Te[i, j] = hj, 2 * dt if half else dt, Tj
    ds = xr.Dataset(
        {"T_elliptic": (("M", "h"), T), "h_check": (("M", "check"), hc),
         "T_integrated": (("M", "check"), Tc), "T_elliptic_check": (("M", "check"), Te)},
        coords={"M": list(M_values), "h": h},
        attrs={"body_mu": mu, "equations": "reduced Hamiltonian on theta1 = 0 of (16)"})
    ds.T_elliptic.attrs.update(long_name="period by complete elliptic integrals K(m)")
    ds.T_integrated.attrs.update(long_name="period from crossings of G = const of the "
                                 "integrated Euler-Poisson orbit")
    ds.T_elliptic_check.attrs.update(long_name="closed-form period at h_check")
    return ds
