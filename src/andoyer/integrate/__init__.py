"""Orbits and Poincare sections (friendly layer over the engines).

Imported on demand (it loads xarray), not by ``import andoyer``. The names below are
loaded at first use, so that ``andoyer.integrate.engines`` (the registry the command
line reads its ``--engine`` choices from) imports without xarray and SciPy.
"""

from __future__ import annotations

import importlib
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from andoyer.integrate.api import initial_states as initial_states
    from andoyer.integrate.api import integrate_canonical as integrate_canonical
    from andoyer.integrate.api import poincare as poincare
    from andoyer.integrate.api import propagate as propagate
    from andoyer.integrate.engines.values import Section as Section
    from andoyer.integrate.fill import fill_section as fill_section
    from andoyer.integrate.hess_manifold import (
        propagate_hess_manifold as propagate_hess_manifold,
    )
    from andoyer.integrate.orientation import attitude as attitude

_LAZY = {
    "attitude": "andoyer.integrate.orientation",
    "initial_states": "andoyer.integrate.api",
    "integrate_canonical": "andoyer.integrate.api",
    "poincare": "andoyer.integrate.api",
    "propagate": "andoyer.integrate.api",
    "fill_section": "andoyer.integrate.fill",
    "propagate_hess_manifold": "andoyer.integrate.hess_manifold",
    "Section": "andoyer.integrate.engines.values",
}

__all__ = ["Section", "attitude", "fill_section", "initial_states", "integrate_canonical",
           "poincare", "propagate", "propagate_hess_manifold"]


def __getattr__(name: str) -> object:
    if name in _LAZY:
        value = getattr(importlib.import_module(_LAZY[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'andoyer.integrate' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY))
