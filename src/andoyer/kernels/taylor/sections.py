r"""Section functions on Taylor polynomials, for the Taylor method of
:mod:`andoyer.kernels.taylor.flow`: the interpreter of a section function's tape along a state's
jet (the jet of ``f(y(t))`` on a step), and the roots of a step's polynomial
``P(s) = sum_k f^[k] (s h)^k`` on ``[0, 1]`` -- Bernstein coefficients, sign changes,
de Casteljau halving, a safeguarded Newton iteration in a bracket.

Plain Numba functions (:func:`~andoyer.kernels.common.kernel_jit`: the fast-math flags
:data:`~andoyer.kernels.common.FASTMATH`, no Python entry) compiled into the cached entry
points of :mod:`andoyer.kernels.taylor.flow` that call them (their cache key,
:data:`andoyer.kernels.taylor.flow.TAYLOR_STAMP`, hashes this file too);
:func:`section_jet` and :func:`section_tape` give the same to Python (tests, the engine).

One pass of the section function per step. The section search of
:mod:`andoyer.kernels.taylor.flow` carries the section function's value at a step's end
``f_b`` over as the next step's start value ``f_a``; both are the Bernstein end
coefficients of their steps (:func:`step_bernstein`), so a root on a step boundary is
counted once: at a step's start it belongs to the previous step, at its end to this one.

* The section of a state component (``G3 = c``, ``gamma_i = c``, ``L = c``: ``f = c_a
  y_i + c_c`` with ``|c_a| <= 1``, :func:`linear_component`) takes its jet from the
  state's column, no tape (:func:`column_polynomial`), and ``f_b = P(h)``, the state's own
  Horner sum to round-off. The next step's polynomial is blended to start at that value
  (:func:`scale_polynomial`), so the section function along the orbit is one continuous
  piecewise polynomial.
* Any other section takes its jet from one pass of the tape (:func:`tape_jet`, which
  the step size uses too; a tape of :func:`product_pair`'s form, the ``g = 0, pi``
  sections', from :func:`pair_jet`'s one loop with the same rows), and ``f_b`` is the
  tape at the step's end state (order 0).
  ``P(h)`` is not reliable there: the series of ``f`` (a square root of ``|G|^2`` for
  the angles and ``|G|``) need not converge on a step sized by the state's jets (carried
  over, such a ``P(h)`` added a theta2 crossing; measured:
  benchmarks/NOTES.md#taylor-sections).
* :func:`end_and_bound` gives ``P(h)`` and the bound :math:`B_2 = \sum_{k \ge 2}
  |f^{[k]}| h^k` in one loop (two independent Horner chains); a step with ``f_a`` and
  ``f_b`` of one sign whose line :math:`f^{[0]} + f^{[1]} \tau` stays farther from zero
  than :math:`B_2` cannot hold a root and skips the isolation (:func:`may_cross`).

Two helpers chosen by the caller, not one with both paths behind a runtime branch: a
helper's call costs (measured: benchmarks/NOTES.md#taylor-sections).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from andoyer.kernels.common import exact_jit, kernel_jit
from andoyer.kernels.generated import recurrences

__all__ = ["VAR", "LIN", "MUL", "SQRT", "DOT", "SCALE", "state_dot",
           "COMPONENT", "PAIR", "TAPE", "FAMILIES", "section_family",
           "ROOT_MAXITER", "tape_jet", "product_pair", "pair_jet",
           "linear_component", "end_and_bound", "may_cross",
           "column_polynomial", "jet_polynomial", "scale_polynomial",
           "bernstein_weights", "step_bernstein", "scaled_bernstein", "monotonic",
           "MAX_DEPTH", "MIN_WIDTH", "isolation_space", "isolate",
           "tape_value", "bernstein", "sign_changes", "poly", "poly_d", "solve_root",
           "casteljau", "section_jet", "section_tape"]

VAR, LIN, MUL, SQRT, DOT, SCALE = 0, 1, 2, 3, 4, 5  # ops of a section tape, see taylor_codegen
ROOT_MAXITER = 200
#: Bracket width (relative) at which :func:`solve_root` stops: 4 eps, a float the
#: compiled code reads as a constant (``np.finfo`` in the kernel would compile Numba's
#: finfo machinery on every cold start). 4 eps is exact: the same comparisons.
_ROOT_XTOL = 4.0 * float(np.finfo(np.float64).eps)


@kernel_jit
def cauchy(u, n, a, b, order):
    """``u[n, k] = sum_{j <= k} u[a, j] u[b, k - j]`` (k = 0 .. order), four orders at a
    time: four independent chains of multiply-adds in one loop over ``j`` (the one-order
    loop is one dependent chain). Each order's sum runs over ``j`` in ascending order."""
    k0 = 0
    while k0 + 3 <= order:
        v0 = 0.0
        v1 = 0.0
        v2 = 0.0
        v3 = 0.0
        for j in range(k0 + 1):
            x = u[a, j]
            v0 += x * u[b, k0 - j]
            v1 += x * u[b, k0 + 1 - j]
            v2 += x * u[b, k0 + 2 - j]
            v3 += x * u[b, k0 + 3 - j]
        x = u[a, k0 + 1]
        v1 += x * u[b, 0]
        v2 += x * u[b, 1]
        v3 += x * u[b, 2]
        x = u[a, k0 + 2]
        v2 += x * u[b, 0]
        v3 += x * u[b, 1]
        v3 += u[a, k0 + 3] * u[b, 0]
        u[n, k0] = v0
        u[n, k0 + 1] = v1
        u[n, k0 + 2] = v2
        u[n, k0 + 3] = v3
        k0 += 4
    for k in range(k0, order + 1):
        v = 0.0
        for j in range(k + 1):
            v += u[a, j] * u[b, k - j]
        u[n, k] = v


@kernel_jit
def state_dot(y, a, b):
    """``sum_{i < 3} y[a + i] y[b + i]``: a tape's ``DOT`` node (a first integral, the
    area ``M = G . gamma`` at ``a, b = 0, 3``) at the state ``y``."""
    return y[a] * y[b] + y[a + 1] * y[b + 1] + y[a + 2] * y[b + 2]


@kernel_jit
def tape_jet(tape, C, x, order, u):
    """Jets ``u[n, 0 .. order]`` of the nodes of a section function's tape along the
    state's jet ``x`` (the last node is the function): the tape interpreter (rows
    ``(op, a, b, ca, cb, cc)`` of :data:`andoyer.kernels.generated.recurrences.SECTION_TAPES`,
    constants ``C``). Products by :func:`cauchy`, four orders at a time (faster; the
    crossings within round-off of a one-order loop's -- measured:
    benchmarks/NOTES.md#taylor-sections); a first integral (``DOT``) by its value alone
    and a product with it (``SCALE``) by one multiplication per order: ``x`` must be
    the jet of a solution of (1) (the state's jets), along which those jets are the
    integral's, to round-off."""
    # Node by node (each node reads earlier nodes only, and the state's jet is known to
    # the full order): one dispatch per node, not per node and order.
    for n in range(tape.shape[0]):
        op = tape[n, 0]
        a = tape[n, 1]
        b = tape[n, 2]
        if op == VAR:
            for k in range(order + 1):
                u[n, k] = x[k, a]
        elif op == LIN:
            ca = C[tape[n, 3]]
            if b >= 0:
                cb = C[tape[n, 4]]
                for k in range(order + 1):
                    u[n, k] = ca * u[a, k] + cb * u[b, k]
            else:
                for k in range(order + 1):
                    u[n, k] = ca * u[a, k]
            if tape[n, 5] >= 0:
                u[n, 0] += C[tape[n, 5]]
        elif op == MUL:
            cauchy(u, n, a, b, order)
        elif op == DOT:  # a first integral: its jet is its value
            u[n, 0] = state_dot(x[0], a, b)
            for k in range(1, order + 1):
                u[n, k] = 0.0
        elif op == SCALE:  # the product with a first integral
            c = u[a, 0]
            for k in range(order + 1):
                u[n, k] = c * u[b, k]
        else:  # SQRT
            r = math.sqrt(u[a, 0])
            u[n, 0] = r
            inv = 1.0 / (2.0 * r) if r != 0.0 else np.nan
            # The sum's pairs of equal terms once (the middle term j = k / 2 halved), the
            # newest pair r^[1] r^[k-1] last: the other terms do not wait for r^[k-1],
            # so the orders' chain is one multiply-add long, not k - 1 (2.7x faster at
            # order 15, the floats within an ulp; the lanes sum in this order). Inline:
            # a helper's call per order costs more than it saves.
            for k in range(1, order + 1):
                v = 0.5 * u[n, k // 2] * u[n, k // 2] if k % 2 == 0 else 0.0
                for j in range((k - 1) // 2, 1, -1):
                    v += u[n, j] * u[n, k - j]
                if k >= 3:
                    v += u[n, 1] * u[n, k - 1]
                u[n, k] = (u[a, k] - 2.0 * v) * inv


#: The rows of a tape whose function is a scaled sum of two products of state
#: components, ``c_s (c_a y_i y_j + c_b y_k y_l)`` (:func:`product_pair`): the reduced
#: ``g = 0, pi`` function ``cos(value) (G2 gamma1 - G1 gamma2)``.
_PAIR_ROWS = 8


@kernel_jit
def product_pair(tape):
    """``(i, j, k, l)`` when the tape's function is ``c_s (c_a y_i y_j + c_b y_k y_l)``
    (rows: the four variables, the two products, their linear sum and its scaling, the
    form of the reduced ``g = 0, pi`` tapes, ``SIN_ZERO_TAPES``), else ``(-1, -1, -1,
    -1)``. Its jet is :func:`pair_jet`'s one loop instead of a pass of the tape
    interpreter."""
    ok = (tape.shape[0] == _PAIR_ROWS and tape[0, 0] == VAR and tape[1, 0] == VAR
          and tape[2, 0] == MUL and tape[2, 1] == 0 and tape[2, 2] == 1
          and tape[3, 0] == VAR and tape[4, 0] == VAR
          and tape[5, 0] == MUL and tape[5, 1] == 3 and tape[5, 2] == 4
          and tape[6, 0] == LIN and tape[6, 1] == 2 and tape[6, 2] == 5 and tape[6, 5] < 0
          and tape[7, 0] == LIN and tape[7, 1] == 6 and tape[7, 2] < 0 and tape[7, 5] < 0)
    if not ok:
        return -1, -1, -1, -1
    return tape[0, 1], tape[1, 1], tape[3, 1], tape[4, 1]


#: The families of section tapes, each with its own compiled loop, so that a call compiles
#: only its own (a cold G3 section none of the angle sections' jets): a state component
#: (:func:`linear_component`), a tape of :func:`product_pair`'s form, any other.
COMPONENT, PAIR, TAPE = 0, 1, 2
FAMILIES = (COMPONENT, PAIR, TAPE)
#: Their names (the tags of their kernels: :func:`andoyer.kernels.common.variant`).
FAMILY_NAMES = ("component", "pair", "tape")


def section_family(tape: np.ndarray, C: np.ndarray) -> int:
    """The family of the section of tape ``tape`` and constants ``C``: the kernels' own
    recognisers (:func:`linear_component`, :func:`product_pair`), run in Python.

    Parameters
    ----------
    tape, C : ndarray
        A section's tape and constants (:func:`section_tape`).

    Examples
    --------
    >>> [section_family(*section_tape(kind, 0.0, 0.0)) for kind in (2, 11, 13)]
    [0, 1, 2]
    """
    if linear_component.py_func(tape, C)[0] >= 0:
        return COMPONENT
    if product_pair.py_func(tape)[0] >= 0:
        return PAIR
    return TAPE


@kernel_jit
def pair_jet(tape, C, x, order, u, i, j, k, l):
    """:func:`tape_jet` of a tape of :func:`product_pair`'s form (``y_i y_j``, ``y_k y_l``
    its products), rows 2, 5, 6 and 7 of ``u`` (the products, their sum, the function):
    the products as :func:`cauchy`'s, four orders at a time, both in one loop, read from
    the state's jet (no copy of the variables), then the linear rows' own expressions,
    with no dispatch per row. On the 7:1 orbit of the report (``g = 0``, order 14) the
    section's step 7-14 % faster than with the interpreter (measured:
    benchmarks/NOTES.md#pair-jet)."""
    k0 = 0
    while k0 + 3 <= order:
        v0 = 0.0
        v1 = 0.0
        v2 = 0.0
        v3 = 0.0
        w0 = 0.0
        w1 = 0.0
        w2 = 0.0
        w3 = 0.0
        for m in range(k0 + 1):
            y = x[m, i]
            z = x[m, k]
            v0 += y * x[k0 - m, j]
            v1 += y * x[k0 + 1 - m, j]
            v2 += y * x[k0 + 2 - m, j]
            v3 += y * x[k0 + 3 - m, j]
            w0 += z * x[k0 - m, l]
            w1 += z * x[k0 + 1 - m, l]
            w2 += z * x[k0 + 2 - m, l]
            w3 += z * x[k0 + 3 - m, l]
        y = x[k0 + 1, i]
        z = x[k0 + 1, k]
        v1 += y * x[0, j]
        v2 += y * x[1, j]
        v3 += y * x[2, j]
        w1 += z * x[0, l]
        w2 += z * x[1, l]
        w3 += z * x[2, l]
        y = x[k0 + 2, i]
        z = x[k0 + 2, k]
        v2 += y * x[0, j]
        v3 += y * x[1, j]
        w2 += z * x[0, l]
        w3 += z * x[1, l]
        v3 += x[k0 + 3, i] * x[0, j]
        w3 += x[k0 + 3, k] * x[0, l]
        u[2, k0] = v0
        u[2, k0 + 1] = v1
        u[2, k0 + 2] = v2
        u[2, k0 + 3] = v3
        u[5, k0] = w0
        u[5, k0 + 1] = w1
        u[5, k0 + 2] = w2
        u[5, k0 + 3] = w3
        k0 += 4
    for n in range(k0, order + 1):
        v = 0.0
        w = 0.0
        for m in range(n + 1):
            v += x[m, i] * x[n - m, j]
            w += x[m, k] * x[n - m, l]
        u[2, n] = v
        u[5, n] = w
    ca = C[tape[6, 3]]
    cb = C[tape[6, 4]]
    cs = C[tape[7, 3]]
    for n in range(order + 1):
        u[6, n] = ca * u[2, n] + cb * u[5, n]
    for n in range(order + 1):
        u[7, n] = cs * u[6, n]


@kernel_jit
def linear_component(tape, C):
    """``(i, ca, cc)`` when the tape's function is ``ca y_i + cc`` with ``|ca| <= 1``
    (the section of a state component, ``G3 = value``, ``gamma1 = value``, ``L = value``
    ...), else ``(-1, 0, 0)``. The jet of such a function is a column of the state's jet:
    no tape pass is needed (:func:`column_polynomial`), and its coefficients never exceed
    the state's, so its step is the state's (``taylor_jets.section_step_size``)."""
    if (tape.shape[0] == 2 and tape[0, 0] == VAR and tape[1, 0] == LIN and tape[1, 1] == 0
            and tape[1, 2] < 0 and abs(C[tape[1, 3]]) <= 1.0):
        cc = C[tape[1, 5]] if tape[1, 5] >= 0 else 0.0
        return tape[0, 1], C[tape[1, 3]], cc
    return -1, 0.0, 0.0


@kernel_jit
def end_and_bound(a, order, h):
    r"""``(P(h), B_2)`` for the jet ``a[k] = f^{[k]}`` of a section function on a step of
    size ``h``: the polynomial :math:`P(\tau) = \sum_k a_k \tau^k` at the step's end and
    :math:`B_2 = \sum_{k \ge 2} |a_k| h^k`, which bounds :math:`|P(\tau) - a_0 - a_1
    \tau|` on the step (:func:`may_cross`). Two independent Horner sums in one loop (two
    chains of dependent multiply-adds side by side)."""
    v = a[order]
    w = abs(a[order])
    for k in range(order - 1, 1, -1):
        v = v * h + a[k]
        w = w * h + abs(a[k])
    v = v * h + a[1]
    return v * h + a[0], w * h * h


@kernel_jit
def may_cross(fa, fb, a0, a1h, bound2):
    r"""False where a step's polynomial cannot reach zero, so the root isolation is
    skipped: ``fa``, ``fb`` (the carried end values) of one sign ``s`` and

    .. math:: s a_0 + \min(0, s a_1 h) > 1.000001\,(B_2 + |f_a - a_0|)
              + 10^{-15} (|a_0| + |a_1 h|)

    (the line :math:`a_0 + a_1 \tau` stays on the side of ``s`` over the step, by more
    than the rest of the polynomial, :math:`B_2` of :func:`end_and_bound`, the blend of
    the start to ``fa`` and round-off). It keeps off every step that the bound
    :math:`|f_a| > B = |a_1| h + B_2` did, and the steps before a crossing whose line
    ends short of zero (about one a crossing; measured: benchmarks/NOTES.md#section-cost).
    """
    if (fa > 0.0 and fb > 0.0) or (fa < 0.0 and fb < 0.0):
        s = 1.0 if fa > 0.0 else -1.0
        low = s * a0 + min(0.0, s * a1h)
        if low > 1.000001 * (bound2 + abs(fa - a0)) + 1e-15 * (abs(a0) + abs(a1h)):
            return False
    return True


@kernel_jit
def column_polynomial(x, component, ca, cc, order, h, a):
    """:func:`end_and_bound` of the function ``ca y_i + cc`` (:func:`linear_component`,
    ``i = component``), whose jet ``a`` is a column of the state's jet ``x``: no tape."""
    for k in range(order + 1):
        a[k] = ca * x[k, component]
    a[0] += cc
    return end_and_bound(a, order, h)


@kernel_jit
def jet_polynomial(f, order, h, a):
    """:func:`end_and_bound` of a section function's jet ``f`` (order + 1,), e.g. the
    last node of :func:`tape_jet`'s work space, copied to ``a``."""
    for k in range(order + 1):
        a[k] = f[k]
    return end_and_bound(a, order, h)


@kernel_jit
def scale_polynomial(a, order, h, fa):
    r"""``a[k] *= h^k`` (the step's polynomial ``P(s)`` on ``s`` in ``[0, 1]``), made
    continuous with the previous step's: ``P(0)`` is set to ``fa``, the previous step's
    ``P(h)``, by the linear blend :math:`(f_a - a_0)(1 - s)`, which vanishes at the end.
    So the section function along the orbit is one continuous piecewise polynomial and a
    root on a step boundary has the same sign on both sides (counted once, see the
    boundary rules of :mod:`andoyer.kernels.taylor.flow`); the blend never accumulates (each
    step's end value is its own ``P(h)``). ``fa - a_0`` is the previous polynomial's
    truncation error at its end (round-off for a linear ``f``)."""
    hk = h
    for k in range(1, order + 1):
        a[k] *= hk
        hk *= h
    d = fa - a[0]
    a[0] = fa
    a[1] -= d


@kernel_jit
def bernstein_weights(order):
    """``W[i, k] = C(i, k) / C(p, k)`` (``p = order``) of :func:`bernstein`: Pascal's
    triangle (exact), then divided by its last row."""
    n = order + 1
    W = np.zeros((n, n))
    for i in range(n):
        W[i, 0] = 1.0
        for k in range(1, i + 1):
            W[i, k] = W[i - 1, k - 1] + (W[i - 1, k] if k < i else 0.0)
    for i in range(n - 1):
        for k in range(i + 1):
            W[i, k] /= W[order, k]
    for k in range(n):
        W[order, k] = 1.0
    return W


@kernel_jit
def step_bernstein(a, order, h, W, fa, fb, B):
    """The Bernstein coefficients ``B`` on ``[0, 1]`` of a step's polynomial: ``a``
    scaled to the step and made to start at ``fa`` (:func:`scale_polynomial`), its end
    coefficients the carried values ``fa`` and ``fb`` (the section function at the
    step's start and end), with the boundary rules: a root at the start (``fa == 0``)
    belongs to the previous step, one at the end (``fb == 0``) to this one (the zero
    end takes the sign that puts the root inside this step, or outside it)."""
    scale_polynomial(a, order, h, fa)
    scaled_bernstein(a, order, W, fa, fb, B)


@kernel_jit
def scaled_bernstein(a, order, W, fa, fb, B):
    """:func:`step_bernstein` of a polynomial ``a`` already scaled to the step
    (:func:`scale_polynomial`)."""
    bernstein(a, order, W, B)
    B[0] = fa
    B[order] = fb
    if fa == 0.0:  # a root at the start belongs to the previous step
        for i in range(1, order + 1):
            if B[i] != 0.0:
                B[0] = 1e-300 * (1.0 if B[i] > 0.0 else -1.0)
                break
    if fb == 0.0:  # a root at the end belongs to this step
        for i in range(order - 1, -1, -1):
            if B[i] != 0.0:
                B[order] = -1e-300 * (1.0 if B[i] > 0.0 else -1.0)
                break


#: Bisections of a step in the root isolation, and the narrowest isolating interval
#: (a fraction of the step): two roots closer than that are taken for none.
MAX_DEPTH = 60
MIN_WIDTH = 1e-13


@kernel_jit
def isolation_space(order):
    """Work space of :func:`isolate` for polynomials of ``order``: the stack of Bernstein
    coefficients, its intervals' ends, de Casteljau's left half, the roots."""
    n = order + 1
    return (np.empty((MAX_DEPTH + 2, n)), np.empty(MAX_DEPTH + 2), np.empty(MAX_DEPTH + 2),
            np.empty(n), np.empty(n))


@kernel_jit
def isolate(a, order, h, W, fa, fb, direction, stack, lo_s, hi_s, left, roots):
    """The roots in ``[0, 1]`` of one step's polynomial ``a`` (the section function's
    jet; ``fa``, ``fb`` its carried end values, see :func:`step_bernstein`) crossed in
    ``direction`` (+1 upward, -1 downward, 0 both), in time order: ``roots[:found]``,
    returns ``found``. An interval whose Bernstein coefficients change sign more than
    once is halved (right half pushed first, so the left one comes out first), down to
    :data:`MIN_WIDTH` of the step; one change is one root, solved by :func:`solve_root`.
    Work space from :func:`isolation_space`.

    A step whose polynomial is monotonic (:func:`monotonic`: most steps that reach this
    function hold one crossing) has one root where ``fa`` and ``fb`` have opposite signs
    and none elsewhere: it is solved (or, crossed in the other direction, skipped)
    without Bernstein coefficients, by the call the isolation makes when they change
    sign once."""
    scale_polynomial(a, order, h, fa)
    if fa != 0.0 and fb != 0.0 and monotonic(a, order):
        if (fa > 0.0) == (fb > 0.0) or (fb > fa) != (a[1] > 0.0):
            return 0 if (fa > 0.0) == (fb > 0.0) else _isolate(
                a, order, W, fa, fb, direction, stack, lo_s, hi_s, left, roots)
        up = fa < 0.0
        if (up and direction < 0) or (not up and direction > 0):
            return 0
        roots[0] = solve_root(a, order, 0.0, 1.0, fa)
        return 1
    return _isolate(a, order, W, fa, fb, direction, stack, lo_s, hi_s, left, roots)


@kernel_jit
def monotonic(a, order):
    r"""Whether :math:`P(s) = \sum_k a_k s^k` is monotonic on ``[0, 1]``:
    :math:`|a_1| > 1.000001 \sum_{k \ge 2} k |a_k|` (a bound of :math:`|P' - a_1|`)."""
    d = 0.0
    for k in range(2, order + 1):
        d += k * abs(a[k])
    return abs(a[1]) > 1.000001 * d


@kernel_jit
def _isolate(a, order, W, fa, fb, direction, stack, lo_s, hi_s, left, roots):
    """:func:`isolate` by Bernstein coefficients, ``a`` scaled to the step."""
    n = order + 1
    scaled_bernstein(a, order, W, fa, fb, stack[0])
    lo_s[0] = 0.0
    hi_s[0] = 1.0
    top = 1
    found = 0
    while top > 0 and found < roots.shape[0]:
        top -= 1
        B = stack[top]
        lo = lo_s[top]
        hi = hi_s[top]
        v = sign_changes(B, n)
        if v == 0:
            continue
        if v >= 2 and hi - lo > MIN_WIDTH and top + 2 <= MAX_DEPTH:
            casteljau(B, n, left, stack[top + 1])
            for i in range(n):
                B[i] = stack[top + 1, i]  # right half, in place
            for i in range(n):
                stack[top + 1, i] = left[i]
            mid = 0.5 * (lo + hi)
            lo_s[top] = mid
            hi_s[top] = hi
            lo_s[top + 1] = lo
            hi_s[top + 1] = mid
            top += 2
            continue
        flo = B[0]
        fhi = B[order]
        if flo == 0.0 or fhi == 0.0 or (flo > 0.0) == (fhi > 0.0):
            continue  # an even number of roots too close to tell apart
        up = flo < 0.0
        if (up and direction < 0) or (not up and direction > 0):
            continue
        roots[found] = solve_root(a, order, lo, hi, flo)
        found += 1
    return found


@kernel_jit
def bernstein(a, order, W, B):
    """Bernstein coefficients on [0, 1] of ``sum_k a[k] s^k``: ``B[i] = sum_{k<=i}
    W[i, k] a[k]`` with ``W[i, k] = C(i, k) / C(p, k)``."""
    for i in range(order + 1):
        acc = 0.0
        for k in range(i + 1):
            acc += W[i, k] * a[k]
        B[i] = acc


@kernel_jit
def sign_changes(B, n):
    count = 0
    last = 0.0
    for i in range(n):
        if B[i] != 0.0:
            if last != 0.0 and (B[i] > 0.0) != (last > 0.0):
                count += 1
            last = B[i]
    return count


@kernel_jit
def poly(a, order, s):
    v = a[order]
    for k in range(order - 1, -1, -1):
        v = v * s + a[k]
    return v


@kernel_jit
def poly_d(a, order, s):
    v = a[order]
    d = 0.0
    for k in range(order - 1, -1, -1):
        d = d * s + v
        v = v * s + a[k]
    return v, d


@kernel_jit
def solve_root(a, order, lo, hi, flo):
    """The root of ``P = sum a[k] s^k`` in ``[lo, hi]`` where ``P`` changes sign once
    (``flo`` its sign at ``lo``): Newton steps kept inside the bracket, else bisection,
    until the bracket is 4 eps wide or a Newton step no longer moves ``s`` (converged:
    ``s`` is then an end of the bracket, and taking that step for one leaving it would
    bisect the whole bracket again, 20-50 evaluations instead of 4-6)."""
    s = 0.5 * (lo + hi)
    up = flo < 0.0
    for _ in range(ROOT_MAXITER):
        v, d = poly_d(a, order, s)
        if v == 0.0:
            return s
        if (v < 0.0) == up:
            lo = s
        else:
            hi = s
        if hi - lo <= _ROOT_XTOL * max(1.0, abs(s)):
            break
        nxt = s - v / d if d != 0.0 else 0.5 * (lo + hi)
        if nxt == s:
            break
        if not (lo < nxt < hi):
            nxt = 0.5 * (lo + hi)
        s = nxt
    return s


@kernel_jit
def casteljau(B, n, left, right):
    """Split Bernstein coefficients ``B[:n]`` of [0, 1] at 1/2 into those of the halves."""
    for i in range(n):
        right[i] = B[i]
    for r in range(1, n):
        left[r - 1] = right[0]
        for i in range(n - r):
            right[i] = 0.5 * (right[i] + right[i + 1])
    left[n - 1] = right[0]


@kernel_jit
def tape_value(tape, C, Y, u):
    """A section tape's function at the state ``Y[0]``: :func:`tape_jet` at order 0, the
    same floats (each node's one multiply-add as there), without its loops over orders.
    Called once a step (the step's end value ``f_b``): less than half the time of
    ``tape_jet`` at order 0 (measured: benchmarks/NOTES.md#taylor-sections)."""
    for n in range(tape.shape[0]):
        op = tape[n, 0]
        a = tape[n, 1]
        b = tape[n, 2]
        if op == VAR:
            u[n, 0] = Y[0, a]
        elif op == LIN:
            ca = C[tape[n, 3]]
            if b >= 0:
                cb = C[tape[n, 4]]
                u[n, 0] = ca * u[a, 0] + cb * u[b, 0]
            else:
                u[n, 0] = ca * u[a, 0]
            if tape[n, 5] >= 0:
                u[n, 0] += C[tape[n, 5]]
        elif op == MUL:
            v = 0.0  # as tape_jet's sum (0 + a b, not a b: the same zero's sign)
            v += u[a, 0] * u[b, 0]
            u[n, 0] = v
        elif op == DOT:
            u[n, 0] = state_dot(Y[0], a, b)
        elif op == SCALE:
            u[n, 0] = u[a, 0] * u[b, 0]
        else:  # SQRT
            u[n, 0] = math.sqrt(u[a, 0])
    return u[tape.shape[0] - 1, 0]


@exact_jit
def section_jet(tape, C, x, order):
    """The jet of a section function or margin (:func:`section_tape`) along a state's
    jet ``x`` (order + 1, 6): shape (order + 1,)."""
    u = np.empty((tape.shape[0], order + 1))
    tape_jet(tape, C, x, order, u)
    return u[tape.shape[0] - 1].copy()


def section_tape(kind: int, phi0: float, value: float, *, margin: bool = False
                 ) -> tuple[np.ndarray, np.ndarray]:
    """The tape (int rows) and constants of the section function ``f`` of ``kind = value``
    (its margin ``w`` if ``margin``): the generated
    :data:`~andoyer.kernels.generated.recurrences.SECTION_TAPES` and ``section_constants``
    (``MARGIN_TAPES``, ``margin_constants``); where ``sin(value)`` or ``cos(value)`` is zero
    (the float nearest ``0``, ``pi``; ``+-pi/2``: within an ulp of ``value``) and the kind
    has one, the reduced ``f`` (``SIN_ZERO_TAPES``, ``COS_ZERO_TAPES``,
    :func:`andoyer.symbolic.sections.section_function_reduced`: the same crossings within
    round-off, no square root; ``g = 0`` about 1.8x faster, measured:
    benchmarks/NOTES.md#scalar-angle-section).

    Parameters
    ----------
    kind : int
        Index into the section kinds.
    phi0 : float
        The body's ``phi0`` (Hess-chart sections).
    value : float
        The section value.
    margin : bool, default False
        The tape of the margin ``w`` instead of ``f``.
    """
    g = recurrences
    tapes: Any
    constants: Any
    # the float nearest k pi / 2 has |sin| or |cos| of at most half its ulp
    if margin:
        tapes, constants = g.MARGIN_TAPES, g.margin_constants
    elif abs(math.sin(value)) <= math.ulp(value) and g.SIN_ZERO_TAPES[kind]:
        tapes, constants = g.SIN_ZERO_TAPES, g.sin_zero_constants
    elif abs(math.cos(value)) <= math.ulp(value) and g.COS_ZERO_TAPES[kind]:
        tapes, constants = g.COS_ZERO_TAPES, g.cos_zero_constants
    else:
        tapes, constants = g.SECTION_TAPES, g.section_constants
    tape = np.array(tapes[kind], dtype=np.int64)
    C = np.array(constants(kind, phi0, value, math.cos(value), math.sin(value)),
                 dtype=np.float64)
    return tape, C
