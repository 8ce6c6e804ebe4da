"""What a scan computes at one point of its grid: a registry of task kinds.

A *task kind* turns one body and one pair of levels ``(h, M)`` of the integrals of
Eq. (1) -- the energy ``H = h`` and the area integral ``(G, gamma) = M`` -- into an
:class:`xarray.Dataset` with the task's own dims (``orbit``, ``crossing`` for a
Poincare section; the plane of a chaos map). The scan adds the swept dims around it.

Registered kinds (:data:`TASKS`):

``section``
    :func:`andoyer.integrate.fill_section` seeds ``n_orbits`` initial states on the
    section plane at ``(h, M)``, and the first ``n_crossings`` crossings of each orbit
    are found by the engine (the computation of :func:`andoyer.integrate.poincare`).
``chaos_map``
    :func:`andoyer.analysis.chaos.lyapunov.chaos_map` (FLI or MEGNO over a grid of the section
    plane), enabled when that module is installed.
``splitting``
    :func:`andoyer.analysis.splitting.measure.separatrix_splitting` at the point's mu: the
    splitting of the separatrices of the rotations about the middle axis, measured and
    predicted by Melnikov (sweep mu, and A, B, C, to see how it scales; sweep epsilon
    to split the Hess branch ``theta1 = 0``).
``chaos_border``
    :func:`andoyer.analysis.chaos.border.chaos_border`: the chaotic fraction of the
    section plane from MEGNO (threshold from the regular free top) and the width of the
    chaotic layer around the former Hess separatrix; sweep ``mu`` and ``epsilon`` for
    the border of chaos (``andoyer atlas`` draws it).

Determinism
-----------
Every task runs single-threaded inside its worker: the heyoka engine with one thread,
the numba engine with ``numba.set_num_threads(1)`` (parallelism comes from the
workers). Each orbit is integrated independently of the others and of the thread
count, so a point gives the same numbers in a serial run, on a local cluster and on
any cluster of the same CPU type (heyoka's SIMD batch width follows the CPU: mixing
CPU types may change results at the 1e-10 level).
"""

from __future__ import annotations

import math
import numbers
import warnings
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from functools import cache
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np
import xarray as xr

from andoyer.analysis.chaos.registry import INDICATORS, MAP_INDICATORS
from andoyer.analysis.unperturbed.separatrix import DEFAULT_BRANCH
from andoyer.validation import integer

if TYPE_CHECKING:
    from andoyer.body import RigidBody
    from andoyer.integrate.engines.base import Engine

__all__ = ["TASKS", "TaskKind", "Option", "Empty", "Integrator", "REQUIRED"]


class _Required:
    def __repr__(self) -> str:
        return "REQUIRED"


#: Default of an option that has none: the configuration must give it.
REQUIRED: Any = _Required()


class Integrator(NamedTuple):
    """Engine and tolerances of every integration of a scan.

    Parameters
    ----------
    engine : str
        Engine name.
    rtol, atol : float
        Tolerances.
    """

    engine: str
    rtol: float
    atol: float


@dataclass(frozen=True)
class Empty:
    """A point with nothing to compute (e.g. the energy level misses the section).

    Attributes
    ----------
    reason : str
        Why there is nothing to compute.
    """

    reason: str


@dataclass(frozen=True)
class Option:
    """One key of a task's ``[task]`` table: default, validation, documentation.

    Attributes
    ----------
    default : object
        Its value when the table does not set it.
    check : callable
        ``check(name, value) -> value``: the validation, raising ``ValueError`` naming the key.
    doc : str
        What it is, for the documentation.
    """

    default: Any
    check: Callable[[str, Any], Any]
    doc: str


@dataclass(frozen=True)
class TaskKind:
    """A kind of task: its options, how to run one point, and what it costs.

    Attributes
    ----------
    name : str
        The ``kind`` in the ``[task]`` table.
    options : mapping str -> Option
        The other keys of ``[task]``.
    run : callable ``(body, h, M, options, integrator) -> Dataset | Empty``
        One point; raise ``ValueError`` for a point that cannot be computed (it is
        stored empty, with the reason reported).
    cost : callable ``options -> (core seconds, stored values)`` per point
        A rough estimate, for the size check of a configuration.
    fixed_coords : tuple of str
        Coordinates of the task's dims that are the same at every point (kept as
        coordinates); other coordinates are stored as variables ``<name>_values``.
    validate : callable ``(options, bodies, integrator) -> None``, optional
        Checks that need the bodies of the grid (e.g. a Hess-chart section needs the
        centre of mass in the G1-G2 plane) or the engine.
    static_attrs : tuple of str
        Attributes of a point's result that are the same at every point: copied to the
        store's attrs.
    levels : tuple of str
        Which of the levels ``h``, ``M`` are parameters of the task (``run`` gets None
        for the others); ``levels_note`` says why a level is not one.
    doc : str
        What the task computes, for the documentation.
    levels_note : str
        Why a level is not one of the task's parameters (empty where both are).
    """

    name: str
    doc: str
    options: Mapping[str, Option]
    run: Callable[..., xr.Dataset | Empty]
    cost: Callable[[Mapping[str, Any]], tuple[float, float]]
    fixed_coords: tuple[str, ...] = ()
    validate: Callable[[Mapping[str, Any], list[RigidBody], Integrator], None] | None = None
    static_attrs: tuple[str, ...] = ()
    levels: tuple[str, ...] = ("h", "M")
    levels_note: str = ""


# ---------------------------------------------------------------------- option checks
def _int_at_least(lo: int) -> Callable[[str, Any], int]:
    def check(key: str, v: Any) -> int:
        return integer(key, v, lo)
    return check


def _choice(*allowed: str) -> Callable[[str, Any], str]:
    def check(key: str, v: Any) -> str:
        if v not in allowed:
            raise ValueError(f"{key} must be one of {', '.join(map(repr, allowed))}, "
                             f"got {v!r}")
        return str(v)
    return check


def _positive_or_none(key: str, v: Any) -> float | None:
    if v is None:
        return None
    if isinstance(v, bool) or not isinstance(v, numbers.Real) or not (
            math.isfinite(float(v)) and float(v) > 0):
        raise ValueError(f"{key} must be a positive finite number, got {v!r}")
    return float(v)


def _positive(key: str, v: Any) -> float:
    out = _positive_or_none(key, v)
    if out is None:
        raise ValueError(f"{key} must be a positive finite number, got {v!r}")
    return out


def _section_text(fillable: bool) -> Callable[[str, Any], str]:
    def check(key: str, v: Any) -> str:
        from andoyer.integrate import Section

        if not isinstance(v, str):
            raise ValueError(f"{key} must be a string like 'theta2=0' or 'g=0:-', got {v!r}")
        sec = Section.parse(v)
        if fillable and sec.coord not in ("g", "theta2"):
            raise ValueError(
                f"{key} = {v!r}: a scan seeds its orbits on the section plane, which is "
                "defined for 'g=VALUE' (plane (l, L)) and 'theta2=VALUE' (plane "
                "(theta1, J1)) sections")
        return f"{sec.coord}={sec.value!r}:{sec.direction:+d}"
    return check


def _pair_of_ints(key: str, v: Any) -> list[int]:
    if (not isinstance(v, list) or len(v) != 2
            or any(isinstance(k, bool) or not isinstance(k, numbers.Integral) or k < 2
                   for k in v)):
        raise ValueError(f"{key} must be two integers >= 2 ([nx, ny]), got {v!r}")
    return [int(k) for k in v]


def _needs_planar(options: Mapping[str, Any], bodies: list[RigidBody],
                  integ: Integrator) -> None:
    if not str(options["section"]).startswith("theta"):
        return
    bad = [b for b in bodies if abs(b.e3) > 1e-12]
    if bad:
        raise ValueError(
            f"task.section = {options['section']!r} is a Hess-chart section, which needs "
            f"the centre of mass in the G1-G2 plane (e3 = 0), but e3 = {bad[0].e3:.6g}; "
            "use a 'g=VALUE' section or r = [e1, e2, 0]")


# ---------------------------------------------------------------------- engines
@cache
def _engine(name: str) -> Engine:
    """The engine a task uses, single-threaded (the workers give the parallelism).

    Cached per process, and heyoka's compiled integrators are pooled per process, so a
    worker compiles (or loads from heyoka's on-disk cache) once and reuses them.
    """
    from andoyer.integrate.engines import resolve_engine

    return resolve_engine(name, n_threads=1)


# ---------------------------------------------------------------------- section
#: Variables of :func:`~andoyer.integrate.poincare` a scan does not store (per-orbit
#: diagnostics of singular passages, with a dimension of their own).
_POINCARE_ONLY = ("momentum_scale", "singular_passages", "singular_passage_t")


def _pick_orbits(y0: np.ndarray, n: int, sampling: str) -> np.ndarray:
    """``n`` rows of the fill: a prefix of a low-discrepancy sequence, or an even subset
    of a grid (whose rows are ordered along the plane, so a prefix would cut it)."""
    if y0.shape[0] <= n:
        return y0
    if sampling == "grid":
        return y0[np.round(np.linspace(0, y0.shape[0] - 1, n)).astype(np.intp)]
    return y0[:n]


def _section_point(body: RigidBody, h: float, M: float, options: Mapping[str, Any],
                   integ: Integrator) -> xr.Dataset | Empty:
    """Poincare section at ``(h, M)``: dims ``(orbit, crossing)``, NaN-padded.

    :func:`~andoyer.integrate.poincare` of the rows of
    :func:`~andoyer.integrate.fill_section`, on this worker's single-threaded engine;
    its singular passages (no crossings) are not stored.
    """
    from andoyer.errors import SingularPassageWarning
    from andoyer.integrate import Section
    from andoyer.integrate.api import poincare
    from andoyer.integrate.fill import fill_section

    sec = Section.parse(options["section"])
    n, k = int(options["n_orbits"]), int(options["n_crossings"])
    try:
        fill = fill_section(body, h, M, (sec.coord, sec.value), n_orbits=n,
                            sampling=options["sampling"], seed=options["seed"],
                            boundary_grid=options["boundary_grid"])
    except ValueError as exc:  # the level misses the section, or no admissible point
        return Empty(str(exc))
    y0 = _pick_orbits(fill["y0"].values, n, options["sampling"])
    m = y0.shape[0]
    t_max = 1000.0 * k if options["t_max"] is None else float(options["t_max"])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SingularPassageWarning)
        sec_ds = poincare(body, y0, sec, k, engine=_engine(integ.engine), rtol=integ.rtol,
                          atol=integ.atol, t_max=t_max, progress=False)
    keep = [v for v in sec_ds.data_vars if v not in _POINCARE_ONLY]
    ds = sec_ds[keep].reindex(orbit=np.arange(n), fill_value={"crossings_found": 0})
    ds.attrs = {}
    ds["n_orbits"] = ((), np.int64(m))
    ds.t.attrs.update(long_name="time of the crossing", units="body time units")
    ds.y0.attrs.update(long_name="initial Euler-Poisson state of the orbit, seeded on "
                                 "the section plane by fill_section",
                       components="G1 G2 G3 gamma1 gamma2 gamma3", equation="(1)")
    ds.crossings_found.attrs.update(long_name="crossings found within t_max")
    ds.section_residual.attrs.update(
        long_name=f"section equation {sec.coord} = {sec.value:g} at the crossing", units="1")
    ds.n_orbits.attrs.update(long_name="orbits seeded at this point (the rest is NaN)")
    return ds


def _section_cost(options: Mapping[str, Any]) -> tuple[float, float]:
    # Measured with heyoka on the paper's body (1 core): about 30 us per crossing and
    # 0.1 s to fill the plane at boundary_grid = 64; 25 stored values per crossing.
    n, k = options["n_orbits"], options["n_crossings"]
    fill = 0.1 * (options["boundary_grid"] / 64.0) ** 2
    return fill + 5e-5 * n * k, 25.0 * n * k


# ---------------------------------------------------------------------- chaos map
def _chaos_point(body: RigidBody, h: float, M: float, options: Mapping[str, Any],
                 integ: Integrator) -> xr.Dataset | Empty:
    """Chaos indicator over the section plane, :func:`andoyer.analysis.chaos.lyapunov.chaos_map`
    (one thread; heyoka's tolerance ``min(rtol, atol)``)."""
    from andoyer.analysis.chaos import lyapunov as chaos
    from andoyer.integrate import Section
    sec = Section.parse(options["section"])
    try:
        ds = chaos.chaos_map(
            body, h, M, (sec.coord, sec.value), chaos.MapGrid(tuple(options["n"])),
            chaos.IndicatorRun(options["indicator"], t_end=options["t_end"],
                               tol=min(integ.rtol, integ.atol)),
            engine=_engine(integ.engine), progress=False)
    except ValueError as exc:  # the level misses the section (arguments were validated)
        return Empty(str(exc))
    # The boundary polyline has a different length at every point: not stored (the
    # indicator is NaN outside the accessible region, which draws it).
    ds = ds.drop_dims("boundary_vertex", errors="ignore")
    for key in ("n_accessible", "n_failed"):
        if key in ds.attrs:
            ds[key] = ((), np.int64(ds.attrs[key]))
    return ds


def _chaos_cost(options: Mapping[str, Any]) -> tuple[float, float]:
    # Measured (heyoka, one core): ~3e-5 s per orbit and time unit with the variational
    # equations; ~6 stored values per cell.
    nx, ny = options["n"]
    return 3e-5 * nx * ny * options["t_end"], 6.0 * nx * ny


def _chaos_bodies(options: Mapping[str, Any], bodies: list[RigidBody],
                  integ: Integrator) -> None:
    _needs_planar(options, bodies, integ)


# ---------------------------------------------------------------------- splitting
def _even_at_least_4(key: str, v: Any) -> int:
    n = _int_at_least(4)(key, v)
    if n % 2:
        raise ValueError(f"{key} must be even, got {n}")
    return n


def _small_positive(key: str, v: Any) -> float:
    x = _positive(key, v)
    if x >= 0.1:
        raise ValueError(f"{key} must be in (0, 0.1) (a distance from the periodic orbit "
                         f"on its section), got {x!r}")
    return x


def _splitting_point(body: RigidBody, h: float | None, M: float | None,
                     options: Mapping[str, Any], integ: Integrator) -> xr.Dataset | Empty:
    """Separatrix splitting at this body's mu,
    :func:`andoyer.analysis.splitting.measure.separatrix_splitting` with one value of mu.

    Dims ``phase`` (the splitting grid on Sigma_0) and ``intersection`` (heteroclinic
    points, NaN-padded to ``n_phase``); the intersection variables are prefixed
    ``heteroclinic_`` (their ``g``, ``G`` become ``g_angle``, ``G_action``).
    """
    from andoyer.analysis.splitting import measure as manifolds
    try:
        out = manifolds.separatrix_splitting(
            body, [body.mu], G=options["G"], branch=options["branch"],
            delta=options["delta"], n_phase=options["n_phase"], progress=False,
            engine=integ.engine)
    except ValueError as exc:
        return Empty(str(exc))
    split = out["splitting"].isel(mu=0, drop=True)
    n = int(options["n_phase"])
    inter = out["intersections"].isel(mu=0, drop=True)
    inter = inter.reindex(intersection=np.arange(n))  # NaN-padded: a fixed length
    names = {"g": "g_angle", "G": "G_action"}
    inter = inter.rename({k: "heteroclinic_" + names.get(str(k), str(k))
                          for k in inter.data_vars})
    ds = xr.merge([split, inter], compat="override", combine_attrs="override")
    ds.attrs = dict(out["splitting"].attrs)
    for key in ("energy", "theta1_line", "rho", "melnikov_function_max", "epsilon"):
        if key in ds.attrs:
            ds[key] = ((), float(ds.attrs[key]))
    return ds


def _splitting_cost(options: Mapping[str, Any]) -> tuple[float, float]:
    # Measured on the paper's body (one core): ~3 s at n_phase = 8.
    n = options["n_phase"]
    return 1.0 + 0.25 * n, 15.0 * n


def _splitting_bodies(options: Mapping[str, Any], bodies: list[RigidBody],
                      integ: Integrator) -> None:
    from andoyer.integrate.engines import engine_class, engines_with
    from andoyer.integrate.engines.base import Capability

    able = engines_with(Capability.TANGENT_CROSSINGS)
    if Capability.TANGENT_CROSSINGS not in engine_class(integ.engine).capabilities:
        raise ValueError(f"the splitting task grows the manifolds with {' or '.join(able)} "
                         f"(tangent flows to a section); set [integrator] engine = "
                         f"\"{able[0]}\" (got {integ.engine!r})")
    for b in bodies:
        try:
            b.nearest_hess()
        except ValueError:
            raise ValueError(f"the splitting task needs a Hess body ([body] kind = \"hess\", "
                             f"turned by epsilon if you like), got A, B, C = {b.A:g}, "
                             f"{b.B:g}, {b.C:g}, r = {b.r}") from None
        if b.mu <= 0.0:
            raise ValueError(f"the splitting task needs mu > 0 (at mu = 0 the separatrices "
                             f"coincide), got mu = {b.mu:g}")


# ---------------------------------------------------------------------- chaos border
def _border_point(body: RigidBody, h: float, M: float, options: Mapping[str, Any],
                  integ: Integrator) -> xr.Dataset | Empty:
    """Chaotic fraction and layer width by
    :func:`~andoyer.analysis.chaos.border.chaos_border` (one thread; tolerance
    ``min(rtol, atol)``)."""
    from andoyer.analysis.chaos.border import chaos_border
    from andoyer.integrate import Section

    sec = Section.parse(options["section"])
    try:
        ds = chaos_border(body, h, M, (sec.coord, sec.value), n=tuple(options["n"]),
                          t_end=options["t_end"], margin=options["margin"],
                          engine=integ.engine, tol=min(integ.rtol, integ.atol),
                          n_threads=1, progress=False)
    except ValueError as exc:  # the level misses the section (arguments were validated)
        return Empty(str(exc))
    return ds.drop_dims("boundary_vertex", errors="ignore")


def _border_cost(options: Mapping[str, Any]) -> tuple[float, float]:
    # Measured (heyoka, one core, MEGNO on the body A, B, C = 2.5, 1, 1.6 at t_end = 300):
    # 0.5 s for a 24 x 24 map, 4-8 s for 96 x 48 with the free-top reference (computed
    # once per worker and level, cached); ~4 stored values per cell.
    nx, ny = options["n"]
    return 4e-6 * nx * ny * options["t_end"], 4.0 * nx * ny


# ---------------------------------------------------------------------- registry
_SECTION_OPTIONS = {
    "section": Option("theta2=0", _section_text(True),
                      "'theta2=VALUE' (plane (theta1, J1)) or 'g=VALUE' (plane (l, L)); "
                      "':+' (default) or ':-' for the crossing direction"),
    "n_orbits": Option(20, _int_at_least(1), "orbits per point (seeded by fill_section)"),
    "n_crossings": Option(300, _int_at_least(1), "crossings per orbit"),
    "sampling": Option("sobol", _choice("sobol", "halton", "grid"),
                       "how the orbits are seeded on the plane"),
    "seed": Option(0, _int_at_least(0), "seed of the scrambled Sobol/Halton points"),
    "boundary_grid": Option(64, _int_at_least(8),
                            "grid of the accessible-region search in fill_section"),
    "t_max": Option(None, _positive_or_none,
                    "integrate at most to this time (default 1000 x n_crossings)"),
}

#: Task kinds by name.
TASKS: dict[str, TaskKind] = {
    "section": TaskKind(
        "section", "Poincare section: fill_section + crossings (dims orbit, crossing)",
        _SECTION_OPTIONS, _section_point, _section_cost, ("orbit", "crossing"),
        validate=_needs_planar),
    "chaos_map": TaskKind(
        "chaos_map", f"chaos indicator ({' or '.join(INDICATORS[k].title for k in MAP_INDICATORS)})"
                     " over a grid of the section plane",
        {"section": Option("theta2=0", _section_text(True), "the section plane"),
         "n": Option([64, 64], _pair_of_ints, "grid [nx, ny] of the plane"),
         "t_end": Option(1000.0, _positive, "integration time of each orbit"),
         "indicator": Option("fli", _choice(*MAP_INDICATORS), "the chaos indicator")},
        _chaos_point, _chaos_cost,
        validate=_chaos_bodies,
        static_attrs=("indicator", "tangent", "t_end", "n_samples", "nx", "ny", "plane_x",
                      "plane_y", "action", "root", "plane_equations", "definitions",
                      "engine", "heyoka_version", "numba_version", "tolerance")),
    "splitting": TaskKind(
        "splitting", "separatrix splitting of the rotations about the middle axis",
        {"G": Option(1.0, _positive, "the level h = c G^2 / 2 of the rotation about the "
                                     "middle axis (at M = 0)"),
         "branch": Option(DEFAULT_BRANCH, _choice("theta1=0", "theta1=4phi0"),
                          "the heteroclinic line: theta1=0 (the Hess separatrix: splits "
                          "off the Hess direction, epsilon != 0) or theta1=4phi0"),
         "n_phase": Option(16, _even_at_least_4, "phases of the splitting grid (even)"),
         "delta": Option(1e-5, _small_positive,
                         "distance of the fundamental domains from the periodic orbits")},
        _splitting_point, _splitting_cost, ("phase", "intersection"),
        validate=_splitting_bodies,
        static_attrs=("branch", "sheet", "G_level", "psi0", "delta", "tolerance",
                      "long_double", "n_phase", "plane", "relation"),
        levels=(), levels_note="its level is h = c G^2 / 2 (option G) at M = 0"),
    "chaos_border": TaskKind(
        "chaos_border", "chaotic fraction (MEGNO) and the chaotic layer around the former "
                        "Hess separatrix",
        {"section": Option("theta2=0", _section_text(True), "the section plane: theta2 "
                           "(the layer width is measured) or g"),
         "n": Option([32, 32], _pair_of_ints, "grid [nx, ny] of the plane"),
         "t_end": Option(300.0, _positive, "integration time of each orbit"),
         "margin": Option(1.0, _positive, "MEGNO threshold above the regular reference")},
        _border_point, _border_cost,
        validate=_chaos_bodies,
        static_attrs=("indicator", "tangent", "t_end", "n_samples", "nx", "ny", "plane_x",
                      "plane_y", "action", "root", "plane_equations", "definitions",
                      "engine", "heyoka_version", "numba_version", "tolerance", "margin",
                      "rule")),
}
