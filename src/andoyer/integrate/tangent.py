"""Orbits with tangent vectors on the numba engine: plain arrays in and out.

The friendly side of :mod:`andoyer.kernels.tangent` (the variational equations of (1)
on the Numba DOP853, orbits in parallel): it validates and shapes the arrays, applies
the engines' tolerance convention and turns a failed orbit into ``ok = False``.

* :func:`propagate_tangent` -- states and ``k`` tangent vectors at output times, with
  the log norms and the MEGNO quadratures of the first vector (chaos indicators);
* :func:`fundamental_matrix` -- ``Phi(t) = d y(t) / d y(0)`` (k = 6, identity at t = 0),
  e.g. the monodromy matrix of a periodic orbit;
* :func:`tangent_crossings` -- the crossings of a section with the tangent vectors
  there (the Jacobian of the flow to a section).

Tolerances follow the engines: ``tol`` is the accuracy asked for, and the DOP853
controller gets ``TOLERANCE_FACTOR * tol`` for both ``rtol`` and ``atol`` (see
:data:`andoyer.integrate.engines.base.TOLERANCE_FACTOR`).

No heyoka anywhere: this is what the chaos indicators, periodic orbits and Floquet
multipliers run on where heyoka has no wheel.
"""

from __future__ import annotations

import math
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from andoyer.charts.euler_poisson import STATE
from andoyer.errors import IntegrationError
from andoyer.integrate.engines.base import TOLERANCE_FACTOR, Params
from andoyer.validation import integer

__all__ = [
    "TangentResult",
    "TangentCrossings",
    "propagate_tangent",
    "fundamental_matrix",
    "tangent_crossings",
    "MAX_STEPS",
]

#: Accepted steps allowed per orbit before it is reported as failed.
MAX_STEPS = 10**9

_N = len(STATE)


class TangentResult(NamedTuple):
    """What :func:`propagate_tangent` returns (``n`` orbits, ``m`` times, ``k`` vectors).

    The tangent vectors are ``w_i(t) = exp(rho_i(t)) u_i(t)`` (:attr:`w`), with ``u_i``
    of unit length and ``w_i(0)`` the given vectors.
    """

    y: NDArray[np.float64]  # (n, m, 6): Euler-Poisson states
    u: NDArray[np.float64]  # (n, m, k, 6): unit tangent vectors w_i / |w_i|
    rho: NDArray[np.float64]  # (n, m, k): ln |w_i|
    megno_num: NDArray[np.float64]  # (n, m): int_0^t (s + delta) d rho_1/ds ds
    megno_int: NDArray[np.float64]  # (n, m): int_0^t 2 megno_num / (s + delta) ds
    ok: NDArray[np.bool_]  # (n,): False where the integration failed (NaN there)

    @property
    def w(self) -> NDArray[np.float64]:
        """The tangent vectors ``exp(rho_i) u_i``, shape (n, m, k, 6)."""
        return np.exp(self.rho)[..., None] * self.u


class TangentCrossings(NamedTuple):
    """What :func:`tangent_crossings` returns (NaN-padded beyond ``count``)."""

    t: NDArray[np.float64]  # (n, n_crossings)
    y: NDArray[np.float64]  # (n, n_crossings, 6)
    w: NDArray[np.float64]  # (n, n_crossings, k, 6): tangent vectors there
    count: NDArray[np.int64]  # type: ignore[assignment]  # (n,); shadows tuple.count
    ok: NDArray[np.bool_]  # (n,)


def _kernels() -> Any:
    from andoyer.kernels import tangent  # Numba loads here, not at import

    return tangent


def _check_params(params: Params) -> NDArray[np.float64]:
    p = np.ascontiguousarray(params, dtype=np.float64).reshape(-1)
    if p.shape != (8,):
        raise ValueError("params must be (a, b, c, mu, e1, e2, e3, phi0), "
                         f"got {p.size} values")
    return p


def _check_tol(tol: float) -> float:
    t = float(tol)
    if not (math.isfinite(t) and 1e-16 <= t <= 1e-3):
        raise ValueError(f"tol must be in [1e-16, 1e-3], got {tol!r}")
    return t


def _initial(y0: ArrayLike, w0: ArrayLike) -> tuple[NDArray[np.float64], int]:
    """The packed initial states (layout of kernels.tangent) and ``k``."""
    Y = np.asarray(y0, dtype=np.float64)
    W = np.asarray(w0, dtype=np.float64)
    if Y.ndim == 1:
        Y = Y[None]
    if Y.ndim != 2 or Y.shape[1] != _N:
        raise ValueError(f"y0 must have shape (6,) or (n, 6), got {np.shape(y0)}")
    if W.ndim == 1:
        W = W[None]
    if W.ndim == 2:  # the same vectors for every orbit
        W = W[None]
    if W.ndim != 3 or W.shape[2] != _N or W.shape[0] not in (1, Y.shape[0]):
        raise ValueError(f"w0 must have shape (6,), (k, 6) or (n, k, 6) with n = "
                         f"{Y.shape[0]} orbits, got {np.shape(w0)}")
    W = np.broadcast_to(W, (Y.shape[0], W.shape[1], _N))
    k = W.shape[1]
    tk = _kernels()
    if not 1 <= k <= tk.MAX_VECTORS:
        raise ValueError(f"between 1 and {tk.MAX_VECTORS} tangent vectors per orbit, "
                         f"got {k}")
    if not (np.all(np.isfinite(Y)) and np.all(np.isfinite(W))):
        raise ValueError("y0 and w0 must be finite")
    norms = np.linalg.norm(W, axis=2)
    if np.any(norms == 0.0):
        raise ValueError("w0 contains a zero vector")
    L = tk.layout(k)
    z = np.zeros((Y.shape[0], tk.dimension(k)))
    z[:, L["y"]] = Y
    z[:, L["u"]] = (W / norms[..., None]).reshape(Y.shape[0], -1)
    z[:, L["rho"]] = np.log(norms)
    return z, k


def propagate_tangent(y0: ArrayLike, w0: ArrayLike, t: ArrayLike, params: Params, *,
                      tol: float = 1e-12, tolerance_factor: float = TOLERANCE_FACTOR,
                      max_steps: int = MAX_STEPS) -> TangentResult:
    """Integrate orbits of (1) with ``k`` tangent vectors each (numba, in parallel).

    Parameters
    ----------
    y0 : array_like, shape (6,) or (n, 6)
        Euler-Poisson initial states.
    w0 : array_like, shape (6,), (k, 6) or (n, k, 6)
        Initial tangent vectors (any non-zero length; ``rho`` starts at ``ln |w0|``):
        ``(k, 6)`` the same for every orbit, ``(n, k, 6)`` per orbit; ``1 <= k <= 6``.
    t : array_like, shape (m,)
        Output times, increasing; ``t[0]`` is the initial time.
    params : tuple
        ``(a, b, c, mu, e1, e2, e3, phi0)`` (:attr:`RigidBody.engine_params`).
    tol : float, default 1e-12
        Accuracy asked for; DOP853 gets ``tolerance_factor * tol``.
    tolerance_factor : float
        See :data:`andoyer.integrate.engines.base.TOLERANCE_FACTOR`.
    max_steps : int
        Accepted steps allowed per orbit.

    Returns
    -------
    TangentResult
        Failed orbits (non-finite state, too many steps) have ``ok`` False and NaN.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> body = RigidBody.euler_poinsot(2.5, 2.0, 2.2)
    >>> res = propagate_tangent([0, 0, 1, 0, 0, 1], [1, 0, 0, 0, 0, 0], [0.0, 10.0],
    ...                         body.engine_params)
    >>> res.u.shape, bool(res.ok[0])
    ((1, 2, 1, 6), True)
    """
    times = np.ascontiguousarray(t, dtype=np.float64).reshape(-1)
    if times.size < 1 or not np.all(np.isfinite(times)) or np.any(np.diff(times) <= 0.0):
        raise ValueError("t must be increasing finite output times")
    z0, k = _initial(y0, w0)
    p = _check_params(params)
    f = float(tolerance_factor) * _check_tol(tol)
    max_steps = integer("max_steps", max_steps, 1)
    tk = _kernels()
    out, info = tk.propagate(z0, times, p, f, f, max_steps)
    ok = (info[:, 0] == 0) & np.all(np.isfinite(out), axis=(1, 2))
    out[~ok] = np.nan
    L = tk.layout(k)
    n, m = out.shape[:2]
    return TangentResult(out[..., L["y"]], out[..., L["u"]].reshape(n, m, k, _N),
                         out[..., L["rho"]], out[..., L["megno_num"]],
                         out[..., L["megno_int"]], ok)


def fundamental_matrix(y0: ArrayLike, t: ArrayLike, params: Params, *,
                       tol: float = 1e-12) -> NDArray[np.float64]:
    """``Phi(t)[i, j] = d y_i(t) / d y_j(t[0])`` of the flow (1), shape (n, m, 6, 6).

    Integrates the six columns of the identity as tangent vectors. Over one period of
    a periodic orbit this is its monodromy matrix (eigenvalues: the Floquet
    multipliers, with 1 four times for the Casimirs, H and the flow direction).

    Raises
    ------
    IntegrationError
        If an orbit fails (non-finite state).

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> body = RigidBody.paper()
    >>> Phi = fundamental_matrix([0.2, 0.1, 0.9, 0.0, 0.6, 0.8], [0.0, 5.0],
    ...                          body.engine_params)
    >>> Phi.shape, bool(np.allclose(Phi[0, 0], np.eye(6)))
    ((1, 2, 6, 6), True)
    """
    res = propagate_tangent(y0, np.eye(_N), t, params, tol=tol)
    if not res.ok.all():
        bad = np.flatnonzero(~res.ok).tolist()
        raise IntegrationError(f"the variational integration failed for orbits {bad}")
    return np.swapaxes(res.w, -1, -2)


def tangent_crossings(y0: ArrayLike, w0: ArrayLike, params: Params, kind: int,
                      value: float, direction: int, n_crossings: int, t_max: float, *,
                      tol: float = 1e-12, tolerance_factor: float = TOLERANCE_FACTOR,
                      max_steps: int = MAX_STEPS) -> TangentCrossings:
    """The first crossings after t = 0 of a section, with the tangent vectors there.

    The section is ``SECTION_KINDS[kind] = value`` (:mod:`andoyer.kernels.generated`)
    crossed in ``direction`` (+1, -1, 0), located as by the numba engine (the same
    DOP853 and root finding, on the augmented system). ``w`` at a crossing is the
    tangent flow at the crossing *time*; the derivative of the flow *to the section*
    adds ``-f (grad s . w) / (grad s . f)``.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> from andoyer.kernels.generated import SECTION_KINDS
    >>> body = RigidBody.paper()
    >>> c = tangent_crossings([0.2, 0.1, 0.9, 0.0, 0.6, 0.8], np.eye(6), body.engine_params,
    ...                       SECTION_KINDS.index("G3"), 0.0, 0, 2, 500.0)
    >>> int(c.count[0]), c.w.shape
    (2, (1, 2, 6, 6))
    """
    z0, k = _initial(y0, w0)
    p = _check_params(params)
    f = float(tolerance_factor) * _check_tol(tol)
    n_crossings = integer("n_crossings", n_crossings, 0)
    max_steps = integer("max_steps", max_steps, 1)
    tk = _kernels()
    tc, zc, count, info = tk.locate_crossings(z0, p, int(kind), float(value),
                                              int(direction), n_crossings,
                                              float(t_max), f, f, max_steps)
    ok = info[:, 0] == 0
    L = tk.layout(k)
    n, c = tc.shape
    w = np.exp(zc[..., L["rho"]])[..., None] * zc[..., L["u"]].reshape(n, c, k, _N)
    return TangentCrossings(tc, zc[..., L["y"]], w, count, ok)
