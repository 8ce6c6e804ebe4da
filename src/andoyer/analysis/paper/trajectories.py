"""Data of the paper's Fig. 3: trajectories of (16) projected on (theta1, J1), and a section.

The paper's Fig. 3 shows, for the Hess body A = 2.5, B = 2.0, C = 2.2 and mu = 0.01,
projections of trajectories of the full M = 0 system (16) on the plane (theta1, J1), with
a region near the separatrix (framed by a dot-dash line) enlarged. Here the trajectories
are integrated in the regular Euler-Poisson variables (1) and read in the Hess chart
(14); the same phase space is also shown as a Poincare section theta2 = const, which
separates the regular curves from the chaotic layer that the projection smears.

Examples
--------
>>> from andoyer import RigidBody
>>> ds = fig3_trajectories(RigidBody.paper(), J1=[0.2], t_end=20.0, dt=1.0, engine="scipy")
>>> ds.theta1.dims, bool(ds.theta1.max() < 2 * 3.1416)
(('orbit', 'time'), True)
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import xarray as xr

from andoyer.analysis.unperturbed.separatrix import separatrix_energy as separatrix_energy
from andoyer.body import RigidBody, checks_body
from andoyer.integrate import budget
from andoyer.integrate.api import poincare, propagate
from andoyer.integrate.fill import fill_section
from andoyer.integrate.results import values_from_attrs
from andoyer.validation import MAX_ACTION, integer, positive, real_array

__all__ = ["fig3_trajectories", "fig3_section", "separatrix_energy", "zoom_box", "DEFAULT_J1"]

#: Default seeds J1/J2 on the lines theta1 = 2 phi0 and 2 phi0 + pi (the two centres).
DEFAULT_J1: tuple[float, ...] = (0.004, 0.012, 0.03, 0.07, 0.13, 0.2, 0.3, 0.42)


@checks_body(ranges={"J2": "action"})
def zoom_box(body: RigidBody, J2: float = 1.0
             ) -> tuple[tuple[float, float], tuple[float, float]]:
    """The enlarged region of Fig. 3: a box around the saddle (theta1, J1) = (4 phi0, 0).

    Returns ``((theta1_min, theta1_max), (J1_min, J1_max))``.

    Parameters
    ----------
    body : RigidBody
        A Hess body (``phi0``).
    J2 : float, default 1.0
        ``J2 = |G|`` of the level: the box scales with it.
    """
    t = 4.0 * body.phi0
    J2 = positive("J2", J2, maximum=MAX_ACTION)
    return (t - 0.3, t + 0.3), (0.0, 0.06 * J2)


def _check_body(body: RigidBody) -> None:
    """The Hess chart of Fig. 3 (the callers' ``@checks_body`` checked the type)."""
    body.require_planar("Fig. 3 (the Hess chart)")


@checks_body(ranges={"J2": "action", "theta2": "angle", "t_end": "time", "rtol": "tolerance",
             "atol": "tolerance"})
def fig3_trajectories(body: RigidBody, *, J2: float = 1.0,
                      J1: Sequence[float] = DEFAULT_J1, theta2: float = 0.0,
                      t_end: float = 400.0, dt: float = 0.1, engine: str | None = None,
                      rtol: float = 1e-12, atol: float = 1e-12,
                      progress: bool | None = False) -> xr.Dataset:
    """Trajectories of the M = 0 system (16), projected on (theta1, J1) as in Fig. 3.

    Orbits start at ``theta2``, ``J2`` and ``M = 0``, on the lines through the two centres
    of the unperturbed system, ``theta1 = 2 phi0`` and ``theta1 = 2 phi0 + pi``, with
    ``J1 = J2 * J1[k]``; they are integrated in Euler-Poisson variables (1) and read in
    the Hess chart (14).

    Parameters
    ----------
    body : RigidBody
        A body with ``e3 = 0`` (the Hess chart needs phi0).
    J2 : float
        The initial modulus of the angular momentum, ``G = J2``.
    J1 : sequence of float
        Seeds ``J1 / J2`` in ``(0, 1/2]``.
    theta2 : float
        Initial theta2.
    t_end, dt : float
        Length of each trajectory and output step.
    engine, rtol, atol, progress
        See :func:`andoyer.integrate.propagate`.

    Returns
    -------
    xarray.Dataset
        Dims ``(orbit, time)``: ``theta1`` (mod 2 pi: H is 2 pi-periodic in theta1 at
        M = 0), ``J1``, ``J2``, ``theta2``, ``H``; dim ``orbit``: ``centre`` (which line
        the orbit starts on) and ``seed`` (J1/J2); attrs: provenance and the figure's
        caption data.
    """
    _check_body(body)
    seeds = real_array("J1", J1).ravel()
    if seeds.size == 0 or np.any(~np.isfinite(seeds)) or np.any(seeds <= 0) \
            or np.any(seeds > 0.5):
        raise ValueError(f"J1 seeds must be fractions of J2 in (0, 1/2], got {list(seeds)}")
    if not (np.isfinite(J2) and J2 > 0):
        raise ValueError(f"J2 must be positive, got {J2!r}")
    if not (np.isfinite(t_end) and np.isfinite(dt) and 0 < dt < t_end):
        raise ValueError(f"need 0 < dt < t_end, got dt = {dt!r}, t_end = {t_end!r}")
    centres = (2.0 * body.phi0, 2.0 * body.phi0 + np.pi)
    x0 = np.array([[c, theta2, s * J2, J2, 0.0] for c in centres for s in seeds])
    budget.check(f"fig3_trajectories t_end/dt = {t_end / dt:.3g} output times",
                 memory=budget.DATASET_BYTES * x0.shape[0] * (t_end / dt + 1.0))
    t = np.arange(0.0, t_end + 0.5 * dt, dt)
    ds = propagate(body, x0, t, chart="hess", engine=engine, rtol=rtol, atol=atol,
                   progress=progress)
    out = xr.Dataset(
        {"theta1": np.mod(ds.theta1, 2.0 * np.pi), "J1": ds.J1, "J2": ds.J2,
         "theta2": ds.theta2, "H": ds.H,
         "centre": ("orbit", np.repeat(centres, seeds.size)),
         "seed": ("orbit", np.tile(seeds, 2))},
        coords={"orbit": ds.orbit, "time": ds.time}, attrs=dict(ds.attrs))
    out.theta1.attrs.update(ds.theta1.attrs, long_name="theta1 mod 2 pi", units="rad")
    out.centre.attrs.update(long_name="theta1 of the starting line (a centre of H0)",
                            units="rad")
    out.seed.attrs.update(long_name="initial J1 / J2", units="1")
    (x0_, x1_), (y0_, y1_) = zoom_box(body, J2)
    out.attrs.update(figure="Fig. 3", equations="(14), (16)", J2=J2, M=0.0,
                     H_max_drift=float(abs(ds.H_drift).max()),
                     zoom_theta1_min=x0_, zoom_theta1_max=x1_, zoom_J1_min=y0_,
                     zoom_J1_max=y1_, phi0=body.phi0)
    return values_from_attrs(out, {"H_max_drift": (
        "", "largest relative energy drift over the trajectories", "1", "(16)")})


@checks_body(ranges={"J2": "action", "h": "energy", "theta2": "angle", "n_orbits": "count",
             "n_crossings": "count", "rtol": "tolerance", "atol": "tolerance"})
def fig3_section(body: RigidBody, *, J2: float = 1.0, h: float | None = None,
                 theta2: float = 0.0, n_orbits: int = 40, n_zoom: int = 12,
                 n_crossings: int = 300,
                 engine: str | None = None, rtol: float = 1e-12, atol: float = 1e-12,
                 progress: bool | None = False) -> tuple[xr.Dataset, xr.Dataset]:
    """The Poincare section theta2 = const of the M = 0 system at the separatrix energy.

    Parameters
    ----------
    body : RigidBody
    J2 : float
        Sets the default energy ``h = c J2^2 / 2`` (:func:`separatrix_energy`).
    h : float, optional
        Energy level (overrides ``J2``).
    theta2 : float
        The section theta2 = const.
    n_orbits, n_zoom, n_crossings : int
        About ``n_orbits`` initial states filling the accessible plane and ``n_zoom``
        more in the enlarged box :func:`zoom_box` near the saddle (4 phi0, 0), where the
        chaotic layer of the separatrix lies; each followed for ``n_crossings`` crossings.
    engine : str, optional
        Integration engine (:func:`andoyer.integrate.poincare`; default taylor, measured
        faster on angle sections: :data:`~andoyer.integrate.engines.MEASURED_DEFAULTS`).
    rtol, atol : float, default 1e-12
        Relative and absolute tolerances.
    progress : bool, optional, default False
        A progress bar of the integration.

    Returns
    -------
    (section, fill) : tuple of xarray.Dataset
        :func:`andoyer.integrate.poincare` and :func:`andoyer.integrate.fill_section`
        datasets (the latter holds the accessible region's boundary).
    """
    _check_body(body)
    J2 = positive("J2", J2, maximum=MAX_ACTION)  # the level's G (checked under its name)
    level = separatrix_energy(body, J2) if h is None else float(h)
    n_orbits = integer("n_orbits", n_orbits, 1)
    n_zoom = integer("n_zoom", n_zoom, 0)
    fill = fill_section(body, level, 0.0, ("theta2", theta2), n_orbits=n_orbits)
    y0 = fill["y0"].values
    if n_zoom > 0:
        box = zoom_box(body, J2)
        near = fill_section(body, level, 0.0, ("theta2", theta2), n_orbits=n_zoom,
                            plane_bounds=box, root="smallest")
        y0 = np.concatenate([y0, near["y0"].values])
    sec = poincare(body, y0, f"theta2={theta2}", n_crossings, engine=engine,
                   rtol=rtol, atol=atol, progress=progress)
    sec.attrs.update(h=level, M=0.0, figure="Fig. 3 (section)", equations="(14), (16)")
    return sec, fill
