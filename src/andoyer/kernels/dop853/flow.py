r"""Dormand-Prince 8(5,3) (Hairer's DOP853) in Numba, on the Euler-Poisson field (1).

An explicit Runge-Kutta method of order 8 with 12 stages (the 13th is the first
stage of the next step, FSAL), a 5th-order error estimate corrected by a 3rd-order
one, step-size control as in Hairer's ``dop853.f`` / :class:`scipy.integrate.DOP853`,
and a dense output of order 7 that costs 3 extra stages per step where it is needed
[1]_, [2]_. The method is written once, for any right-hand side: :func:`make_stepper`
builds it for a compiled ``field(t, y, p, out)`` of any dimension. The entry points
below use the generated Lie-Poisson field :func:`andoyer.kernels.dop853.fields.ep_field`
of Eq. (1) (:func:`ep_rhs`, the stepper :data:`EP`), on states ordered as
:data:`andoyer.charts.euler_poisson.STATE`; :mod:`andoyer.kernels.dop853.tangent` uses
the same stepper on the variational equations.

Everything here works on plain float arrays, ``y`` of shape ``(n_orbits, 6)`` and
``p`` = the 8 kernel parameters :data:`PARAMS`; there is no validation (the
friendly layer validates) and no Python callback per step or per crossing.

Entry points (compiled with ``cache=True`` into the folder
:func:`andoyer.kernels.cache.cache_folder`; each orbit independent):

* :func:`propagate` -- states at given output times, read off the dense output;
* :func:`locate_crossings` -- the first crossings of a section
  ``f(y) = 0`` (from :func:`andoyer.kernels.generated.equations.section`), each root located
  on the dense output polynomial;
* both run blocks of orbits in threads (:func:`andoyer.kernels.threads.over_orbits`)
  through the compiled, nogil :func:`propagate_block` and
  :func:`locate_crossings_block`: :class:`Flow`, the one driver of every field's
  entry points (this module's, :mod:`andoyer.kernels.dop853.tangent`'s and
  :mod:`andoyer.kernels.dop853.attitude`'s);
* :func:`integrate_fixed`, :func:`interpolate_step` -- fixed steps without control
  and the interpolant of one step, for measuring the orders of the method.

Each returns an ``info`` array of shape ``(n_orbits, 4)`` whose columns are
:data:`~andoyer.kernels.common.INFO`: the status
(:data:`~andoyer.kernels.common.SUCCESS`, :data:`~andoyer.kernels.common.STEP_TOO_SMALL`,
:data:`~andoyer.kernels.common.MAX_STEPS`), accepted steps, rejected steps and
evaluations of the field.

Notes
-----
Step control. With the stages :math:`k_i`, the error estimates
:math:`\mathrm{err}_5 = \sum_i e^{(5)}_i k_i` and
:math:`\mathrm{err}_3 = \sum_i (b_i - \hat b_i) k_i`, scaled componentwise by
:math:`sc_j = \mathrm{atol} + \mathrm{rtol}\max(|y_j|, |y_{1,j}|)`, are combined as

.. math::
   \mathrm{err} = |h|\,\frac{\|\mathrm{err}_5\|^2}
   {\sqrt{N\,(\|\mathrm{err}_5\|^2 + 0.01\,\|\mathrm{err}_3\|^2)}}

and a step is accepted when :math:`\mathrm{err} < 1`; the next step is
:math:`h \min(10, 0.9\,\mathrm{err}^{-1/8})` (at least :math:`h/5` after a
rejection, at most :math:`h` right after one).

Dense output. With :math:`\theta = (t - t_0)/h`,

.. math::
   y(t_0 + \theta h) = y_0 + \theta\,(r_1 + (1-\theta)\,(r_2 + \theta\,(r_3
   + (1-\theta)\,(r_4 + \theta\,(r_5 + (1-\theta)\,(r_6 + \theta r_7))))))

where :math:`r_1 = y_1 - y_0`, :math:`r_2 = h k_1 - r_1`,
:math:`r_3 = 2 r_1 - h (k_1 + k_{13})` and :math:`r_{4..7} = h \sum_i d_{\cdot i} k_i`
use the three extra stages 14-16 (``contd8`` of [2]_).

Section crossings. After each accepted step the section function ``f`` is evaluated
at the step end; a sign change in the requested direction is bracketed by the step and
the root is found by Brent's method on :math:`f(y(t_0 + \theta h))` to
:math:`|\Delta\theta| \approx 4\varepsilon` (so ``|f|`` is at its round-off level, far
below 1e-12 of its scale, at any t). The crossing is kept if the margin ``w`` of the
section is positive at the root (for an angle section this rejects the root where the
angle is ``value + pi``: no spurious crossings at the wrap). A pair of roots inside
one step (the orbit dips through the section and back) changes no sign; it can only
hide next to a discrete local minimum of ``|f|`` over the step ends, so the two steps
around each such minimum are searched on their dense output (golden section for the
closest approach, then Brent on each side). This costs a few dense outputs per
oscillation of ``f``, not per step.

Compilation cache. Numba's cache is keyed on the source of the file that defines a
function, not on the functions it calls, so a regenerated
:mod:`andoyer.kernels.generated.equations` would otherwise be served stale machine code. The
cached entry points are therefore built by a factory closing over :data:`KERNEL_STAMP`
(:func:`~andoyer.kernels.common.source_stamp` of the generated kernels, their Numba
wrappers, the stepper and the shared definitions), which Numba hashes into
the cache key; the helpers they call are not cached themselves (their code is part
of each entry point's cached library). The stepper's pieces close over their field
(:func:`make_stepper`) instead of taking it as an argument: a compiled function
passed as a value is lowered as a run-time address, which Numba refuses to cache. For
the same reason the driver is in two parts: the loops over a block of orbits are the
stepper's (``propagate_block``, ``crossings_block`` of :func:`make_stepper`) and the
allocation and threads are :class:`Flow`'s, but each module keeps its own two-line
cached doors around its stepper's blocks (``propagate_block``,
``locate_crossings_block``): a door built by a shared factory would close over the
stepper's functions, whose pickled form (Numba's cache key of a closure) carries a new
uuid in every process, so nothing would ever load from the cache.

References
----------
.. [1] E. Hairer, S. P. Norsett, G. Wanner, *Solving Ordinary Differential Equations I:
   Nonstiff Problems*, 2nd ed., Springer (1993), Sec. II.5 (DOP853) and II.6
   (dense output).
.. [2] E. Hairer, ``dop853.f``, http://www.unige.ch/~hairer/software.html.
"""

from __future__ import annotations

from typing import Any, NamedTuple

import numpy as np

from andoyer.kernels import common
from andoyer.kernels.common import INFO, entry_jit, kernel_jit, source_stamp
from andoyer.kernels.dop853 import coefficients, fields, stepper
from andoyer.kernels.dop853.coefficients import INTERPOLATOR_POWER, N_STAGES, N_STAGES_EXTENDED
from andoyer.kernels.dop853.fields import ep_field
from andoyer.kernels.dop853.stepper import N, dense_eval, make_stepper
from andoyer.kernels.generated import equations
from andoyer.kernels.threads import over_orbits

__all__ = [
    "EP",
    "ep_rhs",
    "PARAMS",
    "KERNEL_STAMP",
    "propagate",
    "locate_crossings",
    "propagate_block",
    "locate_crossings_block",
    "Flow",
    "EP_FLOW",
    "integrate_fixed",
    "interpolate_step",
]

#: Names of the 8 kernel parameters ``p`` (the Engine's ``params``), in order.
PARAMS = ("a", "b", "c", "mu", "e1", "e2", "e3", "phi0")

#: Hash of the generated kernels, their Numba wrappers, the stepper and the shared
#: definitions: part of the cache key.
KERNEL_STAMP = source_stamp(equations.__file__, fields.__file__, stepper.__file__,
                            coefficients.__file__, common.__file__)


@kernel_jit
def ep_rhs(t, y, p, out):
    """The field (1) in the stepper's form ``field(t, y, p, out)``: ``out = f(y)``.

    ``y`` in the order of STATE = (G1, G2, G3, gamma1, gamma2, gamma3), ``p`` of
    :data:`PARAMS`; ``t`` is not used (the flow is autonomous).
    """
    out[0], out[1], out[2], out[3], out[4], out[5] = ep_field(
        y[0], y[1], y[2], y[3], y[4], y[5], p[0], p[1], p[2], p[3], p[4], p[5], p[6])


#: The stepper of the Euler-Poisson field (1).
EP = make_stepper(ep_rhs)
_ep_propagate_block = EP.propagate_block
_ep_crossings_block = EP.crossings_block
_ep_stages = EP.stages
_ep_dense_coefficients = EP.dense_coefficients


def _build(stamp: str) -> tuple[Any, Any, Any, Any]:
    """The cached entry points. Each reads ``stamp`` (a no-op) so that it is a closure
    variable, which Numba hashes into the cache key; an ``assert`` would not do: pytest
    rewrites asserts in modules it imports, which Numba cannot compile."""

    @entry_jit
    def propagate_block(y0, t, p, rtol, atol, max_steps, out, info):
        """:func:`propagate` of a block of orbits on the calling thread, into ``out``
        (n, k, 6) and ``info`` (n, 4)."""
        _ = len(stamp)  # keys the cache, see _build
        _ep_propagate_block(y0, t, p, rtol, atol, max_steps, out, info)

    @entry_jit
    def locate_crossings_block(y0, p, kind, value, direction, t_max, rtol, atol, max_steps,
                               tc, yc, count, info):
        """:func:`locate_crossings` of a block of orbits on the calling thread, into
        ``tc`` (n, n_crossings), ``yc`` (n, n_crossings, 6), ``count`` (n,), ``info``."""
        _ = len(stamp)  # keys the cache, see _build
        _ep_crossings_block(y0, p, kind, value, direction, t_max, rtol, atol, max_steps, tc,
                            yc, count, info)

    @entry_jit
    def integrate_fixed(y0, p, h, n_steps):
        """``n_steps`` steps of size ``h`` without error control: shape (n_steps + 1, 6)."""
        _ = len(stamp)  # keys the cache, see _build
        out = np.empty((n_steps + 1, N))
        K = np.empty((N_STAGES_EXTENDED, N))
        ytmp = np.empty(N)
        y = y0.copy()
        out[0] = y
        ep_rhs(0.0, y, p, K[0])
        for m in range(n_steps):
            _ep_stages(m * h, y, h, p, K, ytmp, 1, N_STAGES + 1)
            for i in range(N):
                y[i] = ytmp[i]
                K[0, i] = K[N_STAGES, i]
            out[m + 1] = y
        return out

    @entry_jit
    def interpolate_step(y0, p, h, x):
        """One step of size ``h`` from ``y0``; its dense output at ``t = x h``,
        shape (len(x), 6)."""
        _ = len(stamp)  # keys the cache, see _build
        K = np.empty((N_STAGES_EXTENDED, N))
        F = np.empty((INTERPOLATOR_POWER, N))
        ytmp = np.empty(N)
        y1 = np.empty(N)
        ep_rhs(0.0, y0, p, K[0])
        _ep_stages(0.0, y0, h, p, K, ytmp, 1, N_STAGES + 1)
        for i in range(N):
            y1[i] = ytmp[i]
        _ep_dense_coefficients(0.0, y0, y1, h, p, K, ytmp, F)
        out = np.empty((x.shape[0], N))
        for m in range(x.shape[0]):
            dense_eval(F, y0, x[m], out[m])
        return out

    return propagate_block, locate_crossings_block, integrate_fixed, interpolate_step


(propagate_block, locate_crossings_block, integrate_fixed,
 interpolate_step) = _build(KERNEL_STAMP)


class Flow(NamedTuple):
    """The entry points of the DOP853 on one field (:func:`make_stepper`): its cached block
    kernels run over blocks of orbits in threads
    (:func:`andoyer.kernels.threads.over_orbits`), for states of any width ``d``
    (:data:`EP_FLOW`: the field (1), ``d = 6``; :mod:`andoyer.kernels.dop853.tangent`,
    :mod:`andoyer.kernels.dop853.attitude`).

    Parameters
    ----------
    propagate_block : numba function
        ``propagate_block(y0, t, p, rtol, atol, max_steps, out, info)``: the cached
        kernel of a block of orbits to output times.
    locate_crossings_block : numba function, optional
        ``locate_crossings_block(y0, p, kind, value, direction, t_max, rtol, atol,
        max_steps, tc, yc, count, info)``: the cached kernel of a block's crossings
        (None: the field has no crossings entry point).
    """

    propagate_block: Any
    locate_crossings_block: Any = None

    def propagate(self, y0: np.ndarray, t: np.ndarray, p: np.ndarray, rtol: float,
                  atol: float, max_steps: int, *, block: int = 1, threads: int | None = None
                  ) -> tuple[np.ndarray, np.ndarray]:
        """States of many orbits at the output times ``t`` (dense output), orbits in threads.

        Parameters
        ----------
        y0 : ndarray, shape (n, d)
            Initial states at time ``t[0]`` (C-contiguous floats).
        t : ndarray, shape (k,)
            Output times, non-decreasing, ``k >= 1``.
        p : ndarray, shape (8,)
            Kernel parameters :data:`PARAMS`.
        rtol, atol : float
            Tolerances of the local error (componentwise ``atol + rtol |y|``).
        max_steps : int
            Maximum accepted steps per orbit.
        block, threads :
            Orbits per block and threads (:func:`andoyer.kernels.threads.over_orbits`).

        Returns
        -------
        y : ndarray, shape (n, k, d)
            ``y[i, j] = y_i(t[j])``; NaN after a failure (see ``info``).
        info : ndarray of int64, shape (n, 4)
            Columns :data:`~andoyer.kernels.common.INFO`.

        Examples
        --------
        A free top spinning about its axis z: G stays (0, 0, 2).

        >>> p = np.array([0.5, 0.4, 0.25, 0.0, 1.0, 0.0, 0.0, 0.0])
        >>> y, info = EP_FLOW.propagate(np.array([[0.0, 0.0, 2.0, 0.0, 0.0, 1.0]]),
        ...                             np.array([0.0, 1.0]), p, 1e-12, 1e-12, 10**6)
        >>> y.shape, y[0, -1, :3].tolist(), int(info[0, 0]) == common.SUCCESS
        ((1, 2, 6), [0.0, 0.0, 2.0], True)
        """
        n = y0.shape[0]
        out = np.full((n, t.shape[0], y0.shape[1]), np.nan)
        info = np.zeros((n, len(INFO)), dtype=np.int64)
        over_orbits(self.propagate_block, n, (y0,), (out, info),
                    (t, p, float(rtol), float(atol), int(max_steps)), block=block,
                    threads=threads)
        return out, info

    def locate_crossings(self, y0: np.ndarray, p: np.ndarray, kind: int, value: float,
                         direction: int, n_crossings: int, t_max: float, rtol: float,
                         atol: float, max_steps: int, *, block: int = 1,
                         threads: int | None = None
                         ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """The first crossings after t = 0 of a section of the Euler-Poisson state (the
        first six components), for many orbits, orbits in threads.

        Parameters
        ----------
        y0 : ndarray, shape (n, d)
            Initial states at t = 0.
        p : ndarray, shape (8,)
            Kernel parameters :data:`PARAMS`.
        kind : int
            Index into :data:`andoyer.kernels.generated.equations.SECTION_KINDS`.
        value : float
            The section is ``SECTION_KINDS[kind] = value`` (mod 2 pi for angles).
        direction : int
            +1: f increasing, -1: decreasing, 0: both.
        n_crossings : int
            Stop an orbit after this many crossings.
        t_max : float
            Stop an orbit at this time.
        rtol, atol : float
            Tolerances.
        max_steps : int
            Maximum accepted steps per orbit.
        block, threads :
            Orbits per block and threads (:func:`andoyer.kernels.threads.over_orbits`).

        Returns
        -------
        t : ndarray, shape (n, n_crossings)
            Crossing times, NaN-padded.
        y : ndarray, shape (n, n_crossings, d)
            States on the section, NaN-padded.
        count : ndarray of int64, shape (n,)
            Crossings found per orbit.
        info : ndarray of int64, shape (n, 4)
            Columns :data:`~andoyer.kernels.common.INFO`.
        """
        if self.locate_crossings_block is None:
            raise TypeError("this flow has no crossings entry point")
        n = y0.shape[0]
        tc = np.full((n, int(n_crossings)), np.nan)
        yc = np.full((n, int(n_crossings), y0.shape[1]), np.nan)
        count = np.zeros(n, dtype=np.int64)
        info = np.zeros((n, len(INFO)), dtype=np.int64)
        over_orbits(self.locate_crossings_block, n, (y0,), (tc, yc, count, info),
                    (p, int(kind), float(value), int(direction), float(t_max), float(rtol),
                     float(atol), int(max_steps)), block=block, threads=threads)
        return tc, yc, count, info


#: The entry points of the field (1).
EP_FLOW = Flow(propagate_block, locate_crossings_block)
#: :meth:`Flow.propagate` of the field (1).
propagate = EP_FLOW.propagate
#: :meth:`Flow.locate_crossings` of the field (1).
locate_crossings = EP_FLOW.locate_crossings
