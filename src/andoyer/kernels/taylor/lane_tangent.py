r"""Renormalised tangent flows with the MEGNO quadratures (:mod:`andoyer.kernels.taylor.tangent`)
on ``LANES`` orbits at once (SIMD).

The scalar kernel of :mod:`andoyer.kernels.taylor.tangent` runs one orbit at a time:
its jets (the state's, each tangent vector's, the MEGNO quadratures') are scalar
multiply-adds. Here :data:`~andoyer.kernels.taylor.lanes.LANES` orbits share each
instruction, as in :mod:`andoyer.kernels.taylor.lanes` (whose lane jets, lane loads,
Horner and queue this module uses), with what the renormalised flow adds:

* **the MEGNO jets on lanes** (:func:`lane_megno_jets`): the Cauchy product
  :math:`P_k = \sum_j w^{[j]} \cdot w^{[k-j]}` of the first vector with itself
  (:func:`andoyer.kernels.simd.series_dot`, each pair of terms once), then the
  logarithm's recurrence
  :math:`\ell_k = (P_k - \frac1k \sum_{j=1}^{k-1} j\,\ell_j P_{k-j}) / P_0` and ``N``,
  ``g``, ``I`` on lane vectors (:func:`andoyer.kernels.simd.megno_orders`) -- the
  recurrences of the scalar kernel's notes, term for term;
* **the scalar kernel's step, lane by lane** (:func:`lane_tangent_steps`): the least
  radius over the state, each vector, ``L`` and (while the pole of ``I`` at distance
  :math:`s_0 = t_0 + \delta` is nearer than that radius) ``I``; as in
  :func:`andoyer.kernels.taylor.lanes.lane_steps`, the least ratio ``m / |x^{[p]}|``
  over the blocks takes the powers (the radii are monotonic in it), two per lane
  except in the first steps; a non-finite state fails the lane's orbit
  (``STEP_TOO_SMALL``) and a non-finite vector or ``L`` leaves the step to the other
  blocks, as the scalar kernel's ``min`` does;
* **renormalisation per lane** at each step's start, the output rows (unit vectors,
  ``rho``, ``N``, ``I``) by Horner per lane at output times.

So each lane takes the scalar kernel's steps (``info`` equal orbit by orbit, tested)
and its rows agree with the scalar kernel's to round-off. Failures are per orbit with
the scalar kernel's statuses; ended orbits hand their lane to the next of the block's
queue; threads run blocks (guided: :func:`andoyer.kernels.taylor.lanes.block_starts`).

Entry point: :func:`propagate` (cached machine code, keyed by :data:`LANE_TANGENT_STAMP`);
rows in the layout of :func:`andoyer.kernels.common.layout`.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from andoyer.kernels import common, simd
from andoyer.kernels.common import (
    INFO,
    MAX_STEPS,
    MEGNO_DELTA,
    N_STATE,
    SUCCESS,
    dimension,
    exact_jit,
    kernel_jit,
    source_stamp,
)
from andoyer.kernels.generated import recurrences
from andoyer.kernels.taylor import jets, lanes, sections, tangent
from andoyer.kernels.taylor.jets import fill_constants, step_to
from andoyer.kernels.taylor.lanes import (
    aligned,
    block_starts,
    goes_on,
    lane_advance,
    lane_horner,
    lane_jets,
    lane_load,
)
from andoyer.kernels.threads import over_orbits

__all__ = ["LANE_TANGENT_STAMP", "lane_megno_jets", "lane_tangent_steps", "propagate"]

_L = lanes.LANES
_N = N_STATE
#: Rows of the quadrature jets ``W[k, row, lane]``: L, N, I, and the work rows P, g,
#: j L_j (the logarithm's weights), as :func:`andoyer.kernels.simd.megno_orders` reads
#: them.
_ROWS = 6
_LN, _NN, _IN, _PN, _GN, _JL = range(_ROWS)

#: Hash of every source the compiled entry point depends on, the lane count and tuning.
LANE_TANGENT_STAMP = source_stamp(
    __file__, lanes.__file__, tangent.__file__, recurrences.__file__, simd.__file__,
    sections.__file__, jets.__file__, common.__file__) + f"-lanes{_L}-tune{simd.TUNE}"


@kernel_jit
def lane_megno_jets(X, order, s0, W, inv):
    """Jets of the MEGNO quadratures of every lane from the first vector's lane jets
    ``X[1]`` (:func:`andoyer.kernels.taylor.tangent.megno_jets` on lanes): ``W[:, 0]`` L,
    ``W[:, 1]`` N, ``W[:, 2]`` I (rows ``W[0, 1], W[0, 2]`` their values at the step's
    start, set by the caller), ``W[:, 3:]`` work rows (P, g, j L_j). ``W`` has shape
    (order + 1, 6, LANES) (the rows of :func:`andoyer.kernels.simd.megno_orders`),
    ``s0[lane] = t0 + delta``, ``inv`` (2, LANES) scratch (``1 / P_0``, ``1 / s0``).
    (``g``'s last coefficient, which the scalar kernel skips, is computed and never
    read.)"""
    simd.tune()
    simd.series_dot(W, _PN, X[1], order)
    for lane in range(_L):
        inv[0, lane] = 1.0 / W[0, _PN, lane]
        inv[1, lane] = 1.0 / s0[lane]
        W[0, _LN, lane] = 0.5 * math.log(W[0, _PN, lane])
        W[0, _GN, lane] = W[0, _NN, lane] * inv[1, lane]
        W[0, _JL, lane] = 0.0
    simd.megno_orders(W, order, s0, inv)


@kernel_jit
def _ratios(x, lo, hi, order, lane):
    """``(m / max|x^[p-1]|, m / max|x^[p]|, finite)`` of the components ``lo .. hi - 1`` of the
    lane jets ``x[k, i, lane]`` (``inf`` where the coefficients are zero; the scale ``m``
    as in :func:`andoyer.kernels.taylor.jets.radius`)."""
    m = 0.0
    n1 = 0.0
    n2 = 0.0
    total = 0.0  # NaN or inf if any coefficient is (max() would drop a NaN)
    for i in range(lo, hi):
        v0 = abs(x[0, i, lane])
        v1 = abs(x[order - 1, i, lane])
        v2 = abs(x[order, i, lane])
        m = max(m, v0)
        n1 = max(n1, v1)
        n2 = max(n2, v2)
        total += v0 + v1 + v2
    m = max(1.0, m)
    a1 = m / n1 if n1 > 0.0 else np.inf
    a2 = m / n2 if n2 > 0.0 else np.inf
    return a1, a2, total < np.inf


@kernel_jit
def _radius_of(a1, a2, order):
    """The radius of the least ratios (:func:`andoyer.kernels.taylor.jets.radius`)."""
    rho = np.inf
    if a1 < np.inf:
        rho = simd.root(a1, 1.0 / (order - 1))
    if a2 < np.inf:
        rho = min(rho, simd.root(a2, 1.0 / order))
    return rho


@kernel_jit
def lane_tangent_steps(X, W, order, s0, busy, h):
    """``h[lane]``: the step of :func:`andoyer.kernels.taylor.tangent.renormalised_orbit`
    for every lane with ``busy[lane]`` (NaN where the state is not finite; see the module
    notes)."""
    simd.tune()
    c = math.exp(-0.7 / (order - 1)) / (math.e * math.e)
    for lane in range(_L):
        h[lane] = 0.0
        if not busy[lane]:
            continue
        a1, a2, ok = _ratios(X[0], 0, _N, order, lane)
        if not ok:  # a non-finite state
            h[lane] = np.nan
            continue
        for b in range(1, X.shape[0]):
            b1, b2, ok = _ratios(X[b], 0, _N, order, lane)
            if ok:
                a1 = min(a1, b1)
                a2 = min(a2, b2)
        b1, b2, ok = _ratios(W, _LN, _LN + 1, order, lane)
        if ok:
            a1 = min(a1, b1)
            a2 = min(a2, b2)
        r = _radius_of(a1, a2, order)
        if not s0[lane] > r:  # I's pole at distance s0 is near: the first steps
            b1, b2, ok = _ratios(W, _IN, _IN + 1, order, lane)
            if ok:
                r = min(r, _radius_of(b1, b2, order))
        h[lane] = r * c


@kernel_jit
def _value(W, row, order, lane, tau):
    """The polynomial ``W[:, row, lane]`` at ``tau`` (Horner)."""
    v = W[order, row, lane]
    for k in range(order - 1, -1, -1):
        v = v * tau + W[k, row, lane]
    return v


@kernel_jit
def _write_row(X, W, order, lane, tau, rho, tmp, row):
    """The output row of ``lane`` at ``t0 + tau`` (``_write_row`` of the scalar kernel)."""
    k = X.shape[0] - 1
    lane_horner(X, order, lane, tau, tmp)
    tangent.write_vectors(tmp, rho[lane], row)
    row[_N + 7 * k] = _value(W, _NN, order, lane, tau)
    row[_N + 7 * k + 1] = _value(W, _IN, order, lane, tau)


@kernel_jit
def _renormalise(X, lane, rho):
    """Rows 0 of ``lane``'s vectors to unit length, their logarithms added to ``rho``."""
    for b in range(1, X.shape[0]):
        s = 0.0
        for i in range(_N):
            s += X[b, 0, i, lane] * X[b, 0, i, lane]
        nrm = math.sqrt(s)
        for i in range(_N):
            X[b, 0, i, lane] /= nrm
        rho[lane, b - 1] += math.log(nrm)


@kernel_jit
def _take_orbit(z0, rho0, t_out, max_steps, X, W, rho, lane, nxt, out, info, nothing):
    """The next orbit of the queue (from ``nxt``) that needs a step, loaded into ``lane``
    with its ``rho`` and zero quadratures; rows at the initial time written as the scalar
    kernel writes them, orbits that need no step finished here. Returns ``(orbit, j,
    next)`` as :func:`andoyer.kernels.taylor.lanes.take_orbit` (an idle lane carries a
    zero state and a unit first vector: finite jets)."""
    m = t_out.shape[0]
    k = rho.shape[1]
    nz = _N + _N * k
    while nxt < z0.shape[0]:
        i = nxt
        nxt += 1
        for j in range(m):  # rows at the initial time
            if j > 0 and t_out[j] > t_out[0]:
                break
            for c in range(nz):
                out[i, j, c] = z0[i, c]
            for b in range(k):
                out[i, j, nz + b] = rho0[i, b]
            out[i, j, nz + k] = 0.0
            out[i, j, nz + k + 1] = 0.0
        if m == 1:
            continue
        j = 1
        while j < m and t_out[j] <= t_out[0]:
            j += 1
        if j >= m:
            continue
        if info[i, 1] >= max_steps:
            info[i, 0] = MAX_STEPS
            continue
        lane_load(X, lane, z0[i])
        for b in range(k):
            rho[lane, b] = rho0[i, b]
        W[0, _NN, lane] = 0.0
        W[0, _IN, lane] = 0.0
        return i, j, nxt
    lane_load(X, lane, nothing)
    X[1, 0, 0, lane] = 1.0
    W[0, _NN, lane] = 0.0
    W[0, _IN, lane] = 0.0
    return -1, 0, nxt


@kernel_jit
def renormalised_lanes(z0, rho0, t_out, q, order, max_steps, out, info):
    """The orbits ``z0`` (n, 6 + 6 k; unit vectors) with ``rho0`` (n, k) to the output
    times ``t_out``: ``out[i, j]`` and ``info[i]`` as
    :func:`andoyer.kernels.taylor.tangent.propagate` (see the module notes)."""
    simd.tune()
    m_out = t_out.shape[0]
    t_end = t_out[m_out - 1]
    nb = z0.shape[1] // _N
    k = nb - 1
    X = aligned(nb * (order + 1) * _N * _L).reshape((nb, order + 1, _N, _L))
    W = aligned((order + 1) * _ROWS * _L).reshape((order + 1, _ROWS, _L))
    mj = aligned(recurrences.LANE_PRODUCTS * _L).reshape((recurrences.LANE_PRODUCTS, _L))
    inv = np.empty((2, _L))
    rho = np.zeros((_L, k))
    h = np.empty(_L)
    hs = aligned(_L)
    s0 = np.empty(_L)
    busy_lane = np.zeros(_L, dtype=np.bool_)
    t = np.zeros(_L)
    t1 = np.zeros(_L)
    j = np.zeros(_L, dtype=np.int64)
    orbit = np.full(_L, -1, dtype=np.int64)
    tmp = np.empty(_N * nb)
    nothing = np.empty(0)
    nxt = 0
    busy = 0
    for lane in range(_L):
        orbit[lane], j[lane], nxt = _take_orbit(z0, rho0, t_out, max_steps, X, W, rho, lane,
                                                nxt, out, info, nothing)
        t[lane] = t_out[0]
        if orbit[lane] >= 0:
            busy += 1
    while busy > 0:
        for lane in range(_L):
            s0[lane] = t[lane] + MEGNO_DELTA
            busy_lane[lane] = orbit[lane] >= 0
        lane_jets(X, order, q, mj)
        lane_megno_jets(X, order, s0, W, inv)
        lane_tangent_steps(X, W, order, s0, busy_lane, h)
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
            while jl < m_out and t_out[jl] <= e:
                _write_row(X, W, order, lane, t_out[jl] - tl if t_out[jl] < e else hl, rho,
                           tmp, out[i, jl])
                jl += 1
            j[lane] = jl
            t1[lane] = e
            hs[lane] = hl
        lane_advance(X, order, hs)
        for lane in range(_L):  # the next step's start; ended orbits give their lane
            i = orbit[lane]
            if i == -1:
                continue
            if i >= 0:
                W[0, _NN, lane] = _value(W, _NN, order, lane, hs[lane])
                W[0, _IN, lane] = _value(W, _IN, order, lane, hs[lane])
                _renormalise(X, lane, rho)
                t[lane] = t1[lane]
                if goes_on(info, i, j[lane] < m_out, max_steps):
                    continue
            orbit[lane], j[lane], nxt = _take_orbit(z0, rho0, t_out, max_steps, X, W, rho,
                                                    lane, nxt, out, info, nothing)
            t[lane] = t_out[0]
            if orbit[lane] < 0:
                busy -= 1


def _build(stamp: str) -> Any:
    """The cached entry point (the closure over ``stamp`` keys the cache, as in
    :func:`andoyer.kernels.taylor.flow._build`)."""

    @exact_jit
    def lane_tangent_block(z0, rho0, t, p, order, max_steps, out, info):
        """:func:`propagate` of a block of orbits on the calling thread."""
        simd.tune()
        _ = len(stamp)  # keys the cache
        q = np.empty(recurrences.N_CONSTANTS)
        fill_constants(p, q)
        renormalised_lanes(z0, rho0, t, q, order, max_steps, out, info)

    return lane_tangent_block


lane_tangent_block = _build(LANE_TANGENT_STAMP)


def propagate(z0: np.ndarray, rho0: np.ndarray, t: np.ndarray, p: np.ndarray, tol: float,
              max_steps: int, *, block: int | None = None, threads: int | None = None
              ) -> tuple[np.ndarray, np.ndarray]:
    """:func:`andoyer.kernels.taylor.tangent.propagate` with
    :data:`~andoyer.kernels.taylor.lanes.LANES` orbits per vector step.

    Parameters
    ----------
    z0 : ndarray, shape (n, 6 + 6 k)
        Initial states and unit vectors ``(y, u_1 .. u_k)`` at ``t[0]``, ``k >= 1``.
    rho0 : ndarray, shape (n, k)
        ``ln|w_i(t[0])|``: where ``rho`` starts (broadcast).
    t : ndarray, shape (m,)
        Output times, non-decreasing; the MEGNO weights are ``t + delta``.
    p : ndarray, shape (8,)
        Kernel parameters :data:`andoyer.kernels.dop853.flow.PARAMS`.
    tol : float
        Tolerance of the local error (:func:`andoyer.kernels.taylor.flow.order_for`).
    max_steps : int
        Maximum steps per orbit.
    block : int, optional
        Orbits per block (default: the guided blocks of
        :func:`andoyer.kernels.taylor.lanes.block_starts`).
    threads : int, optional
        Threads (:func:`andoyer.kernels.threads.over_orbits`).

    Returns
    -------
    z : ndarray, shape (n, m, 6 + 7 k + 2)
        Rows ``(y, u_1 .. u_k, rho_1 .. rho_k, N, I)``; NaN where not reached.
    info : ndarray of int64, shape (n, 4)
        Columns :data:`andoyer.kernels.common.INFO` (``rejected`` is always 0).

    Raises
    ------
    ValueError
        If ``z0`` carries no tangent vector.

    Examples
    --------
    >>> from andoyer import RigidBody, from_andoyer
    >>> y0 = from_andoyer([[0.3, 1.1, 0.2, 1.0, -0.4]] * 9)
    >>> z0 = np.concatenate([y0, np.tile([0.0, 0.0, 0.0, 0.0, 0.0, 1.0], (9, 1))], axis=1)
    >>> z, info = propagate(z0, np.log([[2.0]]), np.array([0.0, 1.0]),
    ...                     np.asarray(RigidBody.paper().engine_params), 1e-12, 10**6)
    >>> z.shape, bool(np.all(info[:, 0] == common.SUCCESS))
    ((9, 2, 15), True)
    """
    import numba

    from andoyer.kernels.taylor.flow import n_vectors, order_for

    n = z0.shape[0]
    k = n_vectors(z0.shape[1])
    if k < 1:
        raise ValueError("z0 must carry at least one tangent vector (6 + 6 k floats, k >= 1)")
    out = np.full((n, t.shape[0], dimension(k)), np.nan)
    info = np.zeros((n, len(INFO)), dtype=np.int64)
    rho = np.ascontiguousarray(np.broadcast_to(rho0, (n, k)), dtype=np.float64)
    m = numba.get_num_threads() if threads is None else int(threads)
    blocks = {"starts": block_starts(n, m)} if block is None else {"block": int(block)}
    over_orbits(lane_tangent_block, n, (np.ascontiguousarray(z0, dtype=np.float64), rho),
                (out, info), (np.ascontiguousarray(t, dtype=np.float64), p, order_for(float(tol)),
                              int(max_steps)), threads=m, **blocks)
    return out, info
