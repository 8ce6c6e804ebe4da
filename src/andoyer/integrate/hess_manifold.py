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
:func:`propagate_hess_manifold` integrates instead the Euler-Poisson equations restricted
to the manifold, in coordinates that satisfy (3) identically: ``G = s n + G3 e_3`` with
``n = (-e2, e1, 0)`` (so ``e1 G1 + e2 G2 = 0`` for every ``s``), the state
``(s, G3, gamma)`` and the cyclic angle ``theta3 = m`` by quadrature of

    dm/dt = dH/dM = mu ((r, G) - M (r, gamma)) / (G^2 - M^2)

(derived from the Andoyer-Deprit chart: ``dgamma/dI`` is ``N x gamma`` about the node
``N``; checked against the chart field in the tests), which on (3) is
``-mu M (r, gamma) / (G^2 - M^2)``. These variables are regular everywhere, for every
``M``: the orbit passes the Hess chart's singular sets (``L = +-G``, where ``s = 0``
and the sheet ``theta1`` switches between ``0`` and ``2 pi``; ``G = 0`` on the M = 0
librations, where the node is undefined and ``m`` jumps by ``pi``) without leaving the
manifold; the relation holds to round-off (about 1e-17) at every time.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from andoyer.body import RigidBody, checks_body
from andoyer.charts.euler_poisson import momentum_bound
from andoyer.charts.hess import as_hess, from_hess
from andoyer.charts.integrals import INTEGRALS, drift_scale
from andoyer.integrate.api import check_times, check_tolerances
from andoyer.integrate.engines.ivp import solve_dop853
from andoyer.integrate.results import provenance, states_dataset
from andoyer.kernels.dop853.fields import ep_field
from andoyer.validation import real_array

__all__ = ["propagate_hess_manifold", "THETA1_TOL", "METHOD", "G_ZERO_RTOL"]

#: A full Hess-chart point must have ``theta1 = 0 (mod 2 pi)`` within this (radians).
THETA1_TOL = 1e-12
#: The method recorded in the result's attributes.
METHOD = "Euler-Poisson equations restricted to the Hess manifold (3)"
#: A zero of ``s`` with ``|G3| <= G_ZERO_RTOL * momentum_bound`` is a ``G = 0`` passage.
G_ZERO_RTOL = 1e-6



def _manifold_point(body: RigidBody, x0: ArrayLike) -> tuple[float, NDArray[np.float64]]:
    """``(theta1_fixed, (theta2, J1, J2, J3))`` from ``x0`` of shape (4,) or (5,)."""
    arr = real_array("x0", x0)
    if arr.shape == (4,):
        theta1 = 0.0
        rest = arr
    elif arr.shape == (5,):
        if not math.isfinite(arr[0]):
            raise ValueError("x0: theta1 is NaN or infinite")
        # theta1 is 4 pi-periodic; theta1 = 0 and theta1 = 2 pi both lie on (3).
        off = math.remainder(float(arr[0]), math.tau)
        if abs(off) > THETA1_TOL:
            raise ValueError(
                f"x0: theta1 = {arr[0]!r} is not on the Hess manifold theta1 = 0 (mod 2 pi) "
                f"(off by {off:.3g} > {THETA1_TOL:g}); the reduced equations only hold "
                "there -- use propagate(..., chart='hess') for other states")
        on_zero = abs(math.remainder(float(arr[0]), 2 * math.tau)) <= THETA1_TOL
        theta1 = 0.0 if on_zero else math.tau
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


def _onto_casimirs(y: NDArray[np.float64], M: float, scale: float
                   ) -> tuple[NDArray[np.float64], float]:
    """Output states moved onto ``|gamma| = 1``, ``(G, gamma) = M`` (the Casimirs that the
    chart integration held exactly); returns them and the largest change of gamma.

    gamma keeps its direction about G: its component along G becomes ``M / |G|`` and
    its perpendicular part is rescaled to length ``sqrt(1 - M^2 / |G|^2)``. Not where
    ``|G| <= G_ZERO_RTOL * scale`` (there G gives no direction; |gamma| only).
    """
    G, gamma = y[:, :3], y[:, 3:]
    Gn = np.linalg.norm(G, axis=-1)
    ok = Gn > G_ZERO_RTOL * scale
    u = G / np.where(ok, Gn, 1.0)[:, None]
    par = np.einsum("ij,ij->i", gamma, u)
    perp = gamma - par[:, None] * u
    pn = np.linalg.norm(perp, axis=-1)
    c = np.clip(M / np.where(ok, Gn, 1.0), -1.0, 1.0)
    target = c[:, None] * u + (np.sqrt(1.0 - c * c) / np.where(pn > 0, pn, 1.0))[:, None] * perp
    new = np.where((ok & (pn > 0))[:, None], target,
                   gamma / np.linalg.norm(gamma, axis=-1)[:, None])
    out = np.concatenate([G, new], axis=-1)
    return out, float(np.max(np.abs(new - gamma), initial=0.0))


@checks_body(ranges={"rtol": "tolerance", "atol": "tolerance"})
def propagate_hess_manifold(body: RigidBody, x0: ArrayLike, t: ArrayLike, *,
                            rtol: float = 1e-12, atol: float = 1e-12,
                            singular_margin: float = 1e-9) -> xr.Dataset:
    """Integrate a Hess-solution orbit on the manifold ``theta1 = 0 (mod 2 pi)``, any ``M``.

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
        For ``M != 0``: stop (``ValueError``) where ``G^2 - M^2 < singular_margin G^2``
        (the angular momentum vertical, where the node and ``dm/dt`` are undefined).

    Returns
    -------
    xarray.Dataset
        Dims ``("time",)`` (one orbit, no ``orbit`` dimension). Holds the Euler-Poisson
        state ``G1 .. gamma3`` (``gamma`` put back on ``|gamma| = 1``,
        ``(G, gamma) = M`` at the output times; the largest correction is the attr
        ``casimir_correction``, 6e-11 over ``t = 1e4`` at 1e-12), the Andoyer-Deprit and
        Hess-chart coordinates of it
        (``theta1`` exactly ``0`` or ``2 pi``: the sheet, switching at each ``L = +-G``
        passage), the cyclic angle ``theta3`` (unreduced, from 0 at ``t[0]``, with the
        jump ``pi`` at each ``G = 0`` passage), the integrals ``H``, ``area``,
        ``geometric``, ``H_drift`` (relative to ``max(|H(t0)|, mu)``), ``hess_relation``
        ``= e1 G1 + e2 G2``, the passage counts ``sheet_switches`` and
        ``g_zero_passages`` with their times in attrs. Attrs: provenance, ``method``,
        ``engine``, tolerances, ``theta1`` (the initial sheet).

    Raises
    ------
    ValueError
        Not a Hess body; ``x0`` off the manifold, of a wrong shape or on the chart's
        singular set; ``M != 0`` and the angular momentum reaching the vertical.

    Examples
    --------
    An orbit with ``M = 0.2`` that passes ``L = +-G`` (the Hess chart's singular set)
    several times:

    >>> from andoyer import RigidBody
    >>> ds = propagate_hess_manifold(RigidBody.paper(), [1.0, 0.4, 1.0, 0.2],
    ...                              [0.0, 100.0, 200.0])
    >>> bool(abs(ds.hess_relation).max() < 1e-14), bool(abs(ds.H_drift).max() < 1e-11)
    (True, True)
    >>> int(ds.sheet_switches) > 0
    True
    """
    body.require_hess("propagate_hess_manifold")
    rtol, atol = check_tolerances(rtol, atol)
    times = check_times(t)
    if not (math.isfinite(singular_margin) and 0.0 < singular_margin < 1.0):
        raise ValueError(f"singular_margin must lie in (0, 1), got {singular_margin!r}")
    theta1, z0 = _manifold_point(body, x0)
    x_start = np.concatenate(([theta1], z0))
    y_start = from_hess(body, x_start)
    a, b, c, mu, e1, e2, e3 = body.params
    n1, n2 = -e2, e1  # n = (-e2, e1, 0): G = s n + G3 e_3 satisfies (3) for every s
    M = float(z0[3])
    s0 = n1 * y_start[0] + n2 * y_start[1]

    def rhs(_t: float, z: NDArray[np.float64]) -> NDArray[np.float64]:
        s_, G3, g1, g2, g3 = z[0], z[1], z[2], z[3], z[4]
        G1, G2 = s_ * n1, s_ * n2
        f = ep_field(G1, G2, G3, g1, g2, g3, a, b, c, mu, e1, e2, e3)
        GG = s_ * s_ + G3 * G3
        Mz = G1 * g1 + G2 * g2 + G3 * g3
        den = GG - Mz * Mz
        # dm/dt = mu ((r, G) - M (r, gamma)) / (G^2 - M^2), (r, G) = 0 on (3); at M = 0
        # it vanishes identically (m jumps by pi at G = 0, added below).
        dm = 0.0 if M == 0.0 else -mu * Mz * (e1 * g1 + e2 * g2) / den
        return np.array([n1 * f[0] + n2 * f[1], f[2], f[3], f[4], f[5], dm])

    def vertical(_t: float, z: NDArray[np.float64]) -> float:
        GG = z[0] ** 2 + z[1] ** 2
        Mz = z[0] * (n1 * z[2] + n2 * z[3]) + z[1] * z[4]
        return float(GG - Mz * Mz - singular_margin * GG) if M != 0.0 else 1.0

    def sheet(_t: float, z: NDArray[np.float64]) -> float:
        return float(z[0])

    vertical.terminal = True  # type: ignore[attr-defined]
    z_start = np.array([s0, y_start[2], *y_start[3:], 0.0])
    sol = solve_dop853(rhs, times, z_start, rtol, atol, events=[vertical, sheet])
    if sol.status == 1:
        raise ValueError(
            f"the Hess-manifold orbit brought the angular momentum to the vertical "
            f"(|M| = G, M = {M:.6g}) at t = {sol.t_events[0][0]:.6g}, where the node and "
            "the cyclic angle theta3 are undefined; integrate this orbit with propagate(), "
            "which does not need theta3")
    s_t, G3_t, g1_t, g2_t, g3_t, m_t = sol.y
    y = np.stack([s_t * n1, s_t * n2, G3_t, g1_t, g2_t, g3_t], axis=-1)
    y, casimir_correction = _onto_casimirs(y, M, float(momentum_bound(body, y_start)))
    # Zeros of s: the sheet theta1 switches (L = +-G); where G3 vanishes too it is a
    # G = 0 passage, where the node of the invariant plane flips and m jumps by pi.
    scale = float(momentum_bound(body, y_start))
    t_sw = np.asarray(sol.t_events[1], dtype=float)
    y_sw = np.asarray(sol.y_events[1], dtype=float).reshape(-1, 6)
    zero = np.abs(y_sw[:, 1]) <= G_ZERO_RTOL * scale
    t_zero = t_sw[zero]
    n_sw = np.searchsorted(t_sw, times, side="left")
    n_zero = np.searchsorted(t_zero, times, side="left")
    theta1_t = np.where(n_sw % 2 == 0, theta1, math.tau - theta1)
    theta3 = m_t + math.pi * n_zero
    attrs: dict[str, Any] = provenance(
        body, engine="scipy-DOP853", method=METHOD, rtol=rtol, atol=atol, theta1=theta1,
        singular_margin=singular_margin, casimir_correction=casimir_correction,
        sheet_switch_times=t_sw.tolist(), g_zero_passage_times=t_zero.tolist(),
        equations="Euler-Poisson equations (1) restricted to the Hess manifold (3), "
                  "G = s (-e2, e1, 0) + G3 e_3; theta3 by quadrature of dH/dM")
    ds = states_dataset(body, y, ("time",), {"time": times}, attrs,
                        extra={"theta3": (("time",), theta3),
                               "sheet_switches": ((), t_sw.size),
                               "g_zero_passages": ((), t_zero.size)})
    ds["theta1"].values[...] = theta1_t
    ds["theta3"].attrs.update(symbol="\\theta_3", long_name="Hess-chart cyclic angle m, "
                              "by quadrature from 0 at t[0]", equation="(14)", units="rad")
    ds["sheet_switches"].attrs.update(long_name="passages through L = +-G (theta1 switches "
                                      "between 0 and 2 pi)", units="1")
    ds["g_zero_passages"].attrs.update(long_name="passages through G = 0 (m jumps by pi)",
                                       units="1")
    ds["hess_relation"] = (ds.G1 * body.e1 + ds.G2 * body.e2)
    ds["hess_relation"].attrs.update(symbol="(G, r)", long_name="Hess invariant relation "
                                     "e1 G1 + e2 G2", equation="(3)", units="1")
    H0 = float(ds.H.isel(time=0))
    scale = float(drift_scale("H", body, np.zeros(6), H0))
    ds["H_drift"] = (ds.H - H0) / (scale if scale > 0 else 1.0)
    ds["H_drift"].attrs.update(units="1", long_name="drift of H since t[0]",
                               relative_to=INTEGRALS["H"].scale_name)
    ds.time.attrs.update(units="body time units", long_name="time")
    return ds
