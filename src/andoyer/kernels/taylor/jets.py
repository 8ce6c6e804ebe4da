r"""Jets and steps of the Taylor method of :mod:`andoyer.kernels.taylor.flow`: the Taylor
coefficients of a state (alone, with tangent vectors, or with the attitude quaternion)
from the generated recurrences of :mod:`andoyer.kernels.generated.recurrences`, the
Jorba-Zou step size from the last two coefficients, and the step's polynomial evaluated
(Horner) at an output time or at the step's end.

The jets of a state of ``k`` blocks are an array ``X`` of shape ``(k, order + 1, 6)``:
row ``X[b, j]`` holds the coefficients of order ``j`` of block ``b`` (the state, then
each tangent vector or the padded quaternion), row 0 the current value.

Plain Numba functions (:func:`~andoyer.kernels.common.kernel_jit`: no Python entry)
compiled into the cached entry points of :mod:`andoyer.kernels.taylor.flow` that call
them (their cache key, :data:`andoyer.kernels.taylor.flow.TAYLOR_STAMP`, hashes this
file too).
"""

from __future__ import annotations

import math

import numpy as np

from andoyer.kernels.common import N_STATE, STEP_TOO_SMALL, SUCCESS, kernel_jit
from andoyer.kernels.generated import recurrences
from andoyer.kernels.simd import root

__all__ = ["fill_constants", "state_jets", "tangent_jets", "attitude_jets",
           "radius", "step_size", "step_to", "section_step_size", "section_scale",
           "section_norms", "SECTION_STEP_FLOOR", "block_at",
           "horner", "advance", "advance_to", "load"]

#: Least fraction of the state's step that a section function's jet may leave
#: (:func:`section_step_size`): near ``G = 0`` an angle's section function has jets
#: growing without bound (its ``|G|`` factor), where it is undefined anyway.
SECTION_STEP_FLOOR = 1.0 / 16.0
#: Its inverse, exactly (a power of two: multiplying by it is dividing by the floor, bit
#: for bit, without a division's latency in the step size's chain).
_INV_FLOOR = 16.0


# Helpers: compiled into the entry points that call them (not cached on their own,
# see andoyer.kernels.dop853.flow's notes on the cache key).
_constants = kernel_jit(recurrences.ep_taylor_constants)
_jet = kernel_jit(recurrences.ep_taylor_jet)
_tangent_jet = kernel_jit(recurrences.ep_taylor_tangent_jet)
_attitude_jet = kernel_jit(recurrences.ep_taylor_attitude_jet)


@kernel_jit
def fill_constants(p, q):
    """``q`` = the folded body coefficients of the jets, from the kernel parameters."""
    c = _constants(p[0], p[1], p[2], p[3], p[4], p[5], p[6])
    for i in range(len(c)):
        q[i] = c[i]


@kernel_jit
def state_jets(X, order, q):
    """Jet of the state ``X[0]`` (row 0 is the current value) to ``order``."""
    _jet(X[0], order, q)


@kernel_jit
def tangent_jets(X, order, q):
    """Jets of the state ``X[0]`` and of the tangent vectors ``X[1:]`` (rows 0 of each
    are the current values), to ``order``."""
    _jet(X[0], order, q)
    for i in range(1, X.shape[0]):
        _tangent_jet(X[0], X[i], order, q)


@kernel_jit
def attitude_jets(X, order, q):
    """Jets of the state ``X[0]`` and of the attitude quaternion ``X[1, :, 0:4]`` (its
    block padded with two zero components, whose jets stay zero)."""
    _jet(X[0], order, q)
    _attitude_jet(X[0], X[1], order, q)
    for k in range(1, order + 1):
        X[1, k, 4] = 0.0
        X[1, k, 5] = 0.0


@kernel_jit
def radius(x, order):
    """rho of :mod:`andoyer.kernels.taylor.flow`'s notes for one block of jets ``x``
    (order + 1, 6)."""
    m = 0.0
    n1 = 0.0
    n2 = 0.0
    total = 0.0  # NaN or inf if any coefficient is (max() would drop a NaN)
    for i in range(x.shape[1]):
        m = max(m, abs(x[0, i]))
        n1 = max(n1, abs(x[order - 1, i]))
        n2 = max(n2, abs(x[order, i]))
        total += abs(x[0, i]) + abs(x[order - 1, i]) + abs(x[order, i])
    if not total < np.inf:  # a non-finite state or jet
        return np.nan
    m = max(1.0, m)
    rho = np.inf
    if n1 > 0.0:
        rho = root(m / n1, 1.0 / (order - 1))
    if n2 > 0.0:
        rho = min(rho, root(m / n2, 1.0 / order))
    return rho


@kernel_jit
def step_size(X, order):
    """Jorba-Zou step of :mod:`andoyer.kernels.taylor.flow`'s notes (least over the state
    and tangent vectors)."""
    rho = radius(X[0], order)
    if rho != rho:
        return rho
    for i in range(1, X.shape[0]):
        r = radius(X[i], order)
        if r != r:  # a non-finite vector (Numba's min(rho, NaN) would be rho)
            return r
        rho = min(rho, r)
    return rho * math.exp(-0.7 / (order - 1)) / (math.e * math.e)


@kernel_jit
def section_step_size(X, order, tape, u):
    """:func:`step_size` with the jet ``u[-1]`` of a section function ``f`` (the jets
    ``u`` of its tape ``tape``, :func:`~andoyer.kernels.taylor.sections.tape_jet`) as one
    more block, where its last two coefficients exceed the state's (elsewhere, and for
    every section of a state component, the step is :func:`step_size`'s). Its scale
    ``m`` is the larger of the state's and the root-sum-square of the two terms that
    ``f``'s last node sums (:func:`section_scale`; for theta2, crossed as
    ``g - (l + phi0 + value)``, the terms ``S_g c`` and ``C_g s``, at most the amplitude
    ``k = sqrt(f^2 + w^2)`` of the angle's pair, ``w`` the margin, so the scale can
    under-read ``k``: shorter steps, never longer). The step is never longer than
    :func:`step_size`'s, nor shorter than :data:`SECTION_STEP_FLOOR` of the state's (see
    :mod:`andoyer.kernels.taylor.flow`'s notes)."""
    last = tape.shape[0] - 1
    a1 = abs(u[last, order - 1])
    a2 = abs(u[last, order])
    m = 0.0
    n1 = 0.0
    n2 = 0.0
    total = 0.0  # NaN or inf if any coefficient is (max() would drop a NaN)
    for i in range(N_STATE):
        m = max(m, abs(X[0, 0, i]))
        n1 = max(n1, abs(X[0, order - 1, i]))
        n2 = max(n2, abs(X[0, order, i]))
        total += abs(X[0, 0, i]) + abs(X[0, order - 1, i]) + abs(X[0, order, i])
    if not (a1 > n1 or a2 > n2) or not total < np.inf:  # also NaN (f undefined: G = 0
        return step_size(X, order)  # on an angle section); a non-finite state: NaN
    a = tape[last, 1]
    b = tape[last, 2]
    m, n1, n2 = section_norms(m, n1, n2, a1, a2, section_scale(u[a, 0], u[b, 0], b),
                              order)
    rho = np.inf
    if n1 > 0.0:
        rho = root(m / n1, 1.0 / (order - 1))
    if n2 > 0.0:
        rho = min(rho, root(m / n2, 1.0 / order))
    for i in range(1, X.shape[0]):
        rho = min(rho, radius(X[i], order))  # NaN stays NaN: min(NaN, r) = NaN
        if rho != rho:
            return rho
    return rho * math.exp(-0.7 / (order - 1)) / (math.e * math.e)


@kernel_jit
def section_scale(fa, fb, b):
    """The scale of a section function's last node, the sum of the terms ``fa`` and
    ``fb`` (``b < 0``: one term): ``|fa|`` or ``sqrt(fa^2 + fb^2)`` (an angle
    section's pair, at most its amplitude: see :func:`section_step_size`)."""
    return abs(fa) if b < 0 else math.sqrt(fa * fa + fb * fb)


@kernel_jit
def section_norms(m, n1, n2, a1, a2, scale, order):
    """``(m, n1, n2)``: the state's scale and norms of its last two coefficients with a
    section function's block merged in (its coefficients ``a1, a2`` at the state's scale,
    capped: :func:`section_step_size`); ``m`` is ``max(1, m)``."""
    m = max(1.0, m)
    # f's block at the state's scale m (its radius unchanged: (M / a)^(1/k) with
    # a -> a m / M), merged into the state's norms, capped so that the radius shrinks
    # at most 1 / SECTION_STEP_FLOOR times.
    c = m / max(m, scale)
    cap = 1.0
    for _ in range(order - 1):
        cap *= _INV_FLOOR
    if a1 * c > n1:
        n1 = min(a1 * c, n1 * cap)
    if a2 * c > n2:
        n2 = min(a2 * c, n2 * cap * _INV_FLOOR)
    return m, n1, n2


@kernel_jit
def block_at(x, order, tau):
    """One block of jets ``x`` (order + 1, 6) at ``t0 + tau``: six Horner sums.

    The six sums run side by side (order outermost, one accumulator per component), not
    one after the other: each sum is a chain of dependent fused multiply-adds, and six
    independent chains keep the FMA units busy. Each component's operations are those
    of its own Horner loop, in the same order, so the values are bit for bit the same
    (about twice as fast; measured: benchmarks/NOTES.md#taylor-jets).
    """
    v0 = x[order, 0]
    v1 = x[order, 1]
    v2 = x[order, 2]
    v3 = x[order, 3]
    v4 = x[order, 4]
    v5 = x[order, 5]
    for k in range(order - 1, -1, -1):
        v0 = v0 * tau + x[k, 0]
        v1 = v1 * tau + x[k, 1]
        v2 = v2 * tau + x[k, 2]
        v3 = v3 * tau + x[k, 3]
        v4 = v4 * tau + x[k, 4]
        v5 = v5 * tau + x[k, 5]
    return v0, v1, v2, v3, v4, v5


@kernel_jit
def step_to(t, t_end, h):
    """``(status, t1, h)`` of a step of size ``h`` from ``t``; ``t1 <= t_end``: the one
    rule of the scalar orbit loops and the SIMD lanes (a step below ten ulps of ``t``, or
    NaN from a non-finite state, is STEP_TOO_SMALL)."""
    min_step = 10.0 * (np.nextafter(t, np.inf) - t)
    if not h >= min_step:  # also NaN (a non-finite state)
        return STEP_TOO_SMALL, t, 0.0
    t1 = t + h
    if t1 >= t_end:
        t1 = t_end
    return SUCCESS, t1, t1 - t  # h such that t + h = t1 in floating point


@kernel_jit
def horner(X, order, tau, out):
    """``out[6 b + i]`` = block ``b`` (state, then vectors) at ``t0 + tau``."""
    for b in range(X.shape[0]):
        v = block_at(X[b], order, tau)
        for i in range(N_STATE):
            out[N_STATE * b + i] = v[i]


@kernel_jit
def advance(X, order, h):
    """Replace rows 0 of the jets by the values at ``t0 + h`` (the next step's start)."""
    for b in range(X.shape[0]):
        v = block_at(X[b], order, h)
        for i in range(N_STATE):
            X[b, 0, i] = v[i]


@kernel_jit
def advance_to(X, order, h, y):
    """:func:`advance` with the state block's value at ``t0 + h`` already known (``y``,
    the six floats :func:`block_at` gave): the other blocks are evaluated."""
    for i in range(N_STATE):
        X[0, 0, i] = y[i]
    for b in range(1, X.shape[0]):
        v = block_at(X[b], order, h)
        for i in range(N_STATE):
            X[b, 0, i] = v[i]


@kernel_jit
def load(X, z):
    """Rows 0 of the jets ``X`` = the state ``z`` (6 + 6 k floats), block by block."""
    for b in range(X.shape[0]):
        for i in range(N_STATE):
            X[b, 0, i] = z[N_STATE * b + i]
