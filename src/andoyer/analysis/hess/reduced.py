"""The reduced system of the Hess solution: on ``theta1 = 0`` (the invariant relation (3)
in the Hess chart (14)) the Hess-chart Hamiltonian loses its ``J1``-dependence,

.. math::

    H = \\tfrac12 c J_2^2 + \\mu \\frac{\\sqrt{J_2^2 - M^2}}{J_2} \\sin\\theta_2 ,

one degree of freedom in ``(theta2, J2)`` with ``M = J3`` a parameter (Eq. (16) of [1]_;
derived from Eq. (1) by :func:`derive_reduced_hamiltonian`): its field, the drift rate of
``psi``, the energy minimum, the kind of motion on a level, the roots of
``P(u) = mu^2 (u - M^2) - u (h - c u/2)^2`` (``u = J2^2``) and the period
``T = 4 K(m) / (c sqrt(u_c - u_a))``. The closed-form motion built on them is
:mod:`andoyer.analysis.hess.solution` (which re-exports these names).

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
from numpy.typing import ArrayLike, NDArray
from scipy.special import ellipk

from andoyer.analysis.hess.pendulum import (
    pendulum_motion,
    pendulum_period,
)
from andoyer.body import RigidBody, checks_body
from andoyer.integrate.hess_manifold import THETA1_TOL
from andoyer.validation import MAX_ACTION, finite_array

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
]

#: Closed forms only: levels and actions up to ``|G| = MAX_ACTION``
#: (:func:`andoyer.validation.momentum_limit`).
CLOSED_FORM = True

#: Motion codes. ``pole_passage`` (``M != 0``, ``h = c M^2/2``): the orbit passes
#: through ``|M| = G`` (gamma parallel to G), the chart's singular point; not a separatrix.
MOTIONS = {"equilibrium": 0, "libration": 1, "separatrix": 2, "rotation": 3,
           "pole_passage": 4}

_EPS = float(np.finfo(float).eps)
_REL = 8.0 * _EPS


def check_hess(body: RigidBody) -> None:
    """The Hess conditions (its callers' ``@checks_body`` checked the type)."""
    body.require_hess("the Hess solution")
    if body.mu <= 0.0:
        raise ValueError("the Hess solution needs mu > 0 (at mu = 0 theta2 rotates "
                         "uniformly); use body.with_mu(mu)")


# ----------------------------------------------------------------------------- reduction
def broadcast_points(**values: ArrayLike) -> list[NDArray[np.float64]]:
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


@checks_body(ranges={"theta2": "angle", "J2": "action", "M": "action"}, closed_form=CLOSED_FORM)
def reduced_hamiltonian(body: RigidBody, theta2: ArrayLike, J2: ArrayLike, M: float = 0.0
                        ) -> NDArray[np.float64]:
    """``H = c J2^2/2 + mu sqrt(J2^2 - M^2) sin(theta2) / J2`` on ``theta1 = 0 (mod 2 pi)``.

    At ``M = 0`` the pendulum ``c J2^2/2 + mu sin(theta2)`` (any sign of ``J2``).

    Parameters
    ----------
    body : RigidBody
        A Hess body.
    theta2, J2 : array_like
        Hess-chart angle (rad) and ``J2 = |G|`` (any sign at ``M = 0``).
    M : float, default 0.0
        Area constant ``(G, gamma) = M`` (``|M| <= |J2|``).

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

    Parameters
    ----------
    body : RigidBody
        A Hess body (``kappa``, ``phi0``, ``sigma`` from its moments).
    """
    return body.kappa * math.sin(2.0 * body.phi0)


@checks_body(ranges={"theta2": "angle", "J1": "action", "J2": "action", "M": "action", "theta1":
             "angle"}, closed_form=CLOSED_FORM)
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

    Parameters
    ----------
    body : RigidBody
        A Hess body.
    theta2, J1, J2 : array_like
        Hess-chart coordinates (Eq. (13)); ``J2 >= |M|``, ``0 <= J1 <= J2``.
    M : float, default 0.0
        Area constant ``(G, gamma) = M``.
    theta1 : float, default 0.0
        The invariant line: ``0`` or ``2 pi`` (``epsilon = cos(theta1/2)``).
    """
    check_hess(body)
    off = math.remainder(float(theta1), math.tau)
    if abs(off) > THETA1_TOL:
        raise ValueError(f"theta1 = {theta1!r} is not on the Hess manifold theta1 = 0 (mod 2 pi)")
    eps = 1.0 if abs(math.remainder(float(theta1), 4.0 * math.pi)) <= THETA1_TOL else -1.0
    t2, j1, j2 = broadcast_points(theta2=theta2, J1=J1, J2=J2)
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
@checks_body(ranges={"M": "action"}, closed_form=CLOSED_FORM)
def energy_minimum(body: RigidBody, M: float = 0.0) -> tuple[float, float]:
    """``(J2*, h_min)``: the centre ``theta2 = 3 pi/2`` of the reduced system.

    ``M = 0``: ``(0, -mu)`` (the body hanging at rest, ``G = 0``). ``M != 0``: the root
    of ``c J2^3 sqrt(J2^2 - M^2) = mu M^2`` (a relative equilibrium, ``J2* > |M|``).

    Parameters
    ----------
    body : RigidBody
        A Hess body.
    M : float, default 0.0
        Area constant ``(G, gamma) = M``.
    """
    from scipy.optimize import brentq

    check_hess(body)
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


@checks_body(ranges={"h": "energy", "M": "action"}, closed_form=CLOSED_FORM)
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

    Parameters
    ----------
    body : RigidBody
        A Hess body (its reduced system on ``theta1 = 0``).
    h : float
        Energy level ``H = h`` (not below :func:`energy_minimum`).
    M : float, default 0.0
        Area constant ``(G, gamma) = M``.
    """
    check_hess(body)
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


@checks_body(ranges={"h": "energy", "M": "action"}, closed_form=CLOSED_FORM)
def cubic_roots(body: RigidBody, h: float, M: float = 0.0) -> tuple[float, float, float]:
    """Roots ``u_a <= u_b <= u_c`` of ``P(u) = mu^2 (u - M^2) - u (h - c u/2)^2``.

    ``u = J2^2`` oscillates in ``[u_b, u_c]``. At ``M = 0`` they are
    ``{0, 2 (h - mu)/c, 2 (h + mu)/c}`` exactly; otherwise ``numpy.roots`` polished by
    Newton steps.

    Parameters
    ----------
    body : RigidBody
        A Hess body (``c``, ``mu``).
    h : float
        Energy level ``H = h``.
    M : float, default 0.0
        Area constant ``(G, gamma) = M``.
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


@checks_body(ranges={"h": "energy", "M": "action"}, closed_form=CLOSED_FORM)
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
    check_hess(body)
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
