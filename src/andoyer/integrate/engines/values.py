r"""The values that cross the engine seam (:mod:`andoyer.integrate.engines.base`):
what an engine can do (:class:`Capability`), a tolerance (:class:`Tolerance`), a section
as an engine sees it (:class:`SectionEvent`), the runtime parameters (:data:`PARAMETERS`,
:func:`runtime_parameters`), the time reversal of (1) and what engines return
(:class:`Crossings`, :class:`TangentFlow`).

They are importable from :mod:`andoyer.integrate.engines.base` as well (the seam's one
page); this module holds them so that the contract page stays the contract.

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
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from andoyer.kernels.generated.equations import EXTRA_SECTION_KINDS, SECTION_KINDS
from andoyer.notation import SECTION_COORDINATES
from andoyer.validation import integer, positive

__all__ = [
    "Capability", "SectionEvent", "Tolerance", "Crossings", "TangentFlow", "PARAMETERS",
    "PAR", "runtime_parameters", "REVERSIBLE", "REVERSAL", "ATTITUDE_REVERSAL",
    "TOLERANCE_FACTOR", "check_tolerance_factor", "Params", "ALL_KINDS", "unit_vectors",
    "MAX_STEPS", "MAX_THREADS", "MAX_CHUNK", "MAX_BATCH",
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
#: forward-only engine can run backward (momentum components and the angle g flip;
#: gamma, ``|G|``, theta1 mod 2 pi and the phase ``psi`` of gamma do not), from
#: :data:`andoyer.notation.SECTION_COORDINATES` (SymPy checks each sign).
REVERSIBLE: dict[str, int] = {k: s.reversal for k, s in SECTION_COORDINATES.items()
                              if s.reversal is not None}


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

    Attributes
    ----------
    rtol : float, default 1e-12
        Relative tolerance, in ``[1e-16, 1e-3]``.
    atol : float, default 1e-12
        Absolute tolerance, in ``(0, 1e-3]``.

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
        """``rtol = atol = tol``, with errors naming the user's argument ``name``.

        Parameters
        ----------
        tol : float
            The one tolerance, in [1e-16, 1e-3].
        name : str, default "tol"
            The user's argument, named in the error.
        """
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
        :func:`andoyer.kernels.generated.equations.section` of that kind.
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
        """The event of section index ``kind`` (into :data:`ALL_KINDS`).

        Parameters
        ----------
        kind : int
            Index into :data:`ALL_KINDS` (the kernels' section kind).
        value : float, default 0
            The section's value (``coord = value``).
        direction : {0, +1, -1}
            Crossings in both directions (0), upward (+1) or downward (-1).
        """
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
    """What :meth:`Engine.crossings` returns.

    Parameters
    ----------
    t : ndarray, shape (n, n_crossings)
        Crossing times, NaN where an orbit had fewer crossings.
    y : ndarray, shape (n, n_crossings, 6)
        Euler-Poisson states at the crossings, NaN-padded likewise.
    count : ndarray of int, shape (n,)
        Crossings found per orbit.
    """

    t: NDArray[np.float64]  # (n, n_crossings), NaN where an orbit had fewer crossings
    y: NDArray[np.float64]  # (n, n_crossings, 6), NaN-padded likewise
    count: NDArray[np.int64]  # type: ignore[assignment]  # (n,); shadows tuple.count


class TangentFlow(NamedTuple):
    """What :meth:`Engine.tangent` returns (``n`` orbits, ``m`` rows, ``k`` vectors).

    The tangent vectors are ``w_i = exp(rho_i) u_i`` (:attr:`w`) with ``u_i`` of unit
    length, ``w_i(0)`` the given vectors. Rows are the output times, or the crossings
    (NaN-padded beyond ``count``) when an event was given.

    Parameters
    ----------
    t : ndarray, shape (n, m)
        Output times, or crossing times.
    y : ndarray, shape (n, m, 6)
        Euler-Poisson states.
    u : ndarray, shape (n, m, k, 6)
        Unit tangent vectors ``w_i / |w_i|``.
    rho : ndarray, shape (n, m, k)
        ``ln |w_i|``.
    megno : ndarray, shape (n, m, 2), or None
        MEGNO quadratures of the first vector (None at crossings and backward).
    count : ndarray of int, shape (n,)
        Rows filled per orbit.
    ok : ndarray of bool, shape (n,)
        False where the integration failed (NaN there).
    """

    t: NDArray[np.float64]  # (n, m): output times, or crossing times
    y: NDArray[np.float64]  # (n, m, 6): Euler-Poisson states
    u: NDArray[np.float64]  # (n, m, k, 6): unit tangent vectors w_i / |w_i|
    rho: NDArray[np.float64]  # (n, m, k): ln |w_i|
    #: (n, m, 2) MEGNO quadratures of the first vector, ``int_0^t (s + delta) f ds`` and
    #: ``int_0^t 2 num / (s + delta) ds`` with ``f = d rho_1/dt`` and ``delta``
    #: :data:`andoyer.kernels.common.MEGNO_DELTA`; None at crossings and backward.
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


#: The ranges of the engines' options, checked by their constructors: steps allowed per
#: orbit (a step costs at least ~100 ns: 10^15 steps are three core-years; the kernels
#: count in int64), threads, orbits handed to a thread at a time, orbits of one heyoka
#: batch integrator (SIMD lanes; wider batches only cost memory).
MAX_STEPS = 10**15
MAX_THREADS = 1024
MAX_CHUNK = 10**9
MAX_BATCH = 64


def check_tolerance_factor(tolerance_factor: float) -> float:
    """Validate a DOP853 engine's ``tolerance_factor`` (in (0, 1]).

    Parameters
    ----------
    tolerance_factor : float
        Factor applied to the tolerances of a DOP853 engine (in ``(0, 1]``).
    """
    return positive("tolerance_factor", tolerance_factor, maximum=1.0)




def unit_vectors(W: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """``(u, rho) = (W/|W|, ln|W|)`` along the last axis: the split of :class:`TangentFlow`.

    Parameters
    ----------
    W : ndarray, shape (..., 6)
        Tangent vectors (non-zero, finite). A finite vector longer than 1e154 (whose
        squared length overflows) is scaled by its largest component first, so it
        still gets its finite ``ln|W|``.

    Examples
    --------
    >>> u, rho = unit_vectors(np.array([0.0, 0.0, 3e200, 4e200, 0.0, 0.0]))
    >>> u[2:4].tolist(), round(float(rho), 6) == round(float(np.log(5e200)), 6)
    ([0.6, 0.8], True)
    """
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        norms = np.linalg.norm(W, axis=-1)
        u, rho = W / norms[..., None], np.asarray(np.log(norms))
        huge = np.isinf(norms) & np.all(np.isfinite(W), axis=-1)
        if np.any(huge):
            big = np.max(np.abs(W[huge]), axis=-1, keepdims=True)
            scaled = W[huge] / big
            size = np.linalg.norm(scaled, axis=-1, keepdims=True)
            u[huge], rho[huge] = scaled / size, np.log(size[..., 0]) + np.log(big[..., 0])
    return u, rho
