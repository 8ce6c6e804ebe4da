"""Points of a section plane where an energy level meets it, for
:func:`andoyer.integrate.fill.fill_section`: the box of the accessible cells, a grid or a
scrambled Sobol/Halton sequence in it keeping the points where the level's equation has a
root, and the accessible region's boundary as polylines (``contourpy``).

The equation is fill's (``H = h`` solved for the missing action on the plane, Eqs. (5),
(14) of the paper); any object with its ``brackets(p, q)`` method serves.
"""

from __future__ import annotations

import math
from typing import Any, Protocol

import contourpy
import numpy as np
from numpy.typing import NDArray

__all__ = ["LevelEquation", "accessible_box", "has_root", "grid_points", "qmc_points",
           "polylines"]


class LevelEquation(Protocol):
    """The level's equation on a plane: ``brackets(p, q)`` gives the points with a root
    (fill's ``_Equation``)."""

    def brackets(self, p: NDArray[np.float64], q: NDArray[np.float64]) -> Any: ...


def accessible_box(acc: NDArray[np.bool_], xs: NDArray[np.float64], ys: NDArray[np.float64]
          ) -> tuple[float, float, float, float, float]:
    """Bounding box of the accessible grid cells (one cell of margin) and its fill ratio.

    Parameters
    ----------
    acc : ndarray of bool, shape (nx, ny)
        Accessible cells of the grid.
    xs : ndarray, shape (nx,)
        Cell centres along the horizontal axis.
    ys : ndarray, shape (ny,)
        Cell centres along the vertical axis.
    """
    i = np.flatnonzero(acc.any(axis=1))
    j = np.flatnonzero(acc.any(axis=0))
    i0, i1 = max(i[0] - 1, 0), min(i[-1] + 1, xs.size - 1)
    j0, j1 = max(j[0] - 1, 0), min(j[-1] + 1, ys.size - 1)
    frac = float(acc[i0:i1 + 1, j0:j1 + 1].mean())
    return float(xs[i0]), float(xs[i1]), float(ys[j0]), float(ys[j1]), frac


def has_root(eq: LevelEquation, p: NDArray[np.float64], q: NDArray[np.float64]
              ) -> NDArray[np.bool_]:
    """Whether the level's equation has a root above each plane point ``(p, q)``.

    Parameters
    ----------
    eq : LevelEquation
        The level's equation on the plane.
    p, q : ndarray, shape (n,)
        Plane points (horizontal, vertical coordinate).

    Returns
    -------
    ndarray of bool, shape (n,)
    """
    pts, _, _, zpts, _ = eq.brackets(p, q)
    out = np.zeros(p.size, dtype=bool)
    out[pts] = True
    out[zpts] = True
    return out


def grid_points(eq: LevelEquation, box: tuple[float, float, float, float, float], n: int,
                max_points: int | None = None
                ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Cell-centred k x k grid over the box, k chosen so that about n points are accessible.

    Parameters
    ----------
    eq : LevelEquation
        The level's equation on the plane.
    box : (x_min, x_max, y_min, y_max, fill ratio)
        The box of :func:`accessible_box`.
    n : int
        About how many accessible points are wanted.
    max_points : int, optional
        Most plane points tried in all (the grids' sizes add up): a level whose
        accessible points have no admissible root (near a degenerate minimum) ends the
        search there, with what was found (possibly nothing).
    """
    x0, x1, y0, y1, frac = box
    k = max(1, math.ceil(math.sqrt(n / max(frac, 1e-6))))
    budget = math.inf if max_points is None else max_points
    best: tuple[int, NDArray[np.float64], NDArray[np.float64]] | None = None
    tried: set[int] = set()
    for _ in range(8):
        if k * k > budget:  # what is left of the budget: a smaller grid, or none
            k = math.isqrt(int(budget))
        if k < 1 or k in tried:
            break
        budget -= k * k
        tried.add(k)
        gx = x0 + (np.arange(k) + 0.5) * (x1 - x0) / k
        gy = y0 + (np.arange(k) + 0.5) * (y1 - y0) / k
        X, Y = (a.ravel() for a in np.meshgrid(gx, gy, indexing="ij"))
        keep = has_root(eq, X, Y)
        count = int(keep.sum())
        if best is None or abs(count - n) < abs(best[0] - n) or best[0] == 0:
            best = (count, X[keep], Y[keep])
        if count == n:
            break
        k = 2 * k if count == 0 else max(1, round(k * math.sqrt(n / count)))
    if best is None:
        return np.empty(0), np.empty(0)
    return best[1], best[2]


def qmc_points(eq: LevelEquation, box: tuple[float, float, float, float, float], n: int,
               method: str, seed: int, max_points: int | None = None
               ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The first n accessible points of a scrambled Sobol or Halton sequence in the box.

    Parameters
    ----------
    eq : LevelEquation
        The level's equation on the plane.
    box : (x_min, x_max, y_min, y_max, fill ratio)
        The box of :func:`accessible_box`.
    n : int
        How many accessible points are wanted.
    method : {"sobol", "halton"}
        The low-discrepancy sequence.
    seed : int
        Seed of its scrambling.
    max_points : int, optional
        Most points of the sequence tried in all (then what was found is returned).
    """
    x0, x1, y0, y1, frac = box
    from scipy.stats import qmc

    engine = (qmc.Sobol if method == "sobol" else qmc.Halton)(d=2, scramble=True, rng=seed)
    # Sobol points keep their balance in blocks of a power of 2.
    m = 2 ** max(1, math.ceil(math.log2(1.25 * n / max(frac, 1e-6))))
    xs: list[NDArray[np.float64]] = []
    ys: list[NDArray[np.float64]] = []
    got = 0
    budget = math.inf if max_points is None else max_points
    if max_points is not None:
        m = max(2, min(m, 2 ** int(math.log2(max(max_points, 2)))))
    for _ in range(64):
        if budget < m:
            break
        budget -= m
        u = engine.random(m)
        X, Y = x0 + (x1 - x0) * u[:, 0], y0 + (y1 - y0) * u[:, 1]
        keep = has_root(eq, X, Y)
        xs.append(X[keep])
        ys.append(Y[keep])
        got += int(keep.sum())
        if got >= n:
            break
    return np.concatenate(xs)[:n], np.concatenate(ys)[:n]


def polylines(xs: NDArray[np.float64], ys: NDArray[np.float64], F: NDArray[np.float64]
               ) -> NDArray[np.float64]:
    """Contour ``F = 0`` as NaN-separated vertices, shape ``(V, 2)``.

    Parameters
    ----------
    xs : ndarray, shape (nx,)
        Grid along the horizontal axis.
    ys : ndarray, shape (ny,)
        Grid along the vertical axis.
    F : ndarray, shape (nx, ny)
        The function whose zero level is drawn.
    """
    gen = contourpy.contour_generator(xs, ys, F.T, line_type="Separate")
    lines = gen.lines(0.0)
    parts: list[NDArray[np.float64]] = []
    for line in lines:
        if parts:
            parts.append(np.full((1, 2), np.nan))
        parts.append(np.asarray(line, dtype=float))
    return np.concatenate(parts) if parts else np.empty((0, 2))
