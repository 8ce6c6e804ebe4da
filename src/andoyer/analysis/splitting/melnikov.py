"""The Melnikov function of the heteroclinic orbits of the Hess chart, for ``mu H1``.

At ``M = 0`` the Hess-chart Hamiltonian (16) is ``H = H0(theta1, J1; J2) + mu H1`` with

.. math::

    H_0 = \\tfrac12 c J_2^2 + \\kappa J_1 (J_1 - J_2)[\\cos(\\theta_1 - 2\\varphi_0)
          - \\cos 2\\varphi_0], \\qquad
    H_1 = [J_1 \\sin(\\theta_1 + \\theta_2) + (J_2 - J_1) \\sin\\theta_2] / J_2 .

At ``mu = 0`` the lines ``theta1 = 0`` and ``theta1 = 4 phi0`` carry the heteroclinic
orbits of :func:`andoyer.analysis.unperturbed.separatrix.heteroclinic` between the rotations
``L = -G`` (``J1 = 0``) and ``L = +G`` (``J1 = J2``), with ``theta2 = theta2_0 + c J2 t``.

Which quantity splits
---------------------
``E = H0 - c J2^2 / 2`` (:func:`andoyer.analysis.splitting.manifolds.euler_poinsot_excess`) is a
first integral of the unperturbed flow that vanishes on the separatrices *and* on the
periodic orbits ``P+-`` of every ``mu`` (there ``G1 = G2 = 0``). Along the full flow
``dE/dt = mu {E, H1}``, an integrand that decays exponentially at both ends of a
heteroclinic orbit. Integrating from ``P-`` to a point of ``W^u`` and from a point of
``W^s`` to ``P+``, and replacing the perturbed orbits by the unperturbed one
(error ``O(mu^2)``):

.. math::

    \\Delta E(\\theta_2^0) = E^u - E^s = \\mu M(\\theta_2^0) + O(\\mu^2), \\qquad
    M(\\theta_2^0) = \\int_{-\\infty}^{\\infty} \\{E, H_1\\}(x_0(t))\\, dt,

``x0`` the unperturbed heteroclinic orbit with ``L = 0`` and ``theta2 = theta2^0`` at
``t = 0``. (The full bracket ``{H0, H1} = {E, H1} + c J2 {J2, H1}`` does not decay:
``{J2, H1} = -dH1/dtheta2`` oscillates on ``P+-``; ``{E, H1}`` is its part that does,
the ``(theta1, J1)`` bracket of the energy-reduced system.)

On the section ``L = 0`` at fixed phase ``g`` the energy relation
``c G^2/2 + E + mu H1 = h`` turns this into the distance along ``g = const``:
``Delta G = -Delta E / (c G) (1 + O(mu))``, and ``theta2^0 = g - theta1/2``.

Closed form
-----------
On the line ``theta1 = const``: ``{E, H1} = dH0/dtheta1 dH1/dJ1 =
-(dJ1/dt / J2) [sin(theta1 + theta2) - sin theta2]`` (the other terms carry the vanishing
bracket ``cos(theta1 - 2 phi0) - cos 2 phi0``), ``J1 / J2 = 1/(1 + e^{-s lambda t})``
(``s = +1`` where J1 increases), ``lambda = 2 sigma J2``. With
``int (lambda/4) sech^2(lambda t / 2) e^{i omega t} dt = pi rho / sinh(pi rho)`` (residues
at ``t = i pi (2k + 1) / lambda``), ``omega = c J2``:

.. math::

    M(\\theta_2^0) = -s\\, \\frac{\\pi\\rho}{\\sinh \\pi\\rho}
        [\\sin(\\theta_1 + \\theta_2^0) - \\sin\\theta_2^0]
      = -2 s\\, \\frac{\\pi\\rho}{\\sinh \\pi\\rho} \\sin\\frac{\\theta_1}{2}\\,
        \\cos\\Big(\\theta_2^0 + \\frac{\\theta_1}{2}\\Big),
    \\qquad \\rho = \\frac{c J_2}{\\lambda} = \\frac{c}{2\\sigma}.

It vanishes identically on ``theta1 = 0`` (the Hess solutions, which do not split). On
``theta1 = 4 phi0`` of a Hess body ``sin 2 phi0 = 2 sigma / (b - a)``, so
``Delta G = 2 pi mu cos g / ((b - a) J2 sinh(pi rho))`` (``phi0 > 0``): about
``7.4e-5 mu`` for the paper's body (``rho = 4.564``, ``pi rho / sinh(pi rho) = 1.7e-5``).

The numerical route evaluates ``{E, H1} = grad E . X_{H1}`` in the Euler-Poisson
variables (``grad E = I^-1 G - c G``; ``X_{H1}`` the field (1) of ``mu = 1`` minus that of
``mu = 0``) along the states of :func:`~andoyer.analysis.unperturbed.separatrix.heteroclinic` and
integrates with the trapezoidal rule on the real line, which converges geometrically for
this integrand (analytic in a strip, decaying exponentially) [2]_; ``method="quad"``
uses :func:`scipy.integrate.quad` instead.

References
----------
.. [1] V. V. Kyrychenko, "Andoyer-Deprit variables use to the Hess gyroscope phase
   trajectories exploring", National Aviation University, Kyiv (``andoyer.cite("paper")``).
.. [2] L. N. Trefethen and J. A. C. Weideman, "The exponentially convergent trapezoidal
   rule", SIAM Review 56 (2014) 385-458.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from andoyer.analysis.unperturbed.separatrix import (
    BRANCHES,
    DEFAULT_BRANCH,
    heteroclinic,
    heteroclinic_rate,
)
from andoyer.body import RigidBody, checks_body
from andoyer.charts.euler_poisson import as_state
from andoyer.dynamics import vector_field
from andoyer.integrate.results import provenance, values_from_attrs
from andoyer.validation import MAX_ACTION, choice, finite, finite_array, integer, positive

__all__ = [
    "heteroclinic_line",
    "melnikov_integrand",
    "melnikov_closed_form",
    "melnikov_quadrature",
    "melnikov_function",
    "predicted_splitting",
    "melnikov_rho",
    "melnikov_off_hess",
]

#: Closed forms only: levels and actions up to ``|G| = MAX_ACTION``
#: (:func:`andoyer.validation.momentum_limit`).
CLOSED_FORM = True

#: The integrand is below ``exp(-TAIL)`` times its maximum beyond the truncation time.
TAIL = 46.0


@checks_body(ranges={"J2": "action", "sheet": "sheet"}, closed_form=CLOSED_FORM)
def heteroclinic_line(body: RigidBody, J2: float, branch: str, sheet: int = 1
                      ) -> tuple[float, int]:
    """``(theta1 of the line in [0, 4 pi), s)``: ``s = +1`` where J1 increases along it.

    Read from :func:`~andoyer.analysis.unperturbed.separatrix.heteroclinic` (the direction is fixed
    by the flow: for ``phi0 > 0`` J1 increases on ``theta1 = 4 phi0``).

    Parameters
    ----------
    body : RigidBody
        A Hess body (``phi0``).
    J2 : float
        ``J2 = G`` of the level (``h = c J2^2 / 2``).
    branch : {"theta1=0", "theta1=4phi0"}
        Which heteroclinic line.
    sheet : {+1, -1}, default 1
        Which of its two orbits (``theta1`` or ``theta1 + 2 pi``).

    Examples
    --------
    >>> theta1, s = heteroclinic_line(RigidBody.paper(), 1.0, "theta1=4phi0")
    >>> round(theta1 / RigidBody.paper().phi0, 12), s
    (4.0, 1)
    """
    if branch not in BRANCHES:
        raise ValueError(f"branch must be one of {BRANCHES}, got {branch!r}")
    het = heteroclinic(body, J2, [0.0], branch, sign=sheet)
    return float(het.attrs["theta1_line"]), (1 if het.attrs["J1_direction"] == "increasing"
                                              else -1)


@checks_body(ranges={"J2": "action"}, closed_form=CLOSED_FORM)
def melnikov_rho(body: RigidBody, J2: float = 1.0) -> float:
    """``rho = c J2 / lambda = c / (2 sigma)``: frequency of theta2 over the rate of J1.

    Parameters
    ----------
    body : RigidBody
        A Hess body (``c``, ``sigma``).
    J2 : float, default 1.0
        ``J2 = G`` of the level.

    Examples
    --------
    >>> round(melnikov_rho(RigidBody.paper()), 6)
    4.564355
    """
    J2 = positive("J2", J2, maximum=MAX_ACTION)
    return body.c * J2 / heteroclinic_rate(body, J2)


@checks_body
def melnikov_integrand(body: RigidBody, y: ArrayLike) -> NDArray[np.float64]:
    """``{E, H1}(y) = (grad E, X_{H1})`` in the Euler-Poisson variables, shape ``(...)``.

    ``E = H0 - c |G|^2/2`` so ``grad_G E = I^-1 G - c G``, ``grad_gamma E = 0``;
    ``X_{H1}`` is the Lie-Poisson field (1) of ``H1 = (r, gamma)``, the difference of the
    fields at ``mu = 1`` and ``mu = 0`` (the field is affine in ``mu``).

    Parameters
    ----------
    body : RigidBody
        The body (moments, ``r``; the bracket is linear in ``mu``, which does not enter).
    y : array_like, shape (..., 6)
        Euler-Poisson states of Eq. (1).
    """
    arr = as_state(y)
    X1 = vector_field(body.with_mu(1.0), arr) - vector_field(body.with_mu(0.0), arr)
    G = arr[..., :3]
    gradE = G * np.array([body.a, body.b, body.c]) - body.c * G
    return np.asarray(np.einsum("...i,...i->...", gradE, X1[..., :3]))


@checks_body(ranges={"J2": "action", "sheet": "sheet"}, closed_form=CLOSED_FORM)
def melnikov_closed_form(body: RigidBody, theta2_0: ArrayLike, *, J2: float = 1.0,
                         branch: str = DEFAULT_BRANCH, sheet: int = 1
                         ) -> NDArray[np.float64]:
    """``M(theta2_0) = -s pi rho / sinh(pi rho) [sin(theta1 + theta2_0) - sin theta2_0]``.

    Parameters
    ----------
    body : RigidBody
        A Hess body.
    theta2_0 : array_like
        ``theta2`` where the unperturbed heteroclinic orbit crosses ``L = 0``.
    J2 : float
        ``J2 = G`` of the level (``h = c J2^2 / 2``).
    branch : {"theta1=0", "theta1=4phi0"}
    sheet : {+1, -1}
        ``theta1`` of the line, or ``theta1 + 2 pi``.

    Examples
    --------
    >>> body = RigidBody.hess(2.5, 1.0, 1.6)
    >>> float(melnikov_closed_form(body, 0.3, branch="theta1=0"))
    0.0
    """
    theta1, s = heteroclinic_line(body, J2, branch, sheet)
    rho = melnikov_rho(body, J2)
    # pi rho / sinh(pi rho), without overflow for large rho.
    x = math.pi * rho
    factor = 2.0 * x * math.exp(-x) / (1.0 - math.exp(-2.0 * x))
    th = finite_array("theta2_0", theta2_0)
    return np.asarray(-s * factor * (np.sin(theta1 + th) - np.sin(th)))


@checks_body(ranges={"J2": "action", "sheet": "sheet", "points_per_period": "count"},
             closed_form=CLOSED_FORM)
def melnikov_quadrature(body: RigidBody, theta2_0: ArrayLike, *, J2: float = 1.0,
                        branch: str = DEFAULT_BRANCH, sheet: int = 1,
                        method: str = "trapezoid", points_per_period: int = 32
                        ) -> NDArray[np.float64]:
    """``M(theta2_0) = int {E, H1}(x0(t)) dt`` by numerical quadrature.

    The integrand is evaluated in Euler-Poisson variables (:func:`melnikov_integrand`)
    on the closed-form unperturbed orbit of
    :func:`~andoyer.analysis.unperturbed.separatrix.heteroclinic`, over ``|t| <= T`` with
    ``T = (TAIL + ln(2 lambda)) / lambda``, beyond which it is below
    ``exp(-TAIL) ~ 1e-20``.

    Parameters
    ----------
    body : RigidBody
        A Hess body.
    theta2_0 : array_like
        Phases (``theta2`` at ``L = 0``, rad).
    J2 : float, default 1.0
        ``J2 = G`` of the level (``h = c J2^2 / 2``).
    branch : {"theta1=0", "theta1=4phi0"}, default "theta1=0"
        Which heteroclinic line
        (:data:`~andoyer.analysis.unperturbed.separatrix.DEFAULT_BRANCH`).
    sheet : {+1, -1}, default 1
        Which of its two orbits.
    method : {"trapezoid", "quad"}
        ``"trapezoid"``: the trapezoidal rule with ``points_per_period`` nodes per period
        of ``theta2`` (or of ``e^{-lambda t}`` if that is shorter): geometric
        convergence, one vectorised call of the closed-form orbit. ``"quad"``:
        :func:`scipy.integrate.quad` (adaptive Gauss-Kronrod; slow, a check).
    points_per_period : int, default 32
        Trapezoidal nodes per period (``"trapezoid"`` only).

    Examples
    --------
    >>> body = RigidBody.hess(2.5, 1.0, 1.6)
    >>> q = melnikov_quadrature(body, [0.0, 1.0], branch="theta1=4phi0")
    >>> c = melnikov_closed_form(body, [0.0, 1.0], branch="theta1=4phi0")
    >>> bool(np.allclose(q, c, rtol=0, atol=1e-14))
    True
    """
    if method not in ("trapezoid", "quad"):
        raise ValueError(f"method must be 'trapezoid' or 'quad', got {method!r}")
    if int(points_per_period) != points_per_period or points_per_period < 8:
        raise ValueError(f"points_per_period must be an integer >= 8, got "
                         f"{points_per_period!r}")
    heteroclinic_line(body, J2, branch, sheet)
    lam = heteroclinic_rate(body, J2)
    omega = body.c * J2
    T = (TAIL + math.log(2.0 * lam + 1.0)) / lam
    th = np.atleast_1d(finite_array("theta2_0", theta2_0))
    out = np.empty(th.shape)

    def f(t: ArrayLike, phase: float) -> NDArray[np.float64]:
        ds = heteroclinic(body, J2, t, branch, sign=sheet, theta2_0=phase)
        return melnikov_integrand(body, ds.y.values)

    for i, phase in np.ndenumerate(th):
        if method == "trapezoid":
            h = min(math.tau / omega, math.tau / lam) / points_per_period
            n = math.ceil(T / h)
            t = h * np.arange(-n, n + 1)
            out[i] = h * float(np.sum(f(t, float(phase))))
        else:
            from scipy.integrate import quad

            val, _ = quad(lambda t, p=float(phase): float(f([t], p)[0]), -T, T,
                          epsabs=1e-15, epsrel=1e-12, limit=4000)
            out[i] = val
    return out.reshape(np.shape(theta2_0))


@checks_body(ranges={"g": "angle", "mu": "scale", "G": "length", "sheet": "sheet"},
             closed_form=CLOSED_FORM)
def predicted_splitting(body: RigidBody, g: ArrayLike, mu: float, *, G: float = 1.0,
                        branch: str = DEFAULT_BRANCH, sheet: int = 1
                        ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """First-order splitting on ``L = 0`` at phase ``g``: ``(Delta E, Delta G)``.

    ``Delta E = mu M(g - theta1/2)``, ``Delta G = -Delta E / (c G)`` (see the module
    notes), with the closed-form ``M``.

    Parameters
    ----------
    body : RigidBody
        A Hess body.
    g : array_like
        Phases ``g`` (rad) on ``L = 0``.
    mu : float
        The perturbation ``mu`` the first order is scaled by (the body's own ``mu`` is not
        used: the prediction is linear in it).
    G : float, default 1.0
        ``|G| = J2`` of the level.
    branch : {"theta1=0", "theta1=4phi0"}, default "theta1=0"
        Which heteroclinic line.
    sheet : {+1, -1}, default 1
        Which of its two orbits.
    """
    g = finite_array("g", g)
    theta1, _ = heteroclinic_line(body, G, branch, sheet)
    dE = float(mu) * melnikov_closed_form(body, g - theta1 / 2.0,
                                          J2=G, branch=branch, sheet=sheet)
    return dE, -dE / (body.c * G)


@checks_body(ranges={"J2": "action", "sheet": "sheet", "n": "count"}, closed_form=CLOSED_FORM)
def melnikov_function(body: RigidBody, theta2_0: ArrayLike | None = None, *,
                      J2: float = 1.0, branch: str = DEFAULT_BRANCH, sheet: int = 1,
                      n: int = 64, quadrature: bool = True) -> xr.Dataset:
    """The Melnikov function of a heteroclinic line as a dataset of the phase.

    Parameters
    ----------
    body : RigidBody
        A Hess body, or any body with its centre of mass in the (e1, e2) plane and
        ``A > C > B``: then the lines and the chart are those of
        :meth:`~andoyer.body.RigidBody.nearest_hess` and the function is
        :func:`melnikov_off_hess` at ``epsilon =``
        :attr:`~andoyer.body.RigidBody.hess_epsilon`.
    theta2_0 : array_like, optional
        Phases (``theta2`` at ``L = 0``); default ``n`` equal steps of ``[0, 2 pi)``.
    J2, branch, sheet :
        As in :func:`melnikov_closed_form`.
    quadrature : bool
        Also compute ``M_quadrature`` (trapezoidal rule).
    n : int, default 64
        Number of phases when ``theta2_0`` is not given (>= 8).

    Returns
    -------
    xarray.Dataset
        Dim ``theta2_0``: ``M`` (closed form), ``M_quadrature``, ``g`` (the phase on
        ``L = 0``), ``Delta_G_per_mu = -M/(c J2)``. Values ``rho``, ``lambda_rate``,
        ``amplitude`` (of ``M``), ``epsilon``; attrs ``theta1_line``, ``J1_direction``.

    Examples
    --------
    >>> ds = melnikov_function(RigidBody.paper(), n=8, quadrature=False, branch="theta1=4phi0")
    >>> f"{ds.attrs['amplitude']:.4e}"
    '3.3829e-05'

    A turned centre of mass splits the Hess branch too, linearly in ``epsilon``:

    >>> turned = RigidBody.near_hess(2.5, 2.0, 2.2, epsilon=0.1)
    >>> ds = melnikov_function(turned, n=8, branch="theta1=0", quadrature=False)
    >>> f"{float(ds.amplitude):.4e}", round(float(ds.epsilon), 12)
    ('3.3913e-06', 0.1)
    """
    J2 = positive("J2", J2, maximum=MAX_ACTION)
    if theta2_0 is None:
        n = integer("n", n, 1)
        th = math.tau * np.arange(n) / n
    else:
        th = np.atleast_1d(finite_array("theta2_0", theta2_0))
        if th.ndim != 1 or not np.all(np.isfinite(th)):
            raise ValueError("theta2_0 must be a 1-D array of finite phases")
    return melnikov_of(body, body.nearest_hess(), th, J2=J2, branch=branch, sheet=sheet,
                       quadrature=quadrature)


def melnikov_of(body: RigidBody, hess: RigidBody, theta2_0: NDArray[np.float64], *,
                J2: float, branch: str, sheet: int, quadrature: bool) -> xr.Dataset:
    """:func:`melnikov_function` of a body whose nearest Hess body ``hess`` is already
    known (a prepared problem's,
    :class:`~andoyer.analysis.splitting.problem.SplittingProblem`), at checked phases.

    Parameters
    ----------
    body : RigidBody
        The body.
    hess : RigidBody
        Its nearest Hess body (:meth:`~andoyer.body.RigidBody.nearest_hess`).
    theta2_0 : ndarray, shape (n,)
        Finite phases.
    J2, branch, sheet, quadrature :
        As in :func:`melnikov_function`.
    """
    th = theta2_0
    eps = float(math.remainder(body.phi0 - hess.phi0, math.tau))
    theta1, s = heteroclinic_line(hess, J2, branch, sheet)
    rho = melnikov_rho(hess, J2)
    x = math.pi * rho
    factor = 2.0 * x * math.exp(-x) / (1.0 - math.exp(-2.0 * x))
    if eps == 0.0:
        M = melnikov_closed_form(hess, th, J2=J2, branch=branch, sheet=sheet)
        closed = ("M = -s pi rho/sinh(pi rho) [sin(theta1 + theta2_0) - sin(theta2_0)], "
                  "rho = c J2/lambda")
    else:
        M = melnikov_off_hess(hess, eps, th, J2=J2, branch=branch, sheet=sheet)
        closed = ("M = -2 s pi rho/sinh(pi rho) sin(theta1/2 + epsilon) cos(theta2_0 + "
                  "theta1/2), rho = c J2/lambda (centre of mass turned by epsilon)")
    data: dict[str, Any] = {"M": (("theta2_0",), M),
                            "g": (("theta2_0",), np.mod(th + theta1 / 2.0, math.tau)),
                            "Delta_G_per_mu": (("theta2_0",), -M / (body.c * J2))}
    if quadrature:
        data["M_quadrature"] = (("theta2_0",), melnikov_quadrature(
            hess, th, J2=J2, branch=branch, sheet=sheet) if eps == 0.0 else
            melnikov_off_hess(hess, eps, th, J2=J2, branch=branch, sheet=sheet,
                              method="trapezoid"))
    ds = xr.Dataset(data, coords={"theta2_0": th}, attrs=provenance(
        body.with_mu(0.0), engine="closed form and trapezoidal rule",
        equations="M(theta2_0) = int {E, H1} dt along the unperturbed heteroclinic orbit, "
                  "E = H0 - c J2^2/2",
        closed_form=closed,
        branch=branch, sheet=sheet, J2=J2, theta1_line=theta1,
        J1_direction="increasing" if s > 0 else "decreasing", rho=rho,
        lambda_rate=heteroclinic_rate(hess, J2),
        amplitude=abs(2.0 * factor * math.sin(theta1 / 2.0 + eps)),
        pi_rho_over_sinh=factor, epsilon=eps))
    values_from_attrs(ds, {
        "epsilon": ("\\epsilon", "turn of the centre of mass off the Hess direction", "rad",
                    "(2)"),
        "amplitude": ("\\max|M|", "amplitude of the Melnikov function", "energy units x time",
                      "(16)"),
        "rho": ("\\rho", "rho = c J2/lambda", "1", ""),
        "lambda_rate": ("\\lambda", "rate of the heteroclinic orbit, 2 sigma J2",
                        "1/body time units", "after Fig. 3"),
        "pi_rho_over_sinh": ("\\pi\\rho/\\sinh\\pi\\rho", "the factor pi rho/sinh(pi rho)", "1",
                             "")})
    ds.theta2_0.attrs.update(symbol="\\theta_2^0", long_name="theta2 where the unperturbed "
                             "heteroclinic orbit crosses L = 0", units="rad", equation="(14)")
    ds["M"].attrs.update(symbol="M", long_name="Melnikov function, closed form",
                         units="energy units x time", equation="(16)")
    ds["g"].attrs.update(symbol="g", long_name="phase g = theta2_0 + theta1/2 on L = 0",
                         units="rad", equation="(15)")
    ds["Delta_G_per_mu"].attrs.update(symbol="-M/(c J_2)", long_name="first-order "
                                      "splitting Delta G / mu on L = 0", units="1")
    if quadrature:
        ds["M_quadrature"].attrs.update(symbol="M", long_name="Melnikov function, trapezoidal "
                                        "rule on the closed-form orbit",
                                        units="energy units x time", equation="(16)")
    return ds


@checks_body(ranges={"epsilon": "finite", "J2": "action", "sheet": "sheet"},
             closed_form=CLOSED_FORM)
def melnikov_off_hess(body: RigidBody, epsilon: float, theta2_0: ArrayLike, *,
                      J2: float = 1.0, branch: str = DEFAULT_BRANCH, sheet: int = 1,
                      method: str = "closed_form") -> NDArray[np.float64]:
    """The Melnikov function when the centre of mass is turned by ``epsilon`` off the Hess
    direction (:meth:`~andoyer.body.RigidBody.near_hess`), on both separatrix branches.

    The unperturbed orbits do not depend on ``r``, so the heteroclinic orbits and the
    chart are those of the Hess ``body``; only ``H1 = (r, gamma)`` changes. At ``M = 0``
    with ``r`` at the angle ``phi0 + epsilon`` (``cos J = (2 J1 - J2)/J2``)::

        H1 = sin(theta2 + theta1/2) cos(theta1/2 + epsilon)
             + cos J cos(theta2 + theta1/2) sin(theta1/2 + epsilon)

    (at ``epsilon = 0`` the paper's ``[J1 sin(theta1 + theta2) + (J2 - J1) sin theta2]/J2``).
    On a line ``theta1 = const`` only ``dH0/dtheta1 dH1/dJ1`` survives in ``{E, H1}``,
    ``dH1/dJ1 = (2/J2) cos(theta2 + theta1/2) sin(theta1/2 + epsilon)``, and the integral
    of the module notes gives

        M(theta2_0) = -2 s (pi rho / sinh(pi rho)) sin(theta1/2 + epsilon)
                      cos(theta2_0 + theta1/2),

    so on the Hess branch ``theta1 = 0`` the amplitude is
    ``2 (pi rho / sinh(pi rho)) |sin epsilon|``: zero exactly at ``epsilon = 0``, linear
    in it. ``method="trapezoid"`` integrates ``{E, H1}`` of the turned body along the
    orbits instead (:func:`melnikov_integrand`), an independent check.

    Parameters
    ----------
    body : RigidBody
        The Hess body (its chart and its heteroclinic orbits).
    epsilon : float
        The turn of the centre of mass in the (e1, e2) plane.
    theta2_0, J2, branch, sheet
        As for :func:`melnikov_closed_form`.
    method : {"closed_form", "trapezoid"}

    Examples
    --------
    >>> body = RigidBody.hess(2.5, 1.0, 1.6)
    >>> a = melnikov_off_hess(body, 0.01, [0.0, 1.0])
    >>> b = melnikov_off_hess(body, 0.01, [0.0, 1.0], method="trapezoid")
    >>> bool(np.allclose(a, b, rtol=0, atol=1e-13)), bool(abs(a[0]) > 0)
    (True, True)
    """
    body.require_hess("melnikov_off_hess")
    eps = finite("epsilon", epsilon)
    method = choice("method", method, ("closed_form", "trapezoid"))
    finite_array("theta2_0", theta2_0)
    if method == "trapezoid":
        branch_sign = 1 if body.e2 >= 0.0 else -1
        turned = RigidBody.near_hess(body.A, body.B, body.C, body.mu, eps, branch=branch_sign)
        lam = heteroclinic_rate(body, J2)
        omega = body.c * J2
        T = (TAIL + math.log(2.0 * lam + 1.0)) / lam
        h = min(math.tau / omega, math.tau / lam) / 32
        n = math.ceil(T / h)
        t = h * np.arange(-n, n + 1)
        th = np.atleast_1d(finite_array("theta2_0", theta2_0))
        out = np.array([h * float(np.sum(melnikov_integrand(
            turned, heteroclinic(body, J2, t, branch, sign=sheet, theta2_0=float(p)).y.values)))
            for p in th.ravel()])
        return out.reshape(np.shape(theta2_0))
    if method != "closed_form":
        raise ValueError(f"method must be 'closed_form' or 'trapezoid', got {method!r}")
    theta1, s = heteroclinic_line(body, J2, branch, sheet)
    x = math.pi * melnikov_rho(body, J2)
    factor = 2.0 * x * math.exp(-x) / (1.0 - math.exp(-2.0 * x))
    th = finite_array("theta2_0", theta2_0)
    return np.asarray(-2.0 * s * factor * math.sin(0.5 * theta1 + eps)
                      * np.cos(th + 0.5 * theta1))
