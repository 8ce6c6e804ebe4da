"""The configuration of a parameter scan: a TOML file, validated into :class:`ScanConfig`.

A scan sweeps any of the body's parameters ``mu, A, B, C`` (Eq. (1) of [1]_) and the
levels of the two integrals, the energy ``H = h`` and the area constant
``(G, gamma) = M`` (Eqs. (1), (4)), over a Cartesian grid, and runs one task per grid
point. Example (``examples/atlas.toml``)::

    [body]
    kind = "hess"                 # Hess conditions (2): r follows from A, B, C
    name = "paper"

    [parameters]                  # a number is fixed; a list or a range is swept
    mu = [0.01, 0.1, 0.3, 0.6]
    h = {start = 0.2, stop = 0.6, num = 3}
    M = 0.0

    [task]
    kind = "section"
    section = "theta2=0"
    n_orbits = 20
    n_crossings = 300

    [integrator]
    engine = "heyoka"

    [store]
    chunks = {mu = 1, h = 1}

Keys
----
``[body]``
    ``kind``: ``"hess"`` (default; ``RigidBody.hess``: ``A > C > B``, ``r`` from the
    Hess conditions (2)) or ``"general"`` (``RigidBody(A, B, C, mu, r)``);
    ``name``: a label (default: the kind); ``branch``: ``1`` (default, the paper's
    ``phi0`` in (0, pi/2)) or ``-1`` (Hess bodies); ``r = [e1, e2, e3]``: direction of
    the centre of mass (general bodies, required; normalised).
``[parameters]``
    ``mu``, ``h``, ``M``, ``A``, ``B``, ``C``: each a number (fixed), a list of distinct
    numbers or a range ``{start, stop, num, spacing = "linear" | "log"}`` (swept; both
    ends included). The swept ones, in the order written, are the grid's dims (stored
    as ``mu``, ``h_level``, ``M_level``, ``A``, ``B``, ``C``). Defaults of a Hess body:
    the paper's ``A, B, C = 2.5, 2.0, 2.2``, ``mu = 0.01``; ``M = 0``; ``h`` has no
    default. A general body needs ``A, B, C, mu``. The ``splitting`` task takes no
    ``h``, ``M`` (its level is ``h = c G^2/2``, ``M = 0``).
``[task]``
    ``kind``: ``"section"``, ``"chaos_map"`` or ``"splitting"``
    (:data:`andoyer.scan.tasks.TASKS`), and its options:

    * ``section``: ``section`` (``"theta2=0"``: plane ``(theta1, J1)``, or ``"g=0"``:
      plane ``(l, L)``; ``":-"`` for the decreasing direction), ``n_orbits`` (20),
      ``n_crossings`` (300), ``sampling``
      (``"sobol"``, ``"halton"``, ``"grid"``),
      ``seed`` (0), ``boundary_grid`` (64), ``t_max`` (default ``1000 * n_crossings``);
    * ``chaos_map``: ``section`` (``"theta2=0"``), ``n = [nx, ny]`` (``[64, 64]``),
      ``t_end`` (1000), ``indicator`` (``"fli"`` or ``"megno"``);
    * ``splitting``: ``G`` (1.0), ``branch`` (``"theta1=0"``, the Hess separatrix, or
      ``"theta1=4phi0"``), ``n_phase`` (16, even), ``delta`` (1e-5).
``[integrator]``
    ``engine``: ``"heyoka"`` (default where installed; taylor for a chaos_map, of the
    FLI or the MEGNO, measured faster: ``andoyer.integrate.engines.MEASURED_DEFAULTS``),
    ``"taylor"``
    (the default without heyoka: one engine for every task, tangent flows included), ``"numba"``,
    ``"scipy"``;
    ``rtol``, ``atol`` (1e-12 each; heyoka and the chaos tasks use ``min(rtol, atol)``),
    or ``tol`` for both (the ``tol`` of the API's chaos indicators).
``[store]``
    ``chunks``: points per task along each swept parameter, e.g. ``{mu = 2}``
    (default 1: one task per point); also the store's Zarr chunks.

Unknown keys (with a suggestion), values that make no body, energy levels below the
minimum ``-mu`` of H, area constants out of reach on the level and grids of more than
:data:`MAX_POINTS` points are refused with a message naming the key;
:func:`check_size` refuses grids of unreasonable estimated cost.

References
----------
.. [1] V. V. Kyrychenko, "Andoyer-Deprit variables use to the Hess gyroscope phase
   trajectories exploring".
"""

from __future__ import annotations

import difflib
import itertools
import json
import math
import numbers
import os
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from andoyer.body import PAPER, RigidBody
from andoyer.errors import DamagedFileError
from andoyer.integrate.engines import ENGINES, installed
from andoyer.integrate.engines.base import Tolerance
from andoyer.scan.tasks import REQUIRED, TASKS, Integrator
from andoyer.validation import integer

__all__ = ["ScanConfig", "load_config", "parse_config", "PARAMETERS", "STORAGE_NAMES",
           "PARAMETER_ATTRS", "MAX_POINTS", "CONFIG_FORMAT"]

#: What can be swept: the body's mu, A, B, C, the turn epsilon of a Hess body's centre of
#: mass (:meth:`~andoyer.body.RigidBody.near_hess`) and the levels h (energy), M (area).
PARAMETERS = ("mu", "epsilon", "h", "M", "A", "B", "C")

#: Parameter -> name of its dim in the store. ``h`` and ``M`` are levels of the
#: integrals; their storage names differ ignoring case from ``H`` (the energy at each
#: crossing) and ``M_action`` (case-insensitive file systems hold Zarr stores too).
STORAGE_NAMES = {"mu": "mu", "epsilon": "epsilon", "h": "h_level", "M": "M_level", "A": "A",
                 "B": "B", "C": "C"}

#: Parameter -> (symbol, long name, equation, units) of its coordinate.
PARAMETER_ATTRS: dict[str, tuple[str, str, str, str]] = {
    "mu": ("\\mu", "weight x distance of the centre of mass", "(1)", "1"),
    "epsilon": ("\\epsilon", "turn of the centre of mass off the Hess direction in the "
                "(e1, e2) plane", "(2)", "rad"),
    "h": ("h", "energy level H = h", "(1)", "1"),
    "M": ("M", "area constant (G, gamma) = M", "(4)", "1"),
    "A": ("A", "principal moment of inertia A", "(1)", "1"),
    "B": ("B", "principal moment of inertia B", "(1)", "1"),
    "C": ("C", "principal moment of inertia C", "(1)", "1"),
}

#: Defaults of a Hess body: the paper's body (Fig. 3, :data:`andoyer.body.PAPER`) on the
#: area level M = 0.
HESS_DEFAULTS = {**PAPER, "epsilon": 0.0, "M": 0.0}

#: A grid of more points than this is refused whatever its cost.
MAX_POINTS = 1_000_000

#: The body kinds of a scan: presets of :data:`andoyer.body.PRESETS` whose parameters
#: (A, B, C, mu) can be swept.
BODY_KINDS = ("hess", "general")

#: Version of the configuration layout recorded in the store.
CONFIG_FORMAT = 1

_SECTIONS = ("body", "parameters", "task", "integrator", "store")
_BODY_KEYS = dict(zip(BODY_KINDS, (("kind", "name", "branch"), ("kind", "name", "r")),
                      strict=True))

Value = float | tuple[float, ...]


# ---------------------------------------------------------------------- messages
def _unknown(where: str, keys: Any, allowed: tuple[str, ...]) -> None:
    for key in keys:
        if key not in allowed:
            close = difflib.get_close_matches(str(key), allowed, n=1, cutoff=0.5)
            hint = f" (did you mean {close[0]!r}?)" if close else ""
            raise ValueError(f"{where}: unknown key {key!r}{hint}; allowed keys: "
                             f"{', '.join(allowed)}")


def _table(data: Mapping[str, Any], name: str, where: str) -> Mapping[str, Any]:
    t = data.get(name, {})
    if not isinstance(t, Mapping):
        raise ValueError(f"{where}: [{name}] must be a table, got {t!r}")
    return t


def _number(where: str, v: Any) -> float:
    if isinstance(v, bool) or not isinstance(v, numbers.Real):
        raise ValueError(f"{where} must be a number, got {v!r}")
    x = float(v)
    if not math.isfinite(x):
        raise ValueError(f"{where} must be finite, got {x!r}")
    return x


def _values(where: str, v: Any) -> Value:
    """A number (fixed), a list of numbers or a range table (swept)."""
    if isinstance(v, Mapping):
        _unknown(where, v, ("start", "stop", "num", "spacing"))
        missing = [k for k in ("start", "stop", "num") if k not in v]
        if missing:
            raise ValueError(f"{where}: a range needs start, stop and num; missing "
                             f"{', '.join(missing)}")
        start, stop = _number(f"{where}.start", v["start"]), _number(f"{where}.stop", v["stop"])
        # Bounded before anything is allocated (num = 1e12 would ask for 8 TB).
        num = integer(f"{where}.num", v["num"], 1)
        if num > MAX_POINTS:
            raise ValueError(f"{where}.num = {num} values: more than the {MAX_POINTS} "
                             "points a whole grid may have; sweep fewer values")
        spacing = v.get("spacing", "linear")
        if spacing == "linear":
            vals = np.linspace(start, stop, int(num))
        elif spacing == "log":
            if not (start > 0 and stop > 0):
                raise ValueError(f"{where}: a log range needs start > 0 and stop > 0, got "
                                 f"{start!r}, {stop!r}")
            vals = np.geomspace(start, stop, int(num))
        else:
            raise ValueError(f"{where}.spacing must be 'linear' or 'log', got {spacing!r}")
        out = tuple(float(x) for x in vals)
    elif isinstance(v, list):
        if not v:
            raise ValueError(f"{where}: an empty list sweeps nothing")
        out = tuple(_number(f"{where}[{i}]", x) for i, x in enumerate(v))
    else:
        return _number(where, v)
    if len(set(out)) != len(out):
        dup = sorted({x for x in out if out.count(x) > 1})
        raise ValueError(f"{where}: repeated values {dup}; every grid value must be distinct")
    return out


def _as_tuple(v: Value) -> tuple[float, ...]:
    return v if isinstance(v, tuple) else (v,)


# ---------------------------------------------------------------------- the config
@dataclass(frozen=True)
class ScanConfig:
    """A validated scan configuration (build it with :func:`load_config`).

    Attributes
    ----------
    body_kind : {"hess", "general"}
    body_name : str
    branch : int
        Sign choice of the Hess conditions (2) (``hess`` bodies).
    r : tuple of 3 floats or None
        Direction of the centre of mass (``general`` bodies).
    parameters : tuple of (name, value)
        Every one of :data:`PARAMETERS`; a float is fixed, a tuple is swept. The
        swept ones, in this order, are the grid's dims.
    task : str
        A key of :data:`andoyer.scan.tasks.TASKS`.
    task_options : tuple of (key, value)
        Every option of the task, defaults filled in.
    integrator : Integrator
        Engine and tolerances.
    chunks : tuple of int
        Points per task along each swept dim (also the Zarr chunks).
    """

    body_kind: str
    body_name: str
    branch: int
    r: tuple[float, float, float] | None
    parameters: tuple[tuple[str, Value], ...]
    task: str
    task_options: tuple[tuple[str, Any], ...]
    integrator: Integrator
    chunks: tuple[int, ...]

    # ------------------------------------------------------------------ the grid
    @property
    def swept(self) -> tuple[str, ...]:
        """The swept parameters, in the order of the grid's dims."""
        return tuple(n for n, v in self.parameters if isinstance(v, tuple))

    @property
    def fixed(self) -> dict[str, float]:
        return {n: v for n, v in self.parameters if not isinstance(v, tuple)}

    @property
    def dims(self) -> tuple[str, ...]:
        """Storage names of the swept dims."""
        return tuple(STORAGE_NAMES[n] for n in self.swept)

    @property
    def shape(self) -> tuple[int, ...]:
        return tuple(len(self.values(n)) for n in self.swept)

    @property
    def n_points(self) -> int:
        return math.prod(self.shape)

    def values(self, name: str) -> tuple[float, ...]:
        """Grid values of parameter ``name`` (one value if it is fixed)."""
        return _as_tuple(dict(self.parameters)[name])

    def point(self, index: tuple[int, ...]) -> dict[str, float]:
        """The parameters at the grid point ``index`` (all six, or A, B, C, mu for a task
        that sets its own level)."""
        out = self.fixed
        out.update({n: self.values(n)[i] for n, i in zip(self.swept, index, strict=True)})
        return out

    def body_at(self, values: Mapping[str, float]) -> RigidBody:
        """The body at a point (``values`` holds A, B, C, mu)."""
        A, B, C, mu = (values[k] for k in ("A", "B", "C", "mu"))
        if self.body_kind == "hess":
            eps = float(values.get("epsilon", 0.0))
            if eps != 0.0:
                return RigidBody.near_hess(A, B, C, mu, eps, branch=self.branch,
                                           name=self.body_name)
            return RigidBody.hess(A, B, C, mu, self.branch, name=self.body_name)
        assert self.r is not None
        return RigidBody(A, B, C, mu, self.r, self.body_name)

    @property
    def block_shape(self) -> tuple[int, ...]:
        """Number of chunks (tasks) along each swept dim."""
        return tuple(-(-n // c) for n, c in zip(self.shape, self.chunks, strict=True))

    def blocks(self) -> list[tuple[int, ...]]:
        """Every chunk of the grid, in C order."""
        return [tuple(int(i) for i in b) for b in np.ndindex(*self.block_shape)]

    def block_slices(self, block: tuple[int, ...]) -> tuple[slice, ...]:
        """Index ranges of the chunk ``block`` along the swept dims."""
        return tuple(slice(b * c, min((b + 1) * c, n))
                     for b, c, n in zip(block, self.chunks, self.shape, strict=True))

    def block_points(self, block: tuple[int, ...]) -> list[tuple[int, ...]]:
        """Grid indices of the points of a chunk, in C order."""
        ranges = [range(s.start, s.stop) for s in self.block_slices(block)]
        return [tuple(p) for p in itertools.product(*ranges)]

    # ------------------------------------------------------------------ (de)serialise
    def to_dict(self) -> dict[str, Any]:
        """The canonical form: every default filled in, ranges expanded to lists."""
        body: dict[str, Any] = {"kind": self.body_kind, "name": self.body_name}
        if self.body_kind == "hess":
            body["branch"] = self.branch
        else:
            body["r"] = list(self.r or ())
        return {
            "format": CONFIG_FORMAT,
            "body": body,
            "parameters": {n: list(v) if isinstance(v, tuple) else v
                           for n, v in self.parameters},
            "task": {"kind": self.task, **dict(self.task_options)},
            "integrator": self.integrator._asdict(),
            "store": {"chunks": dict(zip(self.swept, self.chunks, strict=True))},
        }

    def to_json(self) -> str:
        """Canonical JSON (what the store records and a resume compares)."""
        return json.dumps(self.to_dict(), separators=(", ", ": "))

    @classmethod
    def from_json(cls, text: str) -> ScanConfig:
        """The configuration recorded in a store (``attrs["scan_config"]``).

        Parameters
        ----------
        text : str
            The JSON text of a store's ``attrs["scan_config"]``.
        """
        data = json.loads(text)
        data.pop("format", None)
        return parse_config(data, "the store's scan_config")


# ---------------------------------------------------------------------- parsing
def parse_config(data: Mapping[str, Any], where: str = "config") -> ScanConfig:
    """Validate a configuration given as nested mappings (the parsed TOML).

    Parameters
    ----------
    data : mapping
        The parsed TOML (nested mappings).
    where : str, default "config"
        Where it came from (a file name), for the errors.

    Raises
    ------
    ValueError
        Naming the file (``where``), the table and the key at fault, and how to fix it.
    """
    _unknown(where, data, _SECTIONS)
    # [body]
    body = _table(data, "body", where)
    kind = body.get("kind", "hess")
    if kind not in _BODY_KEYS:
        raise ValueError(f"{where}: [body] kind must be 'hess' (Hess conditions (2)) or "
                         f"'general' (any body, give r = [e1, e2, e3]), got {kind!r}")
    _unknown(f"{where}: [body] ({kind})", body, _BODY_KEYS[kind])
    name = body.get("name", kind)
    if not isinstance(name, str):
        raise ValueError(f"{where}: [body] name must be a string, got {name!r}")
    branch = body.get("branch", 1)
    if branch not in (1, -1) or isinstance(branch, bool):
        raise ValueError(f"{where}: [body] branch must be 1 or -1, got {branch!r}")
    r: tuple[float, float, float] | None = None
    if kind == "general":
        rv = body.get("r")
        if not isinstance(rv, list) or len(rv) != 3:
            raise ValueError(f"{where}: [body] a general body needs r = [e1, e2, e3] (the "
                             f"direction of the centre of mass), got {rv!r}")
        r = (_number(f"{where}: [body] r[0]", rv[0]), _number(f"{where}: [body] r[1]", rv[1]),
             _number(f"{where}: [body] r[2]", rv[2]))

    # [task] kind first: it decides which levels (h, M) are parameters
    ttab = _table(data, "task", where)
    if "kind" not in ttab:
        raise ValueError(f"{where}: [task] needs kind = one of {', '.join(TASKS)}")
    task = ttab["kind"]
    if task not in TASKS:
        close = difflib.get_close_matches(str(task), list(TASKS), n=1)
        raise ValueError(f"{where}: [task] unknown kind {task!r}"
                         + (f" (did you mean {close[0]!r}?)" if close else "")
                         + f"; choose one of {', '.join(TASKS)}")
    tk = TASKS[task]

    # [parameters]
    used = tuple(k for k in PARAMETERS if (k not in ("h", "M") or k in tk.levels)
                 and (k != "epsilon" or kind == "hess"))
    ptab = _table(data, "parameters", where)
    if kind != "hess" and "epsilon" in ptab:
        raise ValueError(f"{where}: [parameters] epsilon turns a Hess body's centre of mass; "
                         "a general body gives its direction r in [body]: remove epsilon or "
                         "use [body] kind = \"hess\"")
    for k in ptab:
        if k in PARAMETERS and k not in used:
            raise ValueError(f"{where}: [parameters] {k}: the {task} task does not take it "
                             f"({tk.levels_note}); remove it")
    _unknown(f"{where}: [parameters]", ptab, used)
    given = {k: _values(f"{where}: [parameters] {k}", v) for k, v in ptab.items()}
    defaults = {k: v for k, v in (HESS_DEFAULTS if kind == "hess" else {"M": 0.0}).items()
                if k in used}
    missing = [k for k in used if k not in given and k not in defaults]
    if missing:
        raise ValueError(f"{where}: [parameters] needs {', '.join(missing)}"
                         + (" (a general body has no default moments or mu)"
                            if kind == "general" and set(missing) - {"h"} else "")
                         + "; give each as a number (fixed) or a list/range (swept)")
    parameters = tuple(given.items()) + tuple(
        (k, defaults[k]) for k in used if k not in given)
    for k, v in parameters:
        bad = [x for x in _as_tuple(v) if (k == "mu" and x < 0) or (k in "ABC" and x <= 0)]
        if bad:
            what = "mu >= 0" if k == "mu" else f"{k} > 0"
            raise ValueError(f"{where}: [parameters] {k} = {bad[0]!r} violates {what}")
    swept = [k for k, v in parameters if isinstance(v, tuple)]
    if not swept:
        raise ValueError(f"{where}: [parameters] sweeps nothing: give at least one of "
                         f"{', '.join(used)} as a list or a range "
                         "{start = ..., stop = ..., num = ...}")
    shape = tuple(len(_as_tuple(dict(parameters)[k])) for k in swept)
    n_points = math.prod(shape)
    if n_points > MAX_POINTS:
        raise ValueError(f"{where}: the grid has {' x '.join(map(str, shape))} = {n_points} "
                         f"points, more than {MAX_POINTS}: an unreasonable size whatever "
                         "the task; sweep fewer values")

    # [task]
    _unknown(f"{where}: [task] ({task})", ttab, ("kind", *tk.options))
    options: list[tuple[str, Any]] = []
    for key, opt in tk.options.items():
        if key not in ttab and opt.default is REQUIRED:
            raise ValueError(f"{where}: [task] {task} needs {key} ({opt.doc})")
        try:
            options.append((key, opt.check(key, ttab.get(key, opt.default))))
        except ValueError as exc:
            raise ValueError(f"{where}: [task] {exc}") from None

    # [integrator]
    itab = _table(data, "integrator", where)
    _unknown(f"{where}: [integrator]", itab, ("engine", "rtol", "atol", "tol"))
    engine = itab.get("engine")
    if engine is None:
        from andoyer.integrate.engines import default_engine_name
        from andoyer.integrate.engines.base import Capability

        # One engine for every task of a scan: the default that also has tangent flows,
        # for the scan's workload (a map of the FLI alone or with MEGNO: MEASURED_DEFAULTS'
        # fli_map, megno_map), so that a scanned point is what the public function gives
        # on defaults.
        workload = None
        if task == "chaos_map":
            workload = "fli_map" if dict(options).get("indicator") == "fli" else "megno_map"
        engine = default_engine_name(Capability.TANGENT, Capability.TANGENT_CROSSINGS,
                                     workload=workload)
    if engine not in ENGINES:
        raise ValueError(f"{where}: [integrator] engine must be one of "
                         f"{', '.join(ENGINES)}, got {engine!r}")
    if not installed(str(engine)):
        raise ValueError(f"{where}: [integrator] engine {engine!r} is not installed here; "
                         "choose another engine")
    if "tol" in itab:  # one number, as the API's tol of the chaos indicators
        both = [k for k in ("rtol", "atol") if k in itab]
        if both:
            raise ValueError(f"{where}: [integrator] give tol (both tolerances) or rtol and "
                             f"atol, not tol and {' and '.join(both)}")
        itab = {**itab, "rtol": itab["tol"], "atol": itab["tol"]}
    rtol = _number(f"{where}: [integrator] rtol", itab.get("rtol", 1e-12))
    atol = _number(f"{where}: [integrator] atol", itab.get("atol", 1e-12))
    try:
        Tolerance(rtol, atol)
    except ValueError as exc:
        raise ValueError(f"{where}: [integrator] {exc}") from None

    # [store]
    stab = _table(data, "store", where)
    _unknown(f"{where}: [store]", stab, ("chunks",))
    ctab = stab.get("chunks", {})
    if not isinstance(ctab, Mapping):
        raise ValueError(f"{where}: [store] chunks must be a table like {{mu = 2}}, "
                         f"got {ctab!r}")
    for k in ctab:
        if k not in swept:
            raise ValueError(f"{where}: [store] chunks: {k!r} is not a swept parameter "
                             f"(swept: {', '.join(swept)})")
    chunks = []
    for k, n in zip(swept, shape, strict=True):
        c = integer(f"{where}: [store] chunks.{k}", ctab.get(k, 1), 1)
        chunks.append(min(c, n))

    cfg = ScanConfig(kind, name, int(branch), r, parameters, task, tuple(options),
                     Integrator(str(engine), rtol, atol), tuple(chunks))
    _check_bodies_and_levels(cfg, where)
    return cfg


def _check_bodies_and_levels(cfg: ScanConfig, where: str) -> None:
    """Every grid point must make a body, and a level set H = h, (G, gamma) = M.

    The body's shape (A, B, C and, for Hess bodies, epsilon: its centre of mass
    direction) does not depend on mu, which only has to be >= 0: every shape is built at
    the first mu and every mu with the first shape, so that a grid swept in mu and the
    levels costs a few bodies, not one per point (an 810 000-point grid loads at once).
    The levels are checked where they are tightest (smallest mu and largest moment).
    """
    shape_names = ("A", "B", "C") + (("epsilon",) if cfg.body_kind == "hess" else ())
    mus = cfg.values("mu")

    def make(values: dict[str, float]) -> RigidBody:
        try:
            return cfg.body_at(values)
        except ValueError as exc:
            point = ", ".join(f"{k} = {v:g}" for k, v in values.items()
                              if k != "epsilon" or v != 0.0)
            swept = [k for k in (*shape_names, "mu") if k in cfg.swept]
            raise ValueError(
                f"{where}: [parameters] the grid point {point} makes no {cfg.body_kind} "
                f"body: {exc}" + (f"; narrow the ranges of {', '.join(swept)}"
                                  if swept else "")) from None

    shapes = [dict(zip(shape_names, combo, strict=True))
              for combo in itertools.product(*(cfg.values(k) for k in shape_names))]
    bodies = [make({**shape, "mu": mus[0]}) for shape in shapes]
    for other in mus[1:]:
        make({**shapes[0], "mu": other})
    validate = TASKS[cfg.task].validate
    if validate is not None:
        try:
            validate(dict(cfg.task_options), bodies, cfg.integrator)
        except ValueError as exc:
            raise ValueError(f"{where}: [task] {exc}") from None
    if "h" not in dict(cfg.parameters):
        return
    # H >= -mu everywhere; |M| <= G <= sqrt(2 (h + mu) max(A, B, C)) on the level h.
    mu = np.array(mus)[:, None]
    h = np.array(cfg.values("h"))[None, :]
    if np.any(h <= -mu):
        i, j = np.argwhere(h <= -mu)[0]
        raise ValueError(f"{where}: [parameters] h = {h[0, j]:g} at mu = {mu[i, 0]:g} is "
                         f"below the minimum -mu of H (Eq. (1)): the level is empty; "
                         "take h > -mu")
    abc = np.array([max(b.A, b.B, b.C) for b in bodies])
    k = int(np.argmin(abc))
    mu_min = min(mus)
    gmax = np.sqrt(2.0 * np.maximum(np.array(cfg.values("h")) + mu_min, 0.0) * abc[k])
    M = np.abs(np.array(cfg.values("M")))
    bad = np.argwhere(M[None, :] >= gmax[:, None])
    if bad.size:
        i, j = bad[0]
        b = bodies[k]
        raise ValueError(
            f"{where}: [parameters] M = {cfg.values('M')[j]:g} is out of reach on the level "
            f"h = {cfg.values('h')[i]:g} (mu = {mu_min:g}, A, B, C = {b.A:g}, {b.B:g}, "
            f"{b.C:g}): |M| <= G <= sqrt(2 (h + mu) max(A, B, C)) = {gmax[i]:.6g}; "
            "lower |M| or raise h")


def load_config(source: str | os.PathLike[str] | Mapping[str, Any]) -> ScanConfig:
    """Read and validate a scan configuration.

    Parameters
    ----------
    source : path of a TOML file, or the parsed mapping

    Returns
    -------
    ScanConfig

    Examples
    --------
    >>> cfg = load_config({"parameters": {"mu": [0.01, 0.1], "h": 0.3},
    ...                    "task": {"kind": "section", "n_orbits": 4, "n_crossings": 10}})
    >>> cfg.swept, cfg.shape, cfg.dims
    (('mu',), (2,), ('mu',))
    >>> load_config({"parameters": {"mu": [0.1], "h": 0.3, "D": 1.0},
    ...              "task": {"kind": "section"}})
    Traceback (most recent call last):
    ...
    ValueError: config: [parameters]: unknown key 'D'; allowed keys: mu, epsilon, h, M, A, B, C
    """
    if isinstance(source, Mapping):
        return parse_config(source)
    path = Path(source)
    if path.is_dir():
        raise ValueError(f"configuration file {str(path)!r} is a folder; give the scan's "
                         "TOML file")
    if not path.is_file():
        raise ValueError(f"configuration file {str(path)!r} not found")
    raw = path.read_bytes()
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise DamagedFileError(
            f"{path}: not UTF-8 text (byte {raw[exc.start]:#04x} at offset {exc.start}): "
            "a scan configuration is a TOML text file; is this the right file?") from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise DamagedFileError(f"{path}: not valid TOML: {exc}") from None
    return parse_config(data, str(path))
