"""Integration engines behind one seam (:mod:`andoyer.integrate.engines.base`).

``heyoka`` (Taylor method compiled with LLVM) is the default where it is installed,
``taylor`` elsewhere (it has every capability of ``numba``);
``numba`` (adaptive DOP853 compiled with Numba) is portable; ``taylor`` (heyoka's
Taylor method compiled with Numba, section events inside the kernel) is portable;
``scipy``
(``solve_ivp(DOP853)``) is kept as an independent check. What each can do is its
:attr:`~andoyer.integrate.engines.base.EngineBase.capabilities`
(:func:`capability_table`); callers ask :func:`resolve_engine` for an engine and check
capabilities, never names.

>>> print(capability_table().splitlines()[0].replace(" | ", ", "))
| engine, propagate, crossings, backward, tangent, tangent_crossings, extended_precision, attitude |
"""

from __future__ import annotations

import importlib
import importlib.util
import inspect
from functools import cache
from typing import Any

from andoyer.integrate.engines.base import Capability, EngineBase
from andoyer.integrate.engines.lazy import heyoka_available

__all__ = ["ENGINES", "FALLBACK_DEFAULTS", "MEASURED_DEFAULTS", "WORKLOADS", "get_engine",
           "resolve_engine", "available_engines", "default_engine_name", "engine_class",
           "engines_with", "capability_table", "EngineLike", "PACKAGES", "installed"]

#: Engine name -> (module, class). The one list of engines: CLI choices, scan configs and
#: the contract tests are derived from it.
ENGINES = {
    "heyoka": ("andoyer.integrate.engines.heyoka_engine", "HeyokaEngine"),
    "numba": ("andoyer.integrate.engines.numba_engine", "NumbaEngine"),
    "scipy": ("andoyer.integrate.engines.scipy_engine", "ScipyEngine"),
    "taylor": ("andoyer.integrate.engines.taylor_engine", "TaylorEngine"),
}

#: What public functions accept as ``engine=``: a name, an engine, or None (default).
EngineLike = str | EngineBase | None

#: The package each engine runs on (checked without importing it).
PACKAGES = {"heyoka": "heyoka", "numba": "numba", "scipy": "scipy", "taylor": "numba"}


def installed(name: str) -> bool:
    """Whether the package engine ``name`` runs on is installed (nothing is imported).

    Parameters
    ----------
    name : str
        A registered engine name.
    """
    if name not in ENGINES:
        raise ValueError(f"unknown engine {name!r}; choose one of {', '.join(ENGINES)}")
    package = PACKAGES.get(name)
    if package == "heyoka":
        return heyoka_available()
    return package is None or importlib.util.find_spec(package) is not None


def engine_class(name: str) -> type[EngineBase]:
    """The class registered as ``name`` (importing it does not import heyoka).

    Parameters
    ----------
    name : str
        A registered engine name (a key of :data:`ENGINES`).
    """
    if name not in ENGINES:
        raise ValueError(f"unknown engine {name!r}; choose one of {', '.join(ENGINES)}")
    module, cls = ENGINES[name]
    klass: type[EngineBase] = getattr(importlib.import_module(module), cls)
    return klass


@cache
def _load(name: str) -> EngineBase:
    if not installed(name):
        # The engine module imports heyoka lazily; refuse it here, not at the first step.
        raise ImportError(f"{PACKAGES[name]} is not installed")
    return engine_class(name)()


def available_engines() -> list[str]:
    """Names of the engines that import on this machine."""
    out = []
    for name in ENGINES:
        try:
            _load(name)
        except ImportError:
            continue
        out.append(name)
    return out


#: The defaults where heyoka is not installed, in order: the first that has what a
#: caller needs (taylor runs heyoka's method in Numba, tangent flows included; numba's
#: DOP853 is the portable fallback).
FALLBACK_DEFAULTS = ("taylor", "numba")

#: The workloads a caller may name to :func:`default_engine_name`: an orbit at output
#: times, sections whose function is a state component (``G3 = c``, ``gamma1 = c``: W2
#: G3 of the benchmarks) or an angle (``theta2 = c``, ``g = c``: W2 theta2), tangent flows,
#: a chaos map of the FLI alone (the state and one tangent vector per start: W3), and a
#: chaos map with the MEGNO (renormalised tangent flows of many starts with the MEGNO
#: quadratures: ``benchmarks/megno_map.py``).
WORKLOADS = ("orbit", "component_section", "angle_section", "tangent", "fli_map",
             "megno_map")

#: Where heyoka is installed, the workloads that another engine was measured to run
#: faster (wall time, both cores, tol 1e-12, in ``python -m benchmarks``: the table
#: "Which engine for what" of ``benchmarks/SUMMARY.md``), and that engine. Decided from
#: the benchmark table, not at run time; every workload not listed runs on heyoka. A
#: workload moves off heyoka only where another engine is faster by more than 10 % (the
#: scatter of one run's medians on a 2-core machine is about 5 %; heyoka's cold start is
#: also far cheaper). Measured: benchmarks/NOTES.md#engine-defaults.
MEASURED_DEFAULTS: dict[str, str] = {
    # W1, one orbit at output times: taylor's compiled loop (kernels.taylor.flow) has no
    # per-step call back into Python; many orbits run on its SIMD lanes.
    "orbit": "taylor",
    # W2 G3, component sections: taylor's lanes balanced by a pilot of each orbit's first
    # crossings (kernels.taylor.lane_crossings) faster than heyoka's batch events.
    "component_section": "taylor",
    # W2 theta2, angle sections: taylor's section jets on SIMD lanes
    # (kernels.taylor.lane_sections) faster than heyoka's events and their callbacks.
    "angle_section": "taylor",
    # W3, the FLI map: taylor's SIMD lanes (kernels.taylor.lanes) faster than heyoka.
    "fli_map": "taylor",
    # The MEGNO map (benchmarks/megno_map.py, W3's map with MEGNO): taylor's renormalised
    # tangent flows on SIMD lanes (kernels.taylor.lane_tangent) faster than heyoka.
    "megno_map": "taylor",
}


def default_engine_name(*capabilities: Capability, workload: str | None = None) -> str:
    """``"heyoka"`` where installed (or the engine :data:`MEASURED_DEFAULTS` gives the
    ``workload``), else the first of :data:`FALLBACK_DEFAULTS` that declares every
    capability asked for.

    Parameters
    ----------
    *capabilities : Capability
        Capabilities the engine must declare (none: any engine).
    workload : str, optional
        One of :data:`WORKLOADS`: what the caller runs, for :data:`MEASURED_DEFAULTS`.

    Examples
    --------
    >>> default_engine_name() in ("heyoka", "taylor")
    True
    >>> default_engine_name(Capability.TANGENT) in ("heyoka", "taylor")
    True
    """
    if workload is not None and workload not in WORKLOADS:
        raise ValueError(f"workload must be one of {', '.join(WORKLOADS)}, got {workload!r}")
    if heyoka_available():
        measured = MEASURED_DEFAULTS.get(workload or "")
        if measured is not None and set(capabilities) <= engine_class(measured).capabilities:
            return measured
        return "heyoka"
    for name in FALLBACK_DEFAULTS:
        if set(capabilities) <= engine_class(name).capabilities:
            return name
    return FALLBACK_DEFAULTS[-1]


def get_engine(name: str | None = None) -> EngineBase:
    """The engine called ``name`` (default: :func:`default_engine_name`).

    Parameters
    ----------
    name : str, optional
        A registered engine name (default: :func:`default_engine_name`).

    Raises
    ------
    ValueError
        For an unknown name, or an engine whose package is not installed.
    """
    name = default_engine_name() if name is None else name
    if not isinstance(name, str) or name not in ENGINES:
        raise ValueError(f"unknown engine {name!r}; choose one of {', '.join(ENGINES)}")
    try:
        return _load(name)
    except ImportError as exc:
        raise ValueError(f"engine {name!r} is not available here ({exc}); "
                         f"available: {', '.join(available_engines())}") from exc


def resolve_engine(engine: EngineLike = None, *capabilities: Capability,
                   workload: str | None = None, **options: Any) -> EngineBase:
    """The one resolver of ``engine=`` arguments: a name, an engine instance, or None.

    Parameters
    ----------
    engine : str, EngineBase or None
        None: :func:`default_engine_name` of ``capabilities``.
    *capabilities : Capability
        What the caller needs; ``ValueError`` naming the engines that have it otherwise.
    workload : str, optional
        What the caller runs (:data:`WORKLOADS`), for the default engine
        (:func:`default_engine_name`).
    **options
        Keyword arguments of the engine's class (``batch_size=``, ``n_threads=`` ...);
        options that are None are ignored, and an option the engine does not take is
        ignored too (engine-specific tuning, e.g. heyoka's SIMD batch size for numba).
        With options, a name gives a new engine so configured.

    Examples
    --------
    >>> resolve_engine("numba", Capability.TANGENT).name
    'numba'
    """
    if isinstance(engine, EngineBase):
        eng = engine
    elif engine is None or isinstance(engine, str):
        eng = get_engine(default_engine_name(*capabilities, workload=workload)
                         if engine is None else engine)
        given = {k: v for k, v in options.items() if v is not None}
        if given:
            accepted = inspect.signature(type(eng)).parameters
            kwargs = {k: v for k, v in given.items() if k in accepted}
            if kwargs:
                eng = type(eng)(**kwargs)
    else:
        raise ValueError(f"engine must be an engine name ({', '.join(ENGINES)}) or an "
                         f"engine instance, got {engine!r}")
    for cap in capabilities:
        if cap not in eng.capabilities:
            able = " or ".join(repr(name) for name in engines_with(cap)) or "(none)"
            raise ValueError(f"engine must be {able} to {cap.description} (capability "
                             f"{cap.value!r}), got {eng.name!r}")
    return eng


def engines_with(capability: Capability) -> list[str]:
    """Registered engines (installed or not) that declare ``capability``.

    Parameters
    ----------
    capability : Capability
        The capability asked for.
    """
    return [name for name in ENGINES if capability in engine_class(name).capabilities]


def capability_table() -> str:
    """The Markdown table "what each engine can do", from the engines' capabilities.

    ``docs/guide.md`` holds this table (a test checks that it is up to date).
    """
    caps = list(Capability)
    lines = ["| engine | " + " | ".join(c.value for c in caps) + " |",
             "| --- |" + " :-: |" * len(caps)]
    for name in ENGINES:
        have = engine_class(name).capabilities
        lines.append(f"| {name} | " + " | ".join("yes" if c in have else "-" for c in caps)
                     + " |")
    return "\n".join(lines)
