"""The decorator of public functions: what each argument must be, said at decoration.

:func:`checks_arguments` checks, before the function runs, every argument annotated as a
plain scalar, a numeric array or a class of the package (from the annotations), and the
ranges it is given explicitly: ``ranges={"h": "energy", "n": "count"}`` maps an argument to
one of the :data:`RANGES` checkers; ``closed_form=True`` lets actions and levels reach
:data:`~andoyer.validation.scalars.MAX_ACTION` (a function that integrates nothing);
``labels`` gives an argument a longer name in messages. Nothing is inferred from an
argument's name or from the function's module: a name alone checks nothing.
"""

from __future__ import annotations

import functools
import inspect
import math
import numbers
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any, ParamSpec, TypeVar, overload

import numpy as np

from andoyer.validation.scalars import MAX_COUNT, MAX_ENERGY, MAX_MOMENTUM, level, momentum_limit

__all__ = ["RANGES", "ArgumentChecks", "checks_arguments"]

_P = ParamSpec("_P")
_R = TypeVar("_R")

#: The range checkers an argument can be given (``ranges={name: checker}``):
#: ``energy``: finite, and in a function of a body (``body=``, :func:`~andoyer.body.
#: checks_body`) a level reaching ``|G|`` within :func:`~andoyer.validation.scalars.
#: momentum_limit` (:func:`~andoyer.validation.scalars.level`), else ``|h|`` within its
#: square; ``action`` (momenta): finite, within the limit; ``length`` (``G = |G|``): also
#: ``>= 0``; ``angle``, ``time``, ``finite``: finite; ``scale`` (``mu``, ``c``): finite,
#: within ``MAX_ENERGY``; ``tolerance``: finite and > 0; ``sheet``: +1 or -1; ``count``: an
#: integer in ``[0, MAX_COUNT]``. Arrays are checked elementwise. ``count`` and ``sheet``
#: need an ``int`` annotation, the others a ``float`` or array one.
RANGES = ("energy", "action", "length", "angle", "time", "finite", "scale", "tolerance",
          "sheet", "count")
_INTEGER_RANGES = ("count", "sheet")

#: The scalar annotations checked for type.
_SCALARS = ("float", "int", "bool", "str")
#: Annotations of numeric arrays (checked for type: numbers, not text, bools or None).
_ARRAYS = ("ArrayLike", "NDArray[np.float64]", "Sequence[float]")


@dataclass(frozen=True)
class ArgumentChecks:
    """What a decorated function checks (its ``__checks__``): the ranges, the labels of
    messages, closed forms or not, the argument holding the body.

    Parameters
    ----------
    ranges : mapping of str to str
        Argument -> one of :data:`RANGES`.
    labels : mapping of str to str
        Argument -> its name in messages.
    closed_form : bool
        Whether actions and levels may reach ``MAX_ACTION`` (closed forms only).
    body : str, optional
        The argument holding the body, for ``energy`` levels.
    """

    ranges: Mapping[str, str] = field(default_factory=dict)
    labels: Mapping[str, str] = field(default_factory=dict)
    closed_form: bool = False
    body: str | None = None


def _scalar_kind(annotation: Any, namespace: Mapping[str, Any] | None = None
                 ) -> tuple[Any, bool] | None:
    """``(kind, optional)`` of an annotation checked for type: a plain scalar (``float``,
    ``int | None``, ...), a numeric array (``ArrayLike``), or one class of the package
    (``RotationSection | None``, resolved as the annotation itself is, in the function's
    module); else ``None`` (tuples, literals, unions of several types stay each
    function's own check)."""
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


def _quantity(label: str, value: Any, kind: str, body: Any, limit: float = MAX_MOMENTUM
              ) -> None:
    """Check ``value`` (named ``label`` in messages) against the range ``kind`` (one of
    :data:`RANGES`); ``body``: the function's body, or None."""
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
    if type(value) is float and kind == "tolerance":  # the common case, without NumPy
        if not (math.isfinite(value) and value > 0.0):
            raise ValueError(f"{label} must be {'> 0' if math.isfinite(value) else 'finite'}"
                             f", got {_shown(value)}")
        return
    scalar: float | None
    if isinstance(value, numbers.Real) and not isinstance(value, bool | np.bool_):
        scalar = float(value)  # a number, the common case: its checks without NumPy
        if not math.isfinite(scalar):
            raise ValueError(f"{label} must be finite, got {_shown(value)}")
        big = abs(scalar)
    else:
        try:
            arr = np.asarray(value, dtype=float)
        except (TypeError, ValueError):
            return  # not numbers: the function's own check names it
        if arr.size == 0:
            return
        if not np.all(np.isfinite(arr)):
            raise ValueError(f"{label} must be finite, got {_shown(value)}")
        big = float(np.max(np.abs(arr)))
        scalar = float(arr) if arr.ndim == 0 else None
    if kind == "energy":
        if scalar is not None and all(hasattr(body, a) for a in ("a", "b", "c", "mu")):
            level(label, scalar, body, limit)
        elif big > limit * limit:
            raise ValueError(f"{label} must be within +-{limit * limit:g}, got "
                             f"{_shown(value)}")
    elif kind == "length" and scalar is not None and not scalar >= 0.0:  # (or a vector G)
        raise ValueError(f"{label} must be >= 0 (a length of the angular momentum), got "
                         f"{_shown(value)}")
    if kind in ("action", "length") and big > limit:
        why = ("its square, an energy, must stay a float" if limit > MAX_MOMENTUM else
               "what the integrators take: the field (1) and its error control would "
               "overflow")
        raise ValueError(f"{label} must be within +-{limit:g} ({why}), got {_shown(value)}")
    elif kind == "scale" and big > MAX_ENERGY:
        raise ValueError(f"{label} must be within +-{MAX_ENERGY:g}, got {_shown(value)}")
    elif kind == "tolerance" and not (scalar > 0.0 if scalar is not None
                                      else np.all(arr > 0.0)):
        raise ValueError(f"{label} must be > 0, got {_shown(value)}")



@overload
def checks_arguments(func: Callable[_P, _R], /) -> Callable[_P, _R]: ...


@overload
def checks_arguments(func: None = None, /, *, ranges: Mapping[str, str] | None = ...,
                     labels: Mapping[str, str] | None = ..., closed_form: bool = ...,
                     body: str | None = ...
                     ) -> Callable[[Callable[_P, _R]], Callable[_P, _R]]: ...


def checks_arguments(func: Callable[_P, _R] | None = None, /, *,
                     ranges: Mapping[str, str] | None = None,
                     labels: Mapping[str, str] | None = None, closed_form: bool = False,
                     body: str | None = None) -> Any:
    """Decorator of a public function: its arguments checked before it runs, each failure
    a ``ValueError`` naming the argument.

    Every argument annotated as a plain scalar (``float``, ``int``, ``bool``, ``str``, each
    optionally ``| None``) must be one (a bool, text, a list or None where a number
    belongs; NaN for a ``float``; a fraction for an ``int``; an ``int`` within
    ``MAX_COUNT``); one annotated ``ArrayLike`` must not be None, a bool or text; one
    annotated with a class of the package must be an instance of it. The arguments named
    in ``ranges`` are held to their range. Finer ranges, shapes and choices stay each
    function's own checks.

    Parameters
    ----------
    func : callable, optional
        The function (``@checks_arguments`` bare: types only, no ranges).
    ranges : mapping of str to str, optional
        Argument -> its range, one of :data:`RANGES` (``{"h": "energy", "n": "count"}``).
    labels : mapping of str to str, optional
        Argument -> a longer name for messages (``{"w0": "w0 (initial tangent
        direction)"}``).
    closed_form : bool, default False
        The function evaluates closed forms only: actions and levels may reach
        :data:`~andoyer.validation.scalars.MAX_ACTION`
        (:func:`~andoyer.validation.scalars.momentum_limit`).
    body : str, optional
        The argument holding the body, whose level an ``energy`` must reach within the
        limit (:func:`~andoyer.body.checks_body` gives its first argument).

    Returns
    -------
    callable
        The wrapped function (its ``__checks__`` an :class:`ArgumentChecks`), or the
        decorator when ``func`` is not given.

    Examples
    --------
    >>> @checks_arguments(ranges={"n": "count"})
    ... def period(h: float, n: int = 1, *, progress: bool | None = None) -> float:
    ...     return h * n
    >>> period(2.0, 3), float(period(np.float32(0.5)))
    (6.0, 0.5)
    >>> period("2.0")
    Traceback (most recent call last):
    ...
    ValueError: h must be a real number, got '2.0'
    >>> period(1.0, -1)
    Traceback (most recent call last):
    ...
    ValueError: n must be an integer in [0, 1e+09], got -1
    >>> period(1.0, progress="yes")
    Traceback (most recent call last):
    ...
    ValueError: progress must be True or False or None, got 'yes'
    """
    spec = ArgumentChecks(dict(ranges or {}), dict(labels or {}), closed_form, body)
    if func is None:
        return functools.partial(_decorate, spec=spec)
    return _decorate(func, spec)


def _decorate(func: Callable[_P, _R], spec: ArgumentChecks) -> Callable[_P, _R]:
    sig = inspect.signature(func)
    where = getattr(func, "__name__", "function")
    namespace = getattr(func, "__globals__", None)
    checks = {p.name: kind for p in sig.parameters.values()
              if (kind := _scalar_kind(p.annotation, namespace)) is not None}
    for name, checker in spec.ranges.items():
        if checker not in RANGES:
            raise TypeError(f"{where}: range {checker!r} of {name} is not one of {RANGES}")
        typed = checks.get(name, (None, False))[0]
        want = ("int",) if checker in _INTEGER_RANGES else ("float", "array")
        if typed not in want:
            raise TypeError(f"{where}: {name} has range {checker!r} but is not annotated "
                            f"{' or '.join(want)}")
    for name in (*spec.labels, *([spec.body] if spec.body else [])):
        if name not in sig.parameters:
            raise TypeError(f"{where}: {name} is not an argument")
    limit = momentum_limit(spec.closed_form)
    labels = spec.labels
    ordered = [(name, checks[name]) for name in sig.parameters if name in checks]
    # Binding by hand where the signature has no *args, **kwargs or positional-only
    # parameters (a few microseconds a call: Signature.bind costs more than the checks);
    # anything else, and every call it cannot bind, goes through Signature.bind.
    params = list(sig.parameters.values())
    simple = all(p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY) for p in params)
    positional = tuple(p.name for p in params if p.kind is p.POSITIONAL_OR_KEYWORD)
    names = frozenset(sig.parameters)
    required = frozenset(p.name for p in params if p.default is p.empty)

    def bind(args: tuple[Any, ...], kwargs: dict[str, Any]) -> dict[str, Any]:
        if simple and len(args) <= len(positional):
            values = dict(zip(positional, args, strict=False))  # the rest: defaults
            if kwargs.keys() <= names and not kwargs.keys() & values.keys():
                values.update(kwargs)
                if required <= values.keys():
                    return values
        try:
            return sig.bind(*args, **kwargs).arguments
        except TypeError as exc:
            raise TypeError(f"{where}: {exc}") from None

    @functools.wraps(func)
    def wrapper(*args: _P.args, **kwargs: _P.kwargs) -> _R:
        values = bind(args, kwargs)
        for name, typed in ordered:  # in the signature's order, as Signature.bind's
            if name in values:
                _check_scalar(labels.get(name, name), values[name], *typed)
        body = values.get(spec.body) if spec.body else None
        for name, kind in spec.ranges.items():
            value = values.get(name)
            if value is not None:
                _quantity(labels.get(name, name), value, kind, body, limit)
        return func(*args, **kwargs)

    wrapper.__checks__ = spec  # type: ignore[attr-defined]
    return wrapper
