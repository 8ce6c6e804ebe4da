"""The initial tangent vectors of the chaos indicators (see :mod:`.lyapunov`, "The
tangent space"): unit vectors tangent to the symplectic leaf, or to the energy level
within it, at Euler-Poisson states.

``|gamma|^2``, ``(G, gamma)`` and ``H`` of Eq. (1) are first integrals, so a tangent
vector orthogonal to their gradients stays so along the linearised flow. The vector at a
state is the orthogonal projection of one fixed generic vector (the same for every
state: a map is deterministic and smooth in its initial conditions), computed for all
states at once in NumPy.

References
----------
.. [1] V. V. Kyrychenko, "Andoyer-Deprit variables use to the Hess gyroscope phase
   trajectories exploring" (Eq. (1)).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from andoyer.analysis.chaos.specs import TANGENT_SPACES, Tangent
from andoyer.body import RigidBody, checks_body
from andoyer.charts.euler_poisson import STATE, hamiltonian_expr
from andoyer.validation import real_array

__all__ = ["initial_tangent"]

# The fixed generic vectors whose projections are the initial tangent vectors (the second
# is used where the first is nearly normal to the tangent space).
_GENERIC = np.array([[1.0, math.sqrt(2), math.sqrt(3), math.sqrt(5), math.sqrt(7),
                      math.sqrt(11)],
                     [math.sqrt(13), -math.sqrt(3), math.sqrt(2), -1.0, math.sqrt(5),
                      -math.sqrt(7)]])
_MIN_PROJECTION = 0.05


def _gradients(body: RigidBody, y: NDArray[np.float64]) -> NDArray[np.float64]:
    """Gradients of ``(G, gamma)``, ``|gamma|^2`` and ``H`` at states ``y``, (n, 3, 6).

    ``grad H`` by complex-step differentiation of the one H of Eq. (1) (exact to
    round-off, nothing transcribed); the Casimirs' gradients are
    ``grad (G, gamma) = (gamma, G)`` and ``grad |gamma|^2 = (0, 2 gamma)``.
    """
    G, gamma = y[:, :3], y[:, 3:]
    rows = [np.concatenate([gamma, G], axis=1),
            np.concatenate([np.zeros_like(gamma), 2.0 * gamma], axis=1)]
    step = 1e-30
    grad = np.empty_like(y)
    for k in range(len(STATE)):
        z = y.astype(complex)
        z[:, k] += 1j * step
        G1, G2, G3, gamma1, gamma2, gamma3 = z.T
        grad[:, k] = np.imag(hamiltonian_expr(G1, G2, G3, gamma1, gamma2, gamma3,
                                              *body.params)) / step
    rows.append(grad)
    return np.stack(rows, axis=1)


@checks_body
def initial_tangent(body: RigidBody, y: ArrayLike, tangent: Tangent = "leaf",
                    direction: ArrayLike | None = None) -> NDArray[np.float64]:
    """Unit initial tangent vectors at Euler-Poisson states ``y``, shape (n, 6).

    Parameters
    ----------
    body : RigidBody
    y : array_like, shape (6,) or (n, 6)
        Euler-Poisson states.
    tangent : {"leaf", "energy"}
        ``"leaf"`` (default): orthogonal to ``grad (G, gamma)`` and ``grad |gamma|^2``
        (tangent to the symplectic leaf); ``"energy"``: also orthogonal to ``grad H``
        (tangent to the energy level of the reduced system).
    direction : array_like, shape (6,) or (n, 6), optional
        The vector to project (default: a fixed generic vector).

    Returns
    -------
    ndarray
        The normalised orthogonal projections.

    Raises
    ------
    ValueError
        If ``direction`` is (nearly) normal to the tangent space at some state.

    Examples
    --------
    >>> from andoyer.charts.andoyer_deprit import from_andoyer
    >>> body = RigidBody.paper()
    >>> y = from_andoyer([0.3, 0.0, 0.3, 1.0, 0.0])
    >>> w = initial_tangent(body, y)
    >>> bool(abs(np.linalg.norm(w) - 1) < 1e-15), bool(abs(w[0, 3:] @ y[3:]) < 1e-15)
    (True, True)
    """
    if tangent not in TANGENT_SPACES:
        raise ValueError(f"unknown tangent space {tangent!r}; choose 'energy' or 'leaf'")
    Y = np.atleast_2d(np.asarray(y, dtype=float))
    if Y.ndim != 2 or Y.shape[1] != len(STATE):
        raise ValueError(f"y must have shape (6,) or (n, 6), got {np.shape(y)}")
    N = _gradients(body, Y)  # (n, 3, 6): the Casimirs' gradients, then grad H
    if direction is not None:
        k = 2 if tangent == "leaf" else 3
        D = real_array("w0 (initial tangent direction)", direction)
        try:
            V = np.broadcast_to(D, Y.shape)
        except ValueError:
            raise ValueError(f"w0 (initial tangent direction) must have shape (6,) or "
                             f"{Y.shape}, got {np.shape(direction)}") from None
        if not np.all(np.isfinite(V)):
            raise ValueError("w0 (initial tangent direction) contains NaN or infinity")
        # Only the direction counts: scaled to its largest component first (a direction
        # of size 1e300 overflowed the norms).
        big = np.max(np.abs(V), axis=1, keepdims=True)
        V = V / np.where(big > 0.0, big, 1.0)
        W = V - _project(N[:, :k], V)
        norm = np.linalg.norm(W, axis=1)
        if np.any(norm <= 1e-8 * np.linalg.norm(V, axis=1)):
            raise ValueError("w0 (initial tangent direction) is normal to the tangent space "
                             "at some state: its projection vanishes; choose another "
                             "direction")
        return W / norm[:, None]
    # The iso-energetic part: a fixed generic vector projected onto the energy level.
    iso = np.empty_like(Y)
    todo = np.ones(Y.shape[0], dtype=bool)
    for v in _GENERIC:
        v = np.broadcast_to(v / np.linalg.norm(v), Y.shape)
        W = v - _project(N, v)
        norm = np.linalg.norm(W, axis=1)
        take = todo & (norm > _MIN_PROJECTION)
        iso[take] = W[take] / norm[take, None]
        todo &= ~take
    if np.any(todo):
        raise RuntimeError("no generic vector projects onto the tangent space; "
                           "please report this state")
    if tangent == "energy":
        return iso
    # "leaf": add the unit normal to the energy level within the leaf, so that the shear
    # between energy levels is excited by the same amount at every state (with a generic
    # vector alone its energy component would vanish on curves of the map, and so would
    # the linear growth on the tori there).
    gH = N[:, 2]
    normal = gH - _project(N[:, :2], gH)
    size = np.linalg.norm(normal, axis=1)
    ok = size > 1e-12 * np.maximum(np.linalg.norm(gH, axis=1), 1e-300)
    out = iso.copy()  # at a relative equilibrium (grad H in the Casimirs' span): iso only
    out[ok] = (iso[ok] + normal[ok] / size[ok, None]) / math.sqrt(2.0)
    # iso and the normal are orthogonal to rounding: unit length to the last bit.
    return out / np.linalg.norm(out, axis=1)[:, None]


#: Relative size below which a Gram-Schmidt residual counts as a dependent direction
#: (the cut-off ``numpy.linalg.pinv`` applies to singular values, relative to the largest).
_RCOND = 1e-15


def _project(N: NDArray[np.float64], V: NDArray[np.float64]) -> NDArray[np.float64]:
    """Orthogonal projection of the rows of ``V`` (n, 6) onto the span of ``N`` (n, k, 6).

    Modified Gram-Schmidt over the ``k <= 3`` spanning vectors, in NumPy over all states
    at once (the batched SVD of ``pinv`` it replaces cost 15 times more); a direction
    whose residual is below ``_RCOND`` times the largest spanning vector is dropped, as
    ``pinv`` drops the singular values below its ``rcond``.
    """
    scale = np.max(np.linalg.norm(N, axis=2), axis=1)  # (n,)
    out = np.zeros_like(V)
    basis: list[NDArray[np.float64]] = []
    for i in range(N.shape[1]):
        r = N[:, i].copy()
        for q in basis:
            r -= np.einsum("nj,nj->n", q, r)[:, None] * q
        size = np.linalg.norm(r, axis=1)
        keep = size > _RCOND * scale
        q = np.where(keep[:, None], r / np.where(keep, size, 1.0)[:, None], 0.0)
        basis.append(q)
        out += np.einsum("nj,nj->n", q, V)[:, None] * q
    return out
