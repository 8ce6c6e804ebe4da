"""The section map of the rotations about the middle axis: sections psi = psi0 (the phase
of gamma about G) and L = 0 of the Euler-Poisson flow, states completed on a level (h, M),
the flow to the next crossing with its variational Jacobian and event projector, and the
return map in section coordinates. :mod:`andoyer.analysis.periodic` finds the periodic
orbits on it by Newton's method.

The flow to a section runs on heyoka's Taylor integrator where heyoka is installed, else
(or with ``engine="numba"``) on the Numba DOP853 with the variational equations generated
by SymPy (:func:`andoyer.integrate.tangent.tangent_crossings`). The DOP853 only steps
forward in time; a backward flow uses the reversibility of (1): with
``R = diag(-1, -1, -1, 1, 1, 1)``, ``y(-t; y0) = R y(t; R y0)``, so the crossing of the
backward orbit is ``R`` of a forward crossing of ``R y0`` and ``dy(-t)/dy0 = R Phi(t) R``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cache
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from andoyer.body import RigidBody, checks_body
from andoyer.charts.euler_poisson import as_state
from andoyer.dynamics import vector_field
from andoyer.integrate.engines import default_engine_name, resolve_engine
from andoyer.integrate.engines.base import SectionEvent, Tolerance
from andoyer.kernels.constants import T_START

__all__ = [
    "Crossing", "DEFAULT_TOL", "FLOW_ENGINES", "NUMBA_TOL", "RotationSection", "SectionReturn",
    "event_projector", "flow_engine", "flow_to_section", "gamma_phase", "middle_axis_rate",
    "return_map", "rotation_energy", "section_coords", "section_state",
]


#: heyoka's tolerance used by default for the periodic orbits and the manifolds.
DEFAULT_TOL = 1e-15
#: The smallest tolerance given to the numba route (DOP853 in double precision).
NUMBA_TOL = 1e-13
#: Time reversal of (1): ``y(-t; y0) = R y(t; R y0)``.
_REVERSAL = np.array([-1.0, -1.0, -1.0, 1.0, 1.0, 1.0])


_I6 = np.eye(6)


# ----------------------------------------------------------------------------- helpers
@checks_body
def middle_axis_rate(body: RigidBody) -> float:
    """``sigma = sqrt((b - c)(c - a))``: the exponent of the rotation about z is ``sigma G``.

    Raises ``ValueError`` unless ``z`` is the middle axis of inertia.

    Examples
    --------
    >>> round(middle_axis_rate(RigidBody.paper()), 12)
    0.049792959773
    """
    return body.require_middle_axis("a hyperbolic rotation about the z axis")


@checks_body
def rotation_energy(body: RigidBody, G: float = 1.0) -> float:
    """``h = c G^2 / 2``: the energy of the permanent rotation about z with ``|G| = G``.

    On this level the unperturbed separatrices of the Hess chart have ``J2 = G``.
    """
    G = float(G)
    if not (math.isfinite(G) and G > 0.0):
        raise ValueError(f"G must be finite and > 0, got {G!r}")
    return 0.5 * body.c * G * G


def gamma_phase(y: ArrayLike) -> NDArray[np.float64]:
    """``psi = atan2(gamma1, gamma2)`` in ``[0, 2 pi)``, the section angle of this module."""
    arr = as_state(y)
    return np.mod(np.arctan2(arr[..., 3], arr[..., 4]), 2.0 * np.pi)


def section_coords(y: ArrayLike) -> NDArray[np.float64]:
    """``(x1, x2) = (G1, G2)/|G|`` of Euler-Poisson states, shape ``(..., 2)``."""
    arr = as_state(y)
    G = np.linalg.norm(arr[..., :3], axis=-1)
    return arr[..., :2] / G[..., None]


def _coords_jacobian(y: NDArray[np.float64]) -> NDArray[np.float64]:
    """``d(x1, x2)/dy`` (2, 6) of :func:`section_coords`."""
    Gv = y[:3]
    G = float(np.linalg.norm(Gv))
    J = np.zeros((2, 6))
    J[:, :3] = -np.outer(Gv[:2], Gv) / G**3
    J[0, 0] += 1.0 / G
    J[1, 1] += 1.0 / G
    return J


@dataclass(frozen=True)
class RotationSection:
    """The section ``psi = psi0`` near the rotation about ``sign * z``.

    Parameters
    ----------
    psi0 : float
        Value of ``psi = atan2(gamma1, gamma2)`` (reduced to ``[0, 2 pi)``).
    sign : {+1, -1}
        Sign of ``L = G3`` at the rotation: ``+1`` for ``L = +G`` (``J1 = J2``),
        ``-1`` for ``L = -G`` (``J1 = 0``). The section is crossed with
        ``dpsi/dt = c G3`` of that sign.

    Examples
    --------
    >>> RotationSection(0.0, -1)
    RotationSection(psi0=0.0, sign=-1)
    """

    psi0: float = 0.0
    sign: int = 1

    def __post_init__(self) -> None:
        try:
            v = float(self.psi0)
        except (TypeError, ValueError):
            raise ValueError(f"psi0 must be a number, got {self.psi0!r}") from None
        if not math.isfinite(v):
            raise ValueError(f"psi0 must be finite, got {v!r}")
        if self.sign not in (1, -1):
            raise ValueError(f"sign must be +1 (rotation L = +G) or -1 (L = -G), "
                             f"got {self.sign!r}")
        object.__setattr__(self, "psi0", math.remainder(v, 2 * math.pi) % (2 * math.pi))

    def attrs(self) -> dict[str, Any]:
        return {"section": "psi = atan2(gamma1, gamma2) = psi0, crossed with "
                           "sign(dpsi/dt) = sign(L)",
                "section_psi0": self.psi0, "rotation_sign": self.sign}


# ----------------------------------------------------------------------------- heyoka
_SECTION_KINDS = ("psi", "L")


@cache
def _heyoka_system() -> tuple[Any, tuple[Any, ...], tuple[Any, ...]]:
    """``(hy, (var, rhs) pairs of (1), section functions (f_psi, w_psi, f_L))``.

    Built from the SymPy field of :mod:`andoyer.symbolic.hamiltonian` (nothing typed):
    runtime parameters ``par[0..6] = (a, b, c, mu, e1, e2, e3)``,
    ``par[7], par[8] = cos psi0, sin psi0``.
    """
    from andoyer.integrate.engines.heyoka_symbolic import heyoka_state_vars, heyoka_system
    from andoyer.integrate.engines.lazy import heyoka as hy

    system = heyoka_system()  # the one SymPy -> heyoka builder
    _, _, G3, g1, g2, _ = heyoka_state_vars()
    cpsi, spsi = hy.par[7], hy.par[8]
    f_psi = g1 * cpsi - g2 * spsi   # = rho sin(psi - psi0)
    w_psi = g1 * spsi + g2 * cpsi   # = rho cos(psi - psi0) > 0 on the crossing
    return hy, system, (f_psi, w_psi, G3)


class _Stop:
    """Terminal-event callback: ``True`` (go on) for the start point and the antipode."""

    def __init__(self, kind: str) -> None:
        self.kind = kind

    def __call__(self, ta: Any, d_sgn: int) -> bool:
        if abs(ta.time) <= T_START:
            return True
        if self.kind == "psi":
            y, p = ta.state, ta.pars
            return not (y[3] * p[8] + y[4] * p[7] > 0.0)
        return False


@cache
def _integrator(kind: str, direction: int, variational: bool, tol: float,
                long_double: bool) -> Any:
    """A compiled heyoka integrator of (1) that stops at a crossing of section ``kind``."""
    hy, system, (f_psi, _, f_L) = _heyoka_system()
    f = f_psi if kind == "psi" else f_L
    dirs = {1: hy.event_direction.positive, -1: hy.event_direction.negative}
    fp: Any = np.longdouble if long_double else float
    ev = hy.t_event(f, callback=_Stop(kind), direction=dirs[direction], fp_type=fp)
    sys_: Any = list(system)
    n = 6
    if variational:
        sys_ = hy.var_ode_sys(sys_, hy.var_args.vars, order=1)
        n = 42
    # compact_mode for the variational system: it compiles in about a second instead of
    # about a minute, and it only runs over single periods (Newton).
    return hy.taylor_adaptive(sys_, np.zeros(n, dtype=fp), tol=fp(tol), t_events=[ev],
                              fp_type=fp, compact_mode=variational)


@dataclass(frozen=True)
class Crossing:
    """A crossing of a section found by :func:`flow_to_section`.

    ``y`` the Euler-Poisson state on the section, ``t`` the (signed) flight time,
    ``stm`` the state-transition matrix ``dy(t)/dy0`` (6, 6) if requested (else None).
    """

    y: NDArray[np.float64]
    t: float
    stm: NDArray[np.float64] | None = None


#: How each engine integrates the flow to a section (dataset provenance).
FLOW_ENGINES = {"heyoka": "heyoka (Taylor, variational equations by var_ode_sys)",
                "numba": "numba (DOP853, variational equations of the Jacobian derived by "
                         "SymPy)"}


def flow_engine(engine: str | None = None) -> str:
    """The engine of :func:`flow_to_section`: ``engine``, else heyoka where installed,
    else numba.

    >>> flow_engine("numba")
    'numba'
    """
    name = default_engine_name() if engine is None else engine
    if name not in FLOW_ENGINES:
        raise ValueError(f"engine must be 'heyoka' or 'numba', got {engine!r}")
    return name


def _pars(body: RigidBody, psi0: float) -> NDArray[np.float64]:
    return np.array([*body.params, math.cos(psi0), math.sin(psi0)])


@checks_body
def flow_to_section(body: RigidBody, y0: ArrayLike, kind: str, direction: int, *,
                    psi0: float = 0.0, backward: bool = False, t_max: float = 1e4,
                    tol: float = DEFAULT_TOL, stm: bool = False,
                    long_double: bool = False, engine: str | None = None) -> Crossing:
    """Integrate (1) from ``y0`` to the first crossing of a section.

    Parameters
    ----------
    body : RigidBody
    y0 : array_like, shape (6,)
        Euler-Poisson initial state.
    kind : {"psi", "L"}
        ``"psi"``: ``psi = psi0`` (:class:`RotationSection`, antipode excluded);
        ``"L"``: ``L = G3 = 0``.
    direction : {+1, -1}
        Sign of the time derivative of the section function at the crossing, in physical
        time (also when ``backward``).
    psi0 : float
        Section value for ``kind="psi"``.
    backward : bool
        Integrate towards negative times (the crossing time ``t`` is then negative).
    t_max : float
        Give up (``RuntimeError``) after ``|t| = t_max``.
    tol : float
        heyoka's tolerance (the numba route gets ``max(tol, NUMBA_TOL)``).
    stm : bool
        Also integrate the variational equations and return ``dy(t)/dy0``.
    long_double : bool
        Integrate in 80-bit extended precision (``numpy.longdouble``; heyoka only).
    engine : {"heyoka", "numba"}, optional
        Default: heyoka where installed, else numba (see the module notes).

    Returns
    -------
    Crossing
        The state is polished onto the section by one Newton step in time.
    """
    if kind not in _SECTION_KINDS:
        raise ValueError(f"kind must be one of {_SECTION_KINDS}, got {kind!r}")
    if direction not in (1, -1):
        raise ValueError(f"direction must be +1 or -1, got {direction!r}")
    y0 = as_state(y0, "y0").reshape(6)
    if not (math.isfinite(tol) and 0.0 < tol < 1e-3):
        raise ValueError(f"tol must lie in (0, 1e-3), got {tol!r}")
    name = flow_engine(engine)
    if name == "numba":
        if long_double:
            raise ValueError("long_double needs engine='heyoka' (the numba DOP853 runs in "
                             "double precision)")
        y, t, phi = _numba_crossing(body, y0, kind, direction, psi0, backward, t_max,
                                    max(float(tol), NUMBA_TOL), stm)
        return _polish(body, kind, psi0, y, t, phi)
    ta = _integrator(kind, direction, bool(stm), float(tol), bool(long_double))
    fp: Any = np.longdouble if long_double else float
    ta.time = fp(0.0)
    ta.state[:6] = y0
    if stm:
        ta.state[6:] = _I6.ravel()
    ta.pars[:] = _pars(body, psi0)[:np.shape(ta.pars)[0]]
    ta.reset_cooldowns()
    outcome = ta.propagate_until(fp(-t_max if backward else t_max))[0]
    from andoyer.integrate.engines.lazy import heyoka as hy

    if outcome in (hy.taylor_outcome.time_limit, hy.taylor_outcome.step_limit):
        raise RuntimeError(
            f"no crossing of the {kind!r} section within |t| = {t_max:g}: the orbit left "
            "the neighbourhood it was started in")
    if outcome == hy.taylor_outcome.err_nf_state:
        raise FloatingPointError("heyoka met a non-finite state")
    y = np.array(ta.state[:6], dtype=float)
    t = float(ta.time)
    phi = np.array(ta.state[6:], dtype=float).reshape(6, 6) if stm else None
    return _polish(body, kind, psi0, y, t, phi)


def _numba_crossing(body: RigidBody, y0: NDArray[np.float64], kind: str, direction: int,
                    psi0: float, backward: bool, t_max: float, tol: float, stm: bool
                    ) -> tuple[NDArray[np.float64], float, NDArray[np.float64] | None]:
    """The first crossing on the Numba DOP853 (backward by time reversal)."""
    from andoyer.errors import IntegrationError

    eng = resolve_engine("numba")
    event = SectionEvent("psi" if kind == "psi" else "L", psi0 if kind == "psi" else 0.0,
                         direction)
    tolerance = Tolerance.single(tol)
    params = body.engine_params
    if stm:
        c = eng.tangent(y0, np.eye(6), params, tolerance, event=event, n_crossings=1,
                        t_max=t_max, backward=backward, renormalise=False)
        if not c.ok[0]:
            raise IntegrationError("the numba DOP853 met a non-finite state")
        found, tc, z = int(c.count[0]), float(c.t[0, 0]), c.y[0, 0]
        phi: NDArray[np.float64] | None = np.ascontiguousarray(c.w[0, 0].T)
    else:
        cr = eng.crossings(y0[None], params, event, 1, t_max, tolerance, backward=backward)
        found, tc, z, phi = int(cr.count[0]), float(cr.t[0, 0]), cr.y[0, 0], None
    if found == 0:
        raise RuntimeError(
            f"no crossing of the {kind!r} section within |t| = {t_max:g}: the orbit left "
            "the neighbourhood it was started in")
    return z, tc, phi


def _polish(body: RigidBody, kind: str, psi0: float, y: NDArray[np.float64], t: float,
            phi: NDArray[np.float64] | None) -> Crossing:
    # One Newton step in time onto f = 0 (heyoka stops on the Taylor root; this removes
    # the rounding of the event time).
    F = vector_field(body, y)
    grad = _section_gradient(kind, psi0)
    fval = float(grad @ y) if kind == "psi" else float(y[2])
    dt = -fval / float(grad @ F)
    if abs(dt) < 1e-8:
        y = y + dt * F
        t += dt
    return Crossing(y, t, phi)


def _section_gradient(kind: str, psi0: float) -> NDArray[np.float64]:
    """Gradient of the (linear) section function in the Euler-Poisson variables."""
    g = np.zeros(6)
    if kind == "psi":
        g[3], g[4] = math.cos(psi0), -math.sin(psi0)
    else:
        g[2] = 1.0
    return g


@checks_body
def event_projector(body: RigidBody, y: NDArray[np.float64], kind: str,
                    psi0: float = 0.0) -> NDArray[np.float64]:
    """``I - F grad(f)^T / (grad(f), F)``: the event sensitivity at a crossing ``y``."""
    F = vector_field(body, y)
    grad = _section_gradient(kind, psi0)
    return _I6 - np.outer(F, grad) / float(grad @ F)


# ----------------------------------------------------------------------------- completion
def _unit_momentum(x: NDArray[np.float64], sign: int) -> tuple[NDArray[np.float64], float]:
    r2 = float(x[0] ** 2 + x[1] ** 2)
    if not r2 < 1.0:
        raise ValueError(f"section point (x1, x2) = ({x[0]:.6g}, {x[1]:.6g}) has "
                         "x1^2 + x2^2 >= 1: (x1, x2) = (G1, G2)/|G| must lie in the unit disc")
    n3 = sign * math.sqrt(1.0 - r2)
    return np.array([x[0], x[1], n3]), n3


def _assemble(n: NDArray[np.float64], G: float, gamma3: float, psi0: float
              ) -> NDArray[np.float64]:
    rho = math.sqrt(max(0.0, 1.0 - gamma3 * gamma3))
    return np.array([G * n[0], G * n[1], G * n[2], rho * math.sin(psi0),
                     rho * math.cos(psi0), gamma3])


@checks_body
def section_state(body: RigidBody, x: ArrayLike, h: float, M: float = 0.0,
                  section: RotationSection | None = None, *, jacobian: bool = False
                  ) -> Any:
    """The Euler-Poisson state on ``Sigma`` with section coordinates ``(x1, x2)``.

    Solves ``H(y) = h`` and ``(G, gamma) = M`` for ``|G|`` and ``gamma3`` with
    ``G = |G| (x1, x2, sign sqrt(1 - x1^2 - x2^2))`` and
    ``gamma = (sqrt(1 - gamma3^2) sin psi0, sqrt(1 - gamma3^2) cos psi0, gamma3)``
    (closed form at ``M = 0``, Newton otherwise).

    Parameters
    ----------
    body : RigidBody
    x : array_like, shape (2,)
        ``(G1, G2)/|G|``.
    h, M : float
        Energy and area constant of the level.
    section : RotationSection, optional
        Default ``RotationSection(0.0, +1)``.
    jacobian : bool
        Also return ``dy/dx`` (6, 2) from the implicit-function theorem.

    Returns
    -------
    y : ndarray (6,), or ``(y, dy/dx)``

    Examples
    --------
    >>> body = RigidBody.paper()
    >>> y = section_state(body, [0.0, 0.0], rotation_energy(body), 0.0,
    ...                   RotationSection(0.0, -1))
    >>> round(float(y[2]), 6), y[3:].tolist()   # the pendulum rotation L = -G, gamma = (0, 1, 0)
    (-0.985056, [0.0, 1.0, 0.0])
    """
    sec = RotationSection() if section is None else section
    xv = np.asarray(x, dtype=float).reshape(2)
    n, n3 = _unit_momentum(xv, sec.sign)
    s0, c0 = math.sin(sec.psi0), math.cos(sec.psi0)
    a, b, c, mu, e1, e2, e3 = body.params
    k = a * n[0] ** 2 + b * n[1] ** 2 + c * n3 * n3
    # M = 0: (n, gamma) = 0 fixes gamma3; then H = h fixes |G|.
    gamma3 = math.sin(math.atan(-(n[0] * s0 + n[1] * c0) / n3))

    def energy_G(gamma3: float) -> float:
        rho = math.sqrt(max(0.0, 1.0 - gamma3 * gamma3))
        V = mu * (e1 * rho * s0 + e2 * rho * c0 + e3 * gamma3)
        if not h - V > 0.0:
            raise ValueError(
                f"no state on the level H = {h:g} at this section point: the potential "
                f"mu (r, gamma) = {V:.6g} exceeds h (raise the energy or lower mu)")
        return math.sqrt(2.0 * (h - V) / k)

    G = energy_G(gamma3)
    if M != 0.0:
        gamma3 = max(-0.999, min(0.999, M / (sec.sign * G)))
        for _ in range(60):
            y = _assemble(n, G, gamma3, sec.psi0)
            F = np.array([0.5 * G * G * k + mu * (e1 * y[3] + e2 * y[4] + e3 * y[5]) - h,
                          float(y[:3] @ y[3:]) - M])
            A = _implicit_matrices(body, y, n, G, sec.psi0)[0]
            dz = np.linalg.solve(A, -F)
            G, gamma3 = G + dz[0], gamma3 + dz[1]
            if not (G > 0.0 and abs(gamma3) < 1.0):
                raise ValueError(f"cannot complete the state at (x1, x2) = {tuple(xv)} on "
                                 f"H = {h:g}, M = {M:g}: |M| too close to |G|?")
            if abs(dz[0]) <= 1e-16 * G and abs(dz[1]) <= 1e-16:
                break
    y = _assemble(n, G, gamma3, sec.psi0)
    if not jacobian:
        return y
    A, B = _implicit_matrices(body, y, n, G, sec.psi0, with_x=True)
    dz_dx = -np.linalg.solve(A, B)
    return y, _lift_partials(y, n, G, sec.psi0)[0] + _lift_partials(y, n, G, sec.psi0)[1] @ dz_dx


def _lift_partials(y: NDArray[np.float64], n: NDArray[np.float64], G: float, psi0: float
                   ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """``(dy/dx at fixed (|G|, gamma3), dy/d(|G|, gamma3) at fixed x)``."""
    n3 = n[2]
    dY_dx = np.zeros((6, 2))
    dY_dx[0, 0] = G
    dY_dx[1, 1] = G
    dY_dx[2, 0] = -G * n[0] / n3
    dY_dx[2, 1] = -G * n[1] / n3
    rho = math.sqrt(max(1e-300, 1.0 - y[5] ** 2))
    dY_dz = np.zeros((6, 2))
    dY_dz[:3, 0] = n
    dY_dz[3, 1] = -y[5] / rho * math.sin(psi0)
    dY_dz[4, 1] = -y[5] / rho * math.cos(psi0)
    dY_dz[5, 1] = 1.0
    return dY_dx, dY_dz


def _constraint_gradients(body: RigidBody, y: NDArray[np.float64]) -> NDArray[np.float64]:
    """Gradients of ``H`` and ``(G, gamma)`` in the Euler-Poisson variables, (2, 6)."""
    a, b, c, mu, e1, e2, e3 = body.params
    return np.array([[a * y[0], b * y[1], c * y[2], mu * e1, mu * e2, mu * e3],
                     [y[3], y[4], y[5], y[0], y[1], y[2]]])


def _implicit_matrices(body: RigidBody, y: NDArray[np.float64], n: NDArray[np.float64],
                       G: float, psi0: float, with_x: bool = False) -> Any:
    dY_dx, dY_dz = _lift_partials(y, n, G, psi0)
    grad = _constraint_gradients(body, y)
    A = grad @ dY_dz
    return (A, grad @ dY_dx) if with_x else (A,)


# ----------------------------------------------------------------------------- return map
@dataclass(frozen=True)
class SectionReturn:
    """One application of the section map: image ``x``, state ``y``, return time ``T``,
    Jacobian ``DP`` (2, 2) and state-transition matrix ``stm`` (6, 6), or None."""

    x: NDArray[np.float64]
    y: NDArray[np.float64]
    T: float
    DP: NDArray[np.float64] | None
    stm: NDArray[np.float64] | None


@checks_body
def return_map(body: RigidBody, x: ArrayLike, h: float, M: float = 0.0,
               section: RotationSection | None = None, *, jacobian: bool = True,
               tol: float = DEFAULT_TOL, long_double: bool = False,
               engine: str | None = None) -> SectionReturn:
    """The Poincare map of ``Sigma = {psi = psi0}`` in the coordinates ``(G1, G2)/|G|``.

    Returns an object with ``x`` (the image), ``y`` (its Euler-Poisson state), ``T``
    (return time), ``DP`` (the 2 x 2 Jacobian, from the variational equations and the
    event sensitivity, or None) and ``stm`` (the 6 x 6 state-transition matrix).
    ``engine`` as in :func:`flow_to_section`.
    """
    sec = RotationSection() if section is None else section
    y0, dy_dx = section_state(body, x, h, M, sec, jacobian=True)
    T0 = 2.0 * math.pi / (body.c * float(np.linalg.norm(y0[:3])))
    cr = flow_to_section(body, y0, "psi", sec.sign, psi0=sec.psi0, t_max=20.0 * T0 + 100.0,
                         tol=tol, stm=jacobian, long_double=long_double, engine=engine)
    x1 = section_coords(cr.y)
    if not jacobian:
        return SectionReturn(x1, cr.y, cr.t, None, None)
    assert cr.stm is not None
    DP = _coords_jacobian(cr.y) @ event_projector(body, cr.y, "psi", sec.psi0) @ cr.stm @ dy_dx
    return SectionReturn(x1, cr.y, cr.t, DP, cr.stm)
