"""The scipy engine: ``scipy.integrate.solve_ivp(method="DOP853")``, orbit by orbit.

Kept as an independent check of the compiled engines in tests: the right-hand side
and the section functions are the generated NumPy kernels
(:mod:`andoyer.kernels.generated`) called from Python at every stage, so it is slow
(seconds per orbit to t = 1e3 at rtol = 1e-12) and runs serially. Its tolerances
mean what they mean for the numba engine: SciPy's controller is given
``tolerance_factor * rtol`` and ``tolerance_factor * atol``
(:data:`andoyer.integrate.engines.base.TOLERANCE_FACTOR` by default), so that the two DOP853
engines take the same steps; below SciPy's floor ``rtol >= 100 eps`` the relative
tolerance is raised to that floor.

Crossings are SciPy events located by ``brentq`` on the dense output with a
tolerance relative to t (``4 eps |t|``), so at large t the residual of the section
equation grows like ``|df/dt| eps t`` (about 1e-12 at t ~ 1e3 for ``|df/dt| ~ 1``),
unlike the numba and heyoka engines whose residual stays at round-off.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray
from scipy.integrate import solve_ivp

from andoyer.errors import IntegrationError
from andoyer.integrate.engines.base import (
    TOLERANCE_FACTOR,
    Crossings,
    Params,
    check_tolerance_factor,
)
from andoyer.kernels.constants import T_START
from andoyer.kernels.generated import ep_field, section

__all__ = ["ScipyEngine", "solve_dop853"]

# Events are collected over windows of integration that double in length from this,
# so that an orbit stops soon after its n-th crossing without a terminal event.
_FIRST_WINDOW = 100.0
# solve_ivp raises smaller relative tolerances to this, with a warning.
_RTOL_FLOOR = 100 * np.finfo(np.float64).eps




class _Field:
    """``fun(t, y)`` of ``solve_ivp``: the generated field (1) with the body fixed."""

    def __init__(self, params: Params) -> None:
        self.p = tuple(float(v) for v in params[:7])

    def __call__(self, t: float, y: NDArray[np.float64]) -> NDArray[np.float64]:
        dy = ep_field(*y.tolist(), *self.p)
        # solve_ivp would loop for ever on a NaN step size.
        if not math.isfinite(sum(dy)):
            raise IntegrationError(f"scipy DOP853: non-finite field at t = {t!r}")
        return np.array(dy)


class _SectionEvent:
    """A ``solve_ivp`` event: the section function f; ``direction`` as SciPy reads it."""

    terminal = False

    def __init__(self, kind: int, value: float, direction: int, phi0: float) -> None:
        self.args = (float(phi0), float(value), math.cos(value), math.sin(value))
        self.kind = int(kind)
        self.direction = float(direction)

    def fw(self, y: NDArray[np.float64]) -> tuple[float, float]:
        args = [self.kind, *y.tolist(), *self.args]
        f, w = section(*args)
        return float(f), float(w)

    def __call__(self, t: float, y: NDArray[np.float64]) -> float:
        return self.fw(y)[0]


def solve_dop853(rhs: Callable[[float, NDArray[np.float64]], NDArray[np.float64]],
                 t: NDArray[np.float64], y0: NDArray[np.float64], rtol: float, atol: float,
                 *, events: Sequence[Callable[..., float]] | None = None) -> Any:
    """``solve_ivp(method="DOP853")`` from ``t[0]`` with output at ``t``: the one helper
    for integrations of right-hand sides other than the Euler-Poisson field (reduced
    systems, canonical charts, quadratures), so that every SciPy integration is built
    in this module. Tolerances are used as given (no :data:`TOLERANCE_FACTOR`).

    Returns SciPy's ``OdeResult`` (status 1 when a terminal event fired); raises
    :class:`~andoyer.errors.IntegrationError` when the integrator fails.

    Examples
    --------
    >>> sol = solve_dop853(lambda t, y: -y, np.array([0.0, 1.0]), np.array([1.0]),
    ...                    1e-12, 1e-12)
    >>> bool(abs(sol.y[0, -1] - np.exp(-1.0)) < 1e-11)
    True
    """
    sol = solve_ivp(rhs, (float(t[0]), float(t[-1])), y0, method="DOP853", t_eval=t,
                    rtol=rtol, atol=atol, events=events)
    _check(sol, "")
    return sol


def _check(sol: object, what: str) -> None:
    if getattr(sol, "status", -1) < 0:
        raise IntegrationError(f"scipy DOP853 failed {what}: {getattr(sol, 'message', '')}")


class ScipyEngine:
    """``solve_ivp(method="DOP853")`` on the generated field, one orbit after another.

    Parameters
    ----------
    tolerance_factor : float, default :data:`andoyer.integrate.engines.base.TOLERANCE_FACTOR`
        SciPy is given ``tolerance_factor * rtol`` and ``tolerance_factor * atol``.

    Examples
    --------
    >>> import numpy as np
    >>> from andoyer import RigidBody, from_andoyer
    >>> body = RigidBody.paper()
    >>> y0 = from_andoyer([[0.3, 1.1, 0.2, 1.0, -0.4]])
    >>> y = ScipyEngine().propagate(y0, np.array([0.0, 10.0]), (*body.params, body.phi0),
    ...                             1e-10, 1e-10)
    >>> y.shape
    (1, 2, 6)
    """

    name = "scipy"

    def __init__(self, *, tolerance_factor: float = TOLERANCE_FACTOR) -> None:
        self.tolerance_factor = check_tolerance_factor(tolerance_factor)

    def __repr__(self) -> str:
        return f"ScipyEngine(tolerance_factor={self.tolerance_factor})"

    def _tolerances(self, rtol: float, atol: float) -> dict[str, float]:
        return {"rtol": max(self.tolerance_factor * rtol, _RTOL_FLOOR),
                "atol": self.tolerance_factor * atol}

    def propagate(self, y0: NDArray[np.float64], t: NDArray[np.float64], params: Params,
                  rtol: float, atol: float) -> NDArray[np.float64]:
        """States at times ``t`` (k,) of the orbits from ``y0`` (n, 6): shape (n, k, 6)."""
        y = np.asarray(y0, dtype=np.float64)
        times = np.asarray(t, dtype=np.float64)
        if y.ndim != 2 or y.shape[1] != 6:
            raise ValueError(f"y0 must have shape (n, 6), got {y.shape}")
        if times.ndim != 1:
            raise ValueError(f"t must have shape (k,), got {times.shape}")
        out = np.empty((y.shape[0], times.size, 6))
        if times.size == 0:
            return out
        fun = _Field(params)
        for i in range(y.shape[0]):
            out[i, 0] = y[i]
            if times[-1] == times[0]:
                out[i, 1:] = y[i]
                continue
            sol = solve_ivp(fun, (times[0], times[-1]), y[i], method="DOP853",
                            dense_output=True, **self._tolerances(rtol, atol))
            _check(sol, "in propagate")
            out[i, 1:] = sol.sol(times[1:]).T
            out[i, -1] = sol.y[:, -1]
        return out

    def crossings(self, y0: NDArray[np.float64], params: Params, kind: int, value: float,
                  direction: int, n_crossings: int, t_max: float, rtol: float,
                  atol: float) -> Crossings:
        """The first ``n_crossings`` crossings after t = 0 of ``SECTION_KINDS[kind] =
        value`` in ``direction`` (+1, -1, 0), integrating at most to ``t_max``.

        SciPy's events cannot require the margin ``w > 0``, so roots are collected
        over windows of growing length and filtered afterwards.
        """
        y = np.asarray(y0, dtype=np.float64)
        if y.ndim != 2 or y.shape[1] != 6:
            raise ValueError(f"y0 must have shape (n, 6), got {y.shape}")
        n, m = y.shape[0], int(n_crossings)
        t_out = np.full((n, m), np.nan)
        y_out = np.full((n, m, 6), np.nan)
        count = np.zeros(n, dtype=np.int64)
        fun = _Field(params)
        event = _SectionEvent(kind, value, direction, params[7])
        for i in range(n):
            t, state, window = 0.0, y[i], _FIRST_WINDOW
            while count[i] < m and t < t_max:
                t1 = min(t + window, t_max)
                try:
                    sol = solve_ivp(fun, (t, t1), state, method="DOP853", events=event,
                                    **self._tolerances(rtol, atol))
                except RuntimeError as exc:  # SciPy's root finder on a degenerate root
                    raise IntegrationError(
                        f"scipy DOP853 could not locate a root of the section function in "
                        f"t = [{t:.6g}, {t1:.6g}] ({exc}); this happens at passages through "
                        "a chart's singular set (e.g. G = 0): use the heyoka or numba "
                        "engine, or a section of a smooth coordinate") from None
                _check(sol, "while locating crossings")
                for te, ye in zip(sol.t_events[0], sol.y_events[0], strict=True):
                    c = count[i]
                    # A root exactly at a window boundary is reported by both windows.
                    if c == m or (c > 0 and te <= t_out[i, c - 1]) or te <= T_START:
                        continue
                    if event.fw(ye)[1] > 0.0:
                        t_out[i, c], y_out[i, c] = te, ye
                        count[i] += 1
                t, state, window = t1, sol.y[:, -1], 2.0 * window
        return Crossings(t_out, y_out, count)
