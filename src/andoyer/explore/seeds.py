"""Seeds of the explorer: the states a click on the section plane starts orbits from
(every root of the missing action above the point, :func:`seed`), and a seed's state in
the three charts for the side panel (:func:`initial_charts`)."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from andoyer.charts.andoyer_deprit import from_andoyer
from andoyer.charts.euler_poisson import STATE, energy
from andoyer.charts.hess import from_hess
from andoyer.dynamics import vector_field
from andoyer.explore.state import OutsideRegionError, Seed, Settings
from andoyer.validation import finite as _finite

__all__ = ["seed", "initial_charts"]


def seed(settings: Settings, x: float, y: float) -> list[Seed]:
    """States through the plane point ``(x, y)`` on ``H = h``: the missing action solved.

    Parameters
    ----------
    settings : Settings
    x, y : float
        ``(theta1, J1)`` on a ``theta2`` section, ``(l, L)`` on a ``g`` section; the
        angle is taken mod :attr:`Settings.x_period`.

    Returns
    -------
    list of Seed
        One seed, or one per solution with ``settings.root == "all"``, ascending.

    Raises
    ------
    OutsideRegionError
        When no admissible action solves ``H = h`` above the point (outside the
        accessible region, or within :data:`andoyer.integrate.fill.SINGULAR_MARGIN` of
        the chart's singular set).

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> from andoyer.explore.state import default_energy
    >>> s = Settings(RigidBody.paper(), default_energy(RigidBody.paper()), section="g=0")
    >>> (sd,) = seed(s, 0.3, 0.3)
    >>> round(sd.action, 12), sd.residual <= 1e-12
    (1.0, True)
    """
    from andoyer.integrate.fill import section_roots

    x, y = _finite("x", x), _finite("y", y)
    p = settings.plane
    x = float(np.mod(x, settings.x_period))
    sec = settings.section
    if p.chart == "hess" and not y > 0.0:
        raise OutsideRegionError(
            f"J1 = (G + L)/2 = {y:.6g} is outside the Hess chart (J1 > 0); click above the "
            "axis J1 = 0")
    roots = section_roots(settings.body, settings.h, settings.M, (sec.coord, sec.value),
                          [x], [y])[0]
    if roots.size == 0:
        raise OutsideRegionError(
            f"({p.text[0]}, {p.text[1]}) = ({x:.6g}, {y:.6g}) is outside the accessible "
            f"region of H = {settings.h:.10g}, M = {settings.M:.6g}: no {p.text[2]} puts "
            f"this point on the energy level (or it lies on the chart's singular set); "
            f"click inside the boundary")
    pick = {"smallest": [0], "largest": [roots.size - 1],
            "all": list(range(roots.size))}[settings.root]
    out = []
    for k in pick:
        pt = np.array([x, sec.value, y, roots[k], settings.M])
        y0 = from_hess(settings.body, pt) if p.chart == "hess" else from_andoyer(pt)
        rate = float(vector_field(settings.body, pt, p.chart)[1])
        scale = max(abs(settings.h), settings.body.mu, np.finfo(float).tiny)
        res = float(abs(energy(settings.body, y0) - settings.h) / scale)
        out.append(Seed(x, y, float(roots[k]), k, int(roots.size), y0, pt, rate, res))
    return out


def initial_charts(settings: Settings, y0: NDArray[np.float64]) -> dict[str, dict[str, float]]:
    """The state ``y0`` in the three charts: Euler-Poisson, Andoyer-Deprit (5)-(6) and,
    for ``e3 = 0``, Hess (14). Angles in ``[0, 2 pi)`` (theta1 in ``[0, 4 pi)``); NaN
    where the state is on the chart's singular set and the angle is undefined
    (:func:`~andoyer.charts.andoyer_deprit.undefined_as_nan`).

    Parameters
    ----------
    settings : Settings
        The body (its charts).
    y0 : ndarray, shape (6,)
        The Euler-Poisson state.
    """
    from andoyer.charts.andoyer_deprit import to_andoyer, undefined_as_nan
    from andoyer.charts.hess import to_hess

    x, flags = to_andoyer(y0, with_mask=True)
    x = undefined_as_nan(x, flags)
    out = {"Euler-Poisson": dict(zip(STATE, map(float, y0), strict=True)),
           "Andoyer-Deprit": dict(zip(("l", "g", "L", "G", "M"), map(float, x), strict=True))}
    if abs(settings.body.e3) <= 1e-12:
        xh = to_hess(settings.body, y0, andoyer=(x, flags))  # NaN where (14) meets one
        out["Hess"] = dict(zip(("theta1", "theta2", "J1", "J2", "J3"), map(float, xh),
                               strict=True))
    return out
