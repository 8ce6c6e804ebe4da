"""The first integrals of the Euler-Poisson equations (1), listed once.

Each row of :data:`INTEGRALS` is an integral's storage name, symbol and long name, its
value as a function of states ``(..., 6)`` (NumPy arithmetic, so that it also evaluates
on an object array of SymPy symbols: ``tests/charts/test_integrals.py`` checks with the
field of :mod:`andoyer.symbolic.hamiltonian` that each is conserved), the bodies it
holds for, and the scale its drift is measured against. The states datasets
(:func:`andoyer.integrate.results.derived_values`: values and drifts), the explorer's
drifts (:func:`andoyer.explore.orbits.integral_drifts`) and the chaos indicators'
``H_drift`` read it, so a body preset that brings an integral (Kovalevskaya's ``K``)
gets it everywhere.

The drift of an integral ``I`` from its reference value ``I0`` (the first state of an
orbit, or the level a caller fixed) is ``(I - I0) / scale``: for ``H``
``max(|I0|, mu)`` (the energy's scale where the level is near 0), for the momenta
``|G0|``, for ``|gamma|^2`` 1 (absolute).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from andoyer.body import RigidBody
from andoyer.charts.euler_poisson import hamiltonian_expr

__all__ = ["Integral", "INTEGRALS", "COMMON", "integrals_of", "drift_scale"]

_ROUND = 1e-12


def _energy(body: RigidBody, y: Any) -> Any:
    G1, G2, G3, gamma1, gamma2, gamma3 = (y[..., k] for k in range(6))
    return hamiltonian_expr(G1, G2, G3, gamma1, gamma2, gamma3, *body.params)


def _area(body: RigidBody, y: Any) -> Any:
    return np.einsum("...i,...i->...", y[..., :3], y[..., 3:])


def _geometric(body: RigidBody, y: Any) -> Any:
    return np.einsum("...i,...i->...", y[..., 3:], y[..., 3:])


def _kovalevskaya(body: RigidBody, y: Any) -> Any:
    w1, w2, nu = y[..., 0] / body.A, y[..., 1] / body.A, body.mu / body.C
    return (w1 ** 2 - w2 ** 2 - nu * y[..., 3]) ** 2 + (2 * w1 * w2 - nu * y[..., 4]) ** 2


def _every_body(body: RigidBody) -> bool:
    return True


def _is_kovalevskaya(body: RigidBody) -> bool:
    return (abs(body.A - body.B) <= _ROUND * body.A and abs(body.A - 2 * body.C) <= _ROUND * body.A
            and abs(body.r[0] - 1.0) <= _ROUND)


def _energy_scale(body: RigidBody, y0: NDArray[np.float64], I0: NDArray[np.float64]
                  ) -> NDArray[np.float64]:
    return np.maximum(np.abs(I0), body.mu)


def _momentum_scale(body: RigidBody, y0: NDArray[np.float64], I0: NDArray[np.float64]
                    ) -> NDArray[np.float64]:
    return np.asarray(np.linalg.norm(y0[..., :3], axis=-1))


def _squared_momentum_scale(body: RigidBody, y0: NDArray[np.float64],
                            I0: NDArray[np.float64]) -> NDArray[np.float64]:
    return np.asarray(np.sum(y0[..., :2] ** 2, axis=-1) / body.A ** 2
                      + body.mu / body.C) ** 2


def _unit_scale(body: RigidBody, y0: NDArray[np.float64], I0: NDArray[np.float64]
                ) -> NDArray[np.float64]:
    return np.ones(np.shape(I0))


@dataclass(frozen=True)
class Integral:
    """One first integral of (1).

    Parameters
    ----------
    name : str
        Its storage name (a dataset variable; its drift is ``<name>_drift``).
    symbol : str
        Its symbol (dataset attribute).
    long_name : str
        What it is (dataset attribute).
    value : callable
        ``value(body, y)``: its value at states ``y`` (``(..., 6)``; NumPy arithmetic,
        also on an object array of SymPy symbols).
    holds : callable
        ``holds(body)``: whether it is an integral of this body's flow.
    scale : callable
        ``scale(body, y0, I0)``: what its drift from the reference ``I0`` at states
        ``y0`` is relative to.
    scale_name : str
        That scale, in words (the drift's attribute).
    """

    name: str
    symbol: str
    long_name: str
    value: Callable[[RigidBody, Any], Any]
    holds: Callable[[RigidBody], bool]
    scale: Callable[[RigidBody, NDArray[np.float64], NDArray[np.float64]],
                    NDArray[np.float64]]
    scale_name: str

    def __call__(self, body: RigidBody, y: NDArray[np.float64]) -> NDArray[np.float64]:
        """Its values at states ``y`` (float arrays)."""
        return np.asarray(self.value(body, np.asarray(y, dtype=float)), dtype=float)

    def drift(self, body: RigidBody, values: NDArray[np.float64], y0: NDArray[np.float64],
              I0: NDArray[np.float64] | float | None = None) -> NDArray[np.float64]:
        """``(values - I0) / scale``: the drift from the reference ``I0`` (default its
        value at ``y0``), relative to its scale (1 where the scale is 0).

        Parameters
        ----------
        body : RigidBody
            The body.
        values : ndarray
            Its values.
        y0 : ndarray, shape (..., 6)
            The reference states (broadcast against ``values``).
        I0 : ndarray or float, optional
            The reference value (a level the caller fixed).
        """
        ref = self(body, y0) if I0 is None else np.asarray(I0, dtype=float)
        scale = self.scale(body, np.asarray(y0, dtype=float), ref)
        return np.asarray((values - ref) / np.where(scale > 0, scale, 1.0))


#: Every first integral andoyer knows, by storage name (the order of datasets).
INTEGRALS: dict[str, Integral] = {i.name: i for i in (
    Integral("H", "H", "energy H = (G, I^-1 G)/2 + mu (r, gamma), Eq. (1)", _energy,
             _every_body, _energy_scale, "max(|H(0)|, mu)"),
    Integral("area", "M", "area integral (G, gamma)", _area, _every_body, _momentum_scale,
             "|G(0)|"),
    Integral("geometric", "|gamma|^2", "geometric integral |gamma|^2", _geometric,
             _every_body, _unit_scale, "1"),
    Integral("K", "K", "Kovalevskaya's integral (w1^2 - w2^2 - (mu/C) gamma1)^2 + "
             "(2 w1 w2 - (mu/C) gamma2)^2, w = I^-1 G", _kovalevskaya, _is_kovalevskaya,
             _squared_momentum_scale, "((G1^2 + G2^2)(0) / A^2 + mu / C)^2"),
)}

#: The integrals of every body (datasets always hold them).
COMMON = tuple(k for k, i in INTEGRALS.items() if i.holds is _every_body)


def integrals_of(body: RigidBody) -> tuple[str, ...]:
    """The names of the integrals of ``body``'s flow: :data:`COMMON` and those its
    moments and centre of mass bring (a Kovalevskaya top's ``K``).

    Parameters
    ----------
    body : RigidBody
        The body.

    Examples
    --------
    >>> integrals_of(RigidBody.kovalevskaya()), integrals_of(RigidBody.paper())
    (('H', 'area', 'geometric', 'K'), ('H', 'area', 'geometric'))
    """
    return tuple(k for k, i in INTEGRALS.items() if i.holds(body))


def drift_scale(name: str, body: RigidBody, y0: NDArray[np.float64],
                I0: NDArray[np.float64] | float | None = None) -> NDArray[np.float64]:
    """The scale of the drift of integral ``name`` from states ``y0`` (or the level
    ``I0``).

    Parameters
    ----------
    name : str
        A key of :data:`INTEGRALS`.
    body : RigidBody
        The body.
    y0 : ndarray, shape (..., 6)
        The reference states.
    I0 : ndarray or float, optional
        The reference value (default: the integral at ``y0``).
    """
    integral = INTEGRALS[name]
    ref = integral(body, y0) if I0 is None else np.asarray(I0, dtype=float)
    return integral.scale(body, np.asarray(y0, dtype=float), ref)
