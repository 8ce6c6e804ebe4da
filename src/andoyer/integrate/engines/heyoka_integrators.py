"""Part of the heyoka engine (:class:`~andoyer.integrate.engines.heyoka_engine.HeyokaEngine`):
its compiled integrators, built from :mod:`andoyer.integrate.engines.heyoka_symbolic` and
lent from one pool per process.

An integrator is keyed by ``(batch size, section kind, direction, tolerance)``
(:class:`IntegratorKey`): the plain propagation integrator (kind ``-1``), the attitude
integrator (kind ``-2``, 10 variables) or one with a non-terminal event on a section
function whose callback records each root (:class:`Recorder`, :class:`BatchRecorder`:
one list append per root, under the GIL). A thread borrows an integrator for a key
(:func:`borrow`) and gives it back; the first borrow compiles it (or loads it from
heyoka's caches), :func:`warm_up` does so before a timed run.
"""

from __future__ import annotations

import threading
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import NDArray

from andoyer.errors import IntegrationError
from andoyer.integrate.engines.heyoka_symbolic import (
    attitude_system,
    heyoka_system,
    section_cfunc,
    section_exprs,
)
from andoyer.integrate.engines.lazy import heyoka as hy

__all__ = ["warm_up", "borrow", "check_outcome", "IntegratorKey", "Slot", "Recorder",
           "BatchRecorder", "NO_SECTION", "ATTITUDE"]

#: Crossing direction -> name of heyoka's event_direction (looked up at use: heyoka is
#: imported lazily).
_DIRECTIONS = {1: "positive", -1: "negative", 0: "any"}

NO_SECTION = -1
ATTITUDE = -2  # the attitude integrator (10 variables), scalar


class Recorder:
    """Non-terminal event callback: records (time, dense-output state) at each root."""

    def __init__(self) -> None:
        self.t: list[float] = []
        self.y: list[NDArray[np.float64]] = []

    def __call__(self, ta: Any, time: float, d_sgn: int) -> None:
        self.t.append(time)
        self.y.append(ta.update_d_output(time).copy())

    def clear(self) -> None:
        self.t.clear()
        self.y.clear()


class BatchRecorder:
    """Batch version: records ``(lane, time, dense-output state)`` at each root.

    One list append per root: this runs once per crossing under the GIL, so it does
    as little as possible (the polish and the bookkeeping are done per chunk).

    Parameters
    ----------
    batch_size : int
        SIMD lanes of the batch integrator.
    """

    def __init__(self, batch_size: int) -> None:
        self.batch_size = batch_size
        self.rows: list[tuple[int, float, NDArray[np.float64]]] = []

    def __call__(self, ta: Any, time: float, d_sgn: int, lane: int) -> None:
        # Dense output is evaluated for all lanes at once; only ``lane`` is meaningful.
        # (A tuple argument is converted faster than an array.)
        d = ta.update_d_output((time,) * self.batch_size)
        self.rows.append((lane, time, d[:, lane].copy()))

    def clear(self) -> None:
        self.rows.clear()


class IntegratorKey(NamedTuple):
    """What a compiled heyoka integrator of the pool is built for.

    Parameters
    ----------
    batch_size : int
        SIMD lanes (1: a scalar integrator).
    kind : int
        Section kind (an index of the generated section kinds), or ``NO_SECTION`` for
        plain propagation.
    direction : {+1, -1}
        Direction of integration in time.
    tol : float
        heyoka's tolerance.
    """

    batch_size: int
    kind: int  # NO_SECTION for plain propagation
    direction: int
    tol: float


class Slot(NamedTuple):
    """A compiled integrator of the pool and what goes with it.

    Parameters
    ----------
    ta : heyoka.taylor_adaptive or heyoka.taylor_adaptive_batch
        The integrator.
    recorder : Recorder, BatchRecorder or None
        Its event callback (None without a section).
    n_pars : int
        Number of runtime parameters it takes.
    """

    ta: Any
    recorder: Recorder | BatchRecorder | None
    n_pars: int


def _build(key: IntegratorKey) -> Slot:
    common: dict[str, Any] = {"tol": key.tol, "compact_mode": False}
    if key.kind == ATTITUDE:
        ta = hy.taylor_adaptive(list(attitude_system()), [0.0] * 10, **common)
        return Slot(ta, None, int(np.shape(ta.pars)[0]))
    system = list(heyoka_system(scalar=key.batch_size == 1))
    if key.kind == NO_SECTION:
        if key.batch_size == 1:
            ta = hy.taylor_adaptive(system, [0.0] * 6, **common)
        else:
            ta = hy.taylor_adaptive_batch(system, np.zeros((6, key.batch_size)), **common)
        return Slot(ta, None, int(np.shape(ta.pars)[0]))
    f = section_exprs(key.kind)[0]
    direction = getattr(hy.event_direction, _DIRECTIONS[key.direction])
    if key.batch_size == 1:
        ev = hy.nt_event(f, Recorder(), direction=direction)
        ta = hy.taylor_adaptive(system, [0.0] * 6, nt_events=[ev], **common)
    else:
        ev = hy.nt_event_batch(f, BatchRecorder(key.batch_size), direction=direction)
        ta = hy.taylor_adaptive_batch(system, np.zeros((6, key.batch_size)),
                                      nt_events=[ev], **common)
    # Events deep-copy their callback: the integrator's own copy records.
    return Slot(ta, ta.nt_events[0].callback, int(np.shape(ta.pars)[0]))


_POOL: dict[IntegratorKey, list[Slot]] = {}
_POOL_LOCK = threading.Lock()


@contextmanager
def borrow(key: IntegratorKey) -> Iterator[Slot]:
    """Borrow a compiled integrator for ``key`` from the process-wide pool.

    Parameters
    ----------
    key : IntegratorKey
        What the integrator is built for (built on first use, then shared).
    """
    with _POOL_LOCK:
        free = _POOL.setdefault(key, [])
        slot = free.pop() if free else None
    if slot is None:
        slot = _build(key)
    try:
        yield slot
    finally:
        with _POOL_LOCK:
            _POOL[key].append(slot)


def warm_up(*, batch_size: int = 1, kind: int = NO_SECTION, direction: int = 1,
            tol: float = 1e-12) -> None:
    """Build (or load from heyoka's caches) the integrator for these settings now.

    ``kind = -1`` is the plain propagation integrator; a section kind also compiles
    the functions used to polish crossings. Useful before timing, or before a
    progress bar starts.

    Parameters
    ----------
    batch_size : int, default 1
        SIMD lanes of the integrator (1: scalar).
    kind : int, default -1
        Section kind (an index of the generated section kinds), or -1 for the plain
        propagation integrator.
    direction : {+1, -1}, default 1
        Direction of integration in time.
    tol : float, default 1e-12
        heyoka's tolerance.
    """
    with borrow(IntegratorKey(batch_size, kind, direction, tol)):
        pass
    if kind != NO_SECTION:
        section_cfunc(kind)


def check_outcome(outcome: Any, what: str) -> None:
    """:class:`~andoyer.errors.IntegrationError` unless heyoka stopped at the time or
    step limit asked for (a non-finite state or step stops it otherwise).

    Parameters
    ----------
    outcome : heyoka.taylor_outcome
        The outcome of a ``propagate_*`` call.
    what : str
        What was integrated, named in the error.
    """
    if outcome in (hy.taylor_outcome.time_limit, hy.taylor_outcome.step_limit):
        return
    raise IntegrationError(
        f"heyoka stopped {what} with outcome {outcome!r} (non-finite state or step)")
