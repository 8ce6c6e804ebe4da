"""What a SciPy user writes without andoyer: ``solve_ivp(method="DOP853")`` in a loop.

* ``orbit``: one orbit on an output grid (``t_eval``).
* ``section``: the upward crossings of a section, from solve_ivp's event location,
  integrating in spans sized from the crossing rate seen so far until there are
  enough (a terminal event counting occurrences would also count the antipodal roots
  of an angle section, and a restart on a root may report it twice).
* ``section_pool``: the same, one orbit per task of a ``multiprocessing`` pool.
"""

from __future__ import annotations

from multiprocessing import get_context
from typing import Any

import numpy as np
from benchmarks.peers.model import T_START, numpy_section, rhs
from scipy.integrate import solve_ivp

#: First time span integrated, and the longest time integrated, looking for crossings.
FIRST_SPAN, HORIZON = 1000.0, 1e7


def orbit(p: dict[str, float], y0: np.ndarray, t: np.ndarray, rtol: float,
          atol: float) -> np.ndarray:
    """States on the grid ``t``: shape (len(t), 6)."""
    sol = solve_ivp(rhs(p), (t[0], t[-1]), y0, method="DOP853", t_eval=t, rtol=rtol,
                    atol=atol)
    return np.asarray(sol.y.T)


def _one_orbit(args: tuple[Any, ...]) -> tuple[np.ndarray, np.ndarray]:
    p, y0, name, value, n, rtol, atol = args
    fw = numpy_section(p, name, value)

    def event(_t: float, y: np.ndarray) -> float:
        return float(fw(y)[0])

    event.direction = 1  # type: ignore[attr-defined]
    f = rhs(p)
    T: list[float] = []
    Y: list[np.ndarray] = []
    t0, y, span = 0.0, np.asarray(y0, dtype=float), FIRST_SPAN
    while len(T) < n and t0 < HORIZON:
        sol = solve_ivp(f, (t0, t0 + span), y, method="DOP853", rtol=rtol, atol=atol,
                        events=event)
        for te, ye in zip(sol.t_events[0], sol.y_events[0], strict=True):
            if te > T_START and fw(ye)[1] > 0.0:
                T.append(float(te))
                Y.append(ye)
        t0, y = float(sol.t[-1]), sol.y[:, -1]
        # Next span: the time the missing crossings should take, at the rate so far.
        span = 1.02 * (n - len(T)) * t0 / len(T) + 1.0 if T else 2.0 * span
    return np.array(T[:n]), np.array(Y[:n])


def section(p: dict[str, float], y0: np.ndarray, name: str, value: float, n: int,
            rtol: float, atol: float) -> tuple[np.ndarray, np.ndarray]:
    """First ``n`` upward crossings of every orbit: times (k, n), states (k, n, 6)."""
    out = [_one_orbit((p, y, name, value, n, rtol, atol)) for y in y0]
    return np.array([o[0] for o in out]), np.array([o[1] for o in out])


def section_pool(p: dict[str, float], y0: np.ndarray, name: str, value: float, n: int,
                 rtol: float, atol: float, processes: int = 2
                 ) -> tuple[np.ndarray, np.ndarray]:
    """:func:`section` with one orbit per task on a pool of ``processes`` processes."""
    with get_context("spawn").Pool(processes) as pool:
        out = pool.map(_one_orbit, [(p, y, name, value, n, rtol, atol) for y in y0],
                       chunksize=1)
    return np.array([o[0] for o in out]), np.array([o[1] for o in out])
