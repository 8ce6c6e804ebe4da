r"""Section tapes on SIMD lanes: the jet of a section function ``f(y(t))`` of
:data:`~andoyer.kernels.taylor.lanes.LANES` orbits at once, and each lane's step with
that jet in it -- the lane counterparts of :func:`~andoyer.kernels.taylor.sections.tape_jet`
and :func:`~andoyer.kernels.taylor.jets.section_step_size`, for the crossings of a
section that is not a state component (the angles theta2, g, l, theta1, psi; ``G``,
``J1``, ``J2``) in :mod:`andoyer.kernels.taylor.lane_crossings`.

The tape's jets of all lanes are one array ``U[k, node, lane]`` (lane innermost, as the
state's lane jets ``X[k, i, lane]``), evaluated node by node as the scalar interpreter
does, every node's orders in one vector loop:

* a variable or linear node is one vector multiply (and a fused multiply-add) per order
  (:func:`andoyer.kernels.simd.series_linear`);
* a product node is the Cauchy product of two earlier nodes, four orders at a time
  (four independent chains of vector multiply-adds,
  :func:`andoyer.kernels.simd.series_product`), the scalar tape's order of terms;
* a first integral (``DOT``: the area ``M = G . gamma``) is its value at order 0, a
  product with it (``SCALE``) one multiplication per order and lane;
* the square root's recurrence ``r^[k] = (a^[k] - sum_{0<j<k} r^[j] r^[k-j]) / (2 r^[0])``
  sums each pair of equal terms once, the newest pair last, in the scalar
  interpreter's order (:func:`~andoyer.kernels.taylor.sections.tape_jet`: the orders'
  chain one multiply-add long), then one multiplication per lane by
  ``1 / (2 r^[0])`` (computed once, as the scalar interpreter does).

Each lane's operations are the scalar interpreter's up to the contraction of sums into
fused multiply-adds, so a lane's section jet is the scalar one to round-off. The step of
every lane is :func:`~andoyer.kernels.taylor.jets.section_step_size`'s arithmetic in one
loop over the lanes (:func:`lane_section_steps`), so a lane takes the scalar kernel's
steps.

Plain Numba functions compiled into the entry point of
:mod:`andoyer.kernels.taylor.lane_crossings` (whose cache key hashes this file too).
"""

from __future__ import annotations

import math

import numpy as np

from andoyer.kernels import simd
from andoyer.kernels.common import N_STATE, kernel_jit
from andoyer.kernels.taylor.jets import section_norms, section_scale
from andoyer.kernels.taylor.sections import DOT, LIN, MUL, SCALE, VAR

__all__ = ["lane_tape_jet", "lane_section_steps"]

_L = simd.LANES
_N = N_STATE


@kernel_jit
def lane_tape_jet(tape, C, x, order, U):
    """``U[k, n, lane]``: the jets to ``order`` of the tape's nodes along the state's
    lane jets ``x[k, i, lane]``, node by node (the module notes). At ``order`` 0: the
    tape's values at the states ``x[0]``
    (:func:`~andoyer.kernels.taylor.sections.tape_value` of every lane)."""
    simd.tune()
    for n in range(tape.shape[0]):
        op = tape[n, 0]
        a = tape[n, 1]
        b = tape[n, 2]
        if op == VAR:
            for k in range(order + 1):
                simd.series_linear(U, n, x, a, 1.0, -1, 0.0, k)
        elif op == LIN:
            ca = C[tape[n, 3]]
            cb = C[tape[n, 4]] if b >= 0 else 0.0
            for k in range(order + 1):
                simd.series_linear(U, n, U, a, ca, b, cb, k)
            if tape[n, 5] >= 0:
                cc = C[tape[n, 5]]
                for lane in range(_L):
                    U[0, n, lane] += cc
        elif op == MUL:
            simd.series_product(U, n, a, b, order)
        elif op == DOT:  # a first integral: its jet is its value (state_dot per lane)
            for lane in range(_L):
                U[0, n, lane] = (x[0, a, lane] * x[0, b, lane]
                                 + x[0, a + 1, lane] * x[0, b + 1, lane]
                                 + x[0, a + 2, lane] * x[0, b + 2, lane])
            for k in range(1, order + 1):
                for lane in range(_L):
                    U[k, n, lane] = 0.0
        elif op == SCALE:  # the product with a first integral
            for k in range(order + 1):
                for lane in range(_L):
                    U[k, n, lane] = U[0, a, lane] * U[k, b, lane]
        elif order > 0:  # SQRT
            inv = np.empty(_L)
            v = np.empty(_L)
            for lane in range(_L):  # an idle lane's zero state: NaN, unused
                r = math.sqrt(U[0, a, lane])
                U[0, n, lane] = r
                inv[lane] = 1.0 / (2.0 * r) if r != 0.0 else np.nan
            for k in range(1, order + 1):  # sections.tape_jet's sum, lane by lane
                m = k // 2
                for lane in range(_L):
                    v[lane] = 0.5 * U[m, n, lane] * U[m, n, lane] if k % 2 == 0 else 0.0
                for j in range((k - 1) // 2, 1, -1):
                    for lane in range(_L):
                        v[lane] += U[j, n, lane] * U[k - j, n, lane]
                if k >= 3:
                    for lane in range(_L):
                        v[lane] += U[1, n, lane] * U[k - 1, n, lane]
                for lane in range(_L):
                    U[k, n, lane] = (U[k, a, lane] - 2.0 * v[lane]) * inv[lane]
        else:
            for lane in range(_L):
                U[0, n, lane] = math.sqrt(U[0, a, lane])


@kernel_jit
def lane_section_steps(X, U, order, tape, h, r1, r2):
    """``h[lane]``: :func:`~andoyer.kernels.taylor.jets.section_step_size` of every
    lane's state jets ``X[0, :, :, lane]`` and section jet ``U[:, :, lane]`` (states
    alone), in one loop over the lanes reading the lane arrays in place, with the
    scalar function's arithmetic (its pieces
    :func:`~andoyer.kernels.taylor.jets.section_norms` and
    :func:`~andoyer.kernels.taylor.jets.section_scale`; its roots on lane vectors,
    :func:`andoyer.kernels.simd.roots`, the same floats), so a lane takes the scalar
    kernel's steps. NaN where a value or coefficient is not finite; an idle lane's value
    is unused. ``r1, r2`` scratch (LANES,)."""
    simd.tune()
    last = tape.shape[0] - 1
    a = tape[last, 1]
    b = tape[last, 2]
    for lane in range(_L):
        a1 = abs(U[order - 1, last, lane])
        a2 = abs(U[order, last, lane])
        m = 0.0
        n1 = 0.0
        n2 = 0.0
        total = 0.0
        for i in range(_N):
            v0 = abs(X[0, 0, i, lane])
            v1 = abs(X[0, order - 1, i, lane])
            v2 = abs(X[0, order, i, lane])
            m = max(m, v0)
            n1 = max(n1, v1)
            n2 = max(n2, v2)
            total += v0 + v1 + v2
        if a1 > n1 or a2 > n2:
            m, n1, n2 = section_norms(m, n1, n2, a1, a2,
                                      section_scale(U[0, a, lane], U[0, b, lane], b), order)
        else:
            m = max(1.0, m)
        r1[lane] = m / n1 if n1 > 0.0 else np.inf
        r2[lane] = m / n2 if n2 > 0.0 else np.inf
        # NaN: not finite; inf: no coefficient (any step); else 0
        h[lane] = (np.nan if not total < np.inf
                   else np.inf if n1 == 0.0 and n2 == 0.0 else 0.0)
    simd.roots(r1, 1.0 / (order - 1), r1)
    simd.roots(r2, 1.0 / order, r2)
    for lane in range(_L):
        if h[lane] == 0.0:
            h[lane] = min(r1[lane], r2[lane]) * math.exp(-0.7 / (order - 1)) / (
                math.e * math.e)
