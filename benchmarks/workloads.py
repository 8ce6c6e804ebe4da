"""The benchmark problems: the paper's body, initial states, sizes of W1-W7.

The body is the paper's Hess gyroscope, A = 2.5, B = 2.0, C = 2.2, mu = 0.01. The
initial states lie on the energy level of the Andoyer-Deprit state
(l, g, L, G, M) = (0.3, 0, 0.3, 1, 0) (h = 0.24657), with M = 0, seeded over the
Hess-chart plane theta2 = 0 by a scrambled Sobol sequence (|G| between 0.98 and 1.12).
They are made once with andoyer (setup, not timed) and handed to every runner as
plain numbers.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cache

import numpy as np

from andoyer import RigidBody, energy, from_andoyer

#: (l, g, L, G, M) fixing the energy level.
LEVEL_STATE = (0.3, 0.0, 0.3, 1.0, 0.0)
#: The sections of W2: (coordinate, value), crossed upward.
SECTIONS = (("G3", 0.0), ("theta2", 0.0))


@dataclass(frozen=True)
class Sizes:
    """How big each workload is (full and quick modes)."""

    w1_t_end: float = 1e4
    w1_points: int = 1001
    w2_orbits: int = 50
    w2_crossings: int = 1000
    scipy_orbits: int = 2  # orbits of the scipy W2 runs (x2 for the pool), extrapolated
    w3_grid: int = 64
    w3_t_end: float = 1000.0
    w3_big: int = 256  # the large map (timed once against the hand-written ensemble; 0: none)
    w2_small: tuple[int, int] = (20, 400)  # W2 G3, taylor against heyoka, beside 50 x 1000
    cost: tuple[int, int] = (16, 300)  # W6: orbits, theta2 crossings fixing the span
    lanes: tuple[int, int, float] = (256, 1000, 1000.0)  # W7: orbits, G3 crossings, t_end
    repeat: int = 5
    w1_rounds: int = 31  # W1's runners, milliseconds each, timed in turn
    tol: float = 1e-12


FULL = Sizes()
QUICK = Sizes(w1_t_end=1e3, w1_points=101, w2_orbits=8, w2_crossings=50, scipy_orbits=1,
              w3_grid=8, w3_t_end=100.0, w3_big=0, w2_small=(4, 20), cost=(8, 20),
              lanes=(16, 20, 50.0), repeat=3, w1_rounds=5)


def body() -> RigidBody:
    return RigidBody.paper()


def params(b: RigidBody) -> dict[str, float]:
    """The body as the plain numbers the peer scripts take."""
    a, b_, c, mu, e1, e2, e3 = b.params
    return {"a": a, "b": b_, "c": c, "mu": mu, "e1": e1, "e2": e2, "e3": e3,
            "phi0": b.phi0}


def energy_level(b: RigidBody) -> float:
    return float(energy(b, from_andoyer(LEVEL_STATE)))


@cache
def initial_states(n: int) -> np.ndarray:
    """``n`` Euler-Poisson states (n, 6) on the level, M = 0, |G| ~ 1."""
    from andoyer.integrate import fill_section

    b = body()
    fill = fill_section(b, energy_level(b), 0.0, ("theta2", 0.0), n_orbits=max(n, 8),
                        sampling="sobol")
    y0 = np.asarray(fill["y0"].values, dtype=float)
    if y0.shape[0] < n:
        raise RuntimeError(f"fill_section gave {y0.shape[0]} states, {n} wanted")
    return y0[:n]


def w1_times(s: Sizes) -> np.ndarray:
    return np.linspace(0.0, s.w1_t_end, s.w1_points)


def subset(n: int, k: int) -> np.ndarray:
    """``k`` orbit indices spread evenly inside ``0..n-1`` (for the slow scipy runs)."""
    return np.unique(np.linspace(0, n - 1, k + 2)[1:-1].round().astype(int))


def angle_value(name: str, value: float) -> float:
    """Section values as andoyer stores them (angles in [0, 2 pi))."""
    return math.remainder(value, 2 * math.pi) % (2 * math.pi) if name == "theta2" else value
