r"""Adaptive Taylor method in Numba on the Euler-Poisson field (1), with tangent vectors.

Each step expands the solution in a Taylor series of order ``p`` about the current
state: the normalised coefficients (the *jet*) come from the Cauchy-product recurrences
generated from the SymPy field (:mod:`andoyer.kernels.generated.recurrences`, written by
:mod:`andoyer.symbolic.taylor_codegen`; nothing typed by hand), the step size from the
last two coefficients, and the new state from the polynomial (Horner). The step's
polynomial is also the dense output (output times) and the event locator (section
crossings), all inside the compiled loop: no Python runs per step or per crossing.

Order and step size (Jorba & Zou [1]_, as in heyoka [2]_). For a tolerance
:math:`\varepsilon` the order is :math:`p = \lceil -\ln\varepsilon / 2 \rceil + 1`
(:func:`order_for`; 15 at 1e-12) and the step is

.. math::
   h = \frac{\rho}{e^2}\, e^{-0.7/(p-1)}, \qquad
   \rho = \min\left( \left(\frac{m}{\|x^{[p-1]}\|_\infty}\right)^{1/(p-1)},
                     \left(\frac{m}{\|x^{[p]}\|_\infty}\right)^{1/p} \right),
   \qquad m = \max(1, \|x^{[0]}\|_\infty)

(absolute error control while :math:`\|x\|_\infty \le 1`, relative above; the two
roots without ``pow``, 1.4e-8 to 3.1e-8 below the exact ones so that no step is longer
than the formula's: :func:`andoyer.kernels.simd.root`, on lane vectors
:func:`andoyer.kernels.simd.roots`). With
tangent vectors, :math:`\rho` is the least over the state and each vector, each block
with its own ``m``, so a growing tangent vector never loosens the state's accuracy.
There is no rejected step.

While it looks for crossings, the section function's jet counts in the step as well,
as in heyoka, whose step norms run over the state and the event functions: where the
last two coefficients of ``f`` exceed the state's, :math:`\rho` is also least over ``f``
as a block of scale :math:`m = \max(1, \|x^{[0]}\|_\infty, \sqrt{f^2 + w^2})` (``w``
the margin: the section's amplitude, which a root does not zero; heyoka takes one scale
:math:`\max(1, \|x^{[0]}\|_\infty, |f|)` for both, which can lengthen the state's step
where :math:`|f| > \|x^{[0]}\|_\infty`). The step is never longer than the state's own
rule -- a section of a state component (``G3 = 0``) steps exactly as :func:`propagate`
-- and never shorter than :data:`~andoyer.kernels.taylor.jets.SECTION_STEP_FLOOR` of
it (near ``G = 0`` an angle's section function has unbounded jets). On the angle
sections this is what makes the crossings as accurate as heyoka's: the error of a
crossing is the integration's global error there, and the angle's jets shorten the
steps a little (the crossings' errors then match heyoka's against the extended-precision
reference; measured: benchmarks/NOTES.md#taylor-sections).

Tangent vectors. The variational equations :math:`\dot w = J(x) w` are linear in
``w`` and bilinear in the jets: a state of ``6 + 6 k`` floats carries ``k`` tangent
vectors (``z = (y, w_1, ..., w_k)``), their jets follow the state's (generated
``ep_taylor_tangent_jet``). The vectors are not renormalised (they are the linear
flow's own vectors; an overflow stops the orbit with a failure status).

Section crossings. With ``f`` a section function of
:func:`andoyer.kernels.generated.equations.section` and its jet along the step (generated
``section_jet``), the roots of the polynomial :math:`P(\tau) = \sum_k f^{[k]} \tau^k`
on the step are isolated in the Bernstein basis of :math:`[0, h]` (the number of sign
changes of the Bernstein coefficients bounds the number of roots, with the same
parity; an interval with more than one change is split by de Casteljau's algorithm, so
two roots inside one step -- the orbit dipping through the section and back -- are
found down to a separation of 1e-13 of the step), then each root is solved by a
safeguarded Newton iteration on ``P`` and polished by one Newton step in time on the
section function itself: :math:`dt = -f(y)/\dot f`, :math:`y \mathrel{+}= dt\, F(y)`
(:math:`\dot f = P'` and ``F`` the field (1); the tangent vectors get ``dt J w``). One
pass of ``f`` per step; its end value is the next step's start value, so a root on a step
boundary is counted once; a state component's jet is the state's column
(:mod:`~andoyer.kernels.taylor.sections`' notes). As in every
engine, a crossing is kept when its direction is wanted, the margin ``w`` of the
section is positive there (an angle section's antipode is not a crossing) and its time
exceeds :data:`andoyer.kernels.common.T_START`.

Entry points (cached, ``nogil``; blocks of orbits in threads through
:func:`andoyer.kernels.threads.over_orbits`): :func:`propagate` and
:func:`locate_crossings`, for states of ``6 + 6 k`` floats. ``info`` columns are
:data:`~andoyer.kernels.common.INFO` (status, steps, 0, jets computed), status codes
of :mod:`andoyer.kernels.common`.

References
----------
.. [1] A. Jorba, M. Zou, "A software package for the numerical integration of ODEs
   by means of high-order Taylor methods", Experimental Mathematics 14, 99 (2005).
.. [2] F. Biscani, D. Izzo, "Revisiting high-order Taylor methods for astrodynamics
   and celestial mechanics", MNRAS 504, 2614 (2021).
"""

from __future__ import annotations

import math
from typing import Any, NamedTuple

import numpy as np

from andoyer.kernels import common
from andoyer.kernels.common import (
    INFO,
    MAX_STEPS,
    N_STATE,
    SUCCESS,
    T_START,
    exact_jit,
    kernel_variant,
    source_stamp,
    variant,
)
from andoyer.kernels.generated import recurrences
from andoyer.kernels.taylor import jets, sections
from andoyer.kernels.taylor.jets import (
    advance,
    advance_to,
    attitude_jets,
    block_at,
    fill_constants,
    horner,
    load,
    section_step_size,
    state_jets,
    step_size,
    step_to,
    tangent_jets,
)
from andoyer.kernels.taylor.sections import (
    COMPONENT,
    FAMILIES,
    FAMILY_NAMES,
    PAIR,
    bernstein_weights,
    column_polynomial,
    isolate,
    isolation_space,
    jet_polynomial,
    linear_component,
    may_cross,
    pair_jet,
    poly_d,
    product_pair,
    section_family,
    section_tape,
    tape_jet,
    tape_value,
)
from andoyer.kernels.threads import over_orbits

__all__ = [
    "MAX_ORDER",
    "MIN_ORDER",
    "TAYLOR_STAMP",
    "order_for",
    "n_vectors",
    "propagate",
    "propagate_attitude",
    "locate_crossings",
    "propagate_block",
    "attitude_propagate_block",
    "CROSSINGS_BLOCKS",
    "tangent_propagate_block",
    "make_orbits",
    "Orbits",
    "STATE",
    "TANGENT",
    "ATTITUDE",
    "jet",
]

#: Highest and lowest Taylor orders (a tolerance of 1e-32 asks for 38).
MAX_ORDER = 40
MIN_ORDER = 4
_N = N_STATE  # the Euler-Poisson state
_MAX_POLISH = 1e-6  # largest Newton time step of the crossing polish (as heyoka's engine)
#: A counter's start, typed int64: a literal 0 (or 1) passed to a compiled helper makes
#: Numba compile a second specialisation of it for ``Literal[int](0)``, a longer cold
#: start (measured: benchmarks/NOTES.md#taylor-sections).
_ZERO = np.int64(0)

#: Hash of every source the compiled entry points depend on (their cache key).
TAYLOR_STAMP = source_stamp(recurrences.__file__, __file__, sections.__file__, jets.__file__,
                            common.__file__)


def order_for(tol: float) -> int:
    """Taylor order for the tolerance ``tol``: ``ceil(-ln(tol) / 2) + 1`` (heyoka's rule),
    kept in ``[MIN_ORDER, MAX_ORDER]``.

    Parameters
    ----------
    tol : float
        The tolerance.

    Examples
    --------
    >>> order_for(1e-12), order_for(1e-15)
    (15, 19)
    """
    return int(min(MAX_ORDER, max(MIN_ORDER, math.ceil(-math.log(tol) / 2.0) + 1)))


def n_vectors(width: int) -> int:
    """Tangent vectors ``k`` of a state of ``width = 6 + 6 k`` floats.

    Parameters
    ----------
    width : int
        Floats per state (``6 + 6 k``).

    Examples
    --------
    >>> n_vectors(12)
    1
    """
    k, r = divmod(width - _N, _N)
    if r or k < 0:
        raise ValueError(f"a state has 6 + 6 k floats, got {width}")
    return k


class Orbits(NamedTuple):
    """The compiled orbit loops of one kind of state (built by :func:`make_orbits`).

    Parameters
    ----------
    take_step : numba function
        One Taylor step (order and size from the jets).
    propagate_orbit : numba function
        One orbit to the output times (dense output from the step's polynomial).
    record : numba function
        Stores a state at an output time.
    crossings_orbit : tuple of numba functions
        One orbit's section crossings (roots on each step's polynomial), one loop per
        section family (indexed by :data:`~andoyer.kernels.taylor.sections.FAMILIES`).
    crossings_from : tuple of numba functions
        :attr:`crossings_orbit` on from a state at a time, its crossings so far given.
    """

    take_step: Any
    propagate_orbit: Any
    record: Any
    crossings_orbit: Any
    crossings_from: Any


def make_orbits(jets: Any) -> Orbits:
    """The orbit loops for states whose jets ``jets(X, order, q)`` computes (the state
    alone, or with tangent vectors): closures over ``jets``, so a call compiles only the
    jets it needs (see :mod:`andoyer.kernels.dop853.stepper` on closures and the cache).

    Parameters
    ----------
    jets : numba function
        ``jets(X, order, q)``: the Taylor coefficients of the state.
    """
    tag = getattr(jets, "py_func", jets).__name__  # the variants' (common.variant)
    kernel = kernel_variant(tag)

    @kernel
    def take_step(t, t_end, X, order, q, info):
        """Jets at ``t`` and the step to take: ``(status, t1, h)``; ``t1 <= t_end``."""
        jets(X, order, q)
        info[3] += 1
        return step_to(t, t_end, step_size(X, order))

    @kernel
    def take_section_step(t, t_end, X, order, q, info, ftape, fC, u):
        """:func:`take_step` with the section function's jets (left in ``u``) in the step
        size (:func:`~andoyer.kernels.taylor.jets.section_step_size`)."""
        jets(X, order, q)
        info[3] += 1
        tape_jet(ftape, fC, X[0], order, u)
        return step_to(t, t_end, section_step_size(X, order, ftape, u))

    @kernel
    def take_pair_step(t, t_end, X, order, q, info, ftape, fC, u, pair):
        """:func:`take_section_step` of a tape of
        :func:`~andoyer.kernels.taylor.sections.product_pair`'s form (its products
        ``pair``): the same jets by :func:`~andoyer.kernels.taylor.sections.pair_jet`."""
        jets(X, order, q)
        info[3] += 1
        pair_jet(ftape, fC, X[0], order, u, pair[0], pair[1], pair[2], pair[3])
        return step_to(t, t_end, section_step_size(X, order, ftape, u))

    @kernel
    def propagate_orbit(z0, t_out, q, order, max_steps, X, out, info):
        """One orbit: ``out[j] = z(t_out[j])`` (rows not reached stay as they are)."""
        k = t_out.shape[0]
        for i in range(z0.shape[0]):
            out[0, i] = z0[i]
        if k == 1:
            return
        t = t_out[0]
        t_end = t_out[k - 1]
        j = 1
        while j < k and t_out[j] <= t:  # repeated initial times
            for i in range(z0.shape[0]):
                out[j, i] = z0[i]
            j += 1
        load(X, z0)
        while j < k:
            if info[1] >= max_steps:
                info[0] = MAX_STEPS
                return
            status, t1, h = take_step(t, t_end, X, order, q, info)
            if status != SUCCESS:
                info[0] = status
                return
            while j < k and t_out[j] <= t1:
                horner(X, order, t_out[j] - t if t_out[j] < t1 else h, out[j])
                j += 1
            advance(X, order, h)
            info[1] += 1
            t = t1


    @kernel
    def record(X, order, q, t, h, s_root, ftape, fC, wtape, wC, a, tc, zc, count, ytmp, P, Y,
                u):
        """Append the crossing at ``t + s_root h`` (polished, see module notes) if ``w > 0``
        and past T_START; returns the count. ``P``: jets of order 1 (the field there)."""
        horner(X, order, s_root * h, ytmp)
        for i in range(_N):
            Y[0, i] = ytmp[i]
        f = tape_value(ftape, fC, Y, u)
        _, fdot = poly_d(a, order, s_root)
        fdot = fdot / h
        dt = -f / fdot if fdot != 0.0 else 0.0
        if not abs(dt) <= _MAX_POLISH:
            dt = 0.0
        if dt != 0.0:
            load(P, ytmp)
            # P[:, 1] = the field (1) and J w at ytmp (order P.shape[1] - 1 = 1, not the
            # literal 1, which would compile second jets: see _ZERO)
            jets(P, P.shape[1] - 1, q)
            for b in range(P.shape[0]):
                for i in range(_N):
                    ytmp[_N * b + i] += dt * P[b, 1, i]
                    if b == 0:
                        Y[0, i] = ytmp[i]
        tr = t + s_root * h + dt
        if tape_value(wtape, wC, Y, u) > 0.0 and tr > T_START:
            tc[count] = tr
            for i in range(ytmp.shape[0]):
                zc[count, i] = ytmp[i]
            count += 1
        return count


    def section_loops(family: int) -> tuple[Any, Any]:
        """``(crossings_orbit, crossings_from)`` of the sections of one family
        (:data:`~andoyer.kernels.taylor.sections.FAMILIES`): ``family`` is a constant of
        the closure, so Numba prunes the other families' branches and compiles only this
        one's jets."""

        family_kernel = kernel_variant(f"{tag}_{FAMILY_NAMES[family]}")

        @family_kernel
        def crossings_from(X, t, fa, count, q, order, ftape, fC, wtape, wC, direction,
                           t_max, max_steps, tc, zc, info):
            """:func:`crossings_orbit` on from the state in ``X`` (order 0) at time ``t``,
            where the section function is ``fa`` and ``count`` crossings are in ``tc, zc``;
            returns the count."""
            n_crossings = tc.shape[0]
            n = order + 1
            a = np.empty(n)  # the section's jet scaled to the step: P(sigma), sigma in [0, 1]
            u = np.empty((max(ftape.shape[0], wtape.shape[0]), n))
            ytmp = np.empty(X.shape[0] * _N)
            P = np.empty((X.shape[0], 2, _N))
            Y = np.empty((1, _N))
            E = np.empty(_N)  # the state at the step's end (a tape section's f_b there)
            stack, lo_s, hi_s, left, roots = isolation_space(order)
            W = bernstein_weights(order)
            if family == COMPONENT:
                component, ca, cc = linear_component(ftape, fC)
            if family == PAIR:
                pair = product_pair(ftape)
            while count < n_crossings and t < t_max:
                if info[1] >= max_steps:
                    info[0] = MAX_STEPS
                    return count
                if family == COMPONENT:  # |f^[k]| <= the state's: the state's step (as below)
                    status, t1, h = take_step(t, t_max, X, order, q, info)
                elif family == PAIR:
                    status, t1, h = take_pair_step(t, t_max, X, order, q, info, ftape, fC, u,
                                                   pair)
                else:
                    status, t1, h = take_section_step(t, t_max, X, order, q, info, ftape, fC,
                                                      u)
                if status != SUCCESS:
                    info[0] = status
                    return count
                if family == COMPONENT:  # fb: f at the end (the next fa); bound: P's k >= 2
                    fb, bound = column_polynomial(X[0], component, ca, cc, order, h, a)
                else:  # the tape's jet (in u); fb = f at the step's end state, not P(h)
                    fb, bound = jet_polynomial(u[ftape.shape[0] - 1], order, h, a)
                    y_end = block_at(X[0], order, h)
                    for i in range(_N):
                        Y[0, i] = y_end[i]
                        E[i] = y_end[i]
                    fb = tape_value(ftape, fC, Y, u)
                if may_cross(fa, fb, a[0], a[1] * h, bound):
                    found = isolate(a, order, h, W, fa, fb, direction, stack, lo_s, hi_s, left,
                                    roots)
                    for r in range(found):
                        if count < n_crossings:
                            count = record(X, order, q, t, h, roots[r], ftape, fC, wtape, wC,
                                           a, tc, zc, count, ytmp, P, Y, u)
                if family == COMPONENT:
                    advance(X, order, h)
                else:  # the state's end is E already
                    advance_to(X, order, h, E)
                info[1] += 1
                fa = fb
                t = t1
            return count

        @family_kernel
        def crossings_orbit(z0, q, order, ftape, fC, wtape, wC, direction, t_max, max_steps,
                            X, tc, zc, info):
            """One orbit: the first ``len(tc)`` crossings in ``(0, t_max]`` of the section
            of tapes ``ftape, fC`` (function) and ``wtape, wC`` (margin); returns their
            number (see the module notes)."""
            if tc.shape[0] == 0 or t_max <= 0.0:
                return 0
            u = np.empty((max(ftape.shape[0], wtape.shape[0]), order + 1))
            Y = np.empty((1, _N))
            load(X, z0)
            for i in range(_N):
                Y[0, i] = z0[i]
            return crossings_from(X, 0.0, tape_value(ftape, fC, Y, u), _ZERO, q, order, ftape,
                                  fC, wtape, wC, direction, t_max, max_steps, tc, zc, info)

        return crossings_orbit, crossings_from

    loops = [section_loops(family) for family in FAMILIES]
    return Orbits(take_step, propagate_orbit, record, tuple(o for o, _ in loops),
                  tuple(f for _, f in loops))


#: Orbits of the state alone, and of the state with tangent vectors.
STATE = make_orbits(state_jets)
TANGENT = make_orbits(tangent_jets)
#: Orbits of the state with the attitude quaternion (blocks (y), (q, 0, 0)).
ATTITUDE = make_orbits(attitude_jets)
_attitude_propagate = ATTITUDE.propagate_orbit
_state_propagate = STATE.propagate_orbit
_state_component, _state_pair, _state_tape = STATE.crossings_orbit
_tangent_propagate = TANGENT.propagate_orbit
_tangent_component, _tangent_pair, _tangent_tape = TANGENT.crossings_orbit


def _build(stamp: str) -> tuple[Any, Any, dict[tuple[bool, int], Any], Any]:
    """The cached entry points (the closure over ``stamp`` keys the cache, as in
    :mod:`andoyer.kernels.dop853.flow`). They call the orbit loops as module globals: a
    compiled function in a closure cell would change the cache key in every process."""

    @exact_jit
    def propagate_block(z0, t, p, order, max_steps, out, info):
        """:func:`propagate` of a block of orbits (states alone) on the calling thread."""
        _ = len(stamp)  # keys the cache
        q = np.empty(recurrences.N_CONSTANTS)
        fill_constants(p, q)
        X = np.empty((1, order + 1, _N))
        for i in range(z0.shape[0]):
            _state_propagate(z0[i], t, q, order, max_steps, X, out[i], info[i])

    @exact_jit
    def tangent_propagate_block(z0, t, p, order, max_steps, out, info):
        """:func:`propagate` of a block of orbits with tangent vectors."""
        _ = len(stamp)  # keys the cache
        q = np.empty(recurrences.N_CONSTANTS)
        fill_constants(p, q)
        X = np.empty((z0.shape[1] // _N, order + 1, _N))
        for i in range(z0.shape[0]):
            _tangent_propagate(z0[i], t, q, order, max_steps, X, out[i], info[i])

    def crossings_block(tangent: bool, family: int) -> Any:
        """The entry point of the sections of one family (states alone, or with tangent
        vectors): ``tangent`` and ``family`` are constants of its closure, so it compiles
        one orbit loop; its cache key is stable (no compiled function in the closure)."""

        @exact_jit
        @variant(f"{'tangent' if tangent else 'state'}_{FAMILY_NAMES[family]}")
        def locate_crossings_block(z0, p, order, ftape, fC, wtape, wC, direction, t_max,
                                   max_steps, tc, zc, count, info):
            """:func:`locate_crossings` of a block of orbits."""
            _ = len(stamp)  # keys the cache
            q = np.empty(recurrences.N_CONSTANTS)
            fill_constants(p, q)
            X = np.empty((z0.shape[1] // _N, order + 1, _N))
            for i in range(z0.shape[0]):
                args = (z0[i], q, order, ftape, fC, wtape, wC, direction, t_max, max_steps,
                        X, tc[i], zc[i], info[i])
                if tangent:
                    if family == COMPONENT:
                        count[i] = _tangent_component(*args)
                    elif family == PAIR:
                        count[i] = _tangent_pair(*args)
                    else:
                        count[i] = _tangent_tape(*args)
                elif family == COMPONENT:
                    count[i] = _state_component(*args)
                elif family == PAIR:
                    count[i] = _state_pair(*args)
                else:
                    count[i] = _state_tape(*args)

        return locate_crossings_block

    @exact_jit
    def attitude_propagate_block(z0, t, p, order, max_steps, out, info):
        """:func:`propagate_attitude` of a block of orbits on the calling thread."""
        _ = len(stamp)  # keys the cache
        q = np.empty(recurrences.N_CONSTANTS)
        fill_constants(p, q)
        X = np.empty((2, order + 1, _N))
        for i in range(z0.shape[0]):
            _attitude_propagate(z0[i], t, q, order, max_steps, X, out[i], info[i])

    blocks = {(tangent, family): crossings_block(tangent, family)
              for tangent in (False, True) for family in FAMILIES}
    return propagate_block, tangent_propagate_block, blocks, attitude_propagate_block


#: ``CROSSINGS_BLOCKS[(tangent, family)]``: :func:`locate_crossings` of a block of orbits
#: (with tangent vectors or not) on a section of one family.
(propagate_block, tangent_propagate_block, CROSSINGS_BLOCKS,
 attitude_propagate_block) = _build(TAYLOR_STAMP)


@exact_jit
def jet(z0, p, order):
    """The jets (state, then tangent vectors) at ``z0`` (6 + 6 k,): shape
    (1 + k, order + 1, 6)."""
    q = np.empty(recurrences.N_CONSTANTS)
    fill_constants(p, q)
    X = np.empty((z0.shape[0] // _N, order + 1, _N))
    load(X, z0)
    tangent_jets(X, order, q)
    return X


def _order(tol: float) -> int:
    return order_for(float(tol))


def propagate(z0: np.ndarray, t: np.ndarray, p: np.ndarray, tol: float, max_steps: int, *,
              block: int = 1, threads: int | None = None) -> tuple[np.ndarray, np.ndarray]:
    """States (with tangent vectors) of many orbits at the output times ``t``.

    Parameters
    ----------
    z0 : ndarray, shape (n, 6 + 6 k)
        Initial states ``(y, w_1 .. w_k)`` at ``t[0]`` (C-contiguous floats).
    t : ndarray, shape (m,)
        Output times, non-decreasing.
    p : ndarray, shape (8,)
        Kernel parameters :data:`andoyer.kernels.dop853.flow.PARAMS`.
    tol : float
        Tolerance of the local error (:func:`order_for` and the module notes).
    max_steps : int
        Maximum steps per orbit.
    block, threads :
        Orbits per block and threads (:func:`andoyer.kernels.threads.over_orbits`).

    Returns
    -------
    z : ndarray, shape (n, m, 6 + 6 k)
        NaN after a failure (see ``info``).
    info : ndarray of int64, shape (n, 4)
        Columns :data:`~andoyer.kernels.common.INFO` (``rejected`` is always 0; ``nfev``
        counts jets).
    """
    n = z0.shape[0]
    out = np.full((n, t.shape[0], z0.shape[1]), np.nan)
    info = np.zeros((n, len(INFO)), dtype=np.int64)
    kernel = propagate_block if z0.shape[1] == _N else tangent_propagate_block
    over_orbits(kernel, n, (z0,), (out, info),
                (t, p, _order(tol), int(max_steps)), block=block, threads=threads)
    return out, info


def propagate_attitude(z0: np.ndarray, t: np.ndarray, p: np.ndarray, tol: float,
                       max_steps: int, *, block: int = 1, threads: int | None = None
                       ) -> tuple[np.ndarray, np.ndarray]:
    """:func:`propagate` of states ``(G, gamma, q)`` (n, 10) with the attitude quaternion
    (its jet ``ep_taylor_attitude_jet``, a second block of 6): ``z`` (n, m, 10), ``info``.

    Parameters
    ----------
    z0 : ndarray, shape (n, 10)
        Initial states ``(G, gamma, q)``: Euler-Poisson state and attitude quaternion.
    t : ndarray, shape (m,)
        Output times.
    p : ndarray
        Kernel parameters.
    tol : float
        The Taylor method's tolerance.
    max_steps : int
        Maximum steps per orbit.
    block, threads : int
        Orbits per block and threads (:func:`andoyer.kernels.threads.over_orbits`).
    """
    n = z0.shape[0]
    z = np.zeros((n, 2 * _N))
    z[:, :10] = z0
    out = np.full((n, t.shape[0], 2 * _N), np.nan)
    info = np.zeros((n, len(INFO)), dtype=np.int64)
    over_orbits(attitude_propagate_block, n, (z,), (out, info),
                (t, p, _order(tol), int(max_steps)), block=block, threads=threads)
    return np.ascontiguousarray(out[..., :10]), info


def locate_crossings(z0: np.ndarray, p: np.ndarray, kind: int, value: float, direction: int,
                     n_crossings: int, t_max: float, tol: float, max_steps: int, *,
                     block: int = 1, threads: int | None = None
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The first crossings after t = 0 of a section, for many orbits (with the tangent
    vectors there when ``z0`` has ``6 + 6 k`` columns).

    Parameters as :func:`andoyer.kernels.dop853.flow.locate_crossings`, with one ``tol``.

    Parameters
    ----------
    z0 : ndarray, shape (n, 6) or (n, 6 + 6 k)
        Initial states (with tangent vectors).
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
    block, threads : int
        Orbits per block and threads.

    Returns
    -------
    t : ndarray, shape (n, n_crossings)
        Crossing times, NaN-padded.
    z : ndarray, shape (n, n_crossings, 6 + 6 k)
        States on the section, NaN-padded.
    count : ndarray of int64, shape (n,)
    info : ndarray of int64, shape (n, 4)
    """
    n = z0.shape[0]
    tc = np.full((n, int(n_crossings)), np.nan)
    zc = np.full((n, int(n_crossings), z0.shape[1]), np.nan)
    count = np.zeros(n, dtype=np.int64)
    info = np.zeros((n, len(INFO)), dtype=np.int64)
    ftape, fC = section_tape(int(kind), float(p[7]), float(value))
    wtape, wC = section_tape(int(kind), float(p[7]), float(value), margin=True)
    kernel = CROSSINGS_BLOCKS[(z0.shape[1] != _N, section_family(ftape, fC))]
    over_orbits(kernel, n, (z0,), (tc, zc, count, info),
                (p, _order(tol), ftape, fC, wtape, wC, int(direction), float(t_max),
                 int(max_steps)), block=block, threads=threads)
    return tc, zc, count, info
