"""Checks of scalar inputs shared by the layers: each a function of the argument's name (for
the message) and its value, called where the user's value arrives; clear messages naming
the argument. The limits of ``|G|`` (:data:`MAX_MOMENTUM`, :data:`MAX_ACTION`) and of
counts (:data:`MAX_COUNT`) are here, read by :mod:`andoyer.validation.arguments` too."""

from __future__ import annotations

import math
import numbers
from collections.abc import Iterable
from typing import Any

import numpy as np
from numpy.typing import NDArray

__all__ = ["MAX_ACTION", "MAX_MOMENTUM", "MAX_ENERGY", "MAX_COUNT", "level", "momentum_limit",
           "finite", "positive", "integer", "real_array", "finite_array", "floats", "choice",
           "grid", "box", "flag"]


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

    Parameters
    ----------
    name : str
        The argument's name, for the error.
    value : object
        The value given.

    Examples
    --------
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


#: Largest momentum (``G``, ``J2``, ``G0``) a closed form takes, as an action or reached
#: by a level (:func:`momentum_limit`): its square, an energy, must stay a float (``G^2``
#: overflows near 1.3e154).
MAX_ACTION = 1e150


#: Largest ``|G|`` the integrators take. The field (1) is quadratic in G and the step
#: control multiplies it once more, so beyond about 1e102 intermediate values overflow
#: (a section at h = 1e300, ``|G|`` ~ 1e150, ended in a division by zero inside the kernel).
MAX_MOMENTUM = 1e100

#: Largest ``|h|`` (an energy) or ``|mu|`` (the scale of the potential energy) taken where
#: no body bounds it (:func:`level` does where one does): ``MAX_MOMENTUM**2``.
MAX_ENERGY = 1e200


def momentum_limit(closed_form: bool) -> float:
    """The largest ``|G|`` a public function takes, whether given as an action (``G``,
    ``J2``, ``M``, ...) or reached by an energy level: the one rule of
    :func:`~andoyer.validation.arguments.checks_arguments`.

    :data:`MAX_MOMENTUM` where the function integrates (the field (1) and its error
    control stay finite); :data:`MAX_ACTION` where it evaluates closed forms only (a
    function decorated with ``closed_form=True``: ``|G|^2``, an energy, stays a float).
    An energy given without a body is held to the square of the limit.

    Parameters
    ----------
    closed_form : bool
        Whether the function evaluates closed forms only (integrates nothing).

    Examples
    --------
    >>> momentum_limit(False) == MAX_MOMENTUM, momentum_limit(True) == MAX_ACTION
    (True, True)
    """
    return MAX_ACTION if closed_form else MAX_MOMENTUM


#: Largest value of an integer argument (counts, sizes, steps, orders): a count beyond
#: it is beyond any machine's memory (8 GB for one float per item); the cost guards
#: (:mod:`andoyer.integrate.budget`) bound the work below it.
MAX_COUNT = 10**9


def level(name: str, h: float, body: Any, maximum: float = MAX_MOMENTUM) -> None:
    """``ValueError`` naming ``name`` unless the level ``H = h`` of ``body`` is finite and
    reaches ``|G| <= maximum`` only (``|G| <= sqrt(2 (h + mu) / min(a, b, c))``, from
    Eq. (1): the kinetic energy is at least ``|G|^2 min(a, b, c) / 2``).

    ``maximum``: :func:`momentum_limit` (:data:`MAX_MOMENTUM` where the level is
    integrated, the default; :data:`MAX_ACTION` in a module of closed forms), which
    :func:`~andoyer.validation.arguments.checks_arguments` applies to an ``"energy"``
    argument of a function that takes a body.

    Parameters
    ----------
    name : str
        The argument's name, for the error.
    h : float
        The energy level ``H = h``.
    body : RigidBody
        The body (``mu`` and its inverse moments ``a, b, c``).
    maximum : float, default MAX_MOMENTUM
        The largest ``|G|`` the level may reach.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> level("h", 1e300, RigidBody.paper())  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: h = 1e+300: the energy level reaches |G| = 2.24e+150, beyond the 1e+100 ...
    """
    h = finite(name, h)
    reach = math.sqrt(2.0 * max(h + body.mu, 0.0) / min(body.a, body.b, body.c))
    if not reach <= maximum:
        why = ("that the integrators take (the field (1) and its error control would "
               "overflow)" if maximum <= MAX_MOMENTUM else "for which |G|^2 stays a float")
        raise ValueError(f"{name} = {h:g}: the energy level reaches |G| = {reach:.3g}, "
                         f"beyond the {maximum:.3g} {why}; take a lower level")


def positive(name: str, value: Any, *, maximum: float | None = None) -> float:
    """``float(value)``, or ``ValueError`` naming ``name`` unless finite and > 0 (and
    ``<= maximum`` when given).

    Parameters
    ----------
    name : str
        The argument's name, for the error.
    value : object
        The value given.
    maximum : float, optional
        The largest value accepted (None: unbounded).

    Examples
    --------
    >>> positive("J2", 1)
    1.0
    >>> positive("J2", 1e300, maximum=MAX_ACTION)
    Traceback (most recent call last):
    ...
    ValueError: J2 must be <= 1e+150, got 1e+300
    """
    v = _real(name, value)
    if not (math.isfinite(v) and v > 0.0):
        raise ValueError(f"{name} must be finite and > 0, got {v!r}")
    if maximum is not None and v > maximum:
        raise ValueError(f"{name} must be <= {maximum:g}, got {v!r}")
    return v


def integer(name: str, value: Any, minimum: int | None = None,
            maximum: int | None = None) -> int:
    """``int(value)``, or ``ValueError`` naming ``name`` unless a whole number in range.

    Counts, sizes and seeds: an integer (Python or NumPy) or a float with an integral
    value (``1e4``); not a bool, a string, a fraction, NaN or infinity.

    Parameters
    ----------
    name : str
        The argument's name, for the error.
    value : object
        The value given.
    minimum, maximum : int, optional
        The accepted range, inclusive (None: unbounded).

    Examples
    --------
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

    Parameters
    ----------
    name : str
        The argument's name, for the error.
    value : array_like
        The values given.
    copy : bool, default False
        Return a new array even where ``value`` already is one.

    Examples
    --------
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

    Parameters
    ----------
    name : str
        The argument's name, for the error.
    value : array_like
        The values given.
    ndim : int, optional
        The number of dimensions required (None: any).
    copy : bool, default False
        Return a new array even where ``value`` already is one.

    Examples
    --------
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

    Parameters
    ----------
    name : str
        The argument's name, for the error.
    value : object
        The value given.
    options : iterable of str
        The accepted strings.

    Examples
    --------
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


def grid(name: str, value: Any, minimum: int = 2) -> tuple[int, int]:
    """A grid size ``n`` or ``(nx, ny)`` as ``(nx, ny)``, or ``ValueError`` naming ``name``.

    Parameters
    ----------
    name : str
        The argument's name, for the error.
    value : int or (int, int)
        The grid size given.
    minimum : int, default 2
        The smallest size accepted along each axis.

    Examples
    --------
    >>> grid("n", 8), grid("n", (8, 4))
    ((8, 8), (8, 4))
    >>> grid("n", "8")
    Traceback (most recent call last):
    ...
    ValueError: n must be an integer or a pair (nx, ny), got '8'
    """
    if isinstance(value, numbers.Real) and not isinstance(value, bool):
        k = integer(name, value, minimum, MAX_COUNT)
        return k, k
    if isinstance(value, str | bytes) or not hasattr(value, "__len__") or len(value) != 2:
        raise ValueError(f"{name} must be an integer or a pair (nx, ny), got {value!r}")
    nx, ny = value
    return (integer(f"{name}[0] (nx)", nx, minimum, MAX_COUNT),
            integer(f"{name}[1] (ny)", ny, minimum, MAX_COUNT))


def box(name: str, value: Any) -> tuple[tuple[float, float], tuple[float, float]]:
    """A rectangle ``((x_min, x_max), (y_min, y_max))`` of finite numbers with
    ``min < max`` on both axes, or ``ValueError`` naming ``name``.

    Parameters
    ----------
    name : str
        The argument's name, for the error.
    value : ((float, float), (float, float))
        The rectangle given.

    Examples
    --------
    >>> box("plane_bounds", [(0, 6.5), (0.1, 0.9)])
    ((0.0, 6.5), (0.1, 0.9))
    >>> box("plane_bounds", ((0, 1), (2, 1)))
    Traceback (most recent call last):
    ...
    ValueError: plane_bounds must have min < max on both axes, got ((0, 1), (2, 1))
    """
    try:
        (x0, x1), (y0, y1) = value
        x0, x1, y0, y1 = (finite(name, v) for v in (x0, x1, y0, y1))
    except (TypeError, ValueError) as err:
        raise ValueError(f"{name} must be ((x_min, x_max), (y_min, y_max)) of finite "
                         f"numbers, got {value!r} ({err})") from None
    if not (x0 < x1 and y0 < y1):
        raise ValueError(f"{name} must have min < max on both axes, got {value!r}")
    return (x0, x1), (y0, y1)


def flag(name: str, value: Any, *, optional: bool = True) -> bool | None:
    """A yes/no option: a bool (NumPy's too), or ``None`` when ``optional`` (the default
    is decided later), or ``ValueError`` naming ``name`` (``"no"`` and ``[]`` would pass
    for their truth values).

    Parameters
    ----------
    name : str
        The argument's name, for the error.
    value : object
        The value given.
    optional : bool, default True
        Whether ``None`` is accepted.

    Examples
    --------
    >>> flag("progress", None), flag("double_cover", True)
    (None, True)
    """
    if value is None and optional:
        return None
    if isinstance(value, bool | np.bool_):
        return bool(value)
    raise ValueError(f"{name} must be True or False{' (or None)' if optional else ''}, "
                     f"got {value!r}")


def floats(text: str, n: int, what: str) -> list[float]:
    """``n`` numbers from ``"a,b,c"`` or ``"a b c"`` (command line, explorer fields).

    Parameters
    ----------
    text : str
        Numbers separated by commas or spaces.
    n : int
        How many numbers are required.
    what : str
        What the text is (a flag or a field), for the error.

    Examples
    --------
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
