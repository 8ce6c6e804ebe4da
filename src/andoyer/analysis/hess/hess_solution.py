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
from functools import cache
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray
from scipy.special import ellipj, ellipk, ellipkinc

from andoyer.analysis.hess.pendulum import (
    pendulum_motion,
    pendulum_period,
    pendulum_solution,
)
from andoyer.body import RigidBody, checks_body
from andoyer.charts.andoyer_deprit import rotation_chain_expr
from andoyer.integrate.hess_manifold import THETA1_TOL
from andoyer.integrate.results import provenance, states_dataset
from andoyer.validation import MAX_ACTION, checks_arguments, finite_array

__all__ = [
    "MOTIONS",
    "derive_reduced_hamiltonian",
    "reduced_hamiltonian",
    "reduced_field",
    "drift_rate",
    "energy_minimum",
    "classify_motion",
    "cubic_roots",
    "period",
    "hess_state",
    "signed_to_hess",
    "hess_solution",
]

#: Motion codes. ``pole_passage`` (``M != 0``, ``h = c M^2/2``): the orbit passes
#: through ``|M| = G`` (gamma parallel to G), the chart's singular point; not a separatrix.
MOTIONS = {"equilibrium": 0, "libration": 1, "separatrix": 2, "rotation": 3,
           "pole_passage": 4}

_EPS = float(np.finfo(float).eps)
_REL = 8.0 * _EPS


def _check_hess(body: RigidBody) -> None:
    """The Hess conditions (its callers' ``@checks_body`` checked the type)."""
    body.require_hess("the Hess solution")
    if body.mu <= 0.0:
        raise ValueError("the Hess solution needs mu > 0 (at mu = 0 theta2 rotates "
                         "uniformly); use body.with_mu(mu)")


# ----------------------------------------------------------------------------- reduction
def _points(**values: ArrayLike) -> list[NDArray[np.float64]]:
    """Finite coordinate arrays broadcast together, or ``ValueError`` naming the one that
    is NaN, infinite or of a shape that does not broadcast."""
    arrays = [finite_array(name, v) for name, v in values.items()]
    try:
        return list(np.broadcast_arrays(*arrays))
    except ValueError:
        shapes = ", ".join(f"{n} {a.shape}" for n, a in zip(values, arrays, strict=True))
        raise ValueError(f"the coordinates must broadcast together, got shapes {shapes}"
                         ) from None


@cache
def derive_reduced_hamiltonian() -> Any:
    """The Hess-chart Hamiltonian on ``theta1 = 0``, derived with SymPy from Eq. (1).

    :func:`andoyer.symbolic.hamiltonian.H_hess` at ``theta1 = 0`` with the Hess
    condition ``c = a sin^2 phi0 + b cos^2 phi0`` (Eq. (8)), simplified: it is
    ``c J2^2/2 + mu sqrt(J2^2 - J3^2) sin(theta2) / J2`` -- without ``J1``. SymPy runs
    here only (about a second); the numeric functions below use the result.
    """
    import sympy as sp

    from andoyer.symbolic.hamiltonian import H_hess, S

    c_hess = S.a * sp.sin(S.phi0) ** 2 + S.b * sp.cos(S.phi0) ** 2
    return sp.simplify(H_hess().subs(S.theta1, 0).subs(S.c, c_hess))


@checks_body
def reduced_hamiltonian(body: RigidBody, theta2: ArrayLike, J2: ArrayLike, M: float = 0.0
                        ) -> NDArray[np.float64]:
    """``H = c J2^2/2 + mu sqrt(J2^2 - M^2) sin(theta2) / J2`` on ``theta1 = 0 (mod 2 pi)``.

    At ``M = 0`` the pendulum ``c J2^2/2 + mu sin(theta2)`` (any sign of ``J2``).

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> from andoyer.dynamics import hamiltonian
    >>> body = RigidBody.paper()
    >>> bool(np.isclose(reduced_hamiltonian(body, 1.0, 0.8, 0.3),
    ...                 hamiltonian(body, [0.0, 1.0, 0.25, 0.8, 0.3], "hess")))
    True
    """
    t2, j2 = finite_array("theta2", theta2), finite_array("J2", J2)
    if M == 0.0:
        return np.asarray(0.5 * body.c * j2**2 + body.mu * np.sin(t2))
    return np.asarray(0.5 * body.c * j2**2
                      + body.mu * np.sqrt((j2 - M) * (j2 + M)) / j2 * np.sin(t2))


@checks_body
def drift_rate(body: RigidBody) -> float:
    """``s = kappa sin(2 phi0) = -2 branch sigma``: the rate in ``dpsi/dt = -(s/2) J2 sin psi``.

    ``sigma = sqrt((b - c)(c - a))``; negative on the paper's branch (``phi0 > 0``).
    """
    return body.kappa * math.sin(2.0 * body.phi0)


@checks_body
def reduced_field(body: RigidBody, theta2: ArrayLike, J1: ArrayLike, J2: ArrayLike,
                  M: float = 0.0, theta1: float = 0.0) -> NDArray[np.float64]:
    """``d(theta2, J1, J2, theta3)/dt`` on ``theta1 = 0`` or ``2 pi`` (a Hess body).

    .. math::

        \\dot\\theta_2 &= c J_2 + \\mu M^2 \\sin\\theta_2 / (J_2^2 \\sqrt{J_2^2 - M^2}), \\quad
        \\dot J_2 = -\\mu \\sqrt{J_2^2 - M^2} \\cos\\theta_2 / J_2, \\\\
        \\dot J_1 &= -s J_1 (J_1 - J_2) - \\mu J_1 \\sqrt{J_2^2 - M^2} \\cos\\theta_2 / J_2^2
                    - \\epsilon \\mu M \\sqrt{J_1 (J_2 - J_1)} / J_2^2, \\\\
        \\dot\\theta_3 &= -\\mu M \\sin\\theta_2 / (J_2 \\sqrt{J_2^2 - M^2}),

    ``s`` = :func:`drift_rate`, ``epsilon = cos(theta1/2) = +-1``. At ``M = 0``:
    Eq. (16) at ``theta1 = 0``. Returns shape ``(..., 4)``.
    """
    _check_hess(body)
    off = math.remainder(float(theta1), math.tau)
    if abs(off) > THETA1_TOL:
        raise ValueError(f"theta1 = {theta1!r} is not on the Hess manifold theta1 = 0 (mod 2 pi)")
    eps = 1.0 if abs(math.remainder(float(theta1), 4.0 * math.pi)) <= THETA1_TOL else -1.0
    t2, j1, j2 = _points(theta2=theta2, J1=J1, J2=J2)
    if np.any(j2 <= abs(M)) or np.any(j1 < 0.0) or np.any(j1 > j2):
        raise ValueError(f"reduced_field needs |M| < J2 and 0 <= J1 <= J2 (the Hess chart's "
                         f"domain), got J1 in [{j1.min():g}, {j1.max():g}], J2 in "
                         f"[{j2.min():g}, {j2.max():g}], M = {M:g}")
    c, mu = body.c, body.mu
    root = np.sqrt((j2 - M) * (j2 + M))
    st, ct = np.sin(t2), np.cos(t2)
    d_theta2 = c * j2 + mu * M * M * st / (j2 * j2 * root)
    d_J2 = -mu * root * ct / j2
    d_J1 = (-drift_rate(body) * j1 * (j1 - j2) - mu * j1 * root * ct / j2**2
            - eps * mu * M * np.sqrt(j1 * (j2 - j1)) / j2**2)
    d_theta3 = -mu * M * st / (j2 * root)
    return np.stack([d_theta2, d_J1, d_J2, d_theta3], axis=-1)


# ----------------------------------------------------------------------------- energies
@checks_body
def energy_minimum(body: RigidBody, M: float = 0.0) -> tuple[float, float]:
    """``(J2*, h_min)``: the centre ``theta2 = 3 pi/2`` of the reduced system.

    ``M = 0``: ``(0, -mu)`` (the body hanging at rest, ``G = 0``). ``M != 0``: the root
    of ``c J2^3 sqrt(J2^2 - M^2) = mu M^2`` (a relative equilibrium, ``J2* > |M|``).
    """
    from scipy.optimize import brentq

    _check_hess(body)
    c, mu = body.c, body.mu
    M = abs(float(M))
    if M == 0.0:
        return 0.0, -mu

    def slope(J: float) -> float:  # dH/dJ2 along theta2 = 3 pi/2
        try:
            return c * J - mu * M * M / (J * J * math.sqrt((J - M) * (J + M)))
        except (ZeroDivisionError, OverflowError):  # under- or overflow: no float answer
            return math.nan

    if M > MAX_ACTION:
        raise ValueError(f"M must be <= {MAX_ACTION:g} in absolute value, got {M!r}")
    lo, hi = M * (1.0 + 1e-15), 2.0 * M
    for _ in range(1100):  # round-off guard: the slope is -inf at M+
        if not slope(lo) > 0.0:
            break
        lo = M + 2.0 * (lo - M)
    for _ in range(1100):
        if not slope(hi) < 0.0:
            break
        hi *= 2.0
    if not (math.isfinite(lo) and math.isfinite(hi) and slope(lo) <= 0.0 <= slope(hi)):
        raise ValueError(f"M = {M!r}: the minimum of the reduced energy is not bracketed "
                         "in floating point (M too large or too small for this body)")
    J = float(brentq(slope, lo, hi, xtol=1e-16, rtol=4 * _EPS, maxiter=200))
    return J, float(reduced_hamiltonian(body, 1.5 * math.pi, J, M))


@checks_body
def classify_motion(body: RigidBody, h: float, M: float = 0.0) -> str:
    """Motion of the reduced system at energy ``h`` (a key of :data:`MOTIONS`).

    ``M = 0`` (pendulum): ``equilibrium`` (``h = -mu``), ``libration``
    (``-mu < h < mu``, through ``G = 0`` at the turning points), ``separatrix``
    (``h = mu``, asymptotic to the top ``theta2 = pi/2, G = 0``), ``rotation``.
    ``M != 0``: ``equilibrium`` (``h = h_min``), ``libration`` (``theta2`` about
    ``3 pi/2``, ``h < c M^2/2``), ``pole_passage`` (``h = c M^2/2``: through
    ``|M| = G``), ``rotation`` (``h > c M^2/2``). There is no separatrix at ``M != 0``:
    the period is finite and smooth across ``c M^2/2``.

    Raises ``ValueError`` below the minimum energy.
    """
    _check_hess(body)
    if M == 0.0:
        return pendulum_motion(body.mu, float(h))
    h = float(h)
    _, h_min = energy_minimum(body, M)
    tol = _REL * max(abs(h), body.mu)
    if not math.isfinite(h) or h < h_min - tol:
        raise ValueError(f"energy h = {h!r} is below the minimum {h_min:.12g} of the Hess "
                         f"solution at M = {M:g}")
    if h <= h_min + tol:
        return "equilibrium"
    pole = 0.5 * body.c * M * M
    if abs(h - pole) <= tol:
        return "pole_passage"
    return "libration" if h < pole else "rotation"


@checks_body
def cubic_roots(body: RigidBody, h: float, M: float = 0.0) -> tuple[float, float, float]:
    """Roots ``u_a <= u_b <= u_c`` of ``P(u) = mu^2 (u - M^2) - u (h - c u/2)^2``.

    ``u = J2^2`` oscillates in ``[u_b, u_c]``. At ``M = 0`` they are
    ``{0, 2 (h - mu)/c, 2 (h + mu)/c}`` exactly; otherwise ``numpy.roots`` polished by
    Newton steps.
    """
    c, mu = body.c, body.mu
    h = float(h)
    if M == 0.0:
        r = sorted((0.0, 2.0 * (h - mu) / c, 2.0 * (h + mu) / c))
        return r[0], r[1], r[2]
    coeffs = [-0.25 * c * c, c * h, mu * mu - h * h, -mu * mu * M * M]
    raw = np.roots(coeffs)
    if np.any(np.abs(raw.imag) > 1e-8 * np.max(np.abs(raw))):
        raise ValueError(f"h = {h!r} at M = {M:g} is below the minimum energy "
                         "(P(u) has complex roots: no motion)")
    roots = np.sort(raw.real)
    for _ in range(3):
        P = ((coeffs[0] * roots + coeffs[1]) * roots + coeffs[2]) * roots + coeffs[3]
        dP = (3 * coeffs[0] * roots + 2 * coeffs[1]) * roots + coeffs[2]
        step = np.where(dP != 0.0, P / np.where(dP != 0.0, dP, 1.0), 0.0)
        # Near a double root (the centre) Newton is ill-conditioned: keep small steps only.
        roots = np.where(np.abs(step) < 1e-6 * np.abs(roots) + 1e-300, roots - step, roots)
    roots = np.sort(roots)
    if roots[2] <= M * M:
        raise ValueError(f"h = {h!r} at M = {M:g}: no motion with J2 > |M|")
    return float(roots[0]), float(max(roots[1], M * M)), float(roots[2])


@checks_body
def period(body: RigidBody, h: float, M: float = 0.0, *, method: str = "elliptic") -> float:
    """Period of the reduced motion in ``(theta2, J2)`` at energy ``h``.

    Parameters
    ----------
    body : RigidBody
        A Hess body, ``mu > 0``.
    h : float
        Energy (value of the reduced Hamiltonian).
    M : float
        Area integral ``J3``.
    method : {"elliptic", "quad"}
        ``"elliptic"``: ``T = 4 K(m) / (c sqrt(u_c - u_a))``, ``m = (u_c - u_b)/(u_c - u_a)``
        (``scipy.special.ellipk``, parameter ``m = k^2``); at ``M = 0`` this is the
        pendulum: libration ``4 K(m)/sqrt(c mu)``, ``m = (h + mu)/(2 mu)``; rotation
        ``4 K(m)/sqrt(2 c (h + mu))``, ``m = 2 mu/(h + mu)``.
        ``"quad"``: ``T = int du / sqrt(P(u))`` over ``[u_b, u_c]`` with ``P`` evaluated
        as written (not factored) by ``scipy.integrate.quad`` after the substitution
        ``u = u_b + (u_c - u_b) sin^2(phi)``, which removes the inverse-square-root
        singularities at both ends (the limits there are taken analytically).

    Returns
    -------
    float
        The period: for an ``M = 0`` libration the full period of the physical motion
        (``theta2, J2`` in the chart repeat after half of it, see the module notes); for a
        rotation the time for ``theta2`` to advance by ``2 pi``; ``inf`` on the separatrix.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> body = RigidBody.paper()
    >>> T1 = period(body, 0.02, M=0.1)
    >>> bool(abs(period(body, 0.02, M=0.1, method="quad") / T1 - 1) < 1e-12)
    True
    """
    _check_hess(body)
    if method not in ("elliptic", "quad"):
        raise ValueError(f"method must be 'elliptic' or 'quad', got {method!r}")
    M = float(M)
    motion = classify_motion(body, h, M)
    c, mu = body.c, body.mu
    if motion == "separatrix":
        return math.inf
    if motion == "equilibrium":
        if M == 0.0:
            return math.tau / math.sqrt(c * mu)
        J, _ = energy_minimum(body, M)
        return math.tau / _centre_frequency(body, J, M)
    if M == 0.0 and method == "elliptic":
        return pendulum_period(c, mu, h)
    ua, ub, uc = cubic_roots(body, h, M)
    if method == "elliptic":
        m = (uc - ub) / (uc - ua)
        return float(4.0 * ellipk(m) / (c * math.sqrt(uc - ua)))
    factor = 2.0 if (M == 0.0 and motion == "libration") else 1.0  # u runs twice
    return factor * _quad_period(body, h, M, ub, uc)


def _centre_frequency(body: RigidBody, J: float, M: float) -> float:
    """Small-oscillation frequency about the centre ``(3 pi/2, J)`` (``M != 0``)."""
    c, mu = body.c, body.mu
    r = math.sqrt((J - M) * (J + M))
    H_tt = mu * r / J  # d2H/dtheta2^2 at sin = -1
    # d2H/dJ2^2 along sin theta2 = -1: c - mu d2/dJ2^2 (sqrt(J^2 - M^2)/J)
    H_jj = c + mu * M * M * (3.0 * J * J - 2.0 * M * M) / (J**3 * r**3)
    return math.sqrt(H_tt * H_jj)


def _quad_period(body: RigidBody, h: float, M: float, ub: float, uc: float) -> float:
    from scipy.integrate import quad

    c, mu = body.c, body.mu
    width = uc - ub

    def P(u: float) -> float:
        return mu * mu * (u - M * M) - u * (h - 0.5 * c * u) ** 2

    def dP(u: float) -> float:
        return mu * mu - (h - 0.5 * c * u) ** 2 + c * u * (h - 0.5 * c * u)

    def integrand(phi: float) -> float:
        s, co = math.sin(phi), math.cos(phi)
        val = P(ub + width * s * s)
        if val <= 0.0:  # at an end (round-off): the limit 2 sqrt(width / |P'(end)|)
            end = ub if s < co else uc
            return 2.0 * math.sqrt(width / abs(dP(end)))
        return 2.0 * width * s * co / math.sqrt(val)

    value, _ = quad(integrand, 0.0, 0.5 * math.pi, epsabs=0.0, epsrel=1e-12, limit=200)
    return float(value)


# ----------------------------------------------------------------------------- embedding
@checks_body
def hess_state(body: RigidBody, theta2: ArrayLike, J2: ArrayLike, psi: ArrayLike,
               M: float = 0.0) -> NDArray[np.float64]:
    """Euler-Poisson state of the Hess solution from ``(theta2, J2, psi)``; shape ``(..., 6)``.

    ``G = J2 (sin(psi) n + cos(psi) k)`` with ``n = k x r = (-e2, e1, 0)`` and ``gamma``
    from the chain (5)-(6) at ``l = -phi0``, ``g = theta2``, ``cos J = cos psi``,
    ``sin J = sin psi`` (``sin psi < 0`` is the sheet ``theta1 = 2 pi``). At ``M = 0``
    ``J2`` may be negative (the signed pendulum picture): the map is regular at ``G = 0``.
    """
    t2, j2, ps = _points(theta2=theta2, J2=J2, psi=psi)
    if M == 0.0:
        cI, sI = np.zeros(j2.shape), np.ones(j2.shape)
    else:
        if np.any(np.abs(j2) < abs(M)):
            raise ValueError("J2 = G must not be below |M|")
        cI, sI = M / j2, np.sqrt((j2 - M) * (j2 + M)) / j2
    cols = rotation_chain_expr(-body.phi0, t2, j2, np.cos(ps), np.sin(ps), cI, sI,
                               sin=np.sin, cos=np.cos)
    return np.stack(np.broadcast_arrays(*cols), axis=-1)


@checks_arguments
def signed_to_hess(theta2: ArrayLike, J2: ArrayLike, psi: ArrayLike, M: float = 0.0
                   ) -> NDArray[np.float64]:
    """Hess-chart values ``(theta1, theta2, J1, J2, J3)`` of signed-picture states.

    For signed ``J2 < 0`` (``M = 0`` only) the chart rule at the ``G = 0`` passage
    applies: ``psi -> psi + pi``, ``theta2 -> pi - theta2``, ``J2 -> -J2`` (module
    notes). ``theta1 = 0`` where ``sin psi >= 0``, else ``2 pi``; ``J1 = J2 cos^2(psi/2)``;
    ``theta2`` reduced to ``[0, 2 pi)``.
    """
    t2, j2, ps = _points(theta2=theta2, J2=J2, psi=psi)
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
    return float(ellipkinc(math.atan2(sn, cn), m))


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


@checks_body
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
    _check_hess(body)
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
