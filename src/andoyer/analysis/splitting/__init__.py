"""Separatrix splitting: the section map, periodic orbits, invariant manifolds, the Melnikov
function, the splitting measured.

``andoyer.analysis.splitting`` was a module before these sub-packages; its names still
resolve here for one release (moved to :mod:`andoyer.analysis.splitting.measure`), with a
``DeprecationWarning``.
"""

from __future__ import annotations

import importlib
import warnings
from typing import Any


def __getattr__(name: str) -> Any:
    if name.startswith("__"):
        raise AttributeError(name)
    module = importlib.import_module("andoyer.analysis.splitting.measure")
    if not hasattr(module, name):
        raise AttributeError(f"module 'andoyer.analysis.splitting' has no attribute {name!r}")
    warnings.warn(f"andoyer.analysis.splitting.{name} moved to andoyer.analysis.splitting.measure."
                  f"{name}; the old path works for one release", DeprecationWarning,
                  stacklevel=2)
    return getattr(module, name)
