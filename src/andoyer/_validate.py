"""Checks of scalar inputs shared by the layers: clear messages naming the argument."""

from __future__ import annotations

import math
from typing import Any

__all__ = ["finite", "positive"]


def finite(name: str, value: Any) -> float:
    """``float(value)``, or ``ValueError`` naming ``name`` if it is not a finite real.

    >>> finite("h", "0.25")
    0.25
    """
    if isinstance(value, bool):  # float(True) = 1.0 would hide a wrong argument
        raise ValueError(f"{name} must be a real number, got {value!r}")
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a real number, got {value!r}") from None
    if not math.isfinite(v):
        raise ValueError(f"{name} must be finite, got {v!r}")
    return v


def positive(name: str, value: Any) -> float:
    """``float(value)``, or ``ValueError`` naming ``name`` unless finite and > 0.

    >>> positive("J2", 1)
    1.0
    """
    v = finite(name, value)
    if v <= 0.0:
        raise ValueError(f"{name} must be finite and > 0, got {v!r}")
    return v
