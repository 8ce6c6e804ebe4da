"""Hess chart ``x = (theta1, theta2, J1, J2, J3)``, the canonical change (14)-(15) of [1]_.

Generating function ``F2 = 2 J1 (l + phi0) + J2 (g - l - phi0) + m J3`` gives

    theta1 = 2 (l + phi0),  theta2 = g - l - phi0,  theta3 = m,
    J1 = (G + L)/2,         J2 = G,                 J3 = M,

with ``phi0`` the angle of the centre of mass in the G1-G2 plane
(``e1 = cos phi0, e2 = sin phi0``, Eq. (11)). The Hess invariant relation (3) reads
``sqrt(J1 (J2 - J1)) sin(theta1/2) = 0``: the Hess solution is ``theta1 = 0 (mod 2 pi)``.

Periodicity of theta1
---------------------
``l`` runs over ``[0, 2 pi)``, so ``theta1`` runs over ``[0, 4 pi)``: this chart is a
double cover in ``theta1`` and :func:`to_hess` returns ``theta1`` in ``[0, 4 pi)``
so that :func:`from_hess` is its exact inverse. The Hamiltonian is 4 pi-periodic in
theta1 when ``M != 0`` (it holds ``sin(theta1/2)``); on ``M = 0`` it is
2 pi-periodic, and ``theta1`` and ``theta1 + 2 pi`` are the two states related by the
symmetry ``(G1, G2, gamma3) -> -(G1, G2, gamma3)``; portraits may reduce mod 2 pi.

Singular set
------------
``J1 = 0`` (``L = -G``) and ``J1 = J2`` (``L = G``): whole lines of theta1 map to one
physical state; ``|J3| = J2``; ``J2 = 0``. Flags as in
:class:`andoyer.charts.andoyer_deprit.Singular`.

The chart needs ``e3 = 0`` (the centre of mass in the G1-G2 plane) to define phi0;
it is canonical for any such body and turns (3) into the line above when the body is
a Hess body.

References
----------
.. [1] V. V. Kyrychenko, "Andoyer-Deprit variables use to the Hess gyroscope phase
   trajectories exploring".
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any, Literal, overload

import numpy as np
from numpy.typing import ArrayLike, NDArray

from andoyer.body import checks_body
from andoyer.charts.andoyer_deprit import (
    SINGULAR_RTOL,
    rotation_chain_expr,
    to_andoyer,
    warn_singular,
)
from andoyer.charts.euler_poisson import as_state
from andoyer.validation import real_array

if TYPE_CHECKING:
    from andoyer.body import RigidBody

__all__ = ["COORDS", "hess_to_andoyer_expr", "andoyer_to_hess_expr", "hess_to_ep_expr",
           "to_hess", "from_hess"]

#: Order of the Hess-chart coordinates (theta3 = m is cyclic and not part of the chart).
COORDS = ("theta1", "theta2", "J1", "J2", "J3")

FOUR_PI = 4.0 * np.pi


def hess_to_andoyer_expr(theta1: Any, theta2: Any, J1: Any, J2: Any, J3: Any,
                         phi0: Any) -> tuple[Any, Any, Any, Any, Any]:
    """Eq. (15): ``(theta1, theta2, J1, J2, J3) -> (l, g, L, G, M)``, written once.

    Parameters
    ----------
    theta1, theta2, J1, J2, J3 : number, array or sympy.Expr
        Hess-chart coordinates (Eq. (13)).
    phi0 : number or sympy.Expr
        The body's ``phi0`` (rad).
    """
    l = theta1 / 2 - phi0
    g = theta2 + theta1 / 2
    return l, g, 2 * J1 - J2, J2, J3


def andoyer_to_hess_expr(l: Any, g: Any, L: Any, G: Any, M: Any,
                         phi0: Any) -> tuple[Any, Any, Any, Any, Any]:
    """Eq. (14): ``(l, g, L, G, M) -> (theta1, theta2, J1, J2, J3)`` (angles unreduced).

    Parameters
    ----------
    l, g, L, G, M : number, array or sympy.Expr
        Andoyer-Deprit coordinates (Eq. (7)).
    phi0 : number or sympy.Expr
        The body's ``phi0`` (rad).
    """
    return 2 * (l + phi0), g - l - phi0, (G + L) / 2, G, M


def hess_to_ep_expr(theta1: Any, theta2: Any, J1: Any, J2: Any, J3: Any, phi0: Any, *,
                    sin: Any, cos: Any, sqrt: Any) -> tuple[Any, ...]:
    """``(theta1, theta2, J1, J2, J3) -> (G1, G2, G3, gamma1, gamma2, gamma3)``.

    Eq. (15) composed with (5)-(6), with ``G^2 - L^2 = 4 J1 (J2 - J1)`` taken exactly so
    that the map keeps full relative accuracy near ``J1 = 0`` and ``J1 = J2``.

    Parameters
    ----------
    theta1, theta2, J1, J2, J3 : number, array or sympy.Expr
        Hess-chart coordinates (Eq. (13)).
    phi0 : number or sympy.Expr
        The body's ``phi0`` (rad).
    sin, cos, sqrt : callable
        The functions to use (NumPy's or SymPy's).
    """
    l, g, L, G, M = hess_to_andoyer_expr(theta1, theta2, J1, J2, J3, phi0)
    return rotation_chain_expr(l, g, G, L / G, 2 * sqrt(J1 * (J2 - J1)) / G,
                               M / G, sqrt((G - M) * (G + M)) / G, sin=sin, cos=cos)


def as_hess(x: ArrayLike, name: str = "x") -> NDArray[np.float64]:
    """Validate Hess-chart coordinates ``(..., 5)``.

    Requires ``J2 > 0``, ``0 <= J1 <= J2``, ``|J3| <= J2`` (round-off excesses clipped).
    """
    arr = real_array(name, x, copy=True)
    if arr.ndim == 0 or arr.shape[-1] != 5:
        raise ValueError(f"{name} must have shape (..., 5) = (theta1, theta2, J1, J2, J3), "
                         f"got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} contains NaN or infinity")
    J1, J2, J3 = arr[..., 2], arr[..., 3], arr[..., 4]
    if np.any(J2 <= 0.0):
        raise ValueError(f"{name}: J2 = G must be > 0 (the chart is singular at G = 0)")
    tol = SINGULAR_RTOL * J2
    if np.any(J1 < -tol) or np.any(J1 > J2 + tol):
        raise ValueError(f"{name}: J1 = (G + L)/2 must lie in [0, J2]; "
                         f"got J1 in [{J1.min():.6g}, {J1.max():.6g}]")
    if np.any(np.abs(J3) > J2 + tol):
        raise ValueError(f"{name}: |J3| = |M| must not exceed J2 = G")
    arr[..., 2] = np.clip(J1, 0.0, J2)
    arr[..., 4] = np.clip(J3, -J2, J2)
    return arr


@checks_body
def from_hess(body: RigidBody, x: ArrayLike, *, name: str = "x") -> NDArray[np.float64]:
    """Euler-Poisson state from Hess-chart coordinates, Eq. (15) then (5)-(6).

    Parameters
    ----------
    body : RigidBody
        Supplies ``phi0`` (needs ``e3 = 0``).
    x : array_like, shape (..., 5)
        ``(theta1, theta2, J1, J2, J3)``, ``J2 > 0``, ``0 <= J1 <= J2``, ``|J3| <= J2``.
    name : str, default "x"
        The argument's name in error messages (a caller passes its own).

    Returns
    -------
    y : ndarray, shape (..., 6)

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> body = RigidBody.paper()
    >>> x = [0.5, 2.0, 0.3, 1.0, 0.1]
    >>> bool(np.allclose(to_hess(body, from_hess(body, x)), x))
    True
    """
    arr = as_hess(x, name)
    args = [*np.moveaxis(arr, -1, 0), body.phi0]
    cols = hess_to_ep_expr(*args, sin=np.sin, cos=np.cos, sqrt=np.sqrt)
    return np.stack(np.broadcast_arrays(*cols), axis=-1)


@overload
@checks_body
def to_hess(body: RigidBody, y: ArrayLike, *, with_mask: Literal[False] = ...,
            andoyer: tuple[NDArray[np.float64], NDArray[np.int_]] | None = ...
            ) -> NDArray[np.float64]: ...
@overload
@checks_body
def to_hess(body: RigidBody, y: ArrayLike, *, with_mask: Literal[True],
            andoyer: tuple[NDArray[np.float64], NDArray[np.int_]] | None = ...
            ) -> tuple[NDArray[np.float64], NDArray[np.int_]]: ...
@checks_body
def to_hess(body: RigidBody, y: ArrayLike, *, with_mask: bool = False,
            andoyer: tuple[NDArray[np.float64], NDArray[np.int_]] | None = None
            ) -> NDArray[np.float64] | tuple[NDArray[np.float64], NDArray[np.int_]]:
    """Hess-chart coordinates of Euler-Poisson states, Eq. (14).

    ``theta1`` in ``[0, 4 pi)``, ``theta2`` in ``[0, 2 pi)`` (see the module notes).
    ``J1 = (G + G3)/2`` is computed as ``(G1^2 + G2^2) / (2 (G - G3))`` when
    ``G3 < 0`` so that it keeps full relative accuracy as ``J1 -> 0`` (the
    heteroclinic orbits approach ``J1 = 0``).

    Parameters
    ----------
    body : RigidBody
        Supplies ``phi0``; needs ``e3 = 0``.
    y : array_like, shape (..., 6)
    with_mask : bool
        Also return the singular flags (conventions of the Andoyer-Deprit chart).
    andoyer : tuple of ndarray, optional
        ``to_andoyer(y, with_mask=True)`` when the caller has it already (the Hess chart
        is computed through the Andoyer-Deprit one; a dataset needs both).
    """
    arr = as_state(y)
    phi0 = body.phi0
    if andoyer is not None and not (isinstance(andoyer, tuple) and len(andoyer) == 2):
        raise ValueError("andoyer must be the pair (x, flags) of to_andoyer(y, "
                         f"with_mask=True), got {type(andoyer).__name__}")
    x, flags = to_andoyer(arr, with_mask=True) if andoyer is None else andoyer
    l, g, L, G, M = np.moveaxis(x, -1, 0)
    theta1, theta2, J1, J2, J3 = andoyer_to_hess_expr(l, g, L, G, M, phi0)
    rho = np.hypot(arr[..., 0], arr[..., 1])
    with np.errstate(divide="ignore", invalid="ignore"):
        J1 = np.where(L < 0.0, rho**2 / np.where(G - L > 0, 2.0 * (G - L), 1.0), J1)
    theta1 = np.mod(theta1, FOUR_PI)
    theta2 = np.mod(theta2, math.tau)
    out = np.stack(np.broadcast_arrays(theta1, theta2, J1, J2, J3), axis=-1)
    out[..., 0] = np.where(out[..., 0] >= FOUR_PI, 0.0, out[..., 0])
    out[..., 1] = np.where(out[..., 1] >= math.tau, 0.0, out[..., 1])
    if with_mask:
        return out, flags
    if andoyer is None:  # a caller that passes the flags has them already
        warn_singular(flags, "to_hess", stacklevel=4)  # past checks_body's wrapper
    return out
