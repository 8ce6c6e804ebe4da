r"""Section crossings on SIMD lanes: :func:`andoyer.kernels.taylor.flow.locate_crossings` of
many orbits (states alone), the jets of :data:`~andoyer.kernels.taylor.lanes.LANES`
orbits in one vector instruction, for every section kind.

The steps are those of :mod:`andoyer.kernels.taylor.lanes` (each lane its own Jorba-Zou
step and time, lanes refilled from the block's queue of orbits, the generated lane jets
and the vector step end); the section search is the scalar kernel's, lane by lane.
Two entry points, chosen by the section:

* **A state component** (``G3 = c``, ``gamma_i = c``, ``L = c``:
  :func:`crossings_on_lanes`): the section's jet is the lane's column of the state's
  jet, its end value ``P(h)`` and root bound from
  :func:`~andoyer.kernels.taylor.sections.end_and_bound` (the scalar kernel's
  arithmetic), the end value carried over to the lane's next step; the lanes' end values
  and bounds are one vector Horner loop (:func:`_end_and_bound`).
* **A section with a tape** (the angles theta2, g, l, theta1, psi, both directions;
  ``G``, ``J1``, ``J2``: :func:`tape_crossings_on_lanes`): the section function's jet of
  every lane from one lane-parallel pass of its tape
  (:func:`~andoyer.kernels.taylor.lane_sections.lane_tape_jet`: the tape's products as
  vector multiply-add chains), every lane's step with that jet in it (the scalar
  :func:`~andoyer.kernels.taylor.jets.section_step_size`'s arithmetic, one loop over the
  lanes: :func:`~andoyer.kernels.taylor.lane_sections.lane_section_steps`), the end
  value ``f_b`` the tape at the step's end state (one more lane-parallel pass, at
  order 0: the scalar kernel's rule, not ``P(h)``), the bound of the step's polynomial
  by a vector Horner loop (:func:`_bounds`).

In both, a step whose polynomial may reach zero (a few % of steps) runs the scalar root
isolation (:func:`~andoyer.kernels.taylor.sections.isolate`, the boundary rules of
:func:`~andoyer.kernels.taylor.sections.step_bernstein`) and, for each root, the scalar
kernel's ``record`` (the polish by one Newton step in time, the margin and ``T_START``
tests) on a copy of that lane's jets. So a lane takes the scalar kernel's steps (to
round-off: the vector code may contract the jets' sums differently) and finds the
crossings the scalar kernel finds on them -- every root of the section function,
including an angle's passages through its chart's singular set (``G = 0``,
``L = +-G``, ``|M| = G``), which :func:`andoyer.integrate.api.section_crossings`
reports apart, never as crossings, whichever kernel found them. States with tangent
vectors stay on the scalar kernel.

On many crossings these lanes take less than half the scalar kernel's time (about 0.35
of it on a component section, 0.45 on an angle section, whose tape's jet is most of
the rest), the same steps as the scalar kernel (measured:
benchmarks/NOTES.md#taylor-lane-crossings).

The blocks: orbits may differ 4x in steps, and a block's lanes idle while its last
orbits finish; from :data:`PILOT_FROM` crossings asked a pilot of every orbit's first
:data:`PILOT_CROSSINGS` crossings predicts its steps, then the orbits run again from
the start in one block per thread, balanced, longest first (:func:`locate_crossings`).
On a component section, once a block's queue is empty and at most :data:`TAIL_LANES`
lanes are busy, the scalar kernel finishes their orbits from their lanes' states
(the component loop of :data:`andoyer.kernels.taylor.flow.STATE`'s ``crossings_from``: the
same steps, the crossings found so far kept); a tape section's lanes run to the block's end.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from andoyer.kernels import common, simd
from andoyer.kernels.common import (
    INFO,
    MAX_STEPS,
    N_STATE,
    SUCCESS,
    exact_jit,
    kernel_jit,
    source_stamp,
)
from andoyer.kernels.generated import recurrences
from andoyer.kernels.taylor import flow, jets, lane_sections, lanes, sections
from andoyer.kernels.taylor.jets import fill_constants, step_to
from andoyer.kernels.taylor.lane_sections import lane_section_steps, lane_tape_jet
from andoyer.kernels.taylor.lanes import (
    LANES,
    aligned,
    lane_advance,
    lane_load,
    lane_state_jets,
    lane_steps,
)
from andoyer.kernels.taylor.sections import (
    bernstein_weights,
    isolate,
    isolation_space,
    linear_component,
    may_cross,
    section_tape,
    tape_value,
)
from andoyer.kernels.threads import over_orbits

__all__ = ["LANE_CROSSINGS_STAMP", "component", "locate_crossings", "lane_crossings_block",
           "lane_tape_crossings_block"]

_L = LANES
_N = N_STATE
_record = flow.STATE.record
_crossings_from = flow.STATE.crossings_from[sections.COMPONENT]
#: Busy lanes at most, once the queue is empty, whose orbits the scalar kernel finishes
#: (an orbit's scalar step costs about half a vector step of 4 lanes, a third of 8:
#: benchmarks/NOTES.md#taylor-lane-schedule).
TAIL_LANES = max(1, 3 * _L // 8)

#: Crossings of every orbit in the pilot run that orders the orbits (:func:`_schedule`):
#: from three, an orbit's steps to its last crossing are predicted to 1 % (to 3 % from two).
PILOT_CROSSINGS = 3
#: Crossings asked from which the pilot runs (it costs about ``PILOT_CROSSINGS /
#: n_crossings`` of the run: 3 % at most).
PILOT_FROM = 100

#: Hash of every source the compiled entry points depend on, the lane count and tuning (their
#: cache key).
LANE_CROSSINGS_STAMP = source_stamp(
    recurrences.__file__, flow.__file__, sections.__file__, jets.__file__, lanes.__file__,
    lane_sections.__file__, simd.__file__, common.__file__, __file__
) + f"-lanes{LANES}-tune{simd.TUNE}"


def component(kind: int, phi0: float, value: float) -> int:
    """The state component whose value is the section ``kind = value`` (``f = c_a y_i +
    c_c``, :func:`~andoyer.kernels.taylor.sections.linear_component`), or -1.

    Parameters
    ----------
    kind : int
        Index into the section kinds.
    phi0 : float
        The body's ``phi0``.
    value : float
        The section value.

    Examples
    --------
    >>> component(2, 0.0, 0.0), component(13, 0.0, 0.0)  # G3, theta2
    (2, -1)
    """
    tape, C = section_tape(kind, phi0, value)
    test = getattr(linear_component, "py_func", linear_component)
    return int(test(tape, C)[0])


@kernel_jit
def _take_orbit(z0, n_crossings, t_max, max_steps, X, lane, nxt, info, nothing):
    """The next orbit of the queue (from ``nxt``) that needs a step, loaded into
    ``lane``: ``(orbit, next)``, orbit -1 (the lane zeroed) when none is left."""
    simd.tune()
    while nxt < z0.shape[0]:
        i = nxt
        nxt += 1
        if n_crossings == 0 or t_max <= 0.0:
            continue
        if info[i, 1] >= max_steps:
            info[i, 0] = MAX_STEPS
            continue
        lane_load(X, lane, z0[i])
        return i, nxt
    lane_load(X, lane, nothing)
    return -1, nxt


@kernel_jit
def _goes_on(lane, orbit, t, t1, count, n_crossings, t_max, max_steps, info):
    """The lane's orbit after its step (the step counted, its time ``t1``): True when it
    goes on; else (its status set where ``max_steps`` ended it) the caller hands the lane
    to the next orbit of the queue (:func:`_take_orbit`). Small, so that it is inlined:
    with the refill inside, one call per lane and step cost as much as the bare flow's
    whole step (measured: benchmarks/NOTES.md#section-cost)."""
    simd.tune()
    i = orbit[lane]
    if i < 0:
        return False
    t[lane] = t1[lane]
    return lanes.goes_on(info, i, count[i] < n_crossings and t[lane] < t_max, max_steps)


@kernel_jit
def _end_and_bound(X, order, comp, ca, cc, hs, fb, bound):
    """:func:`~andoyer.kernels.taylor.sections.end_and_bound` of the section ``ca y_comp +
    cc`` on every lane at once (lane ``i``'s step ``hs[i]``): ``fb`` the end values,
    ``bound`` the bounds ``B_2``. Each lane's operations are the scalar ones, in the same order;
    the lanes run side by side (vector code: one Horner chain for all lanes, not one
    after the other)."""
    simd.tune()
    for lane in range(_L):
        c = ca * X[0, order, comp, lane]
        fb[lane] = c
        bound[lane] = abs(c)
    for k in range(order - 1, 1, -1):
        for lane in range(_L):
            c = ca * X[0, k, comp, lane]
            fb[lane] = fb[lane] * hs[lane] + c
            bound[lane] = bound[lane] * hs[lane] + abs(c)
    for lane in range(_L):
        fb[lane] = fb[lane] * hs[lane] + ca * X[0, 1, comp, lane]
        fb[lane] = fb[lane] * hs[lane] + (ca * X[0, 0, comp, lane] + cc)
        bound[lane] = bound[lane] * hs[lane] * hs[lane]


@kernel_jit
def crossings_on_lanes(z0, q, order, ftape, fC, wtape, wC, direction, t_max, max_steps, tc,
                       zc, count, info):
    """The first ``tc.shape[1]`` crossings in ``(0, t_max]`` of the orbits ``z0`` (n, 6)
    of a state component's section (tapes ``ftape, fC`` and margin ``wtape, wC``), as
    :func:`andoyer.kernels.taylor.flow.locate_crossings` (see the module notes)."""
    simd.tune()  # the lanes' scheduling (simd.lane_tuning)
    n_crossings = tc.shape[1]
    n = order + 1
    comp, ca, cc = linear_component(ftape, fC)
    X = aligned(n * _N * _L).reshape((1, n, _N, _L))
    m = aligned(recurrences.LANE_PRODUCTS * _L).reshape((recurrences.LANE_PRODUCTS, _L))
    h = np.empty(_L)
    hs = aligned(_L)
    a1 = np.empty(_L)
    a2 = np.empty(_L)
    tot = np.empty(_L)
    t = np.zeros(_L)
    t1 = np.zeros(_L)
    fa = np.zeros(_L)
    fb = np.zeros(_L)
    bound = np.zeros(_L)
    orbit = np.full(_L, -1, dtype=np.int64)
    # the scalar section search's work space (one lane at a time)
    Xs = np.empty((1, n, _N))
    a = np.empty(n)
    u = np.empty((max(ftape.shape[0], wtape.shape[0]), n))
    ytmp = np.empty(_N)
    P = np.empty((1, 2, _N))
    Y = np.empty((1, _N))
    W = bernstein_weights(order)
    stack, lo_s, hi_s, left, roots = isolation_space(order)
    nothing = np.empty(0)
    nxt = 0
    busy = 0
    for lane in range(_L):
        orbit[lane], nxt = _take_orbit(z0, n_crossings, t_max, max_steps, X, lane, nxt,
                                       info, nothing)
        fa[lane] = ca * X[0, 0, comp, lane] + cc
        if orbit[lane] >= 0:
            busy += 1
    while busy > 0:
        if nxt >= z0.shape[0] and busy <= TAIL_LANES:  # cheaper on the scalar kernel
            for lane in range(_L):
                i = orbit[lane]
                if i >= 0:
                    for c in range(_N):
                        Xs[0, 0, c] = X[0, 0, c, lane]
                    count[i] = _crossings_from(Xs, t[lane], fa[lane], count[i], q, order,
                                               ftape, fC, wtape, wC, direction, t_max,
                                               max_steps, tc[i], zc[i], info[i])
            return
        lane_state_jets(X, order, q, m)
        lane_steps(X, order, h, a1, a2, tot)
        for lane in range(_L):  # each lane's step (0 on idle and ended lanes)
            i = orbit[lane]
            hs[lane] = 0.0
            if i < 0:
                continue
            info[i, 3] += 1
            status, t1[lane], hs[lane] = step_to(t[lane], t_max, h[lane])
            if status != SUCCESS:
                info[i, 0] = status
                orbit[lane] = -2  # ended: refilled below
                continue
        _end_and_bound(X, order, comp, ca, cc, hs, fb, bound)
        for lane in range(_L):  # the scalar section search where a root may be
            i = orbit[lane]
            if i < 0:
                continue
            f0 = fa[lane]
            fa[lane] = fb[lane]
            a0 = ca * X[0, 0, comp, lane] + cc
            if not may_cross(f0, fb[lane], a0, ca * X[0, 1, comp, lane] * hs[lane],
                             bound[lane]):
                continue
            for k in range(n):  # the section's jet: the lane's column (column_polynomial)
                a[k] = ca * X[0, k, comp, lane]
            a[0] += cc
            found = isolate(a, order, hs[lane], W, f0, fb[lane], direction, stack, lo_s,
                            hi_s, left, roots)
            if found > 0:
                for k in range(n):
                    for c in range(_N):
                        Xs[0, k, c] = X[0, k, c, lane]
            for r in range(found):
                if count[i] < n_crossings:
                    count[i] = _record(Xs, order, q, t[lane], hs[lane], roots[r], ftape, fC,
                                       wtape, wC, a, tc[i], zc[i], count[i], ytmp, P, Y, u)
        lane_advance(X, order, hs)
        for lane in range(_L):  # ended orbits give their lane to the next one
            i = orbit[lane]
            if i == -1:
                continue
            if _goes_on(lane, orbit, t, t1, count, n_crossings, t_max, max_steps, info):
                continue
            orbit[lane], nxt = _take_orbit(z0, n_crossings, t_max, max_steps, X, lane, nxt,
                                           info, nothing)
            t[lane] = 0.0
            fa[lane] = ca * X[0, 0, comp, lane] + cc
            if orbit[lane] < 0:
                busy -= 1


@kernel_jit
def _bounds(U, node, order, hs, bound):
    r"""``bound[lane]``: :math:`B_2 = \sum_{k \ge 2} |f^{[k]}| h^k` of the section jet
    ``U[:, node, lane]`` on every lane's step ``hs[lane]``, the bound of
    :func:`~andoyer.kernels.taylor.sections.end_and_bound` (each lane's operations the
    scalar ones, the lanes side by side)."""
    simd.tune()
    for lane in range(_L):
        bound[lane] = abs(U[order, node, lane])
    for k in range(order - 1, 1, -1):
        for lane in range(_L):
            bound[lane] = bound[lane] * hs[lane] + abs(U[k, node, lane])
    for lane in range(_L):
        bound[lane] = bound[lane] * hs[lane] * hs[lane]


@kernel_jit
def _start_value(ftape, fC, X, lane, Y, u):
    """The section function at ``lane``'s current state (its next step's ``f_a``): the
    scalar :func:`~andoyer.kernels.taylor.sections.tape_value`."""
    simd.tune()
    for c in range(_N):
        Y[0, c] = X[0, 0, c, lane]
    return tape_value(ftape, fC, Y, u)


@kernel_jit
def tape_crossings_on_lanes(z0, q, order, ftape, fC, wtape, wC, direction, t_max, max_steps,
                            tc, zc, count, info):
    """:func:`crossings_on_lanes` for a section with a tape (not a state component):
    the section jet of every lane from one lane-parallel pass of the tape
    (:func:`~andoyer.kernels.taylor.lane_sections.lane_tape_jet`), every lane's step with
    that jet in it (:func:`~andoyer.kernels.taylor.lane_sections.lane_section_steps`), the
    end value ``f_b`` the tape at the step's end state (one more lane-parallel pass at
    order 0), and the scalar kernel's root isolation and ``record`` on a lane whose step
    may hold a root -- as :func:`andoyer.kernels.taylor.flow.locate_crossings`."""
    simd.tune()  # the lanes' scheduling (simd.lane_tuning)
    n_crossings = tc.shape[1]
    n = order + 1
    nodes = ftape.shape[0]
    last = nodes - 1
    X = aligned(n * _N * _L).reshape((1, n, _N, _L))
    m = aligned(recurrences.LANE_PRODUCTS * _L).reshape((recurrences.LANE_PRODUCTS, _L))
    U = aligned(n * nodes * _L).reshape((n, nodes, _L))
    V = aligned(nodes * _L).reshape((1, nodes, _L))
    start = np.empty((_N, _L))
    h = np.empty(_L)
    r1 = aligned(_L)
    r2 = aligned(_L)
    hs = aligned(_L)
    t = np.zeros(_L)
    t1 = np.zeros(_L)
    fa = np.zeros(_L)
    bound = np.zeros(_L)
    orbit = np.full(_L, -1, dtype=np.int64)
    # the scalar section search's work space (one lane at a time)
    Xs = np.empty((1, n, _N))
    a = np.empty(n)
    u = np.empty((max(nodes, wtape.shape[0]), n))
    ytmp = np.empty(_N)
    P = np.empty((1, 2, _N))
    Y = np.empty((1, _N))
    W = bernstein_weights(order)
    stack, lo_s, hi_s, left, roots = isolation_space(order)
    nothing = np.empty(0)
    nxt = 0
    busy = 0
    for lane in range(_L):
        orbit[lane], nxt = _take_orbit(z0, n_crossings, t_max, max_steps, X, lane, nxt,
                                       info, nothing)
        if orbit[lane] >= 0:
            fa[lane] = _start_value(ftape, fC, X, lane, Y, u)
            busy += 1
    while busy > 0:
        lane_state_jets(X, order, q, m)
        lane_tape_jet(ftape, fC, X[0], order, U)
        lane_section_steps(X, U, order, ftape, h, r1, r2)
        for lane in range(_L):  # each lane's step (0 on idle and ended lanes)
            i = orbit[lane]
            hs[lane] = 0.0
            if i < 0:
                continue
            info[i, 3] += 1
            status, t1[lane], hs[lane] = step_to(t[lane], t_max, h[lane])
            if status != SUCCESS:
                info[i, 0] = status
                orbit[lane] = -2  # ended: refilled below
                continue
        _bounds(U, last, order, hs, bound)
        for c in range(_N):
            for lane in range(_L):
                start[c, lane] = X[0, 0, c, lane]
        lane_advance(X, order, hs)
        lane_tape_jet(ftape, fC, X[0], 0, V)  # f at the steps' ends: the next f_a
        for lane in range(_L):  # the scalar section search where a root may be
            i = orbit[lane]
            if i < 0:
                continue
            f0 = fa[lane]
            fb = V[0, last, lane]
            fa[lane] = fb
            a0 = U[0, last, lane]
            if not may_cross(f0, fb, a0, U[1, last, lane] * hs[lane], bound[lane]):
                continue
            for k in range(n):
                a[k] = U[k, last, lane]
            found = isolate(a, order, hs[lane], W, f0, fb, direction, stack, lo_s, hi_s,
                            left, roots)
            if found > 0:
                for k in range(n):
                    for c in range(_N):
                        Xs[0, k, c] = X[0, k, c, lane] if k > 0 else start[c, lane]
            for r in range(found):
                if count[i] < n_crossings:
                    count[i] = _record(Xs, order, q, t[lane], hs[lane], roots[r], ftape, fC,
                                       wtape, wC, a, tc[i], zc[i], count[i], ytmp, P, Y, u)
        for lane in range(_L):  # ended orbits give their lane to the next one
            i = orbit[lane]
            if i == -1:
                continue
            if _goes_on(lane, orbit, t, t1, count, n_crossings, t_max, max_steps, info):
                continue
            orbit[lane], nxt = _take_orbit(z0, n_crossings, t_max, max_steps, X, lane, nxt,
                                           info, nothing)
            t[lane] = 0.0
            if orbit[lane] < 0:
                busy -= 1
            else:
                fa[lane] = _start_value(ftape, fC, X, lane, Y, u)


def _build(stamp: str) -> Any:
    """The cached entry points (the closure over ``stamp`` keys the cache, as in
    :func:`andoyer.kernels.taylor.flow._build`)."""

    @exact_jit
    def lane_crossings_block(z0, p, order, ftape, fC, wtape, wC, direction, t_max, max_steps,
                             tc, zc, count, info):
        """:func:`locate_crossings` of a block of orbits on the calling thread."""
        simd.tune()
        _ = len(stamp)  # keys the cache
        q = np.empty(recurrences.N_CONSTANTS)
        fill_constants(p, q)
        crossings_on_lanes(z0, q, order, ftape, fC, wtape, wC, direction, t_max, max_steps, tc,
                           zc, count, info)

    @exact_jit
    def lane_tape_crossings_block(z0, p, order, ftape, fC, wtape, wC, direction, t_max,
                                  max_steps, tc, zc, count, info):
        """:func:`locate_crossings` of a block of orbits on the calling thread, for a
        section with a tape (:func:`tape_crossings_on_lanes`)."""
        simd.tune()
        _ = len(stamp)  # keys the cache
        q = np.empty(recurrences.N_CONSTANTS)
        fill_constants(p, q)
        tape_crossings_on_lanes(z0, q, order, ftape, fC, wtape, wC, direction, t_max,
                                max_steps, tc, zc, count, info)

    return lane_crossings_block, lane_tape_crossings_block


lane_crossings_block, lane_tape_crossings_block = _build(LANE_CROSSINGS_STAMP)


def locate_crossings(z0: np.ndarray, p: np.ndarray, kind: int, value: float, direction: int,
                     n_crossings: int, t_max: float, tol: float, max_steps: int, *,
                     block: int | None = None, threads: int | None = None
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """:func:`andoyer.kernels.taylor.flow.locate_crossings` of states alone (n, 6) on SIMD
    lanes, for any section: a state component's (:func:`component` not -1) by its
    column of the state's jet, any other by its tape's jet on the lanes.

    Costs: the module notes. Orbits take very different numbers of steps (4x on W2's
    orbits), and a block's lanes idle once its queue is empty while its longest orbits
    finish: so from :data:`PILOT_FROM` crossings asked the orbits run twice, a pilot of
    their first :data:`PILOT_CROSSINGS` crossings (the blocks of
    :func:`~andoyer.kernels.taylor.lanes.block_starts`), then from the start in one block
    per thread, longest first (:func:`_schedule`), as the heyoka engine orders its queue
    (measured: benchmarks/NOTES.md#taylor-lane-schedule). An orbit takes the same steps
    in any lane and block, and its crossings agree to round-off.

    Parameters
    ----------
    z0 : ndarray, shape (n, 6)
        Initial states (C-contiguous floats).
    p : ndarray
        Kernel parameters.
    kind : int
        Index into the section kinds.
    value : float
        The section value.
    direction : int
        +1: f increasing, -1: decreasing, 0: both.
    n_crossings : int
        Stop an orbit after this many crossings.
    t_max : float
        Stop an orbit at this time.
    tol : float
        The Taylor method's tolerance.
    max_steps : int
        Maximum steps per orbit.
    block : int, optional
        Orbits per block, in their order. Default: from :data:`PILOT_FROM` crossings
        asked, the pilot's schedule (the first :data:`PILOT_CROSSINGS` crossings of
        every orbit, then one block per thread, longest orbit first: :func:`_schedule`);
        else the guided blocks of :func:`andoyer.kernels.taylor.lanes.block_starts`.
    threads : int, optional
        Threads (:func:`andoyer.kernels.threads.over_orbits`).

    Returns
    -------
    t, z, count, info :
        As :func:`andoyer.kernels.taylor.flow.locate_crossings`.

    Examples
    --------
    >>> import numpy as np
    >>> from andoyer import RigidBody
    >>> p = RigidBody.paper().engine_params
    >>> z0 = np.array([[0.3, 1.1, 0.2, 0.6, 0.0, 0.8]] * 9)
    >>> t, z, count, info = locate_crossings(z0, p, 2, 0.0, 0, 3, 1000.0, 1e-12, 10**6)
    >>> count.tolist() == [3] * 9, bool(np.all(np.abs(z[:, :, 2]) < 1e-14))
    (True, True)
    >>> t, z, count, info = locate_crossings(z0, p, 13, 0.0, 1, 3, 1000.0, 1e-12, 10**6)
    >>> count.tolist() == [3] * 9  # theta2 = 0, upward
    True
    """
    import numba

    if z0.ndim != 2 or z0.shape[1] != _N:
        raise ValueError(f"z0 must have shape (n, {_N}) (states alone), got {z0.shape}")
    n = z0.shape[0]
    ftape, fC = section_tape(int(kind), float(p[7]), float(value))
    wtape, wC = section_tape(int(kind), float(p[7]), float(value), margin=True)
    m = numba.get_num_threads() if threads is None else int(threads)
    kernel = (lane_crossings_block if component(int(kind), float(p[7]), float(value)) >= 0
              else lane_tape_crossings_block)
    args = (p, flow.order_for(tol), ftape, fC, wtape, wC, int(direction), float(t_max),
            int(max_steps))

    def run(z: np.ndarray, k: int, **blocks: Any) -> tuple[np.ndarray, ...]:
        # The first k crossings of the orbits z, in the blocks given.
        out = _outputs(z.shape[0], k)
        over_orbits(kernel, z.shape[0], (z,), out, args, threads=m, **blocks)
        return out

    if block is not None or int(n_crossings) < PILOT_FROM or n < 2:
        blocks = {"starts": lanes.block_starts(n, m)} if block is None else {"block": int(block)}
        tc, zc, count, info = run(z0, int(n_crossings), **blocks)
        return tc, zc, count, info
    tc, zc, count, info = _outputs(n, int(n_crossings))
    p_tc, p_zc, p_count, p_info = run(z0, PILOT_CROSSINGS, starts=lanes.block_starts(n, m))
    parts = _schedule(p_tc, p_count, p_info, int(n_crossings), float(t_max), m)
    done = p_count < PILOT_CROSSINGS  # ended in the pilot: its results are the run's
    tc[done, :PILOT_CROSSINGS], zc[done, :PILOT_CROSSINGS] = p_tc[done], p_zc[done]
    count[done], info[done] = p_count[done], p_info[done]
    if parts:
        rows = np.concatenate(parts)
        starts = np.cumsum([0] + [len(r) for r in parts[:-1]]).tolist()
        tc[rows], zc[rows], count[rows], info[rows] = run(
            np.ascontiguousarray(z0[rows]), int(n_crossings), starts=starts)
    return tc, zc, count, info


def _outputs(n: int, n_crossings: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The outputs ``tc, zc, count, info`` of ``n`` orbits' first ``n_crossings``
    crossings, before the run (NaN, zero)."""
    return (np.full((n, n_crossings), np.nan), np.full((n, n_crossings, _N), np.nan),
            np.zeros(n, dtype=np.int64), np.zeros((n, len(INFO)), dtype=np.int64))


def _schedule(tc: np.ndarray, count: np.ndarray, info: np.ndarray, n_crossings: int,
              t_max: float, threads: int) -> list[np.ndarray]:
    """The orbits the pilot left to run, one block per thread, each block longest first,
    the blocks balanced by the orbits' predicted steps (longest first to the block with
    the fewest so far).

    An orbit's steps are predicted from its pilot: its steps per unit time times the
    time of its ``n_crossings``-th crossing (the first crossing plus the mean return
    time after it; at most ``t_max``). An orbit that found fewer than
    :data:`PILOT_CROSSINGS` crossings ended in the pilot and is left out.

    Parameters
    ----------
    tc : ndarray, shape (n, PILOT_CROSSINGS)
        The pilot's crossing times.
    count, info : ndarray
        The pilot's crossing counts and ``info``.
    n_crossings : int
        Crossings asked.
    t_max : float
        The time limit.
    threads : int
        Threads (blocks).

    Returns
    -------
    list of ndarray
        The orbits of each block (none empty).

    Examples
    --------
    >>> tc = np.array([[1.0, 2.0, 3.0], [1.0, 3.0, 5.0], [0.5, 1.0, 1.5], [2.0, np.nan, np.nan]])
    >>> info = np.array([[0, 0, 0, 30], [0, 0, 0, 50], [0, 0, 0, 12], [0, 0, 0, 90]])
    >>> [b.tolist() for b in _schedule(tc, np.array([3, 3, 3, 1]), info, 100, np.inf, 2)]
    [[1], [0, 2]]
    """
    left = np.flatnonzero(count >= PILOT_CROSSINGS)
    k = PILOT_CROSSINGS
    t_first, t_last = tc[left, 0], tc[left, k - 1]
    t_end = np.minimum(t_first + (n_crossings - 1) * (t_last - t_first) / (k - 1), t_max)
    steps = info[left, INFO.index("nfev")] / t_last * t_end  # taylor counts steps there
    blocks: list[list[int]] = [[] for _ in range(max(1, threads))]
    load = np.zeros(len(blocks))
    for i in np.argsort(-steps, kind="stable"):  # longest first
        b = int(np.argmin(load))
        blocks[b].append(int(left[i]))
        load[b] += steps[i]
    return [np.array(b, dtype=np.int64) for b in blocks if b]
