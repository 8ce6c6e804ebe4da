"""The numba engine: adaptive DOP853 with dense output, compiled with Numba.

A thin adapter from the :class:`~andoyer.integrate.engines.base.Engine` protocol to
the kernels of :mod:`andoyer.kernels.dop853`: it checks shapes, makes the arrays
contiguous floats, runs the ensemble kernel (blocks of orbits in Numba's number of
threads, :mod:`andoyer.kernels.threads`) and turns a failed orbit into an exception.

Tolerances. The DOP853 controller keeps the estimated local error of each component
below ``f (atol + rtol |y|)`` with ``f = tolerance_factor``
(:data:`andoyer.integrate.engines.base.TOLERANCE_FACTOR` = 0.025 by default): at ``f = 1``
(SciPy's meaning of rtol, atol) the integrals drift by ~1e-9 over t = 1e4 at
rtol = atol = 1e-12 for a heavy top; with the default the engine meets the accuracy
contract (drift below 1e-10 over t = 1e4 at 1e-12) like the heyoka engine.

The machine code is cached on disk (``cache=True``, in the user's cache folder,
:mod:`andoyer.kernels.cache`): the first process on a machine compiles the kernels it
calls (5-8 s each), later processes load them (under a second).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from andoyer.errors import IntegrationError
from andoyer.integrate.engines.base import (
    TOLERANCE_FACTOR,
    Crossings,
    Params,
    check_tolerance_factor,
)
from andoyer.kernels import dop853
from andoyer.validation import integer

__all__ = ["NumbaEngine"]




def _states(y0: NDArray[np.float64]) -> NDArray[np.float64]:
    arr = np.ascontiguousarray(y0, dtype=np.float64)
    if arr.ndim != 2 or arr.shape[1] != 6:
        raise ValueError(f"y0 must have shape (n, 6), got {arr.shape}")
    return arr


def _params(params: Params) -> NDArray[np.float64]:
    p = np.ascontiguousarray(params, dtype=np.float64)
    if p.shape != (len(dop853.PARAMS),):
        raise ValueError(f"params must be the 8 floats {dop853.PARAMS}, got shape {p.shape}")
    return p


def _raise_on_failure(info: NDArray[np.int64], what: str) -> None:
    status = info[:, dop853.INFO.index("status")]
    bad = np.flatnonzero(status != dop853.SUCCESS)
    if bad.size:
        i = int(bad[0])
        raise IntegrationError(
            f"numba DOP853 failed {what} for {bad.size} orbit(s), first orbit {i}: "
            f"{dop853.STATUS_MESSAGES[int(status[i])]} after "
            f"{int(info[i, dop853.INFO.index('accepted')])} steps")


class NumbaEngine:
    """Adaptive Dormand-Prince 8(5,3) (DOP853) in Numba, orbits in parallel.

    Parameters
    ----------
    max_steps : int, default 10**9
        Accepted steps allowed per orbit before it is reported as failed.
    chunksize : int, default 1
        Orbits handed to a thread at a time (:func:`andoyer.kernels.threads.over_orbits`);
        1 balances orbits of unequal cost (0 splits the orbits evenly up front).
    tolerance_factor : float, default :data:`andoyer.integrate.engines.base.TOLERANCE_FACTOR`
        The controller is given ``tolerance_factor * rtol`` and ``tolerance_factor *
        atol`` (see the module notes); 1.0 gives SciPy's meaning of the tolerances.

    Notes
    -----
    Crossings are located on the order-7 dense output of the step that brackets a
    sign change of the section function, by Brent's method to round-off in the step
    fraction, so ``|f|`` at a crossing is at the round-off level of ``f`` at any t.
    See :mod:`andoyer.kernels.dop853`.

    Examples
    --------
    >>> import numpy as np
    >>> from andoyer import RigidBody, from_andoyer
    >>> body = RigidBody.paper()
    >>> y0 = from_andoyer([[0.3, 1.1, 0.2, 1.0, -0.4]])
    >>> y = NumbaEngine().propagate(y0, np.array([0.0, 10.0]), (*body.params, body.phi0),
    ...                             1e-12, 1e-12)
    >>> y.shape
    (1, 2, 6)
    """

    name = "numba"

    def __init__(self, *, max_steps: int = 10**9, chunksize: int = 1,
                 tolerance_factor: float = TOLERANCE_FACTOR) -> None:
        max_steps = integer("max_steps", max_steps, 1)
        chunksize = integer("chunksize", chunksize, 0)
        self.max_steps = max_steps
        self.chunksize = int(chunksize)
        self.tolerance_factor = check_tolerance_factor(tolerance_factor)

    def __repr__(self) -> str:
        return (f"NumbaEngine(max_steps={self.max_steps}, chunksize={self.chunksize}, "
                f"tolerance_factor={self.tolerance_factor})")

    def propagate(self, y0: NDArray[np.float64], t: NDArray[np.float64], params: Params,
                  rtol: float, atol: float) -> NDArray[np.float64]:
        """States at times ``t`` (k,) of the orbits from ``y0`` (n, 6): shape (n, k, 6).

        ``t`` is non-decreasing and ``t[0]`` is the initial time; the states between
        steps are read off the dense output (no step is shortened to hit an output
        time, except the last one).
        """
        y = _states(y0)
        times = np.ascontiguousarray(t, dtype=np.float64)
        if times.ndim != 1:
            raise ValueError(f"t must have shape (k,), got {times.shape}")
        if y.shape[0] == 0 or times.size == 0:
            return np.empty((y.shape[0], times.size, 6))
        out, info = dop853.propagate(y, times, _params(params),
                                     self.tolerance_factor * float(rtol),
                                     self.tolerance_factor * float(atol), self.max_steps,
                                     block=self.chunksize)
        _raise_on_failure(info, "in propagate")
        return out

    def crossings(self, y0: NDArray[np.float64], params: Params, kind: int, value: float,
                  direction: int, n_crossings: int, t_max: float, rtol: float,
                  atol: float) -> Crossings:
        """The first ``n_crossings`` crossings after t = 0 of ``SECTION_KINDS[kind] =
        value`` in ``direction`` (+1, -1, 0), integrating at most to ``t_max``."""
        y = _states(y0)
        n_crossings = int(n_crossings)
        if y.shape[0] == 0 or n_crossings == 0:
            n = y.shape[0]
            return Crossings(np.full((n, n_crossings), np.nan),
                                  np.full((n, n_crossings, 6), np.nan),
                                  np.zeros(n, dtype=np.int64))
        tc, yc, count, info = dop853.locate_crossings(
            y, _params(params), int(kind), float(value), int(direction), n_crossings,
            float(t_max), self.tolerance_factor * float(rtol),
            self.tolerance_factor * float(atol), self.max_steps, block=self.chunksize)
        _raise_on_failure(info, "while locating crossings")
        return Crossings(tc, yc, count)
