"""Chaos: indicators (FLI, MEGNO, the Lyapunov exponent: :mod:`.lyapunov`, listed once in
:mod:`.registry`), alignment indices (SALI, GALI), the border of chaos, frequency analysis.

The public names of :mod:`.lyapunov` and :mod:`.specs` are names of this package too
(``from andoyer.analysis.chaos import indicators, chaos_map``), imported on first use so
that the light modules (:mod:`.registry`, read by the CLI's argument parser) stay light.
"""

from __future__ import annotations

import importlib
from typing import Any

#: Name -> the module of this package that defines it.
EXPORTS = {"indicators": "lyapunov", "chaos_map": "lyapunov", "output_times": "lyapunov",
           "initial_tangent": "tangent_space", "MapGrid": "specs", "IndicatorRun": "specs",
           "TANGENT_SPACES": "specs", "INDICATORS": "registry", "IndicatorSpec": "registry"}

__all__ = sorted(EXPORTS)


def __getattr__(name: str) -> Any:
    if name not in EXPORTS:
        raise AttributeError(f"module 'andoyer.analysis.chaos' has no attribute {name!r}")
    value = getattr(importlib.import_module(f"andoyer.analysis.chaos.{EXPORTS[name]}"), name)
    globals()[name] = value
    return value
