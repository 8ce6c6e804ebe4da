"""Reduced integration on the Hess manifold ``theta1 = 0`` (the Hess invariant relation).

On a Hess body the invariant relation (3), ``e1 G1 + e2 G2 = 0``, reads
``sqrt(J1 (J2 - J1)) sin(theta1 / 2) = 0`` in the Hess chart (14): the Hess solution is
``theta1 = 0 (mod 2 pi)``, and the Hess-chart field has ``dtheta1/dt = 0`` there for
every value ``M = J3`` of the area integral.

In the full Euler-Poisson flow this manifold is invariant but not asymptotically
stable: ``(G, r) = e1 G1 + e2 G2`` obeys exactly

    d(G, r)/dt = -branch * sigma * G3 * (G, r),   sigma = sqrt((b - c)(c - a)),

so round-off off the manifold is amplified by ``exp(-branch sigma int G3 dt)`` and a 6-D
orbit started on the manifold leaves it after a few thousand time units.
:func:`propagate_hess_manifold` integrates instead only ``(theta2, J1, J2)`` -- with
``theta1`` held fixed and ``J3 = M`` constant -- and the cyclic angle ``theta3`` by
quadrature, with the generated Hess-chart field (:func:`andoyer.kernels._generated.
hess_field`, Numba-compiled in :mod:`andoyer.kernels.numba`) evaluated at the fixed
``theta1``. The relation (3) then holds to the
round-off of the chart map (about 1e-16), at every time.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from andoyer.body import RigidBody
from andoyer.charts.hess import as_hess, from_hess
from andoyer.integrate.api import _check_times, _check_tolerances
from andoyer.integrate.results import provenance, states_dataset
from andoyer.kernels.numba import hess_field

__all__ = ["propagate_hess_manifold", "THETA1_TOL", "METHOD"]

#: A full Hess-chart point must have ``theta1 = 0 (mod 2 pi)`` within this (radians).
THETA1_TOL = 1e-12
#: The method recorded in the result's attributes.
METHOD = "reduced Hess-chart equations on theta1 = 0"

_TWO_PI = 2.0 * math.pi
_FOUR_PI = 4.0 * math.pi


def _manifold_point(body: RigidBody, x0: ArrayLike) -> tuple[float, NDArray[np.float64]]:
    """``(theta1_fixed, (theta2, J1, J2, J3))`` from ``x0`` of shape (4,) or (5,)."""
    arr = np.asarray(x0, dtype=float)
    if arr.shape == (4,):
        theta1 = 0.0
        rest = arr
    elif arr.shape == (5,):
        if not math.isfinite(arr[0]):
            raise ValueError("x0: theta1 is NaN or infinite")
        # theta1 is 4 pi-periodic; theta1 = 0 and theta1 = 2 pi both lie on (3).
        off = math.remainder(float(arr[0]), _TWO_PI)
        if abs(off) > THETA1_TOL:
            raise ValueError(
                f"x0: theta1 = {arr[0]!r} is not on the Hess manifold theta1 = 0 (mod 2 pi) "
                f"(off by {off:.3g} > {THETA1_TOL:g}); the reduced equations only hold "
                "there -- use propagate(..., chart='hess') for other states")
        theta1 = 0.0 if abs(math.remainder(float(arr[0]), _FOUR_PI)) <= THETA1_TOL else _TWO_PI
        rest = arr[1:]
    else:
        raise ValueError(
            "x0 must be (theta2, J1, J2, J3), shape (4,), or a full Hess-chart point "
            f"(theta1, theta2, J1, J2, J3) with theta1 = 0, shape (5,); got shape {arr.shape}")
    full = as_hess(np.concatenate(([theta1], rest)), "x0")
    J1, J2, J3 = full[2], full[3], full[4]
    if not (J1 > 0.0 and J1 < J2 and abs(J3) < J2):
        raise ValueError(
            f"x0 = (J1, J2, J3) = ({J1:.6g}, {J2:.6g}, {J3:.6g}) lies on the singular set "
            "of the Hess chart (J1 = 0, J1 = J2 or |J3| = J2); use propagate(), which "
            "integrates the regular Euler-Poisson variables")
    return theta1, full[1:].copy()


def propagate_hess_manifold(body: RigidBody, x0: ArrayLike, t: ArrayLike, *,
                            rtol: float = 1e-12, atol: float = 1e-12,
                            singular_margin: float = 1e-9) -> xr.Dataset:
    """Integrate a Hess-solution orbit with the reduced equations on ``theta1 = 0``.

    Parameters
    ----------
    body : RigidBody
        A Hess body (:attr:`RigidBody.is_hess`).
    x0 : array_like, shape (4,) or (5,)
        ``(theta2, J1, J2, J3)``, taken with ``theta1 = 0``; or a full Hess-chart point
        ``(theta1, theta2, J1, J2, J3)`` whose ``theta1`` is ``0 (mod 2 pi)`` within
        :data:`THETA1_TOL` (``theta1 = 2 pi (mod 4 pi)``, the other sheet of the double
        cover, is kept as ``2 pi``: it is also on the manifold). It must lie strictly
        inside the chart: ``0 < J1 < J2``, ``|J3| < J2``.
    t : array_like, shape (k,)
        Output times, strictly increasing; ``t[0]`` is the initial time.
    rtol, atol : float
        Tolerances of scipy's DOP853.
    singular_margin : float
        Stop (``ValueError``) when ``min(J1, J2 - J1, J2 - |J3|) / J2`` or
        ``J2 / J2(t0)`` falls below this.

    Returns
    -------
    xarray.Dataset
        Dims ``("time",)`` (one orbit, no ``orbit`` dimension). Holds the Euler-Poisson
        state ``G1 .. gamma3`` (through :func:`andoyer.charts.hess.from_hess`), the
        Andoyer-Deprit coordinates, the Hess-chart coordinates as integrated
        (``theta1`` exactly the fixed value, ``theta2`` reduced to ``[0, 2 pi)``), the
        cyclic angle ``theta3`` (unreduced, from 0 at ``t[0]``), the integrals
        ``H``, ``area``, ``geometric``, ``H_drift`` (relative to ``|H(t0)|``) and
        ``hess_relation`` ``= e1 G1 + e2 G2`` of the Euler-Poisson state. Attrs:
        provenance (body, version), ``method``, ``engine``, tolerances, ``theta1``.

    Raises
    ------
    ValueError
        Not a Hess body; ``x0`` off the manifold, of a wrong shape or on the chart's
        singular set; the orbit reaching the singular set (e.g. a Hess libration through
        ``G = 0``, or ``G`` passing along the body axis 3): use
        :func:`andoyer.integrate.api.propagate` for such orbits.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> ds = propagate_hess_manifold(RigidBody.paper(), [1.0, 0.4, 1.0, 0.2], [0, 1, 2])
    >>> bool(abs(ds.hess_relation).max() < 1e-14)
    True
    """
    from scipy.integrate import solve_ivp

    if not isinstance(body, RigidBody):
        raise ValueError(f"body must be a RigidBody, got {type(body).__name__}")
    if not body.is_hess:
        raise ValueError(
            "propagate_hess_manifold needs a Hess body: the Hess conditions (2) "
            "A > C > B, e3 = 0 and (c - b) e1^2 = (a - c) e2^2 must hold (build it with "
            f"RigidBody.hess(A, B, C, mu)); got A={body.A}, B={body.B}, C={body.C}, "
            f"r={body.r}")
    rtol, atol = _check_tolerances(rtol, atol)
    times = _check_times(t)
    if not (math.isfinite(singular_margin) and 0.0 < singular_margin < 1.0):
        raise ValueError(f"singular_margin must lie in (0, 1), got {singular_margin!r}")
    theta1, z0 = _manifold_point(body, x0)
    theta2_0, J1_0, J2_0, J3 = (float(v) for v in z0)
    a, b, c, mu, *_ = body.params
    phi0 = body.phi0

    def rhs(_t: float, z: NDArray[np.float64]) -> NDArray[np.float64]:
        f = hess_field(theta1, z[0], z[1], z[2], J3, a, b, c, mu, phi0)
        # d(theta2, J1, J2, theta3)/dt; dtheta1/dt = f[0] vanishes on theta1 = 0 (mod 2pi).
        return np.array([f[1], f[2], f[3], f[5]], dtype=float)

    def distance(_t: float, z: NDArray[np.float64]) -> float:
        J1, J2 = z[1], z[2]
        if not J2 > 0.0:
            return -1.0
        return float(min(J1 / J2, (J2 - J1) / J2, (J2 - abs(J3)) / J2, J2 / J2_0)
                     - singular_margin)

    distance.terminal = True  # type: ignore[attr-defined]
    sol = solve_ivp(rhs, (times[0], times[-1]), np.array([theta2_0, J1_0, J2_0, 0.0]),
                    method="DOP853", t_eval=times, rtol=rtol, atol=atol, events=distance,
                    dense_output=False)
    if sol.status == 1 or (sol.status == -1 and "step size" in (sol.message or "")):
        where = sol.t_events[0][0] if sol.status == 1 else sol.t[-1]
        raise ValueError(
            f"the Hess-manifold orbit reached the singular set of the Hess chart at "
            f"t = {where:.6g} (J1 -> 0, J1 -> J2, J2 -> |J3| or J2 = G -> 0; e.g. a Hess "
            "libration passing through G = 0, or G passing along body axis 3); the reduced "
            "equations do not hold there -- integrate this orbit with propagate(), which "
            "uses the regular Euler-Poisson variables")
    if not sol.success:
        raise RuntimeError(f"integration failed: {sol.message}")
    theta2, J1, J2, theta3 = sol.y
    n = times.size
    x = np.stack([np.full(n, theta1), theta2, J1, J2, np.full(n, J3)], axis=-1)
    y = from_hess(body, x)
    attrs: dict[str, Any] = provenance(
        body, engine="scipy-DOP853", method=METHOD, rtol=rtol, atol=atol, theta1=theta1,
        singular_margin=singular_margin,
        equations="Hess-chart canonical equations (16) restricted to theta1 = "
                  f"{'0' if theta1 == 0.0 else '2 pi'}, J3 = M constant; theta3 by quadrature")
    ds = states_dataset(body, y, ("time",), {"time": times}, attrs,
                        extra={"theta3": (("time",), theta3)})
    # The chart coordinates are those integrated (to_hess(from_hess(x)) would give
    # theta1 = 4 pi - 1e-16 for a round-off below 0).
    for name, val in (("theta1", x[:, 0]), ("theta2", np.mod(theta2, _TWO_PI)),
                      ("J1", J1), ("J2", J2), ("J3", x[:, 4])):
        ds[name].values[...] = val
    ds["theta3"].attrs.update(symbol="\\theta_3", long_name="Hess-chart cyclic angle m, "
                              "by quadrature from 0 at t[0]", equation="(14)", units="rad")
    ds["hess_relation"] = (ds.G1 * body.e1 + ds.G2 * body.e2)
    ds["hess_relation"].attrs.update(symbol="(G, r)", long_name="Hess invariant relation "
                                     "e1 G1 + e2 G2", equation="(3)", units="1")
    H0 = ds.H.isel(time=0)
    ds["H_drift"] = (ds.H - H0) / (abs(H0) if float(abs(H0)) > 0 else 1.0)
    ds["H_drift"].attrs.update(units="1", long_name="drift of H since t[0]")
    ds.time.attrs.update(units="body time units", long_name="time")
    return ds
