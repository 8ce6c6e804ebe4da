"""The seam between the friendly integration layer and the engines.

Every engine works on plain float arrays of Euler-Poisson states (the regular,
global description) and implements :class:`Engine`. The friendly layer
(:func:`andoyer.integrate.propagate`, :func:`andoyer.integrate.poincare`) validates
inputs, picks the engine and wraps results into xarray datasets.

``params`` is always the 8-tuple ``(a, b, c, mu, e1, e2, e3, phi0)``: the body's
kernel parameters (:attr:`RigidBody.params`) followed by ``phi0`` (0.0 for a body
whose centre of mass is off the G1-G2 plane; it only enters theta sections).

Section kinds are indices into :data:`andoyer.kernels._generated.SECTION_KINDS`;
the section function and its margin come from the generated
``section(kind, G1, G2, G3, gamma1, gamma2, gamma3, phi0, value, cv, sv) -> (f, w)``:
a crossing is a root of ``f`` in the requested direction where ``w > 0``.
"""

from __future__ import annotations

from typing import Protocol

import numpy as np
from numpy.typing import NDArray

__all__ = ["Engine", "Crossings"]

#: (a, b, c, mu, e1, e2, e3, phi0)
Params = tuple[float, float, float, float, float, float, float, float]


class Crossings(Protocol):
    """What :meth:`Engine.crossings` returns (a NamedTuple in practice)."""

    t: NDArray[np.float64]  # (n, n_crossings), NaN where an orbit had fewer crossings
    y: NDArray[np.float64]  # (n, n_crossings, 6), NaN-padded likewise
    count: NDArray[np.int64]  # (n,) crossings found per orbit


class Engine(Protocol):
    """An integration engine for the Euler-Poisson equations (1)."""

    name: str

    def propagate(self, y0: NDArray[np.float64], t: NDArray[np.float64], params: Params,
                  rtol: float, atol: float) -> NDArray[np.float64]:
        """States at times ``t`` (shape (k,), increasing, ``t[0]`` is the initial time)
        for initial states ``y0`` (shape (n, 6)); returns shape (n, k, 6)."""
        ...

    def crossings(self, y0: NDArray[np.float64], params: Params, kind: int, value: float,
                  direction: int, n_crossings: int, t_max: float, rtol: float,
                  atol: float) -> Crossings:
        """The first ``n_crossings`` crossings after t = 0 of the section
        ``SECTION_KINDS[kind] = value`` in ``direction`` (+1: f increasing, -1:
        decreasing, 0: both), integrating at most to ``t_max``. Each crossing is
        located on the dense output / Taylor polynomial so that ``|f| <= 1e-12``
        (relative to the scale of f)."""
        ...
