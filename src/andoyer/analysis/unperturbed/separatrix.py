"""Separatrices and heteroclinic orbits of the unperturbed (Euler-Poinsot) system.

At ``mu = 0`` the reduced system at fixed ``G = G0`` is Eq. (9) of [1]_ in ``(l, L)``
and, in the Hess chart (14) at ``M = 0``, the one-degree-of-freedom system in
``(theta1, J1)`` at fixed ``J2`` (the paper's "unperturbed system" after Fig. 3), with
the Hamiltonian (13)/(16) at ``mu = 0``:

.. math::

    H_0 = \\tfrac12 c J_2^2 + \\kappa J_1 (J_1 - J_2)
          [\\cos(\\theta_1 - 2\\varphi_0) - \\cos 2\\varphi_0],
    \\qquad \\kappa = a - b.

(It is checked against ``andoyer.dynamics.hamiltonian(body.with_mu(0), x, "hess")``
in the tests; nothing here is transcribed from the paper.)

Heteroclinic orbits
-------------------
On ``theta1 = 0`` and ``theta1 = 4 phi0`` the bracket vanishes, so ``dtheta1/dt = 0``
and ``dJ1/dt = kappa J1 (J1 - J2) sin(theta1 - 2 phi0)`` is a logistic equation. On a
Hess body ``kappa sin 2 phi0 = -2 sigma sgn(phi0)`` with
``sigma = sqrt((b - c)(c - a))`` (because ``sin^2 phi0 = (b - c)/(b - a)``), hence

.. math::

    J_1(t) = \\frac{J_2}{1 + e^{-s \\lambda (t - t_0)}}, \\qquad
    \\lambda = 2 \\sigma J_2, \\qquad
    \\theta_2(t) = \\theta_2(t_0) + c J_2 (t - t_0),

with ``s = -sgn(phi0)`` on ``theta1 = 0`` and ``s = +sgn(phi0)`` on
``theta1 = 4 phi0``: for the paper's branch (``phi0 > 0``) J1 *decreases* along
``theta1 = 0`` (from the rotation about +z, ``L = +G``, to the one about -z) and
*increases* along ``theta1 = 4 phi0``. The direction is fixed by the flow, not a choice.
In Euler-Poisson variables ``G3 = L = J2 tanh(x/2)``,
``sqrt(G1^2 + G2^2) = J2 / cosh(x/2)`` with ``x = s lambda (t - t0)``: the physical
Lyapunov exponent at the rotation about the z axis is ``sigma J2 = lambda / 2``; the
chart action ``J1 ~ (G1^2 + G2^2)`` decays at twice that rate.

Separatrices and portraits
--------------------------
``H0(l, L) = (G0^2 s(l) + L^2 (c - s(l)))/2`` with ``s(l) = a sin^2 l + b cos^2 l``
(Eqs. (9), (12)) is quadratic in L, so the level through the saddles,
``h = I_mid G0^2/2`` (the rotation about the middle axis), is in closed form:
``L^2 = G0^2 (I_mid - s(l))/(c - s(l))``. When z is the middle axis (every Hess body)
it splits into the singular lines ``L = +-G0`` and the lines ``s(l) = c``, i.e.
``l = +-phi0 (mod pi)``, which are ``theta1 = 0`` and ``theta1 = 4 phi0`` (mod 2 pi) in
the Hess chart; ``theta1 = 0`` (``l = -phi0 mod pi``), the Hess invariant relation (3),
is the separatrix the Hess solutions approach as ``mu -> 0``.
:func:`separatrix_andoyer` / :func:`separatrix_hess` sample these curves;
:func:`portrait_andoyer` / :func:`portrait_hess` collect what Figs. 1-2 need (H0 on a
grid, contour levels with the separatrix level, the curves, the fixed points of
:mod:`andoyer.analysis.unperturbed.fixed_points` with their types, the digits 1-4 of the uniform
rotations), drawn by :mod:`andoyer.plot.portraits`.

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
from scipy.special import expit

from andoyer.analysis.unperturbed.fixed_points import theta_text
from andoyer.body import RigidBody, checks_body
from andoyer.charts.andoyer_deprit import rotation_chain_expr
from andoyer.charts.euler_poisson import STATE
from andoyer.integrate.results import (
    VariableMeta,
    describe_variables,
    provenance,
    values_from_attrs,
)
from andoyer.validation import MAX_ACTION, MAX_COUNT, checks_arguments, integer
from andoyer.validation import finite as _finite
from andoyer.validation import positive as _positive

__all__ = ["BRANCHES", "DEFAULT_BRANCH", "heteroclinic_rate", "heteroclinic", "separatrix_energy",
           "separatrix_momentum",
           "separatrix_andoyer", "separatrix_hess",
           "FIG2_CAPTION", "SEPARATRIX_LEVEL", "check_grid_size", "separatrix_curves",
           "separatrix_on_level"]

#: Closed forms only: levels and actions up to ``|G| = MAX_ACTION``
#: (:func:`andoyer.validation.momentum_limit`).
CLOSED_FORM = True

#: The two heteroclinic lines of the Hess chart at ``mu = 0`` (theta1 mod 2 pi).
BRANCHES = ("theta1=0", "theta1=4phi0")

#: The separatrix branch of every function that takes one (heteroclinic orbits, Melnikov
#: functions, manifolds, splitting, the scan's splitting task) when the caller names none:
#: the Hess separatrix ``theta1 = 0``, the line of the Hess relation (3). It does not
#: split on a Hess body (the manifolds coincide); turned off the Hess direction by
#: ``epsilon`` it does (:meth:`~andoyer.body.RigidBody.near_hess`). ``"theta1=4phi0"``
#: is the branch that splits on a Hess body: name it.
DEFAULT_BRANCH = "theta1=0"


@checks_body(ranges={"J2": "action"}, closed_form=CLOSED_FORM)
def heteroclinic_rate(body: RigidBody, J2: float = 1.0) -> float:
    """Rate ``lambda = 2 sigma J2`` of the unperturbed heteroclinic orbits, ``J1 ~ e^{-lambda t}``.

    Parameters
    ----------
    body : RigidBody
        Any body whose z axis is the middle axis of inertia (``a < c < b`` or
        ``b < c < a``); ``mu`` is ignored (the orbits are those of ``mu = 0``).
    J2 : float
        ``J2 = G``, the length of the angular momentum (> 0).

    Returns
    -------
    float
        ``lambda = 2 sqrt((b - c)(c - a)) J2``. This is the rate of the chart action
        ``J1`` (and the chart Jacobian's eigenvalue at the points ``(0, 0)``,
        ``(4 phi0, J2)``, ... of the unperturbed system after Fig. 3 of the paper); the
        physical exponent of the rotation about z in ``(G1, G2)`` is ``lambda / 2``.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> round(heteroclinic_rate(RigidBody.paper(), 1.0), 12)
    0.099585919546
    """
    sigma = body.require_middle_axis("a heteroclinic orbit between L = -G and L = G")
    return 2.0 * sigma * _positive("J2", J2, maximum=MAX_ACTION)


def _branch_angle(body: RigidBody, branch: str) -> tuple[float, int]:
    """``(theta1 of the line in [0, 2 pi), s)``: J1 = J2 expit(s lambda (t - t0))."""
    if branch not in BRANCHES:
        raise ValueError(f"branch must be one of {BRANCHES}, got {branch!r}")
    phi0 = body.phi0
    sgn = 1 if phi0 > 0.0 else -1
    if branch == "theta1=0":
        return 0.0, -sgn
    return float(np.mod(4.0 * phi0, math.tau)), sgn


@checks_body(ranges={"J2": "action", "t0": "angle"}, closed_form=CLOSED_FORM)
def heteroclinic(body: RigidBody, J2: float, t: ArrayLike, branch: str = DEFAULT_BRANCH,
                 t0: float = 0.0, sign: int = +1, *, theta2_0: float = 0.0) -> xr.Dataset:
    """The unperturbed (``mu = 0``, ``M = 0``) heteroclinic orbit along a separatrix line.

    Parameters
    ----------
    body : RigidBody
        A Hess body (its ``mu`` is ignored: the orbit is that of ``mu = 0``).
    J2 : float
        ``J2 = G > 0``, constant at ``mu = 0``.
    t : array_like, shape (k,)
        Times (any order; large ``|t - t0|`` are fine: no overflow).
    branch : {"theta1=0", "theta1=4phi0"}
        ``"theta1=0"``: the line of the Hess invariant relation (3) (``l = -phi0
        mod pi``), the separatrix the Hess solutions approach as ``mu -> 0``;
        ``"theta1=4phi0"``: the other one (``l = +phi0 mod pi``).
    t0 : float
        The time at which ``J1 = J2 / 2`` (``L = 0``).
    sign : {+1, -1}
        Which of the two orbits of the branch: ``+1`` gives ``theta1 = 0`` (resp.
        ``4 phi0``) in ``[0, 2 pi)``, ``-1`` the other half of the same great circle of
        the momentum sphere, ``theta1 + 2 pi`` in the double cover ``[0, 4 pi)`` (the
        image under the symmetry ``(G1, G2, gamma3) -> -(G1, G2, gamma3)``). It does
        *not* choose the direction of J1: on each line that is fixed by the flow (see
        the module notes and ``attrs["J1_direction"]``): for ``phi0 > 0`` J1
        decreases on ``theta1 = 0`` and increases on ``theta1 = 4 phi0``.
    theta2_0 : float, keyword-only
        ``theta2(t0)`` (default 0).

    Returns
    -------
    xarray.Dataset
        Dim ``time``: ``theta1``, ``theta2`` (unreduced, ``theta2_0 + c J2 (t - t0)``),
        ``J1``, ``J2``, ``J3`` (= 0), ``J2_minus_J1`` (to full relative accuracy as
        ``J1 -> J2``), ``L_action`` and the Euler-Poisson state ``y`` (time,
        component). Attrs: ``lambda_rate``, ``sigma``, ``branch``, ``sign``,
        ``J1_direction``, ``t0``, the closed forms, provenance (with ``mu = 0``).

    Notes
    -----
    ``J1(t) = J2 / (1 + exp(-s lambda (t - t0)))``, ``lambda = 2 sqrt((b-c)(c-a)) J2``;
    ``theta1`` constant; ``theta2 = theta2_0 + c J2 (t - t0)`` (``dtheta2/dt = dH0/dJ2
    = c J2`` where the bracket of (16) vanishes); ``J2``, ``J3 = M = 0`` constant.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> ds = heteroclinic(RigidBody.paper(), 1.0, [-1e4, 0.0, 1e4])
    >>> [round(float(v), 12) for v in ds.J1]
    [1.0, 0.5, 0.0]
    >>> ds.attrs["J1_direction"]
    'decreasing'
    """
    body.require_hess("heteroclinic")
    J2 = _positive("J2", J2, maximum=MAX_ACTION)
    if sign not in (1, -1):
        raise ValueError(f"sign must be +1 or -1, got {sign!r}")
    times = np.atleast_1d(np.asarray(t, dtype=float))
    if times.ndim != 1 or not np.all(np.isfinite(times)):
        raise ValueError("t must be a 1-D array of finite times")
    t0 = float(t0)
    theta2_0 = float(theta2_0)
    if not (math.isfinite(t0) and math.isfinite(theta2_0)):
        raise ValueError("t0 and theta2_0 must be finite")
    lam = heteroclinic_rate(body, J2)
    line, s = _branch_angle(body, branch)
    theta1 = line + (math.tau if sign == -1 else 0.0)

    x = s * lam * (times - t0)
    J1 = J2 * expit(x)
    J2_minus_J1 = J2 * expit(-x)
    theta2 = theta2_0 + body.c * J2 * (times - t0)
    # Euler-Poisson state by the rotation chain with cos J = L/G = tanh(x/2) and
    # sin J = 2 sqrt(J1 (J2 - J1))/G = 1/cosh(x/2), exact at any |x| (M = 0: I = pi/2).
    l = theta1 / 2.0 - body.phi0
    g = theta2 + theta1 / 2.0
    cJ = np.tanh(x / 2.0)
    sJ = np.exp(-np.logaddexp(x / 2.0, -x / 2.0)) * 2.0
    cols = rotation_chain_expr(np.full_like(times, l), g, J2, cJ, sJ, 0.0, 1.0,
                               sin=np.sin, cos=np.cos)
    y = np.stack(np.broadcast_arrays(*cols), axis=-1)

    direction = "increasing" if s > 0 else "decreasing"
    attrs = provenance(
        body.with_mu(0.0), engine="closed form",
        equations="unperturbed (mu = 0, M = 0) Hess-chart system after Fig. 3 of Kyrychenko",
        branch=branch, sign=int(sign), t0=t0, theta2_0=theta2_0, lambda_rate=lam,
        sigma=lam / (2.0 * J2), J1_direction=direction, theta1_line=theta1,
        closed_form=(f"J1 = J2 / (1 + exp(-({s:+d}) lambda (t - t0))), lambda = 2 sqrt((b-c)"
                     "(c-a)) J2; theta2 = theta2_0 + c J2 (t - t0); theta1 const"),
        body_mu_given=body.mu)
    ds = xr.Dataset(
        {"theta1": (("time",), np.full_like(times, theta1)),
         "theta2": (("time",), theta2),
         "J1": (("time",), J1),
         "J2": (("time",), np.full_like(times, J2)),
         "J3": (("time",), np.zeros_like(times)),
         "J2_minus_J1": (("time",), J2_minus_J1),
         "L_action": (("time",), J2 * cJ),
         "y": (("time", "component"), y),
         # The rates as values too (not only attrs): what a user reads off.
         "lambda_rate": ((), lam),
         "sigma": ((), lam / (2.0 * J2))},
        coords={"time": times, "component": list(STATE)}, attrs=attrs)
    meta: dict[str, VariableMeta] = {
            "J2_minus_J1": ("J_2 - J_1", "J2 - J1 = (G - L)/2", "1", "(14)"),
            "y": ("(G, \\gamma)", "Euler-Poisson state", "1", "(1)"),
            "lambda_rate": ("\\lambda", "rate of the heteroclinic orbit, 2 sigma J2",
                            "1/body time units", "after Fig. 3"),
            "sigma": ("\\sigma", "sqrt((b - c)(c - a))", "1", "")}
    describe_variables(ds, meta, long_names={
        "theta2": "Hess-chart angle g - l - phi0 (unreduced)"})
    ds.time.attrs.update(long_name="time", units="body time units")
    return ds


# ---------------------------------------------------------------------- separatrices
#: Caption of Fig. 2 (stored in the portrait datasets' attrs).
FIG2_CAPTION = (
    "Phase portrait of the unperturbed Euler-Poinsot system of a Hess body: (a) in the "
    "Andoyer-Deprit variables (l, L), (b) in the variables (theta1, J1) of (14). Red: "
    "separatrices (the level H0 = c G^2/2 of the saddle); bold dotted black: the "
    "separatrix theta1 = 0 (l = -phi0 mod pi) that the Hess solutions approach as mu -> 0; "
    "grey: the singular lines L = +-G (J1 = 0, J2) of the charts, each one physical state. "
    "Uniform rotations: 1 about +z (L = G, J1 = J2) and 2 about -z (L = -G, J1 = 0), the "
    "rotations the physical-pendulum motions approach; 3 about +-y (l = 0, pi); 4 about "
    "+-x (l = pi/2, 3 pi/2). Markers: centre (circle), saddle of the chart (cross).")


def _middle(body: RigidBody) -> tuple[str, float]:
    """The middle axis of inertia and its inverse moment."""
    I = {"x": body.a, "y": body.b, "z": body.c}
    axis = sorted(I, key=I.__getitem__)[1]
    vals = sorted(I.values())
    if min(vals[1] - vals[0], vals[2] - vals[1]) <= 1e-12 * vals[2]:
        raise ValueError(
            f"separatrices need three distinct moments of inertia, got A={body.A}, "
            f"B={body.B}, C={body.C}")
    return axis, I[axis]


@checks_body(ranges={"G0": "length"}, closed_form=CLOSED_FORM)
def separatrix_energy(body: RigidBody, G0: float = 1.0) -> float:
    """Energy ``H0 = I_mid G0^2 / 2`` of the separatrix: that of the rotation about the
    middle axis (``c G0^2/2`` when z is the middle axis, as for a Hess body).

    The one owner of the energy level of the separatrices (and of the rotations about
    the middle axis): ``G0 = |G|`` is also the Hess chart's ``J2`` there (Eq. (13) with
    ``L = +-G``); :func:`separatrix_momentum` is the inverse.

    Parameters
    ----------
    body : RigidBody
        The body (its middle inverse moment ``I_mid``).
    G0 : float, default 1.0
        ``|G|`` on the separatrices (> 0).

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> round(separatrix_energy(RigidBody.paper()), 12)
    0.227272727273
    """
    G0 = _positive("G0", G0, maximum=MAX_ACTION)
    return 0.5 * _middle(body)[1] * G0**2


@checks_body(ranges={"h": "energy"}, closed_form=CLOSED_FORM)
def separatrix_momentum(body: RigidBody, h: float) -> float:
    """``|G| = J2 = sqrt(2 h / I_mid)``: the momentum of the separatrices (and of the
    rotations about the middle axis) on the level ``H = h``; the inverse of
    :func:`separatrix_energy`.

    Parameters
    ----------
    body : RigidBody
        The body (its middle inverse moment ``I_mid``).
    h : float
        Energy level ``H0 = h`` (> 0).

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> body = RigidBody.paper()
    >>> separatrix_momentum(body, separatrix_energy(body, 0.7))
    0.7
    """
    h = _positive("h (the energy of the separatrix level)", h)
    return math.sqrt(2.0 * h / _middle(body)[1])


def _s(body: RigidBody, l: NDArray[np.float64]) -> NDArray[np.float64]:
    """``s(l) = a sin^2 l + b cos^2 l``: H0 = (G0^2 s(l) + L^2 (c - s(l)))/2, Eq. (9)."""
    return np.asarray(body.a * np.sin(l) ** 2 + body.b * np.cos(l) ** 2)


Curve = tuple[NDArray[np.float64], NDArray[np.float64], str, bool, str]


def _curves(body: RigidBody, chart: str, action: float, period: float, n: int
            ) -> list[Curve]:
    """Sampled separatrix curves ``(q, p, kind, hess, text)`` of one chart.

    ``H0(l, L) = (G0^2 s(l) + L^2 (c - s(l)))/2`` is quadratic in L, so the level
    ``h = I_mid G0^2/2`` is ``L^2 = G0^2 (I_mid - s(l))/(c - s(l))``. When z is the
    middle axis (``I_mid = c``) this is ``L = +-G0`` (the singular lines) or
    ``s(l) = c``, i.e. ``sin^2 l = (b - c)/(b - a)``: the lines ``l = +-l*`` (mod pi),
    ``l* = |phi0|`` on a Hess body. Otherwise the two curves ``L = +-sqrt(...)`` cross at
    the saddles ``L = 0``.
    """
    axis, I_mid = _middle(body)
    G0 = action
    hess_chart = chart == "hess"
    phi0 = body.phi0 if hess_chart or abs(body.e3) <= 1e-12 else 0.0
    out: list[Curve] = []
    if axis == "z":
        lstar = math.asin(math.sqrt((body.b - body.c) / (body.b - body.a)))
        name = "|phi0|" if body.is_hess else "l*"
        L = np.linspace(-G0, G0, n)
        seen: list[float] = []
        for lv, txt in ((lstar, name), (math.pi - lstar, f"pi - {name}"),
                        (math.pi + lstar, f"pi + {name}"),
                        (2 * math.pi - lstar, f"2 pi - {name}")):
            hess = body.is_hess and abs(math.sin(lv + phi0)) < 1e-9
            if hess_chart:
                t1 = float(np.mod(2.0 * (lv + phi0), period))
                t1 = 0.0 if period - t1 < 1e-12 else t1
                if any(min(abs(t1 - o), period - abs(t1 - o)) < 1e-9 for o in seen):
                    continue
                seen.append(t1)
                named = theta_text(t1, period, body.phi0, None if body.is_hess else lstar)
                out.append((np.full(n, t1), (G0 + L) / 2.0, "separatrix", hess,
                            f"theta1 = {named}"))
                if t1 == 0.0:  # the line theta1 = 0 is also theta1 = period: draw both ends
                    out.append((np.full(n, period), (G0 + L) / 2.0, "separatrix", hess,
                                "theta1 = 2 pi (the line theta1 = 0 again)" if period < 7.0
                                else "theta1 = 4 pi (the line theta1 = 0 again)"))
            else:
                out.append((np.full(n, lv), L, "separatrix", hess, f"l = {txt}"))
        grid = np.linspace(0.0, period, n)
        for sgn in (+1.0, -1.0):
            level = (G0 + sgn * G0) / 2.0 if hess_chart else sgn * G0
            what = ("J1 = J2" if sgn > 0 else "J1 = 0") if hess_chart else (
                "L = G0" if sgn > 0 else "L = -G0")
            out.append((grid, np.full(n, level), "singular line", False,
                        f"{what}: one state, the rotation about {'+' if sgn > 0 else '-'}z"))
        return out
    grid = np.linspace(0.0, period, n)
    l = grid / 2.0 - phi0 if hess_chart else grid
    s = _s(body, l)
    with np.errstate(divide="ignore", invalid="ignore"):
        R = np.clip(G0**2 * (I_mid - s) / (body.c - s), 0.0, G0**2)
    for sgn in (+1.0, -1.0):
        L = sgn * np.sqrt(R)
        out.append((grid, (G0 + L) / 2.0 if hess_chart else L, "separatrix", False,
                    f"L = {'+' if sgn > 0 else '-'}G0 sqrt((I_mid - s(l))/(c - s(l))), "
                    f"s(l) = a sin^2 l + b cos^2 l, middle axis {axis}"))
    return out


@checks_body(ranges={"action": "length", "period": "time", "n": "count"}, closed_form=CLOSED_FORM)
def separatrix_curves(body: RigidBody, chart: str, action: float, period: float,
                    n: int) -> xr.Dataset:
    """The unperturbed separatrices and singular lines of one chart as a dataset.

    The curves of the level ``H0 = I_mid G0^2 / 2`` (:func:`separatrix_energy`) in the
    plane ``(l, L)`` (Eq. (9)) or ``(theta1, J1)`` (Eqs. (13)-(14)).

    Parameters
    ----------
    body : RigidBody
        The body (``mu`` ignored).
    chart : {"andoyer", "hess"}
        Plane ``(l, L)`` or ``(theta1, J1)``.
    action : float
        ``G0 = |G|`` (``J2`` in the Hess chart) of the level.
    period : float
        Period of the chart's angle drawn: ``2 pi``, or ``4 pi`` for the double cover
        of the Hess chart.
    n : int
        Points per curve.

    Returns
    -------
    xarray.Dataset
        Dims ``curve``, ``point``: ``separatrix_<q>``, ``separatrix_<p>`` (the curves),
        ``separatrix_kind`` (``"separatrix"`` or ``"singular line"``),
        ``separatrix_hess`` (1 on the Hess separatrix ``theta1 = 0``),
        ``separatrix_text``; attrs ``separatrix_H0``, ``chart``, ``angle_period``.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> ds = separatrix_curves(RigidBody.paper(), "hess", 1.0, 2 * np.pi, 9)
    >>> sorted(set(ds.separatrix_kind.values.tolist()))
    ['separatrix', 'singular line']
    """
    if not isinstance(chart, str) or chart not in ("andoyer", "hess"):
        raise ValueError(f"chart must be 'andoyer' or 'hess', got {chart!r}")
    qn, pn = ("theta1", "J1") if chart == "hess" else ("l_angle", "L_action")
    curves = _curves(body, chart, action, period, n)
    h = separatrix_energy(body, action)
    ds = xr.Dataset(
        {f"separatrix_{qn}": (("curve", "point"), np.array([c[0] for c in curves])),
         f"separatrix_{pn}": (("curve", "point"), np.array([c[1] for c in curves])),
         "separatrix_kind": (("curve",), np.array([c[2] for c in curves], dtype=str)),
         "separatrix_hess": (("curve",), np.array([c[3] for c in curves])),
         "separatrix_text": (("curve",), np.array([c[4] for c in curves], dtype=str))},
        coords={"curve": np.arange(len(curves)), "point": np.arange(n)})
    ds[f"separatrix_{qn}"].attrs.update(long_name=f"separatrix curve, {qn}",
                                        units="rad")
    ds[f"separatrix_{pn}"].attrs.update(long_name=f"separatrix curve, {pn}", units="1")
    ds["separatrix_kind"].attrs.update(
        long_name="'separatrix' or 'singular line' (part of the level set, one state)")
    ds["separatrix_hess"].attrs.update(
        long_name="1: the separatrix theta1 = 0 (l = -phi0 mod pi) that the Hess solutions "
                  "approach as mu -> 0")
    ds.attrs.update(separatrix_H0=h, chart=chart, angle_period=period)
    return values_from_attrs(ds, SEPARATRIX_LEVEL)


#: The separatrix level ``H0`` as a dataset variable (portraits, separatrix curves).
SEPARATRIX_LEVEL: dict[str, VariableMeta] = {
    "separatrix_H0": ("H_0", "energy of the separatrix level (the saddle's)", "1", "(9)")}


@checks_arguments
def check_grid_size(n: Any, what: str, minimum: int = 8) -> int:
    """A sample count ``n`` of at least ``minimum`` and at most
    :data:`~andoyer.validation.MAX_COUNT` (``ValueError`` naming ``what``).

    Parameters
    ----------
    n : int
        The sample count given.
    what : str
        Its name, for the error message.
    minimum : int, default 8
        The smallest count accepted.
    """
    return integer(what, n, minimum, MAX_COUNT)


@checks_body(ranges={"G0": "length", "n": "count"}, closed_form=CLOSED_FORM)
def separatrix_andoyer(body: RigidBody, G0: float = 1.0, n: int = 401) -> xr.Dataset:
    """The separatrices of (9) in ``(l, L)`` as sampled curves, closed form.

    The level set ``H0 = I_mid G0^2/2`` through the saddles. For a Hess body (z the
    middle axis) it is the four lines ``l = +-phi0 (mod pi)`` and the singular lines
    ``L = +-G0``; ``l = -phi0 (mod pi)`` (``theta1 = 0``) is the one the Hess
    solutions approach as ``mu -> 0`` (``separatrix_hess``).

    Parameters
    ----------
    body : RigidBody
        Three distinct moments.
    G0 : float
        Length of the angular momentum.
    n : int
        Points per curve.

    Returns
    -------
    xarray.Dataset
        Dims ``(curve, point)``: ``separatrix_l_angle``, ``separatrix_L_action``,
        ``separatrix_kind``, ``separatrix_hess``, ``separatrix_text``;
        attrs ``separatrix_H0``.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> ds = separatrix_andoyer(RigidBody.paper(), n=11)
    >>> [str(t) for t in ds.separatrix_text.values[ds.separatrix_hess.values]]
    ['l = pi - |phi0|', 'l = 2 pi - |phi0|']
    """
    G0 = _positive("G0", G0, maximum=MAX_ACTION)
    return separatrix_curves(body, "andoyer", G0, math.tau, check_grid_size(n, "n"))


@checks_body(ranges={"J2": "action", "n": "count"}, closed_form=CLOSED_FORM)
def separatrix_hess(body: RigidBody, J2: float = 1.0, n: int = 401, *,
                    double_cover: bool = False) -> xr.Dataset:
    """The separatrices of the unperturbed Hess-chart system in ``(theta1, J1)``.

    For a Hess body: the lines ``theta1 = 0`` (the Hess one, drawn at both ends of
    ``[0, 2 pi]``) and ``theta1 = 4 phi0`` (mod 2 pi), and the singular lines
    ``J1 = 0``, ``J1 = J2``. Same variables as :func:`separatrix_andoyer` with
    ``theta1``, ``J1``.

    Parameters
    ----------
    body : RigidBody
        A Hess body (or any body with Oz the middle axis).
    J2 : float, default 1.0
        ``J2 = |G|`` of the level.
    n : int, default 401
        Points per curve (>= 8).
    double_cover : bool, default False
        ``theta1`` over ``[0, 4 pi]`` instead of ``[0, 2 pi]``.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> ds = separatrix_hess(RigidBody.paper(), n=11)
    >>> sorted({round(float(q), 6) for q, k in zip(ds.separatrix_theta1[:, 0].values,
    ...         ds.separatrix_kind.values) if k == "separatrix"})
    [0.0, 2.959523, 6.283185]
    """
    J2 = _positive("J2", J2, maximum=MAX_ACTION)
    body.require_planar("the Hess chart")
    period = 2.0 * math.tau if double_cover else math.tau
    return separatrix_curves(body, "hess", J2, period, check_grid_size(n, "n"))




@checks_body(ranges={"h": "energy", "n": "count"}, closed_form=CLOSED_FORM)
def separatrix_on_level(body: RigidBody, h: float, chart: str, n: int = 401, *,
                        double_cover: bool = False) -> xr.Dataset | None:
    """The unperturbed (mu = 0) separatrices that lie on the energy level ``H0 = h``.

    They sit at ``G0 = sqrt(2 h / I_mid)`` (``I_mid`` the middle of ``a, b, c``): the G of
    the rotation about the middle axis on that level. ``chart`` is ``"hess"`` or
    ``"andoyer"``; ``None`` when ``h <= 0`` or two moments are equal (no separatrix).

    Parameters
    ----------
    body : RigidBody
        The body (``mu`` ignored: the unperturbed separatrices).
    h : float
        Energy level ``H0 = h``.
    chart : {"hess", "andoyer"}
        Plane ``(theta1, J1)`` or ``(l, L)``.
    n : int, default 401
        Points per curve (>= 8).
    double_cover : bool, default False
        Hess chart: ``theta1`` over ``[0, 4 pi]`` instead of ``[0, 2 pi]``.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> ds = separatrix_on_level(RigidBody.paper(), 0.25, "hess")
    >>> float(ds.attrs["separatrix_H0"])
    0.25
    """
    h = _finite("h", h)
    if h <= 0.0:
        return None
    try:
        I_mid = 2.0 * separatrix_energy(body, 1.0)
    except ValueError:  # two equal moments: no separatrix
        return None
    G0 = math.sqrt(2.0 * h / I_mid)
    if chart == "hess":
        return separatrix_hess(body, G0, n, double_cover=double_cover)
    if chart == "andoyer":
        return separatrix_andoyer(body, G0, n)
    raise ValueError(f"chart must be 'hess' or 'andoyer', got {chart!r}")
