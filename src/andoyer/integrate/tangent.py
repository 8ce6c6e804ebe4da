"""Orbits with tangent vectors: plain arrays in and out, on any engine with the capability.

The friendly side of :meth:`Engine.tangent <andoyer.integrate.engines.base.EngineBase.tangent>`
(the variational equations of (1), ``k`` vectors renormalised continuously):

* :func:`propagate_tangent` -- states and ``k`` tangent vectors at output times, with
  the log norms and the MEGNO quadratures of the first vector (chaos indicators);
* :func:`fundamental_matrix` -- ``Phi(t) = d y(t) / d y(0)`` (k = 6, identity at t = 0),
  e.g. the monodromy matrix of a periodic orbit;
* :func:`tangent_crossings` -- the crossings of a section with the tangent vectors
  there (the Jacobian of the flow to a section).

The engine is ``"numba"`` by default here (no heyoka needed: what the chaos
indicators, periodic orbits and Floquet multipliers run on where heyoka has no
wheel); ``tol`` is the accuracy asked for (:class:`~andoyer.integrate.engines.base.Tolerance`),
and the DOP853 controller gets ``TOLERANCE_FACTOR * tol``
(:data:`andoyer.integrate.engines.base.TOLERANCE_FACTOR`).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from andoyer.charts.euler_poisson import STATE
from andoyer.errors import IntegrationError
from andoyer.integrate.engines import EngineLike, resolve_engine
from andoyer.integrate.engines.base import (
    TOLERANCE_FACTOR,
    Capability,
    EngineBase,
    Params,
    Section,
    Tolerance,
)

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

    Parameters
    ----------
    y : ndarray, shape (n, m, 6)
        Euler-Poisson states.
    u : ndarray, shape (n, m, k, 6)
        Unit tangent vectors ``w_i / |w_i|``.
    rho : ndarray, shape (n, m, k)
        ``ln |w_i|``.
    megno_num : ndarray, shape (n, m)
        ``int_0^t (s + delta) d rho_1/ds ds``.
    megno_int : ndarray, shape (n, m)
        ``int_0^t 2 megno_num / (s + delta) ds``.
    ok : ndarray of bool, shape (n,)
        False where the integration failed (NaN there).
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
    """What :func:`tangent_crossings` returns (NaN-padded beyond ``count``).

    Parameters
    ----------
    t : ndarray, shape (n, n_crossings)
        Crossing times.
    y : ndarray, shape (n, n_crossings, 6)
        Euler-Poisson states there.
    w : ndarray, shape (n, n_crossings, k, 6)
        Tangent vectors there.
    count : ndarray of int, shape (n,)
        Crossings found per orbit.
    ok : ndarray of bool, shape (n,)
        False where the integration failed.
    """

    t: NDArray[np.float64]  # (n, n_crossings)
    y: NDArray[np.float64]  # (n, n_crossings, 6)
    w: NDArray[np.float64]  # (n, n_crossings, k, 6): tangent vectors there
    count: NDArray[np.int64]  # type: ignore[assignment]  # (n,); shadows tuple.count
    ok: NDArray[np.bool_]  # (n,)


def _engine(engine: EngineLike, capability: Capability, tolerance_factor: float,
            max_steps: int) -> EngineBase:
    return resolve_engine(engine, capability, tolerance_factor=tolerance_factor,
                          max_steps=max_steps)


def propagate_tangent(y0: ArrayLike, w0: ArrayLike, t: ArrayLike, params: Params, *,
                      tol: float = 1e-12, tolerance_factor: float = TOLERANCE_FACTOR,
                      max_steps: int = MAX_STEPS,
                      engine: EngineLike = "numba") -> TangentResult:
    """Integrate orbits of (1) with ``k`` tangent vectors each (numba: in parallel).

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
    engine : str or Engine, default "numba"
        Any engine with the ``tangent`` capability (``tolerance_factor`` and
        ``max_steps`` go to the engines that take them).

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
    eng = _engine(engine, Capability.TANGENT, tolerance_factor, max_steps)
    flow = eng.tangent(y0, w0, params, Tolerance.single(tol), t=times)
    megno = flow.megno if flow.megno is not None else np.full(flow.y.shape[:2] + (2,), np.nan)
    return TangentResult(flow.y, flow.u, flow.rho, megno[..., 0], megno[..., 1], flow.ok)


def fundamental_matrix(y0: ArrayLike, t: ArrayLike, params: Params, *,
                       tol: float = 1e-12, engine: EngineLike = "numba") -> NDArray[np.float64]:
    """``Phi(t)[i, j] = d y_i(t) / d y_j(t[0])`` of the flow (1), shape (n, m, 6, 6).

    Integrates the six columns of the identity as tangent vectors. Over one period of
    a periodic orbit this is its monodromy matrix (eigenvalues: the Floquet
    multipliers, with 1 four times for the Casimirs, H and the flow direction).

    Parameters
    ----------
    y0 : array_like, shape (6,) or (n, 6)
        Initial Euler-Poisson states.
    t : array_like, shape (m,)
        Output times (from ``t[0]``).
    params : tuple of float
        The body's engine parameters (:attr:`~andoyer.body.RigidBody.engine_params`).
    tol : float, default 1e-12
        Integration tolerance.
    engine : str or Engine, default "numba"
        An engine with the ``tangent`` capability.

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
    res = propagate_tangent(y0, np.eye(_N), t, params, tol=tol, engine=engine)
    if not res.ok.all():
        bad = np.flatnonzero(~res.ok).tolist()
        raise IntegrationError(f"the variational integration failed for orbits {bad}")
    return np.swapaxes(res.w, -1, -2)


def tangent_crossings(y0: ArrayLike, w0: ArrayLike, params: Params, kind: int,
                      value: float, direction: int, n_crossings: int, t_max: float, *,
                      tol: float = 1e-12, tolerance_factor: float = TOLERANCE_FACTOR,
                      max_steps: int = MAX_STEPS,
                      engine: EngineLike = "numba") -> TangentCrossings:
    """The first crossings after t = 0 of a section, with the tangent vectors there.

    The section is ``ALL_KINDS[kind] = value`` (:mod:`andoyer.integrate.engines.base`)
    crossed in ``direction`` (+1, -1, 0), located as by the engine's ``crossings``
    (numba: the same DOP853 and root finding, on the augmented system). ``w`` at a crossing is the
    tangent flow at the crossing *time*; the derivative of the flow *to the section*
    adds ``-f (grad s . w) / (grad s . f)``.

    Parameters
    ----------
    y0 : array_like, shape (6,) or (n, 6)
        Initial Euler-Poisson states.
    w0 : array_like, shape (k, 6) or (n, k, 6)
        Initial tangent vectors.
    params : tuple of float
        The body's engine parameters (:attr:`~andoyer.body.RigidBody.engine_params`).
    kind : int
        Section kind: an index of ``ALL_KINDS``.
    value : float
        Section value.
    direction : {+1, -1, 0}
        Crossing direction (0: both).
    n_crossings : int
        Crossings wanted per orbit.
    t_max : float
        Largest integration time (body time units).
    tol : float, default 1e-12
        Integration tolerance.
    tolerance_factor : float, default 0.025
        Factor on the DOP853 tolerances (numba).
    max_steps : int, default 1000000000
        Largest number of steps per orbit (numba).
    engine : str or Engine, default "numba"
        An engine with the ``tangent_crossings`` capability.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> from andoyer.kernels.generated.equations import SECTION_KINDS
    >>> body = RigidBody.paper()
    >>> c = tangent_crossings([0.2, 0.1, 0.9, 0.0, 0.6, 0.8], np.eye(6), body.engine_params,
    ...                       SECTION_KINDS.index("G3"), 0.0, 0, 2, 500.0)
    >>> int(c.count[0]), c.w.shape
    (2, (1, 2, 6, 6))
    """
    eng = _engine(engine, Capability.TANGENT_CROSSINGS, tolerance_factor, max_steps)
    flow = eng.tangent(y0, w0, params, Tolerance.single(tol),
                       event=Section.from_kind(kind, value, direction),
                       n_crossings=n_crossings, t_max=t_max)
    return TangentCrossings(flow.t, flow.y, flow.w, flow.count, flow.ok)
