"""The heyoka engine: Taylor integration compiled with LLVM (heyoka.py).

The Euler-Poisson vector field (1) and every section function are taken from the
SymPy expressions of :mod:`andoyer.symbolic` and converted with
:func:`heyoka.from_sympy` (:mod:`andoyer.integrate.engines.heyoka_symbolic`); nothing is
typed by hand. The body and the section enter as runtime parameters ``par[i]`` in the
order of :data:`~andoyer.integrate.engines.heyoka_symbolic.PARAMETERS`
(``a, b, c, mu, e1, e2, e3, phi0, value, cv, sv``), so one compiled integrator
serves every body, section value and initial state.

Compiled integrators are built once per process and kept in a pool keyed by what
changes the generated code (batch size, section kind, direction, tolerance); a
thread takes one from the pool, resets time, state and parameters, and gives it
back. heyoka's own caches make a rebuild cheap: an in-memory cache within the
process and, since heyoka 7.10, an on-disk cache shared by all processes
(``~/.cache/heyoka`` or ``$HEYOKA_CACHE_DIR``), so a second process skips the LLVM
optimisation and code generation.

Tolerances
----------
heyoka controls the local error of each Taylor step with a single ``tol``: the
error estimate is kept below ``tol`` in absolute terms while ``||y||_inf <= 1`` and
below ``tol ||y||_inf`` above (the Taylor order is chosen from ``tol``, about 15 at
1e-12). The engine uses ``tol = min(rtol, atol)``, which satisfies the mixed
criterion ``err <= atol + rtol |y|`` of the other engines for any state size
(``|gamma| = 1`` and ``|G|`` of order one in this problem).

Sections
--------
A crossing of ``SECTION_KINDS[kind] = value`` is a root of the section function
``f`` (:func:`andoyer.symbolic.sections.section_function`) found by heyoka as a
non-terminal event: the roots of the Taylor polynomial of ``f`` over each step,
with the requested direction of ``f``. The event callback only records the event
time and the dense-output state there (``update_d_output``; a non-terminal callback
must not change the integrator). After the propagation, in NumPy:

* the state is polished onto the section with one Newton step in time,
  ``dt = -f/(df/dt)``, ``y += dt F(y)`` (``df/dt = grad f . F`` differentiated by
  heyoka, evaluated by a compiled function): the event time handed to the callback
  is rounded to a double, which leaves an error in ``|f|`` growing with t --
  about 1e-12 at t ~ 3e4; after the step ``|f|`` is at round-off level;
* crossings with margin ``w <= 0`` (the antipodal root of an angle section,
  ``alpha = value + pi``) are dropped;
* a root at ``t <= T_START`` (1e-10) is the initial state itself lying on the
  section to round-off (heyoka reports a root at the very start of the first
  step) and is dropped, so that "crossings after t = 0" does not depend on the
  sign of the round-off in ``f(y0)``.

An orbit stops after ``n_crossings`` accepted crossings: the propagation runs in
chunks of steps (``max_steps``) and to end times predicted from the crossings found
so far, so no Python code runs per step; per crossing, the callback does one list
append (the polish and the bookkeeping are vectorised per chunk).

Parallelism and scheduling
--------------------------
Independent orbits run on a thread pool: heyoka releases the GIL while it
integrates (event callbacks take it back briefly). With ``batch_size > 1`` a
propagation task is one batch (SIMD) integrator over ``batch_size`` orbits. For
crossings each thread owns one batch integrator and feeds its lanes from a shared
queue of orbits; lanes are independent in heyoka's batch mode (own time, step size
and end time), and a SIMD step costs the same whether or not a lane is busy, so the
schedule keeps the lanes full:

1. a pilot: every orbit takes ``_PILOT_STEPS`` steps (its crossings are kept), which
   measures its return time and its steps per unit time;
2. the orbits are queued longest first (most steps still to go), so that no thread
   is left with a long orbit while the others idle;
3. each lane runs to the predicted time of its orbit's last wanted crossing (half a
   return later); a chunk ends when the first lane should be done, and a lane whose
   orbit is done takes the next orbit from the queue.

Nearly every SIMD lane-step is useful (measured: benchmarks/NOTES.md#heyoka-engine).
Two traps are avoided this way: a terminal event in one lane of a batch integrator
stops every lane, and ``heyoka.ensemble_propagate_until`` takes one end time for all
orbits (and deep-copies the integrator for each one).

What remains per crossing is heyoka's Python event callback (a few microseconds,
under the GIL): it bounds sections whose crossings are only a few steps apart.
"""

from __future__ import annotations

import math
import os
import threading
from collections.abc import Callable, Sequence
from concurrent.futures import ThreadPoolExecutor
from functools import cache, partial
from typing import NamedTuple, TypeVar

import numpy as np
from numpy.typing import NDArray

from andoyer.integrate.engines import heyoka_tangent
from andoyer.integrate.engines.base import (
    MAX_BATCH,
    MAX_THREADS,
    Capability,
    Crossings,
    EngineBase,
    Section,
    TangentFlow,
    Tolerance,
)
from andoyer.integrate.engines.heyoka_integrators import (
    ATTITUDE,
    NO_SECTION,
    BatchRecorder,
    IntegratorKey,
    Recorder,
    borrow,
    check_outcome,
    warm_up,
)
from andoyer.integrate.engines.heyoka_symbolic import (
    field_at,
    field_cfunc,
    section_cfunc,
)
from andoyer.integrate.engines.lazy import heyoka as hy
from andoyer.kernels.common import T_START
from andoyer.validation import integer

# The expressions (heyoka_system, section functions, PARAMETERS) are built in
# andoyer.integrate.engines.heyoka_symbolic, the one SymPy -> heyoka builder.
__all__ = ["HeyokaEngine", "PLAIN_SIMD_MULTIPLE", "T_START", "tolerance", "warm_up"]

_T = TypeVar("_T")
_MAX_POLISH = 1e-6  # largest Newton time step of the crossing polish


@cache
def _simd_size() -> int:
    """:func:`heyoka.recommended_simd_size`, asked once (it is a short call's fixed cost)."""
    return int(hy.recommended_simd_size())


def tolerance(rtol: float, atol: float) -> float:
    """heyoka's single tolerance for the other engines' ``(rtol, atol)``: ``min(rtol, atol)``
    (:attr:`Tolerance.tol <andoyer.integrate.engines.base.Tolerance.tol>`).

    Parameters
    ----------
    rtol, atol : float
        The relative and absolute tolerances asked for.
    """
    return Tolerance(rtol, atol).tol




# ----------------------------------------------------------------------------- propagate


def _propagate_scalar(key: IntegratorKey, y0: NDArray[np.float64], t: NDArray[np.float64],
                      par: NDArray[np.float64]) -> NDArray[np.float64]:
    with borrow(key) as slot:
        ta = slot.ta
        ta.time = float(t[0])
        ta.state[:] = y0
        ta.pars[:] = par[:slot.n_pars]
        res = ta.propagate_grid(t)
        check_outcome(res[0], "propagate_grid")
        return np.array(res[-1])


def _propagate_batch(key: IntegratorKey, y0: NDArray[np.float64], t: NDArray[np.float64],
                     par: NDArray[np.float64]) -> NDArray[np.float64]:
    m = key.batch_size
    k = y0.shape[0]
    lanes = np.concatenate([y0, np.repeat(y0[-1:], m - k, axis=0)]) if k < m else y0
    with borrow(key) as slot:
        ta = slot.ta
        ta.set_time(np.full(m, t[0]))
        ta.state[:] = lanes.T
        ta.pars[:] = par[:slot.n_pars, None]
        out = ta.propagate_grid(np.repeat(t, m).reshape(-1, m))[-1]
        for r in ta.propagate_res:
            check_outcome(r[0], "propagate_grid")
        return np.transpose(out, (2, 0, 1))[:k]


# ----------------------------------------------------------------------------- crossings


class _Found(NamedTuple):
    t: NDArray[np.float64]
    y: NDArray[np.float64]
    lane: NDArray[np.int64] | None = None  # batch lane of each crossing, where known


def _accept(kind: int, t: Sequence[float] | NDArray[np.float64],
            y: Sequence[NDArray[np.float64]], par: NDArray[np.float64],
            lane: NDArray[np.int64] | None = None) -> _Found:
    """Newton-polish raw event states onto the section, drop w <= 0 and t <= T_START."""
    if len(t) == 0:
        return _Found(np.empty(0), np.empty((0, 6)), np.empty(0, dtype=np.int64))
    T = np.asarray(t, dtype=float)
    Y = np.array(y, dtype=float)  # (r, 6)
    cf = section_cfunc(kind)
    P = np.broadcast_to(par[:cf.nparams, None], (cf.nparams, T.size))
    f, w, fdot = cf(np.ascontiguousarray(Y.T), pars=np.ascontiguousarray(P))
    with np.errstate(divide="ignore", invalid="ignore"):
        dt = -f / fdot
    # Expected |dt|: a few ulp of t. A larger step (a nearly tangent crossing) is not
    # taken: the first-order update below would not be accurate.
    dt = np.where(np.abs(dt) <= _MAX_POLISH, dt, 0.0)
    F = field_at(Y, par)
    Y = Y + dt[:, None] * F
    T = T + dt
    keep = (w > 0.0) & (T > T_START)
    return _Found(T[keep], Y[keep], None if lane is None else lane[keep])


def _chunk_steps(n_missing: int, steps: int, found: int) -> int:
    """Steps for the next chunk: the remaining crossings times the steps per crossing."""
    if found == 0:
        return max(64, 2 * steps)
    return max(8, math.ceil(n_missing * steps / found) + 2)


def _crossings_scalar(key: IntegratorKey, y0: NDArray[np.float64], par: NDArray[np.float64],
                      n_crossings: int, t_max: float) -> _Found:
    with borrow(key) as slot:
        ta, rec = slot.ta, slot.recorder
        assert isinstance(rec, Recorder)
        rec.clear()
        ta.time = 0.0
        ta.state[:] = y0
        ta.pars[:] = par[:slot.n_pars]
        found: list[_Found] = []
        n_found = steps = 0
        chunk = 64
        while True:
            outcome, _, _, nsteps, _, _ = ta.propagate_until(t_max, max_steps=chunk)
            check_outcome(outcome, "looking for crossings")
            steps += nsteps
            new = _accept(key.kind, rec.t, rec.y, par)
            rec.clear()
            found.append(new)
            n_found += new.t.size
            if n_found >= n_crossings or outcome == hy.taylor_outcome.time_limit:
                break
            chunk = _chunk_steps(n_crossings - n_found, steps, n_found)
    return _concat(found, n_crossings)


class _Orbit:
    """One orbit of a batched section run: where it is, and the crossings found so far."""

    __slots__ = ("index", "y", "hi", "lo", "steps", "parts", "n", "t_first", "t_last")

    def __init__(self, index: int, y0: NDArray[np.float64]) -> None:
        self.index = index
        self.y = y0
        self.hi = self.lo = 0.0  # double-length time, as heyoka keeps it
        self.steps = 0
        self.parts: list[_Found] = []
        self.n = 0
        self.t_first = self.t_last = math.nan

    def add(self, found: _Found) -> None:
        if found.t.size:
            if self.n == 0:
                self.t_first = float(found.t[0])
            self.t_last = float(found.t[-1])
            self.n += found.t.size
            self.parts.append(found)

    def done(self, n_crossings: int, t_max: float) -> bool:
        return self.n >= n_crossings or self.hi >= t_max

    def return_time(self) -> float:
        """Mean time between crossings so far (NaN before the first crossing)."""
        if self.n >= 2:
            return (self.t_last - self.t_first) / (self.n - 1)
        return self.hi / self.n if self.n else math.nan

    def end_time(self, n_crossings: int, t_max: float) -> float:
        """Predicted time of the last crossing wanted, half a return later; ``t_max``
        while the return time is unknown."""
        r = self.return_time()
        if not math.isfinite(r):
            return t_max
        return min(t_max, self.hi + (n_crossings - self.n + 0.5) * r)

    def steps_to(self, t_end: float) -> float:
        """Steps to ``t_end`` at the step rate seen so far."""
        rate = self.steps / self.hi if self.hi > 0.0 else 1.0
        return max(0.0, t_end - self.hi) * rate


class _Queue:
    """A thread-safe queue of orbits shared by the batch workers."""

    def __init__(self, orbits: Sequence[_Orbit]) -> None:
        self._orbits = list(orbits)
        self._next = 0
        self._lock = threading.Lock()

    def pop(self) -> _Orbit | None:
        with self._lock:
            if self._next >= len(self._orbits):
                return None
            self._next += 1
            return self._orbits[self._next - 1]


#: Steps every orbit takes first (the pilot), to measure its return time and step
#: rate; then the orbits are scheduled longest first.
_PILOT_STEPS = 512
#: Most steps of one chunk of a batch integrator, between two looks at its lanes.
_MAX_CHUNK = 16384
_MIN_CHUNK = 32


def _split_by_lane(kind: int, rows: list[tuple[int, float, NDArray[np.float64]]],
                   par: NDArray[np.float64], m: int) -> list[_Found]:
    """Polish all roots of a chunk at once and split them by lane, in time order."""
    lane = np.fromiter((r[0] for r in rows), dtype=np.int64, count=len(rows))
    t = np.fromiter((r[1] for r in rows), dtype=float, count=len(rows))
    order = np.lexsort((t, lane))
    lane = lane[order]
    found = _accept(kind, t[order], [rows[q][2] for q in order.tolist()], par, lane)
    assert found.lane is not None
    bounds = np.searchsorted(found.lane, np.arange(m + 1))
    return [_Found(found.t[bounds[j]:bounds[j + 1]], found.y[bounds[j]:bounds[j + 1]])
            for j in range(m)]


def _crossings_batch_worker(key: IntegratorKey, par: NDArray[np.float64], n_crossings: int,
                            t_max: float, queue: _Queue, budget: int | None) -> None:
    """Run the orbits of ``queue`` through the lanes of one batch integrator.

    Each lane runs its own orbit with its own end time (heyoka's batch lanes are
    independent: own time, step size and end time). A lane's end time is the
    predicted time of its orbit's last wanted crossing; a chunk stops when the first
    lane should be done (at most ``_MAX_CHUNK`` steps), and a lane whose orbit is done
    takes the next orbit from the queue, so lanes seldom idle. With ``budget`` each
    orbit leaves its lane after that many steps (the pilot), keeping its state.
    """
    m = key.batch_size
    with borrow(key) as slot:
        ta, rec = slot.ta, slot.recorder
        assert isinstance(rec, BatchRecorder)
        rec.clear()
        ta.pars[:] = par[:slot.n_pars, None]
        lanes: list[_Orbit | None] = [None] * m
        taken = np.zeros(m, dtype=np.int64)  # steps of the lane's orbit in this phase
        state = np.empty((6, m))
        hi, lo = np.zeros(m), np.zeros(m)

        def load(j: int) -> None:
            orbit = queue.pop()
            lanes[j] = orbit
            taken[j] = 0
            if orbit is not None:
                state[:, j] = orbit.y
                hi[j], lo[j] = orbit.hi, orbit.lo

        for j in range(m):
            load(j)
        if lanes[0] is None:
            return
        for j in range(1, m):  # idle lanes: any finite state, held at their time
            if lanes[j] is None:
                state[:, j], hi[j], lo[j] = state[:, 0], 0.0, 0.0
        while True:
            t_end = hi.copy()
            chunk = float(_MAX_CHUNK)
            for j, orbit in enumerate(lanes):
                if orbit is None:
                    continue
                if budget is None:
                    t_end[j] = orbit.end_time(n_crossings, t_max)
                    chunk = min(chunk, orbit.steps_to(t_end[j]) + 8.0)
                else:
                    t_end[j] = t_max
                    chunk = min(chunk, float(budget - taken[j]))
            ta.state[:] = state
            ta.set_dtime(hi, lo)
            ta.propagate_until(t_end, max_steps=max(_MIN_CHUNK, math.ceil(chunk)))
            res = ta.propagate_res
            found = _split_by_lane(key.kind, rec.rows, par, m) if rec.rows else None
            rec.clear()
            state = np.array(ta.state)
            hi, lo = (np.array(a, dtype=float) for a in ta.dtime)
            for j, orbit in enumerate(lanes):
                if orbit is None:
                    continue
                check_outcome(res[j][0], "looking for crossings")
                orbit.steps += res[j][3]
                taken[j] += res[j][3]
                if found is not None:
                    orbit.add(found[j])
                orbit.y = state[:, j].copy()
                orbit.hi, orbit.lo = float(hi[j]), float(lo[j])
                if orbit.done(n_crossings, t_max) or (budget is not None
                                                      and taken[j] >= budget):
                    load(j)
            if all(orbit is None for orbit in lanes):
                return


def _schedule(orbits: list[_Orbit], n_crossings: int, t_max: float) -> list[_Orbit]:
    """The unfinished orbits, longest (most steps still to go) first: no thread is left
    with a long orbit at the end while the others idle."""
    todo = [o for o in orbits if not o.done(n_crossings, t_max)]
    return sorted(todo, key=lambda o: -o.steps_to(o.end_time(n_crossings, t_max)))


def _concat(parts: list[_Found], n: int) -> _Found:
    if not parts:
        return _Found(np.empty(0), np.empty((0, 6)))
    return _Found(np.concatenate([f.t for f in parts])[:n],
                  np.concatenate([f.y for f in parts])[:n])


# ----------------------------------------------------------------------------- engine


def _run(tasks: Sequence[Callable[[], _T]], n_threads: int) -> list[_T]:
    """Run independent tasks on up to ``n_threads`` threads (heyoka releases the GIL)."""
    if n_threads <= 1 or len(tasks) <= 1:
        return [task() for task in tasks]
    with ThreadPoolExecutor(max_workers=min(n_threads, len(tasks))) as pool:
        return list(pool.map(lambda task: task(), tasks))


#: SIMD vectors per lane group of the FLI maps' 12-variable tangent flow (its default
#: batch size is this times :func:`heyoka.recommended_simd_size`; measured, see
#: :class:`HeyokaEngine`).
PLAIN_SIMD_MULTIPLE = 2


class HeyokaEngine(EngineBase):
    """Taylor integration of the Euler-Poisson equations with heyoka.py.

    Parameters
    ----------
    batch_size : int, optional
        Orbits integrated together by one SIMD (batch-mode) integrator. Default:
        :func:`heyoka.recommended_simd_size` (4 doubles with AVX2) whenever there are at
        least that many orbits, else 1 (scalar integrators); the 12-variable tangent flow
        of the FLI maps (``tangent(renormalise=False)``, one vector) takes
        :data:`PLAIN_SIMD_MULTIPLE` times that (two SIMD vectors per operation are
        faster; measured: benchmarks/NOTES.md#heyoka-engine). At most
        :data:`~andoyer.integrate.engines.values.MAX_BATCH`.
    n_threads : int, optional
        Threads running independent orbits or batches (at most
        :data:`~andoyer.integrate.engines.values.MAX_THREADS`); default ``os.cpu_count()``.

    Notes
    -----
    See the module docstring for the tolerance mapping and for how crossings are
    located. The first call with new settings compiles (or loads from heyoka's
    on-disk cache) an integrator; later calls reuse it.
    """

    name = "heyoka"
    n_threads: int  # always a count here (default: every core), never None
    repr_options = ("batch_size", "n_threads")
    tangent_method = "heyoka var_ode_sys"
    capabilities = frozenset(Capability)  # everything, extended precision included
    native_backward = frozenset({"tangent_crossings"})

    def __init__(self, *, batch_size: int | None = None, n_threads: int | None = None) -> None:
        self.batch_size = (None if batch_size is None
                           else integer("batch_size", batch_size, 1, MAX_BATCH))
        self.n_threads = (integer("n_threads", n_threads, 1, MAX_THREADS)
                          if n_threads is not None else (os.cpu_count() or 1))
        self._ensemble = 0  # for_ensemble: the default batch sizes are those of n orbits

    def versions(self) -> dict[str, str]:
        return {"heyoka_version": str(hy.__version__)}

    def clear_memory_cache(self) -> None:
        heyoka_tangent.clear_memory_cache()

    def _batch(self, n: int, multiple: int = 1) -> int:
        if self.batch_size is not None:
            return self.batch_size
        simd = _simd_size()
        n = max(n, self._ensemble)
        return multiple * simd if n >= multiple * simd else simd if n >= simd else 1

    def for_ensemble(self, n: int) -> HeyokaEngine:
        """This engine with the batch sizes of ``n`` orbits fixed, so that chunks of fewer
        orbits (the last one) run in the same SIMD code (the same round-off)."""
        if self.batch_size is not None:
            return self
        engine = HeyokaEngine(n_threads=self.n_threads)
        engine._ensemble = max(int(n), self._ensemble)
        return engine

    def _tangent(self, y0: NDArray[np.float64], w0: NDArray[np.float64],
                 t: NDArray[np.float64], par: NDArray[np.float64], tolerance: Tolerance,
                 renormalise: bool, scale: float) -> TangentFlow:
        """Renormalised: the SIMD/threaded system of :mod:`.heyoka_tangent`; else, for one
        vector per orbit and orbits enough to fill SIMD lanes, the 12-variable system
        (state and ``w' = J w``) in the same blocks and threads, and otherwise the
        fundamental matrix (``var_ode_sys``, compact mode), orbit by orbit."""
        if not renormalise:
            batch = self._batch(y0.shape[0], PLAIN_SIMD_MULTIPLE)
            if w0.shape[1] == 1 and batch > 1 and t[-1] > t[0]:
                return heyoka_tangent.plain_flow(y0, w0, t, par, tolerance.tol, batch,
                                                 self.n_threads)
            return heyoka_tangent.matrix_flow(y0, w0, t, par, tolerance.tol)
        return heyoka_tangent.renormalised_flow(y0, w0, t, par, tolerance.tol, scale,
                                                self._batch(y0.shape[0]), self.n_threads)

    def _tangent_crossings(self, y0: NDArray[np.float64], w0: NDArray[np.float64],
                           par: NDArray[np.float64], event: Section, n_crossings: int,
                           t_max: float, tolerance: Tolerance,
                           extended_precision: bool) -> TangentFlow:
        """The fundamental matrix stopped by a terminal event, in double or extended
        precision, forward or (``t_max < 0``) backward."""
        return heyoka_tangent.matrix_crossings(y0, w0, par, event, n_crossings, t_max,
                                               tolerance.tol, extended_precision)

    def warm_up(self, capability: Capability, tolerance: Tolerance, *, n: int = 1,
                k: int = 1) -> tuple[str, float]:
        """Compile (or load) the integrator of a tangent flow of ``n`` orbits now."""
        if capability is not Capability.TANGENT:
            return super().warm_up(capability, tolerance, n=n, k=k)
        return heyoka_tangent.warm_up(batch_size=self._batch(n), tol=tolerance.tol, k=k)

    def _propagate(self, y0: NDArray[np.float64], t: NDArray[np.float64],
                   par: NDArray[np.float64], tolerance: Tolerance) -> NDArray[np.float64]:
        tol = tolerance.tol
        n = y0.shape[0]
        m = self._batch(n)
        key = IntegratorKey(m, NO_SECTION, 0, tol)
        if m == 1:
            rows = _run([partial(_propagate_scalar, key, y0[i], t, par) for i in range(n)],
                        self.n_threads)
            return np.stack(rows)
        blocks = _run([partial(_propagate_batch, key, y0[s:s + m], t, par)
                       for s in range(0, n, m)], self.n_threads)
        return np.concatenate(blocks)

    def _attitude(self, z0: NDArray[np.float64], t: NDArray[np.float64],
                  par: NDArray[np.float64], tolerance: Tolerance) -> NDArray[np.float64]:
        """A scalar integrator of (1) with the quaternion
        (:func:`~andoyer.integrate.engines.heyoka_symbolic.attitude_system`) per orbit,
        orbits in threads."""
        key = IntegratorKey(1, ATTITUDE, 0, tolerance.tol)
        rows = _run([partial(_propagate_scalar, key, z0[i], t, par)
                     for i in range(z0.shape[0])], self.n_threads)
        return np.stack(rows)

    def _crossings(self, y0: NDArray[np.float64], par: NDArray[np.float64],
                   event: Section, n_crossings: int, t_max: float,
                   tolerance: Tolerance) -> Crossings:
        kind, direction, tol = event.kind, event.direction, tolerance.tol
        n = y0.shape[0]
        t_out = np.full((n, n_crossings), np.nan)
        y_out = np.full((n, n_crossings, 6), np.nan)
        count = np.zeros(n, dtype=np.int64)
        m = self._batch(n)
        section_cfunc(kind)  # compile once, outside the threads
        field_cfunc()
        key = IntegratorKey(m, kind, direction, tol)
        results: list[_Found | None]
        if m == 1:
            results = list(_run([partial(_crossings_scalar, key, y0[i], par, n_crossings,
                                         float(t_max)) for i in range(n)], self.n_threads))
        else:
            orbits = [_Orbit(i, y0[i]) for i in range(n)]
            n_workers = min(self.n_threads, -(-n // m))
            # The pilot: every orbit takes a few hundred steps (its first crossings are
            # kept), which measures its return time and step rate ...
            queue = _Queue(orbits)
            _run([partial(_crossings_batch_worker, key, par, n_crossings, float(t_max),
                          queue, _PILOT_STEPS)] * n_workers, n_workers)
            # ... then the rest, longest first, lanes refilled as orbits finish.
            queue = _Queue(_schedule(orbits, n_crossings, float(t_max)))
            _run([partial(_crossings_batch_worker, key, par, n_crossings, float(t_max),
                          queue, None)] * n_workers, n_workers)
            results = [_concat(o.parts, n_crossings) for o in orbits]
        for i, r in enumerate(results):
            assert r is not None
            c = r.t.size
            count[i] = c
            t_out[i, :c] = r.t
            y_out[i, :c] = r.y
        return Crossings(t_out, y_out, count)
