"""Checks of scalar inputs shared by the layers: clear messages naming the argument."""

from __future__ import annotations

import math
from typing import Any

__all__ = ["finite", "positive", "floats"]


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


def floats(text: str, n: int, what: str) -> list[float]:
    """``n`` numbers from ``"a,b,c"`` or ``"a b c"`` (command line, explorer fields).

    >>> floats("0.3, 1", 2, "--state")
    [0.3, 1.0]
    """
    try:
        vals = [float(v) for v in text.replace(",", " ").split()]
    except ValueError:
        raise ValueError(f"{what}: {text!r} is not a list of numbers") from None
    if len(vals) != n:
        raise ValueError(f"{what} needs {n} numbers, got {len(vals)}")
    return vals
