"""Random Andoyer-Deprit points for the kernels' tests, a third near the chart's singular
sets (|L| = G, |M| = G), where the kernels' jets are hardest."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray


def andoyer_points(n: int, rng: np.random.Generator) -> NDArray[np.float64]:
    """``n`` points ``(l, g, L, G, M)``, G in [0.5, 2], drawn from ``rng``; the first sixth
    with ``|L|`` at ``G`` (to 1e-12 or 1e-7), the next sixth with ``|M|`` there."""
    G = rng.uniform(0.5, 2.0, n)
    P = np.stack([rng.uniform(-3, 3, n), rng.uniform(-3, 3, n), G * rng.uniform(-0.9, 0.9, n),
                  G, G * rng.uniform(-0.9, 0.9, n)], axis=-1)
    near = rng.choice([1 - 1e-12, -(1 - 1e-12), 1 - 1e-7], size=n)
    P[: n // 6, 2] = G[: n // 6] * near[: n // 6]
    P[n // 6: n // 3, 4] = G[n // 6: n // 3] * near[n // 6: n // 3]
    return P
