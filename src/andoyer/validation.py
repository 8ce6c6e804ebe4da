"""Checks of scalar inputs shared by the layers: clear messages naming the argument."""

from __future__ import annotations

import math
import numbers
from collections.abc import Iterable
from typing import Any

import numpy as np
from numpy.typing import NDArray

__all__ = ["finite", "positive", "integer", "real_array", "finite_array", "floats", "choice"]


def _real(name: str, value: Any) -> float:
    """``float(value)`` (NaN and infinity included), or ``ValueError`` naming ``name``.

    A bool (``float(True) = 1.0``) and text (``float("1")``) would hide a wrong argument:
    both are refused; text from a command line or a form is parsed where it is read.
    """
    if isinstance(value, (bool, str, bytes)):
        raise ValueError(f"{name} must be a real number, got {value!r}")
    try:
        return float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a real number, got {value!r}") from None


def finite(name: str, value: Any) -> float:
    """``float(value)``, or ``ValueError`` naming ``name`` if it is not a finite real.

    >>> finite("h", 0.25)
    0.25
    >>> finite("h", "0.25")
    Traceback (most recent call last):
    ...
    ValueError: h must be a real number, got '0.25'
    """
    v = _real(name, value)
    if not math.isfinite(v):
        raise ValueError(f"{name} must be finite, got {v!r}")
    return v


def positive(name: str, value: Any) -> float:
    """``float(value)``, or ``ValueError`` naming ``name`` unless finite and > 0.

    >>> positive("J2", 1)
    1.0
    """
    v = _real(name, value)
    if not (math.isfinite(v) and v > 0.0):
        raise ValueError(f"{name} must be finite and > 0, got {v!r}")
    return v


def integer(name: str, value: Any, minimum: int | None = None,
            maximum: int | None = None) -> int:
    """``int(value)``, or ``ValueError`` naming ``name`` unless a whole number in range.

    Counts, sizes and seeds: an integer (Python or NumPy) or a float with an integral
    value (``1e4``); not a bool, a string, a fraction, NaN or infinity.

    >>> integer("n_crossings", 1e3, minimum=1)
    1000
    >>> integer("n_crossings", 2.5, minimum=1)
    Traceback (most recent call last):
    ...
    ValueError: n_crossings must be an integer >= 1, got 2.5
    """
    if minimum is not None and maximum is not None:
        want = f"an integer in [{minimum}, {maximum}]"
    elif minimum is not None:
        want = f"an integer >= {minimum}"
    elif maximum is not None:
        want = f"an integer <= {maximum}"
    else:
        want = "an integer"
    if isinstance(value, numbers.Integral) and not isinstance(value, bool):
        k = int(value)
    elif (isinstance(value, numbers.Real) and not isinstance(value, bool)
          and math.isfinite(value) and float(value).is_integer()):
        k = int(float(value))
    else:
        raise ValueError(f"{name} must be {want}, got {value!r}")
    if (minimum is not None and k < minimum) or (maximum is not None and k > maximum):
        raise ValueError(f"{name} must be {want}, got {value!r}")
    return k


def real_array(name: str, value: Any, *, copy: bool = False) -> NDArray[np.float64]:
    """``value`` as a float array (a new one with ``copy``), or ``ValueError`` naming
    ``name`` when it is not a rectangular array of real numbers (ragged rows, text,
    complex or boolean values).

    >>> real_array("y0", [1, 2.5]).tolist()
    [1.0, 2.5]
    >>> real_array("y0", [[1, 2], [3]])
    Traceback (most recent call last):
    ...
    ValueError: y0 must be a rectangular array of real numbers (rows of equal length)
    """
    try:
        arr = np.asarray(value)
    except ValueError:  # NumPy refuses ragged nested sequences
        raise ValueError(f"{name} must be a rectangular array of real numbers "
                         "(rows of equal length)") from None
    if arr.dtype.kind == "c":  # float() would drop the imaginary part
        raise ValueError(f"{name} must be real, got complex values")
    if arr.dtype.kind == "b":
        raise ValueError(f"{name} must hold real numbers, got booleans")
    try:
        return arr.astype(float, copy=copy)
    except (TypeError, ValueError):
        text = repr(value)
        raise ValueError(f"{name} must hold real numbers, got "
                         f"{text if len(text) <= 60 else text[:57] + '...'}") from None


def finite_array(name: str, value: Any, *, ndim: int | None = None,
                 copy: bool = False) -> NDArray[np.float64]:
    """:func:`real_array` whose values are all finite (and of ``ndim`` dimensions when
    given), or ``ValueError`` naming ``name``: a NaN in goes no further than here.

    >>> finite_array("theta2_0", [0.0, 1.0]).tolist()
    [0.0, 1.0]
    >>> finite_array("theta2_0", [float("nan")])
    Traceback (most recent call last):
    ...
    ValueError: theta2_0 must be finite, got NaN or infinity in [nan]
    """
    arr = real_array(name, value, copy=copy)
    if ndim is not None and arr.ndim != ndim:
        raise ValueError(f"{name} must be a {ndim}-D array, got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        text = repr(value)
        raise ValueError(f"{name} must be finite, got NaN or infinity in "
                         f"{text if len(text) <= 60 else text[:57] + '...'}")
    return arr


def choice(name: str, value: Any, options: Iterable[str]) -> str:
    """``value`` if it is one of the strings ``options``, or ``ValueError`` naming
    ``name`` and listing them (a list, a number or ``None`` included: no ``TypeError:
    unhashable type`` from a dictionary look-up).

    >>> choice("what", "tool", ("all", "tool", "paper"))
    'tool'
    >>> choice("what", ["tool"], ("all", "tool", "paper"))
    Traceback (most recent call last):
    ...
    ValueError: what must be one of 'all', 'tool', 'paper', got ['tool']
    """
    opts = tuple(options)
    if isinstance(value, str) and value in opts:
        return value
    text = repr(value)
    raise ValueError(f"{name} must be one of {', '.join(repr(o) for o in opts)}, got "
                     f"{text if len(text) <= 60 else text[:57] + '...'}")


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
