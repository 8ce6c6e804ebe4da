r"""Where the last torus breaks: Greene's residues of the periodic orbits that approximate
a noble rotation number, and the critical ``mu`` at which they cross 1/4.

The derivation, referred to as (G1)-(G7) in the docstrings and tests.

(G1) The torus. Between the two main chains ``n:1`` and ``(n+1):1`` of one regime (the
tori of the free top about body axis 1 or 2, :mod:`~andoyer.analysis.resonance.predict`,
``W = omega_l / omega_g`` of the section map ``g = const``, (R2)) the noble rotation
number ``W = [0; a_1, ..., a_k, 1, 1, 1, ...]`` with the head ``(a_1, ..., a_k)``,
``a_1 = n``: the head ``(n,)`` is the golden-mean torus of the band,
``W = 1/(n + 1/phi)``, ``phi = (1 + sqrt 5)/2``. Its continued-fraction convergents
``p_j/q_j`` (``p_j = a_j p_{j-1} + p_{j-2}``, the same for ``q``) approximate it
alternately from both sides, ``|W - p_j/q_j| < 1/q_j^2``.

(G2) The symmetry. For a centre of mass in the body plane ``Oxy`` (``e3 = 0``, every Hess
body) the map ``S = diag(1, 1, -1, 1, 1, -1)`` of the Euler-Poisson state -- the time
reversal ``R = diag(-1, -1, -1, 1, 1, 1)`` of (1) composed with the reflection of the
body in its plane ``Oxy`` -- reverses the flow: ``y(-t) = S y(t; S y0)``. It keeps ``H``
and ``M`` and acts on the Andoyer-Deprit variables as
``(l, g, L, G, M) -> (l, pi - g, -L, G, M)`` (checked in the tests). Its fixed set on an
energy level meets the sections ``g = pi/2`` and ``g = 3 pi/2`` in the lines ``L = 0``:
the symmetry lines. (The time reversal ``R`` of
:data:`andoyer.notation.SECTION_COORDINATES` maps ``g = 0`` onto itself only on
``M = 0`` and acts there as ``(l, L) -> (l + pi, -L)``: without fixed points, no line to
search on.)

(G3) Symmetric periodic orbits. An orbit started on a symmetry line that meets the fixed
set of ``S`` again at half its period is periodic (the reversed half closes it), and a
``p/q`` orbit (``q`` returns to ``g = pi/2``, ``p`` turns of ``(l, L)``) advances ``g`` by
``pi q`` in half a period: started on ``g = pi/2``, ``L = 0``, it meets ``L = 0`` again at
the ``q/2``-th crossing of ``g = pi/2`` (``q`` even) or the ``(q + 1)/2``-th crossing of
``g = 3 pi/2`` (``q`` odd). One scalar condition in one unknown, the start ``l0`` on the
line: a root in one dimension, bracketed and closed by Brent's method (far more robust
than Newton in the plane, whose Jacobian ``DP^q - I`` is nearly singular on a thin
chain). The function whose root is taken counts the winding too:
``F(l0) = |Phi(l0)| - pi p`` with ``Phi`` the angle ``atan2(L, l - l_c)`` swept about the
regime's centre ``l_c`` (``pi/2`` about axis 1, 0 about axis 2; the angle is 0 or ``pi``
exactly where ``L = 0``) over the half orbit, unwrapped return by return (each step well
below ``pi`` for ``W < 1/2``; the free-top phase would not do near the separatrix, where
``mu`` moves a point's free-top torus across it): a
root is a symmetric orbit of rotation number exactly ``p/q``, not one of its neighbours
``(p +- 1)/q``. For odd ``q`` both orbits of the chain (the elliptic and the hyperbolic)
cross the line ``g = pi/2, L = 0``, one on each side of the centre; for even ``q`` one
crosses it, the other the line ``g = 3 pi/2, L = 0``.

(G4) The residue. Over the whole period ``T`` (``q`` returns) the state-transition matrix
``Phi(T)`` of (1) (an engine's tangent flow) has the eigenvalues ``1`` four times (the flow
direction, ``H`` and the Casimirs ``M`` and ``|gamma|^2``) and the two multipliers of the
section map's ``q``-th power, so ``Tr DP^q = Tr Phi(T) - 4`` and Greene's residue is

.. math::

    R = \frac{2 - \operatorname{Tr} DP^q}{4} = \frac{6 - \operatorname{Tr}\Phi(T)}{4},

independent of the section and its coordinates: ``0 < R < 1`` elliptic, ``R < 0``
hyperbolic, ``R > 1`` inverse hyperbolic. At first order in ``mu`` the chain's pendulum
(R8) gives ``R = sin^2(pi q Omega)`` and ``-sinh^2(pi q Omega)``.

(G5) Greene's criterion. As ``q_j -> infinity`` the residues of the convergents' orbits
tend to 0 while the torus exists and grow without bound once it is broken; at the
critical ``mu_c`` they tend to a constant near ``1/4`` (0.2500888 for the golden mean's
elliptic orbits of the standard map). ``mu_c(q_j)``, where the elliptic residue of the
``j``-th convergent equals :data:`THRESHOLD` ``= 1/4``, converges to ``mu_c``
geometrically (``convergence_ratio``, the ratio of successive changes, is measured, not
assumed: 0.37 on the golden torus of Hess(3, 1, 2) about axis 1, h = 1, 0.39 on the
paper's body between its chains 30:1 and 31:1); the
estimate of ``mu_c`` is that of the largest ``q`` found, its error the change from the
previous convergent found.

(G6) The overlap estimate. Chirikov's parameter of the two main chains is
``s = (Delta G_n + Delta G_{n+1}) / |G*_n - G*_{n+1}|`` with the first-order
half-widths ``Delta G`` (R6) and centres ``G*`` (R4) of
:func:`~andoyer.analysis.resonance.predict.resonance_widths`; ``Delta G ~ sqrt(mu)`` so
the chains touch (``s = 1``) at ``mu_overlap = mu / s^2``, an estimate known to be high
(on the standard map ``mu_c / mu_overlap ~ 0.39``).

(G7) Scaling. On ``M = 0`` the level ``h`` and ``mu`` enter only through ``mu / h``
(``G -> lambda G``, ``t -> t / lambda`` maps ``(h, mu)`` to ``(lambda^2 h, lambda^2 mu)``):
``mu_c(h) = h mu_c(1)``: :func:`last_torus` does not use it (the tests check it), and
:func:`critical_mu_curve` computes one level and scales the others by it. On ``M != 0``
the area scales too, ``(h, M, mu) -> (lambda^2 h, lambda M, lambda^2 mu)``: at a fixed
``M`` every level is its own problem.

References
----------
.. [1] J. M. Greene, "A method for determining a stochastic transition", J. Math. Phys.
   20, 1183 (1979).
.. [2] R. S. MacKay, "A renormalisation approach to invariant circles in area-preserving
   maps", Physica D 7, 283 (1983).
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, NamedTuple

import numpy as np
import xarray as xr
from numpy.typing import NDArray
from scipy.optimize import brentq

from andoyer.analysis.resonance.predict import (
    ResonantChain,
    check_level_args,
    free_top_at_gap,
    resonant_rows,
)
from andoyer.body import RigidBody, checks_body
from andoyer.charts.andoyer_deprit import from_andoyer
from andoyer.integrate import budget
from andoyer.integrate.engines import EngineLike, resolve_engine
from andoyer.integrate.engines.base import Capability, EngineBase, Section, Tolerance
from andoyer.integrate.fill import section_roots
from andoyer.integrate.results import describe_variables, provenance
from andoyer.progress import Progress
from andoyer.validation import integer, positive

__all__ = ["last_torus", "critical_mu_curve", "convergents", "noble_number", "THRESHOLD",
           "MAX_PERIOD", "MAX_CONVERGENTS", "MAX_LEVELS"]

#: Greene's threshold: the residue of the critical torus's convergents tends to ~1/4 (G5).
THRESHOLD = 0.25
#: Largest period ``q`` of a convergent's orbit (returns to the section).
MAX_PERIOD = 5000
#: Most convergents asked for.
MAX_CONVERGENTS = 16
#: Points of the free-top rotation number on a symmetry line where the root is bracketed.
_GRID = 32
#: The grid spans the band between the main chains widened by this factor each way.
_MARGIN = 4.0
#: ``|F|`` (rad of phase) below which Brent's answer is a root, not a jump of the winding.
_ROOT_F = 1e-6
#: Half-orbit evaluations allowed per orbit (grid + Brent), for the cost estimate.
_EVALUATIONS = _GRID + 60
#: A residue below this many times ``tol |Phi(T)|`` is the integration's error, not the
#: orbit's (``residue_resolution``).
_RESOLUTION = 1.0
#: Evaluations of the residues in ``mu`` per convergent (the steps and Brent's).
_MU_EVALUATIONS = 40
#: The factor of the steps in ``mu`` from the guess until the residue crosses 1/4.
_MU_STEP = 1.15


def _head(head: Any) -> tuple[int, ...]:
    if isinstance(head, int | np.integer) and not isinstance(head, bool):
        head = (int(head),)
    if not isinstance(head, Sequence) or isinstance(head, str) or not head:
        raise ValueError(f"head must be the continued fraction's first partial quotients "
                         f"(a_1, ..., a_k), whole numbers >= 1, a_1 >= 2, got {head!r}")
    out = tuple(integer("head", a, 1, 10**4) for a in head)
    if out[0] < 2:
        raise ValueError(f"head: a_1 >= 2 (W = [0; a_1, ...] < 1/2: the main chains "
                         f"a_1:1 and (a_1+1):1), got {head!r}")
    if len(out) > 8:
        raise ValueError(f"head: at most 8 partial quotients before the tail of ones, got "
                         f"{len(out)}")
    return out


def convergents(head: Sequence[int], n: int) -> list[tuple[int, int]]:
    """The first ``n`` convergents ``p/q`` of ``[0; head, 1, 1, 1, ...]`` (G1).

    Parameters
    ----------
    head : sequence of int
        The partial quotients before the tail of ones (``a_1 >= 2``).
    n : int
        How many convergents (1 to :data:`MAX_CONVERGENTS` + 8).

    Returns
    -------
    list of (int, int)
        ``(p_j, q_j)``, ``q`` increasing.

    Examples
    --------
    >>> convergents((2,), 6)
    [(1, 2), (1, 3), (2, 5), (3, 8), (5, 13), (8, 21)]
    >>> convergents((7, 2), 4)
    [(1, 7), (2, 15), (3, 22), (5, 37)]
    """
    quotients = _head(head)
    n = integer("n", n, 1, MAX_CONVERGENTS + 8)
    a = (list(quotients) + [1] * n)[:n]
    p2, p1, q2, q1 = 1, 0, 0, 1             # p_{-1}, p_0, q_{-1}, q_0 of [0; a_1, ...]
    out = []
    for x in a:
        p2, p1 = p1, x * p1 + p2
        q2, q1 = q1, x * q1 + q2
        out.append((p1, q1))
    return out


def noble_number(head: Sequence[int]) -> float:
    """``W = [0; head, 1, 1, 1, ...]`` (G1).

    Parameters
    ----------
    head : sequence of int
        The partial quotients before the tail of ones (``a_1 >= 2``).

    Examples
    --------
    >>> round(noble_number((2,)), 12)    # 1/phi^2
    0.38196601125
    >>> round(noble_number((7,)), 10)    # between 1/8 and 1/7
    0.1312674637
    """
    quotients = _head(head)
    x = (1.0 + math.sqrt(5.0)) / 2.0       # [1; 1, 1, ...]
    for a in reversed(quotients[1:]):
        x = a + 1.0 / x
    return 1.0 / (quotients[0] + 1.0 / x)


@dataclass
class _Orbit:
    """A symmetric periodic orbit found on a symmetry line (G3) and its residue (G4)."""

    l0: float
    g0: float
    residue: float
    period: float
    closure: float
    winding: int
    resolution: float


class _Level:
    """One body, level, regime and engine: the symmetry lines and the orbits on them.

    ``lines`` holds the free-top ``l`` of each ``(W, side)`` (:meth:`l_of_W`), which does
    not depend on ``mu``: the levels of one body, ``h`` and axis share it."""

    def __init__(self, body: RigidBody, h: float, M: float, axis: int, band: tuple[float, float],
                 engine: EngineBase, tol: Tolerance, return_time: float,
                 lines: dict[tuple[float, int], float | None] | None = None) -> None:
        self.body, self.h, self.M, self.axis = body, h, M, axis
        self.engine, self.tol, self.return_time = engine, tol, return_time
        self.band = band            # free-top W of the two main chains
        self.evaluations = 0        # half orbits integrated
        # Each a function of its arguments on this level, computed once: Brent's method
        # asks again for its bracket's ends, the check of its root and the whole orbit's
        # seed for its last point, and every line and level for the same grid of W.
        self._lines = {} if lines is None else lines
        self._seeds: dict[tuple[float, float], NDArray[np.float64] | None] = {}
        self._halves: dict[tuple[float, float, int, int], float] = {}

    # ---------------------------------------------------------------- the lines (G2)
    def l_of_W(self, W: float, side: int) -> float:
        """``l`` of the free-top torus of rotation number ``W`` on ``L = 0`` (side +-1 of
        the centre), from the gap ``e`` of the torus (R11)."""
        body, h = self.body, self.h
        sign = 1.0 if self.axis == 1 else -1.0
        hi = (body.c / body.a - 1.0) if self.axis == 1 else (1.0 - body.c / body.b)
        lo = 1e-14

        def f(u: float) -> float:
            return free_top_at_gap(body, h, sign * math.exp(u)).rotation_number - W

        e = sign * math.exp(brentq(f, math.log(lo), math.log(hi * (1 - 1e-12)),
                                   xtol=1e-14))
        x = body.c / (1.0 + e)                              # 2h/G^2 = c/(1 + e)
        s = math.sqrt(min(max((body.b - x) / (body.b - body.a), 0.0), 1.0))
        base = math.asin(s)
        if self.axis == 1:          # G1 > 0: l in (0, pi)
            return base if side < 0 else math.pi - base
        return base if side < 0 else -base      # G2 > 0: l in (-pi/2, pi/2)

    def _l_or_none(self, W: float, side: int) -> float | None:
        key = (W, side)
        if key not in self._lines:
            try:
                self._lines[key] = self.l_of_W(W, side)
            except ValueError:
                self._lines[key] = None
        return self._lines[key]

    def seed(self, l0: float, g0: float) -> NDArray[np.float64] | None:
        """The state on the line ``(g0, L = 0)`` at ``l0`` on the level (a copy: the
        caller may keep or change it), None where the level does not reach it."""
        y = self.seeds(np.array([l0]), g0)[0]
        return None if y is None else y.copy()

    def seeds(self, ls: NDArray[np.float64], g0: float
              ) -> list[NDArray[np.float64] | None]:
        """The states on the line ``(g0, L = 0)`` at every ``ls`` (not copies), the root
        ``G`` of the level nearest the free top's; those not computed yet in one call."""
        todo = np.array([x for x in ls.tolist() if (x, g0) not in self._seeds])
        if todo.size:
            b = self.body
            G_free = np.sqrt(2.0 * self.h / (b.a * np.sin(todo) ** 2
                                             + b.b * np.cos(todo) ** 2))
            roots = section_roots(b, self.h, self.M, ("g", g0), todo, np.zeros_like(todo))
            for l0, r, G in zip(todo.tolist(), roots, G_free, strict=True):
                self._seeds[(l0, g0)] = None if r.size == 0 else np.asarray(
                    from_andoyer([l0, g0, 0.0, float(r[np.argmin(np.abs(r - G))]), self.M]),
                    dtype=float)
        return [self._seeds[(x, g0)] for x in ls.tolist()]

    def t_max(self, returns: int) -> float:
        """A flight long enough for ``returns`` returns (four times their free-top time)."""
        return 4.0 * returns * self.return_time + 100.0

    # ---------------------------------------------------------------- (G3)
    def advance(self, mom: NDArray[np.float64]) -> float:
        """The angle swept about the regime's centre in the plane ``(l, L)`` by the
        momenta ``mom`` (one row per crossing), unwrapped crossing by crossing: the angle
        ``atan2(L, l - l_c)`` is 0 or pi exactly where ``L = 0``."""
        l = np.arctan2(mom[:, 0], mom[:, 1])
        centre = math.pi / 2 if self.axis == 1 else 0.0
        theta = np.arctan2(mom[:, 2], l - centre)
        return float(np.sum(np.mod(np.diff(theta) + math.pi, 2.0 * math.pi) - math.pi))

    def half(self, l0: float, g0: float, p: int, q: int) -> float:
        """``F(l0) = Phi - pi p`` over the half orbit (NaN where it cannot be followed),
        integrated once per start (G3)."""
        return float(self.halves(np.array([l0]), g0, p, q)[0])

    def halves(self, ls: NDArray[np.float64], g0: float, p: int, q: int
               ) -> NDArray[np.float64]:
        """:meth:`half` at every start ``ls``: the seeds and half orbits not computed yet in
        one call each (an engine batch, on SIMD lanes when there are enough), cached as
        :meth:`half` caches them."""
        todo = [x for x in ls.tolist() if (x, g0, p, q) not in self._halves]
        if todo:
            for x, v in zip(todo, self._halves_of(np.array(todo), g0, p, q), strict=True):
                self._halves[(x, g0, p, q)] = v
        return np.array([self._halves[(x, g0, p, q)] for x in ls.tolist()])

    def _halves_of(self, ls: NDArray[np.float64], g0: float, p: int, q: int
                   ) -> list[float]:
        ys = self.seeds(ls, g0)
        ok = [i for i, y in enumerate(ys) if y is not None]
        out = [math.nan] * ls.size
        if not ok:
            return out
        g_end, k = self._end(g0, q)
        y0 = np.array([ys[i] for i in ok])
        try:
            cr = self.engine.crossings(y0, self.body.engine_params, Section("g", g_end, 1), k,
                                       self.t_max(k), self.tol)
        except FloatingPointError:      # an orbit failed: NaN alone, or each on its own
            if ls.size == 1:
                return out
            return [self._halves_of(np.array([l0]), g0, p, q)[0] for l0 in ls.tolist()]
        self.evaluations += len(ok)
        for j, i in enumerate(ok):
            if int(cr.count[j]) == k:
                mom = np.vstack([y0[j, :3], cr.y[j, :, :3]])
                out[i] = abs(self.advance(mom)) - math.pi * p
        return out

    @staticmethod
    def _end(g0: float, q: int) -> tuple[float, int]:
        """The section and the crossing where a half orbit from the line ``g0`` ends
        (G3): the ``q/2``-th return to ``g0`` (``q`` even), the ``(q + 1)/2``-th crossing
        of ``g0 + pi`` (``q`` odd)."""
        if q % 2 == 0:
            return g0, q // 2
        return (g0 + math.pi) % (2.0 * math.pi), (q + 1) // 2

    def orbit(self, p: int, q: int, g0: float, side: int,
              near: float | None = None) -> _Orbit | None:
        """The symmetric ``p/q`` orbit on the line ``(g0, side)``: the root of ``F`` nearest
        ``near`` (or the free-top ``l`` of ``p/q``), then its residue (G4)."""
        w_lo, w_hi = self.band
        # geometric in the free-top W, well beyond the band: near the separatrix mu moves
        # the chains by more than the band's width (the W beyond the centre's are dropped)
        Ws = np.geomspace(w_lo / _MARGIN, w_hi * _MARGIN, _GRID)
        ls = np.array([x for x in (self._l_or_none(float(W), side) for W in Ws)
                       if x is not None])      # W beyond the centre's: no torus there
        if ls.size < 2:
            return None
        target = near if near is not None else self._l_or_none(p / q, side)
        if target is None:
            return None
        if near is not None:    # the previous root first: a small bracket around it
            root = self._local(near, g0, p, q, ls)
            if root is not None:
                return self._closed(root, g0, p, q)
        f = self.halves(ls, g0, p, q)
        ok = np.isfinite(f[:-1]) & np.isfinite(f[1:])
        # every sign change: a jump of the winding (F by 2 pi) is no root, and Brent's
        # answer there is refused by the size of F (:meth:`_brent`)
        brackets = [i for i in range(ls.size - 1)
                    if ok[i] and np.sign(f[i]) != np.sign(f[i + 1])]
        for i in sorted(brackets, key=lambda j: abs(0.5 * (ls[j] + ls[j + 1]) - target)):
            root = self._brent(float(ls[i]), float(ls[i + 1]), g0, p, q)
            orbit = None if root is None else self._closed(root, g0, p, q)
            if orbit is not None and orbit.winding == p:
                return orbit
        return None

    def _local(self, near: float, g0: float, p: int, q: int, ls: NDArray[np.float64]
               ) -> float | None:
        f0 = self.half(near, g0, p, q)
        if not np.isfinite(f0):
            return None
        step = 1e-3 * float(np.abs(np.diff(ls)).mean())
        for _ in range(12):
            for s in (1.0, -1.0):
                x = near + s * step
                f1 = self.half(x, g0, p, q)
                if np.isfinite(f1) and np.sign(f1) != np.sign(f0):
                    return self._brent(min(near, x), max(near, x), g0, p, q)
            step *= 3.0
        return None

    def _brent(self, a: float, b: float, g0: float, p: int, q: int) -> float | None:
        fa, fb = self.half(a, g0, p, q), self.half(b, g0, p, q)
        if not (np.isfinite(fa) and np.isfinite(fb)) or np.sign(fa) == np.sign(fb):
            return None

        def f(x: float) -> float:
            v = self.half(x, g0, p, q)
            if not np.isfinite(v):
                raise _LostError
            return v

        try:
            root = float(brentq(f, a, b, xtol=1e-15, rtol=4 * np.finfo(float).eps,
                                maxiter=80))
        except (_LostError, RuntimeError):
            return None
        # a root of F is one to rounding; a jump of the winding leaves F ~ pi there
        return root if abs(self.half(root, g0, p, q)) < _ROOT_F else None

    def _closed(self, l0: float, g0: float, p: int, q: int) -> _Orbit | None:
        """The whole orbit from ``l0`` with its state-transition matrix: residue (G4),
        period, closure and winding."""
        y = self.seed(l0, g0)
        if y is None:
            return None
        try:
            flow = self.engine.tangent(y[None], np.eye(6), self.body.engine_params, self.tol,
                                       event=Section("g", g0, 1), n_crossings=q,
                                       t_max=self.t_max(q), renormalise=False)
        except FloatingPointError:
            return None
        if not (bool(flow.ok[0]) and int(flow.count[0]) == q):
            return None
        w = flow.w[0, -1]
        residue = (6.0 - float(np.trace(w))) / 4.0      # Tr is the same for w and w.T
        mom = np.vstack([y[:3], flow.y[0, :, :3]])
        turns = abs(self.advance(mom)) / (2 * math.pi)
        # the trace's error: the integration's (tol per unit of |Phi|) and the closure's
        resolution = _RESOLUTION * self.tol.tol * max(1.0, float(np.linalg.norm(w)))
        return _Orbit(l0, g0, residue, float(flow.t[0, -1]),
                      float(np.linalg.norm(flow.y[0, -1] - y)), round(turns), resolution)

    def pair(self, p: int, q: int, previous: tuple[_Orbit | None, _Orbit | None] | None = None
             ) -> tuple[_Orbit | None, _Orbit | None]:
        """The elliptic and the hyperbolic symmetric ``p/q`` orbits (G3): on the lines
        ``g = pi/2`` either side of the centre (``q`` odd) or ``g = pi/2`` and ``3 pi/2``
        on one side (``q`` even), then on the other two lines while one is missing (near a
        separatrix ``mu`` can push a line's root out of reach); the larger residue is the
        elliptic one."""
        first = ([(math.pi / 2, -1), (math.pi / 2, 1)] if q % 2
                 else [(math.pi / 2, -1), (3 * math.pi / 2, -1)])
        others = ([(3 * math.pi / 2, -1), (3 * math.pi / 2, 1)] if q % 2
                  else [(math.pi / 2, 1), (3 * math.pi / 2, 1)])
        orbits: list[_Orbit] = []
        for k, (g0, side) in enumerate(first + others):
            if k == len(first) and len(orbits) == 2:
                break
            near = None
            if previous is not None:
                for o in previous:
                    if o is not None and o.g0 == g0 and self._side(o.l0) == side:
                        near = o.l0
            o = self.orbit(p, q, g0, side, near)
            if o is None or o.winding != p:
                continue
            kind = o.residue > 0
            if k >= len(first) and any((x.residue > 0) == kind for x in orbits):
                continue            # the type already found: the other lines add only it
            orbits.append(o)
            if k >= len(first) and len(orbits) == 2:
                break
        if not orbits:
            return None, None
        if len(orbits) == 1:
            one = orbits[0]
            return (one, None) if one.residue > 0 else (None, one)
        a, b = sorted(orbits, key=lambda o: -o.residue)[:2]
        return a, b

    def _side(self, l0: float) -> int:
        if self.axis == 1:
            return -1 if l0 < math.pi / 2 else 1
        return -1 if l0 > 0 else 1


class _LostError(Exception):
    """An orbit of the root search could not be followed (left the regime)."""


_META = {
    "p": ("p", "turns of (l, L) of the convergent's orbit", "1", "(G1)"),
    "q": ("q", "returns to the section g = pi/2 per period of the convergent's orbit", "1",
          "(G1)"),
    "convergent_rotation_number": ("p/q", "the convergent p/q of the noble rotation number",
                                   "1", "(G1)"),
    "residue_elliptic": ("R_e", "Greene's residue (6 - Tr Phi(T))/4 of the elliptic "
                         "symmetric p/q orbit at the body's mu", "1", "(G4)"),
    "residue_hyperbolic": ("R_h", "Greene's residue of the hyperbolic symmetric p/q orbit "
                           "at the body's mu", "1", "(G4)"),
    "start_l_elliptic": ("l_0", "l of the elliptic orbit on its symmetry line L = 0", "rad",
                         "(G3)"),
    "start_g_elliptic": ("g_0", "g of the elliptic orbit's symmetry line (pi/2 or 3 pi/2)",
                         "rad", "(G2)"),
    "start_l_hyperbolic": ("l_0", "l of the hyperbolic orbit on its symmetry line L = 0",
                           "rad", "(G3)"),
    "start_g_hyperbolic": ("g_0", "g of the hyperbolic orbit's symmetry line", "rad",
                           "(G2)"),
    "period_elliptic": ("T", "period of the elliptic orbit (q returns)", "body time units",
                        "(G4)"),
    "period_hyperbolic": ("T", "period of the hyperbolic orbit", "body time units", "(G4)"),
    "closure_elliptic": ("|y(T) - y_0|", "closure of the elliptic orbit after q returns",
                         "1", "(G3)"),
    "closure_hyperbolic": ("|y(T) - y_0|", "closure of the hyperbolic orbit", "1", "(G3)"),
    "residue_resolution_elliptic": ("", "tol |Phi(T)|: a smaller |residue_elliptic| is "
                                    "the integration's error (rounding), not the orbit's",
                                    "1", "(G4)"),
    "residue_resolution_hyperbolic": ("", "tol |Phi(T)| of the hyperbolic orbit", "1",
                                      "(G4)"),
    "mu_critical_convergent": ("\\mu_c(q)", "mu at which the elliptic residue of this "
                               "convergent equals 1/4 (NaN: not in mu_range, or no orbit)",
                               "1", "(G5)"),
    "residue_hyperbolic_critical": ("R_h(\\mu_c(q))", "residue of the hyperbolic orbit at "
                                    "mu_critical_convergent", "1", "(G5)"),
    "seconds": ("", "wall-clock time of this convergent (orbits at the body's mu and the "
                "search in mu)", "s", ""),
    "mu_critical": ("\\mu_c", "critical mu of the torus: mu_critical_convergent of the "
                    "largest q found", "1", "(G5)"),
    "mu_critical_error": ("", "|mu_c(q_j) - mu_c(q_{j-1})| of the last two convergents "
                          "found", "1", "(G5)"),
    "mu_critical_low": ("", "the smaller of the last two mu_c(q_j)", "1", "(G5)"),
    "mu_critical_high": ("", "the larger of the last two mu_c(q_j)", "1", "(G5)"),
    "convergence_ratio": ("", "ratio of the last two successive differences of "
                          "mu_c(q_j): the geometric rate of their convergence", "1",
                          "(G5)"),
    "chirikov_parameter": ("s", "(Delta G_n + Delta G_{n+1}) / |G*_n - G*_{n+1}| of the two "
                           "main chains at the body's mu (first order)", "1", "(G6)"),
    "mu_overlap": ("\\mu_{overlap}", "mu at which the main chains' first-order widths touch "
                   "(s = 1)", "1", "(G6)"),
    "mu_ratio": ("\\mu_c/\\mu_{overlap}", "mu_critical / mu_overlap", "1", "(G5), (G6)"),
}


class _Plan(NamedTuple):
    """The checked inputs of one level of :func:`last_torus`, its main chains and its
    estimated cost (integration steps)."""

    h: float
    M: float
    quotients: tuple[int, ...]
    axis: int
    n_convergents: int
    tolerance: Tolerance
    mus: tuple[float, float] | None
    conv: list[tuple[int, int]]
    eng: EngineBase
    chains: list[ResonantChain]
    s: float
    mu_overlap: float
    band: tuple[float, float]
    evaluations: int
    period: float
    steps: float


def _plan(body: RigidBody, h: float, M: float, head: Any, axis: Any, n_convergents: Any,
          mu_range: Any, tol: float, engine: EngineLike) -> _Plan:
    """Check the inputs of :func:`last_torus` on one level (errors naming the argument),
    find the two main chains (G6) and estimate the cost, before any orbit is integrated."""
    h, M, _ = check_level_args(body, h, M, 2)
    quotients = _head(head)
    axis = integer("axis", axis, 1, 2)
    n_convergents = integer("n_convergents", n_convergents, 1, MAX_CONVERGENTS)
    tolerance = Tolerance.single(tol)
    if not body.mu > 0.0:
        raise ValueError("last_torus needs mu > 0: at mu = 0 every torus exists (every "
                         "residue is 0)")
    if body.e3 != 0.0:
        raise ValueError(f"last_torus needs the centre of mass in the body plane Oxy "
                         f"(e3 = 0, the symmetry of its search), got e3 = {body.e3!r}")
    mus = None
    if mu_range is not None:
        if (not isinstance(mu_range, Sequence) or isinstance(mu_range, str)
                or len(mu_range) != 2):
            raise ValueError(f"mu_range must be (mu_low, mu_high), got {mu_range!r}")
        lo, hi = (positive("mu_range", v) for v in mu_range)
        if not lo < hi:
            raise ValueError(f"mu_range must have mu_low < mu_high, got {mu_range!r}")
        if hi > 1e3 * max(h, 1e-12):
            raise ValueError(f"mu_range: mu_high = {hi!r} is over 1000 h (the level is "
                             f"then the bottom of the potential well)")
        mus = (lo, hi)
    n = quotients[0]
    conv = [(p, q) for p, q in convergents(quotients, n_convergents + 8)
            if q > n + 1][:n_convergents]
    if conv[-1][1] > MAX_PERIOD:
        raise ValueError(f"n_convergents = {n_convergents}: the last convergent has period "
                         f"q = {conv[-1][1]} > MAX_PERIOD = {MAX_PERIOD}; ask for fewer")
    # its cost is one orbit's g sections at a time: the default of angle sections
    eng = resolve_engine(engine, Capability.TANGENT_CROSSINGS, workload="angle_section")
    tolerance = eng.attainable(tolerance)
    # the two main chains and their first-order widths (G6)
    where = (f"head = {quotients!r}: the main chains {n}:1 and {n + 1}:1 on h = {h!r}, "
             f"M = {M!r} about axis {axis}")
    try:
        rows = [r for r in resonant_rows(body, h, M, n + 2) if r["p"] == 1
                and r["q"] in (n, n + 1) and r["axis"] == axis and r["sign"] == 1]
        if len(rows) != 2:
            raise ValueError("they are not both on the level")
        sec = Section("g", 0.0, 1)
        chains = [ResonantChain(body, h, M, r, sec) for r in rows]
    except ValueError as exc:           # absent, or too near the separatrix to sample
        raise ValueError(f"{where}: {exc}") from None
    s = (chains[0].dG + chains[1].dG) / abs(chains[0].torus.G - chains[1].torus.G)
    mu_overlap = body.mu / s**2
    band = (1.0 / (n + 1), 1.0 / n)
    # cost: every half orbit of every evaluation, and the tangent flows (7x a state)
    returns = sum(q * (2 * _EVALUATIONS / 2 + 2 * 7) for _, q in conv)
    evaluations = 1 + (_MU_EVALUATIONS if mus is not None else 0)
    period = 2 * math.pi / chains[0].torus.omega_g
    y_probe = chains[0].states(np.array([0.0]))
    y_probe = np.concatenate([y_probe[0], [0.0, 0.0, 1.0]])[None]
    steps = budget.estimate_steps(body, y_probe, returns * evaluations * period, tolerance.tol)
    return _Plan(h, M, quotients, axis, n_convergents, tolerance, mus, conv, eng, chains, s,
                 mu_overlap, band, evaluations, period, steps)


@checks_body(ranges={"h": "energy", "M": "action", "tol": "tolerance"})
def last_torus(body: RigidBody, h: float, M: float = 0.0, *, head: Sequence[int] = (2,),
               axis: int = 1, n_convergents: int = 6,
               mu_range: tuple[float, float] | None = None, tol: float = 1e-13,
               engine: EngineLike = None, progress: bool | None = None) -> xr.Dataset:
    """Greene's residues of the convergents of a noble torus between two main chains, and
    the critical ``mu`` at which the torus breaks (G1)-(G6).

    The rotation number is ``W = [0; head, 1, 1, ...]`` (:func:`noble_number`), between the
    main chains ``head[0]:1`` and ``(head[0]+1):1`` of the regime about ``axis``. For each
    convergent ``p/q`` beyond those chains (:func:`convergents`) the elliptic and the
    hyperbolic symmetric periodic orbits are found on the symmetry lines ``L = 0`` of the
    sections ``g = pi/2, 3 pi/2`` (G2), (G3) and their residues computed from the
    state-transition matrix over the period (G4), at the body's ``mu``; with ``mu_range``,
    for each convergent the ``mu`` at which the elliptic residue is 1/4 (G5), by Brent's
    method in ``ln mu`` with the orbits continued from one ``mu`` to the next. Beside it,
    the first-order overlap estimate of the two main chains (G6).

    Parameters
    ----------
    body : RigidBody
        Oz the middle axis of inertia, centre of mass in the plane Oxy (``e3 = 0``: the
        symmetry (G2)); its ``mu`` > 0 is where the residues are given.
    h : float
        The energy level (> 0).
    M : float
        The area constant.
    head : sequence of int
        The partial quotients of ``W`` before its tail of ones: ``(n,)`` the golden-mean
        torus between the chains ``n:1`` and ``(n+1):1``, ``(n, k)`` another noble torus
        between them. ``n >= 2``.
    axis : {1, 2}
        The regime: the tori about body axis 1 or 2.
    n_convergents : int
        Convergents followed beyond the two main chains (1 to :data:`MAX_CONVERGENTS`;
        the last ``q`` at most :data:`MAX_PERIOD`).
    mu_range : (float, float), optional
        ``(mu_low, mu_high)``, ``0 < mu_low < mu_high``: where the critical ``mu`` of each
        convergent is sought (NaN where the residue does not cross 1/4 there). None: the
        residues at the body's ``mu`` only.
    tol : float
        Integration tolerance (the engine's; in ``[1e-16, 1e-3]``).
    engine : str or Engine, optional
        An engine with the ``tangent_crossings`` capability (default: that of angle
        sections, :data:`~andoyer.integrate.engines.MEASURED_DEFAULTS`: taylor; the
        searches integrate one orbit's ``g`` sections at a time).
    progress : bool, optional
        A progress bar over the orbits (default: on a terminal).

    Returns
    -------
    xarray.Dataset
        Dim ``convergent``: ``p``, ``q``, ``convergent_rotation_number``,
        ``residue_elliptic``, ``residue_hyperbolic`` (NaN where the orbit was not found,
        ``found_elliptic``/``found_hyperbolic`` False), their symmetry-line starts
        ``start_l_*``, ``start_g_*``, periods ``period_*``, closures ``closure_*`` and
        ``residue_resolution_*`` (the integration error of the residue),
        ``mu_critical_convergent`` and ``residue_hyperbolic_critical``, ``seconds``;
        0-d ``mu_critical`` with ``mu_critical_error``, ``mu_critical_low``,
        ``mu_critical_high``, ``convergence_ratio``, ``chirikov_parameter``,
        ``mu_overlap``, ``mu_ratio``. Attrs: ``rotation_number``, ``head``,
        ``main_chains``, ``axis``, ``threshold``, ``mu_range``, the provenance.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> body = RigidBody.hess(3.0, 1.0, 2.0, mu=2e-3)
    >>> ds = last_torus(body, 1.0, head=(2,), axis=2, n_convergents=2, progress=False)
    >>> [f"{p}/{q}" for p, q in zip(ds.p.values, ds.q.values)]
    ['2/5', '3/8']
    >>> bool((ds.residue_elliptic > 0).all() and (ds.residue_hyperbolic < 0).all())
    True
    >>> bool(ds.residue_elliptic[1] < ds.residue_elliptic[0])   # the torus exists
    True
    """
    plan = _plan(body, h, M, head, axis, n_convergents, mu_range, tol, engine)
    budget.check(f"last_torus (n_convergents = {n_convergents}, mu_range = {mu_range!r})",
                 steps=plan.steps)
    h, M, quotients, axis, tolerance, mus = (plan.h, plan.M, plan.quotients, plan.axis,
                                             plan.tolerance, plan.mus)
    conv, eng, s, mu_overlap, band = plan.conv, plan.eng, plan.s, plan.mu_overlap, plan.band
    evaluations, period, n = plan.evaluations, plan.period, plan.quotients[0]
    bar = Progress(len(conv) * evaluations, f"last torus W = [0; {', '.join(map(str, quotients))}"
                   ", 1, ...]", progress)
    cols: dict[str, list[float]] = {k: [] for k in (
        "residue_elliptic", "residue_hyperbolic", "start_l_elliptic", "start_g_elliptic",
        "start_l_hyperbolic", "start_g_hyperbolic", "period_elliptic", "period_hyperbolic",
        "closure_elliptic", "closure_hyperbolic", "residue_resolution_elliptic",
        "residue_resolution_hyperbolic", "mu_critical_convergent",
        "residue_hyperbolic_critical", "seconds")}
    found_e, found_h = [], []
    lines: dict[tuple[float, int], float | None] = {}
    try:
        for p, q in conv:
            t0 = time.perf_counter()
            level = _Level(body, h, M, axis, band, eng, tolerance, period, lines)
            ell, hyp = level.pair(p, q)
            bar.update(1)
            for name, o in (("elliptic", ell), ("hyperbolic", hyp)):
                cols[f"residue_{name}"].append(o.residue if o else math.nan)
                cols[f"start_l_{name}"].append(o.l0 if o else math.nan)
                cols[f"start_g_{name}"].append(o.g0 if o else math.nan)
                cols[f"period_{name}"].append(o.period if o else math.nan)
                cols[f"closure_{name}"].append(o.closure if o else math.nan)
                cols[f"residue_resolution_{name}"].append(o.resolution if o else math.nan)
            found_e.append(ell is not None)
            found_h.append(hyp is not None)
            mc, rh = math.nan, math.nan
            if mus is not None:
                prior = [m for m in cols["mu_critical_convergent"] if math.isfinite(m)]
                guess = prior[-1] if prior else math.sqrt(mus[0] * mus[1])
                mc, rh = _critical(body, h, M, axis, band, eng, tolerance, period, p, q, mus,
                                   guess, bar, lines)
            cols["mu_critical_convergent"].append(mc)
            cols["residue_hyperbolic_critical"].append(rh)
            cols["seconds"].append(time.perf_counter() - t0)
    finally:
        bar.close()
    crit = np.array(cols["mu_critical_convergent"])
    good = crit[np.isfinite(crit)]
    mu_c = float(good[-1]) if good.size else math.nan
    err = float(abs(good[-1] - good[-2])) if good.size >= 2 else math.nan
    low = float(min(good[-2:])) if good.size >= 2 else mu_c
    high = float(max(good[-2:])) if good.size >= 2 else mu_c
    d = np.diff(good)
    ratio = float(abs(d[-1] / d[-2])) if d.size >= 2 and d[-2] != 0 else math.nan
    ds = xr.Dataset(
        {"p": ("convergent", np.array([p for p, _ in conv], dtype=np.int64)),
         "q": ("convergent", np.array([q for _, q in conv], dtype=np.int64)),
         "convergent_rotation_number": ("convergent", np.array([p / q for p, q in conv])),
         **{k: ("convergent", np.array(v, dtype=float)) for k, v in cols.items()},
         "found_elliptic": ("convergent", np.array(found_e, dtype=bool)),
         "found_hyperbolic": ("convergent", np.array(found_h, dtype=bool)),
         "mu_critical": ((), mu_c), "mu_critical_error": ((), err),
         "mu_critical_low": ((), low), "mu_critical_high": ((), high),
         "convergence_ratio": ((), ratio), "chirikov_parameter": ((), s),
         "mu_overlap": ((), mu_overlap), "mu_ratio": ((), mu_c / mu_overlap)},
        coords={"convergent": np.arange(len(conv))},
        attrs=provenance(
            body, h=h, M=M, rotation_number=noble_number(quotients),
            head=", ".join(map(str, quotients)), main_chains=f"{n}:1, {n + 1}:1", axis=axis,
            threshold=THRESHOLD, tolerance=tolerance.tol, engine=eng.name,
            mu_range="none" if mus is None else f"{mus[0]!r}, {mus[1]!r}",
            section="g = pi/2 (and 3 pi/2), symmetry lines L = 0",
            method="symmetric periodic orbits by Brent's method on the symmetry lines "
                   "(winding counted by the free-top phase); residues (6 - Tr Phi(T))/4 "
                   "from the state-transition matrix; mu_c(q) by Brent in ln mu",
            derivation="andoyer.analysis.resonance.residues (G1)-(G7)"))
    describe_variables(ds, {**_META,
                            "found_elliptic": ("", "the elliptic orbit was found", "1",
                                               "(G3)"),
                            "found_hyperbolic": ("", "the hyperbolic orbit was found", "1",
                                                 "(G3)")})
    return ds


#: Most energy levels :func:`critical_mu_curve` computes one by one (``M != 0``).
MAX_LEVELS = 24

_CURVE_META = {
    "mu_critical": ("\\mu_c", "critical mu of the noble torus on the level h: the last "
                    "torus of its rotation number breaks", "1", "(G5), (G7)"),
    "mu_critical_error": ("", "|mu_c(q_j) - mu_c(q_{j-1})| of the last two convergents "
                          "found on the level", "1", "(G5), (G7)"),
    "h_level": ("h", "energy level H = h", "1", "(1)"),
}


def _levels(h_values: Any) -> NDArray[np.float64]:
    if isinstance(h_values, bool | str | bytes) or h_values is None:
        raise ValueError(f"h_values must be a sequence of energy levels h > 0, got "
                         f"{h_values!r}")
    try:
        hs = np.atleast_1d(np.asarray(h_values, dtype=float))
    except (TypeError, ValueError):
        raise ValueError(f"h_values must be energy levels h > 0, got {h_values!r}") from None
    if hs.ndim != 1 or hs.size == 0:
        raise ValueError(f"h_values must be a sequence of energy levels h > 0, got "
                         f"{h_values!r}")
    if not np.all(np.isfinite(hs)) or not np.all(hs > 0.0):
        raise ValueError(f"h_values must be finite levels h > 0, got {h_values!r}")
    if np.any(np.diff(hs) <= 0.0):
        raise ValueError(f"h_values must increase strictly (one value per level), got "
                         f"{h_values!r}")
    return hs


@checks_body(ranges={"M": "action"})
def critical_mu_curve(body: RigidBody, h_values: Sequence[float], M: float = 0.0, *,
                      mu_range: tuple[float, float], progress: bool | None = None,
                      **last_torus_kwargs: Any) -> xr.Dataset:
    r"""The critical ``mu`` of a noble torus as a function of the energy level,
    ``mu_c(h)`` (G5), (G7): the atlas's overlay of the last torus.

    On ``M = 0`` the scaling ``G -> lambda G``, ``t -> t / lambda`` maps the level
    ``(h, mu)`` onto ``(lambda^2 h, lambda^2 mu)`` (G7), so

    .. math::

        \mu_c(h) = \mu_c(h_0) \, h / h_0

    exactly: :func:`last_torus` runs once, on ``h_0 = h_values[0]``, and the others are
    scaled (``method = "scaled"``). On ``M != 0`` the area scales too,
    ``(h, M, mu) -> (lambda^2 h, lambda M, lambda^2 mu)``, so a fixed ``M`` is another
    problem on every level: :func:`last_torus` runs on each (``method = "per_level"``),
    at most :data:`MAX_LEVELS` of them, after the cost of all of them has been checked
    (:mod:`andoyer.integrate.budget`).

    Parameters
    ----------
    body : RigidBody
        As for :func:`last_torus`; its ``mu`` (> 0) is the one of ``h_values[0]``, scaled
        by ``h / h_0`` on the other levels (where the residues at the body's ``mu`` and
        the overlap estimate are taken).
    h_values : sequence of float
        The energy levels (> 0, strictly increasing).
    M : float
        The area constant, the same on every level.
    mu_range : (float, float)
        ``(mu_low, mu_high)`` where ``mu_c`` is sought on ``h_values[0]``; on the other
        levels scaled by ``h / h_0`` (exact on ``M = 0``, a guess elsewhere).
    progress : bool, optional
        A progress bar over the levels (default: on a terminal).
    **last_torus_kwargs
        ``head``, ``axis``, ``n_convergents``, ``tol``, ``engine`` of :func:`last_torus`.

    Returns
    -------
    xarray.Dataset
        Dim ``h_level``: ``mu_critical`` and ``mu_critical_error`` (NaN where ``mu_c`` was
        not found in the level's ``mu_range``). Attrs: ``method`` (``scaled`` or
        ``per_level``), ``reference_level`` (``h_0``), ``rotation_number``, ``head``,
        ``main_chains``, ``axis``, ``mu_range``, ``M``, ``threshold``, the provenance.

    Examples
    --------
    On ``M = 0`` nothing is integrated beyond the first level (here replaced by a known
    result, so that the example runs in no time):

    >>> from unittest import mock
    >>> import xarray as xr
    >>> from andoyer import RigidBody
    >>> from andoyer.analysis.resonance import residues
    >>> one = xr.Dataset({"mu_critical": 0.0551, "mu_critical_error": 0.006},
    ...                  attrs={"rotation_number": 0.382, "head": "2",
    ...                         "main_chains": "2:1, 3:1", "tolerance": 1e-13,
    ...                         "engine": "heyoka"})
    >>> body = RigidBody.hess(3.0, 1.0, 2.0, mu=2e-3)
    >>> with mock.patch.object(residues, "last_torus", return_value=one):
    ...     curve = residues.critical_mu_curve(body, [1.0, 2.0], mu_range=(0.01, 1.0),
    ...                                        axis=2, progress=False)
    >>> curve.mu_critical.values.round(4).tolist(), curve.attrs["method"]
    ([0.0551, 0.1102], 'scaled')
    """
    hs = _levels(h_values)
    for h in hs:                  # every level, the scaled ones too, within the integrators'
        budget.check_level(body, float(h), "h_values")
    if not isinstance(M, int | float | np.floating | np.integer) or not math.isfinite(M):
        raise ValueError(f"M must be a finite number, got {M!r}")
    unknown = sorted(set(last_torus_kwargs) - {"head", "axis", "n_convergents", "tol",
                                                "engine"})
    if unknown:
        raise TypeError(f"critical_mu_curve: unexpected keyword argument {unknown[0]!r} "
                        "(last_torus's head, axis, n_convergents, tol, engine are passed on)")
    h0 = float(hs[0])
    scaled = float(M) == 0.0
    runs = [h0] if scaled else [float(h) for h in hs]
    if len(runs) > MAX_LEVELS:
        raise ValueError(f"h_values: {len(runs)} levels at M = {M!r} (each its own "
                         f"last_torus, tens of seconds or more) > MAX_LEVELS = {MAX_LEVELS}; "
                         "ask for fewer")
    opts = {"head": (2,), "axis": 1, "n_convergents": 6, "tol": 1e-13, "engine": None,
            **last_torus_kwargs}
    if (not isinstance(mu_range, Sequence) or isinstance(mu_range, str)
            or len(mu_range) != 2):
        raise ValueError(f"mu_range must be (mu_low, mu_high), got {mu_range!r}")
    if any(isinstance(v, bool) or not isinstance(v, int | float | np.integer | np.floating)
           for v in mu_range):
        raise ValueError(f"mu_range must be two numbers (mu_low, mu_high), got {mu_range!r}")
    mu_range = (float(mu_range[0]), float(mu_range[1]))

    def at(h: float) -> tuple[RigidBody, tuple[float, float]]:
        k = h / h0
        return body.with_mu(body.mu * k), (mu_range[0] * k, mu_range[1] * k)

    # every level checked and costed before any orbit is integrated
    steps = 0.0
    for h in runs:
        b, mr = at(h)
        try:
            steps += _plan(b, h, M, opts["head"], opts["axis"], opts["n_convergents"], mr,
                           opts["tol"], opts["engine"]).steps
        except ValueError as exc:
            raise ValueError(f"on the level h = {h!r} of h_values: {exc}") from None
    budget.check(f"critical_mu_curve ({len(runs)} level(s) of last_torus, n_convergents = "
                 f"{opts['n_convergents']}, mu_range = {mu_range!r})", steps=steps)
    bar = Progress(len(runs), "mu_c(h)", progress)
    results = []
    try:
        for h in runs:
            b, mr = at(h)
            results.append(last_torus(b, h, M, mu_range=mr, progress=False, **opts))
            bar.update(1)
    finally:
        bar.close()
    if scaled:
        ref = results[0]
        k = hs / h0
        mu_c = float(ref.mu_critical) * k
        err = float(ref.mu_critical_error) * k
        method = ("scaled: last_torus on the reference level h_0 = h_values[0], "
                  "mu_c(h) = mu_c(h_0) h / h_0 on M = 0 (G7)")
    else:
        ref = results[0]
        mu_c = np.array([float(r.mu_critical) for r in results])
        err = np.array([float(r.mu_critical_error) for r in results])
        method = "per_level: one last_torus on each level (M != 0: no scaling at fixed M)"
    a = ref.attrs
    ds = xr.Dataset(
        {"mu_critical": ("h_level", np.asarray(mu_c, dtype=float)),
         "mu_critical_error": ("h_level", np.asarray(err, dtype=float))},
        coords={"h_level": hs},
        attrs=provenance(
            body, M=float(M), reference_level=h0, rotation_number=a.get("rotation_number"),
            head=a.get("head"), main_chains=a.get("main_chains"),
            axis=int(opts["axis"]), threshold=THRESHOLD, tolerance=a.get("tolerance"),
            engine=a.get("engine"), mu_range=f"{mu_range[0]!r}, {mu_range[1]!r}",
            method=method.split(":")[0], method_description=method,
            kind="critical_mu_curve",
            derivation="andoyer.analysis.resonance.residues (G5), (G7)"))
    describe_variables(ds, _CURVE_META)
    return ds


def _critical(body: RigidBody, h: float, M: float, axis: int, band: tuple[float, float],
              eng: EngineBase, tol: Tolerance, period: float, p: int, q: int,
              mus: tuple[float, float], guess: float, bar: Progress,
              lines: dict[tuple[float, int], float | None]) -> tuple[float, float]:
    """``mu`` in ``mus`` where the elliptic residue of ``p/q`` is :data:`THRESHOLD` (G5),
    and the hyperbolic residue there; NaN where it is not found (``lines``: the level's
    free-top lines, :class:`_Level`).

    From ``guess`` (the previous convergent's ``mu_c``: they converge) ``mu`` steps by
    :data:`_MU_STEP` up or down, each orbit continued from the last, until the residue
    crosses the threshold; Brent's method in ``ln mu`` closes the bracket."""
    last: list[tuple[_Orbit | None, _Orbit | None]] = [(None, None)]
    calls = [0]

    def residues(mu: float) -> tuple[_Orbit | None, _Orbit | None]:
        level = _Level(body.with_mu(mu), h, M, axis, band, eng, tol, period, lines)
        pair = level.pair(p, q, last[-1]) if last[-1][0] is not None else (None, None)
        if pair[0] is None:                      # the continuation lost it: search afresh
            pair = level.pair(p, q)
        if pair[0] is not None:
            last.append(pair)
        calls[0] += 1
        if calls[0] <= _MU_EVALUATIONS:
            bar.update(1)
        return pair

    def g(u: float) -> float:
        e, _ = residues(math.exp(u))
        if e is None:
            raise _LostError
        return math.log(max(e.residue, 1e-300) / THRESHOLD)

    lo, hi = (math.log(m) for m in mus)
    u = min(max(math.log(guess), lo), hi)
    out = (math.nan, math.nan)
    try:
        gu = g(u)
        step = math.log(_MU_STEP) * (1.0 if gu < 0 else -1.0)
        while calls[0] < _MU_EVALUATIONS - 8:
            v = min(max(u + step, lo), hi)
            if v == u:
                break
            try:
                gv = g(v)
            except _LostError:           # beyond the torus the orbit may be lost: nearer
                step *= 0.5
                continue
            if np.sign(gv) != np.sign(gu):
                a, b = sorted((u, v))
                w = brentq(g, a, b, xtol=1e-6, maxiter=40)
                _, hyp = residues(math.exp(w))
                out = (float(math.exp(w)), hyp.residue if hyp is not None else math.nan)
                break
            u, gu = v, gv
    except (_LostError, RuntimeError):
        pass
    bar.update(max(_MU_EVALUATIONS - calls[0], 0))     # the bar counts _MU_EVALUATIONS each
    return out
