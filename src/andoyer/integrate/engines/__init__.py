"""Integration engines behind one seam (:mod:`andoyer.integrate.engines.base`).

``heyoka`` (Taylor method compiled with LLVM) is the default where it is installed;
``numba`` (adaptive DOP853 compiled with Numba) is portable; ``scipy``
(``solve_ivp(DOP853)``) is kept as an independent check.
"""

from __future__ import annotations

import importlib
from functools import cache

from andoyer.integrate.engines.base import Engine
from andoyer.integrate.engines.lazy import heyoka_available

__all__ = ["ENGINES", "get_engine", "available_engines", "default_engine_name"]

#: Engine name -> (module, class).
ENGINES = {
    "heyoka": ("andoyer.integrate.engines.heyoka_engine", "HeyokaEngine"),
    "numba": ("andoyer.integrate.engines.numba_engine", "NumbaEngine"),
    "scipy": ("andoyer.integrate.engines.scipy_engine", "ScipyEngine"),
}


@cache
def _load(name: str) -> Engine:
    if name == "heyoka" and not heyoka_available():
        # The engine module imports heyoka lazily; refuse it here, not at the first step.
        raise ImportError("heyoka is not installed (it has wheels for Linux only)")
    module, cls = ENGINES[name]
    engine: Engine = getattr(importlib.import_module(module), cls)()
    return engine


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


def default_engine_name() -> str:
    """``"heyoka"`` where installed, else ``"numba"``."""
    try:
        importlib.import_module("heyoka")
    except ImportError:
        return "numba"
    return "heyoka"


def get_engine(name: str | None = None) -> Engine:
    """The engine called ``name`` (default: :func:`default_engine_name`).

    Raises
    ------
    ValueError
        For an unknown name, or an engine whose package is not installed.
    """
    name = default_engine_name() if name is None else name
    if name not in ENGINES:
        raise ValueError(f"unknown engine {name!r}; choose one of {', '.join(ENGINES)}")
    try:
        return _load(name)
    except ImportError as exc:
        raise ValueError(f"engine {name!r} is not available here ({exc}); "
                         f"available: {', '.join(available_engines())}") from exc
