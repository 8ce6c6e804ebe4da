r"""Jet transport: the section map of (1) as a polynomial in the section's coordinates.

A *jet* is a truncated polynomial in two variables ``(u, v)`` of total degree ``<= N``
(:class:`JetBasis`: the monomials ``u^i v^j``, ``i + j <= N``, and their products). The
Euler-Poisson field (1) is quadratic in the state (:func:`~andoyer.integrate.validated.
arithmetic.field_terms`, derived by SymPy from the one Hamiltonian), so the flow of a
state whose six components are jets needs nothing but products of jets: an explicit
Runge-Kutta step on jets is the same step on the variational equations of every order
``<= N`` at once (the truncation commutes with the arithmetic). On the section
``g = g*`` of the level ``H = h`` with area constant ``M`` the plane coordinates
``(l, L)`` are canonical (the reduced map (R2) of
:mod:`andoyer.analysis.resonance.predict` preserves ``dl ^ dL``), and the map is built in
four jet steps:

- (J1) the initial state: ``l = l0 + u``, ``L = L0 + v``, ``G`` solving ``H = h`` (chord
  iterations on jets, each exact to one degree more), the state by the chart map
  :func:`~andoyer.charts.andoyer_deprit.andoyer_to_ep_expr` evaluated on jets;
- (J2) the flow to the base orbit's ``n``-th crossing time ``T`` (crossings in the section's
  direction) by fixed steps of the 8th-order DOP853 formula on jets;
- (J3) the crossing time ``T + tau(u, v)``: ``tau`` solves ``f(phi_tau(y)) = 0`` for the
  section function ``f`` of :func:`andoyer.symbolic.sections.section_function` by chord
  iterations, each a Runge-Kutta step of jet length ``tau``;
- (J4) the image point ``(l, L) = (atan2(G1, G2), G3)`` as jets.

The error of the coefficients is estimated by repeating (J2)-(J4) with twice the steps
(8th order: the finer result is ``~2^8`` times closer than their difference).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from functools import cache
from typing import Any

import numpy as np
from numpy.typing import NDArray

from andoyer.kernels.dop853.coefficients import N_STAGES
from andoyer.kernels.dop853.coefficients import A as RK_A
from andoyer.kernels.dop853.coefficients import B as RK_B

__all__ = ["JetBasis", "Jet", "SectionJet", "section_map_jet", "MAX_DEGREE"]

#: Highest degree of the jets (the number of monomials grows like ``N^2 / 2``).
MAX_DEGREE = 15


class JetBasis:
    """The monomials ``u^i v^j`` (``i + j <= degree``) and the table of their products.

    Parameters
    ----------
    degree : int
        Total degree ``N`` of the truncation (0 to :data:`MAX_DEGREE`).
    """

    def __init__(self, degree: int) -> None:
        self.degree = int(degree)
        self.powers = [(i, d - i) for d in range(self.degree + 1) for i in range(d, -1, -1)]
        self.size = len(self.powers)
        index = {p: k for k, p in enumerate(self.powers)}
        self.index = index
        self.total = np.array([i + j for i, j in self.powers])
        pairs = [(a, b, index[(pa[0] + pb[0], pa[1] + pb[1])])
                 for a, pa in enumerate(self.powers) for b, pb in enumerate(self.powers)
                 if sum(pa) + sum(pb) <= self.degree]
        pairs.sort(key=lambda t: t[2])
        self._ia = np.array([p[0] for p in pairs])
        self._ib = np.array([p[1] for p in pairs])
        res = np.array([p[2] for p in pairs])
        self._starts = np.searchsorted(res, np.arange(self.size))

    def mul(self, x: NDArray[Any], y: NDArray[Any]) -> NDArray[Any]:
        """Product of jets (coefficient arrays ``(..., size)``, broadcast)."""
        prod = x[..., self._ia] * y[..., self._ib]
        return np.add.reduceat(prod, self._starts, axis=-1)

    def constant(self, value: Any, dtype: Any = float) -> NDArray[Any]:
        """The jet of a number."""
        c = np.zeros(self.size, dtype=dtype)
        c[0] = value
        return c

    def variable(self, k: int, value: float = 0.0) -> NDArray[np.float64]:
        """The jet ``value + u`` (``k = 0``) or ``value + v`` (``k = 1``)."""
        c = self.constant(value)
        c[1 + k] = 1.0
        return c

    def evaluate(self, c: NDArray[Any], u: Any, v: Any) -> Any:
        """The polynomial ``c`` at ``(u, v)`` (arrays broadcast)."""
        u, v = np.asarray(u), np.asarray(v)
        out = np.zeros(np.broadcast(u, v).shape, dtype=np.result_type(c, u, v))
        for k, (i, j) in enumerate(self.powers):
            out = out + c[..., k] * u**i * v**j if c.ndim > 1 else out + c[k] * u**i * v**j
        return out


@dataclass
class Jet:
    """A jet of :class:`JetBasis` with the arithmetic the chart maps and ``H`` use.

    Parameters
    ----------
    c : ndarray, shape (size,)
        Coefficients of the monomials of ``basis``.
    basis : JetBasis
        The truncation.
    """

    c: NDArray[Any]
    basis: JetBasis

    def _other(self, x: Any) -> NDArray[Any]:
        return x.c if isinstance(x, Jet) else self.basis.constant(x, np.result_type(x, float))

    def __add__(self, x: Any) -> Jet:
        return Jet(self.c + self._other(x), self.basis)

    __radd__ = __add__

    def __sub__(self, x: Any) -> Jet:
        return Jet(self.c - self._other(x), self.basis)

    def __rsub__(self, x: Any) -> Jet:
        return Jet(self._other(x) - self.c, self.basis)

    def __neg__(self) -> Jet:
        return Jet(-self.c, self.basis)

    def __mul__(self, x: Any) -> Jet:
        if isinstance(x, Jet):
            return Jet(self.basis.mul(self.c, x.c), self.basis)
        return Jet(self.c * x, self.basis)

    __rmul__ = __mul__

    def __truediv__(self, x: Any) -> Jet:
        if isinstance(x, Jet):
            return self * reciprocal(x)
        return Jet(self.c / x, self.basis)

    def __rtruediv__(self, x: Any) -> Jet:
        return reciprocal(self) * x

    def __pow__(self, n: int) -> Jet:
        if not (isinstance(n, int | np.integer) and n >= 0):
            raise ValueError(f"a jet takes whole powers >= 0, got {n!r}")
        out = Jet(self.basis.constant(1.0, self.c.dtype), self.basis)
        for _ in range(int(n)):
            out = out * self
        return out

    @property
    def value(self) -> Any:
        """The constant term."""
        return self.c[0]


def _series(x: Jet, coeffs: Sequence[float]) -> Jet:
    """``sum_k coeffs[k] (x - x0)^k`` (``x0`` the constant term of ``x``)."""
    basis = x.basis
    d = x.c.copy()
    d[0] = 0.0
    out = basis.constant(coeffs[0], x.c.dtype) if coeffs else basis.constant(0.0)
    power = basis.constant(1.0, x.c.dtype)
    for k in range(1, min(len(coeffs), basis.degree + 1)):
        power = basis.mul(power, d)
        out = out + coeffs[k] * power
    return Jet(out, basis)


def reciprocal(x: Jet) -> Jet:
    """``1 / x`` (``x`` with a non-zero constant term)."""
    x0 = x.value
    n = x.basis.degree
    return _series(x, [(-1.0) ** k / x0 ** (k + 1) for k in range(n + 1)])


def jet_sqrt(x: Any) -> Any:
    """``sqrt`` of a jet (positive constant term) or of a number."""
    if not isinstance(x, Jet):
        return np.sqrt(x)
    x0 = float(x.value)
    coeffs, c = [], math.sqrt(x0)
    for k in range(x.basis.degree + 1):   # binomial series of (x0 + d)^(1/2)
        coeffs.append(c)
        c *= (0.5 - k) / ((k + 1) * x0)
    return _series(x, coeffs)


def jet_sin(x: Any) -> Any:
    """``sin`` of a jet or of a number."""
    if not isinstance(x, Jet):
        return np.sin(x)
    s, c = math.sin(float(x.value)), math.cos(float(x.value))
    return _series(x, [[s, c, -s, -c][k % 4] / math.factorial(k)
                       for k in range(x.basis.degree + 1)])


def jet_cos(x: Any) -> Any:
    """``cos`` of a jet or of a number."""
    if not isinstance(x, Jet):
        return np.cos(x)
    s, c = math.sin(float(x.value)), math.cos(float(x.value))
    return _series(x, [[c, -s, -c, s][k % 4] / math.factorial(k)
                       for k in range(x.basis.degree + 1)])


def jet_atan(x: Jet) -> Jet:
    """``atan`` of a jet with zero constant term."""
    return _series(x, [0.0 if k % 2 == 0 else (-1.0) ** (k // 2) / k
                       for k in range(x.basis.degree + 1)])


# ------------------------------------------------------------------------ the field
@cache
def _field_structure() -> tuple[tuple[tuple[Any, ...], ...], Any]:
    """The monomials of the field (1) and a function of the body's parameters that
    gives their coefficients."""
    import sympy as sp

    from andoyer.integrate.validated.arithmetic import body_symbols, field_terms

    terms = field_terms().terms
    flat = [(i, coef, idx) for i, comp in enumerate(terms) for coef, idx in comp]
    coefs = sp.lambdify(body_symbols(), [c for _i, c, _x in flat], "math")
    return tuple((i, idx) for i, _c, idx in flat), coefs


class _Field:
    """The field (1) of one body on jets: ``dy/dt = f(y)``, ``y`` of shape ``(6, size)``."""

    def __init__(self, body: Any, basis: JetBasis) -> None:
        structure, coefs = _field_structure()
        values = coefs(body.a, body.b, body.c, body.mu, *body.r)
        self.basis = basis
        self.const = np.zeros(6)
        lin, quad = [], []
        for (i, idx), cval in zip(structure, values, strict=True):
            if len(idx) == 0:
                self.const[i] += float(cval)
            elif len(idx) == 1:
                lin.append((i, idx[0], float(cval)))
            else:
                quad.append((i, idx[0], idx[1], float(cval)))
        self.lin = np.zeros((6, 6))
        for i, j, cval in lin:
            self.lin[i, j] += cval
        pairs = sorted({(j, k) for _i, j, k, _c in quad})
        self._pj = np.array([p[0] for p in pairs])
        self._pk = np.array([p[1] for p in pairs])
        self.quad = np.zeros((6, len(pairs)))
        for i, j, k, cval in quad:
            self.quad[i, pairs.index((j, k))] += cval

    def __call__(self, y: NDArray[Any]) -> NDArray[Any]:
        prods = self.basis.mul(y[self._pj], y[self._pk])
        out = self.lin @ y + self.quad @ prods
        out[:, 0] += self.const
        return np.asarray(out)

    def rk_step(self, y: NDArray[Any], h: Any) -> NDArray[Any]:
        """One DOP853 step (8th-order weights) of length ``h`` (a number or a jet)."""
        jet_h = isinstance(h, np.ndarray)

        def times(k: NDArray[Any]) -> NDArray[Any]:
            return self.basis.mul(h[None, :], k) if jet_h else h * k

        ks = [self(y)]
        for i in range(1, N_STAGES):
            acc = sum(RK_A[i, j] * ks[j] for j in range(i) if RK_A[i, j] != 0.0)
            ks.append(self(y + times(acc)))
        incr = sum(RK_B[i] * ks[i] for i in range(N_STAGES) if RK_B[i] != 0.0)
        return np.asarray(y + times(incr))


# --------------------------------------------------------------- the section map
@dataclass(frozen=True)
class SectionJet:
    """The section map ``(l0 + u, L0 + v) -> (l, L)`` as jets, with its error estimate.

    Parameters
    ----------
    basis : JetBasis
        The truncation.
    l, L : ndarray, shape (size,)
        Coefficients of the image point's ``l`` (its constant term the image of the base
        point, unwrapped to the nearest turn of ``l0``) and ``L``.
    error : ndarray, shape (degree + 1,)
        Per degree, the largest change of a coefficient of ``l`` or ``L`` between the
        steps ``n_steps / 2`` and ``n_steps`` (NaN without the estimate).
    n_steps : int
        Runge-Kutta steps of (J2).
    time : float
        The base orbit's crossing time ``T + tau(0)``.
    G : float
        ``|G|`` of the base point (the root of ``H = h`` the map starts on).
    """

    basis: JetBasis
    l: NDArray[np.float64]
    L: NDArray[np.float64]
    error: NDArray[np.float64]
    n_steps: int
    time: float
    G: float

    def matrix(self) -> NDArray[np.float64]:
        """The linear part ``d(l, L)/d(l0, L0)``."""
        return np.array([[self.l[1], self.l[2]], [self.L[1], self.L[2]]])


def _initial_state(body: Any, basis: JetBasis, h: float, M: float, g_star: float, l0: float,
                   L0: float, G0: float) -> NDArray[np.float64]:
    """(J1): the state jets of ``(l0 + u, g*, L0 + v, G(u, v), M)`` on ``H = h``."""
    from andoyer.charts.andoyer_deprit import andoyer_to_ep_expr
    from andoyer.charts.euler_poisson import hamiltonian_expr

    l = Jet(basis.variable(0, l0), basis)
    L = Jet(basis.variable(1, L0), basis)

    def state(G: Jet) -> list[Jet]:
        cols = andoyer_to_ep_expr(l, g_star, L, G, M, sin=jet_sin, cos=jet_cos,
                                  sqrt=jet_sqrt)
        return [c if isinstance(c, Jet) else Jet(basis.constant(c), basis) for c in cols]

    def energy(G: Jet) -> Jet:
        G1, G2, G3, g1, g2, g3 = state(G)
        e1, e2, e3 = body.r
        out = hamiltonian_expr(G1, G2, G3, g1, g2, g3, body.a, body.b, body.c, body.mu,
                               e1, e2, e3)
        return out if isinstance(out, Jet) else Jet(basis.constant(out), basis)

    eps = 1e-6 * G0
    slope = (energy(Jet(basis.constant(G0 + eps), basis)).value
             - energy(Jet(basis.constant(G0 - eps), basis)).value) / (2 * eps)
    G = Jet(basis.constant(G0), basis)
    for _ in range(basis.degree + 4):   # chord iterations: one degree (or more) each
        G = G - (energy(G) - h) / slope
    return np.array([y.c for y in state(G)])


@cache
def _section_function(coord: str) -> Callable[..., Any]:
    import sympy as sp

    from andoyer.symbolic.sections import SECTION_ARGS, section_function

    f, _w = section_function(coord)
    return sp.lambdify(SECTION_ARGS, f, [{"sqrt": jet_sqrt, "sin": jet_sin, "cos": jet_cos},
                                         "math"])


def _flow(field: _Field, y0: NDArray[np.float64], T: float, n_steps: int, coord: str,
          value: float, phi0: float) -> tuple[NDArray[np.float64], float]:
    """(J2)-(J3): the state jets at the crossing ``T + tau`` and ``T + tau(0)``."""
    basis = field.basis
    y = y0.copy()
    h = T / n_steps
    for _ in range(n_steps):
        y = field.rk_step(y, h)
    fn = _section_function(coord)
    cv, sv = math.cos(value), math.sin(value)

    def sec(state: NDArray[np.float64]) -> Jet:
        jets = [Jet(c, basis) for c in state]
        out = fn(*jets, phi0, value, cv, sv)
        return out if isinstance(out, Jet) else Jet(basis.constant(out), basis)

    base = np.zeros_like(y)
    base[:, 0] = y[:, 0]
    eps = 1e-7 * max(abs(T) / n_steps, 1e-300)
    slope = (sec(field.rk_step(base, eps)).value
             - sec(field.rk_step(base, -eps)).value) / (2 * eps)
    tau = basis.constant(0.0)
    for _ in range(basis.degree + 4):
        tau = tau - sec(field.rk_step(y, tau)).c / slope
    return field.rk_step(y, tau), T + float(tau[0])


def section_map_jet(body: Any, h: float, M: float, g_star: float, l0: float, L0: float,
                    G0: float, T: float, *, degree: int, n_steps: int, phi0: float = 0.0,
                    error_estimate: bool = True) -> SectionJet:
    """The section map of ``g = g*`` on ``H = h`` about ``(l0, L0)`` as jets of degree
    ``degree`` (J1)-(J4), with the error estimate of (J2) at half the steps.

    Parameters
    ----------
    body : RigidBody
        The heavy top.
    h, M : float
        The energy level and the area constant.
    g_star : float
        The section ``g = g*`` (crossings of either direction: ``T`` picks the crossing).
    l0, L0 : float
        The base point in the section plane.
    G0 : float
        ``|G|`` of the base point (a root of ``H = h`` above ``(l0, L0)``).
    T : float
        The base orbit's crossing time (to ``~1e-8``; (J3) corrects it).
    degree : int
        Degree of the jets (1 to :data:`MAX_DEGREE`).
    n_steps : int
        Runge-Kutta steps to ``T`` (even: the error estimate takes half as many).
    phi0 : float
        The body's ``phi0`` (the section functions take it; ``g`` sections ignore it).
    error_estimate : bool
        Repeat (J2)-(J4) with half the steps for ``error``; ``False``: ``error`` NaN, half
        the cost (a Newton iteration's Jacobian needs no estimate).

    Returns
    -------
    SectionJet

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> body = RigidBody.hess(3.0, 1.0, 2.0, mu=0.0)
    >>> jet = section_map_jet(body, 1.0, 0.0, 0.0, math.pi / 2, 0.0, math.sqrt(2 * 3.0),
    ...                       2 * math.pi / math.sqrt(2 / 3.0), degree=1, n_steps=64)
    >>> bool(abs(jet.l[0] - math.pi / 2) < 1e-12), round(float(np.linalg.det(jet.matrix())), 12)
    (True, 1.0)
    """
    if not (isinstance(degree, int) and 1 <= degree <= MAX_DEGREE):
        raise ValueError(f"degree must be a whole number 1 to {MAX_DEGREE}, got {degree!r}")
    if not (isinstance(n_steps, int) and n_steps >= 2 and n_steps % 2 == 0):
        raise ValueError(f"n_steps must be an even whole number >= 2, got {n_steps!r}")
    basis = JetBasis(degree)
    field = _Field(body, basis)
    y0 = _initial_state(body, basis, h, M, g_star, l0, L0, G0)
    results = []
    for n in ((n_steps // 2, n_steps) if error_estimate else (n_steps,)):
        y, t = _flow(field, y0, T, n, "g", g_star, phi0)
        G1, G2, G3 = (Jet(c, basis) for c in y[:3])
        lb = math.atan2(float(G1.value), float(G2.value))
        cl, sl = math.cos(lb), math.sin(lb)
        d = jet_atan((G1 * cl - G2 * sl) / (G2 * cl + G1 * sl))
        lb += 2 * math.pi * round((l0 - lb) / (2 * math.pi))
        lj = d + lb
        results.append((lj.c, G3.c.copy(), t))
    l2, L2, t2 = results[-1]
    if error_estimate:
        l1, L1, _t1 = results[0]
        diff = np.maximum(np.abs(l2 - l1), np.abs(L2 - L1))
        err = np.array([diff[basis.total == k].max() for k in range(degree + 1)])
    else:
        err = np.full(degree + 1, np.nan)
    return SectionJet(basis, l2, L2, err, n_steps, t2, float(G0))
