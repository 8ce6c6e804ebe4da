"""The heavy top as a user outside andoyer writes it: Euler-Poisson equations by hand.

Shared by the peer scripts (plain heyoka, hand-tuned heyoka, scipy). Nothing here
imports andoyer: the peers get the body as plain numbers,

    p = {"a": 1/A, "b": 1/B, "c": 1/C, "mu": mu, "e1": .., "e2": .., "e3": .., "phi0": ..}

and the initial states as an (n, 6) array (G1, G2, G3, gamma1, gamma2, gamma3).

Equations (1): with omega = (a G1, b G2, c G3) and r = (e1, e2, e3),

    dG/dt     = G x omega + mu gamma x r,
    dgamma/dt = gamma x omega.

Sections: ``G3 = value`` and the Hess-chart angle ``theta2 = g - l - phi0 = value``.
For the angle, with the Andoyer-Deprit angles read off the state,

    (cos l, sin l) ~ (G2, G1),
    (cos g, sin g) ~ (G3 (G1 gamma1 + G2 gamma2) - gamma3 (G1^2 + G2^2),
                      |G| (G2 gamma1 - G1 gamma2)),

the event function is ``f = k sin(theta2 - value)`` and the margin
``w = k cos(theta2 - value)`` (k > 0): a root with ``w > 0`` is a crossing, one with
``w < 0`` is the antipode ``theta2 = value + pi`` and is dropped.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

#: A root at t <= T_START is the initial state lying on the section, not a crossing.
T_START = 1e-10


def rhs(p: dict[str, float]) -> Any:
    """``f(t, y)`` for scipy.integrate.solve_ivp."""
    a, b, c, mu, e1, e2, e3 = (p[k] for k in ("a", "b", "c", "mu", "e1", "e2", "e3"))

    def f(_t: float, y: np.ndarray) -> np.ndarray:
        G1, G2, G3, g1, g2, g3 = y
        w1, w2, w3 = a * G1, b * G2, c * G3
        return np.array([G2 * w3 - G3 * w2 + mu * (g2 * e3 - g3 * e2),
                         G3 * w1 - G1 * w3 + mu * (g3 * e1 - g1 * e3),
                         G1 * w2 - G2 * w1 + mu * (g1 * e2 - g2 * e1),
                         g2 * w3 - g3 * w2,
                         g3 * w1 - g1 * w3,
                         g1 * w2 - g2 * w1])
    return f


def heyoka_system(p: dict[str, float], hy: Any) -> list[tuple[Any, Any]]:
    """The same equations as heyoka expressions (numbers folded in)."""
    a, b, c, mu, e1, e2, e3 = (p[k] for k in ("a", "b", "c", "mu", "e1", "e2", "e3"))
    G1, G2, G3, g1, g2, g3 = hy.make_vars("G1", "G2", "G3", "g1", "g2", "g3")
    return [(G1, (c - b) * G2 * G3 + mu * (e3 * g2 - e2 * g3)),
            (G2, (a - c) * G1 * G3 + mu * (e1 * g3 - e3 * g1)),
            (G3, (b - a) * G1 * G2 + mu * (e2 * g1 - e1 * g2)),
            (g1, c * g2 * G3 - b * g3 * G2),
            (g2, a * g3 * G1 - c * g1 * G3),
            (g3, b * g1 * G2 - a * g2 * G1)]


def _theta2_pair(G1: Any, G2: Any, G3: Any, g1: Any, g2: Any, g3: Any, phi0: float,
                 value: float, sqrt: Any) -> tuple[Any, Any]:
    """``(k sin(theta2 - value), k cos(theta2 - value))`` with k > 0."""
    cg = G3 * (G1 * g1 + G2 * g2) - g3 * (G1 * G1 + G2 * G2)
    sg = sqrt(G1 * G1 + G2 * G2 + G3 * G3) * (G2 * g1 - G1 * g2)
    ca, sa = math.cos(phi0 + value), math.sin(phi0 + value)
    cl, sl = G2 * ca - G1 * sa, G1 * ca + G2 * sa  # ~ cos, sin of l + phi0 + value
    return sg * cl - cg * sl, cg * cl + sg * sl


def heyoka_section(p: dict[str, float], name: str, value: float, hy: Any) -> Any:
    """The event function of section ``name = value`` as a heyoka expression."""
    G1, G2, G3, g1, g2, g3 = hy.make_vars("G1", "G2", "G3", "g1", "g2", "g3")
    if name == "G3":
        return G3 - value
    if name == "theta2":
        return _theta2_pair(G1, G2, G3, g1, g2, g3, p["phi0"], value, hy.sqrt)[0]
    raise ValueError(f"unknown section {name!r}")


def numpy_section(p: dict[str, float], name: str, value: float) -> Any:
    """``(f, w)`` of section ``name = value`` on states (..., 6), for scipy and filters."""
    def fw(y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        G1, G2, G3, g1, g2, g3 = np.moveaxis(np.asarray(y, dtype=float), -1, 0)
        if name == "G3":
            return G3 - value, np.ones_like(G3)
        return _theta2_pair(G1, G2, G3, g1, g2, g3, p["phi0"], value, np.sqrt)
    if name not in ("G3", "theta2"):
        raise ValueError(f"unknown section {name!r}")
    return fw
