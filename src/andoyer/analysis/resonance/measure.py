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
inside each bracket. The result: the edges ``s_inner``, ``s_outer`` with their
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
from numpy.typing import NDArray

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
from andoyer.validation import finite, integer, positive

__all__ = ["measure_island"]

#: Drift-guided steps allowed to find a locked seed before giving up.
_MAX_LOCATE = 8
#: Orbits of the search for the stable periodic orbit inside the locked interval.
_STABLE_EVALUATIONS = 45


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


class _Probe:
    """Seeds on the line through one stable point; integrates and classifies them."""

    def __init__(self, chain: ResonantChain, h: float, M: float, g_star: float, n_crossings: int,
                 engine: Any, tol: float) -> None:
        self.c, self.h, self.M, self.g_star = chain, h, M, g_star
        self.n_crossings, self.engine, self.tol = n_crossings, engine, tol
        phase = chain.points(chain.psi_s)
        if phase.size == 0:
            raise ValueError("the predicted chain has no stable point on the section")
        self.phase = float(phase[0])
        mom = chain.states(np.array([self.phase]))
        self.l0 = float(np.arctan2(mom[0, 0], mom[0, 1]))
        self.L0 = float(mom[0, 2])
        dl, dL = chain.normal(mom)
        self.dl, self.dL = float(dl[0]), float(dL[0])
        self.section = Section("g", g_star, 1)

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

    def run(self, s: NDArray[np.float64]
            ) -> tuple[NDArray[np.bool_], NDArray[np.float64], NDArray[np.float64]]:
        """``(locked, drift, span)`` of the orbits seeded at ``s``."""
        y = self.seeds(s)
        ok = np.all(np.isfinite(y), axis=1)
        locked = np.zeros(s.size, bool)
        drift = np.full(s.size, np.nan)
        span = np.full(s.size, np.inf)
        if not ok.any():
            return locked, drift, span
        c = self.c
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            ds = poincare(c.body, y[ok], self.section, self.n_crossings, engine=self.engine,
                          rtol=self.tol, atol=self.tol,
                          t_max=2.0 * self.n_crossings * 2 * math.pi / c.torus.omega_g)
        G = np.stack([ds.G1.values, ds.G2.values, ds.G3.values], axis=-1)
        idx = np.nonzero(ok)[0]
        T = c.torus
        for j, i in enumerate(idx):
            mom = G[j]
            good = np.all(np.isfinite(mom), axis=1)
            if good.sum() < self.n_crossings:
                continue   # left the section's reach: not in the chain
            phi1 = free_top_phase(c.body, mom)
            rho = trig_interpolate(T, T.rho, phi1)
            n = np.arange(phi1.size) + 1.0
            psi = c.q * phi1 - c.p * (self.g_star + 2 * math.pi * n - rho)
            step = np.angle(np.exp(1j * np.diff(psi)))
            path = np.concatenate([[0.0], np.cumsum(step)])
            span[i] = float(np.ptp(path))
            locked[i] = bool(span[i] < 2 * math.pi)
            drift[i] = float(path[-1] / (path.size - 1))
        return locked, drift, span


@checks_body(ranges={"h": "energy", "M": "action", "n_crossings": "count", "tol": "tolerance"})
def measure_island(body: RigidBody, h: float, M: float, resonance: str, *,
                   axis: int | None = None, g_star: float = 0.0,
                   n_crossings: int | None = None,
                   n_seeds: int = 6, n_rounds: int = 3, engine: str | None = None,
                   tol: float = 1e-11) -> xr.Dataset:
    """Measure the half-width of one island chain on the section ``g = g*``.

    See the module's docstring for the method; the prediction it is compared with is
    the first-order half-width ``Delta G`` (R6) of
    :func:`~andoyer.analysis.resonance.predict.resonance_widths`.

    Parameters
    ----------
    body : RigidBody
        Oz the middle axis; its ``mu`` > 0 is the perturbation measured.
    h, M : float
        The energy level and the area constant.
    resonance : str
        ``"q:p"``: the chain of ``frequency_ratio = q/p`` (``W = p/q``, ``p = 1``: the
        chains of first order in ``mu``).
    axis : int, optional
        Body axis (1 or 2) of the regime, where the chain exists in both; default: the
        first the level lists.
    g_star : float
        The section ``g = g*``.
    n_crossings : int, optional
        Returns followed per orbit; default ``12 / Omega`` (at least 200): a small
        libration takes ``1 / Omega`` returns (R7), a circulation just outside the
        separatrix a few times more (its period grows like ``log`` of the distance).
    n_seeds : int
        Seeds per bracket and round.
    n_rounds : int
        Rounds of refinement of each edge (uncertainty ``~ (n_seeds + 1)^-n_rounds``).
    engine : str, optional
        Integration engine (with crossings); default as :func:`andoyer.integrate.poincare`.
    tol : float
        Tolerance of the integration.

    Returns
    -------
    xarray.Dataset
        0-d variables ``predicted_half_width``, ``measured_half_width``,
        ``half_width_error`` (their difference), ``edge_uncertainty``, ``s_inner``,
        ``s_outer``, ``centre_offset`` (the locked interval's midpoint), ``stable_s``
        (the measured stable periodic orbit: least libration of ``psi``, by bounded
        Brent inside the locked interval) with ``stable_span``, ``predicted_stable_s``
        (R10 of :mod:`~andoyer.analysis.resonance.predict`) with
        ``predicted_stable_s_next_order`` (R12: the estimated size of its ``O(mu^2)`` term)
        and ``predicted_stable_s_holds`` (that estimate below the half-width),
        ``predicted_stable_s_2`` (the second-order position, (S1)-(S4) of
        :mod:`~andoyer.analysis.resonance.second_order`: error ``O(mu^3)``; NaN with
        ``attrs['second_order']`` saying why when the normal form cannot be built),
        ``libration_frequency``; ``seed_s``,
        ``seed_locked``, ``seed_drift`` per orbit run (dim ``seed``).

    Examples
    --------
    >>> from andoyer import RigidBody
    >>> body = RigidBody.hess(3.0, 1.0, 2.0, mu=1e-3)
    >>> ds = measure_island(body, 1.0, 0.0, "2:1", n_crossings=300, n_seeds=3,
    ...                     n_rounds=2)  # doctest: +SKIP
    """
    h, M, _ = check_level_args(body, h, M, 2)
    p, q = _parse_resonance(resonance)
    if p != 1:
        raise ValueError(f"resonance {resonance!r}: only the chains of first order in mu "
                         "(p = 1, 'q:1') have a predicted width to measure")
    g_star = finite("g_star", g_star)
    if not abs(g_star) <= 100.0:
        raise ValueError(f"g_star (the section g = g_star) must be an angle within "
                         f"[-100, 100] rad, got {g_star!r}")
    g_star = Section("g", g_star).value
    if n_crossings is not None:
        n_crossings = integer("n_crossings", n_crossings, 20, 10**6)
    n_seeds = integer("n_seeds", n_seeds, 1, 64)
    n_rounds = integer("n_rounds", n_rounds, 1, 20)
    tol = positive("tol", tol, maximum=1e-6)
    if axis is not None:
        axis = integer("axis", axis, 1, 3)
    if not body.mu > 0.0:
        raise ValueError("measure_island needs mu > 0: at mu = 0 there is no island")
    rows = [r for r in resonant_rows(body, h, M, p + q) if r["p"] == p and r["q"] == q
            and r["sign"] == 1 and (axis is None or r["axis"] == axis)]
    if not rows:
        raise ValueError(f"no torus with frequency_ratio {q}/{p} on h = {h!r}, M = {M!r}"
                         + (f" about axis {axis}" if axis is not None else ""))
    chain = ResonantChain(body, h, M, rows[0], Section("g", g_star, 1))
    if n_crossings is None:
        n_crossings = max(200, math.ceil(12.0 / chain.Omega))
    probe = _Probe(chain, h, M, g_star, n_crossings, engine, tol)
    n_orbits = 3 + _MAX_LOCATE + 2 * n_seeds * n_rounds + _STABLE_EVALUATIONS
    seconds_per_return = 2 * math.pi / chain.torus.omega_g
    budget.check("measure_island", steps=budget.estimate_steps(
        body, probe.seeds(np.zeros(1))[:1], n_orbits * n_crossings * seconds_per_return, tol))
    dG = chain.dG
    log_s: list[float] = []
    log_l: list[bool] = []
    log_d: list[float] = []

    def run(s: NDArray[np.float64]) -> NDArray[np.bool_]:
        lk, dr, _span = probe.run(s)
        log_s.extend(s.tolist())
        log_l.extend(lk.tolist())
        log_d.extend(dr.tolist())
        return lk

    run(np.array([0.0, -3.0 * dG, 3.0 * dG]))
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
    edges = []
    for direction in (-1.0, 1.0):
        inside = s_lock
        step = max(dG, 1e-12)
        outside = None
        for _ in range(40):   # march out until an orbit circulates
            trial = inside + direction * step
            if run(np.array([trial]))[0]:
                inside = trial
                step *= 2.0
            else:
                outside = trial
                break
        if outside is None:
            raise ValueError(f"the {resonance} chain has no edge within "
                             f"{abs(inside - s_lock):.3g} of the locked orbit")
        lo, hi = inside, outside
        for _ in range(n_rounds):
            s = lo + (hi - lo) * np.arange(1, n_seeds + 1) / (n_seeds + 1)
            lk = run(s)
            pts = np.concatenate([[lo], s, [hi]])
            flags = np.concatenate([[True], lk, [False]])
            k = int(np.argmin(flags)) if not flags.all() else flags.size - 1
            lo, hi = pts[k - 1], pts[k]
        edges.append((lo, hi))
    (a_lo, a_hi), (b_lo, b_hi) = edges
    s_in, s_out = 0.5 * (a_lo + a_hi), 0.5 * (b_lo + b_hi)
    unc = 0.5 * max(abs(a_hi - a_lo), abs(b_hi - b_lo))
    measured = 0.5 * (s_out - s_in)
    # The stable periodic orbit: where the slow angle's libration is smallest (bounded
    # Brent inside the locked interval).
    from scipy.optimize import minimize_scalar

    stable = minimize_scalar(lambda x: float(probe.run(np.array([x]))[2][0]),
                             bounds=(s_in, s_out), method="bounded",
                             options={"xatol": 1e-7 * (s_out - s_in),
                                      "maxiter": _STABLE_EVALUATIONS})
    predicted_stable = float(chain.stable_shift(np.array([probe.phase]))[0])
    next_order = abs(chain.second_order_mean_shift())
    from andoyer.analysis.resonance.second_order import SecondOrderChain

    try:
        second, why = SecondOrderChain(chain, 2).stable_s(probe.phase, g_star), ""
    except ValueError as exc:   # a node torus the normal form cannot sample
        second, why = math.nan, f"not computed: {exc}"
    ds = xr.Dataset(
        {"predicted_half_width": ((), dG), "measured_half_width": ((), measured),
         "half_width_error": ((), measured - dG), "edge_uncertainty": ((), unc),
         "s_inner": ((), s_in), "s_outer": ((), s_out),
         "centre_offset": ((), 0.5 * (s_in + s_out)),
         "libration_frequency": ((), chain.Omega),
         "stable_s": ((), float(stable.x)), "stable_span": ((), float(stable.fun)),
         "predicted_stable_s": ((), predicted_stable),
         "predicted_stable_s_next_order": ((), next_order),
         "predicted_stable_s_2": ((), second),
         "predicted_stable_s_holds": ((), bool(next_order < dG)),
         "seed_s": ("seed", np.array(log_s)), "seed_locked": ("seed", np.array(log_l)),
         "seed_drift": ("seed", np.array(log_d))},
        attrs=provenance(body, h=h, M=M, resonance=resonance, axis=int(chain.row["axis"]),
                         g_star=g_star, n_crossings=n_crossings, n_seeds=n_seeds,
                         n_rounds=n_rounds, tolerance=tol, G_star=chain.torus.G,
                         stable_phase=probe.phase, second_order=why or "computed",
                         method="seeds on the normal line through a predicted stable point; "
                                "locked: the slow angle psi spans < 2 pi over n_crossings "
                                "returns; edges by rounds of seeds in each bracket"))
    return describe_variables(ds, {
        "predicted_half_width": ("\\Delta G", "first-order half-width (R6)", "1", "(R6)"),
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
                                "1", "(R7)"),
        "stable_s": ("", "measured stable periodic orbit on the seed line: least libration "
                     "of the slow angle (G units)", "1", ""),
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
        "seed_drift": ("", "mean change of psi per return", "rad", "")})
