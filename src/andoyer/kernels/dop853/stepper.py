"""The DOP853 stepper for any right-hand side, compiled with Numba (no entry points).

:func:`make_stepper` builds, for a compiled ``field(t, y, p, out)``, the pieces of the
method described in :mod:`andoyer.kernels.dop853.flow`: stages, starting step,
controlled step, dense output, one orbit to output times and one orbit's section
crossings. The coefficients are :mod:`andoyer.kernels.dop853.coefficients`. The pieces
are not cached themselves: cached entry points (:mod:`andoyer.kernels.dop853.flow`,
:mod:`andoyer.kernels.dop853.tangent`) call them, and their cache key covers this file.
They are compiled into those entry points only
(:func:`~andoyer.kernels.common.kernel_jit`: no Python entry, no optimisation or machine
code of their own; each entry point is optimised once, as one unit; the cold compile is
shorter and the floats the same bit for bit -- measured: benchmarks/NOTES.md#link-only).
"""

from __future__ import annotations

import math
from typing import Any, NamedTuple

import numpy as np

from andoyer.kernels.common import (
    MAX_STEPS,
    N_STATE,
    STEP_TOO_SMALL,
    SUCCESS,
    T_START,
    kernel_jit,
    kernel_variant,
)
from andoyer.kernels.dop853.coefficients import (
    E3,
    ER,
    ERROR_EXPONENT,
    GOLDEN,
    GRAZE_XTOL,
    INTERPOLATOR_POWER,
    MAX_FACTOR,
    MIN_FACTOR,
    N_STAGES,
    N_STAGES_EXTENDED,
    ROOT_MAXITER,
    ROOT_XTOL,
    SAFETY,
    A,
    C,
    D,
)
from andoyer.kernels.generated import equations

#: Dimension of the Euler-Poisson state (G1, G2, G3, gamma1, gamma2, gamma3): the stages
#: of a field of this size keep their sums in registers.
N = N_STATE

__all__ = ["N", "make_stepper", "Stepper", "dense_eval"]

# Helpers: compiled into the entry points that call them only (not cached on their own,
# no Python entry; see the module notes).
_section = kernel_jit(equations.section)



@kernel_jit
def _section_fw(y, p, kind, value, cv, sv):
    # The section reads the Euler-Poisson state, the first six components of y.
    return _section(kind, y[0], y[1], y[2], y[3], y[4], y[5], p[7], value, cv, sv)


@kernel_jit
def _error_norm(y, y1, K, h, rtol, atol):
    n = y.shape[0]
    e5 = 0.0
    e3 = 0.0
    for i in range(n):
        s5 = 0.0
        s3 = 0.0
        for j in range(N_STAGES):
            s5 += ER[j] * K[j, i]
            s3 += E3[j] * K[j, i]
        sc = atol + rtol * max(abs(y[i]), abs(y1[i]))
        e5 += (s5 / sc) ** 2
        e3 += (s3 / sc) ** 2
    if e5 == 0.0 and e3 == 0.0:
        return 0.0
    return abs(h) * e5 / math.sqrt((e5 + 0.01 * e3) * n)


@kernel_jit
def dense_eval(F, y, x, out):
    """``y(t0 + x h)`` from the dense-output rows ``F`` of a step starting at ``y``."""
    x1 = 1.0 - x
    for i in range(y.shape[0]):
        v = F[6, i] * x
        v = (F[5, i] + v) * x1
        v = (F[4, i] + v) * x
        v = (F[3, i] + v) * x1
        v = (F[2, i] + v) * x
        v = (F[1, i] + v) * x1
        v = (F[0, i] + v) * x
        out[i] = y[i] + v


@kernel_jit
def _f_at(F, y, x, p, kind, value, cv, sv, ytmp):
    dense_eval(F, y, x, ytmp)
    return _section_fw(ytmp, p, kind, value, cv, sv)[0]


@kernel_jit
def _root(F, y, p, kind, value, cv, sv, xa, xb, fa, fb, ytmp):
    """Root in ``[xa, xb]`` of ``f(y(t0 + theta h))`` with ``f(xa) = fa``, ``f(xb) = fb``
    of opposite signs: Brent's method as in scipy's ``brentq``, to ``ROOT_XTOL``."""
    xpre, xcur = xa, xb
    fpre, fcur = fa, fb
    xblk, fblk = xa, 0.0
    spre, scur = 0.0, 0.0
    if fpre == 0.0:
        return xpre
    if fcur == 0.0:
        return xcur
    for _ in range(ROOT_MAXITER):
        if fpre != 0.0 and fcur != 0.0 and (fpre < 0.0) != (fcur < 0.0):
            xblk, fblk = xpre, fpre
            spre = scur = xcur - xpre
        if abs(fblk) < abs(fcur):
            xpre, xcur, xblk = xcur, xblk, xcur
            fpre, fcur, fblk = fcur, fblk, fcur
        delta = 0.5 * ROOT_XTOL * (1.0 + abs(xcur))
        sbis = 0.5 * (xblk - xcur)
        if fcur == 0.0 or abs(sbis) < delta:
            return xcur
        if abs(spre) > delta and abs(fcur) < abs(fpre):
            if xpre == xblk:  # secant
                stry = -fcur * (xcur - xpre) / (fcur - fpre)
            else:  # inverse quadratic interpolation
                dpre = (fpre - fcur) / (xpre - xcur)
                dblk = (fblk - fcur) / (xblk - xcur)
                stry = -fcur * (fblk * dblk - fpre * dpre) / (dblk * dpre * (fblk - fpre))
            if 2.0 * abs(stry) < min(abs(spre), 3.0 * abs(sbis) - delta):
                spre, scur = scur, stry
            else:
                spre, scur = sbis, sbis
        else:
            spre, scur = sbis, sbis
        xpre, fpre = xcur, fcur
        if abs(scur) > delta:
            xcur += scur
        else:
            xcur += delta if sbis > 0.0 else -delta
        fcur = _f_at(F, y, xcur, p, kind, value, cv, sv, ytmp)
    return xcur


@kernel_jit
def _closest_approach(F, y, p, kind, value, cv, sv, sign, ytmp):
    """``(theta, f)`` where ``sign * f`` is least on the step (golden-section search,
    assuming one minimum in the step)."""
    a, b = 0.0, 1.0
    x1 = b - GOLDEN * (b - a)
    x2 = a + GOLDEN * (b - a)
    f1 = sign * _f_at(F, y, x1, p, kind, value, cv, sv, ytmp)
    f2 = sign * _f_at(F, y, x2, p, kind, value, cv, sv, ytmp)
    while b - a > GRAZE_XTOL and f1 > 0.0 and f2 > 0.0:
        if f1 < f2:
            b, x2, f2 = x2, x1, f1
            x1 = b - GOLDEN * (b - a)
            f1 = sign * _f_at(F, y, x1, p, kind, value, cv, sv, ytmp)
        else:
            a, x1, f1 = x1, x2, f2
            x2 = a + GOLDEN * (b - a)
            f2 = sign * _f_at(F, y, x2, p, kind, value, cv, sv, ytmp)
    if f1 < f2:
        return x1, sign * f1
    return x2, sign * f2


@kernel_jit
def _record(F, y, t, h, p, kind, value, cv, sv, direction, xa, xb, fa, fb, tc, yc,
            count, ytmp):
    """Locate the root bracketed by ``[xa, xb]`` of a step and append it to ``tc, yc``
    if its direction is wanted and the margin ``w`` is positive; returns the count."""
    up = fa < 0.0
    if count >= tc.shape[0] or (up and direction < 0) or (not up and direction > 0):
        return count
    theta = _root(F, y, p, kind, value, cv, sv, xa, xb, fa, fb, ytmp)
    dense_eval(F, y, theta, ytmp)
    # The margin w > 0 tells the section from its antipode (angle = value + pi); a root
    # at t <= T_START is the initial state lying on the section to round-off.
    if _section_fw(ytmp, p, kind, value, cv, sv)[1] > 0.0 and t + theta * h > T_START:
        tc[count] = t + theta * h
        for i in range(ytmp.shape[0]):
            yc[count, i] = ytmp[i]
        count += 1
    return count



class Stepper(NamedTuple):
    """The DOP853 pieces of one right-hand side, built by :func:`make_stepper`.

    Parameters
    ----------
    stages : numba function
        The twelve DOP853 stages of one step.
    initial_step : numba function
        The starting step size.
    step : numba function
        One step with error control.
    dense_coefficients : numba function
        The coefficients of the dense output over a step.
    propagate_orbit : numba function
        One orbit to the output times.
    crossings_orbit : numba function
        One orbit's section crossings.
    propagate_block : numba function
        :attr:`propagate_orbit` for each orbit of a block.
    crossings_block : numba function
        :attr:`crossings_orbit` for each orbit of a block.
    """

    stages: Any
    initial_step: Any
    step: Any
    dense_coefficients: Any
    propagate_orbit: Any
    crossings_orbit: Any
    propagate_block: Any
    crossings_block: Any


def make_stepper(field: Any) -> Stepper:
    """DOP853 with dense output and section crossings for ``dy/dt = field(t, y)``.

    ``field(t, y, p, out)`` is a Numba-compiled function writing the right-hand side at
    ``(t, y)`` with parameters ``p`` (an array) into ``out``; the dimension is
    ``len(y)`` (at least 6: sections read the Euler-Poisson state ``y[:6]``).

    The pieces close over ``field`` (a closure variable is bound at compile time, so the
    call is static and inlined; a function passed as an argument would be a dynamic
    address, which Numba cannot cache). They are not cached themselves: bind them to
    module globals and call them from cached entry points, whose cache key must then
    cover this module and the field's (see :func:`andoyer.kernels.common.source_stamp`).

    Parameters
    ----------
    field : numba function
        ``field(t, y, p, out)``: the right-hand side.

    Returns
    -------
    Stepper
        ``propagate_orbit(y0, t_out, p, rtol, atol, max_steps, out, info)`` (one orbit,
        ``out[j] = y(t_out[j])``) and ``crossings_orbit(y0, p, kind, value, direction,
        t_max, rtol, atol, max_steps, tc, yc, info)`` (the first ``len(tc)`` crossings,
        returns their number), with the stages, starting step, controlled step and dense
        output they use; ``propagate_block`` and ``crossings_block``, the same for each
        row of a block of orbits (``y0`` (n, d); ``out``, ``tc``, ``yc``, ``info`` with a
        leading dimension n; ``crossings_block`` writes the counts into ``count`` (n,)):
        what a module's cached entry points call (:class:`andoyer.kernels.dop853.flow.Flow`).
    """
    tag = getattr(field, "py_func", field).__name__  # the variants' (common.variant)
    kernel = kernel_variant(tag)

    @kernel
    def stages(t, y, h, p, K, ytmp, first, last):
        """Stages ``first .. last-1`` into ``K`` (``K[:first]`` known); ``ytmp`` ends as the
        argument of the last stage (``y + h sum_j B_j k_j`` = y1 when ``last = 13``)."""
        n = y.shape[0]
        for s in range(first, last):
            if n == N:  # the field (1) alone: six accumulators in registers (faster)
                s0 = s1 = s2 = s3 = s4 = s5 = 0.0
                for j in range(s):
                    w = A[s, j]
                    if w != 0.0:
                        s0 += w * K[j, 0]
                        s1 += w * K[j, 1]
                        s2 += w * K[j, 2]
                        s3 += w * K[j, 3]
                        s4 += w * K[j, 4]
                        s5 += w * K[j, 5]
                ytmp[0] = y[0] + h * s0
                ytmp[1] = y[1] + h * s1
                ytmp[2] = y[2] + h * s2
                ytmp[3] = y[3] + h * s3
                ytmp[4] = y[4] + h * s4
                ytmp[5] = y[5] + h * s5
                field(t + C[s] * h, ytmp, p, K[s])
                continue
            for i in range(n):
                ytmp[i] = 0.0
            for j in range(s):
                w = A[s, j]
                if w != 0.0:
                    for i in range(n):
                        ytmp[i] += w * K[j, i]
            for i in range(n):
                ytmp[i] = y[i] + h * ytmp[i]
            field(t + C[s] * h, ytmp, p, K[s])

    @kernel
    def initial_step(t, y, f0, p, interval, rtol, atol, ytmp, f1):
        """Hairer's starting step (``hinit``; scipy's ``select_initial_step``, order 7)."""
        n = y.shape[0]
        d0 = 0.0
        d1 = 0.0
        for i in range(n):
            sc = atol + abs(y[i]) * rtol
            d0 += (y[i] / sc) ** 2
            d1 += (f0[i] / sc) ** 2
        d0 = math.sqrt(d0 / n)
        d1 = math.sqrt(d1 / n)
        h0 = 1e-6 if (d0 < 1e-5 or d1 < 1e-5) else 0.01 * d0 / d1
        h0 = min(h0, interval)
        for i in range(n):
            ytmp[i] = y[i] + h0 * f0[i]
        field(t + h0, ytmp, p, f1)
        d2 = 0.0
        for i in range(n):
            sc = atol + abs(y[i]) * rtol
            d2 += ((f1[i] - f0[i]) / sc) ** 2
        d2 = math.sqrt(d2 / n) / h0
        if d1 <= 1e-15 and d2 <= 1e-15:
            h1 = max(1e-6, h0 * 1e-3)
        else:
            h1 = (0.01 / max(d1, d2)) ** (1.0 / 8.0)
        return min(100.0 * h0, h1, interval)

    @kernel
    def step(t, y, h_abs, t_end, p, rtol, atol, K, ytmp, y1, info):
        """One accepted step from ``(t, y)`` with ``K[0] = f(t, y)``, at most to ``t_end``.

        Returns ``(status, t1, h, h_abs_next)``; on success ``y1`` holds the new state,
        ``K[:13]`` the stages (``K[12] = f(t1, y1)``).
        """
        n = y.shape[0]
        rejected = False
        while True:
            min_step = 10.0 * (np.nextafter(t, np.inf) - t)
            if not h_abs >= min_step:  # also catches h_abs = NaN (a non-finite state)
                return STEP_TOO_SMALL, t, 0.0, h_abs
            t1 = t + h_abs
            if t1 > t_end:
                t1 = t_end
            h = t1 - t
            stages(t, y, h, p, K, ytmp, 1, N_STAGES + 1)
            info[3] += N_STAGES
            err = _error_norm(y, ytmp, K, h, rtol, atol)
            if err < 1.0:
                if err == 0.0:
                    factor = MAX_FACTOR
                else:
                    factor = min(MAX_FACTOR, SAFETY * err ** ERROR_EXPONENT)
                if rejected:
                    factor = min(1.0, factor)
                for i in range(n):
                    y1[i] = ytmp[i]
                info[1] += 1
                return SUCCESS, t1, h, abs(h) * factor
            # Also for err = NaN (a non-finite state): shrink until min_step stops it.
            if err == err:
                h_abs = abs(h) * max(MIN_FACTOR, SAFETY * err ** ERROR_EXPONENT)
            else:
                h_abs = abs(h) * MIN_FACTOR
            rejected = True
            info[2] += 1

    @kernel
    def dense_coefficients(t, y, y1, h, p, K, ytmp, F):
        """The 7 rows ``r_1 .. r_7`` of the dense output of the step ``y -> y1`` (size h)."""
        n = y.shape[0]
        stages(t, y, h, p, K, ytmp, N_STAGES + 1, N_STAGES_EXTENDED)
        for i in range(n):
            dy = y1[i] - y[i]
            F[0, i] = dy
            F[1, i] = h * K[0, i] - dy
            F[2, i] = 2.0 * dy - h * (K[N_STAGES, i] + K[0, i])
            for r in range(INTERPOLATOR_POWER - 3):
                acc = 0.0
                for j in range(N_STAGES_EXTENDED):
                    acc += D[r, j] * K[j, i]
                F[3 + r, i] = h * acc

    @kernel
    def graze(y, y1, t, h, p, K, F, kind, value, cv, sv, direction, f0, tc, yc, count,
               ytmp, info):
        """Two roots inside one step (the orbit dips through the section and back): look
        for them where ``|f|`` has a discrete local minimum; returns the count."""
        sign = 1.0 if f0 > 0.0 else -1.0
        dense_coefficients(t, y, y1, h, p, K, ytmp, F)
        info[3] += N_STAGES_EXTENDED - N_STAGES - 1
        theta, fmin = _closest_approach(F, y, p, kind, value, cv, sv, sign, ytmp)
        if sign * fmin < 0.0:
            f1 = _f_at(F, y, 1.0, p, kind, value, cv, sv, ytmp)
            count = _record(F, y, t, h, p, kind, value, cv, sv, direction, 0.0, theta, f0,
                            fmin, tc, yc, count, ytmp)
            count = _record(F, y, t, h, p, kind, value, cv, sv, direction, theta, 1.0, fmin,
                            f1, tc, yc, count, ytmp)
        return count

    @kernel
    def propagate_orbit(y0, t_out, p, rtol, atol, max_steps, out, info):
        """One orbit of ``dy/dt = field(t, y)``: ``out[j] = y(t_out[j])`` (rows not reached
        stay as they are); ``info`` (4,) counts as the columns :data:`INFO`.

        ``field(t, y, p, out)`` writes the right-hand side into ``out``; the dimension is
        ``len(y0)``. Not cached itself: compiled into the caller's entry point.
        """
        dim = y0.shape[0]
        k = t_out.shape[0]
        for i in range(dim):
            out[0, i] = y0[i]
        if k == 1:
            return
        y = y0.copy()
        y1 = np.empty(dim)
        ytmp = np.empty(dim)
        f1 = np.empty(dim)
        K = np.empty((N_STAGES_EXTENDED, dim))
        F = np.empty((INTERPOLATOR_POWER, dim))
        t = t_out[0]
        t_end = t_out[k - 1]
        field(t, y, p, K[0])
        h_abs = initial_step(t, y, K[0], p, t_end - t, rtol, atol, ytmp, f1)
        info[3] += 2
        j = 1
        while j < k and t_out[j] <= t:  # repeated initial times
            for i in range(dim):
                out[j, i] = y0[i]
            j += 1
        while j < k:
            if info[1] >= max_steps:
                info[0] = MAX_STEPS
                return
            status, t1, h, h_abs = step(t, y, h_abs, t_end, p, rtol, atol, K, ytmp, y1,
                                         info)
            if status != SUCCESS:
                info[0] = status
                return
            dense = False
            while j < k and t_out[j] <= t1:
                if t_out[j] == t1:
                    for i in range(dim):
                        out[j, i] = y1[i]
                else:
                    if not dense:
                        dense_coefficients(t, y, y1, h, p, K, ytmp, F)
                        info[3] += N_STAGES_EXTENDED - N_STAGES - 1
                        dense = True
                    dense_eval(F, y, (t_out[j] - t) / h, out[j])
                j += 1
            t = t1
            for i in range(dim):
                y[i] = y1[i]
                K[0, i] = K[N_STAGES, i]

    @kernel
    def crossings_orbit(y0, p, kind, value, direction, t_max, rtol, atol, max_steps,
                        tc, yc, info):
        """One orbit of ``dy/dt = field(t, y)``: the first ``len(tc)`` crossings in
        ``(0, t_max]`` of the section ``(kind, value)`` of the first six components (the
        Euler-Poisson state); returns their number. ``yc`` has rows of ``len(y0)``.

        A sign change of ``f`` over a step brackets one root. A pair of roots inside one
        step leaves no sign change; it can only hide next to a discrete local minimum of
        ``|f|`` over the step ends, so the two steps around each such minimum (same sign
        of ``f`` throughout) are searched on their dense output. The previous step's
        stages are kept for that (two stage buffers, swapped after each step).
        """
        dim = y0.shape[0]
        n_crossings = tc.shape[0]
        if n_crossings == 0 or t_max <= 0.0:
            return 0
        cv = math.cos(value)
        sv = math.sin(value)
        y = y0.copy()
        y1 = np.empty(dim)
        y_prev = np.empty(dim)
        ytmp = np.empty(dim)
        f1 = np.empty(dim)
        K = np.empty((N_STAGES_EXTENDED, dim))
        K_prev = np.empty((N_STAGES_EXTENDED, dim))
        F = np.empty((INTERPOLATOR_POWER, dim))
        t = 0.0
        t_prev = 0.0
        h_prev = 0.0
        field(t, y, p, K[0])
        h_abs = initial_step(t, y, K[0], p, t_max, rtol, atol, ytmp, f1)
        info[3] += 2
        f_prev = _section_fw(y, p, kind, value, cv, sv)[0]
        f_prev2 = np.nan  # f one step further back (none yet)
        count = 0
        while count < n_crossings and t < t_max:
            if info[1] >= max_steps:
                info[0] = MAX_STEPS
                return count
            status, t1, h, h_abs = step(t, y, h_abs, t_max, p, rtol, atol, K, ytmp, y1,
                                         info)
            if status != SUCCESS:
                info[0] = status
                return count
            f_new = _section_fw(y1, p, kind, value, cv, sv)[0]
            if (f_prev < 0.0 and f_new >= 0.0) or (f_prev > 0.0 and f_new <= 0.0):
                if f_new == 0.0:  # the root is the step end itself
                    if (f_prev < 0.0 and direction >= 0) or (f_prev > 0.0 and direction <= 0):
                        if _section_fw(y1, p, kind, value, cv, sv)[1] > 0.0:
                            tc[count] = t1
                            for i in range(dim):
                                yc[count, i] = y1[i]
                            count += 1
                else:
                    dense_coefficients(t, y, y1, h, p, K, ytmp, F)
                    info[3] += N_STAGES_EXTENDED - N_STAGES - 1
                    count = _record(F, y, t, h, p, kind, value, cv, sv, direction, 0.0, 1.0,
                                    f_prev, f_new, tc, yc, count, ytmp)
            elif f_prev != 0.0 and (f_prev > 0.0) == (f_new > 0.0) and f_new != 0.0:
                a_prev = abs(f_prev)
                if f_prev2 != f_prev2:  # first step: t = 0 counts as a minimum if |f| grows
                    if a_prev <= abs(f_new):
                        count = graze(y, y1, t, h, p, K, F, kind, value, cv, sv, direction,
                                       f_prev, tc, yc, count, ytmp, info)
                elif ((f_prev2 > 0.0) == (f_prev > 0.0) and f_prev2 != 0.0
                      and a_prev < abs(f_prev2) and a_prev <= abs(f_new)):
                    count = graze(y_prev, y, t_prev, h_prev, p, K_prev, F, kind, value,
                                   cv, sv, direction, f_prev2, tc, yc, count, ytmp, info)
                    count = graze(y, y1, t, h, p, K, F, kind, value, cv, sv, direction,
                                   f_prev, tc, yc, count, ytmp, info)
                if t1 >= t_max and abs(f_new) < abs(f_prev):  # the end is a minimum too
                    count = graze(y, y1, t, h, p, K, F, kind, value, cv, sv, direction,
                                   f_prev, tc, yc, count, ytmp, info)
            f_prev2 = f_prev
            f_prev = f_new
            t_prev = t
            h_prev = h
            t = t1
            K, K_prev = K_prev, K
            for i in range(dim):
                y_prev[i] = y[i]
                y[i] = y1[i]
                K[0, i] = K_prev[N_STAGES, i]
        return count

    @kernel
    def propagate_block(y0, t_out, p, rtol, atol, max_steps, out, info):
        """:func:`propagate_orbit` for each orbit (row) of ``y0``."""
        for i in range(y0.shape[0]):
            propagate_orbit(y0[i], t_out, p, rtol, atol, max_steps, out[i], info[i])

    @kernel
    def crossings_block(y0, p, kind, value, direction, t_max, rtol, atol, max_steps, tc,
                        yc, count, info):
        """:func:`crossings_orbit` for each orbit (row) of ``y0``; counts into ``count``."""
        for i in range(y0.shape[0]):
            count[i] = crossings_orbit(y0[i], p, kind, value, direction, t_max, rtol, atol,
                                       max_steps, tc[i], yc[i], info[i])

    return Stepper(stages, initial_step, step, dense_coefficients, propagate_orbit,
                   crossings_orbit, propagate_block, crossings_block)

