r"""The half-width of an island chain measured on Poincare sections of the full flow.

The independent route to :func:`~andoyer.analysis.resonance.predict.resonance_widths`:
orbits of the perturbed system (``mu > 0``, integrated by an engine through
:func:`andoyer.integrate.poincare`) are seeded on the section ``g = g*`` along the line
through a predicted stable point of the chain, in the direction the free-top tori move
when ``G`` changes (R9): the seed ``s`` sits where the torus ``G* + s`` would cross the
line, so ``s`` is in units of ``G``. At each crossing ``n`` the slow angle
``psi_n = q phi1_n - p phi2_n`` is evaluated (``phi1`` the free-top phase of the
crossing's body momentum, :func:`~andoyer.analysis.resonance.torus.free_top_phase`;
``phi2 = g* + 2 pi n - rho(phi1)``) and unwrapped. An orbit is *locked* in the chain
when ``psi`` stays within an interval shorter than ``2 pi`` over ``n_crossings``
returns (it librates), and *circulating* otherwise; the mean drift of ``psi`` per return,
``2 pi (q W - p)`` on a circulating orbit, is linear in ``s`` off the island and points
to it.

The search: seeds at ``s = 0`` (the predicted stable point) and ``+-3 Delta G``; while no
seed is locked, the next is placed where the drift, fitted linearly through the last two,
vanishes (the first-order centre is off by ``O(mu)``, more than the width of a thin
chain). Then both
edges of the locked interval are bracketed and narrowed by rounds of ``n_seeds`` seeds
inside each bracket. The marching and bracketing orbits are screened: each runs a sixth
of ``n_crossings`` first, and only those whose ``psi`` has not yet spanned ``2 pi`` (still
locked) run the whole ``n_crossings`` (the same verdicts; about a fifth less work on the
report's chains). The result: the edges ``s_inner``, ``s_outer`` with their
uncertainties, the measured half-width ``(s_outer - s_inner) / 2`` and centre offset.
An orbit starting within a thin chaotic layer along the separatrix counts as
circulating (its ``psi`` crosses ``2 pi``); the edges are the layer's, which is what a
section shows.
"""

from __future__ import annotations

import math
import warnings
from typing import Any

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from andoyer.analysis.resonance.predict import (
    ResonantChain,
    check_level_args,
    resonant_rows,
    trig_interpolate,
)
from andoyer.analysis.resonance.torus import free_top_phase
from andoyer.body import RigidBody, checks_body
from andoyer.charts.andoyer_deprit import from_andoyer
from andoyer.integrate import Section, budget
from andoyer.integrate.api import poincare
from andoyer.integrate.fill import section_roots
from andoyer.integrate.results import describe_variables, provenance
from andoyer.validation import finite, integer, positive, real_array

__all__ = ["measure_island", "island_rotation_numbers", "ROUTES", "NAFF_LOCK"]

#: Drift-guided steps allowed to find a locked seed before giving up.
_MAX_LOCATE = 8
#: Orbits of the search for the stable periodic orbit inside the locked interval.
_STABLE_EVALUATIONS = 45
#: Its tolerance, relative to the locked interval: the slow angle's span is flat at its
#: minimum, which it resolves to ~1e-6 half-widths (the seeds' round-off moves it 3e-7);
#: a tighter one spends orbits on noise (benchmarks/NOTES.md#measure_island).
_STABLE_XATOL = 1e-5
#: The screening pass of the edges' orbits, a fraction of ``n_crossings`` (``2 / Omega``
#: of the default ``12 / Omega``): the circulating orbits of the report's chains spanned
#: ``2 pi`` within ``0.1-1.6 / Omega`` returns (benchmarks/NOTES.md#measure_island).
_SCREEN_FRACTION = 1.0 / 6.0
#: Fewest screening returns worth a second engine call.
_SCREEN_MIN = 100


def _parse_resonance(resonance: str) -> tuple[int, int]:
    if not isinstance(resonance, str):
        raise ValueError(f"resonance must be a string 'q:p' (frequency_ratio q/p, as "
                         f"andoyer.analysis.chaos.frequency labels it), got {resonance!r}")
    parts = resonance.split(":")
    try:
        q, p = (int(x) for x in parts)
    except ValueError:
        raise ValueError(f"resonance must be 'q:p' with whole numbers, got "
                         f"{resonance!r}") from None
    if not (q >= 1 and p >= 1 and math.gcd(p, q) == 1):
        raise ValueError(f"resonance {resonance!r}: q and p must be coprime and >= 1")
    return p, q


#: Routes of the classification of an orbit as locked in the chain.
ROUTES = ("slow_angle", "naff")
#: NAFF route: locked when the line of ``exp(i phi1_n)`` nearest ``p/q`` (of the strongest
#: :data:`_NAFF_LINES`) lies within this fraction of the libration frequency of ``p/q``
#: (the libration's sidebands sit at ``p/q +- Omega`` turns per return).
NAFF_LOCK = 0.05
_NAFF_LINES = 8


class _Probe:
    """Seeds on the line through one stable point; integrates and classifies them."""

    def __init__(self, chain: ResonantChain, h: float, M: float, g_star: float, n_crossings: int,
                 engine: Any, tol: float, phase: float | None = None,
                 Omega: float | None = None, route: str = "slow_angle") -> None:
        self.c, self.h, self.M, self.g_star = chain, h, M, g_star
        self.n_crossings, self.engine, self.tol = n_crossings, engine, tol
        self.route = route
        self.Omega = chain.Omega if Omega is None else Omega
        if phase is None:
            phases = chain.points(chain.psi_s)
            if phases.size == 0:
                raise ValueError("the predicted chain has no stable point on the section")
            phase = float(phases[0])
        self.phase = float(phase)
        mom = chain.states(np.array([self.phase]))
        self.l0 = float(np.arctan2(mom[0, 0], mom[0, 1]))
        self.L0 = float(mom[0, 2])
        dl, dL = chain.normal(mom)
        self.dl, self.dL = float(dl[0]), float(dL[0])
        self.section = Section("g", g_star, 1)
        #: ``p/q`` in turns per return, mod 1: where a locked orbit's NAFF line sits.
        self.target = (chain.p / chain.q) % 1.0

    def seeds(self, s: NDArray[np.float64]) -> NDArray[np.float64]:
        body, c = self.c.body, self.c
        l = self.l0 + s * self.dl
        L = self.L0 + s * self.dL
        roots = section_roots(body, self.h, self.M, ("g", self.g_star), l, L)
        y = np.full((s.size, 6), np.nan)
        for i, r in enumerate(roots):
            if r.size:
                G = float(r[np.argmin(np.abs(r - (c.torus.G + s[i])))])
                y[i] = from_andoyer([l[i], self.g_star, L[i], G, self.M])
        return y

    def orbits(self, s: NDArray[np.float64], screen: bool = False) -> dict[str, NDArray[Any]]:
        """Every measure of the orbits seeded at ``s`` (one engine batch): ``locked`` (by
        the route), ``drift`` and ``span`` of the slow angle, ``rotation`` (NAFF: the line
        of ``exp(i phi1_n)`` nearest ``p/q``, turns per return; NaN on the slow-angle
        route) and ``psi_locked`` (the slow angle's verdict).

        ``screen`` (the slow-angle route only): the orbits first run
        :data:`_SCREEN_FRACTION` of ``n_crossings``; one whose slow angle already spans
        ``2 pi`` circulates (a longer run only widens the span), and only the others run
        the whole ``n_crossings``. The verdicts are the same; a screened-out orbit's
        ``drift`` and ``span`` are over its screening returns."""
        out = {"locked": np.zeros(s.size, bool), "psi_locked": np.zeros(s.size, bool),
               "drift": np.full(s.size, np.nan), "span": np.full(s.size, np.inf),
               "rotation": np.full(s.size, np.nan)}
        y = self.seeds(s)
        ok = np.all(np.isfinite(y), axis=1)
        n_screen = math.ceil(_SCREEN_FRACTION * self.n_crossings)
        if screen and self.route == "slow_angle" and n_screen >= _SCREEN_MIN:
            idx = np.nonzero(ok)[0]
            if idx.size:
                self._measure(y[idx], idx, n_screen, out)
                span = out["span"][idx]   # inf: the screen did not finish (undecided)
                ok[idx[np.isfinite(span) & (span >= 2 * math.pi)]] = False
        if ok.any():
            self._measure(y[ok], np.nonzero(ok)[0], self.n_crossings, out)
        if self.route == "naff":
            out["locked"] = (np.abs(out["rotation"] - self.target)
                             < NAFF_LOCK * abs(self.Omega))
        else:
            out["locked"] = out["psi_locked"].copy()
        return out

    def _measure(self, y: NDArray[np.float64], idx: NDArray[np.intp], n_crossings: int,
                 out: dict[str, NDArray[Any]]) -> None:
        """The slow angle (and NAFF lines) of the orbits seeded at ``y`` over
        ``n_crossings`` returns, into the rows ``idx`` of ``out``."""
        c = self.c
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            ds = poincare(c.body, y, self.section, n_crossings, engine=self.engine,
                          rtol=self.tol, atol=self.tol,
                          t_max=2.0 * n_crossings * 2 * math.pi / c.torus.omega_g)
        G = np.stack([ds.G1.values, ds.G2.values, ds.G3.values], axis=-1)
        T = c.torus
        target = self.target
        for j, i in enumerate(idx):
            mom = G[j]
            good = np.all(np.isfinite(mom), axis=1)
            out["span"][i], out["drift"][i], out["psi_locked"][i] = np.inf, np.nan, False
            if good.sum() < n_crossings:
                continue   # left the section's reach: not in the chain
            phi1 = free_top_phase(c.body, mom)
            rho = trig_interpolate(T, T.rho, phi1)
            n = np.arange(phi1.size) + 1.0
            psi = c.q * phi1 - c.p * (self.g_star + 2 * math.pi * n - rho)
            step = np.angle(np.exp(1j * np.diff(psi)))
            path = np.concatenate([[0.0], np.cumsum(step)])
            out["span"][i] = float(np.ptp(path))
            out["psi_locked"][i] = bool(out["span"][i] < 2 * math.pi)
            out["drift"][i] = float(path[-1] / (path.size - 1))
            if self.route == "naff":
                from andoyer.analysis.chaos.frequency import naff

                lines = naff(np.exp(1j * phi1), 1.0, _NAFF_LINES).frequency / (2 * math.pi)
                gap = (lines - target + 0.5) % 1.0 - 0.5
                k = int(np.argmin(np.abs(gap)))
                out["rotation"][i] = target + float(gap[k])

    def run(self, s: NDArray[np.float64]
            ) -> tuple[NDArray[np.bool_], NDArray[np.float64], NDArray[np.float64]]:
        """``(locked, drift, span)`` of the orbits seeded at ``s``."""
        o = self.orbits(s)
        return o["locked"], o["drift"], o["span"]


class _Setup:
    """The chain, its chosen island and the prediction the measurement starts from."""

    def __init__(self, body: RigidBody, h: float, M: float, resonance: str, axis: int | None,
                 island: int, g_star: float, n_crossings: int | None, engine: Any, tol: float,
                 route: str) -> None:
        p, q = _parse_resonance(resonance)
        rows = [r for r in resonant_rows(body, h, M, p + q) if r["p"] == p and r["q"] == q
                and r["sign"] == 1 and (axis is None or r["axis"] == axis)]
        if not rows:
            raise ValueError(f"no torus with frequency_ratio {q}/{p} on h = {h!r}, "
                             f"M = {M!r}" + (f" about axis {axis}" if axis is not None else ""))
        self.p, self.q = p, q
        self.chain = chain = ResonantChain(body, h, M, rows[0], Section("g", g_star, 1))
        self.second: Any = None
        if p == 1:
            phases = chain.points(chain.psi_s)
            self.Omega, self.order = chain.Omega, 1
        else:   # (R5): no resonant harmonic at first order; the width is of order 2 (S4)
            from andoyer.analysis.resonance.second_order import SecondOrderChain

            self.second = SecondOrderChain(chain, 2)
            psi, _x, om = self.second.equilibria().get("stable", (math.nan,) * 3)
            phases = chain.points(psi) if math.isfinite(psi) else np.empty(0)
            self.Omega, self.order = om, 2
        if phases.size == 0:
            raise ValueError(f"resonance {resonance!r}: the predicted chain has no stable "
                             "point on the section")
        if island >= phases.size:
            raise ValueError(f"island must be 0 to {phases.size - 1} (the chain's stable "
                             f"points on the section g = {g_star!r}), got {island!r}")
        self.n_islands = int(phases.size)
        self.phase = float(phases[island])
        if p == 1:
            self.dG, self.s0 = chain.dG, 0.0
        else:
            self.s0 = self.second.stable_s(self.phase, g_star)
            self.dG = self.second.half_width(self.phase, g_star, self.s0)
            if not (math.isfinite(self.dG) and self.dG > 0.0):
                raise ValueError(f"resonance {resonance!r}: the second-order normal form "
                                 "gives no half-width to start from")
        if n_crossings is None:
            n_crossings = max(200, math.ceil(12.0 / self.Omega))
        self.n_crossings = n_crossings
        self.probe = _Probe(chain, h, M, g_star, n_crossings, engine, tol, phase=self.phase,
                            Omega=self.Omega, route=route)


def _common_args(body: RigidBody, h: float, M: float, g_star: float, n_crossings: int | None,
                 tol: float, axis: int | None, island: int, route: str
                 ) -> tuple[float, float, float, int | None, float, int | None, int]:
    h, M, _ = check_level_args(body, h, M, 2)
    g_star = finite("g_star", g_star)
    if not abs(g_star) <= 100.0:
        raise ValueError(f"g_star (the section g = g_star) must be an angle within "
                         f"[-100, 100] rad, got {g_star!r}")
    g_star = Section("g", g_star).value
    if n_crossings is not None:
        n_crossings = integer("n_crossings", n_crossings, 20, 10**6)
    tol = positive("tol", tol, maximum=1e-6)
    if axis is not None:
        axis = integer("axis", axis, 1, 3)
    island = integer("island", island, 0, 10**4)
    if route not in ROUTES:
        raise ValueError(f"route must be one of {ROUTES}, got {route!r}")
    if not body.mu > 0.0:
        raise ValueError("measure_island needs mu > 0: at mu = 0 there is no island")
    return h, M, g_star, n_crossings, tol, axis, island


@checks_body(ranges={"h": "energy", "M": "action", "n_crossings": "count", "tol": "tolerance"})
def measure_island(body: RigidBody, h: float, M: float, resonance: str, *,
                   axis: int | None = None, island: int = 0, g_star: float = 0.0,
                   n_crossings: int | None = None,
                   n_seeds: int = 6, n_rounds: int = 3, stable: bool = True,
                   route: str = "slow_angle", engine: str | None = None,
                   tol: float = 1e-11) -> xr.Dataset:
    """Measure the half-width of one island chain on the section ``g = g*``.

    See the module's docstring for the method; the prediction it is compared with is
    the first-order half-width ``Delta G`` (R6) of
    :func:`~andoyer.analysis.resonance.predict.resonance_widths` (``p = 1``) or the
    second-order one of :mod:`~andoyer.analysis.resonance.second_order` (S4) (``p >= 2``,
    whose width is of order ``mu``: the resonant harmonic enters at ``mu^2``).

    Parameters
    ----------
    body : RigidBody
        Oz the middle axis; its ``mu`` > 0 is the perturbation measured.
    h, M : float
        The energy level and the area constant.
    resonance : str
        ``"q:p"``: the chain of ``frequency_ratio = q/p`` (``W = p/q``; ``p = 1``: the
        chains of first order in ``mu``, ``p >= 2``: of second order).
    axis : int, optional
        Body axis (1 or 2) of the regime, where the chain exists in both; default: the
        first the level lists.
    island : int
        Which of the chain's stable points on the section the seed line goes through
        (0 to ``n_islands - 1``, in the order of their free-top phase; the output's
        ``attrs['island']``, ``attrs['n_islands']``, ``attrs['stable_phase']``).
    g_star : float
        The section ``g = g*``.
    n_crossings : int, optional
        Returns followed per orbit; default ``12 / Omega`` (at least 200): a small
        libration takes ``1 / Omega`` returns (R7), a circulation just outside the
        separatrix a few times more (its period grows like ``log`` of the distance).
    n_seeds : int
        Seeds per bracket and round (both edges' brackets run in one engine batch).
    n_rounds : int
        Rounds of refinement of each edge (uncertainty ``~ (n_seeds + 1)^-n_rounds``).
    stable : bool
        Search the stable periodic orbit inside the locked interval (bounded Brent, up to
        45 sequential orbits: most of the cost); ``False``: ``stable_s``, ``stable_span``
        NaN and ``attrs['stable_search'] = 'skipped'``.
    route : str
        How an orbit is classified as locked: ``"slow_angle"`` (its slow angle spans less
        than ``2 pi``) or ``"naff"`` (the line of ``exp(i phi1_n)`` nearest ``p/q`` lies
        within :data:`NAFF_LOCK` ``Omega`` of it; ``seed_rotation`` holds the lines).
    engine : str, optional
        Integration engine (with crossings); default as :func:`andoyer.integrate.poincare`.
    tol : float
        Tolerance of the integration.

    Returns
    -------
    xarray.Dataset
        0-d variables ``predicted_half_width`` (with ``predicted_order``: 1 from (R6), 2
        from (S4)), ``measured_half_width``,
        ``half_width_error`` (their difference), ``edge_uncertainty``, ``s_inner``,
        ``s_outer``, ``centre_offset`` (the locked interval's midpoint), ``stable_s``
        (the measured stable periodic orbit: least libration of ``psi``, by bounded
        Brent inside the locked interval) with ``stable_span``, ``predicted_stable_s``
        (R10 of :mod:`~andoyer.analysis.resonance.predict`; NaN for ``p >= 2``) with
        ``predicted_stable_s_next_order``
        (R12: the estimated size of its ``O(mu^2)`` term)
        and ``predicted_stable_s_holds`` (that estimate below the half-width),
        ``predicted_stable_s_2`` (the second-order position, (S1)-(S4) of
        :mod:`~andoyer.analysis.resonance.second_order`: error ``O(mu^3)``; NaN with
        ``attrs['second_order']`` saying why when the normal form cannot be built),
        ``libration_frequency``; ``seed_s``,
        ``seed_locked``, ``seed_drift``, ``seed_rotation`` per orbit run (dim ``seed``).

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> body = RigidBody.hess(3.0, 1.0, 2.0, mu=1e-3)
    >>> ds = measure_island(body, 1.0, 0.0, "2:1", n_crossings=300, n_seeds=3,
    ...                     n_rounds=2)  # doctest: +SKIP
    """
    h, M, g_star, n_crossings, tol, axis, island = _common_args(
        body, h, M, g_star, n_crossings, tol, axis, island, route)
    n_seeds = integer("n_seeds", n_seeds, 1, 64)
    n_rounds = integer("n_rounds", n_rounds, 1, 20)
    if not isinstance(stable, bool | np.bool_):
        raise ValueError(f"stable must be True or False, got {stable!r}")
    setup = _Setup(body, h, M, resonance, axis, island, g_star, n_crossings, engine, tol, route)
    chain, probe, n_crossings = setup.chain, setup.probe, setup.n_crossings
    n_orbits = 3 + _MAX_LOCATE + 2 * n_seeds * n_rounds + (_STABLE_EVALUATIONS if stable else 0)
    seconds_per_return = 2 * math.pi / chain.torus.omega_g
    budget.check("measure_island", steps=budget.estimate_steps(
        body, probe.seeds(np.zeros(1))[:1], n_orbits * n_crossings * seconds_per_return, tol))
    dG, s0 = setup.dG, setup.s0
    log_s: list[float] = []
    log_l: list[bool] = []
    log_d: list[float] = []
    log_w: list[float] = []

    def run(s: NDArray[np.float64], screen: bool = False) -> NDArray[np.bool_]:
        o = probe.orbits(s, screen)
        log_s.extend(s.tolist())
        log_l.extend(o["locked"].tolist())
        log_d.extend(o["drift"].tolist())
        log_w.extend(o["rotation"].tolist())
        return np.asarray(o["locked"])

    run(np.array([s0, s0 - 3.0 * dG, s0 + 3.0 * dG]))
    for _ in range(_MAX_LOCATE):
        if any(log_l):
            break
        s_arr, d_arr = np.array(log_s), np.array(log_d)
        good = np.isfinite(d_arr)
        if good.sum() < 2:
            break
        order = np.argsort(np.abs(d_arr[good]))[:2]
        (s1, s2), (d1, d2) = s_arr[good][order], d_arr[good][order]
        if d1 == d2:
            break
        run(np.array([s1 - d1 * (s2 - s1) / (d2 - d1)]))
    if not any(log_l):
        raise ValueError(f"no orbit locked in the {resonance} chain was found near the "
                         "prediction (raise n_crossings, or the chain is destroyed)")
    s_lock = log_s[int(np.argmin([abs(d) if lk else np.inf
                                  for d, lk in zip(log_d, log_l, strict=True)]))]
    # Both edges at once: each direction marches out (doubling steps) until an orbit
    # circulates, then its bracket is narrowed; the two run in one engine batch per step.
    inside = {-1.0: s_lock, 1.0: s_lock}
    step = {-1.0: max(dG, 1e-12), 1.0: max(dG, 1e-12)}
    outside: dict[float, float | None] = {-1.0: None, 1.0: None}
    marching = [-1.0, 1.0]
    for _ in range(40):   # march out until an orbit circulates
        if not marching:
            break
        trial = np.array([inside[d] + d * step[d] for d in marching])
        lk = run(trial, screen=True)
        for d, t, locked in zip(list(marching), trial, lk, strict=True):
            if locked:
                inside[d] = float(t)
                step[d] *= 2.0
            else:
                outside[d] = float(t)
                marching.remove(d)
    if marching:
        d = marching[0]
        raise ValueError(f"the {resonance} chain has no edge within "
                         f"{abs(inside[d] - s_lock):.3g} of the locked orbit")
    bracket = {d: (inside[d], float(outside[d])) for d in (-1.0, 1.0)}   # type: ignore[arg-type]
    frac = np.arange(1, n_seeds + 1) / (n_seeds + 1)
    for _ in range(n_rounds):
        s = np.concatenate([lo + (hi - lo) * frac for lo, hi in bracket.values()])
        lk_all = run(s, screen=True)
        for j, d in enumerate((-1.0, 1.0)):
            lo, hi = bracket[d]
            part = s[j * n_seeds:(j + 1) * n_seeds]
            lk = lk_all[j * n_seeds:(j + 1) * n_seeds]
            pts = np.concatenate([[lo], part, [hi]])
            flags = np.concatenate([[True], lk, [False]])
            k = int(np.argmin(flags)) if not flags.all() else flags.size - 1
            bracket[d] = (float(pts[k - 1]), float(pts[k]))
    (a_lo, a_hi), (b_lo, b_hi) = bracket[-1.0], bracket[1.0]
    s_in, s_out = 0.5 * (a_lo + a_hi), 0.5 * (b_lo + b_hi)
    unc = 0.5 * max(abs(a_hi - a_lo), abs(b_hi - b_lo))
    measured = 0.5 * (s_out - s_in)
    if stable:
        # The stable periodic orbit: where the slow angle's libration is smallest
        # (bounded Brent inside the locked interval).
        from scipy.optimize import minimize_scalar

        found = minimize_scalar(lambda x: float(probe.run(np.array([x]))[2][0]),
                                bounds=(s_in, s_out), method="bounded",
                                options={"xatol": _STABLE_XATOL * (s_out - s_in),
                                         "maxiter": _STABLE_EVALUATIONS})
        stable_s, stable_span = float(found.x), float(found.fun)
    else:
        stable_s = stable_span = math.nan
    predicted_stable = float(chain.stable_shift(np.array([probe.phase]))[0]) \
        if setup.p == 1 else math.nan
    next_order = abs(chain.second_order_mean_shift()) if setup.p == 1 else math.nan
    if setup.second is not None:
        second, why = setup.s0, ""
    else:
        from andoyer.analysis.resonance.second_order import SecondOrderChain

        try:
            second, why = SecondOrderChain(chain, 2).stable_s(probe.phase, g_star), ""
        except ValueError as exc:   # a node torus the normal form cannot sample
            second, why = math.nan, f"not computed: {exc}"
    ds = xr.Dataset(
        {"predicted_half_width": ((), dG), "predicted_order": ((), setup.order),
         "measured_half_width": ((), measured),
         "half_width_error": ((), measured - dG), "edge_uncertainty": ((), unc),
         "s_inner": ((), s_in), "s_outer": ((), s_out),
         "centre_offset": ((), 0.5 * (s_in + s_out)),
         "libration_frequency": ((), setup.Omega),
         "stable_s": ((), stable_s), "stable_span": ((), stable_span),
         "predicted_stable_s": ((), predicted_stable),
         "predicted_stable_s_next_order": ((), next_order),
         "predicted_stable_s_2": ((), second),
         "predicted_stable_s_holds": ((), bool(next_order < dG)),
         "seed_s": ("seed", np.array(log_s)), "seed_locked": ("seed", np.array(log_l)),
         "seed_drift": ("seed", np.array(log_d)),
         "seed_rotation": ("seed", np.array(log_w))},
        attrs=provenance(body, h=h, M=M, resonance=resonance, axis=int(chain.row["axis"]),
                         island=island, n_islands=setup.n_islands,
                         g_star=g_star, n_crossings=n_crossings, n_seeds=n_seeds,
                         n_rounds=n_rounds, tolerance=tol, G_star=chain.torus.G,
                         stable_phase=probe.phase, second_order=why or "computed",
                         stable_search="bounded Brent" if stable else "skipped",
                         route=route,
                         method="seeds on the normal line through a predicted stable point; "
                                + ("locked: the slow angle psi spans < 2 pi over n_crossings "
                                   "returns" if route == "slow_angle" else
                                   "locked: a NAFF line of exp(i phi1_n) within NAFF_LOCK "
                                   "Omega of p/q")
                                + "; edges by rounds of seeds in each bracket"))
    return describe_variables(ds, _VARIABLES)


_VARIABLES = {
    "predicted_half_width": ("\\Delta G", "predicted half-width (order predicted_order: "
                             "(R6) or (S4))", "1", "(R6), (S4)"),
    "predicted_order": ("", "order in mu of the predicted half-width's normal form", "1",
                        "(R5)"),
    "measured_half_width": ("\\Delta G", "half the distance between the edges of the "
                            "locked interval, in G along the seed line", "1", ""),
    "half_width_error": ("", "measured minus predicted half-width", "1", ""),
    "edge_uncertainty": ("", "half the widest final bracket of an edge", "1", ""),
    "s_inner": ("", "inner edge of the locked interval (G units from the prediction)",
                "1", ""),
    "s_outer": ("", "outer edge of the locked interval", "1", ""),
    "centre_offset": ("", "midpoint of the locked interval: the O(mu) shift of the "
                      "chain first order does not give", "1", ""),
    "libration_frequency": ("\\Omega", "predicted libration frequency per radian of g",
                            "1", "(R7), (S4)"),
    "stable_s": ("", "measured stable periodic orbit on the seed line: least libration "
                 "of the slow angle (G units; NaN when not searched)", "1", ""),
    "stable_span": ("", "range of the slow angle on the orbit seeded at stable_s", "rad",
                    ""),
    "predicted_stable_s": ("\\delta G", "first-order offset of the stable point (R10)",
                           "1", "(R10)"),
    "predicted_stable_s_next_order": ("", "estimated size of the O(mu^2) term of "
                                      "predicted_stable_s", "1", "(R12)"),
    "predicted_stable_s_2": ("\\delta G", "second-order position of the stable point "
                             "on the seed line (Lie-Deprit normal form to mu^2)", "1",
                             "(S1)-(S4)"),
    "predicted_stable_s_holds": ("", "the estimate is below the predicted half-width: "
                                 "the first-order stable point lies inside the island",
                                 "1", "(R12)"),
    "seed_s": ("s", "seed position on the line (G units)", "1", ""),
    "seed_locked": ("", "the orbit librates in the chain", "1", ""),
    "seed_drift": ("", "mean change of psi per return (over the screening returns for an "
                   "orbit that circulated within them)", "rad", ""),
    "seed_rotation": ("W", "NAFF line of exp(i phi1_n) nearest p/q, turns per return (naff "
                      "route; NaN otherwise)", "1", ""),
}


@checks_body(ranges={"h": "energy", "M": "action", "n_crossings": "count", "tol": "tolerance"})
def island_rotation_numbers(body: RigidBody, h: float, M: float, resonance: str,
                            s: ArrayLike, *, axis: int | None = None, island: int = 0,
                            g_star: float = 0.0, n_crossings: int | None = None,
                            engine: str | None = None, tol: float = 1e-11) -> xr.Dataset:
    """NAFF rotation numbers of orbits across an island chain: the NAFF route of
    :func:`measure_island` as a library function.

    The orbits are seeded on :func:`measure_island`'s line (``s`` in ``G`` units from the
    resonant torus, through the chosen island's predicted stable point) and integrated
    through the engine seam in one batch; per orbit the rotation number of the section map
    is the line of ``exp(i phi1_n)`` (the crossings' free-top phases) nearest ``p/q`` among
    the strongest eight (:func:`andoyer.analysis.chaos.frequency.naff`): exactly ``p/q``
    inside the island (the libration's sidebands at ``p/q +- Omega``), off it outside.

    Parameters
    ----------
    body : RigidBody
        Oz the middle axis; ``mu`` > 0.
    h, M : float
        The energy level and the area constant.
    resonance : str
        ``"q:p"`` (``W = p/q``).
    s : array_like
        Seed positions on the line (``G`` units).
    axis : int, optional
        Body axis of the regime.
    island : int
        Which stable point the line goes through (as :func:`measure_island`).
    g_star : float
        The section ``g = g*``.
    n_crossings : int, optional
        Returns per orbit (default as :func:`measure_island`).
    engine : str, optional
        Integration engine (with crossings).
    tol : float
        Tolerance of the integration.

    Returns
    -------
    xarray.Dataset
        On dim ``seed``: ``s``, ``rotation_number`` (NAFF, turns per return, near ``p/q``),
        ``rotation_offset`` (minus ``p/q``), ``locked`` (within :data:`NAFF_LOCK` ``Omega``),
        ``psi_locked`` (the slow angle's verdict), ``psi_span`` and ``returned`` (the orbit
        made every return; its rotation number is NaN otherwise); 0-d
        ``libration_frequency``.

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> body = RigidBody.hess(3.0, 1.0, 2.0, mu=1e-3)
    >>> r = island_rotation_numbers(body, 1.0, 0.0, "3:1", [0.0, 0.01], axis=1,
    ...                             engine="numba")
    >>> r.locked.values.tolist(), bool(abs(float(r.rotation_offset[0])) < 1e-6)
    ([True, False], True)
    """
    h, M, g_star, n_crossings, tol, axis, island = _common_args(
        body, h, M, g_star, n_crossings, tol, axis, island, "naff")
    sv = real_array("s", s)
    if sv.ndim > 1 or sv.size == 0 or not np.all(np.isfinite(sv)):
        raise ValueError(f"s must be one or more finite seed positions (1-D), got shape "
                         f"{sv.shape}")
    sv = sv.ravel()
    setup = _Setup(body, h, M, resonance, axis, island, g_star, n_crossings, engine, tol, "naff")
    off = ~np.all(np.isfinite(setup.probe.seeds(sv)), axis=1)
    if off.any():
        raise ValueError(f"s: the seeds at {sv[off][:3].tolist()} have no state on the level "
                         f"h = {h!r} (the line leaves the regime; the chain's half-width is "
                         f"~{setup.dG:.3g})")
    budget.check("island_rotation_numbers", steps=budget.estimate_steps(
        body, setup.probe.seeds(np.zeros(1))[:1],
        sv.size * setup.n_crossings * 2 * math.pi / setup.chain.torus.omega_g, tol))
    o = setup.probe.orbits(sv)
    target = setup.p / setup.q
    ds = xr.Dataset(
        {"s": ("seed", sv), "rotation_number": ("seed", o["rotation"]),
         "rotation_offset": ("seed", o["rotation"] - target),
         "locked": ("seed", o["locked"]), "psi_locked": ("seed", o["psi_locked"]),
         "psi_span": ("seed", o["span"]), "returned": ("seed", np.isfinite(o["rotation"])),
         "libration_frequency": ((), setup.Omega)},
        attrs=provenance(body, h=h, M=M, resonance=resonance,
                         axis=int(setup.chain.row["axis"]), island=island,
                         n_islands=setup.n_islands, g_star=g_star,
                         n_crossings=setup.n_crossings, tolerance=tol,
                         stable_phase=setup.phase, naff_lock=NAFF_LOCK,
                         method="NAFF lines of exp(i phi1_n) on the section g = g*"))
    return describe_variables(ds, {
        "s": ("s", "seed position on the line (G units)", "1", ""),
        "rotation_number": ("W", "NAFF line of exp(i phi1_n) nearest p/q (turns per return)",
                            "1", "(R2)"),
        "rotation_offset": ("W - p/q", "rotation number minus p/q", "1", ""),
        "locked": ("", "|W - p/q| < NAFF_LOCK Omega: inside the island", "1", ""),
        "psi_locked": ("", "the slow angle spans < 2 pi (measure_island's route)", "1", ""),
        "psi_span": ("", "range of the slow angle", "rad", ""),
        "returned": ("", "the orbit made every return (NaN rotation_number otherwise: it "
                     "left the section's reach)", "1", ""),
        "libration_frequency": ("\\Omega", "predicted libration frequency (turns per "
                                "return)", "1", "(R7), (S4)")})
