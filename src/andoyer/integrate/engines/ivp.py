"""``solve_ivp(DOP853)`` for right-hand sides other than the Euler-Poisson field.

The one helper through which every SciPy integration of andoyer runs (reduced systems,
canonical charts, quadratures, the Hess manifold); the scipy *engine*
(:mod:`andoyer.integrate.engines.scipy_engine`) uses it too. Modules outside the
engines import this module, never an engine's.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy.integrate import solve_ivp

from andoyer.errors import IntegrationError

__all__ = ["solve_dop853", "check_solution"]


def solve_dop853(rhs: Callable[[float, NDArray[np.float64]], NDArray[np.float64]],
                 t: NDArray[np.float64], y0: NDArray[np.float64], rtol: float, atol: float,
                 *, events: Sequence[Callable[..., float]] | None = None) -> Any:
    """``solve_ivp(method="DOP853")`` from ``t[0]`` with output at ``t``: the one helper
    for integrations of right-hand sides other than the Euler-Poisson field (reduced
    systems, canonical charts, quadratures), so that every SciPy integration is built
    in this module. Tolerances are used as given (no :data:`TOLERANCE_FACTOR`).

    Returns SciPy's ``OdeResult`` (status 1 when a terminal event fired); raises
    :class:`~andoyer.errors.IntegrationError` when the integrator fails.

    Parameters
    ----------
    rhs : callable
        ``rhs(t, y) -> dy/dt``.
    t : ndarray, shape (m,)
        Output times, from ``t[0]`` (either direction).
    y0 : ndarray
        Initial state at ``t[0]``.
    rtol, atol : float
        Tolerances, used as given.
    events : sequence of callable, optional
        Event functions of :func:`scipy.integrate.solve_ivp`.

    Examples
    --------
    >>> sol = solve_dop853(lambda t, y: -y, np.array([0.0, 1.0]), np.array([1.0]),
    ...                    1e-12, 1e-12)
    >>> bool(abs(sol.y[0, -1] - np.exp(-1.0)) < 1e-11)
    True
    """
    sol = solve_ivp(rhs, (float(t[0]), float(t[-1])), y0, method="DOP853", t_eval=t,
                    rtol=rtol, atol=atol, events=events)
    check_solution(sol, "")
    return sol


def check_solution(sol: object, what: str) -> None:
    """:class:`~andoyer.errors.IntegrationError` if a ``solve_ivp`` result failed.

    Parameters
    ----------
    sol : object
        A :func:`scipy.integrate.solve_ivp` result.
    what : str
        What was integrated, named in the error.
    """
    if getattr(sol, "status", -1) < 0:
        raise IntegrationError(f"scipy DOP853 failed {what}: {getattr(sol, 'message', '')}")
