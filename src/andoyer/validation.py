"""Checks of scalar inputs shared by the layers: clear messages naming the argument."""

from __future__ import annotations

import functools
import inspect
import math
import numbers
from collections.abc import Callable, Iterable
from typing import Any, ParamSpec, TypeVar

import numpy as np
from numpy.typing import NDArray

__all__ = ["MAX_ACTION", "MAX_MOMENTUM", "MAX_ENERGY", "MAX_COUNT", "QUANTITIES", "level",
           "momentum_limit",
           "finite", "positive", "integer", "real_array", "finite_array",
           "floats", "choice", "grid", "box", "flag", "checks_arguments"]


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
    :func:`checks_arguments`.

    :data:`MAX_MOMENTUM` where the function integrates (the field (1) and its error
    control stay finite); :data:`MAX_ACTION` where it evaluates closed forms only (a
    module that sets ``CLOSED_FORM = True`` beside its functions: ``|G|^2``, an energy,
    stays a float). An energy given without a body is held to the square of the limit.

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
    :func:`checks_arguments` applies to each argument ``h`` beside a ``body``.

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


_P = ParamSpec("_P")
_R = TypeVar("_R")

#: The scalar annotations :func:`checks_arguments` enforces.
_SCALARS = ("float", "int", "bool", "str")


#: Annotations of numeric arrays (checked for type: numbers, not text, bools or None).
_ARRAYS = ("ArrayLike", "NDArray[np.float64]", "Sequence[float]")


def _scalar_kind(annotation: Any, namespace: dict[str, Any] | None = None
                 ) -> tuple[Any, bool] | None:
    """``(kind, optional)`` of an annotation :func:`checks_arguments` enforces: a plain
    scalar (``float``, ``int | None``, ...), a numeric array (``ArrayLike``), or one class
    of the function's module (``RotationSection | None``); else ``None`` (tuples,
    literals, unions of several types stay each function's own check)."""
    text = annotation if isinstance(annotation, str) else getattr(annotation, "__name__", "")
    parts = [t.strip() for t in text.split("|")]
    optional = "None" in parts
    kinds = [t for t in parts if t != "None"]
    if len(kinds) == 1 and kinds[0] in _SCALARS:
        return kinds[0], optional
    if kinds and all(k in _ARRAYS for k in kinds) and any(k != "Sequence[float]"
                                                          for k in kinds):
        return "array", optional
    if len(kinds) == 1 and kinds[0].isidentifier() and namespace is not None:
        cls = namespace.get(kinds[0])
        if isinstance(cls, type) and cls.__module__.startswith("andoyer."):
            return cls, optional
    return None


def _shown(value: Any) -> str:
    """``repr(value)`` cut to 60 characters, for an error message (built only on an error:
    the repr of an array costs more than the whole check)."""
    text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


def _check_scalar(name: str, value: Any, kind: Any, optional: bool) -> None:
    if value is None and optional:
        return
    if kind == "int":  # the type, and MAX_COUNT: finer ranges are the function's integer()
        ok = isinstance(value, numbers.Real) and not isinstance(value, bool | np.bool_) \
            and (isinstance(value, numbers.Integral)
                 or (math.isfinite(value) and float(value).is_integer()))
        if not ok:
            raise ValueError(f"{name} must be an integer{' or None' if optional else ''}, "
                             f"got {_shown(value)}")
        if abs(value) > MAX_COUNT:
            raise ValueError(f"{name} must be an integer within +-{MAX_COUNT:.0e}, got "
                             f"{value!r}")
        return
    if isinstance(kind, type):
        if not isinstance(value, kind):
            raise ValueError(f"{name} must be a {kind.__name__}"
                             f"{' or None' if optional else ''}, got {type(value).__name__} "
                             f"{_shown(value)}")
        return
    if kind == "array":
        # The values NumPy would turn silently into a number: None (NaN), a bool (1.0), a
        # numeric text ("1"). Ragged rows, text or bools in a list, complex values are
        # each function's real_array check (with its own name for the argument).
        if value is None or isinstance(value, bool | np.bool_ | str | bytes):
            raise ValueError(f"{name} must be a number or an array of numbers"
                             f"{' or None' if optional else ''}, got {_shown(value)}")
        return
    if kind == "bool":
        if not isinstance(value, bool | np.bool_):
            raise ValueError(f"{name} must be True or False"
                             f"{' or None' if optional else ''}, got {_shown(value)}")
    elif kind == "str":
        if not isinstance(value, str):
            raise ValueError(f"{name} must be a string{' or None' if optional else ''}, "
                             f"got {_shown(value)}")
    elif kind == "float":
        if isinstance(value, np.ndarray) and value.ndim == 0:
            value = value[()]
        if not isinstance(value, numbers.Real) or isinstance(value, bool | np.bool_):
            raise ValueError(f"{name} must be a real number{' or None' if optional else ''}"
                             f", got {_shown(value)}")
        if math.isnan(value):
            raise ValueError(f"{name} must be a number, got NaN")


#: What each argument name means, hence its range: the names follow the paper (one name,
#: one meaning: ``tests/test_vocabulary.py``), so one table bounds every public function.
#: ``energy``: finite, and with a ``body`` argument a level reaching ``|G|`` within
#: :func:`momentum_limit` (:func:`level`; ``MAX_MOMENTUM``, or ``MAX_ACTION`` in a module
#: of closed forms), else ``|h|`` within its square (``MAX_ENERGY`` where integrated);
#: ``action`` (momenta): finite, within :func:`momentum_limit`; ``length``
#: (``G = |G|``, a number; ``J2`` is signed through G = 0): also ``>= 0``; ``angle``,
#: ``time``, ``finite``: finite;
#: ``scale`` (``mu``, ``c``): finite, ``|x| <= MAX_ENERGY``; ``tolerance``: finite and
#: > 0; ``sheet``: +1 or -1; ``count``: an integer in ``[0, MAX_COUNT]``. Every ``int``
#: argument is also bounded by ``MAX_COUNT`` in absolute value. Arrays under these names
#: are checked elementwise.
QUANTITIES: dict[str, str] = {
    **dict.fromkeys(("h", "h0", "energy"), "energy"),
    **dict.fromkeys(("L", "M", "J1", "J2", "J3", "L0", "p", "p0"), "action"),
    **dict.fromkeys(("G", "G0", "action"), "length"),
    **dict.fromkeys(("l", "g", "theta1", "theta2", "theta3", "psi", "psi0", "vartheta",
                     "vartheta0", "q", "q0", "phi0", "t0"), "angle"),
    **dict.fromkeys(("t_end", "T", "period", "duration"), "time"),
    **dict.fromkeys(("mu", "c"), "scale"),
    **dict.fromkeys(("epsilon", "value"), "finite"),
    **dict.fromkeys(("tol", "xtol", "rtol", "atol"), "tolerance"),
    **dict.fromkeys(("sheet",), "sheet"),
    **dict.fromkeys(("n", "k", "steps", "mu_steps", "window", "points_per_period",
                     "boundary_grid", "n_check", "n_times", "n_samples", "n_initial",
                     "n_levels", "n_curve", "n_phase", "n_orbits", "n_crossings", "n_freq",
                     "n_points"), "count"),
}


def _quantity(name: str, label: str, value: Any, kind: str, bound: dict[str, Any],
              limit: float = MAX_MOMENTUM) -> None:
    """Check ``value`` of the argument ``name`` against its quantity ``kind``."""
    if kind == "count":
        if isinstance(value, numbers.Real) and not isinstance(value, bool | np.bool_):
            if not (math.isfinite(value) and 0.0 <= float(value) <= MAX_COUNT):
                raise ValueError(f"{label} must be an integer in [0, {MAX_COUNT:.0e}], got "
                                 f"{value!r}")
        return
    if kind == "sheet":
        if not (isinstance(value, numbers.Real) and not isinstance(value, bool | np.bool_)
                and value in (1, -1)):
            raise ValueError(f"{label} must be +1 or -1, got {value!r}")
        return
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        return  # not numbers: the function's own check names it
    if arr.size == 0:
        return
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{label} must be finite, got {_short(value)}")
    big = float(np.max(np.abs(arr)))
    if kind == "energy":
        body = bound.get("body")
        if arr.ndim == 0 and all(hasattr(body, a) for a in ("a", "b", "c", "mu")):
            level(label, float(arr), body, limit)
        elif big > limit * limit:
            raise ValueError(f"{label} must be within +-{limit * limit:g}, got "
                             f"{_short(value)}")
    elif kind == "length" and arr.ndim == 0 and not arr >= 0.0:  # (G0 may be a vector G)
        raise ValueError(f"{label} must be >= 0 (a length of the angular momentum), got "
                         f"{_short(value)}")
    if kind in ("action", "length") and big > limit:
        why = ("its square, an energy, must stay a float" if limit > MAX_MOMENTUM else
               "what the integrators take: the field (1) and its error control would "
               "overflow")
        raise ValueError(f"{label} must be within +-{limit:g} ({why}), got {_short(value)}")
    elif kind == "scale" and big > MAX_ENERGY:
        raise ValueError(f"{label} must be within +-{MAX_ENERGY:g}, got {_short(value)}")
    elif kind == "tolerance" and not np.all(arr > 0.0):
        raise ValueError(f"{label} must be > 0, got {_short(value)}")


def _short(value: Any) -> str:
    text = repr(value)
    return text if len(text) <= 60 else text[:57] + "..."


def checks_arguments(func: Callable[_P, _R]) -> Callable[_P, _R]:
    """Decorator of a public function: every argument annotated as a plain scalar
    (``float``, ``int``, ``bool``, ``str``, each optionally ``| None``) is checked to be
    one before the function runs (a bool, text, a list or None where a number belongs;
    NaN for a ``float``; a fraction for an ``int``); one annotated ``ArrayLike`` must not
    be None, a bool or text; one annotated with a class of the package must be an
    instance of it. An argument whose name is a quantity of :data:`QUANTITIES` (``h``, the
    actions, angles, times, ``mu``, tolerances, counts, ``sheet``) is held to its range,
    an energy ``h`` to a level its ``body`` reaches within :func:`momentum_limit` (what
    the integrators take, or in a module with ``CLOSED_FORM = True`` what its actions
    take: :func:`level`). Each failure is a
    ``ValueError`` naming the argument (a module's ``ARGUMENT_NAMES`` dict may give a longer
    name). Finer ranges, shapes and choices stay each function's own checks.

    Parameters
    ----------
    func : callable
        The public function to wrap; its annotations say what each argument must be.

    Examples
    --------
    >>> @checks_arguments
    ... def period(h: float, n: int = 1, *, progress: bool | None = None) -> float:
    ...     return h * n
    >>> period(2.0, 3), float(period(np.float32(0.5)))
    (6.0, 0.5)
    >>> period("2.0")
    Traceback (most recent call last):
    ...
    ValueError: h must be a real number, got '2.0'
    >>> period(1.0, progress="yes")
    Traceback (most recent call last):
    ...
    ValueError: progress must be True or False or None, got 'yes'
    """
    sig = inspect.signature(func)
    namespace = getattr(func, "__globals__", None)
    checks = {p.name: kind for p in sig.parameters.values()
              if (kind := _scalar_kind(p.annotation, namespace)) is not None}
    # The quantity of a name applies where the annotation says a number or an array of
    # numbers (an ``int`` only for counts and sheets; ``n`` of elliptic_pi is a float).
    ranged = {name: QUANTITIES[name] for name, kind in checks.items()
              if name in QUANTITIES and (
                  kind[0] in ("float", "array") if QUANTITIES[name] not in ("count", "sheet")
                  else kind[0] == "int")}
    if not checks:
        return func
    where = getattr(func, "__name__", "function")
    # A module may give an argument a longer name for messages ("n (number of plane
    # points)"): ARGUMENT_NAMES = {"n": ...} beside the function.
    labels: dict[str, str] = dict((namespace or {}).get("ARGUMENT_NAMES", {}))
    # A module of closed forms (CLOSED_FORM = True beside the functions) takes levels
    # past what the integrators take, as far as its actions (momentum_limit).
    limit = momentum_limit(bool((namespace or {}).get("CLOSED_FORM", False)))

    @functools.wraps(func)
    def wrapper(*args: _P.args, **kwargs: _P.kwargs) -> _R:
        try:
            bound = sig.bind(*args, **kwargs)
        except TypeError as exc:
            raise TypeError(f"{where}: {exc}") from None
        for name, value in bound.arguments.items():
            if name in checks:
                _check_scalar(labels.get(name, name), value, *checks[name])
        for name, value in bound.arguments.items():
            if name in ranged and value is not None:
                _quantity(name, labels.get(name, name), value, ranged[name],
                          bound.arguments, limit)
        return func(*args, **kwargs)

    return wrapper
