"""The seam between the friendly integration layer and the engines.

Every engine works on plain float arrays of Euler-Poisson states (the regular,
global description) and implements :class:`Engine`. The friendly layer
(:func:`andoyer.integrate.propagate`, :func:`andoyer.integrate.poincare`) validates
inputs, picks the engine and wraps results into xarray datasets.

``params`` is always the 8-tuple ``(a, b, c, mu, e1, e2, e3, phi0)``: the body's
kernel parameters (:attr:`RigidBody.params`) followed by ``phi0`` (0.0 for a body
whose centre of mass is off the G1-G2 plane; it only enters theta sections).

Section kinds are indices into :data:`andoyer.kernels.generated.SECTION_KINDS`;
the section function and its margin come from the generated
``section(kind, G1, G2, G3, gamma1, gamma2, gamma3, phi0, value, cv, sv) -> (f, w)``:
a crossing is a root of ``f`` in the requested direction where ``w > 0``.
"""

from __future__ import annotations

from typing import NamedTuple, Protocol

import numpy as np
from numpy.typing import NDArray

__all__ = ["Engine", "Crossings", "TOLERANCE_FACTOR", "check_tolerance_factor"]

#: (a, b, c, mu, e1, e2, e3, phi0)
Params = tuple[float, float, float, float, float, float, float, float]


class Crossings(NamedTuple):
    """What :meth:`Engine.crossings` returns."""

    t: NDArray[np.float64]  # (n, n_crossings), NaN where an orbit had fewer crossings
    y: NDArray[np.float64]  # (n, n_crossings, 6), NaN-padded likewise
    count: NDArray[np.int64]  # type: ignore[assignment]  # (n,); shadows tuple.count


#: Ratio of the tolerance given to the DOP853 controller to the accuracy an engine is
#: asked for (``rtol, atol`` of the Engine contract). The controller bounds an
#: *estimate* of each step's local error by ``atol + rtol |y|``; the integrals then
#: drift linearly, by ~1e-13 per time unit at rtol = atol = 1e-12 for a heavy top
#: (mu ~ 0.5, ``|G| ~ 1``): 1e-9 at t = 1e4. With the factor the drift of H, (G, gamma)
#: and ``|gamma|^2`` stays below ~2e-11 over t = 1e4 at a requested 1e-12 (paper's body
#: and mu = 0.5, 0.7 bodies, 18 orbits each), for ~1.6x the steps. 0.025 keeps a
#: requested 1e-12 above SciPy's floor rtol >= 100 eps. The kernels never apply it:
#: the engines do (numba and scipy engines).
TOLERANCE_FACTOR = 0.025


def check_tolerance_factor(tolerance_factor: float) -> float:
    """Validate a DOP853 engine's ``tolerance_factor`` (in (0, 1])."""
    if not 0.0 < tolerance_factor <= 1.0:
        raise ValueError(f"tolerance_factor must be in (0, 1], got {tolerance_factor!r}")
    return float(tolerance_factor)


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


