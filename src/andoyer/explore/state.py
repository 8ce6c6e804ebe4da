"""The explorer's logic, free of any GUI: settings, seeds, orbits and the section plane.

Everything the browser app (:mod:`andoyer.explore.ui`) shows is computed here and in
:mod:`andoyer.explore.seeds` and :mod:`andoyer.explore.orbits`, so it can be tested
without a browser:

* :class:`Settings`: body, energy h, area constant M, section, crossings, engine;
* :func:`plane_view`: the accessible region of the section plane on ``H = h`` (from
  :func:`andoyer.integrate.fill_section`) and the unperturbed separatrices
  (:func:`unperturbed_separatrices`);
* :class:`Seed`: the state through a clicked plane point, its missing action solved
  from ``H = h`` (computed by :func:`andoyer.explore.seeds.seed`);
* :class:`Stage`: the orbit's section points in growing stages (computed by
  :func:`andoyer.explore.orbits.crossing_stages`, with the orbit's indicators and the
  chaos-map underlay);
* :class:`Session`: the orbits on screen, one colour each, and their removal.

The planes are those of :mod:`andoyer.integrate.fill`: ``g = const`` in the
Andoyer-Deprit variables (5)-(6), plane ``(l, L)``, ``G`` solved; ``theta2 = const``
in the Hess variables (14), plane ``(theta1, J1)``, ``J2`` solved. On ``M = 0`` the
Hess plane shows ``theta1`` mod 2 pi, as :func:`andoyer.plot.section.plot_section`
and the paper's Fig. 3 do (H is 2 pi-periodic in theta1 there).
"""

from __future__ import annotations

import itertools
import math
import threading
from collections import OrderedDict
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, Literal

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from andoyer.body import RigidBody
from andoyer.integrate import Section
from andoyer.integrate.engines import ENGINES
from andoyer.integrate.fill import default_h
from andoyer.notation import SECTION_PLANES
from andoyer.notation import SectionPlane as Plane
from andoyer.validation import finite as _finite
from andoyer.validation import integer

__all__ = ["Settings", "SharedCache", "Plane", "PLANES", "Seed", "OutsideRegionError",
           "Stage", "Orbit", "Session", "PlaneView", "PALETTE", "default_energy", "make_settings",
           "plane_view", "shared_plane_view", "VIEW_CACHE", "plane_coordinates",
           "unperturbed_separatrices"]


#: Largest number of crossings per orbit a click may ask for.
MAX_CROSSINGS = 200_000

#: Orbit colours, distinct and none of the colours that mean something else in
#: :data:`andoyer.plot.style.COLOURS` (red separatrices, black boundary, grey orbits).
PALETTE: tuple[str, ...] = (
    "#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd", "#8c564b", "#e377c2", "#bcbd22", "#17becf",
    "#393b79", "#637939", "#8c6d31", "#7b4173", "#aec7e8", "#ffbb78", "#98df8a", "#c5b0d5",
    "#c49c94", "#f7b6d2", "#dbdb8d", "#9edae5",
)

RootChoice = Literal["smallest", "largest", "all"]


#: The section planes (one definition: :data:`andoyer.notation.SECTION_PLANES`).
PLANES: dict[str, Plane] = SECTION_PLANES


#: The default energy level (one definition: :func:`andoyer.integrate.fill.default_h`).
default_energy = default_h


@dataclass(frozen=True)
class Settings:
    """What the explorer shows: a body, an energy level, a section and how orbits run.

    Parameters
    ----------
    body : RigidBody
        The Hess plane (``section`` on ``theta2``) needs ``e3 = 0``.
    h : float
        Energy level ``H = h`` (H of Eq. (1)).
    M : float, default 0
        Area constant ``M = (G, gamma)`` (``J3`` in the Hess chart).
    section : Section or str, default ``"theta2=0:+"``
        ``theta2 = const`` (plane ``(theta1, J1)``) or ``g = const`` (plane ``(l, L)``),
        with its crossing direction.
    n_crossings : int, default 500
        Section points per orbit.
    engine : {"heyoka", "taylor", "numba", "scipy"}, optional
        Integration engine of the orbits and the chaos indicators (default: each
        workload's, :data:`~andoyer.integrate.engines.MEASURED_DEFAULTS`: taylor for the
        sections and the underlay, heyoka where installed for one orbit's indicators).
    root : {"smallest", "largest", "all"}, default "smallest"
        Which solutions of ``H = h`` for the missing action a click seeds (one orbit
        each with ``"all"``).
    rtol, atol : float, default 1e-12
        Integration tolerances.

    Examples
    --------
    >>> s = Settings(RigidBody.paper(), 0.25)
    >>> s.plane.x, s.plane.y, s.plane.action, s.x_period == 2 * math.pi
    ('theta1', 'J1', 'J2', True)
    """

    body: RigidBody
    h: float
    M: float = 0.0
    section: Section = field(default_factory=lambda: Section("theta2", 0.0, 1))
    n_crossings: int = 500
    engine: str | None = None
    root: RootChoice = "smallest"
    rtol: float = 1e-12
    atol: float = 1e-12

    def __post_init__(self) -> None:
        if not isinstance(self.body, RigidBody):
            raise ValueError(f"body must be a RigidBody, got {type(self.body).__name__}")
        sec = Section.parse(self.section) if isinstance(self.section, str) else self.section
        if not isinstance(sec, Section):
            raise ValueError(f"section must be a Section or a string like 'theta2=0', "
                             f"got {self.section!r}")
        if sec.coord not in PLANES:
            raise ValueError(f"the explorer shows the planes of 'theta2=...' sections "
                             f"(theta1, J1) and 'g=...' sections (l, L), not {sec.coord!r}")
        if sec.coord == "theta2":
            self.body.require_planar("the Hess plane (theta1, J1) of a theta2 section")
        object.__setattr__(self, "section", sec)
        object.__setattr__(self, "h", _finite("h (energy)", self.h))
        object.__setattr__(self, "M", _finite("M (area constant)", self.M))
        object.__setattr__(self, "n_crossings",
                           integer("crossings per orbit", self.n_crossings, 1, MAX_CROSSINGS))
        if self.engine is not None and self.engine not in ENGINES:
            raise ValueError(f"unknown engine {self.engine!r}; choose one of "
                             f"{', '.join(ENGINES)}")
        if self.root not in ("smallest", "largest", "all"):
            raise ValueError(f"root must be 'smallest', 'largest' or 'all', got {self.root!r}")
        for name in ("rtol", "atol"):
            v = _finite(name, getattr(self, name))
            if not 0.0 < v <= 1e-3:
                raise ValueError(f"{name} must be in (0, 1e-3], got {v!r}")

    @property
    def plane(self) -> Plane:
        return PLANES[self.section.coord]

    @property
    def x_period(self) -> float:
        """Period of the plane's angle as shown: 2 pi, but 4 pi for theta1 when M != 0."""
        return math.tau if (self.plane.coord == "g" or self.M == 0.0) else 2.0 * math.tau

    def attrs(self) -> dict[str, Any]:
        """Flat attributes for datasets (the body's are added by ``provenance``)."""
        return {"h": self.h, "M": self.M, **self.section.attrs(),
                "n_crossings": self.n_crossings, "root_choice": self.root,
                "rtol": self.rtol, "atol": self.atol, "plane_x": self.plane.x,
                "plane_y": self.plane.y, "solved_action": self.plane.action}


def make_settings(body: RigidBody | None = None, *, h: float | None = None, M: float = 0.0,
                  section: Section | str = "theta2=0", n_crossings: int = 500,
                  engine: str | None = None, root: RootChoice = "smallest",
                  rtol: float = 1e-12, atol: float = 1e-12) -> Settings:
    """:class:`Settings` with the explorer's defaults: the paper's body and, without
    ``h``, :func:`default_energy` (which needs ``|M| < 1``).

    Parameters
    ----------
    body : RigidBody, optional
        Default: the paper's body.
    h : float, optional
        Energy level (default: :func:`default_energy`).
    M : float, default 0.0
        Area constant ``(G, gamma) = M``.
    section : Section or str, default "theta2=0"
        The section (:meth:`andoyer.integrate.engines.values.Section.parse`).
    n_crossings : int, default 500
        Crossings per orbit.
    engine : str, optional
        Integration engine of the orbits and the chaos indicators (default: each
        workload's, as :class:`Settings`).
    root : {"smallest", "largest", "all"}, default "smallest"
        Which solutions of ``H = h`` above a click seed orbits.
    rtol, atol : float, default 1e-12
        Tolerances.
    """
    body = RigidBody.paper() if body is None else body
    if h is None:
        if not abs(M) < 1.0:
            raise ValueError(f"give the energy h: the default level sits at G = 1, which "
                             f"needs |M| < 1, got M = {M!r}")
        h = default_energy(body, M)
    sec = Section.parse(section) if isinstance(section, str) else section
    return Settings(body, h, M, sec, n_crossings, engine, root, rtol, atol)


# --------------------------------------------------------------------------- the plane
def plane_coordinates(settings: Settings, ds: xr.Dataset
                      ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The plane coordinates of section points (a :func:`poincare` dataset), as shown.

    ``theta1`` is reduced mod :attr:`Settings.x_period` (mod 2 pi on ``M = 0``).

    Parameters
    ----------
    settings : Settings
        The plane shown.
    ds : xarray.Dataset
        A :func:`~andoyer.integrate.poincare` dataset.
    """
    p = settings.plane
    x = np.asarray(ds[p.x].values, dtype=float)
    y = np.asarray(ds[p.y].values, dtype=float)
    if p.coord == "theta2":
        x = np.mod(x, settings.x_period)
    return x, y


def unperturbed_separatrices(body: RigidBody, h: float, plane: Plane, period: float,
                             n: int = 401) -> list[tuple[NDArray[np.float64],
                                                         NDArray[np.float64]]]:
    """Separatrices of the unperturbed (mu = 0) motion on the plane, at the level's G0.

    Parameters
    ----------
    body : RigidBody
    h : float
        Energy level; the curves are those of :mod:`andoyer.analysis.unperturbed.separatrix` at
        ``G0 = sqrt(2 h / I_mid)`` (``I_mid`` the middle of ``a, b, c``), the G of the
        unperturbed separatrix on ``H0 = h``.
    plane : Plane
        :data:`PLANES` entry.
    period : float
        Period of the horizontal axis: 2 pi, or 4 pi for ``theta1`` when ``M != 0``.
    n : int
        Points per curve.

    Returns
    -------
    list of (x, y) arrays
        The separatrix curves (the chart's singular lines ``L = +-G0``, ``J1 = 0, J2``,
        also part of that level set, are left out); empty when ``h <= 0`` or the body
        has two equal moments (no hyperbolic rotation).

    Notes
    -----
    With ``mu = 0`` the level ``H0 = I_mid G0^2 / 2`` of Eq. (9) is, for z the middle
    axis (every Hess body), the lines ``l = +-phi0 (mod pi)``, i.e. ``theta1 = 0`` and
    ``theta1 = 4 phi0`` in the Hess chart (14); otherwise two curves ``L(l)`` through
    the saddles.

    Examples
    --------
    >>> body = RigidBody.paper()
    >>> lines = unperturbed_separatrices(body, 0.25, PLANES["theta2"], 2 * math.pi)
    >>> sorted(round(float(x[0]), 6) for x, _ in lines) == sorted(
    ...     [0.0, round(4 * body.phi0, 6), round(2 * math.pi, 6)])
    True
    """
    from andoyer.analysis.unperturbed.separatrix import separatrix_on_level

    ds = separatrix_on_level(body, h, plane.chart, n,
                             double_cover=period > 1.5 * math.tau)
    if ds is None:
        return []
    x = ds[f"separatrix_{plane.x}"].values
    y = ds[f"separatrix_{plane.y}"].values
    keep = ds.separatrix_kind.values == "separatrix"
    return [(x[k], y[k]) for k in np.flatnonzero(keep)]


@dataclass(frozen=True)
class PlaneView:
    """The static content of the section plane for one :class:`Settings`.

    Attributes
    ----------
    settings : Settings
        The settings it was computed for.
    x_range, y_range : (float, float)
        The plane's box.
    boundary_x, boundary_y : ndarray
        The accessible region's boundary (NaN-separated curves).
    accessible : ndarray of bool
        The accessible cells of the grid.
    separatrices : list of (ndarray, ndarray)
        The unperturbed (``mu = 0``) separatrices on the level, as curves.
    fill : xarray.Dataset
        The :func:`~andoyer.integrate.fill_section` dataset of the plane.
    """

    settings: Settings
    x_range: tuple[float, float]
    y_range: tuple[float, float]
    boundary_x: NDArray[np.float64]     # accessible-region boundary, NaN-separated
    boundary_y: NDArray[np.float64]
    accessible: NDArray[np.bool_]       # (plane_x, plane_y) grid
    separatrices: list[tuple[NDArray[np.float64], NDArray[np.float64]]]
    fill: xr.Dataset                    # the fill_section dataset it came from


def plane_view(settings: Settings, boundary_grid: int = 160) -> PlaneView:
    """The accessible region of the plane on ``H = h`` and the unperturbed separatrices.

    Raises ``ValueError`` (with the energy range of the section) when the level does
    not meet the section, and for ``|M|`` too large for ``h``.

    Parameters
    ----------
    settings : Settings
        Body, level and section.
    boundary_grid : int, default 160
        Resolution of the accessible-region grid.

    Examples
    --------
    >>> v = plane_view(Settings(RigidBody.paper(), 0.25), boundary_grid=40)
    >>> v.x_range == (0.0, 2 * math.pi), bool(v.accessible.any())
    (True, True)
    """
    from andoyer.integrate.fill import fill_section

    p = settings.plane
    sec = settings.section
    bounds = None
    if p.coord == "theta2":
        # Plane of theta1 in [0, x_period): fill_section's own default, made explicit.
        act = math.sqrt(2.0 * (settings.h + settings.body.mu)
                        / min(settings.body.a, settings.body.b, settings.body.c)) \
            if settings.h > -settings.body.mu else 1.0
        bounds = ((0.0, settings.x_period), (0.0, act))
    fill = fill_section(settings.body, settings.h, settings.M, (sec.coord, sec.value), n_orbits=1,
                        plane_bounds=bounds, boundary_grid=boundary_grid)
    a = fill.attrs
    seps = unperturbed_separatrices(settings.body, settings.h, p, settings.x_period)
    return PlaneView(settings, (float(a["plane_x_min"]), float(a["plane_x_max"])),
                     (float(a["plane_y_min"]), float(a["plane_y_max"])),
                     fill.boundary_x.values, fill.boundary_y.values,
                     fill.accessible.values, seps, fill)


class SharedCache:
    """Results computed once per key and shared, read-only, by every page of a server.

    Pages asking at once for the same key wait for the one computation instead of
    running one each; the last ``size`` results are kept (least recently used dropped).
    The one owner of this pattern in the explorer: plane views, predicted chains.

    Parameters
    ----------
    size : int
        Results kept.

    Examples
    --------
    >>> cache = SharedCache(2)
    >>> cache.get("a", lambda: [1]) is cache.get("a", lambda: [2])
    True
    """

    def __init__(self, size: int) -> None:
        self.size = size
        self._done: OrderedDict[Any, Any] = OrderedDict()
        self._lock = threading.Lock()
        self._computing: dict[Any, threading.Lock] = {}

    def get(self, key: Any, compute: Callable[[], Any]) -> Any:
        """The result for ``key``, calling ``compute()`` once if it is not kept.

        Parameters
        ----------
        key : hashable
            What the result depends on.
        compute : callable
            Builds the result (and makes its arrays read-only).
        """
        with self._lock:
            if key in self._done:
                self._done.move_to_end(key)
                return self._done[key]
            computing = self._computing.setdefault(key, threading.Lock())
        with computing:
            with self._lock:
                if key in self._done:
                    return self._done[key]
            result = compute()
            with self._lock:
                self._done[key] = result
                while len(self._done) > self.size:
                    self._done.popitem(last=False)
                self._computing.pop(key, None)
            return result


#: Plane views kept for sharing between pages (the most recently used).
VIEW_CACHE = 16
_VIEWS = SharedCache(VIEW_CACHE)


def shared_plane_view(settings: Settings, boundary_grid: int = 160) -> PlaneView:
    """:func:`plane_view`, computed once per ``(settings, boundary_grid)`` and shared,
    read-only, by every page of a server.

    Pages opened at once with the same settings wait for the one computation instead of
    running one each (50 rapid page loads made 50 fills). The last :data:`VIEW_CACHE`
    views are kept; their arrays are read-only, so no page can change another's.

    Parameters
    ----------
    settings : Settings
        Body, level and section.
    boundary_grid : int, default 160
        Resolution of the accessible-region grid.

    Examples
    --------
    >>> shared_plane_view(make_settings(None), 40) is shared_plane_view(make_settings(None), 40)
    True
    """
    def compute() -> PlaneView:
        view = plane_view(settings, boundary_grid)
        for arr in (view.boundary_x, view.boundary_y, view.accessible,
                    *(a for pair in view.separatrices for a in pair)):
            arr.flags.writeable = False
        return view

    view: PlaneView = _VIEWS.get((settings, int(boundary_grid)), compute)
    return view


# --------------------------------------------------------------------------- seeds
class OutsideRegionError(ValueError):
    """A clicked point where no value of the missing action puts the state on ``H = h``."""


@dataclass(frozen=True)
class Seed:
    """The initial state through a clicked plane point, on the level ``H = h``.

    Attributes
    ----------
    x, y : float
        The clicked plane point.
    action : float
        The action solved from ``H = h`` above it.
    root_index : int
        Which of the solutions (``root`` of :class:`Settings`).
    n_roots : int
        How many solutions the point has.
    y0 : ndarray, shape (6,)
        The Euler-Poisson initial state.
    chart_point : ndarray, shape (5,)
        The state in the plane's chart.
    section_rate : float
        The time derivative of the section coordinate there (its sign is the crossing
        direction).
    residual : float
        ``|H(y0) - h|``, relative.
    """

    x: float                 # plane point (theta1, J1) or (l, L)
    y: float
    action: float            # the solved action: J2 resp. G
    root_index: int          # 0 = smallest solution above the point
    n_roots: int             # solutions above the point
    y0: NDArray[np.float64]  # Euler-Poisson state (6,)
    chart_point: NDArray[np.float64]  # (theta1, theta2, J1, J2, J3) or (l, g, L, G, M)
    section_rate: float      # d(section coordinate)/dt at the seed
    residual: float          # |H(y0) - h| / max(|h|, mu)

    def crosses_in(self, direction: int) -> bool:
        """Whether the orbit crosses the section at the seed in ``direction`` (+1, -1, 0)."""
        return direction == 0 or direction * self.section_rate > 0.0


# --------------------------------------------------------------------------- orbits
@dataclass(frozen=True)
class Stage:
    """Section points of one orbit computed so far: ``[start, stop)`` are new.

    Attributes
    ----------
    start, stop : int
        The new section points are ``[start, stop)``.
    x, y : ndarray
        All the orbit's points so far, in the plane's coordinates.
    ds : xarray.Dataset
        Its :func:`~andoyer.integrate.poincare` dataset so far.
    done : bool
        The last stage.
    """

    start: int
    stop: int
    x: NDArray[np.float64]   # plane coordinates of the new points
    y: NDArray[np.float64]
    ds: xr.Dataset           # the poincare() dataset of all crossings so far
    done: bool


@dataclass
class Orbit:
    """One seeded orbit on screen.

    Attributes
    ----------
    id : int
        Its number in the table.
    colour : str
        Its colour (``#rrggbb``).
    seed : Seed
        The initial state through the clicked point.
    settings : Settings
        The settings it runs with.
    x, y : ndarray
        Its section points in the plane's coordinates, so far.
    ds : xarray.Dataset or None
        Its :func:`~andoyer.integrate.poincare` dataset so far (None before the first stage).
    status : str
        ``"queued"``, ``"running"``, ``"done"``, ``"failed: ..."`` or ``"stopped"``.
    """

    id: int
    colour: str
    seed: Seed
    settings: Settings
    x: NDArray[np.float64] = field(default_factory=lambda: np.empty(0))
    y: NDArray[np.float64] = field(default_factory=lambda: np.empty(0))
    ds: xr.Dataset | None = None
    status: str = "queued"     # queued, running, done, failed


class Session:
    """The orbits on screen for one :class:`Settings`: ids, colours, points, removal.

    Changed on the app's event loop only, except :meth:`new_id` (safe from any thread)
    and reads of :attr:`removed` (a worker stops an orbit found there).

    Parameters
    ----------
    settings : Settings
        The settings of the plane.

    Examples
    --------
    >>> from andoyer.explore.seeds import seed
    >>> body = RigidBody.paper()
    >>> s = Session(Settings(body, default_energy(body)))
    >>> o1 = s.add(seed(s.settings, 1.0, 0.5)[0])
    >>> o2 = s.add(seed(s.settings, 2.0, 0.5)[0])
    >>> o1.colour != o2.colour, [o.id for o in s.orbits.values()]
    (True, [1, 2])
    >>> s.remove(1); list(s.orbits), sorted(s.removed)
    ([2], [1])
    """

    def __init__(self, settings: Settings) -> None:
        self.settings = settings
        self.orbits: dict[int, Orbit] = {}
        self.removed: set[int] = set()
        # next() of itertools.count is atomic in CPython: workers may reserve ids.
        self._ids = itertools.count(1)

    def new_id(self) -> int:
        """A fresh orbit id (thread-safe), for :meth:`add`."""
        return next(self._ids)

    def _colour(self, orbit_id: int) -> str:
        used = {o.colour for o in self.orbits.values()}
        free = [c for c in PALETTE if c not in used]
        return free[0] if free else PALETTE[(orbit_id - 1) % len(PALETTE)]

    def add(self, sd: Seed, settings: Settings | None = None, *,
            orbit_id: int | None = None) -> Orbit:
        """A new orbit through ``sd``, with a colour no other orbit on screen has (while
        fewer than ``len(PALETTE)`` orbits are shown)."""
        oid = self.new_id() if orbit_id is None else int(orbit_id)
        if oid in self.orbits or oid in self.removed:
            raise ValueError(f"orbit id {oid} is already used")
        orbit = Orbit(oid, self._colour(oid), sd, settings or self.settings)
        self.orbits[oid] = orbit
        return orbit

    def extend(self, orbit_id: int, stage: Stage) -> bool:
        """Append a stage's new points; False if the orbit was removed meanwhile."""
        orbit = self.orbits.get(orbit_id)
        if orbit is None:
            return False
        if stage.start != orbit.x.size:
            raise ValueError(f"orbit {orbit_id}: stage starts at crossing {stage.start}, "
                             f"but {orbit.x.size} points are shown")
        orbit.x = np.concatenate([orbit.x, stage.x])
        orbit.y = np.concatenate([orbit.y, stage.y])
        orbit.ds = stage.ds
        orbit.status = "done" if stage.done else "running"
        return True

    def remove(self, orbit_id: int) -> None:
        """Remove one orbit (unknown ids are ignored: it may be gone already)."""
        if self.orbits.pop(orbit_id, None) is not None:
            self.removed.add(orbit_id)

    def clear(self, settings: Settings | None = None) -> None:
        """Remove every orbit; optionally switch to new settings."""
        self.removed.update(self.orbits)
        self.orbits.clear()
        if settings is not None:
            self.settings = settings

    def points(self) -> dict[str, NDArray[Any]]:
        """All section points on screen: ``x, y, orbit, crossing, colour`` columns."""
        parts = list(self.orbits.values())
        if not parts:
            return {"x": np.empty(0), "y": np.empty(0), "orbit": np.empty(0, dtype=np.int64),
                    "crossing": np.empty(0, dtype=np.int64),
                    "colour": np.empty(0, dtype=object)}
        return {"x": np.concatenate([o.x for o in parts]),
                "y": np.concatenate([o.y for o in parts]),
                "orbit": np.concatenate([np.full(o.x.size, o.id) for o in parts]),
                "crossing": np.concatenate([np.arange(o.x.size) for o in parts]),
                "colour": np.concatenate([np.full(o.x.size, o.colour, dtype=object)
                                          for o in parts])}
