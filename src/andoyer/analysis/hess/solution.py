"""The Hess solution ``theta1 = 0``: the reduced pendulum, its periods and its closed form.

On a Hess body the invariant relation (3) is ``theta1 = 0 (mod 2 pi)`` in the Hess chart
(14). There ``dtheta1/dt = 0`` and the Hess-chart Hamiltonian (derived from Eq. (1),
:func:`andoyer.symbolic.hamiltonian.H_hess`; see :func:`derive_reduced_hamiltonian`)
loses its ``J1``-dependence:

.. math::

    H = \\tfrac12 c J_2^2 + \\mu \\frac{\\sqrt{J_2^2 - M^2}}{J_2} \\sin\\theta_2 ,

a system of one degree of freedom in ``(theta2, J2)`` with ``M = J3`` a parameter. At
``M = 0`` it is the pendulum ``H = c J2^2/2 + mu sin(theta2)``
(:func:`andoyer.analysis.hess.pendulum.pendulum_solution`). Both sheets ``theta1 = 0`` and
``theta1 = 2 pi`` of the double cover give the same reduced Hamiltonian.

The rest follows by quadrature (module functions in brackets):

* ``J1``. The angle ``psi`` of G from the body axis 3 in the Hess plane
  ``(G, r) = 0`` (``cos psi = L/G``, ``J1 = J2 cos^2(psi/2)``; ``sin psi > 0`` on the
  sheet ``theta1 = 0``, ``< 0`` on ``theta1 = 2 pi``) obeys
  ``dpsi/dt = -(s/2) J2 sin(psi) + mu M / J2^2`` with ``s = kappa sin(2 phi0)``
  (:func:`drift_rate`). At ``M = 0``, since ``dtheta2/dt = c J2``,
  ``tan(psi/2) = tan(psi0/2) exp(-s (theta2 - theta2(0)) / (2 c))``: closed form. For
  ``M != 0`` it is a Riccati equation, integrated along the closed-form ``J2(t)``.
* ``theta3 = m``: ``dtheta3/dt = -mu M sin(theta2) / (J2 sqrt(J2^2 - M^2))
  = -M (h - c J2^2/2) / (J2^2 - M^2)``; zero at ``M = 0``.
* ``J2(t)``: ``u = J2^2`` obeys ``(du/dt)^2 = 4 P(u)``,
  ``P(u) = mu^2 (u - M^2) - u (h - c u/2)^2 = (c^2/4)(u - u_a)(u - u_b)(u_c - u)``, so
  ``u = u_c - (u_c - u_b) sn^2(omega t + u0, m)``, ``omega = (c/2) sqrt(u_c - u_a)``,
  ``m = (u_c - u_b)/(u_c - u_a)``, and the period is
  ``T = 4 K(m) / (c sqrt(u_c - u_a))`` (:func:`period`).

The passage through ``G = 0`` (``M = 0`` librations)
----------------------------------------------------
The ``M = 0`` libration of the pendulum in the signed ``J2`` passes ``J2 = G = 0`` twice
per period (at its turning points: the body is momentarily at rest), where every chart
is singular. In the Euler-Poisson variables nothing happens: G passes linearly through
0 and reverses. The chart (``G >= 0``) sees the continuation as

    (theta1, theta2, J1, J2, theta3)
        -> (theta1 + 2 pi, pi - theta2, J1 - J2, -J2, theta3 + pi)

for signed ``J2 < 0`` (``J1 = J2 cos^2(psi/2)`` signed with it): the sheet flips
(``G1, G2`` reverse), ``L/G`` changes sign, ``m`` moves by pi, and ``theta2`` jumps
from one turning point ``3 pi/2 + alpha`` to the other
``3 pi/2 - alpha`` (**not** by pi: ``sin theta2`` is fixed by the energy). So in the
chart ``theta2`` runs over the same arc in every half-period and ``J2 >= 0`` reflects;
``(theta2, J2)`` is T/2-periodic, the physical state is T-periodic. The map
:func:`hess_state` -- the chain (5)-(6) at ``l = -phi0``, ``g = theta2`` with signed
``G = J2`` and ``(cos J, sin J) = (cos psi, sin psi)`` -- is regular across ``G = 0``
and gives the Euler-Poisson state of the continuation.

On the heteroclinic ``M = 0`` rotations: ``psi`` tends to ``pi`` (branch +1, ``s < 0``)
or 0 (branch -1) as ``t -> +inf``: the Hess rotations are heteroclinic between the
physical-pendulum rotations ``L = +G`` and ``L = -G`` (which are hyperbolic,
:mod:`andoyer.analysis.hess.pendulum`). The Hess relation (3) is not attracting; for long
integrations use :func:`andoyer.integrate.propagate_hess_manifold`.

References
----------
.. [1] V. V. Kyrychenko, "Andoyer-Deprit variables use to the Hess gyroscope phase
   trajectories exploring", National Aviation University, Kyiv (``andoyer.cite("paper")``).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray
from scipy.special import ellipj

from andoyer.analysis.hess import reduced
from andoyer.analysis.hess.pendulum import (
    pendulum_solution,
)
from andoyer.analysis.hess.reduced import MOTIONS as MOTIONS
from andoyer.analysis.hess.reduced import broadcast_points, check_hess
from andoyer.analysis.hess.reduced import classify_motion as classify_motion
from andoyer.analysis.hess.reduced import cubic_roots as cubic_roots
from andoyer.analysis.hess.reduced import derive_reduced_hamiltonian as derive_reduced_hamiltonian
from andoyer.analysis.hess.reduced import drift_rate as drift_rate
from andoyer.analysis.hess.reduced import energy_minimum as energy_minimum
from andoyer.analysis.hess.reduced import period as period
from andoyer.analysis.hess.reduced import reduced_field as reduced_field
from andoyer.analysis.hess.reduced import reduced_hamiltonian as reduced_hamiltonian
from andoyer.analysis.unperturbed.euler_poinsot import elliptic_f
from andoyer.body import RigidBody, checks_body
from andoyer.charts.andoyer_deprit import rotation_chain_expr
from andoyer.integrate.hess_manifold import THETA1_TOL
from andoyer.integrate.results import provenance, states_dataset
from andoyer.validation import checks_arguments

#: The reduced system's names (re-exported from :mod:`andoyer.analysis.hess.reduced`) and
#: the closed-form motion's.
__all__ = [
    *reduced.__all__,
    "hess_state",
    "signed_to_hess",
    "hess_solution",
]

#: Closed forms only: levels and actions up to ``|G| = MAX_ACTION``
#: (:func:`andoyer.validation.momentum_limit`).
CLOSED_FORM = True

# ----------------------------------------------------------------------------- embedding
@checks_body(ranges={"theta2": "angle", "J2": "action", "psi": "angle", "M": "action"},
             closed_form=CLOSED_FORM)
def hess_state(body: RigidBody, theta2: ArrayLike, J2: ArrayLike, psi: ArrayLike,
               M: float = 0.0) -> NDArray[np.float64]:
    """Euler-Poisson state of the Hess solution from ``(theta2, J2, psi)``; shape ``(..., 6)``.

    ``G = J2 (sin(psi) n + cos(psi) k)`` with ``n = k x r = (-e2, e1, 0)`` and ``gamma``
    from the chain (5)-(6) at ``l = -phi0``, ``g = theta2``, ``cos J = cos psi``,
    ``sin J = sin psi`` (``sin psi < 0`` is the sheet ``theta1 = 2 pi``). At ``M = 0``
    ``J2`` may be negative (the signed pendulum picture): the map is regular at ``G = 0``.

    Parameters
    ----------
    body : RigidBody
        A Hess body.
    theta2 : array_like
        Hess-chart angle ``theta2`` (rad), Eq. (13).
    J2 : array_like
        ``J2 = |G|`` (signed at ``M = 0``: the signed pendulum picture).
    psi : array_like
        Angle of ``G`` about ``r`` in the plane ``(n, k)``: ``cos J = cos psi``.
    M : float, default 0.0
        Area constant ``(G, gamma) = M``.
    """
    t2, j2, ps = broadcast_points(theta2=theta2, J2=J2, psi=psi)
    if M == 0.0:
        cI, sI = np.zeros(j2.shape), np.ones(j2.shape)
    else:
        if np.any(np.abs(j2) < abs(M)):
            raise ValueError("J2 = G must not be below |M|")
        cI, sI = M / j2, np.sqrt((j2 - M) * (j2 + M)) / j2
    cols = rotation_chain_expr(-body.phi0, t2, j2, np.cos(ps), np.sin(ps), cI, sI,
                               sin=np.sin, cos=np.cos)
    return np.stack(np.broadcast_arrays(*cols), axis=-1)


@checks_arguments(ranges={"theta2": "angle", "J2": "action", "psi": "angle", "M": "action"},
                  closed_form=CLOSED_FORM)
def signed_to_hess(theta2: ArrayLike, J2: ArrayLike, psi: ArrayLike, M: float = 0.0
                   ) -> NDArray[np.float64]:
    """Hess-chart values ``(theta1, theta2, J1, J2, J3)`` of signed-picture states.

    For signed ``J2 < 0`` (``M = 0`` only) the chart rule at the ``G = 0`` passage
    applies: ``psi -> psi + pi``, ``theta2 -> pi - theta2``, ``J2 -> -J2`` (module
    notes). ``theta1 = 0`` where ``sin psi >= 0``, else ``2 pi``; ``J1 = J2 cos^2(psi/2)``;
    ``theta2`` reduced to ``[0, 2 pi)``.

    Parameters
    ----------
    theta2, J2, psi : array_like
        Signed-picture state (``J2 < 0`` allowed at ``M = 0``; angles in rad).
    M : float, default 0.0
        Area constant ``(G, gamma) = M``.
    """
    t2, j2, ps = broadcast_points(theta2=theta2, J2=J2, psi=psi)
    neg = j2 < 0.0
    if np.any(neg) and M != 0.0:
        raise ValueError("J2 < 0 only exists in the M = 0 signed picture")
    ps = np.where(neg, ps + math.pi, ps)
    t2 = np.mod(np.where(neg, math.pi - t2, t2), math.tau)
    t2 = np.where(t2 >= math.tau, 0.0, t2)
    G = np.abs(j2)
    theta1 = np.where(np.sin(ps) >= 0.0, 0.0, math.tau)
    J1 = G * np.cos(0.5 * ps) ** 2
    return np.stack(np.broadcast_arrays(theta1, t2, J1, G, np.full(G.shape, float(M))),
                    axis=-1)


# ----------------------------------------------------------------------------- solution
def _initial(body: RigidBody, x0: ArrayLike) -> tuple[float, float, float, float, float]:
    """``(theta1, theta2, J1, J2, M)`` of a Hess-chart point on the manifold."""
    arr = np.asarray(x0, dtype=float)
    if arr.shape != (5,) or not np.all(np.isfinite(arr)):
        raise ValueError("x0 must be one finite Hess-chart point (theta1, theta2, J1, J2, J3), "
                         f"shape (5,), got {arr.shape}")
    theta1, theta2, J1, J2, M = (float(v) for v in arr)
    if abs(math.remainder(theta1, math.tau)) > THETA1_TOL:
        raise ValueError(f"x0: theta1 = {theta1!r} is not on the Hess manifold theta1 = 0 "
                         "(mod 2 pi); the Hess solution lives there")
    theta1 = 0.0 if abs(math.remainder(theta1, 4.0 * math.pi)) <= THETA1_TOL else math.tau
    if not J2 > 0.0:
        raise ValueError(f"x0: J2 = G must be > 0, got {J2!r}")
    if not 0.0 <= J1 <= J2:
        raise ValueError(f"x0: J1 = (G + L)/2 must lie in [0, J2 = {J2:g}], got {J1!r}")
    if not abs(M) < J2:
        raise ValueError(f"x0: |J3| = |M| must be < J2 = G (|M| = G is the chart's singular "
                         f"point), got M = {M!r}, J2 = {J2!r}")
    return theta1, theta2, J1, J2, M


def _psi0(theta1: float, J1: float, J2: float) -> float:
    """``psi`` at ``t0``: ``cos psi = (2 J1 - J2)/J2`` and the sign from the sheet."""
    psi = 2.0 * math.atan2(math.sqrt(J2 - J1), math.sqrt(J1))
    return psi if theta1 == 0.0 else -psi


def _solution_m0(body: RigidBody, theta2_0: float, J2_0: float, psi0: float,
                 tau: NDArray[np.float64]) -> dict[str, NDArray[np.float64]]:
    c = body.c
    q, p = pendulum_solution(c, body.mu, theta2_0, J2_0, tau)
    # tan(psi/2) = tan(psi0/2) exp(-A), A = s (theta2 - theta2_0) / (2 c); written as an
    # atan2 of two factors so that cos^2(psi/2) keeps its relative accuracy.
    A = np.clip(drift_rate(body) * (q - theta2_0) / (2.0 * c), -700.0, 700.0)
    S = math.sin(0.5 * psi0) * np.exp(-0.5 * A)
    C = math.cos(0.5 * psi0) * np.exp(0.5 * A)
    psi = 2.0 * np.arctan2(S, C)
    theta3 = np.where(p < 0.0, math.pi, 0.0)
    norm = S * S + C * C
    return {"theta2": q, "J2": p, "psi": psi, "theta3": theta3,
            "cos2": C * C / norm, "sin2": S * S / norm}


def _initial_phase(u0: float, udot0: float, ub: float, uc: float, omega: float,
                   m: float) -> float:
    """The argument ``omega t0 + phase`` at ``u0 = J2(t0)^2`` of
    ``u = u_c - (u_c - u_b) sn^2``, without the square-root cancellation of the turning points.

    ``sn^2 = (u_c - u0)/(u_c - u_b)`` alone gives ``sn`` to only ``sqrt(eps)`` near
    ``u0 = u_c`` (``cn`` near ``u_b``), where the root carries an absolute error ``eps u_c``;
    there ``du/dt = -2 (u_c - u_b) omega sn cn dn`` gives the small factor to full
    accuracy (``du/dt`` is a product with the state's ``cos theta2``): ``sn = D/(cn dn)``
    near ``u_c``, ``cn = D/(sn dn)`` near ``u_b``, ``D = -(du/dt)/(2 (u_c - u_b) omega)``.
    Measured at the turning points (``M = 0.03``, paper body): the state against
    integration from 1.2e-8 to 1.5e-12, ``|H - h|`` from 1e-10 to 4e-18.
    """
    width = uc - ub
    if not width > 0.0:
        return 0.0
    s2 = min(1.0, max(0.0, (uc - u0) / width))
    c2 = min(1.0, max(0.0, (u0 - ub) / width))
    D = -udot0 / (2.0 * width * omega)  # = sn cn dn
    if s2 <= c2:       # nearer u_c: sn is the small factor, cn > 0 chosen
        cn = math.sqrt(c2)
        sn = D / (cn * math.sqrt(1.0 - m * s2))
    else:              # nearer u_b: cn is the small factor, sn > 0 chosen
        sn = math.sqrt(s2)
        cn = D / (sn * math.sqrt(1.0 - m * s2))
    return float(elliptic_f(math.atan2(sn, cn), m))


def _solution_m(body: RigidBody, theta2_0: float, J2_0: float, psi0: float, M: float,
                tau: NDArray[np.float64], rtol: float, atol: float
                ) -> dict[str, NDArray[np.float64]]:
    from andoyer.integrate.engines.ivp import solve_dop853

    c, mu = body.c, body.mu
    h = float(reduced_hamiltonian(body, theta2_0, J2_0, M))
    ua, ub, uc = cubic_roots(body, h, M)
    width = uc - ub
    omega = 0.5 * c * math.sqrt(uc - ua)
    m = width / (uc - ua)
    u0 = J2_0 * J2_0
    udot0 = -2.0 * mu * math.sqrt((J2_0 - M) * (J2_0 + M)) * math.cos(theta2_0)
    phase = _initial_phase(u0, udot0, ub, uc, omega, m)

    # At the centre the roots u_b = u_c are ill-conditioned (sqrt(eps)): hold J2 there.
    still = classify_motion(body, h, M) == "equilibrium"

    def closed(t: NDArray[np.float64] | float) -> tuple[Any, Any, Any]:
        if still:
            shape = np.shape(t)
            return np.full(shape, u0), np.full(shape, J2_0), np.full(shape, theta2_0)
        sn, cn, dn, _ = ellipj(omega * np.asarray(t) + phase, m)
        u = uc - width * sn * sn
        udot = -2.0 * width * omega * sn * cn * dn
        J2 = np.sqrt(u)
        theta2 = np.arctan2((h - 0.5 * c * u) * J2, -0.5 * udot)
        return u, J2, theta2

    u, J2, theta2 = closed(tau)
    theta2 = np.unwrap(np.atleast_1d(theta2))
    theta2 = theta2 + (theta2_0 - theta2[0])  # anchor the branch (atan2 gives it mod 2 pi)

    def rhs(t: float, z: NDArray[np.float64]) -> NDArray[np.float64]:
        uu, jj, _ = closed(t)
        uu, jj = float(uu), float(jj)
        return np.array([-0.5 * drift_rate(body) * jj * math.sin(z[0]) + mu * M / uu,
                         -M * (h - 0.5 * c * uu) / ((jj - M) * (jj + M))])

    if tau.size > 1:
        psi, theta3 = solve_dop853(rhs, tau, np.array([psi0, 0.0]), rtol, atol).y
    else:
        psi, theta3 = np.array([psi0]), np.array([0.0])
    return {"theta2": theta2, "J2": np.atleast_1d(J2), "psi": psi, "theta3": theta3,
            "cos2": np.cos(0.5 * psi) ** 2, "sin2": np.sin(0.5 * psi) ** 2}


@checks_body(ranges={"rtol": "tolerance", "atol": "tolerance"})
def hess_solution(body: RigidBody, x0: ArrayLike, t: ArrayLike, *, rtol: float = 1e-12,
                  atol: float = 1e-12) -> xr.Dataset:
    """The Hess solution from a point of ``theta1 = 0``, in closed form where it exists.

    Parameters
    ----------
    body : RigidBody
        A Hess body (``is_hess``), ``mu > 0``.
    x0 : array_like, shape (5,)
        Hess-chart point ``(theta1, theta2, J1, J2, J3)`` with ``theta1 = 0`` or ``2 pi``
        (within ``THETA1_TOL``), ``J2 > 0``, ``0 <= J1 <= J2`` (``J1 = 0, J2`` is the
        physical pendulum), ``|J3| < J2``.
    t : array_like, shape (k,)
        Output times, strictly increasing; ``x0`` is the state at ``t[0]``.
    rtol, atol : float
        Tolerances of the quadrature of ``psi`` and ``theta3`` (``M != 0`` only).

    Returns
    -------
    xarray.Dataset
        Dims ``(time,)``. The chart values ``theta1 .. J3`` (with the ``G = 0`` rule of
        the module notes), ``theta3`` (from 0 at ``t[0]``; at ``M = 0`` it is 0, and pi
        while the signed ``J2 < 0``), the signed picture ``theta2_signed`` (unwrapped)
        and ``J2_signed``, ``psi``, the Euler-Poisson state ``G1 .. gamma3`` of
        :func:`hess_state`, the Andoyer-Deprit coordinates and ``H``. Attrs: ``h``,
        ``M``, ``motion``, ``period`` (:func:`period`), ``drift_rate``, provenance.

    Notes
    -----
    ``M = 0``: everything is closed form (``theta2, J2`` by Jacobi functions, ``psi`` by
    the exponential law). ``M != 0``: ``J2`` and ``theta2`` closed form, ``psi`` and
    ``theta3`` by DOP853 quadrature along them.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> ds = hess_solution(RigidBody.paper(), [0.0, 4.7, 0.03, 0.1, 0.0], [0.0, 50.0])
    >>> ds.attrs["motion"], bool(abs(ds.H - ds.attrs["h"]).max() < 1e-15)
    ('libration', True)
    """
    check_hess(body)
    theta1, theta2_0, J1_0, J2_0, M = _initial(body, x0)
    times = np.asarray(t, dtype=float)
    if times.ndim != 1 or times.size < 1 or not np.all(np.isfinite(times)):
        raise ValueError(f"t must be a 1-D array of finite output times, got shape {times.shape}")
    if np.any(np.diff(times) <= 0.0):
        raise ValueError("t must be strictly increasing")
    psi0 = _psi0(theta1, J1_0, J2_0)
    h = float(reduced_hamiltonian(body, theta2_0, J2_0, M))
    motion = classify_motion(body, h, M)
    if M == 0.0:
        sol = _solution_m0(body, theta2_0, J2_0, psi0, times)
        method = "closed form: Jacobi elliptic functions (theta2, J2), exponential law (psi)"
    else:
        sol = _solution_m(body, theta2_0, J2_0, psi0, M, times, rtol, atol)
        method = ("closed form: Jacobi elliptic functions (J2^2, theta2); DOP853 quadrature "
                  "of psi and theta3 along it")
    y = hess_state(body, sol["theta2"], sol["J2"], sol["psi"], M)
    chart = signed_to_hess(sol["theta2"], sol["J2"], sol["psi"], M)
    # J1 = G cos^2(psi/2) (or G sin^2(psi/2) past G = 0) from factors computed without
    # cancellation, so that J1 keeps its relative accuracy as the orbit nears J1 = 0.
    chart[:, 2] = np.abs(sol["J2"]) * np.where(sol["J2"] < 0.0, sol["sin2"], sol["cos2"])
    T = period(body, h, M)
    attrs: dict[str, Any] = provenance(
        body, method=method, h=h, M=M, motion=motion, period=T,
        drift_rate=drift_rate(body), theta1_sheet=theta1, rtol=rtol, atol=atol,
        equations="reduced Hess-chart Hamiltonian on theta1 = 0: "
                  "H = c J2^2/2 + mu sqrt(J2^2 - M^2) sin(theta2)/J2")
    extra = {"theta3": (("time",), sol["theta3"]),
             "theta2_signed": (("time",), sol["theta2"]),
             "J2_signed": (("time",), sol["J2"]),
             "psi": (("time",), sol["psi"])}
    ds = states_dataset(body, y, ("time",), {"time": times}, attrs, extra=extra)
    for i, name in enumerate(("theta1", "theta2", "J1", "J2", "J3")):
        ds[name].values[...] = chart[:, i]
    ds["theta3"].attrs.update(symbol="\\theta_3", units="rad", equation="(14)",
                              long_name="cyclic angle m, from 0 at t[0]")
    ds["theta2_signed"].attrs.update(
        symbol="\\theta_2", units="rad", equation="(14)",
        long_name="theta2 of the signed-J2 pendulum picture (unwrapped)")
    ds["J2_signed"].attrs.update(symbol="J_2", units="1", equation="(14)",
                                 long_name="J2 = G of the signed pendulum picture (M = 0)")
    ds["psi"].attrs.update(symbol="\\psi", units="rad",
                           long_name="angle of G from body axis 3 towards k x r in the Hess "
                                     "plane (cos psi = L/G, J1 = J2 cos^2(psi/2))")
    ds.time.attrs.update(units="body time units", long_name="time")
    return ds
