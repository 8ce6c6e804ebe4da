"""The Euler-Poisson equations (1) and the section functions as heyoka expressions.

The one SymPy -> heyoka builder: the vector field (1) and every section function are
taken from :mod:`andoyer.symbolic` and converted with :func:`heyoka.from_sympy`
(nothing typed by hand); the body and the section enter as runtime parameters
``par[i]`` in the order of :data:`PARAMETERS` (the layout of
:func:`andoyer.integrate.engines.base.runtime_parameters`, its one owner). Every heyoka
integrator of the heyoka engine (orbits, sections, tangent flows) is built from
:func:`heyoka_system`.
heyoka is imported at first use (:mod:`andoyer.integrate.engines.lazy`).
"""

from __future__ import annotations

import threading
from functools import cache
from typing import Any

import numpy as np
import sympy as sp
from numpy.typing import NDArray

from andoyer.integrate.engines.base import ALL_KINDS, PAR
from andoyer.integrate.engines.base import PARAMETERS as PARAMETER_NAMES
from andoyer.integrate.engines.lazy import heyoka as hy
from andoyer.symbolic.hamiltonian import S, euler_poisson_field, euler_poisson_jacobian
from andoyer.symbolic.sections import SECTION_ARGS, section_function

__all__ = ["PARAMETERS", "COS_PHI0", "SIN_PHI0", "INV_SCALE", "par", "heyoka_state_vars",
           "symbol_map", "taylor_form", "heyoka_system", "section_exprs", "section_cfunc",
           "field_cfunc", "field_at", "attitude_vars", "attitude_system",
           "tangent_coefficients", "coefficient_values", "coefficient_tangent_system"]

#: ``cos phi0``, ``sin phi0`` as runtime parameters of their own in the section functions:
#: heyoka would expand ``cos(par)``, ``sin(par)`` by their Taylor recursions at every step
#: (measured: benchmarks/NOTES.md#heyoka-engine).
COS_PHI0, SIN_PHI0 = sp.symbols("cos_phi0 sin_phi0", real=True)
#: ``1/T``: the scale of the MEGNO quadratures of the tangent flows.
INV_SCALE = sp.Symbol("inv_scale", positive=True)
#: The runtime parameters as SymPy symbols, in the order of
#: :data:`andoyer.integrate.engines.base.PARAMETERS` (checked at import).
PARAMETERS: tuple[sp.Symbol, ...] = (*S.body, *SECTION_ARGS[len(S.y):], COS_PHI0, SIN_PHI0,
                                     INV_SCALE)
if tuple(map(str, PARAMETERS)) != PARAMETER_NAMES:
    raise RuntimeError(f"heyoka parameters {PARAMETERS} differ from the engines' layout "
                       f"{PARAMETER_NAMES}")


def par(name: str) -> Any:
    """heyoka's runtime parameter called ``name`` (:data:`~andoyer.integrate.engines.base.PAR`).

    Parameters
    ----------
    name : str
        A runtime parameter name (:data:`~andoyer.integrate.engines.base.PAR`).
    """
    return hy.par[PAR[name]]



@cache
def heyoka_state_vars() -> tuple[Any, ...]:
    """The heyoka variables of the Euler-Poisson state, named as in ``STATE``."""
    return tuple(hy.make_vars(*(str(s) for s in S.y)))


@cache
def symbol_map() -> dict[sp.Basic, Any]:
    """SymPy symbol -> heyoka variable (state) or runtime parameter (everything else)."""
    smap: dict[sp.Basic, Any] = dict(zip(S.y, heyoka_state_vars(), strict=True))
    smap.update({s: hy.par[i] for i, s in enumerate(PARAMETERS)})
    return smap


def taylor_form(expr: sp.Expr) -> Any:
    """A polynomial in the state with parameter coefficients, as a heyoka expression
    shaped for a cheap Taylor decomposition in a scalar integrator.

    :func:`heyoka.from_sympy` keeps SymPy's canonical order (``G2*G3*b``, ``-G2*G3*c``):
    heyoka then multiplies state by state before the parameters and negates each
    negative term. Here each degree is written ``gcd * (c1*x_k..x_1 - c2*...)``: the
    common parameter factored out, each coefficient multiplied in first, the state
    variables in reverse order (γ before G), signs folded into subtractions: nearly as
    fast as the numbers folded in as constants (measured: benchmarks/NOTES.md#heyoka-engine).

    Parameters
    ----------
    expr : sympy.Expr
        A polynomial in the state variables with parameter coefficients.

    Examples
    --------
    >>> from andoyer.symbolic.hamiltonian import euler_poisson_field
    >>> str(taylor_form(euler_poisson_field()[3]))
    '(((p2 * gamma2) * G3) - ((p1 * gamma3) * G2))'
    """
    smap = symbol_map()
    if sp.expand(expr) == 0:
        return hy.from_sympy(sp.Float(0.0), smap)
    groups: dict[int, list[tuple[sp.Expr, tuple[int, ...]]]] = {}
    for m, c in sp.Poly(expr, *S.y).terms():
        groups.setdefault(sum(m), []).append((sp.factor(c), m))
    total: Any = None
    for _, terms in sorted(groups.items(), reverse=True):
        g = sp.gcd_list([c for c, _ in terms]) if len(terms) > 1 else sp.Integer(1)
        acc: Any = None
        for c, m in terms:
            c = sp.cancel(c / g)
            neg = c.could_extract_minus_sign()
            term: Any = None if (-c if neg else c) == 1 else hy.from_sympy(-c if neg else c, smap)
            for s, k in reversed(list(zip(S.y, m, strict=True))):
                for _ in range(k):
                    term = smap[s] if term is None else term * smap[s]
            if acc is None:
                acc = -term if neg else term
            else:
                acc = acc - term if neg else acc + term
        part = acc if g == 1 else hy.from_sympy(g, smap) * acc
        total = part if total is None else total + part
    return total


@cache
def heyoka_system(scalar: bool = False) -> tuple[tuple[Any, Any], ...]:
    """The Euler-Poisson equations (1) as heyoka ``(variable, rhs)`` pairs.

    Parameters
    ----------
    scalar : bool
        For a scalar (one-orbit) integrator: each right-hand side in
        :func:`taylor_form`, cheaper per step there. Batch (SIMD) integrators keep
        :func:`heyoka.from_sympy`'s form, which is faster with lanes (measured:
        benchmarks/NOTES.md#heyoka-engine).
    """
    smap = symbol_map()
    return tuple((x, taylor_form(e) if scalar else hy.from_sympy(e, smap))
                 for x, e in zip(heyoka_state_vars(), euler_poisson_field(), strict=True))


# ----------------------------------------------------------------------------- FLI system
#: Names of the tangent-vector variables of :func:`coefficient_tangent_system`.
TANGENT_NAMES = tuple(f"w_{s}" for s in map(str, S.y))


@cache
def _coefficient_form() -> tuple[tuple[sp.Expr, ...],
                                  tuple[tuple[tuple[int, tuple[tuple[int, ...], ...]], ...],
                                        ...]]:
    """The field (1) and its tangent equations ``w' = J(y) w`` as sums of monomials in
    ``(y, w)`` grouped by their body coefficients.

    Returns ``(coefficients, equations)``: the distinct coefficients (SymPy expressions
    in the body's symbols, signs included, in order of first appearance), and per
    equation the groups ``(coefficient index, (exponents of (y, w), ...))``.
    """
    w = sp.symbols(" ".join(TANGENT_NAMES), real=True)
    J = euler_poisson_jacobian()
    n = len(S.y)
    exprs = [*euler_poisson_field(),
             *(sp.expand(sum(J[n * i + j] * w[j] for j in range(n))) for i in range(n))]
    coefficients: list[sp.Expr] = []
    equations: list[tuple[tuple[int, tuple[tuple[int, ...], ...]], ...]] = []
    for e in exprs:
        groups: dict[int, list[tuple[int, ...]]] = {}
        for m, c in sp.Poly(e, *S.y, *w).terms():
            c = sp.factor(c)
            same = [i for i, d in enumerate(coefficients) if sp.expand(c - d) == 0]
            if not same:
                coefficients.append(c)
            index = same[0] if same else len(coefficients) - 1
            groups.setdefault(index, []).append(tuple(int(k) for k in m))
        equations.append(tuple((i, tuple(ms)) for i, ms in groups.items()))
    return tuple(coefficients), tuple(equations)


def tangent_coefficients() -> tuple[sp.Expr, ...]:
    """The distinct body coefficients (signs included) of the monomials of the field (1)
    and its tangent equations: the runtime parameters of
    :func:`coefficient_tangent_system`.

    Examples
    --------
    >>> tangent_coefficients()[:3]
    (-b + c, e3*mu, -e2*mu)
    """
    return _coefficient_form()[0]


@cache
def _coefficient_function() -> Any:
    return sp.lambdify(S.body, list(tangent_coefficients()), modules="math")


def coefficient_values(params: Any) -> NDArray[np.float64]:
    """The values of :func:`tangent_coefficients` for a body.

    Parameters
    ----------
    params : sequence of floats
        ``(a, b, c, mu, e1, e2, e3, ...)`` (:attr:`RigidBody.engine_params`; extra
        entries ignored).

    Examples
    --------
    >>> v = coefficient_values((0.4, 0.5, 0.5, 0.01, 1.0, 0.0, 0.0))  # b = c, e = (1, 0, 0)
    >>> [str(c) for c, x in zip(tangent_coefficients(), v) if x == 0.0]
    ['-b + c', 'e3*mu', '-e2*mu', '-e3*mu', 'e2*mu']
    """
    return np.array(_coefficient_function()(*(float(v) for v in params[:len(S.body)])),
                    dtype=float)


@cache
def coefficient_tangent_system(zero: frozenset[int] = frozenset()
                               ) -> tuple[tuple[Any, Any], ...]:
    """The state and ONE tangent vector, ``y' = f(y)``, ``w' = J(y) w`` (12 variables),
    as heyoka ``(variable, rhs)`` pairs whose runtime parameters are the body
    coefficients :func:`tangent_coefficients` (``par[i]``, values from
    :func:`coefficient_values`).

    Each right-hand side is ``sum_i par[i] * (sum of its monomials)``: one product per
    coefficient instead of one per monomial and body symbol, as a script with the
    numbers folded in, while the numbers stay runtime parameters (one compiled
    integrator serves every body). The groups whose coefficient vanishes for the body
    (``zero``: e.g. ``e3 mu`` on a Hess body) are left out, which changes nothing but
    the cost; such a system is compiled once per pattern of zeros.

    Parameters
    ----------
    zero : frozenset of int
        Indices of coefficients that are exactly 0 for the body.
    """
    _, equations = _coefficient_form()
    variables = [*heyoka_state_vars(), *hy.make_vars(*TANGENT_NAMES)]
    out = []
    for x, groups in zip(variables, equations, strict=True):
        parts = []
        for i, monomials in groups:
            if i in zero:
                continue
            terms = []
            for m in monomials:
                term: Any = None
                for v, k in zip(variables, m, strict=True):
                    for _ in range(k):
                        term = v if term is None else term * v
                terms.append(term)
            parts.append(hy.par[i] * (terms[0] if len(terms) == 1 else hy.sum(terms)))
        rhs = (hy.expression(0.0) if not parts else parts[0] if len(parts) == 1
               else hy.sum(parts))
        out.append((x, rhs))
    return tuple(out)


@cache
def attitude_vars() -> tuple[Any, ...]:
    """The heyoka variables of the state with the attitude quaternion ``(G, gamma, q)``."""
    from andoyer.symbolic.attitude import Q

    return (*heyoka_state_vars(), *hy.make_vars(*(str(s) for s in Q)))


@cache
def attitude_system() -> tuple[tuple[Any, Any], ...]:
    """(1) with ``dq/dt = q (x) (0, I^-1 G) / 2`` as heyoka ``(variable, rhs)`` pairs, from
    :func:`andoyer.symbolic.attitude.attitude_field` (scalar-first quaternion, body ->
    space)."""
    from andoyer.symbolic.attitude import Q, attitude_field

    variables = attitude_vars()
    smap = {**symbol_map(), **dict(zip(Q, variables[len(S.y):], strict=True))}
    return tuple((x, hy.from_sympy(e, smap))
                 for x, e in zip(variables, attitude_field(), strict=True))


@cache
def section_exprs(kind: int) -> tuple[Any, Any, Any]:
    """``(f, w, df/dt)`` of section ``kind`` as heyoka expressions.

    ``f`` and ``w`` come from :func:`andoyer.symbolic.sections.section_function`;
    ``df/dt = grad f . F`` (the Lie derivative along (1)) is differentiated by heyoka.
    """
    smap = symbol_map()
    trig = {sp.cos(S.phi0): COS_PHI0, sp.sin(S.phi0): SIN_PHI0}
    f, w = (hy.from_sympy(sp.sympify(e).subs(trig), smap)
            for e in section_function(ALL_KINDS[kind]))
    fdot = hy.sum([hy.diff(f, x) * rhs for x, rhs in heyoka_system()])
    return f, w, fdot


_CFUNC_LOCK = threading.Lock()


@cache
def _section_cfunc_cached(kind: int) -> Any:
    return hy.cfunc(list(section_exprs(kind)), list(heyoka_state_vars()))


def section_cfunc(kind: int) -> Any:
    """Compiled ``y, par -> (f, w, df/dt)`` (vectorised over columns).

    Parameters
    ----------
    kind : int
        Section kind (an index of the generated section kinds).
    """
    with _CFUNC_LOCK:
        return _section_cfunc_cached(kind)


def field_at(Y: NDArray[np.float64], par: NDArray[np.float64]) -> NDArray[np.float64]:
    """The vector field (1) at states ``Y`` (r, 6), from the compiled heyoka function.

    Parameters
    ----------
    Y : ndarray, shape (r, 6)
        Euler-Poisson states.
    par : ndarray
        Runtime parameters (:data:`~andoyer.integrate.engines.base.PAR` order).
    """
    cf = field_cfunc()
    P = np.broadcast_to(par[:cf.nparams, None], (cf.nparams, Y.shape[0]))
    return np.asarray(cf(np.ascontiguousarray(Y.T), pars=np.ascontiguousarray(P))).T


@cache
def _field_cfunc_cached() -> Any:
    return hy.cfunc([rhs for _, rhs in heyoka_system()], list(heyoka_state_vars()))


def field_cfunc() -> Any:
    """The vector field (1) as a compiled heyoka function ``(y, par) -> dy/dt``
    (vectorised over columns), built once per process and shared by threads.

    Returns
    -------
    heyoka.cfunc
        Called by :func:`field_at`.
    """
    with _CFUNC_LOCK:
        return _field_cfunc_cached()
