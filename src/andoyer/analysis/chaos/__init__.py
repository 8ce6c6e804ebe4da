"""Chaos: indicators (FLI, MEGNO), alignment indices (SALI, GALI), the border of chaos,
frequency analysis.

``andoyer.analysis.chaos`` was a module before these sub-packages; its names still
resolve here for one release (moved to :mod:`andoyer.analysis.chaos.indicators`), with a
``DeprecationWarning``.
"""

from __future__ import annotations

import importlib
import warnings
from typing import Any


def __getattr__(name: str) -> Any:
    if name.startswith("__"):
        raise AttributeError(name)
    module = importlib.import_module("andoyer.analysis.chaos.indicators")
    if not hasattr(module, name):
        raise AttributeError(f"module 'andoyer.analysis.chaos' has no attribute {name!r}")
    warnings.warn(f"andoyer.analysis.chaos.{name} moved to andoyer.analysis.chaos.indicators."
                  f"{name}; the old path works for one release", DeprecationWarning,
                  stacklevel=2)
    return getattr(module, name)
