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
    The first ``n_crossings`` roots after ``t = T_START`` (:mod:`andoyer.kernels.common`)
    of the section function ``f`` of ``event`` (a :class:`Section`) in its
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
    ``dq/dt = q (x) (0, omega) / 2``, ``omega = I^-1 G`` (the SymPy field
    :func:`andoyer.symbolic.attitude.attitude_field`, generated as
    :func:`andoyer.kernels.generated.equations.attitude_field`; for Taylor methods its jet,
    ``ep_taylor_attitude_jet``), ``t`` as for ``_propagate``.
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

"""

from __future__ import annotations

from typing import Any, ClassVar

import numpy as np
from numpy.typing import ArrayLike, NDArray

from andoyer.errors import IntegrationError
from andoyer.integrate.engines.values import ALL_KINDS as ALL_KINDS
from andoyer.integrate.engines.values import ATTITUDE_REVERSAL as ATTITUDE_REVERSAL
from andoyer.integrate.engines.values import MAX_BATCH as MAX_BATCH
from andoyer.integrate.engines.values import MAX_CHUNK as MAX_CHUNK
from andoyer.integrate.engines.values import MAX_STEPS as MAX_STEPS
from andoyer.integrate.engines.values import MAX_THREADS as MAX_THREADS
from andoyer.integrate.engines.values import PAR as PAR
from andoyer.integrate.engines.values import PARAMETERS as PARAMETERS
from andoyer.integrate.engines.values import REVERSAL as REVERSAL
from andoyer.integrate.engines.values import REVERSIBLE as REVERSIBLE
from andoyer.integrate.engines.values import SECTION_SINGULAR_RTOL as SECTION_SINGULAR_RTOL
from andoyer.integrate.engines.values import TOLERANCE_FACTOR as TOLERANCE_FACTOR
from andoyer.integrate.engines.values import Capability as Capability
from andoyer.integrate.engines.values import Crossings as Crossings
from andoyer.integrate.engines.values import Params as Params
from andoyer.integrate.engines.values import Section as Section
from andoyer.integrate.engines.values import TangentFlow as TangentFlow
from andoyer.integrate.engines.values import Tolerance as Tolerance
from andoyer.integrate.engines.values import check_tolerance_factor as check_tolerance_factor
from andoyer.integrate.engines.values import runtime_parameters as runtime_parameters
from andoyer.integrate.engines.values import unit_vectors as unit_vectors
from andoyer.validation import MAX_MOMENTUM, integer, positive

__all__ = [
    "Capability", "Section", "SECTION_SINGULAR_RTOL", "Tolerance", "Crossings", "TangentFlow",
    "Engine",
    "EngineBase", "PARAMETERS", "PAR", "runtime_parameters", "REVERSIBLE", "REVERSAL",
    "TOLERANCE_FACTOR", "check_tolerance_factor", "Params", "ALL_KINDS", "unit_vectors",
    "ATTITUDE_REVERSAL",
]


def _states(y0: ArrayLike, name: str = "y0") -> NDArray[np.float64]:
    y = np.asarray(y0, dtype=np.float64)
    if y.ndim == 1:
        y = y[None]
    if y.ndim != 2 or y.shape[1] != 6:
        raise ValueError(f"{name} must have shape (6,) or (n, 6), got {np.shape(y0)}")
    # Every engine starts here: a state no integrator can take is refused by name, not
    # met as an engine's failure (a level h = 1e250 reached heyoka's variational
    # integration through analysis code that built its states itself).
    # (NaN rows are left to the callers: some pass them through as failed orbits.)
    G = float(np.max(np.abs(y[:, :3]), initial=0.0, where=np.isfinite(y[:, :3])))
    if G > MAX_MOMENTUM:
        raise ValueError(f"{name}: |G| = {G:.3g} is beyond the {MAX_MOMENTUM:.3g} that the "
                         "integrators take (the field (1) and its error control would "
                         "overflow); rescale the problem or take a lower energy level")
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
    #: The constructor's options, in the order :meth:`__repr__` shows them.
    repr_options: ClassVar[tuple[str, ...]] = ()
    #: How an engine of compiled ensemble kernels names itself in a failure
    #: (:meth:`_raise_on_failure`), e.g. ``"numba DOP853"``.
    method: ClassVar[str] = ""

    # -- what subclasses implement ------------------------------------------------
    def _propagate(self, y0: NDArray[np.float64], t: NDArray[np.float64],
                   par: NDArray[np.float64], tolerance: Tolerance) -> NDArray[np.float64]:
        raise NotImplementedError

    def _crossings(self, y0: NDArray[np.float64], par: NDArray[np.float64],
                   event: Section, n_crossings: int, t_max: float,
                   tolerance: Tolerance) -> Crossings:
        raise NotImplementedError

    def _tangent(self, y0: NDArray[np.float64], w0: NDArray[np.float64],
                 t: NDArray[np.float64], par: NDArray[np.float64], tolerance: Tolerance,
                 renormalise: bool, scale: float) -> TangentFlow:
        raise NotImplementedError

    def _tangent_crossings(self, y0: NDArray[np.float64], w0: NDArray[np.float64],
                           par: NDArray[np.float64], event: Section, n_crossings: int,
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

        Examples
        --------
        >>> from andoyer import RigidBody
        >>> from andoyer.integrate.engines import get_engine
        >>> y, q = get_engine("scipy").attitude([0, 0, 1.0, 0, 0, 1.0], [1.0, 0, 0, 0],
        ...     [0.0, 2.0], RigidBody.lagrange(2.0, 1.0, 1.0).engine_params, Tolerance())
        >>> q.shape, bool(np.allclose(q[0, 1], [np.cos(1.0), 0, 0, np.sin(1.0)]))
        ((1, 2, 4), True)
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

    def crossings(self, y0: ArrayLike, params: ArrayLike, event: Section,
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
                event: Section | None = None, n_crossings: int = 1,
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
        event : Section, optional
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

    # -- shared by the engines of compiled ensemble kernels (numba, taylor) -------
    def _ensemble_options(self, max_steps: Any, chunksize: Any, n_threads: Any) -> None:
        """Check and keep the options of an engine that runs a Numba kernel over an
        ensemble of orbits (:mod:`andoyer.kernels.threads`): ``max_steps`` (steps allowed
        per orbit, in ``[1, MAX_STEPS]``), ``chunksize`` (orbits handed to a thread at a
        time, in ``[0, MAX_CHUNK]``; 0 splits the orbits evenly up front), ``n_threads``
        (in ``[1, MAX_THREADS]``, or None: Numba's)."""
        self.max_steps = integer("max_steps", max_steps, 1, MAX_STEPS)
        self.chunksize = integer("chunksize", chunksize, 0, MAX_CHUNK)
        self.n_threads = None if n_threads is None else integer("n_threads", n_threads, 1,
                                                                MAX_THREADS)

    @staticmethod
    def _kernel_params(par: NDArray[np.float64]) -> NDArray[np.float64]:
        """The body's part of ``par``, ``(a, b, c, mu, e1, e2, e3, phi0)``, contiguous: the
        parameters of the compiled kernels."""
        return np.ascontiguousarray(par[:PAR["phi0"] + 1])

    def _raise_on_failure(self, info: NDArray[np.int64], kernels: Any, what: str) -> None:
        """:class:`~andoyer.errors.IntegrationError` naming how many orbits failed and
        why the first did, from the ``info`` rows of an ensemble kernel of ``kernels`` (a
        module with ``INFO``, ``SUCCESS`` and ``STATUS_MESSAGES``)."""
        status = info[:, kernels.INFO.index("status")]
        bad = np.flatnonzero(status != kernels.SUCCESS)
        if bad.size:
            i = int(bad[0])
            raise IntegrationError(
                f"{self.method} failed {what} for {bad.size} orbit(s), first orbit {i}: "
                f"{kernels.STATUS_MESSAGES[int(status[i])]} after "
                f"{int(info[i, kernels.INFO.index('accepted')])} steps")

    def __repr__(self) -> str:
        options = ", ".join(f"{k}={getattr(self, k)}" for k in self.repr_options)
        return f"{type(self).__name__}({options})"


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


def _event(event: Any) -> Section:
    if not isinstance(event, Section):
        raise TypeError(f"event must be a Section, got {event!r}")
    return event


def _t_max(t_max: Any) -> float:
    return positive("t_max", t_max)
