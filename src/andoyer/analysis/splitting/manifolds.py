"""Stable and unstable manifolds of the rotation orbits and the splitting of separatrices.

For ``mu > 0`` the permanent rotations about the middle axis z become the hyperbolic
periodic orbits ``P+`` (``L = +G``) and ``P-`` (``L = -G``) of
:mod:`andoyer.analysis.splitting.periodic`. At ``mu = 0`` their invariant manifolds coincide
along the heteroclinic orbits of the Hess chart (14), the lines ``theta1 = 0`` and
``theta1 = 4 phi0`` of the unperturbed system after Fig. 3 of [1]_
(:mod:`andoyer.analysis.unperturbed.separatrix`). For ``mu > 0``:

* on ``theta1 = 0`` the manifolds still coincide: that line is the Hess invariant
  relation (3), invariant for every ``mu`` -- the Hess solutions;
* on ``theta1 = 4 phi0`` they split, by an amount ``mu M(theta2) + O(mu^2)`` with the
  Melnikov function of :mod:`andoyer.analysis.splitting.melnikov`, exponentially small in
  ``rho = c J2 / lambda`` for the paper's body.

Where the manifolds are grown and compared
------------------------------------------
The Hess chart is singular on ``P+-`` themselves, so the local manifolds are grown on
the sections ``Sigma+- = {psi = psi0}`` of :class:`~andoyer.analysis.splitting.periodic.
RotationSection` in the regular coordinates ``(x1, x2) = (G1, G2)/|G|``: from the fixed
point ``p`` along the unit eigenvector ``v`` of the section map, one *fundamental
domain* ``q(s) = p + delta Lambda^s v``, ``0 <= s <= 1`` (``Lambda`` the expanding
multiplier of the map, or of its inverse for the stable manifold): every orbit of the
manifold branch crosses it exactly once (up to ``O(delta^2)`` at the ends). Its points
are carried by the flow (forwards for ``W^u``, backwards for ``W^s``) to the middle
section

.. math::

    \\Sigma_0 = \\{L = G_3 = 0\\},

which every heteroclinic orbit crosses once, transversally (``dL/dt != 0`` there), far
from the chart's singular set (``J1 = J2/2``). On ``Sigma_0`` the Andoyer-Deprit angle
``g`` and the action ``G`` are Darboux coordinates of the section of the energy level
(``dl ^ dL + dg ^ dG = dg ^ dG`` on ``L = 0``; ``l`` is fixed by ``H = h``), so areas
measured in ``(g, G)`` are the symplectic areas (lobe areas are fluxes). Each manifold
branch meets ``Sigma_0`` in a closed curve that is a graph ``G = G^{u,s}(g)`` over
the phase ``g``; the curve is resolved by inserting fundamental-domain points where two
neighbours are farther apart than ``max_gap`` or the curve turns by more than
``max_angle`` (fundamental-domain refinement). The transverse error of a seed,
``O(delta^2)``, is contracted by ``Lambda^{-n}`` during the ``n ~ ln(1/delta)/ln
Lambda`` turns near the orbit.

Splitting
---------
* distance along the transverse line ``g = const`` of ``Sigma_0``:
  ``Delta G(g) = G^u(g) - G^s(g)``, with fresh points on both manifolds (the
  fundamental-domain parameter is solved for the phase ``g``; no interpolation);
* ``Delta E(g)`` of ``E = H0 - c G^2/2 = ((a - c) G1^2 + (b - c) G2^2)/2`` (the
  paper's ``2T - c G^2`` after (12), halved), the quantity the Melnikov integral
  predicts: ``Delta E = mu M + O(mu^2)`` and ``Delta G = -Delta E / (c G) (1 + O(mu))``;
* heteroclinic points: zeros of ``Delta G``, located by root finding on the
  trigonometric interpolant of ``Delta G`` on a phase grid, then refined on fresh
  points (Brent's method in ``g``); on a Hess body at ``M = 0`` the reversor
  ``(G1, G2, G3, gamma1, gamma2, gamma3) -> (G1, G2, -G3, gamma1, gamma2, -gamma3)``
  (time reversal composed with the symmetry ``G3, gamma3 -> -G3, -gamma3``) fixes the
  line ``g = pi/2, 3 pi/2`` of ``Sigma_0`` and maps ``W^u(P-)`` onto ``W^s(P+)``, so
  the primary heteroclinic points lie exactly there;
* splitting angle ``atan(G^u') - atan(G^s')`` at each heteroclinic point (``(g, G)``
  plane), and the lobe area between consecutive points (shoelace on the lobe polygon).

References
----------
.. [1] V. V. Kyrychenko, "Andoyer-Deprit variables use to the Hess gyroscope phase
   trajectories exploring", National Aviation University, Kyiv (``andoyer.cite("paper")``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any, Literal

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from andoyer.analysis.splitting.melnikov import heteroclinic_line
from andoyer.analysis.splitting.periodic import (
    DEFAULT_TOL,
    Crossing,
    RotationOrbit,
    RotationSection,
    continue_rotation_orbit,
    flow_to_section,
    middle_axis_rate,
    section_state,
)
from andoyer.analysis.splitting.problem import SplittingProblem, splitting_problem
from andoyer.analysis.splitting.section_map import FLOW_ENGINES
from andoyer.analysis.unperturbed.separatrix import DEFAULT_BRANCH, separatrix_momentum
from andoyer.body import RigidBody, checks_body
from andoyer.charts.andoyer_deprit import to_andoyer
from andoyer.charts.euler_poisson import STATE, energy
from andoyer.charts.hess import to_hess
from andoyer.integrate.engines import EngineLike
from andoyer.integrate.results import VariableMeta, describe_variables, provenance
from andoyer.validation import checks_arguments, integer, positive

__all__ = [
    "Stability",
    "ManifoldBranch",
    "ManifoldCurve",
    "manifold_branch",
    "grow_manifold",
    "euler_poinsot_excess",
    "heteroclinic_line_of",
]

Stability = Literal["unstable", "stable"]


@checks_body
def euler_poinsot_excess(body: RigidBody, y: ArrayLike) -> NDArray[np.float64]:
    """``E = H0 - c |G|^2 / 2``: zero on the unperturbed separatrices and on ``P+-``.

    ``H0`` is the energy (1) at ``mu = 0``; ``E = ((a - c) G1^2 + (b - c) G2^2)/2``
    (after Eq. (12)), ``kappa J1 (J1 - J2) [cos(theta1 - 2 phi0) - cos 2 phi0]`` in the
    Hess chart (13)-(14). Its bracket with ``H0`` vanishes, so along the full flow
    ``dE/dt = mu {E, H1}``: the integrand of the Melnikov function.

    Parameters
    ----------
    body : RigidBody
        The body (its moments ``a, b, c``; ``mu`` does not enter).
    y : array_like, shape (..., 6)
        Euler-Poisson states of Eq. (1).
    """
    y = np.asarray(y, dtype=float)
    return np.asarray(energy(body.with_mu(0.0), y)
                      - 0.5 * body.c * np.einsum("...i,...i->...", y[..., :3], y[..., :3]))


# ----------------------------------------------------------------------------- branches
@dataclass(frozen=True)
class ManifoldBranch:
    """One branch of ``W^u`` or ``W^s`` of a rotation orbit, seeded on its section.

    Attributes
    ----------
    orbit : RotationOrbit
        The hyperbolic periodic orbit (fixed point ``p`` of the section map).
    stability : {"unstable", "stable"}
    branch : str
        The heteroclinic line it follows at ``mu = 0`` (``"theta1=0"`` or
        ``"theta1=4phi0"``).
    sheet : {+1, -1}
        ``+1``: ``theta1`` on that line in ``[0, 2 pi)``; ``-1``: ``theta1 + 2 pi``
        (the other half of the momentum great circle).
    vector : ndarray (2,)
        Unit eigenvector in ``(x1, x2)``, oriented along the branch.
    factor : float
        Expansion of the fundamental domain, ``Lambda_u`` or ``1/Lambda_s``.
    delta : float
        Distance of the fundamental domain from ``p`` (in ``(x1, x2)``).
    theta1_line : float
        ``theta1`` of the unperturbed line in ``[0, 4 pi)``, in the chart of
        :meth:`~andoyer.body.RigidBody.nearest_hess`.
    crossing_direction : int
        Sign of ``dL/dt`` where the branch crosses ``Sigma_0``.
    """

    orbit: RotationOrbit
    stability: Stability
    branch: str
    sheet: int
    vector: NDArray[np.float64]
    factor: float
    delta: float
    theta1_line: float
    crossing_direction: int

    @property
    def body(self) -> RigidBody:
        return self.orbit.body

    @property
    def h(self) -> float:
        return self.orbit.h

    def seed(self, s: float) -> NDArray[np.float64]:
        """The state ``q(s) = p + delta factor^s v`` on the orbit's section."""
        x = self.orbit.x + self.delta * self.factor ** float(s) * self.vector
        return np.asarray(section_state(self.body, x, self.h, self.orbit.M,
                                        self.orbit.section))

    def trace(self, s: float) -> Crossing:
        """Carry the seed ``q(s)`` by the flow to its crossing of ``Sigma_0 = {L = 0}``."""
        sigma = middle_axis_rate(self.body)
        G = float(np.linalg.norm(self.orbit.y[:3]))
        t_max = 20.0 * self.orbit.period + 60.0 / (sigma * G)
        return flow_to_section(self.body, self.seed(s), "L", self.crossing_direction,
                               backward=self.stability == "stable", t_max=t_max,
                               tol=self.orbit.tol, long_double=self.orbit.long_double,
                               engine=self.orbit.flow)

    def attrs(self) -> dict[str, Any]:
        return {"stability": self.stability, "branch": self.branch, "sheet": self.sheet,
                "rotation_sign": self.orbit.section.sign,
                "section_psi0": self.orbit.section.psi0,
                "fundamental_domain_delta": self.delta,
                "fundamental_domain_factor": self.factor,
                "theta1_line": self.theta1_line, "energy": self.h, "area": self.orbit.M,
                "multiplier_u": float(self.orbit.multipliers[0]),
                "multiplier_s": float(self.orbit.multipliers[1]),
                "period": self.orbit.period, "tolerance": self.orbit.tol}


@checks_body(ranges={"h": "energy", "sheet": "sheet"})
def heteroclinic_line_of(body: RigidBody, h: float, branch: str, sheet: int
                         ) -> tuple[float, int]:
    """``(theta1 of the line, sign of dJ1/dt on it)`` on the level ``h = c J2^2/2``
    (``J2`` from :func:`~andoyer.analysis.unperturbed.separatrix.separatrix_momentum`).

    Parameters
    ----------
    body : RigidBody
        A Hess body, or one turned off it (the lines of its nearest Hess body).
    h : float
        Energy level ``h = c J2^2 / 2`` (> 0).
    branch : {"theta1=0", "theta1=4phi0"}
        Which heteroclinic line.
    sheet : {+1, -1}
        Which of its two orbits (``theta1`` or ``theta1 + 2 pi``).
    """
    return heteroclinic_line(body, separatrix_momentum(body, h), branch, sheet)


@checks_body(ranges={"h": "energy", "sheet": "sheet", "psi0": "angle", "mu_steps": "count", "tol":
             "tolerance"})
def manifold_branch(body: RigidBody, h: float, stability: Stability,
                    branch: str = DEFAULT_BRANCH, *, sheet: int = 1, psi0: float = 0.0,
                    delta: float = 1e-5, orbit: RotationOrbit | None = None,
                    mu_steps: int = 4, tol: float = DEFAULT_TOL,
                    long_double: bool = False, engine: EngineLike = None) -> ManifoldBranch:
    """The branch of ``W^u`` / ``W^s`` that follows a heteroclinic line, ready to grow.

    Parameters
    ----------
    body : RigidBody
        A Hess body (the lines ``theta1 = 0``, ``4 phi0`` are the separatrices), or a
        body turned off it in the (e1, e2) plane
        (:meth:`~andoyer.body.RigidBody.near_hess`; the lines are then those of
        :meth:`~andoyer.body.RigidBody.nearest_hess`, which the unperturbed flow follows
        whatever ``r``); the area constant is ``M = 0``.
    h : float
        Energy level (e.g. :func:`~andoyer.analysis.splitting.periodic.rotation_energy`).
    stability : {"unstable", "stable"}
        ``"unstable"``: ``W^u`` of the rotation the line leaves; ``"stable"``: ``W^s`` of
        the rotation it reaches (at ``mu = 0`` ``J1`` increases along ``theta1 = 4 phi0``
        for ``phi0 > 0``: from ``L = -G`` to ``L = +G``).
    branch : {"theta1=0", "theta1=4phi0"}
    sheet : {+1, -1}
        Which of the two orbits of the line (``theta1`` or ``theta1 + 2 pi``).
    psi0 : float
        Section ``psi = psi0`` on which the fundamental domain is seeded.
    delta : float
        Distance of the fundamental domain from the fixed point in ``(x1, x2)``.
    orbit : RotationOrbit, optional
        The periodic orbit (default: continued in ``mu`` from 0 in ``mu_steps`` steps).
    tol, long_double :
        Integration tolerance and precision (extended precision needs heyoka).
    engine : str or Engine, optional
        The engine of the flow when ``orbit`` is not given (default heyoka where
        installed, else taylor:
        :func:`~andoyer.analysis.splitting.section_map.flow_engine`); a given ``orbit``
        brings its own.
    mu_steps : int, default 4
        Steps of the continuation in ``mu`` from 0 that finds the periodic orbit when
        ``orbit`` is not given.

    Returns
    -------
    ManifoldBranch

    Examples
    --------
    >>> from andoyer.analysis.splitting.periodic import rotation_energy
    >>> body = RigidBody.hess(2.5, 1.0, 1.6, mu=0.01)
    >>> wu = manifold_branch(body, rotation_energy(body), "unstable", "theta1=4phi0",
    ...                      delta=1e-4)
    >>> wu.orbit.section.sign, round(wu.factor, 4)        # leaves L = -G; exp(2 pi sigma/c)
    (-1, 18.5443)
    >>> curve = grow_manifold(wu)
    >>> bool(np.ptp(curve.g) > 2 * np.pi)                  # one fundamental domain: a full turn
    True
    """
    problem = splitting_problem(body, h, branch, sheet,
                                engine if orbit is None else orbit.flow)
    return branch_of(problem, stability, orbit, psi0=psi0, delta=delta, mu_steps=mu_steps,
                     tol=tol, long_double=long_double)


def branch_of(problem: SplittingProblem, stability: Stability,
              orbit: RotationOrbit | None = None, *, psi0: float = 0.0, delta: float = 1e-5,
              mu_steps: int = 4, tol: float = DEFAULT_TOL,
              long_double: bool = False) -> ManifoldBranch:
    """The branch of ``W^u`` / ``W^s`` of a prepared problem (:func:`manifold_branch`
    once its arguments are checked and its problem built).

    Parameters
    ----------
    problem : SplittingProblem
        The body, its nearest Hess body, the level, the line and the engine
        (:func:`~andoyer.analysis.splitting.problem.splitting_problem`).
    stability : {"unstable", "stable"}
        Which manifold.
    orbit : RotationOrbit, optional
        The periodic orbit (default: continued in ``mu`` from 0 in ``mu_steps`` steps on
        the problem's engine).
    psi0, delta, mu_steps, tol, long_double :
        As in :func:`manifold_branch`.
    """
    if stability not in ("unstable", "stable"):
        raise ValueError(f"stability must be 'unstable' or 'stable', got {stability!r}")
    if not (math.isfinite(delta) and 0.0 < delta < 0.1):
        raise ValueError(f"delta must lie in (0, 0.1), got {delta!r}")
    body, h, hess = problem.body, problem.h, problem.hess
    theta1_line = problem.theta1_line
    rot = problem.rotation(stability)
    if orbit is None:
        orbits, _ = continue_rotation_orbit(body, h, 0.0, RotationSection(psi0, rot),
                                            steps=mu_steps, tol=tol, long_double=long_double,
                                            engine=problem.engine)
        orbit = orbits[-1]
    elif orbit.section.sign != rot or orbit.body != body or orbit.M != 0.0:
        raise ValueError(f"orbit must be the rotation L = {'+' if rot > 0 else '-'}G of this "
                         "body on M = 0")
    k = 0 if stability == "unstable" else 1
    lam = float(orbit.multipliers[k])
    if lam < 0.0:
        raise ValueError(f"multiplier {lam:.6g} < 0 (inverse hyperbolic orbit): a fundamental "
                         "domain would alternate between the branches; not supported")
    factor = lam if stability == "unstable" else 1.0 / lam
    v = orbit.eigenvectors[:, k].copy()
    trial = ManifoldBranch(orbit, stability, problem.branch, problem.sheet, v, factor,
                           float(delta), theta1_line, -rot if stability == "unstable" else rot)
    # Orient v: the traced point must arrive near the line's l = theta1/2 - phi0 (mod 2 pi).
    l_line = theta1_line / 2.0 - hess.phi0
    l_seen = float(to_andoyer(trial.trace(0.5).y)[0])
    if abs(math.remainder(l_seen - l_line, math.tau)) > math.pi / 2:
        trial = replace(trial, vector=-v)
    return trial


# ----------------------------------------------------------------------------- curves
@dataclass(frozen=True)
class ManifoldCurve:
    """A manifold branch traced on ``Sigma_0``: fundamental-domain samples sorted by ``s``.

    Attributes
    ----------
    branch : ManifoldBranch
        The branch traced (:func:`manifold_branch`).
    s : ndarray, shape (n,)
        Fundamental-domain parameter of each point, increasing (``[0, 1)`` is one domain,
        with the margins of :func:`grow_manifold` either side).
    y : ndarray, shape (n, 6)
        Euler-Poisson states of the points on ``Sigma_0`` (``L = 0``).
    t : ndarray, shape (n,)
        Flight time from the fundamental domain to ``Sigma_0`` (body time units; negative
        for ``W^s``, traced backward).
    """

    branch: ManifoldBranch
    s: NDArray[np.float64]
    y: NDArray[np.float64]
    t: NDArray[np.float64]

    @property
    def g(self) -> NDArray[np.float64]:
        """Phase ``g`` on ``Sigma_0``, unwrapped along the curve."""
        return np.unwrap(to_andoyer(self.y)[:, 1])

    @property
    def G(self) -> NDArray[np.float64]:
        return np.asarray(np.linalg.norm(self.y[:, :3], axis=-1))

    def point_at_phase(self, g: float, *, stol: float = 1e-14) -> Crossing:
        """A fresh point of the manifold on ``Sigma_0`` with phase ``g`` (mod 2 pi).

        The fundamental-domain parameter ``s`` is found by Brent's method on
        ``remainder(g(s) - g, 2 pi)`` inside the bracket of two neighbouring samples, to
        ``stol`` in ``s`` (the phase to about ``2 pi stol``); each evaluation integrates
        a fresh orbit. The evaluated point nearest the phase is returned.
        """
        from scipy.optimize import brentq

        gs = self.g
        r = np.remainder(gs - g + math.pi, math.tau) - math.pi
        # A sign change of r between two close samples, not its jump at r = +-pi.
        cand = np.flatnonzero((np.sign(r[:-1]) != np.sign(r[1:]))
                              & (np.abs(r[:-1]) < 1.0) & (np.abs(r[1:]) < 1.0))
        if cand.size == 0:
            raise ValueError(f"phase g = {g:.6g} is not covered by the traced curve")
        # Prefer the bracket nearest the middle of the fundamental domain.
        i = int(cand[np.argmin(np.abs(self.s[cand] - 0.5))])
        best: list[tuple[float, Crossing]] = []

        def f(s: float) -> float:
            cr = self.branch.trace(s)
            miss = math.remainder(float(to_andoyer(cr.y)[1]) - g, math.tau)
            best.append((abs(miss), cr))
            return miss

        brentq(f, float(self.s[i]), float(self.s[i + 1]), xtol=stol, rtol=1e-15,
               maxiter=100)
        return min(best, key=lambda item: item[0])[1]

    def dataset(self) -> xr.Dataset:
        """The curve on ``Sigma_0`` with arclength, chart coordinates and checks."""
        b = self.branch
        body = b.body
        x = to_andoyer(self.y)
        xh = to_hess(body, self.y)
        g = self.g
        G = self.G
        arclength = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(g), np.diff(G)))])
        ds = xr.Dataset(
            {"s": (("point",), self.s),
             "g_angle": (("point",), np.mod(g, math.tau)),
             "g_unwrapped": (("point",), g),
             "G_action": (("point",), G),
             "l_angle": (("point",), x[:, 0]),
             "L_action": (("point",), x[:, 2]),
             "theta1": (("point",), xh[:, 0]),
             "theta2": (("point",), xh[:, 1]),
             "J1": (("point",), xh[:, 2]),
             "E": (("point",), euler_poinsot_excess(body, self.y)),
             "H": (("point",), energy(body, self.y)),
             "arclength": (("point",), arclength),
             "flight_time": (("point",), self.t),
             "y": (("point", "component"), self.y)},
            coords={"point": np.arange(self.s.size), "component": list(STATE)},
            attrs=provenance(body, engine=FLOW_ENGINES[self.branch.orbit.engine],
                             method="fundamental domain q(s) = p + delta Lambda^s v on the "
                                    "section psi = psi0, carried by the flow to L = 0; "
                                    "adaptive insertion",
                             plane="Sigma_0 = {L = G3 = 0}: Darboux coordinates (g, G)",
                             **b.attrs()))
        meta: dict[str, VariableMeta] = {
            "s": ("s", "fundamental-domain parameter", "1", ""),
            "g_unwrapped": ("g", "g unwrapped along the curve", "rad", "(5)-(6)"),
            "E": ("H_0 - c G^2/2", "Euler-Poinsot excess ((a-c)G1^2 + (b-c)G2^2)/2", "1",
                  "(12)-(13)"),
            "arclength": ("", "arclength in the (g, G) plane", "1", ""),
            "flight_time": ("t", "time from the seed to Sigma_0 (negative: backwards)",
                            "body time units", ""),
            "y": ("(G, \\gamma)", "Euler-Poisson state", "1", "(1)"),
        }
        return describe_variables(ds, meta, long_names={
            "g_angle": "Andoyer-Deprit angle g on L = 0",
            "L_action": "L = G3 (zero on the section)", "H": "energy (check: constant)"})


def _needs_point(g: NDArray[np.float64], G: NDArray[np.float64], max_gap: float,
                 max_angle: float) -> NDArray[np.bool_]:
    """Segments ``i -> i + 1`` to split: too long, or the curve turns too much at an end."""
    dg, dG = np.diff(g), np.diff(G)
    split = np.hypot(dg, dG) > max_gap
    if g.size >= 3:
        ang = np.abs(np.angle(np.exp(1j * np.diff(np.arctan2(dG, dg)))))
        turn = ang > max_angle
        split[:-1] |= turn
        split[1:] |= turn
    return split


@checks_arguments(ranges={"n_initial": "count"})
def grow_manifold(branch: ManifoldBranch, *, n_initial: int = 48, max_gap: float = 0.15,
                  max_angle: float = 0.1, max_points: int = 2000, s_margin: float = 0.05,
                  min_ds: float = 1e-9) -> ManifoldCurve:
    """Trace one fundamental domain of a branch on ``Sigma_0``, refined adaptively.

    Parameters
    ----------
    branch : ManifoldBranch
    n_initial : int
        Initial number of equal steps in ``s`` on ``[-s_margin, 1 + s_margin]`` (the
        margin, in ``[0, 0.5]``, makes the closed curve overlap itself).
    max_gap : float
        Largest distance between neighbouring points in the ``(g, G)`` plane.
    max_angle : float
        Largest turn of the curve (radians) at a point of the ``(g, G)`` plane.
    max_points : int
        Stop refining (with a ``RuntimeWarning``) beyond this many points.
    min_ds : float
        Do not split fundamental-domain intervals shorter than this.
    s_margin : float, default 0.05
        Margin added to the fundamental domain on either side of ``[0, 1]`` (so that the
        curve overlaps itself).

    Returns
    -------
    ManifoldCurve
    """
    import warnings

    n_initial = integer("n_initial", n_initial, 4)
    max_gap, max_angle = positive("max_gap", max_gap), positive("max_angle", max_angle)
    s_margin = float(s_margin)
    if not 0.0 <= s_margin <= 0.5:  # a margin past half a domain traces it thrice
        raise ValueError(f"s_margin must be in [0, 0.5], got {s_margin!r}")
    s = np.linspace(-s_margin, 1.0 + s_margin, int(n_initial) + 1)
    crossings = [branch.trace(si) for si in s]
    y = np.stack([c.y for c in crossings])
    t = np.array([c.t for c in crossings])
    while True:
        g = np.unwrap(to_andoyer(y)[:, 1])
        G = np.linalg.norm(y[:, :3], axis=-1)
        split = _needs_point(g, G, max_gap, max_angle) & (np.diff(s) > min_ds)
        if not split.any():
            break
        if s.size + int(split.sum()) > max_points:
            warnings.warn(f"manifold not resolved within max_points = {max_points}",
                          RuntimeWarning, stacklevel=2)
            break
        new_s = 0.5 * (s[:-1] + s[1:])[split]
        new = [branch.trace(si) for si in new_s]
        s = np.concatenate([s, new_s])
        y = np.concatenate([y, np.stack([c.y for c in new])])
        t = np.concatenate([t, [c.t for c in new]])
        order = np.argsort(s)
        s, y, t = s[order], y[order], t[order]
    return ManifoldCurve(branch, s, y, t)


