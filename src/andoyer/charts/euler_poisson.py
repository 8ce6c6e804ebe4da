"""Euler-Poisson chart: the regular, global description of the heavy top.

State ``y = (G1, G2, G3, gamma1, gamma2, gamma3)`` in the principal axes: the angular
momentum ``G = (A p, B q, C r)`` and the upward vertical unit vector ``gamma``
(Eq. (1) of [1]_). The chart has no singular set; the physical phase space is the
level ``|gamma|^2 = 1`` of the geometric integral.

The Hamiltonian :math:`H = \\tfrac12(\\mathbf G, \\mathbf I^{-1}\\mathbf G) + \\mu(\\mathbf r,
\\boldsymbol\\gamma)` is written **once**, in :func:`hamiltonian_expr`, with plain
arithmetic so that it evaluates NumPy arrays and builds SymPy expressions alike;
every other form of H in this package is derived from it.

References
----------
.. [1] V. V. Kyrychenko, "Andoyer-Deprit variables use to the Hess gyroscope phase
   trajectories exploring".
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from andoyer.body import checks_body
from andoyer.validation import checks_arguments, real_array

if TYPE_CHECKING:
    from andoyer.body import RigidBody

__all__ = [
    "STATE",
    "hamiltonian_expr",
    "energy",
    "area_integral",
    "geometric_integral",
    "momentum_bound",
    "as_state",
]

#: Order of the Euler-Poisson state vector; index with ``STATE.index(name)``.
STATE = ("G1", "G2", "G3", "gamma1", "gamma2", "gamma3")


def hamiltonian_expr(G1: Any, G2: Any, G3: Any, gamma1: Any, gamma2: Any, gamma3: Any,
                     a: Any, b: Any, c: Any, mu: Any, e1: Any, e2: Any, e3: Any) -> Any:
    """The Hamiltonian of Eq. (1), ``H = (G, I^-1 G)/2 + mu (r, gamma)``: the one source.

    Works for NumPy arrays (numeric) and SymPy symbols (derivations alike).

    Parameters
    ----------
    G1, G2, G3 : number, array or sympy.Expr
        Body-frame angular momentum.
    gamma1, gamma2, gamma3 : number, array or sympy.Expr
        Body-frame vertical unit vector.
    a, b, c : number or sympy.Expr
        Inverse moments of inertia ``1/A, 1/B, 1/C``.
    mu : number or sympy.Expr
        Weight times the distance of the centre of mass.
    e1, e2, e3 : number or sympy.Expr
        Unit vector ``r`` towards the centre of mass (body frame).
    """
    return (a * G1**2 + b * G2**2 + c * G3**2) / 2 + mu * (e1 * gamma1 + e2 * gamma2
                                                          + e3 * gamma3)


def as_state(y: ArrayLike, name: str = "y") -> NDArray[np.float64]:
    """Validate an Euler-Poisson state array of shape ``(..., 6)``.

    Parameters
    ----------
    y : array_like, shape (..., 6)
        Euler-Poisson states ``(G1, G2, G3, gamma1, gamma2, gamma3)``.
    name : str, default "y"
        The argument's name, for the error.

    Raises
    ------
    ValueError
        If the last axis is not 6 long or the array holds NaN or infinity.
    """
    arr = real_array(name, y)
    if arr.ndim == 0 or arr.shape[-1] != 6:
        raise ValueError(
            f"{name} must have shape (..., 6) = (G1, G2, G3, gamma1, gamma2, gamma3), "
            f"got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} contains NaN or infinity")
    return arr


@checks_body
def energy(body: RigidBody, y: ArrayLike) -> NDArray[np.float64]:
    """Total energy ``H(y)`` of Eq. (1) (kinetic + potential), shape ``(...)``.

    Parameters
    ----------
    body : RigidBody
        Supplies the moments, ``mu`` and the centre of mass ``r``.
    y : array_like, shape (..., 6)
        Euler-Poisson states ``(G1, G2, G3, gamma1, gamma2, gamma3)``.

    Returns
    -------
    ndarray, shape (...)
        ``H = (G, I^-1 G)/2 + mu (r, gamma)``.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> body = RigidBody(2.0, 2.0, 1.0, mu=1.0, r=(0, 0, 1))
    >>> float(energy(body, [0, 0, 1.0, 0, 0, 1.0]))
    1.5
    """
    return _energy(body, as_state(y))


def _energy(body: RigidBody, arr: NDArray[np.float64]) -> NDArray[np.float64]:
    """:func:`energy` of checked states."""
    args = [*np.moveaxis(arr, -1, 0), *body.params]
    return np.asarray(hamiltonian_expr(*args))


@checks_arguments
def area_integral(y: ArrayLike) -> NDArray[np.float64]:
    """Area integral ``C1 = M = (G, gamma)``, a Casimir of (1), shape ``(...)``.

    Parameters
    ----------
    y : array_like, shape (..., 6)
        Euler-Poisson states ``(G1, G2, G3, gamma1, gamma2, gamma3)``.

    Returns
    -------
    ndarray, shape (...)
    """
    arr = as_state(y)
    return np.einsum("...i,...i->...", arr[..., :3], arr[..., 3:])


@checks_arguments
def geometric_integral(y: ArrayLike) -> NDArray[np.float64]:
    """Geometric integral ``C2 = |gamma|^2`` (equal to 1 on the physical level).

    Parameters
    ----------
    y : array_like, shape (..., 6)
        Euler-Poisson states ``(G1, G2, G3, gamma1, gamma2, gamma3)``.

    Returns
    -------
    ndarray, shape (...)
    """
    return _geometric(as_state(y))


def _geometric(arr: NDArray[np.float64]) -> NDArray[np.float64]:
    """:func:`geometric_integral` of checked states."""
    return np.einsum("...i,...i->...", arr[..., 3:], arr[..., 3:])


@checks_body
def momentum_bound(body: RigidBody, y: ArrayLike, H: ArrayLike | None = None
                   ) -> NDArray[np.float64]:
    """The largest ``|G|`` on the energy level of ``y``: the orbit's momentum scale.

    On ``H = h`` the kinetic energy ``T = h - mu (r, gamma)`` is at most
    ``h + mu |r| |gamma|`` and at least ``|G|^2 / (2 max(A, B, C))``, so every state of the
    orbit through ``y`` has ``|G| <= sqrt(2 max(A, B, C) (h + mu |r| |gamma|))``. Singular
    sets of the charts (``G -> 0``) are detected relative to this scale, which an orbit
    keeps for all time (the Euler-Poisson state itself has no other momentum scale).
    ``H``, when given, is ``energy(body, y)`` already computed.

    Parameters
    ----------
    body : RigidBody
        The body (moments, ``mu``).
    y : array_like, shape (..., 6)
        Euler-Poisson states.
    H : array_like, optional
        Their energies (default: computed from ``y``).

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> body = RigidBody(2.0, 2.0, 1.0, mu=1.0, r=(0, 0, 1))
    >>> y = [0.0, 0.0, 0.0, 0.0, 0.0, 1.0]  # at rest, upright: h = mu, T <= 2 mu
    >>> round(float(momentum_bound(body, y)), 6)  # sqrt(2 A (h + mu))
    2.828427
    """
    arr = as_state(y)
    a, b, c, mu, e1, e2, e3 = body.params
    rnorm = float(np.sqrt(e1 * e1 + e2 * e2 + e3 * e3))
    # the checked states' own integrals (the public functions would check them again)
    gnorm = np.sqrt(_geometric(arr))
    h = _energy(body, arr) if H is None else np.asarray(H, dtype=float)
    room = np.maximum(h + abs(mu) * rnorm * gnorm, 0.0)
    bound = np.sqrt(2.0 * max(body.A, body.B, body.C) * room)
    return np.maximum(bound, np.linalg.norm(arr[..., :3], axis=-1))
