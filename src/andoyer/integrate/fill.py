"""Filling a Poincare section: initial states on one energy level, and its accessible region.

A section of the reduced system (M fixed) is a plane of one chart at a fixed angle:

* ``g = g*`` in the Andoyer-Deprit chart (5)-(6): plane ``(l, L)``, remaining action
  ``G`` solved from ``H(l, g*, L, G, M) = h`` (H of Eq. (7));
* ``theta2 = theta2*`` in the Hess chart (14)-(15): plane ``(theta1, J1)``, remaining
  action ``J2`` solved from ``H(theta1, theta2*, J1, J2, J3 = M) = h`` (H after (15)).

Both charts order their coordinates ``(angle1, angle2, action1, action2, action3)`` with
the section on ``angle2``, the plane ``(angle1, action1)`` and the solved ``action2``,
so one solver serves both.

The equation for the action is solved on its whole admissible interval and **all**
roots are found: a scan (nodes dense near the lower end, where H has a square-root
singularity) brackets the sign changes, every discrete extremum of the scan that does
not change sign is refined by golden-section search (two roots closer than the scan
step are found too), and the brackets are closed all at once by
:func:`scipy.optimize.elementwise.find_root`.

The accessible region is where ``min over the action of H <= h``: it is reported on a
fine grid of the plane (``accessible``) and as the contour polylines of that minimum at
level h (``boundary_x``, ``boundary_y``, NaN-separated).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np
import xarray as xr
from numpy.typing import NDArray

from andoyer.body import RigidBody, checks_body
from andoyer.charts.andoyer_deprit import from_andoyer
from andoyer.charts.euler_poisson import STATE, energy
from andoyer.charts.hess import from_hess
from andoyer.dynamics import vector_field
from andoyer.integrate import budget
from andoyer.integrate.engines.base import Section
from andoyer.integrate.plane_sampling import (
    accessible_box,
    grid_points,
    polylines,
    qmc_points,
)
from andoyer.integrate.results import describe_variables, provenance
from andoyer.kernels.generated import equations as K
from andoyer.notation import SECTION_PLANES, SectionPlane
from andoyer.validation import box, integer
from andoyer.validation import finite as _finite
from andoyer.validation import positive as _positive

#: Longer names of arguments in messages (andoyer.validation.checks_arguments).
ARGUMENT_NAMES = {"n_orbits": "n_orbits (number of plane points)"}

__all__ = ["fill_section", "section_roots", "default_h", "SECTION_PLANES", "SINGULAR_MARGIN"]


#: Roots closer than this (relative to the action) to the chart's singular set
#: (``G = |L|``, ``G = |M|``; ``J1 = 0``, ``J1 = J2``, ``J2 = |J3|``) are skipped: there the
#: section angle is undefined or ill-conditioned (it loses ``eps / sqrt(margin)``).
SINGULAR_MARGIN = 1e-6

#: Scan nodes per plane point: for root brackets, and for the accessible-region grid.
_N_SCAN_ROOTS = 257
_N_SCAN_GRID = 65
#: Plane points per slab of the scans (their (points, nodes) arrays fit in the cache).
_SCAN_SLAB = 256
#: Lower floor of the action, relative to its upper bound, so that H is never evaluated
#: at G = 0 (where the chart and the kernels are undefined).
_ACTION_FLOOR = 1e-9
_GOLDEN_ITERATIONS = 64
#: Brackets from which one vectorised call closes them all; fewer are closed one by one by
#: Brent's method in C, whose scalar kernel calls cost less than the vectorised call's
#: per-iteration overhead (benchmarks/NOTES.md, "fill_section's roots").
_VECTOR_BRACKETS = 16
#: Most plane points the sampling tries, per orbit asked for (at least
#: :data:`_MIN_SAMPLE_POINTS`): near a degenerate minimum of H on the section the
#: accessible points may have no admissible root (the minimum on the chart's singular
#: set), and the search ends there instead of refining its grid for ever.
SAMPLE_POINTS_PER_ORBIT = 64
_MIN_SAMPLE_POINTS = 4096
_INV_PHI = (math.sqrt(5.0) - 1.0) / 2.0


_ALIASES = {"g_angle": "g"}

Method = Literal["grid", "sobol", "halton"]
RootChoice = Literal["all", "smallest", "largest"]


# ----------------------------------------------------------------------- the equation
@dataclass(frozen=True)
class _Equation:
    """``H(p, value, q, A, M) - h`` on one section, ``A`` in ``[lo(q), act_max]``."""

    plane: SectionPlane
    hamiltonian: Callable[..., Any]
    value: float
    M: float
    h: float
    act_max: float

    def f(self, p: Any, q: Any, A: Any) -> NDArray[np.float64]:
        return np.asarray(self.hamiltonian(p, self.value, q, A, self.M), dtype=float) - self.h

    def lower(self, q: NDArray[np.float64]) -> NDArray[np.float64]:
        """Lower end of the admissible action: ``max(|L|, |M|)`` resp. ``max(J1, |J3|)``."""
        return np.maximum(np.maximum(np.abs(q), abs(self.M)), _ACTION_FLOOR * self.act_max)

    def scan(self, p: NDArray[np.float64], q: NDArray[np.float64], k: int
             ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Action nodes ``(P, k)``, quadratically dense at the lower end, and f there."""
        lo = self.lower(q)
        hi = np.maximum(lo, self.act_max)
        s = np.linspace(0.0, 1.0, k) ** 2
        A = lo[:, None] + (hi - lo)[:, None] * s
        return A, self.f(p[:, None], q[:, None], A)

    def golden_min(self, p: NDArray[np.float64], q: NDArray[np.float64],
                   a: NDArray[np.float64], b: NDArray[np.float64], sign: float = 1.0
                   ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Vectorised golden-section search of the minimum of ``sign * f`` on ``[a, b]``."""
        c = b - _INV_PHI * (b - a)
        d = a + _INV_PHI * (b - a)
        fc, fd = sign * self.f(p, q, c), sign * self.f(p, q, d)
        for _ in range(_GOLDEN_ITERATIONS):
            left = fc < fd
            b = np.where(left, d, b)
            a = np.where(left, a, c)
            new = np.where(left, b - _INV_PHI * (b - a), a + _INV_PHI * (b - a))
            fnew = sign * self.f(p, q, new)
            c, d, fc, fd = (np.where(left, new, d), np.where(left, c, new),
                            np.where(left, fnew, fd), np.where(left, fc, fnew))
        x = np.where(fc < fd, c, d)
        return x, sign * np.minimum(fc, fd)

    def admissible(self, q: NDArray[np.float64]) -> NDArray[np.bool_]:
        return self.act_max * (1.0 - SINGULAR_MARGIN) > self.lower(q)

    def min_over_action(self, p: NDArray[np.float64], q: NDArray[np.float64],
                        k: int = _N_SCAN_GRID, chunk: int = 8192) -> NDArray[np.float64]:
        """``min_A H - h`` per plane point (continuous in ``(p, q)``)."""
        out = np.empty(p.shape, dtype=float)
        slab = max(1, _SCAN_SLAB * _N_SCAN_ROOTS // k)  # scan slabs of the roots' size
        for s in range(0, p.size, chunk):
            ps, qs = p[s:s + chunk], q[s:s + chunk]
            a, b, fscan = np.empty(ps.size), np.empty(ps.size), np.empty(ps.size)
            for r in range(0, ps.size, slab):
                A, F = self.scan(ps[r:r + slab], qs[r:r + slab], k)
                i = np.argmin(F, axis=1)
                rows = np.arange(A.shape[0])
                a[r:r + slab] = A[rows, np.maximum(i - 1, 0)]
                b[r:r + slab] = A[rows, np.minimum(i + 1, k - 1)]
                fscan[r:r + slab] = F[rows, i]
            _, fmin = self.golden_min(ps, qs, a, b)
            out[s:s + chunk] = np.minimum(fscan, fmin)
        return out

    def brackets(self, p: NDArray[np.float64], q: NDArray[np.float64],
                 k: int = _N_SCAN_ROOTS) -> tuple[NDArray[np.intp], NDArray[np.float64],
                                                  NDArray[np.float64], NDArray[np.intp],
                                                  NDArray[np.float64]]:
        """Intervals with a sign change of f, and roots that fell exactly on scan nodes.

        Returns ``(point, a, b)`` of the brackets and ``(point, A)`` of the exact roots.
        A pair of roots inside one scan cell is found through the discrete extremum next
        to it; three roots inside one cell (an extremum pair narrower than the scan
        step, inside a sign change) would show as one.
        """
        A, F = self.scan(p, q, k)
        ok = self.admissible(q)
        A, F = A[ok], F[ok]
        where_ok = np.flatnonzero(ok)
        # Sign changes between neighbouring nodes.
        i, j = np.nonzero(F[:, :-1] * F[:, 1:] < 0.0)
        pts, lo, hi = [where_ok[i]], [A[i, j]], [A[i, j + 1]]
        # Discrete extrema that do not change sign may hide two close roots.
        Fl = np.concatenate([F[:, :1], F[:, :-1]], axis=1)
        Fr = np.concatenate([F[:, 1:], F[:, -1:]], axis=1)
        for sign in (1.0, -1.0):
            g, gl, gr = sign * F, sign * Fl, sign * Fr
            i, j = np.nonzero((g > 0.0) & (g <= gl) & (g <= gr) & (gl > 0.0) & (gr > 0.0))
            if i.size == 0:
                continue
            a = A[i, np.maximum(j - 1, 0)]
            b = A[i, np.minimum(j + 1, k - 1)]
            x, fx = self.golden_min(p[where_ok[i]], q[where_ok[i]], a, b, sign)
            cross = sign * fx < 0.0
            pts += [where_ok[i[cross]], where_ok[i[cross]]]
            lo += [a[cross], x[cross]]
            hi += [x[cross], b[cross]]
        i, j = np.nonzero(F == 0.0)
        return (np.concatenate(pts), np.concatenate(lo), np.concatenate(hi),
                where_ok[i], A[i, j])

    def roots(self, p: NDArray[np.float64], q: NDArray[np.float64]
              ) -> list[NDArray[np.float64]]:
        """All admissible roots ``A`` of ``f(p, q, A) = 0`` per plane point, ascending."""
        if p.size == 0:
            return []
        pts, A = self.root_table(p, q)
        return np.split(A, np.searchsorted(pts, np.arange(1, p.size)))

    def root_table(self, p: NDArray[np.float64], q: NDArray[np.float64]
                   ) -> tuple[NDArray[np.intp], NDArray[np.float64]]:
        """Every admissible root as a row ``(point, A)``, sorted by point then ``A``.

        The scan runs :data:`_SCAN_SLAB` points at a time: its arrays of ``(points,
        257)`` floats then stay in the processor's cache (a 64 x 64 grid at once, 8 MB
        per array, ran 2.4 times slower), and a 256 x 256 map never holds them all
        (1.8 GB). The brackets of all points are then closed by one vectorised call.
        """
        parts = [self.brackets(p[s:s + _SCAN_SLAB], q[s:s + _SCAN_SLAB])
                 for s in range(0, p.size, _SCAN_SLAB)]
        starts = range(0, p.size, _SCAN_SLAB)
        pts = np.concatenate([b[0] + s for b, s in zip(parts, starts, strict=True)]
                             + [np.empty(0, np.intp)])
        lo = np.concatenate([b[1] for b in parts] + [np.empty(0)])
        hi = np.concatenate([b[2] for b in parts] + [np.empty(0)])
        zpts = np.concatenate([b[3] + s for b, s in zip(parts, starts, strict=True)]
                              + [np.empty(0, np.intp)])
        zA = np.concatenate([b[4] for b in parts] + [np.empty(0)])
        found = np.empty(0)
        if 0 < pts.size < _VECTOR_BRACKETS:
            from scipy.optimize import brentq

            found = np.array([brentq(lambda A, pi=p[i], qi=q[i]: float(self.f(pi, qi, A)),
                                     a, b, xtol=1e-14 * self.act_max,
                                     rtol=4 * np.finfo(float).eps, maxiter=200)
                              for i, a, b in zip(pts, lo, hi, strict=True)])
        elif pts.size:
            # Imported here, as qmc below: scipy.stats costs 0.4 s of import time, and
            # importing andoyer.integrate should not pay it.
            from scipy.optimize.elementwise import find_root

            # All brackets at once (Chandrupatla's method, vectorised): one call of the
            # energy kernel per iteration for every bracket, not a Python-level brentq per
            # bracket (timings: benchmarks/NOTES.md, "fill_section's roots").
            res = find_root(lambda A, pi, qi: self.f(pi, qi, A), (lo, hi),
                            args=(p[pts], q[pts]),
                            tolerances={"xatol": 1e-14 * self.act_max,
                                        "xrtol": 4 * np.finfo(float).eps, "fatol": 0.0,
                                        "frtol": 0.0}, maxiter=200)
            if not np.all(res.success):
                bad = int(np.count_nonzero(~res.success))
                raise RuntimeError(f"energy-level root finding failed for {bad} of "
                                   f"{pts.size} brackets (status {np.unique(res.status)})")
            found = np.asarray(res.x, dtype=float)
        point = np.concatenate([pts, zpts]).astype(np.intp)
        A = np.concatenate([found, zA.astype(float)])
        if point.size == 0:
            return point, A
        order = np.lexsort((A, point))
        point, A = point[order], A[order]
        # Per point: the distinct roots (brackets that share an end may return one root
        # twice: exact duplicates go, then roots within 1e-10 act_max of the previous
        # distinct one), then those off the chart's singular set.
        same = np.concatenate([[False], point[1:] == point[:-1]])
        dup = same & np.concatenate([[False], A[1:] == A[:-1]])
        point, A, same = point[~dup], A[~dup], same[~dup]
        near = same & np.concatenate([[False], np.diff(A) <= 1e-10 * self.act_max])
        keep = ~near & self._regular(q[point], A)
        return point[keep], A[keep]

    def _regular(self, q: NDArray[np.float64], A: NDArray[np.float64]) -> NDArray[np.bool_]:
        margin = SINGULAR_MARGIN * A
        ok = (A - np.abs(q) > margin) & (A - abs(self.M) > margin)
        if self.plane.chart == "hess":
            ok &= q > margin
        return np.asarray(ok, dtype=bool)


def _energy_kernel(body: RigidBody, plane: SectionPlane) -> Callable[..., Any]:
    """H in the section's chart, from the generated kernels (derived from Eq. (1))."""
    if plane.chart == "andoyer":
        params = body.params
        return lambda l, g, L, G, M: K.andoyer_hamiltonian(l, g, L, G, M, *params)
    hparams = (body.a, body.b, body.c, body.mu, body.phi0)
    return lambda theta1, theta2, J1, J2, J3: K.hess_hamiltonian(theta1, theta2, J1, J2, J3,
                                                                 *hparams)


def _action_bound(body: RigidBody, h: float) -> float:
    """Largest action on the level h: ``H >= min(a, b, c) G^2 / 2 - mu``."""
    return math.sqrt(2.0 * (h + body.mu) / min(body.a, body.b, body.c))


def _default_bounds(plane: SectionPlane, act_max: float, M: float
                    ) -> tuple[tuple[float, float], tuple[float, float]]:
    if plane.chart == "andoyer":
        return (0.0, math.tau), (-act_max, act_max)
    # H is 4 pi-periodic in theta1, 2 pi-periodic on M = 0 (see andoyer.charts.hess).
    return (0.0, math.tau if M == 0.0 else 2.0 * math.tau), (0.0, act_max)


# ----------------------------------------------------------------------- validation
def _parse_section(section: Any) -> tuple[SectionPlane, float]:
    """The plane and value of a section given as a :class:`Section`, a string parsed by
    :meth:`Section.parse` (a direction suffix is allowed and moot here), a pair
    ``(coord, value)`` or an object with ``.coord`` and ``.value``."""
    if isinstance(section, Section):
        sec = section
    elif isinstance(section, str):
        sec = Section.parse(section)
    else:
        if hasattr(section, "coord") and hasattr(section, "value"):
            coord, value = section.coord, section.value
        else:
            try:
                coord, value = section
            except (TypeError, ValueError):
                raise ValueError(f"section must be (coord, value), e.g. ('g', 0.0), a string "
                                 f"such as 'g=0' or a Section; got {section!r}") from None
        if not isinstance(coord, str):
            raise ValueError(f"section coordinate must be a name such as 'g', got {coord!r}")
        sec = Section(_ALIASES.get(coord, coord), value)
    if sec.coord not in SECTION_PLANES:
        raise ValueError(f"cannot fill a section of coordinate {sec.coord!r}: choose 'g' "
                         "(Andoyer-Deprit plane (l, L)) or 'theta2' (Hess plane (theta1, J1))")
    return SECTION_PLANES[sec.coord], sec.value


def _check_bounds(bounds: Any, plane: SectionPlane
                  ) -> tuple[tuple[float, float], tuple[float, float]]:
    (x0, x1), (y0, y1) = box("plane_bounds", bounds)
    if plane.chart == "hess" and y0 < 0.0:
        raise ValueError(f"plane_bounds: J1 = (G + L)/2 >= 0, got J1 range ({y0}, {y1})")
    return (x0, x1), (y0, y1)


def _label(plane: SectionPlane, value: float, M: float) -> str:
    return f"{plane.coord} = {value:.6g} (M = {M:.6g})"


def _section_minimum(body: RigidBody, plane: SectionPlane, value: float, M: float,
                     bounds: Any) -> float:
    """Approximate minimum of H over the section (h-independent), for error messages."""
    amax = float(np.max(np.abs([body.a, body.b, body.c])))
    if M != 0.0:
        G0 = 2.0 * abs(M)
    elif body.mu > 0.0:
        G0 = math.sqrt(body.mu / amax)
    else:
        G0 = 1.0
    # Some admissible point has H <= H_ref, so the minimum needs G <= G_up.
    H_ref = 0.5 * amax * G0**2 + body.mu
    G_up = _action_bound(body, H_ref)
    eq = _Equation(plane, _energy_kernel(body, plane), value, M, 0.0, G_up)
    (x0, x1), (y0, y1) = bounds if bounds is not None else _default_bounds(plane, G_up, M)
    X, Y = np.meshgrid(np.linspace(x0, x1, 121), np.linspace(y0, y1, 121), indexing="ij")
    return float(np.min(eq.min_over_action(X.ravel(), Y.ravel())))


def _no_intersection(body: RigidBody, plane: SectionPlane, value: float, M: float, h: float,
                     bounds: Any, why: str = "") -> ValueError:
    hmin = _section_minimum(body, plane, value, M, bounds)
    s = plane.symbols
    msg = (f"energy level h = {h:.10g} does not intersect the section "
           f"{_label(plane, value, M)}: on this section H takes values in "
           f"[{hmin:.10g}, +inf) (the minimum over the ({s[0]}, {s[2]}) plane at admissible "
           f"{s[3]}, estimated on a grid; H grows without bound with {s[3]}), so h must "
           f"exceed about {hmin:.6g}")
    if why:
        msg += f"; {why}"
    return ValueError(msg)


# ----------------------------------------------------------------------- public API
@checks_body(ranges={"h": "energy", "M": "action"})
def section_roots(body: RigidBody, h: float, M: float, section: Any, x: Any, y: Any
                  ) -> list[NDArray[np.float64]]:
    """All values of the remaining action on the level h above plane points ``(x, y)``.

    Parameters
    ----------
    body : RigidBody
    h, M : float
        Energy level and area constant.
    section : (coord, value) or object with ``.coord``, ``.value``
        ``("g", g*)`` (plane ``(l, L)``, solves ``G``) or ``("theta2", theta2*)``
        (plane ``(theta1, J1)``, solves ``J2``).
    x, y : array_like, same shape
        Plane coordinates ``(l, L)`` resp. ``(theta1, J1)``.

    Returns
    -------
    list of ndarray
        One ascending array of roots per point (flattened order); empty where the point
        is inaccessible or its roots lie within :data:`SINGULAR_MARGIN` of the chart's
        singular set.

    Examples
    --------
    >>> body = RigidBody.paper()
    >>> [r.round(12) for r in section_roots(body, 0.2466236515821201, 0.0, ("g", 0.0),
    ...                                      [0.3], [0.2])]
    [array([1.])]
    """
    plane, value = _parse_section(section)
    h, M = _finite("h", h), _finite("M", M)
    p = np.ravel(np.asarray(x, dtype=float))
    q = np.ravel(np.asarray(y, dtype=float))
    if p.shape != q.shape:
        raise ValueError(f"x and y must have the same size, got {p.size} and {q.size}")
    if h <= -body.mu:
        return [np.empty(0) for _ in range(p.size)]
    eq = _Equation(plane, _energy_kernel(body, plane), value, M, h, _action_bound(body, h))
    return eq.roots(p, q)


@checks_body(ranges={"M": "action"})
def default_h(body: RigidBody, M: float = 0.0) -> float:
    """The default energy level of the command line and the explorer: H at
    ``(l, g, L, G, M) = (0.3, 0, 0.3, 1, M)`` (Eq. (7)).

    Parameters
    ----------
    body : RigidBody
        The body.
    M : float, default 0.0
        Area constant ``(G, gamma) = M`` (``|M| < 1``).

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> round(default_h(RigidBody.paper()), 10)
    0.2465679623
    """
    M = _finite("M", M)
    if not abs(M) < 1.0:
        raise ValueError(f"the default energy level needs |M| < 1 (it sits at G = 1), got "
                         f"M = {M!r}; give h yourself")
    return float(energy(body, from_andoyer([0.3, 0.0, 0.3, 1.0, M])))


def _bottom(body: RigidBody, M: float) -> float:
    """``min(a, b, c) M^2 / 2 - mu``, the lowest energy at area constant ``M`` (inf on
    overflow, for a message)."""
    with np.errstate(over="ignore"):
        return float(0.5 * min(body.a, body.b, body.c) * np.float64(M) ** 2 - body.mu)


@checks_body(ranges={"h": "energy", "M": "action", "n_orbits": "count", "boundary_grid": "count",
             "tol": "tolerance"}, labels=ARGUMENT_NAMES)
def fill_section(body: RigidBody, h: float, M: float, section: Any, *, n_orbits: int = 40,
                 sampling: Method = "grid", seed: int = 0,
                 plane_bounds: Any = None, root: RootChoice = "all",
                 boundary_grid: int = 200, tol: float = 1e-12) -> xr.Dataset:
    """Initial states filling a Poincare section on the energy level ``H = h``.

    Parameters
    ----------
    body : RigidBody
        The Hess chart (``section=("theta2", .)``) needs ``e3 = 0``.
    h : float
        Energy level.
    M : float
        Area constant ``M = (G, gamma)`` (``J3`` in the Hess chart).
    section : (coord, value) or object with ``.coord`` and ``.value``
        ``("g", g*)``: Andoyer-Deprit plane ``(l, L)``, ``l`` in ``[0, 2 pi)``, ``L`` in
        ``[-G_max, G_max]``; ``G`` is solved. ``("theta2", theta2*)``: Hess plane
        ``(theta1, J1)``, ``theta1`` in ``[0, 2 pi)`` at ``M = 0`` (H is 2 pi-periodic
        there) and ``[0, 4 pi)`` otherwise, ``J1`` in ``[0, G_max]``; ``J2`` is solved.
        ``G_max = sqrt(2 (h + mu) / min(a, b, c))``. The value is taken mod 2 pi.
    n_orbits : int, default 40
        About this many orbits: plane points (more orbits with ``root="all"`` where the
        level has several sheets above one point).
    sampling : {"grid", "sobol", "halton"}
        ``"grid"``: a square grid over the bounding box of the accessible region, sized
        so that about n_orbits of its points are accessible. ``"sobol"``/``"halton"``:
        the first n_orbits accessible points of a scrambled low-discrepancy sequence in
        that box.
    seed : int, default 0
        Scrambling seed of the low-discrepancy sequences.
    plane_bounds : ((x_min, x_max), (y_min, y_max)), optional
        Restrict the plane (default above).
    root : {"all", "smallest", "largest"}
        Which roots of the equation for the action give initial states: every one
        (one orbit per root), or only the smallest/largest per plane point.
    boundary_grid : int, default 200
        Resolution of the accessible-region grid (``boundary_grid`` squared points).
    tol : float, default 1e-12
        Largest accepted ``|H(y0) - h| / max(|h|, mu)`` (> 0); states above it are
        refused with a ``ValueError`` naming ``tol``.

    Returns
    -------
    xarray.Dataset
        Dim ``orbit``: the Euler-Poisson state ``G1 .. gamma3`` and stacked ``y0``
        (``orbit, component``); the five chart coordinates (storage names, e.g.
        ``l_angle, g_angle, L_action, G_action, M_action``); ``residual``;
        ``root_index`` (0 = smallest action above the point) and ``n_roots``;
        ``point`` (index of the plane point); ``section_rate`` (d(coord)/dt, its sign
        is the crossing direction). Dims ``plane_x, plane_y``: ``accessible`` and
        ``H_min`` (minimum of H over the admissible action). Dim ``boundary_vertex``:
        ``boundary_x``, ``boundary_y``, the accessible region's boundary, polylines
        separated by NaN. Attrs: body, h, M, section, sampling, plane names and bounds,
        equations, units.

    Raises
    ------
    ValueError
        Unknown section coordinate, ``n_orbits < 1``, unknown sampling or root choice,
        ``|M|`` too large for h, or an energy level that does not meet the section (the
        message gives the energy range on the section), or meets it only where no orbit
        can start (a degenerate level near the minimum of H on the section: none of the
        ``SAMPLE_POINTS_PER_ORBIT * n_orbits`` plane points tried has a root off the
        chart's singular set).
    andoyer.errors.CostLimitError
        The evaluations of H the search may take (the boundary grid and the plane points
        it may try, bounded before the work starts) exceed the limit of
        :mod:`andoyer.integrate.budget`.

    Notes
    -----
    H is bounded below by the kinetic energy at the smallest moment minus the potential
    bound, :math:`H \\ge \\tfrac12 \\min(a, b, c) G^2 - \\mu`, so the action is sought on
    :math:`\\max(|L|, |M|) < G \\le G_{max}` (resp. :math:`\\max(J_1, |J_3|) < J_2 \\le
    G_{max}`), Eqs. (1), (7), (14)-(15) of the paper.

    References
    ----------
    .. [1] V. V. Kyrychenko, "Andoyer-Deprit variables use to the Hess gyroscope phase
       trajectories exploring".

    Examples
    --------
    >>> body = RigidBody.paper()
    >>> ds = fill_section(body, 0.2466, 0.0, ("g", 0.0), n_orbits=10)
    >>> bool(ds.residual.max() <= 1e-12), bool(abs(ds.g_angle).max() == 0.0)
    (True, True)
    """
    plane, value = _parse_section(section)
    h, M = _finite("h", h), _finite("M", M)
    budget.check_level(body, h)
    tol = _positive("tol", tol)
    n = integer("n_orbits (number of plane points)", n_orbits, 1)
    if sampling not in ("grid", "sobol", "halton"):
        raise ValueError(f"unknown sampling {sampling!r}; choose 'grid', 'sobol' or "
                         "'halton'")
    if root not in ("all", "smallest", "largest"):
        raise ValueError(f"unknown root choice {root!r}; choose 'all', 'smallest' or "
                         "'largest'")
    boundary_grid = integer("boundary_grid", boundary_grid, 8)
    # The work, bounded before it starts: evaluations of H (each about an integration
    # step's cost) on the boundary grid (scan and golden search over the action) and on
    # the plane points the sampling may try (scan over the action); memory of the roots
    # of n points (~500 bytes each) and of the boundary grid (~100 bytes a point).
    max_points = max(SAMPLE_POINTS_PER_ORBIT * n, _MIN_SAMPLE_POINTS)
    evaluations = (float(boundary_grid) ** 2 * (_N_SCAN_GRID + 2 * _GOLDEN_ITERATIONS)
                   + max_points * _N_SCAN_ROOTS * 2.5)
    budget.check("fill_section", steps=evaluations,
                 memory=500.0 * n + 100.0 * float(boundary_grid) ** 2
                 + 8.0 * _N_SCAN_ROOTS * min(max_points, _SCAN_SLAB) * 4)
    energy_fn = _energy_kernel(body, plane)  # the Hess chart raises here if e3 != 0
    bounds = None if plane_bounds is None else _check_bounds(plane_bounds, plane)
    if h <= -body.mu:
        raise _no_intersection(body, plane, value, M, h, bounds,
                               f"H >= -mu = {-body.mu:.6g} everywhere")
    act_max = _action_bound(body, h)
    if abs(M) >= act_max * (1.0 - SINGULAR_MARGIN):
        raise ValueError(
            f"|M| = {abs(M):.6g} is too large for the energy level h = {h:.10g}: the "
            f"actions obey |M| < {plane.symbols[3]} <= G_max = sqrt(2 (h + mu) / min(a, b, c))"
            f" = {act_max:.6g} (H >= min(a, b, c) M^2 / 2 - mu = "
            f"{_bottom(body, M):.6g}); lower |M| or "
            f"raise h")
    eq = _Equation(plane, energy_fn, value, M, h, act_max)
    (x0, x1), (y0, y1) = bounds if bounds is not None else _default_bounds(plane, act_max, M)

    # Accessible region on a fine grid: where min over the action of H is <= h.
    xs = np.linspace(x0, x1, boundary_grid)
    ys = np.linspace(y0, y1, boundary_grid)
    X, Y = np.meshgrid(xs, ys, indexing="ij")
    F = eq.min_over_action(X.ravel(), Y.ravel()).reshape(X.shape)
    acc = (F <= 0.0) & eq.admissible(Y)
    if not acc.any():
        raise _no_intersection(
            body, plane, value, M, h, bounds,
            "or the accessible region is smaller than the boundary grid: raise "
            "boundary_grid or narrow plane_bounds")
    box = accessible_box(acc, xs, ys)
    if sampling == "grid":
        P, Q = grid_points(eq, box, int(n), max_points)
    else:
        P, Q = qmc_points(eq, box, int(n), sampling, int(seed), max_points)
    roots = eq.roots(P, Q) if P.size else []
    if P.size == 0:
        # A thin accessible band the box's grid misses (near a degenerate minimum): the
        # accessible cells of the boundary grid themselves, at most max_points of them.
        cells = np.flatnonzero(acc.ravel())
        cells = cells[np.unique(np.linspace(0, cells.size - 1, min(cells.size, max_points))
                                .round().astype(np.intp))]
        Pc, Qc = X.ravel()[cells], Y.ravel()[cells]
        found = eq.roots(Pc, Qc)
        good = np.array([i for i, r in enumerate(found) if r.size], dtype=np.intp)
        if good.size:
            good = good[np.unique(np.linspace(0, good.size - 1, min(good.size, n))
                                  .round().astype(np.intp))]
        P, Q = Pc[good], Qc[good]
        roots = [found[i] for i in good]
    if P.size == 0:
        hmin = _section_minimum(body, plane, value, M, bounds)
        raise ValueError(
            f"energy level h = {h:.10g} meets the section {_label(plane, value, M)} only "
            f"where no orbit can start: none of {max_points} plane points tried in the "
            f"accessible box has a root {plane.symbols[3]} off the chart's singular set (a "
            "degenerate level: H is within a hair of its minimum on the section, about "
            f"{hmin:.10g}, and the accessible region shrinks to a point or to the singular "
            "set); raise h")
    rows: list[tuple[int, float, int, int]] = []
    for i, r in enumerate(roots):
        pick = {"all": r, "smallest": r[:1], "largest": r[-1:]}[root]
        for A in pick:
            rows.append((i, float(A), int(np.searchsorted(r, A)), r.size))
    if not rows:
        raise _no_intersection(body, plane, value, M, h, bounds,
                               "no sampled point of the plane has an admissible root; "
                               "raise n")
    point = np.array([r[0] for r in rows], dtype=np.intp)
    action = np.array([r[1] for r in rows])
    x = np.stack([P[point], np.full(point.size, value), Q[point], action,
                  np.full(point.size, M)], axis=-1)
    y = from_andoyer(x) if plane.chart == "andoyer" else from_hess(body, x)
    scale = max(abs(h), body.mu)
    residual = np.abs(energy(body, y) - h) / scale
    if np.any(residual > tol):
        raise ValueError(f"the energy residual |H(y0) - h| / max(|h|, mu) reaches "
                         f"{residual.max():.3g} on {int(np.sum(residual > tol))} states, "
                         f"above tol = {tol:g}: the roots of the action are found to about "
                         "1e-15 relative, less near a tangency of the level (a fold of the "
                         "accessible region); raise tol")
    rate = vector_field(body, x, plane.chart)[:, 1]
    lines = polylines(xs, ys, F)

    data: dict[str, Any] = {name: (("orbit",), y[:, k]) for k, name in enumerate(STATE)}
    data["y0"] = (("orbit", "component"), y)
    for k, name in enumerate(plane.storage):
        data[name] = (("orbit",), x[:, k])
    data.update(
        residual=(("orbit",), residual),
        root_index=(("orbit",), np.array([r[2] for r in rows])),
        n_roots=(("orbit",), np.array([r[3] for r in rows])),
        point=(("orbit",), point),
        section_rate=(("orbit",), rate),
        accessible=(("plane_x", "plane_y"), acc),
        H_min=(("plane_x", "plane_y"), F + h),
        boundary_x=(("boundary_vertex",), lines[:, 0]),
        boundary_y=(("boundary_vertex",), lines[:, 1]),
    )
    s = plane.symbols
    attrs = provenance(
        body, h=h, M=M, section_coord=plane.coord, section_value=value,
        section_chart=plane.chart, sampling=sampling, n_requested=int(n), seed=int(seed),
        root=root, plane_x=plane.storage[0], plane_y=plane.storage[2],
        action=plane.storage[3], action_max=act_max,
        plane_x_min=x0, plane_x_max=x1, plane_y_min=y0, plane_y_max=y1,
        equations=plane.equations, residual_tol=tol,
        units="dimensionless: moments of inertia, mu, energies and actions in the "
              "body's units; angles in rad")
    ds = xr.Dataset(
        data,
        coords={"orbit": np.arange(point.size), "component": list(STATE),
                "plane_x": ("plane_x", xs, {"name": plane.storage[0], "symbol": s[0]}),
                "plane_y": ("plane_y", ys, {"name": plane.storage[2], "symbol": s[2]})},
        attrs=attrs)
    describe_variables(ds, units=False)
    ds.residual.attrs.update(long_name="|H(y0) - h| / max(|h|, mu)", units="1")
    ds.section_rate.attrs.update(long_name=f"d{s[1]}/dt at the initial state")
    ds.accessible.attrs.update(long_name=f"some {s[3]} puts ({s[0]}, {s[2]}) on H = h")
    ds.H_min.attrs.update(long_name=f"minimum of H over the admissible {s[3]}")
    ds.boundary_x.attrs.update(long_name=f"{s[0]} on the accessible boundary (NaN: new line)")
    ds.boundary_y.attrs.update(long_name=f"{s[2]} on the accessible boundary (NaN: new line)")
    return ds
