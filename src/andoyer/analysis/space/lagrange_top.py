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

(Gauss-Legendre quadrature to round-off: :func:`lagrange_top`).
"""

from __future__ import annotations

import math

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike

from andoyer.body import RigidBody, checks_body
from andoyer.charts.euler_poisson import as_state
from andoyer.integrate.results import VariableMeta, describe_variables, provenance

__all__ = ["lagrange_top"]

#: Closed forms only: levels and actions up to ``|G| = MAX_ACTION``
#: (:func:`andoyer.validation.momentum_limit`).
CLOSED_FORM = True

#: Gauss-Legendre nodes of the quadratures of :func:`lagrange_top` (smooth integrands).
_QUADRATURE_NODES = 200

_LAGRANGE_META: dict[str, VariableMeta] = {
    "u_roots": ("u_i", "roots u1 <= u2 <= u3 of the cubic f(u) = (du/dt)^2, u = cos θ",
                "1", ""),
    "nutation_min": ("θ_min", "least nutation angle, arccos u2", "rad", ""),
    "nutation_max": ("θ_max", "largest nutation angle, arccos u1", "rad", ""),
    "nutation_period": ("T_θ", "period of the nutation", "body time units", ""),
    "precession_rate": ("<dψ/dt>", "mean precession rate over a nutation period",
                        "rad/body time unit", ""),
}


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
        0-d variables ``nutation_min``, ``nutation_max`` (rad), ``nutation_period``,
        ``precession_rate`` and ``u_roots`` (dim ``root``), from the cubic of the module
        notes. Where the axis stays at one tilt (``u1 = u2``: regular precession) the
        period is the limit of the small nutations.

    Examples
    --------
    >>> body = RigidBody.lagrange(1.0, 0.6, 1.0)
    >>> top = lagrange_top(body, [0.2, 0.1, 1.5, 0.0, math.sin(0.8), math.cos(0.8)])
    >>> round(float(top.nutation_min), 9), round(float(top.nutation_max), 9)
    (0.766506599, 1.681148046)
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
    if roots.size != 3:
        raise ValueError("y0: the cubic of the nutation is degenerate")
    u1, u2, u3 = roots
    # Round-off can put the turning points a hair past the state; clip to it.
    u1, u2 = min(u1, u0), max(u2, u0)
    kappa = 2.0 * a * mu
    x, w = np.polynomial.legendre.leggauss(_QUADRATURE_NODES)
    sv = 0.5 * math.pi * (x + 1.0)
    wv = 0.5 * math.pi * w
    u = u1 + (u2 - u1) * 0.5 * (1.0 - np.cos(sv))
    dt = 1.0 / np.sqrt(kappa * (u3 - u))
    T = 2.0 * float(np.sum(wv * dt))
    rate = 2.0 * float(np.sum(wv * a * (M - L * u) / ((1.0 - u) * (1.0 + u)) * dt)) / T
    # theta of the body axis z (for r = -z the axis to the centre of mass is -z).
    th = np.arccos(np.clip(s * np.array([u2, u1]), -1.0, 1.0))
    ds = xr.Dataset(
        {"u_roots": ("root", s * np.array([u1, u2, u3])),
         "nutation_min": ((), float(th.min())), "nutation_max": ((), float(th.max())),
         "nutation_period": ((), T), "precession_rate": ((), rate)},
        attrs=provenance(body, engine="closed form (Gauss-Legendre quadrature)",
                         equations="Lagrange top: (du/dt)^2 = f(u), u = cos theta",
                         M=M, L=float(G[2]), E=E))
    return describe_variables(ds, _LAGRANGE_META)
