"""Cost guards: estimate the work and memory of a request before doing it.

Every long computation of the friendly layer (:func:`~andoyer.integrate.propagate`,
:func:`~andoyer.integrate.poincare`, chaos maps) first estimates the integration steps
and the memory of its results from the inputs and refuses, with
:class:`~andoyer.errors.CostLimitError`, beyond the limits below; the message gives the
estimate and how to raise the limit. Parameter scans have their own, finer budget
(``andoyer scan --dry-run``).

The step estimate is that of an 8th-order method at ``rtol = 1e-12``, measured on the
numba engine: about ``8 omega T`` steps for an orbit of duration ``T``, where
``omega = |G|max max(a, b, c) + sqrt(2 mu max(a, b, c))`` is the fastest rate of the
body on the orbit's energy level (measured: paper's body at ``|G| = 1``, 3.7 steps per time
unit, estimated 5.3; at ``|G| = 10``, 36; Hess(3, 1, 2) with mu = 1, 12: the estimate errs
high, by less than 3.1x), scaled by
``(1e-12 / rtol)^(1/8)``. A step costs about 0.4 us on one core (numba engine).

Examples
--------
>>> with limits(steps=1e3):
...     check("demo", steps=1e6)  # doctest: +ELLIPSIS
Traceback (most recent call last):
...
andoyer.errors.CostLimitError: demo: about 1e+06 integration steps (~0.4 s on one core) ...
"""

from __future__ import annotations

import contextlib
import math
import numbers
from collections.abc import Iterator

import numpy as np
from numpy.typing import NDArray

from andoyer.body import RigidBody, checks_body
from andoyer.charts.euler_poisson import momentum_bound
from andoyer.errors import ArgumentTypeError, CostLimitError
from andoyer.validation import MAX_MOMENTUM, level

__all__ = ["LIMITS", "set_limits", "limits", "check", "estimate_steps", "SECONDS_PER_STEP",
           "MAX_MOMENTUM", "check_momentum", "check_level", "DATASET_BYTES"]

#: Current limits: integration steps of one call, and bytes of its results.
#: Defaults: 5e9 steps (about half an hour on one core), 4 GiB.
LIMITS: dict[str, float] = {"steps": 5e9, "memory": 4.0 * 2**30}
_DEFAULTS = dict(LIMITS)
#: Measured cost of one DOP853 step of the Euler-Poisson field on one core (numba).
SECONDS_PER_STEP = 4e-7

#: Bytes per state of a states dataset (about 30 float64 variables: the state, three
#: charts, integrals, drifts, flags), for the memory estimate of the cost guard.
DATASET_BYTES = 30 * 8



def set_limits(steps: float | None = None, memory: float | None = None) -> dict[str, float]:
    """Set the limits (``None`` keeps one; ``math.inf`` removes it); returns the old ones.

    ``memory`` is in bytes. All or nothing: every value is checked (a real number > 0,
    not a bool, a string or NaN) before any limit changes.

    Parameters
    ----------
    steps : float, optional
        Largest estimated integration steps of one call (None: unchanged;
        ``math.inf``: no limit).
    memory : float, optional
        Largest estimated memory of one result, bytes (None: unchanged).

    Examples
    --------
    >>> old = set_limits(steps=1e3, memory=-1)
    Traceback (most recent call last):
    ...
    ValueError: memory limit must be a real number > 0 (math.inf for none), got -1
    >>> LIMITS["steps"] == 5e9
    True
    """
    new: dict[str, float] = {}
    for name, value in (("steps", steps), ("memory", memory)):
        if value is None:
            continue
        v = float(value) if (isinstance(value, numbers.Real)
                             and not isinstance(value, bool)) else math.nan
        if not v > 0:
            raise ValueError(f"{name} limit must be a real number > 0 (math.inf for none), "
                             f"got {value!r}")
        new[name] = v
    old = dict(LIMITS)
    LIMITS.update(new)
    return old


@contextlib.contextmanager
def limits(steps: float | None = None, memory: float | None = None) -> Iterator[None]:
    """Temporarily set the limits, e.g. ``with limits(steps=math.inf): ...``.

    Parameters
    ----------
    steps : float, optional
        Largest estimated integration steps of one call (None: unchanged;
        ``math.inf``: no limit).
    memory : float, optional
        Largest estimated memory of one result, bytes (None: unchanged).
    """
    old = set_limits(steps, memory)
    try:
        yield
    finally:
        LIMITS.update(old)


@checks_body(ranges={"duration": "time", "rtol": "tolerance"})
def estimate_steps(body: RigidBody, y: NDArray[np.float64], duration: float,
                   rtol: float = 1e-12) -> float:
    """Estimated DOP853 steps to integrate the states ``y`` (shape (n, 6)) for ``duration``.

    Parameters
    ----------
    body : RigidBody
        The body (its frequencies scale the step).
    y : ndarray, shape (n, 6)
        Initial Euler-Poisson states.
    duration : float
        Integration time of each orbit (body time units).
    rtol : float, default 1e-12
        Relative tolerance (the DOP853 step scales as ``rtol^(1/8)``).

    Examples
    --------
    >>> from andoyer import RigidBody, from_andoyer
    >>> round(estimate_steps(RigidBody.paper(), from_andoyer([0.3, 0, 0.3, 1, 0])[None],
    ...                      1000.0))
    5341
    """
    a, b, c, mu, *_ = body.params
    inv = max(a, b, c)
    G = momentum_bound(body, y)
    omega = G * inv + math.sqrt(2.0 * abs(mu) * inv)
    scale = (1e-12 / max(float(rtol), 1e-16)) ** 0.125
    return float(np.sum(8.0 * omega * abs(float(duration)) * scale + 10.0))


def _human(nbytes: float) -> str:
    for unit in ("B", "KiB", "MiB", "GiB", "TiB"):
        if nbytes < 1024 or unit == "TiB":
            return f"{nbytes:.3g} {unit}"
        nbytes /= 1024
    return f"{nbytes:.3g} TiB"  # pragma: no cover


def check_momentum(G: float, name: str) -> None:
    """``ValueError`` naming ``name`` if ``|G|`` exceeds :data:`MAX_MOMENTUM`.

    Parameters
    ----------
    G : float
        A momentum length ``|G|``.
    name : str
        The name the error gives it (the argument or flag it came from).

    Examples
    --------
    >>> check_momentum(1e150, "y0")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: y0: |G| = 1e+150 is beyond the 1e+100 that the integrators take ...
    """
    if not G <= MAX_MOMENTUM:
        raise ValueError(f"{name}: |G| = {G:.3g} is beyond the {MAX_MOMENTUM:.3g} that the "
                         "integrators take (the field (1) and its error control would "
                         "overflow); rescale the problem (time by 1/|G|, energies by "
                         "1/|G|^2)")


def check_level(body: RigidBody, h: float, name: str = "h") -> None:
    """``ValueError`` naming ``name`` if the level ``H = h`` is not finite or reaches
    ``|G|`` beyond :data:`MAX_MOMENTUM` (``|G| <= sqrt(2 (h + mu) / min(a, b, c))``, Eq.
    (1)): :func:`andoyer.validation.level`, which every public function taking an energy
    ``h`` and a body applies through its argument checks. Not itself decorated by
    :func:`~andoyer.body.checks_body`, whose check of ``h`` would name ``h``, not ``name``
    (``--energy``).

    Parameters
    ----------
    body : RigidBody
        The body (``mu`` and its inverse moments ``a, b, c``).
    h : float
        The energy level ``H = h``.
    name : str, default "h"
        The name the error gives the level (``"--energy"`` on the command line).
    """
    if not isinstance(body, RigidBody):
        raise ArgumentTypeError(f"check_level: body must be a RigidBody, got "
                                f"{type(body).__name__}")
    level(name, h, body)


def check(what: str, *, steps: float = 0.0, memory: float = 0.0) -> None:
    """Raise :class:`~andoyer.errors.CostLimitError` if an estimate exceeds its limit.

    Parameters
    ----------
    what : str
        What is estimated, named in the error (a flag or an argument, e.g.
        ``"--n-out 1000000000"``).
    steps : float, default 0.0
        Estimated integration steps.
    memory : float, default 0.0
        Estimated memory of the results, bytes.
    """
    hint = ("raise it with andoyer.integrate.budget.set_limits({}=...) or, on the command "
            "line, --no-limits")
    if steps > LIMITS["steps"]:
        raise CostLimitError(
            f"{what}: about {steps:.3g} integration steps (~{steps * SECONDS_PER_STEP:.2g} s "
            f"on one core) exceed the limit {LIMITS['steps']:.3g}; " + hint.format("steps"))
    if memory > LIMITS["memory"]:
        raise CostLimitError(
            f"{what}: the results would take about {_human(memory)}, over the limit "
            f"{_human(LIMITS['memory'])}; ask for fewer orbits or points, or "
            + hint.format("memory"))
