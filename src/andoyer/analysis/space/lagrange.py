r"""The body in space: precession, nutation, axis traces, the herpolhode, the Lagrange top.

Everything here reads the attitude datasets of :func:`andoyer.integrate.attitude`
(quaternion, rotation ``R`` body -> space, Euler angles ``z-x-z``; conventions in
:mod:`andoyer.charts.rotation`) or gives a closed form to check them against.

The Lagrange top (``A = B``, centre of mass on the symmetry axis ``z``)
-------------------------------------------------------------------------
With ``a = b`` the integrals are the energy ``E``, ``L = G3`` (``dG3/dt = 0``) and
the area integral ``M = (G, gamma)``. With ``u = gamma3 = cos theta`` (derived here,
checked by integration in the tests): ``du/dt = a (G2 gamma1 - G1 gamma2)`` and the
identity ``(G2 gamma1 - G1 gamma2)^2 + (G1 gamma1 + G2 gamma2)^2 = (G1^2 + G2^2)
(gamma1^2 + gamma2^2)`` with ``G1 gamma1 + G2 gamma2 = M - L u``,
``a (G1^2 + G2^2) = 2 E - c L^2 - 2 mu u`` give

.. math:: \dot u^2 = f(u) = a (2E - cL^2 - 2\mu u)(1 - u^2) - a^2 (M - L u)^2,

a cubic with leading coefficient ``2 a mu > 0``: ``f(u) = 2 a mu (u - u1)(u - u2)(u - u3)``,
``-1 <= u1 <= u2 <= 1 < u3``. The axis nutates between ``theta = arccos u2`` and
``arccos u1``. The precession rate is
``dpsi/dt = (omega1 gamma1 + omega2 gamma2)/(1 - u^2) = a (M - L u)/(1 - u^2)``, and over
one nutation period (``u = u1 + (u2 - u1)(1 - cos s)/2``, ``dt = ds / sqrt(2 a mu (u3 - u))``,
a smooth integrand on ``s in [0, pi]``)

.. math:: T = 2\int_0^\pi \frac{ds}{\sqrt{2 a \mu (u_3 - u)}}, \qquad
          \langle\dot\psi\rangle = \frac{2}{T}\int_0^\pi
          \frac{a (M - L u)}{(1 - u^2)\sqrt{2 a \mu (u_3 - u)}}\, ds

with the period also in closed form, ``T = 4 K(m) / sqrt(2 a mu (u3 - u1))``,
``m = (u2 - u1)/(u3 - u1)`` (Gauss-Legendre quadrature to round-off for the rate, its
error estimated by halving the nodes: :func:`lagrange_top`).

Where the formulas hold: the regimes
------------------------------------
The quadratures describe a nutation between two distinct turning points of ``f``. At
the vertical (``u0 = +-1`` with ``G`` along the axis) the state is an equilibrium and
``f`` has a double root there: the cubic then describes the separatrix leaving it, not
the motion. :func:`lagrange_top` says which case a state is in (``regime``, one of
:data:`REGIMES`) and gives NaN, so flagged, for what the regime leaves undefined:

* ``nutating``: ``u1 < u2``, the axis nutates between ``arccos u2`` and ``arccos u1``;
* ``regular_precession``: ``u1 = u2`` (to :data:`REGIME_RTOL`): a fixed tilt; the period
  is the limit of small nutations;
* ``through_the_pole``: ``M = +-L``: a turning point is ``u = +-1``, the axis passes
  through the vertical, where ``psi`` jumps by ``pi``: no mean precession rate;
* ``sleeping``: upright (``u0 = 1``, ``G`` along the axis) and ``a L^2 > 4 mu``: the
  stable sleeping top, ``theta`` stays at the vertical, no nutation, ``psi`` undefined;
* ``upright_unstable``: upright with ``a L^2 <= 4 mu``: an unstable equilibrium; the
  state stays there, while the cubic (roots ``u*, 1, 1``) describes its separatrix;
* ``separatrix``: on that separatrix (``M = L``, ``2E - c L^2 = 2 mu``, ``u0 < 1``): the
  axis tends to the vertical for ever (infinite period, no mean rate);
* ``hanging``: ``u0 = -1`` with ``G`` along the axis (the centre of mass below the fixed
  point): a stable equilibrium, no nutation, ``psi`` undefined.

Here ``u`` is the height ``(r, gamma)`` of the axis to the centre of mass; the roots
``u_roots`` are those of ``cos theta`` of the body axis ``z``, ascending (for
``r = (0, 0, -1)`` they are the negated roots, so the motion lies between ``u2`` and
``u3``).
"""

from __future__ import annotations

import math

import numpy as np
import scipy.special
import xarray as xr
from numpy.typing import ArrayLike

from andoyer.body import RigidBody, checks_body
from andoyer.charts.euler_poisson import as_state
from andoyer.integrate.results import VariableMeta, describe_variables, provenance
from andoyer.validation import MAX_ACTION

__all__ = ["lagrange_top", "REGIMES", "REGIME_RTOL"]

#: Closed forms only: levels and actions up to ``|G| = MAX_ACTION``
#: (:func:`andoyer.validation.momentum_limit`).
CLOSED_FORM = True

#: Gauss-Legendre nodes of the quadratures of :func:`lagrange_top` (smooth integrands).
_QUADRATURE_NODES = 200

#: The regimes of :func:`lagrange_top` (module notes): name -> what the values mean.
REGIMES = {
    "nutating": "the axis nutates between two tilts",
    "regular_precession": "u1 = u2: the axis precesses at a fixed tilt",
    "through_the_pole": "M = +-L: the axis passes through the vertical (psi jumps by pi: "
                        "no mean precession rate)",
    "sleeping": "upright and a L^2 > 4 mu: the stable sleeping top (no nutation, psi "
                "undefined)",
    "upright_unstable": "upright and a L^2 <= 4 mu: an unstable equilibrium (the cubic "
                        "describes the separatrix, not the motion)",
    "separatrix": "on the separatrix of the upright top: the axis tends to the vertical "
                  "for ever (infinite period, no mean precession rate)",
    "hanging": "hanging with G along the axis: a stable equilibrium (no nutation, psi "
               "undefined)",
}
#: Relative tolerance of the regimes: ``|M -+ L|`` and ``|2E - c L^2 -+ 2 mu|`` against
#: the scales ``max(|G|, sqrt(mu/a))`` and ``a |G|^2 + c L^2 + 2 mu``; ``u2 - u1`` against 1.
REGIME_RTOL = 1e-12

_NAN_NOTE = " (NaN: undefined in the regime, see regime)"
_LAGRANGE_META: dict[str, VariableMeta] = {
    "u_roots": ("u_i", "roots of the cubic f(u) = (du/dt)^2, u = cos θ of the body axis z, "
                "ascending", "1", ""),
    "nutation_min": ("θ_min", "least nutation angle", "rad", ""),
    "nutation_max": ("θ_max", "largest nutation angle", "rad", ""),
    "nutation_period": ("T_θ", "period of the nutation" + _NAN_NOTE, "body time units", ""),
    "precession_rate": ("<dψ/dt>", "mean precession rate over a nutation period" + _NAN_NOTE,
                        "rad/body time unit", ""),
    "precession_rate_error": ("", "estimated error of the quadrature of the rate"
                              + _NAN_NOTE, "rad/body time unit", ""),
    "regime": ("", "the kind of motion: " + ", ".join(REGIMES), "", ""),
}


def _rate(a: float, kappa: float, M: float, L: float, u1: float, u2: float, u3: float,
          nodes: int) -> float:
    """The mean precession rate by Gauss-Legendre quadrature on ``nodes`` nodes."""
    x, w = np.polynomial.legendre.leggauss(nodes)
    sv = 0.5 * math.pi * (x + 1.0)
    wv = 0.5 * math.pi * w
    u = u1 + (u2 - u1) * 0.5 * (1.0 - np.cos(sv))
    dt = 1.0 / np.sqrt(kappa * (u3 - u))
    T = 2.0 * float(np.sum(wv * dt))
    return 2.0 * float(np.sum(wv * a * (M - L * u) / ((1.0 - u) * (1.0 + u)) * dt)) / T


def _regime(a: float, c: float, mu: float, G: np.ndarray, L: float, M: float, E: float,
            u0: float, u1: float, u2: float) -> str:
    """The regime of the module notes (:data:`REGIMES`) of a state."""
    g_scale = max(float(np.linalg.norm(G)), math.sqrt(mu / a))
    e_scale = a * float(G @ G) + c * L * L + 2.0 * mu
    top = abs(M - L) <= REGIME_RTOL * g_scale       # f(1) = 0: u = 1 is a root
    bottom = abs(M + L) <= REGIME_RTOL * g_scale    # f(-1) = 0
    if top and abs(2.0 * E - c * L * L - 2.0 * mu) <= REGIME_RTOL * e_scale:
        # u = 1 is a double root: the upright equilibrium or its separatrix.
        if u0 >= 1.0 - REGIME_RTOL:
            return "sleeping" if a * L * L > 4.0 * mu else "upright_unstable"
        return "separatrix"
    if bottom and abs(2.0 * E - c * L * L + 2.0 * mu) <= REGIME_RTOL * e_scale:
        return "hanging"
    if (top and u2 >= 1.0 - 1e-8) or (bottom and u1 <= -1.0 + 1e-8):
        return "through_the_pole"
    if u2 - u1 <= REGIME_RTOL:
        return "regular_precession"
    return "nutating"


@checks_body
def lagrange_top(body: RigidBody, y0: ArrayLike) -> xr.Dataset:
    """Nutation bounds, nutation period and mean precession rate of a Lagrange top.

    Parameters
    ----------
    body : RigidBody
        ``A = B`` (to 1e-12), the centre of mass on the axis ``z`` (``r = (0, 0, +-1)``),
        ``mu > 0``.
    y0 : array_like, shape (6,)
        A state ``(G, gamma)`` of the orbit (``|gamma| = 1``).

    Returns
    -------
    xarray.Dataset
        0-d variables ``regime`` (one of :data:`REGIMES`: where the formulas hold),
        ``nutation_min``, ``nutation_max`` (rad), ``nutation_period``,
        ``precession_rate``, ``precession_rate_error`` (the quadrature's, estimated with
        half the nodes) and ``u_roots`` (dim ``root``, ascending), from the cubic of the
        module notes. Where the axis stays at one tilt (``regular_precession``) the
        period is the limit of the small nutations; what a regime leaves undefined is
        NaN (no nutation at an equilibrium, an infinite period on the separatrix, no mean
        rate through the pole), and the nutation bounds are those of the motion (an
        equilibrium's tilt, not the separatrix's range).

    Examples
    --------
    >>> body = RigidBody.lagrange(1.0, 0.6, 1.0)
    >>> top = lagrange_top(body, [0.2, 0.1, 1.5, 0.0, math.sin(0.8), math.cos(0.8)])
    >>> str(top.regime.values), round(float(top.nutation_min), 9)
    ('nutating', 0.766506599)
    >>> round(float(top.nutation_max), 9)
    1.681148046

    A slow top standing upright (``a L^2 < 4 mu``) is an unstable equilibrium:

    >>> up = lagrange_top(body, [0.0, 0.0, 0.5, 0.0, 0.0, 1.0])
    >>> str(up.regime.values), float(up.nutation_max), bool(np.isnan(up.nutation_period))
    ('upright_unstable', 0.0, True)
    """
    if not (abs(body.a - body.b) <= 1e-12 * body.a and abs(body.e1) <= 1e-12
            and abs(body.e2) <= 1e-12 and body.mu > 0.0):
        raise ValueError("body must be a Lagrange top: A = B, centre of mass on the axis z "
                         f"(r = (0, 0, +-1)) and mu > 0; got A={body.A}, B={body.B}, "
                         f"r=({body.e1}, {body.e2}, {body.e3}), mu={body.mu}")
    y = as_state(y0, "y0")
    if y.shape != (6,):
        raise ValueError(f"y0 must be one state, shape (6,), got {y.shape}")
    if abs(float(np.linalg.norm(y[3:])) - 1.0) > 1e-12:
        raise ValueError("y0: gamma must be a unit vector")
    if float(np.max(np.abs(y[:3]))) > MAX_ACTION:
        raise ValueError(f"y0: |G| must be at most {MAX_ACTION:g} (a closed form's limit), "
                         f"got {float(np.max(np.abs(y[:3]))):g}")
    a, c = body.a, body.c
    # r = (0, 0, s): write the motion for the axis pointing to the centre of mass.
    s = 1.0 if body.e3 > 0.0 else -1.0
    mu = body.mu
    G, gamma = y[:3], y[3:]
    L = s * G[2]
    u0 = s * gamma[2]
    M = float(G @ gamma)
    E = 0.5 * (a * (G[0] ** 2 + G[1] ** 2) + c * G[2] ** 2) + mu * u0
    P = np.polynomial.Polynomial
    f = a * P([2 * E - c * L * L, -2 * mu]) * P([1.0, 0.0, -1.0]) - a * a * P([M, -L]) ** 2
    roots = np.sort(np.real_if_close(f.roots(), tol=1e6).real)
    if roots.size != 3 or not np.all(np.isfinite(roots)):
        raise ValueError("y0: the cubic of the nutation is degenerate")
    u1, u2, u3 = (float(v) for v in roots)
    # Round-off can put the turning points a hair past the state; clip to it.
    u1, u2 = min(u1, u0), max(u2, u0)
    regime = _regime(a, c, mu, G, L, M, E, u0, u1, u2)
    kappa = 2.0 * a * mu
    nan = math.nan
    if regime in ("sleeping", "upright_unstable", "hanging"):
        lo = hi = u0  # the equilibrium's tilt, not the separatrix's range
        T = rate = error = nan
    elif regime == "separatrix":
        lo, hi = min(u1, u0), 1.0
        T = rate = error = nan
    else:
        lo, hi = u1, u2
        # T = 4 K(m) / sqrt(kappa (u3 - u1)), with 1 - m = (u3 - u2)/(u3 - u1) exactly.
        T = 4.0 * float(scipy.special.ellipkm1((u3 - u2) / (u3 - u1))) / math.sqrt(
            kappa * (u3 - u1))
        if regime == "through_the_pole":
            rate = error = nan
        else:
            rate = _rate(a, kappa, M, L, u1, u2, u3, _QUADRATURE_NODES)
            error = abs(rate - _rate(a, kappa, M, L, u1, u2, u3, _QUADRATURE_NODES // 2))
    # theta of the body axis z (for r = -z the axis to the centre of mass is -z).
    th = np.arccos(np.clip(s * np.array([hi, lo]), -1.0, 1.0))
    ds = xr.Dataset(
        {"u_roots": ("root", np.sort(s * np.array([u1, u2, u3]))),
         "nutation_min": ((), float(th.min())), "nutation_max": ((), float(th.max())),
         "nutation_period": ((), T), "precession_rate": ((), rate),
         "precession_rate_error": ((), error), "regime": ((), regime)},
        attrs=provenance(body, engine="closed form (Gauss-Legendre quadrature)",
                         equations="Lagrange top: (du/dt)^2 = f(u), u = cos theta",
                         M=M, L=float(G[2]), E=E, regime=regime))
    return describe_variables(ds, _LAGRANGE_META)
