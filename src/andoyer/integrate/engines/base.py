r"""The seam between the friendly layers and the integration engines.

Every flow the science uses -- orbits, section crossings, tangent flows (chaos
indicators, monodromy matrices, the Jacobian of a section map), forward or backward
in time -- goes through an :class:`Engine`. Analysis code never imports an engine
module, heyoka or a kernel of its own: it asks the registry
(:func:`andoyer.integrate.engines.resolve_engine`) for an engine, checks its
:attr:`~Engine.capabilities` and calls the methods below.

The contract of an engine
=========================

An engine works on plain float arrays of Euler-Poisson states
``y = (G1, G2, G3, gamma1, gamma2, gamma3)`` (the regular, global description of (1))
and knows nothing of datasets, charts or bodies.

**What an engine implements.** A class deriving from :class:`EngineBase` with

``name`` : str
    Its registry name (``"heyoka"``, ``"numba"``, ...).
``capabilities`` : frozenset of :class:`Capability`
    What it can do; callers check these, never the name. ``PROPAGATE`` and
    ``CROSSINGS`` are required; ``TANGENT`` needs :meth:`~EngineBase._tangent`,
    ``TANGENT_CROSSINGS`` needs :meth:`~EngineBase._tangent_crossings`,
    ``EXTENDED_PRECISION`` means ``extended_precision=True`` is honoured by
    :meth:`~EngineBase._tangent_crossings`. ``BACKWARD`` is given to every engine by
    the base class (time reversal, below); an engine with a native backward flow names
    the methods that take negative times in ``native_backward`` (e.g.
    ``frozenset({"tangent_crossings"})``) and receives them itself.
``_propagate(y0, t, par, tolerance)``
    ``y0`` (n, 6) finite, ``t`` (m,) strictly monotonic with ``t[0]`` the initial time
    (increasing; decreasing too if ``"propagate"`` is ``native_backward``), ``par``
    the runtime parameters
    (:func:`runtime_parameters`), ``tolerance`` a :class:`Tolerance`. Returns the
    states (n, m, 6); ``[:, 0]`` must equal ``y0``.
``_crossings(y0, par, event, n_crossings, t_max, tolerance)``
    The first ``n_crossings`` roots after ``t = T_START`` (:mod:`andoyer.kernels.constants`)
    of the section function ``f`` of ``event`` (a :class:`SectionEvent`) in its
    direction with margin ``w > 0``, integrating at most to ``t_max > 0``; each root
    located so that ``|f| <= 1e-12`` (relative to the scale of f). If ``"crossings"``
    is ``native_backward`` it also receives ``t_max < 0`` (a backward flow: roots at
    ``t < -T_START``, ``event.direction`` in physical time). Returns
    :class:`Crossings` (NaN-padded beyond ``count``).
``_tangent(y0, w0, t, par, tolerance, renormalise, scale)`` (for ``TANGENT``)
    ``w0`` (n, k, 6) non-zero vectors, ``1 <= k <= 6``; ``t`` as for ``_propagate``.
    Integrates (1) with its variational equations ``dw/dt = J(y) w`` and returns a
    :class:`TangentFlow` (``u = w/|w|``, ``rho = ln|w|``; ``rho`` starts at
    ``ln|w0|``). With ``renormalise`` the vectors are carried at unit length while
    integrating (``du/dt = J u - f u``, ``drho/dt = f``, ``f = u.Ju/u.u``: no overflow
    however long the flight) and the MEGNO quadratures of the first vector are
    returned; without, the engine may integrate ``w`` itself (short flights:
    monodromy matrices) and ``megno`` may be None. ``scale`` is the ``T`` of
    ``par[PAR["inv_scale"]]`` (for engines that integrate scaled quadratures). A
    failed orbit has ``ok`` False and NaN (no exception: a chaos map keeps its other
    points).
``_tangent_crossings(y0, w0, par, event, n_crossings, t_max, tolerance, extended_precision)``
    (for ``TANGENT_CROSSINGS``) the crossings of ``_crossings`` with the tangent
    vectors there (the tangent flow at the crossing *time*); ``megno`` is None.
``_attitude(z0, t, par, tolerance)`` (for ``ATTITUDE``)
    ``z0`` (n, 10): the state with the attitude quaternion ``(G, gamma, q0, q1, q2, q3)``
    (scalar first, body -> space, :mod:`andoyer.charts.rotation`); integrates (1) with
    ``dq/dt = q (x) (0, omega) / 2``, ``omega = I G`` (the SymPy field
    :func:`andoyer.symbolic.attitude.attitude_field`, generated as
    :func:`andoyer.kernels.generated.attitude_field`), ``t`` as for ``_propagate``.
    Returns (n, m, 10) with ``[:, 0]`` equal to ``z0``; the quaternion's length is an
    integral of the flow and is not renormalised by the engine.

A failed integration (non-finite state, too many steps) raises
:class:`~andoyer.errors.IntegrationError` (a ``FloatingPointError``) from
``_propagate`` and ``_crossings``.

**What the base class provides** (:class:`EngineBase`): the public methods
:meth:`~EngineBase.propagate`, :meth:`~EngineBase.crossings` and
:meth:`~EngineBase.tangent`, which

* check and shape the arrays (a state ``(6,)`` is one orbit), the event, the counts
  and the :class:`Tolerance`, and answer empty inputs without calling the engine;
* build the runtime parameters once (:func:`runtime_parameters`: the one owner of the
  ``par`` layout, :data:`PARAMETERS`);
* refuse a capability the engine lacks (``NotImplementedError`` naming it);
* run backward flows by the time reversal of (1): with ``R = diag(-1, -1, -1, 1, 1, 1)``,
  ``y(-t; y0) = R y(t; R y0)`` and ``dy(-t)/dy0 = R Phi(t) R``, so a forward-only
  engine integrates ``R y0`` forward and the base maps the result back. A section is
  reversed by :data:`REVERSIBLE`: the sections whose function keeps or flips its sign
  under ``R`` (momentum and gamma components, ``|G|``, ``psi``); crossings keep their
  direction *in physical time* (negative ``t`` for a backward flow). Callers ask for
  a backward flow with decreasing ``t`` or ``backward=True``.

An engine is registered by name in :data:`andoyer.integrate.engines.ENGINES`; the
contract tests (``tests/integrate/engines/test_engine_contract.py``) then run every
capability it declares, against every other engine that has it.

Runtime parameters
==================
One vector ``par`` serves every compiled integrator (:data:`PARAMETERS`): the body
``(a, b, c, mu, e1, e2, e3, phi0)`` (:attr:`RigidBody.engine_params`), the section
``(value, cos value, sin value)``, ``(cos phi0, sin phi0)`` and the MEGNO scale
``1/T`` of the tangent flows. Engines index it by name through :data:`PAR`.
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass
from typing import Any, ClassVar, NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from andoyer.kernels.generated import EXTRA_SECTION_KINDS, SECTION_KINDS
from andoyer.validation import integer, positive

__all__ = [
    "Capability", "SectionEvent", "Tolerance", "Crossings", "TangentFlow", "Engine",
    "EngineBase", "PARAMETERS", "PAR", "runtime_parameters", "REVERSIBLE", "REVERSAL",
    "TOLERANCE_FACTOR", "check_tolerance_factor", "Params", "ALL_KINDS", "unit_vectors",
    "ATTITUDE_REVERSAL",
]

#: (a, b, c, mu, e1, e2, e3, phi0)
Params = tuple[float, float, float, float, float, float, float, float]

#: Every section coordinate an engine can stop on (index = ``SectionEvent.kind``).
ALL_KINDS: tuple[str, ...] = (*SECTION_KINDS, *EXTRA_SECTION_KINDS)

#: The runtime parameters ``par[i]`` of every engine, in this order.
PARAMETERS: tuple[str, ...] = ("a", "b", "c", "mu", "e1", "e2", "e3", "phi0", "value",
                               "cv", "sv", "cos_phi0", "sin_phi0", "inv_scale")
#: Name -> index into :data:`PARAMETERS`.
PAR: dict[str, int] = {name: i for i, name in enumerate(PARAMETERS)}

#: Time reversal of (1): ``y(-t; y0) = R y(t; R y0)``.
REVERSAL = np.array([-1.0, -1.0, -1.0, 1.0, 1.0, 1.0])
#: Time reversal of (1) with the attitude: ``omega`` flips with ``G`` and ``dq/dt`` with
#: the time, so the quaternion is carried over unchanged (:meth:`EngineBase.attitude`).
ATTITUDE_REVERSAL = np.concatenate([REVERSAL, np.ones(4)])

#: Section -> sign ``s`` with ``f(R y; s value) = s f(y; value)``: the sections a
#: forward-only engine can run backward (momentum components flip, gamma and ``|G|``
#: and the phase ``psi`` of gamma do not).
REVERSIBLE: dict[str, int] = {"G1": -1, "G2": -1, "G3": -1, "L": -1, "gamma1": 1,
                              "gamma2": 1, "gamma3": 1, "G": 1, "J2": 1, "psi": 1}


class Capability(enum.Enum):
    """What an engine can do (:attr:`Engine.capabilities`)."""

    #: States at output times (:meth:`EngineBase.propagate`).
    PROPAGATE = "propagate"
    #: Section crossings (:meth:`EngineBase.crossings`).
    CROSSINGS = "crossings"
    #: Negative times: propagate to decreasing times, ``backward=True`` crossings.
    BACKWARD = "backward"
    #: Tangent vectors at output times, renormalised, with MEGNO (:meth:`EngineBase.tangent`).
    TANGENT = "tangent"
    #: Tangent vectors at section crossings (``tangent(event=...)``).
    TANGENT_CROSSINGS = "tangent_crossings"
    #: ``extended_precision=True`` (80-bit long double) for tangent crossings.
    EXTENDED_PRECISION = "extended_precision"
    #: The attitude quaternion integrated with the state (:meth:`EngineBase.attitude`).
    ATTITUDE = "attitude"

    def __str__(self) -> str:
        return self.value

    @property
    def description(self) -> str:
        """What the capability lets an engine do, as a verb phrase."""
        return _DESCRIPTIONS[self]


_DESCRIPTIONS = {
    Capability.PROPAGATE: "propagate orbits",
    Capability.CROSSINGS: "find section crossings",
    Capability.BACKWARD: "integrate backward in time",
    Capability.TANGENT: "integrate tangent vectors",
    Capability.TANGENT_CROSSINGS: "find section crossings with tangent vectors",
    Capability.EXTENDED_PRECISION: "integrate in extended precision",
    Capability.ATTITUDE: "integrate the attitude (orientation quaternion)",
}


# ----------------------------------------------------------------------------- values
_TOL_MIN, _TOL_MAX = 1e-16, 1e-3


@dataclass(frozen=True)
class Tolerance:
    """The accuracy asked of an engine: local error ``<= atol + rtol |y|`` per step.

    The one check of tolerances: ``rtol`` in ``[1e-16, 1e-3]`` and ``atol`` in
    ``(0, 1e-3]``. Methods that take one number (chaos indicators, periodic orbits,
    manifolds, Floquet: ``tol``) use :meth:`single`, ``rtol = atol = tol``. How an
    engine meets it is its own business: heyoka's single Taylor tolerance is
    :attr:`tol` = ``min(rtol, atol)``; the DOP853 engines give their controller
    :data:`TOLERANCE_FACTOR` times both.

    Examples
    --------
    >>> Tolerance.single(1e-12)
    Tolerance(rtol=1e-12, atol=1e-12)
    >>> Tolerance(1e-10, 1e-12).tol
    1e-12
    >>> Tolerance.single(0.1)
    Traceback (most recent call last):
    ...
    ValueError: tol = 0.1 is out of range [1e-16, 1e-3]
    """

    rtol: float = 1e-12
    atol: float = 1e-12

    def __post_init__(self) -> None:
        for name in ("rtol", "atol"):
            object.__setattr__(self, name, _tolerance_value(name, getattr(self, name),
                                                            _TOL_MIN if name == "rtol" else 0.0))

    @classmethod
    def single(cls, tol: Any, name: str = "tol") -> Tolerance:
        """``rtol = atol = tol``, with errors naming the user's argument ``name``."""
        t = _tolerance_value(name, tol, _TOL_MIN)
        return cls(t, t)

    @property
    def tol(self) -> float:
        """One number for a method with a single tolerance: ``min(rtol, atol)``."""
        return min(self.rtol, self.atol)

    def scaled(self, factor: float) -> tuple[float, float]:
        """``(factor rtol, factor atol)``: what a DOP853 controller is given."""
        return factor * self.rtol, factor * self.atol


def _tolerance_value(name: str, value: Any, low: float) -> float:
    v = positive(name, value)
    if not (low <= v <= _TOL_MAX):
        span = "[1e-16, 1e-3]" if low > 0.0 else "(0, 1e-3]"
        raise ValueError(f"{name} = {v:g} is out of range {span}")
    return v


@dataclass(frozen=True)
class SectionEvent:
    """A section ``coord = value`` crossed in ``direction`` (as diffrax's ``Event``).

    Parameters
    ----------
    coord : str
        A name of :data:`ALL_KINDS` (``"G3"``, ``"theta2"``, ``"psi"``, ...): the
        section function ``f`` and margin ``w`` are
        :func:`andoyer.kernels.generated.section` of that kind.
    value : float
        The section value (an angle in rad for angle sections).
    direction : {+1, -1, 0}
        Sign of ``df/dt`` at the crossing in physical time (0: both).

    Examples
    --------
    >>> ev = SectionEvent("G3", 0.0, 1)
    >>> ev.kind, ev.reversed()
    (2, SectionEvent(coord='G3', value=-0.0, direction=1))
    """

    coord: str
    value: float = 0.0
    direction: int = 0

    def __post_init__(self) -> None:
        if self.coord not in ALL_KINDS:
            raise ValueError(f"unknown section coordinate {self.coord!r}; choose one of "
                             f"{', '.join(ALL_KINDS)}")
        v = float(self.value)
        if not math.isfinite(v):
            raise ValueError(f"section value must be finite, got {self.value!r}")
        object.__setattr__(self, "value", v)
        if isinstance(self.direction, bool) or self.direction not in (-1, 0, 1):
            raise ValueError(f"direction must be -1, 0 or +1, got {self.direction!r}")
        object.__setattr__(self, "direction", int(self.direction))

    @classmethod
    def from_kind(cls, kind: int, value: float = 0.0, direction: int = 0) -> SectionEvent:
        """The event of section index ``kind`` (into :data:`ALL_KINDS`)."""
        k = integer("kind", kind, 0, len(ALL_KINDS) - 1)
        return cls(ALL_KINDS[k], value, direction)

    @property
    def kind(self) -> int:
        """Index of :attr:`coord` into :data:`ALL_KINDS` (the kernels' section kind)."""
        return ALL_KINDS.index(self.coord)

    def reversed(self) -> SectionEvent:
        """The event that the reversed orbit ``R y(-t)`` crosses where ``y`` crosses this
        one (see the module notes); ``ValueError`` for a section without that symmetry."""
        s = REVERSIBLE.get(self.coord)
        if s is None:
            raise ValueError(
                f"a backward flow to the {self.coord!r} section needs an engine with a "
                f"native backward flow; time reversal maps only "
                f"{', '.join(REVERSIBLE)} sections onto themselves")
        return SectionEvent(self.coord, s * self.value, -s * self.direction)


def runtime_parameters(params: ArrayLike, event: SectionEvent | None = None,
                       scale: float = 1.0) -> NDArray[np.float64]:
    """The runtime parameters :data:`PARAMETERS` of a body, a section and a scale.

    The one owner of the ``par`` layout of every engine.

    Parameters
    ----------
    params : sequence of 8 floats
        ``(a, b, c, mu, e1, e2, e3, phi0)`` (:attr:`RigidBody.engine_params`).
    event : SectionEvent, optional
        Its value fills ``value, cos value, sin value`` (0, 1, 0 without).
    scale : float
        ``T`` of the MEGNO quadratures (``par[PAR["inv_scale"]] = 1/T``).

    Examples
    --------
    >>> runtime_parameters((0.4, 0.5, 0.5, 0.01, 1.0, 0.0, 0.0, 0.0))[-6:].tolist()
    [0.0, 1.0, 0.0, 1.0, 0.0, 1.0]
    """
    p = np.asarray(params, dtype=np.float64).reshape(-1)
    if p.shape != (8,):
        raise ValueError("params must be (a, b, c, mu, e1, e2, e3, phi0), "
                         f"got {p.size} values")
    value = 0.0 if event is None else event.value
    scale = positive("scale", scale)
    phi0 = float(p[7])
    return np.array([*p.tolist(), value, math.cos(value), math.sin(value),
                     math.cos(phi0), math.sin(phi0), 1.0 / scale])


# ----------------------------------------------------------------------------- results
class Crossings(NamedTuple):
    """What :meth:`Engine.crossings` returns."""

    t: NDArray[np.float64]  # (n, n_crossings), NaN where an orbit had fewer crossings
    y: NDArray[np.float64]  # (n, n_crossings, 6), NaN-padded likewise
    count: NDArray[np.int64]  # type: ignore[assignment]  # (n,); shadows tuple.count


class TangentFlow(NamedTuple):
    """What :meth:`Engine.tangent` returns (``n`` orbits, ``m`` rows, ``k`` vectors).

    The tangent vectors are ``w_i = exp(rho_i) u_i`` (:attr:`w`) with ``u_i`` of unit
    length, ``w_i(0)`` the given vectors. Rows are the output times, or the crossings
    (NaN-padded beyond ``count``) when an event was given.
    """

    t: NDArray[np.float64]  # (n, m): output times, or crossing times
    y: NDArray[np.float64]  # (n, m, 6): Euler-Poisson states
    u: NDArray[np.float64]  # (n, m, k, 6): unit tangent vectors w_i / |w_i|
    rho: NDArray[np.float64]  # (n, m, k): ln |w_i|
    #: (n, m, 2) MEGNO quadratures of the first vector, ``int_0^t (s + delta) f ds`` and
    #: ``int_0^t 2 num / (s + delta) ds`` with ``f = d rho_1/dt`` and ``delta``
    #: :data:`andoyer.kernels.tangent.MEGNO_DELTA`; None at crossings and backward.
    megno: NDArray[np.float64] | None
    count: NDArray[np.int64]  # type: ignore[assignment]  # (n,)
    ok: NDArray[np.bool_]  # (n,): False where the integration failed (NaN there)

    @property
    def w(self) -> NDArray[np.float64]:
        """The tangent vectors ``exp(rho_i) u_i``, shape (n, m, k, 6)."""
        return np.exp(self.rho)[..., None] * self.u


# ----------------------------------------------------------------------------- protocol
#: Ratio of the tolerance given to the DOP853 controller to the accuracy an engine is
#: asked for (:class:`Tolerance`). The controller bounds an *estimate* of each step's
#: local error by ``atol + rtol |y|``; the integrals then drift linearly, by ~1e-13 per
#: time unit at rtol = atol = 1e-12 for a heavy top (mu ~ 0.5, ``|G| ~ 1``): 1e-9 at
#: t = 1e4. With the factor the drift of H, (G, gamma) and ``|gamma|^2`` stays below
#: ~2e-11 over t = 1e4 at a requested 1e-12 (paper's body and mu = 0.5, 0.7 bodies, 18
#: orbits each), for ~1.6x the steps. 0.025 keeps a requested 1e-12 above SciPy's floor
#: rtol >= 100 eps. The kernels never apply it: the engines do (numba and scipy).
TOLERANCE_FACTOR = 0.025


def check_tolerance_factor(tolerance_factor: float) -> float:
    """Validate a DOP853 engine's ``tolerance_factor`` (in (0, 1])."""
    if not 0.0 < tolerance_factor <= 1.0:
        raise ValueError(f"tolerance_factor must be in (0, 1], got {tolerance_factor!r}")
    return float(tolerance_factor)


def _states(y0: ArrayLike, name: str = "y0") -> NDArray[np.float64]:
    y = np.asarray(y0, dtype=np.float64)
    if y.ndim == 1:
        y = y[None]
    if y.ndim != 2 or y.shape[1] != 6:
        raise ValueError(f"{name} must have shape (6,) or (n, 6), got {np.shape(y0)}")
    return np.ascontiguousarray(y)


def _times(t: ArrayLike, backward_ok: bool = True) -> NDArray[np.float64]:
    times = np.ascontiguousarray(t, dtype=np.float64)
    if times.ndim != 1:
        raise ValueError(f"t must have shape (m,), got {times.shape}")
    if not np.all(np.isfinite(times)):
        raise ValueError("t must be finite")
    return times


def _vectors(w0: ArrayLike, n: int) -> NDArray[np.float64]:
    W = np.asarray(w0, dtype=np.float64)
    if W.ndim == 1:
        W = W[None]
    if W.ndim == 2:  # the same vectors for every orbit
        W = W[None]
    if W.ndim != 3 or W.shape[2] != 6 or W.shape[0] not in (1, n):
        raise ValueError(f"w0 must have shape (6,), (k, 6) or (n, k, 6) with n = {n} "
                         f"orbits, got {np.shape(w0)}")
    if not 1 <= W.shape[1] <= 6:
        raise ValueError(f"between 1 and 6 tangent vectors per orbit, got {W.shape[1]}")
    return np.ascontiguousarray(np.broadcast_to(W, (n, W.shape[1], 6)))


def _reverse_flow(flow: TangentFlow, sign: float) -> TangentFlow:
    """A tangent flow of ``R y0, R w0`` forward, mapped to the backward flow of ``y0``."""
    return flow._replace(t=sign * flow.t, y=REVERSAL * flow.y, u=REVERSAL * flow.u,
                         megno=None)


class EngineBase:
    """The base of every engine: validation, parameters, capabilities, time reversal.

    See the module docstring for the contract; subclasses implement ``_propagate``,
    ``_crossings`` and, with the matching capability, ``_tangent`` and
    ``_tangent_crossings``.
    """

    name: ClassVar[str] = ""
    capabilities: ClassVar[frozenset[Capability]] = frozenset()
    #: How the engine builds its tangent flows (for datasets' provenance).
    tangent_method: ClassVar[str] = ""
    #: The finest accuracy the engine honours (:meth:`attainable`); a DOP853 in double
    #: precision cannot resolve a local error below its ``TOLERANCE_FACTOR * tol``.
    min_tolerance: ClassVar[float] = 0.0
    #: The methods (``"propagate"``, ``"crossings"``, ``"tangent"``,
    #: ``"tangent_crossings"``) whose ``_`` implementation runs backward itself; the
    #: others are run backward by time reversal.
    native_backward: ClassVar[frozenset[str]] = frozenset()

    # -- what subclasses implement ------------------------------------------------
    def _propagate(self, y0: NDArray[np.float64], t: NDArray[np.float64],
                   par: NDArray[np.float64], tolerance: Tolerance) -> NDArray[np.float64]:
        raise NotImplementedError

    def _crossings(self, y0: NDArray[np.float64], par: NDArray[np.float64],
                   event: SectionEvent, n_crossings: int, t_max: float,
                   tolerance: Tolerance) -> Crossings:
        raise NotImplementedError

    def _tangent(self, y0: NDArray[np.float64], w0: NDArray[np.float64],
                 t: NDArray[np.float64], par: NDArray[np.float64], tolerance: Tolerance,
                 renormalise: bool, scale: float) -> TangentFlow:
        raise NotImplementedError

    def _tangent_crossings(self, y0: NDArray[np.float64], w0: NDArray[np.float64],
                           par: NDArray[np.float64], event: SectionEvent, n_crossings: int,
                           t_max: float, tolerance: Tolerance,
                           extended_precision: bool) -> TangentFlow:
        raise NotImplementedError

    def _attitude(self, z0: NDArray[np.float64], t: NDArray[np.float64],
                  par: NDArray[np.float64], tolerance: Tolerance) -> NDArray[np.float64]:
        raise NotImplementedError

    def warm_up(self, capability: Capability, tolerance: Tolerance, *, n: int = 1,
                k: int = 1) -> tuple[str, float]:
        """Prepare the code of ``capability`` for ``n`` orbits with ``k`` tangent vectors
        before a timed or progress-bar run: ``(source, seconds)``. Engines that compile
        per setting override it; the default has nothing to do (``"ready"``)."""
        self.require(capability)
        return "ready", 0.0

    def attainable(self, tolerance: Tolerance) -> Tolerance:
        """``tolerance`` raised to :attr:`min_tolerance`: what methods that ask for the
        finest accuracy (``tol = 1e-15`` for periodic orbits, Floquet) give an engine.

        >>> from andoyer.integrate.engines import engine_class
        >>> engine_class("numba")().attainable(Tolerance.single(1e-15))
        Tolerance(rtol=1e-13, atol=1e-13)
        """
        floor = self.min_tolerance
        if tolerance.rtol >= floor and tolerance.atol >= floor:
            return tolerance
        return Tolerance(max(tolerance.rtol, floor), max(tolerance.atol, floor))

    def clear_memory_cache(self) -> None:
        """Forget code compiled in this process (engines with caches override it)."""

    def provenance(self) -> dict[str, str]:
        """What a dataset records of the engine: its name, the versions of the packages
        it runs on, and how it builds tangent flows (:attr:`tangent_method`)."""
        return {"engine": self.name, **self.versions(),
                "tangent_method": self.tangent_method}

    def versions(self) -> dict[str, str]:
        """``{"<package>_version": version}`` of what the engine runs on."""
        return {}

    def for_ensemble(self, n: int) -> EngineBase:
        """This engine set up for batches of ``n`` orbits at a time (the same for every
        batch, so that how orbits are split into chunks cannot change round-off)."""
        return self

    # -- what the base provides ---------------------------------------------------
    def require(self, capability: Capability, what: str = "") -> None:
        """``NotImplementedError`` unless this engine has ``capability``."""
        if capability not in self.capabilities:
            able = ", ".join(sorted(_engines_with(capability))) or "none"
            raise NotImplementedError(
                f"engine {self.name!r} cannot {what or capability.description} "
                f"(capability {capability.value!r}); engines that can: {able}")

    def propagate(self, y0: ArrayLike, t: ArrayLike, params: ArrayLike,
                  tolerance: Tolerance) -> NDArray[np.float64]:
        """States at times ``t`` (m,) of the orbits from ``y0`` (n, 6): shape (n, m, 6).

        ``t[0]`` is the initial time; ``t`` increasing, or decreasing (a backward flow).
        """
        self.require(Capability.PROPAGATE)
        tol = _tolerance(tolerance)
        y = _states(y0)
        times = _times(t)
        if y.shape[0] == 0 or times.size == 0:
            return np.empty((y.shape[0], times.size, 6))
        par = runtime_parameters(params)
        step = np.diff(times)
        if np.all(step >= 0.0) or "propagate" in self.native_backward:
            return self._propagate(y, times, par, tol)
        if not np.all(step <= 0.0):
            raise ValueError("t must be monotonic (increasing, or decreasing backward)")
        self.require(Capability.BACKWARD, "propagate backward")
        z = self._propagate(REVERSAL * y, 2.0 * times[0] - times, par, tol)
        return REVERSAL * z

    def attitude(self, y0: ArrayLike, q0: ArrayLike, t: ArrayLike, params: ArrayLike,
                 tolerance: Tolerance) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """States and attitude quaternions at times ``t`` (``ATTITUDE``).

        Parameters
        ----------
        y0 : array_like, shape (6,) or (n, 6)
        q0 : array_like, shape (4,) or (n, 4)
            Unit quaternions, scalar first, body -> space (``gamma = R(q)^T e_Z``:
            :func:`andoyer.charts.rotation.quaternion_from_vertical` builds one).
        t : array_like, shape (m,)
            As for :meth:`propagate` (decreasing: backward, by time reversal).
        params : sequence of 8 floats
        tolerance : Tolerance

        Returns
        -------
        y : ndarray, shape (n, m, 6)
        q : ndarray, shape (n, m, 4)
        """
        self.require(Capability.ATTITUDE)
        tol = _tolerance(tolerance)
        y = _states(y0)
        q = np.asarray(q0, dtype=np.float64)
        if q.ndim == 1:
            q = q[None]
        if q.ndim != 2 or q.shape[1] != 4 or q.shape[0] not in (1, y.shape[0]):
            raise ValueError(f"q0 must have shape (4,) or (n, 4) with n = {y.shape[0]} "
                             f"orbits, got {np.shape(q0)}")
        if not (np.all(np.isfinite(y)) and np.all(np.isfinite(q))):
            raise ValueError("y0 and q0 must be finite")
        norm = np.linalg.norm(q, axis=1)
        if np.any(np.abs(norm - 1.0) > 1e-12):
            raise ValueError("q0 must hold unit quaternions (|q| = 1 to 1e-12)")
        z = np.ascontiguousarray(np.concatenate(
            [y, np.broadcast_to(q, (y.shape[0], 4))], axis=1))
        times = _times(t)
        if z.shape[0] == 0 or times.size == 0:
            return np.empty((z.shape[0], times.size, 6)), np.empty((z.shape[0], times.size, 4))
        par = runtime_parameters(params)
        step = np.diff(times)
        if np.all(step >= 0.0) or "attitude" in self.native_backward:
            out = self._attitude(z, times, par, tol)
        else:
            if not np.all(step <= 0.0):
                raise ValueError("t must be monotonic (increasing, or decreasing backward)")
            self.require(Capability.BACKWARD, "integrate the attitude backward")
            out = ATTITUDE_REVERSAL * self._attitude(ATTITUDE_REVERSAL * z,
                                                     2.0 * times[0] - times, par, tol)
        return out[..., :6], out[..., 6:]

    def crossings(self, y0: ArrayLike, params: ArrayLike, event: SectionEvent,
                  n_crossings: int, t_max: float, tolerance: Tolerance, *,
                  backward: bool = False) -> Crossings:
        """The first ``n_crossings`` crossings of ``event`` after t = 0, integrating at
        most to ``t_max > 0`` (``backward``: to ``-t_max``, crossing times negative and
        decreasing, ``event.direction`` still in physical time)."""
        self.require(Capability.CROSSINGS)
        ev, tol = _event(event), _tolerance(tolerance)
        y = _states(y0)
        n_crossings = integer("n_crossings", n_crossings, 0)
        t_max = _t_max(t_max)
        n = y.shape[0]
        if n == 0 or n_crossings == 0:
            return Crossings(np.full((n, n_crossings), np.nan),
                             np.full((n, n_crossings, 6), np.nan), np.zeros(n, dtype=np.int64))
        par = runtime_parameters(params, ev)
        if not backward:
            return self._crossings(y, par, ev, n_crossings, t_max, tol)
        self.require(Capability.BACKWARD, "find crossings backward")
        if "crossings" in self.native_backward:
            return self._crossings(y, par, ev, n_crossings, -t_max, tol)
        back = ev.reversed()
        cr = self._crossings(REVERSAL * y, runtime_parameters(params, back), back,
                             n_crossings, t_max, tol)
        return Crossings(-cr.t, REVERSAL * cr.y, cr.count)

    def tangent(self, y0: ArrayLike, w0: ArrayLike, params: ArrayLike,
                tolerance: Tolerance, *, t: ArrayLike | None = None,
                event: SectionEvent | None = None, n_crossings: int = 1,
                t_max: float | None = None, backward: bool = False,
                renormalise: bool = True, scale: float | None = None,
                extended_precision: bool = False) -> TangentFlow:
        """Orbits of (1) with ``k`` tangent vectors each: at output times ``t``, or at
        the first ``n_crossings`` crossings of ``event`` within ``|t| <= |t_max|``.

        Parameters
        ----------
        y0 : array_like, shape (6,) or (n, 6)
        w0 : array_like, shape (6,), (k, 6) or (n, k, 6)
            Initial tangent vectors (any non-zero length; ``rho`` starts at ``ln|w0|``).
        params : sequence of 8 floats
            :attr:`RigidBody.engine_params`.
        tolerance : Tolerance
        t : array_like, shape (m,), optional
            Output times, ``t[0]`` the initial time (the MEGNO quadratures weigh
            ``t + delta``: start at 0 for indicators), increasing (or decreasing:
            backward, then ``megno`` is None).
        event : SectionEvent, optional
            Instead of ``t``: stop at its crossings (``TANGENT_CROSSINGS``).
        n_crossings : int
            Crossings wanted (with ``event``).
        t_max : float
            With ``event``: the longest flight (> 0).
        backward : bool
            With ``event``: integrate towards negative times (crossing times negative).
        renormalise : bool
            Carry the vectors at unit length while integrating, with the MEGNO
            quadratures (long flights, chaos indicators); False for short flights where
            ``w`` itself is wanted (monodromy, section-map Jacobians).
        scale : float, optional
            ``T`` of the MEGNO quadratures while integrating (default ``|t[-1]|``):
            engines with one error norm for the whole state keep them of order one.
        extended_precision : bool
            80-bit arithmetic (``EXTENDED_PRECISION``), with ``event`` only.
        """
        tol = _tolerance(tolerance)
        y = _states(y0)
        n = y.shape[0]
        W = _vectors(w0, n)
        if not (np.all(np.isfinite(y)) and np.all(np.isfinite(W))):
            raise ValueError("y0 and w0 must be finite")
        norms = np.linalg.norm(W, axis=2)
        if np.any(norms == 0.0):
            raise ValueError("w0 contains a zero vector")
        if event is None:
            if t is None:
                raise ValueError("give output times t or an event")
            return self._tangent_times(y, W, _times(t), params, tol, bool(renormalise),
                                       scale)
        if t is not None:
            raise ValueError("give output times t or an event, not both")
        self.require(Capability.TANGENT_CROSSINGS, "find crossings with tangent vectors")
        if extended_precision:
            self.require(Capability.EXTENDED_PRECISION, "integrate in extended precision")
        ev = _event(event)
        n_crossings = integer("n_crossings", n_crossings, 0)
        if t_max is None:
            raise ValueError("t_max is required with an event")
        t_max = _t_max(t_max)
        if not backward:
            return self._tangent_crossings(y, W, runtime_parameters(params, ev), ev,
                                           n_crossings, t_max, tol, bool(extended_precision))
        self.require(Capability.BACKWARD, "find crossings backward")
        if "tangent_crossings" in self.native_backward:
            return self._tangent_crossings(y, W, runtime_parameters(params, ev), ev,
                                           n_crossings, -t_max, tol,
                                           bool(extended_precision))
        back = ev.reversed()
        flow = self._tangent_crossings(REVERSAL * y, REVERSAL * W,
                                       runtime_parameters(params, back), back, n_crossings,
                                       t_max, tol, bool(extended_precision))
        return _reverse_flow(flow, -1.0)

    def _tangent_times(self, y: NDArray[np.float64], W: NDArray[np.float64],
                       times: NDArray[np.float64], params: ArrayLike, tol: Tolerance,
                       renormalise: bool, scale: float | None) -> TangentFlow:
        self.require(Capability.TANGENT, "integrate tangent vectors")
        if times.size < 1:
            raise ValueError("t must hold at least one output time")
        step = np.diff(times)
        forward = bool(np.all(step > 0.0))
        if not forward and not np.all(step < 0.0):
            raise ValueError("t must be strictly monotonic output times")
        T = float(abs(times[-1] - times[0])) if scale is None else float(scale)
        if T == 0.0 and scale is None:
            T = 1.0
        par = runtime_parameters(params, None, T)
        if forward or "tangent" in self.native_backward:
            return self._tangent(y, W, times, par, tol, renormalise, T)
        self.require(Capability.BACKWARD, "integrate tangent vectors backward")
        flow = self._tangent(REVERSAL * y, REVERSAL * W, 2.0 * times[0] - times, par, tol,
                             renormalise, T)
        return _reverse_flow(flow, -1.0)._replace(t=np.broadcast_to(times, flow.t.shape).copy())

    def __repr__(self) -> str:
        return f"{type(self).__name__}()"


#: The type of an engine (what ``engine=`` arguments resolve to): every engine derives
#: from :class:`EngineBase`, whose docstring and this module's are its contract.
Engine = EngineBase


def _engines_with(capability: Capability) -> list[str]:
    from andoyer.integrate.engines import engines_with  # the registry, above this module

    return engines_with(capability)


def _tolerance(tolerance: Any) -> Tolerance:
    if not isinstance(tolerance, Tolerance):
        raise TypeError(f"tolerance must be a Tolerance, got {tolerance!r} (use "
                        "Tolerance(rtol, atol) or Tolerance.single(tol))")
    return tolerance


def _event(event: Any) -> SectionEvent:
    if not isinstance(event, SectionEvent):
        raise TypeError(f"event must be a SectionEvent, got {event!r}")
    return event


def _t_max(t_max: Any) -> float:
    return positive("t_max", t_max)


def unit_vectors(W: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """``(u, rho) = (W/|W|, ln|W|)`` along the last axis: the split of :class:`TangentFlow`."""
    norms = np.linalg.norm(W, axis=-1)
    with np.errstate(divide="ignore", invalid="ignore"):
        return W / norms[..., None], np.log(norms)
