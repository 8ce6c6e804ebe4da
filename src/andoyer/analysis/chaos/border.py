r"""Where chaos begins: the chaotic fraction of a section and the width of the layer
around the former Hess separatrix.

An orbit is called chaotic when its MEGNO :math:`\langle Y\rangle(t)` at ``t_end``
exceeds a threshold chosen from *regular reference orbits*: the same grid of the same
section plane, on the same level, for the top with the same moments and ``mu = 0``
(Euler-Poinsot, integrable: every orbit is regular). On a torus
:math:`\langle Y\rangle \to 2` (0 on a stable periodic orbit), and at a finite ``t_end``
the reference values spread a little above and below 2 (the largest is
``reference_max``, 2.0-2.1 at ``t_end = 300`` on the bodies of the tests); a chaotic
orbit with Lyapunov exponent :math:`\lambda` has
:math:`\langle Y\rangle \approx \lambda t / 2` [1]_. The threshold is
``reference_max + margin`` (``margin`` = 1 by default: a Lyapunov time shorter than
about ``t_end / 2`` above the regular spread). Its sensitivity is reported: the fraction
at ``threshold -+ margin / 2``.

The *chaotic layer* around the former Hess separatrix in the plane ``(theta1, J1)`` of
``theta2 = const`` (at ``M = 0``, ``theta1`` in ``[0, 2 pi)``): the line ``theta1 = 0``
of a Hess body, ``theta1 = 2 epsilon`` of a body turned by ``epsilon``
(:func:`hess_line`); in each row of constant ``J1`` the run of chaotic cells that
contains the line; its width in radians, and the median over the rows of the middle half
of the accessible ``J1`` range (away from the rotations ``P+-`` at ``J1 = 0, J2``, where
the layers of the two separatrix branches meet).

What it shows (measured on the body ``A, B, C = 2.5, 1, 1.6``, ``rho = 1.08``,
``mu = 0.05``, 96 x 48 cells, ``t_end = 300``): on a Hess body the line ``theta1 = 0``
is a regular invariant surface (the manifolds coincide), yet it lies inside a chaotic
layer about 0.3 rad wide, as wide as the layer of the splitting branch
``theta1 = 4 phi0``: orbits beside it pass by the saddles ``P+-`` and leave along the
split branch. Turning the centre of mass by ``epsilon = 0.3`` moves the layer with the
line (to ``theta1 = 2 epsilon``) and keeps its width (0.29 and 0.33 rad); the chaotic
fraction of the plane is set by ``mu`` (0.05-0.07 at ``mu = 0.01``, about 0.3 at
``mu = 0.05``) and changes little with ``epsilon``.

A cell of the grid is ``2 pi / nx`` wide: a layer thinner than the cells shows as
the two cells beside the line (orbits near a hyperbolic set keep a large MEGNO for long
times), so resolve it with ``nx`` and ``t_end`` before reading its width. On a Hess
body that separatrix carries the Hess solutions and does not split; a centre of mass
turned by ``epsilon`` (:meth:`andoyer.body.RigidBody.near_hess`) splits it to first order
(:func:`andoyer.analysis.splitting.melnikov.melnikov_off_hess`).

References
----------
.. [1] P. M. Cincotta, C. M. Giordano and C. Simo, "Phase space structure of
   multi-dimensional systems by means of the mean exponential growth factor of nearby
   orbits", Physica D 182, 151-178 (2003).
"""

from __future__ import annotations

import math
from functools import lru_cache
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from andoyer.analysis.chaos.lyapunov import IndicatorRun, MapGrid, chaos_map
from andoyer.body import RigidBody, checks_body
from andoyer.integrate import Section
from andoyer.integrate.engines import resolve_engine
from andoyer.integrate.engines.base import Capability
from andoyer.integrate.results import describe_variables
from andoyer.validation import checks_arguments, finite, finite_array, flag, grid, integer, positive

__all__ = ["chaos_border", "chaos_border_map", "regular_reference", "layer_width", "hess_line",
           "MARGIN"]

#: Default margin of the threshold above the regular reference's largest <Y>.
MARGIN = 1.0


def _section(section: Any) -> Section:
    if isinstance(section, Section):
        sec = section
    elif isinstance(section, str):
        sec = Section.parse(section)
    elif isinstance(section, tuple | list) and len(section) == 2 \
            and isinstance(section[0], str):
        sec = Section(section[0], finite("section value", section[1]))
    else:
        raise ValueError(f"section must be ('theta2', value), ('g', value), a string such "
                         f"as 'theta2=0' or a Section, got {section!r}")
    if sec.coord not in ("theta2", "g"):
        raise ValueError(f"section must be theta2 = const or g = const, got {sec.coord!r}")
    return sec


@lru_cache(maxsize=32)
def _reference(A: float, B: float, C: float, h: float, M: float, coord: str, value: float,
               n: tuple[int, int], t_end: float, engine: str | None, tol: float,
               n_threads: int | None) -> float:
    free = RigidBody(A, B, C, 0.0, (1.0, 0.0, 0.0), "Euler-Poinsot reference")
    ds = chaos_map(free, h, M, (coord, value), MapGrid(n),
                   IndicatorRun("megno", t_end=t_end, tol=tol),
                   engine=resolve_engine(engine, Capability.TANGENT, n_threads=n_threads),
                   progress=False)
    Y = ds.megno.values
    if not np.any(np.isfinite(Y)):
        raise ValueError(f"the level h = {h:g}, M = {M:g} of the free top does not meet the "
                         f"plane {coord} = {value:g}: no regular reference")
    return float(np.nanmax(Y))


@checks_body(ranges={"h": "energy", "M": "action", "t_end": "time", "tol": "tolerance"})
def regular_reference(body: RigidBody, h: float, M: float = 0.0,
                      section: Any = ("theta2", 0.0), *, n: int | tuple[int, int] = 24,
                      t_end: float = 300.0, engine: str | None = None,
                      tol: float = 1e-12, n_threads: int | None = None) -> float:
    """The largest MEGNO ``<Y>(t_end)`` over the grid for the free top (``mu = 0``) of
    the same moments: every orbit regular. Cached per process (one value serves every
    ``mu``, ``epsilon`` of a sweep).

    Parameters
    ----------
    body : RigidBody
        The body whose moments (and section plane) are used; its ``mu`` is set to 0.
    h, M : float
        The level ``H = h`` (Eq. (1)) and the area constant ``(G, gamma) = M``.
    section : (coord, value) or str, default ("theta2", 0.0)
        The section plane, as in :func:`chaos_border`.
    n : int or (nx, ny), default 24
        Grid of the plane (:func:`andoyer.analysis.chaos.lyapunov.chaos_map`).
    t_end : float, default 300.0
        Integration time of every orbit (body time units).
    engine : str, optional
        Engine of the variational equations, as in
        :func:`~andoyer.analysis.chaos.lyapunov.chaos_map` (default heyoka where
        installed, else taylor).
    tol : float, default 1e-12
        Integration tolerance.
    n_threads : int, optional
        Threads of the numba engine (default: all cores).

    Examples
    --------
    >>> ref = regular_reference(RigidBody.hess(3.0, 1.0, 2.0, mu=1.0), 1.0, n=8, t_end=100.0)
    >>> bool(1.5 < ref < 2.5)
    True
    """
    sec = _section(section)
    nn = grid("n", n)
    if n_threads is not None:
        n_threads = integer("n_threads", n_threads, 1)
    if engine is not None and not isinstance(engine, str):
        raise ValueError(f"engine must be an engine's name or None, got {engine!r}")
    return _reference(body.A, body.B, body.C, finite("h", h), finite("M", M), sec.coord,
                      float(sec.value), nn, positive("t_end", t_end), engine,
                      positive("tol", tol), n_threads)


@checks_arguments(ranges={"theta1": "angle"})
def layer_width(chaotic: NDArray[np.bool_], accessible: NDArray[np.bool_],
                theta1: NDArray[np.float64], line: float = 0.0
                ) -> tuple[NDArray[np.float64], float]:
    """Width (rad) of the chaotic run through the line ``theta1 = line`` in each row, and
    its median over the rows that meet the level.

    ``chaotic``, ``accessible``: shape ``(ny, nx)`` over rows of ``J1`` and columns of
    ``theta1`` (cell centres over ``[0, 2 pi)``, increasing). The cells on either side of
    the line (mod ``2 pi``) border it.

    Parameters
    ----------
    chaotic : ndarray of bool, shape (ny, nx)
        Cells whose indicator exceeds the threshold (rows: ``J1``; columns: ``theta1``).
    accessible : ndarray of bool, shape (ny, nx)
        Cells on the energy level (a row without any is left out of the median).
    theta1 : ndarray of float, shape (nx,)
        Cell centres in ``theta1`` (rad), increasing over ``[0, 2 pi)``.
    line : float, default 0.0
        ``theta1`` of the line (rad; e.g. :func:`hess_line`), taken mod ``2 pi``.

    Examples
    --------
    >>> c = np.array([[1, 1, 0, 0, 0, 1], [0, 0, 0, 0, 0, 0]], dtype=bool)
    >>> th = (np.arange(6) + 0.5) * 2 * np.pi / 6
    >>> w, med = layer_width(c, np.ones_like(c), th)
    >>> np.round(w / (2 * np.pi / 6), 6).tolist(), round(med / (2 * np.pi / 6), 6)
    ([3.0, 0.0], 1.5)
    """
    chaotic = np.asarray(chaotic)
    accessible = np.asarray(accessible)
    if chaotic.dtype.kind != "b" or chaotic.ndim != 2:
        raise ValueError(f"chaotic must be a 2-D boolean array (rows of the plane), got "
                         f"{chaotic.dtype} of shape {chaotic.shape}")
    if accessible.dtype.kind != "b" or accessible.shape != chaotic.shape:
        raise ValueError(f"accessible must be a boolean array of the shape of chaotic "
                         f"{chaotic.shape}, got {accessible.dtype} of shape {accessible.shape}")
    ny, nx = chaotic.shape
    theta1 = finite_array("theta1", theta1, ndim=1)
    if theta1.size != nx:
        raise ValueError(f"theta1 must hold one angle per column ({nx}), got {theta1.size}")
    line = finite("line", line)
    dx = float(theta1[1] - theta1[0]) if nx > 1 else 2.0 * math.pi
    order = np.argsort(np.mod(np.asarray(theta1) - line, 2.0 * math.pi), kind="stable")
    chaotic, accessible = chaotic[:, order], accessible[:, order]
    widths = np.full(ny, np.nan)
    for j in range(ny):
        if not accessible[j].any():
            continue
        row = chaotic[j] & accessible[j]
        if row.all():
            widths[j] = nx * dx
            continue
        right = int(np.argmin(row)) if row[0] else 0           # run from theta1 = 0+
        left = int(np.argmin(row[::-1])) if row[-1] else 0     # run from 2 pi-
        widths[j] = (right + left) * dx
    rows = widths[np.isfinite(widths)]
    return widths, float(np.median(rows)) if rows.size else math.nan


@checks_body
def hess_line(body: RigidBody) -> float:
    """``theta1`` of the former Hess separatrix in ``body``'s Hess chart, in ``[0, 2 pi)``.

    The unperturbed separatrix ``l = -phi0_H`` is fixed by the moments
    (:meth:`~andoyer.body.RigidBody.nearest_hess`); the chart measures
    ``theta1 = 2 (l + phi0)`` with the body's own ``phi0``, so the line sits at
    ``2 (phi0 - phi0_H) = 2 epsilon`` (:attr:`~andoyer.body.RigidBody.hess_epsilon`).
    NaN when the moments admit no Hess body (``A > C > B`` fails) or ``e3 != 0``.

    Parameters
    ----------
    body : RigidBody
        A body with its centre of mass in the (e1, e2) plane (``e3 = 0``) and
        ``A > C > B``, e.g. :meth:`~andoyer.body.RigidBody.near_hess`.

    Examples
    --------
    >>> round(hess_line(RigidBody.near_hess(3.0, 1.0, 2.0, mu=0.1, epsilon=0.05)), 12)
    0.1
    """
    try:
        eps = body.hess_epsilon
    except ValueError:
        return math.nan
    return float(np.mod(2.0 * eps, math.tau))


@checks_body(ranges={"h": "energy", "M": "action", "t_end": "time", "tol": "tolerance"})
def chaos_border(body: RigidBody, h: float, M: float = 0.0,
                 section: Any = ("theta2", 0.0), *, n: int | tuple[int, int] = 24,
                 t_end: float = 300.0, margin: float = MARGIN, engine: str | None = None,
                 tol: float = 1e-12, n_threads: int | None = None,
                 progress: bool | None = None) -> xr.Dataset:
    """The chaotic fraction of a section plane and the chaotic layer around ``theta1 = 0``.

    Parameters
    ----------
    body : RigidBody
        Any body whose plane exists (the Hess plane needs ``e3 = 0``), e.g.
        :meth:`~andoyer.body.RigidBody.near_hess`.
    h, M : float
        The level ``H = h``, ``(G, gamma) = M``.
    section : (coord, value) or str
        ``theta2 = const`` (plane ``(theta1, J1)``, the layer width is measured) or
        ``g = const`` (plane ``(l, L)``; no layer width).
    n : int or (nx, ny)
        Grid of the plane (:func:`andoyer.analysis.chaos.lyapunov.chaos_map`).
    t_end : float
        Integration time of every orbit.
    margin : float
        Threshold above the regular reference (see the module notes).
    engine, tol, n_threads, progress :
        As in :func:`~andoyer.analysis.chaos.lyapunov.chaos_map`.

    Returns
    -------
    xarray.Dataset
        The MEGNO map (``megno``, ``accessible``, ``chaotic``) and the values
        ``chaotic_fraction`` (of the accessible cells), ``chaotic_fraction_low`` and
        ``_high`` (threshold ``-+ margin/2``), ``threshold``, ``reference_max``,
        ``layer_width`` (median over the middle half of the ``J1`` range, rad; NaN for
        ``g`` sections), ``layer_width_row`` (per row), ``hess_line``,
        ``n_accessible``.

    Examples
    --------
    >>> ds = chaos_border(RigidBody.hess(3.0, 1.0, 2.0, mu=1.0), 1.0, n=8, t_end=100.0)
    >>> bool(0.1 < float(ds.chaotic_fraction) < 0.9)
    True
    """
    sec = _section(section)
    h, M = finite("h", h), finite("M", M)
    positive("margin", margin)
    flag("progress", progress)
    ref = regular_reference(body, h, M, sec, n=n, t_end=t_end, engine=engine, tol=tol,
                            n_threads=n_threads)
    ds = chaos_map(body, float(h), float(M), (sec.coord, sec.value), MapGrid(n),
                   IndicatorRun("megno", t_end=t_end, tol=tol),
                   engine=resolve_engine(engine, Capability.TANGENT, n_threads=n_threads),
                   progress=progress)
    Y = ds.megno.values
    acc = ds.accessible.values.astype(bool) & np.isfinite(Y)
    n_acc = int(acc.sum())
    threshold = ref + float(margin)

    def fraction(th: float) -> float:
        return float(np.sum(acc & (Y > th)) / n_acc) if n_acc else math.nan

    chaotic = acc & (Y > threshold)
    out = ds[["megno", "accessible"]].copy()
    out["chaotic"] = (ds.megno.dims, chaotic)
    out["chaotic_fraction"] = ((), fraction(threshold))
    out["chaotic_fraction_low"] = ((), fraction(threshold - 0.5 * margin))
    out["chaotic_fraction_high"] = ((), fraction(threshold + 0.5 * margin))
    out["threshold"] = ((), threshold)
    out["reference_max"] = ((), ref)
    out["n_accessible"] = ((), n_acc)
    line = hess_line(body) if sec.coord == "theta2" else math.nan
    out["hess_line"] = ((), line)
    if math.isfinite(line):
        x = ds[ds.megno.dims[1]].values
        widths, _ = layer_width(chaotic, acc, np.asarray(x, dtype=float), line)
        # Rows of the middle half of the accessible J1 range: away from the rotations
        # P+- (J1 = 0, J2), where the layers of both separatrix branches meet.
        J1 = np.asarray(ds[ds.megno.dims[0]].values, dtype=float)
        rows = acc.any(axis=1)
        lo, hi = (float(J1[rows].min()), float(J1[rows].max())) if rows.any() else (0, 0)
        mid = rows & (np.abs(J1 - 0.5 * (lo + hi)) <= 0.25 * (hi - lo))
        out["layer_width_row"] = ((ds.megno.dims[0],), widths)
        out["layer_width"] = ((), float(np.median(widths[mid])) if mid.any() else math.nan)
    else:
        out["layer_width"] = ((), math.nan)
    out.attrs.update(ds.attrs)
    out.attrs.update(margin=float(margin), rule="chaotic where MEGNO <Y>(t_end) > "
                     "reference_max + margin; reference: the free top (mu = 0) on the "
                     "same grid and level")
    return describe_variables(out, {
        "chaotic": ("", "MEGNO above the threshold", "1", ""),
        "chaotic_fraction": ("f_c", "fraction of the accessible cells that are chaotic",
                             "1", ""),
        "chaotic_fraction_low": ("", "chaotic fraction at threshold - margin/2", "1", ""),
        "chaotic_fraction_high": ("", "chaotic fraction at threshold + margin/2", "1", ""),
        "threshold": ("Y^*", "MEGNO threshold of chaos", "1", ""),
        "reference_max": ("", "largest MEGNO of the regular reference (mu = 0)", "1", ""),
        "n_accessible": ("", "cells where the level meets the plane", "1", ""),
        "hess_line": ("\\theta_1^H", "theta1 of the former Hess separatrix", "rad", "(14)"),
        "layer_width": ("w", "median width of the chaotic run through the former Hess "
                        "separatrix", "rad", "(14)"),
        "layer_width_row": ("", "width of the chaotic run through the former Hess "
                            "separatrix, per row", "rad", "(14)")})


@checks_body(ranges={"mu": "scale", "epsilon": "finite", "h": "energy", "M": "action", "t_end":
             "time", "tol": "tolerance"})
def chaos_border_map(body: RigidBody, mu: ArrayLike, epsilon: ArrayLike, h: float, M: float = 0.0,
                     section: Any = ("theta2", 0.0), *, n: int | tuple[int, int] = 24,
                     t_end: float = 300.0, margin: float = MARGIN,
                     engine: str | None = None, tol: float = 1e-12,
                     progress: bool | None = None) -> xr.Dataset:
    """:func:`chaos_border` over a grid of ``(mu, epsilon)``, in this process: the border
    of chaos at a modest resolution (a scan with the ``chaos_border`` task computes the
    same on Dask, streamed to Zarr).

    Parameters
    ----------
    body : RigidBody
        Gives the moments and the branch of the Hess direction (its ``mu`` and turn are
        replaced: each point is :meth:`~andoyer.body.RigidBody.near_hess`).
    mu, epsilon : sequence of float
        The grid.
    h, M, section, n, t_end, margin, engine, tol :
        As in :func:`chaos_border`.
    progress : bool, optional
        A progress bar over the points.

    Returns
    -------
    xarray.Dataset
        Dims ``(mu, epsilon)``: ``chaotic_fraction``, ``chaotic_fraction_low``,
        ``chaotic_fraction_high``, ``layer_width``, ``threshold``, ``hess_line``,
        ``n_accessible``.

    Examples
    --------
    >>> ds = chaos_border_map(RigidBody.hess(2.5, 1.0, 1.6), [0.01, 0.05], [0.0, 0.3],
    ...                       0.3125, n=8, t_end=60.0)
    >>> ds.chaotic_fraction.dims, bool(ds.chaotic_fraction.max() < 1)
    (('mu', 'epsilon'), True)
    """
    from andoyer.progress import Progress

    hess = body.nearest_hess()
    sign = 1 if hess.e2 >= 0.0 else -1
    mus = np.atleast_1d(finite_array("mu", mu))
    eps = np.atleast_1d(finite_array("epsilon", epsilon))
    for name, arr in (("mu", mus), ("epsilon", eps)):
        if arr.ndim != 1 or not arr.size:
            raise ValueError(f"{name} must be a non-empty 1-D list of values, got shape "
                             f"{arr.shape}")
    h, M = finite("h", h), finite("M", M)
    _section(section)
    grid("n", n)
    positive("t_end", t_end)
    positive("margin", margin)
    flag("progress", progress)
    names = ("chaotic_fraction", "chaotic_fraction_low", "chaotic_fraction_high",
             "layer_width", "threshold", "hess_line", "n_accessible")
    grids = {k: np.full((mus.size, eps.size), np.nan) for k in names}
    first: xr.Dataset | None = None
    bar = Progress(mus.size * eps.size, "border of chaos", progress)
    for i, m in enumerate(mus):
        for j, e in enumerate(eps):
            b = RigidBody.near_hess(hess.A, hess.B, hess.C, float(m), float(e), branch=sign,
                                    name=hess.name)
            ds = chaos_border(b, h, M, section, n=n, t_end=t_end, margin=margin,
                              engine=engine, tol=tol, progress=False)
            first = ds if first is None else first
            for k in names:
                grids[k][i, j] = float(ds[k])
            bar.update(1)
    bar.close()
    assert first is not None
    out = xr.Dataset({k: (("mu", "epsilon"), v) for k, v in grids.items()},
                     coords={"mu": mus, "epsilon": eps})
    out.attrs.update(first.attrs)
    out.attrs.update(body_mu="see the mu coordinate", h_level=float(h), M_level=float(M),
                     **{f"body_{k}": "turned by epsilon (see the epsilon coordinate)"
                        for k in ("e1", "e2", "is_hess")})
    for k in names:
        out[k].attrs.update(first[k].attrs)
    out.mu.attrs.update(symbol="\\mu", long_name="weight x distance of the centre of mass",
                        units="1", equation="(1)")
    out.epsilon.attrs.update(symbol="\\epsilon", long_name="turn of the centre of mass off "
                             "the Hess direction", units="rad", equation="(2)")
    return out
