"""A computer-assisted proof of transversal splitting at finite ``mu`` (validated manifolds).

For a body with its centre of mass in the (e1, e2) plane the field (1) is reversible:
``R = diag(1, 1, -1, 1, 1, -1)`` (``G3 -> -G3``, ``gamma3 -> -gamma3``) with ``t -> -t``
(checked exactly on the SymPy field, :func:`reversor_holds`). ``R`` maps the rotation
``P-`` (``G3 < 0``) onto ``P+`` and the unstable manifold ``W^u(P-)`` onto the stable
manifold ``W^s(P+)``. A point of ``W^u(P-)`` on ``Fix R = {G3 = gamma3 = 0}`` is therefore
heteroclinic, and there (on the section ``L = G3 = 0``, in its Darboux coordinates
``(g, G)``, where ``R`` acts as ``(g, G) -> (pi - g, G)``) the two manifolds' slopes are
``+-sigma``: they cross transversally iff ``sigma != 0``, at the angle
``2 atan(sigma)`` -- the ``angle`` that
:func:`~andoyer.analysis.splitting.measure.separatrix_splitting` measures.

The proof, every number an Arb ball (python-flint):

1. **Local manifold** (:func:`local_unstable_manifold`). On the section
   ``Sigma = {gamma2 = 0}`` near ``p = (0, 0, G3-, 1, 0, 0)`` the level set
   ``H = h, (G, gamma) = 0, |gamma| = 1`` is the graph of the explicit chart
   ``chi(G2, gamma3)``; the return map ``F`` in eigen-coordinates ``(u, v)`` of ``DF(p)``
   (a float frame ``E``) has its derivative enclosed over the whole box
   ``N = [-r, r]^2`` by one validated return (:func:`~andoyer.integrate.validated.taylor.
   validated_poincare`). The cone condition -- every matrix of ``DF(N)`` maps
   ``{|eta| <= kappa |xi|}`` into ``{|eta| <= kappa' |xi|}``, ``kappa' < kappa``, and
   expands ``xi`` by ``m > 1`` -- makes the branch of ``W^u(p)`` through ``N`` the graph
   ``v = w(u)``, ``|u| <= r``, with ``|w'| <= kappa`` and ``w(0) = 0``.
2. **Transport** of the piece ``u in [u_a, u_b]`` of that graph to ``L = 0`` as one
   Lohner parallelepiped (``frame``/``coords`` of ``validated_poincare``): its long side
   along the manifold is carried by the variational matrix, only the thin side
   ``|v| <= kappa u_b`` and the chart's curvature term are wrapped. The two ends are
   carried alone (thin sets).
3. **Sign change**: ``gamma3`` at the crossing has opposite signs at the two ends, so the
   connected piece meets ``Fix R``: a heteroclinic point ``z`` in the image box ``X``.
4. **Transversality**: the tangent ``DP chi' E (1, eta)``, ``|eta| <= kappa``, at ``z``
   has its ``gamma3`` and ``G`` components bounded away from 0 (so it and ``R`` of it
   are independent), and gives the slope ``sigma = dG/dg`` and the angle
   ``2 atan(sigma)``.

With ``mu_radius`` the body's ``mu`` is a ball: every coefficient, the chart and so every
enclosure hold for all ``mu`` of ``[mu - mu_radius, mu + mu_radius]`` at once, and so does
the theorem.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from functools import cache
from typing import Any

import numpy as np
from flint import arb, arb_mat

from andoyer.errors import ArgumentTypeError
from andoyer.integrate.engines.values import E3_ZERO_REVERSAL
from andoyer.integrate.validated.arithmetic import (
    FLINT_VERSION,
    BodySpec,
    ball_text,
    body_symbols,
    decimal,
    evaluate,
    field_terms,
    precision,
    working_precision,
)
from andoyer.integrate.validated.taylor import validated_poincare
from andoyer.validation import integer

__all__ = ["LocalManifold", "local_unstable_manifold", "mu_interval",
           "TransversalProof", "prove_transversal"]

#: The chart's free coordinates (G2, gamma3) and the dependent ones.
FREE, DEPENDENT = (1, 5), (0, 2, 3, 4)
#: The section of the return map near P-: gamma2 = 0.
LOCAL_SECTION = (0, 0, 0, 0, 1, 0)
#: The section where the manifolds are compared: L = G3 = 0.
SECTION_L0 = (0, 0, 1, 0, 0, 0)


def reversor_holds(e3_zero: bool = True) -> bool:
    """Whether ``f(R y) = -R f(y)`` holds exactly for the field (1) of SymPy, monomial by
    monomial (``e3 = 0``: a monomial of the centre of mass' third component must vanish).

    Parameters
    ----------
    e3_zero : bool, default True
        Take the body's ``e3 = 0`` (the bodies of this module).

    Examples
    --------
    >>> reversor_holds()
    True
    """
    e3 = body_symbols()[6]
    for i, comp in enumerate(field_terms().terms):
        for coef, idx in comp:
            if e3_zero and coef.subs(e3, 0) == 0:
                continue
            sign = E3_ZERO_REVERSAL[i] * math.prod(E3_ZERO_REVERSAL[j] for j in idx)
            if sign != -1:
                return False
    return True


@cache
def _energy_gradient() -> tuple[Any, ...]:
    import sympy as sp

    from andoyer.symbolic.hamiltonian import H_euler_poisson, S

    H = H_euler_poisson()
    return tuple(sp.expand(sp.diff(H, v)) for v in S.y)


@dataclass(frozen=True)
class _Setting:
    sign: int
    bits: int
    a: arb
    b: arb
    c: arb
    mu: arb
    e1: arb
    h: arb
    params: dict[Any, arb]


def _setting(spec: BodySpec, G: str, bits: int, sign: int = -1) -> _Setting:
    bb = spec.balls(bits)
    if not bb.e3.is_zero():
        raise ValueError("the proof needs the centre of mass in the (e1, e2) plane")
    Gb = arb(G)
    params = dict(zip(body_symbols(), bb.params(), strict=True))
    return _Setting(sign, bits, bb.a, bb.b, bb.c, bb.mu, bb.e1, bb.c * Gb * Gb / 2, params)


def _chart(st: _Setting, q: tuple[Any, Any]) -> list[arb]:
    """``chi(G2, gamma3)``: the state on ``gamma2 = 0`` near ``P-`` (``G3 < 0``) or ``P+``
    on the levels."""
    G2, g3 = q
    g1 = (1 - g3 * g3).sqrt()
    rad = 2 * (st.h - st.b * G2 * G2 / 2 - st.mu * st.e1 * g1) / (st.c + st.a * g3 * g3
                                                                    / (g1 * g1))
    if not rad > 0:
        raise ArithmeticError("the chart leaves the level (G3^2 <= 0)")
    G3 = st.sign * rad.sqrt()
    return [-G3 * g3 / g1, G2, G3, g1, arb(0), g3]


def _chart_derivative(st: _Setting, x: list[arb]) -> arb_mat:
    """``chi'`` (6 x 2) over the box ``x``: the tangent of the level set on the section
    whose (G2, gamma3) rows are the identity (the kernel of the four constraints)."""
    values = dict(st.params)
    from andoyer.symbolic.hamiltonian import S

    values.update(zip(S.y, x, strict=True))
    dH = [arb(evaluate(e, values)) for e in _energy_gradient()]
    g = x[3:]
    G = x[:3]
    K = [[arb(1) if j == 4 else arb(0) for j in range(6)], dH,
         [g[0], g[1], g[2], G[0], G[1], G[2]],
         [arb(0), arb(0), arb(0), 2 * g[0], 2 * g[1], 2 * g[2]]]
    KD = arb_mat([[row[j] for j in DEPENDENT] for row in K])
    KF = arb_mat([[row[j] for j in FREE] for row in K])
    TD = -KD.solve(KF)
    out = [[arb(0), arb(0)] for _ in range(6)]
    for k, j in enumerate(DEPENDENT):
        out[j] = [TD[k, 0], TD[k, 1]]
    out[FREE[0]] = [arb(1), arb(0)]
    out[FREE[1]] = [arb(0), arb(1)]
    return arb_mat(out)


def _mat(rows: Any) -> arb_mat:
    return arb_mat([[arb(x) for x in row] for row in rows])


def _row_select(M: arb_mat, rows: tuple[int, ...]) -> arb_mat:
    return arb_mat([[M[i, j] for j in range(M.ncols())] for i in rows])


def _hull_box(st: _Setting, E: arb_mat, u: arb, v: arb) -> list[arb]:
    q = (E[0, 0] * u + E[0, 1] * v, E[1, 0] * u + E[1, 1] * v)
    return _chart(st, q)


@dataclass(frozen=True)
class LocalManifold:
    """The branch of ``W^u(P-)`` through ``N``: a graph ``v = w(u)`` with ``|w'| <= kappa``.

    Attributes
    ----------
    rotation : int
        -1 for ``P-`` (``G3 < 0``), +1 for ``P+``.
    mu_radius : str
        It holds for every ``mu`` within this of the body's.
    frame : tuple of tuple of float
        ``E`` (rows): ``(G2, gamma3) = E (u, v)``.
    radius : float
        ``N = [-r, r]^2`` in ``(u, v)``.
    kappa : float
        The cone's slope.
    expansion : str
        ``m``, the least expansion of ``u`` over ``N`` (a ball, ``> 1``).
    derivative : tuple of str
        ``DF(N)`` in ``(u, v)`` (4 balls, rows).
    multiplier : str
        The unstable eigenvalue of ``DF(p)`` (a ball; the other is proved inside the
        unit circle: ``p`` is a saddle).
    holds : bool
        Whether ``p`` is proved a saddle and the cone condition holds on ``N``.
    seconds : float
        Run time.
    """

    rotation: int
    mu_radius: str
    frame: tuple[tuple[float, float], ...]
    radius: float
    kappa: float
    expansion: str
    derivative: tuple[str, ...]
    multiplier: str
    holds: bool
    seconds: float


def _return_map_derivative(spec: BodySpec, st: _Setting, x: list[arb], order: int
                           ) -> arb_mat:
    """``Pi DP chi'`` (2 x 2, in (G2, gamma3)) over the box ``x`` on ``gamma2 = 0``."""
    cross = validated_poincare(spec, x, LOCAL_SECTION, 0.0, direction=-st.sign, order=order,
                               bits=st.bits, skip=0.0)
    DP = _mat([cross.derivative[6 * i: 6 * i + 6] for i in range(6)])
    return _row_select(DP, FREE) * _chart_derivative(st, x)


def local_unstable_manifold(body: Any, *, G: str = "1", rotation: int = 1,
                            radius: float = 3e-5, mu_radius: str = "0", bits: int = 128,
                            order: int = 30,
                            frame: Any = None, kappa: float | None = None) -> LocalManifold:
    """Prove the cone condition for the return map of ``P-`` on a box ``N`` of ``W^u``.

    Parameters
    ----------
    body : BodySpec
        The body (decimals, ``mu > 0``, centre of mass in the (e1, e2) plane).
    G : str, default "1"
        The level ``h = c G^2 / 2``.
    rotation : {-1, +1}, default 1
        ``P+`` (``G3 > 0``) or ``P-``.
    radius : float, default 3e-5
        ``r``: ``N = [-r, r]^2`` in the eigen-coordinates ``(u, v)``.
    mu_radius : str, default "0"
        Prove it for every ``mu`` in ``[mu - mu_radius, mu + mu_radius]`` at once (a
        decimal; the field's coefficients become balls).
    bits, order : int
        Working precision and Taylor order.
    frame : 2 x 2 floats, optional
        ``E`` (default: the float eigenvectors of ``DF(p)``, unstable first, recomputed).
    kappa : float, optional
        The cone's slope to check (default: twice the least slope the enclosure allows).

    Returns
    -------
    LocalManifold

    Examples
    --------
    >>> from andoyer.integrate.validated.arithmetic import BodySpec
    >>> lm = local_unstable_manifold(BodySpec("2.5", "1.0", "1.6", 1, "0.1", "0.05"),
    ...                              radius=1e-6, order=20)   # doctest: +SKIP
    >>> lm.holds                                              # doctest: +SKIP
    True
    """
    start = time.perf_counter()
    spec = _spec(body, mu_radius)
    if frame is not None:
        frame = _frame_arg(frame)
    if kappa is not None:
        kappa = _real("kappa", kappa, 0.0, 1.0)
    G = decimal("G", G, positive=True, maximum=1e3)
    bits = precision("bits", bits)
    order = integer("order", order, 8, 60)
    if not (isinstance(radius, float | int) and 0.0 < float(radius) <= 1e-2):
        raise ValueError(f"radius must be in (0, 1e-2], got {radius!r}")
    rotation = _rotation(rotation)
    with working_precision(bits):
        st = _setting(spec, G, bits, rotation)
        p = _chart(st, (arb(0), arb(0)))
        M0 = _return_map_derivative(spec, st, p, order)
        if frame is None:
            mid0 = np.array([[float(M0[i, j].mid()) for j in range(2)] for i in range(2)])
            w, V = np.linalg.eig(mid0)
            k = int(np.argmax(np.abs(w)))
            V = np.real(V[:, [k, 1 - k]])
            frame = tuple(tuple(float(x) for x in row) for row in V)
        E = _mat(frame)
        Einv = E.inv()
        lam, saddle = _saddle(Einv * M0 * E)
        r = arb(0, float(radius))
        x = _hull_box(st, E, r, r)
        DF = Einv * _return_map_derivative(spec, st, x, order) * E
        holds, kap, m = _cone(DF, radius, kappa)
        holds = holds and saddle
    return LocalManifold(rotation=rotation, mu_radius=getattr(spec, "mu_radius", "0"),
                         frame=frame, radius=float(radius), kappa=kap,
                         expansion=ball_text(m, 20),
                         derivative=tuple(ball_text(DF[i, j], 20) for i in range(2)
                                          for j in range(2)),
                         multiplier=ball_text(lam, 20), holds=holds,
                         seconds=time.perf_counter() - start)


def _saddle(M: arb_mat) -> tuple[arb, bool]:
    """The eigenvalues of the ``2 x 2`` ball matrix ``M = DF(p)``: real, ``lambda+ > 1``
    and ``|lambda-| < 1`` (from the trace and the determinant); returns ``lambda+``."""
    tr = M[0, 0] + M[1, 1]
    det = M[0, 0] * M[1, 1] - M[0, 1] * M[1, 0]
    disc = tr * tr - 4 * det
    if not disc > 0:
        return arb(0), False
    root = disc.sqrt()
    hi, lo = (tr + root) / 2, (tr - root) / 2
    return hi, bool(hi > 1 and abs(lo) < 1)


def _cone(DF: arb_mat, radius: float, kappa: float | None) -> tuple[bool, float, arb]:
    """The cone condition on the interval matrix ``DF`` (see the module's step 1)."""
    a11, a12 = abs(DF[0, 0]), abs(DF[0, 1])
    a21, a22 = abs(DF[1, 0]), abs(DF[1, 1])
    lo11 = arb(a11.lower())
    if kappa is None:
        denom = lo11 - a22.upper()
        if not denom > 0:
            return False, math.inf, arb(0)
        kappa = float((2 * arb(a21.upper()) / denom).upper()) + 1e-300
    kap = arb(kappa)
    m = lo11 - kap * arb(a12.upper())
    image_slope = arb(a21.upper()) + kap * arb(a22.upper())
    holds = bool(m > 1 and image_slope < kap * m and kap < 1 and kap > 0)
    return holds, float(kappa), m


def _real(name: str, value: Any, lo: float, hi: float) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float) or not (
            math.isfinite(value) and lo < value <= hi):
        raise ValueError(f"{name} must be a number in ({lo:g}, {hi:g}], got {value!r:.60}")
    return float(value)


def _frame_arg(frame: Any) -> tuple[tuple[float, ...], ...]:
    try:
        if isinstance(frame, str | bool | bytes):
            raise TypeError
        rows = tuple(tuple(float(x) for x in row) for row in frame)
    except (TypeError, ValueError):
        raise ValueError(f"frame must be a 2 x 2 matrix of numbers, got {frame!r:.60}") from None
    ok = len(rows) == 2 and all(len(r) == 2 for r in rows) and all(
        math.isfinite(x) for r in rows for x in r)
    if not ok or rows[0][0] * rows[1][1] - rows[0][1] * rows[1][0] == 0.0:
        raise ValueError(f"frame must be an invertible 2 x 2 matrix, got {frame!r:.60}")
    return rows


def _rotation(rotation: Any) -> int:
    if isinstance(rotation, bool) or rotation not in (1, -1):
        raise ValueError(f"rotation must be -1 (P-) or +1 (P+), got {rotation!r}")
    return int(rotation)


@dataclass(frozen=True)
class _MuBall(BodySpec):
    """A body whose ``mu`` is every number of ``[mu - mu_radius, mu + mu_radius]``: its
    balls (the field's coefficients, the chart) enclose them all at once."""

    mu_radius: str = "0"

    def balls(self, bits: int) -> Any:
        import dataclasses

        bb = super().balls(bits)
        with working_precision(bits):
            mu = bb.mu + arb(0, float(arb(self.mu_radius).upper()))
        return dataclasses.replace(bb, mu=mu)

    def as_dict(self) -> dict[str, Any]:
        """The spec as JSON-ready values, with ``mu_radius``."""
        return {**super().as_dict(), "mu_radius": self.mu_radius}


def _spec(body: Any, mu_radius: Any = "0") -> BodySpec:
    from decimal import Decimal

    from andoyer.integrate.validated.arithmetic import spec_of

    if not isinstance(body, BodySpec):
        if body is None or isinstance(body, bool | int | float | str):
            raise ArgumentTypeError(f"body must be a BodySpec or a RigidBody, got {body!r}")
    spec = spec_of(body)
    if not float(spec.mu) > 0.0:
        raise ValueError(f"body: mu must be > 0 for P- to be hyperbolic, got {spec.mu}")
    if isinstance(spec, _MuBall):
        return spec
    mu_radius = decimal("mu_radius", mu_radius)
    if not 0 <= Decimal(mu_radius) < Decimal(spec.mu) / 2:
        raise ValueError(f"mu_radius must be >= 0 and below mu/2 = {float(spec.mu) / 2:g}, "
                         f"got {mu_radius}")
    if Decimal(mu_radius) == 0:
        return spec
    return _MuBall(spec.A, spec.B, spec.C, spec.branch, spec.epsilon, spec.mu, mu_radius)


def mu_interval(body: dict[str, Any]) -> tuple[str, str]:
    """``[mu - mu_radius, mu + mu_radius]`` of a proof's body, as exact decimals.

    Parameters
    ----------
    body : dict
        :attr:`TransversalProof.body`.

    Examples
    --------
    >>> mu_interval({"mu": "0.05", "mu_radius": "1e-9"})
    ('0.049999999', '0.050000001')
    """
    from decimal import Decimal, InvalidOperation

    if not isinstance(body, dict) or "mu" not in body:
        raise ValueError(f"body must be a proof's body (a dict with 'mu'), got {body!r:.60}")
    try:
        mu = Decimal(decimal("body['mu']", body["mu"]))
        rad = Decimal(decimal("body['mu_radius']", body.get("mu_radius", "0")))
    except InvalidOperation:
        raise ValueError(f"body's mu and mu_radius must be decimals, got {body!r:.60}") from None
    return str(mu - rad), str(mu + rad)


# ----------------------------------------------------------------------------- search
def _float_crossing(engine: Any, body: Any, y0: np.ndarray, sign: int,
                    t_max: float = 500.0) -> np.ndarray:
    """The first crossing of ``G3 = 0`` away from ``sign`` (floats: the search only,
    nothing proved rests on it), by the numba engine's DOP853 with its crossings in the
    compiled loop (a Python field under ``solve_ivp`` cost 2 s of the proof)."""
    from andoyer.integrate.engines.base import Section, Tolerance

    cr = engine.crossings(y0[None], body.engine_params, Section("G3", 0.0, -sign), 1, t_max,
                          Tolerance(1e-13, 1e-15))
    if int(cr.count[0]) < 1:
        raise ArithmeticError("the float search found no crossing of L = 0")
    return np.asarray(cr.y[0, 0])


def _float_zero(spec: BodySpec, st: _Setting, E: np.ndarray, side: int, lam: float,
                radius: float, which: int) -> float:
    """``u*``: where ``gamma3`` at the crossing vanishes on the approximate manifold
    ``v = 0`` (the ``which``-th sign change in ``u`` in ``[radius / lam, radius]``)."""
    from scipy.optimize import brentq

    from andoyer.integrate.engines import resolve_engine
    from andoyer.integrate.engines.base import Capability

    engine = resolve_engine("numba", Capability.CROSSINGS)
    body = spec.body()
    a, b, c, mu, e1, h = (float(x.mid()) for x in (st.a, st.b, st.c, st.mu, st.e1, st.h))

    def chart(u: float) -> np.ndarray:
        G2, g3 = side * u * E[0, 0], side * u * E[1, 0]
        g1 = math.sqrt(1 - g3 * g3)
        G3 = st.sign * math.sqrt(2 * (h - b * G2 * G2 / 2 - mu * e1 * g1)
                                 / (c + a * g3 * g3 / g1**2))
        return np.array([-G3 * g3 / g1, G2, G3, g1, 0.0, g3])

    def gamma3(u: float) -> float:
        return float(_float_crossing(engine, body, chart(u), st.sign)[5])

    grid = np.geomspace(radius / lam, radius, 25)
    vals = [gamma3(float(u)) for u in grid]
    changes = [i for i in range(len(grid) - 1) if vals[i] * vals[i + 1] < 0]
    if len(changes) <= which:
        raise ArithmeticError("no sign change of gamma3 on the fundamental domain")
    i = changes[which]
    return float(brentq(gamma3, float(grid[i]), float(grid[i + 1]), xtol=1e-18, rtol=1e-15))


# ----------------------------------------------------------------------------- proof
def _piece(st: _Setting, E: arb_mat, side: int, kappa: float, u_lo: float, u_hi: float,
           u_ends: tuple[float, float] | None = None
           ) -> tuple[list[arb], list[list[arb]], list[arb], arb_mat]:
    """The Lohner set ``x0 + Q r`` holding the graph's piece ``u in [u_lo, u_hi]``
    (``u_lo = u_hi``: one point of the graph; ``|v| <= kappa u_ends[1]``), and ``chi' E``
    over it."""
    lo, hi = arb(u_lo), arb(u_hi)
    u0 = (lo + hi) / 2
    U = lo.union(hi)
    vmax = arb(kappa) * (arb(u_ends[1]) if u_ends else hi)
    v = arb(0, float(vmax.upper()))
    x0 = _hull_box(st, E, side * u0, arb(0))
    xh = _hull_box(st, E, side * U, v)
    J = _chart_derivative(st, xh) * E
    W = [side * (U - u0), v]
    Jm = [[arb(J[i, j].mid()) for j in range(2)] for i in range(6)]
    frame = [[Jm[i][0], Jm[i][1]] + [arb(1) if i == k else arb(0) for k in DEPENDENT]
             for i in range(6)]
    extra = [sum(((J[i, j] - Jm[i][j]) * W[j] for j in range(2)), arb(0)) for i in DEPENDENT]
    return x0, frame, [W[0], W[1], *extra], J


def _carry(spec: BodySpec, st: _Setting, piece: Any, order: int, t_max: float) -> Any:
    x0, frame, coords, _ = piece
    return validated_poincare(spec, x0, SECTION_L0, 0.0, direction=-st.sign, order=order,
                              bits=st.bits, frame=frame, coords=coords, t_max=t_max)


def _slope(image: list[arb], tau: list[arb]) -> tuple[arb, arb, arb]:
    """``dG``, ``dg`` and ``sigma = dG/dg`` of the tangent ``tau`` at the box ``image``
    (the Andoyer-Deprit ``g`` of :func:`~andoyer.charts.andoyer_deprit.to_andoyer`)."""
    G1, G2, G3, g1, g2, g3 = image
    d1, d2, d3, e1, e2, e3 = tau
    Gn = (G1 * G1 + G2 * G2 + G3 * G3).sqrt()
    dG = (G1 * d1 + G2 * d2 + G3 * d3) / Gn
    P = G2 * g1 - G1 * g2
    dP = d2 * g1 + G2 * e1 - d1 * g2 - G1 * e2
    Y = Gn * P
    dY = dG * P + Gn * dP
    S2 = G1 * G1 + G2 * G2
    Q = G1 * g1 + G2 * g2
    dQ = d1 * g1 + G1 * e1 + d2 * g2 + G2 * e2
    X = G3 * Q - g3 * S2
    dX = d3 * Q + G3 * dQ - e3 * S2 - g3 * 2 * (G1 * d1 + G2 * d2)
    dg = (X * dY - Y * dX) / (X * X + Y * Y)
    return dG, dg, dG / dg


@dataclass(frozen=True)
class TransversalProof:
    """The theorem of :func:`prove_transversal` and every box it rests on.

    Attributes
    ----------
    body : dict
        The body (decimals, :meth:`BodySpec.as_dict`).
    G : str
        The level ``h = c G^2 / 2`` (area integral 0, ``|gamma| = 1``).
    manifold : LocalManifold
        The local manifold (cone condition).
    side : int
        The branch ``u > 0`` (+1) or ``u < 0`` (-1) of ``W^u_loc``.
    piece : tuple of float
        ``[u_a, u_b]``, the piece of the graph carried.
    ends_gamma3 : tuple of str
        ``gamma3`` at the crossing of ``L = 0`` of the two ends (balls of opposite signs).
    point_box : tuple of str
        ``X``: the box on ``L = 0`` holding the heteroclinic point (six balls,
        ``gamma3 = 0`` and ``G3 = 0`` there).
    crossing_time : str
        The time from ``Sigma`` to ``L = 0`` over the piece.
    slope : str
        ``sigma = dG/dg`` of ``W^u`` at the point (``W^s``: ``-sigma``).
    angle : str
        ``2 atan(sigma)``, the splitting angle in ``(g, G)``.
    proved : bool
        Whether every check passed (the theorem holds).
    widths : dict
        The widths at each step (the manifold's cone, the piece's image, the ends'
        ``gamma3``, the slope).
    seconds : float
        Run time.
    bits, order : int
        Precision and Taylor order.
    flint_version : str
        python-flint's version.
    """

    body: dict[str, Any]
    G: str
    manifold: LocalManifold
    side: int
    piece: tuple[float, float]
    ends_gamma3: tuple[str, str]
    point_box: tuple[str, ...]
    crossing_time: str
    slope: str
    angle: str
    proved: bool
    widths: dict[str, float]
    seconds: float
    bits: int
    order: int
    flint_version: str = FLINT_VERSION

    def _mu_text(self) -> str:
        lo, hi = mu_interval(self.body)
        return f"mu={self.body['mu']}" if lo == hi else f"every mu in [{lo}, {hi}]"

    @property
    def statement(self) -> str:
        """The theorem in words."""
        b = self.body
        u, s = ("P-", "P+") if self.manifold.rotation == -1 else ("P+", "P-")
        return (f"For the body A={b['A']}, B={b['B']}, C={b['C']} with its centre of mass "
                f"turned by epsilon={b['epsilon']} off the Hess direction (branch "
                f"{b['branch']} of (2)), {self._mu_text()}, on the level h = c G^2/2 with "
                f"G={self.G}, (G, gamma) = 0, |gamma| = 1: the unstable manifold of the "
                f"rotation {u} and the stable manifold of {s} intersect "
                "transversally at a point of the box X on L = G3 = 0 (gamma3 = 0 there), "
                f"at the angle 2 atan(sigma) in {self.angle} in the (g, G) plane.")


def prove_transversal(body: Any, *, G: str = "1", rotation: int = 1, radius: float = 3e-5,
                      side: int = 1, mu_radius: str = "0",
                      which: int = 0, half_width: float = 1e-9, bits: int = 128,
                      order: int = 24, t_max: float = 500.0,
                      piece: tuple[float, float] | None = None,
                      manifold: LocalManifold | None = None) -> TransversalProof:
    """Prove that ``W^u(P-)`` and ``W^s(P+)`` intersect transversally (the module's steps).

    Parameters
    ----------
    body : BodySpec or RigidBody
        A body with ``mu > 0`` and its centre of mass in the (e1, e2) plane.
    G : str, default "1"
        The level ``h = c G^2 / 2``.
    rotation : {-1, +1}, default 1
        Whose unstable manifold: ``P+`` (it meets ``L = 0`` with ``G3`` falling; on the
        body ``(2.5, 1.0, 1.6)`` this is the Hess line ``theta1 = 0``, which splits only
        because ``epsilon != 0``) or ``P-`` (the line ``theta1 = 4 phi0`` there); the
        stable manifold is the other rotation's.
    radius : float, default 3e-5
        The local manifold's box ``N = [-r, r]^2``.
    side : {+1, -1}, default 1
        Which branch of ``W^u_loc`` (``u > 0`` or ``u < 0``).
    mu_radius : str, default "0"
        Prove it for every ``mu`` in ``[mu - mu_radius, mu + mu_radius]`` (a decimal);
        the ends' ``gamma3`` then widen by about ``1e3 mu_radius``, so ``half_width``
        must grow with it.
    which : int, default 0
        Which sign change of ``gamma3`` on the fundamental domain ``[r/lambda, r]``.
    half_width : float, default 1e-9
        Relative half-width of the piece around the float zero ``u*``.
    bits, order : int
        Precision and Taylor order.
    t_max : float, default 500
        The longest transport.
    piece : (float, float), optional
        ``[u_a, u_b]`` given (a certificate's): no search.
    manifold : LocalManifold, optional
        A proved local manifold (else proved here).

    Returns
    -------
    TransversalProof
        ``proved`` says whether the theorem holds; ``widths`` what each step achieved.

    Examples
    --------
    >>> from andoyer.integrate.validated.arithmetic import BodySpec
    >>> p = prove_transversal(BodySpec("2.5", "1.0", "1.6", 1, "0.1", "0.05"))
    ... # doctest: +SKIP
    >>> p.proved                                                  # doctest: +SKIP
    True
    """
    start = time.perf_counter()
    spec = _spec(body, mu_radius)
    if isinstance(side, bool) or side not in (1, -1):
        raise ValueError(f"side must be +1 or -1, got {side!r}")
    which = integer("which", which, 0, 10)
    if isinstance(half_width, bool) or not (isinstance(half_width, float | int)
                                            and 0.0 < half_width <= 1e-3):
        raise ValueError(f"half_width must be in (0, 1e-3], got {half_width!r}")
    t_max = _real("t_max", t_max, 0.0, 1e4)
    if manifold is not None and not isinstance(manifold, LocalManifold):
        raise ArgumentTypeError(f"manifold must be a LocalManifold, got {manifold!r:.60}")
    if piece is not None:
        try:
            if isinstance(piece, str | bytes | bool | dict):
                raise TypeError
            u_ab = np.asarray(piece, dtype=float)
        except (TypeError, ValueError):
            u_ab = np.empty(0)
        if u_ab.shape != (2,) or not np.isfinite(u_ab).all():
            raise ValueError(f"piece must be two finite numbers (u_a, u_b), "
                             f"got {piece!r:.60}")
        piece = (float(u_ab[0]), float(u_ab[1]))
    if not reversor_holds():
        raise ArithmeticError("the field (1) is not reversible under R: the proof's "
                              "premise fails")
    rotation = _rotation(rotation if manifold is None else manifold.rotation)
    lm = manifold if manifold is not None else local_unstable_manifold(
        spec, G=G, rotation=rotation, radius=radius, bits=bits, order=order)
    if lm.mu_radius != getattr(spec, "mu_radius", "0"):
        raise ValueError(f"manifold was proved for mu_radius {lm.mu_radius}, not "
                         f"{getattr(spec, 'mu_radius', '0')}")
    if not lm.holds:
        raise ArithmeticError(f"the cone condition fails on N = [-{lm.radius:g}, "
                              f"{lm.radius:g}]^2 (kappa = {lm.kappa:g}, DF(N) = "
                              f"{lm.derivative})")
    r = lm.radius
    with working_precision(bits):
        st = _setting(spec, G, bits, rotation)
        E = _mat(lm.frame)
        lam = float(arb(lm.multiplier).mid())
        if piece is None:
            u_star = _float_zero(spec, st, np.array(lm.frame), side, lam, r, which)
            piece = (u_star * (1 - half_width), u_star * (1 + half_width))
        u_a, u_b = float(piece[0]), float(piece[1])
        if not 0.0 < u_a < u_b <= r:
            raise ValueError(f"piece must satisfy 0 < u_a < u_b <= r = {r:g}, got {piece}")
        seg = _piece(st, E, side, lm.kappa, u_a, u_b)
        cs = _carry(spec, st, seg, order, t_max)
        ends = [_carry(spec, st, _piece(st, E, side, lm.kappa, u, u, (u_a, u_b)), order,
                       t_max) for u in (u_a, u_b)]
        g_a, g_b = (arb(e.image[5]) for e in ends)
        sign_change = bool((g_a < 0 and g_b > 0) or (g_a > 0 and g_b < 0))
        # the ends cross in the piece's certified step (one crossing per point there):
        # their gamma3 are values of the one continuous map on the piece
        T = arb(cs.time)
        same_crossing = all(T.contains(arb(e.time)) for e in ends)
        DP = _mat([cs.derivative[6 * i: 6 * i + 6] for i in range(6)])
        J = seg[3]
        eta = arb(0, lm.kappa)
        t_loc = [J[i, 0] + J[i, 1] * eta for i in range(6)]
        tau = [sum((DP[i, j] * t_loc[j] for j in range(6)), arb(0)) for i in range(6)]
        image = [arb(x) for x in cs.image]
        point = list(image)
        point[5] = arb(0)
        point[2] = arb(0)
        dG, dg, sigma = _slope(point, tau)
        # R tau = tau with gamma3 (and G3 = 0) negated: tau, R tau independent iff
        # tau_gamma3 != 0 and (tau_G1, tau_G2, tau_gamma1, tau_gamma2) != 0 (dG != 0)
        transversal = bool(not tau[5].contains(0) and not dG.contains(0)
                           and not dg.contains(0))
        angle = 2 * sigma.atan()
        widths = {"cone_kappa": lm.kappa, "manifold_error": lm.kappa * u_b,
                  "piece_image": float(max(cs.image_rad)),
                  "end_gamma3_a": float(g_a.rad()), "end_gamma3_b": float(g_b.rad()),
                  "end_gamma3_a_mid": float(g_a.mid()), "end_gamma3_b_mid": float(g_b.mid()),
                  "slope": float(sigma.rad()), "slope_mid": float(sigma.mid()),
                  "tangent_gamma3": float(tau[5].rad()),
                  "tangent_gamma3_mid": float(tau[5].mid())}
        return TransversalProof(
            body=spec.as_dict(), G=G, manifold=lm, side=side, piece=(u_a, u_b),
            ends_gamma3=(ball_text(g_a, 20), ball_text(g_b, 20)),
            point_box=tuple(ball_text(x, 30) for x in point),
            crossing_time=cs.time, slope=ball_text(sigma, 20), angle=ball_text(angle, 20),
            proved=bool(sign_change and same_crossing and transversal), widths=widths,
            seconds=time.perf_counter() - start, bits=bits, order=order)
