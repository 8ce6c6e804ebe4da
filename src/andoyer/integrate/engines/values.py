r"""The values that cross the engine seam (:mod:`andoyer.integrate.engines.base`):
what an engine can do (:class:`Capability`), a tolerance (:class:`Tolerance`), a
Poincare section (:class:`Section`), the runtime parameters (:data:`PARAMETERS`,
:func:`runtime_parameters`), the time reversal of (1) and what engines return
(:class:`Crossings`, :class:`TangentFlow`).

They are importable from :mod:`andoyer.integrate.engines.base` as well (the seam's one
page); this module holds them so that the contract page stays the contract.
:class:`Section` is the one section class of users (``andoyer.Section``, re-exported by
:mod:`andoyer.integrate`) and engines alike: it lives here, at the seam, because engines
import nothing above it.

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
import numbers
import re
from dataclasses import dataclass
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from andoyer.charts.andoyer_deprit import singular_distances
from andoyer.errors import ArgumentTypeError
from andoyer.kernels.generated.equations import EXTRA_SECTION_KINDS, SECTION_KINDS
from andoyer.notation import SECTION_ANGLES, SECTION_COORDINATES, SECTION_PLANES, SectionPlane
from andoyer.validation import integer, positive

__all__ = ["E3_ZERO_REVERSAL",
    "Capability", "Section", "SECTION_SINGULAR_RTOL", "Tolerance", "Crossings", "TangentFlow",
    "PARAMETERS",
    "PAR", "runtime_parameters", "REVERSIBLE", "REVERSAL", "ATTITUDE_REVERSAL",
    "TOLERANCE_FACTOR", "check_tolerance_factor", "Params", "ALL_KINDS", "unit_vectors",
    "MAX_STEPS", "MAX_THREADS", "MAX_CHUNK", "MAX_BATCH",
]

#: (a, b, c, mu, e1, e2, e3, phi0)
Params = tuple[float, float, float, float, float, float, float, float]

#: Every section coordinate an engine can stop on (index = :attr:`Section.kind`).
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
#: The second reversing symmetry of (1), for a centre of mass with ``e3 = 0``:
#: ``y(-t; y0) = S y(t; S y0)`` with ``S`` these signs (``G3`` and ``gamma3`` flip; checked
#: on the SymPy field by :func:`andoyer.analysis.splitting.transversal.reversor_holds`).
E3_ZERO_REVERSAL = np.array([1.0, 1.0, -1.0, 1.0, 1.0, -1.0])

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


#: A crossing of an angle section counts only where the state's relative distance to
#: every singular set the angle depends on (G = 0 relative to the orbit's momentum
#: scale, L = +-G, ``|M| = G``) exceeds this: closer, the angle is resolved no better than
#: (state error) / distance, i.e. to worse than ~1e-6 rad, and at the set itself it is
#: undefined (a "singular passage", reported apart from the crossings).
SECTION_SINGULAR_RTOL = 1e-6

#: ``"coord=value"`` with an optional direction ``":+"``, ``":-"`` or ``":0"``.
_SECTION_TEXT = re.compile(r"\s*(\w+)\s*=\s*([^:\s]+)\s*(?::\s*([+-]?[01]?|[+-]))?\s*")
_DIRECTIONS = {None: 1, "": 1, "+": 1, "+1": 1, "1": 1, "-": -1, "-1": -1, "0": 0}


@dataclass(frozen=True)
class Section:
    r"""The Poincare section ``coord = value`` crossed in ``direction``: what users pass
    to :func:`~andoyer.integrate.poincare` and what engines stop on (as diffrax's ``Event``).

    The section function is that of :func:`andoyer.kernels.generated.equations.section`:
    ``f = coord - value`` for a smooth coordinate; for an angle ``f = sin(angle - value)``
    times a positive factor, a crossing counting only where ``cos(angle - value) > 0``,
    so the wrap at 2 pi makes no spurious crossing (:mod:`andoyer.symbolic.sections`).

    Parameters
    ----------
    coord : str
        A section coordinate of :data:`ALL_KINDS`: of the Euler-Poisson chart (``"G1"``
        .. ``"gamma3"``), the Andoyer-Deprit variables (5)-(6) (``"l"``, ``"g"``, ``"L"``,
        ``"G"``), the Hess variables (14) (``"theta1"``, ``"theta2"``, ``"J1"``,
        ``"J2"``), or the phase ``"psi"`` of gamma (the section maps of
        :mod:`andoyer.analysis.splitting`; no chart's); not ``M`` or ``J3``, constants
        of motion. Each is a row of :data:`andoyer.notation.SECTION_COORDINATES`.
    value : float, default 0
        The plane ``coord = value``; a chart's angle is reduced to ``[0, 2 pi)``.
    direction : {1, -1, 0}, default 1
        The sign of ``df/dt`` at a crossing in physical time: ``coord`` increasing (1),
        decreasing (-1), or both (0). The default is a Poincare section as the paper
        takes it, crossings in one chosen direction: the map ``P`` of the section to
        itself then returns each point to the same side (the report's sections, such
        as the chaos maps' ``theta2 = 0``, count the angle increasing). Both directions
        (0) interleave ``P`` with the half-return; engines' root finding takes them
        when asked, never by default.

    Examples
    --------
    >>> Section("theta2", 0.0)
    Section(coord='theta2', value=0.0, direction=1)
    >>> Section.parse("G3=0:-")
    Section(coord='G3', value=0.0, direction=-1)
    >>> Section.from_kind(2, 0.0, 0) == Section("G3", 0.0, 0)
    True
    >>> Section("g", 7.0).value == 7.0 - 2 * math.pi
    True
    >>> Section("G3", 0.0, 1).reversed()
    Section(coord='G3', value=-0.0, direction=1)
    >>> Section("M", 0.0)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: unknown section coordinate 'M'; choose one of G1, G2, ..., theta2, psi (M ...
    """

    coord: str
    value: float = 0.0
    direction: int = 1

    def __post_init__(self) -> None:
        if not isinstance(self.coord, str):
            raise ArgumentTypeError(f"section coordinate must be a name such as 'theta2', "
                                    f"got {self.coord!r}")
        if self.coord not in ALL_KINDS:
            raise ValueError(f"unknown section coordinate {self.coord!r}; choose one of "
                             f"{', '.join(ALL_KINDS)} (M and J3 are constants of motion)")
        if isinstance(self.value, bool | str | bytes) or not isinstance(
                self.value, numbers.Real):
            raise ArgumentTypeError(f"section value must be a number, got {self.value!r}")
        v = float(self.value)
        if not math.isfinite(v):
            raise ValueError(f"section value must be finite, got {v!r}")
        d = self.direction
        if isinstance(d, bool) or not isinstance(d, numbers.Real) or d not in (-1, 0, 1):
            raise ValueError(f"section direction must be +1, -1 or 0, got {d!r}")
        if self.coord in SECTION_ANGLES:
            v = math.remainder(v, 2 * math.pi) % (2 * math.pi)
        object.__setattr__(self, "value", v)
        object.__setattr__(self, "direction", int(d))

    @classmethod
    def parse(cls, text: str) -> Section:
        """The section ``"coord=value"``, with an optional ``":+"``, ``":-"`` or ``":0"``
        direction (default ``+``), as the command line, scan configs and the explorer
        write it.

        Parameters
        ----------
        text : str
            The section: ``"theta2=0"``, ``"theta2=1.5:+"``, ``"G3=0:-"``.

        Examples
        --------
        >>> Section.parse("theta2=1.5:-").direction
        -1
        """
        if not isinstance(text, str):
            raise ArgumentTypeError(f"section must be a string such as 'g=0', got {text!r}")
        m = _SECTION_TEXT.fullmatch(text)
        if not m:
            raise ValueError(f"cannot parse section {text!r}; write e.g. 'g=0', "
                             "'theta2=1.5:+' or 'G3=0:-'")
        coord, value, d = m.groups()
        direction = _DIRECTIONS.get(d)
        if direction is None:
            raise ValueError(f"bad section direction {d!r} in {text!r}; use +, - or 0")
        try:
            val = float(value)
        except ValueError:
            raise ValueError(f"section value {value!r} in {text!r} is not a number") from None
        return cls(coord, val, direction)

    @classmethod
    def from_kind(cls, kind: int, value: float = 0.0, direction: int = 1) -> Section:
        """The section of the kernels' section index ``kind`` (into :data:`ALL_KINDS`).

        Parameters
        ----------
        kind : int
            Index into :data:`ALL_KINDS` (the kernels' section kind).
        value : float, default 0
            The section's value (``coord = value``).
        direction : {1, -1, 0}, default 1
            As for :class:`Section`.

        Examples
        --------
        >>> Section.from_kind(13)
        Section(coord='theta2', value=0.0, direction=1)
        """
        k = integer("kind", kind, 0, len(ALL_KINDS) - 1)
        return cls(ALL_KINDS[k], value, direction)

    @property
    def kind(self) -> int:
        """Index of :attr:`coord` into :data:`ALL_KINDS` (the kernels' section kind)."""
        return ALL_KINDS.index(self.coord)

    @property
    def chart(self) -> str | None:
        """The chart :attr:`coord` belongs to (``"euler_poisson"``, ``"andoyer"``,
        ``"hess"``; None for ``psi``, no chart's coordinate)."""
        return SECTION_COORDINATES[self.coord].chart

    @property
    def is_angle(self) -> bool:
        """Whether :attr:`coord` is an angle of a chart (``l``, ``g``, ``theta1``,
        ``theta2``: its value is taken mod 2 pi)."""
        return self.coord in SECTION_ANGLES

    @property
    def plane(self) -> SectionPlane:
        """The plane filled on this section (``g`` and ``theta2`` sections only).

        >>> Section.parse("theta2=0").plane.x
        'theta1'
        """
        if self.coord not in SECTION_PLANES:
            raise ValueError(f"a section of {self.coord!r} has no filled plane: choose 'g' "
                             "(plane (l, L)) or 'theta2' (plane (theta1, J1))")
        return SECTION_PLANES[self.coord]

    def reversed(self) -> Section:
        """The section the reversed orbit ``R y(-t)`` crosses where ``y`` crosses this
        one (``R`` is :data:`REVERSAL`; the sign is :data:`REVERSIBLE`'s);
        ``ValueError`` for a section without that symmetry."""
        s = REVERSIBLE.get(self.coord)
        if s is None:
            raise ValueError(
                f"a backward flow to the {self.coord!r} section needs an engine with a "
                f"native backward flow; time reversal maps only "
                f"{', '.join(REVERSIBLE)} sections onto themselves")
        return Section(self.coord, s * self.value, -s * self.direction)

    def defined_distance(self, y: ArrayLike, scale: ArrayLike) -> NDArray[np.float64]:
        """Relative distance of Euler-Poisson states to where the coordinate is undefined.

        ``inf`` for the smooth coordinates (``G1``, ..., ``J2``, ``psi``: defined
        everywhere they are used); for an angle the smallest
        :func:`~andoyer.charts.andoyer_deprit.singular_distances` column it depends on
        (:attr:`andoyer.notation.SectionCoordinate.needs`), ``G`` measured against
        ``scale`` (the orbit's momentum scale,
        :func:`~andoyer.charts.euler_poisson.momentum_bound`). A crossing closer than
        :data:`SECTION_SINGULAR_RTOL` is a singular passage, not a crossing.

        Parameters
        ----------
        y : array_like, shape (..., 6)
            Euler-Poisson states.
        scale : array_like
            The momentum scale of each state's orbit (broadcast against ``y[..., 0]``).

        Examples
        --------
        >>> y = [[0.0, 0.6, 0.8, 0.0, 0.0, 1.0], [0.0, 0.0, 1e-9, 0.0, 0.0, 1.0]]
        >>> Section("l", 0.0).defined_distance(y, 1.0).round(12).tolist()
        [0.6, 0.0]
        >>> Section("G3", 0.0).defined_distance(y, 1.0).tolist()
        [inf, inf]
        """
        arr = np.asarray(y, dtype=float)
        needs = SECTION_COORDINATES[self.coord].needs
        if not needs:
            return np.full(arr.shape[:-1], np.inf)
        d = singular_distances(arr, scale)
        return np.min(d[..., list(needs)], axis=-1)

    def attrs(self) -> dict[str, str | float | int]:
        """Flat attributes for datasets (``section_coord``, ``section_value``,
        ``section_direction`` and, for a chart's coordinate, ``section_chart``)."""
        out: dict[str, str | float | int] = {
            "section_coord": self.coord, "section_value": self.value,
            "section_direction": self.direction}
        if self.chart is not None:
            out["section_chart"] = self.chart
        return out


def runtime_parameters(params: ArrayLike, event: Section | None = None,
                       scale: float = 1.0) -> NDArray[np.float64]:
    """The runtime parameters :data:`PARAMETERS` of a body, a section and a scale.

    The one owner of the ``par`` layout of every engine.

    Parameters
    ----------
    params : sequence of 8 floats
        ``(a, b, c, mu, e1, e2, e3, phi0)`` (:attr:`RigidBody.engine_params`).
    event : Section, optional
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
