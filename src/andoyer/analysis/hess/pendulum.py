"""The physical pendulum ``G^2 = L^2, M = 0`` and its stability (Floquet multipliers).

A body whose centre of mass lies in the principal plane ``Oxy`` (``e3 = 0``; Hess
bodies included) has the invariant set ``G1 = G2 = 0, gamma3 = 0`` (Eq. (8) of [1]_:
``G^2 = L^2`` and ``M = 0``): the body swings about its axis ``Oz``, which stays
horizontal. With ``gamma = (sin(vartheta - phi0), cos(vartheta - phi0), 0)`` and
``L = G3`` the motion is the pendulum

.. math::

    H = \\tfrac12 c L^2 + \\mu \\sin\\vartheta, \\qquad
    \\dot\\vartheta = c L, \\qquad \\dot L = -\\mu \\cos\\vartheta ,

(``vartheta`` is the angle of the upward vertical in the body plane ``Oxy``, shifted
by ``phi0`` so that the potential ``mu (r, gamma)`` is ``mu sin(vartheta)``). The
Hess solution at ``M = 0`` reduces to the same pendulum in ``(theta2, J2)``
(:mod:`andoyer.analysis.hess.solution`), so the closed forms of this module serve both:
:func:`pendulum_solution` solves ``H = c p^2/2 + mu sin q`` with Jacobi elliptic
functions (``scipy.special.ellipj``, parameter convention ``m = k^2``).

Potential in Andoyer-Deprit variables
-------------------------------------
On ``L = +G`` the chart gives ``gamma1 = sin(g + l)``, ``gamma2 = cos(g + l)``, so
``Pi = mu sin(g + l + phi0)``; on ``L = -G`` it gives ``Pi = mu sin(g - l - phi0)``
(:func:`pendulum_potential`). The paper prints ``Pi = mu^-1 sin(g + l - phi0)``
(:func:`paper_pendulum_potential`): ``mu^-1`` for ``mu`` and ``-phi0`` for ``+phi0``.
Only ``g + l`` (on ``L = G``) or ``g - l`` (on ``L = -G``) is defined there; the
chart inverse :func:`andoyer.charts.andoyer_deprit.to_andoyer` returns ``l = 0`` and
puts the whole angle into ``g``.

Stability
---------
The monodromy matrix ``Phi`` of the variational equations of the Euler-Poisson field
(1) over one period is computed by heyoka's variational equations
(``heyoka.var_ode_sys``): they are generated from the same SymPy field as the
integrators (no Jacobian typed by hand) and the Taylor method integrates the 42
equations at ``tol = 1e-15`` in milliseconds; :func:`monodromy` with
``method="finite_difference"`` is the independent check (central differences of the
flow map, compiled DOP853). On the pendulum the variational equations split exactly
into the in-plane block ``(G3, gamma1, gamma2)`` (multipliers 1, 1, 1: the flow, the
energy and ``|gamma|^2``) and the transverse block ``(G1, G2, gamma3)`` (multipliers
``1`` -- the area integral M -- and a pair ``lambda, 1/lambda``). The pair is taken
from the trace, ``lambda + 1/lambda = tr Phi_perp - 1``, which is insensitive to the
Jordan blocks of the trivial multipliers. ``|tr| < 2``: elliptic (linearly stable);
``> 2``: hyperbolic (unstable); ``= 2``: parabolic -- multipliers 1, and where the
matrix is a Jordan block (``shear > 0``) linearly unstable: a perturbation grows in
proportion to time, not exponentially.

On a Hess body the pair is known exactly: ``(G, r)`` obeys
``d(G, r)/dt = -branch sigma G3 (G, r)`` with ``sigma = sqrt((b - c)(c - a))``, and
``int G3 dt`` over a period is ``2 pi / c`` for a rotation and 0 for a libration, so
rotations have ``lambda = exp(+-2 pi sigma / c)`` at every energy
(:func:`hess_rotation_multiplier`) and librations ``lambda = 1`` with a Jordan block.
Measured on the paper's body (tests): the fixed eigenvector of the leaf monodromy and
the range of ``Phi - I`` are both the tangent of the Hess manifold (3). A perturbation
along the manifold comes back unchanged -- the neighbouring Hess librations share the
pendulum's period, which is why that direction is *not* sheared -- while a perturbation
off the manifold, ``(G, r) != 0``, comes back with a shift along the manifold of
``shear`` times its size: a linear (algebraic) instability, growing with the energy
(``shear`` = 1.53, 2.83, 14.95 at ``h / mu`` = 0.2, 0.5, 0.9).

References
----------
.. [1] V. V. Kyrychenko, "Andoyer-Deprit variables use to the Hess gyroscope phase
   trajectories exploring", National Aviation University, Kyiv (``andoyer.cite("paper")``).
"""

from __future__ import annotations

import math

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray
from scipy.special import ellipj, ellipk

from andoyer.analysis.unperturbed.euler_poinsot import elliptic_f
from andoyer.body import RigidBody, checks_body
from andoyer.integrate.results import provenance, states_dataset
from andoyer.validation import checks_arguments, finite_array
from andoyer.validation import positive as _positive

__all__ = [
    "MOTIONS",
    "STABILITY",
    "TRANSVERSE",
    "IN_PLANE",
    "require_pendulum_body",
    "pendulum_energy",
    "pendulum_motion",
    "pendulum_modulus",
    "pendulum_period",
    "pendulum_solution",
    "pendulum_state",
    "pendulum_potential",
    "paper_pendulum_potential",
    "physical_pendulum",
]

#: Closed forms only: levels and actions up to ``|G| = MAX_ACTION``
#: (:func:`andoyer.validation.momentum_limit`).
CLOSED_FORM = True

#: Motion codes stored in datasets (``flag_values`` / ``flag_meanings``).
MOTIONS = {"equilibrium": 0, "libration": 1, "separatrix": 2, "rotation": 3}
#: Linear-stability codes of a periodic orbit.
STABILITY = {"elliptic": 0, "parabolic": 1, "hyperbolic": 2}
#: Euler-Poisson components transverse to the pendulum set ``G1 = G2 = gamma3 = 0``.
TRANSVERSE = ("G1", "G2", "gamma3")
#: Components along the pendulum set.
IN_PLANE = ("G3", "gamma1", "gamma2")

_EPS = float(np.finfo(float).eps)
#: ``|h - mu| <= SEPARATRIX_RTOL * mu`` is the separatrix.
SEPARATRIX_RTOL = 4.0 * _EPS


@checks_body
def require_pendulum_body(body: RigidBody, what: str) -> None:
    """A body whose physical pendulum exists (callers check the type: ``@checks_body``).

    Parameters
    ----------
    body : RigidBody
        The body to check: Oz the middle axis and the centre of mass in the (e1, e2) plane.
    what : str
        The caller's name, for the error message.
    """
    body.require_planar(what)
    if body.mu <= 0.0:
        raise ValueError(f"{what} needs mu > 0 (mu = 0 is the free body: the pendulum "
                         "degenerates into a uniform rotation); use body.with_mu(mu)")


# ----------------------------------------------------------------------------- the pendulum
@checks_arguments(ranges={"c": "scale", "mu": "scale", "q": "angle", "p": "action"},
                  closed_form=CLOSED_FORM)
def pendulum_energy(c: float, mu: float, q: ArrayLike, p: ArrayLike) -> NDArray[np.float64]:
    """``H = c p^2 / 2 + mu sin q``: the reduced Hamiltonian of both pendulums.

    Parameters
    ----------
    c : float
        The inverse moment ``c = 1/C`` (> 0).
    mu : float
        Weight times distance of the centre of mass (> 0).
    q, p : array_like
        Angle (rad) and momentum of the pendulum.
    """
    qq, pp = finite_array("q", q), finite_array("p", p)
    return np.asarray(0.5 * c * pp**2 + mu * np.sin(qq), dtype=float)


def _excess(c: float, mu: float, q: float, p: float) -> float:
    """``h + mu`` (energy above the bottom ``q = -pi/2``) without cancellation."""
    phi = math.remainder(q + 0.5 * math.pi, 2.0 * math.pi)
    return 0.5 * c * p * p + 2.0 * mu * math.sin(0.5 * phi) ** 2


@checks_arguments(ranges={"mu": "scale", "h": "energy"}, closed_form=CLOSED_FORM)
def pendulum_motion(mu: float, h: float) -> str:
    """``"equilibrium"``, ``"libration"``, ``"separatrix"`` or ``"rotation"`` at energy ``h``.

    Raises ``ValueError`` below the minimum ``h = -mu``.

    Parameters
    ----------
    mu : float
        Weight times distance of the centre of mass (> 0).
    h : float
        Energy (``h >= -mu``).
    """
    mu = _positive("mu", mu)
    if not math.isfinite(h) or h < -mu * (1.0 + SEPARATRIX_RTOL):
        raise ValueError(f"energy h = {h!r} is below the pendulum's minimum -mu = {-mu:g}")
    if h <= -mu:
        return "equilibrium"
    if abs(h - mu) <= SEPARATRIX_RTOL * mu:
        return "separatrix"
    return "libration" if h < mu else "rotation"


@checks_arguments(ranges={"mu": "scale", "h": "energy"}, closed_form=CLOSED_FORM)
def pendulum_modulus(mu: float, h: float) -> float:
    """Parameter ``m = k^2`` of the elliptic functions (scipy's convention).

    ``m = (h + mu) / (2 mu)`` for a libration (``k = sin`` of half the amplitude in
    ``q + pi/2``), ``m = 2 mu / (h + mu)`` for a rotation, 1 on the separatrix.

    Parameters
    ----------
    mu : float
        Weight times distance of the centre of mass (> 0).
    h : float
        Energy (``h > -mu``).
    """
    motion = pendulum_motion(mu, h)
    if motion in ("libration", "equilibrium"):
        return max(0.0, (h + mu) / (2.0 * mu))
    if motion == "separatrix":
        return 1.0
    return 2.0 * mu / (h + mu)


@checks_arguments(ranges={"c": "scale", "mu": "scale", "h": "energy"}, closed_form=CLOSED_FORM)
def pendulum_period(c: float, mu: float, h: float) -> float:
    """Period of ``H = c p^2/2 + mu sin q`` at energy ``h``, via ``scipy.special.ellipk``.

    Libration (``-mu < h < mu``): ``T = 4 K(m) / sqrt(c mu)``, ``m = (h + mu)/(2 mu)``
    (``2 pi / sqrt(c mu)`` at the bottom); rotation (``h > mu``):
    ``T = 4 K(m) / sqrt(2 c (h + mu))``, ``m = 2 mu / (h + mu)`` (the time for ``q`` to
    advance by ``2 pi``); ``inf`` on the separatrix ``h = mu``.

    Parameters
    ----------
    c : float
        The inverse moment ``c = 1/C`` (> 0).
    mu : float
        Weight times distance of the centre of mass (> 0).
    h : float
        Energy (``h >= -mu``).

    Examples
    --------
    >>> round(pendulum_period(1.0, 1.0, -1.0), 12) == round(2 * math.pi, 12)
    True
    """
    c = _positive("c", c)
    motion = pendulum_motion(mu, h)
    m = pendulum_modulus(mu, h)
    if motion == "separatrix":
        return math.inf
    if motion == "rotation":
        return float(4.0 * ellipk(m) / math.sqrt(2.0 * c * (h + mu)))
    return float(4.0 * ellipk(m) / math.sqrt(c * mu))


@checks_arguments(ranges={"c": "scale", "mu": "scale", "q0": "angle", "p0": "action"},
                  closed_form=CLOSED_FORM)
def pendulum_solution(c: float, mu: float, q0: float, p0: float, t: ArrayLike
                      ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Closed-form solution of ``dq/dt = c p``, ``dp/dt = -mu cos q`` from ``(q0, p0)`` at ``t[0]``.

    With ``phi = q + pi/2`` (``H = c p^2/2 - mu cos phi + const``), ``omega0 = sqrt(c mu)``
    and the Jacobi functions of ``scipy.special.ellipj`` (parameter ``m = k^2``):

    * libration, ``k^2 = (h + mu)/(2 mu) < 1``:
      ``sin(phi/2) = k sn(u, m)``, ``p = (2 k omega0 / c) cn(u, m)``, ``u = omega0 t + u0``;
    * rotation, ``k^2 > 1``, ``m = 1/k^2``:
      ``phi = 2 s am(u, m)``, ``p = s (2 k omega0 / c) dn(u, m)``, ``u = k omega0 t + u0``,
      ``s = sign(p)``;
    * separatrix: ``phi = 2 s gd(omega0 t + u0)``, ``p = s (2 omega0 / c) sech(...)``.

    ``u0`` is fixed by the initial state through
    :func:`~andoyer.analysis.unperturbed.euler_poinsot.elliptic_f` (not SciPy's
    ``ellipkinc``, wrong at isolated points) of the amplitude ``atan2(sn, cn)``
    (quadrant-correct). ``q`` is returned unwrapped (continuous in ``t``);
    ``(q, p)(t[0]) = (q0, p0)`` to round-off.

    Parameters
    ----------
    c : float
        The inverse moment ``c = 1/C`` (> 0).
    mu : float
        Weight times distance of the centre of mass (> 0).
    q0, p0 : float
        Initial angle (rad) and momentum, at ``t[0]``.
    t : array_like
        Times (body time units), 1-D.

    Examples
    --------
    >>> q, p = pendulum_solution(1.0, 1.0, -math.pi / 2, 0.1, [0.0, 2 * math.pi])
    >>> bool(abs(p[1] - 0.1) < 1e-4)      # small oscillations have period ~ 2 pi
    True
    """
    c = _positive("c", c)
    mu = _positive("mu", mu)
    q0, p0 = float(q0), float(p0)
    if not (math.isfinite(q0) and math.isfinite(p0)):
        raise ValueError(f"initial state (q0, p0) = ({q0!r}, {p0!r}) is not finite")
    times = finite_array("t", t)
    tau = times - times.flat[0] if times.size else times
    omega0 = math.sqrt(c * mu)
    e = _excess(c, mu, q0, p0)  # h + mu
    h = e - mu
    phi0 = math.remainder(q0 + 0.5 * math.pi, 2.0 * math.pi)
    offset = q0 - phi0  # q = phi + offset, offset = -pi/2 + 2 pi n
    motion = pendulum_motion(mu, h)
    if motion == "equilibrium" or e == 0.0:
        return np.full(tau.shape, q0), np.zeros(tau.shape)
    if motion == "separatrix":
        s = 1.0 if p0 > 0 else -1.0
        if p0 == 0.0:  # on the saddle itself
            return np.full(tau.shape, q0), np.zeros(tau.shape)
        x = omega0 * tau + math.asinh(math.tan(0.5 * s * phi0))
        phi = 2.0 * s * np.arctan(np.sinh(x))
        p = s * 2.0 * omega0 / c / np.cosh(x)
        return phi + offset, p
    if motion == "libration":
        m = e / (2.0 * mu)
        k = math.sqrt(m)
        sn0 = math.sin(0.5 * phi0) / k
        cn0 = c * p0 / (2.0 * k * omega0)
        u = omega0 * tau + float(elliptic_f(math.atan2(sn0, cn0), m))
        sn, cn, dn, _ = ellipj(u, m)
        phi = 2.0 * np.arctan2(k * sn, dn)
        return phi + offset, 2.0 * k * omega0 / c * cn
    m = 2.0 * mu / e
    k = 1.0 / math.sqrt(m)
    s = 1.0 if p0 > 0 else -1.0
    half = 0.5 * s * (q0 + 0.5 * math.pi)  # the amplitude am(u0), unreduced
    u = k * omega0 * tau + float(elliptic_f(half, m))
    _, _, dn, am = ellipj(u, m)
    q = 2.0 * s * am - 0.5 * math.pi
    q = q + (q0 - q.flat[0]) if q.size else q  # remove the round-off of F then am
    return q, s * 2.0 * k * omega0 / c * dn


# ----------------------------------------------------------------------------- physical pendulum
@checks_body(ranges={"vartheta": "angle", "L": "action"}, closed_form=CLOSED_FORM)
def pendulum_state(body: RigidBody, vartheta: ArrayLike, L: ArrayLike) -> NDArray[np.float64]:
    """Euler-Poisson states on the physical pendulum: ``G = (0, 0, L)``,
    ``gamma = (sin(vartheta - phi0), cos(vartheta - phi0), 0)``; shape ``(..., 6)``.

    ``mu (r, gamma) = mu sin(vartheta)``; on ``L > 0`` (``L = G``), ``vartheta = g + l + phi0``.

    Parameters
    ----------
    body : RigidBody
        A body whose physical pendulum exists (``phi0``).
    vartheta : array_like
        Pendulum angle ``vartheta`` (rad): ``mu (r, gamma) = mu sin(vartheta)``.
    L : array_like
        ``L = G3`` (signed).
    """
    body.require_planar("the physical pendulum")
    th, LL = np.broadcast_arrays(finite_array("vartheta", vartheta), finite_array("L", L))
    z = np.zeros(th.shape)
    a = th - body.phi0
    return np.stack([z, z, LL, np.sin(a), np.cos(a), z], axis=-1)


@checks_body(ranges={"l": "angle", "g": "angle"})
def pendulum_potential(body: RigidBody, l: ArrayLike, g: ArrayLike, L_sign: int = 1
                       ) -> NDArray[np.float64]:
    """``Pi = mu (r, gamma)`` on the physical pendulum in Andoyer-Deprit variables.

    ``mu sin(g + l + phi0)`` on ``L = +G`` and ``mu sin(g - l - phi0)`` on ``L = -G``
    (derived from (5)-(6) at ``L = +-G, M = 0``; the paper's printed form after (11),
    ``mu^-1 sin(g + l - phi0)``, is wrong: see :func:`paper_pendulum_potential`).

    Parameters
    ----------
    body : RigidBody
        A body whose physical pendulum exists (``mu``, ``phi0``).
    l, g : array_like
        Andoyer-Deprit angles (rad).
    L_sign : {+1, -1}, default 1
        The pendulum ``L = +G`` or ``L = -G``.

    Examples
    --------
    >>> from andoyer import RigidBody, from_andoyer
    >>> body = RigidBody.paper()
    >>> y = from_andoyer([0.4, 1.3, 1.0, 1.0, 0.0])          # L = G, M = 0
    >>> pi = body.mu * (body.e1 * y[3] + body.e2 * y[4])
    >>> bool(np.isclose(pendulum_potential(body, 0.4, 1.3), pi))
    True
    """
    body.require_planar("the physical-pendulum potential")
    if L_sign not in (1, -1):
        raise ValueError(f"L_sign must be +1 (L = G) or -1 (L = -G), got {L_sign!r}")
    l_, g_ = finite_array("l", l), finite_array("g", g)
    if L_sign == 1:
        return np.asarray(body.mu * np.sin(g_ + l_ + body.phi0))
    return np.asarray(body.mu * np.sin(g_ - l_ - body.phi0))


@checks_body(ranges={"l": "angle", "g": "angle"})
def paper_pendulum_potential(body: RigidBody, l: ArrayLike, g: ArrayLike
                             ) -> NDArray[np.float64]:
    """The potential on the physical pendulum as printed after (11): ``mu^-1 sin(g + l - phi0)``.

    Kept to show that it is wrong (``mu^-1`` for ``mu``, ``-phi0`` for ``+phi0``);
    use :func:`pendulum_potential`.

    Parameters
    ----------
    body : RigidBody
        A body whose physical pendulum exists (``mu``, ``phi0``).
    l, g : array_like
        Andoyer-Deprit angles (rad) on the pendulum ``L = G``, ``M = 0``.
    """
    body.require_planar("the physical-pendulum potential")
    return np.asarray(np.sin(finite_array("g", g) + finite_array("l", l)
                             - body.phi0) / body.mu)


@checks_body(ranges={"vartheta0": "angle", "L0": "action"}, closed_form=CLOSED_FORM)
def physical_pendulum(body: RigidBody, vartheta0: float, L0: float, t: ArrayLike
                      ) -> xr.Dataset:
    """The physical-pendulum motion in closed form (Jacobi elliptic functions).

    Parameters
    ----------
    body : RigidBody
        ``e3 = 0`` (the centre of mass in the plane ``Oxy``), ``mu > 0``.
    vartheta0, L0 : float
        Initial angle (``gamma = (sin(vartheta - phi0), cos(vartheta - phi0), 0)``) and
        ``L = G3`` at ``t[0]``.
    t : array_like, shape (k,)
        Output times, strictly increasing.

    Returns
    -------
    xarray.Dataset
        Dims ``(time,)``: ``vartheta`` (unwrapped), the Euler-Poisson state, the chart
        coordinates (on the singular set ``L = +-G``: ``l = 0``, the whole angle in
        ``g``; flags in ``singular``), ``H``. Attrs: ``h``, ``motion``, ``period``,
        ``modulus`` (``m = k^2``), provenance.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> ds = physical_pendulum(RigidBody.paper(), 4.0, 0.1, [0.0, 10.0])
    >>> ds.attrs["motion"], bool(abs(ds.H - ds.H[0]).max() < 1e-15)
    ('libration', True)
    """
    require_pendulum_body(body, "the physical pendulum")
    times = _times(t)
    q, p = pendulum_solution(body.c, body.mu, vartheta0, L0, times)
    y = pendulum_state(body, q, p)
    h = float(pendulum_energy(body.c, body.mu, vartheta0, L0))
    motion = pendulum_motion(body.mu, h)
    attrs = provenance(
        body, method="closed form (Jacobi elliptic functions, scipy.special.ellipj)",
        h=h, motion=motion, period=pendulum_period(body.c, body.mu, h),
        modulus=pendulum_modulus(body.mu, h), modulus_convention="m = k^2 (scipy)",
        equations="physical pendulum G1 = G2 = gamma3 = 0 (G^2 = L^2, M = 0, Eq. (8)): "
                  "H = c L^2/2 + mu sin(vartheta)")
    ds = states_dataset(body, y, ("time",), {"time": times}, attrs,
                        extra={"vartheta": (("time",), q)})
    ds["vartheta"].attrs.update(
        symbol="\\vartheta", units="rad", equation="(8), (11)",
        long_name="pendulum angle: gamma = (sin(vartheta - phi0), cos(vartheta - phi0), 0); "
                  "g + l + phi0 on L = G")
    ds.time.attrs.update(units="body time units", long_name="time")
    return ds


def _times(t: ArrayLike) -> NDArray[np.float64]:
    arr = np.asarray(t, dtype=float)
    if arr.ndim != 1 or arr.size < 1 or not np.all(np.isfinite(arr)):
        raise ValueError(f"t must be a 1-D array of finite output times, got shape {arr.shape}")
    if np.any(np.diff(arr) <= 0.0):
        raise ValueError("t must be strictly increasing")
    return arr


