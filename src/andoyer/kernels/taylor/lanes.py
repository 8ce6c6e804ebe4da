r"""The Taylor method of :mod:`andoyer.kernels.taylor.flow` on ``LANES`` orbits at once (SIMD).

The scalar kernel computes the jet of one orbit at a time: every Cauchy product of
the recurrences of the field (1) is a scalar multiply-add, so the machine's vector
units (AVX-512: 8 doubles, AVX2: 4) idle. Here the jets of :data:`LANES` orbits (one
vector register of this CPU, :func:`andoyer.kernels.simd.lane_width`) are one array
``X[block, k, i, lane]`` with the lane index innermost and a compile-time trip count,
and the generated lane recurrences (``ep_taylor_jet_lanes``,
``ep_taylor_tangent_jet_lanes`` of :mod:`andoyer.kernels.generated.recurrences`, written
by :mod:`andoyer.symbolic.taylor_codegen` from the same SymPy field as the scalar
ones) do every multiply-add for all lanes with one vector instruction -- heyoka's
batch mode, without heyoka.

Design (measured: benchmarks/NOTES.md#taylor-lanes):

* **Vector code by intrinsics** (:mod:`andoyer.kernels.simd`). Plain Numba loops over
  the lanes are not vectorised (their constant trip count is unrolled first, and
  Numba turns LLVM's SLP vectoriser off): they ran slower per orbit than the scalar
  jets in every layout tried, and SLP on for the whole process slows the scalar
  kernels. The intrinsics' hot loop is the ideal one: per ``j``, 12 vector loads and 18
  fused multiply-adds into 18 register accumulators (the tangent jet), on buffers
  aligned to 64 bytes (:func:`aligned`); a lane-step's jets cost about a quarter of a
  scalar orbit-step's.
* **Each lane steps on its own.** A lane has its own time, its own Jorba-Zou step
  (:func:`lane_steps`: the rule of :func:`andoyer.kernels.taylor.jets.step_size`,
  lane by lane) and its own next output time; output times inside a step are the
  step's polynomial there (Horner per lane), exactly as the scalar kernel does. So a
  lane takes the scalar kernel's steps (``info`` equal orbit by orbit, tested) and its
  states agree with the scalar kernel's to round-off, and no lane waits for another:
  only the jets are shared work. (Lanes stopping at common output times, the other
  design of the issue, would cut every lane's steps at each output time: more steps
  for nothing. It was not built.)
* **Lanes are refilled from a queue.** Orbits take different numbers of steps; a
  lane whose orbit ends (all output times reached, or a failure) takes the next orbit
  of its block at once. Lanes left without an orbit at the block's end carry a zero
  state (zero jets, no floating-point exceptions) until the block ends.
* **Failures per orbit**, with the scalar kernel's statuses and ``info`` columns
  (:data:`andoyer.kernels.common.INFO`): a non-finite state or a step below ten
  units in the last place of ``t`` gives ``STEP_TOO_SMALL``, ``max_steps`` steps
  ``MAX_STEPS``; rows of ``out`` not reached are left as they were.
* **Threads over blocks of orbits** (:func:`andoyer.kernels.threads.over_orbits`),
  each block a queue for its own lanes (:func:`block_starts`: guided, shorter as the
  orbits run out).

A lane-step costs about a quarter of the scalar kernel's orbit-step, mostly the jets
(then the step size, its roots on lane vectors: :func:`andoyer.kernels.simd.roots`); one
specialisation of the entry point serves every width ``6 + 6 k`` (per-step costs, FLI
maps against heyoka, compile time: benchmarks/NOTES.md#taylor-lanes).

States of ``6 + 6 k`` floats (the state and ``k`` tangent vectors, not renormalised,
as :func:`andoyer.kernels.taylor.flow.propagate`).

Entry point: :func:`propagate` (cached machine code, keyed by :data:`LANES_STAMP`).
"""

from __future__ import annotations

import math
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
from andoyer.kernels.taylor import jets, sections
from andoyer.kernels.taylor.jets import fill_constants, step_to
from andoyer.kernels.threads import over_orbits

__all__ = ["LANES", "LANES_STAMP", "propagate", "lanes_block", "block_starts"]

#: Orbits advanced together (the vector width of the generated lane jets).
LANES = simd.LANES
_L = LANES
_N = N_STATE
_P = recurrences.LANE_PRODUCTS

#: Hash of every source the compiled entry point depends on, the lane count and tuning (its
#: cache key: code compiled for another width is another entry).
LANES_STAMP = source_stamp(recurrences.__file__, __file__, simd.__file__, sections.__file__,
                           jets.__file__, common.__file__) + f"-lanes{LANES}-tune{simd.TUNE}"

_jet = kernel_jit(recurrences.ep_taylor_jet_lanes)
_tangent_jet = kernel_jit(recurrences.ep_taylor_tangent_jet_lanes)


@kernel_jit
def lane_jets(X, order, q, m):
    """Jets to ``order`` of the state ``X[0]`` and the tangent vectors ``X[1:]`` of every
    lane (rows ``X[:, 0]`` are the current values); ``m`` scratch (LANE_PRODUCTS, LANES)."""
    simd.tune()
    _jet(X[0], order, q, m)
    for b in range(1, X.shape[0]):
        _tangent_jet(X[0], X[b], order, q, m)


@kernel_jit
def lane_state_jets(X, order, q, m):
    """:func:`lane_jets` of states alone (``X`` of one block): a caller that never
    carries tangent vectors compiles no tangent jets (0.3 s of a cold first section)."""
    simd.tune()
    _jet(X[0], order, q, m)


@kernel_jit
def lane_steps(X, order, h, a1, a2, tot):
    """``h[lane]``: the Jorba-Zou step of :func:`andoyer.kernels.taylor.jets.step_size`
    for every lane (NaN where a value or coefficient is not finite). ``a1, a2, tot``
    scratch (LANES,): the least ``m / |x^[p-1]|``, ``m / |x^[p]|`` over the blocks (the
    powers are monotonic, so the least radius is the radius of the least ratio)."""
    simd.tune()
    for lane in range(_L):
        a1[lane] = np.inf
        a2[lane] = np.inf
        tot[lane] = 0.0
    for b in range(X.shape[0]):
        for lane in range(_L):
            m = 0.0
            n1 = 0.0
            n2 = 0.0
            for i in range(_N):
                v0 = abs(X[b, 0, i, lane])
                v1 = abs(X[b, order - 1, i, lane])
                v2 = abs(X[b, order, i, lane])
                m = max(m, v0)
                n1 = max(n1, v1)
                n2 = max(n2, v2)
                tot[lane] += v0 + v1 + v2
            m = max(1.0, m)
            if n1 > 0.0:
                a1[lane] = min(a1[lane], m / n1)
            if n2 > 0.0:
                a2[lane] = min(a2[lane], m / n2)
    c = math.exp(-0.7 / (order - 1)) / (math.e * math.e)
    for lane in range(_L):  # NaN: not finite; inf: no coefficient (any step); else 0
        h[lane] = (np.nan if not tot[lane] < np.inf
                   else np.inf if a1[lane] == np.inf and a2[lane] == np.inf else 0.0)
    simd.roots(a1, 1.0 / (order - 1), a1)  # the radii, every lane in one vector
    simd.roots(a2, 1.0 / order, a2)
    for lane in range(_L):
        if h[lane] == 0.0:
            h[lane] = min(a1[lane], a2[lane]) * c


@kernel_jit
def lane_advance(X, order, h):
    """Rows 0 of every lane's jets = the values at ``t0 + h[lane]`` (vector code,
    :func:`andoyer.kernels.simd.advance`: faster than the scalar loops; measured:
    benchmarks/NOTES.md#taylor-lanes)."""
    simd.tune()
    simd.advance(X, order, h)


@kernel_jit
def lane_horner(X, order, lane, tau, out):
    """``out[6 b + i]`` = block ``b`` of ``lane`` at ``t0 + tau``."""
    simd.tune()
    for b in range(X.shape[0]):
        for i in range(_N):
            v = X[b, order, i, lane]
            for k in range(order - 1, -1, -1):
                v = v * tau + X[b, k, i, lane]
            out[_N * b + i] = v


@kernel_jit
def lane_load(X, lane, z):
    """Rows 0 of ``lane``'s jets = the state ``z`` (zeros when ``z`` is empty: an idle
    lane)."""
    simd.tune()
    for b in range(X.shape[0]):
        for i in range(_N):
            X[b, 0, i, lane] = z[_N * b + i] if z.shape[0] else 0.0


@kernel_jit
def goes_on(info, i, more, max_steps):
    """Orbit ``i`` after an accepted step on its lane: the step counted (``info[i, 1]``);
    True when it goes on (``more`` work left and steps allowed), else False (the lane takes
    the next orbit), with ``MAX_STEPS`` where work was left but no step is."""
    simd.tune()
    info[i, 1] += 1
    if more:
        if info[i, 1] < max_steps:
            return True
        info[i, 0] = MAX_STEPS
    return False


@kernel_jit
def take_orbit(z0, t_out, max_steps, X, lane, nxt, out, info, nothing):
    """Load the next orbit of the queue (from ``nxt``) that needs a step into ``lane``;
    orbits that need none (one output time, repeated initial times, ``max_steps`` 0)
    are finished here as the scalar kernel finishes them. Returns ``(orbit, j, next)``:
    the orbit (-1: none left, the lane is zeroed by the empty ``nothing``), its next
    output index, the queue's next orbit."""
    simd.tune()
    k = t_out.shape[0]
    while nxt < z0.shape[0]:
        i = nxt
        nxt += 1
        for c in range(z0.shape[1]):
            out[i, 0, c] = z0[i, c]
        if k == 1:
            continue
        j = 1
        while j < k and t_out[j] <= t_out[0]:  # repeated initial times
            for c in range(z0.shape[1]):
                out[i, j, c] = z0[i, c]
            j += 1
        if j >= k:
            continue
        if info[i, 1] >= max_steps:
            info[i, 0] = MAX_STEPS
            continue
        lane_load(X, lane, z0[i])
        return i, j, nxt
    lane_load(X, lane, nothing)
    return -1, 0, nxt


@kernel_jit
def aligned(n):
    """``n`` zeros starting on a 64-byte boundary, so that each lane vector is one
    cache line (vector loads straddling two lines slow the Cauchy products down;
    measured: benchmarks/NOTES.md#taylor-lanes)."""
    simd.tune()
    buf = np.zeros(n + 8)
    start = ((-buf.ctypes.data) // 8) % 8
    return buf[start:start + n]


@kernel_jit
def lanes_orbits(z0, t_out, q, order, max_steps, out, info):
    """The orbits ``z0`` (n, 6 + 6 k) to the output times ``t_out``: ``out[i, j]`` and
    ``info[i]`` as :func:`andoyer.kernels.taylor.flow.propagate` (see the module notes)."""
    simd.tune()  # the lanes' scheduling (simd.lane_tuning)
    k = t_out.shape[0]
    t_end = t_out[k - 1]
    nb = z0.shape[1] // _N
    X = aligned(nb * (order + 1) * _N * _L).reshape((nb, order + 1, _N, _L))
    m = aligned(_P * _L).reshape((_P, _L))
    h = np.empty(_L)
    hs = aligned(_L)
    a1 = np.empty(_L)
    a2 = np.empty(_L)
    tot = np.empty(_L)
    t = np.zeros(_L)
    t1 = np.zeros(_L)
    j = np.zeros(_L, dtype=np.int64)
    orbit = np.full(_L, -1, dtype=np.int64)
    nothing = np.empty(0)
    nxt = 0
    busy = 0
    for lane in range(_L):
        orbit[lane], j[lane], nxt = take_orbit(z0, t_out, max_steps, X, lane, nxt, out,
                                               info, nothing)
        t[lane] = t_out[0]
        if orbit[lane] >= 0:
            busy += 1
    while busy > 0:
        lane_jets(X, order, q, m)
        lane_steps(X, order, h, a1, a2, tot)
        for lane in range(_L):  # the step of each lane, its output times inside it
            i = orbit[lane]
            hs[lane] = 0.0
            if i < 0:
                continue
            info[i, 3] += 1
            tl = t[lane]
            status, e, hl = step_to(tl, t_end, h[lane])
            if status != SUCCESS:
                info[i, 0] = status
                orbit[lane] = -2  # ended: refilled below
                continue
            jl = j[lane]
            while jl < k and t_out[jl] <= e:
                lane_horner(X, order, lane, t_out[jl] - tl if t_out[jl] < e else hl,
                            out[i, jl])
                jl += 1
            j[lane] = jl
            t1[lane] = e
            hs[lane] = hl
        lane_advance(X, order, hs)
        for lane in range(_L):  # ended orbits give their lane to the next one
            i = orbit[lane]
            if i == -1:
                continue
            if i >= 0:
                t[lane] = t1[lane]
                if goes_on(info, i, j[lane] < k, max_steps):
                    continue
            orbit[lane], j[lane], nxt = take_orbit(z0, t_out, max_steps, X, lane, nxt,
                                                   out, info, nothing)
            t[lane] = t_out[0]
            if orbit[lane] < 0:
                busy -= 1


def _build(stamp: str) -> Any:
    """The cached entry point (the closure over ``stamp`` keys the cache, as in
    :func:`andoyer.kernels.taylor.flow._build`)."""

    @exact_jit
    def lanes_block(z0, t, p, order, max_steps, out, info):
        """:func:`propagate` of a block of orbits on the calling thread."""
        simd.tune()
        _ = len(stamp)  # keys the cache
        q = np.empty(recurrences.N_CONSTANTS)
        fill_constants(p, q)
        lanes_orbits(z0, t, q, order, max_steps, out, info)

    return lanes_block


lanes_block = _build(LANES_STAMP)


def block_starts(n: int, threads: int) -> list[int]:
    """First orbit of each block handed to a thread: guided, each block the share of one
    thread of half the orbits left, at least two orbits per lane (a block's last orbits
    run with idle lanes beside them), so that the last blocks are short and no thread
    waits long on another at the end of a call.

    Parameters
    ----------
    n : int
        Orbits.
    threads : int
        Threads.

    Examples
    --------
    >>> starts = block_starts(1024, 2)
    >>> starts[:4], 1024 - starts[-1] <= 2 * LANES
    ([0, 256, 448, 592], True)
    >>> block_starts(3 * LANES, 2) == [0, 2 * LANES]    # short blocks: two orbits a lane
    True
    """
    m, starts, i = max(1, int(threads)), [], 0
    while i < n:
        starts.append(i)
        i += max(2 * _L, -(-(n - i) // (2 * m)))
    return starts


def propagate(z0: np.ndarray, t: np.ndarray, p: np.ndarray, order: int, max_steps: int, *,
              block: int | None = None, threads: int | None = None
              ) -> tuple[np.ndarray, np.ndarray]:
    """:func:`andoyer.kernels.taylor.flow.propagate` with :data:`LANES` orbits per vector step.

    Parameters
    ----------
    z0 : ndarray, shape (n, 6 + 6 k)
        Initial states ``(y, w_1 .. w_k)`` at ``t[0]`` (C-contiguous floats).
    t : ndarray, shape (m,)
        Output times, non-decreasing.
    p : ndarray, shape (8,)
        Kernel parameters :data:`andoyer.kernels.dop853.flow.PARAMS`.
    order : int
        The Taylor order (:func:`andoyer.kernels.taylor.flow.order_for` of the tolerance).
    max_steps : int
        Maximum steps per orbit.
    block : int, optional
        Orbits per block (default: the guided blocks of :func:`block_starts`).
    threads : int, optional
        Threads (:func:`andoyer.kernels.threads.over_orbits`).

    Returns
    -------
    z : ndarray, shape (n, m, 6 + 6 k)
        NaN after a failure (see ``info``).
    info : ndarray of int64, shape (n, 4)
        Columns :data:`INFO` (``rejected`` is always 0; ``nfev`` counts jets).

    Examples
    --------
    >>> import numpy as np
    >>> from andoyer import RigidBody
    >>> z0 = np.array([[0.3, 1.1, 0.2, 0.6, 0.0, 0.8]] * 9)
    >>> z, info = propagate(z0, np.array([0.0, 1.0]), RigidBody.paper().engine_params,
    ...                     15, 10**6)
    >>> z.shape, bool(np.all(info[:, 0] == SUCCESS))
    ((9, 2, 6), True)
    """
    import numba

    n = z0.shape[0]
    out = np.full((n, t.shape[0], z0.shape[1]), np.nan)
    info = np.zeros((n, len(INFO)), dtype=np.int64)
    m = numba.get_num_threads() if threads is None else int(threads)
    blocks = {"starts": block_starts(n, m)} if block is None else {"block": int(block)}
    over_orbits(lanes_block, n, (z0,), (out, info), (t, p, int(order), int(max_steps)),
                threads=m, **blocks)
    return out, info
