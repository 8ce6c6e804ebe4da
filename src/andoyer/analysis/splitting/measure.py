"""Splitting of the separatrices: the distance between the unstable and stable manifolds
of :mod:`andoyer.analysis.splitting.manifolds` on the section, the splitting angle and lobe areas,
and the driver that measures them over mu against the Melnikov prediction of
:mod:`andoyer.analysis.splitting.melnikov`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from andoyer.analysis.splitting.manifolds import (
    ManifoldCurve,
    branch_of,
    euler_poinsot_excess,
    grow_manifold,
)
from andoyer.analysis.splitting.periodic import (
    DEFAULT_TOL,
    RotationSection,
    continue_rotation_orbit,
)
from andoyer.analysis.splitting.problem import splitting_problem
from andoyer.analysis.splitting.section_map import FLOW_ENGINES
from andoyer.analysis.unperturbed.separatrix import BRANCHES, DEFAULT_BRANCH, separatrix_energy
from andoyer.body import RigidBody, checks_body
from andoyer.charts.euler_poisson import STATE
from andoyer.integrate.engines import EngineLike
from andoyer.integrate.results import provenance, values_from_attrs
from andoyer.validation import (
    MAX_ACTION,
    checks_arguments,
    choice,
    finite_array,
    flag,
    integer,
    positive,
)

__all__ = ["measure_splitting", "separatrix_splitting", "splitting_at", "splitting_vs_epsilon"]


# ----------------------------------------------------------------------------- splitting
@checks_arguments(ranges={"g": "angle"})
def splitting_at(wu: ManifoldCurve, ws: ManifoldCurve, g: float) -> dict[str, Any]:
    """Fresh points of both manifolds on the line ``g = const`` of ``Sigma_0``.

    Returns a dict with ``Delta_G = G^u - G^s``, ``Delta_E = E^u - E^s``, the states
    ``y_u``, ``y_s`` and their phases.

    Parameters
    ----------
    wu, ws : ManifoldCurve
        The unstable and the stable manifold traced on ``Sigma_0``
        (:func:`~andoyer.analysis.splitting.manifolds.grow_manifold`).
    g : float
        Phase ``g`` (rad) of the line on ``Sigma_0`` where they are compared.
    """
    cu = wu.point_at_phase(g)
    cs = ws.point_at_phase(g)
    body = wu.branch.body
    Gu, Gs = float(np.linalg.norm(cu.y[:3])), float(np.linalg.norm(cs.y[:3]))
    return {"Delta_G": Gu - Gs,
            "Delta_E": float(euler_poinsot_excess(body, cu.y) - euler_poinsot_excess(body,
                                                                                     cs.y)),
            "G_u": Gu, "G_s": Gs, "y_u": cu.y, "y_s": cs.y, "t_u": cu.t, "t_s": cs.t}


def _trig_interp(values: NDArray[np.float64], g: NDArray[np.floating[Any]],
                 derivative: int = 0) -> NDArray[np.float64]:
    """Trigonometric interpolant of samples on ``2 pi k / n`` (n even), at ``g``."""
    n = values.size
    c = np.fft.rfft(values) / n
    k = np.arange(c.size)
    w = np.full(c.size, 2.0)
    w[0] = 1.0
    if n % 2 == 0:
        w[-1] = 1.0
    coef = w * c * (1j * k) ** derivative
    return np.asarray(np.real(np.exp(1j * np.outer(g, k)) @ coef))


def _shoelace(xs: NDArray[np.float64], ys: NDArray[np.float64]) -> float:
    return 0.5 * float(np.dot(xs, np.roll(ys, -1)) - np.dot(ys, np.roll(xs, -1)))


@checks_arguments(ranges={"n_phase": "count"})
def measure_splitting(wu: ManifoldCurve, ws: ManifoldCurve, *, n_phase: int = 32,
                      locate: bool | None = None, gtol: float = 1e-13,
                      noise: float = 1e-11) -> tuple[xr.Dataset, xr.Dataset]:
    """Splitting of ``W^u`` and ``W^s`` on ``Sigma_0`` as a function of the phase ``g``.

    Parameters
    ----------
    wu, ws : ManifoldCurve
        The unstable and the stable manifold of the same heteroclinic line.
    n_phase : int
        Even number of equally spaced phases ``g_k = 2 pi k / n_phase`` at which fresh
        points are computed; ``Delta G`` between them is the trigonometric interpolant
        (the splitting is analytic and periodic in ``g``).
    locate : bool, optional
        Locate the heteroclinic points (default: when ``max |Delta G| > noise``).
    gtol : float
        Tolerance in ``g`` of the located heteroclinic points.
    noise : float
        Below this ``max |Delta G|`` the manifolds are taken to coincide (>= 0).

    Returns
    -------
    splitting : xarray.Dataset
        Dim ``phase``: ``Delta_G``, ``Delta_E``, ``G_u``, ``G_s``.
    intersections : xarray.Dataset
        Dim ``intersection``: ``g`` and ``G`` of each heteroclinic point, the distance
        ``state_distance`` between the two manifolds' states there, ``Delta_G``
        (residual), ``angle`` (splitting angle in the ``(g, G)`` plane), and
        ``lobe_area`` of the lobe that starts there (signed: ``int Delta G dg``).
    """
    from scipy.optimize import brentq

    if not noise >= 0.0:  # NaN too; a negative noise ran 26 s locating nothing
        raise ValueError(f"noise must be >= 0, got {noise!r}")
    if int(n_phase) != n_phase or n_phase < 8 or n_phase % 2:
        raise ValueError(f"n_phase must be an even integer >= 8, got {n_phase!r}")
    if wu.branch.branch != ws.branch.branch or wu.branch.sheet != ws.branch.sheet:
        raise ValueError("wu and ws must follow the same heteroclinic line and sheet")
    if (wu.branch.stability, ws.branch.stability) != ("unstable", "stable"):
        raise ValueError("give the unstable manifold first, then the stable one")
    phases = math.tau * np.arange(n_phase) / n_phase
    rows = [splitting_at(wu, ws, float(g)) for g in phases]
    dG = np.array([r["Delta_G"] for r in rows])
    Gu = np.array([r["G_u"] for r in rows])
    Gs = np.array([r["G_s"] for r in rows])
    body = wu.branch.body
    split = xr.Dataset(
        {"Delta_G": (("phase",), dG),
         "Delta_E": (("phase",), [r["Delta_E"] for r in rows]),
         "G_u": (("phase",), Gu), "G_s": (("phase",), Gs)},
        coords={"phase": phases},
        attrs=provenance(body, engine=FLOW_ENGINES[wu.branch.orbit.engine],
                         branch=wu.branch.branch,
                         sheet=wu.branch.sheet, energy=wu.branch.h,
                         plane="Sigma_0 = {L = G3 = 0}, Darboux coordinates (g, G)",
                         tolerance=wu.branch.orbit.tol,
                         delta_u=wu.branch.delta, delta_s=ws.branch.delta))
    split.phase.attrs.update(symbol="g", long_name="phase: Andoyer-Deprit angle g on L = 0",
                             units="rad", equation="(5)-(6)")
    for name, sym, long in (
            ("Delta_G", "\\Delta G", "G^u - G^s on the line g = const of L = 0"),
            ("Delta_E", "\\Delta E", "E^u - E^s, E = H0 - c G^2/2"),
            ("G_u", "G^u", "G on the unstable manifold"),
            ("G_s", "G^s", "G on the stable manifold")):
        split[name].attrs.update(symbol=sym, long_name=long, units="1", equation="(12)-(13)")
    split["Delta_E"].attrs["units"] = "energy units"

    coincide = float(np.max(np.abs(dG))) <= noise
    split.attrs["max_abs_Delta_G"] = float(np.max(np.abs(dG)))
    split.attrs["manifolds_coincide"] = int(coincide)
    if locate is None:
        locate = not coincide
    rec: dict[str, list[Any]] = {k: [] for k in (
        "g", "G", "state_distance", "Delta_G", "angle", "lobe_area", "y_u", "y_s")}
    if locate:
        # Candidates: sign changes of the interpolant on a fine grid shifted off the
        # sample phases (a zero on a symmetry line would fall on a node).
        step = math.tau / (64 * n_phase)
        dense = step * (np.arange(64 * n_phase + 1) + 0.381966)
        vals = _trig_interp(dG, dense)
        idx = np.flatnonzero(np.sign(vals[:-1]) * np.sign(vals[1:]) < 0)
        zeros = []
        cache: dict[float, dict[str, Any]] = {}

        def f(g: float) -> float:
            r = splitting_at(wu, ws, g)
            cache[g] = r
            return float(r["Delta_G"])

        for i in idx:
            lo, hi = float(dense[i]), float(dense[i + 1])
            # Widen the bracket until the fresh values change sign.
            while f(lo) * f(hi) > 0.0:
                if hi - lo > math.tau / n_phase:
                    raise RuntimeError("could not bracket a heteroclinic point: the "
                                       "interpolated splitting is not accurate; raise "
                                       "n_phase")
                lo, hi = lo - (hi - lo), hi + (hi - lo)
            z = brentq(f, lo, hi, xtol=gtol, rtol=1e-15)
            zeros.append(z % math.tau)
            r = cache.get(z) or splitting_at(wu, ws, z)
            slope_s = float(_trig_interp(Gs, np.array([z]), 1)[0])
            slope_u = float(_trig_interp(Gu, np.array([z]), 1)[0])
            rec["g"].append(z % math.tau)
            rec["G"].append(0.5 * (r["G_u"] + r["G_s"]))
            rec["state_distance"].append(float(np.linalg.norm(r["y_u"] - r["y_s"])))
            rec["Delta_G"].append(r["Delta_G"])
            rec["angle"].append(math.atan(slope_u) - math.atan(slope_s))
            rec["y_u"].append(r["y_u"])
            rec["y_s"].append(r["y_s"])
        order = np.argsort(zeros)
        zs = np.asarray(zeros)[order]
        for key in rec:
            if key != "lobe_area":
                rec[key] = [rec[key][i] for i in order]
        for k, z0 in enumerate(zs):
            z1 = zs[(k + 1) % zs.size] + (math.tau if k + 1 == zs.size else 0.0)
            gg = np.linspace(z0, z1, 2049)
            upper = _trig_interp(Gu, gg)
            lower = _trig_interp(Gs, gg)
            # The lobe polygon: along W^u from z_k to z_{k+1}, back along W^s; the
            # shoelace area is signed with Delta G (counter-clockwise positive).
            poly_g = np.concatenate([gg, gg[::-1]])
            poly_G = np.concatenate([upper, lower[::-1]])
            rec["lobe_area"].append(-_shoelace(poly_g, poly_G))
    n_int = len(rec["g"])
    inter = xr.Dataset(
        {"g": (("intersection",), np.asarray(rec["g"], dtype=float)),
         "G": (("intersection",), np.asarray(rec["G"], dtype=float)),
         "state_distance": (("intersection",), np.asarray(rec["state_distance"], dtype=float)),
         "Delta_G": (("intersection",), np.asarray(rec["Delta_G"], dtype=float)),
         "angle": (("intersection",), np.asarray(rec["angle"], dtype=float)),
         "lobe_area": (("intersection",), np.asarray(rec["lobe_area"], dtype=float)),
         "y_u": (("intersection", "component"),
                 np.asarray(rec["y_u"], dtype=float).reshape(n_int, 6)),
         "y_s": (("intersection", "component"),
                 np.asarray(rec["y_s"], dtype=float).reshape(n_int, 6))},
        coords={"intersection": np.arange(n_int), "component": list(STATE)},
        attrs={**split.attrs, "gtol": gtol})
    for name, sym, long, units in (
            ("g", "g", "phase of the heteroclinic point on L = 0", "rad"),
            ("G", "G", "G of the heteroclinic point", "1"),
            ("state_distance", "|y^u - y^s|", "distance of the two manifolds' states", "1"),
            ("Delta_G", "\\Delta G", "residual G^u - G^s at the located point", "1"),
            ("angle", "\\alpha", "splitting angle atan(G^u') - atan(G^s') in (g, G)", "rad"),
            ("lobe_area", "A", "signed area int Delta G dg of the lobe from this point to "
                               "the next (shoelace)", "action units"),
            ("y_u", "y^u", "state on W^u", "1"), ("y_s", "y^s", "state on W^s", "1")):
        inter[name].attrs.update(symbol=sym, long_name=long, units=units)
    return split, inter


# ----------------------------------------------------------------------------- driver
def _mu_values(body: RigidBody, mu: Sequence[float] | ArrayLike | None
               ) -> NDArray[np.float64]:
    """The values of mu asked for, or the body's own."""
    mus = np.atleast_1d(np.asarray(body.mu, dtype=float) if mu is None
                        else finite_array("mu", mu))
    if mus.ndim != 1 or mus.size == 0 or np.any(mus <= 0):
        where = f"the body's mu = {body.mu!r}" if mu is None else f"mu = {mu!r}"
        raise ValueError(f"mu must be a non-empty list of finite values > 0 (the splitting "
                         f"vanishes at mu = 0), got {where}")
    return mus


@checks_body(ranges={"mu": "scale", "G": "length", "sheet": "sheet", "psi0": "angle", "n_phase":
             "count", "tol": "tolerance"})
def separatrix_splitting(body: RigidBody, mu: Sequence[float] | ArrayLike | None = None, *,
                         G: float = 1.0, branch: str = DEFAULT_BRANCH, sheet: int = 1,
                         psi0: float = 0.0, delta: float = 1e-5, n_phase: int = 16,
                         tol: float = DEFAULT_TOL, long_double: bool = False,
                         grow: dict[str, Any] | None = None, progress: bool | None = None,
                         engine: EngineLike = None) -> dict[str, xr.Dataset]:
    """Measure the separatrix splitting for several ``mu`` and compare it with Melnikov.

    Parameters
    ----------
    body : RigidBody
        A Hess body, or a body with the same moments whose centre of mass is turned in
        the (e1, e2) plane (:meth:`~andoyer.body.RigidBody.near_hess`). The lines and
        the Melnikov phase are those of
        :meth:`~andoyer.body.RigidBody.nearest_hess`; the prediction is
        :func:`~andoyer.analysis.splitting.melnikov.melnikov_off_hess` at ``epsilon =``
        :attr:`~andoyer.body.RigidBody.hess_epsilon` (the Hess branch ``theta1 = 0``
        splits by ``2 mu (pi rho/sinh pi rho) |sin epsilon| / (c G)``).
    mu : sequence of float, optional
        Increasing values ``mu > 0`` (default: the body's own, ``[body.mu]``).
    G : float
        The energy level is ``h = c G^2 / 2`` (the rotation about z with ``|G| = G`` at
        ``mu = 0``); the Melnikov prediction uses ``J2 = G``.
    branch, sheet :
        The heteroclinic line: ``"theta1=0"`` (default,
        :data:`~andoyer.analysis.unperturbed.separatrix.DEFAULT_BRANCH`: the Hess separatrix, which
        does not split on a Hess body and does once the centre of mass is turned) or
        ``"theta1=4phi0"`` (splits on a Hess body too).
    psi0, delta :
        Fundamental domains on ``psi = psi0`` at distance ``delta`` from the orbits.
    n_phase : int
        Phases of the splitting grid (even).
    tol, long_double :
        Integration tolerance and precision (extended precision needs heyoka).
    grow : dict, optional
        Keyword arguments of :func:`grow_manifold`.
    progress : bool, optional
        Progress line on stderr (default: when stderr is a terminal).
    engine : str or Engine, optional
        The engine of the flow (default heyoka where installed, else taylor;
        :func:`~andoyer.analysis.splitting.section_map.flow_engine`).

    Returns
    -------
    dict of xarray.Dataset
        * ``"splitting"`` (mu, phase): measured ``Delta_G``, ``Delta_E``; the first-order
          predictions ``Delta_G_melnikov = -mu M(g - theta1/2)/(c G)``,
          ``Delta_E_melnikov = mu M``; per ``mu``: ``amplitude`` (max over the phase of
          ``|Delta G|``), ``amplitude_melnikov`` (its first-order prediction
          ``mu max|M| / (c G)``), ``relative_error``
          (``max |Delta G - prediction| / amplitude_melnikov``). Values ``rho``,
          ``theta1_line``, ``epsilon`` and ``melnikov_function_max`` (``max|M|``, of the
          Melnikov function itself, not a splitting).
        * ``"intersections"`` (mu, intersection): heteroclinic points ``g``, ``G``,
          ``state_distance``, ``Delta_G``, ``angle``, ``lobe_area`` and their
          first-order predictions ``angle_melnikov``, ``lobe_area_melnikov`` (NaN-padded).
        * ``"melnikov"``: :func:`~andoyer.analysis.splitting.melnikov.melnikov_function` at the
          phases of the grid.
        * ``"orbit_leaves"``, ``"orbit_reaches"`` (mu): the periodic orbits the line
          leaves and reaches, continued from ``mu = 0`` (:func:`~andoyer.analysis.splitting.
          periodic.orbits_dataset`).
        * ``"curve_unstable"``, ``"curve_stable"`` (point): the manifold curves on
          ``Sigma_0`` at the largest ``mu`` (:meth:`ManifoldCurve.dataset`).

    Examples
    --------
    >>> out = separatrix_splitting(RigidBody.hess(2.5, 1.0, 1.6), [0.01], n_phase=8,
    ...                            delta=1e-4)                      # doctest: +SKIP
    >>> float(out["splitting"].relative_error[0]) < 0.05            # doctest: +SKIP
    True
    """
    from andoyer.analysis.splitting.melnikov import melnikov_of
    from andoyer.analysis.splitting.periodic import orbits_dataset
    from andoyer.progress import Progress

    if grow is not None and not isinstance(grow, dict):
        raise ValueError(f"grow must be a dict of grow_manifold's keyword arguments, got "
                         f"{grow!r}")
    mus = _mu_values(body, mu)
    if np.any(np.diff(mus) <= 0):
        raise ValueError("mu must be increasing")
    # The one conversion of the level along the call path: G -> h here, h -> J2 = G in
    # the problem (separatrix_momentum); the problem (nearest Hess body, line, engine)
    # is built once and passed down.
    h = separatrix_energy(body, positive("G", G))
    problem = splitting_problem(body, h, branch, sheet, engine)
    theta1_line = problem.theta1_line
    bar = Progress(2 + 3 * mus.size, f"manifolds of {body.name or 'the body'}", progress)
    # Both rotation orbits, continued in mu once through every requested value.
    path = np.concatenate([[0.0], mus])
    orbits = {}
    for stability in ("unstable", "stable"):
        orbits[stability], _ = continue_rotation_orbit(
            body, h, 0.0, RotationSection(psi0, problem.rotation(stability)), mu=path,
            tol=tol, long_double=long_double, engine=problem.engine)
        bar.update(1)
    orb_u, orb_s = orbits["unstable"], orbits["stable"]
    splits, inters = [], []
    curves: dict[str, xr.Dataset] = {}
    for k, m in enumerate(mus):
        at_mu = problem.with_mu(float(m))
        common: dict[str, Any] = {"psi0": psi0, "delta": delta, "tol": tol,
                                  "long_double": long_double}
        wu = grow_manifold(branch_of(at_mu, "unstable", orb_u[k + 1], **common),
                           **(grow or {}))
        ws = grow_manifold(branch_of(at_mu, "stable", orb_s[k + 1], **common),
                           **(grow or {}))
        bar.update(1)
        sp, it = measure_splitting(wu, ws, n_phase=n_phase)
        bar.update(2)
        splits.append(sp)
        inters.append(it)
        if k == mus.size - 1:
            curves = {"curve_unstable": wu.dataset(), "curve_stable": ws.dataset()}
    bar.close()

    phases = splits[0].phase.values
    # The Melnikov phase: theta2 = g - theta1/2 where the unperturbed line crosses L = 0.
    mel = melnikov_of(body, problem.hess, np.asarray(phases - theta1_line / 2.0, dtype=float),
                      J2=G, branch=branch, sheet=sheet, quadrature=True)
    dG = np.stack([sp.Delta_G.values for sp in splits])
    dE = np.stack([sp.Delta_E.values for sp in splits])
    pred_E = mus[:, None] * mel["M"].values[None, :]
    pred_G = -pred_E / (body.c * G)
    amp = np.max(np.abs(dG), axis=1)
    amp_pred = np.max(np.abs(pred_G), axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        rel = np.where(amp_pred > 0, np.max(np.abs(dG - pred_G), axis=1) / amp_pred, np.nan)
    attrs = provenance(body.with_mu(float(mus[-1])), engine=FLOW_ENGINES[problem.engine.name],
                       branch=branch, sheet=sheet, energy=h, G_level=G, psi0=psi0,
                       delta=delta, tolerance=tol, long_double=int(long_double),
                       n_phase=n_phase, theta1_line=theta1_line, rho=mel.attrs["rho"],
                       epsilon=mel.attrs["epsilon"],
                       melnikov_function_max=mel.attrs["amplitude"],
                       plane="Sigma_0 = {L = G3 = 0}: Darboux coordinates (g, G)",
                       relation="Delta_E = mu M(theta2_0) + O(mu^2); Delta_G = -Delta_E/(c G)"
                                " (1 + O(mu)); theta2_0 = g - theta1_line/2")
    attrs["body_mu"] = "see the mu coordinate"
    splitting = xr.Dataset(
        {"Delta_G": (("mu", "phase"), dG),
         "Delta_E": (("mu", "phase"), dE),
         "Delta_G_melnikov": (("mu", "phase"), pred_G),
         "Delta_E_melnikov": (("mu", "phase"), pred_E),
         "amplitude": (("mu",), amp),
         "amplitude_melnikov": (("mu",), amp_pred),
         "relative_error": (("mu",), rel)},
        coords={"mu": mus, "phase": phases}, attrs=attrs)
    for name, sym, long, units in (
            ("Delta_G", "\\Delta G", "measured G^u - G^s on the line g = const of L = 0", "1"),
            ("Delta_E", "\\Delta E", "measured E^u - E^s, E = H0 - c G^2/2", "energy units"),
            ("Delta_G_melnikov", "-\\mu M/(c G)", "first-order prediction of Delta G", "1"),
            ("Delta_E_melnikov", "\\mu M", "first-order prediction of Delta E",
             "energy units"),
            ("amplitude", "max|\\Delta G|", "measured splitting amplitude: max over the phase "
                                             "of |Delta G|", "1"),
            ("amplitude_melnikov", "\\mu max|M|/(c G)",
             "first-order (Melnikov) prediction of the splitting amplitude: mu "
             "melnikov_function_max / (c G)", "1"),
            ("relative_error", "", "max over the phase |Delta G - prediction| / predicted "
                                   "amplitude", "1")):
        splitting[name].attrs.update(symbol=sym, long_name=long, units=units)
    splitting.mu.attrs.update(symbol="\\mu", long_name="weight x distance of the centre of "
                              "mass", units="1", equation="(1)")
    splitting.phase.attrs.update(splits[0].phase.attrs)
    values_from_attrs(splitting, {
        "rho": ("\\rho", "rho = c J2/lambda of the unperturbed separatrix", "1", ""),
        "melnikov_function_max": ("\\max|M|", "max over the phase of |M|, the Melnikov "
                                  "function itself (Delta E = mu M; not a splitting: "
                                  "see amplitude_melnikov)", "energy units x time",
                                  "(16)"),
        "theta1_line": ("\\theta_1", "theta1 of the unperturbed heteroclinic line", "rad",
                        "(14)"),
        "epsilon": ("\\epsilon", "turn of the centre of mass off the Hess direction", "rad",
                    "(2)")})

    n_max = max([it.sizes["intersection"] for it in inters] + [0])
    data: dict[str, Any] = {}
    for name in ("g", "G", "state_distance", "Delta_G", "angle", "lobe_area"):
        arr = np.full((mus.size, n_max), np.nan)
        for k, it in enumerate(inters):
            arr[k, :it.sizes["intersection"]] = it[name].values
        data[name] = (("mu", "intersection"), arr)
    # A pure harmonic A cos(g + c): slope A at its zeros, lobe area 2 A.
    data["angle_melnikov"] = (("mu",), np.arctan(amp_pred))
    data["lobe_area_melnikov"] = (("mu",), 2.0 * amp_pred)
    intersections = xr.Dataset(data, coords={"mu": mus, "intersection": np.arange(n_max)},
                               attrs={**attrs, "gtol": inters[0].attrs.get("gtol", np.nan)})
    for name in ("g", "G", "state_distance", "Delta_G", "angle", "lobe_area"):
        intersections[name].attrs.update(inters[0][name].attrs)
    intersections["angle_melnikov"].attrs.update(
        symbol="atan(max|\\mu M/(c G)|)", long_name="first-order splitting angle", units="rad")
    intersections["lobe_area_melnikov"].attrs.update(
        symbol="2 max|\\mu M/(c G)|", long_name="first-order lobe area |int Delta G dg|",
        units="action units")
    return {"splitting": splitting, "intersections": intersections, "melnikov": mel,
            "orbit_leaves": orbits_dataset(orb_u), "orbit_reaches": orbits_dataset(orb_s),
            **curves}


@checks_body(ranges={"epsilon": "finite", "mu": "scale", "G": "length", "n_phase": "count", "tol":
             "tolerance"})
def splitting_vs_epsilon(body: RigidBody, epsilon: Sequence[float] | ArrayLike,
                         mu: Sequence[float] | ArrayLike | None = None, *,
                         branch: str = DEFAULT_BRANCH,
                         G: float = 1.0, n_phase: int = 16, delta: float = 1e-5,
                         tol: float = DEFAULT_TOL, progress: bool | None = None,
                         engine: EngineLike = None) -> xr.Dataset:
    """The splitting of a separatrix branch as the centre of mass turns off the Hess
    direction: measured (:func:`separatrix_splitting`) against the first-order Melnikov
    prediction (:func:`~andoyer.analysis.splitting.melnikov.melnikov_off_hess`) over ``epsilon``.

    On the Hess branch ``theta1 = 0`` the amplitude is
    ``mu 2 (pi rho/sinh pi rho) |sin epsilon| / (c G) + O(mu^2)``: it vanishes at
    ``epsilon = 0`` (the Hess relation (3) is invariant, the manifolds coincide) and
    grows linearly with ``epsilon``.

    Parameters
    ----------
    body : RigidBody
        A Hess body (:meth:`~andoyer.body.RigidBody.nearest_hess` of a planar body);
        the turned bodies are :meth:`~andoyer.body.RigidBody.near_hess` of its moments.
    epsilon : sequence of float
        Turns of the centre of mass (rad), each in ``(-pi/2, pi/2)``.
    mu : sequence of float, optional
        Increasing values ``mu > 0`` (default: the body's own, ``[body.mu]``).
    branch, G, n_phase, delta, tol, engine :
        As in :func:`separatrix_splitting`.
    progress : bool, optional
        A progress bar over ``epsilon`` (default: when stderr is a terminal).

    Returns
    -------
    xarray.Dataset
        Dims ``(epsilon, mu)``: ``amplitude`` (measured ``max |Delta G|``),
        ``amplitude_melnikov``, ``relative_error`` (over the phase, of the predicted
        amplitude; NaN where the prediction is 0), ``g_intersection`` (the first
        heteroclinic point). Values ``rho``, ``theta1_line``.

    Examples
    --------
    >>> ds = splitting_vs_epsilon(RigidBody.hess(2.5, 1.0, 1.6), [0.0, 0.1], [0.01],
    ...                           n_phase=8)
    >>> float(ds.amplitude[0, 0]) < 1e-12, float(ds.relative_error[1, 0]) < 0.01
    (True, True)
    """
    from andoyer.progress import Progress

    hess = body.nearest_hess()
    eps = np.atleast_1d(finite_array("epsilon", epsilon))
    branch = choice("branch", branch, BRANCHES)
    positive("G", G, maximum=MAX_ACTION)
    integer("n_phase", n_phase, 1)
    positive("delta", delta)
    positive("tol", tol)
    flag("progress", progress)
    if eps.ndim != 1 or eps.size == 0 or not np.all(np.abs(eps) < 0.5 * math.pi):
        raise ValueError(f"epsilon must be a non-empty list of turns in (-pi/2, pi/2), got "
                         f"{epsilon!r}")
    mus = _mu_values(body, mu)
    sign = 1 if hess.e2 >= 0.0 else -1
    amp = np.full((eps.size, mus.size), np.nan)
    pred, rel, g_star = amp.copy(), amp.copy(), amp.copy()
    last: xr.Dataset | None = None
    bar = Progress(eps.size, f"splitting vs epsilon, {branch}", progress)
    for i, e in enumerate(eps):
        turned = RigidBody.near_hess(hess.A, hess.B, hess.C, 0.0, float(e), branch=sign,
                                     name=hess.name)
        out = separatrix_splitting(turned, mus, G=G, branch=branch, n_phase=n_phase,
                                   delta=delta, tol=tol, progress=False, engine=engine)
        sp, it = out["splitting"], out["intersections"]
        amp[i], pred[i], rel[i] = (sp.amplitude.values, sp.amplitude_melnikov.values,
                                   sp.relative_error.values)
        if it.sizes["intersection"]:
            g_star[i] = it.g.values[:, 0]
        last = sp
        bar.update(1)
    bar.close()
    assert last is not None
    attrs = provenance(hess.with_mu(float(mus[-1])), engine=last.attrs["engine"],
                       branch=branch, energy=0.5 * hess.c * G * G, G_level=G,
                       n_phase=n_phase, delta=delta, tolerance=tol,
                       theta1_line=float(last.theta1_line), rho=float(last.rho),
                       relation="max|Delta G| = mu 2 (pi rho/sinh pi rho) |sin(theta1/2 + "
                                "epsilon)| / (c G) + O(mu^2)")
    attrs["body_mu"] = "see the mu coordinate"
    ds = xr.Dataset({"amplitude": (("epsilon", "mu"), amp),
                     "amplitude_melnikov": (("epsilon", "mu"), pred),
                     "relative_error": (("epsilon", "mu"), rel),
                     "g_intersection": (("epsilon", "mu"), g_star)},
                    coords={"epsilon": eps, "mu": mus}, attrs=attrs)
    values_from_attrs(ds, {
        "rho": ("\\rho", "rho = c J2/lambda of the unperturbed separatrix", "1", ""),
        "theta1_line": ("\\theta_1", "theta1 of the unperturbed heteroclinic line", "rad",
                        "(14)")})
    ds.epsilon.attrs.update(symbol="\\epsilon", long_name="turn of the centre of mass off "
                            "the Hess direction", units="rad", equation="(2)")
    ds.mu.attrs.update(last.mu.attrs)
    for name in ("amplitude", "amplitude_melnikov", "relative_error"):
        ds[name].attrs.update(last[name].attrs)
    ds.g_intersection.attrs.update(symbol="g^*", long_name="phase of the first heteroclinic "
                                   "point on L = 0 (pi/2 by the reversing symmetry)",
                                   units="rad")
    return ds
