"""A validated Taylor integrator for the Euler-Poisson field (1) and its variational equations.

The field (1) is quadratic in the state, so the Taylor coefficients of a solution are
Cauchy products: ``(k + 1) y_{k+1} = f_k(y_0, ..., y_k)``, and those of the variational
matrix ``V' = Df(y) V`` too. A step of length ``h`` and order ``p`` from a set ``X``:

1. **A priori enclosure** (Picard): a box ``B`` with ``X + [0, h] f(B) ⊂ B``; then every
   solution from ``X`` stays in ``B`` on ``[0, h]``, and likewise ``B_V`` for ``V``.
2. **Taylor polynomial + Lagrange remainder**: ``y(h) ∈ sum_{k<p} y_k(x) h^k + y_p(B) h^p``
   (the ``p``-th coefficient of a solution through ``B``), and the step map's derivative
   ``J ∈ sum_{k<p} V_k(X) h^k + V_p(B, B_V) h^p`` over the whole set.
3. **Lohner's wrapping control**: the set is ``x = m + Q r`` (``m`` a point, ``Q`` an
   orthogonal float matrix, ``r`` a box); by the mean value theorem
   ``phi(x) ∈ z + (J Q) r`` with ``z`` the enclosure of ``phi(m)``; the new frame ``Q'``
   is the QR factor of ``mid(J Q)`` (columns ordered by their lengths times the widths of
   ``r``) and ``r' = (Q'^{-1} J Q) r + Q'^{-1} (z - m')`` with ``Q'^{-1}`` enclosed by Arb.

The derivative of the flow over the set is the product of the step derivatives ``J``.
Every number is an Arb ball (python-flint); the body's field comes from
:func:`andoyer.integrate.validated.arithmetic.field_terms` (SymPy, from the one H).

A certified Poincaré map to a linear section ``(w, y) = c`` (e.g. ``G3 = 0``, the
section ``L = 0``) encloses the crossing time by the interval Newton operator on
``sigma(tau) = (w, y(t + tau)) - c`` with ``sigma' = (w, f(B))`` bounded away from 0, and
the image and derivative of the map by the mean value form.
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from flint import arb, arb_mat

from andoyer.integrate.validated.arithmetic import (
    FLINT_VERSION,
    BodySpec,
    ball_text,
    body_symbols,
    evaluate,
    field_terms,
    working_precision,
)

__all__ = ["QuadraticField", "quadratic_field", "ValidatedOrbit", "validated_flow",
           "PoincareCrossing", "validated_poincare", "taylor_jets", "variational_jets"]

Vector = list[Any]


@dataclass(frozen=True)
class QuadraticField:
    """``f_i(y) = sum c y_j + sum c y_j y_k`` with ball coefficients.

    Attributes
    ----------
    linear : tuple
        Per component, ``(c, j)`` pairs.
    quadratic : tuple
        Per component, ``(c, j, k)`` triples.
    bits : int
        The precision the coefficients were enclosed at.
    """

    linear: tuple[tuple[tuple[arb, int], ...], ...]
    quadratic: tuple[tuple[tuple[arb, int, int], ...], ...]
    bits: int

    @property
    def n(self) -> int:
        """The dimension."""
        return len(self.linear)

    def __call__(self, y: Vector) -> Vector:
        """``f(y)`` in ball arithmetic."""
        out = []
        for i in range(self.n):
            s: Any = arb(0)
            for c, j in self.linear[i]:
                s += c * y[j]
            for c, j, k in self.quadratic[i]:
                s += c * y[j] * y[k]
            out.append(s)
        return out

    def reversed(self) -> QuadraticField:
        """The field ``-f`` (the flow backward in time)."""
        return QuadraticField(tuple(tuple((-c, j) for c, j in comp) for comp in self.linear),
                              tuple(tuple((-c, j, k) for c, j, k in comp)
                                    for comp in self.quadratic), self.bits)

    def jacobian(self, y: Vector, linear: bool = True) -> arb_mat:
        """``Df(y)`` as an Arb matrix (without its constant linear part if not ``linear``:
        the Taylor coefficients of ``Df(y(t))`` beyond order 0)."""
        n = self.n
        rows = [[arb(0)] * n for _ in range(n)]
        for i in range(n):
            for c, j in self.linear[i] if linear else ():
                rows[i][j] += c
            for c, j, k in self.quadratic[i]:
                rows[i][j] += c * y[k]
                rows[i][k] += c * y[j]
        return arb_mat(rows)


def quadratic_field(body: Any, bits: int = 128) -> QuadraticField:
    """The field (1) of ``body`` with its coefficients enclosed at ``bits``.

    Parameters
    ----------
    body : RigidBody or BodySpec
        A float body (its parameters are read as the exact binary numbers they are) or
        an exact :class:`~andoyer.integrate.validated.arithmetic.BodySpec` (decimals).
    bits : int, default 128
        Working precision.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> f = quadratic_field(RigidBody.paper())
    >>> f.n, sum(len(q) for q in f.quadratic)
    (6, 9)
    """
    with working_precision(bits):
        if isinstance(body, BodySpec):
            params = body.balls(bits).params()
        else:
            a, b, c, mu, e1, e2, e3 = body.params
            params = (1 / arb(body.A), 1 / arb(body.B), 1 / arb(body.C), arb(mu),
                      arb(e1), arb(e2), arb(e3))
        values = dict(zip(body_symbols(), params, strict=True))
        lin: list[tuple[tuple[arb, int], ...]] = []
        quad: list[tuple[tuple[arb, int, int], ...]] = []
        for comp in field_terms().terms:
            li, qi = [], []
            for coef, idx in comp:
                cval = arb(evaluate(coef, values))
                if len(idx) == 0:
                    raise ValueError("the field (1) has no constant term")
                if len(idx) == 1:
                    li.append((cval, idx[0]))
                else:
                    qi.append((cval, idx[0], idx[1]))
            lin.append(tuple(li))
            quad.append(tuple(qi))
    return QuadraticField(tuple(lin), tuple(quad), bits)


def _cauchy(a: list[Any], b: list[Any], k: int) -> Any:
    s: Any = arb(0)
    for m in range(k + 1):
        s += a[m] * b[k - m]
    return s


def taylor_jets(f: QuadraticField, y0: Vector, order: int) -> list[Vector]:
    """The Taylor coefficients up to ``order`` (per component) of the solution from ``y0``.

    Parameters
    ----------
    f : QuadraticField
        The field.
    y0 : list of arb
        The initial value (balls: the coefficients enclose those of every solution from
        a point of the box).
    order : int
        The highest coefficient.

    Returns
    -------
    list of list of arb
        ``Y[i][k]``.
    """
    n = f.n
    Y = [[y0[i]] for i in range(n)]
    for k in range(order):
        new = []
        for i in range(n):
            s: Any = arb(0)
            for c, j in f.linear[i]:
                s += c * Y[j][k]
            for c, j, l_ in f.quadratic[i]:
                s += c * _cauchy(Y[j], Y[l_], k)
            new.append(s / (k + 1))
        for i in range(n):
            Y[i].append(new[i])
    return Y


def variational_jets(f: QuadraticField, y0: Vector, V0: list[Vector], order: int
                     ) -> tuple[list[Vector], list[list[list[Any]]]]:
    """Taylor coefficients of ``(y, V)`` with ``V' = Df(y) V``: ``(Y[i][k], W[i][c][k])``.

    Parameters
    ----------
    f : QuadraticField
        The field.
    y0 : list of arb
        Initial state (a box).
    V0 : list of list of arb
        Initial matrix (rows), e.g. the identity.
    order : int
        The highest coefficient.
    """
    n = f.n
    Y = taylor_jets(f, y0, order)
    ncol = len(V0[0])
    # V' = Df(y(t)) V with Df(y(t)) = sum_m A_m t^m: V_{k+1} = sum_{m <= k} A_m V_{k-m} / (k+1),
    # each term one Arb matrix product in C (FLINT's dot products), not Python's loops.
    A = [f.jacobian([Y[i][m] for i in range(n)], linear=m == 0) for m in range(order)]
    V = [arb_mat(V0)]
    for k in range(order):
        s = A[0] * V[k]
        for m in range(1, k + 1):
            s += A[m] * V[k - m]
        V.append(s / (k + 1))
    W = [[[V[k][i, c] for k in range(order + 1)] for c in range(ncol)] for i in range(n)]
    return Y, W


def _horner(coeffs: list[Any], h: Any) -> Any:
    s = coeffs[-1]
    for c in reversed(coeffs[:-1]):
        s = s * h + c
    return s


def _inflate(x: arb, factor: float, floor: Any) -> arb:
    return arb(x.mid(), x.rad() * factor + floor)


def _picard(f: QuadraticField, X: Vector, h: arb, tries: int = 30) -> Vector | None:
    """A box ``B`` with ``X + [0, h] f(B) ⊂ B`` (returns ``X + [0, h] f(B)``), or None."""
    H = arb(h / 2, h / 2)
    fX = f(X)
    B = [_inflate(X[i] + H * fX[i], 2.0, abs(fX[i]).upper() * h * arb("0.1") + 2**-100
                  * (abs(X[i]).upper() + 1)) for i in range(f.n)]
    for _ in range(tries):
        fB = f(B)
        NB = [X[i] + H * fB[i] for i in range(f.n)]
        if all(B[i].contains(NB[i]) for i in range(f.n)):
            return NB
        B = [_inflate(NB[i].union(B[i]), 1.5, 2**-60 * (abs(X[i]).upper() + 1))
             for i in range(f.n)]
    return None


def _picard_matrix(f: QuadraticField, By: Vector, h: arb, tries: int = 30
                   ) -> list[Vector] | None:
    """A box ``B_V`` with ``I + [0, h] Df(B) B_V ⊂ B_V`` for ``V' = Df(y) V``, or None."""
    n = f.n
    H = arb(h / 2, h / 2)
    D = f.jacobian(By)
    eye = arb_mat([[arb(1) if i == j else arb(0) for j in range(n)] for i in range(n)])
    BV = eye + D * H
    BV = arb_mat([[_inflate(BV[i, j], 2.0, 2**-100) for j in range(n)] for i in range(n)])
    for _ in range(tries):
        NV = eye + (D * BV) * H
        if all(BV[i, j].contains(NV[i, j]) for i in range(n) for j in range(n)):
            return [[NV[i, j] for j in range(n)] for i in range(n)]
        BV = arb_mat([[_inflate(NV[i, j].union(BV[i, j]), 1.5, 2**-60) for j in range(n)]
                      for i in range(n)])
    return None


@dataclass
class _Step:
    """What one validated step produced."""

    h: arb
    By: Vector          # a priori enclosure of every solution on [0, h]
    BV: list[Vector]
    Ym: list[Vector]    # jets from the point m
    YX: list[Vector]    # jets from the set's hull
    WX: list[list[list[Any]]]
    Rem: list[Vector]   # order-p jets from (By, BV): the remainders' coefficients
    WRem: list[list[list[Any]]]


def _step(f: QuadraticField, m: Vector, hull: Vector, h: float, order: int) -> _Step | None:
    hb = arb(h)
    By = _picard(f, hull, hb)
    if By is None:
        return None
    BV = _picard_matrix(f, By, hb)
    if BV is None:
        return None
    n = f.n
    eye = [[arb(1) if i == j else arb(0) for j in range(n)] for i in range(n)]
    Ym = taylor_jets(f, m, order - 1)
    YX, WX = variational_jets(f, hull, eye, order - 1)
    Rem, WRem = variational_jets(f, By, BV, order)
    return _Step(hb, By, BV, Ym, YX, WX, Rem, WRem)


def _value(step: _Step, jets: list[Vector], tau: Any, order: int) -> Vector:
    """``sum_{k<p} jets_k tau^k + rem_p tau^p`` for ``tau`` in ``[0, h]`` (a ball)."""
    return [_horner(jets[i], tau) + step.Rem[i][order] * tau**order
            for i in range(len(jets))]


def _derivative(step: _Step, tau: Any, order: int) -> arb_mat:
    n = len(step.YX)
    return arb_mat([[_horner(step.WX[i][c], tau) + step.WRem[i][c][order] * tau**order
                     for c in range(n)] for i in range(n)])


def _step_size(f: QuadraticField, m: Vector, order: int, h_max: float, tol: float) -> float:
    """Jorba-Zou's step from the point jets: ``rho tol^{1/p}``, ``rho = (|y|/|y_k|)^{1/k}``
    at the last two orders (the remainder then about ``tol`` relative)."""
    Y = taylor_jets(f, m, order)
    scale = max(max(abs(float(Y[i][0].mid())) for i in range(f.n)), 1e-300)
    rho = math.inf
    for k in (order - 1, order):
        nk = max(abs(float(Y[i][k].mid())) for i in range(f.n))
        if nk > 0.0:
            rho = min(rho, (scale / nk) ** (1.0 / k))
    return min(h_max, rho * tol ** (1.0 / order) if math.isfinite(rho) else h_max)


#: Steps are multiples of 2**-QUANTUM, so that step times add up exactly in floats.
QUANTUM = 30


def _exact_step(h: float, t: float, t_end: float) -> float:
    """A step ``<= h`` with ``t + step`` exact in binary floating point: ``t_end - t`` if that
    is at most ``h`` and exact, else ``h`` rounded down to a multiple of ``2**-QUANTUM``
    (``t`` is one, and sums of such numbers below ``2**22`` are exact)."""
    from fractions import Fraction

    last = t_end - t
    if last <= h and Fraction(t) + Fraction(last) == Fraction(t_end):
        return last
    q = math.floor(min(h, last) * 2.0**QUANTUM) / 2.0**QUANTUM
    if q <= 0.0:
        raise ArithmeticError(f"the step at t = {t} fell below 2**-{QUANTUM}")
    return q


def _qr_frame(A: arb_mat, r: Vector) -> tuple[arb_mat, arb_mat]:
    """Lohner's frame: ``Q`` of ``mid(A)`` (columns by length x width of ``r``), ``Q^-1``."""
    n = A.nrows()
    M = np.array([[float(A[i, j].mid()) for j in range(n)] for i in range(n)])
    widths = np.array([float(x.rad()) + 1e-300 for x in r])
    order = np.argsort(-np.linalg.norm(M * widths, axis=0))
    Q, _ = np.linalg.qr(M[:, order])
    Qb = arb_mat([[arb(float(Q[i, j])) for j in range(n)] for i in range(n)])
    return Qb, Qb.inv()


def _lohner_matrix(J: arb_mat, Dm: arb_mat, Dd: arb_mat, QinvA: arb_mat, Qinv: arb_mat
                   ) -> tuple[arb_mat, arb_mat]:
    """The derivative ``D = Dm + Q Dd`` carried in the set's Lohner frame: ``J D =
    Dm' + Q' Dd'`` with ``Dm' = mid(J Dm)``, ``Dd' = (Q'^-1 J Q) Dd + Q'^-1 (J Dm - Dm')``."""
    JD = J * Dm
    n = J.nrows()
    Dm_new = arb_mat([[arb(JD[i, j].mid()) for j in range(n)] for i in range(n)])
    return Dm_new, QinvA * Dd + Qinv * (JD - Dm_new)


def _vec(M: arb_mat, v: Vector) -> Vector:
    n = M.nrows()
    return [sum((M[i, j] * v[j] for j in range(M.ncols())), arb(0)) for i in range(n)]


@dataclass(frozen=True)
class ValidatedOrbit:
    """Enclosures of the flow of (1) and of its derivative at the step times.

    Attributes
    ----------
    times : tuple of float
        Step times, ``times[0] = 0`` (exact: each the exact sum of the steps taken,
        multiples of ``2**-QUANTUM`` but for the last).
    states : tuple of tuple of str
        The hull of the enclosure of the set at each time (six balls).
    mid, rad : numpy.ndarray, shape (k, 6)
        The balls' midpoints and radii.
    derivative_rad : numpy.ndarray, shape (k,)
        The largest radius of the derivative's enclosure (6 x 6) at each time.
    derivative : tuple of str
        The enclosure of the derivative of the flow at the last time (36 balls, rows).
    steps : int
        Steps taken.
    order : int
        Taylor order.
    bits : int
        Working precision.
    seconds : float
        Run time.
    flint_version : str
        python-flint's version.
    """

    times: tuple[float, ...]
    states: tuple[tuple[str, ...], ...]
    mid: np.ndarray
    rad: np.ndarray
    derivative_rad: np.ndarray
    derivative: tuple[str, ...]
    steps: int
    order: int
    bits: int
    seconds: float
    flint_version: str = field(default=FLINT_VERSION)

    def contains(self, k: int, y: Sequence[float], slack: float = 0.0) -> bool:
        """Whether the enclosure at ``times[k]`` (widened by ``slack``) holds ``y``.

        Parameters
        ----------
        k : int
            The time's index.
        y : sequence of 6 floats
            A state.
        slack : float, default 0
            Added to every radius (e.g. a float engine's own error).
        """
        return bool(np.all(np.abs(np.asarray(y, dtype=float) - self.mid[k])
                           <= self.rad[k] + slack))

    def to_dataset(self) -> Any:
        """An :class:`xarray.Dataset` (time, component): midpoints, radii, balls."""
        import xarray as xr

        from andoyer.charts.euler_poisson import STATE

        ds = xr.Dataset(
            {"y_mid": (("time", "component"), self.mid),
             "y_rad": (("time", "component"), self.rad),
             "y_ball": (("time", "component"), np.array(self.states, dtype=str)),
             "derivative_rad": (("time",), self.derivative_rad)},
            coords={"time": np.array(self.times), "component": list(STATE)},
            attrs={"order": self.order, "bits": self.bits, "steps": self.steps,
                   "seconds": self.seconds, "flint_version": self.flint_version,
                   "engine": "validated Taylor (Arb balls, Lohner QR)",
                   "equations": "(1) and its variational equations"})
        ds["y_mid"].attrs.update(long_name="midpoint of the enclosure", equation="(1)")
        ds["y_rad"].attrs.update(long_name="radius of the enclosure (hull of the set)")
        ds["derivative_rad"].attrs.update(long_name="largest radius of the enclosure of "
                                          "the flow's derivative")
        return ds


def _initial(y0: Sequence[Any], radius: float | Sequence[float]) -> tuple[Vector, Vector]:
    if len(y0) != 6:
        raise ValueError(f"y0 must hold the 6 Euler-Poisson components, got {len(y0)}")
    if isinstance(radius, int | float):
        rads = [float(radius)] * 6
    else:
        rads = [float(r) for r in radius]
    if len(rads) != 6 or not all(math.isfinite(r) and r >= 0.0 for r in rads):
        raise ValueError("radius must be one or six finite numbers >= 0")
    m = []
    for v in y0:
        x = v if isinstance(v, arb) else arb(str(v)) if isinstance(v, str) else arb(float(v))
        if not x.is_finite():
            raise ValueError(f"y0 must be finite, got {v!r}")
        m.append(x)
    r = [arb(0, rr) if rr > 0.0 else arb(0) for rr in rads]
    return m, r


def validated_flow(body: Any, y0: Sequence[Any], t_end: float, *,
                   radius: float | Sequence[float] = 0.0, order: int = 30,
                   bits: int = 128, h_max: float = 1.0, tol: float = 1e-30,
                   max_steps: int = 10_000, backward: bool = False) -> ValidatedOrbit:
    """Enclose the flow of (1) from the box ``y0 +- radius`` up to ``t_end``.

    Parameters
    ----------
    body : RigidBody or BodySpec
        The body (a float body's parameters are taken as the exact binaries they are).
    y0 : sequence of 6 numbers or strings
        The centre of the initial box (strings are read as decimals).
    t_end : float
        The end time (> 0).
    radius : float or sequence of 6 floats, default 0
        The initial box's radii.
    order : int, default 30
        Taylor order.
    bits : int, default 128
        Working precision.
    h_max : float, default 1.0
        The largest step.
    tol : float, default 1e-30
        The remainder aimed at per step, relative to the state (sets the step size).
    max_steps : int, default 10000
        Refuse to take more steps.
    backward : bool, default False
        Integrate backward in time (the field ``-f``) to ``-t_end``; ``times`` are then
        ``<= 0``.

    Returns
    -------
    ValidatedOrbit

    Raises
    ------
    ArithmeticError
        When no a priori enclosure is found even at tiny steps (the enclosure blew up).

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> orb = validated_flow(RigidBody.paper(), [0.3, 0.8, 0.2, 0.6, 0.0, 0.8], 2.0)
    >>> bool(orb.rad[-1].max() < 1e-25), orb.times[-1]
    (True, 2.0)
    """
    start = time.perf_counter()
    t_end = float(t_end)
    if not (math.isfinite(t_end) and 0.0 < t_end <= 1e6):
        raise ValueError(f"t_end must be a time in (0, 1e6], got {t_end!r}")
    if isinstance(order, bool) or not isinstance(order, int) or not 4 <= order <= 60:
        raise ValueError(f"order must be an integer in [4, 60], got {order!r}")
    with working_precision(bits):
        f = quadratic_field(body, bits)
        if backward:
            f = f.reversed()
        m, r = _initial(y0, radius)
        n = 6
        Q = arb_mat([[arb(1) if i == j else arb(0) for j in range(n)] for i in range(n)])
        Dm, Dd = Q, arb_mat(n, n)
        t = 0.0
        times, states, mids, rads, drads = [0.0], [], [], [], [0.0]
        hull = [m[i] + r[i] for i in range(n)]
        states.append(tuple(ball_text(x, 32) for x in hull))
        mids.append([float(x.mid()) for x in hull])
        rads.append([float(x.rad()) for x in hull])
        steps = 0
        while t < t_end:
            if steps >= max_steps:
                raise ArithmeticError(f"max_steps={max_steps} reached at t = {t}")
            h = _exact_step(_step_size(f, m, order, h_max, tol), t, t_end)
            st = None
            for _ in range(12):
                st = _step(f, m, hull, h, order)
                if st is not None:
                    break
                h = max(math.floor(h / 2 * 2.0**QUANTUM), 1) / 2.0**QUANTUM
            if st is None:
                raise ArithmeticError(f"no a priori enclosure at t = {t} (the enclosure "
                                      f"blew up: widths {max(float(x.rad()) for x in hull)})")
            z = _value(st, st.Ym, st.h, order)
            J = _derivative(st, st.h, order)
            A = J * Q
            m_new = [arb(x.mid()) for x in z]
            Qn, Qinv = _qr_frame(A, r)
            r = [a + b for a, b in zip(_vec(Qinv * A, r),
                                        _vec(Qinv, [z[i] - m_new[i] for i in range(n)]),
                                        strict=True)]
            Dm, Dd = _lohner_matrix(J, Dm, Dd, Qinv * A, Qinv)
            m, Q = m_new, Qn
            hull_l = _vec(Q, r)
            hull = [m[i] + hull_l[i] for i in range(n)]
            D = Dm + Q * Dd
            t = t + h
            steps += 1
            times.append(t)
            states.append(tuple(ball_text(x, 32) for x in hull))
            mids.append([float(x.mid()) for x in hull])
            rads.append([float(x.rad()) for x in hull])
            drads.append(max(float(D[i, j].rad()) for i in range(n) for j in range(n)))
        D = Dm + Q * Dd
        deriv = tuple(ball_text(D[i, j], 20) for i in range(n) for j in range(n))
    if backward:
        times = [-x for x in times]
    return ValidatedOrbit(times=tuple(times), states=tuple(states), mid=np.array(mids),
                          rad=np.array(rads), derivative_rad=np.array(drads),
                          derivative=deriv, steps=steps, order=order, bits=bits,
                          seconds=time.perf_counter() - start)


@dataclass(frozen=True)
class PoincareCrossing:
    """A certified crossing of the set through the section ``(w, y) = c``.

    Attributes
    ----------
    time : str
        The enclosure of the crossing times of every point of the set (a ball).
    time_point : str
        The crossing time of the box's centre trajectory (a tight ball).
    image : tuple of str
        The enclosure of the Poincaré image of the set (six balls, mean value form).
    image_mid, image_rad : numpy.ndarray, shape (6,)
        Its midpoints and radii.
    derivative : tuple of str
        The enclosure of the Poincaré map's derivative over the set (36 balls, rows).
    derivative_mid : numpy.ndarray, shape (6, 6)
        Its midpoints.
    seconds : float
        Run time.
    """

    time: str
    time_point: str
    image: tuple[str, ...]
    image_mid: np.ndarray
    image_rad: np.ndarray
    derivative: tuple[str, ...]
    derivative_mid: np.ndarray
    seconds: float


def _newton_time(sig: Any, dsig: Any, lo: arb, hi: arb, tries: int = 60) -> arb | None:
    """Interval Newton ``T <- T ∩ (t_m - sig(t_m) / dsig(T))`` on ``[lo, hi]``, which holds
    exactly one root (a sign change with ``dsig`` bounded away from 0); None if empty."""
    T = lo.union(hi)
    for _ in range(tries):
        d = dsig(T)
        if d.contains(0):
            return None
        tm = arb(T.mid())
        N = tm - sig(tm) / d
        newlo, newhi = max(N.lower(), T.lower()), min(N.upper(), T.upper())
        if newlo > newhi:
            return None
        T_new = arb(newlo).union(arb(newhi))
        if not T_new.rad() < T.rad() * 0.9:
            return T_new
        T = T_new
    return T


def validated_poincare(body: Any, y0: Sequence[Any], weights: Sequence[float], value: float,
                       *, radius: float | Sequence[float] = 0.0, direction: int = 1,
                       order: int = 30, bits: int = 128, h_max: float = 1.0,
                       tol: float = 1e-30, t_max: float = 1000.0, skip: float = 0.0,
                       backward: bool = False, frame: Sequence[Sequence[Any]] | None = None,
                       coords: Sequence[Any] | None = None) -> PoincareCrossing:
    """The certified first crossing of the set ``y0 +- radius`` through ``(w, y) = c``.

    Parameters
    ----------
    body : RigidBody or BodySpec
        The body.
    y0 : sequence of 6 numbers
        The centre of the initial box.
    weights : sequence of 6 floats
        ``w`` of the linear section (``(0, 0, 1, 0, 0, 0)``: ``G3 = L = 0``).
    value : float
        ``c``.
    radius : float or sequence of 6 floats, default 0
        The initial box's radii.
    direction : {+1, -1}, default 1
        Crossings with ``(w, f) > 0`` (+1) or ``< 0`` (-1).
    order, bits, h_max, tol
        As in :func:`validated_flow`.
    t_max : float, default 1000
        Give up after this time.
    skip : float, default 0
        Ignore crossings before this time.
    backward : bool, default False
        Follow the flow backward in time (``time`` is then the elapsed time ``> 0`` of the
        backward flow; ``direction`` refers to the backward motion).
    frame, coords : optional
        A parallelepiped instead of the box: the set ``y0 + frame @ coords`` with
        ``frame`` a ``6 x 6`` matrix of numbers or balls (rows) and ``coords`` six balls
        (Lohner's representation from the start: a long side along one column is
        carried by the variational matrix, not wrapped). ``radius`` must then be 0.

    Returns
    -------
    PoincareCrossing

    Raises
    ------
    ArithmeticError
        If no crossing is certified before ``t_max`` (the crossing time could not be
        enclosed: ``(w, f)`` not bounded away from 0 on the step).

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> c = validated_poincare(RigidBody.paper(), [0.3, 0.8, 0.2, 0.6, 0.0, 0.8],
    ...                        [0, 0, 1, 0, 0, 0], 0.0, direction=-1)
    >>> abs(float(arb(c.image[2]).mid())) < 1e-20
    True
    """
    start = time.perf_counter()
    if direction not in (1, -1):
        raise ValueError(f"direction must be +1 or -1, got {direction!r}")
    if not (math.isfinite(t_max) and 0.0 < t_max <= 1e6):
        raise ValueError(f"t_max must be a time in (0, 1e6], got {t_max!r}")
    if len(weights) != 6:
        raise ValueError("weights must hold 6 numbers")
    with working_precision(bits):
        f = quadratic_field(body, bits)
        if backward:
            f = f.reversed()
        w = [arb(float(x)) for x in weights]
        c = arb(float(value))
        m, r = _initial(y0, radius)
        n = 6
        Q = arb_mat([[arb(1) if i == j else arb(0) for j in range(n)] for i in range(n)])
        Dm, Dd = Q, arb_mat(n, n)
        if frame is not None or coords is not None:
            Q, r = _frame(frame, coords, radius)
            m, r = _absorb(m, Q, r)
            Dm, Dd = arb_mat([[arb(1) if i == j else arb(0) for j in range(n)]
                              for i in range(n)]), arb_mat(n, n)
        t = 0.0
        hull = [m[i] + x for i, x in enumerate(_vec(Q, r))]

        def s_of(y: Vector) -> Any:
            return sum((w[i] * y[i] for i in range(n)), arb(0)) - c

        while t < t_max:
            h = _exact_step(_step_size(f, m, order, h_max, tol), t, t_max)
            st = None
            for _ in range(12):
                st = _step(f, m, hull, h, order)
                if st is not None:
                    break
                h = max(math.floor(h / 2 * 2.0**QUANTUM), 1) / 2.0**QUANTUM
            if st is None:
                raise ArithmeticError(f"no a priori enclosure at t = {t}")
            sB = s_of(st.By)
            if t >= skip and sB.contains(0):
                dB = s_of(f(st.By))
                if not dB.contains(0) and (float(dB.mid()) > 0) == (direction > 0):
                    hit = _locate(st, f, s_of, dB, order, m, Q, r, Dm + Q * Dd)
                    if hit is not None:
                        Tset, Tm, image, DP = hit
                        return PoincareCrossing(
                            time=ball_text(Tset + t), time_point=ball_text(Tm + t),
                            image=tuple(ball_text(x) for x in image),
                            image_mid=np.array([float(x.mid()) for x in image]),
                            image_rad=np.array([float(x.rad()) for x in image]),
                            derivative=tuple(ball_text(DP[i, j], 20) for i in range(n)
                                             for j in range(n)),
                            derivative_mid=np.array([[float(DP[i, j].mid())
                                                      for j in range(n)] for i in range(n)]),
                            seconds=time.perf_counter() - start)
            z = _value(st, st.Ym, st.h, order)
            J = _derivative(st, st.h, order)
            A = J * Q
            m_new = [arb(x.mid()) for x in z]
            Qn, Qinv = _qr_frame(A, r)
            r = [a + b for a, b in zip(_vec(Qinv * A, r),
                                        _vec(Qinv, [z[i] - m_new[i] for i in range(n)]),
                                        strict=True)]
            Dm, Dd = _lohner_matrix(J, Dm, Dd, Qinv * A, Qinv)
            m, Q = m_new, Qn
            hull_l = _vec(Q, r)
            hull = [m[i] + hull_l[i] for i in range(n)]
            t += h
    raise ArithmeticError(f"no certified crossing of the section before t_max = {t_max}")


def _frame(frame: Any, coords: Any, radius: Any) -> tuple[arb_mat, Vector]:
    """The initial Lohner frame ``Q`` and coordinates ``r`` of ``y0 + Q r``."""
    if frame is None or coords is None:
        raise ValueError("frame and coords go together")
    if not (isinstance(radius, int | float) and radius == 0.0):
        raise ValueError("radius must be 0 when frame and coords give the set")
    rows = [list(row) for row in frame]
    if len(rows) != 6 or any(len(row) != 6 for row in rows):
        raise ValueError("frame must be a 6 x 6 matrix (invertible)")
    Q = arb_mat([[x if isinstance(x, arb) else arb(x) for x in row] for row in rows])
    r = [x if isinstance(x, arb) else arb(x) for x in coords]
    if len(r) != 6 or not all(x.is_finite() for x in r):
        raise ValueError("coords must be six finite balls")
    return Q, r


def _absorb(m: Vector, Q: arb_mat, r: Vector) -> tuple[Vector, Vector]:
    """Make ``Q`` a point matrix and ``m`` a point: ``m + Q r = m' + Q' r'`` as sets
    (``Q``'s and ``m``'s radii move into ``r`` through ``Q'^-1``)."""
    n = len(m)
    Qm = arb_mat([[arb(Q[i, j].mid()) for j in range(n)] for i in range(n)])
    exact = all(Q[i, j].rad() == 0 for i in range(n) for j in range(n))
    mm = [arb(x.mid()) for x in m]
    if exact and all(x.rad() == 0 for x in m):
        return mm, r
    Qinv = Qm.inv()
    extra = [(m[i] - mm[i]) + sum(((Q[i, j] - Qm[i, j]) * r[j] for j in range(n)), arb(0))
             for i in range(n)]
    return mm, [a + b for a, b in zip(r, _vec(Qinv, extra), strict=True)]


def _locate(st: _Step, f: QuadraticField, s_of: Any, dB: arb, order: int, m: Vector,
            Q: arb_mat, r: Vector, D: arb_mat) -> tuple[Any, ...] | None:
    """Crossing times (point and set), image (mean value form) and derivative of the map."""
    zero, h = arb(0), st.h
    n = f.n

    def sig_point(tau: arb) -> arb:
        return s_of(_value(st, st.Ym, tau, order))

    def sig_set(tau: arb) -> arb:
        return s_of(_value(st, st.YX, tau, order))

    def dsig(_T: arb) -> arb:
        return dB

    s0, s1 = sig_set(zero), sig_set(h)
    if s0.contains(0) or s1.contains(0) or (s0 > 0) == (s1 > 0):
        return None  # the whole set does not cross inside this step
    Tm = _newton_time(sig_point, dsig, zero, h)
    Tset = _newton_time(sig_set, dsig, zero, h)
    if Tm is None or Tset is None:
        return None
    # the point's image, the map's derivative over the set, the mean value form
    Pm = _value(st, st.Ym, Tm, order)
    Y = _value(st, st.YX, Tset, order)
    fY = f(Y)
    grad = [s_of([arb(1) if j == i else arb(0) for j in range(n)]) - s_of([zero] * n)
            for i in range(n)]
    denom = sum((grad[i] * fY[i] for i in range(n)), arb(0))
    proj = arb_mat([[(arb(1) if i == j else arb(0)) - fY[i] * grad[j] / denom
                     for j in range(n)] for i in range(n)])
    Jt = _derivative(st, Tset, order)
    DP = proj * Jt * D
    local = _vec(proj * Jt * Q, r)
    image = [Pm[i] + local[i] for i in range(n)]
    # intersect with the crude hull (both enclose the image)
    out = []
    for a, b in zip(image, Y, strict=True):
        lo, hi = max(a.lower(), b.lower()), min(a.upper(), b.upper())
        out.append(arb(lo).union(arb(hi)) if lo <= hi else a)
    return Tset, Tm, out, DP
