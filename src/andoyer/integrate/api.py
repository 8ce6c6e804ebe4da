"""Orbits and Poincare sections: validated inputs in, self-describing datasets out.

Integration is done in the Euler-Poisson variables (1), regular everywhere; initial
states may be given in any chart. :func:`integrate_canonical` integrates the canonical
systems (4) or (16) directly, for comparison with the paper.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Mapping
from typing import Any, TypeVar

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from andoyer.body import RigidBody, checks_body
from andoyer.charts.andoyer_deprit import from_andoyer, to_andoyer
from andoyer.charts.euler_poisson import (
    as_state,
    momentum_bound,
)
from andoyer.charts.hess import from_hess, to_hess
from andoyer.errors import SingularPassageWarning
from andoyer.integrate import budget
from andoyer.integrate.engines import EngineLike, resolve_engine
from andoyer.integrate.engines.base import (
    SECTION_SINGULAR_RTOL,
    Capability,
    Crossings,
    Engine,
    Params,
    Section,
    Tolerance,
)
from andoyer.integrate.results import provenance, states_dataset
from andoyer.notation import coordinates, storage_name
from andoyer.progress import Progress
from andoyer.validation import integer, positive, real_array

__all__ = ["propagate", "poincare", "initial_states", "integrate_canonical", "GAMMA_TOL",
           "RESIDUAL_BOUND", "check_times", "check_tolerances", "section_crossings",
           "ORBIT_PARAMETERS", "orbit_docstring", "orbit_inputs", "orbit_dataset"]

#: ``|gamma|`` may differ from 1 by this much (then it is renormalised); more is an error.
GAMMA_TOL = 1e-12
_CHARTS = ("euler_poisson", "andoyer", "hess")
#: Every crossing :func:`poincare` reports satisfies ``|section_residual| <= RESIDUAL_BOUND``
#: (measured: 1e-15 on the heyoka and numba engines, 1.3e-12 on scipy's); a root of the
#: section function that does not is reported as a singular passage, never as a crossing.
RESIDUAL_BOUND = 1e-10
#: Rounds of continuation past singular passages before :func:`poincare` gives up on an
#: orbit (each round asks the engine for more roots than the last, so few are needed).
_MAX_ROUNDS = 40
#: A regular state standing in for NaN padding while roots are classified.
_DUMMY_STATE = np.array([0.6, 0.0, 0.8, 0.0, 0.6, 0.8])
#: Largest scratch array of crossings one engine call may allocate (bytes).
_MAX_SCRATCH = 256 * 2**20


# ---------------------------------------------------------------------- validation
@checks_body
def initial_states(body: RigidBody, y0: ArrayLike, chart: str = "euler_poisson", *,
                   name: str = "y0") -> NDArray[np.float64]:
    """Euler-Poisson initial states, shape (n, 6), from states given in ``chart``.

    ``chart="andoyer"`` takes ``(l, g, L, G, M)``, ``chart="hess"`` takes
    ``(theta1, theta2, J1, J2, J3)``. Euler-Poisson states must have ``|gamma| = 1``
    within :data:`GAMMA_TOL`; within it gamma is renormalised, beyond it
    ``ValueError`` is raised.

    Parameters
    ----------
    body : RigidBody
        Supplies ``phi0`` of the Hess chart.
    y0 : array_like, shape (d,) or (n, d)
        States in ``chart`` coordinates (``d`` = 6, 5, 5).
    chart : {"euler_poisson", "andoyer", "hess"}
        Chart of ``y0``.
    name : str, default "y0"
        The argument's name in error messages (a caller passes its own).

    Returns
    -------
    ndarray, shape (n, 6)
    """
    if chart not in _CHARTS:
        raise ValueError(f"unknown chart {chart!r}; choose one of {', '.join(_CHARTS)}")
    if chart == "andoyer":
        y = from_andoyer(y0, name=name)
    elif chart == "hess":
        y = from_hess(body, y0, name=name)
    else:
        y = as_state(y0, name).copy()
        norm = np.linalg.norm(y[..., 3:], axis=-1)
        bad = np.abs(norm - 1.0) > GAMMA_TOL
        if np.any(bad):
            worst = float(np.max(np.abs(norm - 1.0)))
            raise ValueError(
                f"{name}: gamma must be a unit vector (|gamma| = 1 is the physical level of the "
                f"geometric integral); max ||gamma| - 1| = {worst:.3g} exceeds {GAMMA_TOL:g}. "
                "Normalise gamma yourself if that is what you mean.")
        y[..., 3:] /= norm[..., None]
    y = np.atleast_2d(y)
    if y.ndim != 2:
        raise ValueError(f"y0 must be one state or a list of states, got shape {y.shape}")
    if y.shape[0] == 0:
        raise ValueError("y0 holds no state")
    budget.check_momentum(float(np.max(np.abs(y[:, :3]))), name)
    return y


def check_tolerances(rtol: float, atol: float) -> tuple[float, float]:
    """``(rtol, atol)`` as floats, or ``ValueError`` naming the one out of range
    (the one check, :class:`~andoyer.integrate.engines.base.Tolerance`).

    Parameters
    ----------
    rtol : float
        Relative tolerance, in ``[1e-16, 1e-3]``.
    atol : float
        Absolute tolerance, in ``(0, 1e-3]``.
    """
    tol = Tolerance(rtol, atol)
    return tol.rtol, tol.atol


def check_times(t: ArrayLike) -> NDArray[np.float64]:
    """Output times as a float array: 1-D, at least 2, finite, strictly increasing.

    Parameters
    ----------
    t : array_like
        Output times (body time units).
    """
    arr = real_array("t", t)
    if arr.ndim != 1 or arr.size < 2:
        raise ValueError(f"t must be a 1-D array of at least 2 output times (the first is "
                         f"the initial time), got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ValueError("t contains NaN or infinity")
    if np.any(np.diff(arr) <= 0.0):
        raise ValueError("t must be strictly increasing")
    return arr


#: The parameters the orbit functions share (:func:`propagate`, :func:`poincare`,
#: :func:`andoyer.integrate.attitude`), documented once: name -> the numpydoc lines.
ORBIT_PARAMETERS: dict[str, tuple[str, ...]] = {
    "y0": ("y0 : array_like, shape (6,) or (n, 6) (or (5,)/(n, 5) in the other charts)",
           "    Initial states in ``chart`` coordinates."),
    "t": ("t : array_like, shape (k,)",
          "    Output times, strictly increasing; ``t[0]`` is the initial time."),
    "tolerances": ("rtol, atol : float",
                   "    Tolerances of the mixed criterion ``atol + rtol |y|`` (heyoka has a "
                   "single",
                   "    tolerance: it uses ``min(rtol, atol)``)."),
    "chart": ('chart : {"euler_poisson", "andoyer", "hess"}',
              "    Chart of ``y0``."),
    "progress": ("progress : bool, optional",
                 "    Show a progress line on stderr (default: when stderr is a terminal)."),
}

_F = TypeVar("_F", bound=Callable[..., Any])


def orbit_docstring(func: _F) -> _F:
    """Decorator: a line ``{name}`` of ``func``'s docstring (``name`` a key of
    :data:`ORBIT_PARAMETERS`) becomes that parameter's documentation, at the line's
    indentation (apply it below ``checks_body``, which copies the docstring).

    Parameters
    ----------
    func : callable
        A function whose docstring names shared parameters.

    Examples
    --------
    >>> @orbit_docstring
    ... def f(chart="andoyer"):
    ...     '''Parameters
    ...     ----------
    ...     {chart}
    ...     '''
    >>> print(f.__doc__.splitlines()[3].strip())
    Chart of ``y0``.
    """
    lines = []
    for line in (func.__doc__ or "").split("\n"):
        name = line.strip()[1:-1] if line.strip().startswith("{") else ""
        if name in ORBIT_PARAMETERS:
            indent = line[:len(line) - len(line.lstrip())]
            lines += [indent + part for part in ORBIT_PARAMETERS[name]]
        else:
            lines.append(line)
    func.__doc__ = "\n".join(lines)
    return func


def orbit_inputs(body: RigidBody, y0: ArrayLike, t: ArrayLike, rtol: float, atol: float,
                 chart: str) -> tuple[NDArray[np.float64], NDArray[np.float64], Tolerance]:
    """The checked inputs of an orbit function (:data:`ORBIT_PARAMETERS`): Euler-Poisson
    initial states, shape (n, 6), the output times and the tolerance, checked in that
    order: tolerances, times, states.

    Parameters
    ----------
    body : RigidBody
        The body (``phi0`` of the Hess chart, the momentum bound).
    y0 : array_like
        Initial states in ``chart`` coordinates (:func:`initial_states`).
    t : array_like
        Output times (:func:`check_times`).
    rtol, atol : float
        Tolerances (:func:`check_tolerances`).
    chart : str
        Chart of ``y0``.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> y, t, tol = orbit_inputs(RigidBody.paper(), [0.3, 1.0, 0.2, 1.0, 0.0], [0.0, 1.0],
    ...                          1e-12, 1e-12, "andoyer")
    >>> y.shape, t.tolist(), tol.rtol
    ((1, 6), [0.0, 1.0], 1e-12)
    """
    rtol, atol = check_tolerances(rtol, atol)
    times = check_times(t)
    y = initial_states(body, y0, chart)
    return y, times, Tolerance(rtol, atol)


def orbit_dataset(body: RigidBody, Y: NDArray[np.float64], times: NDArray[np.float64],
                  attrs: Mapping[str, Any],
                  extra: Mapping[str, tuple[Any, Any]] | None = None,
                  coords: Mapping[str, Any] | None = None) -> xr.Dataset:
    """The dataset of orbits at output times (dims ``(orbit, time)``), with the drifts of
    the integrals (:func:`~andoyer.integrate.results.states_dataset`).

    Parameters
    ----------
    body : RigidBody
        The body integrated.
    Y : ndarray, shape (n, k, 6)
        Euler-Poisson states of ``n`` orbits at ``k`` times.
    times : ndarray, shape (k,)
        The output times.
    attrs : mapping
        Dataset attributes (:func:`~andoyer.integrate.results.provenance`).
    extra : mapping, optional
        More variables, ``name -> (dims, values)``.
    coords : mapping, optional
        More coordinates (those of the dims of ``extra``).

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> ds = orbit_dataset(RigidBody.paper(), np.array([[[0.6, 0, 0.8, 0, 0.6, 0.8]] * 2]),
    ...                    np.array([0.0, 1.0]), {})
    >>> dict(ds.sizes), ds.time.attrs["long_name"]
    ({'orbit': 1, 'time': 2}, 'time')
    """
    ds = states_dataset(body, Y, ("orbit", "time"),
                        {"orbit": np.arange(Y.shape[0]), "time": times, **(coords or {})},
                        attrs, extra, drifts=True)
    ds.variables["time"].attrs.update(units="body time units", long_name="time")
    return ds


#: Fewest orbits per engine call while a progress line is shown.
_MIN_CHUNK = 64


def _chunks(n: int, parts: int) -> list[slice]:
    size = max(1, math.ceil(n / parts))
    return [slice(i, min(n, i + size)) for i in range(0, n, size)]


def _run_chunks(fn: Callable[[slice], Any], n: int, label: str,
                progress: bool | None) -> list[Any]:
    bar = Progress(n, label, progress)
    out = []
    # Chunks exist only to move the progress line. The engines balance the orbits of
    # one call over their SIMD lanes and threads (longest first); each chunk boundary
    # waits for its slowest orbit, so chunks are few and large, and there is a single
    # one when no progress is shown.
    parts = max(1, min(20, n // _MIN_CHUNK)) if bar.enabled else 1
    for sl in _chunks(n, parts):
        out.append(fn(sl))
        bar.update(sl.stop - sl.start)
    bar.close()
    return out


# ---------------------------------------------------------------------- orbits
@checks_body(ranges={"rtol": "tolerance", "atol": "tolerance"})
@orbit_docstring
def propagate(body: RigidBody, y0: ArrayLike, t: ArrayLike, *, engine: EngineLike = None,
              rtol: float = 1e-12, atol: float = 1e-12, chart: str = "euler_poisson",
              progress: bool | None = None) -> xr.Dataset:
    """Integrate the Euler-Poisson equations (1) from one or many initial states.

    Parameters
    ----------
    body : RigidBody
    {y0}
    {t}
    engine : str or Engine, optional
        An engine name (:data:`andoyer.integrate.engines.ENGINES`) or instance; default
        taylor, measured faster on orbits
        (:func:`~andoyer.integrate.engines.default_engine_name`, per workload:
        :data:`~andoyer.integrate.engines.MEASURED_DEFAULTS`).
    {tolerances}
    {chart}
    {progress}

    Returns
    -------
    xarray.Dataset
        Dims ``(orbit, time)``: the Euler-Poisson state, the Andoyer-Deprit and Hess
        coordinates, the integrals ``H``, ``area``, ``geometric`` and their drifts
        ``H_drift`` (relative to ``max(|H(0)|, mu)``), ``area_drift`` (relative to ``|G(0)|``)
        and ``geometric_drift``; attrs record body, engine, tolerances and version.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> ds = propagate(RigidBody.paper(), [0.3, 1.0, 0.2, 1.0, 0.0], [0.0, 1.0, 2.0],
    ...                chart="andoyer", engine="scipy")
    >>> ds.sizes["time"], bool(abs(ds.H_drift).max() < 1e-10)
    (3, True)
    """
    y, times, tolerance = orbit_inputs(body, y0, t, rtol, atol, chart)
    budget.check("propagate", steps=budget.estimate_steps(body, y, times[-1] - times[0],
                                                          tolerance.rtol),
                 memory=budget.DATASET_BYTES * y.shape[0] * times.size)
    eng = resolve_engine(engine, Capability.PROPAGATE, workload="orbit")
    name = eng.name
    params = body.engine_params
    parts = _run_chunks(lambda sl: eng.propagate(y[sl], times, params, tolerance),
                        y.shape[0], f"propagate ({name})", progress)
    return orbit_dataset(body, np.concatenate(parts, axis=0), times,
                         provenance(body, engine=name, rtol=tolerance.rtol,
                                    atol=tolerance.atol, initial_chart=chart))


@checks_body(ranges={"n_crossings": "count", "rtol": "tolerance", "atol": "tolerance"})
@orbit_docstring
def poincare(body: RigidBody, y0: ArrayLike, section: Section | str, n_crossings: int, *,
             engine: EngineLike = None, rtol: float = 1e-12, atol: float = 1e-12,
             t_max: float | None = None, chart: str = "euler_poisson",
             progress: bool | None = None) -> xr.Dataset:
    """Poincare section: the first ``n_crossings`` crossings of ``section`` by each orbit.

    Parameters
    ----------
    body : RigidBody
    {y0}
    section : Section or str
        E.g. ``Section("g", 0.0)``, ``"theta2=0"``, ``"G3=0:+"``.
    n_crossings : int
        Crossings wanted per orbit.
    engine : str or Engine, optional
        An engine name (:data:`andoyer.integrate.engines.ENGINES`) or instance; default
        taylor, measured faster on component and angle sections
        (:func:`~andoyer.integrate.engines.default_engine_name`, per workload:
        :data:`~andoyer.integrate.engines.MEASURED_DEFAULTS`).
    {tolerances}
    t_max : float, optional
        Integrate at most to this time (default ``1000 * n_crossings``); orbits with
        fewer crossings are NaN-padded.
    {chart}
    {progress}

    Returns
    -------
    xarray.Dataset
        Dims ``(orbit, crossing)``: crossing time ``t``, all coordinates,
        ``crossings_found`` per orbit, the initial states ``y0``, and
        ``section_residual`` (``coord - value``, or ``sin(angle - value)`` for angles),
        at most :data:`RESIDUAL_BOUND` = 1e-10 in magnitude for every reported crossing
        (measured: about 1e-15 on the heyoka and numba engines, 1e-12 on scipy's).
        ``momentum_scale`` per orbit (the largest ``|G|`` on its energy level) and
        ``singular_passages``, the number of singular passages per orbit, with their
        times in ``singular_passage_t`` (dims ``(orbit, passage)``, present only when
        there were any).

    Warns
    -----
    SingularPassageWarning
        When an orbit passes through a singular set of an angle section: ``G -> 0``
        (relative to ``momentum_scale``), ``L -> +-G`` or ``|M| -> G`` (relative to
        ``|G|``), closer than :data:`~andoyer.integrate.engines.values.SECTION_SINGULAR_RTOL`.
        The angle is undefined there and the section function vanishes identically, so
        such a root is no crossing: it is counted apart and the orbit continued. Every
        M = 0 libration of the Hess solution passes G = 0; section it by a smooth
        coordinate (``"G3=0"``) or integrate it with :func:`propagate_hess_manifold`.

    Examples
    --------
    A Hess libration at M = 0 passes G = 0 twice a period: those passages are not
    crossings of ``theta2 = 1`` (the angle is undefined there), and it has none else.

    >>> import warnings
    >>> from andoyer import RigidBody, from_hess
    >>> body = RigidBody.paper()
    >>> with warnings.catch_warnings():
    ...     warnings.simplefilter("ignore")
    ...     ds = poincare(body, from_hess(body, [0, 4, 0.03, 0.1, 0]), "theta2=1", 2,
    ...                   engine="numba", t_max=500.0)
    >>> int(ds.crossings_found[0]), int(ds.singular_passages[0]) > 0
    (0, True)
    """
    sec = Section.parse(section) if isinstance(section, str) else section
    if not isinstance(sec, Section):
        raise ValueError(f"section must be a Section or a string like 'g=0', got {section!r}")
    if sec.chart is None:
        raise ValueError(f"section {sec.coord!r} is no chart's coordinate (the phase of gamma "
                         "of the section maps of andoyer.analysis.splitting): poincare takes "
                         "a coordinate of the Euler-Poisson, Andoyer-Deprit or Hess chart")
    if sec.chart == "hess":
        body.require_planar(f"the Hess-chart section {sec.coord!r}")
    n_crossings = integer("n_crossings", n_crossings, 1)
    rtol, atol = check_tolerances(rtol, atol)
    t_end = 1000.0 * n_crossings if t_max is None else positive("t_max", t_max)
    y = initial_states(body, y0, chart)
    # The default t_max is a generous cap, not the expected duration: only a t_max the
    # user gave is costed in steps.
    budget.check("poincare",
                 steps=0.0 if t_max is None else budget.estimate_steps(body, y, t_end, rtol),
                 memory=budget.DATASET_BYTES * y.shape[0] * int(n_crossings))
    eng = resolve_engine(engine, Capability.CROSSINGS,
                         workload="angle_section" if sec.is_angle else "component_section")
    name = eng.name
    params = body.engine_params
    scale = momentum_bound(body, y)
    parts = _run_chunks(
        lambda sl: section_crossings(eng, y[sl], scale[sl], params, sec, int(n_crossings),
                                      t_end, rtol, atol, body),
        y.shape[0], f"poincare ({name})", progress)
    T = np.concatenate([p[0].t for p in parts], axis=0)
    Y = np.concatenate([p[0].y for p in parts], axis=0)
    count = np.concatenate([p[0].count for p in parts], axis=0)
    residual = np.concatenate([p[2] for p in parts], axis=0)
    passages = [tp for p in parts for tp in p[1]]
    n_pass = np.array([len(tp) for tp in passages], dtype=np.int64)
    P = np.full((len(passages), int(n_pass.max(initial=0))), np.nan)
    for i, tp in enumerate(passages):
        P[i, :len(tp)] = tp
    ds = states_dataset(
        body, Y, ("orbit", "crossing"),
        {"orbit": np.arange(Y.shape[0]), "crossing": np.arange(int(n_crossings))},
        provenance(body, engine=name, rtol=rtol, atol=atol, t_max=t_end,
                   initial_chart=chart, residual_bound=RESIDUAL_BOUND,
                   section_singular_rtol=SECTION_SINGULAR_RTOL, **sec.attrs()),
        extra={"t": (("orbit", "crossing"), T), "crossings_found": (("orbit",), count),
               "y0": (("orbit", "component"), y),
               "momentum_scale": (("orbit",), scale),
               "singular_passages": (("orbit",), n_pass),
               # The passage dimension exists only where there were passages.
               **({"singular_passage_t": (("orbit", "passage"), P)} if P.size else {})})
    # the residual section_crossings computed: reading the chart here would compute every
    # lazy derived variable of every crossing (a fifth of a long 7:1 orbit's Python time)
    ds["section_residual"] = (("orbit", "crossing"), residual)
    ds.section_residual.attrs.update(
        long_name=f"section equation {sec.coord} = {sec.value:g} at the crossing", units="1")
    ds.t.attrs.update(long_name="time of the crossing", units="body time units")
    ds.momentum_scale.attrs.update(
        long_name="largest |G| on the orbit's energy level (scale of G = 0)", units="1")
    ds.singular_passages.attrs.update(
        long_name=f"roots of the section function where {sec.coord} is undefined "
                  "(not crossings)", units="1")
    if n_pass.any():
        ds.singular_passage_t.attrs.update(long_name="time of the singular passage",
                                           units="body time units")
        warnings.warn(_passage_message(sec, n_pass), SingularPassageWarning, stacklevel=3)
    return ds


def _passage_message(sec: Section, n_pass: NDArray[np.int64]) -> str:
    return (f"{int(np.count_nonzero(n_pass))} of {n_pass.size} orbits passed {int(n_pass.sum())} "
            f"times through a singular set of {sec.coord} (G -> 0, L -> +-G or |M| -> G, "
            f"relative distance < {SECTION_SINGULAR_RTOL:g}), where the angle is undefined; "
            "those passages are not crossings and are listed in singular_passage_t. For "
            "orbits through G = 0 (the Hess librations at M = 0) use a section of a smooth "
            "coordinate such as 'G3=0', or propagate_hess_manifold().")


def section_crossings(eng: Engine, y: NDArray[np.float64], scale: NDArray[np.float64],
                       params: Params, sec: Section, n: int, t_end: float, rtol: float,
                       atol: float, body: RigidBody
                       ) -> tuple[Crossings, list[list[float]], NDArray[np.float64]]:
    """The first ``n`` crossings of each orbit where ``sec`` is defined, the times of
    the roots where it is not (singular passages), and the section equation's residual at
    each crossing (``sin(angle - value)`` or ``coord - value``; NaN padding).

    An engine reports every root of the section function, and for an angle that
    includes the passages through the angle's singular set, where the function's scale
    vanishes. Those are moved apart, and the orbit is continued from its last root for
    the crossings still missing -- in rounds that ask for more roots each time, bounded
    by ``t_end``, :data:`_MAX_ROUNDS` and a scratch-memory budget.

    Parameters
    ----------
    eng : Engine
        The engine, with the ``crossings`` capability.
    y : ndarray, shape (m, 6)
        Initial Euler-Poisson states of the orbits.
    scale : ndarray, shape (m,)
        Momentum scale of each orbit
        (:func:`~andoyer.charts.euler_poisson.momentum_bound`): where ``|G|`` is below
        its relative threshold a root is a singular passage.
    params : tuple of float
        The body's engine parameters (:attr:`~andoyer.body.RigidBody.engine_params`).
    sec : Section
        The section and its crossing direction.
    n : int
        Crossings wanted per orbit.
    t_end : float
        Largest integration time (body time units).
    rtol, atol : float
        Tolerances (:class:`~andoyer.integrate.engines.base.Tolerance`).
    body : RigidBody
        The body (where the section's angle is undefined).
    """
    m = y.shape[0]
    tolerance = Tolerance(rtol, atol)
    if not sec.is_angle:  # smooth coordinates: every root is a crossing
        cr = eng.crossings(y, params, sec, n, t_end, tolerance)
        found = np.isfinite(cr.t)
        res = _residual_values(sec, body, np.where(found[..., None], cr.y, _DUMMY_STATE))
        return cr, [[] for _ in range(m)], np.where(found, res, np.nan)
    T = np.full((m, n), np.nan)
    Y = np.full((m, n, 6), np.nan)
    R = np.full((m, n), np.nan)
    count = np.zeros(m, dtype=np.int64)
    passages: list[list[float]] = [[] for _ in range(m)]
    start_y, start_t = y.copy(), np.zeros(m)
    active = np.arange(m)
    ask = n
    for _ in range(_MAX_ROUNDS):
        # Bound the engine's scratch arrays ((orbits, ask, 7) floats) before the call.
        ask = max(1, min(ask, _MAX_SCRATCH // (56 * max(1, active.size))))
        t0 = float(start_t[active].min())
        cr = eng.crossings(start_y[active], params, sec, ask, t_end - t0, tolerance)
        # Classify every root of this round at once (NaN padding replaced by a dummy
        # state, masked out): a Python loop runs over orbits only, never over crossings.
        tt = cr.t + start_t[active][:, None]
        valid = np.isfinite(tt) & (tt <= t_end)
        yy = np.where(valid[..., None], cr.y, _DUMMY_STATE)
        good = valid & (sec.defined_distance(yy, scale[active][:, None])
                        > SECTION_SINGULAR_RTOL)
        res = _residual_values(sec, body, yy)
        good &= np.abs(res) <= RESIDUAL_BOUND
        still = []
        for j, i in enumerate(active):
            k = int(cr.count[j])
            take = np.flatnonzero(good[j])[:n - count[i]]
            T[i, count[i]:count[i] + take.size] = tt[j, take]
            Y[i, count[i]:count[i] + take.size] = cr.y[j, take]
            R[i, count[i]:count[i] + take.size] = res[j, take]
            count[i] += take.size
            # Passages before the last crossing kept (all of them if more are needed).
            limit = take[-1] if count[i] == n and take.size else k
            bad = np.flatnonzero(valid[j, :limit] & ~good[j, :limit])
            passages[i].extend(tt[j, bad].tolist())
            if count[i] < n and k == ask and valid[j, :k].all():
                start_y[i], start_t[i] = cr.y[j, k - 1], tt[j, k - 1]
                still.append(i)
        if not still:
            break
        active = np.asarray(still)
        ask = int(max(n - count[i] + len(passages[i]) for i in active))
    else:
        warnings.warn(f"poincare: {active.size} orbits still lacked crossings after "
                      f"{_MAX_ROUNDS} rounds of continuation past singular passages; "
                      "they are NaN-padded", SingularPassageWarning, stacklevel=3)
    return Crossings(T, Y, count), passages, R


def _residual_values(sec: Section, body: RigidBody, y: NDArray[np.float64]
                     ) -> NDArray[np.float64]:
    """``sin(angle - value)`` (or ``coord - value``) at Euler-Poisson states ``y``."""
    # Roots on the singular set are classified apart (singular passages): no warning here.
    chart = str(sec.chart)  # a chart's coordinate: poincare refuses psi
    x = {"hess": lambda: to_hess(body, y, with_mask=True)[0],
         "andoyer": lambda: to_andoyer(y, with_mask=True)[0],
         "euler_poisson": lambda: y}[chart]()
    v = x[..., coordinates(chart).index(sec.coord)]
    return np.sin(v - sec.value) if sec.is_angle else v - sec.value


# ---------------------------------------------------------------------- canonical charts
@checks_body(ranges={"rtol": "tolerance", "atol": "tolerance"})
def integrate_canonical(body: RigidBody, x0: ArrayLike, t: ArrayLike, *,
                        chart: str = "hess", rtol: float = 1e-12, atol: float = 1e-12,
                        singular_margin: float = 1e-9) -> xr.Dataset:
    """Integrate the canonical equations (4) (``chart="andoyer"``) or the Hess-chart
    equations ((16) at ``M = 0``) directly, for comparison with the paper.

    The charts are singular at ``L = +-G`` (``J1 = 0``, ``J1 = J2``) and ``|M| = G``;
    integration stops with ``ValueError`` when an orbit comes within
    ``singular_margin * G`` of them (use :func:`propagate` there: it integrates the
    regular Euler-Poisson equations). scipy's DOP853 is used.

    Parameters
    ----------
    body : RigidBody
    x0 : array_like, shape (5,)
        One point of ``chart``: ``(l, g, L, G, M)`` or ``(theta1, theta2, J1, J2, J3)``,
        finite, in the chart's domain and farther than ``singular_margin`` from its
        singular set (else ``ValueError`` naming ``x0``).
    t : array_like, shape (k,)
        Output times, strictly increasing; ``t[0]`` is the initial time.
    chart : {"hess", "andoyer"}
        The chart whose canonical equations are integrated.
    rtol, atol : float
        Tolerances of DOP853 (mixed criterion ``atol + rtol |y|``).
    singular_margin : float
        Relative distance to the singular set (fraction of ``G`` or ``J2``, in
        ``(0, 0.5]``) at which the integration stops.

    Returns
    -------
    xarray.Dataset
        Dims ``(time,)``: the chart coordinates and the cyclic angle (``m`` or
        ``theta3``) by quadrature, from 0 at ``t[0]``.
    """
    from andoyer.dynamics import CHARTS, canonical_field
    from andoyer.integrate.engines.ivp import solve_dop853

    if chart not in ("andoyer", "hess"):
        raise ValueError(f"chart must be 'andoyer' or 'hess', got {chart!r}")
    rtol, atol = check_tolerances(rtol, atol)
    times = check_times(t)
    margin = positive("singular_margin", singular_margin, maximum=0.5)
    x = real_array("x0", x0)
    if x.shape != (5,):
        raise ValueError(f"x0 must be one point of the {chart} chart, shape (5,), "
                         f"got {x.shape}")
    if not np.all(np.isfinite(x)):
        raise ValueError(f"x0 must be finite, got {x.tolist()}")
    y = initial_states(body, x, chart, name="x0")  # the chart's domain, |G| bounded
    budget.check("integrate_canonical",
                 steps=budget.estimate_steps(body, y, times[-1] - times[0], rtol),
                 memory=8 * 6 * times.size)
    names = CHARTS[chart]

    def rhs(_t: float, z: NDArray[np.float64]) -> NDArray[np.float64]:
        return canonical_field(body, z[:5], chart)

    def distance(_t: float, z: NDArray[np.float64]) -> float:
        if chart == "andoyer":
            G = z[3]
            return float(min(G - abs(z[2]), G - abs(z[4])) / G - margin)
        J1, J2, J3 = z[2], z[3], z[4]
        return float(min(J1, J2 - J1, J2 - abs(J3)) / J2 - margin)

    distance.terminal = True  # type: ignore[attr-defined]
    if not distance(0.0, x) > 0.0:
        raise ValueError(f"x0 lies within singular_margin = {margin:g} of the singular set "
                         f"of the {chart} chart (L = +-G or |M| = G, relative to G): the "
                         "canonical equations are singular there; use propagate()")
    sol = solve_dop853(rhs, times, np.append(x, 0.0), rtol, atol, events=[distance])
    if sol.status == 1:
        raise ValueError(
            f"the orbit reached the singular set of the {chart} chart at t = "
            f"{sol.t_events[0][0]:.6g} (L = +-G or |M| = G); integrate it with "
            "propagate(), which uses the regular Euler-Poisson variables")
    cyc = "m" if chart == "andoyer" else "theta3"
    data: dict[str, Any] = {n: (("time",), sol.y[i]) for i, n in enumerate(names)}
    data[cyc] = (("time",), sol.y[5])
    ds = xr.Dataset(data, coords={"time": times},
                    attrs=provenance(body, engine="scipy-DOP853", rtol=rtol, atol=atol,
                                     equations=f"canonical equations in the {chart} chart"))
    return ds.rename({k: storage_name(str(k)) for k in ds.data_vars
                      if storage_name(str(k)) != k})
