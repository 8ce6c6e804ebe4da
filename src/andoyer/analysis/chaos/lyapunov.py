"""Chaos indicators of the heavy top: FLI, MEGNO, maximal Lyapunov exponent, chaos maps.

All three come from one integration of the Euler-Poisson equations (1) with their
first-order variational equations (:mod:`andoyer.integrate.variational`, derived from
``H = (G, I^-1 G)/2 + mu (r, gamma)``: by heyoka's ``var_ode_sys``; for
``engine="taylor"``, the default where heyoka is not installed, by the Taylor jets of the
same SymPy field in Numba; for ``engine="numba"`` by SymPy's Jacobian on the Numba
DOP853), for a tangent vector ``w`` with ``w(0) = w0``, ``|w0| = 1``:

* **FLI** (fast Lyapunov indicator, Froeschle, Lega & Gonczi 1997):
  :math:`\\mathrm{FLI}(t) = \\sup_{0 \\le s \\le t} \\ln \\|w(s)\\|`, the supremum taken
  over the output times (``fli``); ``log_norm`` is :math:`\\ln\\|w(t)\\|` itself. On
  a regular orbit ``|w|`` grows linearly (shear between neighbouring tori), so FLI grows
  like ``ln t``; on a chaotic one exponentially, ``FLI ~ lambda t``.
* **MEGNO** (Cincotta & Simo 2000):
  :math:`Y(t) = \\frac{2}{t}\\int_0^t s\\,\\frac{\\dot w\\cdot w}{w\\cdot w}\\,ds` and its
  mean :math:`\\langle Y\\rangle(t) = \\frac1t\\int_0^t Y(s)\\,ds`. ``<Y> -> 2`` on a
  quasi-periodic orbit (linear growth), ``-> 0`` on a stable periodic orbit when the
  tangent vector is iso-energetic (bounded growth; see below), and
  ``<Y> ~ lambda t / 2`` on a chaotic orbit. The integrals are extra
  state variables of the heyoka system (no Python per step); the mean is taken with
  the weights shifted by ``delta = 1e-6`` (see :mod:`andoyer.integrate.variational`;
  a relative change ``O(delta / t)``), ``Y`` itself is exact.
* **maximal Lyapunov exponent** (finite-time): :math:`\\lambda(t) = \\ln\\|w(t)\\| / t`.
  The tangent vector is renormalised continuously (the system integrates ``w/|w|`` and
  ``ln |w|``), so nothing overflows. ``2 <Y>/t`` is the MEGNO-slope estimate of it.

A chaos map of the FLI alone (``IndicatorRun("fli")``, the default) integrates
only the state and ``w' = J w`` itself, without renormalisation or MEGNO quadratures
(on heyoka 12 variables instead of 17, no division per step, each right-hand side one
product per body coefficient,
:func:`~andoyer.integrate.engines.heyoka_symbolic.coefficient_tangent_system`, in
batches of twice heyoka's SIMD width); the few orbits whose
``ln|w|`` nears overflow (> 600, a double overflows at 709) are integrated again
renormalised. Both routes give the same FLI to 1e-8 on regular orbits (tested).

The tangent space
-----------------
``|gamma|^2``, ``(G, gamma)`` and ``H`` are first integrals of (1), so for each of them
``grad I(y(t)) . w(t)`` is constant along the linearised flow: a tangent vector that
starts orthogonal to a gradient stays so, and no projection is needed while
integrating. The default initial vector (``tangent="leaf"``) is orthogonal to the two
Casimir gradients: ``w`` stays tangent to the symplectic leaf ``|gamma| = 1``,
``(G, gamma) = M`` of the reduced two-degree-of-freedom system, so the Casimir
directions (which, being conserved, could add at most a linear shear) never enter.
It keeps a component across the energy levels, whose shear makes ``|w|`` grow
linearly on every regular orbit, tori and periodic orbits alike: ``<Y> -> 2`` there,
quickly. ``tangent="energy"`` is also orthogonal to ``grad H``: ``w`` stays tangent
to the energy level, and the MEGNO has its iso-energetic limits, 2 on a torus (more
slowly: the shear between tori of one level is weaker) and 0 on a stable periodic
orbit. Either way the initial vector is the orthogonal projection of one fixed generic
vector, the same for every state, so a map is deterministic and smooth in its
initial conditions.

References
----------
.. [1] V. V. Kyrychenko, "Andoyer-Deprit variables use to the Hess gyroscope phase
   trajectories exploring" (Eqs. (1), (5)-(7), (14)-(15)).
.. [2] C. Froeschle, E. Lega, R. Gonczi, "Fast Lyapunov indicators. Application to
   asteroidal motion", Celest. Mech. Dyn. Astron. 67, 41-62 (1997).
.. [3] P. M. Cincotta, C. Simo, "Simple tools to study global dynamics in
   non-axisymmetric galactic potentials - I", Astron. Astrophys. Suppl. 147, 205 (2000).
"""

from __future__ import annotations

from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from andoyer.analysis.chaos.registry import INDICATORS, MAP_EXTRAS, chosen
from andoyer.analysis.chaos.specs import (
    TANGENT_SPACES,
    IndicatorRun,
    MapGrid,
    Tangent,
)
from andoyer.analysis.chaos.tangent_space import initial_tangent
from andoyer.body import RigidBody, checks_body
from andoyer.charts.andoyer_deprit import from_andoyer
from andoyer.charts.euler_poisson import STATE
from andoyer.charts.hess import from_hess
from andoyer.charts.integrals import INTEGRALS
from andoyer.errors import IntegrationError
from andoyer.integrate import budget
from andoyer.integrate.api import initial_states
from andoyer.integrate.engines import EngineLike, engines_with, resolve_engine
from andoyer.integrate.engines.base import Capability, EngineBase, TangentFlow, Tolerance
from andoyer.integrate.fill import fill_section, section_roots
from andoyer.integrate.results import (
    VARIABLE_ATTRS,
    describe_variables,
    provenance,
    values_from_attrs,
)
from andoyer.integrate.variational import MEGNO_DELTA
from andoyer.notation import COORDINATE
from andoyer.progress import Progress
from andoyer.validation import checks_arguments, finite, integer, positive

#: Longer names of arguments in messages (andoyer.validation.checks_arguments).
ARGUMENT_NAMES = {"w0": "w0 (initial tangent direction)"}

__all__ = ["indicators", "chaos_map", "MapGrid", "IndicatorRun", "initial_tangent",
           "output_times", "INDICATORS", "TANGENT_SPACES"]

#: chaos_map's default grid and run (frozen: one object shared by every call).
DEFAULT_GRID = MapGrid()
DEFAULT_RUN = IndicatorRun()

#: ln|w| beyond which a tangent vector integrated without renormalisation is integrated
#: again renormalised (``|w|`` overflows a double at ln|w| ~ 709).
_OVERFLOW_LOG = 600.0

# ----------------------------------------------------------------------------- helpers


def _engine(engine: EngineLike, workload: str = "tangent", **options: Any) -> EngineBase:
    """The engine (name or instance; ``None``: the default of ``workload``, heyoka where
    installed, else taylor)."""
    able = engines_with(Capability.TANGENT)
    if not (engine is None or isinstance(engine, str | EngineBase)) \
            or (isinstance(engine, str) and engine not in able):
        raise ValueError(f"engine {engine!r} cannot integrate the variational equations; "
                         f"choose one of {', '.join(able)}")
    return resolve_engine(engine, Capability.TANGENT, workload=workload, **options)


def log_norm_of_flow(flow: TangentFlow, t: NDArray[np.float64]) -> NDArray[np.float64]:
    """``ln|w(t)|`` of a tangent flow's first vector at its output times ``t``.

    Parameters
    ----------
    flow : TangentFlow
        A tangent flow of one vector (:meth:`~andoyer.integrate.engines.base.EngineBase.
        tangent`).
    t : ndarray, shape (k,)
        Its output times.
    """
    return flow.rho[..., 0]


def fli_of_flow(flow: TangentFlow, t: NDArray[np.float64]) -> NDArray[np.float64]:
    """The FLI ``sup_{s <= t} ln|w(s)|`` over the output times ``t`` (Froeschle et al.).

    Parameters
    ----------
    flow : TangentFlow
        A tangent flow of one vector.
    t : ndarray, shape (k,)
        Its output times.
    """
    return np.fmax.accumulate(flow.rho[..., 0], axis=-1)


def mle_of_flow(flow: TangentFlow, t: NDArray[np.float64]) -> NDArray[np.float64]:
    """The finite-time maximal Lyapunov exponent ``ln|w(t)| / t`` (NaN at ``t = 0``).

    Parameters
    ----------
    flow : TangentFlow
        A tangent flow of one vector.
    t : ndarray, shape (k,)
        Its output times.
    """
    with np.errstate(divide="ignore", invalid="ignore"):
        out: NDArray[np.float64] = np.where(t > 0.0, flow.rho[..., 0] / t, np.nan)
    return out


def megno_y_of_flow(flow: TangentFlow, t: NDArray[np.float64]) -> NDArray[np.float64]:
    """MEGNO ``Y(t) = (2/t) int_0^t s (w'.w)/(w.w) ds`` from the flow's quadratures
    (exact: the shift ``delta`` of the weights taken out; 0 at ``t = 0``).

    Parameters
    ----------
    flow : TangentFlow
        A renormalised tangent flow of one vector, with its MEGNO quadratures.
    t : ndarray, shape (k,)
        Its output times.
    """
    assert flow.megno is not None
    with np.errstate(divide="ignore", invalid="ignore"):
        out: NDArray[np.float64] = np.where(
            t > 0.0, 2.0 * (flow.megno[..., 0] - MEGNO_DELTA * flow.rho[..., 0]) / t, 0.0)
    return out


def megno_of_flow(flow: TangentFlow, t: NDArray[np.float64]) -> NDArray[np.float64]:
    """The mean MEGNO ``<Y>(t) = (1/t) int_0^t Y(s) ds`` (Cincotta & Simo), the weights
    shifted by ``delta`` (a relative change ``O(delta / t)``).

    Parameters
    ----------
    flow : TangentFlow
        A renormalised tangent flow of one vector, with its MEGNO quadratures.
    t : ndarray, shape (k,)
        Its output times.
    """
    assert flow.megno is not None
    out: NDArray[np.float64] = flow.megno[..., 1] / (t + MEGNO_DELTA)
    return out


def _derived(flow: TangentFlow, t: NDArray[np.float64],
             names: tuple[str, ...] | None = None) -> dict[str, NDArray[np.float64]]:
    """The indicators ``names`` (default: every one of :data:`INDICATORS`) from a
    tangent flow (one vector) at times ``t`` (k,)."""
    return {k: INDICATORS[k].function()(flow, t) for k in (names or tuple(INDICATORS))}


def _fli_only(eng: EngineBase, y: NDArray[np.float64], w: NDArray[np.float64],
              params: Any, tol: float, t: NDArray[np.float64]
              ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64],
                         NDArray[np.bool_]]:
    """FLI and ``ln|w(t_end)|/t_end`` at ``t[-1]``, the final states and success flags:
    the state and ONE tangent vector, not renormalised (no MEGNO quadratures: about
    two thirds of the variables and no division per step); orbits whose ``ln|w|``
    nears overflow (:data:`_OVERFLOW_LOG`) or that failed are integrated again
    renormalised."""
    flow = eng.tangent(y, w[:, None, :], params, Tolerance.single(tol), t=t,
                       renormalise=False)
    rho = flow.rho[..., 0]
    with np.errstate(invalid="ignore"):
        redo = np.flatnonzero(~flow.ok | ~(np.max(rho, axis=1) < _OVERFLOW_LOG))
    fli = np.max(rho, axis=1)
    mle = rho[:, -1] / t[-1]
    y_end, ok = flow.y[:, -1].copy(), flow.ok.copy()
    if redo.size:
        again = eng.tangent(y[redo], w[redo, None, :], params, Tolerance.single(tol), t=t,
                            scale=float(t[-1]))
        fli[redo] = np.max(again.rho[..., 0], axis=1)
        mle[redo] = again.rho[:, -1, 0] / t[-1]
        y_end[redo], ok[redo] = again.y[:, -1], again.ok
    fli[~ok], mle[~ok] = np.nan, np.nan
    return fli, mle, y_end, ok


# ----------------------------------------------------------------------------- single orbits


@checks_arguments(ranges={"t_end": "time", "n_times": "count"})
def output_times(t_end: float, n_times: int, t: ArrayLike | None) -> NDArray[np.float64]:
    """The output times of an indicator: ``t`` if given (checked: 1-D, increasing, finite,
    starting at 0), else ``linspace(0, t_end, n_times)``.

    Parameters
    ----------
    t_end : float
        Final time (body time units, > 0), used when ``t`` is None.
    n_times : int
        Number of output times (>= 2), used when ``t`` is None.
    t : array_like, optional
        Explicit output times: 1-D, increasing, finite, starting at 0.

    Examples
    --------
    >>> output_times(10.0, 3, None)
    array([ 0.,  5., 10.])
    """
    if t is None:
        T = positive("t_end", t_end)
        return np.linspace(0.0, T, integer("n_times", n_times, 2))
    times = np.asarray(t, dtype=float)
    if times.ndim != 1 or times.size < 2 or times[0] != 0.0 \
            or np.any(np.diff(times) <= 0.0) or not np.all(np.isfinite(times)):
        raise ValueError("t must be a 1-D array of increasing finite times starting "
                         "at 0 (the indicators count from t = 0)")
    return times



@checks_body(ranges={"t_end": "time", "n_times": "count", "tol": "tolerance"},
             labels=ARGUMENT_NAMES)
def indicators(body: RigidBody, y0: ArrayLike, t_end: float = 1000.0, *, n_times: int = 101,
               t: ArrayLike | None = None, chart: str = "euler_poisson",
               tangent: Tangent = "leaf", w0: ArrayLike | None = None,
               tol: float = 1e-12, engine: str | None = None) -> xr.Dataset:
    """FLI, MEGNO and the maximal Lyapunov exponent of orbits as functions of time.

    Parameters
    ----------
    body : RigidBody
    y0 : array_like, shape (6,) or (n, 6) (or (5,)/(n, 5) in the other charts)
        Initial states in ``chart`` coordinates.
    t_end : float, default 1000
        Final time (body time units).
    n_times : int, default 101
        Output times ``linspace(0, t_end, n_times)`` (ignored when ``t`` is given).
        The FLI's supremum is taken over them.
    t : array_like, optional
        Increasing output times starting at 0.
    chart : {"euler_poisson", "andoyer", "hess"}
        Chart of ``y0``.
    tangent : {"leaf", "energy"}
        Space of the initial tangent vector (see the module docstring).
    w0 : array_like, shape (6,) or (n, 6), optional
        A direction to project onto that space instead of the fixed generic vector.
    tol : float, default 1e-12
        Tolerance of the Taylor integrator (DOP853 gets ``0.025 tol``).
    engine : str or Engine, optional
        Any engine with the ``tangent`` capability (:func:`andoyer.integrate.engines.
        capability_table`). Default: heyoka where installed, else taylor (the Taylor
        method in Numba, orbits in parallel); ``"numba"``: the Numba DOP853;
        ``"scipy"``: ``solve_ivp(DOP853)`` on the same equations, one orbit at a time
        (a slow independent check).

    Returns
    -------
    xarray.Dataset
        Dims ``(orbit, time)``: ``fli``, ``log_norm``, ``megno_y`` (Y), ``megno``
        (<Y>), ``mle``, the Euler-Poisson state ``G1 .. gamma3`` and ``H_drift``
        (``(H - H(0)) / max(|H(0)|, mu)``); ``w0`` (orbit, component). Attrs: body,
        engine, tolerance, heyoka version, definitions.

    Raises
    ------
    ValueError
        Invalid inputs; FloatingPointError if an integration fails.

    Examples
    --------
    >>> ds = indicators(RigidBody.paper(), [0.3, 0.0, 0.3, 1.0, 0.0], 200.0,
    ...                 chart="andoyer")
    >>> bool(1.5 < float(ds.megno.isel(orbit=0, time=-1)) < 2.0)
    True
    """
    eng = _engine(engine)
    tol = Tolerance.single(tol).tol
    y = initial_states(body, y0, chart)
    times = output_times(t_end, n_times, t)
    T = float(times[-1])
    budget.check("indicators", steps=3.0 * budget.estimate_steps(body, y, T, tol),
                 memory=8.0 * 20 * y.shape[0] * times.size)
    w = initial_tangent(body, y, tangent, w0)
    flow = eng.tangent(y, w[:, None, :], body.engine_params, Tolerance.single(tol), t=times,
                       scale=T)
    if not flow.ok.all():
        bad = np.flatnonzero(~flow.ok).tolist()
        raise IntegrationError(f"the variational integration failed (non-finite state) "
                                 f"for orbits {bad}")
    data: dict[str, Any] = {k: (("orbit", "time"), v) for k, v in _derived(flow, times).items()}
    for k, s in enumerate(STATE):
        data[s] = (("orbit", "time"), flow.y[..., k])
    H = INTEGRALS["H"](body, flow.y)
    data["H_drift"] = (("orbit", "time"), INTEGRALS["H"].drift(body, H, flow.y[:, :1]))
    data["w0"] = (("orbit", "component"), w)
    ds = xr.Dataset(data, coords={"orbit": np.arange(y.shape[0]), "time": times,
                                  "component": list(STATE)},
                    attrs=_provenance(body, eng, tol, tangent, T, initial_chart=chart))
    _describe(ds)
    ds.H_drift.attrs.update(long_name="(H - H(0)) / max(|H(0)|, mu)", units="1")
    ds.w0.attrs.update(long_name="initial unit tangent vector")
    ds.time.attrs.update(units="body time units", long_name="time")
    return ds


def _provenance(body: RigidBody, engine: EngineBase, tol: float, tangent: str, T: float,
                renormalised: bool = True, **extra: Any) -> dict[str, Any]:
    meta = engine.provenance()
    built = meta.pop("tangent_method")
    how = ("unit tangent vector w/|w| and ln|w| integrated (continuous renormalisation)"
           if renormalised else
           f"tangent vector w integrated as is (FLI only; renormalised where "
           f"ln|w| > {_OVERFLOW_LOG:g})")
    return provenance(
        body, **meta, tolerance=tol, t_end=T, tangent=tangent, megno_delta=MEGNO_DELTA,
        equations="Euler-Poisson equations (1) of Kyrychenko with their first-order "
                  f"variational equations ({built}), {how}",
        **extra)


def _describe(ds: xr.Dataset) -> None:
    for name, spec in INDICATORS.items():
        if name in ds:
            ds[name].attrs.update(spec.attrs)
    describe_variables(ds, units=False)


# ----------------------------------------------------------------------------- maps


@checks_body(ranges={"h": "energy", "M": "action"})
def chaos_map(body: RigidBody, h: float, M: float, section: Any,
              grid: MapGrid | int | tuple[int, int] = DEFAULT_GRID,
              run: IndicatorRun = DEFAULT_RUN, *, engine: EngineLike = None,
              chunk: int = 1024, progress: bool | None = None) -> xr.Dataset:
    """FLI and/or MEGNO over a grid of a section's plane, on the energy level ``H = h``.

    Every grid point of the plane -- ``(l, L)`` of a ``g = const`` section or
    ``(theta1, J1)`` of a ``theta2 = const`` section -- with the remaining action
    solved from ``H = h`` (:func:`andoyer.integrate.fill.section_roots`) is an initial
    state (:class:`~andoyer.analysis.chaos.specs.MapGrid`); its orbit is integrated with
    the variational equations to ``t_end``
    (:class:`~andoyer.analysis.chaos.specs.IndicatorRun`).

    Parameters
    ----------
    body : RigidBody
        Any body; the Hess plane needs ``e3 = 0``.
    h : float
        Energy level.
    M : float
        Area constant ``(G, gamma)``.
    section : (coord, value), str or object with ``.coord``, ``.value``
        ``("g", g*)`` or ``"g=0"`` (plane ``(l, L)``, ``G`` solved), ``("theta2",
        theta2*)`` (plane ``(theta1, J1)``, ``J2`` solved).
    grid : MapGrid, int or (nx, ny), default MapGrid()
        The starts: ``n`` (an integer or ``(nx, ny)`` alone is ``MapGrid(n)``), the
        plane's box ``plane_bounds`` and the ``root`` where the level has several sheets.
    run : IndicatorRun, default IndicatorRun()
        What is integrated from each start: ``indicator`` (``"fli"``, ``"megno"`` or
        ``"both"``; one integration gives both, ``"fli"`` alone integrates only the state
        and one tangent vector, see the module notes), ``t_end``, ``n_samples`` (output
        times over which the FLI's supremum is taken), ``tangent`` (space of the initial
        tangent vector), ``tol``.
    engine : str or Engine, optional
        Any engine with the ``tangent`` capability. Default: taylor, for the FLI alone
        and with MEGNO (SIMD lanes, the renormalised flow with the MEGNO quadratures
        too; measured faster than heyoka on these maps:
        :data:`~andoyer.integrate.engines.MEASURED_DEFAULTS`); heyoka (batch mode and
        threads) on request; scipy is one orbit at a time, for checks. heyoka's SIMD
        batch size and threads are options of the engine: ``resolve_engine("heyoka",
        batch_size=4, n_threads=1)``.
    chunk : int, default 1024
        Orbits integrated together: memory is bounded by ``chunk * (n_samples + 1) * 15``
        doubles; the progress line advances per chunk.
    progress : bool, optional
        Progress line on stderr (default: when stderr is a terminal).

    Returns
    -------
    xarray.Dataset
        Dims ``(y, x)`` named after the plane (``L_action, l_angle`` or ``J1, theta1``):
        the indicator(s) ``fli`` and/or ``megno`` (<Y> at ``t_end``), ``mle``
        (``ln|w(t_end)|/t_end``), ``accessible`` (the level meets the point), the solved
        action, ``H_error`` (``|H(t_end) - h| / max(|h|, mu)``); NaN outside the
        accessible region and where an integration failed (``n_failed`` attr). Dim
        ``boundary_vertex``: ``boundary_x``, ``boundary_y``, the accessible region's
        boundary (NaN-separated polylines). Attrs: body, h, M, section, plane, t_end,
        tolerance, engine, heyoka version, grid, definitions.

    Notes
    -----
    The result depends only on the arguments (and the batch size, through round-off):
    threads and chunks do not change it, except on taylor, where a chunk of fewer than
    :data:`~andoyer.integrate.engines.taylor_engine.LANES_FROM` orbits runs on the
    scalar kernel rather than the SIMD lanes (the same steps, another order of the
    fused multiply-adds: round-off). The compiled integrator is cached per process
    and on disk, so repeated calls, e.g. one per point of a parameter sweep in worker
    processes, pay the compilation once.

    Examples
    --------
    >>> ds = chaos_map(RigidBody.paper(), 0.2466, 0.0, "theta2=0", grid=4,
    ...                run=IndicatorRun(t_end=50.0))
    >>> ds.fli.dims, int(ds.accessible.sum()) > 0
    (('J1', 'theta1'), True)
    """
    spec, job = MapGrid.of(grid), IndicatorRun.of(run)
    eng = _engine(engine, "fli_map" if job.indicator == "fli" else "megno_map")
    h = finite("h", h)
    M = finite("M", M)
    nx, ny = spec.n  # type: ignore[misc]
    # Grid, roots and result arrays: about 400 bytes per grid point; checked before any.
    budget.check("chaos_map", memory=400.0 * nx * ny)
    T, indicator, n_samples, tangent, tol = (job.t_end, job.indicator, job.n_samples,
                                             job.tangent, job.tol)
    root, plane_bounds = spec.root, spec.plane_bounds
    chunk = integer("chunk", chunk, 1)
    # The plane, its box and the accessible boundary; raises if h misses the section.
    fill = fill_section(body, h, M, section, n_orbits=1, plane_bounds=plane_bounds,
                        boundary_grid=min(200, max(64, 2 * max(nx, ny))))
    a = fill.attrs
    xname, yname, action = str(a["plane_x"]), str(a["plane_y"]), str(a["action"])
    chart, value = str(a["section_chart"]), float(a["section_value"])
    x0, x1 = float(a["plane_x_min"]), float(a["plane_x_max"])
    y0, y1 = float(a["plane_y_min"]), float(a["plane_y_max"])
    if plane_bounds is None:
        # The action axis is cropped to the accessible rows (plus one cell of the fine
        # grid): no grid row is spent above the level. The angle keeps its full turn.
        fine = fill.plane_y.values
        rows = np.flatnonzero(fill.accessible.values.any(axis=0))
        step = fine[1] - fine[0]
        y0, y1 = max(y0, fine[rows[0]] - step), min(y1, fine[rows[-1]] + step)
    xs = x0 + (np.arange(nx) + 0.5) * (x1 - x0) / nx
    ys = y0 + (np.arange(ny) + 0.5) * (y1 - y0) / ny
    Yg, Xg = np.meshgrid(ys, xs, indexing="ij")  # (ny, nx)
    roots = section_roots(body, h, M, (str(a["section_coord"]), value), Xg, Yg)
    count = np.fromiter((r.size for r in roots), dtype=np.intp, count=len(roots))
    acc = (count > 0).reshape(ny, nx)
    idx = np.flatnonzero(acc.ravel())
    A = np.full(ny * nx, np.nan)
    if idx.size:
        # The smallest (or largest) root of each accessible point, from the roots laid
        # end to end (ascending per point).
        end = np.cumsum(count)
        A[idx] = np.concatenate(roots)[end[idx] - 1 if root == "largest"
                                       else end[idx] - count[idx]]
    P = np.stack([Xg.ravel()[idx], np.full(idx.size, value), Yg.ravel()[idx], A[idx],
                  np.full(idx.size, M)], axis=-1)
    states = from_andoyer(P) if chart == "andoyer" else from_hess(body, P)
    times = np.linspace(0.0, T, n_samples + 1)
    # The variational system (state, tangent vector, MEGNO integrals) costs about three
    # plain steps per step.
    budget.check("chaos_map", steps=3.0 * budget.estimate_steps(body, states, T, tol))
    params = body.engine_params
    # One set-up for the whole map (heyoka: one batch size), so that the chunking
    # cannot change round-off.
    eng = eng.for_ensemble(idx.size)
    name = eng.name

    stored = (*chosen(indicator), *MAP_EXTRAS)
    out = {k: np.full(ny * nx, np.nan) for k in (*stored, "H_error")}
    n_failed = 0
    renormalised = job.renormalised
    bar = Progress(idx.size, f"chaos map ({name}, {nx}x{ny}, t = {T:g})", progress)
    for s in range(0, idx.size, chunk):
        sel = idx[s:s + chunk]
        y = states[s:s + chunk]
        w = initial_tangent(body, y, tangent)
        if renormalised:
            flow = eng.tangent(y, w[:, None, :], params, Tolerance.single(tol), t=times,
                               scale=T)
            for k, v in _derived(flow, times, stored).items():
                out[k][sel] = v[:, -1]
            y_end, ok = flow.y[:, -1], flow.ok
        else:  # the FLI alone (and the MLE): the raw tangent vector
            out["fli"][sel], out["mle"][sel], y_end, ok = _fli_only(eng, y, w, params, tol,
                                                                    times)
        out["H_error"][sel] = np.abs(INTEGRALS["H"].drift(
            body, INTEGRALS["H"](body, y_end), y_end, h))
        n_failed += int(np.sum(~ok))
        bar.update(sel.size)
    bar.close()

    dims = (yname, xname)
    data: dict[str, Any] = {k: (dims, out[k].reshape(ny, nx)) for k in stored}
    data["accessible"] = (dims, acc)
    data[action] = (dims, A.reshape(ny, nx))
    data["H_error"] = (dims, out["H_error"].reshape(ny, nx))
    data["boundary_x"] = (("boundary_vertex",), fill.boundary_x.values)
    data["boundary_y"] = (("boundary_vertex",), fill.boundary_y.values)
    ds = xr.Dataset(
        data,
        coords={xname: (xname, xs, {**_coord_attrs(xname), "grid": "cell centres"}),
                yname: (yname, ys, {**_coord_attrs(yname), "grid": "cell centres"})},
        attrs=_provenance(
            body, eng, tol, tangent, T, renormalised, h=h, M=M,
            section_coord=str(a["section_coord"]), section_value=value,
            section_chart=chart, plane_x=xname, plane_y=yname, action=action, root=root,
            indicator=indicator, nx=nx, ny=ny,
            n_samples=n_samples, n_accessible=int(idx.size), n_failed=n_failed,
            plane_x_min=x0, plane_x_max=x1, plane_y_min=y0, plane_y_max=y1,
            plane_equations=str(a["equations"]),
            units="dimensionless: moments of inertia, mu, energies, actions and time in "
                  "the body's units; angles in rad"))
    _describe(ds)
    values_from_attrs(ds, {
        "n_accessible": ("", "grid points where the level meets the plane", "1", ""),
        "n_failed": ("", "grid points whose integration failed (NaN)", "1", "")})
    ds.accessible.attrs.update(long_name=f"the level H = h meets ({xname}, {yname})")
    ds[action].attrs.update(long_name=f"{action} solved from H = h ({root} root)")
    ds.H_error.attrs.update(long_name="|H(t_end) - h| / max(|h|, mu)", units="1")
    ds.boundary_x.attrs.update(long_name=f"{xname} on the accessible boundary (NaN: new line)")
    ds.boundary_y.attrs.update(long_name=f"{yname} on the accessible boundary (NaN: new line)")
    return ds


def _coord_attrs(name: str) -> dict[str, str]:
    if name not in VARIABLE_ATTRS:
        return {}
    sym, long, eqn = VARIABLE_ATTRS[name]
    units = COORDINATE[name].units if name in COORDINATE else "1"
    return {"symbol": sym, "long_name": long, "equation": eqn, "units": units}
